"""Is the periodic solution an orbit of the real contact? (method ``crosscheck``; docs/model.md §11)

The periodic methods assume the contact: a Lee half-sine pulse of impulse J = m_e (1 + e) V_p at
midspan, once per (half) period. The time domain knows only the Hertz contact. This method puts the
periodic solution's own motion into the time domain and lets the real contact act on it:

1. ``fast`` solves the point (span search included); its smallest valid span, impact and stresses.
2. The periodic solution's modal state (odd modes 1 … N, N = ``solver.modes``; even modes at rest) a
   little before the impact, at t = −P/50 (P the time between impacts), starts the time domain
   (:mod:`study.solvers.kernels.modal_span`, the ``time-domain`` method's) on the same span with the same modes, the
   same scene as the periodic model (no mud damping, no drive: the periodic solution has neither), a Hertz contact at
   midspan with the stiffness at the periodic solution's own contact curvature κ, and restitution e.
3. One revolution is integrated (event-driven) and sampled (:mod:`study.solvers.kernels.trajectory`), and
   compared with the periodic solution: the impulse and the peak force of the first contact, the
   largest normal stress and deflection over the revolution (time-domain fields with the quasi-static
   correction), and whether the modal state after one revolution is the state it started from
   (``periodicity_defect``: largest difference over the modes, q in units of c and q̇ in units of Ω c).

4. With an elastic contact (e = 1) the replay's scene is conservative and may have a periodic orbit:
   shooting (:mod:`study.solvers.kernels.orbit`) from the periodic solution's state finds the nearest one, its
   stability (Floquet multipliers), peak force and largest normal stress (:func:`real_orbit`). With
   e < 1 nothing feeds the energy the contact takes, so there is none to find.

Within ``check_tolerance`` (default 0.02, relative; the defect against the same number) on all of them:
status ``ok``. Otherwise status ``disagrees`` and the message names each quantity that differs, both
values, and the reason the model gives for it: the impulse the real contact delivers differs from the
closure's J (its mass m_e is not the mass the span strikes with), the contact's force is not Lee's
half-sine (Lee's pulse is imposed on the span, not a contact: at its peak the periodic solution's
midspan need not be into the wall by the Hertz approach its force needs, :func:`lee_peak_kinematics`;
the equivalent mass alone on the same contact shows how much is the contact law), or the contact
dissipates energy that the undamped periodic solution never loses (e < 1: Lee's pulse does no net work
over a period of the undamped periodic response, a contact with e < 1 does; the paper's end moments,
docs/model.md §7, feed only what the mud's damping takes). A point without a periodic solution keeps
``fast``'s status.
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np

from study.physics import beam, contact, hertz
from study.solvers.kernels import event_driven, modal_span, orbit, trajectory
from study import solvers
from study.solvers.kernels import impact as impact_model
from study.solvers.model.options import CrosscheckOptions, Options
from study.solvers.model.point import DesignPoint
from study.solvers.model.result import PointResult
from study.solvers.model.scene import Scene

METHOD = "crosscheck"
DEFAULT_TOLERANCE = CrosscheckOptions.default("check_tolerance")
#: Compared quantities: name -> (output of the check, what it is).
COMPARED = {
    "impulse": ("impulse_ratio", "impulse of the first contact"),
    "peak_contact_force": ("peak_force_ratio", "peak contact force"),
    "max_normal_stress": ("normal_stress_ratio", "largest normal stress over the revolution"),
    "max_deflection": ("deflection_ratio", "largest deflection over the revolution"),
}


def periodic_state(scene: Scene, impact: impact_model.Impact, options: Options, modes: int,
                   t: float) -> tuple[np.ndarray, np.ndarray]:
    """Modal coordinates q_n [m] and velocities q̇_n [m/s] of modes n = 1 … ``modes`` at time t [s] of the
    periodic solution (t = 0: a pulse starts at the wall y = +c); even modes are at rest (symmetric load).

    q_n = (−J) g_n/(M L/2) · q̂_n(t), q̂ the unit-impulse response of :func:`beam.modal_periodic_response`
    (the load pushes the pipe off the wall, along −y)."""
    L = impact.span_length
    odd = impact_model.odd_modes(modes)
    omega = scene.natural_frequencies(L, odd)
    g = beam.modal_load_factors(odd, L, impact.contact_half_length, options.load_shape)
    amp = -impact.impulse * g / (0.5 * scene.props["mass_per_length"] * L)
    r = beam.modal_periodic_response(np.array([[t]]), omega, impact.contact_duration, scene.period, scene.pattern)
    q, v = np.zeros(modes), np.zeros(modes)
    q[odd.astype(int) - 1] = amp * r.displacement[0]
    v[odd.astype(int) - 1] = amp * r.velocity[0]
    return q, v


def replay(point: DesignPoint, scene: Scene, impact: impact_model.Impact,
           options: Options) -> dict[str, Any]:
    """The periodic solution's state run through one revolution of the real contact (module docstring,
    step 2–3). Returns the time-domain model, its design point (``point`` at the impact's span with the replay's
    time-domain settings) and event system, the samples (or None with ``failure``), the start time [s] relative to
    the periodic pulse start and the start state."""
    n_modes = int(options.modes)
    start = -scene.impact_interval / 50.0
    q0, v0 = periodic_state(scene, impact, options, n_modes, start)
    td_point = point.changed(scene=dict(span_length=impact.span_length), sdof=dict(drive_amplitude=0.0),
                             time=dict(time_modes=n_modes, time_damping="none", contact_points=(0.5,),
                                       time_integrator="event", time_revolutions=0, initial_state=(q0, v0)))
    model = modal_span.build_model(td_point)
    a_sum, b_sum = hertz.curvature_sums(scene.outer_radius, scene.hole_radius, impact.axial_curvature)
    model.stiffness = float(hertz.hertz_stiffness(a_sum, b_sum, scene.compliance_sum))
    run = modal_span.simulate(td_point, model)
    out = dict(model=model, start=start, state=np.concatenate((q0, v0)), samples=None, failure=run["failure"],
               system=run.get("system"), point=td_point)
    if run["failure"] is None:
        out["samples"] = modal_span.sample_after(run, revolutions=1)
    return out


def compare(run: Mapping[str, Any]) -> dict[str, Any]:
    """Time-domain values of :data:`COMPARED` and the periodicity defect from the replay ``run``, with
    the number of contacts, the duration and achieved restitution (midspan rebound/approach speed) of the
    first contact, and the relative change of the span's mechanical energy over the revolution."""
    model, s = run["model"], run["samples"]
    first = s.contacts[0]
    inside = (s.times >= first[1]) & (s.times <= first[2])
    force = np.abs(s.forces[inside, first[0]])
    mid = model.phi[0]
    td = modal_span.stresses(model, s)
    scale = model.state_scale()
    end_state = np.concatenate((s.q[-1], s.v[-1]))
    i_on, i_off = np.flatnonzero(inside)[[0, -1]]
    approach, rebound = mid @ s.v[i_on], mid @ s.v[i_off]
    return dict(
        impulse=float(np.trapezoid(force, s.times[inside])), peak_contact_force=float(force.max()),
        max_normal_stress=td["max_normal_stress"], max_deflection=td["max_deflection"],
        contacts=len(s.contacts), contact_duration=first[2] - first[1],
        achieved_restitution=float(-rebound / approach) if approach else np.nan,
        periodicity_defect=float(np.max(np.abs(end_state - run["state"]) / scale)),
        energy_change=model.energy(s.q[-1], s.v[-1]) / model.energy(*np.split(run["state"], 2)) - 1.0,
    )


