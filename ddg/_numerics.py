"""The numerical guards behind ``ddg``'s formulas, kept apart so that the formulas read plainly.

Nothing here is new mathematics. It is how the lecture's quantities are computed so that they stay
right at any scale, far from the origin, and where a polygon nearly turns straight back. Each
function says what it guards against. (How arguments are checked is ``ddg/_arguments.py``.)
"""

import itertools
import math

import numpy as np


SAFE = 1e-150, 1e150
"""Edge lengths in this range have squares and pairwise products far from under- and overflow."""

ABOVE_MINUS_PI = np.nextafter(-np.pi, 0.0)
"""The least turning angle: the range is ``(-pi, pi]``."""


# ---------------------------------------------------------------------------- read-only


def frozen(array, dtype=float):
    """``array`` as a read-only array, without a copy.

    ``flags.writeable = False`` alone can be undone; an array over a read-only memory view refuses
    ``flags.writeable = True`` on itself and on its base (numpy asks the view, which says no). The
    memory stays reachable through the view's ``obj`` (itself read-only), for code that goes out of
    its way: a curve guards against mistakes, not against its own user (the checks' sandbox does).
    """
    array = np.ascontiguousarray(array, dtype=dtype)
    base: object = array
    while isinstance(base, np.ndarray):  # the array and what it is a view of: ddg's own, made read-only
        base.flags.writeable = False
        base = base.base
    return np.frombuffer(memoryview(array).toreadonly(), dtype=dtype).reshape(array.shape)


# ------------------------------------------------------------------------- along the curve


def previous(values):
    """``values`` moved one place along a closed curve: entry ``i`` holds ``values[i - 1]``."""
    return np.concatenate((values[-1:], values[:-1]))


BLOCK = 1 << 15
"""Turns per block in :func:`edge_lengths`, :func:`turns` and :func:`curvature`. numpy makes a pass
over its arrays for each operation; over a block of 2^15 vertices (256 kB an array) those passes
stay in the processor's cache, where passes over whole arrays of a million vertices would each go
out to memory."""


def blocks(n):
    """``(start, stop)`` of the consecutive blocks of at most :data:`BLOCK` turns that cover ``range(n)``;
    ``[(0, 0)]`` for none (a two-vertex polyline: one edge, no turn)."""
    return [(start, min(start + BLOCK, n)) for start in range(0, n, BLOCK)] or [(0, 0)]


def _window(v, start, stop, closed):
    """The vertices that the turns ``start .. stop - 1`` and their edges need: turn ``j`` is at vertex
    ``j`` of a closed curve (from ``v[j - 1]``, wrapping around) and at ``j + 1`` of an open one."""
    if not closed:
        return v[start:stop + 2]
    window = v[start - 1:stop + 1] if start else np.concatenate((v[-1:], v[:stop + 1]))
    return window if stop < len(v) else np.concatenate((window, v[:1]))


def _edges(v, start, stop, closed):
    """The ``x`` and ``y`` components of the edges into and out of the turns ``start .. stop - 1``."""
    window = _window(v, start, stop, closed)
    return np.subtract(window[1:, 0], window[:-1, 0]), np.subtract(window[1:, 1], window[:-1, 1])


