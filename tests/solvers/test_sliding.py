"""The pipe lying on the wall, sliding (study.solvers.methods.sliding): its rest against closed forms, the whirl about it
against the energy balance and the reference model's own equations, and where it does not answer."""

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from study import config
from study.workflow.grid import Grid
from study.solvers.methods import reference, sliding
from study.solvers import solve_point

ROOT = Path(__file__).resolve().parents[2]
#: The figures of these tests are the aligned pipe joints' eccentricities in a three-joint section (the default
#: study turns them 90° in four joints, docs/reference_model.md §1; the sliding state's answer depends on the turn).
ALIGNED = {"pipe.eccentricity_turn": "aligned", "contact.section_length": "93 ft"}


def _default(rpm: float, klbf: float, ppg: float = 9.0, flow: float = 0.0, **extra) -> dict:
    point = config.load(ROOT / "configs" / "default.toml", {
        "load.rotary_speed": f"{rpm} rpm", "load.axial_tension": f"{klbf * 1000} lbf", "impact.restitution": 0.3,
        "mud.density": f"{ppg} ppg", "mud.flow_velocity": f"{flow} ft/s", **ALIGNED}).point()
    return {**point, **extra}


# The rest on the wall against the closed forms (the continuous beam-column on the joints, the friction angle):
# tests/solvers/test_well.py.


def _energy(model, window):
    """(work of the eccentric load and the contacts, the quadratic drag's dissipation) over the revolution [J]."""
    N = model.n_modes
    t, v = window.times, window.states[:, 2 * N:4 * N]
    load = np.concatenate((np.outer(np.cos(model.rotary_speed * t), model.eccentric),
                           np.outer(np.sin(model.rotary_speed * t), model.eccentric)), axis=1) * model.mass
    contact = np.concatenate((window.forces[:, :, 0] @ model.phi, window.forces[:, :, 1] @ model.phi), axis=1)
    work_in = np.trapezoid(np.sum((load + contact) * v, axis=1), t)
    speed = np.hypot(v[:, :N] @ model.drag_shapes.T, v[:, N:] @ model.drag_shapes.T)  # |u̇| at the Gauss points
    return work_in, np.trapezoid(model.drag * (speed**3) @ model.drag_weights, t)


def test_whirl_about_the_rest_balances_its_energy():
    # over a revolution of the synchronous motion the work of the eccentric load and of the contacts (friction, the
    # linearised contact) equals what the mud's quadratic drag D|u̇|u̇ dissipates: the drag was replaced by the
    # viscous drag of equal dissipation on this motion (the equivalent linearisation), so the balance closes
    state = sliding.steady_state(_default(100, 5))
    model, rested, whirled = state["model"], state["rest"], state["whirl"]
    first = {**whirled, "second": {h: np.zeros_like(a) for h, a in whirled["second"].items()},
             "shift": {h: np.zeros_like(d) for h, d in whirled["shift"].items()}}
    work_in, dissipated = _energy(model, sliding.revolution(model, rested, first)[0])
    assert work_in == pytest.approx(dissipated, rel=1e-6)
    assert dissipated > 0 and whirled["change"] < 1e-10
    # the second-order motion on the wall's arc (0 and 2Ω) takes the drag at the synchronous motion's rate: the
    # whole motion's balance is off by its share only
    work_in, dissipated = _energy(model, state["window"])
    assert work_in == pytest.approx(dissipated, rel=2e-3)


def test_with_viscous_damping_the_reference_model_settles_on_it():
    # with the bending modes damped viscously (ζ = 5 %) the reference model's start-up ringing dies within its first
    # revolutions, so after 120 it is near the steady state; the sliding state of the same equations is that state
    # (measured on the periodic section: peak force 1.8 %, max normal stress 0.19 %, alternating stress 1.1 % apart,
    # the same at 40 revolutions: the string's rigid translation has ω = 0 and no modal damping, friction and drag
    # alone settle it; on the pinned section 0.27 % and 0.02-0.09 %)
    inputs = {**_default(50, 10, ppg=12.0, flow=7.4), "reference_damping": "viscous", "damping_ratio": 0.05}
    mine = sliding.solve(inputs)
    theirs = reference.solve({**inputs, "reference_revolutions": 120})
    assert mine.status == "ok" and theirs.values["whirl_class"] == reference.WHIRL_CLASSES["sliding"]
    for name, tolerance in (("peak_contact_force", 0.025), ("max_normal_stress", 0.004),
                            ("alternating_bending_stress", 0.015)):
        assert mine.values[name] == pytest.approx(theirs.values[name], rel=tolerance), name


def test_the_arc_gives_the_contact_force_its_second_harmonic():
    # a joint sliding on its wall moves on an arc, inside the linear motion's tangent by r Δφ²/2: the force on it
    # has a component at 2Ω (measured in the reference model at 480 revolutions on the pinned section: 2.69 N beside
    # 16.9 N at Ω; on the periodic section's joint at 0 the sliding state gives 2.14 N beside 15.0 N)
    state = sliding.steady_state(_default(50, 10, ppg=12.0, flow=7.4))
    force = state["window"].forces[:-1, 0, 2]  # the joint at 0
    spectrum = np.abs(np.fft.rfft(force)) / force.size * 2
    assert spectrum[2] / spectrum[1] == pytest.approx(2.69 / 16.87, rel=0.15)


