"""A student's journeys through chapter 10's lab, in Chromium, with the network cut: arriving from a
chapter's link, finding a vertex (numbers, the ring, the table), sharing a polygon, playing the
flows, dragging by finger, trusting the readouts, and being told in words whatever the lab cannot
do. Each journey at desktop size with the mouse and at phone size by touch in the dark theme,
fed with generated polygons, addresses and gestures; what the page shows is checked against ddg.

Needs the book built (`make book`).
"""

import re
import urllib.parse

import numpy as np
import pytest
from test_lab_page import PAGE, six, summary_is_ddgs

import ddg
from ddg.explore import POLYGONS
from ddg.flow import flow

DESKTOP, PHONE = {"width": 1280, "height": 720}, {"width": 390, "height": 844}
VIEWS = ["desktop, light, mouse", "phone, dark, touch"]
CHAPTERS = ("03_winding_number", "04_gradient_of_length", "05_inflation", "06_table", "07_convergence",
            "08_classical_theorems", "09_curve_shortening")
LAB = "document.querySelector('.ddg-lab').lab"


@pytest.fixture(scope="module")
def book(servers):
    """The book's site on loopback."""
    return servers["book"]


class Lab:
    """A page of the book in a window of a laptop (mouse, light) or a phone (touch, dark), every
    request that leaves loopback cut off and recorded, every script error recorded."""

    def __init__(self, browser, base, path, phone=False):
        self.base, self.outside, self.errors, self.phone = base, [], [], phone
        self.context = browser.new_context(viewport=PHONE if phone else DESKTOP, has_touch=phone, is_mobile=phone,
                                           color_scheme="dark" if phone else "light")
        self.context.route("**/*", self._route)
        self.page = self.context.new_page()
        self.page.on("pageerror", lambda e: self.errors.append(str(e)))
        self.page.on("console", lambda m: m.type == "error" and self.errors.append(m.text))
        self.page.goto(base + path, wait_until="load")
        if "10_explorers" in path:
            self.ready()

    def _route(self, route):
        url = route.request.url
        if url.startswith(self.base) or url.startswith(("data:", "blob:")):
            route.continue_()
        else:
            self.outside.append(url)
            route.abort()

    def ready(self):
        self.page.wait_for_function(f"() => document.querySelector('.ddg-lab') && {LAB} && {LAB}.circles")

    def get(self, expression):
        return self.page.evaluate(f"() => {{ const lab = {LAB}; return {expression}; }}")

    def press(self, name):
        button = self.page.locator(".ddg-lab").get_by_role("button", name=name, exact=True)
        button.tap() if self.phone else button.click()

    def set_polygon(self, vertices):
        """The polygon as if drawn: Draw, then (vertices placed), Done."""
        self.page.evaluate(f"""v => {{ const lab = {LAB}; lab.remember(); lab.vertices = v; lab.show(); }}""",
                           np.asarray(vertices).tolist())

    def message(self):
        return self.page.locator(".ddg-lab-message").text_content()

    def close(self):
        assert not self.outside, self.outside
        assert not self.errors, self.errors
        self.context.close()


def polygons(count, seed):
    """Generated polygons a student could make: star-shaped, clockwise, 3 to 40 vertices at radii
    0.3 to 1.5, some with a vertex in the middle of an edge (a straight vertex)."""
    rng = np.random.default_rng(seed)
    for j in range(count):
        n = int(rng.integers(3, 41))
        angles = np.sort(rng.uniform(0, 2 * np.pi, n))[::-1]  # decreasing: clockwise
        if np.min(np.abs(np.diff(np.r_[angles, angles[0] - 2 * np.pi]))) < 1e-3:
            continue
        v = rng.uniform(0.3, 1.5, n)[:, None] * np.c_[np.cos(angles), np.sin(angles)]
        v = np.round(v, 3)
        if j % 3 == 0:
            v = np.insert(v, 1, (v[0] + v[1]) / 2, axis=0)
        try:
            ddg.DiscreteCurve(v).curvature("tangent")
        except ValueError:
            continue
        yield v


@pytest.mark.parametrize("view", VIEWS)
def test_every_chapters_link_lands_on_the_drawing(browser, book, view):
    """Each of the seven links of chapters 3-9, followed: the whole drawing is on the first screen,
    under the controls, with its preset; the how-to is folded below it."""
    phone = view.startswith("phone")
    for chapter in CHAPTERS:
        lab = Lab(browser, book, f"book/{chapter}.html", phone)
        try:
            link = lab.page.locator("a.ddg-lab-link")
            link.scroll_into_view_if_needed()
            link.tap() if phone else link.click()
            lab.page.wait_for_url(re.compile(r"10_explorers\.html\?"))
            lab.ready()
            lab.page.wait_for_timeout(300)  # the fonts and the layout settle
            box, height = lab.page.locator("svg.ddg-lab-svg").bounding_box(), lab.page.viewport_size["height"]
            assert box["y"] >= 40 and box["y"] + box["height"] <= height, (chapter, view, box)
            width = lab.page.evaluate("() => document.querySelector('.ddg-lab').getBoundingClientRect().width")
            assert box["width"] >= (0.55 if not phone else 0.95) * width, (chapter, view, box, width)
            query = dict(urllib.parse.parse_qsl(urllib.parse.urlsplit(lab.page.url).query))
            assert lab.get("lab.vertices.length") == int(query.get("n", lab.get("lab.vertices.length")))
            assert lab.get("lab.message.textContent") == ""  # the chapters' links ask for nothing the lab lacks
            how = lab.page.locator("details.dropdown, .admonition.dropdown").filter(has_text="How to use the lab")
            assert how.count() == 1 and not how.locator("li").first.is_visible(), chapter
        finally:
            lab.close()


