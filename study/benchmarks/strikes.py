"""The strikes' local model against the modes (docs/reference_model.md §2.3): the tables' commands.

    python -m study.benchmarks.strikes replays A,B,C 16,32,64 256 out.jsonl
        strikes of bouncing points of configs/default.toml (their runs at each count), each replayed from the run's
        recorded state at every count up to the last (:func:`study.solvers.methods.reference.replay.lift_state`): the
        local model's peak from the run's onset speed, the replays' peaks and onset speeds
    python -m study.benchmarks.strikes sample 12 modes,local,pulse out.jsonl outputs/default/results.nc
            ['{"reference_modes": 128}']
        bouncing reference points of the default study's last sweep (its results.nc, `make sweep`), evenly in the
        sweep's order, each solved with ``solve_point(..., "reference")`` for each ``reference_strike_force``
        (cap 300 s; a capped run is reported failed, solve_point catching the alarm); an option "local/local" sets
        ``reference_strike_stress`` after the slash
    python -m study.benchmarks.strikes sample-at 274,515,687,201 modes,local out.jsonl RESULTS
            '{"reference_modes": 128, "reference_max_modes": 128}'
        the same at the points of those flat indices of the results (cap 1200 s)

    python -m study.benchmarks.strikes recover 274,515,687,201 128 12 out.jsonl
        one motion recovered with fewer modes and with the stresses' band (docs/reference_model.md §2.3.1): each point
        of those flat indices of the default study's grid run at that fixed mode count (``reference_strike_force =
        "pulse"``, ``reference_strike_stress = "local"``, that many revolutions at most), its window's states projected
        onto the first n basis functions (n = 32, 64 and the count) and its stresses recovered with the n-mode model,
        ``reference_stress_band`` "all" and "timoshenko": the means over the window's revolutions and their standard
        errors [MPa]

    python -m study.benchmarks.strikes where 212,229,252,292,332 64,128 out.jsonl
            ['{"reference_max_revolutions": 160}']
        where the strikes of points of the default study's grid at those flat indices are, at each fixed mode count
        (``reference_strike_force = "pulse"``, ``reference_strike_stress = "local"``): per contact point its strikes
        and pulses per revolution, its mean largest force in a revolution (and its pulses' peak) and the share of
        revolutions whose peak it carries, and by the contact law (:func:`strike_sites`)

    python -m study.benchmarks.strikes thrown none,series 16,32,64,128,256 out.jsonl
        the thrown string's bending under a joint from the modes, with the strike's correction and by default
        (docs/reference_model.md §2.3.1)

One JSON line a strike or a point; the CPU seconds are the process's own.
"""

from __future__ import annotations

import json
import signal
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]


def default_grid():
    """configs/default.toml's grid, its points by flat index as the sweep numbers them (the results' flat index)."""
    from study import config
    from study.workflow.sweep import study_grid

    return study_grid(config.load(ROOT / "configs" / "default.toml"))
#: Bouncing points of configs/default.toml (rpm, klbf, restitution, ppg, ft/s, °/100 ft), as docs/reference_model.md
#: §2.2 names them.
POINTS = {"A": (250, 5, 0.7, 9, 0.0, 0.0), "B": (300, 10, 0.7, 12, 7.4, 0.0), "C": (275, 5, 0.3, 9, 0.0, 3.0)}


def point_inputs(study, rpm, klbf, restitution, ppg, flow, dogleg):
    """The SI inputs of a point of ``study`` from the config's units."""
    return study.point(rotary_speed=rpm * np.pi / 30, axial_tension=klbf * 4448.2216152605, restitution=restitution,
                       mud_density=ppg * 119.826427, mud_flow_velocity=flow * 0.3048,
                       dogleg_curvature=dogleg * np.pi / 180 / 30.48)


