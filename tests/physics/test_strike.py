"""The local model of a strike (study.physics.strike; docs/reference_model.md §2.3)."""

import numpy as np
import pytest

from study.physics import hertz, strike
from study.physics.contact import calibrated_hysteresis, hertz_wall_impact

# the default study's pipe and joint (configs/default.toml at 250 rpm, 5 000 lbf, 9 ppg, its three-joint section as
# reference.build_model makes it): m_j, the joints' Hertz K, the string's mass per length (mud and added mass in it), EI
JOINT, K, RHO, EI = 45.117, 6.289e11, 49.346, 827410.0


def test_the_impulse_response_is_a_long_simply_supported_beams_at_short_times():
    # a 200-m simply supported beam struck at its middle: g(t) = Σ_n (2/(ρA ℓ)) sin²(nπ/2) sin(ω_n t)/ω_n,
    # ω_n = (nπ/ℓ)² a (any vibration text's modal sum); at 2-10 ms no wave has come back from 100 m away
    length, n = 200.0, np.arange(1, 400_001, 2, dtype=float)
    a = np.sqrt(EI / RHO)
    omega = (n * np.pi / length) ** 2 * a
    for t in (2e-3, 5e-3, 1e-2):
        modal = np.sum(2.0 / (RHO * length) * np.sin(omega * t) / omega)
        assert strike.beam_impulse_response(t, RHO, EI) == pytest.approx(modal, rel=2e-3), t
    assert strike.beam_impulse_response(-1e-3, RHO, EI) == 0.0


def test_the_impulse_response_has_the_beams_point_receptance():
    # ∫₀^∞ g(t) e^{−st} dt = c Γ(3/2) s^{-3/2}: on the imaginary axis −(1 + i)/(4 ρA √a ω^{3/2}), the point receptance
    # of the infinite beam whose driving-point impedance is 2 ρA c_B (1 + i), c_B = √(ω a) (Cremer, Heckl & Petersson
    # 2005, §5.4): receptance = 1/(iω Z)
    a, omega = np.sqrt(EI / RHO), 2 * np.pi * 700.0
    c = float(strike.beam_impulse_response(1.0, RHO, EI))
    laplace = c * 0.5 * np.sqrt(np.pi) * (1j * omega) ** -1.5
    impedance = 2 * RHO * np.sqrt(omega * a) * (1 + 1j)
    assert laplace == pytest.approx(1.0 / (1j * omega * impedance), rel=1e-12)


def test_the_driving_point_resistance_is_the_real_part_of_the_impulse_responses_impedance():
    # Z = 1/(iω G(iω)), G the Laplace transform of g(t) = c √t, c Γ(3/2) s^{-3/2} (as the test above): its real part is
    # 2 ρA √(ω a) (Cremer, Heckl & Petersson 2005, §5.4), the resistance the residual vectors' "radiating" damping takes
    c = float(strike.beam_impulse_response(1.0, RHO, EI))
    for hz in (300.0, 1500.0, 6000.0):
        omega = 2 * np.pi * hz
        impedance = 1.0 / (1j * omega * c * 0.5 * np.sqrt(np.pi) * (1j * omega) ** -1.5)
        assert strike.driving_point_resistance(omega, RHO, EI) == pytest.approx(impedance.real, rel=1e-10), hz
    assert strike.driving_point_resistance(0.0, RHO, EI) == 0.0


def test_without_the_beam_the_strike_is_hertzs_mass_on_a_spring():
    # ρA → 0: F_max = K^{2/5} (5/4 m v0²)^{3/5} (Johnson 1985 §11.4; hertz.hertz_impact), and with the Hunt–Crossley
    # damping the integrated single impact (contact.hertz_wall_impact)
    h = calibrated_hysteresis(0.7)

    def peak(v, hysteresis):  # the Richardson extrapolation of two steps, as strike_peak_table takes it
        coarse, fine = (strike.strike(JOINT, K, 1e-6, EI, v, hysteresis, n).peak_force for n in (100, 200))
        return 2 * fine - coarse

    for v in (0.01, 0.3, 3.0):
        assert peak(v, 0.0) == pytest.approx(float(hertz.hertz_impact(JOINT, v, K).max_force), rel=2e-3), v
    assert peak(0.3, h) == pytest.approx(hertz_wall_impact(JOINT, K, 0.3, h / 0.3).max_force, rel=2e-3)


