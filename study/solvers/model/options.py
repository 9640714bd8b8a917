"""Every method's options, declared once with their defaults (docs/model.md §9).

Pure data, importing nothing of the solvers: the config (:mod:`study.config`) takes its ``solver.*``
defaults and choices from here, and the methods build their settings from a point's inputs with the same
declarations, so a default is written in one place. Loading this module loads no solver.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from typing import Any, Mapping

#: The methods behind :func:`study.solvers.solve_point`, name -> what it computes (the registry of solve
#: functions, :data:`study.solvers.METHODS`, is built from these names).
METHOD_DESCRIPTIONS = {
    "core": "physics core: section, mud, tension, and the Hertz/Lee impact at a given span",
    "fast": "periodic impact solution: span search, closed-form modal response with a quasi-static correction, "
            "stresses",
    "series": "the paper's double Fourier series (modes x harmonics) with the same span search as fast: the "
              "reproduction, and the slow reference",
    "auto": "the cheapest model of the hierarchy that serves the point: the free whirl where the pipe stays clear "
            "of the wall, the sliding state where it lies on it, else the reference model",
    "periodic": "the paper's periodic solution: fast, then series where only fast's error estimate failed, then "
                "damped where the dropped drag is not small",
    "time-domain": "modal span integrated through Hertz contact with both walls (event-driven, explicit Verlet "
                   "or implicit LSODA) until periodic: the check on the periodic assumption",
    "crosscheck": "the fast periodic solution replayed through one revolution of real Hertz contact in the time "
                  "domain: agrees within solver.check_tolerance, or flagged with the reasons",
    "reference": "the reference model: the pipe section in both lateral directions, driven by its mass "
                 "eccentricity, Hertz wall contact with friction at tool joints and body, mud drag; whirl, contact "
                 "and stresses after the transient",
    "reference-check": "the periodic solution (fast) against the reference model on the same point: contact or "
                       "not, peak force, max normal and alternating stress within solver.check_tolerance",
    "free-whirl": "the reference model's scene clear of the wall in closed form: synchronous whirl under the mass "
                  "eccentricity about the sag, drag exact on the circle; out of scope where it would touch",
    "sliding": "the reference model's scene lying on the wall at its tool joints, sliding round as the pipe turns: "
               "rest on the wall with Hertz contact and friction, and the synchronous whirl about it; out of scope "
               "where the contact would open",
    "damped": "the paper's damped periodic solution (appendices A, B): mud drag linearised by equal dissipation, "
              "end moments in quadrature that keep the response in phase with the impact; span, impact, stresses, "
              "the end moment required and the energy balance",
    "sdof": "one-degree-of-freedom screen: first-mode impact oscillator between the walls, exact period-1 orbit "
            "and Floquet stability at a given span",
}

#: Relative accuracy asked of every method's answer (config ``solver.tolerance``): 1 %, what a design decision
#: needs. A result whose error estimate is above it is ``not_converged`` (study.solvers.model.gate).
DEFAULT_TOLERANCE = 1e-2
def study_tolerance(inputs: Mapping[str, Any]) -> float:
    """The study's relative tolerance of a point (config ``solver.tolerance``; :data:`DEFAULT_TOLERANCE` unset)."""
    value = inputs.get("tolerance")
    return DEFAULT_TOLERANCE if value is None else float(value)


#: Relative accuracy asked of a figure that is a mean over the revolutions of a motion that does not repeat (config
#: ``solver.statistical_tolerance``): 5 %. A chaotic bouncing's figures are means with standard errors that fall as
#: the root of the revolutions, and 1 % would take some 25 times the revolutions of 5 % (thousands, where the
#: per-revolution peak force scatters by 60-100 %: docs/reference_model.md §3.1). 5 % is below what the inputs a
#: drilling engineer knows move them by — a restitution known to ±0.1 of 0.3-0.7, a friction of 0.2-0.4, a mass
#: eccentricity known to within some 10 % (API Spec 5DP's wall tolerance bounds it, docs/reference_model.md §9) —
#: and a 5 % stress is a 28 % damage on the S-N curve's slope m = 5, within the design curve's own scatter (one
#: standard deviation of log10 N, about 0.2 in DNV-RP-C203, is a factor 1.6 in life). The damage rate is held to
#: that same (1 + tolerance)^m - 1 (:func:`study.physics.fatigue.damage_exponent`).
DEFAULT_STATISTICAL_TOLERANCE = 5e-2


