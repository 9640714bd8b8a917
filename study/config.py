"""Study configuration: TOML with units in, validated SI inputs and sweep axes out.

A config has optional top-level ``name`` and ``title`` and the sections ``pipe``, ``hole``,
``rock``, ``mud``, ``load``, ``impact``, ``solver``, ``fatigue`` and ``sweep``. A value is a number (SI)
or a string with units as users write them ("4.5 in", "16.6 lb/ft", "10 ppg", "300 rpm").
Any scalar input can become a sweep axis under ``[sweep.axes]``: a list of values, or a range
``{start, stop, num}`` or ``{start, stop, step}``.

Bad input raises :class:`ConfigError`, which lists every problem at once: the field's path,
its value and the rule it breaks. Validators follow xarray-simlab's style: the message names
the variable, its value and the bound.
"""

from __future__ import annotations

import difflib
import hashlib
import math
import os
import stat
import tomllib
import unicodedata
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

import numpy as np

from study.physics.beam import LOAD_SHAPES
from study.physics.fatigue import MEAN_STRESS_CORRECTIONS, SN_CURVES
from study.physics.materials import GRADES
from study.physics.section import ADDED_MASS_MODELS
from study.physics.well import DOGLEG_DIRECTIONS, MAX_DOGLEG_SEVERITY
from study.solvers.model.options import (DEFAULT_FORCE_TOLERANCE, DEFAULT_STATISTICAL_TOLERANCE, DEFAULT_TOLERANCE,
                                         IMPACT_MASSES, MAX_POLES, METHOD_DESCRIPTIONS, CrosscheckOptions,
                                         DampedOptions, Options, ReferenceOptions, SdofOptions, SeriesOptions,
                                         TimeDomainOptions)
from study.units import UnitProblem, parse_angle_per_length, parse_quantity

REQUIRED = object()


@dataclass(frozen=True)
class Field:
    """One scalar input: where it lives in the config, what it is called inside, its unit and rule.

    unit : SI unit string ("" for dimensionless); ``None`` for a choice or text field.
    lower, upper : bounds in SI; ``lower_open``/``upper_open`` make them strict.
    choices : allowed strings for a choice field.
    integer : the value must be a whole number.
    parser : reads a raw value into SI (raising UnitProblem) where parse_quantity does not serve.
    rule_note : said after the bounds in the rule, e.g. a bound in the units users think in.
    """

    path: str
    name: str
    long_name: str
    unit: str | None = ""
    default: Any = REQUIRED
    lower: float | None = None
    upper: float | None = None
    lower_open: bool = False
    upper_open: bool = False
    choices: tuple[str, ...] | None = None
    integer: bool = False
    angular: bool = False
    display_unit: str | None = None  # the unit users think in, for tables and charts
    why: str = ""  # why the bounds are what they are, told with a value outside them
    parser: Callable[[Any], float] | None = None
    rule_note: str = ""

    @property
    def sweepable(self) -> bool:
        return self.unit is not None or self.choices is not None

    def rule(self) -> str:
        if self.choices is not None:
            return "one of " + ", ".join(repr(c) for c in self.choices)
        parts = []
        if self.lower is not None:
            parts.append(f"{'>' if self.lower_open else '>='} {self.lower:g}")
        if self.upper is not None:
            parts.append(f"{'<' if self.upper_open else '<='} {self.upper:g}")
        kind = "a whole number" if self.integer else "a finite number"
        unit = f" [{self.unit}]" if self.unit else ""
        note = f" ({self.rule_note})" if self.rule_note else ""
        return kind + unit + (" " + " and ".join(parts) if parts else "") + note


def _eccentricity_turn(raw) -> float:
    """The turn between successive pipe joints' eccentricities [rad]: 'aligned' (0) or an angle ("120 deg"; a number
    is in rad)."""
    if isinstance(raw, str) and raw.strip() == "aligned":
        return 0.0
    try:
        return parse_quantity(raw, "rad")
    except UnitProblem as exc:
        raise UnitProblem(f"{exc}; a turn is 'aligned' or an angle such as '120 deg'") from None


def _dogleg_direction(raw) -> float:
    """A dogleg's direction [rad]: a name of ``DOGLEG_DIRECTIONS`` or an angle ("90 deg"; a number is in rad)."""
    if isinstance(raw, str) and raw.strip() in DOGLEG_DIRECTIONS:
        return DOGLEG_DIRECTIONS[raw.strip()]
    try:
        return parse_quantity(raw, "rad")
    except UnitProblem as exc:
        raise UnitProblem(f"{exc}; a direction is one of {', '.join(repr(k) for k in DOGLEG_DIRECTIONS)} or an "
                          "angle from the low side towards +z such as '90 deg'") from None


_POSITIVE = dict(lower=0.0, lower_open=True)
_NON_NEGATIVE = dict(lower=0.0)


def _reference_choice(name: str, description: str) -> "Field":
    """The config field ``solver.<name>`` of a choice option of the reference method (its default and allowed values
    those ReferenceOptions declares)."""
    return Field(f"solver.{name}", name, description, None, default=ReferenceOptions.default(name),
                 choices=ReferenceOptions.choices(name))
_POISSON = dict(lower=-1.0, upper=0.5, lower_open=True, upper_open=True)

