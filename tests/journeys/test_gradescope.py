"""Journey: an instructor makes a Gradescope autograder, and it runs as Gradescope runs it.

`python -m instructor.grade --gradescope-autograder autograder.zip` writes the bundle; here it is
unpacked into /autograder/source of a temporary root (the machine's system, read-only, and its
Python), `setup.sh` builds the image there (from the wheelhouse: no network), and `run_autograder`
grades a right, a wrong and a hostile submission, each in /autograder/submission, into
/autograder/results/results.json, which must be what Gradescope reads.
"""

import json
import shutil
import stat
import sys
import zipfile

from grading_helpers import CHAPTER, HUNT, grade, in_root, needs_root, references, submission
from journey_helpers import WHEELHOUSE

SECRET = "gradescope-secret-not-for-students"
VISIBILITY = {"visible", "hidden", "after_due_date", "after_published"}


def test_the_gradescope_autograder_runs_as_gradescope_runs_it(tmp_path):
    needs_root()
    bundle = tmp_path / "autograder.zip"
    made = grade("--gradescope-autograder", bundle, "--chapter", CHAPTER, "--seed", SECRET)
    assert f"Gradescope autograder for {CHAPTER}: {bundle}" in made.stdout
    root = tmp_path / "root"
    source = root / "autograder" / "source"
    with zipfile.ZipFile(bundle) as archive:
        names = archive.namelist()
        assert {"setup.sh", "run_autograder", "requirements.txt", "autograder.json"} <= set(names)
        assert "ddg/checks/judge.py" in names and "instructor/harness.py" in names
        assert not any(name.endswith(".ipynb") for name in names)  # no notebook of the book, solutions and all
        assert all(SECRET not in archive.read(name).decode(errors="replace") for name in names)
        archive.extractall(source)
        for info in archive.infolist():
            if info.external_attr >> 16:
                (source / info.filename).chmod(stat.S_IMODE(info.external_attr >> 16))
    python = sys.base_prefix
    binds = {python: python, "/wheelhouse": WHEELHOUSE}  # read-only; /autograder is the root's own
    env = {"PATH": f"{python}/bin:/usr/local/bin:/usr/bin:/bin:/usr/sbin:/sbin", "HOME": "/root",
           "PIP_NO_INDEX": "1", "PIP_FIND_LINKS": "/wheelhouse", "PIP_DISABLE_PIP_VERSION_CHECK": "1"}
    setup = in_root(root, "bash /autograder/source/setup.sh", env, binds)
    assert setup.returncode == 0, setup.stdout[-3000:]
    shutil.copy(source / "run_autograder", root / "autograder" / "run_autograder")  # as Gradescope's image build does

    wrong = references()["rebuild"].replace("heading - ", "heading + ")
    results = {}
    for name, answers in (("right", {}), ("wrong", {"rebuild": wrong}), ("hostile", {"turning_angles": HUNT})):
        for folder in ("submission", "results"):
            shutil.rmtree(root / "autograder" / folder, ignore_errors=True)
            (root / "autograder" / folder).mkdir()
        submission(root / "autograder" / "submission" / f"my homework {name}.ipynb", answers)
        ran = in_root(root, "cd /autograder && ./run_autograder", env, binds)
        assert ran.returncode == 0, ran.stdout[-3000:]
        results[name] = json.loads((root / "autograder" / "results" / "results.json").read_text())

    for name, result in results.items():
        assert isinstance(result["score"], (int, float)) and isinstance(result["tests"], list), result
        assert [t["name"] for t in result["tests"]] == ["ex-rebuild: rebuild", "ex-turning-angles: turning_angles"]
        for test in result["tests"]:
            assert set(test) == {"name", "score", "max_score", "output", "visibility"}
            assert isinstance(test["output"], str) and test["visibility"] in VISIBILITY
            assert 0 <= test["score"] <= test["max_score"] == 1
        assert result["score"] == sum(t["score"] for t in result["tests"])
        assert result["output"] == f"graded: my homework {name}.ipynb"
    assert [t["score"] for t in results["right"]["tests"]] == [1, 1]
    assert [t["score"] for t in results["wrong"]["tests"]] == [0, 1]
    assert "the turns go the wrong way" in results["wrong"]["tests"][0]["output"]
    hostile = results["hostile"]["tests"][1]
    assert hostile["score"] == 0 and "it raised RuntimeError: found nothing" in hostile["output"], hostile["output"]
    assert SECRET not in json.dumps(results)

    shutil.rmtree(root / "autograder" / "submission")
    (root / "autograder" / "submission").mkdir()  # a student who uploaded no notebook
    assert in_root(root, "cd /autograder && ./run_autograder", env, binds).returncode == 0
    empty = json.loads((root / "autograder" / "results" / "results.json").read_text())
    assert empty["score"] == 0 and empty["output"].startswith("✗ no notebook (.ipynb) in your submission")
