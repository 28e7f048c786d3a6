"""Tests of ddg.DiscreteCurve: closed forms, signs, symmetries (hypothesis), gradient, inflation.

Tolerances: the inputs are O(1) coordinates, so quantities are computed to ~1e-13 relative; the
bounds below leave a margin of 10-100x over what rounding costs.
"""

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

import ddg

# ---------------------------------------------------------------- closed forms, in the lecture's conventions (clockwise positive)


@pytest.mark.parametrize("n", [3, 4, 7, 100])
@pytest.mark.parametrize("r", [0.3, 1.0, 5.0])
def test_regular_polygon_closed_forms(n, r):
    c = ddg.regular_polygon(n, r)
    np.testing.assert_allclose(c.turning_angles, 2 * np.pi / n, rtol=1e-13)
    np.testing.assert_allclose(c.edge_lengths, 2 * r * np.sin(np.pi / n), rtol=1e-13)
    np.testing.assert_allclose(c.curvature("sine"), 1 / r, rtol=1e-13)  # exact: eq. (3)
    np.testing.assert_allclose(c.curvature("angle"), (2 * np.pi / n) / (2 * r * np.sin(np.pi / n)), rtol=1e-13)
    np.testing.assert_allclose(c.curvature("tangent"), 1 / (r * np.cos(np.pi / n)), rtol=1e-13)
    assert c.total_curvature("angle") == pytest.approx(2 * np.pi, rel=1e-14)
    assert c.total_curvature("sine") == pytest.approx(2 * n * np.sin(np.pi / n), rel=1e-13)
    assert c.total_curvature("tangent") == pytest.approx(2 * n * np.tan(np.pi / n), rel=1e-13)
    assert c.total_curvature("sine") < 2 * np.pi < c.total_curvature("tangent")


def test_clockwise_circle_has_positive_curvature_and_outward_normals():
    cw = ddg.regular_polygon(64, 2.0, clockwise=True)
    ccw = ddg.regular_polygon(64, 2.0, clockwise=False)
    midpoints = cw.vertices + cw.edges / 2
    assert (np.einsum("ij,ij->i", cw.normals, midpoints) > 0).all()  # outward
    assert (np.einsum("ij,ij->i", ccw.normals, ccw.vertices + ccw.edges / 2) < 0).all()
    for kind in ddg.CURVATURES:
        assert (cw.curvature(kind) > 0).all() and (ccw.curvature(kind) < 0).all()
        np.testing.assert_allclose(ccw.curvature(kind), -cw.curvature(kind), rtol=1e-12)
    assert cw.turning_number == 1 and ccw.turning_number == -1
    assert cw.signed_area > 0 > ccw.signed_area
    assert cw.signed_area == pytest.approx(0.5 * 64 * 4 * np.sin(2 * np.pi / 64), rel=1e-13)


def test_unit_square_by_hand():
    square = ddg.DiscreteCurve([[0, 0], [0, 1], [1, 1], [1, 0]])  # up, right, down, left: clockwise
    np.testing.assert_allclose(square.turning_angles, np.pi / 2)
    np.testing.assert_allclose(square.dual_lengths, 1.0)
    np.testing.assert_allclose(square.edges, [[0, 1], [1, 0], [0, -1], [-1, 0]])
    np.testing.assert_allclose(square.tangents, square.edges)
    np.testing.assert_allclose(square.normals, [[-1, 0], [0, 1], [1, 0], [0, -1]])  # J T, outward
    assert square.length == 4 and square.signed_area == 1 and square.turning_number == 1
    np.testing.assert_allclose(square.curvature("sine"), 2 * np.sin(np.pi / 4))
    np.testing.assert_allclose(square.length_gradient(), [[-1, -1], [-1, 1], [1, 1], [1, -1]])


