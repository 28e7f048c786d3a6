"""Optional dependencies: the geometry needs numpy only; drawing, widgets and tools need more.

Each optional part of ``ddg`` belongs to an *extra* of the distribution ``ddg-plane-curves``
(see ``pyproject.toml``). When a part is used without its extra, :func:`missing` makes the
``ImportError`` say which command installs it.
"""

DISTRIBUTION = "ddg-plane-curves"


def missing(extra, error):
    """An ``ImportError`` that names the package that is missing and the extra that brings it."""
    return ImportError(
        f"{error.name or 'a package'} is not installed; this part of ddg needs the extra "
        f'[{extra}]: pip install "{DISTRIBUTION}[{extra}]"',
        name=error.name,
    )
