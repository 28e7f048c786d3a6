"""Discrete plane curves, following §3 of the lecture (Vouga, *Plane Curves*).

Conventions (the lecture's, see the book's chapter on notation):

* ``J`` rotates by +90 degrees: ``J(x, y) = (-y, x)``; normals are ``N = J T``.
* A curve traversed **clockwise** has positive curvature and outward normals.
* ``edges[i]`` is ``e_{i+1/2} = v_{i+1} - v_i``; for a closed curve indices are taken modulo ``n``.
* ``turning_angles[i]`` is ``psi_i``, the clockwise turning angle from ``e_{i-1/2}`` to
  ``e_{i+1/2}``, in ``(-pi, pi]``.

Every quantity is computed once, on first use, with vectorized numpy (no loop over vertices), and
handed out read-only. How each stays accurate at any scale is in ``ddg/_numerics.py``.
"""

from __future__ import annotations

from functools import cached_property

import numpy as np

from . import _numerics as nx

CURVATURES = ("angle", "sine", "tangent")
"""The three discrete curvatures of the lecture: equations (1), (3) and (4)."""

INFLATIONS = ("minkowski", "offset")
"""The lecture's two inflations (§3.4): disk sectors at the vertices, or parallel edges with kites."""

MAX_ARC_STEP = 0.01
"""Largest angle (radians) between two samples of a Minkowski arc in :meth:`DiscreteCurve.inflate`."""

MAX_ARC_POINTS = 1_000_000
"""Most points :meth:`DiscreteCurve.inflate` places on all the Minkowski arcs together."""


