"""Smooth reference curves (lecture §2), to compare discrete curvature against.

A :class:`SmoothCurve` is a regular parametric curve ``gamma(t)``, ``t`` in ``[t0, t1]``, given by
callables for ``gamma``, ``gamma'`` and ``gamma''``. It knows its unit tangent ``T``, normal
``N = J T`` and signed curvature ``kappa = -T' . N`` (positive on a clockwise circle) exactly,
measures arc length by quadrature, and samples itself into a :class:`~ddg.DiscreteCurve`.
"""

from __future__ import annotations

import numbers
from collections.abc import Callable
from functools import cached_property
from typing import Any

import numpy as np
import numpy.typing as npt

from . import _arguments as check
from .curve import Array, DiscreteCurve
from ._quadrature import RTOL, adaptive, gauss  # noqa: F401 (RTOL: the accuracy the docstrings cite)
from .errors import InputError, OutOfRangeError

Function = Callable[[Any], Any]
"""A plane-curve callable: ``t -> (x, y)``, vectorized over arrays of ``t``."""

def _points(f, t):
    """Evaluate a plane-curve callable at ``t`` (scalar or array) as an array of shape ``t.shape + (2,)``.

    ``t`` must be real numbers (not text, NaN or infinity): an ``InputError`` names the first that is not.
    """
    t = np.asarray(t) if isinstance(t, (numbers.Real, np.ndarray, list, tuple)) else np.asarray(t, dtype=object)
    if t.dtype.kind not in "iuf" or not np.isfinite(t).all():
        bad = t.flat[0] if t.dtype.kind not in "iuf" else t[~np.isfinite(t)].flat[0]
        raise InputError(f"t must be finite real numbers, got {bad!r}")
    t = t.astype(float)
    with np.errstate(over="ignore", invalid="ignore"):
        x, y = f(t)
    return np.stack(np.broadcast_arrays(x, y, t)[:2], axis=-1)