def relative_tolerance(inputs: Mapping[str, Any], name: str, default: float, meaning: str) -> float:
    """A relative tolerance of the point (config ``solver.<name>``; ``default`` unset). Raises ValueError naming the
    field, its value and what is allowed (``meaning`` says what it is a tolerance of) for a value that is not a number
    in (0, 1)."""
    value = inputs.get(name)
    if value is None:
        return default
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = float("nan")
    if not 0.0 < number < 1.0:  # NaN fails too
        raise ValueError(f"solver.{name} = {value!r}: must be a number > 0 and < 1 ({meaning}; default {default:g})")
    return number


def statistical_tolerance(inputs: Mapping[str, Any]) -> float:
    """The relative tolerance of statistical figures (config ``solver.statistical_tolerance``;
    :data:`DEFAULT_STATISTICAL_TOLERANCE` unset; :func:`relative_tolerance`)."""
    return relative_tolerance(inputs, "statistical_tolerance", DEFAULT_STATISTICAL_TOLERANCE, "a relative error")


#: Relative accuracy asked of the peak contact force (config ``solver.force_tolerance``): 15 %. What a Hertz impact's
#: peak
#: force is known to from its inputs bounds the accuracy worth asking of it: the peak goes as the contact modulus to the
#: power 2/5 (Johnson, *Contact Mechanics* §11.4), and a rock modulus known to ±50 % (the default grid's 5e6 psi
#: against the pipe's steel) moves it by −22/+15 %; a restitution known to ±0.1 of 0.3-0.7 moves the impulse by
#: ±6-8 %. Held to 5 % instead, the mean of a chaotic bouncing's per-revolution largest forces, which scatter by
#: 14-75 %, would take 80-300 revolutions at the middle half of the bouncing points measured (up to 1 500; 9-34 at
#: 15 %, docs/reference_model.md §3.1) to state a figure no better known.
#: The force's error is still stated whole (``peak_contact_force_error``); the point's ``error_estimate`` counts it as
#: its share of this tolerance times the point's own (:func:`study.solvers.methods.reference.stress_equivalent`).
DEFAULT_FORCE_TOLERANCE = 0.15


def force_tolerance(inputs: Mapping[str, Any]) -> float:
    """The relative tolerance of the peak contact force (config ``solver.force_tolerance``;
    :data:`DEFAULT_FORCE_TOLERANCE` unset; :func:`relative_tolerance`)."""
    return relative_tolerance(inputs, "force_tolerance", DEFAULT_FORCE_TOLERANCE,
                              "a relative error of the peak contact force")


@dataclass(frozen=True)
class Tolerances:
    """The relative tolerances a point's answer is held to (config ``solver.tolerance``,
    ``solver.statistical_tolerance``, ``solver.force_tolerance``), each checked once as it is read."""

    tolerance: float = DEFAULT_TOLERANCE  #: the study's (:func:`study_tolerance`)
    statistical: float = DEFAULT_STATISTICAL_TOLERANCE  #: of means over a motion that does not repeat
    force: float = DEFAULT_FORCE_TOLERANCE  #: of the peak contact force

    @classmethod
    def from_inputs(cls, inputs: Mapping[str, Any]) -> "Tolerances":
        """The tolerances of a point (:func:`study_tolerance`, :func:`statistical_tolerance`,
        :func:`force_tolerance`; ValueError naming the field for a value out of range)."""
        return cls(tolerance=study_tolerance(inputs), statistical=statistical_tolerance(inputs),
                   force=force_tolerance(inputs))


