"""Explorers and animations: ``ddg`` computes every state, a small SVG scene draws it.

>>> from ddg.explore import polygon_explorer, inflation_explorer, vertex_explorer
>>> polygon_explorer()        # doctest: +ELLIPSIS
<ddg.explore.PolygonExplorer object at ...>

In a notebook the last line of a cell shows it: n, the curve and the formula, and the error against
the smooth curvature. ``inflation_explorer()`` gives eps, the shape and the inflation, the formula
against the measured area; ``vertex_explorer()`` lets one drag a vertex while psi_i, every k_i and
the gradient of length respond.

One explorer, two places:

* in a notebook with a running kernel the call shows live controls (ipywidgets): every change is
  computed by ``ddg`` at once, for any value;
* in the built book the same output shows a version that needs no kernel: the states a reader can
  reach (a grid of control values) were computed by ``ddg`` when the book was built and are
  embedded in the page (as gzip-compressed JSON), and the book's player script
  (``book/_assets/ddg-player.js``) only looks them up and draws them. Printed, or without
  JavaScript, the page shows the first state.

A state is a :class:`ddg.scene.Scene`: panels of lines, dots, arrows and text in data coordinates,
plus a line of numbers and a text alternative that says what the picture shows; ``ddg.scene``
also holds what turns controls and scenes into widgets and pages. The chapters' animations
(:func:`inflation_animation`, :func:`flow_animation`) are at the end of this module.
"""

import html

import numpy as np

from . import smooth
from ._extras import missing
from .curve import CURVATURES, INFLATIONS, DiscreteCurve
from .polygons import regular_polygon
from .scene import COLORS, RAMP, Animation, Explorer, Scene, svg

__all__ = ["COLORS", "RAMP", "Animation", "Explorer", "Scene", "svg", "polygon_explorer", "inflation_explorer",
           "vertex_explorer", "inflation_animation", "flow_animation", "inflation_pieces", "measured_region"]


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
            for offset, (kind, color) in enumerate(zip(CURVATURES, (COLORS["blue"], COLORS["orange"], COLORS["green"]), strict=True)):
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


def polygon_explorer(n=12, shape="ellipse", kind="angle"):
    """Controls for ``n``, the curve (``ddg.explore.SHAPES``) and the formula (``ddg.CURVATURES``)."""
    return PolygonExplorer(n, shape, kind)


def inflation_explorer(eps=0.3, shape="non-convex star", method="minkowski"):
    """Controls for ``eps``, the shape (``ddg.explore.POLYGONS``) and the inflation (``ddg.INFLATIONS``)."""
    return InflationExplorer(eps, shape, method)


def vertex_explorer(dx=0.0, dy=0.0):
    """Move one vertex of a regular hexagon: drag it, or use the controls."""
    return VertexExplorer(dx, dy)


# ------------------------------------------------------------------ the chapters' animations

FLOW_COLORS = dict(zip(CURVATURES, (COLORS["blue"], COLORS["orange"], COLORS["green"]), strict=True))
"""The colour of each flow (by its curvature) in the chapters' figures and animations."""

FLOW_WIDTHS = dict(zip(CURVATURES, (5.0, 3.0, 1.25), strict=True))
"""The stroke width of each flow in :func:`flow_animation`, in pixels: the flows are drawn widest first,
so that where they coincide each shows as a band around the next (blue, orange, then green)."""


def inflation_pieces(curve, eps):
    """The pieces of the two inflations of a clockwise convex polygon by ``eps`` (lecture §3.4).

    Returns ``(rectangles, sectors, kites)``: a rectangle (4 points) on each edge, and at each
    corner the disk sector (centre, start and end angle in degrees, clockwise from ``N_{i-1/2}``)
    and the kite (``v_i``, the two moved edge ends and the point where the moved edges meet).
    """
    v, N, psi = curve.vertices, curve.normals, curve.turning_angles
    N_prev, v_next = np.roll(N, 1, axis=0), np.roll(v, -1, axis=0)
    rectangles = [np.array([v[i], v_next[i], v_next[i] + eps * N[i], v[i] + eps * N[i]]) for i in range(len(v))]
    corner = v + eps * (N_prev + N) / (1 + np.einsum("ij,ij->i", N_prev, N))[:, None]  # 1 + cos psi
    kites = [np.array([v[i], v[i] + eps * N_prev[i], corner[i], v[i] + eps * N[i]]) for i in range(len(v))]
    start = np.degrees(np.arctan2(N_prev[:, 1], N_prev[:, 0]))
    sectors = [(v[i], start[i] - np.degrees(psi[i]), start[i]) for i in range(len(v))]
    return rectangles, sectors, kites


def _sector(centre, eps, start, end, steps=12):
    """A disk sector as a polygon: its centre, then its arc (angles in degrees)."""
    angle = np.radians(np.linspace(start, end, steps))
    return np.vstack([centre, centre + eps * np.c_[np.cos(angle), np.sin(angle)]])


