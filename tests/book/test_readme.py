"""The README and the two guides it leads to (INSTRUCTORS.md, CONTRIBUTING.md): short, navigable, true.

Parsed with markdown-it, the parser the book uses. The README opens with the two commands and stays
short; each file's table of contents links every one of its sections, in order; every link between
the three reaches a file and a heading that exist (GitHub's anchors); and what they tell a reader to
type exists: every `make` target and variable is the Makefile's, every option of a
`python -m instructor.X` command is in that command's `--help`, every option of a `tools/X.py`
command is in that tool.
"""

import functools
import pathlib
import re
import shlex
import subprocess
import sys

import pytest
from markdown_it import MarkdownIt

ROOT = pathlib.Path(__file__).resolve().parents[2]
GUIDES = ("README.md", "INSTRUCTORS.md", "CONTRIBUTING.md")
MAX_README_LINES = 160


def text(name):
    return (ROOT / name).read_text()


@functools.cache
def tokens(name):
    return MarkdownIt("commonmark").enable("table").parse(text(name))


def inline_text(inline):
    """A heading's or link's words as GitHub reads them: text and code, without the markup."""
    return "".join(child.content for child in inline.children if child.type in ("text", "code_inline"))


def slug(title):
    """GitHub's anchor for a heading: lower case, punctuation dropped but `-` and `_`, spaces to `-`."""
    return re.sub(r"[^\w\- ]", "", title.strip().lower()).replace(" ", "-")


def headings(name):
    """``[(level, title)]`` of the file's headings, in order."""
    found, stream = [], tokens(name)
    for i, token in enumerate(stream):
        if token.type == "heading_open":
            found.append((int(token.tag[1]), inline_text(stream[i + 1])))
    return found


def anchors(name):
    """Every anchor GitHub gives the file's headings (a repeated title gets -1, -2, ...)."""
    seen, result = {}, set()
    for _, title in headings(name):
        base = slug(title)
        result.add(base if base not in seen else f"{base}-{seen[base]}")
        seen[base] = seen.get(base, 0) + 1
    return result


def links(stream):
    """Every link target in ``stream``."""
    return [child.attrGet("href") for token in stream if token.type == "inline"
            for child in token.children or () if child.type == "link_open"]


def code(name):
    """Every piece of code the file shows: each line of each fence (a line ending in a backslash joined
    with the next, as the shell joins them), and each inline code span."""
    pieces = []
    for token in tokens(name):
        if token.type == "fence":
            pieces += token.content.replace("\\\n", " ").splitlines()
        elif token.type == "inline":
            pieces += [child.content for child in token.children if child.type == "code_inline"]
    return pieces


def words(line):
    line = re.sub(r"(^|\s)#.*", "", line)  # a shell comment
    try:
        return shlex.split(line)
    except ValueError:  # a quote opened in one code span and closed in another
        return line.split()


def make_commands(name):
    """``[(targets, variables)]`` of every `make ...` the file shows as code."""
    commands = []
    for line in code(name):
        parts = words(line)
        for start in (i for i, word in enumerate(parts) if word == "make"):
            targets, variables = [], []
            for word in parts[start + 1:]:
                if word.startswith("-"):
                    continue
                if re.fullmatch(r"[A-Z_][A-Z0-9_]*=.*", word, re.S):
                    variables.append(word.split("=")[0])
                elif re.fullmatch(r"[a-z][\w-]*", word):
                    targets.append(word)
                else:
                    break
            commands.append((targets, variables))
    return commands


@functools.cache
def makefile():
    """The Makefile's targets, and the variables its recipes read."""
    source = text("Makefile")
    targets = {target for line in re.findall(r"^([\w -]+?)\s*:(?!=)", source, re.M) for target in line.split()}
    variables = set(re.findall(r"\$\((\w+)\)", source)) | set(re.findall(r"^(\w+)\s*[?:]?=", source, re.M))
    return targets, variables


@functools.cache
def options_of(module):
    """The options `python -m instructor.MODULE --help` lists."""
    source = (ROOT / "instructor" / f"{module}.py").read_text()
    assert "add_argument" in source, f"instructor/{module}.py has no command-line options"
    shown = subprocess.run([sys.executable, "-m", f"instructor.{module}", "--help"], cwd=ROOT, capture_output=True,
                           text=True, timeout=120)
    assert shown.returncode == 0, shown.stderr
    return set(re.findall(r"(?<![\w-])--[a-z][\w-]*", shown.stdout))


def flags(line):
    return re.findall(r"(?<![\w-])--[a-z][\w-]*", line)


def test_readme_is_short():
    lines = len(text("README.md").splitlines())
    assert lines <= MAX_README_LINES, f"README.md has {lines} lines: move details to INSTRUCTORS.md or CONTRIBUTING.md"


