"""Homework checks tell right from wrong: the catalogue, on 100 seeds each.

For every coding exercise the catalogue lists right answers written in different ways (the book's
reference solution from its notebook, the same returning float32 or a list, another algorithm)
and plausible wrong answers (the other sign convention, a dropped closing edge, missing weights,
an index off by one, a neighbouring formula of the book, an answer a few percent off). Each check
must accept every right answer and reject every wrong one, on each of 100 seeds. Then: an answer
that hangs, crashes, exits, uses the ddg quantity it should compute, or tampers with the check's
state, gets a clear verdict.
"""

import json
import pathlib
import re
import time

import numpy as np
import pytest
import shapely

import ddg
from ddg import checks, edition, smooth

ROOT = pathlib.Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted((ROOT / "book").glob("*.ipynb"))
SEEDS = range(100)


def solution_cells():
    for nb in NOTEBOOKS:
        for cell in json.loads(nb.read_text())["cells"]:
            if "solution" in cell["metadata"].get("tags", []):
                yield nb.stem, "".join(cell["source"])


def namespace(source):
    env = {"np": np, "ddg": ddg, "smooth": smooth}
    exec(source, env)  # noqa: S102 - the book's own reference solutions
    return env


REFERENCE = {}
for _, source in solution_cells():
    REFERENCE.update({k: v for k, v in namespace(source).items() if k not in ("np", "ddg", "smooth", "__builtins__")})


def starter_of(name):
    source = next(s for _, s in solution_cells() if re.search(rf"^(def )?{name}\b", s, re.M))
    return namespace(edition.starter(source)).get(name)


def as_float32(name):
    def answer(*args):
        return np.asarray(REFERENCE[name](*args), dtype=np.float32)
    answer.__name__ = f"{name}_float32"
    return answer


def as_list(name):
    def answer(*args):
        return np.asarray(REFERENCE[name](*args)).tolist()
    answer.__name__ = f"{name}_list"
    return answer


def reference(name):
    return lambda *args: REFERENCE[name](*args)


# ------------------------------------------------------------------------ chapter 1


def osculating_three_points(curve, t, h=1e-4):  # another algorithm: the circle through nearby points
    p, q, r = (curve.position(t + d) for d in (-h, 0, h))
    a, b = q - p, r - p
    d = 2 * (a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])
    ux = (b[:, 1] * (a**2).sum(1) - a[:, 1] * (b**2).sum(1)) / d
    uy = (a[:, 0] * (b**2).sum(1) - b[:, 0] * (a**2).sum(1)) / d
    return p + np.stack([ux, uy], axis=1)


def osculating_outward(curve, t):  # the opposite sign: centre on the outside
    return curve.position(t) + curve.normal(t) / curve.curvature(t)[:, None]


def osculating_unsigned(curve, t):  # |kappa|: right for clockwise curves only
    return curve.position(t) - curve.normal(t) / np.abs(curve.curvature(t))[:, None]


def osculating_no_reciprocal(curve, t):  # kappa instead of 1/kappa
    return curve.position(t) - curve.normal(t) * curve.curvature(t)[:, None]


def osculating_along_tangent(curve, t):  # T instead of N
    return curve.position(t) - curve.tangent(t) / curve.curvature(t)[:, None]


def osculating_few_percent(curve, t):
    return curve.position(t) - 1.03 * curve.normal(t) / curve.curvature(t)[:, None]


def osculating_side_from_orientation(curve, t):  # right only where the curve bends the way it turns
    side = np.sign(curve.total_curvature())
    return curve.position(t) - side * curve.normal(t) / np.abs(curve.curvature(t))[:, None]


def osculating_side_from_first_point(curve, t):  # the side found at one point, used at all
    kappa = curve.curvature(t)
    return curve.position(t) - np.sign(kappa[0]) * curve.normal(t) / np.abs(kappa)[:, None]


# ------------------------------------------------------------------------ chapter 2


