"""Tests of study.solvers.methods.refcheck: the periodic solution against the reference model."""

import numpy as np
import pytest

from study.solvers.methods import refcheck
from study.solvers import solve_point

PERIODIC = dict(peak_contact_force=1000.0, max_normal_stress=2e7, alternating_bending_stress=1e7)


def test_agreement_within_the_tolerance_is_ok():
    reference = {name: value * 1.01 for name, value in PERIODIC.items()}
    status, ratios, reasons = refcheck.verdict(PERIODIC, reference, True, 0.02)
    assert status == "ok" and not reasons
    assert ratios["reference_peak_force_ratio"] == pytest.approx(1 / 1.01)


def test_each_quantity_outside_the_tolerance_is_named():
    reference = dict(PERIODIC, max_normal_stress=1e7)
    status, ratios, reasons = refcheck.verdict(PERIODIC, reference, True, 0.02)
    assert status == "disagrees" and len(reasons) == 1 and "largest normal stress" in reasons[0]
    assert ratios["reference_normal_stress_ratio"] == pytest.approx(2.0)


@pytest.mark.parametrize("periodic, touches, status", [(None, False, "no_impact"), (None, True, "disagrees"),
                                                       (PERIODIC, False, "disagrees")])
def test_contact_on_one_side_only_disagrees(periodic, touches, status):
    reference = dict(PERIODIC, peak_contact_force=500.0 if touches else 0.0)
    assert refcheck.verdict(periodic, reference, touches, 0.02)[0] == status


def test_paper_point_the_periodic_solution_strikes_a_wall_the_reference_never_reaches(paper_inputs):
    # the one-wall, self-consistent reading has valid 22-ft spans (docs/validation.md); the reference model's
    # section whirls forward, clear of the wall (docs/reference_model.md)
    inputs = {**paper_inputs, "closure": "self_consistent", "impact_pattern": "one_wall", "reference_modes": 8}
    result = solve_point(inputs, "reference-check")
    assert result.status == "disagrees", result.message
    assert "does not touch" in result.message
    assert result.values["whirl_class"] == 0 and result.values["contact_fraction"] == 0.0
    assert result.extras["reference"]["whirl_frequency_ratio"] == pytest.approx(1.0, abs=1e-3)
    assert np.isfinite(result.values["peak_contact_force"]) and result.values["peak_contact_force"] > 0
