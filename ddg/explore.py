"""Live explorers: sliders over ``ddg``, for a running notebook.

>>> from ddg.explore import polygon_explorer, inflation_explorer, vertex_explorer
>>> polygon_explorer()        # n, the curve and the formula; the error against the smooth curvature
>>> inflation_explorer()      # eps, the shape and the inflation; the formula against the measured area
>>> vertex_explorer()         # move one vertex; psi_i, every k_i and the gradient of length respond

Each function returns an ipywidgets box; its ``.explorer`` attribute is the object behind it, whose
``refresh()`` recomputes and redraws (what a slider move costs, and what ``make bench`` times).
A built book shows the state saved when it was built. Moving a slider there changes nothing,
because no Python runs behind the page.

Redrawing is kept fast by blitting: axes, ticks and labels depend only on the chosen shape, so they
are drawn once per shape; a slider move redraws just the artists that change.
"""

import io

import numpy as np

from . import smooth
from ._extras import missing

try:
    import ipywidgets as widgets
    import shapely
    from matplotlib import ticker
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.collections import LineCollection
    from matplotlib.figure import Figure
    from matplotlib.patches import Polygon as PolygonPatch
    from PIL import Image
except ImportError as error:
    raise missing("explore", error) from error

from .curve import CURVATURES, INFLATIONS, DiscreteCurve, regular_polygon

SHAPES = {
    "circle": smooth.circle(1.0),
    "ellipse": smooth.ellipse(2.0, 1.0),
    "non-convex blob": smooth.polar(lambda t: 1 + 0.3 * np.cos(3 * t), lambda t: -0.9 * np.sin(3 * t),
                                    lambda t: -2.7 * np.cos(3 * t), name="blob r = 1 + 0.3 cos 3t"),
}
"""Smooth closed curves (clockwise) for the polygon explorer."""


def _star(points=5, inner=0.5):
    angle = np.arange(2 * points) * np.pi / points
    radius = np.where(np.arange(2 * points) % 2 == 0, 1.0, inner)
    return DiscreteCurve(np.stack([radius * np.cos(angle), -radius * np.sin(angle)], axis=1))


POLYGONS = {
    "convex pentagon": DiscreteCurve([[0.0, 0.0], [0.3, 1.5], [1.8, 2.0], [3.0, 1.0], [2.4, -0.4]]),
    "non-convex star": _star(),
}
"""Closed clockwise polygons for the inflation explorer."""


class _Explorer:
    """Common plumbing: controls, a figure rendered to PNG by blitting, a summary line.

    A subclass creates its figure in ``background(key)`` (everything that depends only on ``key``,
    for example the shape) and lists the artists that change in ``self.moving``; ``update(...)``
    sets their data and ``self.summary``, and returns the key.
    """

    def __init__(self, controls, figsize):
        self.controls = controls
        self.figsize = figsize
        self.summary = ""
        self._key = self._background = None

    def _build(self, key):
        """A new figure for ``key``: its fixed parts, and the artists that move (``self.moving``)."""
        self.fig = Figure(figsize=self.figsize, dpi=72)  # no pyplot: never shown twice
        self.canvas = FigureCanvasAgg(self.fig)
        self.moving = []
        self.background(key)
        for artist in self.moving:
            artist.set_animated(True)  # left out of the full draw, drawn on top of the background
        self._key, self._background = key, None

    def png(self):
        """The current picture as PNG bytes: the cached background, the moving artists on top."""
        if self._background is None:
            self.canvas.draw()
            self._background = self.canvas.copy_from_bbox(self.fig.bbox)
        self.canvas.restore_region(self._background)
        for artist in self.moving:
            self.fig.draw_artist(artist)
        buffer = io.BytesIO()
        Image.fromarray(np.asarray(self.canvas.buffer_rgba())).save(buffer, format="png", compress_level=1)
        return buffer.getvalue()

    def refresh(self):
        """Recompute with the controls' current values and redraw: what one slider move costs."""
        values = {name: control.value for name, control in self.controls.items()}
        key = self.key(**values)
        if key != self._key:
            self._build(key)
        self.update(**values)
        return self.png()

    def widget(self):
        image = widgets.Image(value=self.refresh(), format="png")
        summary = widgets.HTML(self.summary)

        def changed(_):
            image.value = self.refresh()
            summary.value = self.summary

        for control in self.controls.values():
            control.observe(changed, names="value")
        box = widgets.VBox([widgets.HBox(list(self.controls.values())), summary, image])
        box.explorer = self
        return box


