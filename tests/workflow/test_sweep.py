"""Sweeps end to end (study.workflow.execute, .dataset, .sweep): dataset, resume, distributed."""

import errno
import os
import shutil
import socket
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from study.config import load_text
from study.workflow.execute import SweepError
from study.workflow.sweep import PARTIAL, run_sweep

ROOT = Path(__file__).resolve().parents[2]
TEXT = (ROOT / "configs" / "paper.toml").read_text()
SMALL_AXES = """[sweep.axes]
load.rotary_speed = { start = "100 rpm", stop = "300 rpm", num = 5 }
load.axial_tension = ["-20000 lbf", "10000 lbf", "20000 lbf"]
impact.restitution = [0.2, 0.8]
"""


def small_study(chunk_size=4):
    text = TEXT.split("[sweep]")[0] + f"[sweep]\nchunk_size = {chunk_size}\n" + SMALL_AXES
    return load_text(text, "small.toml")


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    out = tmp_path_factory.mktemp("reference")
    return xr.load_dataset(run_sweep(small_study(), out, scheduler="synchronous", progress=False))


def test_dataset_is_labelled_cf(reference):
    ds = reference
    assert ds.sizes == {"rotary_speed": 5, "axial_tension": 3, "restitution": 2}
    assert ds.attrs["Conventions"].startswith("CF-")
    for key in ("title", "source", "history", "date_created", "config", "config_hash"):
        assert ds.attrs[key]
    assert ds.rotary_speed.attrs["units"] == "rad s-1" and ds.rotary_speed.attrs["display_units"] == "rpm"
    assert np.all(np.diff(ds.rotary_speed.values) > 0)
    assert ds.peak_contact_force.attrs["units"] == "N" and ds.peak_contact_force.attrs["long_name"]
    assert ds.status.attrs["flag_meanings"].split()[0] == "ok"
    assert ds.outer_diameter.attrs["units"] == "m"  # a fixed input as a scalar coordinate
    assert "max_normal_stress" not in ds  # nothing computed is faked


def test_failing_points_are_flagged_and_the_sweep_goes_on(reference):
    # T0 = -20000 lbf compresses the 345-ft span far beyond its Euler load: buckled, recorded, not fatal.
    buckled = reference.status.sel(axial_tension=reference.axial_tension.values[0])
    assert np.all(buckled == 1)
    assert "Euler load" in str(reference.message.sel(axial_tension=reference.axial_tension.values[0]).values.flat[0])
    # the rest are solved, and none is called ok: at the printed 345-ft span the prescribed closure's contact is
    # metres long on a 4.5-in pipe, not a Hertz contact (the gate, study.solvers.model.gate)
    assert np.all(reference.status.sel(axial_tension=reference.axial_tension.values[1:]) == 2)
    assert np.all(np.isnan(reference.peak_contact_force.sel(axial_tension=reference.axial_tension.values[0])))


def test_no_fill_value_on_coordinates_and_output_layout(tmp_path):
    path = run_sweep(small_study(), tmp_path / "s", scheduler="synchronous", progress=False)
    assert sorted(p.name for p in path.parent.iterdir()) == ["results.nc"]
    import netCDF4

    with netCDF4.Dataset(path) as nc:
        for name in ("rotary_speed", "axial_tension", "restitution", "outer_diameter"):
            assert "_FillValue" not in nc.variables[name].ncattrs()


def test_history_appends_one_line_per_run(tmp_path):
    out = tmp_path / "h"
    run_sweep(small_study(), out, scheduler="synchronous", progress=False)
    path = run_sweep(small_study(), out, scheduler="synchronous", progress=False)
    with xr.open_dataset(path) as ds:
        assert len(ds.attrs["history"].splitlines()) == 2


