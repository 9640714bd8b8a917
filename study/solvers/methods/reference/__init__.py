"""The reference model (method ``reference``; ``docs/reference_model.md``): the rotating pipe section in
the hole, in both lateral directions, driven by what drives it.

Scene (our choices, stated; the equations in :mod:`study.solvers.kernels.whirl_kernel`):

- **section** a piece of a long string, spatially periodic (the string repeats from section to section, so its
  end joints lie on the wall like the others; docs/reference_model.md §1), length L = ``section_length`` (config
  ``contact.section_length``, default 93 ft: three 31-ft joints; a whole number of joints), under the effective
  tension T0 − m_i V_m², mass M = m_p + m_i + m_a per unit length
  (:func:`study.solvers.model.scene.section_of`); deflection u(x, t) = (y, z) = Σ_n (q_yn, q_zn) ψ_n(x) over
  the periodic basis ψ_0 = 1/√2 (the rigid translation, ω_0 = 0), ψ_{2j−1} = cos k_j x, ψ_{2j} = sin k_j x,
  k_j = 2πj/L (:func:`study.physics.string_modes.mode_shapes`), n = 0 … N − 1 (``reference_modes``, default 16, modes
  per direction), modal mass M L/2 and ω_n² = (EI k_n⁴ + T k_n²)/M.
- **drive**: the pipe's mass eccentricity ε (``eccentricity``, config ``pipe.eccentricity``), the same size in every
  pipe joint, whose centrifugal load m_p ε Ω² per unit length turns with the pipe
  (:func:`study.physics.whirl.eccentric_load`), in the same phase in every pipe joint (``eccentricity_turn`` 0, the
  default) or turned from joint to joint (:func:`study.physics.string_modes.eccentric_factors`); and the uniform side
  load (:meth:`study.solvers.model.scene.Scene.side_loads`): in an inclined hole (``inclination``, config
  ``hole.inclination``, default 0) the buoyed weight's side component, in a curved hole (``dogleg_curvature``,
  ``dogleg_direction``) the tension's T κ towards the centre of curvature, whose curvature also bends the pipe that
  follows it (``side_load`` [N/m] sets the load directly in code). A uniform load drives the rigid translation ψ_0
  alone. Nothing else: with ε = 0 and a centred pipe in a straight vertical hole nothing moves.
- **mud**: added mass in M; quadratic drag −D |u̇| u̇ per unit length with the velocity's magnitude in
  both directions (``reference_damping = "drag"``, default; D from
  :func:`study.physics.section.drag_coefficient_per_length`), projected on the modes by
  Gauss–Legendre quadrature with 2N + 8 points (``reference_drag_quadrature = "uniform"``: the periodic midpoint rule
  with 3N/2 + 8, :func:`model.drag_quadrature`). For validation ``"viscous"`` (modal damping ratio
  ``damping_ratio`` in every mode) and ``"none"``; ``"drag+viscous"`` the drag and each mode's viscous loss in
  the mud (:func:`study.physics.damping.viscous_modal_damping_ratio`, ``plastic_viscosity``).
- **contact points**: the tool joints at 0, s, 2s, … (s = ``joint_length``; x = L is the joint at 0 again),
  radius r_tj = ``tool_joint_diameter``/2, clearance R − r_tj; and the pipe body halfway between neighbouring
  joints, radius r_o, clearance R − r_o (:func:`study.physics.string_modes.contact_layout`; ``reference_body_stations``
  of them, raised by :func:`solve_with_modes` where the body passes its wall between them).
  ``contact_points`` (fractions of L) and ``contact_kinds`` (0 body, 1 joint) replace them in code.
- **wall**: Hertz normal force K_p δ^{3/2}(1 + χ δ̇)₊ with K_p from
  :func:`study.physics.hertz.hertz_stiffness` for the point's radius in the hole at the curvature of the
  assumed mode c_p (π/L)² (as :mod:`study.solvers.methods.timedomain`), χ = h(e)/v0 set at each onset with the
  calibrated h(e) of :func:`study.physics.contact.calibrated_hysteresis` (exact restitution for one
  mass); Coulomb friction μ (``friction``, config ``contact.friction``, default 0.3) on the sliding
  velocity u̇·t̂ + Ω r_p, regularised over ``slip_velocity`` (default :data:`SLIP_VELOCITY`). The modes left out
  are given back statically (``reference_residual = "series"``, docs/reference_model.md §2.1): their flexibility
  at each contact point (:func:`residual_flexibility`) in series with its Hertz spring, and their static field
  under every contact force at every instant in the stresses (:func:`static_correction`); or dynamically
  (``"dynamic"``): one residual vector per contact point, that static field, in the integrated modes
  (:func:`residual_ritz`; ``reference_residual_vectors`` K > 1: K a point, the left-out modes' Krylov sequence,
  :func:`krylov_fields`), its modal part measured between N/2 and N modes (:func:`doubling_modal_error`) where no
  strike is replayed; ``"radiating"`` the same damped by the bending waves' resistance at the contact points
  (:func:`radiation_damping`).
- **rotation**: Ω constant (the rotary table holds it; the friction torque does not slow it); no
  gyroscopic terms (a pipe's polar inertia per length is negligible at these speeds).

Run: from the string's rest on the wall where a side load lays it there, else its synchronous whirl without walls
(:func:`initial_state`; ``reference_initial = "rest"``: the centred pipe at rest), revolution by revolution (the
compiled Dormand–Prince integrator of :mod:`study.solvers.kernels.whirl_kernel`, ``reference_rtol`` default 1e-6, in its
Lawson form between contacts: ``reference_integrator``) until the state at the revolution boundaries repeats (1–8
revolutions, :func:`study.solvers.kernels.periodicity.settled_period`), the pipe bounces with stationary statistics
(:func:`stationary`, checked every ``reference_window`` revolutions from three times that on) or
``reference_revolutions`` (default 40) have passed; then a window of ``reference_window`` revolutions (default 6; the
period's multiple when periodic) is recorded and the outputs are taken over it. Where the modes left out take a figure's
error over half the study's tolerance (where the pipe strikes the wall, from a few of the window's strikes replayed at
N, 2N and more modes, :mod:`study.solvers.methods.reference.replay`, docs/reference_model.md §2.2; elsewhere
:func:`modal_check`, measured on the run) the point is run again with more modes, up to ``reference_max_modes`` (default
64; :func:`solve`).
"""