def test_the_how_to_and_the_lab_come_first():
    """In the chapter's source the lab comes before its how-to, which is folded."""
    import json
    import pathlib

    cells = json.loads((pathlib.Path(__file__).parents[2] / "book" / "10_explorers.ipynb").read_text())["cells"]
    text = next("".join(c["source"]) for c in cells if "## The lab" in "".join(c["source"]))
    assert text.index('<div class="ddg-lab" id="lab"') < text.index("How to use the lab") < text.index("- **Move a vertex**")
    assert ":class: dropdown" in text


@pytest.mark.parametrize("view", VIEWS)
def test_find_a_vertex_by_number_ring_and_table(browser, book, view):
    """Numbers on up to 40 vertices, a ring that stays on the selected one, and the table of every
    vertex: its values are ddg's, a row tapped selects its vertex, a vertex tapped marks its row,
    a row pointed at rings its vertex; on generated polygons."""
    phone = view.startswith("phone")
    lab = Lab(browser, book, PAGE + "?lab=regular&n=12#lab", phone)
    page = lab.page
    try:
        page.locator(".ddg-lab-table summary").click()
        for v in list(polygons(12, seed=3))[:6]:
            lab.set_polygon(v)
            n = len(v)
            assert lab.get("lab.numbers.querySelectorAll('text').length") == (n if n <= 40 else 0)
            assert lab.get("lab.shape.value") == "edited" and lab.get("Number(lab.n.value)") == n
            table = page.evaluate(f"() => [...{LAB}.rows.rows].map(r => [...r.cells].map(c => c.textContent))")
            curve = ddg.DiscreteCurve(v)
            assert len(table) == n
            tolerance = 1024 * 2.0**-52 * max(np.abs(v).max() / curve.edge_lengths.min(), 1)
            for i, row in enumerate(table):
                psi = curve.turning_angles[i]
                want = [i, 0 if abs(psi) <= tolerance else np.degrees(psi), curve.dual_lengths[i]]
                want += [0 if abs(k) <= tolerance / curve.dual_lengths.min() else k
                         for k in (curve.curvature(kind)[i] for kind in ddg.CURVATURES)]
                assert [float(x) for x in row[:6]] == [six(x) for x in want], (i, row, want)
            rng = np.random.default_rng(n)
            for i in rng.choice(n, size=3, replace=False).tolist():
                row = page.locator(".ddg-lab-table tbody tr").nth(i)
                row.tap() if phone else row.click()
                assert lab.get("lab.selected") == i
                mark = lab.get("[+lab.mark.getAttribute('cx'), -lab.mark.getAttribute('cy')]")
                assert np.allclose(mark, v[i], atol=1e-12), (i, mark, v[i])
                assert "ddg-lab-row-selected" in (row.get_attribute("class") or "")
                assert lab.get("lab.detail.textContent").startswith(f"Vertex {i} at (")
                if not phone:
                    other = page.locator(".ddg-lab-table tbody tr").nth((i + 1) % n)
                    other.hover()
                    hover = lab.get("[+lab.hoverMark.getAttribute('cx'), -lab.hoverMark.getAttribute('cy'), lab.hoverMark.getAttribute('visibility'), getComputedStyle(lab.hoverMark).stroke]")
                    assert np.allclose(hover[:2], v[(i + 1) % n], atol=1e-12) and hover[2] == "visible"
                    assert hover[3] not in ("none", "", "transparent"), hover  # drawn: a ring that can be seen
                    drawing = page.locator("svg.ddg-lab-svg").bounding_box()  # beside the table: on the screen
                    assert drawing["y"] + drawing["height"] / 2 < DESKTOP["height"] and drawing["y"] + drawing["height"] / 2 > 0
            # a vertex tapped or clicked in the drawing (the nearest to the pointer) marks its row
            j = int(rng.integers(n))
            x, y = page.evaluate(f"""j => {{ const c = {LAB}.circles[j].getBoundingClientRect();
                return [c.x + c.width / 2, c.y + c.height / 2]; }}""", j)
            page.locator("svg.ddg-lab-svg").scroll_into_view_if_needed()
            x, y = page.evaluate(f"""j => {{ const c = {LAB}.circles[j].getBoundingClientRect();
                return [c.x + c.width / 2, c.y + c.height / 2]; }}""", j)
            page.touchscreen.tap(x, y) if phone else page.mouse.click(x, y)
            assert lab.get("lab.selected") == j
            assert "ddg-lab-row-selected" in page.locator(".ddg-lab-table tbody tr").nth(j).get_attribute("class")
    finally:
        lab.close()


