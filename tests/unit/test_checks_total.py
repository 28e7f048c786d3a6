"""Every check is total: whatever an answer returns, or whatever comes back on the pipe in its
name, the check gives a verdict in the student's terms and never raises.

Three doors, each fed by generated values: what an answer returns (``runner.plain`` turns it into
data in the answer's process), the raw results the grader reads back (forged at will by the
answer's process), and the book's own solutions mangled in the ways students' results are.
"""

import importlib
import math

import numpy as np
import pytest
from catalogue import REFERENCE
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from ddg import checks
from ddg.checks import runner
from instructor import references
judging = importlib.import_module("ddg.checks.judge")  # the module (ddg.checks.judge is also a function)

NAMES = sorted(checks.EXERCISES)
CALLS = {name: references.hidden(name, 7) for name in NAMES}
RIGHT = {name: runner.answers(REFERENCE[name], [c.args for c in CALLS[name]], checks.geometry.build) for name in NAMES}
RAW_WORDS = ("Traceback", "broadcast", "operands could not", "inhomogeneous", "object of type", "NoneType' object",
             "index out of bounds", "numpy.")


def verdict(name, raw):
    feedback = judging.judge(checks.EXERCISES[name], CALLS[name], raw, name)
    assert isinstance(feedback, judging.Feedback)
    text = repr(feedback)
    assert not any(word in text for word in RAW_WORDS), text
    return feedback


numbers = st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-10**30, 10**30), st.booleans())
leaves = st.one_of(numbers, st.none(), st.text(max_size=5), st.dictionaries(st.text(max_size=2), numbers, max_size=2))
values = st.recursive(leaves, lambda inner: st.lists(inner, max_size=6), max_leaves=40)
arrays = st.builds(lambda shape, fill: np.full(shape, fill).tolist(),
                   st.lists(st.integers(0, 5), max_size=4).map(tuple), st.floats(allow_nan=True))


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(name=st.sampled_from(NAMES), value=st.one_of(values, arrays), where=st.integers(0, 20),
       kind=st.sampled_from(["value", "error", "forged", "short", "long", "dict"]))
def test_any_raw_result_gets_a_verdict(name, value, where, kind):
    """Raw results as the pipe may carry them: any value at any input, errors, forged entries, lists
    of the wrong length, a dict instead of a list."""
    raw = [dict(r) for r in RIGHT[name]]
    i = where % len(raw)
    if kind == "value":
        raw[i] = {"value": value, "type": "list"}
    elif kind == "error":
        raw[i] = {"error": str(value)[:50], "kind": str(value)[:10]}
    elif kind == "forged":
        raw[i] = value
    elif kind == "short":
        raw = raw[:i]
    elif kind == "long":
        raw = raw + [raw[0]] * (i + 1)
    else:
        raw = {"error": value} if where % 2 else {"timeout": value}
    feedback = verdict(name, raw)
    if kind in ("short", "long", "forged", "error"):
        assert not feedback
    judging.right_inputs(checks.EXERCISES[name], CALLS[name], raw)  # partial credit is total too


class Strange:
    def __array__(self, *args, **kwargs):
        raise SystemExit("an object that ends the process when numpy looks at it")


RETURNED = [None, "1.5", b"1", "abc", {"a": 1}, {1, 2}, 1 + 2j, np.array([1 + 1j, 2]), (x for x in range(3)),
            np.array(["1.0", "2.0"], dtype=object), np.array([1.0, None], dtype=object), [[1, 2], [3]], Strange(),
            np.zeros(2_000_000), [Strange()], math.inf, np.float16(1), np.ma.masked_array([1.0, 2.0], [0, 1]),
            np.zeros((0, 2)), [], (), np.array(3.0), True, object(), type, print]


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("value", RETURNED, ids=[type(v).__name__ for v in RETURNED])
def test_any_returned_value_gets_a_verdict(name, value):
    """What an answer returns goes through ``runner.plain`` in its own process, then the judge here."""
    entry = runner.plain(value)
    assert "value" in entry or entry.get("kind") == "type"
    if isinstance(value, (str, bytes, dict, complex)) or isinstance(value, np.ndarray) and value.dtype.kind == "c":
        assert "error" in entry, entry  # text that looks like a number is not a number
    raw = [dict(r) for r in RIGHT[name]]
    raw[0] = {**entry, "mutated": False}
    assert not verdict(name, raw)