@pytest.mark.parametrize("inputs, why", [
    pytest.param(dict(rpm=300, klbf=30, inclination=0.0), "does not reach the wall", id="vertical hole"),
    pytest.param(dict(rpm=200, klbf=5), "contact would open", id="200 rpm, 5 klbf: the eccentric load lifts it"),
])
def test_where_the_pipe_does_not_lie_on_the_wall_it_does_not_answer(inputs, why):
    extra = {k: v for k, v in inputs.items() if k not in ("rpm", "klbf")}
    result = sliding.solve(_default(inputs["rpm"], inputs["klbf"], **extra))
    assert result.status == "out_of_scope" and why in result.message


def test_in_the_default_study_it_answers_the_slow_points_lying_on_the_wall():
    # 50 rpm, 10 klbf (the slowest point of the last default sweep: 10.8 s in the reference model, not settled)
    result = solve_point(_default(50, 10, ppg=12.0, flow=7.4), "auto")
    assert result.status == "ok" and result.method == "sliding"
    assert list(result.extras["methods_tried"]) == ["free-whirl", "sliding"]
    assert result.values["regime"] == 6 and result.values["contact_fraction"] == 1.0
    assert result.error_estimate < 0.01


# A panel of the default study's grid (configs/default.toml read aligned in three joints, Grid.point(i)) held to the outputs of the periodic
# section (issue 33; the pinned section's of commit 56f73e1 before it): a change of the method must not change a
# value, a status or a message unless it means to. Literals printed by sliding.solve at these points.
PANEL = [
    pytest.param(2, "ok", 0.002849680883143481,
                 (242.15544931109602, 10573463.466846377, 2573028.858702729, 0.03236154476251625, 86068.86536359845),
                 "lying on the wall at 0 m, 9.45 m, 18.9 m, sliding: 225.2 N at rest, ±15.2 N as the eccentric load "
                 "turns; linearisation 0.0028 (contact 0.00019, drag 1.5e-05, orders left out 0.0026), 48 against 24 modes "
                 "4.9e-06, drag settled in 4 iterations", id="2: 50 rpm, 5 klbf, e 0.3, 12 ppg, no flow: ok"),
    pytest.param(40, "ok", 0.002248083653441276,
                 (274.74519917070546, 18654103.44392449, 2636335.5034396113, 0.032406975493652894, 96988.4078346634),
                 "lying on the wall at 0 m, 9.45 m, 18.9 m, sliding: 237.9 N at rest, ±34.5 N as the eccentric load "
                 "turns; linearisation 0.0022 (contact 0.0003, drag 1.3e-05, orders left out 0.0019), 48 against 24 modes "
                 "1.9e-05, drag settled in 3 iterations", id="40: 75 rpm, 10 klbf, e 0.3, 9 ppg, no flow: ok"),
    pytest.param(101, "ok", 0.0031469395315172595,
                 (349.3561020716888, 11828130.769591507, 2909291.89831606, 0.032647482449603686, 123950.87382722364),
                 "lying on the wall at 0 m, 9.45 m, 18.9 m, sliding: 237.9 N at rest, ±104 N as the eccentric load "
                 "turns; linearisation 0.003 (contact 0.00099, drag 2.1e-05, orders left out 0.002), 48 against 24 modes "
                 "0.00017, drag settled in 3 iterations", id="101: 125 rpm, 5 klbf, e 0.7, 9 ppg, 7.4 ft/s: ok"),
    pytest.param(0, "ok", 0.007884216743141978,
                 (256.9943588565637, 10748520.42550849, 2743690.683970855, 0.032401307352774626, 91540.60344520595),
                 "lying on the wall at 0 m, 9.45 m, 18.9 m, sliding: 237.9 N at rest, ±16.1 N as the eccentric load "
                 "turns; linearisation 0.0079 (contact 0.00081, drag 4e-05, orders left out 0.007), 48 against 24 modes "
                 "3.7e-06, drag settled in 4 iterations", id="0: 50 rpm, 5 klbf, e 0.3, 9 ppg, no flow: ok"),
    pytest.param(296, "out_of_scope", None, None,
                 "the contact would open during the revolution at 0 m, 9.45 m, 18.9 m (the turning eccentric load beats "
                 "the weight on the wall): the pipe bounces: a higher model answers",
                 id="296: 275 rpm, 10 klbf, e 0.3, 9 ppg, no flow: the contact opens"),
    pytest.param(150, "ok", 0.0070157048523526565,
                 (415.57809414808133, 35683146.6946752, 2798370.0456557223, 0.032696877991786694, 145362.83293734686),
                 "lying on the wall at 0 m, 9.45 m, 18.9 m, sliding: 225.2 N at rest, ±165 N as the eccentric load "
                 "turns; linearisation 0.0054 (contact 0.002, drag 8.3e-05, orders left out 0.0034), 48 against 24 modes "
                 "0.0016, drag settled in 4 iterations",
                 # checked for a second motion (lift-off 1.57 times the point's eccentricity): the run from rest
                 # left the wall in revolutions 1-8 (the start-up; 1.57 kN in the 2nd) and stayed on it from the 9th;
                 # the full reference run from that rest came to the sliding motion too (regime sliding, 432 N:
                 # solve_point(p, "reference"), measured)
                 id="150: 150 rpm, 20 klbf, e 0.7, 12 ppg, no flow: ok, no second motion"),
]
def _without_joint_mass(point: dict) -> dict:
    """The point with no tool-joint mass lumped (the panel's figures were taken before it was)."""
    return {**point, "tool_joint_length": 0.0}