def replays(names, counts, top, out):
    from study import config
    from study.physics import strike
    from study.solvers.methods.reference import replay as rp
    from study.solvers.methods.reference.integrate import Integrator, merge
    from study.solvers.methods.reference.method import simulate
    from study.solvers.methods.reference.model import build_model
    from study.solvers.methods.reference.statistics import strike_speeds
    from study.solvers.model.options import ReferenceOptions

    study = config.load(ROOT / "configs" / "default.toml")
    for name in names:
        base = point_inputs(study, *POINTS[name])
        for N in counts:
            inputs = {**base, "reference_modes": N, "reference_max_modes": N}
            option = ReferenceOptions.from_inputs(inputs)
            run = simulate(inputs)
            model, window, cycles = run["model"], run["window"], run["cycles"]
            picks = rp.impacts(window, [c["start"] for c in cycles],
                               longest=rp.REPLAY_LONGEST * 2 * np.pi / model.first_left_out())
            rows, points, speed, part = strike_speeds(model, window)
            models = {N: model}
            for onset, row, p in picks:
                k = np.flatnonzero((rows == onset + 1) & (points == p))
                if model.kinds[p] != 1 or k.size == 0:
                    continue
                end = row
                while end < window.times.size - 1 and window.forces[end, p, 2] > 0:
                    end += 1
                duration = rp.REPLAY_SPAN * float(window.times[end] - window.times[onset]) + rp.REPLAY_MARGIN
                local, tc = strike.peak_force([speed[k[0]]], model.joint_mass, model.stiffness[p],
                                              model.props["mass_per_length"], model.props["bending_stiffness"],
                                              model.hysteresis)
                record = dict(point=name, N=N, start=float(window.times[onset]), p=int(p), v0=float(speed[k[0]]),
                              part=float(part[k[0]]), own=float(np.max(window.forces[onset:end + 1, p, 2])),
                              local=float(local[0]), local_duration=float(tc[0]),
                              run_contact=float(window.times[end] - window.times[onset]), replays={})
                for n in [c for c in (16, 32, 64, 128, 256, 512) if N <= c <= top]:
                    if n not in models:
                        models[n] = build_model({**inputs, "reference_modes": n})
                    z = window.states[onset] if n == N else rp.lift_state(model, models[n], window.states[onset],
                                                                          window.forces[onset])
                    clock = time.process_time()
                    integ = Integrator(models[n], float(option.reference_rtol), z, option.reference_integrator)
                    integ.t = float(window.times[onset])
                    pieces = [integ.run(integ.t + duration, record=True)]
                    for _ in range(4):
                        if not integ.active[p] or integ.outcome != 0:
                            break
                        pieces.append(integ.run(integ.t + duration, record=True))
                    w = merge(pieces)
                    r2, p2, s2, _ = strike_speeds(models[n], w)
                    first = np.flatnonzero(p2 == p)
                    record["replays"][n] = dict(peak=float(np.max(w.forces[:, p, 2])),
                                                v0=float(s2[first[0]]) if first.size else float("nan"),
                                                onset=float(w.times[r2[first[0]]]) if first.size else float("nan"),
                                                cpu=time.process_time() - clock)
                print(json.dumps(record), file=out, flush=True)


def result_points(ds):
    """The coordinates of the point at flat index i of a sweep's results ``ds`` (its variables' order), as
    ``study.point`` takes them: a function of i."""
    from study.workflow.grid import Grid

    grid = Grid(base={}, axes={d: ds[d].values for d in ds["method"].dims})  # the sweep's grid, the same C order
    return lambda i: {d: float(v) for d, v in grid.point(int(i)).items()}


