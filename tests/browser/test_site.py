"""Every page of both sites, as a reader sees it: desktop, phone and dark theme, network cut off.

On each page, read through: nothing requested outside loopback and nothing failing, no unexpected
console error, every local link resolving, every script it loads one it uses, at most 700 kB
transferred (gzip), every icon drawn, every formula typeset (when the book was built) in MathJax's
fonts, with a text for screen readers (its MathML), no TeX left in the visible text, exactly one
visible h1, at 1280 px no code or output box scrolling sideways and small figures side by side,
at 390 px no page scrolling sideways (wide tables and equations scroll inside their own box, with
a visible cue) and figures not shrunk, on the dark theme figures not dimmed, and no serious or
critical violation of axe-core's WCAG 2 A/AA rules. Solutions are folded until a reader clicks
their title, which opens them without leaving the page. With DDG_SCREENSHOTS set (`make
screenshots`), a screenshot of each page in each view is saved.
"""

import gzip
import pathlib
import re
from urllib.parse import unquote, urljoin, urlparse

import pytest
from browser_helpers import PROBES, SITES, Visit, pages, sync_api

axe_module = pytest.importorskip("axe_playwright_python.sync_playwright")

# Every WCAG 2 A/AA rule, colour contrast judged on a sample (CONTRAST_SAMPLE). The dark theme
# changes colours only: there the rules about colour are the ones that can change.
AXE_OPTIONS = {"runOnly": {"type": "tag", "values": ["wcag2a", "wcag2aa"]}, "resultTypes": ["violations"]}
AXE_COLOURS = {"runOnly": {"type": "rule", "values": ["color-contrast", "link-in-text-block"]},
               "resultTypes": ["violations"]}
AXE_SOURCE = axe_module.Axe().axe_script

# Colour contrast costs axe 3-4 ms an element (it finds what lies behind each one), and a chapter
# has over a thousand elements with text, most styled alike (each token of each code cell is one).
# Text whose element and ancestors all have the same tag, classes, colours, opacity and font has
# the same contrast, so one element of each such kind is marked and axe judges those: about 280 of
# 1 280 on chapter 7, in a third of the time, and a low-contrast style planted on any kind is found.
CONTRAST_SAMPLE = PROBES["CONTRAST_SAMPLE"]

TEX_LEFT = PROBES["TEX_LEFT"]

# Every formula Sphinx wrote is typeset, hidden from screen readers as drawn and read as its
# MathML (MathJax's assistive MathML); MathJax's fonts for it loaded, none failed.
UNREADABLE_MATH = PROBES["UNREADABLE_MATH"]
FONTS_FAILED = PROBES["FONTS_FAILED"]
MATH_FONTS = PROBES["MATH_FONTS"]

# The theme's icons are drawn (inline SVG, tools/sphinx_assets.py): none is left to a script.
ICONS_UNDRAWN = PROBES["ICONS_UNDRAWN"]

SIDEWAYS = PROBES["SIDEWAYS"]

OPEN_SOLUTIONS = PROBES["OPEN_SOLUTIONS"]
SHOWN_SOLUTIONS = PROBES["SHOWN_SOLUTIONS"]
NOTHING_MOVES = PROBES["NOTHING_MOVES"]
PAGE_IS_WIDER = PROBES["PAGE_IS_WIDER"]

# Whatever scrolls sideways (a table's box, a display equation's container, a code or output box,
# a wide inline formula) shows the cue at its edge; whatever would cut its content off is a defect.
UNCUED = PROBES["UNCUED"]

FALSE_CUE = PROBES["FALSE_CUE"]

CUT_INLINE = PROBES["CUT_INLINE"]

SHRUNK = PROBES["SHRUNK"]

DIMMED = PROBES["DIMMED"]

STACKED = PROBES["STACKED"]

LAUNCH = "a[href*='mybinder.org'], a[href*='colab.research']"

VISIBLE_H1 = PROBES["VISIBLE_H1"]


