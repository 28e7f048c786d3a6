"""Immediate feedback on homework: ``check_*(answer)`` tests an answer and says what is wrong.

>>> from ddg.checks import check_turning_angles
>>> check_turning_angles(turning_angles)          # doctest: +SKIP
✓ turning_angles passed on 14 public inputs

or, for example, ``✗ turning_angles: your angles look like degrees: on a clockwise square, at
vertex 0 you give 90 where 1.571 (radians) was expected``. ``bool(feedback)`` is ``True`` when the
answer is right. Pass ``seed=`` to pick one of the public sets of input (a random one otherwise).

How a check works:

1. It takes a set of *public* input (polygons, curves, parameters) from ``public.json``, which
   ships with ``ddg`` and holds what a right answer returns on each: the checks hold no code that
   computes an answer (the instructor's answer key made that file).
2. It runs your answer on that input in a separate process, one input at a time, for at most
   :data:`TIME_LIMIT` seconds in all, with the ``ddg`` quantity the exercise asks for switched
   off where it is implemented ("write this one yourself"), without the checks' own code, and with
   everything it starts stopped afterwards (``ddg/checks/runner.py`` says how).
3. Back here it compares with the expected values: if yours differ, it looks for the cause among
   the mistakes students make (degrees for radians, the other sign convention, the closed curve's
   wrap-around, an index shifted by one, a missing weight ...) and names it, with the value
   expected next to yours; otherwise it says where the two differ.

The grader (``python -m instructor.grade``) judges the same way, with the same diagnosis, on
*hidden* input: drawn for each student and each version of a notebook from the instructor's secret,
with the answer key, in a sandbox. An answer that passes here by knowing the public input passes
nothing there. What a check is not: a sandbox against deliberate cheating on your own machine; an
answer that copies ``ddg``'s public source can still pass (that is the documented limit). Where
``fork`` is missing (Windows) the answer runs in a thread of this process, and only the time limit
applies.
"""

import functools
import inspect
import json
import keyword
import linecache
import numbers
import pathlib
import re

import numpy as np

from ..errors import InputError
from . import comparing, curvatures, curves, geometry
from .judge import Call, CheckError, Feedback, judge
from .runner import TIME_LIMIT, WriteItYourself, evaluate

EXERCISE_CLASSES = (
    curves.OsculatingCenter,  # 01_smooth_curves
    curves.Staircase,  # 02_discrete_curves
    curves.VertexNormals,
    curvatures.TurningAngles,  # 03_winding_number
    curvatures.Rebuild,
    curvatures.LengthGradient,  # 04_gradient_of_length
    curvatures.MinkowskiArea,  # 05_inflation
    comparing.CircleCurvature,  # 06_table
    comparing.ZigzagExponent,  # 07_convergence
)
"""Every coding exercise of the book, in the order its chapters ask for them. This list is the only
place an exercise is named: defining its class is not enough (CONTRIBUTING.md, 'Adding an exercise
with a check'). :data:`EXERCISES`, :data:`CHECKS` and the ``check_*`` functions are made from it."""

EXERCISES = {exercise.name: exercise() for exercise in EXERCISE_CLASSES}
"""Every coding exercise, by the name of the function it asks for, in the book's order."""

CHECKS = {f"check_{name}": name for name in EXERCISES}
"""The check functions of the book, by name, with the exercise each one checks."""


PUBLIC = pathlib.Path(__file__).with_name("public.json")
"""The public input of every check, with what a right answer returns on it (written by
``python -m instructor.references``, which ``make student`` runs)."""


def draw(name, seed=None):
    """Fresh input of one check (a list of ``judge.Call``, without expected values), from ``seed``."""
    return EXERCISES[name].draw(np.random.default_rng(seed))


@functools.cache
def _public():
    try:
        return json.loads(PUBLIC.read_text())
    except (OSError, ValueError) as error:
        raise CheckError(f"the public input of the checks cannot be read from {PUBLIC} ({error}); the course's "
                         "ddg is incomplete: install it again") from error


def public(name, seed=None):
    """One set of the public input of the check of ``name``: ``judge.Call`` objects with their expected
    values; ``seed`` picks the set (a random one when ``None``)."""
    sets = _public().get(name)
    if not sets:
        raise CheckError(f"the public input of the checks has nothing for {name}: run python -m instructor.references")
    chosen = sets[int(np.random.default_rng(seed).integers(len(sets))) if seed is None else seed % len(sets)]
    return [Call(tuple(c["args"]), c["what"], np.asarray(c["want"], dtype=float),
                 {k: np.asarray(v, dtype=float) for k, v in c.get("given", {}).items()}) for c in chosen]


