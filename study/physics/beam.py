"""Simply supported beam-column under a periodic train of impact pulses at midspan.

The building blocks of the periodic impact solution (docs/model.md §2–5, §9 "fast periodic"):

    EI y'''' − T y'' + M ÿ = f(t) g(x),    y = y'' = 0 at x = 0, L          (docs/model.md §2, paper eq. 1)

undamped, T the effective tension (may be ≤ 0 but above buckling). Modes φ_n = sin(k_n x),
k_n = nπ/L, ω_n² = (EI k_n⁴ + T k_n²)/M, modal mass M L/2. The load is Lee's half-sine
f(t) = F̂ sin(π t/T_L) on 0 ≤ t ≤ T_L of impulse J (paper eq. 15), repeated with period τ
(``pattern``, docs/model.md §4), spread at midspan over the contact half-length b with a shape g(x)
of unit integral (``shape``, paper eq. 18–24). With h(t) = f(t)/J the unit-impulse pulse train,

    y(x, t) = Σ_n [J g_n/(M L/2)] q_n(t) sin(k_n x),   q̈_n + ω_n² q_n = h(t),

where q_n is the exact periodic solution in closed form (:func:`modal_periodic_response`).
The quasi-static split y = J h(t) G(x) + Σ_n [J g_n/(M L/2)] (q_n − h/ω_n²) sin(k_n x), G the
static deflection under the unit spread load in closed form (:func:`static_deflection`), makes
moment and shear converge in few modes (docs/model.md §9).

Beside it: the midspan state of many spans at once, the span search's compiled kernels, in
:mod:`study.physics.midspan`; the paper's double Fourier series of the same response in :mod:`study.physics.fourier`.

Pure functions of numpy arrays, SI units, no I/O.
"""

from __future__ import annotations

import math
from math import factorial
from typing import NamedTuple

import numba
import numpy as np

#: Spatial distributions of the impact load g(x), each of unit integral, centred at midspan.
LOAD_SHAPES = {
    "point": "Dirac δ(x − L/2); g_n = sin(nπ/2)",
    "uniform": "1/(2b) on |x − L/2| ≤ b; g_n = sin(nπ/2) sin(k_n b)/(k_n b)",
    "parabolic": "3/(4b) (1 − ((x − L/2)/b)²) on |x − L/2| ≤ b (semi-ellipsoidal Hertz pressure "
    "integrated across the contact width, paper eq. 18–21); g_n = sin(nπ/2) 3(sin β − β cos β)/β³, β = k_n b",
}

#: Impact patterns over one period τ (docs/model.md §4).
IMPACT_PATTERNS = {
    "one_wall": "one pulse +f at t = 0 per period τ (mean force J/τ, all harmonics of 2π/τ)",
    "alternating": "+f at t = 0 and −f at t = τ/2 (both walls; odd harmonics only, no mean)",
}


class ModalResponse(NamedTuple):
    displacement: np.ndarray  #: q(t) [s] (response per unit impulse of the unit-mass oscillator)
    velocity: np.ndarray  #: q̇(t) [-]


def check_choice(name, value, allowed):
    """Refuse `value` of the option `name` unless it is one of `allowed` (ValueError naming the three)."""
    if value not in allowed:
        raise ValueError(f"{name} = {value!r}; allowed: {', '.join(allowed)}")


# --- modal load factors ------------------------------------------------------------------------
def wavenumbers(span_length, modes):
    """k_n = nπ/L [1/m]; span_length L [m] (broadcast against the last axis ``modes``)."""
    return np.asarray(modes, dtype=float) * np.pi / np.asarray(span_length, dtype=float)[..., None]


#: Maclaurin coefficients of 3(sin β − β cos β)/β³ in powers of β², highest power first (np.polyval).
PARABOLIC_SERIES = np.array([(-1) ** (j + 1) * 6.0 * j / factorial(2 * j + 1) for j in range(9, 0, -1)])


def _parabolic_factor(beta):
    """3(sin β − β cos β)/β³ = 3 j₁(β)/β [-], with its Maclaurin series for |β| < 0.5."""
    beta = np.asarray(beta, dtype=float)
    small = np.abs(beta) < 0.5
    series = np.polyval(PARABOLIC_SERIES, np.where(small, beta, 0.0) ** 2)
    bl = np.where(small, 1.0, beta)
    return np.where(small, series, 3.0 * (np.sin(bl) - bl * np.cos(bl)) / bl**3)


def modal_load_factors(modes, span_length, half_length=0.0, shape="point"):
    """Modal load factors g_n = ∫₀ᴸ g(x) sin(k_n x) dx [-] of the unit midspan load (paper eq. 18–24).

    modes: mode numbers n; span_length L [m]; half_length b [m] (contact half-length, ignored
    for ``"point"``); shape one of :data:`LOAD_SHAPES`. Closed forms, β = k_n b:

    - point: g_n = sin(nπ/2);
    - uniform: g_n = sin(nπ/2) sin β/β;
    - parabolic: g_n = sin(nπ/2) · 3(sin β − β cos β)/β³, from ∫₋₁¹ (1 − s²) cos(βs) ds =
      4(sin β − β cos β)/β³ (series for small β, where the closed form cancels).

    Even modes give 0 (symmetric load). The last axis runs over ``modes``.
    """
    check_choice("shape", shape, LOAD_SHAPES)
    n = np.asarray(modes, dtype=float)
    parity = np.where(n % 2 == 1, np.where(n % 4 == 1, 1.0, -1.0), 0.0)  # sin(nπ/2), exact
    if shape == "point":
        return parity * np.ones_like(np.asarray(span_length, dtype=float))[..., None]
    beta = wavenumbers(span_length, n) * np.asarray(half_length, dtype=float)[..., None]
    if shape == "uniform":
        return parity * np.sinc(beta / np.pi)
    return parity * _parabolic_factor(beta)


def load_shape(x, span_length, half_length, shape="uniform"):
    """Line-load density g(x) [1/m] of unit integral (``"uniform"`` or ``"parabolic"``).

    x [m], span_length L [m], half_length b [m]. The Dirac ``"point"`` shape has no density.
    """
    check_choice("shape", shape, ("uniform", "parabolic"))
    xi = (np.asarray(x, dtype=float) - 0.5 * np.asarray(span_length)) / np.asarray(half_length)
    inside = np.abs(xi) <= 1.0
    if shape == "uniform":
        return np.where(inside, 0.5 / np.asarray(half_length), 0.0)
    return np.where(inside, 0.75 / np.asarray(half_length) * (1.0 - xi**2), 0.0)


