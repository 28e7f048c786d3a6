"""The lab of chapter 10 in the built book, in Chromium: a reader operates every control (presets,
keys, buttons, drawing, dragging by mouse and finger, the three flows) at desktop and phone width,
light and dark, and what the page shows (the summary, the line on the selected vertex, the arrows,
the chart's range, the flows) is what ddg computes for the same polygon.

Needs the book built (`make book`); the student edition is not needed, so the book alone is
served on loopback here.
"""

import functools
import http.server
import re
import threading

import numpy as np
import pytest
from browser_helpers import EVERY_SECTION, SITES, Visit

import ddg
from instructor import references
from ddg.checks.judge import Call
from ddg.explore import FLOW_COLORS, POLYGONS, SHAPES, measured_region
from ddg.flow import flow
from ddg.scene import RAMP, ramp
from ddg.smooth import SmoothCurve

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


def noise(curve):
    """The sizes at which the lab shows a value as 0 (ddg-lab-page.js: noise): a turn, a curvature or
    |grad L|, an area; 1024 rounding errors of the coordinates, relative to the shortest edge."""
    turn = 1024 * 2.0**-52 * max(np.abs(curve.vertices).max() / curve.edge_lengths.min(), 1)
    scale = max(np.abs(curve.vertices).max(), curve.length)
    return {"turn": turn, "k": turn / curve.dual_lengths.min(), "area": 1024 * 2.0**-52 * scale * curve.length}


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
    area = 0 if abs(curve.signed_area) <= noise(curve)["area"] else curve.signed_area  # rounding noise: 0
    assert float(match[2]) == six(curve.length) and float(match[3]) == six(area), (text, want)
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
        drag_vertex(page, lab.locator("circle").nth(3), 40, -25)
        dragged = summary_is_ddgs(page)
        assert dragged[3, 0] > start[3, 0] + 0.1 and dragged[3, 1] > start[3, 1] + 0.05, dragged[3] - start[3]
        assert (np.delete(dragged, 3, axis=0) == np.delete(start, 3, axis=0)).all()
        assert page.evaluate("() => document.activeElement.index") == 3
        fills = page.evaluate("() => document.querySelector('.ddg-lab').lab.circles.map(c => c.getAttribute('fill'))")
        k = ddg.DiscreteCurve(dragged).curvature("angle")  # let go: the colours on the scale of its curvatures
        assert fills == [ramp(RAMP, level) for level in np.round(64 * np.clip(0.5 + k / (2 * np.abs(k).max()), 0, 1)) / 64]

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
        lab.locator("input[type=number]").first.fill("2000")
        lab.locator("input[type=number]").first.dispatch_event("change")
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
            for name in ("ddg-lab.js", "ddg-lab-page.js", "polygon-clipping.umd.min.js"):
                assert any(s.endswith("/" + name) or f"/{name}?" in s for s in scripts) == wanted, (path, name)
        finally:
            visit.close()


def lab_state(page):
    return page.evaluate("""() => { const lab = document.querySelector('.ddg-lab').lab;
        return {vertices: lab.vertices, arrows: lab.arrowPath.getAttribute('d'), detail: lab.detail.textContent,
                caption: lab.caption.textContent, kind: lab.kind.value, selected: lab.selected,
                message: lab.message.textContent}; }""")


def arrows_are_ddgs(state):
    """Each drawn arrow starts at its vertex and points along ddg's gradient of length, the lengths in
    proportion (one scale for all)."""
    v = np.array(state["vertices"])
    numbers = np.array([float(x) for x in re.findall(r"-?[\d.]+(?:e-?\d+)?", state["arrows"])]).reshape(-1, 5, 2)
    assert len(numbers) == len(v), (len(numbers), len(v))
    numbers[..., 1] *= -1  # the SVG's y points down
    gradient = ddg.DiscreteCurve(v).length_gradient()
    assert np.allclose(numbers[:, 0], v, atol=1e-12)
    drawn = numbers[:, 1] - numbers[:, 0]
    scale = np.linalg.norm(drawn, axis=1).max() / np.linalg.norm(gradient, axis=1).max()
    assert np.allclose(drawn, scale * gradient, atol=1e-9 * scale), drawn - scale * gradient


