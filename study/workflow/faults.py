"""Fault injection: kill a sweep and its workers at random moments, resume, compare with a clean run.

    python -m study.workflow.faults --runs 10          # what `make faults` runs

First one uninterrupted ``study sweep`` of the config (the reference);
then ``runs`` times, into a fresh folder: start ``study sweep`` with local workers and inject one to
three faults, each at a random moment, drawn from

- ``kill -9 all``: SIGKILL to the sweep and every process it started;
- ``kill -9 workers``: SIGKILL to every worker process at once, once a random number of chunks is
  stored; the sweep itself must finish on its own;
- ``Ctrl-C``: SIGINT to the sweep's process group (as a terminal does); it must end with exit status
  130 and one line saying what was kept;
- ``damaged chunk``: a kill -9, then one stored chunk file truncated, emptied or bit-flipped;
- ``disk full``: the sweep runs with a file-size limit (``RLIMIT_FSIZE``, half the reference's ``results.nc``), so
  that a write past it fails in the C library as on a full disk (``EFBIG`` instead of ``ENOSPC``, through numpy's
  and netCDF/HDF5's writers alike); it must end with status 1 and one line saying what was kept;

at a moment drawn from three phases (weights 1:3:1): 0-3 s after the start (imports, the cluster's
start-up), while computing (after a random number of chunks is stored), or while ``results.nc`` is
written (its temporary file exists);

then run the same command again (as often as needed) until it finishes. Every sweep is the ``study`` console script
(what a user runs), so a Ctrl-C in its first second lands while it imports. A run passes when no output
has a traceback, every run ends as it should, nothing but ``results.nc`` is left in the folder, and
the dataset equals the reference in every variable but ``wall_time``. Prints a markdown report.
Each sweep is a separate ``study sweep`` process: nothing here imports the command line.
"""

from __future__ import annotations

import argparse
import collections
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import xarray as xr

from study.config import load, parse_set
from study.workflow.grid import auto_chunk_size, chunks as grid_chunks
from study.workflow.sweep import PARTIAL, RESULTS

ROOT = Path(__file__).resolve().parents[2]
DEFAULT_CONFIG = ROOT / "configs" / "screen.toml"
KINDS = ("kill -9 all", "kill -9 workers", "Ctrl-C", "damaged chunk", "disk full")
#: What a Ctrl-C may say (study.cli, study.console): what was kept, that nothing was computed, or that the command had
#: already ended.
CTRL_C_LINES = ("kept", "nothing new was computed", "interrupted while exiting")
MOMENTS = ("start-up", "computing", "writing")


@dataclass
class Run:
    """One faulted sweep: the faults injected, how each attempt ended, and the verdict."""

    faults: list[str] = field(default_factory=list)
    exits: list[int] = field(default_factory=list)
    problems: list[str] = field(default_factory=list)
    seconds: float = 0.0


def console_script() -> str:
    """The ``study`` console script of this interpreter's environment (``python -m study`` where there is none)."""
    script = Path(sys.executable).parent / "study"
    return str(script) if script.exists() else ""


def sweep_command(config: Path, out: Path, workers: int, sets: list[str]) -> list[str]:
    start = [console_script()] if console_script() else [sys.executable, "-m", "study"]
    command = start + ["sweep", str(config), "--out", str(out), "--quiet", "--no-charts", "--workers", str(workers)]
    for item in sets:
        command += ["--set", item]
    return command


def chunk_files(out: Path) -> list[Path]:
    return sorted(p for p in (out / PARTIAL).glob("*.npz") if not p.name.startswith("."))


def worker_processes(pid: int) -> list:
    """The dask worker processes a sweep started (spawned by its nannies)."""
    import psutil

    try:
        children = psutil.Process(pid).children(recursive=True)
    except psutil.NoSuchProcess:
        return []
    workers = []
    for child in children:
        try:
            if "spawn_main" in " ".join(child.cmdline()):
                workers.append(child)
        except psutil.Error:
            pass
    return workers


def damage(path: Path, rng: random.Random) -> str:
    """Truncate, empty or flip one bit of a chunk file; say which."""
    data = bytearray(path.read_bytes())
    how = rng.choice(["truncated", "emptied", "bit-flipped"])
    if how == "truncated":
        data = data[: rng.randrange(len(data))]
    elif how == "emptied":
        data = bytearray()
    else:
        data[rng.randrange(len(data))] ^= 1 << rng.randrange(8)
    path.write_bytes(bytes(data))
    return how