# --- the pulse and its periodic train -----------------------------------------------------------
def unit_pulse(t, pulse_duration):
    """Lee's half-sine of unit impulse, h(t) = (π/(2T_L)) sin(π t/T_L) on 0 ≤ t ≤ T_L [1/s] (eq. 15)."""
    t, tl = np.asarray(t, dtype=float), np.asarray(pulse_duration, dtype=float)
    inside = (t >= 0.0) & (t <= tl)
    return np.where(inside, 0.5 * np.pi / tl * np.sin(np.pi * t / tl), 0.0)


def pulse_spectrum(omega, pulse_duration):
    """H(ω) = ∫ h(t) e^{−iωt} dt = e^{−iωT_L/2} cos(ωT_L/2)/(1 − u²), u = ωT_L/π [-] (complex).

    omega [rad/s], pulse_duration T_L [s]. Evaluated as (π/2) sinc((1 − u)/2)/(1 + u) (np.sinc),
    regular at u = 1 (value π/4); H(0) = 1 (unit impulse).
    """
    om, tl = np.asarray(omega, dtype=float), np.asarray(pulse_duration, dtype=float)
    u = om * tl / np.pi
    with np.errstate(divide="ignore", invalid="ignore"):
        amp = 0.5 * np.pi * np.sinc(0.5 * (1.0 - u)) / (1.0 + u)
    return np.exp(-0.5j * om * tl) * amp


def _wrap(t, period, pattern):
    """(local time in [0, P), sign, P): P = τ (one_wall) or τ/2 with sign (−1)^k (alternating)."""
    t, tau = np.asarray(t, dtype=float), np.asarray(period, dtype=float)
    half = pattern == "alternating"
    p = 0.5 * tau if half else tau
    k = np.floor(t / p)
    sign = np.where(k % 2 == 0, 1.0, -1.0) if half else np.ones_like(k)
    return t - k * p, sign, p


def pulse_train(t, pulse_duration, period, pattern="one_wall"):
    """Periodic unit-impulse pulse train h(t) [1/s]: :func:`unit_pulse` repeated per ``pattern``.

    t [s] (any real), pulse_duration T_L [s], period τ [s]; pattern one of :data:`IMPACT_PATTERNS`.
    """
    check_choice("pattern", pattern, IMPACT_PATTERNS)
    tm, sign, _ = _wrap(t, period, pattern)
    return sign * unit_pulse(tm, pulse_duration)


def resonance_distance(omega_n, period, pattern="one_wall"):
    """Distance to the nearest resonance, in harmonics of 2π/τ [-].

    With ν = ω τ/(2π) (natural frequency in harmonics of the rotation): the undamped periodic
    response is infinite where the train has a harmonic at ω, i.e. ν integer (one_wall) or ν odd
    (alternating). Returns |ν − ν_res| for the nearest resonant ν_res: in [0, 1/2] for one_wall,
    [0, 1] for alternating. The response amplitude grows like 1/(ω · distance).
    """
    check_choice("pattern", pattern, IMPACT_PATTERNS)
    nu = np.asarray(omega_n, dtype=float) * np.asarray(period, dtype=float) / (2.0 * np.pi)
    if pattern == "one_wall":
        return np.abs(nu - np.round(nu))
    return np.abs(nu - (2.0 * np.round(0.5 * (nu - 1.0)) + 1.0))


def _echo(om, tl, tau, pattern, resonance_tol):
    """(bad, ω with bad entries set to 1, C − 1): the vanishing-damping echo of the earlier pulses,
    C − 1 = ½ (−1 + i cot(ωP/2)) (one_wall, P = τ) or ½ (−1 − i tan(ωP/2)) (alternating, P = τ/2), and the
    mask of resonant ω, pulses longer than P, and NaN ω (see :func:`modal_periodic_response`)."""
    p = 0.5 * tau if pattern == "alternating" else tau
    nu = om * tau / (2.0 * np.pi)  # ω in harmonics of 2π/τ
    bad = (resonance_distance(om, tau, pattern) <= resonance_tol * np.maximum(1.0, nu)) | (tl > p) | ~np.isfinite(om)
    oms = np.where(bad, 1.0, om)
    half = 0.5 * oms * p
    with np.errstate(divide="ignore", invalid="ignore"):
        if pattern == "one_wall":
            return bad, oms, -0.5 + 0.5j * np.cos(half) / np.sin(half)
        return bad, oms, -0.5 - 0.5j * np.sin(half) / np.cos(half)


def modal_periodic_response(t, omega_n, pulse_duration, period, pattern="one_wall", resonance_tol=1e-15):
    """Exact steady periodic response of q̈ + ω² q = h(t) to the unit-impulse pulse train (closed form).

    t [s] (any real; broadcast against omega_n, e.g. t[:, None] with omega_n[None, :]), omega_n ω
    [rad/s], pulse_duration T_L [s], period τ [s], pattern one of :data:`IMPACT_PATTERNS`.
    Returns ModalResponse(q [s], q̇ [-]); the modal coordinate of the beam is J g_n/(M L/2) · q.

    Construction (no Fourier series in time). Let P = τ (one_wall) or τ/2 (alternating, where the
    motion is anti-periodic over τ/2: q(t + τ/2) = −q(t)); t is wrapped into [0, P). On [0, P) the
    response is the pulse from rest plus the free vibration left by all earlier pulses,

        q(t) = q_p(t) + Im[e^{iωt} H(ω) (C − 1)]/ω,   q̇ = q̇_p(t) + Re[e^{iωt} H(ω) (C − 1)],

    with H the pulse spectrum (:func:`pulse_spectrum`), and C − 1 = Σ_{m≥1} (±e^{iωP})^m the (Abel-
    summed, i.e. vanishing-damping) echo of earlier pulses: C = 1/(1 − e^{iωP}) = ½ + (i/2) cot(ωP/2)
    (one_wall) or 1/(1 + e^{iωP}) = ½ − (i/2) tan(ωP/2) (alternating). This is the same as solving the
    2×2 periodicity condition (I ∓ Φ(P)) s₀ = ±Φ(P − T_L) s(T_L) for the state s₀ at the pulse start
    (Φ the free-vibration transition matrix). The pulse from rest, a = π/T_L, S(z) = sin z/z:

        0 ≤ t ≤ T_L: q_p = a/(2ω(ω+a)) [sin ωt − ωt cos((ω+a)t/2) S((ω−a)t/2)],
                     q̇_p = a²/(2(ω+a)) t sin((ω+a)t/2) S((ω−a)t/2)       (regular at ω = a),
        t > T_L:     q_p = Im(e^{iωt} H)/ω,  q̇_p = Re(e^{iωt} H)            (Duhamel).

    Impulse limit (T_L → 0): q = cos(ω(t − τ/2))/(2ω sin(ωτ/2)) (one_wall), sin(ω(t − τ/4))/(2ω cos(ωτ/4))
    (alternating) on 0 < t < P. NaN where :func:`resonance_distance` ≤ resonance_tol·max(1, ν), where
    the pulse does not fit in P (T_L > P), or where ω is NaN (buckled mode).
    """
    check_choice("pattern", pattern, IMPACT_PATTERNS)
    tm, sign, p = _wrap(t, period, pattern)
    om = np.asarray(omega_n, dtype=float)
    tl = np.asarray(pulse_duration, dtype=float)
    tm, sign, om, tl, p = np.broadcast_arrays(tm, sign, om, tl, p)
    a = np.pi / tl
    tau = 2.0 * p if pattern == "alternating" else p
    bad, oms, c_minus_one = _echo(om, tl, tau, pattern, resonance_tol)
    with np.errstate(divide="ignore", invalid="ignore"):
        hw = pulse_spectrum(oms, tl)
        ph = np.exp(1j * oms * tm) * hw
        free = ph * c_minus_one
        during = tm <= tl
        s = np.sinc((oms - a) * tm / (2.0 * np.pi))
        q_in = a / (2.0 * oms * (oms + a)) * (np.sin(oms * tm) - oms * tm * np.cos(0.5 * (oms + a) * tm) * s)
        v_in = a**2 / (2.0 * (oms + a)) * tm * np.sin(0.5 * (oms + a) * tm) * s
        q = np.where(during, q_in, ph.imag / oms) + free.imag / oms
        v = np.where(during, v_in, ph.real) + free.real
    return ModalResponse(np.where(bad, np.nan, sign * q), np.where(bad, np.nan, sign * v))