def test_interrupted_sweep_resumes_and_recomputes_only_what_is_missing(tmp_path, reference, monkeypatch):
    out = tmp_path / "r"

    def stop_after_two(done):
        if done == 2:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run_sweep(small_study(), out, scheduler="synchronous", progress=False, on_chunk=stop_after_two)
    stored = sorted((out / PARTIAL).glob("*.npz"))
    assert len(stored) == 2 and not (out / "results.nc").exists()
    assert not list((out / PARTIAL).glob(".tmp-*"))  # no partial file left behind

    import study.workflow.execute as execute

    solved = []
    original = execute.solve_chunk
    monkeypatch.setattr(execute, "solve_chunk", lambda points: solved.append(len(points)) or original(points))
    path = run_sweep(small_study(), out, scheduler="synchronous", progress=False)
    total_chunks = -(-30 // 4)
    assert len(solved) == total_chunks - 2
    resumed = xr.load_dataset(path)
    for name in ("peak_contact_force", "status", "first_natural_frequency"):
        np.testing.assert_array_equal(resumed[name].values, reference[name].values)
    assert not (out / PARTIAL).exists()


def test_changed_inputs_never_reuse_stale_chunks(tmp_path):
    out = tmp_path / "c"
    with pytest.raises(KeyboardInterrupt):
        run_sweep(small_study(), out, scheduler="synchronous", progress=False,
                  on_chunk=lambda done: (_ for _ in ()).throw(KeyboardInterrupt) if done == 3 else None)
    changed = load_text(small_study().text.replace('outer_diameter = "4.5 in"', 'outer_diameter = "4.6 in"'),
                        "small.toml")
    path = run_sweep(changed, out, scheduler="synchronous", progress=False)
    with xr.open_dataset(path) as ds:
        assert float(ds.outer_diameter) == pytest.approx(4.6 * 0.0254)
        fresh = run_sweep(changed, tmp_path / "fresh", scheduler="synchronous", progress=False)
        with xr.open_dataset(fresh) as ref:
            np.testing.assert_array_equal(ds.peak_contact_force.values, ref.peak_contact_force.values)


def test_local_cluster_of_worker_processes_gives_the_same_result(tmp_path, reference):
    # The real distributed path: a dask LocalCluster with 2 worker processes talking TCP on loopback.
    path = run_sweep(small_study(chunk_size=3), tmp_path / "d", scheduler="", workers=2, progress=False)
    with xr.open_dataset(path) as ds:
        for name in ("peak_contact_force", "status", "contact_duration"):
            np.testing.assert_array_equal(ds[name].values, reference[name].values)


def test_local_workers_keep_numpys_blocks_on_the_heap_one_blas_thread_and_quiet_monitors():
    # dask's nanny sets MALLOC_TRIM_THRESHOLD_=65536 in a worker, which turns glibc's dynamic mmap threshold off:
    # the workers solved the default study's points 1.22x slower than one process; blocks up to 64 MiB on the heap
    # took the page faults of a bouncing point's windows off (docs/workers.md); dask's profiler and monitors woke
    # the workers' processes on the cores the points share: 1.08x (docs/workers.md)
    import dask
    from dask.distributed import Client

    from study.workflow.execute import LOCAL_WORKER_CONFIG, _local_cluster

    def read():
        names = ("MALLOC_TRIM_THRESHOLD_", "MALLOC_MMAP_THRESHOLD_", "OPENBLAS_NUM_THREADS")
        return ({name: os.environ.get(name) for name in names},
                {name: dask.config.get(name) for name in LOCAL_WORKER_CONFIG})

    cluster = _local_cluster(1)
    try:
        with Client(cluster) as client:
            (seen,) = client.run(read).values()
    finally:
        cluster.close()
    environ, config = seen
    assert environ == {"MALLOC_TRIM_THRESHOLD_": str(256 * 2**20), "MALLOC_MMAP_THRESHOLD_": str(64 * 2**20),
                       "OPENBLAS_NUM_THREADS": "1"}
    assert config == {"distributed.worker.profile.enabled": False, "distributed.admin.tick.interval": "1s",
                      "distributed.worker.memory.monitor-interval": "1s",
                      "distributed.admin.system-monitor.interval": "5s"}


def test_methods_can_be_swept_side_by_side(tmp_path):
    # solver.method is a choice input, so it can be an axis (solver_method): each method's results over
    # the same grid; the output "method" names the method that solved each point.
    text = TEXT.split("[sweep]")[0] + ('[sweep.axes]\nsolver.method = ["core", "sdof"]\n'
                                      'load.rotary_speed = ["100 rpm", "300 rpm"]\n')
    path = run_sweep(load_text(text, "methods.toml"), tmp_path / "m", scheduler="synchronous", progress=False)
    with xr.open_dataset(path) as ds:
        assert list(ds.solver_method.values) == ["core", "sdof"]
        assert (ds.method.values == ds.solver_method.values[:, None]).all()
        assert np.all(np.isfinite(ds.impact_velocity.values))
        # The two models of the same impact: V_p = Omega c (core) and the sdof orbit's own velocity.
        assert not np.allclose(ds.impact_velocity.sel(solver_method="core"), ds.impact_velocity.sel(solver_method="sdof"))


def test_an_output_named_like_a_swept_input_is_kept_beside_it(tmp_path):
    # Sweeping the given span: the core method reports the span it used as an output too.
    text = TEXT.split("[sweep]")[0] + '[sweep.axes]\nsolver.span_length = ["100 ft", "200 ft"]\n'
    path = run_sweep(load_text(text, "spans.toml"), tmp_path / "s", scheduler="synchronous", progress=False)
    with xr.open_dataset(path) as ds:
        np.testing.assert_allclose(ds.span_length_result.values, ds.span_length.values)
        assert "as solved" in ds.span_length_result.attrs["long_name"]


# --- Faults (issue 19): each test injects one and checks that nothing is lost, mixed or silently broken.

def solved_points(monkeypatch):
    """Count the points this process solves (synchronous sweeps)."""
    import study.workflow.execute as execute

    solved = []
    original = execute.solve_chunk
    monkeypatch.setattr(execute, "solve_chunk", lambda points: solved.append(len(points)) or original(points))
    return solved


def interrupt_at(chunks_done):
    def stop(done):
        if done == chunks_done:
            raise KeyboardInterrupt
    return stop


def same_as(path, reference):
    with xr.open_dataset(path) as ds:
        for name in ("peak_contact_force", "status", "first_natural_frequency", "message"):
            np.testing.assert_array_equal(ds[name].values, reference[name].values, err_msg=name)


def damage_truncate(path):
    path.write_bytes(path.read_bytes()[:-100])


def damage_empty(path):
    path.write_bytes(b"")


def damage_flip(path):
    # one bit of a stored value flipped (inside a member's data, not the zip's metadata, which may not matter)
    import zipfile

    with zipfile.ZipFile(path) as archive:
        member = max(archive.infolist(), key=lambda info: info.file_size)
    data = bytearray(path.read_bytes())
    name_length, extra_length = int.from_bytes(data[member.header_offset + 26:member.header_offset + 28], "little"), \
        int.from_bytes(data[member.header_offset + 28:member.header_offset + 30], "little")
    start = member.header_offset + 30 + name_length + extra_length
    data[start + member.file_size - 4] ^= 0x10  # a byte of the last value, past the .npy header
    path.write_bytes(bytes(data))


@pytest.mark.parametrize("damage", [damage_truncate, damage_empty, damage_flip])
def test_a_damaged_chunk_is_named_and_solved_again(tmp_path, reference, monkeypatch, damage):
    out = tmp_path / "d"
    with pytest.raises(KeyboardInterrupt):  # all 8 chunks stored, the dataset not yet written
        run_sweep(small_study(), out, scheduler="synchronous", progress=False, on_chunk=interrupt_at(8))
    victim = sorted((out / PARTIAL).glob("*.npz"))[3]
    damage(victim)
    said, solved = [], solved_points(monkeypatch)
    path = run_sweep(small_study(), out, scheduler="synchronous", progress=False, say=said.append)
    assert said[0].startswith(f"damaged chunk {victim.name} (") and "solved again" in said[0]
    assert said[1:] == [f"reusing {30 - sum(solved)} of 30 points stored in {out / PARTIAL}"]
    assert sum(solved) in (2, 4)  # the damaged chunk's points only (the last chunk has 2)
    same_as(path, reference)


def test_a_changed_solver_source_recomputes_every_point(tmp_path, reference):
    # The fault of issue 19: a solver's code changed without a version bump, then an interrupted sweep
    # resumed. A copy of the package with core.py edited (peak force doubled) resumes the store of the
    # installed one: every point must be solved again by the new code, none mixed in from the old.
    out = tmp_path / "code"
    with pytest.raises(KeyboardInterrupt):
        run_sweep(small_study(), out, scheduler="synchronous", progress=False, on_chunk=interrupt_at(5))
    package = tmp_path / "edited"
    # numba's cache beside the sources comes along (copy2 keeps the time stamps it is keyed on): the copy loads
    # the compiled kernels instead of compiling them all again (core.py, edited, holds none)
    shutil.copytree(ROOT / "study", package / "study")
    core = package / "study" / "solvers" / "methods" / "core.py"
    core.write_text(core.read_text().replace('"peak_contact_force": peak,', '"peak_contact_force": 2.0 * peak,'))
    config = tmp_path / "small.toml"
    config.write_text(small_study().text)
    proc = subprocess.run([sys.executable, "-m", "study", "sweep", str(config), "--out", str(out), "--scheduler",
                           "synchronous", "--quiet", "--no-charts"], cwd=package, capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    assert "reusing" not in proc.stderr
    with xr.open_dataset(out / "results.nc") as ds:
        np.testing.assert_array_equal(ds.peak_contact_force.values, 2.0 * reference.peak_contact_force.values)
        assert ds.attrs["code_hash"] != reference.attrs["code_hash"]


def test_another_chunking_or_a_changed_axis_value_reuses_every_unchanged_point(tmp_path, monkeypatch):
    out = tmp_path / "axis"
    with pytest.raises(KeyboardInterrupt):
        run_sweep(small_study(), out, scheduler="synchronous", progress=False, on_chunk=interrupt_at(3))
    solved = solved_points(monkeypatch)
    with pytest.raises(KeyboardInterrupt):  # 12 points stored in chunks of 4; resumed in chunks of 5
        run_sweep(small_study(chunk_size=5), out, scheduler="synchronous", progress=False, on_chunk=interrupt_at(4))
    assert solved == [5, 5, 5, 3]  # the 18 missing points, none of the 12 stored
    solved.clear()
    # One of the five rotary speeds changed (150 -> 175 rpm): 6 of the 30 points are new.
    changed = small_study().text.replace('load.rotary_speed = { start = "100 rpm", stop = "300 rpm", num = 5 }',
                                         'load.rotary_speed = ["100 rpm", "175 rpm", "200 rpm", "250 rpm", "300 rpm"]')
    path = run_sweep(load_text(changed, "small.toml"), out, scheduler="synchronous", progress=False)
    assert sum(solved) == 6
    with xr.open_dataset(path) as ds:
        fresh = run_sweep(load_text(changed, "small.toml"), tmp_path / "fresh", scheduler="synchronous",
                          progress=False)
        with xr.open_dataset(fresh) as ref:
            np.testing.assert_array_equal(ds.peak_contact_force.values, ref.peak_contact_force.values)


def test_a_second_sweep_into_a_running_ones_folder_is_refused_and_a_killed_ones_lock_taken_over(tmp_path):
    # A real concurrent run: `study sweep` in another process, 3000 points in chunks of 10.
    config = tmp_path / "long.toml"
    config.write_text(TEXT.split("[sweep]")[0] + '[sweep]\nchunk_size = 10\n[sweep.axes]\n'
                      'load.rotary_speed = { start = "50 rpm", stop = "300 rpm", num = 1000 }\n'
                      'impact.restitution = [0.2, 0.5, 0.8]\n')
    out = tmp_path / "busy"
    running = subprocess.Popen([sys.executable, "-m", "study", "sweep", str(config), "--out", str(out),
                                "--scheduler", "synchronous", "--quiet", "--no-charts"], cwd=ROOT,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        while running.poll() is None and not list((out / PARTIAL).glob("*.npz")):
            time.sleep(0.01)
        assert running.poll() is None, "the first sweep ended before the second one started"
        with pytest.raises(SweepError) as refused:
            run_sweep(small_study(), out, scheduler="synchronous", progress=False)
        message = str(refused.value)
        assert f"{out} is being swept by pid {running.pid} on {socket.gethostname()}, started 20" in message
        assert f"config {config}" in message and "\n" not in message
    finally:
        running.kill()
        running.wait()
    said = []
    path = run_sweep(small_study(), out, scheduler="synchronous", progress=False, say=said.append)
    assert said[0].startswith(f"took over the stale lock of pid {running.pid} ")
    assert path.exists() and not (out / ".lock").exists()


def read_only(out, monkeypatch):
    out.mkdir()
    out.chmod(0o555)
    if os.geteuid() == 0:  # root ignores the mode bits: inject the kernel's answer to everyone else
        import tempfile

        def refuse(*args, dir=None, **kwargs):
            raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), str(dir))

        monkeypatch.setattr(tempfile, "mkstemp", refuse)
    return str(out), "Permission denied"


def file_as_folder(out, monkeypatch):
    out.write_text("not a folder")
    return f"{out}: {out} is a file, not a folder", None


def file_as_parent(out, monkeypatch):
    out.parent.write_text("")  # outputs/ is a file: outputs/small cannot be made
    return f"cannot write {out}: {out.parent} is a file, not a folder", None


def results_a_folder(out, monkeypatch):
    (out / "results.nc").mkdir(parents=True)
    return f"cannot write {out / 'results.nc'}: it is a folder", None


@pytest.mark.parametrize("fault", [read_only, file_as_folder, file_as_parent, results_a_folder])
def test_an_unwritable_output_is_refused_before_any_work(tmp_path, monkeypatch, fault):
    out = tmp_path / "outputs" / "small" if fault is file_as_parent else tmp_path / "small"
    path, reason = fault(out, monkeypatch)
    solved = solved_points(monkeypatch)
    try:
        with pytest.raises(SweepError) as refused:
            run_sweep(small_study(), out, scheduler="synchronous", progress=False)
    finally:
        if out.is_dir():
            out.chmod(0o755)
    message = str(refused.value)
    assert path in message and (reason is None or reason in message)
    assert message.endswith("nothing was computed") and "\n" not in message and solved == []


def test_a_full_disk_while_storing_chunks_keeps_what_was_stored(tmp_path, monkeypatch, reference):
    import study.workflow.execute as execute

    out = tmp_path / "full"
    calls = []
    original = execute.save_chunk

    def save_until_full(path, columns):
        calls.append(path)
        if len(calls) == 3:
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), f"{path.parent}/.tmp-x.npz")
        original(path, columns)

    monkeypatch.setattr(execute, "save_chunk", save_until_full)
    with pytest.raises(SweepError) as full:
        run_sweep(small_study(), out, scheduler="synchronous", progress=False)
    assert str(full.value) == (f"cannot write {out / PARTIAL}/.tmp-x.npz: No space left on device; kept 8 of 30 points "
                               f"in {out / PARTIAL} (run the same command again to resume once it can be written)")
    monkeypatch.setattr(execute, "save_chunk", original)
    solved = solved_points(monkeypatch)
    same_as(run_sweep(small_study(), out, scheduler="synchronous", progress=False), reference)
    assert sum(solved) == 22


