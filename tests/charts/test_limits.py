"""Stress, contact force and fatigue maps with their limits (study.charts.limits), on the synthetic study."""

import numpy as np
import pytest
import xarray as xr
from matplotlib.collections import LineCollection, QuadMesh
from matplotlib.colors import LogNorm

from study.charts import figure_labels
from study.charts.limits import contact_force_map, fatigue_life_map, stress_limit_maps
from study.charts.plane import MISSING_LABEL, PARTIAL_LABEL, ROUGH_LABEL, cell_boundary, plane
from study.solvers.model.result import STATUS_CODES

PSI = 6894.757293168361
LBF = 4.4482216152605
E75_YIELD_PSI = 75_000  # API Spec 5D Table 6.3: grade E-75 minimum yield strength


def panels(figure):
    return [ax for ax in figure.axes if ax.get_label() != "<colorbar>"]


def mesh_values(ax, shape):
    (mesh,) = [c for c in ax.collections if isinstance(c, QuadMesh)]
    return mesh, np.ma.masked_invalid(mesh.get_array()).reshape(shape)


def outline(ax, colour=None):
    return [seg for c in ax.collections if isinstance(c, LineCollection) for seg in c.get_segments()]


def test_one_figure_worst_case_in_psi_with_the_yield_outline_where_the_stress_passes_75_ksi(study):
    (chart,) = stress_limit_maps(study)
    normal, alternating = panels(chart.figure)
    shape = (study.sizes["axial_tension"], study.sizes["rotary_speed"])
    _, values = mesh_values(normal, shape)
    worst = study.max_normal_stress.max(["restitution", "mud_density"]).transpose("axial_tension", "rotary_speed")
    np.testing.assert_allclose(values, worst.values / PSI)
    # the outline is the boundary of the cells whose worst stress is over E-75's yield, computed from the stress
    p = plane(study)
    over = worst.values / PSI > E75_YIELD_PSI
    assert over.any() and not over.all()
    expected = cell_boundary(over, p.xedges, p.yedges)
    drawn = outline(normal)
    assert sorted(map(lambda s: tuple(map(tuple, s)), drawn)) == sorted(expected)
    labels = figure_labels(chart.figure)
    assert "maximum normal stress [psi]" in labels["ylabels"] and "alternating bending stress [psi]" in labels["ylabels"]
    assert "worst case (highest stress) over restitution and mud density" in labels["titles"][-1]
    assert any("E-75 75,000 psi" in t for t in labels["legend"])
    assert outline(alternating)  # the endurance limit is passed somewhere in this study


def test_failed_points_are_hatched_not_coloured(study):
    ds = study.copy(deep=True)
    ds["status"][dict(axial_tension=1, rotary_speed=3)] = 3  # no span at every restitution and mud density
    (chart,) = stress_limit_maps(ds)
    _, values = mesh_values(panels(chart.figure)[0], (4, 13))
    assert values.mask[1, 3] and values.mask.sum() == 1
    assert MISSING_LABEL in figure_labels(chart.figure)["legend"]


def test_contact_force_in_lbf(study):
    (chart,) = contact_force_map(study)
    _, values = mesh_values(panels(chart.figure)[0], (4, 13))
    speeds = study.rotary_speed.values * 60 / (2 * np.pi)
    assert values[3, 0] == pytest.approx(100 * speeds[0] * 1.8)  # made-up 100 lbf/rpm x (1 + e), e = 0.8
    assert "peak contact force [lbf]" in figure_labels(chart.figure)["ylabels"]


def test_the_force_caption_counts_the_points_whose_force_is_the_strikes_local_model(study):
    # output local_strike_force (docs/reference_model.md §2.3): 1 where the reference model stated the local model's
    # force, 0 its modes' own, NaN where another method answered; the caption counts them, silent where none is local
    assert "local model" not in contact_force_map(study)[0].caption
    ds = study.copy(deep=True)
    flag = xr.full_like(ds["peak_contact_force"], np.nan)
    flag[dict(axial_tension=0, rotary_speed=slice(0, 3))] = 1.0  # 3 x 2 x 2 = 12 local
    flag[dict(axial_tension=1, rotary_speed=0)] = 0.0  # 4 the modes' own
    ds["local_strike_force"] = flag
    assert "At 12 of the 16 points the reference model answered, the force is that of the strikes' local model" in (
        contact_force_map(ds)[0].caption)
    ds["local_strike_force"] = xr.where(flag == 1.0, 0.0, flag)
    assert "local model" not in contact_force_map(ds)[0].caption


def test_fatigue_life_in_hours_on_a_log_scale_with_the_curve_named(study):
    (chart,) = fatigue_life_map(study, target_hours=500.0)
    ax = panels(chart.figure)[0]
    mesh, values = mesh_values(ax, (4, 13))
    assert isinstance(mesh.norm, LogNorm)
    shortest = study.fatigue_life.min(["restitution", "mud_density"]).transpose("axial_tension", "rotary_speed") / 3600
    np.testing.assert_allclose(values, shortest.values)
    title = figure_labels(chart.figure)["titles"][-1]
    assert "DNV-RP-C203 B1" in title and "Goodman" in title and "shortest life over restitution" in title
    p = plane(study)
    assert sorted(map(lambda s: tuple(map(tuple, s)), outline(ax))) == \
        sorted(cell_boundary(shortest.values < 500.0, p.xedges, p.yedges))


