"""Grade a class: ``python -m instructor.grade SUBMISSIONS... --seed-file SECRET --out grading``.

SUBMISSIONS are folders (one subfolder per student, or files named ``<student>_<chapter>.ipynb``)
or notebooks; ``instructor/roster.py`` says how each maps to one student and one chapter. For each
submission the grader

1. takes the chapter's coding exercises, their points and their checks from the *instructor's*
   notebooks (``--book``, metadata ``ddg.exercises``), and its written exercises from the
   ``{exercise}`` blocks there: never from the submission;
2. draws each exercise's hidden input here, from the secret, the student and the notebook's code
   (``seed_for``): an input that leaks is worth nothing to another student or to the next version
   of the notebook, and the same notebook always gets the same input and grade;
3. runs the cells each answer needs, then the answer on that input, one input per process, in the
   sandbox of ``instructor/sandbox.py`` (which never receives the secret or the answer key),
   through ``instructor/harness.py``;
4. judges the raw results here, with the students' own checks (``ddg.checks``) and the answer key
   (``instructor/references.py``), and writes feedback that says what happened (on the first
   input that went wrong only), with the executed notebook beside it.

Results are cached per notebook content (``DIR/cache``): a second run grades only what changed,
``--only`` and ``--student`` grade again what they name, and ``--shard K/N`` with ``--merge`` splits
a class over machines. The grades, the Canvas file, the feedback and the class report are written
by ``instructor/exports.py`` and ``instructor/report.py``; ``--gradescope-autograder`` writes a
Gradescope autograder instead (``instructor/gradescope.py``).

One submission never stops a class: whatever happens to it (a crash of the grader's own code
included, :func:`grade_safely`), the others are graded and every file is written. What the
instructor entered and each submission's latest result are kept in ``DIR`` for every later run
(``exports.load_state``). The exit code is 0 when every notebook was graded, 3 when one needs the
instructor (not graded, listed in ``problems.txt``, or failed by the grader), 2 for bad options.
"""

import argparse
import concurrent.futures
import functools
import hashlib
import json
import os
import pathlib
import re
import secrets
import sys
import time

import ddg
from ddg import checks
from ddg.checks.judge import Call, judge, printable, right_inputs

from . import exports, references, roster as rosters, sandbox

LIMITS = {"timeout": 180, "cell_timeout": 30, "answer_timeout": checks.TIME_LIMIT, "memory": 4096}
EXERCISE_BLOCK = re.compile(r"(?:`{3,}|:{3,})\{exercise\}[^\n]*\n((?:[ \t]*:[\w-]+:[^\n]*\n)*)")
MAX_NOTEBOOK = 32 << 20


def seed_for(secret, label, student="", code=""):
    """The seed of one exercise for one submission: from the secret, the student and the notebook's code
    (``code_key``), so that no two students and no two versions of a notebook share an input."""
    text = json.dumps([secret, label, student, code])
    return int.from_bytes(hashlib.sha256(text.encode()).digest()[:8], "big")


def code_key(cells):
    """What the input depends on in a notebook: its code cells (outputs and markdown may change)."""
    return hashlib.sha256(json.dumps([c for c in cells or () if c is not None]).encode()).hexdigest()


def exercises(book):
    """``{chapter: {"coding": {label: {answer, check, points[, partial]}}, "written": {label: points}}}``.

    From the instructor's notebooks: the metadata ``ddg.exercises`` (an entry without ``check`` is a
    written exercise with its ``points``), and every other ``{exercise}`` block's label (1 point).
    """
    table = {}
    for path in sorted(pathlib.Path(book).glob("*.ipynb")):
        nb = json.loads(path.read_text())
        meta = nb.get("metadata", {}).get("ddg", {}).get("exercises") or {}
        coding = {label: e for label, e in meta.items() if "check" in e}
        for label, e in coding.items():
            if e["check"] not in checks.CHECKS:
                raise ValueError(f"{path}: exercise {label}: ddg.checks has no `{e['check']}`")
        labels = [m.group(1) for cell in nb["cells"] if cell["cell_type"] == "markdown"
                  for block in EXERCISE_BLOCK.findall("".join(cell["source"]))
                  for m in [re.search(r":label:\s*(\S+)", block)] if m]
        written = {label: 1 for label in labels if label not in coding}
        written.update({label: e.get("points", 1) for label, e in meta.items() if "check" not in e})
        if coding or written:
            table[path.stem] = {"coding": coding, "written": written}
    return table


