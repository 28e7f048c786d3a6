"""Fixtures of the browser tests: a loopback server per site, one Chromium (browser_helpers.py)."""

from browser_helpers import browser, servers  # noqa: F401
