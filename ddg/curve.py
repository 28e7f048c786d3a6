"""Discrete plane curves, following §3 of the lecture (Vouga, *Plane Curves*).

Conventions (the lecture's, see the book's chapter on notation):

* ``J`` rotates by +90 degrees: ``J(x, y) = (-y, x)``; normals are ``N = J T``.
* A curve traversed **clockwise** has positive curvature and outward normals.
* ``edges[i]`` is ``e_{i+1/2} = v_{i+1} - v_i``; for a closed curve indices are taken modulo ``n``.
* ``turning_angles[i]`` is ``psi_i``, the clockwise turning angle from ``e_{i-1/2}`` to
  ``e_{i+1/2}``, in ``(-pi, pi]``.

Every quantity is computed once, on first use, with vectorized numpy (no loop over vertices).
"""

from __future__ import annotations

import numbers
from functools import cached_property

import numpy as np

CURVATURES = ("angle", "sine", "tangent")
"""The three discrete curvatures of the lecture: equations (1), (3) and (4)."""

INFLATIONS = ("minkowski", "offset")
"""The lecture's two inflations (§3.4): disk sectors at the vertices, or parallel edges with kites."""

MAX_ARC_STEP = 0.01
"""Largest angle (radians) between two samples of a Minkowski arc in :meth:`DiscreteCurve.inflate`.

A chord of angle ``h`` misses ``eps**2 (h - sin h) / 2 <= eps**2 h**3 / 12`` of its sector, a fraction
``h**2 / 6`` (less than 2e-5 at this step) of the area the formula counts."""

MAX_ARC_POINTS = 1_000_000
"""Most points :meth:`DiscreteCurve.inflate` places inside all the Minkowski arcs together.

Beyond it the arc step grows to ``sum |psi_i| / MAX_ARC_POINTS``: a curve with ``10**5`` sharp corners
gets about 10 points per corner (area error below 2% of the sectors' area) instead of 300 (3 GB)."""

_ABOVE_MINUS_PI = np.nextafter(-np.pi, 0.0)
"""The least turning angle: the range is ``(-pi, pi]``."""

_SAFE = 1e-150, 1e150
"""Edge lengths in this range have squares and pairwise products far from under- and overflow."""


def _choose(value, valid, what):
    if value not in valid:
        raise ValueError(f"unknown {what} {value!r}; choose one of {', '.join(map(repr, valid))}")
    return value


