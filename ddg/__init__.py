"""ddg: discrete differential geometry of plane curves, after Vouga's lecture *Plane Curves*.

A small reference implementation to read next to the lecture. Conventions: clockwise is
positive (a clockwise circle has curvature ``+1/r`` and outward normals ``N = J T``).

>>> import ddg
>>> square = ddg.DiscreteCurve([[0, 0], [0, 1], [1, 1], [1, 0]])   # clockwise
>>> square.turning_number, square.signed_area
(1, 1.0)
"""

from . import flow, plot, smooth
from .curve import CURVATURES, INFLATIONS, DiscreteCurve, regular_polygon

__all__ = ["CURVATURES", "INFLATIONS", "DiscreteCurve", "regular_polygon", "flow", "plot", "smooth"]
__version__ = "0.1.0"
