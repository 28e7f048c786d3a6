"""Journeys: what instructors really hand the grader, and what they entered, survive every run.

Real notebooks in the real sandbox, with the files as instructors have them: Canvas's folder of one
assignment and its gradebook export as the roster, CSV written by Excel in Europe (semicolons, a
byte order mark, CRLF, decimal commas), deadlines per chapter with a grace period, a Canvas
assignment's column; written scores merged once and kept through regrades and a run on another
chapter; a file put under another student's name; a sandbox that cannot start; a cell that signals
the harness.
"""

import os
import random
import stat

from grading_helpers import CHAPTER, by_student, grade, needs_root, references, rows, spreadsheet, submission

OTHER = "04_gradient_of_length"


def european(text):
    """``text`` (a row a line, cells between commas) as Excel saves CSV in much of Europe."""
    return spreadsheet([line.split(",") for line in text.splitlines()], "excel-europe")


def test_written_scores_late_notebooks_and_other_chapters_never_drop_what_was_entered(tmp_path):
    needs_root()
    ch3, ch4, out = tmp_path / "ch3", tmp_path / "ch4", tmp_path / "grading"
    for student in ("alice", "bob", "carol"):
        submission(ch3 / student / f"{CHAPTER}.ipynb")
    wrong = references()["rebuild"].replace("heading - ", "heading + ")
    submission(ch3 / "bob" / f"{CHAPTER}.ipynb", {"rebuild": wrong})
    roster = tmp_path / "roster.csv"
    roster.write_bytes(european("id,name,email,Kommentar\nalice,Alice,a@uni.edu,\nbob,Bob,b@uni.edu,late\n"
                                "carol,Carol,c@uni.edu,\ndave,Dave,d@uni.edu,\n"))
    common = ["--roster", roster, "--seed", "s", "--out", out]
    assert grade(ch3, *common).returncode == 0

    scores = tmp_path / "scores.csv"  # a European spreadsheet: semicolons, BOM, CRLF, decimal commas, a comment
    scores.write_bytes(spreadsheet([["student_id", "ex-turning-three", "Kommentar"], ["alice", "1", "good; so far"],
                                    ["bob", "0,5", "partly"]]))
    grade(ch3, *common, "--merge-manual", scores)
    grades = by_student(out / "grades.csv")
    assert [grades[s]["ex-turning-three"] for s in ("alice", "bob", "carol")] == ["1", "0.5", ""]

    submission(ch3 / "dave" / f"{CHAPTER}.ipynb")  # a late notebook, graded with the ordinary command
    submission(ch3 / "bob" / f"{CHAPTER}.ipynb", first_cells=["# fixed"])  # a fixed one
    grade(ch3, *common)
    grades = by_student(out / "grades.csv")
    assert [grades[s]["ex-turning-three"] for s in ("alice", "bob", "carol", "dave")] == ["1", "0.5", "", ""]
    assert [grades[s]["total"] for s in ("alice", "bob", "carol", "dave")] == ["3", "2.5", "2", "2"]
    assert "ex-turning-three: 0.5/1" in (out / "feedback" / "bob" / f"{CHAPTER}.txt").read_text()

    submission(ch4 / "alice" / f"{OTHER}.ipynb", chapter=OTHER)  # the next chapter, graded into the same folder
    assert "4 results of earlier runs kept" in grade(ch4, *common).stdout
    table = rows(out / "grades.csv")
    assert table[0][:6] == ["student_id", "name", "ex-rebuild", "ex-turning-angles", "ex-turning-three",
                            "ex-length-gradient"] and table[0][-1] == "total"
    grades = by_student(out / "grades.csv")
    assert grades["bob"]["ex-turning-three"] == "0.5" and grades["alice"]["ex-length-gradient"] == "1"
    canvas = rows(out / "canvas.csv")
    assert canvas[0][5:] == [CHAPTER, OTHER]
    assert (out / "feedback" / "bob" / f"{CHAPTER}.txt").exists()

    scores.write_bytes(european("student_id,ex-turning-thre\nalice,1\n"))  # a typo is refused, nothing lost
    refused = grade(ch3, *common, "--merge-manual", scores, check=False)
    assert refused.returncode == 2 and "did you mean `ex-turning-three`?" in refused.stdout
    assert by_student(out / "grades.csv")["alice"]["ex-turning-three"] == "1"


