"""``study bench``: methods side by side in one run, with ratios (``make bench`` -> docs/performance.md).

Speed is measured here, never in a timed test. Each figure is the median of repeated runs on this
machine; the report names the machine's core count, its load average at the start and the end (the machine is
shared) and the command that produced it, and times each of its sections (:data:`SECTIONS`; ``study bench --section
NAME`` runs one alone).
"""

from __future__ import annotations

import logging
import os
import platform
import resource
import statistics
import tempfile
import time
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from study import __version__
from study.benchmarks import record, reference as reference_bench, series as series_bench
from study.benchmarks import time_domain as time_domain_bench
from study.config import load
from study.physics import hertz
from study.solvers import METHODS, STATUS_CODES, solve_point
from study.solvers.methods import periodic, reference
from study.solvers.kernels import whirl_kernel
from study.solvers.methods.auto import clear_memo
from study.solvers.model.result import REGIMES
from study.solvers.model.scene import Scene
from study.workflow.execute import configure_local_workers, run_grid, warm_up
from study.workflow.grid import Grid

DEFAULT_CONFIG = Path(__file__).resolve().parents[1] / "configs" / "paper.toml"
SCREEN_CONFIG = DEFAULT_CONFIG.with_name("screen.toml")


def _median_time(func, repeat: int, budget: float = float("inf")) -> float:
    """Median of up to ``repeat`` timed calls, stopping early (after 3) once ``budget`` seconds are spent."""
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        func()
        times.append(time.perf_counter() - start)
        if len(times) >= 3 and sum(times) > budget:
            break
    return statistics.median(times)


def bench_methods(point, repeat: int = 200, budget: float = 10.0) -> list[tuple[str, float]]:
    """Median wall time per design point of each method [s] (span search included)."""
    return [(name, _median_time(lambda n=name: solve_point(point, n), repeat, budget)) for name in METHODS]


#: The periodic solution's readings (docs/model.md §4): impact pattern x closure. The first is the config's
#: default (impact.pattern, impact.closure), the reading the ``periodic`` ladder and ``fast`` run unless a study
#: sets another; the second is the one in which the paper's example has valid spans.
PERIODIC_READINGS = (("alternating", "prescribed"), ("one_wall", "self_consistent"), ("one_wall", "prescribed"),
                     ("alternating", "self_consistent"))


def _timed_points(points, repeat: int = 2) -> tuple[np.ndarray, Counter]:
    """Wall time [s] of each point's solution in this process, the fastest of ``repeat`` solves (a shared
    machine's pauses are not the method's), and the count of each status."""
    seconds, statuses = [], Counter()
    for point in points:
        times = []
        for _ in range(repeat):
            start = time.perf_counter()
            result = solve_point(point)
            times.append(time.perf_counter() - start)
        seconds.append(min(times))
        statuses[result.status] += 1
    return np.array(seconds), statuses


def _spread(seconds) -> str:
    """Median | 90th percentile | largest [ms] as table cells."""
    return " | ".join(f"{v * 1e3:.4g}" for v in (np.median(seconds), np.quantile(seconds, 0.9), np.max(seconds)))


def bench_span_search(study, count: int = 24, full_count: int = 6) -> tuple[list[str], dict]:
    """The fast method (span search included) on ``count`` points spread evenly over the study's grid, in each
    reading of :data:`PERIODIC_READINGS`, with the outcomes; and in the default reading the search over every
    pole (``resonance_width`` = 0) on the first ``full_count`` of those points beside the default search on
    the same points, as a ratio.

    Returns table lines with the median, 90th percentile and largest time per point, and the statistics
    {reading "pattern/closure": {"median", "p90", "max" [s], "statuses"}} (and "median": the default reading's).
    """
    grid = Grid(dict(study.inputs), dict(study.axes))
    picks = np.linspace(0, grid.size - 1, count).round().astype(int)
    base = [{**grid.point(int(i)), "solver_method": "fast", "span_length": None} for i in picks]
    stats, rows = {}, []
    for pattern, closure in PERIODIC_READINGS:
        points = [{**point, "impact_pattern": pattern, "closure": closure} for point in base]
        solve_point(points[0])  # compiled kernels loaded before timing
        seconds, statuses = _timed_points(points)
        name = f"{pattern}/{closure}"
        stats[name] = {"median": float(np.median(seconds)), "p90": float(np.quantile(seconds, 0.9)),
                       "max": float(seconds.max()), "statuses": dict(statuses), "seconds": seconds}
        outcomes = ", ".join(f"{n} {k}" for k, n in sorted(statuses.items()))
        label = name + (" (default: what `periodic` and `fast` run first)" if not rows else "")
        first = stats["/".join(PERIODIC_READINGS[0])]["median"]
        rows.append(f"| {label} | {count} | {outcomes} | {_spread(seconds)} | {first / np.median(seconds):.3g}x |")
    default = stats["/".join(PERIODIC_READINGS[0])]
    part = default["seconds"][:full_count]
    points = [{**point, "impact_pattern": PERIODIC_READINGS[0][0], "closure": PERIODIC_READINGS[0][1],
               "resonance_width": 0.0} for point in base[:full_count]]
    full, _ = _timed_points(points, repeat=1)  # seconds a point: one solve each
    lines = [
        "### The fast periodic solution over the paper's grid, in each reading (span search included)", "",
        f"{count} points spread evenly over the {grid.size}-point grid of `configs/paper.toml` (rpm 50-300, every "
        "tension, restitution and mud density), `solver.method = fast`, 41 modes, spans 3 m to 1000 ft, the same "
        "points in each reading (`impact.pattern` / `impact.closure`), each point's time the faster of two solves "
        "in this process after the compiled kernels were loaded. Where the time goes: `docs/profile_fast.md`.", "",
        "| reading | points | outcomes | median [ms] | 90th percentile [ms] | largest [ms] | speed-up of the median |",
        "|---|---|---|---|---|---|---|",
        *rows, "",
        f"In the default reading, the search over every pole (one solve a point) against the default search on the "
        f"first {full_count} of those points:", "",
        "| search | points | median [ms] | 90th percentile [ms] | largest [ms] | speed-up of the median |",
        "|---|---|---|---|---|---|",
        f"| every pole searched | {full_count} | {_spread(full)} | 1x |",
        f"| default: resonances narrower than 1e-6 L skipped | {full_count} | {_spread(part)} | "
        f"{np.median(full) / np.median(part):.3g}x |", "",
    ]
    for value in stats.values():
        del value["seconds"]
    return lines, {**stats, "median": default["median"]}


def bench_hertz_coefficients(count: int = 2000) -> list[tuple[str, float]]:
    """Exact m, n: per-call scalar inversion vs one array call over the same angles [s per angle]."""
    theta = np.radians(np.linspace(1.0, 89.0, count))
    scalar = _median_time(lambda: [hertz.contact_coefficients(t) for t in theta], 3) / count
    vector = _median_time(lambda: hertz.contact_coefficients(theta), 3) / count
    return [("scalar calls", scalar), ("one array call", vector)]


