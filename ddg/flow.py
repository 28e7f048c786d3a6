"""Discrete curve-shortening flow: move every vertex by ``-k_i N_i`` (the lecture's sign).

Smooth curve-shortening flow is ``d gamma / dt = -kappa N``: with the lecture's convention
(clockwise positive, ``N`` outward on a clockwise circle) a circle shrinks. Discretely each vertex
moves along its unit vertex normal ``N_i`` (the bisector of the two edge normals, the direction of
the gradient of length) with speed given by one of the three discrete curvatures:

    d v_i / dt = -k_i N_i.

For the sine curvature (eq. 3) this is ``-(grad L)_i = (Lap gamma)_i``: the gradient flow of length
for the lecture's inner product (§3.3), a heat equation for the positions. The angle and tangent
curvatures move the same way at other speeds, ``k_i = g_i k_i^sine`` with
``g = (psi/2) / sin(psi/2)`` or ``1 / cos(psi/2)``.

>>> run = flow(regular_polygon(64), "sine", t_end=0.2, progress=False)
>>> run.stopped, float(run.times[-1]), len(run.snapshots)
('reached t_end', 0.2, 30)
"""

import time
from dataclasses import dataclass, field

import numpy as np

from . import _arguments as check
from . import _numerics as nx
from ._linalg import solve_cyclic_tridiagonal
from .curve import Array, DiscreteCurve
from ._frame import Frame, Settings
from .polygons import regular_polygon  # noqa: F401 (the examples' polygons)
from .errors import DegenerateCurveError, InputError, OpenCurveError, OutOfRangeError

try:  # a progress bar on long runs, when tqdm is installed (it is optional)
    from tqdm.auto import tqdm
except ImportError:
    tqdm = None



@dataclass
class FlowRun:
    """What a run recorded: the first and the last state and the states in between, spaced by the
    curve's life (see :func:`flow`), snapshots for drawing, why it stopped, and its cost.

    The snapshots lie where the curve is, and ``origin`` is ``(0, 0)``; but where a snapshot could
    not be placed there (far from the origin a shrunken curve's vertices round onto each other),
    every snapshot is relative to ``origin``, the first vertex of the starting curve: draw
    ``origin + curve.vertices``, or draw all of them relative to ``origin``.

    >>> run = flow(regular_polygon(32), "angle", 0.1, snapshots=3, progress=False)
    >>> run.kind, run.method, run.stopped, [round(t, 3) for t, curve in run.snapshots]
    ('angle', 'explicit', 'reached t_end', [0.0, 0.05, 0.1])
    """

    kind: str
    method: str
    times: np.ndarray
    lengths: np.ndarray
    areas: np.ndarray
    turning_numbers: np.ndarray
    snapshots: list = field(repr=False)  # (time, DiscreteCurve) pairs, relative to origin
    origin: np.ndarray = field(default_factory=lambda: np.zeros(2))
    stopped: str = ""
    steps: int = 0
    seconds: float = 0.0

    def area_rate(self) -> Array:
        """``dA/dt`` by centred differences of the recorded areas (smooth flow: ``-2 pi n``).

        >>> run = flow(regular_polygon(400), "sine", 0.1, progress=False)
        >>> round(float(run.area_rate().mean()) / np.pi, 2)                  # a circle's: -2 pi
        -2.0
        """
        if len(self.times) < 2:
            raise DegenerateCurveError(f"the area rate needs at least 2 records; this run has {len(self.times)} ({self.stopped})")
        return np.gradient(self.areas, self.times)


def velocity(curve: DiscreteCurve, kind: str) -> Array:
    """``-k_i N_i`` for every vertex: the discrete curve-shortening velocity.

    >>> velocity(regular_polygon(4), "sine")[0].round(12) + 0.0     # towards the centre at speed 1 / r
    array([-1.,  0.])
    """
    return -curve.curvature(kind)[:, None] * curve.bisector_normals


def speed_factor(curve: DiscreteCurve, kind: str) -> Array:
    """``g_i = k_i / k_i^sine``: how much faster than the gradient flow of length each vertex moves.

    >>> speed_factor(regular_polygon(4), "tangent") ** 2            # 1 / cos(psi/2), psi = pi/2
    array([2., 2., 2., 2.])
    """
    half = curve.turning_angles / 2
    if kind == "sine":
        return np.ones(len(curve))
    if kind == "angle":
        return 1 / np.sinc(half / np.pi)  # (psi/2) / sin(psi/2), 1 at psi = 0
    return 1 / np.cos(half)