#: The mass of the closure's impulse (periodic.Scene.equivalent_mass): 2ML/π (the paper's) or ML/2.
IMPACT_MASSES = ("momentum", "modal")
#: Resonance candidates the span search may enumerate (config ``solver.max_poles``; a memory guard).
MAX_POLES = 20_000_000


def option(default, choices: tuple[str, ...] | None = None):
    """A declared option: its default and, for a choice, the allowed values."""
    return field(default=default, metadata={"choices": choices} if choices else {})


@dataclass(frozen=True)
class MethodOptions:
    """Base of a method's options: a frozen dataclass whose fields are the option names (as in the point's
    inputs and the config's ``solver.*`` fields) with their defaults."""

    @classmethod
    def from_inputs(cls, inputs: Mapping[str, Any]):
        """The options of a point: its inputs where set (not None), the declared defaults elsewhere (only the
        ``CONFIG_FIELDS`` where a class names them). A choice outside its declared values raises ValueError
        naming the option, the value and what is allowed."""
        names = getattr(cls, "CONFIG_FIELDS", None)
        values = {}
        for spec in fields(cls):
            value = inputs.get(spec.name)
            if value is None or (names is not None and spec.name not in names):
                continue
            allowed = spec.metadata.get("choices")
            if allowed is not None and value not in allowed:
                raise ValueError(f"{spec.name} = {value!r}; allowed: {', '.join(allowed)}")
            if isinstance(spec.default, (int, float)):  # a number as its declared kind (bool, int, float)
                value = type(spec.default)(value)
            values[spec.name] = value
        return cls(**values)

    @classmethod
    def default(cls, name: str):
        """The declared default of option ``name``."""
        return next(spec.default for spec in fields(cls) if spec.name == name)

    @classmethod
    def choices(cls, name: str) -> tuple[str, ...]:
        """The declared values of choice option ``name``."""
        return next(spec.metadata["choices"] for spec in fields(cls) if spec.name == name)


@dataclass(frozen=True)
class Options(MethodOptions):
    """Resolution and search settings of the periodic methods (``fast``, ``series``, ``auto``, ``crosscheck``).

    The first six are config fields (``solver.modes`` ...); the rest are internal resolutions.
    """

    modes: int = 41  #: highest (odd) mode number kept
    min_span: float = 3.0  #: shortest span searched [m]
    max_span: float = 304.8  #: longest span searched [m] (1000 ft)
    load_shape: str = "parabolic"  #: spatial shape of the contact load (beam.LOAD_SHAPES)
    resonance_width: float = 1e-6  #: resonances narrower than this (relative span) are not searched
    max_poles: int = MAX_POLES  #: resonance candidates the span search may enumerate (a memory guard)
    samples: int = 4  #: samples of F inside each interval between (wide) poles
    time_points: int = 480  #: points over one (half) period outside the pulse, for condition 1
    pulse_points: int = 64  #: points across the pulse
    space_points: int = 48  #: points over half the span
    tolerance: float = 1e-6  #: relative slack of condition 1, |y| <= c (1 + tolerance)
    fixed_point_tol: float = 1e-9  #: relative change of T_L that ends the T_L-κ iteration

    #: the fields a config sets (same names in the point's inputs); the others are internal resolutions (the
    #: point's ``tolerance`` is the study's, not condition 1's slack)
    CONFIG_FIELDS = ("modes", "min_span", "max_span", "load_shape", "resonance_width", "max_poles")


#: Time-domain integrators; "auto": the event-driven one where the damping is linear, the explicit one with
#: the quadratic drag.
INTEGRATORS = ("event", "explicit", "implicit")