def draw_inputs(coding, secret, student="", code=""):
    """``{label: [{"args": specs, "what": description}]}``: the hidden input of each coding exercise of
    one submission (``coding``: a chapter's exercises)."""
    inputs = {}
    for label, e in coding.items():
        calls = checks.draw(checks.CHECKS[e["check"]], seed_for(secret, label, student, code))
        inputs[label] = json.loads(json.dumps([{"args": list(c.args), "what": c.what} for c in calls]))
    return inputs


def keyed(name, inputs):
    """The calls of exercise ``name`` on ``inputs`` (as :func:`draw_inputs` gives them), with the answer key."""
    return references.complete(name, [Call(tuple(c["args"]), c["what"]) for c in inputs])


@functools.cache
def version():
    """What a cached result depends on besides the submission and its input: ddg and the harness."""
    digest = hashlib.sha256()
    for path in sorted(pathlib.Path(ddg.__file__).parent.rglob("*.py")) + [sandbox.HARNESS, pathlib.Path(sandbox.__file__)]:
        digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


# ------------------------------------------------------------------ running a notebook (or not)


def parse_notebook(data):
    """``(cells, problem)``: the sources of a notebook's cells (``None`` for the ones that are not code)."""
    if len(data) > MAX_NOTEBOOK:
        return None, f"not a notebook: {len(data) >> 20} MB is more than the grader reads ({MAX_NOTEBOOK >> 20} MB)"
    try:
        nb = json.loads(data.decode("utf-8"))
    except UnicodeDecodeError:
        return None, "not a notebook: the file is not UTF-8 text"
    except ValueError as error:
        return None, f"not a notebook: the file is not valid JSON ({error})"
    if not isinstance(nb, dict) or not isinstance(nb.get("cells"), list):
        return None, "not a notebook: it is JSON, but without a list of cells"
    cells = []
    for i, cell in enumerate(nb["cells"], start=1):
        source = cell.get("source", "") if isinstance(cell, dict) else None
        if isinstance(source, list) and all(isinstance(s, str) for s in source):
            source = "".join(source)
        if not isinstance(source, str):
            return None, f"not a notebook: cell {i} has no text"
        cells.append(source if cell.get("cell_type") == "code" else None)
    return (nb, cells), None


class Cache:
    """Raw results by notebook content and exercise, in ``folder``; an entry is used only under its key."""

    def __init__(self, folder):
        self.folder = pathlib.Path(folder)

    def _path(self, sha, label, key):
        """One entry per notebook, exercise and key (two students with the same notebook get other input)."""
        return self.folder / sha[:2] / sha / f"{label}-{key[:16]}.json"

    def load(self, sha, label, key):
        try:
            data = json.loads(self._path(sha, label, key).read_text())
        except (OSError, ValueError):
            return None
        return data.get("entry") if data.get("key") == key else None

    def store(self, sha, label, key, entry):
        path = self._path(sha, label, key)
        path.parent.mkdir(parents=True, exist_ok=True)
        temporary = path.with_suffix(f".{os.getpid()}.tmp")
        temporary.write_text(json.dumps({"key": key, "entry": entry}))
        os.replace(temporary, path)


