"""The strikes' pulses of the reference model's integrator (``reference_strike_force = "pulse"``;
docs/reference_model.md §2.4): the per-point pulse state's columns and the kernels :func:`whirl_kernel.advance` and
:func:`whirl_kernel.rhs` inline (``inline="always"``: nothing compiled apart is linked into advance,
whirl_kernel.FASTMATH)
to start a strike's pulse and to give its force at a time."""

from __future__ import annotations

import numba
import numpy as np

#: Columns of the per-point pulse state (entry 20 of :func:`kernel_system`'s tuple, updated by :func:`advance`):
#: the point's mode (P_LAW: the contact law; P_PULSE: a strike's force prescribed), the pulse's onset time [s], peak
#: force [N], duration [s], the table's speed index and weight (log v0 between it and the next), its onset speed [m/s],
#: the largest wall shift over the Hertz approach at its pulse's peak (F_peak/K)^(2/3) [-], and the wall's shift [m]:
#: where a pulse ends with the kept modes' point inside the wall (their local compliance is not the strike's), the
#: point's wall is put where the point is (its clearance in the kernel's tuple raised by it), and follows it back as it
#: leaves, down to its place (docs/reference_model.md §2.4); and the largest shift [m].
P_MODE, P_T0, P_PEAK, P_DURATION, P_INDEX, P_WEIGHT, P_SPEED, P_OVERLAP, P_SHIFT, P_SHIFT_MAX = range(10)
P_LAW, P_PULSE = 0.0, 1.0
N_PULSE_STATE = 10


@numba.njit(cache=True, nogil=True, inline="always")
def pulse_force(t, pst, pcoef, p):
    """The normal force [N] at time t [s] of the strike whose pulse point p is under (its state ``pst[p]``, the
    :data:`P_MODE` … columns): the local model's history at its onset speed (study.physics.strike.strike_pulse_table),
    F_peak times its shape at s = (t − t0)/T_c, each speed's natural cubic spline in s (``pcoef`` (P, S, 4, G − 1))
    weighed linearly in log v0 between the two table speeds about v0; 0
    outside 0 < s < 1 and where the spline dips below 0."""
    s = (t - pst[p, P_T0]) / pst[p, P_DURATION]
    if s <= 0.0 or s >= 1.0:
        return 0.0
    g = pcoef.shape[3]
    j = int(s * g)
    if j > g - 1:
        j = g - 1
    x = s - j / g
    i = int(pst[p, P_INDEX])
    w = pst[p, P_WEIGHT]
    a = ((pcoef[p, i, 0, j] * x + pcoef[p, i, 1, j]) * x + pcoef[p, i, 2, j]) * x + pcoef[p, i, 3, j]
    b = ((pcoef[p, i + 1, 0, j] * x + pcoef[p, i + 1, 1, j]) * x + pcoef[p, i + 1, 2, j]) * x + pcoef[p, i + 1, 3, j]
    return pst[p, P_PEAK] * max((1.0 - w) * a + w * b, 0.0)


@numba.njit(cache=True, nogil=True, inline="always")
def point_state(z, phi, p, N):
    """(y, z, ẏ, ż) of contact point p from the state."""
    y = 0.0
    w = 0.0
    yd = 0.0
    wd = 0.0
    for n in range(N):
        y += phi[p, n] * z[n]
        w += phi[p, n] * z[N + n]
        yd += phi[p, n] * z[2 * N + n]
        wd += phi[p, n] * z[3 * N + n]
    return y, w, yd, wd


@numba.njit(cache=True, nogil=True, inline="always")
def onset_speed(z, phi, shapes, p, N, rate):
    """A strike's onset speed at point p [m/s]: the velocity of the modes' ``shapes`` (P, N) at the point along its
    normal (the direction of its whole displacement by ``phi``), from the state z; ``rate``, the whole approach rate,
    where ``shapes`` has no rows (``reference_pulse_speed``, docs/reference_model.md §2.1)."""
    if shapes.shape[0] == 0:
        return rate
    y, w, _, _ = point_state(z, phi, p, N)
    _, _, yd, wd = point_state(z, shapes, p, N)
    r = np.sqrt(y * y + w * w)
    return (y * yd + w * wd) / r if r > 0.0 else 0.0


@numba.njit(cache=True, nogil=True, inline="always")
def start_strike(p, t, speed, pst, floor, logv, lpeak, ldur, K):
    """Point p's strike at time t [s] at approach ``speed`` [m/s] as a pulse (:func:`pulse_force`) where the speed is
    at least the point's ``floor`` (the local model holds: its strike ends before the neighbours' waves return);
    returns whether it did (else the contact law takes it)."""
    if not speed >= floor[p]:
        return False
    S = logv.size
    v = min(speed, np.exp(logv[S - 1]))  # the table's top speed at most
    i = 0
    while i < S - 2 and v >= np.exp(logv[i + 1]):
        i += 1
    # log v0 by Newton's method on e^x = v0 from the table's log speed below it (np.log is not among the functions
    # advance may call: :data:`FASTMATH`): quadratic from within a table step, 1e-16 in six
    x = logv[i]
    for _ in range(6):
        x -= 1.0 - v * np.exp(-x)
    w = (x - logv[i]) / (logv[i + 1] - logv[i])
    if w > 1.0:
        w = 1.0
    pst[p, P_MODE] = P_PULSE
    pst[p, P_T0] = t
    pst[p, P_PEAK] = np.exp((1.0 - w) * lpeak[p, i] + w * lpeak[p, i + 1])
    pst[p, P_DURATION] = np.exp((1.0 - w) * ldur[p, i] + w * ldur[p, i + 1])
    pst[p, P_INDEX] = i
    pst[p, P_WEIGHT] = w
    pst[p, P_SPEED] = speed
    return True