def identical(path: Path, reference: xr.Dataset) -> list[str]:
    """The variables (all but wall_time) where ``path`` differs from ``reference``."""
    differ = []
    with xr.open_dataset(path) as result:
        if dict(result.sizes) != dict(reference.sizes) or set(result.data_vars) != set(reference.data_vars):
            return ["layout"]
        for name in reference.data_vars:
            if name == "wall_time":
                continue
            a, b = result[name].values, reference[name].values
            same = np.array_equal(a, b, equal_nan=True) if a.dtype.kind == "f" else np.array_equal(a, b)
            if not same:
                differ.append(name)
    return differ


def wait_for_moment(proc, out: Path, moment: str, chunks: int, rng: random.Random) -> str:
    """Sleep until a random moment of the given phase of a running sweep; say when it was."""
    if moment == "start-up":
        delay = rng.uniform(0.0, 3.0)
        time.sleep(delay)
        return f"{delay:.1f} s after start"
    if moment == "writing":  # results.nc being written: its temporary file is there
        while proc.poll() is None and not list(out.glob(".tmp-*.nc")):
            time.sleep(0.002)
        return "writing results.nc"
    before = len(chunk_files(out))
    target = rng.randint(1, max(1, chunks - 1))
    while proc.poll() is None and len(chunk_files(out)) - before < target:
        time.sleep(0.002)
    time.sleep(rng.uniform(0.0, 0.05))
    return f"{len(chunk_files(out))} chunks stored"


def file_size_limit(limit: int):
    """A ``preexec_fn`` that caps the size of every file the process (and what it starts) writes at ``limit``
    bytes: a write past it fails with ``EFBIG``, as a full disk fails with ``ENOSPC`` (SIGXFSZ is ignored, as
    Python does anyway, so the write fails instead of the process)."""
    import resource

    def limit_files():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    return limit_files


def one_run(command: list[str], out: Path, chunks: int, rng: random.Random, reference: xr.Dataset,
            disk: int = 0) -> Run:
    """A sweep with 1-3 faults at random moments, then resumed until it finishes. ``disk``: the file-size limit of
    a ``disk full`` fault [bytes]."""
    run = Run()
    start = time.perf_counter()
    faults = rng.randint(1, 3)
    for attempt in range(faults + 5):
        kind = rng.choice(KINDS) if len(run.faults) < faults else None
        label = kind
        proc = subprocess.Popen(command, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                start_new_session=True,
                                preexec_fn=file_size_limit(disk) if kind == "disk full" else None)
        if kind == "kill -9 workers":
            when = wait_for_moment(proc, out, "computing", chunks, rng)
            victims = worker_processes(proc.pid)
            for victim in victims:
                victim.kill()
            label += f" ({len(victims)}, {when})" if victims else " (too late: finished)"
        elif kind == "disk full":
            pass  # the limit strikes where a file outgrows it
        elif kind is not None:
            moment = rng.choices(MOMENTS, weights=(1, 3, 1))[0] if kind != "damaged chunk" else "computing"
            when = wait_for_moment(proc, out, moment, chunks, rng)
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGINT if kind == "Ctrl-C" else signal.SIGKILL)
                label += f" ({when})"
        _, err = proc.communicate()
        if kind == "Ctrl-C" and proc.returncode == 0 and label.endswith("after start)"):
            label = label[:-1] + ": lost while the workers started; finished)"
        elif kind in ("kill -9 all", "Ctrl-C", "damaged chunk") and proc.returncode == 0:  # no moment left
            label += " (too late: finished)"
        elif kind == "disk full":
            said = [line for line in err.strip().splitlines() if line.startswith("study: error: cannot write")]
            where = "results.nc" if said and RESULTS in said[0].split(":")[2] else "a chunk"
            label += f" (writing {where})" if proc.returncode == 1 else " (never reached: finished)"
            if proc.returncode == 1 and (len(said) != 1 or "kept" not in said[0]):
                run.problems.append(f"disk full printed {err.strip()!r}")
        run.exits.append(proc.returncode)
        lines = err.strip().splitlines()
        if any(not line.startswith("study: ") for line in lines):  # one line per event, nothing else
            run.problems.append(f"after {label or 'resume'}, stderr has more than the study's lines: {err.strip()!r}")
        if kind == "Ctrl-C" and proc.returncode == 130:
            said = [line for line in lines if line.startswith("study: interrupted")]
            if len(said) != 1 or not any(words in said[0] for words in CTRL_C_LINES):
                run.problems.append(f"Ctrl-C printed {said!r}")
        if kind == "damaged chunk" and proc.returncode != 0:  # a kill -9, then a chunk damaged
            stored = chunk_files(out)
            if stored:
                label += f", then a chunk {damage(rng.choice(stored), rng)}"
        if proc.returncode not in (0, 130, -signal.SIGKILL) and not (kind == "disk full" and proc.returncode == 1):
            run.problems.append(f"exit status {proc.returncode} after {label or 'resume'}: {err.strip()[-300:]!r}")
        if label is not None:
            run.faults.append(label)
        if proc.returncode == 0 and len(run.faults) >= faults:
            break
    run.seconds = time.perf_counter() - start
    if run.exits[-1] != 0:
        run.problems.append("never finished")
    elif sorted(p.name for p in out.iterdir()) != [RESULTS]:
        run.problems.append(f"left behind: {sorted(p.name for p in out.iterdir())}")
    else:
        differ = identical(out / RESULTS, reference)
        if differ:
            run.problems.append(f"differs from the uninterrupted run in {', '.join(differ)}")
    return run


