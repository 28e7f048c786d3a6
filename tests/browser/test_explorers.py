"""Explorers and animations in the page, with no kernel and no network.

For every explorer and animation of every page: each control (list, slider, play button, the
dragged vertex) changes what is drawn, operated by keyboard where a reader would; the numbers and
the text alternative shown agree with ddg computing the same state in Python. The time a control
step takes in the page is written to _build/explorer-timings/ (a measurement, not a test).
"""

import json
import re

import numpy as np
import pytest
from browser_helpers import PROBES, ROOT, SITES, Visit, pages

from ddg.explore import POLYGONS, PolygonExplorer, VertexExplorer, measured_region

EXPLORERS = {"Polygons on a smooth curve": PolygonExplorer(), "One vertex": VertexExplorer()}
SWEEP = PROBES["SWEEP"]


def explorer_pages():
    return [(site, p) for site in SITES for p in pages(site) if "ddg-explorer" in (SITES[site] / p).read_text()]


def plain(html):
    return re.sub(r"<[^>]+>", "", html).replace("&lt;", "<").replace("&gt;", ">").strip()


def state_of(root):
    """The values the controls show: {name: value}."""
    values = {}
    for label in root.locator(".ddg-controls label").all():
        select, output = label.locator("select"), label.locator("output")
        name = label.locator("span").inner_text().strip()
        values[name] = select.evaluate("s => s.selectedOptions[0].textContent") if select.count() else output.inner_text().strip()
    return values


def expected(title, values):
    """The scene ddg computes for the state the page shows."""
    if title == "Polygons on a smooth curve":
        return EXPLORERS[title].scene(int(values["vertices n"]), values["curve"], values["formula"])
    if title == "One vertex":
        return EXPLORERS[title].scene(float(values["move v2: x"]), float(values["y"]))
    return None


def check_numbers(root, title, where):
    scene = expected(title, state_of(root))
    if scene is not None:
        assert root.locator(".ddg-summary").last.inner_text().strip() == plain(scene.summary), where
        assert root.locator(".ddg-alt").inner_text().strip() == scene.alt, where
    elif "ε = " in (summary := root.locator(".ddg-summary").last.inner_text()):  # the inflation animation
        eps = float(re.search(r"ε = (\d+\.\d+)", summary).group(1))
        for method, name in (("minkowski", "Minkowski sum"), ("offset", "offset with kites")):
            polygon = POLYGONS["convex pentagon"]
            formula = float(re.search(rf"{name}: formula ([\d.]+)", summary).group(1))
            assert abs(formula - polygon.inflated_area(eps, method)) < 1e-4, where
            measured = float(re.search(rf"{name}: formula [\d.]+, measured ([\d.]+)", summary).group(1))
            assert abs(measured - measured_region(polygon, eps, method).area) < 1e-3, where


def drawing(root):
    return root.locator(".ddg-figure").inner_html()


