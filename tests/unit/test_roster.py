"""Intake as instructors have it, on generated classes: every notebook is credited to the student
whose folder or Canvas name holds it, or reported; never to another student. Rosters are read in
any dialect a spreadsheet saves, Excel's older Windows-1252 among them."""

import csv
import io

from hypothesis import given, settings
from hypothesis import strategies as st

from instructor import roster as rosters

CHAPTERS = {"03_winding_number": {}, "04_gradient_of_length": {}}
FIRST = ["Alice", "Bob", "Chloé", "Dmitri", "Eva", "Jörg", "Lena", "Ngozi"]
LAST = ["Becker", "Dubois", "Nowak", "Okafor", "Ruiz", "Smith", "Ødegård", "Liddell"]


def save(table, delimiter, end, bom, encoding):
    buffer = io.StringIO()
    csv.writer(buffer, delimiter=delimiter, lineterminator=end).writerows(table)
    return (bom + buffer.getvalue()).encode(encoding)


@settings(max_examples=60, deadline=None)
@given(people=st.lists(st.tuples(st.sampled_from(FIRST), st.sampled_from(LAST)), min_size=2, max_size=6, unique=True),
       layout=st.lists(st.sampled_from(["folder", "folder-by-name", "canvas", "flat", "impersonation"]), min_size=6,
                       max_size=6),
       dialect=st.sampled_from([(",", "\n", "", "utf-8"), (";", "\r\n", "\ufeff", "utf-8"), ("\t", "\n", "", "utf-8"),
                                (";", "\r\n", "", "cp1252")]),
       comment=st.text(alphabet="ab ;,\"", max_size=8))
def test_every_notebook_goes_to_its_owner_or_is_reported(tmp_path_factory, people, layout, dialect, comment):
    root = tmp_path_factory.mktemp("class")
    students = [(f"s{k:02d}", f"{first} {last}", str(1000 + k)) for k, (first, last) in enumerate(people)]
    (root / "roster.csv").write_bytes(save([["id", "name", "canvas_id", "Kommentar"]]
                                           + [[i, n, c, comment] for i, n, c in students], *dialect))
    roster = rosters.read_roster(root / "roster.csv")
    assert {s.id: (s.name, s.canvas_id) for s in roster.values()} == {i: (n, c) for i, n, c in students}
    subs, owner = root / "submissions", {}
    for k, (sid, name, canvas) in enumerate(students):
        how = layout[k % len(layout)]
        first, last = name.split(" ")
        if how == "folder":
            path = subs / sid / "03_winding_number.ipynb"
        elif how == "folder-by-name":
            path = subs / name / "03_winding_number.ipynb"
        elif how == "canvas":
            path = subs / "hw3" / f"{last.lower()}{first.lower()}_{canvas}_77{k}_03_winding_number-1.ipynb"
        elif how == "flat":
            path = subs / f"{sid}_03_winding_number.ipynb"
        else:  # in this student's folder, under the next student's id
            path = subs / sid / f"{students[(k + 1) % len(students)][0]}_03_winding_number.ipynb"
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text("{}")
        owner[path] = None if how == "impersonation" else sid
    found, problems = rosters.collect([subs], CHAPTERS, roster)
    credited = {s.path: s.student for s in found}
    for path, sid in owner.items():
        assert credited.get(path) in (sid, None), (path, credited.get(path), sid)  # never another student
        if sid is None:
            assert any(str(path) in p and "lies in the folder of" in p for p in problems), problems
        elif path not in credited:
            assert any(str(path) in p or sid in p for p in problems), (path, problems)  # reported, not lost