def circle_curvature(vertices):
    """Chapter 6's circle curvature as its grader computes it, from the circle's centre."""
    return references.circle_curvature(Call(({"polygon": np.asarray(vertices).tolist()},), "the lab's polygon"))


def detail_is_ddgs(state):
    """The line on the selected vertex: its psi in degrees and its four curvatures, as ddg (and chapter
    6's grader, for the circle) gives them."""
    curve, i = ddg.DiscreteCurve(np.array(state["vertices"])), state["selected"]
    assert state["detail"].startswith(f"Vertex {i} at (")
    numbers = [float(x) for x in re.findall(r"-?\d+(?:\.\d+)?(?:e-?\d+)?", state["detail"].split("ψ = ")[1])]
    want = [np.degrees(curve.turning_angles[i]), *(curve.curvature(k)[i] for k in ddg.CURVATURES),
            circle_curvature(curve.vertices)[i], np.linalg.norm(curve.length_gradient()[i])]
    assert np.allclose(numbers, [six(x) for x in want], rtol=1e-12, atol=1e-12), (state["detail"], want)


def touch_drag(page, x, y, dx, dy):
    """A finger on (x, y) moving by (dx, dy) in five steps (Chromium's touch events: pointerType touch)."""
    cdp = page.context.new_cdp_session(page)
    cdp.send("Input.dispatchTouchEvent", {"type": "touchStart", "touchPoints": [{"x": x, "y": y}]})
    for k in range(1, 6):
        cdp.send("Input.dispatchTouchEvent", {"type": "touchMove", "touchPoints": [{"x": x + dx * k / 5, "y": y + dy * k / 5}]})
    cdp.send("Input.dispatchTouchEvent", {"type": "touchEnd", "touchPoints": []})
    cdp.detach()


def lab_visit(browser, book, query, view):
    """The lab opened at PAGE + query (the network cut) in a view: "desktop, light, mouse" or "phone,
    dark, touch"; the visit, and whether it is the phone."""
    phone = view.startswith("phone")
    visit = Visit(browser, book, PAGE + query, touch=phone)
    if phone:
        visit.show("phone")
        visit.page.emulate_media(color_scheme="dark")
    return visit, phone


def drag_vertex(page, dot, dx, dy, touch=False):
    """Drag the vertex `dot` by (dx, dy) pixels in five steps, with the mouse or a finger."""
    dot.scroll_into_view_if_needed()
    box = dot.bounding_box()
    x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    if touch:
        touch_drag(page, x, y, dx, dy)
        return
    page.mouse.move(x, y)
    page.mouse.down()
    for k in range(1, 6):
        page.mouse.move(x + dx * k / 5, y + dy * k / 5)
    page.mouse.up()


