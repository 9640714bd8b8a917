"""Tests of study.physics.well: side loads, doglegs and the pipe body between its tool joints."""

import math

import numpy as np
import pytest

from study.physics import well, whirl

IN = 0.0254
FT = 0.3048
LBF = 4.4482216152605
PSI = 6894.757293168361

# A dimensionless span (EI = s = w = 1) at z = T s²/(4 EI) from compression near the clamped Euler load
# (z = −π²) to a taut string, across the switch between series and closed forms at |z| = 1.
Z_VALUES = [-9.0, -2.5, -1.0000001, -0.9999999, -1e-3, 0.0, 1e-9, 1e-3, 0.9999999, 1.0000001, 4.0, 25.0]


def _tension(z, EI=1.0, s=1.0):
    return 4.0 * EI * z / s**2


# --- limits of the clamped beam (T -> 0) -------------------------------------------------------------


@pytest.mark.parametrize("T", [0.0, 1e-300, 1e-12, -1e-12])
def test_zero_tension_gives_the_clamped_beam(T):
    # Clamped-clamped beam under uniform load (Timoshenko & Gere 1961 ch. 1; Roark table 8.1 case 2e):
    # end moments -w s^2/12, mid-span w s^2/24, deflection w x^2 (s - x)^2 / (24 EI).
    w, EI, s = 350.0, 8.3e5, 9.14
    assert well.support_moment(w, T, EI, s) == pytest.approx(-w * s**2 / 12, rel=1e-12)
    assert well.midspan_moment(w, T, EI, s) == pytest.approx(w * s**2 / 24, rel=1e-12)
    x = np.linspace(0.0, s, 11)
    expected = w * x**2 * (s - x) ** 2 / (24 * EI)
    np.testing.assert_allclose(well.beam_column_deflection(x, w, T, EI, s), expected, rtol=1e-12,
                               atol=1e-15 * expected.max())


def test_small_tension_follows_the_series_of_the_closed_forms():
    # u coth u = 1 + u²/3 − u⁴/45 + ..., u/sinh u = 1 − u²/6 + 7u⁴/360 − ... (Bernoulli numbers; Abramowitz &
    # Stegun 4.5.64, 4.5.67), so M_support = −(w s²/12)(1 − z/15 + ...) and M_mid = (w s²/24)(1 − 7z/60 + ...).
    z = 1e-4
    assert well.support_moment(1.0, _tension(z), 1.0, 1.0) == pytest.approx(-(1 - z / 15 + 2 * z**2 / 315) / 12,
                                                                            rel=1e-12)
    assert well.midspan_moment(1.0, _tension(z), 1.0, 1.0) == pytest.approx((1 - 7 * z / 60) / 24, rel=1e-8)


@pytest.mark.parametrize("z", [0.05, 0.9999999, 1.0000001, 0.3, 2.0, -0.05, -1.0000001, -2.0])
def test_moments_equal_the_closed_forms_on_both_sides_of_the_series_switch(z):
    # M = (w/k²)(1 − u/tanh u) and (w/k²)(1 − u/sinh u) (docs/model.md §13), evaluated directly: at
    # |z| >= 0.05 their cancellation costs under 1e-13, well inside the tolerance.
    w, EI, s = 1.0, 1.0, 1.0
    T = _tension(z)
    k2 = T / EI
    if z > 0:
        u = math.sqrt(z)
        support, mid = w / k2 * (1 - u / math.tanh(u)), w / k2 * (1 - u / math.sinh(u))
    else:
        v = math.sqrt(-z)
        support, mid = w / k2 * (1 - v / math.tan(v)), w / k2 * (1 - v / math.sin(v))
    assert well.support_moment(w, T, EI, s) == pytest.approx(support, rel=1e-11)
    assert well.midspan_moment(w, T, EI, s) == pytest.approx(mid, rel=1e-11)


# --- the beam-column: its equation, its supports and its moments ----------------------------------------


