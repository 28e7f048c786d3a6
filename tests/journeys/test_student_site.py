"""Journey: an instructor publishes the student edition (`make student`): no solution anywhere.

Every solution of the book leaves probes: its code lines and runs of six words of its prose. None
of them may appear anywhere in the student site (pages, sources, downloads, search index) or in
the student notebooks; nearly all of them must appear in the instructor's site, which shows that
the probes would find a leak. The edition must also be portable and have no wrong launch button.
"""

import html
import json
import re

import pytest
from bs4 import BeautifulSoup
from journey_helpers import ROOT

from tools.notebooks import solution_cells

STUDENT = ROOT / "_build" / "student"
SITES = {"student": STUDENT / "html", "book": ROOT / "_build" / "html"}


def normalize(text):
    text = html.unescape(text).replace("’", "'").replace("‘", "'").replace("“", '"').replace("”", '"')
    return re.sub(r"\s+", " ", text)


def shown_to_students():
    """All the book's text outside solutions, and the starter code made from solutions."""
    from instructor.edition import starter

    texts = []
    for path in sorted((ROOT / "book").glob("*.ipynb")):
        cells = json.loads(path.read_text())["cells"]
        first, rest = solution_cells(cells)
        for i, cell in enumerate(cells):
            source = "".join(cell["source"])
            if i not in first | rest:
                texts.append(source)
            elif "solution" in cell["metadata"].get("tags", []):
                texts.append(starter(source))
    return normalize("\n".join(texts))


def probes():
    """(notebook, probe) pairs: distinctive pieces of every solution's code and prose (pieces that
    the book also shows outside its solutions, such as a docstring kept in a starter, are no leak
    and are left out)."""
    found, shown = [], shown_to_students()
    for path in sorted((ROOT / "book").glob("*.ipynb")):
        cells = json.loads(path.read_text())["cells"]
        first, rest = solution_cells(cells)
        for i in sorted(first | rest):
            cell = cells[i]
            source = "".join(cell["source"])
            if "check" in cell["metadata"].get("tags", []):
                continue  # the check call stays in the student edition, on purpose
            if cell["cell_type"] == "code":
                found += [(path.name, line.strip()) for line in source.splitlines()
                          if len(line.strip()) >= 25 and not line.strip().startswith(("#", '"""', "def "))]
            else:
                plain = re.sub(r"```\{solution-(start|end)\}[^`]*```|\$\$.*?\$\$|\$[^$]*\$|`[^`]*`|\{[^}]*\}|\[|\]\([^)]*\)",
                               "|", source, flags=re.S)
                for segment in re.split(r"[|*\n:]+", plain):
                    words = segment.split()
                    if len(words) >= 6:
                        found.append((path.name, " ".join(words[:6])))
    return [(name, probe) for name, probe in found if normalize(probe) not in shown]


def site_text(folder):
    """Everything a reader of the site can get: page text, sources, notebooks, scripts."""
    texts = []
    for path in folder.rglob("*"):
        if path.suffix == ".html":
            texts.append(BeautifulSoup(path.read_text(errors="replace"), "html.parser").get_text(" "))
        elif path.suffix == ".ipynb":
            texts += ["".join(c["source"]) for c in json.loads(path.read_text())["cells"]]
        elif path.suffix in (".js", ".txt", ".md", ".json") and "_vendor" not in path.parts and path.stat().st_size < 5e6:
            texts.append(path.read_text(errors="replace"))
    return normalize("\n".join(texts))


@pytest.fixture(scope="module")
def built():
    for name, site in SITES.items():
        if not (site / "index.html").exists():
            pytest.fail(f"no {name} site in {site}: `make test` builds both (make book-strict, make student)")
    return {name: site_text(site) for name, site in SITES.items()}


def test_no_solution_anywhere_in_the_student_site(built):
    all_probes = probes()
    assert len(all_probes) >= 60
    leaked = [(nb, probe) for nb, probe in all_probes if normalize(probe) in built["student"]]
    assert not leaked, f"solution text in the student site: {leaked[:5]}"
    notebooks = normalize("\n".join(p.read_text() for p in (STUDENT / "book").glob("*.ipynb")))
    assert not [p for _, p in all_probes if json.dumps(p)[1:-1] in notebooks]
    shown = [probe for _, probe in all_probes if normalize(probe) in built["book"]]
    assert len(shown) >= 0.9 * len(all_probes), "the probes do not find the solutions in the instructor's site"


def test_the_student_site_has_every_page_figure_and_exercise_of_the_book():
    for page in sorted((SITES["book"] / "book").glob("*.html")):
        ours, theirs = page.read_text(), (SITES["student"] / "book" / page.name).read_text()
        count = lambda text, pattern: len(re.findall(pattern, text))  # noqa: E731
        assert count(theirs, r"<img ") >= count(ours, r"<img ") - count(ours, r'class="[^"]*solution'), page.name
        assert count(theirs, r'class="[^"]*exercise') == count(ours, r'class="[^"]*exercise'), page.name
        assert "not written yet" in theirs or "tag_check" not in ours, page.name  # the checks ran on starters


def test_the_student_edition_is_portable_and_has_no_wrong_launch_button():
    config = (STUDENT / "_config.yml").read_text()
    assert str(ROOT) not in config and "/root" not in config and "html_static_path: [_vendor, book/_assets]" in config
    pages = "".join(p.read_text() for p in (SITES["student"] / "book").glob("*.html"))
    assert "mybinder.org" not in pages and "colab.research" not in pages
    assert "_sources/book/03_winding_number.ipynb" in pages  # the download leads to the student notebook
    assert str(ROOT) not in pages
