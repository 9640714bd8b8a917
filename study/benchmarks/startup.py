"""The start-up of a bouncing pipe and where the reference model's run at more modes starts (docs/reference_model.md
§3.1, "The run at more modes goes on from the run at fewer").

Each revolution's figures of a run from the wall's rest (``reference_initial = "forced"``) at a fixed mode count, and
their means over the start-up's 6 revolutions, the 12-revolution stretches after it to the 42nd and the second half::

    python -m study.benchmarks.startup record 298,332,338 64 200 out.jsonl

The reference method's answer as the sweep takes it (16 modes, then 64 started where the 16-mode run ended) against
the same point's 64-mode run started from the wall's rest, and, where a coverage record is given (``study coverage``,
docs/coverage.json), against its reference answer at the point::

    python -m study.benchmarks.startup compare 298,332,338 out.jsonl docs/coverage.json

Points are flat indices of configs/default.toml's grid. One JSON line per point; a summary on stdout. CPU seconds are
``time.process_time``.
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np

from study.benchmarks.strikes import default_grid

#: Revolutions of the start-up and of a stretch after it in ``record``'s summary
START, STRETCH = 6, 12


def record(indices, modes: int, revolutions: int, out) -> None:
    """Each revolution's figures (force [N], max normal and alternating stress [Pa], the worst fibre's damage of the
    revolution alone) and contact onsets, from the wall's rest at ``modes`` modes."""
    from study.solvers.methods import reference

    grid = default_grid()
    for index in indices:
        point = {**grid.point(int(index)), "reference_modes": modes, "reference_max_modes": modes}
        model = reference.build_model(point)
        run = reference.Integrator(model, 1e-6, reference.initial_state(model, "forced"))
        rows, started = [], time.process_time()
        for k in range(1, revolutions + 1):
            cycle = run.run(k * model.period, record=True)
            if run.outcome != 0:
                break
            value = reference.cycle_values(point, model, [cycle])[0]
            rows.append(dict(peak_contact_force=float(value["peak_contact_force"]),
                             max_normal_stress=float(value["max_normal_stress"]),
                             alternating_bending_stress=float(value["alternating_bending_stress"]),
                             damage=float(np.max(value[reference.DAMAGE])), onsets=float(np.sum(cycle.onsets))))
        line = dict(index=index, modes=modes, revolutions=len(rows), cpu=time.process_time() - started, rows=rows)
        with open(out, "a") as handle:
            handle.write(json.dumps(line) + "\n")
        force = np.array([r["peak_contact_force"] for r in rows]) / 1e3
        stress = np.array([r["alternating_bending_stress"] for r in rows]) / 1e6
        # the start-up (the 6 revolutions the stationarity test never reads), the 12-revolution stretches after it to
        # the 42nd (the default window read revolutions 7-18 or 13-24), and the record's second half
        stretches = [(0, START)] + [(a, a + STRETCH) for a in range(START, min(42, len(rows)), STRETCH)] + [
            (len(rows) // 2, len(rows))]
        print(f"{index}: {len(rows)} revolutions at {modes} modes, {line['cpu']:.0f} s; per {STRETCH} revolutions, "
              "peak force [kN] / alternating stress [MPa]: "
              + ", ".join(f"{a + 1}-{b}: {force[a:b].mean():.1f} / {stress[a:b].mean():.1f}" for a, b in stretches),
              flush=True)


def compare(indices, out, coverage=None) -> None:
    """The default chain's answer against a run from the wall's rest at the chain's last mode count, each figure's
    value (the coverage's figures, :data:`study.coverage.FIGURES`) and stated error and, with a coverage record, its
    ratio to the record's reference answer."""
    from study.coverage import FIGURES
    from study.solvers.methods import reference
    from study.solvers.model.point import DesignPoint

    def timed(point) -> dict:
        started = time.process_time()
        result = reference.run(point)
        parts = result.extras.get("convergence") or {}
        return dict(cpu=time.process_time() - started, modes=result.extras["reference_modes"],
                    continued_from=result.extras.get("continued_from_modes"),
                    revolutions=float(result.values.get("revolutions_simulated", np.nan)),
                    values={n: float(result.values.get(n, np.nan)) for n in FIGURES},
                    stated={n: float(parts[n]["total"]) for n in FIGURES if n in parts})

    references = {}
    if coverage:
        references = {p["index"]: p["reference"]["values"] for p in json.loads(Path(coverage).read_text())["points"]}
    grid = default_grid()
    for index in indices:
        point = DesignPoint.of(grid.point(int(index)))
        continued = timed(point)
        modes = continued["modes"]
        line = dict(index=index, continued=continued,
                    rest=timed(point.with_reference(reference_modes=modes, reference_max_modes=modes)))
        with open(out, "a") as handle:
            handle.write(json.dumps(line) + "\n")
        ref = references.get(index)
        shown = ", ".join(
            f"{n}: " + " / ".join(f"{line[k]['values'][n] / ref[n]:.2f}" if ref else f"{line[k]['values'][n]:.4g}"
                                  for k in ("continued", "rest")) for n in FIGURES)
        print(f"{index} ({'ratio to the coverage reference' if ref else 'values'}, continued / from rest): {shown}; "
              f"CPU {continued['cpu']:.1f} / {line['rest']['cpu']:.1f} s", flush=True)


def main(argv: list[str]) -> None:
    if argv and argv[0] == "record":
        record([int(i) for i in argv[1].split(",")], int(argv[2]), int(argv[3]), argv[4])
    elif argv and argv[0] == "compare":
        compare([int(i) for i in argv[1].split(",")], argv[2], argv[3] if len(argv) > 3 else None)
    else:
        raise SystemExit(__doc__)


if __name__ == "__main__":
    main(sys.argv[1:])
