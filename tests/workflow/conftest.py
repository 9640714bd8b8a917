"""Shared set-up of the workflow tests."""

import pytest

from study.workflow.compiled import ensure_compiled


@pytest.fixture(scope="session", autouse=True)
def kernels_compiled():
    """The sweeps under test find every kernel in numba's cache, as after `make setup` (which compiles them): what a
    sweep says, and which points it solves, are then its own. The first run's notice is tested in test_compiled.py."""
    ensure_compiled(say=lambda message: None)
