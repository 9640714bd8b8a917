"""The time-domain method (study.solvers.methods.timedomain): modal span integrated through Hertz contact."""

from pathlib import Path

import numpy as np
import pytest

from study import config
from study.benchmarks import time_domain as time_domain_bench
from study.physics import contact, hertz
from study.solvers.methods import sdof
from study.solvers.methods.periodic import make_scene
from study.solvers.methods import timedomain as td
from study.solvers.model.options import INTEGRATORS

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def point():
    return config.load(ROOT / "configs" / "paper.toml").point()


def _single_impact(point, integrator, v0=1.0, e=1.0, **kw):
    """One mode, no drive, no damping; midspan starting at the wall (q1 = c) moving out at v0."""
    c = (point["hole_diameter"] - point["outer_diameter"]) / 2
    inputs = {**point, "time_modes": 1, "time_damping": "none", "drive_amplitude": 0.0, "restitution": e,
              "initial_state": ([c], [v0]), "time_revolutions": 1, "time_check_periodic": False,
              "time_integrator": integrator, **kw}
    run = td.simulate(inputs)
    return run, run["model"]


@pytest.mark.parametrize("integrator,tol", [("event", 0.001), ("explicit", 0.01), ("implicit", 0.005)])
def test_single_elastic_impact_is_the_hertz_impact_of_the_modal_mass(point, integrator, tol):
    # y = q1 sin(pi x/L): midspan deflection = q1; kinetic energy (1/2) M int ydot^2 dx = (1/2)(M L/2) q1dot^2;
    # a point force F at midspan does work F dq1. So (M L/2) q1'' + k q1 = -K (q1 - c)^(3/2): the Hertz
    # impact (paper eq. 8-12) of the mass M L/2 at v0, up to the spring force k c (< 1e-4 of the peak
    # at the default 105 m span).
    run, model = _single_impact(point, integrator)
    assert model.mass == pytest.approx(make_scene(point).props["mass_per_length"] * point["span_length"] / 2)
    ref = hertz.hertz_impact(model.mass, 1.0, model.stiffness)
    first = run["impacts"][0]
    assert first["approach"] == pytest.approx(1.0, rel=1e-6)
    assert first["duration"] == pytest.approx(float(ref.duration), rel=tol)
    assert first["peak"] == pytest.approx(float(ref.max_force), rel=tol)
    assert first["rebound"] == pytest.approx(1.0, rel=tol)


@pytest.mark.parametrize("integrator,tol", [("event", 1e-5), ("explicit", 2e-3), ("implicit", 1e-4)])
def test_energy_is_conserved_over_elastic_impacts(point, integrator, tol):
    inputs = {**point, "span_length": 10.0, "time_modes": 3, "time_damping": "none", "drive_amplitude": 0.0,
              "restitution": 1.0, "time_revolutions": 2, "time_check_periodic": False,
              "time_integrator": integrator}
    run = td.simulate(inputs)
    assert run["verdict"] == "not_periodic" and len(run["impacts"]) >= 4
    E = run["energies"]
    assert np.max(np.abs(E - E[0])) / E[0] < tol
    r = td.solve(inputs)
    assert r.values["energy_drift"] < tol and r.values["impacts_per_revolution"] >= 2


@pytest.mark.parametrize("model,e,tol", [
    # oscillator's tests measured the closed forms: LN +0.37 % at e = 0.95, +1.5 % at 0.9; HC +1.0 % at 0.9
    ("lankarani_nikravesh", 0.95, 0.01), ("lankarani_nikravesh", 0.9, 0.02), ("hunt_crossley", 0.9, 0.015),
    # the calibrated h = chi v0 is exact at any e
    ("calibrated", 0.5, 0.003), ("calibrated", 0.9, 0.003)])
def test_hunt_crossley_contact_reproduces_restitution(point, model, e, tol):
    run, m = _single_impact(point, "implicit", e=e, contact_damping=model)
    rec = run["impacts"][0]
    achieved = rec["rebound"] / rec["approach"]
    assert achieved == pytest.approx(e, rel=tol)
    # the same impact as contact.hertz_wall_impact of the modal mass (up to the spring force k c)
    alone = contact.hertz_wall_impact(m.mass, m.stiffness, 1.0, rec["hysteresis"])
    assert achieved == pytest.approx(alone.restitution, rel=2e-3)
    assert rec["duration"] == pytest.approx(alone.duration, rel=2e-3)
    # the calibration is scale-free: chi v0 fixes e whatever m and K
    h = contact.calibrated_hysteresis(e)
    assert contact.hertz_wall_impact(50.0, 3e9, 2.5, h / 2.5).restitution == pytest.approx(e, rel=1e-6)


