"""The student edition: exercises kept, solutions dropped, starters that raise, checks open and kept."""

import json
import re
import pathlib

import nbformat
import numpy as np
import pytest
import yaml

from ddg import checks
from instructor import edition

ROOT = pathlib.Path(__file__).resolve().parents[2]
NOTEBOOKS = sorted((ROOT / "book").glob("*.ipynb"))


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_every_exercise_stays_and_every_solution_goes(path):
    nb = nbformat.read(path, as_version=4)
    student = edition.student_notebook(nb)
    text = "\n".join(cell.source for cell in student.cells)
    assert "solution-start" not in text and "solution-end" not in text
    assert text.count("{exercise}") == "\n".join(c.source for c in nb.cells).count("{exercise}")
    assert not [c for c in student.cells if "solution" in c.metadata.get("tags", [])]
    for cell in student.cells:
        if {"starter", "check"} & set(cell.metadata.get("tags", [])):
            assert "jupyter" not in cell.metadata, "a starter or check cell is folded for students"
        if cell.cell_type == "code":
            assert cell.outputs == [] and cell.execution_count is None
    assert student.metadata["ddg"] == nb.metadata["ddg"]  # the exercises and their points, for grading


def test_starters_raise_until_written_and_the_checks_say_so():
    nb = edition.student_notebook(nbformat.read(ROOT / "book" / "03_winding_number.ipynb", as_version=4))
    starters = [c.source for c in nb.cells if "starter" in c.metadata.get("tags", [])]
    assert len(starters) == 2
    env = {"np": np}
    exec(starters[0], env)  # noqa: S102
    with pytest.raises(NotImplementedError):
        env["turning_angles"](np.eye(3))
    feedback = checks.check_turning_angles(env["turning_angles"], seed=0)
    assert not feedback and "not written yet" in feedback.problem


def test_student_repository_and_launch_buttons(tmp_path):
    out = edition.write_edition(ROOT, tmp_path / "with", student_repo="https://github.com/someone/course-students")
    config = (out / "_config.yml").read_text()
    assert "url: https://github.com/someone/course-students" in config and "binderhub_url: https://mybinder.org" in config
    first = json.loads((out / "book" / "01_smooth_curves.ipynb").read_text())["cells"]
    setup = "".join(next(c for c in first if c["cell_type"] == "code")["source"])
    assert 'REPOSITORY = "https://github.com/someone/course-students"' in setup
    substitutions = yaml.safe_load(config)["parse"]["myst_substitutions"]
    homework = substitutions["homework"]
    assert "Binder or Colab" in homework and "run the check cell" in homework and "olded" not in homework
    assert "make" not in substitutions["run_locally"]  # a student repository has no Makefile
    readme = (out / "README.md").read_text()
    assert readme.startswith("# Student edition: ") and readme.count("edition") == 1, readme[:200]
    assert "https://someone.github.io/course-students/" in readme and "make " not in readme
    # every chapter with checks says, under its Exercises heading, how to get feedback
    for path in sorted((out / "book").glob("*.ipynb")):
        cells = json.loads(path.read_text())["cells"]
        if not any("check" in c["metadata"].get("tags", []) for c in cells):
            continue
        text = ["".join(c["source"]) for c in cells]
        heading = next(i for i, t in enumerate(text) if "## Exercises" in t)
        tip = next(i for i, t in enumerate(text) if "Feedback on your answers" in t)
        first_check = next(i for i, c in enumerate(cells) if "check" in c["metadata"].get("tags", []))
        assert heading <= tip < first_check and "rocket button" in text[tip], path.name
    out = edition.write_edition(ROOT, tmp_path / "without")
    config = (out / "_config.yml").read_text()
    assert "binderhub_url: ''" in config and "colab_url: ''" in config and "use_repository_button: false" in config
    assert "rocket" not in config.split("launch:")[1].split("\n")[0]  # the intro promises no launch button
    homework = yaml.safe_load(config)["parse"]["myst_substitutions"]["homework"]
    assert "rocket" not in homework and "download" in homework and "run the check cell" in homework
    # _config.yml is edited as YAML: every comment of the course's stays in the edition's
    comments = lambda text: [line.split("#", 1)[1] for line in text.splitlines() if " # " in line or line.startswith("#")]  # noqa: E731
    assert set(comments((ROOT / "_config.yml").read_text())) <= set(comments(config))
    for name in ("ddg/checks/__init__.py", "pyproject.toml", "requirements.txt", "README.md", "_vendor", "book/_assets"):
        assert (out / name).exists(), name


