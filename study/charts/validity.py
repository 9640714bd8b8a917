"""The validity map: what fraction of the points in each rotary speed × axial load cell got each status.

Each cell of the map is a stacked bar: its height split in proportion to the points (over every other swept
input) with each status, ok at the bottom. A cell that is all green is valid everywhere; the legend gives each
status's share of the whole study. This replaces showing the worst status of a cell, which hides the valid
points behind a single failed one.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib import colormaps
from matplotlib.collections import PolyCollection
from matplotlib.figure import Figure
from matplotlib.patches import Patch

from study.charts.design import (DPI, Chart, axis_names, axis_positions, cell_edges, figure_title, format_axis,
                                 full_array, map_or_line_dims, preferred_dims)
from study.charts.labels import quantity
from study.solvers.model.result import STATUS

#: Colours of the status flags: green for ok, warm for physical limits, cool/grey for numerics.
STATUS_COLOURS = {
    "ok": "#41ab5d",
    "buckled": "#d7301f",
    "hertz_invalid": "#fd8d3c",
    "no_span": "#6a51a3",
    "resonance": "#e7298a",
    "terms_not_small": "#fed976",
    "not_converged": "#6baed6",
    "failed": "#252525",
    "incomplete": "#969696",
    "no_impact": "#c7e9c0",
    "unstable": "#a50f15",
    "period_doubling": "#fc9272",
    "chattering": "#8c510a",
    "sticking": "#dfc27d",
    "not_periodic": "#bf812d",
    "disagrees": "#ffff99",
    "unphysical": "#000080",
    "out_of_scope": "#9e9ac8",
    "yields": "#67000d",
}


def flags(status: xr.DataArray) -> dict[int, str]:
    """Status code -> name, from the variable's ``flag_values``/``flag_meanings`` (else :data:`STATUS`)."""
    values = status.attrs.get("flag_values")
    meanings = status.attrs.get("flag_meanings")
    if values is not None and meanings:
        names = str(meanings).split()
        values = np.atleast_1d(values)
        if len(names) == len(values):
            return {int(v): n for v, n in zip(values, names)}
    return {code: name for name, (code, _) in STATUS.items()}


def _layout(ds: xr.Dataset) -> tuple[str, str | None, list[str], list[str]]:
    dims = map_or_line_dims(ds)
    x = dims[0] if dims else preferred_dims(ds)[0]
    y = dims[1] if len(dims) > 1 else None
    fixed = [d for d in ds.sizes if ds.sizes[d] == 1 and d not in (x, y)]
    reduced = [d for d in ds.sizes if d not in (x, y) and d not in fixed]
    return x, y, fixed, reduced


def validity_fractions(ds: xr.Dataset) -> xr.DataArray:
    """Fraction of the points of each (x[, y]) cell with each status present in the study, over the other swept
    inputs: dims ``status`` (names, ok first when present), x and (when a second input is swept) y. Sums to 1
    over ``status`` in every cell."""
    x, y, fixed, reduced = _layout(ds)
    status = full_array(ds, "status").isel({d: 0 for d in fixed})
    names = flags(ds["status"])
    present = sorted(int(v) for v in np.unique(status.values))
    layers = [(status == code).mean(dim=reduced) if reduced else (status == code).astype(float) for code in present]
    fractions = xr.concat(layers, dim="status").assign_coords(status=[names.get(c, f"code {c}") for c in present])
    return fractions.transpose("status", *[d for d in (y, x) if d is not None])


def validity_map(ds: xr.Dataset) -> list[Chart]:
    """Per cell of rotary speed × axial load, the fraction of points with each status as a stacked bar (one strip
    when a single input is swept); other swept inputs are the points counted, the title says which."""
    if "status" not in ds.data_vars or not ds.sizes or 0 in ds.sizes.values():
        return []
    x, y, fixed, reduced = _layout(ds)
    fractions = validity_fractions(ds)
    xq = quantity(ds[x])
    xpos, xticks = axis_positions(ds, x, xq)
    xedges = cell_edges(xpos)
    if y is not None:
        yq = quantity(ds[y])
        ypos, yticks = axis_positions(ds, y, yq)
        yedges = cell_edges(ypos)
        size = (9.0, 5.4)
    else:
        yedges = np.array([0.0, 1.0])
        size = (9.0, 2.8)
    values = fractions.values.reshape(fractions.sizes["status"], len(yedges) - 1, len(xedges) - 1)
    names = [str(s) for s in fractions["status"].values]
    colours = [STATUS_COLOURS.get(n, colormaps["tab10"](i % 10)) for i, n in enumerate(names)]
    fig = Figure(figsize=size, dpi=DPI, layout="constrained")
    ax = fig.subplots()
    polygons, facecolours = stacked_cells(values, xedges, yedges, colours)
    ax.add_collection(PolyCollection(polygons, facecolors=facecolours, edgecolors="none"))
    ax.set_xlim(xedges[0], xedges[-1])
    ax.set_ylim(yedges[0], yedges[-1])
    format_axis(ax.xaxis, xticks, xpos, grid_values=xpos)
    ax.set_xlabel(xq.label)
    if y is not None:
        format_axis(ax.yaxis, yticks, ypos, grid_values=ypos)
        ax.set_ylabel(yq.label)
    else:
        ax.set_yticks([])
    for edge in xedges:
        ax.axvline(edge, color="white", lw=0.8)
    for edge in yedges:
        ax.axhline(edge, color="white", lw=0.8)
    counts = (full_array(ds, "status").isel({d: 0 for d in fixed}) if fixed
              else full_array(ds, "status")).values.ravel()
    code_of = {n: c for c, n in flags(ds["status"]).items()}
    handles = [Patch(facecolor=colours[i], edgecolor="0.5", lw=0.5,
                     label=f"{n} ({100.0 * np.mean(counts == code_of.get(n, -1)):.0f} % of the points)")
               for i, n in enumerate(names)]
    fig.legend(handles=handles, loc="outside right center", fontsize=8, frameon=False,
               title="status (each cell: the fraction\nof its points, ok at the bottom)", title_fontsize=8)
    context = [quantity(ds[d]).describe(ds[d].values[0]) for d in fixed]
    if reduced:
        n = int(np.prod([ds.sizes[d] for d in reduced]))
        context.append(f"each cell holds the {n} points over {axis_names(ds, reduced)}")
    figure_title(fig, "Validity of the design points: fraction of each status", context, 8.0)
    caption = ("Which answers can be trusted: each cell is split in proportion to its points' statuses over the "
               "other swept inputs (green: ok); the legend gives each status's share of the whole study.")
    return [Chart("validity_map", fig, caption)]


def stacked_cells(fractions: np.ndarray, xedges, yedges, colours) -> tuple[list, list]:
    """Rectangles splitting each cell's height by ``fractions`` (status × rows × columns) and their colours;
    empty layers are left out."""
    polygons, facecolours = [], []
    for i in range(fractions.shape[1]):
        for j in range(fractions.shape[2]):
            base = yedges[i]
            height = yedges[i + 1] - yedges[i]
            for k in range(fractions.shape[0]):
                share = float(fractions[k, i, j])
                if share <= 0.0:
                    continue
                top = base + share * height
                polygons.append([(xedges[j], base), (xedges[j + 1], base), (xedges[j + 1], top), (xedges[j], top)])
                facecolours.append(colours[k])
                base = top
    return polygons, facecolours
