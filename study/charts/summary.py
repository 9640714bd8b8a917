"""The few lines a sweep ends with: its points by status and by method, the time, the envelope's verdict per axial
load and where the report is — read from the results dataset and the envelope (:mod:`study.charts.envelope`).
"""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import numpy as np
import xarray as xr

from study.charts.envelope import VERDICTS, _criterion_text, envelope_table, safe_ranges
from study.charts.limits import DEFAULT_TARGET_LIFE_HOURS
from study.solvers.result import STATUS


def _statuses(ds: xr.Dataset) -> np.ndarray:
    """Each point's status name, flattened."""
    names = {code: name for name, (code, _) in STATUS.items()}
    return np.array([names.get(int(c), str(c)) for c in np.asarray(ds["status"].values).ravel()])


def _counts(values) -> str:
    counts = Counter(values)
    return ", ".join(f"{name} {n}" for name, n in counts.most_common())


def _seconds(seconds: float) -> str:
    return f"{seconds:.0f} s" if seconds < 120 else f"{seconds / 60:.1f} min"


def sweep_summary(ds: xr.Dataset, seconds: float | None = None, report: Path | None = None,
                  table: Path | None = None, target_hours: float = DEFAULT_TARGET_LIFE_HOURS,
                  criterion: str = "life") -> str:
    """The end of a sweep in a few lines (see the module docstring).

    seconds: the run's wall-clock time; report, table: the written report.html and envelope.csv (None where not
    written); target_hours, criterion: the envelope's fatigue limit (:func:`study.charts.envelope.failures`).
    """
    size = int(np.prod([n for n in ds.sizes.values()])) if ds.sizes else 1
    took = f" in {_seconds(seconds)}" if seconds is not None else ""
    solve = (f" (the points' own solve time {_seconds(float(np.nansum(ds['wall_time'].values)))})"
             if "wall_time" in ds.data_vars else "")
    lines = [f"sweep done: {size} points{took}{solve}"]
    if "status" in ds.data_vars:
        statuses = _statuses(ds)
        lines.append(f"  by status: {_counts(statuses)}")
        if "method" in ds.data_vars:
            methods = np.asarray(ds["method"].values).ravel().astype(str)
            per = []
            for method, n in Counter(methods).most_common():
                per.append(f"{method} {n} ({_counts(statuses[methods == method])})")
            lines.append(f"  by method: {'; '.join(per)}")
    rows = envelope_table(ds, target_hours, criterion)
    if rows:
        counts = Counter(r["verdict"] for r in rows)
        lines.append(f"  envelope ({_criterion_text(target_hours, criterion)}, below yield, outside ±15 % of the "
                     f"joint's critical speeds): {len(rows)} rotary speed x axial load cells: "
                     + ", ".join(f"{counts.get(v, 0)} {v}" for v in VERDICTS))
        undecided = dict(safe_ranges(rows, "undecided"))
        for load, speeds in safe_ranges(rows):
            line = f"    {load}: safe {speeds}"
            if undecided.get(load, "none") != "none":
                line += f"; undecided {undecided[load]}"
            lines.append(line)
    else:
        lines.append("  envelope: none (it needs rotary speed and axial load both swept and the design limits)")
    if report is not None:
        lines.append(f"  report: {report}" + (f" (every cell of the envelope: {table})" if table is not None else ""))
    return "\n".join(lines)
