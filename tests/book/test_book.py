"""The book's notebooks and configuration stay consistent (what a reader and Colab rely on)."""

import json
import pathlib
import re
import shutil
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import yaml  # noqa: E402

import ddg  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
NOTEBOOKS = sorted((ROOT / "book").glob("*.ipynb"))


def test_every_notebook_is_in_the_table_of_contents():
    toc = (ROOT / "_toc.yml").read_text()
    listed = set(re.findall(r"file: book/(\S+)", toc))
    assert {nb.stem for nb in NOTEBOOKS} <= listed
    assert len(NOTEBOOKS) >= 8


def test_notebooks_are_committed_without_outputs_and_run_python3():
    for nb in NOTEBOOKS:
        data = json.loads(nb.read_text())
        assert data["metadata"]["kernelspec"]["name"] == "python3", nb.name
        for cell in data["cells"]:
            if cell["cell_type"] == "code":
                assert not cell["outputs"] and cell["execution_count"] is None, nb.name


def test_every_notebook_installs_ddg_from_the_configured_repository_where_it_is_missing():
    url = yaml.safe_load((ROOT / "_config.yml").read_text())["repository"]["url"]
    for nb in NOTEBOOKS:
        first_code = next(c for c in json.loads(nb.read_text())["cells"] if c["cell_type"] == "code")
        source = "".join(first_code["source"])
        assert f'REPOSITORY = "{url}"' in source and "git+{REPOSITORY}" in source, nb.name
        assert "remove-cell" in first_code["metadata"].get("tags", []), nb.name
    assert subprocess.run([sys.executable, "tools/repo.py", "--check"], cwd=ROOT).returncode == 0


def test_make_repo_points_config_and_every_notebook_at_a_new_repository(tmp_path):
    for name in ("_config.yml", "tools/repo.py", "tools/config.py", *(f"book/{nb.name}" for nb in NOTEBOOKS)):
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(ROOT / name, tmp_path / name)
    run = lambda *args: subprocess.run([sys.executable, "tools/repo.py", *args], cwd=tmp_path, capture_output=True, text=True)
    assert run("git@github.com:someone/dg-course.git").returncode == 0
    url = "https://github.com/someone/dg-course"
    assert yaml.safe_load((tmp_path / "_config.yml").read_text())["repository"]["url"] == url
    for nb in NOTEBOOKS:
        cells = json.loads((tmp_path / "book" / nb.name).read_text())["cells"]
        assert f'REPOSITORY = "{url}"' in "".join(next(c for c in cells if c["cell_type"] == "code")["source"])
    assert run("--check").returncode == 0
    assert run("not a url").returncode != 0


def test_make_book_takes_the_repository_from_a_github_origin(tmp_path):
    for name in ("_config.yml", "tools/repo.py", "tools/config.py", *(f"book/{nb.name}" for nb in NOTEBOOKS)):
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(ROOT / name, tmp_path / name)
    git = lambda *args: subprocess.run(["git", *args], cwd=tmp_path, capture_output=True, check=True)  # noqa: E731
    git("init", "-q")
    repo = lambda: subprocess.run([sys.executable, "tools/repo.py", "--from-git"], cwd=tmp_path)  # noqa: E731
    git("remote", "add", "origin", "/some/local/path")  # not GitHub: nothing changes
    before = (tmp_path / "_config.yml").read_text()
    repo()
    assert (tmp_path / "_config.yml").read_text() == before
    git("remote", "set-url", "origin", "git@github.com:someone/dg-course.git")
    repo()
    assert yaml.safe_load((tmp_path / "_config.yml").read_text())["repository"]["url"] == "https://github.com/someone/dg-course"
    assert subprocess.run([sys.executable, "tools/repo.py", "--check"], cwd=tmp_path).returncode == 0


def test_prose_cannot_break_and_jupyterlab_folds_what_the_book_folds():
    """No wrapped line turns into markup; solutions folded, hidden cells collapsed (tools/notebooks.py)."""
    result = subprocess.run([sys.executable, "tools/notebooks.py"], cwd=ROOT, capture_output=True, text=True)
    assert result.returncode == 0, result.stdout


def test_reading_a_notebook_compiles_no_grammar():
    """Every process that reads a notebook imports nbformat, hence jsonschema; with rfc3987-syntax
    installed, jsonschema compiles 39 Earley parsers at import (2.2 s here, in each jupyter-book
    run, nbval worker, JupyterLab and grading sandbox). requirements.txt keeps it out."""
    code = "import sys, nbformat, jupyter_events.validators; print(sorted({'rfc3987_syntax', 'lark'} & set(sys.modules)))"
    loaded = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert loaded.strip() == "[]", loaded


def test_plot_curve_closes_closed_curves():
    fig, ax = plt.subplots()
    line = ddg.plot.plot_curve(ddg.regular_polygon(5), ax)
    assert len(line.get_xdata()) == 6 and line.get_xdata()[0] == line.get_xdata()[-1]
    open_line = ddg.plot.plot_curve(ddg.DiscreteCurve([[0, 0], [1, 0], [1, 1]], closed=False), ax)
    assert len(open_line.get_xdata()) == 3
    plt.close(fig)


