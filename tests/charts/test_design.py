"""Design charts (study.charts): which charts are drawn, units on every label, degenerate studies.

Every dataset here is synthetic, built with the conventions of study.workflow.dataset (SI
coordinates with ``units``/``display_units``, outputs with ``units``, the status flag with
``flag_values``/``flag_meanings``); the numbers are made up and only have to vary.
"""

import math
import re

import numpy as np
import pytest
import xarray as xr
from matplotlib.collections import QuadMesh

from study.charts import (
    CHARTS,
    contact_force_and_duration_vs_rpm,
    crosscheck_maps,
    draw,
    draw_all,
    figure_labels,
    natural_frequencies_vs_rpm,
    orbit_maps,
    save_figure,
    span_length_vs_rpm,
    stress_maps,
    validity_map,
)
from study.charts.design import CRITICAL_SPEED_LABEL
from study.solvers.model.result import STATUS

RPM = 2 * math.pi / 60  # rad/s
LBF = 4.4482216152605  # N
PPG = 119.82642731689663  # kg/m^3
FT = 0.3048
PSI = 6894.757293168361

COORDS = {  # name -> (attrs, SI per display unit)
    "rotary_speed": ({"long_name": "rotary speed of the drill string", "units": "rad s-1", "display_units": "rpm"},
                     RPM),
    "axial_tension": ({"long_name": "axial tension at the sample section", "units": "N", "display_units": "lbf"},
                      LBF),
    "restitution": ({"long_name": "coefficient of restitution", "units": "1"}, 1.0),
    "mud_density": ({"long_name": "drilling mud density", "units": "kg m-3", "display_units": "ppg"}, PPG),
    "mud_flow_velocity": ({"long_name": "mud flow velocity inside the pipe", "units": "m s-1",
                           "display_units": "ft/s"}, FT),
    "added_mass_model": ({"long_name": "added-mass model of the annular mud"}, None),
    # as the sweep writes it: the hole's curvature [1/m]; a dogleg severity of 1 deg/100 ft is (pi/180)/(100 ft)
    "dogleg_curvature": ({"long_name": "dogleg severity of the hole as its curvature", "units": "m-1"},
                         math.radians(1.0) / (100 * FT)),
}
OUTPUT_UNITS = {
    "max_normal_stress": "Pa", "alternating_bending_stress": "Pa", "span_length": "m",
    "first_natural_frequency": "Hz", "peak_contact_force": "N", "contact_duration": "s",
    "impact_velocity": "m s-1",
}
ALL_OUTPUTS = tuple(OUTPUT_UNITS)
#: Outputs of method crosscheck (ratios, dimensionless); the orbit's only at e = 1.
CROSSCHECK_OUTPUTS = ("peak_force_ratio", "normal_stress_ratio", "deflection_ratio", "orbit_distance",
                      "orbit_peak_force_ratio", "orbit_normal_stress_ratio", "max_floquet_multiplier")
OUTPUT_UNITS.update({name: "1" for name in CROSSCHECK_OUTPUTS})
FULL_AXES = {
    "rotary_speed": [60, 100, 140, 180, 220, 260, 300],
    "axial_tension": [-5000, 5000, 10000, 20000, 40000],
    "restitution": [0.2, 0.5, 0.8],
    "mud_density": [9, 10, 12],
}