def edge_lengths(v, closed):
    """``(L, safe)``: the edge lengths laid out for the turns, and whether they all lie in :data:`SAFE`.

    ``L[j]`` and ``L[j + 1]`` are the edges into and out of turn ``j``: every vertex of a closed
    curve, whose closing edge is both ``L[0]`` and ``L[n]``, and the interior vertices of an open
    one. Block by block (:data:`BLOCK`), ``sqrt(x*x + y*y)``, several times cheaper than ``hypot``
    and exact to a rounding error where the squares can neither under- nor overflow; if any length
    falls outside :data:`SAFE`, all of them are ``np.hypot(x, y)``: one formula for every edge.
    """
    m = len(v) if closed else len(v) - 2  # the turns
    L, safe = np.empty(m + 1), True
    with np.errstate(all="ignore"):
        for start, stop in blocks(m):
            window = _window(v, start, stop, closed)
            squares = np.subtract(window[1:], window[:-1])  # the edges, then their components squared
            squares *= squares
            block = np.add(squares[:, 0], squares[:, 1], out=L[start:stop + 1])
            np.sqrt(block, out=block)
            safe &= bool(SAFE[0] < block.min() and block.max() < SAFE[1])
        if not safe:  # squares that under- or overflow (or a length of 0 or beyond the floats: refused)
            for start, stop in blocks(m):
                x, y = _edges(v, start, stop, closed)
                np.hypot(x, y, out=L[start:stop + 1])
            safe = bool(SAFE[0] < L.min() and L.max() < SAFE[1])  # (hypot may round back into SAFE)
    return L, safe


def turns(v, closed, L, safe):
    """``tan(psi / 2)`` at each turn of the curve through ``v``, whose edge lengths ``L`` and
    ``safe`` :func:`edge_lengths` gave; block by block (:data:`BLOCK`) by :func:`tan_half_turn`.

    Within about 7 degrees of a turn straight back, where the cross product of the edges cancels,
    the turn is then recomputed from the vertices themselves (:func:`_exact_tan_half_turn`): there
    ``tan(psi/2)`` is that of the exact turn of the vertices given, to a few units in the last
    place; elsewhere the cross product's rounding moves ``psi`` by at most 4.4e-16 radians and
    ``tan(psi/2)`` by at most 4e-15 of itself near ``pi``. Where the edges point in exactly opposite
    directions the result is ``+inf`` (``psi = pi``).
    """
    t, near = np.empty(len(L) - 1), [np.zeros(0, np.intp)]
    with np.errstate(all="ignore"):  # (underflow in the exact products: below 2^-1000 of an edge)
        for start, stop in blocks(len(t)):
            x, y = _edges(v, start, stop, closed)
            near.append(start + tan_half_turn(x, y, L[start:stop + 1], out=t[start:stop], safe=safe))
        at = np.concatenate(near)
        for start in range(0, len(at), BLOCK):  # in blocks too: the exact sum holds 16 terms a turn
            some = at[start:start + BLOCK]
            t[some] = _exact_tan_half_turn(v, some if closed else some + 1)
    return t


def J(u):
    """Rotate each row of ``u`` by +90 degrees: ``J(x, y) = (-y, x)``."""
    return np.stack([-u[:, 1], u[:, 0]], axis=1)


def unit(vectors, norms):
    """``vectors / norms`` row by row; where a norm lies outside :data:`SAFE`, each row is first scaled
    by a power of two (exactly) to at most 1 and divided by its own norm, so that a subnormal row
    (whose norm has lost bits) still gives a unit vector."""
    if len(norms) and SAFE[0] < norms.min() and norms.max() < SAFE[1]:
        return vectors / norms[:, None]
    scaled = np.ldexp(vectors, -np.frexp(np.abs(vectors).max(axis=1))[1][:, None])
    return scaled / np.hypot(scaled[:, 0], scaled[:, 1])[:, None]