def test_a_full_disk_while_writing_the_dataset_keeps_every_point(tmp_path, monkeypatch, reference):
    out = tmp_path / "full"
    original = xr.Dataset.to_netcdf
    writes = []

    def write_until_full(self, path=None, *args, **kwargs):
        writes.append(path)
        if len(writes) == 4:  # the header and two variables are in the temporary file
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        return original(self, path, *args, **kwargs)

    monkeypatch.setattr(xr.Dataset, "to_netcdf", write_until_full)
    with pytest.raises(SweepError) as full:
        run_sweep(small_study(), out, scheduler="synchronous", progress=False)
    assert str(full.value) == (f"cannot write {out / 'results.nc'}: No space left on device; all 30 points are kept "
                               f"in {out / PARTIAL}; run the same command again to write it (nothing is recomputed)")
    assert sorted(p.name for p in out.iterdir()) == [PARTIAL]  # no half-written file
    monkeypatch.setattr(xr.Dataset, "to_netcdf", original)
    solved = solved_points(monkeypatch)
    same_as(run_sweep(small_study(), out, scheduler="synchronous", progress=False), reference)
    assert solved == []


def test_a_netcdf_error_while_writing_the_dataset_is_one_line_and_keeps_every_point(tmp_path, monkeypatch, reference):
    # issue 32: a full disk under the netCDF library is "RuntimeError: NetCDF: HDF error", not an OSError: it was a
    # traceback. (make faults injects a real one: a file-size limit under the writing process.)
    out = tmp_path / "full"
    original = xr.Dataset.to_netcdf
    writes = []

    def write_until_full(self, path=None, *args, **kwargs):
        writes.append(path)
        if len(writes) == 3:
            raise RuntimeError("NetCDF: HDF error")
        return original(self, path, *args, **kwargs)

    monkeypatch.setattr(xr.Dataset, "to_netcdf", write_until_full)
    with pytest.raises(SweepError) as full:
        run_sweep(small_study(), out, scheduler="synchronous", progress=False)
    message = str(full.value)
    assert message.startswith(f"cannot write {out / 'results.nc'}: NetCDF: HDF error (from the netCDF library: a full "
                              "disk or a file-size limit, among others; ")
    assert message.endswith(f"free there); all 30 points are kept in {out / PARTIAL}; run the same command again to "
                            "write it (nothing is recomputed)") and "\n" not in message
    assert sorted(p.name for p in out.iterdir()) == [PARTIAL]  # no half-written file
    monkeypatch.setattr(xr.Dataset, "to_netcdf", original)
    solved = solved_points(monkeypatch)
    same_as(run_sweep(small_study(), out, scheduler="synchronous", progress=False), reference)
    assert solved == []