class SmoothCurve:
    """A regular plane curve ``gamma: [t0, t1] -> R^2`` with known first and second derivatives.

    Parameters
    ----------
    position, velocity, acceleration : callables
        ``t -> (x, y)`` for ``gamma(t)``, ``gamma'(t)`` and ``gamma''(t)``, vectorized over arrays
        of ``t``.
    t0, t1 : float
        The parameter interval.
    closed : bool
        Whether ``gamma(t1) = gamma(t0)`` (to every order); sampling then omits the end point.
    name : str
        Used in plots and messages.

    The callables are kept as ``gamma``, ``dgamma`` and ``ddgamma``, so a new curve can be built
    from an old one (moved, reflected, varied).

    >>> ccw = SmoothCurve(lambda t: (np.cos(t), np.sin(t)), lambda t: (-np.sin(t), np.cos(t)),
    ...                   lambda t: (-np.cos(t), -np.sin(t)), name="counter-clockwise circle")
    >>> float(ccw.curvature(0.0)), round(ccw.length / np.pi, 12)
    (-1.0, 2.0)
    """

    def __init__(self, position: Function, velocity: Function, acceleration: Function, t0: float = 0.0,
                 t1: float = 2 * np.pi, closed: bool = True, name: str = "curve") -> None:
        t0, t1 = check.real(t0, "t0"), check.real(t1, "t1")
        if not t1 > t0:
            raise InputError(f"need t1 > t0, got t0={t0!r}, t1={t1!r}")
        closed = check.flag(closed, "closed")
        self.gamma, self.dgamma, self.ddgamma = position, velocity, acceleration  # the callables given
        self.t0, self.t1, self.closed, self.name = float(t0), float(t1), bool(closed), name

    def __repr__(self) -> str:
        return f"SmoothCurve({self.name!r}, t in [{self.t0:.6g}, {self.t1:.6g}], length={self.length:.6g})"

    def _parameters(self, t):
        """``t`` as an array of parameters in ``[t0, t1]``, or a ``ValueError`` saying which is not."""
        t = np.asarray(t, dtype=float)
        outside = ~((self.t0 <= t) & (t <= self.t1))
        if outside.any():
            raise InputError(f"t must lie in [{self.t0:.6g}, {self.t1:.6g}], the curve's parameter interval; got "
                             f"{t[outside].flat[0]!r}")
        return t

    def moved(self, matrix: npt.ArrayLike = ((1.0, 0.0), (0.0, 1.0)), shift: npt.ArrayLike = (0.0, 0.0),
              name: str | None = None) -> SmoothCurve:
        """The curve ``x -> M x + b``: moved, turned, mirrored or scaled; its derivatives are ``M gamma'``
        and ``M gamma''``. (A mirror reverses the sense of turning, so it flips the curvature's sign.)

        >>> float(circle(1.0).moved([[1, 0], [0, -1]]).curvature(0.0))      # mirrored: counter-clockwise
        -1.0
        """
        M = np.asarray(matrix, dtype=float)
        if M.shape != (2, 2) or not np.isfinite(M).all():
            raise InputError(f"matrix must be a finite 2 x 2 matrix, got {matrix!r}")
        b = check.point(shift, "shift")

        def mapped(f, offset):
            def g(t):
                x, y = f(t)
                return M[0, 0] * x + M[0, 1] * y + offset[0], M[1, 0] * x + M[1, 1] * y + offset[1]
            return g

        return SmoothCurve(mapped(self.gamma, b), mapped(self.dgamma, (0.0, 0.0)), mapped(self.ddgamma, (0.0, 0.0)),
                           self.t0, self.t1, self.closed, name or self.name)

    def reversed(self, name: str | None = None) -> SmoothCurve:
        """The same curve traversed backwards, ``t -> t0 + t1 - t``: its curvature changes sign.

        >>> float(circle(2.0).reversed().curvature(1.0))
        -0.5
        """
        t0, t1 = self.t0, self.t1

        def backwards(f, sign):
            def g(t):
                x, y = f(t0 + t1 - np.asarray(t, dtype=float))
                return sign * np.asarray(x), sign * np.asarray(y)
            return g

        return SmoothCurve(backwards(self.gamma, 1.0), backwards(self.dgamma, -1.0), backwards(self.ddgamma, 1.0),
                           t0, t1, self.closed, name or f"{self.name}, reversed")

    def position(self, t: npt.ArrayLike) -> Array:
        """``gamma(t)``, shape ``t.shape + (2,)``.

        >>> circle(2.0).position([0.0, np.pi / 2]).round(12) + 0.0         # clockwise: down first
        array([[ 2.,  0.],
               [ 0., -2.]])
        """
        return _points(self.gamma, t)

    def speed(self, t: npt.ArrayLike) -> Array:
        """``|gamma'(t)|`` (without under- or overflow at any scale).

        >>> float(ellipse(2.0, 1.0).speed(0.0))
        1.0
        """
        d = _points(self.dgamma, t)
        return np.hypot(d[..., 0], d[..., 1])

    def tangent(self, t: npt.ArrayLike) -> Array:
        """Unit tangent ``T = gamma' / |gamma'|``.

        >>> circle(3.0).tangent(0.0) + 0.0
        array([ 0., -1.])
        """
        d = _points(self.dgamma, t)
        return d / np.hypot(d[..., 0], d[..., 1])[..., None]

    def normal(self, t: npt.ArrayLike) -> Array:
        """Normal ``N = J T`` (``J`` rotates by +90 degrees): outward on a clockwise circle.

        >>> circle(3.0).normal(0.0) + 0.0                       # + 0.0: no -0.
        array([1., 0.])
        """
        T = self.tangent(t)
        return np.stack([-T[..., 1], T[..., 0]], axis=-1)

    def curvature(self, t: npt.ArrayLike) -> Array:
        """Signed curvature ``kappa = -T' . N = -(gamma' x gamma'') / |gamma'|^3`` (lecture §2).

        Positive where the curve turns clockwise: ``+1/r`` on a clockwise circle.

        >>> ellipse(2.0, 1.0).curvature([0.0, np.pi / 2])               # a b / b^3 and a b / a^3
        array([2.  , 0.25])
        """
        d, dd = _points(self.dgamma, t), _points(self.ddgamma, t)
        speed = np.hypot(d[..., 0], d[..., 1])
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            T = d / speed[..., None]  # the same formula, arranged not to under- or overflow at any scale
            kappa = -((T[..., 0] * dd[..., 1] - T[..., 1] * dd[..., 0]) / speed) / speed
        if not np.isfinite(kappa).all():
            raise OutOfRangeError(f"the curvature of {self.name} at t = {np.asarray(t).flat[0]:.6g} is beyond the "
                                  "largest float, or undefined (|gamma'| = 0)")
        return kappa

    # ---------------------------------------------------------------------- arc length

    @cached_property
    def _grid(self):
        """Cell boundaries in ``t`` (adaptive, see ``ddg._quadrature.adaptive``) and the arc length up to each."""
        a, b, integrals = adaptive(self.speed, self.t0, self.t1)
        return np.append(a, b[-1]), np.concatenate([[0.0], np.cumsum(integrals)])

    def _integrate_speed(self, a, b):
        return gauss(self.speed, a, b)[0]

    def arc_length(self, t: npt.ArrayLike) -> Array:
        """``s(t) = int_{t0}^{t} |gamma'|``: arc length from the start to parameter ``t`` in ``[t0, t1]``.

        >>> round(float(circle(2.0).arc_length(np.pi)) / np.pi, 12)
        2.0
        """
        t = self._parameters(t)
        grid, s = self._grid
        cell = np.clip(np.searchsorted(grid, t, side="right") - 1, 0, len(grid) - 2)
        return s[cell] + self._integrate_speed(grid[cell], t)

    @cached_property
    def length(self) -> float:
        """Total arc length ``L``, by adaptive Gauss quadrature to a relative accuracy of about ``RTOL``;
        a length beyond the largest float raises :class:`~ddg.errors.OutOfRangeError`.

        >>> round(circle(1.0).length / np.pi, 12)
        2.0
        """
        with np.errstate(over="ignore", invalid="ignore"):
            length = float(self._grid[1][-1])
        if not np.isfinite(length):
            raise OutOfRangeError(f"the length of {self.name} is beyond the largest float (about 1.8e308): scale "
                                  "it down")
        return length

    def parameter_at(self, s: npt.ArrayLike) -> Array:
        """The parameter ``t`` with ``arc_length(t) = s``, for ``s`` in ``[0, length]`` (inverse of :meth:`arc_length`).

        >>> round(float(circle(2.0).parameter_at(np.pi)), 12)                 # half way round
        1.570796326795
        """
        s = np.asarray(s, dtype=float)
        outside = ~((0 <= s) & (s <= self.length))
        if outside.any():
            raise InputError(f"s must lie in [0, {self.length:.6g}], the curve's length; got {s[outside].flat[0]!r}")
        grid, S = self._grid
        t = np.interp(s, S, grid)
        for _ in range(4):  # Newton's method: ds/dt = |gamma'|
            t = np.clip(t - (self.arc_length(t) - s) / self.speed(t), self.t0, self.t1)
        return t

    def total_curvature(self) -> float:
        """``int kappa ds``: ``2 pi`` times the turning number for a closed curve (Theorem 2.1).

        By adaptive Gauss quadrature of ``kappa |gamma'|`` to about ``RTOL`` of ``int |kappa| ds``,
        also where the curvature is concentrated, as at the tips of a thin ellipse. Only the rounding
        of ``t`` limits it: a tip ``w`` wide in ``t`` costs about ``1e-16 / w`` (``ellipse(1, 1e-6)``:
        ``4e-11`` relative).

        >>> round(ellipse(3.0, 1.0).total_curvature() / np.pi, 12)
        2.0
        """
        _, _, integrals = adaptive(lambda t: self.curvature(t) * self.speed(t), self.t0, self.t1)
        return float(integrals.sum())

    # ------------------------------------------------------------------------ sampling

    def sample_parameters(self, n: int, uniform: str = "parameter") -> Array:
        """``n`` parameter values, equally spaced in ``"parameter"`` or in ``"arclength"``.

        >>> circle().sample_parameters(4) / np.pi
        array([0. , 0.5, 1. , 1.5])
        """
        if uniform not in ("parameter", "arclength"):
            raise InputError(f"uniform must be 'parameter' or 'arclength', got {uniform!r}")
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < (3 if self.closed else 2):
            raise InputError(f"n must be an integer >= {3 if self.closed else 2}, got {n!r}")
        count = n if self.closed else n - 1
        if uniform == "parameter":
            return self.t0 + (self.t1 - self.t0) * np.arange(n) / count
        return self.parameter_at(self.length * np.arange(n) / count)

    def sample(self, n: int, uniform: str = "parameter") -> DiscreteCurve:
        """A :class:`~ddg.DiscreteCurve` with ``n`` vertices on the curve.

        ``uniform="parameter"`` spaces them equally in ``t``; ``"arclength"`` equally in arc
        length. A closed curve leaves out the end point (it repeats the start).

        >>> circle(2.0).sample(6).curvature("sine").round(12)            # 1 / r, exactly so (eq. 3)
        array([0.5, 0.5, 0.5, 0.5, 0.5, 0.5])
        """
        return DiscreteCurve(self.position(self.sample_parameters(n, uniform)), closed=self.closed)


