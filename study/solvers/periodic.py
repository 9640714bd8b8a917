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

Span search. F(L) has a pole wherever a natural frequency ω_n(L) meets a harmonic of the pulse train
(docs/model.md §4): a sign change across a pole is not a root. The poles are located analytically
(:func:`resonant_spans`), F times the distances to the interval's two poles is sampled inside every
interval between consecutive poles (its values at the poles follow from their residues), and only sign
changes inside one interval are bracketed and solved. Roots are then refined with the
exact model and kept as candidates when condition 1 holds: |y| < c everywhere and always except at
the contact during the pulse, and the midspan arrives at the wall moving towards it.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Mapping

import numba
import numpy as np

from study.physics import beam, hertz, section
from study.physics.interpolation import interp_one
from study.physics.roots import bracket_done, closer_end, falsi_point, keep_sign_change
from study.solvers import extremes
from study.solvers.options import DEFAULT_TOLERANCE, IMPACT_MASSES, MAX_POLES, Options, study_tolerance
from study.solvers.result import PointResult
from study.solvers.scene import Scene, make_scene

#: Relative width at which the span search stops shrinking a bracket of the screening residual with no
#: pole within :data:`POLE_FREE_WINDOW` bracket widths (F is continuous there, so its sign change is a
#: root, and the midspan state that the screen reads at it does not swing across the bracket); others
#: go on to 1e-10. The exact root differs from the screening one by more (median 7e-6 relative, over
#: the 24 benchmark points and the paper's point in four readings), and :func:`refine_roots` takes it
#: from there.
ROOT_RTOL = 1e-6
POLE_FREE_WINDOW = 10.0


def odd_modes(n_modes: int) -> np.ndarray:
    """Mode numbers 1, 3, 5, … ≤ n_modes (a symmetric load excites no even mode)."""
    return np.arange(1, int(n_modes) + 1, 2, dtype=float)


def natural_frequencies(scene: Scene, span_length, modes) -> np.ndarray:
    """ω_n [rad/s] for spans ``span_length`` [m] (last axis: ``modes``); NaN where a mode buckles."""
    p = scene.props
    return section.natural_frequencies(span_length, p["bending_stiffness"], p["effective_tension"],
                                       p["mass_per_length"], modes)


def resonant_harmonics(scene: Scene, highest: int) -> np.ndarray:
    """Harmonic numbers of the rotation present in the pulse train: all (one_wall) or odd (alternating)."""
    return np.arange(1, highest + 1, scene.impacts_per_revolution, dtype=float)


def resonance_candidates(scene: Scene, modes, min_span: float) -> int:
    """How many (mode, harmonic) pairs :func:`resonances` enumerates: modes × the harmonics up to the highest
    mode's ω_n at the shortest span over Ω. Each costs about 16 bytes in the search, so a very slow rotary
    speed or a very short ``min_span`` [m] costs memory without bound."""
    modes = np.asarray(modes, dtype=float)
    omega_max = float(np.nanmax(natural_frequencies(scene, min_span, modes[-1:])))
    return int(modes.size * (np.ceil(omega_max / scene.rotary_speed) + 1))


def span_search_too_large(scene: Scene, options: Options, budget: int | None = None) -> str | None:
    """None when the span search's resonance candidates (:func:`resonance_candidates`) fit ``budget`` (config
    ``solver.max_poles``; default :data:`MAX_POLES`), otherwise why not, with the numbers."""
    budget = int(budget or MAX_POLES)
    count = resonance_candidates(scene, odd_modes(options.modes), options.min_span)
    if count <= budget:
        return None
    return (f"the span search would enumerate {count:.3g} resonance candidates (about {count * 16 / 2**30:.3g} GiB) "
            f"at {scene.rotary_speed * 30 / np.pi:.4g} rpm down to a {options.min_span:.4g}-m span, above "
            f"solver.max_poles = {budget:.3g}: raise the rotary speed or solver.min_span, or solver.max_poles on a "
            "larger machine")


def resonances(scene: Scene, modes, min_span: float, max_span: float) -> tuple[np.ndarray, np.ndarray]:
    """Spans [m] in [min_span, max_span] where some ω_n(L) equals a harmonic m Ω of the train, sorted,
    and the mode number n resonating at each.

    From ω² M = EI k⁴ + T k² with k = nπ/L: k² = [−T + √(T² + 4 EI M (mΩ)²)]/(2 EI), L = nπ/k
    (docs/model.md §4). These are the poles of the undamped periodic response.
    """
    p = scene.props
    ei, tension, mass = p["bending_stiffness"], p["effective_tension"], p["mass_per_length"]
    modes = np.asarray(modes, dtype=float)
    omega_max = float(np.nanmax(natural_frequencies(scene, min_span, modes[-1:])))
    highest = int(np.ceil(omega_max / scene.rotary_speed)) + 1
    forcing = resonant_harmonics(scene, highest) * scene.rotary_speed
    k_sq = (-tension + np.sqrt(tension**2 + 4.0 * ei * mass * forcing**2)) / (2.0 * ei)
    # each mode's spans fall as the harmonic rises: only the harmonics whose k² lies near (nπ/L)² for L in the
    # range are computed (two either side of it; the test below is the exact one). Equal spans of two modes keep
    # the order of their modes (a stable sort).
    root_k = np.sqrt(k_sq)
    first = np.maximum(np.searchsorted(k_sq, (modes * np.pi / max_span) ** 2) - 2, 0)
    last = np.minimum(np.searchsorted(k_sq, (modes * np.pi / min_span) ** 2) + 2, k_sq.size)
    spans, mode = [], []
    for n, a, b in zip(modes, first, last):
        row = n * np.pi / root_k[a:b][::-1]  # ascending: the sort below merges runs
        row = row[(row >= min_span) & (row <= max_span)]
        spans.append(row)
        mode.append(np.full(row.size, n))
    spans, mode = np.concatenate(spans), np.concatenate(mode)
    order = np.argsort(spans, kind="stable")
    return spans[order], mode[order]


def resonant_spans(scene: Scene, modes, min_span: float, max_span: float) -> np.ndarray:
    """The distinct spans of :func:`resonances` [m], ascending."""
    return np.unique(resonances(scene, modes, min_span, max_span)[0])


def unit_state(scene: Scene, span_length, pulse_duration, half_length, options: Options, modes=None):
    """Midspan displacement y₁ [m/(N s)], velocity v₁ [m/(N s²)] and curvature y₁'' [1/(m N s)] at the
    start of contact (t = 0) per unit impulse along +y (:func:`beam.midspan_state_at_pulse_start`).

    span_length, pulse_duration, half_length broadcast together (shape S); results of shape S.
    ``modes``: the mode numbers summed (default: the odd modes up to ``options.modes``); an array of
    shape S + (k,) sums its own k modes for every span.
    """
    p = scene.props
    modes = odd_modes(options.modes) if modes is None else modes
    return beam.midspan_state_at_pulse_start(span_length, pulse_duration, half_length, modes,
                                             p["bending_stiffness"], p["effective_tension"],
                                             p["mass_per_length"], scene.period, scene.pattern, options.load_shape)


@dataclass
class Impact:
    """The impact of one span at the fixed point of T_L and the contact curvature."""

    span_length: float
    residual: float  #: F(L) of the closure
    impulse: float = np.nan
    impact_velocity: float = np.nan
    equivalent_mass: float = np.nan
    contact_duration: float = np.nan
    hertz_duration: float = np.nan
    hertz_peak_force: float = np.nan
    peak_contact_force: float = np.nan
    contact_half_length: float = 0.0
    contact_half_width: float = 0.0
    axial_curvature: float = np.nan
    max_approach: float = np.nan
    iterations: int = 0
    problems: list[str] = field(default_factory=list)


def impact_at(scene: Scene, span_length: float, options: Options, max_iterations: int = 60,
              duration: float | None = None, half_length: float = 0.0) -> Impact:
    """Solve the T_L–κ fixed point at one span and return the impact with the closure residual.

    The pulse duration T_L sets the solution, whose contact curvature κ = −y''(L/2, 0), impact velocity
    and impulse set T_L again (Hertz stiffness at κ, Lee's rule). Solved as T_L = map(T_L) by secant
    steps on map(T_L) − T_L, with a relaxed fixed-point step (halved whenever it overshoots) wherever a
    secant step is not usable; converged when the map moves T_L by less than
    ``options.fixed_point_tol`` (relative). ``duration``: the starting T_L [s] (default: that of the
    assumed mode y = c sin(πx/L) hitting at V_p = Ω c); ``half_length``: the starting contact
    half-length b [m] (default 0, a point load), iterated with T_L. One span of :func:`impacts_at`.
    """
    return impacts_at(scene, [span_length], options, max_iterations,
                      None if duration is None else [duration], [half_length])[0]


