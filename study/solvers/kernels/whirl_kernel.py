"""Compiled integrator of the reference model (method ``reference``; ``docs/reference_model.md``).

The pipe section's modal coordinates in both lateral directions, z = (q_y, q_z, q̇_y, q̇_z, W), are
advanced by the Dormand–Prince 5(4) pair with error control (Hairer, Nørsett & Wanner, *Solving
Ordinary Differential Equations I*, 2nd ed., Springer 1993, §II.5, doi:10.1007/978-3-540-78862-1) —
the flights are not linear once the mud's quadratic drag is kept, so no closed-form flight exists.
The last stage of a step is the first of the next (FSAL), and the step size follows the PI
controller of Gustafsson (ACM TOMS 17, 533–554, 1991, doi:10.1145/210232.210242) as in Hairer &
Wanner's DOPRI5 (Hairer, Nørsett & Wanner 1993, §II.4; *Solving ODEs II*, §IV.2): it keeps the step
steady where stability rather than accuracy limits it, as in a held contact.

Between contacts the pair is taken in its Lawson (integrating-factor) form (:func:`_lawson_step`; Lawson, SIAM J.
Numer. Anal. 4, 372–380, 1967, doi:10.1137/0704033; Hochbruck & Ostermann, Acta Numerica 19, 209–286, 2010,
doi:10.1017/S0962492910000048): each mode's linear part −ω_n² q − d_n q̇ is carried by its closed-form flow, so the
free ringing of the high modes that an impact excites costs no steps; while a contact is open the wall's stiffness
sets the step and the plain pair is cheaper (``scheme`` of :func:`advance`; docs/reference_model.md §4, §6).

Every switch of a contact force is located: a step that ends with a contact point inside the wall by
more than ``ONSET_TOLERANCE`` of its clearance, or past the end of a contact force by more than that
(the penetration back below zero, or the bracket of the normal force below it), is redone, cut to
where the step's continuous extension (the 4th-order dense output of DOPRI5, Hairer, Nørsett &
Wanner 1993 §II.6) puts the switch half that tolerance behind, until it lands within it: no step
integrates across a kink of the force. At an onset the Hunt–Crossley hysteresis of the contact is
set from its approach speed (as :mod:`study.solvers.kernels.event_driven` does; no slower than
``ONSET_SPEED_FLOOR``); the contact is closed where
the penetration returns to zero. A step is also capped at the predicted time to the next onset, so
that one step cannot carry a point through a whole contact.

The last four entries of z integrate the power balance: work of the applied loads (eccentric and
side load), work of wall friction on the lateral motion, drag dissipation and contact loss, so
that the energy balance is checked to the integrator's own accuracy.

Right-hand side (per modal mass m = M L/2, φ_pn = ψ_n(x_p), the periodic basis of
:func:`study.physics.string_modes.mode_shapes`):

    q̈ = −ω_n² q − d_n q̇ + Re/Im(ε_n e^{iΩt}) + s_n e_y
         − Σ_g w_g S_gn D |u̇_g| u̇_g / m + Σ_p φ_pn F_p / m

with the contact force on the pipe at point p, penetration δ = |u_p| − c_p, outward normal n̂,
t̂ = e_x × n̂:  F_p = −F_n n̂ − μ F_n v_s/√(v_s² + v_ε²) t̂, v_s = u̇_p·t̂ + Ω r_p, and
F_n = F_s(δ)(1 + χ_p δ̇)₊ (law 0, Hertz with Hunt–Crossley damping) or (k_p δ + c_p δ̇)₊ (law 1,
linear penalty spring-dashpot); or, for a strike at a tool joint with ``reference_strike_force = "pulse"``, the local
strike's force history at its onset speed (:func:`pulse_force`, docs/reference_model.md §2.4), after which the point's
wall is shifted to where the kept modes put the point (``P_SHIFT``). F_s is the Hertz spring K_p δ_H^{3/2} in series
with the residual flexibility f_p
of the modes left out at the point (:func:`series_hertz`; f_p = 0: Hertz alone; docs/reference_model.md §2.1);
the penalty's k_p has it folded in by the model.
"""

from __future__ import annotations

import numba
import numpy as np

from study.physics.contact import hertz_force_one
from study.solvers.kernels.drag import drag_linearised
from study.solvers.kernels.pulse import (N_PULSE_STATE, P_DURATION, P_LAW, P_MODE, P_OVERLAP, P_PEAK,  # noqa: F401
                                         P_PULSE, P_SHIFT, P_SHIFT_MAX, P_T0, onset_speed, point_state, pulse_force,
                                         pulse_step_work, size_pulse, start_strike, work_arrays)

#: Penetration (fraction of the point's clearance) within which an onset is taken as located.
ONSET_TOLERANCE = 1e-6
#: Approach speed [m/s] below which a contact opens with the Hunt–Crossley damping of this speed, χ = h(e)/v
#: (its restitution then nearer 1, as in Hunt & Crossley's law of constant damping): a contact settling onto the
#: wall at a vanishing speed would otherwise get an unbounded χ, a stiffness that held the explicit steps of a
#: pipe sliding on the wall 100 times below those of its elastic contact (docs/reference_model.md §6).
ONSET_SPEED_FLOOR = 1e-3
#: Cuts of a step after which the end of a Hunt–Crossley contact force (its bracket 1 + χ δ̇ through zero while the
#: point is still inside the wall) is located to what the steps resolve of the rate δ̇, ONSET_TOLERANCE of Ω c, instead
#: of ONSET_TOLERANCE of the bracket itself. The bracket moves by χ times the rate's error, and a contact that
#: opened at the floor speed (ONSET_SPEED_FLOOR: χ = h(e)/1e-3 m/s, thousands of s/m) needs the rate to 1e-10 m/s,
#: far below the steps' own error (rtol × Ω c): the continuous extension then put the end a little late at every
#: cut, each cut shortened the step by 0.01-0.1 % and the sixty attempts ran out (a step size underflow; the
#: default study's 275 rpm, 10 000 lbf, 12 ppg, 7.4 ft/s point in its straight hole, docs/reference_model.md §4).
ENDING_RETRIES = 2
#: Outcomes of :func:`advance`.
OK, BLOWN_UP, STEP_UNDERFLOW, TOO_MANY_STEPS = 0, 1, 2, 3
OUTCOMES = {OK: "ok", BLOWN_UP: "non-finite state or deflection above 100 clearances",
            STEP_UNDERFLOW: "step size underflow", TOO_MANY_STEPS: "step budget exhausted"}
#: Entries of the ``stats`` array of :func:`advance` (its work, for profiling; docs/reference_model.md §6):
#: time with any contact [s], accepted steps, steps rejected by the error test, steps redone to locate the
#: onset or end of a contact force, right-hand-side evaluations, steps shortened to the predicted time of an onset,
#: accepted steps with a contact open.
S_CONTACT_TIME, S_ACCEPTED, S_ERROR_REJECTED, S_SWITCH_REDONE, S_RHS, S_CAPPED, S_CONTACT_STEPS = range(7)
#: ... and with the strikes' pulses (``reference_strike_force = "pulse"``, :func:`pulse_force`): pulses applied, and
#: pulses that ended with the joint still moving towards its wall (the contact law then takes it on).
S_PULSES, S_RESTRIKES = 7, 8
N_STATS = 9
#: Schemes of :func:`advance`: Dormand–Prince on the whole right-hand side; its Lawson form at every step; the
#: Lawson form between contacts and Dormand–Prince while one is open.
DOPRI5, LAWSON, LAWSON_FLIGHT = 0, 1, 2
#: The floating-point licence of :func:`advance`: numba's fastmath flags to fuse multiply-adds and reorder sums (so
#: that the drag's and the stages' sums run in vector instructions). Deterministic only because nothing compiled apart
#: is linked into advance: every kernel it calls is inlined at numba's level (``inline="always"``), it allocates
#: nothing (:func:`workspace`), assigns no slices and raises to no integer power — numba compiles the helpers of those
#: once per process, with the licence of the first kernel that needs them, and LLVM inlines them. With any such
#: callee a chaotic motion's answers depended on what the process had compiled before (docs/reference_model.md §6);
#: tests/solvers/test_whirl_kernel.py holds advance to the rule.
FASTMATH = {"contract", "reassoc"}