@pytest.mark.parametrize("site, path", explorer_pages(), ids=lambda x: str(x))
def test_every_control_redraws_and_the_numbers_agree_with_ddg(servers, browser, site, path):
    visit = Visit(browser, servers[site], path)
    page, timings = visit.page, []
    try:
        roots = page.locator(".ddg-explorer")
        assert roots.count() >= 1
        page.wait_for_function("n => document.querySelectorAll('.ddg-figure').length === n", arg=roots.count())
        for index in range(roots.count()):
            root = roots.nth(index)
            title = root.get_attribute("data-title")
            assert root.locator(".ddg-static").is_hidden(), "the player did not take over"
            check_numbers(root, title, f"{path} #{index}: first state")
            inputs = root.locator(".ddg-controls select, .ddg-controls input")
            for k in range(inputs.count()):
                before, control = drawing(root), inputs.nth(k)
                if control.evaluate("e => e.tagName") == "SELECT":
                    options = control.locator("option").all_inner_texts()
                    other = next(o for o in options if o != control.evaluate("s => s.selectedOptions[0].textContent"))
                    control.select_option(label=other)
                else:
                    at_end = control.evaluate("e => Number(e.value) >= Number(e.max)")
                    control.focus()
                    page.keyboard.press("ArrowLeft" if at_end else "ArrowRight")  # the keyboard moves a slider
                    timings += page.evaluate(SWEEP, [index, k])
                assert drawing(root) != before, f"{path} #{index}: control {k} changed nothing drawn"
                check_numbers(root, title, f"{path} #{index}: after control {k}")
            play = root.locator(".ddg-play")
            if play.count():
                control = root.locator("input[type=range]").first
                control.evaluate("e => { e.value = 0; e.dispatchEvent(new Event('input')); }")
                before = drawing(root)
                play.click()
                for _ in range(50):  # a loaded machine may draw the first frames late: up to 10 s
                    page.wait_for_timeout(200)
                    if drawing(root) != before:
                        break
                assert drawing(root) != before, f"{path} #{index}: Play did not animate"
                play.click()  # pause
                paused = drawing(root)
                page.wait_for_timeout(700)
                assert drawing(root) == paused, f"{path} #{index}: Pause did not stop it"
                check_numbers(root, title, f"{path} #{index}: paused")
        assert not visit.unexpected_console() and not visit.outside and not visit.failed
    finally:
        visit.close()
    if timings:  # one file per page: the tests run in parallel
        out = ROOT / "_build" / "explorer-timings" / f"{site}__{path.replace('/', '__')}.json"
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text(json.dumps({"steps": len(timings), "median_ms": float(np.median(timings)),
                                   "max_ms": float(np.max(timings))}))


def test_explorers_and_animations_are_on_their_pages():
    found = {p: (SITES["book"] / p).read_text().count('class="ddg-explorer"') for p in pages("book")}
    assert found["book/10_explorers.html"] == 1
    assert found["book/05_inflation.html"] == 1 and found["book/09_curve_shortening.html"] == 1


def test_without_javascript_the_first_state_is_drawn(servers, browser):
    context = browser.new_context(java_script_enabled=False)
    try:
        page = context.new_page()
        page.goto(servers["book"] + "book/10_explorers.html")
        statics = page.locator(".ddg-static")
        assert statics.count() == 1 and statics.first.is_visible() and statics.first.get_attribute("aria-label")
        assert page.locator(".ddg-static svg path").count() > 10
    finally:
        context.close()


def test_the_vertex_explorers_vertex_moves_by_keys_and_pointer(browser):
    """The one explorer with a vertex to drag is no longer on a page of the book (chapter 10's lab does
    its job) but comes with ddg: its kernel-free HTML, with the book's player, in a page of its own.
    The arrow keys and the pointer move v2; the numbers are ddg's after each."""
    context = browser.new_context(viewport={"width": 1280, "height": 900})
    context.route("**/*", lambda route: route.abort())  # nothing leaves the page
    page = context.new_page()
    try:
        page.set_content(f"<!doctype html><meta charset=utf-8><body>{VertexExplorer().html()}</body>")
        page.add_script_tag(content=(ROOT / "book" / "_assets" / "ddg-player.js").read_text())
        root, title = page.locator(".ddg-explorer"), "One vertex"
        page.wait_for_function("() => document.querySelector('.ddg-figure')")
        values = state_of(root)
        root.locator(".ddg-handle").focus()
        page.keyboard.press("ArrowRight")
        moved = state_of(root)
        assert float(moved["move v2: x"]) > float(values["move v2: x"]), "the arrow key did not move v2"
        check_numbers(root, title, "after an arrow key")
        box = root.locator(".ddg-handle").bounding_box()
        page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
        page.mouse.down()
        page.mouse.move(box["x"] - 30, box["y"] + 40, steps=4)
        page.mouse.up()
        dragged = state_of(root)
        assert dragged != moved, "dragging v2 changed nothing"
        check_numbers(root, title, "after a drag")
        assert root.locator("circle[data-label]").count() >= 6  # each vertex says its psi and k
        root.locator("circle[data-label]").first.hover()
        assert "ψ =" in root.locator(".ddg-detail").inner_text()
    finally:
        context.close()
