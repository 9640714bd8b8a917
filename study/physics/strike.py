"""A strike of a tool joint on the bore-hole wall, from its own local physics (docs/reference_model.md §2.3).

Pure functions, SI units, no I/O. A strike lasts 0.1-1 ms; the bending waves it sends along the pipe travel at the
group velocity c_g = 2√(ω a), a = √(EI/ρA) (Graff, *Wave Motion in Elastic Solids*, 1975, §3.1), about 2 km/s at
1 kHz for a 4½-in drill pipe, and come back from the neighbouring joints (9.45 m away) only after some 5-10 ms. So
the strike's force is decided locally: the tool joint's lumped mass m_j on an infinite Euler–Bernoulli beam (the
string's mass per length ρA, its mud and added mass included, and bending stiffness EI), the whole moving towards
the wall at the approach speed v0 at the onset, the wall's force F = K δ^{3/2} (1 + χ δ̇)₊ at the joint (Hertz
with Hunt–Crossley damping, :func:`study.physics.contact.hertz_force`, χ = h(e)/v0 as the reference model sets it
at an onset).

The infinite beam's displacement at a point under a point force P(t) there is w(t) = ∫₀ᵗ P(τ) g(t − τ) dτ with the
impulse response (Timoshenko 1913; Goldsmith, *Impact*, 1960, ch. 4)

    g(t) = √t / (ρA √(2π a))                                           [m/(N s)]

(:func:`beam_impulse_response`): its Fourier transform, with the Laplace transform of √t, (√π/2) s^{-3/2} at s = iω,
is −(1 + i)/(4 ρA √a ω^{3/2}), the beam's point receptance, whose driving-point impedance is 2 ρA c_B (1 + i),
c_B = √(ω a) the bending phase speed (Cremer, Heckl & Petersson, *Structure-Borne Sound*, 3rd ed., 2005, §5.4;
tested against a modal sum of a long simply supported beam at short times). The beam's tension T adds T k² to
EI k⁴ at the strike's wavenumbers k = √(ω/a): 0.5 % at 500 Hz for 100 kN on a 4½-in pipe, left out.

The strike (:func:`strike`): the joint's approach δ(t) (δ(0) = 0, δ̇(0) = v0) with the beam's reaction P on it,

    m_j δ̈ = P − F(δ, δ̇),        δ(t) = v0 t − ∫₀ᵗ P(τ) g(t − τ) dτ,

a Volterra equation with a √t kernel; differentiated, P = κ D^{1/2}(v0 − δ̇), κ = ρA √(2π a)/Γ(3/2): the beam
is a half-order dashpot on the velocity the point lost (its impedance ∝ √ω). Solved on a fixed step by the L1
scheme for the half-order derivative (Oldham & Spanier, *The Fractional Calculus*, 1974, §8.2; Lin & Xu, J.
Comput. Phys. 225 (2007) 1533–1552, doi:10.1016/j.jcp.2007.02.001), the joint's momentum by backward Euler and
its approach by the trapezoidal rule: first order in the step (a product-integrated first-kind form with P linear
on each step rang unstably), so :func:`strike_peak_table` takes the Richardson extrapolation of two steps, second
order (tested by halving the step). Limits:
ρA → 0 (the beam gives nothing) is the mass on a Hertz spring, F_max = K^{2/5} (5/4 m_j v0²)^{3/5} (Johnson,
*Contact Mechanics*, 1985, §11.4); m_j = 0 (the beam alone on the wall) scales as F_max ∝ v0^{9/8} (δ ~ v0 t and
K δ^{3/2} t^{3/2}/(ρA √a) ~ δ give t ∝ v0^{-1/4}, F ∝ v0^{9/8}; with χ = h/v0 the damping is scale-free too).

The strike's bending moment (docs/reference_model.md §2.3.1): the infinite beam's moment at a distance x from a unit
impulse, m(x, t) = √(a/(4π t)) sin(π/4 − x²/(4at)) (:func:`beam_moment_response`; √(a/(8π t)) under the load), its
step response in closed form by the Fresnel integrals (:func:`beam_moment_step`), the strike's moment by product
integration of the beam's reaction on the joint (:func:`strike_moment`), and the correction for the modes left out,
the local moment less the N kept modes' share of it under the same strike (:func:`strike_moment_table`).
"""

from __future__ import annotations

import functools
from typing import NamedTuple

import numpy as np

from study.physics.contact import hertz_force, linearised_stiffness
from study.physics.restitution import check_range

