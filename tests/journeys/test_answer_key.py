"""Homework a student cannot game: what a determined student tries, through the grader and the checks.

* Harvesting inputs: an answer that walks up its frames and through every object of its process
  finds its own input and no other; inputs depend on the secret, the student and the notebook's
  code, so a lookup table made from a leaked run passes nothing, for that student or another, while
  the same notebook graded again gets the same inputs and grade.
* Shortcuts: ``ddg``'s own helper of the asked-for quantity, ``ddg/curve.py`` run again, shapely's
  buffer by every door (its compiled function found by ``gc``, a second copy of its module), the
  same region as a union of pieces, the grader's answer key: no points.
* The leak guard of ``make student``: answers planted in a hidden cell, in ``ddg/checks`` and in a
  script of the site are named; the edition ``make test`` builds passes it (``make student`` runs it).
"""

import hashlib
import json
import shutil
import subprocess
import sys

import nbformat
import numpy as np
from grading_helpers import CHAPTER, by_student, grade, needs_root, references, submission
from journey_helpers import ROOT

from ddg.checks.judge import Call
from instructor import grade as grader
from instructor import references as key

NOTEBOOK = f"{CHAPTER}.ipynb"
MINKOWSKI = "05_inflation"

HARVEST = '''
import gc
import hashlib
import sys

import numpy as np


def turning_angles(vertices):
    """Every polygon this process can reach (frames above it, every object it holds), as short digests."""
    seen = set()

    def note(value):
        try:
            a = np.asarray(value, dtype=float)
        except Exception:
            return
        if a.ndim == 2 and a.shape[1] == 2 and 3 <= len(a) <= 40:
            seen.add(hashlib.sha1(a.round(9).tobytes()).hexdigest()[:5])

    def walk(value, depth=0):
        if depth > 6:
            return
        if isinstance(value, dict):
            for v in list(value.values()):
                walk(v, depth + 1)
        elif isinstance(value, (list, tuple)):
            note(value)
            for v in list(value)[:50]:
                walk(v, depth + 1)
        elif isinstance(value, np.ndarray):
            note(value)
        else:
            try:  # a curve, or an object that holds one (some objects raise on any attribute)
                if hasattr(value, "vertices"):
                    note(value.vertices)
                elif hasattr(value, "__dict__") and depth < 3:
                    walk(vars(value), depth + 1)
            except Exception:
                pass

    frame = sys._getframe()
    while frame is not None:
        walk(dict(frame.f_locals))
        frame = frame.f_back
    for thing in gc.get_objects():
        if isinstance(thing, (dict, list, tuple)):
            walk(thing, 4)
    raise RuntimeError("HARVESTED " + " ".join(sorted(seen)[:45]))
'''


def digest(polygon):
    return hashlib.sha1(np.asarray(polygon, dtype=float).round(9).tobytes()).hexdigest()[:5]


def lookup_table(inputs, answers):
    """An answer that knows the right result for each of ``inputs`` (polygons) and returns zeros elsewhere."""
    table = {json.dumps(polygon): answer for polygon, answer in zip(inputs, answers, strict=True)}
    return (f"import json\nimport numpy as np\n\nTABLE = {json.dumps(table)}\n\n\n"
            "def turning_angles(vertices):\n"
            "    found = TABLE.get(json.dumps(np.asarray(vertices).tolist()))\n"
            "    return np.array(found if found is not None else np.zeros(len(vertices)))\n")


def hidden(student, path, label="ex-turning-angles"):
    """The hidden input the grader draws for ``student``'s notebook at ``path``, and its right results."""
    table = grader.exercises(ROOT / "book")[CHAPTER]["coding"]
    parsed, _ = grader.parse_notebook(path.read_bytes())
    inputs = grader.draw_inputs(table, SECRET, student, grader.code_key(parsed[1]))[label]
    calls = key.complete("turning_angles", [Call(tuple(c["args"]), c["what"]) for c in inputs])
    return [c["args"][0]["array"] for c in inputs], [call.want.tolist() for call in calls]


SECRET = "class-secret-31"