def test_turning_angle_range_includes_pi_excludes_minus_pi():
    spike = ddg.DiscreteCurve([[0, 0], [2, 0], [1, 0], [1, 1]])  # turns straight back at vertex 1
    assert spike.turning_angles[1] == np.pi
    assert np.all(spike.turning_angles > -np.pi) and np.all(spike.turning_angles <= np.pi)
    assert spike.curvature("sine")[1] == pytest.approx(2 / spike.dual_lengths[1])
    with pytest.raises(ValueError, match="diverges at vertex 1"):
        spike.curvature("tangent")
    clockwise_spike = ddg.DiscreteCurve(spike.vertices * [1, -1])  # mirrored: clockwise, same reversal
    with pytest.raises(ValueError, match="vertex 1"):
        clockwise_spike.inflate(0.1, "offset")


# ---------------------------------------------------------------- random polygons (hypothesis)

coordinates = st.floats(-10, 10, allow_nan=False, allow_infinity=False)


@st.composite
def polygons(draw, min_n=3, max_n=24):
    """Random closed polygons (mostly self-intersecting), away from degenerate corners.

    Vertices are uniform in a box of random aspect ratio; polygons with an edge shorter than 1e-2
    or a turn within 1e-2 of pi (where tan(psi/2) exceeds 200) are redrawn.
    """
    n = draw(st.integers(min_n, max_n))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    while True:
        v = rng.uniform(-10, 10, (n, 2)) * [1.0, rng.uniform(0.05, 1.0)]
        if np.linalg.norm(np.roll(v, -1, axis=0) - v, axis=1).min() > 1e-2:
            if np.abs(ddg.DiscreteCurve(v).turning_angles).max() < np.pi - 1e-2:
                return v


def motions():
    return st.tuples(st.floats(0, 2 * np.pi), coordinates, coordinates)


def rotate(v, angle, dx, dy):
    R = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    return v @ R.T + [dx, dy]


def curvature_scale(c):
    return np.abs(np.concatenate([c.curvature(k) for k in ddg.CURVATURES])).max()


@settings(max_examples=150, deadline=None)
@given(polygons(), motions())
def test_curvature_invariant_under_rigid_motion(v, motion):
    c, moved = ddg.DiscreteCurve(v), ddg.DiscreteCurve(rotate(v, *motion))
    for kind in ddg.CURVATURES:
        np.testing.assert_allclose(moved.curvature(kind), c.curvature(kind), rtol=0, atol=1e-9 * curvature_scale(c))


@settings(max_examples=150, deadline=None)
@given(polygons(), st.floats(0, np.pi))
def test_reflection_flips_sign(v, line_angle):
    # reflect across the line through the origin at angle line_angle
    d = np.array([np.cos(line_angle), np.sin(line_angle)])
    reflected = 2 * (v @ d)[:, None] * d - v
    c, r = ddg.DiscreteCurve(v), ddg.DiscreteCurve(reflected)
    for kind in ddg.CURVATURES:
        np.testing.assert_allclose(r.curvature(kind), -c.curvature(kind), rtol=0, atol=1e-9 * curvature_scale(c))
    assert r.turning_number == -c.turning_number


@settings(max_examples=150, deadline=None)
@given(polygons())
def test_reversal_flips_sign_with_index_map(v):
    # reversed curve w_i = v_{n-1-i}: its vertex i is the original vertex n-1-i
    c, r = ddg.DiscreteCurve(v), ddg.DiscreteCurve(v[::-1])
    for kind in ddg.CURVATURES:
        np.testing.assert_allclose(r.curvature(kind), -c.curvature(kind)[::-1], rtol=0, atol=1e-9 * curvature_scale(c))
    np.testing.assert_allclose(r.dual_lengths, c.dual_lengths[::-1], rtol=1e-12)


@settings(max_examples=150, deadline=None)
@given(polygons(), st.floats(0.01, 100))
def test_scaling_by_alpha_divides_curvature_by_alpha(v, alpha):
    c, s = ddg.DiscreteCurve(v), ddg.DiscreteCurve(alpha * v)
    for kind in ddg.CURVATURES:
        np.testing.assert_allclose(s.curvature(kind), c.curvature(kind) / alpha, rtol=1e-9)


