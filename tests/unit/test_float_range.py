"""ddg over the whole float range, against an exact or high-precision reference (property-based).

Hypothesis draws polygons at scales from 1e-308 to 1e308 (a power of two times small numbers, so
the scale itself is exact), offsets up to 1e15, turns within 1e-17 of a reversal and exact
reversals, vertices a few units in the last place apart; and inputs of the wrong kind (masked,
ragged, object arrays of text, huge Python ints). Every result is compared with a reference
computed from the exact coordinates in 80-digit decimals (``decimal``) or exactly (``fractions``),
or the input must be refused with an error of ``ddg.errors`` that names the problem.

The tolerances are what the docstrings promise: a length to a rounding error of itself; a turning
angle within 4.4e-16 rad of the exact turn (1e-15 here), and tan(psi/2) within 4e-15 of itself
wherever the turn exceeds a right angle; a curvature to those, relative to itself and to its
scale 1/A_i; the area within 1e-13 of the exact one. A value below the normal range (2.2e-308) is compared
to its last subnormal bits. Warnings are errors here: no raw numpy warning may reach a user.
"""

import decimal
import fractions
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import ddg
from ddg.flow import flow

pytestmark = pytest.mark.filterwarnings("error")
CurveError = getattr(ddg, "CurveError", ValueError)
D = decimal.Context(prec=80, Emin=-99999, Emax=99999)
TINY = 4 * 5e-324
BIG = np.finfo(float).max


def dec(x):
    """A Fraction (or float) as an 80-digit Decimal."""
    x = fractions.Fraction(x)
    return D.divide(D.create_decimal(x.numerator), D.create_decimal(x.denominator))


def reference(v):
    """Exact edges, dot and cross products (fractions), then lengths, tan(psi/2) (+inf at an exact
    reversal) and A_i in 80 digits, and the exact area."""
    n = len(v)
    f = [(fractions.Fraction(float(x)), fractions.Fraction(float(y))) for x, y in v]
    e = [(f[(i + 1) % n][0] - f[i][0], f[(i + 1) % n][1] - f[i][1]) for i in range(n)]
    lengths = [D.sqrt(dec(x * x + y * y)) for x, y in e]
    t = []
    for i in range(n):
        (ax, ay), (bx, by) = e[i - 1], e[i]
        dot, minus_cross, ll = ax * bx + ay * by, ay * bx - ax * by, D.multiply(lengths[i - 1], lengths[i])
        if dot >= 0:
            t.append(D.divide(dec(minus_cross), D.add(ll, dec(dot))))
        elif minus_cross == 0:
            t.append(decimal.Decimal("Infinity"))
        else:
            t.append(D.divide(D.subtract(ll, dec(dot)), dec(minus_cross)))
    A = [D.divide(D.add(lengths[i - 1], lengths[i]), 2) for i in range(n)]
    area = -sum(f[i][0] * f[(i + 1) % n][1] - f[(i + 1) % n][0] * f[i][1] for i in range(n)) / 2
    return lengths, t, A, area


def close(got, want, rel, scale=0.0):
    """``got`` within ``rel`` of ``want`` (a Decimal) and of ``scale``, or both below the normal range."""
    want = float(want) if abs(want) < decimal.Decimal("1e400") else math.copysign(math.inf, want)
    return abs(got - want) <= max(rel * (abs(want) + scale), TINY)


def psi_of(t):
    return 2 * math.atan(float(t)) if t != decimal.Decimal("Infinity") else math.pi


# ------------------------------------------------------------------------------- polygons