def tan_half_turn(X, Y, L, out, safe=None):
    """``tan(psi / 2)`` for the clockwise turn ``psi`` from each edge to the next, into ``out``;
    returns the indices of the turns within about 7 degrees of ``pi``, for :func:`turns` to compute
    exactly.

    ``X``, ``Y`` are the edges' components and ``L`` their lengths: turn ``j`` is from
    ``a = (X, Y)[j]`` to ``b = (X, Y)[j + 1]``. With ``|a||b| sin psi = -(a x b)`` (clockwise is
    positive) and ``|a||b| cos psi = a . b``,

        tan(psi/2) = -(a x b) / (|a||b| + a . b) = (|a||b| - a . b) / -(a x b).

    The first form is used where ``a . b >= 0``, the second where the turn exceeds a right angle;
    neither cancels in its half but for the cross product, which near a turn straight back is a
    difference of two nearly equal products: those turns, where ``|a x b| < |a||b| / 8`` and
    ``a . b < 0``, are returned. Unless ``safe`` (every length lies in :data:`SAFE`; ``None``: look),
    each row is first scaled by a power of two (exactly), so that no product under- or overflows.
    (Where every length lies in ``SAFE`` a product of two components can still underflow, if one
    component is far smaller than its edge: then the turn differs from the same turn scaled by
    2^k in its last bits, far within the bound :func:`turns` gives.)
    """
    ax, ay, bx, by, la, lb = X[:-1], Y[:-1], X[1:], Y[1:], L[:-1], L[1:]
    if not (safe if safe is not None else len(L) and SAFE[0] < L.min() and L.max() < SAFE[1]):
        ea, eb = np.frexp(la)[1], np.frexp(lb)[1]
        ax, ay, la = np.ldexp(ax, -ea), np.ldexp(ay, -ea), np.ldexp(la, -ea)
        bx, by, lb = np.ldexp(bx, -eb), np.ldexp(by, -eb), np.ldexp(lb, -eb)
    dot = ax * bx
    dot += ay * by
    minus_cross = ay * bx
    minus_cross -= ax * by
    ll = la * lb
    t = np.add(ll, dot, out=out)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        np.divide(minus_cross, t, out=t)  # right where a . b >= 0: most turns
        wide = np.flatnonzero(dot < 0) if len(dot) and dot.min() < 0 else np.zeros(0, np.intp)
        t[wide] = (ll[wide] - dot[wide]) / minus_cross[wide]
    return wide[8 * np.abs(minus_cross[wide]) < ll[wide]]  # within about 7 degrees of a turn straight back


def sin_half(t, out=None):
    """``sin(psi / 2)`` from ``t = tan(psi / 2)``: ``t / sqrt(1 + t^2)``, and ``sign(t)`` where
    ``|t| > 1e150`` (there ``1 / sqrt(1 + 1 / t^2)`` is 1 to double precision); into ``out`` if given."""
    with np.errstate(over="ignore", invalid="ignore"):
        s = t * t
        big = np.flatnonzero(s > 1e300) if len(s) and s.max() > 1e300 else np.zeros(0, np.intp)  # |t| > 1e150
        s += 1.0
        np.sqrt(s, out=s)
        s = np.divide(t, s, out=s if out is None else out)
    s[big] = np.sign(t[big])
    return s


HALF_TURN = {"angle": lambda t, out: np.maximum(np.arctan(t, out=out), ABOVE_MINUS_PI / 2, out=out),
             "sine": sin_half, "tangent": lambda t, out: t}
"""``psi/2``, ``sin(psi/2)`` and ``tan(psi/2)`` from ``t = tan(psi/2)``: the first two written into
``out``, the last ``t`` itself. ``psi/2`` is kept just above ``-pi/2``, so that ``psi`` lies in ``(-pi, pi]``."""


def curvature(kind, t, L):
    """The curvature ``kind`` at each turn from ``t = tan(psi / 2)`` and the edge lengths ``L``, laid
    out as :func:`edge_lengths` gives them: ``HALF_TURN[kind](t) / (A / 2)``, ``A / 2 = (L[j] + L[j + 1]) / 4``.
    This is ``psi / A``, ``2 sin(psi/2) / A`` or ``2 tan(psi/2) / A`` (eqs. 1, 3, 4), to the last
    bit wherever ``A / 2`` and the edges' halves are normal floats (above 2.2e-308), as halving is
    exact there; ``L[j] + L[j + 1]`` cannot overflow (the curve's length is finite) and no ``2 psi``,
    ``2 sin`` or ``2 tan`` is formed that could. Block by block, as :func:`turns`. Returns
    ``(k, finite)``: ``finite`` is False if an entry may not be (a block's sum is not finite)."""
    k, finite = np.empty(len(t)), True
    with np.errstate(over="ignore", invalid="ignore", under="ignore", divide="ignore"):
        for start, stop in blocks(len(t)):
            half_A = np.add(L[start:stop], L[start + 1:stop + 1])
            half_A *= 0.25
            block = np.divide(HALF_TURN[kind](t[start:stop], out=k[start:stop]), half_A, out=k[start:stop])
            finite &= bool(np.isfinite(np.add.reduce(block)))
    return k, finite


