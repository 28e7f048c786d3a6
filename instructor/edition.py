"""The student edition: ``python -m instructor.edition`` (``make student``) writes ``_build/student/``.

The book's notebooks mark their homework like this:

* a solution is a gated block, from a markdown cell that opens ``{solution-start}`` to one that
  holds ``{solution-end}``; everything in it is the instructor's;
* inside it, a code cell tagged ``solution`` holds the reference answer, and a cell tagged
  ``check`` calls a ``ddg.checks`` function on it.

In the student edition each solution block is removed. Its ``solution`` cells become starter code
(the same function signatures and docstrings, bodies replaced by ``raise NotImplementedError``;
other statements become ``name = ...``), and its ``check`` cells stay, so students get immediate
feedback on their own code. The exercise texts are kept unchanged. A hidden cell tagged
``answer-key`` (one that asserts the book's claims with an exercise's answer) is removed too, one
tagged ``answer-stub`` (an answer a later chapter uses) becomes its starter, and the lab's script
for chapter 6's circle curvature (``ddg-lab-circle.js``), an answer, is left out.

No answer key leaves the instructor: the edition's ``ddg/checks/public.json`` (the input of the
students' checks, with what a right answer returns) is written afresh from the answer key
(``instructor/references.py``), and ``make student`` runs the leak guard (``instructor/guard.py``)
on the result before it calls the edition done.
"""

import argparse
import ast
import hashlib
import json
import pathlib
import re
import shutil
import sys

from tools import config as yaml_config
from tools.repo import pages_address

MANIFEST = ".edition.json"
"""In the edition's notebook folder: the SHA-256 of each notebook as written, to tell a student's
changes from the edition's own files (changed notebooks are never overwritten or deleted)."""

STARTER_NOTE = "# Exercise: write your answer here, then run the check below."

ANSWER_SCRIPTS = ("ddg-lab-circle.js",)
"""The book's scripts that compute an exercise's answer: left out of the student edition and its site."""

# How a student gets feedback, with launch buttons (an edition for a student repository) or without:
# said in the intro (HOMEWORK) and under every chapter's Exercises heading (FEEDBACK). Plain words,
# no {fa} role: the notebooks show them in JupyterLab too.
HOW = {True: "open the chapter on Binder or Colab (the rocket button at the top of its page) or in JupyterLab",
       False: "download the chapter's notebook (the download button at the top of its page) and open it in "
              "JupyterLab or Colab"}
HOMEWORK = ("This edition has no solutions: each coding exercise has starter code and a check that tells you at once "
            "whether your answer is right and, if not, what is wrong. To get that feedback, {how}, replace the "
            "starter's `raise NotImplementedError` with your code, and run the check cell below your answer. On "
            "this page the checks show what they say to the starter code: ☐ to do.")
FEEDBACK = """:::{{admonition}} Feedback on your answers
:class: tip

Each coding exercise below has starter code and, under it, a check cell. To get feedback, {how},
write your answer in place of `raise NotImplementedError` and run the check cell: it says at once
whether the answer is right and, if not, what is wrong. Here, on the page, the checks show "to do".
:::"""
NO_LAUNCH = "The {fa}`download` button at the top of a chapter downloads its `.ipynb`."
RUN_LOCALLY = "`pip install -r requirements.txt`, then `jupyter lab book/`."  # a student repository has no Makefile


