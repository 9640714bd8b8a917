"""Shared by every test."""

import pytest


@pytest.fixture(autouse=True)
def fresh_auto_memo():
    """Each test starts with ``auto``'s memo of rung answers empty, so that a test changing a method (monkeypatch)
    is never answered from another test's run."""
    from study.solvers import auto

    auto.clear_memo()
    yield
    auto.clear_memo()
