"""``study coverage``: does each figure's stated error cover its true error? (issue 36)

The reference model states, for every design figure of a point, a relative error by its parts — the window (the
statistics of a motion that does not repeat), the integrator, the modes left out (docs/reference_model.md §3.1). This
module checks those statements on a held-back sample of impacting points of a study's grid (configs/default.toml):
each point's default answer (``auto``, as the sweep computes it) against a reference answer run with
:data:`MODES_FACTOR` times the modes the default answer used and :data:`WINDOW_FACTOR` times the revolutions (its
window, transient and budget), per figure: the true difference |default − reference| / reference against the stated
relative error, covered or not, and the share covered against :data:`TARGET`.

The sample is a fixed rule, not a choice of points (:func:`candidate_order`, :func:`is_impacting`): the grid's points
in a golden-ratio stride order, each solved by ``auto``; the first :data:`SAMPLE` whose answer is the reference
model's at an impacting regime (bouncing, periodic impacts) are the sample. The points run in a process pool; each
finished run is kept as a JSON file in a cache folder (written atomically, keyed by the point's inputs and the
solver code, :func:`study.workflow.grid.point_key`), so a rerun after an interruption solves only what is missing,
and a change of the solver code solves everything again. The summary is written to :data:`RESULTS`
(docs/coverage.json), from which :func:`coverage_section` renders the table of docs/validation.md: ``study
validate`` includes it without solving anything, and ``study coverage`` rewrites that section of the file in place.

Workflow only: the physics and the solvers are called, never changed.
"""

from __future__ import annotations

import json
import math
import os
import time
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from pathlib import Path
from typing import Any, Callable, Iterable, Mapping

import numpy as np

from study.atomic import atomic_path

ROOT = Path(__file__).resolve().parents[1]
DEFAULT_CONFIG = ROOT / "configs" / "default.toml"
#: The stored coverage results: what :func:`coverage_section` renders into docs/validation.md.
RESULTS = ROOT / "docs" / "coverage.json"
#: The cache of finished runs (one JSON file per run; outputs/ is not committed).
CACHE = ROOT / "outputs" / "coverage"
#: The validation record's file and the heading of the section this module owns in it.
VALIDATION = ROOT / "docs" / "validation.md"
HEADING = "## Held-back coverage of the stated errors (`study coverage`)"
#: Impacting points in the sample (issue 36: at least 20).
SAMPLE = 20
#: The reference answer's modes (times the modes the default answer used) and revolutions (times the transient, the
#: window and the budget of the default options), issue 36's "4x the modes and a long window".
MODES_FACTOR = 4
WINDOW_FACTOR = 4
#: The share of the sample each figure's stated error must cover (issue 36).
TARGET = 0.9
#: Regimes (study.solvers.model.result.Regime) of an impacting point: the pipe strikes the wall.
IMPACTING = ("bouncing", "periodic_impacts")
#: The reported figures (output name -> label); the damage rate's stated error is ``fatigue_life_error``.
FIGURES = {"peak_contact_force": "peak contact force", "max_normal_stress": "max normal stress",
           "alternating_bending_stress": "alternating bending stress", "max_deflection": "max deflection",
           "damage_rate": "fatigue damage rate"}
#: Where a figure's stated total error is, when not at ``<figure>_error``.
ERROR_OUTPUT = {"damage_rate": "fatigue_life_error"}
#: Outputs kept from each run besides the figures.
KEPT = ("regime", "window_revolutions", "revolutions_simulated", "max_bending_stress", "impacts_per_revolution",
        "statistical_figures")
#: The swept inputs shown per point: input name -> (unit, label, format).
SHOWN = {"dogleg_curvature": ("deg_per_100ft", "dogleg [°/100 ft]", "{:.3g}"), "rotary_speed": ("rpm", "rpm", "{:.0f}"),
         "axial_tension": ("lbf", "tension [lbf]", "{:.0f}"), "restitution": ("", "e", "{:g}"),
         "mud_density": ("ppg", "mud [ppg]", "{:.3g}"), "mud_flow_velocity": ("ft/s", "flow [ft/s]", "{:.3g}")}


# --- the sample ------------------------------------------------------------------------------------------------


def golden_step(size: int) -> int:
    """The stride of :func:`candidate_order`: the whole number nearest size/φ (φ the golden ratio) and coprime to
    ``size``, so that the stride visits every point once and its first visits spread over the whole grid (Weyl's
    sequence k/φ mod 1 is the most evenly spread of its kind; Knuth, TAOCP vol. 3 §6.4, Fibonacci hashing)."""
    if size <= 1:
        return 1
    step = max(1, round(size * (math.sqrt(5.0) - 1.0) / 2.0))
    while math.gcd(step, size) != 1:
        step += 1
    return step


