"""The lecture's two inflations of a closed curve (§3.4), behind ``DiscreteCurve.inflated_area``
and ``DiscreteCurve.inflate``, whose docstrings say what they compute.

>>> import ddg
>>> ddg.DiscreteCurve([[0, 0], [0, 1], [1, 1], [1, 0]]).inflated_area(0.5, "offset")   # 1 + 2 + 1
4.0
"""

from __future__ import annotations

import numpy as np

from . import _arguments as check
from . import _numerics as nx
from .curve import INFLATIONS, DiscreteCurve
from .errors import DegenerateCurveError, InputError, OpenCurveError, OutOfRangeError

MAX_ARC_STEP = 0.01
"""Largest angle (radians) between two samples of a Minkowski arc in :func:`inflate`."""

MAX_ARC_POINTS = 1_000_000
"""Most points :func:`inflate` places on all the Minkowski arcs together."""


def _checked(curve: DiscreteCurve, eps: float, method: str) -> float:
    """Check the arguments of an inflation; ``eps`` as a float."""
    check.choose(method, INFLATIONS, "inflation method")
    if not curve.closed:
        raise OpenCurveError("inflation is defined for closed curves only; this curve is open")
    eps = check.real(eps, "eps")
    if eps < 0:
        raise InputError(f"eps must be >= 0, got {eps!r}: erosion is not supported (the lecture's formulas hold "
                         "only until an edge collapses); inflating the reversed curve moves the edges the other way")
    if eps > 0 and curve.signed_area < 0:
        raise InputError("the curve is counter-clockwise (its signed area is negative): its normals point inward, "
                         "so inflating it would erode it, which the formulas describe only until an edge "
                         "collapses; reverse it (vertices[::-1]) to inflate it outward")
    return eps


def _no_reversal(curve: DiscreteCurve) -> None:
    if len(curve.reversals):
        raise DegenerateCurveError(f"no offset corner at vertex {curve.reversals[0]}: the curve turns straight back "
                                   "there (psi = pi), so eps^2 tan(psi/2) is infinite")


def inflated_area(curve: DiscreteCurve, eps: float, method: str = "minkowski") -> float:
    """Signed area of the curve inflated by ``eps >= 0`` along its normals (lecture §3.4).

    * ``"minkowski"``: disk sectors of angle ``psi_i`` at the vertices:
      ``A_0 + eps L + eps^2 / 2 * sum_i psi_i``.
    * ``"offset"``: edges moved parallel by ``eps``, kites at the corners:
      ``A_0 + eps L + eps^2 * sum_i tan(psi_i / 2)``.

    These are the lecture's formulas: the area of the inflated region for a clockwise convex
    polygon, and the signed area of the boundary :meth:`inflate` returns for any curve that is
    not counter-clockwise. A counter-clockwise curve (negative signed area) and ``eps < 0``
    raise :class:`~ddg.errors.InputError`, an area beyond the largest float
    :class:`~ddg.errors.OutOfRangeError`.

    >>> import ddg
    >>> inflated_area(ddg.regular_polygon(4), 0.0) == ddg.regular_polygon(4).signed_area   # eps = 0: A_0
    True
    >>> round(inflated_area(ddg.regular_polygon(4), 1.0, "offset"), 12)          # 2 + 4 sqrt(2) + 4
    11.656854249492
    """
    eps = _checked(curve, eps, method)
    if eps == 0.0:
        return curve.signed_area
    if method == "minkowski":
        corners = 0.5 * float(curve.turning_angles.sum())
    else:  # sum_i tan(psi_i/2), not via k^tangent, which overflows first on a tiny near-reversal
        _no_reversal(curve)
        with np.errstate(over="ignore", invalid="ignore"):
            corners = float(np.sum(curve.tan_half_psi))
    with np.errstate(over="ignore", invalid="ignore"):
        area = curve.signed_area + eps * curve.length + eps * eps * corners
    if not np.isfinite(area):
        raise OutOfRangeError("the inflated area is larger than the largest float (about 1.8e308); scale the curve "
                              "or eps down")
    return area


def inflate(curve: DiscreteCurve, eps: float, method: str = "minkowski") -> DiscreteCurve:
    """The boundary of the inflated region as a new closed :class:`DiscreteCurve`.

    Every edge moves by ``eps >= 0`` along its normal ``N_{i+1/2}``. At vertex ``v_i`` the two
    moved edges are joined by

    * ``"minkowski"``: the arc of radius ``eps`` about ``v_i`` that turns clockwise by
      ``psi_i``, cut into equal chords of angle at most ``h = max(MAX_ARC_STEP,
      sum |psi_i| / MAX_ARC_POINTS)`` . Each chord misses a sliver of its
      sector, so the boundary's signed area falls short of :func:`inflated_area` by at most
      ``eps^2 h^2 sum |psi_i| / 12`` (a fraction ``h^2 / 6`` of the sectors, below 2e-5);
    * ``"offset"``: the corner where the two moved edges meet (the kite's outer vertex).

    ``eps = 0`` returns the curve itself. Points that coincide are kept once. On a non-convex
    curve this boundary sweeps back over itself near the reflex vertices.

    >>> import ddg
    >>> len(inflate(ddg.regular_polygon(4), 1.0, "offset")), len(inflate(ddg.regular_polygon(4), 1.0))
    (4, 636)
    """
    eps = _checked(curve, eps, method)
    if eps == 0.0:
        return curve
    v, psi = curve.vertices, curve.turning_angles
    N_prev, T_prev = nx.previous(curve.normals), nx.previous(curve.tangents)
    if method == "offset":  # the moved edges meet at v + eps (N_{i-1/2} + tan(psi_i/2) T_{i-1/2})
        _no_reversal(curve)
        with np.errstate(over="ignore", invalid="ignore"):
            corners = v + eps * (N_prev + curve.tan_half_psi[:, None] * T_prev)
        return _boundary(corners, np.arange(len(v)), eps)
    h = max(MAX_ARC_STEP, float(np.abs(psi).sum()) / MAX_ARC_POINTS)
    steps = np.ceil(np.abs(psi) / h).astype(int)  # chords per arc
    vertex = np.repeat(np.arange(len(v)), steps + 1)
    k = np.arange(len(vertex)) - np.repeat(np.cumsum(steps + 1) - (steps + 1), steps + 1)  # 0 ... steps_i
    angle = np.arctan2(N_prev[:, 1], N_prev[:, 0])[vertex] - psi[vertex] * k / np.maximum(steps[vertex], 1)
    with np.errstate(over="ignore", invalid="ignore"):
        return _boundary(v[vertex] + eps * np.stack([np.cos(angle), np.sin(angle)], axis=1), vertex, eps)


def _boundary(points, vertex, eps):
    """The inflated boundary through ``points``, each made at the curve's vertex ``vertex[j]``.

    Repeated points (an arc of zero angle, a step below rounding) are dropped; errors name the
    vertex of the input curve.
    """
    check.require_finite(points, lambda j: f"inflating by eps = {eps:g} overflows at vertex {vertex[j]}", OutOfRangeError)
    keep = (points != nx.previous(points)).any(axis=1)
    if keep.sum() < 3:
        raise DegenerateCurveError(f"the boundary inflated by eps = {eps:g} collapses to fewer than 3 points")
    return DiscreteCurve(points[keep])
