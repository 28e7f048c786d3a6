/* The lab on the page (book/10_explorers): a polygon the reader shapes (presets, drawing, dragging,
 * arrow keys, adding and removing vertices, undo), coloured by a discrete curvature (ddg's three, and
 * in the instructor's edition the circle through three vertices of chapter 6's exercise, from
 * ddg-lab-circle.js, which the student edition leaves out: it is an answer), with the
 * gradient of length as arrows, the curvature along the polygon beside the smooth curve's, the
 * polygon inflated by eps (the formula's area beside the area of the region, measured as a union of
 * polygons by polygon-clipping), and the three curve-shortening flows run side by side from it.
 * Everything else is computed by ddg-lab.js (ddg's formulas). Loaded only where there is a .ddg-lab
 * (tools/sphinx_assets.py). Data coordinates have y up; the SVG is drawn with y flipped. The address
 * can choose the start: ?lab=star&kind=tangent&n=24&arrows=1&inflate=minkowski&eps=0.4 (the
 * chapters link to the lab so).
 */
(function () {
  "use strict";
  var SVG = "http://www.w3.org/2000/svg", RAMP = ["#2563eb", "#9ca3af", "#dc2626"];  // ddg.scene.RAMP
  var FLOW_COLORS = {angle: "#3b82f6", sine: "#f59e0b", tangent: "#10b981"};       // ddg.explore.FLOW_COLORS
  var INFLATIONS = {minkowski: ["Minkowski sum", "#f59e0b", "A₀ + εL + ε²/2 Σ ψᵢ"],       // ddg.explore's names and colours,
                    offset: ["offset with kites", "#10b981", "A₀ + εL + ε² Σ tan(ψᵢ/2)"],  // and ddg.scene's purple
                    bisector: ["fill on the bisector of chapter 6", "#a855f7", "A₀ + εL + ε²/2 Σ Aᵢkᵢ"]};
  var ARC_STEP = Math.PI / 360, MEASURED_UP_TO = 300;  // chords of at most 0.5 degrees; the union's cost grows with
  // the square of the rectangles that overlap (a concave stretch inflated by more than its radius)
  function polar(r, dr, ddr) {  // ddg.smooth.polar, clockwise: r(t) (cos t, -sin t) and its derivatives
    return function (t) {
      var c = Math.cos(t), s = Math.sin(t), a = r(t), b = dr(t), d = ddr(t);
      return [[a * c, -a * s], [b * c - a * s, -(b * s + a * c)], [d * c - 2 * b * s - a * c, -(d * s + 2 * b * c - a * s)]];
    };
  }
  /* Smooth closed curves (gamma, gamma', gamma'' at t), sampled at t_k = 2 pi (k + shift) / n: the
   * circle, ellipse and blob of ddg.explore.SHAPES, and a figure-eight (turning number 0). */
  var SMOOTH = {
    "regular n-gon": {shift: 0, at: polar(function () { return 1; }, function () { return 0; }, function () { return 0; })},
    "ellipse": {shift: 0, at: function (t) {
      var c = Math.cos(t), s = Math.sin(t);
      return [[2 * c, -s], [-2 * s, -c], [-2 * c, s]];
    }},
    "non-convex blob": {shift: 0, at: polar(function (t) { return 1 + 0.3 * Math.cos(3 * t); },
                                            function (t) { return -0.9 * Math.sin(3 * t); },
                                            function (t) { return -2.7 * Math.cos(3 * t); })},
    "figure-eight": {shift: 0.5, at: function (t) {  // 1.2 (sin t, sin t cos t): its crossing between two vertices
      var c = Math.cos(t), s = Math.sin(t);
      return [[1.2 * s, 0.6 * Math.sin(2 * t)], [1.2 * c, 1.2 * Math.cos(2 * t)], [-1.2 * s, -2.4 * Math.sin(2 * t)]];
    }}
  };
  var POLYGONS = {  // ddg.explore.POLYGONS: chapter 5's polygons
    "star (chapter 5)": [0, 1, 2, 3, 4, 5, 6, 7, 8, 9].map(function (k) {
      var r = k % 2 ? 0.5 : 1, a = k * Math.PI / 5;
      return [r * Math.cos(a), -r * Math.sin(a)];
    }),
    "convex pentagon (chapter 5)": [[0, 0], [0.3, 1.5], [1.8, 2], [3, 1], [2.4, -0.4]]
  };
  var SHORT_NAMES = {regular: "regular n-gon", ellipse: "ellipse", blob: "non-convex blob", eight: "figure-eight",
                     star: "star (chapter 5)", pentagon: "convex pentagon (chapter 5)"};  // for ?lab=

  function kappa(t, at) {  // ddg.smooth.SmoothCurve.curvature: -(gamma' x gamma'') / |gamma'|^3, clockwise positive
    var p = at(t), d = p[1], dd = p[2], speed = Math.hypot(d[0], d[1]);
    return -(((d[0] / speed) * dd[1] - (d[1] / speed) * dd[0]) / speed) / speed;
  }
  function ramp(value) {  // ddg.scene.ramp on RAMP
    value = Math.min(Math.max(value, 0), 1);
    var i = value <= 0.5 ? 0 : 1, t = value * 2 - i;
    return "#" + [1, 3, 5].map(function (k) {
      var a = parseInt(RAMP[i].slice(k, k + 2), 16), b = parseInt(RAMP[i + 1].slice(k, k + 2), 16);
      return ("0" + Math.floor(a + t * (b - a) + 0.5).toString(16)).slice(-2);
    }).join("");
  }
  var LEVELS = Array.from({length: 65}, function (_, j) { return ramp(j / 64); });  // the ramp in 65 steps: a drag
  // rewrites the colour of a vertex only when it moves by a step (a phone restyles 500 circles slowly)
  function short(x) { return String(Number(x.toPrecision(6))); }  // six significant digits, as the summary shows them
  function element(name, attributes, parent) {
    var svg = ["svg", "path", "circle", "g", "polyline", "line"].indexOf(name) >= 0;
    var e = document.createElementNS(svg ? SVG : "http://www.w3.org/1999/xhtml", name);
    Object.keys(attributes).forEach(function (a) { e.setAttribute(a, attributes[a]); });
    if (parent) parent.appendChild(e);
    return e;
  }
  function control(root, text, input) {
    var label = element("label", {}, root);
    label.appendChild(document.createTextNode(text + " "));
    label.appendChild(input);
    return input;
  }
  function button(root, text, title) {
    var b = element("button", {type: "button", class: "ddg-play", title: title || text}, root);
    b.textContent = text;
    return b;
  }
  /* The pieces of the polygon inflated by eps (lecture §3.4), for a clockwise polygon: the rectangle
   * each edge e_{i+1/2} sweeps as it moves out by eps along N_{i+1/2}, and at each convex corner
   * (psi_i > 0) the disk sector of angle psi_i (Minkowski; its arc as chords of at most ARC_STEP) or
   * the kite up to where the two moved edges meet, v_i + eps (N_{i-1/2} + tan(psi_i/2) T_{i-1/2})
   * (offset): the corners of ddg's DiscreteCurve.inflate; or chapter 6's fill (its theorem thm-fills),
   * the two triangles from v_i to p_i = v_i + h_i N_i on the bisector, h_i = eps A_i k_i / (2 sin(psi_i/2)),
   * which add eps^2/2 A_i k_i for the curvature k (bisector). The polygon and its pieces, united, are
   * the region; at a reflex corner (psi_i < 0) the two rectangles overlap instead. */
  function pieces(curve, eps, method, k) {
    var v = curve.vertices, n = v.length, N = curve.normals, T = curve.tangents, psi = curve.turning_angles;
    var bisectors = method === "bisector" ? curve.bisector_normals : null;  // a getter: computed once here
    var at = function (p, d, s) { return [p[0] + s * d[0], p[1] + s * d[1]]; };
    var rectangles = v.map(function (p, i) { var q = v[(i + 1) % n]; return [p, q, at(q, N[i], eps), at(p, N[i], eps)]; });
    var corners = [];
    v.forEach(function (p, i) {
      if (!(psi[i] > 0)) return;
      var a = N[(i + n - 1) % n], b = N[i], ring = [p, at(p, a, eps)];
      if (method === "bisector") {
        var h = eps * curve.dual_lengths[i] * k[i] / (2 * Math.sin(psi[i] / 2));
        corners.push(ring.concat([at(p, bisectors[i], h), at(p, b, eps)]));
        return;
      }
      if (method === "offset") {
        var Tp = T[(i + n - 1) % n], t = curve.tan_half_psi[i];
        corners.push(ring.concat([at(p, [a[0] + t * Tp[0], a[1] + t * Tp[1]], eps), at(p, b, eps)]));
        return;
      }
      var m = Math.ceil(psi[i] / ARC_STEP), a0 = Math.atan2(a[1], a[0]);
      for (var j = 1; j < m; j++) ring.push(at(p, [Math.cos(a0 - psi[i] * j / m), Math.sin(a0 - psi[i] * j / m)], eps));
      corners.push(ring.concat([at(p, b, eps)]));
    });
    return {rectangles: rectangles, corners: corners};
  }
  function crossing(v) {  // the first two edges, not neighbours, that meet: [i, j] (from v_i and from v_j); null if simple
    var n = v.length, o = function (a, b, c) { return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]); };
    var on = function (a, b, c) {  // c, on the line through a and b, lies between them
      return Math.min(a[0], b[0]) <= c[0] && c[0] <= Math.max(a[0], b[0]) && Math.min(a[1], b[1]) <= c[1] && c[1] <= Math.max(a[1], b[1]);
    };
    for (var i = 0; i < n; i++) {
      for (var j = i + 2; j < n - (i === 0 ? 1 : 0); j++) {
        var a = v[i], b = v[i + 1], c = v[j], d = v[(j + 1) % n], s1 = o(c, d, a), s2 = o(c, d, b), s3 = o(a, b, c), s4 = o(a, b, d);
        if (s1 * s2 < 0 && s3 * s4 < 0) return [i, j];
        if ((!s1 && on(c, d, a)) || (!s2 && on(c, d, b)) || (!s3 && on(a, b, c)) || (!s4 && on(a, b, d))) return [i, j];
      }
    }
    return null;
  }
  // the curvatures the lab shows: ddg's three, and chapter 6's circle where ddg-lab-circle.js is there
  var KINDS = window.ddgLab.CURVATURES.concat(window.ddgLab.circle_curvature ? ["circle"] : []);
  function regionArea(region) {  // a multipolygon of polygon-clipping: outer rings counter-clockwise, holes clockwise
    return region.reduce(function (total, polygon) {
      return polygon.reduce(function (sum, ring) { return sum + window.ddgLab.signed_area_ccw(ring.slice(0, -1)); }, total);
    }, 0);
  }

  function bounds(points) {
    var xs = points.map(function (p) { return p[0]; }), ys = points.map(function (p) { return p[1]; });
    return [Math.min.apply(null, xs), Math.min.apply(null, ys), Math.max.apply(null, xs), Math.max.apply(null, ys)];
  }
  function frame(svg, points) {  // a square view of the points with a margin; y flipped
    var b = bounds(points), size = Math.max(b[2] - b[0], b[3] - b[1], 1e-9) * 1.3, cx = (b[0] + b[2]) / 2, cy = (b[1] + b[3]) / 2;
    svg.setAttribute("viewBox", [cx - size / 2, -cy - size / 2, size, size].join(" "));
    return size;
  }
  function pathOf(points, closed) {
    return points.length ? "M" + points.map(function (p) { return p[0] + "," + -p[1]; }).join("L") + (closed ? "Z" : "") : "";
  }
  function plot(svg, series, x0, x1, y0, y1) {  // polylines in a 360 x 120 chart: [[x, y] ...], styles; kept and reused
    var pad = 0.06 * (y1 - y0 || 1), w = 360, h = 120, sx = w / (x1 - x0 || 1), sy = (h - 8) / (y1 - y0 + 2 * pad);
    y0 -= pad;
    if (!svg.axis) svg.axis = element("line", {x1: 0, x2: w, stroke: "currentColor", "stroke-opacity": 0.3}, svg);
    svg.axis.setAttribute("y1", h - 4 + y0 * sy);
    svg.axis.setAttribute("y2", h - 4 + y0 * sy);
    svg.lines = svg.lines || [];
    while (svg.lines.length > series.length) svg.removeChild(svg.lines.pop());
    series.forEach(function (s, j) {
      var line = svg.lines[j] || (svg.lines[j] = element("polyline", {fill: "none", "stroke-width": 1.5}, svg));
      line.setAttribute("stroke", s.color);
      line.setAttribute("stroke-dasharray", s.dashed ? "5 3" : "none");
      line.setAttribute("points", s.points.map(function (p) {
        return ((p[0] - x0) * sx).toFixed(1) + "," + (h - 4 - (p[1] - y0) * sy).toFixed(1);
      }).join(" "));
    });
  }

  function Lab(root) {
    var self = this, controls = element("div", {class: "ddg-controls"}, root), edits = element("div", {class: "ddg-controls"}, root);
    var query = new URLSearchParams(window.location.search), lab = window.ddgLab;
    root.querySelectorAll(".ddg-lab-static").forEach(function (e) { e.hidden = true; });
    this.shape = control(controls, "shape", element("select", {}, null));
    Object.keys(SMOOTH).concat(Object.keys(POLYGONS)).forEach(function (s) { element("option", {value: s}, self.shape).textContent = s; });
    this.n = control(controls, "n", element("input", {type: "number", min: 3, max: 2000, step: 1, value: query.get("n") || root.dataset.n || 12}));
    this.kind = control(controls, "curvature", element("select", {}, null));
    KINDS.forEach(function (k) { element("option", {value: k}, self.kind).textContent = k; });
    this.arrows = control(controls, "arrows of ∇L", element("input", {type: "checkbox"}, null));
    this.shape.value = SHORT_NAMES[query.get("lab")] || this.shape.value;
    if (KINDS.indexOf(query.get("kind")) >= 0) this.kind.value = query.get("kind");
    this.arrows.checked = query.get("arrows") === "1";
    var reset = button(controls, "Reset", "the preset again");
    this.draw = button(edits, "Draw", "click or tap in the plane to place vertices, clockwise; press again to finish");
    this.draw.setAttribute("aria-pressed", "false");
    var add = button(edits, "Add vertex", "a vertex in the middle of the edge after the selected vertex (key: Insert or +)");
    var remove = button(edits, "Remove vertex", "remove the selected vertex (key: Delete or -)");
    var undo = button(edits, "Undo", "undo the last change (key: Ctrl+Z)");
    var inflating = element("div", {class: "ddg-controls"}, root);
    this.method = control(inflating, "inflate", element("select", {}, null));
    element("option", {value: ""}, this.method).textContent = "no";
    Object.keys(INFLATIONS).forEach(function (m) { element("option", {value: m}, self.method).textContent = INFLATIONS[m][0]; });
    this.method.value = INFLATIONS[query.get("inflate")] ? query.get("inflate") : "";
    this.eps = control(inflating, "by ε", element("input", {type: "range", min: 0, max: 1, step: 0.01, value: query.get("eps") || 0.2}));
    this.epsShown = element("output", {}, this.eps.parentNode);
    this.svg = element("svg", {class: "ddg-panel ddg-lab-svg", width: 360, height: 360, role: "group",
                               "aria-label": "the polygon: each vertex is a button; arrow keys move it, Page Up and Page Down go to the previous and next vertex, Insert adds a vertex after it, Delete removes it"}, root);
    this.region = element("path", {"fill-opacity": 0.25, stroke: "none", class: "ddg-lab-region"}, this.svg);
    this.pieces = element("path", {"fill-opacity": 0.15, "stroke-width": 0.75, "vector-effect": "non-scaling-stroke", class: "ddg-lab-pieces"}, this.svg);
    this.path = element("path", {fill: "none", stroke: "currentColor", "stroke-width": 1.5, "vector-effect": "non-scaling-stroke"}, this.svg);
    this.arrowPath = element("path", {fill: "none", stroke: "#7c3aed", "stroke-width": 1.5, "vector-effect": "non-scaling-stroke", class: "ddg-lab-arrows"}, this.svg);
    this.dots = element("g", {}, this.svg);
    this.summary = element("p", {class: "ddg-summary", "aria-live": "polite"}, root);
    this.detail = element("p", {class: "ddg-detail ddg-lab-detail", "aria-live": "polite"}, root);
    this.inflation = element("p", {class: "ddg-summary ddg-lab-inflation", "aria-live": "polite"}, root);
    this.chart = element("svg", {class: "ddg-panel ddg-lab-chart", viewBox: "0 0 360 120", width: 360, height: 120, "aria-hidden": "true"}, root);
    this.caption = element("p", {class: "ddg-detail ddg-lab-caption"}, root);
    this.history = [];
    this.selected = 0;
    this.flows = new Flows(this, element("div", {class: "ddg-lab-flows"}, root));
    this.shape.addEventListener("change", function () { self.reset(); });
    this.n.addEventListener("change", function () { if (Number(self.n.value) !== self.presetN) self.reset(); });  // not again on blur
    reset.addEventListener("click", function () { self.reset(); });
    this.kind.addEventListener("change", function () { self.update(); });
    this.arrows.addEventListener("change", function () { self.update(); });
    this.method.addEventListener("change", function () { self.fit(); });
    this.eps.addEventListener("input", function () { self.fit(); });
    this.draw.addEventListener("click", function () { self.toggleDrawing(); });
    add.addEventListener("click", function () { self.add(self.selected); });
    remove.addEventListener("click", function () { self.remove(self.selected); });
    undo.addEventListener("click", function () { self.undo(); });
    root.addEventListener("keydown", function (event) {
      if ((event.ctrlKey || event.metaKey) && event.key.toLowerCase() === "z") { event.preventDefault(); self.undo(); }
    });
    this.dots.addEventListener("keydown", function (event) { self.key(event); });
    this.svg.addEventListener("pointerdown", function (event) {
      if (self.drawing) {
        self.remember();
        self.vertices.push(self.point(event));
        self.rebuild();
        return;
      }
      if (event.target.index === undefined) return;
      self.remember();
      self.dragging = event.target.index;
      self.select(event.target.index);
      event.target.setPointerCapture(event.pointerId);
      event.preventDefault();
    });
    this.svg.addEventListener("pointermove", function (event) {
      if (self.dragging === undefined) return;
      self.vertices[self.dragging] = self.point(event);
      if (!self.frame) self.frame = requestAnimationFrame(function () { self.frame = 0; self.update(self.dragging); });
    });
    ["pointerup", "pointercancel"].forEach(function (name) {
      self.svg.addEventListener(name, function () {
        var i = self.dragging;
        self.dragging = undefined;
        if (i !== undefined) self.update(i);  // where it was let go, on the colour scale of its curvatures
      });
    });
    this.reset();
  }

  Lab.prototype.point = function (event) {  // the pointer in data coordinates
    var p = this.svg.createSVGPoint();
    p.x = event.clientX; p.y = event.clientY;
    p = p.matrixTransform(this.svg.getScreenCTM().inverse());
    return [p.x, -p.y];
  };
  Lab.prototype.remember = function () {  // for Undo: the polygon before a change (which ends the last note)
    if (!this.drawing) this.note = "";
    this.history.push(this.vertices.map(function (p) { return p.slice(); }));
    if (this.history.length > 200) this.history.shift();
  };
  Lab.prototype.undo = function () {
    if (!this.history.length) { this.say("Nothing to undo."); return; }
    this.vertices = this.history.pop();
    this.rebuild();
  };
  Lab.prototype.say = function (text) { this.note = text; this.update(); };

  Lab.prototype.reset = function () {  // the preset: n vertices on the smooth curve at t_k, or chapter 5's polygon
    var name = this.shape.value, smooth = SMOOTH[name], n = Math.min(Math.max(Math.round(Number(this.n.value)) || 12, 3), 2000);
    if (this.vertices) this.remember();
    this.n.value = this.presetN = n;
    this.n.disabled = !smooth;
    var t = smooth ? Array.from({length: n}, function (_, k) { return 2 * Math.PI * (k + smooth.shift) / n; }) : [];
    this.vertices = smooth ? t.map(function (s) { return smooth.at(s)[0]; }) : POLYGONS[name].map(function (p) { return p.slice(); });
    this.kappa = smooth ? t.map(function (s) { return kappa(s, smooth.at); }) : null;  // kappa(t_i), for the chart
    this.size = frame(this.svg, smooth ? Array.from({length: 96}, function (_, k) { return smooth.at(k * Math.PI / 48)[0]; }) : this.vertices);
    this.selected = 0;
    if (this.drawing) this.toggleDrawing();
    if (this.method.value) this.fit(); else this.rebuild();
  };

  Lab.prototype.fit = function () {  // the view of the polygon and, when it is inflated, of its pieces
    var points = this.vertices.slice(), eps = Number(this.eps.value), curve = null;
    try { curve = new window.ddgLab.DiscreteCurve(this.vertices); } catch (e) { /* drawn as it is */ }
    if (curve && this.method.value && eps > 0 && curve.signed_area > 0) {
      var parts = pieces(curve, eps, this.method.value === "bisector" ? "offset" : this.method.value);  // a fill lies in its kite
      parts.rectangles.concat(parts.corners).forEach(function (r) { points = points.concat(r); });
    }
    if (points.length) this.size = frame(this.svg, points);
    this.rebuild();
  };

  Lab.prototype.rebuild = function () {  // new handles: after a preset, an added or removed vertex, drawing, undo
    var self = this, n = this.vertices.length, focused = this.dots.contains(document.activeElement);
    if (this.kappa && this.kappa.length !== n) this.kappa = null;  // no longer the smooth curve's sample
    this.selected = Math.min(this.selected, Math.max(n - 1, 0));
    this.dots.textContent = "";
    this.circles = this.vertices.map(function (v, i) {
      var c = element("circle", {r: this.size * Math.max(0.004, Math.min(0.015, 0.5 / n)), tabindex: i === self.selected ? 0 : -1,
                                 role: "button", class: "ddg-handle"}, self.dots);
      c.index = i;
      return c;
    }, this);
    if (focused && n) this.circles[this.selected].focus();  // the keys keep working after Undo
    this.update();
  };

  Lab.prototype.select = function (i) {
    if (this.circles[this.selected]) this.circles[this.selected].setAttribute("tabindex", -1);
    this.selected = i;
    this.circles[i].setAttribute("tabindex", 0);
    this.circles[i].focus();
  };
  Lab.prototype.add = function (i) {  // a vertex in the middle of the edge from v_i to v_{i+1}
    var v = this.vertices, n = v.length;
    if (n < 2) { this.say("Place two vertices first."); return; }
    this.remember();
    var p = v[i], q = v[(i + 1) % n];
    v.splice(i + 1, 0, [(p[0] + q[0]) / 2, (p[1] + q[1]) / 2]);
    this.selected = i + 1;
    this.rebuild();
    this.circles[i + 1].focus();
  };
  Lab.prototype.remove = function (i) {
    if (this.vertices.length <= 3) { this.say("A closed polygon needs at least 3 vertices: vertex " + i + " stays."); return; }
    this.remember();
    this.vertices.splice(i, 1);
    this.selected = i % this.vertices.length;
    this.rebuild();
    this.circles[this.selected].focus();
  };
  Lab.prototype.toggleDrawing = function () {
    this.drawing = !this.drawing;
    this.draw.setAttribute("aria-pressed", String(this.drawing));
    this.draw.textContent = this.drawing ? "Done" : "Draw";
    this.svg.classList.toggle("ddg-drawing", this.drawing);  // a finger draws instead of scrolling
    if (this.drawing) {
      this.remember();
      this.vertices = [];
      this.note = "Click or tap in the plane to place the vertices, clockwise; press Done to finish.";
      this.rebuild();
    } else {
      this.note = "";
      this.update();
    }
  };
  Lab.prototype.move = function (i, p) {
    this.vertices[i] = p;
    this.update(i);
  };

  Lab.prototype.key = function (event) {
    var i = event.target.index, n = this.vertices.length, step = (event.shiftKey ? 0.1 : 0.01);
    var moves = {ArrowLeft: [-step, 0], ArrowRight: [step, 0], ArrowUp: [0, step], ArrowDown: [0, -step]};
    var to = {PageUp: i - 1, PageDown: i + 1, Home: 0, End: n - 1}[event.key];
    if (i === undefined) return;
    if (event.key === "Insert" || event.key === "+") { event.preventDefault(); this.add(i); return; }
    if (event.key === "Delete" || event.key === "-" || event.key === "Backspace") { event.preventDefault(); this.remove(i); return; }
    if (!(event.key in moves || to !== undefined)) return;
    event.preventDefault();
    if (to !== undefined) { this.select((to + n) % n); this.update(); return; }
    var v = this.vertices[i];
    this.remember();
    this.move(i, [v[0] + moves[event.key][0], v[1] + moves[event.key][1]]);
  };

  /* Draw the polygon and say what ddg's formulas give. After vertex `moved` moved, only it and its
   * neighbours have a new place or curvature; the colours may all change (they are scaled by the
   * largest |k|), so each attribute is written only where it changed. */
  Lab.prototype.update = function (moved) {
    var v = this.vertices, n = v.length, kind = this.kind.value, lab = window.ddgLab, curve = null, k = null, parts = [], s = this.summary;
    var ks = this.ks = {}, gradient = null;  // each curvature and the gradient of length, once for everything
    // shown (lab.ks: the tests read the circle curvature there)
    this.path.setAttribute("d", pathOf(v, !this.drawing));
    ["turningNumber", "length", "signedArea"].forEach(function (name) { delete s.dataset[name]; });
    try { curve = new lab.DiscreteCurve(v); } catch (e) { parts.push("Not a polygon the lecture allows: " + e.message + "."); }
    if (curve) {
      KINDS.forEach(function (name) {
        try { ks[name] = name === "circle" ? lab.circle_curvature(curve) : curve.curvature(name); } catch (e) { ks[name] = e; }
      });
      gradient = curve.length_gradient();
      k = Array.isArray(ks[kind]) ? ks[kind] : null;
      if (!k) parts.push("No " + kind + " curvature: " + ks[kind].message + ".");
      try {
        s.dataset.turningNumber = curve.turning_number;
        parts.push("Turning number " + curve.turning_number + ",");
      } catch (e) { parts.push("No turning number (" + e.message + "),"); }
      s.dataset.length = curve.length;
      s.dataset.signedArea = curve.signed_area;
      parts.push("length " + short(curve.length) + ", signed area " + short(curve.signed_area) + ".");
    }
    var top = k ? Math.max.apply(null, k.map(Math.abs)) || 1 : 1;
    if (this.dragging === undefined) this.dragTop = 0;  // a drag keeps its first colour scale: were it to follow the
    else top = this.dragTop = this.dragTop || top;      // dragged vertex's |k|, every vertex would be restyled each frame
    this.circles.forEach(function (c, i) {
      var fill = k ? LEVELS[Math.round(64 * Math.min(Math.max(0.5 + k[i] / (2 * top), 0), 1))] : RAMP[1];
      if (c.fill !== fill) c.setAttribute("fill", c.fill = fill);
      if (moved !== undefined && (i - moved + n + 1) % n > 2) return;  // not moved and not a neighbour
      c.setAttribute("cx", v[i][0]);
      c.setAttribute("cy", -v[i][1]);
      c.setAttribute("aria-label", "vertex " + i + " at (" + short(v[i][0]) + ", " + short(v[i][1]) + ")" +
                     (k ? ", " + kind + " curvature " + short(k[i]) : ""));
    });
    s.textContent = parts.join(" ");
    this.arrowPath.setAttribute("d", gradient && this.arrows.checked ? this.arrowsPath(gradient) : "");
    this.inflate(this.drawing ? null : curve, ks[kind]);
    this.describe(curve, ks, gradient);
  };

  /* The polygon inflated by eps: its pieces and the formula's area at once; the region, their union,
   * measured when the hand stops (a drag asks for it again at every frame). */
  Lab.prototype.inflate = function (curve, k) {
    var method = this.method.value, eps = Number(this.eps.value), p = this.inflation, self = this, formula;
    this.epsShown.textContent = eps.toFixed(2);
    this.eps.disabled = !method;
    clearTimeout(this.measuring);
    this.region.setAttribute("d", "");
    this.pieces.setAttribute("d", "");
    delete p.dataset.formula; delete p.dataset.measured;
    p.textContent = "";
    if (!method || !curve) return;
    var name = INFLATIONS[method][0], color = INFLATIONS[method][1];
    try {  // the formulas are for a simple clockwise polygon (crossings looked for where the region is measured: O(n^2))
      var turns = curve.turning_number, cross = curve.vertices.length <= MEASURED_UP_TO && crossing(curve.vertices);
      if (turns === -1) throw new Error("the polygon runs counter-clockwise, so its normals point inward and inflating it would erode it; reverse it (draw it clockwise)");
      if (turns !== 1) throw new Error("the formulas are for a simple clockwise polygon, and this one has turning number " + turns);
      if (cross) throw new Error("the formulas are for a simple polygon, and the edges from vertex " + cross[0] + " and from vertex " + cross[1] + " meet");
      if (method === "bisector" && !Array.isArray(k)) throw new Error("no " + this.kind.value + " curvature here");
      formula = method !== "bisector" ? curve.inflated_area(eps, method) : curve.signed_area + eps * curve.length +
        eps * eps / 2 * k.reduce(function (sum, x, i) { return sum + curve.dual_lengths[i] * x; }, 0);  // <k, 1> = sum A_i k_i
    } catch (e) { p.textContent = "No inflation: " + e.message + "."; return; }
    var parts = eps > 0 ? pieces(curve, eps, method, k) : {rectangles: [], corners: []}, said = "Inflated by ε = " + eps.toFixed(2) + ", " + name + ": the formula " +
      INFLATIONS[method][2] + (method === "bisector" ? " (k: " + this.kind.value + ")" : "") + " gives " + short(formula);
    p.dataset.formula = formula;
    this.pieces.setAttribute("fill", color);
    this.pieces.setAttribute("stroke", color);
    this.pieces.setAttribute("d", parts.rectangles.concat(parts.corners).map(function (r) { return pathOf(r, true); }).join(""));
    if (curve.vertices.length > MEASURED_UP_TO) { p.textContent = said + "; the region is measured for polygons of up to " + MEASURED_UP_TO + " vertices."; return; }
    p.textContent = said + "; measuring the region …";
    this.measuring = setTimeout(function () {
      var region, area;
      try {
        region = window.polygonClipping.union.apply(null, [[curve.vertices]].concat(parts.rectangles.concat(parts.corners).map(function (r) { return [r]; })));
        area = regionArea(region);
      } catch (e) { p.textContent = said + "; the region could not be measured (" + e.message + ")."; return; }
      p.dataset.measured = area;
      self.region.setAttribute("fill", color);
      self.region.setAttribute("d", region.map(function (polygon) {
        return polygon.map(function (ring) { return pathOf(ring.slice(0, -1), true); }).join("");
      }).join(""));
      p.textContent = said + "; the region (shaded), the polygon with these pieces united, measures " + short(area) +
        ": formula − region = " + Number((formula - area).toPrecision(2)) + ".";
    }, this.dragging !== undefined ? 150 : 0);
  };

  Lab.prototype.arrowsPath = function (g) {  // grad L at each vertex, the longest 0.2 of the view
    var v = this.vertices, top = Math.max.apply(null, g.map(function (x) { return Math.hypot(x[0], x[1]); })) || 1;
    var scale = 0.2 * this.size / top, head = 0.02 * this.size;
    return g.map(function (x, i) {
      var a = v[i], b = [a[0] + scale * x[0], a[1] + scale * x[1]], len = Math.hypot(x[0], x[1]) * scale;
      if (!(len > 0)) return "M" + a[0] + "," + -a[1] + "L" + a[0] + "," + -a[1];  // a straight vertex: nothing to draw
      var ux = (b[0] - a[0]) / len, uy = (b[1] - a[1]) / len, h = Math.min(head, len / 2);
      return "M" + a[0] + "," + -a[1] + "L" + b[0] + "," + -b[1] +
             "M" + (b[0] - h * (ux - 0.5 * uy)) + "," + -(b[1] - h * (uy + 0.5 * ux)) + "L" + b[0] + "," + -b[1] +
             "L" + (b[0] - h * (ux + 0.5 * uy)) + "," + -(b[1] - h * (uy - 0.5 * ux));
    }, this).join("");
  };

  /* The selected vertex in words, and the chosen curvature along the polygon beside the smooth curve's. */
  Lab.prototype.describe = function (curve, ks, gradient) {
    var i = this.selected, words = [], kind = this.kind.value, k = Array.isArray(ks[kind]) ? ks[kind] : null, smooth = this.kappa;
    if (this.note) words.push(this.note);
    if (curve) {
      var psi = curve.turning_angles[i], g = gradient[i];
      words.push("Vertex " + i + ": ψ = " + short(psi * 180 / Math.PI) + "° (" + (psi > 0 ? "turning clockwise" : psi < 0 ? "turning counter-clockwise" : "straight") + "); k: " +
                 KINDS.map(function (name) {
                   return name + " " + (Array.isArray(ks[name]) ? short(ks[name][i]) : "undefined");
                 }).join(", ") + "; |\u2060∇L\u2060| = " + short(Math.hypot(g[0], g[1])) + ".");
    }
    this.detail.textContent = words.join(" ");
    var series = [], values = [];
    if (k) { series.push({color: "currentColor", points: k.map(function (x, j) { return [j, x]; })}); values = values.concat(k); }
    if (smooth) { series.push({color: RAMP[2], dashed: true, points: smooth.map(function (x, j) { return [j, x]; })}); values = values.concat(smooth); }
    var lo = Math.min(0, Math.min.apply(null, values)), hi = Math.max(0, Math.max.apply(null, values));
    plot(this.chart, series, 0, Math.max(this.vertices.length - 1, 1), lo, hi);
    this.caption.textContent = k ? "Above: the " + kind + " curvature k_i (solid) at vertex 0 to " + (k.length - 1) +
      (smooth ? ", and the smooth curve's curvature κ(t_i) where it was sampled (dashed)" : "") +
      "; from " + short(lo) + " to " + short(hi) + "." : "";
  };

  /* The three flows side by side, from the lab's polygon: ddg.flow.flow's explicit steps (ddgLab.flow_step),
   * the one furthest behind in time first, so all three show the same moment. */
  function Flows(lab, root) {
    var self = this, controls = element("div", {class: "ddg-controls"}, root);
    this.lab = lab;
    this.start = button(controls, "Flow this shape", "run the three flows from the polygon above");
    this.play = button(controls, "Play", "play or pause the flows");
    this.play.setAttribute("aria-pressed", "false");
    this.stepButton = button(controls, "Step", "one step of the flow furthest behind");
    this.panels = element("div", {class: "ddg-lab-panels"}, root);
    this.chart = element("svg", {class: "ddg-panel ddg-lab-chart", viewBox: "0 0 360 120", width: 360, height: 120, "aria-hidden": "true"}, root);
    this.caption = element("p", {class: "ddg-detail"}, root);
    this.chart.style.display = "none";  // until a flow starts
    this.status = element("p", {class: "ddg-summary ddg-lab-flow-status", "aria-live": "polite"}, root);
    this.start.addEventListener("click", function () { self.begin(); });
    this.play.addEventListener("click", function () { self.toggle(); });
    this.stepButton.addEventListener("click", function () { if (!self.runs) self.begin(); self.step(); self.draw(); });
  }
  Flows.prototype.begin = function () {
    var self = this, v = this.lab.vertices.map(function (p) { return p.slice(); }), curve;
    this.pause();
    try { curve = new window.ddgLab.DiscreteCurve(v); } catch (e) { this.status.textContent = "No flow: " + e.message + "."; return; }
    this.panels.textContent = "";
    this.chart.style.display = "";
    this.area0 = curve.signed_area;
    this.length0 = curve.length;
    this.areaUnit = Math.abs(this.area0) > 1e-9 * this.length0 * this.length0 ? Math.abs(this.area0) : this.length0 * this.length0 / (4 * Math.PI);
    this.runs = window.ddgLab.CURVATURES.map(function (kind) {
      var figure = element("figure", {class: "ddg-lab-flow"}, self.panels), svg = element("svg", {class: "ddg-panel", width: 170, height: 170, "aria-hidden": "true"}, figure);
      frame(svg, v);
      var run = {kind: kind, vertices: v, t: 0, stopped: null, record: [[0, 1, curve.signed_area / self.areaUnit]],
                 path: element("path", {fill: "none", stroke: FLOW_COLORS[kind], "stroke-width": 2, "vector-effect": "non-scaling-stroke"}, svg),
                 label: element("figcaption", {}, figure)};
      element("path", {d: pathOf(v, true), fill: "none", stroke: "currentColor", "stroke-opacity": 0.3, "vector-effect": "non-scaling-stroke"}, svg);
      return run;
    });
    this.draw();
  };
  Flows.prototype.step = function () {  // one explicit step of the running flow with the smallest t
    var open = (this.runs || []).filter(function (r) { return !r.stopped; });
    if (!open.length) return false;
    var run = open.reduce(function (a, b) { return b.t < a.t ? b : a; });
    try {
      var next = window.ddgLab.flow_step(run.vertices, run.kind, this.length0), c = new window.ddgLab.DiscreteCurve(next.vertices);
      run.vertices = next.vertices;
      run.t += next.dt;
      run.record.push([run.t, c.length / this.length0, c.signed_area / this.areaUnit]);
    } catch (e) {
      run.stopped = e.message.replace(/^stopped at t = [^:]*: /, "");
    }
    return true;
  };
  Flows.prototype.toggle = function () {
    if (this.timer) { this.pause(); return; }
    if (!this.runs || this.runs.every(function (r) { return r.stopped; })) this.begin();
    var self = this;
    this.play.textContent = "Pause";
    this.play.setAttribute("aria-pressed", "true");
    var tick = function () {  // steps for up to 8 ms of each frame
      var until = performance.now() + 8, going = true;
      while (going && performance.now() < until) going = self.step();
      self.draw();
      self.timer = going ? requestAnimationFrame(tick) : 0;
      if (!going) self.pause();
    };
    this.timer = requestAnimationFrame(tick);
  };
  Flows.prototype.pause = function () {
    if (this.timer) cancelAnimationFrame(this.timer);
    this.timer = 0;
    this.play.textContent = "Play";
    this.play.setAttribute("aria-pressed", "false");
  };
  Flows.prototype.draw = function () {
    var series = [], tmax = 0, lo = 0, hi = 1;
    this.runs.forEach(function (r) {
      r.path.setAttribute("d", pathOf(r.vertices, true));
      r.label.textContent = r.kind + " flow, t = " + short(r.t) + (r.stopped ? ": stopped" : "");
      tmax = Math.max(tmax, r.t);
      r.record.forEach(function (p) { lo = Math.min(lo, p[2]); hi = Math.max(hi, p[2]); });
      series.push({color: FLOW_COLORS[r.kind], points: r.record.map(function (p) { return [p[0], p[1]]; })},
                  {color: FLOW_COLORS[r.kind], dashed: true, points: r.record.map(function (p) { return [p[0], p[2]]; })});
    });
    plot(this.chart, series, 0, tmax || 1, lo, hi);
    this.caption.textContent = "Above: the length L/L(0) (solid) and the signed area A/" + (this.areaUnit === Math.abs(this.area0) ? "|A(0)|" : "(L(0)²/4π)") +
      " (dashed) of each flow against time t, from 0 to " + short(tmax) + "; angle blue, sine orange, tangent green.";
    this.status.textContent = this.runs.map(function (r) {
      return r.kind + " flow: " + (r.stopped ? "stopped at t = " + short(r.t) + ": " + r.stopped : "t = " + short(r.t) + ", length " + short(r.record[r.record.length - 1][1] * this.length0)) + ".";
    }, this).join(" ");
  };

  function start() {
    document.querySelectorAll(".ddg-lab").forEach(function (root) { if (!root.lab) root.lab = new Lab(root); });
  }
  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start);
  else start();
})();
