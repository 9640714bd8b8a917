"""The periodic impact solution of one design point: closure, span search and constraint checks.

Shared by the periodic methods (``fast`` and ``series``; ``docs/model.md`` §3–6). The sample span
(simply supported, length L) is struck at midspan by the Hertz/Lee pulse of the equivalent mass once
per period at the wall y = +c (pattern ``one_wall``) or alternately at +c and −c every half period
(``alternating``). The response is linear in the impulse J, so everything is built from the response
to a unit impulse directed along +y; the real load pushes the pipe off the wall (−y at +c).

Unknowns and closures (docs/model.md §4). Condition 2, y(L/2, 0) = c, is one equation; the unknowns are L
and the impact velocity V_p:

- ``prescribed``: V_p = Ω c (the paper's assumed motion), J = m_e (1 + e) V_p; condition 2 is an
  equation for L: F(L) = −J y₁(L)/c − 1 = 0, where y₁ is midspan displacement at t = 0 per unit
  impulse along +y.
- ``self_consistent``: V_p is the solution's own midspan velocity just before contact. Condition 2
  fixes J = −c/y₁, so V_p = c v₁/y₁, and J = m_e (1 + e) V_p becomes F(L) = m_e (1 + e) V_p/J − 1 = 0.

Either way the pulse duration T_L depends (weakly) on V_p, m_e and the Hertz stiffness, which depends
on the curvature of the pipe at the contact, taken from the solution itself: κ = −y''(L/2, 0). They are
iterated to a fixed point at every span evaluated exactly.

The exact model at a span (the span's modes and resonances, the fixed point, the impact) is
:mod:`study.solvers.kernels.impact`; the span search, :mod:`study.solvers.methods.periodic.span_search`;
this module checks the constraints, picks the span and runs the design-point pipeline shared by the periodic methods.

Span search. F(L) has a pole wherever a natural frequency ω_n(L) meets a harmonic of the pulse train
(docs/model.md §4): a sign change across a pole is not a root. The poles are located analytically
(:func:`resonant_spans`), F times the distances to the interval's two poles is sampled inside every
interval between consecutive poles (its values at the poles follow from their residues), and only sign
changes inside one interval are bracketed and solved. Roots are then refined with the
exact model and kept as candidates when condition 1 holds: |y| < c everywhere and always except at
the contact during the pulse, and the midspan arrives at the wall moving towards it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Mapping

import numpy as np

from study.physics import beam, section
from study.solvers.kernels.impact import (PROBLEMS, ROWS, Impact, impacts_of,
                                                         odd_modes, refine_root, refined_rows, span_search_too_large)
from study.solvers.model.options import Options
from study.solvers.model.point import DesignPoint
from study.solvers.model.result import PointResult
from study.solvers.model.scene import Scene, make_scene
from study.solvers.methods.periodic.span_search import (SpanSearch, find_roots, midspan_screen, midspan_weights,
                                                        roots_between, search_intervals)


def truncation_bound(scene: Scene, impact: Impact, options: Options, reach: int = 8) -> float:
    """Upper bound [Pa] on the bending stress carried by the modes left out, n in (N, reach·N].

    Each left-out mode adds at most (r_o/I) EI k_n² |a_n(t) − a_n,qs(t)| to the stress anywhere on the
    span (|sin k_n x| ≤ 1), where a_n − a_n,qs is its dynamic remainder after the quasi-static split
    (docs/model.md §5); its maximum over the period is taken on the solver's time grid. Summing the modes
    up to reach·N catches a near-resonant mode just above the truncation, which a comparison with
    fewer modes cannot see; the modes beyond fall off like n⁻⁴ once ω_n T_L ≫ 1.
    """
    p = scene.props
    r_o, r_i = scene.outer_radius, scene.inner_radius
    inertia = float(section.second_moment_of_area(r_o, r_i))
    n = odd_modes(reach * options.modes)
    n = n[n > options.modes]
    if n.size == 0:
        return 0.0
    t = time_grid(scene, impact.contact_duration, options)
    omega = scene.natural_frequencies(impact.span_length, n)
    g = beam.modal_load_factors(n, impact.span_length, impact.contact_half_length, options.load_shape)
    remainder = np.nanmax(np.abs(beam.dynamic_remainder(t, omega, impact.contact_duration, scene.period,
                                                        scene.pattern)), axis=0)
    k_sq = (n * np.pi / impact.span_length) ** 2
    amplitude = abs(impact.impulse) * np.abs(g) / (0.5 * p["mass_per_length"] * impact.span_length) * remainder
    return float(r_o / inertia * p["bending_stiffness"] * np.sum(k_sq * amplitude))


def first_consistent_root(scene: Scene, options: Options, longer_than: float = 0.0) -> Impact | None:
    """The shortest refined root of condition 2 above ``longer_than`` [m] whose T_L–curvature fixed
    point holds (condition 1 not checked): a fixed span and impact for comparing methods at, where a
    design point has no valid span. None when there is none."""
    search = find_roots(scene, options)
    for root, bracket in zip(search.roots, search.brackets):
        if root <= longer_than:
            continue
        impact = refine_root(scene, options, float(root), bracket)
        if not impact.problems and impact.span_length > longer_than:
            return impact
    return None


def time_grid(scene: Scene, duration: float, options: Options) -> np.ndarray:
    """Times over one period (half a period for alternating: the other half is its mirror image), dense
    across the pulse [0, T_L] and uniform after it, ending just before the next impact."""
    pulse = np.linspace(0.0, duration, options.pulse_points)
    return np.unique(np.concatenate([pulse, _times_after_pulse(scene, [duration], options)[0]]))


def space_grid(span_length: float, half_length: float, options: Options) -> np.ndarray:
    """Points over the half span [0, L/2] (the motion is symmetric), dense across the contact."""
    mid = 0.5 * span_length
    coarse = np.linspace(0.0, mid, options.space_points)
    contact = mid - np.linspace(0.0, max(half_length, 1e-3 * span_length) * 1.5, 16)
    return np.unique(np.concatenate([coarse, contact[contact >= 0]]))


def constraint_violations(scene: Scene, impacts: list[Impact], options: Options) -> list[str | None]:
    """Per impact, None when condition 1 holds for its span; otherwise a message saying where it fails.

    The midspan first, every impact at once (most violations show there): after the pulse — during it
    the midspan is in contact — the deflection is the modal sum of :func:`beam.largest_excursion`, in
    one compiled pass over the times of :func:`time_grid` that stops at each impact's first time past
    the wall (the time reported). Then the whole span × period grid for those that pass there.
    """
    problems: list[str | None] = [None] * len(impacts)
    rows = []
    for k, impact in enumerate(impacts):
        if impact.impact_velocity <= 0:
            problems[k] = ("the midspan moves away from the wall when contact starts "
                           f"(V_p = {impact.impact_velocity:.3g} m/s)")
        else:
            rows.append(k)
    if not rows:
        return problems
    spans, durations, halves, impulses = (np.array([getattr(impacts[k], name) for k in rows]) for name in
                                          ("span_length", "contact_duration", "contact_half_length", "impulse"))
    times = _times_after_pulse(scene, durations, options)
    times = np.where(times > durations[:, None], times, times[:, -1:])  # the midspan is in contact before
    omega, weight = midspan_weights(scene, spans, halves, options)
    bound = scene.clearance * (1.0 + options.tolerance)
    limit = bound / np.abs(impulses)
    largest, where = beam.largest_excursion(times, omega, durations, weight, scene.period, scene.pattern,
                                            limit=limit, where=True)
    for row, k in enumerate(rows):
        if not np.isfinite(largest[row]):
            problems[k] = "the deflection is not finite (resonance)"
        elif largest[row] > limit[row]:
            problems[k] = (f"|y| reaches {largest[row] / limit[row] * bound / scene.clearance:.4g} c at "
                           f"x = {0.5 * spans[row]:.4g} m, t = {times[row, where[row]]:.4g} s (condition 1)")
        else:
            impact = impacts[k]
            problems[k] = _excess(scene, impact, options,
                                  space_grid(impact.span_length, impact.contact_half_length, options),
                                  time_grid(scene, impact.contact_duration, options))
    return problems


def _times_after_pulse(scene: Scene, durations, options: Options) -> np.ndarray:
    """(pulses, times) [s]: the times of :func:`time_grid` after the pulse for each T_L of ``durations``,
    ascending: uniform up to the next impact, then denser on the approach to it (a tail time can fall
    inside a pulse longer than half the interval)."""
    durations = np.asarray(durations, dtype=float)
    span = scene.impact_interval
    rest = np.linspace(durations, span, options.time_points + 1, axis=-1)[:, 1:-1]
    tail = span - np.geomspace(durations * 1e-3, durations, 8, axis=-1)  # the approach to the next impact
    return np.sort(np.concatenate([rest, tail], axis=1), axis=1)


def _excess(scene: Scene, impact: Impact, options: Options, x, t) -> str | None:
    """Where |y| exceeds the clearance on the grid x × t outside the contact (None: nowhere)."""
    p = scene.props
    y = beam.deflection(x, t, impact.span_length, p["bending_stiffness"], p["effective_tension"],
                        p["mass_per_length"], -impact.impulse, impact.contact_duration, scene.period,
                        scene.pattern, impact.contact_half_length, options.load_shape, options.modes)
    in_contact = (np.abs(x - 0.5 * impact.span_length) <= max(impact.contact_half_length, 1e-9))[None, :] \
        & (t <= impact.contact_duration)[:, None]
    excess = np.where(in_contact, 0.0, np.abs(y)) - scene.clearance * (1.0 + options.tolerance)
    if not np.all(np.isfinite(y)):
        return "the deflection is not finite (resonance)"
    if np.max(excess) > 0:
        i, j = np.unravel_index(np.argmax(excess), excess.shape)
        return (f"|y| reaches {abs(y[i, j]) / scene.clearance:.4g} c at x = {x[j]:.4g} m, "
                f"t = {t[i]:.4g} s (condition 1)")
    return None


# --- the design-point pipeline shared by the periodic methods ------------------------------------
def options_from(inputs: Mapping[str, Any]) -> Options:
    """Solver settings from the point's inputs (the declared defaults where the config leaves them out)."""
    return Options.from_inputs(inputs)