#: PI step-size control (Hairer & Wanner's DOPRI5): exponent β of the previous error, safety factor,
#: smallest and largest step ratio.
PI_BETA, SAFETY, SHRINK_LIMIT, GROW_LIMIT = 0.04, 0.9, 0.2, 5.0

# Dormand–Prince 5(4) tableau (Hairer, Nørsett & Wanner 1993, Table II.5.2)
_C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0])
_A = np.zeros((7, 6))
_A[1, :1] = [1 / 5]
_A[2, :2] = [3 / 40, 9 / 40]
_A[3, :3] = [44 / 45, -56 / 15, 32 / 9]
_A[4, :4] = [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729]
_A[5, :5] = [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656]
_A[6, :6] = [35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84]
_E = np.array([71 / 57600, 0.0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40])
# its continuous extension (Hairer, Nørsett & Wanner 1993 §II.6; the d_i of their DOPRI5 code, dense output)
_D = np.array([-12715105075 / 11282082432, 0.0, 87487479700 / 32700410799, -10690763975 / 1880347072,
               701980252875 / 199316789632, -1453857185 / 822651844, 69997945 / 29380423])


@numba.njit(cache=True, nogil=True, inline="always")
def series_hertz(d, K, f):
    """The normal force [N] of the Hertz spring K δ_H^{3/2} [N m^-3/2] in series with the flexibility f [m/N] (the
    modes left out, docs/reference_model.md §2.1) at the total approach d > 0 [m]: δ_H + f F = d, F = K δ_H^{3/2}.
    With x = √δ_H, g(x) = f K x³ + x² − d = 0 by Newton's method from the smaller of √d and (d/(f K))^{1/3}: each
    term of g alone reaches d there, so the start lies above the root, and g is increasing and convex for x > 0, so
    the iterates fall monotonically onto it (quadratically near it). f = 0: K d^{3/2} exactly."""
    if f <= 0.0:
        return hertz_force_one(d, K)
    c = f * K
    x = min(np.sqrt(d), (d / c) ** (1.0 / 3.0))
    for _ in range(40):
        step = (c * x * x * x + x * x - d) / (3.0 * c * x * x + 2.0 * x)
        x -= step
        if step <= 1e-15 * x:
            break
    return K * x * x * x


@numba.njit(cache=True, nogil=True)
def drag_halves(S):
    """The drag shapes S (G, N) at symmetric points (Gauss–Legendre nodes: x_{G−1−g} = L − x_g) as :func:`rhs` sums
    them: SH (N, ⌈G/2⌉), the left half's rows transposed, and each mode's parity, +1 where its shape is symmetric
    about midspan (sin k_n(L − x) = sin k_n x, odd n) and −1 where antisymmetric (even n), read from the first and
    last rows (sin k_n x_0 ≠ 0 for the modes of a rule with more points than modes)."""
    G, N = S.shape
    Hm = (G + 1) // 2
    SH = np.empty((N, Hm))
    parity = np.empty(N)
    for n in range(N):
        for g in range(Hm):
            SH[n, g] = S[g, n]
        parity[n] = 1.0 if abs(S[G - 1, n] - S[0, n]) <= abs(S[G - 1, n] + S[0, n]) else -1.0
    return SH, parity


