"""The lines a sweep ends with (study.charts.summary), on the synthetic study of conftest.py."""

from collections import Counter
from pathlib import Path

import numpy as np

from study.charts.envelope import envelope_table, safe_ranges
from study.charts.summary import sweep_summary
from study.solvers.result import STATUS_CODES


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
