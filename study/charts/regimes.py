"""The regime map: how the pipe moves at each rotary speed and load.

No contact / forward whirl / backward whirl / bouncing impacts / periodic impacts (the source paper's
state) / unstable, as the codes of :data:`study.solvers.model.result.REGIMES`. A method that classifies the motion
writes the output ``regime``; where a point has none, the regime is read from its status (no_impact: no
contact; ok or disagrees: periodic impacts; unstable or period_doubling: unstable; not_periodic or
chattering: bouncing) and the title says so. Any other status leaves the regime undetermined (hatched).
Other swept inputs are reduced to the most severe regime (:data:`SEVERITY`). Cells where a point has two motions
(output ``coexisting_motion`` 1: the pipe lying on the wall, sliding, and a bouncing or chattering motion that a kick
throws it into, whose answer the point carries; docs/reference_model.md §10) are outlined.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib.colors import ListedColormap, LogNorm
from matplotlib.figure import Figure
from matplotlib.patches import Patch

from study.charts.critical import avoid_bands
from study.charts.design import DPI, Chart, figure_title, full_array, mark_missing
from study.charts.plane import BAND_LABEL, BAND_STYLE, Panel, draw_bands, draw_cells, plane, plane_axes, plane_chart
from study.solvers.model.result import REGIMES, STATUS_CODES

#: The regime a status implies, for points without a ``regime`` output.
FROM_STATUS = {"no_impact": "no_contact", "ok": "periodic_impacts", "disagrees": "periodic_impacts",
               "unstable": "unstable", "period_doubling": "unstable", "not_periodic": "bouncing",
               "chattering": "bouncing"}
#: Least to most severe: the map shows the most severe regime over the reduced inputs.
SEVERITY = ("no_contact", "sliding", "forward_whirl", "periodic_impacts", "bouncing", "unstable", "backward_whirl")
COLOURS = {"no_contact": "#c7e9c0", "sliding": "#ffffb2", "forward_whirl": "#9ecae1", "periodic_impacts": "#fdae6b",
           "bouncing": "#e6550d", "unstable": "#a50f15", "backward_whirl": "#54278f"}
LABELS = {"no_contact": "no contact", "sliding": "lying on the wall, sliding", "forward_whirl": "forward whirl",
          "backward_whirl": "backward whirl", "bouncing": "bouncing impacts",
          "periodic_impacts": "periodic impacts (the paper's state)", "unstable": "unstable"}
#: The outline of the cells where two motions coexist (output ``coexisting_motion`` 1).
COEXISTING_STYLE = {"facecolor": "none", "edgecolor": "k", "linewidth": 1.6, "linestyle": "--"}
COEXISTING_LABEL = "two motions: lying on the wall, or bouncing\nor chattering once a kick throws it off"


def regimes(ds: xr.Dataset) -> tuple[xr.DataArray, bool]:
    """The regime code of every point (NaN: undetermined), over every dimension, and whether any point's regime
    was read from its status rather than a ``regime`` output."""
    if "regime" in ds.data_vars:
        given = full_array(ds, "regime").astype(float)
    else:
        given = xr.full_like(full_array(ds, "status"), np.nan, dtype=float) if "status" in ds.data_vars else None
    if given is None:
        raise ValueError("the dataset has neither a regime nor a status variable")
    derived = xr.full_like(given, np.nan)
    if "status" in ds.data_vars:
        status = full_array(ds, "status")
        for flag, regime in FROM_STATUS.items():
            derived = xr.where(status == STATUS_CODES[flag], float(REGIMES[regime]), derived)
    use_status = given.isnull() & derived.notnull()
    return given.where(~use_status, derived), bool(use_status.any())


def regime_map(ds: xr.Dataset) -> list[Chart]:
    """The most severe regime over the other swept inputs at each rotary speed × axial load, in categorical colours,
    with the critical-speed bands."""
    p = plane(ds)
    if p is None or ("regime" not in ds.data_vars and "status" not in ds.data_vars):
        return []
    codes, from_status = regimes(ds)
    rank = xr.full_like(codes, np.nan)
    for name, code in REGIMES.items():
        rank = xr.where(codes == code, float(SEVERITY.index(name)), rank)
    worst = p.reduce(rank, "max")
    present = [SEVERITY[int(r)] for r in np.unique(worst[np.isfinite(worst)])]
    index = np.full(worst.shape, np.nan)
    for i, name in enumerate(present):
        index[worst == SEVERITY.index(name)] = i
    fig = _figure(p, index, present)
    counts = {name: int(np.sum(index == i)) for i, name in enumerate(present)}
    handles = [Patch(facecolor=COLOURS[n], edgecolor="0.5", label=f"{LABELS[n]} ({counts[n]} cells)") for n in present]
    if np.isnan(index).any():
        handles.append(Patch(facecolor="white", edgecolor="0.75", hatch="////",
                             label=f"undetermined: no answer ({int(np.isnan(index).sum())} cells)"))
    partial = p.reduce(codes.isnull(), "any") & np.isfinite(index)
    if partial.any():  # the most severe regime of the points that have one; others might be worse
        draw_cells(fig.axes[0], partial, p, facecolor="none", edgecolor="0.35", hatch="\\\\", linewidth=0)
        handles.append(Patch(facecolor="white", edgecolor="0.35", hatch="\\\\",
                             label=f"some points undetermined ({int(partial.sum())} cells)"))
    if "coexisting_motion" in ds.data_vars:  # a kick throws the pipe lying on the wall into another motion
        twice = p.reduce(full_array(ds, "coexisting_motion") == 1.0, "any")
        if twice.any():
            draw_cells(fig.axes[0], twice, p, **COEXISTING_STYLE)
            handles.append(Patch(**COEXISTING_STYLE, label=f"{COEXISTING_LABEL} ({int(twice.sum())} cells)"))
    bands = avoid_bands(p)
    if bands is not None and draw_bands(fig.axes[0], bands, p) is not None:
        handles.append(Patch(**BAND_STYLE, label=BAND_LABEL))
    fig.legend(handles=handles, loc="outside right center", fontsize=8, frameon=False, title="regime (cells)",
               title_fontsize=8)
    context = p.context("most severe regime (" + " < ".join(LABELS[n].split(" (")[0] for n in SEVERITY) + ")")
    if from_status:
        context.append("regime read from the status where the method gives none (no_impact: no contact; ok, "
                       "disagrees: periodic impacts; unstable, period_doubling: unstable; not_periodic, chattering: "
                       "bouncing)")
    figure_title(fig, "Regime of the motion", context, 8.5)
    caption = ("How the pipe moves at each rotary speed and load - free of the wall, whirling, bouncing or striking "
               "periodically - taking the most severe regime over the other swept inputs; shaded bands are speeds to "
               "avoid; a dashed outline marks where the pipe run up gently may lie on the wall but a kick throws it "
               "into bouncing or chattering (the figures there are that motion's).")
    return [Chart("regime_map", fig, caption)]


def _figure(p, index: np.ndarray, present: list[str]) -> Figure:
    fig = Figure(figsize=(10.0, 5.4), dpi=DPI, layout="constrained")
    ax = fig.subplots()
    masked = np.ma.masked_invalid(index)
    if masked.mask.any():
        mark_missing(ax)
    if present:
        ax.pcolormesh(p.xedges, p.yedges, masked, cmap=ListedColormap([COLOURS[n] for n in present]),
                      vmin=-0.5, vmax=len(present) - 0.5, shading="flat", edgecolors="white", linewidth=0.3)
    plane_axes(ax, p)
    return fig


#: Inches per metre's unit: the lift-off map is drawn in inches, the unit of API Spec 5DP's wall tolerance.
INCH = 0.0254
LIFT_STYLE = {"colors": "k", "linewidths": 2.2}


def lift_off_map(ds: xr.Dataset) -> list[Chart]:
    """The lift-off eccentricity (output ``lift_off_eccentricity``: the pipe's mass eccentricity at which its tool
    joints lift off the wall they lie on, :func:`study.solvers.methods.sliding.lift_off_eccentricity`) over rotary
    speed × axial load, in inches on a log colour scale, the lowest over the other swept inputs (the first to bounce;
    every point where it is defined, whatever its answer's status, as it depends on none). The configured eccentricity
    (the output ``eccentricity``) is marked on the colour bar, and the cells where it is above the lift-off (the joints
    bounce) are outlined; each cell's value is written in it."""
    p = plane(ds)
    if p is None or "lift_off_eccentricity" not in ds.data_vars:
        return []
    lift = full_array(ds, "lift_off_eccentricity")
    values = p.reduce(lift, "min") / INCH
    finite = values[np.isfinite(values) & (values > 0)]
    if not finite.size:
        return []
    marks = []
    if "eccentricity" in ds.data_vars and np.any(np.isfinite(ds["eccentricity"].values)):
        marks = [float(np.nanmax(ds["eccentricity"].values)) / INCH]
    low = min([float(finite.min())] + marks) / 1.5
    high = max([float(finite.max())] + marks) * 1.5
    panel = Panel(np.where(np.isposinf(values), high, values), "lift-off eccentricity [in]",
                  "mass eccentricity at which the joints lift off the wall,\nlowest over every point "
                  + (f"(bar line: the configured {marks[0]:.3g} in)" if marks else ""),
                  cmap="viridis", norm=LogNorm(low, high), marks=marks)
    if marks:
        panel.limits.append((values < marks[0], f"black outline, hatched: the configured eccentricity "
                             f"{marks[0]:.3g} in lifts the joints (they bounce)", LIFT_STYLE))
    context = p.context("lowest lift-off eccentricity (the first to bounce)")
    caption = ("Whether the pipe lies on the wall or bounces, as its mass eccentricity decides: your pipe lies where "
               "its eccentricity is below the value in the cell (in inches; the lowest over the other swept inputs, "
               "by the balance of the sliding state's joint force; blank where no side load lays the string down).")
    chart = plane_chart(p, "lift_off_eccentricity", "Lift-off eccentricity: lying or bouncing", [panel], context,
                        caption, bands=avoid_bands(p))
    ax = chart.figure.axes[0]
    for i, j in zip(*np.nonzero(np.isfinite(values))):
        ax.text(p.xpos[j], p.ypos[i], f"{values[i, j]:.2g}", ha="center", va="center", fontsize=6.5,
                color="w" if values[i, j] < np.sqrt(low * high) else "k", zorder=4, gid="lift-off eccentricity")
    return [chart]
