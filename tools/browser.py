"""Find the Chromium that the browser tests and `make pdf` drive, or install one.

    python tools/browser.py            print the path of a usable Chromium, installing one if needed
    python tools/browser.py --no-install   only look

Where it looks, in order: the CHROMIUM environment variable; `chromium`, `chromium-browser`,
`google-chrome` and `chrome` on PATH; the usual macOS application paths; a browser that
Playwright installed itself (`playwright install chromium`). What it installs when none is found:
Debian's `chromium` with apt-get when run as root on a Debian-like system, otherwise Playwright's
own build. When neither works it prints one line saying what to install and exits with status 1.
Uses the standard library only (Playwright is needed only to install its own browser).
"""

import glob
import os
import shutil
import subprocess
import sys

NAMES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable", "chrome")
MACOS = (
    "/Applications/Chromium.app/Contents/MacOS/Chromium",
    "/Applications/Google Chrome.app/Contents/MacOS/Google Chrome",
)
HELP = (
    "no Chromium found and none could be installed: install Debian's chromium "
    "(sudo apt-get install chromium), or run `.venv/bin/python -m playwright install chromium`, "
    "or set CHROMIUM=/path/to/chromium"
)


def _playwright_browsers():
    """Chromium builds that `playwright install chromium` left in its cache, newest first."""
    roots = [os.environ.get("PLAYWRIGHT_BROWSERS_PATH")]
    home = os.path.expanduser("~")
    roots += [os.path.join(home, ".cache", "ms-playwright"), os.path.join(home, "Library", "Caches", "ms-playwright")]
    patterns = ("chromium-*/chrome-linux*/chrome", "chromium-*/chrome-mac*/*.app/Contents/MacOS/*")
    found = []
    for root in filter(None, roots):
        for pattern in patterns:
            found += sorted(glob.glob(os.path.join(root, pattern)), reverse=True)
    return found


def find():
    """The path of a Chromium-family browser that can be started, or None."""
    candidates = [os.environ.get("CHROMIUM")]
    candidates += [shutil.which(name) for name in NAMES]
    candidates += [path for path in MACOS if sys.platform == "darwin"]
    candidates += _playwright_browsers()
    for path in filter(None, candidates):
        if os.path.isfile(path) and os.access(path, os.X_OK):
            return path
    return None


def install():
    """Try to install a browser; say what is being done on stderr. Returns whether a command ran."""
    is_root = hasattr(os, "geteuid") and os.geteuid() == 0
    if is_root and shutil.which("apt-get"):
        print("installing Debian's chromium with apt-get ...", file=sys.stderr)
        env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
        commands = [["apt-get", "update", "-qq"], ["apt-get", "install", "-y", "-qq", "chromium"]]
        return all(subprocess.run(c, env=env, stdout=subprocess.DEVNULL).returncode == 0 for c in commands)
    try:
        import playwright  # noqa: F401  (only to see whether it is installed)
    except ImportError:
        return False
    print("installing Playwright's own Chromium (playwright install chromium) ...", file=sys.stderr)
    command = [sys.executable, "-m", "playwright", "install", "chromium"]
    return subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode == 0


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    path = find()
    if path is None and "--no-install" not in argv and not os.environ.get("DDG_NO_BROWSER_INSTALL"):
        install()
        path = find()
    if path is None:
        print(f"error: {HELP}", file=sys.stderr)
        return 1
    print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
