"""study bench (study.bench): the benchmark's pieces run and report every method (no timing asserted)."""

import re
from pathlib import Path

import numpy as np
import pytest

from study.bench import DEFAULT_CONFIG, bench_hertz_coefficients, bench_methods, bench_span_search
from study.config import load
from study.solvers import METHODS, STATUS_CODES


def test_bench_reports_every_method_with_a_positive_time():
    rows = bench_methods(load(DEFAULT_CONFIG).point(), repeat=1)
    assert [name for name, _ in rows] == list(METHODS)
    assert all(seconds > 0 for _, seconds in rows)
    assert len(bench_hertz_coefficients(count=10)) == 2


def test_span_search_bench_reports_every_reading_and_both_searches_on_the_same_points():
    from study.bench import PERIODIC_READINGS

    study = load(DEFAULT_CONFIG)
    small = study.__class__(**{**study.__dict__, "axes": {"rotary_speed": study.axes["rotary_speed"][-2:]}})
    lines, stats = bench_span_search(small, count=2, full_count=1)
    table = [line for line in lines if line.startswith("| ")]
    readings = ["/".join(r) for r in PERIODIC_READINGS]
    assert len(table) == 1 + len(readings) + 3 and "every pole searched" in table[-2] and table[-1].endswith("x |")
    assert all(table[1 + i].startswith(f"| {name}") for i, name in enumerate(readings))
    assert "default" in table[1] and ("statuses" in stats[readings[1]])
    assert all(sum(stats[name]["statuses"].values()) == 2 and stats[name]["max"] >= stats[name]["median"] > 0
               for name in readings)
    assert stats["median"] == stats[readings[0]]["median"]
    assert _assert_every_row_carries_a_ratio("\n".join(lines)) == 2


@pytest.fixture(scope="module")
def reference_bench():
    # one small run shared by the two tests below: three compiled tolerances, two of RK45's
    from study.bench import bench_reference

    case = {"reference_modes": 2, "rotary_speed": 6.283185307179586, "eccentricity": 0.0254}
    return bench_reference(load(DEFAULT_CONFIG).point(), revolutions=0.5, repeat=1, compiled_rtols=(1e-3, 1e-6, 1e-9),
                           penalty_rtols=(1e-4, 1e-5), case=case)


def test_reference_bench_compares_the_compiled_integrator_with_rk45_on_the_same_equations(reference_bench):
    rows, lines = reference_bench
    assert [r["name"] for r in rows] == ["compiled"] * 3 + ["penalty_rk45"] * 2
    assert all(r["wall_time"] > 0 and np.isfinite(r["error"]) for r in rows)
    assert rows[2]["error"] < rows[1]["error"]  # a tighter tolerance is more accurate
    assert any(line.startswith("- RK45 at rtol 1e-05") for line in lines)


def test_hierarchy_bench_states_both_times_and_the_methods():
    from study.bench import bench_hierarchy

    lines = bench_hierarchy(count=2)
    text = " ".join(lines)
    assert "solved by `auto` and by the reference model" in text and "| all | 2 |" in text
    assert _assert_every_row_carries_a_ratio("\n".join(lines)) == 1


def test_memory_bench_measures_each_method_in_its_own_process():
    from study.bench import bench_memory, memory_table

    # three methods of the ladder's ends (each a fresh interpreter: every method would be ~15 s of the suite)
    chosen = ("core", "fast", "reference")
    rows = bench_memory([("paper example", DEFAULT_CONFIG, {})], methods=chosen)
    assert [r["method"] for r in rows] == list(chosen)
    # the span search holds thousands of poles; the core method only the point's scalars
    by = {r["method"]: r for r in rows}
    assert by["fast"]["peak"] > 10 * by["core"]["peak"] > 0
    assert all(r["process"] > 50 for r in rows)  # an interpreter with numpy, scipy and numba: tens of MiB at least
    table = memory_table(rows)
    assert sum(line.startswith("| ") for line in table) == len(chosen) + 1
    assert _assert_every_row_carries_a_ratio("\n".join(table)) == 1