@numba.njit(cache=True, nogil=True, inline="always")
def rhs(t, z, chi, out, fc, pen, scratch, sy, linear=True):
    """ż into ``out`` (without ``linear``, only its nonlinear part N(t, z), ż − Lz: the modal terms q̇ and
    −ω_n² q − d_n q̇ left out, as the Lawson step takes them exactly); contact forces on the pipe (F_y, F_z, F_n)
    per point into ``fc`` (P, 3); penetration
    and its rate (δ, δ̇) per point into ``pen`` (P, 2); ``scratch`` (:func:`drag_scratch`) holds the drag points'
    velocities and their half sums, and the modes' velocities, in the drag sums' precision (SH's dtype).

    sy = (omega2, damping, eccentric (1 or 2, N: in phase with cos Ωt, and in quadrature where the joints'
    eccentricities turn), side, SH (N, ⌈G/2⌉), w, phi, clearance, radius, K, kp, cp, fpar, parity (N,),
    fr (P,) the residual flexibility of the modes left out at each point, in series with its Hertz spring; then the
    strikes' pulse tables, floor (P,), log speeds (S,), log peaks and log durations (P, S), shape coefficients (P, S, 4,
    G − 1), the per-point pulse state (P, N_PULSE_STATE) and the shapes (P, N) at the points whose velocity is a pulse's
    onset speed (none, (0, N): the whole approach rate), and ∫ ψ_n² dx / L (N,) of the modes above SH's first Nq ≤ N,
    whose drag is linearised about theirs (zeros: none; :func:`study.solvers.kernels.drag.drag_linearised`),
    :func:`kernel_system`):
    the drag points pair about midspan (x_g and x_{G−1−g} = L − x_g), where mode n's shape is
    parity_n = (−1)^{n+1} times its own, so the drag is summed over the left half's points only (SH, the shapes
    there, transposed): the velocity at a pair is E ± O (E over the symmetric modes, O over the antisymmetric), and a
    mode's drag the sum over the pairs of its shape times the pair's forces added (symmetric) or subtracted —
    half the multiplications of the sums over all G points (:func:`drag_halves`).
    """
    omega2, damp, ecc, side, SH, wts, phi, cl, rc, K, kp, cpen, fpar, parity, fr = sy[:15]
    pcoef, pst = sy[19], sy[20]
    N = omega2.size
    Nq = SH.shape[0]  # the modes whose drag is summed at the drag points (reference_drag_modes; the rest: sy[22])
    G = wts.size
    D, Om, mu, vreg, inv_m, law = fpar[0], fpar[1], fpar[2], fpar[3], fpar[4], fpar[5]
    co = np.cos(Om * t)
    si = np.sin(Om * t)
    turned = ecc.shape[0] > 1
    p_load = 0.0
    for n in range(N):
        vy = z[2 * N + n]
        vz = z[3 * N + n]
        fy = ecc[0, n] * co + side[n]
        fz = ecc[0, n] * si
        if turned:  # the joints' eccentricities in turned phases: the load's part in quadrature
            fy -= ecc[1, n] * si
            fz += ecc[1, n] * co
        if linear:
            out[n] = vy
            out[N + n] = vz
            out[2 * N + n] = -omega2[n] * z[n] - damp[n] * vy + fy
            out[3 * N + n] = -omega2[n] * z[N + n] - damp[n] * vz + fz
        else:
            out[n] = 0.0
            out[N + n] = 0.0
            out[2 * N + n] = fy
            out[3 * N + n] = fz
        p_load += fy * vy + fz * vz
    out[4 * N] = p_load / inv_m
    p_drag = 0.0
    if D > 0.0:
        # the drag points' velocities u̇_g = Σ_n S_gn q̇_n by pairs (E ± O at g and G − 1 − g), the drag force per
        # modal mass on them, then its projection on the modes by pairs: loops over the points run along
        # contiguous rows of SH
        Hm = SH.shape[1]
        H = G // 2
        uy, uz, ey, ez, oy, oz = scratch[0], scratch[1], scratch[2], scratch[3], scratch[4], scratch[5]
        wy, wz = scratch[6], scratch[7]  # the modes' velocities in the sums' precision (SH's: float64 or float32)
        for n in range(N):
            wy[n] = z[2 * N + n]
            wz[n] = z[3 * N + n]
        for g in range(Hm):
            ey[g] = 0.0
            ez[g] = 0.0
            oy[g] = 0.0
            oz[g] = 0.0
        for n in range(Nq):
            vy = wy[n]
            vz = wz[n]
            if parity[n] > 0.0:
                for g in range(Hm):
                    ey[g] += SH[n, g] * vy
                    ez[g] += SH[n, g] * vz
            else:
                for g in range(Hm):
                    oy[g] += SH[n, g] * vy
                    oz[g] += SH[n, g] * vz
        for g in range(H):
            m = G - 1 - g
            uy[g] = ey[g] + oy[g]
            uz[g] = ez[g] + oz[g]
            uy[m] = ey[g] - oy[g]
            uz[m] = ez[g] - oz[g]
        if Hm > H:  # an odd rule's midspan point, its own mirror
            uy[H] = ey[H] + oy[H]
            uz[H] = ez[H] + oz[H]
        if Nq < N and sy[22][Nq] > 0.0:
            p_drag += drag_linearised(z, out, uy, uz, wts, D, sy[22], inv_m, Nq, N)
        for g in range(G):
            sp = np.sqrt(uy[g] * uy[g] + uz[g] * uz[g])
            c = D * sp * wts[g]
            p_drag += c * sp * sp
            uy[g] *= c * inv_m
            uz[g] *= c * inv_m
        for g in range(H):  # the pairs' forces added (ey, ez) and subtracted (oy, oz)
            m = G - 1 - g
            ey[g] = uy[g] + uy[m]
            ez[g] = uz[g] + uz[m]
            oy[g] = uy[g] - uy[m]
            oz[g] = uz[g] - uz[m]
        if Hm > H:
            ey[H] = uy[H]
            ez[H] = uz[H]
            oy[H] = uy[H]
            oz[H] = uz[H]
        for n in range(Nq):
            ay = az = ey[0] - ey[0]  # 0 in the sums' precision
            if parity[n] > 0.0:
                for g in range(Hm):
                    ay += SH[n, g] * ey[g]
                    az += SH[n, g] * ez[g]
            else:
                for g in range(Hm):
                    ay += SH[n, g] * oy[g]
                    az += SH[n, g] * oz[g]
            out[2 * N + n] -= ay
            out[3 * N + n] -= az
    out[4 * N + 2] = p_drag
    p_fric = 0.0
    p_loss = 0.0
    for p in range(phi.shape[0]):
        y, w, yd, wd = point_state(z, phi, p, N)
        r = np.sqrt(y * y + w * w)
        d = r - cl[p]
        pen[p, 0] = d
        pen[p, 1] = (y * yd + w * wd) / r if r > 0.0 else 0.0
        fc[p, 0] = 0.0
        fc[p, 1] = 0.0
        fc[p, 2] = 0.0
        mode = pst[p, P_MODE]
        shifted = pst[p, P_SHIFT] > 0.0
        if (d > 0.0 or mode == P_PULSE or shifted) and r > 0.0:
            ny = y / r
            nz = w / r
            dd = yd * ny + wd * nz  # δ̇
            vt = -yd * nz + wd * ny  # u̇·t̂, t̂ = (−n_z, n_y)
            if mode == P_PULSE or shifted:
                # a strike's force prescribed (its local model's history, pulse_force), or the contact law on a wall
                # shifted after one: the force's whole work on the modes here; the stored energy the kernel's energy
                # counts (the series spring's at the unshifted wall) is taken out of it at each step's end, exactly
                # (:func:`_stored_energy`), so that the rest is the contact's loss (docs/reference_model.md §2.4)
                elastic = 0.0
                if mode == P_PULSE:
                    fn = pulse_force(t, pst, pcoef, p)
                elif d > 0.0:
                    fn = max(series_hertz(d, K[p], fr[p]) * (1.0 + chi[p] * dd), 0.0)
                else:
                    fn = 0.0
            elif law == 0:
                elastic = series_hertz(d, K[p], fr[p])
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


@numba.njit(cache=True, nogil=True, inline="always")
def _stored_energy(d, K, f):
    """The series contact's stored energy [J] at the total approach d [m] (0 for d ≤ 0): the Hertz spring's
    2/5 K δ_H^{5/2} = 2/5 F δ_H plus the flexibility's f F²/2, F = :func:`series_hertz` (as the model's energy)."""
    if d <= 0.0:
        return 0.0
    F = series_hertz(d, K, f)
    dh = (F / K) ** (2.0 / 3.0)
    return 0.4 * F * dh + 0.5 * f * F * F


@numba.njit(cache=True, nogil=True, inline="always")
def _error_norm(difference, z, znew, scale, rtol, N):
    """The step's error norm: RMS over the 4N dynamic entries of the embedded difference (z5 − z4) over
    rtol (scale + max(|z|, |z_new|)); a step is accepted at 1 or less."""
    err = 0.0
    for i in range(4 * N):
        sc = rtol * (scale[i] + max(abs(z[i]), abs(znew[i])))
        ratio = difference[i] / sc
        err += ratio * ratio  # not ** 2: numba compiles powers apart, and advance must have no compiled callee
    return np.sqrt(err / (4 * N))


@numba.njit(cache=True, nogil=True, inline="always")
def _step(t, z, h, chi, sy, k, stage, znew, fc, pen, scratch, scale, rtol, N):
    """One Dormand–Prince step from (t, z) with k[0] = f(t, z) given: the 5th-order state into ``znew``, its
    derivative (the next step's first stage) into k[6], with the forces and penetrations there in ``fc``
    and ``pen``; ``stage`` ends holding the embedded difference z5 − z4. Returns its error norm
    (:func:`_error_norm`)."""
    n = z.size
    for s in range(1, 6):
        for i in range(n):
            acc = 0.0
            for j in range(s):
                acc += _A[s, j] * k[j, i]
            stage[i] = z[i] + h * acc
        rhs(t + _C[s] * h, stage, chi, k[s], fc, pen, scratch, sy)
    for i in range(n):
        znew[i] = z[i] + h * (_A[6, 0] * k[0, i] + _A[6, 2] * k[2, i] + _A[6, 3] * k[3, i]
                              + _A[6, 4] * k[4, i] + _A[6, 5] * k[5, i])
    rhs(t + h, znew, chi, k[6], fc, pen, scratch, sy)
    for i in range(4 * N):
        stage[i] = h * (_E[0] * k[0, i] + _E[2] * k[2, i] + _E[3] * k[3, i] + _E[4] * k[4, i] + _E[5] * k[5, i]
                        + _E[6] * k[6, i])
    return _error_norm(stage, z, znew, scale, rtol, N)


