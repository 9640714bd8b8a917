"""Benchmarks of the reference method (``study bench``; docs/performance.md): its compiled integrator against the
same equations written in numpy for scipy's solve_ivp, as a user would, with the linear penalty contact.
"""

from __future__ import annotations

import time
from typing import Any, Mapping

import numpy as np

from study.solvers.methods import reference
from study.solvers.model.options import ReferenceOptions


def penalty_rhs(model: reference.WhirlModel):
    """The same equations written in numpy, as a user would for solve_ivp, with the linear penalty
    contact (law 1 of :mod:`study.solvers.kernels.whirl_kernel`): returns f(t, z)."""
    N = model.n_modes
    w2 = model.omega**2
    Om, mu, vreg, m = model.rotary_speed, model.friction, model.slip_velocity, model.mass
    S, wts, D = model.drag_shapes, model.drag_weights, model.drag
    phi = model.phi
    ea, eb = reference.eccentric_parts(model)

    def f(t, z):
        qy, qz, vy, vz = z[:N], z[N:2 * N], z[2 * N:3 * N], z[3 * N:4 * N]
        fy = ea * np.cos(Om * t) - eb * np.sin(Om * t) + model.side
        fz = ea * np.sin(Om * t) + eb * np.cos(Om * t)
        ay = -w2 * qy - model.damping * vy + fy
        az = -w2 * qz - model.damping * vz + fz
        uy, uz = S @ vy, S @ vz
        sp = np.hypot(uy, uz)
        ay -= S.T @ (D * sp * uy * wts) / m
        az -= S.T @ (D * sp * uz * wts) / m
        y, w, yd, wd = phi @ qy, phi @ qz, phi @ vy, phi @ vz
        r = np.hypot(y, w)
        d = r - model.clearance
        on = d > 0
        Fy, Fz = np.zeros_like(y), np.zeros_like(y)
        pf = pl = 0.0
        if np.any(on):
            ny, nz = y[on] / r[on], w[on] / r[on]
            dd = yd[on] * ny + wd[on] * nz
            vt = -yd[on] * nz + wd[on] * ny
            elastic = model.penalty_stiffness[on] * d[on]
            fn = np.maximum(elastic + model.penalty_damping[on] * dd, 0.0)
            vs = vt + Om * model.radius[on]
            ft = -mu * fn * vs / np.sqrt(vs**2 + vreg**2)
            Fy[on], Fz[on] = -fn * ny - ft * nz, -fn * nz + ft * ny
            pf, pl = float(np.sum(ft * vt)), float(np.sum((fn - elastic) * dd))
        ay += phi.T @ Fy / m
        az += phi.T @ Fz / m
        power = [m * float(np.sum(fy * vy + fz * vz)), pf, float(np.sum(D * sp**3 * wts)), pl]
        return np.concatenate((vy, vz, ay, az, power))

    return f


def whirl_penalty_reference(inputs: Mapping[str, Any], revolutions: float, *, rtol: float = 1e-6,
                            atol: float | None = None, method: str = "RK45") -> dict[str, Any]:
    """solve_ivp on the penalty-contact equations from the centred pipe at rest over ``revolutions``:
    wall_time [s], status, nfev, final_state (4N + 4,)."""
    from scipy.integrate import solve_ivp

    model = reference.build_model({**inputs, "contact_law": "penalty"})
    N = model.n_modes
    scale = np.concatenate((model.state_scale(), np.full(4, 1.0)))
    start = time.perf_counter()
    sol = solve_ivp(penalty_rhs(model), (0.0, revolutions * model.period), np.zeros(4 * N + 4), method=method,
                    rtol=rtol, atol=(rtol if atol is None else atol) * scale)
    return dict(wall_time=time.perf_counter() - start, status=sol.status, nfev=sol.nfev, final_state=sol.y[:, -1])


def compiled_run(inputs: Mapping[str, Any], revolutions: float, rtol: float = 1e-6) -> dict[str, Any]:
    """The compiled integrator (its scheme ``reference_integrator`` of the inputs) over ``revolutions`` from the
    centred pipe at rest: wall_time [s], outcome, steps, final_state, work (the kernel's counts,
    :data:`study.solvers.kernels.whirl_kernel.N_STATS`)."""
    model = reference.build_model(inputs)
    run = reference.Integrator(model, rtol, scheme=ReferenceOptions.from_inputs(inputs).reference_integrator)
    start = time.perf_counter()
    run.run(revolutions * model.period)
    return dict(wall_time=time.perf_counter() - start, outcome=run.outcome, steps=run.steps, final_state=run.z.copy(),
                work=run.work.copy())


def thrown_state(model: reference.WhirlModel, speed: float, gap: float = 1e-5) -> np.ndarray:
    """The modal state (4N + 4,) of the straight string moved rigidly to ``gap`` [m] off its tool joints' wall on the
    low side (+y) and thrown at it at ``speed`` [m/s]: the rigid translation's coordinate and velocity alone, the
    same physical state at every mode count (tests/solvers/test_modes.py's thrown string)."""
    n = model.n_modes
    z = np.zeros(4 * n + 4)
    z[0] = (float(np.min(model.clearance)) - gap) / model.phi[0, 0]
    z[2 * n] = speed / model.phi[0, 0]
    return z


def fixed_window(inputs: Mapping[str, Any], revolutions: float, speed: float = 0.3,
                 rtol: float = 1e-8) -> dict[str, Any]:
    """The reference model's compiled integrator over ``revolutions`` from :func:`thrown_state` (deterministic: no
    transient, no window growth, the same start at every mode count), its output figures over that window as one
    cycle (:func:`study.solvers.methods.reference.cycle_values`: the stresses with the quasi-static correction, the peak
    contact force). Returns wall_time [s] of the integration alone, revolutions, the figures
    (peak_contact_force [N], max_normal_stress, alternating_bending_stress [Pa], max_deflection [m]), onsets (contact
    onsets in the window) and outcome (the kernel's)."""
    model = reference.build_model(inputs)
    run = reference.Integrator(model, rtol, thrown_state(model, speed),
                               scheme=ReferenceOptions.from_inputs(inputs).reference_integrator)
    start = time.perf_counter()
    window = run.run(revolutions * model.period, record=True)
    wall = time.perf_counter() - start
    values = reference.cycle_values(inputs, model, [window])[0]
    return dict(wall_time=wall, revolutions=float(revolutions), onsets=int(np.sum(window.onsets)), outcome=run.outcome,
                **{name: float(values[name]) for name in FIXED_WINDOW_FIGURES})


#: The figures :func:`fixed_window` returns, as :func:`study.solvers.methods.reference.cycle_values` names them.
FIXED_WINDOW_FIGURES = ("peak_contact_force", "max_normal_stress", "alternating_bending_stress", "max_deflection")
