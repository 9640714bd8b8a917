"""The model hierarchy (study.solvers.methods.auto): method auto climbs free whirl -> reference model; method periodic
climbs the paper's fast -> series."""

from pathlib import Path

import numpy as np
import pytest

from study import config
from study.solvers import solve_point

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def valid_point():
    # The 15-mode case with a valid span (tests/solvers/test_fast.py records it).
    inputs = config.load(ROOT / "configs" / "paper.toml").point()
    return {**inputs, "rotary_speed": 150 * np.pi / 30, "restitution": 0.2, "impact_pattern": "alternating",
            "closure": "self_consistent", "modes": 15, "min_span": 9.0}


def test_a_loose_tolerance_takes_the_fast_method(valid_point):
    result = solve_point({**valid_point, "tolerance": 1.0}, "periodic")
    assert result.method == "fast" and result.status == "ok"
    assert result.error_estimate <= 1.0 and list(result.extras["methods_tried"]) == ["fast"]
    assert result.message.startswith("periodic: fast answered")


def test_a_tolerance_no_method_meets_is_reported_not_hidden(valid_point):
    # With 15 modes the left-out modes alone are worth about 20 % (the truncation bound); more harmonics
    # in the series cannot fix that, so no method may claim 1e-3.
    result = solve_point({**valid_point, "tolerance": 1e-3}, "periodic")
    assert result.status == "not_converged"
    assert result.message.startswith("periodic: no model served")
    assert set(result.extras["methods_tried"]) == {"fast", "series"}
    # the answer nearest convergence stands, the other named in the message
    assert result.error_estimate == min(tried["error_estimate"] for tried in result.extras["methods_tried"].values())
    other = ({"fast", "series"} - {result.method}).pop()
    assert f"after {other}: not_converged (error" in result.message or f", {other}: not_converged (error" in result.message
    assert all(tried["error_estimate"] > 1e-3 for tried in result.extras["methods_tried"].values())


def test_a_point_without_a_span_is_answered_by_the_cheapest_method():
    inputs = config.load(ROOT / "configs" / "paper.toml").point()
    result = solve_point({**inputs, "modes": 11}, "periodic")
    assert result.status == "no_span" and result.method == "fast"
    # the series searches the same spans: a point without one is not sent up to it
    assert list(result.extras["methods_tried"]) == ["fast"]


def test_a_span_that_fails_doubling_is_not_sent_to_the_series():
    # 250 rpm, one wall, self-consistent: the 7.39-m span is gone with 81 modes (tests/solvers/test_gate.py);
    # more harmonics in time cannot bring it back
    inputs = config.load(ROOT / "configs" / "paper.toml").point()
    result = solve_point({**inputs, "rotary_speed": 250 * np.pi / 30, "impact_pattern": "one_wall",
                          "closure": "self_consistent", "span_length": None}, "periodic")
    assert result.status == "not_converged" and list(result.extras["methods_tried"]) == ["fast"]


@pytest.fixture(scope="module")
def paper():
    return config.load(ROOT / "configs" / "paper.toml").point()


def test_clear_of_the_wall_the_free_whirl_answers_and_agrees_with_the_reference(paper):
    # vertical hole, 300 rpm: the reference model's section whirls clear of the wall (docs/reference_model.md);
    # the closed form is that steady state, so it answers, and within the study's 1 % of the reference
    result = solve_point(paper, "auto")
    assert result.status == "ok" and result.method == "free-whirl"
    assert result.message.startswith("auto: free-whirl answered")
    assert list(result.extras["methods_tried"]) == ["free-whirl"]
    ref = solve_point({**paper, "reference_revolutions": 120}, "reference")  # settled: periodic after 61
    assert "periodic every 1 revolution" in ref.message
    # the string whirls nearly as a rigid body; its centre is neutral in a vertical hole (nothing holds it), and the
    # reference model's drifts 0.6 mm off the axis while the mud's drag lags its start-up whirl, so the deflections
    # differ by that offset and the normal stresses (nearly axial alone) agree. The tool joints' mass, which the
    # body's unbalance drives through the body, bends it a little: point inertia forces, which the reference model's
    # quasi-static correction completes (89 psi, within 0.14 % of 32 modes') and the free whirl's 61 modes carry to
    # their 1/n² terms (84 psi, 5 % below; docs/reference_model.md §7, §9)
    assert result.values["max_normal_stress"] == pytest.approx(ref.values["max_normal_stress"], rel=0.01)
    assert 0.0 < result.values["max_bending_stress"] < 0.05 * result.values["max_normal_stress"]
    assert ref.values["max_bending_stress"] == pytest.approx(result.values["max_bending_stress"], rel=0.25)
    assert result.values["max_deflection"] <= ref.values["max_deflection"]