@numba.njit(cache=True, nogil=True, inline="always")
def _propagator(w2, d, s):
    """e^{sL} of one mode's linear part, q̈ = −ω² q − d q̇, on (q, q̇): the damped oscillator's free motion over
    the time s [s] (any sign) in closed form, (a, b, c, e) of [[a, b], [c, e]], and its determinant e^{−d s}.
    With β = d/2 and μ² = ω² − β²: e^{−βs} [[C + βS, S], [−ω² S, C − βS]], C = cos μs, S = sin(μs)/μ (cosh and
    sinh of |μ| s overdamped, C = 1, S = s critically damped)."""
    beta = 0.5 * d
    mu2 = w2 - beta * beta
    if mu2 > 0.0:
        mu = np.sqrt(mu2)
        C = np.cos(mu * s)
        S = np.sin(mu * s) / mu
    elif mu2 < 0.0:
        kappa = np.sqrt(-mu2)
        C = np.cosh(kappa * s)
        S = np.sinh(kappa * s) / kappa
    else:
        C = 1.0
        S = s
    g = np.exp(-beta * s) if beta != 0.0 else 1.0
    return g * (C + beta * S), g * S, -g * w2 * S, g * (C - beta * S), g * g


@numba.njit(cache=True, nogil=True, inline="always")
def _propagate(B, x, out, N):
    """out = e^{sL} x with B (N, 4) the modes' blocks (:func:`_propagator`): (q_y, q̇_y) and (q_z, q̇_z) of each
    mode by its block, the energy integrals unchanged (L = 0 there). ``out`` may be ``x``."""
    for m in range(N):
        a, b, c, e = B[m, 0], B[m, 1], B[m, 2], B[m, 3]
        q, v = x[m], x[2 * N + m]
        out[m] = a * q + b * v
        out[2 * N + m] = c * q + e * v
        q, v = x[N + m], x[3 * N + m]
        out[N + m] = a * q + b * v
        out[3 * N + m] = c * q + e * v
    for i in range(4 * N, x.size):
        out[i] = x[i]


@numba.njit(cache=True, nogil=True, inline="always")
def _store_propagator(ex, i, m, a, b, c, e, det):
    """e^{sL} = [[a, b], [c, e]] into ex[0, i, m] and its inverse [[e, −b], [−c, a]]/det into ex[1, i, m]."""
    ex[0, i, m, 0] = a
    ex[0, i, m, 1] = b
    ex[0, i, m, 2] = c
    ex[0, i, m, 3] = e
    inv = 1.0 / det  # one division, not four (det = 1 exactly without modal damping: the same numbers)
    ex[1, i, m, 0] = e * inv
    ex[1, i, m, 1] = -b * inv
    ex[1, i, m, 2] = -c * inv
    ex[1, i, m, 3] = a * inv


@numba.njit(cache=True, nogil=True, inline="always")
def _turn(a, b):
    """(cos, sin, decay) of the sum of two angles and decay times from theirs (angle addition)."""
    return a[0] * b[0] - a[1] * b[1], a[1] * b[0] + a[0] * b[1], a[2] * b[2]


@numba.njit(cache=True, nogil=True, inline="always")
def _stage_propagators(omega2, damp, h, ex, N):
    """e^{±c hL} of every mode at the Dormand–Prince nodes c = 1/5, 3/10, 4/5, 8/9, 1 into ex (2, 5, N, 4)
    (:func:`_propagator`). For an underdamped mode the cosines, sines and decays at the nodes (18, 27, 72, 80 and
    90 times h/90) are built from those at h/90 by the angle-addition formulas: one sine and cosine a mode instead
    of five (the trigonometric functions were most of the Lawson step's cost beside the right-hand side; the
    products keep them to about 100 rounding errors, 1e-14)."""
    for m in range(N):
        w2, d = omega2[m], damp[m]
        beta = 0.5 * d
        mu2 = w2 - beta * beta
        if mu2 <= 0.0:
            for i in range(5):
                a, b, c, e, det = _propagator(w2, d, _C[i + 1] * h)
                _store_propagator(ex, i, m, a, b, c, e, det)
            continue
        mu = np.sqrt(mu2)
        x = mu * h / 90.0
        p1 = (np.cos(x), np.sin(x), np.exp(-beta * h / 90.0) if beta != 0.0 else 1.0)
        p2 = _turn(p1, p1)
        p8 = _turn(_turn(p2, p2), _turn(p2, p2))
        p16 = _turn(p8, p8)
        p64 = _turn(_turn(p16, p16), _turn(p16, p16))
        p18 = _turn(p16, p2)
        p80 = _turn(p64, p16)
        for i in range(5):
            if i == 0:
                C, S, g = p18  # 1/5
            elif i == 1:
                C, S, g = _turn(p18, _turn(p8, p1))  # 3/10
            elif i == 2:
                C, S, g = _turn(p64, p8)  # 4/5
            elif i == 3:
                C, S, g = p80  # 8/9
            else:
                C, S, g = _turn(p80, _turn(p8, p2))  # 1
            S /= mu
            _store_propagator(ex, i, m, g * (C + beta * S), g * S, -g * w2 * S, g * (C - beta * S), g * g)


@numba.njit(cache=True, nogil=True, inline="always")
def _relative_stage(kv, k, s, omega2, N):
    """Stage s of a Lawson step (:func:`_lawson_step`) relative to its first force, into kv[s] before its image: on the
    dynamic entries of the modes with stiffness k[s] − k[0] (0 for s = 0), whose static deflection under k[0] the step
    is taken about; elsewhere (the energy integrals, the modes with ω = 0) k[s]. By direction and mode: one loop over
    the entries with each one's mode as i % N (an integer division an entry) made a Lawson evaluation 1.50 and 1.34
    times a Dormand–Prince one at 64 and 128 modes, against 1.23 and 1.21 this way (docs/reference_model.md §6)."""
    for j in range(4):
        for m in range(N):
            i = j * N + m
            if omega2[m] > 0.0:
                kv[s, i] = 0.0 if s == 0 else k[s, i] - k[0, i]
            else:
                kv[s, i] = k[s, i]
    for i in range(4 * N, k.shape[1]):
        kv[s, i] = k[s, i]


