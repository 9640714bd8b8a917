"""Parts of the ``sliding`` method (:mod:`study.solvers.methods.sliding`, docs/reference_model.md §10) kept in a
module of their own: its checks by the reference model's own run — whether a periodic motion on the wall is stable
(:func:`stability`), and whether a second motion coexists with it, bouncing or chattering on the wall, reached from
the string's rest on it (:func:`from_rest`, :func:`second_motion`) — and the lift-off search's start
(:func:`least_force_slope`, :func:`polynomial_root`)."""

from __future__ import annotations

from collections.abc import Sequence
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


#: The check for a second motion (:func:`from_rest`, :func:`basin_verdict`). A revolution in which the string is off
#: the wall — every contact open — for more than 1 - ``reference.SLIDING_CONTACT`` of it is a bouncing one: the
#: reference model's own test of its regime (``statistics.whirl_measure``: in contact less of the time, not sliding),
#: by which, with its design figures, ``auto`` tells its full run's motion (``auto._coexisting``). The first
#: :data:`BASIN_TRANSIENT` revolutions decide nothing: the whole eccentric load applied at once throws the joints off
#: the wall (at default grid points 654, 688, 696 and 700 the string flew in revolutions 2-9, 4-6, 6-7 and 5-7 and came
#: back to the wall, as the full reference runs there did). After them :data:`BASIN_LAST` revolutions in a row decide,
#: each a bouncing one (bounces) or none of them bouncing nor chattering (settles); a run still undecided after
#: :data:`BASIN_REVOLUTIONS` revolutions goes up (the reference model's own run decides). :data:`BASIN_LIFT_RATIO`: the
#: lift-off eccentricity over the point's below which the check runs (a joint's least force over the revolution near
#: nil). The figures behind them: docs/reference_model.md §10.
BASIN_REVOLUTIONS, BASIN_TRANSIENT, BASIN_LAST, BASIN_LIFT_RATIO = 40, 5, 5, 2.0
#: A chatter on the wall (:func:`chatters`): a revolution in which a contact opens and strikes again (an onset) at a
#: peak force above :data:`CHATTER_RATIO` times the sliding answer's, the string held on the wall by the other joints.
#: :data:`BASIN_LAST` such revolutions in a row after the first :data:`CHATTER_TRANSIENT` are a chatter beside the
#: sliding motion. Over the 96 points the default sweep checks (48 modes, 40 revolutions from rest): at 384-389 (75
#: rpm, 5 000 lbf, 3°/100 ft) a joint strikes above 4 times the sliding force in 6-15 revolutions in a row after the
#: 15th, at the other points whose string stays on the wall in 3 at most (650, 275 rpm; but 680, which its flights
#: send up), in none at 128-191 (150-175 rpm, straight hole: the start-up's strikes die there, up to 2.8 times after
#: the 15th); the start-up's strikes after a flight pass 4 times in 5-10 revolutions in a row before the 16th (counted
#: from the 11th, 650, 696, 697 and 701 would chatter; with 3 times from the 16th, 650).
CHATTER_RATIO, CHATTER_TRANSIENT = 4.0, 15
#: A chatter that comes late (:func:`late_chatter`): a run settled on the wall by :func:`basin_verdict` runs on to
#: :data:`LATE_REVOLUTIONS`, and the mean of its largest contact force a revolution over the last :data:`LATE_WINDOW`
#: above the sliding answer's peak force beyond the force's tolerance is a chatter beside the sliding motion. Over the
#: 96 points the default sweep checks (48 modes, 120 revolutions from rest): at 650, 651, 654 and 655 (275 rpm,
#: 10 000 lbf, 12 ppg, 3°/100 ft) the run, quiet on the wall at 1.1-1.2 times the sliding force through revolutions
#: 31-50, chatters from the 51st-70th: 1.5-2.1 times it over revolutions 81-100 (1.8-3.0 over 61-80); at the other
#: 76 whose run settles 0.91-1.08 times (the slowest, 136-159 in the straight hole, still dying there: 1.09-1.10 over
#: 61-80).
LATE_REVOLUTIONS, LATE_WINDOW = 100, 20
#: The verdicts of :func:`basin_verdict`.
BOUNCES, CHATTERS, SETTLES = "bounces", "chatters", "settles"


def chatters(onsets: np.ndarray, peak: np.ndarray, sliding_force: float, ratio: float = CHATTER_RATIO) -> bool:
    """Whether a revolution chatters on the wall: a contact point with an onset (``onsets``, per point: it opened and
    struck the wall again) whose largest force over the revolution (``peak`` [N], per point) is above ``ratio`` times
    ``sliding_force`` [N] (the sliding answer's peak contact force)."""
    return bool(np.any((np.asarray(onsets) > 0) & (np.asarray(peak) > ratio * sliding_force)))