def _driven(point, **kw):
    # short stiff span: omega_1 = 15.4 rad/s against Omega = 31.4 rad/s; sdof's stable alternating orbit
    return {**point, "span_length": 10.0, "time_modes": 1, **kw}


def test_explicit_step_above_the_contact_limit_fails(point):
    inputs = _driven(point, time_revolutions=3, time_check_periodic=False)
    lim = td.stability_limit(td.build_model(inputs), point["rotary_speed"] * 0.053975)["step_limit"]
    inputs["time_integrator"] = "explicit"
    bad = td.solve({**inputs, "time_step": 3 * lim})
    assert bad.status == "failed" and td.STEP_FAILURE in bad.message
    ok = td.simulate({**inputs, "time_step": 0.1 * lim})
    imp = td.simulate({**inputs, "time_integrator": "implicit"})
    assert ok["verdict"] == imp["verdict"] == "not_periodic"
    assert len(ok["impacts"]) == len(imp["impacts"]) == 6
    va = np.array([r["approach"] for r in ok["impacts"]])
    vb = np.array([r["approach"] for r in imp["impacts"]])
    np.testing.assert_allclose(va, vb, rtol=5e-3)


@pytest.mark.parametrize("integrator", INTEGRATORS)
def test_driven_damped_span_settles_to_the_sdof_orbit(point, integrator):
    inputs = _driven(point, time_integrator=integrator)
    r = td.solve(inputs)
    # one mode cannot carry the stresses of a 0.9-ms contact (the first mode left out is not quasi-static
    # over it): the event-driven run, which samples them, says so and is not ok; the orbit is still compared
    assert r.status == ("not_converged" if integrator == "event" else "ok"), r.message
    if integrator == "event":
        assert "no stresses: the 1 modes do not resolve the 0.9" in r.message and "max_normal_stress" not in r.values
    assert r.values["period_revolutions"] == 1 and r.values["impacts_per_revolution"] == 2
    ref = sdof.solve(inputs)
    assert ref.status == "ok"
    # Newton's rigid-wall law vs the compliant Hertz wall: the contact lasts ~0.9 ms of the 100 ms
    # half-period, during which the drive, spring and damping keep acting, and the wall is met
    # ~0.5 mm further out; both shift the orbit by well under 1 % (0.4 % found). 2 % allows for
    # the Verlet step (0.1 % against implicit).
    assert r.values["impact_velocity"] == pytest.approx(ref.values["impact_velocity"], rel=0.02)
    assert r.values["achieved_restitution"] == pytest.approx(point["restitution"], rel=0.02)


def test_accumulating_contacts_are_reported_as_chattering(point, monkeypatch):
    # source: the status table (result.STATUS "chattering") - a run that meets more contact onsets and
    # ends in one revolution than event_driven.MAX_EVENTS allows is stopped and flagged as chatter, not
    # as a numerical failure. The cap is lowered to 3 so that the two impacts per revolution of the
    # driven span reach it in its second revolution.
    from study.solvers.kernels import event_driven
    monkeypatch.setattr(event_driven, "MAX_EVENTS", 3)
    r = td.solve(_driven(point, time_integrator="event", time_revolutions=4))
    assert r.status == "chattering"
    assert "more than 3 contact onsets and ends" in r.message and "accumulate" in r.message
    monkeypatch.undo()
    assert td.solve(_driven(point, time_integrator="event", time_revolutions=4)).status != "chattering"


def test_without_span_is_incomplete(point):
    r = td.solve({**point, "span_length": None})
    assert r.status == "incomplete" and r.method == "time-domain"