def _derivatives(z, x, h):
    """y'' and y'''' of the dimensionless span at x by central differences of step h, Richardson-extrapolated."""
    T = _tension(z)

    def at(step):
        y = well.beam_column_deflection(x[:, None] + step * np.arange(-2, 3)[None, :], 1.0, T, 1.0, 1.0)
        second = (y[:, 1] - 2 * y[:, 2] + y[:, 3]) / step**2
        fourth = (y[:, 0] - 4 * y[:, 1] + 6 * y[:, 2] - 4 * y[:, 3] + y[:, 4]) / step**4
        return second, fourth

    (s1, f1), (s2, f2) = at(h), at(h / 2)
    return (4 * s2 - s1) / 3, (4 * f2 - f1) / 3


@pytest.mark.parametrize("z", Z_VALUES)
def test_deflection_satisfies_the_beam_column_equation(z):
    # EI y'''' − T y'' = w (docs/model.md §2 without inertia and drag), by finite differences inside the span.
    x = np.array([0.05, 0.2, 0.37, 0.5, 0.81, 0.95])
    second, fourth = _derivatives(z, x, 0.01)
    residual = fourth - _tension(z) * second - 1.0
    # the differences' error, (k h)^4 after extrapolation and 1e-16/h^4 of round-off: under 1e-5 of w here
    np.testing.assert_allclose(residual, 0.0, atol=1e-5 * max(1.0, abs(_tension(z) * second).max()))


@pytest.mark.parametrize("z", Z_VALUES)
def test_deflection_is_clamped_at_both_supports_and_symmetric(z):
    T = _tension(z)
    y = lambda x: well.beam_column_deflection(np.asarray(x, dtype=float), 1.0, T, 1.0, 1.0)  # noqa: E731
    peak = abs(float(y(0.5)))
    h = 1e-4
    assert abs(float(y(0.0))) <= 1e-14 * peak and abs(float(y(1.0))) <= 1e-14 * peak
    # one-sided slope of fourth order: its error h⁴|y⁽⁵⁾|/5 and round-off 1e-16 peak/h are below 1e-9 peak/s here
    left, right = y(h * np.arange(5)), y(1.0 - h * np.arange(5))
    stencil = np.array([-25.0, 48.0, -36.0, 16.0, -3.0]) / (12 * h)
    assert abs(stencil @ left) < 1e-9 * peak and abs(stencil @ right) < 1e-9 * peak
    x = np.linspace(0.0, 0.5, 7)
    np.testing.assert_allclose(y(x), y(1.0 - x), rtol=1e-12, atol=1e-15 * peak)
    assert peak > 0 and np.all(y(x[1:]) > 0)  # the span bows along w, its deflection largest at mid-span
    assert np.all(np.diff(y(x)) > 0)


@pytest.mark.parametrize("z", Z_VALUES)
def test_moments_of_the_deflection_equal_support_and_midspan_moment(z):
    # M = −EI y'' of the deflection: at the support by a one-sided difference of fourth order, at mid-span
    # by the extrapolated central difference.
    T = _tension(z)
    h = 1e-3
    y = well.beam_column_deflection(h * np.arange(6), 1.0, T, 1.0, 1.0)
    second_at_0 = (45 * y[0] - 154 * y[1] + 214 * y[2] - 156 * y[3] + 61 * y[4] - 10 * y[5]) / (12 * h**2)
    support = well.support_moment(1.0, T, 1.0, 1.0)
    assert -second_at_0 == pytest.approx(support, rel=1e-6)
    second_mid, _ = _derivatives(z, np.array([0.5]), 0.01)
    assert -second_mid[0] == pytest.approx(well.midspan_moment(1.0, T, 1.0, 1.0), rel=1e-6)


