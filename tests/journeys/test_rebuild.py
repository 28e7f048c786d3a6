"""Journey: change ddg, run `make book`, see the change on the pages; break ddg, see the build fail.

In a temporary copy of the repository (sharing .venv, whose pins are the same), with the book
already built there: a message that ddg prints changes, and the next `make book` must run every
notebook again and show the new message. The copy's book keeps chapters 1-5 only (none of them
links to a later one), for time: the Makefile's rule does not look at which notebooks there are. Then the book's stylesheet changes, and the next
`make book` must serve the new one on every page without running a notebook. Then ddg/plot.py is broken, and the build `make test`
gates on (`make book-strict`) must fail, although `make book` has just succeeded.
"""

import re
import shutil

import yaml
from journey_helpers import ROOT, copy_repository, run

DROPPED = re.compile(r"book/(0[6-9]|10)_")  # the chapters the copy's book leaves out (1-5 refer to none of them)


def trim_book(copy):
    """Leave chapters 6-10 out of the copy's table of contents and delete their notebooks; return
    the notebooks the copy's book still has."""
    path = copy / "_toc.yml"
    toc = yaml.safe_load(path.read_text())
    for part in toc["parts"]:
        for chapter in part["chapters"]:
            if DROPPED.match(chapter["file"]):
                (copy / f"{chapter['file']}.ipynb").unlink()
        part["chapters"] = [c for c in part["chapters"] if not DROPPED.match(c["file"])]
    toc["parts"] = [part for part in toc["parts"] if part["chapters"]]
    path.write_text(yaml.safe_dump(toc, sort_keys=False))
    for page in copy.glob("book/*.md"):  # the intro names the explorers' chapter: as plain text now
        page.write_text(re.sub(r"\{doc\}`(\d\d_\w+)`", lambda m: m[0] if (copy / "book" / f"{m[1]}.ipynb").exists()
                               else m[1], page.read_text()))
    listed = sorted(c["file"].removeprefix("book/") for part in toc["parts"] for c in part["chapters"])
    notebooks = sorted(p.stem for p in (copy / "book").glob("*.ipynb"))
    assert set(notebooks) <= set(listed) and len(notebooks) >= 5, (notebooks, listed)
    return notebooks


def test_make_book_shows_a_change_in_ddg_and_the_strict_build_catches_a_broken_ddg(tmp_path):
    copy = copy_repository(tmp_path / "repo")
    built = ROOT / "_build"
    if (built / "html" / "index.html").exists() and (built / ".inputs").exists():  # start from this build
        shutil.copytree(built, copy / "_build", ignore=shutil.ignore_patterns("screenshots", "student", "pdf"))
    else:
        run(["make", "book"], cwd=copy)
    page = copy / "_build" / "html" / "book" / "02_discrete_curves.html"
    assert re.search(r"passed on \d+ public inputs", page.read_text())

    notebooks = trim_book(copy)

    checks = copy / "ddg" / "checks" / "judge.py"
    source = checks.read_text()
    shown = "passed on {self.inputs} {self.kind} inputs"  # what Feedback prints
    assert source.count(shown) == 1
    checks.write_text(source.replace(shown, "passed on {self.inputs} inputs (rebuilt after a change to ddg)"))
    result = run(["make", "book"], cwd=copy)
    assert "every notebook runs again" in result.stdout
    assert "WARNING" not in result.stdout, [line for line in result.stdout.splitlines() if "WARNING" in line]
    executed = sorted(re.findall(r"book/(\w+)\.ipynb: Executed notebook", result.stdout))
    assert executed == notebooks, f"after a change to ddg, ran {executed} of {notebooks}"
    for chapter in ("01_smooth_curves", "02_discrete_curves", "03_winding_number"):
        html = (copy / "_build" / "html" / "book" / f"{chapter}.html").read_text()
        assert "(rebuilt after a change to ddg)" in html, chapter
        assert "public inputs" not in html, chapter

    css = copy / "book" / "_assets" / "ddg-book.css"
    css.write_text(css.read_text() + "\n/* restyled after the first build */\n")
    result = run(["make", "book"], cwd=copy)
    assert "every page is written again" in result.stdout and "every notebook runs again" not in result.stdout
    assert "executing" not in result.stdout.lower(), "a change of the stylesheet ran the notebooks again"
    assert "restyled after the first build" in (copy / "_build" / "html" / "_static" / "ddg-book.css").read_text()
    assert "(rebuilt after a change to ddg)" in (copy / "_build" / "html" / "book" / "02_discrete_curves.html").read_text()

    plot = copy / "ddg" / "plot.py"
    plot.write_text(plot.read_text() + "\nraise RuntimeError('ddg.plot is broken on purpose')\n")
    strict = run(["make", "book-strict"], cwd=copy, check=False)
    assert strict.returncode != 0, "the strict build passed with a broken ddg/plot.py"
    assert re.search(r"ddg\.plot is broken on purpose", strict.stdout), strict.stdout[-3000:]