#: Every input a config can set, in section order. ``name`` is the key inside the package and in
#: the dataset; ``path`` is where it sits in the TOML file.
FIELDS: tuple[Field, ...] = (
    Field("pipe.outer_diameter", "outer_diameter", "pipe outer diameter", "m", display_unit="in", **_POSITIVE),
    Field("pipe.inner_diameter", "inner_diameter", "pipe inner diameter", "m", display_unit="in", **_NON_NEGATIVE),
    Field("pipe.linear_mass", "pipe_linear_mass", "pipe mass per unit length (default: density x steel area)",
          "kg/m", default=None, display_unit="lb/ft", **_POSITIVE),
    Field("pipe.density", "pipe_density", "pipe material density", "kg/m^3", default=7850.0, **_POSITIVE),
    Field("pipe.youngs_modulus", "pipe_youngs_modulus", "pipe Young's modulus", "Pa", default=206.84e9,
          display_unit="psi", **_POSITIVE),
    Field("pipe.poisson_ratio", "pipe_poisson_ratio", "pipe Poisson's ratio", "", default=0.30, **_POISSON),
    Field("pipe.grade", "pipe_grade", "API drill-pipe grade (its minimum yield and tensile strengths)", None,
          default="E-75", choices=tuple(GRADES)),
    Field("pipe.yield_strength", "yield_strength", "pipe yield strength (default: the grade's minimum)", "Pa",
          default=None, display_unit="psi", **_POSITIVE),
    Field("pipe.tensile_strength", "tensile_strength", "pipe tensile strength (default: the grade's minimum)",
          "Pa", default=None, display_unit="psi", **_POSITIVE),
    Field("pipe.stress_concentration", "stress_concentration", "stress concentration factor of the tool joint "
          "and upset on the alternating bending stress (1: the pipe body)", "", default=1.0, lower=1.0),
    Field("pipe.eccentricity", "eccentricity", "mass eccentricity of the pipe, whose centrifugal force turns with it "
          "(method reference; default 0.1 in: just below the 0.11-in offset of a 4 1/2-in body's mass centre that the "
          "-12.5 % wall-thickness tolerance allows; see docs/reference_model.md)", "m",
          default=ReferenceOptions.default("eccentricity"),
          display_unit="in", **_NON_NEGATIVE),
    Field("pipe.eccentricity_turn", "eccentricity_turn", "turn of each pipe joint's mass eccentricity from the "
          "previous joint's along the string (method reference; default 'aligned', 0: all alike, the worst case "
          "turning slowly; '90 deg', the default study's in a four-joint section: a string made up at random has that "
          "turn's joint loads in the mean square; a turn drives the string's lateral wave of that wavenumber; the "
          "periodic section must hold whole turns of the pattern; see docs/reference_model.md)", "rad",
          default=ReferenceOptions.default("eccentricity_turn"), display_unit="deg", lower=0.0, upper=2 * math.pi,
          parser=_eccentricity_turn, rule_note="0 to 360 deg"),
    Field("pipe.tool_joint_diameter", "tool_joint_diameter", "tool-joint outer diameter (method reference)", "m",
          default=ReferenceOptions.default("tool_joint_diameter"), display_unit="in", **_POSITIVE),
    Field("pipe.tool_joint_inner_diameter", "tool_joint_inner_diameter", "tool-joint bore (method reference: the "
          "joint's mass beyond the plain pipe's is lumped at the joints; default 3 1/4 in, the 6 1/4 x 3 1/4-in NC46 "
          "joint of 4 1/2-in 16.60 lb/ft pipe)", "m", default=ReferenceOptions.default("tool_joint_inner_diameter"),
          display_unit="in", **_NON_NEGATIVE),
    Field("pipe.tool_joint_length", "tool_joint_length", "tool-joint length, box and pin (method reference: the "
          "joint's mass beyond the plain pipe's is lumped at the joints; default 20 in, about 0.5 m; 0: no joint "
          "mass, e.g. where pipe.linear_mass is the adjusted weight that counts the joints already)", "m",
          default=ReferenceOptions.default("tool_joint_length"), display_unit="in", **_NON_NEGATIVE),
    Field("pipe.joint_length", "joint_length", "length of one joint of pipe, tool joint to tool joint (API Range 2: "
          "about 31 ft; the reference model's contact stations and the critical speeds of a joint)", "m",
          default=ReferenceOptions.default("joint_length"), display_unit="ft", **_POSITIVE),
    Field("hole.diameter", "hole_diameter", "bore-hole diameter", "m", display_unit="in", **_POSITIVE),
    Field("hole.inclination", "inclination", "hole inclination from vertical: the buoyed weight's side component "
          "pushes the pipe to the low side (method reference)", "rad", default=0.0, display_unit="deg",
          lower=0.0, upper=1.5707963267948966),
    Field("hole.dogleg_severity", "dogleg_curvature", "dogleg severity of the hole as its curvature ('3 deg/100ft', "
          "'3 deg/30m', '0.0017 rad/m'; 0: a straight hole)", "1/m", default=0.0,
          lower=0.0, upper=MAX_DOGLEG_SEVERITY, parser=parse_angle_per_length, rule_note="at most 30 deg/100ft"),
    Field("hole.dogleg_direction", "dogleg_direction", "direction of the dogleg's centre of curvature from the low "
          "side towards +z = x × y: 'drop' (0), 'build' (180 deg), 'walk_right' (-90 deg), 'walk_left' (90 deg) or an "
          "angle", "rad", default=0.0, display_unit="deg",
          lower=-2 * math.pi, upper=2 * math.pi, parser=_dogleg_direction, rule_note="-360 to 360 deg"),
    Field("rock.youngs_modulus", "rock_youngs_modulus", "rock Young's modulus", "Pa", display_unit="psi",
          **_POSITIVE),
    Field("rock.poisson_ratio", "rock_poisson_ratio", "rock Poisson's ratio", "", **_POISSON),
    Field("mud.density", "mud_density", "drilling mud density", "kg/m^3", display_unit="ppg", **_NON_NEGATIVE),
    Field("mud.flow_velocity", "mud_flow_velocity", "mud flow velocity inside the pipe", "m/s", default=0.0,
          display_unit="ft/s", **_NON_NEGATIVE),
    Field("mud.drag_coefficient", "drag_coefficient", "drag coefficient of the annular flow", "", default=0.5,
          **_NON_NEGATIVE),
    Field("mud.plastic_viscosity", "plastic_viscosity", "plastic viscosity of the mud (method reference with "
          "solver.reference_damping = 'drag+viscous': the viscous loss of the pipe's bending modes; default 20 cP, "
          "a water-base mud's, within API RP 13D's ranges)", "Pa*s", default=0.020, display_unit="cP",
          **_NON_NEGATIVE),
    Field("mud.added_mass_model", "added_mass_model", "added-mass model of the annular mud", None,
          default="potential_flow", choices=tuple(ADDED_MASS_MODELS)),
    Field("load.axial_tension", "axial_tension", "axial tension at the sample section (negative: compression)",
          "N", display_unit="lbf"),
    Field("load.rotary_speed", "rotary_speed", "rotary speed of the drill string", "rad/s", angular=True,
          display_unit="rpm", **_POSITIVE),
    Field("impact.restitution", "restitution", "coefficient of restitution", "", lower=0.0, lower_open=True, upper=1.0,
          why="e = 0, a plastic contact, is not modelled: the Hunt-Crossley contact of the time-domain and reference "
              "models cannot stop a rebound (its calibrated damping grows without bound as e -> 0); docs/model.md"),
    Field("impact.pattern", "impact_pattern", "which walls the midspan strikes", None, default="alternating",
          choices=("alternating", "one_wall")),
    Field("impact.closure", "closure", "how the impact velocity is closed", None, default="prescribed",
          choices=("prescribed", "self_consistent")),
    Field("impact.mass", "impact_mass", "mass of the closure's impulse m_e (1 + e) V_p: 'momentum' 2ML/pi (the "
          "paper's), 'modal' ML/2", None, default="momentum", choices=IMPACT_MASSES),
    Field("contact.friction", "friction", "Coulomb friction coefficient of pipe on wall (method reference; default "
          "0.3: water-base mud, 0.25-0.40 in Johancsik, Friesen & Dawson 1984)", "",
          default=ReferenceOptions.default("friction"), **_NON_NEGATIVE),
    Field("contact.section_length", "section_length", "length of the reference model's periodic section of the "
          "string, a whole number of joints (default three 31-ft joints)", "m",
          default=ReferenceOptions.default("section_length"), display_unit="ft", **_POSITIVE),
    Field("solver.method", "solver_method", "solution method", None, default="core",
          choices=tuple(METHOD_DESCRIPTIONS)),
    Field("solver.span_length", "span_length", "span length (given; otherwise found by the periodic solver)",
          "m", default=None, display_unit="ft", **_POSITIVE),
    Field("solver.max_span", "max_span", "longest span searched", "m", default=Options.max_span, display_unit="ft",
          **_POSITIVE),
    Field("solver.min_span", "min_span", "shortest span searched", "m", default=Options.min_span, display_unit="ft",
          **_POSITIVE),
    Field("solver.max_poles", "max_poles", "most resonance candidates (mode x harmonic pairs, about 16 bytes each) "
          "the span search may enumerate: a memory guard, raise it on a larger machine", "", default=MAX_POLES,
          integer=True, lower=1.0),
    Field("solver.modes", "modes", "highest mode number kept by the periodic methods", "", default=Options.modes,
          integer=True, lower=1.0),
    Field("solver.resonance_width", "resonance_width",
          "resonances narrower than this relative span width are not searched for spans", "",
          default=Options.resonance_width,
          lower=0.0, upper=0.1),
    Field("solver.load_shape", "load_shape", "spatial shape of the contact load", None, default=Options.load_shape,
          choices=tuple(LOAD_SHAPES)),
    Field("solver.tolerance", "tolerance", "relative accuracy asked of every method's answer (its error "
          "estimate; the max normal stress for the periodic methods): a result above it is not_converged", "",
          default=DEFAULT_TOLERANCE, lower=0.0, lower_open=True),
    Field("solver.statistical_tolerance", "statistical_tolerance", "relative accuracy asked of a figure that is a "
          "mean over the revolutions of a motion that does not repeat (the reference model's bouncing pipe; the "
          "fatigue damage rate is held to (1 + it)^5 - 1): a result above it is not_converged", "",
          default=DEFAULT_STATISTICAL_TOLERANCE, lower=0.0, upper=1.0, lower_open=True, upper_open=True,
          why="it is a relative error of a mean: 0.05 asks for 5 %"),
    Field("solver.force_tolerance", "force_tolerance", "relative accuracy asked of the peak contact force (the "
          "reference model's; its inputs, the rock's modulus and the restitution, move it by more): a result whose "
          "force error is above it is not_converged", "",
          default=DEFAULT_FORCE_TOLERANCE, lower=0.0, upper=1.0, lower_open=True, upper_open=True,
          why="it is a relative error of the force: 0.15 asks for 15 %"),
    Field("solver.harmonics", "harmonics", "highest time harmonic kept by the series method", "",
          default=SeriesOptions.default("harmonics"),
          integer=True, lower=1.0),
    Field("solver.series_tolerance", "series_tolerance", "relative change of the series method's maximum "
          "normal stress at which it stops doubling the harmonics (unset: fixed harmonics)", "", default=None,
          lower=0.0, lower_open=True),
    Field("solver.series_max_harmonics", "series_max_harmonics", "cap on the series method's harmonics", "",
          default=SeriesOptions.default("series_max_harmonics"), integer=True, lower=1.0),
    Field("solver.damped_harmonics", "damped_harmonics", "highest time harmonic of the damped method's damping "
          "and end-moment correction", "", default=DampedOptions.default("damped_harmonics"), integer=True, lower=1.0),
    Field("solver.damping_iterations", "damping_iterations", "most steps of the damped method's equivalent-damping "
          "iteration", "", default=DampedOptions.default("damping_iterations"), integer=True, lower=1.0),
    Field("solver.damping_tolerance", "damping_tolerance", "relative change of the equivalent damping that ends "
          "the damped method's iteration", "", default=DampedOptions.default("damping_tolerance"), lower=0.0,
          lower_open=True),
    Field("solver.time_integrator", "time_integrator", "integrator of the time-domain method", None,
          default=TimeDomainOptions.default("time_integrator"), choices=TimeDomainOptions.choices("time_integrator")),
    Field("solver.time_modes", "time_modes", "modes of the time-domain model", "",
          default=TimeDomainOptions.default("time_modes"), integer=True,
          lower=1.0),
    Field("solver.time_revolutions", "time_revolutions", "most revolutions the time-domain method integrates",
          "", default=TimeDomainOptions.default("time_revolutions"), integer=True, lower=1.0),
    Field("solver.time_damping", "time_damping", "mud damping in the time domain", None,
          default=TimeDomainOptions.default("time_damping"), choices=TimeDomainOptions.choices("time_damping")),
    Field("solver.time_initial", "time_initial", "initial state of the time-domain run", None,
          default=TimeDomainOptions.default("time_initial"), choices=TimeDomainOptions.choices("time_initial")),
    Field("solver.drive_amplitude", "drive_amplitude", "harmonic force on the first mode (sdof; default: the "
          "mean impact force of the prescribed closure)", "N", default=SdofOptions.default("drive_amplitude"),
          display_unit="lbf", **_NON_NEGATIVE),
    Field("solver.side_force", "side_force", "constant side force towards one wall (sdof)", "N",
          default=SdofOptions.default("side_force"),
          display_unit="lbf"),
    Field("solver.check_tolerance", "check_tolerance", "relative difference the crosscheck method accepts "
          "between the time domain and the periodic solution", "", default=CrosscheckOptions.default("check_tolerance"),
          lower=0.0, lower_open=True),
    Field("solver.sdof_mass", "sdof_mass", "mass of the one-degree-of-freedom model", None,
          default=SdofOptions.default("sdof_mass"), choices=SdofOptions.choices("sdof_mass")),
    Field("solver.reference_modes", "reference_modes", "modes per lateral direction of the reference model", "",
          default=ReferenceOptions.default("reference_modes"), integer=True, lower=1.0),
    Field("solver.reference_max_modes", "reference_max_modes", "most modes per lateral direction the reference model "
          "doubles to where the modes left out take its figures over half of solver.tolerance", "",
          default=ReferenceOptions.default("reference_max_modes"), integer=True, lower=1.0),
    Field("solver.reference_revolutions", "reference_revolutions", "most revolutions of the reference model's "
          "transient", "", default=ReferenceOptions.default("reference_revolutions"), integer=True, lower=1.0),
    Field("solver.reference_min_revolutions", "reference_min_revolutions", "least revolutions of the reference "
          "model's transient from its initial state: none before it enters the window", "",
          default=ReferenceOptions.default("reference_min_revolutions"), integer=True, lower=0.0),
    Field("solver.reference_window", "reference_window", "revolutions of the reference model's output window", "",
          default=ReferenceOptions.default("reference_window"), integer=True, lower=1.0),
    Field("solver.reference_max_revolutions", "reference_max_revolutions", "revolution budget of the reference "
          "model's run while its figures have not converged to their tolerance (solver.statistical_tolerance where the "
          "motion does not repeat; transient included)", "",
          default=ReferenceOptions.default("reference_max_revolutions"), integer=True, lower=1.0),
    Field("solver.reference_damping", "reference_damping", "mud damping of the reference model", None,
          default=ReferenceOptions.default("reference_damping"), choices=ReferenceOptions.choices("reference_damping")),
    _reference_choice("reference_strike_force", "the peak contact force of the reference model's strikes at the "
                      "tool joints: the modes' own, or each strike's local model from its onset speed (the joint's "
                      "mass on an infinite beam against the Hertz wall; docs/reference_model.md §2.3), after the run "
                      "('local') or its force history applied to the modes in the run ('pulse', §2.4), or whichever of "
                      "the modes' own and the local model's states the smaller error ('smaller')"),
    _reference_choice("reference_strike_stress", "the bending of the reference model's strikes at the tool joints: "
                      "the modes' own with their quasi-static correction, or the modes plus the strike's local bending "
                      "that the modes left out miss (docs/reference_model.md §2.3)"),
    _reference_choice("reference_stress_band", "the band of the reference model's stresses: every kept mode's dynamic "
                      "response, or the modes where the Euler-Bernoulli beam holds within 5 % of Timoshenko's "
                      "dynamically and those above by their quasi-static response (docs/reference_model.md §2.3.1)"),
    _reference_choice("reference_drag_quadrature", "the rule the reference model sums the mud's quadratic drag by "
                      "along the section: Gauss-Legendre at 2N + 8 points, or the periodic midpoint rule at 3N/2 + 8 "
                      "evenly spaced points, exact on the modes' products and cheaper (docs/reference_model.md §4)"),
    _reference_choice("reference_drag_precision", "the precision of the reference model's drag sums in its compiled "
                      "integrator: double, or single (float32: rounding 1e-7 of the drag, far below its quadrature's "
                      "error, and faster; docs/reference_model.md §4)"),
    _reference_choice("reference_drag_modes", "the modes whose mud drag the reference model sums exactly: all, those "
                      "up to the stresses' band edge, or the first 32; the rest by reference_drag_rest "
                      "(docs/reference_model.md §4)"),
    _reference_choice("reference_drag_rest", "with reference_drag_modes, the drag of the modes above: linearised "
                      "about the slow modes' velocity field, or none (docs/reference_model.md §4)"),
    Field("solver.sdof_damping", "sdof_damping", "damping of the one-degree-of-freedom model", None,
          default=SdofOptions.default("sdof_damping"), choices=SdofOptions.choices("sdof_damping")),
    Field("fatigue.sn_curve", "sn_curve", "S-N curve in air of DNV-RP-C203 (2016) Table 2-1 (B1: non-welded base "
          "material, the pipe body)", None, default="B1", choices=tuple(SN_CURVES)),
    Field("fatigue.mean_stress", "mean_stress_correction", "mean-stress correction for the axial stress", None,
          default="goodman", choices=tuple(MEAN_STRESS_CORRECTIONS)),
    Field("fatigue.cycles_per_revolution", "cycles_per_revolution", "stress cycles a fibre of the pipe sees per "
          "revolution (1: rotating bending)", "", default=1.0, **_POSITIVE),
)