def candidate_order(size: int) -> list[int]:
    """The grid's flat indices (C order over the axes) in the order the sample takes them: k · :func:`golden_step`
    mod size for k = 0, 1, ... — a permutation of the grid that spreads over the slow axes (dogleg, rpm) at once and
    over the fast ones (tension, restitution, mud) by the stride's remainders; fixed by the grid's size alone."""
    step = golden_step(size)
    return [(k * step) % size for k in range(size)]


def is_impacting(record: Mapping[str, Any]) -> bool:
    """Whether a default answer (:func:`summarise`) is one the sample takes: answered by the reference model at an
    impacting regime (:data:`IMPACTING`)."""
    from study.solvers.model.result import REGIMES

    regime = record.get("values", {}).get("regime")
    codes = {REGIMES[name] for name in IMPACTING}
    return record.get("method") == "reference" and regime is not None and int(regime) in codes


def selected(order: Iterable[int], records: Mapping[int, Mapping[str, Any]], sample: int) -> tuple[list[int], bool]:
    """The sample: the first ``sample`` impacting points of ``order`` (:func:`is_impacting`), and whether it is
    decided — every candidate before the last one taken (or every candidate, when fewer are impacting) solved."""
    taken = []
    for index in order:
        if index not in records:
            return taken, False
        if is_impacting(records[index]):
            taken.append(index)
            if len(taken) == sample:
                return taken, True
    return taken, True


# --- the runs --------------------------------------------------------------------------------------------------


def _finite(value):
    """JSON-safe: non-finite floats become None, numpy scalars Python's."""
    if isinstance(value, (np.floating, np.integer)):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(v) for v in value]
    return value


def stated_errors(result) -> dict[str, dict[str, Any]]:
    """Each figure's stated relative error and its parts (window, integrator, modes; None where a part is not
    stated) from a reference-model result: the output ``<figure>_error`` (the damage rate's ``fatigue_life_error``)
    and ``extras["convergence"]``. The max deflection has no output of its own where the model states none: its
    modes part (``extras["modal_error"]``) and the integrator's, the window part not stated."""
    convergence = result.extras.get("convergence") or {}
    modal = result.extras.get("modal_error") or {}
    integrator = next((float(e["integrator"]) for e in convergence.values() if "integrator" in e), None)
    out = {}
    for name in FIGURES:
        total = result.values.get(ERROR_OUTPUT.get(name, f"{name}_error"))
        parts = convergence.get(name)
        if parts is not None:
            entry = dict(window=parts.get("window"), integrator=parts.get("integrator"), modes=parts.get("modes"),
                         total=parts.get("total") if total is None else total)
        elif name == "max_deflection" and name in modal:
            stated = [float(modal[name]), integrator or 0.0]
            entry = dict(window=None, integrator=integrator, modes=float(modal[name]),
                         total=float(total) if total is not None else float(sum(stated)))
        else:
            entry = dict(window=None, integrator=None, modes=None, total=total)
        out[name] = {k: (None if v is None else float(v)) for k, v in entry.items()}
    return out


def summarise(result) -> dict[str, Any]:
    """What the coverage keeps of a result: method, status, figures and kept outputs, stated errors, modes, cost."""
    values = {name: result.values.get(name) for name in (*FIGURES, *KEPT)}
    return _finite(dict(method=result.method, status=str(result.status), values=values,
                        errors=stated_errors(result), error_estimate=result.error_estimate,
                        modes=result.extras.get("reference_modes"), wall_time=result.wall_time))


def reference_options(inputs: Mapping[str, Any], modes: int, modes_factor: int = MODES_FACTOR,
                      window_factor: int = WINDOW_FACTOR) -> dict[str, Any]:
    """The reference answer's inputs: method ``reference`` with ``modes_factor`` times the default answer's
    ``modes`` (the count fixed: ``reference_max_modes`` raised to it) and ``window_factor`` times the default
    options' window, transient and revolution budget (study.solvers.model.options.ReferenceOptions), the window grown
    for each figure that can reach its tolerance whatever the others (``reference_window_growth = "figure"``: a figure
    whose modes part is over, the strikes' local force's own 9 % among them, does not stop the others' long window)."""
    from study.solvers.model.options import ReferenceOptions

    option = ReferenceOptions.from_inputs(inputs)
    count = int(modes_factor * modes)
    return {**inputs, "solver_method": "reference", "reference_modes": count, "reference_max_modes": count,
            "reference_window": int(window_factor * option.reference_window),
            "reference_revolutions": int(window_factor * option.reference_revolutions),
            "reference_max_revolutions": int(window_factor * option.reference_max_revolutions),
            "reference_window_growth": "figure"}