def circle(radius: float = 1.0, center: npt.ArrayLike = (0.0, 0.0), clockwise: bool = True) -> SmoothCurve:
    """The circle ``center + r (cos t, -sin t)`` (clockwise) or ``(cos t, sin t)``: curvature ``+-1/r``.

    >>> circle(2.0).curvature(0.3), circle(2.0, clockwise=False).curvature(0.3)
    (np.float64(0.5), np.float64(-0.5))
    """
    radius = check.real(radius, "radius", 0.0, strict=True)
    return ellipse(radius, radius, center, clockwise, name=f"circle r={radius:g}")


def ellipse(a: float = 2.0, b: float = 1.0, center: npt.ArrayLike = (0.0, 0.0), clockwise: bool = True,
            name: str | None = None) -> SmoothCurve:
    """The ellipse ``center + (a cos t, -+ b sin t)``, ``t`` in ``[0, 2 pi)``.

    Clockwise, its curvature is ``kappa(t) = a b / (a^2 sin^2 t + b^2 cos^2 t)^(3/2)``. Semi-axes
    whose perimeter (at most ``2 pi max(a, b)``) would pass the largest float are refused.

    >>> round(ellipse(2.0, 2.0).length / np.pi, 12)
    4.0
    """
    a, b = check.real(a, "a", 0.0, strict=True), check.real(b, "b", 0.0, strict=True)
    if max(a, b) > np.finfo(float).max / 8:
        raise OutOfRangeError(f"an ellipse with semi-axes {a:g} and {b:g} has a length beyond the largest float "
                              "(about 1.8e308): scale it down")
    cx, cy = check.point(center, "center")
    s = -1.0 if check.flag(clockwise, "clockwise") else 1.0
    return SmoothCurve(
        lambda t: (cx + a * np.cos(t), cy + s * b * np.sin(t)),
        lambda t: (-a * np.sin(t), s * b * np.cos(t)),
        lambda t: (-a * np.cos(t), -s * b * np.sin(t)),
        name=name or f"ellipse a={a:g}, b={b:g}",
    )