def run_faults(runs: int = 10, seed: int = 1, config: Path = DEFAULT_CONFIG, workers: int = 2,
               sets: tuple[str, ...] = (), folder: Path | None = None) -> tuple[list[Run], str]:
    """Inject faults into ``runs`` sweeps of ``config``; return the runs and a markdown report."""
    rng = random.Random(seed)
    work = Path(folder or tempfile.mkdtemp(prefix="study-faults-"))
    reference_out = work / "reference"
    shutil.rmtree(reference_out, ignore_errors=True)
    start = time.perf_counter()
    clean = subprocess.run(sweep_command(config, reference_out, workers, list(sets)), cwd=ROOT,
                           capture_output=True, text=True)
    duration = time.perf_counter() - start
    if clean.returncode != 0:
        raise SystemExit(f"the uninterrupted sweep failed: {clean.stderr.strip()}")
    reference = xr.load_dataset(reference_out / RESULTS)
    disk = (reference_out / RESULTS).stat().st_size // 2  # results.nc outgrows it; a chunk file may too
    study = load(config, parse_set(list(sets)))
    size = study.sweep["chunk_size"]
    chunks = sum(1 for _ in grid_chunks(np.arange(study.size), size or auto_chunk_size(study.size), taper=not size))
    results = []
    for number in range(runs):
        out = work / f"run-{number}"
        shutil.rmtree(out, ignore_errors=True)
        results.append(one_run(sweep_command(config, out, workers, list(sets)), out, chunks, rng, reference, disk))
        shutil.rmtree(out, ignore_errors=True)
        verdict = "ok" if not results[-1].problems else "; ".join(results[-1].problems)
        print(f"run {number + 1}/{runs}: {', '.join(results[-1].faults)} -> {verdict}", file=sys.stderr)
    if folder is None:
        shutil.rmtree(work, ignore_errors=True)
    return results, report(results, duration, reference.sizes, seed, config, workers)


def report(results: list[Run], duration: float, sizes, seed: int, config: Path, workers: int) -> str:
    kinds = collections.Counter(fault.split(" (")[0].split(",")[0] for run in results for fault in run.faults)
    late = sum("too late" in fault for run in results for fault in run.faults)
    lost = sum("lost while the workers started" in fault for run in results for fault in run.faults)
    passed = sum(not run.problems for run in results)
    points = int(np.prod(list(sizes.values())))
    lines = [
        f"- config `{Path(config).relative_to(ROOT) if Path(config).is_relative_to(ROOT) else config}`, "
        f"{points} points, {workers} local workers; seed {seed}; "
        f"uninterrupted sweep {duration:.1f} s (start-up included)",
        f"- {len(results)} faulted sweeps, {sum(len(r.faults) for r in results)} faults: "
        + ", ".join(f"{kinds[k]} {k}" for k in KINDS) + f" ({late} landed after the sweep had finished; "
        f"{lost} Ctrl-C lost while the local workers started, as documented)",
        f"- attempts per sweep (the faulted ones and the resumes): "
        f"{min(len(r.exits) for r in results)} to {max(len(r.exits) for r in results)}; "
        f"time per faulted sweep {min(r.seconds for r in results):.1f} to {max(r.seconds for r in results):.1f} s",
        f"- **{passed} of {len(results)}** identical to the uninterrupted run in every variable but `wall_time`, "
        "with no traceback, every Ctrl-C and every full disk one line, nothing left but `results.nc`",
    ]
    for number, run in enumerate(results, 1):
        if run.problems:
            lines.append(f"  - run {number} ({', '.join(run.faults)}): {'; '.join(run.problems)}")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m study.workflow.faults", description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=10, help="faulted sweeps (default 10)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--config", type=Path, default=DEFAULT_CONFIG)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--set", action="append", default=[], metavar="SECTION.KEY=VALUE")
    parser.add_argument("--keep", type=Path, default=None, help="work in this folder and keep it")
    args = parser.parse_args(argv)
    results, text = run_faults(args.runs, args.seed, args.config, args.workers, tuple(args.set), args.keep)
    print(text)
    return 0 if all(not run.problems for run in results) else 1


if __name__ == "__main__":
    sys.exit(main())
