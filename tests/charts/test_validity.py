"""The validity map by fraction of points (study.charts.validity)."""

import numpy as np
from matplotlib.collections import PolyCollection

from study.charts import figure_labels
from study.charts.validity import validity_fractions, validity_map


def test_fractions_sum_to_one_and_count_the_points_of_each_cell(study):
    fractions = validity_fractions(study)
    assert list(fractions["status"].values) == ["ok", "no_span"]
    np.testing.assert_allclose(fractions.sum("status"), 1.0)
    speeds = list(np.round(study.rotary_speed.values * 30 / np.pi))
    cell = fractions.isel(axial_tension=0, rotary_speed=speeds.index(220))
    assert cell.sel(status="no_span") == 0.5  # e = 0.8 at both mud densities: 2 of the 4 points
    assert fractions.isel(axial_tension=1).sel(status="ok").min() == 1.0


def test_each_cell_is_a_stacked_bar_of_its_fractions(study):
    (chart,) = validity_map(study)
    ax = chart.figure.axes[0]
    (bars,) = [c for c in ax.collections if isinstance(c, PolyCollection)]
    heights = {}
    for path in bars.get_paths():
        v = path.vertices
        heights.setdefault(round(v[:, 0].min(), 6), []).append(np.ptp(v[:, 1]))
    yedges_span = ax.get_ylim()[1] - ax.get_ylim()[0]
    for x, column in heights.items():  # every column of cells fills the whole load range
        assert abs(sum(column) - yedges_span) < 1e-6 * yedges_span
    labels = figure_labels(chart.figure)
    # 10 of the 208 points have no span (5,000 lbf, 220-300 rpm, e = 0.8, both muds)
    assert "ok (95 % of the points)" in labels["legend"] and "no_span (5 % of the points)" in labels["legend"]
    assert "each cell holds the 4 points over restitution and mud density" in labels["titles"][-1]
    assert labels["xlabels"] == ["rotary speed [rpm]"] and labels["ylabels"] == ["axial tension [lbf]"]
