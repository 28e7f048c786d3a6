"""What an explorer or animation draws (a :class:`Scene`), and how it reaches the page.

A scene is a list of panels and the items drawn in them, in data coordinates. Python draws it as
SVG (:func:`svg`: notebooks' widgets, printed pages, pages without JavaScript); in the built book,
``book/_assets/ddg-player.js`` draws the same items from the page's data, and a browser test
renders one scene both ways and compares the two. The items are plain dicts whose keys are the
schema both read:

==========  ==================================================================================
key         meaning
==========  ==================================================================================
kind        ``"line"``, ``"dots"``, ``"arrows"``, ``"bars"`` or ``"text"``
panel       the index of the panel it is drawn in
points      ``[x0, y0, x1, y1, ...]`` in data coordinates (line, dots); for arrows
            ``[x, y, tip_x, tip_y, ...]``. In the page's data, a long list may be a reference
            ``{"pool": j}`` to the ``j``-th list of the shared pool
color       the stroke of a line or arrow, the fill of a dot or text (a CSS colour)
width       stroke width in pixels (line, arrows)
closed      line: joined back to its first point
fill        line: the colour it encloses
dash        line: an SVG dash pattern such as ``"4 3"``
opacity     line: between 0 and 1
radius      dots: in pixels
values      dots: one number in [0, 1] per dot, coloured on :data:`RAMP` instead of ``color``
labels      dots: one text per dot, shown when the reader hovers or focuses it
handle      dots: the point the reader drags (the vertex explorer)
x           bars: their centres; text: its position
heights     bars: from 0 to each height
bar_width   bars: in data units
colors      bars: one colour per bar
y           text: its position
text        text: the string
anchor      text: ``"start"``, ``"middle"`` or ``"end"``
size        text: font size in pixels
pixels      text: ``x, y`` are pixels from the panel's top left corner, not data
rotate      text: degrees
==========  ==================================================================================

A panel is ``{"box": (x0, y0, x1, y1), "px": (w, h), "title": ..., "margin": (l, r, t, b)}``:
its data box (``y`` up), its size and margins in pixels. The page's data (:func:`pack`) is
``{"controls", "panels", "margin", "ramp", "pool", "items", "states", "drag", "value",
"title"}``; a state is ``{"items": [indices], "panels": index, "summary", "alt"}``.

:class:`Explorer` turns controls and a ``scene`` method into live widgets in a notebook and the
kernel-free player in the book; :class:`Animation` plays a list of scenes.
"""

import base64
import decimal
import gzip
import html
import itertools
import json

import numpy as np

from ._extras import missing

COLORS = {"blue": "#3b82f6", "orange": "#f59e0b", "green": "#10b981", "red": "#ef4444", "purple": "#a855f7",
          "grey": "#9ca3af"}
"""Mid-tone colours, readable on the light and on the dark theme. Text and axes use the page's own
text colour (``currentColor``)."""

RAMP = ("#2563eb", "#9ca3af", "#dc2626")
"""The colour ramp of values in [0, 1] (curvature): blue, grey, red. The player uses the same."""

MARGIN = (46, 10, 28, 42)
"""Panel margins in pixels (left, right, top, bottom): room for ticks, labels and the title."""


def ramp(stops, value):
    """The colour of ``value`` in [0, 1] on ``stops`` (three colours), as ``#rrggbb``."""
    value = min(max(float(value), 0.0), 1.0)
    i = 0 if value <= 0.5 else 1
    t = value * 2 - i
    a, b = ([int(c[k:k + 2], 16) for k in (1, 3, 5)] for c in stops[i:i + 2])
    return "#" + "".join(f"{int(np.floor(x + t * (y - x) + 0.5)):02x}" for x, y in zip(a, b, strict=True))


def fixed(x):
    """``x`` with one decimal, as JavaScript's ``toFixed(1)`` writes it (halves away from zero)."""
    rounded = decimal.Decimal(float(x) + 0.0).quantize(decimal.Decimal("0.1"), decimal.ROUND_HALF_UP)
    return str(rounded)


def number(x):
    """``x`` as JavaScript's ``String()`` writes it: 1.0 is "1", 0.15 is "0.15"."""
    if isinstance(x, str):
        return x
    if isinstance(x, (int, np.integer)) or float(x).is_integer():
        return str(int(x))
    return repr(float(x))


def escape(text):
    """``text`` for HTML, as the player's ``escape`` writes it."""
    return str(text).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;").replace('"', "&quot;")


