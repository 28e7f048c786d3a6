"""Keep the chapter notebooks consistent: `python tools/notebooks.py [--fix] [NOTEBOOK ...]`.

Also `python tools/notebooks.py --add CELLS NOTEBOOK`: append the cells written in CELLS to the
notebook, then fix its folding. CELLS is plain text in the "percent" format: a line
``# %% [markdown]`` starts a markdown cell (the lines after it are its Markdown, as written), a
line ``# %%`` starts a code cell, and ``# %% tags=["solution"]`` gives the cell its tags
(CONTRIBUTING.md uses it to add an exercise). A coding exercise among the cells (an
``{exercise}`` with a label, and a cell tagged ``check`` calling ``check_NAME(...)``) is entered
in the notebook's metadata ``ddg.exercises``, worth 1 point, which is what the grader reads.

Two checks. First, prose that cannot break: in a markdown cell, a line that a Markdown parser
reads as a heading, a list item, a quote or a rule right after a line of running text is
almost always a wrapped sentence (`+ `, `# ` or `1. ` at the start of a line) that became markup,
and inside inline math it leaves raw TeX on the page. Such lines are reported (with ``--fix``
too: re-wrap them by hand). Second, folding:

What the book shows and what JupyterLab shows come from the same notebook. The book folds or
hides cells by their tags and by the gated ``{solution-start}`` ... ``{solution-end}`` blocks;
JupyterLab reads the ``jupyter.source_hidden`` and ``jupyter.outputs_hidden`` cell metadata instead.
This tool derives the second from the first, so a notebook opened in JupyterLab looks like its
page: a solution's cells are folded (the solution's first cell is a collapsed dropdown there),
cells tagged ``remove-cell`` (hidden asserts, the set-up cell) and ``hide-input`` show a folded
input. Without ``--fix`` it only reports the cells that disagree, and exits 1 if there are any.
"""

import json
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
BLOCKS = {"heading_open": "a heading", "bullet_list_open": "a list", "ordered_list_open": "a list",
          "blockquote_open": "a quote", "hr": "a rule"}


MAX_SHOWN = 30  # lines of code a reader sees without unfolding anything


def _markdown():
    """A parser that reads markdown as the book's MyST does (math, directives, targets, roles)."""
    from markdown_it import MarkdownIt
    from mdit_py_plugins.amsmath import amsmath_plugin
    from mdit_py_plugins.colon_fence import colon_fence_plugin
    from mdit_py_plugins.dollarmath import dollarmath_plugin
    from mdit_py_plugins.myst_blocks import myst_block_plugin
    from mdit_py_plugins.myst_role import myst_role_plugin

    md = MarkdownIt("commonmark").enable("table")
    for plugin in (amsmath_plugin, colon_fence_plugin, myst_block_plugin, myst_role_plugin):
        md.use(plugin)
    return md.use(dollarmath_plugin, allow_labels=True, allow_space=True, allow_digits=True)


def prose_problems(text, md=None):
    """Lines of ``text`` that start a heading, list, quote or rule right after running text."""
    md = md or _markdown()
    lines, problems = text.split("\n"), []
    for token in md.parse(text):
        if token.type == "fence" and token.info.startswith("{"):  # a directive: its body is prose too
            body = token.content.split("\n")
            while body and re.match(r"^:\w[\w-]*:", body[0]):
                body.pop(0)
            problems += prose_problems("\n".join(body), md)
        if token.type not in BLOCKS or not token.map:
            continue
        first = token.map[0]
        if token.type == "heading_open" and token.markup in ("=", "-"):  # setext: underlines running text
            problems.append(f"{lines[first][:60]!r} becomes a heading (its next line underlines it)")
            continue
        before = lines[first - 1].strip() if first > 0 else ""
        if before and not re.match(r"^([-+*]|\d+[.)])\s|^>|^#|^```|^:::|^\$\$|^\(\S+\)=$|^\|", before):
            problems.append(f"{lines[first].strip()[:60]!r} becomes {BLOCKS[token.type]} in the middle of a paragraph")
    return problems


def solution_cells(cells):
    """Indices of the cells inside gated solution blocks: (first cell, the cells after it)."""
    first, rest, inside = set(), set(), False
    for i, cell in enumerate(cells):
        source = "".join(cell["source"])
        if cell["cell_type"] == "markdown" and "{solution-start}" in source:
            first.add(i)
            inside = "{solution-end}" not in source
        elif inside:
            rest.add(i)
            inside = not (cell["cell_type"] == "markdown" and "{solution-end}" in source)
    return first, rest


