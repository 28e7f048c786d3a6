"""The exercises of the chapters on the three curvatures: turning angles, rebuilding a polygon,
the gradient of length, the Minkowski sum of a simple polygon.

Each reads: draw the input; list the mistakes, most specific first. What a right answer returns
comes with the input, from the answer key (``ddg.checks.judge.Call.want``).
"""

import numpy as np

from ..curve import DiscreteCurve
from ..polygons import regular_polygon
from . import geometry as g
from .judge import Call, Exercise, Mistake

INTEGER = Mistake(
    "integer input", "on {what}, which comes as integers here, your code does arithmetic in place on the integer "
    "array (numpy cannot store the float results there): convert first, np.asarray(vertices, dtype=float)",
    error=r"[Cc]annot cast ufunc|casting rule|output from dtype")
READ_ONLY = Mistake(
    "read-only input", "on {what} your code changes an array of the curve in place, and a curve's arrays are "
    "read-only: work on a copy (np.array(curve.vertices))", error=r"read-only|not writeable")


def shifted(direction):
    """Right values, each at the neighbouring vertex."""
    return lambda want, call: np.roll(want, direction, axis=0)


def wrap_around(values):
    """The closed curve's wrap-around forgotten, as it shows: ``values`` (at v_0 and v_(n-1)) wrong, or
    one or both of them missing."""
    why = (f"the wrap-around is missing: on a closed curve v_(-1) is v_(n-1) and v_n is v_0, so {values} at "
           "v_0 and v_(n-1) exist too (np.roll wraps around; np.diff does not)")
    return (Mistake("wrap-around", "the first and last vertices are wrong on {what}{at} (expected {want}, got {got}): "
                    + why, test=ends_wrong),
            Mistake("wrap-around", "the first and last vertices are missing on {what}: " + why,
                    predict=lambda want, call: want[1:-1]),
            Mistake("wrap-around", "the last vertex is missing on {what}: " + why, predict=lambda want, call: want[:-1]),
            Mistake("wrap-around", "the first vertex is missing on {what}: " + why, predict=lambda want, call: want[1:]))


def ends_wrong(got, want, call):
    """Right in the middle, wrong (but a number) at the first or the last vertex: the closed curve not
    wrapped around. (A NaN or an infinity there gets its own verdict.)"""
    inner = slice(1, -1)
    return (got.shape == want.shape and np.isfinite(got).all() and np.allclose(got[inner], want[inner], atol=1e-5)
            and not (np.allclose(got[:1], want[:1], atol=1e-5) and np.allclose(got[-1:], want[-1:], atol=1e-5)))