def test_a_point_on_the_wall_climbs_to_the_reference_model(paper):
    # 15 deg, 300 rpm: the sag takes the tool joints to the wall, which the free whirl does not model, and the
    # turning eccentric load lifts them off it each revolution, which the sliding state does not
    result = solve_point({**paper, "inclination": np.radians(15.0)}, "auto")
    assert result.method == "reference"
    assert "after free-whirl: out_of_scope, sliding: out_of_scope" in result.message
    # an answer either way; bouncing at the joints, its figures are sample statistics of a chaotic motion whose
    # error the reference model states (docs/reference_model.md §3.1), over the study's 1 % here
    assert result.status in ("ok", "not_converged") and result.values["peak_contact_force"] > 0
    assert list(result.extras["methods_tried"]) == ["free-whirl", "sliding", "reference"]


def test_a_buckled_section_is_not_sent_up(paper):
    result = solve_point({**paper, "axial_tension": -2e5}, "auto")
    assert result.status == "buckled" and list(result.extras["methods_tried"]) == ["free-whirl"]


def test_a_dropped_drag_that_is_not_small_goes_to_the_damped_solution(monkeypatch):
    # the periodic ladder passes over the series (it mends only an error estimate) and sends the undamped
    # solution's terms_not_small (docs/model.md §6) to the damped one, which keeps the drag (§7.1)
    from study.solvers.methods import auto
    from study.solvers.model.result import PointResult

    def rung(name, status, calls):
        def solve(inputs):
            calls.append(name)
            return PointResult(method=name, status=status)
        return solve

    point = config.load(ROOT / "configs" / "paper.toml").point()  # the gate reads its scene
    calls = []
    monkeypatch.setitem(auto.LADDERS, "periodic", {"fast": (rung("fast", "terms_not_small", calls), auto.as_is),
                                                   "series": (rung("series", "ok", calls), auto.as_is),
                                                   "damped": (rung("damped", "ok", calls), auto.as_is)})
    result = auto.solve_periodic(point)
    assert calls == ["fast", "damped"] and result.method == "damped" and result.status == "ok"
    assert result.message.startswith("periodic: damped answered after fast: terms_not_small")
    calls.clear()
    monkeypatch.setitem(auto.LADDERS, "periodic", {"fast": (rung("fast", "no_span", calls), auto.as_is),
                                                   "series": (rung("series", "ok", calls), auto.as_is),
                                                   "damped": (rung("damped", "ok", calls), auto.as_is)})
    assert auto.solve_periodic(point).method == "fast" and calls == ["fast"]  # nothing above mends no_span


def test_a_thick_mud_climbs_to_the_damped_solution(valid_point):
    # source: tests/solvers/test_statuses.py - drag coefficient 20 on the 15-mode point: the undamped solution's
    # drag term is NOT small (terms_not_small); the damped solution keeps it and finds no span with that much
    # damping (c0 = 3.5e3 N s/m²): what the ladder reports is the damped solution's answer
    result = solve_point({**valid_point, "drag_coefficient": 20.0, "tolerance": 0.025}, "periodic")
    assert list(result.extras["methods_tried"]) == ["fast", "damped"]
    assert result.extras["methods_tried"]["fast"]["status"] == "terms_not_small"
    assert result.method == "damped" and "after fast: terms_not_small" in result.message


