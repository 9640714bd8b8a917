"""One page that holds a study: ``report.html`` with every chart, the safe operating envelope and the provenance.

:func:`write_report` draws every chart of a results dataset (:func:`study.charts.catalogue.save_charts`), writes
the envelope table as CSV beside the charts, and writes the page: the safe rotary speeds per load, each chart
embedded (PNG or SVG as a data URI, so the page stands alone; other formats linked) with a sentence of what it
shows, and the provenance from the dataset's attributes (config text, version, date, config hash, history).
Every file is written atomically (:mod:`study.atomic`).
"""

from __future__ import annotations

import base64
import html
import os
from pathlib import Path

from study.atomic import atomic_path
from study.charts.catalogue import save_charts
from study.charts.critical import api_comparison
from study.charts.envelope import CRITERIA, MARGIN, envelope_table, safe_ranges, write_table
from study.charts.limits import DEFAULT_TARGET_LIFE_HOURS
from study.charts.labels import format_value, quantity

REPORT = "report.html"
TABLE = "envelope.csv"
MEDIA = {"png": "image/png", "svg": "image/svg+xml"}
STYLE = """
body { font-family: sans-serif; max-width: 1200px; margin: 2em auto; padding: 0 1em; color: #222; }
figure { margin: 2em 0; border-top: 1px solid #ddd; padding-top: 1em; }
figure img { max-width: 100%; height: auto; }
figcaption { color: #444; margin-top: 0.5em; }
table { border-collapse: collapse; }
th, td { border: 1px solid #ccc; padding: 0.3em 0.8em; text-align: left; }
pre { background: #f6f6f6; padding: 1em; overflow-x: auto; }
"""


def write_report(dataset_path, out_dir=None, fmt: str = "png", target_hours: float = DEFAULT_TARGET_LIFE_HOURS,
                 criterion: str = "life", regime_points: bool = True) -> list[Path]:
    """Draw every chart, write the envelope CSV beside them and ``report.html``; return the written paths.

    dataset_path : the results netCDF (or an open dataset, then ``out_dir`` is needed).
    out_dir : the charts' folder, default ``charts/`` beside the dataset. The page goes beside the dataset
        (``outputs/<study>/report.html``), or into ``out_dir`` when one is given.
    target_hours, criterion : the fatigue limit of the envelope (see :func:`study.charts.envelope.failures`).
    regime_points : also draw what the pipe does at one point of each regime the study found
        (:func:`study.charts.point.point_chart`, the reference model run again there: a second or so each), where the
        dataset records its config and regimes.
    """
    if criterion not in CRITERIA:
        raise ValueError(f"criterion = {criterion!r}; allowed: {', '.join(CRITERIA)}")
    ds, saved = save_charts(dataset_path, out_dir, fmt, target_hours=target_hours, criterion=criterion)
    if out_dir is None:
        charts_dir = Path(dataset_path).parent / "charts"
        page = Path(dataset_path).parent / REPORT
    else:
        charts_dir = Path(out_dir)
        page = charts_dir / REPORT
    written = [path for path, _ in saved]
    rows = envelope_table(ds, target_hours, criterion)
    table = None
    if rows:
        table = write_table(rows, charts_dir / TABLE)
        written.append(table)
    body = [f"<h1>{_e(ds.attrs.get('title') or ds.attrs.get('study_name') or 'Study')}</h1>",
            f"<p>Study <code>{_e(ds.attrs.get('study_name', ''))}</code>: {_e(_size(ds))}.</p>",
            _answers(ds),
            _envelope_section(rows, table, page.parent, target_hours, criterion, api_comparison(ds)),
            _drivers_section(ds),
            "<h2>Charts</h2>"]
    body += [_figure(path, chart, page.parent) for path, chart in saved]
    if regime_points:
        seen = _regime_figures(ds, charts_dir, fmt)
        written += [path for path, _ in seen]
        if seen:
            body.append('<h2 id="regimes-seen">What the pipe does: one point of each regime</h2>')
            body += [_figure(path, chart, page.parent) for path, chart in seen]
    body.append(_provenance(ds))
    text = ("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            f"<title>{_e(ds.attrs.get('title', 'study report'))}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n"
            + "\n".join(body) + "\n</body>\n</html>\n")
    with atomic_path(page) as tmp:
        Path(tmp).write_text(text, encoding="utf-8")
    written.append(page)
    return written


def _e(text) -> str:
    return html.escape(str(text))


def _size(ds) -> str:
    swept = [f"{quantity(ds[d]).short_name} ({n} values)" for d, n in ds.sizes.items() if n > 1]
    points = 1
    for n in ds.sizes.values():
        points *= n
    return f"{points} design points" + (" over " + ", ".join(swept) if swept else "")


