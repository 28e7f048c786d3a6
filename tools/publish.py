"""Put the book, or the student edition, online: `make publish`, `make publish-student`.

    python tools/publish.py book [--remote REMOTE]
        _build/html onto the gh-pages branch of REMOTE (default: origin; a remote's name, a URL or a
        path), with a .nojekyll file, by ghp-import. GitHub Pages then serves it (Settings, Pages,
        Deploy from a branch: gh-pages) at https://OWNER.github.io/NAME/.

    python tools/publish.py student --repo URL [--remote REMOTE]
        The student edition of `make student` (_build/student) into the student repository: its
        files (not html/ or _build/) as a new commit on main, and its site (_build/student/html) onto
        gh-pages. REMOTE is where to push (default: URL; with STUDENT_REPO_TOKEN in the environment,
        the GitHub URL with that token). Files of the student repository that no edition wrote (a
        note the course team added there) are kept; files an earlier edition wrote and this one does
        not are deleted.

Both refresh the site's service worker first (tools/sphinx_offline.py), so that readers who saved
the book offline get this build on their next visit.
"""

import argparse
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
from tools.repo import https_url, pages_address  # noqa: E402
from tools.sphinx_offline import write_service_worker  # noqa: E402

GHP_IMPORT = pathlib.Path(sys.executable).parent / "ghp-import"
WRITTEN = ".edition-files"  # in the student repository: what the last edition wrote there
LEFT_OUT = ("html", "_build")  # of _build/student: its site (published on gh-pages) and its build


def identity():
    """``-c user.name=... -c user.email=...``: yours where git knows you, else "ddg publish"."""
    known = git("config", "user.email", cwd=ROOT, check=False, capture=True).stdout.strip()
    return [] if known else ["-c", "user.name=ddg publish", "-c", "user.email=publish@localhost"]


def built_from():
    """Which commit of the course repository this is, and whether its work tree had changes."""
    commit = git("rev-parse", "--short", "HEAD", cwd=ROOT, check=False, capture=True).stdout.strip() or "no commit"
    dirty = git("status", "--porcelain", "--untracked-files=no", cwd=ROOT, check=False, capture=True).stdout.strip()
    return f"from {commit}" + (" with uncommitted changes" if dirty else "")


def git(*args, cwd, check=True, capture=False):
    result = subprocess.run(["git", *args], cwd=cwd, text=True, capture_output=capture)
    if check and result.returncode != 0:
        sys.exit(f"error: git {' '.join(args)} failed{': ' + result.stderr.strip() if capture else ''}")
    return result


def site_onto_pages(site, remote, message):
    """``site`` as a new commit on the gh-pages branch of ``remote`` (a URL or a path), after the
    branch's last one, made in a scratch repository (the course repository's branches stay as they
    are)."""
    site = pathlib.Path(site)
    if not (site / "index.html").exists():
        sys.exit(f"error: {site} holds no built site (index.html); build it first")
    version = write_service_worker(site)
    with tempfile.TemporaryDirectory() as scratch:
        git("init", "-q", cwd=scratch)
        git("remote", "add", "target", remote, cwd=scratch)
        git("fetch", "-q", "--depth=1", "target", "gh-pages:refs/remotes/target/gh-pages", cwd=scratch, check=False,
            capture=True)  # none yet: the first publication
        env = dict(os.environ)
        if identity():  # ghp-import commits with git's identity: there is none on a fresh machine
            env.update(GIT_AUTHOR_NAME="ddg publish", GIT_AUTHOR_EMAIL="publish@localhost",
                       GIT_COMMITTER_NAME="ddg publish", GIT_COMMITTER_EMAIL="publish@localhost")
        command = [str(GHP_IMPORT), "--no-jekyll", "--remote", "target", "--branch", "gh-pages",
                   "--message", f"{message}, {built_from()} (build {version})", str(site.resolve())]
        if subprocess.run(command, cwd=scratch, env=env).returncode != 0:
            sys.exit(f"error: could not commit {site} for the gh-pages branch of {safe(remote)}")
        tree = lambda ref: git("rev-parse", "-q", "--verify", f"{ref}^{{tree}}", cwd=scratch, check=False,  # noqa: E731
                               capture=True).stdout.strip()
        if tree("gh-pages") == tree("refs/remotes/target/gh-pages"):
            print(f"the gh-pages branch of {safe(remote)} already holds this site (build {version})")
        elif git("push", "-q", "--force", "target", "gh-pages", cwd=scratch, check=False).returncode != 0:
            sys.exit(f"error: could not push {site} to the gh-pages branch of {safe(remote)}")
    return version


def url_of(remote):
    """A remote's URL: ``remote`` itself, unless it names a remote of the course repository."""
    named = git("remote", "get-url", remote, cwd=ROOT, check=False, capture=True)
    if named.returncode == 0:
        return named.stdout.strip()
    if "/" in remote or ":" in remote:
        return remote
    sys.exit(f"error: the course repository has no remote {remote!r}; give REMOTE=URL (or a path)")


