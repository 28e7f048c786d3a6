"""Helpers of the journey tests (fixtures in conftest.py): each one does what a student or an instructor does, for real.

They run the repository's own commands (make, pip, jupyter, the browser) in temporary copies
and fresh virtual environments. Nothing leaves loopback: fresh environments install from the
wheelhouse that `make` keeps in .venv/wheelhouse (the pinned wheels a notebook needs).
"""

import os
import pathlib
import shutil
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
VENV = ROOT / ".venv"
WHEELHOUSE = VENV / "wheelhouse"
OFFLINE_PIP = {"PIP_NO_INDEX": "1", "PIP_FIND_LINKS": str(WHEELHOUSE), "PIP_DISABLE_PIP_VERSION_CHECK": "1"}


def user_environment():
    """The environment without what make or pytest set for themselves (PYTHONPATH points at this
    checkout's ddg) and without the variables the Makefile reads (FRESH=1 in `make test`)."""
    return {k: v for k, v in os.environ.items()
            if not k.startswith(("PYTEST", "MAKE", "MFLAGS", "PYTHONPATH")) and k not in ("FRESH", "FORCE", "STUDENT_REPO")}


def run(command, cwd=ROOT, env=None, timeout=600, check=True):
    """Run ``command`` (a list), return the CompletedProcess with stdout and stderr merged."""
    full_env = user_environment()
    full_env.update(env or {})
    result = subprocess.run(command, cwd=cwd, env=full_env, timeout=timeout, text=True,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    if check and result.returncode != 0:
        pytest.fail(f"{' '.join(map(str, command))} failed ({result.returncode}):\n{result.stdout[-4000:]}")
    return result


def copy_repository(destination, with_venv=True):
    """A copy of the working tree (tracked and new files, not what .gitignore ignores).

    With ``with_venv`` the copy shares this repository's .venv through a symlink: same pins, so
    `make` in the copy keeps it (it compares the pins by content).
    """
    listed = subprocess.run(["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                            cwd=ROOT, capture_output=True, check=True).stdout.decode().split("\0")
    for name in filter(None, listed):
        source = ROOT / name
        if source.is_file():
            target = destination / name
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, target)
    if with_venv:
        (destination / ".venv").symlink_to(VENV)
    return destination


def fresh_venv(path):
    """A new virtual environment with nothing installed but pip; returns its python."""
    run([sys.executable, "-m", "venv", str(path)])
    return path / "bin" / "python"


@pytest.fixture(scope="session", autouse=True)
def wheelhouse_present():
    if not any(WHEELHOUSE.glob("numpy-*.whl")):
        pytest.fail(f"no wheelhouse in {WHEELHOUSE}: run `make test` (it creates .venv and the wheelhouse)")
