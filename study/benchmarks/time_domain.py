"""Benchmarks of the time-domain method (``study bench``; docs/performance.md): its integrators' work and
precision against what a user would write instead — scipy's solve_ivp on the same modal model with a linear
penalty contact — and their error against their step.
"""

from __future__ import annotations

import time
from typing import Any, Mapping

import numpy as np

from study.physics import contact
from study.solvers.methods import timedomain
from study.solvers.model.options import TimeDomainOptions
from study.solvers.model.point import DesignPoint


def modal_penalty_reference(inputs: Mapping[str, Any], revolutions: float | None = None, *, rtol: float = 1e-6,
                            atol: float = 1e-9, method: str = "RK45") -> dict[str, Any]:
    """What a user would write instead: solve_ivp (RK45) on the same modal model, linear penalty contact.

    Contact force −sign(y)(k_p δ + c_p δ̇)₊ for δ > 0 with k_p the Hertz stiffness linearised at
    the expected penetration and c_p = 2ζ√(k_p m) (:func:`study.physics.contact.linear_contact_damping`: the
    restitution of a linear spring–dashpot contact); no events, default tolerances, whole run at once.
    Returns wall_time [s], status, message, nfev, steps, final_state, impact_speeds (|midspan
    velocity| at the first step point past each wall crossing: crude, as a user would take it),
    penalty_stiffness [N/m], penalty_damping [N s/m].
    """
    from scipy.integrate import solve_ivp

    model = timedomain.build_model(inputs)
    q0, v0 = timedomain.initial_state(model, DesignPoint.of(inputs).time)
    v_scale = max(model.rotary_speed * model.clearance, float(np.max(np.abs(model.phi @ v0))))
    lim = timedomain.stability_limit(model, v_scale)
    kp = lim["linear_contact_stiffness"]
    cp = contact.linear_contact_damping(kp, model.mass, model.restitution)
    N = len(model.modes)
    zero = np.zeros(len(model.points))
    c = model.clearance

    def rhs(t, y):
        q, v = y[:N], y[N:]
        a, fc = model.acceleration(t, q, v, zero)
        a -= model.phi.T @ fc / model.mass  # the Hertz contact out, the penalty contact in
        yy, yd = model.phi @ q, model.phi @ v
        s = np.sign(yy)
        d = np.abs(yy) - c
        f = np.where(d > 0, -s * np.maximum(kp * d + cp * s * yd, 0.0), 0.0)
        return np.concatenate((v, a + model.phi.T @ f / model.mass))

    revs = float(revolutions if revolutions is not None else TimeDomainOptions.from_inputs(inputs).time_revolutions)
    start = time.perf_counter()
    sol = solve_ivp(rhs, (0.0, revs * model.period), np.concatenate((q0, v0)), method=method, rtol=rtol, atol=atol)
    wall = time.perf_counter() - start
    ym = model.phi[0] @ sol.y[:N]
    ydm = model.phi[0] @ sol.y[N:]
    cross = np.flatnonzero((np.abs(ym[:-1]) < c) & (np.abs(ym[1:]) >= c))
    speeds = np.abs(ydm[cross])
    return dict(wall_time=wall, status=sol.status, message=sol.message, nfev=sol.nfev, steps=sol.t.size,
                final_state=sol.y[:, -1], impact_speeds=speeds, penalty_stiffness=kp, penalty_damping=cp)


def _final_error(run_state, reference_state, scale) -> float:
    """Largest difference of two final modal states, q in units of c and q̇ in units of Ωc [-]."""
    return float(np.max(np.abs(np.asarray(run_state) - np.asarray(reference_state)) / scale))


def _converged_run(inputs: Mapping[str, Any], revolutions: int):
    """The inputs of a fixed-length run, the state scale (c, Ωc) and LSODA's final state at rtol 1e-12."""
    base = {**inputs, "time_revolutions": revolutions, "time_check_periodic": False}
    model = timedomain.build_model(base)
    scale = model.state_scale()
    reference = np.concatenate(timedomain.simulate({**base, "time_integrator": "implicit", "time_rtol": 1e-12,
                                         "time_atol": 1e-14})["final_state"])
    return base, scale, reference


