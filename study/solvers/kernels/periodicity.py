"""When a motion has settled: the test on a run's sequence of states one revolution apart, shared by the integrators
that run a point until it repeats (the time domain's, docs/model.md §10, and the reference model's,
docs/reference_model.md §3).
"""

from __future__ import annotations

import numpy as np

#: The longest period looked for [revolutions].
MAX_PERIOD = 8


def settled_period(states, scale, tol):
    """Smallest n ≤ 8 such that the last two boundary states equal those n revolutions earlier (``states`` a
    sequence of boundary states, oldest first; ``scale`` their entries' units; ``tol`` in those units)."""
    if len(states) < 3:
        return None
    S = np.asarray(states[-(MAX_PERIOD + 2):]) / scale  # the last ten are all it reads
    count = min(MAX_PERIOD, len(S) - 2)
    # every gap at once: diff[n - 1] = the larger of |S[-1] − S[-1 − n]| and |S[-2] − S[-2 − n]|, n = 1 … count
    back = np.arange(count)
    diff = np.maximum(np.max(np.abs(S[-1] - S[-2 - back]), axis=1), np.max(np.abs(S[-2] - S[-3 - back]), axis=1))
    for n in range(1, count + 1):
        # a longer period only if no divisor is nearly periodic too: a transient decaying with a
        # negative Floquet multiplier closes its 2-revolution gap first
        if diff[n - 1] < tol and all(diff[d - 1] > 10 * diff[n - 1] for d in range(1, n) if n % d == 0):
            return n
    return None