def test_a_grid_over_the_cap_is_refused_with_an_estimate(tmp_path):
    huge = load_text(TEXT.split("[sweep]")[0] + '[sweep.axes]\n'
                     'load.rotary_speed = { start = "50 rpm", stop = "300 rpm", num = 100000 }\n'
                     'load.axial_tension = { start = "1000 lbf", stop = "40000 lbf", num = 100 }\n', "huge.toml")
    start = time.perf_counter()
    with pytest.raises(SweepError) as refused:
        run_sweep(huge, tmp_path / "huge", progress=False)
    assert time.perf_counter() - start < 1.0 and not (tmp_path / "huge").exists()
    assert str(refused.value).startswith("the grid has 10,000,000 points (100000 rotary_speed x 100 "
                                         "axial_tension), more than sweep.max_points = 1,000,000: about ")
    assert "--max-points 10000000" in str(refused.value)  # the config refuses more than 10^7 (test_config.py)
    with pytest.raises(SweepError, match="more than sweep.max_points = 29"):
        run_sweep(small_study(), tmp_path / "s", max_points=29, progress=False)
    assert run_sweep(small_study(), tmp_path / "s", max_points=30, scheduler="synchronous", progress=False).exists()


def test_a_span_search_too_slow_to_hold_is_refused_before_any_work(tmp_path):
    # the honest-results issue: 0.001 rpm made fast allocate 8-16 GiB for one point; a sweep reaching it is
    # refused before it starts, naming the rotary speed, the span and the budget
    from study.workflow.sweep import SweepError

    text = TEXT.split("[sweep]")[0].replace('method = "core"', 'method = "fast"') + \
        '[sweep.axes]\nload.rotary_speed = ["0.001 rpm", "300 rpm"]\n'
    with pytest.raises(SweepError, match=r"at 0.001 rpm down to a 3-m span, above solver.max_poles = 2e\+07.*nothing was computed"):
        run_sweep(load_text(text, "slow.toml"), tmp_path / "slow", scheduler="synchronous", progress=False)
    assert not (tmp_path / "slow").exists() or not any((tmp_path / "slow").iterdir())


