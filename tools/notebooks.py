"""Keep the chapter notebooks consistent: `python tools/notebooks.py [--fix] [NOTEBOOK ...]`.

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
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]


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
    """Problems with the notebook at ``path`` (a list of strings); with ``fix``, repair them."""
    data = json.loads(path.read_text())
    problems = []
    for i, (cell, fold) in enumerate(zip(data["cells"], folding(data["cells"]))):
        if cell["metadata"].get("jupyter", {}) != fold:
            problems.append(f"{path.name} cell {i}: JupyterLab folding should be {fold or 'none'}")
            if fix:
                cell["metadata"].pop("jupyter", None)
                if fold:
                    cell["metadata"]["jupyter"] = fold
    if fix and problems:
        path.write_text(json.dumps(data, indent=1, ensure_ascii=False, sort_keys=True) + "\n")
    return problems


def main(argv):
    fix = "--fix" in argv
    paths = [pathlib.Path(a) for a in argv if not a.startswith("--")] or sorted((ROOT / "book").glob("*.ipynb"))
    problems = [p for path in paths for p in check(path, fix)]
    for problem in problems:
        print(("fixed: " if fix else "") + problem)
    return 1 if problems and not fix else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