@numba.njit(cache=True, nogil=True)
def _loaded_spectrum_kernel(omega, spans, modes, durations, halves, code):
    real, imag = np.empty(omega.size), np.empty(omega.size)
    for i in range(omega.size):
        real[i], imag[i] = loaded_spectrum_one(omega[i], spans[i], modes[i], durations[i], halves[i], code)
    return real, imag


@numba.njit(cache=True, nogil=True)
def loaded_spectrum_one(omega, span, mode, duration, half, code):
    """(real, imaginary part) of :func:`loaded_pulse_spectrum` at one ω [rad/s], compiled; ``code``:
    the load shape's (``SHAPE_CODES``)."""
    g = abs(_shape_factor(mode * math.pi / span * half, code))
    phi = 0.5 * omega * duration
    c = math.cos(phi)
    amp = g * _echo_amplitude(omega * duration / math.pi, c)
    return amp * c, -amp * math.sin(phi)


def loaded_pulse_spectrum(omega, span_length, modes, pulse_duration, half_length=0.0, shape="point"):
    """|g_n| H(ω) [-] per element: the size of the modal load factor of odd mode n
    (:func:`modal_load_factors`) times the pulse spectrum at ω (:func:`pulse_spectrum`), returned as
    (real part, imaginary part); compiled, one pass (the span search weighs every resonance with it).

    omega ω [rad/s], span_length L [m], modes n (odd), pulse_duration T_L [s], half_length b [m]
    broadcast together; shape one of :data:`LOAD_SHAPES`.
    """
    check_choice("shape", shape, LOAD_SHAPES)
    args = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (omega, span_length, modes, pulse_duration,
                                                                        half_length)))
    real, imag = _loaded_spectrum_kernel(*(np.array(v).ravel() for v in args), SHAPE_CODES[shape])
    return real.reshape(args[0].shape), imag.reshape(args[0].shape)


def modal_state_at_pulse_start(omega_n, pulse_duration, period, pattern="one_wall", resonance_tol=1e-15):
    """State (q(0), q̇(0)) of the steady periodic response at the start of a pulse, closed form.

    The same values as :func:`modal_periodic_response` at t = 0, where the pulse-from-rest part is
    zero and only the echo of the earlier pulses remains, q = Im[H(ω)(C − 1)]/ω, q̇ = Re[H(ω)(C − 1)].
    In real arithmetic (the form the compiled kernels use, :func:`_echo_factors`): with φ = ωT_L/2,
    H = A e^{−iφ}, A = cos φ/(1 − u²) (u = ωT_L/π, as :func:`pulse_spectrum`) and C − 1 = ½(−1 + iκ),
    κ = cot(ωτ/2) (one_wall) or −tan(ωτ/4) (alternating),

        q(0) = A (κ cos φ + sin φ)/(2ω),   q̇(0) = A (κ sin φ − cos φ)/2.

    Arguments and units as :func:`modal_periodic_response`; NaN where it is NaN. The span search
    sums it over modes with :func:`midspan_state_at_pulse_start`.
    """
    check_choice("pattern", pattern, IMPACT_PATTERNS)
    tl = np.asarray(pulse_duration, dtype=float)
    bad, oms, c_minus_one = _echo(np.asarray(omega_n, dtype=float), tl, np.asarray(period, dtype=float),
                                  pattern, resonance_tol)
    with np.errstate(divide="ignore", invalid="ignore"):
        free = pulse_spectrum(oms, tl) * c_minus_one
    return ModalResponse(np.where(bad, np.nan, free.imag / oms), np.where(bad, np.nan, free.real))


#: Load shapes as the integer codes of :func:`_midspan_state_kernel`.
SHAPE_CODES = {"point": 0, "uniform": 1, "parabolic": 2}


@numba.njit(cache=True, nogil=True)
def _shape_factor(beta, code, sin_beta=math.nan, cos_beta=math.nan):
    """|g_n| for an odd mode: 1 (point), sin β/β (uniform), 3(sin β − β cos β)/β³ (parabolic).

    ``sin_beta``, ``cos_beta``: sin β and cos β when the caller has them (NaN: computed here)."""
    if code == 0:
        return 1.0
    if code == 1:
        if beta == 0.0:
            return 1.0
        return (math.sin(beta) if math.isnan(sin_beta) else sin_beta) / beta
    b2 = beta * beta
    if abs(beta) < 0.5:  # Maclaurin series (as _parabolic_factor): 1 − β²/10 + β⁴/280 − β⁶/15120 + …
        acc = 0.0
        for j in range(PARABOLIC_SERIES.size):  # Horner in β² (highest power first, as np.polyval)
            acc = acc * b2 + PARABOLIC_SERIES[j]
        return acc
    if math.isnan(sin_beta):
        sin_beta, cos_beta = math.sin(beta), math.cos(beta)
    return 3.0 * (sin_beta - beta * cos_beta) / (b2 * beta)