__all__ = ["beam_impulse_response", "group_velocity", "driving_point_resistance", "Strike", "strike",
           "strike_peak_table", "peak_force", "return_time", "beam_moment_response", "beam_moment_step",
           "step_convolution", "beam_reaction", "modal_moment_step", "StrikeMoment", "strike_moment",
           "strike_moment_peak", "strike_moment_table", "moment_correction", "strike_pulse_table",
           "strike_moment_history", "strike_history_table", "history_correction"]


def _wave_parameter(mass_per_length, bending_stiffness):
    """a = √(EI/ρA) [m²/s]."""
    return np.sqrt(bending_stiffness / mass_per_length)


def beam_impulse_response(t, mass_per_length, bending_stiffness):
    """g(t) = √t/(ρA √(2π a)) [m/(N s)], a = √(EI/ρA): the displacement at the loaded point of an infinite
    Euler–Bernoulli beam under a unit impulse there at t = 0 (Timoshenko 1913; Goldsmith 1960, ch. 4); 0 for t < 0.
    t [s], mass_per_length ρA [kg/m], bending_stiffness EI [N m²]. Arrays broadcast."""
    t = np.asarray(t, float)
    a = _wave_parameter(mass_per_length, bending_stiffness)
    return np.sqrt(np.maximum(t, 0.0)) / (mass_per_length * np.sqrt(2.0 * np.pi * a))


def group_velocity(omega, mass_per_length, bending_stiffness):
    """c_g = 2√(ω a) [m/s] of bending waves of circular frequency ω [rad/s] on an Euler–Bernoulli beam (Graff 1975,
    §3.1), a = √(EI/ρA)."""
    return 2.0 * np.sqrt(np.asarray(omega, float) * _wave_parameter(mass_per_length, bending_stiffness))


def driving_point_resistance(omega, mass_per_length, bending_stiffness):
    """Re Z = 2 ρA c_B [N s/m], c_B = √(ω a) the bending phase speed, a = √(EI/ρA): the real part of an infinite
    Euler–Bernoulli beam's driving-point impedance Z = 2 ρA c_B (1 + i) under a point force of circular frequency ω
    [rad/s] (Cremer, Heckl & Petersson, *Structure-Borne Sound*, 3rd ed., 2005, §5.4; the Fourier transform of
    :func:`beam_impulse_response`): the resistance of the bending waves the point sends away both ways, the power a
    point moving at velocity amplitude V there loses to them being ½ Re Z V². 0 at ω = 0."""
    omega = np.maximum(np.asarray(omega, float), 0.0)
    return 2.0 * mass_per_length * np.sqrt(omega * _wave_parameter(mass_per_length, bending_stiffness))


def return_time(duration, distance, mass_per_length, bending_stiffness):
    """The time [s] the bending waves of a strike of ``duration`` T_c [s] take to reach a point ``distance`` [m]
    away (the neighbouring joint, whose own strike's waves come back as soon): distance / c_g at ω = 2π/T_c, the
    frequency below which the strike's force spectrum holds its bulk. The local model holds while T_c is shorter."""
    omega = 2.0 * np.pi / np.asarray(duration, float)
    return np.asarray(distance, float) / group_velocity(omega, mass_per_length, bending_stiffness)


class Strike(NamedTuple):
    peak_force: float  #: largest F [N]
    duration: float  #: time from the onset to the end of the force, or to its fall below END_SHARE of its peak [s]
    rebound_speed: float  #: −δ̇ where the force ended [m/s]
    ended: bool  #: whether the force ended within the run
    steps_to_peak: int  #: steps of the run up to the peak
    times: np.ndarray  #: (n,) [s]
    force: np.ndarray  #: (n,) F [N]
    approach: np.ndarray  #: (n,) δ [m]


#: Share of its peak at which a strike's force, falling, is taken as ended.
END_SHARE = 1e-3
#: A run stops at this many times the steps to its peak where the force has not ended (:class:`Strike` ``ended``).
PAST_PEAK = 4


def _l1_weights(n):
    """b_k = (k + 1)^{1/2} − k^{1/2}, k = 0 … n − 1: the L1 scheme's weights of the half-order derivative
    (Oldham & Spanier, *The Fractional Calculus*, 1974, §8.2; Lin & Xu, J. Comput. Phys. 225, 1533–1552, 2007)."""
    k = np.arange(n, dtype=float)
    return np.sqrt(k + 1.0) - np.sqrt(k)