def solve_default(inputs: Mapping[str, Any]) -> dict[str, Any]:
    """The default answer of a point, as the sweep computes it (its method, default options)."""
    from study.solvers import solve_point

    return summarise(solve_point(inputs))


def solve_reference(inputs: Mapping[str, Any]) -> dict[str, Any]:
    """The reference answer of a point (``inputs`` from :func:`reference_options`)."""
    from study.solvers import solve_point

    return summarise(solve_point(inputs, "reference"))


def _cache_file(cache: Path, kind: str, index: int) -> Path:
    return cache / f"{kind}-{index:06d}.json"


def load_cached(cache: Path, kind: str, index: int, key: str) -> dict[str, Any] | None:
    """A finished run from the cache, if its key (inputs and solver code) is ``key``; None otherwise."""
    path = _cache_file(cache, kind, index)
    try:
        stored = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return stored["record"] if stored.get("key") == key else None


def save_cached(cache: Path, kind: str, index: int, key: str, record: Mapping[str, Any]) -> None:
    """Keep a finished run (atomically: a reader sees the whole file or none)."""
    with atomic_path(_cache_file(cache, kind, index)) as tmp:
        Path(tmp).write_text(json.dumps(dict(key=key, record=record), indent=1), encoding="utf-8")


class _Inline:
    """An executor that runs each task at once in this process (``workers = 0``; tests, monkeypatched solvers)."""

    def submit(self, fn, *args) -> Future:
        future: Future = Future()
        try:
            future.set_result(fn(*args))
        except BaseException as exc:  # noqa: BLE001 - handed to the caller through the future
            future.set_exception(exc)
        return future

    def shutdown(self, wait: bool = True, cancel_futures: bool = False) -> None:
        return None


