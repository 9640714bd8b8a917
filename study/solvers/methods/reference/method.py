"""The reference method (``reference``): a design point simulated until its statistics settle (:func:`simulate`),
its figures with their error estimates (:func:`solve_with_stations`), run again with more body stations
(:func:`solve_with_modes`) and more modes (:func:`solve`) where the model's own error asks for them. The
method's contract is the package's docstring (:mod:`study.solvers.methods.reference`)."""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np

from study.physics import fatigue
from study.solvers.kernels import pulse, whirl_kernel
from study.solvers.methods.reference.fields import contact_spacing, energy_balance
from study.solvers.methods.reference.integrate import Integrator, Window, initial_state, merge
from study.solvers.methods.reference.model import WhirlModel, build_model
from study.solvers.methods.reference.replay import impact_modal_error, lift_state, replay_summary
from study.solvers.methods.reference.statistics import (DAMAGE, FIGURES, FORECAST_SLACK, MODAL_FIGURES,
                                                        WHIRL_CLASSES, WHIRL_REGIMES, convergence, cycle_values,
                                                        figure_tolerance, modal_check, revolutions_for, settle_ratio,
                                                        settling, stationary, strike_modal_part,
                                                        strike_stress_modal_part, whirl_measure, window_summary)
from study.solvers.model.point import DesignPoint
from study.solvers.model.result import REGIMES, PointResult
from study.solvers.kernels.periodicity import settled_period


METHOD = "reference"


def transient_bounds(option, start: Mapping[str, Any] | None = None) -> tuple[int, int]:
    """The least and the most revolutions of :func:`simulate`'s transient (``option``: the point's
    :class:`ReferenceOptions`): ``reference_min_revolutions`` from the initial state (0 for a run continued from
    ``start``, past it), and ``reference_revolutions`` or as many as keep the first ``reference_min_revolutions`` out
    of the window and the stretch before it, whichever is more (where there is a least)."""
    least = int(option.reference_min_revolutions) if start is None else 0
    most = int(option.reference_revolutions)
    return least, max(most, least + 2 * int(option.reference_window)) if least else most