def work_precision(point, quick: bool = False) -> list[tuple[list[dict], str, str]]:
    """Fast and series stresses against a converged double series at fixed spans (docs/model.md §9).

    Two cases, each (rows of :func:`study.benchmarks.series.convergence_table`, a description, the chart's
    file name):

    - the paper's example at its smallest valid span: one wall per revolution, the solution's own impact
      velocity, 300 rpm (22.02 ft, docs/validation.md); the stress maximum is the ringing after the
      impact, so both methods need the same modes and the series also needs harmonics enough to
      resolve the pulse;
    - a root of the span condition at 100 rpm, both walls, prescribed closure (the first root longer than
      30 m whose T_L-curvature fixed point holds; condition 1 does not hold there): near-resonant high
      modes ring, and both methods need about 181 modes for 1e-4 (121 leave 1.2e-4).

    ``quick``: the first case alone, two coarse resolutions against a 61 x 1600 series (a smoke run).
    """
    cases = []
    inputs = {**point, "impact_pattern": "one_wall", "closure": "self_consistent"}
    scene = periodic.make_scene(inputs)
    options = periodic.Options(modes=21)
    impact = periodic.find_span(scene, options).candidates[0]
    resolutions = [("fast", n) for n in (11, 21, 41, 61, 81)] + \
        [("series", (n, m)) for n, m in ((21, 800), (41, 1600), (61, 1600), (61, 3200), (81, 3200))]
    if quick:
        rows = series_bench.convergence_table(scene, impact, inputs, [("fast", 11), ("series", (21, 400))],
                                              reference=(61, 1600))
        return [(rows, "the paper's example at its smallest valid span (quick)", "work_precision_paper.png")]
    cases.append((series_bench.convergence_table(scene, impact, inputs, resolutions),
                  f"the paper's example at its smallest valid span, {impact.span_length / 0.3048:.2f} ft, "
                  f"T_L = {impact.contact_duration * 1e3:.3g} ms, 300 rpm, one wall, self-consistent closure; "
                  "reference: double series with 961 modes x 25 600 harmonics", "work_precision_paper.png"))
    inputs = {**point, "rotary_speed": 100 * np.pi / 30, "impact_pattern": "alternating", "closure": "prescribed"}
    scene = periodic.make_scene(inputs)
    options = periodic.Options(modes=15, min_span=9.0)
    impact = periodic.first_consistent_root(scene, options, longer_than=30.0)
    resolutions = [("fast", n) for n in (15, 31, 61, 121, 181, 241)] + \
        [("series", (n, m)) for n, m in ((31, 400), (61, 1600), (121, 3200), (181, 6400), (241, 6400))]
    cases.append((series_bench.convergence_table(scene, impact, inputs, resolutions),
                  f"span {impact.span_length:.2f} m, T_L = {impact.contact_duration * 1e3:.3g} ms, 100 rpm, "
                  "alternating walls, prescribed closure; reference: double series with 961 modes x 25 600 harmonics",
                  "work_precision.png"))
    return cases


#: The reference model's benchmark scene: 1-in eccentricity at 60 rpm, six modes per direction (forward whirl with
#: impacts at the tool joints and body, friction and mud drag).
REFERENCE_CASE = dict(reference_modes=6, rotary_speed=2 * np.pi, eccentricity=0.0254)
#: The compiled integrator's tolerances in the comparison: half decades, so that each RK45 run meets a compiled run
#: of about its accuracy (the pairing takes the cheapest compiled run at least as accurate).
COMPILED_RTOLS = (3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5, 3e-6, 1e-6, 3e-7, 1e-7, 3e-8, 1e-8, 1e-9)
#: Issue 20's target: the compiled integrator at least this many times faster than RK45 at equal accuracy.
REFERENCE_TARGET = 50.0