def feedback(out, student, chapter=CHAPTER):
    return (out / "feedback" / student / f"{chapter}.txt").read_text()


def test_a_harvest_finds_its_own_input_and_a_lookup_table_passes_nothing(tmp_path):
    needs_root()
    subs, out = tmp_path / "submissions", tmp_path / "grading"
    first = submission(subs / "mallory" / NOTEBOOK, {"turning_angles": HARVEST})
    grade(subs, "--seed", SECRET, "--out", out, check=False)
    said = feedback(out, "mallory")
    polygons, right = hidden("mallory", first)
    found = set(said.split("HARVESTED ", 1)[1].split("\n")[0].split()) & {digest(p) for p in polygons}
    assert found == {digest(polygons[0])}, said  # its own input only; on the last release all 14 were in reach
    assert said.count("on a ") <= 1, said  # the verdict shows the first wrong input only

    # The whole leak, as if every input had been harvested: right answers for all of them, as a lookup table.
    assert len({json.dumps(p) for p in polygons}) == len(polygons) > 10
    table = lookup_table(polygons, right)
    shutil.rmtree(subs)
    second = submission(subs / "mallory" / NOTEBOOK, {"turning_angles": table})
    submission(subs / "eve" / NOTEBOOK, {"turning_angles": table})  # the same table, another student
    submission(subs / "honest" / NOTEBOOK)
    grade(subs, "--seed", SECRET, "--out", out, check=False)
    grades = by_student(out / "grades.csv")
    assert grades["mallory"]["ex-turning-angles"] == "0" and grades["eve"]["ex-turning-angles"] == "0", grades
    assert float(grades["honest"]["ex-turning-angles"]) > 0
    assert hidden("mallory", second)[0] != polygons  # a new version of the notebook: new input
    assert hidden("eve", second)[0] != hidden("mallory", second)[0]  # another student: other input

    # The same notebook graded again: the same input, the same grade.
    assert hidden("honest", subs / "honest" / NOTEBOOK) == hidden("honest", subs / "honest" / NOTEBOOK)
    before = (out / "grades.csv").read_text()
    grade(subs, "--seed", SECRET, "--out", out, "--only", "ex-turning-angles", check=False)
    assert (out / "grades.csv").read_text() == before