FIELDS_BY_PATH = {f.path: f for f in FIELDS}
FIELDS_BY_NAME = {f.name: f for f in FIELDS}

#: Sweep settings (not inputs of a design point).
SWEEP_KEYS = {
    "axes": "table of swept inputs",
    "chunk_size": "design points per task (a whole number >= 1 and <= 10000000)",
    "scheduler": "address of a dask.distributed scheduler ('' for local processes)",
    "workers": "local worker processes (a whole number >= 0 and <= 1024; 0: one per core)",
    "max_points": "the most points a sweep accepts (a whole number >= 1 and <= 10000000; --max-points overrides it)",
}
#: The most local worker processes a sweep starts (sweep.workers, --workers).
MAX_WORKERS = 1024
#: Each sweep setting's allowed whole numbers: (lowest, highest).
SWEEP_RANGES = {"chunk_size": (1, 10**7), "workers": (0, MAX_WORKERS), "max_points": (1, 10**7)}
ROOT_KEYS = {"name": "study name (folder under outputs/)", "title": "one-line title"}
SECTIONS = ("pipe", "hole", "rock", "mud", "load", "impact", "contact", "solver", "fatigue", "sweep")
SWEEP_DEFAULTS = {"chunk_size": 0, "scheduler": "", "workers": 0, "max_points": 1_000_000}


