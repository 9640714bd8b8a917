"""The reference model's statistics (docs/reference_model.md §3): whether a motion is stationary or still
settling, the figures of each cycle and their window summary with standard errors, the modal check of the
modes left out, the error estimate of each figure (:func:`convergence`) and the whirl's verdict."""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np
from scipy.stats import t as student_t

from study.physics import fatigue, limits, section, strike
from study.physics.contact import hertz_force
from study.solvers.model.point import DesignPoint
from study.solvers.methods.reference.fields import (above_band, field_states, joint_inertia_forces, periodic_fields,
                                                    stresses)
from study.solvers.methods.reference.integrate import Window, merge
from study.solvers.methods.reference.model import WhirlModel, residual_flexibility
from study.physics.string_modes import series_contact
from study.solvers.model.result import REGIMES
from study.solvers.kernels import whirl_kernel


#: The regime of the study's charts (study.solvers.model.result.REGIMES) each whirl verdict is.
WHIRL_REGIMES = {"no_contact": "no_contact", "forward": "forward_whirl", "backward": "backward_whirl",
                 "bouncing": "bouncing", "sliding": "sliding"}


#: Whirl verdicts -> integer code (output ``whirl_class``): its regime's code, one code table (result.Regime).
WHIRL_CLASSES = {verdict: REGIMES[regime] for verdict, regime in WHIRL_REGIMES.items()}


#: |whirl rate/Ω| below which a pipe in contact at least SLIDING_CONTACT of the time lies on the wall, sliding.
SLIDING_RATE, SLIDING_CONTACT = 0.05, 0.99


#: The design figures whose convergence the error estimate states, with the names of their largest values seen
#: in the window and what the message calls them (docs/reference_model.md §3.1).
FIGURES = {"peak_contact_force": ("window_largest_contact_force", "peak force"),
           "max_normal_stress": ("window_largest_normal_stress", "max normal stress"),
           "alternating_bending_stress": ("window_largest_alternating_stress", "alternating stress"),
           "max_deflection": ("window_largest_deflection", "max deflection")}


#: The statistic of the fatigue damage beside :data:`FIGURES`: Miner's damage per cycle of the worst fibre's stress
#: history, counted by rainflow (:func:`fibre_damage`), named as the output it is reported as (per second; its
#: relative error the same), whose inverse is the fatigue life.
DAMAGE = "damage_rate"


#: Fibres round the pipe, evenly from ψ = 0, whose stress histories the damage is counted on, the worst of them the
#: figure. Where the bending stands in the hole's frame and the pipe turns through it every fibre sees the same
#: history; where it turns with the pipe (a whirl) the fibre nearest the worst may lie π/8 off it, its amplitude
#: cos(π/8) = 0.92 of the worst's, its damage 0.92^5 = 0.67 (and in a chaotic bouncing the fibres are alike on
#: average).
DAMAGE_FIBRES = 8


#: The two-sided level of a figure's window part: a mean's stated error is a bound at 95 %, not its 1-sigma scatter,
#: which a figure passes at one point in three; the held-back check of the stated errors (``study coverage``,
#: docs/validation.md) asks them to cover the true difference at 90 % of points. The bound is Student's t on the
#: batch means' degrees of freedom (:func:`confidence`), not the normal's 2: a window of 12 revolutions has four
#: batches, three degrees of freedom.
CONFIDENCE_LEVEL = 0.95


#: The record is still settling where a figure's window mean differs from the preceding stretch's by more than
#: this many of their combined standard errors (a two-sided z-test at about 95 %).
DRIFT_SIGNIFICANCE = 2.0


#: A figure not converged grows the window, up to the budget, unless it foresees more than this many times the budget (a
#: figure that does not, the others still grow it: reference.method.simulate): a forecast from
#: the scatter of a short record is itself uncertain by about a factor 2 (the standard error of 12 revolutions rests
#: on three batches), and one that gave up at the first look's forecast left 246 of the default grid's 301 bouncing
#: points short of 5 % (docs/reference_model.md §3.1).
FORECAST_SLACK = 2.0


#: The largest per-revolution settling ratio :func:`settle_ratio` states: a drift over h revolutions that shrinks
#: by 1 % a revolution is taken to have 1/(1 − 0.99^h) times itself still to come.
MAX_SETTLE_RATIO = 0.99


def stationary(peaks, impacts, states, scale, n: int) -> bool:
    """Whether a motion that has not repeated is done with its transient: it bounces — contact onsets in at least a
    third of the revolutions of each of the last two stretches of n revolutions —, the means of each revolution's
    largest contact force and of its contact onsets over those two stretches differ by no more than
    :data:`DRIFT_SIGNIFICANCE` of their combined standard errors (:func:`standard_error`), and the state's changes
    from one revolution boundary to the next do not shrink beyond doubt (:func:`settle_ratio`): a chaotic
    bouncing, whose statistics are stationary, and not a motion still settling towards a rest, a slide or a
    cycle (docs/reference_model.md §3.1). The first n revolutions (the start-up, whose scatter would hide any
    drift) are never in the two stretches: False before 3n revolutions."""
    if len(peaks) < 3 * n:
        return False
    if min(np.count_nonzero(impacts[-2 * n:-n]), np.count_nonzero(impacts[-n:])) < n / 3:
        return False  # too few strikes: lying or sliding on the wall, or clear of it, not bouncing
    for series in (impacts, peaks):
        before, last = np.asarray(series[-2 * n:-n], float), np.asarray(series[-n:], float)
        spread = np.hypot(*(standard_error(x) if np.ptp(x) > 0 else 0.0 for x in (before, last)))
        if abs(np.mean(last) - np.mean(before)) > DRIFT_SIGNIFICANCE * spread:
            return False
    return not np.isfinite(settle_ratio(states, scale))


def cycle_values(point: DesignPoint | Mapping[str, Any], model: WhirlModel,
                 cycles: list[Window]) -> list[dict[str, Any]]:
    """The outputs of each of consecutive cycles of the motion (a revolution, or the period when periodic):
    :func:`stresses` (with the quasi-static correction of the modes left out wherever a contact force acts,
    :func:`quasi_static_applies`; the fields computed once) and the peak contact force, exact at every step of the
    integrator; ``correction`` says whether the correction entered, ``start`` is the cycle's start [s]; :data:`DAMAGE`
    the Miner's damage of each of :data:`DAMAGE_FIBRES` fibres in the cycle (F,), counted by rainflow over the cycles'
    joined history at the section of their largest alternating stress (:func:`fibre_damage`)."""
    point = DesignPoint.of(point)
    joined = merge(cycles)
    correction = quasi_static_applies(model, joined)
    ends = np.cumsum([c.times.size for c in cycles])
    segments = list(zip(np.concatenate(([0], ends[:-1])), ends))
    if point.reference.reference_strike_stress != "modes" and model.law == 0 and correction:
        values, (masked, pulses_at) = strike_stress_values(point, model, joined, segments)
        # the modal check's stresses without the correction, per cycle as the corrected ones (modal_check reads them:
        # no whole-window recomputation at each look of the window's growth; the fields are shared, fields.window_memo)
        plain = stresses(point, model, joined, correction=False, segments=segments)
    else:
        values, plain, masked, pulses_at = [], [], None, None
        # the cycles' stresses a batch of cycles at a time (each cycle's are its own rows'): a window grown to a few
        # hundred revolutions held its fields over every row at once, GiBs (docs/reference_model.md §6)
        for batch in stress_batches(cycles):
            part = joined if len(batch) == len(cycles) else merge([cycles[i] for i in batch])
            first = segments[batch[0]][0]
            own = [(a - first, b - first) for a, b in segments[batch[0]:batch[-1] + 1]]
            values += stresses(point, model, part, correction=correction, segments=own)
            plain += stresses(point, model, part, correction=False, segments=own)
    plain = [{name: v[name] for name in UNCORRECTED} for v in plain]
    station = values[int(np.argmax([v["alternating_bending_stress"] for v in values]))]["alternating_bending_stress_x"]
    damage = fibre_damage(point, model, joined, station, [first for first, _ in segments], correction, masked=masked,
                          pulses=pulses_at(station) if pulses_at is not None else None)
    peaks = [float(np.max(c.peak)) for c in cycles]
    local = [None] * len(cycles)
    choice = point.reference.reference_strike_force
    if choice in ("local", "smaller") and model.law == 0:
        local = local_strike_forces(model, joined, segments)
        if choice == "local":
            peaks = [v["peak_contact_force"] for v in local]
    # with "smaller" each cycle carries both forces: the modes' own as its figure, the local model's beside it
    # (``local_strikes``), and the run keeps the one stating the smaller error (method.strike_force_forms)
    key = "strikes" if choice == "local" else "local_strikes"
    return [dict(v, peak_contact_force=f, correction=correction, start=c.start, **{DAMAGE: d}, uncorrected=u,
                 **({key: s} if s is not None else {}))
            for v, c, d, f, s, u in zip(values, cycles, damage, peaks, local, plain)]


