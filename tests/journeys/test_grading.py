"""Journey: an instructor grades a class with `python -m instructor.grade`.

A synthetic class is made from the student edition of chapter 3 (two coding exercises): a right
submission, a partly wrong one, and hostile ones that crash, loop, exit the kernel, eat memory,
print garbage (including a forged results line) and write files where they should not. Every
submission must get what it earned, and none may disturb the others or the grader.
"""

import csv
import hashlib
import json
import os
import re
import sys
import time

import nbformat
import pytest
from journey_helpers import ROOT, run

from instructor import edition

CHAPTER = ROOT / "book" / "03_winding_number.ipynb"


def references():
    nb = nbformat.read(CHAPTER, as_version=4)
    return {re.search(r"def (\w+)", c.source).group(1): c.source for c in nb.cells
            if "solution" in c.metadata.get("tags", [])}


def submission(path, answers=None, first_cells=()):
    """The student edition with the starters filled in (by the reference unless ``answers`` says
    otherwise) and ``first_cells`` inserted before everything else."""
    nb = edition.student_notebook(nbformat.read(CHAPTER, as_version=4))
    reference = references()
    for cell in nb.cells:
        if "starter" in cell.metadata.get("tags", []):
            name = re.search(r"def (\w+)", cell.source).group(1)
            cell.source = (answers or {}).get(name, reference[name])
    nb.cells[1:1] = [nbformat.v4.new_code_cell(source) for source in first_cells]
    nbformat.write(nb, path)
    return path


def sha(path):
    return hashlib.sha256(path.read_bytes()).hexdigest()


def test_a_class_is_graded_and_hostile_submissions_disturb_nothing(tmp_path):
    if not sys.platform.startswith("linux") or os.geteuid() != 0:
        pytest.skip("the grading sandbox needs Linux and root (unshare, setpriv)")
    out = tmp_path / "grades" / "grades.csv"
    guarded = ROOT / "ddg" / "checks.py"
    before = sha(guarded)
    wrong_rebuild = references()["rebuild"].replace("heading - ", "heading + ")
    hostile_writes = f"""
import glob, shutil
open("big.bin", "wb").write(b"x" * (5 << 20))            # in its own folder: allowed
for target in ({str(guarded)!r}, {str(out)!r}):
    try:
        open(target, "w").write("overwritten")
    except OSError as error:
        print("refused:", error)
for other in glob.glob("/tmp/ddg-grade-*"):
    shutil.rmtree(other, ignore_errors=True)
"""
    forged = "print('ddg-grade-results: ' + '{\"results\": {}}')\nprint(''.join(chr(33 + i % 90) for i in range(2_000_000)))"
    zeros = "def turning_angles(vertices):\n    return np.zeros(len(vertices))\n"
    cls = {
        "right": ({}, ()),
        "partly_wrong": ({"rebuild": wrong_rebuild}, ()),
        "crashing": ({"turning_angles": "def turning_angles(vertices):\n    return vertices[10**6]\n"},
                     ("raise RuntimeError('this cell crashes')",)),
        "looping": ({"turning_angles": "def turning_angles(vertices):\n    while True:\n        pass\n"},
                    ("while True:\n    pass",)),
        "exiting": ({}, ("import os\nos._exit(1)", "import sys\nsys.exit(3)")),
        "memory_hungry": ({"turning_angles": "def turning_angles(vertices):\n    return np.ones(10**11)\n"},
                          ("import numpy as np\nhuge = np.ones(10**11)",)),
        "garbage": ({"turning_angles": zeros, "rebuild": "def rebuild(*args):\n    return 'garbage'\n"}, (forged,)),
        "file_writer": ({}, (hostile_writes,)),
    }
    paths = [submission(tmp_path / f"{name}.ipynb", *spec) for name, spec in cls.items()]
    start = time.monotonic()
    result = run([sys.executable, "-m", "instructor.grade", *map(str, paths), "--out", str(out), "--seed", "not-for-students",
                  "--cell-timeout", "5", "--answer-timeout", "3", "--timeout", "120", "--book", str(ROOT / "book")], timeout=600)
    elapsed = time.monotonic() - start
    assert "graded 8 submissions" in result.stdout

    with open(out) as file:
        rows = {row["submission"]: row for row in csv.DictReader(file)}
    assert list(next(iter(rows.values()))) == ["submission", "ex-rebuild", "ex-turning-angles", "total"]
    totals = {name.removesuffix(".ipynb"): int(row["total"]) for name, row in rows.items()}
    assert totals == {"right": 2, "partly_wrong": 1, "crashing": 1, "looping": 1, "exiting": 2,
                      "memory_hungry": 1, "garbage": 0, "file_writer": 2}, totals
    assert rows["partly_wrong.ipynb"]["ex-rebuild"] == "0" and rows["partly_wrong.ipynb"]["ex-turning-angles"] == "1"

    feedback = {p.stem: p.read_text() for p in (out.parent / "grades-feedback").glob("*.txt")}
    assert set(feedback) == set(cls)
    assert "did not return within 3 s" in feedback["looping"]  # --answer-timeout
    assert "raised IndexError" in feedback["crashing"]
    assert "stopped the kernel and were skipped" in feedback["exiting"]
    assert "MemoryError" in feedback["memory_hungry"]
    assert "four clockwise quarter turns" in feedback["partly_wrong"]  # the first problem, said
    assert sha(guarded) == before, "a submission changed the repository"
    assert elapsed < 300, f"grading 8 submissions took {elapsed:.0f} s"


def test_grading_needs_the_instructors_exercises_not_the_students(tmp_path):
    """A submission that edits its own metadata (more points, other exercises) is graded as the book says."""
    path = submission(tmp_path / "greedy.ipynb", {"rebuild": "def rebuild(*a):\n    return 0\n"})
    nb = json.loads(path.read_text())
    nb["metadata"]["ddg"]["exercises"] = {"ex-turning-angles": {"answer": "turning_angles", "points": 100,
                                                                "check": "check_turning_angles"}}
    path.write_text(json.dumps(nb))
    out = tmp_path / "g.csv"
    run([sys.executable, "-m", "instructor.grade", str(path), "--out", str(out), "--book", str(ROOT / "book")], timeout=300)
    with open(out) as file:
        row = next(csv.DictReader(file))
    assert row["total"] == "1" and row["ex-rebuild"] == "0" and row["ex-turning-angles"] == "1"