@st.composite
def polygons(draw):
    n = draw(st.integers(3, 7))
    base = draw(st.lists(st.tuples(st.integers(-9, 9), st.integers(-9, 9)), min_size=n, max_size=n))
    v = np.array(base, dtype=float) + np.array(draw(st.lists(st.tuples(st.floats(-0.5, 0.5), st.floats(-0.5, 0.5)),
                                                             min_size=n, max_size=n)))
    shape = draw(st.sampled_from(["plain", "near reversal", "reversal", "near duplicate"]))
    if shape != "plain":  # vertex 1 between 0 and 2, or a rounding error away
        i = 1
        s = draw(st.floats(0.1, 0.9)) if shape != "near duplicate" else 1.0
        v[i] = v[0] + s * (v[2] - v[0]) if shape != "near duplicate" else np.nextafter(v[0], 100.0)
        if shape == "near reversal":
            v[i] = v[0] + (1.0 + draw(st.floats(0.1, 2.0))) * (v[2] - v[0])  # past v_2: the turn back
            v[i, 1] += draw(st.sampled_from([1e-17, -3e-16, 1e-12, 2.0**-60]))
        elif shape == "reversal":
            v[i] = v[0] + 2.0 * (v[2] - v[0])  # exactly on the line, beyond v_2: psi = pi
    exponent = draw(st.sampled_from([0, 0, -1000, -900, -500, 500, 900, 1015, 1019, 1020, 1021]))
    offset = draw(st.sampled_from([0.0, 0.0, 1e3, -1e9, 1e15]))
    with np.errstate(over="ignore"):
        while not np.isfinite(scaled := np.ldexp(v, exponent) + offset).all():  # keep it finite
            exponent -= 1
    return scaled


def exactly(v):
    return [(fractions.Fraction(float(x)), fractions.Fraction(float(y))) for x, y in v]


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(polygons())
def test_every_quantity_is_right_or_refused_at_every_scale(v):
    n = len(v)
    try:
        c = ddg.DiscreteCurve(v)
    except CurveError as refusal:
        exact = exactly(v)
        if any(exact[i] == exact[(i + 1) % n] for i in range(n)):
            assert "equal" in str(refusal) or "repeats" in str(refusal)
            return
        lengths, *_ = reference(v)
        assert sum(lengths) > decimal.Decimal(BIG), f"refused a curve of length {sum(lengths):.3e}: {refusal}"
        assert "largest float" in str(refusal)
        return
    lengths, t, A, area = reference(v)
    for i in range(n):
        assert close(c.edge_lengths[i], lengths[i], 1e-15), ("edge", i)
        assert close(c.dual_lengths[i], A[i], 1e-15), ("A", i)
        psi = psi_of(t[i])
        assert abs(c.turning_angles[i] - psi) <= 1e-15 or abs(abs(c.turning_angles[i]) - math.pi) < 1e-15 \
            and abs(abs(psi) - math.pi) < 1e-15, ("psi", i, c.turning_angles[i], psi)
    assert close(c.length, sum(lengths), 1e-14)
    assert [i for i in range(n) if t[i] == decimal.Decimal("Infinity")] == \
        [i for i in range(n) if np.isposinf(getattr(c, "tan_half_psi", np.zeros(n))[i])] or not hasattr(c, "reversals")
    for kind in ddg.CURVATURES:
        try:
            k = c.curvature(kind)
        except CurveError as refusal:
            assert "straight back" in str(refusal) and kind == "tangent" or "largest float" in str(refusal), refusal
            continue
        for i in range(n):
            psi = psi_of(t[i])
            if kind == "angle":
                want = D.divide(dec(psi), A[i])
            elif kind == "sine":
                want = D.divide(dec(2 * math.sin(psi / 2)), A[i])
            else:
                want = D.divide(D.multiply(2, t[i]), A[i])
            assert close(k[i], want, 4e-15 if kind == "tangent" else 1e-15, float(1 / A[i])), (kind, i, k[i], want)
    try:
        got = c.signed_area
    except CurveError as refusal:
        assert abs(area) > BIG, refusal
    else:
        assert close(got, decimal.Decimal(area.numerator) / decimal.Decimal(area.denominator), 1e-13), (got, area)


# ----------------------------------------------------------------- inputs of the wrong kind


@settings(max_examples=100, deadline=None)
@given(st.integers(3, 6), st.integers(0, 5), st.sampled_from(["masked", "ragged", "text", "huge int", "None",
                                                              "complex", "nan", "long double"]))
