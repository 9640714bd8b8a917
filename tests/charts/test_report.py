"""The study's page (study.charts.report), opened in headless Chromium: every chart, the envelope, the provenance.

Chromium comes from Debian's packages; the set-up installs it (``apt-get install -y chromium``) only when
/usr/bin/chromium is absent, and the test is skipped, saying so, only if that is not possible.
"""

import base64
import os
import shutil
import subprocess
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import pytest

from study.charts.envelope import envelope_table, safe_ranges
from study.charts.report import write_report

CHROMIUM = Path("/usr/bin/chromium")
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]


@pytest.fixture(scope="module")
def chromium():
    if not CHROMIUM.exists() and shutil.which("apt-get") and os.geteuid() == 0:
        subprocess.run(["apt-get", "install", "-y", "chromium"], capture_output=True, timeout=900, check=False)
    if not CHROMIUM.exists():
        pytest.skip("/usr/bin/chromium is missing and `apt-get install -y chromium` was not possible here")
    return CHROMIUM


class Page(HTMLParser):
    """The images, envelope-table cells and element texts of a DOM."""

    def __init__(self):
        super().__init__()
        self.images, self.cells, self.ids, self.stack, self.text = {}, [], {}, [], {}
        self.verdicts = []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "img":
            self.images[attrs.get("data-chart")] = attrs.get("src", "")
        if "id" in attrs:
            self.ids[attrs["id"]] = tag
        self.stack.append(attrs.get("id") or (self.stack[-1] if self.stack else None))
        if tag == "td" and "envelope" in self.stack:
            self.cells.append("")
        if tag == "tr" and "envelope-cells" in self.stack and "class" in attrs:
            self.verdicts.append(attrs.get("class"))

    def handle_endtag(self, tag):
        if self.stack:
            self.stack.pop()

    def handle_data(self, data):
        owner = self.stack[-1] if self.stack else None
        if owner:
            self.text[owner] = self.text.get(owner, "") + data
        if self.cells and self.stack and self.stack[-1] == "envelope" and self.lasttag == "td":
            self.cells[-1] += data


def test_the_page_holds_every_chart_the_envelope_and_the_provenance(study, tmp_path, chromium):
    results = tmp_path / "synthetic" / "results.nc"
    results.parent.mkdir()
    study.to_netcdf(results)
    written = write_report(results)
    page = results.parent / "report.html"
    assert page in written and (results.parent / "charts" / "envelope.csv") in written
    assert not [p for p in page.parent.rglob(".tmp*")]
    charts = [p for p in written if p.suffix == ".png"]
    assert {p.stem for p in charts} >= {"envelope", "stress_limits", "fatigue_life", "contact_force", "regime_map",
                                        "campbell", "validity_map", "span_length"}
    dom = subprocess.run([str(chromium), *FLAGS, f"--user-data-dir={tmp_path / 'profile'}", "--dump-dom",
                          page.as_uri()], capture_output=True, text=True, timeout=120, check=True).stdout
    parsed = Page()
    parsed.feed(dom)
    for png in charts:  # each chart is in the DOM as an image of exactly the file drawn
        src = parsed.images[png.stem]
        assert src.startswith("data:image/png;base64,")
        assert base64.b64decode(src.split(",", 1)[1]) == png.read_bytes()
        assert parsed.ids[f"chart-{png.stem}"] == "figure"
    rows = envelope_table(study)
    undecided = dict(safe_ranges(rows, "undecided"))
    expected = [cell for load, safe in safe_ranges(rows) for cell in (load, safe, undecided[load])]
    assert parsed.ids["envelope"] == "table" and [c.strip() for c in parsed.cells] == expected
    # every cell of the envelope is a row of the page's cell table, with its verdict
    assert parsed.ids["envelope-cells"] == "table"
    assert parsed.verdicts == [r["verdict"] for r in rows]
    from study.charts.critical import api_comparison  # the model's critical speeds beside API RP 7G's, and why

    assert parsed.text["critical-speeds"].strip() == api_comparison(study) != ""
    from study.charts.drivers import main_effects  # which input drives the design: a row per design figure

    assert parsed.ids["drivers"] == "table" and "drivers" in parsed.images
    assert parsed.text["drivers"].count("of") >= len(main_effects(study)) > 0
    provenance = parsed.text["provenance"]
    assert "abc123" in provenance and "study 0.2.0" in provenance and "2026-11-24T09:00:00+00:00" in provenance
    assert parsed.text["config"].strip() == study.attrs["config"].strip()


def test_other_formats_are_linked_and_an_unknown_criterion_is_refused(study, tmp_path):
    written = write_report(study.isel(rotary_speed=slice(0, 4)), out_dir=tmp_path / "pdf", fmt="pdf")
    text = (tmp_path / "pdf" / "report.html").read_text()
    assert all(f'href="{p.name}"' in text for p in written if p.suffix == ".pdf")
    with pytest.raises(ValueError, match="criterion = 'soon'"):
        write_report(study, out_dir=tmp_path, criterion="soon")


def test_a_study_without_any_answer_says_so_at_the_top(study, tmp_path):
    """Issue 34: configs/paper.toml's 1 404 points are all hertz_invalid, and its report did not say why."""
    ds = study.copy(deep=True)
    ds["status"].values[...] = 2  # hertz_invalid
    ds["message"] = (ds.status.dims, np.full(ds.status.shape, "contact 8.5 m long on a 4.5-in pipe"))
    write_report(ds, out_dir=tmp_path)
    text = (tmp_path / "report.html").read_text()
    top = text.split("<h2>")[0]
    assert f"Points by status: {ds.status.size} hertz_invalid." in top
    assert "No point of this study has an answer" in top and "contact 8.5 m long" in top


def test_one_representative_point_of_each_regime_the_study_found(study):
    from study.charts.report import representative_points
    from study.solvers.model.result import REGIMES

    ds = study.copy(deep=True)
    assert representative_points(ds) == []  # no regime recorded: nothing to draw
    speed = ds.rotary_speed.broadcast_like(ds.status).transpose(*ds.status.dims)
    rpm = speed.values * 30 / np.pi
    regime = np.where(rpm < 150, REGIMES["sliding"], REGIMES["bouncing"]).astype(float)
    ds["regime"] = (ds.status.dims, regime)
    ds["status"].values[...] = 0
    points = dict(representative_points(ds))
    assert set(points) == {"sliding", "bouncing"}
    speeds = ds.rotary_speed.values * 30 / np.pi
    # the median speed of each regime's points: 60-140 rpm (median 100) and 160-300 rpm (median 240)
    assert speeds[points["sliding"]["rotary_speed"]] == pytest.approx(100)
    assert speeds[points["bouncing"]["rotary_speed"]] == pytest.approx(240)
