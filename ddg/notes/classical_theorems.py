"""Chapter 8, classical theorems: the curvature sequences of the four-vertex theorem's figure.

The naive discrete four-vertex theorem fails: on a convex pentagon that is not regular every
discrete curvature can have one maximum and one minimum. :func:`draw_sequences` draws the
sequences ``k_0, ..., k_{n-1}`` once around the polygon, so that their extrema can be counted.
"""

import numpy as np

MARKERS = "os^D"
"""One marker per sequence, in order: the angle, sine, tangent and circle curvatures."""


def draw_sequences(ax, curvatures):
    """Draw each discrete curvature ``k_i`` against the vertex ``i``, once around the polygon.

    ``curvatures`` maps a name to the values at the vertices ``v_0 ... v_{n-1}`` (all of one
    length); each sequence is drawn with its first value repeated at the end, under the tick
    ``0`` again, so that an extremum at ``v_0`` shows as one.

    >>> import matplotlib.pyplot as plt
    >>> import ddg
    >>> pentagon = ddg.DiscreteCurve([[0, 3], [0, 5], [5, 0], [2, 0], [1, 1]])
    >>> fig, ax = plt.subplots()
    >>> draw_sequences(ax, {kind: pentagon.curvature(kind) for kind in ddg.CURVATURES})
    >>> [(line.get_label(), len(line.get_xdata())) for line in ax.lines]
    [('angle', 6), ('sine', 6), ('tangent', 6)]
    >>> [tick.get_text() for tick in ax.get_xticklabels()]
    ['0', '1', '2', '3', '4', '0']
    >>> plt.close(fig)
    """
    from ..plot import legend_above

    n = len(next(iter(curvatures.values())))
    i = np.arange(n + 1)
    for (kind, k), marker in zip(curvatures.items(), MARKERS, strict=False):
        ax.plot(i, np.append(k, k[0]), marker + "-", ms=4, label=kind)
    ax.set_xticks(i, [*range(n), 0])  # once around: v_0 again
    ax.set_xlabel("vertex $i$")
    ax.set_ylabel("$k_i$")
    legend_above(ax, ncol=2)