def test_event_driven_matches_converged_implicit_with_modes_and_contact_points(point):
    # three modes, contact at midspan and at the quarter points, mud damping and drive: the event-driven
    # run (exact flights, RK4 through contact) against LSODA at rtol 1e-11 on the same model
    inputs = _driven(point, time_modes=3, contact_points=(0.25, 0.5, 0.75), time_revolutions=3,
                     time_check_periodic=False)
    ev = td.simulate({**inputs, "time_integrator": "event", "contact_steps": 800})
    ref = td.simulate({**inputs, "time_integrator": "implicit", "time_rtol": 1e-11, "time_atol": 1e-13})
    assert ev["verdict"] == ref["verdict"] == "not_periodic"
    # the quarter points move together (only the symmetric modes are driven): order simultaneous onsets
    ev_imp, ref_imp = (sorted(r["impacts"], key=lambda i: (round(i["start"], 6), i["point"])) for r in (ev, ref))
    assert [r["point"] for r in ev_imp] == [r["point"] for r in ref_imp]
    assert len(ev_imp) >= 6 and {r["point"] for r in ev_imp} == {0, 1, 2}
    m = ev["model"]
    scale = np.r_[np.full(3, m.clearance), np.full(3, m.rotary_speed * m.clearance)]
    assert np.max(np.abs(np.concatenate(ev["final_state"]) - np.concatenate(ref["final_state"])) / scale) < 1e-5
    for a, b in zip(ev_imp, ref_imp):
        # measured at 800 RK4 steps per contact: 5e-9 s, 4e-7, 3e-7 (1.5e-7 s, 1.3e-5, 1e-5 at 200)
        assert a["start"] == pytest.approx(b["start"], abs=2e-8)
        assert a["approach"] == pytest.approx(b["approach"], rel=2e-6)
        assert a["rebound"] == pytest.approx(b["rebound"], rel=2e-6)


@pytest.mark.parametrize("damping,expected", [("linearised", "event"), ("none", "event"), ("drag", "explicit")])
def test_auto_integrator_is_event_driven_unless_drag(point, damping, expected):
    run = td.simulate(_driven(point, time_damping=damping, time_revolutions=1, time_check_periodic=False))
    assert run["integrator"] == expected and run["verdict"] == "not_periodic"
    forced = td.simulate(_driven(point, time_damping="drag", time_integrator="event", time_revolutions=1))
    assert forced["verdict"] == "failed" and "linear damping" in forced["failure"]


def test_benchmark_compares_errors_against_each_models_converged_run(point):
    rows = time_domain_bench.benchmark(_driven(point), revolutions=1, repeat=1, contact_steps=(25, 400), penalty_rtols=(1e-4,))
    names = [r["name"] for r in rows]
    assert names == ["event", "event", "explicit", "implicit", "penalty_rk45"]
    assert all(r["wall_time"] > 0 and r["error"] >= 0 for r in rows)
    assert rows[1]["error"] < rows[0]["error"]  # more RK4 steps per contact, smaller error
    assert rows[0]["impacts"] == rows[2]["impacts"] == rows[3]["impacts"] >= 1
    (ref, best, ratio), = time_domain_bench.equal_accuracy_speedups(rows)
    assert best is None or (best["error"] <= ref["error"] and ratio == ref["wall_time"] / best["wall_time"])


def test_explicit_fails_near_its_limit_while_event_driven_converges(point):
    rows = time_domain_bench.step_stability(_driven(point), revolutions=2, fractions=(0.1, 2.0), contact_steps=(10, 40, 160))
    explicit = [r for r in rows if r["name"] == "explicit"]
    event = [r for r in rows if r["name"] == "event"]
    assert explicit[0]["verdict"] != "failed" and explicit[1]["verdict"] == "failed"
    assert explicit[1]["step_ratio"] == pytest.approx(2.0, rel=0.01)
    errors = [r["error"] for r in event]
    # RK4 through a Hertz contact converges at about the 2.4th order here (contact force ~ delta^1.5)
    assert errors[0] > 8 * errors[1] > 64 * errors[2] and errors[2] < 1e-6


def test_stresses_of_the_settled_motion_converge_with_the_modes(point):
    # Source: convergence. The quasi-static correction (study.solvers.kernels.trajectory) carries the modes
    # above N statically, so the largest normal stress and deflection of the settled motion at a
    # 20 m span change by well under 1 % from 5 to 11 modes.
    runs = [td.solve({**point, "span_length": 20.0, "time_modes": n}) for n in (5, 11)]
    for r in runs:
        assert "stresses over the" in r.message
        assert r.values["max_normal_stress"] > abs(point["axial_tension"]) / make_scene(point).props["steel_area"]
    for name in ("max_normal_stress", "max_deflection", "alternating_bending_stress"):
        assert runs[0].values[name] == pytest.approx(runs[1].values[name], rel=0.01), name


