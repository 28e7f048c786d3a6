"""Journeys: an instructor grades a class with `python -m instructor.grade`, as INSTRUCTORS.md says.

Every submission is a real notebook (the student edition of chapter 3, completed), graded in the
real sandbox (these journeys need Linux and root). Each test is one thing an instructor relies on:
students told apart and nothing guessed; a submission that hunts for the secret and the solutions
and finds nothing; feedback that says what happened for every way a notebook can fail; partial
credit, written exercises, regrades and deadlines; shards merged into one class, and its report;
a right notebook graded under random secrets with the grader's numerics unlike the kernel's.
"""

import hashlib
import json
import secrets
import shutil
import subprocess
import sys

import nbformat
from grading_helpers import CHAPTER, HUNT, by_student, grade, needs_root, references, rows, submission

from journey_helpers import ROOT

NOTEBOOK = f"{CHAPTER}.ipynb"
SECRETS = 8  # random secrets a right notebook is graded under


def feedback(out, student):
    return (out / "feedback" / student / f"{CHAPTER}.txt").read_text()


def test_students_are_told_apart_and_nothing_is_guessed(tmp_path):
    needs_root()
    subs, out = tmp_path / "submissions", tmp_path / "grading"
    wrong_rebuild = references()["rebuild"].replace("heading - ", "heading + ")
    submission(subs / "alice" / NOTEBOOK)
    bob = submission(subs / "bob" / NOTEBOOK, {"rebuild": wrong_rebuild})
    greedy = json.loads(bob.read_text())  # claims another chapter and more points: graded as its name and the book say
    greedy["metadata"]["ddg"] = {"chapter": "01_smooth_curves", "exercises": {"ex-turning-angles": {
        "answer": "turning_angles", "check": "check_turning_angles", "points": 100}}}
    bob.write_text(json.dumps(greedy))
    submission(subs / f"liddelldave_4321_9876_{NOTEBOOK}")  # a Canvas download's name: Dave's canvas_id is 4321
    submission(subs / "eve" / NOTEBOOK)  # not in the roster
    submission(subs / "frank" / NOTEBOOK)
    submission(subs / f"frank_{NOTEBOOK}")  # Frank twice
    submission(subs / "grace" / "homework.ipynb")  # no chapter in its name
    late = submission(tmp_path / "late" / "carol" / NOTEBOOK)  # given by itself, as a shell's glob gives it
    roster = tmp_path / "roster.csv"
    roster.write_text("id,name,email,section,canvas_id\nalice,Alice Liddell,alice@uni.edu,A,1111\n"
                      "bob,Bob Dodgson,bob@uni.edu,A,\ncarol,Carol Hare,carol@uni.edu,B,\n"
                      "dave,Dave Liddell,dave@uni.edu,B,4321\nfrank,Frank Tenniel,,B,\ngrace,Grace Dormouse,,A,\n"
                      "henry,Henry Hatter,henry@uni.edu,A,\n")

    result = grade(subs, late, "--roster", roster, "--seed", "a secret", "--out", out, check=False)
    assert result.returncode == 3, result.stdout  # graded, but notebooks need the instructor

    table = rows(out / "grades.csv")
    assert table[0] == ["student_id", "name", "ex-rebuild", "ex-turning-angles", "ex-turning-three", "total"]
    assert {row[0]: row[1:] for row in table[1:]} == {
        "alice": ["Alice Liddell", "1", "1", "", "2"], "bob": ["Bob Dodgson", "0", "1", "", "1"],
        "carol": ["Carol Hare", "1", "1", "", "2"], "dave": ["Dave Liddell", "1", "1", "", "2"],
        "frank": ["Frank Tenniel", "", "", "", "0"], "grace": ["Grace Dormouse", "", "", "", "0"],
        "henry": ["Henry Hatter", "", "", "", "0"]}
    written = sorted(p.relative_to(out / "feedback").as_posix() for p in (out / "feedback").rglob("*.txt"))
    assert written == [f"{s}/{CHAPTER}.txt" for s in ("alice", "bob", "carol", "dave")]
    assert feedback(out, "alice").startswith(f"{CHAPTER}: Alice Liddell (alice)")
    assert "ex-rebuild: 0/1" in feedback(out, "bob") and "the turns go the wrong way" in feedback(out, "bob")
    problems = (out / "problems.txt").read_text()
    assert "no student in the roster matches the folder `eve`" in problems
    assert f"frank, {CHAPTER}: not graded: 2 submissions" in problems
    assert "homework.ipynb: not graded: its name names no chapter" in problems
    assert problems.strip() in result.stdout.replace("\n  ", "\n")
    assert str((out / "grades.csv").resolve()) in result.stdout and str((out / "feedback").resolve()) in result.stdout

    canvas = rows(out / "canvas.csv")
    assert canvas[:2] == [["Student", "ID", "SIS User ID", "SIS Login ID", "Section", CHAPTER],
                          ["Points Possible", "", "", "", "", "3"]]
    assert canvas[2] == ["Alice Liddell", "1111", "alice", "alice@uni.edu", "A", "2"]
    assert ["Dave Liddell", "4321", "dave", "dave@uni.edu", "B", "2"] in canvas
    assert ["Henry Hatter", "", "henry", "henry@uni.edu", "A", ""] in canvas

    duplicate = tmp_path / "duplicate.csv"
    duplicate.write_text("id,name\nalice,Alice\nalice,Alicia\n")
    refused = grade(subs, "--roster", duplicate, "--seed", "s", "--out", out, check=False)
    assert refused.returncode == 2 and "duplicate.csv line 3: id `alice` appears twice (also on line 2)" in refused.stdout


