"""What grading writes: the class's grades, a Canvas gradebook file, a feedback file per student and chapter.

``grades.csv`` has a row per student (every student of the roster, with or without a submission):
``student_id``, ``name``, a column per exercise of each chapter graded (coding exercises, then
written ones, empty until ``--merge-manual`` fills them), ``late_days`` and ``penalty`` (with a
deadline), and ``total``. ``canvas.csv`` is the same totals, one column per chapter, in the format
Canvas imports (Gradebook > Import): ``Student, ID, SIS User ID, SIS Login ID, Section``, then the
assignments, and a second row ``Points Possible``. ``feedback/<student>/<chapter>.txt`` is what
the student reads; the executed notebook lies beside it.
"""

import csv
import datetime
import hashlib
import json
import math
import pathlib
import re

from . import report

CANVAS = ["Student", "ID", "SIS User ID", "SIS Login ID", "Section"]


def safe(name):
    """``name`` as a folder name: letters, digits, ``.@_-`` kept; anything else, or a change, shows."""
    cleaned = re.sub(r"[^\w.@-]", "_", name).strip(".") or "_"
    return cleaned if cleaned == name else f"{cleaned}-{hashlib.sha256(name.encode()).hexdigest()[:6]}"


def feedback_path(out, student, chapter):
    return pathlib.Path(out) / "feedback" / safe(student) / f"{chapter}.txt"


def _time(text, where):
    try:
        return datetime.datetime.fromisoformat(text.strip())
    except ValueError:
        raise ValueError(f"{where}: `{text}` is not a date and time like 2027-03-01T23:59 or "
                         f"2027-03-01T23:59+01:00") from None


def late_policy(deadline, submitted, penalty, cutoff):
    """The late policy (``None`` without a deadline): the deadline, each submission's time, the penalty."""
    if not deadline and not submitted:
        return None
    if not deadline or not submitted:
        raise ValueError("--deadline and --submitted go together: the deadline, and when each student submitted")
    if not 0 <= penalty <= 100:
        raise ValueError(f"--late-penalty {penalty:g}: give a percentage between 0 and 100")
    deadline, times = _time(deadline, "--deadline"), {}
    with open(submitted, newline="", encoding="utf-8-sig") as file:
        reader = csv.DictReader(file)
        fields = [f.strip().lower() for f in reader.fieldnames or []]
        if "submitted" not in fields or not {"student_id", "id"} & set(fields):
            raise ValueError(f"{submitted}: it needs the columns student_id and submitted (it has: {', '.join(fields)})")
        for number, row in enumerate(reader, start=2):
            row = {k.strip().lower(): (v or "").strip() for k, v in row.items() if k}
            when = _time(row["submitted"], f"{submitted} line {number}")
            if (when.tzinfo is None) != (deadline.tzinfo is None):
                raise ValueError(f"{submitted} line {number}: give the deadline and the times both with a time zone "
                                 "(+01:00) or both without")
            times[(row.get("student_id") or row.get("id"), row.get("chapter") or None)] = when
    return {"deadline": deadline, "times": times, "penalty": penalty, "cutoff": cutoff}


def late(policy, student, chapter):
    """``(days late, share of the points lost)`` for one submission."""
    if not policy:
        return 0, 0.0
    when = policy["times"].get((student, chapter)) or policy["times"].get((student, None))
    if when is None or when <= policy["deadline"]:
        return 0, 0.0
    days = math.ceil((when - policy["deadline"]).total_seconds() / 86400)
    if policy["cutoff"] is not None and days > policy["cutoff"]:
        return days, 1.0
    return days, min(1.0, days * policy["penalty"] / 100)


def read_manual(path, table, students):
    """``{(student, label): score}`` from a CSV with ``student_id`` and a column per written exercise.

    Columns grades.csv has (so that a filled-in copy of it can be read back) are ignored; any other
    column, an unknown student, a score that is not a number or is out of range is a ``ValueError``.
    """
    written = {label: points for chapter in table.values() for label, points in chapter["written"].items()}
    coding = {label for chapter in table.values() for label in chapter["coding"]}
    scores = {}
    with open(path, newline="", encoding="utf-8-sig") as file:
        reader = csv.DictReader(file)
        fields = [f.strip() for f in reader.fieldnames or []]
        key = next((f for f in fields if f.lower() in ("student_id", "id")), None)
        if key is None:
            raise ValueError(f"{path}: no student_id column (its columns: {', '.join(fields)})")
        strange = [f for f in fields if f not in written and f not in coding and f != key
                   and f.lower() not in ("name", "late_days", "penalty", "total")]
        if strange:
            raise ValueError(f"{path}: `{strange[0]}` is no written exercise of the book "
                             f"(written exercises: {', '.join(sorted(written))})")
        for number, row in enumerate(reader, start=2):
            row = {k.strip(): (v or "").strip() for k, v in row.items() if k}
            student = row[key]
            if student not in students:
                raise ValueError(f"{path} line {number}: no student `{student}` among those graded or in the roster")
            for label in (f for f in fields if f in written and row.get(f)):
                try:
                    score = float(row[label])
                except ValueError:
                    raise ValueError(f"{path} line {number}, {label}: `{row[label]}` is not a number") from None
                if not 0 <= score <= written[label]:
                    raise ValueError(f"{path} line {number}, {label}: {score:g} is not between 0 and "
                                     f"{written[label]:g}, the exercise's points")
                scores[(student, label)] = score
    return scores


