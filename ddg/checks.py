"""Immediate feedback on homework: ``check_*(answer)`` tests an answer and says what is wrong.

Each check feeds your function *fresh random input* and tests properties the right answer must
have: symmetries, totals, closed forms on regular polygons, finite differences. It never compares
with a stored answer, and it never prints the solution. What it returns shows as a line in a
notebook:

>>> from ddg.checks import check_turning_angles
>>> check_turning_angles(my_turning_angles)       # doctest: +SKIP
✓ my_turning_angles passed 7 checks on fresh random input

or, for example, ``✗ my_turning_angles: sign convention: on a clockwise square every turn should be
positive, yours are [-1.5708 ...]``. ``bool(feedback)`` is ``True`` when every check passed.
Pass ``seed=`` to repeat the same input.
"""

import numpy as np

from ._extras import missing
from .curve import DiscreteCurve, regular_polygon


class Feedback:
    """The outcome of a check: passed, or the first problem found (with where it was found)."""

    def __init__(self, name, problem=None, checks=0):
        self.name, self.problem, self.checks = name, problem, checks

    @property
    def passed(self):
        return self.problem is None

    def __bool__(self):
        return self.passed

    def __repr__(self):
        if self.passed:
            return f"✓ {self.name} passed {self.checks} checks on fresh random input"
        return f"✗ {self.name}: {self.problem}"

    def _repr_html_(self):
        color = "#1a7f37" if self.passed else "#b3261e"
        text = repr(self).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
        return f'<pre style="color: {color}; white-space: pre-wrap">{text}</pre>'


class _Problem(Exception):
    """Raised inside a check to report what is wrong."""


def _require(condition, message):
    """Report ``message`` (a string, or a function making one, for messages that need the failure) unless ``condition``."""
    if not condition:
        raise _Problem(message() if callable(message) else message)


def _run(answer, checks):
    """Run ``checks`` (pairs of description and callable) and stop at the first problem."""
    name = getattr(answer, "__name__", "your answer")
    for count, (description, check) in enumerate(checks):
        try:
            check()
        except NotImplementedError:
            return Feedback(name, "not written yet: replace `raise NotImplementedError` (or `...`) with your code")
        except _Problem as problem:
            return Feedback(name, f"{description}: {problem}")
        except Exception as error:  # the answer crashed: say where, not how to fix it
            return Feedback(name, f"{description}: raised {type(error).__name__}: {error}")
    return Feedback(name, checks=count + 1)


def _array(result, shape, what):
    try:
        result = np.asarray(result, dtype=float)
    except (TypeError, ValueError):
        raise _Problem(f"{what} should be an array of numbers, got {type(result).__name__}")
    _require(result.shape == shape, f"{what} should have shape {shape}, got {result.shape}")
    _require(np.isfinite(result).all(), f"{what} contains NaN or infinity")
    return result


def _short(values, digits=4):
    return np.array2string(np.asarray(values), precision=digits, threshold=6, suppress_small=True)


def _random_polygon(rng, n=None, convex=False):
    """A random closed polygon, self-intersecting unless ``convex``; clockwise when convex."""
    n = n or int(rng.integers(3, 13))
    while True:
        if convex:
            gaps = rng.uniform(1, 3, n)
            t = 2 * np.pi * np.cumsum(gaps) / gaps.sum()
            v = np.stack([rng.uniform(1, 2) * np.cos(t), -np.sin(t)], axis=1) + rng.normal(size=2)
        else:
            v = rng.uniform(-1, 1, (n, 2))
        c = DiscreteCurve(v)
        if c.edge_lengths.min() > 0.05 and np.abs(c.turning_angles).max() < np.pi - 0.05:
            return c


def _rotation(angle):
    return np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])


# ----------------------------------------------------------------------------- chapter 1


