"""The exercises of the chapters on smooth and discrete curves: the osculating circle, a staircase
around an ellipse, and four vertex normals.

Each reads: draw the input; list the mistakes, most specific first (what a right answer returns comes
with the input, from the answer key).
"""

import numpy as np

from . import geometry as g
from .curvatures import READ_ONLY, shifted, wrap_around
from .judge import Call, Exercise, Mistake, given


def _centre(side, radius, direction="normal"):
    """A prediction: gamma(t) - side(kappa, call) radius(kappa) N (or T, ``direction="tangent"``)."""
    def predict(want, call):
        curve, t = (g.build(a) for a in call.args)
        kappa = curve.curvature(t)
        axis = curve.normal(t) if direction == "normal" else curve.tangent(t)
        return curve.position(t) - (side(kappa, call) * radius(kappa))[:, None] * axis
    return predict


class OsculatingCenter(Exercise):
    """``osculating_center(curve, t)``: centre of the osculating circle of a ``ddg.smooth`` curve at ``t``."""

    name = "osculating_center"
    unit = "point"
    expects = "one centre (x, y) for each parameter in t"

    def draw(self, rng):
        calls = []
        for clockwise in (True, False):
            r, c = rng.uniform(0.5, 3), rng.normal(size=2)
            spec = {"ellipse": [float(r), float(r), float(c[0]), float(c[1]), clockwise]}
            where = "clockwise" if clockwise else "counter-clockwise"
            calls.append(Call((spec, g.array(rng.uniform(0, 2 * np.pi, 5))),
                              f"a {where} circle of radius {r:.3f} centred at ({c[0]:.3f}, {c[1]:.3f})"))
        calls.append(Call((g.ellipse(rng), g.array(rng.uniform(0, 2 * np.pi, 6))), "an ellipse"))
        bean, t = g.bean(rng)
        calls.append(Call((bean, g.array(t)), "a non-convex curve, which bends both ways"))
        return calls

    mistakes = (
        Mistake("outward", "on the wrong side: the centre lies where the curve bends to, and N = J T points the other "
                "way on a clockwise circle, so it is gamma - N / kappa (on {what}{at} expected {want}, got {got})",
                predict=_centre(lambda k, call: -1.0, lambda k: 1 / k)),
        Mistake("unsigned", "right where kappa > 0, but on the wrong side where the curve bends the other way: divide "
                "by the signed kappa, not |kappa| (on {what}{at} expected {want}, got {got})",
                predict=_centre(lambda k, call: 1.0, lambda k: 1 / np.abs(k))),
        Mistake("side of the curve", "the side is decided once for the whole curve; it belongs to each point, by the "
                "sign of kappa there (on {what}{at} expected {want}, got {got})", predict=_centre(
                    lambda k, call: 1.0 if list(call.args[0].values())[0][-1] else -1.0, lambda k: 1 / np.abs(k))),
        Mistake("side of the first point", "the side is decided at the first point and used at all; it belongs to each "
                "point, by the sign of kappa there (on {what}{at} expected {want}, got {got})",
                predict=_centre(lambda k, call: np.sign(k[0]), lambda k: 1 / np.abs(k))),
        Mistake("no reciprocal", "the distance to the centre is the radius of curvature 1/|kappa|, not |kappa| (on "
                "{what}{at} expected {want}, got {got})", predict=_centre(lambda k, call: 1.0, lambda k: k)),
        Mistake("along the tangent", "the centre lies on the normal line through the point, not along the tangent "
                "(on {what}{at} expected {want}, got {got})",
                predict=_centre(lambda k, call: 1.0, lambda k: 1 / k, "tangent")),
        Mistake("vector", "the centre is a point, gamma(t) - N / kappa, not the vector from the curve to it (on "
                "{what}{at} expected {want}, got {got})",
                predict=lambda want, call: want - g.build(call.args[0]).position(g.build(call.args[1]))),
    )