def make_dataset(axes, outputs=ALL_OUTPUTS, fixed=None, status=None):
    """A results dataset over ``axes`` (name -> values in display units, or strings).

    Outputs are made-up smooth functions of the inputs (SI). ``status`` maps a flag name to a
    boolean function of the display-unit inputs (a dict of arrays) marking where it is set.
    """
    fixed = {"rotary_speed": 120, "axial_tension": 10000, "restitution": 0.5, "mud_density": 10,
             "mud_flow_velocity": 7.4, "added_mass_model": "potential_flow", **(fixed or {})}
    coords = {}
    for name, values in axes.items():
        attrs, scale = COORDS[name]
        data = np.array(values, dtype=str) if scale is None else np.asarray(values, float) * scale
        coords[name] = xr.Variable(name, data, attrs)
    for name, value in fixed.items():
        if name not in axes:
            attrs, scale = COORDS[name]
            coords[name] = xr.Variable((), value if scale is None else value * scale, attrs)
    ds = xr.Dataset(coords=coords)
    dims = list(axes)

    def c(name):  # the input in display units, broadcast over its own dimension
        attrs, scale = COORDS[name]
        return ds[name] if scale is None else ds[name] / scale

    n, t, e, rho = c("rotary_speed"), c("axial_tension"), c("restitution"), c("mud_density")
    model = xr.where(c("added_mass_model") == "gap_flow", 1.3, 1.0)
    made = {
        "max_normal_stress": PSI * (8000 + 60 * n + 0.4 * t) * (1 + e) * rho / 10 * model,
        "alternating_bending_stress": PSI * (3000 + 40 * n + 0.1 * t) * (1 + 0.5 * e) * model,
        "span_length": FT * (300 + 0.002 * t - 0.2 * n) * model,
        "first_natural_frequency": (0.12 + 4e-6 * t) * (10 / rho) ** 0.5 + 0 * n,
        "peak_contact_force": LBF * 1e3 * n * (1 + e) * rho / 10,
        "contact_duration": 1e-3 * (1.3 - 0.001 * n) + 0 * e,
        "impact_velocity": 0.02 * n * RPM * (1 + 0 * t),
        "peak_force_ratio": 0.8 + 0.002 * n * e + 0 * t,
        "normal_stress_ratio": 0.97 + 1e-4 * n + 0 * e * t,
        "deflection_ratio": 1.001 + 0 * n * e * t,
        "orbit_distance": xr.where(e == 1, 0.01 + 1e-4 * n + 0 * t, np.nan),
        "orbit_peak_force_ratio": xr.where(e == 1, 0.7 + 0.003 * n + 0 * t, np.nan),
        "orbit_normal_stress_ratio": xr.where(e == 1, 0.98 + 0 * n * t, np.nan),
        "max_floquet_multiplier": xr.where(e == 1, 0.5 + 0.01 * n + 0 * t, np.nan),
    }
    template = xr.DataArray(np.zeros(tuple(len(v) for v in axes.values())), {d: ds[d] for d in dims}, dims)
    for name in outputs:
        values = (made[name] + template).transpose(*dims)
        ds[name] = xr.Variable(dims, np.asarray(values.values, dtype=float),
                               {"units": OUTPUT_UNITS[name], "long_name": name.replace("_", " ")})
    codes = np.zeros(tuple(len(v) for v in axes.values()), dtype=np.int8)
    grids = dict(zip(dims, np.meshgrid(*[np.asarray(v) for v in axes.values()], indexing="ij"))) if dims else {}
    for flag, where in (status or {}).items():
        codes = np.where(where(grids), STATUS[flag][0], codes).astype(np.int8)
    ds["status"] = xr.Variable(dims, codes, {
        "long_name": "status of the design point",
        "flag_values": np.array([code for code, _ in STATUS.values()], dtype=np.int8),
        "flag_meanings": " ".join(STATUS),
    })
    ds["message"] = xr.Variable(dims, np.full(codes.shape, "", dtype=str))
    ds.attrs.update(title="synthetic study", study_name="synthetic")
    return ds


@pytest.fixture(scope="module")
def full():
    return make_dataset(FULL_AXES, status={
        "buckled": lambda g: g["axial_tension"] < 0,
        "resonance": lambda g: (g["rotary_speed"] == 140) & (g["restitution"] == 0.8),
    })


@pytest.fixture(scope="module")
def full_charts(full):
    return draw(full)


def names_of(charts):
    return [chart.name for chart in charts]


def all_texts(figure):
    labels = figure_labels(figure)
    return labels["xlabels"] + labels["ylabels"] + labels["titles"] + labels["legend"]


def meshes(figure):
    """The colour meshes of the panels (colour bars draw one too)."""
    return [c for ax in data_axes(figure) for c in ax.collections if isinstance(c, QuadMesh)]


def data_axes(figure):
    """Visible axes that are not colour bars."""
    return [ax for ax in figure.axes if ax.get_visible() and ax.get_label() != "<colorbar>"]


# --- what is drawn ----------------------------------------------------------------------------