class TurningAngles(Exercise):
    """``turning_angles(vertices)``: clockwise turning angle at every vertex of a closed polygon, in ``(-pi, pi]``."""

    name = "turning_angles"
    expects = "the closed curve turns at every vertex, v_0 and v_(n-1) included"
    forbidden = ("turning_angles", "curvature", "total_curvature", "turning_number", "bisector_normals")
    measures = ("ddg._numerics.tan_half_turn", "ddg._numerics._exact_tan_half_turn")  # ddg's turns (tan_half_psi,
    # for every copy of DiscreteCurve): a curve is still made, its edges and lengths are still there

    def draw(self, rng):
        n = int(rng.integers(3, 20))
        calls = [Call((g.array([[0, 0], [0, 1], [1, 1], [1, 0]], integer=True),), "a clockwise square"),
                 Call((g.array(regular_polygon(n, rng.uniform(0.5, 2)).vertices),), f"a clockwise regular {n}-gon"),
                 Call((g.array(regular_polygon(n, 1.0, False).vertices),), f"a counter-clockwise regular {n}-gon"),
                 Call((g.array(g.reversal(rng, +1)),), "a polygon that turns straight back at vertex 1"),
                 Call((g.array(g.reversal(rng, -1)),), "a mirrored polygon that turns straight back at vertex 1"),
                 Call((g.array(g.slanted_reversal(rng)),), "a polygon that turns straight back along a slanted line")]
        return calls + [Call((g.array(g.random_polygon(rng).vertices),), "a random polygon") for _ in range(8)]

    def close(self, got, want, call):
        """Right to 1e-5; along a slanted line a turn straight back may come out as -pi + tiny: a
        difference of rounded headings can land there, and it is the same turn."""
        if "slanted" in call.what:
            got = np.where((want == np.pi) & (np.abs(np.abs(got) - np.pi) < 1e-6), np.pi, got)
        return super().close(got, want, call)

    mistakes = (
        INTEGER,
        Mistake("degrees", "your angles look like degrees: on {what}{at} you give {got} where {want} (radians) "
                "was expected", predict=lambda want, call: np.degrees(want)),
        Mistake("counter-clockwise", "the sign: psi is measured clockwise in this course, so {what} turns by "
                "{want}{at}; yours turns by {got}, the usual counter-clockwise sign",
                test=lambda got, want, call: bool(np.allclose(np.where(want == np.pi, 0, got + want), 0, atol=1e-5)
                                                  and np.allclose(np.abs(got[want == np.pi]), np.pi, atol=1e-5)),
                undo=lambda got, want, call: np.where(want == np.pi, np.abs(got), -got)),
        Mistake("unsigned", "the sign is lost: on {what}{at} the polygon turns counter-clockwise, psi = {want}, but "
                "yours is {got}; arccos gives the size of a turn, not its direction (the cross product's sign "
                "tells)", predict=lambda want, call: np.abs(want)),
        *wrap_around("the turning angles"),
        Mistake("after", "every value is right but at the vertex after the one it belongs to: psi_i belongs to "
                "v_i, between e_(i-1/2) and e_(i+1/2) (on {what}{at} expected {want}, got {got})", predict=shifted(1)),
        Mistake("before", "every value is right but at the vertex before the one it belongs to: psi_i belongs to "
                "v_i, between e_(i-1/2) and e_(i+1/2) (on {what}{at} expected {want}, got {got})",
                predict=shifted(-1)),
        Mistake("minus pi", "where a polygon turns straight back the angle is pi, the end of the range (-pi, pi] "
                "that belongs to it: on {what}{at} yours is {got} (np.arctan2(-0.0, -1) gives -pi)",
                test=lambda got, want, call: bool(np.allclose(np.where(want == np.pi, 0, got - want), 0, atol=1e-5)
                                                  and np.all(np.isin(got[want == np.pi], (np.pi, -np.pi)))),
                undo=lambda got, want, call: np.where(want == np.pi, np.abs(got), got)),
        Mistake("range", "an angle outside (-pi, pi]: on {what}{at} you give {got} where {want}, the same turn "
                "give or take 2 pi, was expected; bring differences of headings into (-pi, pi]",
                test=lambda got, want, call: (got.shape == want.shape and np.allclose(
                    np.angle(np.exp(1j * (got - want))), 0, atol=1e-5)) and not (
                    (got > -np.pi).all() and (got <= np.pi + 1e-9).all()) or np.allclose(got, want, atol=1e-5),
                undo=lambda got, want, call: np.pi - np.mod(np.pi - got, 2 * np.pi)),
        Mistake("arccos NaN", "NaN on {what}{at}, where the polygon turns straight back: a cosine computed as "
                "a.b / (|a| |b|) can round just below -1 there, and arccos of it is NaN; clip it to [-1, 1] (or "
                "use np.arctan2)", test=lambda got, want, call: bool(
                    np.all(np.isnan(got) <= (np.abs(want) == np.pi)) and np.allclose(
                        np.where(np.isnan(got), want, got), want, atol=1e-5))),
    )


def _mirrored(want, call):
    """A prediction: the right polygon reflected in the line of its first edge."""
    start, heading = g.build(call.args[2]), call.args[3]
    u = np.array([np.cos(heading), np.sin(heading)])
    d = want - start
    return start + 2 * np.outer(d @ u, u) - d


def _turned(angle):
    """A prediction: the right polygon turned about its start by ``angle(call)``."""
    return lambda want, call: g.build(call.args[2]) + (want - g.build(call.args[2])) @ g.rotation(angle(call)).T


