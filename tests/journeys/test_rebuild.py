"""Journey: change ddg, run `make book`, see the change on the pages; break ddg, see the build fail.

In a temporary copy of the repository (sharing .venv, whose pins are the same), with the book
already built there: a message that ddg prints changes, and the next `make book` must run every
notebook again and show the new message. Then the book's stylesheet changes, and the next
`make book` must serve the new one on every page without running a notebook. Then ddg/plot.py is broken, and the build `make test`
gates on (`make book-strict`) must fail, although `make book` has just succeeded.
"""

import re
import shutil

from journey_helpers import ROOT, copy_repository, run


def test_make_book_shows_a_change_in_ddg_and_the_strict_build_catches_a_broken_ddg(tmp_path):
    copy = copy_repository(tmp_path / "repo")
    built = ROOT / "_build"
    if (built / "html" / "index.html").exists() and (built / ".inputs").exists():  # start from this build
        shutil.copytree(built, copy / "_build", ignore=shutil.ignore_patterns("screenshots", "student", "pdf"))
    else:
        run(["make", "book"], cwd=copy)
    page = copy / "_build" / "html" / "book" / "02_discrete_curves.html"
    assert re.search(r"passed \d+ checks on fresh random input", page.read_text())

    checks = copy / "ddg" / "checks.py"
    source = checks.read_text()
    shown = "passed {self.checks} checks on fresh random input"  # what Feedback prints
    assert source.count(shown) == 1
    checks.write_text(source.replace(shown, "passed {self.checks} checks (rebuilt after a change to ddg)"))
    result = run(["make", "book"], cwd=copy)
    assert "every notebook runs again" in result.stdout
    assert "WARNING" not in result.stdout, [line for line in result.stdout.splitlines() if "WARNING" in line]
    for chapter in ("01_smooth_curves", "02_discrete_curves", "07_convergence"):
        html = (copy / "_build" / "html" / "book" / f"{chapter}.html").read_text()
        assert "(rebuilt after a change to ddg)" in html, chapter
        assert "on fresh random input" not in html, chapter

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