def staircase_by_coordinates(curve, m):  # another algorithm: x and y from the point farther out
    p = curve.position(2 * np.pi * np.arange(4 * m) / (4 * m))
    q, c = np.roll(p, -1, axis=0), p.mean(axis=0)
    x = np.where(np.abs(p[:, 0] - c[0]) > np.abs(q[:, 0] - c[0]), p[:, 0], q[:, 0])
    y = np.where(np.abs(p[:, 1] - c[1]) > np.abs(q[:, 1] - c[1]), p[:, 1], q[:, 1])
    return np.stack([p, np.stack([x, y], axis=1)], axis=1).reshape(-1, 2)


def staircase_inscribed(curve, m):  # chords instead of steps
    return curve.position(2 * np.pi * np.arange(4 * m) / (4 * m))


def staircase_no_closing_corner(curve, m):  # drops the corner before the closing edge
    return REFERENCE["staircase"](curve, m)[:-1]


def staircase_inner_corners(curve, m):  # corners inside: the same length, but not around the ellipse
    p = curve.position(2 * np.pi * np.arange(4 * m) / (4 * m))
    q = np.roll(p, -1, axis=0)
    options = np.stack([np.stack([p[:, 0], q[:, 1]], 1), np.stack([q[:, 0], p[:, 1]], 1)])
    nearer = np.linalg.norm(options - p.mean(axis=0), axis=2).argmin(axis=0)
    return np.stack([p, options[nearer, np.arange(4 * m)]], axis=1).reshape(-1, 2)


def staircase_through_8m_points(curve, m):  # finer than asked
    return REFERENCE["staircase"](curve, 2 * m)


def staircase_starting_at_a_corner(curve, m):
    return np.roll(REFERENCE["staircase"](curve, m), 1, axis=0)


def staircase_clockwise_only(curve, m):  # the corner rule worked out on a clockwise ellipse
    p = curve.position(2 * np.pi * np.arange(4 * m) / (4 * m))
    q = np.roll(p, -1, axis=0)
    mid = (p + q) / 2 - p.mean(axis=0)
    first_or_third = mid[:, 0] * mid[:, 1] > 0  # quadrants I and III
    corner = np.where(first_or_third[:, None], np.stack([q[:, 0], p[:, 1]], 1), np.stack([p[:, 0], q[:, 1]], 1))
    return np.stack([p, corner], axis=1).reshape(-1, 2)


def staircase_about_the_origin(curve, m):  # "farther out" measured from the origin, not the centre
    p = curve.position(2 * np.pi * np.arange(4 * m) / (4 * m))
    q = np.roll(p, -1, axis=0)
    x = np.where(np.abs(p[:, 0]) > np.abs(q[:, 0]), p[:, 0], q[:, 0])
    y = np.where(np.abs(p[:, 1]) > np.abs(q[:, 1]), p[:, 1], q[:, 1])
    return np.stack([p, np.stack([x, y], axis=1)], axis=1).reshape(-1, 2)


def staircase_few_percent(curve, m):
    v = REFERENCE["staircase"](curve, m)
    return v.mean(axis=0) + 1.03 * (v - v.mean(axis=0))


def normals_by_complex_numbers(curve, method):  # another algorithm
    z = curve.vertices[:, 0] + 1j * curve.vertices[:, 1]
    e = np.roll(z, -1) - z
    e_prev = np.roll(e, 1)
    if method in ("bisector", "length-gradient"):
        n = 1j * (e_prev / abs(e_prev) + e / abs(e))
        if method == "length-gradient":
            n = e_prev / abs(e_prev) - e / abs(e)
    else:
        n = 1j * (e_prev + e)
    n = n / abs(n)
    return np.stack([n.real, n.imag], axis=1)


def normals_inward(curve, method):  # counter-clockwise convention: N = -J T
    return -REFERENCE["vertex_normals"](curve, method)


def normals_swapped(curve, method):  # area and length gradients confused
    swap = {"length-gradient": "area-gradient", "area-gradient": "length-gradient"}
    return REFERENCE["vertex_normals"](curve, swap.get(method, method))


def normals_bisector_as_weighted(curve, method):  # the length weights forgotten
    return REFERENCE["vertex_normals"](curve, "bisector" if method == "length-weighted" else method)


def normals_unnormalized(curve, method):
    N_prev, N_next = np.roll(curve.normals, 1, axis=0), curve.normals
    scale = 1 + 0.5 * np.abs(np.einsum("ij,ij->i", N_prev, N_next))
    return REFERENCE["vertex_normals"](curve, method) * scale[:, None]


