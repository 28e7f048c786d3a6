"""Fixtures of the browser tests: a loopback server per site (browser_helpers.py); the browser
itself is the session's (tests/conftest.py)."""

from browser_helpers import servers  # noqa: F401