def impacts_at(scene: Scene, spans, options: Options, max_iterations: int = 60, durations=None,
               halves=None) -> list[Impact]:
    """:func:`impact_at` at every span of ``spans`` [m] at once, in one compiled loop
    (:func:`_impacts_kernel`). durations [s], halves [m]: the starting T_L and b per span (None: the
    defaults of :func:`impact_at`; a NaN duration: the default for that span). Returns one
    :class:`Impact` per span, in order."""
    spans = np.atleast_1d(np.asarray(spans, dtype=float))
    rows = _impacts_kernel(np.ascontiguousarray(spans), *_starts(spans.shape, durations, halves), int(max_iterations),
                           *_kernel_args(scene, options))
    return _impacts_of(scene, rows)


def _starts(shape, durations, halves) -> tuple[np.ndarray, np.ndarray]:
    """The starting T_L [s] and b [m] per span for the compiled kernels, of ``shape``: durations None
    gives NaN (the assumed mode's T_L), halves None gives 0."""
    durations = np.nan if durations is None else durations
    halves = 0.0 if halves is None else halves
    return tuple(np.ascontiguousarray(np.broadcast_to(np.asarray(v, dtype=float), shape)) for v in (durations, halves))


def _impacts_of(scene: Scene, rows) -> list[Impact]:
    """The :class:`Impact` of each column of a compiled impact kernel's output (:data:`_ROWS`)."""
    col = dict(zip(_ROWS, rows))
    m_e = np.broadcast_to(np.asarray(scene.equivalent_mass(col["span"]), dtype=float), col["span"].shape)
    with np.errstate(invalid="ignore", divide="ignore"):
        elastic = hertz.hertz_impact(m_e, col["velocity"], col["stiffness"])
    out = []
    for i in range(col["span"].size):
        code = int(col["problem"][i])
        impact = Impact(span_length=float(col["span"][i]), residual=float(col["residual"][i]),
                        impulse=float(col["impulse"][i]), impact_velocity=float(col["velocity"][i]),
                        equivalent_mass=float(m_e[i]), axial_curvature=float(col["curvature"][i]),
                        problems=[_PROBLEMS[code](col["value"][i])] if code else [])
        if code == 0 or code > _FAILED:
            impact.contact_duration = float(col["duration"][i])
            impact.hertz_duration, impact.hertz_peak_force = float(elastic.duration[i]), float(elastic.max_force[i])
            impact.max_approach = float(elastic.max_approach[i])
            impact.peak_contact_force = float(col["peak"][i])
            impact.contact_half_length, impact.contact_half_width = float(col["half"][i]), float(col["half_width"][i])
            impact.iterations = int(col["iterations"][i])
        out.append(impact)
    return out


#: Why the T_L–curvature iteration of a span stopped (codes of :func:`_impacts_kernel`), with the value
#: each message shows.
_PROBLEMS = {
    1: lambda value: f"pulse longer than the time between impacts (T_L = {value:.3g} s)",
    2: lambda value: "the span is at a resonance or buckled",
    3: lambda value: "the pipe is not convex towards the wall at the contact",
    4: lambda value: "the midspan does not approach the wall before contact",
    5: lambda value: "condition 2 needs a negative impulse",
    6: lambda value: f"T_L–curvature iteration not converged in {value:.0f} steps",
    7: lambda value: "the exact root left the interval between the searched poles around the screening root",
    8: lambda value: f"condition 2 residual {value:.2g} after refinement",
}
_FAILED = 5  #: codes up to this one leave the span without a solution


def _kernel_args(scene: Scene, options: Options) -> tuple:
    """The scene and settings as the compiled kernels take them: (beam state, modes, contact, closure)."""
    p = scene.props
    modes = odd_modes(options.modes)
    state = (float(p["bending_stiffness"]), float(p["effective_tension"]), float(p["mass_per_length"]),
             float(scene.period), scene.pattern == "one_wall", beam._SHAPE_CODES[options.load_shape], 1e-15, True)
    contact = (float(scene.outer_radius), float(scene.hole_radius), float(scene.compliance_sum), hertz.guess_table())
    # m_e = mass_factor L (Scene.equivalent_mass is proportional to L)
    closure = (scene.closure == "self_consistent", float(scene.equivalent_mass(1.0)), float(scene.restitution),
               float(scene.rotary_speed), float(scene.clearance), float(scene.impact_interval),
               float(options.fixed_point_tol))
    return state, modes, contact, closure


@numba.njit(cache=True, nogil=True)
def _impacts_kernel(spans, durations, halves, max_iterations, state, modes, contact, closure):
    """The T_L–κ fixed point of every span (compiled; :func:`impacts_at` documents it), all spans in
    lockstep: each round evaluates the midspan states of the spans still iterating in one call
    (:func:`beam.midspan_states`), then moves each span's iteration on as it would move alone.
    ``durations``: the starting T_L [s] per span (NaN or out of range: that of the assumed mode);
    ``halves``: the starting b [m]. Returns one column per span (:data:`_ROWS`): the span, residual,
    impulse, V_p, κ, T_L, b, contact half-width, Hertz stiffness, peak force, iterations, problem code
    (:data:`_PROBLEMS`; 0: none) and its value."""
    self_consistent, mass_factor, restitution, rotary_speed, c, longest, tol = closure
    radius, hole, compliance, table = contact
    ei, tension, mass, period, one_wall, code, resonance_tol, _ = state
    size = spans.size
    out = np.full((13, size), np.nan)
    duration, half, velocity = np.empty(size), np.empty(size), np.full(size, rotary_speed * c)
    relaxation, last_step = np.ones(size), np.zeros(size)
    previous, previous_step = np.full(size, math.nan), np.full(size, math.nan)
    for i in range(size):
        span = spans[i]
        out[0, i], out[11, i], out[3, i] = span, 0.0, velocity[i]
        duration[i] = durations[i]
        if not 0.0 < duration[i] < longest:  # that of the assumed mode y = c sin(πx/L): κ = c (π/L)², V_p = Ω c
            _, _, stiffness = hertz.contact_one(1.0, radius, hole, c * (math.pi / span) ** 2, compliance, table)
            duration[i] = hertz.lee_duration_one(mass_factor * span, velocity[i], stiffness)
        half[i] = min(max(halves[i], 0.0), 0.45 * span)
    running = np.arange(size)
    for iteration in range(1, max_iterations + 1):
        count = 0
        for i in running:
            if not duration[i] < longest:
                out[11, i], out[12, i] = 1.0, duration[i]
                continue
            running[count] = i
            count += 1
        running = running[:count].copy()
        if count == 0:
            break
        y1s, v1s, curv1s = beam.midspan_states(spans[running], duration[running], half[running], modes.size, ei,
                                               tension, mass, period, one_wall, code, resonance_tol)
        count = 0
        for k in range(running.size):
            i, y1, v1, curv1 = running[k], y1s[k], v1s[k], curv1s[k]
            span = spans[i]
            m_e = mass_factor * span
            if not math.isfinite(y1):
                out[11, i] = 2.0
                continue
            if self_consistent:
                impulse, velocity[i] = -c / y1, c * v1 / y1
                residual = m_e * (1.0 + restitution) * velocity[i] / impulse - 1.0
            else:
                impulse = m_e * (1.0 + restitution) * velocity[i]
                residual = -impulse * y1 / c - 1.0
            curvature = impulse * curv1
            out[1, i], out[2, i], out[3, i], out[4, i] = residual, impulse, velocity[i], curvature
            if not (curvature > 0.0 and velocity[i] > 0.0 and impulse > 0.0):
                out[11, i] = 3.0 if curvature <= 0.0 else 4.0 if velocity[i] <= 0.0 else 5.0
                continue
            peak = math.pi * impulse / (2.0 * duration[i])  # hertz.lee_peak_force
            b, half_width, stiffness = hertz.contact_one(peak, radius, hole, curvature, compliance, table)
            half[i] = min(b, 0.45 * span)
            mapped = hertz.lee_duration_one(m_e, velocity[i], stiffness)
            step = mapped - duration[i]
            out[5, i], out[6, i], out[7, i], out[8, i], out[9, i], out[10, i] = (duration[i], half[i], half_width,
                                                                                  stiffness, peak, iteration)
            if abs(step) <= tol * mapped:
                continue
            if iteration == max_iterations:  # report the T_L the solution was computed with
                if max_iterations > 1:
                    out[11, i], out[12, i] = 6.0, max_iterations
                continue
            if last_step[i] * step < 0:
                relaxation[i] *= 0.5
            last_step[i] = step
            secant = math.nan
            if math.isfinite(previous[i]) and step != previous_step[i]:
                secant = duration[i] - step * (duration[i] - previous[i]) / (step - previous_step[i])
            previous[i], previous_step[i] = duration[i], step
            duration[i] = secant if 0.0 < secant < longest else duration[i] + relaxation[i] * step
            running[count] = i
            count += 1
        running = running[:count].copy()
    return out


