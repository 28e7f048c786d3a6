"""Build the book, the strict build, the student edition or the PDFs: ``python tools/build.py WHAT``.

``book``
    The book in ``_build/html``. Sphinx re-reads only pages whose source changed and the notebook
    cache knows only code cells, so when what the pages are computed from changed since the last
    build (:func:`inputs`: Python, ``ddg/``, the pins, ``_config.yml``), the cache and Sphinx's
    state are dropped: every notebook runs again and every page is rebuilt. When only what every
    page carries changed (:func:`assets`: the book's stylesheet, scripts and Sphinx extensions,
    the pinned MathJax), every page is written again from the cached outputs.
``strict``
    What ``make test`` gates on: every notebook executed again and every page re-read, whatever
    was built before; any warning, stray stderr or failing cell fails it.
``student [--fresh] [--force] [--student-repo URL]``
    The student edition (``python -m instructor.edition``) in ``_build/student``, executed and
    built like the book into ``_build/student/html``. The outputs of the last edition's notebooks
    are kept while :func:`inputs` is unchanged, so only notebooks whose code changed run again;
    ``--fresh`` runs them all. Then the leak guard (``instructor/guard.py``): if any function of the
    edition passes an exercise's hidden check, the site is removed and the step fails, naming it.
``pdf``
    Both editions printed by Chromium (``tools/pdf.py``), side by side: ``_build/pdf``; the book is
    built first where missing, the student edition again where it is older than the book.

Each step says in one line what it does again and why.
"""

import argparse
import hashlib
import pathlib
import shutil
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
BUILD = ROOT / "_build"
BIN = pathlib.Path(sys.executable).parent
JB = str(BIN / "jupyter-book")


def digest(paths, extra=b""):
    """SHA-256 of ``extra`` and of the files' names and contents, in a stable order."""
    h = hashlib.sha256(extra)
    for path in sorted(paths):
        h.update(str(path.relative_to(ROOT)).encode() + b"\0" + path.read_bytes())
    return h.hexdigest()


def inputs():
    """What the pages are computed from: a change means every notebook must run again."""
    files = [*(ROOT / "ddg").rglob("*.py"), *(ROOT / name for name in
                                             ("requirements.txt", "pyproject.toml", "_config.yml"))]
    return digest(files, sys.version.encode())


def assets():
    """What every page carries but Sphinx does not watch."""
    files = [p for p in (ROOT / "book" / "_assets").rglob("*") if p.is_file()]
    return digest([*files, *(ROOT / "tools").glob("sphinx_*.py"), ROOT / "tools" / "vendor.py"])


def stamped(folder, name):
    path = folder / f".{name}"
    return path.read_text().strip() if path.exists() else None


def stamp(folder, **values):
    folder.mkdir(parents=True, exist_ok=True)
    for name, value in values.items():
        (folder / f".{name}").write_text(value + "\n")


def run(*command, cwd=ROOT):
    if subprocess.run([str(c) for c in command], cwd=cwd).returncode != 0:
        sys.exit(1)


def book():
    now = {"inputs": inputs(), "assets": assets()}
    built = (BUILD / ".doctrees").exists()
    if stamped(BUILD, "inputs") != now["inputs"]:
        if built:
            print("ddg/, the pins or _config.yml changed: every notebook runs again", flush=True)
        for name in (".jupyter_cache", ".doctrees", "html"):
            shutil.rmtree(BUILD / name, ignore_errors=True)
    elif stamped(BUILD, "assets") != now["assets"]:
        if built:
            print("book/_assets or tools/sphinx_*.py changed: every page is written again", flush=True)
        for name in (".doctrees", "html"):
            shutil.rmtree(BUILD / name, ignore_errors=True)
    run(JB, "build", ".")
    stamp(BUILD, **now)
    print(f"The book is in {BUILD / 'html'}; to read it: python3 -m http.server -d {BUILD / 'html'} "
          "and open http://localhost:8000 (opened as a file, its formulas lose their fonts)")


def strict():
    now = {"inputs": inputs(), "assets": assets()}
    shutil.rmtree(BUILD / ".jupyter_cache", ignore_errors=True)
    run(JB, "build", ".", "--all", "-W", "-n", "--keep-going")
    stamp(BUILD, **now)


