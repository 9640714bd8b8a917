"""The safe operating envelope: the rotary speed × axial load cells where every limit holds.

A cell is safe when every point in it (over every other swept input) is

- solved: status ``ok`` or ``yields`` (which then fails the yield limit; a point without a valid answer is not known to
be safe) — or ``not_converged`` to the
  study's tolerance but decided all the same: every limit below holds, or one fails, with its figure off by
  :data:`MARGIN` times its error — the figure's own where the point states it (the max normal stress's for yield,
  the fatigue life's, the alternating stress's for endurance: :func:`study.charts.plane.figure_errors`), else the
  point's error estimate as a stress error (a design decision far from a limit needs no 1 % answer; stresses that
  might be off by 100 % or more can show a limit holds, never that it fails);
- below yield: ``yield_utilisation`` ≤ 1;
- long-lived: ``fatigue_life`` ≥ the target (default :data:`~study.charts.limits.DEFAULT_TARGET_LIFE_HOURS`
  = 1000 h of rotation), or with ``criterion="endurance"`` below the endurance limit,
  ``endurance_utilisation`` ≤ 1 (an infinite-life design);
- away from resonance: outside ±15 % of every critical speed of the joint (:mod:`study.charts.critical`),
  where the dataset allows computing them (the chart says when it does not).

:func:`envelope_table` gives one row per cell (the CSV written beside the charts and the report's cell table): its
verdict — safe, limited (a decided failure or a critical-speed band) or undecided — and its worst values over every
answered point (undecided ones included) with their error; :func:`safe_ranges` the safe (or undecided) rotary speeds
per load (the report's table), :func:`envelope_chart` the map.
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib.colors import ListedColormap
from matplotlib.figure import Figure
from matplotlib.patches import Patch
from matplotlib.lines import Line2D

from study.atomic import atomic_path
from study.charts.critical import in_band
from study.charts.design import DPI, Chart, figure_title, full_array
from study.charts.labels import format_value, quantity
from study.charts.limits import DEFAULT_TARGET_LIFE_HOURS, HOUR
from study.charts.plane import (LIFE_SLOPE, MARGIN, answered_points, bounds, caption_from, draw_boundary,  # noqa: F401
                                figure_errors, ok_points, plane, plane_axes, solved_points, worst_in_cells)
from study.solvers.model.result import STATUS_CODES

#: Why a cell is outside the envelope, in the order the map colours them (the first that applies).
REASONS = ("no valid answer", "over yield", "fatigue", "critical speed")
COLOURS = {"safe": "#41ab5d", "no valid answer": "#bdbdbd", "over yield": "#a50f15", "fatigue": "#fd8d3c",
           "critical speed": "#6baed6"}
CRITERIA = ("life", "endurance")


def _limit(ds: xr.Dataset, name: str) -> xr.DataArray:
    """The output over every dimension, NaN where absent (an unknown value never passes a limit)."""
    if name in ds.data_vars:
        return full_array(ds, name)
    return xr.full_like(ok_points(ds), np.nan, dtype=float)


def failures(ds: xr.Dataset, target_hours: float = DEFAULT_TARGET_LIFE_HOURS, criterion: str = "life"
             ) -> tuple[dict[str, xr.DataArray], bool]:
    """Per point, which of :data:`REASONS` keep it out of the envelope (each a boolean over every dimension),
    and whether the critical speeds could be checked; beside them, under :data:`UNDECIDED`'s keys, the answered
    points not converged whose figure (yield utilisation, and the fatigue criterion's figure) neither holds nor fails
    its limit within its error: what keeps an undecided point open."""
    if criterion not in CRITERIA:
        raise ValueError(f"criterion = {criterion!r}; allowed: {', '.join(CRITERIA)}")
    if not target_hours > 0:
        raise ValueError(f"target_hours = {target_hours!r}; allowed: a positive number of hours")
    ok = solved_points(ds)  # ok, or yields: solved, and a yielding point fails the yield limit below
    rough = _rough(ds)  # not converged, its error stated
    with np.errstate(invalid="ignore", divide="ignore"):
        use, low, high = _bounded(ds, "yield_utilisation")
        yield_fails = (ok & ~(use <= 1.0)) | (rough & (low > 1.0))
        yield_holds = (ok & (use <= 1.0)) | (rough & (high <= 1.0))
        if criterion == "life":
            target = target_hours * HOUR
            life, low, high = _bounded(ds, "fatigue_life")
            fatigue_fails = (ok & ~(life >= target)) | (rough & (high < target))
            fatigue_holds = (ok & (life >= target)) | (rough & (low >= target))
        else:
            use, low, high = _bounded(ds, "endurance_utilisation")
            fatigue_fails = (ok & ~(use <= 1.0)) | (rough & (low > 1.0))
            fatigue_holds = (ok & (use <= 1.0)) | (rough & (high <= 1.0))
    # decided: ok, or every limit held or one failed within the margin
    answered = ok | (rough & ((yield_holds & fatigue_holds) | yield_fails | fatigue_fails))
    over_yield, fatigue = answered & yield_fails, answered & fatigue_fails
    band = in_band(ds)
    checked = band is not None
    critical = (band.transpose(*ds.sizes) if checked else xr.zeros_like(ok)).astype(bool)
    fatigue_name = "fatigue life" if criterion == "life" else "endurance utilisation"
    open_yield = rough & ~answered & ~yield_holds & ~yield_fails
    open_fatigue = rough & ~answered & ~fatigue_holds & ~fatigue_fails
    return {"no valid answer": ~answered, "over yield": over_yield, "fatigue": fatigue, "critical speed": critical,
            UNDECIDED["yield utilisation"]: open_yield, UNDECIDED[fatigue_name]: open_fatigue}, checked


#: The keys of :func:`failures`' masks of the points whose figure cannot be decided at its error, by figure.
UNDECIDED = {name: f"undecided: {name}" for name in ("yield utilisation", "fatigue life", "endurance utilisation")}


def _rough(ds: xr.Dataset) -> xr.DataArray:
    """True where a point is not converged to its tolerance and states its error estimate."""
    if "status" not in ds.data_vars or "error_estimate" not in ds.data_vars:
        return xr.zeros_like(ok_points(ds), dtype=bool)
    return (full_array(ds, "status") == STATUS_CODES["not_converged"]) & np.isfinite(full_array(ds, "error_estimate"))


def _bounded(ds: xr.Dataset, name: str) -> tuple[xr.DataArray, xr.DataArray, xr.DataArray]:
    """The output ``name`` (NaN where absent) and its low and high bounds with each point's error of it times
    :data:`MARGIN` (:func:`study.charts.plane.bounds`: the figure's own error where the point states it, else its
    error estimate as a stress error; a stress off by 100 % or more might be nil, so such a point cannot fail a
    limit)."""
    values = _limit(ds, name)
    errors, own = figure_errors(ds, name)
    low, high = bounds(values.values, errors.transpose(*values.dims).values, own.transpose(*values.dims).values, name)
    return values, values.copy(data=low), values.copy(data=high)


def decided_within_error(ds: xr.Dataset, target_hours: float = DEFAULT_TARGET_LIFE_HOURS, criterion: str = "life"
                         ) -> xr.DataArray:
    """True where a point not converged to the study's tolerance still counts (see the module docstring)."""
    return _decided(ds, failures(ds, target_hours, criterion)[0])


def _decided(ds: xr.Dataset, fails: dict[str, xr.DataArray]) -> xr.DataArray:
    """:func:`decided_within_error` from the points' :func:`failures`."""
    return ~fails["no valid answer"] & ~solved_points(ds)


def _has_limits(ds: xr.Dataset, criterion: str) -> bool:
    fatigue = "fatigue_life" if criterion == "life" else "endurance_utilisation"
    return "yield_utilisation" in ds.data_vars and fatigue in ds.data_vars


def criterion_text(target_hours: float, criterion: str) -> str:
    if criterion == "life":
        return f"fatigue life ≥ {format_value(target_hours)} h"
    return "below the endurance limit (endurance utilisation ≤ 1)"


#: A cell's verdict (the CSV's ``verdict``): every point decided and every limit held; some limit failed at a
#: decided point (or the cell is in a critical-speed band, which needs no solution); no limit failed at a decided
#: point but some point is undecided (its answer cannot be decided at its error, or it has no answer).
VERDICTS = ("safe", "limited", "undecided")


def envelope_table(ds: xr.Dataset, target_hours: float = DEFAULT_TARGET_LIFE_HOURS, criterion: str = "life"
                   ) -> list[dict]:
    """One row per rotary speed × axial load cell (display units): its verdict (:data:`VERDICTS`), what limits it
    (decided failures) or keeps it undecided, the points it holds (ok, decided within their error, undecided,
    without an answer), and per design figure the worst value over every answered point — undecided ones included —
    with the relative error estimate of the point that gives it and the cell's worst case with the stresses off by
    :data:`MARGIN` times each point's error estimate. Empty without the plane or the limits."""
    p = plane(ds)
    if p is None or not _has_limits(ds, criterion):
        return []
    fails, _ = failures(ds, target_hours, criterion)
    xq, yq = quantity(ds[p.x]), quantity(ds[p.y])
    ok = solved_points(ds)
    answered = answered_points(ds)
    undecided = fails["no valid answer"]
    reduced = {reason: p.reduce(mask, "any") for reason, mask in fails.items()}
    count = p.reduce(xr.ones_like(ok, dtype=int), "sum")
    ok_count = p.reduce(ok.astype(int), "sum")
    within = p.reduce(_decided(ds, fails).astype(int), "sum")
    open_count = p.reduce((undecided & answered).astype(int), "sum")
    no_answer = p.reduce((~answered).astype(int), "sum")
    figures = [("yield_utilisation", "max", "max yield utilisation", "[-]", 1.0),
               ("endurance_utilisation", "max", "max endurance utilisation", "[-]", 1.0),
               ("fatigue_life", "min", "min fatigue life", "[h]", 1.0 / HOUR)]
    absent = {k: np.full((ds.sizes[p.y], ds.sizes[p.x]), np.nan) for k in ("value", "error", "bound")}
    worst = {name: worst_in_cells(ds, name, how, p) if name in ds.data_vars else absent for name, how, *_ in figures}
    rows = []
    for i, load in enumerate(yq.convert(ds[p.y].values)):
        for j, speed in enumerate(xq.convert(ds[p.x].values)):
            limited = [r for r in REASONS[1:] if reduced[r][i, j]]
            verdict = "limited" if limited else ("undecided" if reduced[REASONS[0]][i, j] else "safe")
            why_open = []
            if open_count[i, j]:
                held_open = [name for name, key in UNDECIDED.items() if key in reduced and reduced[key][i, j]]
                why_open.append(f"{int(open_count[i, j])} point(s) undecided at their error"
                                + (f" ({', '.join(held_open)})" if held_open else ""))
            if no_answer[i, j]:
                why_open.append(f"{int(no_answer[i, j])} point(s) without an answer")
            row = {xq.label: _round(speed), yq.label: _round(load), "verdict": verdict, "safe": verdict == "safe",
                   "limited by": "; ".join(limited), "undecided because": "; ".join(why_open),
                   "points": int(count[i, j]), "ok points": int(ok_count[i, j]),
                   "decided within their error": int(within[i, j]), "undecided points": int(open_count[i, j]),
                   "points without an answer": int(no_answer[i, j])}
            for name, _, label, unit, scale in figures:
                w = worst[name]
                row[f"{label} {unit}"] = _round(w["value"][i, j] * scale, 4)
                row[f"{label}: its error estimate [-]"] = _round(w["error"][i, j], 3)
                row[f"{label} at {MARGIN:g}x error {unit}"] = _round(w["bound"][i, j] * scale, 4)
            rows.append(row)
    return rows


def _round(value, digits: int = 10) -> float:
    """``value`` to ``digits`` significant digits (unit conversion leaves 5000.000000000001)."""
    return float(f"{float(value):.{digits}g}")


def safe_ranges(rows: list[dict], verdict: str = "safe") -> list[tuple[str, str]]:
    """Per axial load (from :func:`envelope_table`'s rows), the rotary speeds whose cell has ``verdict`` (default
    safe) as runs of neighbouring grid speeds: [(load text, "60–120, 200 rpm" or "none"), ...]."""
    if verdict not in VERDICTS:
        raise ValueError(f"verdict = {verdict!r}; allowed: {', '.join(VERDICTS)}")
    if not rows:
        return []
    speed_key, load_key = list(rows[0])[:2]
    speed_unit = speed_key.split("[")[-1].rstrip("]")
    load_unit = load_key.split("[")[-1].rstrip("]")
    out = []
    for load in dict.fromkeys(r[load_key] for r in rows):
        mine = [r for r in rows if r[load_key] == load]
        runs: list[list[float]] = []
        previous = False
        for r in mine:
            here = r.get("verdict", "safe" if r["safe"] else "limited") == verdict
            if here:
                if previous:
                    runs[-1].append(r[speed_key])
                else:
                    runs.append([r[speed_key]])
            previous = here
        text = ", ".join(format_value(run[0]) if len(run) == 1 else f"{format_value(run[0])}–{format_value(run[-1])}"
                         for run in runs)
        out.append((f"{format_value(load)} {load_unit}", f"{text} {speed_unit}" if runs else "none"))
    return out


def write_table(rows: list[dict], path) -> Path:
    """Write :func:`envelope_table`'s rows to ``path`` as CSV, atomically."""
    path = Path(path)
    with atomic_path(path) as tmp:
        with open(tmp, "w", newline="", encoding="utf-8") as handle:
            writer = csv.DictWriter(handle, fieldnames=list(rows[0]) if rows else ["safe"])
            writer.writeheader()
            writer.writerows(rows)
    return path


def envelope_chart(ds: xr.Dataset, target_hours: float = DEFAULT_TARGET_LIFE_HOURS, criterion: str = "life"
                   ) -> list[Chart]:
    """The safe cells in green with the envelope outlined; every other cell coloured by the first limit it breaks.
    Drawn when the dataset has the limits (yield utilisation and the fatigue criterion's output)."""
    p = plane(ds)
    if p is None or not _has_limits(ds, criterion):
        return []
    fails, checked = failures(ds, target_hours, criterion)
    reduced = {reason: p.reduce(mask, "any") for reason, mask in fails.items()}
    # as the table's verdict: a decided limit first (in REASONS' order), else undecided, else safe
    names = ["safe", *REASONS[1:], REASONS[0]]
    category = np.zeros(reduced[REASONS[0]].shape, dtype=int)  # 0: safe
    for k, reason in enumerate(names[1:], start=1):
        category[reduced[reason] & (category == 0)] = k
    safe = category == 0
    fig = Figure(figsize=(10.0, 5.4), dpi=DPI, layout="constrained")
    ax = fig.subplots()
    ax.pcolormesh(p.xedges, p.yedges, category, cmap=ListedColormap([COLOURS[n] for n in names]), vmin=-0.5,
                  vmax=len(names) - 0.5, shading="flat", edgecolors="white", linewidth=0.3)
    if safe.any():
        draw_boundary(ax, safe, p, colors="k", linewidths=2.5)
    plane_axes(ax, p)
    shown = {REASONS[0]: "undecided (an answer not decided at its error, or none)"}
    handles = [Patch(facecolor=COLOURS[n], edgecolor="0.5", label=f"{shown.get(n, n)} ({int(np.sum(category == k))} "
                     "cells)") for k, n in enumerate(names) if np.any(category == k)]
    if safe.any():
        handles.append(Line2D([], [], color="k", lw=2.5, label="envelope boundary"))
    fig.legend(handles=handles, loc="outside right center", fontsize=8, frameon=False,
               title="cell (first limit broken)", title_fontsize=8)
    within = int(_decided(ds, fails).sum())
    context = [f"safe: every point answered and decided, yield utilisation ≤ 1, "
               f"{criterion_text(target_hours, criterion)}"
               + (", outside ±15 % of the joint's critical speeds (1× and 2×, the Campbell chart's)" if checked else
                  "; critical speeds NOT checked (the dataset lacks bending_stiffness, effective_tension or "
                  "mass_per_length)")]
    if within:
        context.append(f"decided: ok, or not converged to the study's tolerance with its limits holding or failing "
                       f"with the stresses off by {MARGIN:g}x its error estimate ({within} points)")
    context += p.context("every point must pass")
    figure_title(fig, "Safe operating envelope", context, 8.5)
    caption = caption_from("Where the pipe can run: green cells pass every limit at every value of the other swept "
                           "inputs; other cells show the first limit a decided point breaks, or that the cell is "
                           "undecided.", [h.get_label() for h in handles])
    return [Chart("envelope", fig, caption)]

