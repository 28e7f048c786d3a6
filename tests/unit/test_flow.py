"""The curve-shortening integrator (ddg.flow): rates, invariants, stability, clean stops."""

import numpy as np
import pytest

import ddg
from ddg import smooth
from ddg.flow import flow, remesh, stable_step, velocity


def area_rate_now(curve, kind, h=1e-7):
    V = velocity(curve, kind)
    return (ddg.DiscreteCurve(curve.vertices + h * V).signed_area - ddg.DiscreteCurve(curve.vertices - h * V).signed_area) / (2 * h)


@pytest.mark.parametrize("n", [8, 50])
def test_regular_polygon_area_rates_have_closed_forms(n):
    p = ddg.regular_polygon(n, 1.3)
    expected = {"sine": n * np.sin(2 * np.pi / n), "angle": 2 * np.pi * np.cos(np.pi / n), "tangent": 2 * n * np.sin(np.pi / n)}
    for kind, rate in expected.items():
        assert area_rate_now(p, kind) == pytest.approx(-rate, rel=1e-7)


def test_circle_shrinks_at_the_right_rate():
    # the sine flow keeps a regular n-gon regular with d(area)/dt = -n sin(2 pi / n), so r^2 falls linearly
    n, r0, t_end = 100, 1.0, 0.3
    run = flow(ddg.regular_polygon(n, r0), "sine", t_end, safety=0.05, progress=False)
    r2 = np.linalg.norm(run.snapshots[-1][1].vertices, axis=1) ** 2
    assert run.stopped == "reached t_end"
    assert np.allclose(r2, r0**2 - 2 * t_end, rtol=2e-3)  # the smooth circle: r^2 = r0^2 - 2t (first order in dt)
    assert np.ptp(r2) < 1e-9  # and it stays regular
    rate = np.median(run.area_rate())
    assert rate == pytest.approx(-n * np.sin(2 * np.pi / n), rel=2e-3)


@pytest.mark.parametrize("kind", ddg.CURVATURES)
def test_turning_number_and_convexity_are_preserved(kind):
    ellipse = smooth.ellipse(2, 1).sample(40, "arclength")
    run = flow(ellipse, kind, 0.5, snapshots=10, progress=False)
    assert set(run.turning_numbers.tolist()) == {1}
    assert all((curve.turning_angles > 0).all() for _, curve in run.snapshots)
    assert np.all(np.diff(run.areas) < 0) and run.stopped == "reached t_end"


def test_sine_flow_is_the_gradient_flow_of_length():
    c = ddg.DiscreteCurve(np.random.default_rng(1).uniform(-1, 1, (9, 2)))
    np.testing.assert_allclose(velocity(c, "sine"), -c.length_gradient(), atol=1e-12)


def test_the_stable_step_is_stable_and_four_times_it_is_not():
    rng = np.random.default_rng(3)
    wobbly = ddg.DiscreteCurve(ddg.regular_polygon(40).vertices * (1 + 0.05 * rng.normal(size=(40, 1))))
    safe = stable_step(wobbly, "sine")  # safety 0.25 of the forward-Euler limit
    good = flow(wobbly, "sine", 100 * safe, progress=False)
    assert good.stopped == "reached t_end" and np.all(np.diff(good.lengths) <= 1e-12)
    bad = flow(wobbly, "sine", 100 * safe, dt=16 * safe, progress=False)  # 4x the limit
    assert bad.stopped != "reached t_end" or np.any(np.diff(bad.lengths) > 1e-6)


def test_semi_implicit_takes_large_stable_steps():
    c = smooth.ellipse(2, 1).sample(60, "arclength")
    explicit = flow(c, "angle", 0.3, progress=False)
    implicit = flow(c, "angle", 0.3, method="semi-implicit", progress=False)
    assert implicit.steps < explicit.steps / 10
    assert np.all(np.diff(implicit.lengths) < 0)
    assert implicit.areas[-1] == pytest.approx(explicit.areas[-1], rel=0.05)  # backward Euler, big steps: first order


def test_flow_stops_cleanly_before_degenerating():
    teardrop = ddg.DiscreteCurve([[4, 0], [2, -0.5], [0, -1], [-1, 0], [0, 1], [2, 0.5]][::-1])
    run = flow(teardrop, "tangent", 5.0, progress=False)
    assert run.stopped.startswith("stopped") and run.times[-1] < 5.0
    assert all(np.isfinite(curve.vertices).all() for _, curve in run.snapshots)
    shrinking = flow(ddg.regular_polygon(12), "sine", 10.0, progress=False)
    assert "length fell below" in shrinking.stopped


def test_remesh_spaces_vertices_evenly_along_the_polyline():
    c = ddg.DiscreteCurve([[0, 0], [0, 1], [3, 1], [3, 0]])  # length 8
    r = remesh(c)
    np.testing.assert_allclose(r.vertices, [[0, 0], [1, 1], [3, 1], [2, 0]], atol=1e-12)  # at arc length 0, 2, 4, 6
    assert r.signed_area <= c.signed_area and r.turning_number == 1


def test_bad_arguments():
    with pytest.raises(ValueError, match="'angle', 'sine', 'tangent'"):
        flow(ddg.regular_polygon(5), "mean", 1.0)
    with pytest.raises(ValueError, match="'explicit', 'semi-implicit'"):
        flow(ddg.regular_polygon(5), "sine", 1.0, method="rk4")
    with pytest.raises(ValueError, match="closed curves only"):
        flow(ddg.DiscreteCurve([[0, 0], [1, 0], [2, 1]], closed=False), "sine", 1.0)
    with pytest.raises(ValueError, match="t_end must be positive"):
        flow(ddg.regular_polygon(5), "sine", 0)


def test_progress_bar_appears_for_long_runs(capsys):
    flow(ddg.regular_polygon(200), "sine", 0.05, progress=True, safety=0.01)
    assert "sine flow" in capsys.readouterr().err
