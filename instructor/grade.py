"""Grade a class: ``python -m instructor.grade SUBMISSIONS... --out grades.csv [--seed SECRET]``.

Each submission is a completed notebook of the student edition. For each one the grader

1. finds its chapter (the notebook's ``ddg.chapter`` metadata, else its file name) and that
   chapter's coding exercises, with their points, in the *instructor's* notebook (``--book``,
   metadata ``ddg.exercises``): a student cannot change what is graded or how much it counts;
2. runs the submission in its own process, in an empty temporary directory, with limits on time,
   memory and file size. On Linux, run as root, it also runs in a sandbox (:data:`SANDBOX`): no
   network, every file outside its folder read-only, no privileges; so it cannot change the
   grader's files or another submission's. Elsewhere it runs as the grader's user: grade there
   only notebooks you would run yourself, or inside a container;
3. there, executes every cell (a cell that fails or loops is stopped and skipped; a cell that
   kills the kernel is skipped after a restart), then runs each exercise's answer on input drawn
   from a seed derived from ``--seed`` (a secret the students never see) and sends back only
   what the answers returned;
4. judges those results itself, with the same checks the students use (``ddg.checks``).

It writes one CSV row per submission (``submission``, one column per exercise label with its
points, ``total``) and a feedback file per submission next to the CSV (what passed, and the first
problem of what did not). Submissions are graded in parallel, one per core.
"""

import argparse
import concurrent.futures
import csv
import hashlib
import json
import os
import pathlib
import secrets
import shutil
import signal
import subprocess
import sys
import tempfile

import numpy as np

from ddg import checks
from ddg._extras import missing

MARKER = "ddg-grade-results: "

SANDBOX = """
set -e
mount --make-rprivate /
awk '{print $5}' /proc/self/mountinfo | sort -r | while read -r m; do
    mount -o remount,bind,ro "$m" 2>/dev/null || true
done
mount --bind "$WORK" "$WORK"
mount -o remount,bind,rw "$WORK"
exec setpriv --bounding-set=-all --inh-caps=-all --no-new-privs -- "$@"
"""
"""Run by ``sh`` in new mount, network and process namespaces (``unshare``): every mount read-only
but the submission's folder ``$WORK``, then every capability dropped, so that nothing can be
mounted writable again. The network namespace has only loopback, and it is down. When the grader
ends the sandbox, every process in it ends too (kernels included)."""


def _sandbox():
    """The command prefix that puts a submission in :data:`SANDBOX`, or ``[]`` where it cannot."""
    tools = [shutil.which(tool) for tool in ("unshare", "setpriv", "mount", "awk")]
    if sys.platform.startswith("linux") and hasattr(os, "geteuid") and os.geteuid() == 0 and all(tools):
        return [tools[0], "--mount", "--net", "--pid", "--fork", "--kill-child", "sh", "-c", SANDBOX, "sandbox"]
    return []


def seed_for(secret, label):
    """The seed of one exercise: derived from the secret, the same for every submission."""
    return int.from_bytes(hashlib.sha256(f"{secret}/{label}".encode()).digest()[:8], "big")


def exercises(book):
    """``{chapter: {label: {"answer", "check", "points"}}}`` from the instructor's notebooks."""
    table = {}
    for path in sorted(pathlib.Path(book).glob("*.ipynb")):
        meta = json.loads(path.read_text()).get("metadata", {}).get("ddg", {})
        if meta.get("exercises"):
            table[meta.get("chapter", path.stem)] = meta["exercises"]
    return table


def chapter_of(submission, table):
    """The chapter a submission belongs to: its metadata, else the chapter named in its file name."""
    try:
        chapter = json.loads(pathlib.Path(submission).read_text()).get("metadata", {}).get("ddg", {}).get("chapter")
    except (OSError, ValueError, AttributeError):
        chapter = None
    if chapter in table:
        return chapter
    return next((c for c in table if c in pathlib.Path(submission).name), None)


# ------------------------------------------------------------------ inside the sandbox


EVALUATE = """
import json as _json
from ddg.checks import answer_results as _results
print({marker!r} + _json.dumps({{
    _label: _results(_name, globals().get(_answer), _seed, {limit!r})
    for _label, _name, _answer, _seed in {jobs!r}
}}))
"""


