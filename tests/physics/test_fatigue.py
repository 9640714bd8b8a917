"""S-N curves, mean-stress corrections and Miner's damage (study.physics.fatigue) against the printed
DNV-RP-C203 table and the closed forms of Goodman, Gerber, Soderberg and Miner."""

import numpy as np
import pytest

from study.physics import fatigue

MPA = 1e6

# DNV-RP-C203 (April 2016), Table 2-1, S-N curves in air: m1, log a1, m2, log a2, fatigue limit at
# 10^7 cycles [MPa], as printed.
TABLE_2_1 = {
    "B1": (4.0, 15.117, 5.0, 17.146, 106.97),
    "B2": (4.0, 14.885, 5.0, 16.856, 93.59),
    "C": (3.0, 12.592, 5.0, 16.320, 73.10),
    "D": (3.0, 12.164, 5.0, 15.606, 52.63),
}


@pytest.mark.parametrize("curve", list(TABLE_2_1))
def test_curves_reproduce_their_printed_fatigue_limits(curve):
    m1, log_a1, m2, log_a2, printed = TABLE_2_1[curve]
    # the knee computed from the first segment is the printed fatigue limit, to the rounding of the
    # printed log a1 (half a unit in its third decimal moves log S by 0.0005/m1)
    rounding = 10.0 ** (0.0005 / m1) - 1.0
    assert fatigue.fatigue_limit(curve) / MPA == pytest.approx(printed, rel=rounding)
    # the printed second segment passes through the same knee at 10^7 cycles (to the table's rounding)
    assert log_a2 - m2 * np.log10(printed) == pytest.approx(7.0, abs=2e-3)
    assert fatigue.cycles_to_failure(printed * MPA, curve) == pytest.approx(1e7, rel=2e-3)
    assert fatigue.endurance_limit(curve) == pytest.approx(0.5 * printed * MPA, rel=rounding)


@pytest.mark.parametrize("curve", list(TABLE_2_1))
def test_each_segment_has_its_printed_slope(curve):
    m1, log_a1, m2, log_a2, printed = TABLE_2_1[curve]
    high = np.array([150.0, 300.0]) * MPA  # above every knee: first segment
    low = np.array([10.0, 20.0]) * MPA  # below every knee: second segment
    n_high = fatigue.cycles_to_failure(high, curve)
    n_low = fatigue.cycles_to_failure(low, curve)
    assert n_high[0] / n_high[1] == pytest.approx(2.0**m1, rel=1e-12)
    assert n_low[0] / n_low[1] == pytest.approx(2.0**m2, rel=1e-12)
    # log N = log a - m log(range in MPa), DNV-RP-C203 eq. (2.4.1)
    assert np.log10(n_high[0]) == pytest.approx(log_a1 - m1 * np.log10(150.0), abs=1e-12)
    assert np.log10(n_low[0]) == pytest.approx(log_a2 - m2 * np.log10(10.0), abs=1e-12)


def test_no_range_never_fails_and_an_infinite_range_fails_at_once():
    assert fatigue.cycles_to_failure(0.0) == np.inf
    assert fatigue.cycles_to_failure(np.inf) == 0.0


SU, SY, SE = 724e6, 517e6, 60e6  # S-135-like tensile and yield strengths, an endurance amplitude [Pa]


@pytest.mark.parametrize("correction, strength", [("goodman", SU), ("soderberg", SY)])
def test_points_on_the_straight_lines_are_equivalent_to_the_endurance_amplitude(correction, strength):
    # Goodman: sigma_a/S_e + sigma_m/S_u = 1; Soderberg: the same with S_y (Shigley's Mechanical
    # Engineering Design, ch. 6). Every point on the line from (0, S_e) to (S, 0) has the fully reversed
    # equivalent S_e.
    mean = np.linspace(0.0, 0.9 * strength, 7)
    amplitude = SE * (1.0 - mean / strength)
    result = fatigue.equivalent_alternating_stress(amplitude, mean, SU, SY, correction)
    np.testing.assert_allclose(result, SE, rtol=1e-12)


