"""The linear solve behind the semi-implicit step of ``ddg.flow``."""

import numpy as np


def solve_cyclic_tridiagonal(a, b, c, d):
    """Solve ``a_i x_{i-1} + b_i x_i + c_i x_{i+1} = d_i`` for ``i`` mod ``m`` (``d``: shape ``(m, 2)``).

    Cyclic reduction, vectorized: each pass eliminates the odd-numbered unknowns from the equations
    of their even-numbered neighbours, which leaves a cyclic tridiagonal system half the size
    (when ``m`` is odd, the last and first unknowns are both even and stay coupled directly). The
    last small system is solved densely and the odd unknowns are recovered on the way back: ``log2
    m`` passes of numpy work, ``O(m)`` time and memory, where a dense solve costs ``O(m^3)``.
    Without pivoting, elimination is stable for diagonally dominant systems such as ``I - dt G Lap``.

    >>> m = 7; x = np.arange(2.0 * m).reshape(m, 2)
    >>> a, b, c = np.full(m, -1.0), np.full(m, 4.0), np.full(m, -1.0)
    >>> d = b[:, None] * x + a[:, None] * np.roll(x, 1, axis=0) + c[:, None] * np.roll(x, -1, axis=0)
    >>> bool(np.allclose(solve_cyclic_tridiagonal(a, b, c, d), x))
    True
    """
    levels = []
    while len(b) > 4:
        m = len(b)
        j = np.arange(0, m, 2)  # the unknowns kept
        left, right = (j - 1) % m, (j + 1) % m
        alpha, gamma = -a[j] / b[left], -c[j] / b[right]  # multiples of the neighbouring equations
        new_a, new_c = alpha * a[left], gamma * c[right]
        if m % 2:  # unknowns m - 1 and 0 are both kept: their coupling stays as it is
            alpha[0] = gamma[-1] = 0.0
            new_a[0], new_c[-1] = a[0], c[-1]
        levels.append((a, b, c, d))
        b, d = b[j] + alpha * c[left] + gamma * a[right], d[j] + alpha[:, None] * d[left] + gamma[:, None] * d[right]
        a, c = new_a, new_c
    m, i = len(b), np.arange(len(b))
    M = np.zeros((m, m))
    for offset, coefficients in ((-1, a), (0, b), (1, c)):  # three diagonals; they overlap when m < 3
        np.add.at(M, (i, (i + offset) % m), coefficients)
    x = np.linalg.solve(M, d)
    for a, b, c, d in reversed(levels):  # back-substitute the odd unknowns of each level
        m = len(b)
        full, odd = np.empty_like(d), np.arange(1, m, 2)
        full[::2] = x
        full[odd] = (d[odd] - a[odd, None] * full[odd - 1] - c[odd, None] * full[(odd + 1) % m]) / b[odd, None]
        x = full
    return x