def run_one(notebook, jobs, cell_timeout, limit):
    """In the sandbox: execute ``notebook``, then the answers; print the raw results (one line)."""
    try:
        import nbformat
        from jupyter_client import AsyncKernelManager
        from nbclient import NotebookClient
        from nbclient.exceptions import DeadKernelError
    except ImportError as error:
        raise missing("grade", error) from error

    nb = nbformat.read(notebook, as_version=4)
    code = [cell for cell in nb.cells if cell.cell_type == "code"]
    evaluate = nbformat.v4.new_code_cell(EVALUATE.format(marker=MARKER, jobs=jobs, limit=limit))
    skipped = set()
    for _ in range(4):  # a cell that kills the kernel is skipped, and the notebook runs again
        # sockets are files in this folder: no TCP, so the kernel works without a network
        manager = AsyncKernelManager(kernel_name="python3", transport="ipc", ip=str(pathlib.Path("kernel").resolve()))
        client = NotebookClient(nbformat.v4.new_notebook(cells=[*code, evaluate]), km=manager,
                                interrupt_on_timeout=True, allow_errors=True,
                                timeout_func=lambda cell: limit * (len(jobs) + 1) if cell is evaluate else cell_timeout)
        try:
            with client.setup_kernel():
                for i, cell in enumerate(code):
                    if i not in skipped:
                        current = i
                        client.execute_cell(cell, i)
                current = len(code)
                client.execute_cell(evaluate, len(code))
            break
        except DeadKernelError:
            if current == len(code):
                break
            skipped.add(current)
    lines = [o.get("text", "") for o in evaluate.get("outputs", []) if o.get("output_type") == "stream"]
    results = next((line[len(MARKER):] for line in "".join(lines).splitlines()[::-1] if line.startswith(MARKER)),
                   "{}")
    print(MARKER + json.dumps({"results": json.loads(results), "skipped": sorted(skipped)}))


# ------------------------------------------------------------------ the grader


def _limits(memory, cpu):
    """Resource limits for the sandboxed process (run in the child before it starts)."""
    import resource

    def apply():
        os.setsid()
        resource.setrlimit(resource.RLIMIT_AS, (memory, memory))
        resource.setrlimit(resource.RLIMIT_CPU, (cpu, cpu + 5))
        resource.setrlimit(resource.RLIMIT_FSIZE, (50 << 20, 50 << 20))
    return apply


def grade_one(submission, table, secret, timeout, memory, cell_timeout, answer_timeout=checks.TIME_LIMIT):
    """Grade one submission: ``(points by label, feedback lines)``."""
    chapter = chapter_of(submission, table)
    if chapter is None:
        return {}, ["not graded: no chapter of the book with coding exercises matches this notebook"]
    labels = table[chapter]
    jobs = [(label, e["check"].removeprefix("check_"), e["answer"], seed_for(secret, label))
            for label, e in labels.items()]
    with tempfile.TemporaryDirectory(prefix="ddg-grade-") as work:
        work = pathlib.Path(work)
        shutil.copy(submission, work / "submission.ipynb")
        for name in ("runtime", "ipython", "matplotlib"):
            (work / name).mkdir()
        try:  # matplotlib's font list, so that each submission does not rebuild it
            import matplotlib

            for cache in pathlib.Path(matplotlib.get_cachedir()).glob("fontlist*.json"):
                shutil.copy(cache, work / "matplotlib")
        except ImportError:
            pass
        env = {"PATH": os.environ.get("PATH", "/usr/bin:/bin"), "HOME": str(work), "MPLBACKEND": "Agg",
               "JUPYTER_RUNTIME_DIR": str(work / "runtime"), "IPYTHONDIR": str(work / "ipython"),
               "MPLCONFIGDIR": str(work / "matplotlib"), "PYTHONPATH": os.pathsep.join(sys.path[1:]),
               "PYDEVD_DISABLE_FILE_VALIDATION": "1", "TMPDIR": str(work), "WORK": str(work)}
        command = [*_sandbox(), sys.executable, "-m", "instructor.grade", "--run-one", str(work / "submission.ipynb"),
                   "--jobs-json", json.dumps(jobs), "--cell-timeout", str(cell_timeout),
                   "--answer-timeout", str(answer_timeout)]
        with tempfile.TemporaryFile() as log:  # the grader's own file: only the runner's output lands here
            process = subprocess.Popen(command, cwd=work, env=env, stdout=log, stderr=subprocess.STDOUT,
                                       stdin=subprocess.DEVNULL, preexec_fn=_limits(memory, timeout))
            try:
                process.wait(timeout=timeout)
            except subprocess.TimeoutExpired:
                pass
            finally:
                try:
                    os.killpg(process.pid, signal.SIGKILL)  # the sandbox, and with it every process inside
                except ProcessLookupError:
                    pass
                process.wait()
            log.seek(max(0, log.seek(0, os.SEEK_END) - (16 << 20)))
            output = log.read()
    line = next((line for line in output.decode(errors="replace").splitlines()[::-1] if line.startswith(MARKER)), None)
    try:
        report = json.loads(line[len(MARKER):])
    except (TypeError, ValueError):
        report, line = {"results": {}, "skipped": []}, None
    points, feedback = {}, []
    if line is None:
        feedback.append(f"the notebook did not finish within {timeout} s or within the memory limit")
    for label, e in labels.items():
        raw = report["results"].get(label, {"error": "not graded: the notebook stopped before this exercise"})
        exercise = checks.EXERCISES[e["check"].removeprefix("check_")]
        calls, context = exercise.draw(np.random.default_rng(seed_for(secret, label)))
        verdict = checks.judge(exercise, calls, raw, context)
        verdict.name = e["answer"]
        points[label] = e["points"] if verdict else 0
        feedback.append(f"{label} ({points[label]}/{e['points']}): {verdict!r}")
    if report.get("skipped"):
        feedback.append(f"code cells {report['skipped']} stopped the kernel and were skipped")
    return points, feedback


