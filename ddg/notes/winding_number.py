"""Chapter 3, the turning number: where a polygon crosses itself.

The lecture proves the discrete turning-number theorem (lecture §3.2) by cutting a
self-intersecting polygon at a crossing into two closed polygons whose turning numbers add up to
its own. The chapter tests that step with :func:`crossings`.
"""

import numpy as np


def crossings(P):
    """Where two edges of the closed polygon ``P`` that share no vertex cross: ``[(x, i, j), ...]``.

    ``x`` is the crossing point of the edges ``e_{i+1/2}`` (from ``v_i`` to ``v_{i+1}``) and
    ``e_{j+1/2}``, with ``i < j``, in the order of the pairs ``(i, j)``. Only proper crossings
    count: the two edges must meet inside both (not at an end), and parallel edges never cross.
    Cutting ``P`` at ``x`` leaves the closed polygons ``x, v_{i+1}, ..., v_j`` and
    ``x, v_{j+1}, ..., v_i``, whose turning numbers add up to that of ``P``. (All pairs of edges
    are tested at once: memory grows like ``n^2``.)

    A figure eight crosses itself once, between its first and third edges:

    >>> from ddg import DiscreteCurve
    >>> eight = DiscreteCurve([[0, 0], [1, 1], [1, 0], [0, 1]])
    >>> [(x.tolist(), i, j) for x, i, j in crossings(eight)]
    [([0.5, 0.5], 0, 2)]
    """
    a = P.vertices
    b = np.roll(a, -1, axis=0)
    n = len(a)
    i, j = np.triu_indices(n, 1)
    apart = (j - i != 1) & (j - i != n - 1)  # edges that share no vertex
    i, j = i[apart], j[apart]
    d1, d2, r = b[i] - a[i], b[j] - a[j], a[j] - a[i]
    det = d1[:, 0] * -d2[:, 1] + d2[:, 0] * d1[:, 1]
    with np.errstate(divide="ignore", invalid="ignore"):  # parallel edges: det = 0, never a crossing
        s = (r[:, 0] * -d2[:, 1] + d2[:, 0] * r[:, 1]) / det
        t = (d1[:, 0] * r[:, 1] - d1[:, 1] * r[:, 0]) / det
    cross = (det != 0) & (0 < s) & (s < 1) & (0 < t) & (t < 1)
    points = a[i[cross]] + s[cross, None] * d1[cross]
    return list(zip(points, i[cross].tolist(), j[cross].tolist(), strict=True))