def test_a_submission_that_hunts_for_secrets_finds_nothing_and_scores_nothing(tmp_path):
    needs_root()
    subs, out = tmp_path / "submissions", tmp_path / "grading"
    secret = "not-for-students-" + hashlib.sha256(str(tmp_path).encode()).hexdigest()[:8]
    submission(subs / "mallory" / NOTEBOOK, {"turning_angles": HUNT})
    submission(subs / "victim" / NOTEBOOK, first_cells=["# VICTIM-7f3a: another student's work"])

    grade(subs, "--seed", secret, "--out", out, "--answer-timeout", 60)  # on the command line: the worst case

    everything = "".join(p.read_text(errors="replace") for p in out.rglob("*") if p.is_file())
    assert secret not in everything
    executed = nbformat.read(out / "feedback" / "mallory" / NOTEBOOK, as_version=4)
    printed = next(o["text"] for c in executed.cells for o in c.get("outputs", []) if "HUNT " in o.get("text", ""))
    tried, found = json.loads(printed.split("HUNT ", 1)[1])
    assert found == [], found
    assert tried["processes"] >= 1 and tried["files"] > 100 and tried["objects"] > 1000 and tried["frames"] > 1
    assert tried["descriptors"] >= 3 and tried["environment"] > 0
    assert tried["connect 1.1.1.1"].startswith("refused") and tried["connect 127.0.0.1"].startswith("refused")
    assert [tried[key][:7] for key in tried if key.startswith("write ")] == ["refused"] * 3
    assert "it raised RuntimeError: found nothing" in feedback(out, "mallory")  # in the answer's own process too
    assert by_student(out / "grades.csv")["mallory"]["ex-turning-angles"] == "0"

    # The control: outside the sandbox the same hunt finds a grader's secret and the book's solutions.
    decoy = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(300)", "--seed", "CONTROL-SECRET"])
    try:
        namespace = {}
        exec(HUNT.split("\nprint(")[0], namespace)  # noqa: S102 - the submission's own hunt, run here on purpose
        _, found_here = namespace["hunt"](write=False)
    finally:
        decoy.kill()
    assert any("CONTROL-SECRET" in f for f in found_here), found_here[:5]
    assert any("{solution-start}" in f for f in found_here), found_here[:5]