def test_inputs_of_the_wrong_kind_are_refused_naming_the_vertex(n, at, kind):
    at = at % n
    v = [[float(i), float(i * i % 5)] for i in range(n)]
    if kind == "masked":
        mask = np.zeros((n, 2), dtype=bool)
        mask[at, 1] = True
        data = np.ma.masked_array(np.array(v), mask=mask)
        data.data[at, 1] = 1e6  # what the mask hides must not count
    else:
        data = [list(row) for row in v]
        data[at] = {"ragged": [1.0], "text": [1.0, "2"], "huge int": [1.0, 10**400], "None": [None, 1.0],
                    "complex": [1.0, 1j], "nan": [1.0, float("nan")], "long double": [1.0, 1.0]}[kind]
        if kind == "long double":
            data = np.array(data, dtype=np.longdouble)
            data[at, 1] = np.longdouble(10) ** 400
    with pytest.raises(CurveError) as refusal:
        ddg.DiscreteCurve(data)
    message = str(refusal.value)
    assert f"vertex {at}" in message or kind in ("text", "complex") and "real numbers" in message, message
    if kind in ("huge int", "long double"):
        assert isinstance(refusal.value, getattr(ddg, "OutOfRangeError", ValueError)) and "largest float" in message


def test_a_masked_array_without_masked_entries_is_its_data():
    v = np.ma.masked_array([[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]], mask=False)
    assert ddg.DiscreteCurve(v).signed_area == ddg.DiscreteCurve(v.data).signed_area == 0.5


# --------------------------------------------------------------------- smooth curves and flows


@settings(max_examples=60, deadline=None)
@given(st.integers(-1020, 1020), st.floats(0.5, 1.0))
def test_a_circle_at_any_scale_has_length_2_pi_r_and_curvature_1_over_r(exponent, mantissa):
    r = math.ldexp(mantissa, exponent)
    try:
        circle = ddg.smooth.circle(r)
        length = circle.length
    except CurveError as refusal:
        assert 2 * math.pi * r > BIG / 8 and "largest float" in str(refusal)
        return
    assert length == pytest.approx(2 * math.pi * r, rel=1e-13)
    assert float(circle.curvature(0.7)) == pytest.approx(1 / r, rel=1e-14) or 1 / r > BIG


@settings(max_examples=12, deadline=None)
@given(st.sampled_from([1e3, 1e9, 1e15, -3e14]), st.integers(-40, 40), st.sampled_from(ddg.CURVATURES))
def test_a_flow_far_from_the_origin_is_the_run_at_the_origin_translated(offset, exponent, kind):
    try:
        polygon = ddg.regular_polygon(12, math.ldexp(1.0, exponent), center=(offset, offset))
    except CurveError as refusal:  # too small for its place: vertices round onto each other there
        assert "are equal" in str(refusal) and math.ldexp(1.0, exponent) < 1e-6 * abs(offset)
        return
    near = ddg.DiscreteCurve(polygon.vertices - polygon.vertices[0])  # exact: neighbouring floats
    far_run, near_run = (flow(c, kind, math.ldexp(1.0, 2 * exponent), progress=False, snapshots=5)
                         for c in (polygon, near))
    assert far_run.stopped == near_run.stopped
    for name in ("times", "lengths", "areas", "turning_numbers"):
        np.testing.assert_array_equal(getattr(far_run, name), getattr(near_run, name))
    for (t, far), (s, close_by) in zip(far_run.snapshots, near_run.snapshots, strict=True):
        placed = far.vertices + getattr(far_run, "origin", 0.0) - polygon.vertices[0]
        assert t == s and np.abs(placed - close_by.vertices).max() <= 4 * np.spacing(np.abs(polygon.vertices).max())


# ----------------------------------------------------- what a new user tried (a helper, December 2026)


@pytest.mark.parametrize(("make", "hint"), [
    (lambda: zip([0, 1, 2], [0, 1, 0], strict=True), "list(zip(...))"), (lambda: (p for p in [[0, 0], [1, 1], [1, 0]]), "list(...)"),
    (lambda: ddg.regular_polygon(4), "its .vertices"), (lambda: ddg.smooth.circle(), ".sample(n)"),
    (lambda: "abc", "not text"), (lambda: b"ab", "not text"), (lambda: 5.0, "got a float"), (lambda: None, "NoneType"),
])
def test_what_is_not_an_array_is_refused_saying_what_to_use(make, hint):
    with pytest.raises(ddg.InputError) as refusal:
        ddg.DiscreteCurve(make())
    assert hint in str(refusal.value) and "shape (n, 2)" in str(refusal.value)


