"""The check for a second motion beside the sliding one (:func:`study.solvers.methods.sliding_parts.from_rest`) at
the points a sweep checked, against what the sweep's full reference run gave there (docs/reference_model.md §10)::

    python -m study.benchmarks.second_motion outputs/default/results.nc out.jsonl

The checked points are those with output ``coexisting_motion`` set (0 or 1); the sweep's verdict at each: 1 where the
full reference run bounced beside the sliding motion, 0 where the check did not send it up or that run came to the
sliding motion (its message says so). Per point, one JSON line: the index, the sweep's verdict and whether it went up,
the check's (bounced, chattered, decided, revolutions, the revolutions off the wall and chattering, the least contact
fraction and the peak force after the start-up [N]) and its CPU [s] (``time.process_time``, the check alone: the
sliding state's answer, whose peak contact force the chatter test takes, and model built first). A summary on
stdout: the counts and the CPU's median, largest and sum.

The run from rest, long, at a fixed mode count, against the sliding answer (docs/reference_model.md §10: a start-up
that dies slowly, a chatter the default's modes do not carry)::

    python -m study.benchmarks.second_motion from-rest 128,130,384 48 100 out.jsonl
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np

from study.benchmarks.strikes import ROOT, default_grid, result_points

#: The sliding answer's message where the full reference run went up and came to the sliding motion too
#: (``auto._coexisting``).
CAME_BACK = "run from the rest came to this motion too"


def checked(results: str | Path) -> list[tuple[int, dict, float, bool]]:
    """(flat index, the point's coordinates, the sweep's ``coexisting_motion``, whether it went up) at the points of
    ``results`` where the check ran."""
    import xarray as xr

    ds = xr.open_dataset(results)
    coords = result_points(ds)
    flag = ds["coexisting_motion"].values.reshape(-1)
    message = ds["message"].values.reshape(-1)
    return [(int(i), coords(i), float(flag[i]), bool(flag[i] == 1.0 or CAME_BACK in str(message[i])))
            for i in np.flatnonzero(np.isfinite(flag))]


def run(results: str | Path, out) -> list[dict]:
    """:func:`checked`'s points, each checked again (:func:`sliding_parts.from_rest` on the sliding state's model),
    one JSON line each to ``out``."""
    from study import config
    from study.solvers.methods import sliding, sliding_parts
    from study.solvers.model.options import force_tolerance

    study = config.load(ROOT / "configs" / "default.toml")
    rows = []
    for index, coords, flag, went_up in checked(results):
        point = study.point(**coords)
        force = sliding.solve(point).values.get("peak_contact_force")  # the chatter test's measure
        model = sliding.steady_state(point)["model"]
        clock = time.process_time()
        found = sliding_parts.from_rest(model, force, tolerance=force_tolerance(point))
        row = dict(index=index, sweep=flag, went_up=went_up, **found, cpu=time.process_time() - clock)
        print(json.dumps(row), file=out, flush=True)
        rows.append(row)
    return rows


def summary(rows: list[dict]) -> str:
    """The counts of the sweep's verdicts against the check's, and the check's CPU."""
    true = [r for r in rows if r["sweep"] == 1.0]
    cpu = np.array([r["cpu"] for r in rows])
    up = [r["index"] for r in rows if r["bounced"] or r["chattered"]]
    return "\n".join((
        f"checked {len(rows)}; the sweep's full reference run bounced at {len(true)}, of which the check sends up "
        f"{sum(r['bounced'] for r in true)}",
        f"the check sends up {len(up)} (undecided {sum(not r['decided'] for r in rows)}): {up}",
        f"of them chattering on the wall: {[r['index'] for r in rows if r['chattered']]}",
        f"of those the sweep had sent up and its run came to the sliding motion: "
        f"{[r['index'] for r in rows if r['index'] in up and r['went_up'] and r['sweep'] == 0.0]}",
        f"CPU per point: median {np.median(cpu):.3f} s, largest {np.max(cpu):.3f} s, sum {np.sum(cpu):.1f} s"))


def from_rest(indices, modes: int, revolutions: int, out) -> list[dict]:
    """Per point of configs/default.toml's grid at those flat indices: the sliding answer's peak contact force [N]
    and the reference model's run from its rest on the wall (``reference.initial_state``) at ``modes`` modes, revolution
    by revolution for ``revolutions`` (whole tens): the largest contact force of each, its means per ten revolutions
    and over the last 20, and that mean over the sliding force; one JSON line each to ``out``."""
    from study.solvers import solve_point
    from study.solvers.methods import reference
    from study.solvers.model.options import ReferenceOptions

    grid = default_grid()
    rows = []
    for i in indices:
        inputs = grid.point(int(i))
        sliding_force = float(solve_point(inputs, "sliding").values.get("peak_contact_force", np.nan))
        clock = time.process_time()
        model = reference.build_model({**inputs, "reference_modes": modes})
        integrator = reference.Integrator(model, ReferenceOptions().reference_rtol, reference.initial_state(model))
        peaks = np.array([float(np.max(integrator.run(integrator.t + model.period).peak))
                          for _ in range(revolutions)])
        last = float(np.mean(peaks[-20:]))
        tens = peaks[:revolutions // 10 * 10].reshape(-1, 10).mean(axis=1)
        row = dict(index=int(i), modes=modes, sliding=sliding_force, last20_mean=last,
                   last20_max=float(np.max(peaks[-20:])), ratio=last / sliding_force,
                   by10=[round(float(x), 1) for x in tens], cpu=time.process_time() - clock)
        print(json.dumps(row), file=out, flush=True)
        rows.append(row)
    return rows


if __name__ == "__main__":
    if sys.argv[1] == "from-rest":
        with open(sys.argv[5], "a") as handle:
            from_rest([int(i) for i in sys.argv[2].split(",")], int(sys.argv[3]), int(sys.argv[4]), handle)
    else:
        with open(sys.argv[2], "a") as handle:
            print(summary(run(sys.argv[1], handle)))