#: The rows of the compiled impact kernels' output.
_ROWS = ("span", "residual", "impulse", "velocity", "curvature", "duration", "half", "half_width", "stiffness", "peak",
         "iterations", "problem", "value")


@numba.njit(cache=True, nogil=True)
def _refine_kernel(approx, lo, hi, durations, halves, steps, state, modes, contact, closure):
    """The secant iteration of :func:`refine_roots` for every root (compiled), all roots in lockstep:
    each round solves the T_L–κ fixed points of the roots still moving in one call
    (:func:`_impacts_kernel`), then moves each root's secant as it would move alone; one column per root."""
    size = approx.size
    x0, x1 = approx.copy(), np.empty(size)
    for k in range(size):
        step = min(min(1e-6 * x0[k], 1e-3 * (hi[k] - x0[k])), 1e-3 * (x0[k] - lo[k]))
        x1[k] = x0[k] + (step if hi[k] - x0[k] > x0[k] - lo[k] else -step)
    last = _impacts_kernel(x0, durations, halves, 60, state, modes, contact, closure)
    out = last.copy()  # the roots whose first span fails keep it
    moving = np.ones(size, dtype=np.bool_)
    running = np.array([k for k in range(size) if last[11, k] == 0.0 and math.isfinite(last[1, k])], dtype=np.int64)
    started = running.copy()
    here = np.full((13, size), math.nan)
    if running.size:
        here[:, running] = _impacts_kernel(x1[running], last[5, running], last[6, running], 60, state, modes,
                                           contact, closure)
    for _ in range(steps):
        count = 0
        for k in running:
            if here[11, k] != 0.0 or not math.isfinite(here[1, k]) or abs(here[1, k]) < 1e-10:
                moving[k] = False
                continue
            slope = (here[1, k] - last[1, k]) / (x1[k] - x0[k]) if x1[k] != x0[k] else 0.0
            if slope == 0.0:
                continue
            x2 = x1[k] - here[1, k] / slope
            if not lo[k] <= x2 <= hi[k]:
                here[11, k] = 7.0
                moving[k] = False
                continue
            x0[k], last[:, k], x1[k] = x1[k], here[:, k], x2
            running[count] = k
            count += 1
        running = running[:count].copy()
        if count == 0:
            break
        here[:, running] = _impacts_kernel(x1[running], last[5, running], last[6, running], 60, state, modes,
                                           contact, closure)
    for k in started:
        if moving[k] and here[11, k] == 0.0 and abs(here[1, k]) > 1e-8:  # the steps ran out, or a flat secant
            here[11, k], here[12, k] = 8.0, here[1, k]
        out[:, k] = here[:, k]
    return out


def screen_residual(scene: Scene, options: Options):
    """A cheap, smooth stand-in for F(L), vectorised over spans, for the search.

    T_L(L) and the contact half-length b(L) come from one fixed-point step at a dozen spans,
    interpolated in log L; the roots found with it are refined with the exact model afterwards.
    Returns a function of an array of spans (compiled, :func:`_screen_state`), or None when no span
    gives a valid pulse; its ``shrink`` shrinks sign-changing brackets of F times the distances to two
    poles onto their roots in lockstep rounds of compiled loops (:func:`_shrink_points`, :func:`_shrink_update`).
    """
    grid = np.geomspace(options.min_span, options.max_span, 12)
    impacts = impacts_at(scene, grid, options, max_iterations=1)
    durations = np.array([i.contact_duration for i in impacts])
    halves = np.array([i.contact_half_length for i in impacts])
    ok = np.isfinite(durations) & (durations > 0)
    if not np.any(ok):
        return None
    table = (np.log(grid[ok]), np.log(durations[ok]), halves[ok])
    state, all_modes, _, closure = _kernel_args(scene, options)
    any_modes = state[:-1] + (False,)  # modes not 1, 3, 5, ...

    def pulse(spans):
        """(T_L, b) interpolated at ``spans`` (numpy's log and exp of whole arrays: SIMD)."""
        log_spans = np.log(spans)
        return np.exp(np.interp(log_spans, table[0], table[1])), np.interp(log_spans, table[0], table[2])

    def residual(spans, modes=None):
        """F(L) at ``spans``; with ``modes`` (see :func:`unit_state`) F + 1 from those modes alone."""
        spans = np.asarray(spans, dtype=float)
        if modes is None:
            flat = np.ascontiguousarray(spans.ravel())
            values = _screen_values_batch(flat, *pulse(flat), all_modes.size, 1.0, state, closure)
        else:
            per_span = np.broadcast_to(np.asarray(modes, dtype=float), spans.shape + np.shape(modes)[-1:])
            values = _screen_values(np.ascontiguousarray(spans.ravel()),
                                    np.ascontiguousarray(per_span.reshape(spans.size, -1)), 0.0, table, any_modes,
                                    closure)
        return values.reshape(spans.shape)

    def shrink(lo, hi, f_lo, f_hi, pole_lo, pole_hi, rtol=1e-10, iterations=60, poles=None, pole_free_rtol=None):
        """Brackets [lo, hi] of G = F (L − pole_lo)(pole_hi − L) with G = f_lo, f_hi at the ends, shrunk
        onto their sign change (regula falsi with the Illinois modification, :mod:`study.physics.roots`)
        until narrower than ``rtol`` (relative) or at an exact zero — or than ``pole_free_rtol`` once
        none of ``poles`` (sorted [m]) lies within :data:`POLE_FREE_WINDOW` bracket widths. Returns
        (roots, G at the roots, final lo, final hi, (3, n) y₁, v₁, y₁'' at the roots as
        :func:`unit_state` with the screening pulse, NaN where not evaluated), the root being the end
        with the smaller weighted |G|."""
        a, b, fa, fb, pole_lo, pole_hi = (np.array(v, dtype=float) for v in (lo, hi, f_lo, f_hi, pole_lo, pole_hi))
        raw_a, raw_b, side, tol = fa.copy(), fb.copy(), np.zeros(a.size, dtype=np.int64), np.full(a.size, float(rtol))
        states = np.full((2, 3, a.size), np.nan)  # y₁, v₁, y₁'' at the lower and the upper end
        poles = np.zeros(0) if poles is None else np.ascontiguousarray(poles, dtype=float)
        free_rtol = float(rtol if pole_free_rtol is None else pole_free_rtol)
        running, below = np.arange(a.size), np.full(a.size, -1, dtype=np.int64)
        # every bracket takes the steps it would take alone, all in lockstep: each round evaluates the new
        # points of the brackets still open at once (the pulse by numpy, the modal sums in one SIMD call)
        for done in range(int(iterations)):
            running, points = _shrink_points(a, b, fa, fb, tol, running, poles, free_rtol, below)
            if running.size == 0:
                break
            if running.size <= SHRINK_TAIL:  # the few brackets left (next to a pole) in one compiled loop
                _shrink_tail(running, points, int(iterations) - done, a, b, fa, fb, raw_a, raw_b, side, tol, states,
                             pole_lo, pole_hi, poles, free_rtol, below, table, all_modes.size, state, closure)
                break
            values, y1, v1, curv1 = _screen_batch(points, *pulse(points), all_modes.size, 1.0, state, closure)
            _shrink_update(running, points, values, y1, v1, curv1, a, b, fa, fb, raw_a, raw_b, side, states, pole_lo,
                           pole_hi)
        out = _shrink_result(a, b, fa, fb, raw_a, raw_b, states)
        return out[0], out[1], out[2], out[3], out[4:]

    def residue(spans, modes, floor=0.0):
        """R [m] of the term of mode ``modes`` in F at its pole ``spans``: F ≈ R/(L − L_p) there; NaN
        where |R| is certainly below ``floor`` [m] (broadcast with spans), not computed.

        The term is −m_e(1 + e) Ω w q(0) (prescribed) or −m_e(1 + e) w q̇(0) (self-consistent), w the
        mode's midspan weight, and q(0), q̇(0) (:func:`beam.modal_state_at_pulse_start`) carry the pole
        through κ ≈ 1/(x − x_p), x = ω s (s = τ/2 for cot(ωτ/2), τ/4 for −tan(ωτ/4)): the factor of κ,
        A cos φ/(2ω) or A sin φ/2 (A e^{−iφ} = H(ω), :func:`beam.pulse_spectrum`), over s dω/dL."""
        spans, n, floors = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (spans, modes, floor)))
        flat = [np.ascontiguousarray(v.ravel()) for v in (spans, n)]
        return _residues_kernel(*flat, table, state, closure, np.ascontiguousarray(floors.ravel())).reshape(spans.shape)

    residual.pulse = pulse
    residual.residue = residue
    residual.shrink = shrink
    return residual


