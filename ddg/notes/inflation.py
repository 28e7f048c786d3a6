"""Chapter 5, inflation: the lecture's missing Figures 2 and 3 (lecture §3.4).

Both inflations of a convex polygon drawn piece by piece from ``ddg``'s own quantities
(:func:`ddg.explore.inflation_pieces`): a rectangle on each edge, and at each corner a disk
sector (the Minkowski sum, ``thm-minkowski-convex``) or a kite (the offset, ``thm-offset``),
whose angle is the turning angle ``psi_i``.
"""

import numpy as np

from . import needs

LABELS = {
    "minkowski": "sectors, area $\\varepsilon^2\\psi_i/2$",
    "offset": "kites, area $\\varepsilon^2\\tan(\\psi_i/2)$",
}
"""The legend of each inflation's corner pieces, with their areas."""


def draw_inflation(ax, curve, eps, method):
    """Draw ``curve`` inflated by ``eps`` (``"minkowski"`` or ``"offset"``), piece by piece.

    The polygon (grey), a rectangle of area ``eps |e_{i+1/2}|`` on each edge (blue), at each
    corner a sector of area ``eps^2 psi_i / 2`` (orange, the Minkowski sum) or a kite of area
    ``eps^2 tan(psi_i / 2)`` (green, the offset), and the boundary ``curve.inflate(eps, method)``.
    The pieces are those of a clockwise convex polygon (lecture §3.4).

    >>> import matplotlib.pyplot as plt
    >>> import ddg
    >>> fig, ax = plt.subplots()
    >>> draw_inflation(ax, ddg.regular_polygon(5), 0.3, "offset")
    >>> len(ax.patches)   # the pentagon, 5 rectangles and 5 kites
    11
    >>> plt.close(fig)
    """
    from ..explore import inflation_pieces
    from ..plot import plot_curve

    patches = needs("matplotlib.patches")
    rectangles, sectors, kites = inflation_pieces(curve, eps)
    ax.add_patch(patches.Polygon(curve.vertices, color="0.8", label="$\\Omega_0$"))
    for j, r in enumerate(rectangles):
        label = "rectangles, area $\\varepsilon L$" if j == 0 else None
        ax.add_patch(patches.Polygon(r, color="C0", alpha=0.35, label=label))
    for j in range(len(curve)):
        label = LABELS[method] if j == 0 else None
        if method == "minkowski":
            centre, a, b = sectors[j]
            piece = patches.Wedge(centre, eps, a, b, color="C1", alpha=0.6, label=label)
        else:
            piece = patches.Polygon(kites[j], color="C2", alpha=0.6, label=label)
        ax.add_patch(piece)
    plot_curve(curve.inflate(eps, method), ax, vertices=False, color="k", lw=1)
    plot_curve(curve, ax, color="k", lw=1.2)
    ax.set_xlabel("$x$")
    ax.set_ylabel("$y$")


def draw_corner(ax, curve, eps, method, i):
    """Draw :func:`draw_inflation` zoomed on the vertex ``v_i``: the gap there has the angle ``psi_i``.

    Adds the two edge normals ``N_{i-1/2}`` and ``N_{i+1/2}`` at ``v_i`` (red arrows of length
    ``eps``), the arc between them and the label ``psi_i`` in degrees, and frames the corner.

    >>> import matplotlib.pyplot as plt
    >>> import ddg
    >>> fig, ax = plt.subplots()
    >>> draw_corner(ax, ddg.regular_polygon(4), 0.5, "minkowski", 0)
    >>> [text.get_text() for text in ax.texts]
    ['', '$N_{i-1/2}$', '', '$N_{i+1/2}$', '$\\\\psi_i = 90°$']
    >>> plt.close(fig)
    """
    v, N = curve.vertices[i], curve.normals
    draw_inflation(ax, curve, eps, method)
    arrow = dict(arrowstyle="->", color="C3", lw=1.5)
    for n, name, side in ((N[i - 1], "N_{i-1/2}", "right"), (N[i], "N_{i+1/2}", "left")):
        ax.annotate("", v + eps * n, v, arrowprops=arrow)
        ax.annotate(f"${name}$", v + 1.05 * eps * n, color="C3", ha=side)
    start, end = (np.degrees(np.arctan2(n[1], n[0])) for n in (N[i], N[i - 1]))
    ax.add_patch(needs("matplotlib.patches").Arc(v, 0.6 * eps, 0.6 * eps, theta1=start, theta2=end, color="C3"))
    middle = (N[i - 1] + N[i]) / np.linalg.norm(N[i - 1] + N[i])
    psi = np.degrees(curve.turning_angles[i])
    ax.annotate(f"$\\psi_i = {psi:.0f}°$", v + 1.45 * eps * middle, ha="center")
    centre = v + 0.4 * eps * middle
    ax.set_xlim(centre[0] - 1.6 * eps, centre[0] + 1.6 * eps)
    ax.set_ylim(centre[1] - 1.6 * eps, centre[1] + 1.6 * eps)