def test_the_nearest_vertex_is_taken_among_2000(browser, book):
    """On the 2000-gon (handles of a few pixels, closer than a pixel apart) a click takes the vertex
    nearest to the pointer: the one aimed at, for generated aims."""
    lab = Lab(browser, book, PAGE + "?lab=ellipse&n=2000#lab")
    page = lab.page
    try:
        rng = np.random.default_rng(7)
        for j in rng.choice(2000, size=8, replace=False).tolist():
            x, y = page.evaluate(f"""j => {{ const lab = {LAB}, m = lab.svg.getScreenCTM(), v = lab.vertices[j];
                return [m.a * v[0] + m.e, m.d * -v[1] + m.f]; }}""", j)
            page.mouse.move(x, y)
            page.mouse.down()
            page.mouse.up()
            assert lab.get("lab.selected") == j
            assert lab.get("lab.detail.textContent").startswith(f"Vertex {j} at (")
    finally:
        lab.close()


@pytest.mark.parametrize("view", VIEWS)
def test_copy_as_numpy_and_as_an_address(browser, book, view):
    """Copy as numpy gives the vertices exactly; Copy address opens the lab with the same polygon,
    exactly, and the same settings; for generated polygons and settings."""
    phone = view.startswith("phone")
    lab = Lab(browser, book, PAGE + "#lab", phone)
    lab.context.grant_permissions(["clipboard-read", "clipboard-write"])
    rng = np.random.default_rng(11)
    try:
        for v in list(polygons(8, seed=5))[:4]:
            v = v + rng.normal(0, 1e-7, v.shape)  # coordinates no thousandth rounds
            lab.set_polygon(v)
            kind = str(rng.choice(["angle", "sine", "tangent", "circle"]))
            lab.page.locator(".ddg-lab select").nth(1).select_option(kind)
            lab.press("Copy as numpy")
            lab.page.wait_for_function("() => document.querySelector('.ddg-lab-message').textContent")
            text = lab.page.locator(".ddg-lab-copied").input_value()
            assert text.startswith("np.array([[") and "Copied the" in lab.message(), (text, lab.message())
            copied = eval(text, {"np": np})  # noqa: S307 (the text the student pastes into a notebook)
            assert np.array_equal(copied, v)
            if not phone:
                assert lab.page.evaluate("() => navigator.clipboard.readText()") == text
            lab.press("Copy address")
            lab.page.wait_for_function("() => document.querySelector('.ddg-lab-message').textContent.includes('address')")
            address = lab.page.locator(".ddg-lab-copied").input_value()
            assert address.startswith(lab.base) and address.endswith("#lab")
            shared = Lab(lab.context.browser, lab.base, address.removeprefix(lab.base), phone)
            try:
                assert np.array_equal(shared.get("lab.vertices"), v)
                assert shared.get("lab.kind.value") == kind and shared.get("lab.shape.value") == "edited"
                assert shared.message() == ""
                summary_is_ddgs(shared.page)
            finally:
                shared.close()
    finally:
        lab.close()


def addresses(count, seed):
    """Generated addresses a student could type or break: presets, n, eps, kinds, inflations and
    shared vertices, each valid or not."""
    rng = np.random.default_rng(seed)
    pick = lambda *options: options[int(rng.integers(len(options)))]  # noqa: E731
    for _ in range(count):
        q = {}
        if rng.random() < 0.7:
            q["lab"] = pick("regular", "ellipse", "blob", "eight", "star", "pentagon", "circle", "", "Star")
        if rng.random() < 0.6:
            q["n"] = pick("3", "24", "2000", "2001", "5000", "0", "-4", "2.5", "abc", "", "1e3", "12")
        if rng.random() < 0.5:
            q["eps"] = pick("0.2", "-0.3", "50", "-7", "abc", "", "0.123", "1", "-1", "nan")
        if rng.random() < 0.5:
            q["inflate"] = pick("minkowski", "offset", "bisector", "nope")
        if rng.random() < 0.4:
            q["kind"] = pick("angle", "sine", "tangent", "circle", "curly")
        if rng.random() < 0.25:
            q["v"] = pick("0,0,0,1,1,1", "0,0,1", "0,0,0,1,x,1", "0,1,1,0,0,-1,-1,0", "", "1e400,0,0,1,1,1", "0,0,,1,1,1")
        yield q


def test_every_address_gives_a_lab_and_says_what_it_changed(browser, book):
    """Generated addresses (chapters' links and broken ones): the lab always starts, n and eps are
    within the lab's limits, and every value it could not use is named in the message."""
    lab = Lab(browser, book, PAGE + "#lab")
    try:
        for q in addresses(40, seed=2):
            lab.page.goto(lab.base + PAGE + "?" + urllib.parse.urlencode(q) + "#lab")
            lab.ready()
            n, eps, message = lab.get("[lab.vertices.length, Number(lab.eps.value), lab.message.textContent]")
            assert 3 <= n <= 2000 and -1 <= eps <= 1, (q, n, eps)
            for key, value in q.items():
                fine = {"lab": value in ("regular", "ellipse", "blob", "eight", "star", "pentagon", ""),
                        "n": value in ("3", "24", "2000", "12", "1e3"),
                        "eps": value in ("0.2", "-0.3", "0.123", "1", "-1") and value != "0.123",
                        "inflate": value in ("minkowski", "offset", "bisector"),
                        "kind": value in ("angle", "sine", "tangent", "circle"),
                        "v": value in ("0,0,0,1,1,1", "0,1,1,0,0,-1,-1,0")}[key]
                said = {"lab": f"“{value}”", "n": "n must be", "eps": "ε ", "inflate": f"“{value}”", "kind": f"“{value}”",
                        "v": "v=…"}[key]
                assert (said in message) == (not fine), (q, key, message)
            summary_is_ddgs(lab.page)
    finally:
        lab.close()