def sample(count, options, out, results, extra=None, indices=None, cap=300):
    import xarray as xr

    from study import config
    from study.solvers import solve_point
    from study.solvers.model.result import REGIMES

    ds = xr.open_dataset(results)
    study = config.load(ROOT / "configs" / "default.toml")
    bouncing = ((ds["method"].values.reshape(-1) == "reference")
                & (ds["regime"].values.reshape(-1) == REGIMES["bouncing"]))
    found = np.flatnonzero(bouncing)
    picks = found[np.linspace(0, found.size - 1, count).round().astype(int)] if indices is None else np.asarray(indices)
    point_coords = result_points(ds)

    def stop(*_):
        raise TimeoutError

    signal.signal(signal.SIGALRM, stop)
    for i in picks:
        coords = point_coords(i)
        for option in options:
            clock = time.process_time()
            signal.alarm(cap)
            try:
                force, _, stress = option.partition("/")  # "local/local": the force's option, then the stresses'
                r = solve_point({**study.point(**coords), "reference_strike_force": force,
                                 **({"reference_strike_stress": stress} if stress else {}), **(extra or {})},
                                "reference")
            except TimeoutError:
                print(json.dumps(dict(index=int(i), coords=coords, option=option, status="timeout")), file=out,
                      flush=True)
                continue
            finally:
                signal.alarm(0)
            conv = r.extras.get("convergence", {})
            print(json.dumps(dict(
                index=int(i), coords=coords, option=option, extra=extra or {}, status=r.status,
                error_estimate=r.error_estimate, modes=r.extras.get("reference_modes"), whirl=r.extras.get("whirl"),
                cpu=time.process_time() - clock, strike_pulses=r.extras.get("strike_pulses"),
                steps=r.extras.get("steps"),
                values={k: float(r.values.get(k, np.nan)) for k in ("peak_contact_force", "max_normal_stress",
                                                                    "alternating_bending_stress", "damage_rate",
                                                                    "max_bending_stress",
                                                                    "window_revolutions", "impacts_per_revolution")},
                convergence={k: {p: float(v) for p, v in e.items() if isinstance(v, (int, float))}
                             for k, e in conv.items()})), file=out, flush=True)


def revolution_windows(model, w):
    """The recorded window ``w`` (:class:`~study.solvers.methods.reference.integrate.Window`) cut into its
    revolutions (those of 10 rows or more), each a Window of its rows, its peaks the rows' largest normal forces."""
    from study.solvers.methods.reference.integrate import Window

    turn = np.floor((w.times - w.start) / model.period + 1e-9).astype(int)
    for j in np.unique(turn):
        rows = np.flatnonzero(turn == j)
        if rows.size >= 10:
            at = slice(rows[0], rows[-1] + 1)
            yield Window(times=w.times[at], states=w.states[at], forces=w.forces[at],
                         peak=np.max(w.forces[at, :, 2], axis=0), onsets=np.zeros(w.forces.shape[1], int),
                         contact_time=np.zeros(w.forces.shape[1]), any_contact_time=0.0,
                         start=float(w.times[rows[0]]), end=float(w.times[rows[-1]]))


def recover(indices, count, revolutions, out):
    from study.solvers.methods.reference.integrate import Window
    from study.solvers.methods.reference.method import simulate
    from study.solvers.methods.reference.model import build_model
    from study.solvers.methods.reference.statistics import cycle_values

    grid = default_grid()

    def projected(small, big, w):  # the states on the first n basis functions, in the n-mode model's modes
        N, n = big.n_modes, small.n_modes
        to_basis = big.basis if big.basis is not None else np.eye(N)
        modes = small.basis if small.basis is not None else np.eye(n)
        blocks = [np.linalg.solve(modes, (w.states[:, j * N:(j + 1) * N] @ to_basis.T)[:, :n].T).T for j in range(4)]
        return Window(times=w.times, states=np.hstack(blocks + [w.states[:, 4 * N:]]), forces=w.forces, peak=w.peak,
                      onsets=w.onsets, contact_time=w.contact_time, any_contact_time=w.any_contact_time,
                      start=w.start, end=w.end)

    for i in indices:
        inputs = {**grid.point(int(i)), "reference_strike_force": "pulse",
                  "reference_strike_stress": "local", "reference_modes": count, "reference_max_modes": count,
                  "reference_max_revolutions": revolutions}
        clock = time.process_time()
        run = simulate({**inputs, "reference_stress_band": "all"})
        cycles = list(revolution_windows(run["model"], run["window"]))
        record = dict(index=int(i), N=count, revolutions=len(cycles), cpu=time.process_time() - clock)
        for n in sorted(n for n in {32, 64, count} if n <= count):  # the counts the run has modes for
            for band in ("all", "timoshenko"):
                small = build_model({**inputs, "reference_modes": n, "reference_stress_band": band})
                values = cycle_values(inputs, small, [projected(small, run["model"], c) for c in cycles])
                for name in ("max_normal_stress", "alternating_bending_stress"):
                    x = np.array([v[name] for v in values]) / 1e6
                    record[f"{n}/{band}/{name}"] = [float(np.mean(x)), float(np.std(x, ddof=1) / np.sqrt(x.size))]
                record[f"{n}/{band}/in_band"] = int(np.sum(small.omega <= small.stress_band))
        print(json.dumps(record), file=out, flush=True)


