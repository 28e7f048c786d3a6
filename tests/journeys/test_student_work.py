"""Journey: a student's answers in the student edition survive `make student` and `make clean`."""

import json

from journey_helpers import copy_repository, run


def test_student_answers_are_never_deleted(tmp_path):
    copy = copy_repository(tmp_path / "repo")
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

    run(["make", "clean", "FORCE=1"], cwd=copy)
    assert not (copy / "_build").exists()
    run(["make", "student"], cwd=copy)  # an unchanged edition is rewritten, and cleaned, freely
    run(["make", "student"], cwd=copy)
    run(["make", "clean"], cwd=copy)
    assert not (copy / "_build").exists()
