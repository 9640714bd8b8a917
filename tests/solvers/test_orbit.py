"""Periodic orbits of the modal model found by shooting (study.solvers.kernels.orbit)."""

import numpy as np
import pytest

from study.solvers.kernels import event_driven, orbit
from study.solvers.methods import timedomain

OMEGA = np.array([3.0, 11.0, 27.0])  # rad/s
ZETA = np.array([0.05, 0.02, 0.01])
ROTARY = 2.0  # rad/s
DRIVE = 0.7  # F0/m [m/s^2] on mode 1


def free_system(clearance=1e3):
    """Three damped modes, driven on mode 1, with walls too far away to reach."""
    damping = np.diag(2 * ZETA * OMEGA)
    phi = np.sin(np.pi * np.outer([0.5], [1, 2, 3]))
    return event_driven.prepare(OMEGA, damping, DRIVE, ROTARY, phi, 1.0, 1e9, clearance, 0.0, 1.0)


def _scale(n, clearance=1.0):
    return np.concatenate((np.full(n, clearance), np.full(n, ROTARY * clearance)))


@pytest.mark.parametrize("mirror", [False, True])
@pytest.mark.parametrize("t0", [0.0, 0.9])
def test_without_contact_the_orbit_is_the_forced_response_with_exponential_multipliers(mirror, t0):
    # Source (closed form): q'' + 2 zeta w q' + w^2 q = f cos(Omega t) has the periodic solution
    # Re[f e^{i Omega t}/(w^2 - Omega^2 + 2i zeta w Omega)] and Floquet multipliers exp(lambda tau),
    # lambda = -zeta w +- i w sqrt(1 - zeta^2), tau = 2 pi/Omega; the undriven modes rest.
    tau = 2 * np.pi / ROTARY
    found = orbit.find_orbit(free_system(), np.zeros(6), t0, tau / 2 if mirror else tau, _scale(3), mirror=mirror)
    assert found.status == "converged", found.message
    amplitude = DRIVE / (OMEGA[0] ** 2 - ROTARY**2 + 2j * ZETA[0] * OMEGA[0] * ROTARY)
    expected = np.zeros(6)
    expected[0] = (amplitude * np.exp(1j * ROTARY * t0)).real
    expected[3] = (1j * ROTARY * amplitude * np.exp(1j * ROTARY * t0)).real
    np.testing.assert_allclose(found.state, expected, atol=1e-9)
    lam = -ZETA * OMEGA + 1j * OMEGA * np.sqrt(1 - ZETA**2)
    mu = np.exp(np.concatenate((lam, lam.conj())) * tau)
    np.testing.assert_allclose(np.sort_complex(found.multipliers), np.sort_complex(mu), atol=1e-5)
    assert found.stable and found.largest_multiplier == pytest.approx(np.exp(-np.min(ZETA * OMEGA) * tau), rel=1e-4)
    assert found.contacts == 0 and found.peak_force == 0.0


def test_a_guess_inside_the_wall_is_a_bad_section():
    system = free_system(clearance=0.01)
    guess = np.zeros(6)
    guess[0] = 0.02  # midspan at 2 c
    found = orbit.find_orbit(system, guess, 0.0, np.pi, _scale(3, 0.01))
    assert found.status == "bad_section" and "contact is open at the section" in found.message


def test_newton_reports_the_residual_it_stopped_at():
    found = orbit.find_orbit(free_system(), np.zeros(6), 0.0, np.pi, _scale(3), max_iterations=0)
    assert found.status == "not_converged"
    assert f"residual {found.residual:.3g} after 0 iterations (tolerance 1e-06)" in found.message
    assert found.stable is None and np.isnan(found.largest_multiplier)


@pytest.fixture(scope="module")
def settled(paper_inputs):
    """The time domain on a 105-m span of the paper's example (5 modes, mud damping, the drive): it
    settles into one revolution with two contacts."""
    inputs = {**paper_inputs, "span_length": 105.0, "time_revolutions": 200}
    run = timedomain.simulate(inputs)
    assert run["verdict"] == "periodic" and run["period"] == 1, run["verdict"]
    return inputs, run


def test_where_the_time_domain_settles_shooting_finds_the_same_stable_orbit(settled):
    # Two methods, one answer: integrating revolution after revolution until the state repeats
    # (study.solvers.methods.timedomain) and Newton on the section map from an early, unsettled state.
    inputs, run = settled
    model = run["model"]
    scale = model.state_scale()
    early = run["states"][3]
    assert np.max(np.abs(early - run["states"][-1]) / scale) > 1e-2  # far from settled
    found = orbit.find_orbit(run["system"], early, 0.0, model.period, scale, tol=1e-9)
    assert found.status == "converged", found.message
    # The time domain stops when two revolutions' states differ by at most its tolerance (1e-4); contracting
    # by mu per revolution, it is then within 1e-4 mu/(1 - mu) of the orbit.
    mu = found.largest_multiplier
    np.testing.assert_allclose(found.state / scale, run["states"][-1] / scale, atol=1e-4 * mu / (1 - mu))
    assert found.stable and found.largest_multiplier < 1.0
    assert found.contacts == 2
    last = [c["peak"] for c in run["impacts"][-2:]]
    assert found.peak_force == pytest.approx(max(last), rel=0.02)


def test_the_monodromy_of_the_mirrored_map_squares_its_multipliers():
    # Source: the full-period map of an orbit symmetric under y -> -y, t -> t + tau/2 is the half map
    # applied twice, so its multipliers are the squares of the half map's (floquet_multipliers).
    jac = np.array([[0.0, 2.0], [-0.5, 0.3]])
    half = np.linalg.eigvals(jac)
    np.testing.assert_allclose(np.sort_complex(orbit.floquet_multipliers(jac, mirror=True)),
                               np.sort_complex(half**2))
    np.testing.assert_allclose(np.sort_complex(np.linalg.eigvals(jac @ jac)), np.sort_complex(half**2))
