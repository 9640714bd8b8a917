"""Design charts of a results dataset, for a drilling engineer choosing rotary speed and load.

Each chart function takes the dataset (see :mod:`study.workflow.dataset`) and returns a list of
:class:`Chart` (a file name and a :class:`matplotlib.figure.Figure`), empty when the variables or
dimensions it needs are absent. :func:`draw_all` draws every chart the dataset allows and writes
the files. Figures are built as ``Figure`` objects, never through pyplot, so no global state and
no display is involved.

How the swept dimensions are laid out, the same way in every chart:

- the x axis is the rotary speed (for the maps, x is the rotary speed and y the axial load);
- one line per axial load (in line charts);
- one panel per value of the next swept input (restitution first), one figure per value of the one
  after; any further dimension is reduced by its maximum (the worst status for the validity map)
  and the title says so;
- a dimension along which every plotted value is the same is shown once and the title says so; a
  dimension of length 1 is a fixed input and the title names its value.

Values are converted to the units users think in (see :mod:`study.charts.labels`); a point that
failed (NaN) is left out of lines and hatched in maps, never drawn as zero.
"""

from __future__ import annotations

import math
import re
import textwrap
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Sequence

import numpy as np
import xarray as xr
from matplotlib import colormaps, ticker
from matplotlib.colors import TwoSlopeNorm
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from study.atomic import atomic_path
from study.charts.labels import Quantity, TickFormatter, format_value, quantity, tick_format

DPI = 150
RPM = "rotary_speed"
LOAD = "axial_tension"
#: Swept inputs that become panels before any other extra dimension.
PANEL_FIRST = ("restitution",)
STRESSES = ("max_normal_stress", "alternating_bending_stress")
CONTACT = ("peak_contact_force", "contact_duration")
#: Method crosscheck: the real contact over the periodic solution, on the replayed revolution ...
REPLAY_RATIOS = ("peak_force_ratio", "normal_stress_ratio", "deflection_ratio")
#: ... and on the real contact's periodic orbit nearest the periodic solution, with its stability.
ORBIT_RATIOS = ("orbit_peak_force_ratio", "orbit_normal_stress_ratio", "max_floquet_multiplier")
#: Method reference-check: the periodic solution over the reference model.
REFERENCE_RATIOS = ("reference_peak_force_ratio", "reference_normal_stress_ratio", "reference_alternating_stress_ratio")
HARMONICS = (1, 2, 3)
#: Relative change of the span between neighbouring rotary speeds taken as a jump to another branch.
SPAN_BRANCH_JUMP = 0.2
ROUGH_POINT_LABEL = "not converged to the study's tolerance (its error: envelope.csv, the validity map)"
#: The section's own first mode meeting the 1x line: shown where it is, not as a critical speed of the joint (those are
#: the Campbell chart's, :mod:`study.charts.critical`).
CRITICAL_SPEED_LABEL = "the section's first mode meets 1× (N = 60 f1)"
SECTION_MODE_TEXT = "the section's first mode meets 1× at N = 60 f1"
_ORDINALS = ("first", "second", "third", "fourth", "fifth", "sixth")

@dataclass
class Chart:
    """One drawn figure and the file name (without extension) it is saved under."""

    name: str
    figure: Figure
    caption: str = ""  # one sentence: what the chart shows (the report prints it under the chart)
    title: str = ""  # the figure's title, kept once the figure is saved and cleared


# ---------------------------------------------------------------------------------------------
# Which dimension plays which role


@dataclass
class _Plan:
    x: str
    series: str | None  # one line per value (line charts) or the y axis (maps)
    panel: str | None
    figure: str | None
    reduced: list[str] = field(default_factory=list)
    same: list[str] = field(default_factory=list)
    fixed: list[str] = field(default_factory=list)


def full_array(ds: xr.Dataset, name: str) -> xr.DataArray:
    """The variable over every dimension of the dataset (broadcast where it does not vary)."""
    da = ds[name]
    missing = {d: ds.sizes[d] for d in ds.sizes if d not in da.dims}
    if missing:
        da = da.expand_dims(missing)
    return da.transpose(*ds.sizes)


def _constant_along(da: xr.DataArray, dim: str) -> bool:
    """Every result agrees along ``dim`` (failed points, NaN, are ignored)."""
    values = da.transpose(dim, ...).values
    if values.dtype.kind != "f":
        return bool(np.all(values == values[:1]))
    with np.errstate(invalid="ignore"), warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # all-NaN slices
        high, low = np.nanmax(values, axis=0), np.nanmin(values, axis=0)
    spread = (high - low)[np.isfinite(high)]
    scale = np.maximum(np.abs(high), np.abs(low))[np.isfinite(high)]
    return bool(np.all(spread <= 1e-9 * scale))


def preferred_dims(ds: xr.Dataset) -> list[str]:
    """Dimensions in the order they take roles: rotary speed, axial load, numeric, then text."""
    dims = list(ds.sizes)
    return sorted(dims, key=lambda d: (d != RPM, d != LOAD, ds[d].dtype.kind in "USO", dims.index(d)))