def test_draw_all_writes_every_chart_beside_the_dataset(tmp_path, full):
    path = tmp_path / "results.nc"
    full.to_netcdf(path)
    written = draw_all(path)
    assert all(p.parent == tmp_path / "charts" and p.suffix == ".png" for p in written)
    assert sorted(p.stem for p in written) == sorted([
        "stress_limits", "contact_force", "regime_map",  # decisions: one figure, worst case over the others
        "drivers",  # the main effects of the swept inputs on the design figures
        "span_length",  # the span does not depend on restitution or mud density: one figure
        "contact_force_duration__mud_density_9_ppg", "contact_force_duration__mud_density_10_ppg",
        "contact_force_duration__mud_density_12_ppg",
        "natural_frequencies",
        "validity_map",
    ])
    for p in written:
        assert p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and p.stat().st_size > 5000
    assert not [p for p in (tmp_path / "charts").iterdir() if p.name.startswith(".tmp")]


def test_out_dir_and_format(tmp_path, full):
    path = tmp_path / "results.nc"
    full.isel(mud_density=[0]).to_netcdf(path)
    written = draw_all(str(path), out_dir=tmp_path / "elsewhere", fmt="svg")
    assert written and all(p.parent == tmp_path / "elsewhere" and p.suffix == ".svg" for p in written)
    assert written[0].read_text().lstrip().startswith("<?xml")
    assert not (tmp_path / "charts").exists()


def test_an_open_dataset_needs_an_out_dir(tmp_path, full):
    with pytest.raises(ValueError, match="out_dir"):
        draw_all(full)
    assert draw_all(full.isel(mud_density=[0]), out_dir=tmp_path)


@pytest.mark.parametrize("outputs, expected", [
    (ALL_OUTPUTS, {"stress_limits", "contact_force", "span_length", "contact_force_duration", "natural_frequencies",
                   "regime_map", "validity_map", "drivers"}),
    (("span_length", "first_natural_frequency", "peak_contact_force", "contact_duration", "impact_velocity"),
     {"contact_force", "span_length", "contact_force_duration", "natural_frequencies", "regime_map",
      "validity_map", "drivers"}),
    (("alternating_bending_stress",), {"stress_limits", "regime_map", "validity_map", "drivers"}),
    (("contact_duration",), {"contact_force_duration", "regime_map", "validity_map"}),
    (CROSSCHECK_OUTPUTS[:3], {"crosscheck", "regime_map", "validity_map"}),  # no orbit at e = 0.5 alone
    ((), {"regime_map", "validity_map"}),
])
def test_charts_drawn_follow_the_variables_present(outputs, expected):
    ds = make_dataset({"rotary_speed": [60, 120, 180], "axial_tension": [5000, 10000]}, outputs=outputs)
    assert set(names_of(draw(ds))) == expected


def test_no_status_no_validity_map():
    ds = make_dataset({"rotary_speed": [60, 120]}, outputs=("span_length",)).drop_vars("status")
    assert names_of(draw(ds)) == ["span_length"]


def test_charts_against_rpm_need_the_rpm_dimension():
    ds = make_dataset({"axial_tension": [5000, 10000, 20000], "restitution": [0.2, 0.8]})
    drawn = names_of(draw(ds))
    assert drawn == ["stress_maps", "drivers", "validity_map"]
    figure = stress_maps(ds)[0].figure
    assert "axial tension [lbf]" in figure_labels(figure)["xlabels"]


def test_a_dataset_without_dimensions_draws_nothing(tmp_path):
    ds = make_dataset({})
    assert ds["status"].dims == () and "max_normal_stress" in ds
    for function in CHARTS:
        assert function(ds) == []
    path = tmp_path / "results.nc"
    ds.to_netcdf(path)
    assert draw_all(path) == []
    assert not (tmp_path / "charts").exists()


# --- layout -----------------------------------------------------------------------------------


def test_stress_maps_one_panel_per_restitution_one_figure_per_mud_density(full):
    charts = stress_maps(full)
    assert len(charts) == 3
    figure = charts[1].figure
    assert len(data_axes(figure)) == 2 * 3  # two stresses x three restitutions
    assert len(meshes(figure)) == 6
    texts = all_texts(figure)
    assert any("mud density = 10 ppg" in t for t in texts)
    assert sum("restitution = 0.5" in t for t in figure_labels(figure)["titles"]) == 2
    labels = figure_labels(figure)
    assert set(labels["xlabels"]) == {"rotary speed [rpm]"}
    assert {"axial tension [lbf]", "maximum normal stress [psi]", "alternating bending stress [psi]"} \
        <= set(labels["ylabels"])