def check_osculating_center(osculating_center, seed=None):
    """``osculating_center(curve, t)``: centre of the osculating circle of a ``ddg.smooth`` curve at ``t``."""
    from . import smooth

    rng = np.random.default_rng(seed)

    def circles():
        for clockwise in (True, False):
            r, c = rng.uniform(0.5, 3), rng.normal(size=2)
            t = rng.uniform(0, 2 * np.pi, 5)
            got = _array(osculating_center(smooth.circle(r, c, clockwise), t), (5, 2), "the centres for 5 parameters")
            where = "clockwise" if clockwise else "counter-clockwise"
            _require(np.allclose(got, c, atol=1e-8),
                     f"for a {where} circle of radius {r:.3f} centred at {_short(c)} you found centres such as {_short(got[0])}")

    def distance():
        e = smooth.ellipse(rng.uniform(1.5, 3), rng.uniform(0.5, 1.2), clockwise=bool(rng.integers(2)))
        t = rng.uniform(0, 2 * np.pi, 6)
        got = _array(osculating_center(e, t), (6, 2), "the centres for 6 parameters")
        radius = np.linalg.norm(got - e.position(t), axis=1)
        _require(np.allclose(radius, 1 / np.abs(e.curvature(t)), rtol=1e-8),
                 f"on an ellipse the distance from the curve to your centre is {_short(radius)}; "
                 "it should be the radius of curvature 1/|kappa|")
        side = np.einsum("ij,ij->i", got - e.position(t), e.normal(t)) * e.curvature(t)
        _require((side < 0).all(), "the centre is on the wrong side of the curve: it lies where the curve bends to")

    return _run(osculating_center, [("circles", circles), ("an ellipse", distance)])


# ----------------------------------------------------------------------------- chapter 2


def check_staircase(staircase, seed=None):
    """``staircase(curve, m)``: a closed staircase through the ``4m`` points ``curve.position(2 pi k / 4m)``
    of a ``ddg.smooth`` ellipse (axis-parallel steps, corners outside the curve)."""
    from . import smooth

    rng = np.random.default_rng(seed)

    def random_ellipse():
        a, b = rng.uniform(0.5, 2, 2)
        centre = rng.normal(size=2)
        return smooth.ellipse(a, b, centre, clockwise=bool(rng.integers(2))), a, b, centre

    def build(curve, m):
        v = np.asarray(staircase(curve, m), dtype=float)
        _require(v.ndim == 2 and v.shape[1] == 2, f"staircase(curve, {m}) should return an (n, 2) array, got shape {v.shape}")
        try:
            return DiscreteCurve(v)
        except ValueError as problem:
            raise _Problem(f"staircase(curve, {m}) is not a closed discrete curve: {problem}")

    def steps():
        curve, *_ = random_ellipse()
        m = int(rng.integers(2, 9))
        e = build(curve, m).edges
        flat = (np.abs(e[:, 0]) < 1e-12) | (np.abs(e[:, 1]) < 1e-12)
        _require(flat.all(), lambda: f"edge {np.flatnonzero(~flat)[0]} of staircase(curve, {m}) is neither horizontal nor vertical")

    def close_to_curve():
        curve, a, b, centre = random_ellipse()

        def gap(m):  # how far the vertices are from the ellipse, in its own units
            x, y = ((build(curve, m).vertices - centre) / [a, b]).T
            return np.abs(np.hypot(x, y) - 1).max()

        gaps = [gap(m) for m in (4, 16, 64)]
        _require(gaps[2] < 0.1 and gaps[2] < gaps[0] / 4,
                 f"the vertices do not approach the ellipse as m grows (largest relative distance {_short(gaps)} for m = 4, 16, 64)")
        _require(abs(build(curve, 16).turning_number) == 1, "the staircase should go around the ellipse once")
        outside = np.hypot(*((build(curve, 8).vertices - centre) / [a, b]).T) >= 1 - 1e-12
        _require(outside.all(), "the corners should lie outside the ellipse (each step turns around the outer corner)")

    def length():
        curve, a, b, _ = random_ellipse()
        for m in (3, 10, 50):
            L = build(curve, m).length
            _require(abs(L - 4 * (a + b)) < 1e-9 * (a + b), lambda: f"staircase(curve, {m}) around an ellipse with semi-axes "
                     f"{a:.3f}, {b:.3f} has length {L:.6f}; what does every staircase around this ellipse measure?")

    return _run(staircase, [("steps", steps), ("closeness", close_to_curve), ("length", length)])


