"""The lines a sweep ends with (study.charts.summary), on the synthetic study of conftest.py."""

from collections import Counter
from pathlib import Path

import numpy as np

from study.charts.envelope import envelope_table, safe_ranges
from study.charts.summary import sweep_summary
from study.solvers.model.result import STATUS_CODES


def test_the_summary_counts_the_points_by_status_and_method_and_gives_the_envelope_per_load(study):
    ds = study.copy(deep=True)
    method = np.where(ds.status.values == 0, "free-whirl", "reference")
    ds["method"] = (ds.status.dims, method)
    ds["wall_time"] = (ds.status.dims, np.full(ds.status.shape, 0.5))
    text = sweep_summary(ds, 73.2, Path("outputs/x/report.html"), Path("outputs/x/charts/envelope.csv"))
    lines = text.splitlines()
    size = ds.status.size
    no_span = int((ds.status == STATUS_CODES["no_span"]).sum())
    assert no_span and lines[0] == f"sweep done: {size} points in 73 s (the points' own solve time {0.5 * size:.0f} s)"
    assert lines[1] == f"  by status: ok {size - no_span}, no_span {no_span}"
    assert lines[2] == f"  by method: free-whirl {size - no_span} (ok {size - no_span}); reference {no_span} (no_span {no_span})"
    rows = envelope_table(ds)
    verdicts = Counter(r["verdict"] for r in rows)
    assert (f"{len(rows)} rotary speed x axial load cells: {verdicts['safe']} safe, {verdicts['limited']} limited, "
            f"{verdicts['undecided']} undecided") in lines[3]
    for load, speeds in safe_ranges(rows):  # one line per load, its safe speeds as the report's table has them
        assert any(line.startswith(f"    {load}: safe {speeds}") for line in lines[4:])
    assert lines[-1] == "  report: outputs/x/report.html (every cell of the envelope: outputs/x/charts/envelope.csv)"


def test_without_the_plane_the_summary_says_there_is_no_envelope(study):
    text = sweep_summary(study.isel(axial_tension=[0]))
    assert "envelope: none (it needs rotary speed and axial load both swept" in text and "report" not in text


def test_the_run_record_holds_the_summary_the_errors_and_the_cells_that_are_not_safe(study):
    from study.charts.summary import run_record

    ds = study.copy(deep=True)
    ds["error_estimate"] = (ds.status.dims, np.full(ds.status.shape, np.nan))
    first = (0,) * ds.status.ndim
    ds.status.values[first] = STATUS_CODES["not_converged"]
    ds.error_estimate.values[first] = 0.2
    text = run_record(ds, 10.0)
    assert sweep_summary(ds, 10.0) in text  # the same lines the sweep printed
    assert "| fast | 1 | 20% | 20%–20% | 20% |" in text  # one point not converged, its error 20 %
    assert "The envelope decides 1 of these 1 points at their error" in text
    rows = [r for r in envelope_table(ds) if r["verdict"] != "safe"]
    table = text.split("## The envelope's cells that are not safe")[1]
    assert table.count("\n| ") == len(rows) + 1  # the header and a line per cell that is not safe


def test_the_readme_links_the_record_of_the_default_study_and_quotes_no_figure_of_a_run():
    root = Path(__file__).resolve().parents[2]
    readme = (root / "README.md").read_text()
    record = root / "docs" / "runs" / "default.md"
    assert "docs/runs/default.md" in readme and record.exists()
    assert record.read_text().startswith("# The last run of `default`")
    section = readme.split("### What `make sweep` answers")[1].split("\n## ")[0]
    # the figures of a run (points per status, cells per verdict) are the record's, never retyped here
    import re

    assert not re.findall(r"\b\d+ of the \d+\b|\(\d+ points?, `?ok|\d+ `not_converged`", section)