def strike_sites(model, window) -> list[dict]:
    """Where a recorded ``window``'s strikes are (docs/reference_model.md §2.3.1, "Where the hard points strike"): per
    contact point of ``model`` (``kind`` "joint" or "body", ``x`` [m] along the section): ``strikes`` its contact
    onsets per revolution (the kernel's count), ``pulses`` those taken by the strike's pulse per revolution (a joint's
    onset row whose approach speed, :func:`~study.solvers.methods.reference.statistics.strike_speeds`, is at its
    pulse floor or over, ``reference_strike_force = "pulse"``; a restrike's row, where the contact law takes on a
    joint after its pulse from nil, counts among them where the record has it at nil: at 16 modes, whose joints hold
    their walls, more than the onsets), ``contact`` its mean contact time per onset [s],
    ``speed`` the mean onset speed of its strikes [m/s], ``duration`` the mean T_c of its pulses [s]; over the
    revolutions (:func:`revolution_windows`): ``force`` the mean of its largest recorded normal force in each [N]
    (the rows' largest: a pulse's peak between rows is missed by up to a few %), ``pulse_force`` the mean of its
    largest pulse's peak in each (the pulse table's F_peak at the onset speed, as the kernel takes it; 0 in a
    revolution without one) [N], ``carries`` the share of the revolutions whose largest force is its own, and
    ``law_carries`` the share whose largest force is its own and over its largest
    pulse's peak there (a force of the contact law: a strike under the pulse floor, a contact held on after a pulse,
    or on the body)."""
    from study.solvers.methods.reference.statistics import strike_speeds

    cycles = list(revolution_windows(model, window))
    starts = np.array([c.start for c in cycles])
    peaks = np.array([c.peak for c in cycles])  # (revolutions, P)
    top = np.argmax(peaks, axis=1)
    turns = (window.end - window.start) / model.period
    rows, points, speed, _ = strike_speeds(model, window)
    turn = np.searchsorted(starts, window.times[rows], side="right") - 1
    pulsed = np.zeros(points.size, bool)
    pulse_peaks = np.zeros((len(cycles), model.points.size))
    durations = np.zeros(points.size)
    if model.pulse is not None:
        table = model.pulse
        pulsed = speed >= table["floor"][points]
        for j in np.flatnonzero(pulsed):
            p, x = points[j], np.log(min(speed[j], table["speeds"][-1]))
            f = np.exp(np.interp(x, np.log(table["speeds"]), np.log(table["peak"][p])))
            durations[j] = np.exp(np.interp(x, np.log(table["speeds"]), np.log(table["duration"][p])))
            if turn[j] >= 0:
                pulse_peaks[turn[j], p] = max(pulse_peaks[turn[j], p], f)
    law = peaks[np.arange(len(cycles)), top] > pulse_peaks[np.arange(len(cycles)), top]
    out = []
    for p in range(model.points.size):
        mine = points == p
        out.append(dict(point=p, kind="joint" if model.kinds[p] == 1 else "body", x=float(model.points[p]),
                        strikes=float(window.onsets[p] / turns), pulses=float(np.sum(mine & pulsed) / turns),
                        contact=float(window.contact_time[p] / max(window.onsets[p], 1)),
                        speed=float(np.mean(speed[mine])) if np.any(mine) else 0.0,
                        duration=float(np.mean(durations[mine & pulsed])) if np.any(mine & pulsed) else 0.0,
                        force=float(np.mean(peaks[:, p])), pulse_force=float(np.mean(pulse_peaks[:, p])),
                        carries=float(np.mean(top == p)), law_carries=float(np.mean((top == p) & law))))
    return out


