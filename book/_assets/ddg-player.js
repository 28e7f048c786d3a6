/* The book's player for explorers and animations (ddg.explore): no kernel, no network.
 *
 * Each .ddg-explorer element carries (or names the script file that carries) every state a reader
 * can reach, computed by ddg when the book was built; it is loaded when the explorer comes near the
 * screen. This script builds standard controls (select, range, button), looks up the state that
 * the controls name, and draws it as SVG. It computes nothing of the lecture: it only looks values
 * up and draws them.
 */
(function () {
  "use strict";

  function hex(c) { return [1, 3, 5].map(function (k) { return parseInt(c.slice(k, k + 2), 16); }); }

  function ramp(stops, value) {  // the colour of value in [0, 1]: ddg.scene.ramp
    value = Math.min(Math.max(value, 0), 1);
    var i = value <= 0.5 ? 0 : 1, t = value * 2 - i, a = hex(stops[i]), b = hex(stops[i + 1]);
    return "#" + a.map(function (x, k) {
      return ("0" + Math.floor(x + t * (b[k] - x) + 0.5).toString(16)).slice(-2);
    }).join("");
  }

  function escape(s) {
    return String(s).replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;").replace(/"/g, "&quot;");
  }

  function Player(root, data) {
    this.root = root;
    this.data = data;
    this.values = {};
    var keys = this.data.value.split("|"), self = this;
    this.data.controls.forEach(function (c, i) {
      self.values[c.name] = c.options.map(String).indexOf(keys[i]);
    });
    this.build();
    this.draw();
  }

  Player.prototype.key = function () {
    var self = this;
    return this.data.controls.map(function (c) { return String(c.options[self.values[c.name]]); }).join("|");
  };

  Player.prototype.build = function () {
    var self = this, data = this.data, root = this.root;
    root.querySelector(".ddg-static").hidden = true;
    var controls = document.createElement("div");
    controls.className = "ddg-controls";
    this.inputs = {};
    data.controls.forEach(function (c) {
      var label = document.createElement("label"), span = document.createElement("span");
      span.textContent = c.label + " ";
      label.appendChild(span);
      var input;
      if (c.type === "select") {
        input = document.createElement("select");
        c.options.forEach(function (o, i) {
          var option = document.createElement("option");
          option.value = i;
          option.textContent = o;
          input.appendChild(option);
        });
      } else {
        input = document.createElement("input");
        input.type = "range";
        input.min = 0;
        input.max = c.options.length - 1;
        input.step = 1;
      }
      input.value = self.values[c.name];
      input.addEventListener("input", function () { self.set(c.name, Number(input.value)); });
      label.appendChild(input);
      if (c.type !== "select") {
        var output = document.createElement("output");
        label.appendChild(output);
        input.output = output;
      }
      if (c.type === "frames") {
        var button = document.createElement("button");
        button.type = "button";
        button.className = "ddg-play";
        button.textContent = "▶ Play";
        button.addEventListener("click", function () { self.toggle(c, button); });
        controls.appendChild(button);
      }
      controls.appendChild(label);
      self.inputs[c.name] = input;
    });
    root.appendChild(controls);
    var figure = document.createElement("figure");
    figure.className = "ddg-figure";
    this.panels = data.panels[0].map(function () {
      var svg = document.createElementNS("http://www.w3.org/2000/svg", "svg");
      svg.setAttribute("role", "group");
      svg.setAttribute("class", "ddg-panel");
      figure.appendChild(svg);
      return svg;
    });
    this.caption = document.createElement("figcaption");
    this.caption.className = "ddg-alt";
    figure.appendChild(this.caption);
    root.appendChild(figure);
    this.summary = document.createElement("p");
    this.summary.className = "ddg-summary";
    this.summary.setAttribute("aria-live", "polite");
    root.appendChild(this.summary);
    this.detail = document.createElement("p");
    this.detail.className = "ddg-detail";
    this.detail.setAttribute("aria-live", "polite");
    root.appendChild(this.detail);
    if (data.drag) { this.dragging(); }
  };

  Player.prototype.set = function (name, index) {
    var c = this.data.controls.filter(function (c) { return c.name === name; })[0];
    this.values[name] = Math.min(Math.max(index, 0), c.options.length - 1);
    this.inputs[name].value = this.values[name];
    this.draw();
  };

  Player.prototype.toggle = function (c, button) {
    var self = this;
    if (this.timer) {
      clearInterval(this.timer);
      this.timer = null;
      button.textContent = "▶ Play";
      return;
    }
    button.textContent = "❚❚ Pause";
    if (this.values[c.name] === c.options.length - 1) { this.set(c.name, 0); }
    this.timer = setInterval(function () {
      if (self.values[c.name] >= c.options.length - 1) { self.toggle(c, button); return; }
      self.set(c.name, self.values[c.name] + 1);
    }, c.interval || 250);
  };

  // point, path and render mirror ddg/scene.py (point, path, render), item keys as documented there.
  Player.prototype.point = function (panel, x, y) {  // data coordinates to the panel's pixels
    var b = panel.box, w = panel.px[0], h = panel.px[1];
    return [(x - b[0]) / (b[2] - b[0]) * w, h - (y - b[1]) / (b[3] - b[1]) * h];
  };

  Player.prototype.path = function (panel, points, closed) {
    var parts = [];
    for (var i = 0; i < points.length; i += 2) {
      var p = this.point(panel, points[i], points[i + 1]);
      parts.push(p[0].toFixed(1) + "," + p[1].toFixed(1));
    }
    return "M" + parts.join("L") + (closed ? "Z" : "");
  };

  Player.prototype.render = function (index, panel, items) {
    var data = this.data, out = [], self = this;
    items.forEach(function (item) {
      if (item.panel !== index) { return; }
      var d = item.points && item.points.pool !== undefined ? data.pool[item.points.pool] : item.points, i;
      var color = item.color;
      if (item.kind === "line") {
        out.push('<path d="' + self.path(panel, d, item.closed) + '" stroke="' + color + '" stroke-width="' +
                 item.width + '" fill="' + (item.fill || "none") + '"' +
                 (item.dash ? ' stroke-dasharray="' + item.dash + '"' : "") +
                 (item.opacity ? ' opacity="' + item.opacity + '"' : "") + "/>");
      } else if (item.kind === "dots") {
        for (i = 0; i < d.length; i += 2) {
          var p = self.point(panel, d[i], d[i + 1]), label = item.labels ? item.labels[i / 2] : null;
          var fill = item.values ? ramp(data.ramp, item.values[i / 2]) : color;
          out.push('<circle cx="' + p[0].toFixed(1) + '" cy="' + p[1].toFixed(1) + '" r="' + item.radius +
                   '" fill="' + fill + '"' + (label ? ' tabindex="0" role="img" aria-label="' + escape(label) +
                   '" data-label="' + escape(label) + '"' : "") + (item.handle ? ' class="ddg-handle"' : "") + ">" +
                   (label ? "<title>" + escape(label) + "</title>" : "") + "</circle>");
        }
      } else if (item.kind === "arrows") {
        for (i = 0; i < d.length; i += 4) {
          var a = self.point(panel, d[i], d[i + 1]), b = self.point(panel, d[i + 2], d[i + 3]);
          out.push('<line x1="' + a[0].toFixed(1) + '" y1="' + a[1].toFixed(1) + '" x2="' + b[0].toFixed(1) +
                   '" y2="' + b[1].toFixed(1) + '" stroke="' + color + '" stroke-width="' + item.width + '"/>' +
                   '<circle cx="' + b[0].toFixed(1) + '" cy="' + b[1].toFixed(1) + '" r="2.5" fill="' + color + '"/>');
        }
      } else if (item.kind === "bars") {
        item.x.forEach(function (x, j) {
          var h = item.heights[j], half = item.bar_width / 2;
          var a = self.point(panel, x - half, Math.max(h, 0)), b = self.point(panel, x + half, Math.min(h, 0));
          out.push('<rect x="' + a[0].toFixed(1) + '" y="' + a[1].toFixed(1) + '" width="' + (b[0] - a[0]).toFixed(1) +
                   '" height="' + (b[1] - a[1]).toFixed(1) + '" fill="' + item.colors[j] + '"/>');
        });
      } else if (item.kind === "text") {
        var at = item.pixels ? [item.x, item.y] : self.point(panel, item.x, item.y);
        out.push('<text x="' + at[0].toFixed(1) + '" y="' + at[1].toFixed(1) + '" text-anchor="' + item.anchor +
                 '" font-size="' + item.size + '" fill="' + color + '"' + (item.rotate ? ' transform="rotate(' +
                 item.rotate + " " + at[0].toFixed(1) + " " + at[1].toFixed(1) + ')"' : "") + ">" +
                 escape(item.text) + "</text>");
      }
    });
    return out.join("");
  };

  Player.prototype.draw = function () {
    var self = this, data = this.data, state = data.states[this.key()];
    if (!state) { return; }
    var items = state.items.map(function (i) { return data.items[i]; }), panels = data.panels[state.panels], m;
    this.current = panels;
    this.panels.forEach(function (svg, index) {
      var panel = panels[index], w = panel.px[0], h = panel.px[1];
      m = panel.margin || data.margin;
      svg.setAttribute("viewBox", [-m[0], -m[2], w + m[0] + m[1], h + m[2] + m[3]].join(" "));
      svg.setAttribute("width", w + m[0] + m[1]);
      svg.setAttribute("aria-label", panel.title || "");
      svg.innerHTML = self.render(index, panel, items);
    });
    this.summary.innerHTML = state.summary;
    this.caption.textContent = state.alt;
    this.detail.textContent = "";
    data.controls.forEach(function (c) {
      var input = self.inputs[c.name], shown = (c.shown || c.options)[self.values[c.name]];
      if (input.output) {  // a slider: says its value, to the eye and to a screen reader
        input.output.textContent = " " + shown;
        input.setAttribute("aria-valuetext", String(shown));
      }
    });
    this.root.querySelectorAll("circle[data-label]").forEach(function (dot) {
      var show = function () { self.detail.textContent = dot.getAttribute("data-label"); };
      dot.addEventListener("mouseenter", show);
      dot.addEventListener("focus", show);
      if (dot.classList.contains("ddg-handle")) { self.keys(dot); }
    });
    if (this.focusHandle) {
      var handle = this.root.querySelector(".ddg-handle");
      if (handle) { handle.focus(); }
    }
  };

  Player.prototype.keys = function (handle) {  // arrow keys move the dragged vertex by one grid step
    var self = this, drag = this.data.drag;
    handle.addEventListener("keydown", function (event) {
      var moves = {ArrowLeft: [drag.x, -1], ArrowRight: [drag.x, 1], ArrowDown: [drag.y, -1], ArrowUp: [drag.y, 1]};
      var move = moves[event.key];
      if (!move) { return; }
      event.preventDefault();
      self.focusHandle = true;
      self.set(move[0], self.values[move[0]] + move[1]);
    });
  };

  Player.prototype.dragging = function () {  // the pointer drags a vertex; it snaps to the grid
    var self = this, drag = this.data.drag, svg = this.panels[drag.panel];
    var active = false;
    function nearest(name, value) {
      var options = self.data.controls.filter(function (c) { return c.name === name; })[0].options, best = 0;
      options.forEach(function (o, i) { if (Math.abs(o - value) < Math.abs(options[best] - value)) { best = i; } });
      return best;
    }
    function move(event) {
      var box = svg.getBoundingClientRect(), view = svg.viewBox.baseVal;
      var px = (event.clientX - box.left) / box.width * view.width + view.x;
      var py = (event.clientY - box.top) / box.height * view.height + view.y;
      var panel = self.current[drag.panel], b = panel.box;
      var x = b[0] + px / panel.px[0] * (b[2] - b[0]), y = b[1] + (panel.px[1] - py) / panel.px[1] * (b[3] - b[1]);
      self.values[drag.x] = nearest(drag.x, x - drag.origin[0]);
      self.values[drag.y] = nearest(drag.y, y - drag.origin[1]);
      self.inputs[drag.x].value = self.values[drag.x];
      self.inputs[drag.y].value = self.values[drag.y];
      self.draw();
    }
    svg.addEventListener("pointerdown", function (event) {
      if (!event.target.classList || !event.target.classList.contains("ddg-handle")) { return; }
      active = true;
      svg.setPointerCapture(event.pointerId);
      event.preventDefault();
    });
    svg.addEventListener("pointermove", function (event) { if (active) { move(event); } });
    svg.addEventListener("pointerup", function () { active = false; });
    svg.addEventListener("pointercancel", function () { active = false; });
  };

  // The states are gzip-compressed JSON in base64: in the page, or in a script file of their own
  // (the book moves them there when it is built: tools/sphinx_assets.py), which loads as any script
  // does, also from a downloaded copy (file://, where fetch cannot read a file).
  function states(script) {
    var file = script.getAttribute("data-src");
    if (!file) { return Promise.resolve(script.textContent); }
    return new Promise(function (resolve, reject) {
      var tag = document.createElement("script");
      tag.src = file;
      tag.onload = function () { resolve(window.ddgStates[file.split("/").pop()]); };
      tag.onerror = reject;
      document.head.appendChild(tag);
    });
  }

  function load(root) {
    return states(root.querySelector("script.ddg-data")).then(function (text) {
      var bytes = Uint8Array.from(atob(text.trim()), function (c) { return c.charCodeAt(0); });
      var stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream("gzip"));
      return new Response(stream).json();
    });
  }

  function start(root) {
    if (root.player) { return; }
    root.player = "loading";
    load(root).then(function (data) { root.player = new Player(root, data); });
  }

  function watch() {  // an explorer starts (its states load) when it comes within a screen of the reader
    if (typeof DecompressionStream === "undefined") { return; }  // an old browser: the first state stays
    var roots = document.querySelectorAll(".ddg-explorer");
    if (typeof IntersectionObserver === "undefined") { roots.forEach(start); return; }
    var near = new IntersectionObserver(function (entries) {
      entries.forEach(function (entry) {
        if (entry.isIntersecting) { near.unobserve(entry.target); start(entry.target); }
      });
    }, {rootMargin: "100% 0px"});
    roots.forEach(function (root) { near.observe(root); });
  }

  if (document.readyState === "loading") {
    document.addEventListener("DOMContentLoaded", watch);
  } else {
    watch();
  }
})();
