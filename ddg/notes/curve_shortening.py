"""Chapter 9, curve-shortening flow: area rates with the time step's error extrapolated away.

Under the smooth flow a closed curve loses area at the rate ``2 pi`` times its turning number.
The discrete flows of :mod:`ddg.flow` take forward Euler steps, whose error in the area is first
order in the step: :func:`extrapolated_rate` removes it by Richardson extrapolation from two runs.
"""

import numpy as np


def extrapolated_rate(fine, rough, points=101):
    """``-dA/dt`` over time, from two runs of one flow, extrapolated in the step: ``(t, rate)``.

    ``fine`` and ``rough`` are :class:`ddg.flow.FlowRun` records of the same flow, the first with
    half the step of the second. Their areas are interpolated to ``points`` common times from 0
    to the end of ``fine``, combined as ``2 A(half step) - A(step)``, which cancels the error of
    first order in the step, and differentiated (centred differences, ``np.gradient``).

    Two runs that lose area too slowly, by an error proportional to the step, extrapolate to the
    exact rate ``2 pi``:

    >>> from types import SimpleNamespace as Run
    >>> t = np.linspace(0, 1, 11)
    >>> exact = 3 - 2 * np.pi * t
    >>> fine, rough = Run(times=t, areas=exact + 0.1 * t), Run(times=t, areas=exact + 0.2 * t)
    >>> times, rate = extrapolated_rate(fine, rough, points=5)
    >>> times.tolist(), bool(np.allclose(rate, 2 * np.pi))
    ([0.0, 0.25, 0.5, 0.75, 1.0], True)
    """
    t = np.linspace(0, fine.times[-1], points)
    area = 2 * np.interp(t, fine.times, fine.areas)
    area -= np.interp(t, rough.times, rough.areas)
    return t, -np.gradient(area, t)
