"""study validate (study.validate): the record in docs/validation.md is what the code computes now."""

from pathlib import Path

import pytest

from study.validate import run_validate

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def report():
    return run_validate()


def test_committed_validation_record_is_current(report):
    # docs/validation.md must be regenerated (make validate) whenever a computed value changes.
    assert (ROOT / "docs" / "validation.md").read_text() == report


def test_report_compares_with_the_printed_numbers(report):
    assert "| 30 | 2.731 | 2.73065 | 0.493 | 0.49306 | ok |" in report  # paper app. D table row
    assert "| T_L/T_H | 0.855 | 0.8539 |" in report  # paper eq. 15-17, app. C
    assert "2.1869 m/s" in report  # textbook Example 8.2, printed 2.187 m/s
    assert "| alternating | prescribed |" in report  # the paper's 345 ft span, in every reading
    assert "real-contact orbit found | stable |" in report  # the crosscheck over the design space (e = 1)
