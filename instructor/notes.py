"""The helpers of the chapters' answer-key cells and solutions: the instructor's counterpart of ``ddg.notes``.

``ddg.notes`` holds what the chapters' hidden cells compute, and the student edition copies
``ddg`` as it is. These helpers belong to cells the edition leaves out (tagged ``answer-key``, or
inside a ``{solution-start}`` ... ``{solution-end}`` block) because they compute an exercise's
answer or a solution's argument, so they live here, where ``instructor/`` never reaches students:

* chapter 5 (answer key of ``ex-minkowski-nonconvex``): :func:`local_boundary` is the boundary of
  the Minkowski sum that ``thm-minkowski-simple`` describes; its area is the exercise's answer.
  :func:`minkowski_hypothesis_holds` compares it with the measured region;
* chapter 8 (answer key of ``ex-circle-curvature``): :func:`inside_circles` builds the circles
  through three consecutive vertices, whose reciprocal radii are that exercise's answer;
* chapter 10 (solution of ``ex-explore-ellipse``): :func:`equal_chords`, the vertex with two equal
  chords on a smooth curve, where the solution measures the sine formula's error.

The notebooks import them in those cells only (the book is built and tested from the repository,
where ``instructor`` is importable).
"""

import numpy as np
import shapely

from ddg import DiscreteCurve


def local_boundary(curve, e, step=0.005):
    """The boundary ``thm-minkowski-simple`` assumes for the Minkowski sum of ``curve`` and a disk of radius ``e``.

    The edges moved out by ``e``, cut off where they cross at each reflex corner (the offset's
    vertex there), joined by an arc of radius ``e`` about each convex corner, from
    ``N_{i-1/2}`` clockwise to ``N_{i+1/2}``, with points about ``step`` radians apart. Returns
    a shapely polygon: valid (simple) and equal to the measured sum, up to the arcs' chords,
    exactly when the theorem's picture holds.

    >>> square = DiscreteCurve([[0, 0], [0, 1], [1, 1], [1, 0]])
    >>> round(local_boundary(square, 0.5).area, 4)   # 1 + 4 * 0.5 + pi * 0.25, to the chords
    3.7854
    """
    crossings = curve.inflate(e, "offset").vertices
    N_before = np.roll(curve.normals, 1, axis=0)
    points = []
    for i, psi in enumerate(curve.turning_angles):  # arcs of as many points as each corner needs
        if psi > 0:  # clockwise from N_{i-1/2} to N_{i+1/2}
            start = np.arctan2(N_before[i, 1], N_before[i, 0])
            theta = start - np.linspace(0, psi, int(psi / step) + 2)
            arc = e * np.stack([np.cos(theta), np.sin(theta)], axis=1)
            points.extend(curve.vertices[i] + arc)
        else:
            points.append(crossings[i])
    return shapely.Polygon(points)


def minkowski_hypothesis_holds(curve, e):
    """Whether the Minkowski sum of ``curve`` and a disk of radius ``e`` is the region ``thm-minkowski-simple`` describes.

    The :func:`local_boundary` is simple and bounds the sum as shapely measures it (round joins of
    1024 segments per quarter circle): their symmetric difference is within three times what the
    two polygons' chords miss, ``e^2 psi h^2 / 12`` at a convex corner (``h`` the angle a chord
    spans).

    A square with a slot 0.1 wide (chapter 5's): the moved edges of the slot cross beyond 0.05.

    >>> slot = DiscreteCurve([[0, 0], [0, 2], [2, 2], [2, 0], [1.05, 0], [1.05, 1.5], [0.95, 1.5], [0.95, 0]])
    >>> minkowski_hypothesis_holds(slot, 0.03), minkowski_hypothesis_holds(slot, 0.06)
    (True, False)
    """
    step = 0.002
    boundary = local_boundary(curve, e, step)
    if not boundary.is_valid:
        return False
    region = shapely.Polygon(curve.vertices).buffer(e, quad_segs=1024)
    psi = curve.turning_angles
    chords = e**2 * psi[psi > 0].sum() * (step**2 + (np.pi / 2048) ** 2) / 12
    return bool(boundary.symmetric_difference(region).area < 3 * chords)


def inside_circles(c):
    """Which neighbours lie inside the circle ``C_i`` through ``v_{i-1}, v_i, v_{i+1}``: ``(after, before)``.

    ``after[i]`` says whether ``v_{i+2}`` lies inside ``C_i``, ``before[i]`` whether ``v_{i-2}``
    does. ``C_i`` is extremal (Ovsienko and Tabachnikov) when both or neither do.

    >>> square = DiscreteCurve([[0, 0], [0, 1], [1.2, 1.1], [1, 0]])
    >>> after, before = inside_circles(square)
    >>> after.tolist(), before.tolist()
    ([False, True, False, True], [False, True, False, True])
    """
    v = c.vertices
    a, b, d = np.roll(v, 1, axis=0), v, np.roll(v, -1, axis=0)
    A = np.stack([2 * (b - a), 2 * (d - a)], axis=1)  # centres o: |o-a| = |o-b| = |o-d|
    rhs = np.stack([(b**2).sum(1) - (a**2).sum(1), (d**2).sum(1) - (a**2).sum(1)], 1)
    o = np.linalg.solve(A, rhs[..., None])[..., 0]
    R = np.linalg.norm(b - o, axis=1)
    after = np.linalg.norm(np.roll(v, -2, axis=0) - o, axis=1) < R
    before = np.linalg.norm(np.roll(v, 2, axis=0) - o, axis=1) < R
    return after, before


def equal_chords(curve, t0, h):
    """Three points of the smooth ``curve``: ``v_{i-1}, v_i, v_{i+1}`` with ``v_i`` at ``t0`` and both chords ``h`` long.

    The neighbours are found by bisection in the parameter, within 1 of ``t0`` on each side
    (``h`` must be shorter than the chord that spans that), and returned as an open
    :class:`~ddg.DiscreteCurve`, whose one curvature is at ``v_i``.

    >>> from ddg import smooth
    >>> c = equal_chords(smooth.ellipse(2.0, 1.0), 0.3, 0.1)
    >>> bool(np.allclose(c.edge_lengths, 0.1, rtol=1e-12))
    True
    """
    v = curve.position(t0)
    direction = np.array([-1.0, 1.0])
    lo, hi = np.zeros(2), np.ones(2)
    for _ in range(100):  # bisection for |chord| = h, both sides at once
        mid = (lo + hi) / 2
        near = np.linalg.norm(curve.position(t0 + direction * mid) - v, axis=1) < h
        lo, hi = np.where(near, mid, lo), np.where(near, hi, mid)
    ends = curve.position(t0 + direction * lo)
    return DiscreteCurve([ends[0], v, ends[1]], closed=False)
