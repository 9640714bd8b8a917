"""The ``free-whirl`` method: the steady state of the reference model's scene where the pipe does not touch the
wall, in closed form (docs/reference_model.md; the cheapest rung of the ``auto`` hierarchy).

The scene is the reference model's (:mod:`study.solvers.methods.reference`): a periodic section of the long string
(its modes :func:`study.physics.string_modes.mode_shapes`) in both lateral directions, driven by its mass
eccentricity ε (the centrifugal load m_p ε Ω² turning with the pipe); mud added mass in M and quadratic drag
D |u̇| u̇. The pipe joints' eccentricities aligned (``pipe.eccentricity_turn`` 0), a uniform load drives the rigid
translation ψ_0 alone, so away from the wall the string whirls as a rigid body (Jeffcott's rotor with no stiffness;
Vance 1988 ch. 2), bent only by its tool joints' mass; turned from joint to joint, the load drives the string's wave of
the turn (:func:`study.physics.string_modes.eccentric_factors`) and it whirls bent in it. Either way every section
whirls forward on a circle, on which its speed |u̇| = Ω |A(x)| is constant, so the drag is exactly a viscous damping
c(x) = D Ω |A(x)| and the modal equations (K − Ω² M) a + iΩ C a = ε are solved by fixed-point iteration on |A|
(a few steps).

Clear of the wall only where nothing lies on it: a side load (the buoyed weight in an inclined hole) lays the
string on its tool joints on the low side — the rigid translation has no stiffness to hold it off — so there
the method does not answer (``out_of_scope``, the sliding method or the reference model does). In a vertical
hole the pipe stays clear when the whirl's radius is below the tool joints' clearance R − r_tj; the rigid whirl
does not bend the pipe (no bending stress). Where the whirl would reach the wall (within the study's tolerance),
or the iteration does not settle, the method does not answer: status ``out_of_scope``. Its error estimate is the
iteration's last change.
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np

from study.physics import section, well, whirl
from study.physics.string_modes import contact_layout, eccentric_factors, joint_modes, mode_shapes, mode_wavenumbers
from study.solvers.model.options import ReferenceOptions
from study.solvers.model.point import DesignPoint
from study.solvers.model.result import REGIMES, PointResult
from study.solvers.model.scene import Scene

METHOD = "free-whirl"
#: Inputs the answer does not depend on: nothing strikes the wall, so the restitution (which sets only the contacts'
#: Hunt–Crossley damping) never enters. ``auto`` reuses one answer across them (a test holds the claim).
INDEPENDENT_OF = ("restitution",)
#: Modes per direction kept (the periodic basis; a uniform load drives its first alone).
MODES = 61
#: Points along the section for the clearance check and the stress maxima.
POINTS = 401
#: Fixed-point iterations on the drag at most, and the relative change of |A| that ends them.
ITERATIONS, SETTLED = 50, 1e-10


def steady_state(scene: Scene, option: ReferenceOptions, modes: int = MODES, points: int = POINTS) -> dict[str, Any]:
    """The steady state of the section of the point ``scene`` with the reference model's ``option`` (its section,
    joints and eccentricity) without wall contact: x [m], sag S and whirl A (complex) [m] and their second and third
    derivatives along x, the section's data, and how the drag iteration ended. The sag is NaN where a side load lays
    the string on the wall (its rigid translation has no stiffness)."""
    props = scene.props
    L, M, Om = float(option.section_length), props["mass_per_length"], scene.rotary_speed
    n = np.arange(modes)
    k = mode_wavenumbers(L, modes)
    # the tool joints' mass lumped at the joints, as the reference model's (reference.build_model, joint_modes)
    joint_mass = well.tool_joint_excess(scene.pipe_density, float(option.tool_joint_diameter),
                                        float(option.tool_joint_inner_diameter), float(option.tool_joint_length),
                                        props["pipe_mass"], scene.outer_diameter, scene.inner_diameter,
                                        scene.mud_density)[0]
    joints = contact_layout(L, float(option.joint_length), 0)[0]
    omega, basis = joint_modes(L, modes, M, props["bending_stiffness"], props["effective_tension"], joints,
                               max(joint_mass, 0.0))
    lift = (lambda a: a) if basis is None else (lambda a: a @ basis)  # the basis' values to the modes'
    mass = 0.5 * M * L
    # ∫ e^{iφ(x)} ψ_n dx: aligned, a uniform load drives the rigid translation of the basis alone; the joints'
    # eccentricities turned, the Bloch wave of the turn (string_modes.eccentric_factors, as the reference model's)
    factors = eccentric_factors(L, float(option.joint_length), modes, float(option.eccentricity_turn))
    eccentric = lift(whirl.eccentric_load(props["pipe_mass"], float(option.eccentricity), Om) * factors) / mass
    w_side = float(np.hypot(*scene.side_loads()[:2]))  # the weight's and, in a curved hole, the tension's
    sag_modal = np.zeros(modes)  # a side load has no static answer clear of the wall (the rigid translation falls)
    x = np.linspace(0.0, L, points)
    gx, gw = whirl.gauss_legendre(2 * modes + 8)
    gauss_x, gauss_w = 0.5 * L * (gx + 1.0), 0.5 * L * gw
    gauss_shapes = lift(mode_shapes(gauss_x, L, modes))
    drag = props["drag_coefficient_per_length"]
    stiffness = np.diag(omega**2 - Om**2).astype(complex)
    a = eccentric / (omega**2 - Om**2) + 0j
    change = np.inf
    for iteration in range(1, ITERATIONS + 1):
        speed = Om * np.abs(gauss_shapes @ a)  # |u̇| on the circle [m/s]
        damping = (gauss_shapes * (gauss_w * drag * speed)[:, None]).T @ gauss_shapes / mass  # C/m [1/s]
        new = np.linalg.solve(stiffness + 1j * Om * damping, eccentric + 0j)
        change = float(np.max(np.abs(new - a)) / max(np.max(np.abs(new)), 1e-300))
        a = new
        if change < SETTLED:
            break
    derivative = {d: lift(mode_shapes(x, L, modes, d)) for d in (0, 2, 3)}
    return dict(x=x, L=L, n=n, k=k, omega=omega, rotary_speed=Om, sag={d: s @ sag_modal for d, s in derivative.items()},
                whirl={d: s @ a for d, s in derivative.items()}, sag_modal=sag_modal, whirl_modal=a,
                iterations=iteration, change=change, props=props, option=option, side_load=w_side, basis=basis,
                joint_mass=joint_mass)


def clearances(scene: Scene, x: np.ndarray, option: ReferenceOptions) -> tuple[np.ndarray, np.ndarray]:
    """Clearance along the body [m] at every x, and the tool-joint stations [m] with theirs [m]."""
    hole_r = scene.hole_radius
    body = np.full(x.shape, hole_r - scene.outer_radius)
    L, joint = float(option.section_length), float(option.joint_length)
    stations = np.arange(0.0, L * (1.0 - 1e-9), joint)  # periodic: x = L is the joint at 0
    return body, np.column_stack([stations, np.full(stations.shape, hole_r - float(option.tool_joint_diameter) / 2)])


def solve(inputs: Mapping[str, Any]) -> PointResult:
    """The free whirl at a point given by its SI inputs (:func:`run` of its :class:`DesignPoint`)."""
    return run(DesignPoint.from_inputs(inputs))


def run(point: DesignPoint) -> PointResult:
    """The free steady whirl and sag of the section, or ``out_of_scope`` where it would touch the wall."""
    result = PointResult(method=METHOD)
    tolerance = point.tolerances.tolerance
    scene = point.scene
    props = dict(scene.props)
    option = point.reference
    result.values.update(props)
    L = float(option.section_length)
    # the periodic section's first bending mode has k = 2π/L: the pinned half-length's Euler load
    if section.is_buckled(L / 2.0, props["bending_stiffness"], props["effective_tension"]):
        result.status = "buckled"
        result.message = (f"effective tension {props['effective_tension']:.4g} N buckles the {L:.4g} m section "
                          "(contact.section_length)")
        return result
    state = steady_state(scene, option)
    if state["side_load"] != 0.0:
        result.status = "out_of_scope"
        result.message = (f"a side load of {state['side_load']:.4g} N/m (the buoyed weight in the inclined hole, the "
                          "tension in a curved one) lays the string on its tool joints (on the low side in a straight "
                          "hole): not clear of the wall, a higher model answers")
        return result
    x, sag, spin = state["x"], state["sag"], state["whirl"]
    reach = np.abs(sag[0]) + np.abs(spin[0])  # largest distance from the hole's axis over a revolution [m]
    body, joints = clearances(scene, x, option)
    at_joints = np.interp(joints[:, 0], x, reach)
    margin = 1.0 - tolerance
    touches = [f"the body at x = {x[i]:.3g} m ({reach[i] / body[i]:.3g} of its clearance)"
               for i in [int(np.argmax(reach / body))] if reach[i] >= margin * body[i]]
    touches += [f"the tool joint at x = {xj:.3g} m ({r / cj:.3g} of its clearance)"
                for (xj, cj), r in zip(joints, at_joints) if r >= margin * cj][:1]
    result.values.update(span_length=L, first_natural_frequency=float(state["omega"][0] / (2 * np.pi)),
                         clearance=float(body[0]), eccentricity=float(option.eccentricity))
    if touches or state["change"] > tolerance:
        result.status = "out_of_scope"
        why = ("the free motion reaches the wall: " + "; ".join(touches)) if touches else \
            f"the drag iteration did not settle (last change {state['change']:.2g}; near a resonance)"
        result.message = f"{why}: the closed form holds only clear of the wall, a higher model answers"
        return result
    ei = props["bending_stiffness"]
    r_o, r_i = scene.outer_radius, scene.inner_radius
    scale = r_o / float(section.second_moment_of_area(r_o, r_i))  # σ_b = M r_o / I
    bending = ei * (np.abs(sag[2]) + np.abs(spin[2])) * scale
    alternating = ei * np.abs(sag[2]) * scale
    shear = 2.0 * ei * (np.abs(sag[3]) + np.abs(spin[3])) / props["steel_area"]
    axial = abs(scene.axial_tension) / props["steel_area"]
    i_b, i_a, i_s = int(np.argmax(bending)), int(np.argmax(alternating)), int(np.argmax(shear))
    # truncation: the stress carried by the upper half of the odd modes kept
    upper = state["n"] >= state["n"].size // 2
    moments = mode_shapes(x, L, state["n"].size) * state["k"] ** 2  # each mode's −ψ'' (on the joints' modes)
    moments = moments if state["basis"] is None else moments @ state["basis"]
    tail = ei * scale * float(np.max(np.abs(moments[:, upper] @ (np.abs(state["whirl_modal"][upper])
                                                                  + np.abs(state["sag_modal"][upper])))))
    result.values.update(
        max_deflection=float(np.max(reach)), max_bending_stress=float(bending[i_b]),
        max_normal_stress=float(axial + bending[i_b]), max_normal_stress_x=float(x[i_b]),
        alternating_bending_stress=float(alternating[i_a]), alternating_bending_stress_x=float(x[i_a]),
        max_shear_stress=float(shear[i_s]), max_shear_stress_x=float(x[i_s]), peak_contact_force=0.0,
        contact_fraction=0.0, impacts_per_revolution=0.0, whirl_frequency_ratio=1.0,
        regime=float(REGIMES["no_contact"]))
    result.error_estimate = tail / max(float(axial + bending[i_b]), 1e-300) + state["change"]
    result.message = (f"clear of the wall: synchronous forward whirl of {np.max(np.abs(spin[0])) * 1e3:.3g} mm"
                      + (f" about a sag of {np.max(np.abs(sag[0])) * 1e3:.3g} mm" if state["side_load"] else "")
                      + f", at most {np.max(reach / body):.3g} of the body's clearance; drag settled in "
                      f"{state['iterations']} iterations")
    return result