def _time_scale(joint_mass, stiffness, mass_per_length, bending_stiffness, speed):
    """A time [s] of the strike's rise: the longer of the mass-on-Hertz-spring one, α_max/v0 with
    α_max = (5 m v0²/4K)^{2/5}, and the beam-alone one, (c K √v0)^{-1/2} with g = c √t."""
    c = float(beam_impulse_response(1.0, mass_per_length, bending_stiffness))
    beam = (c * stiffness * np.sqrt(speed)) ** -0.5
    if joint_mass <= 0.0:
        return beam
    mass = (1.25 * joint_mass * speed**2 / stiffness) ** 0.4 / speed
    return max(mass, beam)  # the two inertias together rise slower than either


def strike(joint_mass, stiffness, mass_per_length, bending_stiffness, speed, hysteresis=0.0,
           steps_per_rise: int = 200, max_steps: int = 20_000) -> Strike:
    """A tool joint's strike on the wall, locally (module docstring): its mass ``joint_mass`` m_j [kg] ≥ 0 on an
    infinite beam of ``mass_per_length`` ρA [kg/m] > 0 and ``bending_stiffness`` EI [N m²] > 0, approaching the wall
    at ``speed`` v0 [m/s] > 0 with the beam about it, the wall's Hertz ``stiffness`` K [N m^-3/2] > 0 and the
    Hunt–Crossley ``hysteresis`` h = χ v0 [-] ≥ 0 (:func:`study.physics.contact.calibrated_hysteresis`). A fixed
    step of 1/``steps_per_rise`` of the rise's time scale, run until the force has ended (or ``max_steps``)."""
    m = float(check_range(joint_mass, "joint_mass", 0.0, np.inf, high_open=True))
    K = float(check_range(stiffness, "stiffness", 0.0, np.inf, low_open=True, high_open=True))
    rho = float(check_range(mass_per_length, "mass_per_length", 0.0, np.inf, low_open=True, high_open=True))
    ei = float(check_range(bending_stiffness, "bending_stiffness", 0.0, np.inf, low_open=True, high_open=True))
    v0 = float(check_range(speed, "speed", 0.0, np.inf, low_open=True, high_open=True))
    chi = float(check_range(hysteresis, "hysteresis", 0.0, np.inf, high_open=True)) / v0
    dt = _time_scale(m, K, rho, ei, v0) / steps_per_rise
    # the beam's reaction as a half-order derivative of the velocity it lost, P = κ D^{1/2}(v0 − δ̇),
    # κ = ρA √(2π a)/Γ(3/2) (the derivative of δ(t) = v0 t − ∫ P g: g' = c/(2√t)), by the L1 scheme
    kappa = float(1.0 / (beam_impulse_response(1.0, rho, ei) * 0.5 * np.sqrt(np.pi)))
    b = _l1_weights(max_steps + 1)
    c0 = kappa / np.sqrt(dt)  # P_n = c0 (b_0 (u_n − u_{n−1}) + Σ_{k≥1} b_k (u_{n−k} − u_{n−k−1}))
    F = np.zeros(max_steps + 1)
    d = np.zeros(max_steps + 1)
    v = np.zeros(max_steps + 1)
    du = np.zeros(max_steps + 1)  # u_j − u_{j−1}, u = v0 − δ̇
    v[0] = v0
    ended = False
    n = 0
    for n in range(1, max_steps + 1):
        hist = c0 * np.dot(b[1:n], du[n - 1:0:-1])  # Σ_{k=1}^{n−1} b_k du_{n−k}
        x = d[n - 1] + dt * v[n - 1]  # predictor
        for _ in range(50):
            vn = 2.0 * (x - d[n - 1]) / dt - v[n - 1]
            pn = hist + c0 * (v[n - 1] - vn)  # du_n = u_n − u_{n−1} = v_{n−1} − v_n
            if x > 0.0:
                bracket = 1.0 + chi * vn
                fn = float(hertz_force(x, K, vn, chi))
                dF = (float(linearised_stiffness(x, K)) * bracket + float(hertz_force(x, K)) * chi * 2.0 / dt
                      if bracket > 0 else 0.0)
            else:
                fn, dF = 0.0, 0.0
            # the joint at t_n: m (v_n − v_{n−1})/Δt = P_n − F_n
            r = m * (vn - v[n - 1]) - dt * (pn - fn)
            dr = 2.0 * m / dt + dt * (2.0 * c0 / dt + dF)
            step = r / dr
            x -= step
            if abs(step) <= 1e-13 * max(abs(x), v0 * dt):
                break
        d[n], v[n] = x, 2.0 * (x - d[n - 1]) / dt - v[n - 1]
        du[n] = v[n - 1] - v[n]
        F[n] = float(hertz_force(x, K, v[n], chi)) if x > 0.0 else 0.0
        if n > 1 and (F[n] <= 0.0 or F[n] < END_SHARE * np.max(F[:n])):
            ended = True  # the force has ended, or fallen past its peak to END_SHARE of it
            break
        if n >= PAST_PEAK * max(int(np.argmax(F[:n + 1])), 1):
            break  # the beam alone lets go only as 1/√t (a massless joint's force): its peak lies far behind
    times = np.arange(n + 1) * dt
    peak = int(np.argmax(F[:n + 1]))
    return Strike(peak_force=float(F[peak]), duration=float(times[-1]), rebound_speed=float(-v[n]), ended=ended,
                  steps_to_peak=peak, times=times, force=F[:n + 1].copy(), approach=d[:n + 1].copy())


