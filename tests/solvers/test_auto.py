"""The auto method (study.solvers.auto): the cheapest periodic method that meets the tolerance."""

from pathlib import Path

import numpy as np
import pytest

from study import config
from study.solvers import solve_point

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def valid_point():
    # The 15-mode case with a valid span (tests/solvers/test_fast.py records it).
    inputs = config.load(ROOT / "configs" / "paper.toml").point()
    return {**inputs, "rotary_speed": 150 * np.pi / 30, "restitution": 0.2, "impact_pattern": "alternating",
            "closure": "self_consistent", "modes": 15, "min_span": 9.0}


def test_a_loose_tolerance_takes_the_fast_method(valid_point):
    result = solve_point({**valid_point, "tolerance": 1.0}, "auto")
    assert result.method == "fast" and result.status == "ok"
    assert result.error_estimate <= 1.0 and list(result.extras["methods_tried"]) == ["fast"]
    assert result.message.startswith("auto: fast answered")


def test_a_tolerance_no_method_meets_is_reported_not_hidden(valid_point):
    # With 15 modes the left-out modes alone are worth about 20 % (the truncation bound); more harmonics
    # in the series cannot fix that, so no method may claim 1e-3.
    result = solve_point({**valid_point, "tolerance": 1e-3}, "auto")
    assert result.status == "not_converged"
    assert result.message.startswith("auto: no model served") and "after fast: not_converged" in result.message
    assert set(result.extras["methods_tried"]) == {"fast", "series"}
    assert all(tried["error_estimate"] > 1e-3 for tried in result.extras["methods_tried"].values())


def test_a_point_without_a_span_is_answered_by_the_cheapest_method():
    inputs = config.load(ROOT / "configs" / "paper.toml").point()
    result = solve_point({**inputs, "modes": 11}, "auto")
    assert result.status == "no_span" and result.method == "fast"
    # the series searches the same spans: a point without one is not sent up to it
    assert list(result.extras["methods_tried"]) == ["fast"]


def test_a_span_that_fails_doubling_is_not_sent_to_the_series():
    # 250 rpm, one wall, self-consistent: the 7.39-m span is gone with 81 modes (tests/solvers/test_gate.py);
    # more harmonics in time cannot bring it back
    inputs = config.load(ROOT / "configs" / "paper.toml").point()
    result = solve_point({**inputs, "rotary_speed": 250 * np.pi / 30, "impact_pattern": "one_wall",
                          "closure": "self_consistent", "span_length": None}, "auto")
    assert result.status == "not_converged" and list(result.extras["methods_tried"]) == ["fast"]