class Rebuild(Exercise):
    """``rebuild(psi, lengths, start, heading)``: vertices ``v_0 ... v_n`` from turning angles and edge lengths.

    ``psi[i]`` is the clockwise turn at ``v_i``, ``lengths[i] = |e_{i+1/2}|``, ``start = v_0`` and
    ``heading`` is the angle (counter-clockwise from the x-axis) of the first edge ``e_{1/2}``.
    """

    name = "rebuild"
    expects = "the points v_0 ... v_n, each (x, y): n + 1 rows of 2"

    def draw(self, rng):
        calls = [Call((g.array(np.full(4, np.pi / 2)), g.array(np.ones(4)), g.array(np.zeros(2)), np.pi / 2),
                      "four clockwise quarter turns with unit edges, starting upwards from the origin")]
        for _ in range(4):
            c = g.random_polygon(rng)
            e = c.edges[0]
            calls.append(Call((g.array(c.turning_angles), g.array(c.edge_lengths), g.array(c.vertices[0]),
                               float(np.arctan2(e[1], e[0]))), f"the angles and lengths of a random {len(c)}-gon"))
        convex = g.random_polygon(rng, convex=True)  # turned to a random heading, its first edge made longer
        heading = float(rng.uniform(0, 6))
        turned = (convex.vertices - convex.vertices[0]) @ g.rotation(heading - np.arctan2(*convex.edges[0][::-1])).T
        longer = np.array(convex.edge_lengths)
        longer[0] *= 1.5
        calls.append(Call((g.array(convex.turning_angles), g.array(longer), g.array(turned[0]), heading),
                          f"a convex {len(convex)}-gon with its first edge made half as long again"))
        return calls

    mistakes = (
        Mistake("counter-clockwise", "the turns go the wrong way: psi is clockwise and the heading is "
                "counter-clockwise, so each turn is subtracted from the heading (on {what}{at} expected {want}, "
                "got {got})", predict=_mirrored),
        Mistake("first turn", "the first edge is turned by psi_0: psi_0 is the turn at v_0 between e_(-1/2) and "
                "e_(1/2); the first edge leaves v_0 at the given heading, and the first turn to make is psi_1, at "
                "v_1 (on {what}{at} expected {want}, got {got})",
                predict=_turned(lambda call: -float(g.build(call.args[0])[0]))),
        Mistake("missing last vertex", "it returns v_0 ... v_(n-1): the exercise asks for v_n as well, n + 1 points "
                "(v_n = v_0 when the polygon closes)", predict=lambda want, call: want[:-1]),
        Mistake("heading clockwise", "the heading is measured counter-clockwise from the x-axis, as np.arctan2 "
                "gives it; yours turns the first edge the other way (on {what}{at} expected {want}, got {got})",
                predict=_turned(lambda call: -2 * call.args[3])),
        Mistake("origin", "it starts at the origin: the first vertex is `start` (on {what}{at} expected {want}, "
                "got {got})", predict=lambda want, call: want - g.build(call.args[2])),
        Mistake("x and y", "x and y are swapped (on {what}{at} expected {want}, got {got})",
                predict=lambda want, call: want[:, ::-1]),
    )


def _times(factor):
    """A prediction: the right gradient, each vector times ``factor(curve)`` at its vertex."""
    return lambda want, call: want * factor(DiscreteCurve(g.build(call.args[0])))[:, None]


class LengthGradient(Exercise):
    """``length_gradient(vertices)``: the gradient of length of a closed polygon under the lecture's ``<.,.>``."""

    name = "length_gradient"
    expects = "a gradient vector (x, y) at every vertex of the closed curve, v_0 and v_(n-1) included"
    forbidden = ("length_gradient", "curvature", "laplacian")
    measures = ("ddg.flow.semi_implicit_step",)  # (v - step) / dt tends to the gradient of length

    def draw(self, rng):
        calls = [Call((g.array([[0, 0], [0, 1], [1, 1], [1, 0]], integer=True),), "a clockwise square"),
                 Call((g.array(regular_polygon(12, 2.0).vertices),), "a clockwise regular 12-gon of radius 2")]
        return calls + [Call((g.array(g.unequal_polygon(rng).vertices),), "a random polygon") for _ in range(5)]

    mistakes = (
        INTEGER,
        Mistake("euclidean", "the weights are missing: the gradient for <.,.> divides by A_i, the dual length; "
                "on {what}{at} yours is {got}, A_i times the expected {want}", predict=_times(
                    lambda c: c.dual_lengths)),
        Mistake("one edge", "it divides by |e_(i+1/2)|, where the dual length A_i = (|e_(i-1/2)| + |e_(i+1/2)|) / 2 "
                "belongs (on {what}{at} expected {want}, got {got})",
                predict=_times(lambda c: c.dual_lengths / c.edge_lengths)),
        Mistake("sign", "it points the wrong way: on a clockwise convex polygon the gradient of length points "
                "outward (growing the polygon lengthens it), (T_(i-1/2) - T_(i+1/2)) / A_i; yours is minus that "
                "(on {what}{at} expected {want}, got {got})", predict=lambda want, call: -want),
        Mistake("factor 2", "off by a factor of 2: A_i is the average of the two edges, not their sum (on "
                "{what}{at} expected {want}, got {got})", predict=lambda want, call: want / 2),
        Mistake("twice", "off by a factor of 2: divide by A_i, the average of the two edges (on {what}{at} "
                "expected {want}, got {got})", predict=lambda want, call: 2 * want),
        Mistake("unit", "only the direction is right: your vectors have length 1, but the gradient's length is "
                "the sine curvature 2 sin(psi_i / 2) / A_i (on {what}{at} expected {want}, got {got})",
                predict=lambda want, call: want / np.linalg.norm(want, axis=1, keepdims=True)),
        *wrap_around("the gradient vectors"),
        Mistake("after", "every value is right but at the vertex after the one it belongs to (on {what}{at} "
                "expected {want}, got {got})", predict=shifted(1)),
        Mistake("before", "every value is right but at the vertex before the one it belongs to (on {what}{at} "
                "expected {want}, got {got})", predict=shifted(-1)),
    )


