"""What tools/sphinx_assets.py does to the theme's files when the book is built: the stylesheet
keeps every rule a page or a script can use, the icons come from the theme's own Font Awesome."""

import io

from fontTools.ttLib import TTFont

from tools import sphinx_assets


def test_a_rule_goes_only_when_every_selector_names_a_class_nothing_has():
    css = (".card{a:1}.btn,.card-body{b:2}@media (min-width:9px){.card{c:3}.btn{d:4}}"
           "a:not(.nowhere){e:5}:is(.card,.btn) p{f:6}@font-face{font-family:X}.show.fade{g:7}")
    kept = sphinx_assets.rules_in_use(css, {"btn", "show", "fade"})
    assert kept == (".btn{b:2}@media (min-width:9px){.btn{d:4}}a:not(.nowhere){e:5}:is(.card,.btn) p{f:6}"
                    "@font-face{font-family:X}.show.fade{g:7}")


def test_the_icons_the_theme_uses_are_found_in_its_font_awesome():
    paths = sphinx_assets.icon_paths({("fas", "magnifying-glass"), ("fab", "github"), ("fas", "no-such-icon")})
    assert set(paths) == {("fas", "magnifying-glass"), ("fab", "github")}
    width, height, path = paths["fab", "github"]
    assert (width, height) == ("496", "512") and path.startswith("M")
    assert sphinx_assets.icon("theme-switch fa-solid fa-sun fa-lg".split()) == ("fas", "sun")
    assert sphinx_assets.icon("fa fa-rocket".split()) == ("fas", "rocket")


def test_a_font_is_cut_down_to_the_characters_asked_for(tmp_path):
    font = sphinx_assets.THEME / "vendor" / "fontawesome" / "webfonts" / "fa-solid-900.ttf"
    sphinx_assets.cut_down(font, {0xF05A, 0xF0F3, 0x10FFFF}, tmp_path / "cut.woff")
    cut = TTFont(io.BytesIO((tmp_path / "cut.woff").read_bytes()))
    assert cut.flavor == "woff" and set(cut.getBestCmap()) == {0xF05A, 0xF0F3}
    assert (tmp_path / "cut.woff").stat().st_size < 5000 < font.stat().st_size
