"""Journey: a student's answers in the student edition survive `make student` and `make clean`."""

import json
import shutil

from journey_helpers import ROOT, copy_repository, run


def test_student_answers_are_never_deleted(tmp_path):
    copy = copy_repository(tmp_path / "repo")
    built = ROOT / "_build" / "student"
    if (built / "html" / "index.html").exists():  # the edition `make test` has just made
        shutil.copytree(built, copy / "_build" / "student")
    else:
        run(["make", "student"], cwd=copy)
    notebook = copy / "_build" / "student" / "book" / "03_winding_number.ipynb"
    data = json.loads(notebook.read_text())
    starter = next(c for c in data["cells"] if "starter" in c["metadata"].get("tags", []))
    starter["source"] = "def turning_angles(vertices):\n    return my_answer(vertices)\n"
    notebook.write_text(json.dumps(data))

    for command in (["make", "student"], ["make", "clean"]):
        result = run(command, cwd=copy, check=False)
        assert result.returncode != 0, f"{' '.join(command)} did not refuse"
        assert "03_winding_number.ipynb" in result.stdout and "FORCE=1" in result.stdout, result.stdout
        assert "my_answer" in notebook.read_text(), f"{' '.join(command)} changed the student's notebook"

    run(["make", "student", "FORCE=1"], cwd=copy)  # the student's changes discarded on purpose
    assert "my_answer" not in notebook.read_text()
    run(["make", "clean"], cwd=copy)  # an unchanged edition is deleted freely
    assert not (copy / "_build").exists()
    # the other cases (rewriting an unchanged edition, make clean FORCE=1) are rules of ddg.edition,
    # tested without a build in tests/test_edition.py
