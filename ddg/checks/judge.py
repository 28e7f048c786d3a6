"""What a check reports, and how it finds the cause of a mistake.

An :class:`Exercise` draws its input (:meth:`Exercise.draw`, a list of :class:`Call`), says what a
right answer returns (:meth:`Exercise.expected`, computed only after the answer has run, in the
checking process) and lists the :class:`Mistake`\\ s students make, most specific first. The
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


@dataclass
class Feedback:
    """The outcome of a check: passed, or what is wrong and where; and notes either way."""

    name: str
    problem: str | None = None
    inputs: int = 0
    notes: list = field(default_factory=list)

    @property
    def passed(self):
        return self.problem is None

    def __bool__(self):
        return self.passed

    def __repr__(self):
        name = printable(self.name)[:60]
        lines = [f"✓ {name} passed on {self.inputs} fresh random inputs" if self.passed else
                 f"✗ {name}: {printable(self.problem)}"]
        return "\n".join(lines + [f"  note: {printable(note)}" for note in self.notes])

    def _repr_html_(self):
        color = "#116329" if self.passed else "#a40e26"  # on a light box, in the light and the dark theme
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


EXERCISES = {}
"""Every coding exercise, by the name of the function it asks for: defining a subclass of
:class:`Exercise` with a ``name`` registers it (ddg/checks/__init__.py imports the modules)."""


class Exercise:
    """One coding exercise. Subclasses set :attr:`name`, :attr:`mistakes` and define the methods."""

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        if cls.name:
            EXERCISES[cls.name] = cls()

    name = ""
    forbidden = ()  # DiscreteCurve quantities the answer must not use
    measures = ()  # "module.attribute" callables that measure what the answer must compute
    mistakes = ()
    unit = "vertex"  # what an index of the answer counts, for messages
    tolerance = 1e-5  # relative to the scale of the expected values (float32 answers agree to 1e-7)

    def draw(self, rng):
        """The input: a list of :class:`Call`."""
        raise NotImplementedError

    def expected(self, call):
        """What a right answer returns for ``call`` (only ever computed after the answer ran)."""
        raise NotImplementedError

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


def judge(exercise, calls, raw, name=None):
    """The :class:`Feedback` for the raw results of ``exercise`` on ``calls`` (see ``runner.evaluate``)."""
    feedback = Feedback(name or exercise.name, inputs=len(calls))
    if isinstance(raw, dict):
        if isinstance(raw.get("timeout"), (int, float)):
            feedback.problem = f"it did not return within {raw['timeout']:g} s (an endless loop?)"
        elif raw.get("exited") is True:
            feedback.problem = "it ended the process it ran in (os._exit, or a crash)"
        else:
            feedback.problem = str(raw.get("error", "the answer's process sent back something that is not its results"))
        return feedback
    if not runner.well_formed(raw):  # results read back from elsewhere (the grader's sandbox)
        feedback.problem = "the process the answer ran in sent back something that is not its results"
        return feedback
    if len(raw) < len(calls) and (not raw or "missing" in raw[-1]) or any("missing" in r for r in raw):
        feedback.problem = "not written yet: replace `raise NotImplementedError` with your code"
        return feedback
    with np.errstate(all="ignore"):  # whatever the notebook set: the verdict's arithmetic never raises
        feedback.problem = _verdict(exercise, calls, raw)
    if any(r.get("mutated") for r in raw):
        feedback.notes.append("your function changes the array it is given (in place): work on a copy, as the "
                              "caller still needs it (np.array(vertices) copies)")
    if feedback.passed and any(r.get("type") in ("list", "tuple") for r in raw):
        kind = next(r["type"] for r in raw if r.get("type") in ("list", "tuple"))
        feedback.notes.append(f"it returns a {kind}; the rest of the book works with numpy arrays (np.array(...))")
    return feedback


def _verdict(exercise, calls, raw):
    """``None`` if every result is right, else what is wrong, most specific cause first."""
    errors = [(i, r) for i, r in enumerate(raw) if "error" in r]
    if errors:
        i, r = errors[0]
        for mistake in exercise.mistakes:
            if mistake.error and re.search(mistake.error, r["error"]):
                return _say(mistake, calls[i], None, None, None, exercise)
        if r["kind"] == "type":
            return f"on {calls[i].what}: {r['error']}"
        return f"on {calls[i].what} it raised {r['kind']}: {r['error']}"
    got = [np.asarray(r["value"], dtype=float) if _rectangular(r["value"]) else None for r in raw]
    want = [np.asarray(exercise.expected(call), dtype=float) for call in calls]
    right = [_right(exercise, g, w, c) for g, w, c in zip(got, want, calls, strict=True)]
    if all(right):
        return None
    first = right.index(False)
    for mistake in exercise.mistakes:
        if not mistake.error and _shows(mistake, got, want, calls, exercise):
            g, w = got[first], want[first]
            return _say(mistake, calls[first], g, w, _place(exercise, g, w, calls[first]), exercise)
    g, w, call = got[first], want[first], calls[first]
    if g is None:
        return f"on {call.what} it returned nested lists of different lengths, not an array"
    if g.shape != w.shape:
        return f"on {call.what} the answer should have shape {w.shape}, got {g.shape}"
    if not np.isfinite(g).all():
        at = int(np.flatnonzero(~np.isfinite(g).reshape(len(g), -1).all(axis=1))[0]) if g.ndim else None
        return f"on {call.what} it contains NaN or infinity{_at(exercise, at)}"
    at = exercise.where(g, w, call)
    return (f"on {call.what}{_at(exercise, at)}: expected {short(w if at is None else w[at])}, "
            f"got {short(g if at is None else g[at])}")


def right_inputs(exercise, calls, raw):
    """For each input, whether the answer's result was right (for partial credit): all ``False``
    when the whole run failed, and for any input it raised on or did not reach."""
    if not isinstance(raw, list) or not runner.well_formed(raw):
        return [False] * len(calls)
    with np.errstate(all="ignore"):
        return [i < len(raw) and "value" in raw[i] and _rectangular(raw[i]["value"])
                and _right(exercise, np.asarray(raw[i]["value"], dtype=float),
                           np.asarray(exercise.expected(call), dtype=float), call)
                for i, call in enumerate(calls)]


def _right(exercise, got, want, call):
    return got is not None and got.shape == want.shape and bool(np.isfinite(got).all()) and exercise.close(got, want, call)


def _rectangular(value):
    try:
        np.asarray(value, dtype=float)
    except ValueError:
        return False
    return True


def _prediction(mistake, got, want, call):
    predicted = mistake.predict(want, call)
    return want if predicted is None else np.asarray(predicted, dtype=float)


def _shows(mistake, got, want, calls, exercise):
    """Whether the answer shows ``mistake`` on every input (and is right where it cannot show)."""
    if mistake.across is not None:
        return all(g is not None for g in got) and mistake.across(got, want, calls)
    for g, w, call in zip(got, want, calls, strict=True):
        if g is None:
            return False
        if mistake.test is not None:
            if not mistake.test(g, w, call):
                return False
            continue
        p = _prediction(mistake, g, w, call)
        if g.shape != p.shape or not np.all(np.isfinite(g) == np.isfinite(p)):
            return False
        finite = np.isfinite(p)
        if not exercise.close(np.where(finite, g, 0), np.where(finite, p, 0), call):
            return False
    return any(g is not None and (g.shape != w.shape or not exercise.close(g, w, c))
               for g, w, c in zip(got, want, calls, strict=True))


def _place(exercise, got, want, call):
    """Where to point in a message: the first place the answer differs from the right one."""
    if got is None or got.shape != want.shape or want.ndim == 0:
        return None
    finite = np.isfinite(got).reshape(len(got), -1).all(axis=1)
    if not finite.all():
        return int(np.flatnonzero(~finite)[0])
    return exercise.where(got, want, call)


def _at(exercise, at):
    return "" if at is None else f", at {exercise.unit} {at}"


def _say(mistake, call, got, want, at, exercise):
    """The mistake's message, filled in."""
    pick = (lambda x: x) if at is None else (lambda x: x[at] if x is not None and x.ndim and len(x) > at else x)
    return mistake.message.format(what=call.what, at=_at(exercise, at), want=short(pick(want)) if want is not None
                                  else "", got=short(pick(got)) if got is not None else "", index=at)
