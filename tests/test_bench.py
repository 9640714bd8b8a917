"""study bench (study.bench): the benchmark's pieces run and report every method (no timing asserted)."""

from study.bench import DEFAULT_CONFIG, bench_hertz_coefficients, bench_methods
from study.config import load
from study.solvers import METHODS


def test_bench_reports_every_method_with_a_positive_time():
    rows = bench_methods(load(DEFAULT_CONFIG).point(), repeat=1)
    assert [name for name, _ in rows] == list(METHODS)
    assert all(seconds > 0 for _, seconds in rows)
    assert len(bench_hertz_coefficients(count=10)) == 2