@pytest.mark.parametrize("view", ["desktop, light, mouse", "phone, dark, touch"])
def test_every_control_of_the_lab_against_ddg(browser, book, view):
    """From a chapter's link (?lab=star&kind=tangent&arrows=1): the preset, the arrows and the line on
    the selected vertex are ddg's; a preset with n, adding, removing and undoing by keys and by the
    buttons, drawing a polygon, dragging by mouse or finger; then the three flows, stepped and
    played to their stop rules, as ddg.flow runs them; axe finds nothing serious at the end, and the
    page printed shows the polygon and the flows as they are, without the controls."""
    from test_site import AXE_OPTIONS, axe_violations

    visit, phone = lab_visit(browser, book, "?lab=star&kind=tangent&arrows=1", view)
    page = visit.page
    press = (lambda locator: locator.tap()) if phone else (lambda locator: locator.click())
    try:
        lab = page.locator(".ddg-lab")
        lab.scroll_into_view_if_needed()
        state = lab_state(page)
        assert state["kind"] == "tangent"
        assert np.allclose(state["vertices"], POLYGONS["non-convex star"].vertices, rtol=0, atol=1e-15)
        arrows_are_ddgs(state)
        detail_is_ddgs(state)
        summary_is_ddgs(page)

        # the ellipse with 30 vertices: ddg's sample; the chart's range is ddg's k and kappa
        lab.locator("select").first.select_option("ellipse")
        lab.locator("input[type=number]").first.fill("30")
        lab.locator("input[type=number]").first.dispatch_event("change")
        ellipse = SHAPES["ellipse"]
        t = ellipse.sample_parameters(30)
        state = lab_state(page)
        assert np.allclose(state["vertices"], ellipse.position(t), rtol=0, atol=1e-15)
        values = np.r_[ddg.DiscreteCurve(ellipse.position(t)).curvature("tangent"), ellipse.curvature(t)]
        low, high = re.search(r"from (\S+) to (\S+); the upright", state["caption"]).groups()
        assert float(low) == six(min(0, values.min())) and float(high) == six(values.max()), state["caption"]
        arrows_are_ddgs(state)

        # keys: Insert adds the middle of the edge after vertex 4, Delete removes it, Ctrl+Z undoes
        before = np.array(state["vertices"])
        lab.locator("circle").nth(4).focus()
        page.keyboard.press("Insert")
        added = np.array(lab_state(page)["vertices"])
        assert np.allclose(added, np.insert(before, 5, (before[4] + before[5]) / 2, axis=0), rtol=0, atol=1e-15)
        assert page.evaluate("() => document.activeElement.index") == 5
        detail_is_ddgs(lab_state(page))
        psi = float(re.search(r"ψ = (\S+)°", lab_state(page)["detail"])[1])
        assert abs(psi) < 1e-12  # the new vertex does not turn (to rounding: a midpoint is rounded)
        page.keyboard.press("Delete")
        assert np.array_equal(lab_state(page)["vertices"], before)
        page.keyboard.press("Control+z")
        assert np.array_equal(lab_state(page)["vertices"], added)
        page.keyboard.press("Control+z")
        assert np.array_equal(lab_state(page)["vertices"], before)

        # the buttons, by pointer or finger: add after the selected vertex, remove it, undo
        press(lab.get_by_role("button", name="Add vertex"))
        assert len(lab_state(page)["vertices"]) == 31
        press(lab.get_by_role("button", name="Remove vertex"))
        press(lab.get_by_role("button", name="Undo"))
        assert len(lab_state(page)["vertices"]) == 31
        summary_is_ddgs(page)
        # a polygon keeps three vertices: from four, one removal works and the next is refused, in words
        page.evaluate("() => { const lab = document.querySelector('.ddg-lab').lab; lab.vertices.splice(4); lab.rebuild(); }")
        press(lab.get_by_role("button", name="Remove vertex"))
        press(lab.get_by_role("button", name="Remove vertex"))
        assert len(lab_state(page)["vertices"]) == 3 and "at least 3 vertices" in lab_state(page)["message"]

        # drawing: four clicks or taps, clockwise, make the polygon
        press(lab.get_by_role("button", name="Draw"))
        box = lab.locator("svg.ddg-lab-svg").bounding_box()
        corners = [(0.3, 0.3), (0.7, 0.35), (0.65, 0.7), (0.3, 0.65)]
        for fx, fy in corners:
            x, y = box["x"] + fx * box["width"], box["y"] + fy * box["height"]
            page.touchscreen.tap(x, y) if phone else page.mouse.click(x, y)
        press(lab.get_by_role("button", name="Done"))
        drawn = summary_is_ddgs(page)
        assert len(drawn) == 4 and ddg.DiscreteCurve(drawn).turning_number == 1  # clockwise on the screen
        # dragging vertex 2 by mouse or finger moves it alone
        drag_vertex(page, lab.locator("circle").nth(2), 20, 15, touch=phone)
        moved = summary_is_ddgs(page)
        assert moved[2, 0] > drawn[2, 0] and moved[2, 1] < drawn[2, 1], moved[2] - drawn[2]
        assert np.array_equal(np.delete(moved, 2, axis=0), np.delete(drawn, 2, axis=0))

        # the three flows from the regular 24-gon: three steps are ddg's first step of each flow
        lab.locator("select").first.select_option("regular n-gon")
        lab.locator("input[type=number]").first.fill("24")
        lab.locator("input[type=number]").first.dispatch_event("change")
        polygon = ddg.DiscreteCurve(np.array(lab_state(page)["vertices"]))
        press(lab.get_by_role("button", name="Flow this shape"))
        for _ in range(3):
            press(lab.get_by_role("button", name="Step"))
        runs = page.evaluate("() => document.querySelector('.ddg-lab').lab.flows.runs.map(r => [r.kind, r.t, r.vertices])")
        for kind, t, vertices in runs:
            step = flow(polygon, kind, 10.0, max_steps=1, snapshots=2, progress=False)
            assert abs(t - step.times[-1]) <= 1e-12 * t and np.allclose(vertices, step.snapshots[-1][1].vertices, rtol=0, atol=1e-12)
        lab.locator(".ddg-lab-flows select").select_option(label="fast (3 s)")
        press(lab.get_by_role("button", name="Play"))
        status = lab.locator(".ddg-lab-flow-status")
        page.wait_for_function("() => document.querySelector('.ddg-lab').lab.flows.runs.every(r => r.stopped)", timeout=60_000)
        page.wait_for_function("() => document.querySelector('.ddg-lab').lab.flows.play.textContent === 'Play'", timeout=20_000)
        text = status.inner_text()
        for kind in ddg.CURVATURES:
            run = flow(polygon, kind, 10.0, snapshots=2, progress=False)
            said = re.search(rf"{kind} flow: stopped at t = (\S+): ([^.]+)", text)
            assert said and float(said[1]) == pytest.approx(run.times[-1], rel=1e-5), (kind, text, run.times[-1], run.stopped)
            assert said[2] in run.stopped, (said[2], run.stopped)
        assert lab.get_by_role("button", name="Play").get_attribute("aria-pressed") == "false"

        assert not axe_violations(visit, AXE_OPTIONS), view
        page.emulate_media(media="print")  # printed: the polygon and the flows as they are now, no controls
        assert lab.locator("svg.ddg-lab-svg").is_visible() and lab.locator(".ddg-lab-flows svg").first.is_visible()
        assert lab.locator(".ddg-summary").first.is_visible() and not lab.locator(".ddg-controls").first.is_visible()
        assert lab.locator("svg.ddg-lab-svg circle.ddg-handle").count() == 24
        assert not visit.outside and not visit.failed and not visit.unexpected_console()
    finally:
        visit.close()


