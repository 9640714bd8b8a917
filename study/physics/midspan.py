"""The midspan state of many spans at once: the span search's compiled kernels (docs/model.md §4.5).

For the periodic impact solution of :mod:`study.physics.beam` — modes sin(k_n x), Lee's pulse train, a load spread
over the contact — the midspan's displacement, velocity and curvature per unit impulse at the start of a pulse,
for one span (:func:`midspan_state_one`, the exact model's) or many at once in SIMD instructions
(:func:`midspan_states`, :func:`midspan_sums`: the loop over spans innermost, no jumps, no library calls: sine and
cosine by :func:`sincos`), and the midspan screen's verdicts (:func:`excursion_verdicts`), each taken only where
rounding cannot change it. The scalar and the SIMD loops compute each mode's terms with the same function
(:func:`_mode_term`), so they agree to the last bit. Why each is built so: docs/profile_fast.md.

Pure functions of numpy arrays, SI units, no I/O.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from study.physics.beam import IMPACT_PATTERNS, LOAD_SHAPES, PARABOLIC_SERIES, SHAPE_CODES, check_choice


@numba.njit(cache=True, nogil=True)
def _midspan_state_kernel(spans, durations, halves, modes, ei, tension, mass, period, one_wall, code, tol,
                          consecutive):
    """The loop of :func:`midspan_state_at_pulse_start` over :func:`midspan_state_one`."""
    out = np.empty((3, spans.size))
    per_span = modes.shape[0] > 1
    for i in range(spans.size):
        out[0, i], out[1, i], out[2, i] = midspan_state_one(spans[i], durations[i], halves[i], modes[i if per_span else 0],
                                                            ei, tension, mass, period, one_wall, code, tol, consecutive)
    return out


@numba.njit(cache=True, nogil=True)
def midspan_state_one(span, tl, half, modes, ei, tension, mass, period, one_wall, code, tol, consecutive):
    """(y₁, v₁, y₁'') of :func:`midspan_state_at_pulse_start` at one span, compiled (for the compiled
    root finders of the span search): span L [m], tl T_L [s], half b [m], modes the odd mode numbers
    (1-D), ei, tension, mass, period as there; one_wall: the pattern; code: the load shape's
    (``SHAPE_CODES``); tol: resonance_tol. ``consecutive``: the modes are 1, 3, 5, …, so sin and cos
    of β_n = n β_1 (the load factors) follow by rotation through 2β_1 instead of two transcendentals
    per mode. Each mode's terms are :func:`_mode_term`'s, as in :func:`midspan_states` (many spans at once)."""
    if not tl <= (period if one_wall else 0.5 * period):  # the pulse outlasts the (half) period
        return math.nan, math.nan, math.nan
    inv_mass = 1.0 / mass
    k1 = math.pi / span  # k_n = n k_1
    weight_1 = 2.0 / (mass * span)  # w_n = weight_1 g_n
    u_1 = tl / math.pi  # u = ω T_L/π
    y = 0.0
    v = 0.0
    curv = 0.0
    s_n = c_n = s_2 = c_2 = 0.0
    if consecutive and code != 0:
        s_n, c_n = sincos(k1 * half)  # sin, cos of n β_1 for the current odd n
        s_2, c_2 = sincos(2.0 * k1 * half)
    for j in range(modes.size):
        n = modes[j]
        if not consecutive:
            s_n, c_n = sincos(n * k1 * half)
        q, qd, k2, shape, bad = _mode_term(n, k1, half, tl, u_1, ei, tension, inv_mass, period, one_wall, tol, code,
                                           s_n, c_n)
        if bad:
            return math.nan, math.nan, math.nan
        if consecutive:
            s_n, c_n = s_n * c_2 + c_n * s_2, c_n * c_2 - s_n * s_2
        weight = weight_1 * shape
        y += weight * q
        v += weight * qd
        curv -= weight * k2 * q
    return y, v, curv


# --- the midspan state of many spans at once, in SIMD instructions ----------------------------------
#: π/2 in four parts of at most 27 significant bits (Cody & Waite's reduction): k times each of the first
#: three is exact for |k| < 2^26, so x − k π/2 keeps its accuracy up to |x| ≈ 10^8.
_PIO2_PARTS = (1.570796325802803, 9.920935739593517e-10, 5.721188709663575e-18, 1.6446256936324258e-26)


#: Minimax coefficients of sin and cos on [−π/4, π/4] (fdlibm's __kernel_sin and __kernel_cos, Sun
#: Microsystems 1993; error below 2^−58 on the interval).
_SIN_POLY = (-1.66666666666666324348e-01, 8.33333333332248946124e-03, -1.98412698298579493134e-04,
             2.75573137070700676789e-06, -2.50507602534068634195e-08, 1.58969099521155010221e-10)


_COS_POLY = (4.16666666666666019037e-02, -1.38888888888741095749e-03, 2.48015872894767294178e-05,
             -2.75573143513906633035e-07, 2.08757232129817482790e-09, -1.13596475577881948265e-11)


@numba.njit(cache=True, nogil=True, inline="always")
def sincos(x):
    """(sin x, cos x) without a jump or a library call, so that a loop over arrays of x compiles to SIMD
    instructions (the scalar library calls were most of the span search's time, docs/profile_fast.md):
    x − kπ/2 reduced by :data:`_PIO2_PARTS`, the polynomials of :data:`_SIN_POLY` and :data:`_COS_POLY`
    on [−π/4, π/4], the quadrant chosen by selects. Within 2 ulp of ``math.sin``/``math.cos`` (absolute,
    for |sin|, |cos| ≤ 1) for |x| < 10^7 (tests/physics/test_beam.py); NaN for a NaN x."""
    k = math.floor(x * 0.6366197723675814 + 0.5)
    p1, p2, p3, p4 = _PIO2_PARTS
    r = (((x - k * p1) - k * p2) - k * p3) - k * p4
    z = r * r
    s1, s2, s3, s4, s5, s6 = _SIN_POLY
    c1, c2, c3, c4, c5, c6 = _COS_POLY
    s = r + r * z * (s1 + z * (s2 + z * (s3 + z * (s4 + z * (s5 + z * s6)))))
    c = 1.0 - 0.5 * z + z * z * (c1 + z * (c2 + z * (c3 + z * (c4 + z * (c5 + z * c6)))))
    quadrant = k - 4.0 * math.floor(0.25 * k)  # 0, 1, 2, 3
    odd = (quadrant == 1.0) | (quadrant == 3.0)
    sine = c if odd else s
    cosine = s if odd else c
    sine = -sine if quadrant >= 2.0 else sine
    cosine = -cosine if (quadrant == 1.0) | (quadrant == 2.0) else cosine
    return sine, cosine


@numba.njit(cache=True, nogil=True, inline="always", error_model="numpy")
def _mode_factors(n, k1, half, tl, u_1, ei, tension, inv_mass, period, one_wall, tol, code, sin_beta, cos_beta):
    """The factors of one odd mode n's periodic response, without jumps or library calls: (ω_n [rad/s],
    ν = ωτ/2π [-], κ [-], sin φ, cos φ (φ = ωT_L/2), A [-], |g_n| [-], k_n² [1/m²], resonant or buckled?) for
    k_1 = π/L ``k1`` [1/m], ``half`` b [m], ``tl`` T_L [s], ``u_1`` = T_L/π, sin and cos of β = k_n b. As
    :func:`modal_state_at_pulse_start`: κ = cot of the reduced angle (:func:`_echo_kappa`) as cos/sin,
    A = cos φ/(1 − u²) (:func:`_echo_amplitude`, its sinc by the series where |1 − u| ≤ 2e-3), and the
    load factor of :func:`_shape_factor`."""
    k = n * k1
    k2 = k * k
    om2 = (ei * k2 + tension) * k2 * inv_mass
    om = math.sqrt(abs(om2))
    nu = om * period * (0.5 / math.pi)  # as _echo_kappa: κ near a resonance amplifies ν's rounding
    d = nu - math.floor(nu + 0.5) if one_wall else nu - (2.0 * math.floor(0.5 * (nu - 1.0) + 0.5) + 1.0)
    s_k, c_k = sincos((math.pi if one_wall else 0.5 * math.pi) * d)
    bad = (not om2 > 0.0) | (not abs(d) > tol * max(1.0, nu))
    kappa = c_k / s_k
    sin_phi, cos_phi = sincos(0.5 * om * tl)
    u = om * u_1
    half_gap = 0.5 * (1.0 - u)
    x = math.pi * half_gap  # near u = 1: (π/2) sinc(x)/(1 + u), sinc by its series (|x| ≤ π/1000)
    near = 0.5 * math.pi * (1.0 - x * x * (1.0 / 6.0 - x * x / 120.0)) / (1.0 + u)
    amp = cos_phi / ((1.0 - u) * (1.0 + u)) if abs(half_gap) > 1e-3 else near
    beta = k * half
    b2 = beta * beta
    series = PARABOLIC_SERIES
    acc = (((((((series[0] * b2 + series[1]) * b2 + series[2]) * b2 + series[3]) * b2 + series[4]) * b2
              + series[5]) * b2 + series[6]) * b2 + series[7]) * b2 + series[8]  # unrolled: no inner loop
    parabolic = acc if abs(beta) < 0.5 else 3.0 * (sin_beta - beta * cos_beta) / (b2 * beta)
    uniform = 1.0 if beta == 0.0 else sin_beta / beta
    return om, nu, kappa, sin_phi, cos_phi, amp, 1.0 if code == 0 else uniform if code == 1 else parabolic, k2, bad


@numba.njit(cache=True, nogil=True, inline="always", error_model="numpy")
def _mode_term(n, k1, half, tl, u_1, ei, tension, inv_mass, period, one_wall, tol, code, sin_beta, cos_beta):
    """One odd mode n's part of the midspan state (:func:`midspan_state_one`, without jumps or library calls):
    (q(0) [s], q̇(0) [-], k_n² [1/m²], |g_n| [-], resonant or buckled?) from :func:`_mode_factors` (same
    arguments), q(0) = A (κ cos φ + sin φ)/(2ω), q̇(0) = A (κ sin φ − cos φ)/2."""
    om, _, kappa, sin_phi, cos_phi, amp, shape, k2, bad = _mode_factors(n, k1, half, tl, u_1, ei, tension, inv_mass,
                                                                       period, one_wall, tol, code, sin_beta, cos_beta)
    q = amp * (kappa * cos_phi + sin_phi) / (2.0 * om)
    qd = 0.5 * amp * (kappa * sin_phi - cos_phi)
    return q, qd, k2, shape, bad


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _span_factors(spans, durations, halves, mass):
    """Per span, for the loops over modes of :func:`midspan_states` and :func:`excursion_verdicts`: k_1 = π/L
    [1/m], the midspan weight 2/(M L) [1/kg], u_1 = T_L/π [s], and sin, cos of β_1 = k_1 b and of 2β_1 (the
    odd modes' load factors by rotation)."""
    size = spans.size
    k1, weight_1, u_1 = np.empty(size), np.empty(size), np.empty(size)
    s_n, c_n, s_2, c_2 = np.empty(size), np.empty(size), np.empty(size), np.empty(size)
    for i in range(size):
        k1[i] = math.pi / spans[i]
        weight_1[i] = 2.0 / (mass * spans[i])
        u_1[i] = durations[i] / math.pi
        s_n[i], c_n[i] = sincos(k1[i] * halves[i])
        s_2[i], c_2[i] = sincos(2.0 * k1[i] * halves[i])
    return k1, weight_1, u_1, s_n, c_n, s_2, c_2


@numba.njit(cache=True, nogil=True, error_model="numpy")  # no division check: a jump in the loop stops SIMD
def midspan_states(spans, durations, halves, n_odd, ei, tension, mass, period, one_wall, code, tol):
    """:func:`midspan_state_one` at every span of ``spans`` [m] (with its T_L ``durations`` [s] and
    contact half-length ``halves`` [m]) over the odd modes 1, 3, …, 2 ``n_odd`` − 1, as three arrays
    y₁, v₁, y₁''; other arguments as there.

    The same terms (:func:`_mode_term`) summed in the same order, so the same values to the last bit; the
    loop over spans is innermost and has no jumps (a resonant or buckled mode, or a pulse longer than the
    (half) period, makes its span NaN by arithmetic) and no library calls (:func:`sincos`), so it runs in
    SIMD instructions, about 8 times faster than the scalar loop."""
    size = spans.size
    y, v, curv = np.zeros(size), np.zeros(size), np.zeros(size)  # three arrays, not rows of one: no alias
    k1, weight_1, u_1, s_n, c_n, s_2, c_2 = _span_factors(spans, durations, halves, mass)
    longest = period if one_wall else 0.5 * period
    for i in range(size):
        if not durations[i] <= longest:
            y[i] = v[i] = curv[i] = math.nan
    inv_mass = 1.0 / mass
    for j in range(n_odd):
        n = 2.0 * j + 1.0
        for i in range(size):
            q, qd, k2, shape, bad = _mode_term(n, k1[i], halves[i], durations[i], u_1[i], ei, tension, inv_mass,
                                               period, one_wall, tol, code, s_n[i], c_n[i])
            q, qd = (math.nan, math.nan) if bad else (q, qd)
            s_n[i], c_n[i] = s_n[i] * c_2[i] + c_n[i] * s_2[i], c_n[i] * c_2[i] - s_n[i] * s_2[i]
            weight = weight_1[i] * shape
            y[i] += weight * q
            v[i] += weight * qd
            curv[i] -= weight * k2 * q
    return y, v, curv


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _accumulate_modes(out, k1, weight_1, u_1, s_n, c_n, s_2, c_2, halves, durations, n_odd, ei, tension, inv_mass,
                      period, one_wall, tol, code, velocity):
    """The modal sum of :func:`midspan_sums` into ``out``, the loop over spans innermost (as :func:`midspan_states`)."""
    for j in range(n_odd):
        n = 2.0 * j + 1.0
        for i in range(out.size):
            q, qd, _, shape, bad = _mode_term(n, k1[i], halves[i], durations[i], u_1[i], ei, tension, inv_mass,
                                              period, one_wall, tol, code, s_n[i], c_n[i])
            term = math.nan if bad else qd if velocity else q
            s_n[i], c_n[i] = s_n[i] * c_2[i] + c_n[i] * s_2[i], c_n[i] * c_2[i] - s_n[i] * s_2[i]
            out[i] += weight_1[i] * shape * term


@numba.njit(cache=True, nogil=True, error_model="numpy")
def midspan_sums(spans, durations, halves, n_odd, ei, tension, mass, period, one_wall, code, tol, velocity):
    """y₁ (``velocity`` False) or v₁ (True) of :func:`midspan_states` alone, the same terms in the same order (so
    the same values to the last bit), without the arithmetic of the other two: about an eighth less time (the
    span search's samples need the closure residual only)."""
    size = spans.size
    out = np.zeros(size)
    k1, weight_1, u_1, s_n, c_n, s_2, c_2 = _span_factors(spans, durations, halves, mass)
    longest = period if one_wall else 0.5 * period
    for i in range(size):
        if not durations[i] <= longest:
            out[i] = math.nan
    inv_mass = 1.0 / mass
    if velocity:  # two call sites with a constant each: the compiler drops the other quantity's arithmetic
        _accumulate_modes(out, k1, weight_1, u_1, s_n, c_n, s_2, c_2, halves, durations, n_odd, ei, tension, inv_mass,
                          period, one_wall, tol, code, True)
    else:
        _accumulate_modes(out, k1, weight_1, u_1, s_n, c_n, s_2, c_2, halves, durations, n_odd, ei, tension, inv_mass,
                          period, one_wall, tol, code, False)
    return out


def midspan_state_at_pulse_start(span_length, pulse_duration, half_length, modes, bending_stiffness, tension,
                                 mass, period, pattern="one_wall", shape="point", resonance_tol=1e-15):
    """Midspan displacement y₁ [m/(N s)], velocity v₁ [m/(N s²)] and curvature y₁'' [1/(m N s)] at the
    start of a pulse, per unit impulse along +y, summed over ``modes`` (compiled loop).

    y₁ = Σ_n w_n q_n(0), v₁ = Σ_n w_n q̇_n(0), y₁'' = −Σ_n w_n k_n² q_n(0) with w_n = 2 g_n sin(nπ/2)/(M L)
    (the midspan value of the modal coordinate per unit impulse, :func:`modal_load_factors`) and
    (q_n(0), q̇_n(0)) of :func:`modal_state_at_pulse_start` — the same closed form, one loop instead of
    a spans × modes array: the span search evaluates it for 10⁵ spans.

    span_length L [m], pulse_duration T_L [s], half_length b [m] broadcast together (shape S);
    modes: odd mode numbers, shape (k,) for every span or S + (k,) per span; bending_stiffness EI
    [N m²], tension T [N], mass M [kg/m], period τ [s]; pattern, shape and resonance_tol as
    :func:`modal_periodic_response` and :func:`modal_load_factors`. NaN wherever a kept mode is
    resonant or buckled, or the pulse is longer than the (half) period. Returns three arrays of shape S.
    """
    check_choice("pattern", pattern, IMPACT_PATTERNS)
    check_choice("shape", shape, LOAD_SHAPES)
    span, tl, half = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (span_length, pulse_duration, half_length)))
    modes = np.asarray(modes, dtype=float)
    consecutive = modes.ndim <= 1 and np.array_equal(modes.ravel(), np.arange(1.0, 2.0 * modes.size, 2.0))
    if consecutive:  # the SIMD loop over spans
        return tuple(v.reshape(span.shape) for v in midspan_states(
            np.ascontiguousarray(span.ravel()), np.ascontiguousarray(tl.ravel()), np.ascontiguousarray(half.ravel()),
            modes.size, float(bending_stiffness), float(tension), float(mass), float(period), pattern == "one_wall",
            SHAPE_CODES[shape], float(resonance_tol)))
    if modes.ndim <= 1:
        table = modes.reshape(1, -1)
    else:
        table = np.broadcast_to(modes, span.shape + modes.shape[-1:]).reshape(-1, modes.shape[-1])
    out = _midspan_state_kernel(np.ascontiguousarray(span.ravel()), np.ascontiguousarray(tl.ravel()),
                                np.ascontiguousarray(half.ravel()), np.ascontiguousarray(table), float(bending_stiffness),
                                float(tension), float(mass), float(period), pattern == "one_wall",
                                SHAPE_CODES[shape], float(resonance_tol), consecutive)
    return tuple(out[i].reshape(span.shape) for i in range(3))