#: Approach speeds [m/s] of :func:`strike_peak_table`: 1 mm/s (whirl_kernel.ONSET_SPEED_FLOOR) to 10 m/s, log-spaced.
TABLE_SPEEDS = np.logspace(-3, 1, 17)


@functools.lru_cache(maxsize=32)
def strike_peak_table(joint_mass: float, stiffness: float, mass_per_length: float, bending_stiffness: float,
                      hysteresis: float, steps_per_rise: int = 100) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(speeds [m/s], peak forces [N], durations [s]) of :func:`strike` over :data:`TABLE_SPEEDS`, each the
    Richardson extrapolation of ``steps_per_rise`` and twice that (the scheme is first order), for
    :func:`peak_force`'s interpolation (cached per joint, wall and beam)."""
    peaks, durations = [], []
    for v in TABLE_SPEEDS:
        coarse, fine = (strike(joint_mass, stiffness, mass_per_length, bending_stiffness, v, hysteresis, n)
                        for n in (steps_per_rise, 2 * steps_per_rise))
        peaks.append(2.0 * fine.peak_force - coarse.peak_force)  # Richardson: the scheme is first order
        durations.append(2.0 * fine.duration - coarse.duration)
    return TABLE_SPEEDS.copy(), np.array(peaks), np.array(durations)


def peak_force(speed, joint_mass, stiffness, mass_per_length, bending_stiffness, hysteresis=0.0):
    """(peak force [N], duration [s]) of the local strike (:func:`strike`) at each approach ``speed`` v0 [m/s]
    (array), interpolated in log-log on :func:`strike_peak_table` (between its speeds the peak is a power of v0
    between 9/8 and 6/5 to within 0.1 %, tested); speeds outside the table are clipped to it."""
    speeds, peaks, durations = strike_peak_table(float(joint_mass), float(stiffness), float(mass_per_length),
                                                 float(bending_stiffness), float(hysteresis))
    x = np.log(np.clip(np.asarray(speed, float), speeds[0], speeds[-1]))
    return (np.exp(np.interp(x, np.log(speeds), np.log(peaks))),
            np.exp(np.interp(x, np.log(speeds), np.log(durations))))


# --- the strike's bending moment (docs/reference_model.md §2.3, "The stresses at a strike") ---------------------------

def beam_moment_response(t, x, mass_per_length, bending_stiffness):
    """m(x, t) = √(a/(4π t)) sin(π/4 − x²/(4 a t)) [N m/(N s)], a = √(EI/ρA): the bending moment −EI w'' at a
    distance x [m] from a unit impulse on an infinite Euler–Bernoulli beam at t = 0 (along the force: a sagging moment
    under the load is positive); 0 for t ≤ 0. From w(x, t) = (1/ρA) ∫ e^{ikx} sin(a k² t)/(a k²) dk/2π (Graff 1975,
    §3.1; Timoshenko 1913): −EI w'' = (a/2π) ∫ e^{ikx} sin(a k² t) dk, and ∫ e^{ikx + i a t k²} dk =
    √(π/(a t)) e^{i(π/4 − x²/(4at))} (the Fresnel integral). Under the load (x = 0) √(a/(8π t)). Arrays broadcast."""
    t = np.asarray(t, float)
    a = _wave_parameter(mass_per_length, bending_stiffness)
    s = np.where(t > 0, t, 1.0)
    return np.where(t > 0, np.sqrt(a / (4.0 * np.pi * s)) * np.sin(0.25 * np.pi - np.asarray(x, float) ** 2
                                                                      / (4.0 * a * s)), 0.0)


