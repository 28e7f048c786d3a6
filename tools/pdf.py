"""`make pdf`: the built book, and the student edition when it exists, as PDF.

    python tools/pdf.py SITE OUT        e.g. _build/html _build/pdf

Chromium prints each page of the table of contents, served on loopback, once its fonts have
loaded (the math's among them: its formulas were typeset when the book was built), with
Playwright's `page.pdf` and the book's print stylesheet: no sidebars or buttons, code that wraps,
every explorer and animation as a strip of its states. Solutions print open; code that the page
folds (the code behind a figure) stays out.
Each chapter becomes OUT/<chapter>.pdf, with its title and its page numbers at the foot of every
page; OUT/book.pdf is all of them in order, after a title page whose table of contents links to
each chapter (and a PDF outline), and there the feet count the book's pages, as the contents do. The PDFs are also copied into SITE/pdf/, and each page of the
site offers its chapter's PDF and the book's next to its .ipynb download.
"""

import functools
import html
import http.server
import io
import logging
import pathlib
import re
import sys
import threading

import yaml
from pypdf import PdfReader, PdfWriter
from pypdf.generic import ArrayObject, DictionaryObject, FloatObject, NameObject, NumberObject

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
from tools.browser import find as find_chromium  # noqa: E402
from tools.sphinx_offline import write_service_worker  # noqa: E402

FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--disable-background-networking",
         "--disable-component-update", "--disable-sync"]
logging.getLogger("pypdf").setLevel(logging.ERROR)  # not "Object count 366 exceeds defined trailer size 360"
# for every chapter: Chromium's trailers count one object short, which pypdf reads past unharmed
MARGIN = {"top": "16mm", "bottom": "16mm", "left": "14mm", "right": "14mm"}
FOOT = ('<div style="height: 296mm; position: relative; break-after: page; font: 8px sans-serif; color: #555">'
        '<div style="position: absolute; bottom: 7mm; width: 100%; text-align: center">{}</div></div>')


# The pages' images load as a reader comes near them (loading="lazy"): in print, every one.
EVERY_IMAGE = """() => Promise.all([...document.images].map(image => {
    image.loading = "eager";
    return image.complete ? null : new Promise(done => { image.onload = image.onerror = done; });
}))"""


def chapters(site):
    """(page, title) of each page of the table of contents, in order (read from the site's _toc.yml)."""
    toc = yaml.safe_load((ROOT / "_toc.yml").read_text())
    files = [toc["root"]] + [c["file"] for part in toc.get("parts", []) for c in part["chapters"]]
    found = []
    for name in files:
        page = site / f"{name}.html"
        if page.exists():
            title = re.search(r"<title>(.*?)(?: &#8212;| —|</title>)", page.read_text()).group(1)
            found.append((f"{name}.html", re.sub(r"<[^>]+>", "", title).strip()))
    return found


def serve(site):
    class Quiet(http.server.SimpleHTTPRequestHandler):
        def log_message(self, *args):
            pass

    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(Quiet, directory=str(site)))
    threading.Thread(target=httpd.serve_forever, daemon=True).start()
    return httpd


SECTIONS = """() => [...document.querySelectorAll("main article.bd-article h2")].filter(h => h.getClientRects().length).map(h => {
    const copy = h.cloneNode(true);
    copy.querySelectorAll(".headerlink, mjx-assistive-mml").forEach(e => e.remove());
    return copy.textContent.replace(/\\s+/g, " ").trim();
})"""


def print_page(browser, url, out, title):
    """One page as PDF, with its fonts loaded and solutions open; returns its number of pages and
    its sections (h2) with the page each starts on, for the PDF's bookmarks."""
    context = browser.new_context()
    context.route("**/*", lambda r: r.continue_() if r.request.url.startswith(url.split("/book/")[0])
                  or r.request.url.startswith("data:") else r.abort())
    page = context.new_page()
    page.goto(url, wait_until="networkidle")
    page.evaluate("""() => document.querySelectorAll('.toggle-hidden').forEach(e => e.classList.remove('toggle-hidden'))""")
    page.evaluate(EVERY_IMAGE)
    page.emulate_media(media="print")
    page.evaluate("() => document.fonts.ready.then(() => true)")  # the fonts the printed layout uses
    titles = page.evaluate(SECTIONS)
    # tagged, with Chromium's outline: it knows on which page each heading landed
    page.pdf(path=str(out), format="A4", print_background=True, margin=MARGIN, tagged=True, outline=True)
    context.close()
    reader = PdfReader(out)
    return len(reader.pages), located(titles, outline_pages(reader, reader.outline))