from __future__ import annotations

# The package's public names: ``reference.solve(...)`` and ``from study.solvers.methods.reference import X`` as before
# the split. A test that patches a name patches it in the submodule whose functions look it up, not here.
from study.solvers.methods.reference.model import (CONTACT_LAWS, SECOND_MOMENT_HARMONICS, SLIP_VELOCITY, WhirlModel,
                                                   basis_static_gain, build_model, eccentric_parts, krylov_fields,
                                                   krylov_moments, radiation_damping, residual_flexibility,
                                                   residual_moments, residual_ritz,
                                                   residual_second_moment,
                                                   residual_second_moments, static_correction)
from study.solvers.methods.reference.integrate import (SCHEMES, SCHEME_CODES, STABLE_STEP, Integrator, Window,
                                                       initial_state, merge)
from study.solvers.methods.reference.fields import (body_wall_excess, contact_spacing, energy_balance,
                                                    joint_inertia_forces, modal_accelerations, periodic_fields,
                                                    row_wall_excess, stresses, wall_excess_bound)
from study.solvers.methods.reference.statistics import (CONFIDENCE_LEVEL, DAMAGE, DAMAGE_FIBRES, DRIFT_SIGNIFICANCE,
                                                        FIGURES, FORECAST_SLACK, MAX_SETTLE_RATIO, MODAL_FIGURES,
                                                        NEGLIGIBLE_BENDING, SLIDING_CONTACT, SLIDING_RATE,
                                                        WHIRL_CLASSES, WHIRL_REGIMES, convergence, cycle_values,
                                                        fibre_damage, fibre_stress, figure_tolerance, modal_check,
                                                        quasi_static_applies, quasi_static_ratio, settle_ratio,
                                                        settling, standard_error, stationary, stress_equivalent,
                                                        whirl_measure, window_summary, confidence, revolutions_for)
from study.solvers.methods.reference.method import (METHOD, continued_state, doubling_modal_error, end_state,
                                                    modal_part, run, simulate, solve, solve_with_modes,
                                                    solve_with_stations, start_integrator, transient_bounds)
from study.solvers.model.result import REGIMES

__all__ = ["CONTACT_LAWS", "SLIP_VELOCITY", "WhirlModel", "residual_flexibility", "SECOND_MOMENT_HARMONICS",
           "residual_second_moments", "residual_second_moment", "basis_static_gain", "eccentric_parts",
           "build_model", "residual_ritz", "residual_moments", "krylov_fields", "krylov_moments",
           "radiation_damping", "static_correction", "SCHEMES", "SCHEME_CODES",
           "STABLE_STEP", "Window",
           "merge", "Integrator", "initial_state", "periodic_fields", "body_wall_excess", "row_wall_excess",
           "wall_excess_bound", "modal_accelerations", "joint_inertia_forces", "stresses", "contact_spacing",
           "energy_balance", "WHIRL_REGIMES", "WHIRL_CLASSES", "SLIDING_RATE", "SLIDING_CONTACT", "FIGURES", "DAMAGE",
           "DAMAGE_FIBRES", "CONFIDENCE_LEVEL", "confidence", "revolutions_for", "DRIFT_SIGNIFICANCE",
           "FORECAST_SLACK", "MAX_SETTLE_RATIO", "stationary",
           "cycle_values", "fibre_stress", "fibre_damage", "window_summary", "standard_error", "settle_ratio",
           "settling", "MODAL_FIGURES", "quasi_static_ratio", "quasi_static_applies", "modal_check",
           "NEGLIGIBLE_BENDING", "convergence", "stress_equivalent", "figure_tolerance", "whirl_measure", "METHOD",
           "simulate", "run", "solve", "modal_part", "doubling_modal_error", "solve_with_modes", "solve_with_stations",
           "start_integrator", "end_state", "continued_state", "transient_bounds", "REGIMES"]