@numba.njit(cache=True, nogil=True, inline="always")
def _lawson_step(t, z, h, chi, sy, k, kv, ex, stage, vend, shift, znew, fc, pen, scratch, scale, rtol, N):
    """One Lawson (integrating-factor) Dormand–Prince step from (t, z) with k[0] = N(t, z) given (the nonlinear
    part, ``rhs`` without ``linear``; Lawson 1967, doi:10.1137/0704033; Hochbruck & Ostermann 2010 §2.4,
    doi:10.1017/S0962492910000048), taken about the step's first force: the free motion under the constant
    force N_0 = k[0] is the free motion about the static deflection u_s = −L⁻¹N_0 (q_s = f/ω² per mode, into
    ``shift``; a mode with ω = 0 has none and keeps the plain Lawson form, N_0 in its stages), so with w = u − u_s,
    w' = Lw + N(t, w + u_s) − N_0 exactly, and the Dormand–Prince pair is
    applied to v(τ) = e^{−τL} w(t + τ): stage s is U_s = u_s + e^{c_s hL}[w_0 + h Σ_j a_sj e^{−c_j hL}(N_j − N_0)].
    The modes' free motion is exact at any step, and so is a rest under constant forces, which the plain
    Lawson form is not (its N_0 turns in e^{−τL} at the modes' frequencies; a contact held against the modes'
    stiffness is such a balance). The stages' N in ``k`` (k[6] the next step's first, FSAL), the images
    e^{−c hL}(N − N_0) in ``kv``, the 5th-order state into ``znew`` and its image e^{−hL}(znew − u_s) into
    ``vend`` (with ``kv`` and ``shift`` the continuous extension), the forces and penetrations at the step's
    end in ``fc`` and ``pen``; ``ex`` (2, 5, N, 4) receives the blocks e^{±c hL}. Returns the error norm as
    :func:`_step`, on the embedded difference mapped to t + h."""
    omega2, damp = sy[0], sy[1]
    n = z.size
    _stage_propagators(omega2, damp, h, ex, N)
    # the static deflection under N_0 (whose q entries are 0: q' = q̇ is all linear); w_0 = z − u_s
    for i in range(n):
        shift[i] = 0.0
    for m in range(N):
        if omega2[m] > 0.0:
            shift[m] = k[0, 2 * N + m] / omega2[m]
            shift[N + m] = k[0, 3 * N + m] / omega2[m]
    # the energy integrals (L = 0) and the modes without stiffness (ω = 0: no static deflection balances N_0, e.g.
    # the string's rigid translation) are not shifted: the plain Lawson form, which keeps N_0 in every stage
    _relative_stage(kv, k, 0, omega2, N)
    for s in range(1, 6):
        for i in range(n):
            acc = 0.0
            for j in range(s):
                acc += _A[s, j] * kv[j, i]
            stage[i] = z[i] - shift[i] + h * acc
        _propagate(ex[0, s - 1], stage, stage, N)
        for i in range(n):
            stage[i] += shift[i]
        rhs(t + _C[s] * h, stage, chi, k[s], fc, pen, scratch, sy, False)
        _relative_stage(kv, k, s, omega2, N)
        _propagate(ex[1, s - 1], kv[s], kv[s], N)
    for i in range(n):
        vend[i] = z[i] - shift[i] + h * (_A[6, 0] * kv[0, i] + _A[6, 2] * kv[2, i] + _A[6, 3] * kv[3, i]
                                         + _A[6, 4] * kv[4, i] + _A[6, 5] * kv[5, i])
    _propagate(ex[0, 4], vend, znew, N)
    for i in range(n):
        znew[i] += shift[i]
    rhs(t + h, znew, chi, k[6], fc, pen, scratch, sy, False)
    _relative_stage(kv, k, 6, omega2, N)
    _propagate(ex[1, 4], kv[6], kv[6], N)
    for i in range(n):
        stage[i] = h * (_E[0] * kv[0, i] + _E[2] * kv[2, i] + _E[3] * kv[3, i] + _E[4] * kv[4, i]
                        + _E[5] * kv[5, i] + _E[6] * kv[6, i])
    _propagate(ex[0, 4], stage, stage, N)
    return _error_norm(stage, z, znew, scale, rtol, N)


@numba.njit(cache=True, nogil=True, inline="always")
def _lawson_dense(z, vend, kv, shift, h, th, omega2, damp, N, out):
    """The state at θ of a Lawson step (:func:`_lawson_step`: start z, its end's image ``vend``, stages ``kv``,
    static deflection ``shift``) into ``out``: the Dormand–Prince continuous extension in the step's start frame
    (Hairer, Nørsett & Wanner 1993 §II.6), mapped by e^{θhL}, plus the static deflection."""
    s = 1.0 - th
    for i in range(z.size):
        r0 = z[i] - shift[i]
        r1 = vend[i] - r0
        r2 = h * kv[0, i] - r1
        r3 = r1 - h * kv[6, i] - r2
        r4 = h * (_D[0] * kv[0, i] + _D[2] * kv[2, i] + _D[3] * kv[3, i] + _D[4] * kv[4, i] + _D[5] * kv[5, i]
                  + _D[6] * kv[6, i])
        out[i] = r0 + th * (r1 + s * (r2 + th * (r3 + s * r4)))
    for m in range(N):
        a, b, c, e, _ = _propagator(omega2[m], damp[m], th * h)
        for j in range(2):
            q, v = out[j * N + m], out[(2 + j) * N + m]
            out[j * N + m] = a * q + b * v + shift[j * N + m]
            out[(2 + j) * N + m] = c * q + e * v


@numba.njit(cache=True, nogil=True, inline="always")
def _contact_function(y, w, yd, wd, cl, law, chi, kp, cp, ending):
    """Where the contact force switches, as a fraction of the clearance: the penetration δ/c for an onset;
    for the end of a contact, the smaller of δ/c and the bracket of the normal force, (1 + χ δ̇) (law 0) or
    (k δ + c δ̇)/(k c) (law 1), whose sign ends the force before δ returns to zero when the wall is slower."""
    r = np.sqrt(y * y + w * w)
    d = (r - cl) / cl
    if not ending:
        return d
    rate = (y * yd + w * wd) / r if r > 0.0 else 0.0
    bracket = 1.0 + chi * rate if law == 0 else d + cp * rate / (kp * cl)
    return min(d, bracket)


@numba.njit(cache=True, nogil=True, inline="always")
def _switch_fraction(z, znew, k, h, phi, p, N, cl, law, chi, kp, cp, ending, target, within, lawson, omega2, damp,
                     shift, r, v):
    """The fraction θ of the step at which :func:`_contact_function` of point p, on the step's continuous
    extension, reaches ``target`` within ``within`` (on one side of it at the start, on the other at the end):
    regula falsi with the Illinois modification. With ``lawson`` the extension is that of the Lawson step
    (:func:`_lawson_step`; ``znew`` its end and ``k`` its stages in the frame of the step's start, about the
    static deflection ``shift``) mapped by e^{θhL} (ω² ``omega2``, ``damp`` d of the modes). ``r``, ``v``: room for
    the extension's coefficients and values, (4N, 5) and (4N,) with ``lawson``, else (4, 5) and (4,)."""
    if lawson:
        # every dynamic entry's extension in the start's frame: e^{θhL} is applied per mode at each θ
        for i in range(4 * N):
            r[i, 0] = z[i] - shift[i]
            r[i, 1] = znew[i] - r[i, 0]
            r[i, 2] = h * k[0, i] - r[i, 1]
            r[i, 3] = r[i, 1] - h * k[6, i] - r[i, 2]
            r[i, 4] = h * (_D[0] * k[0, i] + _D[2] * k[2, i] + _D[3] * k[3, i] + _D[4] * k[4, i]
                           + _D[5] * k[5, i] + _D[6] * k[6, i])
    else:
        # the extension's coefficients projected on the point: y, z, ẏ, ż (Hairer, Nørsett & Wanner 1993 §II.6)
        for c in range(4):
            y0 = 0.0
            y1 = 0.0
            f0 = 0.0
            f6 = 0.0
            dsum = 0.0
            for m in range(N):
                i = c * N + m
                y0 += phi[p, m] * z[i]
                y1 += phi[p, m] * znew[i]
                f0 += phi[p, m] * k[0, i]
                f6 += phi[p, m] * k[6, i]
                dsum += phi[p, m] * (_D[0] * k[0, i] + _D[2] * k[2, i] + _D[3] * k[3, i] + _D[4] * k[4, i]
                                     + _D[5] * k[5, i] + _D[6] * k[6, i])
            r[c, 0] = y0
            r[c, 1] = y1 - y0
            r[c, 2] = h * f0 - r[c, 1]
            r[c, 3] = r[c, 1] - h * f6 - r[c, 2]
            r[c, 4] = h * dsum
    lo, hi = 0.0, 1.0
    glo = _switch_gap(r, v, 0.0, cl, law, chi, kp, cp, ending, target, lawson, h, phi, p, N, omega2, damp, shift)
    ghi = _switch_gap(r, v, 1.0, cl, law, chi, kp, cp, ending, target, lawson, h, phi, p, N, omega2, damp, shift)
    side = 0
    for _ in range(60):
        th = (lo * ghi - hi * glo) / (ghi - glo)
        g = _switch_gap(r, v, th, cl, law, chi, kp, cp, ending, target, lawson, h, phi, p, N, omega2, damp, shift)
        if abs(g) < within:
            return th
        if (g > 0.0) == (ghi > 0.0):
            hi, ghi = th, g
            if side == 1:
                glo *= 0.5
            side = 1
        else:
            lo, glo = th, g
            if side == -1:
                ghi *= 0.5
            side = -1
        if hi - lo < 1e-12:
            break
    return hi


