"""The time domain's motion sampled over one revolution, and the stresses it carries (docs/model.md §5, §10).

The event-driven integrator (:mod:`study.solvers.kernels.event_driven`) gives the modal state at any time: the
flights are exact and the contacts are integrated with their own step, so a revolution is sampled by
advancing from sample to sample — uniformly over the revolution and densely across every contact (the
contacts are found by a first pass over the same revolution from the same state).

Fields from the sampled modal states q_n(t) and contact forces F_p(t) (forces on the pipe at x_p = ξ_p L),
with the quasi-static (mode-acceleration) correction for the contact forces, as the ``fast`` method's
split (docs/model.md §5): the N modes carry the dynamics; the modes above N respond to the contact forces
statically, and their sum is the exact static field of a point load minus its first N modal terms.

- moment −EI y'' = EI Σ_n k_n² q_n sin k_n x + Σ_p F_p [m_s(x; x_p) − Σ_{n ≤ N} (2/L) EI sin k_n x_p
  sin k_n x/(EI k_n² + T)], with the static moment of a unit point load on the simply supported
  beam-column in closed form (:func:`study.physics.beam.point_load_moment`);
- deflection y = Σ_n q_n sin k_n x + Σ_p F_p Σ_{N < n ≤ 4096} (2/L) sin k_n x_p sin k_n x/(EI k_n⁴ + T k_n²)
  (the static terms fall like n⁻⁴).

Modal mass M L/2 and ω_n² = (EI k_n⁴ + T k_n²)/M as :mod:`study.solvers.methods.timedomain`. No shear: the
shear of a point contact jumps under the load, which the time domain's point contact cannot resolve.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from study.physics import beam
from study.solvers.kernels import event_driven

#: Highest mode of the static tail sum of the deflection correction.
STATIC_TAIL_MODES = 4096


@dataclass
class Samples:
    """One revolution of the time domain, sampled."""

    times: np.ndarray  #: (T,) [s]
    q: np.ndarray  #: (T, N) modal coordinates [m]
    v: np.ndarray  #: (T, N) modal velocities [m/s]
    forces: np.ndarray  #: (T, P) contact forces on the pipe [N]
    contacts: list  #: (point, start [s], end [s]) of every contact in the revolution
    outcome: int  #: event_driven.OK, BLOWN_UP or TOO_MANY_EVENTS


def contact_intervals(events, active, t0: float, t1: float) -> list[tuple[int, float, float]]:
    """(point, start, end) of every contact between t0 and t1 from the integrator's events; ``active``:
    the contacts already open at t0 (per point). A contact still open at t1 ends there."""
    open_since = {int(p): t0 for p in np.flatnonzero(active)}
    out = []
    for kind, p, t, _, _ in events:
        if kind == event_driven.ONSET:
            open_since[p] = t
        elif p in open_since:
            out.append((p, open_since.pop(p), t))
    out += [(p, start, t1) for p, start in open_since.items()]
    return sorted(out, key=lambda c: c[1])


def sample_revolution(system: event_driven.EventSystem, contact_forces, t0: float, t1: float, z, active, chi, peak,
                      flight_points: int = 256, contact_points: int = 65) -> Samples:
    """Sample the motion from t0 to t1 [s] starting from the state z = (q, v) with the contact state
    (``active``, ``chi``, ``peak`` per point; not modified): ``flight_points`` uniform times and
    ``contact_points`` across each contact. ``contact_forces(q, v, chi)``: the forces on the pipe (P,) [N]."""
    first = event_driven.advance(system, t0, t1, z, active.copy(), chi.copy(), peak.copy())
    contacts = contact_intervals(first[1], active, t0, t1)
    times = [np.linspace(t0, t1, flight_points)]
    times += [np.linspace(start, end, contact_points) for _, start, end in contacts]
    times = np.unique(np.concatenate(times))
    active, chi, peak = active.copy(), chi.copy(), peak.copy()
    n = len(z) // 2
    states = np.empty((times.size, 2 * n))
    forces = np.empty((times.size, active.size))
    state, outcome, now = np.array(z, float), event_driven.OK, t0
    for i, t in enumerate(times):
        if t > now:
            state, _, outcome = event_driven.advance(system, now, t, state, active, chi, peak)
            now = t
        states[i] = state
        forces[i] = contact_forces(state[:n], state[n:], chi)
        if outcome != event_driven.OK:
            times, states, forces = times[:i + 1], states[:i + 1], forces[:i + 1]
            break
    return Samples(times=times, q=states[:, :n], v=states[:, n:], forces=forces, contacts=contacts, outcome=outcome)


def fields(samples: Samples, x, modes, points, span_length: float, bending_stiffness: float,
           tension: float) -> dict[str, np.ndarray]:
    """Deflection y [m] and moment −EI y'' [N m] on x [m] (shape times × x) from the samples, with
    the quasi-static correction for the contact forces (module docstring). ``modes``: mode numbers
    (N,) of the samples' coordinates; ``points``: contact points ξ_p (P,) as fractions of the span. Samples whose
    ``forces`` are None are taken without the correction (the modes alone)."""
    x = np.asarray(x, float)
    L, ei, tn = float(span_length), float(bending_stiffness), float(tension)
    n = np.asarray(modes, float)
    at = np.asarray(points, float) * L  # (P,)
    both = samples.q @ _modal_fields(L, ei, n.tobytes(), x.tobytes())  # one product for both fields: (T, 2X)
    if samples.forces is not None:
        both += samples.forces @ _static_fields(L, ei, tn, n.tobytes(), at.tobytes(), x.tobytes())
    return {"deflection": both[:, :x.size], "moment": both[:, x.size:]}


@functools.lru_cache(maxsize=8)
def _modal_fields(L: float, ei: float, modes: bytes, x: bytes) -> np.ndarray:
    """The modes' shapes beside their moments, [sin k_n x, EI k_n² sin k_n x] (N, 2X), for :func:`fields` (arguments
    as there, the arrays as their bytes: the same for every point of a study whose sections have one length and
    stiffness)."""
    n, x = np.frombuffer(modes), np.frombuffer(x)
    k = n * np.pi / L
    shapes = _shapes(L, n, x)
    modal = np.hstack([shapes, shapes * (ei * k**2)[:, None]])
    modal.flags.writeable = False
    return modal


def _shapes(L: float, n: np.ndarray, x: np.ndarray) -> np.ndarray:
    """sin k_n x (N, X) of the modes n on the points x [m], from the table of :func:`_sines` where it holds them."""
    whole = np.all((n == np.round(n)) & (n >= 1) & (n <= STATIC_TAIL_MODES))
    return _sines(L, x.tobytes())[n.astype(int) - 1] if whole else np.sin(np.outer(n * np.pi / L, x))


@functools.lru_cache(maxsize=8)
def _static_fields(L: float, ei: float, tn: float, modes: bytes, at: bytes, x: bytes) -> np.ndarray:
    """Per unit force at each point, the static deflection and moment of the modes above N, [y_s, m_s] (P, 2X), for
    :func:`fields`' quasi-static correction (arguments as there, the arrays as their bytes, so that the calls on one
    model — both directions, several motions — compute it once; module docstring)."""
    n, at, x = np.frombuffer(modes), np.frombuffer(at), np.frombuffer(x)
    k = n * np.pi / L
    sines = _sines(L, x.tobytes())
    shapes = _shapes(L, n, x)  # (N, X)
    kept = np.sin(np.outer(at, k)) * (2.0 / L)  # (P, N): (2/L) sin k_n x_p
    moment_kept = (kept * (ei / (ei * k**2 + tn))) @ shapes  # (P, X): the kept modes' static moment
    moment_static = beam.point_load_moment(x[None, :], at[:, None], L, ei, tn) - moment_kept
    first = int(n.max()) + 1
    tail = np.arange(first, STATIC_TAIL_MODES + 1, dtype=float)
    kt = tail * np.pi / L
    deflection_static = ((np.sin(np.outer(at, kt)) * (2.0 / L) / (ei * kt**4 + tn * kt**2)) @ sines[first - 1:]
                         if tail.size else np.zeros((at.size, x.size)))
    static = np.hstack([deflection_static, moment_static])
    static.flags.writeable = False
    return static


@functools.lru_cache(maxsize=4)
def _sines(L: float, x: bytes) -> np.ndarray:
    """sin k_n x (STATIC_TAIL_MODES, X) for every mode n = 1 … STATIC_TAIL_MODES, k_n = nπ/L, on the points
    x [m] (as bytes): the same for every point of a study whose sections have one length."""
    k = np.arange(1, STATIC_TAIL_MODES + 1, dtype=float) * np.pi / L
    table = np.sin(np.outer(k, np.frombuffer(x)))
    table.flags.writeable = False
    return table
