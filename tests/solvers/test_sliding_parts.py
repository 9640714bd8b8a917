"""The sliding method's checks kept apart (study.solvers.methods.sliding_parts): the decision whether the reference
model's run from the rest on the wall keeps leaving the wall or chatters on it (a second motion beside the sliding one)
on constructed records of its revolutions, and on the default grid's points against what the full reference run gave there (docs/reference_model.md
§10). The stability test and the second motion through ``sliding.solve``: tests/solvers/test_sliding.py."""

from pathlib import Path

import numpy as np
import pytest

from study import config
from study.solvers.methods import sliding, sliding_parts
from study.solvers.methods.sliding_parts import (BASIN_LAST, BASIN_TRANSIENT, BOUNCES, CHATTER_RATIO,
                                                 CHATTER_TRANSIENT, CHATTERS, SETTLES, basin_verdict, chatters)
from study.workflow.grid import Grid

ROOT = Path(__file__).resolve().parents[2]


def _verdicts(heavy: list[bool], chattering: list[bool] = ()) -> list[str | None]:
    """:func:`basin_verdict` after each revolution of the record ``heavy`` (and ``chattering``), as the run asks it."""
    return [basin_verdict(heavy[:k], chattering[:k]) for k in range(1, len(heavy) + 1)]


def test_flights_that_die_after_the_start_up_settle():
    # the start-up's flights (the load applied at once), then the string on the wall: settled once BASIN_LAST
    # revolutions after the first BASIN_TRANSIENT are on it, not before
    record = [True] * BASIN_TRANSIENT + [False] * (BASIN_LAST + 3)
    verdicts = _verdicts(record)
    assert verdicts.index(SETTLES) == BASIN_TRANSIENT + BASIN_LAST - 1
    assert set(verdicts[:BASIN_TRANSIENT + BASIN_LAST - 1]) == {None}
    # a flight past the start-up puts the decision off until BASIN_LAST revolutions on the wall
    late = [True] * BASIN_TRANSIENT + [False, True, False, False, True] + [False] * BASIN_LAST
    assert _verdicts(late)[-2] is None and _verdicts(late)[-1] == SETTLES
    # a start-up on the wall does not settle it by itself: the revolutions after it decide
    assert basin_verdict([False] * (BASIN_TRANSIENT + BASIN_LAST - 1)) is None


def test_flights_that_persist_bounce_and_intermittent_ones_stay_undecided():
    assert _verdicts([True] * (BASIN_TRANSIENT + BASIN_LAST)) == [None] * (BASIN_TRANSIENT + BASIN_LAST - 1) + [BOUNCES]
    # a run that stays on the wall through the start-up and leaves it later bounces once BASIN_LAST revolutions in
    # a row are off it
    grows = [False] * 4 + [True] * (BASIN_TRANSIENT + BASIN_LAST)
    assert _verdicts(grows).index(BOUNCES) == BASIN_TRANSIENT + BASIN_LAST - 1
    # off the wall every other revolution: neither
    assert set(_verdicts([True, False] * 20)) == {None}


def test_a_revolution_chatters_where_a_contact_that_struck_again_peaks_above_the_ratio():
    # sliding_parts.CHATTER_RATIO times the sliding answer's peak force (at default grid point 384 the sliding answer
    # is 87 N and the joint that lifts strikes at 6-12 times it, docs/reference_model.md §10)
    sliding_force = 87.0
    above, below = 1.01 * CHATTER_RATIO * sliding_force, 0.99 * CHATTER_RATIO * sliding_force
    assert chatters([0, 2, 0], [90.0, above, 80.0], sliding_force)
    assert not chatters([0, 2, 0], [90.0, below, 80.0], sliding_force)
    # a held contact (no onset) carrying the largest force is the sliding motion's, however large
    assert not chatters([0, 0, 1], [above, 90.0, 80.0], sliding_force)


def test_a_chatter_that_persists_past_its_start_up_is_a_second_motion_and_one_that_dies_settles():
    # the string on the wall throughout (no revolution off it): a joint striking above the ratio in every revolution
    # from the 4th (as at default grid point 384) chatters once BASIN_LAST revolutions after the first
    # CHATTER_TRANSIENT did, not before
    n = CHATTER_TRANSIENT + BASIN_LAST
    on_wall, persists = [False] * n, [False] * 3 + [True] * (n - 3)
    verdicts = _verdicts(on_wall, persists)
    assert verdicts == [None] * (n - 1) + [CHATTERS]
    # the start-up's strikes after a flight, past BASIN_TRANSIENT but dying before CHATTER_TRANSIENT + BASIN_LAST (as
    # at 650, 696, 697 and 701, up to the 17th): settled once BASIN_LAST revolutions are quiet
    flight = [False, True, True, True] + [False] * (n + 2)
    dies = [False] * 4 + [True] * 13 + [False] * (n + 2 - 13)
    verdicts = _verdicts(flight, dies)
    assert CHATTERS not in verdicts and verdicts.index(SETTLES) == 17 + BASIN_LAST - 1
    # chattering with a quiet revolution every fourth: neither
    assert set(_verdicts([False] * 40, [True, True, True, False] * 10)) == {None}
    # a revolution off the wall that chatters too: the flight decides
    assert _verdicts([True] * n, [True] * n)[BASIN_TRANSIENT + BASIN_LAST - 1] == BOUNCES