def test_feedback_says_what_happened_for_every_way_a_notebook_fails(tmp_path):
    needs_root()
    subs, out = tmp_path / "submissions", tmp_path / "grading"
    reference = references()
    needs = "\n\n_uses = prepare  # the answer's cell needs the cell above\n"
    helper = "import numpy as np\n\n\ndef prepare(vertices):\n    return np.asarray(vertices, dtype=float)\n\n\n"
    (subs / "corrupt").mkdir(parents=True)
    (subs / "corrupt" / NOTEBOOK).write_text('{"cells": [')
    submission(subs / "syntax" / NOTEBOOK, {"turning_angles": "def turning_angles(vertices)\n    return 0\n"})
    submission(subs / "old" / NOTEBOOK, drop=("rebuild",))
    submission(subs / "wrong" / NOTEBOOK, {"rebuild": reference["rebuild"].replace("heading - ", "heading + ")})
    submission(subs / "looping" / NOTEBOOK, {"turning_angles": reference["turning_angles"] + needs},
               first_cells=["while True:  # not needed by any answer: never runs\n    pass",
                            helper + "while True:\n    pass"])
    submission(subs / "stubborn" / NOTEBOOK, {"turning_angles": reference["turning_angles"] + needs},
               first_cells=[helper + "while True:\n    try:\n        while True:\n            pass\n"
                                     "    except BaseException:\n        pass"])
    submission(subs / "hungry" / NOTEBOOK, {"turning_angles": reference["turning_angles"] + "\n_uses = huge, hog\n"},
               first_cells=["import numpy as np\nhuge = np.ones(10**11)", "import numpy as np\nhog = np.ones(300_000_000)"])
    submission(subs / "crashing" / NOTEBOOK, {"turning_angles": reference["turning_angles"] + "\n_uses = os, ctypes\n"},
               first_cells=["import os\nos._exit(3)", "import ctypes\nctypes.string_at(0)"])
    submission(subs / "noisy" / NOTEBOOK, {"turning_angles": reference["turning_angles"] + "\n_uses = noise\n"},
               first_cells=["import os\nnoise = 'x' * 100\nprint(noise * 30_000)\nos.write(1, b'{\"raw\": []}\\n' * 1000)"])

    result = grade(subs, "--seed", "s", "--out", out, "--cell-timeout", 5, "--answer-timeout", 5, "--memory", 1500)
    assert result.returncode == 0, result.stdout  # every notebook graded: nothing needs the instructor

    grades = by_student(out / "grades.csv")
    assert {s: row["total"] for s, row in grades.items()} == {
        "corrupt": "0", "syntax": "1", "old": "1", "wrong": "1", "looping": "2", "stubborn": "2", "hungry": "2",
        "crashing": "2", "noisy": "2"}, result.stdout
    assert "not a notebook: the file is not valid JSON (Expecting value: line 1 column 12" in feedback(out, "corrupt")
    assert ("the cell starting `def turning_angles(vertices)`, which defines `turning_angles`, has a SyntaxError on "
            "line 1: expected ':'" in feedback(out, "syntax"))
    assert str(tmp_path) not in "".join(p.read_text() for p in (out / "feedback").rglob("*.txt"))  # no path of ours
    assert "no `rebuild` in your notebook: no cell defines it" in feedback(out, "old")
    wrong = feedback(out, "wrong")
    assert "the turns go the wrong way" in wrong and "wrong on 6 of 6 hidden inputs" in wrong
    looping = feedback(out, "looping")
    assert "the cell starting `import numpy as np` was stopped at its time limit of 5 s (an endless loop?)" in looping
    assert "`while True:" not in looping  # the loop no answer needs did not run, and cost nothing
    assert "the cell starting `import numpy as np` did not stop at its time limit of 5 s and was killed; the other " \
           "cells ran again without it" in feedback(out, "stubborn")
    hungry = feedback(out, "hungry")
    assert "the cell starting `import numpy as np` (the 1st cell that starts so) raised MemoryError" in hungry
    assert "the cell starting `import numpy as np` (the 2nd cell that starts so) raised MemoryError: Unable to " \
           "allocate 2.24 GiB" in hungry
    crashing = feedback(out, "crashing")
    assert "the cell starting `import os` ended the Python process (os._exit or a crash: exit status 3)" in crashing
    assert "the cell starting `import ctypes` crashed the Python process (signal 11)" in crashing
    assert "code cells (those the answer needs)" in feedback(out, "noisy")

    executed = nbformat.read(out / "feedback" / "looping" / NOTEBOOK, as_version=4)
    nbformat.validate(executed)
    assert [o["ename"] for o in executed.cells[2].outputs if o["output_type"] == "error"] == ["CellTimeout"]
    assert executed.cells[1].outputs == []  # did not run
    noisy = nbformat.read(out / "feedback" / "noisy" / NOTEBOOK, as_version=4)
    assert "more characters not kept" in noisy.cells[1].outputs[0]["text"]
    assert not (out / "feedback" / "corrupt" / NOTEBOOK).exists()