def _shorter_edges(curve):
    """The shorter of the two edges at each vertex."""
    return np.minimum(curve.edge_lengths, nx.previous(curve.edge_lengths))


def _travel_step(curve, kind):
    """The time in which the fastest vertex, relative to its shorter edge, crosses that edge."""
    with np.errstate(divide="ignore", over="ignore"):  # a straight vertex (k = 0) sets no limit
        return float(np.min(_shorter_edges(curve) / np.abs(curve.curvature(kind))))


def stable_step(curve: DiscreteCurve, kind: str, safety: float = 0.25) -> float:
    """An explicit time step from the shortest edges, safe for forward Euler.

    The sine flow is the heat equation ``dv/dt = Lap v``; the stiffest mode of ``Lap`` decays at a
    rate of at most ``max_i 4 / (h_i A_i)`` (Gershgorin), ``h_i`` the shorter edge at ``v_i``, and
    on most polygons close to that (chapter 9 gives the lower bound). Forward Euler is stable when
    ``dt`` times that rate stays below 2, so ``dt = h A / 2`` at the worst vertex is safe, divided
    by ``g_i`` for the faster flows. A vertex must also not travel farther than a fraction of its
    edges in one step, which matters where ``k`` is huge (near kinks).

    >>> round(stable_step(regular_polygon(4), "sine"), 12)     # 0.25 min(h A / 2, h / k): h = A = sqrt 2, k = 1
    0.25
    """
    safety = check.real(safety, "safety", 0.0, strict=True)
    diffusion = np.min(_shorter_edges(curve) * curve.dual_lengths / (2 * speed_factor(curve, kind)))
    return float(safety * min(diffusion, _travel_step(curve, kind)))


def remaining_lifetime(curve: DiscreteCurve, kind: str) -> float:
    """How long the curve has left under the flow, estimated from the rate of its area (or length).

    Along ``dv_i/dt = -k_i N_i``: ``dA/dt = -sum_i A_i k_i cos(psi_i/2)`` (chain rule; chapter 9 of
    the book), about ``-2 pi`` times the turning number. The estimate is ``A / |dA/dt|``, exact for a
    regular polygon, whose area falls at a constant rate. Where that says nothing (turning number
    0, as for a figure-eight, or an area moving away from 0) it is ``L / |dL/dt|``, with
    ``dL/dt = -sum_i A_i k_i k_i^sine``: twice the lifetime of a circle, and shorter while wiggles
    smooth out.

    >>> round(remaining_lifetime(regular_polygon(10_000), "sine"), 6)     # a unit circle's: r^2 / 2
    0.5
    """
    k, A = curve.curvature(kind), curve.dual_lengths
    area, rate = curve.signed_area, -np.sum(A * k * np.cos(curve.turning_angles / 2))
    if curve.turning_number != 0 and area * rate < 0:
        return float(-area / rate)
    return float(curve.length / np.sum(A * k * curve.curvature("sine")))


def semi_implicit_step(curve: DiscreteCurve, kind: str, dt: float) -> Array:
    """One backward Euler step with the lengths frozen: solve ``(I - dt G Lap) v_new = v``.

    ``(G Lap v)_i = g_i / A_i * ((v_{i+1} - v_i) / |e_{i+1/2}| - (v_i - v_{i-1}) / |e_{i-1/2}|)`` equals
    ``-k_i N_i`` at the current vertices (``curve.laplacian``, with the speeds ``g_i``); treating it
    implicitly removes the ``h^2`` step limit. The system is cyclic tridiagonal and diagonally
    dominant: :func:`~ddg._linalg.solve_cyclic_tridiagonal`.

    >>> square = regular_polygon(4)
    >>> bool(np.abs(semi_implicit_step(square, "sine", 1e-9) - square.vertices).max() < 1e-8)
    True
    """
    w_next, w_prev = 1 / curve.edge_lengths, 1 / nx.previous(curve.edge_lengths)
    s = dt * speed_factor(curve, kind) / curve.dual_lengths
    return solve_cyclic_tridiagonal(-s * w_prev, 1 + s * (w_next + w_prev), -s * w_next, curve.vertices)