def _study_point(index: int) -> dict:
    study = config.load(ROOT / "configs" / "default.toml")
    return Grid(dict(study.inputs), dict(study.axes)).point(index)


@pytest.mark.parametrize("index, sliding_force, verdict", [(168, 578.9, BOUNCES), (130, 480.6, SETTLES),
                                                           (384, 87.28, CHATTERS)])
def test_the_run_from_rest_on_the_default_grid_decides_as_the_full_reference_run(index, sliding_force, verdict):
    # default grid points (configs/default.toml, restitution 0.3, no flow), the sliding answers' peak forces measured
    # (solve_point(p, "sliding")); what the full reference run from the same rest gave in the default sweep
    # (docs/reference_model.md §10): at 168 (175 rpm, 10 000 lbf, 9 ppg, straight hole; lift-off 1.03 times the
    # point's eccentricity) it bounced at 36.6 kN; at 130 (150 rpm, 5 000 lbf, 12 ppg, straight; 1.37 times) it came to
    # the sliding motion, though the run from rest struck the wall at 26 times the rest force in its 3rd revolution
    # (its strikes die: 1.2-1.5 times the sliding force in revolutions 6-10). At 384 (75 rpm, 5 000 lbf, 9 ppg,
    # 3°/100 ft; 1.80 times) the string never leaves the wall, but a joint lifts and strikes it above CHATTER_RATIO
    # times the sliding force in most revolutions from the 5th (6-15 in a row after the 15th on the check's 48 modes,
    # measured over 40 revolutions): a chatter, which the full run at 64 fixed modes finds too (1.07 kN against 87 N)
    model = sliding.steady_state(_study_point(index))["model"]
    found = sliding_parts.from_rest(model, sliding_force)
    assert found["decided"] and found["bounced"] is (verdict == BOUNCES), found
    assert found["chattered"] is (verdict == CHATTERS), found
    if verdict == BOUNCES:  # off the wall about half of every revolution after the start-up, striking it at tens of kN
        assert found["revolutions"] == BASIN_TRANSIENT + BASIN_LAST
        assert found["flying"][-BASIN_LAST:] == list(range(BASIN_TRANSIENT + 1, BASIN_TRANSIENT + BASIN_LAST + 1))
        assert found["contact"] < 0.7 and found["peak"] > 10e3
    else:  # always some joint on the wall after the start-up
        assert not [k for k in found["flying"] if k > BASIN_TRANSIENT] and found["contact"] > 0.99
    if verdict == SETTLES:
        assert found["revolutions"] == BASIN_TRANSIENT + BASIN_LAST  # the start-up's strikes chattered, none after
        assert found["chattering"] and not [k for k in found["chattering"] if k > BASIN_TRANSIENT]
    if verdict == CHATTERS:  # the last BASIN_LAST revolutions chattered, all after the start-up's
        k = found["revolutions"]
        assert CHATTER_TRANSIENT + BASIN_LAST <= k <= sliding_parts.BASIN_REVOLUTIONS
        assert found["chattering"][-BASIN_LAST:] == list(range(k - BASIN_LAST + 1, k + 1))
        assert found["peak"] > CHATTER_RATIO * sliding_force and found["modes"] == sliding.MODES


def test_a_late_chatter_is_told_by_the_force_of_the_last_revolutions_against_the_tolerance():
    # per-revolution peak forces over the sliding answer's (48 modes, the run from rest, revolutions 81-100, measured
    # on the default grid, docs/reference_model.md §10): at 130 the start-up still dying on the wall, 1.05-1.03; at
    # 650 a chatter come after 30 quiet revolutions, 2.3-1.5 (1.91 on average); solver.force_tolerance 15 %
    force, window = 796.3, sliding_parts.LATE_WINDOW
    dying = [force * r for r in np.linspace(1.05, 1.03, window)]
    assert sliding_parts.late_chatter([10 * force] * 80 + dying, force, 0.15) is None  # the start-up's strikes left out
    chatter = [force * r for r in (2.3, 1.5) * (window // 2)]
    assert sliding_parts.late_chatter([force] * 80 + chatter, force, 0.15) == pytest.approx(1.9)
    assert sliding_parts.late_chatter(chatter, force, 1.0) is None  # within a tolerance of 100 %
    assert sliding_parts.late_chatter(chatter[:-1], force, 0.15) is None  # fewer revolutions than the window


def test_a_run_that_settles_on_the_wall_runs_on_for_a_late_chatter_and_keeps_the_sliding_motion():
    # default grid point 130 (150 rpm, 5 000 lbf, 12 ppg, straight hole; the sliding answer 480.6 N, measured): the run
    # from rest settles on the wall by its 10th revolution; given the force's tolerance it runs on to
    # LATE_REVOLUTIONS, its force over revolutions 81-100 1.03-1.04 times the sliding answer's (measured on the host
    # and on the generic CPU path): within the 15 %, no second motion. Without the tolerance it stops where it settled
    model = sliding.steady_state(_study_point(130))["model"]
    found = sliding_parts.from_rest(model, 480.6, tolerance=0.15)
    assert found["revolutions"] == sliding_parts.LATE_REVOLUTIONS and found["settled"] <= 15, found
    assert not found["chattered"] and not found["bounced"] and found["decided"] and found["late"] is None
    short = sliding_parts.from_rest(model, 480.6)
    assert short["revolutions"] == short["settled"] == found["settled"] and short["late"] is None