def basin_verdict(flying: Sequence[bool], chattering: Sequence[bool] = (), transient: int = BASIN_TRANSIENT,
                  last: int = BASIN_LAST, chatter_transient: int = CHATTER_TRANSIENT) -> str | None:
    """Whether a run from rest bounces, chatters or settles, from ``flying`` (per revolution run so far: the string was
    off the wall for more than 1 - ``reference.SLIDING_CONTACT`` of it) and ``chattering`` (per revolution: it
    chattered, :func:`chatters`; none where not given): :data:`BOUNCES` where each of the last ``last`` revolutions
    flew, all after the first ``transient`` (the load's start-up); else :data:`CHATTERS` where each of the last
    ``last`` chattered, all after the first ``chatter_transient`` (the start-up's strikes after its flights); else
    :data:`SETTLES` where none of the last ``last``, all after the first ``transient``, flew or chattered; None
    (undecided) else."""
    tail = list(flying[transient:])[-last:]
    struck = list(chattering[transient:len(flying)])[-last:]
    late = list(chattering[chatter_transient:len(flying)])[-last:]
    if len(tail) == last and all(tail):
        return BOUNCES
    if len(late) == last and all(late):
        return CHATTERS
    return SETTLES if len(tail) == last and not any(tail) and not any(struck) else None


def late_chatter(peaks: Sequence[float], sliding_force: float, tolerance: float,
                 window: int = LATE_WINDOW) -> float | None:
    """The mean of the largest contact force a revolution [N] over the last ``window`` of ``peaks`` (per revolution
    of a run settled on the wall) over ``sliding_force`` [N] (the sliding answer's peak contact force), where it is
    above 1 + ``tolerance`` (the force's, ``solver.force_tolerance``): a joint keeps lifting and striking the wall
    beyond what the sliding motion's force allows, a chatter; None where it is within (the run kept the sliding motion,
    or a start-up still dying on it) or fewer revolutions were run."""
    if len(peaks) < window or not sliding_force > 0:
        return None
    ratio = float(np.mean(peaks[-window:])) / sliding_force
    return ratio if ratio > 1.0 + tolerance else None


def from_rest(model: reference.WhirlModel, sliding_force: float | None = None,
              revolutions: int = BASIN_REVOLUTIONS, tolerance: float | None = None,
              late_revolutions: int = LATE_REVOLUTIONS) -> dict[str, Any]:
    """Whether the reference model's run from the string's rest on the wall (its own start,
    :func:`~study.solvers.methods.reference.integrate.initial_state`: the eccentric load applied whole at t = 0) keeps
    leaving the wall — revolution after revolution past the start-up, the string off it (every contact open) for more
    than 1 - ``reference.SLIDING_CONTACT`` of each — or chatters on it — a joint striking at more than
    :data:`CHATTER_RATIO` times ``sliding_force`` [N] (the sliding answer's peak contact force; no chatter test where
    None) revolution after revolution while the others hold the string on the wall (:func:`basin_verdict`) — or
    settles on it: where it bounces or chatters a second motion is reached from there, beside the sliding one
    (docs/reference_model.md §10). The run stops as soon as it bounces or chatters, and is undecided where it has
    done neither nor settled after ``revolutions``; one undecided, or whose integration fails, counts as bouncing
    (the reference model's own run decides). Where it settles and ``tolerance`` (the force's) is given, it runs on to
    ``late_revolutions`` (a chatter may come after tens of quiet revolutions), bouncing or chattering by
    :func:`basin_verdict` there too, and chatters where the force of its last revolutions is above the sliding
    answer's beyond that tolerance (:func:`late_chatter`). Returns bounced (bool), chattered (bool), decided (bool),
    the revolution of the first onset (opened, or None), the revolutions off the wall (flying) and chattering
    (chattering), the revolutions run, the revolution it settled in (settled, or None), the late chatter's force over
    the sliding answer's (late, or None), the mode count (modes), the least fraction of a revolution in contact after
    the start-up (contact) and the largest contact force after it [N] (peak; over the whole run where it ended within
    it)."""
    start = reference.initial_state(model)  # the rest on the wall, kept in the model's cache
    run = reference.Integrator(model, ReferenceOptions.default("reference_rtol"), start)
    flying: list[bool] = []
    chattering: list[bool] = []
    peaks, contact, opened, verdict, failed, settled = [], [], None, None, False, None
    runs_on = sliding_force is not None and tolerance is not None  # a settled run runs on for a late chatter
    for k in range(1, max(revolutions, late_revolutions if runs_on else 0) + 1):
        cycle = run.run(k * model.period)
        peaks.append(float(np.max(cycle.peak)))
        contact.append(cycle.any_contact_time / model.period)
        failed = run.outcome != whirl_kernel.OK
        opened = k if opened is None and (failed or np.any(cycle.onsets > 0)) else opened
        flying.append(failed or contact[-1] < reference.SLIDING_CONTACT)
        chattering.append(sliding_force is not None and chatters(cycle.onsets, cycle.peak, sliding_force))
        verdict = BOUNCES if failed else basin_verdict(flying, chattering)
        settled = k if settled is None and verdict == SETTLES else settled
        if verdict in (BOUNCES, CHATTERS) or (settled is None and k >= revolutions) or (settled and not runs_on):
            break
    late = None
    if settled and verdict not in (BOUNCES, CHATTERS):  # settled, and neither bounced nor chattered after
        late = late_chatter(peaks, sliding_force, tolerance) if runs_on else None
        verdict = SETTLES if late is None else CHATTERS
    after = slice(BASIN_TRANSIENT if k > BASIN_TRANSIENT else 0, None)
    return dict(bounced=verdict not in (SETTLES, CHATTERS), chattered=verdict == CHATTERS,
                decided=verdict is not None and not failed, opened=opened,
                flying=[i + 1 for i, f in enumerate(flying) if f],
                chattering=[i + 1 for i, c in enumerate(chattering) if c], revolutions=k, settled=settled, late=late,
                modes=model.n_modes, contact=min(contact[after]), peak=max(peaks[after]))


