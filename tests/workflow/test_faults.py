"""The fault-injection script (study.workflow.faults): its damage is caught, its comparison is exact.

A whole run (``make faults``) takes minutes; its figures are in docs/reliability.md. Here its parts.
"""

import random

import numpy as np
import pytest
import xarray as xr

from study.workflow.chunks import ChunkDamaged, load_chunk, save_chunk
from study.workflow.faults import damage, identical


@pytest.mark.parametrize("seed", range(6))
def test_every_damage_the_script_does_is_caught_when_the_chunk_is_read(tmp_path, seed):
    path = tmp_path / "c.npz"
    save_chunk(path, {"peak_contact_force": np.linspace(0.0, 1.0, 50), "point_key": np.array([b"k"] * 50, "S32")})
    how = damage(path, random.Random(seed))
    assert how in ("truncated", "emptied", "bit-flipped")
    with pytest.raises(ChunkDamaged):
        load_chunk(path)


def test_the_comparison_ignores_wall_time_and_nothing_else(tmp_path):
    reference = xr.Dataset({"peak_contact_force": ("x", [1.0, np.nan, 3.0]), "wall_time": ("x", [0.1, 0.2, 0.3]),
                            "message": ("x", ["a", "b", "c"])})
    same = reference.copy(deep=True)
    same["wall_time"] = same.wall_time * 2
    same.to_netcdf(tmp_path / "same.nc")
    assert identical(tmp_path / "same.nc", reference) == []  # NaN equals NaN; wall time differs
    other = reference.copy(deep=True)
    other["peak_contact_force"][2] = np.nextafter(3.0, 4.0)
    other["message"][0] = "z"
    other.to_netcdf(tmp_path / "other.nc")
    assert identical(tmp_path / "other.nc", reference) == ["peak_contact_force", "message"]
