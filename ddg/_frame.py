"""What a curve-shortening run (``ddg.flow.flow``) is set to do, and the frame it is computed in."""

from dataclasses import dataclass

import numpy as np

from . import _arguments as check
from .curve import CURVATURES, DiscreteCurve
from .errors import DegenerateCurveError, InputError

METHODS = ("explicit", "semi-implicit")


@dataclass(frozen=True)
class Settings:
    """A run's settings, checked (see :func:`flow` for their meaning)."""

    kind: str
    method: str
    t_end: float
    dt: float | None
    safety: float
    lifetime_fraction: float
    snapshots: int
    record_every: float | None
    stop_length_fraction: float
    stop_edge_fraction: float
    remesh_every: int | None
    max_steps: int
    max_seconds: float
    progress: bool

    def __post_init__(self):
        check.choose(self.kind, CURVATURES, "curvature kind")
        check.choose(self.method, METHODS, "method")
        for name in ("t_end", "dt", "safety", "lifetime_fraction", "record_every", "max_seconds"):
            if getattr(self, name) is not None or name not in ("dt", "record_every"):
                check.real(getattr(self, name), name, 0.0, strict=True)
        for name in ("stop_length_fraction", "stop_edge_fraction"):
            if check.real(getattr(self, name), name, 0.0) >= 1:
                raise InputError(f"{name} must be a fraction in [0, 1), got {getattr(self, name)!r}")
        check.count(self.snapshots, "snapshots", 0)
        check.count(self.max_steps, "max_steps", 1)
        if self.remesh_every is not None:
            check.count(self.remesh_every, "remesh_every", 1)
        check.flag(self.progress, "progress")


class Frame:
    """Coordinates relative to the curve: ``local = (v - origin) / scale``, time ``t / scale**2``.

    The flow commutes with translations and with scaling (``v -> s v``, ``t -> s**2 t``), so it is
    run near the origin at a size of about 1, where every move, however small against the curve's
    position in the plane, is kept, and no area or step under- or overflows. ``scale`` is a power of
    two, so scaling back is exact.
    """

    def __init__(self, curve):
        self.origin = curve.vertices[0].copy()
        self.exponent = int(np.frexp(curve.length)[1])
        self.scale = float(np.ldexp(1.0, self.exponent))

    def local(self, curve):
        return DiscreteCurve(np.ldexp(curve.vertices - self.origin, -self.exponent))

    def curve(self, local):
        return DiscreteCurve(np.ldexp(local.vertices, self.exponent) + self.origin)

    def snapshots(self, kept):
        """``(snapshots, origin)``: the kept curves where they are, or, where one cannot be placed there
        (far from the origin a shrunken curve's vertices round onto each other), all of them
        relative to ``origin``, the first vertex of the starting curve."""
        try:
            return [(self.time(t), self.curve(c)) for t, c in kept], np.zeros(2)
        except DegenerateCurveError:
            return [(self.time(t), DiscreteCurve(np.ldexp(c.vertices, self.exponent))) for t, c in kept], self.origin

    def time(self, local_time):
        with np.errstate(over="ignore"):  # inf: a time beyond the floats, which flow() refuses
            return float(np.ldexp(local_time, 2 * self.exponent))

    def local_time(self, t):
        with np.errstate(over="ignore"):  # inf: beyond the floats, which flow() refuses
            return float(np.ldexp(t, -2 * self.exponent))
