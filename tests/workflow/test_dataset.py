"""The labelled dataset (study.workflow.dataset): the regime output carries its flags."""

from pathlib import Path

import numpy as np
import xarray as xr

from study.config import load_text
from study.solvers.model.result import OUTPUTS, REGIMES
from study.workflow.dataset import EXTRA_OUTPUTS, write_dataset
from study.workflow.grid import Grid

ROOT = Path(__file__).resolve().parents[2]


def columns(n, regime):
    out = {name: np.full(n, np.nan) for name in [*OUTPUTS, *EXTRA_OUTPUTS]}
    out.update(index=np.arange(n), regime=np.asarray(regime, float), status=np.zeros(n, int),
               message=np.array([""] * n), method=np.array(["sdof"] * n))
    return out


def test_the_regime_is_a_flag_variable_with_the_codes_of_regimes(tmp_path):
    study = load_text((ROOT / "configs" / "default.toml").read_text().split("[sweep]")[0], "tiny.toml")
    grid = Grid(dict(study.inputs), {"rotary_speed": np.array([10.0, 20.0, 30.0])})
    codes = [REGIMES["no_contact"], REGIMES["periodic_impacts"], np.nan]
    with xr.open_dataset(write_dataset(study, grid, columns(3, codes), tmp_path / "r.nc")) as ds:
        assert ds.regime.attrs["flag_meanings"].split() == list(REGIMES)
        np.testing.assert_array_equal(ds.regime.attrs["flag_values"], list(REGIMES.values()))
        np.testing.assert_array_equal(ds.regime.values, codes)
    with xr.open_dataset(write_dataset(study, grid, columns(3, [np.nan] * 3), tmp_path / "none.nc")) as ds:
        assert "regime" not in ds  # no method classified the motion: no variable of fill values


def test_a_coexisting_motion_is_a_flag_variable(tmp_path):
    # the sliding state's check of a bouncing motion beside it (docs/reference_model.md §10): 1 coexists, 0 checked and
    # none, NaN not checked; CF flag attributes name the two values
    study = load_text((ROOT / "configs" / "default.toml").read_text().split("[sweep]")[0], "tiny.toml")
    grid = Grid(dict(study.inputs), {"rotary_speed": np.array([10.0, 20.0, 30.0])})
    cols = columns(3, [np.nan] * 3)
    cols["coexisting_motion"] = np.array([1.0, 0.0, np.nan])
    with xr.open_dataset(write_dataset(study, grid, cols, tmp_path / "c.nc")) as ds:
        assert ds.coexisting_motion.attrs["flag_meanings"].split() == ["one_motion_found", "second_motion_coexists"]
        np.testing.assert_array_equal(ds.coexisting_motion.attrs["flag_values"], [0.0, 1.0])
        np.testing.assert_array_equal(ds.coexisting_motion.values, [1.0, 0.0, np.nan])