def _round(values, step):
    """Values rounded to the decimals that resolve ``step`` (a fraction of a pixel), for short JSON."""
    decimals = max(0, int(np.ceil(-np.log10(step))))
    return [float(x) for x in np.round(np.asarray(values, dtype=float).ravel(), decimals)]


class Scene:
    """What one state of an explorer shows: panels of items, a line of numbers, a text alternative.

    ``panels`` is a list of panel dicts (see the module's docstring); shapes are given in data
    coordinates, text may be placed in pixels (``space="px"``).
    """

    def __init__(self, panels, summary="", alt=""):
        self.panels, self.items, self.summary, self.alt = panels, [], summary, alt
        for i, panel in enumerate(panels):
            if panel.get("title"):
                self.text(i, panel["px"][0] / 2, -10, panel["title"], "middle", 14, space="px")

    def _step(self, panel):
        """A quarter of a pixel, in the panel's data units: finer than anyone can see."""
        x0, y0, x1, y1 = self.panels[panel]["box"]
        w, h = self.panels[panel]["px"]
        return max((x1 - x0) / w, (y1 - y0) / h) / 4

    def _add(self, kind, panel, **keys):
        self.items.append({"kind": kind, "panel": panel, **{k: v for k, v in keys.items() if v is not None}})

    def line(self, panel, points, color="currentColor", width=1.5, closed=False, fill=None, dash=None,
             opacity=None):
        self._add("line", panel, points=_round(points, self._step(panel)), color=color, width=width,
                  closed=closed or None, fill=fill, dash=dash, opacity=opacity)

    def dots(self, panel, points, color="currentColor", r=3, labels=None, handle=False, values=None):
        """Dots; with ``labels`` each one can be focused and hovered to show its label; with
        ``values`` (in [0, 1]) each is coloured on :data:`RAMP` instead of ``color``."""
        self._add("dots", panel, points=_round(points, self._step(panel)), color=color, radius=r,
                  values=None if values is None else _round(values, 0.01),
                  labels=None if labels is None else list(labels), handle=handle or None)

    def arrows(self, panel, origins, vectors, color="currentColor", width=2):
        origins = np.asarray(origins, dtype=float)
        segments = np.hstack([origins, origins + np.asarray(vectors, dtype=float)])
        self._add("arrows", panel, points=_round(segments, self._step(panel)), color=color, width=width)

    def bars(self, panel, x, heights, width, colors):
        """Vertical bars from 0 to ``heights`` at the centres ``x``, each in its colour."""
        step = self._step(panel)
        self._add("bars", panel, x=_round(x, step), heights=_round(heights, step), bar_width=width,
                  colors=list(colors))

    def text(self, panel, x, y, string, anchor="start", size=13, color="currentColor", space="data", rotate=0):
        self._add("text", panel, x=float(x), y=float(y), text=string, anchor=anchor, size=size, color=color,
                  pixels=(space == "px") or None, rotate=rotate or None)

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


def point(panel, x, y):
    """Data coordinates to the panel's pixels (``y`` down)."""
    x0, y0, x1, y1 = panel["box"]
    w, h = panel["px"]
    return (x - x0) / (x1 - x0) * w, h - (y - y0) / (y1 - y0) * h


def path(panel, points, closed=False):
    pts = [point(panel, points[i], points[i + 1]) for i in range(0, len(points), 2)]
    return "M" + "L".join(f"{fixed(x)},{fixed(y)}" for x, y in pts) + ("Z" if closed else "")