def beam_moment_step(t, x, mass_per_length, bending_stiffness):
    """S(x, t) = ∫₀ᵗ m(x, s) ds [N m/N] of :func:`beam_moment_response`: the moment at x [m] under a unit force held
    from t = 0 on, in closed form by the Fresnel integrals (scipy.special.fresnel). With s = u², b = x²/(4a):
    S = √(a/π) [U sin(π/4 − b/U²) − 2b ∫_{1/U}^∞ cos(π/4 − b v²) dv], U = √t, the last
    (1/√2) √(π/(2b)) (1 − C(z) − S(z)), z = √(2b/(π t)); under the load √(a t/(2π)). 0 for t ≤ 0."""
    from scipy.special import fresnel

    t = np.maximum(np.asarray(t, float), 0.0)
    a = _wave_parameter(mass_per_length, bending_stiffness)
    b = np.asarray(x, float) ** 2 / (4.0 * a)
    u = np.sqrt(t)
    phase = np.where(u > 0, 0.25 * np.pi - b / np.where(u > 0, u, 1.0) ** 2, 0.25 * np.pi)
    z = np.sqrt(2.0 * b / np.pi) / np.where(u > 0, u, 1.0)
    fs, fc = fresnel(z)
    tail = np.where(u > 0, np.sqrt(np.pi * b) * (1.0 - fc - fs), 0.0)  # 2b (1/√2) √(π/(2b)) (1 − C − S)
    return np.sqrt(a / np.pi) * np.where(u > 0, u * np.sin(phase) - tail, 0.0)


def step_convolution(force, step_response):
    """M_k = Σ_{j<k} f̄_j [S(t_k − t_j) − S(t_k − t_{j+1})] on a uniform grid t_k = k h: the response to the force
    ``force`` (n,) [N] taken constant at its trapezoidal mean f̄_j on each step, from the step response
    ``step_response`` (n,) = S(t_k) (S(0) = 0; exact for the piecewise constant force: product integration, which
    keeps a kernel's t^{-1/2} singularity out of the sum)."""
    f = np.asarray(force, float)
    s = np.asarray(step_response, float)
    mean = 0.5 * (f[1:] + f[:-1])
    w = np.diff(s)  # w_i = S((i + 1) h) − S(i h)
    out = np.zeros(f.size)
    out[1:] = np.convolve(mean, w)[:f.size - 1]
    return out


def beam_reaction(result: "Strike", joint_mass: float, speed: float) -> np.ndarray:
    """(n,) P [N], the beam's reaction on the joint (the force the joint puts on the beam) over a :func:`strike`
    ``result``: the joint's momentum, m_j (v_n − v_{n−1})/Δt = P_n − F_n, with the scheme's own velocities from its
    approach by the trapezoidal rule (v_0 = ``speed``)."""
    t, d, F = result.times, result.approach, result.force
    dt = float(t[1] - t[0]) if t.size > 1 else 1.0
    v = np.empty(t.size)
    v[0] = speed
    for n in range(1, t.size):
        v[n] = 2.0 * (d[n] - d[n - 1]) / dt - v[n - 1]
    P = np.array(F, float)
    P[1:] += joint_mass * np.diff(v) / dt
    P[0] = 0.0
    return P


def modal_moment_step(t, omega, gains):
    """S_N(t) = Σ_n g_n (1 − cos ω_n t)/ω_n² [N m/N] (g_n t²/2 where ω_n = 0): the moment of N modes of frequencies
    ``omega`` (N,) [rad/s] under a unit force held from t = 0 on, ``gains`` (N,) g_n = ψ_n(x_p) M_n(x)/m [N m/(N s²)]
    (the mode's shape at the force's point, its moment per unit coordinate at the station, over its modal mass).
    t (n,) [s]."""
    t = np.asarray(t, float)[:, None]
    w = np.asarray(omega, float)[None, :]
    safe = np.where(w > 0, w, 1.0)
    terms = np.where(w > 0, (1.0 - np.cos(safe * t)) / safe**2, 0.5 * t**2)
    return terms @ np.asarray(gains, float)


class StrikeMoment(NamedTuple):
    correction: float  #: local − kept at the local moment's largest magnitude [N m], along the strike's force
    time: float  #: that time from the strike's onset [s]
    local: float  #: the local model's moment there [N m]
    kept: float  #: the kept modes' moment under the local wall force there [N m]


def strike_moment(result: "Strike", joint_mass: float, speed: float, distance: float, mass_per_length: float,
                  bending_stiffness: float, omega=None, gains=None) -> tuple[np.ndarray, np.ndarray]:
    """(local, kept) (n,) [N m] over a :func:`strike` ``result``: the local model's bending moment at ``distance``
    [m] from the struck joint (the beam's reaction P, :func:`beam_reaction`, convolved with
    :func:`beam_moment_response` by :func:`step_convolution` on the closed-form :func:`beam_moment_step`), and the
    moment the N modes ``omega``, ``gains`` (:func:`modal_moment_step`) carry under the same strike's wall force F
    (the modes hold the joint's mass, so F and not P drives them; as N grows they tend to the local moment while the
    waves have not come back). ``kept`` zeros without modes."""
    t = result.times
    P = beam_reaction(result, joint_mass, speed)
    local = step_convolution(P, beam_moment_step(t, distance, mass_per_length, bending_stiffness))
    kept = (step_convolution(result.force, modal_moment_step(t, omega, gains)) if omega is not None
            else np.zeros(t.size))
    return local, kept


