"""Tests of the reference model (study.solvers.reference): checked against closed forms no one here wrote."""

import numpy as np
import pytest

from study.physics import whirl
from study.solvers import METHODS, reference, solve_point


@pytest.fixture(scope="module")
def base(paper_inputs):
    return dict(paper_inputs)


def test_nothing_moves_without_a_drive(base):
    # issue 20: zero eccentricity, a vertical hole and a centred pipe -> nothing moves
    inputs = {**base, "eccentricity": 0.0, "inclination": 0.0, "reference_modes": 6, "reference_revolutions": 3}
    run = reference.simulate(inputs)
    assert run["verdict"] == "periodic"
    assert np.all(run["integrator"].z == 0.0)
    assert np.all(run["window"].states == 0.0)
    result = solve_point(inputs, "reference")
    assert result.status == "no_impact"
    assert result.values["max_deflection"] == 0.0 and result.values["peak_contact_force"] == 0.0


def test_contact_layout_of_three_joints():
    # 93-ft section of 31-ft joints: joints at 31 and 62 ft, the body halfway between stations
    x, kinds = reference.contact_layout(93 * 0.3048, 31 * 0.3048)
    assert np.allclose(x / 0.3048, [15.5, 31, 46.5, 62, 77.5])
    assert list(kinds) == [0, 1, 0, 1, 0]


@pytest.mark.parametrize("field, value", [("tool_joint_diameter", 9.0 * 0.0254), ("tool_joint_diameter", 4.0 * 0.0254)])
def test_bad_tool_joint_is_refused_naming_the_field(base, field, value):
    with pytest.raises(ValueError, match="pipe.tool_joint_diameter"):
        reference.build_model({**base, field: value})


def test_registered_as_a_method():
    assert "reference" in METHODS
