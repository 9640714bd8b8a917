"""Linear interpolation of one point in a table, compiled, for the compiled loops of the physics and
solvers (the span search interpolates the pulse duration in log L at every span it evaluates; the
Hertz contact its eccentricity's starting value).

numba's ``np.interp`` of a scalar builds arrays on every call (about 110 ns against 26 ns here).
"""

from __future__ import annotations

import math

import numba
import numpy as np


@numba.njit(cache=True, nogil=True)
def interp_one(x, xp, fp):
    """``np.interp(x, xp, fp)`` of one float x, in numpy's arithmetic: xp ascending; below xp[0]
    fp[0], above xp[-1] fp[-1], NaN for NaN."""
    n = xp.size
    if math.isnan(x):
        return math.nan
    if x <= xp[0]:
        return fp[0]
    if x >= xp[n - 1]:
        return fp[n - 1]
    j = np.searchsorted(xp, x, side="right") - 1
    if x == xp[j]:
        return fp[j]
    slope = (fp[j + 1] - fp[j]) / (xp[j + 1] - xp[j])
    return slope * (x - xp[j]) + fp[j]