def run_notebook(data, coding, inputs, limits, cache=None, force=(), cached_only=False):
    """``(notebook, cells, {label: entry}, problem)``: what the harness found for each exercise (or the
    cache), or why the file is not a notebook."""
    parsed, problem = parse_notebook(data)
    if problem:
        return None, None, {label: {"notebook": problem} for label in coding}, problem
    nb, cells = parsed
    sha = hashlib.sha256(data).hexdigest()
    keys = {label: hashlib.sha256(json.dumps([sha, label, e, inputs[label], limits, version()],
                                             sort_keys=True).encode()).hexdigest() for label, e in coding.items()}
    entries = {}
    for label in coding:
        if cache is not None and label not in force:
            entry = cache.load(sha, label, keys[label])
            if entry is not None:
                entries[label] = {**entry, "cached": True}
    todo = [label for label in coding if label not in entries]
    if todo and cached_only:
        entries.update({label: {"ungraded": True} for label in todo})
    elif todo:
        job = {"cells": cells, "cell_timeout": limits["cell_timeout"], "answer_timeout": limits["answer_timeout"],
               "exercises": [{"label": label, "name": checks.CHECKS[coding[label]["check"]], "answer":
                              coding[label]["answer"], "specs": [c["args"] for c in inputs[label]]} for label in todo]}
        reports, facts = sandbox.run(job, limits["timeout"], limits["memory"] << 20)
        found = {r.get("label"): r for r in reports if isinstance(r, dict)}
        for label in todo:
            entry = found.get(label)
            if entry is None:
                entries[label] = {"failed": facts}
                continue
            entry["oom_kills"] = facts["oom_kills"]
            entries[label] = entry
            if cache is not None:
                cache.store(sha, label, keys[label], entry)
    return nb, cells, entries, None


# ------------------------------------------------------------------ what happened, in words


class GraderFault(Exception):
    """The grader, not the submission, failed (the sandbox did not start, the harness died): the
    instructor is told, the student gets no grade rather than a zero."""


def _head(cells, i):
    line = next((line.strip() for line in (cells[int(i)] or "").splitlines() if line.strip()), "")
    return printable(line if len(line) <= 40 else line[:37] + "...")


def _cell(cells, i):
    """A cell as the student finds it in JupyterLab: by its first line (JupyterLab shows no cell numbers)."""
    head = _head(cells, i)
    same = [j for j, c in enumerate(cells) if c is not None and _head(cells, j) == head]
    which = "" if len(same) < 2 else f" (the {_ordinal(same.index(int(i)) + 1)} cell that starts so)"
    return f"the cell starting `{head}`{which}" if head else f"an empty cell{which}"


def _ordinal(k):
    return f"{k}{'th' if 10 <= k % 100 <= 20 else {1: 'st', 2: 'nd', 3: 'rd'}.get(k % 10, 'th')}"


def cell_story(entry, cells, limits):
    """Lines on the cells that ran for one exercise: how many, and each error, stop or crash."""
    if not entry.get("ran") and not entry.get("stopped"):
        return []
    code = sum(c is not None for c in cells)
    lines = [f"ran {len(entry['ran'])} of the notebook's {code} code cells (those the answer needs)"] if entry.get(
        "ran") else []
    for i, cell in entry.get("cells", {}).items():
        error = cell.get("error")
        if cell.get("timeout"):
            lines.append(f"{_cell(cells, i)} was stopped at its time limit of {limits['cell_timeout']:g} s "
                         "(an endless loop?)")
        elif error:
            lines.append(f"{_cell(cells, i)} raised {printable(error['ename'])}: {printable(error['evalue'])[:200]}")
    for stop in entry.get("stopped", []):
        if stop.get("cell") is None:
            lines.append("the answer's process did not end in time and was stopped")
            continue
        where = _cell(cells, stop["cell"])
        how = stop.get("how", "")
        if stop["why"] == "time":
            what = f"did not stop at its time limit of {limits['cell_timeout']:g} s and was killed"
        elif stop["why"] == "flood":
            what = "printed more than the grader reads"
        elif how == "signal 9" and entry.get("oom_kills"):
            what = f"was killed for using more memory than the limit ({limits['memory']} MB)"
        elif how.startswith("signal"):
            what = f"crashed the Python process ({how})"
        else:
            what = f"ended the Python process (os._exit or a crash: {how})"
        lines.append(f"{where} {what}; the other cells ran again without it")
    return lines


def _failed(facts, limits):
    """The student's words for a run that gave no report: the whole notebook's time limit; anything else is
    the grader's fault (raised, with the sandbox's log for the instructor)."""
    if facts.get("timed_out"):
        return f"the notebook did not finish within {limits['timeout']:g} s (the limit for a whole submission)"
    raise GraderFault(f"the sandbox or the harness ended without a report (status {facts.get('status')}): "
                      f"{facts.get('log', '').strip() or 'no message'}")