@pytest.mark.parametrize("view", VIEWS)
def test_limits_and_clamps_are_said(browser, book, view):
    """Remove at n = 3, Done with two vertices, an n or an eps typed out of range: each is said."""
    phone = view.startswith("phone")
    lab = Lab(browser, book, PAGE + "?lab=regular&n=3#lab", phone)
    page = lab.page
    try:
        lab.press("Remove vertex")
        assert lab.get("lab.vertices.length") == 3 and "at least 3 vertices" in lab.message()
        lab.press("Add vertex")
        assert lab.get("lab.vertices.length") == 4 and lab.message() == ""
        lab.press("Draw")
        box = page.locator("svg.ddg-lab-svg").bounding_box()
        for fx, fy in ((0.3, 0.3), (0.7, 0.4)):
            x, y = box["x"] + fx * box["width"], box["y"] + fy * box["height"]
            page.touchscreen.tap(x, y) if phone else page.mouse.click(x, y)
        assert lab.get("lab.numbers.querySelectorAll('text').length") == 2  # numbered while drawn
        lab.press("Done")
        assert "place 1 more" in lab.message() and lab.get("lab.drawing")
        for _ in range(3):  # the two vertices, then back before Draw: drawing ends
            lab.press("Undo")
        assert not lab.get("lab.drawing") and lab.get("lab.vertices.length") == 4
        assert lab.get("lab.draw.textContent") == "Draw"
        page.goto(lab.base + PAGE + "?lab=regular#lab")
        lab.ready()
        for typed, n, said in (("5000", 2000, "became 2000"), ("1", 3, "became 3"), ("7.6", 8, "became 8"), ("9", 9, "")):
            typing(page, ".ddg-lab input[type=number]", typed)
            assert lab.get("lab.vertices.length") == n and said in lab.message(), (typed, lab.message())
            assert (lab.message() == "") == (said == "")
        page.locator(".ddg-lab select").nth(2).select_option("offset")
        for typed, eps, said in (("50", 1, "became 1"), ("-0.3", -0.3, ""), ("abc", -0.3, "ε stays -0.3"), ("-7", -1, "became -1")):
            typing(page, ".ddg-lab input[aria-label='ε typed']", typed)
            assert lab.get("Number(lab.eps.value)") == eps and said in lab.message(), (typed, lab.message())
    finally:
        lab.close()


def typing(page, selector, typed):
    """Text typed into a number box, then Enter: the box holds it, or "" when it is no number."""
    box = page.locator(selector).first
    box.click()
    box.press("Control+a")
    box.press_sequentially(typed)
    box.press("Enter")


def shoelace(v):
    """The signed area, clockwise positive, in exact rational arithmetic rounded once."""
    from fractions import Fraction

    x, y = [Fraction(float(a)) for a in v[:, 0]], [Fraction(float(b)) for b in v[:, 1]]
    n = len(v)
    return float(-sum(x[i] * y[(i + 1) % n] - x[(i + 1) % n] * y[i] for i in range(n)) / 2)


def test_negative_eps_the_offset_polygon_and_its_reach(browser, book):
    """eps < 0 with the offset: the dashed polygon is v_i + eps (N_{i-1/2} + tan(psi_i/2) T_{i-1/2})
    from ddg's normals, tangents and turns; its signed area is the formula's and the shoelace's; the
    reach inward is where the first edge shrinks to a point, and past it the lab says so. On
    generated polygons and eps; the Minkowski sum refuses eps < 0 in words."""
    lab = Lab(browser, book, PAGE + "?lab=star&inflate=offset&eps=-0.1#lab")
    page = lab.page
    rng = np.random.default_rng(13)
    try:
        assert lab.get("lab.message.textContent") == ""
        for v in [POLYGONS["non-convex star"].vertices, POLYGONS["convex pentagon"].vertices, *polygons(30, seed=9)]:
            curve = ddg.DiscreteCurve(v)
            if curve.turning_number != 1:
                continue
            lab.set_polygon(v)
            if "No inflation" in lab.get("lab.inflation.textContent"):  # a polygon that crosses itself
                continue
            t = np.tan(curve.turning_angles / 2)
            s = curve.edge_lengths / (t + np.roll(t, -1))
            inward = s[s > 0].min() if (s > 0).any() else np.inf
            for eps in (-round(float(rng.uniform(0.01, 1)), 2), -1.0):
                page.evaluate(f"e => {{ const lab = {LAB}; lab.eps.value = e; lab.fit(); }}", eps)
                data = lab.get("Object.assign({}, lab.inflation.dataset)")
                moved = v + eps * (np.roll(curve.normals, 1, axis=0) + t[:, None] * np.roll(curve.tangents, 1, axis=0))
                formula = curve.signed_area + eps * curve.length + eps**2 * t.sum()
                drawn = np.array([float(x) for x in re.findall(r"-?[\d.]+(?:e-?\d+)?", lab.get("lab.offset.getAttribute('d')"))]).reshape(-1, 2)
                drawn[:, 1] *= -1
                assert np.allclose(drawn, moved, atol=1e-12)
                assert float(data["formula"]) == pytest.approx(formula, rel=1e-12, abs=1e-12)
                assert float(data["offsetArea"]) == pytest.approx(shoelace(moved), rel=1e-9, abs=1e-12)
                assert float(data["offsetArea"]) == pytest.approx(formula, rel=1e-9, abs=1e-12)  # for every eps
                text = lab.get("lab.inflation.textContent")
                if np.isfinite(inward):
                    assert float(data["reach"]) == pytest.approx(inward, rel=1e-12)
                    assert ("folds over itself" in text) == (-eps > inward), (eps, inward, text)
                    reflex = (curve.turning_angles < 0).any()
                    assert -eps > inward or ("is smaller" in text) == reflex, text  # convex: the set itself
        page.locator(".ddg-lab select").nth(2).select_option("minkowski")
        assert "for ε < 0 choose the offset" in lab.get("lab.inflation.textContent")
    finally:
        lab.close()


