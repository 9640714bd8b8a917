"""Which input drives the design: how much each swept input moves each design figure, from the full-factorial grid.

The grid is full factorial, so the figure's variance over it splits exactly as in a factorial analysis of variance
(Saltelli et al., *Global Sensitivity Analysis: The Primer*, 2008, §1.2.11 and ch. 4; Montgomery, *Design and
Analysis of Experiments*, ch. 5): the **main effect** of input i is the variance over its levels of the figure's mean
at each level (the mean over every other input), as a share of the figure's whole variance — on a grid, the
first-order Sobol index S_i; the two-way interaction of i and j is the variance of the means over (i, j) less the two
main effects, S_ij; what the main effects leave (1 − Σ S_i) is every interaction together. Beside each main effect,
its **range**: how far the mean figure moves from the input's best level to its worst, in the figure's display unit.

The figures are taken over the answered points (ok, and not converged with their values: the bouncing pipe's
answers), each level's mean over those present; the fatigue life as its logarithm (it spans decades: a share of its
variance is a share of decades; an infinite life, no damage, is left out). A grid with a point missing is then not
exactly orthogonal: the table says how many points were used.
"""

from __future__ import annotations

import itertools

import numpy as np
import xarray as xr
from matplotlib.figure import Figure

from study.charts.design import DPI, Chart, figure_title, full_array
from study.charts.labels import format_value, quantity, short_name
from study.charts.plane import answered_points

#: The design figures: name, whether taken as log10 (the fatigue life spans decades).
FIGURES = (("max_normal_stress", False), ("alternating_bending_stress", False), ("peak_contact_force", False),
           ("fatigue_life", True))
INTERACTIONS = "all interactions"


def _figure_values(ds: xr.Dataset, name: str, log: bool) -> xr.DataArray:
    values = full_array(ds, name).where(answered_points(ds))
    if log:
        with np.errstate(divide="ignore", invalid="ignore"):
            values = np.log10(values.where((values > 0) & np.isfinite(values)))
    return values


def main_effects(ds: xr.Dataset) -> list[dict]:
    """Per design figure present: its main effects (share of variance) and their ranges per swept input, all
    interactions together, the largest two-way interaction, and the points used. Empty with fewer than two swept
    inputs or without any figure."""
    inputs = [d for d in ds.sizes if ds.sizes[d] > 1]
    if len(inputs) < 2:
        return []
    rows = []
    for name, log in FIGURES:
        if name not in ds.data_vars:
            continue
        values = _figure_values(ds, name, log).isel({d: 0 for d in ds.sizes if ds.sizes[d] == 1})
        finite = np.isfinite(values.values)
        if finite.sum() < 3:
            continue
        total = float(np.nanvar(values.values))
        q = quantity(ds[name])
        shares, ranges, means = {}, {}, {}
        for d in inputs:
            mean = values.mean([o for o in inputs if o != d], skipna=True).values
            means[d] = mean
            shares[d] = float(np.nanvar(mean)) / total if total > 0 else 0.0
            if log:
                ranges[d] = float(np.nanmax(mean) - np.nanmin(mean))  # decades
            else:
                shown = q.convert(mean)
                ranges[d] = float(np.nanmax(shown) - np.nanmin(shown))
        pairs = {}
        for a, b in itertools.combinations(inputs, 2):
            mean = values.mean([o for o in inputs if o not in (a, b)], skipna=True).values
            pairs[(a, b)] = (float(np.nanvar(mean)) / total - shares[a] - shares[b]) if total > 0 else 0.0
        top = max(pairs, key=pairs.get)
        rows.append({"figure": name, "label": q.short_name + (" (log₁₀ h)" if log else f" [{q.unit_label}]"),
                     "log": log, "unit": "decades" if log else q.unit_label, "shares": shares, "ranges": ranges,
                     INTERACTIONS: max(0.0, 1.0 - sum(shares.values())), "top pair": top, "top pair share": pairs[top],
                     "points": int(finite.sum()), "of": int(finite.size)})
    return rows


def drivers_chart(ds: xr.Dataset) -> list[Chart]:
    """The main effect of each swept input on each design figure (share of its variance over the grid), and all
    interactions together, as a table of coloured cells with the shares written in."""
    rows = main_effects(ds)
    if not rows:
        return []
    inputs = list(rows[0]["shares"])
    columns = [quantity(ds[d]).short_name for d in inputs] + [INTERACTIONS]
    shares = np.array([[r["shares"][d] for d in inputs] + [r[INTERACTIONS]] for r in rows])
    fig = Figure(figsize=(2.5 + 1.45 * len(columns), 1.6 + 0.75 * len(rows)), dpi=DPI, layout="constrained")
    ax = fig.subplots()
    mesh = ax.pcolormesh(shares * 100.0, cmap="Blues", vmin=0.0, vmax=100.0, edgecolors="white", linewidth=1.0)
    for i, row in enumerate(rows):
        for j, d in enumerate([*inputs, None]):
            value = shares[i, j]
            text = f"{value:.0%}"
            if d is not None:
                moved = row["ranges"][d]
                text += f"\n{format_value(moved)} {row['unit']}" if np.isfinite(moved) else ""
            ax.text(j + 0.5, i + 0.5, text, ha="center", va="center", fontsize=7.5,
                    color="white" if value > 0.6 else "0.1")
    ax.set_xticks(np.arange(len(columns)) + 0.5, columns, rotation=20, ha="right", fontsize=8)
    ax.set_yticks(np.arange(len(rows)) + 0.5, [r["label"] for r in rows], fontsize=8)
    ax.invert_yaxis()
    fig.colorbar(mesh, ax=ax, label="share of the figure's variance over the grid [%]", shrink=0.9)
    figure_title(fig, "Which input drives the design: main effects over the full-factorial grid",
           ["cell: the share of the figure's variance its input's levels explain (first-order index), and below it "
            "how far the mean figure moves across the input's levels",
            "answered points only (ok and not converged); the fatigue life as log₁₀ of hours"],
           2.5 + 1.45 * len(columns))
    caption = ("How much each swept input moves each design figure: main effects from the full-factorial grid (the "
               "variance of the figure's mean at each level of the input, over the figure's variance: a first-order "
               "Sobol index on the grid), the range of those means in the figure's unit, and what every interaction "
               "leaves; the report's table names the largest two-way interaction.")
    return [Chart("drivers", fig, caption)]


def drivers_table_html(rows: list[dict], escape) -> str:
    """The report's table of :func:`main_effects` (``escape``: html.escape)."""
    if not rows:
        return ""
    inputs = list(rows[0]["shares"])
    head = ["design figure", *[short_name(d) for d in inputs], INTERACTIONS, "largest two-way interaction",
            "points used"]
    out = ['<table id="drivers"><thead><tr>' + "".join(f"<th>{escape(h)}</th>" for h in head) + "</tr></thead><tbody>"]
    for r in rows:
        cells = [r["label"]]
        for d in inputs:
            moved = r["ranges"][d]
            cells.append(f"{r['shares'][d]:.0%} ({format_value(moved)} {r['unit']})")
        a, b = r["top pair"]
        cells += [f"{r[INTERACTIONS]:.0%}", f"{short_name(a)} × {short_name(b)}: {r['top pair share']:.0%}",
                  f"{r['points']} of {r['of']}"]
        out.append("<tr>" + "".join(f"<td>{escape(c)}</td>" for c in cells) + "</tr>")
    out.append("</tbody></table>")
    return "\n".join(out)
