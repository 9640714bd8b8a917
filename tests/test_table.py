"""The point table (study.table, ``study point`` without --json): every output a method returns prints, in the
table's unit system, at a clear, a sliding and a bouncing point of the default study."""

import re
from pathlib import Path

import pytest

from study.config import load, parse_set
from study.solvers import solve_point
from study.table import EXTRA_OUTPUTS, describe, message_units, point_table

ROOT = Path(__file__).resolve().parents[1]
DEFAULT = ROOT / "configs" / "default.toml"
PSI = 6894.757293168361  # Pa per psi (NIST SP 811)
FT = 0.3048  # m per ft (exact)

#: Points of the default study and the fastest method that gives each regime there (found with `study point`
#: and auto: in the default 8° hole the string lies on its joints, so the clear point is the vertical hole's, where
#: the free whirl answers at 300 rpm / 30 000 lbf; 50 rpm / 5 000 lbf slides — auto keeps the sliding state's
#: answer — and 200 rpm / 5 000 lbf bounces: the reference model answers).
POINTS = {"clear": ("300 rpm", "30000 lbf", "free-whirl", ['hole.inclination="0 deg"']),
          "sliding": ("50 rpm", "5000 lbf", "sliding", []),
          "bouncing": ("200 rpm", "5000 lbf", "reference", [])}


@pytest.fixture(scope="module")
def results():
    out = {}
    for regime, (speed, load_, method, more) in POINTS.items():
        inputs = load(str(DEFAULT), parse_set([f'load.rotary_speed="{speed}"', f'load.axial_tension="{load_}"',
                                               *more])).point()
        inputs["solver_method"] = method
        out[regime] = solve_point(inputs)
    # auto at the sliding point: its record of the models tried
    inputs = load(str(DEFAULT), parse_set(['load.rotary_speed="50 rpm"', 'load.axial_tension="5000 lbf"'])).point()
    out["auto"] = solve_point(inputs)
    return out


def _rows(table: str) -> dict[str, str]:
    """Row name -> the rest of its line (the value, unit and description; a wrapped description's line joined)."""
    rows, last = {}, None
    for line in table.splitlines()[4:]:
        match = re.match(r"  (\w+)\s+(.*)", line)
        if match and not line.startswith("  " + " " * 30):
            last = match.group(1)
            rows[last] = match.group(2)
        elif last and line.strip():
            rows[last] += "  " + line.strip()
    return rows


@pytest.mark.parametrize("system", ["oilfield", "si"])
def test_every_output_of_every_regime_prints_with_a_description(results, system):
    regimes = {r.extras.get("whirl") for r in results.values()}
    assert {"bouncing"} <= regimes and results["sliding"].values["regime"] == 6  # REGIMES["sliding"]
    assert results["clear"].values["regime"] == 0  # REGIMES["no_contact"]
    for result in results.values():
        rows = _rows(point_table(result, system=system))
        names = [*result.values, *result.extras] + (["error_estimate"] if result.error_estimate is not None else [])
        assert set(names) <= set(rows), set(names) - set(rows)
        for name in names:
            assert "(no description" not in rows[name], name  # every output is described (study.table)
            if name != "error_estimate" and describe(name)[0] == "1":  # dimensionless: no unit "1" after the value
                assert not re.search(r"\d 1\s", rows[name]), (name, rows[name])


def test_units_follow_the_table_s_system(results):
    bouncing = results["bouncing"]
    oil, si = _rows(point_table(bouncing)), _rows(point_table(bouncing, system="si"))
    stress = bouncing.values["max_normal_stress"]
    assert oil["max_normal_stress"].startswith(f"{stress / PSI:.5g} psi")
    assert si["max_normal_stress"].startswith(f"{stress / 1e6:.5g} MPa")
    assert oil["whirl_point"].startswith(f"{bouncing.extras['whirl_point'] / FT:.5g} ft")
    assert si["whirl_point"].startswith(f"{bouncing.extras['whirl_point']:.5g} m")
    assert "1/h" in oil["damage_rate"] and "per hour of rotation" in oil["damage_rate"]
    assert "1/s" in si["damage_rate"] and "per second of rotation" in si["damage_rate"]
    sliding = point_table(results["sliding"])
    message = sliding.splitlines()[1]
    assert " N" not in message.replace(" N s", "") and " mm" not in message and "lbf" in message
    assert " N " in point_table(results["sliding"], system="si").splitlines()[1] + " "


def test_the_error_estimate_names_the_figure_it_is_the_error_of(results):
    bouncing = results["bouncing"]
    # the reference model's estimate is its worst figure's, the damage rate's as the stress error that makes it
    errors = {name: entry["equivalent"] for name, entry in bouncing.extras["convergence"].items()}
    worst = max(errors, key=errors.get)
    assert bouncing.error_estimate == pytest.approx(errors[worst])
    assert errors["damage_rate"] == pytest.approx(
        (1 + bouncing.extras["convergence"]["damage_rate"]["total"]) ** (1 / 5) - 1)
    words = {"peak_contact_force": "peak contact force", "max_normal_stress": "max normal stress",
             "alternating_bending_stress": "alternating bending stress", "damage_rate": "fatigue damage rate"}
    assert f"the worst figure, the {words[worst]}" in _rows(point_table(bouncing))["error_estimate"]
    assert "max normal stress" in _rows(point_table(results["clear"]))["error_estimate"]
    auto = _rows(point_table(results["auto"]))
    assert auto["methods_tried"].startswith("free-whirl out_of_scope; sliding ")


def test_message_quantities_are_converted_and_others_left_alone():
    text = "lying on the wall at 9.449 m, 18.9 m, sliding: 145 N at rest, ±18 N; 48 against 24 modes; 2.5 mm"
    assert message_units(text) == ("lying on the wall at 31 ft, 62.01 ft, sliding: 32.6 lbf at rest, ±4.047 lbf; "
                                   "48 against 24 modes; 0.09843 in")
    assert message_units(text, "si") == text
    assert all(describe(name)[1] for name in EXTRA_OUTPUTS)
