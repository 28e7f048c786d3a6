"""`make bench`, part 2: how many submissions a minute `python -m instructor.grade` grades.

Classes of 30 completed notebooks of chapter 3 (two coding exercises), made from the student
edition, one folder per student, graded in one run each with the grader's default limits, in
parallel over the machine's cores, each submission in its own sandbox (where it can be made):

* an ordinary class: two thirds right, one third with a wrong answer;
* a class with loops: the same, but one submission in ten has an exploring cell that never ends
  (no answer needs it: it never runs) and a `turning_angles` that never returns (stopped at the
  answer limit, 10 s);
* the worst case for loops: one in ten has a cell that never ends *and* is needed by an answer
  (stopped at the cell limit, 30 s).

Every run starts with an empty cache: nothing is reused.
"""

import os
import pathlib
import re
import resource
import subprocess
import sys
import tempfile
import time

import nbformat

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))
from instructor import edition, sandbox  # noqa: E402

CHAPTER = ROOT / "book" / "03_winding_number.ipynb"
COUNT = 30


def make_class(folder, loops=None):
    source = nbformat.read(CHAPTER, as_version=4)
    reference = {re.search(r"def (\w+)", c.source).group(1): c.source for c in source.cells
                 if "solution" in c.metadata.get("tags", [])}
    expected = {}
    for i in range(COUNT):
        nb = edition.student_notebook(source)
        looping = loops is not None and i % 10 == 5
        for cell in nb.cells:
            if "starter" in cell.metadata.get("tags", []):
                name = re.search(r"def (\w+)", cell.source).group(1)
                cell.source = reference[name] + f"\n# student {i}\n"
                if i % 3 == 2 and name == "rebuild":
                    cell.source = cell.source.replace("heading - ", "heading + ")
                if looping and loops == "answer" and name == "turning_angles":
                    cell.source = "def turning_angles(vertices):\n    while True:\n        pass\n"
                if looping and loops == "needed" and name == "turning_angles":
                    cell.source += "\n_explored = exploring\n"
        if looping:
            nb.cells.insert(2, nbformat.v4.new_code_cell("exploring = True\nwhile exploring:\n    pass"))
        expected[f"s{i:02d}"] = 2 - (i % 3 == 2) - (looping and loops == "answer")
        path = folder / f"s{i:02d}" / "03_winding_number.ipynb"
        path.parent.mkdir(parents=True)
        nbformat.write(nb, path)
    return expected


def grade(loops=None):
    """Seconds of wall-clock time and of CPU time (the grader and every process it started) for a class."""
    with tempfile.TemporaryDirectory() as folder:
        folder = pathlib.Path(folder)
        expected = make_class(folder / "submissions", loops)
        before, start = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
        subprocess.run([sys.executable, "-m", "instructor.grade", str(folder / "submissions"), "--out",
                        str(folder / "grading"), "--seed", "bench"], check=True, capture_output=True, cwd=ROOT)
        seconds, after = time.perf_counter() - start, resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
        lines = (folder / "grading" / "grades.csv").read_text().splitlines()[1:]
        totals = {line.split(",")[0]: int(line.rsplit(",", 1)[1]) for line in lines}
    assert totals == expected, (totals, expected)
    return seconds, cpu


def main():
    where = "each in its own sandbox" if sandbox.available() else "without a sandbox (not root, or not Linux)"
    print(f"\ngrading classes of {COUNT} submissions of chapter 3 on {os.cpu_count()} cores, {where}:")
    for title, loops in (("an ordinary class", None), ("1 in 10 with a loop (an unused cell, the answer)", "answer"),
                         ("1 in 10 with a loop in a cell an answer needs", "needed")):
        load = os.getloadavg()[0]
        seconds, cpu = grade(loops)
        print(f"  {title}: {seconds:.1f} s, {60 * COUNT / seconds:.1f} submissions a minute "
              f"({cpu / COUNT:.2f} CPU-seconds each; load average {load:.1f} before, {os.getloadavg()[0]:.1f} after)")


if __name__ == "__main__":
    main()