def test_stress_maps_show_the_values_in_psi_over_rpm_and_lbf(full):
    figure = stress_maps(full)[0].figure
    mesh = meshes(figure)[0]  # maximum normal stress, restitution 0.2, mud 9 ppg
    values = mesh.get_array().reshape(5, 7)  # rows: axial tension
    expected = (8000 + 60 * 60 + 0.4 * -5000) * 1.2 * 0.9
    assert values[0, 0] == pytest.approx(expected)
    coords = mesh.get_coordinates()  # cell corners in display units
    assert coords[0, 0, 0] == pytest.approx(60 - 20) and coords[0, -1, 0] == pytest.approx(300 + 20)
    assert coords[0, 0, 1] == pytest.approx(-5000 - 5000)


def test_a_further_dimension_is_reduced_by_its_maximum_and_the_title_says_so():
    axes = {**FULL_AXES, "mud_flow_velocity": [0.0, 5.0, 10.0]}
    ds = make_dataset(axes)
    attrs = ds["max_normal_stress"].attrs
    ds["max_normal_stress"] = ds["max_normal_stress"] * (1 + ds["mud_flow_velocity"])  # varies with it
    ds["max_normal_stress"].attrs = dict(attrs)
    charts = stress_maps(ds)
    assert len(charts) == 3
    title = figure_labels(charts[0].figure)["titles"][-1]
    assert "maximum over mud flow velocity" in title
    top = meshes(charts[0].figure)[0].get_array().reshape(5, 7)
    expected = ds["max_normal_stress"].isel(mud_density=0, restitution=0).max("mud_flow_velocity") / PSI
    np.testing.assert_allclose(top, expected.transpose("axial_tension", "rotary_speed").values)


def test_lines_per_axial_load_in_display_units(full):
    chart = span_length_vs_rpm(full)[0]
    ax = data_axes(chart.figure)[0]
    lines = [line for line in ax.get_lines() if len(line.get_xdata()) == 7]
    assert len(lines) == 5  # one per axial load
    np.testing.assert_allclose(lines[0].get_xdata(), FULL_AXES["rotary_speed"])
    expected_ft = 300 + 0.002 * -5000 - 0.2 * np.array(FULL_AXES["rotary_speed"])
    np.testing.assert_allclose(lines[0].get_ydata(), expected_ft)
    legend = figure_labels(chart.figure)["legend"]
    assert legend[0] == "axial tension" and "-5,000 lbf" in legend and "40,000 lbf" in legend


def test_a_dimension_the_values_do_not_depend_on_is_shown_once(full):
    # span length does not depend on restitution: no panels per restitution, and the title says so
    chart = span_length_vs_rpm(full)[0]
    assert len(data_axes(chart.figure)) == 1
    assert "same for every restitution" in figure_labels(chart.figure)["titles"][-1]
    # contact duration depends on rpm only; the force on all: panels per restitution, lines per load
    figure = contact_force_and_duration_vs_rpm(full)[0].figure
    assert len(data_axes(figure)) == 6
    assert {"peak contact force [lbf]", "contact duration [ms]"} <= set(figure_labels(figure)["ylabels"])


def test_natural_frequencies_with_harmonics_and_the_classical_critical_speed(full):
    charts = natural_frequencies_vs_rpm(full)
    assert names_of(charts) == ["natural_frequencies"]  # independent of restitution: one figure
    figure = charts[0].figure
    axes = data_axes(figure)
    assert len(axes) == 3  # one panel per mud density
    labels = figure_labels(figure)
    assert set(labels["xlabels"]) == {"rotary speed [rpm]"}
    assert "first natural frequency [Hz]" in labels["ylabels"]
    assert CRITICAL_SPEED_LABEL in labels["legend"]
    ax = axes[0]
    slopes = set()
    for line in ax.get_lines():
        x, y = np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float)
        if len(x) > 100:
            slopes.add(round(float(y[-1] / x[-1] * 60), 6))
    assert slopes == {1.0, 2.0, 3.0}  # f = k N / 60
    f1 = (0.12 + 4e-6 * np.array(FULL_AXES["axial_tension"])) * (10 / 9) ** 0.5
    verticals = sorted(float(line.get_xdata()[0]) for line in ax.get_lines()
                       if len(line.get_xdata()) == 2 and line.get_xdata()[0] == line.get_xdata()[1])
    np.testing.assert_allclose(verticals, np.sort(60 * f1))
    low, high = ax.get_xlim()
    assert low < 60 * f1.min() and high > 300  # both the critical speeds and the sweep are in view
    assert "the section's first mode meets 1× at N = 60 f1" in labels["titles"][-1]


