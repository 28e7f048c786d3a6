"""The catalogue of answers the checks must judge: right ones written in several ways, and the
mistakes students make, each written as a student would write it, with the words the check's
message must contain. tests/unit/test_checks.py runs every entry on 100 seeds.

A new exercise joins at the end (CONTRIBUTING.md, "Adding an exercise with a check"):
``CATALOGUE["name"] = ([right answers besides the book's own], {mistake: (answer, words)})``,
and ``SCALAR.add("name")`` when the answer is one number.
"""

import json
import pathlib
import re

import numpy as np

import ddg
from ddg import smooth
from instructor import edition

ROOT = pathlib.Path(__file__).resolve().parents[2]
NOTEBOOKS = sorted((ROOT / "book").glob("*.ipynb"))


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


def named(name, function):
    function.__name__ = name
    return function


def ref(name):
    return lambda *args: REFERENCE[name](*args)


def as_float32(name):
    return named(f"{name}_float32", lambda *args: np.asarray(REFERENCE[name](*args), dtype=np.float32))


def as_list(name):
    return named(f"{name}_list", lambda *args: np.asarray(REFERENCE[name](*args)).tolist())


def times(name, factor):
    return named(f"{name}_few_percent", lambda *args: factor * np.asarray(REFERENCE[name](*args)))


def rolled(name, shift):
    return named(f"{name}_rolled_{shift}", lambda *args: np.roll(REFERENCE[name](*args), shift, axis=0))


# ------------------------------------------------------------------------ chapter 1


def osculating_three_points(curve, t, h=1e-4):  # another algorithm: the circle through nearby points
    p, q, r = (curve.position(t + d) for d in (-h, 0, h))
    a, b = q - p, r - p
    d = 2 * (a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])
    ux = (b[:, 1] * (a**2).sum(1) - a[:, 1] * (b**2).sum(1)) / d
    uy = (a[:, 0] * (b**2).sum(1) - b[:, 0] * (a**2).sum(1)) / d
    return p + np.stack([ux, uy], axis=1)


def osculating_loop(curve, t):  # a loop over the parameters
    return np.array([curve.position(s) - curve.normal(s) / curve.curvature(s) for s in t])


OSCULATING = {
    "outward": (lambda c, t: c.position(t) + c.normal(t) / c.curvature(t)[:, None], "wrong side"),
    "unsigned": (lambda c, t: c.position(t) - c.normal(t) / np.abs(c.curvature(t))[:, None], "signed kappa"),
    "no_reciprocal": (lambda c, t: c.position(t) - c.normal(t) * c.curvature(t)[:, None], "1/|kappa|"),
    "along_tangent": (lambda c, t: c.position(t) - c.tangent(t) / c.curvature(t)[:, None], "normal line"),
    "side_of_the_curve": (lambda c, t: c.position(t) - np.sign(c.total_curvature()) * c.normal(t)
                          / np.abs(c.curvature(t))[:, None], "belongs to each point"),
    "side_of_first_point": (lambda c, t: c.position(t) - np.sign(c.curvature(t)[0]) * c.normal(t)
                            / np.abs(c.curvature(t))[:, None], "belongs to each point"),
    "vector": (lambda c, t: -c.normal(t) / c.curvature(t)[:, None], "is a point"),
}

# ------------------------------------------------------------------------ chapter 2


def staircase_by_coordinates(curve, m):  # another algorithm: x and y from the point farther out
    p = curve.position(2 * np.pi * np.arange(4 * m) / (4 * m))
    q, c = np.roll(p, -1, axis=0), p.mean(axis=0)
    x = np.where(np.abs(p[:, 0] - c[0]) > np.abs(q[:, 0] - c[0]), p[:, 0], q[:, 0])
    y = np.where(np.abs(p[:, 1] - c[1]) > np.abs(q[:, 1] - c[1]), p[:, 1], q[:, 1])
    return np.stack([p, np.stack([x, y], axis=1)], axis=1).reshape(-1, 2)


def staircase_corners(curve, m, choose):
    p = curve.position(2 * np.pi * np.arange(4 * m) / (4 * m))
    q = np.roll(p, -1, axis=0)
    return np.stack([p, choose(p, q, p.mean(axis=0))], axis=1).reshape(-1, 2)


def inner(p, q, c):
    options = np.stack([np.stack([p[:, 0], q[:, 1]], 1), np.stack([q[:, 0], p[:, 1]], 1)])
    return options[np.linalg.norm(options - c, axis=2).argmin(axis=0), np.arange(len(p))]