@pytest.mark.parametrize("estimate, goes_up", [(0.019, False), (0.05, False), (0.08, True), (float("nan"), True)])
def test_a_sliding_answer_near_the_tolerance_stands_and_a_far_one_goes_up(estimate, goes_up):
    # auto.SLIDING_STANDS_BELOW = 5 %: the reference model reaches the sliding state only over hundreds of
    # revolutions (docs/reference_model.md §10); out_of_scope always goes up
    from study.solvers.methods import auto
    from study.solvers.model.result import PointResult
    answer = PointResult(method="sliding", status="not_converged", error_estimate=estimate)
    assert auto.MENDS["reference"](answer, {}) is goes_up
    assert auto.MENDS["reference"](PointResult(method="sliding", status="out_of_scope"), {}) is True


def _default_points(step):
    from study.workflow.grid import Grid

    study = config.load(Path(__file__).resolve().parents[2] / "configs" / "default.toml")
    grid = Grid(dict(study.inputs), dict(study.axes))
    return list(grid.points(range(0, grid.size, step))), study.axes


@pytest.mark.parametrize("module", ["freewhirl", "sliding"])
def test_a_method_does_not_depend_on_the_inputs_it_says_it_does_not(module):
    # INDEPENDENT_OF is a claim about the physics (the free whirl touches nothing, the sliding state's held contacts
    # have no Hunt-Crossley term): at 16 points of configs/default.toml (every 45th: both holes, each mud and flow) each
    # such input moved to its axis' other end gives the same answer to the bit, status, message, values and error
    # estimate
    import importlib

    method = importlib.import_module(f"study.solvers.methods.{module}")
    points, axes = _default_points(45)
    for name in method.INDEPENDENT_OF:
        for point in points:
            other = {**point, name: axes[name][0] if point[name] != axes[name][0] else axes[name][-1]}
            a, b = method.solve(point), method.solve(other)
            assert (a.status, a.message, a.error_estimate) == (b.status, b.message, b.error_estimate), name
            assert a.values.keys() == b.values.keys()
            np.testing.assert_array_equal([a.values[k] for k in a.values], [b.values[k] for k in a.values])


def test_auto_solves_the_cheap_rungs_once_across_the_inputs_they_do_not_depend_on(monkeypatch):
    # two points that differ only in the restitution: the free whirl is solved once, the
    # second point's answers copies of the first's; the reference model (which the restitution enters) twice
    from study.solvers.methods import auto, freewhirl, reference, sliding

    calls = {"free-whirl": 0, "sliding": 0, "reference": 0}

    def counted(name, solve):
        def run(inputs):
            calls[name] += 1
            return solve(inputs)
        run.__module__ = solve.__module__
        return run

    ladder = {name: (counted(name, solve), prepare) for name, (solve, prepare) in auto.LADDERS["auto"].items()}
    monkeypatch.setitem(auto.LADDERS, "auto", ladder)
    points, _ = _default_points(1)
    for bouncing in points[::16]:  # the first that climbs every rung, solved with the memo empty and counted
        auto.clear_memo()
        calls.update({name: 0 for name in calls})
        first = auto.solve({**bouncing, "restitution": 0.3})
        if first.method == "reference":
            break
    second = auto.solve({**bouncing, "restitution": 0.7})
    assert first.method == "reference"
    # the sliding state's checks of its stability and of a second motion run the reference model, whose held contacts
    # have the restitution's damping: it is solved at each restitution (sliding.INDEPENDENT_OF)
    assert calls == {"free-whirl": 1, "sliding": 2, "reference": 2}
    assert first.extras["methods_tried"]["sliding"] == second.extras["methods_tried"]["sliding"]
    assert first.values["peak_contact_force"] != second.values["peak_contact_force"]  # the reference's own answers
    assert freewhirl.INDEPENDENT_OF == ("restitution",) and sliding.INDEPENDENT_OF == ()
    assert not hasattr(reference, "INDEPENDENT_OF")