@dataclass
class SpanChoice:
    """Outcome of the span search of one design point ."""

    search: SpanSearch  #: the roots found in the searched part of the range, [min_span, ``searched_to``]
    survivors: np.ndarray
    candidates: list  #: refined impacts satisfying every constraint, ascending span
    reasons: dict  #: short reason → roots rejected for it
    summary: str
    options: Options  #: the options used (max_span capped below buckling)
    searched_to: float = np.nan  #: the upper end [m] of the part of the range searched (max_span: all of it)


#: Intervals between wide poles in the first run of :func:`find_span`'s search when it stops at the first valid
#: span; each later run is twice as long as the one before (so a search that finds nothing takes a few runs).
FIRST_RUN = 1024


def find_span(scene: Scene, options: Options, first: bool = False) -> SpanChoice:
    """Span search, midspan screen, exact refinement and condition 1 (all from :mod:`periodic`).

    ``options.max_span`` is used as given (cap it below buckling first, see :func:`design_point`). With
    ``first`` the intervals between wide poles are taken in ascending runs (:data:`FIRST_RUN`, then doubling),
    each searched, screened, refined and checked whole, and the search stops after the run in which a span first
    satisfies every constraint: each root's outcome depends on its own interval alone and a refined root stays
    in its interval, so the smallest valid span is the one the whole search finds, while the roots, rejections
    and valid spans counted are those of [min_span, ``searched_to``] only.
    """
    intervals = search_intervals(scene, options)
    runs, candidates, reasons, start, size = [], [], {}, 0, FIRST_RUN
    while True:
        stop = intervals.lo.size if not first else min(start + size, intervals.lo.size)
        search = roots_between(intervals, start, stop, options)
        screened = midspan_screen(scene, options, search)
        survivors = search.roots[screened]
        durations, halves = search.residual.pulse(survivors) if survivors.size else ([], [])
        rows = refined_rows(scene, options, survivors, search.brackets[screened], durations=durations,
                            halves=halves)
        codes, values = rows[ROWS.index("problem")], rows[ROWS.index("value")]
        sound = impacts_of(scene, rows[:, codes == 0])  # records of the roots refined without a problem
        violations = zip(sound, constraint_violations(scene, sound, options))
        for root, code, value in zip(survivors, codes, values):
            impact, problem = next(violations) if code == 0 else (None, PROBLEMS[int(code)](value))
            if problem is None:
                candidates.append(impact)
            else:
                reasons.setdefault(rejection_kind(problem), []).append(root)
        runs.append((search, survivors))
        start, size = stop, 2 * size
        if start >= intervals.lo.size or candidates:
            break
    searched_to = float(intervals.hi[start - 1]) if 0 < start < intervals.lo.size else options.max_span
    search = SpanSearch(np.concatenate([r.roots for r, _ in runs]), np.concatenate([r.brackets for r, _ in runs]),
                        runs[0][0].pole_count, intervals.residual, intervals.narrow_count,
                        np.concatenate([r.states for r, _ in runs], axis=1))
    survivors = np.concatenate([s for _, s in runs])
    candidates = distinct_spans(candidates)
    poles, narrow = search.pole_count - search.narrow_count, (f"{search.narrow_count} resonances narrower than "
                                                               f"{options.resonance_width:.2g} L not searched")
    if searched_to >= options.max_span:
        summary = (f"{search.roots.size} roots of condition 2 between {poles} poles in [{options.min_span:.4g}, "
                   f"{options.max_span:.4g}] m ({narrow})")
    else:
        summary = (f"{search.roots.size} roots of condition 2 in [{options.min_span:.4g}, {searched_to:.4g}] m, where "
                   f"the search stopped past the first valid span ({poles} poles in [{options.min_span:.4g}, "
                   f"{options.max_span:.4g}] m, {narrow})")
    summary += f"; {survivors.size} pass the midspan screen"
    return SpanChoice(search, survivors, candidates, reasons, summary, options, searched_to)