def by_quadrant(p, q, c):  # the corner rule worked out on a clockwise ellipse
    mid = (p + q) / 2 - c
    odd = mid[:, 0] * mid[:, 1] > 0
    return np.where(odd[:, None], np.stack([q[:, 0], p[:, 1]], 1), np.stack([p[:, 0], q[:, 1]], 1))


def about_origin(p, q, c):  # "farther out" from the origin, not the centre
    x = np.where(np.abs(p[:, 0]) > np.abs(q[:, 0]), p[:, 0], q[:, 0])
    y = np.where(np.abs(p[:, 1]) > np.abs(q[:, 1]), p[:, 1], q[:, 1])
    return np.stack([x, y], axis=1)


STAIRCASE = {
    "inscribed": (lambda curve, m: curve.position(2 * np.pi * np.arange(4 * m) / (4 * m)), "corner between each two"),
    "no_closing_corner": (lambda curve, m: REFERENCE["staircase"](curve, m)[:-1], "is missing"),
    "inner_corners": (lambda curve, m: staircase_corners(curve, m, inner), "farther from the centre"),
    "through_8m_points": (lambda curve, m: REFERENCE["staircase"](curve, 2 * m), "4m points"),
    "starting_at_a_corner": (lambda curve, m: np.roll(REFERENCE["staircase"](curve, m), 1, axis=0),
                             "v[0] should be the first point"),
    "clockwise_only": (lambda curve, m: staircase_corners(curve, m, by_quadrant), "clockwise ellipse only"),
    "about_the_origin": (lambda curve, m: staircase_corners(curve, m, about_origin), "not from the origin"),
}


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


def normals_instead(swap):
    return lambda curve, method: REFERENCE["vertex_normals"](curve, swap.get(method, method))


def normals_unnormalized(curve, method):
    N_prev, N_next = np.roll(curve.normals, 1, axis=0), curve.normals
    scale = 1 + 0.5 * np.abs(np.einsum("ij,ij->i", N_prev, N_next))
    return REFERENCE["vertex_normals"](curve, method) * scale[:, None]


def normals_tangential(curve, method):
    n = REFERENCE["vertex_normals"](curve, method)
    return np.stack([n[:, 1], -n[:, 0]], axis=1)


def normals_orientation_sign(curve, method):
    if method == "length-gradient":
        return REFERENCE["vertex_normals"](curve, "bisector") * np.sign(curve.signed_area)
    return REFERENCE["vertex_normals"](curve, method)


NORMALS = {
    "inward": (lambda curve, method: -REFERENCE["vertex_normals"](curve, method), "inward"),
    "swapped": (normals_instead({"length-gradient": "area-gradient", "area-gradient": "length-gradient"}), "swapped"),
    "bisector_as_weighted": (normals_instead({"length-weighted": "bisector"}), "length-weighted"),
    "unnormalized": (normals_unnormalized, "unit vectors"),
    "tangential": (normals_tangential, "tangent direction"),
    "bisector_signed": (normals_instead({"bisector": "length-gradient"}), "turns round"),
    "orientation_sign": (normals_orientation_sign, "vertex by vertex"),
}

# ------------------------------------------------------------------------ chapter 3


def turning_by_headings(vertices):  # another algorithm: differences of edge headings, wrapped
    e = np.roll(vertices, -1, axis=0) - vertices
    heading = np.arctan2(e[:, 1], e[:, 0])
    turn = np.roll(heading, 1) - heading
    return np.pi - np.mod(np.pi - turn, 2 * np.pi)


def turning_loop(vertices):  # a loop, as a student might start
    n, result = len(vertices), []
    for i in range(n):
        a = np.subtract(vertices[i], vertices[i - 1], dtype=float)
        b = np.subtract(vertices[(i + 1) % n], vertices[i], dtype=float)
        angle = np.arctan2(a[1] * b[0] - a[0] * b[1], a @ b)
        result.append(np.pi if angle == -np.pi else angle)
    return result


def turning_unwrapped(vertices):  # differences of headings, not brought into (-pi, pi]
    e = np.roll(vertices, -1, axis=0) - vertices
    heading = np.arctan2(e[:, 1], e[:, 0])
    return np.roll(heading, 1) - heading


