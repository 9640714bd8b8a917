"""The time domain's modal span (docs/model.md §10; the equations in :mod:`study.solvers.methods.timedomain`): its
modal model through Hertz contact with both walls (:class:`ModalModel`, :func:`build_model`), its integrators
(explicit Verlet, implicit LSODA, the event-driven one of :mod:`study.solvers.kernels.event_driven`), the run
revolution by revolution until periodic (:func:`simulate`), the periodic orbit through its settled state, the sampled
revolution after it and the stresses of a sampled motion (:func:`stresses`).

Shared by the ``time-domain`` method (:mod:`study.solvers.methods.timedomain`) and the crosscheck's replay of the
periodic solution through real contact (:mod:`study.solvers.methods.crosscheck`): each builds its design point, and
the machinery here reads the point's ``time`` and ``sdof`` options and its scene.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any, Mapping

import numpy as np

from study.physics import contact, hertz, section, whirl
from study.solvers.kernels import event_driven, extremes, orbit, trajectory
from study.solvers.kernels.periodicity import settled_period
from study.solvers.model.equivalent import equivalent_parameters
from study.solvers.model.options import TimeDomainOptions
from study.solvers.model.point import DesignPoint


@dataclass
class ModalModel:
    """The span's modal model (SI)."""

    span: float
    mass: float  #: modal mass M L/2 [kg] (every mode)
    modes: np.ndarray  #: mode numbers n
    omega: np.ndarray  #: ω_n [rad/s]
    clearance: float
    stiffness: float  #: Hertz K [N m^-3/2]
    curvature: float  #: κ used for K [1/m]
    points: np.ndarray  #: contact points ξ_p (fractions of L)
    phi: np.ndarray  #: (P, N) sin(nπξ_p)
    rotary_speed: float
    drive: float  #: F0 [N] on mode 1
    drive_source: str
    restitution: float
    contact_damping: str
    damping_model: str
    damping_matrix: np.ndarray | None = None  #: (N, N) [N s/m]
    drag: float = 0.0  #: D [kg/m^2]
    drag_shapes: np.ndarray | None = None  #: (G, N) sin(nπx_g/L)
    drag_weights: np.ndarray | None = None  #: (G,) Gauss weights on [0, L] [m]
    extras: dict = field(default_factory=dict)
    scene: Any = None  #: the point's Scene (section properties, for the stresses)

    @property
    def period(self) -> float:
        return 2.0 * np.pi / self.rotary_speed

    def hysteresis(self, v0: float) -> float:
        """χ [s/m] for a contact starting at approach speed v0."""
        e = self.restitution
        if v0 <= 0 or e >= 1.0:
            return 0.0
        if self.contact_damping == "calibrated":
            return contact.calibrated_hysteresis(e) / v0
        return float(contact.hunt_crossley_damping(v0, e, self.contact_damping))

    def state_scale(self) -> np.ndarray:
        """(2N,) scale of the modal state: c for q [m], Ω c for q̇ [m/s]."""
        n = len(self.modes)
        return np.concatenate((np.full(n, self.clearance), np.full(n, self.rotary_speed * self.clearance)))

    def energy(self, q, v) -> float:
        """Mechanical energy Σ ½ m (q̇² + ω² q²) + Σ_p (2/5) K δ_p^{5/2} [J]."""
        q, v = np.asarray(q, float), np.asarray(v, float)
        d = np.maximum(np.abs(self.phi @ q) - self.clearance, 0.0)
        return float(0.5 * self.mass * np.sum(v**2 + self.omega**2 * q**2)
                     + np.sum(contact.hertz_energy(d, self.stiffness)))

    def contact_forces(self, q, v, chi):
        """Forces on the pipe at the contact points (P,) [N], given χ per point."""
        y, yd = self.phi @ q, self.phi @ v
        s = np.sign(y)
        d = np.abs(y) - self.clearance
        out = np.zeros_like(y)
        on = d > 0
        if np.any(on):
            ddot = s[on] * yd[on]
            out[on] = -s[on] * contact.hertz_force(d[on], self.stiffness, ddot, chi[on])
        return out

    def acceleration(self, t, q, v, chi):
        """q̈ (N,) and the contact forces (P,)."""
        f = self.phi.T @ (fc := self.contact_forces(q, v, chi))
        f[0] += self.drive * np.cos(self.rotary_speed * t)
        if self.damping_matrix is not None:
            f -= self.damping_matrix @ v
        if self.drag_shapes is not None:
            yd = self.drag_shapes @ v
            f -= self.drag_shapes.T @ (self.drag_weights * self.drag * np.abs(yd) * yd)
        return f / self.mass - self.omega**2 * q, fc


