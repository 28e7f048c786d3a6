"""Sphinx extension: each page loads only what it uses, and nothing it does not need for its
first paint holds that paint up.

The theme and the extensions put each of their files on every page. Here:

- A file of an extension loads only on the pages with what it serves (USES): the explorers'
  player where there is an explorer, the lab's two scripts where there is the lab, the toggle
  buttons where something folds, the copy buttons where there is code, sphinx-design's and
  thebe's nowhere (no tabs or cards, no live code). Scripts that wait for the page to be parsed
  anyway are deferred (DEFER).
- The theme's icons (about twenty, of Font Awesome) are written into the pages as inline SVG,
  taken from the theme's own copy of Font Awesome. Its script (1.5 MB, which drew them in the
  reader's browser) and the icon rules of the theme's stylesheet (a third of it) go; its fonts,
  which the stylesheet still uses for the icons of admonitions, are cut down to those (FONT_FILES).
- The search index and its scripts load only on the search page: the theme's search box, without
  search-as-you-type (the default), only opens that page.
- Images load when the reader comes near them (loading="lazy"), in a box of their size; so do the
  explorers' states, moved into files of their own.
- The theme's head loads less before the first paint (HEAD): Sphinx's 300-byte options script is
  written into the page, basic.css is linked, not @imported by a stylesheet, and the theme's two
  scripts are not preloaded (they load, deferred, at the end of the page).

The last four change what the theme's templates write, so they are done to the written pages
when the build finishes (idempotent: a page that Sphinx did not write again is already done).
"""

import itertools
import pathlib
import re
import shutil

import pydata_sphinx_theme
from fontTools import subset
from sphinx.util import logging

logger = logging.getLogger(__name__)

# What a page's body must contain for a file to load there; None: no page.
FOLDS, CODE = re.compile(r'class="[^"]*\b(toggle|dropdown)\b'), re.compile(r'<div class="highlight')
LAB = re.compile(r'class="ddg-lab"')  # the lab of chapter 10: ddg's formulas in JavaScript, and the page's lab
USES = {"ddg-player.js": re.compile(r'class="ddg-explorer"'), "ddg-lab.js": LAB, "ddg-lab-page.js": LAB,
        "ddg-lab-circle.js": LAB,
        "polygon-clipping.umd.min.js": LAB,
        "togglebutton.js": FOLDS, "togglebutton.css": FOLDS,
        "clipboard.min.js": CODE, "copybutton.js": CODE, "copybutton.css": CODE, "design-tabs.js": None,
        "sphinx-design.min.css": None, "sphinx-thebe.js": None, "sphinx-thebe.css": None}
THEBE_SETTINGS = "THEBE_JS_URL"  # thebe's inline settings go with its script
DEFER = {"doctools.js", "sphinx_highlight.js", "clipboard.min.js", "copybutton.js", "sphinx-book-theme.js",
         "togglebutton.js"}
OURS = re.compile(r"^(ddg-.*|polygon-clipping\.umd\.min)\.js$")  # the book's own scripts (_config.yml): always deferred

THEME = pathlib.Path(pydata_sphinx_theme.__file__).parent / "theme" / "pydata_sphinx_theme" / "static"
FONT_AWESOME = THEME / "scripts" / "fontawesome.js"
# <i class="fa-solid fa-sun fa-lg" data-mode="light"></i>, <span class="fa fa-rocket"></span>
ICON = re.compile(r'<(i|span) class="([^"]*\bfa[srb]?\b[^"]*|[^"]*\bfa-(?:solid|regular|brands)\b[^"]*)"([^>]*)>\s*</\1>')
PACKS = {"fa": "fas", "fas": "fas", "fa-solid": "fas", "far": "far", "fa-regular": "far", "fab": "fab",
         "fa-brands": "fab"}
