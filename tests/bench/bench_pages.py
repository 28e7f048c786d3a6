"""`make bench`: what each page of both sites costs a phone on a slow connection.

    python tests/bench/bench_pages.py [WORD ...]     only the pages whose path contains a WORD

Both built sites (_build/html, _build/student/html) are served from 127.0.0.1 compressed with
gzip, as a static host such as GitHub Pages serves them. Each page is opened with a cold cache in
Chromium as a phone sees it: a 390 x 844 viewport, the CPU slowed 4x and a "fast 3G" network
(1.6 Mbit/s down, 750 kbit/s up, 150 ms round trip). For each page it prints the bytes
transferred (as sent: compressed, with headers), the first contentful paint, the time until every
formula is final (typeset and its fonts arrived; on a page with no math, nothing), and the layout
shift score (0 when nothing moves as the page arrives). Then the bytes of the heaviest page by
asset, the same pages on a desktop (1280 x 900, nothing slowed), and the frame times of chapter
10's lab on the phone (a dragged vertex, without and with the polygon inflated; the region
measured when the drag ends; the three flows playing) for n = 100, 300, 500 and 2000.

A benchmark: timings are noisy (the machine is shared), so it reports and asserts nothing; the
browser tests assert what is deterministic (tests/browser/test_site.py: bytes, scripts, math).
"""

import functools
import gzip
import http.server
import pathlib
import re
import sys
import threading

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))
from tools.browser import find as find_chromium  # noqa: E402

SITES = {"book": ROOT / "_build" / "html", "student": ROOT / "_build" / "student" / "html"}
PHONE = {"viewport": {"width": 390, "height": 844}, "device_scale_factor": 3, "is_mobile": True, "has_touch": True}
DESKTOP = {"viewport": {"width": 1280, "height": 900}}
FAST_3G = {"offline": False, "latency": 150, "downloadThroughput": 1.6e6 / 8, "uploadThroughput": 750e3 / 8}
FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--disable-background-networking",
         "--disable-component-update", "--disable-sync", "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1"]
COMPRESSED = (".html", ".css", ".js", ".svg", ".json", ".txt", ".inv", ".map")  # what a static host gzips
REFRESH = re.compile(r'<meta\s+http-equiv="refresh"', re.I)

# When the page's math is final: painted (first contentful paint), typeset (by MathJax in the
# page, when its startup promise resolves; or in the HTML, when the HTML is parsed) and every
# MathJax font it asked for arrived. Also the layout shifts.
MARKS = """(() => {
    const marks = window.__bench = {cls: 0};
    new PerformanceObserver(list => list.getEntries().forEach(e => { if (!e.hadRecentInput) marks.cls += e.value; }))
        .observe({type: "layout-shift", buffered: true});
    document.addEventListener("DOMContentLoaded", () => {
        const typeset = window.MathJax && MathJax.startup && MathJax.startup.promise;
        const parsed = performance.getEntriesByType("navigation")[0].domInteractive;
        (typeset || Promise.resolve()).then(() => { marks.typeset = typeset ? performance.now() : parsed; });
    });
})()"""
RESULT = """() => document.fonts.ready.then(() => {
    const marks = window.__bench, fcp = performance.getEntriesByName("first-contentful-paint")[0];
    const fonts = performance.getEntriesByType("resource").filter(r => /MathJax_|mathjax.*\\.woff/.test(r.name));
    const math = document.querySelectorAll("mjx-container").length;
    return {fcp: fcp ? fcp.startTime : null, math, cls: marks.cls,
            final: math ? Math.max(fcp ? fcp.startTime : 0, marks.typeset, ...fonts.map(r => r.responseEnd)) : null};
})"""


class Gzipped(http.server.SimpleHTTPRequestHandler):
    """A static host: text compressed with gzip, the rest as it is; HTTP/1.1 keep-alive."""

    protocol_version = "HTTP/1.1"

    def log_message(self, *args):
        pass

    def send_head(self):
        path = pathlib.Path(self.translate_path(self.path))
        if path.is_dir():
            path = path / "index.html"
        if not path.is_file():
            return super().send_head()
        data = path.read_bytes()
        if path.suffix in COMPRESSED and "gzip" in self.headers.get("Accept-Encoding", ""):
            data = gzip.compress(data, 6, mtime=0)
            self.send_response(200)
            self.send_header("Content-Encoding", "gzip")
        else:
            self.send_response(200)
        self.send_header("Content-Type", self.guess_type(str(path)))
        self.send_header("Content-Length", str(len(data)))
        self.end_headers()
        self.wfile.write(data)
        return None