def folding(cells):
    """The ``jupyter`` cell metadata each cell should have, as a list of dicts."""
    first, rest = solution_cells(cells)
    wanted = []
    for i, cell in enumerate(cells):
        tags = cell.get("metadata", {}).get("tags", [])
        if i in rest:
            fold = {"source_hidden": True}
            if cell["cell_type"] == "code":
                fold["outputs_hidden"] = True
        elif "remove-cell" in tags or "hide-input" in tags:
            fold = {"source_hidden": True}
        else:
            fold = {}
        wanted.append(fold)
    return wanted


def check(path, fix=False):
    """Problems with the notebook at ``path`` (a list of strings); with ``fix``, repair the folding."""
    data = json.loads(path.read_text())
    md = _markdown()
    problems = [f"{path.name} cell {i}: {problem}" for i, cell in enumerate(data["cells"]) if cell["cell_type"] == "markdown"
                for problem in prose_problems("".join(cell["source"]), md)]
    first, rest = solution_cells(data["cells"])
    for i, cell in enumerate(data["cells"]):
        lines = len("".join(cell["source"]).splitlines())
        hidden = {"remove-cell", "hide-input", "hide-cell"} & set(cell["metadata"].get("tags", []))
        if cell["cell_type"] == "code" and lines > MAX_SHOWN and not hidden and i not in rest:
            problems.append(f"{path.name} cell {i}: {lines} lines shown on the page (fold it or split it: at most {MAX_SHOWN})")
    prose = len(problems)
    for i, (cell, fold) in enumerate(zip(data["cells"], folding(data["cells"]), strict=True)):
        if cell["metadata"].get("jupyter", {}) != fold:
            problems.append(f"{path.name} cell {i}: JupyterLab folding should be {fold or 'none'}")
            if fix:
                cell["metadata"].pop("jupyter", None)
                if fold:
                    cell["metadata"]["jupyter"] = fold
    if fix and len(problems) > prose:
        path.write_text(json.dumps(data, indent=1, ensure_ascii=False, sort_keys=True) + "\n")
    return problems


CELL = re.compile(r"^# %%(?: \[(markdown)\])?(?: tags=(\[[^\]]*\]))?\s*$")


def add(cells_path, path):
    """Append the cells of the percent-format file ``cells_path`` to the notebook at ``path``."""
    data = json.loads(path.read_text())
    cells, ids = [], {cell.get("id") for cell in data["cells"]}
    for line in cells_path.read_text().splitlines(keepends=True):
        header = CELL.match(line.rstrip("\n"))
        if header:
            kind, tags = header.groups()
            cells.append({"cell_type": "markdown" if kind else "code", "metadata": {}, "source": []})
            if tags:
                cells[-1]["metadata"]["tags"] = json.loads(tags)
            if not kind:
                cells[-1].update(execution_count=None, outputs=[])
        elif cells:
            cells[-1]["source"].append(line)
        elif line.strip():
            raise SystemExit(f"{cells_path}: text before the first '# %%' line: {line.strip()[:60]!r}")
    for cell in cells:
        while cell["source"] and not cell["source"][-1].strip():
            cell["source"].pop()
        if cell["source"]:
            cell["source"][-1] = cell["source"][-1].rstrip("\n")
        cell["id"] = next(f"c{i:03d}" for i in range(len(ids) + len(cells) + 1) if f"c{i:03d}" not in ids)
        ids.add(cell["id"])
    data["cells"] += cells
    labels = [m for c in cells if c["cell_type"] == "markdown"
              for m in re.findall(r"```\{exercise\}[^`]*?:label: (\S+)", "".join(c["source"]))]
    checked = [m for c in cells if "check" in c["metadata"].get("tags", [])
               for m in re.findall(r"\bcheck_(\w+)\(", "".join(c["source"]))]
    if labels and checked:  # a coding exercise: the grader reads its answer, check and points here
        graded = data["metadata"].setdefault("ddg", {}).setdefault("exercises", {})
        graded[labels[0]] = {"answer": checked[0], "check": f"check_{checked[0]}", "points": 1}
    path.write_text(json.dumps(data, indent=1, ensure_ascii=False, sort_keys=True) + "\n")
    check(path, fix=True)
    print(f"{path.name}: {len(cells)} cells added")


def main(argv):
    if argv[:1] == ["--add"] and len(argv) == 3:
        add(pathlib.Path(argv[1]), pathlib.Path(argv[2]))
        return 0
    fix = "--fix" in argv
    paths = [pathlib.Path(a) for a in argv if not a.startswith("--")] or sorted((ROOT / "book").glob("*.ipynb"))
    problems = [p for path in paths for p in check(path, fix)]
    for problem in problems:
        print(("fixed: " if fix and "JupyterLab" in problem else "") + problem)
    left = [p for p in problems if not (fix and "JupyterLab" in p)]
    return 1 if left else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