class DiscreteCurve:
    """A discrete curve ``Gamma = (v_0, ..., v_{n-1})`` (lecture §3).

    Parameters
    ----------
    vertices : array-like of shape ``(n, 2)``
        The vertices ``v_i``. The curve keeps its own read-only copy.
    closed : bool
        ``True`` (default): the edge ``e_{n-1/2}`` from the last vertex back to the first is
        implied, so do not repeat the first vertex at the end. ``False``: an open polyline; the
        turning angle (hence every curvature) is defined only at the interior vertices
        ``v_1 ... v_{n-2}``, and what needs a closed curve (turning number, area, inflation)
        raises ``ValueError``.

    Raises ``ValueError``, naming the vertex, for a shape other than ``(n, 2)``, coordinates that
    are not real numbers, NaN or infinite coordinates, too few vertices, or two consecutive equal
    vertices (the lecture requires ``v_{i+1} != v_i``).

    Any scale works, from ``1e-300`` to ``1e300``, and any distance from the origin: lengths,
    angles and curvatures are computed without under- or overflow, and the area is the exact area
    of the vertices given, rounded once. (An area beyond the largest float raises ``ValueError``;
    one below the smallest rounds to 0.) Every array a curve hands out is read-only.
    """

    def __init__(self, vertices, closed=True):
        self._closed = nx.flag(closed, "closed")
        raw = np.asarray(vertices)
        if raw.dtype.kind not in "iufO":
            raise ValueError(f"vertices must be real numbers, got {raw.dtype} values (e.g. {raw.flat[0]!r})")
        try:
            v = np.array(raw, dtype=float)
        except TypeError as problem:  # an object array holding complex numbers or text
            raise ValueError(f"vertices must be real numbers: {problem}") from None
        if v.ndim != 2 or v.shape[1] != 2:
            raise ValueError(f"vertices must have shape (n, 2), got shape {v.shape}")
        minimum = 3 if self.closed else 2
        if len(v) < minimum:
            raise ValueError(f"{'a closed' if self.closed else 'an open'} discrete curve needs at least "
                             f"{minimum} vertices, got {len(v)}")
        nx.require_finite(v, lambda i: f"vertex {i} has a NaN or infinite coordinate: {v[i]}")
        self._v = nx.frozen(v)
        lengths = self.edge_lengths
        if not np.isfinite(lengths).all():
            raise ValueError("the coordinates are too large: an edge's length overflows")
        if lengths.min() == 0.0:
            i = int(np.argmin(lengths))
            if self.closed and i == len(v) - 1:
                raise ValueError(f"the last vertex {i} repeats the first vertex 0 ({v[0]}); a closed curve's "
                                 "closing edge is implied, so leave the repeated vertex out")
            raise ValueError(f"vertices {i} and {i + 1} are equal ({v[i]}); consecutive vertices must differ")

    def __len__(self):
        return len(self._v)

    @property
    def closed(self):
        """Whether the last vertex is joined to the first; read-only, as every cached value depends on it."""
        return self._closed

    @closed.setter
    def closed(self, value):
        raise AttributeError("closed is read-only: make a new curve, DiscreteCurve(curve.vertices, closed=...)")

    def __repr__(self):
        return f"DiscreteCurve(n={len(self)}, {'closed' if self.closed else 'open'}, length={self.length:.6g})"

    def __reduce__(self):
        """Pickled and copied as its vertices: the copy computes everything afresh."""
        return type(self), (np.array(self._v), self.closed)

    def _require_closed(self, what):
        if not self.closed:
            raise ValueError(f"{what} is defined for closed curves only; this curve is open")

    def _at_vertices(self, values):
        """``(previous, next)`` edge values around each vertex where ``psi`` is defined."""
        return (nx.previous(values), values) if self.closed else (values[:-1], values[1:])

    def _vertex_index(self, j):
        """The vertex that entry ``j`` of a per-vertex array belongs to (open curves skip ``v_0``)."""
        return int(j) + (0 if self.closed else 1)

    # ------------------------------------------------------------------ edges (lecture §3)

    @property
    def vertices(self):
        """The vertices ``v_i``, shape ``(n, 2)``, read-only."""
        return self._v

    @cached_property
    def edges(self):
        """``edges[i] = e_{i+1/2} = v_{i+1} - v_i``: ``n`` of them if closed, else ``n - 1``."""
        v = self._v
        nxt = np.concatenate((v[1:], v[:1])) if self.closed else v[1:]
        return nx.frozen(nxt - v[: len(nxt)])

    @cached_property
    def edge_lengths(self):
        """``|e_{i+1/2}|`` for each edge (no under- or overflow at any scale)."""
        return nx.frozen(nx.lengths(self.edges))

    @cached_property
    def length(self):
        """Total arc length ``L = sum_i |e_{i+1/2}|`` (lecture §3)."""
        return float(self.edge_lengths.sum())

    @cached_property
    def tangents(self):
        """Unit edge tangents ``T_{i+1/2} = e_{i+1/2} / |e_{i+1/2}|``."""
        return nx.frozen(self.edges / self.edge_lengths[:, None])

    @cached_property
    def normals(self):
        """Edge normals ``N_{i+1/2} = J T_{i+1/2}``: outward on a clockwise convex curve."""
        return nx.frozen(nx.J(self.tangents))

    # ---------------------------------------------------------- vertices (lecture §3.1-3.2)

    @cached_property
    def _tan_half_psi(self):
        """``tan(psi_i / 2)``, accurate up to a turn straight back, where it is ``+inf``."""
        return nx.tan_half_turn(*self._at_vertices(self.edges))

    @cached_property
    def _reversals(self):
        """Indices, into the per-vertex arrays, where the curve turns straight back (``psi = pi``)."""
        return np.flatnonzero(np.isposinf(self._tan_half_psi))

    @cached_property
    def turning_angles(self):
        """``psi_i``: clockwise turning angle at ``v_i`` from ``e_{i-1/2}`` to ``e_{i+1/2}``, in ``(-pi, pi]``.

        Closed curve: one per vertex. Open curve: interior vertices only, so ``turning_angles[j]``
        belongs to ``v_{j+1}``. A turn a rounding error short of ``-pi`` stays inside the range.
        """
        psi = 2.0 * np.arctan(self._tan_half_psi)
        return nx.frozen(np.maximum(psi, nx.ABOVE_MINUS_PI))

    @cached_property
    def dual_lengths(self):
        """``A_i = (|e_{i-1/2}| + |e_{i+1/2}|) / 2``, the length element at ``v_i`` (lecture §3).

        On an open curve the end vertices get half of their single edge, so that ``<1, 1> = L``.
        """
        half = self.edge_lengths / 2
        if self.closed:
            return nx.frozen(nx.previous(half) + half)
        return nx.frozen(np.concatenate(([0.0], half)) + np.concatenate((half, [0.0])))

    @cached_property
    def _A(self):
        """The dual lengths at the vertices where ``psi`` is defined."""
        return self.dual_lengths if self.closed else self.dual_lengths[1:-1]

    @cached_property
    def bisector_normals(self):
        """``N_i``: the unit bisector of the edge normals ``N_{i-1/2}`` and ``N_{i+1/2}`` at each vertex.

        It is the direction of the gradient of length (lecture §3.3): ``(grad L)_i = k_i^sine N_i``
        (eq. 3). It is ``N_{i-1/2}`` turned clockwise by ``psi_i / 2``; where the curve turns straight
        back (``psi_i = pi``) this is ``T_{i-1/2}``, the limit of the bisector and the direction of
        ``grad L`` there. Closed curve: every vertex; open curve: the interior vertices.
        """
        (N_prev, _), (T_prev, _) = self._at_vertices(self.normals), self._at_vertices(self.tangents)
        t = self._tan_half_psi  # cos(psi/2) and sin(psi/2) from tan(psi/2), accurate near psi = pi
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            cos, sin = 1 / np.hypot(1, t), np.sign(t) / np.hypot(1, 1 / t)
        return nx.frozen(cos[:, None] * N_prev + sin[:, None] * T_prev)

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
            raise ValueError(f"the turning number is not defined: the curve turns straight back at vertex "
                             f"{self._vertex_index(self._reversals[0])} (its two edges, as computed, point in "
                             "exactly opposite directions), where a turn of +pi and one of -pi are equally right")
        return int(round(float(self.turning_angles.sum()) / (2 * np.pi)))

    @cached_property
    def signed_area(self):
        """Enclosed area, positive for a clockwise curve: ``-1/2 sum_i v_i x v_{i+1}`` (the shoelace).

        For a self-intersecting curve this is the winding-number-weighted area. It is the exact
        area of the vertices given, rounded once (see ``ddg/_numerics.py``).
        """
        self._require_closed("the enclosed area")
        with np.errstate(over="ignore"):
            area = -nx.signed_area_ccw(self._v)
        if not np.isfinite(area):
            raise ValueError("the enclosed area is larger than the largest float (about 1.8e308); scale the curve down")
        return area

    def inner(self, F, G):
        """Discrete inner product ``<F, G> = sum_i A_i F_i . G_i`` (lecture §3 and §3.3).

        ``F`` and ``G`` are discrete functions: shape ``(n,)`` (scalar) or ``(n, 2)`` (vector).
        """
        F, G = self._function(F, "F"), self._function(G, "G")
        if F.shape != G.shape:
            raise ValueError(f"F and G must both be scalar or both vector: shapes {F.shape}, {G.shape}")
        products = F * G if F.ndim == 1 else (F * G).sum(axis=1)
        return float(self.dual_lengths @ products)

    def _function(self, F, name):
        """``F`` as a discrete function on the vertices, or a ``ValueError`` saying what it is."""
        if np.iscomplexobj(F):
            raise ValueError(f"{name} must be a real discrete function, got complex values")
        F, n = np.asarray(F, dtype=float), len(self)
        if F.shape not in ((n,), (n, 2)):
            raise ValueError(f"{name} must be a discrete function with one value per vertex, shape ({n},) "
                             f"or ({n}, 2); got shape {F.shape}")
        nx.require_finite(F, lambda i: f"{name} has a NaN or infinite value at vertex {i}: {F[i]}")
        return F

    # ------------------------------------------------------- curvature (lecture §3.2-3.4)

    def curvature(self, kind="angle"):
        """Discrete curvature ``k_i`` by one of the lecture's formulas (``ddg.CURVATURES``).

        With ``2 A_i = |e_{i-1/2}| + |e_{i+1/2}|``:

        * ``"angle"``:   ``k_i = 2 psi_i / (2 A_i)``          (eq. 1, from the turning-number theorem)
        * ``"sine"``:    ``k_i = 4 sin(psi_i/2) / (2 A_i)``   (eq. 3, from the gradient of length)
        * ``"tangent"``: ``k_i = 4 tan(psi_i/2) / (2 A_i)``   (eq. 4, from offset inflation)

        The tangent formula diverges where the curve turns straight back (``psi_i = pi``); there it
        raises ``ValueError`` naming the vertex, as does any curvature too large for a float.
        Open curves: interior vertices ``v_1 ... v_{n-2}``.
        """
        nx.choose(kind, CURVATURES, "curvature kind")
        cache = self.__dict__.setdefault("_curvatures", {})
        if kind not in cache:
            psi, two_A = self.turning_angles, 2 * self._A
            if kind == "tangent" and len(self._reversals):
                raise ValueError(f"the tangent curvature (eq. 4) diverges at vertex "
                                 f"{self._vertex_index(self._reversals[0])}: the curve turns straight back there "
                                 "(psi = pi)")
            with np.errstate(over="ignore", invalid="ignore"):
                if kind == "angle":
                    k = 2 * psi / two_A                          # eq. (1)
                elif kind == "sine":
                    k = 4 * np.sin(psi / 2) / two_A              # eq. (3)
                else:
                    k = 4 * self._tan_half_psi / two_A           # eq. (4): tan(psi/2), accurate near pi
            nx.require_finite(k, lambda j: f"the {kind} curvature at vertex {self._vertex_index(j)} is beyond the "
                              f"largest float (a turn of {np.degrees(psi[j]):.6g} degrees between edges "
                              f"{two_A[j] / 2:.3g} long on average)")
            cache[kind] = nx.frozen(k)
        return cache[kind]

    def total_curvature(self, kind="angle"):
        """``<k, 1> = sum_i A_i k_i`` over the vertices where ``k`` is defined."""
        return float(self._A @ self.curvature(kind))

    def length_gradient(self):
        """Gradient of length under the discrete inner product, shape ``(n, 2)`` (lecture §3.3).

        ``(grad L)_j = (T_{j-1/2} - T_{j+1/2}) / A_j``, so that ``<grad L, delta> = D_delta L``
        (eq. 2) for every variation ``delta``. Its length is the sine curvature (eq. 3). On an open
        curve the end vertices have a single edge: ``(grad L)_0 = -T_{1/2} / A_0`` and
        ``(grad L)_{n-1} = T_{n-3/2} / A_{n-1}``.
        """
        T = self.tangents
        if self.closed:
            g = nx.previous(T) - T
        else:
            g = np.concatenate((np.zeros((1, 2)), T)) - np.concatenate((T, np.zeros((1, 2))))
        return nx.frozen(g / self.dual_lengths[:, None])

    def laplacian(self, F):
        """The discrete Laplacian of ``F`` on a closed curve (the book's chapter 4):

        ``(Lap F)_i = ((F_{i+1} - F_i) / |e_{i+1/2}| - (F_i - F_{i-1}) / |e_{i-1/2}|) / A_i``.

        ``F`` is a discrete function, shape ``(n,)`` or ``(n, 2)``. This is the piecewise-linear
        finite-element Laplacian with the dual lengths as masses, the one-dimensional case of the
        cotan Laplacian. It is symmetric for ``<.,.>``, ``<Lap F, F> <= 0``, and on the vertices it
        is minus the gradient of length: ``laplacian(vertices) == -length_gradient()``.
        """
        self._require_closed("the Laplacian")
        F = self._function(F, "F")
        shape = (-1,) if F.ndim == 1 else (-1, 1)
        flux = (np.concatenate((F[1:], F[:1])) - F) / self.edge_lengths.reshape(shape)  # (F_{i+1} - F_i) / |e|
        return nx.frozen((flux - nx.previous(flux)) / self.dual_lengths.reshape(shape))

    # -------------------------------------------------------------- inflation (lecture §3.4)

    def _inflation(self, eps, method):
        """Check the arguments of an inflation; ``eps`` as a float."""
        nx.choose(method, INFLATIONS, "inflation method")
        self._require_closed("inflation")
        eps = nx.real(eps, "eps")
        if eps < 0:
            raise ValueError(f"eps must be >= 0, got {eps!r}: erosion is not supported (the lecture's formulas hold "
                             "only until an edge collapses); inflating the reversed curve moves the edges the other way")
        if eps > 0 and self.signed_area < 0:
            raise ValueError("the curve is counter-clockwise (its signed area is negative): its normals point inward, "
                             "so inflating it would erode it, which the formulas describe only until an edge "
                             "collapses; reverse it (vertices[::-1]) to inflate it outward")
        return eps

    def inflated_area(self, eps, method="minkowski"):
        """Signed area of the curve inflated by ``eps >= 0`` along its normals (lecture §3.4).

        * ``"minkowski"``: disk sectors of angle ``psi_i`` at the vertices:
          ``A_0 + eps L + eps^2 / 2 * sum_i psi_i``.
        * ``"offset"``: edges moved parallel by ``eps``, kites at the corners:
          ``A_0 + eps L + eps^2 * sum_i tan(psi_i / 2)``.

        These are the lecture's formulas: the area of the inflated region for a clockwise convex
        polygon, and the signed area of the boundary :meth:`inflate` returns for any curve that is
        not counter-clockwise. A counter-clockwise curve (negative signed area), ``eps < 0`` and an
        area beyond the largest float raise ``ValueError``.
        """
        eps = self._inflation(eps, method)
        if eps == 0.0:
            return self.signed_area
        if method == "minkowski":
            corners = 0.5 * float(self.turning_angles.sum())
        else:  # sum_i tan(psi_i/2), not via k^tangent, which overflows first on a tiny near-reversal
            if len(self._reversals):
                raise ValueError(f"no offset corner at vertex {self._vertex_index(self._reversals[0])}: the curve "
                                 "turns straight back there (psi = pi), so eps^2 tan(psi/2) is infinite")
            with np.errstate(over="ignore", invalid="ignore"):
                corners = float(np.sum(self._tan_half_psi))
        with np.errstate(over="ignore", invalid="ignore"):
            area = self.signed_area + eps * self.length + eps * eps * corners
        if not np.isfinite(area):
            raise ValueError("the inflated area is larger than the largest float (about 1.8e308); scale the curve "
                             "or eps down")
        return area

    def inflate(self, eps, method="minkowski"):
        """The boundary of the inflated region as a new closed :class:`DiscreteCurve`.

        Every edge moves by ``eps >= 0`` along its normal ``N_{i+1/2}``. At vertex ``v_i`` the two
        moved edges are joined by

        * ``"minkowski"``: the arc of radius ``eps`` about ``v_i`` that turns clockwise by
          ``psi_i``, cut into equal chords of angle at most ``h = max(MAX_ARC_STEP,
          sum |psi_i| / MAX_ARC_POINTS)``. Each chord misses a sliver of its sector, so the
          boundary's signed area falls short of :meth:`inflated_area` by at most
          ``eps^2 h^2 sum |psi_i| / 12`` (a fraction ``h^2 / 6`` of the sectors, below 2e-5);
        * ``"offset"``: the corner where the two moved edges meet (the kite's outer vertex).

        ``eps = 0`` returns the curve itself. Points that coincide are kept once. On a non-convex
        curve this boundary sweeps back over itself near the reflex vertices.
        """
        eps = self._inflation(eps, method)
        if eps == 0.0:
            return self
        v, psi = self._v, self.turning_angles
        N_prev, _ = self._at_vertices(self.normals)
        if method == "offset":  # the moved edges meet at v + eps (N_{i-1/2} + tan(psi_i/2) T_{i-1/2})
            if len(self._reversals):
                raise ValueError(f"no offset corner at vertex {self._reversals[0]}: the curve turns straight back there")
            T_prev, _ = self._at_vertices(self.tangents)
            with np.errstate(over="ignore"):
                corners = v + eps * (N_prev + self._tan_half_psi[:, None] * T_prev)
            return _boundary(corners, np.arange(len(v)), eps)
        h = max(MAX_ARC_STEP, float(np.abs(psi).sum()) / MAX_ARC_POINTS)
        steps = np.ceil(np.abs(psi) / h).astype(int)  # chords per arc
        vertex = np.repeat(np.arange(len(v)), steps + 1)
        k = np.arange(len(vertex)) - np.repeat(np.cumsum(steps + 1) - (steps + 1), steps + 1)  # 0 ... steps_i
        angle = np.arctan2(N_prev[:, 1], N_prev[:, 0])[vertex] - psi[vertex] * k / np.maximum(steps[vertex], 1)
        with np.errstate(over="ignore"):
            return _boundary(v[vertex] + eps * np.stack([np.cos(angle), np.sin(angle)], axis=1), vertex, eps)


