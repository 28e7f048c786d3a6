"""The built book in a real browser: Debian's chromium driven by Playwright, served on loopback.

Run after the book is built (``make test`` does): every page of ``_build/html`` is opened with
the network cut off beyond 127.0.0.1. A full-page screenshot of each page goes to
``_build/screenshots/``.
"""

import functools
import http.server
import pathlib
import re
import shutil
import threading
from urllib.parse import unquote, urljoin, urlparse

import pytest

playwright = pytest.importorskip("playwright.sync_api")

ROOT = pathlib.Path(__file__).resolve().parents[2]
SITE = ROOT / "_build" / "html"
SHOTS = ROOT / "_build" / "screenshots"
CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--disable-background-networking",
         "--disable-component-update", "--disable-sync"]

# Console errors this stack is known to print, harmless to a reader (GUIDE §5):
ALLOWED_CONSOLE = [
    r"Identifier 'THEBE_JS_URL' has already been declared",  # sphinx-thebe declares it twice
    r"Got invalid theme mode",                               # the theme, before it reads the stored mode
    r"reading 'Queue'",                                      # the widgets embedder calls MathJax 2's Hub.Queue
    r"strict mode: use allowUnionTypes",                     # the embedder's schema validator, a warning
]

PAGES = sorted(str(p.relative_to(SITE)) for p in SITE.rglob("*.html") if "_static" not in p.parts) if SITE.exists() else []


@pytest.fixture(scope="module")
def server():
    if not (SITE / "index.html").exists():
        pytest.fail("no built book in _build/html: run `make book` first")
    shutil.rmtree(SHOTS, ignore_errors=True)  # screenshots of this build only

    class Quiet(http.server.SimpleHTTPRequestHandler):
        def log_message(self, *args):
            pass

    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(Quiet, directory=str(SITE)))
    threading.Thread(target=httpd.serve_forever, daemon=True).start()
    yield f"http://127.0.0.1:{httpd.server_port}/"
    httpd.shutdown()


@pytest.fixture(scope="module")
def browser():
    with playwright.sync_playwright() as p:
        chromium = p.chromium.launch(executable_path=CHROMIUM, args=FLAGS)
        yield chromium
        chromium.close()


class Visit:
    """One page load with every request, failure and console message recorded."""

    def __init__(self, browser, base, path):
        self.base, self.outside, self.failed, self.console = base, [], [], []
        self.context = browser.new_context(viewport={"width": 1280, "height": 900})
        self.context.route("**/*", self._route)
        self.page = self.context.new_page()
        self.page.on("console", lambda m: m.type in ("error", "warning") and self.console.append(m.text))
        self.page.on("pageerror", lambda e: self.console.append(str(e)))
        self.page.on("response", lambda r: r.status >= 400 and self.failed.append(f"{r.status} {r.url}"))
        self.page.on("requestfailed", lambda r: self.failed.append(f"failed {r.url}: {r.failure}"))
        self.page.goto(base + path, wait_until="networkidle")

    def _route(self, route):
        url = route.request.url
        if url.startswith(self.base) or url.startswith("data:") or url.startswith("blob:"):
            route.continue_()
        else:  # nothing may leave loopback: record it and cut it off
            self.outside.append(url)
            route.abort()

    def unexpected_console(self):
        return [m for m in self.console if not any(re.search(a, m) for a in ALLOWED_CONSOLE)]

    def close(self):
        self.context.close()