def test_readouts_show_rounding_as_zero(browser, book):
    """Generated polygons with straight vertices (midpoints inserted): psi and the curvatures there
    read 0, never 1e-15; a figure-eight's signed area reads 0; dragged vertices land on a thousandth."""
    lab = Lab(browser, book, PAGE + "?lab=eight#lab")
    page = lab.page
    try:
        assert "signed area 0." in lab.get("lab.summary.textContent")
        for v in polygons(20, seed=17):
            v = np.insert(v, 2, (v[1] + v[2]) / 2, axis=0)  # vertex 2: straight, to rounding
            lab.set_polygon(v)
            page.evaluate(f"() => {{ {LAB}.select(2, true); {LAB}.update(); }}")
            detail = lab.get("lab.detail.textContent")
            assert re.search(r"ψ = 0° \(straight, to rounding\); k: angle 0, sine 0, tangent 0, circle 0; \|.∇L.\| = 0\.$", detail), detail
            assert not re.search(r"e-1\d", detail + lab.get("lab.summary.textContent"))
        box = page.locator("svg.ddg-lab-svg").bounding_box()
        page.mouse.click(box["x"] + 5, box["y"] + 5)  # far from every vertex: nothing taken
        x, y = page.evaluate(f"""() => {{ const c = {LAB}.circles[0].getBoundingClientRect(); return [c.x + c.width / 2, c.y + c.height / 2]; }}""")
        page.mouse.move(x, y)
        page.mouse.down()
        page.mouse.move(x + 23.3, y + 11.7, steps=4)
        page.mouse.up()
        vertex = lab.get("lab.vertices[0]")
        assert all(abs(c * 1000 - round(c * 1000)) < 1e-9 for c in vertex), vertex
    finally:
        lab.close()


def swipe(page, points, pause=20):
    """A finger put down on the first point, moved through the others, lifted (Chromium's touch
    events through its DevTools protocol, one session for the gesture)."""
    cdp = page.context.new_cdp_session(page)
    for j, (x, y) in enumerate(points):
        cdp.send("Input.dispatchTouchEvent", {"type": "touchMove" if j else "touchStart", "touchPoints": [{"x": x, "y": y}]})
        page.wait_for_timeout(pause)
    cdp.send("Input.dispatchTouchEvent", {"type": "touchEnd", "touchPoints": []})
    cdp.detach()


def test_a_finger_drags_as_far_as_it_moves(browser, book):
    """CDP touch events on the phone: a vertex follows a 64 px swipe to its end in every direction
    (no pointercancel, the page does not scroll); a swipe away from every vertex scrolls the page."""
    lab = Lab(browser, book, PAGE + "?lab=regular&n=8#lab", phone=True)
    page = lab.page
    try:
        page.evaluate(f"() => {{ window.cancelled = 0; {LAB}.svg.addEventListener('pointercancel', () => window.cancelled++); }}")
        rng = np.random.default_rng(4)
        for j in rng.choice(8, size=6).tolist():
            angle = rng.uniform(0, 2 * np.pi)
            dx, dy = 64 * np.cos(angle), 64 * np.sin(angle)
            before, scroll = lab.get("lab.vertices.map(p => p.slice())"), page.evaluate("scrollY")
            x, y = page.evaluate(f"""j => {{ const c = {LAB}.circles[j].getBoundingClientRect(); return [c.x + c.width / 2, c.y + c.height / 2]; }}""", j)
            swipe(page, [(x + dx * k / 8, y + dy * k / 8) for k in range(9)])
            after, scale = lab.get("lab.vertices"), lab.get("lab.svg.getScreenCTM().a")
            moved = (np.array(after[j]) - before[j]) * scale  # in pixels, y up
            assert np.allclose(moved, [dx, -dy], atol=2.5), (j, moved, dx, dy)
            assert page.evaluate("scrollY") == scroll and page.evaluate("window.cancelled") == 0
            assert np.array_equal(np.delete(after, j, axis=0), np.delete(before, j, axis=0))
            assert lab.get("lab.selected") == j
            page.evaluate(f"() => {LAB}.undo()")  # back, so that every vertex stays in the drawing
        box = page.locator("svg.ddg-lab-svg").bounding_box()
        scroll = page.evaluate("scrollY")
        x, y = box["x"] + 6, box["y"] + box["height"] - 6  # a corner, far from the octagon
        swipe(page, [(x, y - 20 * k) for k in range(6)])
        assert page.evaluate("scrollY") == pytest.approx(scroll + 100, abs=2)
    finally:
        lab.close()


