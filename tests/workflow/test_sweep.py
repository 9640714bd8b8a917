"""Sweeps end to end (study.workflow.execute, .dataset, .sweep): dataset, resume, distributed."""

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from study.config import load_text
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
    # metres long on a 4.5-in pipe, not a Hertz contact (the gate, study.solvers.gate)
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
    monkeypatch.setattr(execute, "solve_chunk", lambda grid, idx: solved.append(idx) or original(grid, idx))
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