PRESETS = {"regular": "regular n-gon", "ellipse": "ellipse", "blob": "non-convex blob", "eight": "figure-eight",
           "star": "star (chapter 5)", "pentagon": "convex pentagon (chapter 5)"}  # ?lab= and the list's names


def test_each_chapters_link_opens_the_lab_with_its_preset(browser, book):
    """Chapters 3-9 each link to the lab; the link's preset is what the lab starts from."""
    for chapter in ("03_winding_number", "04_gradient_of_length", "05_inflation", "06_table",
                    "07_convergence", "08_classical_theorems", "09_curve_shortening"):
        visit = Visit(browser, book, f"book/{chapter}.html")  # the network cut
        page = visit.page
        try:
            link = page.locator("a.ddg-lab-link")
            assert link.count() == 1, chapter
            query = dict(re.findall(r"[?&](\w+)=([\w.-]+)", link.get_attribute("href")))
            link.click()
            page.wait_for_url(re.compile(r"10_explorers\.html\?"))
            shape, kind, n, arrows, method, eps = page.evaluate("""() => { const lab = document.querySelector('.ddg-lab').lab;
                return [lab.shape.value, lab.kind.value, lab.vertices.length, lab.arrows.checked, lab.method.value,
                        lab.eps.value]; }""")
            assert method == query.get("inflate", "") and ("eps" not in query or eps == query["eps"]), chapter
            assert shape == PRESETS[query["lab"]], (chapter, shape)
            assert kind == query.get("kind", "angle") and arrows == (query.get("arrows") == "1"), chapter
            assert "n" not in query or n == int(query["n"]), chapter
            assert not visit.outside and not visit.failed and not visit.unexpected_console(), chapter
        finally:
            visit.close()


