"""Small matplotlib helpers shared by the chapters (they draw; the mathematics lives elsewhere)."""

import numpy as np

from ._extras import missing

try:
    import matplotlib.pyplot as plt
except ImportError as error:
    raise missing("plot", error) from error


def plot_curve(curve, ax=None, vertices=True, **style):
    """Draw a :class:`~ddg.DiscreteCurve` (closing edge included when closed); return the line.

    ``vertices=True`` marks the vertices with dots. Extra keyword arguments go to ``ax.plot``.
    """
    ax = ax or plt.gca()
    v = curve.vertices
    if curve.closed:
        v = np.vstack([v, v[:1]])
    style.setdefault("marker", "o" if vertices else None)
    style.setdefault("markersize", 3)
    (line,) = ax.plot(v[:, 0], v[:, 1], **style)
    ax.set_aspect("equal")
    return line


def arrows(ax, points, vectors, **style):
    """Draw one arrow per row: from ``points[i]`` along ``vectors[i]`` (data units)."""
    style.setdefault("angles", "xy")
    style.setdefault("scale_units", "xy")
    style.setdefault("scale", 1)
    style.setdefault("width", 0.004)
    return ax.quiver(points[:, 0], points[:, 1], vectors[:, 0], vectors[:, 1], **style)