#: Steps a rise of :func:`strike_moment_peak`'s coarser run (the finer twice that).
MOMENT_STEPS = 100


@functools.lru_cache(maxsize=256)
def _strike_pair(joint_mass, stiffness, mass_per_length, bending_stiffness, speed, hysteresis, steps_per_rise):
    return tuple(strike(joint_mass, stiffness, mass_per_length, bending_stiffness, speed, hysteresis, n)
                 for n in (steps_per_rise, 2 * steps_per_rise))


def strike_moment_peak(joint_mass, stiffness, mass_per_length, bending_stiffness, speed, hysteresis, distances,
                       omega, gains, steps_per_rise: int = MOMENT_STEPS) -> list[StrikeMoment]:
    """Per station at ``distances`` (S,) [m] from the joint, with the kept modes' ``gains`` (S, N) there and their
    ``omega`` (N,) (:func:`modal_moment_step`): the correction of a strike's bending moment for the modes left out
    (:class:`StrikeMoment`), local − kept (:func:`strike_moment`) at the local moment's largest magnitude over the
    contact — added to the run's modal moment at the matching instant it gives the local moment there, and it
    vanishes as the kept modes come to carry it —, the Richardson extrapolation of ``steps_per_rise`` and twice that
    (the strike's scheme is first order). Other arguments as :func:`strike`'s."""
    runs = _strike_pair(float(joint_mass), float(stiffness), float(mass_per_length), float(bending_stiffness),
                        float(speed), float(hysteresis), int(steps_per_rise))
    gains = np.atleast_2d(np.asarray(gains, float))
    out = []
    for distance, gain in zip(np.atleast_1d(distances), gains):
        pair = []
        for r in runs:
            local, kept = strike_moment(r, joint_mass, speed, float(distance), mass_per_length, bending_stiffness,
                                        omega, gain)
            k = int(np.argmax(np.abs(local)))
            pair.append(StrikeMoment(float(local[k] - kept[k]), float(r.times[k]), float(local[k]), float(kept[k])))
        coarse, fine = pair
        out.append(StrikeMoment(*(2.0 * f - c for f, c in zip(fine, coarse))))
    return out


#: The onset speeds of :func:`strike_moment_table`: every other speed of :data:`TABLE_SPEEDS` (the correction goes as
#: a power of v0 near the force's, 9/8 to 6/5, so log-log interpolation between them holds as the force's does).
MOMENT_SPEEDS = TABLE_SPEEDS[::2]