def figure_eight():
    """The lab's figure-eight, 1.2 (sin t, sin t cos t), as a ddg.smooth curve: the reference for its
    vertices and kappa (the lab samples it at t_k = 2 pi (k + 1/2) / n, its crossing between two vertices)."""
    return SmoothCurve(lambda t: (1.2 * np.sin(t), 0.6 * np.sin(2 * t)), lambda t: (1.2 * np.cos(t), 1.2 * np.cos(2 * t)),
                       lambda t: (-1.2 * np.sin(t), -2.4 * np.sin(2 * t)), name="figure-eight")


def test_every_preset_is_ddgs(browser, book):
    """Each preset's vertices, and the smooth curve's kappa(t_i) that the chart draws, against ddg:
    the circle, ellipse and blob of ddg.explore.SHAPES, chapter 5's polygons of ddg.explore.POLYGONS
    and the figure-eight; every vertex's colour is ddg.scene's ramp (in the page's 65 steps) and the
    flows' colours are ddg.explore's; and the figure-eight's turning number is 0."""
    smooth = {"regular": (SHAPES["circle"], 0.0), "ellipse": (SHAPES["ellipse"], 0.0),
              "blob": (SHAPES["non-convex blob"], 0.0), "eight": (figure_eight(), 0.5)}
    polygons = {"star": POLYGONS["non-convex star"], "pentagon": POLYGONS["convex pentagon"]}
    visit = Visit(browser, book, PAGE)
    try:
        for name, n in [(name, n) for name in PRESETS for n in (7, 64)]:
            visit.page.goto(f"{book}{PAGE}?lab={name}&n={n}")
            state = visit.page.evaluate("""() => { const lab = document.querySelector('.ddg-lab').lab;
                return {vertices: lab.vertices, kappa: lab.kappa, fills: lab.circles.map(c => c.getAttribute('fill'))}; }""")
            if name in smooth:
                curve, shift = smooth[name]
                t = 2 * np.pi * (np.arange(n) + shift) / n
                assert np.allclose(state["vertices"], curve.position(t), rtol=0, atol=1e-15), name
                assert np.allclose(state["kappa"], curve.curvature(t), rtol=1e-14, atol=1e-14), name
            else:
                assert np.allclose(state["vertices"], polygons[name].vertices, rtol=0, atol=1e-15) and state["kappa"] is None
            k = ddg.DiscreteCurve(np.array(state["vertices"])).curvature("angle")
            levels = np.round(64 * np.clip(0.5 + k / (2 * np.abs(k).max()), 0, 1)) / 64  # the page's 65 steps
            assert state["fills"] == [ramp(RAMP, level) for level in levels], name  # ddg.scene's ramp on RAMP
        assert ddg.DiscreteCurve(figure_eight().sample(64).vertices).turning_number == 0
        visit.page.get_by_role("button", name="Flow this shape").click()
        strokes = visit.page.evaluate("() => document.querySelector('.ddg-lab').lab.flows.runs.map(r => [r.kind, r.path.getAttribute('stroke')])")
        assert dict(strokes) == FLOW_COLORS
        assert not visit.outside and not visit.failed and not visit.unexpected_console()
    finally:
        visit.close()