def test_points_on_gerbers_parabola_are_equivalent_to_the_endurance_amplitude():
    # Gerber: sigma_a/S_e + (sigma_m/S_u)^2 = 1 (Shigley's Mechanical Engineering Design, ch. 6).
    mean = np.linspace(0.0, 0.9 * SU, 7)
    amplitude = SE * (1.0 - (mean / SU) ** 2)
    np.testing.assert_allclose(fatigue.equivalent_alternating_stress(amplitude, mean, SU, SY, "gerber"), SE,
                               rtol=1e-12)


@pytest.mark.parametrize("correction", ["goodman", "gerber", "soderberg", "none"])
def test_end_points_of_the_mean_stress_rules(correction):
    # at zero mean every rule is the amplitude itself; a compressive mean earns no credit
    assert fatigue.equivalent_alternating_stress(SE, 0.0, SU, SY, correction) == pytest.approx(SE)
    assert fatigue.equivalent_alternating_stress(SE, -200e6, SU, SY, correction) == pytest.approx(SE)
    end = {"goodman": SU, "gerber": SU, "soderberg": SY}.get(correction)
    if end is not None:
        # at the line's end on the mean axis no alternating stress is allowed: infinite equivalent
        assert fatigue.equivalent_alternating_stress(SE, end, SU, SY, correction) == np.inf


def test_gerber_is_the_least_and_soderberg_the_most_conservative():
    mean = np.linspace(10e6, 0.95 * SY, 9)
    gerber = fatigue.equivalent_alternating_stress(SE, mean, SU, SY, "gerber")
    goodman = fatigue.equivalent_alternating_stress(SE, mean, SU, SY, "goodman")
    soderberg = fatigue.equivalent_alternating_stress(SE, mean, SU, SY, "soderberg")
    assert np.all(SE < gerber) and np.all(gerber < goodman) and np.all(goodman < soderberg)


def test_miners_life_at_the_knee_and_100_rpm():
    # Closed form: at the B1 fatigue limit N = 10^7; one cycle per revolution at 100 rpm is 100/60 cycles
    # per second, so D = 1 after 10^7 / (100/60) s = 6e6 s = 1666.7 h of rotation.
    omega = 100.0 * 2.0 * np.pi / 60.0
    amplitude = fatigue.endurance_limit("B1")
    rate = fatigue.damage_rate(amplitude, omega, 1.0, "B1")
    assert rate == pytest.approx((100.0 / 60.0) / 1e7, rel=1e-9)
    assert fatigue.fatigue_life(rate) / 3600.0 == pytest.approx(1e7 / (100.0 / 60.0) / 3600.0, rel=1e-9)
    assert fatigue.fatigue_life(rate) * rate == pytest.approx(1.0)
    # two cycles per revolution do damage twice as fast
    assert fatigue.damage_rate(amplitude, omega, 2.0, "B1") == pytest.approx(2.0 * rate, rel=1e-12)


def test_stress_concentration_scales_damage_by_its_power_on_the_curve():
    # Above the knee of B1, N ~ range^-4: a tool-joint factor K_t = 1.5 on the alternating stress
    # multiplies the damage rate by 1.5^4 = 5.0625.
    omega = 120.0 * 2.0 * np.pi / 60.0
    nominal = 80e6
    plain = fatigue.local_equivalent_amplitude(nominal, 0.0, SU, SY, stress_concentration=1.0)
    joint = fatigue.local_equivalent_amplitude(nominal, 0.0, SU, SY, stress_concentration=1.5)
    assert joint == pytest.approx(1.5 * plain)
    ratio = fatigue.damage_rate(joint, omega) / fatigue.damage_rate(plain, omega)
    assert ratio == pytest.approx(1.5**4, rel=1e-12)


def test_the_concentration_factor_does_not_raise_the_mean():
    # K_t multiplies the alternating stress only: Goodman with the nominal mean.
    result = fatigue.local_equivalent_amplitude(40e6, 200e6, SU, SY, stress_concentration=2.0)
    assert result == pytest.approx(80e6 / (1.0 - 200e6 / SU), rel=1e-12)