SIZES = {"fa-lg", "fa-xs", "fa-sm", "fa-1x", "fa-2x", "fa-3x", "fa-fw"}
ICON_RULES = re.compile(r'(?:\.fa-[a-z0-9-]+:(?:before|after),?)+\{content:"[^"]*"\}')
# The stylesheet still draws a few icons with Font Awesome's fonts (admonitions' titles, external
# links): each font is cut down to those characters, as a 1-2 kB woff in place of 25-160 kB woff2.
SELECTORS = re.compile(r",(?![^(]*\))")  # the commas between selectors, not those inside :is(...)
PSEUDO = re.compile(r":(?:not|is|where|has)\([^)]*\)")  # what these name may be absent from a page
CLASS = re.compile(r"\.([A-Za-z_][\w-]*)")
DYNAMIC = {"bs-tooltip-auto", "bs-popover-auto"}  # classes Bootstrap's script builds from pieces
FONT_FILES = re.compile(r'url\(([^)]*/webfonts/)(fa-[a-z]+-\d+)\.woff2\) format\("woff2"\),url\([^)]*\.ttf\) format\("truetype"\)')
SEARCH_ONLY = re.compile(r'\s*<script src="[^"]*(searchtools\.js|language_data\.js|searchindex\.js)[^"]*"></script>')
HEAD = [(re.compile(r'\s*<script defer src="[^"]*/fontawesome\.js[^"]*"></script>'), ""),
        # the notebook's widget state, which no script of the book reads (its explorers are drawn by
        # ddg-player.js from their own data) and whose ids are new at every run: without it, a build
        # of the same book is the same bytes, and the service worker's version stays
        (re.compile(r'\s*<script type="application/vnd\.jupyter\.widget-state\+json">.*?</script>', re.S), ""),
        (re.compile(r'\s*<link rel="preload" as="script" href="[^"]*"\s*/>'), ""),
        (re.compile(r'<link href="([^"]*)styles/theme\.css\?[^"]*" rel="stylesheet" />'),
         r'<link href="\1basic.css" rel="stylesheet" />')]
OPTIONS = re.compile(r'<script src="[^"]*documentation_options\.js[^"]*"></script>')
STATES = re.compile(r'<script type="application/gzip\+base64" class="ddg-data">\s*([^<]+?)\s*</script>')
IMAGE = re.compile(r'<img (?![^>]*\bloading=)([^>]*?\bsrc="([^"]+)"[^>]*?)\s*(/?)>')


def only_what_the_page_uses(app, pagename, templatename, context, doctree):
    body = context.get("body", "")
    used = {name for name, pattern in USES.items() if pattern and pattern.search(body)}

    def name(asset):
        return pathlib.PurePosixPath(str(asset.filename)).name

    def keep(asset):
        return THEBE_SETTINGS not in asset.attributes.get("body", "") and (name(asset) not in USES or name(asset) in used)

    def deferred(js):  # not on the search page, whose search scripts run at once and need doctools.js
        later = name(js) in DEFER and pagename != "search" or OURS.match(name(js))
        return type(js)(js.filename, priority=js.priority, **js.attributes, defer="defer") if later else js

    context["script_files"][:] = [deferred(js) for js in context.get("script_files", []) if keep(js)]
    # the theme's mode before a reader picks one: "auto" (the theme's empty default logs "Got invalid
    # theme mode" on every first visit)
    context["default_mode"] = context.get("default_mode") or "auto"
    context["css_files"][:] = [css for css in context.get("css_files", []) if keep(css)]


def icon(classes):
    """(pack, name) of an icon's classes: ("fas", "sun") for "fa-solid fa-sun fa-lg"."""
    pack = next((PACKS[c] for c in classes if c in PACKS), "fas")
    return pack, next((c[3:] for c in classes if c.startswith("fa-") and c not in PACKS and c not in SIZES), "")


def icon_paths(icons):
    """{(pack, name): (width, height, path)} of the icons, from the theme's Font Awesome."""
    source = FONT_AWESOME.read_text()
    found = {}
    for pack, name in icons:
        end = source.index(f'd("{pack}",p)')  # each pack is `var p={name:[w,h,[aliases],"f185","path"],...}`
        text = source[source.rindex("var p={", 0, end):end]
        match = re.search(rf'[{{,]"?{re.escape(name)}"?:\[(\d+),(\d+),\[[^\]]*\],"[^"]*","([^"]+)"\]', text)
        if match:
            found[pack, name] = match.groups()
    return found


def lazy(match, folder):
    """An image loads when the reader comes near it; a figure (a PNG in _images) in a box of its size."""
    attributes, source, slash = match.groups()
    png = folder / source
    if "_images/" in source and png.suffix == ".png" and png.is_file():
        width, height = int.from_bytes(png.read_bytes()[16:20], "big"), int.from_bytes(png.read_bytes()[20:24], "big")
        attributes += f' width="{width}" height="{height}"'
    return f'<img {attributes} loading="lazy"{" /" if slash else ""}>'


def states_apart(html, page, static):
    """An explorer's states (base64 of gzip, 60 to 100 kB) move out of the page into a script file of
    their own, _static/ddg-states/<page>-<n>.js, which the player loads when the explorer comes near
    the screen (book/_assets/ddg-player.js)."""
    names = (f"{page.with_suffix('').as_posix().replace('/', '__')}-{n}.js" for n in itertools.count())
    up = "../" * (len(page.parts) - 1)

    def move(match):
        name = next(names)
        (static / "ddg-states").mkdir(exist_ok=True)
        (static / "ddg-states" / name).write_text(
            f'(window.ddgStates = window.ddgStates || {{}})["{name}"] = "{match.group(1)}";\n')
        return f'<script type="application/gzip+base64" class="ddg-data" data-src="{up}_static/ddg-states/{name}"></script>'

    return STATES.sub(move, html)


