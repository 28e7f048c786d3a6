"""Helpers of the browser tests (the fixtures are in conftest.py). The built sites in a real browser: Chromium (found by tools/browser.py) driven by Playwright.

Both sites that `make test` builds are served on 127.0.0.1: the book (_build/html) and the student
edition (_build/student/html). Every request that leaves loopback is recorded and cut off.
With DDG_SCREENSHOTS set (`make screenshots`), a screenshot of each page in each view goes to
_build/screenshots/<site>/<view>/; `make test` takes none (they assert nothing and cost a quarter
of each page's time).
"""

import functools
import http.server
import os
import pathlib
import re
import threading
import urllib.parse
import urllib.request

import pytest


sync_api = pytest.importorskip("playwright.sync_api")

ROOT = pathlib.Path(__file__).resolve().parents[2]
SITES = {"book": ROOT / "_build" / "html", "student": ROOT / "_build" / "student" / "html"}
SHOTS = ROOT / "_build" / "screenshots"
VIEWS = {"desktop": {"width": 1280, "dark": False}, "phone": {"width": 390, "dark": False},
         "dark": {"width": 1280, "dark": True}}

# <meta http-equiv="Refresh" content="0; url=book/intro.html" />: what Sphinx writes as index.html
REFRESH = re.compile(r'<meta\s+http-equiv="refresh"\s+content="\d+;\s*url=([^"]+)"', re.I)

# Console errors this stack is known to print, harmless to a reader:
ALLOWED_CONSOLE = []


def pages(site):
    folder = SITES[site]
    if not folder.exists():
        return []
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*.html") if "_static" not in p.parts
                  and p.name not in ("genindex.html", "search.html"))


class Server(http.server.ThreadingHTTPServer):
    request_queue_size = 64  # not 5: a page asks for its fonts, images and scripts at once


@pytest.fixture(scope="session")
def servers():
    """One loopback server per built site: {site: base URL}."""
    urls, running = {}, []

    class Quiet(http.server.SimpleHTTPRequestHandler):
        def log_message(self, *args):
            pass

    for site, folder in SITES.items():
        if not (folder / "index.html").exists():
            pytest.fail(f"no {site} site in {folder}: run `make test` (it builds both)")
        httpd = Server(("127.0.0.1", 0), functools.partial(Quiet, directory=str(folder)))
        threading.Thread(target=httpd.serve_forever, daemon=True).start()
        urls[site] = f"http://127.0.0.1:{httpd.server_port}/"
        running.append(httpd)
    yield urls
    for httpd in running:
        httpd.shutdown()


# A reader scrolls through the page, two screens at a time: what loads as it comes near (images,
# the explorers and their states) loads, and each section is laid out (ddg-book.css).
def _probes():
    """The functions the browser tests run in the page, from probes.js (each under a `//# NAME` line)."""
    text = (pathlib.Path(__file__).parent / "probes.js").read_text()
    return {name: body.strip() for name, body in re.findall(r"^//# (\w+)\n(.*?)(?=^//# |\Z)", text, re.M | re.S)}


PROBES = _probes()
SCROLL_THROUGH, WAITING = PROBES["SCROLL_THROUGH"], PROBES["WAITING"]
# A section out of view is not drawn (ddg-book.css: content-visibility), so what looks at the whole
# page at once (axe's colour contrast, a full-page screenshot) has every section drawn.
EVERY_SECTION = "* { content-visibility: visible !important; }"
# Loaded: every figure shown and every explorer, and the fonts (else: what is still waiting)
PENDING = f"""() => ({WAITING})().map(e => e.outerHTML.slice(0, 160))
    .concat(document.fonts.status === "loaded" ? [] : ["fonts: " + document.fonts.status])"""