def build_model(point: DesignPoint | Mapping[str, Any]) -> ModalModel:
    """The modal model of a design point (its scene needs ``span_length``; SI inputs are typed first,
    :meth:`DesignPoint.of`): its ``time`` options, its scene and its ``sdof`` options (the screen's drive and side
    force drive this model)."""
    point = DesignPoint.of(point)
    option = point.time
    scene = point.scene
    # the SDOF model's parameters with the modal mass and this method's damping (its drive and side force as set)
    screen = replace(point.sdof, sdof_mass="modal",
                     sdof_damping="none" if option.time_damping == "none" else "mud")
    par = equivalent_parameters(scene, screen)
    scene = par.scene
    props = scene.props
    L = par.span_length
    N = int(option.time_modes)
    if N < 1:
        raise ValueError(f"time_modes = {N}: at least 1")
    modes = np.arange(1, N + 1)
    omega = np.asarray(section.natural_frequencies(L, props["bending_stiffness"], props["effective_tension"],
                                                   props["mass_per_length"], modes), float).ravel()
    points = np.atleast_1d(np.asarray(option.contact_points, float))
    if np.any((points <= 0) | (points >= 1)):
        raise ValueError("contact_points are fractions of the span in (0, 1)")
    damping_model = option.time_damping
    contact_damping = option.contact_damping
    model = ModalModel(span=L, mass=par.mass, modes=modes, omega=omega, clearance=par.clearance,
                       stiffness=par.hertz_stiffness, curvature=par.axial_curvature, points=points,
                       phi=np.sin(np.pi * np.outer(points, modes)), rotary_speed=par.rotary_speed,
                       drive=par.drive_amplitude, drive_source=par.drive_source,
                       restitution=par.restitution, contact_damping=contact_damping,
                       damping_model=damping_model, scene=scene)
    D = props["drag_coefficient_per_length"]
    if damping_model == "linearised":
        x, w = whirl.gauss_legendre(max(2 * N + 4, 16))
        x, w = 0.5 * L * (x + 1), 0.5 * L * w
        S = np.sin(np.pi * np.outer(x, modes) / L)
        ceq = 8.0 * D * model.rotary_speed * model.clearance / (3 * np.pi) * np.sin(np.pi * x / L)
        model.damping_matrix = (S * (w * ceq)[:, None]).T @ S
    elif damping_model == "drag":
        G = int(option.drag_points)
        x, w = whirl.gauss_legendre(G)
        model.drag, model.drag_weights = D, 0.5 * L * w
        model.drag_shapes = np.sin(np.pi * np.outer(0.5 * L * (x + 1), modes) / L)
    return model


def initial_state(model: ModalModel, option: TimeDomainOptions):
    N = len(model.modes)
    if option.initial_state is not None:
        q0, v0 = (np.asarray(a, float).reshape(N) for a in option.initial_state)
        return q0.copy(), v0.copy()
    kind = option.time_initial
    q0, v0 = np.zeros(N), np.zeros(N)
    if kind == "prescribed":
        v0[0] = model.rotary_speed * model.clearance
    return q0, v0


def stability_limit(model: ModalModel, expected_speed: float) -> dict[str, float]:
    """Velocity Verlet's step limit 2/ω_max with the contact linearised at the expected penetration."""
    alpha = float(hertz.hertz_impact(model.mass, max(expected_speed, 1e-12), model.stiffness).max_approach)
    k_lin = contact.linearised_stiffness(alpha, model.stiffness)
    A = np.diag(model.omega**2) + k_lin / model.mass * (model.phi.T @ model.phi)
    w_max = float(np.sqrt(np.max(np.linalg.eigvalsh(A))))
    return dict(step_limit=2.0 / w_max, linear_contact_stiffness=k_lin, expected_penetration=alpha,
                max_frequency=w_max)


# --- contact bookkeeping ---------------------------------------------------------------------------