def normals_tangential(curve, method):  # T instead of N: turned a quarter
    n = REFERENCE["vertex_normals"](curve, method)
    return np.stack([n[:, 1], -n[:, 0]], axis=1)


def normals_orientation_sign(curve, method):  # the gradient's direction taken as the bisector's
    if method == "length-gradient":  # times the orientation: right where every turn has one sign
        return REFERENCE["vertex_normals"](curve, "bisector") * np.sign(curve.signed_area)
    return REFERENCE["vertex_normals"](curve, method)


def normals_bisector_signed(curve, method):  # the bisector flipped at reflex vertices, like grad L
    return REFERENCE["vertex_normals"](curve, "length-gradient" if method == "bisector" else method)


# ------------------------------------------------------------------------ chapter 3


def turning_by_headings(vertices):  # another algorithm: differences of edge headings
    e = np.roll(vertices, -1, axis=0) - vertices
    heading = np.arctan2(e[:, 1], e[:, 0])
    turn = np.roll(heading, 1) - heading
    return np.pi - np.mod(np.pi - turn, 2 * np.pi)  # into (-pi, pi]


def turning_counterclockwise(vertices):  # the usual (counter-clockwise) sign
    return -REFERENCE["turning_angles"](vertices)


def turning_unsigned(vertices):  # arccos loses the sign
    return np.abs(REFERENCE["turning_angles"](vertices))


def turning_open(vertices):  # the closing edge dropped: no turn at v_0 and v_{n-1}
    psi = REFERENCE["turning_angles"](vertices)
    psi[[0, -1]] = 0.0
    return psi


def turning_off_by_one(vertices):  # the turn at v_i reported at v_{i+1}
    return np.roll(REFERENCE["turning_angles"](vertices), 1)


def turning_degrees(vertices):
    return np.degrees(REFERENCE["turning_angles"](vertices))


def turning_plain_atan2(vertices):  # -pi where the cross product is -0.0
    e_next = np.roll(vertices, -1, axis=0) - vertices
    e_prev = np.roll(e_next, 1, axis=0)
    cross = e_prev[:, 0] * e_next[:, 1] - e_prev[:, 1] * e_next[:, 0]
    return np.arctan2(-cross, (e_prev * e_next).sum(axis=1))


def turning_arccos_unclipped(vertices):  # the sign from the cross product, the size from arccos
    e_next = np.roll(vertices, -1, axis=0) - vertices
    e_prev = np.roll(e_next, 1, axis=0)
    cross = e_prev[:, 0] * e_next[:, 1] - e_prev[:, 1] * e_next[:, 0]
    cosine = (e_prev * e_next).sum(axis=1) / (np.linalg.norm(e_prev, axis=1) * np.linalg.norm(e_next, axis=1))
    with np.errstate(invalid="ignore"):  # NaN where rounding puts the cosine below -1
        return np.where(cross <= 0, 1, -1) * np.arccos(cosine)


def turning_few_percent(vertices):
    return 1.03 * REFERENCE["turning_angles"](vertices)


def rebuild_by_complex_numbers(psi, lengths, start, heading):  # another algorithm
    direction = np.exp(1j * (heading - np.cumsum(np.concatenate([[0.0], psi[1:]]))))
    z = complex(*start) + np.concatenate([[0], np.cumsum(lengths * direction)])
    return np.stack([z.real, z.imag], axis=1)


def rebuild_counterclockwise(psi, lengths, start, heading):
    return REFERENCE["rebuild"](-np.asarray(psi), lengths, start, heading)


def rebuild_off_by_one(psi, lengths, start, heading):  # turns at v_0 before the first edge
    theta = heading - np.cumsum(psi)
    steps = lengths[:, None] * np.stack([np.cos(theta), np.sin(theta)], axis=1)
    return np.asarray(start, float) + np.concatenate([[[0.0, 0.0]], np.cumsum(steps, axis=0)])


def rebuild_no_last_vertex(psi, lengths, start, heading):
    return REFERENCE["rebuild"](psi, lengths, start, heading)[:-1]


def rebuild_few_percent(psi, lengths, start, heading):
    return REFERENCE["rebuild"](psi, 1.03 * np.asarray(lengths), start, heading)


