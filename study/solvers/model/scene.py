"""The design point itself: the scene every method solves (docs/model.md §1–§3).

The pipe section and its mud (masses, stiffness, drag, effective tension, clearance, buckling), the
contact compliance of pipe steel and rock, the rotation and the impact reading — everything about a point
that does not depend on a method, typed. :meth:`Scene.from_inputs` builds it from a point's SI inputs: the one place
outside the config that reads them by name (the options are built likewise in :mod:`study.solvers.model.options`). The
typed design point (:class:`study.solvers.model.point.DesignPoint`) holds it, built once per point; a method that is
given its span rather than searching for one takes it with :func:`given_span`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

from study.physics import hertz, section, well, whirl
from study.solvers.model.options import IMPACT_MASSES
from study.solvers.model.result import PointResult


def section_of(outer_radius: float, inner_radius: float, hole_radius: float, pipe_linear_mass: float | None,
               pipe_density: float, mud_density: float, added_mass_model: str, pipe_youngs_modulus: float,
               axial_tension: float, mud_flow_velocity: float, drag_coefficient: float) -> dict[str, float]:
    """Span-independent properties of the pipe section in its mud (SI floats, keyed as
    :data:`study.solvers.model.result.OUTPUTS`): radii r_o, r_i and the hole's R [m], the pipe's mass per length [kg/m]
    (None: its density [kg/m³] times the steel area), the mud's density [kg/m³], added-mass model and drag
    coefficient [-], Young's modulus [Pa], the axial tension [N] and the mud's flow velocity inside the pipe [m/s]
    (:mod:`study.physics.section`; docs/model.md §1–§2)."""
    area = float(section.steel_area(outer_radius, inner_radius))
    pipe_mass = pipe_linear_mass or pipe_density * area
    m_i = float(section.internal_mud_mass(mud_density, inner_radius))
    m_a = float(section.added_mass(mud_density, outer_radius, hole_radius, added_mass_model))
    ei = float(section.bending_stiffness(pipe_youngs_modulus, outer_radius, inner_radius))
    tension = float(section.effective_tension(axial_tension, m_i, mud_flow_velocity))
    return {
        "bending_stiffness": ei,
        "steel_area": area,
        "pipe_mass": float(pipe_mass),
        "internal_mud_mass": m_i,
        "added_mass": m_a,
        "mass_per_length": float(section.mass_per_length(pipe_mass, m_i, m_a)),
        "drag_coefficient_per_length": float(
            section.drag_coefficient_per_length(mud_density, outer_radius, hole_radius, drag_coefficient)
        ),
        "effective_tension": tension,
        "clearance": float(section.mean_gap(outer_radius, hole_radius)),
        "buckling_length": float(section.buckling_length(ei, tension)),
    }


@dataclass(frozen=True)
class Scene:
    """The design point a method solves (SI): the pipe, the hole, the rock, the mud, the load and the impact of
    the config's sections of those names (:data:`study.config.FIELDS`), and the section's derived properties.
    Built once from a point's inputs by :meth:`from_inputs`, the one place that reads them."""

    props: Mapping[str, float]  #: the section's properties (:func:`section_of`)
    outer_radius: float  #: the pipe's r_o [m] (pipe.outer_diameter / 2)
    inner_radius: float  #: the pipe's bore r_i [m] (pipe.inner_diameter / 2)
    hole_radius: float  #: the hole's R [m] (hole.diameter / 2)
    axial_tension: float  #: the true axial tension T0 [N] (the effective one is ``props["effective_tension"]``)
    compliance_sum: float  #: K1 + K2 [1/Pa] of pipe steel and rock (Hertz, docs/model.md §3)
    rotary_speed: float  #: Ω [rad/s] (load.rotary_speed)
    restitution: float  #: e [-] (impact.restitution)
    pattern: str  #: impact.pattern: "alternating" or "one_wall"
    closure: str  #: impact.closure: "prescribed" or "self_consistent"
    impact_mass: str = "momentum"  #: IMPACT_MASSES
    mud_density: float = 0.0  #: ρ_m [kg/m³] (mud.density)
    mud_flow_velocity: float = 0.0  #: V_m [m/s] inside the pipe (mud.flow_velocity)
    mud_viscosity: float = 0.020  #: the mud's plastic viscosity μ_p [Pa s] (mud.plastic_viscosity)
    pipe_density: float = 7850.0  #: the pipe steel's density [kg/m³] (pipe.density)
    pipe_youngs_modulus: float = 207e9  #: the pipe steel's E [Pa] (pipe.youngs_modulus)
    pipe_poisson_ratio: float = 0.3  #: the pipe steel's ν [-] (pipe.poisson_ratio)
    inclination: float = 0.0  #: the hole's inclination from vertical [rad] (hole.inclination)
    dogleg_curvature: float = 0.0  #: the hole's curvature κ [1/m] (hole.dogleg_severity)
    dogleg_direction: float = 0.0  #: the direction of the hole's centre of curvature from the low side [rad]
    #: the uniform side load along +y [N/m] set directly (code and tests: the ``side_load`` input), None: the
    #: buoyed weight's and the tension's in a curved hole (:meth:`side_loads`)
    side_load: float | None = None
    #: the span given (solver.span_length) [m], None: a method that needs one searches for it or says it has none
    span_length: float | None = None

    @classmethod
    def from_inputs(cls, inputs: Mapping[str, Any]) -> "Scene":
        """The scene of a design point from its SI inputs (keyed as :data:`study.config.FIELDS` names): the one
        place outside the config that reads them by name. Raises ValueError for a choice outside its values."""
        r_o = inputs["outer_diameter"] / 2.0
        r_i = inputs["inner_diameter"] / 2.0
        hole_r = inputs["hole_diameter"] / 2.0
        pipe_density = inputs.get("pipe_density", 7850.0)
        flow = inputs.get("mud_flow_velocity", 0.0)
        props = section_of(r_o, r_i, hole_r, inputs.get("pipe_linear_mass"), pipe_density, inputs["mud_density"],
                           inputs.get("added_mass_model", "potential_flow"), inputs["pipe_youngs_modulus"],
                           inputs["axial_tension"], flow, inputs.get("drag_coefficient", 0.5))
        compliance = float(hertz.compliance(inputs["pipe_youngs_modulus"], inputs["pipe_poisson_ratio"])
                           + hertz.compliance(inputs["rock_youngs_modulus"], inputs["rock_poisson_ratio"]))
        side, span = inputs.get("side_load"), inputs.get("span_length")
        impact_mass = inputs.get("impact_mass", "momentum")  # the config checks it; this guards calls from code
        if impact_mass not in IMPACT_MASSES:
            raise ValueError(f"impact_mass = {impact_mass!r}; allowed: {', '.join(IMPACT_MASSES)}")
        return cls(props=props, outer_radius=r_o, hole_radius=hole_r, compliance_sum=compliance,
                   rotary_speed=float(inputs["rotary_speed"]), restitution=float(inputs["restitution"]),
                   pattern=inputs.get("impact_pattern", "alternating"), closure=inputs.get("closure", "prescribed"),
                   impact_mass=impact_mass,
                   inner_radius=r_i, axial_tension=float(inputs["axial_tension"]),
                   mud_density=inputs["mud_density"], mud_flow_velocity=flow or 0.0,
                   mud_viscosity=float(inputs.get("plastic_viscosity", 0.020)),
                   pipe_density=pipe_density or 7850.0, pipe_youngs_modulus=float(inputs["pipe_youngs_modulus"]),
                   pipe_poisson_ratio=float(inputs["pipe_poisson_ratio"]),
                   inclination=float(inputs.get("inclination") or 0.0),
                   dogleg_curvature=float(inputs.get("dogleg_curvature") or 0.0),
                   dogleg_direction=float(inputs.get("dogleg_direction") or 0.0),
                   side_load=None if side is None else float(side), span_length=span)

    def equivalent_mass(self, span_length):
        """m_e [kg] of the closure's impulse J = m_e (1 + e) V_p: 2ML/π (``momentum``, the paper's
        equivalent mass) or ML/2 (``modal``, the modal mass of sin(πx/L) referred to midspan — the mass a
        one-mode model strikes the wall with; docs/model.md §4, §8)."""
        mass = self.props["mass_per_length"]
        if self.impact_mass == "modal":
            return 0.5 * mass * np.asarray(span_length, dtype=float)
        return section.equivalent_mass(mass, span_length)

    def side_loads(self) -> tuple[float, float, np.ndarray]:
        """The uniform side load (w_y, w_z) [N/m] on the string in the hole's frame (y towards the low side) and the
        hole's curvature vector κ⃗ (2,) [1/m]: :func:`study.physics.well.side_load_vector` of the buoyed weight
        (:func:`study.physics.whirl.side_load`'s, as every method reads it), the inclination, the effective tension
        and, in a curved hole, the scene's ``dogleg_curvature`` κ [1/m] towards ``dogleg_direction`` φ [rad] from the
        low side (the tension's T κ towards the centre of curvature). The scene's ``side_load`` [N/m] sets the load
        along
        +y directly (code and tests). The reference model's and the free whirl's side load."""
        props = self.props
        kappa = self.dogleg_curvature
        phi = self.dogleg_direction
        curvature = kappa * np.array([np.cos(phi), np.sin(phi)])
        if self.side_load is not None:
            return self.side_load, 0.0, curvature
        r_o = self.outer_radius
        buoyed = float(whirl.side_load(props["pipe_mass"], props["internal_mud_mass"], self.mud_density, r_o,
                                       0.5 * np.pi))  # the whole buoyed weight per length (sin 90° = 1)
        w_y, w_z = well.side_load_vector(buoyed, self.inclination, props["effective_tension"], kappa, phi)
        return float(w_y), float(w_z), curvature

    def natural_frequencies(self, span_length, modes) -> np.ndarray:
        """ω_n [rad/s] of spans ``span_length`` [m] (last axis: ``modes``), pinned beam-column under the effective
        tension (:func:`study.physics.section.natural_frequencies`); NaN where a mode buckles."""
        p = self.props
        return section.natural_frequencies(span_length, p["bending_stiffness"], p["effective_tension"],
                                           p["mass_per_length"], modes)

    @property
    def outer_diameter(self) -> float:
        """The pipe's outer diameter 2 r_o [m]."""
        return 2.0 * self.outer_radius

    @property
    def inner_diameter(self) -> float:
        """The pipe's bore 2 r_i [m]."""
        return 2.0 * self.inner_radius

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
    """The scene of a design point from its SI inputs (:meth:`Scene.from_inputs`)."""
    return Scene.from_inputs(inputs)


def given_span(scene: Scene, result: PointResult, method: str, buckled: str) -> float | None:
    """The span of a method that is given one (``solver.span_length``) rather than searching for it.

    Returns the span [m], or None after recording on ``result`` the status ``incomplete`` (no span
    given) or ``buckled`` (``buckled``: the message, formatted with ``tension`` [N] and ``span`` [m]).
    ``method``: how the messages name the method.
    """
    span = scene.span_length
    if span is None:
        result.status = "incomplete"
        result.message = f"{method} needs a span (solver.span_length): it does not search for one"
    else:
        props = scene.props
        if not section.is_buckled(span, props["bending_stiffness"], props["effective_tension"]):
            return float(span)
        result.status = "buckled"
        result.values["span_length"] = float(span)
        result.message = buckled.format(tension=props["effective_tension"], span=float(span))
    return None
