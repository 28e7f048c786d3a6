"""The chapters' helpers (ddg.notes, and the instructor's instructor.notes), each on its own.

The hidden cells of the chapters import these helpers instead of defining them, so that each can
be tested here, on input drawn at random, against what the chapter says it computes. The last
tests keep it so: no hidden cell defines a helper of more than five lines, the helpers import
without their optional dependencies, their examples run, and none of the answer keys' helpers
reaches the student edition.
"""

import ast
import doctest
import importlib
import json
import pathlib
import pkgutil
import subprocess
import sys
import tomllib

import matplotlib
import numpy as np
import pytest
import shapely
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import ddg
import ddg.notes
from ddg import smooth
from ddg.notes import classical_theorems, convergence, curve_shortening, discrete_curves, inflation
from ddg.notes import smooth_curves, table, winding_number
from instructor import notes as key

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
SEEDS = range(8)


@pytest.fixture
def ax():
    fig, axes = plt.subplots()
    yield axes
    plt.close(fig)


def random_vertices(seed, low=3, high=20):
    rng = np.random.default_rng(seed)
    return rng.uniform(-1, 1, (int(rng.integers(low, high)), 2))


def clockwise(vertices):
    curve = ddg.DiscreteCurve(vertices)
    return curve if curve.signed_area > 0 else ddg.DiscreteCurve(np.asarray(vertices)[::-1])


def circumcentre(a, b, c):
    """The centre of the circle through three points, by the classical formula (an independent check)."""
    d = 2 * (a[0] * (b[1] - c[1]) + b[0] * (c[1] - a[1]) + c[0] * (a[1] - b[1]))
    sq = [p @ p for p in (a, b, c)]
    return np.array([sq[0] * (b[1] - c[1]) + sq[1] * (c[1] - a[1]) + sq[2] * (a[1] - b[1]),
                     sq[0] * (c[0] - b[0]) + sq[1] * (a[0] - c[0]) + sq[2] * (b[0] - a[0])]) / d


polygons = st.integers(0, 10**6).map(random_vertices)


# ------------------------------------------------------------------ chapter 1, smooth curves


@given(st.floats(-3, 3), arrays(float, 5, elements=st.floats(-10, 10)))
def test_plus_is_f_plus_h_times_g_pointwise(h, t):
    f = lambda s: (np.sin(s), s**2)  # noqa: E731
    g = lambda s: (np.cos(3 * s), 1 - s)  # noqa: E731
    x, y = smooth_curves.plus(f, g, h)(t)
    np.testing.assert_allclose(x, np.sin(t) + h * np.cos(3 * t), atol=1e-12)
    np.testing.assert_allclose(y, t**2 + h * (1 - t), atol=1e-12)


@pytest.mark.parametrize("seed", range(4))
def test_the_derivative_of_the_varied_length_is_the_inner_product_with_kappa_N(seed):
    """Theorem 2.2 of the lecture: d/dh L(gamma + h delta) at 0 is <kappa N, delta>, for any delta."""
    a, b, p, q = np.random.default_rng(seed).uniform(-1, 1, 4)
    delta = (lambda t: (a * np.cos(2 * t), b * np.sin(3 * t) + p),
             lambda t: (-2 * a * np.sin(2 * t), 3 * b * np.cos(3 * t)),
             lambda t: (-4 * a * np.cos(2 * t), -9 * b * np.sin(3 * t)))
    ellipse = smooth.ellipse(2.0 + q, 1.0)
    h = 1e-5
    derivative = (smooth_curves.varied(ellipse, delta, h).length - smooth_curves.varied(ellipse, delta, -h).length) / (2 * h)
    t = np.linspace(0, 2 * np.pi, 4001)[:-1]  # a periodic integrand: the trapezoidal rule is spectral
    N_dot_delta = np.einsum("ij,ij->i", ellipse.normal(t), np.stack(delta[0](t), 1))
    inner = np.mean(ellipse.curvature(t) * N_dot_delta * ellipse.speed(t)) * 2 * np.pi
    assert derivative == pytest.approx(inner, abs=1e-7)  # finite differences of h^2 ~ 1e-10, quadrature 1e-10
    assert abs(inner) > 1e-3  # a real test: the derivative is not zero


def test_varied_by_nothing_is_the_curve():
    ellipse = smooth.ellipse(2.0, 1.0)
    zero = (lambda t: (np.zeros_like(t), np.zeros_like(t)),) * 3
    t = np.linspace(0, 6, 50)
    np.testing.assert_array_equal(smooth_curves.varied(ellipse, zero, 0.7).position(t), ellipse.position(t))


