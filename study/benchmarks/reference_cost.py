"""The reference method's cost per revolution at bouncing points, one checkout's code against another's, side by side
in one run (docs/reference_model.md §6).

Two worker processes, one per checkout (each imports ``study`` from its checkout's root, with its compiled kernels),
take the same design points in turn (``--rounds`` times each, alternating; the least CPU time of the rounds is
kept), after a warm-up, so that a shared machine's load falls on both alike: the ratios are the measure, not the
absolute times. Per point: the CPU time of :func:`study.solvers.solve_point`
(``reference``) over the revolutions it simulated, the status, the error estimate and the design figures with their
stated errors. Run from a checkout's root::

    .venv/bin/python -m study.benchmarks.reference_cost --before /work/main --after . \\
        --results /work/main/outputs/default/results.nc --indices 274 515 687 201 --modes 32 64

(``--budget`` the revolutions' budget, ``reference_max_revolutions``, 80 by default; ``--options`` the option sets,
``default`` and ``pulse/local``: ``reference_strike_force = "pulse"``, ``reference_strike_stress = "local"``,
``reference_window_growth = "figure"``; ``--after-inputs`` inputs the 'after' runs add, e.g.
``'{"reference_drag_quadrature": "uniform"}'`` with ``--after .`` the checkout of ``--before``: an opt-in option against
the default; several: each a variant, run after the same 'before' run of a point). The table adds the drag's share
of the losses, drag over drag and contact loss of each run's window (its energy budget).)
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path

#: The design figures compared before and after, with their stated errors (``<name>_error``).
FIGURES = ("peak_contact_force", "max_normal_stress", "alternating_bending_stress", "max_deflection")

#: The worker: reads a job (JSON) a line, writes its result (JSON) a line.
WORKER = r"""
import json, sys, time
sys.path.insert(0, sys.argv[1])
import numpy as np, xarray as xr
from study import config
from study.solvers import solve_point
ds = xr.open_dataset(sys.argv[2])
study = config.load(sys.argv[3])
from study.benchmarks.strikes import result_points
coords_of = result_points(ds)
import study as package
print(json.dumps({"ready": package.__file__}), flush=True)
for line in sys.stdin:
    job = json.loads(line)
    inputs = {**study.point(**coords_of(job["index"])), **job["inputs"]}
    if job.get("warm"):
        solve_point({**inputs, "reference_max_revolutions": 1, "reference_revolutions": 2}, "reference")
    start = time.process_time()
    result = solve_point(inputs, "reference")
    cpu = time.process_time() - start
    values = {k: float(v) for k, v in result.values.items() if isinstance(v, (int, float, np.floating, np.integer))}
    budget = {k: float(v) for k, v in (result.extras.get("energy_budget") or {}).items()}
    print(json.dumps(dict(cpu=cpu, status=result.status, error=float(result.error_estimate), values=values,
                          steps=int(result.extras.get("steps") or 0), energy_budget=budget)), flush=True)