def test_the_fatigue_map_says_how_the_damage_was_counted(study):
    # study.solvers.model.utilisation.add_limits: the reference model's own rainflow count where it answered, one
    # cycle per revolution elsewhere; the synthetic study's points are all "fast", then two of them "reference"
    title = figure_labels(fatigue_life_map(study)[0].figure)["titles"][-1]
    assert "1 cycle(s) of the alternating stress per revolution" in title and "rainflow" not in title
    mixed = study.copy()
    method = mixed["method"].values.astype("<U16")
    method.flat[:2] = "reference"
    mixed["method"] = (mixed["method"].dims, method)
    title = figure_labels(fatigue_life_map(mixed)[0].figure)["titles"][-1]
    assert "at the reference model's 2 points over its stress history counted by rainflow (ASTM E1049)" in title
    assert "elsewhere 1 cycle(s) of the alternating stress per revolution" in title


@pytest.mark.parametrize("draw_map", [stress_limit_maps, fatigue_life_map, contact_force_map])
def test_each_maps_title_lies_within_its_figure(study, draw_map):
    # the title and its context wrapped to the figure's width (study.charts.design.figure_title): no line runs past
    # the figure's edges, where the saved image would cut it
    for chart in draw_map(study):
        fig = chart.figure
        fig.canvas.draw()
        box = fig._suptitle.get_window_extent()
        assert box.x0 >= 0 and box.x1 <= fig.bbox.width, (chart.name, box, fig.bbox.width)


def test_without_the_plane_the_stresses_are_lines(study):
    line = study.isel(axial_tension=[0])
    charts = stress_limit_maps(line)
    assert charts and not [c for ax in charts[0].figure.axes for c in ax.collections if isinstance(c, QuadMesh)]
    assert fatigue_life_map(line) == [] and contact_force_map(line) == []


def test_cells_where_only_some_points_are_ok_are_marked(study):
    from matplotlib.collections import PolyCollection

    (chart,) = stress_limit_maps(study)
    ax = panels(chart.figure)[0]
    marked = [c for c in ax.collections if isinstance(c, PolyCollection) and c.get_hatch() == ".."]
    (cells,) = marked
    # 5,000 lbf above 200 rpm: no span at e = 0.8 -> the five cells 220-300 rpm show the worst of e = 0.2
    lefts = sorted(round(float(p.vertices[:, 0].min())) for p in cells.get_paths())
    assert lefts == [210, 230, 250, 270, 290]
    assert PARTIAL_LABEL in figure_labels(chart.figure)["legend"]


def test_a_point_not_converged_is_drawn_with_its_value_veiled_and_its_error_written_in(study):
    """Issue 34: the bouncing region was blank (ok points only); an answer with its error stated is drawn."""
    from matplotlib.collections import PolyCollection

    ds = study.copy(deep=True)
    ds["error_estimate"] = xr.full_like(ds.max_normal_stress, np.nan)
    where = dict(axial_tension=2, rotary_speed=5, restitution=0, mud_density=1)
    ds["status"][where] = STATUS_CODES["not_converged"]
    ds["error_estimate"][where] = 0.38
    ds["max_normal_stress"][where] = 120_000 * PSI  # the cell's worst, from the point not converged
    (chart,) = stress_limit_maps(ds)
    normal = panels(chart.figure)[0]
    _, values = mesh_values(normal, (4, 13))
    assert values[2, 5] == pytest.approx(120_000) and not values.mask.any()
    veiled = [c for c in normal.collections if isinstance(c, PolyCollection) and c.get_hatch() == "//"]
    (cells,) = veiled
    assert len(cells.get_paths()) == 1
    assert [t.get_text() for t in normal.texts if t.get_gid() == "error estimate"] == ["±38%"]
    assert ROUGH_LABEL in figure_labels(chart.figure)["legend"]
    # a failed point (status other than ok and not_converged) is never drawn, whatever value it carries
    ds["status"][where] = STATUS_CODES["failed"]
    (chart,) = stress_limit_maps(ds)
    _, values = mesh_values(panels(chart.figure)[0], (4, 13))
    assert values[2, 5] < 120_000


def test_the_fatigue_scale_shows_its_target_even_where_every_life_is_far_above_it(study):
    (chart,) = fatigue_life_map(study, target_hours=1.0)  # every life of the synthetic study is far above 1 h
    mesh, values = mesh_values(panels(chart.figure)[0], (4, 13))
    assert values.min() > 100.0
    assert mesh.norm.vmin <= 1.0 <= mesh.norm.vmax


@pytest.mark.parametrize("draw_map", [stress_limit_maps, fatigue_life_map, contact_force_map])
def test_each_map_s_caption_names_every_legend_entry_and_no_outline_it_does_not_draw(study, draw_map):
    ds = study.copy(deep=True)
    ds["error_estimate"] = xr.full_like(ds.max_normal_stress, np.nan)
    ds["status"][dict(axial_tension=2, rotary_speed=5, restitution=0, mud_density=1)] = STATUS_CODES["not_converged"]
    for data in (study, ds):
        (chart,) = draw_map(data)
        legend = figure_labels(chart.figure)["legend"]
        assert legend and all(entry in chart.caption for entry in legend), (legend, chart.caption)
        for words in ("outline", "veiled", "dotted", "hatched grey"):  # said only where drawn
            assert (words in chart.caption) == any(words in entry for entry in legend), words
