"""The answer key: what a right answer returns, for every coding exercise. The instructor's only.

``ddg.checks`` holds how each exercise draws its input and the mistakes students make, but no code
that computes an answer: a check judges inputs that carry their expected value (``Call.want``) and
the values some mistakes predict (``Call.given``), from here. Two ways that happens:

* the grader draws hidden inputs (``ddg.checks.draw``) and :func:`complete` fills them in here;
* ``make student`` writes :func:`public_sets` into ``ddg/checks/public.json``: the inputs the
  students' own checks run on, with their expected values as data
  (``python -m instructor.references`` writes it into the repository's ``ddg``).

The references measure where they can (the circle through three points, the area of shapely's round
buffer) rather than restate the lecture's formula, so that the book's answers are checked against
something else.
"""

import argparse
import json
import pathlib

import numpy as np

from ddg import checks
from ddg.checks import geometry as g
from ddg.checks.comparing import ZIGZAG_N
from ddg.curve import DiscreteCurve

PUBLIC_SETS = 4
"""How many sets of public inputs each exercise ships (a student's check picks one)."""

PUBLIC = pathlib.Path(checks.__file__).with_name("public.json")


# ------------------------------------------------------------------ chapter 1: smooth curves


def osculating_center(call):
    """The limit of the circle through three nearby points of the curve (measured, not by formula)."""
    curve, t = (g.build(a) for a in call.args)
    p, q, r = (curve.position(t + d) for d in (-2e-4, 0.0, 2e-4))
    a, b = q - p, r - p
    d = 2 * (a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])
    ux = (b[:, 1] * (a**2).sum(1) - a[:, 1] * (b**2).sum(1)) / d
    uy = (a[:, 0] * (b**2).sum(1) - b[:, 0] * (a**2).sum(1)) / d
    return p + np.stack([ux, uy], axis=1)


# ------------------------------------------------------------------ chapter 2: the staircase and the normals


def _stairs(m, corner, call):
    """The points at 2 pi k / (4m), each followed by the corner ``corner(p, q, centre)`` chooses."""
    curve = g.build(call.args[0])
    p = curve.position(np.arange(4 * m) * (np.pi / (2 * m)))
    q = np.concatenate([p[1:], p[:1]])  # the next point
    centre = np.array(call.args[0]["ellipse"][2:4])
    return np.stack([p, corner(p, q, centre)], axis=1).reshape(-1, 2)


def _outer(p, q, centre):
    """x and y each from the point farther from ``centre`` in that direction."""
    x = np.where(np.abs(p[:, 0] - centre[0]) >= np.abs(q[:, 0] - centre[0]), p[:, 0], q[:, 0])
    y = np.where(np.abs(p[:, 1] - centre[1]) >= np.abs(q[:, 1] - centre[1]), p[:, 1], q[:, 1])
    return np.stack([x, y], axis=1)


def _inner(p, q, centre):
    x = np.where(np.abs(p[:, 0] - centre[0]) < np.abs(q[:, 0] - centre[0]), p[:, 0], q[:, 0])
    y = np.where(np.abs(p[:, 1] - centre[1]) < np.abs(q[:, 1] - centre[1]), p[:, 1], q[:, 1])
    return np.stack([x, y], axis=1)


def _by_quadrant(p, q, centre):  # a rule worked out on a clockwise ellipse, used on every one
    mid = (p + q) / 2 - centre
    odd = mid[:, 0] * mid[:, 1] > 0
    return np.where(odd[:, None], np.stack([q[:, 0], p[:, 1]], 1), np.stack([p[:, 0], q[:, 1]], 1))


def staircase(call):
    return _stairs(call.args[1], _outer, call)


def staircase_given(call):
    m = call.args[1]
    return {"inner corners": _stairs(m, _inner, call),
            "about the origin": _stairs(m, lambda p, q, centre: _outer(p, q, np.zeros(2)), call),
            "one orientation": _stairs(m, _by_quadrant, call),
            "8m points": _stairs(2 * m, _outer, call)}


def normals(curve, method):
    """The unit vertex normal of each method, from ddg's quantities."""
    weighted = np.roll(curve.edge_lengths, 1)[:, None] * np.roll(curve.normals, 1, axis=0)
    weighted += curve.edge_lengths[:, None] * curve.normals  # the direction of the gradient of the area too
    n = {"bisector": curve.bisector_normals, "length-gradient": curve.length_gradient()}.get(method, weighted)
    return n / np.linalg.norm(n, axis=1, keepdims=True)


def vertex_normals(call):
    return normals(DiscreteCurve(call.args[0]["polygon"]), call.args[1])


def vertex_normals_given(call):
    curve, method = DiscreteCurve(call.args[0]["polygon"]), call.args[1]
    instead = {"swapped": {"length-gradient": "area-gradient", "area-gradient": "length-gradient"},
               "weights": {"length-weighted": "bisector", "area-gradient": "bisector"},
               "signed bisector": {"bisector": "length-gradient"}}
    given = {key: normals(curve, swap[method]) for key, swap in instead.items() if method in swap}
    if method == "length-gradient":
        given["orientation"] = normals(curve, "bisector") * np.sign(curve.signed_area)
    return given


# ------------------------------------------------------------------ chapters 3-5: the three curvatures


def turning_angles(call):
    return DiscreteCurve(g.build(call.args[0])).turning_angles


