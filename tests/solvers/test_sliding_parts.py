"""The sliding method's checks kept apart (study.solvers.methods.sliding_parts): the decision whether the reference
model's run from the rest on the wall keeps bouncing (a second motion beside the sliding one) on constructed strike
records, and on the default grid's points against what the full reference run gave there (docs/reference_model.md
§10). The stability test and the second motion through ``sliding.solve``: tests/solvers/test_sliding.py."""

from pathlib import Path

import pytest

from study import config
from study.solvers.methods import sliding, sliding_parts
from study.solvers.methods.sliding_parts import BASIN_LAST, BASIN_TRANSIENT, strikes_verdict
from study.workflow.grid import Grid

ROOT = Path(__file__).resolve().parents[2]


def _verdicts(heavy: list[bool]) -> list[bool | None]:
    """:func:`strikes_verdict` after each revolution of the record ``heavy``, as the run asks it."""
    return [strikes_verdict(heavy[:k]) for k in range(1, len(heavy) + 1)]


def test_strikes_that_die_after_the_start_up_settle():
    # the start-up's strikes (the load applied at once), then none: settled once BASIN_LAST revolutions after the
    # first BASIN_TRANSIENT have none, not before
    record = [True] * BASIN_TRANSIENT + [False] * (BASIN_LAST + 3)
    verdicts = _verdicts(record)
    assert verdicts.index(False) == BASIN_TRANSIENT + BASIN_LAST - 1 and None not in verdicts[BASIN_TRANSIENT + BASIN_LAST - 1:]
    assert set(verdicts[:BASIN_TRANSIENT + BASIN_LAST - 1]) == {None}
    # a strike past the start-up puts the decision off until BASIN_LAST revolutions without one
    late = [True] * BASIN_TRANSIENT + [False, True, False, False, True] + [False] * BASIN_LAST
    assert _verdicts(late)[-2] is None and _verdicts(late)[-1] is False
    # a quiet start-up does not settle it by itself: the revolutions after it decide
    assert strikes_verdict([False] * (BASIN_TRANSIENT + BASIN_LAST - 1)) is None


def test_strikes_that_persist_bounce_and_intermittent_ones_stay_undecided():
    assert _verdicts([True] * (BASIN_TRANSIENT + BASIN_LAST)) == [None] * (BASIN_TRANSIENT + BASIN_LAST - 1) + [True]
    # a run that starts on the wall and is thrown off later (default grid point 384's run: its first strike beyond
    # the bound in revolution 5) bounces once BASIN_LAST revolutions in a row strike
    grows = [False] * 4 + [True] * (BASIN_TRANSIENT + BASIN_LAST)
    assert _verdicts(grows).index(True) == BASIN_TRANSIENT + BASIN_LAST - 1
    # strikes every other revolution: neither
    assert set(_verdicts([True, False] * 20)) == {None}


def _study_point(index: int) -> dict:
    study = config.load(ROOT / "configs" / "default.toml")
    return Grid(dict(study.inputs), dict(study.axes)).point(index)


@pytest.mark.parametrize("index, bounces", [(168, True), (130, False)])
def test_the_run_from_rest_on_the_default_grid_decides_as_the_full_reference_run(index, bounces):
    # default grid points (configs/default.toml, restitution 0.3, no flow, straight hole); what the full reference
    # run from the same rest gave in the default sweep (docs/reference_model.md §10): at 168 (225 rpm, 5 000 lbf,
    # 9 ppg; lift-off 1.03 times the point's eccentricity) it bounced at 36.6 kN; at 130 (150 rpm, 10 000 lbf, 9 ppg;
    # 1.37 times) it came to the sliding motion, though the run from rest struck at 26 times the rest force in its
    # 3rd revolution (the old check escalated it there)
    model = sliding.steady_state(_study_point(index))["model"]
    found = sliding_parts.from_rest(model)
    assert found["decided"] and found["bounced"] is bounces, found
    assert found["revolutions"] < sliding_parts.BASIN_REVOLUTIONS and found["opened"] is not None
    rest = float(max(model.cache["sliding_rest"]["normal"]))
    if bounces:  # every revolution after the start-up struck beyond the bound: 30-160 times the rest force
        assert found["heavy"][-BASIN_LAST:] == list(range(found["revolutions"] - BASIN_LAST + 1, found["revolutions"] + 1))
        assert found["peak"] > 20 * rest
    else:  # the start-up's strikes died: about the sliding motion's own swing after it (2 times the rest force)
        assert found["heavy"] and max(found["heavy"]) <= BASIN_TRANSIENT
        assert found["peak"] < 3 * rest
