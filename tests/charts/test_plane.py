"""The rotary speed × axial load plane (study.charts.plane): worst case over ok points, cell outlines."""

import numpy as np

from study.charts.plane import answered_values, cell_boundary, plane


def test_a_single_cell_is_outlined_by_its_inner_edges_only():
    over = np.array([[True, False], [False, False]])  # rows: load, columns: speed
    xedges, yedges = np.array([0.0, 1.0, 2.0]), np.array([10.0, 20.0, 30.0])
    segments = sorted(cell_boundary(over, xedges, yedges))
    assert segments == sorted([((1.0, 10.0), (1.0, 20.0)),  # right edge of the cell
                               ((0.0, 20.0), (1.0, 20.0))])  # top edge; the plot's own edges are not drawn


def test_a_region_is_outlined_as_a_staircase_without_interpolation():
    over = np.array([[False, False, True], [False, True, True]])
    segments = cell_boundary(over, np.arange(4.0), np.arange(3.0))
    assert len(segments) == 3  # two vertical steps and one horizontal: the staircase
    assert all(a[0] == b[0] or a[1] == b[1] for a, b in segments)  # every segment follows a cell edge
    assert cell_boundary(np.zeros((3, 3), bool), np.arange(4.0), np.arange(4.0)) == []


def test_the_worst_case_is_taken_over_ok_points_only(study):
    ds = study.copy(deep=True)
    not_ok = ds.status != 0
    ds["max_normal_stress"] = ds.max_normal_stress.where(~not_ok, 1e12)  # another branch's value at failed points
    p = plane(ds)
    assert p.reduced == ["restitution", "mud_density"]
    worst = p.reduce(answered_values(ds, "max_normal_stress"), "max")  # here the answered points are the ok ones
    # 5,000 lbf, 300 rpm: no span at e = 0.8, so the worst ok point is at e = 0.2 (the heavier mud)
    expected = float(study.max_normal_stress.sel(restitution=0.2).isel(axial_tension=0, rotary_speed=-1).max())
    assert worst[0, -1] == expected and worst.max() < 1e12
    # 40,000 lbf, 300 rpm: every point ok; the worst is e = 0.8
    assert worst[-1, -1] == float(study.max_normal_stress.isel(axial_tension=-1, rotary_speed=-1).max())
