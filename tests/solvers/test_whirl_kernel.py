"""Tests of the compiled integrator of the reference model (study.solvers.whirl_kernel).

The model's physics checks (Jeffcott, rolling whirl, energy, the event-driven time domain, scipy on the same
equations) are in test_reference.py; here the integrator itself: an impact on a linear wall against the
piecewise-linear oscillator in closed form, the onset located within its tolerance, its work counted, and the
Hunt–Crossley damping set at an onset from the approach speed, down to ONSET_SPEED_FLOOR.
"""

import numpy as np
import pytest

from study.solvers import reference, whirl_kernel


def _one_mode_on_a_linear_wall(base):
    """One mode in one plane, touching at midspan (φ = 1) a linear spring without dashpot (penalty law, e = 1),
    nothing else acting: a piecewise-linear oscillator."""
    inputs = {**base, "reference_modes": 1, "contact_points": [0.5], "contact_kinds": [0], "friction": 0.0,
              "eccentricity": 0.0, "reference_damping": "none", "contact_law": "penalty", "restitution": 1.0}
    model = reference.build_model(inputs)
    assert model.penalty_damping[0] == 0.0 and model.phi[0, 0] == pytest.approx(1.0)
    return model


def _closed_form_cycle(model, v0):
    """Out from the centre at v0, onto the wall, back: (time to the wall, contact time, peak force).

    Flight q = (v0/ω) sin ωt reaches c at t1 = asin(ωc/v0)/ω with speed v1 = √(v0² − ω²c²); in contact
    q̈ = −ω²q − (k/m)(q − c): a harmonic motion about q_e = (k/m)c/Ω² at Ω² = ω² + k/m, which leaves the wall
    after 2(π − ψ)/Ω, ψ = atan2(v1/Ω, c − q_e), at −v1 (Shaw & Holmes 1983, J. Sound Vib. 90, 129–155,
    doi:10.1016/0022-460X(83)90407-8: the flight and contact solutions of the piecewise-linear oscillator)."""
    om, c, k, m = model.omega[0], model.clearance[0], model.penalty_stiffness[0], model.mass
    t1 = np.arcsin(om * c / v0) / om
    v1 = np.sqrt(v0**2 - (om * c) ** 2)
    big = np.sqrt(om**2 + k / m)
    qe = k / m * c / big**2
    psi = np.arctan2(v1 / big, c - qe)
    amplitude = np.hypot(c - qe, v1 / big)
    return t1, 2.0 * (np.pi - psi) / big, k * (qe + amplitude - c)


@pytest.mark.parametrize("rtol", [1e-6, 1e-9])
def test_an_impact_on_a_linear_wall_is_the_closed_form_cycle(paper_inputs, rtol):
    # after flight, contact and the flight back the mode is at the centre again at -v0 (closed form above), to
    # 1e-5 of c and Ωc as the planar impacts of test_reference against the event-driven time domain; at rtol 1e-9
    # the onset tolerance (1e-6 c) is the floor. (The kernel before the located contact ends and PI control:
    # 4.8e-4 c at rtol 1e-6, 2.6e-6 c at 1e-9; with them 9e-7 c and 2.5e-6 c.)
    model = _one_mode_on_a_linear_wall(paper_inputs)
    c, om = model.clearance[0], model.rotary_speed
    v0 = 3.0 * model.omega[0] * c
    t1, contact, peak = _closed_form_cycle(model, v0)
    z0 = np.zeros(4 + 4)
    z0[2] = v0
    run = reference.Integrator(model, rtol, z0)
    window = run.run(2 * t1 + contact)
    tolerance = 1e-5
    assert run.outcome == whirl_kernel.OK
    assert int(window.onsets[0]) == 1
    assert abs(run.z[0]) / c < tolerance
    assert abs(run.z[2] + v0) / (om * c) < tolerance
    assert np.all(run.z[[1, 3]] == 0.0)  # it stays in its plane
    assert window.peak[0] == pytest.approx(peak, rel=1e-2)  # the largest force at a step's end
    # both ends of the contact located: its length (4e-4 measured; before, only to within the steps in it)
    assert window.contact_time[0] == pytest.approx(contact, rel=1e-3)
    # every evaluation counted: the first, six per attempted step, one where the contact opened
    work = run.work
    attempts = work[whirl_kernel.S_ACCEPTED] + work[whirl_kernel.S_ERROR_REJECTED] + work[whirl_kernel.S_SWITCH_REDONE]
    assert work[whirl_kernel.S_RHS] == 1 + 6 * attempts + 1
    assert work[whirl_kernel.S_ACCEPTED] == run.steps


