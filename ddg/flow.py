"""Discrete curve-shortening flow: move every vertex by ``-k_i N_i`` (the lecture's sign).

Smooth curve-shortening flow is ``d gamma / dt = -kappa N``: with the lecture's convention
(clockwise positive, ``N`` outward on a clockwise circle) a circle shrinks. Discretely each vertex
moves along its unit vertex normal ``N_i`` (the bisector of the two edge normals, the direction of
the gradient of length) with speed given by one of the three discrete curvatures:

    d v_i / dt = -k_i N_i.

For the sine curvature (eq. 3) this is ``-(grad L)_i``: the true gradient flow of length for the
lecture's inner product (§3.3). The angle and tangent curvatures move the same direction at other
speeds, ``k_i = g_i k_i^sine`` with ``g = (psi/2) / sin(psi/2)`` or ``1 / cos(psi/2)``.

>>> run = ddg.flow.flow(ddg.regular_polygon(64), "sine", t_end=0.2)        # doctest: +SKIP
>>> run.times, run.lengths, run.areas, run.turning_numbers, run.snapshots  # doctest: +SKIP
"""

import time
from dataclasses import dataclass, field

import numpy as np

from .curve import CURVATURES, DiscreteCurve, _choose, _previous, _real

try:  # a progress bar on long runs, when tqdm is installed (it is optional)
    from tqdm.auto import tqdm
except ImportError:
    tqdm = None

METHODS = ("explicit", "semi-implicit")


@dataclass
class FlowRun:
    """What a run recorded: one entry per recorded step (the first and the last state always),
    snapshots for drawing, why it stopped, and how long it took (``seconds``)."""

    kind: str
    method: str
    times: np.ndarray
    lengths: np.ndarray
    areas: np.ndarray
    turning_numbers: np.ndarray
    snapshots: list = field(repr=False)  # (time, DiscreteCurve) pairs
    stopped: str = ""
    steps: int = 0
    seconds: float = 0.0

    def area_rate(self):
        """``dA/dt`` by centred differences of the recorded areas (smooth flow: ``-2 pi n``)."""
        if len(self.times) < 2:
            raise ValueError(f"the area rate needs at least 2 records; this run has {len(self.times)} ({self.stopped})")
        return np.gradient(self.areas, self.times)


def velocity(curve, kind):
    """``-k_i N_i`` for every vertex: the discrete curve-shortening velocity."""
    return -curve.curvature(kind)[:, None] * curve.bisector_normals


def _speed_factor(curve, kind):
    """``g_i = k_i / k_i^sine``: how much faster than the gradient flow of length each vertex moves."""
    half = curve.turning_angles / 2
    if kind == "sine":
        return np.ones(len(curve))
    if kind == "angle":
        return 1 / np.sinc(half / np.pi)  # (psi/2) / sin(psi/2), = 1 at psi = 0
    return 1 / np.cos(half)


def _travel_step(curve, kind):
    """The time in which the fastest vertex, relative to its shorter edge, crosses that edge."""
    lengths = curve.edge_lengths
    h = np.minimum(lengths, _previous(lengths))  # the shorter edge at each vertex
    with np.errstate(divide="ignore", over="ignore"):  # a straight vertex (k = 0, or nearly) sets no limit
        return float(np.min(h / np.abs(curve.curvature(kind))))


def stable_step(curve, kind, safety=0.25):
    """An explicit time step from the shortest edges, safe for forward Euler.

    The sine flow is a discrete diffusion, ``dv/dt = D v`` with ``D`` a second difference divided by
    the dual lengths; its stiffest mode decays at rate about ``4 / (h A)`` at an edge of length ``h``.
    Forward Euler is stable when ``dt`` times that rate stays below 2, so ``dt = h A / 2`` at the worst
    vertex, divided by ``g_i`` for the faster flows. A vertex must also not travel farther than a
    fraction of its edges in one step, which matters where ``k`` is huge (near kinks).
    """
    safety = _real(safety, "safety", 0.0, strict=True)
    lengths = curve.edge_lengths
    h = np.minimum(lengths, _previous(lengths))
    diffusion = np.min(h * curve.dual_lengths / (2 * _speed_factor(curve, kind)))
    return safety * min(diffusion, _travel_step(curve, kind))


