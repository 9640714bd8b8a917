"""The pipe lying on the wall, sliding (study.solvers.sliding): its rest against closed forms, the whirl about it
against the energy balance and the reference model's own equations, and where it does not answer."""

from pathlib import Path

import numpy as np
import pytest

from study import config
from study.workflow.grid import Grid
from study.physics import whirl as whirl_physics
from study.solvers import reference, sliding, solve_point

ROOT = Path(__file__).resolve().parents[2]


def _default(rpm: float, klbf: float, ppg: float = 9.0, flow: float = 0.0, **extra) -> dict:
    point = config.load(ROOT / "configs" / "default.toml", {
        "load.rotary_speed": f"{rpm} rpm", "load.axial_tension": f"{klbf * 1000} lbf", "impact.restitution": 0.3,
        "mud.density": f"{ppg} ppg", "mud.flow_velocity": f"{flow} ft/s"}).point()
    return {**point, **extra}


@pytest.fixture(scope="module")
def beam_on_one_support():
    # a plain beam (no tension, no flow) pinned at its ends and resting at midspan on a tool joint, 15 deg hole
    inputs = _default(100, 0, inclination=np.radians(15.0), contact_points=[0.5], contact_kinds=[1])
    state = sliding.steady_state({**inputs, "friction": 0.0})
    return inputs, state


def test_rest_on_a_midspan_support_is_the_euler_bernoulli_reaction(beam_on_one_support):
    inputs, state = beam_on_one_support
    model = state["model"]
    assert model.props["effective_tension"] == 0.0
    ei, L = model.props["bending_stiffness"], model.span
    w = float(whirl_physics.side_load(model.props["pipe_mass"], model.props["internal_mud_mass"],
                                      inputs["mud_density"], inputs["outer_diameter"] / 2, np.radians(15.0)))
    c = float(model.clearance[0])
    # simply supported beam: midspan deflection 5wL^4/(384 EI) under the uniform load, PL^3/(48 EI) under a
    # central point load (Roark's Formulas for Stress and Strain, 7th ed., Table 8.1, cases 2e and 1a); the
    # support takes what brings the midspan back to the wall (the Hertz approach, micrometres, beside it)
    reaction = (5 * w * L**4 / (384 * ei) - c) * 48 * ei / L**3
    assert state["rest"]["normal"][0] == pytest.approx(reaction, rel=1e-3)
    assert state["rest"]["u"][0, 1] == pytest.approx(0.0, abs=1e-12)  # no friction: straight down


def test_friction_turns_the_resting_joint_aside(beam_on_one_support):
    inputs, _ = beam_on_one_support
    state = sliding.steady_state({**inputs, "friction": 0.3})
    model, rest = state["model"], state["rest"]
    fn, (uy, uz) = rest["normal"][0], rest["u"][0]
    flex = sliding.flexibility(model)[0, 0]
    # tangential equilibrium of the point on its wall circle (radius c + δ) under friction μ s F_n t̂ and the beam's
    # flexibility G: tan φ = −μ s G F_n / (c + δ + G F_n) (by hand from u = u_free + G F, F = −F_n (n̂ + μ s t̂)),
    # s the regularised sign of the surface's sliding speed Ω r_tj (1 − 7e-5 here)
    s = whirl_physics.friction_factor(model.rotary_speed * model.radius[0], model.slip_velocity)
    radius = np.hypot(uy, uz)
    assert np.arctan2(uz, uy) == pytest.approx(np.arctan(-0.3 * s * flex * fn / (radius + flex * fn)), rel=1e-9)
    assert np.arctan2(uz, uy) < -0.01  # turned against the pipe's rotation (the rotation carries the surface to +z)


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
    # with the modes damped viscously (ζ = 5 %) the reference model's start-up ringing dies within its first
    # revolutions, so after 120 it is in the steady state; the sliding state of the same equations is that state
    # (measured: peak force 0.27 %, stresses 0.02-0.09 % apart; with the mud's quadratic drag alone the ringing
    # decays algebraically, docs/reference_model.md §10)
    inputs = {**_default(50, 10, ppg=12.0, flow=7.4), "reference_damping": "viscous", "damping_ratio": 0.05}
    mine = sliding.solve(inputs)
    theirs = reference.solve({**inputs, "reference_revolutions": 120})
    assert mine.status == "ok" and theirs.values["whirl_class"] == reference.WHIRL_CLASSES["sliding"]
    for name, tolerance in (("peak_contact_force", 0.01), ("max_normal_stress", 0.002),
                            ("alternating_bending_stress", 0.002)):
        assert mine.values[name] == pytest.approx(theirs.values[name], rel=tolerance), name


