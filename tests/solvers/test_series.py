"""The paper's double-Fourier-series method (study.solvers.methods.periodic.series): agreement with the fast method,
convergence, work-precision data, the design-point pipeline and the §VI term ratios.

Measured on the fixed span below (100 rpm, alternating, prescribed, L = 30.287 m, T_L = 1.384 ms,
b = 0.356 m, τ = 0.6 s; solver grid 551 t × 63 x), relative to the double series with
(N, M) = (1921, 51200) (agrees with the fast method at 481 modes to 4e-8 in max normal stress):

    target                        series (N, M) needed          fast N needed
    deflection field  ≤ 1e-6      (241, 6400): 9.0e-7           151: 8.6e-7
    max deflection    ≤ 1e-6      (99, 1600): 1.5e-7            99: 1.5e-7 (101: 1.04e-6)
    max normal stress ≤ 1e-5      (301, 9600): 1.8e-7           261: 3.9e-7
    max shear stress  ≤ 1e-3      (241, 6400): 3.2e-4           221: 3.2e-4 (99: 8.5e-4, but
                                                                101…201: 1.07e-3…1.16e-3)

Below N = 261 both methods stall: modes 219 and 255 sit 0.001 and 0.003 harmonics from resonance
(undamped), and the series needs M past their resonant harmonics (~6200, ~8400) as well. So the
issue's target "fast within 1e-5 in max normal stress and 1e-3 in shear with at most 100 modes" is
NOT met on this case (fast at 99 modes: 2.2e-4 normal); the measured numbers are asserted as they
are (test_fast_at_99_modes_measured_and_flagged), the target is not loosened, and
``periodic.truncation_bound`` flags the shortfall itself (bound ≥ true error).
"""

from itertools import pairwise
from pathlib import Path

import numpy as np
import pytest

from study.benchmarks import series as series_bench
from study.solvers.methods.periodic import checks, fast, series
from study.solvers.methods import periodic
from study.solvers.model.result import PointResult

ROOT = Path(__file__).resolve().parents[2]
RPM = np.pi / 30
TARGETS = {"deflection_error": 1e-6, "max_deflection_error": 1e-6, "error": 1e-5, "shear_error": 1e-3}
REFERENCE = (481, 25_600)  # converged: vs (1921, 51200) 5e-9 normal, 2e-8 deflection, 6e-7 shear
RESOLUTIONS = ([("fast", n) for n in (15, 41, 99, 261, 481)]
               + [("series", nm) for nm in ((41, 400), (99, 800), (99, 1600), (241, 6400), (301, 9600))])


@pytest.fixture(scope="module")
def table(fixed_span):
    inputs, scene, impact = fixed_span
    rows = series_bench.convergence_table(scene, impact, inputs, RESOLUTIONS, reference=REFERENCE)
    return {(r["method"], r["modes"], r["harmonics"]): r for r in rows}


def test_fixed_span_is_the_recorded_case(fixed_span):
    # source: the measurements of the module docstring were made at this span and impact
    impact = fixed_span[2]
    assert impact.span_length == pytest.approx(30.2873, rel=1e-5)
    assert impact.contact_duration == pytest.approx(1.384e-3, rel=1e-3)


def test_stresses_from_fields_is_fast_stresses(fixed_span):
    # source: same contract — series.stresses without harmonics is fast.stresses, key for key, bit for bit
    inputs, scene, impact = fixed_span
    options = periodic.Options(modes=41)
    assert series.stresses(scene, impact, inputs, options) == fast.stresses(scene, impact, inputs, options)


def test_convergence_table_shape_and_falling_errors(table):
    # source: convergence to reference (series REFERENCE); work-precision data for the chart
    assert len(table) == len(RESOLUTIONS)
    for row in table.values():
        assert set(row) == {"method", "modes", "harmonics", "terms", "wall_time", "error", "deflection_error",
                            "max_deflection_error", "shear_error"}
        assert row["wall_time"] > 0 and np.isfinite(row["error"])
    assert table[("series", 99, 800)]["terms"] == 50 * 400  # 50 odd modes × 400 odd harmonics
    fast_err = [table[("fast", n, None)]["error"] for n in (15, 41, 99, 261, 481)]
    series_err = [table[("series", n, m)]["error"] for n, m in ((41, 400), (99, 800), (99, 1600), (241, 6400),
                                                                (301, 9600))]
    assert all(a > b for a, b in pairwise(fast_err)), fast_err
    assert all(a > b for a, b in pairwise(series_err)), series_err


def test_series_converges_to_the_fast_fields(table):
    # source: convergence to reference — the converged series and the converged fast method agree
    # (measured fast 481 vs series REFERENCE: ~4e-8 normal), and the series reaches every target at
    # (N, M) = (301, 9600) (measured 2e-7 deflection field, 2e-7 normal, 7e-6 shear)
    for key in (("fast", 481, None), ("series", 301, 9600)):
        for name, tol in TARGETS.items():
            assert table[key][name] < tol, (key, name, table[key][name])
    # and not before: (241, 6400) still misses the normal-stress target (2.6e-5, mode 255 near resonance)
    assert table[("series", 241, 6400)]["error"] > 1e-5


def test_fast_meets_the_targets_at_261_modes(table):
    # source: convergence to reference (measured 3.9e-7 normal, 6.4e-9 deflection, 6.4e-6 shear)
    row = table[("fast", 261, None)]
    for name, tol in TARGETS.items():
        assert row[name] < tol, (name, row[name])


