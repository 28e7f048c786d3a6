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
import json
import pathlib

import numpy as np

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


def check_osculating_center(osculating_center, seed=None):
    """``osculating_center(curve, t)``: centre of the osculating circle of a ``ddg.smooth`` curve at ``t``."""
    return run("osculating_center", osculating_center, seed)


def check_staircase(staircase, seed=None):
    """``staircase(curve, m)``: the ``8m`` vertices of a closed staircase around a ``ddg.smooth`` ellipse.

    ``v[2k]`` is the point ``curve.position(2 pi k / (4m))`` and ``v[2k + 1]`` the corner after it;
    steps are horizontal or vertical and corners lie outside the ellipse.
    """
    return run("staircase", staircase, seed)


def check_vertex_normals(vertex_normals, seed=None):
    """``vertex_normals(curve, method)``: unit normals at the vertices of a closed curve.

    ``method`` is ``"bisector"`` (the unit bisector of the two edge normals), ``"length-weighted"``
    (the edge normals averaged with weights ``|e|``), ``"length-gradient"`` (the direction of the
    gradient of length) or ``"area-gradient"`` (the direction of the gradient of the signed area).
    """
    return run("vertex_normals", vertex_normals, seed)


def check_turning_angles(turning_angles, seed=None):
    """``turning_angles(vertices)``: clockwise turning angle at every vertex of a closed polygon, in ``(-pi, pi]``."""
    return run("turning_angles", turning_angles, seed)


def check_rebuild(rebuild, seed=None):
    """``rebuild(psi, lengths, start, heading)``: vertices ``v_0 ... v_n`` from turning angles and edge lengths.

    ``psi[i]`` is the clockwise turn at ``v_i``, ``lengths[i] = |e_{i+1/2}|``, ``start = v_0`` and
    ``heading`` is the angle (counter-clockwise from the x-axis) of the first edge ``e_{1/2}``.
    """
    return run("rebuild", rebuild, seed)


def check_length_gradient(length_gradient, seed=None):
    """``length_gradient(vertices)``: the gradient of length of a closed polygon under the lecture's ``<.,.>``."""
    return run("length_gradient", length_gradient, seed)


def check_minkowski_area(minkowski_area, seed=None):
    """``minkowski_area(curve, eps)``: area of the Minkowski sum of a clockwise simple polygon with a disk.

    It must be right for non-convex polygons too, for ``eps`` within the conditions of the book's
    theorem on the Minkowski sum of a simple polygon. It is measured against shapely's round buffer.
    """
    return run("minkowski_area", minkowski_area, seed)


def check_circle_curvature(circle_curvature, seed=None):
    """``circle_curvature(curve)``: signed ``1/R`` of the circle through ``v_{i-1}, v_i, v_{i+1}``, at every vertex."""
    return run("circle_curvature", circle_curvature, seed)


def check_zigzag_exponent(zigzag_exponent, seed=None):
    """``zigzag_exponent(b)``: the exponent ``p`` in ``max_i |k_i - 1| ~ C n^p`` for zigzags of amplitude ``n^-b``, ``b > 1``."""
    return run("zigzag_exponent", zigzag_exponent, seed)


__all__ = ["Feedback", "WriteItYourself", "TIME_LIMIT", "EXERCISE_CLASSES", "EXERCISES", "CHECKS", "run", "draw",
           "public", "answer_results", *CHECKS]
