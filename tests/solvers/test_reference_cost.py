"""The reference method's post-processing computed once per cycle and shared (docs/reference_model.md §6): the same
figures as the whole window's recomputation it replaces."""

from pathlib import Path

import numpy as np
import pytest

from study import config
from study.solvers.methods import reference
from study.solvers.methods.reference.integrate import Integrator, initial_state, merge
from study.solvers.methods.reference.model import build_model
from study.solvers.model.point import DesignPoint


@pytest.fixture(scope="module")
def bouncing():
    """configs/default.toml at 250 rpm, 5 000 lbf, e = 0.7, 9 ppg, no flow (a bouncing point of
    tests/solvers/test_reference.py) at 8 modes: 6 revolutions of transient, then 4 recorded revolutions."""
    study = config.load(Path(__file__).resolve().parents[2] / "configs" / "default.toml")
    point = DesignPoint.from_inputs({**study.point(rotary_speed=250 * np.pi / 30, axial_tension=5 * 4448.2216152605,
                                                   restitution=0.7, mud_density=9 * 119.826427,
                                                   mud_flow_velocity=0.0),
                                     "reference_modes": 8})
    model = build_model(point)
    run = Integrator(model, float(point.reference.reference_rtol), initial_state(model),
                     point.reference.reference_integrator)
    run.run(6 * model.period)
    cycles = [run.run(run.t + model.period, record=True) for _ in range(4)]
    assert np.sum(merge(cycles).onsets) > 0  # it strikes: the correction and the modal check have work
    return point, model, cycles


def without_memo(window):
    """The window again, nothing computed for it yet."""
    return merge([window])


def test_the_modal_check_from_the_cycles_kept_values_is_the_whole_windows(bouncing):
    # the modal check reads each cycle's stresses without the correction as cycle_values kept them (on the cycle's own
    # rows), instead of recomputing the whole window's at each look; the window's recomputation cuts it by the cycles'
    # start times, whose row is shared with the cycle before (the kernel records a run's last and first state), so the
    # two agree to the rounding wherever no cycle's extreme lies on its last row
    point, model, cycles = bouncing
    values = reference.cycle_values(point, model, cycles)
    window = merge(cycles)
    kept = reference.modal_check(point, model, window, values)
    again = reference.modal_check(point, model, without_memo(window),
                                  [{k: v for k, v in c.items() if k != "uncorrected"} for c in values])
    assert kept.keys() == again.keys()
    for name in kept:
        assert kept[name] == pytest.approx(again[name], rel=1e-9, abs=1e-12), name
    assert kept["max_normal_stress"] > 0  # the strikes' correction is measured: the comparison is not of zeros


def test_the_cycles_figures_do_not_depend_on_the_batches_they_are_computed_in(bouncing):
    # the window grows by batches of cycles (simulate): a cycle's figures and its kept uncorrected stresses are the same
    # computed with the others or alone (the quasi-static correction decided alike: it enters wherever a contact does)
    point, model, cycles = bouncing
    whole = reference.cycle_values(point, model, cycles)
    parts = reference.cycle_values(point, model, cycles[:2]) + reference.cycle_values(point, model, cycles[2:])
    # the tool joints' mass is lumped here, so the quasi-static correction enters every batch (quasi_static_applies):
    # decided alike, not skipped where it is not
    assert model.joint_points is not None and len({c["correction"] for c in whole + parts}) == 1
    for a, b in zip(whole, parts):
        for name in ("max_normal_stress", "alternating_bending_stress", "max_deflection", "peak_contact_force"):
            assert a[name] == pytest.approx(b[name], rel=1e-12), name
        assert a["uncorrected"] == pytest.approx(b["uncorrected"], rel=1e-12)


def test_the_shared_fields_give_each_call_what_it_computes_alone(bouncing):
    # the stresses with and without the correction, masked or not, share the window's modal fields and the joints'
    # inertia forces (fields.window_memo): each call's answer is the one it gives on a window computed afresh
    point, model, cycles = bouncing
    window = merge(cycles)
    segments = [(0, cycles[0].times.size), (cycles[0].times.size, window.times.size)]
    masked = np.zeros(window.forces.shape[:2], bool)
    masked[:, model.kinds == 1] = window.forces[:, model.kinds == 1, 2] > 0
    calls = [dict(correction=True), dict(correction=False), dict(correction=True, masked=masked),
             dict(correction=False, segments=segments), dict(correction=True, segments=segments)]
    shared = [reference.stresses(point, model, window, **c) for c in calls]
    assert window.memo  # computed once, kept
    for c, got in zip(calls, shared):
        assert got == reference.stresses(point, model, without_memo(window), **c)
    assert shared[0] != shared[2]  # the mask takes the strikes' loads out: the memo did not answer for it


def test_a_long_windows_stresses_taken_a_batch_of_cycles_at_a_time_are_the_whole_windows(bouncing, monkeypatch):
    # cycle_values takes the stresses statistics.STRESS_ROWS rows at a time and fields.modal_accelerations
    # ACCELERATION_ROWS at a time, so that a window grown to a few hundred revolutions does not hold its fields over
    # every row at once (4.15 GiB at one chatter point of the default study, 2.4 GiB so): each cycle's figures are its
    # own rows', so the batches change nothing but the memory — here a batch a cycle and 50 rows, against the whole
    from study.solvers.methods.reference import fields, statistics

    point, model, cycles = bouncing
    whole = reference.cycle_values(point, model, cycles)
    assert statistics.stress_batches(cycles) == [[0, 1, 2, 3]]  # four revolutions: one batch by default
    rows = max(c.times.size for c in cycles)
    assert statistics.stress_batches(cycles, rows) == [[0], [1], [2], [3]]
    assert statistics.stress_batches(cycles, 2 * rows) == [[0, 1], [2, 3]]
    monkeypatch.setattr(statistics, "STRESS_ROWS", rows)
    monkeypatch.setattr(fields, "ACCELERATION_ROWS", 50)
    assert cycles[0].times.size > 100  # the accelerations too are taken in parts
    batched = reference.cycle_values(point, model, cycles)
    # the same recorded cycles (one run of the compiled kernel, in the fixture) through numpy's products on fewer
    # rows: the arithmetic per row is the same, so only BLAS's blocking can move the last bits (measured: equal)
    for a, b in zip(whole, batched):
        for name in ("max_normal_stress", "alternating_bending_stress", "max_deflection", "max_shear_stress",
                     "peak_contact_force"):
            assert b[name] == pytest.approx(a[name], rel=1e-12), name
        assert b["uncorrected"] == pytest.approx(a["uncorrected"], rel=1e-12)
        np.testing.assert_allclose(b[statistics.DAMAGE], a[statistics.DAMAGE], rtol=1e-12)
