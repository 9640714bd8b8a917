"""Solve a grid in parallel with dask, streaming each finished chunk to a resumable store.

Local worker processes by default (a ``dask.distributed.LocalCluster``), an existing cluster when
given a scheduler address, or ``"synchronous"`` to run in this process. Each chunk's results are
written atomically to ``<store>/<chunk key>.npz`` (with a checksum, :mod:`study.workflow.chunks`)
as soon as they arrive: memory stays bounded and an interrupted sweep resumes by solving only the
points whose keys are not in the store. Every task carries its own points, so a lost worker, or
every worker lost at once, only delays the chunks it held: they are solved again.
"""

from __future__ import annotations

import contextlib
import logging
import os
import sys
from concurrent.futures import CancelledError
from pathlib import Path
from typing import Callable

import numpy as np

from study.workflow import chunks as chunk_module
from study.workflow.chunks import Store, StoredColumns, save_chunk, solve_chunk, solve_task
from study.workflow.grid import Grid, auto_chunk_size, chunk_key, chunks, code_hash

#: How many times a chunk is resubmitted after the worker solving it was lost.
RESUBMITS = 20


class SweepError(Exception):
    """A sweep that cannot go on; str() is one line naming the path, the reason and what was kept."""


class Interrupted(KeyboardInterrupt):
    """Ctrl-C during a sweep; str() says how much was kept and how to resume."""


def warm_up() -> None:
    """Import the solver stack in a worker process (a second or so of scipy/xarray imports), through the module
    that records the code hash of what it loaded (:data:`study.workflow.chunks.LOADED_CODE`)."""
    import study.workflow.chunks  # noqa: F401


class StaleCode(SweepError):
    """A worker runs other solver code than this process: its results would be stored under the wrong keys."""


def check_code(ran: str, code: str, where: str) -> None:
    """Refuse the results of a task that ran with code hash ``ran`` where the keys were made with ``code``."""
    if ran != code:
        raise StaleCode(
            f"{where} runs other solver code (code hash {ran[:12]}) than this study process ({code[:12]}): it "
            "loaded the sources before they were changed (or from another install); restart the cluster's "
            "workers (e.g. Client.restart()) so they load the current code, then run the same command again; "
            "nothing it computed was stored")


def dask_setup(worker) -> None:
    """Preload of a local worker process: Ctrl-C is for the sweep, which stops its workers itself; a
    worker ignores it (otherwise every worker prints a traceback of its own)."""
    import signal
    import threading

    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, signal.SIG_IGN)


def tell(message: str) -> None:
    """The default ``say``: one line on stderr."""
    print(f"study: {message}", file=sys.stderr)


def reason(exc: OSError) -> str:
    """The operating system's words for an OSError (e.g. 'No space left on device')."""
    if exc.errno:
        return exc.strerror or os.strerror(exc.errno)
    return str(exc)


def run_grid(grid: Grid, store: Path, *, scheduler: str | None = None, workers: int = 0,
             chunk_size: int = 0, progress: bool = True, on_chunk: Callable[[int], None] | None = None,
             say: Callable[[str], None] = tell) -> StoredColumns:
    """Solve every point of ``grid`` whose key is not yet in ``store``; return the stored columns of
    the grid's points in grid order.

    scheduler : None or "" for a local process pool, "synchronous" for this process, otherwise
        the address of a running dask.distributed scheduler (e.g. "tcp://10.0.0.5:8786").
    workers : local worker processes (0: one per core).
    chunk_size : points per task (0: :func:`auto_chunk_size` of the grid, its last quarter's tasks tapered,
        :func:`study.workflow.grid.chunks`); never depends on ``workers``.
    on_chunk : called with the number of chunks done after each one is stored (tests use it).
    say : prints a line for the user (a damaged chunk found and removed).
    Raises :class:`SweepError` when a chunk cannot be written, :class:`Interrupted` on Ctrl-C.
    """
    store.mkdir(parents=True, exist_ok=True)
    for stale in store.glob(".tmp-*"):  # a write cut short by a kill: never a result, remove it
        stale.unlink(missing_ok=True)
    code = code_hash()
    keys = grid.point_keys(code)
    stored = Store.scan(store)
    for path, why in stored.damaged:
        say(f"damaged chunk {path.name} ({why}): removed, its points are solved again")
    todo = np.flatnonzero(stored.locate(keys)[0] < 0)
    if len(todo) < grid.size:
        say(f"reusing {grid.size - len(todo)} of {grid.size} points stored in {store}")
    tasks = [(indices, store / f"{chunk_key(keys[indices])}.npz")
             for indices in chunks(todo, chunk_size or auto_chunk_size(grid.size), taper=not chunk_size)]

    from tqdm import tqdm

    kept = grid.size - len(todo)
    bar = tqdm(total=grid.size, initial=kept, unit="point", disable=not progress, desc="sweep",
               dynamic_ncols=True)
    done = 0

    def store_chunk(indices, path, columns):
        nonlocal done, kept
        try:
            save_chunk(path, columns)
        except OSError as exc:
            where = exc.filename or path
            raise SweepError(f"cannot write {where}: {reason(exc)}; kept {kept} of {grid.size} points in "
                             f"{store} (run the same command again to resume once it can be written)") from None
        stored.add(path, columns["point_key"])
        done += 1
        kept += len(indices)
        bar.update(len(indices))
        if on_chunk:
            on_chunk(done)

    try:
        if scheduler == "synchronous":
            if tasks:
                check_code(chunk_module.LOADED_CODE, code, "this process")
            for indices, path in tasks:
                store_chunk(indices, path, solve_chunk(grid.take(indices, keys[indices])))
        elif tasks:
            _run_distributed(grid, keys, code, tasks, store_chunk, scheduler, workers or os.cpu_count() or 1)
    except KeyboardInterrupt:
        _quiet_shutdown()
        # what a resume will reuse, counted on disk: a chunk whose file was renamed into place as the signal came,
        # before store_chunk counted it, is kept too
        kept = int(np.count_nonzero(Store.scan(store).locate(keys)[0] >= 0))
        raise Interrupted(f"interrupted: kept {kept} of {grid.size} points in {store}; run the same command "
                          "again to resume") from None
    finally:
        bar.close()
    return stored.columns(keys)


