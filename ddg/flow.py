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

from dataclasses import dataclass, field

import numpy as np

from .curve import CURVATURES, DiscreteCurve, _choose

try:  # a progress bar on long runs, when tqdm is installed (it is optional)
    from tqdm.auto import tqdm
except ImportError:
    tqdm = None

METHODS = ("explicit", "semi-implicit")


@dataclass
class FlowRun:
    """What a run recorded: one entry per recorded step, snapshots for drawing, why it stopped."""

    kind: str
    method: str
    times: np.ndarray
    lengths: np.ndarray
    areas: np.ndarray
    turning_numbers: np.ndarray
    snapshots: list = field(repr=False)  # (time, DiscreteCurve) pairs
    stopped: str = ""
    steps: int = 0

    def area_rate(self):
        """``dA/dt`` by centred differences of the recorded areas (smooth flow: ``-2 pi n``)."""
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


def stable_step(curve, kind, safety=0.25):
    """An explicit time step from the shortest edges, safe for forward Euler.

    The sine flow is a discrete diffusion, ``dv/dt = D v`` with ``D`` a second difference divided by
    the dual lengths; its stiffest mode decays at rate about ``4 / (h A)`` at an edge of length ``h``.
    Forward Euler is stable when ``dt`` times that rate stays below 2, so ``dt = h A / 2`` at the worst
    vertex, divided by ``g_i`` for the faster flows. A vertex must also not travel farther than a
    fraction of its edges in one step, which matters where ``k`` is huge (near kinks).
    """
    lengths = curve.edge_lengths
    h = np.minimum(lengths, np.roll(lengths, 1))  # the shorter edge at each vertex
    g = _speed_factor(curve, kind)
    diffusion = np.min(h * curve.dual_lengths / (2 * g))
    travel = np.min(h / np.maximum(np.abs(curve.curvature(kind)), 1e-300))
    return safety * min(diffusion, travel)


def _semi_implicit_step(curve, kind, dt):
    """Solve ``(I - dt D) v_new = v`` with ``D`` built from the current curve (lengths frozen).

    ``(D v)_i = g_i / A_i * ((v_{i+1} - v_i) / |e_{i+1/2}| - (v_i - v_{i-1}) / |e_{i-1/2}|)`` equals
    ``-k_i N_i`` at the current vertices; treating it implicitly removes the ``h^2`` step limit.
    """
    n = len(curve)
    lengths = curve.edge_lengths
    w_next, w_prev = 1 / lengths, 1 / np.roll(lengths, 1)
    scale = _speed_factor(curve, kind) / curve.dual_lengths
    i = np.arange(n)
    D = np.zeros((n, n))
    D[i, (i + 1) % n] += scale * w_next
    D[i, (i - 1) % n] += scale * w_prev
    D[i, i] -= scale * (w_next + w_prev)
    return np.linalg.solve(np.eye(n) - dt * D, curve.vertices)


def remesh(curve):
    """The same closed polyline with its vertices redistributed evenly in arc length (same ``n``)."""
    v = np.vstack([curve.vertices, curve.vertices[:1]])
    s = np.concatenate([[0.0], np.cumsum(curve.edge_lengths)])
    target = curve.length * np.arange(len(curve)) / len(curve)
    return DiscreteCurve(np.stack([np.interp(target, s, v[:, 0]), np.interp(target, s, v[:, 1])], axis=1))


