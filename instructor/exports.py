"""What grading writes: the class's grades, a Canvas gradebook file, a feedback file per student and chapter.

``grades.csv`` has a row per student (every student of the roster, with or without a submission):
``student_id``, ``name``, a column per exercise of each chapter graded (coding exercises, then
written ones, empty until ``--merge-manual`` fills them), ``late_days`` and ``penalty`` (with a
deadline), and ``total``. ``canvas.csv`` is the same totals, one column per chapter, in the format
Canvas imports (Gradebook > Import): ``Student, ID, SIS User ID, SIS Login ID, Section``, then the
assignments (named as ``--canvas-column`` maps them), and a second row ``Points Possible``.
``feedback/<student>/<chapter>.txt`` is what the student reads; the executed notebook lies beside it.

What the instructor entered (written scores, deadlines, grace, penalty, submission times, Canvas
column names) is kept in ``instructor.json``, and each submission's latest result in ``records/``:
every later run starts from them, so a regrade, a late notebook or a run on one chapter only never
drops what an earlier run or the instructor put there (:func:`load_state`, :func:`save_records`).
"""

import csv
import datetime
import difflib
import hashlib
import json
import math
import os
import pathlib
import re

from dateutil import parser as dates

from . import report
from .roster import read_table

CANVAS = ["Student", "ID", "SIS User ID", "SIS Login ID", "Section"]


def safe(name):
    """``name`` as a folder name: letters, digits, ``.@_-`` kept; anything else, or a change, shows."""
    cleaned = re.sub(r"[^\w.@-]", "_", name).strip(".") or "_"
    return cleaned if cleaned == name else f"{cleaned}-{hashlib.sha256(name.encode()).hexdigest()[:6]}"


def feedback_path(out, student, chapter):
    return pathlib.Path(out) / "feedback" / safe(student) / f"{chapter}.txt"


def _time(text, where):
    """A date and time as instructors write them: ISO 8601 (2027-03-01T23:59+01:00), or as a
    spreadsheet shows it (01.03.2027 23:59 is day first; 3/1/2027 11:59 PM month first)."""
    text = text.strip()
    try:
        return dates.isoparse(text)
    except ValueError:
        pass
    try:
        return dates.parse(text, dayfirst="." in text)
    except (ValueError, OverflowError):
        raise ValueError(f"{where}: `{text}` is not a date and time like 2027-03-01T23:59 or "
                         f"2027-03-01T23:59+01:00") from None


def _duration(text):
    """Minutes in ``15``, ``15m``, ``2h``, ``90s`` or ``1d``."""
    match = re.fullmatch(r"\s*(\d+(?:\.\d+)?)\s*(s|m|min|h|d)?\s*", str(text))
    if not match:
        raise ValueError(f"--grace {text}: give minutes, or a number with s, m, h or d (15m, 2h)")
    return float(match.group(1)) * {"s": 1 / 60, "m": 1, "min": 1, "h": 60, "d": 1440}[match.group(2) or "m"]


def load_state(out):
    """What the instructor entered in earlier runs into ``out`` (``instructor.json``)."""
    try:
        state = json.loads((pathlib.Path(out) / "instructor.json").read_text(encoding="utf-8"))
    except FileNotFoundError:
        state = {}
    except (OSError, ValueError) as error:
        raise ValueError(f"{pathlib.Path(out) / 'instructor.json'}: cannot be read ({error}); it holds the scores "
                         "and deadlines you entered: repair it or move it away") from None
    for key in ("written", "deadlines", "submitted", "canvas_columns"):
        state.setdefault(key, {})
    return state


def save_state(out, state):
    _write_atomically(pathlib.Path(out) / "instructor.json", json.dumps(state, indent=1, sort_keys=True) + "\n")


def _write_atomically(path, text):
    path.parent.mkdir(parents=True, exist_ok=True)
    temporary = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    temporary.write_text(text, encoding="utf-8")
    os.replace(temporary, path)