@pytest.mark.parametrize("view", VIEWS)
def test_the_flow_player(browser, book, view):
    """Play at a speed, Pause, Step, the time slider over the recorded run, the stop rules marked on
    a chart with axes; the runs are cleared when the polygon changes; a long run (n = 2000) stops
    computing when paused."""
    phone = view.startswith("phone")
    lab = Lab(browser, book, PAGE + "?lab=pentagon#lab", phone)
    page = lab.page
    try:
        pentagon = POLYGONS["convex pentagon"]
        page.locator(".ddg-lab-flows select").select_option(label="fast (3 s)")
        lab.press("Play")
        page.wait_for_function(f"() => {LAB}.flows.runs && {LAB}.flows.runs.every(r => r.stopped)", timeout=60_000)
        assert lab.get("lab.flows.play.getAttribute('aria-pressed')") == "true"  # the run still plays
        page.wait_for_function(f"() => {LAB}.flows.play.getAttribute('aria-pressed') === 'false'", timeout=20_000)
        runs = lab.get("lab.flows.runs.map(r => [r.kind, r.t, r.stopped])")
        for kind, t, stopped in runs:
            run = flow(pentagon, kind, 10.0, snapshots=2, progress=False)
            assert t == pytest.approx(run.times[-1], rel=1e-6) and stopped in run.stopped
        stops = page.locator(".ddg-lab-flows text.ddg-chart-stop").all_text_contents()
        assert stops == ["edge < 2% of mean"] * 3, stops
        assert page.locator(".ddg-lab-flows .ddg-chart-tick").count() >= 6
        assert page.locator(".ddg-lab-flows .ddg-chart-label").all_text_contents() == ["time t", "L/L(0), A/|A(0)|"]
        # the slider at a generated moment: each panel shows its last snapshot by then
        tmax = max(t for _, t, _ in runs)
        for value in (0, 137, 500, 999, 1000):
            page.locator(".ddg-lab-time input").fill(str(value))
            time = value / 1000 * tmax
            shown = lab.get("lab.flows.runs.map(r => [r.shown, r.frames.map(f => f[0]).concat([r.t])])")
            for at, times in shown:
                assert at == max(x for x in times if x <= time + 1e-15), (value, at)
            assert float(lab.get("lab.flows.shownTime.textContent")) == six(time)
        # on generated presets the panels show, at every moment, a snapshot at most t/240 back from the
        # last step by then (the ellipse's once stayed at t = 0 for half its run: its steps shrink late)
        for query in ("ellipse", "ellipse&n=24", "blob&n=40", "regular&n=30", "star"):
            page.goto(lab.base + PAGE + f"?lab={query}#lab")
            lab.ready()
            page.evaluate(f"() => {{ const f = {LAB}.flows; f.begin(); for (let k = 0; k < 20000 && f.step(); k++); }}")
            tmax = lab.get("lab.flows.tmax()")
            for value in range(0, 1001, 50):
                page.locator(".ddg-lab-time input").fill(str(value))
                for shown, times, end in lab.get("lab.flows.runs.map(r => [r.shown, r.record.map(p => p[0]), r.t])"):
                    now = max(t for t in times if t <= value / 1000 * tmax + 1e-15)
                    assert now - now / 240 <= shown <= now, (query, value, now, shown, end)
        page.goto(lab.base + PAGE + "?lab=pentagon#lab")
        lab.ready()
        page.locator(".ddg-lab-flows select").select_option(label="fast (3 s)")
        lab.press("Flow this shape")
        page.evaluate(f"() => {{ const f = {LAB}.flows; while (f.step()); f.draw(); }}")
        # Step from the start goes to the next recorded time
        page.locator(".ddg-lab-time input").fill("0")
        lab.press("Step")
        first = min(t for t in lab.get("lab.flows.runs.map(r => r.record[1][0])"))
        assert lab.get("lab.flows.time") == first
        # the polygon changes: the runs are cleared, and said
        page.evaluate(f"() => {LAB}.circles[0].focus()")
        page.keyboard.press("ArrowUp")
        assert lab.get("lab.flows.runs") is None and "polygon changed" in lab.get("lab.flows.status.textContent")
        assert lab.get("[lab.flows.slider.value, lab.flows.slider.disabled]") == ["0", True]
        assert page.locator(".ddg-lab-flow").count() == 0
        # n = 2000: Play, then Pause; nothing is computed after the pause
        page.goto(lab.base + PAGE + "?lab=regular&n=2000#lab")
        lab.ready()
        lab.press("Play")
        page.wait_for_function(f"() => {LAB}.flows.runs && {LAB}.flows.runs[0].record.length > 3", timeout=30_000)
        lab.press("Pause")
        steps = lab.get("lab.flows.runs.map(r => r.record.length)")
        page.wait_for_timeout(500)
        assert lab.get("lab.flows.runs.map(r => r.record.length)") == steps
        assert lab.get("lab.flows.play.textContent") == "Play"
    finally:
        lab.close()


