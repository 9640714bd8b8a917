"""The drag linearised and the in-phase end moments (study.physics.damping; docs/model.md §7)."""

import numpy as np
import pytest
from scipy import integrate

from study.physics import damping


def test_equal_dissipation_of_harmonic_motion_is_8_D_omega_Y_over_3_pi():
    # source: docs/model.md eq. 7.1 (paper appendix A): ∮ D|ẏ|³ dt = (8/3) D ω² Y³ per cycle, ∮ c ẏ² dt = π c ω Y²
    drag, omega, amplitude = 145.0, 31.4, 0.054
    t = np.linspace(0.0, 2 * np.pi / omega, 4096, endpoint=False)
    velocity = amplitude * omega * np.cos(omega * t)
    expected = 8 * drag * omega * amplitude / (3 * np.pi)
    assert damping.equivalent_damping(drag, velocity) == pytest.approx(expected, rel=1e-12)
    assert damping.harmonic_equivalent_damping(drag, omega, amplitude) == pytest.approx(expected, rel=1e-15)


def test_equal_dissipation_of_the_assumed_mode_adds_the_span_average():
    # source: the paper's assumed motion y = Y sin(πx/L) sin Ωt: ∫ sin³ / ∫ sin² over the span = (4/3)/(π/2) = 8/(3π)
    drag, omega, amplitude, span = 145.0, 31.4, 0.054, 10.0
    x = np.linspace(0.0, span, 2001)
    t = np.linspace(0.0, 2 * np.pi / omega, 2048, endpoint=False)
    v = amplitude * omega * np.sin(np.pi * x / span)[None, :] * np.cos(omega * t)[:, None]
    weights = np.full(x.size, x[1] - x[0])
    weights[[0, -1]] *= 0.5
    c = damping.equivalent_damping(drag, v, weights[None, :])
    assert c == pytest.approx(damping.HARMONIC_FACTOR * damping.harmonic_equivalent_damping(drag, omega, amplitude),
                              rel=1e-6)
    assert damping.equivalent_damping(drag, np.zeros(5)) == 0.0  # no motion, no drag


@pytest.mark.parametrize("tension", [0.0, 4.4e4, -3.0e4], ids=["no-load", "tension", "compression"])
def test_end_moment_shape_solves_the_beam_column(tension):
    # source: EI s'''' − T s'' = 0 with y = 0, −EI y'' = 1 at both ends (docs/model.md §7.1)
    ei, span = 8.27e5, 6.7
    x = np.linspace(0.0, span, 4001)
    s, moment, slope = damping.end_moment_static(x, span, ei, tension)
    assert s[0] == pytest.approx(0.0, abs=1e-15) and s[-1] == pytest.approx(0.0, abs=1e-12)
    assert moment[0] == pytest.approx(1.0) and moment[-1] == pytest.approx(1.0)
    h = x[1] - x[0]
    curvature = np.gradient(np.gradient(s, h), h)
    assert np.allclose(-ei * curvature[5:-5], moment[5:-5], rtol=1e-5)
    assert np.allclose(np.gradient(s, h)[5:-5], slope[5:-5], rtol=1e-5, atol=1e-12)
    if tension == 0.0:  # the parabola x(L − x)/(2EI)
        assert np.allclose(s, x * (span - x) / (2 * ei))


def test_end_moment_modal_factor_is_the_shape_coefficient_times_omega_squared():
    # source: integration by parts of EI s'''' − T s'' = 0 against sin(k_n x): s_n = 4 k_n /(L (EI k_n⁴ + T k_n²))
    ei, tension, mass, span = 8.27e5, 4.4e4, 52.4, 6.7
    modes = np.array([1.0, 3.0, 5.0, 7.0])
    k = modes * np.pi / span
    omega_sq = (ei * k**4 + tension * k**2) / mass
    coefficients = [2 / span * integrate.quad(lambda x, kn=kn: damping.end_moment_static(np.array([x]), span, ei,
                                                                                          tension)[0][0]
                                              * np.sin(kn * x), 0.0, span)[0] for kn in k]
    assert np.allclose(damping.end_moment_modal_factors(modes, span, mass), np.array(coefficients) * omega_sq,
                       rtol=1e-8)


