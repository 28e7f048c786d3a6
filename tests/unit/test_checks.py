"""Homework checks tell right from wrong, and say why: the catalogue, on 100 seeds each.

For every coding exercise the catalogue lists right answers written in different ways (the book's
reference solution from its notebook, the same returning float32 or a list, with a loop, another
algorithm) and the mistakes students make, each written as a student would write it, with the
words the check's message must contain. On each of 100 seeds of hidden input (the grader's, judged
with the answer key) and on every public set (the students' own checks, judged with the data that
ships with ``ddg``) every right answer passes and every wrong one fails with a message naming its
mistake.
"""

import json
import pathlib
import re

import numpy as np
import pytest
import shapely
from catalogue import CATALOGUE, PAIRS, REFERENCE, SCALAR, as_float32, as_list, named, ref, solution_cells, starter_of, times

from ddg import checks
from instructor import references

ROOT = pathlib.Path(__file__).resolve().parents[2]
NOTEBOOKS = sorted((ROOT / "book").glob("*.ipynb"))
SEEDS = range(100)


def verdicts(name, answer):
    """``{where: feedback}`` on 100 seeds of hidden input and on every public set."""
    found = {f"seed {seed}": references.run(name, answer, seed, isolate=False) for seed in SEEDS}
    found.update({f"public set {k}": checks.run(name, answer, k, isolate=False) for k in range(references.PUBLIC_SETS)})
    return found


def right_answers(name):
    answers = [named(name, ref(name)), as_float32(name), *CATALOGUE[name][0]]
    return answers if name in SCALAR else answers + [as_list(name)]


def test_every_coding_exercise_has_a_check_and_six_catalogued_mistakes():
    called = set()
    for nb in NOTEBOOKS:
        for cell in json.loads(nb.read_text())["cells"]:
            if "check" in cell["metadata"].get("tags", []):
                called |= set(re.findall(r"\b(check_\w+)\(", "".join(cell["source"])))
    guide = "see CONTRIBUTING.md, 'Adding an exercise with a check'"
    for nb in NOTEBOOKS:  # the grader grades what the notebook's metadata lists
        data = json.loads(nb.read_text())
        in_cells = {c for cell in data["cells"] if "check" in cell["metadata"].get("tags", [])
                    for c in re.findall(r"\b(check_\w+)\(", "".join(cell["source"]))}
        graded = {e["check"] for e in data["metadata"].get("ddg", {}).get("exercises", {}).values()}
        assert in_cells == graded, f"{nb.name}: checks {in_cells} but metadata ddg.exercises {graded} ({guide})"
    exercises = set(checks.EXERCISES)
    for what, names in (("no cell tagged `check` calling its check in a chapter", exercises - {
                            checks.CHECKS[c] for c in called if c in checks.CHECKS}),
                        ("no reference solution (a cell tagged `solution`) in a chapter", exercises - set(REFERENCE)),
                        ("no answer key (EXPECTED) in instructor/references.py", exercises - set(references.EXPECTED)),
                        ("no public input: run python -m instructor.references", exercises - set(
                            json.loads(checks.PUBLIC.read_text()))),
                        ("no entry in tests/unit/catalogue.py", exercises - set(CATALOGUE)),
                        ("a catalogue entry but no exercise in EXERCISE_CLASSES (ddg/checks/__init__.py)",
                         set(CATALOGUE) - exercises),
                        ("a check called in a chapter that ddg.checks does not have (is its class in "
                         "EXERCISE_CLASSES?)", called - set(checks.CHECKS))):
        assert not names, f"{', '.join(sorted(names))}: {what} ({guide})"
    few = {name: len(mistakes) for name, (_, mistakes) in CATALOGUE.items() if len(mistakes) < 6}
    assert not few, f"fewer than six catalogued mistakes: {few} ({guide})"


@pytest.mark.parametrize("name", sorted(CATALOGUE))
def test_every_right_answer_passes_on_100_seeds(name):
    for answer in right_answers(name):
        failed = {where: repr(f) for where, f in verdicts(name, answer).items() if not f}
        assert not failed, f"{name}: a right answer failed on {len(failed)} seeds, e.g. {next(iter(failed.items()))}"


MISTAKES = [(name, mistake, answer, words) for name, (_, mistakes) in sorted(CATALOGUE.items())
            for mistake, (answer, words) in mistakes.items()]


def assert_named_on_100_seeds(name, label, answer, words, start=""):
    """On every seed the check fails ``answer`` with a message that starts with ``start`` and has ``words``."""
    answer = named(label, answer)
    wrong = {}
    for where, feedback in verdicts(name, answer).items():
        if feedback or not feedback.problem.startswith(start) or not all(w in feedback.problem for w in words):
            wrong[where] = repr(feedback)
    assert not wrong, f"{name}, {label}: not named on {len(wrong)} seeds, e.g. {next(iter(wrong.items()))}"