#: The most rows of a window whose stresses :func:`cycle_values` takes at once (:func:`stress_batches`): some 16
#: revolutions of a 64-mode run's recording; a batch's fields (the deflection and moment at ~100 stations in two
#: directions, with and without the correction) some 0.5 GiB.
STRESS_ROWS = 2**16


def stress_batches(cycles: list[Window], rows: int | None = None) -> list[list[int]]:
    """The cycles' indices in consecutive batches of at most ``rows`` (:data:`STRESS_ROWS`) recorded rows each (a cycle
    longer than that a batch of its own): what :func:`cycle_values` takes the stresses of at once."""
    rows = STRESS_ROWS if rows is None else rows
    batches: list[list[int]] = []
    size = 0
    for i, cycle in enumerate(cycles):
        n = cycle.times.size
        if batches and size + n <= rows:
            batches[-1].append(i)
            size += n
        else:
            batches.append([i])
            size = n
    return batches


#: The stress figures :func:`modal_check` compares with and without the quasi-static correction, kept per cycle
#: (``uncorrected`` of :func:`cycle_values`).
UNCORRECTED = ("max_normal_stress", "alternating_bending_stress", "max_bending_stress", "max_deflection")


#: The local model's own error of a strike's peak force (relative; docs/reference_model.md §2.3): on strikes of three
#: bouncing points of the default study, taken from their 64-mode runs and replayed at 128 and 256 modes, the local
#: model from the run's onset speed was a median 1.0-5.0 % above the 256-mode replays (the series law's, still rising)
#: and 0-8.3 % below their extrapolation by a geometric tail, per point; the largest of those medians, rounded up. The
#: string thrown onto its joints: 1.5 % under its 256-mode run (tests/physics/test_strike.py).
LOCAL_STRIKE_ERROR = 0.09


#: The peak force goes as the onset speed to a power between 9/8 (the beam alone) and 6/5 (the joint's mass alone,
#: Johnson 1985 §11.4): the onset speed's relative error times this is the force's.
SPEED_EXPONENT = 1.2


def displacement(model: WhirlModel, states: np.ndarray, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(y, w) [m] (S,): each of ``points`` (S,) displaced from the hole's axis in the two lateral directions, from the
    kept modes of ``states`` (S, 4N + …)."""
    N = model.n_modes
    phi = model.phi[points]  # (S, N)
    return np.sum(phi * states[:, :N], axis=1), np.sum(phi * states[:, N:2 * N], axis=1)


def approach(model: WhirlModel, states: np.ndarray, points: np.ndarray, mask=1.0) -> tuple[np.ndarray, np.ndarray]:
    """(|u| [m], (u·u̇)/|u| [m/s]) (S,): each of ``points`` (S,) displaced from the hole's axis
    (:func:`displacement`) and its velocity towards its wall, from the kept modes of ``states`` (S, 4N + …), the
    velocity's modes weighed by ``mask`` (N,)."""
    N = model.n_modes
    phi = model.phi[points]  # (S, N)
    y, w = displacement(model, states, points)
    size = np.maximum(np.hypot(y, w), 1e-300)
    return size, (y * np.sum(phi * mask * states[:, 2 * N:3 * N], axis=1)
                  + w * np.sum(phi * mask * states[:, 3 * N:4 * N], axis=1)) / size


def onset_rows(model: WhirlModel, window: Window, rows: np.ndarray, points: np.ndarray) -> np.ndarray:
    """(S,) the row of each strike's onset: for the first row ``rows`` (S,) with a force at ``points`` (S,), the row
    before it where that row is the onset the kernel located and recorded (the point at its wall, within twice
    ``whirl_kernel.ONSET_TOLERANCE`` of the clearance, and moving towards it: the kernel records a row at an onset
    that comes a contact's row spacing or more after its last row), else that first row itself (an onset within a
    row spacing of the last row, or against a wall shifted after a pulse, docs/reference_model.md §2.4)."""
    before = np.maximum(rows - 1, 0)
    size, rate = approach(model, window.states[before], points)
    at_wall = np.abs(size - model.clearance[points]) <= 2.0 * whirl_kernel.ONSET_TOLERANCE * model.clearance[points]
    return np.where((rows > 0) & at_wall & (rate > 0), before, rows)


def strike_speeds(model: WhirlModel, window: Window) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The window's strikes at the tool joints: (rows, points, onset speeds [m/s], modal parts) — each row where a
    joint's normal force is nil at the row before and not at it, the kept modes' velocity of the joint towards its
    wall at the strike's onset (the approach rate, ``(u·u̇)/|u|``, at :func:`onset_rows`: the kernel records a row at
    the onset it locates, with the contact law's force there just over nil, but a pulse's nil — its history starts
    at 0 —, so that with ``reference_strike_force = "pulse"`` the first row with a force comes one contact row spacing,
    60-100 µs, into the strike, where the pulse has taken 10-25 % of the speed off), and
    the onset speed's modal part, relative: the share s_1 of it the last octave of the kept modes carries (the upper
    half by frequency) and, where it falls from the octave before (s_2, the third quarter) by r = s_1/s_2 < 1/2, the
    octaves beyond taken as a geometric series, s_1 r/(1 − r) (the replays' rule: a tail no larger than the last
    change, :func:`study.solvers.methods.reference.replay.stated_part`)."""
    N = model.n_modes
    fn = window.forces[:, :, 2]
    joints = np.flatnonzero(model.kinds == 1)
    on = (fn[1:, joints] > 0) & (fn[:-1, joints] <= 0)
    rows, which = np.nonzero(on)
    rows, points = rows + 1, joints[which]
    if rows.size == 0:
        return rows, points, np.zeros(0), np.zeros(0)
    q = window.states[onset_rows(model, window, rows, points)]
    rank = np.argsort(np.argsort(model.omega, kind="stable"), kind="stable")  # each mode's place by frequency

    def rate(mask):
        return approach(model, q, points, mask)[1]

    speed = rate(1.0)
    size = np.maximum(np.abs(speed), 1e-300)
    upper = np.abs(rate((rank >= N // 2).astype(float))) / size  # the last octave of the kept modes
    lower = np.abs(rate(((rank >= N // 4) & (rank < N // 2)).astype(float))) / size  # the one before
    # the octaves to come, geometric at the ratio r of the last two, no more than the last: upper × r/(1 − r) with r
    # taken at most 1/2 (the last octave itself where the octaves do not fall; no overflow)
    ratio = np.minimum(upper / np.maximum(lower, 1e-300), 0.5)
    return rows, points, speed, upper * (ratio / (1.0 - ratio))


def local_strike_forces(model: WhirlModel, window: Window, segments) -> list[dict[str, Any]]:
    """Per segment of the window's rows (a cycle): the peak contact force with each strike at a tool joint taken from
    its local model (:func:`study.physics.strike.peak_force` at its onset speed, :func:`strike_speeds`: the joint's mass
    on an infinite beam of the string's ρA and EI against the wall's Hertz K and the calibrated Hunt–Crossley damping;
    docs/reference_model.md §2.3), where its contact ends before the bending waves of the neighbouring joints come back
    (:func:`study.physics.strike.return_time`, the joints' spacing away); every other contact (held, on the body, or
    a strike too long) its recorded force: ``peak_contact_force`` [N] (the largest), ``count`` the strikes taken
    locally, ``long`` those left to the modes, ``speed`` the largest onset speed among them [m/s], ``speed_share`` the
    upper modes' share of the onset speed of the strike with the largest local force (:func:`strike_speeds`),
    ``reflection`` the largest contact duration over the waves' return time."""
    fn = window.forces[:, :, 2]
    struck = local_strikes(model, window)
    rows = struck["rows"]
    local = fn.copy()  # the recorded forces, a strike's rows replaced by nothing and its local peak put at its onset
    for row, end, p in zip(rows, struck["ends"], struck["points"]):
        local[row:end, p] = 0.0
    extra = np.zeros(fn.shape[0])
    np.maximum.at(extra, rows, struck["forces"])
    taken = np.bincount(rows, minlength=fn.shape[0])  # strikes taken locally, per onset row
    long_rows = np.bincount(struck["long_rows"], minlength=fn.shape[0])
    reflection = np.zeros(fn.shape[0])
    np.maximum.at(reflection, np.concatenate((rows, struck["long_rows"])),
                  np.concatenate((struck["ratios"], struck["long_ratios"])))
    speed_at = np.zeros(fn.shape[0])
    speed_at[rows] = struck["speeds"]
    out = []
    shares = np.zeros(fn.shape[0])
    shares[rows] = struck["shares"]
    for a, b in segments:
        largest = a + int(np.argmax(extra[a:b])) if b > a else a  # the cycle's strongest strike taken locally
        out.append(dict(peak_contact_force=float(max(np.max(local[a:b], initial=0.0), np.max(extra[a:b], initial=0.0))),
                        count=int(np.sum(taken[a:b])), long=int(np.sum(long_rows[a:b])),
                        speed=float(np.max(np.where(taken[a:b] > 0, speed_at[a:b], 0.0), initial=0.0)),
                        speed_share=float(shares[largest]) if b > a and taken[largest] > 0 else 0.0,
                        reflection=float(np.max(reflection[a:b], initial=0.0))))
    return out