def test_appendix_b_one_degree_of_freedom_in_closed_form():
    # source: paper appendix B, eq. B3–B6: m ẍ + c ẋ + K x = F10 sin ωt + F20 cos ωt; F20 = F10 c ω/(K − m ω²)
    # puts x in phase with F1, x = F10 sin ωt/(K − m ω²) (the undamped response), and then the work of F2 per
    # cycle, π F20 X, equals the dissipation π c ω X².
    mass, stiffness, c, force = 3.0, 1200.0, 25.0, 40.0
    for omega in (5.0, 15.0, 30.0):  # below and above ω_n = 20 rad/s
        transfer = damping.modal_transfer(np.sqrt(stiffness / mass), omega, c / mass)[None, None]
        per_mass = np.array([1.0 / mass])  # the force's (and the second force's) modal forcing per unit mass
        mu = damping.in_phase_moments(per_mass, per_mass, transfer, np.ones(1))[0]
        assert mu == pytest.approx(c * omega / (stiffness - mass * omega**2), rel=1e-12)  # F20/F10, eq. B5
        x = force * damping.compensated_amplitudes(per_mass, per_mass, transfer, [mu])[0, 0]
        assert x.imag == pytest.approx(0.0, abs=1e-15)  # in phase with F1
        assert x.real == pytest.approx(force / (stiffness - mass * omega**2), rel=1e-12)  # eq. B6
        work_second = np.pi * (mu * force) * x.real  # ∮ F20 cos ωt · ẋ dt
        dissipation = np.pi * c * omega * x.real**2
        assert work_second == pytest.approx(dissipation, rel=1e-12)  # W1 = W2


def test_without_damping_no_moment_is_needed():
    # source: appendix A with λ = 0: the undamped response is in phase already
    transfer = damping.modal_transfer(np.array([10.0, 30.0]), np.array([[5.0], [20.0]]), 0.0)
    mu = damping.in_phase_moments(np.array([1.0, -1.0]), np.array([2.0, 6.0]), transfer, np.array([1.0, -1.0]))
    assert np.all(mu == 0.0)


# --- the mud's viscous loss on an oscillating cylinder (Stokes 1851; Chen, Wambsganss & Jendrzejczyk 1976) ---------

PIPE_RADIUS = 0.05715  # 4 1/2-in pipe [m]
HOLE_RADIUS = 0.111125  # 8 3/4-in hole [m]
MUD_DENSITY = 1250.0  # [kg/m³]
MUD_NU = 0.020 / MUD_DENSITY  # 20 cP over the density [m²/s]


def test_unbounded_cylinder_tends_to_the_stokes_layer_and_potential_flow():
    """Large |s| = a√(ω/ν): the damping c → 2√2 πρa√(ων) and the added-mass coefficient → 1, both with relative
    corrections O(1/|s|) (Stokes 1851, Trans. Camb. Phil. Soc. 9, 8; Landau & Lifshitz, Fluid Mechanics §24,
    problem 5: C_m − iC_c = 1 + 4K₁(s)/(sK₀(s)) → 1 + 4/s)."""
    from study.physics.damping import oscillating_cylinder_force_coefficients

    omega = 2 * np.pi * np.array([10.0, 100.0, 1000.0])
    c_m, c_c = oscillating_cylinder_force_coefficients(PIPE_RADIUS, omega, MUD_NU)
    s = PIPE_RADIUS * np.sqrt(omega / MUD_NU)
    layer = 2 * np.sqrt(2) * np.pi * MUD_DENSITY * PIPE_RADIUS * np.sqrt(omega * MUD_NU)
    c = c_c * MUD_DENSITY * np.pi * PIPE_RADIUS**2 * omega
    # the next terms (K₁/K₀ = 1 + 1/(2s) + O(1/s²)): C_m = 1 + 2√2/|s| + O(1/|s|³), C_c = 2√2/|s| + 2/|s|²
    np.testing.assert_allclose(c_m, 1 + 2 * np.sqrt(2) / s, rtol=2 / s.min() ** 2)
    assert np.all(np.abs(c / layer - 1.0) < 1.0 / s)
    assert np.all(np.abs(c / layer - 1.0) > 0.0) and np.all(np.diff(np.abs(c / layer - 1.0)) < 0)


