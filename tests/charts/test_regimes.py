"""The regime map (study.charts.regimes): regimes from the output or the status, the most severe per cell."""

import numpy as np
from matplotlib.collections import QuadMesh

from study.charts import figure_labels
import xarray as xr

from study.charts.regimes import SEVERITY, lift_off_map, regime_map, regimes
from study.solvers.model.result import REGIMES, STATUS


def test_regimes_are_read_from_the_status_where_no_method_gives_one(build_study):
    ds = build_study(status={"no_impact": lambda g: g["rotary_speed"] < 100,
                             "chattering": lambda g: g["rotary_speed"] > 250,
                             "period_doubling": lambda g: (g["rotary_speed"] == 200) & (g["restitution"] == 0.8),
                             "no_span": lambda g: g["rotary_speed"] == 160})
    codes, from_status = regimes(ds)
    assert from_status
    at = dict(axial_tension=0, restitution=1, mud_density=0)
    speeds = list(np.round(ds.rotary_speed.values * 30 / np.pi))
    assert codes.isel(rotary_speed=speeds.index(60), **at) == REGIMES["no_contact"]
    assert codes.isel(rotary_speed=speeds.index(120), **at) == REGIMES["periodic_impacts"]  # ok
    assert codes.isel(rotary_speed=speeds.index(200), **at) == REGIMES["unstable"]
    assert codes.isel(rotary_speed=speeds.index(300), **at) == REGIMES["bouncing"]
    assert np.isnan(codes.isel(rotary_speed=speeds.index(160), **at))  # no span: undetermined
    (chart,) = regime_map(ds)
    (mesh,) = [c for ax in chart.figure.axes for c in ax.collections if isinstance(c, QuadMesh)]
    labels = figure_labels(chart.figure)
    present = [t.split(" (")[0] for t in labels["legend"][1:] if "cells)" in t and "undetermined" not in t]
    index = np.ma.masked_invalid(mesh.get_array()).reshape(4, 13)
    # 200 rpm: unstable at e = 0.8 outranks the periodic impacts at e = 0.2 in every load row
    assert {present[int(v)] for v in index[:, speeds.index(200)]} == {"unstable"}
    assert index.mask[:, speeds.index(160)].all()
    assert "regime read from the status" in labels["titles"][-1]
    assert "most severe regime" in labels["titles"][-1]


def test_a_regime_output_is_used_where_present(study):
    ds = study.copy()
    ds["regime"] = (list(study.status.dims), np.full(study.status.shape, float(REGIMES["backward_whirl"])),
                    {"units": "1", "flag_values": np.array(list(REGIMES.values()), float),
                     "flag_meanings": " ".join(REGIMES)})
    codes, from_status = regimes(ds)
    assert not from_status and (codes == REGIMES["backward_whirl"]).all()
    (chart,) = regime_map(ds)
    labels = figure_labels(chart.figure)
    assert "backward whirl (52 cells)" in labels["legend"] and "regime read" not in labels["titles"][-1]


def test_cells_where_two_motions_coexist_are_outlined(study):
    # output coexisting_motion (study.solvers.methods.sliding_parts.second_motion, auto._coexisting): 1 where the pipe
    # lying on the wall has a bouncing or chattering motion beside it; set at one point of the 120 rpm, lowest-load
    # cell and at every point of the 300 rpm column (4 cells): 5 cells outlined, named in the legend with the count
    from matplotlib.collections import PolyCollection

    from study.charts.regimes import COEXISTING_LABEL, COEXISTING_STYLE

    ds = study.copy()
    flag = np.zeros(study.status.shape)
    speeds = list(np.round(ds.rotary_speed.values * 30 / np.pi))
    dims = list(study.status.dims)
    at = tuple(speeds.index(120) if d == "rotary_speed" else 0 for d in dims)
    flag[at] = 1.0
    flag[tuple(speeds.index(300) if d == "rotary_speed" else slice(None) for d in dims)] = 1.0
    ds["coexisting_motion"] = (dims, flag, {"units": "1"})
    (chart,) = regime_map(ds)
    assert f"{COEXISTING_LABEL} (5 cells)" in figure_labels(chart.figure)["legend"]
    outlined = [c for c in chart.figure.axes[0].collections if isinstance(c, PolyCollection)
                and c.get_linestyle()[0][1] is not None and c.get_linewidth()[0] == COEXISTING_STYLE["linewidth"]]
    assert len(outlined) == 1 and len(outlined[0].get_paths()) == 5
    assert "kick throws it" in chart.caption
    ds["coexisting_motion"] = (dims, np.zeros(study.status.shape), {"units": "1"})  # none: no outline
    assert not any(COEXISTING_LABEL in t for t in figure_labels(regime_map(ds)[0].figure)["legend"])


def test_every_regime_has_a_severity_and_the_codes_do_not_clash_with_the_status():
    assert set(SEVERITY) == set(REGIMES) and len(set(REGIMES.values())) == len(REGIMES)
    assert not set(REGIMES) & set(STATUS) - {"unstable"}


def test_the_lift_off_map_shows_the_lowest_lift_off_eccentricity_and_outlines_where_the_configured_one_lifts(study):
    # study.charts.regimes.lift_off_map on a synthetic dataset: ε_lift falling with the speed, 1 in × (60/n)^1.86
    # (1 in at 60 rpm, 0.05 in at 300 rpm), 0.9 of it at the second mud density: the map shows the minimum over the
    # other inputs, in inches, each cell's value written in it; the configured 0.1 in is in the legend and the cells
    # below it outlined; without the output no chart
    ds = study.copy()
    n = ds.rotary_speed * 30 / np.pi
    lift = 0.0254 * (60 / n) ** 1.86 * (1 + 0 * ds.axial_tension + 0 * ds.restitution)
    lift = lift * xr.where(ds.mud_density == ds.mud_density[-1], 0.9, 1.0)
    ds["lift_off_eccentricity"] = lift.transpose(*ds.status.dims).astype(float).assign_attrs(units="m")
    ds["eccentricity"] = xr.full_like(ds.lift_off_eccentricity, 0.1 * 0.0254).assign_attrs(units="m")
    (chart,) = lift_off_map(ds)
    (mesh,) = [c for c in chart.figure.axes[0].collections if isinstance(c, QuadMesh)]
    values = np.ma.masked_invalid(mesh.get_array()).reshape(ds.sizes["axial_tension"], ds.sizes["rotary_speed"])
    expected = 0.9 * (60 / (ds.rotary_speed.values * 30 / np.pi)) ** 1.86
    np.testing.assert_allclose(values[0], expected, rtol=1e-12)
    labels = figure_labels(chart.figure)
    assert any("configured eccentricity 0.1 in lifts the joints" in t for t in labels["legend"])
    written = [t.get_text() for t in chart.figure.axes[0].texts if t.get_gid() == "lift-off eccentricity"]
    assert len(written) == values.size and f"{expected[0]:.2g}" in written
    assert "your pipe lies where its eccentricity is below" in chart.caption
    assert lift_off_map(study) == []
