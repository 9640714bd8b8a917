"""The design point itself: the scene every method solves (docs/model.md §1–§3).

The pipe section and its mud (masses, stiffness, drag, effective tension, clearance, buckling), the
contact compliance of pipe steel and rock, the rotation and the impact reading — everything about a point
that does not depend on a method. Every method builds its scene here (:func:`make_scene`), and a method
that is given its span rather than searching for one takes it with :func:`given_span`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

from study.physics import hertz, section
from study.solvers.options import IMPACT_MASSES
from study.solvers.result import PointResult, choice_input


def section_properties(inputs: Mapping[str, Any]) -> dict[str, float]:
    """Span-independent properties of the design point (SI floats).

    inputs: the SI inputs of one point, keyed as in :data:`study.config.FIELDS` names.
    """
    r_o = inputs["outer_diameter"] / 2.0
    r_i = inputs["inner_diameter"] / 2.0
    hole_r = inputs["hole_diameter"] / 2.0
    area = float(section.steel_area(r_o, r_i))
    pipe_mass = inputs.get("pipe_linear_mass") or inputs.get("pipe_density", 7850.0) * area
    m_i = float(section.internal_mud_mass(inputs["mud_density"], r_i))
    m_a = float(section.added_mass(inputs["mud_density"], r_o, hole_r, inputs.get("added_mass_model", "potential_flow")))
    ei = float(section.bending_stiffness(inputs["pipe_youngs_modulus"], r_o, r_i))
    tension = float(section.effective_tension(inputs["axial_tension"], m_i, inputs.get("mud_flow_velocity", 0.0)))
    return {
        "bending_stiffness": ei,
        "steel_area": area,
        "pipe_mass": float(pipe_mass),
        "internal_mud_mass": m_i,
        "added_mass": m_a,
        "mass_per_length": float(section.mass_per_length(pipe_mass, m_i, m_a)),
        "drag_coefficient_per_length": float(
            section.drag_coefficient_per_length(inputs["mud_density"], r_o, hole_r, inputs.get("drag_coefficient", 0.5))
        ),
        "effective_tension": tension,
        "clearance": float(section.mean_gap(r_o, hole_r)),
        "buckling_length": float(section.buckling_length(ei, tension)),
    }


def contact_compliance(inputs: Mapping[str, Any]) -> float:
    """K1 + K2 [1/Pa] of pipe steel and rock, K = (1 − ν²)/(π E) (docs/model.md §3, Hertz)."""
    return float(hertz.compliance(inputs["pipe_youngs_modulus"], inputs["pipe_poisson_ratio"])
                 + hertz.compliance(inputs["rock_youngs_modulus"], inputs["rock_poisson_ratio"]))


@dataclass(frozen=True)
class Scene:
    """Span-independent data of the design point (SI)."""

    props: Mapping[str, float]
    outer_radius: float
    inner_radius: float  #: the pipe's bore r_i [m]
    hole_radius: float
    axial_tension: float  #: the true axial tension T0 [N] (the effective one is ``props["effective_tension"]``)
    compliance_sum: float
    rotary_speed: float
    restitution: float
    pattern: str
    closure: str
    impact_mass: str = "momentum"  #: IMPACT_MASSES

    def equivalent_mass(self, span_length):
        """m_e [kg] of the closure's impulse J = m_e (1 + e) V_p: 2ML/π (``momentum``, the paper's
        equivalent mass) or ML/2 (``modal``, the modal mass of sin(πx/L) referred to midspan — the mass a
        one-mode model strikes the wall with; docs/model.md §4, §8)."""
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
    """The scene of a design point from its SI inputs (section, mud, tension, clearance, contact, rotation)."""
    props = section_properties(inputs)
    compliance = contact_compliance(inputs)
    return Scene(props=props, outer_radius=inputs["outer_diameter"] / 2.0, hole_radius=inputs["hole_diameter"] / 2.0,
                 compliance_sum=compliance, rotary_speed=float(inputs["rotary_speed"]),
                 restitution=float(inputs["restitution"]), pattern=inputs.get("impact_pattern", "alternating"),
                 closure=inputs.get("closure", "prescribed"),
                 impact_mass=choice_input(inputs, "impact_mass", "momentum", IMPACT_MASSES),
                 inner_radius=inputs["inner_diameter"] / 2.0, axial_tension=float(inputs["axial_tension"]))


def given_span(inputs: Mapping[str, Any], result: PointResult, method: str, buckled: str) -> float | None:
    """The span of a method that is given one (``solver.span_length``) rather than searching for it.

    Returns the span [m], or None after recording on ``result`` the status ``incomplete`` (no span
    given) or ``buckled`` (``buckled``: the message, formatted with ``tension`` [N] and ``span`` [m]).
    ``method``: how the messages name the method.
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
    return None