def simulate(point: DesignPoint | Mapping[str, Any], model: WhirlModel | None = None,
             start: Mapping[str, Any] | None = None) -> dict[str, Any]:
    """Transient until periodic, stationary bouncing (:func:`stationary`) or ``reference_revolutions``, then the
    recorded window, extended while its figures have not converged (docs/reference_model.md §3.1); from the initial
    state no revolution before ``reference_min_revolutions`` enters the window (neither a period nor stationary
    bouncing ends the transient sooner: :func:`transient_bounds`). ``start``: where to start at a revolution boundary,
    the run at fewer modes' end (:func:`continued_state`: the modal state and the contacts' state); else
    ``reference_initial``'s.

    Periodic: the window is ``reference_window`` revolutions rounded up to whole periods, its cycles the
    periods. Not periodic: the last ``reference_window`` revolutions of the transient are recorded too, and the
    record (one cycle a revolution) grows while the error of a design figure (:func:`convergence`) is above its
    tolerance (:func:`figure_tolerance` of ``solver.statistical_tolerance``, the peak force's
    ``solver.force_tolerance``), more revolutions could bring it there (its window part is what is over; not foreseen
    beyond :data:`FORECAST_SLACK` times the budget) and ``reference_max_revolutions`` allow, by the revolutions
    foreseen, at least ``reference_window`` and at most the record's length at a time: per figure, so that a figure
    that cannot get there (its modes or integrator part over, or its scatter asking far beyond the budget) does not
    stop the others' growth. Where the record's halves agree (no drift beyond :data:`DRIFT_SIGNIFICANCE`) and the
    state does not settle the window is the whole record; else the window is its second half, the preceding stretch
    its first, and where they differ significantly (still settling) the first half is dropped.

    Returns model, integrator, verdict ('periodic', 'not_periodic', 'failed'), period (revolutions or None),
    revolutions (before the window), window (:class:`Window` or None), cycles and preceding (per-cycle values of the
    window and of the stretch before it, :func:`cycle_values`), budget_spent (stopped over the tolerance: the budget
    would not do), revolutions_needed (the revolutions in all foreseen to bring every figure within the tolerance; inf
    where more would not), needed_by (the same per figure left over its tolerance), stopped_by (why the window
    stopped for each of those, :func:`stop_reasons`), ratio (:func:`settle_ratio`),
    failure (text or None), stationary (the transient ended as the bouncing was found stationary), modal
    (:func:`modal_check` of the window), stats (:func:`settling` of the window as the last look took it; None when
    periodic).
    """
    point = DesignPoint.of(point)
    option = point.reference
    model = model or build_model(point)
    run = start_integrator(model, option, start)
    tau = model.period
    least, revolutions = transient_bounds(option, start)
    n_window = int(option.reference_window)
    budget = int(option.reference_max_revolutions)
    tolerance = point.tolerances.statistical  # the window grows only where the motion does not repeat: means
    force = point.tolerances.force  # the peak contact force's own (solver.force_tolerance)
    per_figure = option.reference_window_growth == "figure"
    doubled = modal_by_doubling(model)
    exponent = fatigue.damage_exponent(point.limits.sn_curve or "B1")
    tol = float(option.reference_tolerance)
    scale = model.state_scale()
    states = [run.modal_state()]
    period = None
    ratio = float("nan")
    replays: dict[str, Any] = {}  # the strikes replayed at more modes (impact_modal_error), once per run

    def failed(where: str) -> dict[str, Any]:
        return dict(model=model, integrator=run, verdict="failed", period=None, revolutions=len(states) - 1,
                    window=None, cycles=[], preceding=[], budget_spent=False,
                    failure=f"{whirl_kernel.OUTCOMES[run.outcome]} {where}")

    kept: list[Window] = []  # the transient's last revolutions, recorded
    peaks, impacts = [], []  # each revolution's largest contact force [N] and contact onsets
    bouncing = False  # the transient ended on stationary bouncing
    for k in range(1, revolutions + 1):
        # the last revolutions are kept: n_window where the transient ends at the last, 2 n_window where a
        # stationary bouncing ends it (from 3 n_window on): those are its window and the stretch before it
        keep = k > min(n_window, revolutions - n_window)
        cycle = run.run(k * tau, record=keep)
        if run.outcome != whirl_kernel.OK:
            return failed(f"in revolution {k}")
        if keep:
            kept = (kept + [cycle])[-2 * n_window:]
        peaks.append(float(np.max(cycle.peak)) if cycle.peak.size else 0.0)
        impacts.append(float(np.sum(cycle.onsets)))
        states.append(run.modal_state())
        if np.max(np.abs(states[-1]) / scale) == 0.0:  # nothing moves
            period = 1 if k >= 2 else None
        else:
            period = settled_period(states, scale, tol)
        if period is not None and k >= least:
            break
        if k - 2 * n_window >= least and k % n_window == 0 and stationary(peaks, impacts, states, scale, n_window):
            bouncing = True
            break
    done = len(states) - 1
    budget_spent, needed, needed_by, stopped_by = False, float(done), {}, {}
    if period:
        blocks = []
        for _ in range(max(1, int(np.ceil(n_window / period)))):
            blocks.append(run.run(run.t + period * tau, record=True))
            if run.outcome != whirl_kernel.OK:
                return failed("in the output window")
        window, recorded = merge(blocks), cycle_values(point, model, blocks)
        looks = []
        for form in strike_force_forms(point, recorded):
            cycles = [form(v) for v in recorded]
            modal = figures_modal_part(point, model, window, cycles, replays)
            stats = settling(cycles, [])
            looks.append((cycles, modal, convergence(point, model, window, window_summary(cycles, stats), stats,
                                                     periodic=True, modal=modal)))
        cycles, modal, _ = min(looks, key=lambda look: look[2]["peak_contact_force"]["total"])
        window_cycles, preceding = list(zip(blocks, cycles)), []
    else:
        # (cycle, its values) per recorded revolution: a stationary bouncing has its window and the stretch before
        # it recorded already (the two stretches :func:`stationary` compared); else the transient's last n_window
        kept = kept if bouncing else kept[-n_window:]
        record: list[tuple[Window | None, dict[str, Any]]] = list(zip(kept, cycle_values(point, model, kept)))
        first = 0  # the record's first revolution
        step = 0 if bouncing else n_window  # revolutions to add before the next look
        while True:
            added = []
            window = None  # the last look's joined copy of the window's recordings: merged again below
            for _ in range(step):
                added.append(run.run(run.t + tau, record=True))
                if run.outcome != whirl_kernel.OK:
                    return failed("in the output window")
                states.append(run.modal_state())
            if added:
                record += zip(added, cycle_values(point, model, added))
                live = record[first:]  # the cycles still recorded: one decision on the correction for them all
                if len({values["correction"] for _, values in live}) > 1:
                    record[first:] = zip([c for c, _ in live], cycle_values(point, model, [c for c, _ in live]))
            half = (len(record) - first) // 2
            ratio = settle_ratio(states, scale)
            # the look, for each peak force the run may state (strike_force_forms): the one stating the smaller error
            # is kept; the window's joined recordings are shared between the looks over the same cycles
            looks, joined = [], {}
            for form in strike_force_forms(point, [v for _, v in record[len(record) - 2 * half:]]):
                preceding = [form(v) for _, v in record[len(record) - 2 * half:len(record) - half]]
                window_cycles = [(c, form(v)) for c, v in record[len(record) - half:]]
                stats = settling([v for _, v in window_cycles], preceding, ratio)
                stationary_record = not np.isfinite(ratio) and not any(s["significant"] for s in stats.values())
                if stationary_record:
                    # the halves agree and nothing settles: the figures are means over the whole record, their window
                    # part its standard error; the halves' drifts are kept as what they were (window_spread)
                    window_cycles = [(c, form(v)) for c, v in record[len(record) - 2 * half:]]
                    whole = settling([v for _, v in window_cycles], [], ratio)
                    stats = {name: dict(whole[name], drift=stats[name]["drift"]) for name in whole}
                    preceding = []
                if len(window_cycles) not in joined:
                    joined[len(window_cycles)] = merge([c for c, _ in window_cycles])
                window = joined[len(window_cycles)]
                cycles = [v for _, v in window_cycles]
                modal = figures_modal_part(point, model, window, cycles, replays)
                errors = convergence(point, model, window, window_summary(cycles, stats), stats, periodic=False,
                                     modal=modal)
                looks.append((preceding, window_cycles, stats, stationary_record, window, cycles, modal, errors))
            preceding, window_cycles, stats, stationary_record, window, cycles, modal, errors = min(
                looks, key=lambda look: look[-1]["peak_contact_force"]["total"])
            del looks, joined
            used = len(states) - 1
            # per figure over its tolerance, the revolutions more its window part is foreseen to need (inf: its modes
            # or integrator part alone is over the tolerance, and more revolutions do not help)
            # (where the modal part is the change between whole runs at N/2 and N modes, the in-run measure's part,
            # which is not the one stated there, does not stop the window: the window grows on its own part)
            wants: dict[str, float] = {}
            for name, e in errors.items():
                limit = figure_tolerance(name, tolerance, exponent, force)
                held = e["total"] - (e["modes"] if doubled else 0.0)  # the error the window's growth answers to
                room = limit - (held - e["window"])  # what the window part may be
                if held <= limit:
                    continue
                if room <= 0:
                    wants[name] = np.inf  # the integrator or the modes take it over: more revolutions do not help
                elif np.isfinite(ratio) and e["window"] > stats[name]["confidence"] * stats[name]["error"]:
                    # settling: drifts shrink by ρ
                    wants[name] = np.log(room / e["window"]) / np.log(ratio) if ratio > 0 else 0.0
                else:  # the standard error falls as the root of the window's length (half the record's if settling)
                    length = len(window_cycles) * (1 if stationary_record else 2)
                    if bouncing and e["window"] > stats[name]["confidence"] * stats[name]["error"]:
                        # a stationary bouncing's halves' drift, not a standard error (its intermittency): no root law
                        # foresees it (it vanishes once the halves agree and the window is the whole record), so one
                        # record's length more and look again (a slide that settles slowly keeps the forecast)
                        wants[name] = float(length)
                    else:  # its bound's t quantile falls too as the window's batches grow
                        wants[name] = revolutions_for(length, len(window_cycles), e["window"], room)
            # the window grows for every figure that can get there within the budget (a forecast within FORECAST_SLACK
            # of it), whatever the others: a figure its modes take over, or whose scatter asks far more than the budget,
            # does not stop the others' growth (issue 36)
            # (with reference_window_growth = "point", the default, the window grows only while every figure over its
            # tolerance can get there: a point that stays over it whatever the window stops at its first look)
            reachable = [m for m in wants.values() if used + m <= FORECAST_SLACK * budget]
            if per_figure or len(reachable) == len(wants):
                more = max(reachable, default=0.0)
            else:
                more = 0.0
            needed = used + max(wants.values(), default=0.0)
            needed_by = {name: float(used + m) for name, m in wants.items()}
            if more == 0.0 or used >= budget:
                budget_spent = bool(wants)
                stopped_by = stop_reasons(needed_by, used, budget)
                break
            # on towards where the figures are foreseen to be within the tolerance, at least a window more and at most
            # the record's length again (a forecast from a short record's scatter is itself rough): few looks; the
            # budget is spent where the forecast is within FORECAST_SLACK of it
            step = int(np.ceil(min(max(more, n_window), max(len(record) - first, n_window), budget - used)))
            if any(s["significant"] for s in stats.values()):
                first = len(record) - half  # still settling: drop the first half
            for i in range(first):
                record[i] = (None, record[i][1])  # free the recordings no longer needed
        done = used - len(window_cycles)
    return dict(model=model, integrator=run, verdict="periodic" if period else "not_periodic", period=period,
                revolutions=done, window=window, cycles=[v for _, v in window_cycles], preceding=preceding,
                budget_spent=budget_spent, revolutions_needed=float(needed), needed_by=needed_by,
                stopped_by=stopped_by, ratio=ratio,
                failure=None, stationary=bouncing, modal=modal, stats=None if period else stats,
                replay=replays.get("replay"))


