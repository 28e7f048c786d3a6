"""Immediate feedback on homework: ``check_*(answer)`` tests an answer and says what is wrong.

>>> from ddg.checks import check_turning_angles
>>> check_turning_angles(turning_angles)          # doctest: +SKIP
✓ turning_angles passed on 14 fresh random inputs

or, for example, ``✗ turning_angles: your angles look like degrees: on a clockwise square, at
vertex 0 you give 90 where 1.571 (radians) was expected``. ``bool(feedback)`` is ``True`` when the
answer is right. Pass ``seed=`` to repeat the same input.

How a check works:

1. It draws fresh random input (polygons, curves, parameters), all of it before your answer runs.
2. It runs your answer on that input in a separate process, for at most :data:`TIME_LIMIT`
   seconds, with the ``ddg`` quantity the exercise asks for switched off ("write this one
   yourself"), without the checks' own code, and with everything it starts stopped afterwards
   (``ddg/checks/runner.py`` says how).
3. Back here it works out what a right answer returns and compares: if yours differs, it looks
   for the cause among the mistakes students make (degrees for radians, the other sign convention,
   the closed curve's wrap-around, an index shifted by one, a missing weight ...) and names it,
   with the value expected next to yours; otherwise it says where the two differ.

What a check is not: a sandbox against deliberate cheating. Switching a quantity off catches the
one-line shortcut (``return DiscreteCurve(v).turning_angles``); an answer that copies ``ddg``'s
public source can still pass. Where ``fork`` is missing (Windows) the answer runs in a thread of
this process, and only the time limit applies.

The same exercises are graded by ``python -m instructor.grade``: there the input is drawn by the
grader from a secret seed, only the student's answer runs, in a sandbox, and the grader judges.
"""

import numpy as np

from . import comparing, curvatures, curves, geometry  # noqa: F401 (importing them registers their exercises)
from .judge import EXERCISES, CheckError, Feedback, judge
from .runner import TIME_LIMIT, WriteItYourself, evaluate

CHECKS = {f"check_{name}": name for name in EXERCISES}
"""The check functions of the book, by name, with the exercise each one checks."""


def draw(name, seed=None):
    """The input of one check: a list of ``judge.Call``, from ``seed`` (random when ``None``)."""
    return EXERCISES[name].draw(np.random.default_rng(seed))


def run(name, answer, seed=None, isolate=True):
    """Check ``answer`` for the exercise ``name`` (a key of :data:`EXERCISES`): its :class:`Feedback`.

    ``isolate=False`` runs the answer in this process (no time limit, nothing switched off): for
    tests, where the answers are the test's own.
    """
    exercise = EXERCISES[name]
    calls = draw(name, seed)
    specs = [call.args for call in calls]
    if isolate:
        raw = evaluate(answer, specs, exercise.forbidden, exercise.measures, build=geometry.build)
    else:
        from .runner import answers
        raw = answers(answer, specs, geometry.build)
    label = getattr(answer, "__name__", name) if callable(answer) else name
    try:
        return judge(exercise, calls, raw, label if isinstance(label, str) else name)
    except CheckError as error:
        return Feedback(name, problem=f"{error}: please tell your instructor", inputs=len(calls))


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


__all__ = ["Feedback", "WriteItYourself", "TIME_LIMIT", "EXERCISES", "CHECKS", "run", "draw", "answer_results",
           *CHECKS]