PANEL_FIGURES = ("peak_contact_force", "max_normal_stress", "alternating_bending_stress", "max_deflection",
                 "max_shear_stress")


@pytest.fixture(scope="module")
def default_grid():
    study = config.load(ROOT / "configs" / "default.toml", ALIGNED)
    return Grid(dict(study.inputs), dict(study.axes))


#: The panel's precision: the method's rest is solved to xtol 1e-13 and its drag iterated to a relative change of
#: 1e-10 (sliding.SETTLED); another CPU's last bits (numba compiles for the host) moved the estimate, a difference of
#: forces, by 7e-9 relative (issue 32: 0.005705578895 against 0.005705578853). 1e-6 holds the outputs to what the
#: method resolves with a margin, and far below the 1e-3 at which a change of the method would show.
PANEL_PRECISION = 1e-6


@pytest.mark.parametrize("index, status, estimate, figures, message", PANEL)
def test_a_panel_of_the_default_study_keeps_the_outputs_it_had(default_grid, index, status, estimate, figures,
                                                                message):
    # without the tool joints' mass (pipe.tool_joint_length = 0) the outputs are those of before it was lumped; every
    # kept mode in the stresses, as then (the stresses' band, reference_stress_band = "timoshenko", moved point 101's
    # max shear stress by 1.6e-6 and point 150's error estimate by 1.3e-4, the first assertions off, measured)
    result = sliding.solve({**_without_joint_mass(default_grid.point(index)), "reference_stress_band": "all"})
    assert (result.status, result.message) == (status, message)
    if estimate is None:
        assert result.error_estimate is None
    else:
        assert result.error_estimate == pytest.approx(estimate, rel=PANEL_PRECISION)
        for name, value in zip(PANEL_FIGURES, figures):
            assert result.values[name] == pytest.approx(value, rel=PANEL_PRECISION), name


def test_where_an_error_variant_is_not_this_state_the_answer_still_states_its_outputs(default_grid, monkeypatch):
    # as at 56f73e1: the answer's outputs (its stresses, peak force) are in the result beside the variant's reason,
    # here the drag variant made to say it is not this state at panel point 2 (its literals above)
    solved = sliding.steady_state

    def drag_variant_out(inputs, *args, **options):
        state = solved(inputs, *args, **options)
        return {**state, "why": "is made to bounce"} if options.get("drag_rule") == "mean_speed" else state

    monkeypatch.setattr(sliding, "steady_state", drag_variant_out)
    result = sliding.solve(_without_joint_mass(default_grid.point(2)))
    assert result.status == "out_of_scope"
    assert result.message == "with the drag made viscous at the mean speed is made to bounce: a higher model answers"
    figures = PANEL[0].values[3]
    for name, value in zip(PANEL_FIGURES, figures):
        assert result.values[name] == pytest.approx(value, rel=PANEL_PRECISION), name


def test_an_answer_above_the_tolerance_is_not_converged_and_stands_in_auto(default_grid, monkeypatch):
    # panel point 0 (50 rpm, 5 klbf, e 0.3, 9 ppg, no flow) under a study tolerance of 0.5 %: the sliding state's
    # estimate of 0.79 % is above it and within SLIDING_STANDS_BELOW, so auto keeps the sliding answer, not_converged,
    # and does not run the reference model (the harmonic balance, which would answer it within the tolerance, made to
    # fail here: where it does not settle the linear answer stands)
    monkeypatch.setattr(sliding, "refine", lambda inputs, state: None)
    point = {**_without_joint_mass(default_grid.point(0)), "tolerance": 0.005}
    alone = solve_point(point, "sliding")
    assert alone.status == "not_converged" and alone.error_estimate == pytest.approx(0.007884216743141978,
                                                                                     rel=PANEL_PRECISION)
    assert alone.values["peak_contact_force"] == pytest.approx(PANEL[3].values[3][0], rel=PANEL_PRECISION)
    chosen = solve_point(point, "auto")
    assert chosen.method == "sliding" and chosen.status == "not_converged"
    assert set(chosen.extras["methods_tried"]) == {"free-whirl", "sliding"}


def _study_point(index: int) -> dict:
    """The default study's grid point ``index`` (configs/default.toml as it is: 90° turn, four joints, the dogleg)."""
    study = config.load(ROOT / "configs" / "default.toml")
    return Grid(dict(study.inputs), dict(study.axes)).point(index)