@pytest.mark.parametrize("degrees", [21, 25, 40, 80])
def test_the_c_shape_has_its_closed_forms(degrees):
    alpha = np.radians(degrees)
    C = smooth_curves.c_shape(alpha, m=4000)
    theta = 2 * np.pi - 2 * alpha
    assert C.turning_number == 1 and C.signed_area > 0  # clockwise
    assert shapely.LinearRing(C.vertices).is_simple
    assert C.signed_area == pytest.approx(1.5 * theta + np.pi / 4, rel=1e-5)
    assert C.length == pytest.approx(3 * theta + np.pi, rel=1e-5)
    k = C.curvature("angle")  # inside its four arcs: 1/2 on the outer one, 2 on the caps, -1 on the inner one
    for j, kappa in enumerate((0.5, 2, -1, 2)):
        np.testing.assert_allclose(k[j * 3999 + 1:(j + 1) * 3999], kappa, rtol=1e-6)
    caps = [shapely.LineString(C.vertices[j * 3999:(j + 1) * 3999]) for j in (1, 3)]
    assert caps[0].distance(caps[1]) == pytest.approx(3 * np.sin(alpha) - 1, abs=1e-5)


def test_the_c_shape_crosses_itself_once_its_caps_overlap():
    assert not shapely.LinearRing(smooth_curves.c_shape(np.radians(18), m=500).vertices).is_simple  # sin 18° < 1/3


def test_draw_parallels_draws_the_curve_and_each_parallel_curve(ax):
    t = np.linspace(0, 2 * np.pi, 300)
    ellipse = smooth.ellipse(2.0, 1.0)
    position, normal = ellipse.position(t), ellipse.normal(t)
    eroded = shapely.Polygon(position).buffer(-0.5)
    offsets = ((0.2, "C0"), (-0.5, "C5"))
    smooth_curves.draw_parallels(ax, position, normal, eroded, offsets)
    assert len(ax.lines) == 3 and [line.get_label() for line in ax.lines[1:]] == ["+0.2", "−0.5"]
    np.testing.assert_allclose(ax.lines[0].get_xydata(), position)
    for line, (eps, color) in zip(ax.lines[1:], offsets, strict=True):
        np.testing.assert_allclose(line.get_xydata(), position + eps * normal)
        assert line.get_color() == color
    assert len(ax.patches) == 1 and ax.get_aspect() == 1.0  # the eroded region, to scale


def test_draw_c_draws_the_region_its_overlap_and_the_closed_parallel_curve(ax):
    C = smooth_curves.c_shape(np.radians(25), m=200)
    region = shapely.Polygon(C.vertices).buffer(0.2)
    parallel = C.vertices + 0.2 * C.bisector_normals
    smooth_curves.draw_c(ax, C, region, region.intersection(shapely.box(1, -0.1, 2, 0.1)), parallel)
    labels = [artist.get_label() for artist in [*ax.patches, *ax.lines]]
    assert labels == ["within ε", "overlap", "the C", "γ + εN"]
    dashed = ax.lines[-1].get_xydata()
    np.testing.assert_allclose(dashed[:-1], parallel)
    np.testing.assert_allclose(dashed[-1], dashed[0])  # closed


# ------------------------------------------------------------------ chapter 2, discrete curves


