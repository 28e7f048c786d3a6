"""Who submitted what: the roster, and each submitted notebook mapped to one student and one chapter.

A submission belongs to

* the student named by its folder: ``submissions/alice/03_winding_number.ipynb`` is Alice's (any
  depth below the folder given on the command line; the first folder is the student); or, for a
  notebook directly in the folder given,
* the student named by its file name before the chapter: ``alice_03_winding_number.ipynb`` or
  ``alice-03_winding_number.ipynb``, or by Canvas's download name,
  ``<lastfirst>[_late]_<canvas user id>_<submission id>_<file name>``. A notebook given by itself
  (``submissions/*/*.ipynb``) belongs to the name in front of the chapter, or else to its folder.

With a roster, that name must name exactly one student: the ``id``, ``canvas_id``, login or email
(or the part before its @), or the name, first-last or last-first, in any case, with or without
spaces and accents (``Bob Becker``, ``beckerbob``); or contain exactly one such name as a part
between underscores. A folder that is no student of the roster (``submissions/hw3/``, as
Canvas's zip of one assignment unpacks) is a folder of files whose names say whose they are. A file
is never credited to another student than the one whose folder holds it:
``alice/bob_03_winding_number.ipynb`` is reported, not graded. The chapter is the chapter of the book
whose name the file name contains (``03_winding_number (1).ipynb`` is chapter 3), never what the
notebook's metadata claims. A notebook that matches no student or no chapter, and two notebooks for
one student and chapter, are reported and not graded: nothing is guessed.

The CSV files an instructor hands the grader (roster, scores, submission times) are read in any
common dialect (:func:`read_table`): comma, semicolon or tab, with or without Excel's byte order
mark, CRLF line ends, extra columns; a Canvas gradebook export serves as a roster.
"""

import csv
import io
import pathlib
import re
import unicodedata
from dataclasses import dataclass

CANVAS_NAME = re.compile(r"^(?P<name>[^_]+)(?P<late>_late)?_(?P<user>\d+)_(?P<submission>\d+)_(?P<file>.+)$", re.I)
"""Canvas's name for a file in its "Download submissions" zip."""


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
CANVAS_COLUMNS = {"id": ("sis user id", "sis login id"), "name": ("student",), "email": ("email",),
                  "section": ("section",), "login": ("sis login id",), "canvas_id": ("id",)}
"""A Canvas gradebook export (Grades > Export) as a roster: its first columns name the students."""


def read_table(path):
    """``(columns, [(line number, {column: value})])`` of a CSV file in any common dialect.

    The text is UTF-8 (with or without a byte order mark) or else Windows-1252, as older Excel
    writes it; the delimiter (comma, semicolon, tab) is found by :class:`csv.Sniffer`. Column names
    are stripped; empty rows are skipped.
    """
    path = pathlib.Path(path)
    data = path.read_bytes()
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError:
        text = data.decode("cp1252", errors="replace")
    header = text.lstrip("\r\n").splitlines()[0] if text.strip() else ""
    try:  # the header line alone: a quoted comment with a semicolon further down cannot mislead it
        dialect = csv.Sniffer().sniff(header, delimiters=",;\t")
    except csv.Error:
        dialect = csv.excel
    dialect.quotechar, dialect.doublequote = '"', True
    reader = csv.reader(io.StringIO(text, newline=""), dialect)
    rows = [(number, row) for number, row in enumerate(reader, start=1) if any(cell.strip() for cell in row)]
    if not rows:
        return [], []
    (_, header), body = rows[0], rows[1:]
    columns = [h.strip() for h in header]
    return columns, [(number, {c: (row[i].strip() if i < len(row) else "") for i, c in enumerate(columns) if c})
                     for number, row in body]


def read_roster(path):
    """``{id: Student}`` from a CSV with columns ``id``, ``name`` and optionally ``email``, ``section``,
    ``sis_login_id`` and ``canvas_id``, or from a Canvas gradebook export. A missing column, an empty or
    repeated id is a ``ValueError``."""
    path = pathlib.Path(path)
    columns, rows = read_table(path)
    header = [h.lower() for h in columns]
    canvas = "sis user id" in header or "sis login id" in header
    names = CANVAS_COLUMNS if canvas else COLUMNS
    where = {field: next((columns[header.index(h)] for h in options if h in header), None)
             for field, options in names.items()}
    for field in ("id", "name"):
        if where[field] is None:
            raise ValueError(f"{path}: no `{field}` column (its columns: {', '.join(columns) or 'none'}); "
                             "the first line must name the columns: id,name[,email,section,sis_login_id,canvas_id]")
    students, lines = {}, {}
    for number, row in rows:
        if canvas and (row.get(where["name"], "").strip().lower() in ("points possible", "student, test", "test student")
                       or not row.get(where["canvas_id"] or "", "x").strip()):
            continue  # Canvas's rows that are no student
        student = Student(**{field: row.get(column, "") for field, column in where.items() if column})
        if canvas and not student.id:
            student.id = row.get(where["login"] or "", "") or student.canvas_id
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


