"""study coverage (study.coverage): the held-back check of the stated errors (issue 36) — its arithmetic, its sample
rule, its cache, and its section of docs/validation.md. Synthetic results and monkeypatched solvers: no long runs."""

import json
import math
from pathlib import Path

import pytest

from study import coverage, validate
from study.solvers.model.result import REGIMES, PointResult

ROOT = Path(__file__).resolve().parents[1]


def record(method="reference", regime="bouncing", values=None, errors=None, modes=16):
    """A default or reference run as :func:`coverage.summarise` keeps it, from a PointResult built by hand."""
    values = {"regime": float(REGIMES[regime]), "max_bending_stress": 10.0, **(values or {})}
    convergence = {name: dict(window=e / 2, integrator=1e-6, modes=e / 2 - 1e-6, total=e)
                   for name, e in (errors or {}).items() if name != "max_deflection"}
    result = PointResult(method=method, values=dict(values), extras={"reference_modes": modes,
                                                                     "convergence": convergence})
    for name, e in (errors or {}).items():
        if name == "max_deflection":
            result.extras["modal_error"] = {"max_deflection": e}
        else:
            result.values[coverage.ERROR_OUTPUT.get(name, f"{name}_error")] = e
    return coverage.summarise(result)


def point(default_values, reference_values, errors):
    return dict(index=0, inputs={}, default=record(values=default_values, errors=errors),
                reference=record(values=reference_values, modes=64))


def test_a_figure_is_covered_where_its_true_difference_is_within_its_stated_error():
    # true differences by hand: force |110 - 100|/100 = 10 % within 12 % stated; normal stress |80 - 100|/100 = 20 %
    # beyond 15 %; the alternating stress |6 - 4| relative to the reference's max bending stress 10 (its scale,
    # docs/reference_model.md §3.1) = 20 % within 25 %; the damage rate |2 - 1|/1 = 100 % beyond 50 %
    p = point({"peak_contact_force": 110.0, "max_normal_stress": 80.0, "alternating_bending_stress": 6.0,
               "max_deflection": 0.0105, "damage_rate": 2.0},
              {"peak_contact_force": 100.0, "max_normal_stress": 100.0, "alternating_bending_stress": 4.0,
               "max_deflection": 0.0100, "damage_rate": 1.0},
              {"peak_contact_force": 0.12, "max_normal_stress": 0.15, "alternating_bending_stress": 0.25,
               "max_deflection": 0.04, "damage_rate": 0.5})
    rows = coverage.point_rows(p)
    assert rows["peak_contact_force"]["true"] == pytest.approx(0.10)
    assert rows["peak_contact_force"]["covered"] is True
    assert rows["max_normal_stress"]["true"] == pytest.approx(0.20)
    assert rows["max_normal_stress"]["covered"] is False
    assert rows["alternating_bending_stress"]["true"] == pytest.approx(0.20)
    assert rows["alternating_bending_stress"]["covered"] is True
    assert rows["damage_rate"]["covered"] is False
    # the deflection's stated error where no output states it: its modes part and the integrator's, no window part
    assert rows["max_deflection"]["parts"] == {"window": None, "integrator": 1e-6, "modes": 0.04}
    assert rows["max_deflection"]["stated"] == pytest.approx(0.04 + 1e-6)
    assert rows["max_deflection"]["true"] == pytest.approx(0.05)
    assert rows["max_deflection"]["covered"] is False
    # the parts stated beside the total (window + integrator + modes)
    assert rows["peak_contact_force"]["parts"]["window"] == pytest.approx(0.06)


def test_a_figure_without_a_stated_error_is_not_covered_and_one_without_a_reference_is_not_compared():
    p = point({"peak_contact_force": 100.0}, {"peak_contact_force": 100.0}, {})
    rows = coverage.point_rows(p)
    assert rows["peak_contact_force"]["true"] == 0.0 and rows["peak_contact_force"]["covered"] is False
    assert rows["max_normal_stress"]["true"] is None and rows["max_normal_stress"]["covered"] is None


