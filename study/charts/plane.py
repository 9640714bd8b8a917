"""The rotary speed × axial load plane: the worst case of a dataset over its other inputs, drawn as cells.

Every decision chart (stress and force with their limits, fatigue life, regimes, the safe envelope) is
a map over rotary speed (x) and axial load (y). Any other swept input (restitution, mud density, mud
flow velocity, ...) is reduced to the worst case — the highest stress, the shortest life — over every
answered point: ``ok``, or ``not_converged`` with its values kept (the bouncing pipe's answers, with their error
estimate); a cell whose worst value is from a point not converged is veiled and its error estimate written in, a
cell where some points have no answer is dotted, and a cell without any answered point is hatched grey. A failed
point's values (where it has any) are never drawn. A limit is drawn as the boundary of the cells
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

from study.charts.design import (DPI, LOAD, RPM, Chart, axis_names, axis_positions, cell_edges, figure_title,
                                 format_axis, full_array, mark_missing)
from study.charts.labels import TickFormatter, quantity
from study.solvers.model.result import STATUS_CODES

BAND_STYLE = {"facecolor": (0.25, 0.35, 0.9, 0.22), "edgecolor": (0.15, 0.25, 0.75, 0.9), "linewidth": 0.8}
BAND_LABEL = "critical speed ±15 % (rpm to avoid)"
PARTIAL_STYLE = {"facecolor": "none", "edgecolor": "0.3", "hatch": "..", "linewidth": 0}
PARTIAL_LABEL = "dotted: some points without an answer (worst of the others shown)"
ROUGH_STYLE = {"facecolor": (1.0, 1.0, 1.0, 0.35), "edgecolor": (0.0, 0.0, 0.0, 0.3), "hatch": "//", "linewidth": 0}
ROUGH_LABEL = "veiled, ±n %: the worst point is not converged, n % its error estimate"
MISSING_LABEL = "hatched grey: no answered point (see the validity map)"
LIMIT_HATCH = "\\\\"  # inside a limit's outline
#: Cells annotated with their error estimate only up to this many (beyond, the veil alone).
MAX_ANNOTATED = 200
#: A point not converged to the study's tolerance decides a limit when the limit holds (or fails) with its stresses
#: off by MARGIN times its error estimate: the reference model's estimate of its window erred low by up to 2x in its
#: tests (docs/reference_model.md §3.1), so twice.
MARGIN = 2.0
#: The steepest S-N slope of the fatigue curves (DNV-RP-C203: m = 3 and 5): life goes as S^-m, so stresses off by a
#: factor (1 + d) move the life by at most (1 + d)^5.
LIFE_SLOPE = 5.0


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
        return axis_positions(self.ds, self.x)[0]

    @property
    def ypos(self) -> np.ndarray:
        return axis_positions(self.ds, self.y)[0]

    @property
    def xedges(self) -> np.ndarray:
        return cell_edges(self.xpos)

    @property
    def yedges(self) -> np.ndarray:
        return cell_edges(self.ypos)

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
            parts.append(f"{reduction} over {axis_names(self.ds, self.reduced)}")
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
    return full_array(ds, "status") == STATUS_CODES["ok"]


#: Statuses whose figures are answers: ``ok``, and ``yields`` (solved and valid, its normal stress past the grade's
#: yield: the limit charts and the envelope must show it, not leave it blank).
ANSWERED = ("ok", "yields")


def solved_points(ds: xr.Dataset) -> xr.DataArray:
    """True where a point's status is one of :data:`ANSWERED`, its figures answers to the study's tolerance (every
    point when the dataset has no status)."""
    if "status" not in ds.data_vars:
        return ok_points(ds)
    return full_array(ds, "status").isin([STATUS_CODES[name] for name in ANSWERED])


def answered_points(ds: xr.Dataset) -> xr.DataArray:
    """True where a point has an answer to show: solved (:func:`solved_points`: ``ok`` or ``yields``), or
    ``not_converged`` with its values kept (an answer with its error stated); other statuses' values (where any)
    are not answers."""
    solved = solved_points(ds)
    if "status" not in ds.data_vars:
        return solved
    return solved | (full_array(ds, "status") == STATUS_CODES["not_converged"])


def answered_values(ds: xr.Dataset, name: str) -> xr.DataArray:
    """The output ``name`` over every dimension, NaN where the point has no answer (:func:`answered_points`)."""
    return full_array(ds, name).where(answered_points(ds))


def point_errors(ds: xr.Dataset) -> xr.DataArray:
    """Each point's relative error estimate (0 where the dataset has none)."""
    if "error_estimate" not in ds.data_vars:
        return xr.zeros_like(ok_points(ds), dtype=float)
    return full_array(ds, "error_estimate").fillna(0.0)


#: The output whose own relative error a figure's uncertainty is (the reference model states them by figure), where the
#: dataset has it; elsewhere the point's error estimate, a stress error, stands for it (:func:`figure_errors`).
FIGURE_ERRORS = {"yield_utilisation": "max_normal_stress_error", "max_normal_stress": "max_normal_stress_error",
                 "endurance_utilisation": "alternating_bending_stress_error",
                 "equivalent_alternating_stress": "alternating_bending_stress_error",
                 "alternating_bending_stress": "alternating_bending_stress_error",
                 "peak_contact_force": "peak_contact_force_error", "fatigue_life": "fatigue_life_error",
                 "damage_rate": "fatigue_life_error", "max_deflection": "max_deflection_error"}