def assess(label, meta, entry, inputs, cells, limits):
    """``{"points", "max", "lines", "problem", "right"}`` for one exercise of one submission."""
    name, answer, points = checks.CHECKS[meta["check"]], meta["answer"], meta.get("points", 1)
    exercise, raw, notes = checks.EXERCISES[name], entry.get("raw"), []
    calls = keyed(name, inputs)
    if "notebook" in entry:
        problem = entry["notebook"]
    elif entry.get("ungraded"):
        problem = "not graded: no shard has graded this notebook"
    elif "missing" in entry:
        syntax = entry["missing"]["syntax"]
        defining = [i for i, (_, _, defines) in syntax.items() if defines]
        if defining:
            line, message, _ = syntax[defining[-1]]
            problem = (f"{_cell(cells or [], defining[-1])}, which defines `{answer}`, has a SyntaxError on line "
                       f"{line}: {printable(message)}; the cell cannot run")
        else:
            broken = [_cell(cells or [], i) for i in syntax]
            problem = f"no `{answer}` in your notebook: no cell defines it" + (
                f" ({', '.join(broken)} could not be read: a SyntaxError)" if syntax else "")
    elif "failed" in entry:
        problem = _failed(entry["failed"], limits)
    elif entry.get("answer") is None:
        problem = f"`{answer}` was not defined after the cells that define it ran (see below)"
    else:
        verdict = judge(exercise, calls, raw, answer)
        problem, notes = verdict.problem, verdict.notes
    if "notebook" in entry:  # said once for the notebook, above the exercises
        return {"points": 0, "max": points, "lines": [f"{label}: 0/{points:g}"], "problem": problem,
                "right": [0, len(calls)]}
    right = right_inputs(exercise, calls, raw) if raw is not None else [False] * len(calls)
    earned = points if problem is None else round(points * sum(right) / len(calls), 2) if meta.get("partial") else 0
    verdict_line = (f"✓ {answer} passed on {len(calls)} hidden inputs" if problem is None
                    else f"✗ {answer}: {printable(problem)}")
    lines = [f"{label}: {earned:g}/{points:g}" + (f" ({sum(right)} of {len(calls)} inputs right)"
                                                    if meta.get("partial") and problem else ""), "  " + verdict_line]
    if problem is not None and isinstance(raw, list) and not all(right):  # the count only: the verdict names one input
        lines.append(f"  wrong on {len(right) - sum(right)} of {len(calls)} hidden inputs")
    lines += [f"  note: {printable(note)}" for note in notes]
    lines += ["  " + line for line in cell_story(entry, cells or [], limits)]
    return {"points": earned, "max": points, "lines": lines, "problem": problem, "right": [sum(right), len(calls)]}


# ------------------------------------------------------------------ a class


def grade_one(submission, table, secret, limits, out, forced, cached_only):
    """The record of one submission (the fields ``exports`` reads); its executed notebook is written to ``out``."""
    coding = table[submission.chapter]["coding"]
    try:
        data = submission.path.read_bytes()
    except OSError as error:
        data = f"not read: {error}".encode()
    parsed, _ = parse_notebook(data)
    inputs = draw_inputs(coding, secret, submission.student, code_key(parsed and parsed[1]))
    nb, cells, entries, problem = run_notebook(data, coding, inputs, limits, Cache(out / "cache"),
                                               forced(submission, coding), cached_only)
    record = {"student": submission.student, "chapter": submission.chapter, "path": str(submission.path),
              "points": {}, "max": {}, "problem": {}, "right": {}, "lines": [],
              "ungraded": any(e.get("ungraded") for e in entries.values()),
              "cached": bool(entries) and all(e.get("cached") for e in entries.values())}
    if problem:
        record["lines"].append(f"✗ {problem}")
    for label, meta in coding.items():
        result = assess(label, meta, entries[label], inputs[label], cells, limits)
        for field in ("points", "max", "problem", "right"):
            record[field][label] = result[field]
        record["lines"] += result["lines"]
    course = str(pathlib.Path(ddg.__file__).resolve().parents[1])  # where ddg is, in a message of the submission's
    record["lines"] = [line.replace(course, "<course>") for line in record["lines"]]
    if nb is not None and not record["ungraded"]:
        path = exports.feedback_path(out, submission.student, submission.chapter).with_suffix(".ipynb")
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(exports.executed_notebook(nb, entries), indent=1))
    return record


