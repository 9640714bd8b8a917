"""Event-driven integration (study.solvers.kernels.event_driven): exact flights, located onsets, RK4 through contact."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from study.physics import hertz
from study.solvers.kernels import event_driven as ev

MASS, STIFFNESS, CLEARANCE = 300.0, 3e9, 0.05  # modal mass [kg], Hertz K [N m^-3/2], c [m]


def _system(omega, damping=None, drive=0.0, rotary_speed=10.0, phi=((1.0,),), **kw):
    return ev.prepare(np.asarray(omega, float), damping, drive, rotary_speed, np.asarray(phi, float), MASS,
                      STIFFNESS, CLEARANCE, kw.pop("hysteresis", 0.0), kw.pop("speed", 1.0), **kw)


@pytest.mark.parametrize("q0,v0", [(0.0, 0.3), (0.01, -0.2)])
def test_undamped_driven_flight_is_the_closed_form(q0, v0):
    # x'' + w^2 x = f cos(W t): x = q0 cos wt + v0/w sin wt + f/(w^2 - W^2)(cos Wt - cos wt)
    # (the undamped forced response, e.g. Thomson, Theory of Vibration, sec. 3.1)
    w, W, f = 7.0, 10.0, 2.5
    system = _system([w], drive=f, rotary_speed=W)
    t = np.linspace(0.0, 3.0, 31)
    z = ev.flight_state(system, 0.0, [q0, v0], t)
    x = q0 * np.cos(w * t) + v0 / w * np.sin(w * t) + f / (w**2 - W**2) * (np.cos(W * t) - np.cos(w * t))
    xd = -q0 * w * np.sin(w * t) + v0 * np.cos(w * t) + f / (w**2 - W**2) * (-W * np.sin(W * t) + w * np.sin(w * t))
    np.testing.assert_allclose(z[:, 0], x, atol=1e-13)
    np.testing.assert_allclose(z[:, 1], xd, atol=1e-12)


def test_damped_coupled_flight_matches_a_converged_integration():
    # three modes coupled by a full damping matrix (like the projected mud damping), driven on mode 1
    omega = np.array([5.0, 21.0, 48.0])
    C = np.array([[0.4, 0.1, 0.05], [0.1, 0.5, 0.1], [0.05, 0.1, 0.6]])
    system = _system(omega, damping=C, drive=1.5, rotary_speed=9.0, phi=((1.0, 0.0, -1.0),))
    z0 = np.array([0.01, -0.02, 0.003, 0.1, 0.0, -0.05])
    A = np.block([[np.zeros((3, 3)), np.eye(3)], [-np.diag(omega**2), -C]])
    sol = solve_ivp(lambda t, z: A @ z + np.r_[0, 0, 0, 1.5 * np.cos(9.0 * t), 0, 0], (0.3, 4.3), z0,
                    method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True)
    t = np.linspace(0.3, 4.3, 17)
    np.testing.assert_allclose(ev.flight_state(system, 0.3, z0, t), sol.sol(t).T, atol=1e-9)


def test_undamped_drive_at_a_natural_frequency_is_refused():
    with pytest.raises(ValueError, match="undamped natural frequency"):
        _system([10.0], drive=1.0, rotary_speed=10.0)


def _free_run(system, z0, t1):
    active, chi, peak = np.zeros(1, bool), np.zeros(1), np.zeros(1)
    return ev.advance(system, 0.0, t1, z0, active, chi, peak), active


@pytest.mark.parametrize("amplitude", [2.0, 1.0 + 1e-7])
def test_onset_is_located_on_the_exact_flight(amplitude):
    # free oscillation y = A sin(w t + 0.3): first reaches c at w t = arcsin(c/A) - 0.3 (mod 2 pi). At
    # A = (1 + 1e-7) c the maximum overshoots the wall by 1e-7 c between two samples: a grazing contact.
    w = 40.0
    system = _system([w], rotary_speed=3.0)
    A = amplitude * CLEARANCE
    z0 = [A * np.sin(0.3), A * w * np.cos(0.3)]
    (z, events, outcome), active = _free_run(system, z0, 1.0)
    expected = (np.arcsin(1.0 / amplitude) - 0.3) / w
    assert outcome == ev.OK and events[0][0] == ev.ONSET
    assert events[0][2] == pytest.approx(expected, rel=1e-10, abs=1e-13)
    assert events[0][3] == pytest.approx(A * w * np.cos(np.arcsin(1.0 / amplitude)), rel=1e-6, abs=1e-9)


@pytest.mark.parametrize("steps,tol", [(100, 1e-5), (400, 2e-7)])
def test_elastic_contact_is_the_hertz_impact(steps, tol):
    # mass at the wall moving in at v0 (no spring to speak of): the elastic Hertz impact, paper eq. 8-12,
    # T_H = 2.94 alpha/v0 and F_max = K alpha^1.5 with alpha = (5 m v0^2 / 4K)^(2/5) (hertz.hertz_impact)
    v0 = 1.5
    system = _system([1e-3], rotary_speed=3.0, speed=v0, contact_steps=steps)
    (z, events, outcome), active = _free_run(system, [CLEARANCE, v0], 0.05)
    ref = hertz.hertz_impact(MASS, v0, STIFFNESS)
    onset, end = events[0], events[1]
    assert outcome == ev.OK and onset[0] == ev.ONSET and end[0] == ev.END and not active[0]
    assert end[2] - onset[2] == pytest.approx(float(ref.duration), rel=tol)
    assert end[3] == pytest.approx(v0, rel=tol)
    assert end[4] == pytest.approx(float(ref.max_force), rel=1e-3)  # peak sampled at the RK4 steps


def test_events_beyond_the_cap_stop_the_run(monkeypatch):
    monkeypatch.setattr(ev, "MAX_EVENTS", 3)
    system = _system([40.0], rotary_speed=3.0)
    (z, events, outcome), _ = _free_run(system, [0.0, 2 * CLEARANCE * 40.0], 1.0)
    assert outcome == ev.TOO_MANY_EVENTS and len(events) == 3
