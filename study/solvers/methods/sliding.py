"""The ``sliding`` method: the steady state of the reference model's scene with the pipe lying on the wall at some
of its contact points, the contact held and sliding round as the pipe turns (docs/reference_model.md §10; a rung of
the ``auto`` hierarchy between the free whirl and the reference model).

The scene and its equations are the reference model's (:mod:`study.solvers.methods.reference`, built by its
:func:`~study.solvers.methods.reference.build_model`: the same modes, loads, Hertz stiffness, friction and drag). In an
inclined hole the buoyed weight lays the section on the low side at its tool joints; the pipe turns there, its
surface sliding on the wall at Ω r_p, so the friction μ F_n keeps one sense and the contact never opens. The
motion that remains is then the response to the eccentric load turning with the pipe, which is small beside the
weight at low speed. It is solved in two parts:

- **rest**: the static equilibrium under the side load with Hertz contact and sliding friction at the touching
  points, F_p = −F_n (n̂ + μ s t̂) with F_n = K_p (|u_p| − c_p)^{3/2} and s = v_s/√(v_s² + v_ε²) at
  v_s = Ω r_p: per touching point the unknowns (F_n, angle of n̂), the deflection from the section's modal
  flexibility; the touching set found by adding the points past their wall and dropping those pulled off it;
- **whirl about the rest**: the synchronous response Re(A e^{iΩt}) to the eccentric load, the contact forces
  linearised about the rest (their 2×2 stiffness and damping per touching point, by differences of the force
  law; no Hunt–Crossley term, which depends on an onset a held contact never had), the quadratic drag
  replaced by the viscous drag that dissipates as much over the cycle, iterated with the motion as in the free
  whirl (:mod:`study.solvers.methods.freewhirl`).

The outputs are the reference model's, computed by its own functions on one revolution of this motion (the
contact forces from the exact force law on it): stresses with the quasi-static correction, peak contact force,
the whirl measure. Where the answer would not be this state, the method does not answer (``out_of_scope``, the
reference model does): no point touches (the free whirl's case); the contact would open during the revolution
(F_n ≤ 0: bouncing); a point not touching would reach its wall; or the linearisation is not good to the study's
tolerance — its error estimate is the largest difference, over the revolution, between the exact contact forces
on the motion and their linearisation, relative to the peak force, plus the modal truncation's share of the
largest moment and the drag iteration's last change.

Where that estimate is above the study's tolerance the same periodic state is solved without linearising, by
harmonic balance on the exact force laws (:func:`refine`, :func:`balance`), and answers where it settles with a
smaller error (its harmonic truncation and the modes'); where the joints swing far along the wall, in the wall's own
coordinates (each touching joint's angle along it and radial approach, :func:`balance`), not answered
where that motion is unstable (:func:`stability`: the reference model's run kicked off it leaves it).

Why a rung of its own: the reference model reaches this state only as its start-up ringing dies, and in the tangential
direction nothing but the quadratic drag damps it (sliding friction has a constant sense), so at 50–150 rpm it had not
settled after 120 revolutions, at 1–20 s a point; this state is what it tends to."""

from __future__ import annotations

import dataclasses
from typing import Any, Mapping

import numpy as np
from scipy import optimize

from study.physics import contact
from study.physics import whirl as whirl_physics
from study.solvers.methods import reference
from study.solvers.methods.sliding_parts import (STABILITY_KICK, STABILITY_SWING, least_force_slope,
                                                polynomial_root, second_motion, stability)
from study.solvers.model.options import force_tolerance, study_tolerance
from study.solvers.model.point import DesignPoint
from study.solvers.model.result import PointResult

METHOD = "sliding"
#: Inputs the answer does not depend on (``auto`` reuses one answer across them; a test holds the claim): none. Its
#: figures do not depend on the restitution, but its checks (:mod:`~study.solvers.methods.sliding_parts`) run the
#: reference model, whose held contacts it damps.
INDEPENDENT_OF = ()
SAMPLES = 256  #: Samples over the revolution for the outputs and the drag's equal dissipation.
#: Fixed-point iterations on the drag at most, and the relative change of A that ends them.
ITERATIONS, SETTLED = 50, 1e-10
ACTIVE_SET_STEPS = 10  #: Changes of the touching set at most.
#: e^{iθ} at the phases over the cycle at which the drag's equal dissipation is averaged.
PHASES = np.exp(1j * np.linspace(0.0, 2 * np.pi, 64, endpoint=False))