class _Contacts:
    """Onset/end records per contact point."""

    def __init__(self, model: ModalModel):
        self.model = model
        P = len(model.points)
        self.chi = np.zeros(P)
        self.active = np.zeros(P, bool)
        self.current: list[dict | None] = [None] * P
        self.done: list[dict] = []

    def start(self, p, t, v0):
        self.chi[p] = self.model.hysteresis(v0)
        self.active[p] = True
        self.current[p] = dict(point=p, start=t, approach=v0, peak=0.0, hysteresis=self.chi[p])

    def peak(self, forces):
        for p in np.flatnonzero(self.active):
            self.current[p]["peak"] = max(self.current[p]["peak"], abs(float(forces[p])))

    def end(self, p, t, rebound):
        rec = self.current[p]
        self.active[p] = False
        self.chi[p] = 0.0
        if rec is None:
            return
        rec.update(end=t, duration=t - rec["start"], rebound=rebound)
        self.done.append(rec)
        self.current[p] = None


# --- integrators -----------------------------------------------------------------------------------


def _free_step_matrix(model, dt):
    """The velocity-Verlet step without contact as an affine map of z = (q, v, a) (linear damping only).

    z' = A z + b cos(Ω t'): the same arithmetic as the general step (predicted velocity v + Δt a in
    the damping), fused into one matrix so that the flight between contacts costs one product.
    """
    N = len(model.modes)
    I = np.eye(N)
    W = np.diag(model.omega**2)
    Cm = model.damping_matrix / model.mass if model.damping_matrix is not None else np.zeros((N, N))
    h, h2 = 0.5 * dt, 0.5 * dt * dt
    Aq = np.hstack((I, dt * I, h2 * I))
    Aa = np.hstack((-W, -W * dt - Cm, -W * h2 - Cm * dt))
    Av = np.hstack((np.zeros((N, N)), I, h * I)) + h * Aa
    g = np.zeros(N)
    g[0] = model.drive / model.mass
    return np.vstack((Aq, Av, Aa)), np.concatenate((np.zeros(N), h * g, g))


def _verlet_revolution(model, t0, q, v, a, fc, dt, n_steps, contacts, budget, fused=None):
    """n_steps velocity-Verlet steps; returns (q, v, a, fc, failure message or None).

    budget = [E0, W]: initial energy and the drive's work so far (updated in place).
    """
    c = model.clearance
    phi = model.phi
    N = len(model.modes)
    Om = model.rotary_speed
    z = np.concatenate((q, v, a))
    F0 = model.drive
    cos_old = np.cos(Om * t0)
    for i in range(1, n_steps + 1):
        t = t0 + i * dt
        cos_new = np.cos(Om * t)
        if fused is not None and not contacts.active.any():
            zn = fused[0] @ z + fused[1] * cos_new
            y = phi @ zn[:N]
            if np.max(np.abs(y)) <= c:
                budget[1] += F0 * 0.5 * (cos_old + cos_new) * (zn[0] - z[0])
                z = zn
                cos_old = cos_new
                continue
        q, v, a = z[:N], z[N:2 * N], z[2 * N:]
        y_old, yd_old, ydd_old = phi @ q, phi @ v, phi @ a
        q = q + dt * v + 0.5 * dt * dt * a
        y = phi @ q
        d = np.abs(y) - c
        for p in range(len(d)):
            if d[p] > 0 and not contacts.active[p]:
                d_old = abs(y_old[p]) - c
                s = d_old / (d_old - d[p]) if d_old < 0 else 0.0  # crossing fraction of the step
                v0 = np.sign(y[p]) * (yd_old[p] + s * dt * ydd_old[p])
                contacts.start(p, t - (1 - s) * dt, max(float(v0), 0.0))
        budget[1] += F0 * 0.5 * (cos_old + cos_new) * (q[0] - z[0])
        cos_old = cos_new
        v_pred = v + dt * a
        a_new, fc = model.acceleration(t, q, v_pred, contacts.chi)
        v = v + 0.5 * dt * (a + a_new)
        a = a_new
        z = np.concatenate((q, v, a))
        if contacts.active.any():
            contacts.peak(fc)
            for p in np.flatnonzero(contacts.active & (d <= 0)):
                d_old = abs(y_old[p]) - c
                s = d_old / (d_old - d[p]) if d_old > 0 else 0.0  # crossing fraction of the step
                sg = np.sign(y_old[p])
                rebound = -sg * (yd_old[p] + s * (phi[p] @ v - yd_old[p]))
                contacts.end(p, t - (1 - s) * dt, float(rebound))
                # only the drive feeds energy in: E <= E0 + W_drive (damping and the contact take it out)
                E = model.energy(q, v)
                E0, W = budget
                if not np.isfinite(E) or E - (E0 + W) > 0.05 * (E0 + abs(W)) + 1e-12:
                    return q, v, a, fc, (f"energy {E:.4g} J after the contact ending at t = {t:.6g} s exceeds "
                                         f"the initial energy plus the drive's work, {E0 + W:.4g} J")
        if not np.all(np.isfinite(z)):
            return q, v, a, fc, f"non-finite state at t = {t:.6g} s"
        if np.max(np.abs(y)) > 100 * c:
            return q, v, a, fc, f"deflection {np.max(np.abs(y)) / c:.3g} c at t = {t:.6g} s"
    return z[:N], z[N:2 * N], z[2 * N:], fc, None


