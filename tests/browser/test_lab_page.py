"""The lab of chapter 10 in the built book, in Chromium: a reader drags a vertex and moves another
with the keys, and the summary says what ddg says of the moved polygon.

Needs the book built (`make book`); the student edition is not needed, so the book alone is
served on loopback here.
"""

import functools
import http.server
import re
import threading

import numpy as np
import pytest
from browser_helpers import SITES, Visit

import ddg

PAGE = "book/10_explorers.html"


@pytest.fixture(scope="module")
def book():
    folder = SITES["book"]
    if not (folder / PAGE).exists():
        pytest.fail(f"no {PAGE} in {folder}: build the book first (`make book`)")

    class Quiet(http.server.SimpleHTTPRequestHandler):
        def log_message(self, *args):
            pass

    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(Quiet, directory=str(folder)))
    threading.Thread(target=httpd.serve_forever, daemon=True).start()
    yield f"http://127.0.0.1:{httpd.server_port}/"
    httpd.shutdown()


def six(x):
    """``x`` to six significant digits, as the summary shows it."""
    return float(f"{x:.6g}")


def summary_is_ddgs(page):
    """The summary and its data attributes against ddg on the polygon the page holds; that polygon."""
    vertices = np.array(page.evaluate("() => document.querySelector('.ddg-lab').lab.vertices"))
    curve = ddg.DiscreteCurve(vertices)
    text, data = page.evaluate("() => { const s = document.querySelector('.ddg-lab .ddg-summary');"
                               " return [s.textContent, Object.assign({}, s.dataset)]; }")
    want = {"turningNumber": curve.turning_number, "length": curve.length, "signedArea": curve.signed_area}
    for name, value in want.items():
        assert abs(float(data[name]) - value) <= 1e-12 * abs(value), (name, data[name], value)
    match = re.fullmatch(r"Turning number (-?\d+), length (\S+), signed area (\S+)\.", text)
    assert match, text
    assert int(match[1]) == curve.turning_number
    assert float(match[2]) == six(curve.length) and float(match[3]) == six(curve.signed_area), (text, want)
    return vertices


def test_drag_a_vertex_and_move_one_with_the_keys(browser, book):
    visit = Visit(browser, book, PAGE)
    try:
        page = visit.page
        assert not visit.outside and not visit.failed and not visit.unexpected_console()
        assert page.evaluate("() => document.querySelector('.ddg-lab-static').hidden")
        lab = page.locator(".ddg-lab")
        lab.locator("select").first.select_option("non-convex blob")
        start = summary_is_ddgs(page)
        assert len(start) == 12 and ddg.DiscreteCurve(start).turning_number == 1

        # drag vertex 3 by (40, -25) pixels: it moves right and up, and no other vertex moves
        dot = lab.locator("circle").nth(3)
        dot.scroll_into_view_if_needed()
        box = dot.bounding_box()
        x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
        page.mouse.move(x, y)
        page.mouse.down()
        for k in range(1, 6):
            page.mouse.move(x + 8 * k, y - 5 * k)
        page.mouse.up()
        dragged = summary_is_ddgs(page)
        assert dragged[3, 0] > start[3, 0] + 0.1 and dragged[3, 1] > start[3, 1] + 0.05, dragged[3] - start[3]
        assert (np.delete(dragged, 3, axis=0) == np.delete(start, 3, axis=0)).all()
        assert page.evaluate("() => document.activeElement.index") == 3

        # with the keys: to vertex 4 (Page Down), three steps right, one large step down
        page.keyboard.press("PageDown")
        assert page.evaluate("() => document.activeElement.index") == 4
        for key in ("ArrowRight", "ArrowRight", "ArrowRight", "Shift+ArrowDown"):
            page.keyboard.press(key)
        moved = summary_is_ddgs(page)
        assert np.allclose(moved[4] - dragged[4], [0.03, -0.1], atol=1e-12)
        assert "curvature" in page.evaluate("() => document.activeElement.getAttribute('aria-label')")

        # a regular 2000-gon: ddg.regular_polygon's vertices, and the summary is still ddg's
        lab.locator("select").first.select_option("regular n-gon")
        lab.locator("input[type=number]").fill("2000")
        lab.locator("input[type=number]").dispatch_event("change")
        big = summary_is_ddgs(page)
        assert np.allclose(big, ddg.regular_polygon(2000).vertices, rtol=0, atol=1e-15)  # V8's sin and cos
        milliseconds = page.evaluate("""() => { const lab = document.querySelector('.ddg-lab').lab, t = performance.now();
            for (let k = 0; k < 10; k++) lab.move(7, [lab.vertices[7][0] + 0.001, lab.vertices[7][1]]);
            return (performance.now() - t) / 10; }""")
        summary_is_ddgs(page)
        print(f"\none update of the 2000-gon: {milliseconds:.1f} ms")
    finally:
        visit.close()


def test_the_lab_scripts_load_only_on_the_labs_page(browser, book):
    for path, wanted in ((PAGE, True), ("book/05_inflation.html", False)):
        visit = Visit(browser, book, path)
        try:
            scripts = visit.page.evaluate("() => [...document.scripts].map(s => s.src)")
            for name in ("ddg-lab.js", "ddg-lab-page.js"):
                assert any(s.endswith("/" + name) or f"/{name}?" in s for s in scripts) == wanted, (path, name)
        finally:
            visit.close()