# ------------------------------------------------------------------------ chapter 4


def gradient_from_sine_curvature(vertices):  # another algorithm: eq. (3) times the bisector
    c = ddg.DiscreteCurve(vertices)
    return (2 * np.sin(c.turning_angles / 2) / c.dual_lengths)[:, None] * c.bisector_normals


def gradient_euclidean(vertices):  # forgets the weights A_i
    e = np.roll(vertices, -1, axis=0) - vertices
    T = e / np.linalg.norm(e, axis=1)[:, None]
    return np.roll(T, 1, axis=0) - T


def gradient_negated(vertices):
    return -REFERENCE["length_gradient"](vertices)


def gradient_open(vertices):  # the closing edge dropped
    return ddg.DiscreteCurve(vertices, closed=False).length_gradient()


def gradient_one_sided_weight(vertices):  # |e_{i+1/2}| instead of A_i
    e = np.roll(vertices, -1, axis=0) - vertices
    lengths = np.linalg.norm(e, axis=1)
    T = e / lengths[:, None]
    return (np.roll(T, 1, axis=0) - T) / lengths[:, None]


def gradient_shifted(vertices):  # rolled the wrong way: vertex i gets the gradient of v_{i+1}
    return np.roll(REFERENCE["length_gradient"](vertices), -1, axis=0)


def gradient_few_percent(vertices):
    return 1.03 * REFERENCE["length_gradient"](vertices)


# ------------------------------------------------------------------------ chapter 5


def minkowski_measured(curve, eps):  # another algorithm: measure it
    return shapely.Polygon(curve.vertices).buffer(eps, quad_segs=256).area


def minkowski_convex_formula(curve, eps):  # the lecture's formula everywhere
    return curve.signed_area + eps * curve.length + eps**2 / 2 * curve.turning_angles.sum()


def minkowski_offset_formula(curve, eps):  # the other inflation
    return curve.signed_area + eps * curve.length + eps**2 * np.tan(curve.turning_angles / 2).sum()


def minkowski_half_sector(curve, eps):  # a factor of 2 lost in the sector area
    psi = curve.turning_angles
    return curve.signed_area + eps * curve.length + eps**2 * np.where(psi >= 0, psi / 4, np.tan(psi / 2)).sum()


def minkowski_reflex_sign(curve, eps):  # the overlap added instead of removed
    psi = curve.turning_angles
    return curve.signed_area + eps * curve.length + eps**2 * np.where(psi >= 0, psi / 2, -np.tan(psi / 2)).sum()


def minkowski_no_strips(curve, eps):
    return REFERENCE["minkowski_area"](curve, eps) - eps * curve.length


def minkowski_few_percent(curve, eps):
    return 1.03 * REFERENCE["minkowski_area"](curve, eps)


# ------------------------------------------------------------------------ chapter 6


def circle_by_menger(curve):  # another algorithm: 4 area / (product of the sides)
    v = curve.vertices
    a, b = v - np.roll(v, 1, axis=0), np.roll(v, -1, axis=0) - v
    twice_area = a[:, 1] * b[:, 0] - a[:, 0] * b[:, 1]  # positive for clockwise turns
    sides = np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1) * np.linalg.norm(a + b, axis=1)
    return 2 * twice_area / sides


def circle_wrong_chord(curve):  # |v_{i+1} - v_i| instead of |v_{i+1} - v_{i-1}|
    return 2 * np.sin(curve.turning_angles) / curve.edge_lengths


def circle_sine_formula(curve):  # a neighbouring formula of the book
    return curve.curvature("sine")


def circle_unsigned(curve):
    return np.abs(REFERENCE["circle_curvature"](curve))


def circle_no_factor_two(curve):
    return REFERENCE["circle_curvature"](curve) / 2


def circle_counterclockwise(curve):
    return -REFERENCE["circle_curvature"](curve)


def circle_orientation_sign(curve):  # the sign of the whole polygon, not of each turn
    return np.abs(REFERENCE["circle_curvature"](curve)) * np.sign(curve.signed_area)


def circle_few_percent(curve):
    return 1.03 * REFERENCE["circle_curvature"](curve)


# ------------------------------------------------------------------------ chapter 7