def render(panel_index, panel, items, pool=(), stops=RAMP):
    """The SVG elements of one panel's items: what the player's ``render`` writes, less its
    interactive attributes (focus and hover on labelled dots, the handle's class)."""
    out = []
    for item in (i for i in items if i["panel"] == panel_index):
        kind, color = item["kind"], item.get("color")
        d = item.get("points", [])
        d = pool[d["pool"]] if isinstance(d, dict) else d
        if kind == "line":
            out.append(f'<path d="{path(panel, d, item.get("closed"))}" stroke="{color}" '
                       f'stroke-width="{number(item["width"])}" fill="{item.get("fill") or "none"}"'
                       + (f' stroke-dasharray="{item["dash"]}"' if item.get("dash") else "")
                       + (f' opacity="{number(item["opacity"])}"' if item.get("opacity") else "") + "/>")
        elif kind == "dots":
            for j in range(0, len(d), 2):
                x, y = point(panel, d[j], d[j + 1])
                fill = ramp(stops, item["values"][j // 2]) if "values" in item else color
                out.append(f'<circle cx="{fixed(x)}" cy="{fixed(y)}" r="{number(item["radius"])}" fill="{fill}"></circle>')
        elif kind == "arrows":
            for j in range(0, len(d), 4):
                (x, y), (u, v) = point(panel, d[j], d[j + 1]), point(panel, d[j + 2], d[j + 3])
                out.append(f'<line x1="{fixed(x)}" y1="{fixed(y)}" x2="{fixed(u)}" y2="{fixed(v)}" stroke="{color}" '
                           f'stroke-width="{number(item["width"])}"/><circle cx="{fixed(u)}" cy="{fixed(v)}" r="2.5" '
                           f'fill="{color}"/>')
        elif kind == "bars":
            for x, height, fill in zip(item["x"], item["heights"], item["colors"], strict=True):
                (left, top) = point(panel, x - item["bar_width"] / 2, max(height, 0))
                (right, bottom) = point(panel, x + item["bar_width"] / 2, min(height, 0))
                out.append(f'<rect x="{fixed(left)}" y="{fixed(top)}" width="{fixed(right - left)}" '
                           f'height="{fixed(bottom - top)}" fill="{fill}"/>')
        elif kind == "text":
            x, y = (item["x"], item["y"]) if item.get("pixels") else point(panel, item["x"], item["y"])
            turn = f' transform="rotate({number(item["rotate"])} {fixed(x)} {fixed(y)})"' if item.get("rotate") else ""
            out.append(f'<text x="{fixed(x)}" y="{fixed(y)}" text-anchor="{item["anchor"]}" '
                       f'font-size="{number(item["size"])}" fill="{color}"{turn}>{escape(item["text"])}</text>')
    return "".join(out)


def svg(scene, panel_index):
    """One panel of ``scene`` as an SVG element (for pages without JavaScript, print and widgets)."""
    panel = scene.panels[panel_index]
    w, h = panel["px"]
    left, right, top, bottom = panel.get("margin", MARGIN)
    return (f'<svg xmlns="http://www.w3.org/2000/svg" class="ddg-panel" viewBox="{-left} {-top} {w + left + right} '
            f'{h + top + bottom}" width="{w + left + right}" height="{h + top + bottom}" role="img" '
            f'aria-label="{html.escape(panel.get("title", ""))}" font-family="sans-serif" fill="currentColor">'
            f'{render(panel_index, panel, scene.items)}</svg>')


def pack(scenes, controls, drag=None):
    """The page's data: controls, panels, and every state as references into shared pools.

    Items that several states share (the axes, a curve, a polygon drawn for three formulas) and
    long number arrays are stored once; a state lists the indices of its items.
    """
    pool, pool_index, items, item_index, states, panel_sets, panel_index = [], {}, [], {}, {}, [], {}

    def shared(value, index, store):
        text = json.dumps(value, sort_keys=True)
        if text not in index:
            index[text] = len(store)
            store.append(value)
        return index[text]

    for key, scene in scenes.items():
        refs = []
        for item in scene.items:
            if len(item.get("points", [])) > 16:
                item = {**item, "points": {"pool": shared(item["points"], pool_index, pool)}}
            refs.append(shared(item, item_index, items))
        panels = shared(scene.panels, panel_index, panel_sets)  # boxes and sizes, shared when equal
        states[key] = {"items": refs, "panels": panels, "summary": scene.summary, "alt": scene.alt}
    return {"controls": controls, "panels": panel_sets, "margin": MARGIN, "ramp": RAMP,
            "pool": pool, "items": items, "states": states, "drag": drag}


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
        return "|".join(number(values[c["name"]]) for c in self.controls)

    def states(self):
        """Every state a reader of the static page can reach, by key."""
        names = [c["name"] for c in self.controls]
        grid = itertools.product(*(c["options"] for c in self.controls))
        return {self.key(dict(zip(names, combo, strict=True))): self.scene(**dict(zip(names, combo, strict=True))) for combo in grid}

    def html(self):
        """The kernel-free explorer: data for the player, and the first state drawn for no-JS and print.

        A control's value that the static page does not offer is moved to the nearest one it does.
        """
        values = self.values()
        for c in self.controls:
            if c["type"] == "range" and values[c["name"]] not in c["options"]:
                values[c["name"]] = min(c["options"], key=lambda option: abs(option - values[c["name"]]))
        first = self.scene(**values)
        data = pack(self.states(), self.controls, self.drag)
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
