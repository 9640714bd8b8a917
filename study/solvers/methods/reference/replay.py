"""The modal part of an impacting point's error, measured by replaying its impacts (docs/reference_model.md §2.2,
§3.1).

A bouncing window's figures are means over revolutions of a chaotic motion; the change of those means between two
whole runs at N/2 and N modes holds both windows' scatter (the per-revolution peak force scatters by 60-130 %), not
only what the modes do. Here a few of the window's impacts are integrated again, each from the recorded state just
before its strike until the contact has opened, with N modes and with 2N (and more) from the same field: the
difference of the event's peak contact force and stresses is what the modes do to that impact, free of the windows'
scatter, at the cost of a few short integrations.
"""

from __future__ import annotations

from typing import Any, Callable, Mapping

import numpy as np

from study.solvers.model.point import DesignPoint
from study.solvers.methods.reference.fields import stresses
from study.solvers.methods.reference.integrate import Integrator, merge
from study.solvers.methods.reference.model import build_model
from study.physics.string_modes import mode_shapes, mode_wavenumbers
from study.solvers.methods.reference.statistics import whirl_measure

#: Impacts replayed per window: the largest half and the rest spread evenly over the others (typical strikes).
REPLAY_IMPACTS = 4
#: A replay runs this many times the recorded contact's duration past the row before its strike, plus
#: :data:`REPLAY_MARGIN`: the strike, its rebound and the ringing just after (the stresses' peak may follow the
#: contact).
REPLAY_SPAN = 1.5
REPLAY_MARGIN = 5e-4  #: [s]
#: Strikes whose contact lasts longer than this many periods of the first mode left out are not replayed: the modes left
#: out follow such a contact nearly statically, as the quasi-static correction and the in-run measure
#: (:func:`reference.modal_check`, whose ratio (2π/(ω_{N+1} T_c))² is then below 1 %) take them.
REPLAY_LONGEST = 10.0
#: The replayed figures, by the names of the design figures they stand for.
REPLAY_FIGURES = ("peak_contact_force", "max_normal_stress", "alternating_bending_stress", "max_bending_stress",
                  "max_deflection")