def zigzag_numpy(b):  # the same, another way
    return float(np.clip(2 - b, -2, None))


def zigzag_measured(b):  # another algorithm: measure the slope
    ns = np.array([1024, 2048, 4096, 8192])
    errors = []
    for n in ns:
        theta = 2 * np.pi * np.arange(n) / n
        r = 1 + n**-b * (-1.0) ** np.arange(n)
        c = ddg.DiscreteCurve(np.stack([r * np.cos(theta), -r * np.sin(theta)], axis=1))
        errors.append(np.abs(c.curvature("angle") - 1).max())
    return np.polyfit(np.log(ns), np.log(errors), 1)[0]


def zigzag_no_floor(b):  # forgets the polygon's own error
    return 2 - b


def zigzag_threshold(b):  # the old answer: the threshold, not the exponent
    return 2.0


def zigzag_linear(b):
    return 1 - b


def zigzag_squared(b):
    return 2 - 2 * b


def zigzag_floor_at_three(b):  # right below b = 3 only
    return 2 - b if b < 3 else -2.0


def zigzag_floor_too_low(b):  # the polygon's own error taken a little too small
    return max(2 - b, -2.1)


def zigzag_no_floor_until_five(b):
    return 2 - b if b < 4.8 else -2.0


CATALOGUE = {
    "osculating_center": ([osculating_three_points], [osculating_outward, osculating_unsigned, osculating_no_reciprocal,
                                                     osculating_along_tangent, osculating_few_percent,
                                                     osculating_side_from_orientation,
                                                     osculating_side_from_first_point]),
    "staircase": ([staircase_by_coordinates], [staircase_inscribed, staircase_no_closing_corner,
                                               staircase_inner_corners, staircase_through_8m_points,
                                               staircase_starting_at_a_corner, staircase_few_percent,
                                               staircase_clockwise_only, staircase_about_the_origin]),
    "vertex_normals": ([normals_by_complex_numbers], [normals_inward, normals_swapped, normals_bisector_as_weighted,
                                                      normals_unnormalized, normals_tangential,
                                                      normals_bisector_signed, normals_orientation_sign]),
    "turning_angles": ([turning_by_headings], [turning_counterclockwise, turning_unsigned, turning_open,
                                               turning_off_by_one, turning_degrees, turning_plain_atan2,
                                               turning_arccos_unclipped, turning_few_percent]),
    "rebuild": ([rebuild_by_complex_numbers], [rebuild_counterclockwise, rebuild_off_by_one, rebuild_no_last_vertex,
                                               rebuild_few_percent]),
    "length_gradient": ([gradient_from_sine_curvature], [gradient_euclidean, gradient_negated, gradient_open,
                                                         gradient_one_sided_weight, gradient_shifted,
                                                         gradient_few_percent]),
    "minkowski_area": ([minkowski_measured], [minkowski_convex_formula, minkowski_offset_formula, minkowski_half_sector,
                                              minkowski_reflex_sign, minkowski_no_strips, minkowski_few_percent]),
    "circle_curvature": ([circle_by_menger], [circle_wrong_chord, circle_sine_formula, circle_unsigned,
                                              circle_no_factor_two, circle_counterclockwise, circle_orientation_sign,
                                              circle_few_percent]),
    "zigzag_exponent": ([zigzag_numpy, zigzag_measured], [zigzag_no_floor, zigzag_threshold, zigzag_linear,
                                                          zigzag_squared, zigzag_floor_at_three, zigzag_floor_too_low,
                                                          zigzag_no_floor_until_five]),
}
SCALAR = {"minkowski_area", "zigzag_exponent"}  # answers that return one number: no list version


def right_answers(name):
    answers = [reference(name), as_float32(name), *CATALOGUE[name][0]]
    return answers if name in SCALAR else answers + [as_list(name)]


def test_every_coding_exercise_of_the_book_has_a_check_and_a_catalogue():
    called = set()
    for nb in NOTEBOOKS:
        for cell in json.loads(nb.read_text())["cells"]:
            if "check" in cell["metadata"].get("tags", []):
                called |= set(re.findall(r"\b(check_\w+)\(", "".join(cell["source"])))
    assert called == set(checks.CHECKS) and set(checks.CHECKS.values()) == set(CATALOGUE) == set(REFERENCE)
    assert all(len(wrong) >= 4 for _, wrong in CATALOGUE.values())