def rebuild(call):
    """The polygon the angles and lengths came from, drawn edge by edge as complex numbers."""
    psi, lengths, start, heading = (g.build(a) for a in call.args)
    steps = lengths * np.exp(1j * heading) * np.exp(-1j * np.cumsum(np.r_[0.0, psi[1:]]))
    z = complex(*start) + np.r_[0, np.cumsum(steps)]
    return np.stack([z.real, z.imag], axis=1)


def length_gradient(call):
    return DiscreteCurve(g.build(call.args[0])).length_gradient()


def minkowski_area(call):
    """The area of the sum, measured by shapely (round joins of 1024 segments per quarter circle)."""
    curve, eps = (g.build(a) for a in call.args)
    return np.float64(g.shapely_module().Polygon(curve.vertices).buffer(eps, quad_segs=1024).area)


# ------------------------------------------------------------------ chapters 6-7: comparing the curvatures


def circle_curvature(call):
    """Measured: the centre equidistant from the three vertices, from two linear equations; the sign
    from the direction of the turn; 0 where the three are collinear."""
    v = np.array(call.args[0]["polygon"])
    prev, nxt = np.roll(v, 1, axis=0), np.roll(v, -1, axis=0)
    a, b = v - prev, nxt - v
    turn = a[:, 1] * b[:, 0] - a[:, 0] * b[:, 1]  # positive where the polygon turns clockwise
    straight = np.abs(turn) < 1e-12 * np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1)
    rows = 2 * np.stack([a, b], axis=1)
    rows[straight] = np.eye(2)
    sides = np.stack([(v**2).sum(1) - (prev**2).sum(1), (nxt**2).sum(1) - (v**2).sum(1)], axis=1)
    centres = np.linalg.solve(rows, sides[..., None])[..., 0]
    return np.where(straight, 0.0, np.sign(turn) / np.linalg.norm(centres - v, axis=1))


def circle_curvature_given(call):
    curve = DiscreteCurve(call.args[0]["polygon"])
    return {"orientation": np.sign(curve.signed_area) * np.abs(circle_curvature(call))}


def zigzag_exponent(call):
    """Measured: the slope of log max |k_i - 1| against log n, on zigzags with n = 512 ... 4096."""
    b, errors = call.args[0], []
    for n in ZIGZAG_N:
        theta = 2 * np.pi * np.arange(n) / n
        radius = 1 + n ** (-b) * (-1.0) ** np.arange(n)
        c = DiscreteCurve(np.stack([radius * np.cos(theta), -radius * np.sin(theta)], axis=1))
        errors.append(np.abs(c.curvature("angle") - 1).max())
    return np.float64(np.polyfit(np.log(ZIGZAG_N), np.log(errors), 1)[0])


EXPECTED = {"osculating_center": osculating_center, "staircase": staircase, "vertex_normals": vertex_normals,
            "turning_angles": turning_angles, "rebuild": rebuild, "length_gradient": length_gradient,
            "minkowski_area": minkowski_area, "circle_curvature": circle_curvature,
            "zigzag_exponent": zigzag_exponent}
"""What a right answer returns, by exercise: ``EXPECTED[name](call)``."""

GIVEN = {"staircase": staircase_given, "vertex_normals": vertex_normals_given,
         "circle_curvature": circle_curvature_given}
"""What the mistakes that ``ddg.checks`` cannot compute without an answer key predict, by exercise."""


def complete(name, calls):
    """``calls`` with their expected values and the mistakes' given predictions filled in."""
    for call in calls:
        call.want = np.asarray(EXPECTED[name](call), dtype=float)
        call.given = {key: np.asarray(value, dtype=float) for key, value in GIVEN.get(name, lambda c: {})(call).items()}
    return calls


def hidden(name, seed):
    """The grader's input for exercise ``name`` drawn from ``seed``, with its key."""
    return complete(name, checks.draw(name, seed))


def run(name, answer, seed=None, isolate=True):
    """Check ``answer`` as the grader would, on hidden input drawn from ``seed``: its ``Feedback``."""
    return checks.run(name, answer, isolate=isolate, calls=hidden(name, seed), kind="hidden")


def public_sets():
    """``{name: [set, ...]}``: each set a list of inputs with their expected values, as JSON data."""
    def data(call):
        return {"args": json.loads(json.dumps(list(call.args))), "what": call.what, "want": call.want.tolist(),
                **({"given": {k: v.tolist() for k, v in call.given.items()}} if call.given else {})}
    return {name: [[data(call) for call in hidden(name, 1000 + k)] for k in range(PUBLIC_SETS)]
            for name in sorted(checks.EXERCISES)}


def write_public(path=PUBLIC):
    """Write :func:`public_sets` to ``path`` (by default the ``ddg`` of this repository)."""
    path = pathlib.Path(path)
    path.write_text(json.dumps(public_sets(), separators=(",", ":")) + "\n")
    return path


def main(argv=None):
    parser = argparse.ArgumentParser(description="Write the public inputs of the students' checks, with their "
                                                 "expected values, from the answer key.")
    parser.add_argument("--out", default=str(PUBLIC), help=f"where to write them (default: {PUBLIC})")
    args = parser.parse_args(argv)
    print(f"public inputs written to {write_public(args.out)}")


if __name__ == "__main__":  # through the module as imported, so that what is appended below this line counts too
    import instructor.references

    instructor.references.main()
