"""The README renders as intended (markdown-it, the parser the book uses) and opens with the commands."""

import pathlib

from markdown_it import MarkdownIt

ROOT = pathlib.Path(__file__).resolve().parents[2]


def tokens():
    return MarkdownIt("commonmark").enable("table").parse((ROOT / "README.md").read_text())


def test_every_code_block_closes_and_no_heading_is_swallowed():
    text = (ROOT / "README.md").read_text()
    headings = [line for line in text.splitlines() if line.startswith("## ")]
    rendered = [t for t in tokens() if t.type == "heading_open" and t.tag == "h2"]
    assert len(rendered) == len(headings) >= 6  # a fence left open would swallow the rest
    for fence in (t for t in tokens() if t.type == "fence"):
        assert "\n## " not in fence.content and "\n| " not in fence.content, fence.content[:200]
        assert fence.map[1] <= len(text.splitlines())


def test_readme_opens_with_the_two_commands():
    first_fence = next(t for t in tokens() if t.type == "fence")
    assert first_fence.content.startswith("make book") and "\nmake test" in first_fence.content


def test_readme_tables_render():
    assert sum(t.type == "table_open" for t in tokens()) == 3