def remaining_lifetime(curve, kind):
    """How long the curve has left under the flow, estimated from the rate of its area (or length).

    Along ``dv_i/dt = -k_i N_i``: ``dA/dt = -sum_i A_i k_i cos(psi_i/2)`` (chain rule; chapter 9 of
    the book), about ``-2 pi`` times the turning number. The estimate is ``A / |dA/dt|``, exact for a
    regular polygon, whose area falls at a constant rate. Where that says nothing (turning number
    0, as for a figure-eight, or an area moving away from 0) it is ``L / |dL/dt|``, with
    ``dL/dt = -sum_i A_i k_i k_i^sine``: twice the lifetime of a circle, and shorter while wiggles
    smooth out.
    """
    k, A = curve.curvature(kind), curve.dual_lengths
    area, rate = curve.signed_area, -np.sum(A * k * np.cos(curve.turning_angles / 2))
    if curve.turning_number != 0 and area * rate < 0:
        return -area / rate
    return curve.length / np.sum(A * k * curve.curvature("sine"))


def solve_cyclic_tridiagonal(a, b, c, d):
    """Solve ``a_i x_{i-1} + b_i x_i + c_i x_{i+1} = d_i`` for ``i`` mod ``m`` (``d``: shape ``(m, 2)``).

    Cyclic reduction, vectorized. Each pass eliminates the odd-numbered unknowns from the equations
    of their even-numbered neighbours, which leaves a cyclic tridiagonal system for the even ones,
    half the size. (When ``m`` is odd, the last and first unknowns are both even and stay coupled
    directly.) The last small system is solved densely; the odd unknowns are recovered on the way
    back. That is ``log2 m`` Python-level passes of numpy work over ``m, m/2, m/4, ...`` unknowns:
    ``O(m)`` time and memory in all, where a dense solve costs ``O(m^3)`` time and ``O(m^2)``
    memory (and the Thomas algorithm, also ``O(m)``, is a Python loop over the unknowns). Without
    pivoting, elimination is stable for diagonally dominant systems such as ``I - dt D`` below.
    """
    levels = []
    while len(b) > 4:
        m = len(b)
        j = np.arange(0, m, 2)  # the unknowns kept
        left, right = (j - 1) % m, (j + 1) % m
        alpha, gamma = -a[j] / b[left], -c[j] / b[right]  # multiples of the neighbouring equations
        new_a, new_c = alpha * a[left], gamma * c[right]
        if m % 2:  # unknowns m - 1 and 0 are both kept: their coupling stays as it is
            alpha[0] = gamma[-1] = 0.0
            new_a[0], new_c[-1] = a[0], c[-1]
        levels.append((a, b, c, d))
        b, d = b[j] + alpha * c[left] + gamma * a[right], d[j] + alpha[:, None] * d[left] + gamma[:, None] * d[right]
        a, c = new_a, new_c
    m, i = len(b), np.arange(len(b))
    M = np.zeros((m, m))
    for offset, coefficients in ((-1, a), (0, b), (1, c)):  # three diagonals; they overlap when m < 3
        np.add.at(M, (i, (i + offset) % m), coefficients)
    x = np.linalg.solve(M, d)
    for a, b, c, d in reversed(levels):  # back-substitute the odd unknowns of each level
        m = len(b)
        full, odd = np.empty_like(d), np.arange(1, m, 2)
        full[::2] = x
        full[odd] = (d[odd] - a[odd, None] * full[odd - 1] - c[odd, None] * full[(odd + 1) % m]) / b[odd, None]
        x = full
    return x


def semi_implicit_step(curve, kind, dt):
    """Solve ``(I - dt D) v_new = v`` with ``D`` built from the current curve (lengths frozen).

    ``(D v)_i = g_i / A_i * ((v_{i+1} - v_i) / |e_{i+1/2}| - (v_i - v_{i-1}) / |e_{i-1/2}|)`` equals
    ``-k_i N_i`` at the current vertices; treating it implicitly removes the ``h^2`` step limit.
    ``I - dt D`` is cyclic tridiagonal and diagonally dominant: :func:`solve_cyclic_tridiagonal`.
    """
    lengths = curve.edge_lengths
    w_next, w_prev = 1 / lengths, 1 / _previous(lengths)
    s = dt * _speed_factor(curve, kind) / curve.dual_lengths
    return solve_cyclic_tridiagonal(-s * w_prev, 1 + s * (w_next + w_prev), -s * w_next, curve.vertices)