class PolygonExplorer(_Explorer):
    """Sample a smooth curve with ``n`` vertices; colour the polygon by a discrete curvature."""

    def __init__(self, n=12, shape="ellipse", kind="angle"):
        super().__init__({
            "n": widgets.IntSlider(value=n, min=3, max=1000, description="n", continuous_update=False),
            "shape": widgets.Dropdown(options=list(SHAPES), value=shape, description="curve"),
            "kind": widgets.Dropdown(options=list(CURVATURES), value=kind, description="formula"),
        }, figsize=(10, 4))

    def key(self, n, shape, kind):
        return shape

    def background(self, shape):
        curve = SHAPES[shape]
        ax_curve, ax_error = self.fig.subplots(1, 2)
        self.fig.subplots_adjust(left=0.05, right=0.97, bottom=0.13, top=0.9, wspace=0.25)
        tt = np.linspace(curve.t0, curve.t1, 400)
        points = curve.position(tt)
        ax_curve.plot(*points.T, color="0.6", lw=1, label="smooth curve")
        pad = 0.15 * np.ptp(points, axis=0).max()
        ax_curve.set_xlim(points[:, 0].min() - pad, points[:, 0].max() + pad)
        ax_curve.set_ylim(points[:, 1].min() - pad, points[:, 1].max() + pad)
        ax_curve.set_aspect("equal")
        kappa = curve.curvature(tt)
        spread = max(np.ptp(kappa), 0.5 * np.abs(kappa).max())
        self.segments = LineCollection([], cmap="coolwarm", linewidths=3)
        self.segments.set_clim(kappa.min() - 0.3 * spread, kappa.max() + 0.3 * spread)  # fixed: colours compare
        ax_curve.add_collection(self.segments)
        self.fig.colorbar(self.segments, ax=ax_curve, label="$k_i$ on each vertex's dual edge")
        ax_curve.legend(loc="upper right", fontsize=8)
        ax_curve.set_title(curve.name)
        self.error_line, = ax_error.semilogy([0.5], [1.0], ".-", ms=3)
        # plain "1e-05" tick labels: fixed limits, so the axis is drawn once per curve
        ax_error.set_xlim(0, 1)
        ax_error.set_ylim(1e-12, 10)
        ax_error.yaxis.set_major_formatter(ticker.FuncFormatter(lambda y, _: f"{y:.0e}"))
        ax_error.yaxis.set_minor_formatter(ticker.NullFormatter())
        ax_error.set_xlabel("parameter $t_i / 2\\pi$")
        ax_error.set_ylabel("$|k_i - \\kappa(t_i)|$")
        ax_error.set_title("error against the smooth curvature")
        self.moving = [self.segments, self.error_line]

    def update(self, n, shape, kind):
        curve = SHAPES[shape]
        t = curve.sample_parameters(n)
        polygon = DiscreteCurve(curve.position(t))
        k, kappa = polygon.curvature(kind), curve.curvature(t)
        v = polygon.vertices
        mid_prev = v - np.roll(polygon.edges, 1, axis=0) / 2  # dual edge: midpoint, vertex, midpoint
        mid_next = v + polygon.edges / 2
        self.segments.set_segments(np.stack([mid_prev, v, mid_next], axis=1))
        self.segments.set_array(k)
        error = np.abs(k - kappa)
        self.error_line.set_data(t / (2 * np.pi), np.maximum(error, 1e-12))
        self.summary = (f"{curve.name}, n = {n}, {kind} formula: max |k<sub>i</sub> &minus; &kappa;(t<sub>i</sub>)| = "
                        f"{error.max():.3e}; &lang;k, 1&rang; / 2&pi; = {polygon.total_curvature(kind) / (2 * np.pi):.6f}")
        return error.max()


