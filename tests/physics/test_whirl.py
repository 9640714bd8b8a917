"""Tests of study.physics.whirl: the drive, the friction and the closed forms of the reference model."""

import numpy as np
import pytest
from scipy.integrate import quad

from study.physics import oscillator, whirl

IN = 0.0254


def test_eccentric_load_is_the_centrifugal_force_of_the_offset_mass():
    # 15 lb/ft pipe, 0.1 in offset, 300 rpm: m e Omega^2 (Vance 1988 ch. 2, the unbalance force)
    m = 15 * 0.45359237 / 0.3048
    assert whirl.eccentric_load(m, 0.1 * IN, 10 * np.pi) == pytest.approx(m * 0.1 * IN * (10 * np.pi) ** 2, rel=1e-14)
    assert whirl.eccentric_load(m, 0.0, 10 * np.pi) == 0.0


# the 4 1/2-in, 3.826-in bore pipe of the default study (E = 30e6 psi) on 31-ft joints
EI_DEFAULT = 30e6 * 6894.757 * np.pi / 64 * ((4.5 * IN) ** 4 - (3.826 * IN) ** 4)
SPACING = 31 * 0.3048
LBF = 4.4482216


@pytest.mark.parametrize("deg", [0, 30, 60, 90, 120, 150, 179, 180, 270, 360])
def test_turned_joint_share_without_tension_is_clapeyrons_three_moments(deg):
    # equal spans, uniform load q e^{ijτ} on span j, supports pinned: the three-moment equation M_{j-1} + 4 M_j +
    # M_{j+1} = −(q s²/4)(load on the two spans) with M_j ∝ e^{ijτ} gives each support |cos(τ/2)| (5 + cos τ)/(4 + 2 cos τ)
    # of q s (Clapeyron; Timoshenko, Strength of Materials I, §47) — the Fourier–Bloch series to its truncation
    tau = np.radians(deg)
    expected = abs(np.cos(tau / 2)) * (5 + np.cos(tau)) / (4 + 2 * np.cos(tau))
    assert whirl.turned_joint_share(tau, 0.0, EI_DEFAULT, SPACING) == pytest.approx(expected, abs=1e-9)


def test_turned_joint_share_under_tension_tends_to_the_two_half_spans():
    # a string on its supports carries half of each span: |1 + e^{iτ}|/2 = |cos(τ/2)| (T s²/EI = 1e6 here: the beam's
    # continuity over the supports leaves a share of order 1/(k s), k = √(T/EI))
    T = 1e6 * EI_DEFAULT / SPACING**2
    for deg in (60, 90, 120):
        tau = np.radians(deg)
        assert whirl.turned_joint_share(tau, T, EI_DEFAULT, SPACING) == pytest.approx(abs(np.cos(tau / 2)), rel=5e-3)
    assert whirl.random_joint_share_rms(T, EI_DEFAULT, SPACING) == pytest.approx(np.sqrt(0.5), rel=5e-3)


@pytest.mark.parametrize("klbf", [0, 5, 30])
def test_a_ninety_degree_turn_carries_a_random_strings_rms_joint_load(klbf):
    # why the default study turns its pipe joints' eccentricities 90° apart (docs/reference_model.md §1, §7): in a
    # string made up at random a joint's mean-square load is the mean over every turn (Parseval); a 90° turn's share
    # lies within 10 % above that root mean square (8.9, 8.7, 7.4 % at 0, 5 000, 30 000 lbf: the beam's continuity),
    # the aligned string's 23–29 % above it and a 120° turn's 8–15 % below
    T = klbf * 1000 * LBF
    rms = whirl.random_joint_share_rms(T, EI_DEFAULT, SPACING)
    share = lambda deg: float(whirl.turned_joint_share(np.radians(deg), T, EI_DEFAULT, SPACING))
    assert 1.0 < share(90) / rms < 1.1
    assert 1.2 < share(0) / rms < 1.3
    assert 0.84 < share(120) / rms < 0.93


def test_lift_off_speed_is_the_balance_of_a_joints_forces():
    # share m_p ε Ω² s = F at the returned Ω; aligned (share 1) the whole string's balance m_p ε Ω² L = F L/s
    m, eps, F = 22.3, 0.1 * IN, 302.7
    for share in (1.0, 0.8325, 0.5):
        om = whirl.lift_off_speed(F, share, m, eps, SPACING)
        assert share * whirl.eccentric_load(m, eps, om) * SPACING == pytest.approx(F, rel=1e-12)


@pytest.mark.parametrize("n", [1, 2, 3, 4, 7])
def test_uniform_load_modal_factor_is_the_integral_of_the_mode(n):
    L = 28.3
    expected = quad(lambda x: np.sin(n * np.pi * x / L), 0.0, L)[0]
    assert whirl.uniform_load_modal_factors([n], L)[0] == pytest.approx(expected, abs=1e-12)


