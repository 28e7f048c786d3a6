"""Chapter 1, smooth plane curves: a varied curve, the C-shape, and the figures past the reach.

The chapter checks the lecture's three theorems on smooth curves (lecture §2): the gradient of
length (Theorem 2.2, the book's ``thm-gradient-of-length``) with :func:`varied`, and the
inflation theorem (Theorem 2.3, ``thm-inflation``) up to the reach and beyond it, with
:func:`c_shape` and the two drawings :func:`draw_parallels` and :func:`draw_c`.
"""

import numpy as np

from .. import smooth
from ..curve import DiscreteCurve
from . import needs

PARALLELS = ((0.3, "C0"), (-0.3, "C2"), (-0.8, "C3"))
"""The parallel curves of the chapter's ellipse: ``(eps, colour)``, outside, inside, past the reach."""


def plus(f, g, h):
    """The function ``t -> f(t) + h g(t)``, for plane-curve callables ``t -> (x, y)``.

    >>> f, g = (lambda t: (t, 2 * t)), (lambda t: (1.0, -1.0))
    >>> [float(x) for x in plus(f, g, 0.5)(3.0)]
    [3.5, 5.5]
    """
    return lambda t: tuple(np.add(a, h * np.asarray(b)) for a, b in zip(f(t), g(t), strict=True))


def varied(curve, delta, h):
    """The curve ``gamma + h delta`` of the gradient of length (lecture Theorem 2.2).

    ``curve`` is a :class:`ddg.smooth.SmoothCurve`, ``delta`` the variation as three callables
    ``(delta, delta', delta'')``; the result is a ``SmoothCurve`` again, whose length the chapter
    differentiates in ``h`` (its derivative at 0 is ``<kappa N, delta>``).

    A clockwise unit circle moved along its own outward normal ``delta = gamma`` is the circle of
    radius ``1 + h``:

    >>> circle = smooth.circle(1.0)
    >>> radial = (circle.gamma, circle.dgamma, circle.ddgamma)
    >>> round(float(varied(circle, radial, 0.5).length / np.pi), 9)
    3.0
    """
    d, dd, ddd = delta
    return smooth.parametric(plus(curve.gamma, d, h), plus(curve.dgamma, dd, h), plus(curve.ddgamma, ddd, h))


def c_shape(alpha, m=2000):
    """The C-shape of "When the two ends meet": a simple closed curve made of circular arcs.

    The annulus ``1 < r < 2`` without the angles ``(-alpha, alpha)``, closed by two half-disks of
    radius 1/2; its boundary traversed clockwise, as a :class:`~ddg.DiscreteCurve` of four arcs
    of ``m - 1`` edges each. Its curvature is 1/2 on the outer arc, 2 on the caps and -1 on the
    inner arc; the caps are ``3 sin(alpha) - 1`` apart, so the curve is simple for
    ``sin(alpha) > 1/3`` (``alpha`` above about 19.5 degrees) and crosses itself below. With
    ``theta = 2 pi - 2 alpha`` it encloses ``1.5 theta + pi / 4`` and has length ``3 theta + pi``:

    >>> alpha = np.radians(25)
    >>> C = c_shape(alpha)
    >>> C.turning_number, len(C)
    (1, 7996)
    >>> theta = 2 * np.pi - 2 * alpha
    >>> bool(np.isclose(C.signed_area, 1.5 * theta + np.pi / 4, rtol=1e-5))
    True
    """

    def arc(centre, radius, start, stop):
        a = np.linspace(start, stop, m)[:-1]
        return centre + radius * np.c_[np.cos(a), np.sin(a)]

    top = 1.5 * np.array([np.cos(alpha), np.sin(alpha)])  # a cap's centre
    bottom = top * [1, -1]
    outer = arc(0, 2, 2 * np.pi - alpha, alpha)  # clockwise
    inner = arc(0, 1, alpha, 2 * np.pi - alpha)  # counter-clockwise
    caps = (arc(top, 0.5, alpha, alpha - np.pi), arc(bottom, 0.5, np.pi - alpha, -alpha))
    return DiscreteCurve(np.vstack([outer, caps[0], inner, caps[1]]))


def draw_parallels(ax, position, normal, eroded, offsets=PARALLELS):
    """Draw a curve (black), its parallel curves ``gamma + eps N`` and, shaded, an eroded region.

    ``position`` and ``normal`` are ``gamma`` and ``N`` at sample points (arrays ``(m, 2)``);
    ``offsets`` the ``(eps, colour)`` of each parallel curve, labelled by its signed ``eps``;
    ``eroded`` a shapely polygon, the points deeper than the largest erosion, shaded in the last
    colour. This is the chapter's figure of the inflation theorem past the reach (lecture Theorem
    2.3): where ``1 + eps kappa`` changes sign the parallel curve grows a swallowtail.

    >>> import matplotlib.pyplot as plt, shapely
    >>> t = np.linspace(0, 2 * np.pi, 100)
    >>> ellipse = smooth.ellipse(2.0, 1.0)
    >>> core = shapely.Polygon(ellipse.position(t)).buffer(-0.8)
    >>> fig, ax = plt.subplots()
    >>> draw_parallels(ax, ellipse.position(t), ellipse.normal(t), core)
    >>> [line.get_label() for line in ax.lines[1:]]
    ['+0.3', '−0.3', '−0.8']
    >>> plt.close(fig)
    """
    ax.fill(*np.asarray(eroded.exterior.coords).T, color=offsets[-1][1], alpha=0.2)
    ax.plot(*position.T, "k", lw=2)
    for eps, color in offsets:
        label = f"{eps:+}".replace("-", "−")
        ax.plot(*(position + eps * normal).T, color=color, lw=1, label=label)
    ax.set_aspect("equal")


def draw_c(ax, C, inflated, overlap, parallel):
    """Draw the C-shape inflated past its reach: the region, the overlap of its ends, ``gamma + eps N``.

    ``C`` is the curve (:func:`c_shape`), ``inflated`` and ``overlap`` shapely polygons (the
    points within ``eps`` of it, and where its two inflated halves overlap), ``parallel`` the
    vertices of the parallel curve ``gamma + eps N`` (dashed, closed). The region is smaller than
    the inflation theorem says by exactly the overlap, although ``1 + eps kappa > 0`` everywhere.

    >>> import matplotlib.pyplot as plt, shapely
    >>> C = c_shape(np.radians(25), m=50)
    >>> region = shapely.Polygon(C.vertices).buffer(0.2)
    >>> fig, ax = plt.subplots()
    >>> draw_c(ax, C, region, region.buffer(-0.5), C.vertices + 0.2 * C.bisector_normals)
    >>> [line.get_label() for line in ax.lines]
    ['the C', 'γ + εN']
    >>> plt.close(fig)
    """
    from ..plot import plot_curve

    plot_polygon = needs("shapely.plotting").plot_polygon
    style = dict(ax=ax, add_points=False, edgecolor="none")
    plot_polygon(inflated, facecolor="C0", alpha=0.3, label="within ε", **style)
    plot_polygon(overlap, facecolor="C3", alpha=0.9, label="overlap", **style)
    plot_curve(C, ax, vertices=False, color="k", lw=1.2, label="the C")
    closed = np.vstack([parallel, parallel[:1]])
    ax.plot(*closed.T, "--", color="C0", lw=1, label="γ + εN")
    ax.set_aspect("equal")
