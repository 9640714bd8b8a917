"""The labelled result: an xarray Dataset with CF-style metadata, written atomically to netCDF.

One dimension per swept input (SI coordinates with ``units`` and ``long_name``, sorted), fixed inputs
as scalar coordinates, every solver output as a variable with units and long name, the status as an
integer flag with ``flag_values``/``flag_meanings``, and provenance in the global attributes.
"""

from __future__ import annotations

import datetime as _dt
from pathlib import Path
from typing import Any, Mapping, Sequence

import numpy as np
import xarray as xr

from study import __version__
from study.atomic import atomic_path
from study.config import FIELDS_BY_NAME, Study
from study.solvers import OUTPUTS, STATUS
from study.workflow.grid import Grid

CONVENTIONS = "CF-1.10"

# CF/UDUNITS spellings of the SI units used in config.FIELDS.
_UDUNITS = {"m": "m", "kg/m": "kg m-1", "kg/m^3": "kg m-3", "Pa": "Pa", "": "1", "m/s": "m s-1", "N": "N",
            "rad/s": "rad s-1"}

EXTRA_OUTPUTS = {
    "error_estimate": ("1", "error estimate of the method (relative)"),
    "wall_time": ("s", "wall-clock time to solve the point"),
}


def _input_attrs(name: str) -> dict[str, str]:
    spec = FIELDS_BY_NAME[name]
    attrs = {"long_name": spec.long_name}
    if spec.unit is not None:
        attrs["units"] = _UDUNITS.get(spec.unit, spec.unit)
    if spec.display_unit:
        attrs["display_units"] = spec.display_unit
    return attrs


def build_dataset(study: Study, grid: Grid, columns: Mapping[str, np.ndarray], history: Sequence[str] = ()) -> xr.Dataset:
    """Assemble the dataset from the stacked chunk columns (each of length ``grid.size``)."""
    dims, shape = grid.dims, grid.shape
    order = np.argsort(columns["index"])
    if not np.array_equal(columns["index"][order], np.arange(grid.size)):
        raise ValueError("chunk results do not cover the grid exactly once")

    def grid_array(name):
        return np.asarray(columns[name])[order].reshape(shape)

    coords: dict[str, Any] = {}
    for name, values in grid.axes.items():
        values = np.asarray(values)
        coords[name] = xr.Variable(name, values if values.dtype != object else values.astype(str), _input_attrs(name))
    data_vars = {}
    for name, (unit, long_name) in {**OUTPUTS, **EXTRA_OUTPUTS}.items():
        values = grid_array(name)
        if name in OUTPUTS and np.all(np.isnan(values)):
            continue  # no method computed it: absent, never a column of fill values
        data_vars[name] = xr.Variable(dims, values, {"units": unit, "long_name": long_name})
    codes = [code for code, _ in STATUS.values()]
    data_vars["status"] = xr.Variable(dims, grid_array("status").astype(np.int8), {
        "long_name": "status of the design point",
        "flag_values": np.array(codes, dtype=np.int8),
        "flag_meanings": " ".join(STATUS),
        "comment": "; ".join(f"{k}: {v}" for k, (_, v) in STATUS.items()),
    })
    data_vars["message"] = xr.Variable(dims, grid_array("message").astype(str), {"long_name": "solver message"})
    data_vars["method"] = xr.Variable(dims, grid_array("method").astype(str), {"long_name": "solution method"})

    for name, value in grid.base.items():  # fixed inputs; an output of the same name carries its own
        if name in grid.axes or value is None or name in data_vars:
            continue
        coords[name] = xr.Variable((), value, _input_attrs(name))

    now = _dt.datetime.now(_dt.timezone.utc).replace(microsecond=0).isoformat()
    attrs = {
        "Conventions": CONVENTIONS,
        "title": study.title,
        "source": f"study {__version__}",
        "history": "\n".join([*history, f"{now} study sweep {study.path}"]),
        "date_created": now,
        "study_name": study.name,
        "config_hash": study.config_hash,
        "config": study.text,
    }
    return xr.Dataset(data_vars, coords, attrs)


def write_atomic(dataset: xr.Dataset, path: Path) -> Path:
    """Write ``dataset`` to ``path`` via a temporary file in the same folder and a rename."""
    encoding = {name: {"_FillValue": None} for name in dataset.coords}
    for name, var in dataset.data_vars.items():
        if var.dtype.kind == "f":
            encoding[name] = {"zlib": True, "complevel": 4}
    with atomic_path(path) as tmp:
        dataset.to_netcdf(tmp, engine="netcdf4", encoding=encoding)
    return path


def previous_history(path: Path) -> list[str]:
    """History lines of an existing result, so each run appends one line."""
    if not path.exists():
        return []
    try:
        with xr.open_dataset(path) as old:
            return [line for line in str(old.attrs.get("history", "")).splitlines() if line]
    except (OSError, ValueError):
        return []