def _number(x):
    return "" if x is None else f"{round(x, 2):g}"


def gradebook(records, table, roster, manual, policy):
    """The rows of grades.csv and of the Canvas file, with the chapters they cover."""
    by = {(r["student"], r["chapter"]): r for r in records}
    written_chapter = {label: c for c, chapter in table.items() for label in chapter["written"]}
    chapters = sorted({r["chapter"] for r in records} | {written_chapter[label] for _, label in manual})
    students = list(roster) if roster else sorted({r["student"] for r in records} | {s for s, _ in manual})
    rows = []
    for student in students:
        row = {"student_id": student, "name": roster[student].name if roster else student, "chapters": {}}
        for chapter in chapters:
            record = by.get((student, chapter))
            coding = {label: (record["points"][label] if record else None) for label in table[chapter]["coding"]}
            written = {label: manual.get((student, label)) for label in table[chapter]["written"]}
            scores = {**coding, **written}
            days, share = late(policy, student, chapter) if record else (0, 0.0)
            earned = sum(v for v in scores.values() if v is not None)
            row.update(scores)
            row["chapters"][chapter] = {"late_days": days, "penalty": round(earned * share, 2),
                                        "total": round(earned * (1 - share), 2),
                                        "present": record is not None or any(v is not None for v in written.values())}
        row["late_days"] = max((c["late_days"] for c in row["chapters"].values()), default=0)
        row["penalty"] = round(sum(c["penalty"] for c in row["chapters"].values()), 2)
        row["total"] = round(sum(c["total"] for c in row["chapters"].values()), 2)
        rows.append(row)
    return rows, chapters


def write_grades(path, rows, chapters, table, policy):
    labels = [label for c in chapters for label in [*table[c]["coding"], *table[c]["written"]]]
    columns = ["student_id", "name", *labels, *(["late_days", "penalty"] if policy else []), "total"]
    with open(path, "w", newline="", encoding="utf-8") as file:
        writer = csv.writer(file)
        writer.writerow(columns)
        for row in rows:
            writer.writerow([row[c] if c in ("student_id", "name", "late_days") else _number(row.get(c)) for c in columns])


def write_canvas(path, rows, chapters, table, roster):
    """Canvas's gradebook import: identity columns, a column per chapter, and the Points Possible row."""
    possible = {c: sum(e.get("points", 1) for e in table[c]["coding"].values()) + sum(table[c]["written"].values())
                for c in chapters}
    with open(path, "w", newline="", encoding="utf-8") as file:
        writer = csv.writer(file)
        writer.writerow([*CANVAS, *chapters])
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
        row, written = by_student[student], table[chapter]["written"]
        info = row["chapters"][chapter]
        name = roster[student].name if roster else student
        lines = [f"{chapter}: {name} ({student})", f"notebook: {record['path']}",
                 f"score: {_number(info['total'])} of {_number(sum(record['max'].values()) + sum(written.values()))}"]
        if info["late_days"]:
            lines.append(f"late by {info['late_days']} day{'s' * (info['late_days'] > 1)}: "
                         f"{_number(info['penalty'])} points off")
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


def write_all(records, table, roster, out, problems, policy, manual):
    """Every output of a grading run in ``out`` (``manual``: what :func:`read_manual` read); the main files."""
    out = pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    rows, chapters = gradebook(records, table, roster, manual, policy)
    write_grades(out / "grades.csv", rows, chapters, table, policy)
    write_canvas(out / "canvas.csv", rows, chapters, table, roster)
    write_feedback(records, rows, table, roster, out)
    (out / "problems.txt").unlink(missing_ok=True)
    if problems:
        (out / "problems.txt").write_text("\n".join(problems) + "\n", encoding="utf-8")
    report.write(out / "report.html", records, rows, chapters, table)
    return [out / "grades.csv", out / "canvas.csv", out / "report.html", out / "feedback"]