@settings(max_examples=300, deadline=None)
@given(polygons(max_n=60))
def test_turning_angles_sum_to_multiple_of_2pi(v):
    c = ddg.DiscreteCurve(v)
    total = c.turning_angles.sum()
    assert abs(total - 2 * np.pi * c.turning_number) < 1e-9
    assert c.total_curvature("angle") == pytest.approx(2 * np.pi * c.turning_number, abs=1e-9)


def test_turning_number_of_figure_eight_and_doubly_wound_polygon():
    t = np.linspace(0, 2 * np.pi, 40, endpoint=False)
    eight = ddg.DiscreteCurve(np.stack([np.sin(2 * t), np.sin(t)], axis=1))
    assert eight.turning_number == 0 and abs(eight.turning_angles.sum()) < 1e-12
    theta = 2 * (2 * np.pi / 7) * np.arange(7)  # the heptagram {7/2}
    double = ddg.DiscreteCurve(np.stack([np.cos(theta), -np.sin(theta)], axis=1))
    assert double.turning_number == 2
    assert double.turning_angles.sum() == pytest.approx(4 * np.pi, abs=1e-12)
    wound = ddg.DiscreteCurve(np.concatenate([ddg.regular_polygon(9).vertices, 1.5 * ddg.regular_polygon(9).vertices]))
    assert wound.turning_number == 2


# ---------------------------------------------------------------- gradient of length (§3.3)


@settings(max_examples=60, deadline=None)
@given(polygons(), st.integers(0, 2**32 - 1))
def test_length_gradient_matches_finite_differences(v, seed):
    c = ddg.DiscreteCurve(v)
    delta = np.random.default_rng(seed).normal(size=v.shape)
    h = 1e-6
    directional = (ddg.DiscreteCurve(v + h * delta).length - ddg.DiscreteCurve(v - h * delta).length) / (2 * h)
    assert c.inner(c.length_gradient(), delta) == pytest.approx(directional, rel=1e-6, abs=1e-6)


@settings(max_examples=60, deadline=None)
@given(polygons())
def test_length_gradient_norm_is_sine_curvature(v):
    c = ddg.DiscreteCurve(v)
    norm = np.linalg.norm(c.length_gradient(), axis=1)
    np.testing.assert_allclose(norm, np.abs(c.curvature("sine")), rtol=1e-9)


def test_length_gradient_of_open_curve_matches_finite_differences():
    v = np.array([[0.0, 0.0], [1.0, 0.2], [2.0, -0.3], [2.5, 1.0]])
    c = ddg.DiscreteCurve(v, closed=False)
    delta = np.random.default_rng(1).normal(size=v.shape)
    h = 1e-6
    fd = (ddg.DiscreteCurve(v + h * delta, closed=False).length - ddg.DiscreteCurve(v - h * delta, closed=False).length) / (2 * h)
    assert c.inner(c.length_gradient(), delta) == pytest.approx(fd, rel=1e-7)


# ---------------------------------------------------------------- inflation (§3.4) against shapely


def random_convex_polygon(seed, n):
    """Clockwise convex polygon: sorted random angles on an ellipse, rotated and shifted."""
    rng = np.random.default_rng(seed)
    gaps = rng.uniform(1, 3, n)  # angular gaps between neighbours differ by at most 3x
    angles = 2 * np.pi * np.cumsum(gaps) / gaps.sum()
    v = np.stack([2 * np.cos(angles), -np.sin(angles)], axis=1)
    return rotate(v, rng.uniform(0, 2 * np.pi), *rng.normal(size=2))


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(3, 30), st.floats(0.01, 2.0))
def test_minkowski_inflation_matches_round_buffer(seed, n, eps):
    c = ddg.DiscreteCurve(random_convex_polygon(seed, n))
    measured = shapely.Polygon(c.vertices).buffer(eps, quad_segs=512, join_style="round").area
    # a round buffer is a polygon: with 512 segments per quarter circle it misses ~ (pi/1024)^2/6 of the disk
    assert c.inflated_area(eps, "minkowski") == pytest.approx(measured, rel=1e-5)


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(3, 30), st.floats(0.01, 2.0))
def test_offset_inflation_matches_mitre_buffer(seed, n, eps):
    c = ddg.DiscreteCurve(random_convex_polygon(seed, n))
    measured = shapely.Polygon(c.vertices).buffer(eps, join_style="mitre", mitre_limit=1e6).area
    assert c.inflated_area(eps, "offset") == pytest.approx(measured, rel=1e-10)