def remesh(curve: DiscreteCurve) -> DiscreteCurve:
    """Vertices spread evenly in arc length along the same polyline, as many as before.

    The new vertices lie on the old edges; corners between them are cut, so the length and (for a
    convex curve) the area can only shrink. An open curve keeps its two ends. A curve that turns
    straight back, before or after, raises :class:`~ddg.errors.DegenerateCurveError`.

    >>> remesh(DiscreteCurve([[0, 0], [1, 0], [4, 0]], closed=False)).vertices
    array([[0., 0.],
           [2., 0.],
           [4., 0.]])
    """
    if not isinstance(curve, DiscreteCurve):
        raise InputError(f"curve must be a DiscreteCurve, got {type(curve).__name__}")
    if len(curve.reversals):
        raise DegenerateCurveError(_reversal(curve))
    v = np.vstack([curve.vertices, curve.vertices[:1]]) if curve.closed else curve.vertices
    s = np.concatenate([[0.0], np.cumsum(curve.edge_lengths)])
    n = len(curve)
    target = curve.length * np.arange(n) / (n if curve.closed else n - 1)
    new = DiscreteCurve(np.stack([np.interp(target, s, v[:, 0]), np.interp(target, s, v[:, 1])], axis=1),
                        closed=curve.closed)
    if len(new.reversals):
        raise DegenerateCurveError(f"remeshing gives a curve that turns straight back at vertex {new.reversals[0]}"
                         " (the polyline nearly does there)")
    return new


def _reversal(curve):
    return (f"the curve turns straight back at vertex {curve.reversals[0]} (psi = pi): neither "
            "its turning number nor the tangent curvature is defined there")


# ---------------------------------------------------------------------------------- the run