@given(polygons)
def test_knot_curvatures_are_the_one_sided_values_the_chapter_gives(v):
    before, after = discrete_curves.knot_curvatures(v)
    Q = ddg.DiscreteCurve(v)
    e, psi = Q.edge_lengths, Q.turning_angles
    np.testing.assert_allclose(before, np.roll(e, 1) * np.sin(psi) / e**2, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(after, np.roll(e, -1) * np.sin(np.roll(psi, -1)) / e**2, rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("seed", SEEDS)
def test_knot_curvatures_agree_on_parallelograms_only(seed):
    rng = np.random.default_rng(seed)
    a, b = rng.uniform(0.3, 2, 2), rng.uniform(0.3, 2, 2) * [-1, 1]
    parallelogram = np.array([[0, 0], a, a + b, b])
    np.testing.assert_allclose(*discrete_curves.knot_curvatures(parallelogram), rtol=1e-12)
    trapezoid = np.array([[0, 0], [0, 1], [1 + rng.uniform(0, 1), 1], [3, 0]])  # clockwise, not a parallelogram
    before, after = discrete_curves.knot_curvatures(trapezoid)
    assert np.abs(before - after).max() > 0.1


def chaikin(points, rounds):
    for _ in range(rounds):
        nxt = np.roll(points, -1, axis=0)
        points = np.stack([0.75 * points + 0.25 * nxt, 0.25 * points + 0.75 * nxt], axis=1).reshape(-1, 2)
    return ddg.DiscreteCurve(points)


@pytest.mark.parametrize("seed", range(4))
def test_knot_curvatures_are_the_limits_of_chaikin_refinement(seed):
    """The discrete curvature of the refined polygon next to each knot tends to the one-sided values."""
    P = ddg.regular_polygon(5).vertices * np.random.default_rng(seed).uniform(0.6, 1.4, (5, 1))
    before, after = discrete_curves.knot_curvatures(P)
    k = chaikin(P, 11).curvature("angle")
    knots = 2**11 * np.arange(5)  # the refined vertex at the end of the knot's edge
    np.testing.assert_allclose(k[knots], before, atol=0.01)
    np.testing.assert_allclose(k[knots + 1], after, atol=0.01)


# ------------------------------------------------------------------ chapter 3, the turning number


def crossings_by_loop(P):
    """Every pair of edges, one at a time: the chapter's first version of crossings."""
    a, b = P.vertices, np.roll(P.vertices, -1, axis=0)
    n, found = len(a), []
    for i in range(n):
        for j in range(i + 1, n):
            if j - i in (1, n - 1):
                continue
            d1, d2, r = b[i] - a[i], b[j] - a[j], a[j] - a[i]
            det = d1[0] * -d2[1] + d2[0] * d1[1]
            if det == 0:
                continue
            s, t = (r[0] * -d2[1] + d2[0] * r[1]) / det, (d1[0] * r[1] - d1[1] * r[0]) / det
            if 0 < s < 1 and 0 < t < 1:
                found.append((a[i] + s * d1, i, j))
    return found


@given(st.integers(0, 10**6).map(lambda seed: random_vertices(seed, 3, 30)))
def test_crossings_are_those_of_a_loop_over_pairs_in_the_same_order(v):
    P = ddg.DiscreteCurve(v)
    got, want = winding_number.crossings(P), crossings_by_loop(P)
    assert [(i, j) for _, i, j in got] == [(i, j) for _, i, j in want]
    for (x, _, _), (y, _, _) in zip(got, want, strict=True):
        np.testing.assert_array_equal(x, y)


@pytest.mark.parametrize("seed", SEEDS)
def test_a_polygon_crosses_itself_exactly_when_shapely_says_so(seed):
    v = random_vertices(seed, 4, 12)
    P = ddg.DiscreteCurve(v)
    found = winding_number.crossings(P)
    assert bool(found) == (not shapely.LinearRing(v).is_simple)
    for x, i, j in found:  # each point lies on both edges
        for k in (i, j):
            assert shapely.LineString([v[k], v[(k + 1) % len(v)]]).distance(shapely.Point(x)) < 1e-12


@pytest.mark.parametrize("seed", SEEDS)
def test_cutting_at_a_crossing_splits_the_turning_number(seed):
    P = ddg.DiscreteCurve(random_vertices(seed, 6, 20))
    v, tested = P.vertices, 0
    for x, i, j in winding_number.crossings(P):
        pieces = [np.vstack([x, v[i + 1:j + 1]]), np.vstack([x, v[j + 1:], v[:i + 1]])]
        if min(map(len, pieces)) >= 3:
            assert sum(ddg.DiscreteCurve(q).turning_number for q in pieces) == P.turning_number
            tested += 1
    assert tested or not winding_number.crossings(P)


# ------------------------------------------------------------------ chapter 5, inflation


@pytest.mark.parametrize("method", ddg.INFLATIONS)
@pytest.mark.parametrize("n", [3, 5, 8])
def test_draw_inflation_draws_a_piece_on_every_edge_and_at_every_corner(ax, method, n):
    curve = ddg.regular_polygon(n, 1.5)
    inflation.draw_inflation(ax, curve, 0.3, method)
    assert len(ax.patches) == 1 + 2 * n
    labelled = [p.get_label() for p in ax.patches if not (p.get_label() or "_").startswith("_")]
    assert labelled == ["$\\Omega_0$", "rectangles, area $\\varepsilon L$", inflation.LABELS[method]]
    corners = ax.patches[1 + n:]
    if method == "minkowski":  # each sector spans the turning angle
        spans = [(w.theta2 - w.theta1) % 360 for w in corners]
        np.testing.assert_allclose(spans, np.degrees(curve.turning_angles))
    else:  # each kite reaches the corner of the offset
        np.testing.assert_allclose([k.get_xy()[2] for k in corners], curve.inflate(0.3, "offset").vertices, atol=1e-12)
    np.testing.assert_allclose(ax.lines[0].get_xydata()[:-1], curve.inflate(0.3, method).vertices)


@pytest.mark.parametrize("i", range(5))
def test_draw_corner_centres_the_corner_and_names_its_angle(ax, i):
    curve = ddg.DiscreteCurve([[0.0, 0.0], [0.3, 1.5], [1.8, 2.0], [3.0, 1.0], [2.4, -0.4]])
    inflation.draw_corner(ax, curve, 0.5, "offset", i)
    assert ax.texts[-1].get_text() == f"$\\psi_i = {np.degrees(curve.turning_angles[i]):.0f}°$"
    x0, x1 = ax.get_xlim()
    assert x1 - x0 == pytest.approx(1.6) and x0 < curve.vertices[i, 0] < x1
    arc = ax.patches[-1]  # from N_{i+1/2} to N_{i-1/2}: the angle psi_i
    assert (arc.theta2 - arc.theta1) % 360 == pytest.approx(np.degrees(curve.turning_angles[i]))


# ------------------------------------------------------------------ chapter 6, Table 1


def chapter_6_polygons(rng, draw):
    """The three families as the chapter drew them before its generators moved (for the same polygons)."""
    if draw == "random":
        while True:
            c = ddg.DiscreteCurve(rng.uniform(-1, 1, (rng.integers(3, 25), 2)))
            if np.abs(c.turning_angles).max() < np.pi - 0.05 and c.edge_lengths.min() > 0.02:
                return c
    if draw == "convex":
        gaps = rng.uniform(1, 3, 7)
        t = 2 * np.pi * np.cumsum(gaps) / gaps.sum()
        return ddg.DiscreteCurve(np.stack([1.5 * np.cos(t), -np.sin(t)], axis=1))
    while True:
        t = np.sort(rng.uniform(0, 2 * np.pi, 9))
        r = rng.uniform(0.5, 1.5, 9)
        c = ddg.DiscreteCurve(np.stack([r * np.cos(t), -r * np.sin(t)], 1))
        if shapely.Polygon(c.vertices).is_valid and c.turning_angles.min() < 0:
            return c


@pytest.mark.parametrize("seed", SEEDS)
def test_the_generators_draw_the_polygons_the_chapter_drew(seed):
    draws = {"random": lambda rng: table.random_polygon(rng), "convex": lambda rng: table.random_convex_polygon(rng, 7),
             "star": lambda rng: table.random_star_polygon(rng, 9)}
    for name, draw in draws.items():
        ours, theirs = np.random.default_rng(seed), np.random.default_rng(seed)
        np.testing.assert_array_equal(draw(ours).vertices, chapter_6_polygons(theirs, name).vertices)
        assert ours.random() == theirs.random()  # and leave the generator where the chapter's did


@pytest.mark.parametrize("seed", SEEDS)
def test_each_generator_keeps_its_promise(seed):
    rng = np.random.default_rng(seed)
    P = table.random_polygon(rng)
    assert 3 <= len(P) < 25 and np.abs(P.turning_angles).max() < np.pi - 0.05 and P.edge_lengths.min() > 0.02
    assert len(table.random_polygon(rng, 11)) == 11
    convex = table.random_convex_polygon(rng, int(rng.integers(3, 20)))
    assert convex.turning_angles.min() > 0 and convex.turning_number == 1
    star = table.random_star_polygon(rng, int(rng.integers(5, 15)))
    assert shapely.Polygon(star.vertices).is_valid and star.turning_angles.min() < 0 and star.signed_area > 0


@pytest.mark.parametrize("seed", SEEDS)
def test_the_offset_hypothesis_holds_on_convex_polygons_at_every_eps(seed):
    convex = table.random_convex_polygon(np.random.default_rng(seed), 8)
    assert all(table.hypothesis_holds(convex, eps) for eps in (0.01, 1.0, 100.0))


def test_the_offset_hypothesis_fails_where_an_edge_between_reflex_corners_vanishes():
    notch = ddg.DiscreteCurve([[0, 0], [0, 2], [0.9, 2], [0.9, 1], [1.1, 1], [1.1, 2], [2, 2], [2, 0]])
    assert table.hypothesis_holds(notch, 0.09) and not table.hypothesis_holds(notch, 0.11)  # it vanishes at 0.1
    mitre = shapely.Polygon(notch.vertices).buffer(0.09, join_style="mitre", mitre_limit=100).area
    assert mitre == pytest.approx(notch.inflated_area(0.09, "offset"), rel=1e-12)  # where it holds, the theorem does


@given(st.integers(0, 10**6), st.floats(0.01, 2.0), st.sampled_from(ddg.CURVATURES))
def test_the_signed_boundary_encloses_the_formula_area(seed, eps, kind):
    c = table.random_polygon(np.random.default_rng(seed))  # self-intersecting mostly, no turn near a reversal
    boundary = table.signed_boundary(c, eps, lambda curve: curve.curvature(kind))
    formula = c.signed_area + eps * c.length + eps**2 / 2 * c.total_curvature(kind)
    assert len(boundary) == 3 * len(c)
    assert boundary.signed_area == pytest.approx(formula, rel=1e-9, abs=1e-9)


def test_the_signed_boundary_of_the_sine_formula_puts_each_apex_at_distance_eps():
    c = table.random_convex_polygon(np.random.default_rng(3), 6)
    apexes = table.signed_boundary(c, 0.4, lambda curve: curve.curvature("sine")).vertices[1::3]
    np.testing.assert_allclose(np.linalg.norm(apexes - c.vertices, axis=1), 0.4)


@pytest.mark.parametrize("seed", SEEDS)
def test_rates_are_the_derivatives_of_length_along_each_unit_velocity(seed):
    P = table.random_polygon(np.random.default_rng(seed))
    rate, steepest = table.rates(P)
    h = 1e-6
    for kind in ddg.CURVATURES:
        V = -P.curvature(kind)[:, None] * P.bisector_normals
        W = V / np.sqrt(P.inner(V, V))  # unit speed in the lecture's inner product
        fd = (ddg.DiscreteCurve(P.vertices + h * W).length - ddg.DiscreteCurve(P.vertices - h * W).length) / (2 * h)
        assert rate[kind] == pytest.approx(fd, rel=1e-5)
        assert rate[kind] >= steepest * (1 + 1e-9)  # none steeper than the gradient
    assert rate["sine"] == pytest.approx(steepest, rel=1e-12)


def test_every_rate_is_the_steepest_on_a_regular_polygon():
    rate, steepest = table.rates(ddg.regular_polygon(9, 0.7))
    np.testing.assert_allclose(list(rate.values()), steepest, rtol=1e-12)


def test_draw_fillings_outlines_each_region_with_its_area(ax):
    c = ddg.DiscreteCurve([[-3.0, 0.0], [0.0, 0.0], [-0.5, -(0.75**0.5)]])
    region = shapely.Polygon(c.vertices)
    fillings = [("round", region.buffer(0.5), "C1", "-"), ("mitre", region.buffer(0.5, join_style="mitre"), "C3", ":")]
    table.draw_fillings(ax, c, fillings)
    for line, (name, geometry, color, style) in zip(ax.lines, fillings, strict=False):
        assert line.get_label() == f"{name}: area {geometry.area:.3f}"
        assert (line.get_color(), line.get_linestyle()) == (color, style)
        np.testing.assert_allclose(line.get_xydata(), np.asarray(geometry.exterior.coords))
    assert len(ax.lines) == len(fillings) + 1  # and the triangle


# ------------------------------------------------------------------ chapter 7, convergence


@pytest.mark.parametrize("n", [3, 8, 100])
def test_the_largest_distance_of_a_regular_polygon_is_at_its_edge_midpoints(n):
    assert convergence.largest_distance(ddg.regular_polygon(n)) == pytest.approx(1 - np.cos(np.pi / n), rel=1e-12)


def test_the_largest_distance_sees_a_vertex_pushed_off_the_circle():
    v = ddg.regular_polygon(64).vertices.copy()
    v[5] *= 1.3
    assert convergence.largest_distance(ddg.DiscreteCurve(v)) == pytest.approx(0.3, rel=1e-12)


def test_the_distance_to_the_circle_vanishes_for_regular_polygons_at_their_orders():
    ns = np.array([32, 64, 128, 256])
    parts = np.array([convergence.distance_to_circle(ddg.regular_polygon(int(n))) for n in ns])
    slopes = np.polyfit(np.log(ns), np.log(parts), 1)[0]
    assert slopes[0] == pytest.approx(-2, abs=0.05) and slopes[1] == pytest.approx(-1, abs=0.05)


def test_a_zigzag_keeps_its_tangent_part_as_its_position_part_vanishes():
    parts = []
    for n in (64, 256, 1024):
        theta, radius = 2 * np.pi * np.arange(n) / n, 1 + (-1.0) ** np.arange(n) / n
        parts.append(convergence.distance_to_circle(ddg.DiscreteCurve(np.c_[radius * np.cos(theta), -radius * np.sin(theta)])))
    position, tangent = np.array(parts).T
    assert np.all(np.diff(position) < 0) and position[-1] < 0.01
    assert np.all(np.abs(tangent - 2) < 0.1)  # the edges never line up with the circle


def test_the_distance_to_the_circle_sees_where_the_polygon_starts():
    regular = ddg.regular_polygon(100)
    turned = ddg.DiscreteCurve(np.roll(regular.vertices, 25, axis=0))  # the same polygon from v_25
    assert convergence.distance_to_circle(turned)[0] > 100 * convergence.distance_to_circle(regular)[0]


def circle_tangent(fraction):
    s = 2 * np.pi * fraction
    return np.stack([-np.sin(s), -np.cos(s)], axis=-1)


@pytest.mark.parametrize("n", [6, 64, 512])
def test_the_worst_angle_of_a_regular_polygon_is_half_its_turn(n):
    assert convergence.worst_angle(ddg.regular_polygon(n), circle_tangent) == pytest.approx(np.pi / n, rel=1e-9)


@pytest.mark.parametrize("n", [256, 4096])
def test_the_worst_angle_of_a_zigzag_stays_as_its_vertices_approach_the_circle(n):
    theta, radius = 2 * np.pi * np.arange(n) / n, 1 + 0.5 * (-1.0) ** np.arange(n) / n
    zigzag = ddg.DiscreteCurve(np.c_[radius * np.cos(theta), -radius * np.sin(theta)])
    # each edge tilts by about 2 delta / h = 1 / (2 pi), and the circle turns by pi / n along it
    tilt = np.arctan(1 / (2 * np.pi)) + np.pi / n
    assert convergence.worst_angle(zigzag, circle_tangent) == pytest.approx(tilt, rel=0.01)


# ------------------------------------------------------------------ chapter 8, classical theorems


def test_draw_sequences_draws_each_curvature_once_around(ax):
    c = ddg.DiscreteCurve(random_vertices(4, 5, 9))
    sequences = {kind: c.curvature(kind) for kind in ddg.CURVATURES}
    classical_theorems.draw_sequences(ax, sequences)
    assert [line.get_label() for line in ax.lines] == list(ddg.CURVATURES)
    for line, k in zip(ax.lines, sequences.values(), strict=True):
        np.testing.assert_array_equal(line.get_ydata(), np.append(k, k[0]))
        np.testing.assert_array_equal(line.get_xdata(), np.arange(len(c) + 1))
    assert [t.get_text() for t in ax.get_xticklabels()] == [*map(str, range(len(c))), "0"]


# ------------------------------------------------------------------ chapter 9, curve-shortening flow


def test_extrapolation_cancels_an_error_of_first_order_in_the_step():
    """Areas with an error c dt g(t), sampled at different times: 2 A(dt/2) - A(dt) leaves the exact rate."""
    from types import SimpleNamespace

    exact = lambda t: 4 - 2 * np.pi * t + 0.3 * np.sin(t)  # noqa: E731
    error = lambda t: 0.8 * t**2  # noqa: E731
    dt = 0.01
    rough_t, fine_t = np.sort(np.r_[0, np.random.default_rng(0).uniform(0, 1, 300), 1]), np.linspace(0, 1, 777)
    rough = SimpleNamespace(times=rough_t, areas=exact(rough_t) + dt * error(rough_t))
    fine = SimpleNamespace(times=fine_t, areas=exact(fine_t) + dt / 2 * error(fine_t))
    t, rate = curve_shortening.extrapolated_rate(fine, rough)
    np.testing.assert_array_equal(t, np.linspace(0, 1, 101))
    want = 2 * np.pi - 0.3 * np.cos(t)
    assert np.abs(rate - want)[1:-1].max() < 2e-3  # interpolation and differences, not the step's error
    naive = -np.gradient(np.interp(t, rough.times, rough.areas), t)
    assert np.abs(naive - want)[1:-1].max() > 5 * np.abs(rate - want)[1:-1].max()


def test_the_extrapolated_rate_of_a_flowing_regular_polygon_is_its_closed_form():
    polygon = ddg.regular_polygon(16)
    t_end = 0.5 * polygon.signed_area / (2 * np.pi)
    runs = [ddg.flow.flow(polygon, "sine", t_end, safety=s, lifetime_fraction=0.08 * s, snapshots=0, progress=False)
            for s in (0.125, 0.25)]
    t, rate = curve_shortening.extrapolated_rate(*runs)
    closed = 16 * np.sin(2 * np.pi / 16)  # the sine flow keeps it regular, losing area at this rate
    before_the_last_steps = t < 0.9 * t_end  # where the runs shorten their steps to end at t_end
    assert np.abs(rate - closed)[before_the_last_steps].max() < 1e-9
    assert np.abs(runs[1].area_rate() + closed).min() > 0.01  # the default step alone is off by 0.03


# ------------------------------------------------------------------ the instructor's: answer keys and solutions


@pytest.mark.parametrize("seed", SEEDS)
def test_the_local_boundary_of_a_convex_polygon_is_its_minkowski_sum(seed):
    P = table.random_convex_polygon(np.random.default_rng(seed), 7)
    eps = 0.3
    boundary = key.local_boundary(P, eps, step=0.002)
    assert boundary.is_valid
    assert boundary.area == pytest.approx(P.inflated_area(eps, "minkowski"), rel=1e-6)  # chords of 0.002 rad
    assert key.minkowski_hypothesis_holds(P, eps)


def test_the_minkowski_picture_fails_past_the_slot():
    slot = ddg.DiscreteCurve([[0, 0], [0, 2], [2, 2], [2, 0], [1.05, 0], [1.05, 1.5], [0.95, 1.5], [0.95, 0]])
    assert key.minkowski_hypothesis_holds(slot, 0.049)
    assert not key.minkowski_hypothesis_holds(slot, 0.051) and not key.local_boundary(slot, 0.051).is_valid


@pytest.mark.parametrize("seed", SEEDS)
def test_inside_circles_says_which_neighbours_the_circumcircles_hold(seed):
    c = table.random_convex_polygon(np.random.default_rng(seed), 9)
    v, n = c.vertices, len(c)
    after, before = key.inside_circles(c)
    for i in range(n):
        o = circumcentre(v[i - 1], v[i], v[(i + 1) % n])
        R = np.linalg.norm(v[i] - o)
        assert after[i] == (np.linalg.norm(v[(i + 2) % n] - o) < R)
        assert before[i] == (np.linalg.norm(v[i - 2] - o) < R)
    assert np.sum(after == before) >= 4  # Ovsienko-Tabachnikov: at least four extremal circles


@pytest.mark.parametrize("t0", [0.3, 1.1, 2.0, 4.0])
def test_equal_chords_are_equal_and_put_the_vertex_on_their_circle(t0):
    ellipse = smooth.ellipse(2.0, 1.0)
    c = key.equal_chords(ellipse, t0, 0.05)
    np.testing.assert_allclose(c.edge_lengths, 0.05, rtol=1e-12)
    np.testing.assert_array_equal(c.vertices[1], ellipse.position(t0))
    o = circumcentre(*c.vertices)  # equal edges: the sine formula is 1/R of the circle through the three
    assert c.curvature("sine")[0] == pytest.approx(1 / np.linalg.norm(c.vertices[1] - o), rel=1e-9)


# ------------------------------------------------------------------ the rules that keep it so


HIDDEN = {"hide-input", "hide-cell", "remove-input", "remove-cell", "answer-key", "answer-stub"}
"""Tags of the cells whose code a reader of the book does not see unfolded."""

LONGEST = 5
"""Lines a helper defined in a hidden cell may have: anything longer goes into ddg.notes (or instructor.notes)."""


def long_definitions(source):
    """``[(name, lines)]`` of the functions and classes a cell defines outside any function, over LONGEST lines."""
    found, todo = [], list(ast.parse(source).body)
    while todo:
        node = todo.pop()
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            first = min([d.lineno for d in node.decorator_list] + [node.lineno])
            if node.end_lineno - first + 1 > LONGEST:
                found.append((node.name, node.end_lineno - first + 1))
        else:  # inside if, for, with, try: still defined at the cell's level
            todo += [child for child in ast.iter_child_nodes(node) if isinstance(child, ast.stmt)]
    return found


def hidden_cells():
    for path in sorted((ROOT / "book").glob("*.ipynb")):
        for cell in json.loads(path.read_text())["cells"]:
            if cell["cell_type"] == "code" and HIDDEN & set(cell["metadata"].get("tags", [])):
                yield path.name, cell["id"], "".join(cell["source"])


def test_no_hidden_cell_defines_a_helper_longer_than_five_lines():
    long = {(name, cid): found for name, cid, source in hidden_cells() if (found := long_definitions(source))}
    assert not long, f"move these into ddg/notes (or, for an answer key, instructor/notes.py): {long}"


@pytest.mark.parametrize("source, found", [
    ("def f(x):\n    return x\n", []),
    ("def f(x):\n    a = 1\n    b = 2\n    c = 3\n    return a + b + c + x\n", []),  # five lines: fine
    ("def f(x):\n    a = 1\n    b = 2\n    c = 3\n    d = 4\n    return a + b + c + d\n", [("f", 6)]),
    ("@np.vectorize\ndef f(x):\n    a = 1\n    b = 2\n    c = 3\n    return a + b + c\n", [("f", 6)]),
    ("x = 1\nif x:\n    def g():\n        '''\n        a\n        b\n        c\n        '''\n", [("g", 6)]),
    ("with open('f') as f:\n    for _ in f:\n        def g(\n            a,\n            b,\n        ):\n            return a\n", [("g", 5 + 0)]),
    ("class K:\n    a = 1\n    b = 2\n    c = 3\n    d = 4\n    e = 5\n", [("K", 6)]),
    ("def f():\n    def inner():\n        return 1\n    return inner\n", []),
])
def test_the_scan_counts_the_lines_of_every_definition_at_a_cells_level(source, found):
    assert long_definitions(source) == [(name, lines) for name, lines in found if lines > LONGEST]


def test_the_scan_sees_every_hidden_cell_and_the_helpers_are_imported_there():
    cells = {(name, cid): source for name, cid, source in hidden_cells()}
    assert len(cells) > 60
    imports = "\n".join(cells.values())
    for module in ("smooth_curves", "discrete_curves", "winding_number", "inflation", "table", "convergence",
                   "classical_theorems", "curve_shortening"):
        assert f"from ddg.notes.{module} import" in imports or f"from ddg.notes import {module}" in imports, module
    assert imports.count("from instructor.notes import") == 3  # chapter 5's and 8's answer keys, chapter 10's solution


NOTES = sorted(info.name for info in pkgutil.iter_modules(ddg.notes.__path__, "ddg.notes."))


@pytest.mark.parametrize("module", ["ddg.notes", *NOTES, "instructor.notes"])
def test_the_examples_in_the_docstrings_run(module):
    result = doctest.testmod(importlib.import_module(module), optionflags=doctest.ELLIPSIS)
    assert result.failed == 0 and (result.attempted > 0 or module == "ddg.notes")


def test_every_function_has_a_docstring_with_an_example():
    for name in [*NOTES, "instructor.notes"]:
        module = importlib.import_module(name)
        for attribute, value in vars(module).items():
            if callable(value) and getattr(value, "__module__", None) == name and not attribute.startswith("_"):
                assert ">>> " in (value.__doc__ or ""), f"{name}.{attribute} has no example"


BLOCKED = """
import sys
for name in ("matplotlib", "shapely"):
    sys.modules[name] = None  # as if not installed
import importlib, pkgutil
import ddg, ddg.notes
for info in pkgutil.iter_modules(ddg.notes.__path__, "ddg.notes."):
    importlib.import_module(info.name)
from ddg.notes import discrete_curves, table
import numpy as np
print(discrete_curves.knot_curvatures([[0, 0], [0, 1], [1, 1], [1, 0]])[0].tolist())
print(len(table.random_convex_polygon(np.random.default_rng(0), 5)))
for use in (lambda: table.random_star_polygon(np.random.default_rng(0), 5), lambda: ddg.notes.inflation.draw_corner(None, ddg.regular_polygon(3), 0.1, "offset", 0)):
    try:
        use()
    except ImportError as error:
        print(error)
"""


def test_the_helpers_import_without_matplotlib_and_shapely_and_name_the_extra_when_used():
    done = subprocess.run([sys.executable, "-c", BLOCKED], capture_output=True, text=True, cwd=ROOT,
                          env={"PYTHONPATH": str(ROOT), "PATH": ""})
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[:2] == ["[1.0, 1.0, 1.0, 1.0]", "5"]
    assert len(lines) == 4 and all("pip install" in line and "[" in line for line in lines[2:]), lines


def test_no_answer_key_helper_is_in_ddg_and_ddg_notes_ships_in_the_wheel():
    """The student edition copies ddg/ as it is: the answer keys' helpers must live in instructor/."""
    tree = ast.parse("\n".join(p.read_text() for p in (ROOT / "ddg").rglob("*.py")))
    defined = {node.name for node in ast.walk(tree) if isinstance(node, ast.FunctionDef)}
    instructors = {"local_boundary", "minkowski_hypothesis_holds", "inside_circles", "equal_chords"}
    answers = {"circle_k", "circle_curvature", "theorem_area", "minkowski_area", "zigzag_exponent"}
    assert not defined & (instructors | answers) and all(callable(getattr(key, name)) for name in instructors)
    imported = {alias.name for node in ast.walk(tree) if isinstance(node, ast.Import) for alias in node.names}
    imported |= {node.module for node in ast.walk(tree) if isinstance(node, ast.ImportFrom) and node.module}
    assert not {name for name in imported if name.split(".")[0] == "instructor"}
    packages = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["packages"]
    found = {".".join(p.parent.relative_to(ROOT).parts) for p in (ROOT / "ddg").rglob("__init__.py")}
    assert set(packages) == found


def test_the_leak_guard_looks_into_the_notes(tmp_path, monkeypatch):
    """A helper that answers an exercise, planted in a package of notes, is named by the guard."""
    from instructor import guard

    planted = tmp_path / "planted_notes"
    planted.mkdir()
    (planted / "__init__.py").write_text("")
    (planted / "chapter.py").write_text(
        "import numpy as np\n\n\n"
        "def turns(vertices):\n"
        "    v = np.asarray(vertices, float)\n"
        "    a, b = v - np.roll(v, 1, axis=0), np.roll(v, -1, axis=0) - v\n"
        "    psi = np.arctan2(a[:, 1] * b[:, 0] - a[:, 0] * b[:, 1], (a * b).sum(1))\n"
        "    return np.where(psi <= -np.pi, np.pi, psi)\n\n\n"
        "def harmless(vertices):\n"
        "    return np.zeros(len(vertices))\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    found = guard.notes_leaks(b"0123456789abcdef", package="planted_notes")
    assert found == [("planted_notes.chapter.turns", ["turning_angles"])]


def test_no_cell_of_the_student_edition_imports_the_instructors_notes():
    """The cells that import instructor.notes are answer keys or solutions, which the edition leaves out."""
    import nbformat

    from instructor import edition

    kept = 0
    for path in sorted((ROOT / "book").glob("*.ipynb")):
        student = edition.student_notebook(nbformat.read(path, as_version=4))
        assert not [c.source for c in student.cells if "instructor" in c.source], path.name
        kept += sum("from ddg.notes" in c.source for c in student.cells)
    assert kept >= 12  # while the chapters' own helpers stay, from ddg.notes
