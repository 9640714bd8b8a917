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

from dataclasses import dataclass, field, replace
from typing import Any, Mapping

import numpy as np

from study.physics import contact, hertz, section, whirl
from study.solvers.kernels import event_driven, extremes, orbit, trajectory
from study.solvers.kernels.periodicity import settled_period
from study.solvers.model.equivalent import equivalent_parameters
from study.solvers.model.options import SdofOptions, TimeDomainOptions
from study.solvers.model.point import DesignPoint
from study.solvers.model.result import PointResult
from study.solvers.model.scene import Scene, given_span

METHOD = "time-domain"
STEP_FAILURE = "explicit step above the contact stability limit"


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


def build_model(inputs: Mapping[str, Any], option: TimeDomainOptions | None = None, scene: Scene | None = None,
                screen: SdofOptions | None = None) -> ModalModel:
    """The modal model of ``inputs`` (needs ``span_length``); ``option``, ``scene`` and ``screen`` (the sdof screen's
    options, whose drive and side force drive this model): the point's (:class:`DesignPoint`), else built from
    ``inputs``."""
    option = TimeDomainOptions.from_inputs(inputs) if option is None else option
    scene = Scene.from_inputs(inputs) if scene is None else scene
    # the SDOF model's parameters with the modal mass and this method's damping (its drive and side force as set)
    screen = replace(SdofOptions.from_inputs(inputs) if screen is None else screen, sdof_mass="modal",
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


def initial_state(model: ModalModel, inputs: Mapping[str, Any], option: TimeDomainOptions | None = None):
    N = len(model.modes)
    option = TimeDomainOptions.from_inputs(inputs) if option is None else option
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


def simulate(inputs: Mapping[str, Any], model: ModalModel | None = None,
             option: TimeDomainOptions | None = None) -> dict[str, Any]:
    """Integrate revolution by revolution until periodic or ``time_revolutions`` (default 60).

    Returns a dict: verdict ('periodic', 'not_periodic', 'chattering', 'failed'), message, period (revolutions
    or None), impacts (contact records: point, start, approach, peak, duration, rebound,
    hysteresis), boundary states, times, energies at the boundaries, step data, model. ``option``: the method's
    options (built once by :func:`solve`), else read from ``inputs``.
    """
    option = TimeDomainOptions.from_inputs(inputs) if option is None else option
    model = model or build_model(inputs, option)
    integrator = option.time_integrator
    if integrator == "auto":
        integrator = "explicit" if model.drag_shapes is not None else "event"
    revolutions = int(option.time_revolutions)
    tol = float(option.time_tolerance)
    check = bool(option.time_check_periodic)
    tau = model.period
    q, v = initial_state(model, inputs, option)
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


def stresses(inputs: Mapping[str, Any], model: ModalModel, samples: trajectory.Samples,
             space_points: int = 65) -> dict[str, float]:
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
    option, inputs = point.time, point.inputs
    result = PointResult(method=METHOD)
    if given_span(point.scene, result, "the time-domain method",
                  "effective tension {tension:.4g} N buckles the {span:.4g} m span") is None:
        return result
    run = simulate(inputs, build_model(inputs, option, point.scene, point.sdof), option=option)
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
        vals.update(stresses(inputs, model, samples))
        messages.append(f"stresses over the {'period' if run['verdict'] == 'periodic' else 'next revolution'} "
                        f"after the run")
    result.message = "; ".join(messages)
    return result