def _power_balance(model, window):
    """(work of the eccentric load and the contacts, dissipation by the quadratic drag and the modal damping) over the
    revolution [J]; the eccentric load complex where the joints' eccentricities turn (its (cos, sin) Ωt parts)."""
    N = model.n_modes
    t, v = window.times, window.states[:, 2 * N:4 * N]
    turning = np.exp(1j * model.rotary_speed * t)[:, None] * model.eccentric[None]
    load = np.concatenate((turning.real, turning.imag), axis=1) * model.mass
    contact = np.concatenate((window.forces[:, :, 0] @ model.phi, window.forces[:, :, 1] @ model.phi), axis=1)
    work_in = np.trapezoid(np.sum((load + contact) * v, axis=1), t)
    speed = np.hypot(v[:, :N] @ model.drag_shapes.T, v[:, N:] @ model.drag_shapes.T)
    damped = np.trapezoid(np.sum(np.tile(model.damping, 2) * v**2, axis=1), t) * model.mass
    return work_in, np.trapezoid(model.drag * (speed**3) @ model.drag_weights, t) + damped


def test_the_harmonic_balance_solves_the_exact_equations_on_the_wall():
    # default grid point 505 (150 rpm, 30 000 lbf, 9 ppg, 7.4 ft/s, 3°/100 ft): its linear answer states 1.1 % (the
    # default sweep's not_converged, issue 36). The harmonic balance keeps the Hertz law, the friction and the quadratic
    # drag exact: over its revolution the work of the eccentric load and the contacts equals what the drag dissipates
    # (the power balance of the equations of motion; measured 1.4e-8 apart, the linear answer's 9e-4)
    point = _study_point(505)
    result = solve_point(point, "sliding")  # through the method: ok, its error the harmonics' and the modes'
    assert result.status == "ok" and "harmonic balance" in result.message, result.message
    assert result.error_estimate < 0.01 and result.extras["harmonic_balance"]["linear_estimate"] > 0.01
    # the reference model's time integration from the sliding rest settles there: periodic every revolution after
    # 146 (reference.solve with 240 and 480 revolutions alike, 32 modes: 1974.22 N, 86.503 MPa, 38.161 MPa); the
    # harmonic balance lies within its stated error of it (measured 0.029 %, 0.011 %, 0.025 % against a stated
    # 0.049 %), where the linear answer was 1.4 % off the peak force beside its stated 1.1 %
    for name, settled in (("peak_contact_force", 1974.2222686439425), ("max_normal_stress", 86503190.31088927),
                          ("alternating_bending_stress", 38161345.29000387)):
        assert result.values[name] == pytest.approx(settled, rel=result.error_estimate), name
    state = sliding.steady_state(point)
    fine = sliding.refine(point, state)
    assert fine is not None and fine["error"] < 0.005  # measured 4.3e-4 (8 against 4 harmonics)
    work_in, dissipated = _power_balance(state["model"], fine["window"])
    assert work_in == pytest.approx(dissipated, rel=1e-6)
    work_in, dissipated = _power_balance(state["model"], state["window"])
    assert abs(work_in / dissipated - 1) > 1e-4
    # without the turning load it is the rest: nothing moves, and each joint lies at the Hertz approach of its force,
    # δ = (F_n/K)^{2/3} past its clearance (Johnson 1985, §4.2; the rest's force to 1e-9)
    model = state["model"]
    still = dataclasses.replace(model, eccentric=0.0 * model.eccentric, cache={})
    calm = sliding.balance(still, state["rest"], sliding.whirl(still, state["rest"], linear=state["linear"]))
    assert calm["settled"] and np.max(np.abs(calm["harmonics"][1:])) < 1e-12
    window = sliding.balanced_revolution(still, calm)
    held, N = state["rest"]["touching"], model.n_modes
    u = np.stack((window.states[0, :N] @ model.phi.T, window.states[0, N:2 * N] @ model.phi.T), axis=-1)[held]
    force = window.forces[0, held, 2]
    np.testing.assert_allclose(force, state["rest"]["normal"][held], rtol=1e-9)
    np.testing.assert_allclose(np.hypot(u[:, 0], u[:, 1]) - model.clearance[held],
                               (force / model.stiffness[held]) ** (2 / 3), rtol=1e-9)



def test_the_reference_point_s_lift_off_is_computed_about_the_rest_its_run_started_from(monkeypatch):
    # issue 33: solve_point adds the lift-off eccentricity to a reference point; the run started from the sliding rest
    # on its model (48 modes here, as the sliding method's), and the lift-off is computed about that rest on that model:
    # the rest solved once, no state of the inputs solved again (a short run at default grid point 230: 100 rpm,
    # 10 000 lbf, 9 ppg, no flow, the dogleg)
    point = {**_study_point(230), "reference_modes": 48, "reference_max_modes": 48, "reference_revolutions": 1,
             "reference_window": 1, "reference_max_revolutions": 1, "reference_max_body_stations": 1}
    solved, rest = [], sliding.rest

    def counting(model):
        if "sliding_rest" not in model.cache:
            solved.append(model.n_modes)
        return rest(model)

    steady_state = sliding.steady_state

    def again(inputs, *args, like=None, **options):  # on the run's model and rest (like) it builds nothing again
        if like is None:
            raise AssertionError("the lift-off solved the sliding state of the inputs again")
        return steady_state(inputs, *args, like=like, **options)

    monkeypatch.setattr(sliding, "rest", counting)
    monkeypatch.setattr(sliding, "steady_state", again)
    result = solve_point(point, "reference")
    assert solved == [48] and result.rest_model is None
    monkeypatch.undo()
    # the same value as solved from the inputs (sliding.lift_off_eccentricity: 0.02905 in here)
    assert result.values["lift_off_eccentricity"] == pytest.approx(sliding.lift_off_eccentricity(point), rel=1e-6)