#: The phrase by which :func:`second_motion`'s message names the motion it found beside the sliding one (which
#: ``auto._coexisting`` takes off where the full run came to the sliding motion after all).
COEXISTS = {BOUNCES: "a bouncing motion coexists", CHATTERS: "a chattering motion coexists"}


def second_motion(result: PointResult, model: reference.WhirlModel, tolerance: float) -> PointResult:
    """``result`` (the sliding state answered on ``model``) with the output ``coexisting_motion``: 1 where a second
    motion coexists with the sliding one (:func:`from_rest`: the reference model's run from the rest on the wall keeps
    leaving it, or chatters on it at more than :data:`CHATTER_RATIO` times the answer's peak contact force, or, late,
    above that force beyond ``tolerance``, the force's; or is undecided), its message saying so and its extras
    ``second_motion`` the run's; 0 where the run stays on the wall or settles back on it; not set (NaN) where the
    lift-off eccentricity is :data:`BASIN_LIFT_RATIO` times the point's or more (not checked)."""
    lift, eps = result.values.get("lift_off_eccentricity", np.nan), model.eccentricity
    if not (eps > 0 and np.isfinite(lift) and lift < BASIN_LIFT_RATIO * eps):
        return result
    found = result.extras["second_motion"] = from_rest(model, result.values.get("peak_contact_force"),
                                                       tolerance=tolerance)
    result.values["coexisting_motion"] = float(found["bounced"] or found["chattered"])
    k = found["revolutions"]
    how = (f"the reference model's run from the rest on the wall (the eccentric load applied at once; lift-off "
           f"eccentricity {lift / eps:.3g} times the point's")
    if found["late"] is not None:
        result.message += (f"; {COEXISTS[CHATTERS]}: in {how}, {found['modes']} modes) the string settled on the wall "
                           f"by revolution {found['settled']}, then a joint lifted and struck it again: over "
                           f"revolutions {k - LATE_WINDOW + 1}-{k} its largest contact force a revolution was "
                           f"{found['late'] * result.values['peak_contact_force']:.4g} N on average, "
                           f"{found['late']:.3g} times this answer's peak force, beyond the force's tolerance of "
                           f"{tolerance:.0%})")
    elif found["chattered"]:
        result.message += (f"; {COEXISTS[CHATTERS]}: in {how}, {found['modes']} modes) a joint lifted and struck the "
                           f"wall at more than {CHATTER_RATIO:.3g} times this answer's peak force in each of "
                           f"revolutions {k - BASIN_LAST + 1}-{k}, the others holding the string on it (in contact "
                           f"{found['contact']:.0%} of a revolution at least, striking it at up to "
                           f"{found['peak']:.3g} N)")
    elif found["bounced"]:
        result.message += (f"; {COEXISTS[BOUNCES]}: {how}) lifted a joint off the wall in revolution "
                           f"{found['opened']} and "
                           + (f"the string was off it in each of revolutions {k - BASIN_LAST + 1}-{k}"
                              if found["decided"] else
                              f"the string was still off it in {len(found['flying'])} of {k} revolutions")
                           + f" (in contact {found['contact']:.0%} of a revolution at least, striking it at up to "
                             f"{found['peak']:.3g} N)")
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
