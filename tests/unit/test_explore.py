"""The explorers compute what they show, pack every reachable state, and work live and static."""

import base64
import gzip
import json
import pathlib
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest

import ddg
from ddg.explore import (SHAPES, Animation, InflationExplorer, PolygonExplorer, Scene, VertexExplorer,
                         inflation_explorer, polygon_explorer, svg, vertex_explorer)


def packed(explorer):
    """The data a page's player receives: the gzip-compressed JSON inside the explorer's HTML."""
    blob = re.search(r'class="ddg-data">([^<]*)</script>', explorer.html()).group(1)
    return json.loads(gzip.decompress(base64.b64decode(blob)))


@pytest.mark.parametrize("shape", list(SHAPES))
@pytest.mark.parametrize("kind", ddg.CURVATURES)
def test_polygon_explorer_error_is_error_against_smooth_curvature(shape, kind):
    polygon, t, k, kappa, error = PolygonExplorer().compute(50, shape, kind)
    curve = SHAPES[shape]
    assert np.allclose(error, np.abs(curve.sample(50).curvature(kind) - curve.curvature(t)))
    summary = PolygonExplorer().scene(50, shape, kind).summary
    assert f"largest |kᵢ − κ(tᵢ)| = {error.max():.3e}" in summary


def test_sine_formula_is_exact_on_the_circle_in_the_explorer():
    assert PolygonExplorer().compute(7, "circle", "sine")[-1].max() < 1e-13
    assert PolygonExplorer().compute(7, "circle", "angle")[-1].max() > 1e-3


@pytest.mark.parametrize("method", ddg.INFLATIONS)
def test_inflation_explorer_formula_and_measurement(method):
    e = InflationExplorer()
    _, region, formula = e.compute(0.7, "convex pentagon", method)
    assert region.area == pytest.approx(formula, rel=1e-5)  # convex: the lecture's formulas hold
    _, region, formula = e.compute(0.3, "non-convex star", method)
    if method == "minkowski":
        assert region.area < formula - 1e-3  # reflex corners: the angle formula overestimates
    else:
        assert region.area == pytest.approx(formula, rel=1e-9)  # the tangent formula stays exact
    assert "difference" in e.scene(0.3, "non-convex star", method).summary


def test_vertex_explorer_curvatures_and_gradient():
    e = VertexExplorer()
    _, ks, grad = e.compute(0.0, 0.0)
    np.testing.assert_allclose(ks["sine"], 1.0)
    _, ks, grad = e.compute(0.45, 0.45)  # pushed inward: a reflex vertex
    assert ks["angle"][2] < 0 and ks["sine"][2] < 0
    assert np.allclose(np.linalg.norm(grad, axis=1), np.abs(ks["sine"]))  # |grad L| = |k sine|


def test_vertex_explorer_reports_an_impossible_position():
    e = VertexExplorer()
    e.base[3] = e.base[2] + (0.5, -0.5)  # a neighbour the dragged vertex can reach exactly
    scene = e.scene(0.5, -0.5)
    assert "not a discrete curve" in scene.summary and "vertices 2 and 3 are equal" in scene.summary


@pytest.mark.parametrize("explorer", [PolygonExplorer(24, "non-convex blob"), InflationExplorer(), VertexExplorer(0.3, -0.15)],
                         ids=lambda e: type(e).__name__)
def test_every_reachable_state_is_packed_and_drawn(explorer):
    data = packed(explorer)
    count = np.prod([len(c["options"]) for c in data["controls"]])
    assert len(data["states"]) == count and data["value"] in data["states"]
    for state in data["states"].values():
        assert all(0 <= i < len(data["items"]) for i in state["items"]) and state["summary"] and state["alt"]
        assert 0 <= state["panels"] < len(data["panels"])
    first = explorer.scene(**explorer.values())
    for i in range(len(first.panels)):
        ET.fromstring(svg(first, i))  # well-formed SVG, for pages without JavaScript
    assert len(explorer.html()) < 200_000


def test_the_static_page_offers_the_nearest_value_of_a_live_one():
    assert packed(VertexExplorer(0.3, -0.2))["value"] == "0.3|-0.15"


def test_state_names_are_written_as_the_page_writes_them():
    """The page names a state by String() of its control values: 0.0 is "0", 1.0 is "1"."""
    for explorer in (VertexExplorer(0.0, 0.0), InflationExplorer(eps=1.0)):
        data = packed(explorer)
        for combo in zip(*(c["options"] for c in data["controls"]), strict=False):
            key = "|".join(str(int(v)) if isinstance(v, float) and v.is_integer() else str(v) for v in combo)
            assert key in data["states"], key
    assert packed(VertexExplorer(0.0, 0.0))["value"] == "0|0"


