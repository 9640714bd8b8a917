"""Design points shared by the solver tests."""

from pathlib import Path

import numpy as np
import pytest

from study import config
from study.solvers import periodic

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