@pytest.mark.parametrize("r", [0.3, 0.9, 1.0, 1.7, 5.0])
@pytest.mark.parametrize("zeta", [0.02, 0.1, 0.5])
def test_jeffcott_response_matches_the_direct_complex_solution(r, zeta):
    # m x'' + c x' + k x = m e Omega^2 exp(i Omega t), solved as a complex linear equation
    m, k, e = 3.0, 12.0, 0.01
    w = np.sqrt(k / m)
    om = r * w
    x = m * e * om**2 / (k - m * om**2 + 1j * 2 * zeta * np.sqrt(k * m) * om)
    amp, lag = whirl.jeffcott_response(r, zeta)
    assert amp * e == pytest.approx(abs(x), rel=1e-12)
    assert lag == pytest.approx(-np.angle(x) % (2 * np.pi), abs=1e-12)
    # and the textbook's dynamic magnifier and phase (Harrison & Nettleton ch. 9): r^2 times the magnifier
    assert amp == pytest.approx(r**2 * oscillator.dynamic_magnifier(r, zeta), rel=1e-12)
    assert lag == pytest.approx(oscillator.phase_angle(r, zeta), abs=1e-12)


def test_jeffcott_printed_limits():
    # Vance 1988 / Childs 1993: at the critical speed amplitude e/(2 zeta), lag 90 deg; far above, e and 180 deg
    amp, lag = whirl.jeffcott_response(1.0, 0.05)
    assert amp == pytest.approx(10.0) and lag == pytest.approx(np.pi / 2)
    amp, lag = whirl.jeffcott_response(1e4, 0.05)
    assert amp == pytest.approx(1.0, rel=1e-6) and lag == pytest.approx(np.pi, abs=1e-4)


@pytest.mark.parametrize("zeta, ratio", [(0.05, 3.0), (0.05, 0.5), (0.2, 2.0), (0.0, 4.0)])
def test_speed_reaching_clearance_is_where_the_response_equals_it(zeta, ratio):
    w, e = 7.0, 0.002
    c = ratio * e
    om = whirl.speed_reaching_clearance(w, zeta, e, c)
    amp, _ = whirl.jeffcott_response(om / w, zeta)
    assert amp * e == pytest.approx(c, rel=1e-10)
    # it is the first: every slower speed stays below the clearance
    slower = np.linspace(0.0, om, 2000)[:-1]
    assert np.all(whirl.jeffcott_response(slower / w, zeta)[0] * e < c)


def test_speed_reaching_clearance_is_nan_when_the_peak_stays_below():
    # peak about e/(2 zeta) = 2.5 e < 3 e
    assert np.isnan(whirl.speed_reaching_clearance(7.0, 0.2, 0.002, 0.006))


def test_friction_factor_tends_to_coulomb_and_is_smooth_through_zero():
    assert whirl.friction_factor(0.0, 0.01) == 0.0
    assert whirl.friction_factor(2.5, 0.01) == pytest.approx(1.0, abs=1e-5)
    assert whirl.friction_factor(-2.5, 0.01) == pytest.approx(-1.0, abs=1e-5)
    assert whirl.friction_factor(0.01, 0.01) == pytest.approx(1 / np.sqrt(2))


def test_sliding_velocity_vanishes_when_rolling_backwards():
    r, c, om = 2.25 * IN, 2.125 * IN, 10 * np.pi
    whirl_rate = whirl.rolling_whirl_ratio(r, c) * om
    # the centre moves along t-hat at whirl_rate * c: rolling without slip
    assert whirl.sliding_velocity(whirl_rate * c, om, r) == pytest.approx(0.0, abs=1e-14)


def test_rolling_whirl_ratios_of_the_issue():
    # issue 20 (classical dry whip): 4.5-in body in an 8.75-in hole about -1.06; 6.25-in tool joint -2.5
    assert whirl.rolling_whirl_ratio(2.25, 4.375 - 2.25) == pytest.approx(-1.0588, abs=1e-4)
    assert whirl.rolling_whirl_ratio(3.125, 4.375 - 3.125) == pytest.approx(-2.5)


def test_side_load_is_the_buoyed_weight_component():
    # 10 ppg mud, 4.5 x 3.826-in pipe, 15 lb/ft; buoyed weight = steel in mud (Archimedes)
    rho = 1198.26
    r_o, r_i = 2.25 * IN, 1.913 * IN
    m_p = 15 * 0.45359237 / 0.3048
    m_i = rho * np.pi * r_i**2
    buoyed = (m_p + m_i - rho * np.pi * r_o**2) * 9.80665
    assert whirl.side_load(m_p, m_i, rho, r_o, np.pi / 2) == pytest.approx(buoyed)
    assert whirl.side_load(m_p, m_i, rho, r_o, np.pi / 6) == pytest.approx(0.5 * buoyed)
    assert whirl.side_load(m_p, m_i, rho, r_o, 0.0) == 0.0
    # the displaced annulus takes off exactly the mud's share of the steel's own volume
    steel_volume = np.pi * (r_o**2 - r_i**2)
    assert buoyed == pytest.approx((m_p - rho * steel_volume) * 9.80665)


@pytest.mark.parametrize("points", [4, 40])
def test_gauss_legendre_rule_is_exact_to_its_degree_and_shared(points):
    # an n-point Gauss-Legendre rule integrates x^(2n-1) and x^(2n-2) over [-1, 1] exactly (Abramowitz & Stegun
    # 25.4.29): 0 and 2/(2n-1)
    nodes, weights = whirl.gauss_legendre(points)
    assert np.sum(weights * nodes ** (2 * points - 1)) == pytest.approx(0.0, abs=1e-13)
    assert np.sum(weights * nodes ** (2 * points - 2)) == pytest.approx(2.0 / (2 * points - 1), rel=1e-12)
    assert whirl.gauss_legendre(points)[0] is nodes and not nodes.flags.writeable  # computed once, read only
