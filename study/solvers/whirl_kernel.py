"""Compiled integrator of the reference model (method ``reference``; ``docs/reference_model.md``).

The pipe section's modal coordinates in both lateral directions, z = (q_y, q_z, q̇_y, q̇_z, W), are
advanced by the Dormand–Prince 5(4) pair with error control (Hairer, Nørsett & Wanner, *Solving
Ordinary Differential Equations I*, 2nd ed., Springer 1993, §II.5, doi:10.1007/978-3-540-78862-1) —
the flights are not linear once the mud's quadratic drag is kept, so no closed-form flight exists.
Every contact onset is located: a step that ends with a contact point inside the wall by more than
``ONSET_TOLERANCE`` of its clearance is redone, cut by the secant of the penetration, until the
onset lands within it; the Hunt–Crossley hysteresis of the contact is then set from its approach
speed (as :mod:`study.solvers.event_driven` does), and its end is taken where the penetration
returns to zero. A step is also capped at the predicted time to the next onset, so that one step
cannot carry a point through a whole contact.

The last four entries of z integrate the power balance: work of the applied loads (eccentric and
side load), work of wall friction on the lateral motion, drag dissipation and contact loss, so
that the energy balance is checked to the integrator's own accuracy.

Right-hand side (per modal mass m = M L/2, k_n = nπ/L, φ_pn = sin k_n x_p):

    q̈ = −ω_n² q − d_n q̇ + ε_n (cos Ωt, sin Ωt) + s_n e_y
         − Σ_g w_g S_gn D |u̇_g| u̇_g / m + Σ_p φ_pn F_p / m

with the contact force on the pipe at point p, penetration δ = |u_p| − c_p, outward normal n̂,
t̂ = e_x × n̂:  F_p = −F_n n̂ − μ F_n v_s/√(v_s² + v_ε²) t̂, v_s = u̇_p·t̂ + Ω r_p, and
F_n = K_p δ^{3/2}(1 + χ_p δ̇)₊ (law 0, Hertz with Hunt–Crossley damping) or (k_p δ + c_p δ̇)₊ (law 1,
linear penalty spring-dashpot).
"""

from __future__ import annotations

import numba
import numpy as np

#: Penetration (fraction of the point's clearance) within which an onset is taken as located.
ONSET_TOLERANCE = 1e-6
#: Outcomes of :func:`advance`.
OK, BLOWN_UP, STEP_UNDERFLOW, TOO_MANY_STEPS = 0, 1, 2, 3
OUTCOMES = {OK: "ok", BLOWN_UP: "non-finite state or deflection above 100 clearances",
            STEP_UNDERFLOW: "step size underflow", TOO_MANY_STEPS: "step budget exhausted"}
#: Indices of fpar (the scalar parameters).
F_DRAG, F_OMEGA, F_MU, F_VREG, F_INV_M, F_LAW, F_HYST = range(7)

# Dormand–Prince 5(4) tableau
_C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0])
_A = np.zeros((7, 6))
_A[1, :1] = [1 / 5]
_A[2, :2] = [3 / 40, 9 / 40]
_A[3, :3] = [44 / 45, -56 / 15, 32 / 9]
_A[4, :4] = [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729]
_A[5, :5] = [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656]
_A[6, :6] = [35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84]
_E = np.array([71 / 57600, 0.0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40])


@numba.njit(cache=True, nogil=True)
def point_state(z, phi, p, N):
    """(y, z, ẏ, ż) of contact point p from the state."""
    y = 0.0
    w = 0.0
    yd = 0.0
    wd = 0.0
    for n in range(N):
        y += phi[p, n] * z[n]
        w += phi[p, n] * z[N + n]
        yd += phi[p, n] * z[2 * N + n]
        wd += phi[p, n] * z[3 * N + n]
    return y, w, yd, wd