def test_large_tension_approaches_the_taut_string_with_boundary_layers():
    # A taut string under w: y = w x (s − x)/(2T), mid-span w s²/(8T); the clamped ends take boundary layers of
    # width 1/k, which lower the mid-span deflection by w s/(2 k T) and put −w/k² · (u − 1) ≈ −w s/(2k) at the
    # supports (the closed forms with tanh u = 1 and 1/sinh u = 0, exact to e^(−2u) at u = 50).
    w, EI, s = 300.0, 8.3e5, 9.0
    k = 100.0 / s
    T = EI * k**2
    assert well.beam_column_deflection(s / 2, w, T, EI, s) == pytest.approx(w / T * (s**2 / 8 - s / (2 * k)),
                                                                           rel=1e-12)
    assert well.support_moment(w, T, EI, s) == pytest.approx(w / k**2 * (1 - k * s / 2), rel=1e-12)
    assert well.midspan_moment(w, T, EI, s) == pytest.approx(w / k**2, rel=1e-12)
    # and far beyond exp's range (u = 5000): no overflow, no nan
    T = EI * (1e4 / s) ** 2
    with np.errstate(all="raise"):
        assert np.isfinite(well.beam_column_deflection(np.array([0.0, 0.1, s / 2]), w, T, EI, s)).all()
        assert np.isfinite(well.midspan_moment(w, T, EI, s))


def test_compression_beyond_the_clamped_euler_load_is_nan():
    # A clamped-clamped span buckles at T = −4π² EI/s² (Timoshenko & Gere 1961 ch. 2): z = −π².
    EI, s = 8.3e5, 9.0
    euler = 4 * np.pi**2 * EI / s**2
    below = -0.999 * euler
    assert np.isfinite(well.support_moment(1.0, below, EI, s))
    assert abs(well.support_moment(1.0, -0.999999 * euler, EI, s)) > 1e4 * s**2 / 12  # grows without bound
    for T in (-euler, -1.01 * euler):
        assert np.isnan(well.support_moment(1.0, T, EI, s))
        assert np.isnan(well.midspan_moment(1.0, T, EI, s))
        assert np.isnan(well.beam_column_deflection(s / 2, 1.0, T, EI, s))


def test_beam_column_functions_broadcast_over_arrays():
    T = np.array([0.0, 1e3, 1e5])
    moments = well.support_moment(200.0, T, 8.3e5, 9.0)
    assert moments.shape == (3,)
    assert moments[0] == pytest.approx(-200.0 * 81 / 12)
    assert np.all(np.diff(moments) > 0)  # tension straightens the body: smaller hogging moments at the joints
    y = well.beam_column_deflection(np.linspace(0, 9.0, 5)[:, None], 200.0, T[None, :], 8.3e5, 9.0)
    assert y.shape == (5, 3)
    assert np.isnan(well.beam_column_deflection(9.5, 200.0, 1e3, 8.3e5, 9.0))  # outside the span


# --- doglegs ------------------------------------------------------------------------------------------


def test_lubinski_tends_to_the_pipe_following_the_curve_as_tension_vanishes():
    # Lubinski 1961 (doi:10.2118/1543-G-PA): KL/tanh KL -> 1, sigma -> E D kappa / 2 = E r_o kappa.
    E, D, kappa, EI, L = 206.8e9, 4.5 * IN, 0.0017, 8.3e5, 4.6
    plain = well.curvature_bending_stress(E, D / 2, kappa)
    assert plain == pytest.approx(E * D * kappa / 2, rel=1e-15)
    assert well.lubinski_bending_stress(E, D, kappa, 0.0, EI, L) == pytest.approx(plain, rel=1e-15)
    # KL/tanh KL = 1 + (KL)²/3 − ... (A&S 4.5.67): at (KL)² = 1e-6 the stress is up by 1e-6/3
    T = 1e-6 * EI / L**2
    assert well.lubinski_bending_stress(E, D, kappa, T, EI, L) == pytest.approx(plain * (1 + 1e-6 / 3), rel=1e-13)