# Every script a page loads, and what a page must have for it to load there ("": every page).
SCRIPTS = {
    "bootstrap.js": "", "pydata-sphinx-theme.js": "", "sphinx-book-theme.js": "",  # the theme's menus and sidebars
    "doctools.js": "", "sphinx_highlight.js": "",  # Sphinx: the words searched for, marked on the page a result opens
    "ddg-book.js": "",  # scroll boxes and their cues
    "clipboard.min.js": "div.highlight pre", "copybutton.js": "div.highlight pre",  # a copy button on code
    "togglebutton.js": ".toggle, .admonition.dropdown",  # what folds: solutions
    "ddg-player.js": ".ddg-explorer", "ddg-states": ".ddg-explorer",  # explorers and animations, and their states
    "ddg-lab.js": ".ddg-lab", "ddg-lab-page.js": ".ddg-lab",  # the lab of chapter 10: ddg's formulas in JavaScript
    "ddg-lab-circle.js": ".ddg-lab",  # and chapter 6's circle curvature (the instructor's edition only)
    "polygon-clipping.umd.min.js": ".ddg-lab",  # and the union with which it measures an inflated region
    "searchtools.js": "#search-results", "language_data.js": "#search-results", "searchindex.js": "#search-results",
}
BUDGET = 700_000  # bytes a page may transfer, compressed as a static host compresses text (gzip)
COMPRESSED = (".html", ".css", ".js", ".svg", ".json", ".txt")


def scripts_unused(page, requests):
    """Scripts the page loaded that it has no use for (SCRIPTS), or that nobody said what they are for."""
    unused = []
    for path in dict.fromkeys(urlparse(url).path for url in requests if urlparse(url).path.endswith(".js")):
        name = next((key for key in SCRIPTS if key == path.split("/")[-1] or f"/{key}/" in path), None)
        if name is None or (SCRIPTS[name] and not page.locator(SCRIPTS[name]).count()):
            unused.append(path.split("/")[-1])
    return unused


def transferred(site, server, requests):
    """The bytes of what the page loaded from the site, text compressed with gzip (level 6) as a
    static host compresses it: a deterministic count (no headers)."""
    total = 0
    for url in dict.fromkeys(requests):
        if not url.startswith(server):
            continue
        local = SITES[site] / unquote(urlparse(url).path).lstrip("/")
        data = (local / "index.html" if local.is_dir() else local).read_bytes()
        total += len(gzip.compress(data, 6)) if local.suffix in COMPRESSED or local.is_dir() else len(data)
    return total


def local_targets_missing(page, site, server):
    """Local links, images, scripts and styles of the page that name no file of the site."""
    targets = page.eval_on_selector_all("a[href], img[src], script[src], link[href]",
                                        "els => els.map(e => e.getAttribute('href') || e.getAttribute('src'))")
    missing = []
    for target in targets:
        url = urlparse(urljoin(page.url, target))
        if url.scheme in ("http", "https") and url.netloc == urlparse(server).netloc:
            local = SITES[site] / unquote(url.path).lstrip("/")
            if local.is_dir():
                local = local / "index.html"
            if not local.exists():
                missing.append(target)
    return missing


def axe_violations(visit, options):
    """axe-core's serious and critical violations of the rules in ``options`` on the page, with
    colour contrast judged on the elements CONTRAST_SAMPLE marks: one axe run, axe injected once."""
    visit.ignoring = True  # axe's own requests are not the page's
    try:
        page = visit.page
        page.wait_for_function(PROBES["NO_TRANSITION"])  # colours mid-fade are neither theme's
        page.evaluate(CONTRAST_SAMPLE)
        if not page.evaluate("() => typeof axe !== 'undefined'"):
            page.evaluate(AXE_SOURCE)
            page.evaluate("() => axe.configure({rules: [{id: 'color-contrast', selector: '[data-ddg-contrast]'}]})")
        violations = page.evaluate("options => axe.run(document, options).then(r => r.violations)", options)
    finally:
        visit.ignoring = False
    return [f"{v['id']} ({v['impact']}): {v['help']} — {v['nodes'][0]['target']}"
            for v in violations if v["impact"] in ("serious", "critical")]


FAINT = [("desktop", "main .highlight .k", "#c8c8c8"), ("dark", "main figcaption", "#4a4a4a")]