def _real(value, name, minimum=None, strict=False):
    """``value`` as a finite float, or a ``ValueError`` naming ``name``: no NaN, no arrays, no complex."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ValueError(f"{name} must be a real number, got {value!r}")
    value = float(value)
    if not np.isfinite(value):
        raise ValueError(f"{name} must be finite, got {value!r}")
    if minimum is not None and (value <= minimum if strict else value < minimum):
        bound = "positive" if strict and minimum == 0 else f"{'>' if strict else '>='} {minimum:g}"
        raise ValueError(f"{name} must be {bound}, got {value!r}")
    return value


def _cross(a, b):
    """z-component of the cross product of rows of ``a`` and ``b`` (counter-clockwise positive)."""
    return a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]


def _dot(a, b):
    return a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1]


def _previous(values):
    """``values`` moved one place along a closed curve: entry ``i`` holds ``values[i - 1]``.

    The same as ``np.roll(values, 1, axis=0)``, several times cheaper on short arrays (the flow
    needs it at every step).
    """
    return np.concatenate((values[-1:], values[:-1]))


def _J(u):
    """Rotate each row of ``u`` by +90 degrees: ``J(x, y) = (-y, x)``."""
    return np.stack([-u[:, 1], u[:, 0]], axis=1)


class DiscreteCurve:
    """A discrete curve ``Gamma = (v_0, ..., v_{n-1})`` (lecture §3).

    Parameters
    ----------
    vertices : array-like of shape ``(n, 2)``
        The vertices ``v_i``. The curve keeps its own read-only float copy.
    closed : bool
        ``True`` (default): the edge ``e_{n-1/2}`` from the last vertex back to the first is
        implied, so do not repeat the first vertex at the end. ``False``: an open polyline; the
        turning angle (hence every curvature) is defined only at the interior vertices
        ``v_1 ... v_{n-2}``, and the quantities that need a closed curve (turning number, area,
        inflation) raise ``ValueError``.

    Raises
    ------
    ValueError
        For a shape other than ``(n, 2)``, coordinates that are not real numbers (complex, text),
        NaN or infinite coordinates, too few vertices, or two consecutive equal vertices (the
        lecture requires ``v_{i+1} != v_i``). The message names the vertex.

    Any scale works, from ``1e-300`` to ``1e300``: lengths, angles, curvatures and areas are
    computed without under- or overflow. (An area beyond the largest float raises ``ValueError``;
    one below the smallest, as for a curve of size ``1e-170``, rounds to 0.)
    """

    def __init__(self, vertices, closed=True):
        if not isinstance(closed, (bool, np.bool_)):
            raise ValueError(f"closed must be True or False, got {closed!r}")
        raw = np.asarray(vertices)
        if raw.dtype.kind not in "iufO":
            raise ValueError(f"vertices must be real numbers, got {raw.dtype} values (e.g. {raw.flat[0]!r})")
        try:
            v = np.array(raw, dtype=float, copy=True)
        except TypeError as problem:  # an object array holding complex numbers or text
            raise ValueError(f"vertices must be real numbers: {problem}") from None
        if v.ndim != 2 or v.shape[1] != 2:
            raise ValueError(f"vertices must have shape (n, 2), got shape {v.shape}")
        self.closed = bool(closed)
        n = len(v)
        minimum = 3 if self.closed else 2
        if n < minimum:
            kind = "a closed" if self.closed else "an open"
            raise ValueError(f"{kind} discrete curve needs at least {minimum} vertices, got {n}")
        v.flags.writeable = False
        self._v = v
        if self._edge_buffers[3]:  # every edge length in _SAFE: finite, nonzero, no overflow
            return
        lengths = self.edge_lengths
        if not np.isfinite(self.length):  # a NaN or inf coordinate reaches the length: locate it
            bad = np.flatnonzero(~np.isfinite(v).all(axis=1))
            if len(bad):
                raise ValueError(f"vertex {bad[0]} has a NaN or infinite coordinate: {v[bad[0]]}")
            raise ValueError("the coordinates are too large: the curve's length overflows")
        if lengths.min() == 0.0:
            i = int(np.argmin(lengths))
            j = (i + 1) % n
            if self.closed and i == n - 1:
                raise ValueError(
                    f"the last vertex {i} repeats the first vertex 0 ({v[0]}); a closed curve's "
                    "closing edge is implied, so leave the repeated vertex out"
                )
            raise ValueError(
                f"vertices {i} and {j} are equal ({v[i]}); consecutive vertices must differ"
            )

    def __len__(self):
        return len(self._v)

    def __repr__(self):
        kind = "closed" if self.closed else "open"
        return f"DiscreteCurve(n={len(self)}, {kind}, length={self.length:.6g})"

    def _require_closed(self, what):
        if not self.closed:
            raise ValueError(f"{what} is defined for closed curves only; this curve is open")

    # ------------------------------------------------------------------ edges (lecture §3)

    @property
    def vertices(self):
        """The vertices ``v_i``, shape ``(n, 2)``, read-only."""
        return self._v

    @cached_property
    def _edge_buffers(self):
        """Edge components and lengths ``(ex, ey, l, safe)``, the first three contiguous arrays.

        For a closed curve each buffer has ``n + 1`` entries, the last edge ``e_{n-1/2}`` repeated in
        front, so that around vertex ``v_i`` the previous edge is ``buffer[i]`` and the next is
        ``buffer[i + 1]`` for every ``i``: ``buffer[:-1]`` and ``buffer[1:]`` are the two edges
        at each vertex, without copies. An open curve's buffers hold its ``n - 1`` edges.

        ``safe`` says whether every length lies in ``_SAFE``, so that products of two lengths can
        neither under- nor overflow. Where it does not, ``sqrt(x*x + y*y)`` may have under- or
        overflowed too, and the lengths are recomputed with ``np.hypot``, which cannot.
        """
        v = self._v
        w = 1 if self.closed else 0
        ex, ey = np.empty(len(v) - 1 + 2 * w), np.empty(len(v) - 1 + 2 * w)
        for out, column in ((ex, v[:, 0]), (ey, v[:, 1])):
            np.subtract(column[1:], column[:-1], out=out[w : len(v) - 1 + w])
            if self.closed:
                out[0] = out[-1] = column[0] - column[-1]
        with np.errstate(over="ignore", under="ignore"):
            length = ex * ex
            length += ey * ey
        np.sqrt(length, out=length)  # sqrt(x*x + y*y): several times cheaper than np.hypot
        safe = bool(_SAFE[0] < length.min() and length.max() < _SAFE[1])
        if not safe:  # extreme scales (or a NaN): the squares may have under- or overflowed
            np.hypot(ex, ey, out=length)
        return ex, ey, length, safe

    @cached_property
    def edges(self):
        """Edge vectors: ``edges[i] = e_{i+1/2} = v_{i+1} - v_i``; ``n`` of them if closed, else ``n-1``."""
        ex, ey, _, _ = self._edge_buffers
        w = 1 if self.closed else 0
        e = np.stack([ex[w:], ey[w:]], axis=1)
        e.flags.writeable = False
        return e

    @cached_property
    def edge_lengths(self):
        """``|e_{i+1/2}|`` for each edge."""
        lengths = self._edge_buffers[2][1:] if self.closed else self._edge_buffers[2].copy()
        lengths.flags.writeable = False
        return lengths

    @cached_property
    def length(self):
        """Total arc length ``L = sum_i |e_{i+1/2}|`` (lecture §3)."""
        return float(self.edge_lengths.sum())

    @cached_property
    def tangents(self):
        """Unit edge tangents ``T_{i+1/2} = e_{i+1/2} / |e_{i+1/2}|``."""
        return self.edges / self.edge_lengths[:, None]

    @cached_property
    def normals(self):
        """Edge normals ``N_{i+1/2} = J T_{i+1/2}``: outward on a clockwise convex curve."""
        return _J(self.tangents)

    @cached_property
    def bisector_normals(self):
        """``N_i``: unit bisector of the edge normals ``N_{i-1/2}`` and ``N_{i+1/2}`` at each vertex.

        It is the direction of the gradient of length (lecture §3.3): ``(grad L)_i = k_i^sine N_i``
        (eq. 3). Computed as ``N_{i-1/2}`` turned clockwise by ``psi_i / 2``,
        ``cos(psi_i/2) N_{i-1/2} + sin(psi_i/2) T_{i-1/2}`` (cosine and sine from ``tan(psi_i/2)``),
        which stays accurate where the two normals nearly cancel. Where the curve turns straight
        back (``psi_i = pi``, the normals cancel exactly) this gives ``N_i = T_{i-1/2}``: the limit of
        the bisector as ``psi -> pi``, and the direction of ``grad L = 2 T_{i-1/2} / A_i`` there, so
        eq. (3) still holds. Closed curve: every vertex; open curve: the interior vertices.
        """
        N_prev, _ = self._around_vertices(self.normals)
        T_prev, _ = self._around_vertices(self.tangents)
        t, steep = self._tan_half_psi, self._steep
        with np.errstate(over="ignore", invalid="ignore"):  # steep turns: fixed next
            cos = 1.0 / np.sqrt(1.0 + t * t)
            sin = t * cos
        sin[steep], cos[steep] = np.sign(t[steep]), 1.0 / np.abs(t[steep])
        return cos[:, None] * N_prev + sin[:, None] * T_prev

    # ---------------------------------------------------------- vertices (lecture §3.1-3.2)

    def _around_vertices(self, values):
        """``(previous, next)`` edge values around each vertex where ``psi`` is defined."""
        if self.closed:
            return _previous(values), values
        return values[:-1], values[1:]

    @cached_property
    def _tan_half_psi(self):
        """``tan(psi_i / 2)`` from the cross and dot products of the two edges at ``v_i``.

        With ``a = e_{i-1/2}``, ``b = e_{i+1/2}``: ``|a||b| sin psi = -(a x b)`` (clockwise is
        positive) and ``|a||b| cos psi = a . b``, so, trig-free,

            tan(psi/2) = -(a x b) / (|a||b| + a . b) = (|a||b| - a . b) / -(a x b).

        The first form is used where ``a . b >= 0`` and the second where the curve turns by more
        than a right angle (each avoids cancellation in its half). ``psi = 2 arctan(tan(psi/2))``
        then lies in ``(-pi, pi]``; where the curve turns straight back this is ``+inf`` (``psi = pi``).
        Both forms are homogeneous in ``a`` and in ``b`` separately, so at extreme scales (see
        ``_edge_buffers``) unit edges are used instead: their products cannot under- or overflow.
        """
        ex, ey, length, safe = self._edge_buffers
        if not safe:
            ex, ey, length = ex / length, ey / length, np.ones_like(length)
        a, b = slice(None, -1), slice(1, None)  # previous and next edge at each vertex
        dot = ex[a] * ex[b]
        scratch = ey[a] * ey[b]  # one temporary, reused: fewer passes over fresh memory
        dot += scratch
        t = ey[a] * ex[b]
        t -= np.multiply(ex[a], ey[b], out=scratch)  # t = -(a x b)
        denominator = np.multiply(length[a], length[b], out=scratch)
        denominator += dot
        with np.errstate(divide="ignore", invalid="ignore"):  # 0 only where the second form applies
            t /= denominator
        if len(t) and dot.min() < 0.0:  # sharp turns: use the second form there
            i = np.flatnonzero(dot < 0.0)
            minus_cross = ey[a][i] * ex[b][i] - ex[a][i] * ey[b][i]
            with np.errstate(divide="ignore", over="ignore"):
                t[i] = (length[a][i] * length[b][i] - dot[i]) / minus_cross
            t[i[minus_cross == 0.0]] = np.inf  # a reversal: psi = +pi, whatever the sign of zero
        return t

    @cached_property
    def _steep(self):
        """Indices, into the per-vertex arrays, where ``|tan(psi_i/2)| > 1e150``: near or at a reversal.

        There ``tan^2`` overflows, and ``sin(psi_i/2) = +-1`` to double precision.
        """
        t = self._tan_half_psi
        if len(t) == 0 or -1e150 <= t.min() and t.max() <= 1e150:  # two cheap passes in the usual case
            return np.array([], dtype=int)
        return np.flatnonzero(np.abs(t) > 1e150)

    @cached_property
    def _reversals(self):
        """Indices, into the per-vertex arrays, of the vertices where the curve turns straight back."""
        return self._steep[np.isposinf(self._tan_half_psi[self._steep])]

    def _vertex_index(self, j):
        """The vertex that entry ``j`` of a per-vertex array belongs to (open curves skip ``v_0``)."""
        return int(j) + (0 if self.closed else 1)

    @cached_property
    def turning_angles(self):
        """``psi_i``: clockwise turning angle at ``v_i`` from ``e_{i-1/2}`` to ``e_{i+1/2}``, in ``(-pi, pi]``.

        Closed curve: one per vertex. Open curve: interior vertices only, so ``turning_angles[j]``
        belongs to ``v_{j+1}``.
        """
        psi = np.arctan(self._tan_half_psi)
        psi *= 2.0
        # a clockwise turn of nearly -pi whose sign is known (the edges are not exactly opposite)
        # may round to -pi, outside the range: it is kept just inside
        np.maximum(psi, _ABOVE_MINUS_PI, out=psi)
        psi.flags.writeable = False
        return psi

    @cached_property
    def dual_lengths(self):
        """``A_i = (|e_{i-1/2}| + |e_{i+1/2}|) / 2``, the length element at ``v_i`` (lecture §3).

        On an open curve the end vertices get half of their single edge, so that ``<1, 1> = L``.
        """
        length = self._edge_buffers[2]
        if self.closed:
            A = length[:-1] + length[1:]
        else:
            A = np.zeros(len(self))
            A[1:] += length
            A[:-1] += length
        A *= 0.5
        A.flags.writeable = False
        return A

    @cached_property
    def turning_number(self):
        """``sum_i psi_i / (2 pi)``, an integer for every closed polygon (lecture §3.2).

        A curve that turns straight back somewhere (``psi_i = pi``: its two edges point in exactly
        opposite directions) has no turning number: counting that turn as ``+pi``, as the range
        ``(-pi, pi]`` does, would make a reflection keep the count instead of negating it. It
        raises ``ValueError`` naming the vertex; ``turning_angles.sum() / (2 pi)`` gives the count
        under the book's convention.
        """
        self._require_closed("the turning number")
        if len(self._reversals):
            raise ValueError(
                f"the turning number is not defined: the curve turns straight back at vertex "
                f"{self._vertex_index(self._reversals[0])} (its two edges, as computed, point in "
                "exactly opposite directions), where a turn of +pi and one of -pi are equally right"
            )
        return int(round(float(self.turning_angles.sum()) / (2 * np.pi)))

    @cached_property
    def signed_area(self):
        """Enclosed area, positive for a clockwise curve (the shoelace formula, sign flipped).

        For a self-intersecting curve this is the winding-number-weighted area. The vertices are
        first scaled by a power of two (exact) to coordinates of order 1, then centred (which
        avoids cancellation far from the origin), so the products cannot under- or overflow.
        """
        self._require_closed("the enclosed area")
        exponent = min(max(int(np.frexp(np.abs(self._v).max())[1]), -1000), 1000)
        v = np.ldexp(self._v, -exponent)  # exact: the largest coordinate is now between 1/2 and 1
        v -= v.mean(axis=0)
        area = -0.5 * _cross(_previous(v), v).sum()  # the sum of v_{i-1} x v_i
        with np.errstate(over="ignore"):
            area = float(np.ldexp(area, 2 * exponent))
        if not np.isfinite(area):
            raise ValueError("the enclosed area is larger than the largest float (about 1.8e308); scale the curve down")
        return area

    def inner(self, F, G):
        """Discrete inner product ``<F, G> = sum_i A_i F_i . G_i`` (lecture §3 and §3.3).

        ``F`` and ``G`` are discrete functions: shape ``(n,)`` (scalar) or ``(n, 2)`` (vector).
        """
        if np.iscomplexobj(F) or np.iscomplexobj(G):
            raise ValueError("F and G must be real discrete functions, got complex values")
        F, G = np.asarray(F, dtype=float), np.asarray(G, dtype=float)
        n = len(self)
        for name, X in (("F", F), ("G", G)):
            if X.shape not in ((n,), (n, 2)):
                raise ValueError(
                    f"{name} must be a discrete function with one value per vertex, shape ({n},) "
                    f"or ({n}, 2); got shape {X.shape}"
                )
        if F.shape != G.shape:
            raise ValueError(f"F and G must both be scalar or both vector: shapes {F.shape}, {G.shape}")
        products = F * G if F.ndim == 1 else _dot(F, G)
        return float(self.dual_lengths @ products)

    # ------------------------------------------------------- curvature (lecture §3.2-3.4)

    @cached_property
    def _tangent_curvature(self):
        """``2 tan(psi_i / 2) / A_i`` (eq. 4), ``inf`` where the curve turns straight back."""
        k = self._tan_half_psi / (self.dual_lengths if self.closed else self.dual_lengths[1:-1])
        k *= 2.0
        return k

    def curvature(self, kind="angle"):
        """Discrete curvature ``k_i`` by one of the lecture's formulas (``ddg.CURVATURES``).

        With ``2 A_i = |e_{i-1/2}| + |e_{i+1/2}|``:

        * ``"angle"``:   ``k_i = 2 psi_i / (2 A_i)``          (eq. 1, from the winding number theorem)
        * ``"sine"``:    ``k_i = 4 sin(psi_i/2) / (2 A_i)``   (eq. 3, from the gradient of length)
        * ``"tangent"``: ``k_i = 4 tan(psi_i/2) / (2 A_i)``   (eq. 4, from offset inflation)

        The tangent formula diverges where the curve turns straight back (``psi_i = pi``); there it
        raises ``ValueError`` naming the vertex, as does any curvature too large for a float.
        Open curves: interior vertices ``v_1 ... v_{n-2}``.
        """
        _choose(kind, CURVATURES, "curvature kind")
        cache = self.__dict__.setdefault("_curvatures", {})
        if kind in cache:
            return cache[kind]
        t, steep = self._tan_half_psi, self._steep
        A = self.dual_lengths if self.closed else self.dual_lengths[1:-1]
        if kind == "tangent" and len(self._reversals):
            raise ValueError(
                f"the tangent curvature (eq. 4) diverges at vertex "
                f"{self._vertex_index(self._reversals[0])}: the curve turns straight back there (psi = pi)"
            )
        if kind == "angle":
            k = self.turning_angles / A
        elif kind == "tangent":
            k = self._tangent_curvature
        else:  # sin(psi/2) = tan(psi/2) / sqrt(1 + tan^2(psi/2)): the tangent formula, rescaled
            with np.errstate(over="ignore", invalid="ignore"):  # steep turns overflow: fixed next
                k = t * t
                k += 1.0
                np.sqrt(k, out=k)
                np.divide(self._tangent_curvature, k, out=k)
            if len(steep) or not self._edge_buffers[3]:  # there sin(psi/2) = 1 / sqrt(1 + 1/tan^2)
                i = np.union1d(steep, np.flatnonzero(~np.isfinite(k)))
                with np.errstate(divide="ignore", over="ignore"):
                    k[i] = 2.0 * np.sign(t[i]) / np.sqrt(1.0 + (1.0 / t[i]) ** 2) / A[i]
        if len(steep) or not self._edge_buffers[3]:  # extreme input: check for overflow
            bad = np.flatnonzero(~np.isfinite(k))
            if len(bad):
                raise ValueError(
                    f"the {kind} curvature at vertex {self._vertex_index(bad[0])} is beyond the largest float "
                    f"(a turn of {np.degrees(self.turning_angles[bad[0]]):.6g} degrees between edges "
                    f"{A[bad[0]]:.3g} long on average)"
                )
        k.flags.writeable = False
        cache[kind] = k
        return k

    def total_curvature(self, kind="angle"):
        """``<k, 1> = sum_i A_i k_i`` over the vertices where ``k`` is defined."""
        A = self.dual_lengths if self.closed else self.dual_lengths[1:-1]
        return float(A @ self.curvature(kind))

    def length_gradient(self):
        """Gradient of length under the discrete inner product, shape ``(n, 2)`` (lecture §3.3).

        ``(grad L)_j = (T_{j-1/2} - T_{j+1/2}) / A_j``, so that ``<grad L, delta> = D_delta L``
        (eq. 2) for every variation ``delta``. Its length is the sine curvature (eq. 3). On an open
        curve the end vertices have a single edge: ``(grad L)_0 = -T_{1/2} / A_0`` and
        ``(grad L)_{n-1} = T_{n-3/2} / A_{n-1}``.
        """
        T = self.tangents
        if self.closed:
            g = _previous(T) - T
        else:
            g = np.zeros((len(self), 2))
            g[1:] += T
            g[:-1] -= T
        return g / self.dual_lengths[:, None]

    def laplacian(self, F):
        """The discrete Laplacian of ``F`` on a closed curve (the book's chapter 4):

        ``(Lap F)_i = ((F_{i+1} - F_i) / |e_{i+1/2}| - (F_i - F_{i-1}) / |e_{i-1/2}|) / A_i``.

        ``F`` is a discrete function, shape ``(n,)`` or ``(n, 2)``. This is the piecewise-linear
        finite-element Laplacian with the dual lengths as masses, the one-dimensional case of the
        cotan Laplacian. It is symmetric for ``<.,.>``, ``<Lap F, F> <= 0``, and on the vertices
        it is minus the gradient of length: ``laplacian(vertices) == -length_gradient()``.
        """
        self._require_closed("the Laplacian")
        if np.iscomplexobj(F):
            raise ValueError("F must be a real discrete function, got complex values")
        F = np.asarray(F, dtype=float)
        n = len(self)
        if F.shape not in ((n,), (n, 2)):
            raise ValueError(f"F must have one value per vertex, shape ({n},) or ({n}, 2); got shape {F.shape}")
        lengths = self.edge_lengths if F.ndim == 1 else self.edge_lengths[:, None]
        flux = (np.roll(F, -1, axis=0) - F) / lengths  # (F_{i+1} - F_i) / |e_{i+1/2}|
        A = self.dual_lengths if F.ndim == 1 else self.dual_lengths[:, None]
        return (flux - _previous(flux)) / A

    # -------------------------------------------------------------- inflation (lecture §3.4)

    def inflated_area(self, eps, method="minkowski"):
        """Signed area of the curve inflated by ``eps >= 0`` along its normals (lecture §3.4).

        * ``"minkowski"``: disk sectors of angle ``psi_i`` at the vertices:
          ``A_0 + eps L + eps^2 / 2 * sum psi_i``.
        * ``"offset"``: edges moved parallel by ``eps``, kites at the corners:
          ``A_0 + eps L + eps^2 * sum tan(psi_i / 2)``.

        These are the lecture's formulas; they are the true area of the inflated region when the
        polygon is convex and clockwise. (For other curves, compare with :meth:`inflate`.)
        ``eps < 0`` (erosion) raises ``ValueError``: the formulas hold only until an edge
        collapses. Inflating the reversed curve moves the edges the other way. An area beyond the
        largest float raises ``ValueError`` too.
        """
        _choose(method, INFLATIONS, "inflation method")
        self._require_closed("inflation")
        eps = _epsilon(eps)
        if eps == 0.0:
            return self.signed_area
        if method == "minkowski":
            quadratic = 0.5 * float(self.turning_angles.sum())
        else:
            quadratic = 0.5 * self.total_curvature("tangent")
        with np.errstate(over="ignore", invalid="ignore"):
            area = self.signed_area + eps * self.length + eps * eps * quadratic
        if not np.isfinite(area):
            raise ValueError("the inflated area is larger than the largest float (about 1.8e308); "
                             "scale the curve or eps down")
        return area

    def inflate(self, eps, method="minkowski"):
        """The boundary of the inflated region as a new closed :class:`DiscreteCurve`.

        Every edge moves by ``eps >= 0`` along its normal ``N_{i+1/2}``. At vertex ``v_i`` the two
        moved edges are joined by

        * ``"minkowski"``: the arc of radius ``eps`` about ``v_i`` that turns clockwise by
          ``psi_i``, cut into equal chords of angle at most ``h = max(MAX_ARC_STEP,
          sum |psi_i| / MAX_ARC_POINTS)``: at most ``pi / h + 1`` points per vertex and
          ``2 n + MAX_ARC_POINTS`` in all. Each chord of angle ``h'`` misses
          ``eps^2 (h' - sin h') / 2`` of its sector, so the boundary's signed area differs from
          :meth:`inflated_area` by at most ``eps^2 h^2 sum |psi_i| / 12``, a fraction ``h^2 / 6``
          of the sectors' area (below 2e-5 at the default step);
        * ``"offset"``: the corner where the two moved edges meet (the kite's outer vertex).

        ``eps = 0`` returns the curve itself. Points that coincide (an arc of zero angle, or an
        offset edge that shrinks to a point) are kept once: the area is unchanged. On a non-convex
        curve this boundary crosses itself near the reflex vertices.
        """
        _choose(method, INFLATIONS, "inflation method")
        self._require_closed("inflation")
        eps = _epsilon(eps)
        if eps == 0.0:
            return self
        v, psi = self._v, self.turning_angles
        N_prev, _ = self._around_vertices(self.normals)
        if method == "offset":  # the moved edges meet at v + eps (N_{i-1/2} + tan(psi_i/2) T_{i-1/2})
            if len(self._reversals):
                i = self._reversals[0]
                raise ValueError(f"no offset corner at vertex {i}: the curve turns straight back there")
            T_prev, _ = self._around_vertices(self.tangents)
            with np.errstate(over="ignore"):  # _boundary reports it
                return _boundary(v + eps * (N_prev + self._tan_half_psi[:, None] * T_prev), np.arange(len(v)), eps)
        h = max(MAX_ARC_STEP, float(np.abs(psi).sum()) / MAX_ARC_POINTS)
        steps = np.ceil(np.abs(psi) / h).astype(int)  # arc segments per vertex
        counts = steps + 1  # points per arc (one where psi = 0)
        vertex = np.repeat(np.arange(len(v)), counts)
        start = np.cumsum(counts) - counts
        k = np.arange(counts.sum()) - np.repeat(start, counts)  # 0 ... steps_i along each arc
        fraction = k / np.maximum(np.repeat(steps, counts), 1)
        angle = np.arctan2(N_prev[:, 1], N_prev[:, 0])[vertex] - psi[vertex] * fraction
        with np.errstate(over="ignore"):  # _boundary reports it
            return _boundary(v[vertex] + eps * np.stack([np.cos(angle), np.sin(angle)], axis=1), vertex, eps)


def _epsilon(eps):
    eps = _real(eps, "eps")
    if eps < 0:
        raise ValueError(
            f"eps must be >= 0, got {eps!r}: erosion is not supported (the lecture's formulas hold only "
            "until an edge collapses); inflating the reversed curve moves the edges the other way"
        )
    return eps


def _boundary(points, vertex, eps):
    """The inflated boundary through ``points``, each made at the user's vertex ``vertex[j]``.

    Repeated points (an arc of zero angle, a step below rounding) are dropped; errors name the
    vertex of the input curve.
    """
    bad = np.flatnonzero(~np.isfinite(points).all(axis=1))
    if len(bad):
        raise ValueError(f"inflating by eps = {eps:g} overflows at vertex {vertex[bad[0]]}")
    keep = (points != np.roll(points, 1, axis=0)).any(axis=1)
    if keep.sum() < 3:
        raise ValueError(f"the boundary inflated by eps = {eps:g} collapses to fewer than 3 points")
    return DiscreteCurve(points[keep])


def regular_polygon(n, radius=1.0, clockwise=True, center=(0.0, 0.0)):
    """The regular ``n``-gon with its vertices on the circle of the given radius.

    ``v_k = center + radius (cos(2 pi k / n), -sin(2 pi k / n))`` when clockwise. Its turning angles
    are all ``2 pi / n`` (clockwise) and its edges have length ``2 r sin(pi / n)``.
    """
    try:
        valid = int(n) == n and n >= 3
    except (TypeError, ValueError, OverflowError):  # NaN, inf, text, arrays
        valid = False
    if not valid or isinstance(n, bool):
        raise ValueError(f"a regular polygon needs an integer n >= 3, got {n!r}")
    if int(n) > np.iinfo(np.intp).max // 16:
        raise ValueError(f"n = {n} vertices cannot be stored: the array would need {16 * int(n):.3g} bytes")
    radius = _real(radius, "radius", 0.0, strict=True)
    if not isinstance(clockwise, (bool, np.bool_)):
        raise ValueError(f"clockwise must be True or False, got {clockwise!r}")
    if np.iscomplexobj(center) or np.shape(center) != (2,):
        raise ValueError(f"center must be a point (x, y), got {center!r}")
    center = np.asarray(center, dtype=float)
    if not np.isfinite(center).all():
        raise ValueError(f"center must be a finite point (x, y), got {center!r}")
    theta = (2 * np.pi / int(n)) * np.arange(int(n))
    sign = -1.0 if clockwise else 1.0
    vertices = np.stack([np.cos(theta), sign * np.sin(theta)], axis=1)
    vertices *= radius
    vertices += center
    return DiscreteCurve(vertices)