def test_where_the_joints_swing_far_along_the_wall_the_balance_in_the_wall_s_coordinates_answers():
    # default grid point 40 (75 rpm, 10 000 lbf, 9 ppg, no flow, straight hole; issue 36): the joints swing 0.24 rad
    # along the wall, the linear answer states 3.7 % and the Cartesian harmonic balance stalls (its line search at
    # steps of 1/256, the Jacobian's condition number 4e9); in each joint's angle along the wall and radial approach it
    # settles in 7 iterations and states 0.015 % (16 against 12 harmonics and the modes)
    point = _study_point(40)
    state = sliding.steady_state(point)
    with np.errstate(all="ignore"):
        assert not sliding.balance(state["model"], state["rest"], state["whirl"])["settled"]
    result = solve_point(point, "sliding")
    assert result.status == "ok" and "in the wall's coordinates" in result.message, result.message
    assert result.error_estimate < 1e-3 and result.extras["harmonic_balance"]["linear_estimate"] > 0.01
    # a swing beyond sliding.STABILITY_SWING: its stability tested, the reference model kicked off it by 1 % coming
    # back 0.92-fold a revolution over revolutions 11-20 (measured; an unstable one grew 1.21-fold)
    assert result.extras["stability"]["stable"] and result.extras["stability"]["growth"] < 0.97
    assert "coexisting_motion" not in result.values  # its lift-off 8.6 times the point's eccentricity: not checked
    # the reference model's time integration from the sliding rest on the same 48 modes settles on it (periodic
    # every revolution after 140: 415.131 N, 20.3433 MPa, 4.09698 MPa; measured 0.058 %, 0.001 %, 0.051 % apart, the
    # peak force the last to settle, §10; started on the balance's orbit it stays there, 0.008 % apart)
    for name, settled, within in (("peak_contact_force", 415.131, 1.5e-3), ("max_normal_stress", 20.3433e6, 2e-4),
                                  ("alternating_bending_stress", 4.09698e6, 1.5e-3)):
        assert result.values[name] == pytest.approx(settled, rel=within), name
    # the exact equations: over the revolution the work of the eccentric load and the contacts is what the drag and
    # the modal damping dissipate (the power balance)
    fine = sliding.refine(point, state)
    assert fine["coordinates"] == "polar"
    work_in, dissipated = _power_balance(state["model"], fine["window"])
    assert work_in == pytest.approx(dissipated, rel=1e-6)


def test_where_the_motion_on_the_wall_is_unstable_it_does_not_answer():
    # default grid point 54 (75 rpm, 20 000 lbf, 12 ppg, no flow, straight hole): the balance in the wall's
    # coordinates settles with the joints swinging 0.37 rad along the wall, but that motion is unstable: the reference
    # model started on it with its velocities 1 % off leaves it, the kick growing 1.21-fold a revolution from the 10th
    # (measured, sliding.STABILITY_REVOLUTIONS; the contact opened in the 36th, peak 9.5 kN in the 40th,
    # docs/reference_model.md §10); the reference model answers
    result = sliding.solve(_study_point(54))
    assert result.status == "out_of_scope" and "swing 0.37 rad along the wall" in result.message, result.message
    assert "unstable" in result.message and "the kick grew 1.2" in result.message, result.message
    assert result.error_estimate is None and result.values["peak_contact_force"] > 0


def test_where_a_bouncing_motion_coexists_with_the_sliding_one_the_answer_says_so():
    # default grid point 322 (300 rpm, 5 000 lbf, 12 ppg, no flow, straight hole): the sliding motion (by the balance
    # in the wall's coordinates) is stable (the kicked run comes back, 0.94-fold a revolution), but the lift-off
    # eccentricity is 1.11 times the point's and the reference model's run from the rest on the wall leaves the wall in
    # its first revolution (it then bounces at 24 kN: docs/reference_model.md §10)
    result = sliding.solve(_study_point(322))
    assert result.status == "ok" and result.extras["stability"]["stable"], result.message
    assert result.extras["stability"]["growth"] < 0.97
    assert result.values["coexisting_motion"] == 1.0 and "a bouncing motion coexists" in result.message
    assert result.extras["second_motion"]["opened"] == 1
    # default grid point 146 (150 rpm, 20 000 lbf, 12 ppg, no flow): lift-off 1.72 times the point's eccentricity,
    # below sliding.BASIN_LIFT_RATIO, so checked: the run from rest lifts off in its first revolution (584 N, 2.5
    # times the rest force) and settles on the wall, no strike after the 7th revolution: no second motion
    calm = sliding.solve(_study_point(146))
    assert calm.status == "ok" and calm.values["coexisting_motion"] == 0.0, calm.message
    assert "coexists" not in calm.message and calm.extras["second_motion"]["opened"] == 1


