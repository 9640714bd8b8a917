"""The reference model's outputs over a window: the section's bending fields with the static correction of the
modes left out, the wall excess between the contact points, the modal accelerations and the joints' inertia
forces, the stresses, the contacts' spacing and the energy balance."""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np

from study.physics import section
from study.solvers.kernels import stress_kernel
from study.solvers.methods.reference.integrate import Window
from study.solvers.methods.reference.model import WhirlModel, eccentric_parts, static_correction
from study.physics.string_modes import mode_shapes
from study.solvers.model.point import DesignPoint


def modal_fields(model: WhirlModel, q: np.ndarray, x: np.ndarray) -> np.ndarray:
    """(T, 2X) the kept modes' deflection [m] and moment −EI u'' [N m] (without the hole's curvature) on the stations
    x [m] of one direction from the modal states q (T, N): the modal part of :func:`periodic_fields`, which the
    stresses with and without the quasi-static correction share (:func:`stresses`)."""
    x = np.asarray(x, float)
    base = mode_shapes(x, model.span, model.modes)
    moments = base * (model.props["bending_stiffness"] * model.wavenumber**2)  # each mode's −EI ψ''
    if model.basis is not None:
        base, moments = base @ model.basis, moments @ model.basis
    return q @ np.vstack([base, moments]).T


def periodic_fields(model: WhirlModel, q: np.ndarray | None, forces: np.ndarray | None, x: np.ndarray,
                    direction: int | None = None, modal: np.ndarray | None = None) -> dict:
    """Deflection [m] and moment −EI u'' [N m] on the stations x [m] (shape times × x) of one direction from the
    modal states q (T, N) (ψ_n'' = −k_n² ψ_n: mode n's moment is EI k_n² ψ_n q_n, none for the rigid translation),
    plus with ``forces`` (T, P) on the pipe the quasi-static correction for the modes left out
    (:func:`static_correction`). With ``direction`` (0 y, 1 z) the moment is the pipe's whole, −EI (κ + u''), κ the
    hole's curvature in that direction (the pipe follows the curved hole). ``modal``: :func:`modal_fields` of q and x
    where computed already (q then unused: None)."""
    x = np.asarray(x, float)
    both = modal_fields(model, q, x) if modal is None else modal
    if forces is not None:
        if direction == 0 and model.point_side is not None:
            forces = forces + model.point_side  # the joints' weight at the joints: a point load as the contacts'
        both = both + forces @ static_correction(model, x)
    moment = both[:, x.size:]
    if direction is not None and model.hole_curvature[direction] != 0.0:
        # the pipe follows the hole: its curvature is the hole's κ⃗ plus its own u'', M = −EI (κ⃗ + u'')
        moment = moment - model.props["bending_stiffness"] * model.hole_curvature[direction]
    return {"deflection": both[:, :x.size], "moment": moment}


def body_wall_excess(model: WhirlModel, x: np.ndarray, uy: np.ndarray, uz: np.ndarray, normal: np.ndarray,
                     largest_moment: float) -> tuple[float, float]:
    """How far the pipe body passes its wall beyond the Hertz approach of its contacts, anywhere along it
    (docs/reference_model.md §2): the largest over the rows (times) and the stations x [m] (X,) of
    |u(x, t)| − c_b − α(x, t), with u = (``uy``, ``uz``) (T, X) [m], c_b the body's clearance and α the Hertz
    approach (F_n/K)^{2/3} of the body's contact points at that row (``normal`` (T, P) [N]), linear between
    neighbouring ones along the periodic string (a contact's own at its station); plus the bound of what lies
    between the stations, h²/8 max|u''| (h the widest gap between stations; the linear interpolant of the vector
    u errs by at most that, and |u| of the interpolant is at most its ends' by convexity), with |u''| ≤ (|M| + EI
    |κ⃗|)/EI from the largest moment ``largest_moment`` [N m] (the hole's curvature κ⃗ is in the moment, not in u).
    Returns (excess [m], the bound in it [m]); a negative excess: clear of the wall everywhere. NaN without body
    stations of contact kind in the model (no body clearance to hold it to)."""
    rows = row_wall_excess(model, x, uy, uz, normal)
    bound = wall_excess_bound(model, x, largest_moment)
    return (float(np.max(rows)) + bound if rows.size else float("nan")), bound


