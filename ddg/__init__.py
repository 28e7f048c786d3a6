"""ddg: discrete differential geometry of plane curves, after Vouga's lecture *Plane Curves*.

A small reference implementation to read next to the lecture. It needs numpy only; plotting
(``ddg.plot``), the explorers (``ddg.explore``) and the homework checks (``ddg.checks``) need the
extras named in their error messages, and so do the chapters' own helpers (``ddg.notes``) where
they draw or measure regions. Conventions: clockwise is positive (a clockwise circle has
curvature ``+1/r`` and outward normals ``N = J T``). What it refuses it refuses as one of the
errors of ``ddg.errors``, all of them ``ValueError``.

Every example in the docstrings runs as shown after ``import numpy as np`` and ``from ddg.<module>
import *`` (for example ``from ddg.curve import *``, ``from ddg.smooth import *``).

>>> import ddg
>>> square = ddg.DiscreteCurve([[0, 0], [0, 1], [1, 1], [1, 0]])   # clockwise
>>> square.turning_number, square.signed_area
(1, 1.0)
"""

import importlib

from . import errors, flow, smooth
from .curve import CURVATURES, INFLATIONS, DiscreteCurve
from .polygons import regular_polygon
from .errors import CurveError, DegenerateCurveError, InputError, OpenCurveError, OutOfRangeError

__all__ = ["CURVATURES", "INFLATIONS", "DiscreteCurve", "regular_polygon", "flow", "smooth", "errors", "CurveError",
           "DegenerateCurveError", "InputError", "OpenCurveError", "OutOfRangeError"]
__version__ = "0.1.0"

# The geometry above needs numpy only. These parts need more (matplotlib, ipywidgets, shapely):
# each is imported on first use, so `import ddg` works without them, and a missing
# dependency is an ImportError that names the extra to install (ddg/_extras.py).
_OPTIONAL = ("plot", "explore", "checks", "notes")


def __getattr__(name):
    if name in _OPTIONAL:
        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
