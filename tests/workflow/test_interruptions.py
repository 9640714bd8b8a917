"""Reliability of sweeps (study.workflow): killed at random moments, workers lost, resumed - same results."""

import os
import random
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from study.config import load_text
from study.workflow.chunks import load_chunk
from study.workflow.sweep import PARTIAL, run_sweep

ROOT = Path(__file__).resolve().parents[2]
BASE = (ROOT / "configs" / "paper.toml").read_text().split("[sweep]")[0]
AXES = """[sweep]
chunk_size = 40
[sweep.axes]
load.rotary_speed = { start = "50 rpm", stop = "300 rpm", num = 200 }
load.axial_tension = ["-20000 lbf", "5000 lbf", "10000 lbf", "20000 lbf", "40000 lbf"]
impact.restitution = [0.2, 0.5, 0.8]
"""  # 3000 points; with the first tension every point buckles: failures are part of the data


def same_results(a: xr.Dataset, b: xr.Dataset):
    assert a.sizes == b.sizes
    for name in a.data_vars:
        if name == "wall_time":
            continue
        np.testing.assert_array_equal(a[name].values, b[name].values, err_msg=name)


def stored(out: Path) -> list[Path]:
    """The chunks a sweep has stored (a temporary .tmp-* file is a write in progress, not a chunk)."""
    return [p for p in (out / PARTIAL).glob("*.npz") if not p.name.startswith(".")]


@pytest.fixture(scope="module")
def config_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("cfg") / "kill.toml"
    path.write_text(BASE + AXES)
    return path


@pytest.fixture(scope="module")
def uninterrupted(config_file, tmp_path_factory):
    out = tmp_path_factory.mktemp("ref")
    return xr.load_dataset(run_sweep(load_text(config_file.read_text(), str(config_file)), out,
                                     scheduler="synchronous", progress=False))


def test_kill_9_at_random_moments_then_resume(config_file, uninterrupted, tmp_path):
    out = tmp_path / "killed"
    command = [sys.executable, "-m", "study", "sweep", str(config_file), "--out", str(out),
               "--scheduler", "synchronous", "--quiet", "--no-charts"]
    rng = random.Random(20261122)
    kills = 0
    for _ in range(4):
        target = rng.randint(1, 60)  # kill once this many of the 75 chunks are stored, plus 0-30 ms
        proc = subprocess.Popen(command, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        while proc.poll() is None and len(stored(out)) < target:
            time.sleep(0.002)
        time.sleep(rng.uniform(0.0, 0.03))
        if proc.poll() is None:
            proc.send_signal(signal.SIGKILL)
            kills += 1
        proc.wait()
        # Whatever is on disk is complete: every stored chunk loads and matches its checksum.
        for chunk in stored(out):
            assert load_chunk(chunk)["point_key"].size > 0
        if (out / "results.nc").exists():
            break
    assert kills >= 3
    finished = subprocess.run(command, cwd=ROOT, capture_output=True, text=True)
    assert finished.returncode == 0, finished.stderr
    assert sorted(p.name for p in out.iterdir()) == ["results.nc"]  # no partial or temporary file left
    with xr.open_dataset(out / "results.nc") as resumed:
        same_results(resumed.load(), uninterrupted)


@pytest.mark.parametrize("killed", [1, 2], ids=["one worker", "both workers"])
def test_workers_killed_mid_sweep_are_survived(config_file, uninterrupted, tmp_path, killed):
    # A real dask.distributed LocalCluster (2 worker processes, TCP on loopback); one worker, or both at
    # once, killed with SIGKILL after the first chunk lands. Every task carries its own points, so the
    # restarted workers redo the lost chunks; nothing is lost.
    from dask.distributed import LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        pids = [nanny.process.pid for nanny in cluster.workers.values()]  # the worker processes
        assert len(pids) == 2 and os.getpid() not in pids
        done_at_kill = []

        def kill(done):
            if not done_at_kill:
                for pid in pids[:killed]:
                    os.kill(pid, signal.SIGKILL)
                done_at_kill.append(done)

        study = load_text(config_file.read_text(), str(config_file))
        path = run_sweep(study, tmp_path / "w", scheduler=cluster.scheduler_address, progress=False,
                         on_chunk=kill)
        assert not set(pids[:killed]) & {nanny.process.pid for nanny in cluster.workers.values()}  # replaced
    assert done_at_kill == [1]
    with xr.open_dataset(path) as result:
        same_results(result.load(), uninterrupted)


def test_ctrl_c_prints_one_line_saying_what_was_kept_then_resumes(config_file, uninterrupted, tmp_path):
    # Ctrl-C at a terminal sends SIGINT to the whole foreground process group: the sweep and its two
    # local worker processes. One line, exit status 130; a resumed sweep reuses what it kept.
    out = tmp_path / "c"
    command = [sys.executable, "-m", "study", "sweep", str(config_file), "--out", str(out), "--quiet",
               "--no-charts"]
    proc = subprocess.Popen(command + ["--workers", "2"], cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, start_new_session=True)
    while proc.poll() is None and len(stored(out)) < 3:
        time.sleep(0.005)
    os.killpg(proc.pid, signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130
    kept = int(err.split("kept ")[1].split()[0])
    assert err == f"study: interrupted: kept {kept} of 3000 points in {out / PARTIAL}; run the same command again " \
                  "to resume\n"
    assert kept >= 120 and kept % 40 == 0
    said = []
    path = run_sweep(load_text(config_file.read_text(), str(config_file)), out, scheduler="synchronous",
                     progress=False, say=said.append)
    assert said == [f"reusing {kept} of 3000 points stored in {out / PARTIAL}"]
    with xr.open_dataset(path) as result:
        same_results(result.load(), uninterrupted)
