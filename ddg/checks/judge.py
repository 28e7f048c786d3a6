"""What a check reports, and how it finds the cause of a mistake.

An :class:`Exercise` draws its input (:meth:`Exercise.draw`, a list of :class:`Call`) and lists the
:class:`Mistake`\\ s students make, most specific first. What a right answer returns is not here: each
input carries it as data (``Call.want``: shipped with the public inputs of the students' checks, or
filled in by the grader from the instructor's answer key, which never leaves the instructor). The
verdict (:func:`judge`) first establishes what is wrong: the first mistake whose prediction the
answer matches on *every* input explains it, in the student's terms, with the value expected next
to the value that came back, at the first vertex where they differ. An answer that matches no
catalogued mistake gets the plain facts: which input, which vertex, expected and got. Changing the
input in place, or returning a list where numpy arrays are the rule, gets a line of its own.
"""

import re
from dataclasses import dataclass, field

import numpy as np

from . import runner


@dataclass
class Call:
    """One input of a check: the arguments, as JSON-ready specs (see ``geometry.build``), and what it is."""

    args: tuple
    what: str
    want: object = None  # what a right answer returns (from the answer key, never computed here)
    given: dict = field(default_factory=dict)  # what the mistakes that need the key predict, by key


def given(key):
    """A prediction the answer key supplies (``Call.given[key]``): for a mistake that is a slip in the
    answer's own construction, where computing it would take the answer's code."""
    return lambda want, call: call.given.get(key)


@dataclass
class Mistake:
    """A mistake students make, and how to recognise it.

    ``predict(want, call)`` returns what an answer with this mistake returns (``None`` where the
    mistake does not show, so the right value is expected there); or ``test(got, want, call)``
    says whether ``got`` shows it. ``message`` is a format string with ``{what}`` (the input),
    ``{at}`` (where), ``{want}`` and ``{got}`` (there), and ``words`` are the words a test expects
    in the message. Mistakes that show as a raised error match ``error`` (a regular expression).
    """

    name: str
    message: str
    predict: object = None
    test: object = None
    error: str = ""
    across: object = None  # ``across(gots, wants, calls)``, for a mistake seen only across the inputs
    undo: object = None  # ``undo(got, want, call)``: the answer without this mistake (for one seen by ``test``)


@dataclass
class Feedback:
    """The outcome of a check: passed, or what is wrong and where; and notes either way."""

    name: str
    problem: str | None = None
    inputs: int = 0
    notes: list = field(default_factory=list)
    kind: str = "public"  # the inputs: "public" (shipped with the checks) or "hidden" (drawn by the grader)
    todo: bool = False  # the answer is still the starter (it raises NotImplementedError): not passed, no error

    @property
    def passed(self):
        return self.problem is None

    def __bool__(self):
        return self.passed

    def __repr__(self):
        name = printable(self.name)[:60]
        lines = [f"✓ {name} passed on {self.inputs} {self.kind} inputs" if self.passed else
                 f"☐ {name}: to do, {printable(self.problem)}, then run this cell again" if self.todo else
                 f"✗ {name}: {printable(self.problem)}"]
        return "\n".join(lines + [f"  note: {printable(note)}" for note in self.notes])

    def _repr_html_(self):
        # on a light box, in the light and the dark theme: green, red, or a neutral grey for "to do"
        color = "#116329" if self.passed else "#424a53" if self.todo else "#a40e26"
        text = repr(self).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
        return (f'<pre style="color: {color}; background: #f6f8fa; padding: 0.4em 0.6em; '
                f'white-space: pre-wrap">{text}</pre>')


def printable(text):
    """``text`` without control characters (an answer's name or message could carry terminal codes)."""
    return "".join(" " if ord(c) < 32 or 127 <= ord(c) < 160 else c for c in str(text))


def short(values, digits=4):
    """Numbers as a reader wants them in a message: a few decimals, long arrays shortened."""
    values = np.asarray(values, dtype=float)
    if values.ndim == 0:
        return f"{float(values):.{digits}g}"
    return np.array2string(values, precision=digits, threshold=6, suppress_small=True, separator=", ")