TURNS = {
    "ddg's own helper": "import numpy as np\nimport ddg._numerics\n\n\ndef turning_angles(vertices):\n"
                        "    v = np.asarray(vertices, dtype=float)\n    e = np.roll(v, -1, axis=0) - v\n"
                        "    return 2 * np.arctan(ddg._numerics.tan_half_turn(np.roll(e, 1, axis=0), e))\n",
    "curve.py run again": "import ddg\n\n\ndef turning_angles(vertices):\n"
                          "    ns = {'__name__': 'ddg.curve', '__package__': 'ddg'}\n"
                          "    exec(open(ddg.curve.__file__).read(), ns)\n"
                          "    return ns['DiscreteCurve'](vertices).turning_angles\n",
    "the answer key": "from instructor import references\nfrom ddg.checks.judge import Call\n\n\n"
                      "def turning_angles(vertices):\n"
                      "    return references.turning_angles(Call(({'array': vertices.tolist()},), ''))\n",
}
AREAS = {
    "shapely.constructive": "import shapely\n\n\ndef minkowski_area(curve, eps):\n    return shapely.constructive.buffer("
                            "shapely.Polygon(curve.vertices), eps, quad_segs=1024).area\n",
    "shapely.lib": "import shapely\nimport shapely.lib\n\n\ndef minkowski_area(curve, eps):\n    return shapely.area("
                   "shapely.lib.buffer(shapely.Polygon(curve.vertices), eps, 1024, 0, 0, 5.0, False))\n",
    "a second shapely.lib": "import importlib.util\nimport shapely\n\n\ndef minkowski_area(curve, eps):\n"
                            "    spec = importlib.util.find_spec('shapely.lib')\n"
                            "    lib = importlib.util.module_from_spec(spec)\n    spec.loader.exec_module(lib)\n"
                            "    return shapely.area(lib.buffer(shapely.Polygon(curve.vertices), eps, 1024, 0, 0, 5.0, "
                            "False))\n",
    "a union of the pieces": "import numpy as np\nimport shapely\n\n\ndef minkowski_area(curve, eps):\n"
                             "    v, t = curve.vertices, np.linspace(0, 2 * np.pi, 4096, endpoint=False)\n"
                             "    disks = [shapely.Polygon(p + eps * np.c_[np.cos(t), np.sin(t)]) for p in v]\n"
                             "    strips = [shapely.Polygon(np.r_[[a, b], [b, a] + eps * np.array([[b - a] * 2])[0]"
                             " @ [[0, -1], [1, 0]] / np.linalg.norm(b - a)])\n"
                             "              for a, b in zip(v, np.roll(v, -1, axis=0))]\n"
                             "    return shapely.union_all([shapely.Polygon(v), *disks, *strips]).area\n",
    "Polygon.buffer": "import shapely\n\n\ndef minkowski_area(curve, eps):\n"
                      "    return shapely.Polygon(curve.vertices).buffer(eps, quad_segs=1024).area\n",
    "the original, found by gc": "import gc\nimport shapely\n\n\ndef minkowski_area(curve, eps):\n"
                                 "    found = [d['buffer'] for d in gc.get_objects() if isinstance(d, dict)\n"
                                 "             and type(d.get('buffer')).__name__ == 'ufunc']\n"
                                 "    return shapely.area(found[0](shapely.Polygon(curve.vertices), eps, 1024, 0, 0, "
                                 "5.0, False))\n",
    "the import guard's own loader": "import _imp\nimport importlib.util\nimport shapely\n\n\n"
                                     "def minkowski_area(curve, eps):\n"
                                     "    load = [c.cell_contents for c in _imp.create_dynamic.__closure__\n"
                                     "            if callable(c.cell_contents)][0]\n"
                                     "    lib = load(importlib.util.find_spec('shapely.lib'))\n"
                                     "    return shapely.area(lib.buffer(shapely.Polygon(curve.vertices), eps, 1024, 0, 0, "
                                     "5.0, False))\n",
}


GRADIENT = ("04_gradient_of_length", "import ddg\n\n\ndef length_gradient(vertices):\n"
            "    ns = {'__name__': 'ddg.curve', '__package__': 'ddg'}\n"
            "    exec(open(ddg.curve.__file__).read(), ns)  # a DiscreteCurve with nothing switched off\n"
            "    return ns['DiscreteCurve'](vertices).length_gradient()\n")


def test_every_shortcut_gets_no_points_from_the_grader_or_the_check(tmp_path):
    needs_root()
    subs, out = tmp_path / "submissions", tmp_path / "grading"
    chapter, source = GRADIENT  # in the grader, ddg's source is not there to run again
    submission(subs / "gradient" / f"{chapter}.ipynb", {"length_gradient": source}, chapter=chapter)
    for i, source in enumerate(TURNS.values()):
        submission(subs / f"turns{i}" / NOTEBOOK, {"turning_angles": source})
    for i, source in enumerate(AREAS.values()):
        submission(subs / f"areas{i}" / f"{MINKOWSKI}.ipynb", {"minkowski_area": source}, chapter=MINKOWSKI)
    submission(subs / "honest" / NOTEBOOK)
    grade(subs, "--seed", SECRET, "--out", out, check=False)
    grades = by_student(out / "grades.csv")
    for i, what in enumerate(TURNS):
        assert grades[f"turns{i}"]["ex-turning-angles"] == "0", (what, feedback(out, f"turns{i}"))
    for i, what in enumerate(AREAS):
        assert grades[f"areas{i}"]["ex-minkowski-nonconvex"] == "0", (what, feedback(out, f"areas{i}", MINKOWSKI))
        said = feedback(out, f"areas{i}", MINKOWSKI)  # refused by name, or (gc) the original is nowhere
        assert "shapely" in said or "IndexError: list index out of range" in said, (what, said)
    assert float(grades["honest"]["ex-turning-angles"]) > 0
    assert grades["gradient"]["ex-length-gradient"] == "0", feedback(out, "gradient", GRADIENT[0])
    assert "No such file" in feedback(out, "gradient", GRADIENT[0])

    # and the students' own checks, in a kernel of their own (here: a fresh Python), say the same
    from ddg import checks  # noqa: F401 - the sources are run below, in a child Python

    for what, source in [*TURNS.items(), *AREAS.items()]:
        if what == "the answer key":  # not in a student's hands at all (not in the student edition)
            continue
        name = "turning_angles" if "def turning_angles" in source else "minkowski_area"
        program = f"{source}\nfrom ddg import checks\nf = checks.run({name!r}, {name})\nprint('PASSED' if f else 'FAILED', f)"
        done = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True, timeout=120,
                              cwd=tmp_path)
        assert done.stdout.startswith("FAILED"), (what, done.stdout, done.stderr[-500:])


