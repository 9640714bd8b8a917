"""Parts of the ``sliding`` method (:mod:`study.solvers.methods.sliding`, docs/reference_model.md §10) kept in a
module of their own: its checks by the reference model's own run — whether a periodic motion on the wall is stable
(:func:`stability`), and whether a bouncing motion coexists with it, reached from the string's rest on the wall
(:func:`from_rest`, :func:`second_motion`) — and the lift-off search's start (:func:`least_force_slope`,
:func:`polynomial_root`)."""

from __future__ import annotations

from typing import Any

import numpy as np

from study.solvers.kernels import whirl_kernel
from study.solvers.methods import reference
from study.solvers.model.options import ReferenceOptions
from study.solvers.model.result import PointResult

#: The stability test of a motion solved in the wall's coordinates (:func:`stability`): the relative kick of its modal
#: velocities, the revolutions run, and the swing [rad] along the wall at or below which a motion is not tested (the
#: linear answers and the Cartesian balance, which settle only below it, never test). At default grid point 54
#: (0.37 rad) the kicked run's distance from the motion fell for 10 revolutions, then grew 1.21-fold a revolution and
#: the contact opened at 36; at point 40 (0.25 rad) it fell 0.92-fold a revolution: over revolutions 11-20 the two are
#: told apart by the sign of the growth.
STABILITY_KICK, STABILITY_REVOLUTIONS, STABILITY_SWING = 0.01, 20, 0.1


