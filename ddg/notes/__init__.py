"""The chapters' own helpers: what the book computes and draws behind its figures and hidden checks.

A chapter's hidden cells (folded code, and the asserts the book never shows) once defined these
functions inline, where nobody could import or test them. Here each one has a docstring that says
what it computes, citing the lecture or the book, an example that runs, and a unit test
(``tests/unit/test_notes.py``). One module per chapter, named after its topic, and imported by
its notebook, for example ``from ddg.notes.inflation import draw_corner``:

=======================  ==============================
``smooth_curves``        chapter 1, smooth plane curves
``discrete_curves``      chapter 2, discrete curves
``winding_number``       chapter 3, the turning number
``inflation``            chapter 5, inflation
``table``                chapter 6, Table 1
``convergence``          chapter 7, convergence
``classical_theorems``   chapter 8, classical theorems
``curve_shortening``     chapter 9, curve-shortening flow
=======================  ==============================

Like the rest of ``ddg`` they need numpy only, until they draw (matplotlib) or measure a region
(shapely): those are imported when used, and a missing one is an ``ImportError`` that names the
extra to install. No helper here computes an exercise's answer or belongs to a solution: the
student edition ships this package as it is, while the helpers of the answer keys and solutions
stay with the instructor.
"""

import importlib

from .._extras import missing

EXTRA = "notebooks"
"""The extra that brings everything the chapters (and so their helpers) use."""


def needs(name):
    """The module ``name`` (``"shapely"``, ``"matplotlib.patches"``), or an ``ImportError`` naming the extra.

    >>> needs("numpy").__name__
    'numpy'
    """
    try:
        return importlib.import_module(name)
    except ImportError as error:
        raise missing(EXTRA, error) from error
