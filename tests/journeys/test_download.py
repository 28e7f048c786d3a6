"""Journey: download a chapter's notebook from the book and run it in a plain Jupyter.

A fresh environment with Jupyter's kernel and nothing else (no ddg, no matplotlib) runs the
notebook exactly as the book's download button serves it. Its first cell must install ddg from
the course repository and say so in one line, after which the chapter runs. Where the repository
cannot be reached, the first cell must print the exact command to run instead. The course
repository is served by git's HTTP protocol on 127.0.0.1, since tests use loopback only; pip
installs the other packages from the wheelhouse.
"""

import functools
import http.server
import json
import re
import threading

from journey_helpers import OFFLINE_PIP, ROOT, copy_repository, fresh_venv, run

CHAPTER = "02_discrete_curves"
RUN = r"""
import json, sys
import nbformat
from nbclient import NotebookClient
nb = nbformat.read(sys.argv[1], as_version=4)
NotebookClient(nb, timeout=300, kernel_name="python3", allow_errors=True).execute()
def shown(o):  # what an output shows: its text, or its kinds of data and their text
    if o.output_type == "stream":
        return o.text
    if o.output_type == "error":
        return "ERROR " + o.ename
    return " ".join(sorted(o.data)) + " " + o.data.get("text/plain", "")
print(json.dumps([[shown(o) for o in c.get("outputs", [])] for c in nb.cells if c.cell_type == "code"]))
"""


def outputs_of(python, notebook, cwd):
    result = run([str(python), "-c", RUN, str(notebook)], cwd=cwd, env=OFFLINE_PIP | {"PYTHONPATH": ""})
    return json.loads(result.stdout.strip().splitlines()[-1])


def with_repository(source, target, url):
    data = json.loads(source.read_text())
    first = next(c for c in data["cells"] if c["cell_type"] == "code")
    text = "".join(first["source"])
    assert re.search(r'^REPOSITORY = "[^"]+"$', text, re.MULTILINE)
    first["source"] = re.sub(r'^REPOSITORY = "[^"]+"$', f'REPOSITORY = "{url}"', text, flags=re.MULTILINE)
    target.write_text(json.dumps(data))
    return target


def test_a_downloaded_notebook_installs_ddg_where_it_is_missing(tmp_path):
    page = (ROOT / "_build" / "html" / "book" / f"{CHAPTER}.html").read_text()
    download = ROOT / "_build" / "html" / "_sources" / "book" / f"{CHAPTER}.ipynb"
    assert f"_sources/book/{CHAPTER}.ipynb" in page and download.exists(), "build the book first (make test does)"

    repository = copy_repository(tmp_path / "course", with_venv=False)  # the course repository, as git
    for command in (["git", "init", "-q"], ["git", "add", "-A"],
                    ["git", "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "course"],
                    ["git", "clone", "-q", "--bare", ".", str(tmp_path / "served" / "course.git")]):
        run(command, cwd=repository)
    run(["git", "update-server-info"], cwd=tmp_path / "served" / "course.git")  # git's "dumb" HTTP protocol
    handler = functools.partial(http.server.SimpleHTTPRequestHandler, directory=str(tmp_path / "served"))
    handler.log_message = lambda *args: None
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    python = fresh_venv(tmp_path / "jupyter")
    run([str(python), "-m", "pip", "install", "--quiet", "ipykernel", "nbclient"], env=OFFLINE_PIP)
    work = tmp_path / "downloads"
    work.mkdir()

    # the repository cannot be reached: the first cell says what to run, and the chapter stops there
    unreachable = "http://127.0.0.1:9/nonexistent.git"  # the discard port: nothing there
    cells = outputs_of(python, with_repository(download, work / "a.ipynb", unreachable), work)
    first = "".join(cells[0])
    assert f"Installing ddg from {unreachable} ..." in first
    assert f'install it with: pip install "ddg-plane-curves[notebooks] @ git+{unreachable}"' in first
    assert any("ERROR ModuleNotFoundError" in str(outputs) for outputs in cells[1:])

    # the repository is there: one line says so, then the whole chapter runs
    url = f"http://127.0.0.1:{server.server_port}/course.git"
    try:
        cells = outputs_of(python, with_repository(download, work / "b.ipynb", url), work)
    finally:
        server.shutdown()
    assert "".join(cells[0]).strip() == f"Installing ddg from {url} ..."
    assert not [outputs for outputs in cells if "ERROR" in str(outputs)], cells
    assert sum("image/png" in str(outputs) for outputs in cells) >= 2
    assert any("passed" in str(outputs) for outputs in cells)
