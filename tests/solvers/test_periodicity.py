"""When a run has settled (study.solvers.kernels.periodicity): the time domain's and the reference model's test."""

import numpy as np

from study.solvers.kernels import periodicity


def _period_by_definition(states, scale, tol):
    """settled_period written as its docstring says, gap by gap (the reference for the vectorised one)."""
    S = [np.asarray(s) / scale for s in states]
    gaps = {}
    for n in range(1, periodicity.MAX_PERIOD + 1):
        if len(S) < n + 2:
            return None
        gaps[n] = max(np.max(np.abs(S[-1] - S[-1 - n])), np.max(np.abs(S[-2] - S[-2 - n])))
        if gaps[n] < tol and all(gaps[d] > 10 * gaps[n] for d in range(1, n) if n % d == 0):
            return n
    return None


def test_settled_period_finds_the_period_of_noisy_repeating_states_as_defined():
    # boundary states repeating with periods 1-8 plus noise from 1e-9 to 1e-2 of their units, 0-13 of them: the
    # smallest n whose last two states repeat n back within the tolerance (and no divisor nearly does)
    rng = np.random.default_rng(3)
    scale = rng.uniform(0.5, 2.0, 12)
    found = 0
    for _ in range(3000):
        period = int(rng.integers(1, 9))
        base = rng.standard_normal((period, 12))
        states = [base[i % period] + rng.standard_normal(12) * 10.0 ** rng.uniform(-9, -2)
                  for i in range(int(rng.integers(0, 14)))]
        expected = _period_by_definition(states, scale, 1e-4)
        assert periodicity.settled_period(states, scale, 1e-4) == expected
        found += expected is not None
    assert found > 300  # periods were found, not only None