def test_readme_opens_with_the_two_commands():
    first_fence = next(t for t in tokens("README.md") if t.type == "fence")
    assert first_fence.content.startswith("make book") and "\nmake test" in first_fence.content


def test_readme_leads_each_reader_to_their_guide():
    targets = {link.split("#")[0] for link in links(tokens("README.md"))}
    assert {"INSTRUCTORS.md", "CONTRIBUTING.md"} <= targets


def test_readme_lists_no_timings():
    """One current duration (how long `make test` takes) at most: benchmarks belong in CONTRIBUTING.md."""
    durations = re.findall(r"\d+(?:\.\d+)? ?(?:ms|s|min|minutes?|h|hours?)\b", text("README.md"))
    assert len(durations) <= 1, durations


@pytest.mark.parametrize("name", GUIDES)
def test_every_code_block_closes_and_no_heading_or_table_is_swallowed(name):
    source = text(name)
    stream = tokens(name)
    raw = [line for line in source.splitlines() if line.startswith("## ")]
    rendered = [t for t in stream if t.type == "heading_open" and t.tag == "h2"]
    assert len(rendered) == len(raw) >= 3  # a fence left open would swallow the rest
    fences = [t for t in stream if t.type == "fence"]
    for fence in fences:
        assert "\n## " not in fence.content and "\n| " not in fence.content, fence.content[:200]
        assert fence.map[1] <= len(source.splitlines())
    in_fence = {n for fence in fences for n in range(*fence.map)}
    in_table = {n for t in stream if t.type == "table_open" for n in range(*t.map)}
    table_lines = {n for n, line in enumerate(source.splitlines()) if line.startswith("|") and n not in in_fence}
    assert table_lines <= in_table, f"{name}: lines {sorted(table_lines - in_table)} look like a table but do not render"


@pytest.mark.parametrize("name", GUIDES)
def test_the_table_of_contents_links_every_section_in_order(name):
    stream = tokens(name)
    h2 = [title for level, title in headings(name) if level == 2]
    assert h2[0] == "Contents", f"{name}: its first section should be the table of contents"
    start = next(i for i, t in enumerate(stream) if t.type == "heading_open" and inline_text(stream[i + 1]) == "Contents")
    end = next(i for i, t in enumerate(stream[start + 3:], start + 3) if t.type == "heading_open" and t.tag == "h2")
    listed = [link[1:] for link in links(stream[start:end]) if link.startswith("#")]
    sections = [slug(title) for title in h2[1:]]
    assert [a for a in listed if a in sections] == sections, (name, listed, sections)
    assert set(listed) <= anchors(name), (name, set(listed) - anchors(name))


@pytest.mark.parametrize("name", GUIDES)
def test_every_link_reaches_a_file_and_a_heading(name):
    for link in links(tokens(name)):
        if re.match(r"^[a-z]+:", link):  # a web address
            continue
        path, _, anchor = link.partition("#")
        target = (ROOT / path).resolve() if path else ROOT / name
        assert target.exists(), f"{name}: the link {link} leads to no file"
        if anchor:
            assert target.suffix == ".md" and anchor in anchors(target.name), f"{name}: {link}: no such heading"


@pytest.mark.parametrize("name", GUIDES)
def test_every_make_command_is_the_makefiles(name):
    targets, variables = makefile()
    commands = make_commands(name)
    assert commands or name != "README.md"
    for named, given in commands:
        assert set(named) <= targets, f"{name}: make {' '.join(named)}: no target {set(named) - targets} in the Makefile"
        assert set(given) <= variables, f"{name}: make {' '.join(named)}: the Makefile reads no {set(given) - variables}"


@pytest.mark.parametrize("name", GUIDES)
def test_every_option_shown_is_the_commands(name):
    shown = 0
    for line in code(name):
        for module, rest in re.findall(r"-m instructor\.(\w+)(.*)", line):
            unknown = set(flags(rest)) - options_of(module)
            assert not unknown, f"{name}: python -m instructor.{module} has no {unknown}: {line}"
            shown += 1
        for tool, rest in re.findall(r"tools/(\w+)\.py(.*)", line):
            source = (ROOT / "tools" / f"{tool}.py").read_text()
            assert all(flag in source for flag in flags(rest)), f"{name}: tools/{tool}.py: {line}"
        if line.startswith("--"):  # an option named alone: the grader's or the edition's; in CONTRIBUTING.md a tool's too
            option = flags(line)[0]
            known = options_of("grade") | options_of("edition")
            if name == "CONTRIBUTING.md":
                known |= {flag for tool in (ROOT / "tools").glob("*.py") for flag in flags(tool.read_text())}
            assert option in known, f"{name}: no command has {option}"
            shown += 1
    assert shown or name == "README.md"
