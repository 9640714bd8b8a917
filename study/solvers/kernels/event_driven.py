"""Event-driven integration of the span's modal model: exact flights, fixed-step RK4 through contact.

The time-domain method's fastest integrator (``time_integrator = "event"``; docs/model.md §10). Between
contacts the modal model is linear, m q̈ + C q̇ + m W q = F0 cos(Ωt) e_1, so the flight is known in
closed form: with z = (q, q̇), ż = A z + b cos Ωt,

    z(t) = Re(Z e^{iΩt}) + V e^{Λ (t − t_s)} V⁻¹ (z(t_s) − Re(Z e^{iΩ t_s})),   (iΩ I − A) Z = b,

A = V Λ V⁻¹ its eigen-decomposition. No time step enters a flight: the state is exact (to rounding)
at any time. The contact points' deflections y_p = φ_p · q are sampled on a grid of 1/16 of the
shortest free period (and at most τ/32), and every crossing of a wall, |y_p| = c, is located by a
safeguarded Newton iteration on the exact solution. A grazing contact between two samples is caught by
finding each maximum of |y_p| (a root of ẏ_p) and testing it against c.

Through contact the full nonlinear model (Hertz force K δ^{3/2}(1 + χ δ̇)₊,
:func:`study.physics.contact.hertz_force`) is integrated by the classical Runge–Kutta method with a fixed step,
``contact_steps`` steps (default 100) per elastic Hertz contact of the smallest effective mass at the
expected approach speed (hertz.hertz_impact's T_H), and at most 1/ω_max. A contact ends where δ_p
returns to 0: the last step is cut to that instant by a secant iteration on its length, so the flight
that follows starts exactly where the contact ended.

Needs linear damping (``time_damping`` ``"linearised"`` or ``"none"``): the quadratic drag has no
closed-form flight.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np

from study.physics import hertz
from study.physics.contact import hertz_force_one

#: Event kinds reported by :func:`advance`.
ONSET, END = 0, 1
#: Outcomes of :func:`advance`.
OK, BLOWN_UP, TOO_MANY_EVENTS = 0, 1, 2
MAX_EVENTS = 4096  #: contact onsets and ends per call before it gives up (chatter)


@dataclass(frozen=True)
class EventSystem:
    """The modal model in the form the compiled kernel takes (SI; see the module docstring)."""

    lam: np.ndarray  #: (2N,) eigenvalues of A [1/s]
    V: np.ndarray  #: (2N, 2N) eigenvectors
    Vinv: np.ndarray
    Z: np.ndarray  #: (2N,) complex amplitude of the periodic particular solution
    R: np.ndarray  #: (P, 2N) φ V[:N]: contact deflections from eigen-coordinates
    Rd: np.ndarray  #: (P, 2N) φ V[N:]: contact velocities
    Y: np.ndarray  #: (P,) φ Z[:N]
    Yd: np.ndarray  #: (P,) φ Z[N:]
    rotary_speed: float  #: Ω [rad/s]
    phi: np.ndarray  #: (P, N) mode shapes at the contact points
    omega2: np.ndarray  #: (N,) ω_n² [1/s²]
    damping: np.ndarray  #: (N, N) C/m [1/s]
    drive: float  #: F0/m [m/s²] on mode 1
    inv_mass: float  #: 1/m [1/kg]
    stiffness: float  #: Hertz K [N m^-3/2]
    clearance: float  #: c [m]
    hysteresis: float  #: h = χ v0 [-]
    flight_step: float  #: sampling step of the flights [s]
    contact_step: float  #: RK4 step through contact [s]


def prepare(omega, damping_per_mass, drive_per_mass, rotary_speed, phi, mass, stiffness, clearance,
            hysteresis, expected_speed, contact_steps: int = 100) -> EventSystem:
    """Eigen-decomposition, particular solution and steps of the modal model.

    omega (N,) [rad/s]; damping_per_mass (N, N) C/m [1/s] or None; drive_per_mass F0/m [m/s²];
    rotary_speed Ω [rad/s]; phi (P, N); mass m [kg]; stiffness K [N m^-3/2]; clearance c [m];
    hysteresis h = χ v0 [-]; expected_speed: approach speed that sets the contact step [m/s].
    Raises ValueError when the drive is at an undamped natural frequency (no periodic particular
    solution) or the damping makes A defective.
    """
    omega = np.asarray(omega, float)
    N = omega.size
    Cm = np.zeros((N, N)) if damping_per_mass is None else np.asarray(damping_per_mass, float)
    A = np.block([[np.zeros((N, N)), np.eye(N)], [-np.diag(omega**2), -Cm]])
    lam, V = np.linalg.eig(A)
    if np.linalg.cond(V) > 1e10:
        raise ValueError("the damped modal model is (nearly) defective: no eigen-decomposition for exact flights")
    b = np.zeros(2 * N)
    b[N] = drive_per_mass
    M = 1j * rotary_speed * np.eye(2 * N) - A
    if np.linalg.cond(M) > 1e13:
        raise ValueError(f"rotary speed {rotary_speed:.6g} rad/s is an undamped natural frequency: "
                         "no periodic flight")
    Z = np.linalg.solve(M, b.astype(complex))
    phi = np.asarray(phi, float)
    m_eff = mass / np.sum(phi**2, axis=1)  # the contact point's effective mass
    t_hertz = float(np.min(hertz.hertz_impact(m_eff, max(expected_speed, 1e-9), stiffness).duration))
    w_max = float(np.max(np.abs(lam)))
    period = 2.0 * np.pi / rotary_speed
    return EventSystem(lam=lam, V=V.astype(complex), Vinv=np.linalg.inv(V).astype(complex), Z=Z,
                       R=phi @ V[:N].astype(complex), Rd=phi @ V[N:].astype(complex), Y=phi @ Z[:N],
                       Yd=phi @ Z[N:], rotary_speed=float(rotary_speed), phi=phi, omega2=omega**2, damping=Cm,
                       drive=float(drive_per_mass), inv_mass=1.0 / mass, stiffness=float(stiffness),
                       clearance=float(clearance), hysteresis=float(hysteresis),
                       flight_step=min(period / 32.0, 2.0 * np.pi / w_max / 16.0),
                       contact_step=min(t_hertz / contact_steps, 1.0 / w_max))


def flight_state(system: EventSystem, t_start: float, z_start, t) -> np.ndarray:
    """The exact contact-free state z(t) (2N,) or (len(t), 2N) from z(t_start) (closed form above)."""
    t = np.asarray(t, float)
    s = system.Z
    w0 = system.Vinv @ (np.asarray(z_start, float) - (s * np.exp(1j * system.rotary_speed * t_start)).real)
    w = w0 * np.exp(np.multiply.outer(t - t_start, system.lam))
    return (w @ system.V.T).real + (np.multiply.outer(np.exp(1j * system.rotary_speed * t), s)).real


# --- compiled kernel ------------------------------------------------------------------------------


@numba.njit(cache=True, nogil=True)
def _contact_y(R, Rd, Y, Yd, w0, lam, Om, t_start, s, p):
    """Deflection and velocity of contact point p at t_start + s in flight."""
    y = 0.0
    yd = 0.0
    for j in range(lam.size):
        wj = w0[j] * np.exp(lam[j] * s)
        y += (R[p, j] * wj).real
        yd += (Rd[p, j] * wj).real
    e = np.exp(1j * Om * (t_start + s))
    return y + (Y[p] * e).real, yd + (Yd[p] * e).real


@numba.njit(cache=True, nogil=True)
def _contact_state(z, phi, p, N):
    """Deflection and velocity of contact point p from the modal state z = (q, q̇)."""
    y = 0.0
    yd = 0.0
    for n in range(N):
        y += phi[p, n] * z[n]
        yd += phi[p, n] * z[N + n]
    return y, yd


@numba.njit(cache=True, nogil=True)
def _acceleration(t, z, chi, phi, omega2, Cm, g0, inv_m, K, c, Om, out, forces):
    """ż of the full model (contact included) into ``out``; contact forces into ``forces``."""
    N = omega2.size
    for n in range(N):
        out[n] = z[N + n]
        acc = -omega2[n] * z[n]
        for k in range(N):
            acc -= Cm[n, k] * z[N + k]
        out[N + n] = acc
    out[N] += g0 * np.cos(Om * t)
    for p in range(phi.shape[0]):
        y, yd = _contact_state(z, phi, p, N)
        d = abs(y) - c
        f = 0.0
        if d > 0.0:
            sg = 1.0 if y > 0.0 else -1.0
            f = -sg * hertz_force_one(d, K, sg * yd, chi[p])
            for n in range(N):
                out[N + n] += phi[p, n] * f * inv_m
        forces[p] = f


@numba.njit(cache=True, nogil=True)
def _rk4(t, z, dt, chi, phi, omega2, Cm, g0, inv_m, K, c, Om, forces):
    n = z.size
    k1, k2, k3, k4, tmp = np.empty(n), np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    _acceleration(t, z, chi, phi, omega2, Cm, g0, inv_m, K, c, Om, k1, forces)
    tmp[:] = z + 0.5 * dt * k1
    _acceleration(t + 0.5 * dt, tmp, chi, phi, omega2, Cm, g0, inv_m, K, c, Om, k2, forces)
    tmp[:] = z + 0.5 * dt * k2
    _acceleration(t + 0.5 * dt, tmp, chi, phi, omega2, Cm, g0, inv_m, K, c, Om, k3, forces)
    tmp[:] = z + dt * k3
    _acceleration(t + dt, tmp, chi, phi, omega2, Cm, g0, inv_m, K, c, Om, k4, forces)
    out = z + dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
    _acceleration(t + dt, out, chi, phi, omega2, Cm, g0, inv_m, K, c, Om, tmp, forces)  # forces at the end
    return out


@numba.njit(cache=True, nogil=True)
def _onset_root(R, Rd, Y, Yd, w0, lam, Om, ts, p, sg, c, a, b):
    """The instant in [a, b] where sg·y_p − c = 0 (negative at a, non-negative at b)."""
    s = b
    step_old = b - a
    for _ in range(200):
        y, yd = _contact_y(R, Rd, Y, Yd, w0, lam, Om, ts, s, p)
        f = sg * y - c
        if f >= 0.0:
            b = s
        else:
            a = s
        if abs(f) <= 1e-14 * c:
            return s
        if b - a <= 1e-15 * (1.0 + abs(ts + b)):
            break
        df = sg * yd
        # Newton where it lands inside the bracket and converges fast enough, else bisection (rtsafe)
        if df != 0.0 and a < s - f / df < b and abs(2.0 * f) <= abs(step_old * df):
            step_old = abs(f / df)
            s = s - f / df
        else:
            step_old = 0.5 * (b - a)
            s = 0.5 * (a + b)
    return b


@numba.njit(cache=True, nogil=True)
def _velocity_root(R, Rd, Y, Yd, w0, lam, Om, ts, p, sg, a, b):
    """A maximum of sg·y_p in [a, b] (sg·ẏ_p > 0 at a, < 0 at b), by bisection."""
    for _ in range(60):
        m = 0.5 * (a + b)
        _, yd = _contact_y(R, Rd, Y, Yd, w0, lam, Om, ts, m, p)
        if sg * yd > 0.0:
            a = m
        else:
            b = m
        if b - a <= 1e-15 * (1.0 + abs(ts + b)):
            break
    return 0.5 * (a + b)


@numba.njit(cache=True, nogil=True)
def _record(ev_kind, ev_p, ev_t, ev_v, ev_peak, n, kind, p, t, v, f):
    """Store event n; returns n + 1, or -1 when the arrays are full."""
    if n >= ev_kind.size:
        return -1
    ev_kind[n], ev_p[n], ev_t[n], ev_v[n], ev_peak[n] = kind, p, t, v, f
    return n + 1


@numba.njit(cache=True, nogil=True)
def _onset(active, chi, peak, hyst, p, t, v0, ev_kind, ev_p, ev_t, ev_v, ev_peak, n):
    """A contact of point p starts at t with approach speed v0: χ = h/v0, peak reset, event recorded."""
    active[p] = True
    chi[p] = hyst / v0 if v0 > 0.0 else 0.0
    peak[p] = 0.0
    return _record(ev_kind, ev_p, ev_t, ev_v, ev_peak, n, 0, p, t, v0, 0.0)


@numba.njit(cache=True, nogil=True)
def _advance(t0, t1, z, active, chi, peak, lam, V, Vinv, Z, R, Rd, Y, Yd, Om, phi, omega2, Cm, g0, inv_m, K,
             c, hyst, h_flight, dt_contact, ev_kind, ev_p, ev_t, ev_v, ev_peak):
    N = omega2.size
    P = phi.shape[0]
    n_ev = 0
    t = t0
    forces = np.zeros(P)
    w0 = np.empty(2 * N, dtype=np.complex128)
    while t < t1:
        any_active = False
        for p in range(P):
            any_active = any_active or active[p]
        if any_active:
            dt = min(dt_contact, t1 - t)
            zn = _rk4(t, z, dt, chi, phi, omega2, Cm, g0, inv_m, K, c, Om, forces)
            # the first active contact to end within the step cuts the step there (secant on its length)
            frac = 2.0
            p_end = -1
            for p in range(P):
                if active[p]:
                    y1, _ = _contact_state(zn, phi, p, N)
                    if abs(y1) - c <= 0.0:
                        y0, _ = _contact_state(z, phi, p, N)
                        d0, d1 = abs(y0) - c, abs(y1) - c
                        s = d0 / (d0 - d1) if d0 > d1 else 1.0
                        if s < frac:
                            frac, p_end = s, p
            if p_end >= 0:  # Illinois regula falsi on the step length for δ_p = 0
                y0, _ = _contact_state(z, phi, p_end, N)
                sg = 1.0 if y0 > 0.0 else -1.0
                y1, _ = _contact_state(zn, phi, p_end, N)
                lo, d_lo, hi, d_hi = 0.0, abs(y0) - c, 1.0, sg * y1 - c
                for _ in range(40):
                    if d_lo <= 0.0 or hi - lo <= 1e-14:
                        break
                    s = lo + (hi - lo) * d_lo / (d_lo - d_hi)
                    if not lo < s < hi:
                        s = 0.5 * (lo + hi)
                    zs = _rk4(t, z, s * dt, chi, phi, omega2, Cm, g0, inv_m, K, c, Om, forces)
                    ys, _ = _contact_state(zs, phi, p_end, N)
                    ds = sg * ys - c
                    if ds > 0.0:
                        lo, d_lo = s, ds
                        d_hi *= 0.5
                    else:
                        hi, d_hi = s, ds
                        d_lo *= 0.5
                        if ds >= -1e-13 * c:
                            break
                dt = hi * dt
                zn = _rk4(t, z, dt, chi, phi, omega2, Cm, g0, inv_m, K, c, Om, forces)
            for p in range(P):  # onsets within the step (another point reaching a wall)
                y1, yd1 = _contact_state(zn, phi, p, N)
                if not active[p] and abs(y1) - c > 0.0:
                    y0, yd0 = _contact_state(z, phi, p, N)
                    d0, d1 = abs(y0) - c, abs(y1) - c
                    s = d0 / (d0 - d1) if d0 < 0.0 else 0.0
                    sg = 1.0 if y1 > 0.0 else -1.0
                    v0 = max(sg * (yd0 + s * (yd1 - yd0)), 0.0)
                    n_ev = _onset(active, chi, peak, hyst, p, t + s * dt, v0, ev_kind, ev_p, ev_t, ev_v, ev_peak, n_ev)
                    if n_ev < 0:
                        return zn, ev_kind.size, 2
            for p in range(P):
                if active[p]:
                    peak[p] = max(peak[p], abs(forces[p]))
            if p_end >= 0:
                y1, yd1 = _contact_state(zn, phi, p_end, N)
                sg = 1.0 if y1 > 0.0 else -1.0
                active[p_end] = False
                chi[p_end] = 0.0
                n_ev = _record(ev_kind, ev_p, ev_t, ev_v, ev_peak, n_ev, 1, p_end, t + dt, -sg * yd1, peak[p_end])
                if n_ev < 0:
                    return zn, ev_kind.size, 2
            z = zn
            t = t + dt if p_end >= 0 or dt < t1 - t else t1
            for k in range(2 * N):
                if not np.isfinite(z[k]):
                    return z, n_ev, 1
            for p in range(P):
                y1, _ = _contact_state(z, phi, p, N)
                if abs(y1) > 100.0 * c:
                    return z, n_ev, 1
        else:
            # flight: eigen-coordinates of the free part at its start
            e = np.exp(1j * Om * t)
            for j in range(2 * N):
                acc = 0.0 + 0.0j
                for k in range(2 * N):
                    acc += Vinv[j, k] * (z[k] - (Z[k] * e).real)
                w0[j] = acc
            span = t1 - t
            a = 0.0
            ya = np.empty(P)
            yda = np.empty(P)
            for p in range(P):
                ya[p], yda[p] = _contact_y(R, Rd, Y, Yd, w0, lam, Om, t, 0.0, p)
            hit = -1.0
            hit_p = -1
            hit_sg = 1.0
            for p in range(P):  # starting on a wall and moving into it: an onset now
                sg = 1.0 if ya[p] > 0.0 else -1.0
                if abs(ya[p]) - c >= 0.0 and sg * yda[p] > 0.0 and hit < 0.0:
                    hit, hit_p, hit_sg = 0.0, p, sg
            while a < span and hit < 0.0:
                b = min(a + h_flight, span)
                for p in range(P):
                    yb, ydb = _contact_y(R, Rd, Y, Yd, w0, lam, Om, t, b, p)
                    sg = 1.0 if yb > 0.0 else -1.0
                    if abs(yb) - c >= 0.0 and abs(ya[p]) - c < 0.0:
                        root = _onset_root(R, Rd, Y, Yd, w0, lam, Om, t, p, sg, c, a, b)
                    elif (abs(ya[p]) < c and ya[p] * yb > 0.0 and sg * yda[p] > 0.0 and sg * ydb < 0.0):
                        top = _velocity_root(R, Rd, Y, Yd, w0, lam, Om, t, p, sg, a, b)  # grazing?
                        ym, _ = _contact_y(R, Rd, Y, Yd, w0, lam, Om, t, top, p)
                        root = _onset_root(R, Rd, Y, Yd, w0, lam, Om, t, p, sg, c, a, top) if sg * ym >= c else -1.0
                    else:
                        root = -1.0
                    if root >= 0.0 and (hit < 0.0 or root < hit):
                        hit, hit_p, hit_sg = root, p, sg
                    ya[p], yda[p] = yb, ydb
                a = b
            s_end = hit if hit >= 0.0 else span
            e = np.exp(1j * Om * (t + s_end))
            for k in range(2 * N):
                acc = 0.0 + 0.0j
                for j in range(2 * N):
                    acc += V[k, j] * w0[j] * np.exp(lam[j] * s_end)
                z[k] = acc.real + (Z[k] * e).real
            if hit >= 0.0:
                _, yd = _contact_state(z, phi, hit_p, N)
                v0 = max(hit_sg * yd, 0.0)
                n_ev = _onset(active, chi, peak, hyst, hit_p, t + hit, v0, ev_kind, ev_p, ev_t, ev_v, ev_peak, n_ev)
                if n_ev < 0:
                    return z, ev_kind.size, 2
                t = t + hit
            else:
                t = t1
    return z, n_ev, 0


def advance(system: EventSystem, t0: float, t1: float, z, active, chi, peak):
    """Integrate from t0 to t1; ``active``, ``chi``, ``peak`` (per contact point) are updated in place.

    Returns (z at t1 or where it stopped, events, outcome): events is a list of
    (kind ONSET/END, point, time [s], speed [m/s]: approach at onset, rebound at end, peak force [N]
    at end); outcome OK, BLOWN_UP (non-finite or |y| > 100 c) or TOO_MANY_EVENTS.
    """
    s = system
    kind, point = np.empty(MAX_EVENTS, np.int64), np.empty(MAX_EVENTS, np.int64)
    when, speed, force = np.empty(MAX_EVENTS), np.empty(MAX_EVENTS), np.empty(MAX_EVENTS)
    z, n, outcome = _advance(float(t0), float(t1), np.array(z, float), active, chi, peak, s.lam, s.V, s.Vinv, s.Z,
                             s.R, s.Rd, s.Y, s.Yd, s.rotary_speed, s.phi, s.omega2, s.damping, s.drive,
                             s.inv_mass, s.stiffness, s.clearance, s.hysteresis, s.flight_step, s.contact_step,
                             kind, point, when, speed, force)
    events = [(int(kind[i]), int(point[i]), float(when[i]), float(speed[i]), float(force[i])) for i in range(n)]
    return z, events, int(outcome)
