"""The exact model of the periodic impact solution at a span: the span's modes and resonances, and the impact.

Shared by the periodic methods (:mod:`study.solvers.methods.periodic`) and the crosscheck, which rebuilds fast's
impact at its span (docs/model.md §3–4). At a given span the closure (``prescribed`` or ``self_consistent``, see
:mod:`study.solvers.methods.periodic`) and the pulse duration T_L, which depends on the Hertz stiffness at the contact's
curvature, are iterated to their fixed point (:func:`impact_at`; many spans in lockstep in one compiled kernel,
:func:`impacts_at`), and a screening root is refined to the exact root by secant steps (:func:`refine_roots`,
:func:`refined_rows`). The resonant spans, where a natural frequency meets a harmonic of the pulse train
(:func:`resonances`), bound the span search's intervals (:mod:`study.solvers.methods.periodic.span_search`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numba
import numpy as np

from study.physics import beam, hertz, midspan
from study.solvers.model.options import Options
from study.solvers.model.scene import Scene


def odd_modes(n_modes: int) -> np.ndarray:
    """Mode numbers 1, 3, 5, … ≤ n_modes (a symmetric load excites no even mode)."""
    return np.arange(1, int(n_modes) + 1, 2, dtype=float)


def resonant_harmonics(scene: Scene, highest: int) -> np.ndarray:
    """Harmonic numbers of the rotation present in the pulse train: all (one_wall) or odd (alternating)."""
    return np.arange(1, highest + 1, scene.impacts_per_revolution, dtype=float)


def resonance_candidates(scene: Scene, modes, min_span: float) -> int:
    """How many (mode, harmonic) pairs :func:`resonances` enumerates: modes × the harmonics up to the highest
    mode's ω_n at the shortest span over Ω. Each costs about 16 bytes in the search, so a very slow rotary
    speed or a very short ``min_span`` [m] costs memory without bound."""
    modes = np.asarray(modes, dtype=float)
    omega_max = float(np.nanmax(scene.natural_frequencies(min_span, modes[-1:])))
    return int(modes.size * (np.ceil(omega_max / scene.rotary_speed) + 1))


def span_search_too_large(scene: Scene, options: Options) -> str | None:
    """None when the span search's resonance candidates (:func:`resonance_candidates`) fit ``options.max_poles``
    (config ``solver.max_poles``; default :data:`study.solvers.model.options.MAX_POLES`), otherwise why not, with the
    numbers."""
    budget = int(options.max_poles)
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
    omega_max = float(np.nanmax(scene.natural_frequencies(min_span, modes[-1:])))
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
    start of contact (t = 0) per unit impulse along +y (:func:`midspan.midspan_state_at_pulse_start`).

    span_length, pulse_duration, half_length broadcast together (shape S); results of shape S.
    ``modes``: the mode numbers summed (default: the odd modes up to ``options.modes``); an array of
    shape S + (k,) sums its own k modes for every span.
    """
    p = scene.props
    modes = odd_modes(options.modes) if modes is None else modes
    return midspan.midspan_state_at_pulse_start(span_length, pulse_duration, half_length, modes,
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
                           *kernel_args(scene, options))
    return impacts_of(scene, rows)


def _starts(shape, durations, halves) -> tuple[np.ndarray, np.ndarray]:
    """The starting T_L [s] and b [m] per span for the compiled kernels, of ``shape``: durations None
    gives NaN (the assumed mode's T_L), halves None gives 0."""
    durations = np.nan if durations is None else durations
    halves = 0.0 if halves is None else halves
    return tuple(np.ascontiguousarray(np.broadcast_to(np.asarray(v, dtype=float), shape)) for v in (durations, halves))


def impacts_of(scene: Scene, rows) -> list[Impact]:
    """The :class:`Impact` of each column of a compiled impact kernel's output (:data:`ROWS`)."""
    col = dict(zip(ROWS, rows))
    m_e = np.broadcast_to(np.asarray(scene.equivalent_mass(col["span"]), dtype=float), col["span"].shape)
    with np.errstate(invalid="ignore", divide="ignore"):
        elastic = hertz.hertz_impact(m_e, col["velocity"], col["stiffness"])
    out = []
    for i in range(col["span"].size):
        code = int(col["problem"][i])
        impact = Impact(span_length=float(col["span"][i]), residual=float(col["residual"][i]),
                        impulse=float(col["impulse"][i]), impact_velocity=float(col["velocity"][i]),
                        equivalent_mass=float(m_e[i]), axial_curvature=float(col["curvature"][i]),
                        problems=[PROBLEMS[code](col["value"][i])] if code else [])
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
PROBLEMS = {
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


def kernel_args(scene: Scene, options: Options) -> tuple:
    """The scene and settings as the compiled kernels take them: (beam state, modes, contact, closure)."""
    p = scene.props
    modes = odd_modes(options.modes)
    state = (float(p["bending_stiffness"]), float(p["effective_tension"]), float(p["mass_per_length"]),
             float(scene.period), scene.pattern == "one_wall", beam.SHAPE_CODES[options.load_shape], 1e-15, True)
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
    (:func:`midspan.midspan_states`), then moves each span's iteration on as it would move alone.
    ``durations``: the starting T_L [s] per span (NaN or out of range: that of the assumed mode);
    ``halves``: the starting b [m]. Returns one column per span (:data:`ROWS`): the span, residual,
    impulse, V_p, κ, T_L, b, contact half-width, Hertz stiffness, peak force, iterations, problem code
    (:data:`PROBLEMS`; 0: none) and its value."""
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
        y1s, v1s, curv1s = midspan.midspan_states(spans[running], duration[running], half[running], modes.size, ei,
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
ROWS = ("span", "residual", "impulse", "velocity", "curvature", "duration", "half", "half_width", "stiffness", "peak",
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
    return impacts_of(scene, rows) if rows.shape[1] else []


def refined_rows(scene: Scene, options: Options, approx, brackets, steps: int = 8, durations=None,
                 halves=None) -> np.ndarray:
    """:func:`refine_roots` as the compiled kernel's columns (rows :data:`ROWS`), before they become
    :class:`Impact` records (:func:`impacts_of`): the span search makes records of the sound ones only."""
    approx = np.atleast_1d(np.asarray(approx, dtype=float))
    if approx.size == 0:
        return np.zeros((len(ROWS), 0))
    brackets = np.asarray(brackets, dtype=float).reshape(-1, 2)
    lo, hi = brackets.min(axis=1), brackets.max(axis=1)
    return _refine_kernel(np.ascontiguousarray(approx), np.ascontiguousarray(lo), np.ascontiguousarray(hi),
                          *_starts(approx.shape, durations, halves), int(steps), *kernel_args(scene, options))