def strike_stations(point: DesignPoint) -> np.ndarray:
    """(3,) the distances [m] from a struck tool joint of the stations its strike's bending is corrected at: the joint
    itself and the pipe body either side of it, half the tool joint's length away (``pipe.tool_joint_length``), where
    the section is the body's (docs/reference_model.md §2.3)."""
    half = 0.5 * float(point.reference.tool_joint_length)
    return np.array([0.0, half, -half])


def strike_moment_tables(point: DesignPoint, model: WhirlModel, kept: int | None = None) -> dict:
    """Per tool-joint contact point p: :func:`study.physics.strike.strike_moment_table` at :func:`strike_stations`,
    the correction of a strike's bending for the modes left out against its onset speed, with the model's kept modes
    (the ``kept`` slowest only where given: the change from N/2 to N is the correction's modal part). Cached on the
    model."""
    key = ("strike_moment", kept)
    if key in model.cache:
        return model.cache[key]
    N = model.n_modes
    omega = np.nan_to_num(np.asarray(model.omega[:N], float))
    use = ~above_band(model)  # the modes above the stresses' band are quasi-static in the fields, as the left out
    if kept is not None:
        use &= np.argsort(np.argsort(omega, kind="stable"), kind="stable") < kept
    offsets = strike_stations(point)
    ei, rho = model.props["bending_stiffness"], model.props["mass_per_length"]
    out = {}
    for p in np.flatnonzero(model.kinds == 1):
        x = np.mod(model.points[p] + offsets, model.span)
        gains = model.phi[p][None, :] * model.moment_shapes(x) / model.mass * use[None, :]
        out[int(p)] = strike.strike_moment_table(model.joint_mass, model.stiffness[p], rho, ei, model.hysteresis,
                                                 offsets, omega, gains)
    model.cache[key] = out
    return out



def strike_history_tables(point: DesignPoint, model: WhirlModel) -> dict:
    """Per tool-joint contact point p: :func:`study.physics.strike.strike_history_table` at :func:`strike_stations`
    with the model's kept modes, the correction of a strike's bending for the modes left out as a history after its
    onset (docs/reference_model.md §2.3.1), over the horizon :func:`history_horizon`. Cached on the model."""
    key = ("strike_history",)
    if key in model.cache:
        return model.cache[key]
    N = model.n_modes
    omega = np.nan_to_num(np.asarray(model.omega[:N], float))
    offsets = strike_stations(point)
    ei, rho = model.props["bending_stiffness"], model.props["mass_per_length"]
    out = {}
    joints = np.flatnonzero(model.kinds == 1)
    for k in np.unique(model.stiffness[joints]):  # the joints of one wall stiffness together: one strike, one sum
        group = joints[model.stiffness[joints] == k]
        gains = np.concatenate([model.phi[p][None, :] * model.moment_shapes(np.mod(model.points[p] + offsets,
                                                                                   model.span)) / model.mass
                                for p in group]) * ~above_band(model)[None, :]
        horizon = min(history_horizon(model, p) for p in group)
        table = strike.strike_history_table(model.joint_mass, k, rho, ei, model.hysteresis,
                                            np.tile(offsets, group.size), omega, gains, horizon)
        for j, p in enumerate(group):
            out[int(p)] = dict(table, corrections=table["corrections"][:, :, j * offsets.size:(j + 1) * offsets.size])
    model.cache[key] = out
    return out


def history_horizon(model: WhirlModel, p: int) -> float:
    """The time [s] after a strike's onset over which its correction for the modes left out is the infinite beam's
    (:func:`strike_history_tables`): until the first of the waves it carries come back from the neighbouring joints,
    whose mass reflects them. Its band lies above the kept modes' highest frequency ω_N and below the strike's own,
    2π/T_c (T_c the shortest strike of the force's table, :func:`study.physics.strike.strike_peak_table`): its fastest
    waves travel at c_g of the higher of the two, and are back after 2 s/c_g (s the joints' spacing)."""
    ei, rho = model.props["bending_stiffness"], model.props["mass_per_length"]
    top = float(np.max(np.nan_to_num(np.asarray(model.omega[:model.n_modes], float))[~above_band(model)]))
    _, _, durations = strike.strike_peak_table(float(model.joint_mass), float(model.stiffness[p]), float(rho),
                                               float(ei), float(model.hysteresis))
    band = 2.0 * np.pi / float(np.min(durations))
    return float(2.0 * model.joint_spacing / strike.group_velocity(max(top, band), rho, ei))

