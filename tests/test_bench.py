"""study bench (study.bench): the benchmark's pieces run and report every method (no timing asserted)."""

from study.bench import DEFAULT_CONFIG, bench_hertz_coefficients, bench_methods, bench_span_search
from study.config import load
from study.solvers import METHODS


def test_bench_reports_every_method_with_a_positive_time():
    rows = bench_methods(load(DEFAULT_CONFIG).point(), repeat=1)
    assert [name for name, _ in rows] == list(METHODS)
    assert all(seconds > 0 for _, seconds in rows)
    assert len(bench_hertz_coefficients(count=10)) == 2


def test_span_search_bench_reports_both_searches_on_the_same_points():
    study = load(DEFAULT_CONFIG)
    small = study.__class__(**{**study.__dict__, "axes": {"rotary_speed": study.axes["rotary_speed"][-2:]}})
    lines, stats = bench_span_search(small, count=2, full_count=1)
    table = [line for line in lines if line.startswith("| ")]
    assert len(table) == 4 and "every pole searched" in table[1] and table[2].endswith("x |")
    assert stats["median"] > 0
