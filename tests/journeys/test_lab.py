"""Journey: open a chapter in JupyterLab, see it rendered like the book, run it.

The real JupyterLab from .venv (with jupyterlab-myst) serves a copy of the notebooks on
127.0.0.1, and Chromium opens a chapter with the network cut. An exercise must render as an
exercise, its solution folded, and after "Run All Cells" the notebook must show a figure and
no error. The server is stopped by its process group, whatever happens.
"""

import json
import os
import re
import secrets
import shutil
import signal
import socket
import subprocess
import time
import urllib.error
import urllib.request

import pytest
from journey_helpers import ROOT, VENV


CHAPTER = "02_discrete_curves.ipynb"
# JupyterLab settings for a test: every cell rendered (no windowing), no news or update checks
SETTINGS = {
    "@jupyterlab/notebook-extension/tracker.jupyterlab-settings": {"windowingMode": "none"},
    "@jupyterlab/apputils-extension/notification.jupyterlab-settings": {"fetchNews": "false", "checkForUpdates": False},
}


# the execution count of every code cell of the open notebook (the app is exposed for tests)
COUNTS = """() => {
    const cells = window.jupyterapp.shell.currentWidget.content.model.cells;
    const counts = [];
    for (let i = 0; i < cells.length; i++) {
        const cell = cells.get(i);
        if (cell.type === "code") counts.push(cell.executionCount);
    }
    return counts;
}"""


def stop(server):
    """End a server and everything it started (its process group)."""
    os.killpg(server.pid, signal.SIGTERM)
    try:
        server.wait(timeout=20)
    except subprocess.TimeoutExpired:
        os.killpg(server.pid, signal.SIGKILL)


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture
def lab(tmp_path):
    """JupyterLab on a copy of book/: yields (url, token); stops the server afterwards."""
    notebooks = tmp_path / "book"
    shutil.copytree(ROOT / "book", notebooks)
    for name, values in SETTINGS.items():
        path = tmp_path / "settings" / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(values))
    port, token = free_port(), secrets.token_hex(16)
    command = [str(VENV / "bin" / "jupyter"), "lab", "--no-browser", "--ip=127.0.0.1", f"--port={port}",
               "--ServerApp.port_retries=0", f"--IdentityProvider.token={token}", f"--notebook-dir={notebooks}",
               "--LabApp.news_url=None", "--LabApp.expose_app_in_browser=True", "--LabApp.check_for_updates_class=jupyterlab.NeverCheckForUpdate"]
    if hasattr(os, "geteuid") and os.geteuid() == 0:
        command.append("--allow-root")
    env = dict(os.environ, JUPYTERLAB_SETTINGS_DIR=str(tmp_path / "settings"), PYTHONPATH=str(ROOT),
               JUPYTERLAB_WORKSPACES_DIR=str(tmp_path / "workspaces"),
               JUPYTER_RUNTIME_DIR=str(tmp_path / "runtime"))
    log = open(tmp_path / "lab.log", "w")
    server = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT, env=env, start_new_session=True)
    url = f"http://127.0.0.1:{port}"
    try:
        deadline = time.monotonic() + 60
        while True:
            try:
                urllib.request.urlopen(f"{url}/api/status?token={token}", timeout=2)
                break
            except OSError:
                if server.poll() is not None or time.monotonic() > deadline:
                    pytest.fail(f"JupyterLab did not start:\n{(tmp_path / 'lab.log').read_text()[-3000:]}")
                time.sleep(0.5)
        yield url, token
    finally:
        stop(server)
        log.close()