@pytest.mark.parametrize("method", ddg.INFLATIONS)
@pytest.mark.parametrize("seed", range(5))
def test_inflated_boundary_area_matches_formula_on_convex_curves(method, seed):
    c = ddg.DiscreteCurve(random_convex_polygon(seed, 12))
    for eps in (0.05, 0.5, 3.0):
        boundary = c.inflate(eps, method)
        assert boundary.signed_area == pytest.approx(c.inflated_area(eps, method), rel=1e-4)
        assert boundary.turning_number == 1


def test_inflating_a_counter_clockwise_curve_is_refused_as_erosion():
    ccw = ddg.regular_polygon(7, clockwise=False)  # N points inward: inflating it would erode it
    for method in ddg.INFLATIONS:
        for call in (ccw.inflated_area, ccw.inflate):
            with pytest.raises(ValueError, match="counter-clockwise.*reverse it"):
                call(2.0, method)
        assert ccw.inflated_area(0.0, method) == ccw.signed_area  # eps = 0 moves nothing
    cw = ddg.DiscreteCurve(ccw.vertices[::-1])
    assert cw.inflated_area(2.0) > cw.signed_area > 0


# ---------------------------------------------------------------- inner product and open curves


def test_inner_product_of_ones_is_length():
    for c in (ddg.regular_polygon(11, 3.0), ddg.DiscreteCurve([[0, 0], [1, 0], [1, 2], [5, 2]], closed=False)):
        n = len(c)
        assert c.inner(np.ones(n), np.ones(n)) == pytest.approx(c.length)
        assert c.inner(np.ones((n, 2)), np.ones((n, 2))) == pytest.approx(2 * c.length)


def test_open_curve_defines_interior_quantities_only():
    c = ddg.DiscreteCurve([[0, 0], [1, 0], [2, 1], [2, 2]], closed=False)
    assert c.edges.shape == (3, 2) and c.turning_angles.shape == (2,)
    np.testing.assert_allclose(c.turning_angles, [-np.pi / 4, -np.pi / 4])  # both turns to the left
    assert c.curvature("angle").shape == (2,)
    assert c.dual_lengths.sum() == pytest.approx(c.length)
    for what in ("turning_number", "signed_area"):
        with pytest.raises(ValueError, match="closed curves only"):
            getattr(c, what)
    with pytest.raises(ValueError, match="closed curves only"):
        c.inflated_area(0.1)
    with pytest.raises(ValueError, match="closed curves only"):
        c.inflate(0.1)
    two = ddg.DiscreteCurve([[0, 0], [1, 1]], closed=False)
    assert two.length == pytest.approx(np.sqrt(2)) and two.curvature("sine").shape == (0,)


# ---------------------------------------------------------------- bad input


@pytest.mark.parametrize(
    "vertices, closed, message",
    [
        (np.zeros((4, 3)), True, r"shape \(n, 2\), got shape \(4, 3\)"),
        (np.zeros(6), True, r"shape \(n, 2\)"),
        ([[0, 0], [1, 0]], True, "at least 3 vertices, got 2"),
        ([[0, 0]], False, "at least 2 vertices, got 1"),
        ([[0, 0], [1, np.nan], [2, 0]], True, "vertex 1 has a NaN"),
        ([[0, 0], [1, 0], [2, np.inf], [3, 3]], True, "vertex 2 has a NaN or infinite"),
        ([[0, 0], [1, 1], [1, 1], [2, 0]], True, "vertices 1 and 2 are equal"),
        ([[0, 0], [1, 1], [2, 0], [0, 0]], True, "last vertex 3 repeats the first.*closing edge is implied"),
        ([[0, 0], [0, 0], [1, 1]], False, "vertices 0 and 1 are equal"),
    ],
)
def test_bad_input_raises_clear_error(vertices, closed, message):
    with pytest.raises(ValueError, match=message):
        ddg.DiscreteCurve(vertices, closed=closed)