def grade_safely(submission, table, secret, limits, out, forced, cached_only):
    """:func:`grade_one`, or, when the grader fails on this submission, a record that says so: no
    points (not a zero), a line for the student, the traceback in ``grader-errors.log``."""
    try:
        return grade_one(submission, table, secret, limits, out, forced, cached_only)
    except Exception as error:  # noqa: BLE001 - one submission never stops a class
        import traceback

        coding = table[submission.chapter]["coding"]
        log = pathlib.Path(out) / "grader-errors.log"
        log.parent.mkdir(parents=True, exist_ok=True)
        with open(log, "a", encoding="utf-8") as file:
            file.write(f"--- {time.strftime('%Y-%m-%d %H:%M:%S')} {submission.student}, {submission.chapter}: "
                       f"{submission.path}\n{''.join(traceback.format_exception(error))}\n")
        reason = str(error).splitlines()[0][:200] if str(error) else type(error).__name__
        return {"student": submission.student, "chapter": submission.chapter, "path": str(submission.path),
                "points": {label: None for label in coding}, "max": {label: e.get("points", 1) for label, e in
                                                                     coding.items()},
                "problem": {label: None for label in coding}, "right": {label: [0, 0] for label in coding},
                "lines": ["✗ not graded yet: the grader failed on this notebook (not your doing); your instructor "
                          "has been told and will grade it again"],
                "ungraded": False, "cached": False, "fault": f"{type(error).__name__}: {reason}"}


def grade(submissions, table, secret, limits, out, jobs=None, only=(), students=(), cached_only=False, progress=None):
    """Grade ``submissions`` in parallel (``only`` exercises and ``students`` are graded afresh); their records.

    Whatever happens to one submission, the others are graded (:func:`grade_safely`)."""
    def forced(submission, coding):
        return set(coding) if submission.student in students else set(only) & set(coding)

    with concurrent.futures.ThreadPoolExecutor(jobs or os.cpu_count()) as pool:
        futures = [pool.submit(grade_safely, s, table, secret, limits, pathlib.Path(out), forced, cached_only)
                   for s in submissions]
        records = []
        for future in futures:
            records.append(future.result())
            if progress:
                progress(len(records), len(futures))
        return records


def _secret(args, parser):
    if args.seed and args.seed_file:
        parser.error("give --seed or --seed-file, not both")
    if args.seed_file:
        secret = pathlib.Path(args.seed_file).read_text().strip()
        if not secret:
            parser.error(f"--seed-file {args.seed_file} is empty")
        return secret
    if args.seed:
        return args.seed
    print("note: no --seed-file: the input is drawn from a random secret, so a later run cannot reuse these "
          "results (regrades, shards and the merge need the same secret)", file=sys.stderr)
    return secrets.token_hex(16)