def test_reference_bench_pairs_every_rk45_run_and_states_the_target(reference_bench):
    from study.bench import REFERENCE_TARGET

    rows, lines = reference_bench
    compiled = [r for r in rows if r["name"] == "compiled"]
    assert all(r["work"][0] >= 0 and r["steps"] == r["work"][1] for r in compiled)  # contact time, accepted steps
    assert sum(line.startswith("- RK45 at rtol") for line in lines) == 2
    summary = next(line for line in lines if line.startswith("Equal-accuracy ratios"))
    assert f"target of {REFERENCE_TARGET:g}x" in summary and summary.endswith(("met.", "not met."))


def test_reference_modes_bench_states_each_law_and_count_as_ratios_to_the_converged_run():
    from study.bench import REFERENCE_MODES_POINT, bench_reference_modes

    point = {**load(DEFAULT_CONFIG.with_name("default.toml")).point(), **REFERENCE_MODES_POINT}
    rows, lines = bench_reference_modes(point, modes=(4,), residuals=("series", "dynamic"), converged=8,
                                        revolutions=0.05, repeat=1)
    assert [(r["method"], r["modes"]) for r in rows] == [("series", 4), ("dynamic", 4), ("none", 8), ("dynamic", 8)]
    assert all(r["wall_time"] > 0 and r["time_ratio"] > 0 for r in rows)
    # the converged run against itself: every ratio exactly 1 (the same run)
    assert rows[2]["time_ratio"] == 1.0 and all(rows[2][f"{n}_ratio"] == 1.0 for n in
                                                ("peak_contact_force", "max_normal_stress", "alternating_bending_stress"))
    # four modes with the static series law are far from eight (measured: 0.02 of the force)
    assert rows[0]["shear_error"] > 0.1
    assert sum(line.startswith("| series | 4 |") for line in lines) == 1


def test_sweep_bench_times_the_same_grid_three_ways_and_states_its_mix():
    from study.bench import bench_sweep

    from study.bench import _table

    rows, notes = bench_sweep(load(DEFAULT_CONFIG), points=20, repeat=1)
    assert [label.split(" (")[0] for label, _ in rows] == ["in process", "1 worker", "2 workers"]
    assert _assert_every_row_carries_a_ratio("\n".join(_table("sweep", rows, "s", 1.0))) == 1
    assert all(seconds > 0 for _, seconds in rows)
    # every point of the last run counted by its method and status
    mix = notes[-1]
    assert mix.startswith("the points' methods and statuses: ")
    parts = [part.split(" ") for part in mix.split(": ", 1)[1].split(", ")]
    assert {method for method, _, _ in parts} == {"core"}
    assert all(status in STATUS_CODES for _, status, _ in parts)  # named, not coded
    size = int(rows[0][0].split("(")[1].split()[0])
    assert sum(int(count) for _, _, count in parts) == size


def test_reference_schemes_bench_compares_the_schemes_on_a_sweeps_bouncing_points(tmp_path):
    # a sweep's dataset reduced to what the bench reads: one bouncing point (default grid, 300 rpm, 5 000 lbf, e 0.3,
    # 9 ppg, no flow) that reference answered; the bench solves it by each scheme and states each against the first
    import pytest
    import xarray as xr

    from study.bench import bench_reference_schemes
    from study.solvers.model.result import REGIMES

    config = DEFAULT_CONFIG.with_name("default.toml")
    study = load(config)
    shape = tuple(len(v) for v in study.axes.values())
    method = np.full(shape, "free-whirl", dtype="<U10")
    whirl = np.full(shape, np.nan)
    where = (0, shape[1] - 1, 0, 0, 0, 0)  # the straight hole (the dogleg axis first), the fastest speed
    method[where], whirl[where] = "reference", REGIMES["bouncing"]
    dims = list(study.axes)
    ds = xr.Dataset({"method": (dims, method), "regime": (dims, whirl)}, attrs={"config_hash": study.config_hash})
    ds.to_netcdf(tmp_path / "results.nc")
    rows, lines = bench_reference_schemes(config, tmp_path / "results.nc", count=3, rounds=1,
                                          schemes=("dopri5", "lawson-flight"))
    assert [r["index"] for r in rows] == [int(np.ravel_multi_index(where, shape))]
    runs = rows[0]["runs"]
    assert runs["dopri5"][0]["whirl"] == "bouncing" and runs["dopri5"][0]["wall"] > runs["dopri5"][0]["integrator"] > 0
    table = [line for line in lines if line.startswith("| ")]
    assert table[1].startswith("| dopri5 |") and table[2].startswith("| lawson-flight |")
    assert "1.00 (1.00–1.00)" in table[1] and "1 of 1" in table[2]
    columns = [line.count("|") for line in lines if line.startswith("|")]  # header, rule and rows alike
    assert len(set(columns)) == 1, columns
    ds.attrs["config_hash"] = "another study"
    ds.to_netcdf(tmp_path / "other.nc")
    with pytest.raises(ValueError, match="config_hash"):
        bench_reference_schemes(config, tmp_path / "other.nc", count=1, rounds=1)


