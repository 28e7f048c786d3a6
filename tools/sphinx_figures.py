"""Sphinx extension: the book's notebook figures get their text alternative and a numbered caption.

`ddg.plot.show(fig, alt, caption)` stores the figure's text alternative (PNG ``Description``) and
caption (PNG ``Title``) inside the image. When a page is read, this sets the image's ``alt`` from
it, and wraps an image that has a caption in a figure, which Sphinx numbers by chapter.
"""

import pathlib

from docutils import nodes
from sphinx.transforms import SphinxTransform

from ddg.plot import png_text


class FiguresFromPng(SphinxTransform):
    default_priority = 400  # before Sphinx collects the figures it numbers

    def apply(self):
        for count, image in enumerate(list(self.document.findall(nodes.image))):
            path = pathlib.Path(self.env.srcdir, image["uri"].lstrip("/"))  # "/..." is from the source root
            if path.suffix != ".png" or not path.is_file():
                continue
            text = png_text(path.read_bytes())
            if "Description" in text and not image.get("alt"):
                image["alt"] = text["Description"]
            if text.get("Title") and not isinstance(image.parent, nodes.figure):
                figure = nodes.figure("", classes=["ddg-figure-caption"])
                image.replace_self(figure)
                figure += image
                figure += nodes.caption(text["Title"], text["Title"])
                figure["ids"].append(f"fig-{self.env.docname.replace('/', '-')}-{count}")
                self.document.note_implicit_target(figure)


def setup(app):
    app.add_transform(FiguresFromPng)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