@numba.njit(cache=True, nogil=True)
def _screen_state(span, modes, offset, table, state, closure):
    """(F(L) + 1 − ``offset``, y₁, v₁, y₁'') at one span [m] (compiled): T_L and b interpolated in
    log L from ``table`` (log L, log T_L, b), the midspan state per unit impulse summed over ``modes``
    (:func:`beam.midspan_state_one` with ``state``), then the closure (``closure`` of
    :func:`_kernel_args`: self-consistent?, m_e/L [kg/m], e, Ω [rad/s], ...): −m_e (1 + e) v₁ (self-consistent: m_e (1+e) V_p/J with V_p = c v₁/y₁,
    J = −c/y₁) or −m_e (1 + e) Ω y₁ (prescribed: −J y₁/c with J = m_e (1 + e) Ω c); y₁, v₁, y₁'' the
    midspan state per unit impulse of :func:`unit_state`."""
    duration, half = _pulse_one(span, table)
    ei, tension, mass, period, one_wall, code, tol, consecutive = state
    y1, v1, curv1 = beam.midspan_state_one(span, duration, half, modes, ei, tension, mass, period, one_wall, code,
                                           tol, consecutive)
    self_consistent, mass_factor, restitution, omega, _, _, _ = closure
    impulse_factor = mass_factor * span * (1.0 + restitution)
    if self_consistent:
        return -impulse_factor * v1 - offset, y1, v1, curv1
    return -impulse_factor * omega * y1 - offset, y1, v1, curv1


@numba.njit(cache=True, nogil=True)
def _pulse_one(span, table):
    """(T_L [s], b [m]) of the screening residual at one span [m]: ``pulse`` of :func:`screen_residual`,
    compiled, from ``table`` (log L, log T_L, b)."""
    log_span = math.log(span)
    return math.exp(interp_one(log_span, table[0], table[1])), interp_one(log_span, table[0], table[2])


@numba.njit(cache=True, nogil=True, error_model="numpy")  # no division check: a jump in the loop stops SIMD
def _residues_kernel(spans, modes, table, state, closure, floors):
    """``screen_residual(...).residue`` at every pole (compiled): spans L_p [m], modes n, the rest as
    :func:`_screen_state`; NaN, not computed, where a bound without trigonometry puts |R| below
    ``floors`` [m] (one per pole).

    The bound: |g_n H(ω)| ≤ min(1, 1/|u² − 1|), u = ωT_L/π. The load and the pulse are non-negative, so
    |g_n| ≤ g(0) = 1 and |H(ω)| ≤ H(0) = 1, and H = A e^{−iφ} with |A| = |cos φ/(1 − u²)|. T_L is at
    least the table's shortest (the interpolation stays within its values), so u ≥ ω min T_L/π."""
    ei, tension, mass, _, _, code, _, _ = state
    self_consistent, mass_factor, restitution, omega_rot, _, interval, _ = closure
    shortest = math.exp(np.min(table[1]))
    out = np.empty(spans.size)
    omegas, scales = np.empty(spans.size), np.empty(spans.size)
    for i in range(spans.size):  # the bound of every pole first, in SIMD instructions (no jump, no library call)
        span, n = spans[i], modes[i]
        k_sq = (n * math.pi / span) ** 2
        om_sq = (ei * k_sq + tension) * k_sq / mass
        omega = math.sqrt(om_sq) if om_sq > 0.0 else math.nan
        slope = -(2.0 * ei * k_sq**2 + tension * k_sq) / (mass * span * omega)  # dω/dL
        scale = -mass_factor * span * (1.0 + restitution) * 2.0 / (mass * span) / (0.5 * interval * slope)
        u = omega * shortest / math.pi
        bound = abs(scale) * (1.0 / (u * u - 1.0) if u * u > 2.0 else 1.0) * (
            0.5 if self_consistent else omega_rot / (2.0 * omega))
        omegas[i], scales[i], out[i] = omega, scale, math.nan if bound < floors[i] else 0.0
    for i in range(spans.size):
        if out[i] != 0.0:
            continue
        span, n, omega, scale = spans[i], modes[i], omegas[i], scales[i]
        duration, half = _pulse_one(span, table)
        real, imag = beam.loaded_spectrum_one(omega, span, n, duration, half, code)  # |g_n| H(ω)
        out[i] = scale * (-0.5 * imag if self_consistent else omega_rot * real / (2.0 * omega))
    return out


@numba.njit(cache=True, nogil=True)
def _screen_batch(spans, durations, halves, n_odd, offset, state, closure):
    """(F(L) + 1 − ``offset``, y₁, v₁, y₁'') of :func:`_screen_state` at every span of ``spans`` [m] with the
    screening pulse's T_L ``durations`` [s] and b ``halves`` [m] there (``pulse`` of :func:`screen_residual`)
    and the odd modes 1, 3, …, 2 ``n_odd`` − 1, the modal sums of all spans at once in SIMD instructions
    (:func:`beam.midspan_states`; equal to :func:`_screen_state` but for rounding)."""
    ei, tension, mass, period, one_wall, code, tol, _ = state
    y1, v1, curv1 = beam.midspan_states(spans, durations, halves, n_odd, ei, tension, mass, period, one_wall, code, tol)
    self_consistent, mass_factor, restitution, omega, _, _, _ = closure
    factor = mass_factor * spans * (1.0 + restitution)
    values = -factor * v1 - offset if self_consistent else -factor * omega * y1 - offset
    return values, y1, v1, curv1


@numba.njit(cache=True, nogil=True)
def _screen_values_batch(spans, durations, halves, n_odd, offset, state, closure):
    """The first of :func:`_screen_batch`'s arrays alone, to the last bit: the modal sum of y₁ (prescribed) or v₁
    (self-consistent) only (:func:`beam.midspan_sums`)."""
    ei, tension, mass, period, one_wall, code, tol, _ = state
    self_consistent, mass_factor, restitution, omega, _, _, _ = closure
    total = beam.midspan_sums(spans, durations, halves, n_odd, ei, tension, mass, period, one_wall, code, tol,
                              self_consistent)
    factor = mass_factor * spans * (1.0 + restitution)
    return -factor * total - offset if self_consistent else -factor * omega * total - offset


@numba.njit(cache=True, nogil=True)
def _screen_values(spans, modes, offset, table, state, closure):
    """The screening residual of :func:`_screen_state` at every span; ``modes`` one row for all spans or
    one row per span."""
    out = np.empty(spans.size)
    per_span = modes.shape[0] > 1
    for i in range(spans.size):
        out[i] = _screen_state(spans[i], modes[i if per_span else 0], offset, table, state, closure)[0]
    return out


@numba.njit(cache=True, nogil=True)
def _search_right(values, x, hint):
    """``np.searchsorted(values, x, side="right")`` of ascending ``values`` and a finite x, galloping from index
    ``hint`` (steps of 1, 2, 4, … towards the answer, then halving): a few comparisons when the answer is near
    the hint, as it is for the span search's brackets taken in ascending order."""
    n = values.size
    hint = min(max(hint, 0), n)
    step = 1
    if hint < n and values[hint] <= x:  # the answer is above the hint
        lo = hint + 1
        hi = lo
        while hi < n and values[hi] <= x:
            lo = hi + 1
            hi = lo + step
            step *= 2
        hi = min(hi, n)
    else:  # at or below it
        hi = hint
        lo = hi
        while lo > 0 and values[lo - 1] > x:
            hi = lo - 1
            lo = hi - step
            step *= 2
        lo = max(lo, 0)
    while lo < hi:  # values[lo - 1] <= x (or lo = 0) and values[hi] > x (or hi = n)
        mid = (lo + hi) // 2
        if values[mid] <= x:
            lo = mid + 1
        else:
            hi = mid
    return lo


