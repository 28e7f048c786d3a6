"""Who submitted what: the roster, and each submitted notebook mapped to one student and one chapter.

A submission belongs to

* the student named by its folder: ``submissions/alice/03_winding_number.ipynb`` is Alice's (any
  depth below the folder given on the command line; the first folder is the student); or, for a
  notebook directly in the folder given,
* the student named by its file name before the chapter: ``alice_03_winding_number.ipynb`` or
  ``alice-03_winding_number.ipynb``. A notebook given by itself (``submissions/*/*.ipynb``) belongs
  to the name in front of the chapter, or else to its folder.

With a roster, that name must be a student's ``id`` (or ``canvas_id``), or contain exactly one as
a part between underscores, as Canvas's downloads do (``liddellalice_1234_5678_03_winding_number.ipynb``
with ``canvas_id`` 1234). The chapter is the chapter of the book whose name the file name contains
(``03_winding_number (1).ipynb`` is chapter 3), never what the notebook's metadata claims. A notebook
that matches no student or no chapter, and two notebooks for one student and chapter, are reported
and not graded: nothing is guessed.
"""

import csv
import pathlib
from dataclasses import dataclass


@dataclass
class Student:
    id: str
    name: str
    email: str = ""
    section: str = ""
    login: str = ""
    canvas_id: str = ""


@dataclass
class Submission:
    student: str
    chapter: str
    path: pathlib.Path


COLUMNS = {"id": ("id", "student_id"), "name": ("name",), "email": ("email",), "section": ("section",),
           "login": ("sis_login_id", "login"), "canvas_id": ("canvas_id",)}


def read_roster(path):
    """``{id: Student}`` from a CSV with columns ``id``, ``name`` and optionally ``email``, ``section``,
    ``sis_login_id`` and ``canvas_id``. A missing column, an empty or repeated id is a ``ValueError``."""
    path = pathlib.Path(path)
    with open(path, newline="", encoding="utf-8-sig") as file:
        reader = csv.DictReader(file)
        header = [h.strip().lower() for h in reader.fieldnames or []]
        where = {field: next((h for h in names if h in header), None) for field, names in COLUMNS.items()}
        for field in ("id", "name"):
            if where[field] is None:
                raise ValueError(f"{path}: no `{field}` column (its columns: {', '.join(header) or 'none'})")
        students, lines = {}, {}
        for number, row in enumerate(reader, start=2):
            row = {k.strip().lower(): (v or "").strip() for k, v in row.items() if k}
            student = Student(**{field: row.get(column, "") for field, column in where.items() if column})
            if not student.id:
                raise ValueError(f"{path} line {number}: no id")
            if student.id in students:
                raise ValueError(f"{path} line {number}: id `{student.id}` appears twice (also on line {lines[student.id]})")
            students[student.id], lines[student.id] = student, number
    return students


def _notebooks(argument):
    """``(path, folder, given)`` for every notebook an argument names: the student's folder (``None`` for a
    notebook directly in the folder given), and whether the notebook was given by itself."""
    argument = pathlib.Path(argument)
    if argument.is_file():  # given by itself, say by a shell's glob: its name, else its folder, says whose
        return [(argument, argument.resolve().parent.name, True)]
    if not argument.is_dir():
        raise FileNotFoundError(f"{argument}: no such file or folder")
    found = []
    for path in sorted(argument.rglob("*.ipynb")):
        parts = path.relative_to(argument).parts
        if any(part.startswith(".") for part in parts):  # .ipynb_checkpoints and the like
            continue
        found.append((path, parts[0] if len(parts) > 1 else None, False))
    return found


def _chapter(name, chapters):
    """The chapter whose name occurs in the file name ``name`` (the longest such), and where it starts."""
    hits = [(len(c), name.find(c), c) for c in chapters if c in name]
    if not hits:
        return None, -1
    _, at, chapter = max(hits)
    return chapter, at


def _student(token, roster):
    """The roster id ``token`` names (itself, a canvas_id, or exactly one underscore-separated part of it)."""
    if roster is None:
        return token
    if token in roster:
        return token
    by_canvas = {s.canvas_id: s.id for s in roster.values() if s.canvas_id}
    if token in by_canvas:
        return by_canvas[token]
    parts = {p for p in token.split("_") if p}
    matches = {p for p in parts if p in roster} | {by_canvas[p] for p in parts if p in by_canvas}
    return matches.pop() if len(matches) == 1 else None


def collect(arguments, chapters, roster=None):
    """``(submissions, problems)``: each notebook mapped to a student and a chapter, and what could not be."""
    problems, found = [], {}
    for argument in arguments:
        for path, folder, given in _notebooks(argument):
            chapter, at = _chapter(path.stem, chapters)
            if chapter is None:
                problems.append(f"{path}: not graded: its name names no chapter of the book with exercises "
                                f"({', '.join(sorted(chapters))})")
                continue
            prefix = path.stem[:at].rstrip("_-. ")
            token = (prefix or folder) if given else folder if folder is not None else prefix
            if not token:
                problems.append(f"{path}: not graded: whose is it? Put it in a folder named after the student "
                                f"(alice/{path.name}) or name it alice_{chapter}.ipynb")
                continue
            student = _student(token, roster)
            if student is None:
                problems.append(f"{path}: not graded: no student in the roster matches `{token}`")
                continue
            found.setdefault((student, chapter), []).append(path)
    submissions = []
    for (student, chapter), paths in sorted(found.items()):
        if len(paths) > 1:
            problems.append(f"{student}, {chapter}: not graded: {len(paths)} submissions "
                            f"({', '.join(map(str, paths))}); keep one and grade again")
            continue
        submissions.append(Submission(student, chapter, paths[0]))
    return submissions, problems
