"""What ``ddg`` raises when it refuses an input, by kind, so that a caller can catch one kind.

Every error is a ``ValueError`` (code that catches ``ValueError`` keeps working) and a
:class:`CurveError`, and its message names the problem and where it is (the vertex, the argument):

* :class:`InputError`: not what was asked for: a shape other than ``(n, 2)``, text or complex
  numbers, NaN or infinity, a masked value, an unknown choice, a count or a flag of the wrong type;
* :class:`DegenerateCurveError`: a curve on which the quantity does not exist: two consecutive
  equal vertices, too few vertices, a turn straight back (``psi = pi``) where a formula divides by
  ``cos(psi / 2)``, an inflation that collapses;
* :class:`OpenCurveError`: a quantity defined for closed curves only, asked of an open one;
* :class:`OutOfRangeError`: a number beyond what a float holds (an area or a length over about
  ``1.8e308``, a curvature that overflows) or beyond what the machine can store.

>>> import ddg
>>> try:
...     ddg.DiscreteCurve([[0, 0], [0, 0], [1, 1]])
... except ddg.DegenerateCurveError as error:
...     print(error)
vertices 0 and 1 are equal ([0. 0.], as floats); consecutive vertices must differ
>>> issubclass(ddg.OutOfRangeError, ValueError)
True
"""


class CurveError(ValueError):
    """The input cannot be used as given: the base of every error ``ddg`` raises on purpose."""


class InputError(CurveError):
    """An argument of the wrong type, shape or value (NaN, text, an unknown choice ...)."""


class DegenerateCurveError(CurveError):
    """The curve is degenerate for what is asked: equal neighbours, too few vertices, a turn of ``pi``."""


class OpenCurveError(CurveError):
    """A quantity of closed curves only (area, turning number, inflation ...) asked of an open curve."""


class OutOfRangeError(CurveError):
    """A value beyond the range of floats, or an array beyond what can be stored."""


__all__ = ["CurveError", "InputError", "DegenerateCurveError", "OpenCurveError", "OutOfRangeError"]
