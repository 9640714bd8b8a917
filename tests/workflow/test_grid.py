"""The design grid (study.workflow.grid): C-order points, chunks, point keys and the code hash."""

import shutil
from pathlib import Path

import numpy as np
import pytest

import study
from study.workflow.grid import Grid, auto_chunk_size, chunk_key, chunks, code_hash, point_key

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


def test_grid_without_axes_is_one_point():
    grid = Grid(BASE, {})
    assert grid.size == 1 and grid.point(0) == BASE


def test_point_key_depends_on_every_input_and_nothing_else():
    a = point_key({"x": 1.0, "y": "gap_flow"}, "code")
    assert a == point_key({"y": "gap_flow", "x": 1.0}, "code")  # order does not matter
    assert a != point_key({"x": 1.0 + 1e-15, "y": "gap_flow"}, "code")  # any change of a value does
    assert a != point_key({"x": 1.0, "y": "potential_flow"}, "code")
    assert a != point_key({"x": 1.0, "y": "gap_flow"}, "other code")  # and a change of the code


def test_grid_point_keys_are_the_keys_of_its_points_in_c_order():
    grid = Grid({**BASE, "method": "core"}, {"restitution": AXES["restitution"], "method": np.array(["core", "sdof"], dtype=object),
                 "rotary_speed": AXES["rotary_speed"]})
    keys = grid.point_keys("code")
    assert keys.tolist() == [point_key(grid.point(i), "code") for i in range(grid.size)]
    assert len(set(keys.tolist())) == grid.size
    assert Grid(BASE, {}).point_keys("code").tolist() == [point_key(BASE, "code")]


def test_a_changed_axis_value_changes_only_the_keys_of_its_points():
    grid = Grid(BASE, AXES)
    changed = Grid(BASE, {**AXES, "rotary_speed": np.array([1.0, 2.5, 3.0])})
    same = np.isin(changed.point_keys("c"), grid.point_keys("c"))
    assert same.tolist() == [True, True, False, False, True, True]  # rotary_speed 2.5: points 2 and 3


def test_code_hash_changes_with_a_solver_source_and_not_with_other_files(tmp_path):
    # The fault of issue 19: a solver edited without a version bump must change every key.
    package = Path(study.__file__).parent
    copy = tmp_path / "study"
    shutil.copytree(package, copy, ignore=shutil.ignore_patterns("__pycache__"))
    assert code_hash(str(copy)) == code_hash()  # the same sources, wherever they are
    (copy / "cli.py").write_text((copy / "cli.py").read_text() + "\n# a comment\n")
    assert code_hash(str(copy)) == code_hash()  # the command line does not compute a point
    core = copy / "solvers" / "methods" / "core.py"
    core.write_text(core.read_text().replace('"peak_contact_force": peak,', '"peak_contact_force": 2.0 * peak,'))
    assert code_hash(str(copy)) != code_hash()


def test_chunk_key_names_the_points_it_holds():
    keys = Grid(BASE, AXES).point_keys("c")
    assert chunk_key(keys[:3]) == chunk_key(keys[:3].copy()) != chunk_key(keys[1:4])


@pytest.mark.parametrize("size, expected", [(10, 8), (352, 11), (1404, 44), (10**6, 512)])
def test_auto_chunk_size_depends_on_the_grid_alone(size, expected):
    assert auto_chunk_size(size) == expected


def test_chunks_are_runs_of_the_given_indices():
    indices = np.array([0, 3, 4, 7, 9])
    assert [c.tolist() for c in chunks(indices, 2)] == [[0, 3], [4, 7], [9]]


@pytest.mark.parametrize("size, chunk_size", [(1408, 44), (100, 8), (7, 3), (103_424, 512)])
def test_chunks_taper_over_the_last_quarter_and_cover_every_index_once(size, chunk_size):
    indices = np.arange(size) * 3
    assert [r.size for r in chunks(indices, chunk_size)] == [r.size for r in np.array_split(  # a chunk size asked
        indices, range(chunk_size, size, chunk_size))]  # for is kept
    runs = list(chunks(indices, chunk_size, taper=True))
    np.testing.assert_array_equal(np.concatenate(runs), indices)
    last = size - size // 4  # the last quarter's points go in chunks a quarter the size
    starts = np.cumsum([0] + [r.size for r in runs[:-1]])
    for start, run in zip(starts, runs):
        assert run.size <= (chunk_size if start < last else max(1, chunk_size // 4))
    assert runs[0].size == min(chunk_size, size)


def test_points_of_a_stepped_range_are_those_points():
    # a range with a step (every k-th point) gives those points, not the first len(range) ones
    grid = Grid(base={"a": 1.0}, axes={"x": np.arange(4.0), "y": np.arange(3.0)})
    picked = list(grid.points(range(1, 12, 5)))
    assert [(p["x"], p["y"]) for p in picked] == [(0.0, 1.0), (2.0, 0.0), (3.0, 2.0)]
