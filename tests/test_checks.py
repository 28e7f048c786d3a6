"""Homework checks: each accepts the book's reference solution and rejects the starter and plausible
wrong answers (the opposite sign convention, a missing factor, a dropped closing edge, ...).

Reference solutions are taken from the notebooks (code cells tagged ``solution``), so the book and
these tests cannot drift apart.
"""

import json
import pathlib
import re
import subprocess
import sys

import numpy as np
import pytest

import ddg
from ddg import checks, edition, smooth

ROOT = pathlib.Path(__file__).resolve().parents[1]
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


# ------------------------------------------------------------------ wrong answers, by exercise


def osculating_outward(curve, t):  # the opposite sign: centre on the outside
    return curve.position(t) + curve.normal(t) / curve.curvature(t)[:, None]


def osculating_unsigned(curve, t):  # |kappa|: right for clockwise curves only
    return curve.position(t) - curve.normal(t) / np.abs(curve.curvature(t))[:, None]


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


def normals_inward(curve, method):  # counter-clockwise convention: N = -J T
    return -REFERENCE["vertex_normals"](curve, method)


def normals_swapped(curve, method):  # area and length gradients confused
    swap = {"length-gradient": "area-gradient", "area-gradient": "length-gradient"}
    return REFERENCE["vertex_normals"](curve, swap.get(method, method))


def normals_unnormalized(curve, method):
    N_prev, N_next = np.roll(curve.normals, 1, axis=0), curve.normals
    return REFERENCE["vertex_normals"](curve, method) * (1 + 0.5 * np.abs(np.einsum("ij,ij->i", N_prev, N_next)))[:, None]


def turning_counterclockwise(vertices):  # the usual (counter-clockwise) sign
    return -REFERENCE["turning_angles"](vertices)


def turning_unsigned(vertices):  # arccos loses the sign
    return np.abs(REFERENCE["turning_angles"](vertices))


def turning_open(vertices):  # the closing edge dropped: no turn at v_0 and v_{n-1}
    psi = REFERENCE["turning_angles"](vertices)
    psi[[0, -1]] = 0.0
    return psi


def rebuild_counterclockwise(psi, lengths, start, heading):
    return REFERENCE["rebuild"](-np.asarray(psi), lengths, start, heading)


def rebuild_off_by_one(psi, lengths, start, heading):  # turns at v_0 before the first edge
    theta = heading - np.cumsum(psi)
    steps = lengths[:, None] * np.stack([np.cos(theta), np.sin(theta)], axis=1)
    return np.asarray(start, float) + np.concatenate([[[0.0, 0.0]], np.cumsum(steps, axis=0)])


def gradient_euclidean(vertices):  # forgets the weights A_i
    e = np.roll(vertices, -1, axis=0) - vertices
    T = e / np.linalg.norm(e, axis=1)[:, None]
    return np.roll(T, 1, axis=0) - T


def gradient_negated(vertices):
    return -REFERENCE["length_gradient"](vertices)


def gradient_open(vertices):  # the closing edge dropped
    return ddg.DiscreteCurve(vertices, closed=False).length_gradient()


def minkowski_lecture(curve, eps):  # the convex formula everywhere
    return curve.inflated_area(eps, "minkowski")


def minkowski_half(curve, eps):  # a factor of 2 lost in the sector area
    return curve.signed_area + eps * curve.length + eps**2 / 4 * curve.turning_angles.sum()


def minkowski_offset(curve, eps):  # the other inflation
    return curve.inflated_area(eps, "offset")


def circle_unsigned(curve):
    return np.abs(REFERENCE["circle_curvature"](curve))


def circle_no_factor_two(curve):
    return REFERENCE["circle_curvature"](curve) / 2


def circle_counterclockwise(curve):
    return -REFERENCE["circle_curvature"](curve)


WRONG = {
    "check_osculating_center": ("osculating_center", [osculating_outward, osculating_unsigned]),
    "check_staircase": ("staircase", [staircase_inscribed, staircase_no_closing_corner, staircase_inner_corners]),
    "check_vertex_normals": ("vertex_normals", [normals_inward, normals_swapped, normals_unnormalized]),
    "check_turning_angles": ("turning_angles", [turning_counterclockwise, turning_unsigned, turning_open]),
    "check_rebuild": ("rebuild", [rebuild_counterclockwise, rebuild_off_by_one]),
    "check_length_gradient": ("length_gradient", [gradient_euclidean, gradient_negated, gradient_open]),
    "check_minkowski_area": ("minkowski_area", [minkowski_lecture, minkowski_half, minkowski_offset]),
    "check_circle_curvature": ("circle_curvature", [circle_unsigned, circle_no_factor_two, circle_counterclockwise]),
}


def test_every_coding_exercise_has_a_check_and_wrong_answers():
    called = set()
    for nb in NOTEBOOKS:
        for cell in json.loads(nb.read_text())["cells"]:
            if "check" in cell["metadata"].get("tags", []):
                called |= set(re.findall(r"\b(check_\w+)\(", "".join(cell["source"])))
    assert called == set(WRONG) | {"check_zigzag_exponent"}
    assert len(called) >= 8


