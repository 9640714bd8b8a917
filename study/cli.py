"""The ``study`` command: point, sweep, charts, compile, bench, validate, coverage.

Bad input ends with one clear message listing every problem and exit status 2, never a traceback.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time

from study import __version__
from study.config import MAX_GRID, MAX_WORKERS, ConfigError, load, parse_set
from study.solvers import METHODS, solve_point
from study.workflow.compiled import cached, compile_ahead, ensure_compiled, kernels, uncached
from study.workflow.execute import Interrupted, SweepError, tell

DEFAULT_CONFIG = "configs/default.toml"

def _finite_or_none(value):
    """JSON has no inf, NaN or complex: non-finite floats become null, complex numbers [re, im]."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, complex):
        return [_finite_or_none(value.real), _finite_or_none(value.imag)]
    if isinstance(value, (list, tuple)):
        return [_finite_or_none(v) for v in value]
    if isinstance(value, dict):
        return {k: _finite_or_none(v) for k, v in value.items()}
    return value


def _point_json(result, inputs) -> str:
    payload = {"inputs": {k: _finite_or_none(v) for k, v in inputs.items() if v is not None}}
    payload.update({k: _finite_or_none(v) for k, v in result.as_dict().items()})
    return json.dumps(payload, indent=2)


def _point_table(result, inputs, system: str = "oilfield") -> str:
    from study.table import point_table

    return point_table(result, inputs, system)


def cmd_point(args) -> int:
    if args.plot and not args.plot.lower().endswith((".png", ".pdf", ".svg")):
        raise ValueError(f"--plot {args.plot}: allowed: a file ending in .png, .pdf or .svg")
    study = load(args.config, parse_set(args.set or []))
    inputs = study.point()
    if args.method:
        inputs["solver_method"] = args.method
    ensure_compiled(inputs, say=tell)
    result = solve_point(inputs)
    print(_point_json(result, inputs) if args.json else _point_table(result, inputs, "si" if args.si else "oilfield"))
    if args.plot:
        from pathlib import Path

        from study.charts.design import save_figure
        from study.charts.point import point_chart

        path = Path(args.plot)
        fmt = path.suffix.lstrip(".").lower()
        chart = point_chart(inputs)
        save_figure(chart.figure, path, fmt)
        print(f"{'' if args.json else 'plot: '}{path}", file=sys.stderr if args.json else sys.stdout)
    return 0


def cmd_sweep(args) -> int:
    start = time.perf_counter()
    try:
        from study.workflow.sweep import run_sweep

        study = load(args.config, parse_set(args.set or []))
        path = run_sweep(study, out_dir=args.out, scheduler=args.scheduler, workers=args.workers,
                         progress=not args.quiet, max_points=args.max_points, charts=not args.no_charts)
    except Interrupted:
        raise
    except KeyboardInterrupt:
        raise KeyboardInterrupt("interrupted before the sweep started: nothing new was computed") from None
    print(f"results: {path}")
    from study.charts.catalogue import open_results
    from study.charts.summary import sweep_summary

    report = table = None
    if not args.no_charts:
        from study.charts.report import REPORT, TABLE, write_report

        written = write_report(path)
        figures = [p for p in written if p.name not in (REPORT, TABLE)]
        if figures:
            print(f"charts:  {len(figures)} in {figures[0].parent}")
        report = next((p for p in written if p.name == REPORT), None)
        table = next((p for p in written if p.name == TABLE), None)
    results = open_results(path)
    seconds = time.perf_counter() - start
    print(sweep_summary(results, seconds, report, table))
    if args.no_charts:
        print(f"  report: not written (--no-charts); draw it with: study charts {path}")
    if args.record:
        from pathlib import Path

        from study.atomic import atomic_path
        from study.charts.summary import run_record

        record = Path(args.record) / f"{study.name}.md"
        record.parent.mkdir(parents=True, exist_ok=True)
        with atomic_path(record) as tmp:
            Path(tmp).write_text(run_record(results, seconds), encoding="utf-8")
        print(f"  record: {record}")
    return 0


