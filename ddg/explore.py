"""Explorers and animations: ``ddg`` computes every state, a small SVG scene draws it.

>>> from ddg.explore import polygon_explorer, inflation_explorer, vertex_explorer
>>> polygon_explorer()        # n, the curve and the formula; the error against the smooth curvature
>>> inflation_explorer()      # eps, the shape and the inflation; the formula against the measured area
>>> vertex_explorer()         # drag one vertex; psi_i, every k_i and the gradient of length respond

One explorer, two places:

* in a notebook with a running kernel the call shows live controls (ipywidgets): every change is
  computed by ``ddg`` at once, for any value;
* in the built book the same output shows a version that needs no kernel: the states a reader can
  reach (a grid of control values) were computed by ``ddg`` when the book was built and are
  embedded in the page (as gzip-compressed JSON), and the book's player script
  (``book/_assets/ddg-player.js``) only looks them up and draws them. Printed, or without
  JavaScript, the page shows the first state.

A state is a :class:`Scene`: panels of lines, dots, arrows and text in data coordinates, plus a
line of numbers and a text alternative that says what the picture shows. :class:`Animation` plays
a list of scenes (the inflation and curve-shortening chapters use it).
"""

import base64
import gzip
import html
import itertools
import json

import numpy as np

from . import smooth
from ._extras import missing
from .curve import CURVATURES, INFLATIONS, DiscreteCurve, regular_polygon

COLORS = {"blue": "#3b82f6", "orange": "#f59e0b", "green": "#10b981", "red": "#ef4444", "purple": "#a855f7",
          "grey": "#9ca3af"}
"""Mid-tone colours, readable on the light and on the dark theme. Text and axes use the page's own
text colour (``currentColor``)."""

RAMP = ("#2563eb", "#9ca3af", "#dc2626")
"""The colour ramp of values in [0, 1] (curvature): blue, grey, red. The player uses the same."""


def _ramp(value):
    """The colour of ``value`` in [0, 1] on :data:`RAMP` (for the Python rendering)."""
    value = min(max(float(value), 0.0), 1.0)
    i = 0 if value <= 0.5 else 1
    t = value * 2 - i
    a, b = (np.array([int(c[k:k + 2], 16) for k in (1, 3, 5)]) for c in RAMP[i:i + 2])
    return "#" + "".join(f"{int(round(x)):02x}" for x in a + t * (b - a))


def _round(values, step):
    """Values rounded to the decimals that resolve ``step`` (a fraction of a pixel), for short JSON."""
    decimals = max(0, int(np.ceil(-np.log10(step))))
    return [float(x) for x in np.round(np.asarray(values, dtype=float).ravel(), decimals)]