def ratios(periodic_values: Mapping[str, float], td: Mapping[str, Any]) -> dict[str, float]:
    """Time domain over periodic solution for each of :data:`COMPARED`, keyed by its output name."""
    return {output: td[name] / periodic_values[name] for name, (output, _) in COMPARED.items()}


def verdict(periodic_values: Mapping[str, float], td: Mapping[str, Any], scene: Scene,
            impact: impact_model.Impact, tolerance: float) -> list[str]:
    """The reasons the time domain disagrees with the periodic solution (empty: it agrees)."""
    reasons = []
    if td["contacts"] != scene.impacts_per_revolution:
        reasons.append(f"the real contact gives {td['contacts']} contact(s) in the revolution, the periodic "
                       f"solution {scene.impacts_per_revolution}")
    ratio_of = ratios(periodic_values, td)
    for name, (output, what) in COMPARED.items():
        ratio = ratio_of[output]
        if abs(ratio - 1.0) > tolerance:
            reasons.append(f"{what}: time domain {td[name]:.4g}, periodic {periodic_values[name]:.4g} "
                           f"(ratio {ratio:.3g})")
    if td["periodicity_defect"] > tolerance:
        reasons.append(f"the modal state does not return after one revolution (defect "
                       f"{td['periodicity_defect']:.3g} in units of c and Omega c)")
    if reasons:
        if abs(ratio_of["impulse_ratio"] - 1.0) > tolerance:
            reasons.append(f"why: the closure's impulse J = m_e (1 + e) V_p takes m_e = {impact.equivalent_mass:.4g} "
                           "kg "
                           f"({scene.impact_mass} mass); the span's modes take {ratio_of['impulse_ratio']:.3g} "
                           "J from the Hertz contact")
        if abs(ratio_of["peak_force_ratio"] - 1.0) > tolerance:
            one_mass = td["one_mass_peak_force"] / periodic_values["peak_contact_force"]
            gap = td["midspan_at_lee_peak"]
            reasons.append(f"why: Lee's half-sine (the impulse m_e (1 + e) V_p over the elastic Hertz duration "
                           f"T_L = {impact.contact_duration * 1e3:.3g} ms) is imposed on the span, not a contact: at "
                           f"its peak the periodic solution's midspan is {abs(gap) * 1e6:.3g} um "
                           f"{'into' if gap > 0 else 'off'} the wall, where that force needs "
                           f"{td['approach_at_lee_peak'] * 1e6:.3g} um of Hertz approach; the real contact follows "
                           f"the span's modes and peaks {ratio_of['peak_force_ratio']:.3g}x Lee's (its contact lasts "
                           f"{td['contact_duration'] * 1e3:.3g} ms). The contact law alone, the equivalent mass on the "
                           f"same contact, peaks {one_mass:.3g}x Lee's (exactly 1 at e = 1)")
        found = td.get("orbit", {})
        if found.get("status") == "converged":
            reasons.append(f"the real contact's periodic orbit nearest the periodic solution (shooting, "
                           f"{found['distance']:.3g} from its state in units of c and Omega c) peaks "
                           f"{found['peak_force_ratio']:.3g}x Lee's with {found['normal_stress_ratio']:.3g}x the "
                           f"stress, and is {'stable' if found['stable'] else 'unstable'} (largest Floquet "
                           f"multiplier {found['largest_multiplier']:.3g})")
        elif found:
            reasons.append(f"no periodic orbit of the real contact near the periodic solution: {found['message']}")
        if td["energy_change"] < -tolerance:
            reasons.append(f"why: the contact dissipates {-td['energy_change']:.3g} of the span's energy per "
                           "revolution "
                           f"(e = {scene.restitution:g}), which the undamped, undriven periodic solution never loses: "
                           "Lee's pulse does no net work over a period of the undamped periodic response; the "
                           "paper's energy input (end moments, docs/model.md §7) balances the mud's damping only")
    return reasons


