"""The book offline after one visit: a service worker and a web app manifest (Sphinx extension).

Every page links ``manifest.webmanifest`` (so a phone can add the book to its home screen), and
``book/_assets/ddg-book.js`` registers ``sw.js`` once the page has loaded, so it never delays the
first paint. The service worker then fetches, in the background, every page of the site and every
file a page loads (its styles, scripts, fonts, images, the explorers' states and the search
index; not the PDFs and not the notebooks' downloads) into a cache named after the build.
Offline, pages and files come from that cache. Online, a page comes from the network (the cache
is refreshed with it), so a reader always sees the latest build; a new build writes a new
``sw.js`` (its ``VERSION`` is a digest of every cached file), which the browser installs on the
next visit, deleting the old cache.

``write_service_worker(site)`` is called when the build has finished and again by ``tools/pdf.py``,
which changes the pages after the build.
"""

import hashlib
import json
import pathlib
import posixpath
import re

NAME = "sw.js"
MANIFEST = "manifest.webmanifest"
REFERENCE = re.compile(r"""\b(?:src|href|data-src)=["']([^"'#]+)["']""")  # data-src: an explorer's states
URL = re.compile(r"""url\(\s*["']?([^"')#]+)["']?\s*\)""")
NOT_CACHED = ("_sources/", "pdf/")  # the notebooks' and the PDFs' downloads: large, and fetched on purpose

WORKER = """\
// The book offline after one visit (written by tools/sphinx_offline.py; do not edit).
const VERSION = "{version}";
const FILES = {files};
const CACHE = "ddg-book-" + VERSION;

self.addEventListener("install", (event) => {{
  event.waitUntil(caches.open(CACHE).then((cache) => cache.addAll(FILES)).then(() => self.skipWaiting()));
}});

self.addEventListener("activate", (event) => {{  // a new build: the old editions' caches go
  event.waitUntil(caches.keys()
    .then((names) => Promise.all(names.filter((n) => n.startsWith("ddg-book-") && n !== CACHE).map((n) => caches.delete(n))))
    .then(() => self.clients.claim()));
}});

self.addEventListener("fetch", (event) => {{
  const request = event.request;
  if (request.method !== "GET" || new URL(request.url).origin !== self.location.origin) return;
  if (request.mode === "navigate") {{  // a page: the latest from the network, else the cached one
    event.respondWith(fetch(request).then((response) => {{
      if (response.ok) {{
        const copy = response.clone();
        caches.open(CACHE).then((cache) => cache.put(request, copy));
      }}
      return response;
    }}).catch(() => caches.match(request, {{ignoreSearch: true}}).then((cached) => cached
      || new Response("<h1>Offline</h1><p>This page was not saved for reading offline.</p>",
                      {{status: 503, headers: {{"Content-Type": "text/html; charset=utf-8"}}}}))));
  }} else {{  // what a page loads: named by its digest, so the cached copy is the right one
    event.respondWith(caches.match(request).then((cached) => cached || fetch(request)));
  }}
}});
"""


def cached_files(site):
    """The site's pages and every file they load, as paths relative to ``site`` (with the query a
    page asks them by, such as ``?v=1a2b``), sorted."""
    site = pathlib.Path(site)
    present = {p.relative_to(site).as_posix() for p in site.rglob("*") if p.is_file()}
    pages = sorted(p for p in present if p.endswith(".html") and not p.startswith(NOT_CACHED))
    found, todo = set(pages), list(pages)
    while todo:
        path = todo.pop()
        if not path.endswith((".html", ".css")):
            continue
        text = (site / path).read_text(errors="replace")
        for reference in (REFERENCE if path.endswith(".html") else URL).findall(text):
            if "://" in reference or reference.startswith(("data:", "mailto:", "javascript:", "/")):
                continue
            name, _, query = reference.partition("?")
            target = posixpath.normpath(posixpath.join(posixpath.dirname(path), name))
            if target in present and not target.startswith(NOT_CACHED):
                # a file by the address the page asks for it (?v=digest); a page once, whatever its
                # query (the lab's presets): pages are looked up without it
                entry = f"{target}?{query}" if query and not target.endswith(".html") else target
                if entry not in found:
                    found.add(entry)
                    todo.append(target)
    return ["./", *sorted(found)]  # "./": the site's address itself, as a reader may open it


def write_service_worker(site):
    """Write ``site/sw.js`` for the site as it is now; return its version (a digest of every file)."""
    site = pathlib.Path(site)
    files = cached_files(site)
    digest = hashlib.sha256()
    for entry in files[1:]:
        digest.update(entry.encode() + b"\0" + (site / entry.partition("?")[0]).read_bytes())
    version = digest.hexdigest()[:16]
    (site / NAME).write_text(WORKER.format(version=version, files=json.dumps(files, indent=0)))
    return version


def write_manifest(site, title):
    manifest = {"name": title, "short_name": "DDG curves", "start_url": "./index.html", "scope": "./",
                "display": "standalone", "background_color": "#ffffff", "theme_color": "#1a5fb4",
                "icons": [{"src": f"_static/ddg-icon-{size}.png", "sizes": f"{size}x{size}", "type": "image/png",
                           "purpose": "any"} for size in (192, 512)]}
    (pathlib.Path(site) / MANIFEST).write_text(json.dumps(manifest, indent=1, ensure_ascii=False) + "\n")


def link_manifest(app, pagename, templatename, context, doctree):
    """The manifest and the colour of the phone's bar (the icon is `html.favicon` in _config.yml)."""
    link = context["pathto"](MANIFEST, 1)
    context["metatags"] = context.get("metatags", "") + (
        f'\n    <link rel="manifest" href="{link}" />\n    <meta name="theme-color" content="#1a5fb4" />')


def finish(app, exception):
    if exception or app.builder.format != "html":
        return
    write_manifest(app.outdir, app.config.html_title or app.config.project)
    write_service_worker(app.outdir)


def setup(app):
    app.connect("html-page-context", link_manifest)
    app.connect("build-finished", finish, priority=900)  # after tools/sphinx_assets.py rewrote the pages
    return {"parallel_read_safe": True, "parallel_write_safe": True}