def test_large_sweep_bench_sweeps_the_config_and_accounts_for_every_point(tmp_path):
    # the default study on a 6-point grid (the dense config's 103 424 points are make bench-large's): the report
    # states the grid, the time against issue 23's target, the not_converged share and every point under its method
    # and status
    from study.bench import LARGE_TARGET, STUDY_CONFIG, bench_large_sweep

    text = STUDY_CONFIG.read_text().split("[sweep.axes]")[0] + (
        '[sweep.axes]\nload.rotary_speed = ["100 rpm", "175 rpm", "250 rpm"]\nimpact.restitution = [0.3, 0.7]\n')
    config = tmp_path / "small.toml"
    config.write_text(text)
    # thinned to 4 points as `make bench-large POINTS=4` does (the longest axis first, its ends kept)
    report = bench_large_sweep(config, workers=1, out=tmp_path / "large.md", points=4)
    assert (tmp_path / "large.md").read_text() == report
    assert report.startswith("# The large sweep's command on its grid thinned to 4 points (a smoke test")
    assert "`study bench --large --points 4`" in report
    assert "**Grid:** 4 points, 2 rotary_speed × 2 restitution." in report
    assert f"10^5 points in {LARGE_TARGET / 60:.0f} minutes: not judged on 4 points" in report
    assert re.search(r"\*\*Not converged:\*\* \d of 4 points \(\d+\.\d%\)\.", report)
    assert re.search(r"\*\*0 min \d{1,2} s\*\*", report)  # whole minutes, then the seconds left (under 60)
    rows = [line.split(" | ") for line in report.splitlines() if line.startswith("| `")]
    assert sum(int(row[1]) for row in rows) == 4
    for row in rows:  # the statuses' counts add up to the method's points
        assert sum(int(part.rsplit(" ", 1)[1]) for part in row[2].split(", ")) == int(row[1])
        assert row[2].split(", ")[0].split(" ")[0] in STATUS_CODES


def _tables(report: str) -> list[tuple[list[str], list[list[str]]]]:
    """The markdown tables of a report: (header cells, rows of cells) each."""
    tables, lines = [], report.splitlines()
    for i, line in enumerate(lines):
        if line.startswith("|---") and i > 0 and lines[i - 1].startswith("| "):
            rows = []
            for row in lines[i + 1:]:
                if not row.startswith("| "):
                    break
                rows.append([cell.strip() for cell in row.strip("|").split(" | ")])
            tables.append(([cell.strip() for cell in lines[i - 1].strip("|").split(" | ")], rows))
    return tables


def _assert_every_row_carries_a_ratio(report: str) -> int:
    """Every table has a ratio column ("ratio", "speed-up" or "share" in its header) and every row a positive
    number there ("1.67x", "0.982"); returns the number of tables."""
    tables = _tables(report)
    for header, rows in tables:
        columns = [i for i, name in enumerate(header) if re.search(r"ratio|speed-up|share", name)]
        assert columns and rows, header
        for row in rows:
            assert len(row) == len(header), (header, row)
            for i in columns:
                assert float(row[i].removesuffix("x")) > 0, (header[i], row)
    return len(tables)