def impacts(window, starts, count: int = REPLAY_IMPACTS, longest: float = np.inf) -> list[tuple[int, int, int]]:
    """(first row, peak row, point) of up to ``count`` impacts of the window: each cycle's (its rows from ``starts``)
    largest contact force where it is a strike (its contact opened within the window: the force is nil at a row before
    it and it lasts no longer than ``longest`` [s]), the largest half of them and the others spread evenly over the
    rest (the typical strikes, whose mean the figures are); the first row is the last recorded before the strike, where
    its point's force is nil."""
    fn = window.forces[:, :, 2]
    first = np.searchsorted(window.times, starts)
    found = []
    for a, b in zip(first, list(first[1:]) + [window.times.size]):
        if b <= a or not np.any(fn[a:b] > 0):
            continue
        row, p = np.unravel_index(int(np.argmax(fn[a:b])), fn[a:b].shape)
        row += a
        onset = row
        while onset > 0 and fn[onset, p] > 0:
            onset -= 1
        end = row
        while end < fn.shape[0] - 1 and fn[end, p] > 0:
            end += 1
        if fn[onset, p] > 0 or window.times[end] - window.times[onset] > longest:
            continue  # held from the window's start, or as long as a held contact: not a strike
        found.append((float(fn[row, p]), int(onset), int(row), int(p)))
    found.sort(reverse=True)
    if len(found) > count:
        rest = found[count // 2:]
        picks = np.linspace(0, len(rest) - 1, count - count // 2 + 2)[1:-1].round().astype(int)
        found = found[:count // 2] + [rest[i] for i in picks]
    return [(onset, row, p) for _, onset, row, p in found]


def lift_state(model, big, z, forces=None) -> np.ndarray:
    """The modal state (4M + 4,) of ``big`` (the same point with M ≥ N modes) that carries ``model``'s (4N + 4,) field:
    the kept modes' coefficients on the periodic basis as they are, the basis functions N … M − 1 at their static
    response to the point loads at that instant (``forces`` (P, 3) on the pipe, F_y and F_z, and the joints' weight
    beyond the pipe's) with no velocity — what the N-mode model's quasi-static correction gives them (§3) — and the
    power integrals as they are. The basis' stiffness is diagonal, (L/2)(EI k⁴ + T k²), so their static response is
    exact per function."""

    N, M = model.n_modes, big.n_modes
    z = np.asarray(z, float)
    out = np.zeros(4 * M + 4)
    out[-4:] = z[4 * N:4 * N + 4]
    extra = np.arange(N, M)
    k = mode_wavenumbers(model.span, extra)
    stiffness = 0.5 * model.span * (model.props["bending_stiffness"] * k**4 + model.props["effective_tension"] * k**2)
    at_points = mode_shapes(model.points, model.span, extra)  # (P, M − N)
    for j in range(4):
        q = z[j * N:(j + 1) * N]
        c = np.zeros(M)
        c[:N] = model.basis @ q if model.basis is not None else q
        if j < 2 and extra.size:
            load = np.zeros(model.points.size) if forces is None else np.asarray(forces, float)[:, j].copy()
            if j == 0 and model.point_side is not None:
                load = load + model.point_side
            c[N:] = (at_points.T @ load) / stiffness
        out[j * M:(j + 1) * M] = np.linalg.solve(big.basis, c) if big.basis is not None else c
    return out


def replay(design: DesignPoint | Mapping[str, Any], model, state, start: float, duration: float, point: int,
           rtol: float) -> dict[str, float]:
    """One impact integrated again (:class:`reference.Integrator`, the point's scheme) from ``state`` at ``start`` [s]
    for ``duration`` [s] and longer while ``point``'s contact is still open (up to 4 times): the largest normal force
    at the point [N], the event's stresses (:func:`reference.stresses`, the quasi-static correction on), the
    integrator's steps and the point's time in contact [s]; ``design``: the design point (SI inputs are typed
    first)."""

    design = DesignPoint.of(design)
    option = design.reference
    run = Integrator(model, rtol, state, option.reference_integrator)
    run.t = float(start)
    pieces = [run.run(start + duration, record=True)]
    for _ in range(4):
        if not run.active[point] or run.outcome != 0:
            break
        pieces.append(run.run(run.t + duration, record=True))
    window = merge(pieces)
    if run.outcome != 0 or window.times.size == 0:
        return {}
    values = stresses(design, model, window, correction=True)
    return dict(peak_contact_force=float(np.max(window.forces[:, point, 2])),
                **{name: float(values[name]) for name in REPLAY_FIGURES[1:]}, steps=float(run.steps),
                contact_time=float(window.contact_time[point]))


def replayed(point: DesignPoint, model, window, cycles, counts) -> dict[str, Any]:
    """The window's strikes (:func:`impacts`, none longer than :data:`REPLAY_LONGEST` periods of the first mode left
    out) replayed with each mode count of ``counts`` (ascending, doubling, the run's own first), each from the run's
    recorded state just before its strike lifted onto that count (:func:`lift_state`). Returns ``counts``,
    ``impacts`` (each strike's start [s], point and figures per count) and ``stated``: for each count n but the last,
    each figure's modal part at n (:func:`stated_part`) over the counts from n on, the mean over the strikes."""

    option = point.reference
    rtol = float(option.reference_rtol)
    counts = [int(n) for n in counts]
    longest = REPLAY_LONGEST * 2.0 * np.pi / model.first_left_out()
    picks = impacts(window, [c["start"] for c in cycles], longest=longest)
    models = {model.n_modes: model}
    events = []
    for onset, row, p in picks:
        end = row
        while end < window.times.size - 1 and window.forces[end, p, 2] > 0:
            end += 1
        duration = REPLAY_SPAN * float(window.times[end] - window.times[onset]) + REPLAY_MARGIN
        state, forces = window.states[onset], window.forces[onset]
        figures = {}
        for n in counts:
            if n not in models:
                models[n] = build_model(point.with_reference(reference_modes=n))
            z = state if n == model.n_modes else lift_state(model, models[n], state, forces)
            figures[n] = replay(point.with_reference(reference_modes=n), models[n], z, window.times[onset], duration,
                                p, rtol)
        if all(figures.values()):
            events.append(dict(start=float(window.times[onset]), point=p, figures=figures))
    stated = {}
    for i, n in enumerate(counts[:-1]):
        stated[n] = {name: float(np.mean([stated_part(name, [e["figures"][c] for c in counts[i:]]) for e in events]))
                     if events else 0.0 for name in REPLAY_FIGURES}
    return dict(counts=counts, impacts=events, stated=stated)


def stated_part(name: str, figures: list[Mapping[str, float]]) -> float:
    """The modal part (relative) of figure ``name`` of one replayed strike at the first of counts that double, from
    its figures at them: the change from the first count to the last plus the last change, relative to the first
    count's figure (the alternating stress's to the larger of it and the bending stress, as
    :func:`reference.convergence` counts it) — the change measured and, beyond the last count, a tail no larger than
    the last change (the changes falling at least by half per doubling, a geometric tail at most the last term)."""
    first, before, last = figures[0], figures[-2], figures[-1]
    size = max(first[name], first["max_bending_stress"]) if name == "alternating_bending_stress" else first[name]
    if size <= 0:
        return 0.0
    return float((abs(last[name] - first[name]) + abs(last[name] - before[name])) / size)


def impact_modal_error(point: DesignPoint, model, window, cycles, cache: dict,
                       measure: Callable[..., dict[str, float]]) -> dict[str, float]:
    """The modal part of each figure's error (relative) at a run's N modes (docs/reference_model.md §3.1): where the
    window holds strikes (contact onsets, the Hertz law, the pipe not lying on the wall) from its strikes replayed at N,
    2N and on to ``reference_max_modes`` (:func:`replayed`, done once per run and kept in ``cache["replay"]``), the
    part :func:`stated_part` states at N; elsewhere, and where no strike is short enough to replay, the in-run measure
    ``measure`` (:func:`reference.modal_check`), as before; and everywhere unless ``reference_modal_measure`` is
    ``"replay"``."""

    if (point.reference.reference_modal_measure != "replay" or model.law != 0
            or not np.any(window.onsets > 0) or whirl_measure(model, window)["whirl"] == "sliding"):
        return measure(point, model, window, cycles)
    if "replay" not in cache:
        counts = [model.n_modes, 2 * model.n_modes]
        while counts[-1] < int(point.reference.reference_max_modes):
            counts.append(2 * counts[-1])
        cache["replay"] = replayed(point, model, window, cycles, counts)
    found = cache["replay"]
    if not found["impacts"]:
        return measure(point, model, window, cycles)
    return dict(found["stated"][model.n_modes])


def replay_summary(found: Mapping[str, Any]) -> dict[str, Any]:
    """What a result keeps of :func:`replayed` (``extras["replay"]``): the counts, the stated parts per count, and per
    strike its start [s], point and peak contact force, max normal and alternating stress per count."""
    keep = ("peak_contact_force", "max_normal_stress", "alternating_bending_stress")
    return dict(counts=list(found["counts"]), stated={int(n): dict(v) for n, v in found["stated"].items()},
                impacts=[dict(start=e["start"], point=e["point"],
                              figures={int(n): {k: f[k] for k in keep} for n, f in e["figures"].items()})
                         for e in found["impacts"]])