def figures_modal_part(point: DesignPoint, model: WhirlModel, window: Window, cycles: list[Mapping[str, Any]],
                       replays: dict) -> dict[str, float] | None:
    """The modal part of each figure's error over a window (relative): the in-run measure or the replays'
    (:func:`impact_modal_error`), the peak force's from its strikes' onset speeds where the cycles' force is the
    local model's (:func:`strike_modal_part`), the stresses' with the strikes' local bending
    (:func:`strike_stress_modal_part`)."""
    return strike_stress_modal_part(cycles, strike_modal_part(
        cycles, impact_modal_error(point, model, window, cycles, replays, modal_check)))


def modes_force(values: Mapping[str, Any]) -> dict[str, Any]:
    """A cycle's values (:func:`cycle_values`) with the modes' own peak force (the local model's left out)."""
    return {name: v for name, v in values.items() if name != "local_strikes"}


def local_force(values: Mapping[str, Any]) -> dict[str, Any]:
    """A cycle's values (:func:`cycle_values`, ``reference_strike_force = "smaller"``) with its strikes' peak force
    from their local model (as ``"local"`` states it: ``strikes`` the local model's account of the cycle)."""
    out = modes_force(values)
    found = values.get("local_strikes")
    if found is not None:
        out.update(peak_contact_force=found["peak_contact_force"], strikes=found)
    return out


