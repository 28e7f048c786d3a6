"""Tests of ddg.smooth: exact curvature, arc length, sampling."""

import numpy as np
import pytest

import ddg
from ddg import smooth


def test_ellipse_curvature_matches_closed_form():
    a, b = 3.0, 1.2
    t = np.linspace(0, 2 * np.pi, 50)
    expected = a * b / (a**2 * np.sin(t) ** 2 + b**2 * np.cos(t) ** 2) ** 1.5
    np.testing.assert_allclose(smooth.ellipse(a, b).curvature(t), expected, rtol=1e-13)
    np.testing.assert_allclose(smooth.ellipse(a, b, clockwise=False).curvature(t), -expected, rtol=1e-13)


def test_circle_sign_normal_and_length():
    c = smooth.circle(2.0, center=(1.0, -1.0))
    t = np.linspace(0, 2 * np.pi, 9)
    np.testing.assert_allclose(c.curvature(t), 0.5)
    outward = (c.position(t) - [1.0, -1.0]) / 2.0
    np.testing.assert_allclose(c.normal(t), outward, atol=1e-15)
    assert c.length == pytest.approx(4 * np.pi, rel=1e-14)
    assert c.total_curvature() == pytest.approx(2 * np.pi, rel=1e-13)


def test_ellipse_perimeter_against_series():
    # Ramanujan's second approximation is accurate to ~1e-10 relative for this eccentricity
    a, b = 2.0, 1.0
    h = ((a - b) / (a + b)) ** 2
    ramanujan = np.pi * (a + b) * (1 + 3 * h / (10 + np.sqrt(4 - 3 * h)))
    assert smooth.ellipse(a, b).length == pytest.approx(ramanujan, rel=1e-9)


def test_arclength_sampling_is_uniform_in_arc_length():
    e = smooth.ellipse(3.0, 1.0)
    t = e.sample_parameters(40, "arclength")
    np.testing.assert_allclose(np.diff(e.arc_length(t)), e.length / 40, rtol=1e-10)
    curve = e.sample(40, "arclength")
    assert isinstance(curve, ddg.DiscreteCurve) and len(curve) == 40
    assert curve.turning_number == 1


def test_parametric_curve_from_callables():
    # a limacon, traversed clockwise: total curvature 2 pi; an open arc of the unit circle
    r = lambda t: 2 + np.cos(t)  # noqa: E731
    c, s = np.cos, np.sin
    limacon = smooth.parametric(
        lambda t: (r(t) * c(t), -r(t) * s(t)),
        lambda t: (-s(t) * c(t) - r(t) * s(t), s(t) ** 2 - r(t) * c(t)),
        lambda t: (2 * s(t) ** 2 - c(t) ** 2 - r(t) * c(t), 3 * s(t) * c(t) + r(t) * s(t)),
        name="limacon",
    )
    t = np.linspace(0, 6, 7)
    h = 1e-5  # the derivatives given are consistent with the position (central differences)
    np.testing.assert_allclose((limacon.position(t + h) - limacon.position(t - h)) / (2 * h),
                               np.stack(limacon.dgamma(t), axis=1), atol=1e-8)
    assert limacon.total_curvature() == pytest.approx(2 * np.pi, rel=1e-10)
    arc = smooth.parametric(lambda t: (np.cos(t), -np.sin(t)), lambda t: (-np.sin(t), -np.cos(t)),
                            lambda t: (-np.cos(t), np.sin(t)), 0, np.pi / 2, closed=False)
    assert arc.length == pytest.approx(np.pi / 2)
    sampled = arc.sample(5)
    assert not sampled.closed and np.allclose(sampled.vertices[[0, -1]], [[1, 0], [0, -1]])


def test_discrete_curvature_converges_to_smooth_on_ellipse():
    e = smooth.ellipse(2.0, 1.0)
    errors = []
    for n in (100, 200):
        t = e.sample_parameters(n)
        errors.append(np.abs(e.sample(n).curvature("angle") - e.curvature(t)).max())
    assert errors[1] < errors[0] / 3  # second order: the error falls by about 4


def test_bad_arguments():
    with pytest.raises(ValueError, match="radius must be positive"):
        smooth.circle(0)
    with pytest.raises(ValueError, match="must be positive"):
        smooth.ellipse(1, -1)
    with pytest.raises(ValueError, match="'parameter' or 'arclength'"):
        smooth.circle().sample(10, "angle")
