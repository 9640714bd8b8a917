"""The one-degree-of-freedom screen of a design point (method ``sdof``; docs/model.md §8, paper fig. 1).

The span's first mode, y(x, t) = q(t) sin(πx/L), reduced to a mass on a spring between the two
walls of the hole at q = ±c, driven harmonically at the rotary speed Ω, striking the walls with
Newton's law of restitution. Between impacts the motion is known in closed form
(:mod:`study.physics.oscillator`), so the period-1 impacting orbit and its Floquet multipliers are
found exactly, without time stepping.

Equivalent parameters (our choices, stated):

- **mass** ``sdof_mass``: ``"modal"`` (default) m = M L/2, the modal mass of sin(πx/L) referred to
  midspan (kinetic energy ½ M ∫ ẏ² dx = ½ (M L/2) q̇²). It is the mass of the energy-consistent
  (Rayleigh–Ritz/Galerkin) one-mode model, the same as the first modal equation of the
  ``time-domain`` method with contact at midspan, so the two methods can be compared directly.
  ``"momentum"``: the paper's m_e = 2 M L/π (eq. 5, equal momentum), 27 % heavier; it changes the
  Hertz peak force (∝ m^(3/5)) and the drive per unit mass, not the natural frequency.
- **stiffness** k = m ω₁², ω₁ from :func:`study.physics.section.natural_frequencies` (beam-column,
  effective tension): the one-mode model reproduces the span's first natural frequency exactly.
- **clearance** c = R_hole − r_o, walls at ±c.
- **drive** F0 cos Ωt, a generalised force on the first mode: what a distributed whirl/unbalance
  load p(x, t) = (2F0/L) sin(πx/L) cos Ωt puts into it (input ``drive_amplitude`` [N]). The paper
  feeds energy through end moments instead (docs/model.md §7); a harmonic force at Ω is our choice. When
  ``drive_amplitude`` is not given, the default is the **mean impact force of the paper's prescribed
  closure**: F0 = n_i m (1 + e) Ω c/τ (n_i = 2 impacts per revolution for the alternating pattern,
  1 for one wall; V_p = Ω c; τ = 2π/Ω) — a force of the size the wall exerts on average, not a
  hidden constant. ``result.extras['drive_source']`` says which was used.
- **restitution** e from the inputs.
- **damping** ``sdof_damping``: ``"mud"`` (default) the paper's linearised drag (docs/model.md §7,
  appendix A): c_eq = 8 D Ω Y/(3π) per unit length for harmonic motion of amplitude Y at Ω, with
  Y = c sin(πx/L) (the assumed mode) and projected on the mode: c_modal = ∫ c_eq(x) sin²(πx/L) dx
  = (8 D Ω c/(3π)) (4L/(3π)). ``"none"``: undamped.
- **side force** ``side_force`` [N] (default 0): a constant generalised force towards the +c wall
  (e.g. the weight component of an inclined hole), the preload a one-wall orbit needs in a hole
  with two walls; the symmetric (alternating) orbit exists only without it.
- **pattern** ``impact_pattern``: ``"alternating"`` (default) looks for the symmetric orbit that
  strikes +c and −c half a revolution apart (x(t + τ/2) = −x(t)), ``"one_wall"`` for the orbit
  striking +c once per revolution (checked not to reach −c).

Symmetric orbit. The drive is odd under a half-period shift, so w(s) = −x(s − τ/2) obeys the same
equation as x. The flight of x from +c (leaving at t_i with −e v) to −c is the flight of w from
(−c, +e v) at t_i + τ/2 to +c; a symmetric orbit is a fixed point of this half-map R with the hit
at t_i + τ and the same approach speed. The flight is affine in the launch velocity, which gives
it explicitly for every phase; one scalar residual is bracketed over a phase grid and solved with
brentq (as :func:`oscillator.periodic_orbits` does for one wall). Stability: the analytic Jacobian
of R (implicit function theorem on the hit, as :func:`oscillator.impact_map_jacobian`); the
Floquet multipliers of the period-τ orbit are the squares of R's eigenvalues (both reported).
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np

from study.physics import hertz, oscillator
from study.solvers.model.equivalent import EquivalentSdof, equivalent_parameters
from study.solvers.model.point import DesignPoint
from study.solvers.model.result import PointResult
from study.solvers.model.scene import given_span

#: Stability verdicts of the screen -> the STATUS flag used until dedicated flags exist.
VERDICT_STATUS = {
    "stable": "ok",
    "no_impact": "no_impact",
    "period_doubling": "period_doubling",
    "unstable": "unstable",
    "chattering": "chattering",
    "sticking": "sticking",
    "not_periodic": "not_periodic",
}



def impact_params(par: EquivalentSdof) -> oscillator.ImpactParams:
    """The :class:`oscillator.ImpactParams` of the SDOF (wall at +c)."""
    return oscillator.ImpactParams(mass=par.mass, stiffness=par.stiffness, damping=par.damping,
                                   force_amplitude=par.drive_amplitude,
                                   forcing_frequency=par.rotary_speed, gap=par.clearance,
                                   constant_force=par.side_force,
                                   restitution=par.restitution)


# --- closed-form pieces (public oscillator API only) ----------------------------------------------


def _unforced(p: oscillator.ImpactParams) -> oscillator.ImpactParams:
    return p._replace(force_amplitude=0.0, constant_force=0.0)


def _transition(dt: float, p: oscillator.ImpactParams) -> np.ndarray:
    """Homogeneous transition matrix Φ(dt) (2×2), from the closed-form unforced flight."""
    q = _unforced(p)
    a = oscillator.flight_state(dt, (1.0, 0.0), q)
    b = oscillator.flight_state(dt, (0.0, 1.0), q)
    return np.array([[float(a.x), float(b.x)], [float(a.v), float(b.v)]])


def _particular(t, p: oscillator.ImpactParams):
    """Steady harmonic particular solution (x_p, v_p) of m ẍ + c ẋ + k x = F0 cos Ωt (vectorised)."""
    den = complex(p.stiffness - p.mass * p.forcing_frequency**2, p.damping * p.forcing_frequency)
    z = p.force_amplitude / den * np.exp(1j * p.forcing_frequency * np.asarray(t, float))
    return z.real, (1j * p.forcing_frequency * z).real


def _accel(t, x, v, p: oscillator.ImpactParams) -> float:
    return (p.force_amplitude * np.cos(p.forcing_frequency * t) - p.damping * v - p.stiffness * x) / p.mass


def half_map_jacobian(t_start, y_start, t_hit, v_hit, dy_dv, p: oscillator.ImpactParams) -> np.ndarray:
    """∂(t_hit, v_hit)/∂(t_i, v_i) of a flight launched at t_start = t_i + const from y_start.

    dy_dv = ∂y_start/∂v_i. ∂y(s)/∂v_i = Φ(Δ) dy_dv; ∂y(s)/∂t_i = −Φ(Δ) f(t_start, y_start) at fixed
    s; the hit x(s) = c gives ∂s/∂p = −(∂x/∂p)/ẋ(s) and ∂v/∂p = ∂ẋ/∂p + ẍ(s) ∂s/∂p.
    """
    Phi = _transition(t_hit - t_start, p)
    f0 = np.array([y_start[1], _accel(t_start, y_start[0], y_start[1], p)])
    acc = _accel(t_hit, p.gap, v_hit, p)
    J = np.empty((2, 2))
    for j, dy in enumerate((-Phi @ f0, Phi @ np.asarray(dy_dv, float))):
        ds = -dy[0] / v_hit
        J[0, j] = ds
        J[1, j] = dy[1] + acc * ds
    return J


def _classify(full_multipliers, half_multipliers=None):
    mags = np.abs(full_multipliers)
    if np.all(mags < 1):
        return "stable", "stable: all |Floquet multipliers| < 1"
    if half_multipliers is not None:
        neg = [m for m in half_multipliers if abs(m.imag) < 1e-12 and m.real < -1]
        if neg:
            return "unstable", (f"unstable: the half-period map has a real multiplier {neg[0].real:.6g} < -1 "
                                "(symmetry-breaking instability of the alternating orbit)")
    neg = [m for m in full_multipliers if abs(m.imag) < 1e-12 and m.real < -1]
    if neg:
        return "period_doubling", (f"a real Floquet multiplier {neg[0].real:.6g} < -1: past a "
                                   "period-doubling bifurcation (unstable)")
    return "unstable", f"unstable: max |Floquet multiplier| = {mags.max():.6g}"


def symmetric_orbits(p: oscillator.ImpactParams, n_scan: int = 400) -> list[dict]:
    """Symmetric period-1 orbits striking +c and −c alternately, half a period apart.

    Returns a list of dicts: phase τ_i ∈ [0, T) of the +c impact [s], velocity v [m/s], the
    half-map Jacobian and its eigenvalues ``half_multipliers``, the Floquet multipliers of the
    period-T orbit ``multipliers`` (= squares), verdict and message.
    """
    from scipy.optimize import brentq

    T = 2 * np.pi / p.forcing_frequency
    h = 0.5 * T
    c, e = p.gap, p.restitution
    Phi = _transition(h, p)
    # generic: the position at +c gives u, the rebound u = e v1 is the equation in τ; degenerate (T/2 a
    # multiple of π/ω_d, Φ01 = 0): the position does not depend on u and is the equation in τ, the rebound
    # gives u (as oscillator.periodic_orbits)
    degenerate = abs(Phi[0, 1]) < 1e-12 * h
    if degenerate and abs(1.0 - e * Phi[1, 1]) < 1e-12:
        return []  # a continuous family, no isolated orbit

    def launch(tau):  # w leaves −c at s0 = τ + T/2 with u = e v, hits +c at s1 = τ + T
        tau = np.asarray(tau, float)
        xp0, vp0 = _particular(tau + h, p)
        xp1, vp1 = _particular(tau + T, p)
        if degenerate:
            u = e * (vp1 + Phi[1, 0] * (-c - xp0) - Phi[1, 1] * vp0) / (1.0 - e * Phi[1, 1])
        else:
            u = (c - xp1 - Phi[0, 0] * (-c - xp0)) / Phi[0, 1] + vp0
        v1 = vp1 + Phi[1, 0] * (-c - xp0) + Phi[1, 1] * (u - vp0)
        return u, v1, xp0, xp1

    def resid(tau):
        u, v1, xp0, xp1 = launch(tau)
        return xp1 + Phi[0, 0] * (-c - xp0) - c if degenerate else e * v1 - u

    taus = np.linspace(0.0, T, int(n_scan) + 1)
    r = resid(taus)
    out = []
    for i in range(len(taus) - 1):
        if not (r[i] == 0 or r[i] * r[i + 1] < 0):
            continue
        tau = taus[i] if r[i] == 0 else brentq(lambda s: float(resid(s)), taus[i], taus[i + 1], xtol=1e-15)
        if abs(float(resid(tau))) > 1e-8 * (1 + np.max(np.abs(r))):
            continue
        u, v1 = (float(q) for q in launch(tau)[:2])
        if u <= 0 or v1 <= 0:
            continue
        v = v1
        # admissible flight: stays within the walls, first reaches +c at τ + T
        s = np.linspace(tau + h, tau + T, 401)[1:-1]
        w = oscillator.flight_state(s, (-c, u), p, tau + h).x
        if np.any(np.abs(w) > c * (1 + 1e-9)):
            continue
        J = half_map_jacobian(tau + h, (-c, u), tau + T, v, (0.0, e), p)
        half = np.linalg.eigvals(J)
        full = half**2
        verdict, msg = _classify(full, half)
        out.append(dict(phase=float(tau % T), velocity=v, period=T, jacobian=J, half_multipliers=half,
                        multipliers=full, verdict=verdict, message="alternating walls: " + msg))
    return out


def one_wall_orbit(p: oscillator.ImpactParams, n_scan: int = 400) -> list[dict]:
    """Period-1 orbits striking +c once per period (oscillator.periodic_orbits), kept if they stay above −c."""
    T = 2 * np.pi / p.forcing_frequency
    out = []
    try:
        found = oscillator.periodic_orbits(p, 1, n_scan=n_scan)
    except ValueError:  # brentq bracket lost at a grazing flight inside oscillator.next_impact_time
        found = []
    for o in found:
        s = np.linspace(o.phase, o.phase + T, 401)[1:-1]
        x = oscillator.flight_state(s, (p.gap, -p.restitution * o.velocity), p, o.phase).x
        if np.min(x) < -p.gap:
            continue
        verdict, msg = _classify(o.multipliers)
        out.append(dict(phase=o.phase, velocity=o.velocity, period=o.period, jacobian=o.jacobian,
                        half_multipliers=None, multipliers=o.multipliers, verdict=verdict,
                        message="one wall: " + msg))
    return out


def free_amplitude(p: oscillator.ImpactParams) -> float:
    """Steady amplitude of the drive without walls, F0/|k − mΩ² + icΩ| [m] (inf at undamped resonance)."""
    den = abs(complex(p.stiffness - p.mass * p.forcing_frequency**2, p.damping * p.forcing_frequency))
    return abs(p.force_amplitude) / den if den > 0 else np.inf


def solve(inputs: Mapping[str, Any]) -> PointResult:
    """The sdof screen at a point given by its SI inputs (:func:`run` of its :class:`DesignPoint`)."""
    return run(DesignPoint.from_inputs(inputs))


def run(point: DesignPoint) -> PointResult:
    """The ``sdof`` method: period-1 impacting orbit of the first-mode oscillator and its stability.

    Values (SI): span_length, first_natural_frequency, equivalent_mass (the SDOF mass),
    sdof_stiffness, sdof_damping, drive_amplitude, impact_velocity, impulse (m (1 + e) v),
    impacts_per_revolution, max_approach, hertz_duration, peak_contact_force (elastic Hertz impact
    of the SDOF mass at v, :func:`hertz.hertz_impact`), free_amplitude, max_floquet_multiplier.
    Extras: floquet_multipliers, half_period_multipliers, stability, drive_source, orbit_phase, orbits_found.
    """
    result = PointResult(method="sdof")
    if given_span(point.scene, result, "the sdof screen", "effective tension {tension:.4g} N is at or below the Euler "
                  "load of the {span:.4g} m span: no first mode to reduce to") is None:
        return result
    par = equivalent_parameters(point.scene, point.sdof)
    p = impact_params(par)
    v = result.values
    v.update(span_length=par.span_length, first_natural_frequency=par.omega1 / (2 * np.pi),
             equivalent_mass=par.mass, sdof_stiffness=par.stiffness, sdof_damping=par.damping,
             drive_amplitude=par.drive_amplitude, clearance=par.clearance)
    result.extras.update(drive_source=par.drive_source, sdof_mass_model=par.mass_model,
                         sdof_damping_model=par.damping_model, impact_pattern=par.pattern)
    X = free_amplitude(p)
    v["free_amplitude"] = X
    if p.stiffness > 0:  # the static offset of the side force adds to the excursion
        X = X + abs(p.constant_force) / p.stiffness
    if not np.isfinite(X):
        result.status = "resonance"
        result.message = "undamped drive at the first natural frequency: the free amplitude is unbounded"
        return result
    if par.pattern == "alternating" and par.side_force != 0:
        result.status = "incomplete"
        result.message = "a side force breaks the symmetry: no alternating orbit (use impact_pattern one_wall)"
        return result
    n_scan = int(point.sdof.sdof_scan)
    orbits = symmetric_orbits(p, n_scan) if par.pattern == "alternating" else one_wall_orbit(p, n_scan)
    result.extras["orbits_found"] = len(orbits)
    stable = [o for o in orbits if o["verdict"] == "stable"]
    orbit = stable[0] if stable else (orbits[0] if orbits else None)
    messages = []
    if orbit is None:
        if X < par.clearance:
            verdict = "no_impact"
            messages.append(f"no impact: no period-1 impacting orbit, and the drive alone moves the mass "
                            f"{X / par.clearance:.3g} c (< c) in steady state")
            v.update(impacts_per_revolution=0.0, impact_velocity=0.0, impulse=0.0)
        else:
            verdict, msg = _without_orbit(p, par)
            messages.append(msg)
    else:
        verdict = orbit["verdict"]
        messages.append(orbit["message"])
        vel = orbit["velocity"]
        elastic = hertz.hertz_impact(par.mass, vel, par.hertz_stiffness)
        v.update(impact_velocity=vel, impulse=par.mass * (1 + par.restitution) * vel,
                 impacts_per_revolution=2.0 if par.pattern == "alternating" else 1.0,
                 max_approach=float(elastic.max_approach), hertz_duration=float(elastic.duration),
                 peak_contact_force=float(elastic.max_force), axial_curvature=par.axial_curvature,
                 max_floquet_multiplier=float(np.max(np.abs(orbit["multipliers"]))))
        result.extras.update(floquet_multipliers=[complex(z) for z in orbit["multipliers"]],
                             orbit_phase=orbit["phase"])
        if orbit["half_multipliers"] is not None:
            result.extras["half_period_multipliers"] = [complex(z) for z in orbit["half_multipliers"]]
        if X < par.clearance:
            messages.append(f"a non-impacting steady state (amplitude {X / par.clearance:.3g} c) coexists")
    result.extras["stability"] = verdict
    result.status = VERDICT_STATUS[verdict]
    result.message = "; ".join(messages)
    return result


def _without_orbit(p: oscillator.ImpactParams, par, revolutions: int = 60) -> tuple[str, str]:
    """Verdict when the drive reaches the wall but no admissible stable-or-not period-1 orbit exists.

    The motion between both walls is simulated event by event from rest at the centre for
    ``revolutions`` revolutions (:func:`two_wall_impacts`): impact speeds collapsing towards zero
    mean chattering (sticking when the net force then holds the mass on the wall); otherwise the
    impact sequence of the last revolutions is tested for a period of up to 8 revolutions.
    """
    T = 2 * np.pi / p.forcing_frequency
    imp = two_wall_impacts(0.0, (0.0, 0.0), p, 40 * revolutions, t_end=revolutions * T)
    if not imp:
        return "no_impact", (f"no period-1 orbit and no impact in {revolutions} revolutions from rest (free "
                             f"amplitude {free_amplitude(p) / p.gap:.3g} c)")
    speeds = np.array([i[2] for i in imp])
    if len(imp) >= 3 and speeds[-1] < 1e-6 * speeds.max():
        wall = imp[-1][1]
        # net force towards that wall at rest on it: drive and side force (towards +c), less the spring k c
        force = wall * (p.force_amplitude * np.cos(p.forcing_frequency * imp[-1][0]) + p.constant_force) \
            - p.stiffness * p.gap
        kind = "sticking" if force > 0 else "chattering"
        return kind, f"no period-1 orbit; simulated from rest the impact speeds collapse to zero ({kind})"
    times = np.array([i[0] for i in imp])
    late = times >= times[-1] - 10 * T
    per_rev = late.sum() / 10.0
    for n in range(1, 9):  # the last impacts repeat those n revolutions earlier: period n
        k = int(np.sum(times > times[-1] - n * T + 1e-9 * T))
        if k == 0 or 2 * k > len(imp):
            continue
        dt = times[-k:] - times[-2 * k:-k]
        if (np.allclose(dt, n * T, atol=1e-6 * T)
                and np.allclose(speeds[-k:], speeds[-2 * k:-k], rtol=1e-6, atol=1e-9 * speeds.max())):
            return "not_periodic", (f"no period-1 orbit; simulated from rest the motion settles to a period of "
                                    f"{n} revolutions with {k} impacts per period")
    return "not_periodic", (f"no period-1 orbit; simulated from rest for {revolutions} revolutions: "
                            f"{len(imp)} impacts, {per_rev:.3g} per revolution over the last 10, not "
                            "a period-1 orbit (higher period, chaotic or still transient)")


def two_wall_impacts(t0, state0, p: oscillator.ImpactParams, n_impacts: int,
                     t_end: float = np.inf) -> list[tuple[float, float, float]]:
    """Event-driven motion between the walls ±c (exact flights): the first ``n_impacts`` impacts.

    Returns (time [s], wall ±1, approach speed [m/s]) per impact. A hit of −c is found as a hit of
    +c by the mirrored motion w(s) = −x(s − T/2) (same equation, drive shifted half a period).
    An independent check of the orbit solvers (used in the tests); stops early on a grazing rest.
    """
    T = 2 * np.pi / p.forcing_frequency
    h = 0.5 * T
    t, x, v = float(t0), float(state0[0]), float(state0[1])
    mirror = p._replace(constant_force=-p.constant_force)  # the side force flips with x -> -x
    out = []
    for _ in range(int(n_impacts)):
        horizon = min(t + 20 * T, t_end)
        if horizon <= t:
            break
        up = oscillator.next_impact_time(t, (x, v), p, horizon)
        down = oscillator.next_impact_time(t + h, (-x, -v), mirror, horizon + h)
        t_up = up.time if up.status == "impact" else np.inf
        t_down = down.time - h if down.status == "impact" else np.inf
        if not np.isfinite(min(t_up, t_down)):
            break
        if t_up <= t_down:
            t, x, v = t_up, p.gap, -p.restitution * up.velocity
            out.append((t, 1.0, up.velocity))
        else:
            t, x, v = t_down, -p.gap, p.restitution * down.velocity
            out.append((t, -1.0, down.velocity))
        if out[-1][2] <= 0:
            break
    return out