def test_legends_sit_outside_the_data_and_the_title(full_charts):
    for chart in full_charts:
        figure = chart.figure
        figure.draw_without_rendering()
        title = figure._suptitle.get_window_extent()
        for legend in figure.legends:
            box = legend.get_window_extent()
            assert not box.overlaps(title), chart.name
            for ax in data_axes(figure):
                assert not box.overlaps(ax.get_window_extent()), chart.name
                assert not ax.get_legend()


def test_every_label_says_its_unit(full_charts):
    for chart in full_charts:
        labels = figure_labels(chart.figure)
        for label in labels["xlabels"] + labels["ylabels"]:
            assert re.search(r"\[[^\]]+\]$", label), (chart.name, label)


# --- degenerate studies -----------------------------------------------------------------------


def test_failed_points_are_masked_not_zero(full):
    ds = full.copy(deep=True)
    for name in ("max_normal_stress", "span_length", "peak_contact_force"):
        ds[name][dict(rotary_speed=2, axial_tension=1)] = np.nan
    figure = stress_maps(ds)[0].figure
    array = meshes(figure)[0].get_array().reshape(5, 7)
    assert np.ma.is_masked(array) and array.mask[1, 2] and array.mask.sum() == 1
    assert "hatched: no result" in figure_labels(figure)["titles"][-1]
    line = [ln for ln in data_axes(span_length_vs_rpm(ds)[0].figure)[0].get_lines()
            if len(ln.get_xdata()) == 7][1]
    y = np.asarray(line.get_ydata(), float)
    assert np.isnan(y[2]) and np.isfinite(np.delete(y, 2)).all()


def test_many_panels_wrap_into_rows():
    ds = make_dataset({"rotary_speed": [60, 120, 180], "axial_tension": [5000, 10000],
                       "restitution": [0.1, 0.2, 0.3, 0.5, 0.7, 0.9]})
    figure = stress_maps(ds)[0].figure
    assert len(data_axes(figure)) == 12  # two stresses x six restitutions, as 2 x (2 rows of 3)
    assert max(ax.get_subplotspec().colspan.stop for ax in data_axes(figure)) == 3


def test_a_panel_without_any_result_is_left_empty(full):
    ds = full.copy(deep=True)
    ds["max_normal_stress"][dict(restitution=0)] = np.nan
    figure = stress_maps(ds)[0].figure
    assert meshes(figure)[0].get_array().mask.all()
    assert "hatched: no result" in figure_labels(figure)["titles"][-1]


def test_a_load_without_any_result_is_named_in_the_legend(full):
    ds = full.copy(deep=True)
    ds["span_length"][dict(axial_tension=0)] = np.nan
    legend = figure_labels(span_length_vs_rpm(ds)[0].figure)["legend"]
    assert "-5,000 lbf (no result)" in legend and "5,000 lbf" in legend


def test_failed_points_do_not_hide_that_the_results_agree(full):
    ds = full.copy(deep=True)
    ds["contact_duration"][dict(axial_tension=0)] = np.nan  # depends on the speed only
    ds["contact_duration"][dict(rotary_speed=3, restitution=1)] = np.nan
    figure = contact_force_and_duration_vs_rpm(ds.drop_vars("peak_contact_force"))[0].figure
    assert len(data_axes(figure)) == 1
    assert "same for every axial tension, restitution and mud density" in figure_labels(figure)["titles"][-1]
    (line,) = [ln for ln in data_axes(figure)[0].get_lines() if len(ln.get_xdata()) == 7]
    np.testing.assert_allclose(line.get_ydata(), 1.3 - 0.001 * np.array(FULL_AXES["rotary_speed"]))


