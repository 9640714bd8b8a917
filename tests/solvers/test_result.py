"""The typed result of a design point (study.solvers.model.result, issue 35): the status an Enum of strings with one code
table, the regime one code table written once to the dataset, the wall time stamped once by solve_point."""

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from study import config
from study.solvers.methods import core
from study.solvers import solve_point
from study.solvers.model.result import ALIASES, OUTPUTS, REGIMES, STATUS, STATUS_CODES, PointResult, Regime, Status

ROOT = Path(__file__).resolve().parents[2]


def test_a_status_is_a_string_and_a_member_with_its_code():
    # source: the definition (study.solvers.model.result.Status): existing string comparisons keep working
    result = PointResult(method="core", status="not_converged")
    assert result.status is Status.NOT_CONVERGED and result.status == "not_converged"
    assert f"{result.status}" == "not_converged" and result.status_code == 6
    result.status = "yields"  # assigned by its name, as the methods do
    assert result.status is Status.YIELDS and result.as_dict()["status"] == "yields"
    with pytest.raises(ValueError, match="bogus"):
        result.status = "bogus"


def test_the_status_tables_are_views_of_the_one_enum():
    assert list(STATUS) == [s.value for s in Status] and len({s.code for s in Status}) == len(Status)
    assert all(STATUS_CODES[s] == s.code and STATUS[s] == (s.code, s.meaning) for s in Status)


def test_the_regime_has_one_code_table_and_the_whirl_verdicts_use_it():
    from study.solvers.methods import reference

    assert REGIMES == {r.name.lower(): r.value for r in Regime} and len(set(REGIMES.values())) == len(Regime)
    assert all(reference.WHIRL_CLASSES[v] == REGIMES[r] for v, r in reference.WHIRL_REGIMES.items())
    assert set(ALIASES) <= set(OUTPUTS) and set(ALIASES.values()) <= set(OUTPUTS)


def test_the_dataset_writes_an_aliased_output_once_under_its_stored_name(tmp_path):
    from study.workflow.dataset import EXTRA_OUTPUTS, write_dataset
    from study.workflow.grid import Grid

    study = config.load_text((ROOT / "configs" / "default.toml").read_text().split("[sweep]")[0], "tiny.toml")
    grid = Grid(dict(study.inputs), {"rotary_speed": np.array([10.0, 20.0])})
    columns = {name: np.full(2, np.nan) for name in [*OUTPUTS, *EXTRA_OUTPUTS]}
    sliding = float(REGIMES["sliding"])
    columns.update(index=np.arange(2), regime=np.full(2, sliding), whirl_class=np.full(2, sliding),
                   status=np.zeros(2, int), message=np.array(["", ""]), method=np.array(["sliding"] * 2))
    with xr.open_dataset(write_dataset(study, grid, columns, tmp_path / "r.nc")) as ds:
        assert "regime" in ds and "whirl_class" not in ds


def test_the_wall_time_is_stamped_once_by_solve_point():
    point = config.load(ROOT / "configs" / "paper.toml").point()
    assert core.solve(point).wall_time == 0.0  # a method does not time itself
    timed = solve_point(point, "core")
    assert 0.0 < timed.wall_time < 5.0
    failed = solve_point({**point, "rotary_speed": "not a number"}, "core")  # caught: status failed, still timed
    assert failed.status == "failed" and failed.wall_time > 0.0
