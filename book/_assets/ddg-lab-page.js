/* The lab on the page (book/10_explorers): a polygon the reader shapes (presets, drawing, dragging,
 * arrow keys, adding and removing vertices, undo), coloured by a discrete curvature (ddg's three, and
 * in the instructor's edition the circle through three vertices of chapter 6's exercise, from
 * ddg-lab-circle.js, which the student edition leaves out: it is an answer), with the
 * gradient of length as arrows, the curvature along the polygon beside the smooth curve's, the
 * polygon inflated by eps (the formula's area beside the area of the region, measured as a union of
 * polygons by polygon-clipping), and the three curve-shortening flows run side by side from it.
 * Everything else is computed by ddg-lab.js (ddg's formulas). Loaded only where there is a .ddg-lab
 * (tools/sphinx_assets.py). Data coordinates have y up; the SVG is drawn with y flipped. The address
 * can choose the start: ?lab=star&kind=tangent&n=24&arrows=1&inflate=minkowski&eps=0.4#lab (the
 * chapters link to the lab so), or a polygon of its own: ?v=x0,y0,x1,y1,...#lab (Copy address).
 * Whatever the reader types or the address asks that the lab cannot do is said in words
 * (.ddg-lab-message), and values at the rounding level of the polygon's scale are shown as 0.
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
    var svg = ["svg", "path", "circle", "g", "polyline", "line", "text"].indexOf(name) >= 0;
    var e = document.createElementNS(svg ? SVG : "http://www.w3.org/1999/xhtml", name);
    if (name === "select" || name === "input") e.setAttribute("autocomplete", "off");  // no values the browser restores on reload
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
  /* Round numbers for the axes: about `count` steps of 1, 2 or 5 times a power of ten from a to b. */
  function ticks(a, b, count) {
    var span = b - a || 1, step = Math.pow(10, Math.floor(Math.log10(span / count))), r = span / count / step, out = [];
    step *= r >= 7.5 ? 10 : r >= 3.5 ? 5 : r >= 1.5 ? 2 : 1;
    for (var i = Math.ceil(a / step - 1e-9); i * step <= b + 1e-9 * span; i++) out.push(Number((i * step).toPrecision(12)));
    return out;
  }
  /* A chart with axes, ticks, axis labels and a legend, its lines kept and reused (a drag redraws it
   * at every frame): series [{color, dashed, points: [[x, y] ...]}], marks [{x, color, label}]
   * (vertical dashed lines: where a flow stopped, the time shown). */
  var W = 400, H = 176, LEFT = 46, RIGHT = 10, TOP = 32, BOTTOM = 30;  // the legend above the y axis's name
  function Chart(parent, xlabel, ylabel, legend) {
    this.svg = element("svg", {class: "ddg-panel ddg-lab-chart", viewBox: "0 0 " + W + " " + H, width: W, height: H, role: "img"}, parent);
    this.axes = element("g", {class: "ddg-chart-axes", "font-size": 11, fill: "currentColor"}, this.svg);
    this.plotted = element("g", {}, this.svg);
    this.marked = element("g", {}, this.svg);
    this.labels = [xlabel, ylabel];
    this.lines = [];
    var x = LEFT;
    this.legend = legend.map(function (item) {  // [text, color, dashed]: a group each, hidden without its series
      var g = element("g", {}, this.svg);
      element("line", {x1: x, x2: x + 18, y1: 8, y2: 8, stroke: item[1], "stroke-width": 2, "stroke-dasharray": item[2] ? "5 3" : "none"}, g);
      var t = element("text", {x: x + 22, y: 12, "font-size": 11, fill: "currentColor", class: "ddg-chart-legend"}, g);
      t.textContent = item[0];
      x += 30 + 6.2 * item[0].length;
      return g;
    }, this);
  }
  Chart.prototype.draw = function (series, x0, x1, y0, y1, marks, alt, legendShown) {
    this.legend.forEach(function (g, j) {
      var shown = !legendShown || legendShown[j];
      if (g.shown !== shown) { g.shown = shown; g.setAttribute("visibility", shown ? "visible" : "hidden"); }
    });
    var w = W - LEFT - RIGHT, h = H - TOP - BOTTOM, round = ticks(y0, y1, 4), step = round[1] - round[0] || 1;
    y0 = Math.floor(y0 / step + 1e-9) * step;  // out to round numbers: while a drag stays within them,
    y1 = Math.ceil(y1 / step - 1e-9) * step;   // the axes are not drawn again
    if (y1 <= y0) y1 = y0 + step;
    if (this.roundX) {  // so too while a flow's time grows
      var across = ticks(x0, x1, 6), xstep = across[1] - across[0] || 1;
      x1 = Math.max(Math.ceil(x1 / xstep - 1e-9) * xstep, x0 + xstep);
    }
    var sx = w / (x1 - x0 || 1), sy = h / (y1 - y0 || 1);
    var X = function (x) { return LEFT + (x - x0) * sx; }, Y = function (y) { return TOP + h - (y - y0) * sy; };
    this.svg.setAttribute("aria-label", alt);
    var key = [x0, x1, y0, y1].join();
    if (key !== this.key) {  // the axes change only with the range (not at each frame of a drag)
      this.key = key;
      this.axes.textContent = "";
      element("path", {d: "M" + LEFT + "," + TOP + "V" + (TOP + h) + "H" + (LEFT + w), fill: "none", stroke: "currentColor", "stroke-opacity": 0.6}, this.axes);
      ticks(x0, x1, 6).forEach(function (x) {
        element("line", {x1: X(x), x2: X(x), y1: TOP + h, y2: TOP + h + 4, stroke: "currentColor"}, this.axes);
        var t = element("text", {x: X(x), y: TOP + h + 15, "text-anchor": "middle", class: "ddg-chart-tick"}, this.axes);
        t.textContent = short(x);
      }, this);
      ticks(y0, y1, 4).forEach(function (y) {
        element("line", {x1: LEFT - 4, x2: LEFT + w, y1: Y(y), y2: Y(y), stroke: "currentColor", "stroke-opacity": y === 0 ? 0.5 : 0.12}, this.axes);
        var t = element("text", {x: LEFT - 6, y: Y(y) + 4, "text-anchor": "end", class: "ddg-chart-tick"}, this.axes);
        t.textContent = short(y);
      }, this);
      var xl = element("text", {x: LEFT + w, y: H - 2, "text-anchor": "end", class: "ddg-chart-label"}, this.axes);
      xl.textContent = this.labels[0];
      var yl = element("text", {x: 2, y: TOP - 8, class: "ddg-chart-label"}, this.axes);
      yl.textContent = this.labels[1];
    }
    while (this.lines.length > series.length) this.plotted.removeChild(this.lines.pop());
    series.forEach(function (s, j) {
      var line = this.lines[j] || (this.lines[j] = element("polyline", {fill: "none", "stroke-width": 1.5}, this.plotted));
      line.setAttribute("stroke", s.color);
      line.setAttribute("stroke-dasharray", s.dashed ? "5 3" : "none");
      if (s.same && line.drawn === s.same + this.key) return;  // a series that did not change, on the same axes
      line.drawn = s.same && s.same + this.key;
      line.setAttribute("points", s.points.map(function (p) { return X(p[0]).toFixed(1) + "," + Y(p[1]).toFixed(1); }).join(" "));
    }, this);
    var now = (marks || []).filter(function (m) { return !m.label; }), stops = (marks || []).filter(function (m) { return m.label; });
    this.now = this.now || [];  // upright lines at a moment: kept and moved (a drag moves the selected vertex's)
    while (this.now.length > now.length) this.marked.removeChild(this.now.pop());
    now.forEach(function (m, j) {
      var line = this.now[j] || (this.now[j] = element("line", {y1: TOP, y2: TOP + h, class: "ddg-chart-now"}, this.marked));
      line.setAttribute("x1", X(m.x));
      line.setAttribute("x2", X(m.x));
      line.setAttribute("stroke", m.color);
    }, this);
    var key = stops.map(function (m) { return [m.x, m.label, m.color]; }).join() + this.key;
    if (key === this.stopKey) return;
    this.stopKey = key;
    if (this.stops) this.svg.removeChild(this.stops);
    this.stops = element("g", {}, this.svg);
    stops.forEach(function (m) {
      element("line", {x1: X(m.x), x2: X(m.x), y1: TOP, y2: TOP + h, stroke: m.color, "stroke-dasharray": "2 2", class: "ddg-chart-stop"}, this.stops);
      if (m.label) {
        var left = X(m.x) > LEFT + w / 2, t = element("text", {x: X(m.x) + (left ? -3 : 3), y: TOP + 11 + 11 * (m.row || 0), "text-anchor": left ? "end" : "start", "font-size": 10, fill: m.color, class: "ddg-chart-stop"}, this.stops);
        t.textContent = m.label;
      }
    }, this);
  };

  var LABELS_UP_TO = 40, NEAR = {mouse: 12, pen: 12, touch: 24};  // vertex numbers drawn; how near (px) a pointer grabs
  var N_MAX = 2000, EPS_RANGE = [-1, 1], ROUNDING = 1024 * Math.pow(2, -52);
  var SPEEDS = {"slow (30 s)": 30, "normal (10 s)": 10, "fast (3 s)": 3};  // the seconds a whole recorded run plays in
  function clamp(x, lo, hi) { return Math.min(Math.max(x, lo), hi); }
  function shown(x, tolerance) { return Math.abs(x) <= tolerance ? "0" : short(x); }  // rounding noise shown as 0

  function Lab(root) {
    var self = this, controls = element("div", {class: "ddg-controls"}, root), edits = element("div", {class: "ddg-controls"}, root);
    var query = new URLSearchParams(window.location.search), told = [];
    this.root = root;
    root.querySelectorAll(".ddg-lab-static").forEach(function (e) { e.hidden = true; });
    this.shape = control(controls, "shape", element("select", {}, null));
    Object.keys(SMOOTH).concat(Object.keys(POLYGONS)).forEach(function (s) { element("option", {value: s}, self.shape).textContent = s; });
    this.editedOption = element("option", {value: "edited", disabled: ""}, this.shape);
    this.editedOption.textContent = "your polygon (edited)";
    this.n = control(controls, "n", element("input", {type: "number", min: 3, max: N_MAX, step: 1, value: root.dataset.n || 12}));
    this.kind = control(controls, "curvature", element("select", {}, null));
    KINDS.forEach(function (k) { element("option", {value: k}, self.kind).textContent = k; });
    this.arrows = control(controls, "arrows of ∇L", element("input", {type: "checkbox"}, null));
    this.draw = button(edits, "Draw", "click or tap in the plane to place vertices, clockwise; press again to finish");
    this.draw.setAttribute("aria-pressed", "false");
    var add = button(edits, "Add vertex", "a vertex in the middle of the edge after the selected vertex (key: Insert or +)");
    var remove = button(edits, "Remove vertex", "remove the selected vertex (key: Delete or -)");
    var undo = button(edits, "Undo", "undo the last change (key: Ctrl+Z)");
    var reset = button(edits, "Reset", "the preset again");
    this.full = button(edits, "Full screen", "the lab alone on the screen (key: Escape to leave)");
    this.full.setAttribute("aria-pressed", "false");
    var inflating = element("div", {class: "ddg-controls"}, root);
    this.method = control(inflating, "inflate", element("select", {}, null));
    element("option", {value: ""}, this.method).textContent = "no";
    Object.keys(INFLATIONS).forEach(function (m) { element("option", {value: m}, self.method).textContent = INFLATIONS[m][0]; });
    this.eps = control(inflating, "by ε", element("input", {type: "range", min: EPS_RANGE[0], max: EPS_RANGE[1], step: 0.01, value: 0.2}));
    this.epsTyped = element("input", {type: "number", min: EPS_RANGE[0], max: EPS_RANGE[1], step: 0.01, value: 0.2, "aria-label": "ε typed"}, this.eps.parentNode);
    var stage = element("div", {class: "ddg-lab-stage"}, root), view = element("div", {class: "ddg-lab-view"}, stage);
    this.svg = element("svg", {class: "ddg-panel ddg-lab-svg", width: 360, height: 360, role: "group",
                               "aria-label": "the polygon: each vertex is a button; arrow keys move it, Page Up and Page Down go to the previous and next vertex, Insert adds a vertex after it, Delete removes it"}, view);
    this.grid = element("path", {fill: "none", stroke: "currentColor", "stroke-opacity": 0.1, "vector-effect": "non-scaling-stroke", class: "ddg-lab-grid"}, this.svg);
    this.ghost = element("path", {fill: "none", stroke: "currentColor", "stroke-opacity": 0.35, "stroke-dasharray": "4 4", "vector-effect": "non-scaling-stroke", class: "ddg-lab-ghost"}, this.svg);
    this.region = element("path", {"fill-opacity": 0.25, stroke: "none", class: "ddg-lab-region"}, this.svg);
    this.pieces = element("path", {"fill-opacity": 0.15, "stroke-width": 0.75, "vector-effect": "non-scaling-stroke", class: "ddg-lab-pieces"}, this.svg);
    this.offset = element("path", {fill: "none", "stroke-width": 1.5, "stroke-dasharray": "6 3", "vector-effect": "non-scaling-stroke", class: "ddg-lab-offset"}, this.svg);
    this.path = element("path", {fill: "none", stroke: "currentColor", "stroke-width": 1.5, "vector-effect": "non-scaling-stroke"}, this.svg);
    this.arrowPath = element("path", {fill: "none", stroke: "#7c3aed", "stroke-width": 1.5, "vector-effect": "non-scaling-stroke", class: "ddg-lab-arrows"}, this.svg);
    this.dots = element("g", {}, this.svg);
    this.hoverMark = element("circle", {fill: "none", stroke: "currentColor", "stroke-width": 1.5, "stroke-dasharray": "3 2", "vector-effect": "non-scaling-stroke", class: "ddg-lab-hover", visibility: "hidden"}, this.svg);
    this.mark = element("circle", {fill: "none", "stroke-width": 2.5, "vector-effect": "non-scaling-stroke", class: "ddg-lab-mark"}, this.svg);
    this.numbers = element("g", {class: "ddg-lab-numbers", "aria-hidden": "true", fill: "currentColor", "text-anchor": "middle"}, this.svg);
    var side = element("div", {class: "ddg-lab-side"}, stage);
    this.message = element("p", {class: "ddg-lab-message", role: "status"}, side);
    this.summary = element("p", {class: "ddg-summary", "aria-live": "polite"}, side);
    this.detail = element("p", {class: "ddg-detail ddg-lab-detail", "aria-live": "polite"}, side);
    this.inflation = element("p", {class: "ddg-summary ddg-lab-inflation", "aria-live": "polite"}, side);
    var pad = element("div", {class: "ddg-controls ddg-lab-pad", role: "group", "aria-label": "the selected vertex"}, side);
    element("span", {}, pad).textContent = "selected vertex:";
    [["‹", "the previous vertex (key: Page Up)", -1], ["›", "the next vertex (key: Page Down)", 1],
     ["←", "move it left by 0.01 (key: ←)", [-0.01, 0]], ["↑", "move it up by 0.01 (key: ↑)", [0, 0.01]],
     ["↓", "move it down by 0.01 (key: ↓)", [0, -0.01]], ["→", "move it right by 0.01 (key: →)", [0.01, 0]]].forEach(function (b) {
      var knob = button(pad, b[0], b[1]);
      knob.setAttribute("aria-label", b[1]);
      knob.addEventListener("click", function () { self.nudge(b[2]); });
    });
    var sharing = element("div", {class: "ddg-controls"}, side);
    var copyArray = button(sharing, "Copy as numpy", "the vertices as a numpy array, to paste into a notebook");
    var copyAddress = button(sharing, "Copy address", "an address that opens the lab with this polygon and these settings");
    this.copied = element("textarea", {class: "ddg-lab-copied", readonly: "", rows: 3, "aria-label": "the text copied", hidden: ""}, side);
    this.tableBox = element("details", {class: "ddg-lab-table"}, side);
    element("summary", {}, this.tableBox).textContent = "Every vertex in a table (hover or tap a row to find its vertex)";
    this.tableScroll = element("div", {class: "ddg-lab-table-scroll", tabindex: 0, role: "region", "aria-label": "the table of vertices (scrolls)"}, this.tableBox);
    this.table = element("table", {}, this.tableScroll);
    var head = element("tr", {}, element("thead", {}, this.table));
    ["i", "ψᵢ (°)", "Aᵢ"].concat(KINDS.map(function (k) { return "k " + k; })).forEach(function (h) { element("th", {scope: "col"}, head).textContent = h; });
    this.rows = element("tbody", {}, this.table);
    this.chart = new Chart(root, "vertex i", "kᵢ", [["kᵢ of the polygon", "currentColor", false], ["κ(tᵢ) of the smooth curve", RAMP[2], true]]);
    this.caption = element("p", {class: "ddg-detail ddg-lab-caption"}, root);
    this.history = [];
    this.version = 0;
    this.selected = 0;
    this.flows = new Flows(this, element("div", {class: "ddg-lab-flows"}, root));

    // the address's settings (a chapter's link, or a shared polygon); what cannot be used is said
    var name = query.get("lab"), kind = query.get("kind"), method = query.get("inflate"), vs = query.get("v");
    if (name && !SHORT_NAMES[name]) told.push("the address asks for a preset “" + name + "”, which the lab does not have (" + Object.keys(SHORT_NAMES).join(", ") + ")");
    this.shape.value = SHORT_NAMES[name] || this.shape.value;
    if (kind && KINDS.indexOf(kind) < 0) told.push("the address asks for a curvature “" + kind + "”; the lab has " + KINDS.join(", "));
    if (KINDS.indexOf(kind) >= 0) this.kind.value = kind;
    if (method && !INFLATIONS[method]) told.push("the address asks to inflate by “" + method + "”; the lab has " + Object.keys(INFLATIONS).join(", "));
    this.method.value = INFLATIONS[method] ? method : "";
    this.arrows.checked = query.get("arrows") === "1";
    if (query.has("n")) told.push(this.setN(query.get("n")));
    if (query.has("n") && (vs !== null || POLYGONS[this.shape.value])) told.push("n in the address is not used: " + (vs !== null ? "the address gives the vertices" : "chapter 5's polygons have their own"));
    if (query.has("eps")) told.push(this.setEps(query.get("eps")));
    if (vs !== null) told.push(this.readVertices(vs));
    this.preset = this.shape.value;

    this.shape.addEventListener("change", function () { self.reset(); });
    this.n.addEventListener("change", function () {
      var said = self.setN(self.n.value);
      if (self.presetN !== Number(self.n.value)) self.reset(said);  // not again on blur, nor for the same n
      else self.tell(said);
    });
    reset.addEventListener("click", function () { self.n.value = self.presetN || self.n.value; self.reset(); });  // the preset as it was
    this.kind.addEventListener("change", function () { self.update(); });
    this.arrows.addEventListener("change", function () { self.fit(); });
    this.method.addEventListener("change", function () { self.fit(); });
    this.eps.addEventListener("input", function () { self.sliding = performance.now(); self.epsTyped.value = self.eps.value; self.fit(); });
    this.epsTyped.addEventListener("change", function () { var said = self.setEps(self.epsTyped.value); self.fit(); self.tell(said); });
    this.epsTyped.addEventListener("input", function () {  // as it is typed, when it is already a number in range
      var x = Number(self.epsTyped.value);
      if (self.epsTyped.value !== "" && x >= EPS_RANGE[0] && x <= EPS_RANGE[1]) { self.eps.value = x; self.fit(); }
    });
    this.draw.addEventListener("click", function () { self.toggleDrawing(); });
    add.addEventListener("click", function () { self.add(self.selected); });
    remove.addEventListener("click", function () { self.remove(self.selected); });
    undo.addEventListener("click", function () { self.undo(); });
    this.full.addEventListener("click", function () { self.fullScreen(!root.classList.contains("ddg-lab-full")); });
    copyArray.addEventListener("click", function () { self.copy(self.asNumpy(), "the " + self.vertices.length + " vertices as a numpy array: paste them into a notebook cell"); });
    copyAddress.addEventListener("click", function () { self.copy(self.address(), "the address of this polygon and these settings"); });
    this.tableBox.addEventListener("toggle", function () {  // open: a smaller drawing, a wider table beside it
      root.classList.toggle("ddg-lab-tabled", self.tableBox.open);
      if (self.tableBox.open) self.update();
    });
    this.rows.addEventListener("click", function (event) {
      var row = event.target.closest("tr");
      if (row) { self.select(row.index, true); self.update(); }
    });
    this.rows.addEventListener("pointerover", function (event) { var row = event.target.closest("tr"); self.hover(row ? row.index : undefined); });
    this.rows.addEventListener("pointerleave", function () { self.hover(undefined); });
    this.svg.addEventListener("pointerover", function (event) { self.hover(event.target.index); });
    this.svg.addEventListener("pointerleave", function () { self.hover(undefined); });
    var unsay = function (event) { if (!self.svg.contains(event.target)) self.tell(""); };
    root.addEventListener("click", unsay, true);
    root.addEventListener("change", unsay, true);
    root.addEventListener("keydown", function (event) {
      var typing = /^(INPUT|TEXTAREA|SELECT)$/.test(event.target.tagName);  // Ctrl+Z there undoes the typing
      if ((event.ctrlKey || event.metaKey) && !event.shiftKey && !typing && event.key.toLowerCase() === "z") { event.preventDefault(); self.undo(); }
    });
    document.addEventListener("keydown", function (event) {
      if (event.key === "Escape" && root.classList.contains("ddg-lab-full")) self.fullScreen(false);
    });
    this.dots.addEventListener("keydown", function (event) { self.key(event); });
    this.svg.addEventListener("pointerdown", function (event) { self.down(event); });
    this.svg.addEventListener("pointermove", function (event) {
      if (event.pointerId !== self.pointer) return;  // one finger at a time
      if (self.panning !== undefined) {  // a finger away from every vertex scrolls the page (the drawing takes every touch)
        (root.classList.contains("ddg-lab-full") ? root : window).scrollBy(0, self.panning - event.clientY);
        self.panning = event.clientY;
        return;
      }
      if (self.dragging === undefined) return;
      if (!self.dragMoved) {  // a drag starts after a few pixels: a tap, or a finger's tremor, only selects
        if (Math.hypot(event.clientX - self.grabbed[0], event.clientY - self.grabbed[1]) < (event.pointerType === "touch" ? 6 : 3)) return;
        self.dragMoved = true;
        self.remember();
      }
      var p = self.point(event, true), o = self.offsetGrab;  // the vertex keeps its place relative to the pointer
      self.vertices[self.dragging] = self.snap([p[0] + o[0], p[1] + o[1]]);
      if (!self.frame) self.frame = requestAnimationFrame(function () { self.frame = 0; if (self.dragging !== undefined) self.update(self.dragging); });
    });
    ["pointerup", "pointercancel", "lostpointercapture"].forEach(function (name) {
      self.svg.addEventListener(name, function (event) {
        if (event.pointerId !== self.pointer) return;
        var i = self.dragging, box = self.svg.getAttribute("viewBox").split(" ").map(Number), v = self.vertices[i];
        self.dragging = self.panning = self.pointer = undefined;
        self.quiet(false);
        if (i === undefined) return;
        if (v[0] < box[0] || v[0] > box[0] + box[2] || -v[1] < box[1] || -v[1] > box[1] + box[3]) self.fit();  // let go outside: shown
        else self.update(i);  // where it was let go, on the colour scale of its curvatures
      });
    });
    if (this.shared) this.show(); else this.reset();
    told = told.filter(Boolean);
    if (told.length) this.tell(told.join("; ") + ".");
  }

  /* Settings typed or read from the address: used when they are allowed, else clamped, and said. */
  Lab.prototype.setN = function (typed) {
    var x = Number(typed), n = clamp(Math.round(x), 3, N_MAX);
    if (typed === "" || !isFinite(x)) { this.n.value = this.presetN || 12; return "n must be a whole number from 3 to " + N_MAX + (typed === "" ? "" : ", and “" + typed + "” is not one") + ": n stays " + this.n.value; }
    this.n.value = n;
    if (n !== x) return "n must be a whole number from 3 to " + N_MAX + ": " + typed + " became " + n;
    return "";
  };
  Lab.prototype.setEps = function (typed) {
    var x = Number(typed), eps = clamp(x, EPS_RANGE[0], EPS_RANGE[1]);
    if (typed === "" || !isFinite(x)) { this.epsTyped.value = this.eps.value; return "ε must be a number from " + EPS_RANGE[0] + " to " + EPS_RANGE[1] + (typed === "" ? "" : ", and “" + typed + "” is not one") + ": ε stays " + this.eps.value; }
    this.eps.value = this.epsTyped.value = eps;
    if (Number(this.eps.value) !== x) return "ε goes from " + EPS_RANGE[0] + " to " + EPS_RANGE[1] + " in steps of 0.01 here: " + typed + " became " + this.eps.value;
    return "";
  };
  Lab.prototype.readVertices = function (text) {  // ?v=x0,y0,x1,y1,...: a shared polygon
    var fields = text.split(","), xs = fields.map(Number);
    if (xs.length < 6 || xs.length % 2 || !xs.every(isFinite) || fields.some(function (f) { return !f.trim(); })) return "the address's vertices (v=…) are not pairs of numbers x,y for 3 vertices or more, so the preset is shown";
    if (xs.length > 2 * N_MAX) return "the address has " + xs.length / 2 + " vertices, more than the lab's " + N_MAX + ", so the preset is shown";
    this.vertices = [];
    for (var i = 0; i < xs.length; i += 2) this.vertices.push([xs[i], xs[i + 1]]);
    this.shared = true;
    return "";
  };
  Lab.prototype.show = function () {  // a polygon that is no preset: fitted into view, and called edited
    this.edited();
    this.fit();
  };
  Lab.prototype.edited = function () {  // no longer a preset: no smooth curve beside it, n is the count
    this.shape.value = this.shown = "edited";
    this.kappa = null;
    this.n.disabled = true;
  };
  Lab.prototype.tell = function (text) { this.message.textContent = text; };  // refusals, clamps, what was copied

  Lab.prototype.down = function (event) {
    if (event.button !== 0 || (this.pointer !== undefined && event.pointerId !== this.pointer)) return;  // the main button, one pointer
    if (this.drawing) {
      this.remember();
      this.vertices.push(this.point(event));
      this.rebuild();
      this.tell("Vertex " + (this.vertices.length - 1) + " placed" + (this.vertices.length < 3 ? ": place " + (3 - this.vertices.length) + " more at least." : "; press Done to finish."));
      return;
    }
    var i = this.nearest(event);
    if (i === undefined) {
      if (event.pointerType === "touch") { this.pointer = event.pointerId; this.panning = event.clientY; this.svg.setPointerCapture(event.pointerId); }
      else if (this.circles[this.selected]) { event.preventDefault(); this.circles[this.selected].focus({preventScroll: true}); }  // the keys move it
      return;
    }
    this.dragging = i;  // remembered for Undo when it first moves: a tap only selects
    this.dragMoved = false;
    this.pointer = event.pointerId;
    this.grabbed = [event.clientX, event.clientY];
    var p = this.point(event, true);
    this.offsetGrab = [this.vertices[i][0] - p[0], this.vertices[i][1] - p[1]];
    this.quiet(true);
    this.select(i, true, true);
    this.svg.setPointerCapture(event.pointerId);
    event.preventDefault();
  };
  Lab.prototype.nearest = function (event) {  // the vertex nearest the pointer, if it is near enough to mean it
    var scale = this.svg.getScreenCTM().a, p = this.point(event, true), best, far = (NEAR[event.pointerType] || 12) / scale;
    this.vertices.forEach(function (v, i) {
      var d = Math.hypot(v[0] - p[0], v[1] - p[1]);
      if (d <= far) { far = d; best = i; }
    });
    return best;
  };
  Lab.prototype.point = function (event, exact) {  // the pointer in data coordinates, to a thousandth of the view
    var m = this.svg.getScreenCTM(), x = (event.clientX - m.e) / m.a, y = (event.clientY - m.f) / m.d;
    return exact ? [x, -y] : this.snap([x, -y]);
  };
  Lab.prototype.snap = function (p) {  // to a thousandth of the view
    var digits = Math.max(0, 3 - Math.floor(Math.log10(this.size))), step = Math.pow(10, -digits);
    return p.map(function (z) { return Number((Math.round(z / step) * step).toFixed(digits)) || 0; });
  };
  Lab.prototype.quiet = function (on) {  // no screen reader chatter at every frame of a drag or a flow
    [this.summary, this.detail, this.inflation].forEach(function (e) { e.setAttribute("aria-live", on ? "off" : "polite"); });
  };
  Lab.prototype.remember = function () {  // for Undo: the polygon before a change (which ends the last message)
    this.tell("");
    this.version++;  // the flows from the polygon before are out of date
    this.history.push({vertices: this.vertices.map(function (p) { return p.slice(); }), shape: this.shown || "edited", kappa: this.kappa,
                       preset: this.preset, presetN: this.presetN, drawing: !!this.drawing});
    if (this.history.length > 200) this.history.shift();
    if (!this.resetting) this.edited();
  };
  Lab.prototype.undo = function () {
    if (!this.history.length) { this.tell("Nothing to undo."); return; }
    var before = this.history.pop();  // the polygon, whether it was a preset untouched, whether it was being drawn
    this.vertices = before.vertices;
    if (before.drawing !== !!this.drawing) this.drawingMode(before.drawing);
    this.version++;
    this.shape.value = this.shown = before.shape;
    this.kappa = before.kappa;
    this.preset = before.preset;
    this.presetN = before.presetN;
    this.n.disabled = !SMOOTH[before.shape];
    if (this.drawing) this.rebuild(); else this.fit();
  };

  Lab.prototype.reset = function (said) {  // the preset: n vertices on the smooth curve at t_k, or chapter 5's polygon
    var name = this.shape.value === "edited" ? this.preset : this.shape.value, smooth = SMOOTH[name];
    var n = clamp(Math.round(Number(this.n.value)) || 12, 3, N_MAX);
    this.resetting = true;
    if (this.vertices) this.remember();
    this.resetting = false;
    this.shape.value = this.preset = this.shown = name;
    this.vertices = smooth ? null : POLYGONS[name].map(function (p) { return p.slice(); });
    this.n.value = smooth ? n : this.vertices.length;
    this.presetN = Number(this.n.value);
    this.n.disabled = !smooth;
    var t = smooth ? Array.from({length: n}, function (_, k) { return 2 * Math.PI * (k + smooth.shift) / n; }) : [];
    if (smooth) this.vertices = t.map(function (s) { return smooth.at(s)[0]; });
    this.kappa = smooth ? t.map(function (s) { return kappa(s, smooth.at); }) : null;  // kappa(t_i), for the chart
    this.selected = 0;
    if (this.drawing) this.drawingMode(false);
    this.fit();
    if (said) this.tell(said);
  };

  /* The view: the polygon (for a preset, its smooth curve), its arrows and its inflated pieces. The
   * arrows' scale is a fifth of the polygon's extent, and stays so while a vertex is dragged. */
  Lab.prototype.fit = function () {
    var points = this.vertices.slice(), eps = Number(this.eps.value), curve = null, smooth = SMOOTH[this.shape.value];
    try { curve = new window.ddgLab.DiscreteCurve(this.vertices); } catch (e) { /* drawn as it is */ }
    if (smooth && this.kappa) points = points.concat(Array.from({length: 96}, function (_, k) { return smooth.at(k * Math.PI / 48)[0]; }));
    var b = points.length ? bounds(points) : [-1, -1, 1, 1];
    this.arrowScale = 0.2 * Math.max(b[2] - b[0], b[3] - b[1], 1e-9);
    if (curve && this.arrows.checked) {
      var g = curve.length_gradient(), top = Math.max.apply(null, g.map(function (x) { return Math.hypot(x[0], x[1]); })) || 1, s = this.arrowScale / top;
      points = points.concat(g.map(function (x, i) { return [curve.vertices[i][0] + s * x[0], curve.vertices[i][1] + s * x[1]]; }));
    }
    if (curve && this.method.value && eps !== 0 && curve.signed_area > 0) {
      try {
        if (eps > 0) {
          var parts = pieces(curve, eps, this.method.value === "bisector" ? "offset" : this.method.value);  // a fill lies in its kite
          parts.rectangles.concat(parts.corners).forEach(function (r) { points = points.concat(r); });
        } else if (this.method.value === "offset") points = points.concat(offsetPolygon(curve, eps));
      } catch (e) { /* said where it is drawn */ }
    }
    var extent = points.length ? Math.max(b[2] - b[0], b[3] - b[1]) : 0;
    if (points.length && (extent > 1e-9 * (this.size || 1) || !this.size)) this.size = frame(this.svg, points);  // no extent: the view stays
    this.drawGrid();
    this.rebuild(true);
  };
  Lab.prototype.drawGrid = function () {  // light lines at round coordinates, behind everything
    var box = this.svg.getAttribute("viewBox").split(" ").map(Number), step = ticks(0, box[2], 8)[1] || 1, d = [], j, z;
    for (j = Math.ceil(box[0] / step); (z = j * step) <= box[0] + box[2] && d.length < 100; j++) d.push("M" + z + "," + box[1] + "V" + (box[1] + box[3]));
    for (j = Math.ceil(box[1] / step); (z = j * step) <= box[1] + box[3] && d.length < 200; j++) d.push("M" + box[0] + "," + z + "H" + (box[0] + box[2]));
    this.grid.setAttribute("d", d.join(""));
  };

  Lab.prototype.rebuild = function (keep) {  // new handles: after a preset, an added or removed vertex, drawing, undo
    var self = this, n = this.vertices.length, focused = this.dots.contains(document.activeElement);
    if (this.kappa && this.kappa.length !== n) this.kappa = null;  // no longer the smooth curve's sample
    this.selected = Math.min(this.selected, Math.max(n - 1, 0));
    if (keep && this.circles && this.circles.length === n) {  // the same handles, sized for the new view
      this.radius = this.size * Math.max(0.006, Math.min(0.015, 0.5 / n));
      this.circles.forEach(function (c) { c.setAttribute("r", self.radius); });
      this.labels.forEach(function (t) { t.setAttribute("font-size", self.size * 0.038); });
      this.mark.setAttribute("r", 2 * this.radius);
      this.hoverMark.setAttribute("r", 2.4 * this.radius);
      this.update();
      return;
    }
    this.dots.textContent = "";
    this.numbers.textContent = "";
    this.radius = this.size * Math.max(0.006, Math.min(0.015, 0.5 / n));
    this.circles = this.vertices.map(function (v, i) {
      var c = element("circle", {r: this.radius, tabindex: i === self.selected ? 0 : -1, role: "button", class: "ddg-handle"}, self.dots);
      c.index = i;
      return c;
    }, this);
    this.labels = n <= LABELS_UP_TO ? this.vertices.map(function (v, i) {
      var t = element("text", {"font-size": this.size * 0.038, "dominant-baseline": "central"}, self.numbers);
      t.textContent = i;
      return t;
    }, this) : [];
    this.mark.setAttribute("r", 2 * this.radius);
    this.hoverMark.setAttribute("r", 2.4 * this.radius);
    this.rows.textContent = "";
    this.cells = null;
    if (focused && n) this.circles[this.selected].focus();  // the keys keep working after Undo
    this.update();
  };

  Lab.prototype.select = function (i, quiet, focus) {  // focus: the keys move it next (a click on it, Page Up/Down)
    if (this.circles[this.selected]) this.circles[this.selected].setAttribute("tabindex", -1);
    this.selected = i;
    this.circles[i].setAttribute("tabindex", 0);
    if (focus) this.circles[i].focus({preventScroll: !!quiet});
  };
  Lab.prototype.hover = function (i) {  // a vertex and its row, found from either
    var v = this.vertices[i], old = this.hovered;
    this.hovered = v ? i : undefined;
    this.hoverMark.setAttribute("visibility", v ? "visible" : "hidden");
    if (v) { this.hoverMark.setAttribute("cx", v[0]); this.hoverMark.setAttribute("cy", -v[1]); }
    if (this.cells && this.cells[old]) this.cells[old].row.classList.remove("ddg-lab-row-hover");
    if (this.cells && v && this.cells[i]) this.cells[i].row.classList.add("ddg-lab-row-hover");
  };
  Lab.prototype.add = function (i) {  // a vertex in the middle of the edge from v_i to v_{i+1}
    var v = this.vertices, n = v.length;
    if (n < 2) { this.tell("Place two vertices first: a new vertex goes in the middle of an edge."); return; }
    this.remember();
    var p = v[i], q = v[(i + 1) % n];
    v.splice(i + 1, 0, [(p[0] + q[0]) / 2, (p[1] + q[1]) / 2]);
    this.selected = i + 1;
    this.rebuild();  // the focus stays where it was (on the vertex after Insert, on the button after a press)
  };
  Lab.prototype.remove = function (i) {
    if (this.vertices.length <= 3) { this.tell("A closed polygon needs at least 3 vertices: vertex " + i + " stays. " + (this.drawing ? "Place more, or press Undo." : "Add one first, or press Draw for a new polygon.")); return; }
    this.remember();
    this.vertices.splice(i, 1);
    this.selected = i % this.vertices.length;
    this.rebuild();
  };
  Lab.prototype.drawingMode = function (on) {  // the button, the cursor and the dashed polygon from before
    this.drawing = on;
    this.draw.setAttribute("aria-pressed", String(on));
    this.draw.textContent = on ? "Done" : "Draw";
    this.svg.classList.toggle("ddg-drawing", on);
    if (!on) this.ghost.setAttribute("d", "");
  };
  Lab.prototype.toggleDrawing = function () {
    if (this.drawing && this.vertices.length < 3) {
      this.tell("A polygon needs at least 3 vertices, and " + this.vertices.length + (this.vertices.length === 1 ? " is" : " are") + " placed: place " + (3 - this.vertices.length) + " more, or press Undo to go back.");
      return;
    }
    if (!this.drawing) {
      this.ghost.setAttribute("d", pathOf(this.vertices, true));  // the polygon before, dashed, for scale
      this.remember();  // before drawing: Undo back to it ends drawing
      this.drawingMode(true);
      this.vertices = [];
      this.rebuild();
      this.tell("Click or tap in the plane to place the vertices, clockwise; press Done to finish.");
    } else {
      this.drawingMode(false);
      this.tell("");
      this.fit();
    }
  };
  Lab.prototype.fullScreen = function (on) {
    this.root.classList.toggle("ddg-lab-full", on);
    document.documentElement.classList.toggle("ddg-lab-full-page", on);
    this.full.setAttribute("aria-pressed", String(on));
    this.full.textContent = on ? "Leave full screen" : "Full screen";
    if (!on) this.root.scrollIntoView({block: "start"});
  };
  Lab.prototype.nudge = function (how) {  // the pad: to the previous or next vertex, or the selected one moved
    var n = this.vertices.length, i = this.selected, v = this.vertices[i];
    if (!v) { this.tell("No vertex yet: click or tap in the plane to place one."); return; }
    if (typeof how === "number") { this.select((i + how + n) % n, true); this.update(); return; }
    this.remember();
    this.move(i, [v[0] + how[0], v[1] + how[1]]);
  };
  Lab.prototype.move = function (i, p) {
    this.vertices[i] = p;
    this.update(i);
  };

  Lab.prototype.asNumpy = function () {  // every coordinate as JavaScript writes it: the shortest that reads back exactly
    return "np.array([" + this.vertices.map(function (p) { return "[" + String(p[0]) + ", " + String(p[1]) + "]"; }).join(", ") + "])";
  };
  Lab.prototype.address = function () {
    var q = [];
    if (this.shape.value === "edited") q.push("v=" + this.vertices.map(function (p) { return encodeURIComponent(p[0]) + "," + encodeURIComponent(p[1]); }).join(","));
    else {
      var name = Object.keys(SHORT_NAMES).filter(function (k) { return SHORT_NAMES[k] === this.shape.value; }, this)[0];
      q.push("lab=" + name);
      if (!this.n.disabled) q.push("n=" + this.n.value);
    }
    q.push("kind=" + this.kind.value);
    if (this.arrows.checked) q.push("arrows=1");
    if (this.method.value) q.push("inflate=" + this.method.value, "eps=" + this.eps.value);
    return window.location.origin + window.location.pathname + "?" + q.join("&") + "#lab";
  };
  Lab.prototype.copy = function (text, what) {
    var self = this, box = this.copied;
    box.hidden = false;
    box.value = text;
    var fallback = function () { box.focus(); box.select(); self.tell("Your browser did not let the page copy: the text is selected below; copy it (Ctrl+C, or a long press on a phone)."); };
    if (!navigator.clipboard) { fallback(); return; }
    navigator.clipboard.writeText(text).then(function () { self.tell("Copied " + what + "."); }, fallback);
  };

  Lab.prototype.key = function (event) {
    var i = event.target.index, n = this.vertices.length, step = (event.shiftKey ? 0.1 : 0.01);
    var moves = {ArrowLeft: [-step, 0], ArrowRight: [step, 0], ArrowUp: [0, step], ArrowDown: [0, -step]};
    var to = {PageUp: i - 1, PageDown: i + 1, Home: 0, End: n - 1}[event.key];
    if (i === undefined || event.ctrlKey || event.metaKey || event.altKey) return;  // Ctrl and +/-: the browser's zoom
    if (event.key === "Insert" || event.key === "+") { event.preventDefault(); this.add(i); return; }
    if (event.key === "Delete" || event.key === "-" || event.key === "Backspace") { event.preventDefault(); this.remove(i); return; }
    if (!(event.key in moves || to !== undefined)) return;
    event.preventDefault();
    if (to !== undefined) { this.select((to + n) % n, false, true); this.update(); return; }
    var v = this.vertices[i];
    this.remember();
    this.move(i, [v[0] + moves[event.key][0], v[1] + moves[event.key][1]]);
  };

  /* The sizes below which a value is rounding noise for this polygon: a turn (radians), a curvature
   * and |grad L|, an area. Coordinates carry a relative error of 2^-52; a turn between edges of
   * length h at coordinates of size c inherits about 2^-52 c / h; we allow 1024 times that. */
  function noise(curve) {
    var c = 0, h = Infinity, A = Infinity, v = curve.vertices, l = curve.edge_lengths, d = curve.dual_lengths;
    for (var i = 0; i < v.length; i++) {  // a plain loop: this runs at every frame of a drag
      c = Math.max(c, Math.abs(v[i][0]), Math.abs(v[i][1]));
      if (l[i] < h) h = l[i];
      if (d[i] < A) A = d[i];
    }
    var turn = ROUNDING * Math.max(c / h, 1);
    return {turn: turn, k: turn / A, area: ROUNDING * Math.max(c, curve.length) * curve.length, place: ROUNDING * c};
  }

  /* Draw the polygon and say what ddg's formulas give. After vertex `moved` moved, only it and its
   * neighbours have a new place or curvature; the colours may all change (they are scaled by the
   * largest |k|), so each attribute is written only where it changed. */
  Lab.prototype.update = function (moved) {
    var v = this.vertices, n = v.length, kind = this.kind.value, lab = window.ddgLab, curve = null, k = null, parts = [], s = this.summary;
    var ks = this.ks = {}, gradient = null, tol = null;  // each curvature and the gradient of length, once for everything
    // shown (lab.ks: the tests read the circle curvature there)
    if (this.flows.runs && this.flows.version !== this.version) this.flows.clear("The polygon changed after these flows ran: press Flow this shape or Play to run them from it.");
    this.path.setAttribute("d", pathOf(v, !this.drawing));
    if (Number(this.n.value) !== n && document.activeElement !== this.n) this.n.value = n;  // the polygon's own n
    ["turningNumber", "length", "signedArea"].forEach(function (name) { delete s.dataset[name]; });
    try { curve = new lab.DiscreteCurve(v); } catch (e) { parts.push(this.drawing ? "Drawing: " + n + (n === 1 ? " vertex" : " vertices") + " placed." : "Not a polygon the lecture allows: " + e.message + "."); }
    if (curve) {
      tol = this.tolerance = noise(curve);
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
      parts.push("length " + short(curve.length) + ", signed area " + shown(curve.signed_area, tol.area) + ".");
    }
    var top = k ? Math.max.apply(null, k.map(Math.abs)) : 0;
    top = k && top > tol.k ? top : 1;
    if (this.dragging === undefined) this.dragTop = 0;  // a drag keeps its first colour scale: were it to follow the
    else top = this.dragTop = this.dragTop || top;      // dragged vertex's |k|, every vertex would be restyled each frame
    var near = function (i) { return moved === undefined || (i - moved + n + 1) % n <= 2; };  // moved or a neighbour
    var N = curve && this.labels.length ? curve.bisector_normals : null, off = 0.06 * this.size;
    this.circles.forEach(function (c, i) {
      var fill = k ? LEVELS[Math.round(64 * clamp(0.5 + (Math.abs(k[i]) <= tol.k ? 0 : k[i]) / (2 * top), 0, 1))] : RAMP[1];
      if (c.fill !== fill) c.setAttribute("fill", c.fill = fill);
      if (!near(i)) return;
      c.setAttribute("cx", v[i][0]);
      c.setAttribute("cy", -v[i][1]);
      c.setAttribute("aria-label", "vertex " + i + " at (" + short(v[i][0]) + ", " + short(v[i][1]) + ")" +
                     (k ? ", " + kind + " curvature " + shown(k[i], tol.k) : ""));
      var label = this.labels[i];
      if (label) {  // outside the polygon, along the normal at the vertex (up and right while drawing)
        var d = N && isFinite(N[i][0]) ? N[i] : [0.7, 0.7];
        label.setAttribute("x", v[i][0] + off * d[0]);
        label.setAttribute("y", -(v[i][1] + off * d[1]));
      }
    }, this);
    var sel = v[this.selected];
    this.mark.setAttribute("visibility", sel ? "visible" : "hidden");
    if (sel) { this.mark.setAttribute("cx", sel[0]); this.mark.setAttribute("cy", -sel[1]); }
    if (this.hovered !== undefined) this.hover(this.hovered < n ? this.hovered : undefined);
    s.textContent = parts.join(" ");
    this.arrowPath.setAttribute("d", gradient && this.arrows.checked ? this.arrowsPath(gradient) : "");
    this.inflate(this.drawing ? null : curve, ks[kind]);
    this.describe(curve, ks, gradient);
    this.tabulate(curve, ks, moved);
  };

  /* The table of every vertex (while it is open): after a drag, only the moved vertex's rows. */
  Lab.prototype.tabulate = function (curve, ks, moved) {
    if (!this.tableBox.open) return;
    var n = this.vertices.length, self = this, tol = this.tolerance;
    if (!this.cells || this.cells.length !== n) {
      this.rows.textContent = "";
      this.cells = this.vertices.map(function (_, i) {
        var row = element("tr", {}, self.rows), cells = [];
        row.index = i;
        for (var j = 0; j < 3 + KINDS.length; j++) cells.push(element(j ? "td" : "th", j ? {} : {scope: "row"}, row));
        cells[0].textContent = i;
        return {row: row, cells: cells};
      });
      moved = undefined;
    }
    this.cells.forEach(function (entry, i) {
      entry.row.classList.toggle("ddg-lab-row-selected", i === self.selected);
      if (moved !== undefined && (i - moved + n + 1) % n > 2) return;
      var c = entry.cells;
      if (!curve) { for (var j = 1; j < c.length; j++) c[j].textContent = "–"; return; }
      var psi = curve.turning_angles[i];
      c[1].textContent = curve.reversals.indexOf(i) >= 0 ? "±180" : shown(psi * 180 / Math.PI, tol.turn * 180 / Math.PI);
      c[2].textContent = short(curve.dual_lengths[i]);
      KINDS.forEach(function (name, j) { c[3 + j].textContent = Array.isArray(ks[name]) ? shown(ks[name][i], tol.k) : "undefined"; });
    });
    var row = this.cells[this.selected];  // the selected vertex's row in view, inside the table's own scroll box
    if (row && moved === undefined) {
      var box = this.tableScroll, top = row.row.offsetTop, head = this.table.tHead.offsetHeight;
      if (top - head < box.scrollTop || top + row.row.offsetHeight > box.scrollTop + box.clientHeight) box.scrollTop = top - head - box.clientHeight / 3;
    }
  };

  /* The offset polygon's vertices, v_i + eps (N_{i-1/2} + tan(psi_i/2) T_{i-1/2}): where its moved
   * edges meet (ddg's DiscreteCurve.inflate(eps, "offset"), here for eps of either sign). */
  function offsetPolygon(curve, eps) {
    var N = curve.normals, T = curve.tangents, n = curve.vertices.length;
    if (curve.reversals.length) throw new Error("no offset corner at vertex " + curve.reversals[0] + ": the curve turns straight back there");
    return curve.vertices.map(function (p, i) {
      var a = N[(i + n - 1) % n], t = T[(i + n - 1) % n], s = curve.tan_half_psi[i];
      return [p[0] + eps * (a[0] + s * t[0]), p[1] + eps * (a[1] + s * t[1])];
    });
  }
  /* The reach of the offsets on each side: moved by eps, the edge from v_i keeps the length
   * |e_{i+1/2}| + eps (tan(psi_i/2) + tan(psi_{i+1}/2)); the first edge to shrink to a point, inward
   * (eps < 0) and outward (eps > 0): {inward: [r, i], outward: [r, i]}. */
  function reach(curve) {
    var t = curve.tan_half_psi, n = t.length, out = {inward: [Infinity, -1], outward: [Infinity, -1]}, r = [];
    curve.edge_lengths.forEach(function (l, i) {
      var s = t[i] + t[(i + 1) % n], side = s > 0 ? "inward" : "outward";
      r[i] = s > 0 ? l / s : Infinity;
      if (s !== 0 && l / Math.abs(s) < out[side][0]) out[side] = [l / Math.abs(s), i];
    });
    out.inwardAll = r.map(function (x, i) { return x <= out.inward[0] * (1 + 1e-9) ? i : -1; }).filter(function (i) { return i >= 0; });  // all at once (a symmetric star)
    return out;
  }

  /* The polygon inflated by eps: its pieces and the formula's area at once; the region, their union,
   * measured when the hand stops (a drag asks for it again at every frame). For eps < 0, the offset
   * polygon moved inward, its signed area, and its reach. */
  Lab.prototype.inflate = function (curve, k) {
    var method = this.method.value, eps = Number(this.eps.value), p = this.inflation, self = this, formula;
    if (Number(this.epsTyped.value) !== eps && document.activeElement !== this.epsTyped) this.epsTyped.value = eps;  // written only when it changed: a drag
    if (this.eps.disabled !== !method) this.eps.disabled = this.epsTyped.disabled = !method;  // updates at every frame
    clearTimeout(this.measuring);
    this.region.setAttribute("d", "");
    this.pieces.setAttribute("d", "");
    if (this.offset.getAttribute("d")) this.offset.setAttribute("d", "");
    delete p.dataset.formula; delete p.dataset.measured; delete p.dataset.offsetArea; delete p.dataset.reach;
    p.textContent = "";
    if (!method || !curve) return;
    var name = INFLATIONS[method][0], color = INFLATIONS[method][1], tol = this.tolerance;
    try {  // the formulas are for a simple clockwise polygon (crossings looked for where the region is measured: O(n^2))
      var turns = curve.turning_number, cross = curve.vertices.length <= MEASURED_UP_TO && crossing(curve.vertices);
      if (turns === -1) throw new Error("the polygon runs counter-clockwise, so its normals point inward and inflating it would erode it; reverse it (draw it clockwise)");
      if (turns !== 1) throw new Error("the formulas are for a simple clockwise polygon, and this one has turning number " + turns);
      if (cross) throw new Error("the formulas are for a simple polygon, and the edges from vertex " + cross[0] + " and from vertex " + cross[1] + " meet");
      if (eps < 0 && method !== "offset") throw new Error("ε < 0 moves the edges inward, and the " + name + " only grows the region; for ε < 0 choose the offset with kites, whose edges move either way");
      if (method === "bisector" && !Array.isArray(k)) throw new Error("no " + this.kind.value + " curvature here");
      formula = method !== "bisector" ? (eps < 0 ? curve.signed_area + eps * curve.length + eps * eps * curve.tan_half_psi.reduce(function (a, b) { return a + b; }, 0) : curve.inflated_area(eps, method)) :
        curve.signed_area + eps * curve.length + eps * eps / 2 * k.reduce(function (total, x, i) { return total + curve.dual_lengths[i] * x; }, 0);  // <k, 1> = sum A_i k_i
    } catch (e) { p.textContent = "No inflation: " + e.message + "."; return; }
    p.dataset.formula = formula;
    var reaches = method === "offset" ? reach(curve) : null;
    if (eps < 0) {  // the offset moved inward: its polygon, its signed area (the formula's, for every eps), its reach
      var moved = offsetPolygon(curve, eps), area = -window.ddgLab.signed_area_ccw(moved), r = reaches.inward;
      var first = reaches.inwardAll, reflex = curve.turning_angles.some(function (psi) { return psi < 0; });
      var which = first.length > 1 ? "the edges from vertices " + first.slice(0, 4).join(", ") + (first.length > 4 ? " and " + (first.length - 4) + " more" : "") + " shrink to points"
                                   : "the edge from vertex " + r[1] + " shrinks to a point";
      p.dataset.offsetArea = area;
      p.dataset.reach = r[0];
      this.offset.setAttribute("stroke", color);
      this.offset.setAttribute("d", pathOf(moved, true));
      p.textContent = "Moved inward by ε = " + eps.toFixed(2) + " (dashed): the edges move along −N, and the formula A₀ + εL + ε² Σ tan(ψᵢ/2) gives " +
        short(formula) + ", the signed area of the dashed polygon (" + short(area) + "). " +
        (r[1] < 0 ? "No edge shrinks when this polygon moves inward." :
         "The reach inward is " + short(r[0]) + ": at ε = −" + short(r[0]) + " " + which +
         (-eps > r[0] ? "; ε is past it, so those edges run backwards and the dashed polygon folds over itself: the formula is still its signed area, which is no longer the area of any region." :
          reflex ? "; until then the dashed polygon lies inside the set of points at least |ε| inside, but is smaller: at a corner that turns counter-clockwise (ψᵢ < 0) that set is rounded by an arc about vᵢ, where the moved edges meet in a sharp corner." :
          "; until then, the polygon being convex, the dashed polygon is the set of points at least |ε| inside."));
      return;
    }
    var parts = eps > 0 ? pieces(curve, eps, method, k) : {rectangles: [], corners: []}, said = "Inflated by ε = " + eps.toFixed(2) + ", " + name + ": the formula " +
      INFLATIONS[method][2] + (method === "bisector" ? " (k: " + this.kind.value + ")" : "") + " gives " + short(formula);
    if (method === "offset" && eps > reaches.outward[0]) said += " (past the outward reach " + short(reaches.outward[0]) + ", where the edge from vertex " + reaches.outward[1] + " shrinks to a point)";
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
      var difference = formula - area;
      p.textContent = said + "; the region (shaded), the polygon with these pieces united, measures " + short(area) +
        ": formula − region = " + (Math.abs(difference) <= tol.area + ROUNDING * Math.abs(area) ? "0" : Number(difference.toPrecision(2))) + ".";
    }, this.dragging !== undefined || performance.now() - (this.sliding || -1e9) < 300 ? 150 : 0);  // measured when the hand rests
  };

  Lab.prototype.arrowsPath = function (g) {  // grad L at each vertex, the longest a fifth of the polygon's extent
    var v = this.vertices, top = Math.max.apply(null, g.map(function (x) { return Math.hypot(x[0], x[1]); })) || 1;
    var scale = this.arrowScale / top, head = 0.02 * this.size;
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
    var i = this.selected, words = [], kind = this.kind.value, k = Array.isArray(ks[kind]) ? ks[kind] : null, smooth = this.kappa, tol = this.tolerance;
    if (curve) {
      var psi = curve.turning_angles[i], g = gradient[i], straight = Math.abs(psi) <= tol.turn, back = curve.reversals.indexOf(i) >= 0;
      var v = this.vertices[i];
      words.push("Vertex " + i + " at (" + shown(v[0], tol.place) + ", " + shown(v[1], tol.place) + "): ψ = " +
                 (back ? "±180° (its edges point in exactly opposite directions, so a turn of +180° and one of −180° are equally right)" :
                  shown(psi * 180 / Math.PI, tol.turn * 180 / Math.PI) + "° (" + (straight ? "straight, to rounding" : psi > 0 ? "turning clockwise" : "turning counter-clockwise") + ")") +
                 "; k: " + KINDS.map(function (name) {
                   return name + " " + (Array.isArray(ks[name]) ? shown(ks[name][i], tol.k) : "undefined");
                 }).join(", ") + "; |\u2060∇L\u2060| = " + shown(Math.hypot(g[0], g[1]), tol.k) + ".");
    }
    this.detail.textContent = words.join(" ");
    var series = [], values = [];
    if (k) { series.push({color: "currentColor", points: k.map(function (x, j) { return [j, x]; })}); values = values.concat(k); }
    if (smooth) {  // the smooth curve's: the same while the polygon is dragged (`same`: drawn again only on new axes)
      if (smooth !== this.kappaPoints) this.kappaPoints = smooth, this.kappaSeries = smooth.map(function (x, j) { return [j, x]; }), this.kappaId = (this.kappaId || 0) + 1;
      series.push({color: RAMP[2], dashed: true, points: this.kappaSeries, same: "kappa" + this.kappaId + "|"});
      values = values.concat(smooth);
    }
    var lo = Math.min(0, Math.min.apply(null, values)), hi = Math.max(0, Math.max.apply(null, values));
    this.chart.draw(series, 0, Math.max(this.vertices.length - 1, 1), lo, hi, k ? [{x: i, color: "currentColor"}] : [],
                    "the " + kind + " curvature at each vertex" + (smooth ? ", and the smooth curve's" : ""), [!!k, !!smooth]);
    this.caption.textContent = k ? "Above: the " + kind + " curvature k_i (solid) at vertex 0 to " + (k.length - 1) +
      (smooth ? ", and the smooth curve's curvature κ(t_i) where it was sampled (dashed)" : "") +
      "; from " + short(lo) + " to " + short(hi) + "; the upright line marks the selected vertex." : "";
  };

  /* The three flows side by side, from the lab's polygon: ddg.flow.flow's explicit steps (ddgLab.flow_step),
   * the one furthest behind in time first, so all three reach the same moments. Computing runs ahead
   * while playing; a player shows the recorded run at time `time`, at a chosen speed, or where the
   * time slider puts it. */
  var FRAMES = 240;  // snapshots kept per flow: one each t/FRAMES of time (flows.step)
  function Flows(lab, root) {
    var self = this, controls = element("div", {class: "ddg-controls"}, root), player = element("div", {class: "ddg-controls"}, root);
    this.lab = lab;
    this.start = button(controls, "Flow this shape", "run the three flows from the polygon above");
    this.play = button(controls, "Play", "play or pause the flows (a long run stops computing while paused)");
    this.play.setAttribute("aria-pressed", "false");
    this.play.style.minWidth = "4.6em";  // Play and Pause the same width: Step stays where it is
    this.stepButton = button(controls, "Step", "to the next snapshot of the flows, or one step of the flow furthest behind");
    this.speed = control(controls, "speed", element("select", {}, null));
    Object.keys(SPEEDS).forEach(function (s) { element("option", {value: SPEEDS[s]}, self.speed).textContent = s; });
    this.speed.value = 10;
    this.slider = control(player, "time t", element("input", {type: "range", min: 0, max: 1000, step: 1, value: 0, disabled: ""}, null));
    this.slider.parentNode.classList.add("ddg-lab-time");
    this.shownTime = element("output", {}, this.slider.parentNode);
    this.panels = element("div", {class: "ddg-lab-panels"}, root);
    this.chart = new Chart(root, "time t", "L/L(0), A/|A(0)|",
                           window.ddgLab.CURVATURES.map(function (k) { return [k, FLOW_COLORS[k], false]; }).concat([["length", "currentColor", false], ["area", "currentColor", true]]));
    this.caption = element("p", {class: "ddg-detail"}, root);
    this.chart.roundX = true;
    this.chart.svg.style.display = "none";  // until a flow starts
    this.status = element("p", {class: "ddg-summary ddg-lab-flow-status", "aria-live": "polite"}, root);
    this.start.addEventListener("click", function () { self.begin(); });
    this.play.addEventListener("click", function () { self.toggle(); });
    this.stepButton.addEventListener("click", function () {
      self.pause();
      if (!self.runs) self.begin();
      if (!self.runs) return;  // no flow from this polygon: begin() said why
      self.next();
      self.draw();
    });
    this.slider.addEventListener("input", function () { self.pause(); self.time = Number(self.slider.value) / 1000 * self.tmax(); self.draw(true); });
  }
  Flows.prototype.clear = function (why) {  // the polygon changed: the runs no longer belong to it
    this.pause();
    this.runs = null;
    this.panels.textContent = "";
    this.chart.svg.style.display = "none";
    this.caption.textContent = "";
    this.slider.disabled = true;
    this.slider.value = 0;
    this.shownTime.textContent = "";
    this.status.textContent = why;
  };
  Flows.prototype.begin = function () {
    var self = this, v = this.lab.vertices.map(function (p) { return p.slice(); }), curve;
    this.pause();
    try { curve = new window.ddgLab.DiscreteCurve(v); } catch (e) { this.status.textContent = "No flow: " + e.message + "."; return; }
    this.version = this.lab.version;
    this.panels.textContent = "";
    this.chart.svg.style.display = "";
    this.slider.disabled = false;
    this.time = 0;
    this.area0 = curve.signed_area;
    this.length0 = curve.length;
    this.areaUnit = Math.abs(this.area0) > 1e-9 * this.length0 * this.length0 ? Math.abs(this.area0) : this.length0 * this.length0 / (4 * Math.PI);
    this.chart.labels[1] = "L/L(0), A/" + (this.areaUnit === Math.abs(this.area0) ? "|A(0)|" : "(L(0)²/4π)");
    this.chart.key = null;  // the axes drawn again, with that name
    this.runs = window.ddgLab.CURVATURES.map(function (kind) {
      var figure = element("figure", {class: "ddg-lab-flow"}, self.panels), svg = element("svg", {class: "ddg-panel", width: 170, height: 170, "aria-hidden": "true"}, figure);
      frame(svg, v);
      element("path", {d: pathOf(v, true), fill: "none", stroke: "currentColor", "stroke-opacity": 0.3, "vector-effect": "non-scaling-stroke"}, svg);
      return {kind: kind, vertices: v, t: 0, stopped: null, record: [[0, 1, curve.signed_area / self.areaUnit]], frames: [[0, v]],
              path: element("path", {fill: "none", stroke: FLOW_COLORS[kind], "stroke-width": 2, "vector-effect": "non-scaling-stroke"}, svg),
              label: element("figcaption", {}, figure)};
    });
    this.draw();
  };
  Flows.prototype.step = function () {  // one explicit step of the running flow with the smallest t; false when all stopped
    var open = (this.runs || []).filter(function (r) { return !r.stopped; });
    if (!open.length) return false;
    var run = open.reduce(function (a, b) { return b.t < a.t ? b : a; });
    try {
      var next = window.ddgLab.flow_step(run.vertices, run.kind, this.length0), c = new window.ddgLab.DiscreteCurve(next.vertices);
      run.vertices = next.vertices;
      run.t += next.dt;
      run.record.push([run.t, c.length / this.length0, c.signed_area / this.areaUnit]);
      // a snapshot when the time has moved on by t/FRAMES since the last one (steps are long early and
      // short late): every moment is within t/FRAMES of one; past 2 FRAMES, spaced again by t/FRAMES
      if (run.t - run.frames[run.frames.length - 1][0] >= run.t / FRAMES) run.frames.push([run.t, next.vertices]);
      if (run.frames.length > 2 * FRAMES) {
        var gap = run.t / FRAMES, last = -Infinity;
        run.frames = run.frames.filter(function (f) { if (f[0] - last < gap) return false; last = f[0]; return true; });
      }
    } catch (e) {
      run.stopped = e.message.replace(/^stopped at t = [^:]*: /, "");
    }
    return true;
  };
  Flows.prototype.tmax = function () { return Math.max.apply(null, (this.runs || []).map(function (r) { return r.t; })); };
  Flows.prototype.next = function () {  // Step: the next snapshot after the time shown, or one step more
    var after = [];
    this.runs.forEach(function (r) { r.frames.concat([[r.t]]).forEach(function (f) { if (f[0] > this.time) after.push(f[0]); }, this); }, this);
    if (after.length) { this.time = Math.min.apply(null, after); return; }
    var open = this.runs.filter(function (r) { return !r.stopped; });
    if (!open.length) { this.note = "All three have stopped: nothing to step."; return; }
    var run = open.reduce(function (a, b) { return b.t < a.t ? b : a; });
    this.step();
    this.time = Math.max(this.time, run.t);
  };
  Flows.prototype.toggle = function () {
    if (this.timer) { this.pause(); return; }
    if (!this.runs) this.begin();
    if (!this.runs) return;
    var self = this, last = performance.now();
    if (this.runs.every(function (r) { return r.stopped; }) && this.time >= this.tmax()) this.time = 0;  // again from the start
    this.play.textContent = "Pause";
    this.play.setAttribute("aria-pressed", "true");
    var tick = function (now) {  // compute for up to 8 ms of each frame, then move the time shown on
      var until = performance.now() + 8, going = true;
      while (going && performance.now() < until) going = self.step();
      var open = self.runs.filter(function (r) { return !r.stopped; }), frontier = open.length ? Math.min.apply(null, open.map(function (r) { return r.t; })) : Infinity;
      var end = self.tmax(), rate = end / Number(self.speed.value);
      self.time = Math.min(self.time + rate * (now - last) / 1000, frontier, end);
      last = now;
      self.draw();
      if (!going && self.time >= end) { self.pause(); return; }
      self.timer = requestAnimationFrame(tick);
    };
    this.timer = requestAnimationFrame(tick);
  };
  Flows.prototype.pause = function () {
    if (this.timer) cancelAnimationFrame(this.timer);
    this.timer = 0;
    this.play.textContent = "Play";
    this.play.setAttribute("aria-pressed", "false");
  };
  var RULES = [[/nearly vanished/, "length < 5%"], [/edge fell below/, "edge < 2% of mean"], [/turning number changed/, "turning number changed"],
               [/step fell below/, "step too small"], [/turns straight back/, "ψ = π"], [/degenerate/, "degenerate"]];
  function rule(text) { var r = RULES.filter(function (x) { return x[0].test(text); })[0]; return r ? r[1] : "stopped"; }
  Flows.prototype.draw = function (scrubbed) {
    var series = [], tmax = this.tmax(), lo = 0, hi = 1, time = Math.min(this.time, tmax), marks = [];
    this.runs.forEach(function (r, j) {
      var f = r.frames.concat([[r.t, r.vertices]]), a = 0, b = f.length - 1;  // the snapshots and where it is now
      while (a < b) { var m = (a + b + 1) >> 1; if (f[m][0] <= time) a = m; else b = m - 1; }  // the last one by `time`
      r.path.setAttribute("d", pathOf(f[a][1], true));
      r.shown = f[a][0];
      var done = r.stopped && a === f.length - 1;
      r.label.textContent = r.kind + " flow, t = " + short(f[a][0]) + (done ? ": stopped (" + rule(r.stopped) + ")" : "");
      r.record.forEach(function (p) { lo = Math.min(lo, p[2]); hi = Math.max(hi, p[2]); });
      var every = Math.ceil(r.record.length / 600), last = r.record.length - 1;  // at most 600 points a line
      var plotted = every > 1 ? r.record.filter(function (p, j) { return j % every === 0 || j === last; }) : r.record;
      series.push({color: FLOW_COLORS[r.kind], points: plotted.map(function (p) { return [p[0], p[1]]; })},
                  {color: FLOW_COLORS[r.kind], dashed: true, points: plotted.map(function (p) { return [p[0], p[2]]; })});
      if (r.stopped) marks.push({x: r.t, color: FLOW_COLORS[r.kind], label: rule(r.stopped), row: j});
    });
    marks.push({x: time, color: "currentColor"});
    this.chart.draw(series, 0, tmax || 1, lo, hi, marks, "length and area of the three flows against time");
    if (!scrubbed) this.slider.value = tmax ? Math.round(1000 * time / tmax) : 0;
    this.shownTime.textContent = short(time);
    this.caption.textContent = "Above: the length L/L(0) (solid) and the signed area A/" + (this.areaUnit === Math.abs(this.area0) ? "|A(0)|" : "(L(0)²/4π)") +
      " (dashed) of each flow against time t, from 0 to " + short(tmax) + "; angle blue, sine orange, tangent green; a dotted line where a flow stopped, named by the rule that stopped it; the solid upright line is the time shown.";
    var note = this.note || "";
    this.note = "";
    this.status.textContent = (note ? note + " " : "") + this.runs.map(function (r) {
      return r.kind + " flow: " + (r.stopped ? "stopped at t = " + short(r.t) + ": " + r.stopped : "computed to t = " + short(r.t) + " (" + (r.record.length - 1) + " steps), length " + short(r.record[r.record.length - 1][1] * this.length0)) + ".";
    }, this).join(" ");
  };

  function start() {
    document.documentElement.classList.add("ddg-lab-page");  // the theme's Back to top stays hidden (ddg-book.css)
    var query = new URLSearchParams(window.location.search);
    document.querySelectorAll(".ddg-lab").forEach(function (root) {
      if (root.lab) return;
      root.lab = new Lab(root);
      // a link into the lab (?lab=..., ?v=...) lands on it, also where the link has no #lab
      if (!window.location.hash && (query.has("lab") || query.has("v"))) root.scrollIntoView({block: "start"});
    });
  }
  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start);
  else start();
})();