def test_where_the_run_from_rest_chatters_on_the_wall_a_second_motion_is_flagged():
    # default grid point 384 (75 rpm, 5 000 lbf, 9 ppg, no flow, 3°/100 ft; lift-off 1.80 times the point's
    # eccentricity): the sliding answer 87 N; the check's run from rest on its 48 modes never leaves the wall, but a
    # joint lifts and strikes it above sliding_parts.CHATTER_RATIO times that in every revolution of a stretch after
    # the 15th (measured: 6-15 in a row over 40 revolutions; at 64 fixed modes the full run is ok at 1.07 kN,
    # docs/reference_model.md §10): a chattering motion beside the sliding one, flagged
    from study.solvers.methods import sliding_parts

    result = sliding.solve(_study_point(384))
    assert result.status == "ok" and result.values["peak_contact_force"] == pytest.approx(87.3, rel=0.01)
    found = result.extras["second_motion"]
    assert result.values["coexisting_motion"] == 1.0 and found["chattered"] and not found["bounced"], found
    assert "a chattering motion coexists" in result.message and "48 modes" in result.message, result.message
    assert found["peak"] > sliding_parts.CHATTER_RATIO * result.values["peak_contact_force"]


def test_where_the_run_from_rest_chatters_after_tens_of_quiet_revolutions_a_second_motion_is_flagged():
    # default grid point 650 (275 rpm, 10 000 lbf, 12 ppg, no flow, 3°/100 ft; lift-off 1.39 times the point's
    # eccentricity): the sliding answer 796 N; the check's run from rest on its 48 modes settles on the wall (quiet at
    # 1.1-1.2 times that through revolutions 31-50), then a joint lifts and strikes it again from the 51st: over
    # revolutions 81-100 1.91 times the sliding force on average (2.0 on the generic CPU path; the full run, 64 modes:
    # 2.31 kN, docs/reference_model.md §10), beyond solver.force_tolerance's 15 %: a chattering motion, flagged
    from study.solvers.methods import sliding_parts

    result = sliding.solve(_study_point(650))
    assert result.status == "ok" and result.values["peak_contact_force"] == pytest.approx(796.3, rel=0.01)
    found = result.extras["second_motion"]
    assert result.values["coexisting_motion"] == 1.0 and found["chattered"] and not found["bounced"], found
    assert found["settled"] <= sliding_parts.BASIN_REVOLUTIONS
    assert found["revolutions"] == sliding_parts.LATE_REVOLUTIONS
    assert found["late"] > 1.15 and "then a joint lifted and struck it again" in result.message, result.message
    assert "beyond the force's tolerance of 15%" in result.message


def test_auto_reports_the_bouncing_motion_where_both_exist_and_flags_it():
    # the engineer's safe side: where the stable sliding answer has a bouncing motion beside it, the reference model
    # answers (the motion reached from rest, the worse for the limits), flagged, the sliding figures in its message
    from study.solvers.methods import auto
    from study.solvers.model.options import Tolerances
    from study.solvers.model.result import PointResult

    lying = PointResult(method="sliding", values=dict(coexisting_motion=1.0, peak_contact_force=595.4, regime=6.0,
                                                      max_normal_stress=22.04e6, alternating_bending_stress=5e6))
    assert auto.MENDS["reference"](lying, {}) is True
    bouncing = PointResult(method="reference", status="not_converged", values=dict(peak_contact_force=24e3,
                                                                                    regime=3.0), message="bouncing")
    assert auto._coexisting([lying, bouncing], Tolerances()) is bouncing
    assert bouncing.values["coexisting_motion"] == 1.0 and bouncing.extras["coexisting"]["peak_contact_force"] == 595.4
    assert ("stable sliding motion (peak force 595.4 N, max normal stress 22.04 MPa, alternating stress 5 MPa)"
            in bouncing.message)
    # where the reference model's run came to the sliding regime after all, its figures the sliding ones within their
    # errors, the sliding answer stands, flagged 0
    lying.message = "lying; a bouncing motion coexists: ..."
    settled = PointResult(method="reference", values=dict(peak_contact_force=596.0, regime=6.0,
                                                          max_normal_stress=22.05e6, alternating_bending_stress=5e6),
                          message="sliding")
    assert auto._coexisting([lying, settled], Tolerances()) is lying
    assert lying.values["coexisting_motion"] == 0.0 and "coexists" not in lying.message
    assert "came to this motion too (peak force 596 N" in lying.message, lying.message