@numba.njit(cache=True, nogil=True)
def rhs(t, z, chi, out, fc, sy):
    """ż into ``out``; contact forces on the pipe (F_y, F_z, F_n) per point into ``fc`` (P, 3).

    sy = (omega2, damping, eccentric, side, S, w, phi, clearance, radius, K, kp, cp, fpar).
    """
    omega2, damp, ecc, side, S, wts, phi, cl, rc, K, kp, cpen, fpar = sy
    N = omega2.size
    D, Om, mu, vreg, inv_m, law = fpar[0], fpar[1], fpar[2], fpar[3], fpar[4], fpar[5]
    co = np.cos(Om * t)
    si = np.sin(Om * t)
    p_load = 0.0
    for n in range(N):
        vy = z[2 * N + n]
        vz = z[3 * N + n]
        out[n] = vy
        out[N + n] = vz
        fy = ecc[n] * co + side[n]
        fz = ecc[n] * si
        out[2 * N + n] = -omega2[n] * z[n] - damp[n] * vy + fy
        out[3 * N + n] = -omega2[n] * z[N + n] - damp[n] * vz + fz
        p_load += fy * vy + fz * vz
    out[4 * N] = p_load / inv_m
    p_drag = 0.0
    if D > 0.0:
        for g in range(wts.size):
            uy = 0.0
            uz = 0.0
            for n in range(N):
                uy += S[g, n] * z[2 * N + n]
                uz += S[g, n] * z[3 * N + n]
            sp = np.sqrt(uy * uy + uz * uz)
            c = D * sp * wts[g] * inv_m
            p_drag += D * sp * sp * sp * wts[g]
            for n in range(N):
                out[2 * N + n] -= c * S[g, n] * uy
                out[3 * N + n] -= c * S[g, n] * uz
    out[4 * N + 2] = p_drag
    p_fric = 0.0
    p_loss = 0.0
    for p in range(phi.shape[0]):
        y, w, yd, wd = point_state(z, phi, p, N)
        r = np.sqrt(y * y + w * w)
        d = r - cl[p]
        fc[p, 0] = 0.0
        fc[p, 1] = 0.0
        fc[p, 2] = 0.0
        if d > 0.0:
            ny = y / r
            nz = w / r
            dd = yd * ny + wd * nz  # δ̇
            vt = -yd * nz + wd * ny  # u̇·t̂, t̂ = (−n_z, n_y)
            if law == 0:
                elastic = K[p] * d * np.sqrt(d)
                fn = max(elastic * (1.0 + chi[p] * dd), 0.0)
            else:
                elastic = kp[p] * d
                fn = max(elastic + cpen[p] * dd, 0.0)
            vs = vt + Om * rc[p]
            ft = -mu * fn * vs / np.sqrt(vs * vs + vreg * vreg)
            fy = -fn * ny - ft * nz
            fz = -fn * nz + ft * ny
            fc[p, 0] = fy
            fc[p, 1] = fz
            fc[p, 2] = fn
            p_fric += ft * vt
            p_loss += (fn - elastic) * dd
            for n in range(N):
                out[2 * N + n] += phi[p, n] * fy * inv_m
                out[3 * N + n] += phi[p, n] * fz * inv_m
    out[4 * N + 1] = p_fric
    out[4 * N + 3] = p_loss


@numba.njit(cache=True, nogil=True)
def _step(t, z, h, chi, sy, k, tmp, fc, A, C):
    """One Dormand–Prince step from (t, z) with k[0] = f(t, z) given: the 5th-order state in tmp[6]."""
    n = z.size
    for s in range(1, 7):
        for i in range(n):
            acc = z[i]
            for j in range(s):
                acc += h * A[s, j] * k[j, i]
            tmp[s, i] = acc
        rhs(t + C[s] * h, tmp[s], chi, k[s], fc, sy)


@numba.njit(cache=True, nogil=True)
def _penetration(z, phi, cl, p, N):
    y, w, yd, wd = point_state(z, phi, p, N)
    r = np.sqrt(y * y + w * w)
    rate = (y * yd + w * wd) / r if r > 0.0 else 0.0
    return r - cl[p], rate


