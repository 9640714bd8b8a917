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
#: leaves, down to its place (docs/reference_model.md §2.4); the largest shift [m]; and with the work-matched pulses
#: (:func:`matched_scale`, with the local strikes' losses in the kernel's tuple) the sum of the scales λ that match
#: the pulses' work to the local strikes' and their count, and the sums of the work [J] the tabulated pulse (λ = 1)
#: would do on the modes, predicted at the onsets, and of the local strikes' (−loss); the pulses' count, and the sum
#: of the work [J] the pulses applied did on the modes, −∫F δ̇ dt (each step's trapezoid; :func:`whirl_kernel.advance`).
(P_MODE, P_T0, P_PEAK, P_DURATION, P_INDEX, P_WEIGHT, P_SPEED, P_OVERLAP, P_SHIFT, P_SHIFT_MAX, P_SCALE_SUM,
 P_SCALE_COUNT, P_WORK_TABLE, P_WORK_LOCAL, P_PULSES, P_WORK_DONE) = range(16)
P_LAW, P_PULSE = 0.0, 1.0
N_PULSE_STATE = 16


@numba.njit(cache=True, nogil=True, inline="always")
def spline_shape(pcoef, p, i, w, j, x):
    """The pulse's shape [-] at x into its piece j (of G, x in [0, 1/G]) at point p: the natural cubic splines of the
    table speeds i and i + 1 (``pcoef`` (P, S, 4, G − 1), Horner in x) weighed w and 1 − w (linearly in log v0),
    nil where that dips below 0. x = 0 gives a piece's first knot exactly (its constant term)."""
    a = ((pcoef[p, i, 0, j] * x + pcoef[p, i, 1, j]) * x + pcoef[p, i, 2, j]) * x + pcoef[p, i, 3, j]
    b = ((pcoef[p, i + 1, 0, j] * x + pcoef[p, i + 1, 1, j]) * x + pcoef[p, i + 1, 2, j]) * x + pcoef[p, i + 1, 3, j]
    return max((1.0 - w) * a + w * b, 0.0)


@numba.njit(cache=True, nogil=True, inline="always")
def pulse_force(t, pst, pcoef, p):
    """The normal force [N] at time t [s] of the strike whose pulse point p is under (its state ``pst[p]``, the
    :data:`P_MODE` … columns): the local model's history at its onset speed (study.physics.strike.strike_pulse_table),
    F_peak times its shape at s = (t − t0)/T_c (:func:`spline_shape`, each speed's natural cubic spline in s weighed
    linearly in log v0 between the two table speeds about v0); 0 outside 0 < s < 1 and where the spline dips below 0."""
    s = (t - pst[p, P_T0]) / pst[p, P_DURATION]
    if s <= 0.0 or s >= 1.0:
        return 0.0
    g = pcoef.shape[3]
    j = int(s * g)
    if j > g - 1:
        j = g - 1
    return pst[p, P_PEAK] * spline_shape(pcoef, p, int(pst[p, P_INDEX]), pst[p, P_WEIGHT], j, s - j / g)


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


@numba.njit(cache=True, nogil=True, inline="always")
def pulse_work_terms(z, phi, omega2, inv_m, p, N, shape, duration):
    """The work [J] a force F(t) = F̂ shape(t/T) along the inward normal at point p does on the modes over 0 < t < T,
    W(F̂) = −F̂ A + F̂² B, for undamped linear modes (q̈_n = −ω_n² q_n + φ_pn F_n/m) from the state z: returns (A, B).
    A = ∫ shape(t/T) δ̇_free(t) dt [m], the pulse against the point's free normal velocity δ̇_free = Σ_n φ_pn (b_n cos
    ω_n t − ω_n a_n sin ω_n t) (a_n, b_n: mode n's displacement and velocity along the normal at the onset), and
    B = Σ_n φ_pn² (C_n² + S_n²) m⁻¹/2 [m/N], the energy the pulse leaves in the modes from rest, C_n, S_n = ∫ shape(t/T)
    (cos, sin) ω_n t dt (a force's work on an oscillator from rest, |∫ f e^{iωt} dt|²/2m). ``shape`` (G + 1,) on the
    even grid of s = t/T ∈ [0, 1] (the trapezoidal rule), ``duration`` T [s], ``inv_m`` 1/m [1/kg]."""
    y, w, _, _ = point_state(z, phi, p, N)
    r = np.sqrt(y * y + w * w)
    ny = y / r if r > 0.0 else 1.0
    nz = w / r if r > 0.0 else 0.0
    G = shape.size - 1
    ds = duration / G
    A = 0.0
    B = 0.0
    for n in range(N):
        om = np.sqrt(max(omega2[n], 0.0))
        c = 0.0
        s = 0.0
        for j in range(G + 1):
            wt = 0.5 * ds if j == 0 or j == G else ds
            c += wt * shape[j] * np.cos(om * j * ds)
            s += wt * shape[j] * np.sin(om * j * ds)
        a = z[n] * ny + z[N + n] * nz
        b = z[2 * N + n] * ny + z[3 * N + n] * nz
        A += phi[p, n] * (b * c - om * a * s)
        B += phi[p, n] * phi[p, n] * (c * c + s * s) * 0.5 * inv_m
    return A, B