def stability(model: reference.WhirlModel, window: reference.Window, revolutions: int = STABILITY_REVOLUTIONS,
              kick: float = STABILITY_KICK) -> dict[str, Any]:
    """Whether a periodic motion on the wall is stable, by the reference model's own time integration (its compiled
    kernel, the Hertz wall with the Hunt–Crossley damping of a held contact, which depends on the restitution): the
    run starts on the motion's state at
    t = 0 (``window``, one revolution of it) with its modal velocities ``kick`` larger, and runs ``revolutions``
    revolutions. At the end of each the distance d_k of the modal state from the motion's (its largest component in
    units of the clearance and Ω × the clearance) is the perturbation left (a Poincaré map: the motion repeats every
    revolution); its growth per revolution, exp of the least-squares slope of ln d_k over the second half of the run
    (the faster parts of the perturbation died in the first), estimates the largest Floquet multiplier's modulus.
    Unstable where a contact opens and strikes again or a point off the wall reaches it (an onset, either), or where
    the perturbation grows (growth ≥ 1).

    Returns stable (bool), growth (per revolution), decay (d over d_0 at the end), revolutions run and opened (the
    revolution at which a contact opened, or None)."""
    N = model.n_modes
    start = np.zeros(4 * N + 4)
    start[:4 * N] = window.states[0, :4 * N]
    motion = start[:4 * N].copy()
    start[2 * N:4 * N] *= 1.0 + kick
    c = float(np.max(model.clearance))
    scale = np.concatenate((np.full(2 * N, c), np.full(2 * N, model.rotary_speed * c)))
    d0 = max(float(np.max(np.abs(start[:4 * N] - motion) / scale)), 1e-300)
    run = reference.Integrator(model, ReferenceOptions.default("reference_rtol"), start)
    distance, opened = [], None
    for k in range(1, revolutions + 1):
        cycle = run.run(k * model.period)
        if run.outcome != whirl_kernel.OK or np.any(cycle.onsets > 0):
            opened = k
            break
        distance.append(float(np.max(np.abs(run.modal_state() - motion) / scale)))
    late = np.log(np.maximum(distance[len(distance) // 2:], 1e-300))
    growth = (float(np.exp(np.polyfit(np.arange(late.size), late, 1)[0])) if opened is None and late.size > 1
              else float("inf"))
    return dict(stable=bool(opened is None and growth < 1.0), growth=growth,
                decay=distance[-1] / d0 if distance else float("inf"), revolutions=k, opened=opened)


#: The check for a second motion (:func:`from_rest`): the revolutions the reference model runs from the sliding rest,
#: the last of them in which a strike means the pipe still bounces, the strike beyond this many times a joint's rest
#: force that decides it at once, and the lift-off eccentricity over the point's below which the check runs (a joint's
#: least force over the revolution near nil: the whole eccentric load applied at once may throw it off the wall). At
#: default grid points 128 and 146 the run lifted off in its first revolutions (600 N, 2.2 and 2.5 times the rest
#: force) and settled on the wall by the 15th and the 7th; at 384 it still struck in each of revolutions 16-30.
BASIN_REVOLUTIONS, BASIN_LAST, BASIN_STRIKE, BASIN_LIFT_RATIO = 20, 5, 5.0, 2.0


def from_rest(model: reference.WhirlModel, revolutions: int = BASIN_REVOLUTIONS,
              last: int = BASIN_LAST) -> dict[str, Any]:
    """Whether the reference model's run from the string's rest on the wall (its own start,
    :func:`~study.solvers.methods.reference.integrate.initial_state`: the eccentric load applied whole at t = 0) still
    bounces after ``revolutions`` revolutions — a contact opens and strikes again (an onset) in the ``last`` of them,
    or a strike exceeds :data:`BASIN_STRIKE` times the largest rest force — or settles on the wall: where it bounces a
    bouncing motion is reached from there, beside the sliding one (docs/reference_model.md §10). Returns bounced
    (bool), the revolution of the first onset (or None), the revolutions run and the largest contact force seen [N]."""
    start = reference.initial_state(model)  # the rest on the wall, kept in the model's cache
    run = reference.Integrator(model, ReferenceOptions.default("reference_rtol"), start)
    strike = BASIN_STRIKE * float(np.max(model.cache["sliding_rest"]["normal"]))
    peak, opened, late = 0.0, None, 0
    for k in range(1, revolutions + 1):
        cycle = run.run(k * model.period)
        peak = max(peak, float(np.max(cycle.peak)))
        struck = run.outcome != whirl_kernel.OK or np.any(cycle.onsets > 0)
        opened = k if struck and opened is None else opened
        late += bool(struck and k > revolutions - last)
        if struck and (peak > strike or run.outcome != whirl_kernel.OK):
            late = 1
            break
    return dict(bounced=late > 0, opened=opened, peak=peak, revolutions=k)


def second_motion(result: PointResult, model: reference.WhirlModel) -> PointResult:
    """``result`` (the sliding state answered on ``model``) with the output ``coexisting_motion``: 1 where a bouncing
    motion coexists with the sliding one (:func:`from_rest`: the reference model's run from the rest on the wall
    bounces),
    its message saying so and its extras ``second_motion`` the run's; 0 where the run stays on the wall; not set
    (NaN) where the lift-off eccentricity is :data:`BASIN_LIFT_RATIO` times the point's or more (not checked)."""
    lift, eps = result.values.get("lift_off_eccentricity", np.nan), model.eccentricity
    if not (eps > 0 and np.isfinite(lift) and lift < BASIN_LIFT_RATIO * eps):
        return result
    found = result.extras["second_motion"] = from_rest(model)
    result.values["coexisting_motion"] = float(found["bounced"])
    if found["bounced"]:
        result.message += (f"; a bouncing motion coexists: the reference model's run from the rest on the wall (the "
                           f"eccentric load applied at once; lift-off eccentricity {lift / eps:.3g} times the point's) "
                           f"left the wall in revolution {found['opened']} and "
                           + (f"struck it at {found['peak']:.3g} N, over {BASIN_STRIKE:g} times the rest force"
                              if found["revolutions"] < BASIN_REVOLUTIONS else
                              f"still struck it in the last {BASIN_LAST} of {found['revolutions']} revolutions "
                              f"({found['peak']:.3g} N)"))
    return result


def least_force_slope(model: reference.WhirlModel, rested: dict[str, Any], linear: tuple[np.ndarray, np.ndarray],
                      matrix: np.ndarray) -> float:
    """dh/dε at ε = 0 times ε [-] of the least normal force over the revolution relative to the rest
    (``sliding._least_force``) for ``model``'s eccentric load: the drag made viscous by equal dissipation grows with
    the motion (its damping as ε) and the arc's second order as ε², so as ε → 0 the motion is the synchronous response
    without drag, A = Z⁻¹ L (``matrix`` Z: the section's modal equations at Ω with the touching points' linearised
    contact ``linear``, (stiffness, damping) (P, 2, 2), about the rest ``rested``), and a touching point's normal force
    swings by |n̂ᵀ (K + iΩ D) a_p| about its rest F_p, a_p its displacement amplitude: h'(0) ε = −max_p of that over
    F_p.
    One complex solve."""
    N, held = model.n_modes, np.flatnonzero(rested["touching"])
    stiff, damp = linear
    A = np.linalg.solve(matrix, np.concatenate((model.eccentric, -1j * model.eccentric)).astype(complex))
    a = np.stack((model.phi[held] @ A[:N], model.phi[held] @ A[N:]), axis=-1)  # (H, 2) complex
    u0 = rested["u"][held]
    n0 = u0 / np.hypot(u0[:, 0], u0[:, 1])[:, None]
    swing = np.abs(np.einsum("hi,hij,hj->h", n0, stiff[held] + 1j * model.rotary_speed * damp[held], a))
    return float(-np.max(swing / rested["normal"][held]))


def polynomial_root(points: list[tuple[float, float]], near: float, slope: float | None = None) -> float | None:
    """The real positive root nearest ``near`` of the polynomial through the (x, y) ``points`` and, where ``slope`` is
    given, with that slope at the first point, which is then at x = 0 (a parabola through three points without it);
    None where it has none."""
    x, y = np.array([p[0] for p in points]), [p[1] for p in points]
    scale = float(np.max(np.abs(x)))
    powers = np.arange(len(points) + (slope is not None))
    rows = (x[:, None] / scale) ** powers
    if slope is not None:  # d/dx at 0 is the linear coefficient
        rows, y = np.vstack((rows, (powers == 1).astype(float))), y + [slope * scale]
    roots = np.roots(np.linalg.solve(rows, np.array(y))[::-1]) * scale
    roots = roots[(np.abs(roots.imag) <= 1e-9 * scale) & (roots.real > 0)].real
    return float(roots[np.argmin(np.abs(roots - near))]) if roots.size else None