class ConfigError(ValueError):
    """Every problem found in a config; ``problems`` is the list, str() shows one per line."""

    def __init__(self, problems: list[str], source: str = "config"):
        self.problems = list(problems)
        self.source = source
        super().__init__(f"{source}: {len(problems)} problem(s)\n" + "\n".join(f"  - {p}" for p in problems))


@dataclass
class Study:
    """A validated study: fixed inputs and sweep axes, all in SI."""

    name: str
    title: str
    inputs: dict[str, Any]  # name -> SI float, or str for choices; None where unset (optional, or swept only)
    axes: dict[str, np.ndarray] = field(default_factory=dict)  # name -> sorted SI values
    sweep: dict[str, Any] = field(default_factory=lambda: dict(SWEEP_DEFAULTS))
    text: str = ""  # the config text as read
    path: str = ""

    @property
    def config_hash(self) -> str:
        """SHA-256 of the config text, for provenance."""
        return hashlib.sha256(self.text.encode()).hexdigest()

    def point(self, **overrides) -> dict[str, Any]:
        """Inputs of one design point: the fixed inputs with ``overrides`` (name -> SI value).

        Raises :class:`ConfigError` when a required input is given only as a sweep axis and not
        overridden here.
        """
        values = dict(self.inputs)
        for key, value in overrides.items():
            if key not in FIELDS_BY_NAME:
                raise KeyError(key)
            values[key] = value
        missing = [
            FIELDS_BY_NAME[k].path for k, v in values.items()
            if v is None and FIELDS_BY_NAME[k].default is REQUIRED
        ]
        if missing:
            raise ConfigError(
                [f"{path}: given only as a sweep axis; give one value (e.g. --set {path}=...)" for path in missing],
                self.path or "config",
            )
        return values

    @property
    def size(self) -> int:
        return math.prod(len(v) for v in self.axes.values())