def inflation_is_ddgs(page, curve):
    """The inflation line against ddg and shapely: the formula is ddg's inflated_area; the region the
    lab measures (its polygon-clipping union) is shapely's, to the chords of both (the lab's of half
    a degree, shapely's of 90/256 degrees, each missing a fraction h^2/6 of a sector); the difference
    is said to two digits."""
    page.wait_for_function("() => 'measured' in document.querySelector('.ddg-lab-inflation').dataset")
    method, eps, text, data = page.evaluate("""() => { const lab = document.querySelector('.ddg-lab').lab, p = lab.inflation;
        return [lab.method.value, Number(lab.eps.value), p.textContent, Object.assign({}, p.dataset)]; }""")
    formula, measured = float(data["formula"]), float(data["measured"])
    assert abs(formula - curve.inflated_area(eps, method)) <= 1e-12 * abs(formula), (method, eps)
    shapely_area = measured_region(curve, eps, method).area
    chords = (np.pi / 360) ** 2 / 6 * eps**2 / 2 * curve.turning_angles.clip(0).sum() if method == "minkowski" else 0
    assert abs(measured - shapely_area) <= 2 * chords + 1e-12 * shapely_area, (method, eps, measured - shapely_area, chords)
    said = re.search(r"by ε = ([\d.]+), .* formula − region = (\S+)\.$", text)
    rounding = noise(curve)["area"] + 1024 * 2.0**-52 * abs(measured)  # shown as 0 (ddg-lab-page.js)
    difference = 0 if abs(formula - measured) <= rounding else float(f"{formula - measured:.2g}")
    assert said and float(said[1]) == eps and float(said[2]) == difference, text
    return formula - measured


