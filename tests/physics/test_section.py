"""Section, mud and beam-column properties (study.physics.section) against closed forms and sources."""

import numpy as np
import pytest
from scipy.integrate import quad

from study.physics import section

INCH = 0.0254  # m, exact (international inch)
LB = 0.45359237  # kg, exact
FT = 0.3048  # m, exact


def test_paper_pipe_weighs_about_15_lb_per_ft():
    # Source: paper §VI ("15 lb/ft pipe"); API 5DP 4-1/2 in 16.60 ppf body, wall 0.337 in, plain-end
    # weight 15.00 lb/ft. Steel 490 lb/ft^3 (7850 kg/m^3) times the wall area must give it.
    area = section.steel_area(4.5 / 2 * INCH, 3.826 / 2 * INCH)
    linear_mass = 7850.0 * area / (LB / FT)  # lb/ft
    assert linear_mass == pytest.approx(15.0, abs=0.05)


@pytest.mark.parametrize(
    "r_o, r_i",
    [(2.25 * INCH, 1.913 * INCH), (0.1, 0.0), (0.05, 0.049)],
    ids=["paper-pipe", "solid-rod", "thin-tube"],
)
def test_second_moment_matches_thin_and_solid_closed_forms(r_o, r_i):
    # Closed forms: solid rod I = pi r^4/4; any tube is the difference of two rods.
    expected = np.pi * r_o**4 / 4 - np.pi * r_i**4 / 4
    assert section.second_moment_of_area(r_o, r_i) == pytest.approx(expected, rel=1e-14)
    assert section.bending_stiffness(2e11, r_o, r_i) == pytest.approx(2e11 * expected, rel=1e-14)


def test_mud_density_conversion_printed_in_paper():
    # Source: paper §VI prints the mud as 74.8 lb/ft^3 = 0.0433 lb/in^3 (10 lb/gal).
    assert 0.0433 * 1728 == pytest.approx(74.8, abs=0.05)


def test_potential_flow_added_mass_tends_to_displaced_mass_in_a_wide_hole():
    # Closed form: a cylinder in unbounded ideal fluid has added mass rho pi r^2 (Lamb, Hydrodynamics §68).
    r_o = 0.05
    wide = section.added_mass(1000.0, r_o, 1e3, "potential_flow")
    assert wide == pytest.approx(1000.0 * np.pi * r_o**2, rel=1e-6)


@pytest.mark.parametrize("ratio", [1.05, 1.2, 1.5, 1.55, 2.0, 4.0, 20.0])
def test_gap_flow_and_potential_flow_cross_where_x3_minus_x_minus_2_vanishes(ratio):
    # Closed forms: gap flow rho pi r (R + r), potential flow rho pi r^2 (R^2 + r^2)/(R^2 - r^2); with
    # x = R/r they are equal where x^3 - x - 2 = 0 (x = 1.5214); gap flow is larger in wider holes.
    r_o = 0.05
    gap = section.added_mass(1200.0, r_o, ratio * r_o, "gap_flow")
    potential = section.added_mass(1200.0, r_o, ratio * r_o, "potential_flow")
    crossing = np.real(np.roots([1, 0, -1, -2])[np.isreal(np.roots([1, 0, -1, -2]))][0])
    assert crossing == pytest.approx(1.5214, abs=1e-4)
    assert (gap > potential) == (ratio > crossing)
    assert gap == pytest.approx(1200.0 * np.pi * r_o * (ratio * r_o + r_o), rel=1e-12)


def test_gap_flow_formula_as_read_in_model():
    # docs/model.md §2: m_a = rho pi (R^2 - r_o^2) r_o / S with S = R - r_o; here R = 2 r_o gives 3 rho pi r_o^2.
    r_o = 0.05
    assert section.added_mass(1.0, r_o, 2 * r_o, "gap_flow") == pytest.approx(3 * np.pi * r_o**2, rel=1e-14)


def test_unknown_added_mass_model_names_the_choices():
    with pytest.raises(ValueError, match="potential_flow, gap_flow"):
        section.added_mass(1.0, 0.05, 0.1, "magic")


def test_drag_coefficient_as_read_in_model():
    # docs/model.md §2 (paper eq. 30): D = 1/2 rho C_d (2 r_o)(1 + r_o/S)^2; S = r_o gives 4 rho C_d r_o.
    assert section.drag_coefficient_per_length(1000.0, 0.05, 0.1, 0.5) == pytest.approx(4 * 1000 * 0.5 * 0.05)


def test_effective_tension_subtracts_mud_momentum_flux():
    # Paper eq. 3, A1 of eq. 34: T_eff = T0 - m_i V_m^2.
    assert section.effective_tension(1e4, 10.0, 3.0) == pytest.approx(1e4 - 90.0)


