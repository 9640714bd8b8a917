"""The physics-core method (study.solvers.methods.core) and the method registry (study.solvers)."""

from pathlib import Path

import numpy as np
import pytest

from study import config
from study.physics import hertz
from study.solvers import METHODS, OUTPUTS, STATUS, solve_point

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def paper_point():
    return config.load(ROOT / "configs" / "paper.toml").point()


def test_paper_example_is_consistent_and_not_a_hertz_contact(paper_point):
    # At the paper's printed 345-ft span the prescribed closure drives the equivalent mass 2ML/pi (7700 lb)
    # into the wall at Omega c: Lee's peak is 1.6e7 N (3.6 million lbf) over an 8.5-m contact on a 4.5-in
    # pipe - not a Hertz contact, so the gate (study.solvers.model.gate) does not call it ok; the values stay.
    result = solve_point(paper_point)
    assert result.status == "hertz_invalid", result.message
    assert "length_vs_pipe_diameter" in result.message and "1.594e+07 N" in result.message
    v = result.values
    assert 2 * v["contact_half_length"] > 70 * paper_point["outer_diameter"]
    c = (8.75 - 4.5) / 2 * 0.0254  # clearance of the reconstructed hole [m]
    assert v["clearance"] == pytest.approx(c)
    # Prescribed closure (docs/model.md §4): V_p = Omega c with Omega = 10 pi rad/s (300 rpm).
    assert v["impact_velocity"] == pytest.approx(10 * np.pi * c)
    # Paper eq. 5 and 16: m_e = 2 M L / pi, J = m_e (1 + e) V_p.
    assert v["equivalent_mass"] == pytest.approx(2 * v["mass_per_length"] * v["span_length"] / np.pi)
    assert v["impulse"] == pytest.approx(v["equivalent_mass"] * 1.5 * v["impact_velocity"])
    # Lee's rule T_L/T_H = 0.8539 (paper: 0.855).
    assert v["contact_duration"] / v["hertz_duration"] == pytest.approx(0.855, rel=2e-3)
    # Lee's peak carries the impulse: F = pi J / (2 T_L); with e = 1 it would equal the Hertz peak.
    assert v["peak_contact_force"] == pytest.approx(np.pi * v["impulse"] / (2 * v["contact_duration"]))
    assert v["peak_contact_force"] == pytest.approx(v["hertz_peak_force"] * 1.5 / 2)
    assert v["contact_half_length"] > v["contact_half_width"] > 0
    # The first natural frequency of the span follows omega^2 = [EI (pi/L)^4 + T (pi/L)^2]/M.
    k = np.pi / v["span_length"]
    omega = np.sqrt((v["bending_stiffness"] * k**4 + v["effective_tension"] * k**2) / v["mass_per_length"])
    assert v["first_natural_frequency"] == pytest.approx(omega / (2 * np.pi))
    assert set(v) <= set(OUTPUTS)


def test_a_short_slow_span_is_a_hertz_contact_and_ok(paper_point):
    # 3-m span at 50 rpm: Lee's peak 66 kN over a 99-mm contact (less than the 114-mm pipe diameter)
    result = solve_point({**paper_point, "span_length": 3.0, "rotary_speed": 50 * np.pi / 30})
    assert result.status == "ok", result.message
    assert 2 * result.values["contact_half_length"] < paper_point["outer_diameter"]


def test_restitution_limits_scale_the_pulse(paper_point):
    # e = 0: J = m_e V_p (plastic); e = 1: J = 2 m_e V_p and Lee's peak equals the Hertz peak (app. C).
    plastic = solve_point({**paper_point, "restitution": 0.0}).values
    elastic = solve_point({**paper_point, "restitution": 1.0}).values
    assert plastic["impulse"] == pytest.approx(plastic["equivalent_mass"] * plastic["impact_velocity"])
    assert elastic["impulse"] == pytest.approx(2 * plastic["impulse"])
    assert elastic["peak_contact_force"] == pytest.approx(elastic["hertz_peak_force"], rel=1e-12)


def test_buckled_span_is_a_status_not_an_exception(paper_point):
    # Euler: the 345-ft span buckles under any compression beyond EI (pi/L)^2 (a few newtons).
    result = solve_point({**paper_point, "axial_tension": -1e4})
    assert result.status == "buckled"
    assert "Euler load" in result.message
    assert "first_natural_frequency" not in result.values


def test_without_a_span_only_span_free_outputs(paper_point):
    result = solve_point({**paper_point, "span_length": None})
    assert result.status == "incomplete"
    assert "span_length" not in result.values and "bending_stiffness" in result.values


def test_self_consistent_closure_is_not_faked_by_the_core(paper_point):
    result = solve_point({**paper_point, "closure": "self_consistent"})
    assert result.status == "incomplete"
    assert "impact_velocity" not in result.values


def test_soft_formation_flags_hertz_with_the_criterion(paper_point):
    # In a soft formation (E_rock = 1e8 Pa, about 15 kpsi) the contact of the prescribed-closure
    # impact stretches beyond a tenth of the span, where Hertz's half-space assumption fails; the
    # status says so and names the criterion instead of reporting a number as if it were valid.
    result = solve_point({**paper_point, "rock_youngs_modulus": 1e8})
    assert result.status == "hertz_invalid"
    assert "half_length_vs_span" in result.message
    assert result.values["contact_half_length"] > 0.1 * result.values["span_length"]


def test_an_exception_inside_a_method_becomes_status_failed(paper_point):
    result = solve_point({**paper_point, "outer_diameter": "not a number"})
    assert result.status == "failed"
    assert "TypeError" in result.message


def test_registry_lists_methods_and_statuses_have_distinct_codes():
    assert "core" in METHODS
    codes = [code for code, _ in STATUS.values()]
    assert len(set(codes)) == len(codes)
    with pytest.raises(ValueError, match="allowed: core"):
        solve_point({}, method="nope")


def test_core_hertz_stiffness_matches_the_sphere_closed_form_when_curvatures_are_equal():
    # Sanity link between core and hertz: equal curvatures -> sphere: F = (4/3) E* sqrt(R) d^1.5.
    e_star = 1 / (np.pi * (hertz.compliance(2e11, 0.3) + hertz.compliance(3e10, 0.2)))
    radius = 0.05
    k = hertz.hertz_stiffness(1 / (2 * radius), 1 / (2 * radius), 1 / (np.pi * e_star))
    assert k == pytest.approx(4 / 3 * e_star * np.sqrt(radius), rel=1e-9)