@numba.njit(cache=True, nogil=True)
def _echo_kappa(om, tl, period, one_wall, tol):
    """(bad, κ) of one mode for the compiled kernels: the resonance/overlong-pulse mask (as
    :func:`resonance_distance`) and κ with C − 1 = ½(−1 + iκ) (cot(ωτ/2) or −tan(ωτ/4)).

    Both are read from ν = ωτ/(2π), resonant at whole ν (one_wall) or odd ν (alternating), and its
    distance d to the nearest such ν: κ = cot(πd) (one_wall) or cot(πd/2) (alternating, from
    −tan(πν/2) with ν odd + d). The reduced angle keeps the tangent's argument within ±π/2 (its
    argument reduction from ωτ/2, thousands of radians, was half the span search's time) and carries
    the same rounding as ωτ itself."""
    nu = om * period * (0.5 / math.pi)
    if one_wall:
        d = nu - round(nu)
    else:
        d = nu - (2.0 * round(0.5 * (nu - 1.0)) + 1.0)
    if not math.isfinite(om) or tl > (period if one_wall else 0.5 * period) or abs(d) <= tol * max(1.0, nu):
        return True, 0.0
    return False, 1.0 / math.tan(math.pi * d if one_wall else 0.5 * math.pi * d)


@numba.njit(cache=True, nogil=True)
def _echo_factors(om, tl, period, one_wall, tol):
    """(bad, κ, φ, A) of one mode: :func:`_echo_kappa`, φ = ωT_L/2 and A = cos φ/(1 − u²) =
    (π/2) sinc((1 − u)/2)/(1 + u), u = ωT_L/π (:func:`_echo_amplitude`)."""
    bad, kappa = _echo_kappa(om, tl, period, one_wall, tol)
    if bad:
        return True, 0.0, 0.0, 0.0
    phi = 0.5 * om * tl
    return False, kappa, phi, _echo_amplitude(om * tl / math.pi, math.cos(phi))


@numba.njit(cache=True, nogil=True)
def _echo_amplitude(u, cos_phi):
    """A = cos φ/(1 − u²) with φ = πu/2, as (π/2) sinc((1 − u)/2)/(1 + u) near u = 1 where both
    factors of the first form vanish (sin(π(1 − u)/2) = cos φ)."""
    d = 0.5 * (1.0 - u)
    if abs(d) > 1e-3:
        return cos_phi / ((1.0 - u) * (1.0 + u))
    return 0.5 * math.pi * (1.0 if d == 0.0 else math.sin(math.pi * d) / (math.pi * d)) / (1.0 + u)


@numba.njit(cache=True, nogil=True)
def _since_last_pulse(t, p, one_wall):
    """(time since the last pulse in [0, P), sign (−1)^k of the alternating train, the pulse's number
    k), as :func:`_wrap`."""
    k = math.floor(t / p)
    return t - k * p, (1.0 if one_wall or k % 2 == 0 else -1.0), k


@numba.njit(cache=True, nogil=True)
def _modal_displacement(tm, om, tl, kappa, phi, amp):
    """q at the time tm ∈ [0, P) since the last pulse, given the mode's :func:`_echo_factors`."""
    psi = om * tm - phi
    s, c = math.sin(psi), math.cos(psi)
    if tm <= tl:  # pulse from rest + echo of the earlier pulses
        a = math.pi / tl
        z = 0.5 * (om - a) * tm
        sinc = 1.0 if z == 0.0 else math.sin(z) / z
        q = a / (2.0 * om * (om + a)) * (math.sin(om * tm) - om * tm * math.cos(0.5 * (om + a) * tm) * sinc)
        return q + 0.5 * amp / om * (kappa * c - s)
    return 0.5 * amp / om * (s + kappa * c)  # free vibration after the pulse, its echo included


#: Steps a uniform run of times is advanced by rotation before sin, cos are evaluated afresh (bounds
#: the drift of the rotation to a few rounding errors of the phase per step).
_ROTATION_STEPS = 32


@numba.njit(cache=True, nogil=True)
def _phases_at(tm, prev_tm, continuing, omega, phi, p, sin_psi, cos_psi, turn_c, turn_s, run_step, steps):
    """sin ψ_j, cos ψ_j with ψ_j = ω_j tm − φ_j for every mode, in place; returns (run_step, steps).

    ``continuing``: sin_psi, cos_psi hold the phases at prev_tm (the same pulse interval), so they are
    turned by ω_j (tm − prev_tm) instead of evaluated: along a run of equal steps (equal to a few
    roundings of the pulse interval ``p``: the grids come from linspace) turn_c, turn_s = cos, sin ω_jΔ are
    computed once, at the run's first step, and the phases are evaluated afresh every
    _ROTATION_STEPS steps."""
    if continuing:
        step = tm - prev_tm
        if abs(step - run_step) > 8.0 * 2.220446049250313e-16 * p:  # a new run: its turn per step
            run_step, steps = step, 0
            for j in range(omega.size):
                turn_c[j], turn_s[j] = math.cos(omega[j] * step), math.sin(omega[j] * step)
        if steps < _ROTATION_STEPS:
            for j in range(omega.size):
                s = sin_psi[j] * turn_c[j] + cos_psi[j] * turn_s[j]
                cos_psi[j] = cos_psi[j] * turn_c[j] - sin_psi[j] * turn_s[j]
                sin_psi[j] = s
            return run_step, steps + 1
    for j in range(omega.size):
        psi = omega[j] * tm - phi[j]
        sin_psi[j], cos_psi[j] = math.sin(psi), math.cos(psi)
    return run_step, 0