def test_the_sections_are_declared_and_every_table_of_the_report_carries_ratios():
    # each section runs alone at its smallest sizes (quick: a smoke run, no figure to read, no timing asserted); the
    # sections measured elsewhere in this file at small sizes (span search, hierarchy, sweeps, memory) or opt-in (compile, minutes
    # of both cores) are left out here, their tables checked by their own tests
    from study.bench import SECTIONS, run_bench

    assert all(name == section.name and section.what for name, section in SECTIONS.items())
    assert {"methods", "reference-rk45", "reference-modes", "sweeps"} <= {n for n, s in SECTIONS.items() if s.default}
    assert not SECTIONS["compile"].default
    chosen = ["hertz", "periodic", "time-domain", "reference-rk45", "reference-modes"]
    report = run_bench(sections=chosen, quick=True)
    header = report.split("\n### ")[0]
    assert "load average" in header and "at the start and" in header and "at the end" in header
    assert all(f"`{name}` " in header for name in chosen) and "`compile`, " in header  # what ran, what is opt-in
    assert report.count("\n### ") == len(chosen)
    # the header's table of the sections' times, then at least one table per section
    assert _assert_every_row_carries_a_ratio(report) >= 1 + len(chosen)
    with pytest.raises(ValueError, match="allowed: methods"):
        run_bench(sections=["no-such-section"])


def test_bench_command_refuses_an_unknown_section_and_points_without_large(capsys):
    from study.cli import main

    assert main(["bench", "--section", "nope"]) == 2
    assert "--section 'nope': not a section; allowed: methods" in capsys.readouterr().err
    assert main(["bench", "--points", "5"]) == 2
    assert "--points 5: only with --large" in capsys.readouterr().err


def test_study_of_size_thins_every_axis_evenly_keeping_its_ends():
    from study.bench import LARGE_CONFIG, study_of_size

    study = load(LARGE_CONFIG)
    small = study_of_size(study, 40)
    assert 1 <= small.size <= 40 < study.size and list(small.axes) == list(study.axes)
    for name, values in small.axes.items():
        full = study.axes[name]
        assert set(values) <= set(full) and values[0] == full[0]
        assert values.size < 2 or values[-1] == full[-1]
    assert study_of_size(study, 1).size == 1


def test_the_performance_record_is_make_benchs_output_with_every_default_section():
    # docs/performance.md as `make bench` writes it (nothing added by hand): its header names the command, the load at
    # start and end and every default section with its time, and each of its tables carries ratios
    from pathlib import Path

    from study.bench import SECTIONS

    report = (Path(__file__).resolve().parents[1] / "docs" / "performance.md").read_text()
    header = report.split("\n### ")[0]
    assert header.startswith("# Performance\n\nGenerated by `study bench --out docs/performance.md` (`make bench`)")
    assert re.search(r"load average \(1, 5, 15 min\) was [\d.]+, [\d.]+, [\d.]+ at the start and [\d.]+, [\d.]+, "
                     r"[\d.]+ at the end", header)
    for name, section in SECTIONS.items():
        assert (f"`{name}` " in header) if section.default else (f"`{name}`, " in header), name
    assert _assert_every_row_carries_a_ratio(report) > len(SECTIONS)


def test_the_record_keeps_its_sections_measured_by_hand(tmp_path):
    # docs/performance.md carries sections measured by hand (their commands in their text) beside what `study bench`
    # makes; a rewrite of the record keeps them as they are, and only them
    from study.benchmarks.record import HAND_MARK, hand_sections, write_record

    path = tmp_path / "performance.md"
    assert hand_sections(path) == ""  # no record yet
    hand = f"### Drag options {HAND_MARK}\n\nmeasured: 1.17x\n\n    command --with-options\n"
    write_record(path, "# Performance\n\n### Time per point\n\n| a | 1x |\n\n" + hand + "### Made again\n\nx\n")
    assert hand_sections(path) == hand
    write_record(path, "# Performance\n\n### Time per point\n\n| a | 2x |\n")  # made again: the hand's kept
    assert path.read_text() == "# Performance\n\n### Time per point\n\n| a | 2x |\n\n" + hand
    committed = hand_sections(Path(__file__).resolve().parents[1] / "docs" / "performance.md")
    assert committed.count("### ") == committed.count(HAND_MARK) >= 1
    assert "Time per design point" not in committed