def test_endurance_utilisation_is_one_at_the_endurance_limit_and_no_damage_without_stress():
    assert fatigue.endurance_utilisation(fatigue.endurance_limit("C"), "C") == pytest.approx(1.0)
    assert fatigue.damage_rate(0.0, 30.0) == 0.0
    assert fatigue.fatigue_life(0.0) == np.inf


def test_unknown_curve_and_correction_are_refused_with_the_allowed_names():
    with pytest.raises(ValueError, match=r"S-N curve = 'Z'; allowed: B1, B2, C, D"):
        fatigue.cycles_to_failure(1e8, "Z")
    with pytest.raises(ValueError, match=r"mean-stress correction = 'walker'; allowed: goodman, gerber"):
        fatigue.equivalent_alternating_stress(1e7, 0.0, SU, SY, "walker")


def test_rainflow_counts_the_astm_e1049_example():
    # ASTM E1049-85 (2017) §5.4.4 and its Fig. 6: the history -2, 1, -3, 5, -1, 3, -4, 4, -2 counts ranges
    # 3, 4, 6, 8, 9 units with 0.5, 1.5, 0.5, 1.0, 0.5 cycles (as printed in the standard's table)
    ranges, means, counts = fatigue.rainflow_cycles(np.array([-2, 1, -3, 5, -1, 3, -4, 4, -2]) * MPA)
    counted = {}
    for r, c in zip(ranges / MPA, counts):
        counted[round(r, 9)] = counted.get(round(r, 9), 0.0) + c
    assert counted == {3.0: 0.5, 4.0: 1.5, 6.0: 0.5, 8.0: 1.0, 9.0: 0.5}


@pytest.mark.parametrize("mean", [0.0, 150 * MPA])
def test_a_sinusoidal_history_does_the_damage_of_one_cycle_a_period(mean):
    # closed form (Miner): 20 whole periods of amplitude 60 MPa about the mean, 1.5 s each, do 20 cycles of the
    # constant-amplitude rate of fatigue.damage_rate at one cycle a period (rotary speed 2π/1.5 rad/s); the history
    # starts and ends at a peak (rainflow counts 19 cycles and two half cycles of the full range: 20)
    period, amplitude = 1.5, 60 * MPA
    t = np.linspace(0.0, 20 * period, 20 * 64 + 1)
    stress = mean + amplitude * np.cos(2 * np.pi * t / period)
    rate = fatigue.history_damage_rate(stress, 20 * period, 517e6 * 1.3, stress_concentration=1.2)
    sigma_ar = fatigue.local_equivalent_amplitude(amplitude, mean, 517e6 * 1.3, stress_concentration=1.2)
    expected = fatigue.damage_rate(sigma_ar, 2 * np.pi / period)
    assert rate == pytest.approx(float(expected), rel=1e-9)


def test_impacts_add_the_small_cycles_one_cycle_a_revolution_misses():
    # a revolution's bending (range 100 MPa) with three impact ringings of range 40 MPa on it: rainflow counts the
    # large cycle once and the three small ones, and the damage exceeds the large cycle's alone by their share
    one = np.array([-50.0, 50.0])
    ring = np.array([-50.0, 50.0, 10.0, 50.0, 10.0, 50.0, 10.0, 50.0])
    revolutions = 10
    plain = np.concatenate([one] * revolutions + [[-50.0]]) * MPA
    rung = np.concatenate([ring] * revolutions + [[-50.0]]) * MPA
    base = fatigue.history_damage_rate(plain, 1.0, 1e12, correction="none")
    more = fatigue.history_damage_rate(rung, 1.0, 1e12, correction="none")
    # both ranges lie below B1's knee (106.97 MPa): its second slope m2 = 5, so each small cycle does (40/100)^5 of
    # the large one's damage (DNV-RP-C203 Table 2-1)
    expected = 1.0 + 3.0 * (40.0 / 100.0) ** 5
    assert more / base == pytest.approx(expected, rel=1e-9)


def test_an_empty_history_does_no_damage():
    assert fatigue.history_damage_rate(np.full(10, 5 * MPA), 1.0, 700e6) == 0.0


