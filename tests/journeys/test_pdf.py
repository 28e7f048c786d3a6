"""Journey: a student prints the notes, an instructor posts the PDF (`make pdf`, run by `make test`).

For the book and the student edition: every chapter's PDF exists and has its headings, no TeX
source, at least as many images as the page has figures, and code lines that are not cut; the
book's PDF has every chapter in order with a linked table of contents; the student PDF has no
solution. Each page offers its PDF.
"""

import functools
import re

import pypdfium2
import pytest
import yaml
from bs4 import BeautifulSoup
from journey_helpers import ROOT
from pypdf import PdfReader
from test_student_site import normalize, probes

SITES = {"book": (ROOT / "_build" / "html", ROOT / "_build" / "pdf"),
         "student": (ROOT / "_build" / "student" / "html", ROOT / "_build" / "pdf" / "student")}


def chapters():
    import yaml

    toc = yaml.safe_load((ROOT / "_toc.yml").read_text())
    return [toc["root"]] + [c["file"] for part in toc["parts"] for c in part["chapters"]]


@functools.cache
def read(pdf):
    """The text of each page of ``pdf`` and the number of images it draws, read by PDFium (the
    PDF engine of Chromium's viewer; pypdf, which reads the outline and links below, takes 15
    times as long for the text)."""
    document = pypdfium2.PdfDocument(pdf)
    pages = [document[i] for i in range(len(document))]
    texts = [page.get_textpage().get_text_bounded() for page in pages]
    images = sum(len(list(page.get_objects(filter=[pypdfium2.raw.FPDF_PAGEOBJ_IMAGE], max_depth=5)))
                 for page in pages)
    document.close()
    return texts, images


def tex_source(text):
    """What looks like TeX in ``text``, its spaces read as one (a PDF breaks code lines with \\r\\n)."""
    return set(re.findall(r"\\[a-zA-Z]{2,}|\$[^$\s][^$]{0,40}\$", re.sub(r"\s+", " ", text)))


def squeeze(text):
    return re.sub(r"\s+", "", normalize(text)).replace("ﬁ", "fi").replace("ﬀ", "ff").replace("ﬂ", "fl")


@pytest.mark.parametrize("site", list(SITES))
def test_every_chapter_prints_with_its_headings_figures_and_whole_code_lines(site):
    html_dir, pdf_dir = SITES[site]
    if not (pdf_dir / "book.pdf").exists():
        pytest.fail(f"no {pdf_dir / 'book.pdf'}: `make test` runs `make pdf`")
    for name in chapters():
        pdf = pdf_dir / f"{name.split('/')[-1]}.pdf"
        assert pdf.exists(), pdf
        texts, images = read(pdf)
        text = "\n".join(texts)
        soup = BeautifulSoup((html_dir / f"{name}.html").read_text(), "html.parser")
        main = soup.select_one("main") or soup
        for heading in main.select("h1, h2"):
            title = re.sub(r"^[\d.]+\s*", "", heading.get_text(" ", strip=True).rstrip("#").strip())
            title = re.sub(r"\\\(.*?\\\)", "", title)  # math is typeset, and extracted apart
            assert squeeze(title) in squeeze(text), f"{pdf.name}: heading {title!r} missing"
        code_text = " ".join(pre.get_text() for pre in main.select("pre"))
        tex = tex_source(text) - tex_source(code_text)
        assert not tex, f"{pdf.name}: TeX source outside the code: {sorted(tex)[:5]}"
        figures = len(main.select("figure img, .cell_output img"))
        assert images >= figures, f"{pdf.name}: {images} images for {figures} figures"
        assert "Press ▶" not in text, f"{pdf.name}: a printed strip cannot be played"
        # bookmarks: the chapter, and below it each section (h2), on the page it starts on
        outline = PdfReader(pdf).outline
        titles = [re.sub(r"\s+", " ", h.get_text(" ", strip=True).rstrip("#").strip())
                  for h in main.select("article.bd-article h2")]
        assert len(outline) == (2 if titles else 1), (pdf.name, outline)  # a page without sections: its title
        assert [item.title for item in outline[1:] and outline[1]] == titles, (pdf.name, outline)
        for item in outline[1:] and outline[1]:
            page = PdfReader(pdf).get_destination_page_number(item)
            words = lambda text: re.sub(r"[\W_]+", "", squeeze(text))  # noqa: E731  (a hyphen prints as \x02)
            heading = re.sub(r"^[\d.]+\s*", "", item.title)
            assert words(heading)[:30] in words(texts[page]), (pdf.name, item.title, page)
        code = [line for pre in main.select("div.cell_input pre") if not pre.find_parent("details")
                for line in pre.get_text().splitlines()]  # the code a page shows (folded code prints folded)
        longest = max(code, key=len, default="")
        if len(longest) > 60:  # the longest code line is printed whole, wrapped or not
            assert squeeze(longest) in squeeze(text), f"{pdf.name}: code line cut: {longest!r}"


