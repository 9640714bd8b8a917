"""Shared by every test."""

import pytest


@pytest.fixture(autouse=True)
def fresh_auto_memo():
    """Each test starts with ``auto``'s memo of rung answers empty, so that a test changing a method (monkeypatch)
    is never answered from another test's run."""
    from study.solvers.methods import auto

    auto.clear_memo()
    yield
    auto.clear_memo()


#: Test modules whose figures come out of adaptive integrators, iterations, root searches or chaotic motions: the
#: ones a CPU's last bits (numba compiles for the host) can move. ``make test-generic`` (CI, after ``make test``) runs them a second time with numba
#: compiling for a generic x86-64 CPU (``NUMBA_CPU_NAME=generic``, ``-m precision``), so that each holds its figures
#: to their real accuracy, not to one machine's bits (issue 32).
PRECISION_MODULES = {
    "test_replay.py",
    "test_validate.py", "test_sliding.py", "test_reference.py", "test_auto.py", "test_whirl_kernel.py",
    "test_timedomain.py", "test_fast.py", "test_periodic.py", "test_freewhirl.py", "test_event_driven.py",
    "test_orbit.py", "test_crosscheck.py", "test_damped.py", "test_refcheck.py", "test_trajectory.py",
    "test_stress_kernel.py", "test_beam.py", "test_roots.py", "test_sdof.py", "test_series.py", "test_well.py",
    "test_modes.py", "test_sliding_parts.py", "test_drag_quadrature.py", "test_drag_modes.py", "test_strike_force.py",
}


def pytest_collection_modifyitems(config, items):
    for item in items:
        if item.path.name in PRECISION_MODULES:
            item.add_marker(pytest.mark.precision)