def outline_pages(reader, items):
    """Every bookmark of ``items`` (nested lists, as pypdf reads them) in order: (title, page)."""
    return [pair for item in items for pair in (outline_pages(reader, item) if isinstance(item, list)
                                                else [(item.title, reader.get_destination_page_number(item))])]


def located(titles, headings):
    """Each title with the page of the first heading of Chromium's outline (from the last one found
    on) that holds its words. Its own titles are not used: in them words run together, some twice."""
    squeeze = lambda text: re.sub(r"[\W_]+", "", text).lower()  # noqa: E731
    found, at = [], 0
    for title in titles:
        words = squeeze(re.sub(r"^[\d.]+\s*", "", title))
        at = next((k for k in range(at, len(headings)) if words and words in squeeze(headings[k][0])), at)
        found.append((title, headings[at][1] if headings else 0))
    return found


def outlined(writer, name, start, sections):
    """Bookmarks: ``name`` at page ``start``, its sections below it."""
    parent = writer.add_outline_item(title=name, page_number=start)
    for title, page in sections:
        writer.add_outline_item(title=title, page_number=start + page, parent=parent)


def feet(browser, texts, out):
    """A PDF of blank A4 pages, each with its text at the foot: laid over the printed pages."""
    context = browser.new_context()
    page = context.new_page()
    page.set_content("<html><head><meta charset='utf-8'><style>body { margin: 0 }</style></head><body>"
                     + "".join(FOOT.format(text) for text in texts) + "</body></html>")
    page.pdf(path=str(out), format="A4", margin={"top": "0", "bottom": "0", "left": "0", "right": "0"})
    context.close()
    return PdfReader(out).pages


def compact(writer):
    """Each page's drawing compressed at zlib's level 9, and every repeated object (the fonts each
    chapter embeds again, an image printed twice) kept once: the book's PDF was 15.1 MB, now 6.4."""
    # the tags Chromium wrote so that its outline finds the headings' pages go (the structure tree;
    # the marks in the drawing stay): the book's PDF is 6.6 MB, 6.5 untagged
    writer.root_object.pop(NameObject("/StructTreeRoot"), None)
    writer.root_object.pop(NameObject("/MarkInfo"), None)
    for page in writer.pages:
        page.pop(NameObject("/StructParents"), None)
        page.compress_content_streams(level=9)
    writer.compress_identical_objects(remove_duplicates=True, remove_unreferenced=True)


def numbered(pdf, overlays, out, name, sections):
    """``pdf`` with each page's foot laid over it and its bookmarks, written to ``out``."""
    writer = PdfWriter(clone_from=PdfReader(io.BytesIO(pathlib.Path(pdf).read_bytes())))
    for page, foot in zip(writer.pages, overlays, strict=True):
        page.merge_page(foot)
    writer.root_object.pop(NameObject("/Outlines"), None)  # Chromium's, in place of ours
    outlined(writer, name, 0, sections)
    compact(writer)
    with open(out, "wb") as file:
        writer.write(file)


def contents_page(browser, title, entries, out, repository=None):
    """The title page with a table of contents; each entry links to a placeholder URL, then fixed.
    With ``repository``, it says where the chapters' notebooks are."""
    rows = "".join(f'<li><a href="https://contents.invalid/{i}">{html.escape(name)}</a><span>{page}</span></li>'
                   for i, (name, page) in enumerate(entries))
    where = (f'<p>The chapters as notebooks to run: <a href="{html.escape(repository)}">{html.escape(repository)}</a></p>'
             if repository else "")
    page_html = (f"<html><head><meta charset='utf-8'><style>body {{ font-family: sans-serif; margin: 3cm 2.5cm; }}"
            "h1 { font-size: 26pt; } li { display: flex; justify-content: space-between; margin: 0.4em 0; }"
            "a { color: #0a4f8a; text-decoration: none; } ol { padding: 0; list-style: none; }</style></head>"
            f"<body><h1>{html.escape(title)}</h1>{where}<h2>Contents</h2><ol>{rows}</ol></body></html>")
    context = browser.new_context()
    page = context.new_page()
    page.set_content(page_html)
    page.pdf(path=str(out), format="A4", print_background=True)
    context.close()