def test_the_contrast_sample_finds_a_faint_style(servers, browser):
    """Colour contrast is judged on a sample of elements: one kind of text made faint (keywords in
    the code cells; figure captions on the dark theme, sampled again after the switch) is found,
    on a page that had no contrast violation in that view before."""
    visit = Visit(browser, servers["book"], "book/07_convergence.html")  # as the page test: desktop first
    try:
        for view, selector, colour in FAINT:
            visit.show(view)
            assert not axe_violations(visit, AXE_COLOURS), view
            style = visit.page.add_style_tag(content=f"{selector} {{ color: {colour} !important; }}")
            found = axe_violations(visit, AXE_COLOURS)
            assert any(v.startswith("color-contrast") for v in found), f"{view}: {selector} in {colour}: {found}"
            style.evaluate("element => element.remove()")
    finally:
        visit.close()


def folded_solutions(page, path):
    """Solutions are folded; a solution's title opens it and stays on the page."""
    solutions = page.locator(".solution")
    if not solutions.count():
        return []
    problems = [f"{n} solutions show before they are opened"] if (n := page.evaluate(SHOWN_SOLUTIONS)) else []
    before = page.url
    solutions.first.locator(".admonition-title a").first.click()  # the title's link to the exercise
    try:  # it opens at once; a loaded machine is given up to 5 s
        page.wait_for_function(f"() => ({SHOWN_SOLUTIONS})() === 1", timeout=5000)
    except sync_api.TimeoutError:
        problems += ["a solution's title did not open it"]
    problems += ["clicking a solution's title jumped away"] if page.url != before else []
    return problems


CASES = [(site, path) for site in SITES for path in pages(site)]


@pytest.mark.parametrize("site, path", CASES, ids=[f"{s}:{p}" for s, p in CASES])
def test_page_reads_right_in_every_view(servers, browser, site, path):
    problems = []
    visit = Visit(browser, servers[site], path)
    page = visit.page
    try:
        for view in ("desktop", "phone", "dark"):
            visit.show(view)
            if view == "desktop":
                problems += [f"requests outside loopback: {visit.outside}"] if visit.outside else []
                problems += [f"local targets that do not resolve: {m}"] if (m := local_targets_missing(page, site, servers[site])) else []
                problems += [f"MathJax errors: {n}"] if (n := page.locator("mjx-merror").count()) else []
                problems += [f"formulas without a text: {u[:3]}"] if (u := page.evaluate(UNREADABLE_MATH)) else []
                fonts = page.evaluate(MATH_FONTS)
                if page.locator("main .math").count() and (fonts.get("error") or not fonts.get("loaded")):
                    problems += [f"MathJax's fonts: {fonts}"]
                problems += [f"TeX left in the text: {t[:3]}"] if (t := page.evaluate(TEX_LEFT)) else []
                problems += [f"visible h1: {h}"] if len(h := page.evaluate(VISIBLE_H1)) != 1 else []
                problems += [f"scripts it has no use for: {u}"] if (u := scripts_unused(page, visit.requests)) else []
                problems += [f"icons not drawn: {i[:3]}"] if (i := page.evaluate(ICONS_UNDRAWN)) else []
                problems += [f"fonts that failed: {f}"] if (f := page.evaluate(FONTS_FAILED)) else []
                if (size := transferred(site, servers[site], visit.requests)) > BUDGET:
                    problems += [f"{size / 1000:.0f} kB transferred (gzip), over {BUDGET / 1000:.0f} kB"]
                launch = page.locator(LAUNCH).count()  # Binder and Colab: the book's chapters, never the student site
                chapter = site == "book" and re.match(r"book/\d\d_", path)
                if (launch < 2) if chapter else launch:
                    problems += [f"{launch} launch buttons"]
                problems += folded_solutions(page, path)
                page.evaluate(OPEN_SOLUTIONS)  # a reader opens them: their code must fit too
                page.wait_for_function(NOTHING_MOVES)  # they fade in: colours are judged after
                boxes = page.evaluate(SIDEWAYS, "main div.highlight pre, main .cell_output .output")
                problems += [f"boxes that scroll sideways at 1280 px: {boxes[:3]}"] if boxes else []
                problems += [f"small figures stacked at 1280 px: {f[:3]}"] if (f := page.evaluate(STACKED)) else []
            if view == "phone":
                wider = page.evaluate(PAGE_IS_WIDER)
                problems += [f"the page scrolls sideways by {wider} px at 390 px"] if wider > 1 else []
                problems += [f"wide content without a scroll box and cue: {u[:3]}"] if (u := page.evaluate(UNCUED)) else []
                problems += [f"figures shrunk on a phone: {s[:3]}"] if (s := page.evaluate(SHRUNK)) else []
                problems += [f"a scroll cue on what does not scroll: {f[:3]}"] if (f := page.evaluate(FALSE_CUE)) else []
                problems += [f"inline formulas cut off at 390 px: {c[:3]}"] if (c := page.evaluate(CUT_INLINE)) else []
            if view == "dark":
                theme = page.evaluate("document.documentElement.dataset.theme")
                problems += [f"the page is not in dark mode ({theme})"] if theme != "dark" else []
                problems += [f"figures dimmed on the dark theme: {d[:3]}"] if (d := page.evaluate(DIMMED)) else []
            if view in ("desktop", "dark"):
                rules = AXE_OPTIONS if view == "desktop" else AXE_COLOURS
                problems += [f"{view}: axe: {v}" for v in axe_violations(visit, rules)]
            visit.screenshot(site, view, path)
        problems += [f"failed requests: {visit.failed}"] if visit.failed else []
        problems += [f"console errors: {c}"] if (c := visit.unexpected_console()) else []
    finally:
        visit.close()
    assert not problems, "\n".join(problems)


