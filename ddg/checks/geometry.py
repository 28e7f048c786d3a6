"""The checks' random input, as specs that travel as JSON: drawn in one process, built in another.

A spec is a number, a string, ``{"array": ..., "integer": bool}``, ``{"polygon": vertices}`` (a
closed ``DiscreteCurve``) or ``{"ellipse": [a, b, cx, cy, clockwise]}`` and
``{"bean": [c, turn, cx, cy, clockwise]}`` (smooth curves). The input is drawn once, where the
verdict is computed, and only the specs cross to the process that runs the answer; so the verdict
never depends on how another process would round a random draw.
"""

import numpy as np

from .. import smooth
from .._extras import missing
from ..curve import DiscreteCurve
from ..polygons import regular_polygon


def build(spec):
    """The object a spec stands for."""
    if not isinstance(spec, dict):
        return spec
    (kind, value), = spec.items() if len(spec) == 1 else [(k, v) for k, v in spec.items() if k != "integer"]
    if kind == "array":
        return np.array(value, dtype=int if spec.get("integer") else float)
    if kind == "polygon":
        return DiscreteCurve(value)
    if kind == "ellipse":
        a, b, cx, cy, clockwise = value
        return smooth.ellipse(a, b, (cx, cy), bool(clockwise))
    if kind == "bean":  # r = 1 + c cos 2t, turned by `turn` and moved to (cx, cy): non-convex
        c, turn, cx, cy, clockwise = value
        return smooth.flower(c, 2, bool(clockwise), name="bean").moved(rotation(turn), (cx, cy))
    raise ValueError(f"unknown input {spec!r}")


def array(values, integer=False):
    return {"array": np.asarray(values).tolist(), "integer": integer}


def polygon(vertices):
    return {"polygon": np.asarray(vertices, dtype=float).tolist()}


def rotation(angle):
    return np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])


def random_polygon(rng, n=None, convex=False, min_edge=0.05, max_turn=np.pi - 0.05):
    """A random closed polygon, self-intersecting unless ``convex``; clockwise when convex."""
    n = n or int(rng.integers(4, 13))
    while True:
        if convex:
            gaps = rng.uniform(1, 3, n)
            t = 2 * np.pi * np.cumsum(gaps) / gaps.sum()
            v = np.stack([rng.uniform(1, 2) * np.cos(t), -np.sin(t)], axis=1) + rng.normal(size=2)
        else:
            v = rng.uniform(-1, 1, (n, 2))
        c = DiscreteCurve(v)
        if c.edge_lengths.min() > min_edge and np.abs(c.turning_angles).max() < max_turn:
            return c


def unequal_polygon(rng, max_turn=np.pi - 0.2):
    """A random polygon that turns both ways, with neighbouring edges of clearly different lengths."""
    while True:
        c = random_polygon(rng, max_turn=max_turn)
        ratio = c.edge_lengths / np.roll(c.edge_lengths, 1)
        psi = c.turning_angles
        if np.abs(np.log(ratio)).max() > 0.7 and np.abs(psi).min() > 0.05 and psi.min() < -0.2 and psi.max() > 0.2:
            return c


def reversal(rng, sign):
    """A closed polygon that turns straight back at vertex 1; mirrored (``sign < 0``), its cross product is -0."""
    a = rng.uniform(1, 3)
    v = np.array([[0.0, 0.0], [a, 0.0], [a / 2, 0.0], [a / 2, rng.uniform(0.5, 2)]])
    return v if sign > 0 else v * [-1.0, 1.0]


def slanted_reversal(rng):
    """A polygon that turns straight back at vertex 1 along a slanted line, chosen so that the cosine
    of the turn, computed as a.b / (|a| |b|) in the usual ways, rounds to just below -1."""
    while True:
        d = rng.normal(size=2)
        a, b = 2 * d, -d  # exactly opposite
        rows = np.array([a]), np.array([b])
        cosines = (np.dot(a, b) / (np.linalg.norm(a) * np.linalg.norm(b)),
                   (a[0] * b[0] + a[1] * b[1]) / (np.hypot(*a) * np.hypot(*b)),
                   ((rows[0] * rows[1]).sum(axis=1) / (np.linalg.norm(rows[0], axis=1)
                                                       * np.linalg.norm(rows[1], axis=1)))[0])
        if max(cosines) < -1:
            return np.array([[0.0, 0.0], a, a + b, a + b + 0.7 * np.array([-d[1], d[0]])])


def ellipse(rng, clockwise=None):
    """A random ellipse spec, centred at least 0.5 from the origin in x and in y."""
    a, b = rng.uniform(1.2, 2.5), rng.uniform(0.4, 1.0)
    centre = rng.choice([-1.0, 1.0], 2) * rng.uniform(0.5, 1.5, 2)
    clockwise = bool(rng.integers(2)) if clockwise is None else clockwise
    return {"ellipse": [float(a), float(b), float(centre[0]), float(centre[1]), clockwise]}


def bean(rng):
    """A random non-convex smooth curve spec, and parameters where it bends each way (none nearly straight)."""
    spec = {"bean": [float(rng.uniform(0.45, 0.7)), float(rng.uniform(0, 2 * np.pi)), *map(float, rng.normal(size=2)),
                     bool(rng.integers(2))]}
    curve = build(spec)
    t = rng.uniform(0, 2 * np.pi, 400)
    t = t[np.abs(curve.curvature(t)) > 0.25]
    bends = np.sign(curve.curvature(t))
    return spec, np.concatenate([t[bends > 0][:4], t[bends < 0][:4]])


def shapely_module():
    """shapely, which measures polygons for the inflation exercises (the extra [checks])."""
    try:
        import shapely
    except ImportError as error:
        raise missing("checks", error) from error
    return shapely


def star_shaped(rng):
    """A random clockwise star-shaped polygon with a reflex vertex, and room to inflate by ``eps <= 0.2``.

    Room: edges at least 0.5 long, a reflex corner turning by more than 0.6 rad and none by more
    than 100 degrees, edges that share no vertex at least 0.5 apart: the conditions of the book's
    theorem on the Minkowski sum of a simple polygon hold for ``eps < 0.25``.
    """
    shapely = shapely_module()
    while True:  # candidates in batches: about one in a thousand has room
        n = int(rng.integers(5, 8))
        t = 2 * np.pi * (np.arange(n) + rng.uniform(-0.2, 0.2, (2000, n))) / n
        r = rng.uniform(0.7, 1.6, (2000, n))
        v = np.stack([r * np.cos(t), -r * np.sin(t)], axis=2)
        e = np.roll(v, -1, axis=1) - v
        a, b = np.roll(e, 1, axis=1), e
        psi = np.arctan2(a[..., 1] * b[..., 0] - a[..., 0] * b[..., 1], (a * b).sum(axis=2))
        ok = (np.linalg.norm(e, axis=2).min(axis=1) >= 0.5) & (psi.min(axis=1) < -0.6)
        ok &= psi.min(axis=1) > -np.radians(100)
        for candidate in v[ok]:
            edges = [shapely.LineString([candidate[i], candidate[(i + 1) % n]]) for i in range(n)]
            apart = min(edges[i].distance(edges[j]) for i in range(n) for j in range(i + 2, n) if (j + 1) % n != i)
            if apart >= 0.5 and shapely.Polygon(candidate).is_valid:
                return candidate


__all__ = ["build", "array", "polygon", "regular_polygon", "random_polygon"]