def _sliding_and_reference(reference_values: dict, reference_status: str = "not_converged",
                           reference_error: float | None = 0.1127):
    """Default grid point 650 (275 rpm, 10 000 lbf, 12 ppg, no flow, 3°/100 ft): the sliding answer (harmonic balance,
    stated 0.35 %) flagged with a bouncing motion beside it, and a reference run with ``reference_values`` (measured:
    solve_point(p, "sliding") and solve_point(p, "reference"), docs/reference_model.md §10)."""
    from study.solvers.model.result import PointResult

    lying = PointResult(method="sliding", error_estimate=0.003489, message="lying; a bouncing motion coexists: ...",
                        values=dict(coexisting_motion=1.0, regime=6.0, peak_contact_force=796.29,
                                    max_normal_stress=48.386e6, alternating_bending_stress=27.347e6))
    run = PointResult(method="reference", status=reference_status, error_estimate=reference_error,
                      values=dict(regime=6.0, **reference_values), message="whirl sliding")
    return lying, run


def test_a_run_come_to_the_sliding_regime_that_strikes_harder_is_another_motion():
    # default grid point 650: the full reference run (64 modes, 139 revolutions) stays on the wall (regime sliding)
    # while a joint keeps lifting and striking, its per-revolution peak force 2.31 kN ± 34 % against the sliding
    # state's 796 N (measured): by its figures another motion, the worse one reported, flagged, the sliding figures
    # named; its stresses, 3.0 % and 4.4 % above, are within the statistical 5 % and their 0.8-1 %
    from study.solvers.methods import auto
    from study.solvers.model.options import Tolerances

    lying, run = _sliding_and_reference(dict(
        peak_contact_force=2313.8, peak_contact_force_error=0.3382, max_normal_stress=49.859e6,
        max_normal_stress_error=0.00833, alternating_bending_stress=28.542e6, alternating_bending_stress_error=0.0102,
        statistical_figures=1.0))
    answer = auto._coexisting([lying, run], Tolerances())
    assert answer is run and run.values["coexisting_motion"] == 1.0
    assert run.extras["coexisting"]["peak_contact_force"] == 796.29
    assert run.extras["coexisting"]["worse"] == ["peak_contact_force"]
    assert "its regime the same, its figures above the sliding motion's beyond their tolerance and errors: peak " \
           "force 2314 N against 796.3)" in run.message, run.message
    assert "a stable sliding motion" in run.message
    # where the check's run from rest had settled on the sliding motion and left it by itself (a late chatter), the
    # message does not call that motion stable
    lying, run = _sliding_and_reference(dict(peak_contact_force=2313.8, statistical_figures=1.0))
    lying.extras["second_motion"] = dict(chattered=True, late=1.91)
    assert auto._coexisting([lying, run], Tolerances()) is run and "stable" not in run.message, run.message
    assert "came near and then left by itself" in run.message


def test_a_figure_is_judged_within_its_tolerance_and_its_stated_error_credited_up_to_it():
    # h - l > (t + e_h) h + e_l l, each e at most the figure's tolerance t (solver.force_tolerance 15 %; for the
    # stresses the study's 1 %, the statistical 5 % where the run's figures are means over a motion that does not
    # repeat): a run not converged is another motion where its figure is far enough above, however large its error
    from study.solvers.methods import auto
    from study.solvers.model.options import Tolerances

    stresses = dict(max_normal_stress=48.9e6, max_normal_stress_error=0.3, alternating_bending_stress=27.4e6,
                    alternating_bending_stress_error=0.3, statistical_figures=1.0)
    lying, close = _sliding_and_reference(dict(peak_contact_force=1000.0, peak_contact_force_error=4.6, **stresses),
                                          reference_error=4.6)
    assert auto.worse_figures(lying, close, Tolerances()) == {}  # 203.7 N <= (0.15 + 0.15) 1000 + 0.0035 796.3 N
    assert auto._coexisting([lying, close], Tolerances()) is lying and lying.values["coexisting_motion"] == 0.0
    lying, far = _sliding_and_reference(dict(peak_contact_force=1200.0, peak_contact_force_error=4.6, **stresses),
                                        reference_error=4.6)
    assert list(auto.worse_figures(lying, far, Tolerances())) == ["peak_contact_force"]  # 403.7 N > 362.8 N
    assert auto._coexisting([lying, far], Tolerances()) is far and far.values["coexisting_motion"] == 1.0
    # a stress 3 % above, stated within 4 %: within 5 % + 4 % where the figures are means, beyond 1 % + 1 % where the
    # motion repeats
    lying, periodic = _sliding_and_reference(dict(peak_contact_force=800.0, max_normal_stress=49.84e6,
                                                  max_normal_stress_error=0.04, alternating_bending_stress=27.35e6),
                                             reference_error=0.04)
    assert list(auto.worse_figures(lying, periodic, Tolerances())) == ["max_normal_stress"]
    periodic.values["statistical_figures"] = 1.0
    assert auto.worse_figures(lying, periodic, Tolerances()) == {}


