"""Which input drives the design (study.charts.drivers): main effects from a full-factorial grid."""

import html

import numpy as np
import pytest

from study.charts import figure_labels
from study.charts.drivers import INTERACTIONS, drivers_chart, drivers_table_html, main_effects

PSI = 6894.757293168361


def _additive(study, interaction=0.0):
    """max normal stress = a(rpm) + b(load) [+ interaction x a·b], in psi, over the synthetic study's grid."""
    ds = study.copy(deep=True)
    a = (ds.rotary_speed - ds.rotary_speed.mean()) / ds.rotary_speed.std()  # standardised: variance 1
    b = 2.0 * (ds.axial_tension - ds.axial_tension.mean()) / ds.axial_tension.std()  # variance 4
    stress = (10_000 + 1_000 * (a + b + interaction * a * b)).broadcast_like(ds.status).transpose(*ds.status.dims)
    ds["max_normal_stress"] = stress * PSI
    ds["max_normal_stress"].attrs["units"] = "Pa"
    ds["status"].values[...] = 0
    return ds


def test_an_additive_figure_splits_into_its_main_effects_with_no_interaction(study):
    rows = {r["figure"]: r for r in main_effects(_additive(study))}
    row = rows["max_normal_stress"]
    # Var(a + b) = 1 + 4 on the orthogonal grid: the shares are 1/5 and 4/5, nothing else moves it
    assert row["shares"]["rotary_speed"] == pytest.approx(0.2, abs=1e-9)
    assert row["shares"]["axial_tension"] == pytest.approx(0.8, abs=1e-9)
    assert row["shares"]["restitution"] == pytest.approx(0.0, abs=1e-9)
    assert row[INTERACTIONS] == pytest.approx(0.0, abs=1e-9)
    # the range of the means across the load's levels: 1 000 psi x 2 x (max - min of the standardised load)
    loads = study.axial_tension.values
    expected = 2000 * (loads.max() - loads.min()) / loads.std()
    assert row["ranges"]["axial_tension"] == pytest.approx(expected, rel=1e-9)
    assert row["points"] == row["of"] == study.status.size


def test_a_product_term_shows_as_an_interaction_and_the_chart_holds_the_shares(study):
    rows = {r["figure"]: r for r in main_effects(_additive(study, interaction=1.0))}
    row = rows["max_normal_stress"]
    # Var(a + b + ab) = 1 + 4 + Var(a)Var(b) = 9 for independent centred a, b on the grid: ab's share 4/9
    assert row[INTERACTIONS] == pytest.approx(4 / 9, abs=1e-9)
    assert row["top pair"] == ("rotary_speed", "axial_tension") and row["top pair share"] == pytest.approx(4 / 9)
    (chart,) = drivers_chart(_additive(study, interaction=1.0))
    texts = [t.get_text() for t in chart.figure.axes[0].texts]
    assert "44%" in texts  # the interactions' cell of the stress row
    assert "maximum normal stress [psi]" in [t.get_text() for t in chart.figure.axes[0].get_yticklabels()]
    assert "main effects" in figure_labels(chart.figure)["titles"][-1]


def test_the_report_s_table_names_the_inputs_as_the_charts_do():
    # the hole's curvature is a dogleg severity to a driller (API RP 7G), in the table's head and its interactions
    row = {"label": "fatigue life (log₁₀ h)", "shares": {"dogleg_curvature": 0.38, "rotary_speed": 0.37},
           "ranges": {"dogleg_curvature": 3.06, "rotary_speed": 3.72}, "unit": "decades", INTERACTIONS: 0.25,
           "top pair": ("dogleg_curvature", "rotary_speed"), "top pair share": 0.17, "points": 704, "of": 704}
    table = drivers_table_html([row], html.escape)
    assert "<th>dogleg severity</th><th>rotary speed</th>" in table
    assert "dogleg severity × rotary speed: 17%" in table and "curvature" not in table