def test_chapter_renders_like_the_book_and_runs_in_jupyterlab(lab, browser):
    url, token = lab
    outside = []
    context = browser.new_context(viewport={"width": 1280, "height": 900})
    try:
        page = context.new_page()

        def route(r):
            if r.request.url.startswith(url) or r.request.url.startswith(("data:", "blob:")):
                r.continue_()
            else:
                outside.append(r.request.url)
                r.abort()

        page.route("**/*", route)
        page.goto(f"{url}/lab/tree/{CHAPTER}?token={token}")
        page.wait_for_selector(".jp-Notebook .myst", timeout=60000)

        # the exercise renders as an exercise (MyST), not as raw ```{exercise} markup
        exercise = page.locator("aside.myst-exercise", has_text="Staircases around an ellipse")
        exercise.wait_for(timeout=30000)
        assert "Exercise 1" in exercise.inner_text()
        assert "{exercise}" not in page.locator(".jp-Notebook").first.inner_text()
        # its solution is folded: a closed dropdown, and the solution's code cells collapsed
        solution = page.locator("details.myst-exercise", has_text="Solution to").first
        assert solution.get_attribute("open") is None
        assert not solution.get_by_text("monotone pieces").is_visible()
        assert page.locator(".jp-InputPlaceholder", has_text="def staircase").count() == 1
        assert not page.get_by_text("farther = np.linalg.norm").first.is_visible()  # its body

        # run it: Run > Run All Cells, then wait until every code cell has an execution count
        page.locator(".jp-Notebook").first.click(position={"x": 5, "y": 5})
        page.get_by_role("menuitem", name="Run", exact=True).click()
        page.get_by_role("menuitem", name="Run All Cells", exact=True).click()
        deadline = time.monotonic() + 120
        while True:
            counts = page.evaluate(COUNTS)
            if counts and all(c is not None for c in counts):
                break
            assert time.monotonic() < deadline, f"the notebook did not finish running: execution counts {counts}"
            page.wait_for_timeout(500)
        errors = page.locator(".jp-OutputArea-output[data-mime-type='application/vnd.jupyter.stderr']")
        assert errors.count() == 0, errors.all_inner_texts()[:3]
        assert page.locator(".jp-RenderedImage img").count() >= 2  # the chapter's figures
        checks = page.locator(".jp-OutputArea-output", has_text="passed")
        assert checks.count() >= 2  # the checks ran, inside the folded solutions
        # JupyterLab shows a cell's output once it runs (CodeCell.execute sets outputHidden = false):
        # the verdicts show, the solutions' code stays folded
        assert not page.get_by_text("farther = np.linalg.norm").first.is_visible()
        assert page.locator(".jp-InputPlaceholder", has_text="def staircase").count() == 1
        page.screenshot(path=str(ROOT / "_build" / "lab-journey.png"))
    finally:
        context.close()
    assert not outside, f"JupyterLab requested outside loopback: {outside[:5]}"


def test_make_lab_starts_jupyterlab_on_the_notebooks_and_prints_its_url(tmp_path):
    """`make lab`, the README's command: it must print a URL that opens JupyterLab on book/."""
    env = dict(os.environ, BROWSER="true", JUPYTER_RUNTIME_DIR=str(tmp_path / "runtime"))  # no browser window
    for name in ("MAKEFLAGS", "MAKELEVEL", "MFLAGS"):
        env.pop(name, None)
    server = subprocess.Popen(["make", "lab"], cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              text=True, start_new_session=True)
    lines = []
    try:
        deadline = time.monotonic() + 60
        url = None
        while url is None and time.monotonic() < deadline and server.poll() is None:
            line = server.stdout.readline()
            lines.append(line)
            match = re.search(r"(http://127\.0\.0\.1:\d+/lab\?token=\w+)", line)
            url = match and match.group(1)
        assert url, "make lab printed no URL:\n" + "".join(lines)
        for _ in range(40):  # the URL is printed a moment before the server accepts connections
            try:
                page = urllib.request.urlopen(url, timeout=10).read()
                break
            except ConnectionRefusedError:
                time.sleep(0.25)
            except urllib.error.URLError as error:
                if not isinstance(error.reason, ConnectionRefusedError):
                    raise
                time.sleep(0.25)
        assert b"JupyterLab" in page
        contents = json.loads(urllib.request.urlopen(url.replace("/lab?", "/api/contents?"), timeout=10).read())
        assert CHAPTER in {item["name"] for item in contents["content"]}  # it serves book/
    finally:
        stop(server)