def test_stresses_need_the_event_driven_integrator(point):
    r = td.solve({**point, "span_length": 20.0, "time_integrator": "explicit", "time_revolutions": 2})
    assert "max_normal_stress" not in r.values
    assert "no stresses: they are sampled from the event-driven integrator only" in r.message


def test_quadratic_drag_decays_the_free_first_mode_as_averaging_predicts(point):
    # Source: closed form. One mode q sin(pi x/L) under the drag D |ydot| ydot per length: the modal
    # force is D |qdot| qdot int_0^L sin^3(pi x/L) dx = c2 |qdot| qdot with c2 = 4 D L/(3 pi). For light
    # damping, averaging over a cycle of amplitude A (energy (1/2) m omega^2 A^2, loss (8/3) c2 omega^2 A^3
    # per cycle) gives dA/dt = -(4/(3 pi)) (c2/m) omega A^2, i.e. 1/A(t) = 1/A0 + (4/(3 pi)) (c2/m) omega t.
    span, a0 = 20.0, 0.002  # amplitude well inside the clearance: no contact
    inputs = {**point, "span_length": span, "time_modes": 1, "time_damping": "drag", "drive_amplitude": 0.0,
              "time_integrator": "explicit", "time_step": 2e-3, "time_check_periodic": False, "time_revolutions": 60}
    model = td.build_model(inputs)  # a 2-ms step: omega dt = 0.01 (no contact, so no contact step limit)
    omega, m = model.omega[0], model.mass
    run = td.simulate({**inputs, "initial_state": ([0.0], [a0 * omega])}, model)
    assert run["verdict"] != "failed" and not run["impacts"]
    c2 = 4.0 * make_scene(point).props["drag_coefficient_per_length"] * span / (3 * np.pi)
    t = np.arange(len(run["states"])) * model.period
    amplitude = np.sqrt(2.0 * run["energies"] / (m * omega**2))
    predicted = 1.0 / (1.0 / a0 + 4.0 / (3 * np.pi) * c2 / m * omega * t)
    assert amplitude[-1] < 0.9 * a0  # the drag has visibly acted (over 10 % of the amplitude)
    assert np.max(np.abs(amplitude / predicted - 1.0)) < 0.01


@pytest.mark.parametrize("span", [20.0, 105.0])
def test_a_settled_run_reports_the_floquet_multiplier_it_converged_with(paper_inputs, span):
    # Independent check: the largest Floquet multiplier of the settled orbit (shooting, study.solvers.kernels.orbit)
    # is the rate at which the run's own revolution-to-revolution change shrinks once it is near the
    # orbit (log-linear fit over revolutions 20-49 of a run that does not stop when periodic).
    r = td.solve({**paper_inputs, "span_length": span})
    mu = r.values["max_floquet_multiplier"]
    assert 0 < mu < 1 and f"stable: largest Floquet multiplier {mu:.4g}" in r.message
    run = td.simulate({**paper_inputs, "span_length": span, "time_check_periodic": False,
                               "time_revolutions": 50})
    model = run["model"]
    scale = model.state_scale()
    change = np.linalg.norm(np.diff(run["states"], axis=0) / scale, axis=1)
    revolution = np.arange(20, 50)
    rate = np.exp(np.polyfit(revolution, np.log(change[revolution]), 1)[0])  # measured 0.757 and 0.791
    assert rate == pytest.approx(mu, abs=0.03)


def test_solve_reads_its_options_from_the_inputs_once(point, monkeypatch):
    # issue 35: the method's options are built once, at solve, and passed down to simulate, build_model and
    # initial_state (each read them from the inputs again before: four builds a point)
    builds = []
    read = td.TimeDomainOptions.from_inputs
    monkeypatch.setattr(td.TimeDomainOptions, "from_inputs",
                        classmethod(lambda cls, inputs: builds.append(cls) or read(inputs)))
    result = td.solve({**point, "span_length": 10.0, "time_revolutions": 1, "time_check_periodic": False})
    assert result.values["revolutions_simulated"] >= 1 and builds == [td.TimeDomainOptions]