def link_contents(writer, starts):
    """Point the contents page's placeholder links at the chapters' first pages."""
    page = writer.pages[0]
    for annotation in page.get("/Annots", []):
        annotation = annotation.get_object()
        uri = annotation.get("/A", {}).get("/URI", "")
        match = re.match(r"https://contents\.invalid/(\d+)", str(uri))
        if match:
            target = writer.pages[starts[int(match.group(1))]].indirect_reference
            annotation[NameObject("/A")] = DictionaryObject({
                NameObject("/S"): NameObject("/GoTo"),
                NameObject("/D"): ArrayObject([target, NameObject("/XYZ"), NumberObject(0), FloatObject(842),
                                               NumberObject(0)])})


def offer_downloads(site, pages):
    """Each page's download menu offers its chapter's PDF and the book's (idempotent)."""
    for path, _ in pages:
        page = site / path
        html = page.read_text()
        if "ddg-pdf-link" in html:
            continue
        up = "../" * path.count("/")
        items = (f'<li><a href="{up}pdf/{pathlib.Path(path).stem}.pdf" class="btn btn-sm dropdown-item ddg-pdf-link">'
                 f'<span class="btn__text-container">PDF of this chapter</span></a></li>'
                 f'<li><a href="{up}pdf/book.pdf" class="btn btn-sm dropdown-item ddg-pdf-link">'
                 f'<span class="btn__text-container">PDF of the book</span></a></li>')
        menu = html.find('<ul class="dropdown-menu">', html.find("dropdown-download-buttons"))  # not the launch menu
        if "dropdown-download-buttons" in html and menu >= 0:
            menu += len('<ul class="dropdown-menu">')
            page.write_text(html[:menu] + items + html[menu:])


def main(site, out):
    from playwright.sync_api import sync_playwright

    site, out = pathlib.Path(site), pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    pages = chapters(site)
    config = site.parent / "_config.yml"  # the student edition's, next to its html/; else the book's
    config = config if config.exists() else ROOT / "_config.yml"
    settings = yaml.safe_load(config.read_text())
    title = settings["title"]
    # the repository the site's buttons lead to (none: the student edition without a student repository)
    repository = settings["repository"]["url"] if settings.get("html", {}).get("use_repository_button") else None
    httpd = serve(site)
    base = f"http://127.0.0.1:{httpd.server_port}/"
    counts, sections = [], []
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=find_chromium(), args=FLAGS)
        for path, name in pages:
            count, found = print_page(browser, base + path, out / f"{pathlib.Path(path).stem}.pdf", name)
            counts.append(count)
            sections.append(found)
        starts = [1 + sum(counts[:i]) for i in range(len(counts))]  # after the contents page
        contents_page(browser, title, [(name, start + 1) for (_, name), start in zip(pages, starts, strict=True)],
                      out / "contents.pdf", repository)
        total = 1 + sum(counts)
        book_feet = feet(browser, [""] + [f"{name} &middot; page {start + k} of {total}" for (_, name), start, count
                                          in zip(pages, starts, counts, strict=True) for k in range(1, count + 1)],
                         out / "feet.pdf")
        chapter_feet = [feet(browser, [f"{name} &middot; page {k} of {count}" for k in range(1, count + 1)],
                             out / f"feet-{i}.pdf") for i, ((_, name), count) in enumerate(zip(pages, counts, strict=True))]
        browser.close()
    httpd.shutdown()
    writer = PdfWriter()
    writer.append(out / "contents.pdf")
    for (path, name), start, found in zip(pages, starts, sections, strict=True):
        writer.append(out / f"{pathlib.Path(path).stem}.pdf", import_outline=False)
        outlined(writer, name, start, found)
    for page, foot in zip(writer.pages, book_feet, strict=True):
        page.merge_page(foot)
    for (path, name), overlays, found in zip(pages, chapter_feet, sections, strict=True):  # after the book took them
        chapter = out / f"{pathlib.Path(path).stem}.pdf"
        numbered(chapter, overlays, chapter, name, found)
    link_contents(writer, starts)
    writer.add_metadata({"/Title": title})
    compact(writer)
    with open(out / "book.pdf", "wb") as file:
        writer.write(file)
    for scratch in (out / "contents.pdf", *out.glob("feet*.pdf")):
        scratch.unlink()
    copy = site / "pdf"
    copy.mkdir(exist_ok=True)
    for pdf in out.glob("*.pdf"):
        (copy / pdf.name).write_bytes(pdf.read_bytes())
    offer_downloads(site, pages)
    write_service_worker(site)  # the pages changed: readers who kept the book offline get them
    print(f"{out / 'book.pdf'}: {1 + sum(counts)} pages, {(out / 'book.pdf').stat().st_size / 2**20:.1f} MB; "
          f"{len(pages)} chapter PDFs in {out}")


if __name__ == "__main__":
    main(*sys.argv[1:3])