def next_step(url):
    address = pages_address(url)
    where = f" to serve it at {address}" if address else ""
    print(f"once, on GitHub: Settings > Pages > Deploy from a branch > gh-pages{where}")


def publish_book(remote):
    url = url_of(remote)
    version = site_onto_pages(ROOT / "_build" / "html", url, "The book, published by make publish")
    print(f"published: _build/html (build {version}) on the gh-pages branch of {safe(remote)}")
    next_step(url)


def edition_files(edition):
    """The student edition's files (relative paths) that go into the student repository."""
    return sorted(p.relative_to(edition).as_posix() for p in edition.rglob("*") if p.is_file()
                  and p.relative_to(edition).parts[0] not in LEFT_OUT and "__pycache__" not in p.parts)


def publish_student(repo, remote):
    edition = ROOT / "_build" / "student"
    if not (edition / "html" / "index.html").exists():
        sys.exit("error: no student edition in _build/student; run `make student STUDENT_REPO=...` first")
    with tempfile.TemporaryDirectory() as scratch:
        work = pathlib.Path(scratch) / "student"
        files = edition_files(edition)
        if git("clone", "-q", remote, str(work), cwd=scratch, check=False, capture=True).returncode != 0:
            sys.exit(f"error: cannot clone {safe(remote)}, where the student edition goes: does the repository "
                     "exist, and may you write to it (with GitHub Actions: the secret STUDENT_REPO_TOKEN)?")
        # the edition goes on main, after its last commit (whatever the repository's default branch)
        if git("ls-remote", "--exit-code", "--heads", "origin", "main", cwd=work, check=False, capture=True).returncode == 0:
            git("checkout", "-q", "-B", "main", "origin/main", cwd=work)
        else:  # an empty repository, or one without main (what its default branch holds is kept): main begins
            git("checkout", "-q", "--orphan", "main", cwd=work)
        before = (work / WRITTEN).read_text().split("\n") if (work / WRITTEN).exists() else []
        for name in set(before) - set(files) - {""}:  # what the last edition wrote and this one does not
            (work / name).unlink(missing_ok=True)
        for name in files:
            (work / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(edition / name, work / name)
        (work / WRITTEN).write_text("\n".join(files) + "\n")
        git("add", "-A", cwd=work)
        if git("diff", "--cached", "--quiet", cwd=work, check=False).returncode:
            git(*identity(), "commit", "-q", "-m", f"The student edition, published by make publish-student, {built_from()}",
                cwd=work)
            git("push", "-q", "origin", "HEAD:main", cwd=work)
            print(f"published: {len(files)} files of the student edition on main of {safe(remote)}")
        else:
            print(f"the student repository ({safe(remote)}) already holds this edition")
    version = site_onto_pages(edition / "html", remote, "The student site, published by make publish-student")
    print(f"published: the student site (build {version}) on the gh-pages branch of {safe(remote)}")
    next_step(repo)


def reachable(remote):
    """Exit with a clear error, before anything is built, if ``remote`` cannot be read."""
    result = git("ls-remote", "--heads", remote, cwd=ROOT, check=False, capture=True)
    if result.returncode != 0:
        reason = (result.stderr.strip().splitlines() or ["no answer"])[0].removeprefix("fatal: ")
        sys.exit(f"error: cannot reach {safe(remote)}, where this would be published ({safe(reason)}); "
                 "nothing was built or pushed")


def safe(url):
    """``url`` without a token in it, to print."""
    token = os.environ.get("STUDENT_REPO_TOKEN")
    return url.replace(token, "***") if token else url


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("what", choices=["book", "student"])
    parser.add_argument("--remote", help="where to push: a remote's name, a URL or a path")
    parser.add_argument("--repo", help="student: the student repository's URL (https://github.com/owner/name)")
    parser.add_argument("--check", action="store_true", help="only check that the remote can be reached (before a build)")
    args = parser.parse_args(argv)
    if args.what == "book":
        if args.check:
            reachable(url_of(args.remote or "origin"))
        else:
            publish_book(args.remote or "origin")
        return
    if not args.repo:
        parser.error("student: --repo URL is needed (make publish-student STUDENT_REPO=URL)")
    args.repo = https_url(args.repo, "STUDENT_REPO")
    remote = args.remote
    token = os.environ.get("STUDENT_REPO_TOKEN")
    if not remote and token and args.repo.startswith("https://github.com/"):
        remote = f"https://x-access-token:{token}@github.com/{args.repo.removeprefix('https://github.com/')}.git"
    if args.check:
        reachable(remote or args.repo)
    else:
        publish_student(args.repo, remote or args.repo)


if __name__ == "__main__":
    main()