class Exercise:
    """One coding exercise. Subclasses set :attr:`name`, :attr:`mistakes` and define the methods.

    A subclass's docstring says what the exercise asks for, starting with the call, as in
    ``turning_angles(vertices)``: that text is where the docstring of its ``check_*`` function
    comes from. Defining a subclass registers nothing: ``EXERCISE_CLASSES`` in
    ``ddg/checks/__init__.py`` lists the exercises of the book.
    """

    name = ""
    forbidden = ()  # DiscreteCurve quantities the answer must not use
    measures = ()  # "module.attribute" callables that measure what the answer must compute
    mistakes = ()
    unit = "vertex"  # what an index of the answer counts, for messages
    expects = "one value at every vertex"  # what a right answer returns, for a student who returned another shape
    tolerance = 1e-5  # relative to the scale of the expected values (float32 answers agree to 1e-7)

    def draw(self, rng):
        """The input: a list of :class:`Call`."""
        raise NotImplementedError

    def expected(self, call):
        """What a right answer returns for ``call``: the value it carries from the answer key."""
        if call.want is None:
            raise CheckError(f"the input {call.what!r} of {self.name} has no expected value")
        return call.want

    def close(self, got, want, call):
        """Whether ``got`` is right (arrays of the same shape)."""
        scale = max(float(np.abs(want).max()) if want.size else 0.0, 1.0)
        return bool(np.all(np.abs(got - want) <= self.tolerance * scale))

    def where(self, got, want, call):
        """The first place where ``got`` and ``want`` differ: an index (or ``None`` for a number)."""
        if want.ndim == 0:
            return None
        scale = max(float(np.abs(want).max()) if want.size else 0.0, 1.0)
        wrong = np.abs(got - want) > self.tolerance * scale
        wrong = wrong.any(axis=tuple(range(1, wrong.ndim))) if wrong.ndim > 1 else wrong
        return int(np.flatnonzero(wrong | np.isnan(got).reshape(len(got), -1).any(axis=1))[0])


class CheckError(Exception):
    """A fault of the check itself (never of the answer): raised only for a bug in ``ddg.checks``."""


def judge(exercise, calls, raw, name=None):
    """The :class:`Feedback` for the raw results of ``exercise`` on ``calls`` (see ``runner.evaluate``).

    Total: whatever ``raw`` holds (the answer's process may send anything) gets a verdict. Only a
    fault of the check's own code raises, as :class:`CheckError`.
    """
    feedback = Feedback(name or exercise.name, inputs=len(calls))
    if isinstance(raw, dict):
        if isinstance(raw.get("timeout"), (int, float)):
            feedback.problem = f"it did not return within {raw['timeout']:g} s (an endless loop?)"
        elif raw.get("exited") is True:
            feedback.problem = "it ended the process it ran in (os._exit, or a crash)"
        else:
            feedback.problem = printable(raw.get("error", "the answer's process sent back something that is not "
                                                          "its results"))[:400]
        return feedback
    if runner.well_formed(raw) and len(raw) <= len(calls) and any("missing" in r for r in raw[-1:]):
        feedback.problem = "not written yet: replace `raise NotImplementedError` with your code"
        feedback.todo = True
        return feedback
    if not runner.well_formed(raw) or len(raw) != len(calls):  # read back from elsewhere (the grader's sandbox)
        feedback.problem = "the process the answer ran in sent back something that is not its results"
        return feedback
    try:
        with np.errstate(all="ignore"):  # whatever the notebook set: the verdict's arithmetic never raises
            feedback.problem = _verdict(exercise, calls, raw)
    except Exception as error:  # noqa: BLE001 - a bug of the check, said as such
        raise CheckError(f"the check of {exercise.name} failed on its own ({type(error).__name__}: {error}); "
                         "this is a fault of the check, not of the answer") from error
    if any(r.get("mutated") is True for r in raw):
        feedback.notes.append("your function changes the array it is given (in place): work on a copy, as the "
                              "caller still needs it (np.array(vertices) copies)")
    if feedback.passed and any(r.get("type") in ("list", "tuple") for r in raw):
        kind = next(r["type"] for r in raw if r.get("type") in ("list", "tuple"))
        feedback.notes.append(f"it returns a {kind}; the rest of the book works with numpy arrays (np.array(...))")
    return feedback


def result_array(entry):
    """The one door every result passes through before it is compared: a float array, or ``None``
    where the result is none (nested lists of different lengths, text, objects: whatever the answer's
    process sent). :func:`shape_problem` then says, in the student's terms, what is wrong with it."""
    value = entry.get("value") if isinstance(entry, dict) else None
    try:
        array = np.asarray(value)
        return array.astype(float) if array.dtype.kind in "biuf" else None
    except (TypeError, ValueError, OverflowError, RecursionError, MemoryError):
        return None


def _expected(exercise, call):
    return np.asarray(exercise.expected(call), dtype=float)