def check_vertex_normals(vertex_normals, seed=None):
    """``vertex_normals(curve, method)``: unit normals at the vertices of a closed curve.

    ``method`` is one of ``"bisector"`` (the unit bisector of the two edge normals),
    ``"length-weighted"`` (the edge normals averaged with weights ``|e|``),
    ``"length-gradient"`` (the direction of the gradient of length) and ``"area-gradient"`` (the
    direction of the gradient of the signed area).
    """
    rng = np.random.default_rng(seed)
    methods = ("bisector", "length-weighted", "length-gradient", "area-gradient")

    def normals(c, method):
        return _array(vertex_normals(c, method), (len(c), 2), f"vertex_normals(curve, {method!r}) for {len(c)} vertices")

    def unit_and_outward():
        c = _random_polygon(rng, convex=True)
        for method in methods:
            got = normals(c, method)
            _require(np.allclose(np.linalg.norm(got, axis=1), 1, atol=1e-9), f"{method!r}: the normals should have length 1")
            outward = np.einsum("ij,ij->i", got, c.vertices - c.vertices.mean(axis=0))
            _require((outward > 0).all(), lambda: f"{method!r}: on a clockwise convex polygon the normals should point outward, "
                     f"at vertex {np.flatnonzero(outward <= 0)[0]} yours points inward (mind the lecture's sign convention)")

    def bisector():
        c = _random_polygon(rng)
        got = normals(c, "bisector")
        N_prev, N_next = np.roll(c.normals, 1, axis=0), c.normals
        a, b = np.einsum("ij,ij->i", got, N_prev), np.einsum("ij,ij->i", got, N_next)
        _require(np.allclose(a, b, atol=1e-9) and (a > 0).all(),
                 "'bisector': each normal should make the same angle with the two edge normals at its vertex")

    def gradient_direction(method, quantity):
        c = _random_polygon(rng)
        got = normals(c, method)
        h = 1e-6
        for i in rng.choice(len(c), size=min(3, len(c)), replace=False):
            grad = np.zeros(2)
            for d in range(2):
                step = np.zeros((len(c), 2))
                step[i, d] = h
                grad[d] = (quantity(DiscreteCurve(c.vertices + step)) - quantity(DiscreteCurve(c.vertices - step))) / (2 * h)
            cosine = abs(grad @ got[i]) / np.linalg.norm(grad)
            _require(cosine > 1 - 1e-6, f"{method!r}: at vertex {i} of a random polygon your normal {_short(got[i])} is not "
                     f"along the gradient that finite differences measure (their angle is {np.degrees(np.arccos(min(cosine, 1))):.2f}°)")

    return _run(vertex_normals, [
        ("unit length and outward", unit_and_outward),
        ("bisector", bisector),
        ("gradient of length", lambda: gradient_direction("length-gradient", lambda c: c.length)),
        ("gradient of area", lambda: gradient_direction("area-gradient", lambda c: c.signed_area)),
    ])


# ----------------------------------------------------------------------------- chapter 3