@dataclass(frozen=True)
class TimeDomainOptions(MethodOptions):
    """Options of the ``time-domain`` method (docs/model.md §10)."""

    time_integrator: str = option("auto", ("auto",) + INTEGRATORS)
    time_modes: int = 5  #: modes of the span
    time_revolutions: int = 60  #: most revolutions integrated
    time_damping: str = option("linearised", ("linearised", "drag", "none"))
    time_initial: str = option("prescribed", ("prescribed", "rest"))
    contact_damping: str = option("calibrated", ("calibrated", "lankarani_nikravesh", "hunt_crossley"))
    time_tolerance: float = 1e-4  #: periodicity tolerance, in units of c and Ωc
    time_check_periodic: bool = True
    time_step: float | None = None  #: explicit step [s] (None: time_step_fraction of the stability limit)
    time_step_fraction: float = 0.1
    contact_steps: int = 100  #: RK4 steps per elastic Hertz contact (event-driven)
    time_ode_method: str = "LSODA"  #: solve_ivp method of the implicit integrator
    time_rtol: float = 1e-8
    time_atol: float = 1e-10
    drag_points: int = 8  #: Gauss points of the quadratic drag
    contact_points: tuple = (0.5,)  #: contact points as fractions of the span
    initial_state: tuple | None = None  #: (q, q̇) arrays, overriding time_initial


@dataclass(frozen=True)
class SdofOptions(MethodOptions):
    """Options of the ``sdof`` screen (docs/model.md §8.2); ``drive_amplitude`` and ``side_force`` also drive the
    time domain."""

    sdof_mass: str = option("modal", ("modal", "momentum"))
    sdof_damping: str = option("mud", ("mud", "none"))
    drive_amplitude: float | None = None  #: F0 [N] (None: the mean impact force of the prescribed closure)
    side_force: float = 0.0  #: constant side force towards +c [N]
    sdof_scan: int = 400  #: phases scanned for period-1 orbits


@dataclass(frozen=True)
class SeriesOptions(MethodOptions):
    """Options of the ``series`` method (docs/model.md §9)."""

    harmonics: int = 400  #: highest time harmonic kept
    series_tolerance: float | None = None  #: relative change at which the harmonics stop doubling (None: fixed)
    series_max_harmonics: int = 25_600  #: cap on the doubling


@dataclass(frozen=True)
class DampedOptions(MethodOptions):
    """Options of the ``damped`` method (docs/model.md §7.1)."""

    damped_harmonics: int = 400  #: highest time harmonic of the damping and end-moment correction
    damping_iterations: int = 30  #: most steps of the equivalent-damping iteration
    damping_tolerance: float = 1e-4  #: relative change of c that ends the iteration


@dataclass(frozen=True)
class CrosscheckOptions(MethodOptions):
    """Options of the ``crosscheck`` method (docs/model.md §11)."""

    check_tolerance: float = 0.02  #: relative difference accepted between the real contact and the periodic solution


#: The default turn of each pipe joint's mass eccentricity from the previous joint's along the string [rad]: none, the
#: joints aligned, which drives the string's stiffest lateral wave alone (the worst case turning slowly; valid in any
#: section); a turn drives the wave of its wavenumber, whose resonance the rotary speed sweeps through. The default
#: study (configs/default.toml) sets 90° in a four-joint section, a random make-up's joint loads in the mean square
#: (docs/reference_model.md §1, §7).
TURN = 0.0
#: Schemes of the reference model's compiled integrator (option ``reference_integrator``).
INTEGRATOR_SCHEMES = ("lawson", "lawson-flight", "dopri5")


