"""Chapter 6, Table 1 computed: the random polygons it tests on, and the helpers of its checks.

The lecture's Table 1 (lecture §3.5) says which property each discrete curvature keeps. The
chapter computes every cell on three families of random polygons (:func:`random_polygon`,
:func:`random_convex_polygon`, :func:`random_star_polygon`), checks the hypothesis of the offset
theorem (:func:`hypothesis_holds`), the signed reading of an inflation (:func:`signed_boundary`)
and how steeply each formula's flow descends length (:func:`rates`), and draws the corner fills
(:func:`draw_fillings`).
"""

import numpy as np

from ..curve import CURVATURES, DiscreteCurve
from . import needs


def random_polygon(rng, n=None):
    """A random closed polygon, usually self-intersecting, with no turn near a reversal.

    ``n`` vertices (by default 3 to 24, drawn from ``rng``) uniform in the square
    ``[-1, 1]^2``, drawn again until every ``|psi_i| < pi - 0.05`` and every edge is longer
    than 0.02, so that the symmetries of Table 1 can be tested without the one exception, a turn
    straight back (``psi_i = pi``), and without rounding dominating the curvature.

    >>> P = random_polygon(np.random.default_rng(0), 7)
    >>> len(P), bool(np.abs(P.turning_angles).max() < np.pi - 0.05)
    (7, True)
    """
    while True:
        c = DiscreteCurve(rng.uniform(-1, 1, (n or rng.integers(3, 25), 2)))
        if np.abs(c.turning_angles).max() < np.pi - 0.05 and c.edge_lengths.min() > 0.02:
            return c


def random_convex_polygon(rng, n):
    """A random convex clockwise polygon with ``n`` vertices: sorted random angles on an ellipse.

    The vertices lie on the ellipse with semi-axes 1.5 and 1, at angles ``t`` whose gaps are
    uniform in ``[1, 3]`` (scaled to add up to ``2 pi``), taken clockwise: every ``psi_i > 0``.

    >>> P = random_convex_polygon(np.random.default_rng(0), 6)
    >>> P.turning_number, bool(P.turning_angles.min() > 0)
    (1, True)
    """
    gaps = rng.uniform(1, 3, n)
    t = 2 * np.pi * np.cumsum(gaps) / gaps.sum()
    return DiscreteCurve(np.stack([1.5 * np.cos(t), -np.sin(t)], axis=1))


def random_star_polygon(rng, n):
    """A random simple clockwise polygon with a reflex corner (``psi_i < 0``): a "star".

    ``n`` vertices at sorted random angles around the origin and random distances in
    ``[0.5, 1.5]``, taken clockwise, drawn again until the polygon is simple (shapely) and has a
    reflex corner.

    >>> P = random_star_polygon(np.random.default_rng(0), 8)
    >>> P.turning_number, bool(P.turning_angles.min() < 0), bool(P.signed_area > 0)
    (1, True, True)
    """
    shapely = needs("shapely")
    while True:
        t = np.sort(rng.uniform(0, 2 * np.pi, n))
        r = rng.uniform(0.5, 1.5, n)
        c = DiscreteCurve(np.stack([r * np.cos(t), -r * np.sin(t)], 1))
        if shapely.Polygon(c.vertices).is_valid and c.turning_angles.min() < 0:
            return c


def hypothesis_holds(c, eps):
    """Whether the hypothesis of the offset theorem (``thm-offset``) holds for ``c`` at ``eps``.

    Every edge moved out by ``eps`` keeps its direction, and the moved edges meet no edge but
    their two neighbours: the offset polygon ``c.inflate(eps, "offset")`` has as many edges,
    each pointing the same way as before, and is simple (shapely). On a convex polygon it holds
    for every ``eps``; at a reflex corner it fails once the moved edges overrun each other.

    >>> square = DiscreteCurve([[0, 0], [0, 2], [2, 2], [2, 0]])
    >>> notched = DiscreteCurve([[0, 0], [0, 2], [0.9, 2], [0.9, 1], [1.1, 1], [1.1, 2], [2, 2], [2, 0]])
    >>> hypothesis_holds(square, 5.0), hypothesis_holds(notched, 0.05), hypothesis_holds(notched, 0.15)
    (True, True, False)
    """
    moved = c.inflate(eps, "offset")
    same = len(moved) == len(c) and np.all(np.einsum("ij,ij->i", moved.edges, c.edges) > 0)
    return bool(same and needs("shapely").Polygon(moved.vertices).is_valid)