def student(fresh=False, force=False, student_repo=None):
    out = ROOT / "_build" / "student"
    cache, kept = out / "_build" / ".jupyter_cache", BUILD / ".student-cache"
    shutil.rmtree(kept, ignore_errors=True)
    passed = stamped(out / "_build", "guarded")  # what the leak guard last passed (the edition is written afresh)
    now = inputs()
    if not fresh and cache.is_dir() and stamped(out / "_build", "inputs") == now:
        shutil.move(cache, kept)  # the edition writes _build/student afresh: the outputs wait aside
    command = [sys.executable, "-m", "instructor.edition", "--out", out, "--vendor", BIN.parent / "vendor"]
    command += ["--force"] * force + (["--student-repo", student_repo] if student_repo else [])
    finished = subprocess.run([str(c) for c in command], cwd=ROOT).returncode == 0
    if kept.is_dir():
        (out / "_build").mkdir(parents=True, exist_ok=True)
        shutil.move(kept, cache)
    if not finished:
        sys.exit(1)
    stamp(out / "_build", inputs=now, assets=assets())
    print("ddg/, the pins and _config.yml unchanged: only notebooks whose code changed run again"
          if cache.is_dir() else "every notebook of the student edition runs", flush=True)
    run(JB, "build", out, "-W", "-n", "--keep-going")
    shutil.rmtree(out / "html", ignore_errors=True)
    shutil.move(out / "_build" / "html", out / "html")
    # the leak guard, again whenever the edition, its ddg, its site's scripts or the answer key changed
    guarded = digest([*sorted((out / "book").glob("*.ipynb")), *sorted((out / "ddg").rglob("*.py")),
                      *sorted((out / "html" / "_static").glob("ddg-*.js")), *sorted((ROOT / "instructor").glob("*.py"))])
    if passed == guarded:
        print("leak guard: the edition is as it was when the guard last passed it", flush=True)
    elif subprocess.run([sys.executable, "-m", "instructor.guard", str(out)], cwd=ROOT).returncode != 0:
        shutil.rmtree(out / "html")  # nothing to publish
        sys.exit("make student: the student edition was not finished (its site removed): see above")
    else:
        stamp(out / "_build", guarded=guarded)
    print(f"The student site is in {out / 'html'}; to read it: python3 -m http.server -d {out / 'html'}")


def student_is_current():
    """Whether the student site was built from the book as it is: the same inputs and page assets
    (book/_assets, the Sphinx extensions), and no chapter, page or configuration changed since."""
    site = BUILD / "student" / "html" / "index.html"
    stamps = BUILD / "student" / "_build"
    if not site.exists() or stamped(stamps, "inputs") != inputs() or stamped(stamps, "assets") != assets():
        return False
    sources = [*(ROOT / "book").iterdir(), ROOT / "_toc.yml", ROOT / "_config.yml"]
    return all(path.stat().st_mtime <= site.stat().st_mtime for path in sources if path.is_file())


def pdf():
    if not (BUILD / "html" / "index.html").exists():
        book()
    if (BUILD / "student" / "html").exists() and not student_is_current():
        print("the student edition is older than the book: it is built again first", flush=True)
        student()
    jobs = [[sys.executable, "tools/pdf.py", "_build/html", "_build/pdf"]]
    if (BUILD / "student" / "html" / "index.html").exists():
        jobs.append([sys.executable, "tools/pdf.py", "_build/student/html", "_build/pdf/student"])
    running = [subprocess.Popen(job, cwd=ROOT) for job in jobs]
    if any([process.wait() != 0 for process in running]):  # every one waited for
        sys.exit(1)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("what", choices=["book", "strict", "student", "pdf"])
    parser.add_argument("--fresh", action="store_true", help="student: run every notebook again")
    parser.add_argument("--force", action="store_true", help="student: overwrite students' changed notebooks")
    parser.add_argument("--student-repo", help="student: the repository the launch buttons open")
    args = parser.parse_args(argv)
    if args.what == "student":
        sys.path.insert(0, str(ROOT))
        from tools.repo import https_url  # an ssh remote or a trailing .git would break the launch buttons

        student(args.fresh, args.force, args.student_repo and https_url(args.student_repo, "STUDENT_REPO"))
    else:
        {"book": book, "strict": strict, "pdf": pdf}[args.what]()


if __name__ == "__main__":
    main()
