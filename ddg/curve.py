"""Discrete plane curves, following §3 of the lecture (Vouga, *Plane Curves*).

Conventions (the lecture's, see the book's chapter on notation):

* ``J`` rotates by +90 degrees: ``J(x, y) = (-y, x)``; normals are ``N = J T``.
* A curve traversed **clockwise** has positive curvature and outward normals.
* ``edges[i]`` is ``e_{i+1/2} = v_{i+1} - v_i``; for a closed curve indices are taken modulo ``n``.
* ``turning_angles[i]`` is ``psi_i``, the clockwise turning angle from ``e_{i-1/2}`` to
  ``e_{i+1/2}``, in ``(-pi, pi]``.

Every quantity is computed once, on first use, with vectorized numpy (no loop over vertices), and
handed out read-only. How each stays accurate at any scale is in ``ddg/_numerics.py``; what is
refused, and as which error, in ``ddg/errors.py``.
"""

from __future__ import annotations

from functools import cached_property

import numpy as np
import numpy.typing as npt

from . import _arguments as check
from . import _numerics as nx
from .errors import DegenerateCurveError, InputError, OpenCurveError, OutOfRangeError

Array = npt.NDArray[np.float64]

CURVATURES = ("angle", "sine", "tangent")
"""The three discrete curvatures of the lecture: equations (1), (3) and (4)."""

INFLATIONS = ("minkowski", "offset")
"""The lecture's two inflations (§3.4): disk sectors at the vertices, or parallel edges with kites."""


