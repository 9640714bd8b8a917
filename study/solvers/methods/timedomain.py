"""The time-domain method (method ``time-domain``; docs/model.md §10): the span integrated through real contact.

The check on the periodic assumption itself: the span's modal model is integrated in time through
Hertz contact with both walls, from a stated initial state, revolution after revolution, until the
modal state repeats one to eight revolutions apart (periodic) or ``time_revolutions`` have passed.

Model (our choices, stated):

- **modes** y(x, t) = Σ q_n(t) sin(nπx/L), n = 1 … N (odd and even: the contact points need not be
  symmetric), N = option ``time_modes`` (default 5). Modal mass m = M L/2 for every n (kinetic
  energy ½ M ∫ ẏ² dx = Σ ½ (M L/2) q̇_n²), ω_n from :func:`study.physics.section.natural_frequencies`
  (beam-column, effective tension). With N = 1 and contact at midspan, q_1 is the midspan deflection
  and the model is the SDOF of :mod:`study.solvers.methods.sdof` with its ``"modal"`` mass.
- **contact** at the points x_p = ξ_p L (option ``contact_points``, fractions of the span, default
  (0.5,)): walls at y = ±c; penetration δ_p = |y(x_p)| − c; force −sign(y) K δ^{3/2}(1 + χ δ̇)₊ on
  the pipe, generalised force F_p sin(nπξ_p) on mode n. K from :func:`study.physics.hertz.hertz_stiffness`
  at the assumed-mode curvature κ = c (π/L)² (the curvature of c sin(πx/L) at midspan — the same K as
  ``sdof``; used at every contact point). χ = h(e)/v0 is set at each contact onset from that
  contact's approach speed v0. The dimensionless h = χ v0 alone fixes the restitution of a
  Hunt–Crossley Hertz impact (scale δ by α_max and t by α_max/v0: m and K drop out), so
  ``contact_damping = "calibrated"`` (default) solves h(e) once
  (:func:`study.physics.contact.calibrated_hysteresis`: exact e for any e in (0, 1]);
  ``"lankarani_nikravesh"`` / ``"hunt_crossley"`` take the closed forms of
  :func:`study.physics.contact.hunt_crossley_damping` (good only for e ≳ 0.85). The law, its energy
  and its linearised stiffness are :mod:`study.physics.contact`'s.
- **damping** ``time_damping``: ``"linearised"`` (default) the sdof method's equal-dissipation mud
  damping c_eq(x) = 8 D Ω c sin(πx/L)/(3π) per unit length (amplitude of the assumed mode),
  projected on the modes: C_nm = ∫ c_eq sin(nπx/L) sin(mπx/L) dx (C_11 = sdof's damping);
  ``"drag"`` the nonlinear mud drag D |ẏ| ẏ projected on the modes by Gauss–Legendre quadrature
  (``drag_points``, default 8); ``"none"``.
- **drive** F0 cos Ωt on the first mode, F0 and its default exactly as in
  :func:`study.solvers.model.equivalent.equivalent_parameters` (``drive_amplitude``).
- **initial state** ``time_initial``: ``"prescribed"`` (default) the paper's assumed motion
  y = c sin(πx/L) sin(Ωt) at t = 0 (q_1 = 0, q̇_1 = Ωc), ``"rest"``; or ``initial_state`` =
  (q, q̇) arrays.

Integrators (``time_integrator``; ``"auto"``, the default, is ``"event"`` unless the damping is
``"drag"``, then ``"explicit"``):

- ``"event"``: exact flights between contacts (the closed-form response of the linear modal model),
  fixed-step RK4 through each contact, every onset and end located exactly
  (:mod:`study.solvers.kernels.event_driven`; compiled). Linear damping only.
- ``"explicit"``: velocity Verlet, fixed step (``time_step``; default ``time_step_fraction`` = 0.1
  of the stability limit, rounded down to a whole number of steps per revolution). Velocity-dependent
  forces (damping, χ δ̇) use the predicted velocity v + Δt a (second order). Stability limit
  Δt_max = 2/ω_max, ω_max² the largest eigenvalue of diag(ω_n²) + (K_lin/m) Σ_p φ_p φ_pᵀ with
  K_lin = 1.5 K α^{1/2} the Hertz stiffness linearised at the expected penetration α (elastic Hertz
  impact of the modal mass at the larger of Ωc and the initial speed); for one mode this is
  2/max(ω_1, √(K_lin/m)) roughly. A blow-up stops the run (status ``failed``): a non-finite state, |y| > 100 c, or an
  energy budget broken at a contact end — only the drive feeds energy in, so the mechanical energy
  may not exceed its initial value plus the drive's work (trapezoid sum of F0 cos Ωt Δq_1) by more
  than 5 %. (A per-contact test "rebound ≤ approach" is wrong with several modes: the other modes
  can pass energy to the contact point.)
- ``"implicit"``: scipy ``solve_ivp`` (``time_ode_method``, default LSODA: stiff/non-stiff switching,
  5–8x faster than Radau here for the same impact speeds) with terminal events at
  every contact onset (which sets χ) and end.

Periodicity: the modal state at the end of each revolution is compared with the states 1 … 8
revolutions earlier, scaled by c and Ωc; a period of n revolutions needs the two latest
boundaries to match within ``time_tolerance`` (default 1e-4).
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np

from study.solvers.kernels import event_driven
# the modal span's model, integrators, run and stresses, shared with the crosscheck's replay (kernels/modal_span.py)
from study.solvers.kernels.modal_span import (QUASI_STATIC_LIMIT, ModalModel, build_model, contact_resolution,
                                              initial_state, sample_after, settled_orbit, simulate, stability_limit,
                                              stresses)
from study.solvers.model.options import TimeDomainOptions
from study.solvers.model.point import DesignPoint
from study.solvers.model.result import PointResult
from study.solvers.model.scene import given_span

METHOD = "time-domain"
STEP_FAILURE = "explicit step above the contact stability limit"

__all__ = ["METHOD", "STEP_FAILURE", "QUASI_STATIC_LIMIT", "ModalModel", "TimeDomainOptions", "build_model",
           "contact_resolution", "initial_state", "run", "sample_after", "settled_orbit", "simulate", "solve",
           "stability_limit", "stresses"]


def solve(inputs: Mapping[str, Any]) -> PointResult:
    """The time domain at a point given by its SI inputs (:func:`run` of its :class:`DesignPoint`)."""
    return run(DesignPoint.from_inputs(inputs))


def run(point: DesignPoint) -> PointResult:
    """The ``time-domain`` method (see the module docstring).

    Values (SI): span_length, first_natural_frequency, equivalent_mass (modal mass M L/2),
    drive_amplitude, clearance, axial_curvature, impact_velocity (approach speed of the last
    impact), peak_contact_force (largest over the last period), contact_duration (of the last
    impact), impacts_per_revolution (over the last period), and new: period_revolutions,
    achieved_restitution (rebound/approach of the last impact), time_step, step_limit,
    revolutions_simulated, energy_drift (undamped, undriven runs only); with the event-driven integrator
    also max_deflection, max_bending_stress, max_normal_stress (with its x and t) and
    alternating_bending_stress over one more period (:func:`stresses`; t from its start), and for a
    periodic run max_floquet_multiplier of its orbit (:func:`settled_orbit`).
    """
    option = point.time
    result = PointResult(method=METHOD)
    if given_span(point.scene, result, "the time-domain method",
                  "effective tension {tension:.4g} N buckles the {span:.4g} m span") is None:
        return result
    run = simulate(point)
    model = run["model"]
    vals = result.values
    vals.update(span_length=model.span, first_natural_frequency=model.omega[0] / (2 * np.pi),
                equivalent_mass=model.mass, drive_amplitude=model.drive, clearance=model.clearance,
                axial_curvature=model.curvature, step_limit=run["step_limit"],
                revolutions_simulated=float(run["revolutions_simulated"]))
    if run["time_step"] is not None:
        vals["time_step"] = run["time_step"]
    result.extras.update(time_integrator=run["integrator"], drive_source=model.drive_source,
                         time_damping=model.damping_model, contact_damping=model.contact_damping,
                         time_modes=int(len(model.modes)), contact_points=[float(x) for x in model.points])
    if run["verdict"] == "chattering":
        result.status = "chattering"
        result.message = f"impacts accumulate instead of settling: {run['failure']}"
        return result
    if run["verdict"] == "failed":
        result.status = "failed"
        above = run["time_step"] is not None and run["time_step"] > run["step_limit"]
        reason = STEP_FAILURE if above else "explicit integration blew up" if run["time_step"] else "integration failed"
        result.message = (f"{reason} (step {run['time_step']:.4g} s, limit {run['step_limit']:.4g} s): "
                          f"{run['failure']}" if run["time_step"] else f"{reason}: {run['failure']}")
        return result
    tau = model.period
    n = run["period"] or 1
    t_end = run["revolutions_simulated"] * tau
    last = [r for r in run["impacts"] if r["start"] >= t_end - n * tau]
    messages = []
    if run["verdict"] == "periodic":
        result.status = "ok"
        vals["period_revolutions"] = float(n)
        messages.append(f"periodic: the modal state repeats every {n} revolution(s) (tolerance "
                        f"{option.time_tolerance}) after {run['revolutions_simulated']} revolutions")
        found = settled_orbit(run)
        if found is not None and found.converged:
            vals["max_floquet_multiplier"] = found.largest_multiplier
            messages.append(f"{'stable' if found.stable else 'unstable'}: largest Floquet multiplier "
                            f"{found.largest_multiplier:.4g} (shooting from the settled state)")
        elif found is not None:
            messages.append(f"stability unknown: shooting from the settled state gave {found.status} "
                            f"({found.message})")
    else:
        result.status = "not_periodic"
        messages.append(f"not periodic within {run['revolutions_simulated']} revolutions"
                        if option.time_check_periodic else
                        f"periodicity not checked; {run['revolutions_simulated']} revolutions simulated")
    if run["impacts"]:
        rec = run["impacts"][-1]
        vals.update(impact_velocity=rec["approach"], contact_duration=rec["duration"],
                    achieved_restitution=rec["rebound"] / rec["approach"] if rec["approach"] > 0 else np.nan,
                    peak_contact_force=max(r["peak"] for r in (last or [rec])))
    vals["impacts_per_revolution"] = len(last) / n
    if not last and run["verdict"] == "periodic":
        result.status = "no_impact"
        messages.append("no impact in the periodic state")
    if model.drive == 0 and model.damping_model == "none":
        e = run["energies"]
        vals["energy_drift"] = float(np.max(np.abs(e - e[0])) / e[0]) if e[0] > 0 else 0.0
    result.extras["impact_record"] = [dict(r) for r in run["impacts"][-8:]]
    samples = sample_after(run)
    if samples is None:
        messages.append("no stresses: they are sampled from the event-driven integrator only")
    elif samples.outcome != event_driven.OK:
        messages.append("no stresses: the revolution sampled after the run stopped (blow-up or chatter)")
    elif (unresolved := contact_resolution(model, samples)) is not None:
        messages.append(f"no stresses: {unresolved}")
        if result.status == "ok":
            result.status = "not_converged"
    else:
        vals.update(stresses(model, samples))
        messages.append(f"stresses over the {'period' if run['verdict'] == 'periodic' else 'next revolution'} "
                        f"after the run")
    result.message = "; ".join(messages)
    return result
