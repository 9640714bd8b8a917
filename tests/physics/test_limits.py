"""The limits of a design point (study.physics.limits) against closed forms built from printed values."""

import numpy as np
import pytest

from study.physics import fatigue, limits, materials

PSI = materials.PSI
RPM = 2.0 * np.pi / 60.0


def test_defaults_are_e75_b1_goodman_one_cycle_per_revolution():
    # E-75 minimum yield 75 000 psi (API Spec 5D Table 6.3); B1 fatigue limit 106.97 MPa at 1e7 cycles
    # (DNV-RP-C203 Table 2-1), so half of it is the endurance amplitude; zero mean, K_t = 1.
    endurance = fatigue.endurance_limit("B1")
    result = limits.design_limits(75_000 * PSI, endurance, 0.0, 100 * RPM)
    assert result.yield_utilisation == pytest.approx(1.0)
    assert result.endurance_utilisation == pytest.approx(1.0)
    # Miner at the knee: N = 1e7 cycles at 100/60 cycles per second -> 6e6 s
    assert result.fatigue_life == pytest.approx(1e7 / (100 / 60), rel=2e-3)
    assert result.damage_rate * result.fatigue_life == pytest.approx(1.0)


def test_goodman_mean_and_tool_joint_factor_enter_as_their_closed_forms():
    # S-135: tensile 145 000 psi. Goodman: sigma_ar = K_t sigma_a / (1 - sigma_m/sigma_u).
    sigma_a, sigma_m, k_t = 5_000 * PSI, 30_000 * PSI, 1.4
    result = limits.design_limits(40_000 * PSI, sigma_a, sigma_m, 150 * RPM, pipe_grade="S-135",
                                  stress_concentration=k_t)
    expected = k_t * sigma_a / (1 - 30_000 / 145_000)
    assert result.equivalent_amplitude == pytest.approx(expected, rel=1e-12)
    assert result.yield_utilisation == pytest.approx(40_000 / 135_000, rel=1e-12)
    cycles_per_second = 150 / 60
    assert result.damage_rate == pytest.approx(cycles_per_second / fatigue.cycles_to_failure(2 * expected),
                                               rel=1e-12)


def test_given_strengths_replace_the_grade_and_soderberg_uses_the_yield():
    result = limits.design_limits(600e6, 50e6, 200e6, 10.0, pipe_grade="G-105", yield_strength=800e6,
                                  tensile_strength=900e6, mean_stress_correction="soderberg")
    assert result.yield_utilisation == pytest.approx(0.75)
    assert result.equivalent_amplitude == pytest.approx(50e6 / (1 - 200e6 / 800e6))


def test_limits_broadcast_over_a_grid_of_rotary_speed_and_load():
    rpm = np.array([60.0, 120.0, 240.0])[:, None]
    mean = np.array([0.0, 20e6, 40e6])[None, :]
    result = limits.design_limits(100e6 + mean, 60e6, mean, rpm * RPM)
    assert result.damage_rate.shape == (3, 3) and result.yield_utilisation.shape == (1, 3)
    # damage grows with rpm in proportion (same amplitude) and with the mean (Goodman)
    np.testing.assert_allclose(result.damage_rate[1] / result.damage_rate[0], 2.0, rtol=1e-12)
    assert np.all(np.diff(result.damage_rate, axis=1) > 0)
    np.testing.assert_allclose(result.fatigue_life * result.damage_rate, 1.0)