def test_live_widgets_recompute_on_every_change():
    for explorer in (polygon_explorer(), inflation_explorer(), vertex_explorer()):
        box = explorer.widget()
        controls, summary, picture = box.children
        assert len(controls.children) == len(explorer.controls) and "<svg" in picture.value
        before, first = (picture.value, summary.value), controls.children[0]
        first.value = next(o for o in first.options if o != first.value) if hasattr(first, "options") else first.max
        assert (picture.value, summary.value) != before
    live = polygon_explorer().widget().children[0].children[1]
    assert live.max == 1000  # a kernel computes any n, not only the static page's


def test_output_is_live_in_a_kernel_and_static_in_the_book():
    bundle = polygon_explorer()._repr_mimebundle_()
    assert "application/vnd.jupyter.widget-view+json" in bundle and "ddg-explorer" in bundle["text/html"]


def test_animation_plays_its_scenes_in_order():
    frames = []
    for t in (0.0, 0.1, 0.2):
        scene = Scene([{"box": (-1, -1, 1, 1), "px": (100, 100), "title": f"t = {t}"}], f"t = {t}", f"a circle, t = {t}")
        scene.line(0, ddg.regular_polygon(12, 1 - t).vertices, closed=True)
        frames.append(scene)
    data = packed(Animation(frames, "t", [0.0, 0.1, 0.2]))
    assert list(data["states"]) == ["0", "1", "2"] and data["controls"][0]["type"] == "frames"
    assert data["value"] == "0" and packed(Animation(frames, "t", [0.0, 0.1, 0.2], start=1))["value"] == "1"
    for bad in (3, -1, 1.5, True):
        with pytest.raises(ValueError, match="start must be a frame index from 0 to 2"):
            Animation(frames, "t", [0.0, 0.1, 0.2], start=bad)
    assert [s["summary"] for s in data["states"].values()] == ["t = 0.0", "t = 0.1", "t = 0.2"]


def test_flows_that_coincide_stay_visible_as_nested_bands():
    """flow_animation draws each flow in its colour and width, the widest first: on a regular polygon,
    where the three flows keep one shape, every colour still shows around the narrower ones."""
    from ddg.explore import FLOW_COLORS, FLOW_WIDTHS, flow_animation
    from ddg.flow import flow

    polygon = ddg.regular_polygon(12)
    runs = {"12-gon": {kind: flow(polygon, kind, 0.2, snapshots=3, progress=False) for kind in ddg.CURVATURES}}
    scene = flow_animation(runs, frames=3).frames[-1]
    lines = [item for item in scene.items if item["kind"] == "line" and item["color"] in FLOW_COLORS.values()]
    assert [item["color"] for item in lines] == [FLOW_COLORS[kind] for kind in ddg.CURVATURES]
    assert [item["width"] for item in lines] == [FLOW_WIDTHS[kind] for kind in ddg.CURVATURES]
    assert FLOW_WIDTHS["angle"] > FLOW_WIDTHS["sine"] > FLOW_WIDTHS["tangent"]
    assert "angle flow in blue (5 px), sine flow in orange (3 px), tangent flow in green (1.25 px)" in scene.summary
    widths = re.findall(r'stroke="(#[0-9a-f]{6})" stroke-width="([\d.]+)"', svg(scene, 0))
    assert [w for c, w in widths if c in FLOW_COLORS.values()] == ["5", "3", "1.25"]


def test_scene_items_use_only_the_documented_keys():
    """ddg/scene.py documents each item key once; the player (ddg-player.js) reads the same names."""
    import ddg.scene

    documented = set(re.findall(r"^(\w+) {2,}", ddg.scene.__doc__, re.M)) - {"key"}
    player = (pathlib.Path(ddg.__file__).parents[1] / "book" / "_assets" / "ddg-player.js").read_text()
    used = set()
    for explorer in (PolygonExplorer(), InflationExplorer(), VertexExplorer(0.3, 0.3)):
        for item in packed(explorer)["items"]:
            used |= set(item)
    assert used <= documented, used - documented
    assert {"kind", "panel", "points", "color", "radius", "values", "labels", "handle", "bar_width"} <= used
    assert all(f"item.{key}" in player for key in documented - {"kind", "panel", "points"}), documented