def where(indices, counts, out, extra=None):
    """Per point of configs/default.toml's grid at those flat indices and per mode count: the run of
    :func:`~study.solvers.methods.reference.method.simulate` at that fixed count (``reference_strike_force`` "pulse",
    ``reference_strike_stress`` "local", or as ``extra`` sets) and :func:`strike_sites` of its window, with the window's
    revolutions, its largest body wall excess over the clearance (above the study's tolerance the solve would raise
    the body's stations), the kept modes' highest frequency [Hz] and the CPU seconds."""
    from study.solvers.methods.reference.method import pulse_summary, simulate

    grid = default_grid()
    for i in indices:
        for n in counts:
            inputs = {**grid.point(int(i)), "reference_strike_force": "pulse", "reference_strike_stress": "local",
                      "reference_modes": n, "reference_max_modes": n, **(extra or {})}
            clock = time.process_time()
            run = simulate(inputs)
            model, window = run["model"], run["window"]
            sites = strike_sites(model, window) if window is not None else []
            excess = max((c["max_wall_excess"] for c in run["cycles"]), default=np.nan)
            pulses = pulse_summary(model, run["integrator"]) if model.pulse is not None else {}
            print(json.dumps(dict(index=int(i), N=n, extra=extra or {}, verdict=run["verdict"], pulses=pulses,
                                  top_frequency=float(np.max(model.omega) / (2.0 * np.pi)),
                                  revolutions=float((window.end - window.start) / model.period) if window else 0.0,
                                  excess=float(excess / np.max(model.clearance)), sites=sites,
                                  cpu=time.process_time() - clock)), file=out, flush=True)


