"""Journey: a student's answers in the student edition survive `make student` and `make clean`.

An instructor rebuilding the edition gets the outputs of notebooks whose code did not change from
the last build, unless ddg/ changed since: then every notebook runs again.
"""

import json
import os
import queue
import shutil
import signal
import subprocess
import threading

from journey_helpers import ROOT, copy_repository, run, user_environment


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
    assert "Executing notebook" not in result.stdout and result.stdout.count("Using cached notebook") == len(list((ROOT / "book").glob("*.ipynb")))
    assert "not written yet" in (copy / "_build" / "student" / "html" / "book" / "02_discrete_curves.html").read_text()

    # FRESH=1, and after a change to ddg/ a plain rebuild, drop the cache: the first notebook runs
    # (the rebuild is stopped there; the book's journey in test_rebuild.py sees one to the end)
    checks, state = copy / "ddg" / "curve.py", copy / "_build" / "student" / "_build"
    saved = shutil.copytree(state, tmp_path / "saved")  # the cache and its record, as the build left them
    for command, change in ((["make", "student", "FRESH=1"], None), (["make", "student"], "# changed by the instructor\n")):
        shutil.rmtree(state, ignore_errors=True)
        shutil.copytree(saved, state)
        if change:
            checks.write_text(checks.read_text() + "\n" + change)
        lines = started_notebook(command, copy)
        assert "every notebook of the student edition runs" in lines, (command, lines[-20:])
        assert not any("Using cached notebook" in line for line in lines), (command, lines[-20:])
        assert "Executing notebook" in lines[-1], (command, lines[-20:])  # it runs, not its cached outputs

    run(["make", "clean"], cwd=copy)  # an unchanged edition is deleted freely
    assert not (copy / "_build").exists()
    # the other cases (rewriting an unchanged edition, make clean FORCE=1) are rules of instructor.edition,
    # tested without a build in tests/test_edition.py


def started_notebook(command, copy, limit=300):
    """Run ``command`` in ``copy`` until jupyter-book starts executing a notebook or reuses one (or
    ``limit`` seconds pass); stop it there and return the lines it printed."""
    process = subprocess.Popen(command, cwd=copy, env=user_environment(), text=True, stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, start_new_session=True)
    lines = queue.Queue()
    threading.Thread(target=lambda: [lines.put(line.rstrip("\n")) for line in process.stdout] + [lines.put(None)],
                     daemon=True).start()
    seen = []
    try:
        while True:
            line = lines.get(timeout=limit)  # queue.Empty: it printed nothing for `limit` seconds
            if line is None:
                break
            seen.append(line)
            if "Executing notebook" in line or "Using cached notebook" in line:
                break
    finally:
        try:
            os.killpg(process.pid, signal.SIGTERM)
        except ProcessLookupError:  # it had ended (and its lines say why)
            pass
        process.wait(timeout=30)
    return seen