def canvas_export(students, dialect):
    """A Canvas gradebook export (Grades, Export) saved in one of the dialects instructors save it in."""
    table = [["Student", "ID", "SIS User ID", "SIS Login ID", "Section", "Homework 3 (123456)"],
             ["    Points Possible", "", "", "", "", "3"]]
    table += [[f"{last}, {first}", canvas, sis, login, "A", ""] for first, last, canvas, sis, login in students]
    return spreadsheet([*table, ["Student, Test", "999", "", "", "A", ""]], dialect)


def test_canvas_folders_names_rosters_and_columns(tmp_path):
    """Canvas's zip of one assignment, unpacked as it comes, graded against Canvas's own gradebook export."""
    needs_root()
    rng = random.Random(3)
    people = [("Alice", "Liddell"), ("Bob", "Dodgson"), ("Carol", "Hare"), ("Dave", "Tenniel")]
    students = [(first, last, str(rng.randrange(10**5, 10**6)), f"{first.lower()}{k}", f"{first.lower()}@uni.edu")
                for k, (first, last) in enumerate(people)]
    subs, out = tmp_path / "submissions", tmp_path / "grading"
    for first, last, canvas, _, _ in students[:3]:
        late = "_late" if first == "Carol" else ""
        submission(subs / "hw3" / f"{last.lower()}{first.lower()}{late}_{canvas}_{rng.randrange(10**7)}_"
                                  f"{CHAPTER}-1.ipynb")
    submission(subs / "dave3" / f"alice0_{CHAPTER}.ipynb")  # Dave's folder, Alice's name on the file
    for dialect in ("comma", "excel-europe", "crlf", "tab"):
        roster = tmp_path / f"gradebook-{dialect}.csv"
        roster.write_bytes(canvas_export(students, dialect))
        result = grade(subs, "--roster", roster, "--seed", "s", "--out", out, "--canvas-column",
                       f"{CHAPTER}=Homework 3 (123456)", check=False)
        assert result.returncode == 3, result.stdout  # the file under another name needs the instructor
        grades = by_student(out / "grades.csv")
        assert {s: grades[s]["total"] for s in grades} == {"alice0": "2", "bob1": "2", "carol2": "2", "dave3": "0"}
        problems = (out / "problems.txt").read_text()
        assert "the file names `alice0` but lies in the folder of `dave3`" in problems
        canvas = rows(out / "canvas.csv")
        assert canvas[0] == ["Student", "ID", "SIS User ID", "SIS Login ID", "Section", "Homework 3 (123456)"]
        assert canvas[2][:3] == ["Liddell, Alice", students[0][2], "alice0"] and canvas[2][5] == "2"
        assert "Student, Test" not in "".join(map(str, canvas))
    again = grade(subs, "--roster", roster, "--seed", "s", "--out", out, check=False)  # the mapping is kept
    assert rows(out / "canvas.csv")[0][-1] == "Homework 3 (123456)" and again.returncode == 3