def run(name, answer, seed=None, isolate=True, calls=None, kind="public"):
    """Check ``answer`` for the exercise ``name`` (a key of :data:`EXERCISES`): its :class:`Feedback`.

    ``calls`` (with their expected values) replaces the public input: the grader's hidden input.
    ``isolate=False`` runs the answer in this process (no time limit, nothing switched off): for
    tests, where the answers are the test's own.
    """
    if seed is not None and (isinstance(seed, bool) or not isinstance(seed, numbers.Integral)):
        raise InputError(f"seed must be a whole number (it picks one of the sets of public input) or None, got {seed!r}")
    exercise = EXERCISES[name]
    label = getattr(answer, "__name__", name) if callable(answer) else name
    label = label if isinstance(label, str) else name
    try:
        calls = public(name, seed) if calls is None else calls
        specs = [call.args for call in calls]
        if isolate:
            raw = evaluate(answer, specs, exercise.forbidden, exercise.measures, build=geometry.build)
        else:
            from .runner import answers
            raw = answers(answer, specs, geometry.build)
        feedback = judge(exercise, calls, raw, label)
    except CheckError as error:
        return Feedback(name, problem=f"{error}: please tell your instructor", inputs=len(calls or ()), kind=kind)
    feedback.kind = kind
    return feedback


def answer_results(name, answer, specs, limit=TIME_LIMIT):
    """For the grader's sandbox: the raw results of ``answer`` on the given input specs."""
    exercise = EXERCISES[name]
    return evaluate(answer, specs, exercise.forbidden, exercise.measures, limit, geometry.build)


# ------------------------------------------------------------------ the check functions, one per exercise


def _docstring(exercise):
    """The docstring of the check of ``exercise``: what the exercise asks for (its class's docstring,
    which starts with the call, ``name(args)``), what the check does, and an example that runs."""
    name = exercise.name
    description = inspect.cleandoc(type(exercise).__doc__ or f"``{name}``")
    call = re.match(rf"``{name}\((.*?)\)``", description)
    return f"""{description}

Runs your ``{name}`` on one set of public input (``seed`` picks it; a random one when ``None``)
and says whether it is right: the :class:`Feedback` shows ✓, or ✗ with what is wrong and where.
``bool(feedback)`` is ``True`` when the answer is right.

Examples
--------
An answer not written yet is still to do:

>>> from ddg.checks import check_{name}
>>> def {name}({call.group(1) if call else "*args"}):
...     raise NotImplementedError
>>> check_{name}({name})
☐ {name}: to do, not written yet: replace `raise NotImplementedError` with your code, then run this cell again

Once it is written, the same call says ``✓ {name} passed on N public inputs``, or ``✗ {name}:`` and
what is wrong.
"""


def _check_function(exercise):
    """``check_<name>(<name>, seed=None)`` for ``exercise``, the function one would write by hand here.

    It is compiled from its two lines of source (as :mod:`dataclasses` makes ``__init__``), so that
    its first parameter is really named after the answer: Python itself binds
    ``check_turning_angles(turning_angles=f)`` and words the error of a wrong call. The source is
    kept in :mod:`linecache`, for ``inspect.getsource`` (``check_turning_angles??`` in Jupyter).
    """
    name = exercise.name
    if not name.isidentifier() or keyword.iskeyword(name) or name in ("run", "seed"):
        raise ValueError(f"an exercise's name must be a Python name other than run and seed, not {name!r}")
    source = f'def check_{name}({name}, seed=None):\n    return run("{name}", {name}, seed)\n'
    filename = f"<ddg.checks: check_{name}>"
    made = {}
    exec(compile(source, filename, "exec"), globals(), made)  # the function's globals are this module's
    linecache.cache[filename] = (len(source), None, source.splitlines(keepends=True), filename)
    check = made[f"check_{name}"]
    check.__doc__ = _docstring(exercise)
    return check


globals().update({check: _check_function(EXERCISES[name]) for check, name in CHECKS.items()})

__all__ = ["Feedback", "WriteItYourself", "TIME_LIMIT", "EXERCISE_CLASSES", "EXERCISES", "CHECKS", "run", "draw",
           "public", "answer_results", *CHECKS]
