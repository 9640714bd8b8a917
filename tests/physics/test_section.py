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