#: Bounds on what a config may hold, checked before anything is built from it (issue 32): a config is a small
#: text, and nothing in it may cost more than reading it. MAX_AXIS: the most values of one axis; MAX_GRID: the most
#: points of a study (sweep.max_points and --max-points are at most this); MAX_CONFIG_BYTES: the largest config
#: file; MAX_DEPTH: the deepest nesting of tables and arrays (a range axis under [sweep.axes] nests 5 deep);
#: MAX_KEY and MAX_STRING: the longest key and string; MAX_LIST: the longest array.
MAX_AXIS = 10**7
MAX_GRID = 10**7
MAX_CONFIG_BYTES = 1_000_000
MAX_DEPTH = 10
MAX_KEY = 100
MAX_STRING = 1000
MAX_LIST = 100_000

#: The longest study name: it is one folder name under outputs/ (filesystems allow 255 bytes).
MAX_NAME = 100
#: The longest title: one line of provenance in the dataset and the charts.
MAX_TITLE = 1000


def _shown(value, limit: int = 60) -> str:
    """``repr(value)`` for a message, cut to about ``limit`` characters: a long value is named by its start and its
    length, a long array or table by its kind and length, never printed whole."""
    text = repr(value)
    if len(text) <= limit:
        return text
    if isinstance(value, str):
        return f"{text[:limit - 20]}... ({len(value)} characters)"
    if isinstance(value, (dict, list)):
        return f"<{'a table' if isinstance(value, dict) else 'an array'} of {len(value)}>"
    return f"{text[:limit - 20]}... ({len(text)} characters written)"


def name_problem(name) -> str | None:
    """Why ``name`` cannot be a study name (one plain folder name under ``outputs/``), or None.

    A study name is joined to ``outputs/``: it must stay one path component there, so no path separator,
    no ``.`` or ``..``, no control character, at most :data:`MAX_NAME` characters and no blank ends."""
    if not isinstance(name, str) or not name.strip():
        return "must be a non-empty string"
    if len(name) > MAX_NAME:
        return f"has {len(name)} characters; at most {MAX_NAME}"
    bad = [c for c in name if unicodedata.category(c)[0] == "C" or unicodedata.category(c) in ("Zl", "Zp")]
    if bad:
        return f"holds the control character {bad[0]!r}"
    if "/" in name or "\\" in name:
        return "holds a path separator ('/' or '\\')"
    if name in (".", ".."):
        return "is a relative folder ('.' or '..')"
    if name != name.strip():
        return "begins or ends with a space"
    return None


NAME_RULE = (f"one folder name under outputs/: 1 to {MAX_NAME} characters, no '/' or '\\', not '.' or '..', "
             "no control characters, no spaces at the ends")