@pytest.mark.parametrize("site", list(SITES))
def test_the_book_pdf_has_every_chapter_in_order_and_a_linked_contents_page(site):
    _, pdf_dir = SITES[site]
    book = PdfReader(pdf_dir / "book.pdf")
    counts = [len(PdfReader(pdf_dir / f"{name.split('/')[-1]}.pdf").pages) for name in chapters()]
    assert len(book.pages) == 1 + sum(counts)
    outline = [item for item in book.outline if not isinstance(item, list)]  # a chapter's sections: a list after it
    assert len(outline) == len(chapters())
    starts = [book.get_destination_page_number(item) for item in outline]
    assert starts == [1 + sum(counts[:i]) for i in range(len(counts))]
    below = {}  # each chapter's sections: the list after it in the outline (none for a page without h2)
    for before, item in zip(book.outline, book.outline[1:], strict=False):
        if isinstance(item, list):
            below[before.title] = item
    assert sum(len(s) >= 3 for s in below.values()) >= 10, {k: len(v) for k, v in below.items()}
    for item, start, count in zip(outline, starts, counts, strict=True):  # each within its chapter, in order
        pages = [book.get_destination_page_number(section) for section in below.get(item.title, [])]
        assert pages == sorted(pages) and all(start <= p < start + count for p in pages), (item.title, start, pages)
    links = [a.get_object() for a in book.pages[0].get("/Annots", [])]
    links = [a for a in links if "/D" in a["/A"]]  # to a page of the book (the repository's link is a URI)
    targets = [book.get_page_number(a["/A"]["/D"][0]) if hasattr(book, "get_page_number") else None for a in links]
    assert targets == starts, "the contents page does not link to each chapter's first page"
    texts = read(pdf_dir / "book.pdf")[0]
    total = len(book.pages)
    for name, start, count in zip(chapters(), starts, counts, strict=True):  # the feet count the book's pages
        assert f"page {start + 1} of {total}" in texts[start], (name, texts[start][-120:])
        assert f"page {start + count} of {total}" in texts[start + count - 1], name
        first = read(pdf_dir / f"{name.split('/')[-1]}.pdf")[0][0]
        assert f"page 1 of {count}" in first, (name, first[-120:])  # a chapter's own PDF counts its own
    contents = texts[0]
    course = yaml.safe_load((ROOT / "_config.yml").read_text())["repository"]["url"]
    if site == "book":  # where the notebooks are; the student edition (built without one) names none
        assert course in squeeze(contents) or squeeze(course) in squeeze(contents), contents[:300]
    else:
        assert "github.com" not in contents, contents[:300]
    for name, start in zip(chapters(), starts, strict=True):  # as the contents page says
        assert re.search(rf"(?<!\d){start + 1}(\s|$)", contents), (name, start + 1)


@pytest.mark.parametrize("site", list(SITES))
def test_no_printed_page_is_nearly_empty(site):
    """A page with little text holds figures or an explorer's printed states, never nothing."""
    document = pypdfium2.PdfDocument(SITES[site][1] / "book.pdf")
    empty = []
    for i in range(len(document)):
        page = document[i]
        text = page.get_textpage().get_text_bounded()
        drawn = len(list(page.get_objects(filter=[pypdfium2.raw.FPDF_PAGEOBJ_IMAGE, pypdfium2.raw.FPDF_PAGEOBJ_PATH],
                                          max_depth=5)))
        if len(text) < 300 and not drawn:
            empty.append((i + 1, text.strip()[:60]))
    document.close()
    assert not empty, f"nearly empty pages: {empty}"


def test_the_student_pdf_has_no_solution():
    text = normalize("\n".join(read(SITES["student"][1] / "book.pdf")[0]))
    book = normalize("\n".join(read(SITES["book"][1] / "book.pdf")[0]))
    flat = lambda t: re.sub(r"\s+", " ", t)  # noqa: E731
    code = [p for _, p in probes() if "(" in p or "=" in p]  # code lines survive extraction best
    assert not [p for p in code if flat(p) in flat(text)], "solution code in the student PDF"
    assert sum(flat(p) in flat(book) for p in code) >= 0.5 * len(code), "the probes find nothing even in the book"


def test_each_page_offers_its_pdf():
    for site, (html_dir, _) in SITES.items():
        page = (html_dir / "book" / "03_winding_number.html").read_text()
        assert 'href="../pdf/03_winding_number.pdf"' in page and 'href="../pdf/book.pdf"' in page, site
        menu = BeautifulSoup(page, "html.parser").select_one(".dropdown-download-buttons .dropdown-menu")
        assert {a["href"] for a in menu.select("a.ddg-pdf-link")} == {"../pdf/03_winding_number.pdf", "../pdf/book.pdf"}
        assert (html_dir / "pdf" / "03_winding_number.pdf").exists()