def parser():
    p = argparse.ArgumentParser(prog="python -m instructor.grade", description=__doc__.split("\n\n")[0])
    p.add_argument("submissions", nargs="*", help="folders of submissions (one folder per student), or notebooks")
    p.add_argument("--out", default="grading", help="the folder to write into (default: grading)")
    p.add_argument("--roster", help="CSV with columns id, name[, email, section, sis_login_id, canvas_id]")
    p.add_argument("--seed-file", help="a file holding the secret the input is drawn from")
    p.add_argument("--seed", help="the secret itself (visible to your other processes: prefer --seed-file)")
    p.add_argument("--book", default=str(pathlib.Path(__file__).resolve().parents[1] / "book"),
                   help="the instructor's notebooks: exercises and points (default: the book of this repository)")
    p.add_argument("--only", action="append", default=[], metavar="LABEL", help="grade this exercise again")
    p.add_argument("--student", action="append", default=[], metavar="ID", help="grade this student again")
    p.add_argument("--shard", help="K/N: grade only the K-th of N equal parts of the class (then --merge)")
    p.add_argument("--merge", action="store_true", help="run nothing: write the outputs from the shards' results")
    p.add_argument("--merge-manual", metavar="CSV", help="scores of the written exercises (student_id, labels); "
                   "kept in OUT/instructor.json for every later run")
    p.add_argument("--deadline", action="append", default=[], metavar="[CHAPTER=]WHEN",
                   help="a deadline, ISO date and time (2027-03-01T23:59+01:00), for every chapter or one "
                        "(03_winding_number=2027-03-01T23:59); repeat for each chapter; kept for later runs")
    p.add_argument("--submitted", metavar="CSV", help="when each student submitted (student_id, submitted[, chapter])")
    p.add_argument("--grace", metavar="TIME", help="a submission this soon after the deadline is on time (15m, 2h)")
    p.add_argument("--late-penalty", type=float, help="percent of the points lost per day late (10)")
    p.add_argument("--late-cutoff", type=float, help="days after which a late submission earns nothing")
    p.add_argument("--canvas-column", action="append", default=[], metavar="CHAPTER=HEADER",
                   help="the Canvas assignment a chapter's total goes to, as its column is headed in Canvas's "
                        "gradebook export, e.g. '03_winding_number=Homework 3 (123456)'; kept for later runs")
    p.add_argument("--jobs", type=int, help="submissions graded at once (default: one per core)")
    p.add_argument("--timeout", type=float, default=LIMITS["timeout"], help="seconds for one submission (180)")
    p.add_argument("--cell-timeout", type=float, default=LIMITS["cell_timeout"], help="seconds for one cell (30)")
    p.add_argument("--answer-timeout", type=float, default=LIMITS["answer_timeout"],
                   help=f"seconds for an answer on all its input ({checks.TIME_LIMIT:g}, as the checks)")
    p.add_argument("--memory", type=int, default=LIMITS["memory"], help="megabytes for one submission (4096)")
    p.add_argument("--gradescope-autograder", metavar="ZIP", help="write a Gradescope autograder instead of grading")
    p.add_argument("--chapter", help="the chapter of the Gradescope autograder (its notebook's name)")
    return p