def strike_force_forms(point: DesignPoint, values: list[Mapping[str, Any]]) -> tuple:
    """The forms of the cycles' ``values`` a run's look weighs (:func:`simulate`): with ``reference_strike_force =
    "smaller"``, where a strike's force came from its local model in one of them, the modes' own peak force and the
    strikes' local model's (:func:`modes_force`, :func:`local_force`), of which the look keeps the one whose error
    (:func:`convergence`, window and modes parts) is the smaller (docs/reference_model.md §2.3); else the values as
    they are."""
    if point.reference.reference_strike_force == "smaller" and any(
            v.get("local_strikes", {}).get("count", 0) > 0 for v in values):
        return modes_force, local_force
    return (modes_force,)


def modal_by_doubling(model: WhirlModel) -> bool:
    """Whether a bouncing run's modal part is the figures' change between whole runs at N/2 and N modes
    (:func:`doubling_modal_error`) rather than the in-run measure (:func:`modal_check`): with the residual vectors
    (``reference_residual = "dynamic"``) and with the strikes' pulses (``reference_strike_force = "pulse"``, whose
    force at a joint is not the series law's that the in-run measure softens; docs/reference_model.md §2.4)."""
    return bool(model.dynamic or model.pulse is not None)


def stop_reasons(needed_by: Mapping[str, float], used: int, budget: int) -> dict[str, str]:
    """Why the window stopped (:func:`simulate`) for each figure left over its tolerance, from the revolutions in all
    foreseen to bring it within (``needed_by``; inf where more would not), the revolutions ``used`` and the
    ``budget``: "modes" (its modes or integrator part alone is over the tolerance), "forecast" (its own forecast
    beyond :data:`FORECAST_SLACK` times the budget), "budget" (the budget spent), "others" (within reach, the window
    stopped by a figure that could not get there: ``reference_window_growth = "point"``), "none" (its forecast asks
    for no more revolutions)."""
    def reason(n: float) -> str:
        if not np.isfinite(n):
            return "modes"
        if n > FORECAST_SLACK * budget:
            return "forecast"
        if n <= used:
            return "none"
        if used >= budget:
            return "budget"
        # within reach and the budget not spent: the window stopped only as another figure could not get there
        return "others" if any(m > FORECAST_SLACK * budget for m in needed_by.values()) else "none"

    return {name: reason(n) for name, n in needed_by.items()}


def stop_message(needed_by: Mapping[str, float], stopped_by: Mapping[str, str], budget: int,
                 labels: Mapping[str, str]) -> str:
    """The message's account of a window stopped over the tolerance: each figure left over it (``labels`` its name)
    and why (:func:`stop_reasons`)."""
    blocking = [labels[name] for name, why in stopped_by.items() if why in ("modes", "forecast")]
    budget_text = f"the budget of {budget} (solver.reference_max_revolutions)"

    def why(name: str, n: float) -> str:
        reason = stopped_by.get(name, "budget")
        if reason == "modes":
            return "more revolutions would not bring it within (its modes or integrator part is over)"
        if reason == "forecast":
            return (f"about {n:.0f} revolutions in all would, beyond {FORECAST_SLACK:g} times {budget_text}: its "
                    f"forecast is out of reach")
        if reason == "others":
            return (f"about {n:.0f} revolutions in all would, within reach of {budget_text}, but the window stopped "
                    f"as {' and '.join(blocking)} could not get there (solver.reference_window_growth = \"point\")")
        if reason == "none":
            return "its forecast asked for no more revolutions"
        return f"about {n:.0f} revolutions in all would, more than {budget_text}, spent"

    return "; ".join(f"{labels[name]}: {why(name, n)}" for name, n in needed_by.items())


def solve(inputs: Mapping[str, Any]) -> PointResult:
    """The ``reference`` method at a point given by its SI inputs (:func:`run` of its :class:`DesignPoint`)."""
    return run(DesignPoint.from_inputs(inputs))