def test_the_onset_is_located_within_its_tolerance(paper_inputs):
    # stopped inside the contact, the time in contact dates the onset: within ONSET_TOLERANCE c of the wall, at the
    # closed-form approach speed, from the closed-form time (above)
    model = _one_mode_on_a_linear_wall(paper_inputs)
    c = model.clearance[0]
    v0 = 3.0 * model.omega[0] * c
    t1, contact, _ = _closed_form_cycle(model, v0)
    v1 = np.sqrt(v0**2 - (model.omega[0] * c) ** 2)
    z0 = np.zeros(8)
    z0[2] = v0
    run = reference.Integrator(model, 1e-6, z0)
    run.h = 0.5 * t1  # a first step that would carry the point well past the wall
    end = t1 + 0.1 * contact
    window = run.run(end)
    assert window.onsets[0] == 1 and run.active[0]
    onset = end - window.contact_time[0]
    assert abs(onset - t1) <= 2 * whirl_kernel.ONSET_TOLERANCE * c / v1


def _one_mode_hertz(base, **extra):
    """One mode in one plane touching at midspan, Hertz contact with e = 0.5, nothing else acting."""
    return reference.build_model({**base, "reference_modes": 1, "contact_points": [0.5], "contact_kinds": [0],
                                  "friction": 0.0, "eccentricity": 0.0, "reference_damping": "none",
                                  "restitution": 0.5, **extra})


def test_hunt_crossley_damping_is_set_from_the_approach_speed(paper_inputs):
    # χ = h(e)/v1 (Hunt & Crossley 1975, doi:10.1115/1.3423596, with the calibrated h(e)) at the closed-form
    # approach speed v1 = √(v0² − ω²c²) of the free flight (as in _closed_form_cycle)
    from study.solvers.timedomain import calibrated_hysteresis

    model = _one_mode_hertz(paper_inputs)
    om, c = model.omega[0], model.clearance[0]
    v0 = np.hypot(om * c, 3.0 * om * c)
    t1 = np.arcsin(om * c / v0) / om
    z0 = np.zeros(8)
    z0[2] = v0
    run = reference.Integrator(model, 1e-9, z0)
    run.run(t1 * (1 + 1e-3))
    assert run.active[0]
    assert run.chi[0] == pytest.approx(calibrated_hysteresis(0.5) / (3.0 * om * c), rel=1e-4)


def test_a_contact_settling_at_a_vanishing_speed_gets_the_damping_of_the_floor(paper_inputs):
    # laid 1e-10 c off the wall under a side load that sags it to twice the clearance: it reaches the wall at
    # √(2 a 1e-10 c) (about 1e-6 m/s, a = s - ω²c), far below ONSET_SPEED_FLOOR, and takes that floor's χ
    from study.solvers.timedomain import calibrated_hysteresis

    unit = _one_mode_hertz(paper_inputs, side_load=1.0)
    om, c = unit.omega[0], unit.clearance[0]
    model = _one_mode_hertz(paper_inputs, side_load=2.0 * om**2 * c / unit.side[0])
    a = model.side[0] - om**2 * c
    assert np.sqrt(2 * a * 1e-10 * c) < 1e-2 * whirl_kernel.ONSET_SPEED_FLOOR
    z0 = np.zeros(8)
    z0[0] = c * (1 - 1e-10)
    run = reference.Integrator(model, 1e-9, z0)
    run.run(0.01 / om)
    assert run.active[0]
    assert run.chi[0] == pytest.approx(calibrated_hysteresis(0.5) / whirl_kernel.ONSET_SPEED_FLOOR, rel=1e-12)
