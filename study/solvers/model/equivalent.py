"""The span's first mode as a one-degree-of-freedom oscillator between the walls (docs/model.md §8.2).

Its mass, stiffness, mud damping, drive and Hertz stiffness from the point's :class:`~study.solvers.model.scene.Scene`
and the screen's :class:`~study.solvers.model.options.SdofOptions`: the model the ``sdof`` screen solves
(:mod:`study.solvers.methods.sdof`, whose module docstring states the choices) and whose drive and damping drive the
``time-domain`` method's modal model (:func:`study.solvers.kernels.modal_span.build_model`).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from study.physics import hertz
from study.solvers.model.options import SdofOptions
from study.solvers.model.scene import Scene


@dataclass(frozen=True)
class EquivalentSdof:
    """The one-degree-of-freedom model of a design point's span (SI; see the module docstring)."""

    span_length: float  #: L [m]
    mass: float  #: m [kg] (modal M L/2 or momentum 2 M L/π, ``mass_model``)
    stiffness: float  #: k = m ω₁² [N/m]
    omega1: float  #: ω₁ [rad/s]
    clearance: float  #: c [m]
    rotary_speed: float  #: Ω [rad/s]
    restitution: float  #: e [-]
    damping: float  #: linearised mud damping of the first mode [N s/m]
    drive_amplitude: float  #: F0 [N] of F0 cos Ωt
    drive_source: str  #: where F0 comes from
    hertz_stiffness: float  #: K [N m^-3/2] at the assumed-mode curvature
    axial_curvature: float  #: κ = c (π/L)² [1/m]
    pattern: str  #: impact pattern
    mass_model: str
    damping_model: str
    side_force: float  #: constant side force towards +c [N]
    scene: Scene  #: the point's scene (section properties)


def equivalent_parameters(scene: Scene, option: SdofOptions) -> EquivalentSdof:
    """The one-degree-of-freedom model of the span ``scene.span_length`` (needs it given, ``solver.span_length``) with
    the screen's options ``option`` (its mass and damping models, its drive and side force); the choices are
    :mod:`study.solvers.methods.sdof`'s (its module docstring). The Hertz stiffness is at the assumed-mode curvature
    κ = c (π/L)²."""
    span = float(scene.span_length)
    props = scene.props
    mass_model, damping_model = option.sdof_mass, option.sdof_damping
    m = float(replace(scene, impact_mass=mass_model).equivalent_mass(span))
    omega1 = float(scene.natural_frequencies(span, [1])[0])
    c = scene.clearance
    Om = scene.rotary_speed
    e = scene.restitution
    if damping_model == "mud":
        damping = 8.0 * props["drag_coefficient_per_length"] * Om * c / (3 * np.pi) * 4.0 * span / (3 * np.pi)
    else:
        damping = 0.0
    impacts = scene.impacts_per_revolution
    if option.drive_amplitude is not None:
        F0, source = float(option.drive_amplitude), "input drive_amplitude"
    else:
        F0 = impacts * m * (1.0 + e) * Om * c / scene.period
        source = (f"default: mean impact force of the prescribed closure, {impacts} x m (1 + e) Omega c / tau")
    kappa = c * (np.pi / span) ** 2
    a_sum, b_sum = hertz.curvature_sums(scene.outer_radius, scene.hole_radius, kappa)
    K = float(hertz.hertz_stiffness(a_sum, b_sum, scene.compliance_sum))
    return EquivalentSdof(span_length=span, mass=m, stiffness=m * omega1**2, omega1=omega1, clearance=c,
                          rotary_speed=Om, restitution=e, damping=damping, drive_amplitude=F0, drive_source=source,
                          hertz_stiffness=K, axial_curvature=kappa, pattern=scene.pattern, mass_model=mass_model,
                          damping_model=damping_model, side_force=float(option.side_force),
                          scene=scene)