def cmd_charts(args) -> int:
    from study.charts.report import write_report

    for figure in write_report(args.dataset, out_dir=args.out, fmt=args.format):
        print(figure)
    return 0


def cmd_compile(args) -> int:
    missing = uncached()
    print(f"compiling the solver kernels ahead ({len(missing)} of {len(kernels())} not in numba's cache); "
          "every method once on the warm-up points:")
    seconds = compile_ahead(say=print)
    left = [name for name, dispatcher in kernels().items() if not cached(dispatcher)]
    print(f"compiled in {seconds:.0f} s; not reached at the warm-up points (compiled on their first use): "
          f"{', '.join(left) or 'none'}")
    return 0


def cmd_bench(args) -> int:
    from study.bench import SECTIONS, bench_large_sweep, run_bench

    problems = [f"--section {name!r}: not a section; allowed: {', '.join(SECTIONS)}"
                for name in args.section or () if name not in SECTIONS]
    if args.points is not None and not args.large:
        problems.append(f"--points {args.points}: only with --large (the large sweep's grid thinned to N points)")
    if args.large and args.section:
        problems.append("--section: not with --large (the large sweep is one measurement)")
    if problems:
        print("study bench: " + "; ".join(problems), file=sys.stderr)
        return 2
    if args.large:
        print(bench_large_sweep(out=args.out, points=args.points))
    else:
        print(run_bench(args.out, sections=args.section))
    return 0


def cmd_validate(args) -> int:
    from study.validate import run_validate

    report = run_validate()
    if args.out:
        with open(args.out, "w") as handle:
            handle.write(report)
        print(f"written {args.out}")
    else:
        print(report)
    return 0


def cmd_coverage(args) -> int:
    from study import coverage

    study = load(args.config)
    ensure_compiled(study.point(**{name: values[0] for name, values in study.axes.items()}), say=tell)
    results = coverage.run_coverage(args.config, sample=args.sample, modes_factor=args.modes_factor,
                                    window_factor=args.window_factor, workers=args.workers, cache=args.cache,
                                    say=print)
    written = coverage.write_results(results, args.out)
    print(f"written {written}")
    if args.validation:
        print(f"written {coverage.update_validation(args.validation, written)} (its coverage section)")
    for name, share in coverage.shares(results["points"], results["target"]).items():
        print(f"  {coverage.FIGURES[name]}: {share['covered']} of {share['compared']} covered "
              f"({'meets' if share['meets'] else 'misses'} the {results['target']:.0%} target)")
    return 0


