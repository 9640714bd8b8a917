"""Benchmarks of the reference method (``study bench``; docs/performance.md): its compiled integrator against the
same equations written in numpy for scipy's solve_ivp, as a user would, with the linear penalty contact.
"""

from __future__ import annotations

import time
from typing import Any, Mapping

import numpy as np

from study.solvers.kernels import whirl_kernel
from study.solvers.methods import reference
from study.solvers.model.options import ReferenceOptions
from study.solvers.model.scene import Scene


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


#: The figures of the contact-step record, with their column names.
CONTACT_STEP_FIGURES = {"peak_contact_force": "peak contact force", "max_normal_stress": "max normal stress",
                        "alternating_bending_stress": "alternating bending stress"}
#: The bouncing point of the contact-step record: the default study's 175 rpm, 5 000 lbf, e = 0.3, 12 ppg (its
#: flow and hole as configs/default.toml's first point), the first of issue 36's bouncing points.
CONTACT_STEP_POINT = dict(rotary_speed=175 * np.pi / 30, axial_tension=5_000 * 4.4482216152605, restitution=0.3,
                          mud_density=12 * 119.826427)
#: The kernel's stepping in contact compared (option ``reference_integrator``): Dormand–Prince in contact (the default,
#: Lawson in flight), the Lawson form in contact too, Dormand–Prince throughout.
CONTACT_STEP_SCHEMES = ("lawson-flight", "lawson", "dopri5")