def grade(submissions, book, out, secret, jobs=None, timeout=180, memory=4 << 30, cell_timeout=60,
          answer_timeout=checks.TIME_LIMIT):
    """Grade ``submissions`` in parallel; write the CSV ``out`` and a feedback folder next to it."""
    table = exercises(book)
    labels = [label for chapter in table.values() for label in chapter]
    out = pathlib.Path(out)
    folder = out.with_name(out.stem + "-feedback")
    folder.mkdir(parents=True, exist_ok=True)
    with concurrent.futures.ThreadPoolExecutor(jobs or os.cpu_count()) as pool:
        futures = {s: pool.submit(grade_one, s, table, secret, timeout, memory, cell_timeout, answer_timeout)
                   for s in submissions}
        graded = {s: f.result() for s, f in futures.items()}
    used = [label for label in labels if any(label in points for points, _ in graded.values())]
    with open(out, "w", newline="") as file:
        writer = csv.writer(file)
        writer.writerow(["submission", *used, "total"])
        for submission, (points, feedback) in graded.items():
            name = pathlib.Path(submission).name
            writer.writerow([name, *(points.get(label, "") for label in used), sum(points.values())])
            (folder / (pathlib.Path(submission).stem + ".txt")).write_text("\n".join([name, *feedback]) + "\n")
    return graded


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("submissions", nargs="*", help="completed notebooks of the student edition")
    parser.add_argument("--out", default="grades.csv", help="the CSV to write (feedback goes next to it)")
    parser.add_argument("--seed", help="a secret: the input of the checks is drawn from it (default: random)")
    parser.add_argument("--book", default="book", help="the instructor's notebooks (exercises and points)")
    parser.add_argument("--jobs", type=int, help="submissions graded at once (default: one per core)")
    parser.add_argument("--timeout", type=int, default=180, help="seconds for one submission")
    parser.add_argument("--memory", type=int, default=4096, help="megabytes for one submission")
    parser.add_argument("--cell-timeout", type=int, default=60, help="seconds for one cell")
    parser.add_argument("--answer-timeout", type=float, default=checks.TIME_LIMIT,
                        help=f"seconds for each exercise's answer on its input (default {checks.TIME_LIMIT:g}, as the checks)")
    parser.add_argument("--run-one", help=argparse.SUPPRESS)
    parser.add_argument("--jobs-json", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.run_one:  # inside the sandbox
        run_one(args.run_one, [tuple(job) for job in json.loads(args.jobs_json)], args.cell_timeout, args.answer_timeout)
        return
    if not args.submissions:
        parser.error("no submissions given")
    if not _sandbox():
        print("note: no sandbox on this machine (it needs Linux, root, unshare and setpriv): the "
              "submissions run as you, with time and memory limits only", file=sys.stderr)
    graded = grade(args.submissions, args.book, args.out, args.seed or secrets.token_hex(16), args.jobs,
                   args.timeout, args.memory << 20, args.cell_timeout, args.answer_timeout)
    print(f"graded {len(graded)} submissions: {args.out}, feedback in {pathlib.Path(args.out).stem}-feedback/")


if __name__ == "__main__":
    main()