@numba.njit(cache=True, nogil=True)
def _periodic_displacement_kernel(t, omega, tl, tau, one_wall, tol, factor, static):
    # out[:, j] = factor_j (q_j − static h/ω_j²), out[:, -1] = h (the pulse train, sign included)
    n_t, n_m = t.size, omega.size
    out = np.empty((n_t, n_m + 1))
    p = tau if one_wall else 0.5 * tau
    a = math.pi / tl
    # per mode: A = cos φ/(1 − u²), φ = ωT_L/2, κ (C − 1 = ½(−1 + iκ)), and the resonance mask
    amp, phi, kappa = np.empty(n_m), np.empty(n_m), np.empty(n_m)
    bad = np.empty(n_m, dtype=np.bool_)
    for j in range(n_m):
        bad[j], kappa[j], phi[j], amp[j] = _echo_factors(omega[j], tl, tau, one_wall, tol)
    free_amp = np.where(bad, np.nan, 0.5 * amp / omega)  # A/(2ω)
    free_factor = free_amp * factor
    pulse_static = static / omega**2
    cos_phi, sin_phi = np.cos(phi), np.sin(phi)
    pulse_amp = a / (2.0 * omega * (omega + a))
    near = np.abs(omega - a) * tl < 2e-2  # ω ≈ π/T_L: the pulse from rest by its sinc form
    # q = A (sin ψ + κ cos ψ)/(2ω), ψ = ωt_P − φ, after the pulse; during it the pulse from rest
    # a/(2ω(ω + a)) (sin ωt_P − ω (sin ωt_P − sin at_P)/(ω − a)), a = π/T_L, is added and the echo
    # has −sin ψ. The phases ψ turn along the grid (_phases_at).
    sin_psi, cos_psi, turn_c, turn_s = np.empty(n_m), np.empty(n_m), np.empty(n_m), np.empty(n_m)
    run_step, steps, prev_tm, prev_k = -1.0, 0, 0.0, -1
    for i in range(n_t):
        tm, sign, k = _since_last_pulse(t[i], p, one_wall)
        run_step, steps = _phases_at(tm, prev_tm, i > 0 and k == prev_k, omega, phi, p, sin_psi, cos_psi,
                                     turn_c, turn_s, run_step, steps)
        prev_tm, prev_k = tm, k
        if tm > tl:
            for j in range(n_m):
                out[i, j] = sign * free_factor[j] * (sin_psi[j] + kappa[j] * cos_psi[j])
            out[i, n_m] = 0.0
            continue
        sin_at = math.sin(a * tm)
        h = 0.5 * a * sin_at  # the unit pulse
        for j in range(n_m):
            om = omega[j]
            if near[j]:
                z = 0.5 * (om - a) * tm
                sinc = 1.0 if z == 0.0 else math.sin(z) / z
                sin_wt = math.sin(om * tm)
                rest = pulse_amp[j] * (sin_wt - om * tm * math.cos(0.5 * (om + a) * tm) * sinc)
            else:
                sin_wt = sin_psi[j] * cos_phi[j] + cos_psi[j] * sin_phi[j]  # sin(ψ + φ)
                rest = pulse_amp[j] * (sin_wt - om * (sin_wt - sin_at) / (om - a))
            out[i, j] = sign * factor[j] * (rest + free_amp[j] * (kappa[j] * cos_psi[j] - sin_psi[j])
                                            - pulse_static[j] * h)
        out[i, n_m] = sign * h
    return out


@numba.njit(cache=True, nogil=True)
def _largest_excursion_kernel(t, omega, tl, weights, tau, one_wall, tol, limit):
    out, where = np.empty(omega.shape[0]), np.zeros(omega.shape[0], dtype=np.int64)
    p = tau if one_wall else 0.5 * tau
    M = omega.shape[1]
    amp, phi, kappa, free_weight = np.empty(M), np.empty(M), np.empty(M), np.empty(M)
    sin_psi, cos_psi, turn_c, turn_s = np.empty(M), np.empty(M), np.empty(M), np.empty(M)
    for r in range(omega.shape[0]):
        bad = False
        for j in range(M):
            b, kappa[j], phi[j], amp[j] = _echo_factors(omega[r, j], tl[r], tau, one_wall, tol)
            bad = bad or b
            free_weight[j] = weights[r, j] * 0.5 * amp[j] / omega[r, j]  # w A/(2ω)
        if bad:
            out[r] = math.nan
            continue
        # after the pulse q = A (sin ψ + κ cos ψ)/(2ω), the phases ψ turning along the times (_phases_at)
        largest, run_step, steps = 0.0, -1.0, 0
        prev_tm, prev_k, prev_free = 0.0, -1, False
        for i in range(t.shape[1]):
            tm, _, k = _since_last_pulse(t[r, i], p, one_wall)  # the sign drops out of |y|
            free = tm > tl[r]
            y = 0.0
            if free:
                run_step, steps = _phases_at(tm, prev_tm, prev_free and k == prev_k, omega[r], phi, p, sin_psi,
                                             cos_psi, turn_c, turn_s, run_step, steps)
                for j in range(M):
                    y += free_weight[j] * (sin_psi[j] + kappa[j] * cos_psi[j])
            else:
                for j in range(M):
                    y += weights[r, j] * _modal_displacement(tm, omega[r, j], tl[r], kappa[j], phi[j], amp[j])
            prev_tm, prev_k, prev_free = tm, k, free
            if abs(y) > largest:
                largest, where[r] = abs(y), i
            if largest > limit[r]:  # the row's verdict is known: the rest of its times cannot lower it
                break
        out[r] = largest
    return out, where


def largest_excursion(t, omega_n, pulse_duration, weights, period, pattern="one_wall", resonance_tol=1e-15,
                      limit=None, where=False):
    """max over t of |Σ_m w_m q_m(t)| per row, q of :func:`modal_periodic_response` (compiled loop).

    t [s] of shape (R, T), omega_n ω [rad/s] and weights w_m of shape (R, M), pulse_duration T_L [s] of
    shape (R,), scalar period τ [s]. With w_m the modal load factors at a point per unit impulse, this
    is the largest deflection there per unit impulse at the times t (the span search's midspan
    screen). NaN for a row with a resonant or buckled mode or a pulse longer than the (half) period.
    ``limit`` (shape (R,), same units; None: no limit): a row stops at the first time its excursion
    exceeds its limit, and returns that excursion — above the limit, but not the maximum over all of
    t; put the times most likely to exceed first. ``where``: also return, per row, the index along t
    of the returned excursion (the first of equal ones).
    """
    check_choice("pattern", pattern, IMPACT_PATTERNS)
    t, omega, weights = (np.ascontiguousarray(np.asarray(v, dtype=float)) for v in (t, omega_n, weights))
    durations = np.ascontiguousarray(np.broadcast_to(np.asarray(pulse_duration, dtype=float), omega.shape[:1]))
    limit = np.full(omega.shape[0], np.inf) if limit is None else np.asarray(limit, dtype=float)
    largest, index = _largest_excursion_kernel(t, omega, durations, weights, float(period), pattern == "one_wall",
                                               float(resonance_tol),
                                               np.ascontiguousarray(np.broadcast_to(limit, omega.shape[:1])))
    return (largest, index) if where else largest


@numba.njit(cache=True, nogil=True)
def _odd_harmonics(theta, count):
    """(sin nθ, cos nθ) for n = 1, 3, …, 2 count − 1 (rows) at each θ (columns) [-]: angle addition
    from one mode to the next (turn by 2θ), sin and cos afresh every _ROTATION_STEPS modes."""
    sines, cosines = np.empty((count, theta.size)), np.empty((count, theta.size))
    for i in range(theta.size):
        turn_s, turn_c = math.sin(2.0 * theta[i]), math.cos(2.0 * theta[i])
        s = c = 0.0
        for j in range(count):
            if j % _ROTATION_STEPS == 0:
                s, c = math.sin((2 * j + 1) * theta[i]), math.cos((2 * j + 1) * theta[i])
            else:
                s, c = s * turn_c + c * turn_s, c * turn_c - s * turn_s
            sines[j, i], cosines[j, i] = s, c
    return sines, cosines