#: Relative distance below which two refined spans are one root (reached from two brackets' screening roots).
SAME_SPAN_RTOL = 1e-9


def distinct_spans(impacts: list) -> list:
    """The impacts in ascending span with each root once: a span within :data:`SAME_SPAN_RTOL` of the one
    kept before it is the same root, refined from two screening roots."""
    out = []
    for impact in sorted(impacts, key=lambda i: i.span_length):
        if not out or impact.span_length > out[-1].span_length * (1.0 + SAME_SPAN_RTOL):
            out.append(impact)
    return out


def doubled(options: Options) -> Options:
    """The same settings with the modes doubled (41 -> 81: every odd mode up to twice the highest)."""
    return Options(**{**options.__dict__, "modes": 2 * options.modes - 1})


def span_survives_doubling(scene: Scene, options: Options, span_length: float, tolerance: float) -> str | None:
    """None when a span satisfying every constraint lies within ``tolerance`` (relative) of ``span_length`` [m]
    with the modes doubled (:func:`doubled`); otherwise why not. A span that is an artefact of the
    truncation — a root pinned by a mode just below it, or one whose condition 1 a higher mode breaks —
    does not survive (docs/model.md §9: a span must converge with the modes like every other output)."""
    finer = doubled(options)
    window = Options(**{**finer.__dict__, "min_span": span_length * (1.0 - 2.0 * tolerance),
                        "max_span": span_length * (1.0 + 2.0 * tolerance)})
    found = find_span(scene, window)
    near = [c.span_length for c in found.candidates if abs(c.span_length - span_length) <= tolerance * span_length]
    if near:
        return None
    why = "; ".join(f"{len(v)} x {k}" for k, v in found.reasons.items()) or "no root of condition 2 near it"
    return (f"the span {span_length:.6g} m does not survive doubling the modes to {finer.modes}: no valid span "
            f"within {tolerance:.2g} of it ({why})")


