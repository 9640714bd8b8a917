"""Rotary speeds to avoid: the critical speeds of one joint of pipe, from a results dataset.

The span between tool joints (span = the ``joint_length`` input) whirls at its natural frequencies
ω_n² = [EI (nπ/L)⁴ + T_eff (nπ/L)²]/M (:func:`study.physics.critical_speeds.critical_rotary_speeds`,
docs/model.md §2) with the dataset's own ``bending_stiffness``, ``effective_tension`` (tension less the
mud flow's share) and ``mass_per_length`` (pipe, internal mud and annular added mass) at every point,
so the critical speeds follow the load and the mud; each mode is critical where the 1× (synchronous whirl: the
out-of-balance, a bent joint) or the 2× excitation (two forcing cycles a revolution) meets it, at 60 f_n / k
(:func:`every_critical_speed`: the crossings the Campbell chart marks, the bands on every map and the envelope's
check are this one set). A rotary speed within ±15 % of one is to be
avoided (:func:`study.physics.critical_speeds.avoid_band`, API RP 7G's margin); API RP 7G's rule of
thumb (:func:`study.physics.critical_speeds.rp7g_critical_speed`: no tension, no mud) is drawn beside.

Unlike the span's natural frequencies (the span is itself an output of the periodic solution), these
are not circular: the joint length is an input.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from study.charts.design import (DPI, LOAD, RPM, Chart, axis_names, figure_title, format_axis, full_array,
                                 series_colours)
from study.charts.labels import format_value, quantity
from study.charts.plane import Plane
from study.physics.critical_speeds import (API_RP7G_ACCURACY, avoid_band, critical_rotary_speeds,
                                           rp7g_critical_speed)

#: Modes whose critical speeds are computed, and the excitation orders of the Campbell chart (1x: whirl
#: forced by an out-of-balance or bent pipe; 2x: two forcing cycles per revolution).
MODES = (1, 2, 3)
ORDERS = (1, 2)
RPM_PER_RAD_S = 60.0 / (2.0 * np.pi)
NEEDS = ("bending_stiffness", "effective_tension", "mass_per_length")


def _input(ds: xr.Dataset, name: str) -> xr.DataArray | None:
    if name not in ds.coords and name not in ds.data_vars:
        return None
    da = ds[name]
    missing = {d: ds.sizes[d] for d in ds.sizes if d not in da.dims}
    return (da.expand_dims(missing) if missing else da).transpose(*ds.sizes)


def critical_speeds(ds: xr.Dataset, modes=MODES, order: int = 1) -> xr.DataArray | None:
    """Critical rotary speeds [rpm] of the joint, over every dimension of ``ds`` and ``mode``.

    None when the dataset lacks any of :data:`NEEDS` or the ``joint_length`` input; NaN where a point
    has no value or the mode has buckled.
    """
    length = _input(ds, "joint_length")
    if length is None or any(n not in ds.data_vars for n in NEEDS):
        return None
    ei, tension, mass = (full_array(ds, n).values for n in NEEDS)
    omega = critical_rotary_speeds(length.values, ei, tension, mass, modes=modes, order=order)
    return xr.DataArray(omega * RPM_PER_RAD_S, dims=[*ds.sizes, "mode"],
                        coords={**{d: ds[d] for d in ds.sizes}, "mode": list(modes)},
                        attrs={"units": "rpm", "long_name": f"critical rotary speed ({order}x)"})


def rp7g_speeds(ds: xr.Dataset) -> np.ndarray:
    """API RP 7G's critical speed(s) [rpm] of the dataset's joint length and pipe diameters (one per
    combination where they are swept); empty when an input is absent."""
    inputs = [ds[n] for n in ("joint_length", "outer_diameter", "inner_diameter") if n in ds.coords or n in ds]
    if len(inputs) < 3:
        return np.array([])
    values = xr.apply_ufunc(rp7g_critical_speed, *inputs) * RPM_PER_RAD_S
    return np.unique(np.round(np.atleast_1d(values.values).ravel(), 9))


def _merge(intervals) -> list[tuple[float, float]]:
    merged: list[list[float]] = []
    for lo, hi in sorted(intervals):
        if merged and lo <= merged[-1][1]:
            merged[-1][1] = max(merged[-1][1], hi)
        else:
            merged.append([lo, hi])
    return [(lo, hi) for lo, hi in merged]


def every_critical_speed(ds: xr.Dataset, modes=MODES, orders=ORDERS) -> xr.DataArray | None:
    """The critical rotary speeds [rpm] of the joint at every excitation order the Campbell chart marks (60 f_n / k
    for k in ``orders``): over every dimension of ``ds``, ``mode`` and ``order``. The one set of critical speeds the
    Campbell chart, the bands on every map and the envelope use. None as :func:`critical_speeds`."""
    per_order = [critical_speeds(ds, modes, order=k) for k in orders]
    if any(s is None for s in per_order):
        return None
    return xr.concat(per_order, dim=xr.DataArray(list(orders), dims="order", name="order"))


def avoid_bands(p: Plane, margin: float = API_RP7G_ACCURACY, modes=MODES, orders=ORDERS
                ) -> list[list[tuple[float, float]]] | None:
    """Per load row of the plane, the rotary speeds [rpm] within ``margin`` of a critical speed of any
    point of that row (every mode and order, every value of the reduced inputs), merged into intervals."""
    speeds = every_critical_speed(p.ds, modes, orders)
    if speeds is None:
        return None
    speeds = speeds.isel({d: 0 for d in p.fixed})
    rows = []
    for i in range(p.ds.sizes[p.y]):
        centres = speeds.isel({p.y: i}).values.ravel()
        centres = np.unique(centres[np.isfinite(centres)])
        lo, hi = avoid_band(centres, margin)
        rows.append(_merge(zip(lo.tolist(), hi.tolist())))
    return rows


def in_band(ds: xr.Dataset, margin: float = API_RP7G_ACCURACY, modes=MODES, orders=ORDERS) -> xr.DataArray | None:
    """True where a point's rotary speed is within ``margin`` of one of its own critical speeds (every mode and
    order of :func:`every_critical_speed`)."""
    speeds = every_critical_speed(ds, modes, orders)
    if speeds is None or RPM not in ds.coords:
        return None
    rpm = ds[RPM] * RPM_PER_RAD_S
    lo, hi = (speeds.copy(data=edge) for edge in avoid_band(speeds.values, margin))
    return ((rpm >= lo) & (rpm <= hi)).any(["mode", "order"])


def _range_text(values) -> str:
    values = np.asarray(values, dtype=float)
    values = values[np.isfinite(values)]
    if not values.size:
        return "buckled"
    low, high = values.min(), values.max()
    return f"{format_value(low)} rpm" if high - low <= 5e-3 * high else f"{format_value(low)}–{format_value(high)} rpm"


def campbell_chart(ds: xr.Dataset) -> list[Chart]:
    """Natural frequencies of the joint against rotary speed with the 1x and 2x excitation lines (a
    Campbell diagram), crossings marked; one line per axial load (its spread over the other inputs
    shaded); API RP 7G's rule of thumb drawn beside with its ±15 %."""
    speeds = critical_speeds(ds)  # 1x critical speeds = 60 f_n
    if speeds is None or not ds.sizes or 0 in ds.sizes.values():
        return []
    freqs = speeds / 60.0  # Hz
    api = rp7g_speeds(ds)
    swept = np.asarray(ds[RPM].values, dtype=float) * RPM_PER_RAD_S if RPM in ds.coords else np.array([])
    first = speeds.sel(mode=1).values
    reach = [*swept.tolist(), *api.tolist()] + ([float(np.nanmax(first))] if np.isfinite(first).any() else [])
    x_high = 1.1 * max(reach or [100.0])
    f_high = 1.05 * max(ORDERS) * x_high / 60.0
    series = LOAD if LOAD in ds.sizes and ds.sizes[LOAD] > 1 else None
    others = [d for d in ds.sizes if d not in (series, RPM) and ds.sizes[d] > 1]
    fixed = [d for d in ds.sizes if d not in (series, RPM) and ds.sizes[d] == 1]
    colours = series_colours(ds, series)
    fig = Figure(figsize=(10.0, 6.0), dpi=DPI, layout="constrained")
    ax = fig.subplots()
    line_x = np.array([0.0, x_high])
    if swept.size:
        ax.axvspan(swept.min(), swept.max(), color="#fff7bc", zorder=0)
    for k in ORDERS:
        ax.plot(line_x, k * line_x / 60.0, color="0.35", lw=1.0, ls=(0, (5, 3)), zorder=2)
        x_text = min(x_high, f_high * 60.0 / k) * 0.97
        ax.text(x_text, k * x_text / 60.0, f"{k}×", fontsize=9, color="0.2", ha="right", va="bottom")
    crossings = {}
    hidden = []
    n_series = ds.sizes[series] if series else 1
    for s in range(n_series):
        slice_ = freqs.isel({series: s}) if series else freqs
        for mode in MODES:
            values = slice_.sel(mode=mode).values.ravel()
            values = values[np.isfinite(values)]
            if not values.size:
                continue
            low, high, mid = float(values.min()), float(values.max()), float(np.median(values))
            if low > f_high:
                hidden.append(mode)
                continue
            if high - low > 1e-6 * high:
                ax.fill_between(line_x, low, high, color=colours[s], alpha=0.25, lw=0, zorder=1)
            ax.plot(line_x, [mid, mid], color=colours[s], lw=1.4, ls="-" if mode == 1 else ("--" if mode == 2 else ":"),
                    zorder=3)
            for k, marker in zip(ORDERS, ("o", "s")):
                if 60.0 * mid / k <= x_high:
                    ax.plot([60.0 * mid / k], [mid], marker=marker, ms=6, mfc="white", mec=colours[s], mew=1.5,
                            ls="none", zorder=4, gid=f"crossing {k}x mode {mode}")
                    crossings[k] = marker
    api_handles = []
    for value in api:
        lo, hi = avoid_band(value)
        ax.axvspan(lo, hi, color="0.5", alpha=0.12, lw=0, zorder=0)
        ax.axvline(value, color="k", lw=1.6, ls="-.", zorder=5, gid="API RP 7G")
    if api.size:
        api_handles.append(Line2D([], [], color="k", lw=1.6, ls="-.",
                                  label=f"API RP 7G rule of thumb: {_range_text(api)}\n(no tension, no mud; "
                                        "shaded ±15 %)"))
    ax.set_xlim(0.0, x_high)
    ax.set_ylim(0.0, f_high)
    format_axis(ax.xaxis)
    format_axis(ax.yaxis)
    ax.grid(True, color="0.9", lw=0.6)
    ax.set_axisbelow(True)
    ax.set_xlabel("rotary speed [rpm]")
    ax.set_ylabel("natural frequency of the joint [Hz]")
    handles = []
    if series:
        sq = quantity(ds[series])
        handles += [Line2D([], [], color=colours[s], lw=1.4, label=sq.value_text(ds[series].values[s]))
                    for s in range(n_series)]
    handles += [Line2D([], [], color="0.3", lw=1.4, ls=ls, label=f"mode {m}") for m, ls in zip(MODES, ("-", "--", ":"))]
    handles += [Line2D([], [], color="0.35", lw=1.0, ls=(0, (5, 3)), label="excitation f = k·N/60")]
    handles += [Line2D([], [], marker=m, mfc="white", mec="0.2", ls="none", label=f"crossing {k}× (critical speed)")
                for k, m in crossings.items()]
    handles += api_handles
    if swept.size:
        handles.append(Patch(color="#fff7bc", label="swept rotary speeds"))
    fig.legend(handles=handles, loc="outside right center", fontsize=8, frameon=False,
               title=quantity(ds[series]).short_name if series else None, title_fontsize=8)
    joint = (quantity(ds["joint_length"]).value_text(ds["joint_length"].values.ravel()[0])
             if ds["joint_length"].size == 1 else "the swept joint lengths")
    context = [f"span = joint length {joint}, with the effective tension and the mud's mass at each point"]
    context += [quantity(ds[d]).describe(ds[d].values[0]) for d in fixed]
    if others:
        context.append(f"shaded: the spread over {axis_names(ds, others)}")
    every = every_critical_speed(ds)
    context.append("critical speeds (the bands on every map and the envelope's): " + "; ".join(
        f"{k}× " + ", ".join(f"mode {m} {_range_text(every.sel(order=k, mode=m).values)}" for m in MODES)
        for k in ORDERS))
    figure_title(fig, "Rotary speeds to avoid: natural frequencies of the joint against rotary speed (Campbell "
                      "diagram)",
           context, 8.5)
    caption = ("Where a 1× or 2× excitation line crosses a natural frequency of the joint between tool joints the pipe "
               "whirls in resonance: the marked crossings are the critical speeds, the same ones the shaded bands on "
               "every map and the envelope keep 15 % away from. " + api_comparison(ds))
    return [Chart("campbell", fig, caption)]


def api_comparison(ds: xr.Dataset) -> str:
    """A sentence setting the model's critical speeds of the joint beside API RP 7G's rule of thumb, and why they
    differ; "" where either cannot be computed."""
    api, every = rp7g_speeds(ds), every_critical_speed(ds)
    if not api.size or every is None:
        return ""
    lo, hi = avoid_band(api)
    mode1 = every.sel(order=1, mode=1).values
    finite = mode1[np.isfinite(mode1)]
    if not finite.size:
        return ""
    band = f"{format_value(float(lo.min()))}–{format_value(float(hi.max()))} rpm"
    low, high = float(finite.min()), float(finite.max())
    where = ("above it" if low > api.max() else "below it" if high < api.min() else "on both sides of it")
    return (f"API RP 7G's rule of thumb, drawn as a reference, puts the joint's critical speed at "
            f"{_range_text(api)} (avoid {band}) for a bare joint with no tension and no mud; the model's first mode "
            f"at 1× is {_range_text(finite)} here, {where}, because the axial tension stiffens the joint (the "
            "T (nπ/L)² term raises every natural frequency, most at high tension) while the mud inside and around "
            "the pipe adds mass and lowers them; the envelope and the bands use the model's, with the 2× crossings.")
