"""ddg computes the turns and the curvatures block by block (``ddg._numerics.BLOCK``, 2^15 turns):
where the blocks begin and end changes nothing.

Each curve is computed again with blocks of 1, 2, 3, 5 and 64 turns, so that every vertex lies on a
block's first or last turn somewhere, and must give the same bits: edges, lengths, tan(psi/2), the
reversals and all three curvatures, or the same refusal. The curves are drawn with a seeded rng:
closed and open, from 2 vertices up, with exact and near reversals (a vertex in the middle of its
neighbours' line, or just off it), at scales whose edges lie outside ``_numerics.SAFE`` (where
``tan_half_turn`` rescales each edge), with repeated vertices and NaN; and one closed and one open
curve of more than two default blocks.
"""

import fractions

import numpy as np
import pytest

import ddg
from ddg import _numerics

SIZES = (1, 2, 3, 5, 64)


def drawn(rng, count):
    """``count`` polygons (vertices, closed) of every kind the docstring lists."""
    found = []
    for i in range(count):
        closed = bool(i % 2)
        n = int(rng.integers(3 if closed else 2, 40))
        v = rng.normal(size=(n, 2))
        if i % 5 == 0:
            v = np.round(v * 4) / 4  # a lattice: exact reversals and repeated vertices
        if i % 3 == 0 and n >= 3:  # a reversal at vertex j: v_j beyond v_(j+1) on the line from v_(j-1), or just off it
            j = int(rng.integers(1, n - 1))
            v[j] = v[j - 1] + 2 * (v[j + 1] - v[j - 1]) + (0 if i % 2 else rng.normal(size=2) * 1e-13)
        if i % 7 == 0:
            v = v * 2.0 ** rng.choice([-700, -520, 520, 700])  # edges outside SAFE, exactly
        if i % 13 == 0:  # one edge outside SAFE in a curve of unit size: every length by hypot
            j = int(rng.integers(0, n - 1))
            v = v - v[j]  # at the origin, where a step of 1e-160 is not lost
            v[j + 1] = rng.normal(size=2) * 1e-160
        if i % 11 == 0:
            v[int(rng.integers(0, n))] = np.nan
        found.append((v, closed))
    return found


def everything(v, closed):
    """All that the blocks compute, or the refusal."""
    try:
        curve = ddg.DiscreteCurve(v, closed=closed)
    except ValueError as refused:
        return [type(refused).__name__, str(refused)]
    found = [curve.edges, curve.edge_lengths, curve.length, curve.tan_half_psi, curve.reversals]
    for kind in ddg.CURVATURES:
        try:
            found.append(curve.curvature(kind))
        except ValueError as refused:
            found.append(str(refused))
    return found


def independently(v, closed):
    """The edge lengths and tan(psi/2) from whole-array numpy, for turns away from a reversal; NaN elsewhere."""
    e = np.diff(v, axis=0, append=v[:1]) if closed else np.diff(v, axis=0)
    a, b = (np.roll(e, 1, axis=0), e) if closed else (e[:-1], e[1:])
    psi = np.arctan2(a[:, 1] * b[:, 0] - a[:, 0] * b[:, 1], (a * b).sum(axis=1))  # clockwise positive
    return np.hypot(e[:, 0], e[:, 1]), np.where(np.abs(psi) < 3, np.tan(psi / 2), np.nan)


def one_formula(curve):
    """Every edge length by the same formula: sqrt(x^2 + y^2) if all of those lie in _numerics.SAFE,
    else hypot."""
    e = curve.edges
    with np.errstate(all="ignore"):
        fast = np.sqrt(e[:, 0] * e[:, 0] + e[:, 1] * e[:, 1])
    if (_numerics.SAFE[0] < fast).all() and (fast < _numerics.SAFE[1]).all():
        return fast
    return np.hypot(e[:, 0], e[:, 1])


def same(a, b):
    assert len(a) == len(b)
    for x, y in zip(a, b, strict=True):
        assert np.array_equal(x, y, equal_nan=True) if isinstance(x, np.ndarray) else x == y, (x, y)


@pytest.mark.parametrize("size", SIZES)
def test_blocks_of_any_size_give_the_same_bits(size, monkeypatch):
    cases = drawn(np.random.default_rng(size), 150)
    expected = [everything(v, closed) for v, closed in cases]
    for (v, closed), want in zip(cases, expected, strict=True):  # right, and not only alike
        if not isinstance(want[0], str) and 1e-100 < np.abs(v).max() < 1e100:  # where products are plain
            lengths, t = independently(v, closed)
            assert np.array_equal(want[1], one_formula(ddg.DiscreteCurve(v, closed=closed))), (v, closed)
            assert np.allclose(want[1], lengths, rtol=1e-15, atol=0), (v, closed)
            away = ~np.isnan(t)
            assert np.allclose(want[3][away], t[away], rtol=1e-12, atol=1e-15), (v, closed)
    assert sum(isinstance(e[0], str) for e in expected) >= 10  # refusals were drawn
    assert sum(len(e[4]) for e in expected if not isinstance(e[0], str)) >= 5  # and exact reversals
    monkeypatch.setattr(_numerics, "BLOCK", size)
    for (v, closed), want in zip(cases, expected, strict=True):
        same(everything(v, closed), want)