@pytest.mark.parametrize("name", sorted(CATALOGUE))
def test_every_right_answer_passes_on_100_seeds(name):
    for answer in right_answers(name):
        failed = {seed: repr(f) for seed in SEEDS if not (f := checks.run(name, answer, seed, isolate=False))}
        assert not failed, f"{name}: a right answer failed on {len(failed)} seeds, e.g. {next(iter(failed.items()))}"


@pytest.mark.parametrize("name, wrong", [(n, w) for n, (_, ws) in sorted(CATALOGUE.items()) for w in ws],
                         ids=lambda x: getattr(x, "__name__", x))
def test_every_wrong_answer_fails_on_each_of_100_seeds(name, wrong):
    passed = [seed for seed in SEEDS if checks.run(name, wrong, seed, isolate=False)]
    assert not passed, f"{name} accepted {wrong.__name__} on seeds {passed[:10]}"


@pytest.mark.parametrize("name", sorted(CATALOGUE))
def test_isolated_checks_agree_and_the_starter_is_not_written_yet(name):
    check = getattr(checks, f"check_{name}")
    assert check(reference(name), seed=1), check(reference(name), seed=1)
    wrong = CATALOGUE[name][1][0]
    assert not check(wrong, seed=1) and wrong.__name__ in repr(check(wrong, seed=1))
    feedback = check(starter_of(name), seed=0)
    assert not feedback and "not written yet" in feedback.problem


def test_feedback_never_shows_the_solution():
    for name, (_, wrongs) in CATALOGUE.items():
        source = next(s for _, s in solution_cells() if re.search(rf"^def {name}\b", s, re.M))
        body = [line.strip() for line in source.split("\n")[1:] if len(line.strip()) > 12
                and not line.strip().startswith(("#", '"""'))]
        for wrong in wrongs:
            message = repr(checks.run(name, wrong, 0, isolate=False))
            assert not [line for line in body if line in message], (name, message)


def test_no_check_holds_the_solution_of_its_exercise():
    """The distinctive lines of every reference solution are absent from ddg/checks.py."""
    source = (ROOT / "ddg" / "checks.py").read_text()
    for _, solution in solution_cells():
        code = [line.strip() for line in solution.splitlines() if len(line.strip()) > 20
                and not line.strip().startswith(("#", '"""', "def ", "return n /"))]
        assert not [line for line in code if line in source], code
    assert "np.tan(psi / 2)" not in source and "np.where(psi >= 0" not in source  # the Minkowski formula


# ------------------------------------------------------------------ answers that misbehave


def test_an_answer_that_never_returns_gets_a_verdict_within_the_time_limit():
    def endless(vertices):
        while True:
            pass

    start = time.monotonic()
    feedback = checks.check_turning_angles(endless, seed=0)
    assert not feedback and "did not return within 10 s" in feedback.problem
    assert time.monotonic() - start < checks.TIME_LIMIT + 2


def test_the_quantity_the_exercise_asks_for_is_switched_off_while_the_answer_runs():
    for name, answer in (("turning_angles", lambda v: ddg.DiscreteCurve(v).turning_angles),
                         ("turning_angles", lambda v: ddg.DiscreteCurve(v).curvature("angle")
                          * ddg.DiscreteCurve(v).dual_lengths),
                         ("length_gradient", lambda v: ddg.DiscreteCurve(v).length_gradient()),
                         ("length_gradient", lambda v: -ddg.flow.velocity(ddg.DiscreteCurve(v), "sine")),
                         ("vertex_normals", lambda c, m: c.bisector_normals),
                         ("minkowski_area", lambda c, eps: c.inflated_area(eps))):
        feedback = checks.run(name, answer, 0)
        assert not feedback and "write yourself" in feedback.problem, feedback
    curve = ddg.regular_polygon(5)  # and everything is back afterwards
    assert np.allclose(curve.turning_angles, 2 * np.pi / 5) and curve.length_gradient().shape == (5, 2)


