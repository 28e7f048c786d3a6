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


def contrast(a, b):
    """WCAG's contrast ratio of two colours given as #rrggbb."""
    def luminance(colour):
        channels = [int(colour.lstrip("#")[i:i + 2], 16) / 255 for i in (0, 2, 4)]
        r, g, b = (c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4 for c in channels)
        return 0.2126 * r + 0.7152 * g + 0.0722 * b
    high, low = sorted((luminance(a), luminance(b)), reverse=True)
    return (high + 0.05) / (low + 0.05)


def test_highlighted_code_reads_at_wcag_aa_in_the_light_and_the_dark_theme():
    """Every token colour of the code highlighting the book's pages use (the theme's light and dark
    Pygments styles) is at least 4.5:1 on the code's background."""
    import configparser

    from pygments.styles import get_style_by_name

    theme = configparser.ConfigParser()
    theme.read(sphinx_assets.THEME.parent / "theme.conf")
    names = [theme["options"][f"pygments_{mode}_style"] for mode in ("light", "dark")]
    assert names == ["a11y-high-contrast-light", "a11y-high-contrast-dark"]
    for name in names:
        style = get_style_by_name(name)
        background = style.background_color
        colours = {token: spec["color"] for token, spec in style if spec["color"]}
        assert len(colours) > 20, name
        low = {str(token): f"#{colour} {contrast(background, '#' + colour):.2f}" for token, colour in colours.items()
               if contrast(background, "#" + colour) < 4.5}
        assert not low, (name, low)
    assert contrast("#a78155", "#f7f7f8") < 4.5  # what axe measured in a block still fading in: it can fail