def test_a_worker_running_other_code_is_refused_and_nothing_of_it_stored(tmp_path, monkeypatch):
    # issue 32: a long-lived cluster's workers kept the solver code they loaded; after an edit their points were
    # stored under the new code's keys. Simulated: the worker side reports another code hash than the keys'.
    from dask.distributed import LocalCluster

    import study.workflow.chunks as chunks

    monkeypatch.setattr(chunks, "LOADED_CODE", "0" * 64)
    out = tmp_path / "stale"
    with pytest.raises(SweepError, match=r"this process runs other solver code \(code hash 000000000000\) than "
                                         r"this study process .*restart the cluster's workers"):
        run_sweep(small_study(), out / "sync", scheduler="synchronous", progress=False)
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None) as cluster:
        with pytest.raises(SweepError, match=r"a worker of \w+://.* runs other solver code .*nothing it computed "
                                             "was stored"):
            run_sweep(small_study(), out / "cluster", scheduler=cluster.scheduler_address, progress=False)
    assert list((out / "sync" / PARTIAL).glob("*.npz")) == [] == list((out / "cluster" / PARTIAL).glob("*.npz"))


def test_a_task_that_fails_on_a_worker_is_one_line_naming_the_chunk(tmp_path, monkeypatch):
    # a worker of a cluster started before this code (its study.workflow.chunks without solve_task) fails the
    # unpickling of every task: that was a traceback of the worker's exception; now one line with what to do
    from dask.distributed import LocalCluster

    import study.workflow.execute as execute

    def old_worker(points, code):
        raise AttributeError("module 'study.workflow.chunks' has no attribute 'solve_task'")

    monkeypatch.setattr(execute, "solve_task", old_worker)
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None) as cluster:
        with pytest.raises(SweepError, match=r"chunk \w+\.npz failed on a worker of \w+://.* \(AttributeError: module "
                                             r"'study.workflow.chunks' has no attribute 'solve_task'\); a cluster "
                                             r"started before the code changed runs the old code: restart its workers"):
            run_sweep(small_study(), tmp_path / "old", scheduler=cluster.scheduler_address, progress=False)
    assert list((tmp_path / "old" / PARTIAL).glob("*.npz")) == []