def check(point: DesignPoint, scene: Scene, impact: impact_model.Impact, options: Options,
          periodic_values: Mapping[str, float], tolerance: float = DEFAULT_TOLERANCE) -> tuple[dict | None, list[str]]:
    """Replay and compare one periodic solution (``impact`` at a root of condition 2, with its
    ``periodic_values``: impulse, peak_contact_force, max_normal_stress, max_deflection). Returns the
    time-domain values of :func:`compare` (None when the replay failed or never reached the wall) and
    the reasons for disagreement (empty: agreement within ``tolerance``)."""
    run = replay(point, scene, impact, options)
    samples = run["samples"]
    if samples is None or samples.outcome != event_driven.OK:
        return None, ["the time-domain replay failed: " + str(run["failure"] or "integration stopped")]
    if not samples.contacts:
        return None, ["the periodic solution's motion does not reach the wall in the time domain"]
    td = compare(run)
    model, velocity = run["model"], impact.impact_velocity
    td["one_mass_peak_force"] = one_mass_peak_force(impact.equivalent_mass, velocity, model.stiffness,
                                                    model.hysteresis(velocity))
    td["midspan_at_lee_peak"], td["approach_at_lee_peak"] = lee_peak_kinematics(
        scene, impact, options, model.stiffness, periodic_values["peak_contact_force"])
    td["orbit"] = real_orbit(run, scene, periodic_values)
    return td, verdict(periodic_values, td, scene, impact, tolerance)