def _corners(convex, reflex):
    """A prediction: A + eps L + eps^2 times the sum of convex(psi) at convex corners and reflex(psi) at
    reflex ones."""
    def predict(want, call):
        curve, eps = (g.build(a) for a in call.args)
        turns = curve.turning_angles
        corners = convex(turns[turns > 0]).sum() + reflex(turns[turns < 0]).sum()
        return np.float64(curve.signed_area + eps * curve.length + eps**2 * corners)
    return predict


class MinkowskiArea(Exercise):
    """``minkowski_area(curve, eps)``: area of the Minkowski sum of a clockwise simple polygon with a disk.

    It must be right for non-convex polygons too, for ``eps`` within the conditions of the book's
    theorem on the Minkowski sum of a simple polygon. It is measured against shapely's round buffer.
    """

    name = "minkowski_area"
    expects = "the area of the Minkowski sum, a single number"
    forbidden = ("inflated_area", "inflate")
    # shapely's buffer, and every set operation of its compiled core that could measure the same region
    # (a union of the polygon, edge rectangles and disks, its area by inclusion-exclusion, a fill made valid)
    measures = ("shapely.buffer", *(f"shapely.lib.{name}{form}" for name in (
        "buffer", "offset_curve", "union", "unary_union", "coverage_union", "disjoint_subset_union", "intersection",
        "intersection_all", "difference", "symmetric_difference", "symmetric_difference_all", "make_valid_with_params",
        "polygonize", "polygonize_full", "node") for form in ("", "_scalar", "_prec", "_prec_scalar")))
    tolerance = 1e-6

    def draw(self, rng):
        calls = [Call((g.polygon(g.random_polygon(rng, convex=True).vertices), float(rng.uniform(0.05, 1))),
                      "a random convex polygon")]
        for _ in range(4):
            calls.append(Call((g.polygon(g.star_shaped(rng)), float(rng.uniform(0.1, 0.2))),
                              "a star-shaped polygon with reflex corners"))
        return calls

    def close(self, got, want, call):
        eps = call.args[1]
        return bool(abs(got - want) < 1e-6 * abs(want) + 1e-4 * eps**2)

    mistakes = (
        Mistake("lecture's formula", "right on convex polygons, but {what} has reflex corners (psi_i < 0), where the "
                "disk adds no sector: the two moved edges overlap there instead (the book's theorem on the "
                "Minkowski sum of a simple polygon): expected {want}, got {got}",
                predict=_corners(lambda p: p / 2, lambda p: p / 2)),
        Mistake("overlap ignored", "at a reflex corner the two rectangles on the edges overlap, and the overlap, "
                "counted twice, must be taken off once (on {what}: expected {want}, got {got})",
                predict=_corners(lambda p: p / 2, lambda p: 0 * p)),
        Mistake("overlap added", "at a reflex corner the overlap of the two rectangles must be taken off, not added "
                "(on {what}: expected {want}, got {got})",
                predict=_corners(lambda p: p / 2, lambda p: np.tan(-p / 2))),
        Mistake("offset", "the kite eps^2 tan(psi/2) belongs to the offset; at a convex corner the Minkowski sum adds "
                "a disk sector, eps^2 psi / 2 (on {what}: expected {want}, got {got})",
                predict=_corners(lambda p: np.tan(p / 2), lambda p: np.tan(p / 2))),
        Mistake("half sector", "a factor of 2 in the sectors: a sector of angle psi and radius eps has area "
                "eps^2 psi / 2 (on {what}: expected {want}, got {got})",
                predict=_corners(lambda p: p / 4, lambda p: np.tan(p / 2))),
        Mistake("no strips", "the rectangles on the edges are missing: together they add eps L (on {what}: "
                "expected {want}, got {got})", predict=lambda want, call: want - call.args[1] * g.build(
                    call.args[0]).length),
        READ_ONLY,
    )