def test_screenshots_are_saved_whole_when_asked_for(servers, browser, monkeypatch, tmp_path):
    """`make screenshots` (DDG_SCREENSHOTS set) saves each view of a page whole, as a JPEG."""
    import browser_helpers

    monkeypatch.setattr(browser_helpers, "SHOTS", tmp_path)
    monkeypatch.delenv("DDG_SCREENSHOTS", raising=False)
    visit = Visit(browser, servers["student"], "book/04_gradient_of_length.html")
    try:
        visit.screenshot("student", "phone", "book/04_gradient_of_length.html")
        assert not list(tmp_path.rglob("*.jpg")), "a screenshot without DDG_SCREENSHOTS"
        monkeypatch.setenv("DDG_SCREENSHOTS", "1")
        visit.show("phone")
        height = visit.page.evaluate("document.documentElement.scrollHeight")
        visit.screenshot("student", "phone", "book/04_gradient_of_length.html")
    finally:
        visit.close()
    from PIL import Image

    with Image.open(tmp_path / "student" / "phone" / "book__04_gradient_of_length.jpg") as shot:
        assert (shot.format, shot.size) == ("JPEG", (390, height)), "not the whole page at phone width"


@pytest.mark.parametrize("site", list(SITES))
def test_a_reader_searches_from_a_chapter(servers, browser, site):
    """The search box of a chapter (which loads no search index) opens the search page, which
    loads the index and lists the pages that have the words, with the network cut."""
    visit = Visit(browser, servers[site], "book/04_gradient_of_length.html")
    page = visit.page
    try:
        page.locator(".search-button__button:visible").first.click()
        page.locator("#pst-search-dialog input[name=q]").fill("turning number")
        page.keyboard.press("Enter")
        page.wait_for_url("**/search.html?q=turning*")
        page.wait_for_function("() => document.querySelectorAll('#search-results li').length >= 3", timeout=20000)
        found = page.eval_on_selector_all("#search-results li a", "links => links.map(a => a.getAttribute('href'))")
        assert any("03_winding_number" in href for href in found), found
        # each result quotes the prose: no TeX, no formula read out as a run of symbols, no code
        page.wait_for_function("() => document.querySelectorAll('#search-results li .context').length >= 3")
        snippets = page.eval_on_selector_all("#search-results li .context", "ps => ps.map(p => p.textContent)")
        noise = [t for t in snippets if re.search(r"\\[a-zA-Z]+|\$|∫|=2π|import |ddg\.\w+\(|\[\[", t)]
        assert not noise and any("turning number" in t for t in snippets), (noise[:3], snippets[:3])
        assert not scripts_unused(page, visit.requests[visit.requests.index(page.url):])
        assert not visit.outside and not visit.failed and not visit.unexpected_console()
    finally:
        visit.close()