def turning_in_place(vertices):  # divides the (integer) input in place
    e = np.roll(vertices, -1, axis=0) - vertices
    e //= 1
    e = e / np.linalg.norm(e, axis=1)[:, None]
    a = np.roll(e, 1, axis=0)
    return np.arctan2(a[:, 1] * e[:, 0] - a[:, 0] * e[:, 1], (a * e).sum(axis=1))


def turning_in_place_float(vertices):
    e = np.roll(vertices, -1, axis=0) - vertices
    e /= np.linalg.norm(e, axis=1)[:, None]  # fails on integer input
    a = np.roll(e, 1, axis=0)
    psi = np.arctan2(a[:, 1] * e[:, 0] - a[:, 0] * e[:, 1], (a * e).sum(axis=1))
    return np.where(psi == -np.pi, np.pi, psi)


def turning_open(vertices):
    psi = REFERENCE["turning_angles"](vertices)
    psi[[0, -1]] = 0.0
    return psi


def turning_plain_atan2(vertices):
    e_next = np.roll(vertices, -1, axis=0) - vertices
    e_prev = np.roll(e_next, 1, axis=0)
    cross = e_prev[:, 0] * e_next[:, 1] - e_prev[:, 1] * e_next[:, 0]
    return np.arctan2(-cross, (e_prev * e_next).sum(axis=1))


def turning_arccos_unclipped(vertices):
    e_next = np.roll(vertices, -1, axis=0) - vertices
    e_prev = np.roll(e_next, 1, axis=0)
    cross = e_prev[:, 0] * e_next[:, 1] - e_prev[:, 1] * e_next[:, 0]
    cosine = (e_prev * e_next).sum(axis=1) / (np.linalg.norm(e_prev, axis=1) * np.linalg.norm(e_next, axis=1))
    with np.errstate(invalid="ignore"):
        return np.where(cross <= 0, 1, -1) * np.arccos(cosine)


TURNING = {
    "counterclockwise": (lambda v: -REFERENCE["turning_angles"](v), "counter-clockwise sign"),
    "unsigned": (lambda v: np.abs(REFERENCE["turning_angles"](v)), "sign is lost"),
    "open": (turning_open, "first and last vertices"),
    "off_by_one": (rolled("turning_angles", 1), "vertex after"),
    "off_by_one_backwards": (rolled("turning_angles", -1), "vertex before"),
    "degrees": (lambda v: np.degrees(REFERENCE["turning_angles"](v)), "degrees"),
    "plain_atan2": (turning_plain_atan2, "arctan2(-0.0, -1)"),
    "arccos_unclipped": (turning_arccos_unclipped, "arccos"),
    "unwrapped": (turning_unwrapped, "outside (-pi, pi]"),
    "in_place_on_integers": (turning_in_place_float, "integers"),
}


def rebuild_by_complex_numbers(psi, lengths, start, heading):  # another algorithm
    direction = np.exp(1j * (heading - np.cumsum(np.concatenate([[0.0], psi[1:]]))))
    z = complex(*start) + np.concatenate([[0], np.cumsum(lengths * direction)])
    return np.stack([z.real, z.imag], axis=1)


def rebuild_off_by_one(psi, lengths, start, heading):  # turns at v_0 before the first edge
    theta = heading - np.cumsum(psi)
    steps = lengths[:, None] * np.stack([np.cos(theta), np.sin(theta)], axis=1)
    return np.asarray(start, float) + np.concatenate([[[0.0, 0.0]], np.cumsum(steps, axis=0)])


REBUILD = {
    "counterclockwise": (lambda psi, lengths, start, heading: REFERENCE["rebuild"](-np.asarray(psi), lengths, start,
                                                                                   heading), "wrong way"),
    "off_by_one": (rebuild_off_by_one, "first turn to make is psi_1"),
    "no_last_vertex": (lambda *args: REFERENCE["rebuild"](*args)[:-1], "v_n as well"),
    "heading_clockwise": (lambda psi, lengths, start, heading: REFERENCE["rebuild"](psi, lengths, start, -heading),
                          "counter-clockwise from the x-axis"),
    "from_the_origin": (lambda psi, lengths, start, heading: REFERENCE["rebuild"](psi, lengths, (0.0, 0.0), heading),
                        "starts at the origin"),
    "x_and_y_swapped": (lambda *args: REFERENCE["rebuild"](*args)[:, ::-1], "swapped"),
}

# ------------------------------------------------------------------------ chapter 4


