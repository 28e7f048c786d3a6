"""Journey: a real class, messy as real classes are, graded in one run and through Gradescope.

A class of 29 students hands in every chapter with coding exercises (203 notebooks): 7 in 29 of
each chapter are right (written in several forms), the others are the book's own solutions with
their result mangled in one of 22 ways students' results are (a value short or too many, empty, a
column, a 3-d array, text, ``None``, complex, a generator, a dict, an exception, ``sys.exit``, ...).
The run completes; every right answer gets full points, every mangled one 0 and a verdict in the
student's terms, no feedback shows a traceback or a path of ours, nothing is left for the
instructor; the same notebooks through Gradescope's ``run_autograder`` each get a valid
``results.json`` with the same scores.
"""

import json
import re
import zipfile

import pytest
from grading_helpers import by_student, grade, needs_root, references, submission

from journey_helpers import ROOT

CHAPTERS = {path.stem: json.loads(path.read_text())["metadata"]["ddg"]["exercises"]
            for path in sorted((ROOT / "book").glob("*.ipynb"))
            if any("check" in e for e in json.loads(path.read_text())["metadata"].get("ddg", {}).get(
                "exercises", {}).values())}
MANGLES = {
    "one short": "r[:-1]", "one too many": "np.concatenate([r, r[:1]])", "ends missing": "r[1:-1]",
    "first missing": "r[1:]", "empty": "r[:0]", "column": "r.reshape(len(r), -1)[:, :1] if r.ndim else r.reshape(1, 1)",
    "3-d": "r.reshape(1, *r.shape, 1)", "first only": "r.ravel()[:1]", "doubled": "np.stack([r, r])",
    "NaN": "r * np.nan", "as text": "str(r.tolist())", "None": "None", "complex": "r + 1j",
    "nested ragged": "[r.tolist(), [1]]", "dict": "{'result': r.tolist()}", "tuple of two": "(r, r)",
    "object array": "np.array([r, None], dtype=object)", "generator": "(x for x in r.ravel())",
    "raises": "1 / 0", "exits": "sys.exit(3)", "off": "r * 1.5 + 0.7", "degrees": "np.degrees(r)",
}
RIGHT = {  # right answers in other forms than the reference's
    "reference": "r", "a list": "r.tolist()", "float32": "r.astype(np.float32)", "a copy": "np.array(r)",
    "long double": "r.astype(np.longdouble)", "a tuple of rows": "tuple(r.tolist()) if r.ndim else r",
    "a masked array": "np.ma.masked_array(r)",
}
VARIANTS = [*MANGLES.items(), *RIGHT.items()]
STUDENTS = [f"s{k:03d}" for k in range(len(VARIANTS))]
FORBIDDEN = ("Traceback", 'File "', "/usr/", "/work/", "/tmp/", "site-packages", "grader-errors")


def mangled(reference, answer, expression):
    """The reference answer, renamed, and ``answer`` returning ``expression`` of its result ``r``."""
    return (reference.replace(f"def {answer}(", f"def _right_{answer}(", 1)
            + f"\n\ndef {answer}(*args):\n    import sys\n    import numpy as np\n\n"
              f"    r = np.asarray(_right_{answer}(*args), dtype=float)\n    return {expression}\n")


def plan():
    """``{(student, chapter): (label of the mangled exercise or None, variant)}`` for the whole class."""
    table = {}
    for c, (chapter, exercises) in enumerate(CHAPTERS.items()):
        labels = sorted(label for label, e in exercises.items() if "check" in e)
        for k, student in enumerate(STUDENTS):
            variant = (k + c) % len(VARIANTS)
            name, _ = VARIANTS[variant]
            table[student, chapter] = (labels[(k // len(VARIANTS) + variant) % len(labels)] if name in MANGLES
                                       else None, variant)
    return table


@pytest.fixture(scope="module")
def klass(tmp_path_factory):
    root = tmp_path_factory.mktemp("class")
    subs = root / "submissions"
    for (student, chapter), (label, variant) in plan().items():
        exercises = CHAPTERS[chapter]
        reference = references(chapter)
        name, expression = VARIANTS[variant]
        answers = {}
        for each, e in exercises.items():
            if "check" not in e:
                continue
            if each == label or (label is None and name != "reference"):
                answers[e["answer"]] = mangled(reference[e["answer"]], e["answer"], expression)
        submission(subs / student / f"{chapter}.ipynb", answers, chapter=chapter)
    return root, subs


def test_a_class_of_200_messy_notebooks_is_graded_in_one_run(klass):
    needs_root()
    root, subs = klass
    out = root / "grading"
    result = grade(subs, "--seed", "a class", "--out", out, timeout=3000, check=False)
    assert result.returncode == 0, result.stdout[-3000:]
    assert f"graded {len(plan())} submissions" in result.stdout
    assert not (out / "problems.txt").exists() and not (out / "grader-errors.log").exists()
    grades = by_student(out / "grades.csv")
    assert sorted(grades) == STUDENTS
    for (student, chapter), (label, variant) in plan().items():
        feedback = (out / "feedback" / student / f"{chapter}.txt").read_text()
        assert not [w for w in FORBIDDEN if w in feedback], (student, chapter, feedback)
        for each, e in CHAPTERS[chapter].items():
            if "check" not in e:
                continue
            expected = "0" if each == label else f"{e.get('points', 1):g}"
            assert grades[student][each] == expected, (student, chapter, VARIANTS[variant][0], each, feedback)
            if each == label:
                verdict = re.search(rf"^{re.escape(each)}: 0/\S+\n  (✗ .*)$", feedback, re.M)
                assert verdict and len(verdict.group(1)) > 20, feedback  # a verdict, in words
    report = (out / "report.html").read_text()
    assert f"{len(plan())} submissions graded, {len(STUDENTS)} students" in report


def test_the_same_class_through_gradescope_always_writes_results(klass, tmp_path):
    """``run_autograder`` as Gradescope calls it, once per submission, for every notebook of the class."""
    needs_root()
    import shutil

    from instructor import gradescope
    from instructor import grade as grader

    _, subs = klass
    table = grader.exercises(ROOT / "book")
    for chapter in CHAPTERS:
        bundle = tmp_path / f"{chapter}.zip"
        gradescope.build(bundle, table, chapter, "a class", dict(grader.LIMITS))
        root = tmp_path / chapter
        with zipfile.ZipFile(bundle) as archive:
            (root / "source").mkdir(parents=True)
            (root / "source" / "autograder.json").write_bytes(archive.read("autograder.json"))
        for student in STUDENTS:
            shutil.rmtree(root / "submission", ignore_errors=True)
            shutil.rmtree(root / "results", ignore_errors=True)
            (root / "submission").mkdir()
            shutil.copy(subs / student / f"{chapter}.ipynb", root / "submission" / f"{chapter}.ipynb")
            gradescope.run(root)
            results = json.loads((root / "results" / "results.json").read_text())
            label, variant = plan()[student, chapter]
            assert isinstance(results["score"], (int, float)) and results["tests"], results
            for test in results["tests"]:
                assert set(test) == {"name", "score", "max_score", "output", "visibility"}
                assert not [w for w in FORBIDDEN if w in test["output"]], test
                mangled_here = test["name"].split(":")[0] == label
                assert test["score"] == (0 if mangled_here else test["max_score"]), (student, chapter, test)