def local_strikes(model: WhirlModel, window: Window) -> dict[str, np.ndarray]:
    """The window's strikes at the tool joints taken by their local model (:func:`strike_speeds`; those whose contact
    ends before the neighbouring joints' waves come back, :func:`study.physics.strike.return_time`, the joints' spacing
    away): ``rows`` the onsets (the first rows with a force), ``starts`` their times [s] (:func:`onset_rows`),
    ``points``, ``speeds`` [m/s], ``shares`` their modal parts (:func:`strike_speeds`),
    ``forces`` the local model's peak force [N] (:func:`study.physics.strike.peak_force` at the onset speed),
    ``ratios`` the contact's duration over the waves' return time, ``ends`` the first row after the run's contact,
    ``peaks`` the row of the run's largest force in it, ``directions`` (S, 2) the unit direction of the wall's force on
    the pipe (towards the hole's axis from the joint); and of the strikes too long for it, left to the modes,
    ``long_rows`` the onsets and ``long_ratios``."""
    fn = window.forces[:, :, 2]
    rows, points, speed, share = strike_speeds(model, window)
    ei, rho = model.props["bending_stiffness"], model.props["mass_per_length"]
    forces, durations = np.zeros(rows.size), np.zeros(rows.size)
    for p in np.unique(points):  # one interpolation per joint (its wall's K)
        at = points == p
        forces[at], durations[at] = strike.peak_force(speed[at], model.joint_mass, model.stiffness[p], rho, ei,
                                                      model.hysteresis)
    ratios = durations / strike.return_time(durations, model.joint_spacing, rho, ei)
    keep = ratios < 1.0
    long_rows, long_ratios = rows[~keep], ratios[~keep]
    rows, points, speed, share, forces, ratios = (x[keep] for x in (rows, points, speed, share, forces, ratios))
    ends, peaks = np.zeros(rows.size, int), np.zeros(rows.size, int)
    for k, (row, p) in enumerate(zip(rows, points)):
        end = row
        while end < fn.shape[0] and fn[end, p] > 0:
            end += 1
        ends[k], peaks[k] = end, row + int(np.argmax(fn[row:max(end, row + 1), p]))
    y, w = displacement(model, window.states[rows], points)
    norm = np.maximum(np.hypot(y, w), 1e-300)
    return dict(rows=rows, points=points, speeds=speed, ends=ends, peaks=peaks,
                starts=window.times[onset_rows(model, window, rows, points)],
                directions=-np.column_stack([y / norm, w / norm]), forces=forces, shares=share, ratios=ratios,
                long_rows=long_rows, long_ratios=long_ratios)


def strike_stress_values(point: DesignPoint, model: WhirlModel, window: Window, segments):
    """:func:`stresses` per segment with the strikes' local bending (``reference_strike_stress = "local"``;
    docs/reference_model.md §2.3): the quasi-static correction leaves out the struck joints' loads over their strikes
    (their contact and inertia forces, ``masked``; with ``reference_strike_force = "pulse"`` over the pulse's T_c only,
    the contact law's held force after it corrected quasi-statically), and the correction's history of
    :func:`strike_history_tables` (the infinite beam's moment under the local model's force less the kept modes' share,
    at the strike's onset speed) is added along the wall's force to the moment at each of :func:`strike_stations`, at
    every row from the onset over its horizon (:func:`history_horizon`; the run's kept modes then carry what the
    table's kept modes do, as N grows):
    the max bending and normal stress of a segment are the larger of the fields' and the struck stations' so
    corrected, the alternating stress the larger of the fields' and the struck stations' fibre histories with the
    correction added at the strike's row. Each segment's ``strike_modal``: the stress figures' modal part, absolute —
    where a struck station's corrected value is the figure, its strike's (``change``): the kept modes' share of the
    local moment times the run's own strike force's relative difference from the local model's peak (the run's kept
    modes carry their share under their own force), plus :data:`LOCAL_STRIKE_ERROR` of the local moment (half of it on
    the alternating stress, a half range of which it moves one extreme); and the quasi-static correction of the loads
    not masked times :func:`quasi_static_ratio` (``rest``). Returns (values, (masked, pulses_at)),
    ``pulses_at(station)`` the (R, 2) moments the correction adds at a station for :func:`fibre_damage`."""
    N = model.n_modes
    struck = local_strikes(model, window)
    R, P = window.forces.shape[:2]
    masked = np.zeros((R, P), bool)
    ei, rho = model.props["bending_stiffness"], model.props["mass_per_length"]
    pulse = point.reference.reference_strike_force == "pulse"
    for row, end, p, v, t0 in zip(struck["rows"], struck["ends"], struck["points"], struck["speeds"],
                                  struck["starts"]):
        if pulse:  # the run's force is the local strike's for its T_c, then the contact law's (held: quasi-static)
            duration = float(strike.peak_force([v], model.joint_mass, model.stiffness[p], rho, ei,
                                               model.hysteresis)[1][0])
            end = min(end, max(int(np.searchsorted(window.times, t0 + duration)), row + 1))
        masked[row:end, p] = True
    values = stresses(point, model, window, correction=True, segments=segments, masked=masked)
    if struck["rows"].size == 0:
        return values, (masked, None)
    plain = stresses(point, model, window, correction=False, segments=segments)
    ratio = quasi_static_ratio(model, window)
    offsets = strike_stations(point)
    full = strike_moment_tables(point, model)
    S = struck["rows"].size
    corrections, errors = np.zeros((S, offsets.size)), np.zeros((S, offsets.size))
    at_rows = np.zeros((S, offsets.size), int)  # the rows nearest each station's local peak after the onset
    ei, rho = model.props["bending_stiffness"], model.props["mass_per_length"]
    for p in np.unique(struck["points"]):
        at = struck["points"] == p
        corrections[at] = strike.moment_correction(struck["speeds"][at], full[int(p)])
        kept = strike.moment_correction(struck["speeds"][at], full[int(p)], column=3)
        local = strike.peak_force(struck["speeds"][at], model.joint_mass, model.stiffness[p], rho, ei,
                                  model.hysteresis)[0]
        own = np.array([np.max(window.forces[r:max(e, r + 1), p, 2]) for r, e in
                        zip(struck["rows"][at], struck["ends"][at])])
        # the run's kept modes carry their share of the strike under the run's own force, not the local one's; and
        # the local model's own error on what it gives
        errors[at] = (np.abs(kept) * np.abs(own / local - 1.0)[:, None]
                      + LOCAL_STRIKE_ERROR * np.abs(corrections[at] + kept))
        speeds, times = full[int(p)][0], full[int(p)][2]
        v = np.log(np.clip(struck["speeds"][at], speeds[0], speeds[-1]))
        for s in range(offsets.size):
            when = struck["starts"][at] + np.interp(v, np.log(speeds), times[:, s])
            after = np.clip(np.searchsorted(window.times, when), 1, R - 1)
            nearer = np.abs(window.times[after - 1] - when) < np.abs(window.times[after] - when)
            at_rows[at, s] = np.maximum(np.where(nearer, after - 1, after), struck["rows"][at])
    scene = point.scene
    r_o, r_i = scene.outer_radius, scene.inner_radius
    scale = r_o / float(section.second_moment_of_area(r_o, r_i))
    axial = abs(scene.axial_tension) / model.props["steel_area"]
    inertia = (joint_inertia_forces(model, window) if model.joint_points is not None
               and (not model.dynamic or model.recovery == "force") else None)

    def loads(j):
        forces = window.correction_forces(model, j)
        if inertia is not None:
            forces = forces + inertia[:, :, j]
        return np.where(masked, 0.0, forces)

    stations = {}  # station x -> (strike indices, offset index)
    for k, p in enumerate(struck["points"]):
        for s, off in enumerate(offsets):
            x = float(np.mod(model.points[p] + off, model.span))
            stations.setdefault(round(x, 9), []).append((k, s))
    xs = np.array(sorted(stations))
    moments = [periodic_fields(model, field_states(model, window, j, masked), loads(j), xs, j)["moment"]
               for j in range(2)]  # (R, X) each
    fibre = np.linspace(0.0, np.pi, 16, endpoint=False)
    turn = model.rotary_speed * window.times

    def pulses(i, table):
        out = np.zeros((R, 2))
        for k, s in stations[xs[i]]:
            onset, stop, history = histories(k)
            out[onset:stop] += history[:, s, None] * struck["directions"][k][None, :]
        return out

    history_tables, history_rows = strike_history_tables(point, model), {}

    def histories(k):
        if k not in history_rows:
            onset, table = int(struck["rows"][k]), history_tables[int(struck["points"][k])]
            stop = int(np.searchsorted(window.times, struck["starts"][k] + table["times"][-1], side="right"))
            history_rows[k] = (onset, stop, strike.history_correction(
                float(struck["speeds"][k]), window.times[onset:stop] - struck["starts"][k], table))
        return history_rows[k]

    pulse_full = [pulses(i, corrections) for i in range(xs.size)]
    station_error = np.zeros(xs.size)  # the largest error of a correction at each station
    for i in range(xs.size):
        for k, s in stations[xs[i]]:
            station_error[i] = max(station_error[i], errors[k, s])
    figures = ("max_bending_stress", "max_normal_stress", "alternating_bending_stress")
    # the fibres' turned directions over the window, once (the same values as per segment: elementwise)
    angle = turn[:, None] + fibre[None, :]
    cos_angle, sin_angle = np.cos(angle), np.sin(angle)
    out = []
    for (a, b), v, bare in zip(segments, values, plain):
        fields_only = v
        bend, where, when, alt, alt_x, bend_error, alt_error = -1.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0
        for i in range(xs.size):
            if not np.any(pulse_full[i][a:b]):
                continue
            my, mz = moments[0][a:b, i] + pulse_full[i][a:b, 0], moments[1][a:b, i] + pulse_full[i][a:b, 1]
            size = np.hypot(my, mz)
            k = int(np.argmax(size))
            if size[k] > bend:
                bend, where, when = float(size[k]), float(xs[i]), float(window.times[a + k] - window.times[a])
                bend_error = station_error[i]
            stress = my[:, None] * cos_angle[a:b] + mz[:, None] * sin_angle[a:b]
            h = float(np.max(0.5 * (np.max(stress, axis=0) - np.min(stress, axis=0))))
            if h > alt:
                alt, alt_x, alt_error = h, float(xs[i]), station_error[i]
        v = dict(fields_only)
        change = dict.fromkeys(figures, 0.0)
        if bend * scale > v["max_bending_stress"]:
            v.update(max_bending_stress=bend * scale, max_normal_stress=axial + bend * scale,
                     max_normal_stress_x=where, max_normal_stress_t=when)
            change.update(max_bending_stress=bend_error * scale, max_normal_stress=bend_error * scale)
        if alt * scale > v["alternating_bending_stress"]:
            v.update(alternating_bending_stress=alt * scale, alternating_bending_stress_x=alt_x)
            change["alternating_bending_stress"] = 0.5 * alt_error * scale  # one extreme of the half range moves
        v["strike_modal"] = {f: dict(change=change[f], rest=ratio * abs(fields_only[f] - bare[f])) for f in figures}
        out.append(v)
    return out, (masked, lambda station: next((pulse_full[i] for i in range(xs.size)
                                              if abs(xs[i] - station) < 1e-9), None))