def gradient_loop(vertices):  # a loop over the vertices
    v, n = np.asarray(vertices, dtype=float), len(vertices)
    out = np.zeros((n, 2))
    for i in range(n):
        a, b = v[i] - v[i - 1], v[(i + 1) % n] - v[i]
        out[i] = (a / np.linalg.norm(a) - b / np.linalg.norm(b)) / ((np.linalg.norm(a) + np.linalg.norm(b)) / 2)
    return out


def gradient_parts(vertices, weight):
    e = np.roll(vertices, -1, axis=0) - vertices
    lengths = np.linalg.norm(e, axis=1)
    T = e / lengths[:, None]
    return (np.roll(T, 1, axis=0) - T) / weight(lengths)[:, None]


GRADIENT = {
    "euclidean": (lambda v: gradient_parts(v, lambda l: np.ones_like(l)), "weights are missing"),
    "negated": (lambda v: -REFERENCE["length_gradient"](v), "wrong way"),
    "open": (lambda v: ddg.DiscreteCurve(v, closed=False).length_gradient(), "first and last vertices"),
    "one_sided_weight": (lambda v: gradient_parts(v, lambda l: l), "|e_(i+1/2)|"),
    "shifted": (rolled("length_gradient", -1), "vertex before"),
    "sum_not_average": (lambda v: gradient_parts(v, lambda l: l + np.roll(l, 1)), "factor of 2"),
    "unit_vectors": (lambda v: (g := REFERENCE["length_gradient"](v)) / np.linalg.norm(g, axis=1)[:, None],
                     "length 1"),
}

# ------------------------------------------------------------------------ chapter 5


def minkowski_parts(curve, eps, convex, reflex):
    psi = curve.turning_angles
    corners = convex(psi[psi > 0]).sum() + reflex(psi[psi < 0]).sum()
    return curve.signed_area + eps * curve.length + eps**2 * corners


MINKOWSKI = {
    "convex_formula": (lambda c, e: c.signed_area + e * c.length + e**2 / 2 * c.turning_angles.sum(),
                       "reflex corners"),
    "offset_formula": (lambda c, e: c.signed_area + e * c.length + e**2 * np.tan(c.turning_angles / 2).sum(),
                       "offset"),
    "half_sector": (lambda c, e: minkowski_parts(c, e, lambda p: p / 4, lambda p: np.tan(p / 2)), "factor of 2"),
    "reflex_sign": (lambda c, e: minkowski_parts(c, e, lambda p: p / 2, lambda p: -np.tan(p / 2)), "not added"),
    "overlap_ignored": (lambda c, e: minkowski_parts(c, e, lambda p: p / 2, lambda p: 0 * p), "counted twice"),
    "no_strips": (lambda c, e: REFERENCE["minkowski_area"](c, e) - e * c.length, "rectangles on the edges"),
}

# ------------------------------------------------------------------------ chapter 6


def circle_by_menger(curve):  # another algorithm: 4 area / (product of the sides)
    v = curve.vertices
    a, b = v - np.roll(v, 1, axis=0), np.roll(v, -1, axis=0) - v
    twice_area = a[:, 1] * b[:, 0] - a[:, 0] * b[:, 1]
    sides = np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1) * np.linalg.norm(a + b, axis=1)
    return 2 * twice_area / sides


def circle_by_sine(curve):  # 1/R = 2 sin(psi) / chord, computed with sin of psi: NaN-free, but inf
    v = curve.vertices
    chord = np.linalg.norm(np.roll(v, -1, axis=0) - np.roll(v, 1, axis=0), axis=1)
    with np.errstate(divide="ignore"):
        return chord / (2 * np.sin(curve.turning_angles))


CIRCLE = {
    "wrong_chord": (lambda c: 2 * np.sin(c.turning_angles) / c.edge_lengths, "chord is wrong"),
    "sine_formula": (lambda c: c.curvature("sine"), "sine formula"),
    "unsigned": (lambda c: np.abs(REFERENCE["circle_curvature"](c)), "negative where"),
    "no_factor_two": (lambda c: REFERENCE["circle_curvature"](c) / 2, "factor of 2"),
    "counterclockwise": (lambda c: -REFERENCE["circle_curvature"](c), "positive where"),
    "orientation_sign": (lambda c: np.abs(REFERENCE["circle_curvature"](c)) * np.sign(c.signed_area), "each turn"),
    "radius": (circle_by_sine, "radius R"),
}

# ------------------------------------------------------------------------ chapter 7