@numba.njit(cache=True, nogil=True)
def _shrink_points(a, b, fa, fb, tol, running, poles, pole_free_rtol, below):
    """One round of ``screen_residual(...).shrink`` for the brackets ``running``: each bracket's tolerance
    (``pole_free_rtol`` once none of ``poles`` lies within :data:`POLE_FREE_WINDOW` bracket widths, updated in
    ``tol``), and the brackets not yet done with their next point (regula falsi, :mod:`study.physics.roots`).
    ``below``: per bracket, how many poles lie at or below a − W (b − a) (W the window) at its last check, −1
    before the first; that point only moves up as the bracket shrinks, so each check walks on from there.
    Returns (those brackets, their points)."""
    still, points = np.empty(running.size, dtype=np.int64), np.empty(running.size)
    count, hint = 0, 0
    for i in running:
        if tol[i] != pole_free_rtol and b[i] - a[i] <= pole_free_rtol * abs(b[i]):  # far from every pole?
            left = a[i] - POLE_FREE_WINDOW * (b[i] - a[i])
            if below[i] < 0:  # the brackets come in ascending order: search on from the last one's place
                below[i] = hint = _search_right(poles, left, hint)
            while below[i] < poles.size and poles[below[i]] <= left:
                below[i] += 1
            first = below[i]
            if first == poles.size or poles[first] >= b[i] + POLE_FREE_WINDOW * (b[i] - a[i]):
                tol[i] = pole_free_rtol
        if bracket_done(a[i], b[i], fa[i], fb[i], tol[i]):
            continue
        still[count], points[count] = i, falsi_point(a[i], b[i], fa[i], fb[i])
        count += 1
    return still[:count].copy(), points[:count].copy()


@numba.njit(cache=True, nogil=True)
def _shrink_update(running, points, values, y1, v1, curv1, a, b, fa, fb, raw_a, raw_b, side, states, pole_lo,
                   pole_hi):
    """The brackets ``running`` after F = ``values`` at their ``points`` (G = F (L − pole_lo)(pole_hi − L)):
    the end with G's sign moves there (Illinois weights, :func:`keep_sign_change`), and y₁, v₁, y₁'' there
    are kept for that end (``states`` [0] lower, [1] upper)."""
    for k in range(running.size):
        i, x = running[k], points[k]
        g = values[k] * (x - pole_lo[i]) * (pole_hi[i] - x)
        a[i], b[i], fa[i], fb[i], raw_a[i], raw_b[i], side[i] = keep_sign_change(
            a[i], b[i], fa[i], fb[i], raw_a[i], raw_b[i], side[i], x, g)
        end = 0 if side[i] == 1 else 1
        states[end, 0, i], states[end, 1, i], states[end, 2, i] = y1[k], v1[k], curv1[k]


#: Brackets left below which ``screen_residual(...).shrink`` takes its remaining rounds in one compiled loop
#: (:func:`_shrink_tail`): the brackets next to a pole, shrunk to 1e-10, take up to 40 rounds of a few hundred.
SHRINK_TAIL = 1024


@numba.njit(cache=True, nogil=True)
def _shrink_tail(running, points, rounds, a, b, fa, fb, raw_a, raw_b, side, tol, states, pole_lo, pole_hi, poles,
                 pole_free_rtol, below, table, n_odd, state, closure):
    """The last ``rounds`` rounds of ``screen_residual(...).shrink`` from the brackets ``running`` and their next
    ``points`` on, in one compiled loop: each round the screening pulse at the points (:func:`_pulse_one`), the
    residual and midspan state there (:func:`_screen_batch`), the brackets moved (:func:`_shrink_update`) and
    their next points (:func:`_shrink_points`)."""
    for _ in range(rounds):
        if running.size == 0:
            break
        durations, halves = np.empty(points.size), np.empty(points.size)
        for k in range(points.size):
            durations[k], halves[k] = _pulse_one(points[k], table)
        values, y1, v1, curv1 = _screen_batch(points, durations, halves, n_odd, 1.0, state, closure)
        _shrink_update(running, points, values, y1, v1, curv1, a, b, fa, fb, raw_a, raw_b, side, states, pole_lo,
                       pole_hi)
        running, points = _shrink_points(a, b, fa, fb, tol, running, poles, pole_free_rtol, below)


@numba.njit(cache=True, nogil=True)
def _shrink_result(a, b, fa, fb, raw_a, raw_b, states):
    """Rows root, G at the root, final lo, final hi, and y₁, v₁, y₁'' at the root (NaN at an end no round
    evaluated), the root being the end with the smaller weighted |G| (:func:`closer_end`)."""
    out = np.empty((7, a.size))
    for i in range(a.size):
        out[0, i], out[1, i] = closer_end(a[i], b[i], fa[i], fb[i], raw_a[i], raw_b[i])
        out[2, i], out[3, i] = a[i], b[i]
        end = 0 if out[0, i] == a[i] else 1
        out[4, i], out[5, i], out[6, i] = states[end, 0, i], states[end, 1, i], states[end, 2, i]
    return out


def resonance_widths(residual, spans, modes) -> np.ndarray:
    """Relative width of each resonance [-]: |R|/L_p, R the residue in L of the resonant mode's term of
    the closure residual F at its pole L_p (``spans``, mode numbers ``modes``), in closed form
    (``residual.residue`` of :func:`screen_residual`).

    Near the pole F = R/(L − L_p) + B(L): the resonant mode alone moves F by more than 1 (it alone
    carries the midspan to the wall) only within |L − L_p| < |R|, and the root it pins sits within
    |R/B| of the pole. Light damping of ratio ζ bounds the resonant term by about |R|/(ζ L_p), so a
    resonance with |R|/L_p ≪ ζ has no root once the pipe is damped at all (docs/model.md §7): such a root is
    an artefact of the undamped model.
    """
    spans = np.asarray(spans, dtype=float)
    return np.abs(residual.residue(spans, np.asarray(modes, dtype=float))) / spans


@dataclass
class SpanSearch:
    """All roots of condition 2 in the search range, ascending, with their brackets."""

    roots: np.ndarray
    brackets: np.ndarray  #: (n, 2) the interval between the two poles around each root (free of wide poles)
    pole_count: int
    residual: Any = None  #: the screening residual (with ``.pulse``), for the screening checks
    narrow_count: int = 0  #: poles not searched, their resonance narrower than ``Options.resonance_width``
    #: (3, n) y₁, v₁, y₁'' at each root as :func:`unit_state` with the screening pulse (NaN: not evaluated)
    states: np.ndarray | None = None


def find_roots(scene: Scene, options: Options) -> SpanSearch:
    """Roots of the closure residual F(L) in [min_span, max_span], bracketed between poles.

    Poles whose resonance is narrower than ``options.resonance_width`` (:func:`resonance_widths`) are
    not searched (their residues not even computed where a bound without trigonometry shows it,
    :func:`_residues_kernel`): the root each pins lies within that relative distance of the pole and
    vanishes with any damping of that order. Between the remaining poles the search works on G = F (L − a)(b − L),
    a and b the poles around L: the same roots, continuous up to both poles, where it equals R_a (b − a)
    and −R_b (b − a) (R the poles' residues, :func:`resonance_widths`) — the ends' values in closed
    form, so a root pinned however close to a pole is bracketed. G is sampled between the poles and
    its sign changes are shrunk by regula falsi, to :data:`ROOT_RTOL` where no pole is near and to
    1e-10 where one is. A sign change that converges onto no pole but the interval's own is a root (G
    is continuous there); one with a narrow pole in its last bracket is a root only where |F| has
    fallen far below its values at the samples. (:func:`search_intervals`, then :func:`roots_between`
    over all its intervals.)
    """
    intervals = search_intervals(scene, options)
    return roots_between(intervals, 0, intervals.lo.size, options)


