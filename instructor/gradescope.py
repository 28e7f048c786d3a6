"""A Gradescope autograder for one chapter: ``python -m instructor.grade --gradescope-autograder autograder.zip``.

The zip is what Gradescope's autograder specification asks for
(https://gradescope-autograders.readthedocs.io/en/latest/specs/): ``setup.sh`` and
``run_autograder`` at its root. Gradescope runs ``setup.sh`` once, as root, to build an image: it
installs a Python of 3.11 or newer, a virtual environment in ``/autograder/venv`` with the pins of
``requirements.txt`` (the packages the notebooks import, at the versions this grader uses), copies
``ddg`` into it, and closes ``/autograder/source`` to every user but root. For each submission
Gradescope starts a fresh container with the student's files in ``/autograder/submission`` and runs
``run_autograder``, which runs this module (:func:`run`): the notebook in the submission is graded
as ``python -m instructor.grade`` grades it (the same sandbox where the container allows one; else
as a user of its own), and ``/autograder/results/results.json`` gets one test per coding exercise
(``name``, ``score``, ``max_score``, ``output``: the feedback, ``visibility``).

The bundle holds ``ddg`` (the checks), ``instructor`` (the grader and its answer key) and
``autograder.json``: the chapter's exercises and points from the instructor's notebook, the limits
and a key derived from the secret for this chapter alone (never the secret itself), from which each
submission's hidden input is drawn for its student (the user ids in Gradescope's
``submission_metadata.json``) and its code, as ``python -m instructor.grade`` draws it. The zip is
the instructor's (Gradescope keeps it in ``/autograder/source``, which ``setup.sh`` closes to every
user but root); the sandbox receives neither that key nor the answer key, and no notebook of the
book is in the bundle.
"""

import hashlib
import json
import pathlib
import re
import sys
import time
import zipfile

ROOTS = ("numpy", "matplotlib", "shapely", "ipython", "ipywidgets", "pillow", "tqdm")
"""What the chapters' notebooks import; the bundle pins these and everything they need."""

SETUP = """#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder's image.
set -euo pipefail
cd /autograder/source
python=""
for version in {versions}; do
    if command -v "python$version" >/dev/null; then python="$(command -v "python$version")"; break; fi
done
if [ -z "$python" ]; then  # Ubuntu 22.04 has Python 3.10 only: 3.11 is in its universe archive
    apt-get update && apt-get install -y python3.11 python3.11-venv
    python=/usr/bin/python3.11
fi
"$python" -m venv /autograder/venv
/autograder/venv/bin/python -m pip install --quiet --no-cache-dir -r requirements.txt
cp -r ddg "$(/autograder/venv/bin/python -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')/"
chmod -R a+rX /autograder/venv
/autograder/venv/bin/python -c "import matplotlib.pyplot"  # matplotlib's font list, built once, not per submission
chmod 700 /autograder/source
"""

RUN = """#!/usr/bin/env bash
# Gradescope runs this for every submission, as root, in a fresh container.
cd /autograder/source
PYTHONPATH=/autograder/source exec /autograder/venv/bin/python -m instructor.gradescope
"""

VISIBILITY = "visible"
"""Who sees each test's result: ``autograder.json`` in the zip may say ``after_due_date`` instead (Gradescope's values)."""


def _canonical(name):
    return re.sub(r"[-_.]+", "-", name).lower()


def requirements():
    """``name==version`` for :data:`ROOTS` and all they require, as installed here."""
    from importlib import metadata

    from packaging.requirements import Requirement

    pins, todo = {}, list(ROOTS)
    while todo:
        name = _canonical(todo.pop())
        if name in pins:
            continue
        distribution = metadata.distribution(name)
        pins[name] = distribution.version
        for line in distribution.requires or []:
            requirement = Requirement(line)
            if requirement.marker is None or requirement.marker.evaluate({"extra": ""}):
                todo.append(requirement.name)
    return [f"{name}=={version}" for name, version in sorted(pins.items())]


