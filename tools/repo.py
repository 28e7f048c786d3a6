"""One place names the course repository: `make repo URL=https://github.com/owner/name`.

The URL appears in `_config.yml` (`repository.url`: the launch buttons for Binder and Colab and
the repository button) and in the first cell of every notebook (where `ddg` is missing, that cell
installs it from the repository). This tool writes the URL into all of them at once.

    python tools/repo.py URL          point everything at URL
    python tools/repo.py --from-git   use `git remote get-url origin`, if that is a GitHub repository
    python tools/repo.py --check      exit 1 if a notebook disagrees with _config.yml
"""

import json
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
from tools import config as yaml_config  # noqa: E402  (ruamel.yaml: _config.yml keeps its comments)

CONFIG = ROOT / "_config.yml"
SETUP = re.compile(r'^(REPOSITORY = )"([^"]*)"', re.MULTILINE)  # in each notebook's first code cell
GITHUB = re.compile(r"^(?:https://github\.com/|git@github\.com:|ssh://git@github\.com/)([\w.-]+/[\w.-]+?)(?:\.git)?/?$")


def configured():
    return yaml_config.repository(yaml_config.load(CONFIG))


def notebooks():
    return sorted((ROOT / "book").glob("*.ipynb"))


def setup_url(path):
    """The URL in the notebook's set-up cell (its first code cell), or None."""
    cells = json.loads(path.read_text())["cells"]
    first = next((c for c in cells if c["cell_type"] == "code"), None)
    match = first and SETUP.search("".join(first["source"]))
    return match.group(2) if match else None


def github_url(url):
    """``https://github.com/owner/name`` for any spelling of a GitHub remote, else None."""
    match = GITHUB.match(url.strip())
    return f"https://github.com/{match.group(1)}" if match else None


def pages_address(url):
    """Where GitHub Pages serves the gh-pages branch of ``url``, if it is a GitHub repository."""
    github = github_url(url or "")
    if not github:
        return None
    owner, name = github.removeprefix("https://github.com/").split("/")
    return f"https://{owner.lower()}.github.io/{name}/"


def https_url(url, what="the repository"):
    """``url`` as the launch buttons need it, ``https://github.com/owner/name`` for any spelling of a
    GitHub remote (ssh, a trailing .git); anything but an https address is refused, saying what to give."""
    url = github_url(url) or url.strip().rstrip("/")
    if not re.match(r"^https://\S+$", url) or url.endswith(".git"):
        sys.exit(f"error: {what} {url!r}: give the repository's address, https://github.com/owner/name")
    return url


def set_url(url):
    url = https_url(url)
    try:
        CONFIG.write_text(yaml_config.dump(yaml_config.set_repository(yaml_config.load(CONFIG), url)))
    except KeyError as error:
        sys.exit(f"error: {error.args[0]}")
    for path in notebooks():
        data = json.loads(path.read_text())
        first = next(c for c in data["cells"] if c["cell_type"] == "code")
        source = "".join(first["source"])
        if not SETUP.search(source):
            sys.exit(f"error: the first code cell of {path.name} has no `REPOSITORY = \"...\"` line")
        first["source"] = SETUP.sub(lambda m: f'{m.group(1)}"{url}"', source).splitlines(keepends=True)
        path.write_text(json.dumps(data, indent=1, ensure_ascii=False) + "\n")
    print(f"repository: {url} (_config.yml and {len(notebooks())} notebooks)")


def main(argv):
    if argv == ["--check"]:
        url = configured()
        wrong = [p.name for p in notebooks() if setup_url(p) != url]
        if wrong:
            sys.exit(f"error: these notebooks do not install from {url}: {', '.join(wrong)}; run `make repo URL={url}`")
        return
    if argv == ["--from-git"]:
        origin = subprocess.run(["git", "remote", "get-url", "origin"], cwd=ROOT, capture_output=True, text=True)
        url = github_url(origin.stdout) if origin.returncode == 0 else None
        if url and url != configured():
            set_url(url)
        return
    if len(argv) != 1 or argv[0].startswith("-"):
        sys.exit(__doc__)
    set_url(argv[0])


if __name__ == "__main__":
    main(sys.argv[1:])