def run(point: DesignPoint) -> PointResult:
    """The ``reference`` method (module docstring) at the typed design point (:data:`study.solvers.METHODS`). Values
    (SI) are listed in ``docs/reference_model.md``.

    The mode count is chosen per point: from ``reference_modes`` it doubles (or grows by the power of two that the
    residual flexibility's N⁻³ foresees) while the modal part of a design figure's error (:func:`modal_check`) is over
    half the study's tolerance and the count is within ``reference_max_modes``; the last run is the answer
    (``extras["reference_modes"]``), the counts tried and their figures in ``extras["modes_tried"]``
    (docs/reference_model.md §3.1)."""
    option = point.reference
    count, top = int(option.reference_modes), max(int(option.reference_modes), int(option.reference_max_modes))
    tried = []
    previous = None
    while True:
        result = solve_with_modes(point.with_reference(reference_modes=count), previous)
        # with the residual vectors, or the strikes' pulses (§2.4), the modal part is the figures' change from half
        # the modes: as the run's model took it (:func:`modal_by_doubling`; the options alone may ask for a law the
        # model could not keep, e.g. the vectors at contact points not symmetric about the middle)
        dynamic = bool(result.extras.get("modal_by_doubling"))
        parts = result.extras.get("convergence") or {}
        modal = modal_part(result)
        tried.append(dict(modes=count, modal=modal, error_estimate=float(result.error_estimate or 0.0),
                          **{name: float(result.values.get(name, np.nan)) for name in FIGURES},
                          window={name: float(e["window"]) for name, e in parts.items()}))
        # the gate's tolerance of the point: the statistical one where its figures are means over a motion that does
        # not repeat (with the residual vectors; the static law keeps the study's)
        replayed = result.extras.get("replay")
        tolerance = (point.tolerances.statistical if (dynamic or replayed) and result.values.get("statistical_figures")
                     else point.tolerances.tolerance)
        # a first run whose modal part is to be measured by doubling has only the in-run measure (not its part: the
        # pulse's force is not the series law's), so a bouncing one goes on to twice the modes whatever it says
        unmeasured = dynamic and previous is None and bool(result.values.get("statistical_figures"))
        if result.status != "ok" or (modal <= 0.5 * tolerance and not unmeasured) or 2 * count > top:
            break
        if replayed:
            # the count chosen by the strikes replayed from this run (docs/reference_model.md §2.2): the fewest modes
            # whose stated part (from the replays at it and more) is within half the tolerance, else the most
            later = [n for n in replayed["stated"] if count < n < top
                     and max(replayed["stated"][n][name] for name in FIGURES) <= 0.5 * tolerance]
            count = min(later) if later else count * 2 ** int(np.log2(top // count))
            previous = result
            continue
        # the next count: doubled, or more where the modal part is far over (the residual flexibility falls like N⁻³,
        # so a part m asks about (m / (tolerance/2))^(1/3) times the modes): a choice of the count only, the part
        # stated is the one measured with it. With the residual vectors doubled: their modal part is measured
        # between a count and its half (:func:`doubling_modal_error`)
        factor = 2 if dynamic else 2 ** max(1, int(np.ceil(np.log2(max(modal / (0.5 * tolerance), 1.0)) / 3.0)))
        while count * factor > top:
            factor //= 2
        count *= factor
        previous = result
    result.extras["modes_tried"] = tried
    result.final_state = None  # (a model: not handed on)
    if len(tried) > 1:
        result.message += (f"; modes doubled from {tried[0]['modes']} to {count} (the modal part "
                           + ", ".join(f"{t['modes']}: {t['modal']:.2%}" for t in tried) + ")")
    return result


def pulse_summary(model: WhirlModel, integrator) -> dict[str, float]:
    """The strikes' pulses of a run (``reference_strike_force = "pulse"``, docs/reference_model.md §2.4): pulses
    applied, restrikes (pulses that ended with the joint still towards its wall, the contact law taking it on), the
    steps in contact and in all, and the largest wall shift at a pulse's end [m], over the joints' clearance and over
    the Hertz approach at its pulse's peak; per pulse, the scale λ that matches its work to the local strike's
    (``mean_scale``: applied with ``reference_pulse_work = "matched"``), the work [J] the tabulated pulse would do
    on the modes, predicted at its onset (``mean_table_work``), the local strike's net work (``mean_local_work``),
    and the work the pulse applied did on the modes (``mean_work_done``); nan where no pulse."""
    state, work = integrator.pulse, integrator.work
    joints = model.kinds == 1
    scaled = float(np.sum(state[:, pulse.P_SCALE_COUNT]))
    return dict(pulses=float(work[whirl_kernel.S_PULSES]), restrikes=float(work[whirl_kernel.S_RESTRIKES]),
                mean_scale=float(np.sum(state[:, pulse.P_SCALE_SUM]) / scaled) if scaled > 0 else float("nan"),
                mean_table_work=(float(np.sum(state[:, pulse.P_WORK_TABLE]) / scaled) if scaled > 0
                                 else float("nan")),
                mean_local_work=(float(np.sum(state[:, pulse.P_WORK_LOCAL]) / scaled) if scaled > 0
                                 else float("nan")),
                mean_work_done=(float(np.sum(state[:, pulse.P_WORK_DONE])
                                      / np.sum(state[:, pulse.P_PULSES]))
                                if np.sum(state[:, pulse.P_PULSES]) > 0 else float("nan")),
                contact_steps=float(work[whirl_kernel.S_CONTACT_STEPS]), steps=float(work[whirl_kernel.S_ACCEPTED]),
                largest_shift=float(np.max(state[joints, whirl_kernel.P_SHIFT_MAX], initial=0.0)),
                largest_shift_clearance=float(np.max(state[joints, whirl_kernel.P_SHIFT_MAX]
                                                     / model.clearance[joints], initial=0.0)),
                largest_shift_approach=float(np.max(state[joints, whirl_kernel.P_OVERLAP], initial=0.0)))


def modal_part(result: PointResult) -> float:
    """The largest modal part of a run's figures' errors (``extras["convergence"]``; 0 where none is stated): what
    decides whether the point goes on to more modes (:func:`solve`, :func:`solve_with_modes`)."""
    parts = result.extras.get("convergence") or {}
    return max((float(e["modes"]) for e in parts.values()), default=0.0)


def doubling_modal_error(previous: PointResult, values: Mapping[str, Any]) -> dict[str, float]:
    """The modal part of each figure's error (relative) at N modes with the residual vectors or the strikes' pulses,
    from the run at N/2 (``previous``): the figures' change between the two, relative to the figure at N (the
    alternating stress's to the larger of it and the max bending stress, as :func:`convergence` counts it). It is the
    error left at N if that falls at least as fast as 1/N, and its statistical part (the two windows' scatter) is not
    taken out: at the bouncing points measured the figures did not change monotonically from 8 to 128 modes
    (docs/reference_model.md §2.1), and with the strikes' pulses the stresses changed more from 64 to 128 modes than
    from 32 to 64; taking the windows' scatter out of the change covered fewer of the 128-mode answers still (§3.1)."""
    out = dict.fromkeys(MODAL_FIGURES, 0.0)
    for name in MODAL_FIGURES:
        now, then = float(values.get(name, np.nan)), float(previous.values.get(name, np.nan))
        if not (np.isfinite(now) and np.isfinite(then)) or now <= 0:
            continue
        size = max(now, float(values.get("max_bending_stress", now))) if name == "alternating_bending_stress" else now
        out[name] = float(abs(now - then) / size)
    return out


def start_integrator(model: WhirlModel, option, start: Mapping[str, Any] | None = None) -> Integrator:
    """The integrator a run starts with: at ``reference_initial``'s state (which also finds the wall's rest the
    lift-off is measured from), or at ``start`` (:func:`continued_state`) with its contacts open as they were and the
    step size it had, where the contact points are the same."""
    rest = initial_state(model, option.reference_initial)
    run = Integrator(model, float(option.reference_rtol), rest if start is None else start["state"],
                     option.reference_integrator)
    if start is not None and start["active"] is not None:
        run.active[:], run.chi[:], run.h = start["active"], start["chi"], start["step"]
    return run


def end_state(run: Integrator, window: Window | None) -> dict[str, Any]:
    """Where a run ended (:func:`continued_state` starts the run at more modes from it): its model, the modal state
    (4N,), each contact point's open contact and Hunt–Crossley factor, the step size, and the contact forces (P, 3)
    where the window's last row is the run's end (else None)."""
    at_end = (window is not None and window.times.size
              and abs(window.times[-1] - run.t) <= 1e-9 * max(run.model.period, abs(run.t)))
    return dict(model=run.model, state=run.modal_state(), active=run.active.copy(), chi=run.chi.copy(), step=run.h,
                forces=window.forces[-1].copy() if at_end else None)


def continued_state(previous: PointResult | None, model: WhirlModel) -> dict[str, Any] | None:
    """Where a run at more modes starts (:func:`simulate`'s ``start``): where the run at fewer (``previous``) ended, at
    a revolution boundary, where the rotating loads' phase is the start's. Its modes as they were and the ones added at
    their static response to the contact forces and the joints' weight then (:func:`replay.lift_state`; without the
    forces at the end, to the weight alone); its power integrals from nil; its contacts open as they were (each one's
    Hunt–Crossley factor of its onset speed) and its step size, where the contact points are the same (active and
    chi None where not). None where there is no such run (then ``reference_initial``'s start).

    Why: the start-up of a bouncing pipe from its rest on the wall rings down over some 20-40 revolutions
    (docs/reference_model.md §3.1), longer than the stationarity test can tell from two 6-revolution stretches of a
    chaotic motion; the run at more modes goes on from where the one before left the motion instead of starting it
    again."""
    end = getattr(previous, "final_state", None)
    if end is None or end["model"].n_modes > model.n_modes:
        return None
    small = end["model"]
    same = small.points.size == model.points.size and np.allclose(small.points, model.points)
    state = lift_state(small, model, np.concatenate((end["state"], np.zeros(4))), end["forces"] if same else None)
    return dict(state=state, active=end["active"] if same else None, chi=end["chi"] if same else None,
                step=end["step"], modes=small.n_modes)


def solve_with_modes(point: DesignPoint | Mapping[str, Any], previous: PointResult | None = None) -> PointResult:
    """The ``reference`` method with the inputs' ``reference_modes`` (:func:`solve` chooses the count): one run
    (:func:`solve_with_stations`), run again with the body's contact stations raised k -> 2k + 1 (the stations kept, one
    more between each pair) while the body passes its wall between them (``max_wall_excess``, a bound along the whole
    body, docs/reference_model.md §2) by more than the study's tolerance of its clearance — the gate's test — up to
    ``reference_max_body_stations``, at a mode count whose modal part does not send the point to more modes anyway; the
    count of the answer in ``extras["reference_body_stations"]``, the counts tried, their excess and wall times in
    ``extras["body_stations_tried"]``. Contact points given in code (``contact_points``) are kept. With the residual
    vectors and the run at half the modes (``previous``) the modal part of the errors is measured between the two
    (:func:`doubling_modal_error`) where the motion does not repeat."""
    point = DesignPoint.of(point)
    option = point.reference
    count = int(option.reference_body_stations)
    top = max(count, int(option.reference_max_body_stations))
    tolerance = point.tolerances.tolerance
    more_modes = 2 * int(option.reference_modes) <= int(option.reference_max_modes)
    tried = []
    while True:
        result = solve_with_stations(point.with_reference(reference_body_stations=count), previous)
        excess, clearance = result.values.get("max_wall_excess"), result.values.get("clearance")
        passed = (excess is not None and clearance is not None and np.isfinite(excess)
                  and excess > tolerance * clearance)
        tried.append(dict(stations=count, max_wall_excess=float(excess) if excess is not None else np.nan))
        # a run whose modes left out take a figure over half the tolerance is run again with more modes (solve), which
        # raise their own stations: its stations are not raised
        modal = modal_part(result)
        if (result.status != "ok" or not passed or 2 * count + 1 > top or option.contact_points is not None
                or (more_modes and modal > 0.5 * tolerance)):
            break
        count = 2 * count + 1
    result.extras["reference_body_stations"] = count
    result.extras["body_stations_tried"] = tried
    if len(tried) > 1:
        result.message += (f"; body stations raised from {tried[0]['stations']} to {count} (the body past its wall by "
                           + ", ".join(f"{t['stations']}: {t['max_wall_excess'] / clearance:.2%} c" for t in tried)
                           + ")")
    return result


def solve_with_stations(point: DesignPoint, previous: PointResult | None = None) -> PointResult:
    """One run of the ``reference`` method with the inputs' ``reference_modes`` and ``reference_body_stations``; with
    the residual vectors and the run at half the modes (``previous``) the modal part of the errors is measured between
    the two (:func:`doubling_modal_error`)."""
    result = PointResult(method=METHOD)
    model = build_model(point)
    vals = result.values
    vals.update(model.props)  # the section's properties, as every method of the hierarchy reports them
    vals.update(span_length=model.span, first_natural_frequency=model.omega[0] / (2 * np.pi)
                if np.isfinite(model.omega[0]) else np.nan, clearance=float(np.max(model.clearance)))
    if not np.all(np.isfinite(model.omega)):
        result.status = "buckled"
        result.message = (f"effective tension {model.props['effective_tension']:.4g} N buckles the "
                          f"{model.span:.4g} m section")
        return result
    start = continued_state(previous, model)
    run = simulate(point, model, start)
    if run["verdict"] != "failed":  # where the next count's run starts (solve; not an output)
        result.final_state = end_state(run["integrator"], run["window"])
    # the lift-off eccentricity is computed about the rest the run started from (sliding.add_lift_off)
    result.rest_model = model if "sliding_rest" in model.cache else None
    result.extras.update(contact_points=[float(v) for v in model.points], contact_kinds=[int(v) for v in model.kinds],
                         reference_modes=model.n_modes,
                         reference_residual=(point.reference.reference_residual if model.dynamic else "series"
                                             if np.any(model.flexibility > 0) else "none"),
                         reference_residual_vectors=model.ritz["count"] if model.dynamic else 0,
                         modal_by_doubling=modal_by_doubling(model),
                         continued_from_modes=None if start is None else start["modes"])
    if run["verdict"] == "failed":
        result.status = "failed"
        result.message = f"integration failed: {run['failure']}"
        return result
    window, cycles = run["window"], run["cycles"]
    tau = model.period
    revs = (window.end - window.start) / tau
    periodic = bool(run["period"])
    vals.update(revolutions_simulated=float(run["revolutions"] + revs), window_revolutions=float(revs),
                impacts_per_revolution=float(np.sum(window.onsets) / revs),
                contact_fraction=float(window.any_contact_time / (window.end - window.start)),
                eccentricity=model.eccentricity)
    if run["period"]:
        vals["period_revolutions"] = float(run["period"])
    measure = whirl_measure(model, window)
    vals.update(whirl_frequency_ratio=measure["whirl_frequency_ratio"],
                whirl_class=float(WHIRL_CLASSES[measure["whirl"]]),
                regime=float(REGIMES[WHIRL_REGIMES[measure["whirl"]]]))
    spacing, touching = contact_spacing(model, window)
    vals["contact_spacing"] = spacing
    # the largest Hertz approach of a contact on the body (the gate holds the largest deflection, on the body, to the
    # body's clearance plus it): its peak force's (F/K)^(2/3), or the penalty's F/k
    body = model.kinds == 0
    if np.any(body):
        peak = window.peak[body]
        approach = ((peak / model.stiffness[body]) ** (2.0 / 3.0) if model.law == 0
                    else peak / model.penalty_stiffness[body])
        vals["max_approach"] = float(np.max(approach))
    stats = run.get("stats") or settling(cycles, run["preceding"], run.get("ratio", np.nan))
    summary = window_summary(cycles, stats)
    budget = energy_balance(model, window)
    modal = run["modal"]
    replayed = run.get("replay") if (run.get("replay") or {}).get("impacts") else None
    if (modal_by_doubling(model) and previous is not None and not periodic
            and previous.status == "ok" and replayed is None
            and previous.extras.get("reference_modes") == model.n_modes // 2):
        modal = doubling_modal_error(previous, summary)
    errors = convergence(point, model, window, summary, stats, periodic, residual=budget["residual"], modal=modal)
    correction = summary.pop("correction")
    quarter = summary.pop("modal_quarter_fraction")
    damage = summary.pop(DAMAGE)  # the worst fibre's mean damage per cycle
    vals.update(summary, window_spread=stats["peak_contact_force"]["drift"])
    # the damage rate counted by rainflow (add_limits keeps it and gives its fatigue life), its error the life's
    vals.update(damage_rate=float(damage * len(cycles) / (window.end - window.start)),
                fatigue_life_error=errors[DAMAGE]["total"], statistical_figures=float(not periodic),
                **{f"{name}_error": errors[name]["total"] for name in FIGURES})
    result.error_estimate = float(max(e["equivalent"] for e in errors.values()))
    # whose peak force the figures carry: the strikes' local model's (reference_strike_force "local", or "smaller"
    # where it stated the smaller error) or the modes' own
    struck = int(sum(c.get("strikes", {}).get("count", 0) for c in cycles))
    vals["local_strike_force"] = float(struck > 0)
    result.extras.update(whirl=measure["whirl"], whirl_point=measure["whirl_point"], touching_points=touching,
                         local_strikes=struck,
                         energy_budget=budget, steps=run["integrator"].steps,
                         **({"strike_pulses": pulse_summary(model, run["integrator"])} if model.pulse is not None
                            else {}),
                         quasi_static_correction=correction,
                         revolutions_needed=float(run.get("revolutions_needed", np.nan)),
                         modal_quarter_fraction=quarter,
                         revolutions_needed_by_figure=dict(run.get("needed_by") or {}),
                         window_stopped_by=dict(run.get("stopped_by") or {}),
                         modal_error={name: float(v) for name, v in (modal or {}).items()},
                         replay=None if replayed is None else replay_summary(replayed),
                         convergence={name: {**e, "drift": stats[name]["drift"], "standard_error": stats[name]["error"]}
                                      for name, e in errors.items()})
    option = point.reference
    cycle = f"{run['period']} revolution(s)" if periodic else "revolution"
    needed = run.get("revolutions_needed", np.nan)
    names = {**{name: label for name, (_, label) in FIGURES.items()}, DAMAGE: "fatigue damage rate"}
    stopped = ""
    if run["budget_spent"]:
        # each figure left over its tolerance, and why: the window grew for the others all the same
        why = stop_message(run.get("needed_by") or {}, run.get("stopped_by") or {},
                           int(option.reference_max_revolutions), names)
        stopped = "; over the tolerance where the window stopped: " + (
            why or f"about {needed:.0f} revolutions in all would bring them within")
    figures = ", ".join(f"{names[name]} {e['total']:.2%} (mostly {e['dominant']}: window {e['window']:.2%}, "
                        f"integrator {e['integrator']:.1e}, "
                        f"modes {e['modes']:.2%})"
                        for name, e in errors.items())
    least, longest = transient_bounds(option, start)
    messages = [f"whirl {measure['whirl']} ({measure['whirl_frequency_ratio']:+.3f} Omega)",
                (f"periodic every {run['period']} revolution(s) after {run['revolutions']}" if periodic else
                 f"bouncing with stationary statistics after {run['revolutions']} revolutions (transient ended)"
                 if run.get("stationary") and run["revolutions"] < longest else
                 f"not periodic within {run['revolutions']} revolutions")
                + (f" (started where the {start['modes']}-mode run ended)" if start is not None else
                   f" (none of the first {least} revolutions in the window: solver.reference_min_revolutions)"
                   if least else ""),
                f"figures: means over the window's {len(cycles)} cycle(s) of {cycle} of each cycle's largest value"
                f" (largest seen: window_largest_*){stopped}",
                f"window {revs:g} revolutions; {model.n_modes} modes per direction, rtol "
                f"{float(option.reference_rtol):g}"
                f"""{' and the residual flexibility and quasi-static correction of the modes left out'
                     if correction else ''}"""
                f" (modal error of the largest deflection {(modal or {}).get('max_deflection', 0.0):.2%})"
                + (f"; modal parts from {len(replayed['impacts'])} strike(s) replayed at "
                   + ", ".join(str(n) for n in replayed["counts"]) + " modes" if replayed else ""),
                f"error of each figure (its largest part): {figures}"
                + (f"; the peak force from {struck} strike(s)' local model (docs/reference_model.md §2.3)"
                   if struck else ""),
                (f"held to solver.statistical_tolerance {point.tolerances.statistical:.3g} (means over the revolutions"
                 f" of a motion that does not repeat; the damage rate to (1 + it)^m - 1)" if not periodic else
                 f"held to solver.tolerance {point.tolerances.tolerance:.3g}")
                + f", the peak force to solver.force_tolerance {point.tolerances.force:.3g}"]
    # clear of the wall is an answer too (the free whirl), so it is ok: the regime says which; an error above the
    # study's tolerance makes the gate call it not_converged
    result.status = "ok"
    result.message = "; ".join(messages)
    return result