@pytest.mark.parametrize("check", sorted(WRONG))
@pytest.mark.parametrize("seed", range(3))
def test_check_accepts_the_reference_solution(check, seed):
    name, _ = WRONG[check]
    feedback = getattr(checks, check)(REFERENCE[name], seed=seed)
    assert feedback, feedback


@pytest.mark.parametrize("check", sorted(WRONG))
def test_check_rejects_the_starter(check):
    name, _ = WRONG[check]
    feedback = getattr(checks, check)(starter_of(name), seed=0)
    assert not feedback and "not written yet" in feedback.problem


@pytest.mark.parametrize("check, wrong", [(c, w) for c, (_, ws) in sorted(WRONG.items()) for w in ws],
                         ids=lambda x: getattr(x, "__name__", x))
def test_check_rejects_a_plausible_wrong_answer(check, wrong):
    for seed in range(3):
        feedback = getattr(checks, check)(wrong, seed=seed)
        assert not feedback, f"{check} accepted {wrong.__name__} (seed {seed})"
        assert wrong.__name__ in repr(feedback)


def test_feedback_never_shows_the_solution():
    for check, (name, wrongs) in WRONG.items():
        reference = next(s for _, s in solution_cells() if re.search(rf"^def {name}\b", s, re.M))
        body_lines = [l.strip() for l in reference.split("\n")[1:] if l.strip() and not l.strip().startswith(("#", '"""'))]
        for wrong in wrongs:
            message = repr(getattr(checks, check)(wrong, seed=0))
            assert not any(line in message for line in body_lines if len(line) > 12), (check, message)


def test_zigzag_threshold_check():
    assert checks.check_zigzag_exponent(2.0, seed=0)
    for wrong in (1.0, 3.0, 0.5):
        assert not checks.check_zigzag_exponent(wrong, seed=0)
    assert not checks.check_zigzag_exponent("two", seed=0)


def test_a_crashing_answer_is_reported_not_raised():
    def broken(vertices):
        return vertices[10**6]

    feedback = checks.check_turning_angles(broken, seed=0)
    assert not feedback and "raised IndexError" in feedback.problem
    assert "✗ broken" in repr(feedback) and "✗" in feedback._repr_html_()


# ------------------------------------------------------------------ the student edition


@pytest.fixture(scope="module")
def student(tmp_path_factory):
    out = tmp_path_factory.mktemp("edition") / "student"
    subprocess.run([sys.executable, "-m", "ddg.edition", "--root", str(ROOT), "--out", str(out)], check=True,
                   capture_output=True)
    return out


def outside_solutions(cells):
    """The text of the cells outside {solution-start} ... {solution-end} blocks."""
    text, inside = [], False
    for cell in cells:
        source = "".join(cell["source"])
        opens, closes = "{solution-start}" in source, "{solution-end}" in source
        if opens:
            inside = not closes
        elif closes:
            inside = False
        elif not inside:
            text.append(source)
    return "\n".join(text)


def test_student_edition_keeps_exercises_and_drops_solutions(student):
    for nb in NOTEBOOKS:
        ours = json.loads(nb.read_text())["cells"]
        theirs = json.loads((student / "book" / nb.name).read_text())["cells"]
        text = "\n".join("".join(c["source"]) for c in theirs)
        assert "solution-start" not in text and "solution-end" not in text, nb.name
        exercises = len(re.findall(r"\{exercise\}", nb.read_text()))
        assert len(re.findall(r"\{exercise\}", text)) == exercises >= 3, nb.name
        shared = outside_solutions(ours)  # what the chapter shows anyway is no leak
        for _, source in solution_cells():
            body = [l.strip() for l in source.split("\n")[1:] if l.strip() and not l.strip().startswith(("#", '"""', "def "))]
            leaked = [line for line in body if len(line) > 15 and line in text and line not in shared]
            assert not leaked, (nb.name, leaked)


def test_student_starters_raise_until_written(student):
    nb = json.loads((student / "book" / "03_winding_number.ipynb").read_text())
    starters = ["".join(c["source"]) for c in nb["cells"] if "starter" in c["metadata"].get("tags", [])]
    assert len(starters) == 2
    env = {"np": np}
    exec(starters[0], env)  # noqa: S102
    with pytest.raises(NotImplementedError):
        env["turning_angles"](np.eye(3))
    assert not checks.check_turning_angles(env["turning_angles"], seed=0)


def test_student_edition_builds(student):
    result = subprocess.run([str(pathlib.Path(sys.executable).parent / "jupyter-book"), "build", str(student)],
                            capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-3000:]
    page = (student / "_build" / "html" / "book" / "03_winding_number.html").read_text()
    assert "Turning angles, by hand" in page and "np.arctan2(-cross, dot)" not in page