def _boundary(points, vertex, eps):
    """The inflated boundary through ``points``, each made at the user's vertex ``vertex[j]``.

    Repeated points (an arc of zero angle, a step below rounding) are dropped; errors name the
    vertex of the input curve.
    """
    nx.require_finite(points, lambda j: f"inflating by eps = {eps:g} overflows at vertex {vertex[j]}")
    keep = (points != nx.previous(points)).any(axis=1)
    if keep.sum() < 3:
        raise ValueError(f"the boundary inflated by eps = {eps:g} collapses to fewer than 3 points")
    return DiscreteCurve(points[keep])


def regular_polygon(n, radius=1.0, clockwise=True, center=(0.0, 0.0)):
    """The regular ``n``-gon with its vertices on the circle of the given radius.

    ``v_k = center + radius (cos(2 pi k / n), -sin(2 pi k / n))`` when clockwise. Its turning angles
    are all ``2 pi / n`` (clockwise) and its edges have length ``2 r sin(pi / n)``.
    """
    try:
        valid = int(n) == n and n >= 3 and not isinstance(n, (bool, np.bool_))
    except (TypeError, ValueError, OverflowError):  # NaN, inf, text, arrays
        valid = False
    if not valid:
        raise ValueError(f"a regular polygon needs an integer n >= 3, got {n!r}")
    if int(n) > np.iinfo(np.intp).max // 16:
        raise ValueError(f"n = {n} vertices cannot be stored: the array would need {16 * int(n):.3g} bytes")
    radius = nx.real(radius, "radius", 0.0, strict=True)
    clockwise = nx.flag(clockwise, "clockwise")
    if np.iscomplexobj(center) or np.shape(center) != (2,):
        raise ValueError(f"center must be a point (x, y), got {center!r}")
    center = np.asarray(center, dtype=float)
    if not np.isfinite(center).all():
        raise ValueError(f"center must be a finite point (x, y), got {center!r}")
    theta = (2 * np.pi / int(n)) * np.arange(int(n))
    vertices = np.stack([np.cos(theta), (-1.0 if clockwise else 1.0) * np.sin(theta)], axis=1)
    return DiscreteCurve(radius * vertices + center)