def _bounds(data: dict) -> list[str]:
    """What in a parsed config breaks :data:`MAX_DEPTH`, :data:`MAX_KEY`, :data:`MAX_STRING` or :data:`MAX_LIST`
    (walked without recursion, so that no nesting can exhaust the stack); empty when it is within them."""
    problems: list[str] = []
    stack = [("", data, 1)]
    while stack and len(problems) < 5:
        where, value, depth = stack.pop()
        if isinstance(value, (dict, list)) and depth > MAX_DEPTH:
            problems.append(f"{where[:80] or 'the config'}: tables or arrays nested more than {MAX_DEPTH} deep")
            continue
        if isinstance(value, dict):
            for key, item in value.items():
                if len(key) > MAX_KEY:
                    problems.append(f"{where + '.' if where else ''}{_shown(key)}: a key of {len(key)} characters; "
                                    f"at most {MAX_KEY}")
                    continue
                stack.append((f"{where}.{key}" if where else key, item, depth + 1))
        elif isinstance(value, list):
            if len(value) > MAX_LIST:
                problems.append(f"{where}: an array of {len(value)} values; at most {MAX_LIST} (a long axis is a "
                                "range {start, stop, num})")
                continue
            stack.extend((f"{where}[{i}]", item, depth + 1) for i, item in enumerate(value))
        elif isinstance(value, str) and len(value) > MAX_STRING:
            problems.append(f"{where} = {_shown(value)}: a string of {len(value)} characters; at most {MAX_STRING}")
    return problems


def _suggest(key: str, known) -> str:
    if len(key) > MAX_KEY:
        return ""
    close = difflib.get_close_matches(key, list(known), n=1)
    return f" (did you mean {close[0]!r}?)" if close else ""


def _check_value(spec: Field, raw, where: str, problems: list[str]):
    """Convert one raw value for ``spec``; append a problem and return None when it is bad."""
    if spec.choices is not None:
        if not isinstance(raw, str) or raw not in spec.choices:
            problems.append(f"{where} = {_shown(raw)}: must be {spec.rule()}")
            return None
        return raw
    try:
        value = spec.parser(raw) if spec.parser else parse_quantity(raw, spec.unit, angular=spec.angular)
    except UnitProblem as exc:
        problems.append(f"{where} = {_shown(raw)}: {exc}")
        return None
    if not math.isfinite(value):
        problems.append(f"{where} = {_shown(raw)}: must be finite; allowed: {spec.rule()}")
        return None
    if spec.integer and value != int(value):
        problems.append(f"{where} = {_shown(raw)}: must be {spec.rule()}")
        return None
    low_bad = spec.lower is not None and (value <= spec.lower if spec.lower_open else value < spec.lower)
    high_bad = spec.upper is not None and (value >= spec.upper if spec.upper_open else value > spec.upper)
    if low_bad or high_bad:
        shown = _shown(raw)
        si = f" (= {value:g} {spec.unit})" if isinstance(raw, str) and spec.unit else ""
        why = f" ({spec.why})" if spec.why and low_bad else ""  # why the lower bound is where it is
        problems.append(f"{where} = {shown}{si}: must be {spec.rule()}{why}")
        return None
    return int(value) if spec.integer else value


def _axis_values(spec: Field, raw, where: str, problems: list[str]):
    """Expand one sweep axis: a list, or {start, stop, num} / {start, stop, step}."""
    if isinstance(raw, list):
        if not raw:
            problems.append(f"{where} = []: an axis needs at least one value")
            return None
        values = [_check_value(spec, v, f"{where}[{i}]", problems) for i, v in enumerate(raw)]
    elif isinstance(raw, dict):
        if spec.choices is not None:
            problems.append(f"{where}: a choice axis must be a list of {spec.rule()}")
            return None
        unknown = set(raw) - {"start", "stop", "num", "step"}
        for key in sorted(unknown):
            problems.append(f"{where}.{key}: unknown key; a range has start, stop and num or step")
        if not {"start", "stop"} <= set(raw) or ("num" in raw) == ("step" in raw):
            problems.append(f"{where} = {_shown(raw)}: a range needs start, stop and exactly one of num or step")
            return None
        start = _check_value(spec, raw["start"], f"{where}.start", problems)
        stop = _check_value(spec, raw["stop"], f"{where}.stop", problems)
        if start is None or stop is None:
            return None
        if "num" in raw:
            num = raw["num"]
            if isinstance(num, bool) or not isinstance(num, int) or not 1 <= num <= MAX_AXIS:
                problems.append(f"{where}.num = {_shown(num)}: must be a whole number >= 1 and <= {MAX_AXIS:.0e} "
                                "(the most values of one axis)")
                return None
            array = np.linspace(start, stop, num)
        else:
            step = _check_value(Field(spec.path, spec.name, spec.long_name, spec.unit, angular=spec.angular,
                                      parser=spec.parser), raw["step"], f"{where}.step", problems)
            if step is None:
                return None
            if stop < start:
                problems.append(f"{where}: stop = {raw['stop']!r} is below start = {raw['start']!r}; a range "
                                "with a step runs up from start to stop >= start")
                return None
            if step <= 0:
                problems.append(f"{where}.step = {raw['step']!r}: must be > 0")
                return None
            count = (stop - start) / step
            if not count < MAX_AXIS:
                problems.append(f"{where}: {count:.3g} steps; at most {MAX_AXIS:.0e} values on one axis")
                return None
            num = int(math.floor(count + 1e-9)) + 1
            array = np.minimum(start + step * np.arange(num), stop)  # never past stop by a rounding
        # every value lies between start and stop, which are checked; a whole-number field checks each value
        if spec.integer and not np.all(array == np.round(array)):
            bad = float(array[np.flatnonzero(array != np.round(array))[0]])
            problems.append(f"{where} = {bad:g}: a value of the range is not whole; must be {spec.rule()}")
            return None
        return np.unique(np.asarray(array, dtype=float))
    else:
        problems.append(f"{where} = {_shown(raw)}: an axis is a list or a table {{start, stop, num|step}}")
        return None
    if any(v is None for v in values):
        return None
    if spec.choices is not None:
        unique = list(dict.fromkeys(values))
        return np.array(unique, dtype=object)
    array = np.unique(np.asarray(values, dtype=float))  # sorted, duplicates dropped
    return array


def _flatten_axes(table: dict, prefix: str = "") -> dict[str, Any]:
    """[sweep.axes] with dotted keys (load.rotary_speed = ...) arrives nested; flatten it."""
    flat = {}
    for key, value in table.items():
        path = f"{prefix}.{key}" if prefix else key
        if isinstance(value, dict) and not ({"start", "stop"} & set(value)) and path not in FIELDS_BY_PATH \
                and path not in FIELDS_BY_NAME:
            flat.update(_flatten_axes(value, path))
        else:
            flat[path] = value
    return flat