def check_turning_angles(turning_angles, seed=None):
    """``turning_angles(vertices)``: clockwise turning angle at every vertex of a closed polygon, in ``(-pi, pi]``."""
    rng = np.random.default_rng(seed)

    def angles(v, what="the turning angles"):
        return _array(turning_angles(np.asarray(v, dtype=float)), (len(v),), f"{what} of {len(v)} vertices (one per vertex)")

    def square():
        got = angles([[0, 0], [0, 1], [1, 1], [1, 0]], "the turning angles of a clockwise unit square")
        _require(np.allclose(got, np.pi / 2), f"sign convention: on a clockwise square every turn should be positive, yours are {_short(got)}")

    def regular():
        n = int(rng.integers(3, 20))
        for clockwise, sign in ((True, 1), (False, -1)):
            got = angles(regular_polygon(n, rng.uniform(0.5, 2), clockwise).vertices)
            _require(np.allclose(got, sign * 2 * np.pi / n), f"on a {'clockwise' if clockwise else 'counter-clockwise'} regular "
                     f"{n}-gon you found {_short(got)}")

    def total():
        for _ in range(20):
            c = _random_polygon(rng)
            got = angles(c.vertices)
            _require((got > -np.pi).all() and (got <= np.pi + 1e-12).all(), f"angles should lie in (-pi, pi], yours include {got.min():.4f}, {got.max():.4f}")
            k = got.sum() / (2 * np.pi)
            _require(abs(k - round(k)) < 1e-9, f"on a random closed polygon your angles sum to {got.sum():.6f}, "
                     "which is not a multiple of 2 pi (is every vertex's turn there, the closing edge's too?)")

    def symmetries():
        c = _random_polygon(rng)
        got = angles(c.vertices)
        moved = angles(c.vertices @ _rotation(rng.uniform(0, 6)).T + rng.normal(size=2), "the turning angles of a rotated copy")
        _require(np.allclose(moved, got, atol=1e-9), "not invariant under rotation and translation")
        backwards = angles(c.vertices[::-1], "the turning angles of the reversed polygon")
        _require(np.allclose(backwards, -got[::-1], atol=1e-9), "reversing the polygon should negate the angles (and reverse their order)")

    def locality():
        c = _random_polygon(rng, n=8)
        v = c.vertices.copy()
        got = angles(v)
        v[4] += rng.normal(scale=0.05, size=2)
        changed = np.flatnonzero(~np.isclose(angles(v), got, atol=1e-12))
        _require(set(changed) <= {3, 4, 5}, f"moving vertex 4 changed the angles at vertices {changed.tolist()}; "
                 "psi_i should depend only on the two edges at v_i")

    return _run(turning_angles, [("a clockwise square", square), ("regular polygons", regular),
                                 ("totals on random polygons", total), ("symmetries", symmetries), ("locality", locality)])


def check_rebuild(rebuild, seed=None):
    """``rebuild(psi, lengths, start, heading)``: vertices ``v_0 ... v_n`` from turning angles and edge lengths.

    ``psi[i]`` is the clockwise turn at ``v_i``, ``lengths[i] = |e_{i+1/2}|``, ``start = v_0`` and
    ``heading`` is the angle (counter-clockwise from the x-axis) of the first edge ``e_{1/2}``.
    The result has ``n + 1`` rows; it closes when the last equals the first.
    """
    rng = np.random.default_rng(seed)

    def rebuilt(c, start, heading):
        return _array(rebuild(c.turning_angles, c.edge_lengths, start, heading), (len(c) + 1, 2),
                      f"rebuild(...) for {len(c)} angles and lengths (v_0 ... v_n)")

    def own_polygon():
        for _ in range(5):
            c = _random_polygon(rng)
            e = c.edges[0]
            got = rebuilt(c, c.vertices[0], np.arctan2(e[1], e[0]))
            wrong = np.flatnonzero(~np.isclose(got[:-1], c.vertices, atol=1e-9).all(axis=1))
            _require(len(wrong) == 0, lambda: f"rebuilding a random polygon from its own angles and lengths misplaces vertex {wrong[0]} "
                     f"(at {_short(got[wrong[0]])}, expected {_short(c.vertices[wrong[0]])}); "
                     "check the direction of the turns and which turn comes before which edge")
            _require(np.allclose(got[-1], got[0], atol=1e-9), "the rebuilt polygon should close: v_n = v_0")

    def square():
        got = _array(rebuild(np.full(4, np.pi / 2), np.ones(4), (0.0, 0.0), np.pi / 2), (5, 2), "a rebuilt square")
        _require(np.allclose(got, [[0, 0], [0, 1], [1, 1], [1, 0], [0, 0]], atol=1e-12),
                 f"four clockwise quarter turns with unit edges, starting upwards from the origin, gave {_short(got)}")

    def not_closing():
        c = _random_polygon(rng, convex=True)
        lengths = c.edge_lengths.copy()
        lengths[0] *= 1.5
        got = _array(rebuild(c.turning_angles, lengths, (0.0, 0.0), 0.0), (len(c) + 1, 2), "a rebuilt polygon")
        gap = np.linalg.norm(got[-1] - got[0])
        _require(abs(gap - 0.5 * c.edge_lengths[0]) < 1e-9,
                 f"with one edge made longer by half its length the gap v_n - v_0 should be that half ({0.5 * c.edge_lengths[0]:.4f}); yours is {gap:.4f}")

    return _run(rebuild, [("a square", square), ("random polygons", own_polygon), ("a polygon that cannot close", not_closing)])