def update_policy(state, table, deadlines=(), submitted=None, penalty=None, cutoff=None, grace=None):
    """Enter deadlines (``[CHAPTER=]WHEN``: one chapter's, or every chapter's), submission times (a CSV
    with ``student_id``, ``submitted`` and optionally ``chapter``), penalty, cutoff and grace into ``state``."""
    for text in deadlines:
        chapter, _, when = text.rpartition("=") if re.match(r"^[\w.-]+=", text) else ("", "", text)
        if chapter and chapter not in table:
            raise ValueError(f"--deadline {text}: `{chapter}` is no chapter of the book ({', '.join(sorted(table))})")
        state["deadlines"][chapter or "*"] = _time(when, "--deadline").isoformat()
    if submitted:
        columns, rows = read_table(submitted)
        lower = {c.lower(): c for c in columns}
        key = lower.get("student_id") or lower.get("id")
        if "submitted" not in lower or key is None:
            raise ValueError(f"{submitted}: it needs the columns student_id and submitted (it has: {', '.join(columns)})")
        for number, row in rows:
            when = _time(row.get(lower["submitted"], ""), f"{submitted} line {number}")
            chapter = row.get(lower.get("chapter", ""), "") or "*"
            state["submitted"].setdefault(row[key], {})[chapter] = when.isoformat()
    if penalty is not None:
        if not 0 <= penalty <= 100:
            raise ValueError(f"--late-penalty {penalty:g}: give a percentage between 0 and 100")
        state["penalty"] = penalty
    if cutoff is not None:
        state["cutoff"] = cutoff
    if grace is not None:
        state["grace_minutes"] = _duration(grace)
    if state["submitted"] and not state["deadlines"]:
        raise ValueError("--submitted needs a deadline: give --deadline (for every chapter, or CHAPTER=WHEN)")
    zones = {datetime.datetime.fromisoformat(t).tzinfo is None for t in state["deadlines"].values()} | {
        datetime.datetime.fromisoformat(t).tzinfo is None for times in state["submitted"].values() for t in times.values()}
    if len(zones) > 1:
        raise ValueError("give the deadlines and the submission times all with a time zone (+01:00) or all without")
    return state


def late(policy, student, chapter):
    """``(days late, share of the points lost)`` for one submission, under the state's late policy."""
    if not policy or not policy.get("deadlines"):
        return 0, 0.0
    deadline = policy["deadlines"].get(chapter) or policy["deadlines"].get("*")
    times = policy.get("submitted", {}).get(student, {})
    when = times.get(chapter) or times.get("*")
    if deadline is None or when is None:
        return 0, 0.0
    deadline = datetime.datetime.fromisoformat(deadline)
    when = datetime.datetime.fromisoformat(when)
    grace = datetime.timedelta(minutes=policy.get("grace_minutes", 0))
    if when <= deadline + grace:
        return 0, 0.0
    days = math.ceil((when - deadline).total_seconds() / 86400)
    if policy.get("cutoff") is not None and days > policy["cutoff"]:
        return days, 1.0
    return days, min(1.0, days * policy.get("penalty", 10) / 100)


def read_manual(path, table, students):
    """``{(student, label): score}`` from a CSV with ``student_id`` and a column per written exercise.

    Columns grades.csv has (so that a filled-in copy of it can be read back) and columns that are no
    exercise (a comment, an email) are ignored; a column that looks like a mistyped exercise label, an
    unknown student, a score that is not a number or is out of range is a ``ValueError``.
    A decimal comma (``1,5``) is read as a decimal point. An empty cell changes nothing.
    """
    written = {label: points for chapter in table.values() for label, points in chapter["written"].items()}
    coding = {label for chapter in table.values() for label in chapter["coding"]}
    scores = {}
    fields, rows = read_table(path)
    key = next((f for f in fields if f.lower() in ("student_id", "id")), None)
    if key is None:
        raise ValueError(f"{path}: no student_id column (its columns: {', '.join(fields)})")
    labels = [*written, *coding]
    strange = [f for f in fields if f not in written and f not in coding and f != key
               and (f.lower().startswith("ex-") or difflib.get_close_matches(f, labels, n=1, cutoff=0.75))]
    if strange:  # a label mistyped would silently score nothing; other columns (comments, email) are left alone
        near = difflib.get_close_matches(strange[0], labels, n=1, cutoff=0.6)
        raise ValueError(f"{path}: `{strange[0]}` is no written exercise of the book"
                         + (f" (did you mean `{near[0]}`?)" if near else "")
                         + f" (written exercises: {', '.join(sorted(written))})")
    for number, row in rows:
        student = row.get(key, "")
        if student not in students:
            raise ValueError(f"{path} line {number}: no student `{student}` among those graded or in the roster")
        for label in (f for f in fields if f in written and row.get(f)):
            try:
                score = float(row[label].replace(",", "."))
            except ValueError:
                raise ValueError(f"{path} line {number}, {label}: `{row[label]}` is not a number") from None
            if not 0 <= score <= written[label]:
                raise ValueError(f"{path} line {number}, {label}: {score:g} is not between 0 and "
                                 f"{written[label]:g}, the exercise's points")
            scores[(student, label)] = score
    return scores


