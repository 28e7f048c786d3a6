"""The environment: ``python3 tools/env.py .venv`` creates it from the pins, or keeps it.

The pins are ``requirements.txt`` (what a notebook needs, also what Binder installs) and
``requirements-build.txt`` (what building the book needs besides: Node). The environment is
rebuilt when their content or ``pyproject.toml``'s changes (a stamp in ``.venv/.installed``), so a
fresh clone or a copy with the same pins keeps it.

They are installed by uv (about 15 s here, against 95 s with pip), or by pip where uv cannot reach
the index (uv does not read pip's configuration, a mirror set there, say). uv compiles the
bytecode as pip does: where ``PYTHONDONTWRITEBYTECODE`` is set, every Python process, each
notebook's kernel among them, would otherwise compile matplotlib & co. again (imports 2.4 s
instead of 0.9 s). Meanwhile, the wheels a notebook needs are downloaded into
``.venv/wheelhouse``, so that the journey tests can install into fresh environments offline.

Standard library only: it runs before the environment exists.
"""

import hashlib
import pathlib
import shutil
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
PINS = ["requirements.txt", "requirements-build.txt", "pyproject.toml"]
UV = "uv==0.13.9"
WHEELS = ["numpy", "matplotlib", "ipywidgets", "shapely", "pillow", "tqdm", "ipython", "ipykernel", "nbclient",
          "setuptools", "wheel"]
QUIET = ["--quiet", "--disable-pip-version-check"]


def stamp():
    """The digest of the pin files: the environment is current while it is unchanged."""
    return hashlib.sha256(b"".join((ROOT / name).read_bytes() for name in PINS)).hexdigest()


def create(venv):
    """A new environment in ``venv`` with the pins installed and the wheelhouse downloaded."""
    shutil.rmtree(venv, ignore_errors=True)
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    pip, python = [str(venv / "bin" / "pip")], str(venv / "bin" / "python")
    constraints = venv / "constraints.txt"
    lines = (ROOT / "requirements.txt").read_text().splitlines()
    constraints.write_text("\n".join(line for line in lines if not line.startswith("-e")) + "\n")
    log = (venv / "wheelhouse.log").open("w")
    download = subprocess.Popen([*pip, "download", *QUIET, "-d", str(venv / "wheelhouse"), "-c", str(constraints),
                                 *WHEELS], stdout=log, stderr=subprocess.STDOUT)
    requirements = ["-r", str(ROOT / "requirements.txt"), "-r", str(ROOT / "requirements-build.txt")]
    uv = subprocess.run([*pip, "install", *QUIET, UV]).returncode == 0 and subprocess.run(
        [str(venv / "bin" / "uv"), "pip", "install", "--quiet", "--compile-bytecode", "--python", python,
         *requirements], cwd=ROOT).returncode == 0
    if not uv:
        print("uv could not install the pins; installing them with pip ...", flush=True)
        subprocess.run([*pip, "install", *QUIET, *requirements], cwd=ROOT, check=True)
    if download.wait() != 0:
        log.close()
        sys.exit((venv / "wheelhouse.log").read_text() + "\nerror: the wheelhouse could not be downloaded")
    subprocess.run([python, "-c", "import matplotlib.pyplot"], check=True)  # its font cache, once


def main(venv):
    if sys.version_info < (3, 11):  # noqa: UP036 (this runs on whatever python3 is, before .venv)
        sys.exit(f"error: {sys.executable} is Python {sys.version.split()[0]}, older than 3.11; "
                 "run: make PYTHON=python3.11 ...")
    venv = ROOT / venv
    marker = venv / ".installed"
    if marker.exists() and marker.read_text().strip() == stamp():
        marker.touch()  # newer than the pins again: make is content
        return
    print(f"setting up {venv.name} from requirements.txt ...", flush=True)
    create(venv)
    marker.write_text(stamp() + "\n")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".venv")