def whole_number(low: int, high: int, meaning: str = ""):
    """An argparse type: a whole number in [low, high]; anything else is refused naming the value and the range
    (argparse adds the option's name and exits with status 2)."""

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            value = None
        if value is None or not low <= value <= high:
            raise argparse.ArgumentTypeError(f"{text[:40]!r}: must be a whole number >= {low} and <= {high}{meaning}")
        return value

    return parse


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="study", description=__doc__.splitlines()[0])
    parser.add_argument("--version", action="version", version=f"study {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)

    p = sub.add_parser("point", help="evaluate one design point")
    p.add_argument("config", nargs="?", default=DEFAULT_CONFIG)
    p.add_argument("--set", action="append", metavar="SECTION.KEY=VALUE",
                   help='override an input, e.g. --set load.rotary_speed="200 rpm" (repeatable)')
    p.add_argument("--method", choices=sorted(METHODS))
    p.add_argument("--json", action="store_true", help="print one JSON object, SI values")
    p.add_argument("--si", action="store_true", help="the table in SI units (default: oilfield units)")
    p.add_argument("--plot", default=None, metavar="FILE",
                   help="also draw what the pipe does there (the reference model's orbit, contact forces and "
                        "deflection) into FILE (.png, .pdf, .svg)")
    p.set_defaults(func=cmd_point)

    p = sub.add_parser("sweep", help="solve every point of the config's grid and write outputs/<name>/")
    p.add_argument("config", nargs="?", default=DEFAULT_CONFIG)
    p.add_argument("--set", action="append", metavar="SECTION.KEY=VALUE")
    p.add_argument("--out", default=None, help="output folder (default outputs/<study name>)")
    p.add_argument("--scheduler", default=None, help="address of a dask.distributed scheduler")
    p.add_argument("--workers", type=whole_number(0, MAX_WORKERS, " (0: one per core)"), default=None,
                   help="local worker processes (default: sweep.workers, else one per core)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.add_argument("--no-charts", action="store_true", help="skip the charts")
    p.add_argument("--record", default=None, metavar="FOLDER",
                   help="also write the run's record, FOLDER/<study name>.md (make sweep: docs/runs)")
    p.add_argument("--max-points", type=whole_number(1, MAX_GRID), default=None, metavar="N",
                   help="largest grid accepted (default sweep.max_points, 1000000)")
    p.set_defaults(func=cmd_sweep)

    p = sub.add_parser("charts", help="draw the design charts of a results dataset")
    p.add_argument("dataset")
    p.add_argument("--out", default=None, help="folder (default: charts/ beside the dataset)")
    p.add_argument("--format", default="png", choices=["png", "pdf", "svg"])
    p.set_defaults(func=cmd_charts)

    p = sub.add_parser("compile", help="compile the solver kernels ahead, once (make setup runs it)")
    p.set_defaults(func=cmd_compile)

    p = sub.add_parser("bench", help="benchmark the methods side by side")
    p.add_argument("--out", default=None, help="also write the report to this markdown file")
    p.add_argument("--large", action="store_true",
                   help="instead, the measured sweep of configs/dense.toml's 103 424 points (about 9 minutes)")
    p.add_argument("--section", action="append", metavar="NAME",
                   help="run this section alone (repeatable; default: make bench's sections); the sections: "
                        "study.bench.SECTIONS")
    p.add_argument("--points", type=whole_number(1, 10**6), default=None, metavar="N",
                   help="with --large: the grid thinned evenly to at most N points (a smoke test of the command)")
    p.set_defaults(func=cmd_bench)

    p = sub.add_parser("validate", help="compare with the printed numbers of the sources")
    p.add_argument("--out", default=None, help="write the report to this markdown file")
    p.set_defaults(func=cmd_validate)

    p = sub.add_parser("coverage", help="check the stated errors on a held-back sample of impacting points against "
                                        "runs with more modes and a longer window (docs/validation.md)")
    p.add_argument("config", nargs="?", default=DEFAULT_CONFIG)
    p.add_argument("--sample", type=whole_number(1, 1000), default=20, metavar="N",
                   help="impacting points in the sample (default 20)")
    p.add_argument("--modes-factor", type=whole_number(2, 16), default=4, metavar="K",
                   help="the reference runs' modes, times the default answer's (default 4)")
    p.add_argument("--window-factor", type=whole_number(1, 16), default=4, metavar="K",
                   help="the reference runs' window, transient and revolution budget, times the defaults (default 4)")
    p.add_argument("--workers", type=whole_number(0, MAX_WORKERS, " (0: in this process)"), default=2,
                   help="worker processes (default 2)")
    p.add_argument("--cache", default=None, metavar="FOLDER",
                   help="finished runs, reused by a rerun (default outputs/coverage/<study name>)")
    p.add_argument("--out", default="docs/coverage.json", help="the results (default docs/coverage.json)")
    p.add_argument("--validation", default="docs/validation.md", metavar="FILE",
                   help="rewrite the coverage section of this file (default docs/validation.md; '' for none)")
    p.set_defaults(func=cmd_coverage)
    return parser


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except KeyboardInterrupt as exc:  # a sweep says what it kept; anything else just stops
        print(f"study: {str(exc) or 'interrupted'}", file=sys.stderr)
        return 130
    except SweepError as exc:  # an unwritable output, a running sweep, a grid too large: one line
        print(f"study: error: {exc}", file=sys.stderr)
        return 1
    except ConfigError as exc:
        print(f"study: error: {exc}", file=sys.stderr)
        return 2
    except ValueError as exc:  # e.g. an unknown method: a user's mistake, not a crash
        print(f"study: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