@numba.njit(cache=True, nogil=True, inline="always")
def _switch_gap(r, v, th, cl, law, chi, kp, cp, ending, target, lawson, h, phi, p, N, omega2, damp, shift):
    """:func:`_contact_function` − target on the continuous extension at θ: coefficients r (4, 5) projected on
    the point, or with ``lawson`` (4N, 5) of every dynamic entry in the step's start frame about the static
    deflection ``shift``, mapped by e^{θhL}."""
    s = 1.0 - th
    for c in range(v.size):
        v[c] = r[c, 0] + th * (r[c, 1] + s * (r[c, 2] + th * (r[c, 3] + s * r[c, 4])))
    if not lawson:
        return _contact_function(v[0], v[1], v[2], v[3], cl, law, chi, kp, cp, ending) - target
    y = 0.0
    w = 0.0
    yd = 0.0
    wd = 0.0
    for m in range(N):
        a, b, c, e, _ = _propagator(omega2[m], damp[m], th * h)
        f = phi[p, m]
        y += f * (a * v[m] + b * v[2 * N + m] + shift[m])
        yd += f * (c * v[m] + e * v[2 * N + m])
        w += f * (a * v[N + m] + b * v[3 * N + m] + shift[N + m])
        wd += f * (c * v[N + m] + e * v[3 * N + m])
    return _contact_function(y, w, yd, wd, cl, law, chi, kp, cp, ending) - target


@numba.njit(cache=True, nogil=True, inline="always")
def _any_open(active):
    """Whether any contact point is in contact (a loop: numpy's ``any`` would link a compiled helper into
    :func:`advance`)."""
    for p in range(active.size):
        if active[p]:
            return True
    return False


@numba.njit(cache=True, nogil=True, inline="always")
def _any_held(active, pst):
    """Whether any contact point is in contact under the contact law (not a strike's pulse: :func:`_any_open`)."""
    for p in range(active.size):
        if active[p] and pst[p, P_MODE] == P_LAW:
            return True
    return False


@numba.njit(cache=True, nogil=True, inline="always")
def _record(rec_t, rec_z, rec_f, row, t, z, fc):
    """Row ``row`` of the recording: the time, the state and the contact forces (loops: no slice assignment, whose
    shape check would link a compiled helper into :func:`advance`)."""
    rec_t[row] = t
    for i in range(z.size):
        rec_z[row, i] = z[i]
    for p in range(fc.shape[0]):
        for j in range(3):
            rec_f[row, p, j] = fc[p, j]


def kernel_system(sy: tuple, drag_dtype=float, drag_rest=None, pulse_loss=None, matched: str = "local") -> tuple:
    """The tuple :func:`rhs` and :func:`advance` take from a model's (``reference.WhirlModel.system``: its drag shapes
    S (G, N)): S replaced by its left half transposed (in ``drag_dtype``, the drag sums' precision: float64, or
    float32 with ``reference_drag_precision = "single"``), and each mode's parity appended (:func:`drag_halves`) before
    the residual flexibility per point; then the strikes' pulse tables (the model's, in logs; without them a floor no
    speed reaches) and a fresh per-point pulse state (P, :data:`N_PULSE_STATE`), which :func:`advance` updates (the
    clearances are the kernel's own copy: a shifted wall moves them); then the shapes (P, N) whose velocity at a point
    is its pulse's onset speed, the model's after its pulse tables (``reference_pulse_speed = "kept"``), else none
    (0, N): the whole approach rate; then ``drag_rest`` (N,), ∫ ψ_n² dx / L of the modes whose drag is linearised
    (:func:`study.solvers.kernels.drag.drag_linearised`, ``WhirlModel.slow_drag``; None: zeros), pulse.work_arrays'."""
    omega2, damp, ecc, side, S, wts, phi, cl, rc, K, kp, cpen, fpar, fr = sy[:14]
    cl = np.array(cl, dtype=float)  # the kernel's own: a wall shifted after a strike's pulse moves it (P_SHIFT)
    P = cl.size
    # the strikes' pulses (reference_strike_force = "pulse"; WhirlModel.system): per point the floor speed [m/s] (inf:
    # none), the table's log speeds, log peaks and log durations and the shapes' spline coefficients; none: one
    # dummy speed pair no point reaches
    if len(sy) > 14:
        pfloor, speeds, peaks, durations, coef = sy[14:19]
    else:
        pfloor, speeds = np.full(P, np.inf), np.array([1e-3, 1e1])
        peaks, durations, coef = np.ones((P, 2)), np.ones((P, 2)), np.zeros((P, 2, 4, 1))
    SH, parity = drag_halves(np.ascontiguousarray(S, dtype=float))
    SH = SH.astype(drag_dtype, copy=False)  # the drag sums' precision
    # the eccentric load's modal amplitudes as rows (in phase with cos Ωt; in quadrature, where complex: the joints'
    # eccentricities turned, string_modes.eccentric_factors)
    ecc = (np.stack((ecc.real, ecc.imag)) if np.iscomplexobj(ecc) else np.asarray(ecc, float)[None, :]).astype(float)
    return (omega2, damp, ecc, side, SH, wts, phi, cl, rc, K, kp, cpen, fpar, parity,
            np.ascontiguousarray(fr, dtype=float), np.asarray(pfloor, float), np.log(np.asarray(speeds, float)),
            np.log(np.asarray(peaks, float)), np.log(np.asarray(durations, float)),
            np.ascontiguousarray(coef, dtype=float), np.zeros((P, N_PULSE_STATE)),
            np.ascontiguousarray(sy[19], dtype=float) if len(sy) > 19 else np.zeros((0, np.asarray(phi).shape[1])),
            np.zeros(omega2.size) if drag_rest is None else np.ascontiguousarray(drag_rest, dtype=float)
            ) + work_arrays(pulse_loss, np.shape(coef)[3], matched)


def drag_scratch(n_modes: int, n_drag: int, dtype=float) -> np.ndarray:
    """The drag's scratch of :func:`rhs` for N modes and G drag points, (8, max(G, N)) in the drag sums' precision
    (``dtype``, that of the drag shapes SH: float64, or float32 with ``reference_drag_precision = "single"``)."""
    return np.zeros((8, max(n_drag, n_modes)), dtype=dtype)


