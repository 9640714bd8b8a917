"""The sliding method's checks kept apart (study.solvers.methods.sliding_parts): the decision whether the reference
model's run from the rest on the wall keeps leaving the wall (a second motion beside the sliding one) on constructed
records of its revolutions, and on the default grid's points against what the full reference run gave there (docs/reference_model.md
§10). The stability test and the second motion through ``sliding.solve``: tests/solvers/test_sliding.py."""

from pathlib import Path

import pytest

from study import config
from study.solvers.methods import sliding, sliding_parts
from study.solvers.methods.sliding_parts import BASIN_LAST, BASIN_TRANSIENT, basin_verdict
from study.workflow.grid import Grid

ROOT = Path(__file__).resolve().parents[2]


def _verdicts(heavy: list[bool]) -> list[bool | None]:
    """:func:`basin_verdict` after each revolution of the record ``heavy``, as the run asks it."""
    return [basin_verdict(heavy[:k]) for k in range(1, len(heavy) + 1)]


def test_flights_that_die_after_the_start_up_settle():
    # the start-up's flights (the load applied at once), then the string on the wall: settled once BASIN_LAST
    # revolutions after the first BASIN_TRANSIENT are on it, not before
    record = [True] * BASIN_TRANSIENT + [False] * (BASIN_LAST + 3)
    verdicts = _verdicts(record)
    assert verdicts.index(False) == BASIN_TRANSIENT + BASIN_LAST - 1
    assert set(verdicts[:BASIN_TRANSIENT + BASIN_LAST - 1]) == {None}
    # a flight past the start-up puts the decision off until BASIN_LAST revolutions on the wall
    late = [True] * BASIN_TRANSIENT + [False, True, False, False, True] + [False] * BASIN_LAST
    assert _verdicts(late)[-2] is None and _verdicts(late)[-1] is False
    # a start-up on the wall does not settle it by itself: the revolutions after it decide
    assert basin_verdict([False] * (BASIN_TRANSIENT + BASIN_LAST - 1)) is None


def test_flights_that_persist_bounce_and_intermittent_ones_stay_undecided():
    assert _verdicts([True] * (BASIN_TRANSIENT + BASIN_LAST)) == [None] * (BASIN_TRANSIENT + BASIN_LAST - 1) + [True]
    # a run that stays on the wall through the start-up and leaves it later bounces once BASIN_LAST revolutions in
    # a row are off it
    grows = [False] * 4 + [True] * (BASIN_TRANSIENT + BASIN_LAST)
    assert _verdicts(grows).index(True) == BASIN_TRANSIENT + BASIN_LAST - 1
    # off the wall every other revolution: neither
    assert set(_verdicts([True, False] * 20)) == {None}


def _study_point(index: int) -> dict:
    study = config.load(ROOT / "configs" / "default.toml")
    return Grid(dict(study.inputs), dict(study.axes)).point(index)


@pytest.mark.parametrize("index, bounces", [(168, True), (130, False), (384, False)])
def test_the_run_from_rest_on_the_default_grid_decides_as_the_full_reference_run(index, bounces):
    # default grid points (configs/default.toml, restitution 0.3, no flow); what the full reference run from the same
    # rest gave in the default sweep (docs/reference_model.md §10): at 168 (175 rpm, 10 000 lbf, 9 ppg, straight hole;
    # lift-off 1.03 times the point's eccentricity) it bounced at 36.6 kN; at 130 (150 rpm, 5 000 lbf, 12 ppg,
    # straight; 1.37 times) it came to the sliding motion, though the run from rest struck the wall at 26 times the
    # rest force in its 3rd revolution; at 384 (75 rpm, 5 000 lbf, 9 ppg, 3°/100 ft; 1.80 times) it came to the
    # sliding motion too, though in the run from rest a joint strikes at up to 25 times the rest force, beyond 5
    # times in most revolutions from the 5th to the 60th: the string never leaves the wall (measured, 60 revolutions)
    model = sliding.steady_state(_study_point(index))["model"]
    found = sliding_parts.from_rest(model)
    assert found["decided"] and found["bounced"] is bounces, found
    assert found["revolutions"] == BASIN_TRANSIENT + BASIN_LAST
    if bounces:  # off the wall about half of every revolution after the start-up, striking it at tens of kN
        assert found["flying"][-BASIN_LAST:] == list(range(BASIN_TRANSIENT + 1, BASIN_TRANSIENT + BASIN_LAST + 1))
        assert found["contact"] < 0.7 and found["peak"] > 10e3
    else:  # always some joint on the wall after the start-up
        assert not [k for k in found["flying"] if k > BASIN_TRANSIENT] and found["contact"] > 0.99