#: Dask settings for the local workers a sweep starts (:func:`configure_local_workers`): dask's statistical profiler
#: off (it samples a worker's stack every 10 ms for the dashboard's profile page) and its event-loop, memory and
#: system monitors at intervals of seconds instead of 20-500 ms. Each of those wakes a process that shares the two
#: cores with the points being solved. The default study's 1408-point bench grid on two local workers, five runs of
#: each alternating (docs/workers.md): 13.6-14.0 s with dask's defaults, 12.6-13.0 s with these (medians 13.73 and
#: 12.74 s: 1.08x); the profiler alone gave most of it. A cluster the user starts keeps the user's settings.
LOCAL_WORKER_CONFIG = {
    "distributed.worker.profile.enabled": False,
    "distributed.admin.tick.interval": "1s",
    "distributed.worker.memory.monitor-interval": "1s",
    "distributed.admin.system-monitor.interval": "5s",
}


#: glibc's allocator in the local workers (:func:`configure_local_workers`): blocks up to 64 MiB from the heap, not
#: each its own mmap, and the heap given back to the system only beyond 256 MiB free at its top. A reference window
#: at 64 modes records some 25 000 rows of 260 states (51 MB) and its figures take numpy temporaries of 3-13 MB; as
#: fresh mmaps (glibc's dynamic threshold stops at 32 MiB, dask's 64 KiB trim threshold turns it off) each is paid
#: again in page faults, some 10 % of a bouncing point's CPU (docs/workers.md).
LOCAL_WORKER_MALLOC = {"MALLOC_MMAP_THRESHOLD_": str(64 * 2**20), "MALLOC_TRIM_THRESHOLD_": str(256 * 2**20)}


def configure_local_workers() -> None:
    """Set up this process's local dask workers: :data:`LOCAL_WORKER_CONFIG`, and their environment with glibc's
    allocator as :data:`LOCAL_WORKER_MALLOC` sets it in place of dask's ``MALLOC_TRIM_THRESHOLD_`` of 64 KiB, the
    rest of what dask's nanny sets there (``distributed.nanny.pre-spawn-environ``: one BLAS/OpenMP thread) kept.
    Dask's trim threshold gives freed memory back to the system at once and turns glibc's dynamic mmap threshold
    off, so every numpy temporary above 128 KiB is a fresh mmap paid in page faults: a worker solved the default
    study's points 1.22x slower than this process (its numpy parts 1.6x), and 0.94x without it; with the
    thresholds of :data:`LOCAL_WORKER_MALLOC` the process itself solves them faster still (docs/workers.md). What a
    worker holds between points stays below what its largest point took (its peak). Set for the process, not in a
    context: each nanny reads both when it is made (and passes the config to its worker) and keeps them for its
    restarts."""
    import dask
    import distributed  # noqa: F401 - its defaults are in dask's config once imported

    environ = dict(dask.config.get("distributed.nanny.pre-spawn-environ", default={}) or {})
    environ.update(LOCAL_WORKER_MALLOC)
    dask.config.set({"distributed.nanny.pre-spawn-environ": environ, **LOCAL_WORKER_CONFIG})