def _cross_checks(inputs: dict, axes: dict, problems: list[str]):
    """Rules between fields, checked over the whole range of any swept field."""

    def span(name):
        if name in axes:
            return float(np.min(axes[name])), float(np.max(axes[name]))
        value = inputs.get(name)
        return (value, value) if isinstance(value, float) else (None, None)

    def below(small: str, large: str, why: str):
        """The largest value of field ``small`` must be below the smallest of field ``large``."""
        high, low = span(small)[1], span(large)[0]
        if None not in (high, low) and high >= low:
            problems.append(f"{FIELDS_BY_NAME[small].path} = {high:g} m: must be < {FIELDS_BY_NAME[large].path} = "
                            f"{low:g} m ({why})")

    below("inner_diameter", "outer_diameter", "a pipe wall needs thickness")
    below("outer_diameter", "hole_diameter", "the pipe must fit in the hole with a clearance")
    below("tool_joint_inner_diameter", "tool_joint_diameter", "a tool joint's wall needs thickness")
    below("tool_joint_length", "joint_length", "the tool joint is a part of the joint of pipe")
    below("min_span", "max_span", "the span search needs a range")

    def values(name):
        if name in axes:
            return [float(v) for v in np.atleast_1d(axes[name])]
        value = inputs.get(name, FIELDS_BY_NAME[name].default)
        return [float(value)] if isinstance(value, (int, float)) else []

    # the reference model's periodic section holds whole turns of the pipe joints' eccentricity pattern
    # (study.physics.string_modes.eccentricity_phases says it again where a section is built in code)
    for length in values("section_length"):
        for joint in values("joint_length"):
            joints = length / joint
            if abs(joints - round(joints)) > 1e-6 * max(joints, 1.0) or round(joints) < 1:
                continue  # not a whole number of joints: the reference model says so
            for turn in values("eccentricity_turn"):
                turns = round(joints) * turn / (2 * math.pi)
                if abs(turns - round(turns)) > 1e-9 * max(turns, 1.0):
                    problems.append(
                        f"pipe.eccentricity_turn = {math.degrees(turn):g} deg: the reference model's periodic section "
                        f"(contact.section_length = {length:g} m, {round(joints)} joints of pipe.joint_length = "
                        f"{joint:g} m) must hold whole turns of it; allowed: 0 (aligned) or a multiple of "
                        f"{360 / round(joints):g} deg, or a section of a multiple of 360/turn joints")
                    return
    yield_hi = span("yield_strength")[1]
    tensile_lo = span("tensile_strength")[0]
    for grade in axes.get("pipe_grade", [inputs.get("pipe_grade")]):
        if grade not in GRADES:
            continue
        yield_strength = GRADES[grade].min_yield if yield_hi is None else yield_hi
        tensile_strength = GRADES[grade].min_tensile if tensile_lo is None else tensile_lo
        if yield_strength >= tensile_strength:
            problems.append(
                f"pipe.yield_strength = {yield_strength:g} Pa: must be < pipe.tensile_strength = "
                f"{tensile_strength:g} Pa (given, or grade {grade}'s minimum; steel yields before it breaks)"
            )
            break


