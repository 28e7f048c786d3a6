"""Chapter 2, discrete curves: the jump of curvature in Chaikin's limit curve.

"What is a polygon a picture of?" refines one quadrilateral by Chaikin's corner cutting, whose
limit is a quadratic B-spline with its knots at the midpoints of the control polygon's edges.
Along each parabolic arc the curvature is smooth; at a knot it jumps, and :func:`knot_curvatures`
gives the two one-sided values.
"""

import numpy as np


def _cross(a, b):
    """``a x b = a_x b_y - a_y b_x``, row by row."""
    return a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]


def knot_curvatures(P):
    """The curvature of Chaikin's limit curve on the two sides of each knot: ``(before, after)``.

    The limit of Chaikin's corner cutting on the closed control polygon ``P`` (``n x 2``) is the
    quadratic B-spline with control points ``P``; its knot ``j`` is the midpoint of the edge
    from ``P[j]`` to ``P[j + 1]``. With the lecture's sign (``kappa = -T' . N``, positive on a
    clockwise curve), the arc that ends at knot ``j`` has there the curvature
    ``|e_before| sin(psi_j) / |e_j|^2`` and the arc that starts there
    ``|e_after| sin(psi_{j+1}) / |e_j|^2``, where ``psi_j`` is the turn at ``P[j]``, ``e_before``
    the edge that ends at ``P[j]`` and ``e_after`` the one that starts at ``P[j + 1]``. They agree
    on every parallelogram, and differ in general: the curvature jumps.

    >>> before, after = knot_curvatures([[0, 0], [0, 1], [1, 1], [1, 0]])  # a clockwise unit square
    >>> before, after
    (array([1., 1., 1., 1.]), array([1., 1., 1., 1.]))
    >>> before, after = knot_curvatures([[0, 0], [0, 1], [2, 1], [3, 0]])  # a trapezoid: two jumps
    >>> before.round(3), after.round(3)
    (array([3.   , 0.25 , 0.707, 0.111]), array([2.   , 0.25 , 1.061, 0.111]))
    """
    P = np.asarray(P, dtype=float)
    before, after = np.roll(P, 1, axis=0), np.roll(P, -1, axis=0)
    e_prev, e, e_next = P - before, after - P, np.roll(after - P, -1, axis=0)
    length3 = np.linalg.norm(e, axis=1) ** 3
    return -_cross(e_prev, e) / length3, -_cross(e, e_next) / length3