def test_confined_cylinder_limits():
    """The annulus of Chen, Wambsganss & Jendrzejczyk (1976, J. Appl. Mech. 43, 325): as ν → 0 the added-mass
    coefficient tends to the potential flow's (b² + a²)/(b² − a²) (Chen 1987, Flow-induced vibration of circular
    cylindrical structures, eq. for concentric cylinders) and the damping to the thin-layer one, the unbounded
    2√2 πρa√(ων) times (1 + (a/b)³)/(1 − (a/b)²)²; a far wall (b = 100 a) gives the unbounded cylinder within
    O((a/b)²)."""
    from study.physics.damping import oscillating_cylinder_force_coefficients

    a, b, omega = PIPE_RADIUS, HOLE_RADIUS, 2 * np.pi * 100.0
    gamma = a / b
    for nu in (1e-8, 1e-10):
        c_m, c_c = oscillating_cylinder_force_coefficients(a, omega, nu, outer_radius=b)
        s = a * np.sqrt(omega / nu)
        np.testing.assert_allclose(c_m, (b * b + a * a) / (b * b - a * a), rtol=20 / s)
        layer = 2 * np.sqrt(2) / s * (1 + gamma**3) / (1 - gamma**2) ** 2
        np.testing.assert_allclose(c_c, layer, rtol=10 / s)
    far = oscillating_cylinder_force_coefficients(a, omega, MUD_NU, outer_radius=100 * a)
    free = oscillating_cylinder_force_coefficients(a, omega, MUD_NU)
    np.testing.assert_allclose(far, free, rtol=2e-3)
    with pytest.raises(ValueError, match="outer_radius"):
        oscillating_cylinder_force_coefficients(a, omega, MUD_NU, outer_radius=0.5 * a)


def test_viscous_modal_damping_ratio_of_the_default_pipe():
    """ζ = c/(2mω): for the default pipe in 20 cP mud (m = 58.4 kg/m) the unbounded Stokes layer gives ζ ≈ 8.7e-4
    at 100 Hz and 3.9e-4 at 500 Hz (2√2 πρa√(ων)/(2mω) by hand, within the O(1/|s|) ~ 0.2 % correction), falling as
    ω^(-1/2); the hole's confinement raises it by (1 + (a/b)³)/(1 − (a/b)²)² ≈ 1.6; NaN (a buckled mode) stays NaN."""
    from study.physics.damping import viscous_modal_damping_ratio

    omega = 2 * np.pi * np.array([100.0, 500.0, np.nan])
    zeta = viscous_modal_damping_ratio(omega, 58.4, MUD_DENSITY, PIPE_RADIUS, MUD_NU)
    by_hand = 2 * np.sqrt(2) * np.pi * MUD_DENSITY * PIPE_RADIUS * np.sqrt(omega[:2] * MUD_NU) / (2 * 58.4 * omega[:2])
    np.testing.assert_allclose(zeta[:2], by_hand, rtol=5e-3)
    np.testing.assert_allclose(zeta[:2], [8.7e-4, 3.9e-4], rtol=0.02)
    assert np.isnan(zeta[2])
    gamma = PIPE_RADIUS / HOLE_RADIUS
    confined = viscous_modal_damping_ratio(omega[:2], 58.4, MUD_DENSITY, PIPE_RADIUS, MUD_NU, HOLE_RADIUS)
    np.testing.assert_allclose(confined / zeta[:2], (1 + gamma**3) / (1 - gamma**2) ** 2, rtol=0.02)
    assert viscous_modal_damping_ratio(omega[0], 58.4, MUD_DENSITY, PIPE_RADIUS, 0.0) == 0.0