def workspace(n_modes: int, n_points: int, n_drag: int, drag_dtype=float) -> tuple:
    """The arrays :func:`advance` works in, for N modes, P contact points and G drag points: the stages k and their
    Lawson images kv (7, 4N + 4), the propagators (2, 5, N, 4), four states (4N + 4,), forces (P, 3) and penetrations
    (P, 2) at the stages and at the step's end, the drag's scratch (:func:`drag_scratch`), and the switch location's
    coefficients and values for a Lawson step, (4N, 5) and (4N,), and for a Dormand–Prince step, (4, 5) and (4,)."""
    N, P, n = n_modes, n_points, 4 * n_modes + 4
    return (np.zeros((7, n)), np.zeros((7, n)), np.zeros((2, 5, N, 4)), np.zeros(n), np.zeros(n), np.zeros(n),
            np.zeros(n), np.zeros((P, 3)), np.zeros((P, 3)), np.zeros((P, 2)), np.zeros((P, 2)),
            drag_scratch(N, n_drag, drag_dtype), np.zeros((4 * N, 5)), np.zeros(4 * N), np.zeros((4, 5)), np.zeros(4))


@numba.njit(cache=True, nogil=True, fastmath=FASTMATH)
def advance(t, t_end, z, active, chi, h, sy, work, rtol, scale, h_max, max_steps,
            stats, peak, onsets, contact_time, record, rec_dt, rec_t, rec_z, rec_f, n_rec, scheme, h_stable):
    """Integrate from t to t_end. Returns (t, h, outcome, n_rec, steps).

    ``scheme`` (:data:`SCHEMES`): ``DOPRI5`` the Dormand–Prince pair on the whole right-hand side
    (:func:`_step`), ``LAWSON`` its Lawson form (:func:`_lawson_step`, the modes' linear part exact) at every
    step, ``LAWSON_FLIGHT`` the Lawson form while no contact is open and Dormand–Prince while one is (a step
    never crosses a switch, so each step is one or the other; the first stage carried over is converted, f =
    Lz + N). The contact bookkeeping, the step cap and the counts are the same. A Dormand–Prince step is no
    longer than ``h_stable`` (its stability on the modes' frequencies), a Lawson step no longer than ``h_max``.

    ``active``/``chi`` (P,): contact state, updated (and the strikes' pulse state, the last entry of ``sy``).
    ``scale`` (4N,): error scale of the dynamic
    entries (c for q, Ωc for q̇); error per entry (z5 − z4)/(rtol (scale + |z|)), RMS ≤ 1 accepted.
    ``peak`` (P,): largest F_n; ``onsets`` (P,): contact onsets; ``contact_time`` (P,): time in
    contact; ``stats`` (N_STATS,): the work, added to (S_* above). With ``record``, rows (t, z, F) are
    stored every rec_dt[0] (no contact) or rec_dt[1] (a contact open) from index n_rec on, while room
    remains. ``sy`` as for :func:`rhs` (:func:`kernel_system`), ``work`` its room (:func:`workspace`): advance
    allocates nothing and calls no compiled function (everything it calls is inlined: :data:`FASTMATH`).
    """
    omega2, damp, ecc, side, SH, wts, phi, cl, rc, K, kp, cpen, fpar, parity, fr = sy[:15]
    pfloor, logv, lpeak, ldur, pst, speed_shapes = sy[15], sy[16], sy[17], sy[18], sy[20], sy[21]
    k, kv, ex, vend, shift, stage, znew, fc, fc_end, pen, pen_end, scratch, r_lawson, v_lawson, r_point, v_point = work
    hyst = fpar[6]
    law = int(fpar[5])
    om = fpar[1]
    N = omega2.size
    P = phi.shape[0]
    n = z.size
    # the form of the first stage k[0]: the whole ż (Dormand–Prince) or its nonlinear part N (Lawson)
    nonlinear = scheme == LAWSON or (scheme == LAWSON_FLIGHT and not _any_held(active, pst))
    rhs(t, z, chi, k[0], fc_end, pen_end, scratch, sy, not nonlinear)
    stats[S_RHS] += 1
    last_rec = -1e300
    steps = 0
    h_floor = 1e-14 * (1.0 + abs(t_end))
    err_old = 1e-4  # the previous accepted step's error (PI control)
    expo = 0.2 - 0.75 * PI_BETA
    while t < t_end:
        any_open = _any_open(active)
        if record and n_rec < rec_t.size:
            if t - last_rec >= (rec_dt[1] if any_open else rec_dt[0]) or t_end - t <= h_floor:
                _record(rec_t, rec_z, rec_f, n_rec, t, z, fc_end)
                n_rec += 1
                last_rec = t
        if t_end - t <= h_floor:
            t = t_end
            break
        steps += 1
        if steps > max_steps:
            return t, h, TOO_MANY_STEPS, n_rec, steps
        # a strike's pulse is a smooth force of time, no stiffness: the Lawson form takes it as a flight
        lawson = scheme == LAWSON or (scheme == LAWSON_FLIGHT and not _any_held(active, pst))
        if lawson != nonlinear:  # k[0] into this step's form: f = Lz + N
            sign = -1.0 if lawson else 1.0
            for m in range(N):
                for j in range(2):
                    q, v = z[j * N + m], z[(2 + j) * N + m]
                    k[0, j * N + m] += sign * v
                    k[0, (2 + j) * N + m] += sign * (-omega2[m] * q - damp[m] * v)
            nonlinear = lawson
        h = min(h, h_max if lawson else min(h_max, h_stable), t_end - t)
        # cap at the predicted onset of a point moving towards the wall, and a step lands on a pulse's end
        for p in range(P):
            if pst[p, P_MODE] == P_PULSE:
                left = pst[p, P_T0] + pst[p, P_DURATION] - t
                if left < h:
                    h = max(left, h_floor)
            elif not active[p] and pst[p, P_MODE] == P_LAW:
                d, rate = pen_end[p, 0], pen_end[p, 1]
                if rate > 0.0 and d < 0.0:
                    cap = max(-d / rate * 1.05, 1e-4 * h_max)
                    if cap < h:
                        h = cap
                        stats[S_CAPPED] += 1
        accepted = False
        rejected = False
        err = 0.0
        for _attempt in range(60):
            if h < h_floor:
                return t, h, STEP_UNDERFLOW, n_rec, steps
            if lawson:
                err = _lawson_step(t, z, h, chi, sy, k, kv, ex, stage, vend, shift, znew, fc, pen, scratch, scale,
                                   rtol, N)
            else:
                err = _step(t, z, h, chi, sy, k, stage, znew, fc, pen, scratch, scale, rtol, N)
            stats[S_RHS] += 6
            if not np.isfinite(err):
                h *= 0.1
                rejected = True
                continue
            if err > 1.0:
                h *= max(SHRINK_LIMIT, SAFETY * err ** -0.2)
                stats[S_ERROR_REJECTED] += 1
                rejected = True
                continue
            # an onset, or the end of a contact force, located within ONSET_TOLERANCE (of the clearance): else
            # the step is cut where the continuous extension puts it at half the tolerance past the switch
            cut = 2.0
            for p in range(P):
                if pst[p, P_MODE] != P_LAW:
                    continue  # a pulse ends at its time (the step lands on it), a free overlap has no force
                if active[p]:
                    y, w, yd, wd = point_state(z, phi, p, N)
                    if _contact_function(y, w, yd, wd, cl[p], law, chi[p], kp[p], cpen[p], True) <= 0.0:
                        continue
                    y, w, yd, wd = point_state(znew, phi, p, N)
                    f1 = _contact_function(y, w, yd, wd, cl[p], law, chi[p], kp[p], cpen[p], True)
                    # the end of the force: located within ONSET_TOLERANCE at the first cut; on a cut again, within
                    # what the steps resolve of the Hunt–Crossley bracket 1 + χ δ̇, ONSET_TOLERANCE of Ω c_p in δ̇
                    # (ENDING_RETRIES)
                    tol = ONSET_TOLERANCE
                    if law == 0 and _attempt >= ENDING_RETRIES:
                        tol = ONSET_TOLERANCE * (1.0 + chi[p] * om * cl[p])
                    if f1 < -tol:
                        th = _switch_fraction(z, vend if lawson else znew, kv if lawson else k, h, phi, p, N, cl[p],
                                              law, chi[p], kp[p], cpen[p], True, -0.5 * tol,
                                              0.25 * tol, lawson, omega2, damp, shift,
                                              r_lawson if lawson else r_point, v_lawson if lawson else v_point)
                        cut = min(cut, max(th, 0.02))
                elif pen[p, 0] > ONSET_TOLERANCE * cl[p] and pen_end[p, 0] < 0.0:
                    th = _switch_fraction(z, vend if lawson else znew, kv if lawson else k, h, phi, p, N, cl[p],
                                          law, 0.0, kp[p], cpen[p], False, 0.5 * ONSET_TOLERANCE,
                                          0.25 * ONSET_TOLERANCE, lawson, omega2, damp, shift,
                                          r_lawson if lawson else r_point, v_lawson if lawson else v_point)
                    cut = min(cut, max(th, 0.02))
            if cut < 2.0:
                h *= cut
                stats[S_SWITCH_REDONE] += 1
                continue
            accepted = True
            break
        if not accepted:
            return t, h, STEP_UNDERFLOW, n_rec, steps
        # accept
        stats[S_ACCEPTED] += 1
        if any_open:
            stats[S_CONTACT_TIME] += h
            stats[S_CONTACT_STEPS] += 1
        for p in range(P):
            if active[p]:
                contact_time[p] += h
        if record and lawson and not any_open:
            # a flight's rows at their times inside the step, from the continuous extension (the forces are 0):
            # a Lawson step in flight may be far longer than the rows' spacing
            tr = last_rec + rec_dt[0]
            while t + h - tr > 1e-6 * rec_dt[0] and n_rec < rec_t.size:  # not the step's end: recorded as such
                _lawson_dense(z, vend, kv, shift, h, (tr - t) / h, omega2, damp, N, rec_z[n_rec])
                rec_t[n_rec] = tr
                for p in range(P):
                    for j in range(3):
                        rec_f[n_rec, p, j] = 0.0
                n_rec += 1
                last_rec = tr
                tr += rec_dt[0]
        t = t + h if h < t_end - t else t_end
        for p in range(P):  # the stored energy's change at a pulse's or a shifted wall's point (rhs), exactly
            pulse_step_work(pst, p, h, fc_end, pen_end, fc, pen)
            if pst[p, P_MODE] == P_PULSE or pst[p, P_SHIFT] > 0.0:
                base = pst[p, P_SHIFT]
                znew[4 * N + 3] -= (_stored_energy(pen[p, 0] + base, K[p], fr[p])
                                    - _stored_energy(pen_end[p, 0] + base, K[p], fr[p]))
        for i in range(n):
            z[i] = znew[i]
            k[0, i] = k[6, i]  # FSAL: the last stage is the next step's first
        for p in range(P):
            for j in range(3):
                fc_end[p, j] = fc[p, j]
            pen_end[p, 0] = pen[p, 0]
            pen_end[p, 1] = pen[p, 1]
        opened = False
        for p in range(P):
            d, rate = pen_end[p, 0], pen_end[p, 1]
            if pst[p, P_MODE] == P_PULSE:
                if t < pst[p, P_T0] + pst[p, P_DURATION] - 2.0 * h_floor:
                    continue
                # the pulse's end: the wall put where the kept modes' point is, if inside it
                opened = True
                pst[p, P_MODE] = P_LAW
                active[p] = False
                chi[p] = 0.0
                if d > 0.0:
                    pst[p, P_SHIFT] += d
                    cl[p] += d
                    pen_end[p, 0] = 0.0
                    ratio = pst[p, P_SHIFT] / (pst[p, P_PEAK] / K[p]) ** (2.0 / 3.0)
                    if ratio > pst[p, P_OVERLAP]:
                        pst[p, P_OVERLAP] = ratio
                    if pst[p, P_SHIFT] > pst[p, P_SHIFT_MAX]:
                        pst[p, P_SHIFT_MAX] = pst[p, P_SHIFT]
                if rate > 0.0 and pen_end[p, 0] >= 0.0:
                    # still towards the wall: the strike is over and what pushes on is the string's motion, a contact
                    # the contact law holds (from the wall where the point is, its force from nil)
                    active[p] = True
                    chi[p] = hyst / max(rate, ONSET_SPEED_FLOOR)
                    stats[S_RESTRIKES] += 1
                continue
            if pst[p, P_SHIFT] > 0.0 and not active[p]:
                # a shifted wall follows the point back as it leaves (to ONSET_TOLERANCE of the clearance behind it, so
                # that its next onset is located), down to its place
                back = min(pst[p, P_SHIFT], max(-d - ONSET_TOLERANCE * (cl[p] - pst[p, P_SHIFT]), 0.0))
                if back > 0.0:
                    pst[p, P_SHIFT] -= back
                    cl[p] -= back
                    d += back
                    pen_end[p, 0] = d
            if active[p] and d <= 0.0:
                active[p] = False  # no force at d <= 0 whatever chi: the last stage stands
                chi[p] = 0.0
            elif not active[p] and d > 0.0:
                active[p] = True
                onsets[p] += 1
                opened = True
                speed = onset_speed(z, phi, speed_shapes, p, N, rate)
                if start_strike(p, t, speed, pst, pfloor, logv, lpeak, ldur, K):
                    stats[S_PULSES] += 1
                    size_pulse(z, phi, omega2, fpar[4], p, N, pst, sy[19], sy[23], sy[24], sy[25][0])
                    if pst[p, P_PEAK] > peak[p]:
                        peak[p] = pst[p, P_PEAK]
                else:
                    chi[p] = hyst / max(rate, ONSET_SPEED_FLOOR)
        if opened:  # the new chi changes the force at the step's end
            rhs(t, z, chi, k[0], fc_end, pen_end, scratch, sy, not nonlinear)
            stats[S_RHS] += 1
        for p in range(P):
            if fc_end[p, 2] > peak[p]:
                peak[p] = fc_end[p, 2]
        for i in range(4 * N):
            if not np.isfinite(z[i]):
                return t, h, BLOWN_UP, n_rec, steps
        for p in range(P):
            if pen_end[p, 0] > 100.0 * cl[p]:
                return t, h, BLOWN_UP, n_rec, steps
        # PI controller (Gustafsson 1991; DOPRI5): no growth right after a rejected step
        e = max(err, 1e-10)
        factor = min(GROW_LIMIT, max(SHRINK_LIMIT, SAFETY * e ** -expo * err_old ** PI_BETA))
        if rejected:
            factor = min(factor, 1.0)
        err_old = max(err, 1e-4)
        h = h * factor
    if record and n_rec < rec_t.size:
        _record(rec_t, rec_z, rec_f, n_rec, t, z, fc_end)
        n_rec += 1
    return t, h, OK, n_rec, steps