@pytest.mark.parametrize("name, mistake, answer, words", MISTAKES, ids=[f"{n}-{m}" for n, m, _, _ in MISTAKES])
def test_every_mistake_fails_and_is_named_on_100_seeds(name, mistake, answer, words):
    assert_named_on_100_seeds(name, mistake, answer, [words])


PAIRED = [(name, pair, answer, words) for name, pairs in sorted(PAIRS.items())
          for pair, (answer, words) in pairs.items()]


@pytest.mark.parametrize("name, pair, answer, words", PAIRED, ids=[f"{n}-{p}" for n, p, _, _ in PAIRED])
def test_two_mistakes_at_once_are_both_named_on_100_seeds(name, pair, answer, words):
    """A sign or range convention together with an index or wrap-around slip: both named."""
    assert_named_on_100_seeds(name, pair, answer, words, start="two mistakes at once")


@pytest.mark.parametrize("name", sorted(CATALOGUE))
def test_a_few_percent_off_gets_the_plain_facts(name):
    factor = 1.2 if name == "zigzag_exponent" else 1.03  # an exponent is judged to within 0.08
    feedback = checks.run(name, times(name, factor), 0, isolate=False)
    assert not feedback and "expected" in feedback.problem and "got" in feedback.problem, feedback


@pytest.mark.parametrize("name", sorted(CATALOGUE))
def test_isolated_checks_agree_and_the_starter_is_not_written_yet(name):
    check = getattr(checks, f"check_{name}")
    assert check(ref(name), seed=1), check(ref(name), seed=1)
    mistake, (answer, words) = next(iter(CATALOGUE[name][1].items()))
    feedback = check(named(mistake, answer), seed=1)
    assert not feedback and mistake in repr(feedback) and words in feedback.problem
    feedback = check(starter_of(name), seed=0)
    assert not feedback and "not written yet" in feedback.problem


def test_lists_and_changed_input_get_a_note():
    feedback = checks.run("turning_angles", as_list("turning_angles"), 0, isolate=False)
    assert feedback and any("returns a list" in note for note in feedback.notes), feedback

    def vandal(vertices):  # changes its input in place, then answers right
        psi = REFERENCE["turning_angles"](vertices.copy())
        vertices[:] = 0
        return psi

    for isolate in (False, True):
        feedback = checks.run("turning_angles", vandal, 0, isolate=isolate)
        assert feedback and any("in place" in note for note in feedback.notes), feedback


def test_feedback_never_shows_the_solution():
    for name, (_, mistakes) in CATALOGUE.items():
        source = next(s for _, s in solution_cells() if re.search(rf"^def {name}\b", s, re.M))
        body = [line.strip() for line in source.split("\n")[1:] if len(line.strip()) > 12
                and not line.strip().startswith(("#", '"""'))]
        for mistake, (answer, _) in mistakes.items():
            message = repr(checks.run(name, named(mistake, answer), 0, isolate=False))
            assert not [line for line in body if line in message], (name, message)


def test_no_check_holds_the_solution_of_its_exercise():
    """The distinctive lines of every reference solution are absent from the checks' source."""
    source = "\n".join(p.read_text() for p in (ROOT / "ddg" / "checks").glob("*.py"))
    for _, solution in solution_cells():
        code = [line.strip() for line in solution.splitlines() if len(line.strip()) > 20
                and not line.strip().startswith(("#", '"""', "def ", "return n /"))]
        assert not [line for line in code if line in source], code
    assert "np.tan(psi / 2)" not in source and "np.where(psi >= 0" not in source  # the Minkowski formula


def test_measuring_instead_of_computing_is_refused_where_the_answer_runs():
    measured = named("minkowski_measured", lambda c, eps: shapely.Polygon(c.vertices).buffer(eps, 1024).area)
    assert checks.run("minkowski_area", measured, 0, isolate=False)  # right values, measured
    feedback = checks.check_minkowski_area(measured, seed=0)
    assert not feedback and "measures what this exercise asks you to compute" in feedback.problem, feedback


def test_a_nan_at_an_end_is_a_nan_not_a_forgotten_wrap_around():
    """A new user's finding: a NaN at vertex 0 was said to be a forgotten wrap-around; a number off
    there still is."""
    def right(vertices):
        v = np.asarray(vertices, dtype=float)
        e = np.roll(v, -1, axis=0) - v
        a = np.roll(e, 1, axis=0)
        psi = np.arctan2(a[:, 1] * e[:, 0] - a[:, 0] * e[:, 1], (a * e).sum(axis=1))
        return np.where(psi == -np.pi, np.pi, psi)

    def last_off(vertices):
        psi = right(vertices)
        psi[-1] += 0.1
        return psi

    def first_nan(vertices):
        psi = right(vertices)
        psi[0] = np.nan
        return psi

    assert checks.run("turning_angles", right, 0, isolate=False)
    off = checks.run("turning_angles", last_off, 0, isolate=False)
    assert not off and "wrap-around is missing" in off.problem
    nan = checks.run("turning_angles", first_nan, 0, isolate=False)
    assert not nan and "NaN" in nan.problem and "wrap-around" not in nan.problem