def periodic_displacement(t, omega_n, pulse_duration, period, pattern="one_wall", resonance_tol=1e-15):
    """q(t) of :func:`modal_periodic_response` on the grid t × ω (compiled loop, real arithmetic).

    t [s] of shape (T,), omega_n ω [rad/s] of shape (M,), scalar pulse_duration T_L [s] and period τ
    [s]; returns shape (T, M). With ψ = ωt_P − φ (t_P the time since the last pulse, φ = ωT_L/2),
    A = cos φ/(1 − u²) and κ as in :func:`modal_state_at_pulse_start`: after the pulse
    q = A (sin ψ + κ cos ψ)/(2ω); during it q = q_p + A (κ cos ψ − sin ψ)/(2ω) with q_p the pulse from
    rest. The per-mode factors are computed once, not per time. NaN where that function is NaN.
    """
    check_choice("pattern", pattern, IMPACT_PATTERNS)
    omega = np.ascontiguousarray(np.asarray(omega_n, dtype=float).ravel())
    return _modal_columns(t, omega, pulse_duration, period, pattern, np.ones_like(omega), 0.0, resonance_tol)[:, :-1]


def dynamic_remainder(t, omega_n, pulse_duration, period, pattern="one_wall", resonance_tol=1e-15):
    """q(t) − h(t)/ω² of :func:`modal_periodic_response` and :func:`pulse_train` on the grid t × ω [s]: each
    mode's part left after the quasi-static split (docs/model.md §5), by the compiled loop of
    :func:`periodic_displacement`. Arguments and shape as there; NaN where it is NaN."""
    check_choice("pattern", pattern, IMPACT_PATTERNS)
    omega = np.ascontiguousarray(np.asarray(omega_n, dtype=float).ravel())
    return _modal_columns(t, omega, pulse_duration, period, pattern, np.ones_like(omega), 1.0, resonance_tol)[:, :-1]


def _modal_columns(t, omega, pulse_duration, period, pattern, factor, static, resonance_tol=1e-15):
    """(times × [modes, pulse]) of :func:`_periodic_displacement_kernel`: factor_n (q_n − static h/ω_n²)
    and h(t), on the flattened t (the one entry to the kernel)."""
    return _periodic_displacement_kernel(np.ascontiguousarray(np.asarray(t, dtype=float).ravel()),
                                         np.ascontiguousarray(omega, dtype=float), float(pulse_duration),
                                         float(period), pattern == "one_wall", float(resonance_tol),
                                         np.ascontiguousarray(factor, dtype=float), float(static))


# --- static beam-column under the unit spread load (closed form) ---------------------------------
_SERIES_TERMS = 36
_INV_FACT = np.array([1.0 / factorial(i) for i in range(2 * _SERIES_TERMS + 8)])


@numba.njit(cache=True, nogil=True)
def _stumpff(w, out):
    """c_0(w) … c_k(w) into ``out`` (k = out.size − 1), c_j(w) = Σ_i w^i/(2i + j)! (Stumpff functions
    with argument −w) [-].

    c_0 = cosh √w, c_1 = sinh √w/√w (cos, sin for w < 0), c_{j+2} = (c_j − 1/j!)/w. Series (Horner,
    _SERIES_TERMS terms) for −30 ≤ w ≤ 60 (positive terms for w > 0; for w < 0 the beam is below
    buckling only while |w| < π²/4), closed form and upward recursion outside, where it loses no digits.
    """
    if -30.0 <= w <= 60.0:
        for k in range(out.size):
            acc = 0.0
            for j in range(_SERIES_TERMS - 1, -1, -1):
                acc = acc * w + _INV_FACT[2 * j + k]
            out[k] = acc
        return
    r = math.sqrt(abs(w))
    out[0] = math.cosh(r) if w > 0 else math.cos(r)
    if out.size > 1:
        out[1] = (math.sinh(r) if w > 0 else math.sin(r)) / r
    for k in range(2, out.size):
        out[k] = (out[k - 2] - _INV_FACT[k - 2]) / w


@numba.njit(cache=True, nogil=True)
def _gen_hyp(x, s, out):
    """F_0(x) … F_k(x) into ``out`` (k = out.size − 1), F_j(x) = x^j c_j(s x²) [m^j], x ≥ 0: F_0 = cosh λx,
    F_1 = sinh(λx)/λ, F_{j+1}' = F_j, λ² = s.

    Entire in s = T/EI (tension s > 0, compression s < 0, s = 0 gives x^j/j!), so one formula
    covers the beam-column, the plain beam and the compressed column without cancellation.
    """
    _stumpff(s * x * x, out)
    power = 1.0
    for j in range(out.size):
        out[j] *= power
        power *= x


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _load_response(xx, a, b, s, ei, code, f, out):
    """P, P', P'', P''' at xx into ``out``: the causal response to the spread load on [a, xx] (see
    :func:`_static_derivatives`); ``f`` is scratch for F_0 … F_6."""
    if code == 0:  # point load: none on the open half span
        out[:] = 0.0
        return
    _gen_hyp(max(xx - a, 0.0), s, f)
    for j in range(4):
        if code == 1:
            out[j] = f[4 - j] / (2.0 * b * ei)
        else:
            out[j] = 3.0 * (b * f[5 - j] - f[6 - j]) / (2.0 * b**3 * ei)


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _static_kernel(x, span, ei, tension, b, code):
    # the beam's parameters: one per x, or one for all (arrays of size 1)
    out = np.empty((4, x.size))
    f, at_half, at_x = np.empty(7), np.empty(3), np.empty(4)
    p_half, p_x = np.empty(4), np.empty(4)
    g_half = 0.0 if code == 0 else 0.5
    big_a = big_b = 0.0
    one = span.size == 1
    for i in range(x.size):
        j = 0 if one else i
        L, e, bj = span[j], ei[j], b[j]
        s = tension[j] / e
        half = 0.5 * L
        mirror = x[i] > half
        xh = min(max(L - x[i] if mirror else x[i], 0.0), half)
        a = half - bj
        if i == 0 or (not one and (L != span[j - 1] or e != ei[j - 1] or tension[j] != tension[j - 1]
                                   or bj != b[j - 1])):  # A and B, once per beam
            _gen_hyp(half, s, at_half)
            _load_response(half, a, bj, s, e, code, f, p_half)
            big_b = -((0.5 - g_half) / e + p_half[3]) / at_half[0]
            big_a = -big_b * at_half[2] - p_half[1]
        _gen_hyp(xh, s, at_x)
        _load_response(xh, a, bj, s, e, code, f, p_x)
        sgn = -1.0 if mirror else 1.0
        out[0, i] = big_a * xh + big_b * at_x[3] + p_x[0]
        out[1, i] = sgn * (big_a + big_b * at_x[2] + p_x[1])
        out[2, i] = big_b * at_x[1] + p_x[2]
        out[3, i] = sgn * (big_b * at_x[0] + p_x[3])
        if bj < 0 or bj >= half or not s * half**2 > -0.25 * math.pi**2:  # buckled: F_0(L/2) ≤ 0
            out[:, i] = math.nan
    return out