def finish_pages(app, exception):
    if exception or app.builder.format != "html":
        return
    out = pathlib.Path(app.outdir)
    static = out / "_static"
    pages = {path: path.read_text() for path in out.rglob("*.html") if "_static" not in path.parts}
    icons = {icon(match.group(2).split()) for html in pages.values() for match in ICON.finditer(html)}
    paths = icon_paths(icons)
    for pack, name in sorted(icons - paths.keys()):
        logger.warning("the theme's Font Awesome has no icon %r (%s): it shows as nothing", name, pack)

    def draw(match):  # the SVG that Font Awesome's script put in place of an <i> or <span>
        classes = match.group(2).split()
        pack, name = icon(classes)
        if (pack, name) not in paths:
            return ""
        width, height, path = paths[pack, name]
        kept = "".join(f" {c}" for c in classes if c not in PACKS and c != f"fa-{name}")
        return (f'<svg class="svg-inline--fa fa-{name}{kept}" aria-hidden="true" focusable="false" role="img" '
                f'viewBox="0 0 {width} {height}"{match.group(3).rstrip()}><path fill="currentColor" d="{path}"/></svg>')

    options = f"<script>{(static / 'documentation_options.js').read_text().strip()}</script>"
    for path, html in pages.items():
        new = IMAGE.sub(lambda match, folder=path.parent: lazy(match, folder), ICON.sub(draw, html))
        new = states_apart(new, path.relative_to(out), static)
        for pattern, replacement in HEAD:
            new = pattern.sub(replacement, new)
        new = OPTIONS.sub(lambda _: options, new)
        if path.relative_to(out) != pathlib.Path("search.html"):
            new = SEARCH_ONLY.sub("", new)
        if new != html:
            path.write_text(new)
    stylesheet = static / "styles" / "pydata-sphinx-theme.css"
    used = {c for html in pages.values() for attribute in re.findall(r'class="([^"]*)"', html) for c in attribute.split()}
    used |= DYNAMIC | {word for script in static.rglob("*.js") if "ddg-states" not in script.parts
                       for word in re.findall(r"[A-Za-z_][\w-]*", script.read_text())}
    css = re.sub(r"/\*.*?\*/", "", (THEME / "styles" / "pydata-sphinx-theme.css").read_text(), flags=re.S)
    css = FONT_FILES.sub(r'url(\1\2.woff) format("woff")', rules_in_use(ICON_RULES.sub("", css), used))
    stylesheet.write_text(css)
    fonts = static / "vendor" / "fontawesome" / "webfonts"
    shutil.rmtree(fonts, ignore_errors=True)
    fonts.mkdir(parents=True)
    icons_in_css = {ord(c) for c in css if 0xE000 <= ord(c) <= 0xF8FF}  # Font Awesome's code points
    for font in (THEME / "vendor" / "fontawesome" / "webfonts").glob("*.ttf"):
        cut_down(font, icons_in_css, fonts / f"{font.stem}.woff")
    for unused in ("scripts/fontawesome.js", "scripts/fontawesome.js.map"):
        (static / unused).unlink(missing_ok=True)


def rules_in_use(css, used):
    """The stylesheet without the rules whose every selector names a class in no page and no script
    (the theme's stylesheet is all of Bootstrap: cards, carousels, grids the book never uses)."""
    kept, at = [], 0
    while (brace := css.find("{", at)) >= 0:
        depth, end = 1, brace + 1
        while depth:
            depth += {"{": 1, "}": -1}.get(css[end], 0)
            end += 1
        head, body = css[at:brace].strip(), css[brace + 1:end - 1]
        if head.startswith(("@media", "@supports", "@container", "@layer")):
            inner = rules_in_use(body, used)
            kept += [f"{head}{{{inner}}}"] if inner else []
        elif head.startswith("@"):
            kept.append(f"{head}{{{body}}}")
        else:
            selectors = [s for s in SELECTORS.split(head) if set(CLASS.findall(PSEUDO.sub("", s))) <= used]
            kept += [f"{','.join(selectors)}{{{body}}}"] if selectors else []
        at = end
    return "".join(kept)


def cut_down(font, characters, out):
    """The font with only these of its characters, as a woff."""
    options = subset.Options(flavor="woff")
    loaded = subset.load_font(str(font), options)
    subsetter = subset.Subsetter(options)
    subsetter.populate(unicodes=characters & set(loaded.getBestCmap()))
    subsetter.subset(loaded)
    subset.save_font(loaded, str(out), options)


def setup(app):
    app.connect("html-page-context", only_what_the_page_uses, priority=900)
    app.connect("build-finished", finish_pages)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