def save_records(out, records):
    """Keep each record of this run (but a grader's fault) as the latest result of its submission."""
    for record in records:
        if not record.get("fault"):
            path = pathlib.Path(out) / "records" / safe(record["student"]) / f"{record['chapter']}.json"
            _write_atomically(path, json.dumps(record))


def load_records(out):
    """Every submission's latest result kept in ``out``, by ``(student, chapter)``."""
    records = {}
    for path in sorted((pathlib.Path(out) / "records").glob("*/*.json")):
        try:
            record = json.loads(path.read_text(encoding="utf-8"))
            records[(record["student"], record["chapter"])] = record
        except (OSError, ValueError, KeyError, TypeError):
            continue
    return records


def _number(x):
    return "" if x is None else f"{round(x, 2):g}"


def gradebook(records, table, roster, manual, policy):
    """The rows of grades.csv and of the Canvas file, with the chapters they cover.

    ``records`` are the latest result of each submission, ``manual`` the written scores
    ``{(student, label): score}`` and ``policy`` the late policy (see :func:`late`). A record of a
    grader's fault has no points: its cells stay empty, never 0."""
    records = [r for r in records if r["chapter"] in table]
    by = {(r["student"], r["chapter"]): r for r in records}
    written_chapter = {label: c for c, chapter in table.items() for label in chapter["written"]}
    chapters = sorted({r["chapter"] for r in records} | {written_chapter[label] for _, label in manual})
    students = list(roster) if roster else sorted({r["student"] for r in records} | {s for s, _ in manual})
    rows = []
    for student in students:
        row = {"student_id": student, "name": roster[student].name if roster else student, "chapters": {}}
        for chapter in chapters:
            record = by.get((student, chapter))
            coding = {label: (record["points"].get(label) if record else None) for label in table[chapter]["coding"]}
            written = {label: manual.get((student, label)) for label in table[chapter]["written"]}
            scores = {**coding, **written}
            graded = record is not None and not record.get("fault")
            days, share = late(policy, student, chapter) if graded else (0, 0.0)
            earned = sum(v for v in scores.values() if v is not None)
            row.update(scores)
            row["chapters"][chapter] = {"late_days": days, "penalty": round(earned * share, 2),
                                        "total": round(earned * (1 - share), 2),
                                        "present": graded or any(v is not None for v in written.values())}
        row["late_days"] = max((c["late_days"] for c in row["chapters"].values()), default=0)
        row["penalty"] = round(sum(c["penalty"] for c in row["chapters"].values()), 2)
        row["total"] = round(sum(c["total"] for c in row["chapters"].values()), 2)
        rows.append(row)
    return rows, chapters


def write_grades(path, rows, chapters, table, policy):
    labels = [label for c in chapters for label in [*table[c]["coding"], *table[c]["written"]]]
    columns = ["student_id", "name", *labels, *(["late_days", "penalty"] if policy and policy.get("deadlines") else []),
               "total"]
    with open(path, "w", newline="", encoding="utf-8") as file:
        writer = csv.writer(file)
        writer.writerow(columns)
        for row in rows:
            writer.writerow([row[c] if c in ("student_id", "name", "late_days") else _number(row.get(c)) for c in columns])


def write_canvas(path, rows, chapters, table, roster, columns=None):
    """Canvas's gradebook import: identity columns, a column per chapter, and the Points Possible row.

    ``columns`` maps a chapter to the header of an existing Canvas assignment (``Homework 3 (123456)``,
    as Canvas's own export names it), which Canvas's import then fills instead of adding a column."""
    possible = {c: sum(e.get("points", 1) for e in table[c]["coding"].values()) + sum(table[c]["written"].values())
                for c in chapters}
    with open(path, "w", newline="", encoding="utf-8") as file:
        writer = csv.writer(file)
        writer.writerow([*CANVAS, *((columns or {}).get(c, c) for c in chapters)])
        writer.writerow(["Points Possible", "", "", "", "", *(_number(possible[c]) for c in chapters)])
        for row in rows:
            student = roster[row["student_id"]] if roster else None
            writer.writerow([row["name"], student.canvas_id if student else "", row["student_id"],
                             (student.login or student.email) if student else "", student.section if student else "",
                             *(_number(row["chapters"][c]["total"]) if row["chapters"][c]["present"] else ""
                               for c in chapters)])