class InflationExplorer(_Explorer):
    """Inflate a polygon by ``eps``; compare the formula's area with the region's measured area."""

    def __init__(self, eps=0.3, shape="non-convex star", method="minkowski"):
        super().__init__({
            "eps": widgets.FloatSlider(value=eps, min=0.0, max=1.0, step=0.01, description="ε", continuous_update=False),
            "shape": widgets.Dropdown(options=list(POLYGONS), value=shape, description="shape"),
            "method": widgets.Dropdown(options=list(INFLATIONS), value=method, description="inflation"),
        }, figsize=(6, 5))

    def key(self, eps, shape, method):
        return shape

    @staticmethod
    def measured_region(polygon, eps, method):
        """The inflated region, measured independently by shapely (round join, or mitre join)."""
        region = shapely.Polygon(polygon.vertices)
        if method == "minkowski":
            return region.buffer(eps, quad_segs=256)
        return region.buffer(eps, join_style="mitre", mitre_limit=1e6)

    def background(self, shape):
        polygon = POLYGONS[shape]
        ax = self.fig.subplots()
        self.fig.subplots_adjust(left=0.1, right=0.97, bottom=0.22, top=0.93)
        largest = self.measured_region(polygon, 1.0, "minkowski").bounds
        ax.set_xlim(largest[0] - 0.1, largest[2] + 0.1)
        ax.set_ylim(largest[1] - 0.1, largest[3] + 0.1)
        ax.set_aspect("equal")
        self.region = PolygonPatch(np.zeros((3, 2)), color="C1", alpha=0.45, label="inflated region (measured)")
        ax.add_patch(self.region)
        polygon_patch = PolygonPatch(polygon.vertices, color="0.6", label="polygon")
        ax.add_patch(polygon_patch)
        self.boundary, = ax.plot([], [], "k--", lw=0.8, label="$\\Gamma + \\varepsilon N$ (ddg.inflate)")
        ax.legend(loc="upper left", fontsize=8, bbox_to_anchor=(0, -0.08), ncol=2)
        ax.set_title(shape)
        self.moving = [self.region, polygon_patch, self.boundary]  # drawn in this order

    def update(self, eps, shape, method):
        polygon = POLYGONS[shape]
        region = self.measured_region(polygon, eps, method)
        formula = polygon.inflated_area(eps, method)
        self.region.set_xy(np.asarray(region.exterior.coords))
        self.region.set_color("C1" if method == "minkowski" else "C2")
        boundary = polygon.inflate(eps, method).vertices if eps > 0 else polygon.vertices
        self.boundary.set_data(*np.vstack([boundary, boundary[:1]]).T)
        self.summary = (f"{method}, &epsilon; = {eps:.2f}: formula A<sub>0</sub> + &epsilon;L + &epsilon;&sup2;/2 &lang;k, 1&rang; "
                        f"= {formula:.6f}; measured {region.area:.6f}; difference {region.area - formula:+.2e}")
        return formula, region.area


