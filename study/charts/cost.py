"""Cost against accuracy of the methods, point by point: what each answer cost and how sure it is.

Every point of a sweep carries the method that answered it, its wall-clock time and the method's own error
estimate (relative). The chart puts each point at (time, error estimate), one colour per method, with the study's
tolerance as a line: an answer above it is not ``ok`` (:func:`study.solvers.model.gate.admit`). Points whose method
gives no estimate sit on a band at the bottom, so that every point is seen. The legend says, per method, how
many points it answered, their median time and the share of the sweep's compute they took: where the time
went, and what it bought.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib import colormaps
from matplotlib.figure import Figure

from study.charts.design import DPI, Chart


def study_tolerance_of(ds: xr.Dataset) -> float | None:
    """The study's tolerance (``solver.tolerance``) from the config the dataset carries, None without one."""
    text = ds.attrs.get("config")
    if not text:
        return None
    from study.config import ConfigError, load_text
    from study.solvers.model.options import study_tolerance

    try:
        return float(study_tolerance(load_text(str(text)).point()))
    except (ConfigError, ValueError):
        return None


def cost_accuracy_chart(ds: xr.Dataset) -> list[Chart]:
    """Wall time [ms] against error estimate [%] of every point, coloured by the method that answered it."""
    if not {"wall_time", "method"} <= set(ds.data_vars) or not ds.sizes or 0 in ds.sizes.values():
        return []
    methods = np.asarray(ds["method"].values, dtype=str).ravel()
    times = 1e3 * np.asarray(ds["wall_time"].values, dtype=float).ravel()
    errors = (100.0 * np.asarray(ds["error_estimate"].values, dtype=float).ravel() if "error_estimate" in ds
              else np.full(times.shape, np.nan))
    keep = np.isfinite(times) & (times > 0) & (methods != "")
    if not keep.any():
        return []
    methods, times, errors = methods[keep], times[keep], errors[keep]
    estimated = np.isfinite(errors) & (errors > 0)
    floor = 0.3 * (np.min(errors[estimated]) if estimated.any() else 1e-3)
    fig = Figure(figsize=(9.0, 5.4), dpi=DPI, layout="constrained")
    ax = fig.subplots()
    total = times.sum()
    for i, method in enumerate(dict.fromkeys(methods)):
        mine = methods == method
        colour = colormaps["tab10"](i % 10)
        share = 100.0 * times[mine].sum() / total
        label = (f"{method}: {mine.sum()} points, median {np.median(times[mine]):.3g} ms, "
                 f"{share:.3g} % of the compute")
        for subset, y, marker in ((mine & estimated, errors, "o"),
                                  (mine & ~estimated, np.full(times.shape, floor), "v")):
            if subset.any():
                ax.scatter(times[subset], y[subset], s=14, color=colour, marker=marker, alpha=0.75, label=label)
                label = None  # one legend entry per method
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall-clock time per point [ms]")
    ax.set_ylabel("error estimate of the method [%]")
    tolerance = study_tolerance_of(ds)
    if tolerance is not None:
        ax.axhline(100.0 * tolerance, color="0.2", ls="--", lw=1.0)
        ax.annotate(f"study tolerance {100.0 * tolerance:.3g} %: above it a point is not ok", (0.01, 100.0 * tolerance),
                    xycoords=("axes fraction", "data"), va="bottom", fontsize=8, color="0.2")
    if (~estimated).any():
        ax.axhline(floor, color="0.6", lw=0.6, ls=":")
        ax.annotate("▼ no error estimate from the method", (0.99, floor), xycoords=("axes fraction", "data"),
                    ha="right", va="bottom", fontsize=8, color="0.4")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
    title = "Cost against accuracy of the methods, point by point"
    fig.suptitle(title)
    caption = (f"Each of the {times.size} points at its wall-clock time and its method's error estimate; "
               f"{total / 1e3:.3g} s of compute in all.")
    return [Chart("cost_accuracy", fig, caption=caption, title=title)]