@pytest.mark.parametrize("KL", [3.0, 10.0, 40.0, 1e3])
def test_lubinski_grows_like_KL_for_large_KL(KL):
    E, D, kappa, EI, L = 206.8e9, 4.5 * IN, 0.0017, 8.3e5, 4.6
    T = (KL / L) ** 2 * EI
    ratio = well.lubinski_bending_stress(E, D, kappa, T, EI, L) / (E * D * kappa / 2)
    assert ratio == pytest.approx(KL / math.tanh(KL), rel=1e-14)
    # coth KL − 1 = 2 e^(−2KL)/(1 − e^(−2KL)), under 2.01 e^(−2KL) for KL >= 3
    assert 0.0 <= ratio / KL - 1.0 <= 2.01 * math.exp(-2 * KL) + 1e-15


def test_lubinski_worked_example_4_half_inch_pipe():
    # By hand, API RP 7G's form of Lubinski's equation in oilfield units:
    #   4½-in 16.6 ppf drill pipe: OD 4.5 in, ID 3.826 in (API RP 7G pipe table, wall 0.337 in);
    #   I = π/64 (4.5⁴ − 3.826⁴) = π/64 (410.06 − 214.28) = 9.610 in⁴; E = 30e6 psi; EI = 2.883e8 lbf·in²;
    #   T = 100 000 lbf; K = √(T/EI) = √(1e5/2.883e8) = 0.01862 1/in;
    #   30-ft joints: L = 15 ft = 180 in; KL = 3.352; tanh 3.352 = 0.99755; KL/tanh KL = 3.3605;
    #   dogleg 3°/100 ft: κ = (3π/180)/1200 in = 4.363e-5 1/in; E D κ/2 = 30e6·4.5·4.363e-5/2 = 2945 psi;
    #   σ_b = 2945 × 3.3605 = 9 897 psi.
    I = np.pi / 64 * ((4.5 * IN) ** 4 - (3.826 * IN) ** 4)
    E = 30e6 * PSI
    kappa = well.dogleg_curvature(3 * well.DEG_PER_100FT)
    sigma = well.lubinski_bending_stress(E, 4.5 * IN, kappa, 100_000 * LBF, E * I, 15 * FT)
    assert sigma / PSI == pytest.approx(9897, rel=2e-4)  # the hand figures' four digits
    assert well.curvature_bending_stress(E, 2.25 * IN, kappa) / PSI == pytest.approx(2945, rel=2e-4)


@pytest.mark.parametrize("T", [0.0, 1e3, 4.4e4, 4.4e5, 1.3e6])
def test_lubinski_is_the_curve_plus_the_beam_column_under_the_tensions_pull(T):
    # docs/model.md §13.3: seen from the hole's axis, a span between joints that follow a curve κ is the clamped
    # beam-column under the tension's pull T κ; its moment at the joints added to the curve's own −EI κ gives
    # Lubinski's −EI κ KL/tanh KL (L = s/2), and at mid-joint −EI κ KL/sinh KL. Two derivations, one number.
    E, r_o, r_i, s = 206.8e9, 2.25 * IN, 1.913 * IN, 31 * FT
    I = np.pi / 4 * (r_o**4 - r_i**4)
    kappa = 3 * well.DEG_PER_100FT
    at_joint = -E * I * kappa + well.support_moment(T * kappa, T, E * I, s)
    sigma = well.lubinski_bending_stress(E, 2 * r_o, kappa, T, E * I, s / 2)
    assert abs(at_joint) * r_o / I == pytest.approx(sigma, rel=1e-12)
    KL = math.sqrt(T / (E * I)) * s / 2
    at_mid = -E * I * kappa + well.midspan_moment(T * kappa, T, E * I, s)
    assert at_mid == pytest.approx(-E * I * kappa * (KL / math.sinh(KL) if KL else 1.0), rel=1e-10)


def test_lubinski_is_nan_in_compression():
    assert np.isnan(well.lubinski_bending_stress(206.8e9, 0.1143, 0.0017, -1e3, 8.3e5, 4.6))


