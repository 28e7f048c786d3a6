"""ddg reads like the libraries students meet next: examples that run, type hints that a type
checker accepts, errors by kind, no raw numpy warning, no private attribute read across modules.

The public API is every name without a leading underscore in the geometry's modules (``CORE``):
functions, classes, their methods and properties.
"""

import ast
import doctest
import functools
import importlib
import inspect
import pathlib
import pkgutil
import subprocess
import sys

import numpy as np
import pytest

import ddg

ROOT = pathlib.Path(ddg.__file__).parent
CORE = ["ddg.curve", "ddg.polygons", "ddg.inflation", "ddg.smooth", "ddg.flow", "ddg.errors"]
OPTIONS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE


def public(module):
    """``(name, object)`` of every public function, class, method and property defined in ``module``."""
    for name, obj in vars(module).items():
        if name.startswith("_") or getattr(obj, "__module__", None) != module.__name__:
            continue
        if inspect.isfunction(obj):
            yield name, obj
        elif inspect.isclass(obj):
            yield name, obj
            for attr, member in vars(obj).items():
                if attr.startswith("_"):
                    continue
                function = member.func if hasattr(member, "func") else member  # cached_property
                function = function.fget if isinstance(function, property) else function
                if inspect.isfunction(function):
                    yield f"{name}.{attr}", function


def cached_property_examples(module, globs):
    """The examples of ``functools.cached_property`` docstrings, which doctest's finder skips."""
    parser, tests = doctest.DocTestParser(), []
    for cls in (obj for obj in vars(module).values() if inspect.isclass(obj) and obj.__module__ == module.__name__):
        for attr, member in vars(cls).items():
            if isinstance(member, functools.cached_property) and member.__doc__:
                name = f"{module.__name__}.{cls.__name__}.{attr}"
                tests.append(parser.get_doctest(member.__doc__, dict(globs), name, module.__file__, 0))
    return [test for test in tests if test.examples]


def every_module():
    return [info.name for info in pkgutil.walk_packages([str(ROOT)], "ddg.")]


@pytest.mark.parametrize("module", CORE)
def test_every_public_function_and_property_has_an_example(module):
    module = importlib.import_module(module)
    missing = [name for name, obj in public(module) if ">>>" not in (obj.__doc__ or "")
               and not (inspect.isclass(obj) and issubclass(obj, Exception))]
    assert not missing, f"{module.__name__}: no runnable example in the docstring of {missing}"


@pytest.mark.parametrize("module", every_module())
def test_the_examples_run(module):
    """Every docstring example of every module of ddg, as the reader would type it after
    ``import numpy as np`` and ``from ddg.<module> import *`` (what ddg/__init__.py says)."""
    imported = importlib.import_module(module)
    names = getattr(imported, "__all__", [name for name in vars(imported) if not name.startswith("_")])
    globs = {"np": np, **{name: getattr(imported, name) for name in names}}
    found = doctest.DocTestFinder().find(imported, globs=globs) + cached_property_examples(imported, globs)
    runner = doctest.DocTestRunner(optionflags=OPTIONS)
    with np.errstate(all="raise"):
        for test in found:
            runner.run(test)
    results = runner.summarize(verbose=False)
    assert results.failed == 0, f"{results.failed} of {results.attempted} examples of {module} failed"


def test_the_example_test_finds_examples_and_fails_a_wrong_one():
    """The examples test can fail: a wrong expected value is counted as a failure."""
    test = doctest.DocTestParser().get_doctest(">>> 1 + 1\n3\n", {}, "wrong", "wrong.py", 0)
    runner = doctest.DocTestRunner(optionflags=OPTIONS)
    runner.run(test, out=lambda text: None)
    assert runner.summarize(verbose=False).failed == 1
    modules = [importlib.import_module(m) for m in CORE]
    assert sum(len(doctest.DocTestFinder().find(m)) for m in modules) > 60
    assert len(cached_property_examples(importlib.import_module("ddg.curve"), {})) >= 12  # edges, lengths, ...


@pytest.mark.parametrize("module", CORE)
def test_the_public_api_is_typed(module):
    module = importlib.import_module(module)
    untyped = []
    for name, obj in public(module):
        if inspect.isclass(obj):
            continue
        signature = inspect.signature(obj)
        loose = [p for p in signature.parameters.values() if p.name not in ("self", "cls")
                 and p.annotation is inspect.Parameter.empty]
        if loose or signature.return_annotation is inspect.Signature.empty:
            untyped.append(name)
    assert not untyped, f"{module.__name__}: no complete type hints on {untyped}"


def test_mypy_accepts_the_type_hints():
    """mypy, configured in pyproject.toml, on the geometry's modules."""
    done = subprocess.run([sys.executable, "-m", "mypy", "--no-incremental"], cwd=ROOT.parent,
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr


@pytest.mark.parametrize("module", ["ddg/_numerics.py", "ddg/_arguments.py", *(m.replace(".", "/") + ".py" for m in CORE)])
def test_refusals_are_errors_by_kind(module):
    """No bare ValueError: each refusal is one of ddg.errors, so a caller can catch it by kind."""
    tree = ast.parse((ROOT.parent / module).read_text())
    bare = [node.lineno for node in ast.walk(tree) if isinstance(node, ast.Raise) and node.exc is not None
            and isinstance(node.exc, ast.Call) and getattr(node.exc.func, "id", "") == "ValueError"]
    assert not bare, f"{module}: raise ValueError at lines {bare}"
    for error in (ddg.InputError, ddg.DegenerateCurveError, ddg.OpenCurveError, ddg.OutOfRangeError):
        assert issubclass(error, ddg.CurveError) and issubclass(error, ValueError)


def test_no_private_attribute_is_read_across_modules():
    """``x._name`` only on ``self`` or ``cls``: what another module needs has a public name."""
    allowed = {"os._exit", "box._repr_mimebundle_"}  # the standard library's; IPython's display protocol
    found = []
    for path in sorted(ROOT.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if (isinstance(node, ast.Attribute) and node.attr.startswith("_") and not node.attr.startswith("__")
                    and not (isinstance(node.value, ast.Name) and node.value.id in ("self", "cls"))
                    and ast.unparse(node) not in allowed):
                found.append(f"{path.relative_to(ROOT.parent)}:{node.lineno} {ast.unparse(node)}")
    assert not found, found