def test_shares_count_per_figure_against_the_target():
    # 10 points with the force 5 % off at a stated 10 %, of which k have it 20 % off: 9 of 10 covered meets 90 %,
    # 8 of 10 does not
    def sample(misses):
        return [point({"peak_contact_force": 120.0 if k < misses else 105.0},
                      {"peak_contact_force": 100.0}, {"peak_contact_force": 0.10}) for k in range(10)]

    one = coverage.shares(sample(1))["peak_contact_force"]
    assert (one["compared"], one["covered"], one["share"], one["meets"]) == (10, 9, 0.9, True)
    assert one["worst"] == pytest.approx(2.0) and one["true"] == pytest.approx(0.05)
    two = coverage.shares(sample(2))["peak_contact_force"]
    assert (two["covered"], two["meets"]) == (8, False)
    assert coverage.shares(sample(0))["max_normal_stress"]["compared"] == 0  # nothing to compare: no share


def test_the_candidate_order_is_a_fixed_permutation_spread_over_the_grid():
    # the default grid: 704 points; 704/φ = 435.1, coprime to 704 = 2^6 11
    assert coverage.golden_step(704) == 435
    order = coverage.candidate_order(704)
    assert sorted(order) == list(range(704)) and order == coverage.candidate_order(704)
    # its first 40 candidates reach both doglegs (352 points each) and all 11 speeds (32 points each)
    assert {i // 352 for i in order[:40]} == {0, 1}
    assert {(i // 32) % 11 for i in order[:40]} == set(range(11))
    assert coverage.golden_step(12) == 7  # round(7.4) = 7, coprime to 12


def test_the_sample_takes_the_first_impacting_reference_points_in_order():
    records = {0: record("free-whirl", "no_contact"), 1: record(), 2: record("reference", "sliding"),
               3: record("sliding", "sliding"), 4: record("reference", "periodic_impacts"), 5: record()}
    assert coverage.selected([0, 1, 2, 3, 4, 5], records, 2) == ([1, 4], True)
    assert coverage.selected([5, 3, 1], records, 5) == ([5, 1], True)  # every candidate solved: fewer is decided
    assert coverage.selected([0, 6, 1], records, 2) == ([], False)  # candidate 6 not solved yet: undecided


#: configs/default.toml with a 12-point grid of its own.
CONFIG = ((ROOT / "configs" / "default.toml").read_text().split("[sweep.axes]")[0].replace('name = "default"', 'name = "tiny"')
          + '[sweep.axes]\nload.rotary_speed = ["100 rpm", "200 rpm", "300 rpm"]\nimpact.restitution = [0.3, 0.5, 0.7, 0.9]\n')


@pytest.fixture
def tiny(tmp_path, monkeypatch):
    """A 12-point config whose points above 150 rpm bounce (reference model), the others slide; the solvers
    monkeypatched to count their calls."""
    path = tmp_path / "tiny.toml"
    path.write_text(CONFIG)
    calls = {"default": [], "reference": []}

    def fake_default(inputs):
        calls["default"].append(inputs)
        if inputs["rotary_speed"] > 150 * 2 * math.pi / 60:
            return record(values={"peak_contact_force": 100.0 * inputs["restitution"]},
                          errors={"peak_contact_force": 0.1})
        return record("sliding", "sliding")

    def fake_reference(inputs):
        calls["reference"].append(inputs)
        return record(values={"peak_contact_force": 105.0 * inputs["restitution"]}, modes=inputs["reference_modes"])

    monkeypatch.setattr(coverage, "solve_default", fake_default)
    monkeypatch.setattr(coverage, "solve_reference", fake_reference)
    return path, calls, tmp_path / "cache"


def test_a_run_samples_impacting_points_and_runs_their_references_with_4x_modes_and_window(tiny):
    path, calls, cache = tiny
    results = coverage.run_coverage(path, sample=3, workers=0, cache=cache, say=lambda _: None)
    order = coverage.candidate_order(12)  # step 7: 0, 7, 2, 9, 4, 11, 6, ...; rpm index = i // 4
    expected = [i for i in order if i // 4 > 0][:3]
    assert [p["index"] for p in results["points"]] == expected == [7, 9, 4]
    assert all(coverage.is_impacting(p["default"]) for p in results["points"])
    # screened in order up to the last point taken (0, 7, 2, 9, 4), no further
    assert len(calls["default"]) == results["screened"] == 5
    # the reference runs: 4 x 16 modes, the count fixed; 4 x the default window (6), transient (40), budget (200)
    assert len(calls["reference"]) == 3
    ref = calls["reference"][0]
    assert (ref["reference_modes"], ref["reference_max_modes"]) == (64, 64)
    assert (ref["reference_window"], ref["reference_revolutions"], ref["reference_max_revolutions"]) == (24, 160, 800)
    assert ref["reference_window_growth"] == "figure"  # each figure's window grown whatever the others' modes parts
    assert coverage.shares(results["points"])["peak_contact_force"]["covered"] == 3  # 100 e vs 105 e: 4.8 % < 10 %


def test_a_rerun_resumes_from_the_cache_and_solves_only_what_is_missing(tiny):
    path, calls, cache = tiny
    first = coverage.run_coverage(path, sample=3, workers=0, cache=cache, say=lambda _: None)
    coverage.run_coverage(path, sample=3, workers=0, cache=cache, say=lambda _: None)
    assert (len(calls["default"]), len(calls["reference"])) == (5, 3)  # the rerun solved nothing
    # an interrupted run: one reference file lost; the rerun solves that one alone and finds the same table
    (cache / f"reference-{first['points'][1]['index']:06d}.json").unlink()
    again = coverage.run_coverage(path, sample=3, workers=0, cache=cache, say=lambda _: None)
    assert (len(calls["default"]), len(calls["reference"])) == (5, 4)
    assert [p["reference"] for p in again["points"]] == [p["reference"] for p in first["points"]]
    # a cached run of other inputs or other code (its key differs) is not reused
    stored = json.loads((cache / "default-000007.json").read_text())
    assert coverage.load_cached(cache, "default", 7, stored["key"]) == stored["record"]
    assert coverage.load_cached(cache, "default", 7, "another key") is None


def test_the_section_is_written_into_its_place_and_survives_study_validate(tiny, monkeypatch):
    path, calls, cache = tiny
    results = coverage.run_coverage(path, sample=3, workers=0, cache=cache, say=lambda _: None)
    stored = coverage.write_results(results, cache / "coverage.json")
    section = coverage.coverage_section(stored)
    assert section[0] == coverage.HEADING
    assert any(line.startswith("| peak contact force | 3 of 3 | 100 % | met (90 %)") for line in section)
    # the section replaces its own, the rest kept; again the same (idempotent); appended where absent
    text = "# Validation\n\n## A\n\na\n\n" + coverage.HEADING + "\n\nstale text\n\n## B\n\nb\n"
    once = coverage.replace_section(text, section)
    assert "stale text" not in once and "## A\n\na\n" in once and once.endswith("## B\n\nb\n")
    assert coverage.replace_section(once, section) == once
    assert coverage.replace_section("# Validation\n", section).startswith("# Validation\n\n" + coverage.HEADING)
    # study validate includes the stored section (read, not computed): the record's other sections left aside here
    for name in ("hertz_table_section", "impact_constants_section", "textbook_section", "paper_example_section",
                 "cross_check_section", "periodic_solution_section", "damped_section", "replay_section",
                 "survey_section", "hierarchy_section"):
        monkeypatch.setattr(validate, name, lambda: [])
    monkeypatch.setattr(coverage, "RESULTS", stored)
    assert "\n".join(section) in validate.run_validate()


def test_the_committed_record_holds_the_stored_coverage_table():
    # docs/validation.md carries the section as docs/coverage.json renders it (study coverage rewrites it; study
    # validate includes it)
    section = "\n".join(coverage.coverage_section())
    assert section in (ROOT / "docs" / "validation.md").read_text()


@pytest.mark.parametrize("argv", [["coverage", "--sample", "0"], ["coverage", "--modes-factor", "1"],
                                  ["coverage", "--workers", "-1"]])
def test_the_command_refuses_bad_counts_with_exit_status_2(argv, capsys):
    from study.cli import main

    with pytest.raises(SystemExit) as stop:
        main(argv)
    assert stop.value.code == 2
    assert argv[1] in capsys.readouterr().err  # the option named