def test_dogleg_curvature_is_the_severity_in_si():
    # 3°/100 ft: (3 π/180) / 30.48 m = 1.7178e-3 1/m, a radius of 582.1 m (1909.9 ft = 18 000/(3π) ft)
    kappa = well.dogleg_curvature(3 * well.DEG_PER_100FT)
    assert kappa == pytest.approx(3 * np.pi / 180 / 30.48, rel=1e-15)
    assert 1 / kappa / FT == pytest.approx(18000 / (3 * np.pi), rel=1e-12)
    assert well.dogleg_curvature(0.0) == 0.0
    np.testing.assert_array_equal(well.dogleg_curvature(np.array([0.0, 1e-3])), [0.0, 1e-3])
    for bad in (-1e-3, np.nan, np.inf):
        with pytest.raises(ValueError, match="dogleg severity"):
            well.dogleg_curvature(bad)
    assert well.MAX_DOGLEG_SEVERITY == pytest.approx(30 * np.pi / 180 / 30.48, rel=1e-15)


# --- side loads and whirl -----------------------------------------------------------------------------


def test_buoyed_weight_is_the_weight_less_the_displaced_mud():
    # 16.6 lb/ft pipe (24.70 kg/m) with 10-ppg mud (1198.3 kg/m³) inside and out: (m_p − ρ A_s) g, A_s the steel
    m_p = 16.6 * 0.45359237 / FT
    rho = 10 * 0.45359237 / 3.785411784e-3
    r_o, r_i = 2.25 * IN, 1.913 * IN
    m_i = rho * np.pi * r_i**2
    expected = (m_p - rho * np.pi * (r_o**2 - r_i**2)) * 9.80665
    assert well.buoyed_weight(m_p, m_i, rho, r_o) == pytest.approx(expected, rel=1e-14)
    assert well.buoyed_weight(m_p, m_i, rho, r_o) * np.sin(0.3) == pytest.approx(
        whirl.side_load(m_p, m_i, rho, r_o, 0.3), rel=1e-15)


@pytest.mark.parametrize("name,expected", [
    ("drop", (300.0 + 50.0, 0.0)),    # centre of curvature on the low side: tension adds to the weight
    ("build", (300.0 - 50.0, 0.0)),   # centre on the high side: tension lifts the pipe off the low side
    ("walk_right", (300.0, -50.0)),   # centre to the driller's right, −z (z = x × y is to the left)
    ("walk_left", (300.0, 50.0)),
])
def test_side_load_vector_for_build_drop_and_walk(name, expected):
    # w_b = 600 N/m at 30° (side component 300 N/m), T = 5e4 N, κ = 1e-3 1/m: T κ = 50 N/m
    w_y, w_z = well.side_load_vector(600.0, np.pi / 6, 5e4, 1e-3, well.DOGLEG_DIRECTIONS[name])
    assert (w_y, w_z) == pytest.approx(expected, abs=1e-12)


def test_side_load_vector_magnitude_is_the_soft_string_normal_force():
    # Johancsik, Friesen & Dawson 1984 (doi:10.2118/11380-PA): N = √((T Δα sin θ)² + (T Δθ + w sin θ)²) per
    # length, the tension's part T κ split into its components in the vertical plane and across it.
    w_b, theta, T, kappa, phi = 420.0, 0.7, 8e4, 2e-3, 2.2
    w_y, w_z = well.side_load_vector(w_b, theta, T, kappa, phi)
    in_plane, across = T * kappa * np.cos(phi), T * kappa * np.sin(phi)
    assert np.hypot(w_y, w_z) == pytest.approx(np.sqrt(across**2 + (in_plane + w_b * np.sin(theta)) ** 2),
                                               rel=1e-14)
    # a straight hole: the weight's side component alone (docs/model.md §13: N = w)
    assert well.side_load_vector(w_b, theta, T, 0.0, phi) == pytest.approx((w_b * np.sin(theta), 0.0))
    # a vertical hole in a drop: only the tension's pull
    assert well.side_load_vector(w_b, 0.0, T, kappa, 0.0) == pytest.approx((T * kappa, 0.0))