def test_unknown_kind_or_method_lists_the_valid_ones():
    c = ddg.regular_polygon(5)
    with pytest.raises(ValueError, match="'angle', 'sine', 'tangent'"):
        c.curvature("cotan")
    with pytest.raises(ValueError, match="'minkowski', 'offset'"):
        c.inflated_area(0.1, "bevel")
    with pytest.raises(ValueError, match="'minkowski', 'offset'"):
        c.inflate(0.1, "round")
    with pytest.raises(ValueError, match=r"shape \(5,\) or \(5, 2\)"):
        c.inner(np.ones(4), np.ones(4))
    with pytest.raises(ValueError, match="integer n >= 3"):
        ddg.regular_polygon(2)


def test_vertices_are_a_read_only_copy():
    v = np.array([[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]])
    c = ddg.DiscreteCurve(v)
    v[0] = 5.0
    assert c.vertices[0, 0] == 0.0
    with pytest.raises(ValueError, match="read-only"):
        c.vertices[0, 0] = 1.0
    with pytest.raises(ValueError, match="read-only"):
        c.curvature("angle")[0] = 1.0


def test_large_regular_polygon_keeps_the_accuracy_the_input_allows():
    c = ddg.regular_polygon(10**6, 0.7)
    assert abs(c.turning_angles.sum() - 2 * np.pi) < 1e-9
    assert np.abs(c.curvature("sine") - 1 / 0.7).max() < 1e-4


@settings(max_examples=60, deadline=None)
@given(polygons())
def test_length_gradient_is_sine_curvature_times_bisector_normal(v):
    c = ddg.DiscreteCurve(v)
    np.testing.assert_allclose(c.length_gradient(), c.curvature("sine")[:, None] * c.bisector_normals, atol=1e-9)
    np.testing.assert_allclose(np.linalg.norm(c.bisector_normals, axis=1), 1.0)


def test_bisector_normals_point_outward_on_a_clockwise_polygon():
    c = ddg.regular_polygon(7, 2.0)
    np.testing.assert_allclose(c.bisector_normals, c.vertices / 2.0, atol=1e-12)


@pytest.mark.parametrize("value", [True, False, "yes", 1, None])
def test_closed_is_read_only_whatever_is_assigned(value):
    """Assigning closed after the fact once corrupted the caches (an open square's inflated area came
    out 7.14 instead of 5 + pi); now every assignment is refused and the curve keeps its answers."""
    square = [[0, 0], [0, 1], [1, 1], [1, 0]]
    c = ddg.DiscreteCurve(square, closed=False)
    length = c.length
    with pytest.raises(AttributeError, match="closed is read-only"):
        c.closed = value
    assert c.closed is False and c.length == length == 3
    closed = ddg.DiscreteCurve(square)
    assert closed.inflated_area(1) == pytest.approx(5 + np.pi)


@pytest.mark.parametrize("bad, where", [(np.nan, 2), (np.inf, 0), (-np.inf, 4)])
def test_a_discrete_function_with_nan_is_refused_naming_the_vertex(bad, where):
    c = ddg.regular_polygon(6)
    for F in (np.ones(6), np.ones((6, 2))):
        F = F.copy()
        F[where] = bad
        for call in (c.laplacian, lambda F: c.inner(F, F)):
            with pytest.raises(ValueError, match=f"NaN or infinite value at vertex {where}"):
                call(F)


def test_every_module_of_ddg_stays_under_450_lines():
    """CONTRIBUTING's rule that keeps ddg readable beside the lecture: one module, one job."""
    import pathlib

    root = pathlib.Path(ddg.__file__).parent
    long = {p.name: n for p in root.rglob("*.py") if (n := len(p.read_text().splitlines())) > 450}
    assert not long, long
