"""Shared by every test: the repository root is importable (for tools/)."""

import os
import pathlib
import sys

import pytest
from hypothesis import settings

# make test draws the same hypothesis examples on every run, so CI cannot fail on a case found by
# chance; HYPOTHESIS_PROFILE=explore draws new ones (a case it finds is then kept as an @example).
settings.register_profile("make-test", derandomize=True, database=None)
settings.register_profile("explore", derandomize=False)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "make-test"))

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--disable-background-networking",
         "--disable-component-update", "--disable-sync"]
"""Chromium's flags for tests: no sandbox (root), nothing that would reach the network by itself."""


@pytest.fixture(scope="session")
def browser():
    """One Chromium for the whole session (Playwright's sync API allows one per thread)."""
    sync_api = pytest.importorskip("playwright.sync_api")
    from tools.browser import find as find_chromium

    chromium = find_chromium()
    if chromium is None:
        pytest.fail("no Chromium: run `make test`, whose first step finds or installs one")
    with sync_api.sync_playwright() as p:
        launched = p.chromium.launch(executable_path=chromium, args=FLAGS)
        yield launched
        launched.close()
