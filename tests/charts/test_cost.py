"""Cost against accuracy of the methods, point by point (study.charts.cost)."""

from pathlib import Path

import numpy as np
import xarray as xr

from study.charts import figure_labels
from study.charts.cost import cost_accuracy_chart, study_tolerance_of

ROOT = Path(__file__).resolve().parents[2]


def _results(config_text: str = "") -> xr.Dataset:
    # six points: three answered by a cheap method with estimates, three by a dear one without
    methods = np.array(["free-whirl"] * 3 + ["reference"] * 3)
    times = np.array([0.002, 0.003, 0.004, 0.2, 0.3, 1.5])
    errors = np.array([1e-4, 2e-4, 5e-4, np.nan, np.nan, np.nan])
    ds = xr.Dataset({"method": ("rotary_speed", methods), "wall_time": ("rotary_speed", times),
                     "error_estimate": ("rotary_speed", errors)}, coords={"rotary_speed": np.arange(6.0)})
    if config_text:
        ds.attrs["config"] = config_text
    return ds


def test_every_point_is_drawn_with_its_method_share_and_the_tolerance():
    ds = _results((ROOT / "configs" / "default.toml").read_text())
    (chart,) = cost_accuracy_chart(ds)
    labels = figure_labels(chart.figure)
    # medians and shares of the synthetic points: 3 ms and 9/2009 of the compute; 300 ms and 2000/2009
    assert "free-whirl: 3 points, median 3 ms, 0.448 % of the compute" in labels["legend"]
    assert "reference: 3 points, median 300 ms, 99.6 % of the compute" in labels["legend"]
    ax = chart.figure.axes[0]
    drawn = sum(len(c.get_offsets()) for c in ax.collections)
    assert drawn == 6  # the three without an estimate sit on the bottom band
    assert [line.get_ydata()[0] for line in ax.get_lines()][0] == 1.0  # default.toml's tolerance: 1 %
    assert labels["xlabels"] == ["wall-clock time per point [ms]"]


def test_the_tolerance_is_read_from_the_dataset_config():
    assert study_tolerance_of(_results((ROOT / "configs" / "default.toml").read_text())) == 0.01
    assert study_tolerance_of(_results()) is None  # no config: no line, no guess


def test_no_chart_without_the_variables():
    assert cost_accuracy_chart(_results().drop_vars("method")) == []