def test_walk_right_is_towards_east_for_a_hole_heading_north():
    # The hole frame in north-east-down axes: a horizontal hole heading north, x = N, y = low side = down,
    # z = x × y. Turning right (azimuth increasing) moves the hole east: the centre of curvature is east.
    x, y = np.array([1.0, 0.0, 0.0]), np.array([0.0, 0.0, 1.0])
    z = np.cross(x, y)
    east = np.array([0.0, 1.0, 0.0])
    phi = well.DOGLEG_DIRECTIONS["walk_right"]
    assert np.cos(phi) * y + np.sin(phi) * z == pytest.approx(east, abs=1e-15)
    # and the drill string's rotation, positive from +y towards +z, is clockwise seen from above (about +down)
    assert np.dot(np.cross(y, z), np.array([1.0, 0.0, 0.0])) > 0


def test_rolling_whirl_rate():
    # Black 1968; Jansen 1991: −Ω R/c. A 6¼-in tool joint in an 8¾-in hole at 120 rpm: R = 3.125 in, c = 1.25 in,
    # −2.5 Ω = −31.42 rad/s (−300 rpm).
    omega = 120 * 2 * np.pi / 60
    assert well.rolling_whirl_rate(omega, 3.125 * IN, 1.25 * IN) == pytest.approx(-2.5 * omega, rel=1e-14)
    assert well.rolling_whirl_rate(omega, 3.125 * IN, 1.25 * IN) * 60 / (2 * np.pi) == pytest.approx(-300.0)
    np.testing.assert_allclose(well.rolling_whirl_rate(np.array([0.0, omega]), 2.25 * IN, 2.125 * IN),
                               [0.0, -omega * 2.25 / 2.125], rtol=1e-14)


def test_a_tool_joint_adds_its_steel_and_bore_beyond_the_plain_pipe_and_their_buoyed_weight():
    # docs/reference_model.md §9: a 6 1/4 x 3 1/4-in joint of 20 in is ρ_s π/4 (D² − d²) ℓ = 57.6 kg of steel (by
    # hand: 7850 kg/m³ x 0.014442 m² x 0.508 m); with no pipe, no mud it is all of the lumped mass and its weight m g
    D, d, length = 6.25 * 0.0254, 3.25 * 0.0254, 0.508
    steel = 7850.0 * 0.25 * np.pi * (D**2 - d**2) * length
    assert steel == pytest.approx(57.59, abs=0.01)
    mass, weight = well.tool_joint_excess(7850.0, D, d, length, 0.0, 0.0, 0.0, 0.0)
    assert mass == pytest.approx(steel, rel=1e-12) and weight == pytest.approx(steel * 9.80665, rel=1e-12)
    # a "joint" the size of the pipe (same diameters, the pipe's own steel mass per length) adds nothing, in any mud
    r_o, r_i = 0.05715, 0.04859
    m_p = 7850.0 * np.pi * (r_o**2 - r_i**2)
    assert well.tool_joint_excess(7850.0, 2 * r_o, 2 * r_i, length, m_p, 2 * r_o, 2 * r_i, 1198.0) == \
        pytest.approx((0.0, 0.0), abs=1e-12)
    # Archimedes on the excess: the mud in the joint's smaller bore is gone from the mass, the annular mud its larger
    # outside displaces from the weight; a zero length adds nothing
    rho = 1198.0
    mass, weight = well.tool_joint_excess(7850.0, D, d, length, m_p, 2 * r_o, 2 * r_i, rho)
    quarter = 0.25 * np.pi * length
    assert mass == pytest.approx(steel - m_p * length + rho * quarter * (d**2 - (2 * r_i) ** 2), rel=1e-12)
    assert weight == pytest.approx((mass - rho * quarter * (D**2 - (2 * r_o) ** 2)) * 9.80665, rel=1e-12)
    assert well.tool_joint_excess(7850.0, D, d, 0.0, m_p, 2 * r_o, 2 * r_i, rho) == (0.0, 0.0)
