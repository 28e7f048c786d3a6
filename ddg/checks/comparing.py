"""The exercises of the chapters that compare the curvatures: the circle through three vertices,
and how fast a zigzag's curvature grows.

Each reads: draw the input; list the mistakes, most specific first (what a right answer returns comes
with the input, from the answer key).
"""

import numpy as np

from ..curve import DiscreteCurve
from ..polygons import regular_polygon
from . import geometry as g
from .curvatures import READ_ONLY, shifted, wrap_around
from .judge import Call, Exercise, Mistake, given


def _of_curve(formula):
    """A prediction: ``formula(curve)`` of the input's polygon."""
    return lambda want, call: formula(DiscreteCurve(call.args[0]["polygon"]))


class CircleCurvature(Exercise):
    """``circle_curvature(curve)``: signed ``1/R`` of the circle through ``v_{i-1}, v_i, v_{i+1}``, at every vertex."""

    name = "circle_curvature"
    expects = "a curvature at every vertex of the closed curve, v_0 and v_(n-1) included"

    def draw(self, rng):
        n, r = int(rng.integers(3, 30)), float(rng.uniform(0.3, 3))
        other = g.unequal_polygon(rng)
        alpha = float(rng.uniform(0.2, 5))
        return [Call((g.polygon(regular_polygon(n, r).vertices),), f"a clockwise regular {n}-gon of radius {r:.3f}"),
                Call((g.polygon(regular_polygon(n, r, clockwise=False).vertices),),
                     f"a counter-clockwise regular {n}-gon of radius {r:.3f}"),
                Call((g.polygon(other.vertices),), "a random polygon with unequal edges"),
                Call((g.polygon(alpha * other.vertices @ g.rotation(rng.uniform(0, 6)).T + rng.normal(size=2)),),
                     f"the same polygon moved, turned and scaled by {alpha:.3f}"),
                Call((g.polygon(other.vertices * [1, -1]),), "the same polygon mirrored"),
                Call((g.polygon([[0.0, 0.0], [1.0, 0.0], [2.5, 0.0], [1.0, 1.0]]),),
                     "a polygon whose vertex 1 lies on the line through its neighbours")]

    mistakes = (
        READ_ONLY,
        Mistake("straight vertex", "at a straight vertex (three collinear vertices, {what}{at}) the circle's radius is "
                "infinite and k = 0; yours gives {got}: divide by the chord, not by sin psi",
                test=lambda got, want, call: bool(np.any(~np.isfinite(got) & (want == 0)) and np.allclose(
                    got[np.isfinite(got)], want[np.isfinite(got)], atol=1e-5))),
        Mistake("chord", "the chord is wrong: the circle through v_(i-1), v_i, v_(i+1) has 2 R sin psi_i = "
                "|v_(i+1) - v_(i-1)|, the side opposite v_i, not an edge (on {what}{at} expected {want}, got {got})",
                predict=_of_curve(lambda c: 2 * np.sin(c.turning_angles) / c.edge_lengths)),
        Mistake("sine formula", "that is the sine formula (eq. 3), which agrees with the circle only where the two "
                "edges are equal (on {what}{at} expected {want}, got {got})",
                predict=_of_curve(lambda c: c.curvature("sine"))),
        Mistake("radius", "that is the radius R; the curvature is 1/R (on {what}{at} expected {want}, got {got})",
                predict=lambda want, call: np.where(want == 0, np.inf, 1 / np.where(want == 0, 1, want))),
        Mistake("half", "off by a factor of 2: 1/R = 2 sin psi_i / |v_(i+1) - v_(i-1)| (on {what}{at} expected "
                "{want}, got {got})", predict=lambda want, call: want / 2),
        Mistake("unsigned", "the sign: k_i is negative where the polygon turns counter-clockwise (on {what}{at} "
                "expected {want}, got {got})", predict=lambda want, call: np.abs(want)),
        Mistake("counter-clockwise", "the sign: k_i is positive where the polygon turns clockwise, as for the other "
                "formulas (on {what}{at} expected {want}, got {got})", predict=lambda want, call: -want),
        Mistake("orientation", "the sign belongs to each turn, not to the whole polygon (on {what}{at} expected "
                "{want}, got {got})", predict=given("orientation")),
        Mistake("after", "every value is right but at the vertex after the one it belongs to (on {what}{at} "
                "expected {want}, got {got})", predict=shifted(1)),
        Mistake("before", "every value is right but at the vertex before the one it belongs to (on {what}{at} "
                "expected {want}, got {got})", predict=shifted(-1)),
        *wrap_around("the curvatures"),
    )


ZIGZAG_N = (512, 1024, 2048, 4096)


def _of_b(formula):
    """A prediction: the exponent ``formula(b)``."""
    return lambda want, call: np.float64(formula(call.args[0]))


def _with_or_without_floor(formula):
    """A test: the answer is ``formula(b)``, with or without the floor at -2 of the polygon's own error."""
    return lambda got, want, call: bool(min(abs(got - formula(call.args[0])),
                                            abs(got - max(formula(call.args[0]), -2))) < 1e-6)


class ZigzagExponent(Exercise):
    """``zigzag_exponent(b)``: the exponent ``p`` in ``max_i |k_i - 1| ~ C n^p`` for zigzags of amplitude ``n^-b``, ``b > 1``."""

    name = "zigzag_exponent"
    unit = "b"
    expects = "the exponent p, a single number"

    def draw(self, rng):
        # b > 1, on each side of b = 2 and b = 4, but not near them: there two kinds of error cross
        # over slowly, and the exponent measured on n <= 4096 lies between the two (within 0.04 of
        # the limit for b <= 3.2 and b >= 4.2, off by 0.11 at b = 3.4)
        bs = [rng.uniform(1.2, 1.8), rng.uniform(2.2, 3.0), rng.uniform(3.0, 3.2), rng.uniform(4.2, 4.8),
              rng.uniform(4.8, 6), rng.uniform(1.2, 3.2)]
        return [Call((float(b),), f"b = {b:.3f}") for b in bs]

    def close(self, got, want, call):
        return bool(abs(got - want) < 0.08)

    mistakes = (
        Mistake("no floor", "for {what} you give {got}, but the polygon's own error, pi^2 / (6 n^2), is there whatever "
                "the zigzag does: the error cannot fall faster than n^-2 (measured: {want})",
                predict=_of_b(lambda b: 2 - b)),
        Mistake("constant", "the same number for every b: the exponent depends on b (for {what} the error grows "
                "like n^{want}, you give {got})", across=lambda got, want, calls: len({float(x) for x in got}) == 1),
        Mistake("one power short", "one power of n too few: the tilt of an edge is about 2 delta / h and the "
                "curvature divides the turn by another h, so the zigzag's part grows like delta / h^2 = n^(2 - b) "
                "(for {what}: measured {want}, you give {got})", test=_with_or_without_floor(lambda b: 1 - b)),
        Mistake("twice b", "the amplitude enters once: delta = n^-b gives an error like n^(2 - b), not n^(2 - 2b) "
                "(for {what}: measured {want}, you give {got})", test=_with_or_without_floor(lambda b: 2 - 2 * b)),
        Mistake("sign", "the sign: a larger b means a smaller zigzag and a smaller error (for {what}: measured "
                "{want}, you give {got})", predict=_of_b(lambda b: b - 2)),
        Mistake("floor too early", "the polygon's own error takes over only where the zigzag's, n^(2 - b), falls "
                "below n^-2, from b = 4 on (for {what}: measured {want}, you give {got})",
                predict=_of_b(lambda b: 2 - b if b < 3 else -2.0)),
    )
