"""Journey: `make test` on a machine without a browser says what to install, at once."""

import os
import shutil
import sys
import time

import pytest
from journey_helpers import ROOT, run


def test_without_a_browser_the_first_step_says_what_to_install(tmp_path):
    if not shutil.which("unshare") or os.geteuid() != 0:
        pytest.skip("needs `unshare --net` (root) to cut the network so that no browser can be downloaded")
    empty = tmp_path / "bin"
    empty.mkdir()
    env = {"PATH": str(empty), "HOME": str(tmp_path), "PLAYWRIGHT_BROWSERS_PATH": str(tmp_path / "pw"), "CHROMIUM": ""}
    start = time.monotonic()
    # no browser on PATH, none in Playwright's cache, no apt-get, no network to download one
    result = run([shutil.which("unshare"), "--net", sys.executable, str(ROOT / "tools" / "browser.py")],
                 env=env, check=False, timeout=120)
    elapsed = time.monotonic() - start
    assert result.returncode == 1
    lines = [line for line in result.stdout.splitlines() if line.startswith("error:")]
    assert len(lines) == 1 and "apt-get install chromium" in lines[0] and "playwright install chromium" in lines[0], result.stdout
    assert elapsed < 30, f"it took {elapsed:.0f} s to give up"


def test_a_browser_is_found_where_the_user_has_one(tmp_path):
    fake = tmp_path / "bin" / "chromium"
    fake.parent.mkdir()
    fake.write_text("#!/bin/sh\n")
    fake.chmod(0o755)
    result = run([sys.executable, str(ROOT / "tools" / "browser.py"), "--no-install"],
                 env={"PATH": str(fake.parent), "CHROMIUM": ""}, check=False)
    assert result.stdout.strip() == str(fake)
    result = run([sys.executable, str(ROOT / "tools" / "browser.py"), "--no-install"],
                 env={"PATH": str(fake.parent), "CHROMIUM": "/nowhere/chrome"}, check=False)
    assert result.stdout.strip() == str(fake)  # a CHROMIUM that does not exist is skipped