def _plan(ds: xr.Dataset, arrays: Sequence[xr.DataArray], x: str, series: str | None, *,
          collapse_series: bool) -> _Plan:
    dims = list(ds.sizes)
    fixed = [d for d in dims if ds.sizes[d] == 1 and d not in (x, series)]
    same = [d for d in dims if d != x and d not in fixed and ds.sizes[d] > 1
            and (collapse_series or d != series) and all(_constant_along(a, d) for a in arrays)]
    if series in same:
        series = None
    extras = [d for d in dims if d not in (x, series) and d not in fixed and d not in same]
    extras.sort(key=lambda d: (d not in PANEL_FIRST, dims.index(d)))
    return _Plan(x, series, extras[0] if extras else None, extras[1] if len(extras) > 1 else None,
                 extras[2:], same, fixed)


def _select(da: xr.DataArray, plan: _Plan, figure_index: int | None, panel_index: int | None) -> xr.DataArray:
    """The (x[, series]) slice of one panel; extra dimensions reduced by their maximum.

    Dimensions along which the results agree are reduced by their maximum too, so a point that
    failed at one of their values but not at another still shows its result.
    """
    index = {d: 0 for d in plan.fixed}
    if plan.figure is not None:
        index[plan.figure] = figure_index
    if plan.panel is not None:
        index[plan.panel] = panel_index
    da = da.isel(index)
    if plan.reduced or plan.same:
        with np.errstate(invalid="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            da = da.max(dim=plan.reduced + plan.same, skipna=True)
    return da.transpose(*[d for d in (plan.x, plan.series) if d is not None])


def axis_names(ds: xr.Dataset, dims: Sequence[str]) -> str:
    return _join([quantity(ds[d]).short_name for d in dims])


def _join(words: Sequence[str]) -> str:
    words = list(words)
    return words[0] if len(words) == 1 else ", ".join(words[:-1]) + " and " + words[-1]


def _context(ds: xr.Dataset, plan: _Plan, figure_index: int | None, reduction: str = "maximum over") -> list[str]:
    """Title lines saying which slice a figure shows and how other dimensions were treated."""
    parts = []
    if plan.figure is not None:
        parts.append(quantity(ds[plan.figure]).describe(ds[plan.figure].values[figure_index]))
    parts += [quantity(ds[d]).describe(ds[d].values[0]) for d in plan.fixed]
    if plan.same:
        parts.append(f"same for every {axis_names(ds, plan.same)}")
    if plan.reduced:
        parts.append(f"{reduction} {axis_names(ds, plan.reduced)}")
    return parts


# ---------------------------------------------------------------------------------------------
# Axes helpers


def axis_positions(ds: xr.Dataset, dim: str, q: Quantity | None = None):
    """Display positions of a dimension's values and tick labels (text values sit at 0, 1, ...)."""
    q = q or quantity(ds[dim])
    values = ds[dim].values
    if q.is_text:
        return np.arange(len(values), dtype=float), [str(v) for v in values]
    return np.asarray(q.convert(values), dtype=float), None


def cell_edges(centres: np.ndarray) -> np.ndarray:
    """Cell edges around grid points: midway between neighbours, half a step beyond the ends."""
    centres = np.asarray(centres, dtype=float)
    if centres.size == 1:
        half = 0.05 * abs(centres[0]) or 0.5
        return np.array([centres[0] - half, centres[0] + half])
    mid = 0.5 * (centres[1:] + centres[:-1])
    return np.concatenate([[2 * centres[0] - mid[0]], mid, [2 * centres[-1] - mid[-1]]])


def _limits(values, pad: float = 0.05):
    finite = np.asarray(values, dtype=float)
    finite = finite[np.isfinite(finite)]
    if finite.size == 0:
        return None
    low, high = float(finite.min()), float(finite.max())
    if high == low:
        half = 0.1 * abs(low) or 1.0
        return low - half, high + half
    return low - pad * (high - low), high + pad * (high - low)


def format_axis(axis, ticklabels=None, positions=None, grid_values=None):
    """Tick labels of an axis: text values by name; a short numeric sweep (at most 12 values) at its
    own values, so a non-uniform grid reads off directly; otherwise plain numbers."""
    if ticklabels is not None:
        axis.set_major_locator(ticker.FixedLocator(positions))
        axis.set_major_formatter(ticker.FixedFormatter(ticklabels))
        return
    if grid_values is not None and 1 <= len(grid_values) <= 12 and axis.get_scale() == "linear":
        axis.set_major_locator(ticker.FixedLocator(grid_values))
    elif axis.get_scale() == "log":
        low, high = sorted(axis.get_view_interval())
        narrow = low > 0 and math.log10(high / low) < 1.2  # less than a decade or so: label 1 to 9
        axis.set_major_locator(ticker.LogLocator(subs=np.arange(1.0, 10.0) if narrow else (1.0, 2.0, 5.0)))
        axis.set_minor_formatter(ticker.NullFormatter())
    axis.set_major_formatter(TickFormatter())


def series_colours(ds: xr.Dataset, dim: str | None) -> list:
    if dim is None:
        return ["C0"]
    n = ds.sizes[dim]
    if ds[dim].dtype.kind in "USO":
        return [colormaps["tab10"](i % 10) for i in range(n)]
    cmap = colormaps["viridis"]
    return [cmap(0.85 * i / (n - 1)) if n > 1 else cmap(0.0) for i in range(n)]


def _grid(n_panels: int, max_columns: int = 4) -> tuple[int, int]:
    """Columns and rows for ``n_panels`` panels, at most ``max_columns`` wide."""
    rows = math.ceil(n_panels / max_columns)
    columns = math.ceil(n_panels / rows)
    return columns, rows


def figure_title(fig: Figure, title: str, context: Sequence[str], width_inches: float):
    """The figure's title and its context lines, wrapped to the figure's width: about 10 characters of the 11-pt
    title font per inch (DejaVu Sans averages 0.6 em a character), so that no line runs past the figure's edges."""
    width = max(40, int(width_inches * 10))
    lines = textwrap.wrap(title, width) + (textwrap.wrap("; ".join(context), width) if context else [])
    fig.suptitle("\n".join(lines), fontsize=11)


def _outer_labels(axes: np.ndarray, visible: np.ndarray):
    """Keep x tick labels on the lowest visible panel of each column, y tick labels on the first column."""
    rows, columns = axes.shape
    for r in range(rows):
        for c in range(columns):
            if not visible[r, c]:
                axes[r, c].set_visible(False)
                continue
            below = any(visible[r2, c] for r2 in range(r + 1, rows))
            if below:
                axes[r, c].tick_params(labelbottom=False)
                axes[r, c].set_xlabel("")
            if c > 0:
                axes[r, c].tick_params(labelleft=False)
                axes[r, c].set_ylabel("")


def mark_missing(ax):
    """Hatch the axes background: cells left empty (NaN) show as hatched, not as a colour."""
    ax.patch.set_facecolor("white")
    ax.patch.set_hatch("////")
    ax.patch.set_edgecolor("0.75")


# ---------------------------------------------------------------------------------------------
# Generic line and map figures


def _panel_figures(ds, plan, size, rows, columns):
    """One figure per value of the plan's figure dimension (one figure without it): yields the index
    (or None), the figure of ``size`` [in], its rows × columns axes and a mask of the axes drawn on."""
    for fi in (range(ds.sizes[plan.figure]) if plan.figure else [None]):
        fig = Figure(figsize=size, dpi=DPI, layout="constrained")
        axes = fig.subplots(rows, columns, squeeze=False)
        yield fi, fig, axes, np.zeros(axes.shape, dtype=bool)


def _line_charts(ds: xr.Dataset, chart: str, title: str, names: Sequence[str], x: str, series: str | None, *,
                 overlay: str | None = None, x_quantity: Quantity | None = None,
                 y_quantities: dict[str, Quantity] | None = None,
                 decorate: Callable | None = None, extra_handles: Sequence = (),
                 scales: tuple[str, str] = ("linear", "linear"),
                 xlim=None, ylim=None, extra_context: Callable | None = None, break_jump: float | None = None,
                 caption: str = "", rough: xr.DataArray | None = None) -> list[Chart]:
    """Lines of ``names`` against ``x``, one per value of ``series``; one row of panels per name,
    or all names in the same panels (line styles) when ``overlay`` gives their common y label; with
    ``break_jump`` a line is broken where it jumps (see :func:`branch_breaks`); with ``rough`` (a mask over the
    dataset's dimensions) a value from a point there (reduced dimensions: any) is drawn as a hollow marker."""
    arrays = {n: full_array(ds, n) for n in names}
    rough_full = rough.transpose(*ds.sizes).astype(float) if rough is not None else None
    any_rough = False
    plan = _plan(ds, list(arrays.values()), x, series, collapse_series=True)
    xq = x_quantity or quantity(ds[x])
    xpos, xticks = axis_positions(ds, x, xq)
    yq = {n: (y_quantities or {}).get(n) or quantity(ds[n]) for n in names}
    n_panels = ds.sizes[plan.panel] if plan.panel else 1
    columns, rows_per = _grid(n_panels)
    blocks = [list(names)] if overlay else [[n] for n in names]
    rows = rows_per * len(blocks)
    styles = ["-", "--", ":", "-."]
    colours = series_colours(ds, plan.series)
    limits = {n: ylim or _limits(yq[n].convert(arrays[n].values)) for n in names}
    if overlay:
        lows = [v[0] for v in limits.values() if v]
        limits = {n: ylim or ((min(lows), max(v[1] for v in limits.values() if v)) if lows else None) for n in names}
    legend_width = 2.2
    width = min(4.0 + 3.6 * columns, 20.0) + legend_width - 1.0
    height = min(max(5.0, 1.3 + 2.9 * rows), 16.0)
    charts = []
    for fi, fig, axes, visible in _panel_figures(ds, plan, (width, height), rows, columns):
        drawn = np.zeros(ds.sizes[plan.series] if plan.series else 1, dtype=bool)  # a series with a result
        for b, block in enumerate(blocks):
            for p in range(n_panels):
                r, c = b * rows_per + p // columns, p % columns
                ax = axes[r, c]
                visible[r, c] = True
                panel_has_data = False
                for k, name in enumerate(block):
                    values = yq[name].convert(_select(arrays[name], plan, fi, p).values)
                    if plan.series is None:
                        values = values[:, None]
                    drawn |= np.isfinite(values).any(axis=0)
                    panel_has_data |= bool(np.isfinite(values).any())
                    marked = None
                    if rough_full is not None:
                        marked = _select(rough_full, plan, fi, p).values > 0
                        marked = marked[:, None] if plan.series is None else marked
                    for s in range(values.shape[1]):
                        xs, ys = (xpos, values[:, s]) if break_jump is None else branch_breaks(xpos, values[:, s],
                                                                                                break_jump)
                        ax.plot(xs, ys, color=colours[s], ls=styles[k % len(styles)], lw=1.6,
                                marker="o", ms=3 if xpos.size <= 40 or break_jump is not None else 0)
                        if marked is not None and np.any(marked[:, s] & np.isfinite(values[:, s])):
                            where = marked[:, s] & np.isfinite(values[:, s])
                            any_rough = True
                            ax.plot(xpos[where], values[where, s], ls="none", marker="o", ms=6, mfc="white",
                                    mec=colours[s], mew=1.3, zorder=4, gid="not converged")
                ax.set_xscale(scales[0])
                ax.set_yscale(scales[1])
                if not panel_has_data:  # keep the panel's axis on the swept range and say why it is empty
                    ax.set_xlim(xpos[0], xpos[-1]) if xpos.size > 1 else None
                    ax.text(0.5, 0.5, "no result at these inputs\n(see the validity map)", transform=ax.transAxes,
                            ha="center", va="center", fontsize=9, color="0.4")
                if decorate is not None:
                    decorate(ax, plan, fi, p, colours)
                if xlim is not None:
                    ax.set_xlim(xlim)
                if limits[block[0]] is not None:
                    ax.set_ylim(limits[block[0]])
                format_axis(ax.xaxis, xticks, xpos, grid_values=xpos)
                format_axis(ax.yaxis)
                ax.grid(True, which="major", color="0.9", lw=0.6)
                ax.set_axisbelow(True)
                ax.set_xlabel(xq.label)
                ax.set_ylabel(overlay or yq[block[0]].label)
                if plan.panel is not None and (b == 0 or rows_per > 1):
                    ax.set_title(quantity(ds[plan.panel]).describe(ds[plan.panel].values[p]), fontsize=10)
        _outer_labels(axes, visible)
        handles = []
        if plan.series is not None:
            sq = quantity(ds[plan.series])
            for s in range(ds.sizes[plan.series]):
                label = sq.value_text(ds[plan.series].values[s])
                if not drawn[s]:
                    label += " (no result)"
                handles.append(Line2D([], [], color=colours[s], lw=1.6, marker="o", ms=3, label=label))
        if overlay and len(names) > 1:
            handles += [Line2D([], [], color="0.3", ls=styles[k % len(styles)], label=yq[n].short_name)
                        for k, n in enumerate(names)]
        handles += list(extra_handles)
        if any_rough:
            handles.append(Line2D([], [], ls="none", marker="o", ms=6, mfc="white", mec="0.2", mew=1.3,
                                  label=ROUGH_POINT_LABEL))
        if handles:
            fig.legend(handles=handles, loc="outside right center", fontsize=8,
                       title=quantity(ds[plan.series]).short_name if plan.series else None, title_fontsize=8,
                       frameon=False)
        context = _context(ds, plan, fi)
        if extra_context is not None:
            context += extra_context(plan, fi)
        figure_title(fig, title, context, width)
        labels = [h.get_label() for h in handles if h.get_label() == ROUGH_POINT_LABEL]
        charts.append(Chart(_file_name(ds, chart, plan.figure, fi), fig,
                            caption + (f" Hollow markers: {ROUGH_POINT_LABEL}." if labels else "")))
    return charts


def branch_breaks(x: np.ndarray, y: np.ndarray, jump: float) -> tuple[np.ndarray, np.ndarray]:
    """``x`` and ``y`` with a NaN point inserted midway wherever ``y`` changes by more than ``jump`` (relative to
    the smaller of the two neighbours): a line drawn through them is broken there, so two solution branches
    are never joined."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    with np.errstate(invalid="ignore", divide="ignore"):
        change = np.abs(np.diff(y)) / np.minimum(np.abs(y[:-1]), np.abs(y[1:]))
    cut = np.flatnonzero(change > jump) + 1
    return np.insert(x, cut, 0.5 * (x[cut - 1] + x[cut])), np.insert(y, cut, np.nan)


def _map_charts(ds: xr.Dataset, chart: str, title: str, names: Sequence[str], x: str, y: str,
                cmap: str = "YlOrRd", centre: float | None = None, caption: str = "") -> list[Chart]:
    """Colour maps of ``names`` over ``x`` x ``y``: a row of panels per name, a colour bar per row; with
    ``centre`` the colour scale diverges from that value (e.g. 1 for a ratio)."""
    arrays = {n: full_array(ds, n) for n in names}
    plan = _plan(ds, list(arrays.values()), x, y, collapse_series=False)
    xq, yq_axis = quantity(ds[x]), quantity(ds[y])
    xpos, xticks = axis_positions(ds, x, xq)
    ypos, yticks = axis_positions(ds, y, yq_axis)
    xedges, yedges = cell_edges(xpos), cell_edges(ypos)
    vq = {n: quantity(ds[n]) for n in names}
    ranges = {n: _limits(vq[n].convert(arrays[n].values), pad=0.0) for n in names}
    n_panels = ds.sizes[plan.panel] if plan.panel else 1
    columns, rows_per = _grid(n_panels)
    rows = rows_per * len(names)
    width = min(2.0 + 3.6 * columns, 20.0)
    height = min(1.4 + 2.9 * rows, 16.0)
    contours = xpos.size >= 3 and ypos.size >= 3
    charts = []
    for fi, fig, axes, visible in _panel_figures(ds, plan, (width, height), rows, columns):
        any_missing = False
        for b, name in enumerate(names):
            mesh = None
            block_axes = []
            vmin, vmax = ranges[name] or (0.0, 1.0)
            norm = None
            if centre is not None:
                spread = max(vmax - centre, centre - vmin, 1e-3 * abs(centre) or 1e-3)
                vmin, vmax = min(vmin, centre - 1e-3 * spread), max(vmax, centre + 1e-3 * spread)
                norm = TwoSlopeNorm(centre, vmin, vmax)
            for p in range(n_panels):
                r, c = b * rows_per + p // columns, p % columns
                ax = axes[r, c]
                visible[r, c] = True
                block_axes.append(ax)
                values = vq[name].convert(_select(arrays[name], plan, fi, p).values).T  # rows: y
                masked = np.ma.masked_invalid(values)
                if masked.mask.any():
                    any_missing = True
                    mark_missing(ax)
                limits = {"norm": norm} if norm is not None else {"vmin": vmin, "vmax": vmax}
                mesh = ax.pcolormesh(xedges, yedges, masked, cmap=cmap, shading="flat", **limits)
                if contours and not masked.mask.any() and np.ptp(masked.compressed()) > 0:  # filled data only
                    levels = ticker.MaxNLocator(9).tick_values(vmin, vmax)
                    lines = ax.contour(xpos, ypos, masked, levels=levels, colors="k", linewidths=0.5, alpha=0.6)
                    ax.clabel(lines, fmt=tick_format, fontsize=7, inline=True)
                ax.set_xlim(xedges[0], xedges[-1])
                ax.set_ylim(yedges[0], yedges[-1])
                format_axis(ax.xaxis, xticks, xpos, grid_values=xpos)
                format_axis(ax.yaxis, yticks, ypos, grid_values=ypos)
                ax.set_xlabel(xq.label)
                ax.set_ylabel(yq_axis.label)
                panel = quantity(ds[plan.panel]).describe(ds[plan.panel].values[p]) if plan.panel else ""
                ax.set_title(f"{vq[name].short_name}" + (f", {panel}" if panel else ""), fontsize=9)
            bar = fig.colorbar(mesh, ax=block_axes, label=vq[name].label, shrink=0.95, pad=0.02)
            bar.ax.yaxis.set_major_formatter(TickFormatter())
        _outer_labels(axes, visible)
        context = _context(ds, plan, fi)
        if any_missing:
            context.append("hatched: no result (the validity map says why)")
        figure_title(fig, title, context, width)
        charts.append(Chart(_file_name(ds, chart, plan.figure, fi), fig, caption))
    return charts


def _file_name(ds: xr.Dataset, chart: str, dim: str | None, index: int | None) -> str:
    if dim is None:
        return chart
    slug = quantity(ds[dim]).describe(ds[dim].values[index]).lower().replace(",", "")
    slug = re.sub(r"[^a-z0-9.\-]+", "_", slug).strip("_")
    return f"{chart}__{slug}"


# ---------------------------------------------------------------------------------------------
# The charts


def map_or_line_dims(ds: xr.Dataset) -> list[str]:
    """Swept dimensions with more than one value, rotary speed and axial load first."""
    return [d for d in preferred_dims(ds) if ds.sizes[d] > 1]


def _line_series(ds: xr.Dataset, x: str) -> str | None:
    if LOAD in ds.sizes and LOAD != x:
        return LOAD
    others = [d for d in preferred_dims(ds) if d != x and ds.sizes[d] > 1]
    return others[0] if others else None


def stress_maps(ds: xr.Dataset) -> list[Chart]:
    """Maximum normal stress and alternating bending stress over rotary speed x axial load.

    Filled maps with labelled iso-lines, one panel per restitution (or the next swept input), one
    figure per mud density (or the one after), further inputs reduced by their maximum. Unless both
    the speed and the load are swept (more than one value each), lines instead: against the speed
    (else the load, else the first swept input), one line per value of the next swept input.
    """
    names = [n for n in STRESSES if n in ds.data_vars]
    if not names:
        return []
    return _maps_or_lines(ds, "stress_maps", "Pipe stresses: " + _join([quantity(ds[n]).short_name for n in names]),
                          names, caption="The largest normal stress and the alternating bending stress of the pipe "
                                         "over the swept inputs.")


def _maps_or_lines(ds: xr.Dataset, chart: str, title: str, names: Sequence[str], cmap: str = "YlOrRd",
                   centre: float | None = None, caption: str = "") -> list[Chart]:
    """Maps of ``names`` over rotary speed x axial load where both are swept, else lines against the
    first swept input, one line per value of the next (see :func:`stress_maps`)."""
    if not ds.sizes or 0 in ds.sizes.values():
        return []
    dims = map_or_line_dims(ds)
    if RPM in dims and LOAD in dims:
        return _map_charts(ds, chart, title, names, RPM, LOAD, cmap=cmap, centre=centre, caption=caption)
    x = dims[0] if dims else preferred_dims(ds)[0]
    return _line_charts(ds, chart, title, names, x, dims[1] if len(dims) > 1 else None, caption=caption)


def crosscheck_maps(ds: xr.Dataset) -> list[Chart]:
    """Method crosscheck: peak contact force, largest normal stress and largest deflection of the real
    contact over the periodic solution's (1: they agree), laid out as :func:`stress_maps`."""
    names = [n for n in REPLAY_RATIOS if n in ds.data_vars]
    if not names:
        return []
    words = {"peak_force_ratio": "peak contact force", "normal_stress_ratio": "normal stress",
             "deflection_ratio": "deflection"}
    return _maps_or_lines(ds, "crosscheck", "Real contact over the periodic solution (1: they agree): "
                          + _join([words[n] for n in names]), names, cmap="coolwarm", centre=1.0,
                          caption="How far the periodic solution is from a replay with real contact: 1 means the "
                                  "two methods agree.")


def _where_found(ds: xr.Dataset, found: xr.DataArray) -> xr.Dataset:
    """``ds`` at only the values of each swept input where ``found`` holds at some point: the others would be
    empty panels, and "the same for every ..." (a dimension whose values agree where present) would not be
    true."""
    keep = {d: found.any([o for o in found.dims if o != d]).values for d in found.dims}
    return ds.isel({d: np.flatnonzero(k) for d, k in keep.items() if not k.all()})


def orbit_maps(ds: xr.Dataset) -> list[Chart]:
    """Method crosscheck: the real contact's periodic orbit nearest the periodic solution - its peak force
    and largest normal stress over the periodic solution's, and its largest Floquet multiplier (above 1:
    unstable). Drawn only where some point has such an orbit."""
    names = [n for n in ORBIT_RATIOS if n in ds.data_vars]
    if "orbit_distance" not in ds.data_vars or not names:
        return []
    found = np.isfinite(full_array(ds, "orbit_distance"))
    if not found.any():
        return []
    ds = _where_found(ds, found)  # e = 1 alone, typically
    title = ("The real contact's orbit nearest the periodic solution: force and stress over the periodic "
             "solution's, and its stability (multiplier above 1: unstable)")
    return _maps_or_lines(ds, "orbit", title, names, cmap="coolwarm", centre=1.0,
                          caption="The real contact's own periodic orbit against the periodic solution, and whether "
                                  "it is stable (multiplier under 1).")


def reference_maps(ds: xr.Dataset) -> list[Chart]:
    """Method reference-check: peak contact force, largest normal stress and alternating bending stress of the
    periodic solution over the reference model's (1: the paper's model may be trusted there; blank where
    either does not strike the wall), laid out as :func:`stress_maps`, at the values of the swept inputs
    where some point has a ratio."""
    names = [n for n in REFERENCE_RATIOS if n in ds.data_vars]
    found = np.isfinite(full_array(ds, names[0])) if names else None
    if found is None or not found.any():
        return []
    ds = _where_found(ds, found)  # where both strike the wall
    words = {"reference_peak_force_ratio": "peak contact force", "reference_normal_stress_ratio": "normal stress",
             "reference_alternating_stress_ratio": "alternating stress"}
    return _maps_or_lines(ds, "reference_check", "Periodic solution over the reference model (1: they agree): "
                          + _join([words[n] for n in names]), names, cmap="coolwarm", centre=1.0)


#: Methods whose span is an answer (a search over the span condition); elsewhere the span is an input (the section
#: length, ``solver.span_length``) and its chart would be a flat line of the input.
SPAN_SEARCHES = ("fast", "series", "periodic", "damped", "crosscheck", "reference-check")


def span_length_vs_rpm(ds: xr.Dataset) -> list[Chart]:
    """Span length between nodes against rotary speed, one line per axial load; drawn only where some point's span
    is an answer (a method of :data:`SPAN_SEARCHES`, or a dataset that does not say its methods)."""
    if "span_length" not in ds.data_vars or RPM not in ds.sizes or ds.sizes[RPM] == 0:
        return []
    if "method" in ds.data_vars and not np.isin(np.asarray(ds["method"].values).astype(str), SPAN_SEARCHES).any():
        return []
    return _line_charts(ds, "span_length", "Span length against rotary speed", ["span_length"], RPM,
                        _line_series(ds, RPM), break_jump=SPAN_BRANCH_JUMP,
                        extra_context=lambda plan, fi: [f"a line is broken where the span changes by more than "
                                                        f"{SPAN_BRANCH_JUMP:.0%} between neighbouring speeds "
                                                        "(another solution branch)"],
                        caption="The length between nodes of the vibrating span the periodic solution finds at each "
                                "speed; a break in a line is a jump to another solution branch, not a trend.")


def contact_force_and_duration_vs_rpm(ds: xr.Dataset) -> list[Chart]:
    """Peak contact force and contact duration against rotary speed, one line per axial load."""
    names = [n for n in CONTACT if n in ds.data_vars]
    if not names or RPM not in ds.sizes or ds.sizes[RPM] == 0:
        return []
    title = _join([quantity(ds[n]).short_name for n in names]).capitalize() + " against rotary speed"
    rough = None
    if "status" in ds.data_vars:  # answers only: ok, or not converged (marked); other statuses' values are not drawn
        from study.solvers.model.result import STATUS_CODES

        status = full_array(ds, "status")
        answered = (status == STATUS_CODES["ok"]) | (status == STATUS_CODES["not_converged"])
        rough = status == STATUS_CODES["not_converged"]
        ds = ds.assign({n: full_array(ds, n).where(answered) for n in names})
    what = "How hard and how long" if "contact_duration" in names else "How hard"
    return _line_charts(ds, "contact_force_duration", title, names, RPM, _line_series(ds, RPM), rough=rough,
                        caption=f"{what} the pipe strikes the wall at each speed, one line per load (the largest over "
                                "the inputs reduced), answered points only.")


def _mode_names(ds: xr.Dataset) -> list[str]:
    names = [n for n in ds.data_vars if str(n).endswith("natural_frequency")]

    def order(name):
        prefix = str(name)[: -len("natural_frequency")].rstrip("_")
        return (_ORDINALS.index(prefix) if prefix in _ORDINALS else len(_ORDINALS), str(name))

    return sorted(names, key=order)


def _critical_speeds(speeds: np.ndarray, f1: np.ndarray) -> list[float]:
    """Speeds [rpm] where the classical rule N = 60 f1 holds along one swept curve f1(N) [Hz].

    Where f1 does not depend on the speed this is just 60 f1. Otherwise it is where the 1x line
    crosses the curve, interpolated between grid points; without a crossing in the swept range,
    60 f1 at the end of the range nearest to one.
    """
    ok = np.isfinite(f1) & np.isfinite(speeds)
    n, f = speeds[ok], f1[ok]
    if n.size == 0:
        return []
    g = 60.0 * f - n
    roots = [float(n[i]) for i in range(n.size) if g[i] == 0.0]
    for i in range(n.size - 1):
        if g[i] * g[i + 1] < 0.0:
            roots.append(float(n[i] + g[i] * (n[i + 1] - n[i]) / (g[i] - g[i + 1])))
    if roots:
        return sorted(roots)
    return [float(60.0 * f[int(np.argmin(np.abs(g)))])]


def _curves(values: np.ndarray) -> np.ndarray:
    """An array with the speed first as columns of curves: shape (speeds, curves)."""
    return values.reshape(values.shape[0], -1)


def natural_frequencies_vs_rpm(ds: xr.Dataset) -> list[Chart]:
    """Natural frequencies of the span against rotary speed (a Campbell diagram).

    With the rotation harmonics f = k N / 60 (k = 1, 2, 3; N in rpm) and where the span's first mode meets the 1x
    line, N = 60 f1, as a dotted vertical line per axial load with a circle: a low mode of the whole span, not a
    critical speed (the joint's, which the envelope and the bands use, are :mod:`study.charts.critical`'s). Both axes
    turn logarithmic when the frequencies or speeds span more than a decade or so, as they do when the span is long.
    """
    names = _mode_names(ds)
    if not names or RPM not in ds.sizes or ds.sizes[RPM] == 0:
        return []
    xq = quantity(ds[RPM], unit="rpm")
    fq = {n: quantity(ds[n], unit="Hz") for n in names}
    xpos, _ = axis_positions(ds, RPM, xq)
    full_first = full_array(ds, names[0]).transpose(RPM, ...)  # speed first, for _curves

    def critical(values):
        curves = _curves(fq[names[0]].convert(values))
        return np.array([n for c in range(curves.shape[1]) for n in _critical_speeds(xpos, curves[:, c])])

    freqs = np.concatenate([fq[n].convert(ds[n].values).ravel() for n in names])
    freqs = freqs[np.isfinite(freqs) & (freqs > 0)]
    crit = critical(full_first.values)
    crit = crit[crit > 0]
    x_low, x_high = float(np.min(xpos)), float(np.max(xpos))
    if crit.size:  # show the classical critical speeds, within a factor of 20 of the swept speeds
        x_low = min(x_low, max(float(crit.min()), x_low / 20.0))
        x_high = max(x_high, min(float(crit.max()), x_high * 20.0))
    if x_high == x_low:
        x_low, x_high = (0.8 * x_low, 1.25 * x_high) if x_high > 0 else (0.0, 1.0)
    f_low = min([x_low / 60.0] + ([float(freqs.min())] if freqs.size else []))
    f_high = max([max(HARMONICS) * x_high / 60.0] + ([float(freqs.max())] if freqs.size else []))
    log = x_low > 0 and f_low > 0 and (x_high / x_low > 8.0 or f_high / f_low > 20.0)
    if log:
        xlim, ylim = (x_low / 1.15, x_high * 1.15), (f_low / 1.3, f_high * 1.3)
    else:
        xlim = (max(0.0, x_low - 0.05 * (x_high - x_low)), x_high + 0.05 * (x_high - x_low))
        ylim = (0.0, 1.05 * f_high)
    line_x = np.geomspace(*xlim, 200) if log else np.linspace(*xlim, 200)

    def decorate(ax, plan, fi, p, colours):
        for k in HARMONICS:
            ax.plot(line_x, k * line_x / 60.0, color="0.45", lw=0.9, ls=(0, (5, 3)), zorder=1)
            # label each harmonic where it leaves the plot (right edge or top)
            x_end = min(xlim[1], ylim[1] * 60.0 / k)
            x_text = x_end / 1.08 if log else x_end - 0.03 * (xlim[1] - xlim[0])
            ax.text(x_text, k * x_text / 60.0, f"{k}×", fontsize=8, color="0.3", ha="right", va="bottom")
        curves = _curves(fq[names[0]].convert(_select(full_first, plan, fi, p).values))
        for s in range(curves.shape[1]):
            for speed in _critical_speeds(xpos, curves[:, s]):
                ax.axvline(speed, color=colours[s], ls=":", lw=1.4, zorder=2)
                ax.plot([speed], [speed / 60.0], marker="o", ms=4, mfc="white", mec=colours[s], zorder=3)

    handles = [
        Line2D([], [], color="0.45", lw=0.9, ls=(0, (5, 3)), label="rotation harmonics\nf = k·N/60, k = 1, 2, 3"),
        Line2D([], [], color="0.2", lw=1.4, ls=":", marker="o", ms=4, mfc="white", mec="0.2",
               label=CRITICAL_SPEED_LABEL),
    ]

    def extra_context(plan, fi):
        index = {plan.figure: fi} if plan.figure is not None else {}
        values = critical(full_first.isel(index).values)
        if not values.size:
            return []
        low, high = float(values.min()), float(values.max())
        where = ""
        if high < float(np.min(xpos)):
            where = ", below the swept speeds"
        elif low > float(np.max(xpos)):
            where = ", above the swept speeds"
        span = format_value(low) if high - low <= 1e-6 * abs(high) else f"{format_value(low)}–{format_value(high)}"
        return [f"{SECTION_MODE_TEXT}: {span} rpm{where} (a mode of the whole span; the joint's critical speeds are "
                "the Campbell chart's)"]

    title = "Natural frequencies of the span and rotation harmonics against rotary speed"
    overlay = "natural frequency [Hz]" if len(names) > 1 else None
    scale = "log" if log else "linear"
    return _line_charts(ds, "natural_frequencies", title, names, RPM, _line_series(ds, RPM), overlay=overlay,
                        x_quantity=xq, y_quantities=fq, decorate=decorate, extra_handles=handles,
                        scales=(scale, scale),
                        xlim=xlim, ylim=ylim, extra_context=extra_context,
                        caption="Natural frequencies of the span the method answers on (the periodic solution's span, "
                                "or the reference model's section), against the rotation harmonics; where its first "
                                "mode meets the 1× line is marked, a low mode of the whole span rather than a critical "
                                "speed: the joint's critical speeds, which the envelope and the bands use, are the "
                                "Campbell chart's.")


def save_figure(figure: Figure, path: Path, fmt: str = "png") -> Path:
    """Save ``figure`` to ``path`` atomically (a temporary file in the same folder, then a rename)."""
    with atomic_path(path) as tmp:
        figure.savefig(tmp, format=fmt, dpi=DPI)
    return Path(path)