def signed_boundary(c, eps, curvature):
    """The boundary of the apex fill of ``c`` by ``eps``, in order, as a closed curve.

    At each vertex the moved edge ends at ``v_i + eps N_{i-1/2}``, goes to the apex
    ``p_i = v_i + h_i N_i`` on the bisector (``N_i`` the bisector normal, with
    ``h_i = eps A_i k_i / (2 sin(psi_i / 2))``, the fill of ``thm-fills``) and on to
    ``v_i + eps N_{i+1/2}``: three vertices per corner, swept backwards at a reflex corner.
    Signed areas add, so on every polygon whose turning angles are not 0, convex or not,
    simple or not, its signed area is ``A_0 + eps L + eps^2 / 2 <k, 1>`` exactly for the
    curvature ``k = curvature(c)``: the "signed boundary" reading of Table 1's inflation column.

    >>> import ddg
    >>> hexagon = ddg.regular_polygon(6)
    >>> sine = signed_boundary(hexagon, 0.1, lambda c: c.curvature("sine"))
    >>> len(sine), bool(np.isclose(sine.signed_area, hexagon.inflated_area(0.1, "minkowski")))
    (18, False)
    >>> formula = hexagon.signed_area + 0.1 * hexagon.length + 0.1**2 / 2 * hexagon.total_curvature("sine")
    >>> bool(np.isclose(sine.signed_area, formula, rtol=1e-12))
    True
    """
    v, N, psi = c.vertices, c.normals, c.turning_angles
    h = eps * c.dual_lengths * curvature(c) / (2 * np.sin(psi / 2))
    apex = v + h[:, None] * c.bisector_normals
    corners = np.stack([v + eps * np.roll(N, 1, axis=0), apex, v + eps * N], 1)
    return DiscreteCurve(corners.reshape(-1, 2))


def rates(P):
    """How fast each formula's flow shortens ``P`` per unit of speed, and the steepest rate.

    For each curvature ``k`` in :data:`ddg.CURVATURES` the velocity ``V = -k N`` (``N`` the
    bisector normal) changes the length at the rate ``<grad L, V> / |V|``; returns
    ``({kind: rate}, -|grad L|)``, the second the rate of steepest descent. The sine formula's
    flow is gradient descent (``grad L = k N`` with the sine formula, lecture §3.3): its rate is
    the steepest; the others' equal it only where all the non-zero ``|psi_i|`` are equal.

    >>> import ddg
    >>> rate, steepest = rates(DiscreteCurve([[0, 0], [0, 1], [3, 2], [2, 0]]))
    >>> bool(np.isclose(rate["sine"], steepest)), bool(rate["angle"] > steepest)
    (True, True)
    >>> rate, steepest = rates(ddg.regular_polygon(5))
    >>> bool(np.allclose(list(rate.values()), steepest))
    True
    """
    grad = P.length_gradient()
    result = {}
    for kind in CURVATURES:
        V = -P.curvature(kind)[:, None] * P.bisector_normals
        result[kind] = P.inner(grad, V) / np.sqrt(P.inner(V, V))
    return result, -np.sqrt(P.inner(grad, grad))


def draw_fillings(ax, c, fillings):
    """Draw the polygon ``c`` (grey) and the outlines of its inflated regions, with their areas.

    ``fillings`` holds ``(name, region, colour, line style)`` for each region (shapely
    polygons: the round join, the sine formula's apex fill, the bevel), each labelled
    ``"name: area ..."``. The chapter's figure of ``thm-fills``.

    >>> import matplotlib.pyplot as plt, shapely
    >>> triangle = DiscreteCurve([[-3.0, 0.0], [0.0, 0.0], [-0.5, -0.75**0.5]])
    >>> region = shapely.Polygon(triangle.vertices)
    >>> fillings = [("round", region.buffer(0.5), "C1", "-"), ("bevel", region.buffer(0.5, join_style="bevel"), "C0", "--")]
    >>> fig, ax = plt.subplots()
    >>> draw_fillings(ax, triangle, fillings)
    >>> [line.get_label() for line in ax.lines[:2]]
    ['round: area 5.406', 'bevel: area 4.894']
    >>> plt.close(fig)
    """
    from ..plot import plot_curve

    ax.fill(*c.vertices.T, color="0.85")
    for name, geometry, color, style in fillings:
        outline = np.asarray(geometry.exterior.coords).T
        label = f"{name}: area {geometry.area:.3f}"
        ax.plot(*outline, style, color=color, lw=2, label=label)
    plot_curve(c, ax, color="k")
    ax.set_xlabel("$x$")
    ax.set_ylabel("$y$")