def main(argv=None):
    p = parser()
    args = p.parse_args(argv)
    try:
        table = exercises(args.book)
    except (OSError, ValueError) as error:
        p.error(f"--book {args.book}: {error}")
    if not table:
        p.error(f"--book {args.book}: no notebook there has exercises")
    limits = {"timeout": args.timeout, "cell_timeout": args.cell_timeout, "answer_timeout": args.answer_timeout,
              "memory": args.memory}
    secret = _secret(args, p)
    if args.gradescope_autograder:
        from . import gradescope

        chapter = gradescope.build(args.gradescope_autograder, table, args.chapter, secret, limits)
        print(f"Gradescope autograder for {chapter}: {pathlib.Path(args.gradescope_autograder).resolve()}")
        return
    if not args.submissions:
        p.error("no submissions given")
    out = pathlib.Path(args.out)
    if out.suffix == ".csv":
        p.error(f"--out is the folder to write into (grades.csv goes inside it), not {args.out}")
    try:
        roster = rosters.read_roster(args.roster) if args.roster else None
        submissions, problems = rosters.collect(args.submissions, table, roster)
        state = exports.load_state(out)
        exports.update_policy(state, table, args.deadline, args.submitted, args.late_penalty, args.late_cutoff,
                              args.grace)
        for text in args.canvas_column:
            chapter, equals, header = text.partition("=")
            if not equals or chapter not in table or not header.strip():
                raise ValueError(f"--canvas-column {text}: give CHAPTER=HEADER with a chapter of the book "
                                 f"({', '.join(sorted(table))}) and the assignment's column header in Canvas")
            state["canvas_columns"][chapter] = header.strip()
        earlier = exports.load_records(out)  # every submission's result from earlier runs
        students = set(roster or ()) | {s.student for s in submissions} | {student for student, _ in earlier}
        manual = exports.read_manual(args.merge_manual, table, students) if args.merge_manual else {}
    except (OSError, ValueError) as error:
        p.error(str(error))
    for (student, label), score in manual.items():
        state["written"].setdefault(student, {})[label] = score
    unknown = [label for label in args.only if not any(label in c["coding"] for c in table.values())]
    if unknown:
        p.error(f"--only {unknown[0]}: no coding exercise has this label")
    if args.merge and (args.only or args.student):
        p.error("--merge runs no notebook: --only and --student go with a run that grades")
    strangers = [s for s in args.student if s not in {sub.student for sub in submissions}]
    if strangers:
        p.error(f"--student {strangers[0]}: no submission of this student")
    graded_here = submissions
    if args.shard:
        match = re.fullmatch(r"(\d+)/(\d+)", args.shard)
        if not match or not 1 <= int(match.group(1)) <= int(match.group(2)):
            p.error(f"--shard {args.shard}: give K/N with 1 <= K <= N, for example 3/10")
        k, n = int(match.group(1)), int(match.group(2))
        graded_here = submissions[k - 1::n]
    if not sandbox.available() and not args.merge:
        print("note: no sandbox here (it needs Linux, root, unshare, mount and chroot, and namespaces): "
              "each submission runs as you and can read what you can (see INSTRUCTORS.md, Security)", file=sys.stderr)
    out.mkdir(parents=True, exist_ok=True)
    exports.save_state(out, state)  # what the instructor entered is kept before anything runs
    start = time.monotonic()

    def progress(done, total):
        if sys.stderr.isatty() and total > 1:
            print(f"\rgraded {done} of {total} submissions", end="\n" if done == total else "", file=sys.stderr,
                  flush=True)

    records = grade(graded_here, table, secret, limits, out, args.jobs, set(args.only), set(args.student), args.merge,
                    progress)
    seconds = time.monotonic() - start
    ungraded = [r for r in records if r["ungraded"]]
    if ungraded:
        sys.exit("error: no shard graded " + ", ".join(f"{r['path']}" for r in ungraded[:20])
                 + (" ..." if len(ungraded) > 20 else "") + ": run those shards again, or grade without --merge")
    faults = [r for r in records if r.get("fault")]
    if args.shard:
        print(f"shard {args.shard}: graded {len(records)} of {len(submissions)} submissions in {seconds:.0f} s; "
              f"when every shard is done: python -m instructor.grade ... --merge --out {out}")
        for record in faults:
            print(f"  grader fault: {record['path']}: {record['fault']}")
        return 3 if faults else 0
    exports.save_records(out, records)
    latest = {(r["student"], r["chapter"]): r for r in records}
    kept = {**latest, **{key: r for key, r in earlier.items() if key not in latest or latest[key].get("fault")}}
    problems = problems + [f"{r['path']}: not graded: the grader failed on it ({r['fault']}); the traceback is in "
                           f"{(out / 'grader-errors.log').resolve()}; grade it again once fixed"
                           + (" (its earlier result is kept meanwhile)" if key in earlier else "")
                           for key, r in latest.items() if r.get("fault")]
    written = exports.write_all(list(kept.values()), table, roster, out, problems, state)
    cached = sum(r["cached"] for r in records)
    others = sum(key not in latest for key in kept)
    print(f"graded {len(records)} submissions ({cached} from earlier results) in {seconds:.0f} s"
          + (f"; {others} results of earlier runs kept" if others else ""))
    if cached < len(records):
        print(f"  each submission's processes bounded together by: {sandbox.limits()}")
    for path in written:
        print(f"  {path.resolve()}")
    if problems:
        print(f"{len(problems)} notebook{'s' * (len(problems) != 1)} need{'s' * (len(problems) == 1)} you (also in "
              f"{(out / 'problems.txt').resolve()}):")
        for problem in problems:
            print(f"  {problem}")
        return 3
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except BrokenPipeError:  # the output piped into `head` and the like, which stopped reading
        sys.stderr.close()
        sys.exit(0)