def _plain(text):
    """Letters and digits only, lower case, accents dropped: how Canvas writes a name (``duboischloe``)."""
    return "".join(c for c in unicodedata.normalize("NFKD", text).lower() if c.isalnum())


def _aliases(roster):
    """Every name a folder or file may give a student by, that names one student only: the id, the
    ``canvas_id``, the login, the email and its part before the @, and the name, first-last or last-first."""
    found = {}
    for student in roster.values():
        words = student.name.replace(",", " ").split()
        names = {student.id, student.canvas_id, student.login, student.email, student.email.split("@")[0],
                 _plain(student.name), _plain("".join(words[1:] + words[:1])) if words else "",
                 _plain("".join(words[-1:] + words[:-1])) if words else ""}
        for alias in names - {""}:
            found.setdefault(alias, set()).add(student.id)
    return {alias: ids.pop() for alias, ids in found.items() if len(ids) == 1}


class Identities:
    """Whom a folder or a file name means. With a roster: the student it names (see :func:`_aliases`),
    itself or as exactly one of its parts between underscores, else ``None``; without one, the name itself."""

    def __init__(self, roster):
        self.roster = roster
        self.aliases = _aliases(roster) if roster is not None else {}

    def student(self, token):
        if not token or self.roster is None or token in self.roster:
            return token or None
        for form in (token, _plain(token)):
            if form in self.aliases:
                return self.aliases[form]
        parts = {p for p in token.split("_") if p}
        matches = {p if p in self.roster else self.aliases.get(p) for p in parts} - {None}
        return matches.pop() if len(matches) == 1 else None

    def named(self, path, prefix):
        """Whom the file's own name names: its Canvas name (by the Canvas user id, else by the name in it),
        else the name in front of the chapter."""
        match = CANVAS_NAME.match(path.name)
        if match and self.roster is None:
            return match.group("name")
        if match:
            return self.student(match.group("user")) or self.student(match.group("name"))
        return self.student(prefix)


def _whose(path, folder, given, prefix, who):
    """``(student, problem)``: whose notebook this is, or why that cannot be said (``(None, None)``: no name
    says whose)."""
    named = who.named(path, prefix)
    canvas = CANVAS_NAME.match(path.name)
    if given:  # a notebook given by itself: its name, else its folder
        student = named or who.student(folder)
        return (student, None) if student else (None, f"no student in the roster matches `{prefix or folder}`")
    if folder is None:
        if named or not (prefix or canvas):
            return named, None
        return None, f"no student in the roster matches `{prefix or path.name}`"
    owner = None if who.roster is None and canvas else who.student(folder)  # a folder of Canvas's files: no one's
    if owner is None:
        if named:
            return named, None
        return None, (f"no student in the roster matches the folder `{folder}`, nor the file's name"
                      if who.roster is not None else
                      f"whose is it? the folder `{folder}` holds Canvas's files, but this name is not Canvas's")
    if who.roster is not None and named not in (None, owner):
        return None, (f"the file names `{named}` but lies in the folder of `{owner}`; a file is credited only "
                      f"to the student whose folder holds it")
    return owner, None


def collect(arguments, chapters, roster=None):
    """``(submissions, problems)``: each notebook mapped to a student and a chapter, and what could not be."""
    problems, found, who = [], {}, Identities(roster)
    for argument in arguments:
        for path, folder, given in _notebooks(argument):
            chapter, at = _chapter(path.stem, chapters)
            if chapter is None:
                problems.append(f"{path}: not graded: its name names no chapter of the book with exercises "
                                f"({', '.join(sorted(chapters))})")
                continue
            prefix = path.stem[:at].rstrip("_-. ")
            match = CANVAS_NAME.match(path.name)
            if match and chapter in match.group("file"):
                prefix = ""  # the Canvas name is the whole prefix
            student, problem = _whose(path, folder, given, prefix, who)
            if problem:
                problems.append(f"{path}: not graded: {problem}")
                continue
            if student is None:
                problems.append(f"{path}: not graded: whose is it? Put it in a folder named after the student "
                                f"(alice/{path.name}) or name it alice_{chapter}.ipynb")
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