@dataclass
class SearchIntervals:
    """The span search's intervals between consecutive wide poles (and the ends of the search range), ascending,
    with what sampling them needs (:func:`search_intervals`)."""

    poles: np.ndarray  #: every pole in the range [m], ascending (the narrow ones included)
    lo: np.ndarray  #: each interval's lower end [m]
    hi: np.ndarray  #: each interval's upper end [m]
    residue_lo: np.ndarray  #: the residue [m] of the pole at lo (NaN: the end of the search range)
    residue_hi: np.ndarray  #: the residue [m] of the pole at hi (NaN: the end of the search range)
    residual: Any = None  #: the screening residual (:func:`screen_residual`); None: no span gives a valid pulse
    narrow_count: int = 0  #: poles not searched, their resonance narrower than ``Options.resonance_width``


def search_intervals(scene: Scene, options: Options) -> SearchIntervals:
    """The poles in [min_span, max_span], their residues, and the intervals between the wide ones
    (steps 1–2 of :func:`find_roots`): no interval when no span gives a valid pulse."""
    modes = odd_modes(options.modes)
    poles, pole_modes = resonances(scene, modes, options.min_span, options.max_span)
    residual = screen_residual(scene, options)
    if residual is None:
        empty = np.zeros(0)
        return SearchIntervals(poles, empty, empty, empty, empty)
    floors = options.resonance_width * poles  # resonance_widths, from the same residues (NaN: narrow for sure)
    residues = residual.residue(poles, pole_modes.astype(float), floors) if poles.size else np.zeros(0)
    wide = np.abs(residues) >= floors
    edges, edge_residues = _merged_poles(poles[wide], residues[wide])
    edges = np.concatenate([[options.min_span], edges, [options.max_span]])
    edge_residues = np.concatenate([[np.nan], edge_residues, [np.nan]])  # NaN: the search range's end, no pole
    lo, hi = edges[:-1], edges[1:]
    keep = hi > lo * (1 + 1e-12)
    return SearchIntervals(poles, lo[keep], hi[keep], edge_residues[:-1][keep], edge_residues[1:][keep], residual,
                           int(np.count_nonzero(~wide)))


def roots_between(intervals: SearchIntervals, first: int, stop: int, options: Options) -> SpanSearch:
    """The roots of condition 2 in the intervals ``first`` to ``stop`` − 1 of ``intervals`` (steps 3 of
    :func:`find_roots`: sampled, bracketed and shrunk), ascending. Each interval's roots depend on that
    interval alone, so the search can be taken a run of intervals at a time."""
    lo, hi = intervals.lo[first:stop], intervals.hi[first:stop]
    residue_lo, residue_hi = intervals.residue_lo[first:stop], intervals.residue_hi[first:stop]
    poles, residual = intervals.poles, intervals.residual
    if lo.size == 0:
        return SpanSearch(np.array([]), np.zeros((0, 2)), int(poles.size), residual,
                          narrow_count=intervals.narrow_count, states=np.zeros((3, 0)))
    # samples strictly inside each interval, denser towards the poles where F changes fastest; at a
    # pole G is R (b − a) in closed form, at an end of the search range F is computed just inside it
    fractions = 0.5 - 0.5 * np.cos(np.pi * (np.arange(options.samples) + 0.5) / options.samples)
    spans, inside = _sample_spans(lo, hi, residue_lo, residue_hi, fractions)
    brackets = _sign_changes(spans, residual(inside), lo, hi, residue_lo, residue_hi)
    if brackets.shape[1] == 0:
        return SpanSearch(np.array([]), np.zeros((0, 2)), int(poles.size), residual,
                          narrow_count=intervals.narrow_count, states=np.zeros((3, 0)))
    # regula falsi on G: no singularity at the ends, so it converges in a few steps instead of
    # crawling along the pole's hyperbola
    roots, root_values, final_lo, final_hi, states = residual.shrink(*brackets[:6], poles=poles,
                                                                     pole_free_rtol=ROOT_RTOL)
    # G is continuous between poles and at the wide ones around the interval: a sign change left in a
    # bracket free of every other pole (the narrow ones included) is a root. One with a narrow pole
    # inside may have converged onto the pole, where |F| grows: it is a root only if |F| there is
    # far below its value at the samples.
    real = _real_roots(roots, root_values, final_lo, final_hi, brackets[4], brackets[5], brackets[6], poles)
    between = np.stack([brackets[4][real], brackets[5][real]], axis=1)
    return SpanSearch(roots=roots[real], brackets=between, pole_count=int(poles.size), residual=residual,
                      narrow_count=intervals.narrow_count, states=states[:, real])


@numba.njit(cache=True, nogil=True)
def _sample_spans(lo, hi, residue_lo, residue_hi, fractions):
    """The samples of :func:`roots_between`, (intervals, samples + 2) [m]: each interval's ends (its poles;
    the search range's ends, NaN residue, moved 1e-12 inside) and lo + (hi − lo) ``fractions`` between them;
    and, flat in row order, those where F is computed (all but the poles)."""
    n, m = lo.size, fractions.size
    spans = np.empty((n, m + 2))
    inside = np.empty(n * (m + 2))
    count = 0
    for i in range(n):
        width = hi[i] - lo[i]
        spans[i, 0] = lo[i] * (1.0 + 1e-12) if math.isnan(residue_lo[i]) else lo[i]
        spans[i, m + 1] = hi[i] * (1.0 - 1e-12) if math.isnan(residue_hi[i]) else hi[i]
        for j in range(m):
            spans[i, j + 1] = lo[i] + width * fractions[j]
        for j in range(m + 2):
            if 0 < j < m + 1 or (j == 0 and math.isnan(residue_lo[i])) or (j == m + 1 and math.isnan(residue_hi[i])):
                inside[count] = spans[i, j]
                count += 1
    return spans, inside[:count].copy()


@numba.njit(cache=True, nogil=True)
def _sign_changes(spans, inside_values, lo, hi, residue_lo, residue_hi):
    """The sign changes of G = F (L − lo)(hi − L) between consecutive samples of :func:`_sample_spans` (F at its
    flat ``inside`` spans; at a pole G is R (hi − lo) and −R (hi − lo), R its residue). Rows: bracket lo, hi [m],
    G there, the interval's lo, hi [m], and the smaller |F| at the bracket's two samples (infinite at a pole)."""
    n, m = spans.shape
    g, f = np.empty(m), np.empty(m)
    out = np.empty((7, n * (m - 1)))
    count, k = 0, 0
    for i in range(n):
        width = hi[i] - lo[i]
        for j in range(m):
            pole = (j == 0 and not math.isnan(residue_lo[i])) or (j == m - 1 and not math.isnan(residue_hi[i]))
            if pole:
                f[j] = math.inf
                g[j] = residue_lo[i] * width if j == 0 else -residue_hi[i] * width
            else:
                f[j] = inside_values[k]
                g[j] = f[j] * (spans[i, j] - lo[i]) * (hi[i] - spans[i, j])
                k += 1
        for j in range(m - 1):
            if (g[j] > 0.0 and g[j + 1] < 0.0) or (g[j] < 0.0 and g[j + 1] > 0.0):
                out[0, count], out[1, count], out[2, count], out[3, count] = spans[i, j], spans[i, j + 1], g[j], g[j + 1]
                out[4, count], out[5, count], out[6, count] = lo[i], hi[i], min(abs(f[j]), abs(f[j + 1]))
                count += 1
    return out[:, :count].copy()


@numba.njit(cache=True, nogil=True)
def _real_roots(roots, root_values, final_lo, final_hi, lo, hi, ends, poles):
    """Which shrunk sign changes of G are roots (:func:`roots_between`): those whose last bracket [final_lo,
    final_hi] (widened by 1e-12, the interval [lo, hi]'s own poles excluded) holds no pole of ``poles`` (sorted),
    and those where |F| = |G|/((L − lo)(hi − L)) has fallen below 1e-3 of ``ends`` (the smaller |F| at the
    bracket's samples). The brackets come in ascending order, so the poles are walked through once."""
    out = np.empty(roots.size, dtype=np.bool_)
    k = np.searchsorted(poles, lo[0]) if roots.size else 0
    for r in range(roots.size):
        margin = 1e-12 * final_hi[r]
        start = max(final_lo[r] - margin, lo[r] * (1 + 2e-12))
        stop = min(final_hi[r] + margin, hi[r] * (1 - 2e-12))
        while k > 0 and poles[k - 1] >= start:
            k -= 1
        while k < poles.size and poles[k] < start:
            k += 1
        unsure = k < poles.size and poles[k] <= stop
        distance = (roots[r] - lo[r]) * (hi[r] - roots[r])
        out[r] = not unsure or abs(root_values[r] / distance) < 1e-3 * ends[r]
    return out