def parametric(position: Function, velocity: Function, acceleration: Function, t0: float = 0.0,
               t1: float = 2 * np.pi, closed: bool = True, name: str = "curve") -> SmoothCurve:
    """Any curve given by callables for ``gamma``, ``gamma'`` and ``gamma''`` (see :class:`SmoothCurve`).

    >>> parabola = parametric(lambda t: (t, t * t), lambda t: (1 + 0 * t, 2 * t), lambda t: (0 * t, 2 + 0 * t),
    ...                       t0=-1.0, t1=1.0, closed=False, name="y = x^2")
    >>> float(parabola.curvature(0.0))                          # turning counter-clockwise: negative
    -2.0
    """
    return SmoothCurve(position, velocity, acceleration, t0, t1, closed, name)


def from_curvature(kappa: Function, length: float, samples: int = 20001, start: npt.ArrayLike = (0.0, 0.0),
                   direction: float = 0.0) -> tuple[Array, Array]:
    """Rebuild a curve from its curvature: Property 0 of the lecture (§2) as a computation.

    Property 0 says ``T' = -kappa J T`` and ``gamma' = T``. Writing ``T = (cos theta, sin theta)``
    gives ``T' = theta' J T``, so ``theta' = -kappa``: integrate ``kappa`` once for the direction
    and ``(cos theta, sin theta)`` once more for the position (trapezoidal rule, second order).

    Parameters
    ----------
    kappa : callable
        ``s -> kappa(s)``, vectorized, for arc length ``s`` in ``[0, length]``.
    length : float
        Length of the curve to rebuild.
    start, direction :
        ``gamma(0)`` and the angle of ``T(0)`` (radians, counter-clockwise from the x-axis): the
        two things curvature does not determine.

    Returns
    -------
    s, points : arrays of shape ``(samples,)`` and ``(samples, 2)``

    >>> s, points = from_curvature(lambda s: 1 + 0 * s, 2 * np.pi)     # kappa = 1: a clockwise unit circle
    >>> bool(np.abs(points[-1] - points[0]).max() < 1e-6)
    True
    """
    length = check.real(length, "length", 0.0, strict=True)
    samples = check.count(samples, "samples", 2)
    p0, direction = check.point(start, "start"), check.real(direction, "direction")
    s = np.linspace(0.0, length, samples)
    k = np.broadcast_to(np.asarray(kappa(s), dtype=float), s.shape)
    if not np.isfinite(k).all():
        raise InputError(f"kappa is not finite at s = {s[~np.isfinite(k)][0]:.6g}")
    theta = direction - np.concatenate([[0.0], np.cumsum((k[1:] + k[:-1]) / 2 * np.diff(s))])
    T = np.stack([np.cos(theta), np.sin(theta)], axis=1)
    steps = (T[1:] + T[:-1]) / 2 * np.diff(s)[:, None]
    return s, p0 + np.concatenate([[[0.0, 0.0]], np.cumsum(steps, axis=0)])


