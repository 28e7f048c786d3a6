"""How ``ddg`` checks what it is given, so that bad input gets an error of ``ddg.errors`` that names
the problem and where it is (the vertex, the argument), instead of a NaN or numpy's own message."""

import math
import numbers
import warnings

import numpy as np

from .errors import DegenerateCurveError, InputError, OutOfRangeError


def choose(value, valid, what):
    """``value`` if it is one of ``valid``, else an ``InputError`` listing the choices."""
    if not isinstance(value, str) or value not in valid:
        raise InputError(f"unknown {what} {value!r}; choose one of {', '.join(map(repr, valid))}")
    return value


def real(value, name, minimum=None, strict=False):
    """``value`` as a finite float, or an ``InputError`` naming ``name``: no NaN, no arrays, no complex."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise InputError(f"{name} must be a real number, got {value!r}")
    try:
        value = float(value)
    except OverflowError:  # an int beyond the floats
        raise OutOfRangeError(f"{name} is beyond the largest float (about 1.8e308), got {value:.3g}") from None
    if not math.isfinite(value):
        raise InputError(f"{name} must be finite, got {value!r}")
    if minimum is not None and (value <= minimum if strict else value < minimum):
        bound = "positive" if strict and minimum == 0 else f"{'>' if strict else '>='} {minimum:g}"
        raise InputError(f"{name} must be {bound}, got {value!r}")
    return value


def count(value, name, minimum, maximum=None):
    """``value`` as an ``int`` in ``[minimum, maximum]``, or an ``InputError`` (no bools, no floats)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral) or value < minimum:
        raise InputError(f"{name} must be an integer >= {minimum}, got {value!r}")
    if maximum is not None and value > maximum:
        raise OutOfRangeError(f"{name} must be at most {maximum}, got {value!r}")
    return int(value)


def flag(value, name):
    """``value`` if it is ``True`` or ``False`` (a truthy string such as ``"no"`` is refused)."""
    if not isinstance(value, (bool, np.bool_)):
        raise InputError(f"{name} must be True or False, got {value!r}")
    return bool(value)


def require_finite(values, say, error=None):
    """Raise ``error(say(i))`` (an ``InputError`` by default) at the first row ``i`` of ``values`` that
    holds a NaN or an infinity. One sum decides for all rows but where an entry is not finite."""
    with np.errstate(over="ignore", invalid="ignore"):
        if np.isfinite(np.add.reduce(values, axis=None)):
            return
    finite = np.isfinite(values)
    bad = np.flatnonzero(~(finite if finite.ndim == 1 else finite.all(axis=1)))
    if len(bad):
        raise (error or InputError)(say(int(bad[0])))


def _real_or_why(x):
    """An object array's entry as a float, or a string saying why it is not one."""
    if isinstance(x, (bool, np.bool_)) or not isinstance(x, numbers.Real):
        return "that is not a real number"
    try:
        return float(x)
    except OverflowError:
        return "beyond the largest float (about 1.8e308)"


def _short(x):
    """``repr(x)``, cut short (a Python int can have thousands of digits)."""
    text = repr(x.tolist() if isinstance(x, np.ndarray) else x)
    return text if len(text) <= 60 else f"{text[:24]}...{text[-8:]} ({len(text)} characters)"