def _implicit_revolution(model, t0, t1, q, v, contacts, opts):
    """solve_ivp from t0 to t1 with contact events; returns (q, v, failure message or None)."""
    from scipy.integrate import solve_ivp

    N, P = len(model.modes), len(model.points)
    c = model.clearance

    def rhs(t, y):
        a, _ = model.acceleration(t, y[:N], y[N:], contacts.chi)
        return np.concatenate((y[N:], a))

    def onset(p):
        def g(t, y):
            return -1.0 if contacts.active[p] else abs(model.phi[p] @ y[:N]) - c
        g.terminal, g.direction = True, 1
        return g

    def leave(p):
        def g(t, y):
            return abs(model.phi[p] @ y[:N]) - c if contacts.active[p] else 1.0
        g.terminal, g.direction = True, -1
        return g

    events = [onset(p) for p in range(P)] + [leave(p) for p in range(P)]
    t, y = t0, np.concatenate((q, v))
    max_step = opts.get("max_step", np.inf)
    for _ in range(100_000):
        if t >= t1:
            break
        sol = solve_ivp(rhs, (t, t1), y, method=opts["method"], rtol=opts["rtol"], atol=opts["atol"],
                        events=events, max_step=max_step)
        if sol.status == -1:
            return y[:N], y[N:], f"solve_ivp failed: {sol.message}"
        if contacts.active.any():
            for k in range(sol.t.size):
                contacts.peak(model.contact_forces(sol.y[:N, k], sol.y[N:, k], contacts.chi))
        if sol.status == 0:
            t, y = t1, sol.y[:, -1]
            break
        fired = [(float(te[0]), j) for j, te in enumerate(sol.t_events) if te.size]
        te, j = min(fired)
        y = sol.y_events[j][0].copy()
        t = te
        p = j % P
        yd = model.phi[p] @ y[N:]
        sgn = np.sign(model.phi[p] @ y[:N])
        if j < P:
            contacts.start(p, t, max(float(sgn * yd), 0.0))
        else:
            contacts.end(p, t, float(-sgn * yd))
    return y[:N], y[N:], None


def _event_revolution(system, model, t0, t1, q, v, contacts, peak):
    """The event-driven integrator from t0 to t1; returns (q, v, failure message or None, verdict of a
    failure: 'chattering' when contact onsets and ends accumulate past event_driven.MAX_EVENTS, else
    'failed')."""
    N = len(model.modes)
    z, events, outcome = event_driven.advance(system, t0, t1, np.concatenate((q, v)), contacts.active,
                                              contacts.chi, peak)
    for kind, p, t, speed, force in events:
        if kind == event_driven.ONSET:
            contacts.start(p, t, speed)
        else:
            if contacts.current[p] is not None:
                contacts.current[p]["peak"] = max(contacts.current[p]["peak"], force)
            contacts.end(p, t, speed)
    for p in np.flatnonzero(contacts.active):
        if contacts.current[p] is not None:
            contacts.current[p]["peak"] = max(contacts.current[p]["peak"], float(peak[p]))
    if outcome == event_driven.BLOWN_UP:
        return z[:N], z[N:], f"non-finite state or deflection above 100 c before t = {t1:.6g} s", "failed"
    if outcome == event_driven.TOO_MANY_EVENTS:
        return z[:N], z[N:], (f"more than {event_driven.MAX_EVENTS} contact onsets and ends between t = {t0:.6g} "
                              f"and {t1:.6g} s (chatter)"), "chattering"
    return z[:N], z[N:], None, None


