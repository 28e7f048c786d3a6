"""`make bench`, part 2: how many submissions a minute `python -m instructor.grade` grades.

Fifty completed notebooks of chapter 3 (two coding exercises), made from the student edition:
two thirds right, one third with a wrong answer. They are graded in one run, in parallel over the
machine's cores, each in its own sandboxed process.
"""

import os
import pathlib
import re
import subprocess
import sys
import tempfile
import time

import nbformat

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))
from instructor import edition  # noqa: E402

CHAPTER = ROOT / "book" / "03_winding_number.ipynb"


def main(count=50):
    source = nbformat.read(CHAPTER, as_version=4)
    reference = {re.search(r"def (\w+)", c.source).group(1): c.source for c in source.cells
                 if "solution" in c.metadata.get("tags", [])}
    with tempfile.TemporaryDirectory() as folder:
        folder = pathlib.Path(folder)
        for i in range(count):
            nb = edition.student_notebook(source)
            for cell in nb.cells:
                if "starter" in cell.metadata.get("tags", []):
                    name = re.search(r"def (\w+)", cell.source).group(1)
                    cell.source = reference[name]
                    if i % 3 == 2 and name == "rebuild":
                        cell.source = cell.source.replace("heading - ", "heading + ")
            nbformat.write(nb, folder / f"student{i:02d}.ipynb")
        start = time.perf_counter()
        subprocess.run([sys.executable, "-m", "instructor.grade", *map(str, sorted(folder.glob("*.ipynb"))),
                        "--out", str(folder / "grades.csv"), "--seed", "bench", "--book", str(ROOT / "book")],
                       check=True, capture_output=True)
        seconds = time.perf_counter() - start
        totals = [line.rsplit(",", 1)[1] for line in (folder / "grades.csv").read_text().splitlines()[1:]]
    assert totals.count("2") == count - count // 3 and totals.count("1") == count // 3, totals
    print(f"\ngrading {count} submissions of chapter 3 on {os.cpu_count()} cores: {seconds:.1f} s, "
          f"{60 * count / seconds:.1f} submissions a minute, {seconds / count:.2f} s each on average")


if __name__ == "__main__":
    main()
