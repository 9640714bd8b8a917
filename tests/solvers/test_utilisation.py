"""Design limits added to every solved point (study.solvers.model.utilisation): data, never a status."""

from pathlib import Path

import pytest

from study import config
from study.physics import fatigue
from study.solvers import solve_point

ROOT = Path(__file__).resolve().parents[2]
PSI = 6894.757293168


@pytest.fixture(scope="module")
def paper_one_wall():
    inputs = config.load(ROOT / "configs" / "paper.toml").point()
    return {**inputs, "impact_pattern": "one_wall", "closure": "self_consistent", "span_length": None}


@pytest.mark.parametrize("grade, yield_psi", [("E-75", 75_000), ("S-135", 135_000)])  # API Spec 5DP minima
def test_yield_utilisation_is_the_stress_over_the_grade_yield_and_past_it_the_status_yields(paper_one_wall, grade,
                                                                                         yield_psi):
    result = solve_point({**paper_one_wall, "pipe_grade": grade}, "fast")
    v = result.values
    # over yield with E-75 (90 ksi): solved and valid, status yields with the figures kept (issue 32); S-135 holds it
    assert result.status == ("yields" if v["yield_utilisation"] > 1 else "ok"), result.message
    assert (grade == "E-75") == (v["yield_utilisation"] > 1)
    assert v["yield_utilisation"] == pytest.approx(v["max_normal_stress"] / (yield_psi * PSI), rel=1e-12)


def test_endurance_and_life_follow_the_alternating_stress(paper_one_wall):
    result = solve_point(paper_one_wall, "fast")
    v = result.values
    # the equivalent amplitude carries the alternating stress and the axial mean (Goodman raises it)
    assert v["equivalent_alternating_stress"] > v["alternating_bending_stress"]
    assert v["endurance_utilisation"] == pytest.approx(
        v["equivalent_alternating_stress"] / fatigue.endurance_limit("B1"), rel=1e-12)
    # Miner: life = 1/damage rate; rate = cycles per second / N(2 sigma_a) with one cycle per revolution
    assert v["fatigue_life"] == pytest.approx(1.0 / v["damage_rate"], rel=1e-12)
    revolutions_per_second = paper_one_wall["rotary_speed"] / (2 * 3.141592653589793)
    cycles = fatigue.cycles_to_failure(2 * v["equivalent_alternating_stress"], "B1")
    assert v["damage_rate"] == pytest.approx(revolutions_per_second / cycles, rel=1e-9)


def test_no_limits_without_stresses(paper_one_wall):
    result = solve_point({**paper_one_wall, "span_length": 105.156, "closure": "prescribed"}, "core")
    assert "yield_utilisation" not in result.values and "fatigue_life" not in result.values


def test_limits_of_a_method_that_does_not_report_the_section(paper_one_wall):
    # a result with stresses but not the steel area: the limits take it from the inputs
    from study.solvers.model.result import PointResult
    from study.solvers.model.options import LimitOptions
    from study.solvers.model.scene import Scene
    from study.solvers.model.utilisation import add_limits

    result = add_limits(PointResult(method="test", values={"max_normal_stress": 1e8, "alternating_bending_stress": 1e7}),
                        Scene.from_inputs(paper_one_wall), LimitOptions.from_inputs(paper_one_wall))
    assert result.values["yield_utilisation"] == pytest.approx(1e8 / (75_000 * PSI))


def test_the_reference_model_reports_the_section_as_every_method_of_the_hierarchy(paper_one_wall):
    # the charts' critical speeds read EI, the effective tension and the mass from every point
    v = solve_point({**paper_one_wall, "reference_modes": 6}, "reference").values
    for name in ("bending_stiffness", "effective_tension", "mass_per_length", "steel_area"):
        assert v[name] > 0, name
