/* The lab on the page (book/10_explorers): a polygon whose vertices the reader drags, or moves with
 * the arrow keys, coloured by a discrete curvature, with its turning number, length and signed area,
 * computed by ddg-lab.js (ddg's formulas) as it changes. Loaded only where there is a .ddg-lab
 * (tools/sphinx_assets.py). Data coordinates have y up; the SVG is drawn with y flipped.
 */
(function () {
  "use strict";
  var SVG = "http://www.w3.org/2000/svg", RAMP = ["#2563eb", "#9ca3af", "#dc2626"];  // ddg.scene.RAMP
  var SHAPES = {"regular n-gon": function () { return 1; },
                "non-convex blob": function (t) { return 1 + 0.3 * Math.cos(3 * t); }};  // ddg.explore.SHAPES

  function ramp(value) {  // ddg.scene.ramp on RAMP
    value = Math.min(Math.max(value, 0), 1);
    var i = value <= 0.5 ? 0 : 1, t = value * 2 - i;
    return "#" + [1, 3, 5].map(function (k) {
      var a = parseInt(RAMP[i].slice(k, k + 2), 16), b = parseInt(RAMP[i + 1].slice(k, k + 2), 16);
      return ("0" + Math.floor(a + t * (b - a) + 0.5).toString(16)).slice(-2);
    }).join("");
  }
  function short(x) { return String(Number(x.toPrecision(6))); }  // six significant digits, as the summary shows them
  function element(name, attributes, parent) {
    var e = document.createElementNS(name === "svg" || name === "path" || name === "circle" || name === "g" ? SVG : "http://www.w3.org/1999/xhtml", name);
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

  function Lab(root) {
    var self = this, controls = element("div", {class: "ddg-controls"}, root);
    root.querySelectorAll(".ddg-lab-static").forEach(function (e) { e.hidden = true; });
    this.shape = control(controls, "shape", element("select", {}, null));
    Object.keys(SHAPES).forEach(function (s) { element("option", {value: s}, self.shape).textContent = s; });
    this.n = control(controls, "n", element("input", {type: "number", min: 3, max: 2000, step: 1, value: root.dataset.n || 12}));
    this.kind = control(controls, "curvature", element("select", {}, null));
    window.ddgLab.CURVATURES.forEach(function (k) { element("option", {value: k}, self.kind).textContent = k; });
    var reset = element("button", {type: "button", class: "ddg-play"}, controls);
    reset.textContent = "Reset";
    this.svg = element("svg", {class: "ddg-panel ddg-lab-svg", viewBox: "-1.5 -1.5 3 3", width: 360, height: 360, role: "group",
                               "aria-label": "the polygon: each vertex is a button; arrow keys move it, Page Up and Page Down go to the previous and next vertex"}, root);
    this.path = element("path", {fill: "none", stroke: "currentColor", "stroke-width": 1.5, "vector-effect": "non-scaling-stroke"}, this.svg);
    this.dots = element("g", {}, this.svg);
    this.summary = element("p", {class: "ddg-summary", "aria-live": "polite"}, root);
    [this.shape, this.n].forEach(function (input) { input.addEventListener("change", function () { self.reset(); }); });
    reset.addEventListener("click", function () { self.reset(); });
    this.kind.addEventListener("change", function () { self.update(); });
    this.dots.addEventListener("keydown", function (event) { self.key(event); });
    this.dots.addEventListener("pointerdown", function (event) {
      if (event.target.index === undefined) return;
      self.dragging = event.target.index;
      event.target.setPointerCapture(event.pointerId);
      event.target.focus();
      event.preventDefault();
    });
    this.dots.addEventListener("pointermove", function (event) {
      if (self.dragging === undefined) return;
      var p = self.svg.createSVGPoint();
      p.x = event.clientX; p.y = event.clientY;
      p = p.matrixTransform(self.svg.getScreenCTM().inverse());
      self.vertices[self.dragging] = [p.x, -p.y];
      if (!self.frame) self.frame = requestAnimationFrame(function () { self.frame = 0; self.update(self.dragging); });
    });
    ["pointerup", "pointercancel"].forEach(function (name) {
      self.dots.addEventListener(name, function () {
        if (self.dragging !== undefined) self.update(self.dragging);  // the summary of where it was let go
        self.dragging = undefined;
      });
    });
    this.reset();
  }

  Lab.prototype.reset = function () {  // the preset: n vertices on the shape, clockwise, at t = 2 pi k / n
    var n = Math.min(Math.max(Math.round(Number(this.n.value)) || 12, 3), 2000), r = SHAPES[this.shape.value], self = this;
    this.n.value = n;
    this.vertices = [];
    for (var k = 0; k < n; k++) {
      var t = (2 * Math.PI / n) * k;
      this.vertices.push([r(t) * Math.cos(t), -r(t) * Math.sin(t)]);
    }
    this.dots.textContent = "";
    this.circles = this.vertices.map(function (v, i) {
      var c = element("circle", {r: Math.max(0.012, Math.min(0.045, 1.5 / n)), tabindex: i ? -1 : 0, role: "button", class: "ddg-handle"}, self.dots);
      c.index = i;
      return c;
    });
    this.update();
  };

  Lab.prototype.move = function (i, p) {
    this.vertices[i] = p;
    this.update(i);
  };

  Lab.prototype.key = function (event) {
    var i = event.target.index, n = this.vertices.length, step = event.shiftKey ? 0.1 : 0.01;
    var moves = {ArrowLeft: [-step, 0], ArrowRight: [step, 0], ArrowUp: [0, step], ArrowDown: [0, -step]};
    var to = {PageUp: i - 1, PageDown: i + 1, Home: 0, End: n - 1}[event.key];
    if (i === undefined || !(event.key in moves || to !== undefined)) return;
    event.preventDefault();
    if (to !== undefined) {
      to = (to + n) % n;
      this.circles[i].setAttribute("tabindex", -1);
      this.circles[to].setAttribute("tabindex", 0);
      this.circles[to].focus();
      return;
    }
    var v = this.vertices[i];
    this.move(i, [v[0] + moves[event.key][0], v[1] + moves[event.key][1]]);
  };

  /* Draw the polygon and say what ddg's formulas give. After vertex `moved` moved, only it and its
   * neighbours have a new place or curvature; the colours may all change (they are scaled by the
   * largest |k|), so each attribute is written only where it changed. */
  Lab.prototype.update = function (moved) {
    var v = this.vertices, n = v.length, kind = this.kind.value, lab = window.ddgLab, curve = null, k = null, parts = [], s = this.summary;
    this.path.setAttribute("d", "M" + v.map(function (p) { return p[0] + "," + -p[1]; }).join("L") + "Z");
    ["turningNumber", "length", "signedArea"].forEach(function (name) { delete s.dataset[name]; });
    try { curve = new lab.DiscreteCurve(v); } catch (e) { parts.push("Not a polygon the lecture allows: " + e.message + "."); }
    if (curve) {
      try { k = curve.curvature(kind); } catch (e) { parts.push("No " + kind + " curvature: " + e.message + "."); }
      try {
        s.dataset.turningNumber = curve.turning_number;
        parts.push("Turning number " + curve.turning_number + ",");
      } catch (e) { parts.push("No turning number (" + e.message + "),"); }
      s.dataset.length = curve.length;
      s.dataset.signedArea = curve.signed_area;
      parts.push("length " + short(curve.length) + ", signed area " + short(curve.signed_area) + ".");
    }
    var top = k ? Math.max.apply(null, k.map(Math.abs)) || 1 : 1;
    this.circles.forEach(function (c, i) {
      var fill = k ? ramp(0.5 + k[i] / (2 * top)) : RAMP[1];
      if (c.fill !== fill) c.setAttribute("fill", c.fill = fill);
      if (moved !== undefined && (i - moved + n + 1) % n > 2) return;  // not moved and not a neighbour
      c.setAttribute("cx", v[i][0]);
      c.setAttribute("cy", -v[i][1]);
      c.setAttribute("aria-label", "vertex " + i + " at (" + short(v[i][0]) + ", " + short(v[i][1]) + ")" +
                     (k ? ", " + kind + " curvature " + short(k[i]) : ""));
    });
    s.textContent = parts.join(" ");
  };

  function start() {
    document.querySelectorAll(".ddg-lab").forEach(function (root) { if (!root.lab) root.lab = new Lab(root); });
  }
  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start);
  else start();
})();