def inflation_animation(curve, epsilons, start=0, name="the pentagon"):
    """Both inflations of a clockwise convex polygon, one frame per ``eps``: the rectangles on the
    edges, the sectors or kites at the corners, the boundary ``ddg`` computes, and the formula's
    area next to the area of the region measured by shapely. ``frame_areas`` holds
    ``(method, eps, formula, measured)`` for every frame and method."""
    names = {"minkowski": "Minkowski sum", "offset": "offset with kites"}
    colors = {"minkowski": COLORS["orange"], "offset": COLORS["green"]}
    (x0, y0), (x1, y1) = curve.vertices.min(axis=0) - 1.1 * max(epsilons), curve.vertices.max(axis=0) + max(epsilons)
    records, frames = [], []
    for eps in epsilons:
        scene = Scene([{"box": (x0, y0, x1, y1), "px": (250, round(250 * (y1 - y0) / (x1 - x0))), "title": title}
                       for title in names.values()])
        rectangles, sectors, kites = inflation_pieces(curve, eps)
        numbers = []
        for panel, method in enumerate(INFLATIONS):
            grey, blue, color = COLORS["grey"], COLORS["blue"], colors[method]
            scene.line(panel, curve.vertices, grey, 1, True, grey)
            for rectangle in rectangles:
                scene.line(panel, rectangle, blue, 0.5, True, blue, opacity=0.35)
            corners = kites if method == "offset" else [_sector(c, eps, a, b) for c, a, b in sectors]
            for piece in corners:
                scene.line(panel, piece, color, 0.5, True, color, opacity=0.7)
            boundary = curve.inflate(eps, method).vertices
            scene.line(panel, boundary[:: max(1, len(boundary) // 150)], closed=True)  # 150 points are plenty
            scene.line(panel, curve.vertices, closed=True)
            formula = curve.inflated_area(eps, method)
            measured = measured_region(curve, eps, method).area
            records.append((method, eps, formula, measured))
            numbers.append(f"{names[method]}: formula {formula:.4f}, measured {measured:.4f}")
        scene.summary = f"ε = {eps:.2f}. " + "; ".join(numbers)
        scene.alt = (f"{name.capitalize()} inflated by ε = {eps:.2f} in two ways: rectangles on the edges (blue) and, "
                     "at the corners, disk sectors (left, orange) or kites (right, green). " + "; ".join(numbers) + ".")
        frames.append(scene)
    animation = Animation(frames, "ε", np.round(epsilons, 3), title="The two inflations", start=start)
    animation.frame_areas = records
    return animation


def flow_animation(runs, frames=16):
    """Snapshots of curve-shortening flows, one panel per curve with every flow drawn over its start.

    ``runs`` maps a curve's name to ``{kind: FlowRun}`` (see ``ddg.flow.flow``, run with at least
    ``frames`` snapshots); frame ``j`` shows snapshot ``j`` of every run. Each flow has its colour
    (:data:`FLOW_COLORS`) and width (:data:`FLOW_WIDTHS`), and the widest is drawn first, so that
    flows that coincide stay visible as nested bands.
    """
    boxes = []
    for by_kind in runs.values():
        first = next(iter(by_kind.values())).snapshots[0][1].vertices
        (x0, y0), (x1, y1) = first.min(axis=0), first.max(axis=0)
        pad = 0.08 * max(x1 - x0, y1 - y0)
        box = (x0 - pad, y0 - pad, x1 + pad, y1 + pad)
        boxes.append({"box": box, "px": (140, round(140 * (box[3] - box[1]) / (box[2] - box[0]))),
                      "margin": (6, 6, 26, 6)})  # no axes
    scenes = []
    for frame in range(frames):
        scene = Scene(boxes)
        for panel, (name, by_kind) in enumerate(runs.items()):
            scene.line(panel, next(iter(by_kind.values())).snapshots[0][1].vertices, COLORS["grey"], 1, True)
            for kind, run in sorted(by_kind.items(), key=lambda item: -FLOW_WIDTHS[item[0]]):  # widest first
                t, curve = run.snapshots[min(frame, len(run.snapshots) - 1)]
                scene.line(panel, curve.vertices, FLOW_COLORS[kind], FLOW_WIDTHS[kind], True)
            scene.text(panel, 70, -10, f"{name}, t = {t:.2f}", "middle", 13, space="px")
        kinds = sorted(next(iter(runs.values())), key=lambda kind: -FLOW_WIDTHS[kind])
        names = {COLORS["blue"]: "blue", COLORS["orange"]: "orange", COLORS["green"]: "green"}
        lines = [f"{k} flow in {names[FLOW_COLORS[k]]} ({FLOW_WIDTHS[k]:g} px)" for k in kinds]
        scene.summary = ", ".join(lines) + ", drawn in that order, widest first; the starting curve in grey."
        scene.alt = (f"Frame {frame + 1} of {frames}: " + ", ".join(runs) + " shrinking under the flows, drawn on top "
                     "of each other over their starting curves, the widest line first: where the flows coincide, "
                     "the narrower lines run inside the wider ones.")
        scenes.append(scene)
    return Animation(scenes, "snapshot", range(1, frames + 1), title="Curve-shortening flow")
