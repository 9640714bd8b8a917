"""Design charts of a results dataset: stresses, span, contact, natural frequencies, the crosscheck of the
periodic solution against the real contact, validity.

``draw_all(dataset_path)`` draws every chart the dataset's variables and dimensions allow and
returns the written paths; each chart function returns :class:`Chart` objects (name and
``matplotlib.figure.Figure``) for use in notebooks and tests.
"""

from study.charts.design import (
    CHARTS,
    Chart,
    contact_force_and_duration_vs_rpm,
    crosscheck_maps,
    draw,
    draw_all,
    natural_frequencies_vs_rpm,
    orbit_maps,
    reference_maps,
    save_figure,
    span_length_vs_rpm,
    stress_maps,
    validity_map,
)
from study.charts.labels import figure_labels, quantity

__all__ = [
    "CHARTS",
    "Chart",
    "contact_force_and_duration_vs_rpm",
    "crosscheck_maps",
    "draw",
    "draw_all",
    "figure_labels",
    "natural_frequencies_vs_rpm",
    "orbit_maps",
    "quantity",
    "reference_maps",
    "save_figure",
    "span_length_vs_rpm",
    "stress_maps",
    "validity_map",
]
