"""The strikes' local model against the modes (docs/reference_model.md §2.3): the tables' commands.

    python -m study.benchmarks.strikes replays A,B,C 16,32,64 256 out.jsonl
        strikes of bouncing points of configs/default.toml (their runs at each count), each replayed from the run's
        recorded state at every count up to the last (:func:`study.solvers.methods.reference.replay.lift_state`): the
        local model's peak from the run's onset speed, the replays' peaks and onset speeds
    python -m study.benchmarks.strikes sample 12 modes,local,pulse out.jsonl outputs/default/results.nc ['{"reference_modes": 128}']
        bouncing reference points of the default study's last sweep (its results.nc, `make sweep`), evenly in the sweep's
        order, each solved with ``solve_point(..., "reference")`` for each ``reference_strike_force`` (cap 300 s; a
        capped run is reported failed, solve_point catching the alarm)
    python -m study.benchmarks.strikes sample-at 274,515,687,201 modes,local out.jsonl RESULTS '{"reference_modes": 128, "reference_max_modes": 128}'
        the same at the points of those flat indices of the results (cap 1200 s)

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


def sample(count, options, out, results, extra=None, indices=None, cap=300):
    import xarray as xr

    from study import config
    from study.solvers import solve_point
    from study.solvers.model.result import REGIMES

    ds = xr.open_dataset(results)
    study = config.load(ROOT / "configs" / "default.toml")
    dims = list(ds["method"].dims)
    bouncing = (ds["method"].values.reshape(-1) == "reference") & (ds["regime"].values.reshape(-1) == REGIMES["bouncing"])
    found = np.flatnonzero(bouncing)
    picks = found[np.linspace(0, found.size - 1, count).round().astype(int)] if indices is None else np.asarray(indices)
    grid = np.stack(np.meshgrid(*[ds[d].values for d in dims], indexing="ij"), -1).reshape(-1, len(dims))

    def stop(*_):
        raise TimeoutError

    signal.signal(signal.SIGALRM, stop)
    for i in picks:
        coords = {d: float(v) for d, v in zip(dims, grid[i])}
        for option in options:
            clock = time.process_time()
            signal.alarm(cap)
            try:
                r = solve_point({**study.point(**coords), "reference_strike_force": option, **(extra or {})},
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
                                                                    "window_revolutions", "impacts_per_revolution")},
                convergence={k: {p: float(v) for p, v in e.items() if isinstance(v, (int, float))}
                             for k, e in conv.items()})), file=out, flush=True)


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
            sample(0, sys.argv[3].split(","), handle, sys.argv[5], json.loads(sys.argv[6]) if len(sys.argv) > 6 else None,
                   indices=[int(i) for i in sys.argv[2].split(",")], cap=1200)
    else:
        raise SystemExit(f"kind = {kind!r}; allowed: replays, sample, sample-at")
