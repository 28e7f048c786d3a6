"""Journey: a student's answers in the student edition survive `make student` and `make clean`.

An instructor rebuilding the edition gets the outputs of notebooks whose code did not change from
the last build, unless ddg/ changed since: then every notebook runs again.
"""

import json
import os
import shutil
import signal
import subprocess
import time

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

    result = run(["make", "student", "FORCE=1"], cwd=copy)  # the student's changes discarded on purpose
    assert "my_answer" not in notebook.read_text()
    # nothing the outputs depend on changed (03's starter is back as it was): no notebook runs
    assert "only notebooks whose code changed run again" in result.stdout, result.stdout[-2000:]
    assert "Executing notebook" not in result.stdout and result.stdout.count("Using cached notebook") == 9
    assert "not written yet" in (copy / "_build" / "student" / "html" / "book" / "02_discrete_curves.html").read_text()

    # after a change to ddg/ the cache is dropped: the rebuild starts running the notebooks (it is
    # stopped there; the book's journey in test_rebuild.py sees such a rebuild to the end)
    checks = copy / "ddg" / "checks.py"
    checks.write_text(checks.read_text() + "\n# changed by the instructor\n")
    lines = started_notebook(copy)
    assert "every notebook of the student edition runs" in lines, lines[-20:]
    assert "Executing notebook" in lines[-1], lines[-20:]  # the first notebook runs, not its cached outputs

    run(["make", "clean"], cwd=copy)  # an unchanged edition is deleted freely
    assert not (copy / "_build").exists()
    # the other cases (rewriting an unchanged edition, make clean FORCE=1) are rules of ddg.edition,
    # tested without a build in tests/test_edition.py


def started_notebook(copy, limit=300):
    """Run `make student` in ``copy`` until jupyter-book starts executing a notebook or reuses one;
    stop it there and return the lines it printed."""
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PYTEST", "MAKE", "MFLAGS", "PYTHONPATH"))}
    process = subprocess.Popen(["make", "student"], cwd=copy, env=env, text=True, stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, start_new_session=True)
    lines, deadline = [], time.monotonic() + limit
    try:
        for line in process.stdout:
            lines.append(line.rstrip("\n"))
            if "Executing notebook" in line or "Using cached notebook" in line or time.monotonic() > deadline:
                break
    finally:
        try:
            os.killpg(process.pid, signal.SIGTERM)
        except ProcessLookupError:  # it had ended (and its lines say why)
            pass
        process.wait(timeout=30)
    return lines
