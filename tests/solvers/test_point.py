"""The typed design point (study.solvers.model.point): built once per point by solve_point and passed down."""

from pathlib import Path

import pytest

from study import config
from study.solvers import solve_point
from study.solvers.model import point as point_module
from study.solvers.model.options import SeriesOptions
from study.solvers.model.point import DesignPoint
from study.solvers.model.scene import Scene

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def paper():
    # configs/paper.toml: the paper's example at its printed 345-ft span (the methods that take a span have one)
    return config.load(ROOT / "configs" / "paper.toml").point()


def test_the_point_holds_the_scene_and_every_option_of_its_inputs(paper):
    point = DesignPoint.from_inputs({**paper, "time_modes": 3, "harmonics": 200, "check_tolerance": 0.05})
    assert point.scene == Scene.from_inputs(paper)
    assert (point.time.time_modes, point.series.harmonics, point.check.check_tolerance) == (3, 200, 0.05)
    with pytest.raises(TypeError):  # read-only: a method cannot change the point under another
        point.inputs["restitution"] = 0.9
    changed = point.with_series(SeriesOptions(series_tolerance=0.01))
    assert changed.series.series_tolerance == 0.01 and changed.inputs["series_tolerance"] == 0.01
    assert changed.scene is point.scene and point.series.series_tolerance is None


def test_a_bad_choice_names_the_field(paper):
    with pytest.raises(ValueError, match="time_integrator = 'leapfrog'; allowed: auto, event"):
        DesignPoint.from_inputs({**paper, "time_integrator": "leapfrog"})


@pytest.mark.parametrize("method", ["core", "fast", "series", "periodic", "damped", "sdof", "time-domain",
                                    "free-whirl"])
def test_solve_point_builds_the_scene_once(paper, method, monkeypatch):
    # issue 35: the scene of a point is built once, by the design point solve_point passes to the method, the limits
    # and the gate (each method built its own at its entry before, and solve_point another for the gate)
    builds = []
    build = Scene.from_inputs
    monkeypatch.setattr(Scene, "from_inputs", classmethod(lambda cls, inputs: builds.append(1) or build(inputs)))
    result = solve_point({**paper, "time_revolutions": 1, "time_check_periodic": False}, method)
    assert result.status != "failed", result.message
    assert len(builds) == 1, method
    assert point_module.Scene is Scene  # the builder patched is the one the point calls