def bench_reference(point, revolutions: float = 3.0, repeat: int = 3, compiled_rtols=COMPILED_RTOLS,
                    penalty_rtols=(1e-4, 1e-5, 1e-6, 1e-7), case=None) -> tuple[list[dict], list[str]]:
    """The reference model's compiled integrator against scipy's solve_ivp (RK45) on the same equations (the
    linear penalty contact, :func:`study.benchmarks.reference.penalty_rhs`), from the centred pipe at rest over
    ``revolutions``. Error: largest difference of the final state (q in units of c, q' in units of Omega c)
    from DOP853 at rtol 1e-11 on the same equations. Each RK45 run is paired with the cheapest compiled run at
    least as accurate. Returns rows (name, setting, wall_time (median of ``repeat``), error, steps, work: the
    compiled kernel's counts) and the report's lines with the equal-accuracy ratios."""
    inputs = {**point, **(REFERENCE_CASE if case is None else case), "contact_law": "penalty"}
    model = reference.build_model(inputs)
    scale, n = model.state_scale(), 4 * model.n_modes
    exact = reference_bench.whirl_penalty_reference(inputs, revolutions, rtol=1e-11,
                                                    method="DOP853")["final_state"][:n]
    reference_bench.compiled_run(inputs, 0.1)  # compiled kernels loaded before timing

    def error(state):
        return float(np.max(np.abs(state[:n] - exact) / scale))

    runners = [("compiled", rtol, lambda r: reference_bench.compiled_run(inputs, revolutions, r), "steps")
               for rtol in compiled_rtols]
    runners += [("penalty_rk45", rtol,
                 lambda r: reference_bench.whirl_penalty_reference(inputs, revolutions, rtol=r), "nfev")
                for rtol in penalty_rtols]
    rows = []
    for name, rtol, run, count in runners:
        runs = [run(rtol) for _ in range(repeat)]
        rows.append(dict(name=name, setting=f"rtol {rtol:g}", wall_time=statistics.median(r["wall_time"] for r in runs),
                         error=error(runs[-1]["final_state"]), steps=runs[-1][count], work=runs[-1].get("work")))
    lines = ["### Reference model: compiled integrator against scipy's RK45 on the same equations", "",
             f"Case: the paper's example with {model.n_modes} modes per direction, "
             f"{model.rotary_speed * 30 / np.pi:.4g} rpm, eccentricity {model.eccentricity / 0.0254:.3g} in, "
             f"linear penalty contact, {revolutions:g} revolutions from rest (`study.bench.bench_reference`). Error: "
             "largest difference of the final state from DOP853 at rtol 1e-11 on the same equations. Compiled "
             "work: steps accepted / rejected by the error test / redone to locate a contact's onset or end, and "
             "right-hand-side evaluations.", "",
             "| integrator | setting | time [ms] | speed-up to the first row | error | steps (RK45: evaluations) | "
             "compiled work |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        work = r["work"]
        counts = "-" if work is None else (
            f"{work[whirl_kernel.S_ACCEPTED]:.0f} / {work[whirl_kernel.S_ERROR_REJECTED]:.0f} / "
            f"{work[whirl_kernel.S_SWITCH_REDONE]:.0f}, {work[whirl_kernel.S_RHS]:.0f} evaluations")
        lines.append(f"| {r['name']} | {r['setting']} | {r['wall_time'] * 1e3:.3g} | "
                     f"{rows[0]['wall_time'] / r['wall_time']:.3g}x | {r['error']:.2g} | {r['steps']} | {counts} |")
    lines.append("")
    ratios = []
    for ref, best, ratio in time_domain_bench.equal_accuracy_speedups(rows, method="compiled"):
        ratios.append(ratio)
        lines.append(f"- RK45 at {ref['setting']} (error {ref['error']:.2g}, {ref['wall_time'] * 1e3:.3g} ms): "
                     + (f"compiled at {best['setting']} (error {best['error']:.2g}, {best['wall_time'] * 1e3:.3g} ms) "
                        f"is {ratio:.3g}x faster" if best else "no compiled setting above is as accurate"))
    if ratios:
        met = all(r >= REFERENCE_TARGET for r in ratios)
        lines += ["", f"Equal-accuracy ratios {', '.join(f'{r:.3g}x' for r in ratios)}: smallest {min(ratios):.3g}x; "
                  f"issue 20's target of {REFERENCE_TARGET:g}x at every accuracy is "
                  + ("met." if met else "not met.")]
    lines.append("")
    return rows, lines


def bench_reference_schemes(config: str | Path = DEFAULT_CONFIG.with_name("default.toml"),
                            results: str | Path = "outputs/default/results.nc", count: int = 20, rounds: int = 3,
                            schemes=("dopri5", "lawson-flight", "lawson", "dopri5@7e-7"),
                            ) -> tuple[list[dict], list[str]]:
    """The reference model's integrator schemes (``reference_integrator``; a scheme ``name@rtol`` at another
    ``reference_rtol``) on ``count`` bouncing points of a study (the points of ``config`` that its sweep's dataset
    ``results`` says ``reference`` answered with a bouncing whirl, spread evenly over them), each point solved
    ``rounds`` times by every scheme in one process after a warm-up, the order of the schemes alternating. Per point
    and scheme: the fastest wall time of the solve and of its integrator (``Integrator.run``), the kernel's counts
    (:data:`whirl_kernel.N_STATS`), the design figures and their stated errors. Returns the rows and the report's
    lines: each scheme against the first (time, evaluations, figures' differences over their combined stated
    errors). docs/reference_model.md §6."""
    import xarray as xr

    study = load(config)
    with xr.open_dataset(results) as ds:
        if ds.attrs.get("config_hash") != study.config_hash:
            raise ValueError(f"results = {results}: not a sweep of {config} (its config_hash differs)")
        answered = (ds["method"].values.ravel() == "reference") & (
            ds["regime"].values.ravel() == REGIMES["bouncing"])
    grid = Grid(dict(study.inputs), dict(study.axes))
    found = np.flatnonzero(answered)
    picked = found[np.linspace(0, found.size - 1, min(count, found.size)).round().astype(int)]
    timer = {"run": 0.0, "work": None}
    plain_run, plain_simulate = reference.Integrator.run, reference.method.simulate

    def timed_run(self, *args, **kwargs):
        start = time.perf_counter()
        try:
            return plain_run(self, *args, **kwargs)
        finally:
            timer["run"] += time.perf_counter() - start

    def counted_simulate(inputs, model=None, start=None):
        out = plain_simulate(inputs, model, start)
        timer["work"] = out["integrator"].work.copy()
        return out

    def solve(point, scheme):
        name, _, rtol = scheme.partition("@")
        timer.update(run=0.0, work=None)
        start = time.perf_counter()
        result = reference.solve({**point, "reference_integrator": name,
                                  **({"reference_rtol": float(rtol)} if rtol else {})})
        wall = time.perf_counter() - start
        conv = result.extras.get("convergence", {})
        return dict(wall=wall, integrator=timer["run"], work=timer["work"], whirl=result.extras.get("whirl"),
                    values={k: result.values.get(k) for k in reference.FIGURES},
                    errors={k: v["total"] for k, v in conv.items()},
                    residual=result.extras.get("energy_budget", {}).get("residual", float("nan")))

    reference.Integrator.run, reference.method.simulate = timed_run, counted_simulate  # where solve looks it up
    try:
        points = [grid.point(int(i)) for i in picked]
        for scheme in schemes:
            solve(points[0], scheme)  # compiled kernels loaded
        rows = []
        for k, point in enumerate(points):
            runs = {s: [] for s in schemes}
            for r in range(rounds):
                for scheme in (schemes if (k + r) % 2 == 0 else schemes[::-1]):
                    runs[scheme].append(solve(point, scheme))
            rows.append(dict(index=int(picked[k]), point=point, runs=runs))
    finally:
        reference.Integrator.run, reference.method.simulate = plain_run, plain_simulate

    def best(row, scheme, key):
        return min(run[key] for run in row["runs"][scheme])

    first = schemes[0]
    lines = ["### Reference model: integrator schemes at bouncing points", "",
             f"{len(rows)} of the {found.size} bouncing points `reference` answered in `{results}`, {rounds} solves "
             "of each by each scheme, alternating, in one process after a warm-up "
             "(`study.bench.bench_reference_schemes`); the fastest solve. Figures: the difference from the first "
             "scheme's over the two stated errors combined (root sum of squares).", "",
             "| scheme | point [ms] median | speed-up median (range) | integrator [ms] median | speed-up median "
             "(range) | evaluations median | fewer median (range) | peak force: diff median, max; within 1x, 2x | max "
             "normal stress | alternating stress | max deflection | energy residual max |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]  # a figure column per reference.FIGURES
    for scheme in schemes:
        wall = np.array([best(r, scheme, "wall") for r in rows])
        integ = np.array([best(r, scheme, "integrator") for r in rows])
        rhs = np.array([r["runs"][scheme][0]["work"][whirl_kernel.S_RHS] for r in rows])
        base_wall = np.array([best(r, first, "wall") for r in rows])
        base_integ = np.array([best(r, first, "integrator") for r in rows])
        base_rhs = np.array([r["runs"][first][0]["work"][whirl_kernel.S_RHS] for r in rows])
        cells = []
        for name in reference.FIGURES:
            rel, z = [], []
            for r in rows:
                a, b = r["runs"][first][0], r["runs"][scheme][0]
                rel.append(abs(b["values"][name] / a["values"][name] - 1.0))
                z.append(rel[-1] / max(np.hypot(a["errors"][name], b["errors"][name]), 1e-300))
            rel, z = np.array(rel), np.array(z)
            cells.append(f"{np.median(rel):.1%}, {np.max(rel):.0%}; {np.sum(z <= 1)}, {np.sum(z <= 2)} of {z.size}")
        residual = max(abs(r["runs"][scheme][0]["residual"]) for r in rows)
        speed, ispeed, fewer = base_wall / wall, base_integ / integ, base_rhs / rhs
        lines.append(f"| {scheme} | {np.median(wall) * 1e3:.1f} | {np.median(speed):.2f} "
                     f"({speed.min():.2f}–{speed.max():.2f}) "
                     f"| {np.median(integ) * 1e3:.1f} | {np.median(ispeed):.2f} "
                     f"({ispeed.min():.2f}–{ispeed.max():.2f}) "
                     f"| {np.median(rhs):.0f} | {np.median(fewer):.2f} ({fewer.min():.2f}–{fewer.max():.2f}) | "
                     + " | ".join(cells) + f" | {residual:.1e} |")
    lines.append("")
    return rows, lines


#: The reference model's deterministic work-and-precision case: configs/default.toml's pipe at a bouncing point of the
#: default study (250 rpm, 5 000 lbf, e = 0.7, 9 ppg, no flow; tests/solvers/test_modes.py's), the string thrown
#: rigidly at :data:`REFERENCE_MODES_SPEED` onto its tool joints' wall on the low side from 10 µm off it, then driven
#: (eccentricity, side load, friction, drag) for :data:`REFERENCE_MODES_REVOLUTIONS` (``fixed_window``).
REFERENCE_MODES_POINT = dict(rotary_speed=250 * np.pi / 30, axial_tension=5_000 * 4.4482216152605, restitution=0.7,
                             mud_density=9 * 119.826427, mud_flow_velocity=0.0)
REFERENCE_MODES_SPEED = 0.3  #: [m/s]
REFERENCE_MODES_REVOLUTIONS = 0.25  #: the window: the impact and its ringing, 40-50 contact onsets at 64 modes
#: The figures of the table, with their column names.
REFERENCE_MODES_FIGURES = {"peak_contact_force": "peak contact force", "max_normal_stress": "max normal stress",
                           "alternating_bending_stress": "alternating bending stress"}


def bench_reference_modes(point=None, modes=(16, 32, 64), residuals=("series", "none", "dynamic"), converged=256,
                          revolutions: float = REFERENCE_MODES_REVOLUTIONS, speed: float = REFERENCE_MODES_SPEED,
                          rtol: float = 1e-8, repeat: int = 3) -> tuple[list[dict], list[str]]:
    """The reference model's work and precision in its modes and residual laws (``reference_modes``,
    ``reference_residual``) on one deterministic case (:func:`study.benchmarks.reference.fixed_window` from the thrown
    string: the same start at every count, no window growth, no mode doubling): time per revolution of the integrator
    (median of ``repeat``) and each figure of :data:`REFERENCE_MODES_FIGURES` as a ratio to a run with ``converged``
    modes (the kept modes alone, ``reference_residual = "none"``: at 256 modes it and ``"dynamic"`` agree within 0.3 %
    in the peak force, tests/solvers/test_modes.py, and 1.2 % in the stresses over the window, docs/performance.md;
    the converged count's run with ``"dynamic"`` is a row
    too, when that law is in ``residuals``, to show it), all in one run. The converged run is timed once. Returns rows
    (method: the residual
    law, modes, harmonics None, wall_time [s per revolution], time_ratio (the converged run's time over this one's),
    figure ratios ``<figure>_ratio``, error (max normal stress) and shear_error (peak force), relative) and the
    report's lines."""
    if point is None:
        point = {**load(STUDY_CONFIG).point(), **REFERENCE_MODES_POINT}
    # compiled kernels loaded before timing (each law its own system)
    for residual in dict.fromkeys((*residuals, "none")):
        reference_bench.fixed_window({**point, "reference_modes": 4, "reference_residual": residual}, 0.01, speed, rtol)

    def run(n, residual, times):
        inputs = {**point, "reference_modes": n, "reference_max_modes": max(n, 1), "reference_residual": residual,
                  "reference_strike_force": "modes"}  # each law's own force, not the local model's (§2.3)
        runs = [reference_bench.fixed_window(inputs, revolutions, speed, rtol) for _ in range(times)]
        return dict(runs[-1], wall_time=statistics.median(r["wall_time"] for r in runs) / revolutions)

    best = run(converged, "none", 1)
    rows = []
    cases = [(residual, n) for residual in residuals for n in modes] + [("none", converged)] + (
        [("dynamic", converged)] if "dynamic" in residuals else [])
    for residual, n in cases:
        got = best if (residual, n) == ("none", converged) else run(n, residual, 1 if n == converged else repeat)
        ratios = {f"{name}_ratio": got[name] / best[name] for name in REFERENCE_MODES_FIGURES}
        rows.append(dict(method=residual, modes=n, harmonics=None, wall_time=got["wall_time"],
                         time_ratio=best["wall_time"] / got["wall_time"], onsets=got["onsets"], **ratios,
                         error=abs(ratios["max_normal_stress_ratio"] - 1.0),
                         shear_error=abs(ratios["peak_contact_force_ratio"] - 1.0)))
    mpa = 1e-6
    scene = Scene.from_inputs(point)
    lines = ["### Reference model: work and precision in the modes and the residual law", "",
             f"`configs/default.toml` at {scene.rotary_speed * 30 / np.pi:.4g} rpm, "
             f"{scene.axial_tension / 4.4482216152605:.5g} lbf, e = {scene.restitution:g}, "
             f"{scene.mud_density / 119.826427:.3g} ppg, {scene.mud_flow_velocity / 0.3048:.3g} ft/s (a bouncing "
             f"point of the default study), its string thrown rigidly at {speed:g} m/s onto its tool joints' wall on "
             f"the low side, then driven for {revolutions:g} revolution{'s' if revolutions != 1 else ''} at rtol "
             f"{rtol:g} (`study.bench.bench_reference_modes`): one deterministic window, the same start at every mode "
             "count, no transient, window growth or mode doubling. Time per revolution of the compiled integrator "
             f"(the stresses computed after it, not timed) and each figure over the window as a ratio to {converged} "
             f"modes with the kept modes alone (residual law `none`: {best['wall_time'] * 1e3:.3g} ms a revolution, "
             f"{best['onsets']} contact onsets; peak force {best['peak_contact_force'] / 1e3:.4g} kN, max normal "
             f"stress {best['max_normal_stress'] * mpa:.4g} MPa, alternating "
             f"{best['alternating_bending_stress'] * mpa:.4g} MPa). The time is the median of "
             f"{repeat} runs ({converged} modes: one). Residual laws (`solver.reference_residual`): `series`, the "
             "modes left out as a static flexibility in series with each contact (the default); `none`, the kept "
             "modes alone; `dynamic`, one residual vector a contact point in the integrated modes.", "",
             "| residual law | modes | time per revolution [ms] | speed-up to " + f"{converged} modes | onsets | "
             + " | ".join(f"{label}, ratio to {converged} modes" for label in REFERENCE_MODES_FIGURES.values()) + " |",
             "|---|---|---|---|---|" + "---|" * len(REFERENCE_MODES_FIGURES)]
    lines += [f"| {r['method']} | {r['modes']} | {r['wall_time'] * 1e3:.3g} | {r['time_ratio']:.3g}x | {r['onsets']} | "
              + " | ".join(f"{r[name + '_ratio']:.3f}" for name in REFERENCE_MODES_FIGURES) + " |" for r in rows]
    lines.append("")
    return rows, lines



def bench_reference_contact_step(point=None, **kwargs) -> tuple[list[dict], list[str]]:
    """The reference model's step in contact at a bouncing point of the default study, per scheme and mode count
    (:func:`study.benchmarks.reference.contact_step`, its keywords; the point :data:`CONTACT_STEP_POINT` on
    configs/default.toml unless given). Returns the rows and the report's lines."""
    if point is None:
        point = {**load(STUDY_CONFIG).point(), **reference_bench.CONTACT_STEP_POINT}
    return reference_bench.contact_step(point, **kwargs)

def bench_hierarchy(count: int = 12) -> list[str]:
    """The default study's hierarchy (``auto``) against the reference model at every point, on the held-back
    sample of :func:`study.validate.hierarchy_sample` (the reference run where a cheaper model answered)."""
    from study.validate import hierarchy_sample

    rows = hierarchy_sample(count)
    auto_time, ref_time = sum(r["auto_time"] for r in rows), sum(r["ref_time"] for r in rows)
    lines = ["### The default study's model hierarchy against the reference model everywhere", "",
             f"{len(rows)} points spread over `configs/default.toml`'s grid (the sample of docs/validation.md), each "
             "solved by `auto` and by the reference model (`study.bench.bench_hierarchy`): by the model that answered, "
             "the points' time in each and the speed-up of the hierarchy.", "",
             "| model that answered | points | hierarchy [s] | reference model [s] | speed-up |",
             "|---|---|---|---|---|"]
    for method in dict.fromkeys(r["method"] for r in rows):
        mine = [r for r in rows if r["method"] == method]
        a, b = sum(r["auto_time"] for r in mine), sum(r["ref_time"] for r in mine)
        lines.append(f"| `{method}` | {len(mine)} | {a:.3g} | {b:.3g} | {b / a:.3g}x |")
    lines += [f"| all | {len(rows)} | {auto_time:.3g} | {ref_time:.3g} | {ref_time / auto_time:.3g}x |", "",
              "The free whirl costs milliseconds, but the reference model is cheap too where the pipe stays clear (no "
              "contact to integrate); the points in contact, which only the reference model answers, take most of "
              "the time.", ""]
    return lines


STUDY_CONFIG = DEFAULT_CONFIG.with_name("default.toml")

#: Run in a fresh process per method: the point solved once (its compiled kernels loaded), then again under
#: tracemalloc, which sees every allocation of Python and numpy (numba's own arrays inside a kernel are not seen).
_MEMORY_SCRIPT = """
import json, sys, tracemalloc
from study.config import load
from study.solvers import solve_point
point = load(sys.argv[1], json.loads(sys.argv[3])).point()
solve_point(point, sys.argv[2])
tracemalloc.start()
result = solve_point(point, sys.argv[2])
peak = tracemalloc.get_traced_memory()[1]
tracemalloc.stop()
# this process's own high-water mark (VmHWM; ru_maxrss on Linux keeps the parent's across exec)
hwm = next(int(line.split()[1]) for line in open("/proc/self/status") if line.startswith("VmHWM:"))
print(json.dumps(dict(peak=peak, process=hwm, status=result.status)))
"""


#: The cases of :func:`bench_memory`: (label, config, overrides).
MEMORY_CASES = (("paper example, one wall, self-consistent", DEFAULT_CONFIG,
                 {"impact.pattern": "one_wall", "impact.closure": "self_consistent"}),
                ("default study, first point", STUDY_CONFIG, {}))


def bench_memory(cases=None, methods=None) -> list[dict]:
    """Peak memory per design point of every method (or of ``methods``; :data:`_MEMORY_SCRIPT`), each in a fresh
    process: rows
    with the case, the method, the point's peak traced allocation [MiB], the process's peak resident memory
    [MiB] (interpreter, solver stack and kernels included) and the point's status."""
    import json
    import subprocess
    import sys

    cases = cases or MEMORY_CASES
    rows = []
    for label, config, overrides in cases:
        for method in methods or METHODS:
            run = subprocess.run([sys.executable, "-c", _MEMORY_SCRIPT, str(config), method, json.dumps(overrides)],
                                 capture_output=True, text=True, timeout=600, check=True)
            got = json.loads(run.stdout.strip().splitlines()[-1])
            rows.append(dict(case=label, method=method, peak=got["peak"] / 2**20, process=got["process"] / 1024,
                             status=got["status"]))
    return rows


def memory_table(rows: list[dict]) -> list[str]:
    """The rows of :func:`bench_memory` as a markdown table, one column per case."""
    cases = list(dict.fromkeys(r["case"] for r in rows))
    lines = ["### Peak memory per design point, by method", "",
             "Each method in a fresh process per case (`study.bench.bench_memory`): the point solved once to load "
             "its compiled kernels, then again under tracemalloc, which counts every allocation of Python and numpy "
             "during the point (numba's arrays inside a kernel are not counted). In brackets: the process's peak "
             "resident memory, interpreter and solver stack included; then the point's status.", "",
             "| method | " + " | ".join(f"{c}: peak [MiB] (process) status" for c in cases)
             + f" | ratio of the process's resident memory to {rows[0]['method']}'s, {cases[0]} |",
             "|---|" + "---|" * (len(cases) + 1)]
    for method in dict.fromkeys(r["method"] for r in rows):
        cells = [next(f"{r['peak']:.3g} ({r['process']:.0f}) {r['status']}" for r in rows
                      if r["method"] == method and r["case"] == c) for c in cases]
        own = next(r["process"] for r in rows if r["method"] == method and r["case"] == cases[0])
        lines.append(f"| {method} | " + " | ".join(cells) + f" | {own / rows[0]['process']:.3g}x |")
    return lines + [""]


def bench_compile(repeat: int = 3) -> list[str]:
    """The first run after installation against later ones: ``study compile`` into an empty numba cache
    (a fresh install; ``make setup`` runs it), then ``study point`` on the default study with the cache
    filled (median of ``repeat`` processes, start-up and imports included)."""
    import subprocess
    import sys

    with tempfile.TemporaryDirectory() as cache:
        env = {**os.environ, "NUMBA_CACHE_DIR": cache}
        start = time.perf_counter()
        subprocess.run([sys.executable, "-m", "study.cli", "compile"], env=env, check=True, capture_output=True)
        cold = time.perf_counter() - start
        point = [sys.executable, "-m", "study.cli", "point", str(STUDY_CONFIG)]
        times = []
        for _ in range(repeat):
            start = time.perf_counter()
            subprocess.run(point, env=env, check=True, capture_output=True)
            times.append(time.perf_counter() - start)
        start = time.perf_counter()
        subprocess.run([sys.executable, "-c", "import study.cli"], env=env, check=True)
        imports = time.perf_counter() - start
    return ["### Compiling ahead: the first run after installation against later ones", "",
            "`study compile` (run by `make setup`) solves every method on the warm-up points "
            "(`study.workflow.compiled`) into an empty numba cache, as on a fresh install; then `study point "
            "configs/default.toml` (the reference model answers its first point) as a new process, with the "
            "cache filled.", "",
            "| step | time [s] | ratio to the first row |", "|---|---|---|",
            f"| `study compile`, empty cache | {cold:.3g} | 1x |",
            f"| `study point configs/default.toml` after it (median of {repeat} processes) | "
            f"{statistics.median(times):.3g} "
            f"| {statistics.median(times) / cold:.3g}x |",
            f"| of which starting Python and importing the command | {imports:.3g} | {imports / cold:.3g}x |", ""]


def _grid_of_size(study, points: int) -> Grid:
    """The study's grid with its first axis resampled so that the grid has about ``points`` points; with fewer
    points than the other axes make, every axis thinned instead (:func:`study_of_size`)."""
    grid = Grid(dict(study.inputs), dict(study.axes))
    first = next(iter(grid.axes))
    others = grid.size // len(grid.axes[first])
    if points < others:
        small = study_of_size(study, points)
        return Grid(dict(small.inputs), dict(small.axes))
    count = max(1, round(points / others))
    values = grid.axes[first]
    return Grid(grid.base, {**grid.axes, first: np.linspace(values[0], values[-1], count)})


def bench_sweep(study, points: int = 10_000, repeat: int = 3) -> tuple[list[tuple[str, float]], list[str]]:
    """The same grid in this process and on 1 and 2 local dask worker processes, median of ``repeat``.

    Cluster start-up is timed apart from the sweep (each cluster is started once and swept ``repeat``
    times into fresh folders). Returns the rows (label, median seconds) and notes with the measured
    scheduling overhead of the median run: 1 − (Σ per-point solve time)/(workers × wall time).
    """
    from dask.distributed import Client, LocalCluster

    configure_local_workers()  # as a sweep's local workers
    grid = _grid_of_size(study, points)
    mix = Counter()  # (method, status) of the points of the last run

    def timed(scheduler, workers, client=None):
        # every run from nothing: auto's memo of rung answers emptied in this process and the workers
        (client.run if client else lambda f: f())(clear_memo)
        with tempfile.TemporaryDirectory() as tmp:
            start = time.perf_counter()
            stored = run_grid(grid, Path(tmp), scheduler=scheduler, workers=workers, progress=False)
            wall = time.perf_counter() - start
            mix.clear()
            names = {code: name for name, code in STATUS_CODES.items()}
            mix.update((method, names.get(int(code), code)) for method, code in zip(stored["method"].tolist(),
                                                                                 stored["status"].tolist()))
            return wall, float(stored["wall_time"].sum())

    runs = sorted(timed("synchronous", 1) for _ in range(repeat))
    rows, notes = [(f"in process ({grid.size} points)", runs[len(runs) // 2][0])], []
    for workers in (1, 2):
        start = time.perf_counter()
        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None,
                          silence_logs=logging.CRITICAL) as cluster, Client(cluster) as client:
            client.run(warm_up)  # worker start-up: processes and their imports
            startup = time.perf_counter() - start
            runs = sorted(timed(cluster.scheduler_address, workers, client) for _ in range(repeat))
        wall, solve = runs[len(runs) // 2]
        rows.append((f"{workers} worker{'s' if workers > 1 else ''} ({grid.size} points)", wall))
        notes.append(f"{workers} worker(s): cluster start-up with imports {startup:.2g} s (not in the table); "
                     f"runs {', '.join(f'{w:.3g}' for w, _ in runs)} s; in the median run points were solved in "
                     f"{solve:.3g} s of worker time, scheduling and storage overhead "
                     f"{1 - solve / (workers * wall):.0%} of {workers} x {wall:.3g} s")
    notes.append("the points' methods and statuses: "
                 + ", ".join(f"{method} {status} {count}" for (method, status), count in sorted(mix.items())))
    return rows, notes


def _table(title: str, rows, unit: str, scale: float, base_index: int = 0) -> list[str]:
    base = rows[base_index][1]
    lines = [f"### {title}", "", f"| case | time [{unit}] | ratio to {rows[base_index][0]} |", "|---|---|---|"]
    for name, seconds in rows:
        lines.append(f"| {name} | {seconds * scale:.4g} | {base / seconds:.3g}x |")
    return lines + [""]


@dataclass
class Context:
    """What the sections of a run share: the paper's study and its point, where the report goes (its charts beside
    it), and ``quick``: the smallest sizes, every table in seconds (a smoke run; its figures are not to be read)."""

    study: Any
    point: dict
    out: Path | None = None
    quick: bool = False


@dataclass(frozen=True)
class Section:
    """A section of the report: its name (``study bench --section NAME``), what it measures, the function that
    measures it and writes its lines, and whether ``make bench`` runs it (``default``) or it is opt-in."""

    name: str
    what: str
    run: Callable[[Context], list[str]]
    default: bool = True


def _speedups(times) -> list[str]:
    """Each time's speed-up relative to the first, as table cells ("1x" for the first)."""
    return [f"{times[0] / t:.3g}x" if t > 0 else "-" for t in times]


def section_methods(ctx: Context) -> list[str]:
    rows = bench_methods(ctx.point, repeat=1 if ctx.quick else 20, budget=1.0)
    return _table("Time per design point, by method (paper example)", rows, "ms", 1e3)


def section_span_search(ctx: Context) -> list[str]:
    return bench_span_search(ctx.study, count=2 if ctx.quick else 24, full_count=1 if ctx.quick else 6)[0]


def section_hertz(ctx: Context) -> list[str]:
    return _table("Exact Hertz coefficients m, n: time per angle", bench_hertz_coefficients(20 if ctx.quick else 2000),
                  "µs", 1e6)


def section_periodic(ctx: Context) -> list[str]:
    lines = ["### Work and precision of the periodic methods at a fixed span", "",
             "Time per evaluation of the fields and their maxima at the span and impact found, against the "
             "relative error of the max normal and shear stresses "
             "(`study.benchmarks.series.convergence_table`); speed-up relative to the first row.", ""]
    for rows, case, chart_name in work_precision(ctx.point, quick=ctx.quick):
        lines += [f"Case: {case}.", "",
                  "| method | modes | harmonics | time per evaluation [ms] | speed-up to the first row | "
                  "error, max normal stress | error, max shear stress |", "|---|---|---|---|---|---|---|"]
        for r, ratio in zip(rows, _speedups([r["wall_time"] for r in rows])):
            lines.append(f"| {r['method']} | {r['modes']} | {r['harmonics'] or '-'} | {r['wall_time'] * 1e3:.3g} | "
                         f"{ratio} | {r['error']:.2e} | {r['shear_error']:.2e} |")
        cheapest = {}
        for r in rows:
            if r["error"] <= 1e-4 and (r["method"] not in cheapest
                                       or r["wall_time"] < cheapest[r["method"]]["wall_time"]):
                cheapest[r["method"]] = r
        if len(cheapest) == 2:
            ratio = cheapest["series"]["wall_time"] / cheapest["fast"]["wall_time"]
            lines += ["", f"At 1e-4 in max normal stress: fast {cheapest['fast']['wall_time'] * 1e3:.3g} ms "
                      f"({cheapest['fast']['modes']} modes), series {cheapest['series']['wall_time'] * 1e3:.3g} ms "
                      f"({cheapest['series']['modes']} modes x {cheapest['series']['harmonics']} harmonics): "
                      f"fast is {ratio:.2g}x faster."]
        if ctx.out:
            from study.charts.precision import work_precision_chart

            chart = Path(ctx.out).with_name(chart_name)
            work_precision_chart(rows, case).savefig(chart, dpi=150)
            lines += ["", f"Chart: `{chart.name}` beside this file."]
        lines.append("")
    return lines


def section_time_domain(ctx: Context) -> list[str]:
    case = {**ctx.point, "span_length": 10.0, "time_modes": 1}
    if ctx.quick:
        rows = time_domain_bench.benchmark(case, revolutions=1, repeat=1, contact_steps=(25,), penalty_rtols=(1e-4,))
        stability = time_domain_bench.step_stability(case, revolutions=1, fractions=(0.1, 2.0), contact_steps=(10,))
    else:
        rows = time_domain_bench.benchmark(case, revolutions=10)
        stability = time_domain_bench.step_stability(case)
    lines = ["### Time domain against a penalty spring in scipy's RK45, at equal accuracy", "",
             f"Case: the paper's example at a 10 m span, first mode only, {10 if not ctx.quick else 1} revolutions, no "
             "early stop (`study.benchmarks.time_domain.benchmark`). Error: largest difference of the final modal "
             "state (q in units of c, q' in units of Omega c) from a converged run of the same model (LSODA at "
             "rtol 1e-12 for the Hertz contact; DOP853 at rtol 1e-12 for the linear penalty contact, a "
             "different model, so only errors, not states, are compared across the two); speed-up relative to the "
             "first row.", "",
             "| integrator | setting | time [ms] | speed-up to the first row | error | impacts | "
             "last impact velocity [m/s] |", "|---|---|---|---|---|---|---|"]
    for row, ratio in zip(rows, _speedups([r["wall_time"] for r in rows])):
        lines.append(f"| {row['name']} | {row['setting']} | {row['wall_time'] * 1e3:.3g} | {ratio} | "
                     f"{row['error']:.2g} | "
                     f"{row['impacts']} | {row['impact_velocity']:.4g} |")
    lines.append("")
    for ref, best, ratio in time_domain_bench.equal_accuracy_speedups(rows):
        lines.append(f"- penalty RK45 at {ref['setting']} (error {ref['error']:.2g}, {ref['wall_time'] * 1e3:.3g} ms): "
                     + (f"event-driven with {best['setting']} (error {best['error']:.2g}, "
                        f"{best['wall_time'] * 1e3:.3g} ms) is {ratio:.3g}x faster" if best else
                        "no event-driven setting above is as accurate"))
    lines += ["", "Stability of the integrators against the contact stiffness, same case over "
              f"{1 if ctx.quick else 3} revolutions: the step as a multiple of the explicit limit 2/omega_max (contact "
              "linearised at the expected penetration): the Verlet step of `explicit`, the RK4 contact step of "
              "`event`. Error as above, against LSODA at rtol 1e-12.", "",
              "| integrator | setting | ratio of the step to the limit | outcome | error |", "|---|---|---|---|---|"]
    for row in stability:
        outcome = {"failed": "failed: blow-up detected", "chattering": "stopped: chatter"}.get(row["verdict"], "ran")
        lines.append(f"| {row['name']} | {row['setting']} | {row['step_ratio']:.3g} | {outcome} | {row['error']:.2g} |")
    lines.append("")
    if ctx.out:
        from study.charts.precision import time_domain_chart

        chart = Path(ctx.out).with_name("time_domain.png")
        time_domain_chart(rows, stability, "the paper's example at a 10 m span, first mode").savefig(chart, dpi=150)
        lines += [f"Chart: `{chart.name}` beside this file.", ""]
    return lines


def section_reference_rk45(ctx: Context) -> list[str]:
    if ctx.quick:
        return bench_reference(ctx.point, revolutions=0.5, repeat=1, compiled_rtols=(1e-6, 1e-9), penalty_rtols=(1e-5,),
                               case=dict(REFERENCE_CASE, reference_modes=2))[1]
    return bench_reference(ctx.point)[1]


def section_reference_modes(ctx: Context) -> list[str]:
    if ctx.quick:
        rows, lines = bench_reference_modes(modes=(4,), residuals=("series", "dynamic"), converged=8, revolutions=0.05)
        step_lines = bench_reference_contact_step(modes=(4,), startup=0.5, revolutions=0.2)[1]
    else:
        rows, lines = bench_reference_modes()
        step_lines = bench_reference_contact_step()[1]
    if ctx.out:
        from study.charts.precision import work_precision_chart

        chart = Path(ctx.out).with_name("work_precision_reference.png")
        work_precision_chart(rows, lines[2].split(" (`")[0].replace("`", ""),
                             title="Work and precision of the reference model (modes x residual law)",
                             time_label="time per revolution [ms]",
                             labels=("max normal stress", "peak contact force")).savefig(chart, dpi=150)
        lines += [f"Chart: `{chart.name}` beside this file.", ""]
    return lines + step_lines


def section_hierarchy(ctx: Context) -> list[str]:
    return bench_hierarchy(count=2 if ctx.quick else 12)


def _sweep_lines(cases) -> list[str]:
    """The sweep tables of ``cases``: (study, points, runs, whether to extrapolate to 10^5 points, what it is)."""
    lines = []
    for config, points, repeat, project, what in cases:
        sweep_rows, notes = bench_sweep(config, points, repeat)
        size = _grid_of_size(config, points).size
        lines += _table(f"Sweep of {what}, {size} points: in process vs local dask workers (median of "
                        f"{repeat} run{'s' if repeat > 1 else ''} each)", sweep_rows, "s", 1.0)
        speedup = sweep_rows[1][1] / sweep_rows[2][1]
        lines += [f"Two workers vs one: {speedup:.2f}x.", ""] + [f"- {note}" for note in notes] + [""]
        if project:
            hours = sweep_rows[2][1] / size * 1e5 / 3600
            lines += [f"At this mix's measured rate on 2 workers, 10^5 points of the default study would take "
                      f"about {hours:.3g} h (an extrapolation of the {size}-point run, not a measured 10^5-point "
                      "sweep: `make bench-large` measures one).", ""]
    return lines


def section_sweeps(ctx: Context) -> list[str]:
    (paper, paper_runs), (screen, screen_runs) = SWEEP_SIZES if not ctx.quick else ((20, 1), (20, 1))
    return _sweep_lines(((ctx.study, paper, paper_runs, False, "`configs/paper.toml` (method core, about 0.2 ms per "
                          "point: scheduling- and storage-bound)"),
                         (load(SCREEN_CONFIG), screen, screen_runs, False, "`configs/screen.toml` (method sdof, about "
                          "2 ms per point: compute-bound)")))


def section_sweep_default(ctx: Context) -> list[str]:
    points, runs = DEFAULT_SWEEP_SIZE if not ctx.quick else (4, 1)
    return _sweep_lines(((load(STUDY_CONFIG), points, runs, True, "the default study `configs/default.toml` (method "
                          "auto: the free whirl where the pipe stays clear, the sliding state where it lies on the "
                          "wall, the reference model elsewhere), every axis thinned evenly"),))


def section_compile(ctx: Context) -> list[str]:
    return bench_compile(repeat=1 if ctx.quick else 3)


def section_memory(ctx: Context) -> list[str]:
    if ctx.quick:
        return memory_table(bench_memory(MEMORY_CASES[:1], methods=("core", "fast")))
    # the paper's example in its default reading is left out: there the periodic methods find no span and every
    # method but the reference model's holds what it holds on the default study's first point
    return memory_table(bench_memory())


#: The sweeps of the paper's and the screening study: (points, runs) each.
SWEEP_SIZES = ((5_000, 3), (2_000, 3))
#: The default study's sweep (opt-in: its points in contact take about a second each): (points, runs).
DEFAULT_SWEEP_SIZE = (96, 1)

#: The report's sections in order (``study bench --section NAME`` runs one; ``make bench`` the default ones).
SECTIONS = {s.name: s for s in (
    Section("methods", "time per design point of every method on the paper's example", section_methods),
    Section("span-search", "the fast method's span search over the paper's grid, in each reading", section_span_search),
    Section("hertz", "the exact Hertz coefficients, scalar against array calls", section_hertz),
    Section("periodic", "work and precision of the fast and series methods at fixed spans", section_periodic),
    Section("time-domain", "the time-domain integrators against scipy's RK45 with a penalty spring, and their "
            "stability against the step", section_time_domain),
    Section("reference-rk45", "the reference model's compiled integrator against scipy's RK45 on the same equations",
            section_reference_rk45),
    Section("reference-modes", "the reference model's work and precision in its modes and residual laws against "
            "256 modes, and the step in contact at a bouncing point", section_reference_modes),
    Section("hierarchy", "the default study's model hierarchy against the reference model everywhere",
            section_hierarchy),
    Section("sweeps", "sweeps in process against 1 and 2 local dask workers", section_sweeps),
    Section("sweep-default", "the default study's sweep in process against 1 and 2 local dask workers, on its grid "
            "thinned to about 100 points (minutes: its points in contact take about a second each; `make sweep` "
            "records the whole study's, docs/runs/)", section_sweep_default, default=False),
    Section("memory", "peak memory per design point of every method", section_memory),
    Section("compile", "`study compile` into an empty numba cache, then a first point (about 2 minutes of both "
            "cores; run alone)", section_compile, default=False),
)}


def _load() -> str:
    return ", ".join(f"{v:.2f}" for v in os.getloadavg())


def run_bench(out: str | None = None, sections=None, quick: bool = False) -> str:
    """The report of ``sections`` (names of :data:`SECTIONS`; default: the default ones, ``make bench``), each timed;
    written to ``out`` when given (the charts beside it). Raises ValueError naming an unknown section."""
    names = [name for name, s in SECTIONS.items() if s.default] if not sections else list(dict.fromkeys(sections))
    unknown = [name for name in names if name not in SECTIONS]
    if unknown:
        raise ValueError(f"section = {', '.join(map(repr, unknown))}; allowed: {', '.join(SECTIONS)}")
    study = load(DEFAULT_CONFIG)
    ctx = Context(study=study, point=study.point(), out=Path(out) if out else None, quick=quick)
    load_start, started = _load(), time.perf_counter()
    body, spent = [], []
    for name in names:
        start = time.perf_counter()
        body += SECTIONS[name].run(ctx)
        spent.append((name, time.perf_counter() - start))
    if "memory" in names:
        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # KiB on Linux
        body += [f"Peak memory of the benchmark process (every section above run in it): {peak:.0f} MiB.", ""]
    total = time.perf_counter() - started
    default = [name for name, s in SECTIONS.items() if s.default]
    command = ("study bench" + "".join(f" --section {n}" for n in names if sections)
               + (f" --out {out}" if out else ""))
    opt_in = [s for s in SECTIONS.values() if not s.default and s.name not in names]
    lines = [
        "# Performance", "",
        f"Generated by `{command}`" + (" (`make bench`)" if names == default and not quick else "")
        + f", study {__version__}, on {os.cpu_count()} cores, Python {platform.python_version()}, in {total:.0f} s"
        + (" (quick: the smallest sizes, a smoke run; its figures are not to be read)" if quick else "") + ". "
        "Medians of repeated runs; ratios are speed-ups relative to the first row of each table unless the table "
        "says otherwise.", "",
        f"The machine is shared: its load average (1, 5, 15 min) was {load_start} at the start and {_load()} at the "
        "end; a load above the core count slows every time below alike, more for the sweeps over two workers.", "",
        "Sections run (`study bench --section NAME` runs one alone): "
        + ", ".join(f"`{name}` {seconds:.0f} s" for name, seconds in spent) + "."
        + ("" if not opt_in else " Not run by `make bench` (opt-in): " + "; ".join(
            f"`{s.name}`, {s.what} (`make bench-{s.name}`: `study bench --section {s.name} --out "
            f"docs/performance_{s.name}.md`)" for s in opt_in) + "."), "",
        "| section | time [s] | share of the run |", "|---|---|---|",
        *[f"| {name} | {seconds:.3g} | {seconds / total:.2g} |" for name, seconds in spent], "",
    ]
    report = "\n".join(lines + body).rstrip() + "\n"
    if out:
        record.write_record(out, report)
    return report


#: The measured large sweep (issue 23): the default study on every axis refined, 103 424 points.
LARGE_CONFIG = DEFAULT_CONFIG.with_name("dense.toml")
#: Issue 23's target for 10^5 points of the default study's mix on this machine's 2 cores [s].
LARGE_TARGET = 600.0


def study_of_size(study, points: int):
    """The study with its axes thinned evenly (each axis's ends kept while it has two values or more), the longest
    axis first, until the grid has at most ``points`` points (at least one: every axis's first value)."""
    import dataclasses

    axes = {name: np.asarray(values) for name, values in study.axes.items()}
    while axes and int(np.prod([v.size for v in axes.values()])) > max(int(points), 1):
        name = max(axes, key=lambda k: axes[k].size)
        values = axes[name]
        keep = max(values.size - max(values.size // 4, 1), 1)
        axes[name] = values[np.unique(np.linspace(0, values.size - 1, keep).round().astype(int))]
    return dataclasses.replace(study, axes=axes)


def bench_large_sweep(config: str | Path = LARGE_CONFIG, workers: int = 2, out: str | Path | None = None,
                      points: int | None = None) -> str:
    """Sweep ``config`` as ``study sweep`` does (local dask workers, the dataset written, then the report's
    charts) into a temporary folder, timed; a report of the time and where it went, by method (the points'
    own ``wall_time``), written to ``out`` when given (``make bench-large``: ``docs/large_sweep.md``).
    ``points``: the grid thinned to at most that many points first (:func:`study_of_size`: a smoke test of the
    command; its report says so)."""
    import xarray as xr

    from study.charts.report import write_report
    from study.workflow.sweep import run_sweep

    study = load(config)
    if points is not None:
        study = study_of_size(study, points)
    with tempfile.TemporaryDirectory() as tmp:
        start = time.perf_counter()
        path = run_sweep(study, Path(tmp) / "sweep", workers=workers, progress=False, say=lambda _: None)
        sweep = time.perf_counter() - start
        start = time.perf_counter()
        write_report(path, out_dir=Path(tmp) / "charts")
        charts = time.perf_counter() - start
        with xr.open_dataset(path) as ds:
            method = ds["method"].values.ravel().astype(str)
            meanings = ds["status"].attrs["flag_meanings"].split()
            status = np.asarray(meanings)[ds["status"].values.ravel().astype(int)]
            wall = ds["wall_time"].values.ravel().astype(float)
    size = method.size
    if size < 100_000:
        verdict = f"not judged on {size} points"
    else:
        verdict = "met" if sweep <= LARGE_TARGET else f"not met: {sweep / LARGE_TARGET:.3g} times as long"
    not_converged = int(np.sum(status == "not_converged"))
    lines = ["# A sweep of 10^5 points, measured" if points is None else
             f"# The large sweep's command on its grid thinned to {size} points (a smoke test, not the record)", "",
             ("Generated by `study bench --large --out docs/large_sweep.md` (`make bench-large`)" if points is None else
              f"Generated by `study bench --large --points {points}` (`make bench-large POINTS={points}`: a smoke test "
              "of the command, the grid thinned evenly, each axis's ends kept while it has two values or more)")
             + f", study {__version__}, "
             f"on {os.cpu_count()} cores, Python {platform.python_version()}: `{Path(config).name}` swept as "
             f"`study sweep` does, on {workers} local dask workers, into a fresh folder (the kernels compiled "
             "ahead).", "",
             f"**Grid:** {size} points, " + " × ".join(f"{len(v)} {name}" for name, v in study.axes.items()) + ".", "",
             f"**Time:** the sweep (every point solved and the dataset written) **{int(sweep // 60)} min "
             f"{int(sweep % 60)} s**; the report's charts {charts:.0f} s more. The points' own times sum to "
             f"{wall.sum():.0f} s of worker time ({wall.sum() / (workers * sweep):.0%} of {workers} x the sweep). "
             f"Issue 23's target, 10^5 points in {LARGE_TARGET / 60:.0f} minutes: {verdict}.", "",
             f"**Not converged:** {not_converged} of {size} points ({not_converged / max(size, 1):.1%}).", "",
             "**Where the time went** (the points' own `wall_time`):", "",
             "| method | points | statuses | worker time [s] | share | median per point [ms] | largest [s] |",
             "|---|---|---|---|---|---|---|"]
    for name in sorted(set(method), key=lambda m: -wall[method == m].sum()):
        mine = method == name
        counts = Counter(status[mine].tolist())
        lines.append(f"| `{name}` | {mine.sum()} | " + ", ".join(f"{s} {n}" for s, n in counts.most_common())
                     + f" | {wall[mine].sum():.0f} | {wall[mine].sum() / wall.sum():.0%} | "
                       f"{np.median(wall[mine]) * 1e3:.3g} | {wall[mine].max():.2g} |")
    report = "\n".join(lines) + "\n"
    if out:
        record.write_record(out, report)
    return report