def run_coverage(config: str | Path = DEFAULT_CONFIG, sample: int = SAMPLE, modes_factor: int = MODES_FACTOR,
                 window_factor: int = WINDOW_FACTOR, workers: int = 2, cache: str | Path | None = None,
                 say: Callable[[str], None] = print) -> dict[str, Any]:
    """Pick the sample and run its default and reference answers (resuming from ``cache``); the results as a dict
    (:func:`write_results` stores it). ``workers`` processes (0: in this process)."""
    from study.config import load
    from study.workflow.grid import point_key
    from study.workflow.sweep import study_grid

    study = load(config)
    grid = study_grid(study)
    cache = Path(cache) if cache is not None else CACHE / study.name
    order = candidate_order(grid.size)
    say(f"coverage: the first {sample} impacting points of {study.name}'s {grid.size}-point grid (stride "
        f"{golden_step(grid.size)}), each against the reference model with {modes_factor}x its modes and "
        f"{window_factor}x the revolutions; {workers or 'no'} worker processes; finished runs kept in {cache}")
    started = time.perf_counter()
    defaults: dict[int, dict] = {}
    references: dict[int, dict] = {}
    keys: dict[tuple[str, int], str] = {}
    ref_inputs: dict[int, dict] = {}

    def key_of(kind: str, index: int, inputs: Mapping[str, Any]) -> str:
        keys[kind, index] = point_key(inputs).decode()
        return keys[kind, index]

    pool = ProcessPoolExecutor(max_workers=workers) if workers > 0 else _Inline()
    pending: dict[Future, tuple[str, int]] = {}
    position = 0  # the next candidate of ``order`` to screen

    def report(kind: str, index: int, record: Mapping[str, Any], cached: bool) -> None:
        cost = "cached" if cached else f"{record['wall_time']:.1f} s"
        if kind == "default":
            verdict = "impacting: in the sample" if is_impacting(record) else "not impacting"
            say(f"coverage: default   point {index:4d}: `{record['method']}` ({record['status']}, "
                f"{record.get('modes') or '-'} modes) {verdict}; {cost}")
        else:
            done = sum(1 for i in taken if i in references)
            say(f"coverage: reference point {index:4d} ({done} of {len(taken)} sampled so far): {record.get('modes')} "
                f"modes, {record['values'].get('revolutions_simulated') or float('nan'):.0f} revolutions, "
                f"{record['status']}; {cost} ({time.perf_counter() - started:.0f} s elapsed)")

    def submit_reference(index: int) -> None:
        inputs = reference_options(grid.point(index), defaults[index].get("modes") or 16, modes_factor,
                                   window_factor)
        ref_inputs[index] = inputs
        key = key_of("reference", index, inputs)
        record = load_cached(cache, "reference", index, key)
        if record is not None:
            references[index] = record
            report("reference", index, record, True)
            return
        pending[pool.submit(solve_reference, inputs)] = ("reference", index)

    taken: list[int] = []
    try:
        while True:
            # the impacting points of the solved prefix of the order are surely in the sample: their reference runs
            taken, decided = selected(order, defaults, sample)
            for index in taken:
                if index not in ref_inputs:
                    submit_reference(index)
            found = sum(1 for record in defaults.values() if is_impacting(record))
            in_flight = sum(1 for kind, _ in pending.values() if kind == "default")
            progressed = False
            # screen further candidates, in order, while fewer impacting points than the sample are found
            while not decided and position < len(order) and in_flight < max(workers, 1) and found < sample:
                index = order[position]
                position += 1
                inputs = grid.point(index)
                record = load_cached(cache, "default", index, key_of("default", index, inputs))
                if record is not None:
                    defaults[index] = record
                    report("default", index, record, True)
                    found += is_impacting(record)
                    progressed = True
                    continue
                pending[pool.submit(solve_default, inputs)] = ("default", index)
                in_flight += 1
            if progressed:
                continue
            if not pending:  # the sample decided and its reference runs done, or the candidates exhausted
                break
            done, _ = wait(list(pending), return_when=FIRST_COMPLETED)
            for future in done:
                kind, index = pending.pop(future)
                record = future.result()
                save_cached(cache, kind, index, keys[kind, index], record)
                (defaults if kind == "default" else references)[index] = record
                report(kind, index, record, False)
    except BaseException:  # Ctrl-C or a failure: the finished runs are in the cache; a rerun resumes from them
        pool.shutdown(wait=False, cancel_futures=True)
        raise
    pool.shutdown(wait=True)
    taken, _ = selected(order, defaults, sample)
    seconds = time.perf_counter() - started
    points = []
    for index in taken:
        inputs = grid.point(index)
        points.append(dict(index=index, inputs={name: _finite(inputs.get(name)) for name in SHOWN},
                           default=defaults[index], reference=references[index]))
    screened = [i for i in order if i in defaults]
    say(f"coverage: {len(points)} impacting points of {len(screened)} screened in {seconds:.0f} s")
    return dict(config=str(Path(config).resolve().relative_to(ROOT)) if Path(config).resolve().is_relative_to(ROOT)
                else str(config), grid_size=grid.size, step=golden_step(grid.size), sample=sample,
                screened=len(order[:max((order.index(i) for i in taken), default=-1) + 1]),
                modes_factor=modes_factor, window_factor=window_factor, target=TARGET, seconds=seconds,
                points=points)


# --- the arithmetic --------------------------------------------------------------------------------------------


def true_difference(name: str, default: Mapping[str, Any], reference: Mapping[str, Any]) -> float | None:
    """|default − reference| / reference of a figure (``default``, ``reference``: the runs' values); the
    alternating stress's relative to the larger of the reference's alternating and max bending stresses, the scale
    its stated error is relative to (docs/reference_model.md §3.1). None where either is missing; inf where the
    reference is 0 and the default is not."""
    d, r = default.get(name), reference.get(name)
    if d is None or r is None or not (math.isfinite(d) and math.isfinite(r)):
        return None
    scale = abs(r)
    if name == "alternating_bending_stress":
        scale = max(scale, abs(reference.get("max_bending_stress") or 0.0))
    if scale == 0.0:
        return 0.0 if d == r else math.inf
    return abs(d - r) / scale


def point_rows(point: Mapping[str, Any]) -> dict[str, dict[str, Any]]:
    """Per figure of one sampled point: the stated error (total and parts), the true difference, and whether it is
    covered (true ≤ stated; not covered where no error is stated, None where there is no true difference)."""
    out = {}
    for name in FIGURES:
        stated = point["default"]["errors"][name]
        true = true_difference(name, point["default"]["values"], point["reference"]["values"])
        total = stated.get("total")
        covered = None if true is None else (total is not None and true <= total)
        out[name] = dict(stated=total, parts={k: stated.get(k) for k in ("window", "integrator", "modes")},
                         true=true, covered=covered)
    return out


