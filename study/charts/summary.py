"""The few lines a sweep ends with: its points by status and by method, the time, the envelope's verdict per axial
load and where the report is — read from the results dataset and the envelope (:mod:`study.charts.envelope`).
"""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import numpy as np
import xarray as xr

from study.charts.envelope import VERDICTS, criterion_text, envelope_table, safe_ranges
from study.charts.limits import DEFAULT_TARGET_LIFE_HOURS
from study.solvers.model.result import STATUS


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
        lines.append(f"  envelope ({criterion_text(target_hours, criterion)}, below yield, outside ±15 % of the "
                     f"joint's critical speeds at 1× and 2×): {len(rows)} rotary speed x axial load cells: "
                     + ", ".join(f"{counts.get(v, 0)} {v}" for v in VERDICTS)
                     + f" (decided: {len(rows) - counts.get('undecided', 0)} of {len(rows)}, "
                       f"{(len(rows) - counts.get('undecided', 0)) / len(rows):.0%})")
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


def _percent(values: np.ndarray, q: float) -> str:
    return f"{np.percentile(values, q):.0%}"


def run_record(ds: xr.Dataset, seconds: float | None = None, target_hours: float = DEFAULT_TARGET_LIFE_HOURS,
               criterion: str = "life") -> str:
    """The record of a run (markdown) that the README links for its figures, never retyped: the provenance, the
    summary of :func:`sweep_summary`, and the figures a reader quotes — the points each method answered and how sure
    the points not converged are, how many of them the envelope decides at their error, and each cell's verdict."""
    from study.charts.envelope import MARGIN, decided_within_error

    attrs = ds.attrs
    lines = [f"# The last run of `{attrs.get('study_name', 'the study')}`", "",
             "Written by `make sweep` (`study sweep CONFIG --record docs/runs`) from the run's results; the README "
             "quotes its figures from here. Do not edit: run it again.", "",
             f"- study: {attrs.get('title', attrs.get('study_name', ''))}",
             f"- version: {attrs.get('source', '')}; date: {attrs.get('date_created', '')}; "
             f"config hash: {attrs.get('config_hash', '')}", "", "```", sweep_summary(ds, seconds, None, None,
                                                                                           target_hours, criterion),
             "```", ""]
    if "status" in ds.data_vars and "error_estimate" in ds.data_vars:
        statuses = _statuses(ds)
        errors = np.asarray(ds["error_estimate"].values, dtype=float).ravel()
        methods = (np.asarray(ds["method"].values).ravel().astype(str) if "method" in ds.data_vars
                   else np.full(statuses.shape, "?"))
        rough = statuses == "not_converged"
        lines += ["## Points not converged to the study's tolerance (answered, with their error stated)", "",
                  "| method | points | error estimate: median | 10th–90th percentile | largest |",
                  "|---|---|---|---|---|"]
        for method in sorted(set(methods[rough])):
            e = errors[rough & (methods == method) & np.isfinite(errors)]
            if e.size:
                lines.append(f"| {method} | {e.size} | {_percent(e, 50)} | {_percent(e, 10)}–{_percent(e, 90)} | "
                             f"{e.max():.0%} |")
        if rough.any() and envelope_table(ds, target_hours, criterion):
            decided = int(decided_within_error(ds, target_hours, criterion).sum())
            lines += ["", f"The envelope decides {decided} of these {int(rough.sum())} points at their error (their "
                      f"limits hold, or one fails, with the stresses off by {MARGIN:g}x their error estimate)."]
        lines.append("")
    rows = envelope_table(ds, target_hours, criterion)
    if rows:
        speed_key, load_key = list(rows[0])[:2]
        life = "min fatigue life [h]"
        lines += ["## The envelope's cells that are not safe", "",
                  f"| {load_key} | {speed_key} | verdict | why | {life} | its error estimate |",
                  "|---|---|---|---|---|---|"]
        for r in rows:
            if r["verdict"] != "safe":
                error = r.get(f"{life[:-4]}: its error estimate [-]", float("nan"))
                lines.append(f"| {r[load_key]:,.0f} | {r[speed_key]:g} | {r['verdict']} | "
                             f"{'; also '.join(w for w in (r['limited by'], r['undecided because']) if w)} | "
                             f"{r.get(life, float('nan')):,.4g} | "
                             f"{error:.0%} |")
        lines.append("")
    return "\n".join(lines)
