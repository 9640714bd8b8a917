"""The physics core of one design point: everything that needs no periodic solution.

Section and mud properties, effective tension and buckling, and — when the span is known —
its natural frequency, the equivalent mass and the Hertz/Lee impact of the midspan on the wall
with the velocity of the prescribed closure V_p = Ω c (docs/model.md §2–4). The scene of
the point (:mod:`study.solvers.model.scene`) is what every method builds on; the ``core`` method reports it as
it is.
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np

from study.physics import hertz, section
from study.solvers.model.result import PointResult
from study.solvers.model.point import DesignPoint
from study.solvers.model.scene import Scene

# Modes reported for the natural frequencies of a given span.
FREQUENCY_MODES = (1, 3, 5)


def impact(scene: Scene, span_length: float, impact_velocity: float, axial_curvature: float) -> dict[str, float]:
    """Hertz impact of the equivalent mass and Lee's pulse for a span and impact velocity.

    scene: the design point's (:class:`study.solvers.model.scene.Scene`: section, radii, contact compliance,
    restitution); span_length L [m], impact_velocity V_p [m/s], axial_curvature κ of the pipe at the contact
    [1/m]. Returns the impact quantities (SI). The contact ellipse is evaluated at the pulse's peak
    force (paper §IV C: the ellipse is sized by the maximum force); whether it is a Hertz contact is
    decided by the gate every result passes (:mod:`study.solvers.model.gate`).
    """
    r_o, hole_r, compliance = scene.outer_radius, scene.hole_radius, scene.compliance_sum
    m_e = float(section.equivalent_mass(scene.props["mass_per_length"], span_length))
    a_sum, b_sum = hertz.curvature_sums(r_o, hole_r, axial_curvature)
    stiffness = float(hertz.hertz_stiffness(a_sum, b_sum, compliance))
    elastic = hertz.hertz_impact(m_e, impact_velocity, stiffness)
    duration = float(hertz.lee_duration(m_e, impact_velocity, stiffness))
    impulse = float(hertz.impact_impulse(m_e, impact_velocity, scene.restitution))
    peak = float(hertz.lee_peak_force(impulse, duration))
    ellipse = hertz.contact_ellipse(peak, r_o, hole_r, axial_curvature, compliance)
    values = {
        "equivalent_mass": m_e,
        "impact_velocity": float(impact_velocity),
        "impulse": impulse,
        "axial_curvature": float(axial_curvature),
        "max_approach": float(elastic.max_approach),
        "hertz_duration": float(elastic.duration),
        "hertz_peak_force": float(elastic.max_force),
        "contact_duration": duration,
        "peak_contact_force": peak,
        "contact_half_length": float(ellipse.contact_half_length),
        "contact_half_width": float(ellipse.contact_half_width),
    }
    return values


def solve(inputs: Mapping[str, Any]) -> PointResult:
    """The ``core`` method at a point given by its SI inputs (:func:`run` of its :class:`DesignPoint`)."""
    return run(DesignPoint.from_inputs(inputs))


def run(point: DesignPoint) -> PointResult:
    """The ``core`` method: the physics core at a given span, or span-independent parts only.

    With ``span_length`` given, the span's first natural frequency and, under the prescribed
    closure, the impact with V_p = Ω c and the pipe curvature of the assumed mode
    κ = c (π/L)² at midspan. Never raises for a physical condition: buckling, an invalid Hertz
    contact and missing inputs are statuses.
    """
    result = PointResult(method="core")
    scene = point.scene
    props = scene.props
    result.values.update(props)
    span = scene.span_length
    messages = []
    if span is None:
        result.status = "incomplete"
        messages.append("no span given (solver.span_length) and the core method does not search for one: "
                        "span-dependent outputs are omitted")
    elif section.is_buckled(span, props["bending_stiffness"], props["effective_tension"]):
        result.values["span_length"] = float(span)
        result.status = "buckled"
        messages.append(
            f"effective tension {props['effective_tension']:.4g} N is at or below the Euler load "
            f"{float(section.euler_buckling_tension(span, props['bending_stiffness'])):.4g} N of the "
            f"{span:.4g} m span (buckling length {props['buckling_length']:.4g} m)"
        )
    else:
        result.values["span_length"] = float(span)
        omega = section.natural_frequencies(span, props["bending_stiffness"], props["effective_tension"],
                                            props["mass_per_length"], FREQUENCY_MODES)
        result.values["first_natural_frequency"] = float(omega[0] / (2.0 * np.pi))
        if scene.closure != "prescribed":
            result.status = "incomplete"
            messages.append(f"closure {scene.closure!r} needs the periodic solution's own impact "
                            "velocity: impact outputs are omitted by the core method")
        else:
            clearance = props["clearance"]
            velocity = scene.rotary_speed * clearance
            curvature = clearance * (np.pi / span) ** 2
            result.values.update(impact(scene, span, velocity, curvature))
    result.message = "; ".join(messages) if messages else "physics core evaluated at the given span"
    return result