@numba.njit(cache=True, nogil=True)
def advance(t, t_end, z, active, chi, h, sy, rtol, scale, h_max, max_steps,
            stats, peak, onsets, contact_time, record, rec_dt, rec_t, rec_z, rec_f, n_rec):
    """Integrate from t to t_end. Returns (t, h, outcome, n_rec, steps).

    ``active``/``chi`` (P,): contact state, updated. ``scale`` (4N,): error scale of the dynamic
    entries (c for q, Ωc for q̇); error per entry (z5 − z4)/(rtol (scale + |z|)), RMS ≤ 1 accepted.
    ``peak`` (P,): largest F_n; ``onsets`` (P,): contact onsets; ``contact_time`` (P,): time in
    contact; ``stats`` [time with any contact]. With ``record``, rows (t, z, F) are stored every
    rec_dt[0] (no contact) or rec_dt[1] (a contact open) from index n_rec on, while room remains.
    """
    omega2, phi, cl, fpar = sy[0], sy[6], sy[7], sy[12]
    hyst = fpar[6]
    N = omega2.size
    P = phi.shape[0]
    n = z.size
    k = np.empty((7, n))
    tmp = np.empty((7, n))
    fc = np.empty((P, 3))
    fc_end = np.empty((P, 3))
    A = _A
    C = _C
    E = _E
    rhs(t, z, chi, k[0], fc_end, sy)
    last_rec = -1e300
    steps = 0
    h_floor = 1e-14 * (1.0 + abs(t_end))
    while t < t_end:
        if record and n_rec < rec_t.size:
            any_open = False
            for p in range(P):
                any_open = any_open or active[p]
            if t - last_rec >= (rec_dt[1] if any_open else rec_dt[0]) or t_end - t <= h_floor:
                rec_t[n_rec] = t
                rec_z[n_rec, :] = z
                rec_f[n_rec, :, :] = fc_end
                n_rec += 1
                last_rec = t
        if t_end - t <= h_floor:
            t = t_end
            break
        steps += 1
        if steps > max_steps:
            return t, h, TOO_MANY_STEPS, n_rec, steps
        h = min(h, h_max, t_end - t)
        # cap at the predicted onset of a point moving towards the wall
        for p in range(P):
            if not active[p]:
                d, rate = _penetration(z, phi, cl, p, N)
                if rate > 0.0 and d < 0.0:
                    h = min(h, max(-d / rate * 1.05, 1e-4 * h_max))
        accepted = False
        for _attempt in range(60):
            if h < h_floor:
                return t, h, STEP_UNDERFLOW, n_rec, steps
            _step(t, z, h, chi, sy, k, tmp, fc, A, C)
            err = 0.0
            for i in range(4 * N):
                e = 0.0
                for j in range(7):
                    e += E[j] * k[j, i]
                e *= h
                sc = rtol * (scale[i] + max(abs(z[i]), abs(tmp[6, i])))
                err += (e / sc) ** 2
            err = np.sqrt(err / (4 * N))
            if not np.isfinite(err):
                h *= 0.1
                continue
            if err > 1.0:
                h *= max(0.2, 0.9 * err ** -0.2)
                continue
            # onset located within ONSET_TOLERANCE of the clearance
            cut = 2.0
            for p in range(P):
                if not active[p]:
                    d1, _ = _penetration(tmp[6], phi, cl, p, N)
                    if d1 > ONSET_TOLERANCE * cl[p]:
                        d0, _ = _penetration(z, phi, cl, p, N)
                        s = d0 / (d0 - d1) if d0 < 0.0 else 0.5
                        cut = min(cut, max(s, 0.02))
            if cut < 2.0:
                h *= cut
                continue
            accepted = True
            break
        if not accepted:
            return t, h, STEP_UNDERFLOW, n_rec, steps
        # accept
        any_open = False
        for p in range(P):
            any_open = any_open or active[p]
        if any_open:
            stats[0] += h
        for p in range(P):
            if active[p]:
                contact_time[p] += h
        t_new = t + h if h < t_end - t else t_end
        for i in range(n):
            z[i] = tmp[6, i]
        t = t_new
        for i in range(n):
            k[0, i] = k[6, i]
        changed = False
        for p in range(P):
            d, rate = _penetration(z, phi, cl, p, N)
            if active[p] and d <= 0.0:
                active[p] = False
                chi[p] = 0.0
                changed = True
            elif not active[p] and d > 0.0:
                active[p] = True
                chi[p] = hyst / rate if rate > 0.0 else 0.0
                onsets[p] += 1
                changed = True
        if changed:
            rhs(t, z, chi, k[0], fc_end, sy)
        else:
            fc_end[:, :] = fc  # the last stage is the step's end (FSAL)
        for p in range(P):
            if fc_end[p, 2] > peak[p]:
                peak[p] = fc_end[p, 2]
        for i in range(4 * N):
            if not np.isfinite(z[i]):
                return t, h, BLOWN_UP, n_rec, steps
        for p in range(P):
            d, _ = _penetration(z, phi, cl, p, N)
            if d > 100.0 * cl[p]:
                return t, h, BLOWN_UP, n_rec, steps
        h = h * min(5.0, max(0.2, 0.9 * max(err, 1e-10) ** -0.2))
    if record and n_rec < rec_t.size:
        rec_t[n_rec] = t
        rec_z[n_rec, :] = z
        rec_f[n_rec, :, :] = fc_end
        n_rec += 1
    return t, h, OK, n_rec, steps