def _merged_poles(poles, residues):
    """Poles [m] closer than 1e-12 (relative) to the one before merged into one, with the sum of their
    residues [m] (coinciding resonances of two modes add their terms); both ascending."""
    if poles.size == 0:
        return poles, residues
    first = np.concatenate([[True], poles[1:] > poles[:-1] * (1 + 1e-12)])
    starts = np.nonzero(first)[0]
    return poles[starts], np.add.reduceat(residues, starts)


def midspan_screen(scene: Scene, options: Options, search: SpanSearch) -> np.ndarray:
    """Cheap necessary conditions for every root at once (with the screening T_L and b): the midspan
    approaches the wall before contact, the pipe is convex towards the wall there (the checks
    :func:`impact_at` makes at its first iterate) and the midspan stays inside the hole over the
    period. True = survives."""
    if search.roots.size == 0:
        return np.zeros(0, dtype=bool)
    spans = search.roots
    duration, half = search.residual.pulse(spans)
    c, e = scene.clearance, scene.restitution
    y0, v0, curv0 = np.full((3, spans.size), np.nan) if search.states is None else search.states.copy()
    missing = np.isnan(y0)  # where the search did not evaluate the state at the root
    if np.any(missing):
        y0[missing], v0[missing], curv0[missing] = unit_state(scene, spans[missing], duration[missing], half[missing],
                                                              options)
    m_e = scene.equivalent_mass(spans)
    impulse = -c / y0 if scene.closure == "self_consistent" else m_e * (1.0 + e) * scene.rotary_speed * c
    # as impact_at rejects at its first iterate: approach, convex towards the wall, a positive impulse
    keep = (-impulse * v0 > 0) & (impulse * curv0 > 0) & (impulse > 0)
    rows = np.nonzero(keep)[0]
    if rows.size == 0:
        return keep
    spans, duration, half, impulse = spans[rows], duration[rows], half[rows], np.broadcast_to(impulse, keep.shape)[rows]
    span_t = scene.impact_interval
    # coarse (sampling can miss a violation, never invent one): 48 times after the pulse, interleaved
    # so that the first dozen span the whole period, each root dropped at its first violation
    fractions = np.linspace(0.0, 1.0, 50)[1:-1].reshape(-1, 4).T.ravel()
    times = duration[:, None] + (span_t - duration[:, None]) * fractions[None, :]  # after the pulse, per root
    limit = c * 1.02 / np.abs(impulse)
    # the verdict of largest_excursion without its library calls where rounding cannot change it, it elsewhere
    p = scene.props
    verdict = beam.excursion_verdicts(times, spans, duration, half, odd_modes(options.modes).size,
                                      p["bending_stiffness"], p["effective_tension"], p["mass_per_length"], scene.period,
                                      scene.pattern, options.load_shape, limit=limit)
    within = verdict == 0
    unsure = np.nonzero(verdict < 0)[0]
    if unsure.size:
        omega, weight = _midspan_weights(scene, spans[unsure], half[unsure], options)
        largest = beam.largest_excursion(times[unsure], omega, duration[unsure], weight, scene.period, scene.pattern,
                                         limit=limit[unsure])
        within[unsure] = largest <= limit[unsure]  # NaN (a resonant mode): dropped
    keep[rows] = within
    return keep


def _midspan_weights(scene: Scene, spans, halves, options: Options) -> tuple[np.ndarray, np.ndarray]:
    """(ω_n [rad/s], w_n [m/(N s)]) of shape (spans, odd modes): the natural frequencies and the
    midspan deflection of each mode per unit modal coordinate per unit impulse, 2 g_n sin(nπ/2)/(M L)
    (g_n :func:`beam.modal_load_factors` for contact half-lengths ``halves`` [m]) — the weights that
    :func:`beam.largest_excursion` sums, as :func:`beam.periodic_fields` does at x = L/2."""
    spans = np.asarray(spans, dtype=float)
    modes = odd_modes(options.modes)
    g = beam.modal_load_factors(modes, spans, np.asarray(halves, dtype=float), options.load_shape)
    weight = 2.0 * g / (scene.props["mass_per_length"] * spans[:, None]) * np.where(modes % 4 == 1, 1.0, -1.0)
    return natural_frequencies(scene, spans, modes), weight


def refine_root(scene: Scene, options: Options, approx: float, bracket, steps: int = 8,
                duration: float | None = None, half_length: float = 0.0) -> Impact:
    """The root of the exact residual (T_L–κ fixed point at every span) near the screening root
    ``approx``, by secant steps kept inside ``bracket`` (an interval free of wide poles). Each T_L–κ
    iteration starts from the last span's T_L and contact half-length (the first from ``duration`` [s]
    and ``half_length`` [m] when given). One root of :func:`refine_roots`."""
    return refine_roots(scene, options, [approx], [bracket], steps,
                        None if duration is None else [duration], [half_length])[0]


def refine_roots(scene: Scene, options: Options, approx, brackets, steps: int = 8, durations=None,
                 halves=None) -> list[Impact]:
    """:func:`refine_root` for every screening root of ``approx`` [m] at once, in one compiled loop
    (:func:`_refine_kernel`; ``brackets``: one interval per root; durations [s], halves [m]: starting
    T_L and b per root, None for the defaults). The first secant step is small against the distance
    to the nearer pole (a root pinned next to a pole); a root still off by more than 1e-8 in F when
    the steps run out, or whose secant leaves its bracket, carries the problem. Returns one
    :class:`Impact` per root, in order."""
    rows = refined_rows(scene, options, approx, brackets, steps, durations, halves)
    return _impacts_of(scene, rows) if rows.shape[1] else []


def refined_rows(scene: Scene, options: Options, approx, brackets, steps: int = 8, durations=None,
                 halves=None) -> np.ndarray:
    """:func:`refine_roots` as the compiled kernel's columns (rows :data:`_ROWS`), before they become
    :class:`Impact` records (:func:`_impacts_of`): the span search makes records of the sound ones only."""
    approx = np.atleast_1d(np.asarray(approx, dtype=float))
    if approx.size == 0:
        return np.zeros((len(_ROWS), 0))
    brackets = np.asarray(brackets, dtype=float).reshape(-1, 2)
    lo, hi = brackets.min(axis=1), brackets.max(axis=1)
    return _refine_kernel(np.ascontiguousarray(approx), np.ascontiguousarray(lo), np.ascontiguousarray(hi),
                          *_starts(approx.shape, durations, halves), int(steps), *_kernel_args(scene, options))


def truncation_bound(scene: Scene, impact: Impact, inputs: Mapping[str, Any],
                     options: Options, reach: int = 8) -> float:
    """Upper bound [Pa] on the bending stress carried by the modes left out, n in (N, reach·N].

    Each left-out mode adds at most (r_o/I) EI k_n² |a_n(t) − a_n,qs(t)| to the stress anywhere on the
    span (|sin k_n x| ≤ 1), where a_n − a_n,qs is its dynamic remainder after the quasi-static split
    (docs/model.md §5); its maximum over the period is taken on the solver's time grid. Summing the modes
    up to reach·N catches a near-resonant mode just above the truncation, which a comparison with
    fewer modes cannot see; the modes beyond fall off like n⁻⁴ once ω_n T_L ≫ 1.
    """
    p = scene.props
    r_o, r_i = inputs["outer_diameter"] / 2.0, inputs["inner_diameter"] / 2.0
    inertia = float(section.second_moment_of_area(r_o, r_i))
    n = odd_modes(reach * options.modes)
    n = n[n > options.modes]
    if n.size == 0:
        return 0.0
    t = time_grid(scene, impact.contact_duration, options)
    omega = natural_frequencies(scene, impact.span_length, n)
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
    omega, weight = _midspan_weights(scene, spans, halves, options)
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