def planted_edition(tmp_path):
    """A copy of the student edition with an answer in a hidden cell, in ddg/checks and in a script."""
    student = ROOT / "_build" / "student"
    edition = tmp_path / "edition"
    shutil.copytree(student / "ddg", edition / "ddg", ignore=shutil.ignore_patterns("__pycache__"))
    (edition / "html" / "_static").mkdir(parents=True)
    for name in ("ddg-lab.js", "ddg-lab-page.js"):
        shutil.copy(student / "html" / "_static" / name, edition / "html" / "_static" / name)
    shutil.copy(ROOT / "book" / "_assets" / "ddg-lab-circle.js", edition / "html" / "_static")  # the book's, planted
    nb = nbformat.read(student / "book" / "06_table.ipynb", as_version=4)
    source = next("".join(c["source"]) for c in json.loads((ROOT / "book" / "06_table.ipynb").read_text())["cells"]
                  if "def circle_k" in "".join(c["source"]))
    hidden = nbformat.v4.new_code_cell(source[source.index("def circle_k"):source.index("four = ")])
    hidden.metadata = {"tags": ["remove-cell"], "jupyter": {"source_hidden": True}}
    nb.cells = [c for c in nb.cells if c.cell_type == "markdown"][:1] + [
        nbformat.v4.new_code_cell("import numpy as np\nimport ddg"), hidden]
    (edition / "book").mkdir()
    nbformat.write(nb, edition / "book" / "06_table.ipynb")
    geometry = edition / "ddg" / "checks" / "geometry.py"
    geometry.write_text(geometry.read_text() + '''

def rebuilt(psi, lengths, start, heading):
    """A helper that happens to answer ex-rebuild."""
    steps = lengths * np.exp(1j * heading) * np.exp(-1j * np.cumsum(np.r_[0.0, psi[1:]]))
    z = complex(*start) + np.r_[0, np.cumsum(steps)]
    return np.stack([z.real, z.imag], axis=1)
''')
    return edition


def test_the_leak_guard_names_every_planted_answer(tmp_path):
    if not (ROOT / "_build" / "student" / "html" / "_static" / "ddg-lab.js").exists():
        raise AssertionError("no student site: `make test` builds it (make student) before the journeys")
    assert not (ROOT / "_build" / "student" / "html" / "_static" / "ddg-lab-circle.js").exists()
    edition = planted_edition(tmp_path)
    done = subprocess.run([sys.executable, "-m", "instructor.guard", str(edition)], capture_output=True, text=True,
                          timeout=600, cwd=ROOT)
    assert done.returncode == 1, done.stdout + done.stderr
    for named in ("06_table.ipynb: `circle_k` passes the hidden check of circle_curvature",
                  "ddg.checks.geometry.rebuilt passes the hidden check of rebuild",
                  "ddgLab.circle_curvature (in ddg-lab-circle.js, ddg-lab-page.js, ddg-lab.js) passes the hidden "
                  "check of circle_curvature"):
        assert named in done.stderr, done.stderr
    assert references()  # the chapter the grading journeys use still has its solutions here
