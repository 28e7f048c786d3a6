"""The formulas are typeset when the book is built (tools/sphinx_math.py), and a formula MathJax
cannot typeset fails the build, naming its page, its line and the formula."""

import re
import subprocess
import sys

from conftest import ROOT

from tools import sphinx_math

CONF = """extensions = ["myst_parser", "sphinx_math"]
myst_enable_extensions = ["amsmath", "dollarmath"]
html_math_renderer = "ddg_math"
"""


def sphinx_build(tmp_path, page):
    (tmp_path / "conf.py").write_text(CONF)
    (tmp_path / "index.md").write_text(page)
    command = [sys.executable, "-m", "sphinx", "-q", "-b", "html", str(tmp_path), str(tmp_path / "html")]
    env = {"PYTHONPATH": str(ROOT / "tools")}
    return subprocess.run(command, capture_output=True, text=True, env=env, timeout=120)


def test_the_macros_the_book_uses_are_typeset_with_their_mathml():
    formulas = [(r"\lVert e\rVert + \dfrac{1}{2} + \tfrac{1}{2} + \operatorname{sign} x + \mathbb{R}", False),
                (r"\begin{aligned} a &= \text{for every } \delta \\ b &= \varepsilon \end{aligned} \tag{2}", True)]
    html, css, errors = sphinx_math.typeset(formulas)
    assert not errors
    for formula in formulas:
        assert html[formula].startswith('<mjx-container class="MathJax" jax="CHTML"')
        assert '<mjx-assistive-mml unselectable="on"' in html[formula] and "</math>" in html[formula]
        assert "NaN" not in html[formula]
    assert 'display="true"' in html[formulas[1]] and "<mtext>(2)</mtext>" in html[formulas[1]]
    assert 'src: url("mathjax/fonts/MathJax_Main-Regular.woff")' in css


def test_a_display_formula_is_given_to_mathjax_as_sphinx_gives_it():
    class Block(dict):
        def __init__(self, text, nowrap=False):
            super().__init__(nowrap=nowrap)
            self.text = text

        def astext(self):
            return self.text

    assert sphinx_math.display_source(Block("x = 1")) == "x = 1"
    assert sphinx_math.display_source(Block(r"a \\ b")) == r"\begin{split}a \\ b\end{split}"
    assert sphinx_math.display_source(Block("a\n\nb")) == r"\begin{align}\begin{aligned}a\\b\end{aligned}\end{align}"
    assert sphinx_math.display_source(Block(r"\begin{align}a\end{align}", nowrap=True)) == r"\begin{align}a\end{align}"


def test_a_page_arrives_with_its_math_finished(tmp_path):
    result = sphinx_build(tmp_path, "# Page\n\nInline $\\kappa = 1/r$ and\n\n$$\\sum_i A_i k_i = 2\\pi$$ (total)\n")
    assert result.returncode == 0, result.stderr
    page = (tmp_path / "html" / "index.html").read_text()
    assert page.count("<mjx-container") == 2 and "\\(" not in page and "\\[" not in page
    assert 'href="_static/ddg-math.css' in page and not re.search(r"<script[^>]*mathjax", page, re.I)
    assert '<span class="eqno">(1)' in page  # Sphinx numbers the labelled equation
    assert (tmp_path / "html" / "_static" / "ddg-math.css").stat().st_size > 5000


def test_a_formula_mathjax_cannot_typeset_fails_the_build_and_names_it(tmp_path):
    result = sphinx_build(tmp_path, "# Page\n\nFine $x$.\n\nBroken $\\frac{1}{2$ and $\\kapa$.\n")
    assert result.returncode != 0
    assert "index.md:5: WARNING: MathJax cannot typeset $\\frac{1}{2$: Missing close brace" in result.stderr
    assert "index.md:5: WARNING: MathJax cannot typeset $\\kapa$: Undefined control sequence \\kapa" in result.stderr
    assert "2 formulas could not be typeset" in result.stderr
    assert not (tmp_path / "html" / "index.html").exists()
