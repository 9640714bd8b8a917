"""The design grid (study.workflow.grid): C-order points, chunks, and point ids."""

import numpy as np
import pytest

from study.workflow.grid import Grid, auto_chunk_size, chunk_key, point_id

AXES = {"rotary_speed": np.array([1.0, 2.0, 3.0]), "restitution": np.array([0.2, 0.8])}
BASE = {"rotary_speed": 9.0, "restitution": 0.5, "axial_tension": 1e4}


def test_points_run_in_c_order_over_the_axes():
    grid = Grid(BASE, AXES)
    assert grid.shape == (3, 2) and grid.size == 6 and grid.dims == ("rotary_speed", "restitution")
    points = [grid.point(i) for i in range(grid.size)]
    assert [(p["rotary_speed"], p["restitution"]) for p in points] == [
        (1.0, 0.2), (1.0, 0.8), (2.0, 0.2), (2.0, 0.8), (3.0, 0.2), (3.0, 0.8)]
    assert all(p["axial_tension"] == 1e4 for p in points)
    assert type(points[0]["rotary_speed"]) is float


@pytest.mark.parametrize("size, chunk", [(6, 4), (6, 6), (6, 1), (6, 100)])
def test_chunks_cover_the_grid_once(size, chunk):
    grid = Grid(BASE, AXES)
    covered = [i for c in grid.chunks(chunk) for i in c]
    assert covered == list(range(size))


def test_grid_without_axes_is_one_point():
    grid = Grid(BASE, {})
    assert grid.size == 1 and grid.point(0) == BASE


def test_point_id_depends_on_every_input_and_nothing_else():
    a = point_id({"x": 1.0, "y": "gap_flow"})
    assert a == point_id({"y": "gap_flow", "x": 1.0})  # order does not matter
    assert a != point_id({"x": 1.0 + 1e-15, "y": "gap_flow"})  # any change of a value does
    assert a != point_id({"x": 1.0, "y": "potential_flow"})


def test_chunk_key_changes_when_an_input_changes():
    grid = Grid(BASE, AXES)
    other = Grid({**BASE, "axial_tension": 2e4}, AXES)
    assert chunk_key(grid, range(0, 3)) != chunk_key(other, range(0, 3))
    assert chunk_key(grid, range(0, 3)) == chunk_key(Grid(dict(BASE), dict(AXES)), range(0, 3))


@pytest.mark.parametrize("size, workers, expected", [(10, 2, 16), (1404, 2, 88), (10**6, 2, 512)])
def test_auto_chunk_size_balances_and_amortises(size, workers, expected):
    assert auto_chunk_size(size, workers) == expected


def test_points_of_a_stepped_range_are_those_points():
    # a range with a step (every k-th point) gives those points, not the first len(range) ones
    grid = Grid(base={"a": 1.0}, axes={"x": np.arange(4.0), "y": np.arange(3.0)})
    picked = list(grid.points(range(1, 12, 5)))
    assert [(p["x"], p["y"]) for p in picked] == [(0.0, 1.0), (2.0, 0.0), (3.0, 2.0)]
