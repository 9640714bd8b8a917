"""A whole sweep: config -> grid -> parallel solve -> ``outputs/<study name>/results.nc``."""

from __future__ import annotations

import shutil
from pathlib import Path


from study.config import Study
from study.workflow.dataset import ChunkColumns, previous_history, write_dataset
from study.workflow.execute import run_grid
from study.workflow.grid import Grid

PARTIAL = ".partial"  # chunk store inside the study folder, removed once the dataset is written


def study_grid(study: Study) -> Grid:
    return Grid(base=dict(study.inputs), axes=dict(study.axes))


def run_sweep(study: Study, out_dir: str | Path | None = None, *, scheduler: str | None = None,
              workers: int | None = None, progress: bool = True, on_chunk=None) -> Path:
    """Solve the study's grid and write ``<out_dir>/results.nc``; return its path.

    Resumable: chunks already in ``<out_dir>/.partial`` (from an interrupted run of the same inputs
    and solver version) are not recomputed.
    """
    out = Path(out_dir) if out_dir else Path("outputs") / study.name
    for stale in out.glob(".tmp-*"):  # a dataset write cut short by a kill
        stale.unlink(missing_ok=True)
    grid = study_grid(study)
    store = out / PARTIAL
    paths = run_grid(
        grid, store,
        scheduler=study.sweep["scheduler"] if scheduler is None else scheduler,
        workers=study.sweep["workers"] if workers is None else workers,
        chunk_size=study.sweep["chunk_size"], progress=progress, on_chunk=on_chunk,
    )
    result = out / "results.nc"
    write_dataset(study, grid, ChunkColumns(paths), result, previous_history(result))
    shutil.rmtree(store, ignore_errors=True)
    return result