def test_a_curve_cannot_be_changed_after_it_is_made():
    c = ddg.DiscreteCurve([[0, 0], [0, 1], [1, 1], [1, 0]])
    for name in ("turning_angles", "signed_area", "closed", "anything"):
        with pytest.raises(AttributeError, match=f"{name} is read-only"):
            setattr(c, name, 0)
        with pytest.raises(AttributeError, match="read-only"):
            delattr(c, name)
    assert c.turning_number == 1 and c.signed_area == 1.0 and np.all(c.curvature("tangent") == 2)
    gradient = c.length_gradient()  # a new array at every call: the caller's to change
    gradient *= 2
    assert np.array_equal(c.length_gradient() * 2, gradient)


@pytest.mark.parametrize("t", ["0.3", np.nan, [0.1, np.inf], None, "abc"])
def test_a_smooth_curve_refuses_parameters_that_are_not_numbers(t):
    with pytest.raises(ddg.InputError, match="t must be finite real numbers"):
        ddg.smooth.circle(2.0).curvature(t)


def test_a_smooth_curvature_beyond_the_floats_is_refused():
    with pytest.raises(ddg.OutOfRangeError, match="beyond the largest float"):
        ddg.smooth.ellipse(1.0, 1e-300).curvature(0.0)


@pytest.mark.parametrize("seed", ["a", 1.5, True])
def test_a_check_refuses_a_seed_that_is_not_a_whole_number(seed):
    from ddg.checks import check_turning_angles

    with pytest.raises(ddg.InputError, match="seed must be a whole number"):
        check_turning_angles(lambda vertices: vertices, seed=seed)


# ------------------------------------------------------------ what a reviewer found (a helper, December 2026)


@pytest.mark.parametrize("d", [1e-170, 1e-160, 1e-200, 2.0**-1000])
def test_a_tiny_edge_beside_a_unit_edge_turns_exactly(d):
    """The exact cross product scales each edge on its own: scaled together, d * d underflowed to 0
    and the turn at vertex 1 was called a reversal."""
    v = np.array([[d, 0.0], [0.0, 0.0], [1.0, d], [0.5, 3.0]])
    c = ddg.DiscreteCurve(v)
    _, t, _, _ = reference(v)
    assert len(c.reversals) == 0 and c.turning_number == 0
    assert close(c.tan_half_psi[1], t[1], 1e-15)


def test_a_subnormal_edge_has_unit_tangents_and_normals():
    c = ddg.DiscreteCurve([[0.0, 0.0], [5e-324, 0.0], [5e-324, 5e-324]])
    np.testing.assert_allclose(np.linalg.norm(c.tangents, axis=1), 1.0, rtol=1e-15)
    np.testing.assert_allclose(np.linalg.norm(c.bisector_normals, axis=1), 1.0, rtol=1e-15)


def test_a_run_too_short_to_take_a_step_ends_with_its_first_state():
    run = flow(ddg.DiscreteCurve(ddg.regular_polygon(12).vertices * 1e100), "sine", 1e-300, progress=False)
    assert run.stopped == "reached t_end" and len(run.snapshots) >= 1


@pytest.mark.parametrize(("vertices", "said"), [
    ([[0, 0], [1, 0], ["1", 0]], "vertex 2 has a coordinate that is not a real number"),
    ([[0, 0], [1, 0], [1j, 0]], "vertex 2 has a coordinate that is not a real number"),
    ([[0, 0], [np.ma.masked, 1], [1, 1], [1, 0]], "vertex 1 has a masked coordinate"),
])
def test_text_and_masked_entries_in_a_list_are_named_where_they_are(vertices, said):
    with pytest.raises(ddg.InputError, match=said):
        ddg.DiscreteCurve(vertices)


def test_no_array_behind_a_curves_lengths_is_writable():
    c = ddg.DiscreteCurve([[0, 0], [0, 1], [1, 1], [1, 0]])
    for array in (c.edge_lengths, c.dual_lengths, c.vertices, c.tan_half_psi):
        base = array
        while base is not None:
            if isinstance(base, np.ndarray):
                assert not base.flags.writeable
            base = getattr(base, "base", None) if not isinstance(base, memoryview) else base.obj
