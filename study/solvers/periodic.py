"""The periodic impact solution of one design point: closure, span search and constraint checks.

Shared by the periodic methods (``fast`` and ``series``; ``../shared/MODEL.md`` §3–6). The sample span
(simply supported, length L) is struck at midspan by the Hertz/Lee pulse of the equivalent mass once
per period at the wall y = +c (pattern ``one_wall``) or alternately at +c and −c every half period
(``alternating``). The response is linear in the impulse J, so everything is built from the response
to a unit impulse directed along +y; the real load pushes the pipe off the wall (−y at +c).

Unknowns and closures (MODEL.md §4). Condition 2, y(L/2, 0) = c, is one equation; the unknowns are L
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
(MODEL.md §4): a sign change across a pole is not a root. The poles are located analytically
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
from study.physics.roots import shrink_brackets
from study.solvers.core import scene as section_scene
from study.solvers.result import PointResult, choice_input

#: The mass of the closure's impulse (Scene.equivalent_mass).
IMPACT_MASSES = ("momentum", "modal")


@dataclass(frozen=True)
class Options:
    """Resolution and search settings of the periodic methods."""

    modes: int = 41  #: highest (odd) mode number kept
    min_span: float = 3.0  #: shortest span searched [m]
    max_span: float = 304.8  #: longest span searched [m] (1000 ft)
    load_shape: str = "parabolic"  #: spatial shape of the contact load (beam.LOAD_SHAPES)
    samples: int = 4  #: samples of F inside each interval between (wide) poles
    resonance_width: float = 1e-6  #: resonances narrower than this (relative span) are not searched
    time_points: int = 480  #: points over one (half) period outside the pulse, for condition 1
    pulse_points: int = 64  #: points across the pulse
    space_points: int = 48  #: points over half the span
    tolerance: float = 1e-6  #: relative slack of condition 1, |y| <= c (1 + tolerance)
    fixed_point_tol: float = 1e-9  #: relative change of T_L that ends the T_L-κ iteration


@dataclass(frozen=True)
class Scene:
    """Span-independent data of the design point (SI)."""

    props: Mapping[str, float]
    outer_radius: float
    hole_radius: float
    compliance_sum: float
    rotary_speed: float
    restitution: float
    pattern: str
    closure: str
    impact_mass: str = "momentum"  #: IMPACT_MASSES

    def equivalent_mass(self, span_length):
        """m_e [kg] of the closure's impulse J = m_e (1 + e) V_p: 2ML/π (``momentum``, the paper's
        equivalent mass) or ML/2 (``modal``, the modal mass of sin(πx/L) referred to midspan — the mass a
        one-mode model strikes the wall with; MODEL.md §4, §8)."""
        mass = self.props["mass_per_length"]
        if self.impact_mass == "modal":
            return 0.5 * mass * np.asarray(span_length, dtype=float)
        return section.equivalent_mass(mass, span_length)

    @property
    def clearance(self) -> float:
        return self.props["clearance"]

    @property
    def period(self) -> float:
        """Period of the motion τ = 2π/Ω [s] (one revolution)."""
        return 2.0 * np.pi / self.rotary_speed

    @property
    def impacts_per_revolution(self) -> int:
        """Impacts per revolution: 2 (alternating walls) or 1 (one wall)."""
        return 2 if self.pattern == "alternating" else 1

    @property
    def impact_interval(self) -> float:
        """Time from one impact to the next [s]: τ/2 (alternating walls) or τ (one wall)."""
        return self.period / self.impacts_per_revolution


def make_scene(inputs: Mapping[str, Any]) -> Scene:
    props = section_scene(inputs)
    compliance = float(hertz.compliance(inputs["pipe_youngs_modulus"], inputs["pipe_poisson_ratio"])
                       + hertz.compliance(inputs["rock_youngs_modulus"], inputs["rock_poisson_ratio"]))
    return Scene(props=props, outer_radius=inputs["outer_diameter"] / 2.0, hole_radius=inputs["hole_diameter"] / 2.0,
                 compliance_sum=compliance, rotary_speed=float(inputs["rotary_speed"]),
                 restitution=float(inputs["restitution"]), pattern=inputs.get("impact_pattern", "alternating"),
                 closure=inputs.get("closure", "prescribed"),
                 impact_mass=choice_input(inputs, "impact_mass", "momentum", IMPACT_MASSES))


def given_span(inputs: Mapping[str, Any], result: PointResult, start: float, method: str,
               buckled: str) -> float | None:
    """The span of a method that is given one (``solver.span_length``) rather than searching for it.

    Returns the span [m], or None after recording on ``result`` the status ``incomplete`` (no span
    given) or ``buckled`` (``buckled``: the message, formatted with ``tension`` [N] and ``span`` [m]),
    with its wall time since ``start``. ``method``: how the messages name the method.
    """
    span = inputs.get("span_length")
    if span is None:
        result.status = "incomplete"
        result.message = f"{method} needs a span (solver.span_length): it does not search for one"
    else:
        props = make_scene(inputs).props
        if not section.is_buckled(span, props["bending_stiffness"], props["effective_tension"]):
            return float(span)
        result.status = "buckled"
        result.values["span_length"] = float(span)
        result.message = buckled.format(tension=props["effective_tension"], span=float(span))
    result.wall_time = time.perf_counter() - start
    return None


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


def resonances(scene: Scene, modes, min_span: float, max_span: float) -> tuple[np.ndarray, np.ndarray]:
    """Spans [m] in [min_span, max_span] where some ω_n(L) equals a harmonic m Ω of the train, sorted,
    and the mode number n resonating at each.

    From ω² M = EI k⁴ + T k² with k = nπ/L: k² = [−T + √(T² + 4 EI M (mΩ)²)]/(2 EI), L = nπ/k
    (MODEL.md §4). These are the poles of the undamped periodic response.
    """
    p = scene.props
    ei, tension, mass = p["bending_stiffness"], p["effective_tension"], p["mass_per_length"]
    modes = np.asarray(modes, dtype=float)
    omega_max = float(np.nanmax(natural_frequencies(scene, min_span, modes[-1:])))
    highest = int(np.ceil(omega_max / scene.rotary_speed)) + 1
    forcing = resonant_harmonics(scene, highest) * scene.rotary_speed
    k_sq = (-tension + np.sqrt(tension**2 + 4.0 * ei * mass * forcing**2)) / (2.0 * ei)
    spans = (modes[:, None] * np.pi / np.sqrt(k_sq[None, :]))
    mode = np.broadcast_to(modes[:, None], spans.shape)
    inside = (spans >= min_span) & (spans <= max_span)
    spans, mode = spans[inside], mode[inside]
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
    """:func:`impact_at` at every span of ``spans`` [m] at once: each step of the iteration is one array
    evaluation for all the spans still iterating (the refinement of a design point's roots). durations
    [s], halves [m]: the starting T_L and b per span (None: the defaults of :func:`impact_at`; a
    NaN duration: the default for that span). Returns one :class:`Impact` per span, in order."""
    spans = np.atleast_1d(np.asarray(spans, dtype=float))
    count = spans.size
    c, e = scene.clearance, scene.restitution
    m_e = np.broadcast_to(np.asarray(scene.equivalent_mass(spans), dtype=float), spans.shape)
    longest = scene.impact_interval
    problems: list[list[str]] = [[] for _ in range(count)]

    def duration_for(curvature, velocity, mass):
        a_sum, b_sum = hertz.curvature_sums(scene.outer_radius, scene.hole_radius, curvature)
        stiffness = hertz.hertz_stiffness(a_sum, b_sum, scene.compliance_sum)
        return hertz.lee_duration(mass, velocity, stiffness), stiffness

    # Start from the assumed mode y = c sin(πx/L): κ = c (π/L)², V_p = Ω c.
    velocity = np.full(count, scene.rotary_speed * c)
    start, stiffness = duration_for(c * (np.pi / spans) ** 2, velocity, m_e)
    given = np.full(count, np.nan) if durations is None else np.broadcast_to(np.asarray(durations, dtype=float), spans.shape)
    duration = np.where((given > 0) & (given < longest), given, start)
    half = np.broadcast_to(np.asarray(0.0 if halves is None else halves, dtype=float), spans.shape)
    half = np.minimum(np.maximum(half, 0.0), 0.45 * spans)
    residual, impulse, curvature, peak, half_width = (np.full(count, np.nan) for _ in range(5))
    relaxation, last_step = np.ones(count), np.zeros(count)
    previous, previous_step = np.full(count, np.nan), np.full(count, np.nan)  # the last iterate, for the secant
    iterations, converged = np.zeros(count, dtype=int), np.zeros(count, dtype=bool)
    active = np.arange(count)
    for iteration in range(1, max_iterations + 1):
        long_pulse = ~(duration[active] < longest)
        for i in active[long_pulse]:
            problems[i].append(f"pulse longer than the time between impacts (T_L = {duration[i]:.3g} s)")
        active = active[~long_pulse]
        if active.size == 0:
            break
        y1, v1, curv1 = unit_state(scene, spans[active], duration[active], half[active], options)
        for i in active[~np.isfinite(y1)]:
            problems[i].append("the span is at a resonance or buckled")
        finite = np.isfinite(y1)
        active, y1, v1, curv1 = active[finite], y1[finite], v1[finite], curv1[finite]
        if scene.closure == "self_consistent":
            imp, vel = -c / y1, c * v1 / y1
            res = m_e[active] * (1.0 + e) * vel / imp - 1.0
        else:
            vel = velocity[active]
            imp = m_e[active] * (1.0 + e) * vel
            res = -imp * y1 / c - 1.0
        curv = imp * curv1
        residual[active], impulse[active], velocity[active], curvature[active] = res, imp, vel, curv
        wrong = ~((curv > 0) & (vel > 0) & (imp > 0))
        for i in active[wrong]:
            problems[i].append("the pipe is not convex towards the wall at the contact" if curvature[i] <= 0 else
                               "the midspan does not approach the wall before contact" if velocity[i] <= 0 else
                               "condition 2 needs a negative impulse")
        active, imp, vel, curv = active[~wrong], imp[~wrong], vel[~wrong], curv[~wrong]
        if active.size == 0:
            break
        peak[active] = hertz.lee_peak_force(imp, duration[active])
        ellipse = hertz.contact_ellipse(peak[active], scene.outer_radius, scene.hole_radius, curv, scene.compliance_sum)
        half[active] = np.minimum(ellipse.contact_half_length, 0.45 * spans[active])
        half_width[active] = ellipse.contact_half_width
        mapped, stiffness[active] = duration_for(curv, vel, m_e[active])
        step = mapped - duration[active]
        iterations[active] = iteration
        done = np.abs(step) <= options.fixed_point_tol * mapped
        converged[active[done]] = True
        if iteration == max_iterations:  # report the T_L the solution was computed with
            break
        active, step = active[~done], step[~done]
        relaxation[active] = np.where(last_step[active] * step < 0, 0.5 * relaxation[active], relaxation[active])
        last_step[active] = step
        with np.errstate(divide="ignore", invalid="ignore"):
            secant = np.where(np.isfinite(previous[active]) & (step != previous_step[active]),
                              duration[active] - step * (duration[active] - previous[active]) / (step - previous_step[active]),
                              np.nan)
        previous[active], previous_step[active] = duration[active], step
        duration[active] = np.where((secant > 0) & (secant < longest), secant, duration[active] + relaxation[active] * step)
    failed = np.array([bool(p) for p in problems], dtype=bool)
    elastic = hertz.hertz_impact(m_e, velocity, stiffness)
    out = []
    for i in range(count):
        impact = Impact(span_length=float(spans[i]), residual=float(residual[i]), impulse=float(impulse[i]),
                        impact_velocity=float(velocity[i]), equivalent_mass=float(m_e[i]),
                        axial_curvature=float(curvature[i]), problems=problems[i])
        if not failed[i]:
            impact.contact_duration = float(duration[i])
            impact.hertz_duration, impact.hertz_peak_force = float(elastic.duration[i]), float(elastic.max_force[i])
            impact.max_approach = float(elastic.max_approach[i])
            impact.peak_contact_force = float(peak[i])
            impact.contact_half_length, impact.contact_half_width = float(half[i]), float(half_width[i])
            impact.iterations = int(iterations[i])
            if not converged[i] and max_iterations > 1:
                impact.problems.append(f"T_L–curvature iteration not converged in {max_iterations} steps")
        out.append(impact)
    return out


def screen_residual(scene: Scene, options: Options):
    """A cheap, smooth stand-in for F(L), vectorised over spans, for the search.

    T_L(L) and the contact half-length b(L) come from one fixed-point step at a dozen spans,
    interpolated in log L; the roots found with it are refined with the exact model afterwards.
    Returns a function of an array of spans, or None when no span gives a valid pulse.
    """
    grid = np.geomspace(options.min_span, options.max_span, 12)
    impacts = impacts_at(scene, grid, options, max_iterations=1)
    durations = np.array([i.contact_duration for i in impacts])
    halves = np.array([i.contact_half_length for i in impacts])
    ok = np.isfinite(durations) & (durations > 0)
    if not np.any(ok):
        return None
    logs = np.log(grid[ok])
    e = scene.restitution

    def pulse(spans):
        """(T_L, b) interpolated at ``spans``."""
        return (np.exp(np.interp(np.log(spans), logs, np.log(durations[ok]))),
                np.interp(np.log(spans), logs, halves[ok]))

    def residual(spans, modes=None):
        """F(L) at ``spans``; with ``modes`` (see :func:`unit_state`) F + 1 from those modes alone."""
        spans = np.asarray(spans, dtype=float)
        duration, half = pulse(spans)
        y1, v1, _ = unit_state(scene, spans, duration, half, options, modes=modes)
        m_e = scene.equivalent_mass(spans)
        offset = 1.0 if modes is None else 0.0
        if scene.closure == "self_consistent":
            return -m_e * (1.0 + e) * v1 - offset  # m_e (1+e) V_p / J - 1 with V_p = c v1/y1, J = -c/y1
        return -m_e * (1.0 + e) * scene.rotary_speed * y1 - offset  # -J y1/c - 1 with J = m_e (1+e) Omega c

    def residue(spans, modes):
        """R [m] of the term of mode ``modes`` in F at its pole ``spans``: F ≈ R/(L − L_p) there.

        The term is −m_e(1 + e) Ω w q(0) (prescribed) or −m_e(1 + e) w q̇(0) (self-consistent), w the
        mode's midspan weight, and q(0), q̇(0) (:func:`beam.modal_state_at_pulse_start`) carry the pole
        through κ ≈ 1/(x − x_p), x = ω s (s = τ/2 for cot(ωτ/2), τ/4 for −tan(ωτ/4)): the factor of κ,
        A cos φ/(2ω) or A sin φ/2 (A e^{−iφ} = H(ω), :func:`beam.pulse_spectrum`), over s dω/dL."""
        spans, n = np.asarray(spans, dtype=float), np.asarray(modes, dtype=float)
        duration, half = pulse(spans)
        p = scene.props
        k_sq = (n * np.pi / spans) ** 2
        omega = natural_frequencies(scene, spans, n[:, None])[:, 0]  # each pole's own mode
        real, imag = beam.loaded_pulse_spectrum(omega, spans, n, duration, half, options.load_shape)  # |g_n| H(ω)
        factor = -scene.equivalent_mass(spans) * (1.0 + e) * 2.0 / (p["mass_per_length"] * spans) * (
            -0.5 * imag if scene.closure == "self_consistent" else scene.rotary_speed * real / (2.0 * omega))
        slope = -(2.0 * p["bending_stiffness"] * k_sq**2 + p["effective_tension"] * k_sq) \
            / (p["mass_per_length"] * spans * omega)  # dω/dL
        return factor / (0.5 * scene.impact_interval * slope)

    residual.pulse = pulse
    residual.residue = residue
    return residual


def resonance_widths(residual, spans, modes) -> np.ndarray:
    """Relative width of each resonance [-]: |R|/L_p, R the residue in L of the resonant mode's term of
    the closure residual F at its pole L_p (``spans``, mode numbers ``modes``), in closed form
    (``residual.residue`` of :func:`screen_residual`).

    Near the pole F = R/(L − L_p) + B(L): the resonant mode alone moves F by more than 1 (it alone
    carries the midspan to the wall) only within |L − L_p| < |R|, and the root it pins sits within
    |R/B| of the pole. Light damping of ratio ζ bounds the resonant term by about |R|/(ζ L_p), so a
    resonance with |R|/L_p ≪ ζ has no root once the pipe is damped at all (MODEL.md §7): such a root is
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


def find_roots(scene: Scene, options: Options) -> SpanSearch:
    """Roots of the closure residual F(L) in [min_span, max_span], bracketed between poles.

    Poles whose resonance is narrower than ``options.resonance_width`` (:func:`resonance_widths`) are
    not searched: the root each pins lies within that relative distance of the pole and vanishes with
    any damping of that order. Between the remaining poles the search works on G = F (L − a)(b − L),
    a and b the poles around L: the same roots, continuous up to both poles, where it equals R_a (b − a)
    and −R_b (b − a) (R the poles' residues, :func:`resonance_widths`) — the ends' values in closed
    form, so a root pinned however close to a pole is bracketed. G is sampled between the poles and
    its sign changes are shrunk by regula falsi. A sign change that converges onto no pole is a root
    (F is continuous there); one with a (narrow) pole in its last bracket is a root only where |F| has
    fallen far below its values at the samples.
    """
    modes = odd_modes(options.modes)
    poles, pole_modes = resonances(scene, modes, options.min_span, options.max_span)
    residual = screen_residual(scene, options)
    if residual is None:
        return SpanSearch(np.array([]), np.zeros((0, 2)), int(poles.size), None)
    residues = residual.residue(poles, pole_modes.astype(float)) if poles.size else np.zeros(0)
    wide = np.abs(residues) >= options.resonance_width * poles  # resonance_widths, from the same residues
    edges, edge_residues = _merged_poles(poles[wide], residues[wide])
    edges = np.concatenate([[options.min_span], edges, [options.max_span]])
    edge_residues = np.concatenate([[np.nan], edge_residues, [np.nan]])  # NaN: the search range's end, no pole
    lo, hi = edges[:-1], edges[1:]
    keep = hi > lo * (1 + 1e-12)
    lo, hi, residue_lo, residue_hi = lo[keep], hi[keep], edge_residues[:-1][keep], edge_residues[1:][keep]
    width = hi - lo
    # samples strictly inside each interval, denser towards the poles where F changes fastest; at a
    # pole G is R (b − a) in closed form, at an end of the search range F is computed just inside it
    fractions = 0.5 - 0.5 * np.cos(np.pi * (np.arange(options.samples) + 0.5) / options.samples)
    ends_lo, ends_hi = np.isnan(residue_lo), np.isnan(residue_hi)
    start = np.where(ends_lo, lo * (1.0 + 1e-12), lo)
    stop = np.where(ends_hi, hi * (1.0 - 1e-12), hi)
    spans = np.column_stack([start, lo[:, None] + width[:, None] * fractions[None, :], stop])
    inside = np.zeros(spans.shape, dtype=bool)
    inside[:, 1:-1], inside[:, 0], inside[:, -1] = True, ends_lo, ends_hi
    values = np.full(spans.shape, np.inf)  # F (infinite at the poles)
    values[inside] = residual(spans[inside])
    with np.errstate(invalid="ignore"):  # inf x 0 at the poles, replaced next
        smooth = values * (spans - lo[:, None]) * (hi[:, None] - spans)  # G
    smooth[:, 0] = np.where(ends_lo, smooth[:, 0], residue_lo * width)
    smooth[:, -1] = np.where(ends_hi, smooth[:, -1], -residue_hi * width)
    i, j = np.nonzero(np.sign(smooth[:, :-1]) * np.sign(smooth[:, 1:]) < 0)
    brackets = np.stack([spans[i, j], spans[i, j + 1]], axis=1)
    intervals = np.stack([lo[i], hi[i]], axis=1)  # the interval between the two wide poles around each root
    # regula falsi on G: no singularity at the ends, so it converges in a few steps instead of
    # crawling along the pole's hyperbola

    def distances(x, rows):
        return (x - intervals[rows, 0]) * (intervals[rows, 1] - x)

    def smoothed(x, rows):
        return residual(x) * distances(x, rows)

    roots = np.array([])
    if len(i):  # the ends' values are the samples'
        every = np.arange(len(i))
        shrunk = shrink_brackets(smoothed, brackets[:, 0], brackets[:, 1], rtol=1e-10,
                                 f_lo=smooth[i, j], f_hi=smooth[i, j + 1])
        roots = shrunk.roots
        # F is continuous between poles: a sign change left in a bracket free of every pole (the narrow
        # ones included) is a root. One with a pole inside may have converged onto the pole, where |F|
        # grows: it is a root only if |F| there is far below its value at the samples.
        margin = 1e-12 * shrunk.hi
        unsure = (np.searchsorted(poles, shrunk.lo - margin, side="left")
                  < np.searchsorted(poles, shrunk.hi + margin, side="right"))
        ends = np.minimum(np.abs(values[i, j]), np.abs(values[i, j + 1]))
        with np.errstate(divide="ignore", invalid="ignore"):
            real = ~unsure | (np.abs(shrunk.values / distances(roots, every)) < 1e-3 * ends)
        roots, intervals = roots[real], intervals[real]
    return SpanSearch(roots=roots, brackets=intervals, pole_count=int(poles.size), residual=residual,
                      narrow_count=int(np.count_nonzero(~wide)))


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
    c, e, mass = scene.clearance, scene.restitution, scene.props["mass_per_length"]
    y0, v0, curv0 = unit_state(scene, spans, duration, half, options)
    m_e = scene.equivalent_mass(spans)
    impulse = -c / y0 if scene.closure == "self_consistent" else m_e * (1.0 + e) * scene.rotary_speed * c
    # as impact_at rejects at its first iterate: approach, convex towards the wall, a positive impulse
    keep = (-impulse * v0 > 0) & (impulse * curv0 > 0) & (impulse > 0)
    rows = np.nonzero(keep)[0]
    if rows.size == 0:
        return keep
    spans, duration, half, impulse = spans[rows], duration[rows], half[rows], np.broadcast_to(impulse, keep.shape)[rows]
    span_t = scene.impact_interval
    modes = odd_modes(options.modes)
    omega = natural_frequencies(scene, spans, modes)  # (R, M)
    g = beam.modal_load_factors(modes, spans, half, options.load_shape)
    weight = 2.0 * g / (mass * spans[:, None]) * np.where(modes % 4 == 1, 1.0, -1.0)
    # coarse (sampling can miss a violation, never invent one), in rounds that drop a root at its first
    # violation: 48 times after the pulse, interleaved so the early rounds span the whole period
    fractions = np.linspace(0.0, 1.0, 50)[1:-1].reshape(-1, 4).T
    inside = np.ones(rows.size, dtype=bool)
    for t in fractions:
        r = np.nonzero(inside)[0]
        if r.size == 0:
            break
        times = duration[r, None] + (span_t - duration[r, None]) * t[None, :]  # after the pulse, per root
        largest = beam.largest_excursion(times, omega[r], duration[r], weight[r], scene.period, scene.pattern)
        inside[r] = np.abs(impulse[r]) * largest <= c * 1.02  # NaN (a resonant mode): dropped
    keep[rows] = inside
    return keep


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
    """:func:`refine_root` for every screening root of ``approx`` [m] at once (``brackets``: one
    interval per root; durations [s], halves [m]: starting T_L and b per root, None for the defaults):
    each secant step is one :func:`impacts_at` call for all the roots still moving. Returns one
    :class:`Impact` per root, in order."""
    approx = np.atleast_1d(np.asarray(approx, dtype=float))
    if approx.size == 0:
        return []
    brackets = np.asarray(brackets, dtype=float).reshape(-1, 2)
    lo, hi = brackets.min(axis=1), brackets.max(axis=1)
    # the first secant step: small against the distance to the nearer pole (a root pinned next to a pole)
    x0 = approx.copy()
    x1 = approx + np.minimum(np.minimum(1e-6 * approx, 1e-3 * (hi - approx)), 1e-3 * (approx - lo)) \
        * np.where(hi - approx > approx - lo, 1.0, -1.0)
    first = impacts_at(scene, x0, options, durations=durations, halves=halves)
    result = list(first)
    moving = [k for k, i in enumerate(first) if not i.problems and np.isfinite(i.residual)]
    last = {k: first[k] for k in moving}  # the impact at x0 of each root still moving
    latest = dict(zip(moving, _impacts_from(scene, options, x1, moving, last)))  # at x1
    for _ in range(steps):
        again = []
        for k in moving:
            here = latest[k]
            if here.problems or not np.isfinite(here.residual) or abs(here.residual) < 1e-10:
                result[k] = here
                continue
            slope = (here.residual - last[k].residual) / (x1[k] - x0[k]) if x1[k] != x0[k] else 0.0
            if slope == 0:
                result[k] = _checked(here)
                continue
            x2 = x1[k] - here.residual / slope
            if not lo[k] <= x2 <= hi[k]:
                here.problems.append("the exact root left the interval between the searched poles around the screening root")
                result[k] = here
                continue
            x0[k], last[k], x1[k] = x1[k], here, x2
            again.append(k)
        latest.update(zip(again, _impacts_from(scene, options, x1, again, last)))
        moving = again
    for k in moving:  # the steps ran out
        result[k] = _checked(latest[k])
    return result


def _impacts_from(scene: Scene, options: Options, spans, rows, start) -> list[Impact]:
    """:func:`impacts_at` at ``spans[rows]``, each T_L–κ iteration started from ``start[row]``'s T_L and b."""
    if not rows:
        return []
    return impacts_at(scene, spans[rows], options, durations=[start[k].contact_duration for k in rows],
                      halves=[start[k].contact_half_length for k in rows])


def _checked(impact: Impact) -> Impact:
    """The refined impact, with a problem when condition 2 still has a residual above 1e-8."""
    if abs(impact.residual) > 1e-8:
        impact.problems.append(f"condition 2 residual {impact.residual:.2g} after refinement")
    return impact


def truncation_bound(scene: Scene, impact: Impact, inputs: Mapping[str, Any],
                     options: Options, reach: int = 8) -> float:
    """Upper bound [Pa] on the bending stress carried by the modes left out, n in (N, reach·N].

    Each left-out mode adds at most (r_o/I) EI k_n² |a_n(t) − a_n,qs(t)| to the stress anywhere on the
    span (|sin k_n x| ≤ 1), where a_n − a_n,qs is its dynamic remainder after the quasi-static split
    (MODEL.md §9); its maximum over the period is taken on the solver's time grid. Summing the modes
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
    q = beam.modal_periodic_response(t[:, None], omega, impact.contact_duration, scene.period,
                                     scene.pattern).displacement
    h = beam.pulse_train(t[:, None], impact.contact_duration, scene.period, scene.pattern)
    remainder = np.nanmax(np.abs(q - h / omega**2), axis=0)
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
    span = scene.impact_interval
    pulse = np.linspace(0.0, duration, options.pulse_points)
    rest = np.linspace(duration, span, options.time_points + 1)[1:-1]
    tail = span - np.geomspace(duration * 1e-3, duration, 8)  # the approach to the next impact
    return np.unique(np.concatenate([pulse, rest, tail]))


def space_grid(span_length: float, half_length: float, options: Options) -> np.ndarray:
    """Points over the half span [0, L/2] (the motion is symmetric), dense across the contact."""
    mid = 0.5 * span_length
    coarse = np.linspace(0.0, mid, options.space_points)
    contact = mid - np.linspace(0.0, max(half_length, 1e-3 * span_length) * 1.5, 16)
    return np.unique(np.concatenate([coarse, contact[contact >= 0]]))


def constraint_violation(scene: Scene, impact: Impact, options: Options) -> str | None:
    """None when condition 1 holds for this span; otherwise a message saying where it fails."""
    if impact.impact_velocity <= 0:
        return f"the midspan moves away from the wall when contact starts (V_p = {impact.impact_velocity:.3g} m/s)"
    t = time_grid(scene, impact.contact_duration, options)
    # the midspan alone first (one point instead of the whole span): most violations show there
    for x in (np.array([0.5 * impact.span_length]), space_grid(impact.span_length, impact.contact_half_length, options)):
        problem = _excess(scene, impact, options, x, t)
        if problem:
            return problem
    return None


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
    """Solver settings from the point's inputs (defaults where the config leaves them out)."""
    defaults = Options()
    return Options(
        modes=int(inputs.get("modes") or defaults.modes),
        min_span=float(inputs.get("min_span") or defaults.min_span),
        max_span=float(inputs.get("max_span") or defaults.max_span),
        load_shape=inputs.get("load_shape") or defaults.load_shape,
        resonance_width=float(defaults.resonance_width if inputs.get("resonance_width") is None
                              else inputs["resonance_width"]),
    )


def stresses_from_fields(scene: Scene, inputs: Mapping[str, Any], x, t, deflection, moment,
                         shear=None, mirrored: bool | None = None) -> dict[str, float]:
    """Deflection and stress maxima over the span and the period from the fields (MODEL.md §5, paper
    eq. 37–38) — the same for every method, whatever made the fields.

    x [m], t [s] (the half period for the alternating pattern: the other half mirrors it), deflection
    y [m], moment M_b = −EI y'' [N m], shear V = −EI y''' [N] (None: no shear outputs), each of shape
    t × x. ``mirrored``: whether the other half period is the mirror image (default: the alternating
    pattern of ``scene``). Bending stress σ_b = M_b r_o/I; combined normal stress |T0/A_s| + |σ_b|
    (the larger of T0/A_s ± σ_b); shear stress 2V/A_s (thin tube); alternating bending stress: half the
    range of σ_b over the period at the worst section (σ(t + τ/2) = −σ(t) when mirrored).
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
    rows, cols = values.shape
    largest, smallest = np.full(cols, -np.inf), np.full(cols, np.inf)
    index, peak = -1, -1.0
    for i in range(rows):
        for j in range(cols):
            v = values[i, j]
            if abs(v) > peak:  # False for NaN
                index, peak = i * cols + j, abs(v)
            if not columns:
                continue
            if math.isnan(v):
                largest[j] = smallest[j] = math.nan
            elif v > largest[j]:
                largest[j] = v
            if v < smallest[j]:
                smallest[j] = v
    if index >= 0:  # the first value within TIE_TOLERANCE of the peak: ties broken by time, then x
        floor = peak * (1.0 - TIE_TOLERANCE)
        for k in range(index):
            if abs(values[k // cols, k % cols]) >= floor:
                return k, largest, smallest
    return index, largest, smallest


@dataclass
class SpanChoice:
    """Outcome of the span search of one design point ."""

    search: SpanSearch
    survivors: np.ndarray
    candidates: list  #: refined impacts satisfying every constraint, ascending span
    reasons: dict  #: short reason → roots rejected for it
    summary: str
    options: Options  #: the options used (max_span capped below buckling)


def find_span(scene: Scene, options: Options) -> SpanChoice:
    """Span search, midspan screen, exact refinement and condition 1 (all from :mod:`periodic`).

    ``options.max_span`` is used as given (cap it below buckling first, see :func:`design_point`).
    """
    search = find_roots(scene, options)
    screened = midspan_screen(scene, options, search)
    survivors = search.roots[screened]
    candidates, reasons = [], {}
    durations, halves = search.residual.pulse(survivors) if survivors.size else ([], [])
    refined = refine_roots(scene, options, survivors, search.brackets[screened], durations=durations, halves=halves)
    for root, impact in zip(survivors, refined):
        problem = "; ".join(impact.problems) or constraint_violation(scene, impact, options)
        if problem is None:
            candidates.append(impact)
        else:
            reasons.setdefault(_reason(problem), []).append(root)
    summary = (f"{search.roots.size} roots of condition 2 between {search.pole_count - search.narrow_count} poles "
               f"in [{options.min_span:.4g}, {options.max_span:.4g}] m ({search.narrow_count} resonances narrower "
               f"than {options.resonance_width:.2g} L not searched); {survivors.size} pass the midspan screen")
    return SpanChoice(search, survivors, candidates, reasons, summary, options)


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
    choice = find_span(scene, options)
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
    result.message = f"{choice.summary}; {len(choice.candidates)} satisfy the constraints; the smallest is reported"
    finish(scene, chosen, inputs, options, result)
    result.wall_time = time.perf_counter() - start
    return result
