"""Solve a grid in parallel with dask, streaming each finished chunk to a resumable store.

Local worker processes by default (a ``dask.distributed.LocalCluster``), an existing cluster when
given a scheduler address, or ``"synchronous"`` to run in this process. Each chunk's results are
written atomically to ``<store>/<chunk key>.npz`` as soon as they arrive: memory stays bounded,
a killed worker's chunk is simply redone by dask, and an interrupted sweep resumes by skipping the
chunks already on disk.
"""

from __future__ import annotations

import logging
import os
from pathlib import Path
from typing import Callable, Mapping

import numpy as np

from study.atomic import atomic_path
from study.solvers import OUTPUTS, STATUS_CODES, solve_point
from study.workflow.grid import Grid, auto_chunk_size, chunk_key, grid_id


def solve_chunk(grid: Grid, indices: range) -> dict[str, np.ndarray]:
    """Solve the points ``indices`` of the grid; columns of SI values, NaN where not computed."""
    n = len(indices)
    columns = {name: np.full(n, np.nan) for name in OUTPUTS}
    columns["error_estimate"] = np.full(n, np.nan)
    columns["wall_time"] = np.zeros(n)
    status = np.zeros(n, dtype=np.int8)
    messages, methods = [], []
    for row, inputs in enumerate(grid.points(indices)):
        result = solve_point(inputs)
        for name, value in result.values.items():
            if name in columns:
                columns[name][row] = value
        if result.error_estimate is not None:
            columns["error_estimate"][row] = result.error_estimate
        columns["wall_time"][row] = result.wall_time
        status[row] = STATUS_CODES[result.status]
        messages.append(result.message)
        methods.append(result.method)
    columns["status"] = status
    columns["message"] = np.array(messages, dtype=str)
    columns["method"] = np.array(methods, dtype=str)
    columns["index"] = np.arange(indices.start, indices.stop)
    return columns


def warm_up() -> None:
    """Import the solver stack in a worker process (a second or so of scipy/xarray imports)."""
    import study.solvers  # noqa: F401


def _save_atomic(path: Path, columns: Mapping[str, np.ndarray]) -> None:
    with atomic_path(path) as tmp:
        np.savez(tmp, **columns)


def load_chunk(path: Path) -> dict[str, np.ndarray]:
    with np.load(path, allow_pickle=False) as data:
        return {key: data[key] for key in data.files}


def run_grid(grid: Grid, store: Path, *, scheduler: str | None = None, workers: int = 0,
             chunk_size: int = 0, progress: bool = True,
             on_chunk: Callable[[int], None] | None = None) -> list[Path]:
    """Solve every chunk of ``grid`` not yet in ``store``; return the chunk files in grid order.

    scheduler : None or "" for a local process pool, "synchronous" for this process, otherwise
        the address of a running dask.distributed scheduler (e.g. "tcp://10.0.0.5:8786").
    workers : local worker processes (0: one per core).
    on_chunk : called with the number of chunks done after each one is stored (tests use it).
    """
    store.mkdir(parents=True, exist_ok=True)
    for stale in store.glob(".tmp-*"):  # a write cut short by a kill: never a result, remove it
        stale.unlink(missing_ok=True)
    workers = workers or os.cpu_count() or 1
    chunk_size = chunk_size or auto_chunk_size(grid.size, workers)
    chunks = list(grid.chunks(chunk_size))
    grid_hash = grid_id(grid)
    paths = [store / f"{chunk_key(grid, chunk, grid_hash)}.npz" for chunk in chunks]
    todo = [(chunk, path) for chunk, path in zip(chunks, paths) if not path.exists()]

    from tqdm import tqdm

    bar = tqdm(total=grid.size, initial=grid.size - sum(len(c) for c, _ in todo), unit="point",
               disable=not progress, desc="sweep", dynamic_ncols=True)
    done = len(chunks) - len(todo)
    try:
        if not todo:
            return paths
        if scheduler == "synchronous":
            for chunk, path in todo:
                _save_atomic(path, solve_chunk(grid, chunk))
                done += 1
                bar.update(len(chunk))
                if on_chunk:
                    on_chunk(done)
            return paths
        from dask.distributed import Client, LocalCluster, as_completed

        cluster = None
        if scheduler:
            client = Client(scheduler)
        else:
            cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                   dashboard_address=None, silence_logs=logging.ERROR)
            client = Client(cluster)
        try:
            client.run(warm_up)  # import the solvers on every worker before the clock of the first chunk
            shared = client.scatter(grid, broadcast=True)
            futures = {client.submit(solve_chunk, shared, chunk, pure=False): (chunk, path) for chunk, path in todo}
            for future in as_completed(futures):
                chunk, path = futures.pop(future)
                _save_atomic(path, future.result())
                future.release()
                done += 1
                bar.update(len(chunk))
                if on_chunk:
                    on_chunk(done)
        finally:
            client.close()
            if cluster is not None:
                cluster.close()
        return paths
    finally:
        bar.close()