@pytest.mark.parametrize("h", [0.0, calibrated_hysteresis(0.7)])
def test_a_massless_joint_on_the_beam_alone_scales_as_v0_to_the_nine_eighths(h):
    # m_j = 0: δ ~ v0 t and K δ^{3/2} t^{3/2}/(ρA √a) ~ δ give t ∝ v0^{-1/4}, F ∝ v0^{9/8} (module docstring; with
    # χ = h/v0 the damping term χ δ̇ is scale-free too)
    slow, fast = (strike.strike(0.0, K, RHO, EI, v, h, 100).peak_force for v in (0.1, 1.0))
    assert np.log10(fast / slow) == pytest.approx(9 / 8, abs=1e-6)


def test_the_scheme_is_first_order_and_its_extrapolation_second():
    # halving the step halves the peak's error (first order); the Richardson extrapolation of two steps
    # (strike_peak_table) moves by far less than either step's error
    h = calibrated_hysteresis(0.7)
    peaks = [strike.strike(JOINT, K, RHO, EI, 0.3, h, n).peak_force for n in (50, 100, 200, 400)]
    d = np.diff(peaks)
    assert np.all(d[1:] / d[:-1] == pytest.approx(0.5, abs=0.05)), d
    extrapolated = [2 * f - c for c, f in zip(peaks[:-1], peaks[1:])]
    assert abs(extrapolated[-1] - extrapolated[-2]) < 0.05 * abs(d[-1])


def test_the_thrown_string_strikes_as_its_256_mode_run():
    # the string thrown at 0.3 m/s onto its three joints (tests/solvers/test_modes.py): 143.2 kN at 256 modes (the
    # residual vectors; 143.5 kN the kept modes alone), 146-245 kN at 16-128 modes. The local model from v0, m_j, ρA,
    # EI, K and the calibrated χ of e = 0.7: 141.1 kN, 1.5 % low (the joint's mass as a point, the section's
    # tension and its 0.5-m length left out)
    force, duration = strike.peak_force([0.3], JOINT, K, RHO, EI, calibrated_hysteresis(0.7))
    assert force[0] == pytest.approx(143.2e3, rel=0.025)
    # the contact (0.48 ms) ends long before the waves of the neighbouring joints' strikes (9.45 m) arrive
    assert duration[0] < 0.2 * strike.return_time(duration[0], 9.45, RHO, EI)


def test_the_moment_kernel_is_its_fourier_integral():
    # −EI w'' under a unit force held from t = 0 (from w = (1/ρA) ∫ e^{ikx} sin(a k² t)/(a k²) dk/2π, integrated in
    # t): S(x, t) = (1/π) ∫₀^∞ cos(kx) (1 − cos(a k² t))/k² dk, with u = k √(at) √(at)/π ∫₀^∞ cos(u x/√(at))
    # (1 − cos u²)/u² du: scipy's quad to U = √(2000π), beyond it ∫_U^∞ cos(cu)/u² du by its Fourier weight (QAWF)
    # and the rest, of order U⁻³, left out; at x = 0 √(a t/(2π))
    from scipy.integrate import quad
    a = np.sqrt(EI / RHO)
    edges = np.sqrt(np.pi * np.arange(0, 2001, 50))  # between zeros of cos u²
    for x in (0.0, 0.25):
        for t in (2e-4, 1e-3):
            c = x / np.sqrt(a * t)
            whole = sum(quad(lambda u: np.cos(c * u) * (1 - np.cos(u * u)) / (u * u) if u > 0 else 0.0,
                             lo, hi, limit=200)[0] for lo, hi in zip(edges[:-1], edges[1:]))
            whole += (quad(lambda u: 1.0 / (u * u), edges[-1], np.inf, weight="cos", wvar=c)[0] if c > 0
                      else 1.0 / edges[-1])
            assert strike.beam_moment_step(t, x, RHO, EI) == pytest.approx(np.sqrt(a * t) / np.pi * whole,
                                                                           rel=2e-3), (x, t)
    assert strike.beam_moment_step(1e-3, 0.0, RHO, EI) == pytest.approx(np.sqrt(a * 1e-3 / (2 * np.pi)), rel=1e-12)
    # the kernel is the step's derivative: −√(a/(8π t)) as EI w'' under the load, the brief's constant
    t, h = 4e-4, 1e-9
    for x in (0.0, 0.25):
        slope = (strike.beam_moment_step(t + h, x, RHO, EI) - strike.beam_moment_step(t - h, x, RHO, EI)) / (2 * h)
        assert float(strike.beam_moment_response(t, x, RHO, EI)) == pytest.approx(float(slope), rel=1e-5)
    assert float(strike.beam_moment_response(t, 0.0, RHO, EI)) == pytest.approx(np.sqrt(a / (8 * np.pi * t)))