class Staircase(Exercise):
    """``staircase(curve, m)``: the ``8m`` vertices of a closed staircase around a ``ddg.smooth`` ellipse.

    ``v[2k]`` is the point ``curve.position(2 pi k / (4m))`` and ``v[2k + 1]`` the corner after it;
    steps are horizontal or vertical and corners lie outside the ellipse.
    """

    name = "staircase"
    expects = "8m vertices (x, y): a point on the ellipse, then a corner, 4m times"

    def draw(self, rng):
        calls = []
        for clockwise, ms in ((True, [int(rng.integers(2, 9)), 4, 16]), (False, [3, 10])):
            spec = g.ellipse(rng, clockwise)
            where = "a clockwise ellipse" if clockwise else "a counter-clockwise ellipse"
            calls += [Call((spec, m), f"staircase(curve, {m}) around {where}") for m in ms]
        return calls

    mistakes = (
        Mistake("no corners", "only the 4m points on the ellipse: a staircase has a corner between each two, "
            "8m vertices in all", predict=lambda want, call: want[::2]),
        Mistake("closing corner", "the corner after the last point, before the step back to v_0, is missing",
            predict=lambda want, call: want[:-1]),
        Mistake("inner corners", "a corner lies inside the ellipse: of the two corners between consecutive "
            "points take the one farther from the centre (on {what}{at} expected {want}, got {got})",
            predict=given("inner corners")),
        Mistake("about the origin", "'farther out' is measured from the ellipse's centre, not from the origin "
            "(on {what}{at} expected {want}, got {got})", predict=given("about the origin")),
        Mistake("one orientation", "the corner rule works on a clockwise ellipse only: on {what} a corner lies "
            "inside{at} (expected {want}, got {got}); choose the corner farther from the centre",
            predict=given("one orientation")),
        Mistake("8m points", "v[2k] should be the k-th of 4m points, curve.position(2 pi k / (4m)): yours runs "
            "through 8m points", predict=given("8m points")),
        Mistake("starts at a corner", "v[0] should be the first point, curve.position(0), and v[1] the corner "
            "after it (on {what}{at} expected {want}, got {got})", predict=shifted(1)),
        READ_ONLY,
    )


METHODS = ("bisector", "length-weighted", "length-gradient", "area-gradient")


class VertexNormals(Exercise):
    """``vertex_normals(curve, method)``: unit normals at the vertices of a closed curve.

    ``method`` is ``"bisector"`` (the unit bisector of the two edge normals), ``"length-weighted"``
    (the edge normals averaged with weights ``|e|``), ``"length-gradient"`` (the direction of the
    gradient of length) or ``"area-gradient"`` (the direction of the gradient of the signed area).
    """

    name = "vertex_normals"
    expects = "a unit normal (x, y) at every vertex of the closed curve, v_0 and v_(n-1) included"
    forbidden = ("bisector_normals", "length_gradient", "curvature")
    measures = ("ddg.flow.semi_implicit_step",)  # (v - step) / dt tends to the gradient of length

    def draw(self, rng):
        convex, other = g.random_polygon(rng, convex=True), g.unequal_polygon(rng, max_turn=np.pi - 0.3)
        return [Call((g.polygon(c.vertices), method), f"{method!r} on {where}") for c, where in (
            (convex, "a clockwise convex polygon"), (other, "a polygon with unequal edges that turns both ways"))
            for method in METHODS]

    mistakes = (
        READ_ONLY,
        Mistake("inward", "the normals point inward: with N = J T they point outward on a clockwise polygon, mind "
                "the sign convention (on {what}{at} expected {want}, got {got})", predict=lambda want, call: -want),
        Mistake("swapped", "the gradients of length and of area are swapped (on {what}{at} expected {want}, got "
                "{got})", predict=given("swapped")),
        Mistake("weights", "'length-weighted' weighs each edge normal by its edge's length; yours is the plain "
                "bisector (on {what}{at} expected {want}, got {got})",
                predict=given("weights")),
        Mistake("signed bisector", "the bisector of the two edge normals points to their side at every vertex; "
                "yours turns round where the polygon turns counter-clockwise, as the gradient of length does (on "
                "{what}{at} expected {want}, got {got})", predict=given("signed bisector")),
        Mistake("orientation", "the gradient of length points along the bisector where the polygon turns "
                "clockwise and against it where it turns counter-clockwise, vertex by vertex, not by the turn of the "
                "whole polygon (on {what}{at} expected {want}, got {got})", predict=given("orientation")),
        Mistake("tangent", "turned a quarter: that is a tangent direction; the normal is N = J T (on {what}{at} "
                "expected {want}, got {got})", predict=lambda want, call: np.stack([want[:, 1], -want[:, 0]], 1)),
        Mistake("unnormalized", "not unit vectors: divide each by its length (on {what}{at} expected {want}, got "
                "{got})", test=lambda got, want, call: got.shape == want.shape and np.allclose(
                    got / np.linalg.norm(got, axis=1, keepdims=True), want, atol=1e-5)),
        *wrap_around("the normals"),
    )