def fibre_stress(point: DesignPoint, model: WhirlModel, window: Window, station: float,
                 correction: bool = True, fibres: int = DAMAGE_FIBRES, masked: np.ndarray | None = None,
                 pulses: np.ndarray | None = None) -> np.ndarray:
    """(R, F) the normal stress [Pa] of ``fibres`` fibres of the turning pipe, at ψ = 2πk/F from the fibre that
    faces +y at t = 0, at the section x = ``station`` [m] over the window's rows: T0/A_s plus
    (M_y cos(Ωt + ψ) + M_z sin(Ωt + ψ)) r_o/I (the moments of :func:`periodic_fields`, with the quasi-static
    correction where ``correction``; the fibre stress whose half range over a cycle is the alternating stress of
    :func:`stresses`). ``masked`` (R, P) the loads the correction leaves out and ``pulses`` (R, 2) moments [N m] added
    at the station: the strikes' local bending (:func:`strike_stress_values`)."""
    N = model.n_modes
    x = np.array([float(station)])

    def loads(j):
        if not correction:
            return None
        forces = window.correction_forces(model, j)
        return forces if masked is None else np.where(masked, 0.0, forces)

    moments = [periodic_fields(model, field_states(model, window, j, masked if correction else None), loads(j), x,
                               j)["moment"][:, 0] for j in range(2)]
    if pulses is not None:
        moments = [moments[j] + pulses[:, j] for j in range(2)]
    scene = point.scene
    r_o, r_i = scene.outer_radius, scene.inner_radius
    scale = r_o / float(section.second_moment_of_area(r_o, r_i))
    angle = model.rotary_speed * window.times[:, None] + 2.0 * np.pi * np.arange(fibres)[None, :] / fibres
    bending = moments[0][:, None] * np.cos(angle) + moments[1][:, None] * np.sin(angle)
    return scene.axial_tension / model.props["steel_area"] + scale * bending


def fibre_damage(point: DesignPoint, model: WhirlModel, window: Window, station: float, starts,
                 correction: bool = True, masked: np.ndarray | None = None,
                 pulses: np.ndarray | None = None) -> np.ndarray:
    """(S, F) Miner's damage [-] in each of the stretches that begin at the window's rows ``starts`` (its cycles), of
    each fibre of :func:`fibre_stress` at x = ``station`` [m]: the fibre's stress history over the whole window
    counted by rainflow (ASTM E1049, :func:`study.physics.limits.history_damage` with the point's strengths, stress
    concentration, S-N curve and mean-stress correction), each cycle's damage spread over the stretches the time
    between its two reversals spans, so that several cycles a revolution (impacts ringing the pipe) count each, a
    periodic motion's revolutions get the same damage, and the stretches' damages sum to the window's."""
    stress = fibre_stress(point, model, window, station, correction, masked=masked, pulses=pulses)
    options = point.limits.keywords()
    return np.column_stack([limits.history_damage(stress[:, k], starts, at=window.times, **options)
                            for k in range(stress.shape[1])])