def test_the_moment_kernel_is_a_long_simply_supported_beams_at_short_times():
    # a 200-m simply supported beam under a unit force held at its middle from t = 0: the moment at x from the middle
    # is the static (ℓ/2 − |x|)/2 less Σ_n (2/ℓ) sin(nπ/2) sin(k_n (ℓ/2 + x)) cos(ω_n t)/k_n², k_n = nπ/ℓ,
    # ω_n = a k_n² (the modal sum of any vibration text: EI k² ψ ψ/(ρA ℓ/2 ω²) = (2/ℓ) ψ ψ/k²); at 2-10 ms no wave has
    # come back from 100 m away
    length, n = 200.0, np.arange(1, 400_001, 2, dtype=float)
    a = np.sqrt(EI / RHO)
    k = n * np.pi / length
    for x in (0.0, 0.25):
        shape = np.sin(n * np.pi / 2) * np.sin(k * (length / 2 + x))
        for t in (2e-3, 1e-2):
            modal = (length / 2 - abs(x)) / 2 - np.sum(2.0 / length * shape * np.cos(a * k * k * t) / (k * k))
            assert strike.beam_moment_step(t, x, RHO, EI) == pytest.approx(modal, rel=2e-3), (x, t)


def test_the_moment_history_after_the_strike_is_the_infinite_beams_impulse_response():
    # without kept modes the correction's history is the infinite beam's moment under the local strike; long after the
    # strike (t ≫ T_c = 0.43 ms) that is its impulse's response, I m(x, t − t̄) with the closed form
    # m(x, t) = √(a/(4π t)) sin(π/4 − x²/(4at)) (strike.beam_moment_response; Graff 1975, §3.1), I = ∫P dt and t̄ the
    # reaction's centroid: the next term is of order (T_c/t)², 0.1 % of the envelope √(a/(4πt)) I at 3-6 ms
    speed, distances = 0.3, np.array([0.0, 0.25, 1.0])
    times, history, duration = strike.strike_moment_history(JOINT, K, RHO, EI, speed, 0.0, distances,
                                                            np.zeros(1), np.zeros((3, 1)), 0.006)
    r = strike.strike(JOINT, K, RHO, EI, speed, 0.0, 200)
    P = strike.beam_reaction(r, JOINT, speed)
    impulse = np.trapezoid(P, r.times)
    centroid = np.trapezoid(P * r.times, r.times) / impulse
    a = np.sqrt(EI / RHO)
    late = times > 3e-3
    for s, x in enumerate(distances):
        closed = impulse * strike.beam_moment_response(times[late] - centroid, x, RHO, EI)
        envelope = impulse * np.sqrt(a / (4 * np.pi * times[late]))
        assert np.max(np.abs(history[late, s] - closed) / envelope) < 0.005, x  # 0.11 % measured (3-6 % at t̄ = 0)
    assert duration == pytest.approx(2 * strike.strike(JOINT, K, RHO, EI, speed, 0.0, 200).duration
                                     - strike.strike(JOINT, K, RHO, EI, speed, 0.0, 100).duration)


def test_the_moment_history_at_the_local_peak_is_the_peaks_correction():
    # the history (local less the kept modes' share) at the instant the local moment peaks is the single correction
    # strike_moment_peak states there (both the Richardson extrapolation of the same two runs); modes of a 37.8-m
    # simply supported beam, 64 of them, the joint off its middle
    length, n = 37.8, np.arange(1, 65)
    a = np.sqrt(EI / RHO)
    k = n * np.pi / length
    xp, distances = 0.5 * length + 0.1, np.array([0.0, 0.25])
    gains = np.array([np.sin(k * xp) * EI * k * k * np.sin(k * (xp + x)) / (RHO * length / 2) for x in distances])
    peaks = strike.strike_moment_peak(JOINT, K, RHO, EI, 0.3, 0.0, distances, a * k * k, gains)
    times, history, _ = strike.strike_moment_history(JOINT, K, RHO, EI, 0.3, 0.0, distances, a * k * k, gains, 0.004)
    for s, peak in enumerate(peaks):
        assert np.interp(peak.time, times, history[:, s]) == pytest.approx(peak.correction, rel=2e-3)
    # and history_correction gives it back at the table's own speed
    table = dict(speeds=np.array([0.1, 0.3, 0.9]), durations=np.full(3, 4.3e-4), times=times,
                 corrections=np.stack([history] * 3))
    assert strike.history_correction(0.3, times[:50], table) == pytest.approx(history[:50], rel=1e-12, abs=1e-9)