def load_text(text: str, source: str = "config", overrides: dict[str, Any] | None = None) -> Study:
    """Parse and validate a TOML config text; ``overrides`` maps 'section.key' to raw values.

    Raises :class:`ConfigError` listing every problem.
    """
    problems: list[str] = []
    if len(text) > MAX_CONFIG_BYTES:
        raise ConfigError([f"a config of {len(text):,} characters; at most {MAX_CONFIG_BYTES:,} (a config is a small "
                           "text: a long axis is a range {start, stop, num})"], source)
    data = _toml(text, source)
    for path, raw in (overrides or {}).items():
        section, _, key = path.partition(".")
        if not key or section not in SECTIONS:
            problems.append(f"--set {path}: unknown field; fields are section.key with sections {', '.join(SECTIONS)}"
                            + _suggest(path, FIELDS_BY_PATH))
            continue
        data.setdefault(section, {})
        if not isinstance(data[section], dict):
            continue
        data[section][key] = raw
    bounds = _bounds(data)
    if bounds:  # nothing else is looked at: a deeper or larger config is not one
        raise ConfigError(problems + bounds, source)

    for key, value in data.items():
        if key in SECTIONS:
            if not isinstance(value, dict):
                problems.append(f"{key} = {_shown(value)}: must be a table [{key}]")
        elif key == "name":
            why = name_problem(value)
            if why is not None:
                problems.append(f"name = {_shown(value)}: {why}; allowed: {NAME_RULE}")
        elif key in ROOT_KEYS:
            if not isinstance(value, str) or not value.strip():
                problems.append(f"{key} = {_shown(value)}: must be a non-empty string ({ROOT_KEYS[key]})")
            elif len(value) > MAX_TITLE:
                problems.append(f"{key} = {_shown(value)}: has {len(value)} characters; at most {MAX_TITLE}")
        else:
            problems.append(f"{key}: unknown key{_suggest(key, list(SECTIONS) + list(ROOT_KEYS))};"
                            f" allowed at top level: {', '.join(list(ROOT_KEYS) + list(SECTIONS))}")

    inputs: dict[str, Any] = {}
    for section in SECTIONS[:-1]:
        table = data.get(section, {})
        if not isinstance(table, dict):
            continue
        known = {f.path.split(".", 1)[1] for f in FIELDS if f.path.startswith(section + ".")}
        for key in table:
            if key not in known:
                problems.append(f"{section}.{key}: unknown key{_suggest(key, known)}; allowed in [{section}]: "
                                + ", ".join(sorted(known)))

    sweep_table = data.get("sweep", {}) if isinstance(data.get("sweep", {}), dict) else {}
    for key in sweep_table:
        if key not in SWEEP_KEYS:
            problems.append(f"sweep.{key}: unknown key{_suggest(key, SWEEP_KEYS)}; allowed in [sweep]: "
                            + ", ".join(SWEEP_KEYS))
    raw_axes = sweep_table.get("axes", {})
    if not isinstance(raw_axes, dict):
        problems.append(f"sweep.axes = {_shown(raw_axes)}: must be a table of field = list or range")
        raw_axes = {}
    axes: dict[str, np.ndarray] = {}
    for key, raw in _flatten_axes(raw_axes).items():
        spec = FIELDS_BY_PATH.get(key) or FIELDS_BY_NAME.get(key)
        where = f"sweep.axes.{key}"
        if spec is None:
            problems.append(f"{where}: not an input{_suggest(key, list(FIELDS_BY_PATH) + list(FIELDS_BY_NAME))};"
                            " an axis is named by its field, e.g. load.rotary_speed")
            continue
        if spec.name in axes:
            problems.append(f"{where}: {spec.path} is swept twice")
            continue
        values = _axis_values(spec, raw, where, problems)
        if values is not None:
            axes[spec.name] = values

    for spec in FIELDS:
        section, key = spec.path.split(".", 1)
        table = data.get(section, {})
        table = table if isinstance(table, dict) else {}
        if key in table:
            inputs[spec.name] = _check_value(spec, table[key], spec.path, problems)
        elif spec.name in axes:
            inputs[spec.name] = None  # only swept: each point takes it from the axis
        elif spec.default is REQUIRED:
            problems.append(f"{spec.path}: missing; required ({spec.long_name}, {spec.rule()})")
        else:
            inputs[spec.name] = spec.default

    sweep = dict(SWEEP_DEFAULTS)
    for key in ("chunk_size", "workers", "max_points"):
        if key in sweep_table:
            value = sweep_table[key]
            low, high = SWEEP_RANGES[key]
            if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
                problems.append(f"sweep.{key} = {_shown(value)}: must be {SWEEP_KEYS[key]}")
            else:
                sweep[key] = value
    if "scheduler" in sweep_table:
        if not isinstance(sweep_table["scheduler"], str):
            problems.append(f"sweep.scheduler = {sweep_table['scheduler']!r}: must be a string address or ''")
        else:
            sweep["scheduler"] = sweep_table["scheduler"]

    size = math.prod(len(values) for values in axes.values())
    if size > MAX_GRID:
        shape = " x ".join(f"{len(values)} {name}" for name, values in axes.items())
        problems.append(f"sweep.axes: the grid has {size:,} points ({shape}); at most {MAX_GRID:,} in one study "
                        "(split it into studies)")
    _cross_checks(inputs, axes, problems)
    if problems:
        raise ConfigError(problems, source)
    name = data.get("name") or Path(source).stem or "study"
    if "name" not in data and name_problem(name) is not None:  # from the file's name: say so
        problems.append(f"name = {_shown(name)} (the config file's name; no name is given): {name_problem(name)}; "
                        f"allowed: {NAME_RULE}; give one with name = \"...\"")
        raise ConfigError(problems, source)
    title = data.get("title") or name
    return Study(name=name, title=title, inputs=inputs, axes=axes, sweep=sweep, text=text, path=source)


def _toml(text: str, source: str) -> dict:
    """``tomllib.loads(text)``, its every failure a :class:`ConfigError`: invalid TOML, arrays or inline tables
    nested deeper than Python's recursion allows, an integer of more digits than Python converts."""
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError([f"not valid TOML: {exc}"], source) from None
    except RecursionError:
        raise ConfigError([f"arrays or tables nested too deep (at most {MAX_DEPTH})"], source) from None
    except ValueError as exc:  # e.g. an integer of more than 4300 digits
        raise ConfigError([f"not a valid value: {str(exc)[:200]}"], source) from None


def load(path: str | Path, overrides: dict[str, Any] | None = None) -> Study:
    """Read and validate a TOML config file. Raises :class:`ConfigError` (also for a missing file)."""
    path = Path(path)
    try:  # a regular file, at most MAX_CONFIG_BYTES of it read: never a FIFO or a device that blocks or never ends
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
        with os.fdopen(fd, "rb") as handle:
            if not stat.S_ISREG(os.fstat(handle.fileno()).st_mode):
                raise ConfigError(["cannot read config: not a regular file"], str(path))
            data = handle.read(MAX_CONFIG_BYTES + 1)
    except OSError as exc:
        raise ConfigError([f"cannot read config: {exc.strerror or exc}"], str(path)) from None
    if len(data) > MAX_CONFIG_BYTES:
        raise ConfigError([f"a config file of more than {MAX_CONFIG_BYTES:,} bytes (a config is a small text: a long "
                           "axis is a range {start, stop, num})"], str(path))
    try:
        text = data.decode("utf-8").replace("\r\n", "\n").replace("\r", "\n")  # as read_text's universal newlines
    except UnicodeDecodeError as exc:
        raise ConfigError([f"not a text config: byte {exc.object[exc.start]:#04x} at offset {exc.start} is not "
                           "UTF-8 (a config is a TOML text file)"], str(path)) from None
    return load_text(text, str(path), overrides)


def parse_set(assignments: list[str]) -> dict[str, Any]:
    """Turn CLI ``--set section.key=VALUE`` strings into overrides; VALUE is TOML or a bare string."""
    overrides: dict[str, Any] = {}
    problems = []
    for item in assignments:
        key, sep, value = item.partition("=")
        if not sep or not key.strip():
            problems.append(f"--set {item!r}: expected section.key=VALUE")
            continue
        if len(item) > MAX_STRING:
            problems.append(f"--set {_shown(item)}: {len(item)} characters; at most {MAX_STRING}")
            continue
        try:
            overrides[key.strip()] = tomllib.loads(f"v = {value.strip()}")["v"]
        except (tomllib.TOMLDecodeError, ValueError):
            overrides[key.strip()] = value.strip()
        except RecursionError:
            problems.append(f"--set {_shown(item)}: arrays nested too deep (at most {MAX_DEPTH})")
    if problems:
        raise ConfigError(problems, "command line")
    return overrides