@pytest.mark.parametrize("view", ["desktop, light, mouse", "phone, dark, touch"])
def test_inflation_in_the_lab_against_ddg_and_shapely(browser, book, view):
    """From chapter 5's link (?lab=star&inflate=minkowski&eps=0.2): the star inflated both ways at the
    exercise's eps, moved by the keys; the formula is ddg's and the region is shapely's; the offset
    is exact on the star and the Minkowski sum misses by eps^2 times a constant. Chapter 6's fill on
    the bisector matches its formula for each curvature on convex polygons, on the star for the tangent
    curvature only. On random simple
    polygons the region is the Minkowski sum shapely computes, whatever their reflex corners; a
    drag re-measures the region when it ends; a figure-eight, a polygon that crosses itself, a
    counter-clockwise polygon and a polygon of more than 300 vertices are refused in words; axe finds nothing serious."""
    from test_site import AXE_OPTIONS, axe_violations

    visit, phone = lab_visit(browser, book, "?lab=star&inflate=minkowski&eps=0.2", view)
    page = visit.page
    try:
        lab = page.locator(".ddg-lab")
        star = POLYGONS["non-convex star"]
        slider = lab.locator("input[type=range]").first
        missed = {}
        for method, name in (("minkowski", "Minkowski sum"), ("offset", "offset with kites")):
            lab.locator("select").nth(2).select_option(label=name)
            for eps in (0.2, 0.4, 0.8):
                slider.evaluate("(e, eps) => { e.value = eps; e.dispatchEvent(new Event('input')); }", eps)
                missed[method, eps] = inflation_is_ddgs(page, star)
            slider.focus()
            page.keyboard.press("ArrowLeft")  # the keys move eps by 0.01
            assert slider.input_value() == "0.79"
            inflation_is_ddgs(page, star)
        assert abs(missed["minkowski", 0.4] / missed["minkowski", 0.2] - 4) < 1e-3
        assert abs(missed["minkowski", 0.8] / missed["minkowski", 0.4] - 4) < 1e-3
        assert all(abs(missed["offset", eps]) < 1e-12 for eps in (0.2, 0.4, 0.8))
        assert lab.locator(".ddg-lab-region").get_attribute("d") and lab.locator(".ddg-lab-pieces").get_attribute("d")

        # chapter 6's fill on the bisector, for each curvature: its formula A_0 + eps L + eps^2/2 <k, 1>
        # is ddg's, and its region matches it on convex polygons (thm-fills); on the star only for the
        # tangent curvature, whose fill is the offset's kite and whose reflex term is the overlap's area
        page.goto(f"{book}{PAGE}?lab=star&inflate=bisector&kind=sine&eps=0.3")  # as a link would open it
        assert lab.locator("select").nth(2).evaluate("s => s.selectedOptions[0].textContent") == "fill on the bisector of chapter 6"
        rng = np.random.default_rng(6)
        ellipses = [np.c_[2 * np.cos(t), -np.sin(t)] for t in (np.sort(rng.uniform(0, 2 * np.pi, n)) for n in (5, 9, 30))]
        for convex, vertices in [(False, star.vertices), (True, POLYGONS["convex pentagon"].vertices),
                                 *((True, v) for v in ellipses)]:
            curve = ddg.DiscreteCurve(vertices)
            for kind in (*ddg.CURVATURES, "circle"):
                data = page.evaluate("""([v, kind]) => { const lab = document.querySelector('.ddg-lab').lab;
                    lab.vertices = v; lab.kind.value = kind; lab.eps.value = 0.3; lab.rebuild();
                    return new Promise(done => setTimeout(() => done(Object.assign({}, lab.inflation.dataset)), 0)); }""",
                                     [vertices.tolist(), kind])
                k = circle_curvature(vertices) if kind == "circle" else curve.curvature(kind)
                formula = curve.signed_area + 0.3 * curve.length + 0.3**2 / 2 * (curve.dual_lengths @ k)
                assert abs(float(data["formula"]) - formula) <= 1e-12 * formula, kind
                short = float(data["formula"]) - float(data["measured"])
                assert (abs(short) < 1e-12 * formula) == (convex or kind == "tangent"), (kind, short)  # tangent: the offset

        # random simple polygons (star-shaped, 5 to 40 vertices, clockwise): the Minkowski region is shapely's
        lab.locator("select").nth(2).select_option(label="Minkowski sum")
        rng = np.random.default_rng(24)
        for _ in range(12):
            n = int(rng.integers(5, 41))
            theta = np.sort(rng.uniform(0, 2 * np.pi, n))
            radii = rng.uniform(0.3, 1.0, n)
            polygon = np.c_[radii * np.cos(theta), -radii * np.sin(theta)]
            eps = round(float(rng.uniform(0.01, 1.0)), 2)
            page.evaluate("""([v, eps]) => { const lab = document.querySelector('.ddg-lab').lab;
                lab.vertices = v; lab.eps.value = eps; lab.rebuild(); }""", [polygon.tolist(), eps])
            inflation_is_ddgs(page, ddg.DiscreteCurve(polygon))

        # a drag: the pieces follow at once, the region is measured again when the hand stops
        page.goto(f"{book}{PAGE}?lab=pentagon&inflate=offset&eps=0.3")
        page.add_style_tag(content=EVERY_SECTION)  # as the visit's first load: every section drawn, for axe
        visit.show("phone" if phone else "desktop")
        if phone:
            page.emulate_media(color_scheme="dark")
        pieces = lab.locator(".ddg-lab-pieces").get_attribute("d")
        drag_vertex(page, lab.locator("circle").nth(2), 15, 10, touch=phone)
        assert lab.locator(".ddg-lab-pieces").get_attribute("d") != pieces
        dragged = summary_is_ddgs(page)
        assert not np.allclose(dragged, POLYGONS["convex pentagon"].vertices)
        assert abs(inflation_is_ddgs(page, ddg.DiscreteCurve(dragged))) < 1e-12  # still convex: exact
        lab.locator("select").nth(2).select_option(label="Minkowski sum")  # short by the chords, at most
        short = inflation_is_ddgs(page, ddg.DiscreteCurve(dragged))  # (pi/360)^2/6 = 1.3e-5 of the sectors
        assert 0 < short <= 1.27e-5 * 0.3**2 / 2 * 2 * np.pi, short

        # refused in words: the figure-eight, a polygon that crosses itself, a counter-clockwise one; more
        # than 300 vertices: the formula alone
        inflation = lab.locator(".ddg-lab-inflation")
        lab.locator("select").first.select_option("figure-eight")
        assert "turning number 0" in inflation.inner_text()
        page.evaluate("""() => { const lab = document.querySelector('.ddg-lab').lab;  // turning number 1, but it crosses itself
            lab.vertices = [[0, 0], [0, 3], [1, 3], [1, -1], [2, -1], [2, 3], [3, 3], [3, 0]]; lab.rebuild(); }""")
        assert "simple polygon, and the edges from vertex 2 and from vertex 7 meet" in inflation.inner_text()
        lab.locator("select").first.select_option("regular n-gon")
        page.evaluate("() => { const lab = document.querySelector('.ddg-lab').lab; lab.vertices.reverse(); lab.rebuild(); }")
        assert "counter-clockwise" in inflation.inner_text() and "reverse it" in inflation.inner_text()
        lab.locator("input[type=number]").first.fill("301")
        lab.locator("input[type=number]").first.dispatch_event("change")
        assert "measured for polygons of up to 300 vertices" in inflation.inner_text()
        assert not lab.locator(".ddg-lab-region").get_attribute("d")
        assert not axe_violations(visit, AXE_OPTIONS), view
        assert not visit.outside and not visit.failed and not visit.unexpected_console()
    finally:
        visit.close()