def _static_derivatives(x, span_length, bending_stiffness, tension, half_length, shape):
    """(y, y', y'', y''') [m/N, 1/N, 1/(N m), 1/(N m²)] of the static beam-column under the unit load.

    Solves EI y'''' − T y'' = g(x) on the half-span 0 ≤ x ≤ L/2 with y(0) = y''(0) = 0 and the
    symmetry conditions y'(L/2) = 0, −EI y'''(L/2⁻) = ½ − ∫_a^{L/2} g (the half of a point load
    sitting on the symmetry plane), a = L/2 − b; x > L/2 is mirrored. Solution
    y = A x + B F_3(x) + P(x), P the causal response to the load on [a, x]:
    P^{(j)}(x) = (1/EI) ∫_a^x g(x') F_{3−j}(x − x') dx', r = x − a, which for the shapes is
    uniform: F_{4−j}(r)/(2b EI); parabolic (g = 3ρ(2b − ρ)/(4b³), ρ = x' − a):
    3(b F_{5−j}(r) − F_{6−j}(r))/(2b³ EI) — from ∫₀^r ρ^m/m! F_k(r − ρ) dρ = F_{k+m+1}(r).
    B = −[(½ − G_half)/EI + P'''(L/2)]/F_0(L/2), A = −B F_2(L/2) − P'(L/2). Compiled, one point at a
    time (:func:`_static_kernel`); the arguments broadcast.
    """
    check_choice("shape", shape, LOAD_SHAPES)
    b = 0.0 if shape == "point" else half_length
    beam = [np.asarray(v, dtype=float) for v in (span_length, bending_stiffness, tension, b)]
    x = np.asarray(x, dtype=float)
    if all(v.ndim == 0 for v in beam):  # one beam: its parameters once
        shape_out, flat = x.shape, [x.ravel()] + [v.reshape(1) for v in beam]
    else:
        args = np.broadcast_arrays(x, *beam)
        shape_out, flat = args[0].shape, [np.array(v).ravel() for v in args]  # writeable copies
    out = _static_kernel(*flat, SHAPE_CODES[shape])
    return [row.reshape(shape_out) for row in out]


def static_deflection(x, span_length, bending_stiffness, tension, half_length=0.0, shape="point"):
    """Static deflection G(x) [m/N] of the simply supported beam-column under the unit midspan load.

    EI G'''' − T G'' = g(x) (docs/model.md §2 with ÿ = 0), g of unit integral (:data:`LOAD_SHAPES`).
    x [m] (0 ≤ x ≤ L), span_length L [m], bending_stiffness EI [N m²], tension T [N] (any sign
    above buckling), half_length b [m] (0 ≤ b < L/2; ignored for ``"point"``). Closed form in the
    generalised hyperbolic functions F_k(x) = x^k c_k(T x²/EI) (see ``_static_derivatives``),
    one expression for T > 0 (sinh/cosh), T = 0 and T < 0 (sin/cos). For the point load it is
    G = (x F_2(L/2) − F_3(x))/(2 EI F_0(L/2)), x ≤ L/2, i.e. (Timoshenko & Gere, Roark table 8.8)
    T > 0: [x − sinh(λx)/(λ cosh(λL/2))]/(2T), λ² = T/EI;  T = 0: x(3L² − 4x²)/(48 EI);
    T < 0: [x − sin(λx)/(λ cos(λL/2))]/(2T), λ² = −T/EI.
    NaN where buckled (T ≤ −EI π²/L²) or b outside [0, L/2). Overflows for λL/2 ≳ 700 (string limit).
    """
    return _static_derivatives(x, span_length, bending_stiffness, tension, half_length, shape)[0]


def static_moment(x, span_length, bending_stiffness, tension, half_length=0.0, shape="point"):
    """Bending moment −EI G''(x) [m] (N m per N of load) of the static unit-load solution (docs/model.md §5).

    Arguments as :func:`static_deflection`. Point load: sinh(λx)/(2λ cosh(λL/2)), x ≤ L/2 (T > 0),
    x/2 (T = 0). Sagging positive.
    """
    ei = np.asarray(bending_stiffness, dtype=float)
    return -ei * _static_derivatives(x, span_length, bending_stiffness, tension, half_length, shape)[2]


def static_shear(x, span_length, bending_stiffness, tension, half_length=0.0, shape="point",
                 include_tension=False):
    """Shear force of the static unit-load solution [-] (N per N of load) (docs/model.md §5).

    Returns the section shear V = −EI G''' (= dM_b/dx, the force normal to the deflected axis that
    sets the wall shear stress); with ``include_tension`` the transverse force −EI G''' + T G'
    (fixed direction), which equals ½ − ∫_a^x g on the left half. Arguments as :func:`static_deflection`.
    """
    ei = np.asarray(bending_stiffness, dtype=float)
    _, y1, _, y3 = _static_derivatives(x, span_length, bending_stiffness, tension, half_length, shape)
    return -ei * y3 + (np.asarray(tension, dtype=float) * y1 if include_tension else 0.0)


# --- the periodic field: modal sums with the quasi-static correction ----------------------------
#: Fields :func:`periodic_fields` evaluates: kind → description [unit].
def point_load_moment(x, load_at, span_length: float, bending_stiffness: float, tension: float) -> np.ndarray:
    """Bending moment −EI y'' [N m per N] at x [m] of a unit point load at ``load_at`` [m] on a simply
    supported beam-column EI y'''' − T y'' = δ(x − a) (closed form below); x and load_at
    broadcast together. Tension T [N] (negative: compression, below the buckling load).

    With u = y'': EI u'' − T u = δ(x − a), u(0) = u(L) = 0, so the moment −EI u is the Green's function
    sinh μx_< sinh μ(L − x_>)/(μ sinh μL), μ² = T/EI, x_< = min(x, a), x_> = max(x, a); its limit
    x_<(L − x_>)/L at T = 0 (the string-free beam) and sin for compression. Equal to the modal sum
    Σ_n (2/L) EI sin k_n a sin k_n x/(EI k_n² + T), k_n = nπ/L."""
    x, a = np.broadcast_arrays(np.asarray(x, float), np.asarray(load_at, float))
    lo, hi = np.minimum(x, a), np.maximum(x, a)
    L, mu2 = float(span_length), float(tension) / float(bending_stiffness)
    if mu2 == 0.0:
        return lo * (L - hi) / L
    if mu2 < 0.0:
        nu = np.sqrt(-mu2)
        return np.sin(nu * lo) * np.sin(nu * (L - hi)) / (nu * np.sin(nu * L))
    mu = np.sqrt(mu2)
    # sinh A sinh B / sinh C = e^(A+B-C) (1 - e^-2A)(1 - e^-2B) / (2 (1 - e^-2C)), A + B <= C: no overflow
    A, B, C = mu * lo, mu * (L - hi), mu * L
    return np.exp(A + B - C) * -np.expm1(-2 * A) * -np.expm1(-2 * B) / (-2.0 * np.expm1(-2 * C) * mu)