def shares(points: Iterable[Mapping[str, Any]], target: float = TARGET) -> dict[str, dict[str, Any]]:
    """Per figure over the sample: points compared, covered, the share covered, whether it meets ``target``, the
    median stated and true differences, and the largest true/stated ratio."""
    rows = [point_rows(p) for p in points]
    out = {}
    for name in FIGURES:
        compared = [r[name] for r in rows if r[name]["covered"] is not None]
        covered = sum(1 for r in compared if r["covered"])
        share = covered / len(compared) if compared else math.nan
        ratios = [r["true"] / r["stated"] if r["stated"] else math.inf for r in compared]
        out[name] = dict(compared=len(compared), covered=covered, share=share,
                         meets=bool(compared) and share >= target,
                         stated=float(np.median([r["stated"] for r in compared if r["stated"] is not None]))
                         if any(r["stated"] is not None for r in compared) else math.nan,
                         true=float(np.median([r["true"] for r in compared])) if compared else math.nan,
                         worst=max(ratios) if ratios else math.nan)
    return out


# --- the record ------------------------------------------------------------------------------------------------


def write_results(results: Mapping[str, Any], path: str | Path = RESULTS) -> Path:
    """Store the coverage results (atomically) for :func:`coverage_section`."""
    path = Path(path)
    with atomic_path(path) as tmp:
        Path(tmp).write_text(json.dumps(_finite(dict(results)), indent=1) + "\n", encoding="utf-8")
    return path


def _pct(value) -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    if math.isinf(value):
        return "inf"
    return f"{100 * value:.3g} %"


def _ratio(value) -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    return "inf" if math.isinf(value) else f"{value:.3g}"


def _shown(name: str, value) -> str:
    from study.units import convert

    unit, _, fmt = SHOWN[name]
    if value is None:
        return "-"
    return fmt.format(convert(float(value), SHOWN_SI[name], unit) if unit else float(value))


#: SI units of the shown inputs.
SHOWN_SI = {"dogleg_curvature": "1/m", "rotary_speed": "rad/s",
            "axial_tension": "N", "mud_density": "kg/m^3", "mud_flow_velocity": "m/s"}


