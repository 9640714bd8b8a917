"""Rotary speeds to avoid (study.charts.critical): critical speeds of the joint, bands, the Campbell chart."""

import math

import numpy as np
import pytest

from study.charts import figure_labels
from study.charts.critical import (api_comparison, avoid_bands, campbell_chart, critical_speeds,
                                   every_critical_speed, in_band, rp7g_speeds)
from study.charts.plane import plane

#: API RP 7G's rule of thumb for 4 1/2-in x 3.826-in pipe, 30-ft joint: 4 760 000 sqrt(D^2 + d^2)/L^2, L in inches
API_RPM = 4_760_000 * math.sqrt(4.5**2 + 3.826**2) / (30 * 12) ** 2


def test_the_api_line_sits_where_the_formula_puts_it(study):
    assert rp7g_speeds(study) == pytest.approx([API_RPM])
    assert API_RPM == pytest.approx(216.9, abs=0.05)
    (chart,) = campbell_chart(study)
    (ax,) = [a for a in chart.figure.axes if a.get_visible()]
    (api,) = [line for line in ax.get_lines() if line.get_gid() == "API RP 7G"]
    assert api.get_xdata()[0] == pytest.approx(API_RPM)
    labels = figure_labels(chart.figure)
    assert labels["xlabels"] == ["rotary speed [rpm]"] and labels["ylabels"] == ["natural frequency of the joint [Hz]"]
    assert any("API RP 7G rule of thumb: 217 rpm" in t for t in labels["legend"])


def test_a_bare_joint_without_tension_meets_the_rule_of_thumb(build_study):
    # API RP 7G's constant is the first mode of a bare steel tube without axial load (E 30e6 psi, 490 lb/ft^3):
    # 4.762e6 by the closed form, printed rounded to 4.76e6 -> agreement to 0.05 %
    ds = build_study({"rotary_speed": [100.0, 200.0], "axial_tension": [0.0, 10000.0]}, mud_mass=False)
    first = critical_speeds(ds).sel(mode=1).isel(axial_tension=0).values
    np.testing.assert_allclose(first, API_RPM, rtol=6e-4)
    tensioned = critical_speeds(ds).sel(mode=1).isel(axial_tension=1).values
    assert (tensioned > first * 1.1).all()  # tension stiffens the joint


def test_crossings_are_at_60_f_over_k(study):
    (chart,) = campbell_chart(study)
    (ax,) = [a for a in chart.figure.axes if a.get_visible()]
    one = [ln for ln in ax.get_lines() if ln.get_gid() == "crossing 1x mode 1"]
    two = [ln for ln in ax.get_lines() if ln.get_gid() == "crossing 2x mode 1"]
    assert len(one) == len(two) == study.sizes["axial_tension"]
    for a, b in zip(one, two):
        f = a.get_ydata()[0]
        assert a.get_xdata()[0] == pytest.approx(60 * f) and b.get_xdata()[0] == pytest.approx(30 * f)
        assert b.get_ydata()[0] == f


def test_bands_are_15_percent_either_side_of_every_critical_speed_of_a_row(study):
    p = plane(study)
    bands = avoid_bands(p)
    speeds = every_critical_speed(study).isel(axial_tension=0).values.ravel()  # 1x and 2x
    speeds = speeds[np.isfinite(speeds)]
    row = bands[0]
    for c in speeds:  # every critical speed of the 5,000-lbf row lies in a band with its margins
        assert any(lo <= 0.85 * c + 1e-9 and 1.15 * c <= hi + 1e-9 for lo, hi in row)
    lows = [lo for lo, _ in row]
    assert min(lows) == pytest.approx(0.85 * speeds.min())
    assert bands[-1][0][0] > bands[0][0][0]  # tension raises the first band
    inside = in_band(study)
    rpm = study.rotary_speed * 60 / (2 * np.pi)
    mode1 = critical_speeds(study).sel(mode=1)
    expected = (abs(rpm - mode1) <= 0.15 * mode1)
    assert bool((inside | ~expected).all())  # near mode 1 is always in a band


def test_no_stiffness_no_critical_speeds(study):
    ds = study.drop_vars("bending_stiffness")
    assert critical_speeds(ds) is None and campbell_chart(ds) == [] and avoid_bands(plane(ds)) is None


def test_one_critical_speed_answer_the_campbell_crossings_are_the_bands_and_the_envelope_s(study):
    """Issue 34: the Campbell chart marked 2x crossings the envelope did not check. Every marked crossing (1x and 2x,
    every mode and load) lies inside its load row's band, and a point at a 2x crossing is in_band (the envelope's
    critical-speed check)."""
    (chart,) = campbell_chart(study)
    (ax,) = [a for a in chart.figure.axes if a.get_visible()]
    p = plane(study)
    bands = avoid_bands(p)
    colours = {}
    marks = [ln for ln in ax.get_lines() if (ln.get_gid() or "").startswith("crossing")]
    assert {ln.get_gid().split()[1] for ln in marks} == {"1x", "2x"}
    for ln in marks:  # the marker's edge colour is its load row's
        colours.setdefault(ln.get_markeredgecolor(), []).append(float(ln.get_xdata()[0]))
    assert len(colours) == study.sizes["axial_tension"]
    for row, speeds in zip(bands, colours.values()):
        for speed in speeds:
            assert any(lo <= speed <= hi for lo, hi in row), (speed, row)
    two = every_critical_speed(study).sel(order=2, mode=1)  # 30 f1 at each point [rpm]
    assert np.allclose(two, critical_speeds(study).sel(mode=1) / 2)
    near = study.isel(rotary_speed=[0])
    near = near.assign_coords(rotary_speed=("rotary_speed", [float(two.isel(axial_tension=0).mean()) * np.pi / 30]))
    assert bool(in_band(near).isel(axial_tension=0).all())
    assert "same ones the shaded bands on every map and the envelope keep 15 % away from" in chart.caption
    sentence = api_comparison(study)
    assert sentence in chart.caption and "API RP 7G" in sentence and "tension stiffens" in sentence
