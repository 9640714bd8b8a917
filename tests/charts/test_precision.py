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


def test_the_reference_model_chart_tags_each_point_with_modes_and_rtol():
    rows = [{"method": "reference", "modes": n, "rtol": rtol, "harmonics": None, "wall_time": 0.1 * n,
             "error": 0.1 / n, "shear_error": 0.2 / n} for n in (8, 16) for rtol in (1e-4, 1e-6)]
    figure = work_precision_chart(rows, "case", title="Work and precision of the reference model",
                                  time_label="time per design point [ms]")
    tags = {t.get_text() for t in figure.axes[0].texts}
    assert tags == {"N=8, rtol 0.0001", "N=8, rtol 1e-06", "N=16, rtol 0.0001", "N=16, rtol 1e-06"}
    assert figure.axes[0].get_xlabel() == "time per design point [ms]"
    assert figure.get_suptitle().startswith("Work and precision of the reference model")


def test_time_domain_chart_marks_failures_and_labels_units():
    from study.charts.precision import time_domain_chart

    work = [{"name": "event", "wall_time": 0.002, "error": 1e-6},
            {"name": "penalty_rk45", "wall_time": 0.5, "error": 1e-5}]
    stability = [{"name": "explicit", "step_ratio": 0.1, "error": 1e-3},
                 {"name": "explicit", "step_ratio": 2.0, "error": float("nan")},
                 {"name": "event", "step_ratio": 0.02, "error": 3e-7}]
    figure = time_domain_chart(work, stability, "test case")
    work_ax, step_ax = figure.axes
    assert work_ax.get_xlabel() == "time for the run [ms]" and step_ax.get_xlabel().endswith("[-]")
    labels = [t.get_text() for t in step_ax.get_legend().get_texts()]
    assert "explicit: failed (blow-up detected)" in labels and "event (RK4 contact step)" in labels
    assert "penalty_rk45 (linear penalty model)" in [t.get_text() for t in work_ax.get_legend().get_texts()]