def starter(source):
    """Starter code for a solution cell: signatures, decorators and docstrings kept, bodies removed.

    Functions (``async`` ones too) keep their signature and docstring and raise
    ``NotImplementedError``; a class keeps its bases and docstring, with each method stubbed the
    same way; an assignment becomes ``name = ...``; imports stay. A cell that is not plain Python
    (an IPython magic such as ``%matplotlib``, a shell line) raises ``ValueError`` saying so.
    """
    magic = re.search(r"^\s*([%!].*)$", source, re.MULTILINE)
    if magic:
        raise ValueError(f"a solution cell must be plain Python, but it has the line {magic.group(1)!r}: move "
                         "magics and shell commands to a cell of their own")
    try:
        tree = ast.parse(source)
    except SyntaxError as error:
        raise ValueError(f"a solution cell is not valid Python: {error.msg} on line {error.lineno}") from None
    parts = [STARTER_NOTE]
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            parts.append(ast.unparse(_stub(node)))
        elif isinstance(node, (ast.Assign, ast.AnnAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            parts.append(" = ".join(ast.unparse(t) for t in targets) + " = ...  # your answer")
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            parts.append(ast.unparse(node))
    code = "\n\n".join(parts) + "\n"
    compile(code, "<starter>", "exec")  # ast.unparse writes valid Python, docstrings quoted as needed
    return code


def _stub(node):
    """``node`` with its body replaced: the docstring, then ``raise NotImplementedError`` (methods stubbed)."""
    doc = ast.get_docstring(node, clean=False)
    body = [ast.Expr(ast.Constant(doc))] if doc is not None else []
    if isinstance(node, ast.ClassDef):
        body += [_stub(item) for item in node.body if isinstance(item, (ast.FunctionDef, ast.AsyncFunctionDef))]
        body = body or [ast.Pass()]
    else:
        body.append(ast.Raise(ast.Call(ast.Name("NotImplementedError", ast.Load()), [ast.Constant("write this function")],
                                       [])))
    stub = type(node)(**{**{field: getattr(node, field) for field in node._fields}, "body": body})
    return ast.fix_missing_locations(ast.copy_location(stub, node))


def _opens(cell):
    return cell.cell_type == "markdown" and re.search(r"\{solution-start\}", cell.source)


def _closes(cell):
    return cell.cell_type == "markdown" and re.search(r"\{solution-end\}", cell.source)


def _nbformat():
    try:
        import nbformat
    except ImportError as error:  # not a part of ddg, so no extra of its distribution: the book's environment
        raise ImportError(f"{error.name or 'nbformat'} is not installed; the student edition is made in the book's "
                          "environment: `make student`, or .venv/bin/python (make sets it up from requirements.txt)",
                          name=error.name) from error
    return nbformat


def student_notebook(nb):
    """A copy of ``nb`` with every solution block replaced by starter and check cells."""
    nb = _nbformat().from_dict(nb)
    cells, inside = [], False
    for cell in nb.cells:
        tags = cell.get("metadata", {}).get("tags", [])
        if _opens(cell):
            if inside:
                raise ValueError("a {solution-start} block opens inside another one")
            inside = not _closes(cell)  # a short solution may open and close in one cell
            continue
        if _closes(cell):
            if not inside:
                raise ValueError("a {solution-end} without its {solution-start}")
            inside = False
            continue
        if "answer-key" in tags:
            continue
        if "answer-stub" in tags:
            cell.source = starter(cell.source)
        if not inside:
            cells.append(cell)
        elif "solution" in tags:
            try:
                cell.source = starter(cell.source)
            except ValueError as problem:
                raise ValueError(f"code cell {len(cells)} of the student edition: {problem}") from None
            cell.metadata["tags"] = [t for t in tags if t != "solution"] + ["starter"]
            cell.metadata.pop("jupyter", None)  # folded with the solution in the book: open for students
            cells.append(cell)
        elif "check" in tags:
            cell.metadata.pop("jupyter", None)
            cells.append(cell)
    if inside:
        raise ValueError("a {solution-start} block is never closed")
    for i, cell in enumerate(cells):
        if cell.cell_type == "code":
            cell.outputs, cell.execution_count = [], None
        cell["id"] = f"s{i:03d}"
    nb.cells = cells
    return nb


def _sha256(path):
    return hashlib.sha256(path.read_bytes()).hexdigest()


def changed_notebooks(folder):
    """Notebooks in ``folder`` that someone changed or added since the edition wrote them."""
    folder = pathlib.Path(folder)
    if not folder.is_dir():
        return []
    manifest = folder / MANIFEST
    written = json.loads(manifest.read_text()) if manifest.exists() else {}
    return sorted(p.name for p in folder.glob("*.ipynb") if written.get(p.name) != _sha256(p))


def _refuse_if_changed(folder, force, doing):
    changed = changed_notebooks(folder)
    if changed and not force:
        sys.exit(f"error: not {doing} {folder}: these notebooks were changed there, perhaps with a "
                 f"student's answers: {', '.join(changed)}. Copy them elsewhere, or pass --force "
                 "(make ... FORCE=1) to discard them.")


STUDENT_README = """# {title}

The chapter notebooks of the course, for you to work in: each coding exercise has starter code
and, below it, a check (`ddg.checks`) that says at once whether your answer is right and, if not,
what is wrong.{site}

- **Online:** open a chapter on Binder or Colab with the rocket button at the top of its page on
  the site, or open `book/<chapter>.ipynb` here in Colab. The notebook's first cell installs what
  it needs.
- **On your machine:** `pip install -r requirements.txt`, then `jupyter lab book/`.
- In a chapter, write your answer in place of `raise NotImplementedError`, then run the check
  cell below it. Until then it says "to do".

The checks run your answers on public input, whose right results come with `ddg`
(`ddg/checks/public.json`); your instructor grades them on other, hidden input drawn for you, so
an answer that only fits the public input will not pass.
"""


def _configure(text, student_repo):
    """The course's ``_config.yml`` (its text), made into the student edition's (edited as YAML with
    ruamel.yaml, so that its comments stay)."""
    config = yaml_config.load(text)
    config["title"] = f"Student edition: {config['title']}"
    # executed like the book's, from a cache that `make student` keeps only while ddg/ is unchanged
    config["execute"]["execute_notebooks"] = "cache"
    sphinx = config["sphinx"]["config"]
    sphinx["html_static_path"][0] = "_vendor"  # portable: the assets travel with the edition
    for name in ("html", "_vendor")[::-1]:
        config["exclude_patterns"].insert(0, name)
    scripts = sphinx["html_js_files"]
    for script in [s for s in scripts if s in ANSWER_SCRIPTS]:
        scripts.remove(script)
    substitutions = config["parse"]["myst_substitutions"]
    substitutions["homework"] = HOMEWORK.format(how=HOW[bool(student_repo)])
    substitutions["run_locally"] = RUN_LOCALLY
    if student_repo:
        yaml_config.set_repository(config, student_repo)
    else:  # no repository of student notebooks: no launch or repository button rather than a wrong one
        config["launch_buttons"]["binderhub_url"] = ""
        config["launch_buttons"]["colab_url"] = ""
        config["html"]["use_repository_button"] = False
        substitutions["launch"] = NO_LAUNCH
    return yaml_config.dump(config)


def _say_how_to_check(nb, nbformat, student_repo):
    """Under a chapter's "Exercises" heading, where it has checks: how to run them, and where."""
    if not any("check" in c.metadata.get("tags", []) for c in nb.cells):
        return
    heading = next((i for i, c in enumerate(nb.cells) if c.cell_type == "markdown"
                    and re.search(r"^## Exercises", c.source, re.MULTILINE)), None)
    if heading is None:
        return
    cell = nbformat.v4.new_markdown_cell(FEEDBACK.format(how=HOW[bool(student_repo)]))
    cell.id = f"{nb.cells[heading].id}-how"
    if nb.cells[heading].source.strip() == "## Exercises":
        nb.cells.insert(heading + 1, cell)
    else:  # the heading is part of a longer cell: the tip goes right under the heading's line
        nb.cells[heading].source = re.sub(r"^(## Exercises[^\n]*)\n*", lambda m: f"{m.group(1)}\n\n{cell.source}\n\n",
                                          nb.cells[heading].source, count=1, flags=re.MULTILINE)


def write_edition(root, out, force=False, vendor=None, student_repo=None):
    """Write the student edition of the book at ``root`` into ``out``: a Jupyter Book to build,
    and everything a repository of student notebooks needs (``ddg``, the pins, a README).

    Refuses (``SystemExit``) to overwrite notebooks changed since the edition wrote them, unless
    ``force``. ``vendor`` is the folder of offline front-end assets (copied into ``_vendor``);
    ``student_repo`` is the URL the launch buttons and the notebooks' set-up cells point at.
    """
    nbformat = _nbformat()
    root, out = pathlib.Path(root), pathlib.Path(out)
    _refuse_if_changed(out / "book", force, "overwriting")
    if out.exists():
        shutil.rmtree(out)
    (out / "book").mkdir(parents=True)
    written = {}
    for path in sorted((root / "book").iterdir()):
        if path.suffix == ".ipynb":
            nb = student_notebook(nbformat.read(path, as_version=4))
            for cell in nb.cells:  # the set-up cell installs ddg from the student repository, never the course's
                cell.source = re.sub(r'^REPOSITORY = "[^"]*"', f'REPOSITORY = "{student_repo or ""}"', cell.source,
                                     flags=re.MULTILINE)
            _say_how_to_check(nb, nbformat, student_repo)
            target = out / "book" / path.name
            nbformat.write(nb, target)
            written[path.name] = _sha256(target)
        elif path.is_file():
            shutil.copy(path, out / "book" / path.name)
        elif path.name == "_assets":  # the book's own styles and scripts
            shutil.copytree(path, out / "book" / path.name, ignore=shutil.ignore_patterns(*ANSWER_SCRIPTS))
    (out / "book" / MANIFEST).write_text(json.dumps(written, indent=1) + "\n")
    shutil.copy(root / "_toc.yml", out / "_toc.yml")
    config = _configure((root / "_config.yml").read_text(), student_repo)
    (out / "_config.yml").write_text(config)
    shutil.copytree(pathlib.Path(vendor or root / ".venv" / "vendor"), out / "_vendor")
    shutil.copytree(root / "ddg", out / "ddg", ignore=shutil.ignore_patterns("__pycache__"))
    from . import references

    references.write_public(out / "ddg" / "checks" / "public.json")  # from the answer key, which stays here
    extensions = sorted(p.relative_to(root) for p in (root / "tools").glob("sphinx_*.py"))  # the book's Sphinx extensions
    for name in ("pyproject.toml", "requirements.txt", *extensions):
        (out / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(root / name, out / name)
    title = yaml_config.load(config)["title"]
    address = pages_address(student_repo)
    site = f"\n\nThe course notes, with every chapter: <{address}>." if address else ""
    (out / "README.md").write_text(STUDENT_README.format(title=title, site=site))
    (out / ".gitignore").write_text("html/\n_build/\n__pycache__/\n")
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--root", default=".", help="the repository (with book/, _config.yml, _toc.yml)")
    parser.add_argument("--out", default="_build/student", help="where to write the edition")
    parser.add_argument("--force", action="store_true", help="overwrite or delete changed notebooks")
    parser.add_argument("--vendor", help="the offline front-end assets (default: ROOT/.venv/vendor)")
    parser.add_argument("--student-repo", help="URL of the repository of student notebooks (launch buttons)")
    parser.add_argument("--check-unchanged", metavar="FOLDER",
                        help="only check that no notebook in FOLDER was changed (before deleting it)")
    args = parser.parse_args(argv)
    if args.check_unchanged:
        _refuse_if_changed(pathlib.Path(args.check_unchanged), args.force, "deleting")
        return
    out = write_edition(args.root, args.out, args.force, args.vendor, args.student_repo)
    print(f"student edition written to {out.resolve()}")


if __name__ == "__main__":
    main()