class Visit:
    """One page load, read through, with every request, failure and console message recorded.

    The page is loaded once at desktop width in the light theme; `show(view)` then turns the same
    page into another view the way a reader's device would: a narrower window (the page lays
    itself out again) or the system switching to dark (the theme follows it live). With
    ``touch=True`` the page also takes taps and finger drags.
    """

    def __init__(self, browser, base, path, view="desktop", touch=False):
        self.base, self.outside, self.failed, self.console, self.requests = base, [], [], [], []
        self.ignoring = False  # requests made by axe itself are not the site's
        self.context = browser.new_context(viewport={"width": 1280, "height": 900}, color_scheme="light", has_touch=touch)
        self.context.route("**/*", self._route)
        self.page = self.context.new_page()
        self.page.on("request", lambda r: not self.ignoring and self.requests.append(r.url))
        self.page.on("console", lambda m: m.type == "error" and not self.ignoring and self.console.append(m.text))
        self.page.on("pageerror", lambda e: self.console.append(str(e)))
        self.page.on("response", lambda r: r.status >= 400 and not self.ignoring and self.failed.append(f"{r.status} {r.url}"))
        self.page.on("requestfailed", lambda r: not self.ignoring and not self._icon_dropped(r)
                     and self.failed.append(f"failed {r.url}: {r.failure}"))
        url = base + path
        try:  # loopback only; a page that cannot be read is reported by the visit itself
            with urllib.request.urlopen(url, timeout=10) as response:
                redirect = REFRESH.search(response.read().decode("utf-8", "replace"))
        except OSError:
            redirect = None
        self.page.goto(url, wait_until="load")
        if redirect:  # a redirect page (the site's index.html): the reader lands on its target
            self.page.wait_for_url(urllib.parse.urljoin(url, redirect.group(1)), wait_until="load")
        self.page.evaluate(SCROLL_THROUGH, WAITING)
        try:
            self.page.wait_for_function(f"() => !({PENDING})().length", timeout=60_000)
        except sync_api.TimeoutError:
            raise AssertionError(f"{path}: not loaded after a minute: {self.page.evaluate(PENDING)}") from None
        self.page.add_style_tag(content=EVERY_SECTION)
        self.show(view)

    def show(self, view):
        """Turn the loaded page into `view`: its window width and its system colour scheme."""
        width, dark = VIEWS[view]["width"], VIEWS[view]["dark"]
        self.page.emulate_media(color_scheme="dark" if dark else "light")
        self.page.set_viewport_size({"width": width, "height": 900})
        self.page.evaluate("() => new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))")
        self.page.wait_for_timeout(100)
        # the theme's buttons fade their colours over 0.15 s: on a busy machine axe judged a search
        # button half-way to dark (CI, stop 39), so colours are read once every fade has ended
        self.page.wait_for_function(PROBES["NO_TRANSITION"])

    @staticmethod
    def _icon_dropped(request):
        """The browser fetches the tab's icon after the page loaded, and an explorer's states as it
        comes near (chapter 10's lab scrolls to itself, next to the explorer): both are dropped when
        a test moves on to another page."""
        path = request.url.split("?")[0]
        return (path.endswith("/_static/ddg-icon-192.png") or "/_static/ddg-states/" in path) and "ERR_ABORTED" in str(request.failure)

    def _route(self, route):
        url = route.request.url
        if url.startswith(self.base) or url.startswith(("data:", "blob:")):
            route.continue_()
        else:  # nothing may leave loopback: record it and cut it off
            self.outside.append(url)
            route.abort()

    def unexpected_console(self):
        return [m for m in self.console if not any(re.search(a, m) for a in ALLOWED_CONSOLE)]

    def screenshot(self, site, view, path):
        if os.environ.get("DDG_SCREENSHOTS", "") in ("", "0"):  # set by `make screenshots`
            return
        folder = SHOTS / site / view
        folder.mkdir(parents=True, exist_ok=True)
        self.page.screenshot(path=str(folder / (path.replace("/", "__").removesuffix(".html") + ".jpg")),
                             full_page=True, type="jpeg", quality=70)

    def close(self):
        self.context.close()
