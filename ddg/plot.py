"""Small matplotlib helpers shared by the chapters (they draw; the mathematics lives elsewhere).

The book's figures are made to be read on a phone as on a desktop: one panel per figure, 330
pixels wide, its text as large as the page's (:data:`STYLE`). Figures that belong together are
shown one after the other; the page places them side by side where there is room. Each figure is
shown with :func:`show`, which keeps its text alternative (and caption) with the image.
"""

import io

import numpy as np

from ._extras import missing

try:
    import matplotlib.pyplot as plt
except ImportError as error:
    raise missing("plot", error) from error


STYLE = {
    "figure.dpi": 100, "savefig.dpi": 100, "figure.figsize": (3.3, 2.8), "figure.constrained_layout.use": True,
    "font.size": 12, "axes.titlesize": 12, "axes.labelsize": 12, "xtick.labelsize": 12, "ytick.labelsize": 12,
    "legend.fontsize": 12, "figure.titlesize": 12,
}
"""The book's figure style: 12-point text at 100 dots per inch is 16.7 pixels, the size of the
page's body text; a panel is 3.3 inches (330 pixels) wide, so that two fit side by side."""


def use_book_style():
    """Make new figures in this notebook follow :data:`STYLE`."""
    plt.rcParams.update(STYLE)


def panels(count=1, width=3.3, height=2.8, **subplot_kw):
    """``count`` figures of one panel each; returns their axes (one, or a list).

    A panel per figure keeps every panel at full size on a phone, where side-by-side panels
    would shrink to a third.
    """
    axes = [plt.subplots(figsize=(width, height), layout="constrained", subplot_kw=subplot_kw)[1]
            for _ in range(count)]
    return axes[0] if count == 1 else axes


def show(fig, alt, caption=None):
    """Display ``fig`` with its text alternative ``alt``, and a ``caption`` (numbered in the book).

    Both travel inside the PNG (its Description and Title); the book's build puts them on the
    page (tools/sphinx_figures.py). The figure is closed, so it is shown once.
    """
    from IPython.display import Image, display

    if "$" in alt or "$" in (caption or ""):
        raise ValueError("write the alt text and caption in plain words (ψ, ε, π are fine), without $...$ math")
    metadata = {"Description": alt, **({"Title": caption} if caption else {})}
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", metadata=metadata, bbox_inches="tight", pad_inches=0.03)
    plt.close(fig)
    display(Image(buffer.getvalue()))


def legend_above(ax, **options):
    """The legend above the axes, where it covers no data (keyword arguments go to ``ax.legend``)."""
    return ax.legend(loc="lower left", bbox_to_anchor=(0, 1.02), frameon=False, **options)


def png_text(data):
    """The text chunks (``tEXt``) of PNG bytes, as a dict: what :func:`show` stored."""
    import struct
    import zlib

    text, at = {}, 8
    while at + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        chunk = data[at + 8:at + 8 + length]
        if kind == b"tEXt":
            key, _, value = chunk.partition(b"\0")
            text[key.decode("latin-1")] = value.decode("latin-1")
        elif kind == b"iTXt":
            key, _, rest = chunk.partition(b"\0")
            flag, _, rest = rest[0], rest[1], rest[2:]
            rest = rest.split(b"\0", 2)[2]  # language tag, translated keyword
            text[key.decode("latin-1")] = (zlib.decompress(rest) if flag else rest).decode("utf-8")
        at += 12 + length
    return text


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
    """Draw one arrow per row: from ``points[i]`` along ``vectors[i]`` (data units).

    The axes' limits grow to take in the arrows' tips (matplotlib's autoscaling ignores arrows).
    """
    style.setdefault("angles", "xy")
    style.setdefault("scale_units", "xy")
    style.setdefault("scale", 1)
    style.setdefault("width", 0.004)
    points, vectors = np.asarray(points, dtype=float), np.asarray(vectors, dtype=float)
    quiver = ax.quiver(points[:, 0], points[:, 1], vectors[:, 0], vectors[:, 1], **style)
    if style["scale_units"] == "xy" and style["angles"] == "xy":
        ax.update_datalim(np.vstack([points, points + vectors / style["scale"]]))
        ax.autoscale_view()
    return quiver