def flow(curve: DiscreteCurve, kind: str = "sine", t_end: float = 1.0, *, method: str = "explicit",
         dt: float | None = None, safety: float = 0.25, lifetime_fraction: float = 0.02, snapshots: int = 30,
         record_every: float | None = None, stop_length_fraction: float = 0.05, stop_edge_fraction: float = 0.02,
         remesh_every: int | None = None, max_steps: int = 500_000, max_seconds: float = 600.0,
         progress: bool = True) -> FlowRun:
    """Run discrete curve-shortening flow from ``curve`` until ``t_end`` or until it must stop.

    Parameters
    ----------
    curve : DiscreteCurve (closed, not turning straight back anywhere)
    kind : one of ``ddg.CURVATURES``, the curvature that sets the speed.
    t_end : float, the time to stop at (it may lie beyond the curve's life: the run stops first).
    method : ``"explicit"`` (forward Euler, the step from :func:`stable_step` at every step) or
        ``"semi-implicit"`` (:func:`semi_implicit_step`, stable at any step; the step is the one in
        which a vertex moves ``safety`` of its shorter edge).
    dt : float, optional fixed step instead of the automatic one, checked neither for stability nor
        for accuracy (use with care), only kept below half the remaining lifetime.
    safety : float, the fraction of the explicit stability limit (explicit), or of the shorter edge
        a vertex may travel in one step (semi-implicit).
    lifetime_fraction : float
        Accuracy: no automatic step is longer than this fraction of the curve's remaining
        lifetime (:func:`remaining_lifetime`). Both methods are first order: on a regular polygon
        the area comes out too large by ``c * lifetime_fraction`` times the area lost, ``c = 1/4``
        (explicit) or ``3/4`` (semi-implicit): 0.5% or 1.5% at the default.
    snapshots : int, curves kept for drawing, evenly spaced over the run's expected span (the
        shorter of ``t_end`` and the curve's estimated lifetime), and the last state. They lie
        where the curve is, unless it is so far from the origin that a snapshot's vertices would
        round onto each other there: then all of them are relative to ``run.origin``.
    record_every : float, time between records (default: a 400th of that span).
    stop_length_fraction, stop_edge_fraction :
        Stop cleanly, before the polygon degenerates, once its length falls below this fraction of
        the initial length (the curve has nearly vanished), or its shortest edge below this
        fraction of the mean edge.
    remesh_every : int, optional: :func:`remesh` every so many steps (tangential motion that keeps
        vertices from bunching; the sine flow is then no longer exactly the gradient flow).
    max_steps, max_seconds : the run's budget; it stops, saying so, when either is spent.
    progress : bool, show a progress bar when a run takes more than a second (needs ``tqdm``).

    The run is computed in coordinates relative to the curve (its first vertex, at its own scale),
    so a curve far from the origin, or at any scale, flows as it would near the origin at size 1:
    the same run, translated and scaled, to the last bit.

    Returns
    -------
    FlowRun with the recorded times, lengths, areas, turning numbers (the first and the last state
    always among them), snapshots and ``stopped``: ``"reached t_end"``, or why it stopped earlier.

    >>> run = flow(regular_polygon(12, center=(1e15, 1e15)), "sine", 1.0, progress=False)
    >>> run.origin                    # so far away the snapshots are relative to the first vertex
    array([1.e+15, 1.e+15])
    """
    settings = Settings(kind, method, t_end, dt, safety, lifetime_fraction, snapshots, record_every,
                        stop_length_fraction, stop_edge_fraction, remesh_every, max_steps, max_seconds, progress)
    if not isinstance(curve, DiscreteCurve):
        raise InputError(f"curve must be a DiscreteCurve, got {type(curve).__name__}")
    if not curve.closed:
        raise OpenCurveError("curve-shortening flow is defined here for closed curves only; this curve is open")
    if len(curve.reversals):
        raise DegenerateCurveError(_reversal(curve))
    frame = Frame(curve)
    start = frame.local(curve)
    if len(start.reversals):  # a turn a rounding error short of pi, rounded onto it by the move
        raise DegenerateCurveError(_reversal(start))
    end = frame.local_time(float(t_end))
    lifetime = remaining_lifetime(start, kind)
    degenerate = not 0 < lifetime < np.inf  # at the curve's own scale: a collapsed curve
    if not degenerate and not np.finfo(float).tiny < frame.time(lifetime) < np.inf:  # so every step is > 0
        power = np.log10(lifetime) + 2 * frame.exponent * np.log10(2)
        raise OutOfRangeError(f"the curve's lifetime under the flow, about 1e{power:.0f}, is beyond the range of floats "
                              "in which its steps can be told apart: scale the curve (times scale with the square of "
                              "its size)")
    if dt is not None and not degenerate and min(end, lifetime) / frame.local_time(dt) > max_steps:
        needed = min(end, lifetime) / frame.local_time(dt)
        raise OutOfRangeError(f"dt = {dt!r} would take about {needed:.1e} steps to reach t = "
                         f"{frame.time(min(end, lifetime)):.4g} (t_end or the curve's end, whichever comes first), "
                         f"more than max_steps = {max_steps}: take a larger dt, or leave it out for a stable one")
    run = _Run(settings, frame, start, end, end if degenerate else min(end, lifetime))
    if degenerate:
        run.record()
        run.stopped = "stopped at t = 0: the curve is degenerate (its remaining lifetime is 0 to rounding)"
    else:
        run.go()
    return run.result()