def test_charts_have_axes_and_the_drawing_holds_its_arrows(browser, book):
    """The curvature chart has ticks, axis labels and a legend; with the arrows of grad L on the
    star, every arrow lies inside the drawing's view."""
    lab = Lab(browser, book, PAGE + "?lab=star&arrows=1#lab")
    try:
        assert lab.page.locator(".ddg-lab > svg.ddg-lab-chart .ddg-chart-tick").count() >= 6
        labels = lab.page.locator(".ddg-lab > svg.ddg-lab-chart .ddg-chart-label").all_text_contents()
        assert labels == ["vertex i", "kᵢ"]
        shown = "() => [...document.querySelectorAll('.ddg-lab > svg.ddg-lab-chart text.ddg-chart-legend')].filter(t => t.closest('g').getAttribute('visibility') !== 'hidden').map(t => t.textContent)"
        assert lab.page.evaluate(shown) == ["kᵢ of the polygon"]  # the star is no sample of a smooth curve
        lab.page.locator(".ddg-lab select").first.select_option("ellipse")
        assert lab.page.evaluate(shown) == ["kᵢ of the polygon", "κ(tᵢ) of the smooth curve"]
        lab.page.evaluate(f"() => {{ {LAB}.circles[3].focus(); }}")
        lab.page.keyboard.press("ArrowUp")  # no longer the ellipse's sample: no kappa beside it
        assert lab.page.evaluate(shown) == ["kᵢ of the polygon"] and lab.get("lab.shape.value") == "edited"
        lab.page.keyboard.press("Control+z")  # back to the preset, untouched (the keys: the ring's vertex)
        assert lab.page.evaluate(shown) == ["kᵢ of the polygon", "κ(tᵢ) of the smooth curve"]
        assert lab.get("[lab.shape.value, lab.n.value, lab.n.disabled]") == ["ellipse", "10", False]  # n: the star's 10, carried over
        x, y, w, h = map(float, lab.get("lab.svg.getAttribute('viewBox')").split())
        numbers = np.array([float(a) for a in re.findall(r"-?[\d.]+(?:e-?\d+)?", lab.get("lab.arrowPath.getAttribute('d')"))]).reshape(-1, 2)
        assert (numbers[:, 0] >= x).all() and (numbers[:, 0] <= x + w).all()
        assert (numbers[:, 1] >= y).all() and (numbers[:, 1] <= y + h).all()
    finally:
        lab.close()


@pytest.mark.parametrize("view", VIEWS)
def test_full_screen_and_nothing_covers_the_readouts(browser, book, view):
    """Full screen: the lab alone, the drawing whole on the screen; Escape (or the button) leaves
    it. On the page, the theme's Back to top button never shows over the lab."""
    phone = view.startswith("phone")
    lab = Lab(browser, book, PAGE + "?lab=blob#lab", phone)
    page = lab.page
    try:
        lab.press("Full screen")
        box, root = page.locator("svg.ddg-lab-svg").bounding_box(), page.locator(".ddg-lab").bounding_box()
        size = page.viewport_size
        assert root["x"] == 0 and root["y"] == 0 and root["width"] == size["width"]
        assert box["y"] + box["height"] <= size["height"] and box["width"] >= 0.55 * min(size["width"], size["height"])
        if phone:
            lab.press("Leave full screen")
        else:
            page.keyboard.press("Escape")
        assert page.locator(".ddg-lab").bounding_box()["y"] >= 0 and lab.get("lab.full.textContent") == "Full screen"
        page.mouse.wheel(0, 400)
        page.mouse.wheel(0, -200)  # the theme shows Back to top when the reader scrolls up
        page.wait_for_timeout(300)
        assert not page.locator("#pst-back-to-top").is_visible()
    finally:
        lab.close()


@pytest.mark.parametrize("view", VIEWS)
def test_exercise_when_a_corner_turns_reflex_by_touch_or_keys(browser, book, view):
    """Chapter 10's exercise ex-explore-reflex as a student does it: the hexagon, vertex 2 selected
    by a tap on its row in the table (phone) or on the vertex (desktop), then ↑ pressed (the pad's
    button by finger, the arrow key on the desktop): psi_2 turns negative at the 58th press, as the
    solution says, and each press moves v_2 by 0.01."""
    phone = view.startswith("phone")
    lab = Lab(browser, book, PAGE + "?lab=regular&n=6#lab", phone)
    page = lab.page
    try:
        start = np.array(lab.get("lab.vertices"))
        if phone:
            page.locator(".ddg-lab-table summary").tap()
            page.locator(".ddg-lab-table tbody tr").nth(2).tap()
        else:
            x, y = page.evaluate(f"() => {{ const c = {LAB}.circles[2].getBoundingClientRect(); return [c.x + c.width / 2, c.y + c.height / 2]; }}")
            page.mouse.click(x, y)
        assert lab.get("lab.selected") == 2
        up = page.locator(".ddg-lab-pad").get_by_role("button", name="move it up by 0.01 (key: ↑)")
        for presses in range(1, 59):
            up.tap() if phone else page.keyboard.press("ArrowUp")
            if presses in (1, 57, 58):
                psi = float(re.search(r"ψ = (-?[\d.]+)°", lab.get("lab.detail.textContent"))[1])
                assert (psi > 0) == (presses <= 57), (presses, psi)
        v = np.array(lab.get("lab.vertices"))
        assert np.allclose(v[2] - start[2], [0, 0.58], atol=1e-12) and np.array_equal(np.delete(v, 2, 0), np.delete(start, 2, 0))
        assert lab.get("lab.message.textContent") == ""
    finally:
        lab.close()