def test_reversals_in_numpy_count_as_the_rainflow_package_does():
    # fatigue.rainflow_cycles reduces a history to its reversals first; the package's own count of the whole
    # history (rainflow.extract_cycles, ASTM E1049 §5.4.4) is the reference, plateaus and repeated values included
    import rainflow

    rng = np.random.default_rng(3)
    for _ in range(50):
        x = np.round(rng.normal(size=int(rng.integers(1, 80))), 1)  # rounded: plateaus and repeats
        expected = sorted((r, m, c) for r, m, c, *_ in rainflow.extract_cycles(x))
        ranges, means, counts = fatigue.rainflow_cycles(x)
        assert np.allclose(np.reshape(expected, (-1, 3)), np.reshape(sorted(zip(ranges, means, counts)), (-1, 3)))


def test_the_compiled_count_is_the_rainflow_packages_cycle_for_cycle():
    # fatigue._rainflow_kernel replaces rainflow.extract_cycles (3.2.0) on a history's reversals: the same cycles in
    # the same order (Miner's sums and the spread over revolutions add them in that order), the same arithmetic,
    # bit for bit; on any series, reversals or not, plateaus, repeats and the 0-3 point ends included
    import rainflow

    rng = np.random.default_rng(5)
    series = [np.zeros(0), np.array([1.0]), np.array([1.0, 2.0]), np.array([2.0, 2.0]), np.array([0.0, 1.0, 0.0])]
    series += [np.round(rng.normal(size=int(rng.integers(3, 120))), int(rng.integers(0, 3))) for _ in range(200)]
    series += [rng.normal(size=2000)]
    for x in series:
        expected = list(rainflow.extract_cycles(x))
        got = list(zip(*(v.tolist() for v in fatigue._rainflow_kernel(x))))
        assert got == [tuple(row) for row in expected]


def test_three_strikes_a_revolution_do_three_times_the_damage_of_one_cycle_a_revolution():
    # closed form: a fibre whose stress rings through three whole cycles of the same range each revolution (three
    # impacts) counts three cycles a revolution by rainflow; one cycle a revolution of that alternating stress
    # (fatigue.damage_rate, rotating bending) does a third of the damage. fatigue.damage_rate at Ω = 2π rad/s is the
    # damage of one revolution
    revolutions, amplitude, mean, strength = 12, 80 * MPA, 40 * MPA, 517e6 * 1.3
    one_cycle = float(fatigue.damage_rate(fatigue.equivalent_alternating_stress(amplitude, mean, strength), 2 * np.pi))
    # sampled (64 points a cycle, the peaks between the samples): the rate over the history, to the sampling
    t = np.linspace(0.0, revolutions, revolutions * 3 * 64 + 1)  # time in revolutions
    sampled = mean + amplitude * np.sin(2 * np.pi * 3 * t + 0.1)
    assert fatigue.history_damage_rate(sampled, revolutions, strength) / one_cycle == pytest.approx(3.0, rel=0.03)
    # its reversals alone, exactly +-amplitude: rainflow counts each range as a half cycle (ASTM E1049 §5.4.4, every
    # range equal to the one before), six a revolution; per revolution (the stretches of history_damage, each
    # cycle's damage spread over the time between its reversals) every revolution does three cycles' damage and the
    # revolutions' damages sum to the history's
    reversals = mean + amplitude * np.append(np.tile([1.0, -1.0], 3 * revolutions), 1.0)  # the next one's first
    per_revolution = fatigue.history_damage(reversals, strength, segments=np.arange(revolutions) * 6)
    assert per_revolution == pytest.approx(3.0 * one_cycle, rel=1e-12)
    assert per_revolution.sum() == pytest.approx(fatigue.history_damage(reversals, strength), rel=1e-12)
    # and where a revolution's cycles close does not move its damage: the same history from mid-revolution
    shifted = fatigue.history_damage(reversals, strength, segments=np.arange(revolutions) * 6 + 3)
    assert shifted[1:-1] == pytest.approx(3.0 * one_cycle, rel=1e-12)


def test_damage_exponent_is_the_second_slope():
    # DNV-RP-C203 Table 2-1: m2 = 5 for every curve in air
    assert [fatigue.damage_exponent(c) for c in TABLE_2_1] == [5.0] * 4