class Scene:
    """What one state of an explorer shows: panels with shapes, a line of numbers, a text alternative.

    Each panel is a dict: its data box ``box = (x0, y0, x1, y1)`` (``y`` up), its size in pixels
    ``px = (w, h)``, a ``title``, and optionally a ``margin`` in pixels (left, right, top, bottom;
    default :data:`MARGIN`, room for axes). Shapes are given in data coordinates; text positions
    may also be given in pixels (``space="px"``).
    """

    def __init__(self, panels, summary="", alt=""):
        self.panels = panels  # list of {"box": (x0, y0, x1, y1), "px": (w, h), "title": str}
        self.items = []
        self.summary, self.alt = summary, alt
        for i, panel in enumerate(panels):
            if panel.get("title"):
                self.text(i, panel["px"][0] / 2, -10, panel["title"], "middle", 14, space="px")

    def _step(self, panel):
        """A quarter of a pixel, in the panel's data units: finer than anyone can see."""
        x0, y0, x1, y1 = self.panels[panel]["box"]
        w, h = self.panels[panel]["px"]
        return max((x1 - x0) / w, (y1 - y0) / h) / 4

    def line(self, panel, points, color="currentColor", width=1.5, closed=False, fill=None, dash=None,
             opacity=None):
        points = np.asarray(points, dtype=float).reshape(-1, 2)
        item = {"k": "line", "p": panel, "d": _round(points, self._step(panel)), "s": color, "w": width}
        item.update({k: v for k, v in (("z", closed), ("f", fill), ("dash", dash), ("o", opacity)) if v})
        self.items.append(item)

    def dots(self, panel, points, color="currentColor", r=3, labels=None, handle=False, values=None):
        """Dots; with ``labels`` each one can be focused and hovered to show its label; with
        ``values`` (in [0, 1]) each is coloured on :data:`RAMP` instead of ``color``."""
        item = {"k": "dots", "p": panel, "d": _round(points, self._step(panel)), "s": color, "r": r}
        if values is not None:
            item["c"] = _round(values, 0.01)
        if labels is not None:
            item["l"] = list(labels)
        if handle:
            item["h"] = True  # the point a reader drags (the vertex explorer)
        self.items.append(item)

    def arrows(self, panel, origins, vectors, color="currentColor", width=2):
        tips = np.asarray(origins, dtype=float) + np.asarray(vectors, dtype=float)
        self.items.append({"k": "arrows", "p": panel, "d": _round(np.hstack([np.asarray(origins, float), tips]),
                                                                  self._step(panel)), "s": color, "w": width})

    def bars(self, panel, x, heights, width, colors):
        """Vertical bars from 0 to ``heights`` at the centres ``x``, each in its colour."""
        step = self._step(panel)
        self.items.append({"k": "bars", "p": panel, "x": _round(x, step), "h": _round(heights, step),
                           "b": width, "c": list(colors)})

    def text(self, panel, x, y, string, anchor="start", size=13, color="currentColor", space="data", rotate=0):
        item = {"k": "text", "p": panel, "x": float(x), "y": float(y), "t": string, "a": anchor, "z": size, "s": color}
        if space == "px":
            item["px"] = True
        if rotate:
            item["r"] = rotate
        self.items.append(item)

    def axes(self, panel, xticks, yticks, xlabel="", ylabel="", xfmt="{:g}", yfmt="{:g}"):
        """A frame with ticks and labels at the given values (in the panel's data coordinates)."""
        x0, y0, x1, y1 = self.panels[panel]["box"]
        self.line(panel, [(x0, y0), (x1, y0), (x1, y1), (x0, y1)], closed=True, width=0.8, opacity=0.6)
        w, h = self.panels[panel]["px"]
        for x in xticks:
            self.line(panel, [(x, y0), (x, y0 + (y1 - y0) * 0.02)], width=0.8)
            self.text(panel, (x - x0) / (x1 - x0) * w, h + 17, xfmt.format(x), "middle", 13, space="px")
        for y in yticks:
            self.line(panel, [(x0, y), (x0 + (x1 - x0) * 0.02, y)], width=0.8)
            self.text(panel, -5, h - (y - y0) / (y1 - y0) * h + 4, yfmt.format(y), "end", 13, space="px")
        if xlabel:
            self.text(panel, w / 2, h + 36, xlabel, "middle", 14, space="px")
        if ylabel:
            self.text(panel, -34, h / 2, ylabel, "middle", 14, space="px", rotate=-90)


# ------------------------------------------------------------------ SVG, here and in the page

MARGIN = (46, 10, 28, 42)
"""Panel margins in pixels (left, right, top, bottom): room for ticks, labels and the title."""


def _to_px(panel, x, y):
    x0, y0, x1, y1 = panel["box"]
    w, h = panel["px"]
    return (x - x0) / (x1 - x0) * w, h - (y - y0) / (y1 - y0) * h


def _path(panel, flat, closed=False):
    pts = [_to_px(panel, flat[i], flat[i + 1]) for i in range(0, len(flat), 2)]
    return "M" + "L".join(f"{x:.1f},{y:.1f}" for x, y in pts) + ("Z" if closed else "")


