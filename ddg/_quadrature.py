"""Adaptive Gauss quadrature, behind the arc length and total curvature of ``ddg.smooth``."""

import numpy as np

from .errors import OutOfRangeError

# Gauss-Legendre rule on [0, 1], 8 nodes: exact for polynomials of degree 15.
_GL_X, _GL_W = np.polynomial.legendre.leggauss(8)
_GL_X, _GL_W = (_GL_X + 1) / 2, _GL_W / 2

RTOL = 1e-13
"""Relative accuracy the adaptive quadrature behind arc length and total curvature aims at. Its error
estimate can be fooled by chance near a narrow feature: on 1500 ellipses with b / a from 1 to 1e-6
the worst length was 4e-13 off (relative)."""

_EPS = np.finfo(float).eps


def gauss(f, a, b):
    """``int_a^b f`` and ``int_a^b |f|`` on each cell ``[a_j, b_j]`` by the 8-node Gauss rule."""
    values = f(a[..., None] + (b - a)[..., None] * _GL_X)
    return (b - a) * (values @ _GL_W), (b - a) * (np.abs(values) @ _GL_W)


def adaptive(f, t0, t1, cells=1024, max_levels=60, max_cells=10**5):
    """Cells ``(a, b)``, sorted, and ``int f`` on each, to a relative accuracy :data:`RTOL`.

    Adaptive Gauss quadrature, vectorized over cells. Every cell is integrated whole and as two
    halves; their difference estimates the error of the whole. A cell is done when that error is
    below its share (its width over ``t1 - t0``) of ``RTOL * int |f|``, or at the level of rounding
    in its own ``int |f|``, and its halves' sum is kept;
    all other cells are halved at once and examined again. Narrow features (a thin ellipse's tips)
    get small cells, smooth stretches stay coarse. Once the errors left sum to less than
    ``RTOL * int |f|`` (a kink or a jump in ``f``) every cell is done. If that takes more than
    ``max_levels`` halvings or ``max_cells`` cells, or cells narrower than the rounding of ``t``
    allows, or ``f`` is not finite, ``ValueError`` says where.
    """
    a = np.linspace(t0, t1, cells + 1)
    a, b = a[:-1], a[1:]
    why = f"it needs more than {max_levels} halvings"
    whole, _ = gauss(f, a, b)
    done, done_abs = [], 0.0
    for _ in range(max_levels):
        m = (a + b) / 2
        (left, left_abs), (right, right_abs) = gauss(f, a, m), gauss(f, m, b)
        if not np.isfinite(left_abs + right_abs).all():
            worst = a[~np.isfinite(left_abs + right_abs)][0]
            why = "the integrand is not finite there (is the curve regular, |gamma'| > 0?)"
            break
        error, tolerance = np.abs(whole - left - right), RTOL * (done_abs + np.sum(left_abs + right_abs))
        ok = error <= np.maximum(tolerance * (b - a) / (t1 - t0), 64 * _EPS * (left_abs + right_abs))  # or rounding
        if np.sum(error[~ok]) <= tolerance:
            ok[:] = True
        done.append((a[ok], b[ok], (left + right)[ok]))
        done_abs += np.sum((left_abs + right_abs)[ok])
        if ok.all():
            a, b, I = (np.concatenate(parts) for parts in zip(*done, strict=True))
            order = np.argsort(a)
            return a[order], b[order], I[order]
        worst = a[~ok][np.argmax(error[~ok])]
        a, m, b = a[~ok], m[~ok], b[~ok]
        why = (f"it needs more than {max_cells} cells: the integrand has a feature too narrow or too steep there "
               "(the tip of a very eccentric ellipse, say), or a kink")
        if len(a) > max_cells / 2:
            break
        if np.any(b - a < 1024 * np.spacing(np.maximum(abs(a), abs(b)))):
            why = ("the integrand changes on a scale finer than the rounding of the parameter t allows (as at "
                   "the tip of a very eccentric ellipse); parametrize the curve so that t moves faster there")
            break
        a, b, whole = np.concatenate([a, m]), np.concatenate([m, b]), np.concatenate([left[~ok], right[~ok]])
    raise OutOfRangeError(f"the quadrature did not converge near t = {worst:.6g}: {why}")