def test_the_circle_curvature_is_the_graders(browser, book):
    """The lab's fourth curvature, 2 sin(psi_i) / |v_{i+1} - v_{i-1}|, against chapter 6's grader, which
    measures it from the circle's centre, on 400 random polygons (convex and not, unequal edges,
    scales 1e-3 to 1e3) to 1e-9 of the largest |k|; where v_{i-1} = v_{i+1} there is no circle, and the page says so."""
    visit = Visit(browser, book, PAGE + "?kind=circle")
    page = visit.page
    try:
        rng = np.random.default_rng(6)
        polygons = []
        for k in range(400):
            n = int(rng.integers(3, 40))
            if k % 2:  # star-shaped, convex or not
                theta = np.sort(rng.uniform(0, 2 * np.pi, n))
                v = rng.uniform(0.2, 1, n)[:, None] * np.c_[np.cos(theta), -np.sin(theta)]
            else:  # any polygon
                v = rng.normal(size=(n, 2))
            polygons.append((v + rng.normal(size=2)) * 10.0 ** rng.uniform(-3, 3))  # moved by its own size: the
            # grader's centre comes from |v|^2 differences, which a far move would cancel
        got = page.evaluate("""polygons => { const lab = document.querySelector('.ddg-lab').lab;
            return polygons.map(v => { lab.vertices = v; lab.rebuild(); return lab.ks.circle; }); }""",
                            [v.tolist() for v in polygons])
        worst = 0.0
        for v, k in zip(polygons, got, strict=True):
            want = circle_curvature(v)
            scale = np.abs(want).max()
            assert np.allclose(k, want, rtol=1e-9, atol=1e-9 * scale), (v, np.array(k) - want)
            worst = max(worst, float(np.max(np.abs(np.array(k) - want)) / scale))
        print(f"\ncircle curvature, 400 polygons: largest difference {worst:.1e} of the largest |k|")
        page.evaluate("() => { const lab = document.querySelector('.ddg-lab').lab; lab.vertices = [[0, 0], [1, 0], [0, 0.5], [1, 0]]; lab.rebuild(); }")
        detail = page.locator(".ddg-lab-detail").inner_text()
        assert "circle undefined" in detail and "No circle curvature: no circle through vertices" in page.locator(".ddg-lab .ddg-summary").first.inner_text()
        assert not visit.outside and not visit.failed and not visit.unexpected_console()
    finally:
        visit.close()