@pytest.mark.parametrize("n", [1, 2, 3, 7])
def test_natural_frequency_limits(n):
    # Closed forms: a simply supported Euler-Bernoulli beam (T = 0): omega_n = (n pi/L)^2 sqrt(EI/M);
    # a taut string (EI = 0): omega_n = (n pi/L) sqrt(T/M).
    L, EI, M, T = 30.0, 8e5, 50.0, 4e4
    beam = section.natural_frequencies(L, EI, 0.0, M, [n])[0]
    string = section.natural_frequencies(L, 0.0, T, M, [n])[0]
    assert beam == pytest.approx((n * np.pi / L) ** 2 * np.sqrt(EI / M), rel=1e-13)
    assert string == pytest.approx(n * np.pi / L * np.sqrt(T / M), rel=1e-13)


def test_buckling_at_the_euler_load():
    # Closed form: a pinned column buckles at P = EI (pi/L)^2 (Euler), i.e. T_eff = -EI (pi/L)^2.
    L, EI, M = 20.0, 8e5, 50.0
    t_cr = section.euler_buckling_tension(L, EI)
    assert t_cr == pytest.approx(-EI * (np.pi / L) ** 2)
    assert not section.is_buckled(L, EI, 0.999 * t_cr)
    assert section.is_buckled(L, EI, 1.001 * t_cr)
    assert np.isnan(section.natural_frequencies(L, EI, 1.001 * t_cr, M)[0])
    assert section.buckling_length(EI, t_cr) == pytest.approx(L)
    assert section.buckling_length(EI, 1.0) == np.inf


def test_equivalent_mass_carries_the_span_momentum():
    # Paper eq. 5: momentum of the span moving as sin(pi x/L) equals m_e times the midspan velocity.
    M, L = 52.0, 105.0
    momentum, _ = quad(lambda x: M * np.sin(np.pi * x / L), 0.0, L)
    assert section.equivalent_mass(M, L) == pytest.approx(momentum, rel=1e-12)


def test_functions_broadcast_over_arrays():
    spans = np.array([10.0, 20.0, 40.0])
    omega = section.natural_frequencies(spans, 8e5, 1e4, 50.0, [1, 3])
    assert omega.shape == (3, 2)
    assert np.all(np.diff(omega[:, 0]) < 0)  # longer span, lower frequency


# Timoshenko's beam (section.timoshenko_frequencies, timoshenko_band_edge): the 4½-in pipe of the default study in
# 12-ppg mud (EI of E 207 GPa, M the section's whole mass with mud and added mass, the steel's shear stiffness and
# rotary inertia), as docs/reference_model.md §2.3.1 takes it
R_O, R_I = 0.05715, 0.0485902
E_STEEL, NU_STEEL, RHO_STEEL = 207e9, 0.3, 7850.0
I_PIPE = float(section.second_moment_of_area(R_O, R_I))
A_PIPE = float(section.steel_area(R_O, R_I))
EI_PIPE, M_PIPE, J_PIPE = E_STEEL * I_PIPE, 58.35, RHO_STEEL * I_PIPE
KGA_PIPE = float(section.cowper_shear_coefficient(NU_STEEL, R_O, R_I)) * E_STEEL / (2 * (1 + NU_STEEL)) * A_PIPE


def test_cowpers_shear_coefficient_has_his_solid_and_thin_tube_limits():
    # Cowper 1966 (J. Appl. Mech. 33, 335), Table 1: solid circle 6(1 + ν)/(7 + 6ν), thin-walled round tube
    # 2(1 + ν)/(4 + 3ν); at ν = 0.3, 0.886 and 0.530
    assert section.cowper_shear_coefficient(0.3, 1.0, 0.0) == pytest.approx(6 * 1.3 / 8.8, rel=1e-15)
    assert section.cowper_shear_coefficient(0.3, 1.0, 0.0) == pytest.approx(0.886, abs=5e-4)
    assert section.cowper_shear_coefficient(0.3, 1.0, 1.0 - 1e-9) == pytest.approx(2 * 1.3 / 4.9, rel=1e-8)
    assert section.cowper_shear_coefficient(0.3, 1.0, 1.0 - 1e-9) == pytest.approx(0.531, abs=5e-4)


