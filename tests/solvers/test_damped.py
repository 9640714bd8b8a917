"""The damped periodic solution (study.solvers.methods.periodic.damped; paper appendices A and B, docs/model.md §7.1)."""

from pathlib import Path

import numpy as np
import pytest

from study import config
from study.solvers.methods.periodic import damped, fast
from study.solvers import solve_point
from study.solvers.methods import periodic

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def one_wall():
    """The paper's example searched in the reading where the undamped solution has spans (one wall per revolution,
    the solution's own impact velocity: 22.02 ft, docs/validation.md), 41 modes."""
    inputs = config.load(ROOT / "configs" / "paper.toml").point()
    return {**inputs, "impact_pattern": "one_wall", "closure": "self_consistent", "span_length": None}


@pytest.fixture(scope="module")
def solved(one_wall):
    return damped.solve(one_wall)


def test_undamped_solution_is_recovered_as_the_drag_vanishes(one_wall):
    # source: paper appendix A with λ A3 -> 0 - no damping, no end moment: the undamped solution (method fast)
    inputs = {**one_wall, "modes": 21, "drag_coefficient": 1e-9}
    thin, undamped = damped.solve(inputs), fast.solve(inputs)
    assert thin.status == undamped.status == "ok"
    assert thin.values["span_length"] == pytest.approx(undamped.values["span_length"], rel=1e-9)
    for name in ("max_normal_stress", "alternating_bending_stress", "max_deflection", "impulse", "contact_duration"):
        assert thin.values[name] == pytest.approx(undamped.values[name], rel=1e-6), name
    assert thin.values["end_moment_amplitude"] < 1e-3  # N m; 8.1 kN m with the paper's drag (C_d = 0.5)


def test_the_damped_point_keeps_its_span_and_moves_its_stresses(solved):
    # source: the undamped solution at this point (docs/validation.md: 22.02 ft); damping ratio of mode 1 ~ 0.2
    assert solved.status == "ok", solved.message
    assert solved.values["span_length"] == pytest.approx(6.7126, rel=1e-3)
    assert 0.1 < solved.values["damping_ratio"] < 0.4
    assert solved.extras["damping_converged"] and solved.extras["span_converged"]
    history = solved.extras["end_moment_history"]
    assert len(history["t"]) == len(history["moment"]) == 64
    assert solved.values["end_moment_amplitude"] == pytest.approx(np.max(np.abs(history["moment"])))


def test_end_moments_feed_what_the_drag_takes(solved, one_wall):
    # source: paper appendix B (extended to the span by the paper): with the response in phase with the impact
    # force, the force does no net work and the second agent's work equals the dissipation
    v, x = solved.values, solved.extras
    taken = v["drag_dissipation"]
    assert v["energy_residual"] < 1e-3
    assert abs(x["impact_work"]) < 1e-9 * taken
    # nonlinear drag D∫∫|ẏ|³ = linear damper c∫∫ẏ² at the settled c (equal dissipation, paper eq. A3)
    assert x["damper_dissipation"] == pytest.approx(taken, rel=1e-3)
    period = 2 * np.pi / one_wall["rotary_speed"]
    assert v["end_moment_power"] * period == pytest.approx(x["damper_dissipation"], rel=1e-4)


def test_the_damping_is_the_equal_dissipation_of_its_own_motion(solved, one_wall):
    # source: paper eq. A3-A4 - c is a fixed point of the map c -> D∫∫|ẏ|³/∫∫ẏ² of the motion c gives
    scene, options = periodic.make_scene(one_wall), periodic.options_from(one_wall)
    c = solved.values["equivalent_damping"]
    found = damped.impact_at(scene, solved.values["span_length"], c, options, 400,
                             solved.values["contact_duration"], solved.values["contact_half_length"])
    assert damped.energy(scene, found)["equivalent_damping"] == pytest.approx(c, rel=1e-3)
    # and it is far from the paper's first guess, the assumed mode's (8/3π)² D Ω c
    assert c > 2 * damped.assumed_damping(scene)


def test_an_unsettled_damping_is_reported_not_raised(one_wall):
    result = damped.solve({**one_wall, "modes": 21, "damping_iterations": 1})
    assert result.status == "not_converged"
    assert "the equivalent damping did not settle in 1 steps" in result.message


def test_the_paper_reading_without_spans_has_none_with_damping_either(one_wall):
    # source: docs/validation.md - both walls, V_p = Ω c: no valid undamped span; the damped search continues
    # only what passes the undamped midspan screen
    result = solve_point({**one_wall, "impact_pattern": "alternating", "closure": "prescribed", "modes": 21},
                         "damped")
    assert result.status == "no_span" and "none satisfies condition 1 with damping" in result.message


def test_the_end_moment_is_the_bending_moment_at_the_ends(solved, one_wall):
    # source: boundary condition of eq. 7.3 (docs/model.md §7.1), −EI y''(0, t) = M_e(t): the field's moment at
    # x = 0 (modes vanish there, the static shape m_s(0) = 1) is the end moment the method reports
    scene, options = periodic.make_scene(one_wall), periodic.options_from(one_wall)
    v = solved.values
    found = damped.impact_at(scene, v["span_length"], v["equivalent_damping"], options, 400, v["contact_duration"],
                             v["contact_half_length"])
    t, moment = damped.end_moment_history(scene, found)
    at_end = damped.fields(scene, found.impact, found.spec, options, np.array([0.0, 1e-9]), t, ["moment"])["moment"]
    assert np.allclose(at_end[:, 0], moment, rtol=1e-9, atol=1e-9 * np.abs(moment).max())
    assert np.abs(moment).max() == pytest.approx(v["end_moment_amplitude"], rel=1e-3)


@pytest.mark.parametrize("pattern", ["alternating", "one_wall"])
def test_energy_balance_at_a_fixed_span_and_damping(one_wall, pattern):
    # source: paper appendix B carried to the span - the impact load in phase with the displacement it works on
    # does no net work, so the end moments' work equals the damper's dissipation (harmonics against the velocity
    # field on a grid); at an arbitrary span, damping and either impact pattern
    inputs = {**one_wall, "impact_pattern": pattern, "closure": "prescribed", "modes": 21}
    scene, options = periodic.make_scene(inputs), periodic.options_from(inputs)
    found = damped.impact_at(scene, 40.0, 300.0, options, 400, 2e-3, 0.01, max_iterations=1)
    balance = damped.energy(scene, found)
    assert balance["end_moment_work"] > 0
    assert balance["end_moment_work"] == pytest.approx(balance["damper_dissipation"], rel=1e-4)
    assert abs(balance["impact_work"]) < 1e-9 * balance["damper_dissipation"]