def write_feedback(records, rows, table, roster, out):
    """``feedback/<student>/<chapter>.txt`` for each submission graded."""
    by_student = {row["student_id"]: row for row in rows}
    paths = []
    for record in records:
        student, chapter = record["student"], record["chapter"]
        if student not in by_student or chapter not in by_student[student]["chapters"]:
            continue
        row, written = by_student[student], table[chapter]["written"]
        info = row["chapters"][chapter]
        name = roster[student].name if roster else student
        score = ("not graded yet" if record.get("fault") else
                 f"{_number(info['total'])} of {_number(sum(record['max'].values()) + sum(written.values()))}")
        lines = [f"{chapter}: {name} ({student})", f"notebook: {pathlib.PurePath(record['path']).name}",
                 f"score: {score}"]
        if info["late_days"]:
            lines.append(f"late by {info['late_days']} day{'s' * (info['late_days'] > 1)}: "
                         f"{_number(info['penalty'])} point{'s' * (info['penalty'] != 1)} off")
        lines += ["", *record["lines"]]
        if written:
            lines += ["", "written exercises (scored by hand):"]
            lines += [f"{label}: " + (f"{_number(row[label])}/{points:g}" if row.get(label) is not None
                                      else f"not scored yet (of {points:g})") for label, points in written.items()]
        path = feedback_path(out, student, chapter)
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text("\n".join(lines) + "\n", encoding="utf-8")
        paths.append(path)
    return paths


def executed_notebook(nb, entries):
    """The submission with the outputs of the cells that ran, and a last cell that says which ran."""
    nb = json.loads(json.dumps(nb))
    ran = {}
    for label, entry in entries.items():
        for i, cell in entry.get("cells", {}).items():
            ran.setdefault(int(i), (label, cell))
    for i, cell in enumerate(nb["cells"]):
        if cell.get("cell_type") != "code":
            continue
        cell["outputs"], cell["execution_count"] = [], None
        if i in ran:
            label, result = ran[i]
            for stream in ("stdout", "stderr"):
                if result.get(stream):
                    cell["outputs"].append({"output_type": "stream", "name": stream, "text": result[stream]})
            if result.get("error"):
                error = result["error"]
                cell["outputs"].append({"output_type": "error", "ename": error["ename"], "evalue": error["evalue"],
                                        "traceback": error.get("traceback", [])})
            cell.setdefault("metadata", {})["ddg_grading"] = {"ran_for": label, "seconds": result.get("seconds")}
    which = ", ".join(str(i + 1) for i in sorted(ran)) or "none"
    nb["cells"].append({"cell_type": "markdown", "id": "ddg-grading", "metadata": {},
                        "source": f"**Run by the grader**: cells {which} (the cells the graded answers need, "
                                  "with their outputs then); the others did not run."})
    return nb


def write_all(records, table, roster, out, problems, state):
    """Every output of a grading run in ``out``: ``records`` are every submission's latest result (this
    run's and those kept from earlier ones), ``state`` what the instructor entered; the main files."""
    out = pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    manual = {(student, label): score for student, scores in state.get("written", {}).items()
              for label, score in scores.items()}
    rows, chapters = gradebook(records, table, roster, manual, state)
    write_grades(out / "grades.csv", rows, chapters, table, state)
    write_canvas(out / "canvas.csv", rows, chapters, table, roster, state.get("canvas_columns"))
    write_feedback(records, rows, table, roster, out)
    (out / "problems.txt").unlink(missing_ok=True)
    if problems:
        (out / "problems.txt").write_text("\n".join(problems) + "\n", encoding="utf-8")
    graded = [r for r in records if not r.get("fault") and r["chapter"] in chapters]
    report.write(out / "report.html", graded, rows, chapters, table)
    return [out / "grades.csv", out / "canvas.csv", out / "report.html", out / "feedback"]