def polar(r: Function, dr: Function, ddr: Function, clockwise: bool = True, name: str = "polar curve") -> SmoothCurve:
    """The closed curve ``r(t) (cos t, -+ sin t)``, ``t`` in ``[0, 2 pi)``, from ``r``, ``r'`` and ``r''``.

    With ``clockwise=True`` (default) the curve is traversed clockwise, as the lecture prefers.

    >>> round(float(polar(lambda t: 2 + 0 * t, lambda t: 0 * t, lambda t: 0 * t).curvature(1.0)), 12)
    0.5
    """
    sign = -1.0 if check.flag(clockwise, "clockwise") else 1.0
    c, s = np.cos, np.sin
    return SmoothCurve(
        lambda t: (r(t) * c(t), sign * r(t) * s(t)),
        lambda t: (dr(t) * c(t) - r(t) * s(t), sign * (dr(t) * s(t) + r(t) * c(t))),
        lambda t: (ddr(t) * c(t) - 2 * dr(t) * s(t) - r(t) * c(t),
                   sign * (ddr(t) * s(t) + 2 * dr(t) * c(t) - r(t) * s(t))),
        name=name,
    )


def flower(amplitude: float, petals: int, clockwise: bool = True, name: str | None = None) -> SmoothCurve:
    """The closed curve ``r(t) = 1 + amplitude cos(petals t)`` in polar form: a circle with ``petals``
    bumps, non-convex once ``amplitude`` is large enough (``1 / (1 + petals^2)`` and more).

    >>> bool((flower(0.3, 5).sample(200).curvature() < 0).any())        # 0.3 > 1/26: non-convex
    True
    """
    c, k = check.real(amplitude, "amplitude"), check.count(petals, "petals", 1)
    return polar(lambda t: 1 + c * np.cos(k * t), lambda t: -c * k * np.sin(k * t),
                 lambda t: -c * k * k * np.cos(k * t), clockwise, name or f"r = 1 + {c:g} cos {k}t")