# ----------------------------------------------------------------------------- chapter 4


def check_length_gradient(length_gradient, seed=None):
    """``length_gradient(vertices)``: the gradient of length of a closed polygon under the inner product ``<.,.>`` of the lecture."""
    rng = np.random.default_rng(seed)

    def finite_differences():
        for _ in range(5):
            c = _random_polygon(rng)
            got = _array(length_gradient(c.vertices.copy()), (len(c), 2), f"the gradient for {len(c)} vertices")
            delta = rng.normal(size=(len(c), 2))
            h = 1e-6
            directional = (DiscreteCurve(c.vertices + h * delta).length - DiscreteCurve(c.vertices - h * delta).length) / (2 * h)
            yours = c.inner(got, delta)
            _require(abs(yours - directional) < 1e-6 * max(1, abs(directional)),
                     f"on a random polygon <grad L, delta> = {yours:.6f} but the derivative of length along delta is "
                     f"{directional:.6f} (finite differences); remember the weights A_i in <.,.>")

    def circle():
        c = regular_polygon(12, 2.0)
        got = _array(length_gradient(c.vertices.copy()), (12, 2), "the gradient on a regular 12-gon")
        outward = np.einsum("ij,ij->i", got, c.vertices) > 0
        _require(outward.all(), "on a clockwise regular polygon the gradient of length should point outward (growing the polygon lengthens it)")

    return _run(length_gradient, [("finite differences", finite_differences), ("direction on a circle", circle)])


# ----------------------------------------------------------------------------- chapter 5


def check_minkowski_area(minkowski_area, seed=None):
    """``minkowski_area(curve, eps)``: area of the Minkowski sum of a clockwise simple polygon with a disk of radius ``eps``.

    It must be right for non-convex polygons too, for ``eps`` small enough that the inflated
    edges meet only their neighbours. It is measured against shapely's round buffer.
    """
    try:
        import shapely
    except ImportError as error:
        raise missing("checks", error) from error

    rng = np.random.default_rng(seed)

    def star_shaped():
        """A random clockwise star-shaped polygon (simple, usually with reflex vertices)."""
        n = int(rng.integers(5, 12))
        t = 2 * np.pi * (np.arange(n) + rng.uniform(-0.3, 0.3, n)) / n
        r = rng.uniform(0.5, 1.5, n)
        return DiscreteCurve(np.stack([r * np.cos(t), -r * np.sin(t)], axis=1))

    def compare(c, eps, what):
        got = float(minkowski_area(c, eps))
        measured = shapely.Polygon(c.vertices).buffer(eps, quad_segs=1024).area
        _require(abs(got - measured) < 1e-8 * measured + 1e-5 * eps**2,
                 f"{what}, eps = {eps:.4f}: you give {got:.8f}, the measured area is {measured:.8f}")

    def convex():
        compare(_random_polygon(rng, convex=True), rng.uniform(0.05, 1), "a random convex polygon")

    def non_convex():
        tested = 0
        while tested < 8:
            c = star_shaped()
            reflex = c.turning_angles < 0
            eps = 0.1 * c.edge_lengths.min()
            # keep polygons whose inflated edges meet only their neighbours at this eps: there the area
            # is the polygon, the strips, sectors at convex corners and overlaps at reflex ones
            psi = c.turning_angles
            corners = np.where(reflex, np.tan(psi / 2), psi / 2).sum()
            exact = c.signed_area + eps * c.length + eps**2 * corners
            if not reflex.any() or abs(shapely.Polygon(c.vertices).buffer(eps, quad_segs=1024).area - exact) > 1e-8 * exact:
                continue
            compare(c, eps, f"a star-shaped polygon with {reflex.sum()} reflex vertices")
            tested += 1

    return _run(minkowski_area, [("convex polygons", convex), ("non-convex polygons", non_convex)])


