"""The work-precision chart (study.charts.precision): both methods, both stresses, labelled axes."""

from study.charts.precision import work_precision_chart

ROWS = [
    {"method": "fast", "modes": 15, "harmonics": None, "wall_time": 0.01, "error": 0.3, "shear_error": 0.5},
    {"method": "fast", "modes": 61, "harmonics": None, "wall_time": 0.02, "error": 1e-4, "shear_error": 1e-3},
    {"method": "series", "modes": 61, "harmonics": 1600, "wall_time": 0.05, "error": 1e-4, "shear_error": 0.0},
]


def test_chart_has_both_methods_log_axes_and_units():
    figure = work_precision_chart(ROWS, "test case")
    axes = figure.axes
    assert len(axes) == 2
    for ax in axes:
        assert ax.get_xscale() == "log" and ax.get_yscale() == "log"
        assert ax.get_xlabel() == "time per evaluation [ms]" and ax.get_ylabel().endswith("[-]")
        assert sorted(t.get_text() for t in ax.get_legend().get_texts()) == ["fast", "series"]
    # An exact (zero) error is drawn at the floor, not dropped.
    series_line = [line for line in axes[1].get_lines() if line.get_label() == "series"][0]
    assert series_line.get_ydata()[0] == 1e-16