def test_a_run_still_ringing_on_its_way_to_the_sliding_motion_is_that_motion():
    # measured (solve_point(p, "sliding") and solve_point(p, "reference") at default grid points 418 and 128): at 418
    # (100 rpm, 5 000 lbf, 12 ppg, no flow, 3°/100 ft) the reference run, not periodic within 34 revolutions, ok at
    # 2.9 %, is 3.3 % above the sliding peak force and 0.5 % above its stresses, beyond the 0.1-1.2 % it states (its
    # window's scatter, not the ringing it has not shed): within the tolerances, the sliding motion. At 128 (150 rpm,
    # 5 000 lbf, 9 ppg, straight hole) its alternating stress is 24 % above the sliding state's: another motion
    from study.solvers.methods import auto
    from study.solvers.model.options import Tolerances
    from study.solvers.model.result import PointResult

    def pair(lower, lower_error, higher, errors, higher_error):
        names = ("peak_contact_force", "max_normal_stress", "alternating_bending_stress")
        lying = PointResult(method="sliding", error_estimate=lower_error,
                            values=dict(coexisting_motion=1.0, regime=6.0, **dict(zip(names, lower))))
        run = PointResult(method="reference", error_estimate=higher_error,
                          values=dict(regime=6.0, statistical_figures=1.0, **dict(zip(names, higher)),
                                      **{f"{n}_error": e for n, e in zip(names, errors)}))
        return lying, run

    lying, run = pair((133.96, 30.315e6, 21.681e6), 0.00125, (138.34, 30.466e6, 21.795e6), (0.0121, 0.0009, 0.0005),
                      0.0291)
    assert auto._coexisting([lying, run], Tolerances()) is lying and lying.values["coexisting_motion"] == 0.0
    lying, run = pair((471.84, 13.067e6, 3.1828e6), 0.00346, (512.07, 13.771e6, 3.9586e6), (0.0356, 0.0232, 0.0315),
                      0.0416)
    assert list(auto.worse_figures(lying, run, Tolerances())) == ["alternating_bending_stress"]


def test_a_run_milder_than_the_sliding_state_leaves_the_sliding_answer_standing():
    # the safe side: the sliding answer stands where no figure of the run is above it beyond their errors, the run's
    # figures lower (the bound the sliding figures give holds)
    from study.solvers.methods import auto
    from study.solvers.model.options import Tolerances

    lying, milder = _sliding_and_reference(dict(peak_contact_force=500.0, max_normal_stress=40e6,
                                                alternating_bending_stress=20e6), "ok", 0.002)
    assert auto._coexisting([lying, milder], Tolerances()) is lying and lying.values["coexisting_motion"] == 0.0


def test_the_lift_off_holds_its_precision_with_fewer_sliding_solves(monkeypatch):
    # default grid point 0 (50 rpm, 5 000 lbf, 9 ppg, no flow, straight hole): the least normal force over the
    # revolution h(ε) falls to nil at the lift-off eccentricity; its root to 1e-12 by Brent's method on the same
    # states (each the whirl about the rest with the eccentric load scaled, its drag settled to 1e-10) is the fine
    # answer, and the search holds it to its 0.1 % (measured 2e-7) with at most 2 states (the secant took 5, the
    # parabola started by the secant 3; started by the slope at ε = 0, sliding._least_force_slope, 2)
    point = _study_point(0)
    state = sliding.steady_state(point)
    model, rested, linear = state["model"], state["rest"], state["linear"]

    def least(eps):
        scaled = dataclasses.replace(model, eccentric=model.eccentric * (eps / model.eccentricity), eccentricity=eps)
        window, _ = sliding.revolution(scaled, rested, sliding.whirl(scaled, rested, linear=linear))
        return sliding._least_force(dict(rest=rested, window=window))

    from scipy import optimize

    fine = optimize.brentq(least, model.eccentricity, 20 * model.eccentricity, xtol=1e-12, rtol=1e-12)
    whirled, solve = [], sliding.whirl

    def counting(*args, **options):
        whirled.append(1)
        return solve(*args, **options)

    monkeypatch.setattr(sliding, "whirl", counting)
    assert sliding.lift_off_eccentricity(point, state) == pytest.approx(fine, rel=1e-3)
    assert len(whirled) <= 2


@pytest.mark.precision
def test_at_grid_point_384_the_run_from_rest_chatters_on_32_modes_not_on_16():
    # docs/reference_model.md §10 (75 rpm, 5 000 lbf, 9 ppg, 3°/100 ft): the sliding answer 87 N; the run from its rest
    # (study.benchmarks.second_motion.from_rest) settles at 108-109 N on 16 modes (the default full run's count), while
    # on 32 modes a joint lifts and strikes from the 4th revolution on, the means per ten revolutions 262, 502, 544,
    # 465, 671 N over the first 50 (on 64 modes 1.07 kN: a chatter the default's modes do not carry). Held to the
    # regime, not to the trajectory: over revolutions 31-50 within 1.5 times the sliding force on 16 modes (its
    # start-up's strikes die by the 30th), over 3 times on 32
    import io
    import json

    from study.benchmarks.second_motion import from_rest

    out = io.StringIO()
    quiet, chatter = from_rest([384], 16, 50, out)[0], from_rest([384], 32, 50, out)[0]
    assert quiet["sliding"] == pytest.approx(87.3, rel=0.01)
    assert quiet["ratio"] < 1.5 and chatter["ratio"] > 3.0, (quiet, chatter)
    assert [json.loads(line)["modes"] for line in out.getvalue().splitlines()] == [16, 32]