def test_one_swept_input_gives_lines_instead_of_maps(tmp_path):
    ds = make_dataset({"rotary_speed": [60, 120, 180, 240]})
    charts = draw(ds)
    assert names_of(charts) == ["stress_maps", "validity_map", "span_length", "contact_force_duration",
                                "natural_frequencies"]
    stress = charts[0].figure
    assert not meshes(stress) and len(data_axes(stress)) == 2
    assert {"maximum normal stress [psi]", "alternating bending stress [psi]"} \
        <= set(figure_labels(stress)["ylabels"])
    strip = charts[1].figure
    assert len(strip.axes[0].collections[0].get_paths()) == 4  # one all-ok bar per speed
    assert figure_labels(strip)["ylabels"] == []
    path = tmp_path / "results.nc"
    ds.to_netcdf(path)
    assert len(draw_all(path)) == 5


def test_dimensions_of_length_one_are_fixed_inputs_named_in_the_title():
    ds = make_dataset({"rotary_speed": [60, 120, 180], "axial_tension": [10000], "restitution": [0.5],
                       "mud_density": [9, 12]})
    charts = draw(ds)
    stress = charts[0].figure
    assert not meshes(stress)  # one load: lines against rpm
    assert "restitution = 0.5" in figure_labels(stress)["titles"][-1]
    for chart in charts:
        assert chart.figure.axes


def test_a_single_rotary_speed_still_draws_points():
    ds = make_dataset({"rotary_speed": [120], "axial_tension": [5000, 10000, 20000]})
    for chart in draw(ds):
        assert chart.figure.axes
    span = span_length_vs_rpm(ds)[0].figure
    markers = [ln for ln in data_axes(span)[0].get_lines() if ln.get_marker() == "o" and len(ln.get_xdata()) == 1]
    assert len(markers) == 3
    stress = stress_maps(ds)[0].figure  # one speed: lines over the load
    assert figure_labels(stress)["xlabels"] == ["axial tension [lbf]"]


def test_string_dimensions_become_panels_and_file_names(tmp_path):
    ds = make_dataset({"rotary_speed": [60, 120, 180], "axial_tension": [5000, 10000],
                       "added_mass_model": ["potential_flow", "gap_flow"]})
    stress = stress_maps(ds)[0].figure
    titles = figure_labels(stress)["titles"]
    assert any("added-mass model = gap_flow" in t for t in titles)
    assert "worst case (highest stress) over added-mass model" in figure_labels(draw(ds)[0].figure)["titles"][-1]
    ds2 = make_dataset({"rotary_speed": [60, 120, 180], "axial_tension": [5000, 10000], "restitution": [0.2, 0.8],
                        "added_mass_model": ["potential_flow", "gap_flow"]})
    assert "stress_maps__added-mass_model_gap_flow" in names_of(stress_maps(ds2))
    path = tmp_path / "results.nc"
    ds2.to_netcdf(path)
    assert all(p.stat().st_size > 0 for p in draw_all(path))


def test_a_dogleg_is_labelled_as_drillers_state_it():
    # API RP 7G states a dogleg severity in degrees per 100 ft: the hole's curvature [1/m] is shown so, in titles,
    # legends and file names, not as 0.000524 1/ft
    ds = make_dataset({"rotary_speed": [60, 120, 180], "axial_tension": [5000, 10000], "restitution": [0.2, 0.8],
                       "dogleg_curvature": [0.0, 3.0]})
    attrs = ds["peak_contact_force"].attrs
    ds["peak_contact_force"] = ds["peak_contact_force"] * (1 + 100 * ds["dogleg_curvature"])  # varies with it
    ds["peak_contact_force"].attrs = dict(attrs)
    charts = contact_force_and_duration_vs_rpm(ds)
    assert "contact_force_duration__dogleg_severity_3_100_ft" in names_of(charts)
    titles = [" ".join(figure_labels(chart.figure)["titles"]) for chart in charts]
    assert any("dogleg severity = 3 °/100 ft" in title for title in titles), titles
    assert not any("1/ft" in title for title in titles), titles


def test_a_string_dimension_alone_is_drawn_with_named_ticks():
    ds = make_dataset({"added_mass_model": ["potential_flow", "gap_flow"]})
    charts = draw(ds)
    assert names_of(charts) == ["stress_maps", "validity_map"]
    charts[0].figure.draw_without_rendering()
    ax = data_axes(charts[0].figure)[-1]
    assert [t.get_text() for t in ax.get_xticklabels()] == ["potential_flow", "gap_flow"]