def values(data, name, what="vertex", columns=None, finite=True):
    """``data`` as a new float array, or an ``InputError`` naming the row at fault (``what`` and its index).

    Refused: text (even text that reads as a number), complex numbers and booleans; rows of
    different lengths; masked entries; NaN and infinities; and numbers beyond the largest float
    (``OutOfRangeError``). ``columns`` is the length every row must have (``None``: any).
    ``finite=False`` leaves NaN and infinities given as floats to the caller (:func:`edges`).
    """
    def say(i, problem):
        if name == "vertices":
            return f"{what} {i} has a {problem.replace('value', 'coordinate')}"
        return f"{name} has a {problem.replace(':', f' at {what} {i}:', 1) if ':' in problem else problem}"

    if isinstance(data, np.ma.MaskedArray):
        masked = np.ma.getmaskarray(data)
        if masked.any():
            i = int(np.flatnonzero(masked.reshape(len(masked), -1).any(axis=1))[0]) if masked.ndim else 0
            raise InputError(say(i, f"masked value: {data[i]}; drop or fill masked entries first (np.ma.compress_rows)"))
        data = data.data
    hint = {"zip": "list(zip(...))", "generator": "list(...)", "map": "list(...)", "DiscreteCurve": "its .vertices",
            "SmoothCurve": ".sample(n) for a DiscreteCurve, then its .vertices", "str": "numbers, not text",
            "bytes": "numbers, not text", "dict": "a list of points"}.get(type(data).__name__)
    try:
        with warnings.catch_warnings():  # (a masked element: said below)
            warnings.simplefilter("ignore")
            scalar = np.ndim(data) == 0 and (columns or not isinstance(data, numbers.Real))
    except ValueError:  # ragged rows: said below
        scalar = False
    if hint or scalar:
        kind = type(data).__name__
        raise InputError(f"{name} must be an array of numbers{f' of shape (n, {columns})' if columns else ''}, got "
                         f"{'an' if kind[0] in 'aeiou' else 'a'} {kind}{f': use {hint}' if hint else ''}")
    try:
        with warnings.catch_warnings(record=True) as caught:  # np.ma.masked in a list: numpy warns, makes it NaN
            warnings.simplefilter("always")
            raw = np.asarray(data)
        if any("masked element" in str(w.message) for w in caught):
            i = int(np.flatnonzero(np.isnan(raw.reshape(len(raw), -1)).any(axis=1))[0])
            raise InputError(say(i, f"masked value: {_short(data[i])}; drop or fill masked entries first"))
        if raw.dtype.kind in "USc" and not isinstance(data, np.ndarray):  # a list with text: find which entry
            raw = np.asarray(data, dtype=object)
    except ValueError as refused:  # rows of different lengths
        if isinstance(refused, InputError):
            raise
        lengths = [np.size(row) if np.ndim(row) else -1 for row in data]
        i = next((i for i, k in enumerate(lengths) if k != (columns or lengths[0])), 0)
        raise InputError(f"{name} must be rows of {columns or lengths[0]} numbers: {what} {i} is {data[i]!r}") from None
    if raw.dtype == object:
        converted = np.frompyfunc(_real_or_why, 1, 1)(raw)
        why = np.frompyfunc(lambda x: isinstance(x, str), 1, 1)(converted).astype(bool)
        if why.any():
            at = tuple(np.argwhere(why)[0]) if why.ndim else ()
            problem = converted[at]
            error = OutOfRangeError if "beyond" in problem else InputError
            raise error(say(at[0] if at else 0, f"value {problem}: {_short(raw[at])}"))
        raw = converted.astype(float)
    elif raw.dtype.kind not in "iuf":
        sample = f": {what} 0 is {_short(raw[0])}" if raw.size else ""
        raise InputError(f"{name} must be real numbers, got {raw.dtype} values{sample}")
    with np.errstate(over="ignore"):
        v = np.array(raw, dtype=float)
    if columns and (v.ndim != 2 or v.shape[1] != columns):
        raise InputError(f"{name} must have shape (n, {columns}), got shape {v.shape}")

    if not finite and raw.dtype.kind == "f" and raw.itemsize <= 8:  # converted exactly: the caller checks
        return v
    with np.errstate(over="ignore", invalid="ignore"):
        if not np.isfinite(np.add.reduce(v, axis=None)):
            fine = np.isfinite(v)
            bad = np.flatnonzero(~(fine if fine.ndim == 1 else fine.all(axis=1)))
            row = int(bad[0]) if len(bad) else None  # None: all finite, only their sum overflowed
            if row is not None and (raw.dtype.kind in "iu" or bool(np.isfinite(raw[row]).all())):  # long double, huge int
                raise OutOfRangeError(say(row, f"value beyond the largest float (about 1.8e308): {raw[row]}"))
            if row is not None:
                raise InputError(say(row, f"NaN or infinite value: {v[row]}"))
    return v


def discrete_function(F, n, name):
    """``F`` as a discrete function on ``n`` vertices, shape ``(n,)`` or ``(n, 2)``, or an ``InputError``."""
    F = values(F, name)
    if F.shape not in ((n,), (n, 2)):
        raise InputError(f"{name} must be a discrete function with one value per vertex, shape ({n},) "
                         f"or ({n}, 2); got shape {F.shape}")
    return F


def points(data, what, finite=True):
    """``data`` as a new float array of shape ``(n, 2)``, checked as :func:`values` checks."""
    return values(data, "vertices", what, columns=2, finite=finite)


def enough(v, closed):
    """``v`` if it has the vertices a closed (3) or open (2) curve needs, else a ``DegenerateCurveError``."""
    if len(v) < (3 if closed else 2):
        raise DegenerateCurveError(f"{'a closed' if closed else 'an open'} discrete curve needs at least "
                                   f"{3 if closed else 2} vertices, got {len(v)}")
    return v


def edges(v, lengths, length, closed, ok):
    """Refuse a curve with a NaN or infinite coordinate (``InputError``), two equal consecutive
    vertices (``DegenerateCurveError``), or an edge or length beyond the largest float
    (``OutOfRangeError``), naming the vertex. ``ok``: every edge length is known to be positive and
    finite (``lengths`` lie in ``_numerics.SAFE``)."""
    if ok and np.isfinite(length):
        return
    points(v, "vertex")  # the check the curve left out (finite=False): a NaN or infinite vertex named
    if lengths.min() == 0.0:
        i = int(np.argmin(lengths))
        if closed and i == len(v) - 1:
            raise DegenerateCurveError(f"the last vertex {i} repeats the first vertex 0 ({v[0]}); a closed curve's "
                                       "closing edge is implied, so leave the repeated vertex out")
        raise DegenerateCurveError(f"vertices {i} and {i + 1} are equal ({v[i]}, as floats); consecutive vertices "
                                   "must differ")
    if not np.isfinite(length):  # an edge, or only their sum
        require_finite(lengths, lambda i: f"the edge from vertex {i} to vertex {(i + 1) % len(v)} is longer than the "
                       "largest float (about 1.8e308): scale the curve down", OutOfRangeError)
        raise OutOfRangeError("the curve's length is beyond the largest float (about 1.8e308): scale it down")


def point(data, name):
    """``data`` as one finite point ``(x, y)``, or an ``InputError``."""
    if np.iscomplexobj(data) or np.shape(data) != (2,):
        raise InputError(f"{name} must be a point (x, y), got {data!r}")
    return values(np.reshape(np.asarray(data, dtype=object), (1, 2)), name, "point", columns=2)[0]