def _exact_tan_half_turn(v, at):
    """``tan(psi / 2)`` at the vertices ``at`` of ``v``, its cross product exact (see :func:`turns`)."""
    n = len(v)
    p, q, r = v[(at - 1) % n], v[at], v[(at + 1) % n]
    a, da = _two_difference(q, p)  # the edges: a + da = q - p and b + db = r - q exactly
    b, db = _two_difference(r, q)
    for edge in ((a, da), (b, db)):  # each edge scaled by a power of two to at most 1: no product under-
        scale = -np.frexp(np.abs(edge[0]).max(axis=1))[1][:, None]  # or overflows (but errors below 2^-1000
        edge[0][:], edge[1][:] = np.ldexp(edge[0], scale), np.ldexp(edge[1], scale)  # of an edge's size)
    terms = [term for (x, dx), (y, dy), sign in (((a[:, 1], da[:, 1]), (b[:, 0], db[:, 0]), 1.0),
                                                 ((a[:, 0], da[:, 0]), (b[:, 1], db[:, 1]), -1.0))
             for u in (x, dx) for w in (y, dy) for term in _two_product(sign * u, w)]
    minus_cross = exact_sum(np.stack(terms, axis=1))
    la, lb = np.hypot(a[:, 0], a[:, 1]), np.hypot(b[:, 0], b[:, 1])
    dot = a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1]
    with np.errstate(divide="ignore", over="ignore"):
        t = (la * lb - dot) / minus_cross
    t = np.clip(t, -np.finfo(float).max, np.finfo(float).max)  # beyond the floats, but not a reversal
    t[minus_cross == 0] = np.inf  # exactly opposite: psi = +pi, whatever the sign of 0
    return t


def _two_difference(x, y):
    """``(d, e)`` with ``d + e == x - y`` exactly (Knuth's two-sum)."""
    d = x - y
    z = d - x
    return d, (x - (d - z)) - (y + z)


def exact_sum(terms):
    """The sum of each row of ``terms``, to the float nearest (ties aside), and its exact sign.

    Repeated passes of error-free additions (Ogita, Rump and Oishi's cascade) move the rounding
    errors of each partial sum to the right until none is left; the last entry then holds the sum.
    """
    terms = terms.copy()
    for _ in range(4 * terms.shape[1] + 8):  # converges well within this; each pass is exact
        before = terms.copy()
        for j in range(1, terms.shape[1]):
            s = terms[:, j - 1] + terms[:, j]
            z = s - terms[:, j - 1]
            terms[:, j - 1] = (terms[:, j - 1] - (s - z)) + (terms[:, j] - z)
            terms[:, j] = s
        if np.array_equal(before, terms):
            break
    return terms[:, -1]


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
    which is exact. So the result is within 1e-13 of the exact area of the polygon given (and is
    that area rounded once wherever the bound could exceed that), up to under- and overflow of the
    area itself.
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
    values, exponents = np.concatenate(parts), np.concatenate(powers)
    shift = int(exponents[values != 0].max()) - 1000 if np.any(values != 0) else 0
    with np.errstate(under="ignore"):
        terms = np.ldexp(values, exponents - shift)
    chunks = (terms[i:i + 65536].tolist() for i in range(0, len(terms), 65536))  # bounded memory
    total = math.fsum(itertools.chain.from_iterable(chunks))
    with np.errstate(over="ignore", under="ignore"):
        return float(np.ldexp(total, shift - 1))  # half the sum: exact