def real_orbit(run: Mapping[str, Any], scene: Scene, periodic_values: Mapping[str, float]) -> dict[str, Any]:
    """The real contact's periodic orbit nearest the periodic solution (:func:`study.solvers.kernels.orbit.find_orbit`
    from the replay's start state, section at that time, one time between impacts, mirrored for the
    alternating pattern) and its stability, peak force and stresses over one revolution against the
    periodic solution's. Only an elastic contact (e = 1) can have one: the replay's scene has no energy
    input, so with e < 1 every contact loses energy and no motion with contact repeats (status
    ``no_orbit``)."""
    model = run["model"]
    if model.restitution < 1.0:
        return dict(status="no_orbit", message=f"the contact dissipates energy (e = {model.restitution:g}) and "
                    "nothing feeds it, so no motion with contact repeats")
    scale = model.state_scale()
    found = orbit.find_orbit(run["system"], run["state"], 0.0, scene.impact_interval, scale,
                             mirror=scene.pattern != "one_wall")
    out = dict(status=found.status, message=found.message)
    if not found.converged:
        return out
    points = len(model.points)
    active, chi, peak = np.zeros(points, bool), np.zeros(points), np.zeros(points)
    samples = trajectory.sample_revolution(run["system"], model.contact_forces, 0.0, model.period, found.state,
                                           active, chi, peak)
    stresses = modal_span.stresses(model, samples)
    out.update(state=found.state, jacobian=found.jacobian, peak_force=found.peak_force,
               largest_multiplier=found.largest_multiplier,
               stable=found.stable, distance=float(np.max(np.abs(found.state - run["state"]) / scale)),
               peak_force_ratio=found.peak_force / periodic_values["peak_contact_force"],
               normal_stress_ratio=stresses["max_normal_stress"] / periodic_values["max_normal_stress"])
    return out


def lee_peak_kinematics(scene: Scene, impact: impact_model.Impact, options: Options,
                        stiffness: float, peak_force: float) -> tuple[float, float]:
    """(y − c, (F̂/K)^{2/3}) [m] at the peak of Lee's pulse, t = T_L/2: how far the periodic solution's
    midspan (the same ``options.modes`` modes as the replay, :func:`periodic_state`) is into the wall
    while the pulse peaks, and the Hertz approach its peak force F̂ [N] needs on the contact of stiffness
    K [N m^-3/2] (F = K α^{3/2}, paper eq. 7–8, elastic). A contact would have the two equal; Lee's
    pulse is imposed, so they need not be."""
    q, _ = periodic_state(scene, impact, options, int(options.modes), 0.5 * impact.contact_duration)
    midspan = np.sin(0.5 * np.pi * np.arange(1, len(q) + 1))
    return float(midspan @ q - scene.clearance), float((peak_force / stiffness) ** (2.0 / 3.0))


def one_mass_peak_force(mass: float, velocity: float, stiffness: float, hysteresis: float) -> float:
    """Peak force [N] of a Hertz contact of stiffness K [N m^-3/2] with Hunt–Crossley damping χ
    (``hysteresis`` [s/m]; the replay's, ``ModalModel.hysteresis``) struck by one mass [kg] at
    ``velocity`` [m/s] (:func:`study.physics.contact.hertz_wall_impact`): for the closure's m_e and V_p, what the
    contact law alone does to Lee's peak, apart from the span's modes."""
    return float(contact.hertz_wall_impact(mass, stiffness, velocity, hysteresis).max_force)


def solve(inputs: Mapping[str, Any]) -> PointResult:
    """The crosscheck at a point given by its SI inputs (:func:`run` of its :class:`DesignPoint`)."""
    return run(DesignPoint.from_inputs(inputs))


def run(point: DesignPoint) -> PointResult:
    """The ``crosscheck`` method (module docstring): the ``fast`` method (through the registry,
    :func:`study.solvers.method`) at the point, replayed."""
    result = solvers.method("fast")(point)
    result.method = METHOD
    if result.status != "ok":
        result.message = f"no periodic solution to check: {result.message}"
        return result
    options, scene = point.periodic, point.scene
    v = result.values  # the impact again, from fast's own fixed point of T_L and the contact length
    impact = impact_model.impact_at(scene, v["span_length"], options, duration=v["contact_duration"],
                                half_length=v["contact_half_length"])
    tolerance = float(point.check.check_tolerance)
    td, reasons = check(point, scene, impact, options, v, tolerance)
    if td is not None:
        v.update(ratios(v, td))
        v["periodicity_defect"] = td["periodicity_defect"]
        found = td["orbit"]
        for name, key in (("orbit_peak_force_ratio", "peak_force_ratio"), ("orbit_normal_stress_ratio",
                          "normal_stress_ratio"), ("orbit_distance", "distance"),
                          ("max_floquet_multiplier", "largest_multiplier")):
            v[name] = float(found.get(key, np.nan))
        result.extras["time_domain"] = dict(td)
    if reasons:
        result.status = "disagrees"
        result.message = "the real contact disagrees with the periodic solution: " + "; ".join(reasons)
    else:
        result.message = (f"{result.message}; the real contact agrees with the periodic solution within "
                          f"{tolerance:g} over one revolution")
    return result