"""


def options(name: str, modes: int, budget: int) -> dict:
    """The inputs of an option set at a mode count (the count fixed: ``reference_max_modes`` the same)."""
    inputs = {"reference_modes": modes, "reference_max_modes": modes, "reference_max_revolutions": budget}
    if name == "pulse/local":
        inputs.update(reference_strike_force="pulse", reference_strike_stress="local",
                      reference_window_growth="figure")
    elif name != "default":
        raise ValueError(f"--options {name!r}; allowed: default, pulse/local")
    return inputs


class Worker:
    """A process running :data:`WORKER` on a checkout's code."""

    def __init__(self, root: str, results: str, config: str):
        self.process = subprocess.Popen([sys.executable, "-c", WORKER, str(Path(root).resolve()), results, config],
                                        stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
        self.ready = json.loads(self.process.stdout.readline())["ready"]
        self.warm = True

    def run(self, index: int, inputs: dict) -> dict:
        self.process.stdin.write(json.dumps(dict(index=index, inputs=inputs, warm=self.warm)) + "\n")
        self.process.stdin.flush()
        self.warm = False
        return json.loads(self.process.stdout.readline())

    def close(self):
        self.process.stdin.close()
        self.process.wait()


def table(rows: list[dict]) -> str:
    """The comparison as a markdown table: CPU per revolution before and after and their ratio, revolutions, status
    and error estimate, and each figure's relative change after against before with the larger stated error."""
    head = ("| point | modes | options | ms/rev before | ms/rev after | ratio | revolutions before/after | status "
            "before/after | error before/after | figures' change / stated error | drag loss share before/after |")
    lines = [head, "|" + "|".join("---" for _ in range(head.count("|") - 1)) + "|"]
    for r in rows:
        b, a = r["before"], r["after"]
        per = [1e3 * x["cpu"] / max(x["values"].get("revolutions_simulated", 1.0), 1.0) for x in (b, a)]
        changes = []
        for name in FIGURES:
            x, y = b["values"].get(name), a["values"].get(name)
            if x is None or y is None or x == 0:
                continue
            stated = max(b["values"].get(f"{name}_error", 0.0), a["values"].get(f"{name}_error", 0.0))
            changes.append(f"{abs(y - x) / abs(x):.1%}/{stated:.1%}")
        lines.append(f"| {r['index']} | {r['modes']} | {r['options']} | {per[0]:.1f} | {per[1]:.1f} | "
                     f"{per[0] / per[1]:.2f} | {b['values'].get('revolutions_simulated', 0):.0f}/"
                     f"{a['values'].get('revolutions_simulated', 0):.0f} | {b['status']}/{a['status']} | "
                     f"{b['error']:.2%}/{a['error']:.2%} | {', '.join(changes)} | "
                     f"{drag_share(b):.1%}/{drag_share(a):.1%} |")
    return "\n".join(lines)


def drag_share(run: dict) -> float:
    """The drag's loss over the drag and contact losses of a run's window (its energy budget; NaN without)."""
    budget = run.get("energy_budget") or {}
    drag, contact = budget.get("drag_loss", float("nan")), budget.get("contact_loss", float("nan"))
    return drag / (drag + contact) if drag + contact > 0 else float("nan")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--before", required=True, help="the checkout whose code is 'before'")
    parser.add_argument("--after", default=".", help="the checkout whose code is 'after' (this one)")
    parser.add_argument("--results", default="outputs/default/results.nc")
    parser.add_argument("--config", default="configs/default.toml")
    parser.add_argument("--indices", type=int, nargs="+", default=[274, 515, 687, 201])
    parser.add_argument("--modes", type=int, nargs="+", default=[32, 64])
    parser.add_argument("--options", nargs="+", default=["default", "pulse/local"])
    parser.add_argument("--budget", type=int, default=80)
    parser.add_argument("--rounds", type=int, default=3, help="runs of each point, before and after alternating")
    parser.add_argument("--after-inputs", nargs="+", default=["{}"],
                        help="inputs (JSON) the 'after' runs add, e.g. an opt-in option measured against the default; "
                             "several: each a variant run after the same 'before' run")
    parser.add_argument("--json", help="write the rows here too")
    args = parser.parse_args(argv)
    after_inputs = [json.loads(text) for text in args.after_inputs]
    before, after = (Worker(root, args.results, args.config) for root in (args.before, args.after))
    print(f"before: {before.ready}\nafter: {after.ready}", file=sys.stderr)
    rows = []
    try:
        for name in args.options:
            for modes in args.modes:
                for index in args.indices:
                    inputs = options(name, modes, args.budget)
                    runs = []
                    for _ in range(args.rounds):  # before, then each 'after' variant, in turn
                        first = before.run(index, inputs)
                        runs.append((first, [after.run(index, {**inputs, **extra}) for extra in after_inputs]))
                    for at, extra in enumerate(after_inputs):
                        label = name
                        if len(after_inputs) > 1:
                            label = " ".join([name] + [f"{k}={v}" for k, v in extra.items()])
                        row = dict(index=index, modes=modes, options=label, before=runs[0][0], after=runs[0][1][at])
                        for key, pick in (("before", lambda r: r[0]), ("after", lambda r: r[1][at])):
                            # the least CPU of the rounds: the load only adds
                            row[key] = dict(row[key], cpu=min(pick(r)["cpu"] for r in runs),
                                            cpus=[pick(r)["cpu"] for r in runs])
                        rows.append(row)
                        print(table([row]).splitlines()[-1], file=sys.stderr, flush=True)
    finally:
        before.close()
        after.close()
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=1))
    print(table(rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