#: Relative rounding allowance of :func:`excursion_verdicts` per unit of each term's size (a few hundred times
#: the double precision's 1.1e-16: the library's and :func:`sincos`'s last bits, the phase rotation of
#: :func:`largest_excursion` over its runs of 32 steps, and the sum of a few dozen terms).
_VERDICT_ROUNDING = 1e-13


#: Times of :func:`excursion_verdicts` summed at once: a whole number of SIMD blocks (a loop of fewer ran without
#: SIMD instructions).
_VERDICT_BLOCK = 8


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _verdicts_kernel(t, spans, durations, halves, n_odd, ei, tension, mass, period, one_wall, code, tol, limit,
                     first):
    rows, count = t.shape
    out = np.full(rows, -1, dtype=np.int8)
    p = period if one_wall else 0.5 * period
    tm = np.empty((rows, count))
    t_max, margin = np.zeros(rows), np.zeros(rows)
    usable = np.ones(rows, dtype=np.bool_)
    for r in range(rows):
        for i in range(count):
            tm[r, i] = t[r, i] - math.floor(t[r, i] / p) * p
            usable[r] = usable[r] and tm[r, i] > durations[r]  # after the pulse
            t_max[r] = max(t_max[r], tm[r, i])
        usable[r] = usable[r] and durations[r] <= p and durations[r] > 0.0 and spans[r] > 0.0
    # the modes' factors of every row, the loop over rows innermost (SIMD, as midspan_states)
    om, phi, kappa, fw = np.empty((n_odd, rows)), np.empty((n_odd, rows)), np.empty((n_odd, rows)), np.empty((n_odd, rows))
    k1, weight_1, u_1, s_n, c_n, s_2, c_2 = _span_factors(spans, durations, halves, mass)
    inv_mass = 1.0 / mass
    small = 1e-2 * _VERDICT_ROUNDING
    for j in range(n_odd):
        n = 2.0 * j + 1.0
        for r in range(rows):
            w, nu, kap, _, _, amp, shape, _, bad = _mode_factors(n, k1[r], halves[r], durations[r], u_1[r], ei, tension,
                                                                 inv_mass, period, one_wall, tol, code, s_n[r], c_n[r])
            s_n[r], c_n[r] = s_n[r] * c_2[r] + c_n[r] * s_2[r], c_n[r] * c_2[r] - s_n[r] * s_2[r]
            f = weight_1[r] * shape * 0.5 * amp / w
            om[j, r], phi[j, r], kappa[j, r], fw[j, r] = w, 0.5 * w * durations[r], kap, f
            term = abs(f) * ((1.0 + abs(kap)) * (small * w * t_max[r] + _VERDICT_ROUNDING)
                             + small * math.pi * (1.0 + kap * kap) * (nu + 1.0))
            margin[r] += math.nan if bad else term
    y, times = np.empty(count + _VERDICT_BLOCK), np.empty(count + _VERDICT_BLOCK)
    for r in range(rows):
        if not (usable[r] and math.isfinite(margin[r])):
            continue  # undecided: largest_excursion says
        out[r] = 0
        start = 0
        for stop in (min(first, count), count):  # the first times, then (if none is past the limit) the rest
            if stop <= start:
                continue
            # whole blocks (_VERDICT_BLOCK), the last time repeated: the largest |y| is unchanged
            size = -(-(stop - start) // _VERDICT_BLOCK) * _VERDICT_BLOCK
            for i in range(size):
                times[i] = tm[r, min(start + i, stop - 1)]
            sums = y[:size]
            sums[:] = 0.0
            for j in range(n_odd):
                w, ph, kap, f = om[j, r], phi[j, r], kappa[j, r], fw[j, r]
                for i in range(sums.size):
                    s, c = sincos(w * times[i] - ph)
                    sums[i] += f * (s + kap * c)
            for i in range(size):
                largest = abs(sums[i])
                if largest - margin[r] > limit[r]:
                    out[r] = 1
                elif not largest + margin[r] <= limit[r] and out[r] == 0:
                    out[r] = -1
            if out[r] == 1:
                break
            start = stop
    return out


def excursion_verdicts(t, spans, durations, halves, n_odd, bending_stiffness, tension, mass, period,
                       pattern="one_wall", shape="point", resonance_tol=1e-15, limit=None, first=8):
    """Whether the midspan's deflection per unit impulse exceeds ``limit`` at any of the times ``t`` after the
    pulse, per row: 1 it does, 0 it does not, −1 undecided — the verdict of :func:`largest_excursion`
    (``largest_excursion(...) > limit``, its weights 2|g_n|/(M L) of the odd modes 1, 3, …, 2 ``n_odd`` − 1 at
    x = L/2) without its library calls, decided only where the two cannot disagree.

    t [s] of shape (R, T); spans L [m], durations T_L [s], halves b [m] and limit [m/(N s)] of shape (R,); the
    rest as :func:`midspan_states`. The modal sum of each time is evaluated with :func:`sincos`, the modes'
    factors as :func:`_mode_term`, so each term differs from :func:`largest_excursion`'s by rounding only;
    a row is decided where its largest |y| is farther from ``limit`` than a bound on that rounding, summed over
    the modes: |f_n| [(1 + |κ_n|)(ε ω_n t + ε₀) + ε π (1 + κ_n²)(ν_n + 1)], f_n = w_n A_n/(2ω_n), ε₀ =
    :data:`_VERDICT_ROUNDING` and ε = ε₀/100 [-] per radian of phase ω_n t and per unit of ν_n = ω_n τ/2π (κ's
    sensitivity to it near a resonance). Undecided: a row within that bound of its limit, with a resonant or
    buckled mode, a pulse longer than the (half) period or a time inside the pulse — ask
    :func:`largest_excursion`. The first ``first`` times are summed first, and a row past its limit there
    stops; put the times most likely to exceed first."""
    check_choice("pattern", pattern, IMPACT_PATTERNS)
    check_choice("shape", shape, LOAD_SHAPES)
    t = np.ascontiguousarray(np.asarray(t, dtype=float))
    rows = t.shape[0]
    spans, durations, halves, limit = (np.ascontiguousarray(np.broadcast_to(np.asarray(v, dtype=float), (rows,)))
                                       for v in (spans, durations, halves, np.inf if limit is None else limit))
    return _verdicts_kernel(t, spans, durations, halves, int(n_odd), float(bending_stiffness), float(tension),
                            float(mass), float(period), pattern == "one_wall", SHAPE_CODES[shape],
                            float(resonance_tol), limit, int(first))