def test_a_vertex_let_go_outside_the_view_is_shown_and_messages_end(browser, book):
    """A vertex dragged out of the drawing and let go there: the view grows to show it. A message
    lasts until the next action: Remove on a triangle is said, and the next press ends it."""
    lab = Lab(browser, book, PAGE + "?lab=regular&n=3#lab")
    page = lab.page
    try:
        x, y = page.evaluate(f"() => {{ const c = {LAB}.circles[0].getBoundingClientRect(); return [c.x + c.width / 2, c.y + c.height / 2]; }}")
        box = page.locator("svg.ddg-lab-svg").bounding_box()
        page.mouse.move(x, y)
        page.mouse.down()
        page.mouse.move(box["x"] + box["width"] + 150, y - 40, steps=6)
        page.mouse.up()
        vx, vy = lab.get("lab.vertices[0]")
        left, top, width, height = map(float, lab.get("lab.svg.getAttribute('viewBox')").split())
        assert vx > 1.5 and left <= vx <= left + width and top <= -vy <= top + height, (vx, vy, left, width)
        lab.press("Remove vertex")
        assert "at least 3 vertices" in lab.message()
        page.locator(".ddg-lab select").nth(1).select_option("sine")
        assert lab.message() == ""
        lab.press("Remove vertex")
        lab.press("Undo")
        assert lab.message() == "" and lab.get("lab.vertices[0][0]") < 1.01  # the drag undone
    finally:
        lab.close()


def test_undo_goes_back_through_presets_with_their_names(browser, book):
    """Preset after preset, then Undo: each polygon comes back with its own name in the list, its n,
    and whether n can be changed."""
    lab = Lab(browser, book, PAGE + "?lab=regular&n=12#lab")
    page = lab.page
    try:
        shape = page.locator(".ddg-lab select").first
        for name in ("star (chapter 5)", "ellipse", "figure-eight"):
            shape.select_option(name)
        for name, n, fixed in (("ellipse", 10, False), ("star (chapter 5)", 10, True), ("regular n-gon", 12, False)):
            lab.press("Undo")
            assert lab.get("[lab.shape.value, lab.vertices.length, lab.n.value, lab.n.disabled]") == [name, n, str(n), fixed]
        assert np.allclose(lab.get("lab.vertices"), ddg.regular_polygon(12).vertices, atol=1e-15)
        lab.press("Undo")
        assert lab.message() == "Nothing to undo."
    finally:
        lab.close()


def test_a_tap_selects_and_what_undo_and_step_leave(browser, book):
    """A click beside a vertex (within reach, no movement) selects it and moves nothing; a drag keeps
    the vertex where it was relative to the pointer; Undo after a preset change gives Reset that
    preset back; Step on a polygon that cannot flow says why; Ctrl+Z in the eps box is the box's."""
    lab = Lab(browser, book, PAGE + "?lab=regular&n=8&inflate=offset#lab")
    page = lab.page
    try:
        start = lab.get("lab.vertices.map(p => p.slice())")
        x, y = page.evaluate(f"() => {{ const c = {LAB}.circles[3].getBoundingClientRect(); return [c.x + c.width / 2, c.y + c.height / 2]; }}")
        page.mouse.click(x + 8, y - 5)
        assert lab.get("lab.selected") == 3 and lab.get("lab.vertices") == start and lab.get("lab.shape.value") == "regular n-gon"
        page.mouse.move(x + 8, y - 5)
        page.mouse.down()
        page.mouse.move(x + 48, y - 5, steps=5)
        page.mouse.up()
        moved, scale = lab.get("lab.vertices[3]"), lab.get("lab.svg.getScreenCTM().a")
        assert np.allclose((np.array(moved) - start[3]) * scale, [40, 0], atol=1.5), (moved, start[3])
        page.locator(".ddg-lab select").first.select_option("star (chapter 5)")
        lab.press("Undo")  # the dragged octagon again
        lab.press("Undo")  # the octagon as preset
        lab.press("Reset")
        assert lab.get("[lab.shape.value, lab.vertices.length]") == ["regular n-gon", 8]
        box = page.locator(".ddg-lab input[aria-label='ε typed']")
        box.click()
        box.press("Control+a")
        box.press_sequentially("0.3")
        box.press("Control+z")
        assert lab.get("lab.vertices.length") == 8 and lab.get("lab.shape.value") == "regular n-gon"
        lab.press("Draw")
        lab.press("Step")  # no polygon: said, no error
        assert "No flow" in lab.get("lab.flows.status.textContent")
    finally:
        lab.close()