@pytest.mark.parametrize("site, scheme", [(site, scheme) for site in SITES for scheme in ("light", "dark")])
def test_a_phone_reader_opens_the_chapter_list_by_tapping_the_menu(servers, browser, site, scheme):
    """On a phone, light or dark, the ☰ button opens the list of every chapter (the theme alone
    binds a hidden twin of it), a tap on a chapter there opens that chapter, the contents button
    (the same story) opens the page's sections and a tap goes to one, and the page logs no error
    on its first load (no stored theme)."""
    context = browser.new_context(viewport={"width": 390, "height": 844}, has_touch=True, is_mobile=True,
                                  color_scheme=scheme)
    page = context.new_page()
    errors, outside = [], []
    page.on("console", lambda m: m.type == "error" and errors.append(m.text))
    page.on("pageerror", lambda e: errors.append(str(e)))
    context.route("**/*", lambda r: r.continue_() if r.request.url.startswith(servers[site])
                  else (outside.append(r.request.url), r.abort()))
    try:
        page.goto(servers[site] + "book/04_gradient_of_length.html", wait_until="load")
        page.wait_for_function("s => document.documentElement.dataset.theme === s", arg=scheme)
        page.locator(".primary-toggle:visible").first.tap()
        page.wait_for_selector("#pst-primary-sidebar-modal[open]", timeout=5000)
        listed = page.eval_on_selector_all("#pst-primary-sidebar-modal a.reference:visible",
                                           "links => links.map(a => a.getAttribute('href'))")
        chapters = sum(bool(re.search(r"\d\d_\w+\.html$", h)) for h in listed) + listed.count("#")  # "#": this one
        assert chapters >= 10, listed
        link = page.locator("#pst-primary-sidebar-modal a[href$='03_winding_number.html']").first
        link.tap()
        page.wait_for_url("**/03_winding_number.html")
        # the page's contents (the button at the top right): its sections, and a tap goes to one
        page.locator(".secondary-toggle:visible").first.tap()
        page.wait_for_selector("#pst-secondary-sidebar-modal[open]", timeout=5000)
        sections = page.locator("#pst-secondary-sidebar-modal nav a.nav-link:visible")
        assert sections.count() >= 3, sections.all_text_contents()
        target = sections.nth(1).get_attribute("href")
        sections.nth(1).tap()
        page.wait_for_url(f"**/03_winding_number.html{target}")
        page.wait_for_selector("#pst-secondary-sidebar-modal:not([open])", state="attached", timeout=5000)  # closed
        assert not errors and not outside, (errors, outside)
    finally:
        context.close()


def test_both_sites_were_found():
    for site in SITES:
        found = pages(site)
        assert "book/05_inflation.html" in found and len(found) >= 12, (site, found)


@pytest.mark.parametrize("site", list(SITES))
def test_every_page_and_the_site_fit_their_budgets(site):
    """Each page (its HTML and the images it shows) at most 1 MB; the site at most 10 MB without its
    PDFs (their tags, with which the bookmarks find their pages, made them grow) and these 20 MB."""
    import re

    folder, heavy = SITES[site], {}
    for path in pages(site):
        html = (folder / path).read_text(encoding="utf-8")
        # ids drawn anew at every run would make each build new bytes (and every offline reader fetch it again)
        assert "widget-state+json" not in html, path
        images = {m for m in re.findall(r'<img[^>]+src="([^"]+)"', html) if not m.startswith(("data:", "http"))}
        size = (folder / path).stat().st_size + sum((folder / path).parent.joinpath(s).stat().st_size for s in images)
        if size > 2**20:
            heavy[path] = size
    assert not heavy, f"pages over 1 MB: {heavy}"
    files = [p for p in pathlib.Path(folder).rglob("*") if p.is_file()]
    pdfs = sum(p.stat().st_size for p in files if p.relative_to(folder).parts[0] == "pdf")
    total = sum(p.stat().st_size for p in files) - pdfs  # what the service worker may keep, and the downloads
    assert total < 10 * 2**20, f"the {site} site is {total / 2**20:.1f} MB without its PDFs"
    assert pdfs < 20 * 2**20, f"the {site} site's PDFs are {pdfs / 2**20:.1f} MB"