#: Figures that go as the stress to the power −:data:`LIFE_SLOPE` where only a stress error is known.
LIFE_FIGURES = ("fatigue_life",)


def figure_errors(ds: xr.Dataset, name: str) -> tuple[xr.DataArray, xr.DataArray]:
    """Each point's relative error of the output ``name`` and whether it is the figure's own (True) or the point's
    error estimate standing for it (False; 0 where there is none): :data:`FIGURE_ERRORS`. A fatigue life's own error
    e is its damage rate's (the life within life/(1 ± e)); a stress error d moves it by (1 ± d)^−LIFE_SLOPE."""
    fallback = point_errors(ds)
    own = FIGURE_ERRORS.get(name)
    if own is None or own not in ds.data_vars:
        return fallback, xr.zeros_like(fallback, dtype=bool)
    mine = full_array(ds, own)
    has = np.isfinite(mine)
    return mine.where(has, fallback), has


def bounds(values, error, own, name: str, margin: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """(low, high) of ``values`` of the output ``name`` with their relative ``error`` times ``margin`` (default
    :data:`MARGIN`) either way: a fatigue life with its own error (``own``) within life/(1 ± m e), with a stress error
    within life (1 ± m e)^−LIFE_SLOPE; another figure within value (1 ± m e). A bound past nothing (m e ≥ 1) is
    unbounded: 0 below a figure, inf above a life (the stresses might be nil)."""
    m = MARGIN if margin is None else margin
    off = m * np.asarray(error, dtype=float)
    values = np.asarray(values, dtype=float)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        if name in LIFE_FIGURES:
            own = np.asarray(own, dtype=bool)
            low = np.where(own, values / (1.0 + off), values * (1.0 + off) ** -LIFE_SLOPE)
            high = np.where(off < 1.0, np.where(own, values / (1.0 - off), values * (1.0 - off) ** -LIFE_SLOPE),
                            np.inf)
            return low, high
        return values * np.maximum(1.0 - off, 0.0), values * (1.0 + off)


def _cells(p: "Plane", da: xr.DataArray) -> np.ndarray:
    """``da`` over the dataset's dimensions as (load, speed, points of the cell): the fixed dimensions at their value,
    the reduced ones stacked."""
    da = da.isel({d: 0 for d in p.fixed if d in da.dims})
    da = da.transpose(p.y, p.x, *[d for d in p.reduced if d in da.dims])
    values = np.asarray(da.values)
    return values.reshape(values.shape[0], values.shape[1], -1)


def worst_in_cells(ds: xr.Dataset, name: str, how: str, p: "Plane | None" = None) -> dict[str, np.ndarray]:
    """Per rotary speed × axial load cell, the worst ``name`` (``how``: "max" or "min") over every answered point
    (ok, and not converged with its values: undecided ones included), the relative error of the figure at the point
    that gives it (:func:`figure_errors`: its own where stated, else the point's error estimate), whether that point
    is not ok (``rough``), and the worst case over the cell with each point's figure off by :data:`MARGIN` times its
    error (``bound``, :func:`bounds`: a stress or utilisation goes as the stress, a fatigue life — the one "min"
    figure — within life/(1 + 2e) with its own error e, or as the stress to the power −:data:`LIFE_SLOPE`).

    Returns ``{"value", "error", "rough", "bound"}`` arrays (load × speed), NaN (False) where the cell has no
    answered point."""
    if how not in ("max", "min"):
        raise ValueError(f"how = {how!r}; allowed: max, min")
    p = p or plane(ds)
    values = _cells(p, full_array(ds, name).where(answered_points(ds)))
    errors, own = figure_errors(ds, name)
    error = _cells(p, errors)
    rough = _cells(p, ~solved_points(ds))
    low, high = bounds(values, error, _cells(p, own), name)
    bound = high if how == "max" else low
    empty = np.all(np.isnan(values), axis=-1)
    fill = -np.inf if how == "max" else np.inf
    pick = np.where(np.isnan(values), fill, values)
    index = (np.argmax(pick, axis=-1) if how == "max" else np.argmin(pick, axis=-1))[..., None]
    value = np.take_along_axis(values, index, -1)[..., 0]
    err = np.take_along_axis(error, index, -1)[..., 0]
    from_rough = np.take_along_axis(rough, index, -1)[..., 0]
    worst_bound = (np.max if how == "max" else np.min)(np.where(np.isnan(bound), fill, bound), axis=-1)
    return {"value": np.where(empty, np.nan, value), "error": np.where(empty, np.nan, err),
            "rough": from_rough & ~empty, "bound": np.where(empty, np.nan, worst_bound)}


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
    format_axis(ax.xaxis, None, p.xpos, grid_values=p.xpos)
    format_axis(ax.yaxis, None, p.ypos, grid_values=p.ypos)
    ax.set_xlabel(quantity(p.ds[p.x]).label)
    ax.set_ylabel(quantity(p.ds[p.y]).label)


@dataclass
class Panel:
    """One map of the plane: cell values (load × speed, display units; NaN hatched), its colour scale, the limits
    drawn as cell boundaries (mask, legend label, line style), and where a cell's value is from a point not
    converged (``rough``) with that point's relative error estimate (``errors``)."""

    values: np.ndarray
    label: str
    title: str
    cmap: str = "YlOrRd"
    norm: Normalize | None = None
    limits: list[tuple[np.ndarray, str, dict]] = field(default_factory=list)
    marks: list[float] = field(default_factory=list)  # values marked on the colour bar (a limit's value)
    rough: np.ndarray | None = None
    errors: np.ndarray | None = None


def worst_panel(p: Plane, ds: xr.Dataset, name: str, how: str, label: str, title: str, scale=None, **options) -> Panel:
    """A :class:`Panel` of each cell's worst ``name`` over every answered point (:func:`worst_in_cells`), converted by
    ``scale`` (default: the output's display unit), with the cells whose value is from a point not converged marked
    with its error estimate."""
    worst = worst_in_cells(ds, name, how, p)
    convert = scale or quantity(ds[name]).convert
    return Panel(convert(worst["value"]), label, title, rough=worst["rough"], errors=worst["error"], **options)


def _annotate_errors(ax, p: Plane, rough: np.ndarray, errors: np.ndarray):
    """Write each marked cell's error estimate in it (±38 %), where the map has few enough cells to read them."""
    if rough.sum() > MAX_ANNOTATED:
        return
    for i, j in zip(*np.nonzero(rough)):
        if np.isfinite(errors[i, j]):
            ax.text(p.xpos[j], p.ypos[i], f"±{errors[i, j]:.0%}", ha="center", va="center", fontsize=6.5,
                    color="0.1", zorder=4, gid="error estimate")


def caption_from(lead: str, labels: Sequence[str]) -> str:
    """A chart's caption from its lead sentence and the legend entries drawn, so it names only what is drawn."""
    return lead + (" Key: " + "; ".join(labels) + "." if labels else "")


def plane_chart(p: Plane, name: str, title: str, panels: Sequence[Panel], context: Sequence[str], caption: str,
                bands=None) -> Chart:
    """One figure of side-by-side panels over the plane, with the limit outlines, the rpm bands and the cells whose
    value is from a point not converged (veiled, their error written in). ``caption`` is the lead sentence; the
    chart's caption adds the legend's entries (:func:`caption_from`)."""
    columns = len(panels)
    width = min(3.0 + 4.6 * columns, 20.0)
    fig = Figure(figsize=(width, 5.4), dpi=DPI, layout="constrained")
    axes = fig.subplots(1, columns, squeeze=False)[0]
    handles: dict[str, object] = {}
    missing = False
    some_failed = p.reduce(~answered_points(p.ds), "any")
    for ax, panel in zip(axes, panels):
        masked = np.ma.masked_invalid(np.asarray(panel.values, dtype=float))
        if masked.mask.any():
            missing = True
            mark_missing(ax)
        partial = some_failed & ~masked.mask
        if partial.any():  # the worst of the answered points only: a point without an answer there might be worse
            draw_cells(ax, partial, p, **PARTIAL_STYLE)
            handles[PARTIAL_LABEL] = Patch(**PARTIAL_STYLE, label=PARTIAL_LABEL)
        norm = panel.norm
        if norm is None:
            finite = masked.compressed()
            low, high = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 1.0)
            for value in panel.marks:  # the scale shows its limits
                low, high = min(low, value), max(high, value)
            norm = Normalize(low, high if high > low else low + (abs(low) or 1.0))
        mesh = ax.pcolormesh(p.xedges, p.yedges, masked, cmap=panel.cmap, norm=norm, shading="flat")
        bar = fig.colorbar(mesh, ax=ax, label=panel.label, shrink=0.95, pad=0.02)
        if not isinstance(norm, LogNorm):
            bar.ax.yaxis.set_major_formatter(TickFormatter())
        for value in panel.marks:
            if norm.vmin <= value <= norm.vmax:
                bar.ax.axhline(value, color="k", lw=2.0)
        if panel.rough is not None and np.any(panel.rough & ~masked.mask):
            rough = panel.rough & ~masked.mask
            draw_cells(ax, rough, p, **ROUGH_STYLE)
            _annotate_errors(ax, p, rough, panel.errors if panel.errors is not None else np.full(rough.shape, np.nan))
            handles[ROUGH_LABEL] = Patch(**ROUGH_STYLE, label=ROUGH_LABEL)
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
        handles[MISSING_LABEL] = Patch(facecolor="white", edgecolor="0.75", hatch="////", label=MISSING_LABEL)
    if handles:
        columns_of_legend = max(1, min(len(handles), int(width // 7)))
        fig.legend(handles=list(handles.values()), loc="outside lower center", ncols=columns_of_legend,
                   fontsize=8, frameon=False)
    figure_title(fig, title, context, width)
    return Chart(name, fig, caption_from(caption, list(handles)))