def test_the_verdict_does_not_depend_on_state_the_answer_can_reach():
    import inspect

    def tamper(vertices):  # make every requirement pass, and reseed the check's generator
        checks._require = lambda condition, message: None
        for frame in inspect.stack():
            for value in frame.frame.f_locals.values():
                if isinstance(value, np.random.Generator):
                    value.bit_generator.state = np.random.default_rng(0).bit_generator.state
        return np.zeros(len(vertices))

    feedback = checks.check_turning_angles(tamper, seed=3)
    assert not feedback and "sign convention" in feedback.problem
    assert checks._require.__module__ == "ddg.checks" and checks.check_turning_angles(reference("turning_angles"))


def test_crashing_exiting_and_odd_answers_are_reported_not_raised():
    import os
    import sys

    cases = [(lambda v: v[10**6], "raised IndexError"), (lambda v: os._exit(3), "ended the process"),
             (lambda v: sys.exit(1), "raised SystemExit"), (lambda v: "psi", "not real numbers"),
             (lambda v: np.zeros(len(v)) * 1j, "not real numbers"), (lambda v: [1.0], "shape"),
             (lambda v: np.full(len(v), np.nan), "NaN"), (2.0, "should be a function")]
    for answer, expected in cases:
        feedback = checks.check_turning_angles(answer, seed=0)
        assert not feedback and expected in feedback.problem, (expected, feedback)
    assert "✗" in checks.check_turning_angles(cases[0][0], seed=0)._repr_html_()


def test_what_an_answer_sends_back_or_leaves_behind_gets_a_verdict():
    import os
    import sys

    def pipe_end():  # the write end of the pipe its results go back through, from the caller's frame
        frame = sys._getframe(2)
        while "write" not in frame.f_locals:
            frame = frame.f_back
        return frame.f_locals["write"]

    def forger(data):
        def answer(vertices):
            os.write(pipe_end(), data)
            os._exit(0)
        return answer

    for data in (b"not json", b'{"x": 1}', b'{"timeout": "soon"}', b'[{"v": 1}]', b'[{"value": [[1, 2], [3]]}]',
                 b'[{"value": "1"}]'):
        feedback = checks.check_turning_angles(forger(data), seed=0)
        assert not feedback and ("not its results" in feedback.problem or "not an array" in feedback.problem), \
            (data, feedback)

    marker = pathlib.Path(os.environ.get("TMPDIR", "/tmp")) / f"ddg-check-grandchild-{os.getpid()}"

    def leaves_a_process(vertices):  # answers right away, but a process it started holds the pipe open
        if os.fork() == 0:
            marker.write_text(str(os.getpid()))
            time.sleep(30)
            os._exit(0)
        return REFERENCE["turning_angles"](vertices)

    start = time.monotonic()  # a time limit of 2 s, not the default 10 s: the wait is what is tested
    assert checks.answer_results("turning_angles", leaves_a_process, 0, limit=2.0) == {"timeout": 2.0}
    assert time.monotonic() - start < 4
    grandchild = int(marker.read_text())
    marker.unlink()
    time.sleep(0.2)
    stat = pathlib.Path(f"/proc/{grandchild}/stat")
    assert not stat.exists() or stat.read_text().split(") ")[-1].split()[0] == "Z", "the answer's process lives on"

    previous = np.seterr(all="raise")  # a notebook that makes numpy raise on 1/0: still a verdict
    try:
        feedback = checks.check_circle_curvature(lambda c: np.zeros(len(c)), seed=0)
    finally:
        np.seterr(**previous)
    assert not feedback and "radius" in feedback.problem

    def disguised(vertices):
        raise ValueError("\r✓ turning_angles passed 6 checks\x1b[8m")
    disguised.__name__ = "\r✓ passed\x1b[8m"
    shown = repr(checks.check_turning_angles(disguised, seed=0))
    assert shown.startswith("✗") and not any(ord(ch) < 32 or 127 <= ord(ch) < 160 for ch in shown), shown


def test_input_the_answer_changes_does_not_change_the_verdict():
    def vandal(vertices):  # changes its input in place, then answers right
        psi = REFERENCE["turning_angles"](vertices.copy())
        vertices[:] = 0.0
        return psi

    assert checks.check_turning_angles(vandal, seed=0)
    assert checks.run("turning_angles", vandal, 0, isolate=False)