def flow(curve, kind="sine", t_end=1.0, *, method="explicit", dt=None, safety=0.25, snapshots=30,
         record_every=None, stop_length_fraction=0.05, stop_edge_fraction=0.02, remesh_every=None,
         max_steps=500_000, progress=True):
    """Run discrete curve-shortening flow from ``curve`` until ``t_end`` or until it must stop.

    Parameters
    ----------
    curve : DiscreteCurve (closed)
    kind : one of ``ddg.CURVATURES``, the curvature that sets the speed.
    t_end : float, the time to stop at.
    method : ``"explicit"`` (forward Euler, the step from :func:`stable_step` at every step) or
        ``"semi-implicit"`` (a linear solve per step; ``dt`` defaults to 20 explicit steps).
    dt : float, optional fixed step (explicit: at most the stable step; use with care).
    snapshots : int, curves kept for drawing, evenly spaced in time.
    stop_length_fraction, stop_edge_fraction :
        Stop cleanly, before the polygon degenerates, once its length falls below this fraction of
        the initial length, or its shortest edge below this fraction of the mean edge.
    remesh_every : int, optional
        Redistribute the vertices evenly in arc length every so many steps (:func:`remesh`). This
        adds tangential motion, which keeps vertices from bunching at sharp corners; the sine flow
        is then no longer exactly the gradient flow of length. Off by default.
    progress : bool, show a progress bar when a run takes more than a second (needs ``tqdm``;
        without it the run is the same, with no bar).

    Returns
    -------
    FlowRun with the recorded times, lengths, areas, turning numbers, snapshots and ``stopped``
    (why it stopped: ``"reached t_end"``, or what degenerated).
    """
    _choose(kind, CURVATURES, "curvature kind")
    _choose(method, METHODS, "method")
    if not curve.closed:
        raise ValueError("curve-shortening flow is defined here for closed curves only; this curve is open")
    if not t_end > 0:
        raise ValueError(f"t_end must be positive, got {t_end!r}")
    L0, n = curve.length, len(curve)
    number = curve.turning_number
    record_every = record_every or max(t_end / 400, 1e-12)
    snapshot_times = list(np.linspace(0, t_end, snapshots)) if snapshots else []
    times, lengths, areas, turnings, kept = [], [], [], [], []
    t, steps, stopped, next_record = 0.0, 0, "reached t_end", 0.0

    bar = None
    if progress and tqdm is not None:
        bar = tqdm(total=t_end, delay=1.0, unit="time", desc=f"{kind} flow", leave=False,
                   bar_format="{l_bar}{bar}| t = {n:.3g} of {total:.3g} [{elapsed}<{remaining}]")

    while True:
        if t >= next_record - 1e-15 or t >= t_end:
            times.append(t), lengths.append(curve.length), areas.append(curve.signed_area), turnings.append(curve.turning_number)
            next_record = t + record_every
        while snapshot_times and t >= snapshot_times[0] - 1e-12:
            kept.append((t, curve))
            snapshot_times.pop(0)
        if t >= t_end - 1e-15:
            break
        if steps >= max_steps:
            stopped = f"stopped after max_steps = {max_steps} steps"
            break
        if curve.length < stop_length_fraction * L0:
            stopped = f"stopped: the length fell below {stop_length_fraction:g} of the initial length"
            break
        if curve.edge_lengths.min() < stop_edge_fraction * curve.length / n:
            stopped = f"stopped: an edge fell below {stop_edge_fraction:g} of the mean edge (vertices bunch up)"
            break
        try:
            explicit_dt = stable_step(curve, kind, safety)
            if method == "explicit":
                step = min(dt or explicit_dt, t_end - t)
                new = curve.vertices + step * velocity(curve, kind)
            else:
                step = min(dt or 20 * explicit_dt, t_end - t)
                new = _semi_implicit_step(curve, kind, step)
            curve = DiscreteCurve(new)
            if remesh_every and (steps + 1) % remesh_every == 0:
                curve = remesh(curve)
        except ValueError as problem:  # a vertex hit its neighbour, or the tangent curvature diverged
            stopped = f"stopped at t = {t:.4g}: {problem}"
            break
        if curve.turning_number != number:
            stopped = f"stopped at t = {t:.4g}: the turning number changed (the step was too large)"
            break
        t += step
        steps += 1
        if bar is not None:
            bar.update(step)
    if bar is not None:
        bar.close()
    if not kept or kept[-1][1] is not curve:
        kept.append((t, curve))
    return FlowRun(kind, method, np.array(times), np.array(lengths), np.array(areas), np.array(turnings, dtype=int),
                   kept, stopped, steps)
