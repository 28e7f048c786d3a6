"""Sphinx extension: the proof index lists "Theorem 5.2 (The offset of a simple polygon)", by chapter.

sphinx-proof's own index names each entry by its label (``thm-offset``), one group per label.
This one names it as the page does, with its number and title, groups the entries by chapter
and keeps the chapters' order.
"""

from collections import defaultdict

from docutils import nodes
from sphinx_proof.domain import ProofDomain, ProofIndex


class ReadableProofIndex(ProofIndex):
    def generate(self, docnames=None):
        env = self.domain.env
        chapters = defaultdict(list)
        for anchor, values in getattr(env, "proof_list", {}).items():
            doc = values["docname"]
            number = env.toc_fignumbers.get(doc, {}).get(values["countertype"], {}).get(anchor)
            name = values["realtype"].capitalize()
            if number:
                name += " " + ".".join(map(str, number))
            name += self.title(doc, anchor)
            chapter = env.toc_secnumbers.get(doc, {}).get("", ())
            heading = ".".join(map(str, chapter)) + ". " if chapter else ""
            chapters[chapter, heading + env.titles[doc].astext()].append(
                (number or (0,), (name, 0, doc, anchor, "", "", "")))
        content = [(heading, [entry for _, entry in sorted(entries)])
                   for (_, heading), entries in sorted(chapters.items())]
        return content, False

    def title(self, doc, anchor):
        """The box's title as the page shows it after the number, e.g. " (The offset ...)"."""
        for node in self.domain.env.get_doctree(doc).findall(nodes.Element):
            if anchor in node["ids"] and node.children and isinstance(node.children[0], nodes.title):
                return node.children[0].astext()
        return ""


def setup(app):
    ProofDomain.indices = [ReadableProofIndex]
    return {"parallel_read_safe": True, "parallel_write_safe": True}
