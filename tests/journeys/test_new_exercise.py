"""Journey: a new instructor adds an exercise with a check, following CONTRIBUTING.md to the letter.

On a copy of the repository, the guide's blocks are applied in its order (the code appended where
it says, the class added to the list of exercises below the line it names, the cells saved and
added with its command), and its commands are run. Before the catalogue entry is added, the check
of the exercises must name what is missing; after it, the new exercise's catalogue tests and its
chapter must pass, and the notebook must list the exercise for the grader.
"""

import json
import re
import subprocess

from journey_helpers import ROOT, copy_repository, run

BLOCK = re.compile(r"<!-- (append to|add to the list|cells|run):? ?([^>]*?) -->\n(`{3,})\w*\n(.*?)\n\3\n", re.S)


def steps():
    """The guide's blocks, in order: (kind, where, text)."""
    found = [(kind, where.strip(), text) for kind, where, _, text in BLOCK.findall((ROOT / "CONTRIBUTING.md").read_text())]
    assert [kind for kind, _, _ in found] == ["append to"] * 2 + ["add to the list", "append to", "cells", "run"], found
    return found


def test_an_exercise_added_from_the_guide_is_checked_graded_and_built(tmp_path):
    copy = copy_repository(tmp_path / "repo")
    blocks = steps()
    catalogue = next(b for b in blocks if b[1] == "tests/unit/catalogue.py")
    for kind, where, text in blocks:
        if kind == "append to" and where != "tests/unit/catalogue.py":
            with (copy / where).open("a") as file:
                file.write("\n\n" + text + "\n")
        elif kind == "add to the list":  # "FILE, after LINE": the block goes below the line that starts with LINE
            path, _, after = where.partition(", after ")
            lines = (copy / path).read_text().splitlines(keepends=True)
            at = next(i for i, line in enumerate(lines) if line.strip().startswith(after))
            (copy / path).write_text("".join(lines[:at + 1]) + text + "\n" + "".join(lines[at + 1:]))
        elif kind == "cells":
            (copy / where).write_text(text + "\n")
    commands = [line for line in blocks[-1][2].splitlines() if line.strip()]
    tests = [command for command in commands if command.startswith("make pytest")]
    for command in commands:  # the cells added to the chapter, formatted and linted
        if command not in tests:
            run(["bash", "-c", command], cwd=copy)

    # before the catalogue entry: the check of the exercises says what is missing, and where to read
    missing = run(["make", "pytest", "ARGS=tests/unit/test_checks.py -k every_coding_exercise -q"], cwd=copy,
                  check=False)
    assert missing.returncode != 0
    assert "signed_area: no entry in tests/unit/catalogue.py" in missing.stdout, missing.stdout[-3000:]
    assert "CONTRIBUTING.md" in missing.stdout

    with (copy / catalogue[1]).open("a") as file:
        file.write("\n\n" + catalogue[2] + "\n")
    for command in tests:
        result = run(["bash", "-c", command], cwd=copy)
        assert re.search(r"\d+ passed", result.stdout) and "failed" not in result.stdout, result.stdout[-3000:]

    chapter = json.loads((copy / "book" / "02_discrete_curves.ipynb").read_text())
    assert chapter["metadata"]["ddg"]["exercises"]["ex-signed-area"] == {
        "answer": "signed_area", "check": "check_signed_area", "points": 1}
    lint = subprocess.run([str(copy / ".venv" / "bin" / "python"), "tools/notebooks.py"], cwd=copy,
                          capture_output=True, text=True)
    assert lint.returncode == 0, lint.stdout
    # a student's wrong answer gets the mistake's own words
    code = ("import numpy as np; from ddg.checks import check_signed_area\n"
            "def signed_area(v):\n    x, y = np.asarray(v, float).T\n"
            "    return (x * np.roll(y, -1) - np.roll(x, -1) * y).sum() / 2\n"
            "print(check_signed_area(signed_area, seed=3))")
    said = run([str(copy / ".venv" / "bin" / "python"), "-c", code], cwd=copy, env={"PYTHONPATH": str(copy)})
    assert "usual counter-clockwise sign" in said.stdout, said.stdout