def serve(folder):
    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(Gzipped, directory=str(folder)))
    threading.Thread(target=httpd.serve_forever, daemon=True).start()
    return httpd


def pages(folder, words):
    found = sorted(str(p.relative_to(folder)) for p in folder.rglob("*.html") if "_static" not in p.parts)
    found = [p for p in found if not REFRESH.search((folder / p).read_text(errors="replace")[:2000])]
    return [p for p in found if not words or any(w in p for w in words)]


def measure(browser, url, profile, slow):
    """One cold page load: {bytes, fcp, final, cls, math, assets: {path: bytes}}."""
    context = browser.new_context(**profile)
    page = context.new_page()
    cdp = context.new_cdp_session(page)
    urls, assets, open_ = {}, {}, set()

    def sent(event):
        urls[event["requestId"]] = event["request"]["url"]
        open_.add(event["requestId"])

    def finished(event):
        url = urls.get(event["requestId"], event["requestId"])
        assets[url] = assets.get(url, 0) + event.get("encodedDataLength", 0)
        open_.discard(event["requestId"])

    cdp.on("Network.requestWillBeSent", sent)
    cdp.on("Network.loadingFinished", finished)
    cdp.on("Network.loadingFailed", finished)
    cdp.send("Network.enable")
    if slow:
        cdp.send("Network.emulateNetworkConditions", FAST_3G)
        cdp.send("Emulation.setCPUThrottlingRate", {"rate": 4})
    page.add_init_script(MARKS)
    page.goto(url, wait_until="load", timeout=120_000)
    page.wait_for_function("() => window.__bench && window.__bench.typeset !== undefined", timeout=120_000)
    quiet = 0
    while quiet < 4:  # nothing asked for during 1 s (lazy loads, fonts)
        page.wait_for_timeout(250)
        quiet = 0 if open_ else quiet + 1
    result = page.evaluate(RESULT)
    context.close()
    base = "/".join(url.split("/")[:3])  # http://127.0.0.1:port
    result["assets"] = {u.removeprefix(base).split("?")[0]: b for u, b in assets.items() if not u.startswith("data:")}
    result["bytes"] = sum(result["assets"].values())
    return result


# The lab's frame (chapter 10): a vertex moved as a pointer drags it, then two animation frames (the
# update, its layout and paint); and one frame of the three flows playing (8 ms of steps, drawn).
LAB_FRAMES = """async (count) => {
    const lab = document.querySelector('.ddg-lab').lab, frame = () => new Promise(r => requestAnimationFrame(r));
    const drag = [], flow = [];
    for (let k = 0; k < 6; k++) lab.move(3, lab.vertices[3].slice());  // compiled first, as after a moment's use
    lab.dragging = 3;  // as a pointer drags it
    for (let k = 0; k < count; k++) {
        const t = performance.now(), v = lab.vertices[3];
        lab.move(3, [v[0] + (k % 2 ? -0.01 : 0.01), v[1]]);
        await frame(); await frame();
        drag.push(performance.now() - t);
    }
    const inflated = [], measured = [], p = lab.inflation;  // inflated as a Minkowski sum by 0.2
    lab.method.value = "minkowski"; lab.eps.value = 0.2;
    for (let k = 0; k < count; k++) {  // dragged: the pieces and the formula at once, the region later
        const t = performance.now(), v = lab.vertices[3];
        lab.move(3, [v[0] + (k % 2 ? -0.01 : 0.01), v[1]]);
        await frame(); await frame();
        inflated.push(performance.now() - t);
    }
    lab.dragging = undefined;
    for (let k = 0; k < 5 && lab.vertices.length <= 300; k++) {  // let go: until the region is measured
        const t = performance.now(), v = lab.vertices[3];
        lab.move(3, [v[0] + (k % 2 ? -0.01 : 0.01), v[1]]);
        while (!("measured" in p.dataset)) await frame();
        measured.push(performance.now() - t);
    }
    lab.method.value = ""; lab.update();
    lab.flows.begin();
    for (let k = 0; k < count; k++) {
        const t = performance.now(), until = t + 8;
        while (performance.now() < until && lab.flows.step()) {}
        lab.flows.draw();
        await frame(); await frame();
        flow.push(performance.now() - t);
    }
    const median = xs => xs.sort((a, b) => a - b)[xs.length >> 1];
    return {drag: median(drag), flow: median(flow), steps: lab.flows.runs.map(r => r.record.length - 1),
            inflated: median(inflated), measured: measured.length ? median(measured) : null};
}"""