def build(path, table, chapter, secret, limits):
    """Write the autograder zip for ``chapter`` (the only chapter with coding exercises if ``None``)."""
    import ddg


    coded = [c for c, chapter_table in table.items() if chapter_table["coding"]]
    if chapter is None:
        if len(coded) != 1:
            raise SystemExit(f"error: name the chapter of the autograder with --chapter (one of {', '.join(coded)})")
        chapter = coded[0]
    if chapter not in coded:
        raise SystemExit(f"error: --chapter {chapter}: no chapter with coding exercises has this name "
                         f"(one of {', '.join(coded)})")
    coding = table[chapter]["coding"]
    key = hashlib.sha256(json.dumps(["gradescope", secret, chapter]).encode()).hexdigest()  # this chapter's only
    config = {"chapter": chapter, "coding": coding, "secret": key, "limits": limits, "visibility": VISIBILITY}
    minor = sys.version_info[1]
    versions = " ".join(f"3.{m}" for m in [minor, *(m for m in (13, 12, 11) if m != minor)])
    package = pathlib.Path(ddg.__file__).parent
    here = pathlib.Path(__file__).parent
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as bundle:
        for name, text, mode in (("setup.sh", SETUP.format(versions=versions), 0o755), ("run_autograder", RUN, 0o755),
                                 ("requirements.txt", "\n".join(requirements()) + "\n", 0o644),
                                 ("autograder.json", json.dumps(config, indent=1), 0o644)):
            info = zipfile.ZipInfo(name, date_time=(2020, 1, 1, 0, 0, 0))
            info.external_attr = (0o100000 | mode) << 16
            bundle.writestr(info, text)
        for source in sorted(package.rglob("*.py")):
            bundle.write(source, "ddg/" + source.relative_to(package).as_posix())
        for source in sorted(here.glob("*.py")):
            bundle.write(source, f"instructor/{source.name}")
    return chapter


def _notebook(folder, chapter):
    """The submitted notebook: the only one, or the only one named after the chapter; else why not."""
    found = [p for p in sorted(pathlib.Path(folder).rglob("*.ipynb"))
             if not any(part.startswith(".") for part in p.relative_to(folder).parts)]
    named = [p for p in found if chapter in p.name]
    if len(found) == 1:
        return found[0], None
    if len(named) == 1:
        return named[0], None
    if not found:
        return None, "no notebook (.ipynb) in your submission: upload your completed notebook"
    return None, (f"{len(found)} notebooks in your submission ({', '.join(p.name for p in found)}): upload only "
                  f"{chapter}.ipynb")


def run(root="/autograder"):
    """Grade the submission in ``root/submission``; write ``root/results/results.json``, always: a fault of
    the grader is said there (and its traceback printed for the instructor, in the autograder's output)."""
    root = pathlib.Path(root)
    start = time.monotonic()
    try:
        return _run(root, start)
    except Exception:  # noqa: BLE001 - Gradescope needs its results.json whatever happened
        import traceback

        traceback.print_exc()
        results = {"score": 0, "execution_time": round(time.monotonic() - start),
                   "output": "✗ not graded: the autograder failed on this submission (not your doing); your "
                             "instructor can see why and will grade it again", "tests": []}
        (root / "results").mkdir(parents=True, exist_ok=True)
        (root / "results" / "results.json").write_text(json.dumps(results, indent=1))
        return results


def _student(root):
    """Who submitted, as Gradescope's ``submission_metadata.json`` says (its users' ids; "" if it does not)."""
    try:
        users = json.loads((root / "submission_metadata.json").read_text()).get("users") or []
        return ",".join(sorted(str(u.get("id", "")) for u in users if isinstance(u, dict)))
    except (OSError, ValueError, AttributeError):
        return ""


def _run(root, start):
    from . import grade

    config = json.loads((root / "source" / "autograder.json").read_text())
    chapter, coding, limits = config["chapter"], config["coding"], config["limits"]
    path, problem = _notebook(root / "submission", chapter)
    data = path.read_bytes() if path is not None else b""
    parsed, _ = grade.parse_notebook(data)
    inputs = grade.draw_inputs(coding, config["secret"], _student(root), grade.code_key(parsed and parsed[1]))
    if path is None:
        cells, entries = [], {label: {"notebook": problem} for label in coding}
    else:
        _, cells, entries, problem = grade.run_notebook(data, coding, inputs, limits)
    output = "\n".join(line for line in (path and f"graded: {path.relative_to(root / 'submission')}",
                                          problem and f"✗ {problem}") if line)
    tests = []
    for label, meta in coding.items():
        result = grade.assess(label, meta, entries[label], inputs[label], cells, limits)
        tests.append({"name": f"{label}: {meta['answer']}", "score": result["points"], "max_score": result["max"],
                      "output": "\n".join(result["lines"]), "visibility": config.get("visibility", VISIBILITY)})
    results = {"score": round(sum(t["score"] for t in tests), 2), "execution_time": round(time.monotonic() - start),
               "output": output, "tests": tests}
    (root / "results").mkdir(parents=True, exist_ok=True)
    (root / "results" / "results.json").write_text(json.dumps(results, indent=1))
    return results


if __name__ == "__main__":
    run()
