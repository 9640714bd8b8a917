"""One point, seen (study.charts.point, ``study point --plot``): the reference model's motion at a bouncing point of
the default study (200 rpm, 5 000 lbf: the reference model answers there, whirl bouncing; tests/test_table.py)."""

from pathlib import Path

import numpy as np
import pytest

from study.charts import figure_labels
from study.charts.point import point_chart
from study.cli import main
from study.config import load, parse_set

ROOT = Path(__file__).resolve().parents[2]
DEFAULT = str(ROOT / "configs" / "default.toml")
SETS = ['load.rotary_speed="200 rpm"', 'load.axial_tension="5000 lbf"']


def test_the_orbit_stays_inside_the_wall_at_a_tool_joint_and_the_forces_are_drawn(tmp_path):
    inputs = load(DEFAULT, parse_set(SETS)).point()
    chart = point_chart(inputs)
    orbit, forces, shape = chart.figure.axes[:3]
    (wall,) = [ln for ln in orbit.get_lines() if ln.get_gid() == "wall"]
    radius = np.hypot(wall.get_xdata(), wall.get_ydata())
    # the most-touching point is a tool joint: its clearance is (hole − tool joint diameter)/2, in inches
    joint = (inputs["hole_diameter"] - inputs["tool_joint_diameter"]) / 2 / 0.0254
    assert radius == pytest.approx(joint, rel=1e-9)
    centre = [ln for ln in orbit.get_lines() if ln.get_gid() != "wall"][0]
    reach = np.hypot(centre.get_xdata(), centre.get_ydata())
    assert reach.max() <= joint * 1.01  # inside the wall but for the Hertz approach
    peaks = [np.max(ln.get_ydata()) for ln in forces.get_lines()]
    assert peaks and max(peaks) > 100.0  # it bounces: contact forces of thousands of lbf
    assert "whirl bouncing" in figure_labels(chart.figure)["titles"][-1]
    path = tmp_path / "point.png"
    assert main(["point", DEFAULT, *sum([["--set", s] for s in SETS], []), "--plot", str(path)]) == 0
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert main(["point", DEFAULT, "--plot", str(tmp_path / "point.gif")]) == 2  # a format it cannot write
