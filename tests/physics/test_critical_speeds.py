"""Critical rotary speeds (study.physics.critical_speeds): API RP 7G's rule of thumb against printed
values, the span's critical speeds against the bare-beam closed form, and the two against each other."""

import numpy as np
import pytest

from study.physics import critical_speeds as cs
from study.physics import section

INCH, FT, LB = 0.0254, 0.3048, 0.45359237  # exact
RPM = 2.0 * np.pi / 60.0


def rpm(omega):
    return np.asarray(omega) / RPM


def test_worked_example_of_the_rule_of_thumb():
    # drillingformulas.com, "Critical RPM to avoid excessive vibration": one joint L = 32 ft,
    # OD 4.0 in, ID 3.5 in -> critical RPM = 172 (printed, rounded to 1 rpm).
    assert rpm(cs.rp7g_critical_speed(32 * FT, 4.0 * INCH, 3.5 * INCH)) == pytest.approx(172.0, abs=0.5)


def test_formula_as_defined():
    # rpm = 4 760 000 sqrt(D^2 + d^2)/L^2, inches (API RP 7G); L = 360 in, D = 4.5 in, d = 3.826 in.
    expected = 4_760_000 * np.sqrt(4.5**2 + 3.826**2) / 360.0**2
    assert rpm(cs.rp7g_critical_speed(360 * INCH, 4.5 * INCH, 3.826 * INCH)) == pytest.approx(expected, rel=1e-12)


# HOMCO Technical Data Handbook §9, Table 9.1/9.2 ("Pipe sizes vs. critical rotary speeds", from the
# rule of thumb): size [in] -> approx. critical rotary speed [rpm], printed to 5 rpm. The copy does
# not show the weights or the joint length; the inner diameters here are those of the commonest API
# weight of each size (API RP 7G new drill-pipe table: 4.85, 10.40, 13.30, 14.00, 16.60, 19.50,
# 21.90 lb/ft).
HOMCO = [
    (2.375, 1.995, 110), (2.875, 2.151, 130), (3.5, 2.764, 160), (4.0, 3.340, 185),
    (4.5, 3.826, 210), (5.0, 4.276, 235), (5.5, 4.778, 260),
]


def test_printed_table_follows_the_diameter_dependence():
    # With the joint length fitted on the 4-1/2 in entry, the other six entries follow to the table's
    # 5-rpm rounding (the diameter dependence sqrt(D^2 + d^2) of the rule).
    od, id_, printed = 4.5, 3.826, 210
    length = np.sqrt(4_760_000 * np.sqrt(od**2 + id_**2) / printed) * INCH
    assert 29 * FT < length < 32 * FT  # a Range 2 joint (27-30 ft) with its tool joints
    for od, id_, printed in HOMCO:
        assert rpm(cs.rp7g_critical_speed(length, od * INCH, id_ * INCH)) == pytest.approx(printed, abs=2.5)


def test_the_constant_is_the_first_mode_of_a_bare_simply_supported_steel_tube():
    # rpm = 60 f1 = (15 pi/2) sqrt(E/rho) sqrt(D^2+d^2)/L^2 in inches; E = 30e6 psi, rho = 490 lb/ft^3.
    g = 9.80665 / INCH  # in/s^2
    rho = 490.0 / 1728.0 / g  # lbf s^2/in^4
    constant = 15.0 * np.pi / 2.0 * np.sqrt(30e6 / rho)
    assert constant == pytest.approx(cs.API_RP7G_CONSTANT, rel=1e-3)


def bare_joint(length=30 * FT, od=4.5 * INCH, id_=3.826 * INCH, youngs=206.84e9, density=7850.0):
    ei = section.bending_stiffness(youngs, od / 2, id_ / 2)
    mass = density * section.steel_area(od / 2, id_ / 2)
    return length, ei, mass


def test_span_critical_speeds_are_the_bare_beam_closed_form_without_tension_or_mud():
    # Simply supported Euler-Bernoulli beam: omega_n = (n pi/L)^2 sqrt(EI/m) (Timoshenko, Vibration
    # Problems in Engineering, §60); synchronous whirl at Omega = omega_n.
    length, ei, mass = bare_joint()
    modes = (1, 2, 3)
    expected = [(n * np.pi / length) ** 2 * np.sqrt(ei / mass) for n in modes]
    np.testing.assert_allclose(cs.critical_rotary_speeds(length, ei, 0.0, mass, modes), expected, rtol=1e-12)
    # an excitation twice per revolution meets each mode at half the speed
    np.testing.assert_allclose(cs.critical_rotary_speeds(length, ei, 0.0, mass, modes, order=2),
                               np.array(expected) / 2, rtol=1e-12)


@pytest.mark.parametrize("od, id_", [(d, i) for d, i, _ in HOMCO])
def test_rule_of_thumb_and_span_model_agree_for_a_bare_joint(od, id_):
    # The rule is the same physics (a bare pinned tube, no tension, no mud): with the project's steel
    # (E = 206.84 GPa, rho = 7850 kg/m^3) the two agree far inside the rule's stated 15 %; the residue
    # is the rule's rounded constant and its steel (30e6 psi, 490 lb/ft^3).
    length, ei, mass = bare_joint(od=od * INCH, id_=id_ * INCH)
    span = cs.critical_rotary_speeds(length, ei, 0.0, mass, modes=(1,))[..., 0]
    rule = cs.rp7g_critical_speed(length, od * INCH, id_ * INCH)
    assert span / rule == pytest.approx(1.0, abs=2e-3)
    assert abs(span / rule - 1.0) < cs.API_RP7G_ACCURACY


def test_tension_raises_and_mud_lowers_the_joints_critical_speed():
    # The paper's example load (10 000 lbf) and mud (10 ppg) on a 30-ft joint of 4-1/2 in 16.6 lb/ft pipe
    # in an 8-1/2 in hole: tension stiffens the span, internal mud and added mass weigh it down. The
    # rule of thumb knows neither; here tension alone moves the speed by more than its 15 %.
    length, ei, steel = bare_joint()
    r_o, r_i, hole = 2.25 * INCH, 1.913 * INCH, 4.25 * INCH
    mud = 10 * LB / 3.785411784e-3
    wet = section.mass_per_length(steel, section.internal_mud_mass(mud, r_i), section.added_mass(mud, r_o, hole))
    tension = 10_000 * LB * 9.80665
    bare = cs.critical_rotary_speeds(length, ei, 0.0, steel, (1,))[0]
    pulled = cs.critical_rotary_speeds(length, ei, tension, steel, (1,))[0]
    muddy = cs.critical_rotary_speeds(length, ei, 0.0, wet, (1,))[0]
    k = np.pi / length
    assert pulled / bare == pytest.approx(np.sqrt(1.0 + tension * k**2 / (ei * k**4)), rel=1e-12)
    assert pulled / bare > 1.0 + cs.API_RP7G_ACCURACY
    assert muddy / bare == pytest.approx(np.sqrt(steel / wet), rel=1e-12)
    assert muddy < bare


def test_buckled_span_has_no_critical_speed_and_bands_are_fifteen_percent():
    length, ei, mass = bare_joint()
    compression = 2.0 * section.euler_buckling_tension(length, ei)  # twice the buckling load
    assert np.isnan(cs.critical_rotary_speeds(length, ei, compression, mass, (1,))[0])
    low, high = cs.avoid_band(100.0 * RPM)
    assert rpm(low) == pytest.approx(85.0) and rpm(high) == pytest.approx(115.0)
