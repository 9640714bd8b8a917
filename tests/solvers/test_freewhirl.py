"""The free whirl (study.solvers.methods.freewhirl): the reference model's scene clear of the wall, in closed form."""

from pathlib import Path

import numpy as np
import pytest

from study import config
from study.solvers.methods import freewhirl
from study.solvers import solve_point
from study.solvers.model.options import ReferenceOptions
from study.solvers.model.scene import Scene
from study.physics.string_modes import mode_shapes

ROOT = Path(__file__).resolve().parents[2]
DEG = np.pi / 180


def typed(inputs):
    """The point's scene and reference options, as the method builds them at its entry."""
    return Scene.from_inputs(inputs), ReferenceOptions.from_inputs(inputs)


@pytest.fixture(scope="module")
def paper():
    return config.load(ROOT / "configs" / "paper.toml").point()


def test_in_an_inclined_hole_the_weight_lays_the_string_on_the_wall(paper):
    # docs/reference_model.md §1: the string's rigid translation has no stiffness, so the weight's side load lays its
    # tool joints on the low side however small: never clear of the wall, the free whirl does not answer
    result = solve_point({**paper, "eccentricity": 0.0, "inclination": 0.5 * DEG}, "free-whirl")
    assert result.status == "out_of_scope" and "low side" in result.message


def test_without_drag_the_whirl_is_a_rigid_jeffcott_rotor(paper):
    # source: the Jeffcott rotor (Vance 1988 eq. 2.11): the synchronous response to the rotating unbalance m_p eps
    # Omega^2 of a mass M per length on a support of natural frequency omega is (m_p/M) eps r^2/(1 - r^2), r =
    # Omega/omega; a uniform load drives the string's rigid translation alone (omega = 0, r -> infinity): a circle of
    # radius (m_p/M) eps at every section, opposite the unbalance, and no bending
    # radius (m_p/M) eps at every section, opposite the unbalance, and no bending (without the tool joints' mass,
    # which the body's unbalance would bend the string against)
    inputs = {**paper, "drag_coefficient": 0.0, "tool_joint_length": 0.0}
    state = freewhirl.steady_state(*typed(inputs))
    props = state["props"]
    radius = props["pipe_mass"] / props["mass_per_length"] * paper["eccentricity"]
    np.testing.assert_allclose(np.abs(state["whirl"][0]), radius, rtol=1e-12)
    assert np.max(np.abs(state["whirl"][2])) < 1e-12 * radius  # straight: no curvature
    result = solve_point(inputs, "free-whirl")
    assert result.status == "ok" and result.values["max_bending_stress"] < 1e-6


def test_the_mud_drag_only_takes_from_the_whirl(paper):
    dry = freewhirl.steady_state(*typed({**paper, "drag_coefficient": 0.0}))
    wet = freewhirl.steady_state(*typed(paper))
    assert np.max(np.abs(wet["whirl"][0])) < np.max(np.abs(dry["whirl"][0]))
    assert wet["change"] < 1e-10 and wet["iterations"] > 1


def test_a_whirl_reaching_the_wall_is_out_of_scope(paper):
    # 4-in eccentricity in a vertical hole: the rigid whirl of radius (m_p/M) 4 in would pass the 1.25-in tool-joint
    # clearance
    result = solve_point({**paper, "eccentricity": 4 * 0.0254}, "free-whirl")
    assert result.status == "out_of_scope" and "tool joint" in result.message
    assert "max_normal_stress" not in result.values


def test_with_the_joints_mass_the_string_whirls_about_its_centre_of_mass(paper):
    # Newton for the whole string, nothing holding it (no drag, clear of the wall): the turning load on the body,
    # m_p ε Ω² L, balances the centrifugal force of the whole mass on its centre's circle, so the mass-weighted mean
    # deflection (∫ M u dx + Σ m_j u(x_j))/(M L + Σ m_j) is a circle of radius m_p ε L/(M L + Σ m_j), opposite the
    # unbalance; the joints lag the body, so the string bends a little (the uniform circle without them: above)
    state = freewhirl.steady_state(*typed({**paper, "drag_coefficient": 0.0}))
    props, L = state["props"], state["L"]
    m_j = state["joint_mass"]
    assert m_j > 40.0
    x, whirl = state["x"], state["whirl"][0]
    spacing = x[1] - x[0]
    body = np.sum(whirl[:-1]) * spacing  # the periodic trapezoid rule: exact for the modes' trigonometric sums
    joints = mode_shapes([0.0, L / 3, 2 * L / 3], L, state["n"].size) @ state["basis"] @ state["whirl_modal"]
    total = props["mass_per_length"] * L + 3 * m_j
    centre = (props["mass_per_length"] * body + m_j * np.sum(joints)) / total
    radius = props["pipe_mass"] * paper["eccentricity"] * L / total
    assert abs(centre) == pytest.approx(radius, rel=1e-9)
    assert np.max(np.abs(whirl)) > abs(centre) > np.min(np.abs(whirl))  # bent: not one circle
