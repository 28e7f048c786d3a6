"""Fixtures of the journey tests (journey_helpers.py)."""

from journey_helpers import wheelhouse_present  # noqa: F401