def test_partial_credit_written_exercises_regrades_and_deadlines(tmp_path):
    needs_root()
    subs, out, book = tmp_path / "submissions", tmp_path / "grading", tmp_path / "book"
    book.mkdir()
    nb = json.loads((ROOT / "book" / NOTEBOOK).read_text())
    nb["metadata"]["ddg"]["exercises"]["ex-turning-angles"].update(points=2, partial=True)
    nb["metadata"]["ddg"]["exercises"]["ex-turning-three"] = {"points": 2}  # a written exercise, worth 2
    (book / NOTEBOOK).write_text(json.dumps(nb))
    reference = references()["turning_angles"]
    small_only = (reference.replace("def turning_angles(", "def _angles(") + "\n\ndef turning_angles(vertices):\n"
                  "    return _angles(vertices) if len(vertices) <= 8 else np.zeros(len(vertices))\n")
    for student in ("alice", "carol", "dave"):
        submission(subs / student / NOTEBOOK)
    bob = submission(subs / "bob" / NOTEBOOK, {"turning_angles": small_only})
    times = tmp_path / "submitted.csv"
    times.write_text("student_id,submitted\nalice,2027-03-01T20:00\nbob,2027-03-01T23:00\n"
                     "carol,2027-03-11T10:00\ndave,2027-03-03T09:00\n")
    common = ["--seed", "s", "--out", out, "--book", book, "--deadline", "2027-03-01T23:59", "--submitted", times,
              "--late-penalty", 10, "--late-cutoff", 7]

    grade(subs, *common)

    table = rows(out / "grades.csv")
    assert table[0] == ["student_id", "name", "ex-rebuild", "ex-turning-angles", "ex-turning-three", "late_days",
                        "penalty", "total"]
    grades = by_student(out / "grades.csv")
    right = int(feedback(out, "bob").split("ex-turning-angles: ")[1].split("(")[1].split(" of 14")[0])
    assert 0 < right < 14
    assert grades["bob"]["ex-turning-angles"] == f"{round(2 * right / 14, 2):g}"
    assert [grades["alice"][k] for k in ("ex-turning-angles", "late_days", "penalty", "total")] == ["2", "0", "0", "3"]
    assert [grades["dave"][k] for k in ("late_days", "penalty", "total")] == ["2", "0.6", "2.4"]
    assert [grades["carol"][k] for k in ("late_days", "penalty", "total")] == ["10", "3", "0"]
    assert "late by 2 days: 0.6 points off" in feedback(out, "dave")
    assert "ex-turning-three: not scored yet (of 2)" in feedback(out, "alice")

    # The written exercise, scored by hand in a copy of grades.csv, merged without running anything.
    scores = tmp_path / "scores.csv"
    filled = [row[:4] + [{"alice": "2", "bob": "1", "dave": "1.5"}.get(row[0], row[4])] + row[5:] for row in table]
    scores.write_text("\n".join(",".join(row) for row in filled) + "\n")
    merged = grade(subs, *common, "--merge-manual", scores)
    assert "graded 4 submissions (4 from earlier results)" in merged.stdout
    grades = by_student(out / "grades.csv")
    assert [grades[s]["total"] for s in ("alice", "dave", "carol")] == ["5", "3.6", "0"]
    assert "ex-turning-three: 1.5/2" in feedback(out, "dave")
    scores.write_text("student_id,ex-turning-thre\nalice,1\n")
    assert "`ex-turning-thre` is no written exercise" in grade(subs, *common, "--merge-manual", scores, check=False).stdout
    scores.write_text("student_id,ex-turning-three\nalice,3\n")
    assert "scores.csv line 2, ex-turning-three: 3 is not between 0 and 2" in grade(
        subs, *common, "--merge-manual", scores, check=False).stdout

    # Regrades: one exercise for everyone, one student, a changed notebook; the rest comes from the cache.
    def stamps():  # an entry per notebook, exercise and input (LABEL-KEY.json): three students share one notebook
        return {(p.parent.name, p.stem): p.stat().st_mtime_ns for p in (out / "cache").rglob("*.json")}

    def changed(old, new):
        return {(sha, stem.rsplit("-", 1)[0]) for sha, stem in old if old[sha, stem] != new[sha, stem]}

    def sha(student):
        return hashlib.sha256((subs / student / NOTEBOOK).read_bytes()).hexdigest()

    before = stamps()
    grade(subs, *common, "--only", "ex-rebuild")
    after = stamps()
    assert changed(before, after) == {(sha(s), "ex-rebuild") for s in
                                                                     ("alice", "bob", "carol", "dave")}
    grade(subs, *common, "--student", "bob")
    again = stamps()
    assert changed(after, again) == {(sha("bob"), label)
                                                                   for label in ("ex-rebuild", "ex-turning-angles")}
    submission(bob, {"turning_angles": reference + "# fixed\n"})  # Bob fixes his answer
    fixed = grade(subs, *common)
    assert "graded 4 submissions (3 from earlier results)" in fixed.stdout
    assert by_student(out / "grades.csv")["bob"]["ex-turning-angles"] == "2"
    assert "--submitted needs a deadline" in grade(subs, "--seed", "s", "--out", tmp_path / "elsewhere", "--submitted",
                                                   times, check=False).stdout