ZIGZAG = {
    "no_floor": (lambda b: 2 - b, "cannot fall faster"),
    "threshold": (lambda b: 2.0, "same number for every b"),
    "linear": (lambda b: 1 - b, "one power of n too few"),
    "squared": (lambda b: 2 - 2 * b, "enters once"),
    "sign": (lambda b: b - 2, "the sign"),
    "floor_at_three": (lambda b: 2 - b if b < 3 else -2.0, "from b = 4 on"),
}

CATALOGUE = {  # exercise: (right answers besides the reference, {mistake: (answer, words)}, generic wrong)
    "osculating_center": ([osculating_three_points, osculating_loop], OSCULATING),
    "staircase": ([staircase_by_coordinates], STAIRCASE),
    "vertex_normals": ([normals_by_complex_numbers], NORMALS),
    "turning_angles": ([turning_by_headings, turning_loop], TURNING),
    "rebuild": ([rebuild_by_complex_numbers], REBUILD),
    "length_gradient": ([gradient_loop], GRADIENT),
    "minkowski_area": ([], MINKOWSKI),
    "circle_curvature": ([circle_by_menger], CIRCLE),
    "zigzag_exponent": ([named("zigzag_numpy", lambda b: float(np.clip(2 - b, -2, None)))], ZIGZAG),
}
SCALAR = {"minkowski_area", "zigzag_exponent"}  # answers that return one number: no list version


# ------------------------------------------------------------------------ two mistakes at once


def both(name, change):
    """The reference answer of ``name`` with its result changed by ``change(result, *args)``."""
    return lambda *args: change(np.asarray(REFERENCE[name](*args), dtype=float), *args)


def open_ends(result):
    result = np.array(result)
    result[[0, -1]] = 0.0
    return result


def minus_pi(result):
    return np.where(result == np.pi, -np.pi, result)


def mirrored_rebuild(psi, lengths, start, heading):  # the turns added to the heading, not subtracted
    steps = lengths * np.exp(1j * (heading + np.cumsum(np.r_[0.0, psi[1:]])))
    z = complex(*start) + np.r_[0, np.cumsum(steps)]
    return np.stack([z.real, z.imag], axis=1)


PAIRS = {  # exercise: {pair: (answer, [words of the first mistake, words of the second])}
    "turning_angles": {
        "degrees_and_after": (both("turning_angles", lambda r, v: np.roll(np.degrees(r), 1)), ["degrees", "vertex after"]),
        "counterclockwise_and_open": (both("turning_angles", lambda r, v: open_ends(-r)),
                                      ["measured clockwise", "first and last vertices"]),
        "minus_pi_and_open": (both("turning_angles", lambda r, v: open_ends(minus_pi(r))),
                              ["turns straight back", "first and last vertices"]),
        "unsigned_and_before": (both("turning_angles", lambda r, v: np.roll(np.abs(r), -1)),
                                ["sign is lost", "vertex before"]),
        "degrees_and_ends_missing": (both("turning_angles", lambda r, v: np.degrees(r)[1:-1]),
                                     ["degrees", "wrap-around"]),
    },
    "length_gradient": {
        "sign_and_after": (both("length_gradient", lambda r, v: np.roll(-r, 1, axis=0)), ["wrong way", "vertex after"]),
        "euclidean_and_ends_missing": (
            both("length_gradient", lambda r, v: (r * ddg.DiscreteCurve(v).dual_lengths[:, None])[1:-1]),
            ["weights are missing", "wrap-around"]),
    },
    "circle_curvature": {
        "counterclockwise_and_after": (both("circle_curvature", lambda r, c: np.roll(-r, 1)), ["the sign", "vertex after"]),
        "half_and_open": (both("circle_curvature", lambda r, c: open_ends(r / 2)), ["factor of 2", "first and last"]),
    },
    "vertex_normals": {
        "inward_and_open": (both("vertex_normals", lambda r, c, m: open_ends(-r)), ["inward", "first and last"]),
    },
    "rebuild": {
        "counterclockwise_and_no_last_vertex": (lambda *args: mirrored_rebuild(*args)[:-1], ["wrong way", "v_n"]),
    },
    "staircase": {
        "inner_corners_and_starting_at_a_corner": (
            lambda curve, m: np.roll(staircase_corners(curve, m, inner), 1, axis=0),
            ["inside the ellipse", "v[0] should be"]),
    },
    "osculating_center": {
        "outward_and_vector": (lambda curve, t: curve.position(t) + curve.normal(t) / curve.curvature(t)[:, None]
                               - curve.position(t), ["wrong side", "is a point"]),
    },
}
