"""A whole sweep: config -> grid -> parallel solve -> ``outputs/<study name>/results.nc``.

Before any work: the grid's size against its cap (``sweep.max_points``), the output folder's
writability, and the folder's lock (one sweep at a time). During and after it, an OS error or a
Ctrl-C ends the run with one line saying what was kept and how to resume.
"""

from __future__ import annotations

import itertools
import os
import shutil
import tempfile
from pathlib import Path

import numpy as np

from study.config import Study
from study.solvers import OUTPUTS
from study.solvers.kernels import impact as impact_model
from study.solvers.model.point import DesignPoint
from study.workflow.dataset import previous_history, write_dataset
from study.workflow.chunks import ChunkDamaged
from study.workflow.compiled import ensure_compiled
from study.workflow.execute import Interrupted, SweepError, reason, run_grid, tell
from study.workflow.grid import Grid
from study.workflow.lock import Locked, folder_lock

PARTIAL = ".partial"  # chunk store inside the study folder, removed once the dataset is written
RESULTS = "results.nc"


def study_grid(study: Study) -> Grid:
    return Grid(base=dict(study.inputs), axes=dict(study.axes))


def _bytes(n: float) -> str:
    for unit in ("B", "kB", "MB", "GB", "TB", "PB"):
        if n < 1000 or unit == "PB":
            return f"{n:.3g} {unit}"
        n /= 1000
    raise AssertionError


def _free(folder: Path) -> str:
    """The free space of the disk holding ``folder``, for a message ("unknown" when it cannot be read)."""
    try:
        return _bytes(shutil.disk_usage(folder).free)
    except OSError:
        return "unknown"


def check_size(study: Study, cap: int) -> None:
    """Refuse a grid of more than ``cap`` points, with an estimate of what it would take."""
    size = study.size
    if size <= cap:
        return
    shape = " x ".join(f"{len(values)} {name}" for name, values in study.axes.items())
    per_point = 8 * (len(OUTPUTS) + 4) + 32 + 64  # float outputs, status, key and message text [bytes]
    raise SweepError(
        f"the grid has {size:,} points ({shape}), more than sweep.max_points = {cap:,}: about "
        f"{_bytes(size * per_point)} of results and {_bytes(size * 8)} of memory per output column, and "
        f"{size * 1e-3 / 3600:,.3g} core-hours at 1 ms a point; "
        f"to run it anyway set sweep.max_points or pass --max-points {size}")


#: Methods that search the span over resonances (their memory grows as the rotary speed falls).
SPAN_SEARCHES = ("fast", "series", "periodic", "crosscheck", "reference-check", "damped")


def check_span_search(study: Study) -> None:
    """Refuse, before any work, a grid whose span search cannot be held in memory at some point: the resonance
    candidates at every corner of the grid (the slowest rotary speed and the shortest span searched decide)
    against ``solver.max_poles`` (docs/model.md §9)."""
    methods = study.axes.get("solver_method", [study.inputs.get("solver_method")])
    if not any(m in SPAN_SEARCHES for m in methods):
        return
    axes = {name: (np.min(v), np.max(v)) for name, v in study.axes.items() if np.asarray(v).dtype.kind == "f"}
    for corner in itertools.product(*axes.values()):
        point = DesignPoint.from_inputs({**study.inputs, **dict(zip(axes, corner))})
        problem = impact_model.span_search_too_large(point.scene, point.periodic)
        if problem is not None:
            raise SweepError(f"{problem}; nothing was computed")


def check_writable(out: Path, charts: bool = False) -> None:
    """Before any work: the output folder, its chunk store and results file can be written."""
    for folder in [out, *out.parents]:
        if folder.exists() and not folder.is_dir():
            raise SweepError(f"cannot write {out}: {folder} is a file, not a folder; nothing was computed")
    for name in [PARTIAL, RESULTS] + (["charts"] if charts else []):
        path = out / name
        if name == RESULTS and path.is_dir():
            raise SweepError(f"cannot write {path}: it is a folder; remove or rename it; nothing was computed")
        if name != RESULTS and path.exists() and not path.is_dir():
            raise SweepError(f"cannot write {path}: it is a file, not a folder; nothing was computed")
    try:
        for folder in (out, out / PARTIAL):
            folder.mkdir(parents=True, exist_ok=True)
            fd, probe = tempfile.mkstemp(dir=folder, prefix=".tmp-probe-")
            os.close(fd)
            os.unlink(probe)
    except OSError as exc:
        raise SweepError(f"cannot write {exc.filename or out}: {reason(exc)}; nothing was computed") from None


def run_sweep(study: Study, out_dir: str | Path | None = None, *, scheduler: str | None = None,
              workers: int | None = None, progress: bool = True, on_chunk=None, max_points: int | None = None,
              charts: bool = False, say=None) -> Path:
    """Solve the study's grid and write ``<out_dir>/results.nc``; return its path.

    Resumable: points already in ``<out_dir>/.partial`` (from an interrupted run, solved by the same
    code for the same inputs, in any grid) are not recomputed. ``charts``: also check that the charts
    folder can be written. Raises :class:`SweepError` (one line) for a grid over ``max_points``
    (default ``sweep.max_points``), an unwritable output, or a sweep already running in the folder;
    :class:`Interrupted` on Ctrl-C.
    """
    out = Path(out_dir) if out_dir else Path("outputs") / study.name
    check_size(study, study.sweep["max_points"] if max_points is None else max_points)
    check_span_search(study)
    check_writable(out, charts)
    say = say or tell
    try:
        with folder_lock(out, study.path or study.name, say):
            return _locked_sweep(study, out, scheduler, workers, progress, on_chunk, say)
    except Locked as exc:
        raise SweepError(str(exc)) from None


def _locked_sweep(study, out, scheduler, workers, progress, on_chunk, say) -> Path:
    for stale in out.glob(".tmp-*"):  # a dataset write cut short by a kill
        stale.unlink(missing_ok=True)
    grid = study_grid(study)
    store = out / PARTIAL
    scheduler = study.sweep["scheduler"] if scheduler is None else scheduler
    if not scheduler or scheduler == "synchronous":  # local workers share this machine's kernel cache
        ensure_compiled(study.point(), say=say)
    columns = run_grid(
        grid, store,
        scheduler=scheduler,
        workers=study.sweep["workers"] if workers is None else workers,
        chunk_size=study.sweep["chunk_size"], progress=progress, on_chunk=on_chunk, say=say,
    )
    result = out / RESULTS
    kept = f"all {grid.size} points are kept in {store}; run the same command again to write it (nothing is recomputed)"
    try:
        write_dataset(study, grid, columns, result, previous_history(result))
    except OSError as exc:
        raise SweepError(f"cannot write {result}: {reason(exc)}; {kept}") from None
    except RuntimeError as exc:  # the netCDF/HDF5 library's own error, e.g. "NetCDF: HDF error" on a full disk
        raise SweepError(f"cannot write {result}: {str(exc) or type(exc).__name__} (from the netCDF library: a full "
                         f"disk or a file-size limit, among others; {_free(out)} free there); {kept}") from None
    except ChunkDamaged as exc:
        raise SweepError(f"a chunk was damaged while {result} was written ({exc}); run the same command "
                         "again: it is found and solved again") from None
    except KeyboardInterrupt:
        raise Interrupted(f"interrupted while writing {result}; {kept}") from None
    shutil.rmtree(store, ignore_errors=True)
    return result
