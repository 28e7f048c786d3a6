"""The numerical guards behind ``ddg``'s formulas, kept apart so that the formulas read plainly.

Nothing here is new mathematics. It is how the lecture's quantities are computed so that they stay
right at any scale (coordinates from ``1e-300`` to ``1e300``), far from the origin, and where a
polygon nearly turns straight back; and how arguments are checked, so that bad input gets a
``ValueError`` that names the problem instead of a NaN. Each function says what it guards against.
"""

import itertools
import math
import numbers

import numpy as np

SAFE = 1e-150, 1e150
"""Edge lengths in this range have squares and pairwise products far from under- and overflow."""

ABOVE_MINUS_PI = np.nextafter(-np.pi, 0.0)
"""The least turning angle: the range is ``(-pi, pi]``."""


# ------------------------------------------------------------------------ checking arguments


def choose(value, valid, what):
    """``value`` if it is one of ``valid``, else a ``ValueError`` listing the choices."""
    if not isinstance(value, str) or value not in valid:
        raise ValueError(f"unknown {what} {value!r}; choose one of {', '.join(map(repr, valid))}")
    return value


def real(value, name, minimum=None, strict=False):
    """``value`` as a finite float, or a ``ValueError`` naming ``name``: no NaN, no arrays, no complex."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise ValueError(f"{name} must be a real number, got {value!r}")
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{name} must be finite, got {value!r}")
    if minimum is not None and (value <= minimum if strict else value < minimum):
        bound = "positive" if strict and minimum == 0 else f"{'>' if strict else '>='} {minimum:g}"
        raise ValueError(f"{name} must be {bound}, got {value!r}")
    return value


def count(value, name, minimum):
    """``value`` as an ``int`` of at least ``minimum``, or a ``ValueError`` (no bools, no floats)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral) or value < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return int(value)


def flag(value, name):
    """``value`` if it is ``True`` or ``False`` (a truthy string such as ``"no"`` is refused)."""
    if not isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} must be True or False, got {value!r}")
    return bool(value)


def require_finite(values, say):
    """Raise ``ValueError(say(i))`` at the first row ``i`` of ``values`` holding a NaN or an infinity."""
    finite = np.isfinite(values)
    bad = np.flatnonzero(~(finite if finite.ndim == 1 else finite.all(axis=1)))
    if len(bad):
        raise ValueError(say(int(bad[0])))


def frozen(array):
    """A read-only copy of ``array`` that cannot be made writable again.

    ``flags.writeable = False`` alone can be undone, and a view's ``base`` is writable; an array
    over an immutable ``bytes`` buffer is neither.
    """
    array = np.ascontiguousarray(array, dtype=float)
    return np.frombuffer(array.tobytes(), dtype=float).reshape(array.shape)


# ------------------------------------------------------------------------- along the curve


def previous(values):
    """``values`` moved one place along a closed curve: entry ``i`` holds ``values[i - 1]``."""
    return np.concatenate((values[-1:], values[:-1]))


def J(u):
    """Rotate each row of ``u`` by +90 degrees: ``J(x, y) = (-y, x)``."""
    return np.stack([-u[:, 1], u[:, 0]], axis=1)


def cross(a, b):
    """z-component of the cross product of rows of ``a`` and ``b`` (counter-clockwise positive)."""
    return a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]


def lengths(vectors):
    """Euclidean lengths of the rows, without under- or overflow at any scale.

    ``sqrt(x*x + y*y)`` is several times cheaper than ``np.hypot``; it is used where every length
    lies in :data:`SAFE`, where its squares can neither under- nor overflow.
    """
    x, y = vectors[:, 0], vectors[:, 1]
    with np.errstate(over="ignore", under="ignore", invalid="ignore"):
        fast = np.sqrt(x * x + y * y)
    if len(fast) and SAFE[0] < fast.min() and fast.max() < SAFE[1]:
        return fast
    return np.hypot(x, y)


def tan_half_turn(a, b):
    """``tan(psi / 2)`` for the clockwise turn ``psi`` from each row of ``a`` to the row of ``b``.

    With ``|a||b| sin psi = -(a x b)`` (clockwise is positive) and ``|a||b| cos psi = a . b``,

        tan(psi/2) = -(a x b) / (|a||b| + a . b) = (|a||b| - a . b) / -(a x b).

    The first form is used where ``a . b >= 0``, the second where the turn exceeds a right angle:
    each avoids cancellation in its half, so the result is accurate even for a turn a rounding error
    away from ``pi``, where ``psi`` itself cannot tell ``pi - 1e-17`` from ``pi``. Where the edges
    point in exactly opposite directions the result is ``+inf`` (``psi = pi``). Both forms are
    homogeneous in ``a`` and in ``b``, so each row is first scaled by a power of two to a length in
    ``[1/2, 1)``: exactly, so the result is the same at every scale, and no product under- or
    overflows, however small the turn's sine.
    """
    la, lb = lengths(a), lengths(b)
    ea, eb = np.frexp(la)[1], np.frexp(lb)[1]
    a, b, la, lb = np.ldexp(a, -ea[:, None]), np.ldexp(b, -eb[:, None]), np.ldexp(la, -ea), np.ldexp(lb, -eb)
    dot = a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1]
    minus_cross = a[:, 1] * b[:, 0] - a[:, 0] * b[:, 1]
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        t = np.where(dot >= 0, minus_cross / (la * lb + dot), (la * lb - dot) / minus_cross)
    t[(dot < 0) & (minus_cross == 0)] = np.inf  # exactly opposite: psi = +pi, whatever the sign of 0
    return t


