"""The exercises are listed in one place, and the check functions made from that list read as if
written by hand.

``EXERCISE_CLASSES`` in ``ddg/checks/__init__.py`` names every exercise once, in the book's order;
``EXERCISES``, ``CHECKS`` and the ``check_*`` functions are made from it, and nothing else registers
an exercise (not defining a class, not importing a module). Each ``check_*`` has the name, module,
signature and docstring a hand-written one would have, and the example in its docstring runs.
"""

import doctest
import importlib
import importlib.util
import inspect
import json
import pathlib
import pkgutil
import re
import time

import pytest

from ddg import checks
from ddg.checks.judge import Exercise

ROOT = pathlib.Path(__file__).resolve().parents[2]
CHECKS_DIR = pathlib.Path(checks.__file__).parent
MODULES = sorted(module.name for module in pkgutil.iter_modules([str(CHECKS_DIR)]))
NAMES = list(checks.EXERCISES)


def defined_exercises():
    """Every exercise class defined in a module of ``ddg/checks``, listed or not."""
    found = set()
    for name in MODULES:
        module = importlib.import_module(f"ddg.checks.{name}")
        found |= {value for value in vars(module).values() if isinstance(value, type) and issubclass(value, Exercise)
                  and value is not Exercise and value.__module__ == module.__name__}
    return found


def test_every_exercise_defined_in_ddg_checks_is_listed():
    missing = defined_exercises() - set(checks.EXERCISE_CLASSES)
    assert not missing, (f"{sorted(c.__name__ for c in missing)}: defined in ddg/checks but not in EXERCISE_CLASSES "
                         "(ddg/checks/__init__.py): an exercise counts only once it is listed")


def test_the_list_names_each_exercise_once():
    listed = checks.EXERCISE_CLASSES
    twice = sorted({c.__name__ for c in listed if listed.count(c) > 1})
    assert not twice, f"EXERCISE_CLASSES names {twice} more than once"
    names = [c.name for c in listed]
    shared = sorted({n for n in names if names.count(n) > 1})
    assert not shared, f"two classes in EXERCISE_CLASSES ask for the same function: {shared}"
    assert all(isinstance(c, type) and issubclass(c, Exercise) for c in listed)
    assert list(checks.EXERCISES) == names and [type(e) for e in checks.EXERCISES.values()] == list(listed)
    assert checks.CHECKS == {f"check_{n}": n for n in names}


def test_the_list_is_in_the_order_of_the_book():
    """The order in which the chapters first call each check (the chapters' files sort in the book's order)."""
    order = []
    for notebook in sorted((ROOT / "book").glob("*.ipynb")):
        for cell in json.loads(notebook.read_text())["cells"]:
            if "check" in cell["metadata"].get("tags", []):
                order += [c for c in re.findall(r"\b(check_\w+)\(", "".join(cell["source"])) if c not in order]
    assert list(checks.CHECKS) == order, "EXERCISE_CLASSES should follow the book's order"


def test_importing_a_module_of_ddg_checks_registers_nothing():
    """A fresh copy of each module run again, and a new subclass of Exercise: EXERCISES stays as it was."""
    before = {name: id(exercise) for name, exercise in checks.EXERCISES.items()}
    for name in MODULES:
        spec = importlib.util.spec_from_file_location(f"ddg.checks.fresh_{name}", CHECKS_DIR / f"{name}.py")
        spec.loader.exec_module(importlib.util.module_from_spec(spec))
    type("Unlisted", (Exercise,), {"name": "unlisted"})
    assert {name: id(exercise) for name, exercise in checks.EXERCISES.items()} == before
    assert list(checks.CHECKS) == [f"check_{name}" for name in before] and not hasattr(checks, "check_unlisted")


def test_every_exercise_says_what_it_asks_for_once():
    """Its class's own docstring starts with the call (``name(args)``), and is where its check's begins."""
    for name, exercise in checks.EXERCISES.items():
        own = vars(type(exercise)).get("__doc__")
        assert own and re.match(rf"``{name}\([^)]*\)``: \S", own), f"{type(exercise).__name__}: no description"
        assert getattr(checks, f"check_{name}").__doc__.startswith(inspect.cleandoc(own) + "\n\n")


@pytest.mark.parametrize("name", NAMES)
def test_each_check_looks_written_by_hand(name):
    check = getattr(checks, f"check_{name}")
    assert inspect.isfunction(check)
    assert (check.__name__, check.__qualname__, check.__module__) == (f"check_{name}", f"check_{name}", "ddg.checks")
    assert str(inspect.signature(check)) == f"({name}, seed=None)"
    assert f"check_{name}" in checks.__all__ and checks.CHECKS[f"check_{name}"] == name
    exec(f"from ddg.checks import check_{name}", namespace := {})
    assert namespace[f"check_{name}"] is check
    assert inspect.getsource(check).startswith(f"def check_{name}({name}, seed=None):")
    doc = inspect.getdoc(check)
    assert doc.startswith(f"``{name}(") and "Examples\n--------\n" in doc and f">>> check_{name}({name})" in doc
    assert "Runs your" in doc and "seed" in doc


@pytest.mark.parametrize("name", NAMES)
def test_each_check_takes_its_answer_by_name_too(name):
    def starter(*args):
        raise NotImplementedError

    feedback = getattr(checks, f"check_{name}")(**{name: starter, "seed": 0})
    assert not feedback and feedback.todo, feedback
    with pytest.raises(TypeError, match=f"check_{name}\\(\\) missing 1 required positional argument: '{name}'"):
        getattr(checks, f"check_{name}")()


@pytest.mark.parametrize("name", NAMES)
def test_each_checks_example_runs(name):
    check = getattr(checks, f"check_{name}")
    tests = doctest.DocTestFinder().find(check, f"check_{name}", globs={})
    assert len(tests) == 1 and len(tests[0].examples) >= 3
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    start = time.monotonic()
    runner.run(tests[0])
    assert runner.summarize(verbose=False).failed == 0
    assert time.monotonic() - start < 5  # well under a second on an idle machine


def test_no_module_of_ddg_checks_uses_func():
    """A helper of a class body is a plain function, not ``@staticmethod`` called as ``_helper.__func__``."""
    found = [f"{path.name}:{n}" for path in sorted(CHECKS_DIR.glob("*.py"))
             for n, line in enumerate(path.read_text().splitlines(), 1) if "__func__" in line]
    assert not found, f"__func__ in ddg/checks: {found}"