def svg(scene, panel_index):
    """One panel of ``scene`` as an SVG element (what the player draws, for no-JS pages and widgets)."""
    panel = scene.panels[panel_index]
    w, h = panel["px"]
    left, right, top, bottom = panel.get("margin", MARGIN)
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" class="ddg-panel" viewBox="{-left} {-top} {w + left + right} '
           f'{h + top + bottom}" width="{w + left + right}" height="{h + top + bottom}" role="img" '
           f'aria-label="{html.escape(panel.get("title", ""))}" font-family="sans-serif" fill="currentColor">']
    for item in (i for i in scene.items if i["p"] == panel_index):
        kind, d = item["k"], item.get("d", [])
        if kind == "line":
            style = f'stroke="{item["s"]}" stroke-width="{item["w"]}" fill="{item.get("f", "none")}"'
            style += f' stroke-dasharray="{item["dash"]}"' if item.get("dash") else ""
            style += f' opacity="{item["o"]}"' if item.get("o") else ""
            out.append(f'<path d="{_path(panel, d, item.get("z"))}" {style}/>')
        elif kind == "dots":
            for j in range(0, len(d), 2):
                x, y = _to_px(panel, d[j], d[j + 1])
                color = _ramp(item["c"][j // 2]) if "c" in item else item["s"]
                out.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="{item["r"]}" fill="{color}"/>')
        elif kind == "arrows":
            for j in range(0, len(d), 4):
                (x, y), (u, v) = _to_px(panel, d[j], d[j + 1]), _to_px(panel, d[j + 2], d[j + 3])
                out.append(f'<line x1="{x:.1f}" y1="{y:.1f}" x2="{u:.1f}" y2="{v:.1f}" stroke="{item["s"]}" '
                           f'stroke-width="{item["w"]}"/><circle cx="{u:.1f}" cy="{v:.1f}" r="2.5" '
                           f'fill="{item["s"]}"/>')
        elif kind == "bars":
            for x, height, color in zip(item["x"], item["h"], item["c"]):
                (left, top), (right, bottom) = (_to_px(panel, x - item["b"] / 2, max(height, 0)),
                                                _to_px(panel, x + item["b"] / 2, min(height, 0)))
                out.append(f'<rect x="{left:.1f}" y="{top:.1f}" width="{right - left:.1f}" height="{bottom - top:.1f}" '
                           f'fill="{color}"/>')
        elif kind == "text":
            x, y = (item["x"], item["y"]) if item.get("px") else _to_px(panel, item["x"], item["y"])
            rotate = f' transform="rotate({item["r"]} {x:.1f} {y:.1f})"' if item.get("r") else ""
            out.append(f'<text x="{x:.1f}" y="{y:.1f}" text-anchor="{item["a"]}" font-size="{item["z"]}" '
                       f'fill="{item["s"]}"{rotate}>{html.escape(item["t"])}</text>')
    out.append("</svg>")
    return "".join(out)


def _pack(scenes, controls, drag=None):
    """The page's data: controls, panels, and every state as references into shared pools.

    Items that several states share (the axes, a curve, a polygon drawn for three formulas) and
    long number arrays are stored once; a state lists the indices of its items.
    """
    pool, pool_index, items, item_index, states, panel_sets, panel_index = [], {}, [], {}, {}, [], {}
    for key, scene in scenes.items():
        refs = []
        for item in scene.items:
            item = dict(item)
            if len(item.get("d", [])) > 16:
                text = json.dumps(item["d"])
                item["d"] = {"$": pool_index.setdefault(text, len(pool))}
                if item["d"]["$"] == len(pool):
                    pool.append(json.loads(text))
            text = json.dumps(item, sort_keys=True)
            refs.append(item_index.setdefault(text, len(items)))
            if refs[-1] == len(items):
                items.append(item)
        text = json.dumps(scene.panels, sort_keys=True)  # the panels' boxes and sizes, shared when equal
        panels = panel_index.setdefault(text, len(panel_sets))
        if panels == len(panel_sets):
            panel_sets.append(json.loads(text))
        states[key] = {"i": refs, "p": panels, "t": scene.summary, "a": scene.alt}
    return {"controls": controls, "panels": panel_sets, "margin": MARGIN, "ramp": RAMP, "pool": pool,
            "items": items, "states": states, "drag": drag}


# ------------------------------------------------------------------ explorers


class Explorer:
    """Controls over ``ddg`` computations; a subclass defines them and :meth:`scene`.

    ``controls`` is a list of dicts: ``name``, ``label``, ``type`` (``"select"``, ``"range"`` or
    ``"frames"``), ``options`` (the values a static page offers) and ``value``. A live notebook
    accepts any value in the range of a ``"range"`` control (``live_min``, ``live_max``, ``step``).
    """

    controls = []
    drag = None
    title = ""

    def values(self):
        return {c["name"]: c["value"] for c in self.controls}

    def scene(self, **values):
        raise NotImplementedError

    def key(self, values):
        """The state's name: its control values as the page's script writes them (1.0 as "1")."""
        return "|".join(_key_text(values[c["name"]]) for c in self.controls)

    def states(self):
        """Every state a reader of the static page can reach, by key."""
        names = [c["name"] for c in self.controls]
        grid = itertools.product(*(c["options"] for c in self.controls))
        return {self.key(dict(zip(names, combo))): self.scene(**dict(zip(names, combo))) for combo in grid}

    def html(self):
        """The kernel-free explorer: data for the player, and the first state drawn for no-JS and print.

        A control's value that the static page does not offer is moved to the nearest one it does.
        """
        values = self.values()
        for c in self.controls:
            if c["type"] == "range" and values[c["name"]] not in c["options"]:
                values[c["name"]] = min(c["options"], key=lambda option: abs(option - values[c["name"]]))
        first = self.scene(**values)
        data = _pack(self.states(), self.controls, self.drag)
        data["value"] = self.key(values)
        data["title"] = self.title
        figures = "".join(svg(first, i) for i in range(len(first.panels)))
        strip = "".join(f'<div class="ddg-print-state" role="img" aria-label="{html.escape(scene.alt)}">'
                        + "".join(svg(scene, i) for i in range(len(scene.panels)))
                        + f'<p class="ddg-summary">{scene.summary}</p></div>' for scene in self.print_states())
        blob = base64.b64encode(gzip.compress(json.dumps(data, separators=(",", ":")).encode(), mtime=0)).decode()
        return (f'<div class="ddg-explorer" data-title="{html.escape(self.title)}">'
                f'<div class="ddg-static" role="img" aria-label="{html.escape(first.alt)}">{figures}'
                f'<p class="ddg-summary">{first.summary}</p></div>'
                f'<div class="ddg-print"><p class="ddg-print-note">{html.escape(self.title or "An animation")}, '
                f'in {len(self.print_states())} of its states. The live version is in the web edition of this '
                f'page and in the chapter\'s notebook.</p>{strip}</div>'
                f'<script type="application/gzip+base64" class="ddg-data">{blob}</script></div>')

    def print_states(self, count=3):
        """A few states for a printed page: the first slider (or frames) from start to end."""
        values = self.values()
        moving = next((c for c in self.controls if c["type"] in ("range", "frames")), None)
        if moving is None:
            return [self.scene(**values)]
        picks = np.unique(np.linspace(0, len(moving["options"]) - 1, count).round().astype(int))
        return [self.scene(**{**values, moving["name"]: moving["options"][i]}) for i in picks]

    def widget(self):
        """Live controls (ipywidgets) that recompute the scene with ``ddg`` on every change."""
        try:
            import ipywidgets as widgets
        except ImportError as error:
            raise missing("explore", error) from error
        inputs = {}
        for c in self.controls:
            if c["type"] == "select":
                inputs[c["name"]] = widgets.Dropdown(options=c["options"], value=c["value"], description=c["label"])
            elif c["type"] == "range":
                low, high = c.get("live_min", c["options"][0]), c.get("live_max", c["options"][-1])
                step = c.get("step", 1)
                kind = widgets.IntSlider if isinstance(step, int) else widgets.FloatSlider
                inputs[c["name"]] = kind(value=c["value"], min=low, max=high, step=step, description=c["label"],
                                         continuous_update=False)
            else:  # frames
                inputs[c["name"]] = widgets.IntSlider(value=c["value"], min=0, max=len(c["options"]) - 1,
                                                      description=c["label"])
        picture, summary = widgets.HTML(), widgets.HTML()

        def redraw(_=None):
            scene = self.scene(**{name: control.value for name, control in inputs.items()})
            picture.value = (f'<div class="ddg-static" role="img" aria-label="{html.escape(scene.alt)}">'
                             + "".join(svg(scene, i) for i in range(len(scene.panels))) + "</div>")
            summary.value = scene.summary

        for control in inputs.values():
            control.observe(redraw, names="value")
        redraw()
        box = widgets.VBox([widgets.HBox(list(inputs.values())), summary, picture])
        box.explorer = self
        return box

    def _repr_mimebundle_(self, **kwargs):
        """Live widgets where a kernel runs; the kernel-free explorer in the book (``text/html``)."""
        bundle = {"text/html": self.html(), "text/plain": f"<{type(self).__name__}: {self.title}>"}
        try:
            box = self.widget()
        except ImportError:
            return bundle
        return {**box._repr_mimebundle_(**kwargs), **{k: v for k, v in bundle.items() if k != "text/plain"}}


def _key_text(value):
    """A control value as JavaScript's ``String()`` writes it: 0.0 is "0", 0.15 is "0.15"."""
    if isinstance(value, float) and value.is_integer():
        return str(int(value))
    return str(value)


def _nice_ticks(low, high, count=5):
    """About ``count`` round tick values between ``low`` and ``high``."""
    step = 10 ** np.floor(np.log10((high - low) / count))
    for factor in (1, 2, 5, 10):
        if (high - low) / (step * factor) <= count:
            step *= factor
            break
    return list(np.arange(np.ceil(low / step), np.floor(high / step) + 1) * step)


SHAPES = {
    "circle": smooth.circle(1.0),
    "ellipse": smooth.ellipse(2.0, 1.0),
    "non-convex blob": smooth.polar(lambda t: 1 + 0.3 * np.cos(3 * t), lambda t: -0.9 * np.sin(3 * t),
                                    lambda t: -2.7 * np.cos(3 * t), name="blob r = 1 + 0.3 cos 3t"),
}
"""Smooth closed curves (clockwise) for the polygon explorer."""


class PolygonExplorer(Explorer):
    """Sample a smooth curve with ``n`` vertices; colour the polygon by a discrete curvature."""

    title = "Polygons on a smooth curve"
    N_STATIC = [*range(3, 25), 32, 48, 64, 96, 128, 192, 256]

    def __init__(self, n=12, shape="ellipse", kind="angle"):
        self.controls = [
            {"name": "shape", "label": "curve", "type": "select", "options": list(SHAPES), "value": shape},
            {"name": "n", "label": "vertices n", "type": "range", "options": self.N_STATIC, "value": n,
             "live_min": 3, "live_max": 1000, "step": 1},
            {"name": "kind", "label": "formula", "type": "select", "options": list(CURVATURES), "value": kind},
        ]

    def compute(self, n, shape, kind):
        """The polygon, its curvature ``k``, the smooth ``kappa`` at the same points, and the errors."""
        curve = SHAPES[shape]
        t = curve.sample_parameters(int(n))
        polygon = DiscreteCurve(curve.position(t))
        k, kappa = polygon.curvature(kind), curve.curvature(t)
        return polygon, t, k, kappa, np.abs(k - kappa)

    def scene(self, n, shape, kind):
        curve = SHAPES[shape]
        polygon, t, k, kappa, error = self.compute(n, shape, kind)
        tt = np.linspace(curve.t0, curve.t1, 240)
        outline = curve.position(tt)
        pad = 0.12 * np.ptp(outline, axis=0).max()
        (x0, y0), (x1, y1) = outline.min(axis=0) - pad, outline.max(axis=0) + pad
        size = 270
        w, h = (size, size * (y1 - y0) / (x1 - x0)) if x1 - x0 >= y1 - y0 else (size * (x1 - x0) / (y1 - y0), size)
        scene = Scene([{"box": (x0, y0, x1, y1), "px": (round(w), round(h)), "title": f"{curve.name}: kᵢ by colour"},
                       {"box": (0, -12, 1, 1), "px": (260, 220), "title": "error |kᵢ − κ(tᵢ)|"}])
        scene.line(0, outline, color=COLORS["grey"], width=1, closed=True)
        spread = max(np.ptp(curve.curvature(tt)), 0.5 * np.abs(curve.curvature(tt)).max())
        low, high = curve.curvature(tt).min() - 0.3 * spread, curve.curvature(tt).max() + 0.3 * spread
        scene.line(0, polygon.vertices, width=0.8, closed=True, opacity=0.5)
        scene.dots(0, polygon.vertices, r=3.5, values=(k - low) / (high - low))
        scene.axes(1, [0, 0.5, 1], list(range(-12, 1, 3)), "parameter tᵢ / 2π", "log₁₀ error", yfmt="{:.0f}")
        scene.line(1, np.stack([t / (2 * np.pi), np.log10(np.maximum(error, 1e-12))], axis=1),
                   color=COLORS["blue"], width=1.5)
        total = polygon.total_curvature(kind) / (2 * np.pi)
        scene.summary = (f"{curve.name}, n = {n}, {kind} formula: largest |kᵢ − κ(tᵢ)| = {error.max():.3e}; "
                         f"⟨k, 1⟩ / 2π = {total:.6f}")
        scene.alt = (f"The {curve.name} with a polygon of {n} vertices on it, coloured by the {kind} curvature "
                     f"(blue low, red high), and each vertex's error on a log scale, at most {error.max():.1e}.")
        return scene


POLYGONS = {
    "convex pentagon": DiscreteCurve([[0.0, 0.0], [0.3, 1.5], [1.8, 2.0], [3.0, 1.0], [2.4, -0.4]]),
    "non-convex star": DiscreteCurve(np.stack([np.where(np.arange(10) % 2 == 0, 1.0, 0.5) * np.cos(np.arange(10) * np.pi / 5),
                                               -np.where(np.arange(10) % 2 == 0, 1.0, 0.5) * np.sin(np.arange(10) * np.pi / 5)],
                                              axis=1)),
}
"""Closed clockwise polygons for the inflation explorer."""


def measured_region(polygon, eps, method, quad_segs=256):
    """The inflated region, measured independently by shapely: round joins (the Minkowski sum),
    or mitre joins (the offset)."""
    try:
        import shapely
    except ImportError as error:
        raise missing("explore", error) from error
    region = shapely.Polygon(polygon.vertices)
    if method == "minkowski":
        return region.buffer(eps, quad_segs=quad_segs)
    return region.buffer(eps, join_style="mitre", mitre_limit=1e6)


class InflationExplorer(Explorer):
    """Inflate a polygon by ``eps``; compare the formula's area with the region's measured area."""

    title = "Inflation"

    def __init__(self, eps=0.3, shape="non-convex star", method="minkowski"):
        self.controls = [
            {"name": "shape", "label": "shape", "type": "select", "options": list(POLYGONS), "value": shape},
            {"name": "eps", "label": "ε", "type": "range", "options": [round(e, 2) for e in np.arange(0, 1.0001, 0.05)],
             "value": eps, "live_min": 0.0, "live_max": 1.0, "step": 0.01},
            {"name": "method", "label": "inflation", "type": "select", "options": list(INFLATIONS), "value": method},
        ]

    def compute(self, eps, shape, method):
        polygon = POLYGONS[shape]
        region = measured_region(polygon, eps, method)
        return polygon, region, polygon.inflated_area(eps, method)

    def scene(self, eps, shape, method):
        polygon, region, formula = self.compute(eps, shape, method)
        x0, y0, x1, y1 = measured_region(polygon, 1.0, "minkowski", 16).bounds
        scene = Scene([{"box": (x0 - 0.1, y0 - 0.1, x1 + 0.1, y1 + 0.1),
                        "px": (320, round(320 * (y1 - y0 + 0.2) / (x1 - x0 + 0.2))), "title": shape}])
        color = COLORS["orange"] if method == "minkowski" else COLORS["green"]
        drawn = measured_region(polygon, eps, method, quad_segs=8) if eps > 0 else None
        if drawn is not None:
            scene.line(0, np.asarray(drawn.exterior.coords), color=color, fill=color, opacity=0.45, width=1, closed=True)
        scene.line(0, polygon.vertices, color=COLORS["grey"], fill=COLORS["grey"], width=1, closed=True)
        if eps > 0:
            boundary = polygon.inflate(eps, method).vertices
            step = max(1, len(boundary) // 200)  # a drawing: about 200 points are plenty
            scene.line(0, boundary[::step], color="currentColor", width=1, closed=True, dash="4 3")
        name = {"minkowski": "Minkowski sum", "offset": "offset"}[method]
        scene.summary = (f"{name}, ε = {eps:.2f}: formula A₀ + εL + ε²/2 ⟨k, 1⟩ = {formula:.6f}; "
                         f"measured {region.area:.6f}; difference {region.area - formula:+.2e}")
        scene.alt = (f"The {shape} (grey) inflated by ε = {eps:.2f}, the {name}: the region it covers, "
                     f"measured by shapely (shaded), and the boundary ddg computes (dashed). The formula gives "
                     f"{formula:.4f}, the region measures {region.area:.4f}.")
        return scene


class VertexExplorer(Explorer):
    """Drag vertex ``j`` of a regular hexagon; watch its turning angle, curvatures and the gradient of length."""

    title = "One vertex"
    GRID = np.round(np.arange(-1.5, 1.5001, 0.15), 2) + 0.0  # + 0.0: no -0.0, whose key would differ

    def __init__(self, dx=0.0, dy=0.0, j=2):
        self.base = regular_polygon(6, 1.0).vertices.copy()
        self.j = j
        self.controls = [
            {"name": "dx", "label": f"move v{j}: x", "type": "range", "options": list(self.GRID), "value": dx,
             "live_min": -1.5, "live_max": 1.5, "step": 0.02},
            {"name": "dy", "label": "y", "type": "range", "options": list(self.GRID), "value": dy,
             "live_min": -1.5, "live_max": 1.5, "step": 0.02},
        ]
        self.drag = {"panel": 0, "x": "dx", "y": "dy", "origin": [float(c) for c in self.base[j]]}

    def compute(self, dx, dy):
        """The polygon with ``v_j`` moved, its curvatures by formula (None where undefined), its gradient."""
        v = self.base.copy()
        v[self.j] += (dx, dy)
        polygon = DiscreteCurve(v)  # raises ValueError where v_j lands on a neighbour
        ks = {}
        for kind in CURVATURES:
            try:
                ks[kind] = polygon.curvature(kind)
            except ValueError:  # the tangent formula where the curve turns straight back
                ks[kind] = None
        return polygon, ks, polygon.length_gradient()

    def scene(self, dx, dy):
        j = self.j
        scene = Scene([{"box": (-2.2, -2.2, 2.2, 2.2), "px": (270, 270), "title": f"drag v{j}: ∇L at each vertex"},
                       {"box": (-0.6, -6, 2.6, 6), "px": (240, 270), "title": f"kᵢ at v{j - 1}, v{j}, v{j + 1}"}])
        try:
            polygon, ks, grad = self.compute(dx, dy)
        except ValueError as problem:
            v = self.base.copy()
            v[j] += (dx, dy)
            scene.line(0, v, closed=True, width=1.5, dash="3 3")
            scene.dots(0, v[j:j + 1], color=COLORS["red"], r=7, handle=True, labels=[f"v{j}: {problem}"])
            scene.summary = f"<b>not a discrete curve:</b> {html.escape(str(problem))}"
            scene.alt = f"Vertex v{j} sits on a neighbour: {problem}."
            return scene
        v, psi = polygon.vertices, polygon.turning_angles
        scene.line(0, v, closed=True, width=1.5)
        scene.arrows(0, v, 0.3 * grad, color=COLORS["red"])
        for i in range(len(v)):
            values = ", ".join(f"{kind} {ks[kind][i]:+.4f}" if ks[kind] is not None else f"{kind} diverges"
                               for kind in CURVATURES)
            scene.dots(0, v[i:i + 1], r=7 if i == j else 4, color=COLORS["red"] if i == j else "currentColor",
                       labels=[f"v{i}: ψ = {psi[i]:+.4f}; k: {values}"], handle=i == j)
        neighbours = np.array([j - 1, j, j + 1]) % len(v)
        scene.axes(1, [], [-6, -3, 0, 3, 6], "", "kᵢ (clipped to ±6)")
        scene.line(1, [(-0.6, 0), (2.6, 0)], width=0.8)
        x, heights, colors = [], [], []
        for slot, i in enumerate(neighbours):
            scene.text(1, (slot + 0.6) / 3.2 * 240, 270 + 17, f"v{i}", "middle", 13, space="px")
            for offset, (kind, color) in enumerate(zip(CURVATURES, (COLORS["blue"], COLORS["orange"], COLORS["green"]))):
                if ks[kind] is not None:
                    x.append(slot + (offset - 1) * 0.25)
                    heights.append(float(np.clip(ks[kind][i], -6, 6)))
                    colors.append(color)
            norm = min(float(np.linalg.norm(grad[i])), 6)
            scene.line(1, [(slot - 0.4, norm), (slot + 0.4, norm)], width=2, dash="5 3")
        scene.bars(1, x, heights, 0.22, colors)
        scene.text(1, 4, 14, "angle", "start", 13, COLORS["blue"], space="px")
        scene.text(1, 50, 14, "sine", "start", 13, COLORS["orange"], space="px")
        scene.text(1, 86, 14, "tangent", "start", 13, COLORS["green"], space="px")
        scene.text(1, 146, 14, "- - |∇L|", "start", 13, space="px")
        tangent = (f"k tangent = {ks['tangent'][j]:+.4f}" if ks["tangent"] is not None
                   else "k tangent diverges (ψ = π)")
        scene.summary = (f"at v{j}: ψ = {psi[j]:+.4f} ({np.degrees(psi[j]):+.1f}°), k angle = {ks['angle'][j]:+.4f}, "
                         f"k sine = {ks['sine'][j]:+.4f}, {tangent}, |∇L| = {np.linalg.norm(grad[j]):.4f}; "
                         f"L = {polygon.length:.4f}")
        scene.alt = (f"A hexagon with v{j} moved by ({dx:+.2f}, {dy:+.2f}), arrows along the gradient of length, and "
                     f"bars of the three curvatures at v{j} and its neighbours; at v{j}, ψ = {psi[j]:+.3f}.")
        return scene


class Animation(Explorer):
    """Scenes played in order: a play/pause button and a slider to scrub through them.

    ``frames`` is a list of :class:`Scene` objects (all with the same panels), computed by the
    caller with ``ddg``; ``label`` names the quantity that changes (``"ε"``, ``"t"``), ``values``
    its value in each frame; ``start`` the frame shown first (and on paper).
    """

    def __init__(self, frames, label, values, title="", interval=250, start=0):
        self.frames, self.title, self.interval = list(frames), title, interval
        if isinstance(start, bool) or not isinstance(start, (int, np.integer)) or not 0 <= start < len(self.frames):
            raise ValueError(f"start must be a frame index from 0 to {len(self.frames) - 1}, got {start!r}")
        self.controls = [{"name": "frame", "label": label, "type": "frames", "options": list(range(len(self.frames))),
                          "value": int(start), "shown": [f"{v:g}" for v in values], "interval": interval}]

    def scene(self, frame):
        return self.frames[int(frame)]

    def states(self):
        return {str(i): frame for i, frame in enumerate(self.frames)}

    def key(self, values):
        return str(values["frame"])


def polygon_explorer(n=12, shape="ellipse", kind="angle"):
    """Controls for ``n``, the curve (``ddg.explore.SHAPES``) and the formula (``ddg.CURVATURES``)."""
    return PolygonExplorer(n, shape, kind)


def inflation_explorer(eps=0.3, shape="non-convex star", method="minkowski"):
    """Controls for ``eps``, the shape (``ddg.explore.POLYGONS``) and the inflation (``ddg.INFLATIONS``)."""
    return InflationExplorer(eps, shape, method)


def vertex_explorer(dx=0.0, dy=0.0):
    """Move one vertex of a regular hexagon: drag it, or use the controls."""
    return VertexExplorer(dx, dy)
