"""Sampled time-domain motion and its fields (study.solvers.kernels.trajectory)."""

import numpy as np
import pytest

from study.physics import beam
from study.solvers.kernels import event_driven, trajectory


def test_contact_intervals_pair_onsets_with_ends():
    on, end = event_driven.ONSET, event_driven.END
    events = [(end, 1, 0.1, 0.0, 5.0), (on, 0, 0.2, 1.0, 0.0), (end, 0, 0.3, 0.5, 9.0), (on, 0, 0.8, 1.0, 0.0)]
    active = np.array([False, True])  # point 1 is in contact when the interval starts
    assert trajectory.contact_intervals(events, active, 0.0, 1.0) == [(1, 0.0, 0.1), (0, 0.2, 0.3), (0, 0.8, 1.0)]


@pytest.mark.parametrize("tension", [4.4e4, 1.0e4])  # two tensions in turn: fields' static parts are kept per model
@pytest.mark.parametrize("pattern", ["one_wall", "alternating"])
def test_fields_of_the_periodic_motion_are_the_fast_methods_fields(pattern, tension):
    # Source: the fast method's quasi-static split (beam.periodic_fields) is an identity for the periodic
    # response to a point pulse train; fed the same modal states and the same contact force, the
    # time-domain fields (kept modes + closed-form static remainder) must reproduce it.
    span, ei, mass = 12.0, 8.3e5, 52.0
    impulse, duration, period, n_modes = -120.0, 1.5e-3, 0.2, 21
    t = np.concatenate([np.linspace(0.0, duration, 40), np.linspace(duration, period, 200)])
    x = np.linspace(0.0, span, 31)
    odd = np.arange(1, n_modes + 1, 2, dtype=float)
    k = odd * np.pi / span
    omega = np.sqrt((ei * k**4 + tension * k**2) / mass)
    amp = impulse * beam.modal_load_factors(odd, span) / (0.5 * mass * span)
    r = beam.modal_periodic_response(t[:, None], omega, duration, period, pattern)
    q = np.zeros((t.size, n_modes))
    q[:, ::2] = amp * r.displacement
    force = impulse * beam.pulse_train(t, duration, period, pattern)[:, None]  # on the pipe at midspan
    samples = trajectory.Samples(times=t, q=q, v=np.zeros_like(q), forces=force, contacts=[], outcome=0)
    got = trajectory.fields(samples, x, np.arange(1, n_modes + 1), [0.5], span, ei, tension)
    want = beam.periodic_fields(x, t, ["deflection", "moment"], span, ei, tension, mass, impulse, duration, period,
                                pattern, 0.0, "point", n_modes)
    for kind in ("deflection", "moment"):
        assert np.max(np.abs(got[kind] - want[kind])) <= 1e-9 * np.max(np.abs(want[kind])), kind