def test_notebook_code_is_formatted_to_fit_the_page_column():
    """79 characters: no code box scrolls sideways (fix with `ruff format --line-length 79 book/*.ipynb`)."""
    ruff = [sys.executable, "-m", "ruff"]
    paths = [str(nb) for nb in NOTEBOOKS]
    formatted = subprocess.run([*ruff, "format", "--line-length", "79", "--check", *paths], cwd=ROOT,
                               capture_output=True, text=True)
    assert formatted.returncode == 0, formatted.stdout + formatted.stderr


def test_the_code_passes_ruff():
    """ddg, the tools, the tests, the grader and the notebooks: the rules in pyproject.toml."""
    paths = ["ddg", "tools", "tests", "instructor", *(str(nb) for nb in NOTEBOOKS)]
    linted = subprocess.run([sys.executable, "-m", "ruff", "check", "--output-format", "concise", *paths], cwd=ROOT,
                            capture_output=True, text=True)
    assert linted.returncode == 0, linted.stdout + linted.stderr


def test_the_prose_check_finds_wrapped_lines_that_become_markup():
    from tools.notebooks import prose_problems

    assert prose_problems("since the sine\n# formula *is* the gradient") != []
    assert prose_problems("with $a = b\n+ c$ and more") != []
    assert prose_problems("a line\n> quoted by accident") != []
    assert prose_problems("a line\n---") != []  # a setext heading
    assert prose_problems("```{note}\nwhere\n- a list starts in a directive\n```") != []
    assert prose_problems("Text.\n\n- a list\n- of two\n\n# A heading\n\n$$x\n- y$$") == []
    assert prose_problems("```{solution-start} ex\n:class: dropdown\n```\n1. first\n2. second") == []


def test_the_notebook_check_finds_long_code_a_reader_sees(tmp_path):
    """A chapter reads as a lecture: at most 30 lines of code shown; folded cells and solutions aside."""
    from tools.notebooks import check

    def cell(lines, tags=()):
        return {"cell_type": "code", "source": "x = 1\n" * lines, "metadata": {"tags": list(tags)}, "outputs": []}

    def problems(*cells):
        path = tmp_path / "nb.ipynb"
        path.write_text(json.dumps({"cells": list(cells), "metadata": {}, "nbformat": 4, "nbformat_minor": 5}))
        return [p for p in check(path) if "lines shown" in p]

    assert problems(cell(30)) == []
    assert problems(cell(31)) == ["nb.ipynb cell 0: 31 lines shown on the page (fold it or split it: at most 30)"]
    assert problems(cell(90, ["hide-input"]), cell(90, ["remove-cell"])) == []


def test_the_pdf_step_knows_a_stale_student_edition(tmp_path, monkeypatch):
    """`make pdf` builds the student edition again when the book changed after it was built."""
    import os

    from tools import build

    root = tmp_path / "repo"
    for name in ("book/_assets", "ddg", "tools", "_build/student/html", "_build/student/_build"):
        (root / name).mkdir(parents=True)
    for name in ("requirements.txt", "pyproject.toml", "_config.yml", "_toc.yml", "book/01.ipynb", "ddg/x.py",
                 "book/_assets/lab.js", "tools/vendor.py"):
        (root / name).write_text("x")
    monkeypatch.setattr(build, "ROOT", root)
    monkeypatch.setattr(build, "BUILD", root / "_build")
    site = root / "_build/student/html/index.html"
    site.write_text("<html>")
    build.stamp(root / "_build/student/_build", inputs=build.inputs(), assets=build.assets())
    assert build.student_is_current()
    (root / "book/_assets/lab.js").write_text("y")  # a script of the pages changed: they are written again
    assert not build.student_is_current()
    build.stamp(root / "_build/student/_build", assets=build.assets())
    assert build.student_is_current()
    chapter = root / "book/01.ipynb"
    os.utime(chapter, (site.stat().st_mtime + 5,) * 2)  # the instructor edits a chapter afterwards
    assert not build.student_is_current()
    os.utime(chapter, (site.stat().st_mtime - 5,) * 2)
    (root / "ddg/x.py").write_text("y")  # ddg changed: every output may differ
    assert not build.student_is_current()


def test_every_spelling_of_a_github_repository_is_one_address_and_anything_else_a_clear_error():
    """What an instructor types as STUDENT_REPO or `make repo URL=...`: any spelling of a GitHub
    repository gives https://github.com/owner/name (and its Pages address); anything else exits
    with a message that says what to give, never another exception."""
    from hypothesis import given, strategies as st

    from tools.repo import github_url, https_url, pages_address

    part = st.from_regex(r"[A-Za-z0-9][A-Za-z0-9_.-]{0,20}", fullmatch=True).filter(lambda p: not p.endswith(".git"))
    forms = ["https://github.com/{}/{}", "https://github.com/{}/{}.git", "https://github.com/{}/{}/",
             "git@github.com:{}/{}.git", "git@github.com:{}/{}", "ssh://git@github.com/{}/{}.git"]

    @given(part, part, st.sampled_from(forms))
    def spelled(owner, name, form):
        url = https_url(form.format(owner, name))
        assert url == f"https://github.com/{owner}/{name}" == github_url(url)
        assert pages_address(url) == f"https://{owner.lower()}.github.io/{name}/"

    @given(st.text(max_size=60))
    def anything(text):
        try:
            url = https_url(text, "STUDENT_REPO")
        except SystemExit as error:
            assert "STUDENT_REPO" in str(error) and "https://github.com/owner/name" in str(error)
        else:
            assert url.startswith("https://") and not url.endswith(".git")

    spelled()
    anything()
