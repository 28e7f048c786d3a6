"""The explorers compute what they show, stay fast enough to drag, and survive bad positions."""

import numpy as np
import pytest

import ddg
from ddg.explore import InflationExplorer, PolygonExplorer, VertexExplorer, inflation_explorer, polygon_explorer, vertex_explorer

PNG = b"\x89PNG"


@pytest.mark.parametrize("shape", ["circle", "ellipse", "non-convex blob"])
@pytest.mark.parametrize("kind", ddg.CURVATURES)
def test_polygon_explorer_error_is_error_against_smooth_curvature(shape, kind):
    e = PolygonExplorer(n=50, shape=shape, kind=kind)
    assert e.refresh().startswith(PNG)
    curve = ddg.explore.SHAPES[shape]
    t = curve.sample_parameters(50)
    expected = np.abs(curve.sample(50).curvature(kind) - curve.curvature(t)).max()
    assert e.update(n=50, shape=shape, kind=kind) == pytest.approx(expected)


def test_sine_formula_is_exact_on_the_circle_in_the_explorer():
    e = PolygonExplorer()
    e.refresh()
    assert e.update(n=7, shape="circle", kind="sine") < 1e-13
    assert e.update(n=7, shape="circle", kind="angle") > 1e-3


@pytest.mark.parametrize("method", ddg.INFLATIONS)
def test_inflation_explorer_formula_and_measurement(method):
    e = InflationExplorer(shape="convex pentagon", method=method)
    e.refresh()
    formula, measured = e.update(eps=0.7, shape="convex pentagon", method=method)
    assert measured == pytest.approx(formula, rel=1e-5)  # convex: the lecture's formulas hold
    formula, measured = e.update(eps=0.3, shape="non-convex star", method=method)
    if method == "minkowski":
        assert measured < formula - 1e-3  # reflex corners: the angle formula overestimates
    else:
        assert measured == pytest.approx(formula, rel=1e-9)  # the tangent formula stays exact
    assert "difference" in e.summary


def test_vertex_explorer_curvatures_and_gradient():
    e = VertexExplorer()
    e.refresh()
    ks = e.update(dx=0.0, dy=0.0)
    np.testing.assert_allclose(ks["sine"], 1.0)
    ks = e.update(dx=0.4, dy=0.5)  # pushed inward: a reflex vertex
    assert ks["angle"][2] < 0 and ks["sine"][2] < 0
    assert "k<sub>sine</sub>" in e.summary


def test_vertex_explorer_reports_an_impossible_position():
    e = VertexExplorer()
    e.refresh()
    neighbour = e.base[3] - e.base[2]
    e.base[3] = e.base[2] + np.round(neighbour, 2)  # make the neighbour reachable on the slider grid
    assert e.update(dx=float(np.round(neighbour[0], 2)), dy=float(np.round(neighbour[1], 2))) is None
    assert "not a discrete curve" in e.summary and "vertices 2 and 3 are equal" in e.summary


def test_widgets_are_built_with_controls_and_an_image():
    for make, n_controls in ((polygon_explorer, 3), (inflation_explorer, 3), (vertex_explorer, 2)):
        box = make()
        controls, summary, image = box.children
        assert len(controls.children) == n_controls
        assert bytes(image.value).startswith(PNG) and summary.value
        before = bytes(image.value)
        first = controls.children[0]
        first.value = first.max  # a slider move recomputes and redraws
        assert bytes(image.value) != before