# --- the run -----------------------------------------------------------------------------------------


def simulate(point: DesignPoint | Mapping[str, Any], model: ModalModel | None = None) -> dict[str, Any]:
    """Integrate revolution by revolution until periodic or ``time_revolutions`` (default 60).

    Returns a dict: verdict ('periodic', 'not_periodic', 'chattering', 'failed'), message, period (revolutions
    or None), impacts (contact records: point, start, approach, peak, duration, rebound,
    hysteresis), boundary states, times, energies at the boundaries, step data, model (``model``: the point's,
    :func:`build_model`, where not given). SI inputs are typed first (:meth:`DesignPoint.of`).
    """
    point = DesignPoint.of(point)
    option = point.time
    model = model or build_model(point)
    integrator = option.time_integrator
    if integrator == "auto":
        integrator = "explicit" if model.drag_shapes is not None else "event"
    revolutions = int(option.time_revolutions)
    tol = float(option.time_tolerance)
    check = bool(option.time_check_periodic)
    tau = model.period
    q, v = initial_state(model, option)
    v_scale = max(model.rotary_speed * model.clearance, float(np.max(np.abs(model.phi @ v))))
    lim = stability_limit(model, v_scale)
    contacts = _Contacts(model)
    out: dict[str, Any] = dict(model=model, integrator=integrator, **lim)
    # contacts already closed at t = 0 start inside a wall: χ = 0 until they end
    d0 = np.abs(model.phi @ q) - model.clearance
    contacts.active[:] = d0 > 0
    failure = None  # a set-up failure skips the integration
    if integrator == "explicit":
        dt_req = option.time_step
        if dt_req is None:
            dt_req = float(option.time_step_fraction) * lim["step_limit"]
        n_steps = max(int(np.ceil(tau / float(dt_req) - 1e-9)), 1)
        dt = tau / n_steps
        out.update(time_step=dt, steps_per_revolution=n_steps)
        a, fc = model.acceleration(0.0, q, v, contacts.chi)
        fused = _free_step_matrix(model, dt) if model.drag_shapes is None else None
        budget = [model.energy(q, v), 0.0]
    elif integrator == "event":
        out.update(time_step=None)
        if model.drag_shapes is not None:
            failure = ("the event-driven integrator needs linear damping (time_damping = 'linearised' or 'none'); "
                       "with time_damping = 'drag' use 'explicit' or 'implicit'")
        else:
            damping = None if model.damping_matrix is None else model.damping_matrix / model.mass
            try:
                system = event_driven.prepare(model.omega, damping, model.drive / model.mass, model.rotary_speed,
                                              model.phi, model.mass, model.stiffness, model.clearance,
                                              model.hysteresis(1.0), v_scale,
                                              int(option.contact_steps))
            except ValueError as exc:
                failure = str(exc)
            else:
                out.update(contact_step=system.contact_step, flight_step=system.flight_step)
                peak = np.zeros(len(model.points))
    else:
        opts = dict(method=option.time_ode_method,
                    rtol=float(option.time_rtol),
                    atol=float(option.time_atol) * np.concatenate(
                        (np.full(len(model.modes), model.clearance), np.full(len(model.modes), v_scale))))
        out.update(time_step=None)
    scale = np.concatenate((np.full(len(model.modes), model.clearance), np.full(len(model.modes), v_scale)))
    states = [np.concatenate((q, v))]
    energies = [model.energy(q, v)]
    verdict, period = ("failed" if failure else "not_periodic"), None
    if failure:
        revolutions = 0
    for k in range(1, revolutions + 1):
        t0 = (k - 1) * tau
        stop = "failed"  # the verdict of a failure in this revolution
        if integrator == "explicit":
            q, v, a, fc, failure = _verlet_revolution(model, t0, q, v, a, fc, dt, n_steps, contacts, budget, fused)
        elif integrator == "event":
            q, v, failure, stop = _event_revolution(system, model, t0, k * tau, q, v, contacts, peak)
        else:
            q, v, failure = _implicit_revolution(model, t0, k * tau, q, v, contacts, opts)
        if failure:
            verdict = stop
            break
        states.append(np.concatenate((q, v)))
        energies.append(model.energy(q, v))
        if check:
            period = settled_period(states, scale, tol)
            if period is not None:
                verdict = "periodic"
                break
    if integrator == "event" and not failure:  # where the run stopped, for sampling it further
        out.update(system=system, end_time=(len(states) - 1) * tau,
                   contact_state=(contacts.active.copy(), contacts.chi.copy(), peak.copy()))
    out.update(verdict=verdict, period=period, failure=failure, impacts=contacts.done,
               open_contacts=[r for r in contacts.current if r is not None], states=np.array(states),
               energies=np.array(energies), revolutions_simulated=len(states) - 1,
               final_state=(q, v))
    return out


