"""The labelled result: an xarray Dataset with CF-style metadata, written atomically to netCDF.

One dimension per swept input (SI coordinates with ``units`` and ``long_name``, sorted), fixed inputs
as scalar coordinates, every solver output as a variable with units and long name, the status as an
integer flag with ``flag_values``/``flag_meanings``, and provenance in the global attributes.
"""

from __future__ import annotations

import datetime as _dt
from pathlib import Path
from typing import Any, Iterator, Sequence

import numpy as np
import xarray as xr

from study import __version__
from study.atomic import atomic_path
from study.config import FIELDS_BY_NAME, Study
from study.solvers import OUTPUTS, STATUS
from study.solvers.model.result import ALIASES, REGIMES
from study.workflow.grid import Grid, code_hash

CONVENTIONS = "CF-1.10"

# CF/UDUNITS spellings of the SI units used in config.FIELDS.
_UDUNITS = {"m": "m", "kg/m": "kg m-1", "kg/m^3": "kg m-3", "Pa": "Pa", "": "1", "m/s": "m s-1", "N": "N",
            "rad/s": "rad s-1", "1/m": "m-1", "Pa*s": "Pa s"}

EXTRA_OUTPUTS = {
    "error_estimate": ("1", "error estimate of the method (relative)"),
    "wall_time": ("s", "wall-clock time to solve the point"),
}


#: CF flag attributes of the outputs that are flags (besides ``regime``'s codes).
FLAGS = {"coexisting_motion": {"flag_values": np.array([0.0, 1.0]),
                               "flag_meanings": "one_motion_found second_motion_coexists"}}


def _input_attrs(name: str) -> dict[str, str]:
    spec = FIELDS_BY_NAME[name]
    attrs = {"long_name": spec.long_name}
    if spec.unit is not None:
        attrs["units"] = _UDUNITS.get(spec.unit, spec.unit)
    if spec.display_unit:
        attrs["display_units"] = spec.display_unit
    return attrs


def _data_variables(grid: Grid, columns, order: np.ndarray) -> Iterator[tuple[str, xr.Variable]]:
    """Every output as a labelled variable, one at a time (an output no method computed is absent,
    never a column of fill values)."""
    dims, shape = grid.dims, grid.shape

    def grid_array(name):
        return np.asarray(columns[name])[order].reshape(shape)

    for name, (unit, long_name) in {**OUTPUTS, **EXTRA_OUTPUTS}.items():
        if name in ALIASES:  # the same idea as another output: stored once, as that one
            continue
        values = grid_array(name)
        if name in OUTPUTS and np.all(np.isnan(values)):
            continue
        flags = {"flag_values": np.array(list(REGIMES.values()), dtype=float),
                 "flag_meanings": " ".join(REGIMES)} if name == "regime" else FLAGS.get(name, {})
        yield name, xr.Variable(dims, values, {"units": unit, "long_name": long_name, **flags})
    codes = [code for code, _ in STATUS.values()]
    yield "status", xr.Variable(dims, grid_array("status").astype(np.int8), {
        "long_name": "status of the design point",
        "flag_values": np.array(codes, dtype=np.int8),
        "flag_meanings": " ".join(STATUS),
        "comment": "; ".join(f"{k}: {v}" for k, (_, v) in STATUS.items()),
    })
    yield "message", xr.Variable(dims, grid_array("message").astype(str), {"long_name": "solver message"})
    yield "method", xr.Variable(dims, grid_array("method").astype(str), {"long_name": "solution method"})


def write_dataset(study: Study, grid: Grid, columns, path: Path, history: Sequence[str] = ()) -> Path:
    """Write the labelled dataset of a sweep to ``path``, atomically and one variable at a time.

    columns: ``columns[name]`` gives that output for every point of the grid in any order, with the
    flat grid index in ``columns["index"]`` (a :class:`~study.workflow.chunks.StoredColumns` reads them
    from the chunk files).
    The coordinates and attributes are written first; each output is then read, reshaped and appended,
    so memory holds one variable however many outputs the sweep has.
    """
    order = np.argsort(columns["index"])
    if not np.array_equal(np.asarray(columns["index"])[order], np.arange(grid.size)):
        raise ValueError("chunk results do not cover the grid exactly once")
    outputs = set(OUTPUTS) | set(EXTRA_OUTPUTS) | {"status", "message", "method"}
    coords: dict[str, Any] = {}
    for name, values in grid.axes.items():
        values = np.asarray(values)
        coords[name] = xr.Variable(name, values if values.dtype != object else values.astype(str), _input_attrs(name))
    scalars = []
    for name, value in grid.base.items():  # fixed inputs; an output of the same name carries its own
        if name in grid.axes or value is None or name in outputs:
            continue
        coords[name] = xr.Variable((), value, _input_attrs(name))
        scalars.append(name)
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
        "code_hash": code_hash(),  # of the sources that computed the points (study.workflow.grid.code_hash)
    }
    header = xr.Dataset(coords=coords, attrs=attrs)
    with atomic_path(path) as tmp:
        header.to_netcdf(tmp, engine="netcdf4", encoding={name: {"_FillValue": None} for name in coords})
        for name, variable in _data_variables(grid, columns, order):
            if name in grid.axes:  # an output named like a swept input (method, span_length) keeps both
                name = f"{name}_result"
                variable.attrs["long_name"] += " (as solved; the coordinate of the same name is the input)"
            if scalars:  # CF: the fixed inputs are this variable's scalar coordinates
                variable.encoding["coordinates"] = " ".join(scalars)
            encoding = {"zlib": True, "complevel": 4} if variable.dtype.kind == "f" else {}
            xr.Dataset({name: variable}).to_netcdf(tmp, mode="a", engine="netcdf4", encoding={name: encoding})
    return path


def previous_history(path: Path) -> list[str]:
    """History lines of an existing result, so each run appends one line."""
    if not path.exists():
        return []
    try:
        with xr.open_dataset(path) as old:
            return [line for line in str(old.attrs.get("history", "")).splitlines() if line]
    except (OSError, ValueError, RuntimeError):  # not a readable dataset: its history is lost, not the run
        return []