def test_deadlines_per_chapter_with_a_grace_period(tmp_path):
    needs_root()
    subs, out = tmp_path / "submissions", tmp_path / "grading"
    for student in ("ann", "ben", "cat"):
        submission(subs / student / f"{CHAPTER}.ipynb")
        submission(subs / student / f"{OTHER}.ipynb", chapter=OTHER)
    times = tmp_path / "times.csv"  # day first, as a European spreadsheet shows dates
    times.write_bytes(european(f"student_id,chapter,submitted\nann,{CHAPTER},01.03.2027 23:59:59\n"
                               f"ann,{OTHER},08.03.2027 23:00\nben,{CHAPTER},02.03.2027 00:14\n"
                               f"ben,{OTHER},10.03.2027 12:00\ncat,{CHAPTER},03.03.2027 10:00\ncat,{OTHER},08.03.2027 10:00\n"))
    grade(subs, "--seed", "s", "--out", out, "--deadline", f"{CHAPTER}=2027-03-01T23:59",
          "--deadline", f"{OTHER}=2027-03-08T23:59", "--submitted", times, "--grace", "15m")
    grades = by_student(out / "grades.csv")
    # ann: 59 s late for chapter 3, ben 14 min: both within the grace; ben 1.5 days late for chapter 4 (1 point),
    # cat 1.4 days for chapter 3 (2 points): each 2 days at 10 % of what the chapter earned
    assert [grades[s]["late_days"] for s in ("ann", "ben", "cat")] == ["0", "2", "2"]
    assert [grades[s]["penalty"] for s in ("ann", "ben", "cat")] == ["0", "0.2", "0.4"]
    grade(subs, "--seed", "s", "--out", out)  # a later run without the options keeps the policy
    assert by_student(out / "grades.csv")["cat"]["penalty"] == "0.4"


def test_a_grader_fault_is_the_instructors_never_a_students_zero(tmp_path):
    """A sandbox that cannot start: every student's grade left empty, not 0; the instructor told why."""
    needs_root()
    subs, out, fake = tmp_path / "submissions", tmp_path / "grading", tmp_path / "bin"
    reference = references()["turning_angles"]
    for student in ("ann", "ben"):
        submission(subs / student / f"{CHAPTER}.ipynb")
    submission(subs / "kim" / f"{CHAPTER}.ipynb", {"turning_angles": reference + "\n_uses = signals\n"},
               first_cells=["import os, signal\nsignals = 0\nfor s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):\n"
                            "    for pid in (1, os.getppid()):\n        try:\n            os.kill(pid, s)\n"
                            "            signals += 1\n        except OSError:\n            pass"])
    fake.mkdir()
    (fake / "mount").write_text('#!/bin/sh\ncase "$*" in *ddg-sandbox*) echo "mount: ddg-sandbox: permission denied '
                                'by policy" >&2; exit 32;; esac\nexec /usr/bin/mount "$@"\n')
    (fake / "mount").chmod(0o755 | stat.S_IXUSR)
    broken = grade(subs, "--seed", "s", "--out", out, check=False,
                   env={**os.environ, "PATH": f"{fake}:{os.environ['PATH']}"})
    assert broken.returncode == 3, broken.stdout
    grades = by_student(out / "grades.csv")
    assert {s: (grades[s]["ex-turning-angles"], grades[s]["total"]) for s in grades} == {
        s: ("", "0") for s in ("ann", "ben", "kim")}
    assert rows(out / "canvas.csv")[2][5] == ""  # no zero goes to Canvas either
    feedback = (out / "feedback" / "ann" / f"{CHAPTER}.txt").read_text()
    assert "not graded yet: the grader failed on this notebook (not your doing)" in feedback
    assert "mount" not in feedback and str(tmp_path) not in feedback
    assert "the grader failed on it" in (out / "problems.txt").read_text()
    assert "permission denied by policy" in (out / "grader-errors.log").read_text()

    fixed = grade(subs, "--seed", "s", "--out", out)  # once the machine is repaired: graded, nothing cached wrong
    assert fixed.returncode == 0, fixed.stdout
    grades = by_student(out / "grades.csv")
    assert {s: grades[s]["total"] for s in grades} == {"ann": "2", "ben": "2", "kim": "2"}  # kim's signals did nothing

    broken = grade(subs, "--seed", "s", "--out", out, "--student", "ann", check=False,
                   env={**os.environ, "PATH": f"{fake}:{os.environ['PATH']}"})
    assert broken.returncode == 3 and "its earlier result is kept meanwhile" in broken.stdout
    assert by_student(out / "grades.csv")["ann"]["total"] == "2"