def _count(array):
    """An array's shape in words: "one number", "3 numbers", "4 rows of 2", "an array of shape (2, 2, 2)"."""
    if array.ndim == 0:
        return "one number"
    if array.ndim == 1:
        return f"{len(array)} number{'s' * (len(array) != 1)}"
    if array.ndim == 2:
        return f"{len(array)} row{'s' * (len(array) != 1)} of {array.shape[1]}"
    return f"an array of shape {array.shape}"


def shape_problem(exercise, got, want, call):
    """What is wrong with the shape of ``got``, in the student's terms (``None`` if it is right)."""
    if got is None:
        return f"on {call.what} it returned nested lists of different lengths or things that are not numbers"
    if got.shape == want.shape:
        return None
    if want.ndim == 0:
        return f"on {call.what} it returned {_count(got)} where one number was expected: {exercise.expects}"
    unit = exercise.unit
    wanted = f"{_count(want)} (one per {unit})"
    if got.ndim == 0:
        return f"on {call.what} it returned one number where {wanted} were expected: {exercise.expects}"
    if len(got) != len(want):
        return f"you returned {_count(got)} for {call.what}, where {wanted} were expected: {exercise.expects}"
    each = "one number" if want.ndim == 1 else f"{want.shape[1]} numbers" if want.ndim == 2 else f"shape {want.shape[1:]}"
    return (f"on {call.what} it returned {_count(got)}, the right count, but each {unit} needs {each}: "
            f"{exercise.expects}")


def _verdict(exercise, calls, raw):
    """``None`` if every result is right, else what is wrong, most specific cause first."""
    errors = [(i, r) for i, r in enumerate(raw) if "error" in r]
    if errors:
        i, r = errors[0]
        for mistake in exercise.mistakes:
            if mistake.error and _safe(lambda m=mistake: re.search(m.error, r["error"])):
                return _say(mistake, calls[i], None, None, None, exercise)
        if r["kind"] in ("type", "exited"):
            return f"on {calls[i].what}: {printable(r['error'])}"
        return f"on {calls[i].what} it raised {printable(r['kind'])[:60]}: {printable(r['error'])}"
    got = [result_array(r) for r in raw]
    want = [_expected(exercise, call) for call in calls]
    right = [_right(exercise, g, w, c) for g, w, c in zip(got, want, calls, strict=True)]
    if all(right):
        return None
    first = right.index(False)
    for mistake in exercise.mistakes:
        if not mistake.error and _safe(lambda m=mistake: _shows(m, got, want, calls, exercise)):
            g, w = got[first], want[first]
            return _say(mistake, calls[first], g, w, _place(exercise, g, w, calls[first]), exercise)
    paired = _pair(exercise, got, want, calls)
    if paired:
        return paired
    for g, w, call in zip(got, want, calls, strict=True):
        problem = shape_problem(exercise, g, w, call)
        if problem:
            return problem
    g, w, call = got[first], want[first], calls[first]
    if not np.isfinite(g).all():
        at = int(np.flatnonzero(~np.isfinite(g).reshape(len(g), -1).all(axis=1))[0]) if g.ndim else None
        return f"on {call.what} it contains NaN or infinity{_at(exercise, at)}"
    at = exercise.where(g, w, call)
    return (f"on {call.what}{_at(exercise, at)}: expected {short(w if at is None else w[at])}, "
            f"got {short(g if at is None else g[at])}")


def _safe(test):
    """``test()``, or ``False`` where a mistake's recogniser cannot apply to this answer (it raised)."""
    try:
        return bool(test())
    except Exception:  # noqa: BLE001 - a prediction that does not fit this answer's shape is no match
        return False


def right_inputs(exercise, calls, raw):
    """For each input, whether the answer's result was right (for partial credit): all ``False``
    when the whole run failed, and for any input it raised on or did not reach."""
    if not isinstance(raw, list) or not runner.well_formed(raw) or len(raw) > len(calls):
        return [False] * len(calls)
    try:
        with np.errstate(all="ignore"):
            return [i < len(raw) and "value" in raw[i]
                    and _right(exercise, result_array(raw[i]), _expected(exercise, call), call)
                    for i, call in enumerate(calls)]
    except Exception as error:  # noqa: BLE001 - a bug of the check, said as such
        raise CheckError(f"the check of {exercise.name} failed on its own ({type(error).__name__}: {error})") from error


def _right(exercise, got, want, call):
    return (got is not None and got.shape == want.shape and bool(np.isfinite(got).all())
            and _safe(lambda: exercise.close(got, want, call)))


