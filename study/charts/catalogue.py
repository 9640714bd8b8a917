"""Which charts a results dataset gets, in the order a reader needs them, and drawing them to files.

Decision charts first (the safe envelope, stresses against their limits, fatigue life, contact force, the regime
of the motion, the rotary speeds to avoid, the validity of the points, what each answer cost and how sure it is), then
the solution's own charts (span, contact, the span's natural frequencies) and the method crosschecks. Each chart
function takes the dataset and returns a list of :class:`~study.charts.design.Chart`, empty when the variables or
dimensions it needs are absent.
"""

from __future__ import annotations

from pathlib import Path

import xarray as xr

from study.charts.cost import cost_accuracy_chart
from study.charts.critical import campbell_chart
from study.charts.design import (Chart, contact_force_and_duration_vs_rpm, crosscheck_maps, natural_frequencies_vs_rpm,
                                 orbit_maps, reference_maps, save_figure, span_length_vs_rpm)
from study.charts.drivers import drivers_chart
from study.charts.envelope import envelope_chart
from study.charts.limits import DEFAULT_TARGET_LIFE_HOURS, contact_force_map, fatigue_life_map, stress_limit_maps
from study.charts.regimes import lift_off_map, regime_map
from study.charts.validity import validity_map

#: Every chart, in the order :func:`draw` draws them.
CHARTS = (envelope_chart, stress_limit_maps, fatigue_life_map, contact_force_map, drivers_chart, regime_map,
          lift_off_map, campbell_chart, validity_map, cost_accuracy_chart, span_length_vs_rpm,
          contact_force_and_duration_vs_rpm, natural_frequencies_vs_rpm, crosscheck_maps, orbit_maps, reference_maps)
#: Charts that take the fatigue target (target_hours [h]) and, for the envelope, the fatigue criterion.
_TAKE_TARGET = {envelope_chart: ("target_hours", "criterion"), fatigue_life_map: ("target_hours",)}


def draw(ds: xr.Dataset, target_hours: float = DEFAULT_TARGET_LIFE_HOURS, criterion: str = "life") -> list[Chart]:
    """Every chart the dataset's variables and dimensions allow (none for a dataset without dimensions).

    target_hours: the fatigue life [h] the envelope and the fatigue map hold the pipe to; criterion: "life"
    (fatigue life ≥ target_hours) or "endurance" (below the endurance limit) for the envelope.
    """
    options = {"target_hours": target_hours, "criterion": criterion}
    charts = []
    for function in CHARTS:
        charts += function(ds, **{k: options[k] for k in _TAKE_TARGET.get(function, ())})
    return charts


def open_results(dataset_path) -> xr.Dataset:
    """The results dataset at ``dataset_path``, loaded into memory and closed."""
    with xr.open_dataset(Path(dataset_path)) as opened:
        return opened.load()


def draw_all(dataset_path, out_dir=None, fmt: str = "png", **options) -> list[Path]:
    """Draw every chart the dataset allows into ``out_dir`` and return the written paths.

    dataset_path : the results netCDF (or an open :class:`xarray.Dataset`, then ``out_dir`` is needed).
    out_dir : default ``charts/`` beside the dataset; created only when a chart is drawn.
    fmt : file format, e.g. "png", "pdf", "svg". options: as :func:`draw`.
    """
    return [path for path, _ in save_charts(dataset_path, out_dir, fmt, **options)[1]]


def save_charts(dataset_path, out_dir=None, fmt: str = "png", **options) -> tuple[xr.Dataset, list[tuple[Path, Chart]]]:
    """The dataset and every chart saved (see :func:`draw_all`): (path, chart) pairs, the figures cleared after
    saving (their captions and titles kept)."""
    if isinstance(dataset_path, xr.Dataset):
        if out_dir is None:
            raise ValueError("out_dir is needed when drawing an in-memory dataset")
        ds = dataset_path
    else:
        ds = open_results(dataset_path)
        if out_dir is None:
            out_dir = Path(dataset_path).parent / "charts"
    out_dir = Path(out_dir)
    written = []
    for chart in draw(ds, **options):
        try:
            title = chart.figure.get_suptitle()
            written.append((save_figure(chart.figure, out_dir / f"{chart.name}.{fmt}", fmt), chart))
            chart.title = title
        finally:
            chart.figure.clear()
    return ds, written