def remesh(curve):
    """The same closed polyline with its vertices redistributed evenly in arc length (same ``n``)."""
    v = np.vstack([curve.vertices, curve.vertices[:1]])
    s = np.concatenate([[0.0], np.cumsum(curve.edge_lengths)])
    target = curve.length * np.arange(len(curve)) / len(curve)
    return DiscreteCurve(np.stack([np.interp(target, s, v[:, 0]), np.interp(target, s, v[:, 1])], axis=1))


def _reversal(curve):
    return (f"the curve turns straight back at vertex {curve._reversals[0]} (psi = pi): neither its turning "
            "number nor the tangent curvature is defined there")


def _count(value, name, minimum):
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return int(value)


def _fraction(value, name):
    value = _real(value, name, 0.0)
    if value >= 1:
        raise ValueError(f"{name} must be a fraction in [0, 1), got {value!r}")
    return value


def flow(curve, kind="sine", t_end=1.0, *, method="explicit", dt=None, safety=0.25, lifetime_fraction=0.02,
         snapshots=30, record_every=None, stop_length_fraction=0.05, stop_edge_fraction=0.02,
         remesh_every=None, max_steps=500_000, max_seconds=600.0, progress=True):
    """Run discrete curve-shortening flow from ``curve`` until ``t_end`` or until it must stop.

    Parameters
    ----------
    curve : DiscreteCurve (closed)
    kind : one of ``ddg.CURVATURES``, the curvature that sets the speed.
    t_end : float, the time to stop at.
    method : ``"explicit"`` (forward Euler, the step from :func:`stable_step` at every step) or
        ``"semi-implicit"`` (a linear solve per step, stable at any step; the step is the one in
        which a vertex moves ``safety`` of its shorter edge).
    dt : float, optional fixed step instead of the automatic one, checked neither for stability nor
        for accuracy (use with care), only kept below half the remaining lifetime.
    safety : float, the fraction of the explicit stability limit (explicit), or of the shorter edge
        a vertex may travel in one step (semi-implicit).
    lifetime_fraction : float
        Accuracy: no automatic step is longer than this fraction of the curve's remaining
        lifetime (:func:`remaining_lifetime`). Both methods are first order: on a regular polygon,
        where the lifetime rule sets the step, the area comes out too large by
        ``c * lifetime_fraction`` times the area lost, ``c = 1/4`` (explicit) or ``3/4``
        (semi-implicit): 0.5% or 1.5% at the default. A curve that would vanish before ``t_end``
        is approached in ever shorter steps and the run stops, saying so.
    snapshots : int, curves kept for drawing, evenly spaced in time.
    record_every : float, time between records (default ``t_end / 400``).
    stop_length_fraction, stop_edge_fraction :
        Stop cleanly, before the polygon degenerates, once its length falls below this fraction of
        the initial length (the curve has nearly vanished), or its shortest edge below this
        fraction of the mean edge.
    remesh_every : int, optional
        Redistribute the vertices evenly in arc length every so many steps (:func:`remesh`). This
        adds tangential motion, which keeps vertices from bunching at sharp corners; the sine flow
        is then no longer exactly the gradient flow of length. Off by default.
    max_steps, max_seconds : the run's budget; it stops, saying so, when either is spent.
    progress : bool, show a progress bar when a run takes more than a second (needs ``tqdm``;
        without it the run is the same, with no bar).

    Returns
    -------
    FlowRun with the recorded times, lengths, areas, turning numbers (the first and the last state
    always among them), snapshots and ``stopped``: ``"reached t_end"``, or why it stopped earlier.
    """
    _choose(kind, CURVATURES, "curvature kind")
    _choose(method, METHODS, "method")
    if not isinstance(curve, DiscreteCurve):
        raise ValueError(f"curve must be a DiscreteCurve, got {type(curve).__name__}")
    if not curve.closed:
        raise ValueError("curve-shortening flow is defined here for closed curves only; this curve is open")
    if len(curve._reversals):
        raise ValueError(_reversal(curve))
    t_end = _real(t_end, "t_end", 0.0, strict=True)
    dt = None if dt is None else _real(dt, "dt", 0.0, strict=True)
    safety = _real(safety, "safety", 0.0, strict=True)
    lifetime_fraction = _real(lifetime_fraction, "lifetime_fraction", 0.0, strict=True)
    record_every = t_end / 400 if record_every is None else _real(record_every, "record_every", 0.0, strict=True)
    snapshots, max_steps = _count(snapshots, "snapshots", 0), _count(max_steps, "max_steps", 1)
    remesh_every = None if remesh_every is None else _count(remesh_every, "remesh_every", 1)
    max_seconds = _real(max_seconds, "max_seconds", 0.0, strict=True)
    stop_length_fraction = _fraction(stop_length_fraction, "stop_length_fraction")
    stop_edge_fraction = _fraction(stop_edge_fraction, "stop_edge_fraction")

    L0, n, number = curve.length, len(curve), curve.turning_number
    snapshot_times = list(np.linspace(0, t_end, snapshots)) if snapshots else []
    times, lengths, areas, turnings, kept = [], [], [], [], []
    t, steps, stopped, next_record = 0.0, 0, "reached t_end", 0.0
    near = 1e-9 * t_end  # times this close count as equal: relative to the run's time scale

    def record(t, curve):
        times.append(t), lengths.append(curve.length), areas.append(curve.signed_area)
        turnings.append(curve.turning_number)

    bar = None
    if progress and tqdm is not None:
        bar = tqdm(total=t_end, delay=1.0, unit="time", desc=f"{kind} flow", leave=False,
                   bar_format="{l_bar}{bar}| t = {n:.3g} of {total:.3g} [{elapsed}<{remaining}]")
    start = time.perf_counter()
    while True:
        if t >= next_record - near or t == t_end:
            record(t, curve)
            next_record = t + record_every
        while snapshot_times and t >= snapshot_times[0] - near:
            kept.append((t, curve))
            snapshot_times.pop(0)
        if t == t_end:
            break
        if steps >= max_steps:
            stopped = f"stopped at t = {t:.4g} after max_steps = {max_steps} steps"
            break
        if time.perf_counter() - start > max_seconds:
            stopped = f"stopped at t = {t:.4g} after max_seconds = {max_seconds:g} seconds ({steps} steps)"
            break
        if curve.length < stop_length_fraction * L0:
            stopped = (f"stopped at t = {t:.4g}: the curve has nearly vanished (its length fell below "
                       f"{stop_length_fraction:g} of the initial length)")
            break
        if curve.edge_lengths.min() < stop_edge_fraction * curve.length / n:
            stopped = f"stopped at t = {t:.4g}: an edge fell below {stop_edge_fraction:g} of the mean edge (vertices bunch up)"
            break
        try:
            if dt is not None:  # the user's step: only kept from jumping past the curve's end
                step = min(dt, 0.5 * remaining_lifetime(curve, kind))
            else:
                step = stable_step(curve, kind, safety) if method == "explicit" else safety * _travel_step(curve, kind)
                step = min(step, lifetime_fraction * remaining_lifetime(curve, kind))
            if step < 1e-12 * t_end:
                stopped = (f"stopped at t = {t:.4g}: the step fell below 1e-12 of t_end "
                           "(the curve is about to vanish or degenerate)")
                break
            last = step >= t_end - t
            step = min(step, t_end - t)
            if method == "explicit":
                new = curve.vertices + step * velocity(curve, kind)
            else:
                new = semi_implicit_step(curve, kind, step)
            new = DiscreteCurve(new)
            if remesh_every and (steps + 1) % remesh_every == 0:
                new = remesh(new)
            if len(new._reversals):
                raise ValueError(_reversal(new))
            changed = new.turning_number != number
        except ValueError as problem:  # a vertex hit its neighbour, or the tangent curvature diverged
            stopped = f"stopped at t = {t:.4g}: {problem}"
            break
        if changed:
            stopped = f"stopped at t = {t:.4g}: the turning number changed (the step was too large)"
            break
        curve, t, steps = new, t_end if last else t + step, steps + 1
        if bar is not None:
            bar.update(step)
    if bar is not None:
        bar.close()
    if times[-1] != t:  # the final state is always recorded
        record(t, curve)
    if not kept or kept[-1][1] is not curve:
        kept.append((t, curve))
    return FlowRun(kind, method, np.array(times), np.array(lengths), np.array(areas), np.array(turnings, dtype=int),
                   kept, stopped, steps, time.perf_counter() - start)