def test_fast_at_99_modes_measured_and_flagged(fixed_span, table):
    # source: measured (module docstring): max deflection met, normal stress and deflection field not;
    # the fast method's own error estimate (truncation bound) does not understate the error
    inputs, scene, impact = fixed_span
    row = table[("fast", 99, None)]
    assert row["max_deflection_error"] < 1e-6
    assert 1e-4 < row["error"] < 5e-4 and 1e-6 < row["deflection_error"] < 1e-5
    options = periodic.Options(modes=99)
    bound = periodic.truncation_bound(scene, impact, options) / fast.stresses(scene, impact, inputs,
                                                                                   options)["max_normal_stress"]
    assert bound >= row["error"]


def test_series_change_in_harmonics_is_not_a_bound(fixed_span, table):
    # source: measured — at N = 99 the series has converged in M (change 1600 → 3200 below 1e-6) while its
    # error against the converged series is 2.2e-4: the series' error estimate is not a bound
    inputs, scene, impact = fixed_span
    s = series.converged_stresses(scene, impact, inputs, periodic.Options(modes=99), series.Truncation(3200))
    assert s.harmonics == 3200 and [m for m, _ in s.history] == [1600, 3200]
    assert s.change < 1e-6 < table[("series", 99, 1600)]["error"]


def test_tolerance_doubles_harmonics_until_met_or_capped(fixed_span):
    # source: measured at N = 41: max normal stress changes 1.1e-2, 2.5e-5, 1.6e-6, 9e-8 for M = 400…3200
    inputs, scene, impact = fixed_span
    options = periodic.Options(modes=41)
    s = series.converged_stresses(scene, impact, inputs, options, series.Truncation(400, 1e-6))
    assert s.converged and s.harmonics == 3200 and s.change < 1e-6
    assert [m for m, _ in s.history] == [200, 400, 800, 1600, 3200]
    capped = series.converged_stresses(scene, impact, inputs, options, series.Truncation(400, 1e-6, cap=1600))
    assert not capped.converged and capped.harmonics == 1600 and capped.change >= 1e-6


def test_term_ratio_table_on_the_fixed_span(fixed_span):
    # source: closed form of the table's convention (paper §VI: the dropped drag term = 1); every term finite
    inputs, scene, impact = fixed_span
    out = series.term_ratio_table(scene, impact, periodic.Options(modes=41), harmonics=400)
    assert set(out["ratios"]) == set(checks.TERMS)
    assert out["ratios"]["drag"] == {"max": 1.0, "mean": 1.0, "least": 1.0}
    assert all(np.isfinite(v[k]) and v[k] > 0 for v in out["ratios"].values() for k in checks.RATIO_KINDS)
    assert isinstance(out["ok"], bool) and "drag" in out["message"]
    # measured: inertia and bending ~44× the drag on average (B), mud flow ~2e-4× (m_i V_m² ≪ T0)
    assert 20 < out["ratios"]["inertia"]["mean"] < 100 and out["ratios"]["mud_flow"]["mean"] < 1e-2


def test_term_verdict_sets_status_only_on_an_ok_point(fixed_span, monkeypatch):
    inputs, scene, impact = fixed_span
    monkeypatch.setattr(checks, "dropped_terms_small", lambda ratios: (False, "drag is NOT small"))
    ok = PointResult(method="series")
    series.add_term_ratios(scene, impact, inputs, periodic.Options(modes=15), ok, harmonics=200)
    assert ok.status == "terms_not_small" and "NOT small" in ok.message and not ok.extras["term_ratios"]["ok"]
    other = PointResult(method="series", status="not_converged")
    series.add_term_ratios(scene, impact, inputs, periodic.Options(modes=15), other, harmonics=200)
    assert other.status == "not_converged"


def test_solve_paper_example_finds_no_span_like_fast(paper_inputs):
    # source: fast.solve on the same inputs (the same search): no_span, the same roots between 27080 poles
    r, f = series.solve(paper_inputs), fast.solve(paper_inputs)
    assert r.method == "series" and r.status == "no_span" and f.status == "no_span"
    assert r.values["root_count"] == f.values["root_count"] > 0 and r.values["pole_count"] == 27080
    assert "none satisfies condition 1" in r.message


def test_solve_valid_point_same_span_as_fast(paper_inputs):
    # source: fast.solve on the same inputs (tests/solvers/test_fast.py: 150 rpm, e = 0.2, 15 modes,
    # one valid span of 34.27 ft); series stresses agree with fast to 2e-6 at 15 modes × 400 harmonics
    inputs = {**paper_inputs, "rotary_speed": 150 * RPM, "restitution": 0.2, "impact_pattern": "alternating",
              "closure": "self_consistent", "min_span": 9.0, "modes": 15}
    r, f = series.solve(inputs), fast.solve(inputs)
    assert f.status == "ok" and r.status in ("ok", "terms_not_small")
    assert r.values["span_length"] == f.values["span_length"]
    assert r.values["max_normal_stress"] == pytest.approx(f.values["max_normal_stress"], rel=1e-4)
    assert r.extras["series_harmonics"] == series.DEFAULT_HARMONICS
    # The series' estimate includes the bound on the modes left out (the same 15 modes as fast), so it
    # never claims more accuracy than fast's bound at the same modes.
    assert r.error_estimate >= f.error_estimate * (1 - 1e-4)  # bounds divided by stresses equal to 1e-4
    assert r.extras["term_ratios"]["ratios"]["drag"]["mean"] == 1.0