def test_changed_notebooks_are_kept_unless_forced(tmp_path):
    """The rules behind `make student` and `make clean` (the journey test_student_work runs them with make)."""
    out = edition.write_edition(ROOT, tmp_path / "student")
    edition.write_edition(ROOT, out)  # an unchanged edition is rewritten freely
    edition.main(["--check-unchanged", str(out / "book")])  # ... and may be deleted
    answer = out / "book" / "03_winding_number.ipynb"
    answer.write_text(answer.read_text().replace("NotImplementedError", "my_answer", 1))
    for doing in (lambda: edition.write_edition(ROOT, out), lambda: edition.main(["--check-unchanged", str(out / "book")])):
        with pytest.raises(SystemExit, match="03_winding_number.ipynb"):
            doing()
        assert "my_answer" in answer.read_text()
    edition.main(["--check-unchanged", str(out / "book"), "--force"])  # make clean FORCE=1 may delete it
    edition.write_edition(ROOT, out, force=True)  # make student FORCE=1 overwrites it
    assert "my_answer" not in answer.read_text() and not edition.changed_notebooks(out / "book")


STARTER_CASES = {
    "a class": ("class Walker:\n    '''Walks.'''\n    def step(self, x):\n        return x + 1\n",
                ["class Walker:", "def step(self, x):"]),
    "async def": ("async def fetch(x):\n    return x\n", ["async def fetch(x):"]),
    "decorators": ("import functools\n@functools.cache\ndef f(n):\n    return n\n", ["@functools.cache", "def f(n):"]),
    "a docstring holding triple quotes": ("def f():\n    '''Say \"\"\"hi\"\"\".'''\n    return 1\n", ["def f():"]),
    "a docstring ending in a quote": ('def f():\n    """Say "hi\\""""\n    return 1\n', ["def f():"]),
}


@pytest.mark.parametrize("case", list(STARTER_CASES))
def test_a_starter_keeps_every_definition_and_compiles(case):
    source, kept = STARTER_CASES[case]
    code = edition.starter(source)
    for line in kept:
        assert line in code, code
    namespace = {}
    exec(compile(code, "<starter>", "exec"), namespace)  # noqa: S102 (it compiles and runs)
    reference = {}
    exec(source, reference)  # noqa: S102
    for name, value in reference.items():
        if callable(value) and not name.startswith("__") and getattr(value, "__doc__", None):
            assert namespace[name].__doc__ == value.__doc__, name  # the docstring, exactly


@pytest.mark.parametrize("line", ["%matplotlib inline", "!pip install shapely", "  %timeit f()"])
def test_a_magic_in_a_solution_is_a_clear_error(line):
    with pytest.raises(ValueError, match=re.escape(f"must be plain Python, but it has the line '{line.strip()}'")):
        edition.starter(f"import numpy as np\n{line}\ndef f(x):\n    return x\n")


def test_no_answer_key_leaves_the_instructor(tmp_path):
    """The edition carries the checks' public input with its expected values, made from the answer key,
    but no code of the key: no answer-key cell, no reference in ddg/checks, not the lab's circle
    curvature; its notebooks install ddg from no repository but the student one."""
    from instructor import references

    out = edition.write_edition(ROOT, tmp_path / "edition")
    cells = [c for path in sorted((out / "book").glob("*.ipynb")) for c in json.loads(path.read_text())["cells"]]
    assert not [c for c in cells if "answer-key" in c["metadata"].get("tags", [])]
    code = "\n".join("".join(c["source"]) for c in cells if c["cell_type"] == "code")
    assert "def circle_k" not in code and "def theorem_area" not in code
    assert 'REPOSITORY = ""' in code and "github.com/ddg-course" not in code
    assert not (out / "book" / "_assets" / "ddg-lab-circle.js").exists()
    assert "ddg-lab-circle" not in (out / "_config.yml").read_text()
    source = "\n".join(p.read_text() for p in (out / "ddg" / "checks").glob("*.py"))
    assert "def expected" in source and source.count("def expected") == 1  # the one that reads Call.want
    assert not (out / "instructor").exists()
    assert json.loads((out / "ddg" / "checks" / "public.json").read_text()) == references.public_sets()
    book = [c for path in NOTEBOOKS for c in json.loads(path.read_text())["cells"]]
    tags = [t for c in book for t in c["metadata"].get("tags", [])]
    assert tags.count("answer-key") == 7 and tags.count("answer-stub") == 1  # what the edition drops or stubs


def test_the_public_input_is_current():
    """ddg/checks/public.json is what the answer key makes (python -m instructor.references writes it)."""
    from instructor import references

    shipped = json.loads(references.PUBLIC.read_text())
    assert shipped == references.public_sets(), "run: python -m instructor.references"
    assert {name: len(sets) for name, sets in shipped.items()} == {name: references.PUBLIC_SETS for name in checks.EXERCISES}
