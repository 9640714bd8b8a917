"""One-degree-of-freedom oscillator, free, forced and impacting against a rigid wall.

Pure functions of numpy arrays where natural (broadcasting; floats accepted), SI units, no I/O.
This is the reduced model of docs/model.md §8: a mass m on a spring k with viscous damping c (or
Coulomb friction f), driven by F_c + F0 cos(Ωt), with a rigid wall at x = gap that it strikes
with Newton's law of restitution (coefficient e).

Sources: Harrison & Nettleton, *Principles of Engineering Mechanics*, 2nd ed., ch. 9
"Vibration" (the book's equation numbers; the relations used are listed in docs/model.md §8.3 and
``docs/textbook_examples.md``), and ch. 8 for the impact law (``study.physics.restitution``).
Impact-oscillator map and its stability: Shaw & Holmes, J. Sound Vib. 90 (1983) 129–155;
Budd & Dux, Phil. Trans. R. Soc. A 347 (1994) 365–389 (chattering). The compliant wall (Hertz's
spring with Hunt–Crossley damping, one impact on it) is the contact law's: :mod:`study.physics.contact`.

Notation: ω_n = √(k/m) [rad/s]; ζ = c/(2√(km)) [-]; ω_d = ω_n √(1 − ζ²) [rad/s]; r = Ω/ω_n [-].
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from study.physics.restitution import check_range, check_restitution

__all__ = [
    "natural_frequency",
    "damping_ratio",
    "damped_frequency",
    "free_response",
    "logarithmic_decrement",
    "coulomb_free_response",
    "step_response",
    "ramp_response",
    "dynamic_magnifier",
    "phase_angle",
    "State",
    "ImpactParams",
    "ImpactEvent",
    "ImpactHistory",
    "PeriodicOrbit",
    "flight_state",
    "next_impact_time",
    "impact_velocity_after",
    "simulate_impacts",
    "impact_map",
    "impact_map_jacobian",
    "periodic_orbits",
    "periodic_orbit",
]


class State(NamedTuple):
    x: np.ndarray  #: displacement [m]
    v: np.ndarray  #: velocity [m/s]


# --- closed-form free and forced responses (textbook ch. 9) -----------------------------------


def natural_frequency(mass, stiffness):
    """Undamped natural frequency ω_n = √(k/m) [rad/s].

    Parameters: mass m [kg] > 0, stiffness k [N/m] ≥ 0.
    Textbook: eq. 9.4.
    """
    m = check_range(mass, "mass", 0.0, np.inf, low_open=True, high_open=True)
    k = check_range(stiffness, "stiffness", 0.0, np.inf, high_open=True)
    return np.sqrt(k / m)


def damping_ratio(mass, stiffness, damping):
    """Damping ratio ζ = c / c_crit, c_crit = 2√(km) [-].

    Parameters: mass m [kg] > 0, stiffness k [N/m] > 0, damping c [N s/m] ≥ 0.
    Textbook: eq. 9.21–9.22.
    """
    m = check_range(mass, "mass", 0.0, np.inf, low_open=True, high_open=True)
    k = check_range(stiffness, "stiffness", 0.0, np.inf, low_open=True, high_open=True)
    c = check_range(damping, "damping", 0.0, np.inf, high_open=True)
    return c / (2.0 * np.sqrt(k * m))


def damped_frequency(natural_freq, zeta):
    """Damped natural frequency ω_d = ω_n √(1 − ζ²) [rad/s], for 0 ≤ ζ < 1.

    Textbook: eq. 9.23.
    """
    wn = check_range(natural_freq, "natural_freq", 0.0, np.inf, high_open=True)
    z = check_range(zeta, "zeta", 0.0, 1.0, high_open=True)
    return wn * np.sqrt(1.0 - z**2)


def _cs(t, wn, zeta):
    """e^(−ζω_n t) × (C, S) with C = cos ω_d t, S = sin(ω_d t)/ω_d, valid for every ζ ≥ 0.

    ω_d² = ω_n²(1 − ζ²) may be negative (over-damped: cosh, sinh/|ω_d|) or zero (critical: 1, t);
    the exponentials are combined so that large t does not overflow.
    """
    t, wn, zeta = np.broadcast_arrays(np.asarray(t, float), np.asarray(wn, float),
                                      np.asarray(zeta, float))
    a = zeta * wn
    wd2 = wn**2 * (1.0 - zeta**2)
    w = np.sqrt(np.abs(wd2))
    wt = w * t
    small = wt < 1e-4
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        # under-damped
        c_u = np.exp(-a * t) * np.cos(wt)
        s_u = np.exp(-a * t) * np.sin(wt) / np.where(w > 0, w, 1.0)
        # over-damped: e^(−at) cosh(wt) = ½(e^(−(a−w)t) + e^(−(a+w)t))
        e1 = np.exp(-(a - w) * t)
        e2 = np.exp(-(a + w) * t)
        c_o = 0.5 * (e1 + e2)
        s_o = 0.5 * (e1 - e2) / np.where(w > 0, w, 1.0)
        # series for small w t (covers critical damping): sin(wt)/w ≈ t(1 ∓ (wt)²/6)
        sgn = np.sign(wd2)
        c_s = np.exp(-a * t) * (1.0 - sgn * wt**2 / 2.0 + wt**4 / 24.0)
        s_s = np.exp(-a * t) * t * (1.0 - sgn * wt**2 / 6.0 + wt**4 / 120.0)
    under = wd2 > 0
    C = np.where(small, c_s, np.where(under, c_u, c_o))
    S = np.where(small, s_s, np.where(under, s_u, s_o))
    return C, S


def free_response(t, natural_freq, zeta, x0, v0=0.0) -> State:
    """Damped free vibration x(t), ẋ(t) of ẍ + 2ζω_n ẋ + ω_n² x = 0 from x(0) = x0, ẋ(0) = v0.

        x = e^(−ζω_n t) [x0 cos ω_d t + (v0 + ζω_n x0) sin(ω_d t)/ω_d],

    under-damped (ζ < 1); the same expression with cos → cosh, sin/ω_d → sinh/|ω_d| (over-damped,
    ζ > 1) and → 1, t (critical, ζ = 1). ζ = 0 is eq. 9.7.

    Parameters
    ----------
    t : array_like
        Time [s], ≥ 0.
    natural_freq : array_like
        ω_n [rad/s], ≥ 0.
    zeta : array_like
        ζ [-], ≥ 0.
    x0, v0 : array_like
        Initial displacement [m] and velocity [m/s].

    Returns
    -------
    State
        ``x`` [m], ``v`` [m/s].

    Textbook: eq. 9.7 (ζ = 0), 9.18–9.20, 9.26 (x0, v0 = 0).
    """
    t = check_range(t, "t", 0.0, np.inf, high_open=True)
    wn = check_range(natural_freq, "natural_freq", 0.0, np.inf, high_open=True)
    z = check_range(zeta, "zeta", 0.0, np.inf, high_open=True)
    x0 = np.asarray(x0, float)
    v0 = np.asarray(v0, float)
    C, S = _cs(t, wn, z)
    a = z * wn
    x = x0 * C + (v0 + a * x0) * S
    v = v0 * C - (a * v0 + wn**2 * x0) * S
    return State(x=x, v=v)


def logarithmic_decrement(zeta):
    """Logarithmic decrement δ = ln(x_n / x_(n+1)) = 2πζ/√(1 − ζ²) [-], for 0 ≤ ζ < 1.

    Textbook: eq. 9.27–9.28.
    """
    z = check_range(zeta, "zeta", 0.0, 1.0, high_open=True)
    return 2.0 * np.pi * z / np.sqrt(1.0 - z**2)


def coulomb_free_response(t, natural_freq, friction_displacement, x0) -> State:
    """Free vibration with Coulomb friction, m ẍ + kx = ∓f, released from rest at x0.

    Each half cycle is a simple-harmonic arc about ±f/k (the side opposing the motion), so the
    amplitude drops by 2f/k per half cycle and the period 2π/ω_n is unchanged; the motion stops
    at the first velocity reversal with |x| ≤ f/k (the spring cannot overcome static friction,
    taken equal to the kinetic value).

    Parameters
    ----------
    t : array_like
        Time [s], ≥ 0.
    natural_freq : float
        ω_n = √(k/m) [rad/s], > 0.
    friction_displacement : float
        f/k [m], ≥ 0 (friction force over stiffness).
    x0 : float
        Release displacement [m] (from rest).

    Returns
    -------
    State
        ``x`` [m], ``v`` [m/s].

    Textbook: eq. 9.30 and the text after it.
    """
    t = check_range(t, "t", 0.0, np.inf, high_open=True)
    wn = float(check_range(natural_freq, "natural_freq", 0.0, np.inf, low_open=True,
                            high_open=True))
    d = float(check_range(friction_displacement, "friction_displacement", 0.0, np.inf,
                           high_open=True))
    x0 = float(x0)
    s0 = 1.0 if x0 >= 0 else -1.0
    X0 = abs(x0)
    n_stop = int(np.ceil((X0 - d) / (2.0 * d))) if (X0 > d and d > 0) else (0 if X0 <= d else -1)
    j = np.floor(wn * t / np.pi)
    if n_stop >= 0:
        j = np.minimum(j, n_stop)
    tau = t - j * np.pi / wn
    amp = X0 - 2.0 * j * d
    sign = s0 * np.where(j % 2 == 0, 1.0, -1.0)
    moving = j < n_stop if n_stop >= 0 else np.ones_like(t, bool)
    x = np.where(moving, sign * (d + (amp - d) * np.cos(wn * tau)), sign * amp)
    v = np.where(moving, -sign * (amp - d) * wn * np.sin(wn * tau), 0.0)
    return State(x=x, v=v)


def step_response(t, natural_freq, zeta) -> State:
    """Response to a step force P0 applied at t = 0 from rest, as x/(P0/k) [-] and ẋ/(P0/k) [1/s].

        x/(P0/k) = 1 − e^(−ζω_n t) [cos ω_d t + ζ/√(1 − ζ²) sin ω_d t]

    (continued analytically to ζ ≥ 1). Overshoot for ζ < 1: exp(−ζπ/√(1 − ζ²)) at ω_d t = π.

    Textbook: eq. 9.33–9.34.
    """
    r = free_response(t, natural_freq, zeta, -1.0, 0.0)
    return State(x=1.0 + r.x, v=r.v)


def ramp_response(t, natural_freq, zeta) -> State:
    """Response to a ramp force P = a t from rest, as x/(a/k) [s] and ẋ/(a/k) [-].

        x/(a/k) = t − 2ζ/ω_n + e^(−ζω_n t)[2ζ cos ω_d t − (1 − 2ζ²)/√(1 − ζ²) sin ω_d t]/ω_n

    i.e. the steady ramp t − 2ζ/ω_n plus the free response that cancels its initial
    displacement −2ζ/ω_n and velocity 1.

    Textbook: eq. 9.36.
    """
    wn = check_range(natural_freq, "natural_freq", 0.0, np.inf, low_open=True, high_open=True)
    z = np.asarray(zeta, float)
    r = free_response(t, wn, z, 2.0 * z / wn, -1.0)
    return State(x=np.asarray(t, float) - 2.0 * z / wn + r.x, v=1.0 + r.v)


def dynamic_magnifier(frequency_ratio, zeta):
    """Steady-state dynamic magnifier β = X/(F0/k) = 1/√((1 − r²)² + (2ζr)²) [-].

    Parameters: frequency_ratio r = Ω/ω_n [-] ≥ 0; zeta ζ [-] ≥ 0 (β = inf at r = 1, ζ = 0).
    Textbook: eq. 9.46, 9.50.
    """
    r = check_range(frequency_ratio, "frequency_ratio", 0.0, np.inf, high_open=True)
    z = check_range(zeta, "zeta", 0.0, np.inf, high_open=True)
    with np.errstate(divide="ignore"):
        return 1.0 / np.hypot(1.0 - r**2, 2.0 * z * r)


def phase_angle(frequency_ratio, zeta):
    """Phase lag φ = atan2(2ζr, 1 − r²) ∈ [0, π] of x = X cos(Ωt − φ) behind F0 cos Ωt [rad].

    Textbook: eq. 9.47.
    """
    r = check_range(frequency_ratio, "frequency_ratio", 0.0, np.inf, high_open=True)
    z = check_range(zeta, "zeta", 0.0, np.inf, high_open=True)
    return np.arctan2(2.0 * z * r, 1.0 - r**2)


# --- event-driven flight against a rigid wall ---------------------------------------------------


class ImpactParams(NamedTuple):
    """Impact oscillator m ẍ + c ẋ + k x = F_c + F0 cos(Ωt), rigid wall at x = gap (x ≤ gap)."""

    mass: float  #: m [kg], > 0
    stiffness: float  #: k [N/m], ≥ 0 (0: no spring, e.g. the bouncing ball)
    damping: float = 0.0  #: c [N s/m], ≥ 0
    force_amplitude: float = 0.0  #: F0 [N]
    forcing_frequency: float = 0.0  #: Ω [rad/s], ≥ 0 (0: F0 is a constant force)
    constant_force: float = 0.0  #: F_c [N], positive towards the wall (e.g. m g for a floor)
    gap: float = 0.0  #: wall position [m] measured from the spring's unstretched position
    restitution: float = 1.0  #: Newton's e [-], 0 ≤ e ≤ 1


class ImpactEvent(NamedTuple):
    time: float  #: impact time [s] (nan if none)
    velocity: float  #: approach velocity ẋ at impact [m/s] (≥ 0; nan if none)
    status: str  #: 'impact' or 'no_impact'
    message: str


def _validated(params: ImpactParams) -> ImpactParams:
    p = ImpactParams(*params)
    check_range(p.mass, "mass", 0.0, np.inf, low_open=True, high_open=True)
    check_range(p.stiffness, "stiffness", 0.0, np.inf, high_open=True)
    check_range(p.damping, "damping", 0.0, np.inf, high_open=True)
    check_range(p.forcing_frequency, "forcing_frequency", 0.0, np.inf, high_open=True)
    check_restitution(p.restitution)
    for name in ("force_amplitude", "constant_force", "gap"):
        check_range(getattr(p, name), name, -np.inf, np.inf, low_open=True, high_open=True)
    return p


def _particular(t, p: ImpactParams, t_ref=0.0):
    """A particular solution (x_p, v_p, a_p) of m ẍ + c ẋ + k x = F_c + F0 cos Ωt at times t.

    Without a spring the constant-force part grows with time; it is taken relative to t_ref
    (any particular solution will do) so that x_p stays small over one flight and x − gap does not
    lose digits to cancellation.
    """
    t = np.asarray(t, float)
    tau = t - t_ref
    m, k, c, F0, Om, Fc = (p.mass, p.stiffness, p.damping, p.force_amplitude,
                           p.forcing_frequency, p.constant_force)
    if Om == 0.0:
        Fc, F0 = Fc + F0, 0.0
    # constant part
    if k > 0:
        x, v, a = np.full_like(t, Fc / k), np.zeros_like(t), np.zeros_like(t)
    elif c > 0:  # no spring: terminal velocity Fc/c
        x, v, a = Fc / c * tau, np.full_like(t, Fc / c), np.zeros_like(t)
    else:  # free mass under a constant force
        x, v, a = 0.5 * Fc / m * tau**2, Fc / m * tau, np.full_like(t, Fc / m)
    if F0 != 0.0:
        den = complex(k - m * Om**2, c * Om)
        if den == 0:  # undamped resonance: x_p = F0 t sin(Ωt)/(2mΩ)
            s, co = np.sin(Om * t), np.cos(Om * t)
            g = F0 / (2 * m * Om)
            x = x + g * t * s
            v = v + g * (s + Om * t * co)
            a = a + g * (2 * Om * co - Om**2 * t * s)
        else:
            z = F0 / den * np.exp(1j * Om * t)
            x = x + z.real
            v = v + (1j * Om * z).real
            a = a + (-(Om**2) * z).real
    return x, v, a


def _transition(dt, p: ImpactParams):
    """Homogeneous transition matrix entries (Φ11, Φ12, Φ21, Φ22) over dt [s] (any damping)."""
    m, k, c = p.mass, p.stiffness, p.damping
    wn = np.sqrt(k / m)
    a = c / (2 * m)
    if wn > 0:
        C, S = _cs(dt, wn, a / wn)
    else:  # k = 0: ω_d² = −a², C = e^(−at) cosh(at), S = e^(−at) sinh(at)/a (→ 1, t for a = 0)
        dt = np.asarray(dt, float)
        C = 0.5 * (1 + np.exp(-2 * a * dt))
        S = -np.expm1(-2 * a * dt) / (2 * a) if a > 0 else dt.copy()
    return C + a * S, S, -(wn**2) * S, C - a * S


def flight_state(t, state0, params: ImpactParams, t0=0.0) -> State:
    """Closed-form state x(t), ẋ(t) of the impact-free motion of the driven oscillator.

    m ẍ + c ẋ + k x = F_c + F0 cos(Ωt), from x(t0) = x0, ẋ(t0) = v0: the homogeneous solution
    (as :func:`free_response`, including over-damped and k = 0) plus a particular solution
    (F_c/k, or the terminal velocity F_c/c, or F_c t²/2m when k = c = 0; and the steady state
    Re[F0 e^(iΩt)/(k − mΩ² + icΩ)], or F0 t sin(Ωt)/(2mΩ) at undamped resonance). The wall is
    ignored here: this is one flight between impacts. Time is absolute (the drive phase is Ωt).

    Parameters
    ----------
    t : array_like
        Times [s], ≥ t0.
    state0 : (float, float)
        (x0 [m], v0 [m/s]) at t0.
    params : ImpactParams
    t0 : float
        Start time [s].

    Returns
    -------
    State
        ``x`` [m], ``v`` [m/s] at t.

    Textbook: eq. 9.18–9.26 (homogeneous), 9.42–9.47 (steady state).
    """
    p = _validated(params)
    t = np.asarray(t, float)
    if np.any(t < t0):
        raise ValueError(f"t = {float(np.min(t))!r} is outside the allowed range [t0, inf), "
                         f"t0 = {t0!r}")
    return _flight(t, float(state0[0]), float(state0[1]), p, float(t0))


def _flight(t, x0, v0, p: ImpactParams, t0):
    """:func:`flight_state` without validation (t ≥ t0 assumed)."""
    xp0, vp0, _ = _particular(t0, p, t0)
    xp, vp, _ = _particular(t, p, t0)
    dx, dv = x0 - float(xp0), v0 - float(vp0)
    dt = t - t0
    f11, f12, f21, f22 = _transition(dt, p)
    return State(x=xp + f11 * dx + f12 * dv, v=vp + f21 * dx + f22 * dv)


def _accel(t, x, v, p: ImpactParams):
    F = p.constant_force + p.force_amplitude * np.cos(p.forcing_frequency * np.asarray(t, float))
    return (F - p.damping * v - p.stiffness * x) / p.mass


def _time_step(p: ImpactParams) -> float:
    """Bracketing step [s]: an eighth of the shortest time scale (ω_n, Ω, damping rate)."""
    rates = [np.sqrt(p.stiffness / p.mass), p.forcing_frequency, p.damping / p.mass]
    w = max(rates)
    return np.pi / (8 * w) if w > 0 else np.inf


def next_impact_time(t0, state0, params: ImpactParams, t_max, *, step=None,
                     xtol=1e-14) -> ImpactEvent:
    """First time t > t0 at which the flight from ``state0`` reaches the wall x = gap.

    Exact event location without time stepping of the motion: x(t) − gap is evaluated in closed
    form (:func:`flight_state`) on a grid of step h = π/(8 ω_max) (ω_max the largest of ω_n, Ω and
    c/m), short enough that ẋ changes sign at most once per step; a root is bracketed either by
    a sign change of x − gap or, for an interior maximum of x (ẋ from + to −), by locating the
    maximum with brentq on ẋ and testing it (so grazing approaches are not skipped). The root is
    then refined with brentq. A start on the wall (x0 = gap) moving away is handled by starting
    the bracket at the first minimum.

    Parameters
    ----------
    t0 : float
        Start time [s].
    state0 : (float, float)
        (x0, v0) at t0, x0 ≤ gap [m], [m/s].
    params : ImpactParams
    t_max : float
        Search horizon [s]; beyond it the result is 'no_impact'.
    step : float, optional
        Override of the bracketing step [s].
    xtol : float
        Absolute time tolerance of brentq [s].

    Returns
    -------
    ImpactEvent
        Time, approach velocity (≥ 0), status 'impact' or 'no_impact', message.

    Reference: standard event-driven treatment of impact oscillators (Shaw & Holmes 1983).
    """
    from scipy.optimize import brentq

    p = _validated(params)
    h = float(step) if step is not None else min(_time_step(p), max(t_max - t0, 0.0))
    if not np.isfinite(h) or h <= 0:
        h = max(t_max - t0, 1e-300)
    x0, v0 = float(state0[0]), float(state0[1])

    def g(t):
        return float(_flight(t, x0, v0, p, t0).x) - p.gap

    def vel(t):
        return float(_flight(t, x0, v0, p, t0).v)

    ta, ga, va = t0, x0 - p.gap, v0
    if ga > 0:
        return ImpactEvent(t0, max(v0, 0.0), "impact", "start beyond the wall")
    on_wall = ga == 0.0
    if on_wall and v0 > 0:
        return ImpactEvent(t0, v0, "impact", "start on the wall moving into it")
    n_steps = int(np.ceil((t_max - t0) / h)) if np.isfinite(t_max) else 10**7
    chunk = 32  # grid points evaluated per vectorised closed-form call
    for i0 in range(0, n_steps, chunk):
        tbs = np.minimum(t0 + np.arange(i0 + 1, min(i0 + chunk, n_steps) + 1) * h, t_max)
        sts = _flight(tbs, x0, v0, p, t0)
        for tb, gb, vb in zip(tbs.tolist(), (sts.x - p.gap).tolist(), sts.v.tolist()):
            lo, glo, vlo = ta, ga, va
            if on_wall and ta == t0:
                # x − gap = 0 at t0: move the bracket start to the first minimum (ẋ from − to +)
                if va < 0 or (va == 0 and _accel(t0, x0, 0.0, p) < 0):
                    if vb > 0:
                        lo = brentq(vel, ta, tb, xtol=xtol) if va < 0 else ta
                        if lo == t0:
                            lo = t0 + 1e-12 * max(h, 1.0)
                        glo, vlo = g(lo), vel(lo)
                        if glo >= 0:
                            lo = None
                    else:
                        lo = None
                else:
                    return ImpactEvent(t0, 0.0, "impact",
                                       "start on the wall at rest, pushed into it")
            if lo is not None:
                if glo < 0 and gb >= 0:
                    tr = brentq(g, lo, tb, xtol=xtol) if gb > 0 else tb
                    return ImpactEvent(tr, max(vel(tr), 0.0), "impact", "")
                if glo < 0 and gb < 0 and vlo > 0 and vb < 0:
                    tm = brentq(vel, lo, tb, xtol=xtol)
                    gm = g(tm)
                    if gm >= 0:
                        tr = brentq(g, lo, tm, xtol=xtol) if gm > 0 else tm
                        return ImpactEvent(tr, max(vel(tr), 0.0), "impact", "")
            ta, ga, va = tb, gb, vb
            if tb >= t_max:
                break
    return ImpactEvent(float("nan"), float("nan"), "no_impact",
                       f"no impact before t_max = {t_max:g} s")


def impact_velocity_after(approach_velocity, params: ImpactParams):
    """Velocity just after striking the rigid wall, −e v [m/s] (Newton's law of restitution).

    Uses :func:`study.physics.restitution.collision` with an immovable wall (m2 = inf).
    """
    from study.physics.restitution import collision

    p = _validated(params)
    return collision(p.mass, approach_velocity, np.inf, 0.0, p.restitution).v1


# --- impact sequences, chattering and sticking ------------------------------------------------


class ImpactHistory(NamedTuple):
    times: np.ndarray  #: impact times [s]
    velocities: np.ndarray  #: approach velocities at the impacts [m/s] (≥ 0)
    final_time: float  #: time at which the run stopped [s]
    final_state: State  #: (x [m], v [m/s]) at final_time (after the last impact)
    accumulation_time: float  #: limit time of a chattering sequence [s] (nan if none)
    status: str  #: 'completed', 'chattering', 'sticking' or 'not_converged'
    message: str


def _wall_force(t, p: ImpactParams):
    """Net force towards the wall on the mass resting on it, F(t) − k·gap [N]."""
    return (p.constant_force + p.force_amplitude * np.cos(p.forcing_frequency * t)
            - p.stiffness * p.gap)


def simulate_impacts(t0, state0, params: ImpactParams, t_end, *, max_impacts: int = 10_000,
                     chatter_tol: float = 1e-6) -> ImpactHistory:
    """Event-driven motion against the rigid wall: exact flights, exact impacts, no time stepping.

    Each flight is :func:`flight_state` (closed form), each impact time :func:`next_impact_time`
    (bracketing + brentq), each impact Newton's law v → −e v (:func:`impact_velocity_after`).

    Chattering: when the approach velocity falls below ``chatter_tol`` × (largest approach
    velocity so far), the impacts are taken as a geometric sequence with the ratio r of the last
    two velocities (→ e for impacts against a force that is nearly constant over the sequence;
    Budd & Dux 1994): the remaining flight times sum to Δt_last · r/(1 − r), giving the
    accumulation time, after which the mass rests on the wall. If the net force then pushes into
    the wall (F(t) − k·gap > 0) the status is 'sticking' (the mass stays until the force reverses,
    which is not followed here); otherwise 'chattering'. A post-impact velocity of exactly zero
    (e = 0) is treated the same way, with accumulation at the impact.

    Parameters
    ----------
    t0 : float
        Start time [s].
    state0 : (float, float)
        (x0 ≤ gap [m], v0 [m/s]) at t0.
    params : ImpactParams
    t_end : float
        End of the run [s].
    max_impacts : int
        Cap on the number of impacts; reaching it gives 'not_converged'.
    chatter_tol : float
        Relative approach velocity below which the sequence is treated as chattering [-].

    Returns
    -------
    ImpactHistory
        status 'completed' (t_end reached), 'chattering', 'sticking' or 'not_converged'.
    """
    p = _validated(params)
    times, vels = [], []
    t, x, v = float(t0), float(state0[0]), float(state0[1])
    vmax = 0.0

    def done(status, msg, t_stop, xs, vs, t_acc=float("nan")):
        return ImpactHistory(np.array(times), np.array(vels), float(t_stop),
                             State(float(xs), float(vs)), float(t_acc), status, msg)

    def stop_on_wall(t_acc, how):
        f = float(_wall_force(t_acc, p))
        if f > 0:
            return done("sticking", f"{how}; impacts accumulate at t = {t_acc:.12g} s and the net "
                        f"force {f:.4g} N pushes into the wall: the mass sticks", t_acc, p.gap,
                        0.0, t_acc)
        return done("chattering", f"{how}; impacts accumulate at t = {t_acc:.12g} s (net force "
                    f"{f:.4g} N does not push into the wall)", t_acc, p.gap, 0.0, t_acc)

    for _ in range(int(max_impacts)):
        ev = next_impact_time(t, (x, v), p, t_end)
        if ev.status != "impact":
            st = flight_state(t_end, (x, v), p, t)
            return done("completed", f"{len(times)} impacts up to t_end", t_end, st.x, st.v)
        times.append(ev.time)
        vels.append(ev.velocity)
        vmax = max(vmax, ev.velocity)
        u = float(impact_velocity_after(ev.velocity, p))
        if u == 0.0 and float(_wall_force(ev.time, p)) >= 0:
            return stop_on_wall(ev.time, "zero rebound velocity (e = 0 or grazing contact)")
        if len(vels) >= 3 and ev.velocity < chatter_tol * vmax:
            r = vels[-1] / vels[-2]
            dt_last = times[-1] - times[-2]
            if 0 < r < 1:
                return stop_on_wall(times[-1] + dt_last * r / (1 - r),
                                    f"chattering detected (velocity ratio {r:.6g})")
        t, x, v = ev.time, p.gap, u
    return done("not_converged", f"max_impacts = {max_impacts} reached before t_end", t, x, v)


# --- the impact map and periodic impacting orbits -----------------------------------------------


class PeriodicOrbit(NamedTuple):
    phase: float  #: impact time modulo the forcing period, in [0, 2π/Ω) [s]
    velocity: float  #: approach velocity at the impact [m/s]
    period: float  #: orbit period n·2π/Ω [s]
    multipliers: np.ndarray  #: Floquet multipliers: eigenvalues of the impact map's Jacobian [-]
    jacobian: np.ndarray  #: 2×2 Jacobian ∂(t_next, v_next)/∂(t, v) of the impact map
    status: str  #: 'periodic', 'period_doubling', 'unstable' or 'not_converged'
    message: str


def impact_map(t_impact, approach_velocity, params: ImpactParams, t_max=None):
    """One application of the impact map P: (t_i, v_i) → (t_(i+1), v_(i+1)).

    The mass leaves the wall at t_i with velocity −e v_i, flies in closed form, and strikes the
    wall again at t_(i+1) with approach velocity v_(i+1) (:func:`next_impact_time`).

    Returns
    -------
    ImpactEvent
        Next impact (status 'no_impact' if none before ``t_max``, default t_i + 100 forcing or
        natural periods).
    """
    p = _validated(params)
    if t_max is None:
        w = max(p.forcing_frequency, np.sqrt(p.stiffness / p.mass), 1e-300)
        t_max = t_impact + 100 * 2 * np.pi / w
    u = float(impact_velocity_after(approach_velocity, p))
    return next_impact_time(t_impact, (p.gap, u), p, t_max)


def impact_map_jacobian(t_impact, approach_velocity, t_next, v_next, params: ImpactParams):
    """Analytic Jacobian of the impact map, ∂(t_(i+1), v_(i+1)) / ∂(t_i, v_i) (2×2).

    With y0 = (gap, −e v_i) the state leaving the wall at t_i, Φ(Δ) the homogeneous transition
    matrix over Δ = t_(i+1) − t_i and f(t, y) the right-hand side: ∂y(s)/∂v_i = Φ(Δ)(0, −e)ᵀ,
    ∂y(s)/∂t_i = −Φ(Δ) f(t_i, y0) at fixed s; the implicit function theorem on x(s) = gap gives
    ∂s/∂p = −(∂x/∂p)/ẋ(s), and ∂v_(i+1)/∂p = ∂ẋ/∂p + ẍ(s) ∂s/∂p. Singular at grazing
    (v_(i+1) = 0). Its determinant is e² exp(−(c/m)Δ) · v_i/v_(i+1).

    Reference: Shaw & Holmes (1983), §3 (the impact map and its linearisation).
    """
    p = _validated(params)
    e = p.restitution
    d = float(t_next) - float(t_impact)
    f11, f12, f21, f22 = (float(q) for q in _transition(d, p))
    u = -e * float(approach_velocity)
    fy = np.array([u, float(_accel(t_impact, p.gap, u, p))])
    Phi = np.array([[f11, f12], [f21, f22]])
    dy_dt = -Phi @ fy
    dy_dv = Phi @ np.array([0.0, -e])
    vs = float(v_next)
    acc = float(_accel(t_next, p.gap, vs, p))
    J = np.empty((2, 2))
    for j, dy in enumerate((dy_dt, dy_dv)):
        ds = -dy[0] / vs
        J[0, j] = ds
        J[1, j] = dy[1] + acc * ds
    return J


def _classify(mult):
    mags = np.abs(mult)
    if np.all(mags < 1):
        return "periodic", "stable: all |multipliers| < 1"
    real_neg = [m for m in mult if abs(m.imag) < 1e-12 and m.real < -1]
    if real_neg:
        return "period_doubling", (f"a real multiplier {real_neg[0].real:.6g} < −1: the orbit "
                                   "has passed a period-doubling bifurcation (unstable)")
    return "unstable", f"unstable: max |multiplier| = {mags.max():.6g} (not through −1)"


def periodic_orbits(params: ImpactParams, n: int = 1, *, n_scan: int = 400,
                    check_flight: bool = True) -> list:
    """All 1-impact-per-n-forcing-periods orbits of the impact oscillator, with their stability.

    Solved directly on the impact map, without simulation: for an impact at time τ the mass
    leaves the wall with u = −e v and must return at τ + nT (T = 2π/Ω) with approach velocity v.
    Because the flight is affine in u, the condition x(τ + nT) = gap gives u(τ) explicitly, and
    the remaining condition ẋ(τ + nT) = −u(τ)/e is one scalar equation in τ, bracketed on a grid
    of ``n_scan`` phases over one period and solved with brentq. Candidates with v ≤ 0 or whose
    flight meets the wall before τ + nT (checked with :func:`next_impact_time`) are discarded.
    Stability from the Floquet multipliers (eigenvalues of :func:`impact_map_jacobian`).

    Parameters
    ----------
    params : ImpactParams
        Needs Ω > 0 and 0 < e ≤ 1.
    n : int
        Forcing periods per impact, ≥ 1.
    n_scan : int
        Grid size for bracketing the phase.
    check_flight : bool
        Discard orbits whose flight would strike the wall early (physically inadmissible).

    Returns
    -------
    list of PeriodicOrbit
        Sorted by phase; empty if none. status 'periodic' (stable), 'period_doubling' (a
        multiplier < −1), 'unstable' (otherwise unstable), each with a message.

    Reference: Shaw & Holmes (1983); Budd & Dux (1994) for the n-periodic orbits.
    """
    from scipy.optimize import brentq

    p = _validated(params)
    if p.forcing_frequency <= 0 or p.restitution <= 0:
        raise ValueError("periodic_orbits needs forcing_frequency > 0 and restitution > 0")
    if int(n) != n or n < 1:
        raise ValueError(f"n = {n!r} is outside the allowed range: integers >= 1")
    T = 2 * np.pi / p.forcing_frequency
    P = n * T
    e = p.restitution
    f11, f12, f21, f22 = (float(q) for q in _transition(P, p))
    # x(τ + nT) = xp1 + f11 (gap − xp0) + f12 (u − vp0) and ẋ(τ + nT) = vp1 + f21 (gap − xp0) + f22 (u − vp0).
    # Generic case: the position condition gives u, the velocity condition is the equation in τ.
    # Degenerate case, nT a multiple of π/ω_d (f12 = 0): x(τ + nT) does not depend on u, so the position
    # condition is the equation in τ and the velocity condition e ẋ(τ + nT) + u = 0 gives u.
    degenerate = abs(f12) < 1e-12 * max(P, 1.0)
    if degenerate and abs(1.0 + e * f22) < 1e-12:
        return []  # e = 1 with ẋ(τ + nT) = −u: a continuous family, no isolated orbit

    def u_of(tau):
        xp0, vp0, _ = _particular(tau, p, tau)
        xp1, vp1, _ = _particular(tau + P, p, tau)
        if degenerate:
            u = -e * (vp1 + f21 * (p.gap - xp0) - f22 * vp0) / (1.0 + e * f22)
            return u, (xp0, vp0, xp1, vp1)
        return (p.gap - xp1 - f11 * (p.gap - xp0)) / f12 + vp0, (xp0, vp0, xp1, vp1)

    def resid(tau):
        u, (xp0, vp0, xp1, vp1) = u_of(tau)
        if degenerate:
            return xp1 + f11 * (p.gap - xp0) - p.gap
        v_next = vp1 + f21 * (p.gap - xp0) + f22 * (u - vp0)
        return e * v_next + u

    taus = np.linspace(0.0, T, int(n_scan) + 1)
    r = np.array([resid(t) for t in taus])
    orbits = []
    for i in range(len(taus) - 1):
        if r[i] == 0 or r[i] * r[i + 1] < 0:
            tau = taus[i] if r[i] == 0 else brentq(resid, taus[i], taus[i + 1], xtol=1e-15)
            if abs(resid(tau)) > 1e-8 * (1 + np.max(np.abs(r))):
                continue  # a pole, not a root
            u, _ = u_of(tau)
            v = -u / e
            if v <= 0:
                continue
            if check_flight:
                ev = next_impact_time(tau, (p.gap, u), p, tau + P + 0.5 * T)
                if ev.status != "impact" or abs(ev.time - (tau + P)) > 1e-8 * P:
                    continue
            J = impact_map_jacobian(tau, v, tau + P, v, p)
            mult = np.linalg.eigvals(J)
            status, msg = _classify(mult)
            orbits.append(PeriodicOrbit(float(tau % T), float(v), float(P), mult, J, status,
                                        f"n = {n}: " + msg))
    return orbits


def periodic_orbit(params: ImpactParams, n: int = 1, **kw) -> PeriodicOrbit:
    """The stable 1-impact-per-n-periods orbit if there is one, else the first found.

    status 'not_converged' (with nan fields) when :func:`periodic_orbits` finds none.
    """
    orbits = periodic_orbits(params, n, **kw)
    for o in orbits:
        if o.status == "periodic":
            return o
    if orbits:
        return orbits[0]
    nan = float("nan")
    return PeriodicOrbit(nan, nan, nan, np.full(2, nan), np.full((2, 2), nan), "not_converged",
                         f"no admissible 1-impact-per-{n}-period orbit found")
