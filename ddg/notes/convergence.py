"""Chapter 7, convergence: how far a polygon is from a smooth curve (lecture §3.6).

The lecture's postscript measures the distance between a polygon ``Gamma`` and a smooth curve
``gamma`` with tangents included,
``d(Gamma, gamma) = integral of |Gamma(s) - gamma(s)| + |T_Gamma(s) - gamma'(s)| ds``, both
curves parametrized proportionally to arc length from matching starting points.
:func:`distance_to_circle` computes its two parts against the clockwise unit circle,
:func:`largest_distance` the pointwise distance that does not see tangents, and
:func:`worst_angle` the hypothesis of part 2 of the book's ``thm-weak-convergence``.
"""

import numpy as np


def largest_distance(polygon):
    """The largest distance from ``polygon`` (its vertices and 31 points inside every edge) to the unit circle.

    >>> import ddg
    >>> round(float(largest_distance(ddg.regular_polygon(4))), 6)   # at the middle of an edge
    0.292893
    """
    u = np.linspace(0, 1, 33)[:, None, None]  # points along every edge
    points = polygon.vertices + u * polygon.edges
    return np.abs(np.linalg.norm(points, axis=-1) - 1).max()


def distance_to_circle(polygon, samples_per_edge=16):
    """The position and tangent parts of the lecture's distance ``d`` to the clockwise unit circle.

    Both curves are parametrized proportionally to arc length, ``polygon`` from ``v_0`` and the
    circle ``(cos s, -sin s)`` from ``(1, 0)``, over the circle's length ``2 pi``; the integrals of
    ``|Gamma(s) - gamma(s)|`` and ``|T_Gamma(s) - gamma'(s)|`` over that parameter ``s`` are
    taken by the midpoint rule, ``samples_per_edge`` points on each edge. Returns the two parts
    as floats; ``d`` is their sum.

    A regular polygon is close in both parts; a zigzag stays far in the tangent part, however
    close its vertices come (the chapter's "Pointwise convergence is not enough"):

    >>> import ddg
    >>> position, tangent = distance_to_circle(ddg.regular_polygon(256))
    >>> bool(position < 1e-3 and tangent < 0.05)
    True
    >>> theta = 2 * np.pi * np.arange(256) / 256
    >>> radius = 1 + (-1.0) ** np.arange(256) / 256
    >>> zigzag = ddg.DiscreteCurve(np.c_[radius * np.cos(theta), -radius * np.sin(theta)])
    >>> position, tangent = distance_to_circle(zigzag)
    >>> bool(position < 0.02 and tangent > 1.5)
    True
    """
    ell, m = polygon.edge_lengths, samples_per_edge
    u = (np.arange(m) + 0.5) / m
    points = polygon.vertices[:, None] + u[:, None] * polygon.edges[:, None]
    s = np.cumsum(ell)[:, None] - (1 - u) * ell[:, None]  # along the polygon
    s *= 2 * np.pi / polygon.length  # the matching point of the circle
    circle = np.stack([np.cos(s), -np.sin(s)], axis=-1)
    circle_tangent = np.stack([-np.sin(s), -np.cos(s)], axis=-1)
    ds = (2 * np.pi * ell / (polygon.length * m))[:, None]
    position = np.linalg.norm(points - circle, axis=-1)
    tangent = np.linalg.norm(polygon.tangents[:, None] - circle_tangent, axis=-1)
    return float((position * ds).sum()), float((tangent * ds).sum())


def worst_angle(P, tangent_at, samples=3):
    """The largest angle between an edge of ``P`` and the smooth tangent at the matching points.

    Points are matched by arc length, as in the lecture's distance ``d``: the point a fraction
    ``f`` of the way round ``P`` is matched with the smooth curve's point a fraction ``f`` of
    the way round it, and ``tangent_at(f)`` gives the smooth unit tangent there (``f`` an array,
    the result of shape ``f.shape + (2,)``). Each edge is sampled at ``samples`` points, ends
    included. Part 2 of ``thm-weak-convergence`` asks for a bound ``alpha < pi / 2`` on this
    angle.

    >>> import ddg
    >>> def circle_tangent(f):
    ...     s = 2 * np.pi * f
    ...     return np.stack([-np.sin(s), -np.cos(s)], axis=-1)
    >>> bool(worst_angle(ddg.regular_polygon(256), circle_tangent) <= np.pi / 256 + 1e-9)
    True
    """
    ell = P.edge_lengths
    u = np.linspace(0, 1, samples)
    fraction = (np.cumsum(ell)[:, None] - (1 - u) * ell[:, None]) / P.length
    T = tangent_at(fraction)  # (n, samples, 2)
    cosine = np.einsum("nsk,nk->ns", T, P.tangents)
    return float(np.arccos(np.clip(cosine, -1, 1)).max())