def test_timoshenkos_frequencies_are_the_roots_of_his_determinant():
    # Graff 1975 §3.4: the 2×2 determinant of the beam's equations for w, ψ ∝ e^{i(kx − ωt)} vanishes at both
    # branches; found here independently by bracketing its sign changes in ω (scipy's brentq), with tension too
    from scipy.optimize import brentq

    for tension in (0.0, 9e4):
        for k in (0.05, 1.0, 5.0, 20.0, 80.0):
            def det(w):
                a = KGA_PIPE * k**2 + tension * k**2 - M_PIPE * w**2
                d = EI_PIPE * k**2 + KGA_PIPE - J_PIPE * w**2
                return a * d - (KGA_PIPE * k) ** 2  # |[a, iκGAk], [−iκGAk, d]|

            lower, upper = section.timoshenko_frequencies(k, EI_PIPE, KGA_PIPE, M_PIPE, J_PIPE, tension)
            grid = np.geomspace(1e-3, 10 * upper, 20001)
            values = det(grid)
            roots = [brentq(det, grid[i], grid[i + 1], xtol=1e-13, rtol=1e-14)
                     for i in np.flatnonzero(np.sign(values[:-1]) != np.sign(values[1:]))]
            assert len(roots) == 2
            np.testing.assert_allclose([lower, upper], roots, rtol=1e-10)


def test_timoshenkos_frequencies_have_their_limit_cases():
    k = np.array([0.1, 1.0, 5.0, 20.0])
    eb = section.euler_bernoulli_frequency(k, EI_PIPE, M_PIPE)
    # no rotary inertia: the shear beam, ω² = EI k⁴/(M (1 + EI k²/κGA)) (Han, Benaroya & Wei 1999, JSV 225:935,
    # doi:10.1006/jsvi.1999.2257: its shear model's dispersion relation)
    shear = section.timoshenko_frequencies(k, EI_PIPE, KGA_PIPE, M_PIPE, 0.0)[0]
    np.testing.assert_allclose(shear, eb / np.sqrt(1 + EI_PIPE * k**2 / KGA_PIPE), rtol=1e-12)
    # rigid in shear: the Rayleigh beam, ω² = EI k⁴/(M + ρI k²) (ibid.: the Rayleigh model's)
    rayleigh = section.timoshenko_frequencies(k, EI_PIPE, 1e12 * KGA_PIPE, M_PIPE, J_PIPE)[0]
    np.testing.assert_allclose(rayleigh, np.sqrt(EI_PIPE * k**4 / (M_PIPE + J_PIPE * k**2)), rtol=1e-9)
    # k → 0: Euler–Bernoulli's, the gap to first order (k r)²/2 (E/κG + ρ_s A_s/M), r² = I/A_s (Graff §3.4); the
    # upper branch starts at the cut-off √(κGA/ρI)
    small = np.array([1e-3, 1e-2])
    gap = 1 - (section.timoshenko_frequencies(small, EI_PIPE, KGA_PIPE, M_PIPE, J_PIPE)[0]
               / section.euler_bernoulli_frequency(small, EI_PIPE, M_PIPE))
    first = small**2 / 2 * (EI_PIPE / KGA_PIPE + J_PIPE / M_PIPE)
    np.testing.assert_allclose(gap, first, rtol=1e-3)
    assert section.timoshenko_frequencies(1e-9, EI_PIPE, KGA_PIPE, M_PIPE, J_PIPE)[1] == pytest.approx(
        np.sqrt(KGA_PIPE / J_PIPE), rel=1e-12)


def test_the_band_edge_is_where_timoshenko_parts_from_euler_bernoulli_by_the_fraction():
    for fraction, tension in ((0.02, 0.0), (0.05, 0.0), (0.05, 9e4), (0.1, 0.0)):
        edge = section.timoshenko_band_edge(fraction, EI_PIPE, KGA_PIPE, M_PIPE, J_PIPE, tension)
        # its wavenumber from the EB relation, then Timoshenko's at it
        k = np.sqrt((-tension + np.sqrt(tension**2 + 4 * EI_PIPE * M_PIPE * edge**2)) / (2 * EI_PIPE))
        ratio = section.timoshenko_frequencies(k, EI_PIPE, KGA_PIPE, M_PIPE, J_PIPE, tension)[0] / edge
        assert ratio == pytest.approx(1 - fraction, abs=1e-10)
    # the default pipe at 5 %: some 0.28 kHz, where the first-order estimate puts it within its O(k⁴) error
    edge = section.timoshenko_band_edge(0.05, EI_PIPE, KGA_PIPE, M_PIPE, J_PIPE)
    k1 = np.sqrt(2 * 0.05 / (EI_PIPE / KGA_PIPE + J_PIPE / M_PIPE))
    assert edge == pytest.approx(float(section.euler_bernoulli_frequency(k1, EI_PIPE, M_PIPE)), rel=0.1)
    assert 250 < edge / (2 * np.pi) < 320
    with pytest.raises(ValueError, match=r"fraction = 1.5: must lie in \(0, 1\)"):
        section.timoshenko_band_edge(1.5, EI_PIPE, KGA_PIPE, M_PIPE, J_PIPE)