def test_the_arc_gives_the_contact_force_its_second_harmonic():
    # a joint sliding on its wall moves on an arc, inside the linear motion's tangent by r Δφ²/2: the force on it
    # has a component at 2Ω (measured in the reference model at 480 revolutions: 2.69 N beside 16.9 N at Ω)
    state = sliding.steady_state(_default(50, 10, ppg=12.0, flow=7.4))
    force = state["window"].forces[:-1, 1, 2]
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
    # the reference model's revolutions walk towards it (docs/reference_model.md §10, measured: 102.7 N, 3036 psi,
    # 761.3 psi at 40 revolutions; 84.7, 3015, 737.0 at 120; 77.5, 3001, 723.5 at 480)
    assert result.values["peak_contact_force"] == pytest.approx(77.5, rel=0.025)
    assert result.values["max_normal_stress"] == pytest.approx(3001 * 6894.757, rel=0.001)
    assert result.values["alternating_bending_stress"] == pytest.approx(723.5 * 6894.757, rel=0.002)


# A panel of the default study's grid (configs/default.toml, Grid.point(i)) held to the outputs of commit 56f73e1,
# before the method was made cheaper (shared model, rest and linearisation across the error variants, the stresses
# of the variants from one call, trajectory.fields' static parts cached): the speed-up must not change a value, a
# status or a message. Literals printed by that commit's sliding.solve at these points.
PANEL = [
    pytest.param(2, "ok", 0.005705578852772462,
                 (155.11939887497059, 13279134.103915108, 5403849.889998018, 0.036481100474067954, 80792.15547934567),
                 "lying on the wall at 9.45 m, 18.9 m, sliding: 135.6 N at rest, ±17 N as the eccentric load turns; "
                 "linearisation 0.0055 (contact 0.00061, drag 4e-05), 48 against 24 modes 0.00023, drag settled in 4 "
                 "iterations", id="2: 50 rpm, 5 klbf, e 0.3, 12 ppg, no flow: ok"),
    pytest.param(40, "ok", 0.0049303363670331534,
                 (112.1436435363444, 20798649.853207584, 5037874.835464681, 0.03633005734427791, 78391.69790805096),
                 "lying on the wall at 9.45 m, 18.9 m, sliding: 70.58 N at rest, ±38.2 N as the eccentric load turns; "
                 "linearisation 0.0047 (contact 0.00066, drag 3.3e-05), 48 against 24 modes 0.00025, drag settled in 3 "
                 "iterations", id="40: 75 rpm, 10 klbf, e 0.3, 9 ppg, no flow: ok"),
    pytest.param(101, "ok", 0.008757765899453051,
                 (296.5691215336105, 14149914.107190238, 5750118.74939841, 0.03709212023143554, 123774.93929481095),
                 "lying on the wall at 9.45 m, 18.9 m, sliding: 149.6 N at rest, ±126 N as the eccentric load turns; "
                 "linearisation 0.0076 (contact 0.0017, drag 4.6e-05), 48 against 24 modes 0.0011, drag settled in 4 "
                 "iterations", id="101: 125 rpm, 5 klbf, e 0.7, 9 ppg, 7.4 ft/s: ok"),
    # (at 56f73e1 the method called this one out_of_scope itself, "...: error estimate 0.019 above the study's
    # tolerance 0.01, a higher model answers"; since then it answers and the gate calls it not_converged, the
    # values and the estimate the same)
    pytest.param(0, "ok", 0.018814903542632374,
                 (173.56333833637922, 13363374.795379773, 5486038.234489788, 0.036513647077900876, 84225.9762600765),
                 "lying on the wall at 9.45 m, 18.9 m, sliding: 149.5 N at rest, ±19.5 N as the eccentric load turns; "
                 "linearisation 0.019 (contact 0.0029, drag 0.0001), 48 against 24 modes 0.00024, drag settled in 4 "
                 "iterations", id="0: 50 rpm, 5 klbf, e 0.3, 9 ppg, no flow: error estimate above the tolerance"),
    pytest.param(296, "out_of_scope", None, None,
                 "the contact would open during the revolution at 9.45 m, 18.9 m (the turning eccentric load beats the "
                 "weight on the wall): the pipe bounces: a higher model answers",
                 id="296: 275 rpm, 10 klbf, e 0.3, 9 ppg, no flow: the contact opens (drag not settled in 50)"),
    pytest.param(150, "out_of_scope", None, None,
                 "the section at rest does not reach the wall (the free whirl's case): a higher model answers",
                 id="150: 150 rpm, 20 klbf, e 0.7, 12 ppg, no flow: no touch"),
]
PANEL_FIGURES = ("peak_contact_force", "max_normal_stress", "alternating_bending_stress", "max_deflection",
                 "max_shear_stress")