@numba.njit(cache=True, nogil=True, inline="always")
def matched_amplitude(A, B, loss):
    """The amplitude F̂ [N] at which W(F̂) = −F̂ A + F̂² B (:func:`pulse_work_terms`) is −``loss`` [J] (the local
    strike's net work on its joint-and-beam), the larger root: the point rebounds, as the local joint does, and leaves
    with the energy the local strike leaves (a restitution-consistent exit). Where no amplitude takes that much
    (A² < 4 B loss) the one that takes the most, A/2B (the point stopped in the work's sense). 0 where B ≤ 0."""
    if not B > 0.0:
        return 0.0
    disc = A * A - 4.0 * B * loss
    return (A + np.sqrt(disc if disc > 0.0 else 0.0)) / (2.0 * B)


@numba.njit(cache=True, nogil=True, inline="always")
def matched_scale(z, phi, omega2, inv_m, p, N, pst, pcoef, lloss, shape, steady=False):
    """λ [-], the scale of point p's pulse just started (``pst[p]``, :func:`start_strike`) at which its work on the
    modes, predicted from the state z at its onset by :func:`pulse_work_terms` (undamped linear modes, the normal
    fixed), equals the local strike's net work on its joint-and-beam, −loss (``lloss`` (P, S): log ∫F dδ [J] of
    study.physics.strike.strike_pulse_table, interpolated as the peak); ``reference_pulse_work = "matched"``,
    docs/reference_model.md §2.4. ``shape`` (G + 1,) is room for the pulse's shape on its grid. 1 where none fits.
    With ``steady`` the point's free motion is taken as the local model's, a steady approach at the onset speed
    (A = v0 ∫ shape dt; ``reference_pulse_work = "mobility"``): only the kept modes' energy B is the model's.
    Adds the tabulated pulse's predicted work and the local strike's to ``pst[p]`` (P_WORK_TABLE, P_WORK_LOCAL)."""
    i = int(pst[p, P_INDEX])
    w = pst[p, P_WEIGHT]
    G = pcoef.shape[3]
    for j in range(G):
        shape[j] = spline_shape(pcoef, p, i, w, j, 0.0)
    shape[G] = spline_shape(pcoef, p, i, w, G - 1, 1.0 / G)  # the last knot: the last piece's end
    A, B = pulse_work_terms(z, phi, omega2, inv_m, p, N, shape, pst[p, P_DURATION])
    if steady:
        A = 0.0
        for j in range(G + 1):
            A += (0.5 if j == 0 or j == G else 1.0) * shape[j]
        A *= pst[p, P_SPEED] * pst[p, P_DURATION] / G
    loss = np.exp((1.0 - w) * lloss[p, i] + w * lloss[p, i + 1])
    amplitude = matched_amplitude(A, B, loss)
    peak = pst[p, P_PEAK]
    pst[p, P_WORK_TABLE] += -peak * A + peak * peak * B
    pst[p, P_WORK_LOCAL] -= loss
    if not amplitude > 0.0:
        return 1.0
    return amplitude / pst[p, P_PEAK]


@numba.njit(cache=True, nogil=True, inline="always")
def size_pulse(z, phi, omega2, inv_m, p, N, pst, pcoef, lloss, shape, mode):
    """Point p's pulse just started (:func:`start_strike`): counted, and with the local strikes' losses ``lloss``
    (P, S; none: (0, 2)) its matching scale λ (:func:`matched_scale`; ``mode`` 2.0: the steady approach's) summed,
    and applied where ``mode`` > 0 (``reference_pulse_work`` "matched" 1.0, "mobility" 2.0; :func:`work_arrays`)."""
    pst[p, P_PULSES] += 1.0
    if lloss.shape[0] == 0:
        return
    lam = matched_scale(z, phi, omega2, inv_m, p, N, pst, pcoef, lloss, shape, mode > 1.5)
    pst[p, P_SCALE_SUM] += lam
    pst[p, P_SCALE_COUNT] += 1.0
    if mode > 0.0:
        pst[p, P_PEAK] *= lam


@numba.njit(cache=True, nogil=True, inline="always")
def pulse_step_work(pst, p, h, f0, r0, f1, r1):
    """Adds a step's work [J] of point p's pulse on the modes, −∫F δ̇ dt by the step's trapezoid (h [s]; the normal
    forces ``f0``/``f1`` (P, 3) column 2 [N] and approach rates ``r0``/``r1`` (P, 2) column 1 [m/s] at its start and
    end), to ``pst[p, P_WORK_DONE]`` while p is under a pulse."""
    if pst[p, P_MODE] == P_PULSE:
        pst[p, P_WORK_DONE] -= 0.5 * h * (f0[p, 2] * r0[p, 1] + f1[p, 2] * r1[p, 1])


#: ``reference_pulse_work``'s values, as coded in the kernel's tuple (:func:`work_arrays`).
PULSE_WORK = ("local", "matched", "mobility")


def work_arrays(pulse_loss, intervals: int, matched: str = "local") -> tuple:
    """The kernel tuple's entries for the pulses' work (whirl_kernel.kernel_system): the local strikes' losses
    ``pulse_loss`` (P, S) [J] in logs (None: (0, 2), no pulse's work predicted), room for a pulse's shape on its
    ``intervals`` + 1 knots, and ``matched`` (``reference_pulse_work``) coded as its index in :data:`PULSE_WORK`,
    (1,)."""
    return (np.zeros((0, 2)) if pulse_loss is None else np.log(np.asarray(pulse_loss, float)),
            np.zeros(intervals + 1), np.array([float(PULSE_WORK.index(matched))]))