# ----------------------------------------------------------------------------- chapter 6


def check_circle_curvature(circle_curvature, seed=None):
    """``circle_curvature(curve)``: signed ``1/R`` of the circle through ``v_{i-1}, v_i, v_{i+1}``, at every vertex."""
    rng = np.random.default_rng(seed)

    def values(c, what):
        return _array(circle_curvature(c), (len(c),), f"{what} ({len(c)} vertices)")

    def regular():
        n, r = int(rng.integers(3, 30)), rng.uniform(0.3, 3)
        got = values(regular_polygon(n, r), f"the curvature of a clockwise regular {n}-gon")
        _require(np.allclose(got, 1 / r), f"every vertex of a clockwise regular {n}-gon lies on a circle of radius {r:.4f}; "
                 f"you found {_short(got)}")
        ccw = values(regular_polygon(n, r, clockwise=False), "a counter-clockwise regular polygon")
        _require(np.allclose(ccw, -1 / r), f"counter-clockwise, the curvature should be negative (clockwise is positive); you found {_short(ccw)}")

    def symmetries():
        c = _random_polygon(rng)
        k = values(c, "a random polygon")
        v = c.vertices
        moved = values(DiscreteCurve(v @ _rotation(rng.uniform(0, 6)).T + rng.normal(size=2)), "a moved copy")
        _require(np.allclose(moved, k, rtol=1e-9, atol=1e-9), "not invariant under rotation and translation")
        alpha = rng.uniform(0.2, 5)
        scaled = values(DiscreteCurve(alpha * v), "a scaled copy")
        _require(np.allclose(scaled, k / alpha, rtol=1e-9, atol=1e-9), f"scaling by {alpha:.3f} should divide the curvature by {alpha:.3f}")
        reflected = values(DiscreteCurve(v * [1, -1]), "a reflected copy")
        _require(np.allclose(reflected, -k, rtol=1e-9, atol=1e-9), "a reflection should flip the sign")

    def straight():
        v = np.array([[0.0, 0.0], [1.0, 0.0], [2.5, 0.0], [1.0, 1.0]])
        got = values(DiscreteCurve(v), "a polygon with a straight vertex")
        _require(abs(got[1]) < 1e-12, f"three collinear vertices lie on a circle of infinite radius: expected 0, you found {got[1]:.4g}")

    return _run(circle_curvature, [("regular polygons", regular), ("symmetries", symmetries), ("a straight vertex", straight)])


# ----------------------------------------------------------------------------- chapter 7


def check_zigzag_exponent(a, seed=None):
    """Your threshold ``a``: zigzags of amplitude ``n^-b`` about the unit circle have converging curvature exactly when ``b > a``."""
    rng = np.random.default_rng(seed)

    def zigzag_error(n, b):
        theta = 2 * np.pi * np.arange(n) / n
        radius = 1 + n ** (-b) * (-1.0) ** np.arange(n)
        c = DiscreteCurve(np.stack([radius * np.cos(theta), -radius * np.sin(theta)], axis=1))
        return np.abs(c.curvature("angle") - 1).max()

    def value():
        _require(np.ndim(a) == 0 and np.isfinite(a), f"the answer should be one number, got {a!r}")

    def below():
        b = float(a) - rng.uniform(0.3, 0.5)
        errors = [zigzag_error(n, b) for n in (256, 1024, 4096)]
        _require(errors[2] > 0.5 * errors[0],
                 f"with amplitude n^-{b:.2f} (below your threshold) the curvature error still falls: {_short(errors)} for n = 256, 1024, 4096")

    def above():
        b = float(a) + rng.uniform(0.3, 0.5)
        errors = [zigzag_error(n, b) for n in (256, 1024, 4096)]
        _require(errors[2] < 0.5 * errors[0],
                 f"with amplitude n^-{b:.2f} (above your threshold) the curvature error does not fall: {_short(errors)} for n = 256, 1024, 4096")

    feedback = _run(check_zigzag_exponent, [("a number", value), ("just below it", below), ("just above it", above)])
    feedback.name = f"threshold {a!r}"
    return feedback