class DiscreteCurve:
    """A discrete curve ``Gamma = (v_0, ..., v_{n-1})`` (lecture §3).

    Parameters
    ----------
    vertices : array-like of shape ``(n, 2)``
        The vertices ``v_i``: real numbers (a list, a numpy array, a masked array without masked
        entries). The curve keeps its own read-only copy.
    closed : bool
        ``True`` (default): the edge ``e_{n-1/2}`` from the last vertex back to the first is
        implied, so do not repeat the first vertex at the end. ``False``: an open polyline; the
        turning angle (hence every curvature) is defined only at the interior vertices
        ``v_1 ... v_{n-2}``, and what needs a closed curve (turning number, area, inflation)
        raises :class:`~ddg.errors.OpenCurveError`.

    Raises :class:`~ddg.errors.InputError` for anything but ``n`` pairs of finite real numbers,
    :class:`~ddg.errors.DegenerateCurveError` for too few vertices or two consecutive equal ones
    (``v_{i+1} != v_i``), :class:`~ddg.errors.OutOfRangeError` for a length beyond the largest
    float; each names the vertex. Any scale works, and any distance from the origin: each method
    says to what accuracy. A curve does not change: its quantities are computed once and shared,
    read-only (``.copy()`` one to change it), and setting one raises ``AttributeError``.

    >>> square = DiscreteCurve([[0, 0], [0, 1], [1, 1], [1, 0]])     # up, right, down, left
    >>> square
    DiscreteCurve(n=4, closed, length=4)
    >>> square.turning_number, square.signed_area                    # clockwise: positive
    (1, 1.0)
    """

    def __init__(self, vertices: npt.ArrayLike, closed: bool = True) -> None:
        self._closed = check.flag(closed, "closed")
        v = check.enough(check.points(vertices, "vertex", finite=False), self._closed)
        self._v = nx.frozen(v)
        L, self._safe = nx.edge_lengths(v, self._closed)  # laid out for the turns: a closed curve's last edge first too
        self._L = nx.frozen(L)
        check.edges(v, self.edge_lengths, self.length, self._closed, self._safe)  # finite, no equal neighbours or overflow

    def __len__(self) -> int:
        return len(self._v)

    @property
    def closed(self) -> bool:
        """Whether the last vertex is joined to the first; read-only, as every cached value depends on it.

        >>> DiscreteCurve([[0, 0], [1, 0], [1, 1]], closed=False).closed
        False
        """
        return self._closed

    def __setattr__(self, name: str, value: object) -> None:
        if not name.startswith("_"):  # a quantity set by hand would make the others disagree with it
            raise AttributeError(f"{name} is read-only: a curve's quantities follow from its vertices; make a new "
                                 f"curve, DiscreteCurve(vertices, closed=...), or keep your own value in a variable")
        object.__setattr__(self, name, value)

    def __delattr__(self, name: str) -> None:
        self.__setattr__(name, None) if not name.startswith("_") else object.__delattr__(self, name)

    def __repr__(self) -> str:
        return f"DiscreteCurve(n={len(self)}, {'closed' if self.closed else 'open'}, length={self.length:.6g})"

    def __reduce__(self):  # pickled and copied as its vertices: the copy computes everything afresh
        return type(self), (np.array(self._v), self.closed)

    def _require_closed(self, what: str) -> None:  # an OpenCurveError for what needs a closed curve
        if not self.closed:
            raise OpenCurveError(f"{what} is defined for closed curves only; this curve is open")

    # ------------------------------------------------------------------ edges (lecture §3)

    @property
    def vertices(self) -> Array:
        """The vertices ``v_i``, shape ``(n, 2)``, read-only.

        >>> DiscreteCurve([[0, 0], [0, 1], [1, 0]]).vertices
        array([[0., 0.],
               [0., 1.],
               [1., 0.]])
        """
        return self._v

    @cached_property
    def edges(self) -> Array:
        """``edges[i] = e_{i+1/2} = v_{i+1} - v_i``: ``n`` of them if closed, else ``n - 1``.

        >>> DiscreteCurve([[0, 0], [0, 1], [1, 0]]).edges
        array([[ 0.,  1.],
               [ 1., -1.],
               [-1.,  0.]])
        """
        v = self._v
        with np.errstate(over="ignore"):  # an edge beyond the floats: the curve refuses it
            return nx.frozen(np.diff(v, axis=0, append=v[:1]) if self.closed else np.diff(v, axis=0))

    @cached_property
    def edge_lengths(self) -> Array:
        """``|e_{i+1/2}|`` for each edge, to a rounding error of itself at any scale.

        >>> DiscreteCurve([[0, 0], [3, 4], [3, 0]]).edge_lengths
        array([5., 4., 3.])
        """
        return self._L[int(self.closed):]

    @cached_property
    def length(self) -> float:
        """Total arc length ``L = sum_i |e_{i+1/2}|`` (lecture §3); finite, or the curve is refused.

        >>> DiscreteCurve([[0, 0], [3, 4], [3, 0]]).length
        12.0
        """
        with np.errstate(over="ignore"):
            return float(self.edge_lengths.sum())

    @cached_property
    def tangents(self) -> Array:
        """Unit edge tangents ``T_{i+1/2} = e_{i+1/2} / |e_{i+1/2}|``.

        >>> DiscreteCurve([[0, 0], [3, 4], [3, 0]]).tangents[0]
        array([0.6, 0.8])
        """
        return nx.frozen(nx.unit(self.edges, self.edge_lengths))

    @cached_property
    def normals(self) -> Array:
        """Edge normals ``N_{i+1/2} = J T_{i+1/2}``: outward on a clockwise convex curve.

        >>> DiscreteCurve([[0, 0], [0, 1], [1, 1], [1, 0]]).normals[0]   # the clockwise unit square
        array([-1.,  0.])
        """
        return nx.frozen(nx.J(self.tangents))

    # ---------------------------------------------------------- vertices (lecture §3.1-3.2)

    @cached_property
    def tan_half_psi(self) -> Array:
        """``tan(psi_i / 2)``, accurate up to a turn straight back, where it is ``+inf`` (see ``reversals``).

        >>> DiscreteCurve([[0, 0], [0, 1], [1, 1], [1, 0]]).tan_half_psi        # tan(45 degrees)
        array([1., 1., 1., 1.])
        """
        return nx.frozen(nx.turns(self._v, self.closed, self._L, self._safe))

    @cached_property
    def reversals(self) -> npt.NDArray[np.intp]:
        """The vertices where the curve turns straight back (``psi_i = pi``): its two edges point in
        exactly opposite directions, for the vertices given (no rounding decides it).

        >>> DiscreteCurve([[0, 0], [2, 0], [1, 0], [1, 1]]).reversals
        array([1])
        """
        found = np.flatnonzero(np.isposinf(self.tan_half_psi))
        return nx.frozen(found if self.closed else found + 1, np.intp)

    @cached_property
    def turning_angles(self) -> Array:
        """``psi_i``: clockwise turning angle at ``v_i`` from ``e_{i-1/2}`` to ``e_{i+1/2}``, in ``(-pi, pi]``.

        Closed curve: one per vertex. Open curve: interior vertices only, so ``turning_angles[j]``
        belongs to ``v_{j+1}``. Each is within 1e-15 radians of the exact turn of the vertices
        given; within 7 degrees of ``pi`` it is that turn rounded once (``ddg/_numerics.py``).

        >>> DiscreteCurve([[0, 0], [0, 1], [1, 1], [1, 0]]).turning_angles / np.pi
        array([0.5, 0.5, 0.5, 0.5])
        """
        psi = np.arctan(self.tan_half_psi)
        psi *= 2.0
        return nx.frozen(np.maximum(psi, nx.ABOVE_MINUS_PI, out=psi))

    @cached_property
    def dual_lengths(self) -> Array:
        """``A_i = (|e_{i-1/2}| + |e_{i+1/2}|) / 2``, the length element at ``v_i`` (lecture §3).

        On an open curve the end vertices get half of their single edge, so that ``<1, 1> = L``.

        >>> DiscreteCurve([[0, 0], [3, 4], [3, 0]]).dual_lengths
        array([4. , 4.5, 3.5])
        """
        with np.errstate(under="ignore"):  # a subnormal edge loses its last bit
            half = self._L * 0.5
        if self.closed:
            return nx.frozen(np.add(half[:-1], half[1:], out=half[1:]))
        return nx.frozen(np.concatenate(([0.0], half)) + np.concatenate((half, [0.0])))

    @cached_property
    def _A(self) -> Array:  # the dual lengths at the vertices where psi is defined
        return self.dual_lengths if self.closed else self.dual_lengths[1:-1]

    @cached_property
    def bisector_normals(self) -> Array:
        """``N_i``: the unit bisector of the edge normals ``N_{i-1/2}`` and ``N_{i+1/2}`` at each vertex.

        It is the direction of the gradient of length (lecture §3.3): ``(grad L)_i = k_i^sine N_i``
        (eq. 3). It is ``N_{i-1/2}`` turned clockwise by ``psi_i / 2``; where the curve turns straight
        back (``psi_i = pi``) this is ``T_{i-1/2}``, the limit of the bisector and the direction of
        ``grad L`` there. Open curves: the interior vertices.

        >>> DiscreteCurve([[0, 0], [0, 1], [1, 1], [1, 0]]).bisector_normals[1] * np.sqrt(2)
        array([-1.,  1.])
        """
        N, T = self.normals, self.tangents  # N_{i-1/2}, T_{i-1/2} at each vertex where psi is defined
        N_prev, T_prev = (nx.previous(N), nx.previous(T)) if self.closed else (N[:-1], T[:-1])
        t = self.tan_half_psi  # cos(psi/2) and sin(psi/2) from tan(psi/2), accurate near psi = pi
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            cos, sin = 1 / np.hypot(1, t), np.sign(t) / np.hypot(1, 1 / t)
        return nx.frozen(cos[:, None] * N_prev + sin[:, None] * T_prev)

    @cached_property
    def turning_number(self) -> int:
        """``sum_i psi_i / (2 pi)``, an integer for every closed polygon (lecture §3.2).

        A curve that turns straight back somewhere (``psi_i = pi``: its two edges point in exactly
        opposite directions) has no turning number: counting that turn as ``+pi``, as the range
        ``(-pi, pi]`` does, would make a reflection keep the count instead of negating it. It
        raises :class:`~ddg.errors.DegenerateCurveError` naming the vertex (``turning_angles.sum() /
        (2 pi)`` counts it as ``+pi``).

        >>> DiscreteCurve([[0, 0], [1, 0], [1, 1], [0, 1]]).turning_number     # counter-clockwise
        -1
        """
        self._require_closed("the turning number")
        if len(self.reversals):
            raise DegenerateCurveError(f"the turning number is not defined: the curve turns straight back at vertex "
                                       f"{self.reversals[0]} (its two edges point in exactly opposite directions), "
                                       "where a turn of +pi and one of -pi are equally right")
        return int(round(float(self.turning_angles.sum()) / (2 * np.pi)))

    @cached_property
    def signed_area(self) -> float:
        """Enclosed area, positive for a clockwise curve: ``-1/2 sum_i v_i x v_{i+1}`` (the shoelace).

        For a self-intersecting curve this is the winding-number-weighted area. It is within 1e-13
        of the exact area of the vertices given (a bound computed alongside; where it could be
        more, the exact area rounded once: ``ddg/_numerics.py``); an area beyond the largest float
        raises :class:`~ddg.errors.OutOfRangeError`, one below the smallest is 0.

        >>> DiscreteCurve([[0, 0], [0, 2], [3, 0]]).signed_area
        3.0
        """
        self._require_closed("the enclosed area")
        with np.errstate(over="ignore"):
            area = -nx.signed_area_ccw(self._v)
        if not np.isfinite(area):
            raise OutOfRangeError("the enclosed area is larger than the largest float (about 1.8e308); scale the "
                                  "curve down")
        return area

    def inner(self, F: npt.ArrayLike, G: npt.ArrayLike) -> float:
        """Discrete inner product ``<F, G> = sum_i A_i F_i . G_i`` (lecture §3 and §3.3).

        ``F`` and ``G`` are discrete functions: shape ``(n,)`` (scalar) or ``(n, 2)`` (vector).
        A product beyond the largest float raises :class:`~ddg.errors.OutOfRangeError`.

        >>> square = DiscreteCurve([[0, 0], [0, 1], [1, 1], [1, 0]])
        >>> square.inner(np.ones(4), np.ones(4))           # <1, 1> = L
        4.0
        """
        f, g = check.discrete_function(F, len(self), "F"), check.discrete_function(G, len(self), "G")
        if f.shape != g.shape:
            raise InputError(f"F and G must both be scalar or both vector: shapes {f.shape}, {g.shape}")
        with np.errstate(over="ignore", invalid="ignore"):
            products = f * g if f.ndim == 1 else (f * g).sum(axis=1)
            result = float(self.dual_lengths @ products)
        if not np.isfinite(result):
            raise OutOfRangeError("<F, G> is beyond the largest float (about 1.8e308): scale F or G down")
        return result

    # ------------------------------------------------------- curvature (lecture §3.2-3.4)

    def curvature(self, kind: str = "angle") -> Array:
        """Discrete curvature ``k_i`` by one of the lecture's formulas (``ddg.CURVATURES``).

        With ``2 A_i = |e_{i-1/2}| + |e_{i+1/2}|``:

        * ``"angle"``:   ``k_i = 2 psi_i / (2 A_i)``          (eq. 1, from the turning-number theorem)
        * ``"sine"``:    ``k_i = 4 sin(psi_i/2) / (2 A_i)``   (eq. 3, from the gradient of length)
        * ``"tangent"``: ``k_i = 4 tan(psi_i/2) / (2 A_i)``   (eq. 4, from offset inflation)

        Each is computed as ``(psi_i/2) / (A_i/2)``, ``sin(psi_i/2) / (A_i/2)`` or ``tan(psi_i/2) / (A_i/2)``
        from ``tan(psi_i/2)``, so no ``2 tan(psi_i/2)`` overflows where ``k_i`` would not. Accuracy: that of ``psi_i``
        (see :attr:`turning_angles`) and a few rounding errors;
        a curvature below the smallest normal float (2.2e-308) keeps only its subnormal bits. The
        tangent formula diverges where the curve turns straight back (``psi_i = pi``): there it
        raises :class:`~ddg.errors.DegenerateCurveError`, and a curvature beyond the largest float
        :class:`~ddg.errors.OutOfRangeError`, naming the vertex. Open curves: interior vertices.

        >>> square = DiscreteCurve([[0, 0], [0, 1], [1, 1], [1, 0]])
        >>> square.curvature("angle") / np.pi, square.curvature("tangent")
        (array([0.5, 0.5, 0.5, 0.5]), array([2., 2., 2., 2.]))
        """
        check.choose(kind, CURVATURES, "curvature kind")
        cache = self.__dict__.setdefault("_curvatures", {})
        if kind not in cache:
            k, finite = nx.curvature(kind, self.tan_half_psi, self._L)  # eq. (1), (3) or (4)
            if not finite and kind == "tangent" and len(self.reversals):
                raise DegenerateCurveError(f"the tangent curvature (eq. 4) diverges at vertex {self.reversals[0]}: the "
                                           "curve turns straight back there (psi = pi)")
            if not finite:
                first = 0 if self.closed else 1
                check.require_finite(k, lambda j: f"the {kind} curvature at vertex {j + first} is beyond the largest "
                                     f"float (a turn of {np.degrees(self.turning_angles[j]):.6g} degrees between "
                                     f"edges {self._A[j]:.3g} long on average)", OutOfRangeError)
            cache[kind] = nx.frozen(k)
        return cache[kind]

    def total_curvature(self, kind: str = "angle") -> float:
        """``<k, 1> = sum_i A_i k_i`` over the vertices where ``k`` is defined: ``sum_i psi_i``,
        ``2 sum_i sin(psi_i/2)`` or ``2 sum_i tan(psi_i/2)``, summed from the angles (no product
        ``A_i k_i`` under- or overflows).

        >>> round(DiscreteCurve([[0, 0], [0, 1], [1, 1], [1, 0]]).total_curvature() / np.pi, 12)
        2.0
        """
        check.choose(kind, CURVATURES, "curvature kind")
        self.curvature(kind)  # its refusals
        if kind == "angle":
            return float(self.turning_angles.sum())
        with np.errstate(over="ignore"):
            half = nx.sin_half(self.tan_half_psi) if kind == "sine" else self.tan_half_psi
            total = 2.0 * float(half.sum())
        if not np.isfinite(total):
            raise OutOfRangeError(f"the total {kind} curvature is beyond the largest float (about 1.8e308)")
        return total

    def length_gradient(self) -> Array:
        """Gradient of length under the discrete inner product, shape ``(n, 2)`` (lecture §3.3).

        ``(grad L)_j = (T_{j-1/2} - T_{j+1/2}) / A_j``, so that ``<grad L, delta> = D_delta L``
        (eq. 2) for every variation ``delta``. Its length is the sine curvature (eq. 3). On an open
        curve the end vertices have a single edge: ``(grad L)_0 = -T_{1/2} / A_0`` and
        ``(grad L)_{n-1} = T_{n-3/2} / A_{n-1}``. A gradient beyond the largest float (edges below
        about 1e-308) raises :class:`~ddg.errors.OutOfRangeError`.

        >>> DiscreteCurve([[0, 0], [0, 1], [1, 1], [1, 0]]).length_gradient()[0]
        array([-1., -1.])
        """
        T = self.tangents
        if self.closed:
            g = nx.previous(T) - T
        else:
            g = np.concatenate((np.zeros((1, 2)), T)) - np.concatenate((T, np.zeros((1, 2))))
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            g /= self.dual_lengths[:, None]
        check.require_finite(g, lambda j: f"the gradient of length at vertex {j} is beyond the largest float "
                             f"(its edges are {self.dual_lengths[j]:.3g} long on average)", OutOfRangeError)
        return g  # a new array at every call: yours to change

    def laplacian(self, F: npt.ArrayLike) -> Array:
        """The discrete Laplacian of ``F`` on a closed curve (the book's chapter 4):

        ``(Lap F)_i = ((F_{i+1} - F_i) / |e_{i+1/2}| - (F_i - F_{i-1}) / |e_{i-1/2}|) / A_i``.

        ``F`` is a discrete function, shape ``(n,)`` or ``(n, 2)``. This is the piecewise-linear
        finite-element Laplacian with the dual lengths as masses, the one-dimensional case of the
        cotan Laplacian. It is symmetric for ``<.,.>``, ``<Lap F, F> <= 0``, and on the vertices it
        is minus the gradient of length: ``laplacian(vertices) == -length_gradient()``. A value
        beyond the largest float raises :class:`~ddg.errors.OutOfRangeError` naming the vertex.

        >>> DiscreteCurve([[0, 0], [0, 1], [1, 1], [1, 0]]).laplacian([0, 0, 1, 0])
        array([ 0.,  1., -2.,  1.])
        """
        self._require_closed("the Laplacian")
        f = check.discrete_function(F, len(self), "F")
        shape = (-1,) if f.ndim == 1 else (-1, 1)
        with np.errstate(over="ignore", invalid="ignore"):
            flux = (np.concatenate((f[1:], f[:1])) - f) / self.edge_lengths.reshape(shape)  # (F_{i+1} - F_i) / |e|
            lap = (flux - nx.previous(flux)) / self.dual_lengths.reshape(shape)
        check.require_finite(lap, lambda j: f"the Laplacian at vertex {j} is beyond the largest float: scale F down "
                             "or the curve up", OutOfRangeError)
        return lap  # a new array at every call: yours to change

    # -------------------------------------------------------------- inflation (lecture §3.4)

    def inflated_area(self, eps: float, method: str = "minkowski") -> float:
        """Signed area of the curve inflated by ``eps >= 0`` along its normals (lecture §3.4):
        ``A_0 + eps L + eps^2 / 2 sum_i psi_i`` (``"minkowski"``: disk sectors at the vertices) or
        ``A_0 + eps L + eps^2 sum_i tan(psi_i / 2)`` (``"offset"``: parallel edges, kites at the
        corners). What is refused, and when this is the area of a region: ``ddg.inflation``.

        >>> square = DiscreteCurve([[0, 0], [0, 1], [1, 1], [1, 0]])
        >>> square.inflated_area(1.0, "offset"), round(square.inflated_area(1.0) - np.pi, 12)
        (9.0, 5.0)
        """
        from .inflation import inflated_area

        return inflated_area(self, eps, method)

    def inflate(self, eps: float, method: str = "minkowski") -> DiscreteCurve:
        """The boundary of the region inflated by ``eps >= 0``, a new closed :class:`DiscreteCurve`:
        every edge moved by ``eps`` along its normal, joined at each vertex by an arc of radius
        ``eps`` (``"minkowski"``) or where the moved edges meet (``"offset"``); ``ddg.inflation``
        says how finely the arcs are cut and what that costs in area.

        >>> DiscreteCurve([[0, 0], [0, 1], [1, 1], [1, 0]]).inflate(1.0, "offset").vertices
        array([[-1., -1.],
               [-1.,  2.],
               [ 2.,  2.],
               [ 2., -1.]])
        """
        from .inflation import inflate

        return inflate(self, eps, method)