@pytest.fixture(scope="module")
def default_grid():
    study = config.load(ROOT / "configs" / "default.toml")
    return Grid(dict(study.inputs), dict(study.axes))


#: The panel's precision: the method's rest is solved to xtol 1e-13 and its drag iterated to a relative change of
#: 1e-10 (sliding.SETTLED); another CPU's last bits (numba compiles for the host) moved the estimate, a difference of
#: forces, by 7e-9 relative (issue 32: 0.005705578895 against 0.005705578853). 1e-6 holds the outputs to what the
#: method resolves with a margin, and far below the 1e-3 at which a change of the method would show.
PANEL_PRECISION = 1e-6


@pytest.mark.parametrize("index, status, estimate, figures, message", PANEL)
def test_a_panel_of_the_default_study_keeps_the_outputs_it_had(default_grid, index, status, estimate, figures,
                                                                message):
    result = sliding.solve(default_grid.point(index))
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
    result = sliding.solve(default_grid.point(2))
    assert result.status == "out_of_scope"
    assert result.message == "with the drag made viscous at the mean speed is made to bounce: a higher model answers"
    figures = PANEL[0].values[3]
    for name, value in zip(PANEL_FIGURES, figures):
        assert result.values[name] == pytest.approx(value, rel=PANEL_PRECISION), name


def test_an_answer_above_the_tolerance_is_not_converged_and_stands_in_auto(default_grid):
    # panel point 0 (50 rpm, 5 klbf, e 0.3, 9 ppg, no flow): the sliding state with an estimate of 1.9 %, above the
    # study's 1 %; the reference model there ended 22 % from convergence after 46 revolutions, foreseeing about 163
    # (docs/reference_model.md §10), so auto keeps the sliding answer, not_converged, and does not run it
    point = default_grid.point(0)
    alone = solve_point(point, "sliding")
    assert alone.status == "not_converged" and alone.error_estimate == pytest.approx(0.018814903542632374, rel=PANEL_PRECISION)
    assert alone.values["peak_contact_force"] == pytest.approx(PANEL[3].values[3][0], rel=PANEL_PRECISION)
    chosen = solve_point(point, "auto")
    assert chosen.method == "sliding" and chosen.status == "not_converged"
    assert set(chosen.extras["methods_tried"]) == {"free-whirl", "sliding"}
