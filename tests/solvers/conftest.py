"""Design points shared by the solver tests."""

from pathlib import Path

import numpy as np
import pytest

from study import config
from study.solvers.methods import periodic

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def paper_inputs():
    """The SI inputs of the paper's example (configs/paper.toml, its fixed values)."""
    return config.load(ROOT / "configs" / "paper.toml").point()


@pytest.fixture(scope="session")
def fixed_span(paper_inputs):
    """A refined root of condition 2 that satisfies its own T_L-curvature fixed point (100 rpm, both walls,
    prescribed closure; the first above 30 m): a span to compare methods at, since the paper's inputs
    have no valid span."""
    inputs = {**paper_inputs, "rotary_speed": 100 * np.pi / 30, "impact_pattern": "alternating",
              "closure": "prescribed"}
    scene = periodic.make_scene(inputs)
    impact = periodic.first_consistent_root(scene, periodic.Options(modes=15, min_span=9.0), longer_than=30.0)
    assert impact is not None, "no refined root without problems above 30 m"
    return inputs, scene, impact


@pytest.fixture(scope="session")
def default_point():
    """``default_point(rpm, klbf, restitution, ppg, flow)``: a point of configs/default.toml's grid (8-degree hole,
    straight), its swept inputs in the config's units, the SI inputs returned (study.config.Study.point). The joints'
    eccentricities aligned in three joints, the reading the figures of test_modes.py and test_replay.py were measured
    in (the default study's is 90° in four)."""
    study = config.load(ROOT / "configs" / "default.toml",
                        {"pipe.eccentricity_turn": "aligned", "contact.section_length": "93 ft"})

    def point(rpm, klbf, restitution, ppg, flow):
        return study.point(rotary_speed=rpm * np.pi / 30, axial_tension=klbf * 4448.2216152605,
                           restitution=restitution, mud_density=ppg * 119.826427, mud_flow_velocity=flow * 0.3048)

    return point


@pytest.fixture(scope="session")
def kernel_drag():
    """f(sy, z): the mud drag's part of the compiled integrator's right-hand side (whirl_kernel.rhs without its
    linear modal terms) at state z: the modes' drag accelerations (2N,) [m/s²], the right-hand side with the drag
    less without it (sy's drag coefficient 0), and the drag's power [W]."""
    from study.solvers.kernels import whirl_kernel

    def drag(sy, z):
        N, P = sy[0].size, sy[6].shape[0]
        no_drag = sy[12].copy()
        no_drag[0] = 0.0
        parts = []
        for system in (sy, sy[:12] + (no_drag,) + sy[13:]):
            out = np.zeros(4 * N + 4)
            whirl_kernel.rhs(0.0, z, np.zeros(P), out, np.zeros((P, 3)), np.zeros((P, 2)),
                             whirl_kernel.drag_scratch(N, sy[5].size, sy[4].dtype), system, False)
            parts.append(out)
        return parts[0][2 * N:4 * N] - parts[1][2 * N:4 * N], parts[0][4 * N + 2]

    return drag
