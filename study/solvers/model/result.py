"""The result of solving one design point, whatever the method.

Like scipy.integrate's OdeResult, a result carries ``status`` and ``message`` instead of raising
on a numerical failure of the design point: a sweep records the flag and goes on.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum, StrEnum
from typing import Any


class Status(StrEnum):
    """What happened at a design point: one member per status, its value the name a user reads (a ``str``, so that
    ``result.status == "ok"`` holds), with its integer ``code`` (the dataset's ``flag_values``) and its ``meaning``.
    This is the one code table of the statuses; :data:`STATUS` and :data:`STATUS_CODES` are views of it."""

    def __new__(cls, value: str, code: int, meaning: str):
        member = str.__new__(cls, value)
        member._value_ = value
        member.code = code
        member.meaning = meaning
        return member

    OK = "ok", 0, "solved; every validity check passed"
    BUCKLED = "buckled", 1, "effective tension at or below the Euler load of the span: the span buckles"
    HERTZ_INVALID = "hertz_invalid", 2, "contact too large or too elongated for Hertz theory (see message)"
    NO_SPAN = "no_span", 3, "no span satisfies the constraints within the search range"
    RESONANCE = "resonance", 4, "a harmonic of the rotation meets a natural frequency of the span"
    TERMS_NOT_SMALL = "terms_not_small", 5, "a term dropped from the equation of motion is not small"
    NOT_CONVERGED = "not_converged", 6, "the method did not reach its tolerance"
    FAILED = "failed", 7, "the method failed; see message"
    INCOMPLETE = "incomplete", 8, "inputs needed for some outputs are missing (see message)"
    NO_IMPACT = "no_impact", 9, "the pipe does not reach the wall in steady state"
    UNSTABLE = "unstable", 10, "the periodic impacting motion exists but is unstable"
    PERIOD_DOUBLING = "period_doubling", 11, "the periodic impacting motion has lost stability by period doubling"
    CHATTERING = "chattering", 12, "impacts accumulate (chatter) instead of a periodic motion"
    STICKING = "sticking", 13, "the pipe comes to rest against the wall"
    NOT_PERIODIC = "not_periodic", 14, "no periodic motion found"
    DISAGREES = "disagrees", 15, ("the time domain with real contact disagrees with the periodic solution (see "
                                  "message)")
    UNPHYSICAL = "unphysical", 16, ("a computed value breaks a physical bound: deflection past the wall, "
                                    "inconsistent stresses (see message)")
    OUT_OF_SCOPE = "out_of_scope", 17, ("the model's assumptions do not hold at this point (see message): a higher "
                                        "model answers")
    YIELDS = "yields", 18, ("solved and valid as an elastic answer, but the largest normal stress is past the "
                            "grade's yield strength (yield_utilisation > 1): the pipe yields and the elastic figures "
                            "(kept) overstate what it carries")


#: Status flags: name -> integer code (the dataset's ``flag_values``) and what it means (a view of :class:`Status`).
STATUS = {status.value: (status.code, status.meaning) for status in Status}
STATUS_CODES = {name: code for name, (code, _) in STATUS.items()}


class Regime(Enum):
    """Regimes of the pipe's motion (the output ``regime``, with these codes as its ``flag_values``): no contact
    with the wall; forward / backward whirl (rolling or sliding round the wall with or against the rotation);
    bouncing (impacts that do not settle into a periodic motion, chattering included); periodic impacts (the
    source paper's state); unstable (the periodic impacting motion exists but is unstable); sliding (lying on the
    wall at the tool joints, sliding round as the pipe turns). The one code table of the regimes: the dataset
    carries this code alone."""

    NO_CONTACT = 0
    FORWARD_WHIRL = 1
    BACKWARD_WHIRL = 2
    BOUNCING = 3
    PERIODIC_IMPACTS = 4
    UNSTABLE = 5
    SLIDING = 6


#: Regime name -> code (a view of :class:`Regime`; the dataset's ``flag_meanings`` and ``flag_values``).
REGIMES = {regime.name.lower(): regime.value for regime in Regime}

#: Outputs that repeat another output's idea and code under another name: name -> the output the dataset stores
#: in its place (a method may still return both; the dataset writes the idea once).
ALIASES = {"whirl_class": "regime"}


@dataclass
class PointResult:
    """Outputs of one design point, SI values keyed by the names of :data:`OUTPUTS`."""

    method: str
    status: Status = Status.OK
    message: str = ""
    values: dict[str, Any] = field(default_factory=dict)
    extras: dict[str, Any] = field(default_factory=dict)  # non-scalar outputs (JSON only)
    error_estimate: float | None = None
    wall_time: float = 0.0
    #: the reference model a run started from on the wall (its sliding rest in its ``cache``), handed to the lift-off
    #: eccentricity (:func:`study.solvers.methods.sliding.add_lift_off`, which empties it); not an output
    rest_model: Any = field(default=None, repr=False, compare=False)
    #: where a reference run ended (its model, state and contacts: reference.method.end_state), handed to the run at
    #: more modes (reference.method.continued_state); emptied when the reference method returns; not an output
    final_state: Any = field(default=None, repr=False, compare=False)

    def __setattr__(self, name: str, value: Any) -> None:
        # a status given by its name (``result.status = "ok"``) becomes its member; an unknown one is refused here
        object.__setattr__(self, name, Status(value) if name == "status" else value)

    @property
    def status_code(self) -> int:
        return self.status.code

    def as_dict(self) -> dict[str, Any]:
        out = dict(self.values)
        out.update(self.extras)
        out.update(status=self.status, message=self.message, method=self.method, wall_time=self.wall_time)
        if self.error_estimate is not None:
            out["error_estimate"] = self.error_estimate
        return out


#: Every scalar output a method may produce: name -> (SI unit, long name). The dataset and the
#: JSON output take units and long names from here; a method fills the ones it can compute.
OUTPUTS = {
    "bending_stiffness": ("N m2", "bending stiffness EI of the pipe"),
    "steel_area": ("m2", "cross-section area of the pipe wall"),
    "pipe_mass": ("kg m-1", "pipe mass per unit length"),
    "internal_mud_mass": ("kg m-1", "mass of mud inside unit length of pipe"),
    "added_mass": ("kg m-1", "added (virtual) mass of the annular mud per unit length"),
    "mass_per_length": ("kg m-1", "total vibrating mass per unit length M"),
    "drag_coefficient_per_length": ("kg m-2", "quadratic mud drag coefficient D"),
    "effective_tension": ("N", "effective tension T0 - m_i V_m^2"),
    "clearance": ("m", "radial clearance between pipe and bore-hole wall"),
    "buckling_length": ("m", "shortest simply supported span that buckles"),
    "span_length": ("m", "length of the sample span between nodes"),
    "first_natural_frequency": ("Hz", "first natural frequency of the span"),
    "equivalent_mass": ("kg", "mass of the impact closure (impact.mass: 2ML/pi momentum or ML/2 modal; sdof and time "
                              "domain: the modal mass)"),
    "impact_velocity": ("m s-1", "lateral velocity of midspan just before impact"),
    "impulse": ("N s", "impulse of one impact m_e (1 + e) V_p"),
    "axial_curvature": ("m-1", "curvature of the bent pipe at the contact"),
    "max_approach": ("m", "maximum Hertz approach of pipe and wall"),
    "max_wall_excess": ("m", "largest distance the pipe body passes its wall beyond its contacts' Hertz approach, "
                             "anywhere along it (a bound; negative: clear; method reference)"),
    "hertz_duration": ("s", "duration of the elastic Hertz impact T_H"),
    "contact_duration": ("s", "duration of the contact (Lee's half-sine T_L; time domain: as integrated)"),
    "hertz_peak_force": ("N", "peak force of the elastic Hertz impact"),
    "peak_contact_force": ("N", "peak contact force of the impact pulse"),
    "contact_half_length": ("m", "contact-ellipse semi-axis along the pipe at peak force"),
    "contact_half_width": ("m", "contact-ellipse semi-axis around the pipe at peak force"),
    "root_count": ("1", "roots of condition 2 (midspan at the wall at contact) in the part of the search range "
                       "searched (fast, series: all of it where no span is valid, else up to the first valid span)"),
    "pole_count": ("1", "resonant spans (poles of the periodic response) in the search range"),
    "narrow_count": ("1", "resonances narrower than solver.resonance_width, not searched"),
    "candidate_count": ("1", "spans that satisfy every constraint in the part of the search range searched "
                            "(at least 1 exactly where a span is reported)"),
    "equivalent_damping": ("N s m-2", "uniform viscous damping dissipating what the mud's drag does (damped)"),
    "damping_ratio": ("1", "damping ratio of the first mode under the equivalent damping (damped)"),
    "end_moment_amplitude": ("N m", "largest end moment that keeps the damped motion in phase with the impact"),
    "end_moment_power": ("W", "mean power the two end moments feed into the span (damped)"),
    "drag_dissipation": ("J", "energy the mud's quadratic drag dissipates per revolution (damped)"),
    "energy_residual": ("1", "|end moments' work - drag dissipation| / drag dissipation per revolution (damped)"),
    "max_deflection": ("m", "largest lateral deflection over the span and the period"),
    "max_bending_stress": ("Pa", "largest bending stress M r_o / I"),
    "max_normal_stress": ("Pa", "largest combined normal stress |T0/A| + |bending stress|"),
    "max_normal_stress_x": ("m", "position along the span of the largest normal stress"),
    "max_normal_stress_t": ("s", "time after contact of the largest normal stress"),
    "max_shear_stress": ("Pa", "largest shear stress 2V/A of the thin tube"),
    "max_shear_stress_x": ("m", "position along the span of the largest shear stress"),
    "max_shear_stress_t": ("s", "time after contact of the largest shear stress"),
    "alternating_bending_stress": ("Pa", "half the range of the bending stress over the period, worst section"),
    "yield_utilisation": ("1", "largest normal stress over the grade's minimum yield strength (over 1: yields)"),
    "endurance_utilisation": ("1", "equivalent alternating stress at the tool joint over the S-N curve's endurance "
                              "limit (over 1: finite fatigue life)"),
    "equivalent_alternating_stress": ("Pa", "alternating bending stress x stress concentration, corrected for the "
                                      "axial mean stress"),
    "damage_rate": ("s-1", "Miner's fatigue damage per second of rotation"),
    "fatigue_life": ("s", "time of rotation to fatigue failure (Miner's sum 1)"),
    "regime": ("1", "regime of the motion, a code of study.solvers.model.result.REGIMES (see flag_meanings)"),
    "location_residual": ("1", "relative change of the located stress maxima in their last refinement round "
                          "(part of the error estimate)"),
    "sdof_stiffness": ("N m-1", "stiffness m omega_1^2 of the one-degree-of-freedom model"),
    "sdof_damping": ("N s m-1", "linearised mud damping of the first mode"),
    "drive_amplitude": ("N", "amplitude of the harmonic generalised force on the first mode at the rotary speed"),
    "free_amplitude": ("m", "steady amplitude of the drive without walls"),
    "impacts_per_revolution": ("1", "wall impacts per revolution"),
    "max_floquet_multiplier": ("1", "largest modulus of the Floquet multipliers of the impacting orbit"),
    "period_revolutions": ("1", "period of the settled motion in revolutions"),
    "achieved_restitution": ("1", "rebound/approach speed of the last impact"),
    "time_step": ("s", "fixed step of the explicit integrator"),
    "step_limit": ("s", "explicit stability limit 2/omega_max with the contact linearised"),
    "revolutions_simulated": ("1", "revolutions integrated"),
    "energy_drift": ("1", "largest relative energy change (undriven, undamped runs)"),
    "impulse_ratio": ("1", "impulse of the real contact over the periodic solution's J (method crosscheck)"),
    "peak_force_ratio": ("1", "peak force of the real contact over the periodic solution's (method crosscheck)"),
    "normal_stress_ratio": ("1", "largest normal stress, time domain over periodic solution (method crosscheck)"),
    "deflection_ratio": ("1", "largest deflection, time domain over periodic solution (method crosscheck)"),
    "periodicity_defect": ("1", "change of the modal state over one revolution of the real contact, in units of "
                           "c and Omega c (method crosscheck)"),
    "orbit_peak_force_ratio": ("1", "peak force of the real contact's periodic orbit over the periodic solution's "
                               "(method crosscheck)"),
    "orbit_normal_stress_ratio": ("1", "largest normal stress on the real contact's periodic orbit over the periodic "
                                  "solution's (method crosscheck)"),
    "eccentricity": ("m", "mass eccentricity of the pipe (method reference)"),
    "lift_off_eccentricity": ("m", "mass eccentricity at which the tool joints lift off the wall they lie on: below "
                              "it the pipe lies there, above it bounces (the sliding state's balance; NaN where no "
                              "side load lays the string down, inf where no eccentricity lifts it; methods sliding, "
                              "reference, auto)"),
    "coexisting_motion": ("1", "1 where a second motion coexists with the stable sliding one (the reference "
                          "model's run from the rest on the wall bounces, or chatters on it, a joint striking at "
                          "several times the sliding force; auto then reports the reference model's "
                          "answer, unless its run came to the sliding motion by its regime and design figures), 0 "
                          "where that run settles on the wall or the reference model's came to the sliding motion, "
                          "NaN where not checked (the lift-off eccentricity twice the point's or more; methods "
                          "sliding, auto)"),
    "contact_fraction": ("1", "fraction of the window's time with any wall contact (method reference)"),
    "whirl_frequency_ratio": ("1", "whirl rate of the most-touching point over the rotary speed, negative backwards "
                              "(method reference)"),
    "whirl_class": ("1", "whirl verdict (method reference) as its regime's code (study.solvers.model.result.Regime); "
                    "the dataset stores it once, as regime"),
    "contact_spacing": ("m", "largest distance between neighbouring touching points along the periodic string "
                        "(method reference)"),
    "alternating_bending_stress_x": ("m", "position along the section of the largest alternating bending stress"),
    "modal_tail_fraction": ("1", "share of the largest bending moment carried by the upper half of the modes "
                            "(method reference: a truncation indicator)"),
    "window_spread": ("1", "relative difference of the peak contact force between the output window and the "
                      "equal stretch before it (method reference: a settling indicator)"),
    "window_revolutions": ("1", "revolutions of the output window over which the design figures are averaged "
                           "(method reference)"),
    "window_largest_contact_force": ("N", "largest contact force seen in the output window: a sample value that "
                                     "grows with the window where the motion is not periodic (method reference)"),
    "window_largest_normal_stress": ("Pa", "largest combined normal stress seen in the output window (method "
                                     "reference; a sample value, as window_largest_contact_force)"),
    "window_largest_alternating_stress": ("Pa", "largest per-cycle alternating bending stress seen in the output "
                                          "window (method reference; a sample value)"),
    "window_largest_deflection": ("m", "largest lateral deflection seen in the output window (method reference; a "
                                  "sample value, as window_largest_contact_force)"),
    "statistical_figures": ("1", "1 where the figures are means over the revolutions of a motion that does not "
                            "repeat, held to solver.statistical_tolerance; 0 where held to solver.tolerance (method "
                            "reference)"),
    "local_strike_force": ("1", "1 where peak_contact_force is the strikes' local model's (the joint's mass on an "
                           "infinite beam against the Hertz wall, from each strike's onset speed), 0 where it is the "
                           "modes' own contact's: whichever states the smaller error (solver.reference_strike_force; "
                           "method reference)"),
    "peak_contact_force_error": ("1", "relative error of peak_contact_force, by its parts (method reference)"),
    "max_normal_stress_error": ("1", "relative error of max_normal_stress, by its parts (method reference)"),
    "alternating_bending_stress_error": ("1", "relative error of alternating_bending_stress, relative to the larger of "
                                         "it and the max bending stress (method reference)"),
    "max_deflection_error": ("1", "relative error of max_deflection, by its parts (method reference)"),
    "fatigue_life_error": ("1", "relative error e of the damage rate counted by rainflow: the fatigue life lies within "
                           "life/(1 + e) and life/(1 - e) (method reference)"),
    "reference_peak_force_ratio": ("1", "peak contact force, periodic solution over the reference model (method "
                                   "reference-check)"),
    "reference_normal_stress_ratio": ("1", "largest normal stress, periodic solution over the reference model (method "
                                      "reference-check)"),
    "reference_alternating_stress_ratio": ("1", "alternating bending stress, periodic solution over the reference "
                                           "model (method reference-check)"),
    "orbit_distance": ("1", "largest difference of the real contact's periodic orbit from the periodic solution's "
                       "modal state, in units of c and Omega c (method crosscheck)"),
}