def window_summary(cycles: list[Mapping[str, Any]], stats: Mapping[str, Mapping[str, Any]]) -> dict[str, Any]:
    """The stress outputs of the window from its cycles' (:func:`cycle_values`): the design figures as
    :func:`settling` states them (the mean over the cycles) and their largest values; the max bending stress
    the mean of the cycles' too (so that normal = axial + bending holds); the largest shear stress over the
    window (a bound); positions and times (from the window's start) of the cycle with the
    largest normal (alternating) stress; the modal tail and quarter fractions the means over the cycles;
    ``correction`` whether the quasi-static correction was applied in every cycle."""
    out = {name: s["value"] for name, s in stats.items()}
    out.update({largest: stats[name]["largest"] for name, (largest, _) in FIGURES.items()})
    origin = cycles[0]["start"]
    worst = cycles[int(np.argmax([c["max_normal_stress"] for c in cycles]))]
    alternating = cycles[int(np.argmax([c["alternating_bending_stress"] for c in cycles]))]
    sheared = cycles[int(np.argmax([c["max_shear_stress"] for c in cycles]))]
    out.update(max_bending_stress=float(np.mean([c["max_bending_stress"] for c in cycles])),
               max_wall_excess=float(np.max([c["max_wall_excess"] for c in cycles])),
               max_normal_stress_x=worst["max_normal_stress_x"],
               max_normal_stress_t=worst["max_normal_stress_t"] + worst["start"] - origin,
               alternating_bending_stress_x=alternating["alternating_bending_stress_x"],
               max_shear_stress=sheared["max_shear_stress"], max_shear_stress_x=sheared["max_shear_stress_x"],
               max_shear_stress_t=sheared["max_shear_stress_t"] + sheared["start"] - origin,
               modal_tail_fraction=float(np.mean([c["modal_tail_fraction"] for c in cycles])),
               modal_quarter_fraction=float(np.mean([c["modal_quarter_fraction"] for c in cycles])),
               correction=all(c["correction"] for c in cycles))
    return out


def batch_count(n: int) -> int:
    """The number of batch means :func:`standard_error` takes over n values (batches of ⌊√n⌋ values each)."""
    return int(n) // max(1, int(np.sqrt(n)))


def standard_error(x) -> float:
    """Standard error of the mean of the series x: the larger of the batch-means estimate (:func:`batch_count`
    batches of ⌊√n⌋ consecutive values, the first values dropped to make them whole; Schmeiser 1982,
    doi:10.1287/opre.30.3.556), which holds where consecutive values are correlated, and the plain s/√n, which is
    steadier where the batches are few. 0 for a constant series, NaN for fewer than two values."""
    x = np.asarray(x, float)
    if x.size < 2:
        return float("nan")
    plain = float(np.std(x, ddof=1) / np.sqrt(x.size))
    size = max(1, int(np.sqrt(x.size)))
    count = batch_count(x.size)
    if count < 2:
        return plain
    means = x[x.size - count * size:].reshape(count, size).mean(axis=1)
    return max(plain, float(np.std(means, ddof=1) / np.sqrt(count)))


def batch_quantile(batches: int, level: float = CONFIDENCE_LEVEL) -> float:
    """Standard errors [-] in the two-sided ``level`` bound of a mean by batch means: Student's t quantile on b − 1
    degrees of freedom for b ``batches`` (at least 2; the batch-means interval, Schmeiser 1982,
    doi:10.1287/opre.30.3.556)."""
    return float(student_t.ppf(0.5 + level / 2.0, max(int(batches), 2) - 1))


def confidence(n: int, level: float = CONFIDENCE_LEVEL) -> float:
    """Standard errors [-] in the two-sided ``level`` bound of the mean of n values by :func:`standard_error`:
    :func:`batch_quantile` on its :func:`batch_count` batches: 4.30 for 6 values (three batches of two), 3.18 for 12
    and 18, 2.57 for 24-48, 2.26 for 100, towards 1.96."""
    return batch_quantile(batch_count(n), level)


def revolutions_for(length: int, window: int, part: float, room: float) -> float:
    """Revolutions more [-] a record of ``length`` revolutions, whose window of ``window`` of them states ``part``
    (:func:`confidence` standard errors of its mean), is foreseen to need for that part to fall to ``room``: the
    standard error s falls as the root of the window's length and the bound's t quantile with its batches, so the
    window grows to the least w' with t s √(window / w') ≤ room (t on ⌊√w'⌋ − 1 degrees of freedom, the fewest
    batches w' values give, so that the bound falls with w'), the record in proportion. 0 where ``part`` is within
    ``room``; inf where no window of fewer than 10⁹ revolutions reaches it."""
    if part <= room:
        return 0.0
    error = part / confidence(window)

    def bound(w: int) -> float:
        return batch_quantile(int(np.sqrt(w))) * error * np.sqrt(window / w)

    low, high = window, 2 * window
    while bound(high) > room:
        low, high = high, 2 * high
        if high > 1e9:
            return float("inf")
    while high - low > 1:  # bound(low) > room >= bound(high)
        middle = (low + high) // 2
        low, high = (low, middle) if bound(middle) <= room else (middle, high)
    return length * (high / window - 1.0)