def settled_orbit(run: Mapping[str, Any]) -> orbit.Orbit | None:
    """The periodic orbit through the run's settled state (:func:`study.solvers.kernels.orbit.find_orbit` from the
    last revolution boundary over the run's period, q in units of c and q̇ in units of Ω c), which gives
    its Floquet multipliers; None unless the run is periodic and used the event-driven integrator."""
    if "system" not in run or not run["period"]:
        return None
    model = run["model"]
    return orbit.find_orbit(run["system"], np.concatenate(run["final_state"]), run["end_time"],
                            run["period"] * model.period, model.state_scale())


def sample_after(run: Mapping[str, Any], revolutions: int | None = None) -> trajectory.Samples | None:
    """The motion over ``revolutions`` (default: the run's period, else 1) after the run's end,
    sampled (:func:`study.solvers.kernels.trajectory.sample_revolution`); None unless the run used the
    event-driven integrator and did not fail."""
    if "system" not in run:
        return None
    model = run["model"]
    t0 = run["end_time"]
    t1 = t0 + (revolutions or run["period"] or 1) * model.period
    active, chi, peak = run["contact_state"]
    return trajectory.sample_revolution(run["system"], model.contact_forces, t0, t1,
                                        np.concatenate(run["final_state"]), active, chi, peak)


def stresses(model: ModalModel, samples: trajectory.Samples, space_points: int = 65) -> dict[str, float]:
    """Deflection and normal-stress maxima (docs/model.md §5) over the sampled motion, on ``space_points``
    points along the whole span and at the contact points, the fields with the quasi-static correction
    for the contact forces (:func:`study.solvers.kernels.trajectory.fields`); times from the first sample."""
    x = np.unique(np.concatenate([np.linspace(0.0, model.span, space_points), model.points * model.span]))
    props = model.scene.props
    f = trajectory.fields(samples, x, model.modes, model.points, model.span, props["bending_stiffness"],
                          props["effective_tension"])
    return extremes.stresses_from_fields(model.scene, x, samples.times - samples.times[0],
                                         f["deflection"], f["moment"], mirrored=False)


#: The quasi-static correction carries the modes above N statically; that holds only for modes whose
#: half-period is shorter than the contact: ω_{N+1} T_c ≥ π (docs/model.md §9). Below it the modes between
#: are neither integrated nor static, and the fields are not resolved.
QUASI_STATIC_LIMIT = np.pi


def contact_resolution(model: ModalModel, samples: trajectory.Samples) -> str | None:
    """None when the model's first mode left out is quasi-static over the shortest contact of the samples
    (ω_{N+1} T_c ≥ :data:`QUASI_STATIC_LIMIT`, or no contact); otherwise what fails, with the number of
    modes that would resolve it."""
    durations = [end - begin for _, begin, end in samples.contacts if end > begin]
    if not durations:
        return None
    shortest = min(durations)
    props = model.scene.props
    modes = np.arange(1, trajectory.STATIC_TAIL_MODES + 1)
    omega = np.ravel(section.natural_frequencies(model.span, props["bending_stiffness"], props["effective_tension"],
                                                 props["mass_per_length"], modes))
    first_left_out = omega[len(model.modes)]
    if first_left_out * shortest >= QUASI_STATIC_LIMIT:
        return None
    enough = np.flatnonzero(omega * shortest >= QUASI_STATIC_LIMIT)
    need = f"about {int(modes[enough[0]]) - 1} modes (solver.time_modes)" if enough.size else \
        f"more than {trajectory.STATIC_TAIL_MODES} modes"
    return (f"the {len(model.modes)} modes do not resolve the {shortest * 1e3:.3g}-ms contact: the first mode left "
            f"out has omega T_c = {first_left_out * shortest:.3g} < pi, so it is not quasi-static and the "
            f"fields' correction does not hold; the stresses need {need}")