def strike_moment_table(joint_mass, stiffness, mass_per_length, bending_stiffness, hysteresis, distances, omega,
                        gains) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(speeds (V,) [m/s], corrections (V, S) [N m], times (V, S) [s], kept (V, S) [N m]) of
    :func:`strike_moment_peak` over :data:`MOMENT_SPEEDS` at the stations ``distances`` (S,): per joint, like
    :func:`strike_peak_table` for the force."""
    rows = [strike_moment_peak(joint_mass, stiffness, mass_per_length, bending_stiffness, v, hysteresis, distances,
                               omega, gains) for v in MOMENT_SPEEDS]
    return (MOMENT_SPEEDS.copy(), np.array([[r.correction for r in row] for row in rows]),
            np.array([[r.time for r in row] for row in rows]), np.array([[r.kept for r in row] for row in rows]))


def moment_correction(speed, table, column: int = 1) -> np.ndarray:
    """(n, S) the correction [N m] at each onset ``speed`` (n,) [m/s], interpolated on :func:`strike_moment_table`'s
    ``table`` per station (or its ``column``: 2 the times [s], 3 the kept modes' moment [N m]): in log-log where
    the values keep one sign, linearly in log v0 otherwise; speeds outside the table clipped to it."""
    speeds, values = table[0], table[column]
    x = np.log(np.clip(np.atleast_1d(np.asarray(speed, float)), speeds[0], speeds[-1]))
    out = np.zeros((x.size, values.shape[1]))
    for s in range(values.shape[1]):
        c = values[:, s]
        if np.all(c > 0) or np.all(c < 0):
            out[:, s] = np.sign(c[0]) * np.exp(np.interp(x, np.log(speeds), np.log(np.abs(c))))
        else:
            out[:, s] = np.interp(x, np.log(speeds), c)
    return out



#: Samples of :func:`strike_history_table`'s correction histories over their horizon, evenly in time.
HISTORY_SAMPLES = 512


def strike_moment_history(joint_mass, stiffness, mass_per_length, bending_stiffness, speed, hysteresis, distances,
                          omega, gains, horizon, steps_per_rise: int = MOMENT_STEPS, samples: int = HISTORY_SAMPLES
                          ) -> tuple[np.ndarray, np.ndarray, float]:
    """The correction of a strike's bending for the modes left out as a history (docs/reference_model.md §2.3.1):
    (times (T,) [s] from the onset, evenly over [0, ``horizon``], corrections (T, S) [N m] at the stations
    ``distances`` (S,) [m] from the joint, the strike's duration T_c [s]): the infinite beam's moment under the local
    strike (:func:`strike_moment`, the beam's reaction P convolved with the closed-form step response) less the kept
    modes' share under its wall force F (``omega`` (N,), ``gains`` (S, N) as :func:`strike_moment_peak`'s), with the
    force nil after the strike: the waves it sent go on past the stations, and under the joint the beam's moment
    falls as t^{-1/2} only, its part above the kept modes' band ringing at their highest frequency and falling as
    1/(k_N √(a t)) of it (:func:`beam_moment_response`). Added to the run's kept modes' moment along the strike's
    force at each row of the horizon it gives the infinite beam's moment there as the kept modes tend to it; the
    Richardson extrapolation of ``steps_per_rise`` and twice that (the strike's scheme is first order). Other
    arguments as :func:`strike`'s."""
    runs = _strike_pair(float(joint_mass), float(stiffness), float(mass_per_length), float(bending_stiffness),
                        float(speed), float(hysteresis), int(steps_per_rise))
    gains = np.atleast_2d(np.asarray(gains, float))
    out_t = np.linspace(0.0, float(horizon), samples)
    pair = []
    for r in runs:
        dt = float(r.times[1] - r.times[0])
        n = max(int(np.ceil(horizon / dt)) + 2, r.times.size + 1)
        t = np.arange(n) * dt
        m = r.times.size  # the force is nil from there on: its steps' means (as step_convolution's) over the strike
        P, F = np.zeros(m + 1), np.zeros(m + 1)
        P[:m], F[:m] = beam_reaction(r, joint_mass, speed), r.force
        mean_p, mean_f = 0.5 * (P[1:] + P[:-1]), 0.5 * (F[1:] + F[:-1])
        kept_step = modal_moment_step(t, omega, gains.T)  # (n, S)
        rows = np.zeros((samples, gains.shape[0]))
        locals_ = {}  # per distance (the infinite beam's moment is the same at every joint's station that far)
        for s, d in enumerate(np.atleast_1d(distances)):
            if float(d) not in locals_:
                local = np.zeros(n)
                local[1:] = np.convolve(mean_p, np.diff(beam_moment_step(t, float(d), mass_per_length,
                                                                         bending_stiffness)))[:n - 1]
                locals_[float(d)] = local
            local = locals_[float(d)]
            kept = np.zeros(n)
            kept[1:] = np.convolve(mean_f, np.diff(kept_step[:, s]))[:n - 1]
            rows[:, s] = np.interp(out_t, t, local - kept)
        pair.append(rows)
    coarse, fine = pair
    return out_t, 2.0 * fine - coarse, 2.0 * runs[1].duration - runs[0].duration


def strike_history_table(joint_mass, stiffness, mass_per_length, bending_stiffness, hysteresis, distances, omega,
                         gains, horizon) -> dict[str, np.ndarray]:
    """:func:`strike_moment_history` over :data:`MOMENT_SPEEDS`: ``speeds`` (V,) [m/s], ``durations`` (V,) T_c [s],
    ``times`` (T,) [s], ``corrections`` (V, T, S) [N m], for :func:`history_correction`."""
    rows = [strike_moment_history(joint_mass, stiffness, mass_per_length, bending_stiffness, v, hysteresis, distances,
                                  omega, gains, horizon) for v in MOMENT_SPEEDS]
    return dict(speeds=MOMENT_SPEEDS.copy(), durations=np.array([r[2] for r in rows]), times=rows[0][0],
                corrections=np.array([r[1] for r in rows]))


def history_correction(speed: float, after, table) -> np.ndarray:
    """(R, S) the correction [N m] of :func:`strike_history_table`'s ``table`` at the times ``after`` (R,) [s] from the
    onset of a strike at ``speed`` [m/s]: between the two table speeds about it, each history at the time scaled by
    its duration over the strike's (T_c interpolated in log-log; the rise scales with T_c), weighted linearly in
    log v0; speeds outside the table clipped to it; nil beyond the table's horizon."""
    speeds, durations, times, c = table["speeds"], table["durations"], table["times"], table["corrections"]
    x = float(np.clip(np.log(max(float(speed), speeds[0])), np.log(speeds[0]), np.log(speeds[-1])))
    i = int(np.clip(np.searchsorted(np.log(speeds), x) - 1, 0, speeds.size - 2))
    w = (x - np.log(speeds[i])) / (np.log(speeds[i + 1]) - np.log(speeds[i]))
    own = float(np.exp((1 - w) * np.log(durations[i]) + w * np.log(durations[i + 1])))
    after = np.asarray(after, float)
    out = np.zeros((after.size, c.shape[2]))
    for j, weight in ((i, 1.0 - w), (i + 1, w)):
        t = after * durations[j] / own
        for s in range(c.shape[2]):
            out[:, s] += weight * np.interp(t, times, c[j, :, s], left=0.0, right=0.0)
    return np.where(((after >= 0) & (after <= times[-1]))[:, None], out, 0.0)

#: Points of the grid of t/T_c on which :func:`strike_pulse_table` tabulates a strike's force shape F/F_peak.
PULSE_GRID = 65


@functools.lru_cache(maxsize=32)
def strike_pulse_table(joint_mass: float, stiffness: float, mass_per_length: float, bending_stiffness: float,
                       hysteresis: float, steps_per_rise: int = 100, grid: int = PULSE_GRID) -> dict[str, np.ndarray]:
    """The local strike's force history at each of :data:`TABLE_SPEEDS` (docs/reference_model.md §2.4), for the
    reference run to apply it to its modes in place of the contact law: ``speeds`` (S,) [m/s], ``peak`` (S,) F_peak
    [N] and ``duration`` (S,) T_c [s] (the Richardson extrapolations of ``steps_per_rise`` and twice that, as
    :func:`strike_peak_table`), ``impulse`` (S,) ∫F dt [N s] (the finer run's, trapezoidal), ``loss`` (S,) ∫F dδ [J],
    the energy the wall takes from the joint and its beam over the history (trapezoidal in the runs' approach δ,
    their Richardson extrapolation: the Hunt–Crossley loss, and where the force has not ended the Hertz energy still
    stored; the local strike's net work on its joint-and-beam is −loss, docs/reference_model.md §2.4), ``ended`` (S,)
    whether the force ended within the run (where the wall's damping eats the rebound the joint does not let go: the
    run stops at :data:`PAST_PEAK` times its rise, 13-18 % of the peak left at e = 0.3, and the history is taken to
    there), and the force's shape F/F_peak on ``grid`` points
    of s = t/T_c ∈ [0, 1], ``shape`` (S, grid) (the finer run's, linear between its steps), with ``coefficients`` (S,
    4, grid − 1) of its natural cubic spline in s (value at s_i + x: ((c0 x + c1) x + c2) x + c3), which is smooth to
    its second derivative for an explicit integrator. Arguments as :func:`strike`; cached per joint, wall and beam."""
    from scipy.interpolate import CubicSpline

    s = np.linspace(0.0, 1.0, grid)
    peaks, durations, impulses, losses, ended, shapes, coefficients = [], [], [], [], [], [], []
    for v in TABLE_SPEEDS:
        coarse, fine = (strike(joint_mass, stiffness, mass_per_length, bending_stiffness, v, hysteresis, n)
                        for n in (steps_per_rise, 2 * steps_per_rise))
        peaks.append(2.0 * fine.peak_force - coarse.peak_force)
        durations.append(2.0 * fine.duration - coarse.duration)
        impulses.append(float(np.trapezoid(fine.force, fine.times)))
        losses.append(2.0 * float(np.trapezoid(fine.force, fine.approach))
                      - float(np.trapezoid(coarse.force, coarse.approach)))
        ended.append(fine.ended and coarse.ended)
        shape = np.interp(s * fine.duration, fine.times, fine.force) / fine.peak_force
        shape[0] = 0.0
        shapes.append(shape)
        coefficients.append(CubicSpline(s, shape, bc_type="natural").c)
    return dict(speeds=TABLE_SPEEDS.copy(), peak=np.array(peaks), duration=np.array(durations),
                impulse=np.array(impulses), loss=np.array(losses), ended=np.array(ended), shape=np.array(shapes),
                grid=s, coefficients=np.array(coefficients))