@pytest.mark.parametrize("closed", [True, False])
@pytest.mark.parametrize("tiny", [False, True])
def test_one_tiny_edge_anywhere_changes_how_every_length_is_computed(closed, tiny, monkeypatch):
    """Whether the lengths are sqrt(x^2 + y^2) or hypot is decided for the whole curve, as the lab's
    JavaScript decides it, not block by block: a curve of three default blocks with one edge of
    1e-160 in its last block has every length by hypot, to the last bit."""
    rng = np.random.default_rng(11)
    n = 2 * _numerics.BLOCK + 5
    v = ddg.regular_polygon(n).vertices + rng.normal(size=(n, 2)) * 1e-7
    if tiny:
        v = v - v[n - 3]  # at the origin, where a step of 1e-160 is not lost
        v[n - 2] = [1e-160, 3e-161]
    curve = ddg.DiscreteCurve(v, closed=closed)
    assert np.array_equal(curve.edge_lengths, one_formula(curve))
    want = everything(v, closed)
    monkeypatch.setattr(_numerics, "BLOCK", 4096)
    same(everything(v, closed), want)


def test_the_turns_are_scaled_as_the_final_lengths_say():
    """An edge whose sqrt(x^2 + y^2) is 1e150 (outside SAFE) but whose hypot is just below (inside):
    every length is then by hypot, and as they all lie in SAFE the turns are not rescaled, as the
    lab's JavaScript does (a reviewer's case: rescaled, the turn at vertex 1 moved in its 15th digit)."""
    v = np.array([[0, 0], [1e-149, 1e-160], [2e-149, 2.5e-160], [5.072945131968628e+149, 8.617727524587661e+149]])
    curve = ddg.DiscreteCurve(v)
    L = curve._L
    assert L.max() < _numerics.SAFE[1] and np.array_equal(curve.edge_lengths, one_formula(curve))
    e = curve.edges
    X, Y, t = np.r_[e[-1:, 0], e[:, 0]], np.r_[e[-1:, 1], e[:, 1]], np.empty(len(v))
    with np.errstate(all="ignore"):
        near = _numerics.tan_half_turn(X, Y, L, out=t)  # deciding from the lengths themselves
        t[near] = _numerics._exact_tan_half_turn(v, near)
    assert 1 not in near and np.array_equal(curve.tan_half_psi, t)


def test_numpy_set_to_raise_still_makes_a_curve():
    """Underflow inside the exact turn (products below 2^-1000 of an edge), or in halving a subnormal
    edge, is not an error."""
    with np.errstate(all="raise"):
        curve = ddg.DiscreteCurve([[0.1, 0.2], [1e300, 1], [0.3, 0.7]], closed=False)
        assert np.isfinite(curve.tan_half_psi).all() and len(curve.reversals) == 0
        tiny = ddg.DiscreteCurve(np.array([[0, 0], [0, 1], [1, 1], [1, 0]]) * 1e-310)
        assert (tiny.dual_lengths > 0).all() and tiny.turning_number == 1


def test_a_tangent_curvature_whose_double_overflows_is_still_given():
    """k = tan(psi/2) / (A/2): no 2 tan(psi/2) is formed, which would overflow here (t > 2^1023)."""
    curve = ddg.DiscreteCurve([[0, 0], [8, 0], [0, 1.6e-307]], closed=False)
    t, (a, b) = curve.tan_half_psi[0], curve.edge_lengths
    assert abs(t) > 2.0**1023
    k = curve.curvature("tangent")[0]
    assert k == float(4 * fractions.Fraction(t) / (fractions.Fraction(a) + fractions.Fraction(b)))


@pytest.mark.parametrize("closed", [True, False])
def test_a_curve_of_several_default_blocks_is_computed_as_one_of_small_blocks(closed, monkeypatch):
    rng = np.random.default_rng(7)
    n = 2 * _numerics.BLOCK + 3
    v = np.round((ddg.regular_polygon(n).vertices + rng.normal(size=(n, 2)) * 1e-6) * 2**20) / 2**20
    v[_numerics.BLOCK] = 2 * v[_numerics.BLOCK - 1] - v[_numerics.BLOCK + 1]  # exact: a reversal where a block begins
    want = everything(v, closed)
    assert len(want[4]) == 1, want[4]
    lengths, t = independently(v, closed)
    away = ~np.isnan(t)
    assert np.allclose(want[1], lengths, rtol=1e-15, atol=0) and np.allclose(want[3][away], t[away], rtol=1e-9)
    monkeypatch.setattr(_numerics, "BLOCK", 1000)
    same(everything(v, closed), want)