def coverage_section(path: str | Path | None = None) -> list[str]:
    """The section of docs/validation.md: the stored coverage results (``path``, default :data:`RESULTS`) as
    markdown; a note saying how to make them where there are none."""
    lines = [HEADING, ""]
    path = Path(RESULTS if path is None else path)
    if not path.exists():
        return lines + [f"No coverage results stored ({path.name} absent): `make coverage` runs them.", ""]
    results = json.loads(path.read_text(encoding="utf-8"))
    points = results["points"]
    summary = shares(points, results.get("target", TARGET))
    mf, wf = results["modes_factor"], results["window_factor"]
    modes = sorted({p["default"].get("modes") for p in points if p["default"].get("modes")})
    lines += [
        f"Generated by `study coverage` (`make coverage`), stored in `docs/coverage.json` and included here by "
        f"`study validate`. Does each figure's stated error (docs/reference_model.md §3.1: window, integrator and "
        f"modes parts) cover its true error? The sample: the points of `{results['config']}`'s "
        f"{results['grid_size']}-point grid in a golden-ratio stride order (flat index k·{results['step']} mod "
        f"{results['grid_size']}), each solved as the sweep solves it (`auto`, default options), the first "
        f"{results['sample']} whose answer is the reference model's at an impacting regime (bouncing, periodic "
        f"impacts) taken ({len(points)} found among the first {results['screened']} candidates). Each is solved "
        f"again by the reference model with {mf}x the modes its default answer used "
        f"({', '.join(str(m) for m in modes) or '-'} -> {', '.join(str(mf * m) for m in modes) or '-'} per "
        f"direction) and {wf}x the window, transient and revolution budget: the true difference is |default − "
        f"that| / that (the alternating stress's relative to the larger of it and the max bending stress, as its "
        f"stated error is), covered where it is within the default answer's stated error."
        + (" The max deflection has no error output: its stated error is its modes part "
           "(`extras[\"modal_error\"]`) and the integrator's, no window part stated (shown as -)."
           if any((p["default"]["errors"].get("max_deflection") or {}).get("window") is None for p in points) else
           " Every figure's stated error is the model's own output (`*_error`), by its parts.")
        + ("" if (mf, wf) >= (MODES_FACTOR, WINDOW_FACTOR) and len(points) >= SAMPLE else
           f" **Preliminary**: {len(points)} points, {mf}x the modes and {wf}x the revolutions, where issue 36 asks "
           f"for at least {SAMPLE} points against {MODES_FACTOR}x the modes and a long window; `make coverage` runs "
           f"that."), "",
        "| figure | covered | share | target | median stated error | median true difference | largest true / stated |",
        "| --- | --- | --- | --- | --- | --- | --- |"]
    target = results.get("target", TARGET)
    for name, label in FIGURES.items():
        s = summary[name]
        lines.append(f"| {label} | {s['covered']} of {s['compared']} | {_pct(s['share'])} | "
                     f"{'met' if s['meets'] else 'not met'} ({_pct(target)}) | {_pct(s['stated'])} | {_pct(s['true'])} "
                     f"| {_ratio(s['worst'])} |")
    met = [FIGURES[name] for name in FIGURES if summary[name]["meets"]]
    missed = [FIGURES[name] for name in FIGURES if not summary[name]["meets"]]
    lines += ["", f"The stated error covers the true difference at {_pct(target)} of the points or more for "
              f"{', '.join(met) or 'no figure'}" + (f"; not for {', '.join(missed)}." if missed else ": every figure.")]
    lines += ["", "Per point: each figure's true difference / stated error (parts of the stated error: window + "
              "integrator + modes; `*` not covered), and the cost of each run (wall time on the machine the command "
              "ran on, its cores shared).", "",
              "| " + " | ".join(label for _, label, _ in SHOWN.values()) + " | default: status, modes, revolutions, "
              "time | reference: modes, revolutions, its own error estimate, time | "
              + " | ".join(FIGURES.values()) + " |",
              "| " + " | ".join(["---"] * (len(SHOWN) + 2 + len(FIGURES))) + " |"]
    for p in points:
        rows = point_rows(p)
        d, r = p["default"], p["reference"]
        cells = [_shown(name, p["inputs"].get(name)) for name in SHOWN]
        cells.append(f"{d['status']}, {d.get('modes') or '-'}, {d['values'].get('revolutions_simulated') or 0:.0f}, "
                     f"{d['wall_time']:.1f} s")
        cells.append(f"{r.get('modes') or '-'}, {r['values'].get('revolutions_simulated') or 0:.0f}, "
                     f"{_pct(r.get('error_estimate'))}, {r['wall_time']:.1f} s")
        for name in FIGURES:
            row = rows[name]
            parts = " + ".join(_pct(row["parts"][k]) for k in ("window", "integrator", "modes"))
            mark = "" if row["covered"] in (True, None) else " *"
            cells.append(f"{_pct(row['true'])} / {_pct(row['stated'])}{mark} ({parts})")
        lines.append("| " + " | ".join(cells) + " |")
    cost_d = [p["default"]["wall_time"] for p in points]
    cost_r = [p["reference"]["wall_time"] for p in points]
    if points:
        lines += ["", f"Cost: the default answers {np.median(cost_d):.1f} s median ({sum(cost_d):.0f} s in all), the "
                  f"reference answers {np.median(cost_r):.1f} s median ({sum(cost_r):.0f} s in all); the command's "
                  "last "
                  f"invocation took {results['seconds']:.0f} s on its workers (runs it found in its cache cost it "
                  "nothing)."]
    return lines + [""]


def replace_section(text: str, section: list[str]) -> str:
    """``text`` (docs/validation.md) with its :data:`HEADING` section (to the next ``## `` heading or the end)
    replaced by ``section``, or ``section`` appended where there is none."""
    lines = text.rstrip("\n").split("\n")
    new = [line for chunk in section for line in str(chunk).split("\n")]
    if HEADING in lines:
        start = lines.index(HEADING)
        end = next((k for k in range(start + 1, len(lines)) if lines[k].startswith("## ")), len(lines))
        lines = lines[:start] + new + lines[end:]
    else:
        lines = lines + [""] + new
    return "\n".join(lines).rstrip() + "\n"


def update_validation(path: str | Path = VALIDATION, results: str | Path | None = None) -> Path:
    """Rewrite the coverage section of docs/validation.md from the stored results (atomically), the rest kept."""
    path = Path(path)
    text = path.read_text(encoding="utf-8") if path.exists() else ""
    with atomic_path(path) as tmp:
        Path(tmp).write_text(replace_section(text, coverage_section(results)), encoding="utf-8")
    return path