def row_wall_excess(model: WhirlModel, x: np.ndarray, uy: np.ndarray, uz: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """(T,) each row's largest |u(x, t)| − c_b − α(x, t) over the stations x [m] (:func:`body_wall_excess`, without
    the bound between the stations); NaN without body contact points."""
    body = model.kinds == 0
    if not np.any(body):
        return np.full(uy.shape[0], np.nan)
    clearance = float(np.max(model.clearance[body]))
    at = model.points[body]
    if model.law == 0:
        alpha = (np.maximum(normal[:, body], 0.0) / model.stiffness[body]) ** (2.0 / 3.0)
    else:
        alpha = np.maximum(normal[:, body], 0.0) / model.penalty_stiffness[body]
    # the linear interpolation between the body's contact points along the periodic string, as a matrix (X, Pb),
    # cached on the model per stations
    key = ("wall", np.asarray(x, float).tobytes())
    weights = model.cache.get(key)
    if weights is None:
        order = np.argsort(at)
        ext = np.concatenate((at[order][-1:] - model.span, at[order], at[order][:1] + model.span))
        weights = np.zeros((x.size, at.size))
        j = np.clip(np.searchsorted(ext, x, side="right") - 1, 0, ext.size - 2)
        share = (x - ext[j]) / (ext[j + 1] - ext[j])
        cols = np.concatenate((order[-1:], order, order[:1]))
        np.add.at(weights, (np.arange(x.size), cols[j]), 1.0 - share)
        np.add.at(weights, (np.arange(x.size), cols[j + 1]), share)
        model.cache[key] = weights
    return np.max(np.hypot(uy, uz) - clearance - alpha @ weights.T, axis=1)


def wall_excess_bound(model: WhirlModel, x: np.ndarray, largest_moment: float) -> float:
    """h²/8 max|u''| [m], h the widest gap between the stations x [m], |u''| ≤ (|M| + EI |κ⃗|)/EI with the largest
    moment ``largest_moment`` [N m] (:func:`body_wall_excess`)."""
    ei = model.props["bending_stiffness"]
    h = float(np.max(np.diff(x))) if x.size > 1 else 0.0
    return h * h / 8.0 * (float(largest_moment) + ei * float(np.hypot(*model.hole_curvature))) / ei


#: The most rows :func:`modal_accelerations` takes at once: its temporaries (the drag's speeds at its 2N + 8 points,
#: three arrays of rows × points) for a window grown to a few hundred revolutions were GiBs.
ACCELERATION_ROWS = 2**15


def modal_accelerations(model: WhirlModel, window: Window, shapes: np.ndarray | None = None) -> np.ndarray:
    """(T, 2N) q̈ of the recorded rows (y then z modes) from the modal equations (module docstring of
    :mod:`study.solvers.kernels.whirl_kernel`) with the recorded contact forces: the modes' stiffness and linear
    damping, the turning eccentric load, the side load, the quadratic drag and the contacts. With ``shapes`` (N, K) the
    accelerations Σ_n q̈_n shapes_nk at K points instead, (T, 2K) (y then z). Each row's its own: taken
    :data:`ACCELERATION_ROWS` rows at a time."""
    N = model.n_modes
    rows = window.times.size
    out = np.empty((rows, 2 * (N if shapes is None else shapes.shape[1])))
    for first in range(0, rows, ACCELERATION_ROWS):
        part = slice(first, min(first + ACCELERATION_ROWS, rows))
        out[part] = _modal_accelerations(model, window.states[part], window.times[part], window.forces[part], shapes)
    return out


def _modal_accelerations(model: WhirlModel, z: np.ndarray, times: np.ndarray, forces: np.ndarray,
                         shapes: np.ndarray | None) -> np.ndarray:
    """:func:`modal_accelerations` of the rows of states ``z``, ``times`` and contact ``forces``."""
    N = model.n_modes
    qy, qz, vy, vz = z[:, :N], z[:, N:2 * N], z[:, 2 * N:3 * N], z[:, 3 * N:4 * N]
    turn = model.rotary_speed * times[:, None]
    w2 = model.omega**2
    ea, eb = eccentric_parts(model)
    # the modal loads, projected on the shapes where given (the modes themselves need no product with the identity)
    own = (lambda a: a @ shapes) if shapes is not None else (lambda a: a)
    cos, sin = np.cos(turn), np.sin(turn)
    ay = own(-w2 * qy - model.damping * vy + model.side) + cos * own(ea) - sin * own(eb)
    az = own(-w2 * qz - model.damping * vz) + sin * own(ea) + cos * own(eb)
    if model.drag > 0.0:
        S, wts = model.drag_shapes, model.drag_weights
        uy, uz = vy @ S.T, vz @ S.T
        # the speed as the integrator's kernel takes it (whirl_kernel's drag, √(u_y² + u_z²)); np.hypot, correctly
        # rounded, took 40 % of this function at 64 modes
        c = model.drag * np.sqrt(uy * uy + uz * uz) * wts
        projected = own(S) / model.mass
        ay -= (c * uy) @ projected
        az -= (c * uz) @ projected
    at = own(model.phi) / model.mass
    ay += forces[:, :, 0] @ at
    az += forces[:, :, 1] @ at
    return np.hstack([ay, az])


def above_band(model: WhirlModel) -> np.ndarray:
    """(N,) which kept modes lie above the stresses' band, ω_n > ω_b (``reference_stress_band``,
    :attr:`WhirlModel.stress_band`; none with "all")."""
    return np.asarray(model.omega[:model.n_modes], float) > model.stress_band


def field_states(model: WhirlModel, window: Window, direction: int, masked: np.ndarray | None = None) -> np.ndarray:
    """(T, N) the modal coordinates the fields take in one direction (0 y, 1 z): each kept mode's own q_n within the
    stresses' band, and above it (:func:`above_band`) its quasi-static response to its loads, L_n/ω_n² (the
    mode-acceleration method, as the modes left out take theirs, docs/reference_model.md §3), with
    L_n = q̈_n + d_n q̇_n + ω_n² q_n [m/s²] the load per modal mass its equation has at the row (the contact forces,
    the eccentric and side loads, the drag: :func:`modal_accelerations`), less the ``masked`` (T, P) contact forces
    (the strikes whose local bending is added instead, statistics.strike_stress_values). Without masked loads computed
    once per window and model (:func:`window_memo`): do not write into it."""
    N = model.n_modes
    above = above_band(model)
    if not np.any(above):
        return window.states[:, direction * N:(direction + 1) * N]
    if masked is None:
        return window_memo(window, model, ("band", direction), lambda: _field_states(model, window, direction, None))
    return _field_states(model, window, direction, masked)


def _field_states(model: WhirlModel, window: Window, direction: int, masked: np.ndarray | None) -> np.ndarray:
    N = model.n_modes
    above = above_band(model)
    q = window.states[:, direction * N:(direction + 1) * N]
    v = window.states[:, (2 + direction) * N:(3 + direction) * N]
    w2 = model.omega[:N][above] ** 2
    acc = window_memo(window, model, ("accelerations",), lambda: modal_accelerations(model, window))
    loads = acc[:, direction * N:(direction + 1) * N][:, above] + model.damping[above] * v[:, above] + w2 * q[:, above]
    if masked is not None:
        loads = loads - np.where(masked, window.forces[:, :, direction], 0.0) @ model.phi[:, above] / model.mass
    out = q.copy()
    out[:, above] = loads / w2
    return out


def window_memo(window: Window, model: WhirlModel, key: tuple, compute):
    """What ``compute()`` gives for the window and model under ``key``, computed once per window (kept in
    ``window.memo``, with the model it was computed for): the post-processing paths of a window (the stresses with
    and without the correction, the strikes' stations, the modal check) share its fields instead of recomputing them
    (docs/reference_model.md §6)."""
    full = (id(model),) + key
    hit = window.memo.get(full)
    if hit is None or hit[0] is not model:
        hit = window.memo[full] = (model, compute())
    return hit[1]


def joint_inertia_forces(model: WhirlModel, window: Window) -> np.ndarray:
    """(T, P, 2) the inertia forces −m_j ü(x_j) [N] of the tool joints' lumped mass on the pipe at the contact points
    that are joints (zero elsewhere), from :func:`modal_accelerations`: point loads whose part on the modes left out
    the quasi-static correction completes (:func:`periodic_fields`; docs/reference_model.md §3); ü of the modes
    within the stresses' band (:func:`above_band`), those above it being quasi-static. Computed once per window and
    model (:func:`window_memo`): do not write into it."""
    return window_memo(window, model, ("inertia",), lambda: _joint_inertia_forces(model, window))


def _joint_inertia_forces(model: WhirlModel, window: Window) -> np.ndarray:
    at = model.joint_points
    J = int(np.count_nonzero(at))
    # the in-band modes' accelerations at the joints: those above the band are quasi-static (field_states)
    shapes = model.phi[at].T * ~above_band(model)[:, None]
    if np.any(above_band(model)):  # the modes' own accelerations are computed for field_states anyway: projected
        N = model.n_modes
        modal = window_memo(window, model, ("accelerations",), lambda: modal_accelerations(model, window))
        acc = np.hstack([modal[:, :N] @ shapes, modal[:, N:] @ shapes])
    else:
        acc = modal_accelerations(model, window, shapes)  # at the joints
    out = np.zeros(window.forces.shape[:2] + (2,))
    for j in range(2):
        out[:, at, j] = -model.joint_mass * acc[:, j * J:(j + 1) * J]
    return out


def stresses(point: DesignPoint | Mapping[str, Any], model: WhirlModel, window: Window, space_points: int = 97,
             fibres: int = 16, correction: bool = True, segments: list[tuple[int, int]] | None = None,
             masked: np.ndarray | None = None):
    """Bending, normal and shear stresses over the window (the paper's §5 stresses in two directions;
    docs/reference_model.md §3).

    Moments M_y, M_z (−EI (κ_y + y''), −EI (κ_z + z'')) from :func:`periodic_fields` in each direction
    (the modes, plus with ``correction`` the quasi-static correction for the contact forces: the static response
    of the modes left out, whose flexibility the contacts have in series, :func:`residual_flexibility`; what the
    modes above N do beyond it is in :func:`modal_check`); bending stress |M| r_o/I; the
    alternating stress is half the range, over the window, of the stress of one fibre of the turning
    pipe, (M_y cos(Ωt + ψ) + M_z sin(Ωt + ψ)) r_o/I, at the worst fibre ψ and section; shear force
    dM/dx (the −EI y''' part, by differences of the corrected moment), shear stress 2|V|/A_s.

    With ``segments`` (row ranges [start, stop) of the recording), a list of those values per segment, times
    from each segment's first row (the fields computed once for all). ``modal_quarter_fraction``: the share of
    the modes N/4 … N/2 in the largest moment, beside ``modal_tail_fraction``'s of N/2 … N (truncation indicators).
    ``masked`` (R, P) the rows and points whose loads (contact and joint inertia forces) the quasi-static correction
    leaves out: the strikes whose local bending is added instead (statistics.strike_stress_values).
    """
    N = model.n_modes
    L = model.span
    x = np.unique(np.concatenate([np.linspace(0.0, L, space_points), model.points]))
    fields = []
    # the joints' inertia forces corrected statically; with the residual vectors too where the fields are recovered from
    # the contact forces (the mode-acceleration method: the modes left out take the contact force and the joints'
    # inertia statically; without the inertia the stresses of replayed strikes were 5-81 % off a 256-mode replay at 128
    # modes, with it 1-5 %, docs/reference_model.md §2.1), not where from the vectors' coordinates (their
    # coupling with the joints' mass is in the motion)
    inertia = (joint_inertia_forces(model, window) if correction and model.joint_points is not None
               and (not model.dynamic or model.recovery == "force") else None)
    scene = DesignPoint.of(point).scene  # its inputs typed where the sliding state's parts pass them
    r_o, r_i = scene.outer_radius, scene.inner_radius
    if not correction and masked is None:  # the modes alone: once per window (the modal check reads them too)
        key = ("plain", space_points, fibres, r_o, r_i, scene.axial_tension,
               None if segments is None else tuple((int(a), int(b)) for a, b in segments))
        outs = window_memo(window, model, key, lambda: _stresses(model, window, x, scene, fibres, None, segments))
        return [dict(v) for v in outs] if segments is not None else dict(outs[0])
    for j in range(2):
        forces = window.correction_forces(model, j) if correction else None  # without it, the modes alone
        if inertia is not None:
            forces = forces + inertia[:, :, j]  # the joints' inertia forces, point loads as the contacts'
        if masked is not None and forces is not None:
            forces = np.where(masked, 0.0, forces)
        modal = (modal_fields(model, field_states(model, window, j, masked), x)
                 if masked is not None and np.any(above_band(model)) else shared_modal_fields(model, window, x, j))
        fields.append(periodic_fields(model, None, forces, x, j, modal=modal))
    outs = _stresses(model, window, x, scene, fibres, fields, segments)
    return outs if segments is not None else outs[0]


def shared_modal_fields(model: WhirlModel, window: Window, x: np.ndarray, direction: int) -> np.ndarray:
    """:func:`modal_fields` of the window's states in one direction (0 y, 1 z) on the stations x [m] (the coordinates of
    :func:`field_states`: within the stresses' band), computed once per window, model and stations
    (:func:`window_memo`): do not write into it."""
    x = np.asarray(x, float)
    return window_memo(window, model, ("modal", direction, x.tobytes()),
                       lambda: modal_fields(model, field_states(model, window, direction), x))


def _stresses(model: WhirlModel, window: Window, x: np.ndarray, scene, fibres: int, fields: list | None,
              segments) -> list[dict]:
    """:func:`stresses`' values per segment from the fields of each direction (:func:`periodic_fields`; None: the
    modes alone, from :func:`shared_modal_fields`)."""
    N = model.n_modes
    ei = model.props["bending_stiffness"]
    if fields is None:
        fields = [periodic_fields(model, None, None, x, j, modal=shared_modal_fields(model, window, x, j))
                  for j in range(2)]
    r_o, r_i = scene.outer_radius, scene.inner_radius
    scale = r_o / float(section.second_moment_of_area(r_o, r_i))
    area = model.props["steel_area"]
    k = model.wavenumber
    upper = model.modes >= N // 2
    second = (model.modes >= N // 4) & ~upper  # the quarter below: how fast the modal terms fall
    turn = model.rotary_speed * window.times
    cos_turn, sin_turn = np.cos(turn), np.sin(turn)
    psi = np.linspace(0.0, np.pi, fibres, endpoint=False)  # ψ and ψ + π have the same half range
    cos_fibre, sin_fibre = np.cos(psi), np.sin(psi)
    # how far the body passes its wall beyond its contacts' approach, row by row, for all the segments at once; where
    # no body contact pushes (no approach to allow) it is the largest deflection less the body's clearance
    body = model.kinds == 0
    pressed = np.any(window.forces[:, body, 2] > 0.0, axis=1) if np.any(body) else np.zeros(window.times.size, bool)
    excess_rows = (row_wall_excess(model, x, fields[0]["deflection"], fields[1]["deflection"], window.forces[:, :, 2])
                   if np.any(pressed) else None)
    body_clearance = float(np.max(model.clearance[body])) if np.any(body) else float("nan")
    outs = []
    for first, stop in (segments or [(0, window.times.size)]):
        rows = slice(first, stop)
        times = window.times[rows]
        my, mz = fields[0]["moment"][rows], fields[1]["moment"][rows]
        uy, uz = fields[0]["deflection"][rows], fields[1]["deflection"][rows]
        largest, it, ix, deflection, shear, jt, jx, half = stress_kernel.window_extremes(
            my, mz, uy, uz, x, cos_turn[rows], sin_turn[rows], cos_fibre, sin_fibre)
        # modal truncation indicator: the upper half of the modes' share of the largest modal moment
        shapes = model.shapes(x[ix])[0] * ei * k**2 if model.basis is None else model.moment_shapes(x[ix])[0]
        qy, qz = (field_states(model, window, j)[first + it] for j in range(2))
        bend = ei * model.hole_curvature  # the hole's curvature: exact, in no mode
        full = np.hypot(qy @ shapes - bend[0], qz @ shapes - bend[1])
        tail = np.hypot(qy[upper] @ shapes[upper], qz[upper] @ shapes[upper])
        below = np.hypot(qy[second] @ shapes[second], qz[second] @ shapes[second])
        if excess_rows is not None and np.any(pressed[rows]):
            excess = float(np.max(excess_rows[rows]))
        else:
            excess = float(deflection) - body_clearance
        excess += wall_excess_bound(model, x, largest)
        outs.append(dict(max_deflection=float(deflection), max_wall_excess=excess,
                         max_bending_stress=float(largest * scale),
                         max_normal_stress=float(abs(scene.axial_tension) / area + largest * scale),
                         max_normal_stress_x=float(x[ix]), max_normal_stress_t=float(times[it] - times[0]),
                         alternating_bending_stress=float(np.max(half) * scale),
                         alternating_bending_stress_x=float(x[int(np.argmax(half))]),
                         max_shear_stress=float(2.0 * shear / area),
                         max_shear_stress_x=float(0.5 * (x[jx] + x[jx + 1])),
                         max_shear_stress_t=float(times[jt] - times[0]),
                         modal_tail_fraction=float(tail / full) if full > 0 else 0.0,
                         modal_quarter_fraction=float(below / full) if full > 0 else 0.0))
    return outs


def contact_spacing(model: WhirlModel, window: Window) -> tuple[float, list[float]]:
    """Largest distance between neighbouring touching points along the periodic string (the first of the next
    section, x + L, follows the last) [m]; and the touching positions [m]."""
    touching = np.sort(model.points[(window.contact_time > 0) | (window.onsets > 0)])
    if touching.size == 0:
        return float("nan"), []
    stations = np.concatenate((touching, [touching[0] + model.span]))
    return float(np.max(np.diff(stations))), [float(v) for v in touching]


def energy_balance(model: WhirlModel, window: Window) -> dict[str, float]:
    """Energy budget over the window [J]: change of the mechanical energy, work of the loads and of the
    friction, drag and contact losses, and the residual relative to the largest term."""
    N = model.n_modes
    a, b = window.states[0], window.states[-1]
    dW = b[4 * N:] - a[4 * N:]
    if window.ends is not None:  # with the residual vectors: the kernel's energy, theirs in its modes
        dE = model.kernel_energy(window.ends[1]) - model.kernel_energy(window.ends[0])
    else:
        dE = model.energy(b) - model.energy(a)
    residual = dW[0] + dW[1] - dW[2] - dW[3] - dE
    size = max(abs(dW[0]), abs(dW[1]), abs(dW[2]), abs(dW[3]), abs(dE), 1e-300)
    return dict(energy_change=dE, load_work=dW[0], friction_work=dW[1], drag_loss=dW[2], contact_loss=dW[3],
                residual=float(residual / size))