@pytest.mark.parametrize("path", PAGES)
def test_page_works_offline(server, browser, path):
    visit = Visit(browser, server, path)
    page = visit.page
    try:
        if page.locator(".math").count():  # a page with math shows rendered equations, no MathJax error
            page.wait_for_selector("mjx-container", state="attached", timeout=15000)
            assert page.locator("mjx-merror").count() == 0
        page.wait_for_timeout(300)
        # every local link and image resolves to a file of the site
        targets = page.eval_on_selector_all(
            "a[href], img[src], script[src], link[href]", "els => els.map(e => e.getAttribute('href') || e.getAttribute('src'))")
        missing = []
        for target in targets:
            url = urlparse(urljoin(page.url, target))  # page.url: index.html redirects to the first chapter
            if url.scheme in ("http", "https") and url.netloc == urlparse(server).netloc:
                local = SITE / unquote(url.path).lstrip("/")
                if local.is_dir():
                    local = local / "index.html"
                if not local.exists():
                    missing.append(target)
        SHOTS.mkdir(parents=True, exist_ok=True)
        page.screenshot(path=str(SHOTS / (path.replace("/", "__").removesuffix(".html") + ".png")), full_page=True)
        assert not visit.outside, f"requests outside loopback: {visit.outside}"
        assert not visit.failed, f"failed requests: {visit.failed}"
        assert not visit.unexpected_console(), f"console errors: {visit.unexpected_console()}"
        assert not missing, f"local links or images that do not resolve: {missing}"
    finally:
        visit.close()


def test_pages_were_found():
    assert "book/05_inflation.html" in PAGES and len(PAGES) >= 10


@pytest.mark.parametrize("path", ["book/05_inflation.html", "book/08_curve_shortening.html"])
def test_animation_plays(server, browser, path):
    visit = Visit(browser, server, path)
    try:
        frame = visit.page.locator("img[id^='_anim_img']").first
        before = frame.get_attribute("src")
        visit.page.locator("button[onclick*='play_animation']").first.click()
        visit.page.wait_for_timeout(1200)
        assert frame.get_attribute("src") != before, "the animation did not change frame after Play"
    finally:
        visit.close()


def test_explorers_show_their_saved_state(server, browser):
    visit = Visit(browser, server, "book/09_explorers.html")
    try:
        page = visit.page
        page.wait_for_selector(".widget-slider", timeout=15000)
        assert page.locator(".widget-slider").count() >= 4  # n, eps and the two vertex sliders
        images = page.locator(".jupyter-widgets img")
        assert images.count() == 3
        assert all(images.nth(i).evaluate("img => img.naturalWidth") > 300 for i in range(3))
        assert "needs a running kernel" in page.inner_text("body").lower() or "need a running kernel" in page.inner_text("body").lower()
    finally:
        visit.close()


def test_solutions_stay_hidden_until_clicked(server, browser):
    pages = [p for p in PAGES if "solution" in (SITE / p).read_text(encoding="utf-8")]
    solution_pages = [p for p in pages if re.search(r'class="[^"]*\bsolution\b', (SITE / p).read_text(encoding="utf-8"))]
    if not solution_pages:
        pytest.skip("the book has no solutions yet")
    for path in solution_pages:
        visit = Visit(browser, server, path)
        try:
            solutions = visit.page.locator(".solution")
            assert solutions.count() >= 3, f"{path}: expected the chapter's solutions"
            for i in range(solutions.count()):  # every solution starts folded
                body = solutions.nth(i).locator(":scope > :not(.admonition-title)")
                assert body.count() and not any(body.nth(j).is_visible() for j in range(body.count())), \
                    f"{path}: solution {i} is visible before its toggle is clicked"
            first = solutions.first
            first.locator(".toggle-button").click()
            visit.page.wait_for_timeout(500)
            assert first.locator(":scope > :not(.admonition-title)").first.is_visible(), f"{path}: a solution does not open when clicked"
        finally:
            visit.close()


def test_every_page_and_the_site_fit_their_budgets():
    """Each page (its HTML and the images it shows) at most 2 MB; the whole site at most 25 MB."""
    heavy = {}
    for path in PAGES:
        html = (SITE / path).read_text(encoding="utf-8")
        images = {m for m in re.findall(r'<img[^>]+src="([^"]+)"', html) if not m.startswith(("data:", "http"))}
        size = (SITE / path).stat().st_size + sum((SITE / path).parent.joinpath(src).stat().st_size for src in images)
        if size > 2 * 2**20:
            heavy[path] = size
    assert not heavy, f"pages over 2 MB: {heavy}"
    site = sum(p.stat().st_size for p in SITE.rglob("*") if p.is_file())
    assert site < 25 * 2**20, f"the site is {site / 2**20:.1f} MB"