FIELD_KINDS = {
    "deflection": "y [m]",
    "moment": "bending moment −EI y'' [N m] (sagging positive)",
    "shear": "section shear −EI y\u2034 [N] (with ``include_tension``: the transverse force −EI y\u2034 + T y')",
}


def periodic_fields(x, t, kinds, span_length, bending_stiffness, tension, mass, impulse, pulse_duration, period,
                    pattern="one_wall", half_length=0.0, shape="point", n_modes=101, quasi_static=True,
                    include_tension=False) -> dict:
    """Several fields of the periodic solution at once (:data:`FIELD_KINDS`), sharing the modal
    amplitudes: {kind: array of shape t.shape + x.shape}. Arguments as :func:`deflection`.

    Each field is Σ_n a_n(t) D^order[sin k_n x] assembled as a matrix product (times × modes) @
    (modes × x), plus J h(t) times the closed-form static field with ``quasi_static``.
    """
    check_choice("pattern", pattern, IMPACT_PATTERNS)
    for kind in kinds:
        check_choice("kind", kind, FIELD_KINDS)
    x, t = np.asarray(x, dtype=float), np.asarray(t, dtype=float)
    L, ei, tn, m = (float(v) for v in (span_length, bending_stiffness, tension, mass))
    n = np.arange(1, int(n_modes) + 1, 2, dtype=float)  # even modes carry no symmetric load
    k = n * np.pi / L
    with np.errstate(invalid="ignore"):
        omega = np.sqrt(np.where(ei * k**4 + tn * k**2 > 0, (ei * k**4 + tn * k**2) / m, np.nan))
    g = modal_load_factors(n, L, half_length, shape)
    # (times × [modes, pulse]): the modal coordinates [m] J g_n/(M L/2) (q_n − h/ω_n² with
    # ``quasi_static``) and J h(t), the weight of the static field
    columns = _modal_columns(t, omega, pulse_duration, period, pattern, float(impulse) * g / (0.5 * m * L),
                             1.0 if quasi_static else 0.0)
    columns[:, -1] *= float(impulse)
    if quasi_static:  # the static solution and its derivatives, once for every kind (as static_*)
        g0, g1, g2, g3 = _static_derivatives(x.ravel(), L, ei, tn, half_length, shape)
        static = {"deflection": g0, "moment": -ei * g2, "shear": -ei * g3 + (tn * g1 if include_tension else 0.0)}
    else:
        columns = columns[:, :-1]
    # one matrix product for every kind: (times × [modes, static]) @ ([modes, static] × (kinds × x))
    sin_kx, cos_kx = _odd_harmonics(np.pi / L * x.ravel(), n.size)
    kc = k[:, None]
    rows = np.empty((columns.shape[1], len(kinds) * x.size))
    for i, kind in enumerate(kinds):
        block = rows[:n.size, i * x.size:(i + 1) * x.size]
        if kind == "deflection":
            block[:] = sin_kx
        elif kind == "moment":  # −EI y''
            np.multiply(ei * kc**2, sin_kx, out=block)
        else:  # −EI y''' (+ T y')
            np.multiply(ei * kc**3 + (tn * kc if include_tension else 0.0), cos_kx, out=block)
        if quasi_static:
            rows[n.size, i * x.size:(i + 1) * x.size] = static[kind]
    fields = columns @ rows
    size = x.size
    return {kind: fields[:, i * size:(i + 1) * size].reshape(t.shape + x.shape) for i, kind in enumerate(kinds)}


_FIELD_DOC = """

    x [m] (0 ≤ x ≤ L), t [s] (any real); result has shape t.shape + x.shape. Scalars: span_length
    L [m], bending_stiffness EI [N m²], tension T [N], mass M [kg/m], impulse J [N s], pulse_duration
    T_L [s], period τ [s]; pattern (:data:`IMPACT_PATTERNS`), half_length b [m] and shape
    (:data:`LOAD_SHAPES`) of the load; n_modes: highest mode number N kept (odd n ≤ N: the load is
    symmetric). Modal sum y = Σ [J g_n/(M L/2)] q_n(t) sin(k_n x) with q_n from
    :func:`modal_periodic_response` (docs/model.md §4, §9). With ``quasi_static`` (default) the sum is
    split (docs/model.md §5): y = J h(t) G(x) + Σ [J g_n/(M L/2)] (q_n − h(t)/ω_n²) sin(k_n x), G the
    closed-form static solution (:func:`static_deflection`); the remainder's terms fall like
    ω_n⁻³ faster, so moment and shear converge in few modes. NaN at resonance or buckling."""


def deflection(x, t, span_length, bending_stiffness, tension, mass, impulse, pulse_duration, period,
               pattern="one_wall", half_length=0.0, shape="point", n_modes=101, quasi_static=True):
    return periodic_fields(x, t, ["deflection"], span_length, bending_stiffness, tension, mass, impulse, pulse_duration,
                           period, pattern, half_length, shape, n_modes, quasi_static)["deflection"]


deflection.__doc__ = "Periodic deflection y(x, t) [m] of the span under the impact train." + _FIELD_DOC


def bending_moment(x, t, span_length, bending_stiffness, tension, mass, impulse, pulse_duration, period,
                   pattern="one_wall", half_length=0.0, shape="point", n_modes=101, quasi_static=True):
    return periodic_fields(x, t, ["moment"], span_length, bending_stiffness, tension, mass, impulse, pulse_duration,
                           period, pattern, half_length, shape, n_modes, quasi_static)["moment"]


bending_moment.__doc__ = ("Bending moment M_b = −EI y''(x, t) [N m] (docs/model.md §5, paper eq. 37), sagging "
                          "positive." + _FIELD_DOC)


def shear_force(x, t, span_length, bending_stiffness, tension, mass, impulse, pulse_duration, period,
                pattern="one_wall", half_length=0.0, shape="point", n_modes=101, quasi_static=True,
                include_tension=False):
    return periodic_fields(x, t, ["shear"], span_length, bending_stiffness, tension, mass, impulse, pulse_duration,
                           period, pattern, half_length, shape, n_modes, quasi_static, include_tension)["shear"]


shear_force.__doc__ = ("Shear force [N] (docs/model.md §5, paper eq. 38): by default the section shear "
                       "V = −EI y''' = ∂M_b/∂x (normal to the deflected axis, sets the wall shear stress); with "
                       "``include_tension`` the transverse force −EI y''' + T y'. At x = L/2 under a point "
                       "load the series gives the mean of the two sides (0) while the closed form gives "
                       "the left limit." + _FIELD_DOC)