def lab_frames(browser, base):
    """The lab's frame times on a phone with its CPU 4x slower, for n = 100, 300, 500 and 2000: a drag, a
    drag with the polygon inflated, the region measured when the hand stops (up to 300 vertices), and
    the flows playing."""
    print("\nthe lab on a phone, CPU 4x slower: median of 30 frames (ms; two animation frames each, 33 ms at 60 Hz)")
    print(f"{'n':>6} {'drag a vertex':>14} {'drag, inflated':>15} {'region measured':>16} {'flows playing':>14} "
          f"{'flow steps in 30 frames':>24}")
    for n in (100, 300, 500, 2000):
        context = browser.new_context(**PHONE)
        page = context.new_page()
        page.goto(f"{base}book/10_explorers.html?lab=blob&n={n}", wait_until="load")
        page.locator("svg.ddg-lab-svg").scroll_into_view_if_needed()  # on the screen: drawn (off it, skipped)
        cdp = context.new_cdp_session(page)
        cdp.send("Emulation.setCPUThrottlingRate", {"rate": 4})
        r = page.evaluate(LAB_FRAMES, 30)
        region = "not measured" if r["measured"] is None else f"{r['measured']:.1f}"
        print(f"{n:>6} {r['drag']:>14.1f} {r['inflated']:>15.1f} {region:>16} {r['flow']:>14.1f} "
              f"{'/'.join(map(str, r['steps'])):>24}")
        context.close()


def seconds(ms):
    return "-" if ms is None else f"{ms / 1000:.1f}"


def report(title, rows):
    print(f"\n{title}")
    print(f"{'page':<40} {'kB':>7} {'FCP s':>6} {'math s':>7} {'shift':>6} {'formulas':>8}")
    for name, r in rows:
        print(f"{name:<40} {r['bytes'] / 1000:>7.0f} {seconds(r['fcp']):>6} {seconds(r['final']):>7} "
              f"{r['cls']:>6.3f} {r['math']:>8}")


def main(words):
    from playwright.sync_api import sync_playwright

    servers = {site: serve(folder) for site, folder in SITES.items() if (folder / "index.html").exists()}
    if not servers:
        sys.exit("no site built: run `make book` (and `make student`) first")
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=find_chromium(), args=FLAGS)
        for name, profile, slow in (("phone, CPU 4x slower, fast 3G", PHONE, True), ("desktop", DESKTOP, False)):
            rows = []
            for site, httpd in servers.items():
                for path in pages(SITES[site], words):
                    url = f"http://127.0.0.1:{httpd.server_port}/{path}"
                    rows.append((f"{site}:{path}", measure(browser, url, profile, slow)))
            report(f"{name} (transferred, first contentful paint, every formula final, layout shift)", rows)
            if slow:
                heaviest, result = max(rows, key=lambda row: row[1]["bytes"])
                print(f"\n{heaviest}: {result['bytes'] / 1000:.0f} kB by asset")
                for asset, size in sorted(result["assets"].items(), key=lambda item: -item[1]):
                    print(f"  {size / 1000:>7.1f} kB  {asset}")
        if "book" in servers and (not words or any(w in "book/10_explorers.html" for w in words)):
            lab_frames(browser, f"http://127.0.0.1:{servers['book'].server_port}/")
        browser.close()
    for httpd in servers.values():
        httpd.shutdown()


if __name__ == "__main__":
    main(sys.argv[1:])