def _prediction(mistake, got, want, call):
    predicted = mistake.predict(want, call)
    return want if predicted is None else np.asarray(predicted, dtype=float)


def _matches(mistake, got, want, call, exercise):
    """Whether ``got`` is what ``mistake`` makes of ``want`` on one input."""
    if got is None:
        return False
    if mistake.test is not None:
        return bool(mistake.test(got, want, call))
    p = _prediction(mistake, got, want, call)
    if got.shape != p.shape or not np.all(np.isfinite(got) == np.isfinite(p)):
        return False
    finite = np.isfinite(p)
    return exercise.close(np.where(finite, got, 0), np.where(finite, p, 0), call)


def _shows(mistake, got, want, calls, exercise):
    """Whether the answer shows ``mistake`` on every input (and is right where it cannot show); asked only
    of an answer that is wrong somewhere."""
    if mistake.across is not None:
        return all(g is not None for g in got) and mistake.across(got, want, calls)
    return all(_matches(mistake, g, w, call, exercise) for g, w, call in zip(got, want, calls, strict=True))


def _pair(exercise, got, want, calls):
    """Two catalogued mistakes at once, ``a`` then ``b``: ``b`` is seen on what ``a`` makes of the right
    answer (``a.predict``), or on the answer with ``a`` undone (``a.undo``, for a mistake recognised
    by a ``test``). The message names both, or ``None`` if no pair explains the answer."""
    candidates = [m for m in exercise.mistakes if not m.error and m.across is None]
    for a in candidates:
        try:
            if a.predict is not None:
                pairs = [(g, _prediction(a, None, w, c)) for g, w, c in zip(got, want, calls, strict=True)]
            elif a.undo is not None:
                pairs = [(np.asarray(a.undo(g, w, c), dtype=float), w) for g, w, c in zip(got, want, calls, strict=True)]
            else:
                continue
        except Exception:  # noqa: BLE001 - the mistake does not apply to this answer's shape
            continue
        if all(x.shape == y.shape and np.allclose(x, y, equal_nan=True) for x, y in
               ((p, w) if a.predict is not None else (g, p) for (g, p), w in zip(pairs, want, strict=True))):
            continue  # a does not show: the pair would be b alone, which did not match
        for b in candidates:
            if b is a or b.name == a.name:
                continue
            if _safe(lambda b=b, pairs=pairs: all(_matches(b, g, w, c, exercise) for (g, w), c in zip(pairs, calls, strict=True))):
                if a.predict is not None:  # a shows where its prediction differs from the right answer
                    i, at = _differ(exercise, [p for _, p in pairs], want, calls)
                else:  # a shows where undoing it changes the answer
                    i, at = _differ(exercise, [g for g, _ in pairs], got, calls)
                j, bt = _differ(exercise, got, [p if a.predict is not None else w for (_, p), w in
                                                zip(pairs, want, strict=True)], calls)
                return (f"two mistakes at once. First, {_say(a, calls[i], got[i], want[i], at, exercise)}. "
                        f"Second, {_say(b, calls[j], got[j], want[j], bt, exercise)}")
    return None


def _differ(exercise, xs, ys, calls):
    """The first input where ``xs`` and ``ys`` differ, and the place there (``None`` where the shapes differ)."""
    for i, (x, y, call) in enumerate(zip(xs, ys, calls, strict=True)):
        if x.shape != y.shape:
            return i, None
        if not _safe(lambda x=x, y=y, call=call: exercise.close(x, y, call)):
            return i, _place(exercise, x, y, call)
    return 0, None


def _place(exercise, got, want, call):
    """Where to point in a message: the first place the answer differs from the right one."""
    if got is None or got.shape != want.shape or want.ndim == 0:
        return None
    finite = np.isfinite(got).reshape(len(got), -1).all(axis=1)
    if not finite.all():
        return int(np.flatnonzero(~finite)[0])
    try:
        return exercise.where(got, want, call)
    except (IndexError, ValueError):
        return None


def _at(exercise, at):
    return "" if at is None else f", at {exercise.unit} {at}"


def _say(mistake, call, got, want, at, exercise):
    """The mistake's message, filled in."""
    def pick(x):
        if x is None:
            return None
        try:
            return x[at] if at is not None and x.ndim and len(x) > at else x
        except (IndexError, TypeError):
            return x
    return mistake.message.format(what=call.what, at=_at(exercise, at), want=short(pick(want)) if want is not None
                                  else "", got=short(pick(got)) if got is not None else "", index=at)