class VertexExplorer(_Explorer):
    """Move vertex ``j`` of a hexagon; watch its turning angle, curvatures and the gradient of length."""

    def __init__(self, dx=0.0, dy=0.0, j=2):
        super().__init__({
            "dx": widgets.FloatSlider(value=dx, min=-1.5, max=1.5, step=0.02, description=f"move v{j}: x", continuous_update=False),
            "dy": widgets.FloatSlider(value=dy, min=-1.5, max=1.5, step=0.02, description="y", continuous_update=False),
        }, figsize=(10, 4.2))
        self.base = regular_polygon(6, 1.0).vertices.copy()
        self.j = j

    def key(self, dx, dy):
        return "hexagon"

    def background(self, key):
        ax, ax_bars = self.fig.subplots(1, 2, width_ratios=[1.2, 1])
        self.fig.subplots_adjust(left=0.05, right=0.98, bottom=0.1, top=0.9, wspace=0.2)
        ax.set_aspect("equal")
        ax.set_xlim(-2.6, 2.6)
        ax.set_ylim(-2.6, 2.6)
        self.line, = ax.plot([], [], "ko-", ms=4)
        self.marker, = ax.plot([], [], "o", color="C3", ms=9)
        self.arrows = ax.quiver(*self.base.T, *np.zeros_like(self.base).T, color="C3", angles="xy",
                                scale_units="xy", scale=1, width=0.006, label="$0.3\\,(\\nabla L)_i$")
        ax.legend(loc="lower left", fontsize=8)
        ax.set_title(f"move $v_{self.j}$: the polygon and its gradient of length")
        width = 0.25
        self.bars = {kind: ax_bars.bar(np.arange(3) + offset, np.zeros(3), width, label=kind)
                     for offset, kind in zip((-width, 0, width), CURVATURES)}
        self.norms = ax_bars.bar(np.arange(3), np.zeros(3), 3 * width, fill=False, edgecolor="k", label="$|\\nabla L|$")
        ax_bars.axhline(0, color="k", lw=0.8)
        neighbours = np.array([self.j - 1, self.j, self.j + 1]) % len(self.base)
        ax_bars.set_xticks(np.arange(3), [f"$v_{i}$" for i in neighbours])
        ax_bars.set_ylim(-6, 6)
        ax_bars.set_ylabel("$k_i$ (clipped to ±6)")
        ax_bars.legend(fontsize=8, loc="lower right")
        ax_bars.set_title(f"$k_i$ at $v_{self.j}$ and its neighbours")
        self.moving = [self.line, self.marker, self.arrows,
                       *(bar for container in (*self.bars.values(), self.norms) for bar in container)]

    def update(self, dx, dy):
        v = self.base.copy()
        v[self.j] += (dx, dy)
        j = self.j
        try:
            polygon = DiscreteCurve(v)
            tangent_ok = True
            polygon.curvature("tangent")
        except ValueError as problem:  # v_j moved onto a neighbour, or the curve turns straight back
            if "tangent" not in str(problem):
                self.summary = f"<b>not a discrete curve:</b> {problem}"
                return None
            tangent_ok = False
        grad = polygon.length_gradient()
        self.line.set_data(*np.vstack([v, v[:1]]).T)
        self.marker.set_data([v[j, 0]], [v[j, 1]])
        self.arrows.set_offsets(v)
        self.arrows.set_UVC(*(0.3 * grad).T)
        neighbours = np.array([j - 1, j, j + 1]) % len(v)
        ks = {kind: polygon.curvature(kind) for kind in CURVATURES if kind != "tangent" or tangent_ok}
        for kind, container in self.bars.items():
            heights = ks[kind][neighbours] if kind in ks else np.zeros(3)
            for bar, height in zip(container, np.clip(heights, -6, 6)):
                bar.set_height(height)
        for bar, height in zip(self.norms, np.linalg.norm(grad[neighbours], axis=1)):
            bar.set_height(min(height, 6))
        self.summary = (f"at v<sub>{j}</sub>: &psi; = {polygon.turning_angles[j]:+.4f} "
                        f"({np.degrees(polygon.turning_angles[j]):+.1f}&deg;), "
                        + ", ".join(f"k<sub>{kind}</sub> = {ks[kind][j]:+.4f}" for kind in ks)
                        + ("" if tangent_ok else ", k<sub>tangent</sub> diverges (&psi; = &pi;)")
                        + f", |&nabla;L| = {np.linalg.norm(grad[j]):.4f}; L = {polygon.length:.4f}")
        return ks


def polygon_explorer(n=12, shape="ellipse", kind="angle"):
    """Sliders for ``n``, the curve (``ddg.explore.SHAPES``) and the formula (``ddg.CURVATURES``)."""
    return PolygonExplorer(n, shape, kind).widget()


def inflation_explorer(eps=0.3, shape="non-convex star", method="minkowski"):
    """Sliders for ``eps``, the shape (``ddg.explore.POLYGONS``) and the inflation (``ddg.INFLATIONS``)."""
    return InflationExplorer(eps, shape, method).widget()


def vertex_explorer(dx=0.0, dy=0.0):
    """Two sliders move one vertex of a regular hexagon."""
    return VertexExplorer(dx, dy).widget()
