"""Read and change `_config.yml` as YAML (ruamel.yaml's round trip), keeping its comments and layout.

`tools/repo.py` (the course repository) and `instructor/edition.py` (the student edition's
configuration) change the book's configuration through these few functions, never by editing
its text.
"""

import io
import pathlib

from ruamel.yaml import YAML


def _yaml():
    yaml = YAML()  # round trip: comments, key order, quotes and flow lists stay as written
    yaml.preserve_quotes = True
    yaml.width = 4096  # never fold a long line
    return yaml


def load(text):
    """The configuration in ``text`` (a str or a path), as a mapping that remembers its comments."""
    if isinstance(text, pathlib.Path):
        text = text.read_text()
    return _yaml().load(text)


def dump(config):
    """The text of ``config``: what was not changed reads as it did, comments included."""
    out = io.StringIO()
    _yaml().dump(config, out)
    return out.getvalue()


def set_repository(config, url):
    """Point the launch buttons and the repository button at ``url``."""
    if not isinstance(config.get("repository"), dict) or "url" not in config["repository"]:
        raise KeyError("_config.yml has no `repository: url:` entry to set")
    config["repository"]["url"] = url
    return config


def repository(config):
    """The repository the launch buttons point at, or None."""
    return (config.get("repository") or {}).get("url")