def rejection_kind(problem: str) -> str:
    """The kind of a rejection, for counting: the message without where and by how much."""
    if problem.startswith("|y| reaches"):
        return "the pipe reaches past a wall elsewhere (condition 1)"
    if problem.startswith("condition 2 residual"):
        return "condition 2 not met after refinement"
    return problem.split(" at ")[0].split(" (")[0]


Finish = Callable[[Scene, Impact, Mapping[str, Any], Options, PointResult], None]


def design_point(point: DesignPoint, method: str, finish: Finish) -> PointResult:
    """The design-point pipeline shared by the periodic methods: buckling check, :func:`find_span` with the point's
    :attr:`~DesignPoint.periodic` options, the smallest valid span's impact in ``result.values``; then
    ``finish(scene, chosen, inputs, options, result)`` adds the method's fields, stresses and error estimate."""
    result = PointResult(method=method)
    options, scene, inputs = point.periodic, point.scene, point.inputs
    result.values.update(scene.props)
    max_span = min(options.max_span, scene.props["buckling_length"] * (1 - 1e-9))
    if max_span <= options.min_span:
        result.status = "buckled"
        result.message = (f"effective tension {scene.props['effective_tension']:.4g} N buckles every span "
                          f"longer than {scene.props['buckling_length']:.4g} m, below the shortest searched")
        return result
    options = Options(**{**options.__dict__, "max_span": max_span})
    too_many = span_search_too_large(scene, options)
    if too_many is not None:
        result.status = "failed"
        result.message = too_many
        return result
    choice = find_span(scene, options, first=True)
    result.values.update(root_count=float(choice.search.roots.size), pole_count=float(choice.search.pole_count),
                         narrow_count=float(choice.search.narrow_count), candidate_count=float(len(choice.candidates)))
    result.extras.update(closure=scene.closure, impact_pattern=scene.pattern,
                         candidate_spans=[c.span_length for c in choice.candidates])
    if not choice.candidates:
        result.status = "no_span"
        detail = "; ".join(f"{len(v)} x {k}" for k, v in
                           sorted(choice.reasons.items(), key=lambda kv: -len(kv[1]))[:3])
        result.message = f"{choice.summary}; none satisfies condition 1" + (f" ({detail})" if detail else "")
        return result
    chosen = choice.candidates[0]
    survives = span_survives_doubling(scene, options, chosen.span_length, point.tolerances.tolerance)
    result.extras["span_converged"] = survives is None
    if survives is not None:
        result.status = "not_converged"
    result.values.update(
        span_length=chosen.span_length, equivalent_mass=chosen.equivalent_mass,
        impact_velocity=chosen.impact_velocity, impulse=chosen.impulse, axial_curvature=chosen.axial_curvature,
        max_approach=chosen.max_approach, hertz_duration=chosen.hertz_duration,
        hertz_peak_force=chosen.hertz_peak_force, contact_duration=chosen.contact_duration,
        peak_contact_force=chosen.peak_contact_force, contact_half_length=chosen.contact_half_length,
        contact_half_width=chosen.contact_half_width,
    )
    omega = scene.natural_frequencies(chosen.span_length, [1.0])
    result.values["first_natural_frequency"] = float(omega[0] / (2.0 * np.pi))
    smallest = ("the smallest is reported" if survives is None else
                f"the smallest, {chosen.span_length:.6g} m, is not converged: {survives}")
    result.message = f"{choice.summary}; {len(choice.candidates)} satisfy the constraints; {smallest}"
    finish(scene, chosen, inputs, options, result)
    return result