def contact_forces(model: reference.WhirlModel, u: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Forces on the pipe (..., P, 2) [N] and normal forces (..., P) [N] at displacements u and velocities v
    (..., P, 2) [m, m/s] of the contact points: the reference model's law (Hertz, sliding Coulomb friction on
    v_s = u̇·t̂ + Ω r_p regularised over v_ε) without the Hunt–Crossley term."""
    r = np.hypot(u[..., 0], u[..., 1])
    depth = np.maximum(r - model.clearance, 0.0)
    safe = np.where(r > 0, r, 1.0)
    ny, nz = u[..., 0] / safe, u[..., 1] / safe
    fn = contact.hertz_force(depth, model.stiffness)
    vs = whirl_physics.sliding_velocity(-v[..., 0] * nz + v[..., 1] * ny, model.rotary_speed, model.radius)
    ft = -model.friction * fn * whirl_physics.friction_factor(vs, model.slip_velocity)
    return np.stack((-fn * ny - ft * nz, -fn * nz + ft * ny), axis=-1), fn


def flexibility(model: reference.WhirlModel) -> np.ndarray:
    """Static deflection of point p per unit force at point q (P, P) [m/N] of the modal model's modes with stiffness
    (either direction); the rigid translation (ω = 0) has none: the contacts carry its load (:func:`rest`)."""
    gain = np.zeros(model.n_modes)
    stiff = model.omega > 0
    gain[stiff] = 1.0 / (model.mass * model.omega[stiff] ** 2)
    return (model.phi * gain) @ model.phi.T


def rest(model: reference.WhirlModel) -> dict[str, Any]:
    """The static equilibrium on the wall (module docstring): displacements u (P, 2) [m], forces (P, 2) [N], normal
    forces (P,) [N], the touching points (bool P), the modal state (2N,) and whether it was found.

    The string's rigid translation has no stiffness: its share of the loads (the whole of a uniform side load) is
    carried by the touching points, whose forces balance it (two equations beside each touching point's two), and
    its position is an unknown. The touching set starts from the tool joints (where a side load lays the string),
    loses a point the wall would have to pull (F_n < 0) and gains the point furthest past its wall, until every
    touching point pushes and no other is past its wall. Without a side load nothing touches (the pipe is centred).

    Kept in the model's ``cache`` (``"sliding_rest"``): the reference model's run starts from it
    (:func:`~study.solvers.methods.reference.integrate.initial_state`) and its lift-off eccentricity is computed about
    the same rest (:func:`add_lift_off`), solved once."""
    known = model.cache.get("sliding_rest")
    if known is not None:
        return known
    P, N = model.points.size, model.n_modes
    G = flexibility(model)
    stiff = model.omega > 0
    rigid = np.flatnonzero(~stiff)
    R = model.phi[:, rigid]  # (P, r) the rigid modes' shapes at the points
    held_load = model.mass * model.side[rigid]  # (r,) the side load's generalised force on them, +y [N]
    static = np.zeros(N)
    static[stiff] = model.side[stiff] / model.omega[stiff] ** 2
    free = np.zeros((P, 2))
    free[:, 0] = model.phi @ static
    loaded = np.any(held_load != 0.0) or np.any(np.hypot(free[:, 0], free[:, 1]) > model.clearance)
    touching = np.zeros(P, bool)
    if loaded:
        touching[:] = model.kinds == 1 if np.any(model.kinds == 1) else True
    forces, found = np.zeros((P, 2)), not touching.any()
    lift = np.zeros((rigid.size, 2))  # the rigid coordinates (y, z)
    s = whirl_physics.friction_factor(whirl_physics.sliding_velocity(0.0, model.rotary_speed, model.radius),
                                      model.slip_velocity)  # the friction's regularised sign at rest
    scale = max(float(np.max(np.abs(held_load))) if held_load.size else 0.0, 1e-300)
    r = rigid.size
    for _ in range(ACTIVE_SET_STEPS * P):
        idx = np.flatnonzero(touching)
        if idx.size == 0:
            found = True
            break
        Gaa, Ra = G[np.ix_(idx, idx)], R[idx]
        # the touching points' constants, taken out of the residual that the root finder calls many times
        count, slide, stiffness, wall, unloaded = (idx.size, model.friction * s[idx, None], model.stiffness[idx],
                                                   model.clearance[idx], free[idx])

        def force_of(x):  # unknowns per touching point: F_n and the angle of n̂ from the low side
            fn, angle = x[:count], x[count:2 * count]
            cos, sin = np.cos(angle), np.sin(angle)
            n, t = np.empty((count, 2)), np.empty((count, 2))
            n[:, 0], n[:, 1], t[:, 0], t[:, 1] = cos, sin, -sin, cos
            return -(fn[:, None] * (n + slide * t)), fn, n

        def residual(x):
            f, fn, n = force_of(x)
            held = x[2 * count:].reshape(r, 2)
            depth = np.sign(fn) * np.abs(fn / stiffness) ** (2.0 / 3.0)
            u = unloaded + Gaa @ f + Ra @ held
            balance = (np.column_stack((held_load, np.zeros(r))) + Ra.T @ f) / scale
            return np.concatenate((((u - (wall + depth)[:, None] * n) / wall[:, None]).ravel(), balance.ravel()))

        # start: the touching points held at the wall's low side by rigid supports: G F_n − R q_r = free − c and
        # Rᵀ F_n = the rigid modes' load
        A = np.block([[Gaa, -Ra], [Ra.T, np.zeros((r, r))]])
        start = np.linalg.lstsq(A, np.concatenate((free[idx, 0] - model.clearance[idx], held_load)), rcond=None)[0]
        x0 = np.concatenate((start[:count], np.zeros(count), np.column_stack((start[count:], np.zeros(r))).ravel()))
        sol = optimize.root(residual, x0, method="hybr", options=dict(xtol=1e-13))
        if not (sol.success and np.max(np.abs(residual(sol.x))) < 1e-9):
            break
        f, fn, _ = force_of(sol.x)
        if np.min(fn) < 0:  # the wall would pull: that point leaves it
            touching[idx[int(np.argmin(fn))]] = False
            continue
        forces[:] = 0.0
        forces[idx] = f
        lift = sol.x[2 * count:].reshape(r, 2)
        reach = np.hypot(*(free + G @ forces + R @ lift).T) / model.clearance
        reach[touching] = 0.0
        if np.max(reach) <= 1:
            found = True
            break
        touching[int(np.argmax(reach))] = True
    if not found:
        forces[:] = 0.0
        lift[:] = 0.0
    u = free + G @ forces + R @ lift
    _, fn = contact_forces(model, u, np.zeros_like(u))
    q = np.zeros(2 * N)
    q[:N][stiff] = (model.side + model.phi.T @ forces[:, 0] / model.mass)[stiff] / model.omega[stiff] ** 2
    q[N:][stiff] = (model.phi.T @ forces[:, 1] / model.mass)[stiff] / model.omega[stiff] ** 2
    q[:N][rigid], q[N:][rigid] = lift[:, 0], lift[:, 1]
    out = model.cache["sliding_rest"] = dict(u=u, forces=forces, normal=fn, touching=touching & (fn > 0), state=q,
                                             found=found)
    return out


def _linearised(model: reference.WhirlModel, u0: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The contact forces' stiffness −∂F/∂u and damping −∂F/∂u̇ (P, 2, 2) about the rest, by central differences."""
    P = model.points.size
    stiff, damp = np.zeros((P, 2, 2)), np.zeros((P, 2, 2))
    v0 = np.zeros_like(u0)
    du = 1e-7 * model.clearance
    dv = 1e-4 * model.slip_velocity
    e = np.zeros((2, P, 2))  # a unit step of each point in y (e[0]) and in z (e[1])
    e[0, :, 0] = e[1, :, 1] = 1.0
    step_u, step_v = e * du[:, None], e * dv
    # the eight displaced states at once (the force law acts point by point): u ± step in y and z, then u̇ ± step
    f, _ = contact_forces(model, np.concatenate((u0 + step_u, u0 - step_u, np.broadcast_to(u0, (4, P, 2)))),
                          np.concatenate((np.broadcast_to(v0, (4, P, 2)), v0 + step_v, v0 - step_v)))
    for j in range(2):
        stiff[:, :, j] = -(f[j] - f[2 + j]) / (2 * du[:, None])
        damp[:, :, j] = -(f[4 + j] - f[6 + j]) / (2 * dv)
    return stiff, damp


#: How the quadratic drag D|u̇|u̇ becomes a viscous drag c u̇ on a periodic motion: by equal dissipation over the
#: cycle, c = D⟨|u̇|³⟩/⟨|u̇|²⟩ (the answer), or c = D⟨|u̇|⟩ (the mean speed: the spread between the two measures
#: what the linearisation of the drag leaves out).
DRAG_RULES = ("dissipation", "mean_speed")


def whirl(model: reference.WhirlModel, rested: dict[str, Any], contact_scale: float = 1.0,
          drag_rule: str = "dissipation", linear: tuple[np.ndarray, np.ndarray] | None = None,
          start: np.ndarray | None = None, settled: float = SETTLED) -> dict[str, Any]:
    """The synchronous response about the rest (module docstring): complex modal amplitudes A (2N,) of
    Re(A e^{iΩt}) [m], the second-order motion on the wall's arc (modal amplitudes at 0 and 2Ω, and the inward
    shift of each point), the drag iteration's count and last change; ``contact_scale`` multiplies the contacts'
    linearised stiffness and ``drag_rule`` (:data:`DRAG_RULES`) says how the drag is made viscous (the
    linearisation's error is measured by changing them); ``linear``: the contacts' linearisation about this rest
    (:func:`_linearised`) where already made; ``start``: A to start the drag's iteration from, ``settled`` its end."""
    N, Om = model.n_modes, model.rotary_speed
    stiff, damp = linear if linear is not None else _linearised(model, rested["u"])
    stiff = stiff * contact_scale
    touching = rested["touching"]
    held = np.flatnonzero(touching)
    base = _dynamic_matrix(model, stiff, damp, held, 1)
    load = np.concatenate((model.eccentric, -1j * model.eccentric)).astype(complex)  # (cos, sin) Ωt
    S, w = model.drag_shapes, model.drag_weights
    phase = PHASES
    A = np.linalg.solve(base, load) if start is None else start
    change, iteration, C = 0.0, 0, None
    if model.drag > 0:
        for iteration in range(1, ITERATIONS + 1):
            vel = 1j * Om * np.stack((S @ A[:N], S @ A[N:]))  # (2, G) complex velocity amplitudes
            speed = np.hypot((vel[0][:, None] * phase).real, (vel[1][:, None] * phase).real)  # (G, 64)
            mean2 = np.mean(speed**2, axis=1)
            if drag_rule == "dissipation":
                c_eq = model.drag * np.where(mean2 > 0,
                                             np.mean(speed**3, axis=1) / np.where(mean2 > 0, mean2, 1.0), 0.0)
            else:
                c_eq = model.drag * np.mean(speed, axis=1)
            C = (S * (w * c_eq)[:, None]).T @ S / model.mass
            new = np.linalg.solve(_with_drag(base, Om, C), load)
            change = float(np.max(np.abs(new - A)) / max(np.max(np.abs(new)), 1e-300))
            A = new
            if change < settled:
                break
    # second order: a touching point moves on its wall's arc, inside the straight tangent of the linear motion by
    # r Δφ²/2 = r (|Φ|²/2 + Re(Φ² e^{2iΩt}/2))/2; the contact pulls it there, a load at 0 and 2Ω on the section
    u0 = rested["u"][held]
    r0 = np.hypot(u0[:, 0], u0[:, 1])
    n0 = u0 / r0[:, None]
    t0 = np.stack((-n0[:, 1], n0[:, 0]), axis=-1)
    moved = np.stack((model.phi[held] @ A[:N], model.phi[held] @ A[N:]), axis=-1)  # (H, 2) complex
    angle = np.einsum("hi,hi->h", moved, t0) / r0
    shift = {0: -r0 * np.abs(angle) ** 2 / 4, 2: -r0 * angle**2 / 4}  # inward normal shift, per harmonic [m]
    second = {}
    for h, d in shift.items():
        pull = np.einsum("hij,hj->hi", stiff[held], n0) * d[:, None]  # K_c (d n̂0) per point, (H, 2)
        load_h = np.concatenate((model.phi[held].T @ pull[:, 0], model.phi[held].T @ pull[:, 1])) / model.mass
        matrix = _dynamic_matrix(model, stiff, damp, held, h)
        second[h] = np.linalg.solve(_with_drag(matrix, h * Om, C) if h and C is not None else matrix,
                                    load_h.astype(complex))
    return dict(amplitudes=A, iterations=iteration, change=change, stiffness=stiff, damping=damp, drag_matrix=C,
                second=second, shift={h: _spread(d, held, touching.size) for h, d in shift.items()})


def _dynamic_matrix(model: reference.WhirlModel, stiff: np.ndarray, damp: np.ndarray, held: np.ndarray,
                    harmonic: int) -> np.ndarray:
    """The section's modal equations at the frequency harmonic × Ω without the drag, (2N, 2N) complex, rows and
    columns the y-modes then the z-modes: ω² − (hΩ)² + ihΩ d_n and the touching points' linearised contact
    (stiffness and damping, (P, 2, 2)); :func:`_with_drag` adds the drag."""
    N, frequency = model.n_modes, harmonic * model.rotary_speed
    matrix = np.diag(np.tile(model.omega**2 - frequency**2 + 1j * frequency * model.damping, 2))
    blocks = matrix.reshape(2, N, 2, N)  # [a, n, b, m]: direction a's mode n, direction b's mode m
    for p in held:
        k = stiff[p] + 1j * frequency * damp[p]
        outer = np.outer(model.phi[p], model.phi[p])
        blocks += k[:, None, :, None] * outer[None, :, None, :] / model.mass
    return matrix


def _with_drag(matrix: np.ndarray, frequency: float, drag: np.ndarray) -> np.ndarray:
    """The modal equations ``matrix`` (2N, 2N) of :func:`_dynamic_matrix` at ``frequency`` [rad/s] with the viscous drag
    ``drag`` (N, N) per modal mass, the same in both directions: + i frequency · drag on each direction's block."""
    N = drag.shape[0]
    out = matrix.copy()
    term = 1j * frequency * drag
    out[:N, :N] += term
    out[N:, N:] += term
    return out


def _spread(values: np.ndarray, where: np.ndarray, size: int) -> np.ndarray:
    """``values`` at the indices ``where`` of a zero array of ``size``."""
    out = np.zeros(size, complex)
    out[where] = values
    return out


def _per_point(matrices: np.ndarray, vectors: np.ndarray) -> np.ndarray:
    """Each point's 2×2 ``matrices`` (P, 2, 2) times its vectors ``vectors`` (..., P, 2) (as einsum "pij,...pj->...pi",
    written out: a sixth of its time on a revolution)."""
    y, z = vectors[..., 0], vectors[..., 1]
    return np.stack((matrices[:, 0, 0] * y + matrices[:, 0, 1] * z, matrices[:, 1, 0] * y + matrices[:, 1, 1] * z),
                    axis=-1)


def revolution(model: reference.WhirlModel, rested: dict[str, Any], whirled: dict[str, Any],
               samples: int = SAMPLES) -> tuple[reference.Window, dict[str, float]]:
    """One revolution of the motion as the reference model's :class:`~study.solvers.methods.reference.Window`, the
    contact forces linearised about the rest as the motion was solved; and the motion's sizes the linearisation
    is judged by: the largest swing of a touching point's angle on the wall [rad] and the Hertz secant stiffness
    over the normal approach's swing relative to the tangent one."""
    N, P, Om = model.n_modes, model.points.size, model.rotary_speed
    t = np.linspace(0.0, model.period, samples + 1)
    e = np.exp(1j * Om * t)
    A, second = whirled["amplitudes"], whirled["second"]
    e2 = e**2
    synchronous, double = A[None, :] * e[:, None], second[2][None, :] * e2[:, None]  # (R, 2N) complex
    q = rested["state"][None, :] + second[0].real[None, :] + (synchronous + double).real
    v = -Om * (synchronous + 2 * double).imag  # Re(iΩ z) = −Ω Im z
    u = np.stack((q[:, :N] @ model.phi.T, q[:, N:] @ model.phi.T), axis=-1)  # (R, P, 2)
    ud = np.stack((v[:, :N] @ model.phi.T, v[:, N:] @ model.phi.T), axis=-1)
    held = rested["touching"]
    u0 = rested["u"]
    r0 = np.hypot(u0[:, 0], u0[:, 1])
    n0 = u0 / np.where(r0 > 0, r0, 1.0)[:, None]
    t0 = np.stack((-n0[:, 1], n0[:, 0]), axis=-1)
    du = u - u0[None]
    inward = (whirled["shift"][0].real[None, :] + (whirled["shift"][2][None, :] * e2[:, None]).real)  # (R, P)
    forces = (rested["forces"][None] - _per_point(whirled["stiffness"], du - inward[..., None] * n0[None])
              - _per_point(whirled["damping"], ud))
    forces[:, ~held] = 0.0
    fn = -np.einsum("rpi,pi->rp", forces, n0)
    fn[:, ~held] = 0.0
    # the sizes of the motion on the wall: its angle's swing, and how far the Hertz law bends over the approach
    swing = np.einsum("rpi,pi->rp", du, t0)[:, held] / r0[held]
    depth0 = np.maximum(r0 - model.clearance, 0.0)[held]
    depth = depth0 + np.einsum("rpi,pi->rp", du, n0)[:, held]
    top = np.max(depth, axis=0)
    with np.errstate(divide="ignore", invalid="ignore"):
        secant = np.where(top > depth0, (contact.hertz_force(top, 1.0) - contact.hertz_force(depth0, 1.0))
                          / (top - depth0) / contact.linearised_stiffness(depth0, 1.0), 1.0)
    # the second-order motion's share of the contact force: the next order is about the angle's swing times it
    first = np.stack((synchronous[:, :N].real @ model.phi.T, synchronous[:, N:].real @ model.phi.T),
                     axis=-1)  # the synchronous motion's displacements at the points, (R, P, 2)
    first_order = (rested["forces"][None] - _per_point(whirled["stiffness"], first)
                   - _per_point(whirled["damping"], ud))
    second_share = float(np.max(np.abs(fn[:, held] + np.einsum("rpi,pi->rp", first_order, n0)[:, held]))
                         / max(float(np.max(fn)), 1e-300)) if np.any(held) else 0.0
    sizes = dict(second_order=second_share,
                 angle_swing=float(np.max(np.abs(swing))) if swing.size else 0.0,
                 secant_ratio=float(np.max(secant)) if secant.size else 1.0)
    peak = np.max(fn, axis=0)
    touching = held & np.all(fn > 0, axis=0)
    states = np.zeros((t.size, 4 * N + 4))
    states[:, :2 * N], states[:, 2 * N:4 * N] = q, v
    window = reference.Window(times=t, states=states, forces=np.concatenate((forces, fn[..., None]), axis=-1),
                              peak=peak, onsets=np.zeros(P, np.int64),
                              contact_time=np.where(touching, model.period, 0.0),
                              any_contact_time=model.period if np.any(touching) else 0.0, start=0.0, end=model.period)
    return window, sizes


#: Harmonics of Ω the steady state keeps (:func:`balance`), and the harmonics of the coarser solution its harmonic
#: truncation is measured against.
HARMONICS, COARSE_HARMONICS = 8, 4
#: Samples of a revolution per harmonic kept at which :func:`balance` evaluates the force laws (the products of the
#: motion's harmonics in the Hertz law and the drag fold back onto the harmonics kept only from beyond 3H).
SAMPLES_PER_HARMONIC = 4
#: Chord iterations of the harmonic balance at most, and the relative size of the last correction that ends them.
BALANCE_ITERATIONS, BALANCE_SETTLED = 30, 1e-8
#: The least motion about the rest the correction is measured against, over the rest's size (less is its rounding).
STILL_MOTION = 1e-6
#: The balance gives up where its line search cut the step below this in so many iterations running (1/256-1/512).
BALANCE_STALLED, BALANCE_STALLS = 1 / 64, 3


def _force_jacobians(model: reference.WhirlModel, u: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """∂F/∂u and ∂F/∂u̇ (..., P, 2, 2) [N/m, N s/m] of the contact forces (:func:`contact_forces`) at displacements u
    and velocities v (..., P, 2), by central differences (the steps of :func:`_linearised`)."""
    du = 1e-7 * model.clearance[:, None]
    dv = 1e-4 * model.slip_velocity
    ku, kv = np.empty(u.shape + (2,)), np.empty(u.shape + (2,))
    for j in range(2):
        e = np.zeros(u.shape)
        e[..., j] = 1.0
        plus, _ = contact_forces(model, u + e * du, v)
        minus, _ = contact_forces(model, u - e * du, v)
        ku[..., j] = (plus - minus) / (2 * du)
        plus, _ = contact_forces(model, u, v + e * dv)
        minus, _ = contact_forces(model, u, v - e * dv)
        kv[..., j] = (plus - minus) / (2 * dv)
    return ku, kv


def balance(model: reference.WhirlModel, rested: dict[str, Any], whirled: dict[str, Any],
            harmonics: int = HARMONICS, start: np.ndarray | None = None,
            coordinates: str = "cartesian") -> dict[str, Any]:
    """The periodic steady state of the reference model's equations on the wall, solved by harmonic balance: the modal
    coordinates q(t) = Re Σ_{h=0}^{H} Q_h e^{ihΩt} (Q (H+1, 2N) complex, Q_0 real) whose harmonics satisfy

        (ω² − (hΩ)² + ihΩ d) Q_h = L_h + F_h(Q),   h = 0 … H,

    L_0 the side load, L_1 the eccentric load, F_h the harmonics of the exact contact forces (Hertz, sliding
    friction, :func:`contact_forces`) and quadratic drag on the motion, taken from
    :data:`SAMPLES_PER_HARMONIC` × H samples of a revolution (alternating frequency–time; Cameron & Griffin 1989).

    The contacts' nonlinearity is local: the equations are condensed onto the touching points' displacements U
    (their 2(2H + 1) real Fourier coefficients each) through the section's receptance there, R_h = Φ Z_h⁻¹ Φᵀ / m
    with Z_h the modal equations linearised about the rest (:func:`_dynamic_matrix`, the drag of equal dissipation
    :func:`_with_drag`), and solved by Newton's method on U − U_L − R G(U) = 0, G the harmonics of the exact contact
    forces less their linearisation, its Jacobian from the force law's derivatives at each sample (a joint turning
    on its wall turns its stiff normal with it, which a Jacobian held at the rest does not follow). The drag's
    difference from its viscous equivalent is a load on the modes, updated from each iterate's motion. It starts
    from the linear answer (the rest, the synchronous whirl and the arc's second order of :func:`whirl`) and stops
    where the correction is below :data:`BALANCE_SETTLED` of the motion about the rest (:data:`STILL_MOTION` of the
    rest at least): the harmonics above H are what is left. ``start``: harmonics Q to start from (cut or padded).

    ``coordinates`` (:data:`BALANCE_COORDINATES`): the touching points' unknowns, their Cartesian displacement
    harmonics, or the harmonics of each one's angle φ along its wall and radial approach ρ, u = (c + ρ)(cos φ, sin φ)
    at the samples (a joint swinging 0.1-0.7 rad along the wall is a large angle, on which the Hertz law does not act;
    in y and z Newton's tangent step leaves the wall's circle into the stiff contact and its line search stalls).

    Returns the harmonics Q, the iterations, the last correction's relative size and whether it settled."""
    from scipy import linalg

    N, Om, H = model.n_modes, model.rotary_speed, harmonics
    M = SAMPLES_PER_HARMONIC * H
    Q = np.zeros((H + 1, 2 * N), complex)
    if start is None:
        Q[0] = rested["state"] + whirled["second"][0].real
        Q[1] = whirled["amplitudes"]
        if H >= 2:
            Q[2] = whirled["second"][2]
    else:
        rows = min(H + 1, start.shape[0])
        Q[:rows] = start[:rows]
    held = np.flatnonzero(rested["touching"])
    K0, D0 = whirled["stiffness"][held], whirled["damping"][held]  # −∂F/∂u, −∂F/∂u̇ at the rest
    C = whirled.get("drag_matrix")
    load = np.zeros((H + 1, 2 * N), complex)
    load[0, :N] = model.side
    load[1] = np.concatenate((model.eccentric, -1j * model.eccentric))  # (cos, sin) Ωt, as :func:`whirl`
    # the touching points' displacements (y then z) from the modal coordinates, and the modal loads of their forces
    B = np.zeros((2 * held.size, 2 * N))
    B[:held.size, :N], B[held.size:, N:] = model.phi[held], model.phi[held]
    K = 2 * held.size
    receptance, inverse = [], []  # per harmonic: R_h at the touching points, Z_h factorised
    for k in range(H + 1):
        matrix = _dynamic_matrix(model, whirled["stiffness"], whirled["damping"], held, k)
        if k and C is not None:
            matrix = _with_drag(matrix, k * Om, C)
        factor = linalg.lu_factor(matrix, check_finite=False)
        inverse.append(factor)
        receptance.append(B @ linalg.lu_solve(factor, B.T.astype(complex) / model.mass, check_finite=False))
    # the real Fourier basis over the samples: a0, then (Re, Im) of each harmonic:
    # x(θ) = a0 + Σ Re c_h cos hθ − Im c_h sin hθ
    theta = 2 * np.pi * np.arange(M) / M
    E, Ed = np.zeros((M, 2 * H + 1)), np.zeros((M, 2 * H + 1))
    E[:, 0] = 1.0
    for k in range(1, H + 1):
        E[:, 2 * k - 1], E[:, 2 * k] = np.cos(k * theta), -np.sin(k * theta)
        Ed[:, 2 * k - 1], Ed[:, 2 * k] = -k * Om * np.sin(k * theta), -k * Om * np.cos(k * theta)
    W = np.full(2 * H + 1, 2.0 / M)
    W[0] = 1.0 / M
    Rr = np.zeros((2 * H + 1, K, 2 * H + 1, K))  # the receptance on the real coefficients
    Rr[0, :, 0, :] = receptance[0].real
    for k in range(1, H + 1):
        re, im = receptance[k].real, receptance[k].imag
        Rr[2 * k - 1, :, 2 * k - 1, :], Rr[2 * k - 1, :, 2 * k, :] = re, -im
        Rr[2 * k, :, 2 * k - 1, :], Rr[2 * k, :, 2 * k, :] = im, re
    n = (2 * H + 1) * K
    Rr = Rr.reshape(n, n)

    def to_real(X):  # (H+1, ...) complex -> (2H+1, ...) real
        out = np.empty((2 * H + 1,) + X.shape[1:])
        out[0] = X[0].real
        out[1::2], out[2::2] = X[1:].real, X[1:].imag
        return out

    def to_complex(x):
        out = np.empty((H + 1,) + x.shape[1:], complex)
        out[0] = x[0]
        out[1:] = x[1::2] + 1j * x[2::2]
        return out

    def modal(Qh):  # the modal coordinates and velocities at the samples (M, 2N)
        x = to_real(Qh)
        return E @ x, Ed @ x

    def drag_load(v):  # the drag's difference from its viscous equivalent, as a modal load's harmonics (H+1, 2N)
        if not model.drag > 0:
            return np.zeros((H + 1, 2 * N), complex)
        S = model.drag_shapes
        vy, vz = v[:, :N] @ S.T, v[:, N:] @ S.T
        c = model.drag * np.hypot(vy, vz) * model.drag_weights
        exact = -np.concatenate(((c * vy) @ S, (c * vz) @ S), axis=-1) / model.mass
        if C is not None:
            exact += np.concatenate((v[:, :N] @ C.T, v[:, N:] @ C.T), axis=-1)
        return to_complex((W[:, None] * (E.T @ exact)))

    count, wall = held.size, model.clearance[held]

    def assemble(stiff, damp):  # (n, n): per-sample, per-point 2×2 maps (M, P_t, 2, 2) of (E x, Ed x) on the harmonics
        out = np.zeros((2 * H + 1, K, 2 * H + 1, K))
        WE = (W * E).T
        for p in range(count):
            for i in range(2):
                for j in range(2):
                    term = stiff[:, p, i, j, None] * E
                    if damp is not None:
                        term = term + damp[:, p, i, j, None] * Ed
                    out[:, i * count + p, :, j * count + p] = WE @ term
        return out.reshape(n, n)

    def parts(X, jacobian=True):  # U(X) and G(X) (2H+1, K), G the forces less their linearisation; their Jacobians
        if coordinates == "polar":  # X: each point's angle φ then radial approach ρ; u = (c + ρ) n̂(φ)
            x_t, xd_t = E @ X, Ed @ X
            phi, rho, phid, rhod = x_t[:, :count], x_t[:, count:], xd_t[:, :count], xd_t[:, count:]
            r = wall[None] + rho
            nn = np.stack((np.cos(phi), np.sin(phi)), axis=-1)
            tt = np.stack((-nn[..., 1], nn[..., 0]), axis=-1)
            u, v = r[..., None] * nn, rhod[..., None] * nn + (r * phid)[..., None] * tt
            U = W[:, None] * (E.T @ np.concatenate((u[..., 0], u[..., 1]), axis=1))
        else:  # X: the Cartesian displacement harmonics
            u_t, v_t = E @ X, Ed @ X  # (M, K)
            u = np.stack((u_t[:, :count], u_t[:, count:]), axis=-1)  # (M, H_p, 2)
            v = np.stack((v_t[:, :count], v_t[:, count:]), axis=-1)
            U = X
        full_u = np.zeros((M, model.points.size, 2))
        full_v = np.zeros_like(full_u)
        full_u[:, held], full_v[:, held] = u, v
        f, _ = contact_forces(model, full_u, full_v)
        g = f[:, held] + np.einsum("pij,mpj->mpi", K0, u) + np.einsum("pij,mpj->mpi", D0, v)
        G = W[:, None] * (E.T @ np.concatenate((g[..., 0], g[..., 1]), axis=1))
        if not jacobian:
            return U, G
        ku, kv = _force_jacobians(model, full_u, full_v)
        ku, kv = ku[:, held] + K0[None], kv[:, held] + D0[None]
        if coordinates != "polar":  # dG[c, k, d, l] = W_c Σ_t E_tc (ku_t[k, l] E_td + kv_t[k, l] Ed_td)
            return U, G, np.eye(n), assemble(ku, kv)
        Ju = np.stack((r[..., None] * tt, nn), axis=-1)  # ∂u/∂(φ, ρ) = ∂u̇/∂(φ̇, ρ̇)
        Jv = np.stack((rhod[..., None] * tt - (r * phid)[..., None] * nn, phid[..., None] * tt), axis=-1)  # ∂u̇/∂(φ, ρ)
        return U, G, assemble(Ju, None), assemble(ku @ Ju + kv @ Jv, kv @ Ju)

    def respond(loads):  # modal harmonics (H+1, 2N) for modal loads' harmonics
        out = np.empty_like(loads)
        for k in range(H + 1):
            out[k] = linalg.lu_solve(inverse[k], loads[k], check_finite=False)
        return out

    q, v = modal(Q)
    U = to_real(Q @ B.T)  # (2H+1, K) the touching points' displacement harmonics
    if start is None:
        # the start on the wall's arc: the linear motion's swing along the tangent turned into an angle about the hole's
        # axis, its normal part kept (the tangent's straight line takes a stiff Hertz contact deep into the wall)
        u0 = rested["u"][held]
        r0 = np.hypot(u0[:, 0], u0[:, 1])
        n0 = u0 / r0[:, None]
        t0 = np.stack((-n0[:, 1], n0[:, 0]), axis=-1)
        a = B @ whirled["amplitudes"]  # the synchronous motion at the touching points (K,) complex
        first = np.concatenate((u0[:, 0], u0[:, 1]))[None] + E[:, 1:3] @ np.stack((a.real, a.imag))
        ut = np.stack((first[:, :held.size], first[:, held.size:]), axis=-1) - u0[None]  # (M, H_p, 2)
        angle = np.arctan2(n0[:, 1], n0[:, 0])[None] + np.einsum("mpi,pi->mp", ut, t0) / r0[None]
        radius = r0[None] + np.einsum("mpi,pi->mp", ut, n0)
        arc = np.concatenate((radius * np.cos(angle), radius * np.sin(angle)), axis=1)  # (M, K)
        U = W[:, None] * (E.T @ arc)
    # the motion about the rest, at least STILL_MOTION of the rest (with no turning load it is the rest's rounding)
    dynamic = lambda X: max(float(np.max(np.abs(X[1:]))), STILL_MOTION * float(np.max(np.abs(X[0]))), 1e-300)
    X = U
    if coordinates == "polar":  # the start in the wall's coordinates
        if start is not None:
            u_s = E @ U
            angle = np.unwrap(np.arctan2(u_s[:, count:], u_s[:, :count]), axis=0)
            radius = np.hypot(u_s[:, :count], u_s[:, count:])
        X = W[:, None] * (E.T @ np.concatenate((angle, radius - wall[None]), axis=1))
    change, settled, iteration, stalled = np.inf, False, 0, 0
    for iteration in range(1, BALANCE_ITERATIONS + 1):
        extra = load + drag_load(v)
        base = respond(extra)
        U_lin = to_real(base @ B.T)
        U, G, dU, dG = parts(X)
        residual = (U - U_lin).ravel() - Rr @ G.ravel()
        step = np.linalg.solve(dU - Rr @ dG, -residual).reshape(X.shape)
        # damped: the step halved while it does not lower the residual (a swing large beside the wall's curvature
        # takes the full step off the wall circle)
        size, alpha = float(np.linalg.norm(residual)), 1.0
        while alpha > 1e-3:
            U_try, G_try = parts(X + alpha * step, jacobian=False)
            trial = (U_try - U_lin).ravel() - Rr @ G_try.ravel()
            if float(np.linalg.norm(trial)) <= (1 - 1e-4 * alpha) * size or size == 0.0:
                break
            alpha *= 0.5
        else:  # no step lowered it: the smallest, with its own forces (the last tried were twice its step's)
            _, G_try = parts(X + alpha * step, jacobian=False)
        X = X + alpha * step
        G = G_try
        # stalled: the step cut below BALANCE_STALLED in BALANCE_STALLS iterations running (:func:`refine`)
        stalled = stalled + 1 if alpha < BALANCE_STALLED else 0
        new = base + respond(to_complex(G) @ B / model.mass)
        change = float(np.max(np.abs(new - Q)) / dynamic(new))
        Q = new
        q, v = modal(Q)
        if not np.isfinite(change):
            break
        if change < BALANCE_SETTLED:
            settled = True
            break
        if stalled >= BALANCE_STALLS:
            break
    return dict(harmonics=Q, iterations=iteration, change=change, settled=settled)


#: The unknowns of :func:`balance` at the touching points: displacements in y and z, or angle along the wall and
#: approach.
BALANCE_COORDINATES = ("cartesian", "polar")


def balanced_revolution(model: reference.WhirlModel, balanced: dict[str, Any],
                        samples: int = SAMPLES) -> reference.Window:
    """One revolution of the harmonic balance's motion (:func:`balance`) as the reference model's
    :class:`~study.solvers.methods.reference.Window`, its contact forces from the exact law on it."""
    N, P, Om = model.n_modes, model.points.size, model.rotary_speed
    Q = balanced["harmonics"]
    t = np.linspace(0.0, model.period, samples + 1)
    e = np.exp(1j * Om * np.outer(t, np.arange(Q.shape[0])))  # (R, H+1)
    q = (e @ Q).real
    v = (e @ (Q * (1j * Om * np.arange(Q.shape[0]))[:, None])).real
    u = np.stack((q[:, :N] @ model.phi.T, q[:, N:] @ model.phi.T), axis=-1)
    ud = np.stack((v[:, :N] @ model.phi.T, v[:, N:] @ model.phi.T), axis=-1)
    forces, fn = contact_forces(model, u, ud)
    peak = np.max(fn, axis=0)
    touching = np.all(fn > 0, axis=0)
    states = np.zeros((t.size, 4 * N + 4))
    states[:, :2 * N], states[:, 2 * N:4 * N] = q, v
    return reference.Window(times=t, states=states, forces=np.concatenate((forces, fn[..., None]), axis=-1),
                            peak=peak, onsets=np.zeros(P, np.int64),
                            contact_time=np.where(touching, model.period, 0.0),
                            any_contact_time=model.period if np.any(fn > 0) else 0.0, start=0.0, end=model.period)


#: Modes per direction of the answer, and of the coarser solution its truncation error is measured against.
MODES, COARSE_MODES = 48, 24
#: The figures whose change with the modes is the truncation error.
FIGURES = ("peak_contact_force", "max_normal_stress", "alternating_bending_stress")


def steady_state(inputs: Mapping[str, Any], modes: int = MODES, contact_scale: float = 1.0,
                 drag_rule: str = "dissipation", like: Mapping[str, Any] | None = None) -> dict[str, Any]:
    """The state on the wall with ``modes`` modes per direction: the model, the rest, the contacts' linearisation
    about it, the whirl (``contact_scale`` and ``drag_rule`` as :func:`whirl`), one revolution and its sizes
    (:func:`revolution`) and, when the state is not this method's, ``why`` (text). ``like``: a state of the same
    inputs and modes on the wall, whose model, rest and linearisation this one shares (they do not depend on
    ``contact_scale`` or ``drag_rule``)."""
    if like is not None:
        model, rested, linear = like["model"], like["rest"], like["linear"]
        out = dict(model=model, rest=rested, linear=linear, why=None)
    else:
        model = reference.build_model({**inputs, "reference_modes": modes})
        out = dict(model=model, why=None)
        if not np.all(np.isfinite(model.omega)) or np.any(model.omega[model.wavenumber > 0] <= 0):
            out["why"] = "buckled"
            return out
        rested = out["rest"] = rest(model)
        if not rested["found"]:
            out["why"] = "no equilibrium on the wall was found (the touching set did not settle)"
            return out
        if not np.any(rested["touching"]):
            out["why"] = "the section at rest does not reach the wall (the free whirl's case)"
            return out
        linear = out["linear"] = _linearised(model, rested["u"])
    whirled = out["whirl"] = whirl(model, rested, contact_scale, drag_rule, linear)
    window, out["sizes"] = revolution(model, rested, whirled)
    out["window"] = window
    N = model.n_modes
    reach = np.hypot(window.states[:, :N] @ model.phi.T, window.states[:, N:2 * N] @ model.phi.T)
    held = rested["touching"]
    lifts = held & (np.min(window.forces[:, :, 2], axis=0) <= 0)
    strikes = (~held) & (np.max(reach, axis=0) >= model.clearance)
    if np.any(lifts):
        out["why"] = ("the contact would open during the revolution at "
                      + ", ".join(f"{x:.3g} m" for x in model.points[lifts])
                      + " (the turning eccentric load beats the weight on the wall): the pipe bounces")
    elif np.any(strikes):
        out["why"] = ("a point off the wall would reach it during the revolution at "
                      + ", ".join(f"{x:.3g} m" for x in model.points[strikes]))
    return out


#: The lift-off eccentricity's secant iteration (:func:`lift_off_eccentricity`): states solved at most, and the
#: relative change of the eccentricity that ends it.
LIFT_ITERATIONS, LIFT_SETTLED = 8, 1e-3
#: The drag iteration's relative change that ends it in the lift-off's states (far below :data:`LIFT_SETTLED`).
LIFT_DRAG_SETTLED = 1e-7
#: The eccentricity [m] the lift-off is first sought at where the point's own is nil (0.1 in).
LIFT_TRIAL = 0.1 * 0.0254


def _least_force(state: Mapping[str, Any]) -> float:
    """The smallest normal force over the revolution at the points touching at rest, over each one's force at rest
    [-]: 1 at ε = 0, 0 where the contact opens (:func:`steady_state`'s window)."""
    held = state["rest"]["touching"]
    fn = state["window"].forces[:, held, 2]
    return float(np.min(np.min(fn, axis=0) / state["rest"]["normal"][held]))


def lift_off_eccentricity(inputs: Mapping[str, Any], state: Mapping[str, Any] | None = None) -> float:
    """The mass eccentricity ε_lift [m] at which the point's joints lift off the wall: the smallest ε at which the
    sliding state's normal force at a point touching at rest falls to nil during the revolution (the contact opens,
    the pipe bounces; docs/reference_model.md §7, §10). The rest does not depend on ε and the turning load is linear in
    it, so the swing of a joint's force is nearly so: ε_lift ≈ ε F_rest/(F_rest − min F_n), the joint's force at rest
    over its fall at the point's ε; the drag made viscous by equal dissipation and the arc's second order (both
    growing with the motion) are kept by a secant iteration on the least force (:data:`LIFT_ITERATIONS`, to
    :data:`LIFT_SETTLED`), each step the whirl about the same rest with the eccentric load scaled. Slowly turning it is
    the balance of a joint's forces, share · m_p ε Ω² s = F_rest (:func:`study.physics.whirl.lift_off_speed`
    inverted); near the spans' modes on the joints the dynamics lower it.

    NaN where no side load lays the string on the wall (nothing touches at rest: a vertical straight hole), where
    the section buckles or no rest on the wall is found; inf where the turning load does not lower the force (the
    two spans' loads cancel at every joint: a 180° turn). Slowly turning it may exceed any real eccentricity (inches
    at 30 rpm): nothing a pipe has lifts the joints there.
    ``state``: :func:`steady_state` of these inputs, where already solved."""
    state = steady_state(inputs) if state is None else state
    if state.get("rest") is None or state["why"] in ("buckled",) or not np.any(state["rest"]["touching"]):
        return float("nan")
    if "window" not in state:  # the rest was found, the whirl not solved (not this function's caller)
        return float("nan")
    model, rested, linear = state["model"], state["rest"], state["linear"]
    base = model.eccentricity
    if not base > 0:
        model = reference.build_model({**inputs, "reference_modes": model.n_modes, "eccentricity": LIFT_TRIAL})
        base = model.eccentricity

    # the whirl at the last ε solved, whose amplitudes scaled to the next ε start its drag iteration there (the
    # motion is linear in ε but for the drag's and the arc's growth)
    last = {"eps": base, "amplitudes": state["whirl"]["amplitudes"] if state["model"].eccentricity > 0 else None}

    def least(eps: float) -> float:
        scaled = dataclasses.replace(model, eccentric=model.eccentric * (eps / base), eccentricity=eps)
        start = None if last["amplitudes"] is None else last["amplitudes"] * (eps / last["eps"])
        whirled = whirl(scaled, rested, linear=linear, start=start, settled=LIFT_DRAG_SETTLED)
        last.update(eps=eps, amplitudes=whirled["amplitudes"])
        window, _ = revolution(scaled, rested, whirled)
        return _least_force(dict(rest=rested, window=window))

    # the least force h(ε) from h(0) = 1 (the rest), its slope there (:func:`least_force_slope`: the drag's and the
    # arc's parts grow as ε², so h = 1 + h'(0) ε + O(ε²)) and the point's own ε (or the trial's): the root of the
    # polynomial with that value and slope at 0 through the last two values (docs/reference_model.md §10: 41 whirls
    # against the parabola's 48 over 20 points), the secant where it has none
    e0, h0 = 0.0, 1.0
    e1 = base
    h1 = _least_force(state) if state["model"].eccentricity > 0 else least(e1)
    if not h1 < h0:  # the turning load does not lower the force
        return float("inf")
    known = [(e0, h0), (e1, h1)]
    slope = least_force_slope(model, rested, linear,
                              _dynamic_matrix(model, *linear, np.flatnonzero(rested["touching"]), 1)) / base
    for _ in range(LIFT_ITERATIONS):
        (e0, h0), (e1, h1) = known[-2:]
        e2 = e1 + h1 * (e1 - e0) / (h0 - h1) if h0 != h1 else e1
        curve = polynomial_root(known[:1] + known[-2:] if len(known) > 3 else known, e2, slope if slope < 0 else None)
        e2 = curve if curve is not None else e2
        if not (np.isfinite(e2) and e2 > 0):
            break
        if abs(e2 - e1) <= LIFT_SETTLED * e2:
            return float(e2)
        known.append((e2, least(e2)))
    return float(known[-1][0])


def add_lift_off(result: PointResult, inputs: Mapping[str, Any]) -> PointResult:
    """``result`` with ``lift_off_eccentricity`` (:func:`lift_off_eccentricity`) in its values where it is not there
    yet (unchanged otherwise): :func:`study.solvers.solve_point` adds it to the results of the methods whose scene is
    this one's, the reference model's (:data:`study.solvers.LIFT_OFF_METHODS`). Where the result carries the model its
    run started from on the wall (``result.rest_model``: the reference model's, whose rest :func:`rest` kept in its
    cache) with at least :data:`MODES` modes per direction, the lift-off is computed on that model about that rest
    (:func:`on_rest`), nothing solved twice; the field is emptied here (the model is not an output)."""
    given, result.rest_model = result.rest_model, None
    if "lift_off_eccentricity" not in result.values:
        # on the run's model where it has at least this method's modes (its lift-off at least as accurate: at 16 and
        # 32 modes it was 1.2-3.8 % and 0.1-0.35 % off the 48 modes' at two points of the default study, at 64 modes
        # 0.03-0.09 %, docs/reference_model.md §10); else from the inputs, on MODES modes
        state = on_rest(inputs, given) if given is not None and given.n_modes >= MODES else None
        result.values["lift_off_eccentricity"] = lift_off_eccentricity(inputs, state)
    return result


def on_rest(inputs: Mapping[str, Any], model: reference.WhirlModel) -> dict[str, Any] | None:
    """The state on the wall of :func:`steady_state` on ``model`` about the rest its cache holds (:func:`rest`, solved
    as a run started from it): what :func:`lift_off_eccentricity` needs, without building the model or solving the
    rest again. Without a window where nothing touches at rest or no rest was found (the lift-off is then NaN); None
    where the cache holds no rest or the point's eccentricity is nil (the lift-off is then sought from the inputs:
    :func:`lift_off_eccentricity` builds a model with a trial one)."""
    rested = model.cache.get("sliding_rest")
    if rested is None or not model.eccentricity > 0:
        return None
    if not rested["found"] or not np.any(rested["touching"]):
        return dict(model=model, rest=rested, why=None)
    return steady_state(inputs, like=dict(model=model, rest=rested, linear=_linearised(model, rested["u"])))


def values(inputs: Mapping[str, Any], states: list[Mapping[str, Any]]) -> list[dict[str, float]]:
    """The reference model's outputs (its own functions) on the revolution of each of ``states``, in order. The
    states of one model with the same quasi-static correction have their stresses from one call on their
    revolutions one after the other (``reference.stresses``' segments: the fields computed once for all)."""
    out: list[dict[str, float] | None] = [None] * len(states)
    groups: dict[tuple[int, bool], list[int]] = {}
    for i, state in enumerate(states):
        model, window = state["model"], state["window"]
        groups.setdefault((id(model), reference.quasi_static_applies(model, window)), []).append(i)
    for (_, correction), members in groups.items():
        model = states[members[0]]["model"]
        windows = [states[i]["window"] for i in members]
        rows = np.cumsum([0] + [w.times.size for w in windows])
        stressed = reference.stresses(inputs, model, reference.merge(windows), correction=correction,
                                      segments=list(zip(rows[:-1], rows[1:])))
        for i, window, vals in zip(members, windows, stressed):
            measure = reference.whirl_measure(model, window)
            spacing, _ = reference.contact_spacing(model, window)
            vals.update(peak_contact_force=float(np.max(window.peak)), impacts_per_revolution=0.0,
                        contact_fraction=1.0, whirl_frequency_ratio=measure["whirl_frequency_ratio"],
                        contact_spacing=spacing, whirl_class=float(reference.WHIRL_CLASSES["sliding"]),
                        regime=float(reference.REGIMES["sliding"]))
            out[i] = vals
    return out


def run(point: DesignPoint) -> PointResult:
    """The sliding state at the typed design point (:data:`study.solvers.METHODS`): :func:`solve` of its inputs, which
    the reference model's builder it shares (:func:`study.solvers.methods.reference.build_model`) takes whole."""
    return solve(point.inputs)


def refine(inputs: Mapping[str, Any], state: Mapping[str, Any]) -> dict[str, Any] | None:
    """The state on the wall of :func:`steady_state` (its model, rest and linear whirl) solved exactly by harmonic
    balance (:func:`balance`, :data:`HARMONICS`), with its outputs (:func:`values`) and its error: the figures' largest
    relative change from :data:`COARSE_HARMONICS` harmonics (``harmonic_error``) plus the last Newton correction.
    Where that does not settle or states more than the study's tolerance, the balance in the wall's coordinates
    (:data:`BALANCE_COORDINATES`, :data:`POLAR_HARMONICS` against the coarser count) where it states less.
    None where the balance does not settle at either count; ``opens`` (why) where the motion is not this method's."""
    found = _refined(inputs, state, "cartesian", HARMONICS, COARSE_HARMONICS)
    if found is None or "opens" in found or found["error"] > study_tolerance(inputs):
        polar = _refined(inputs, state, "polar", *POLAR_HARMONICS)
        if polar is not None and (found is None or "opens" in polar or "opens" in found
                                  or polar["error"] < found["error"]):
            found = polar
    return found


#: Harmonics of the balance in the wall's coordinates (:func:`balance`) and of its coarser solution (at default grid
#: points 40 and 505 the figures with 4 harmonics were 75 % and 59 % off, with 8 1.7 % and 3e-5, with 12 and 16 4e-5).
POLAR_HARMONICS = (16, 12)
def _refined(inputs: Mapping[str, Any], state: Mapping[str, Any], coordinates: str, harmonics: int,
             coarser: int) -> dict[str, Any] | None:
    """:func:`refine` with the balance in ``coordinates`` (:data:`BALANCE_COORDINATES`) at ``harmonics`` against
    ``coarser``."""
    model, rested, whirled = state["model"], state["rest"], state["whirl"]
    with np.errstate(all="ignore"):
        fine = balance(model, rested, whirled, harmonics=harmonics, coordinates=coordinates)
        if not fine["settled"]:
            return None
        coarse = balance(model, rested, whirled, harmonics=coarser, start=fine["harmonics"], coordinates=coordinates)
    windows = [balanced_revolution(model, fine)] + ([balanced_revolution(model, coarse)] if coarse["settled"] else [])
    held = rested["touching"]
    N = model.n_modes
    for k, window in enumerate(windows):
        reach = np.hypot(window.states[:, :N] @ model.phi.T, window.states[:, N:2 * N] @ model.phi.T)
        opens, strikes = (np.min(window.forces[:, :, 2], axis=0) <= 0) & held, (np.max(reach, axis=0)
                                                                                  >= model.clearance) & ~held
        if np.any(opens) or np.any(strikes):
            if k or coordinates == "cartesian":  # the coarser motion's, or the Cartesian one's (as before): no answer
                return None
            where = ", ".join(f"{x:.3g} m" for x in model.points[opens | strikes])
            how = (f"during the revolution at {where} by harmonic balance in the wall's coordinates "
                   f"({harmonics} harmonics)")
            return dict(opens=f"the contact opens {how}: the pipe bounces" if np.any(opens) else
                        f"a point off the wall reaches it {how}")
    if not coarse["settled"]:
        return None
    tested = None
    if coordinates == "polar":  # the joints' largest angle along the wall from their rest; beyond STABILITY_SWING
        u, at_rest = windows[0].states[:, :2 * N].reshape(-1, 2, N) @ model.phi[held].T, rested["u"][held]
        turned = np.unwrap(np.arctan2(u[:, 1], u[:, 0]), axis=0) - np.arctan2(at_rest[:, 1], at_rest[:, 0])[None]
        swing = float(np.max(np.abs(turned)))
        if swing > STABILITY_SWING:  # the motion's stability by the reference model's run kicked off it
            tested = dict(stability(model, windows[0]), swing=swing)
            if not tested["stable"]:
                left = (f"a contact opened in revolution {tested['opened']}" if tested["opened"] else
                        f"the kick grew {tested['growth']:.3g}-fold a revolution")
                return dict(opens=f"the joints swing {swing:.2g} rad along the wall by harmonic balance in the wall's "
                                  f"coordinates, and that motion is unstable: the reference model started on it with "
                                  f"its velocities {STABILITY_KICK:.0%} off left it ({left}): the pipe bounces",
                            stability=tested)
    mine, other = values(inputs, [{**state, "window": w} for w in windows])
    harmonic = max(abs(other[k] - mine[k]) / max(abs(mine[k]), 1e-300) for k in FIGURES)
    return dict(values=mine, window=windows[0], error=float(harmonic + fine["change"]), harmonic_error=float(harmonic),
                iterations=fine["iterations"], change=float(fine["change"]), harmonics=harmonics, coarser=coarser,
                coordinates=coordinates, stability=tested)


def solve(inputs: Mapping[str, Any]) -> PointResult:
    """The pipe lying on the wall, sliding (module docstring), or ``out_of_scope`` where that is not the state."""
    result = PointResult(method=METHOD)
    state = steady_state(inputs)
    model = state["model"]
    vals = result.values
    vals.update(model.props)
    vals.update(span_length=model.span, clearance=float(np.max(model.clearance)), eccentricity=model.eccentricity,
                first_natural_frequency=model.omega[0] / (2 * np.pi) if np.isfinite(model.omega[0]) else np.nan,
                lift_off_eccentricity=lift_off_eccentricity(inputs, state))

    def finish(status: str, message: str) -> PointResult:
        result.status, result.message = status, message
        if status == "ok":
            second_motion(result, model, force_tolerance(inputs))
        return result

    if state["why"] == "buckled":
        return finish("buckled", f"effective tension {model.props['effective_tension']:.4g} N buckles the "
                                 f"{model.span:.4g} m section")
    if state["why"]:
        return finish("out_of_scope", f"{state['why']}: a higher model answers")
    # the same state solved another way: with half the modes (the truncation), with the Hertz secant stiffness over
    # the approach's swing instead of the tangent one and with the drag made viscous at the mean speed instead of by
    # equal dissipation (the linearisation); each part of the error is the largest relative change of a figure
    sizes = state["sizes"]
    variants = {"truncation": (dict(modes=COARSE_MODES), f"with {COARSE_MODES} modes per direction",
                               ": the state is not resolved, a higher model answers"),
                "contact": (dict(contact_scale=sizes["secant_ratio"], like=state), "with the Hertz secant stiffness",
                            ": a higher model answers"),
                "drag": (dict(drag_rule="mean_speed", like=state), "with the drag made viscous at the mean speed",
                         ": a higher model answers")}
    others = {}
    for name, (options, how, consequence) in variants.items():
        other = others[name] = steady_state(inputs, **options)
        if other["why"]:
            vals.update(values(inputs, [state])[0])  # the answer's outputs, stated beside why it is not one
            return finish("out_of_scope", f"{how} {other['why']}{consequence}")
    mine, *changed = values(inputs, [state, *others.values()])
    vals.update(mine)
    part = {name: max(abs(other[k] - vals[k]) / max(abs(vals[k]), 1e-300) for k in FIGURES)
            for name, other in zip(others, changed)}
    truncation, contact_part, drag_part = part["truncation"], part["contact"], part["drag"]
    # the orders left out: the second-order part of the angle's swing on the wall (1 − cos a ≈ a²/2), and the arc's
    # third order, about the angle's swing times the second order's share of the force
    left_out = 0.5 * sizes["angle_swing"] ** 2 + sizes["angle_swing"] * sizes["second_order"]
    linearisation = contact_part + drag_part + left_out
    rested, whirled = state["rest"], state["whirl"]
    result.error_estimate = float(linearisation + truncation + whirled["change"])
    result.extras.update(touching_points=[float(x) for x in model.points[rested["touching"]]],
                         rest_normal_force=[float(v) for v in rested["normal"]], drag_iterations=whirled["iterations"],
                         linearisation_error=linearisation, contact_linearisation=contact_part,
                         drag_linearisation=drag_part, truncation_error=truncation,
                         contact_points=[float(v) for v in model.points], reference_modes=model.n_modes)
    where = ", ".join(f"{x:.3g} m" for x in model.points[rested["touching"]])
    lying = f"lying on the wall at {where}, sliding: {float(np.max(rested['normal'])):.4g} N at rest, "
    if result.error_estimate > study_tolerance(inputs):
        # the linear answer is not good to the tolerance: the exact periodic state by harmonic balance, where it
        # settles and states a smaller error (the linear answer and its estimate are kept otherwise)
        fine = refine(inputs, state)
        if fine is not None and "opens" in fine:  # the exact periodic state is not this one: a higher model answers
            vals.update(values(inputs, [state])[0])  # the linear answer's outputs, stated beside why it is not one
            result.error_estimate = None
            return finish("out_of_scope", f"{lying}linearisation {linearisation:.2g}; {fine['opens']}: a higher "
                                          f"model answers")
        if fine is not None and fine["error"] + truncation < result.error_estimate:
            vals.update(fine["values"])
            result.error_estimate = float(fine["error"] + truncation)
            result.extras.update(harmonic_balance=dict(harmonics=fine["harmonics"], iterations=fine["iterations"],
                                                       change=fine["change"], harmonic_error=fine["harmonic_error"],
                                                       linear_estimate=float(linearisation + truncation
                                                                             + whirled["change"])),
                                 linearisation_error=0.0)
            fn = fine["window"].forces[:, :, 2]
            swing = float(np.max(np.max(fn, axis=0) - np.min(fn, axis=0)) / 2)
            where_on = " in the wall's coordinates" if fine["coordinates"] == "polar" else ""
            if fine.get("stability"):  # tested stable (:func:`stability`)
                tested = fine["stability"]
                result.extras["stability"] = tested
                where_on += (f" (the joints swing {tested['swing']:.2g} rad; stable: the reference model kicked off it "
                             f"by {STABILITY_KICK:.0%} came back, {tested['growth']:.3g}-fold a revolution over "
                             f"{tested['revolutions']} revolutions)")
            return finish("ok", f"{lying}±{swing:.3g} N as the eccentric load turns; harmonic balance of the exact "
                                f"contact and drag{where_on} in {fine['iterations']} iterations (the linearisation's "
                                f"{linearisation:.2g} removed), {fine['harmonics']} against {fine['coarser']} "
                                f"harmonics {fine['harmonic_error']:.2g}, {model.n_modes} against {COARSE_MODES} modes "
                                f"{truncation:.2g} (on the linear state)")
    fn = state["window"].forces[:, :, 2]
    swing = float(np.max(np.max(fn, axis=0) - np.min(fn, axis=0)) / 2)
    message = (f"{lying}±{swing:.3g} N as the eccentric load turns; linearisation {linearisation:.2g} (contact "
               f"{contact_part:.2g}, drag {drag_part:.2g}, orders left out {left_out:.2g}), "
               f"{model.n_modes} against {COARSE_MODES} modes {truncation:.2g}, drag settled in "
               f"{whirled['iterations']} iterations")
    # this is the state: above the study's tolerance the gate calls the answer not_converged, its values kept
    return finish("ok", message)