def thrown(residuals, counts, out):
    """The string of tests/solvers/test_modes.py thrown at 0.3 m/s onto its three joints (the default study's pipe at
    250 rpm, 5 klbf, 9 ppg, e 0.7, straight vertical hole, no damping; 4 ms recorded at 16 384 rows a revolution): the
    bending stress [MPa] under the first joint and on the body half the tool joint's length either side at the instant
    the local moment peaks after the onset, from the modes alone, with the strike's correction
    (``reference_strike_stress = "local"``'s, :func:`study.solvers.methods.reference.statistics.strike_moment_tables`),
    and the default fields' largest over the window (the quasi-static correction); the correction itself and with
    N/2 kept modes."""
    from study import config
    from study.physics import section, strike
    from study.solvers.methods import reference
    from study.solvers.methods.reference.fields import periodic_fields
    from study.solvers.methods.reference.statistics import strike_moment_tables, strike_stations
    from study.solvers.model.point import DesignPoint
    from study.solvers.model.scene import Scene

    study = config.load(ROOT / "configs" / "default.toml",
                        {"pipe.eccentricity_turn": "aligned", "contact.section_length": "93 ft"})
    inputs = {**point_inputs(study, 250, 5, 0.7, 9, 0.0, 0.0), "inclination": 0.0, "eccentricity": 0.0,
              "reference_damping": "none"}
    scene = Scene.from_inputs(inputs)
    scale = scene.outer_radius / float(section.second_moment_of_area(scene.outer_radius, scene.inner_radius)) / 1e6
    point = DesignPoint.from_inputs(inputs)
    speed, offsets = 0.3, strike_stations(point)
    for residual in residuals:
        for n in counts:
            clock = time.process_time()
            m = reference.build_model({**inputs, "reference_modes": n, "reference_residual": residual})
            z = np.zeros(4 * n + 4)
            z[0] = (float(np.min(m.clearance)) - 1e-5) / m.phi[0, 0]
            z[2 * n] = speed / m.phi[0, 0]
            w = reference.Integrator(m, 1e-8, z).run(0.004, record=True, rows_per_revolution=256 * 64)
            p = int(np.flatnonzero(m.kinds == 1)[0])
            xs = np.mod(m.points[p] + offsets, m.span)
            N = m.n_modes
            modes = periodic_fields(m, w.states[:, :N], None, xs, 0)["moment"]
            default = periodic_fields(m, w.states[:, :N], w.correction_forces(m, 0), xs, 0)["moment"]
            table, half = strike_moment_tables(point, m)[p], strike_moment_tables(point, m, kept=n // 2)[p]
            c, ch = strike.moment_correction([speed], table)[0], strike.moment_correction([speed], half)[0]
            onset = int(np.flatnonzero(w.forces[:, p, 2] > 0)[0])
            peaks = strike.moment_correction([speed], table, column=2)[0]
            rows = [int(np.argmin(np.abs(w.times - (w.times[onset] + t)))) for t in peaks]
            print(json.dumps(dict(
                residual=residual, N=n, peak_force=float(np.max(w.forces[:, p, 2])), t_peak=[float(t) for t in peaks],
                modes=[abs(float(modes[r, i])) * scale for i, r in enumerate(rows)],
                corrected=[abs(float(modes[r, i] - c[i])) * scale for i, r in enumerate(rows)],
                default=[float(np.max(np.abs(default[:, i]))) * scale for i in range(offsets.size)],
                correction=[float(x) * scale for x in c], correction_half=[float(x) * scale for x in ch],
                cpu=time.process_time() - clock)), file=out, flush=True)


if __name__ == "__main__":
    kind = sys.argv[1]
    if kind == "replays":
        with open(sys.argv[5], "a") as handle:
            replays(sys.argv[2].split(","), [int(x) for x in sys.argv[3].split(",")], int(sys.argv[4]), handle)
    elif kind == "sample":
        with open(sys.argv[4], "a") as handle:
            sample(int(sys.argv[2]), sys.argv[3].split(","), handle, sys.argv[5],
                   json.loads(sys.argv[6]) if len(sys.argv) > 6 else None)
    elif kind == "sample-at":  # the points of the results at these flat indices, each run capped at 1200 s
        with open(sys.argv[4], "a") as handle:
            sample(0, sys.argv[3].split(","), handle, sys.argv[5],
                   json.loads(sys.argv[6]) if len(sys.argv) > 6 else None,
                   indices=[int(i) for i in sys.argv[2].split(",")], cap=1200)
    elif kind == "recover":  # python -m study.benchmarks.strikes recover 274,515 128 12 out.jsonl
        with open(sys.argv[5], "a") as handle:
            recover([int(i) for i in sys.argv[2].split(",")], int(sys.argv[3]), int(sys.argv[4]), handle)
    elif kind == "where":  # python -m study.benchmarks.strikes where 212,229 64,128 out.jsonl ['{...}']
        with open(sys.argv[4], "a") as handle:
            where([int(i) for i in sys.argv[2].split(",")], [int(x) for x in sys.argv[3].split(",")], handle,
                  json.loads(sys.argv[5]) if len(sys.argv) > 5 else None)
    elif kind == "thrown":  # python -m study.benchmarks.strikes thrown none,series 16,32,64,128,256 out.jsonl
        with open(sys.argv[4], "a") as handle:
            thrown(sys.argv[2].split(","), [int(x) for x in sys.argv[3].split(",")], handle)
    else:
        raise SystemExit(f"kind = {kind!r}; allowed: replays, sample, sample-at, recover, where, thrown")