# --- files ------------------------------------------------------------------------------------


def test_save_is_atomic(tmp_path, full):
    figure = validity_map(full)[0].figure
    target = tmp_path / "sub" / "chart.png"
    save_figure(figure, target)
    assert target.stat().st_size > 0
    before = target.read_bytes()
    with pytest.raises(ValueError):
        save_figure(figure, target, fmt="no-such-format")
    assert target.read_bytes() == before
    assert sorted(p.name for p in target.parent.iterdir()) == ["chart.png"]


def test_figures_are_not_registered_with_pyplot(full_charts):
    for chart in full_charts:
        assert chart.figure.canvas.manager is None
        assert chart.figure.dpi == 150


def test_a_panel_with_no_result_keeps_the_swept_range_and_says_why():
    ds = make_dataset(FULL_AXES)
    ds["peak_contact_force"] = ds.peak_contact_force.where(ds.restitution > 0.3)  # no impact at e = 0.2
    chart = contact_force_and_duration_vs_rpm(ds)[0]
    empty = [ax for ax in chart.figure.axes if any("no result at these inputs" in t.get_text() for t in ax.texts)]
    assert len(empty) == 1 and "0.2" in empty[0].get_title()
    assert empty[0].get_xlim() == pytest.approx((60.0, 300.0))  # rpm, not matplotlib's default range


def test_crosscheck_ratios_diverge_from_one_and_say_what_they_compare():
    # method crosscheck: 1 is agreement, so the colour scale is centred there
    ds = make_dataset({"rotary_speed": [60, 120, 180], "axial_tension": [5000, 10000], "restitution": [0.5, 1.0]},
                      outputs=CROSSCHECK_OUTPUTS)
    chart, = crosscheck_maps(ds)
    labels = figure_labels(chart.figure)
    assert labels["titles"][-1].startswith("Real contact over the periodic solution (1: they agree)")
    assert "peak force, real / periodic [-]" in labels["ylabels"]
    norms = {type(mesh.norm).__name__: mesh.norm for mesh in meshes(chart.figure)}
    assert set(norms) == {"TwoSlopeNorm"} and norms["TwoSlopeNorm"].vcenter == 1.0
    assert len(meshes(chart.figure)) == 3 * 2  # three ratios, a panel per restitution


def test_orbit_maps_keep_only_the_inputs_where_an_orbit_was_found():
    ds = make_dataset({"rotary_speed": [60, 120, 180], "axial_tension": [5000, 10000], "restitution": [0.5, 1.0]},
                      outputs=CROSSCHECK_OUTPUTS)
    chart, = orbit_maps(ds)
    labels = figure_labels(chart.figure)
    assert "restitution = 1" in labels["titles"][-1]  # e = 0.5 has no orbit: not an empty panel
    assert "largest Floquet multiplier [-]" in labels["ylabels"]
    assert len(meshes(chart.figure)) == 3
    multiplier = meshes(chart.figure)[-1]
    assert multiplier.get_array().min() == pytest.approx(0.5 + 0.01 * 60)  # made-up values, shown as made
    no_orbit = make_dataset({"rotary_speed": [60, 120, 180], "axial_tension": [5000, 10000], "restitution": [0.5]},
                            outputs=CROSSCHECK_OUTPUTS)
    assert orbit_maps(no_orbit) == []


def test_reference_check_ratios_are_centred_on_agreement():
    # method reference-check: periodic solution over the reference model, 1 is agreement
    from study.charts import reference_maps
    from study.charts.design import REFERENCE_RATIOS

    ds = make_dataset({"rotary_speed": [60, 120, 180], "axial_tension": [5000, 10000]},
                      outputs=CROSSCHECK_OUTPUTS[:3]).rename(dict(zip(CROSSCHECK_OUTPUTS[:3], REFERENCE_RATIOS)))
    chart, = reference_maps(ds)
    labels = figure_labels(chart.figure)
    assert labels["titles"][-1].startswith("Periodic solution over the reference model (1: they agree)")
    assert "alternating stress, periodic / reference [-]" in labels["ylabels"]
    norms = {type(mesh.norm).__name__: mesh.norm for mesh in meshes(chart.figure)}
    assert set(norms) == {"TwoSlopeNorm"} and norms["TwoSlopeNorm"].vcenter == 1.0
    assert reference_maps(make_dataset({"rotary_speed": [60, 120]}, outputs=())) == []