def settle_ratio(states, scale) -> float:
    """Per-revolution ratio ρ by which the change of the state from one revolution boundary to the next shrinks
    while the motion settles, taken at the slow end of what the data allow: exp of the least-squares slope of the
    change's logarithm over the later half of the revolutions run, plus two of its standard errors, at most
    :data:`MAX_SETTLE_RATIO`. NaN where the changes do not shrink beyond doubt (that bound is 1 or more: a
    stationary or wandering motion) or there are fewer than six of them."""
    S = np.asarray(states) / scale
    change = np.max(np.abs(np.diff(S, axis=0)), axis=1)
    change = change[change.size // 2:]
    k = np.flatnonzero(change > 0)
    if k.size < 6:
        return float("nan")
    (slope, _), cov = np.polyfit(k, np.log(change[k]), 1, cov=True)
    upper = float(np.exp(slope + 2.0 * np.sqrt(cov[0, 0])))
    return min(upper, MAX_SETTLE_RATIO) if upper < 1.0 else float("nan")


def settling(window: list[Mapping[str, Any]], preceding: list[Mapping[str, Any]],
             ratio: float = float("nan")) -> dict[str, dict[str, Any]]:
    """Per design figure (:data:`FIGURES`, and :data:`DAMAGE` where the cycles carry it: per fibre, the fibre of the
    largest mean over the window taken, ``fibre``), from its per-cycle values over the window and the preceding
    stretch of equal length (empty when the motion is periodic, or taken as stationary): ``value`` (the mean over
    the window's cycles), ``largest`` (over them), ``error`` (relative standard error of the mean by batch means),
    ``confidence`` (the standard errors in its 95 % bound, :func:`confidence`),
    ``drift`` (relative difference of the window's and the preceding stretch's means), ``significant`` (that
    difference is more than :data:`DRIFT_SIGNIFICANCE` combined standard errors: still settling) and ``window``, the
    window's part of the figure's error: the larger of ``confidence`` standard errors and the drift, and where the
    motion settles (the state's changes shrink by ``ratio`` ρ a revolution, :func:`settle_ratio`) with the drifts still
    to come if they shrink alike, drift/(1 − ρ^h) for a window of h revolutions."""
    out = {}
    h = len(window)
    bound = confidence(h)  # the same window for every figure
    settles = bool(np.isfinite(ratio))  # the state's changes shrink: it settles
    for name in (*FIGURES, DAMAGE):
        if name not in window[0]:
            continue
        x = np.array([v[name] for v in window], float)
        fibre = None
        if x.ndim == 2:  # the damage per fibre: the fibre of the largest mean over the window
            fibre = int(np.argmax(np.mean(x, axis=0)))
            x = x[:, fibre]
        value, largest = float(np.mean(x)), float(np.max(x))
        size = max(abs(value), 1e-300)
        error = standard_error(x) if np.ptp(x) > 0 else 0.0
        drift, significant = 0.0, False
        if preceding:
            before = np.array([v[name] for v in preceding], float)
            before = before[:, fibre] if fibre is not None else before
            change = abs(value - float(np.mean(before)))
            spread = np.hypot(np.nan_to_num(error, nan=np.inf), standard_error(before) if np.ptp(before) > 0 else 0.0)
            drift, significant = change / size, bool(change > DRIFT_SIGNIFICANCE * spread)
        error = error / size if np.isfinite(error) else np.inf
        part = max(bound * error, drift / (1.0 - ratio**h) if settles else drift)
        out[name] = dict(value=value, largest=largest, error=error, confidence=bound, drift=drift,
                         significant=significant, window=float(part))
        if fibre is not None:
            out[name]["fibre"] = fibre
    return out


#: The figures whose modal part :func:`modal_check` measures: the design figures, the bending stress and the deflection.
MODAL_FIGURES = ("peak_contact_force", "max_normal_stress", "alternating_bending_stress", "max_bending_stress",
                 "max_deflection")


def quasi_static_ratio(model: WhirlModel, window: Window) -> float:
    """(2π/(ω_{N+1} T_c))², at most 1: how far the first mode left out is from responding statically to the window's
    contacts, T_c the shortest mean contact (contact time over onsets per touching point; the window's length for a
    contact held throughout). A mode of frequency ω under a force that changes over a time T responds statically but
    for a remainder of relative size (2π/(ω T))² (its static response's second derivative over ω²); a held contact's
    is nil, an impact's (shorter than that mode's period) the whole. 0 without contact."""
    touching = window.contact_time > 0
    if not np.any(touching):  # clear of the wall: the joints' inertia forces corrected, their frequency Ω's
        if model.joint_points is None or np.any(window.onsets > 0):
            return 0.0
        return float(min(1.0, (model.rotary_speed / model.first_left_out()) ** 2))
    durations = window.contact_time[touching] / np.maximum(window.onsets[touching], 1)
    ratio = 2.0 * np.pi / (model.first_left_out() * float(np.min(durations)))
    return float(min(1.0, ratio**2))


def quasi_static_applies(model: WhirlModel, window: Window) -> bool:
    """Whether the quasi-static correction of the modes left out (:func:`static_correction`) enters the window's
    stresses: wherever a contact force acts in it. It is applied to every contact force at every instant, in step
    with the residual flexibility the contact's spring has in series (:func:`residual_flexibility`), and is not
    switched on or off by the contacts' durations (docs/reference_model.md §2.1, §3). Without contact: where the tool
    joints' mass is lumped (their inertia forces, point loads of the motion's own frequencies, are completed
    statically: :func:`joint_inertia_forces`), else False (nothing to correct)."""
    return bool(np.any(window.contact_time > 0) or np.any(window.onsets > 0) or model.joint_points is not None)


def modal_check(point: DesignPoint, model: WhirlModel, window: Window,
                cycles: list[Mapping[str, Any]]) -> dict[str, float]:
    """The modal part of each figure's error (relative), measured on the run (docs/reference_model.md §3.1): the size
    of what the modes left out were given — the quasi-static correction of the fields and the residual flexibility in
    series with the contacts (:func:`residual_flexibility`) — times :func:`quasi_static_ratio`, how far they are from
    responding statically (1 at impacts: the whole correction; nil for held contacts, where it is exact). Stresses
    and deflection: the cycles' figures from the same motion and forces without the correction (kept per cycle by
    :func:`cycle_values`, ``uncorrected``, on the cycle's own rows; else recomputed over the window), the mean
    over the cycles of each cycle's difference over the figure's mean (the largest deflection: its difference).
    Peak contact force: at each cycle's largest recorded force, the Hertz force K d^{3/2} at the contact's total
    approach d against the series force there (:func:`series_contact`), the mean of their relative differences: how
    much the flexibility of the modes left out softened the contact. Both vanish as the modes grow (the residual
    flexibility like N⁻³). Zeros without contact."""
    out = dict.fromkeys(MODAL_FIGURES, 0.0)
    ratio = quasi_static_ratio(model, window)
    if not cycles or window.times.size == 0 or ratio == 0.0:
        return out
    first = np.searchsorted(window.times, [c["start"] for c in cycles])
    segments = list(zip(first, list(first[1:]) + [window.times.size]))
    if all("uncorrected" in c for c in cycles):  # kept per cycle by cycle_values, on the cycle's own rows
        plain = [c["uncorrected"] for c in cycles]
    else:
        plain = stresses(point, model, window, correction=False, segments=segments)
    for name in ("max_normal_stress", "alternating_bending_stress", "max_bending_stress"):
        mean = float(np.mean([c[name] for c in cycles]))
        if name == "alternating_bending_stress":  # relative to the bending it alternates within (convergence)
            mean = max(mean, float(np.mean([c["max_bending_stress"] for c in cycles])))
        if mean > 0:
            out[name] = ratio * float(np.mean([abs(a[name] - c[name]) for a, c in zip(plain, cycles)]) / mean)
    largest = max(c["max_deflection"] for c in cycles)
    if largest > 0:
        out["max_deflection"] = ratio * abs(max(a["max_deflection"] for a in plain) - largest) / largest
    # the peak force: the Hertz force at each cycle's largest recorded force's total approach against the series one
    N = model.n_modes
    flexibility = model.flexibility if np.any(model.flexibility > 0) else residual_flexibility(model)
    fn = window.forces[:, :, 2]
    changes = []
    for a, b in segments:
        if b <= a or not np.any(fn[a:b] > 0):
            continue
        row, p = np.unravel_index(int(np.argmax(fn[a:b])), fn[a:b].shape)
        q = window.states[a + row]
        d = float(np.hypot(model.phi[p] @ q[:N], model.phi[p] @ q[N:2 * N]) - model.clearance[p])
        if d <= 0:
            continue
        series = float(series_contact(np.array([d]), model.stiffness[p], flexibility[p])[1][0])
        hertz = float(hertz_force(d, model.stiffness[p]))
        if model.law == 0 and series > 0:
            changes.append(hertz / series - 1.0)
    out["peak_contact_force"] = ratio * float(np.mean(changes)) if changes else 0.0
    return out


def strike_modal_part(cycles: list[Mapping[str, Any]], modal: Mapping[str, float] | None) -> dict[str, float] | None:
    """The modal part of the figures' errors with the strikes' peak forces from their local model (``cycles`` of
    :func:`cycle_values` with ``reference_strike_force = "local"``; docs/reference_model.md §2.3): the peak force's is
    its onset speed's, the upper half of the kept modes' share of it (:func:`strike_speeds`) times
    :data:`SPEED_EXPONENT`, the mean over the cycles whose peak a strike's local model gave; beside it
    ``peak_contact_force_local`` the local model's own part, :data:`LOCAL_STRIKE_ERROR`. The other figures' as
    ``modal`` states them. ``modal`` unchanged where no cycle's force came from a strike's local model."""
    taken = [c["strikes"] for c in cycles if c.get("strikes") and c["strikes"]["count"] > 0]
    if not taken:
        return modal
    out = dict(modal or {})
    out["peak_contact_force"] = SPEED_EXPONENT * float(np.mean([t["speed_share"] for t in taken]))
    out["peak_contact_force_local"] = LOCAL_STRIKE_ERROR
    return out


def strike_stress_modal_part(cycles: list[Mapping[str, Any]], modal: Mapping[str, float] | None
                             ) -> dict[str, float] | None:
    """The stresses' modal part with the strikes' local bending (``reference_strike_stress = "local"``, cycles of
    :func:`cycle_values` carrying ``strike_modal``; docs/reference_model.md §2.3): per stress figure, the mean over
    the cycles of the struck stations' error (:func:`strike_stress_values`) plus the quasi-static correction of the
    loads that are not strikes times :func:`quasi_static_ratio`, over the figure's mean (the alternating stress's over
    the larger of it and the max bending stress, as :func:`modal_check`'s). The other figures as ``modal`` states them;
    ``modal`` unchanged where no cycle carries a struck joint's correction."""
    taken = [c for c in cycles if "strike_modal" in c]
    if not taken:
        return modal
    out = dict(modal or {})
    for name in ("max_normal_stress", "alternating_bending_stress", "max_bending_stress"):
        mean = float(np.mean([c[name] for c in cycles]))
        if name == "alternating_bending_stress":
            mean = max(mean, float(np.mean([c["max_bending_stress"] for c in cycles])))
        if mean > 0:
            out[name] = float(np.sum([c["strike_modal"][name]["change"] + c["strike_modal"][name]["rest"]
                                      for c in taken]) / len(cycles) / mean)
    return out


#: A bending stress below this share of the max normal stress is nothing (the rounding of a string whirling as a
#: rigid body): its error parts are counted relative to the normal stress (:func:`convergence`).
NEGLIGIBLE_BENDING = 1e-9


def convergence(point: DesignPoint, model: WhirlModel, window: Window, values: Mapping[str, Any],
                stats: Mapping[str, Mapping[str, Any]], periodic: bool, residual: float | None = None,
                modal: Mapping[str, float] | None = None) -> dict:
    """The error of each design figure by its parts (relative; docs/reference_model.md §3.1): ``window`` (the
    larger of the standard error and the drift from the preceding stretch; the periodicity tolerance when the
    motion is periodic), ``integrator`` (the larger of rtol and the energy balance's residual over the window,
    which is whole but with ``reference_damping = "viscous"`` and ``reference_residual = "radiating"``),
    ``modes`` (measured on the run, :func:`modal_check`, given as ``modal``; 0 where not given); ``total`` their
    sum; ``equivalent`` the total as the stress error the point's ``error_estimate`` counts (:func:`stress_equivalent`:
    the damage's through the S-N exponent, the peak force's as its share of ``solver.force_tolerance``). The
    alternating stress's error is relative to the larger of it and the max bending stress."""
    option = point.reference
    # the energy balance is whole only without the linear modal damping of "viscous" and "drag+viscous" and the residual
    # vectors' radiation damping ("radiating"), whose loss is not integrated
    whole = (residual is not None and option.reference_damping not in ("viscous", "drag+viscous")
             and option.reference_residual != "radiating")
    integrator = max(float(option.reference_rtol), abs(residual) if whole else 0.0)
    normal = values["max_normal_stress"]
    modes = {name: float((modal or {}).get(name, 0.0)) for name in FIGURES}
    # an alternating stress far below the bending stress (a synchronous whirl's remnant) is counted relative to the
    # bending it alternates within, as the modal part is: its relative size alone would make noise of nothing; and a
    # bending stress below NEGLIGIBLE_BENDING of the normal stress (the rounding of a string whirling as a rigid body,
    # 1e-11 Pa) relative to that
    floor = NEGLIGIBLE_BENDING * normal
    if values["max_bending_stress"] < floor:
        modes = {name: 0.0 for name in modes}
    scale = {"alternating_bending_stress": max(values["alternating_bending_stress"], values["max_bending_stress"],
                                               floor)}
    # the damage goes as the stress to the S-N curve's power m: the stresses' integrator and modal parts as damage
    exponent = fatigue.damage_exponent(point.limits.sn_curve or "B1")
    # the peak force is held to its own tolerance: its error counts in the point's as its share of it
    # (stress_equivalent)
    force_share = (point.tolerances.tolerance if periodic else point.tolerances.statistical) / point.tolerances.force
    modes[DAMAGE] = (1.0 + modes["alternating_bending_stress"]) ** exponent - 1.0
    # the damage rate goes as the alternating stress to the power m: its window part, as the stress error that makes
    # it, is counted relative to the bending the stress alternates within, as the alternating stress's is (a
    # synchronous whirl's remnant of tens of Pa has a damage rate whose relative scatter is large and means nothing)
    alternating_share = min(1.0, values["alternating_bending_stress"] / scale["alternating_bending_stress"]
                            if scale["alternating_bending_stress"] > 0 else 1.0)
    out = {}
    for name, s in stats.items():
        share = abs(s["value"]) / scale[name] if scale.get(name, 0) > 0 else 1.0
        window_part = float(option.reference_tolerance) if periodic else s["window"] * share
        if name == DAMAGE and not periodic:
            window_part = (1.0 + stress_equivalent(DAMAGE, s["window"], exponent) * alternating_share) ** exponent - 1.0
        own = (1.0 + integrator) ** exponent - 1.0 if name == DAMAGE else integrator
        parts = dict(window=window_part, integrator=own, modes=modes[name])
        if name == "peak_contact_force" and "peak_contact_force_local" in (modal or {}):
            parts["local"] = float(modal["peak_contact_force_local"])  # the strikes' local model's own (§2.3)
        total = float(sum(parts.values()))
        out[name] = dict(parts, total=total, dominant=max(parts, key=parts.get),
                         equivalent=stress_equivalent(name, total, exponent, force_share))
    return out


def stress_equivalent(name: str, error: float, exponent: float, force_share: float = 1.0) -> float:
    """A figure's relative error as the stress error that makes it: the damage's (:data:`DAMAGE`) (1 + e)^(1/m) − 1
    (D ∝ σ^m); the peak contact force's its share of its own tolerance (``solver.force_tolerance``) in the point's,
    e × ``force_share`` (the point's tolerance over the force's); the stress figures' the error itself. The point's
    ``error_estimate`` is the largest of these, held against the tolerance as a stress error."""
    if name == DAMAGE:
        return float((1.0 + error) ** (1.0 / exponent) - 1.0)
    return float(error * force_share) if name == "peak_contact_force" else float(error)


def figure_tolerance(name: str, tolerance: float, exponent: float, force: float | None = None) -> float:
    """The relative error a figure may have at the stress ``tolerance``: the damage's (:data:`DAMAGE`) (1 + tolerance)^m
    − 1 (27.6 % for 5 % on m = 5), the peak contact force's its own tolerance ``force`` (``solver.force_tolerance``,
    :func:`study.solvers.model.options.force_tolerance`; the stress tolerance where None), the others' the tolerance."""
    if name == DAMAGE:
        return float((1.0 + tolerance) ** exponent - 1.0)
    return float(force) if name == "peak_contact_force" and force is not None else float(tolerance)


def whirl_measure(model: WhirlModel, window: Window) -> dict[str, Any]:
    """Whirl rate over Ω of the most-touching contact point (midspan without contact) and its verdict:
    no_contact; sliding (in contact nearly all the time, |rate| < 0.05 Ω: lying on the wall); forward
    (rate > 0.5 Ω); backward (rate < −0.5 Ω); otherwise bouncing (impacts without a settled whirl)."""
    N = model.n_modes
    if np.any(window.contact_time > 0):
        p = int(np.argmax(window.contact_time))
        shape = model.phi[p]
        where = float(model.points[p])
    else:
        p, where = -1, 0.5 * model.span
        shape = model.shapes(where)[0]
    y = window.states[:, :N] @ shape
    w = window.states[:, N:2 * N] @ shape
    angle = np.unwrap(np.arctan2(w, y))
    duration = window.times[-1] - window.times[0]
    ratio = float((angle[-1] - angle[0]) / (model.rotary_speed * duration)) if duration > 0 else float("nan")
    if not np.any(window.onsets > 0) and not np.any(window.contact_time > 0):
        verdict = "no_contact"
    elif abs(ratio) < SLIDING_RATE and window.any_contact_time >= SLIDING_CONTACT * duration:
        verdict = "sliding"
    elif ratio > 0.5:
        verdict = "forward"
    elif ratio < -0.5:
        verdict = "backward"
    else:
        verdict = "bouncing"
    return dict(whirl_frequency_ratio=ratio, whirl=verdict, whirl_point=where)
