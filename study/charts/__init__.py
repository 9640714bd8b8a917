"""Design charts of a results dataset: the safe operating envelope, stresses against yield and endurance,
fatigue life, contact force, the regime of the motion, the rotary speeds to avoid (Campbell diagram), the
validity of the points, the span, contact and natural frequencies, the method crosschecks, and the report page
that holds them all.

``draw_all(dataset_path)`` draws every chart the dataset's variables and dimensions allow and returns the
written paths; ``write_report(dataset_path)`` draws them, writes the envelope table and ``report.html``; each
chart function returns :class:`Chart` objects (name, ``matplotlib.figure.Figure``, caption) for use in
notebooks and tests.
"""

from study.charts.catalogue import CHARTS, draw, draw_all
from study.charts.critical import campbell_chart
from study.charts.design import (
    Chart,
    contact_force_and_duration_vs_rpm,
    crosscheck_maps,
    natural_frequencies_vs_rpm,
    orbit_maps,
    reference_maps,
    save_figure,
    span_length_vs_rpm,
    stress_maps,
)
from study.charts.envelope import envelope_chart, envelope_table
from study.charts.labels import figure_labels, quantity
from study.charts.limits import contact_force_map, fatigue_life_map, stress_limit_maps
from study.charts.regimes import regime_map
from study.charts.validity import validity_fractions, validity_map

__all__ = [
    "CHARTS",
    "Chart",
    "campbell_chart",
    "contact_force_and_duration_vs_rpm",
    "contact_force_map",
    "crosscheck_maps",
    "draw",
    "draw_all",
    "envelope_chart",
    "envelope_table",
    "fatigue_life_map",
    "figure_labels",
    "natural_frequencies_vs_rpm",
    "orbit_maps",
    "quantity",
    "reference_maps",
    "regime_map",
    "save_figure",
    "span_length_vs_rpm",
    "stress_limit_maps",
    "stress_maps",
    "validity_fractions",
    "validity_map",
]