def _local_cluster(workers: int, attempts: int = 3):
    """A LocalCluster of ``workers`` single-thread processes that never see Ctrl-C.

    SIGINT is ignored in this process while the cluster starts, so the worker processes it spawns
    inherit the ignored signal (a spawned Python keeps an ignored SIGINT ignored); a Ctrl-C in those
    1-3 s is lost (press it again). A worker restarted later ignores it once :func:`dask_setup` has
    run. A worker killed while the cluster starts fails the start: it is tried again; whatever a failed start
    had begun is closed (each cluster is recorded before it starts, by a subclass: dask names no public registry
    of clusters whose constructor raised).
    """
    import signal
    import threading

    from dask.distributed import LocalCluster

    class Recorded(LocalCluster):
        def __init__(self, record: list, **kwargs):
            record.append(self)
            super().__init__(**kwargs)

    configure_local_workers()

    started: list = []
    for attempt in range(attempts):
        main = threading.current_thread() is threading.main_thread()  # only it may set handlers
        handler = signal.signal(signal.SIGINT, signal.SIG_IGN) if main else None
        try:
            return Recorded(started, n_workers=workers, threads_per_worker=1, processes=True,
                            dashboard_address="127.0.0.1:0", silence_logs=logging.CRITICAL, preload=[__name__])
        except BaseException as exc:
            retry = isinstance(exc, RuntimeError) and attempt < attempts - 1
            if not retry:
                _quiet_shutdown()
            for cluster in started:
                with contextlib.suppress(Exception):
                    cluster.close(timeout=5)
            started.clear()
            if isinstance(exc, RuntimeError) and not retry:
                raise SweepError(f"could not start {workers} local workers ({exc}); nothing was computed in "
                                 "this run: run the same command again") from None
            if not retry:
                raise
        finally:
            if main:
                signal.signal(signal.SIGINT, handler)


def _quiet_shutdown() -> None:
    """Going down on purpose: the event loop's and dask's complaints about half-started or cancelled
    work would only bury the one line the user needs."""
    for name in ("asyncio", "distributed", "tornado"):
        logging.getLogger(name).setLevel(logging.CRITICAL + 1)


def _run_distributed(grid, keys, code, tasks, store_chunk, scheduler, workers) -> None:
    """Submit every chunk with its own points; store each as it completes; resubmit a chunk whose
    worker was lost (dask gives up on a task after a few lost workers: ``KilledWorker``). Each task reports the
    code hash its worker runs (:func:`study.workflow.chunks.solve_task`): a worker that runs other code than
    ``code`` (a long-lived cluster started before the sources changed) ends the sweep, nothing of it stored."""
    from dask.distributed import Client, as_completed
    from distributed.comm.core import CommClosedError
    from distributed.scheduler import KilledWorker

    if scheduler:
        cluster, client = None, Client(scheduler)
    else:
        cluster = _local_cluster(workers)
        client = Client(cluster)
    try:
        try:  # import the solvers on every worker before the clock of the first chunk
            client.run(warm_up)
        except Exception:  # noqa: BLE001 - only a head start: a worker lost meanwhile imports on its first task
            pass

        def submit(task):
            indices, _ = task
            return client.submit(solve_task, grid.take(indices, keys[indices]), code, pure=False)

        futures = {submit(task): (task, 0) for task in tasks}
        pending = as_completed(futures)
        for future in pending:
            task, resubmits = futures.pop(future)
            try:
                ran, columns = future.result()
            except (KilledWorker, CancelledError, CommClosedError) as exc:
                if resubmits >= RESUBMITS:
                    raise SweepError(f"chunk {task[1].name} lost its worker {resubmits + 1} times "
                                     f"({type(exc).__name__}); run the same command again to resume") from None
                again = submit(task)
                futures[again] = (task, resubmits + 1)
                pending.add(again)
                continue
            except Exception as exc:  # noqa: BLE001 - raised on the worker (solve_point records a point's own faults)
                raise SweepError(f"chunk {task[1].name} failed on a worker of {scheduler or 'the local cluster'} "
                                 f"({type(exc).__name__}: {str(exc)[:200]}); a cluster started before the code "
                                 "changed runs the old code: restart its workers and run the same command "
                                 "again") from None
            finally:
                future.release()
            check_code(ran, code, f"a worker of {scheduler or 'the local cluster'}")
            store_chunk(*task, columns)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()