def test_shards_graded_apart_merge_into_one_class_with_its_report(tmp_path):
    needs_root()
    subs, secret = tmp_path / "submissions", tmp_path / "secret.txt"
    secret.write_text("shared by every shard\n")
    wrong = references()["rebuild"].replace("heading - ", "heading + ")
    for student in ("ann", "ben", "cat"):
        submission(subs / student / NOTEBOOK, first_cells=[f"# {student}'s"])  # all different
    submission(subs / "dan" / NOTEBOOK, {"rebuild": wrong})
    for k in (1, 2):  # two machines, each with its own folder
        result = grade(subs, "--seed-file", secret, "--out", tmp_path / f"shard{k}", "--shard", f"{k}/2")
        assert f"shard {k}/2: graded 2 of 4 submissions" in result.stdout
    final = tmp_path / "grading"
    shutil.copytree(tmp_path / "shard1" / "cache", final / "cache")
    incomplete = grade(subs, "--seed-file", secret, "--out", final, "--merge", check=False)
    assert incomplete.returncode == 1 and "no shard graded" in incomplete.stdout
    assert "/ben/" in incomplete.stdout and "/dan/" in incomplete.stdout and "/ann/" not in incomplete.stdout
    shutil.copytree(tmp_path / "shard2" / "cache", final / "cache", dirs_exist_ok=True)
    merged = grade(subs, "--seed-file", secret, "--out", final, "--merge")
    assert "graded 4 submissions (4 from earlier results)" in merged.stdout
    assert {s: row["total"] for s, row in by_student(final / "grades.csv").items()} == {
        "ann": "2", "ben": "2", "cat": "2", "dan": "1"}
    report = (final / "report.html").read_text()
    assert report.count('<img src="data:image/png;base64,') == 1
    assert "<td>ex-rebuild</td><td>1</td><td>0.75</td><td>3 of 4 (75%)</td>" in report
    assert "the turns go the wrong way" in report and "ex-turning-three (written)" in report
    assert "--shard 3/2: give K/N" in grade(subs, "--seed", "s", "--out", final, "--shard", "3/2", check=False).stdout


def test_a_right_answer_gets_full_points_under_any_secret_and_any_numerics(tmp_path):
    """The input is drawn once, in the grader, and only its specs reach the kernel: a right notebook
    gets every point under random secrets, though the grader's numpy runs with another BLAS core type
    than the sandboxed kernel's (which keeps none of the grader's environment)."""
    needs_root()
    subs = tmp_path / "submissions"
    submission(subs / "alice" / NOTEBOOK)
    for k in range(SECRETS):
        out = tmp_path / f"grading{k}"
        grade(subs, "--seed", secrets.token_hex(8), "--out", out, env={"OPENBLAS_CORETYPE": "Prescott"})
        table = rows(out / "grades.csv")
        assert table[1][0] == "alice" and table[1][-1] == "2", table
