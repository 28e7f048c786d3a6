"""Polygons to start from: the regular ``n``-gon.

>>> regular_polygon(4).vertices.round(12) + 0.0
array([[ 1.,  0.],
       [ 0., -1.],
       [-1.,  0.],
       [ 0.,  1.]])
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from . import _arguments as check
from .curve import DiscreteCurve
from .errors import InputError, OutOfRangeError


def regular_polygon(n: int, radius: float = 1.0, clockwise: bool = True,
                    center: npt.ArrayLike = (0.0, 0.0)) -> DiscreteCurve:
    """The regular ``n``-gon with its vertices on the circle of the given radius.

    ``v_k = center + radius (cos(2 pi k / n), -sin(2 pi k / n))`` when clockwise. Its turning angles
    are all ``2 pi / n`` (clockwise) and its edges have length ``2 r sin(pi / n)``.

    >>> hexagon = regular_polygon(6, radius=2.0)
    >>> hexagon.curvature("sine")                      # 1 / r, exactly so (eq. 3)
    array([0.5, 0.5, 0.5, 0.5, 0.5, 0.5])
    """
    try:
        valid = int(n) == n and n >= 3 and not isinstance(n, (bool, np.bool_))
    except (TypeError, ValueError, OverflowError):  # NaN, inf, text, arrays
        valid = False
    if not valid:
        raise InputError(f"a regular polygon needs an integer n >= 3, got {n!r}")
    if int(n) > np.iinfo(np.intp).max // 16:
        raise OutOfRangeError(f"n = {n} vertices cannot be stored: the array would need {16 * int(n):.3g} bytes")
    radius = check.real(radius, "radius", 0.0, strict=True)
    clockwise = check.flag(clockwise, "clockwise")
    c = check.point(center, "center")
    theta = (2 * np.pi / int(n)) * np.arange(int(n))
    vertices = np.stack([np.cos(theta), (-1.0 if clockwise else 1.0) * np.sin(theta)], axis=1)
    with np.errstate(over="ignore"):
        vertices = radius * vertices + c
    check.require_finite(vertices, lambda i: f"vertex {i} of a regular polygon of radius {radius:g} about {c} is "
                         "beyond the largest float", OutOfRangeError)
    return DiscreteCurve(vertices)