def test_a_span_line_is_broken_where_it_jumps_to_another_branch(full):
    from study.charts.design import SPAN_BRANCH_JUMP, branch_breaks

    ds = full.copy(deep=True)
    ds["span_length"][dict(rotary_speed=slice(4, None))] *= 1.5  # from 220 rpm on: another solution branch
    chart = span_length_vs_rpm(ds)[0]
    line = [ln for ln in data_axes(chart.figure)[0].get_lines() if len(ln.get_xdata()) == 8][0]
    x, y = np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float)
    assert np.isnan(y[4]) and x[4] == pytest.approx(200) and np.isfinite(np.delete(y, 4)).all()
    assert "more than 20% between neighbouring speeds" in figure_labels(chart.figure)["titles"][-1].replace("\n", " ")
    assert SPAN_BRANCH_JUMP == 0.2
    # a smooth change of 15 % is not a jump; NaN stays NaN without a break added
    x2, y2 = branch_breaks(np.arange(3.0), np.array([1.0, 1.15, np.nan]), 0.2)
    assert x2.size == 3 and np.isnan(y2[2])


def test_iso_lines_only_on_filled_maps():
    from matplotlib.contour import ContourSet

    ds = make_dataset({"rotary_speed": [60, 120, 180], "axial_tension": [5000, 10000, 20000]},
                      outputs=CROSSCHECK_OUTPUTS[:1])

    def contour_sets(data):
        figure = crosscheck_maps(data)[0].figure
        return [c for ax in data_axes(figure) for c in ax.collections if isinstance(c, ContourSet)] + \
            [c for ax in data_axes(figure) for c in getattr(ax, "containers", []) if isinstance(c, ContourSet)]

    filled = contour_sets(ds)
    holed = ds.copy(deep=True)
    holed["peak_force_ratio"][dict(rotary_speed=1, axial_tension=1)] = np.nan
    assert filled and not contour_sets(holed)  # no scribbles drawn around a hole in the data


def test_the_span_chart_is_not_drawn_where_no_point_searched_a_span(full):
    """Issue 34: with auto the span is the section's length, an input: a flat line captioned as an answer."""
    from study.charts.design import span_length_vs_rpm

    assert span_length_vs_rpm(full)  # the synthetic study does not say its method
    for method, drawn in (("fast", True), ("reference", False)):
        other = full.assign(method=(full.status.dims, np.full(full.status.shape, method)))
        assert bool(span_length_vs_rpm(other)) == drawn, method


def test_contact_lines_draw_answers_only_and_mark_the_points_not_converged(full):
    """Issue 34: the contact chart drew unmarked not-converged points, and values of invalid points."""
    from study.charts.design import ROUGH_POINT_LABEL, contact_force_and_duration_vs_rpm
    from study.solvers.model.result import STATUS_CODES

    ds = full.copy(deep=True)
    dims = ds.status.dims
    ds["peak_contact_force"] = ds.peak_contact_force.broadcast_like(ds.status).transpose(*dims).copy()
    index = {d: 0 for d in dims}
    index.update(rotary_speed=2, axial_tension=2)
    rough = tuple(index[d] for d in dims)
    index.update(rotary_speed=4)
    invalid = tuple(index[d] for d in dims)
    ds.status.values[rough] = STATUS_CODES["not_converged"]
    ds.status.values[invalid] = STATUS_CODES["hertz_invalid"]
    ds.peak_contact_force.values[invalid] = 1e9  # an invalid point's value: never drawn
    charts = contact_force_and_duration_vs_rpm(ds)
    lines = [ln for chart in charts for ax in chart.figure.axes for ln in ax.get_lines()]
    assert max(np.nanmax(np.asarray(ln.get_ydata(), float)) for ln in lines if len(ln.get_ydata())) < 1e9 / 4.448
    hollow = [ln for ln in lines if ln.get_gid() == "not converged"]
    assert hollow and all(ln.get_xdata()[0] == 140 for ln in hollow)  # 140 rpm, the point not converged
    assert any(ROUGH_POINT_LABEL in chart.caption for chart in charts)
    assert any(ROUGH_POINT_LABEL in figure_labels(chart.figure)["legend"] for chart in charts)