@dataclass(frozen=True)
class ReferenceOptions(MethodOptions):
    """Options of the ``reference`` method (docs/reference_model.md)."""

    eccentricity: float = 0.1 * 0.0254  #: mass eccentricity of the pipe [m]
    #: the turn of each pipe joint's eccentricity from the previous joint's along the string [rad] (0: aligned, the
    #: default; docs/reference_model.md §1, §7)
    eccentricity_turn: float = TURN
    tool_joint_diameter: float = 6.25 * 0.0254  #: [m]
    #: the tool joint's bore and length (box and pin), whose mass beyond the plain pipe's is lumped at the joints [m]
    tool_joint_inner_diameter: float = 3.25 * 0.0254
    tool_joint_length: float = 20 * 0.0254
    joint_length: float = 31 * 0.3048  #: tool joint to tool joint [m]
    section_length: float = 93 * 0.3048  #: the periodic section of the string, three joints [m]
    #: contact stations on the pipe body between neighbouring tool joints, evenly spaced (reference model)
    reference_body_stations: int = 1
    #: the most body stations: the count goes k -> 2k + 1 (the stations kept, one more between each pair) while the body
    #: passes its wall between them beyond the study's tolerance of its clearance (reference.solve_with_modes)
    reference_max_body_stations: int = 31
    friction: float = 0.3  #: Coulomb coefficient of pipe on wall
    reference_modes: int = 16  #: modes per lateral direction (the first count tried)
    #: the most modes per direction: the count doubles from reference_modes while the modal part of an error is over
    #: half the study's tolerance (reference.solve)
    reference_max_modes: int = 64
    reference_revolutions: int = 40  #: most revolutions of the transient
    #: least revolutions of the transient from the initial state: none before it enters the window (neither a period
    #: nor stationary bouncing ends the transient sooner; auto sets it where the sliding check's run from rest chattered
    #: only after tens of quiet revolutions, docs/reference_model.md §10); 0: none
    reference_min_revolutions: int = 0
    reference_window: int = 6  #: revolutions of the output window (and of each extension of the record)
    #: revolution budget of a run that has not converged (transient included): where the motion does not repeat the
    #: window grows within it for every figure that can reach its tolerance; at 10 bouncing points of the default grid
    #: it holds the force's 15 % at all 10, the stresses' 5 % at 8 and the damage rate's at 7 (docs/reference_model.md
    #: §3.1)
    reference_max_revolutions: int = 200
    #: the mud's damping of the modes: "drag" its quadratic drag (docs/reference_model.md §2); "drag+viscous" that and
    #: the viscous loss of each mode, the Stokes layer of mud.plastic_viscosity in the annulus (linear, 2ζ_nω_n:
    #: study.physics.damping.viscous_modal_damping_ratio); "viscous" the ratio ``damping_ratio`` on every mode alone
    reference_damping: str = option("drag", ("drag", "viscous", "none", "drag+viscous"))
    reference_initial: str = option("forced", ("forced", "rest"))
    contact_law: str = option("hertz", ("hertz", "penalty"))
    reference_rtol: float = 1e-6  #: relative tolerance of the compiled integrator
    #: the compiled integrator's scheme: the Lawson (integrating-factor) form of Dormand–Prince 5(4), exact on the
    #: modes' linear part, or Dormand–Prince 5(4) on the whole right-hand side (whirl_kernel.advance)
    reference_integrator: str = option("lawson-flight", INTEGRATOR_SCHEMES)
    #: the rule the mud's quadratic drag is summed by along the section: Gauss–Legendre at 2N + 8 points ("gauss"), or
    #: the periodic midpoint rule at 3N/2 + 8 evenly spaced points ("uniform": exact on the periodic basis' products,
    #: fewer points and a smaller quadrature error; opt-in; docs/reference_model.md §4, §6,
    #: reference.model.drag_quadrature)
    reference_drag_quadrature: str = option("gauss", ("gauss", "uniform"))
    #: the precision of the drag's sums over its points in the compiled integrator: "double", or "single" (float32:
    #: twice the numbers a vector instruction takes, rounding 1e-7 of the drag, far below its quadrature's error;
    #: opt-in, docs/reference_model.md §4)
    reference_drag_precision: str = option("double", ("double", "single"))
    #: the modes whose drag the quadrature sums (at the 2N_d + 8 points, or 3N_d/2 + 8, of their count N_d): "all"
    #: the kept modes, "band" those up to the stresses' band edge (reference.model.stress_band_edge, ~300 Hz), "32"
    #: the first 32; the modes above get ``reference_drag_rest`` (opt-in; docs/reference_model.md §4)
    reference_drag_modes: str = option("all", ("all", "band", "32"))
    #: with ``reference_drag_modes``, the drag of the modes above N_d: "linear" the quadratic drag linearised about
    #: the first N_d modes' velocity field, span-averaged (kernels.drag.drag_linearised), or "none"
    reference_drag_rest: str = option("linear", ("linear", "none"))
    reference_tolerance: float = 1e-4  #: periodicity tolerance, in units of c and Ωc
    damping_ratio: float = 0.05  #: modal damping ratio of ``reference_damping = "viscous"``
    slip_velocity: float = 0.01  #: regularisation velocity of the Coulomb friction [m/s]
    #: the modes left out at a contact: their static flexibility in series with its spring ("series"), a residual
    #: oscillator per contact point matched to their flexibility and its second moment ("dynamic"), the same damped
    #: by the bending waves' resistance at the points ("radiating"), or nothing
    reference_residual: str = option("series", ("series", "none", "dynamic", "radiating"))
    #: with the residual vectors ("dynamic", "radiating"), how many per contact point: the left-out modes' static field
    #: under a unit force there and K − 1 more of their Krylov sequence (their flexibility applied to the mass times
    #: the last), a whole number of 1 or more (reference.model.residual_ritz; opt-in, docs/reference_model.md §2.1)
    reference_residual_vectors: int = 1
    #: with the residual vectors and the strikes' pulses, a pulse's onset speed: the joint's whole approach rate
    #: ("approach"), or the kept modes' part of it ("kept": the vectors' ringing left out)
    reference_pulse_speed: str = option("approach", ("approach", "kept"))
    #: the fields' part of the modes left out with the residual vectors: their static response to the contact forces and
    #: the joints' inertia ("force": the mode-acceleration method, the vectors integrated for the contact), or the
    #: vectors' own motion s_p ("vectors", which rings after a strike); docs/reference_model.md §2.1. The residual
    #: vectors stay opt-in: their stresses either way converge slower than the series law's (§2.2)
    reference_recovery: str = option("force", ("force", "vectors"))
    #: the modal part of a bouncing point's error: each figure's change between whole runs at N/2 and N modes
    #: ("doubling"), or from its strikes replayed at N, 2N … reference_max_modes modes ("replay",
    #: docs/reference_model.md §2.2; opt-in: it did not lower the default study's not_converged share and costs more)
    reference_modal_measure: str = option("doubling", ("doubling", "replay"))
    #: how a chaotic window grows: while every figure over its tolerance can reach it within the budget ("point"), or
    #: for each figure that can, whatever the others ("figure": the stresses converged where the force cannot be;
    #: on 24 reference points of the default study 3.4 times the CPU for one point fewer not_converged,
    #: docs/reference_model.md §3.1)
    reference_window_growth: str = option("point", ("point", "figure"))
    #: the peak contact force of a strike at a tool joint: the modes' own ("modes", the series law's contact), or the
    #: strike's local model from its onset speed ("local": the joint's mass on an infinite beam against the Hertz wall,
    #: study.physics.strike; docs/reference_model.md §2.3), where its contact ends before the waves of the neighbouring
    #: joints come back; or at each look at the window the one of the two whose error (window and modes parts, the
    #: local model's own 9 % included) is the smaller ("smaller", the default): the local model at a bouncing point
    #: (on the held-back sample of docs/validation.md its answers at 64 modes lay a median 7 % from the 128-mode long
    #: runs', the modes' own 34 %, all below), the modes' own at a joint chattering on its wall (the default study's 13
    #: chattering points, where the local model states 34-139 % and the modes' own 9-15 %). "local" alone took those
    #: 13 to not_converged. "pulse": each such strike applies its local model's force history to the modes in the run
    #: itself, in place of the contact law (the motion between strikes then follows the strikes' own impulse;
    #: docs/reference_model.md §2.4). Opt-in: with the strikes' local bending ("pulse" and reference_strike_stress
    #: "local") on 22 not_converged bouncing points of the default study it took the force's stated error from a
    #: median 242 % to 16 % at 5 times the CPU and decided none (the stresses' modal parts; their change from 32 to 64
    #: modes covered the 128-mode answers at 5-6 of 12 points)
    reference_strike_force: str = option("smaller", ("modes", "local", "pulse", "smaller"))
    #: with the strikes' pulses, each pulse's size: the local strike's history as it is ("local", its impulse), or
    #: scaled at its onset so that its work on the kept modes (predicted from their state, undamped and linear over the
    #: pulse) is the local strike's net work on its joint-and-beam, the point rebounding ("matched",
    #: study.solvers.kernels.pulse.matched_scale; docs/reference_model.md §2.4), or the same with the point's free
    #: motion taken as the local model's steady approach at the onset speed, so that only the kept modes' missing
    #: mobility is made up ("mobility"). Opt-in: at three bouncing points of the default study at 32-128 modes the
    #: "matched" pulses did the local work within 4-10 %, but the figures did not converge on 256 modes' (at two
    #: points they fell further from them than the tabulated pulses'); "mobility" at 128 modes came within 0.4-19 % of
    #: them (the tabulated pulses 3-28 % under), at 64 modes no nearer than those
    reference_pulse_work: str = option("local", ("local", "matched", "mobility"))
    #: the bending of a strike at a tool joint: the modes' own with the quasi-static correction ("modes"), or the
    #: run's modes plus the strike's local bending that the modes left out miss ("local": the infinite beam's moment
    #: under the local model's force less the kept modes' share of it, study.physics.strike.strike_history_table, in
    #: place of the strike's quasi-static correction; docs/reference_model.md §2.3, the stresses at a strike)
    reference_strike_stress: str = option("modes", ("modes", "local"))
    #: the band of the section's bending the stresses state: every kept mode's dynamic response ("all"), or the modes
    #: within the band where the Euler–Bernoulli beam holds within study.solvers.methods.reference.model.BAND_FRACTION
    #: of Timoshenko's ("timoshenko": study.physics.section.timoshenko_band_edge) dynamically and the kept modes
    #: above it by their quasi-static response to their loads, as the modes left out; the motion keeps all N
    #: (docs/reference_model.md §2.3.1, §3). The default: with it the stresses of four bouncing points of the default
    #: study, one motion recovered at 64 and 128 modes, agree within 2.1 %, every mode's 2.4-12 % apart; under the
    #: default strike law ("modes") too: there the held-back coverage (study coverage, 20 points, 2x the modes)
    #: covers 77 of 100 figures with it and 75 with "all" (the stresses 28 each), not_converged as often
    #: (docs/reference_model.md §2.3.1)
    reference_stress_band: str = option("timoshenko", ("all", "timoshenko"))
    #: contact points as fractions of the section, in place of the tool joints and body stations (code and tests), and
    #: their kinds (1: a tool joint, 0: the body; default all body)
    contact_points: tuple | None = None
    contact_kinds: tuple | None = None


@dataclass(frozen=True)
class LimitOptions(MethodOptions):
    """The design limits' settings of a point (the config's fields of :data:`study.physics.limits.LIMIT_INPUTS`:
    the grade, its strengths [Pa], the stress concentration, the S-N curve, the mean-stress correction and the cycles
    per revolution), None where unset: :meth:`keywords` passes the set ones to
    :func:`study.physics.limits.design_limits` and :func:`study.physics.limits.history_damage`, whose own defaults
    hold elsewhere."""

    pipe_grade: str | None = None
    yield_strength: float | None = None
    tensile_strength: float | None = None
    stress_concentration: float | None = None
    sn_curve: str | None = None
    mean_stress_correction: str | None = None
    cycles_per_revolution: float | None = None

    def keywords(self) -> dict[str, Any]:
        """The set settings, as keywords of :func:`study.physics.limits.design_limits`."""
        return {spec.name: getattr(self, spec.name) for spec in fields(self) if getattr(self, spec.name) is not None}