def benchmark(inputs: Mapping[str, Any], revolutions: int = 10, repeat: int = 3,
              contact_steps=(25, 100, 400), penalty_rtols=(1e-4, 1e-6, 1e-8)) -> list[dict[str, Any]]:
    """Work and precision of the integrators and the penalty reference on one case.

    Every run covers exactly ``revolutions`` revolutions (no early stop) from the same state. The
    error of a run is :func:`_final_error` of its final state against a converged run of *its own
    model*: LSODA at rtol 1e-12 for the Hertz model (event, explicit, implicit), DOP853 at rtol 1e-12
    for the linear penalty model. Times are medians of ``repeat`` runs after a warm-up (compiled
    kernels loaded). Returns rows: name, setting, wall_time [s], error [-], impacts, impact_velocity
    [m/s] of the last impact.
    """
    base, scale, hertz_ref = _converged_run(inputs, revolutions)
    penalty_ref = modal_penalty_reference(base, revolutions, rtol=1e-12, atol=1e-15, method="DOP853")["final_state"]
    timedomain.simulate({**base, "time_integrator": "event", "time_revolutions": 1})  # compiled kernels loaded

    def timed(func):
        times, result = [], None
        for _ in range(repeat):
            start = time.perf_counter()
            result = func()
            times.append(time.perf_counter() - start)
        return float(np.median(times)), result

    rows = []
    settings = [("event", f"{n} RK4 steps per contact", {"time_integrator": "event", "contact_steps": n})
                for n in contact_steps]
    settings += [("explicit", "step 0.1 of its limit", {"time_integrator": "explicit"}),
                 ("implicit", "LSODA, rtol 1e-8", {"time_integrator": "implicit"})]
    for name, setting, extra in settings:
        wall, run = timed(lambda: timedomain.simulate({**base, **extra}))
        imp = run["impacts"]
        rows.append(dict(name=name, setting=setting, wall_time=wall,
                         error=_final_error(np.concatenate(run["final_state"]), hertz_ref, scale),
                         impacts=len(imp), impact_velocity=imp[-1]["approach"] if imp else np.nan))
    for rtol in penalty_rtols:
        wall, ref = timed(lambda: modal_penalty_reference(base, revolutions, rtol=rtol, atol=rtol * 1e-3))
        rows.append(dict(name="penalty_rk45", setting=f"rtol {rtol:g}", wall_time=wall,
                         error=_final_error(ref["final_state"], penalty_ref, scale),
                         impacts=int(ref["impact_speeds"].size),
                         impact_velocity=float(ref["impact_speeds"][-1]) if ref["impact_speeds"].size else np.nan))
    return rows


def step_stability(inputs: Mapping[str, Any], revolutions: int = 3, fractions=(0.05, 0.1, 0.2, 0.5, 0.9, 1.1, 2.0, 4.0),
                   contact_steps=(1, 2, 3, 5, 10, 25, 100, 400)) -> list[dict[str, Any]]:
    """Error and outcome of the explicit and event-driven integrators against their step (docs/model.md §9).

    The step is given as a fraction of the explicit step limit 2/ω_max
    (:func:`study.solvers.methods.timedomain.stability_limit`, the contact linearised at the expected penetration): the
    Verlet step for ``"explicit"`` at each of
    ``fractions``, the RK4 contact step for ``"event"`` at each of ``contact_steps`` steps per contact.
    Error as in :func:`benchmark`, against LSODA at rtol 1e-12. Returns rows: name, step_ratio,
    setting, verdict, error (NaN when the run failed), failure.
    """
    base, scale, reference = _converged_run(inputs, revolutions)
    runs = [("explicit", f"step {f:g} of the limit", {"time_integrator": "explicit", "time_step_fraction": f})
            for f in fractions]
    runs += [("event", f"{n} RK4 steps per contact", {"time_integrator": "event", "contact_steps": n})
             for n in contact_steps]
    rows = []
    for name, setting, extra in runs:
        run = timedomain.simulate({**base, **extra})
        step = run["time_step"] if name == "explicit" else run.get("contact_step", np.nan)
        failed = run["verdict"] in ("failed", "chattering")
        rows.append(dict(name=name, setting=setting, step_ratio=step / run["step_limit"], verdict=run["verdict"],
                         error=np.nan if failed else _final_error(np.concatenate(run["final_state"]), reference, scale),
                         failure=run["failure"]))
    return rows


def equal_accuracy_speedups(rows: list[dict[str, Any]], reference: str = "penalty_rk45",
                            method: str = "event") -> list[tuple[dict, dict | None, float]]:
    """For each ``reference`` row, the fastest ``method`` row at least as accurate, and the time ratio."""
    out = []
    for ref in (r for r in rows if r["name"] == reference):
        better = [r for r in rows if r["name"] == method and r["error"] <= ref["error"]]
        best = min(better, key=lambda r: r["wall_time"]) if better else None
        out.append((ref, best, ref["wall_time"] / best["wall_time"] if best else float("nan")))
    return out
