"""Tests of study.physics.oscillator.

"book" = Harrison & Nettleton, Principles of Engineering Mechanics, 2nd ed., ch. 8-9
(docs/model.md §8.3); equation numbers are the book's, as catalogued in
docs/textbook_examples.md (chapter 9 table: the copy has no numerical examples in ch. 9, so the
closed-form relations are tested symbolically and against scipy.integrate.solve_ivp).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from study.physics import oscillator as osc

# the parameter set used in docs/textbook_examples.md for the starred ch. 9 relations
M, K = 2.0, 800.0
WN = math.sqrt(K / M)


def _ivp(rhs, y0, t_eval, **kw):
    sol = solve_ivp(rhs, (0.0, t_eval[-1]), y0, t_eval=t_eval, rtol=1e-11, atol=1e-13,
                    method="DOP853", **kw)
    assert sol.success
    return sol.y


# --- free response, eq. 9.7, 9.18-9.26 ----------------------------------------------------------


@pytest.mark.parametrize("zeta", [0.0, 0.08, 0.7, 1.0, 1.0 + 1e-9, 1.6])
def test_free_response_matches_ivp(zeta):
    # eq. 9.18-9.22: x'' + 2 zeta wn x' + wn^2 x = 0, all damping regimes
    t = np.linspace(0.0, 0.5, 101)
    x0, v0 = 0.01, -0.3
    y = _ivp(lambda _, y: [y[1], -2 * zeta * WN * y[1] - WN**2 * y[0]], [x0, v0], t)
    r = osc.free_response(t, WN, zeta, x0, v0)
    assert np.max(np.abs(r.x - y[0])) < 1e-10
    assert np.max(np.abs(r.v - y[1])) < 1e-8


def test_free_response_eq_9_26():
    # eq. 9.26:
    # x = x0 e^(-zeta wn t)[cos wd t + zeta/sqrt(1-zeta^2) sin wd t]
    zeta, x0 = 0.08, 0.02
    wd = osc.damped_frequency(WN, zeta)
    t = np.linspace(0, 1, 57)
    expect = x0 * np.exp(-zeta * WN * t) * (np.cos(wd * t)
                                            + zeta / math.sqrt(1 - zeta**2) * np.sin(wd * t))
    assert np.allclose(osc.free_response(t, WN, zeta, x0).x, expect, rtol=0, atol=1e-15)


def test_undamped_free_response_eq_9_7():
    # eq. 9.7-9.8: y = Y cos wn t + (V/wn) sin wn t, amplitude C
    t = np.linspace(0, 1, 33)
    r = osc.free_response(t, WN, 0.0, 0.01, 0.5)
    assert np.allclose(r.x, 0.01 * np.cos(WN * t) + 0.5 / WN * np.sin(WN * t), atol=1e-15)
    assert np.max(np.abs(r.x)) <= math.hypot(0.01, 0.5 / WN) + 1e-15


def test_parameters_eq_9_4_9_21_9_23():
    # eq. 9.4 wn = sqrt(k/m); eq. 9.21 c_crit = 2 sqrt(km); eq. 9.23 wd = wn sqrt(1 - zeta^2)
    assert osc.natural_frequency(M, K) == pytest.approx(20.0, rel=1e-15)
    assert osc.damping_ratio(M, K, 2 * math.sqrt(K * M)) == pytest.approx(1.0, rel=1e-15)
    assert osc.damped_frequency(20.0, 0.6) == pytest.approx(16.0, rel=1e-15)
    with pytest.raises(ValueError, match="mass"):
        osc.natural_frequency(0.0, K)


@pytest.mark.parametrize("zeta", [0.01, 0.08, 0.3])
def test_logarithmic_decrement_eq_9_27(zeta):
    # eq. 9.27-9.28: ln(x_n/x_(n+1)) over one damped period
    delta = osc.logarithmic_decrement(zeta)
    wd = osc.damped_frequency(WN, zeta)
    t = np.array([0.3, 0.3 + 2 * math.pi / wd])
    x = osc.free_response(t, WN, zeta, 0.01, 0.2).x
    assert math.log(x[0] / x[1]) == pytest.approx(float(delta), rel=1e-12)
    assert float(delta) == pytest.approx(2 * math.pi * zeta, rel=zeta**2)  # small-zeta form
    # eq. 9.29: specific loss 1 - exp(-2 delta) ~ 2 delta
    assert 1 - math.exp(-2 * delta) == pytest.approx(2 * delta, rel=2 * delta)


# --- Coulomb damping, eq. 9.30 --------------------------------------------------------------------


def _coulomb_ivp(x0, d, t_end):
    """Piecewise integration of x'' + wn^2 x = -wn^2 d sign(x'), restarting at each v = 0."""
    ts = []
    t0, y = 0.0, np.array([x0, 0.0])
    while t0 < t_end:
        if abs(y[0]) <= d:
            break
        s = -np.sign(y[0])  # direction of the coming motion
        ev = lambda t, yy: yy[1]  # noqa: E731
        ev.terminal, ev.direction = True, -s
        sol = solve_ivp(lambda t, yy: [yy[1], -WN**2 * yy[0] - WN**2 * d * s], (t0, t_end), y,
                        events=ev, rtol=1e-11, atol=1e-13, dense_output=True, method="DOP853",
                        first_step=1e-6)
        ts.append((t0, sol.t[-1], sol.sol))
        t0, y = sol.t[-1], sol.y[:, -1]
    return ts, y


def test_coulomb_response_eq_9_30():
    # eq. 9.30: amplitude drops 2f/k per half cycle, period 2 pi/wn,
    # motion stops at a velocity reversal with |x| <= f/k
    x0, d = 0.01, 0.0012  # d = f/k [m]
    half = math.pi / WN
    n = np.arange(12)
    x_rev = osc.coulomb_free_response(n * half, WN, d, x0).x
    expect = np.array([(-1) ** j * max(x0 - 2 * j * d, 0) for j in n])
    n_stop = math.ceil((x0 - d) / (2 * d))  # = 4: amplitudes 10, 7.6, 5.2, 2.8, 0.4 mm
    assert n_stop == 4
    assert np.allclose(x_rev[: n_stop + 1], expect[: n_stop + 1], atol=1e-15)
    assert np.all(x_rev[n_stop:] == x_rev[n_stop]) and abs(x_rev[n_stop]) <= d
    # against piecewise solve_ivp
    segs, y_end = _coulomb_ivp(x0, d, 10 * half)
    assert len(segs) == n_stop
    assert y_end[0] == pytest.approx(x_rev[n_stop], abs=1e-11)
    for a, b, sol in segs:
        t = np.linspace(a, b, 20)
        assert np.allclose(osc.coulomb_free_response(t, WN, d, x0).x, sol(t)[0], atol=1e-11)
        assert np.allclose(osc.coulomb_free_response(t, WN, d, x0).v, sol(t)[1], atol=1e-9)


# --- forced responses, eq. 9.33-9.36, 9.46-9.47 ---------------------------------------------------


@pytest.mark.parametrize("zeta", [0.08, 1.0, 2.0])
def test_step_response_eq_9_33(zeta):
    # eq. 9.33: x/(P0/k) against solve_ivp of
    # x'' + 2 zeta wn x' + wn^2 x = wn^2
    t = np.linspace(0, 0.6, 61)
    y = _ivp(lambda _, y: [y[1], WN**2 - 2 * zeta * WN * y[1] - WN**2 * y[0]], [0.0, 0.0], t)
    r = osc.step_response(t, WN, zeta)
    assert np.max(np.abs(r.x - y[0])) < 1e-10
    assert np.max(np.abs(r.v - y[1])) < 1e-8


def test_step_overshoot_eq_9_34():
    # eq. 9.34: overshoot exp(-zeta pi/sqrt(1-zeta^2)) at wd t = pi
    zeta = 0.08
    wd = osc.damped_frequency(WN, zeta)
    r = osc.step_response(math.pi / wd, WN, zeta)
    assert float(r.x) - 1 == pytest.approx(math.exp(-zeta * math.pi / math.sqrt(1 - zeta**2)),
                                           rel=1e-13)
    assert abs(float(r.v)) < 1e-13


@pytest.mark.parametrize("zeta", [0.08, 0.5, 1.0])
def test_ramp_response_eq_9_36(zeta):
    # eq. 9.36; printed closed form for zeta < 1 and solve_ivp
    t = np.linspace(0, 0.6, 61)
    y = _ivp(lambda s, y: [y[1], WN**2 * s - 2 * zeta * WN * y[1] - WN**2 * y[0]], [0.0, 0.0], t)
    r = osc.ramp_response(t, WN, zeta)
    assert np.max(np.abs(r.x - y[0])) < 1e-11
    if zeta < 1:
        wd = WN * math.sqrt(1 - zeta**2)
        book = (np.exp(-zeta * WN * t) * (2 * zeta * np.cos(wd * t) - (1 - 2 * zeta**2)
                                          / math.sqrt(1 - zeta**2) * np.sin(wd * t))
                + WN * t - 2 * zeta) / WN
        assert np.allclose(r.x, book, atol=1e-15)


def test_dynamic_magnifier_and_phase_eq_9_46_9_47():
    # eq. 9.42-9.47 against the complex receptance and solve_ivp
    zeta = 0.08
    r = np.array([0.0, 0.5, 1.0, 1.5, 3.0])
    H = 1.0 / (1 - r**2 + 2j * zeta * r)
    assert np.allclose(osc.dynamic_magnifier(r, zeta), np.abs(H), rtol=1e-14)
    assert np.allclose(osc.phase_angle(r, zeta), -np.angle(H), atol=1e-14)
    assert osc.dynamic_magnifier(1.0, zeta) == pytest.approx(1 / (2 * zeta), rel=1e-14)
    assert osc.phase_angle(1.0, zeta) == pytest.approx(math.pi / 2, rel=1e-14)
    # started on the steady state x = (F0/k) beta cos(Omega t - phi), integration stays on it
    Om = 1.5 * WN
    beta, phi = float(osc.dynamic_magnifier(1.5, zeta)), float(osc.phase_angle(1.5, zeta))
    t = np.linspace(0, 1.0, 501)
    y = _ivp(lambda s, y: [y[1], WN**2 * math.cos(Om * s) - 2 * zeta * WN * y[1] - WN**2 * y[0]],
             [beta * math.cos(phi), beta * Om * math.sin(phi)], t)
    assert np.max(np.abs(y[0] - beta * np.cos(Om * t - phi))) < 1e-10


# --- event-driven flight: closed form between impacts ------------------------------------------

FLIGHT_CASES = {
    "underdamped_driven": osc.ImpactParams(1.0, 1.0, 0.1, 0.8, 1.3, 0.0, 0.5, 0.8),
    "overdamped_driven": osc.ImpactParams(1.0, 1.0, 3.0, 0.8, 0.7, 0.2, 0.5, 0.8),
    "critical": osc.ImpactParams(1.0, 4.0, 4.0, 0.5, 2.5, 0.0, 0.5, 0.8),
    "undamped_resonance": osc.ImpactParams(1.0, 1.0, 0.0, 0.3, 1.0, 0.1, 0.5, 0.8),
    "no_spring_gravity": osc.ImpactParams(0.5, 0.0, 0.0, 0.0, 0.0, 0.5 * 9.81, 0.0, 0.7),
    "no_spring_damped": osc.ImpactParams(0.5, 0.0, 0.4, 1.0, 3.0, 1.0, 0.0, 0.7),
}


def _rhs(p):
    def f(t, y):
        F = p.constant_force + p.force_amplitude * math.cos(p.forcing_frequency * t)
        return [y[1], (F - p.damping * y[1] - p.stiffness * y[0]) / p.mass]
    return f


@pytest.mark.parametrize("name", list(FLIGHT_CASES))
def test_flight_state_matches_ivp(name):
    # homogeneous (eq. 9.18-9.26) + particular (eq. 9.42-9.47) solution vs solve_ivp
    p = FLIGHT_CASES[name]
    t0, y0 = 0.7, [-0.2, 0.3]
    t = np.linspace(t0, t0 + 6.0, 61)
    sol = solve_ivp(_rhs(p), (t0, t[-1]), y0, t_eval=t, rtol=1e-11, atol=1e-13, method="DOP853")
    st = osc.flight_state(t, y0, p, t0)
    assert np.max(np.abs(st.x - sol.y[0])) < 1e-9
    assert np.max(np.abs(st.v - sol.y[1])) < 1e-9


def test_flight_state_rejects_earlier_time():
    with pytest.raises(ValueError, match="t0"):
        osc.flight_state(0.0, (0.0, 0.0), FLIGHT_CASES["critical"], 1.0)


@pytest.mark.parametrize("name", list(FLIGHT_CASES))
def test_next_impact_time_matches_ivp_event(name):
    # first root of x(t) - gap, from the wall moving away (just after an impact)
    p = FLIGHT_CASES[name]
    t0, y0 = 0.7, [p.gap, -0.4]
    ev = osc.next_impact_time(t0, y0, p, t_max=t0 + 40.0)
    hit = lambda t, y: y[0] - p.gap  # noqa: E731
    hit.terminal, hit.direction = True, 1
    sol = solve_ivp(_rhs(p), (t0 + 1e-9, t0 + 40.0), osc.flight_state(t0 + 1e-9, y0, p, t0),
                    events=hit, rtol=1e-12, atol=1e-14, method="DOP853")
    if sol.t_events[0].size == 0:
        assert ev.status == "no_impact" and math.isnan(ev.time)
    else:
        assert ev.status == "impact"
        assert ev.time == pytest.approx(sol.t_events[0][0], abs=1e-8)
        assert ev.velocity == pytest.approx(sol.y_events[0][0][1], abs=1e-8)


def test_next_impact_half_cycle_bounce():
    # undriven oscillator with the wall at its equilibrium (gap = 0): a bounce takes pi/wn,
    # eq. 9.7 / 9.9, and returns at the same speed
    p = osc.ImpactParams(M, K, 0.0, gap=0.0, restitution=1.0)
    ev = osc.next_impact_time(0.0, (0.0, -0.3), p, t_max=1.0)
    assert ev.time == pytest.approx(math.pi / WN, rel=1e-13)
    assert ev.velocity == pytest.approx(0.3, rel=1e-12)


def test_next_impact_grazing_not_skipped():
    # undamped free motion of amplitude A about 0: wall just inside the amplitude (grazing)
    p = osc.ImpactParams(1.0, 1.0, 0.0, gap=1.0 - 1e-9)
    ev = osc.next_impact_time(0.0, (0.0, 1.0), p, t_max=10.0, step=1.0)  # coarse step
    assert ev.status == "impact"
    assert ev.time == pytest.approx(math.asin(1.0 - 1e-9), abs=1e-7)
    miss = osc.next_impact_time(0.0, (0.0, 1.0), p._replace(gap=1.0 + 1e-9), t_max=10.0)
    assert miss.status == "no_impact"


def test_impact_velocity_after_uses_restitution():
    p = osc.ImpactParams(2.0, 1.0, restitution=0.6)
    assert osc.impact_velocity_after(1.5, p) == pytest.approx(-0.9, rel=1e-15)


# --- impact sequences: bouncing ball, chattering, sticking ------------------------------------

G = 9.81


@pytest.mark.parametrize("e", [0.0, 0.3, 0.5, 0.9])
def test_bouncing_ball_accumulation_time(e):
    # ball leaving a fixed floor at v0 (no spring, gravity towards the wall; x measured downwards):
    # flights 2 e^j v0/g, so impacts accumulate at 2 v0/g / (1 - e) and the ball sticks (ch. 8,
    # geometric series as in restitution.bounce_to_rest, Problem 8.1)
    v0 = 1.3
    p = osc.ImpactParams(0.2, 0.0, constant_force=0.2 * G, gap=0.0, restitution=e)
    h = osc.simulate_impacts(0.0, (0.0, -v0), p, t_end=100.0)
    assert h.status == "sticking", h.message
    assert h.accumulation_time == pytest.approx(2 * v0 / G / (1 - e), rel=1e-12)
    k = np.arange(min(len(h.times), 10))
    assert np.allclose(h.velocities[k], v0 * e**k, rtol=1e-12)  # approach speeds v0 e^k
    assert h.final_state == (0.0, 0.0)


def test_bouncing_ball_accumulation_matches_restitution_module():
    # dropped from rest at height h_d: accumulation = restitution.bounce_to_rest total time
    from study.physics.restitution import bounce_to_rest
    hd, e = 2.0, math.sqrt(0.75)  # Problem 8.1
    p = osc.ImpactParams(1.0, 0.0, constant_force=G, gap=0.0, restitution=e)
    h = osc.simulate_impacts(0.0, (-hd, 0.0), p, t_end=100.0)
    assert h.status == "sticking"
    assert h.accumulation_time == pytest.approx(float(bounce_to_rest(hd, e).total_time), rel=1e-12)


def test_elastic_half_cycle_bounces():
    # undriven, wall at the equilibrium (gap = 0), e = 1: impacts every pi/wn at the same speed
    p = osc.ImpactParams(M, K, 0.0, gap=0.0, restitution=1.0)
    h = osc.simulate_impacts(0.0, (0.0, -0.3), p, t_end=10.5 * math.pi / WN)
    assert h.status == "completed"
    assert np.allclose(h.times, np.arange(1, 11) * math.pi / WN, rtol=1e-12)
    assert np.allclose(h.velocities, 0.3, rtol=1e-12)


def test_damped_half_cycle_bounces():
    # gap = 0 with viscous damping and restitution: each half cycle takes pi/wd and the speed
    # falls by e exp(-zeta wn pi/wd) per bounce (eq. 9.26-9.27)
    zeta, e = 0.05, 0.8
    p = osc.ImpactParams(M, K, 2 * zeta * math.sqrt(K * M), gap=0.0, restitution=e)
    wd = float(osc.damped_frequency(WN, zeta))
    h = osc.simulate_impacts(0.0, (0.0, -0.3), p, t_end=5.5 * math.pi / wd)
    assert np.allclose(h.times, np.arange(1, 6) * math.pi / wd, rtol=1e-12)
    ratio = math.exp(-zeta * WN * math.pi / wd)
    assert np.allclose(h.velocities, 0.3 * ratio * (e * ratio) ** np.arange(5), rtol=1e-11)


def test_driven_preloaded_wall_sticks():
    # wall beyond the spring's equilibrium (gap < 0): the preload -k gap = 1 N exceeds the drive
    # amplitude 0.5 N, so low-restitution impacts chatter and the mass sticks
    p = osc.ImpactParams(1.0, 1.0, 0.0, 0.5, 3.0, 0.0, gap=-1.0, restitution=0.3)
    h = osc.simulate_impacts(0.0, (-1.0, -0.5), p, t_end=50.0)
    assert h.status == "sticking", h.message
    assert h.accumulation_time > h.times[-1]
    assert 1.0 - 0.5 * math.cos(3.0 * h.accumulation_time) > 0


def test_impact_cap_reports_not_converged():
    p = osc.ImpactParams(M, K, 0.0, gap=0.0, restitution=1.0)
    h = osc.simulate_impacts(0.0, (0.0, -0.3), p, t_end=1e6, max_impacts=7)
    assert h.status == "not_converged" and len(h.times) == 7 and "max_impacts" in h.message


# --- impact map and periodic orbits -------------------------------------------------------------

# m = k = 1, c = 0.05, F0 = 1, e = 0.8, wall at the equilibrium: the period-1 orbit is stable at
# Omega = 2.6 and has passed a period doubling at Omega = 2.8 (multiplier ~ -2.79).
STABLE = osc.ImpactParams(1.0, 1.0, 0.05, 1.0, 2.6, 0.0, 0.0, 0.8)
FLIPPED = STABLE._replace(forcing_frequency=2.8)


def _ivp_impacts(p, t0, x0, v0, n_impacts):
    """Reference: solve_ivp with a terminal event at x = gap, restarted with v -> -e v."""
    hit = lambda t, y: y[0] - p.gap  # noqa: E731
    hit.terminal, hit.direction = True, 1
    times, vels = [], []
    t, y = t0, [x0, v0]
    while len(times) < n_impacts:
        sol = solve_ivp(_rhs(p), (t, t + 200.0), y, events=hit, rtol=1e-12, atol=1e-14,
                        method="DOP853", first_step=1e-6)
        te, ye = sol.t_events[0][0], sol.y_events[0][0]
        times.append(te)
        vels.append(ye[1])
        # leave the wall a hair inside so the event does not re-trigger at the start
        t, y = te, [p.gap, -p.restitution * ye[1]]
        y = list(osc.flight_state(te + 1e-9, y, p, te))
        t = te + 1e-9
    return np.array(times), np.array(vels)


def test_periodic_orbit_verified_by_direct_simulation():
    orb = osc.periodic_orbit(STABLE, 1)
    assert orb.status == "periodic", orb.message
    assert np.all(np.abs(orb.multipliers) < 1)
    T = 2 * math.pi / STABLE.forcing_frequency
    assert orb.period == pytest.approx(T, rel=1e-15)
    # 30 forcing periods of solve_ivp with events, started on the orbit
    times, vels = _ivp_impacts(STABLE, orb.phase, STABLE.gap, -0.8 * orb.velocity, 30)
    assert np.max(np.abs(times - (orb.phase + T * np.arange(1, 31)))) < 1e-10  # measured 1.4e-13
    assert np.max(np.abs(vels - orb.velocity)) < 1e-10  # measured 2.9e-13
    # and by the event-driven closed form (no integration)
    h = osc.simulate_impacts(orb.phase, (STABLE.gap, -0.8 * orb.velocity), STABLE,
                             t_end=orb.phase + 30.5 * T)
    assert np.max(np.abs(h.times - (orb.phase + T * np.arange(1, 31)))) < 1e-10
    assert np.max(np.abs(h.velocities - orb.velocity)) < 1e-10


def test_stable_orbit_attracts():
    # a perturbed start converges to the orbit (the multipliers are inside the unit circle)
    orb = osc.periodic_orbit(STABLE, 1)
    T = orb.period
    h = osc.simulate_impacts(orb.phase + 0.05, (STABLE.gap, -0.8 * orb.velocity * 1.1), STABLE,
                             t_end=orb.phase + 80.5 * T)
    assert h.velocities[-1] == pytest.approx(orb.velocity, rel=1e-8)
    assert (h.times[-1] - orb.phase) / T == pytest.approx(round((h.times[-1] - orb.phase) / T),
                                                          abs=1e-8)


@pytest.mark.parametrize("p", [STABLE, FLIPPED])
def test_jacobian_analytic_vs_finite_difference(p):
    orb = osc.periodic_orbit(p, 1)
    t, v = orb.phase, orb.velocity
    J = np.empty((2, 2))
    for j, (dt, dv) in enumerate([(1e-6, 0.0), (0.0, 1e-6 * v)]):
        a = osc.impact_map(t + dt, v + dv, p)
        b = osc.impact_map(t - dt, v - dv, p)
        J[:, j] = [(a.time - b.time) / (2 * (dt + dv)), (a.velocity - b.velocity) / (2 * (dt + dv))]
    assert np.allclose(orb.jacobian, J, rtol=1e-6, atol=1e-7)
    # Liouville: det J = e^2 exp(-(c/m) nT) on a periodic orbit
    assert np.linalg.det(orb.jacobian) == pytest.approx(
        p.restitution**2 * math.exp(-p.damping / p.mass * orb.period), rel=1e-12)


def test_period_doubling_detected():
    orb = osc.periodic_orbit(FLIPPED, 1)
    assert orb.status == "period_doubling", orb.message
    mu = orb.multipliers[np.argmin(orb.multipliers.real)]
    assert abs(mu.imag) < 1e-12 and mu.real < -1
    # the impact map itself shows the flip: deviations alternate in sign and grow by ~|mu|
    t, v = orb.phase, orb.velocity * (1 + 1e-7)
    dev = []
    for _ in range(6):
        ev = osc.impact_map(t, v, FLIPPED)
        t, v = ev.time, ev.velocity
        dev.append(v - orb.velocity)
    dev = np.array(dev)
    assert np.all(np.sign(dev[1:]) == -np.sign(dev[:-1]))
    assert abs(dev[-1] / dev[-2]) == pytest.approx(abs(mu.real), rel=0.05)
    # the stable neighbour at Omega = 2.6: the flip lies between the two frequencies
    assert np.min(osc.periodic_orbit(STABLE, 1).multipliers.real) > -1


def test_no_orbit_reports_not_converged():
    # no force at all: nothing drives the mass back to the wall periodically
    p = STABLE._replace(force_amplitude=0.0, gap=0.5)
    orb = osc.periodic_orbit(p, 1)
    assert orb.status == "not_converged" and math.isnan(orb.velocity)


def test_invalid_arguments_raise():
    with pytest.raises(ValueError, match="forcing_frequency"):
        osc.periodic_orbits(STABLE._replace(forcing_frequency=0.0))
    with pytest.raises(ValueError, match="restitution"):
        osc.flight_state(1.0, (0.0, 0.0), STABLE._replace(restitution=1.2))
