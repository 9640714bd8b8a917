"""The free whirl (study.solvers.freewhirl): the reference model's scene clear of the wall, in closed form."""

from pathlib import Path

import numpy as np
import pytest

from study import config
from study.physics import section
from study.solvers import freewhirl, solve_point

ROOT = Path(__file__).resolve().parents[2]
DEG = np.pi / 180


@pytest.fixture(scope="module")
def paper():
    return config.load(ROOT / "configs" / "paper.toml").point()


def test_the_sag_bends_the_rotating_pipe_like_a_beam_column_under_its_weight(paper):
    # source: Timoshenko & Gere, Theory of Elastic Stability, §1.11 (Roark's beam-column tables): a pinned
    # beam-column of length L under a uniform load w and tension T has its largest moment at midspan,
    # M = (w / lambda^2) (1 - 1 / cosh(lambda L / 2)), lambda^2 = T / EI. With no eccentricity the pipe does not
    # whirl; every fibre passes through that bend once a revolution: the alternating stress is M r_o / I.
    inputs = {**paper, "eccentricity": 0.0, "inclination": 5 * DEG}
    result = solve_point(inputs, "free-whirl")
    assert result.status == "ok", result.message
    state = freewhirl.steady_state(inputs)
    props = state["props"]
    ei, tension, L, w = props["bending_stiffness"], props["effective_tension"], state["L"], state["side_load"]
    lam = np.sqrt(tension / ei)
    moment = w / lam**2 * (1.0 - 1.0 / np.cosh(lam * L / 2.0))
    r_o, r_i = paper["outer_diameter"] / 2, paper["inner_diameter"] / 2
    expected = moment * r_o / float(section.second_moment_of_area(r_o, r_i))
    assert result.values["alternating_bending_stress"] == pytest.approx(expected, rel=1e-4)
    assert result.values["max_bending_stress"] == pytest.approx(expected, rel=1e-4)  # nothing else bends it
    assert result.values["alternating_bending_stress_x"] == pytest.approx(L / 2, rel=1e-2)


def test_without_drag_the_whirl_is_jeffcotts_on_every_mode(paper):
    # source: the Jeffcott rotor (Vance 1988 eq. 2.11): each mode's synchronous response to the rotating unbalance
    # m_p eps Omega^2 is eps_n / (omega_n^2 - Omega^2) with eps_n its modal share (4 / (n pi) of a uniform load);
    # with no drag the modal sum at midspan is that series, summed here independently
    inputs = {**paper, "drag_coefficient": 0.0}
    state = freewhirl.steady_state(inputs)
    props, Om, L = state["props"], paper["rotary_speed"], state["L"]
    n = np.arange(1, 200, 2, dtype=float)
    omega = np.ravel(section.natural_frequencies(L, props["bending_stiffness"], props["effective_tension"],
                                                 props["mass_per_length"], n))
    eps_n = props["pipe_mass"] / props["mass_per_length"] * paper["eccentricity"] * Om**2 * 4 / (n * np.pi)
    midspan = np.sum(eps_n / (omega**2 - Om**2) * np.sin(n * np.pi / 2))
    i = np.argmin(np.abs(state["x"] - L / 2))
    assert abs(state["whirl"][0][i]) == pytest.approx(abs(midspan), rel=1e-6)


def test_the_mud_drag_only_takes_from_the_whirl(paper):
    dry = freewhirl.steady_state({**paper, "drag_coefficient": 0.0})
    wet = freewhirl.steady_state(paper)
    assert np.max(np.abs(wet["whirl"][0])) < np.max(np.abs(dry["whirl"][0]))
    assert wet["change"] < 1e-10 and wet["iterations"] > 1


def test_a_whirl_reaching_the_wall_is_out_of_scope(paper):
    # 4-in eccentricity in a vertical hole: the free whirl would pass the 1.25-in tool-joint clearance
    result = solve_point({**paper, "eccentricity": 4 * 0.0254}, "free-whirl")
    assert result.status == "out_of_scope" and "tool joint" in result.message
    assert "max_normal_stress" not in result.values