def contact_step(point, modes=(32, 64, 128), startup: float = 3.0, revolutions: float = 2.0, rtol: float = 1e-6,
                 tight: float = 1e-8, low_modes: int = 8, schemes=CONTACT_STEP_SCHEMES) -> tuple[list[dict], list[str]]:
    """Where a bouncing point's revolution goes at ``modes`` per direction, and what the step in contact could save
    (docs/reference_model.md §6). Per mode count: the point (e.g. :data:`CONTACT_STEP_POINT` on configs/default.toml)
    is run ``startup`` revolutions from its initial state, then from that one state (its contacts opened as
    :class:`reference.Integrator` opens a start on the wall) each of ``schemes`` integrates ``revolutions`` recorded
    at ``rtol``; a last row is the first scheme with its error test on the first ``low_modes`` modes alone: a bound
    of what a step exact on the higher modes could save at the same tolerance. Per row: CPU per revolution of the
    integrator and of the window's figures (:func:`reference.cycle_values`), steps and evaluations per revolution
    in contact and in flight, the mean step in contact against the stability bound 2.5/ω_N, the cost of an
    evaluation, and each figure of :data:`CONTACT_STEP_FIGURES` over the window as its difference from the first
    scheme's at ``tight`` from the same state. Returns the rows and the report's lines."""
    from study.solvers.methods.reference.integrate import STABLE_STEP, initial_state

    rows = []
    for n in modes:
        inputs = {**point, "reference_modes": n, "reference_max_modes": n}
        model = reference.build_model(inputs)
        tau = model.period
        warm = reference.Integrator(model, rtol, initial_state(model), schemes[0])
        warm.run(startup * tau)
        start = warm.modal_state()
        state = np.concatenate((start, warm.z[4 * model.n_modes:4 * model.n_modes + 4]))
        omega_n = float(np.max(model.omega))

        def window(scheme, tol, low=None):
            run = reference.Integrator(model, tol, state, scheme)
            run.t = warm.t
            if low is not None:  # the error test on the first `low` modes alone
                for j in range(4):
                    run.scale[j * n + low:(j + 1) * n] *= 1e12
            cpu = time.process_time()
            recorded = run.run(warm.t + revolutions * tau, record=True)
            cpu = time.process_time() - cpu
            post = time.process_time()
            values = reference.cycle_values(inputs, model, [recorded])[0]
            post = time.process_time() - post
            work = run.work
            return dict(cpu=cpu / revolutions, post=post / revolutions, outcome=run.outcome,
                        contact_steps=work[whirl_kernel.S_CONTACT_STEPS] / revolutions,
                        flight_steps=(work[whirl_kernel.S_ACCEPTED] - work[whirl_kernel.S_CONTACT_STEPS]) / revolutions,
                        evaluations=work[whirl_kernel.S_RHS] / revolutions,
                        contact_step=work[whirl_kernel.S_CONTACT_TIME] / max(work[whirl_kernel.S_CONTACT_STEPS], 1.0),
                        evaluation=cpu / max(work[whirl_kernel.S_RHS], 1.0), onsets=int(np.sum(recorded.onsets)),
                        **{name: float(values[name]) for name in CONTACT_STEP_FIGURES})

        best = window(schemes[0], tight)
        cases = [(s, None) for s in schemes] + [(schemes[0], low_modes)]
        first = None
        for scheme, low in cases:
            got = window(scheme, rtol, low)
            first = first or got
            rows.append(dict(modes=n, scheme=scheme, low=low, stable_step=STABLE_STEP / omega_n, tight=best,
                             ratio=first["cpu"] / got["cpu"], **got,
                             **{f"{name}_diff": got[name] / best[name] - 1.0 for name in CONTACT_STEP_FIGURES}))
    scene = Scene.from_inputs(point)
    lines = ["**The step in contact at a bouncing point.**", "",
             f"`configs/default.toml` at {scene.rotary_speed * 30 / np.pi:.4g} rpm, "
             f"{scene.axial_tension / 4.4482216152605:.5g} lbf, e = {scene.restitution:g}, "
             f"{scene.mud_density / 119.826427:.3g} ppg (a bouncing point of the default study): {startup:g} "
             "revolutions "
             f"from its initial state, then {revolutions:g} recorded from that one state by each scheme "
             "(`solver.reference_integrator`; the step in contact: `lawson-flight` Dormand–Prince, `lawson` the "
             "Lawson "
             f"form, `dopri5` Dormand–Prince in flight too) at rtol {rtol:g} "
             "(`study.bench.bench_reference_contact_step`). "
             f"The last row of each count: `{schemes[0]}` with its error test on the first {low_modes} modes alone, "
             "the bound of what a step exact on the higher modes saves at the same tolerance. CPU per revolution: the "
             "integrator's and the window's figures' (`reference.cycle_values`). Steps in contact against the "
             "stability bound 2.5/ω_N of the fastest kept mode. Figures over the window: the difference from "
             f"`{schemes[0]}` at rtol {tight:g} from the same state.", "",
             "| modes | step in contact | integrator CPU per revolution [ms] | speed-up | figures CPU per revolution "
             "[ms] | steps per revolution in contact / in flight | mean step in contact / 2.5/ω_N [µs] | evaluations "
             "per revolution | per evaluation [µs] | onsets | "
             + " | ".join(f"{label} diff" for label in CONTACT_STEP_FIGURES.values()) + " |",
             "|---|---|---|---|---|---|---|---|---|---|" + "---|" * len(CONTACT_STEP_FIGURES)]
    for r in rows:
        label = r["scheme"] if r["low"] is None else f"{r['scheme']}, error on modes ≤ {r['low']} (bound)"
        lines.append(f"| {r['modes']} | {label} | {r['cpu'] * 1e3:.3g} | {r['ratio']:.2f}x | {r['post'] * 1e3:.3g} | "
                     f"{r['contact_steps']:.0f} / {r['flight_steps']:.0f} | {r['contact_step'] * 1e6:.3g} / "
                     f"{r['stable_step'] * 1e6:.3g} | {r['evaluations']:.0f} | {r['evaluation'] * 1e6:.3g} | "
                     f"{r['onsets']} | " + " | ".join(f"{r[name + '_diff']:+.1%}" for name in CONTACT_STEP_FIGURES)
                     + " |")
    lines.append("")
    return rows, lines