# -------------------------------------------------------------------------------- the area


def signed_area_ccw(v):
    """``1/2 sum_i v_i x v_{i+1}`` for the closed polygon ``v`` (counter-clockwise positive), accurately.

    The shoelace formula loses everything to cancellation far from the origin, and centring the
    vertices first loses small coordinates next to large ones. Here it is written with edges,
    ``sum_i (x_i - x_{i+1}) (y_i + y_{i+1})``, with ``y`` taken relative to ``y_0``: each term is an
    edge times a distance within the polygon, so on ordinary polygons the rounding is a few units
    of the last place of the area. A bound on the rounding is computed alongside; where it could
    matter (a polygon with one vertex far from the others, a figure-eight of area 0), the sum is
    recomputed exactly from the original coordinates, each product split into two floats that add
    up to it exactly (Dekker's product) and all of them summed exactly (``math.fsum``). Where
    products of coordinates would overflow, the coordinates are first scaled by a power of two,
    which is exact. So the result is the exact area of the polygon given, rounded once, up to under-
    and overflow of the area itself.
    """
    x, y = v[:, 0], v[:, 1] - v[0, 1]
    with np.errstate(over="ignore", invalid="ignore", under="ignore"):
        dx = x - np.concatenate((x[1:], x[:1]))
        ys = np.abs(y) + np.abs(np.concatenate((y[1:], y[:1])))
        twice = float(dx @ (y + np.concatenate((y[1:], y[:1]))))
        bound = (6 + math.log2(len(v))) * np.finfo(float).eps * float(np.abs(dx) @ ys)
        bound += 8 * len(v) * 5e-324  # what rounding costs where the products are subnormal
    if math.isfinite(twice) and math.isfinite(bound) and bound <= 1e-13 * abs(twice):
        return 0.5 * twice
    return _exact_area(v)


def _split(x):
    """Veltkamp's split: ``x = high + low`` with each half fitting in 26 bits (so products are exact)."""
    c = 134217729.0 * x  # 2**27 + 1
    high = c - (c - x)
    return high, x - high


def _two_product(x, y):
    """``(p, e)`` with ``p + e == x * y`` exactly (Dekker), for ``x``, ``y`` of order 1."""
    p = x * y
    (xh, xl), (yh, yl) = _split(x), _split(y)
    e = ((xh * yh - p) + xh * yl + xl * yh) + xl * yl
    return p, e


def _exact_area(v):
    """``1/2 sum_i x_i y_{i+1} - x_{i+1} y_i`` from the original coordinates, exactly (see
    :func:`signed_area_ccw`).

    Each coordinate is split into its mantissa and its power of two (``frexp``); the mantissas'
    products are exact sums of two floats (Dekker), and every term is scaled by one common power of
    two that keeps the largest below ``2**1000``, so that only terms below ``2**-1074`` of it could
    be lost. ``math.fsum`` then adds them all exactly.
    """
    x, y = v[:, 0], v[:, 1]
    x_next, y_next = np.concatenate((x[1:], x[:1])), np.concatenate((y[1:], y[:1]))
    parts, powers = [], []
    for sign, a, b in ((1.0, x, y_next), (-1.0, x_next, y)):
        (ma, ea), (mb, eb) = np.frexp(a), np.frexp(b)
        p, e = _two_product(ma, mb)  # exact: mantissas lie in [0.5, 1)
        parts += [sign * p, sign * e]
        powers += [ea + eb, ea + eb]
    parts, powers = np.concatenate(parts), np.concatenate(powers)
    shift = int(powers[parts != 0].max()) - 1000 if np.any(parts != 0) else 0
    with np.errstate(under="ignore"):
        terms = np.ldexp(parts, powers - shift)
    chunks = (terms[i:i + 65536].tolist() for i in range(0, len(terms), 65536))  # bounded memory
    total = math.fsum(itertools.chain.from_iterable(chunks))
    with np.errstate(over="ignore", under="ignore"):
        return float(np.ldexp(total, shift - 1))  # half the sum: exact