def representative_points(ds) -> list[tuple[str, dict]]:
    """One answered point of each regime in the dataset (the one at the median rotary speed of that regime's
    points): [(regime name, {dimension: index})]."""
    import numpy as np

    from study.charts.design import full_array
    from study.charts.plane import answered_points
    from study.solvers.model.result import REGIMES

    if "regime" not in ds.data_vars or not ds.sizes:
        return []
    regime = full_array(ds, "regime").where(answered_points(ds)).values
    dims = list(ds.sizes)
    out = []
    for name, code in REGIMES.items():
        where = np.argwhere(regime == code)
        if not where.size:
            continue
        order = where[:, dims.index("rotary_speed")] if "rotary_speed" in dims else np.arange(len(where))
        pick = where[np.argsort(order, kind="stable")[len(where) // 2]]
        out.append((name, {d: int(i) for d, i in zip(dims, pick)}))
    return out


def _regime_figures(ds, folder: Path, fmt: str) -> list:
    """:func:`representative_points` drawn (study.charts.point) and saved; a point whose config cannot be read back
    or whose motion cannot be drawn is left out (the report never fails on it)."""
    from study.charts.design import save_figure
    from study.charts.point import point_chart
    from study.config import ConfigError, load_text

    text = ds.attrs.get("config")
    points = representative_points(ds)
    if not text or not points:
        return []
    try:
        study = load_text(text, "the dataset's config")
    except (ConfigError, ValueError):
        return []
    saved = []
    for name, index in points:
        where = {d: ds[d].values[i] for d, i in index.items() if ds.sizes[d] > 1}
        try:
            inputs = study.point(**{d: v.item() if hasattr(v, "item") else v for d, v in where.items()})
            chart = point_chart(inputs)
        except Exception:  # noqa: BLE001 - a drawing aid: the report stands without it
            continue
        chart.name = f"point__{name}"
        shown = ", ".join(quantity(ds[d]).describe(ds[d].values[i]) for d, i in index.items() if ds.sizes[d] > 1)
        chart.caption = f"Regime {name.replace('_', ' ')}, at {shown}: " + chart.caption[0].lower() + chart.caption[1:]
        try:
            chart.title = chart.figure.get_suptitle()
            saved.append((save_figure(chart.figure, folder / f"{chart.name}.{fmt}", fmt), chart))
        finally:
            chart.figure.clear()
    return saved


def _drivers_section(ds) -> str:
    from study.charts.drivers import drivers_table_html, main_effects

    rows = main_effects(ds)
    if not rows:
        return ""
    return ("<h2>Which input drives the design</h2>\n<p>How much each swept input moves each design figure, from the "
            "full-factorial grid: its main effect — the variance of the figure's mean at each of the input's levels "
            "(the mean over every other input), as a share of the figure's variance over the grid, a first-order "
            "Sobol index on the grid — with, in brackets, how far that mean moves across the levels; what the main "
            "effects leave is every interaction together, and the largest two-way interaction (the variance of the "
            "means over a pair less their main effects) is named. Answered points only; the fatigue life as log₁₀ "
            "of hours (a share of its decades).</p>\n" + drivers_table_html(rows, _e))


def _answers(ds) -> str:
    """The points by status, and — where no point has an answer — why, at the top of the page."""
    if "status" not in ds.data_vars:
        return ""
    from collections import Counter

    import numpy as np

    from study.charts.plane import answered_points
    from study.solvers.model.result import STATUS

    names = {code: name for name, (code, _) in STATUS.items()}
    codes = np.asarray(ds["status"].values).ravel()
    counts = Counter(names.get(int(c), str(c)) for c in codes)
    text = ", ".join(f"{n} {name}" for name, n in counts.most_common())
    out = f'<p id="statuses">Points by status: {_e(text)}.</p>'
    if not bool(answered_points(ds).any()):
        common = counts.most_common(1)[0][0]
        sample = ""
        if "message" in ds.data_vars:
            messages = np.asarray(ds["message"].values).ravel()
            sample = str(messages[int(np.flatnonzero(codes == STATUS[common][0])[0])]) if common in STATUS else ""
        out += (f'<p id="no-answer"><strong>No point of this study has an answer</strong>: every point is '
                f"{_e(', '.join(counts))} — {_e(STATUS.get(common, (0, ''))[1])}. The maps are empty and there is no "
                f"envelope; choose a method that serves these inputs (solver.method). For example: "
                f"{_e(sample)}</p>")
    return out


def _envelope_section(rows, table, folder: Path, target_hours: float, criterion: str, critical: str = "") -> str:
    if not rows:
        return ("<h2>Safe operating envelope</h2><p>No envelope: it needs rotary speed and axial load both swept and "
                "the design limits (yield utilisation and fatigue) in the dataset.</p>")
    limit = (f"fatigue life at least {format_value(target_hours)} h" if criterion == "life"
             else "below the endurance limit")
    lines = ["<h2>Safe operating envelope</h2>",
             f"<p>Rotary speeds where every point (over every other swept input) is answered and decided, below yield, "
             f"{_e(limit)} and outside ±15 % of the joint's critical speeds (1× and 2×: the crossings the Campbell "
             "chart marks). A point not converged to the study's tolerance counts where its limits hold (or fail) "
             f"with its stresses off by {MARGIN:g} times its error estimate; where they do not, the cell is "
             "undecided.</p>",
             f'<p id="critical-speeds">{_e(critical)}</p>' if critical else "",
             '<table id="envelope"><thead><tr><th>axial load</th><th>safe rotary speeds</th>'
             "<th>undecided rotary speeds</th></tr></thead><tbody>"]
    undecided = dict(safe_ranges(rows, "undecided"))
    lines += [f"<tr><td>{_e(load)}</td><td>{_e(speeds)}</td><td>{_e(undecided.get(load, ''))}</td></tr>"
              for load, speeds in safe_ranges(rows)]
    lines.append("</tbody></table>")
    link = os.path.relpath(table, folder)
    lines.append(f'<p>Every cell: its verdict, what limits it or keeps it undecided, and its worst values over every '
                 f'answered point — undecided ones included — with the error estimate of the point that gives each and '
                 f'the worst case at {MARGIN:g}x the error (also as <a href="{_e(Path(link).as_posix())}">'
                 f"{_e(TABLE)}</a>).</p>")
    lines.append(_cell_table(rows, criterion))
    return "\n".join(lines)


def _cell_table(rows: list[dict], criterion: str) -> str:
    """Every cell of the envelope as a row of the page (the CSV's columns that decide)."""
    speed_key, load_key = list(rows[0])[:2]
    figure = "min fatigue life" if criterion == "life" else "max endurance utilisation"
    unit = "[h]" if criterion == "life" else "[-]"
    head = [load_key, speed_key, "verdict", "limited by / undecided because", f"{figure} {unit}",
            "its error estimate", f"{figure} at {MARGIN:g}x error {unit}", "max yield utilisation [-]",
            f"max yield utilisation at {MARGIN:g}x error [-]", "points (ok, decided within error, undecided, no "
                                                               "answer)"]
    out = ['<table id="envelope-cells"><thead><tr>' + "".join(f"<th>{_e(h)}</th>" for h in head)
           + "</tr></thead><tbody>"]
    for r in rows:
        why = r["limited by"] or r["undecided because"]
        error = r[f"{figure}: its error estimate [-]"]
        cells = [format_value(r[load_key]), format_value(r[speed_key]), r["verdict"], why,
                 format_value(r[f"{figure} {unit}"]), f"{error:.0%}" if error == error else "",
                 format_value(r[f"{figure} at {MARGIN:g}x error {unit}"]), format_value(r["max yield utilisation [-]"]),
                 format_value(r[f"max yield utilisation at {MARGIN:g}x error [-]"]),
                 f"{r['points']} ({r['ok points']}, {r['decided within their error']}, {r['undecided points']}, "
                 f"{r['points without an answer']})"]
        out.append(f'<tr class="{_e(r["verdict"])}">' + "".join(f"<td>{_e(c)}</td>" for c in cells) + "</tr>")
    out.append("</tbody></table>")
    return "\n".join(out)


def _figure(path: Path, chart, folder: Path) -> str:
    fmt = path.suffix.lstrip(".").lower()
    title = (chart.title or chart.name).split("\n")[0]
    if fmt in MEDIA:
        data = base64.b64encode(path.read_bytes()).decode("ascii")
        shown = f'<img src="data:{MEDIA[fmt]};base64,{data}" alt="{_e(chart.name)}" data-chart="{_e(chart.name)}">'
    else:
        link = Path(os.path.relpath(path, folder)).as_posix()
        shown = f'<p><a href="{_e(link)}" data-chart="{_e(chart.name)}">{_e(path.name)}</a></p>'
    return (f'<figure id="chart-{_e(chart.name)}">\n<h3>{_e(title)}</h3>\n{shown}\n'
            f"<figcaption>{_e(chart.caption)}</figcaption>\n</figure>")


def _provenance(ds) -> str:
    attrs = ds.attrs
    items = [("study", attrs.get("study_name", "")), ("version", attrs.get("source", "")),
             ("date", attrs.get("date_created", "")), ("config hash", attrs.get("config_hash", "")),
             ("history", attrs.get("history", ""))]
    rows = "\n".join(f"<dt>{_e(k)}</dt><dd>{_e(v)}</dd>" for k, v in items if v)
    return (f'<h2>Provenance</h2>\n<dl id="provenance">\n{rows}\n</dl>\n<h3>Configuration</h3>\n'
            f'<pre id="config">{_e(attrs.get("config", "(not recorded)"))}</pre>')
