"""Which charts a study gets (study.charts.catalogue): the decision charts first, units and a caption on each."""

import re

from study.charts import draw, figure_labels


def test_a_full_study_gets_every_decision_chart_once_with_units_and_a_caption(study):
    charts = draw(study)
    names = [c.name for c in charts]
    assert names[:8] == ["envelope", "stress_limits", "fatigue_life", "contact_force", "drivers", "regime_map",
                         "campbell", "validity_map"]
    assert len(names) == len(set(names))  # one figure per question, not one per mud density
    for chart in charts:
        labels = figure_labels(chart.figure)
        for label in labels["xlabels"] + labels["ylabels"]:
            assert re.search(r"\[[^\]]+\]$", label), (chart.name, label)
        assert chart.caption.endswith("."), chart.name


def test_the_fatigue_target_reaches_the_envelope_and_the_fatigue_map(study):
    charts = {c.name: c for c in draw(study, target_hours=5000.0, criterion="endurance")}
    assert "below the endurance limit" in figure_labels(charts["envelope"].figure)["titles"][-1].replace("\n", " ")
    assert "target 5,000 h" in " ".join(figure_labels(charts["fatigue_life"].figure)["titles"])