def mangles():
    """The ways a student's result differs from a right one in form (each keeps the right numbers somewhere)."""
    return {
        "one short": lambda r: r[:-1], "one too many": lambda r: np.concatenate([r, r[:1]]),
        "ends missing": lambda r: r[1:-1], "first missing": lambda r: r[1:], "empty": lambda r: r[:0],
        "column": lambda r: r.reshape(len(r), -1)[:, :1] if r.ndim else r.reshape(1, 1),
        "3-d": lambda r: r.reshape(1, *r.shape, 1), "first only": lambda r: r.ravel()[:1],
        "transposed": lambda r: r.T if r.ndim == 2 else r.reshape(1, -1), "flattened": lambda r: r.ravel(),
        "doubled": lambda r: np.stack([r, r]), "scalar of the sum": lambda r: np.float64(r.sum()),
        "NaN": lambda r: r * np.nan, "inf at 0": lambda r: np.where(np.arange(r.size).reshape(r.shape) == 0, np.inf, r),
        "as text": lambda r: str(r.tolist()), "None": lambda r: None, "complex": lambda r: r + 1j,
        "nested ragged": lambda r: [r.tolist(), [1]], "dict": lambda r: {"result": r.tolist()},
        "tuple of two": lambda r: (r, r), "object array": lambda r: np.array([r, None], dtype=object),
    }


def same(mangle, right):
    """Whether ``mangle`` leaves the result ``right`` as it is."""
    try:
        mangled = np.asarray(mangle(right))
        if mangled.dtype.kind not in "biuf":
            return False
    except (TypeError, ValueError, IndexError):
        return False
    return mangled.shape == right.shape and np.array_equal(mangled, right)


@pytest.mark.parametrize("name", NAMES)
def test_the_books_solutions_mangled_get_a_verdict_never_a_crash(name):
    """The issue's 20 ways (and one more), through every check: each gets a clear verdict, none passes."""
    for seed in range(3):
        calls = references.hidden(name, seed)
        for mangle_name, mangle in mangles().items():
            def answer(*args, mangle=mangle):
                return mangle(np.asarray(REFERENCE[name](*args), dtype=float))
            answer.__name__ = name
            raw = runner.answers(answer, [c.args for c in calls], checks.geometry.build)
            feedback = judging.judge(checks.EXERCISES[name], calls, raw, name)
            text = repr(feedback)
            assert not any(word in text for word in RAW_WORDS), (mangle_name, text)
            unchanged = all(same(mangle, np.asarray(r["value"])) for r in runner.answers(
                REFERENCE[name], [c.args for c in calls], checks.geometry.build))
            if not unchanged:  # a flattened 1-d result, the sum of one number: the same result, rightly passed
                assert not feedback, (mangle_name, text)


def test_a_missing_wrap_around_and_the_wrong_count_are_said_in_the_students_terms():
    def short(vertices):
        return REFERENCE["turning_angles"](vertices)[1:-1]

    def zeros(vertices):
        return np.zeros(len(vertices) - 1)

    feedback = checks.run("turning_angles", short, 0, isolate=False)
    assert "the first and last vertices are missing" in feedback.problem and "wrap-around" in feedback.problem
    feedback = checks.run("turning_angles", zeros, 0, isolate=False)
    assert "you returned 3 numbers for a clockwise square, where 4 numbers (one per vertex) were expected" in \
        feedback.problem, feedback