def stresses_from_fields(scene: Scene, inputs: Mapping[str, Any], x, t, deflection, moment,
                         shear=None, mirrored: bool | None = None, field_at=None,
                         tolerance: float | None = None) -> dict[str, float]:
    """Deflection and stress maxima over the span and the period from the fields (docs/model.md §5, paper
    eq. 37–38) — the same for every method, whatever made the fields.

    x [m], t [s] (the half period for the alternating pattern: the other half mirrors it), deflection
    y [m], moment M_b = −EI y'' [N m], shear V = −EI y''' [N] (None: no shear outputs), each of shape
    t × x. ``mirrored``: whether the other half period is the mirror image (default: the alternating
    pattern of ``scene``). Bending stress σ_b = M_b r_o/I; combined normal stress |T0/A_s| + |σ_b|
    (the larger of T0/A_s ± σ_b); shear stress 2V/A_s (thin tube); alternating bending stress: half the
    range of σ_b over the period at the worst section (σ(t + τ/2) = −σ(t) when mirrored).

    With ``field_at(kind, x, t)`` (the fields anywhere, shape t × x) each maximum found on the grid is
    located to ``tolerance`` (relative) by :mod:`study.solvers.extremes`, and ``location_residual`` is
    the largest relative change of the last refinement round — what is left of the sampling error.
    """
    p = scene.props
    mirrored = scene.pattern == "alternating" if mirrored is None else mirrored
    x, t = np.asarray(x, dtype=float), np.asarray(t, dtype=float)
    r_o, r_i = inputs["outer_diameter"] / 2.0, inputs["inner_diameter"] / 2.0
    inertia = float(section.second_moment_of_area(r_o, r_i))
    area = p["steel_area"]
    deflection, moment = np.asarray(deflection, dtype=float), np.asarray(moment, dtype=float)
    i_b, largest, smallest = _field_extremes(moment, columns=True)
    scale = r_o / inertia  # σ_b = M_b r_o/I
    # over the full period σ(t + τ/2) = −σ(t) when mirrored, so half its range is max |σ| there
    half_range = np.maximum(largest, -smallest) if mirrored else 0.5 * (largest - smallest)
    axial = abs(inputs["axial_tension"]) / area
    i_y = _field_extremes(deflection)[0]
    out = {
        "max_deflection": float(np.abs(deflection[i_y])),
        "max_bending_stress": float(np.abs(moment[i_b]) * scale),
        "max_normal_stress": float(axial + np.abs(moment[i_b]) * scale),
        "max_normal_stress_x": float(x[i_b[1]]),
        "max_normal_stress_t": float(t[i_b[0]]),
        "alternating_bending_stress": float(np.nanmax(half_range) * scale),
    }
    if shear is not None:
        shear = np.asarray(shear, dtype=float)
        i_s = _field_extremes(shear)[0]
        out.update(max_shear_stress=float(2.0 * np.abs(shear[i_s]) / area), max_shear_stress_x=float(x[i_s[1]]),
                   max_shear_stress_t=float(t[i_s[0]]))
    if field_at is None:
        return out
    tol = 0.1 * (DEFAULT_TOLERANCE if tolerance is None else tolerance)
    y = extremes.locate(field_at, "deflection", x, t, *i_y, tol)
    m = extremes.locate(field_at, "moment", x, t, *i_b, tol)
    out.update(max_deflection=max(out["max_deflection"], abs(y.value)),
               max_bending_stress=abs(m.value) * scale, max_normal_stress=axial + abs(m.value) * scale,
               max_normal_stress_x=m.x, max_normal_stress_t=m.t)
    residuals = [y.residual, m.residual]
    if mirrored:
        out["alternating_bending_stress"] = max(out["alternating_bending_stress"], out["max_bending_stress"])
    else:
        a = extremes.locate_half_range(field_at, "moment", x, t, moment, tol)
        out["alternating_bending_stress"] = max(out["alternating_bending_stress"], a.value * scale)
        residuals.append(a.residual)
    if shear is not None:
        v = extremes.locate(field_at, "shear", x, t, *i_s, tol)
        out.update(max_shear_stress=max(out["max_shear_stress"], 2.0 * abs(v.value) / area),
                   max_shear_stress_x=v.x, max_shear_stress_t=v.t)
        residuals.append(v.residual)
    out["location_residual"] = float(max(residuals))
    return out


#: Relative difference below which two maxima of a field are equal: the first in time (then x) is reported,
#: so that rounding cannot move the reported (x, t) of a maximum reached twice (a symmetric motion).
TIE_TOLERANCE = 1e-9


def _field_extremes(values, columns: bool = False) -> tuple:
    """(index of the largest |value| ignoring NaN — the first within :data:`TIE_TOLERANCE` of it, in
    time, then x — and with ``columns`` the largest and smallest value of
    each column, NaN in a column with a NaN) of a field of shape t × x; a ValueError when every value is
    NaN (as np.nanargmax)."""
    values = np.asarray(values, dtype=float)  # any layout: the fields are views of one product
    index, largest, smallest = _extremes_kernel(values, columns)
    if index < 0:
        raise ValueError("all the field's values are NaN (a resonant or buckled mode)")
    return np.unravel_index(index, values.shape), largest, smallest


@numba.njit(cache=True, nogil=True)
def _extremes_kernel(values, columns):
    """Three passes without data-dependent jumps in the first two, so that they run at memory speed:
    the largest |value| (NaN never compares larger), each column's largest and smallest (a NaN sticks),
    then the first value within TIE_TOLERANCE of the largest, in time, then x (-1: none)."""
    rows, cols = values.shape
    peak = -1.0
    for i in range(rows):
        for j in range(cols):
            size = abs(values[i, j])
            peak = size if size > peak else peak
    largest, smallest = np.full(cols, -np.inf), np.full(cols, np.inf)
    if columns:
        for i in range(rows):
            for j in range(cols):
                v = values[i, j]
                largest[j] = v if (v > largest[j] or v != v) else largest[j]
                smallest[j] = v if (v < smallest[j] or v != v) else smallest[j]
    if peak < 0.0:  # every value NaN
        return -1, largest, smallest
    floor = peak * (1.0 - TIE_TOLERANCE)
    for i in range(rows):
        for j in range(cols):
            if abs(values[i, j]) >= floor:
                return i * cols + j, largest, smallest
    return -1, largest, smallest


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
        codes, values = rows[_ROWS.index("problem")], rows[_ROWS.index("value")]
        sound = _impacts_of(scene, rows[:, codes == 0])  # records of the roots refined without a problem
        violations = zip(sound, constraint_violations(scene, sound, options))
        for root, code, value in zip(survivors, codes, values):
            impact, problem = next(violations) if code == 0 else (None, _PROBLEMS[int(code)](value))
            if problem is None:
                candidates.append(impact)
            else:
                reasons.setdefault(_reason(problem), []).append(root)
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


def _reason(problem: str) -> str:
    """The kind of a rejection, for counting: the message without where and by how much."""
    if problem.startswith("|y| reaches"):
        return "the pipe reaches past a wall elsewhere (condition 1)"
    if problem.startswith("condition 2 residual"):
        return "condition 2 not met after refinement"
    return problem.split(" at ")[0].split(" (")[0]


Finish = Callable[[Scene, Impact, Mapping[str, Any], Options, PointResult], None]


def design_point(inputs: Mapping[str, Any], method: str, finish: Finish,
                 options: Options | None = None) -> PointResult:
    """The design-point pipeline shared by the periodic methods : buckling check,
    :func:`find_span`, the smallest valid span's impact in ``result.values``; then ``finish(scene,
    chosen, inputs, options, result)`` adds the method's fields, stresses and error estimate."""
    start = time.perf_counter()
    result = PointResult(method=method)
    options = options or options_from(inputs)
    scene = make_scene(inputs)
    result.values.update(scene.props)
    max_span = min(options.max_span, scene.props["buckling_length"] * (1 - 1e-9))
    if max_span <= options.min_span:
        result.status = "buckled"
        result.message = (f"effective tension {scene.props['effective_tension']:.4g} N buckles every span "
                          f"longer than {scene.props['buckling_length']:.4g} m, below the shortest searched")
        result.wall_time = time.perf_counter() - start
        return result
    options = Options(**{**options.__dict__, "max_span": max_span})
    too_many = span_search_too_large(scene, options, inputs.get("max_poles"))
    if too_many is not None:
        result.status = "failed"
        result.message = too_many
        result.wall_time = time.perf_counter() - start
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
        result.wall_time = time.perf_counter() - start
        return result
    chosen = choice.candidates[0]
    survives = span_survives_doubling(scene, options, chosen.span_length, study_tolerance(inputs))
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
    omega = natural_frequencies(scene, chosen.span_length, [1.0])
    result.values["first_natural_frequency"] = float(omega[0] / (2.0 * np.pi))
    smallest = ("the smallest is reported" if survives is None else
                f"the smallest, {chosen.span_length:.6g} m, is not converged: {survives}")
    result.message = f"{choice.summary}; {len(choice.candidates)} satisfy the constraints; {smallest}"
    finish(scene, chosen, inputs, options, result)
    result.wall_time = time.perf_counter() - start
    return result