class _Run:
    """The state of one run: its step, its stop rule and its record, in local coordinates."""

    def __init__(self, settings, frame, curve, end, span):
        self.settings, self.frame, self.curve, self.end, self.span = settings, frame, curve, end, span
        self.t, self.steps, self.stopped = 0.0, 0, "reached t_end"
        self.length0, self.number = curve.length, curve.turning_number
        every = frame.local_time(settings.record_every) if settings.record_every else span / 400
        self.every, self.next_record, self.records, self.kept = every, 0.0, [], []
        self.next_snapshot = 0  # how many of the snapshot times, span * j / (snapshots - 1), have been kept
        self.dt = None if settings.dt is None else frame.local_time(settings.dt)
        self.seconds = 0.0

    def record(self):
        """Keep the state when it is due (and the snapshots whose times have come)."""
        if self.t >= self.next_record * (1 - 1e-12) or self.t == self.end:
            self.records.append((self.t, self.curve.length, self.curve.signed_area, self.curve.turning_number))
            self.next_record = self.t + self.every
        wanted = self.settings.snapshots
        if wanted > 1 and self.span > 0:
            due = min(wanted, 1 + int(self.t * (1 + 1e-12) / self.span * (wanted - 1)))
        else:  # one snapshot, or a run with nothing to span: the first state, then the last
            due = min(wanted, 1)
        if due > self.next_snapshot:
            self.kept.append((self.t, self.curve))
            self.next_snapshot = due

    def stop_reason(self, started):
        """Why the run must stop now, or ``""``."""
        s, t = self.settings, self.frame.time(self.t)
        if self.t >= self.end:
            return "reached t_end"
        if self.steps >= s.max_steps:
            return f"stopped at t = {t:.4g} after max_steps = {s.max_steps} steps"
        if time.perf_counter() - started > s.max_seconds:
            return f"stopped at t = {t:.4g} after max_seconds = {s.max_seconds:g} seconds ({self.steps} steps)"
        if self.curve.length < s.stop_length_fraction * self.length0:
            return (f"stopped at t = {t:.4g}: the curve has nearly vanished (its length fell below "
                    f"{s.stop_length_fraction:g} of the initial length)")
        if self.curve.edge_lengths.min() < s.stop_edge_fraction * self.curve.length / len(self.curve):
            return f"stopped at t = {t:.4g}: an edge fell below {s.stop_edge_fraction:g} of the mean edge (vertices bunch up)"
        return ""

    def step_size(self):
        """The next step: the user's, or the stable one capped by the remaining lifetime."""
        s, kind = self.settings, self.settings.kind
        if self.dt is not None:  # the user's step, only kept from jumping past the curve's end
            return min(self.dt, 0.5 * remaining_lifetime(self.curve, kind), self.end - self.t)
        if s.method == "explicit":
            step = stable_step(self.curve, kind, s.safety)
        else:
            step = s.safety * _travel_step(self.curve, kind)
        step = min(step, s.lifetime_fraction * remaining_lifetime(self.curve, kind))
        if not step > 1e-12 * self.span:  # (a step of 0, or NaN, included)
            raise _Stop(f"the step fell below 1e-12 of the curve's expected lifetime "
                        f"({self.frame.time(self.span):.3g}): the curve is about to vanish or degenerate")
        return min(step, self.end - self.t)

    def advance(self, step):
        """One step of the flow: the new curve, or a reason to stop."""
        s = self.settings
        if s.method == "explicit":
            new = self.curve.vertices + step * velocity(self.curve, s.kind)
        else:
            new = semi_implicit_step(self.curve, s.kind, step)
        new = DiscreteCurve(new)
        if s.remesh_every and (self.steps + 1) % s.remesh_every == 0:
            new = remesh(new)
        if len(new.reversals):
            raise _Stop(_reversal(new))
        if new.turning_number != self.number:
            raise _Stop("the turning number changed (the step was too large)")
        return new

    def go(self):
        s, started = self.settings, time.perf_counter()
        bar = None
        if s.progress and tqdm is not None:
            bar = tqdm(total=self.frame.time(self.span), delay=1.0, unit="time", desc=f"{s.kind} flow", leave=False,
                       bar_format="{l_bar}{bar}| t = {n:.3g} of {total:.3g} [{elapsed}<{remaining}]")
        while True:
            self.record()
            self.stopped = self.stop_reason(started)
            if self.stopped:
                break
            try:
                step = self.step_size()
                new = self.advance(step)
            except (_Stop, ValueError) as problem:  # ValueError: a vertex hit its neighbour, k overflowed
                self.stopped = f"stopped at t = {self.frame.time(self.t):.4g}: {problem}"
                break
            last = step >= self.end - self.t
            self.curve, self.t, self.steps = new, self.end if last else self.t + step, self.steps + 1
            if bar is not None:
                bar.update(min(self.frame.time(step), max(0.0, bar.total - bar.n)))
        if bar is not None:
            bar.close()
        self.seconds = time.perf_counter() - started

    def result(self):
        if self.records[-1][0] != self.t:  # the final state is always recorded
            self.records.append((self.t, self.curve.length, self.curve.signed_area, self.curve.turning_number))
        if not self.kept or self.kept[-1][1] is not self.curve:
            self.kept.append((self.t, self.curve))
        f = self.frame
        t, lengths, areas, numbers = (np.array(column) for column in zip(*self.records, strict=True))
        snapshots, origin = f.snapshots(self.kept)
        return FlowRun(self.settings.kind, self.settings.method, np.ldexp(t, 2 * f.exponent),
                       np.ldexp(lengths, f.exponent), np.ldexp(areas, 2 * f.exponent), numbers.astype(int),
                       snapshots, origin, self.stopped, self.steps, self.seconds)


class _Stop(Exception):
    """A reason to stop the run, said in words."""