def test_where_the_sliding_check_found_a_chatter_the_reference_model_starts_at_the_checks_modes():
    # docs/reference_model.md §10: at default grid point 384 the sliding state's check (its run from rest on 48
    # modes) chatters on the wall, while the reference model's run from the same rest on its default 16 modes settles
    # (108-109 N against the sliding 87 N) and on 32-64 chatters: the reference rung starts at the check's count
    from study.solvers.methods import auto
    from study.solvers.model.point import DesignPoint
    from study.solvers.model.result import PointResult

    point = DesignPoint.from_inputs(_default_points(1)[0][384])
    assert point.reference.reference_modes == 16 and point.reference.reference_max_modes == 64
    prepare = auto.LADDERS["auto"]["reference"][1]
    chatter = PointResult(method="sliding", values=dict(coexisting_motion=1.0),
                          extras=dict(second_motion=dict(bounced=False, chattered=True, modes=48)))
    raised = prepare(point, chatter)
    assert raised.reference.reference_modes == 48 and raised.reference.reference_max_modes == 64
    assert raised.inputs["reference_modes"] == 48 and raised.scene == point.scene
    # a bouncing motion (the string off the wall), a settled check, no check, the first rung: the point as given
    for below in (PointResult(method="sliding", extras=dict(second_motion=dict(bounced=True, chattered=False,
                                                                               modes=48))),
                  PointResult(method="sliding", extras=dict(second_motion=dict(bounced=False, chattered=False,
                                                                               modes=48))),
                  PointResult(method="sliding"), None):
        assert prepare(point, below) is point
    # more modes asked for than the check's are kept, and the most raised to the first where it is below
    many = point.with_reference(reference_modes=64, reference_max_modes=32)
    assert prepare(many, chatter).reference.reference_modes == 64
    assert prepare(many, chatter).reference.reference_max_modes == 64
    # a chatter that came late (the check's run settled, then chattered over its last LATE_WINDOW revolutions): the
    # reference run's transient keeps the start-up out of its window, up to where the check's window began
    from study.solvers.methods import sliding_parts

    assert raised.reference.reference_min_revolutions == 0
    late = PointResult(method="sliding", values=dict(coexisting_motion=1.0), extras=dict(second_motion=dict(
        bounced=False, chattered=True, modes=48, revolutions=sliding_parts.LATE_REVOLUTIONS, late=1.91)))
    floored = prepare(point, late).reference
    assert floored.reference_modes == 48
    assert floored.reference_min_revolutions == sliding_parts.LATE_REVOLUTIONS - sliding_parts.LATE_WINDOW


def test_a_full_run_come_to_the_sliding_motion_takes_the_chatter_flag_off():
    # where the reference model's run came to the sliding motion after all (its figures within their tolerance and
    # errors, auto.worse_figures), the sliding answer stands, flagged 0, its message no longer naming the chatter; where
    # it chatters at 12 times the sliding force (384 at 64 fixed modes: 1.07 kN, 30.47 and 22.02 MPa against 87 N,
    # 29.73 and 21.56 MPa, docs/reference_model.md §10) its answer is the point's, flagged 1
    from study.solvers.methods import auto
    from study.solvers.model.options import Tolerances
    from study.solvers.model.result import PointResult

    names = ("peak_contact_force", "max_normal_stress", "alternating_bending_stress")

    def lying():
        return PointResult(method="sliding", error_estimate=0.005, values=dict(coexisting_motion=1.0, regime=6.0,
                                                                               **dict(zip(names, (87.3, 29.73e6,
                                                                                                  21.56e6)))),
                           message="lying; a chattering motion coexists: in the reference model's run ...")

    came_back = PointResult(method="reference", error_estimate=0.01, values=dict(regime=6.0, **dict(zip(
        names, (88.0, 29.75e6, 21.57e6)))), message="sliding")
    stands = auto._coexisting([lying(), came_back], Tolerances())
    assert stands.method == "sliding" and stands.values["coexisting_motion"] == 0.0
    assert stands.message.startswith("lying; the reference model's run from the rest came to this motion too")
    chatter = PointResult(method="reference", error_estimate=0.01, values=dict(regime=6.0, **dict(zip(
        names, (1070.0, 30.47e6, 22.02e6)))), message="sliding")
    assert auto._coexisting([lying(), chatter], Tolerances()) is chatter
    assert chatter.values["coexisting_motion"] == 1.0 and chatter.extras["coexisting"]["worse"] == [
        "peak_contact_force"]
