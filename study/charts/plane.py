"""The rotary speed × axial load plane: the worst case of a dataset over its other inputs, drawn as cells.

Every decision chart (stress and force with their limits, fatigue life, regimes, the safe envelope) is
a map over rotary speed (x) and axial load (y). Any other swept input (restitution, mud density, mud
flow velocity, ...) is reduced to the worst case — the highest stress, the shortest life — over the
points whose status is ``ok`` only, so a failed point or another solution branch never speckles the
colour scale; a cell without any ok point is hatched. A limit is drawn as the boundary of the cells
over it (no contouring of scattered data), and the rotary speeds to avoid as bands per load row.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import Sequence

import numpy as np
import xarray as xr
from matplotlib.collections import LineCollection, PolyCollection
from matplotlib.colors import LogNorm, Normalize
from matplotlib.figure import Figure
from matplotlib.patches import Patch

from study.charts.design import (DPI, LOAD, RPM, Chart, _edges, _format_axis, _full, _mark_missing, _names,
                                 _positions, _title)
from study.charts.labels import TickFormatter, quantity
from study.solvers.result import STATUS_CODES

BAND_STYLE = {"facecolor": (0.25, 0.35, 0.9, 0.22), "edgecolor": (0.15, 0.25, 0.75, 0.9), "linewidth": 0.8}
BAND_LABEL = "critical speed ±15 % (rpm to avoid)"
PARTIAL_STYLE = {"facecolor": "none", "edgecolor": "0.3", "hatch": "..", "linewidth": 0}
PARTIAL_LABEL = "worst of the ok points; some points there failed"
LIMIT_HATCH = "\\\\"  # inside a limit's outline


@dataclass
class Plane:
    """How a dataset maps onto the rotary speed × axial load plane."""

    ds: xr.Dataset
    x: str = RPM
    y: str = LOAD
    reduced: list[str] = field(default_factory=list)  # swept inputs reduced to the worst case
    fixed: list[str] = field(default_factory=list)  # dimensions of length 1

    @property
    def xpos(self) -> np.ndarray:
        return _positions(self.ds, self.x)[0]

    @property
    def ypos(self) -> np.ndarray:
        return _positions(self.ds, self.y)[0]

    @property
    def xedges(self) -> np.ndarray:
        return _edges(self.xpos)

    @property
    def yedges(self) -> np.ndarray:
        return _edges(self.ypos)

    def reduce(self, da: xr.DataArray, how: str) -> np.ndarray:
        """``da`` (over the dataset's dimensions) as a (load, speed) array: the fixed dimensions at their
        value, the others reduced by ``how`` ("max", "min", "any", "all", "sum", "mean"), NaN ignored."""
        da = da.isel({d: 0 for d in self.fixed if d in da.dims})
        dims = [d for d in self.reduced if d in da.dims]
        if dims:
            with np.errstate(invalid="ignore"), warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)
                da = getattr(da, how)(dim=dims)
        return np.asarray(da.transpose(self.y, self.x).values)

    def context(self, reduction: str) -> list[str]:
        """Title lines naming the fixed inputs and how the others were reduced."""
        parts = [quantity(self.ds[d]).describe(self.ds[d].values[0]) for d in self.fixed]
        if self.reduced:
            parts.append(f"{reduction} over {_names(self.ds, self.reduced)}")
        return parts


def plane(ds: xr.Dataset) -> Plane | None:
    """The plane of ``ds``, or None unless both the rotary speed and the axial load are swept."""
    if RPM not in ds.sizes or LOAD not in ds.sizes or ds.sizes[RPM] < 2 or ds.sizes[LOAD] < 2:
        return None
    others = [d for d in ds.sizes if d not in (RPM, LOAD)]
    return Plane(ds, reduced=[d for d in others if ds.sizes[d] > 1], fixed=[d for d in others if ds.sizes[d] == 1])


def ok_points(ds: xr.Dataset) -> xr.DataArray:
    """True where a point's status is ``ok`` (every point when the dataset has no status), over every dimension."""
    if "status" not in ds.data_vars:
        return xr.DataArray(np.ones(tuple(ds.sizes.values()), dtype=bool), dims=list(ds.sizes))
    return _full(ds, "status") == STATUS_CODES["ok"]


#: Statuses whose figures are answers: ``ok``, and ``yields`` (solved and valid, its normal stress past the grade's
#: yield: the limit charts and the envelope must show it, not leave it blank).
ANSWERED = ("ok", "yields")


def answered_points(ds: xr.Dataset) -> xr.DataArray:
    """True where a point's status is one of :data:`ANSWERED` (every point when the dataset has no status)."""
    if "status" not in ds.data_vars:
        return ok_points(ds)
    return _full(ds, "status").isin([STATUS_CODES[name] for name in ANSWERED])


def ok_values(ds: xr.Dataset, name: str) -> xr.DataArray:
    """The output ``name`` over every dimension, NaN where the point has no answer (:func:`answered_points`)."""
    return _full(ds, name).where(answered_points(ds))


def cell_boundary(over: np.ndarray, xedges: np.ndarray, yedges: np.ndarray) -> list:
    """Segments [((x0, y0), (x1, y1)), ...] separating the cells where ``over`` (load × speed) holds
    from their neighbours where it does not: the outline of a region of cells, no interpolation."""
    over = np.asarray(over, dtype=bool)
    segments = []
    rows, columns = over.shape
    for i in range(rows):
        for j in range(columns - 1):
            if over[i, j] != over[i, j + 1]:
                segments.append(((xedges[j + 1], yedges[i]), (xedges[j + 1], yedges[i + 1])))
    for i in range(rows - 1):
        for j in range(columns):
            if over[i, j] != over[i + 1, j]:
                segments.append(((xedges[j], yedges[i + 1]), (xedges[j + 1], yedges[i + 1])))
    return segments


def draw_boundary(ax, over: np.ndarray, p: Plane, **style) -> LineCollection:
    """Draw :func:`cell_boundary` of ``over`` on ``ax`` (``style``: LineCollection keywords)."""
    lines = LineCollection(cell_boundary(over, p.xedges, p.yedges), **{"colors": "k", "linewidths": 2.0, **style})
    ax.add_collection(lines)
    return lines


def draw_cells(ax, mask: np.ndarray, p: Plane, **style) -> PolyCollection:
    """Overlay the cells where ``mask`` (load × speed) holds, e.g. hatched (``style``: PolyCollection keywords)."""
    rows, columns = np.nonzero(mask)
    x, y = p.xedges, p.yedges
    cells = [[(x[j], y[i]), (x[j + 1], y[i]), (x[j + 1], y[i + 1]), (x[j], y[i + 1])] for i, j in zip(rows, columns)]
    collection = PolyCollection(cells, **style, zorder=2)
    ax.add_collection(collection)
    return collection


def band_polygons(bands: Sequence[Sequence[tuple[float, float]]], yedges: np.ndarray) -> list:
    """Rectangles, one per interval (lo, hi) [display rpm] of each load row's bands."""
    return [[(lo, yedges[i]), (hi, yedges[i]), (hi, yedges[i + 1]), (lo, yedges[i + 1])]
            for i, row in enumerate(bands) for lo, hi in row]


def draw_bands(ax, bands, p: Plane) -> PolyCollection | None:
    """Shade the rotary speeds to avoid, per load row (``bands``: a list of (lo, hi) per row)."""
    polygons = band_polygons(bands, p.yedges)
    if not polygons:
        return None
    collection = PolyCollection(polygons, **BAND_STYLE, zorder=3)
    ax.add_collection(collection)
    return collection


def plane_axes(ax, p: Plane):
    """Limits, ticks at the grid values and labels with units of a map of the plane."""
    ax.set_xlim(p.xedges[0], p.xedges[-1])
    ax.set_ylim(p.yedges[0], p.yedges[-1])
    _format_axis(ax.xaxis, None, p.xpos, grid_values=p.xpos)
    _format_axis(ax.yaxis, None, p.ypos, grid_values=p.ypos)
    ax.set_xlabel(quantity(p.ds[p.x]).label)
    ax.set_ylabel(quantity(p.ds[p.y]).label)


@dataclass
class Panel:
    """One map of the plane: cell values (load × speed, display units; NaN hatched), its colour scale,
    and the limits drawn as cell boundaries (mask, legend label, line style)."""

    values: np.ndarray
    label: str
    title: str
    cmap: str = "YlOrRd"
    norm: Normalize | None = None
    limits: list[tuple[np.ndarray, str, dict]] = field(default_factory=list)
    marks: list[float] = field(default_factory=list)  # values marked on the colour bar (a limit's value)


def plane_chart(p: Plane, name: str, title: str, panels: Sequence[Panel], context: Sequence[str], caption: str,
                bands=None) -> Chart:
    """One figure of side-by-side panels over the plane, with the limit outlines and the rpm bands."""
    columns = len(panels)
    width = min(3.0 + 4.6 * columns, 20.0)
    fig = Figure(figsize=(width, 5.4), dpi=DPI, layout="constrained")
    axes = fig.subplots(1, columns, squeeze=False)[0]
    handles: dict[str, object] = {}
    missing = False
    some_failed = p.reduce(~ok_points(p.ds), "any")
    for ax, panel in zip(axes, panels):
        masked = np.ma.masked_invalid(np.asarray(panel.values, dtype=float))
        if masked.mask.any():
            missing = True
            _mark_missing(ax)
        partial = some_failed & ~masked.mask
        if partial.any():  # the worst of the ok points only: a failed point there might be worse
            draw_cells(ax, partial, p, **PARTIAL_STYLE)
            handles[PARTIAL_LABEL] = Patch(**PARTIAL_STYLE, label=PARTIAL_LABEL)
        norm = panel.norm
        if norm is None:
            finite = masked.compressed()
            low, high = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 1.0)
            norm = Normalize(low, high if high > low else low + (abs(low) or 1.0))
        mesh = ax.pcolormesh(p.xedges, p.yedges, masked, cmap=panel.cmap, norm=norm, shading="flat")
        bar = fig.colorbar(mesh, ax=ax, label=panel.label, shrink=0.95, pad=0.02)
        if not isinstance(norm, LogNorm):
            bar.ax.yaxis.set_major_formatter(TickFormatter())
        for value in panel.marks:
            if norm.vmin <= value <= norm.vmax:
                bar.ax.axhline(value, color="k", lw=2.0)
        for mask, label, style in panel.limits:
            if np.any(mask):  # outlined, and hatched inside so the side over the limit reads at a glance
                draw_boundary(ax, mask, p, **style)
                colour = style.get("colors", "k")
                draw_cells(ax, mask, p, facecolor="none", edgecolor=colour, hatch=LIMIT_HATCH, linewidth=0)
                handles[label] = Patch(facecolor="none", edgecolor=colour, hatch=LIMIT_HATCH,
                                       lw=style.get("linewidths", 2.0), ls=style.get("linestyles", "-"), label=label)
        if bands is not None and draw_bands(ax, bands, p) is not None:
            handles[BAND_LABEL] = Patch(**BAND_STYLE, label=BAND_LABEL)
        plane_axes(ax, p)
        ax.set_title(panel.title, fontsize=9)
    for ax in axes[1:]:
        ax.tick_params(labelleft=False)
        ax.set_ylabel("")
    context = list(context)
    if missing:
        handles["no ok point"] = Patch(facecolor="white", edgecolor="0.75", hatch="////", label="no ok point "
                                       "(see the validity map)")
    if handles:
        columns_of_legend = max(1, min(len(handles), int(width // 5)))
        fig.legend(handles=list(handles.values()), loc="outside lower center", ncols=columns_of_legend,
                   fontsize=8, frameon=False)
    _title(fig, title, context, width)
    return Chart(name, fig, caption)
