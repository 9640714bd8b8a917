"""Config loading and validation (study.config): units in, SI out, every bad input named."""

import math
from pathlib import Path

import numpy as np
import pytest

from study import config
from study.config import ConfigError, load_text

ROOT = Path(__file__).resolve().parents[1]

MINIMAL = """
[pipe]
outer_diameter = "4.5 in"
inner_diameter = "3.826 in"
[hole]
diameter = "8.5 in"
[rock]
youngs_modulus = "5e6 psi"
poisson_ratio = 0.2
[mud]
density = "10 ppg"
[load]
axial_tension = "10000 lbf"
rotary_speed = "300 rpm"
[impact]
restitution = 0.5
"""


def with_lines(*lines, base=MINIMAL):
    """The minimal config with "[section] key = value" lines set: replaced if present, else added."""
    text = base
    for line in lines:
        section, assignment = line.split(" ", 1)
        key = assignment.split("=", 1)[0].strip()
        header = f"{section}\n"
        if header not in text:
            text += f"\n{section}\n{assignment}\n"
            continue
        head, body = text.split(header, 1)
        block, sep, rest = body.partition("\n[")
        kept = [ln for ln in block.splitlines() if ln.split("=", 1)[0].strip() != key]
        block = "\n".join([assignment, *kept]) + ("\n" if not sep else "")
        text = head + header + block + sep + rest
    return text


# Unit definitions (exact by definition): inch 0.0254 m, lb 0.45359237 kg, lbf = lb x 9.80665 m/s^2,
# US gallon 3.785411784e-3 m^3, psi = lbf/in^2, rpm = 2 pi/60 rad/s.
LBF = 0.45359237 * 9.80665
PSI = LBF / 0.0254**2


@pytest.mark.parametrize(
    "path, raw, expected",
    [
        ("pipe.outer_diameter", '"4.5 in"', 4.5 * 0.0254),
        ("pipe.outer_diameter", "0.1143", 0.1143),
        ("pipe.linear_mass", '"16.6 lb/ft"', 16.6 * 0.45359237 / 0.3048),
        ("hole.diameter", '"8.5 in"', 8.5 * 0.0254),
        ("pipe.youngs_modulus", '"30e6 psi"', 30e6 * PSI),
        ("pipe.youngs_modulus", '"30000 ksi"', 30e6 * PSI),
        ("mud.density", '"10 lb/gal"', 10 * 0.45359237 / 3.785411784e-3),
        ("mud.density", '"10 ppg"', 10 * 0.45359237 / 3.785411784e-3),
        ("mud.density", '"0.0433 lb/in^3"', 0.0433 * 0.45359237 / 0.0254**3),
        ("mud.flow_velocity", '"88.6 in/s"', 88.6 * 0.0254),
        ("load.axial_tension", '"10000 lbf"', 1e4 * LBF),
        ("load.axial_tension", '"44.5 kN"', 44.5e3),
        ("load.rotary_speed", '"300 rpm"', 300 * 2 * np.pi / 60),
        ("load.rotary_speed", '"5 rev/s"', 5 * 2 * np.pi),
        ("load.rotary_speed", "31.4", 31.4),
        ("solver.max_span", '"1000 ft"', 304.8),
        ("pipe.tool_joint_inner_diameter", '"3.25 in"', 3.25 * 0.0254),
        ("pipe.tool_joint_length", '"20 in"', 0.508),
        ("pipe.tool_joint_length", '"0.5 m"', 0.5),
        ("mud.plastic_viscosity", '"20 cP"', 0.020),  # 1 cP = 1 mPa s
        ("mud.plastic_viscosity", '"0.035 Pa s"', 0.035),
    ],
    ids=lambda v: v if isinstance(v, str) else None,
)
def test_units_users_write_are_converted_to_si(path, raw, expected):
    section, key = path.split(".")
    study = load_text(with_lines(f"[{section}] {key} = {raw}"))
    assert study.inputs[config.FIELDS_BY_PATH[path].name] == pytest.approx(expected, rel=1e-12)


def test_defaults_fill_optional_inputs():
    study = load_text(MINIMAL)
    assert study.inputs["pipe_poisson_ratio"] == 0.30
    assert study.inputs["drag_coefficient"] == 0.5  # paper §IV D
    assert study.inputs["plastic_viscosity"] == 0.020  # 20 cP: a water-base mud's (config.FIELDS' note)
    assert study.inputs["added_mass_model"] == "potential_flow"
    assert study.inputs["pipe_linear_mass"] is None
    assert study.size == 1 and study.axes == {}


BAD = [
    # (extra line, fragment the error must contain) - one per rule of the foundation issue.
    ('[pipe] outer_diameter = "4.5 lbf"', "pipe.outer_diameter = '4.5 lbf'"),  # wrong dimension
    ('[pipe] outer_diameter = "4.5"', "has no units"),  # a bare number in a string
    ('[pipe] colour = "red"', "pipe.colour: unknown key"),  # unknown key
    ('[pipe] outer_diamter = "4.5 in"', "did you mean 'outer_diameter'"),  # misspelt key
    ("[impact] restitution = 1.5", "impact.restitution = 1.5: must be a finite number > 0 and <= 1"),
    # issue 32: e = 0 was accepted and the reference model computed it as a perfectly elastic contact
    ("[impact] restitution = 0", "impact.restitution = 0: must be a finite number > 0 and <= 1 (e = 0, a plastic "
                                 "contact, is not modelled: the Hunt-Crossley contact"),
    ("[impact] restitution = -0.1", "impact.restitution = -0.1"),
    ('[mud] density = "-10 ppg"', "mud.density = '-10 ppg'"),  # negative
    ("[mud] drag_coefficient = nan", "must be finite"),  # non-finite
    ("[mud] drag_coefficient = inf", "must be finite"),
    ('[pipe] inner_diameter = "5 in"', "pipe.inner_diameter"),  # inner >= outer
    ('[hole] diameter = "4 in"', "hole.diameter"),  # hole <= pipe
    ('[load] rotary_speed = "5 Hz"', "ambiguous as a rotary speed"),
    ('[load] rotary_speed = "0 rpm"', "load.rotary_speed = '0 rpm'"),
    ('[mud] added_mass_model = "magic"', "one of 'potential_flow', 'gap_flow'"),
    ('[solver] method = "quantum"', "solver.method = 'quantum'"),
    ("[pipe] poisson_ratio = 0.7", "pipe.poisson_ratio = 0.7"),
    ('[pipe] youngs_modulus = "lots"', "cannot be read as a quantity"),
    ("[pipe] youngs_modulus = true", "is a boolean"),
    ('colour = "red"', "colour: unknown key"),
    ('[sweep] axes = { "load.rpm" = [1, 2] }', "sweep.axes.load.rpm: not an input"),
    ('[sweep] axes = { "impact.restitution" = [0.5, 1.2] }', "sweep.axes.impact.restitution[1] = 1.2"),
    ('[sweep] axes = { "load.rotary_speed" = { start = "50 rpm", stop = "300 rpm" } }', "exactly one of num or step"),
    ('[sweep] axes = { "load.rotary_speed" = { start = "50 rpm", stop = "300 rpm", num = 0 } }', "num = 0"),
    ('[sweep] axes = { "load.rotary_speed" = [] }', "at least one value"),
    ('[sweep] axes = { "pipe.inner_diameter" = ["3 in", "4.6 in"] }', "pipe.inner_diameter"),
    ('[pipe] tool_joint_length = "-1 in"', "pipe.tool_joint_length = '-1 in'"),
    ('[pipe] tool_joint_inner_diameter = "7 in"', "pipe.tool_joint_inner_diameter = 0.1778 m: must be < "
                                                  "pipe.tool_joint_diameter"),  # the joint's bore >= its OD
    ('[pipe] tool_joint_length = "40 ft"', "pipe.tool_joint_length = 12.192 m: must be < pipe.joint_length"),
    ("[sweep] chunk_size = 0", "sweep.chunk_size = 0"),
    # issue 36: the tolerance of statistical figures is a relative error in (0, 1)
    ("[solver] statistical_tolerance = 0", "solver.statistical_tolerance = 0: must be a finite number > 0 and < 1 "
                                           "(it is a relative error of a mean: 0.05 asks for 5 %)"),
    ("[solver] statistical_tolerance = 5", "solver.statistical_tolerance = 5: must be a finite number > 0 and < 1"),
    # the peak contact force's own tolerance likewise (docs/reference_model.md §3.1)
    ("[solver] force_tolerance = 0", "solver.force_tolerance = 0: must be a finite number > 0 and < 1 (it is a "
                                     "relative error of the force: 0.15 asks for 15 %)"),
    ("[solver] force_tolerance = 1.5", "solver.force_tolerance = 1.5: must be a finite number > 0 and < 1"),
    ("[sweep] chunksize = 10", "did you mean 'chunk_size'"),
    # issue 36: the mud's plastic viscosity, a viscosity >= 0
    ('[mud] plastic_viscosity = "-5 cP"', "mud.plastic_viscosity = '-5 cP'"),
    ('[mud] plastic_viscosity = "20 ppg"', "mud.plastic_viscosity = '20 ppg': '20 ppg' has dimension"),
]


@pytest.mark.parametrize("line, fragment", BAD, ids=[b[0] for b in BAD])
def test_each_rule_is_refused_with_field_value_and_rule(line, fragment):
    if line.startswith("colour"):
        text = line + "\n" + MINIMAL
    else:
        text = with_lines(line)
    with pytest.raises(ConfigError) as info:
        load_text(text)
    assert fragment in str(info.value)


def test_missing_required_field_is_named_with_its_rule():
    with pytest.raises(ConfigError, match=r"rock.poisson_ratio: missing; required"):
        load_text(MINIMAL.replace("poisson_ratio = 0.2\n", ""))


def test_duplicate_key_is_a_toml_error_not_a_crash():
    with pytest.raises(ConfigError, match="not valid TOML"):
        load_text(MINIMAL + "\n[impact]\nrestitution = 0.3\n")


def test_multiple_rules_reported_together():
    text = MINIMAL.replace("restitution = 0.5", "restitution = 2").replace('"8.5 in"', '"1 in"')
    text = text.replace("[pipe]\n", '[pipe]\ncolour = "red"\n')
    with pytest.raises(ConfigError) as info:
        load_text(text)
    joined = "\n".join(info.value.problems)
    assert "impact.restitution = 2" in joined
    assert "pipe.colour" in joined
    assert "hole.diameter" in joined
    assert len(info.value.problems) == 3


@pytest.mark.parametrize(
    "axis, expected",
    [
        ('{ start = "50 rpm", stop = "300 rpm", step = "50 rpm" }', np.array([50, 100, 150, 200, 250, 300.0])),
        ('{ start = "50 rpm", stop = "300 rpm", num = 3 }', np.array([50, 175, 300.0])),
        ('["300 rpm", "100 rpm", "100 rpm"]', np.array([100, 300.0])),  # sorted, duplicates dropped
    ],
    ids=["step", "num", "list"],
)
def test_sweep_axes_expand_sorted_in_si(axis, expected):
    study = load_text(with_lines(f"[sweep.axes] load.rotary_speed = {axis}"))
    np.testing.assert_allclose(study.axes["rotary_speed"], expected * 2 * np.pi / 60, rtol=1e-12)
    assert study.inputs["rotary_speed"] == pytest.approx(300 * 2 * np.pi / 60)  # the fixed value stays


def test_axis_may_be_named_by_short_name_and_choice_axes_work():
    study = load_text(with_lines('[sweep.axes] restitution = [0.8, 0.2]\nmud.added_mass_model = ["gap_flow", "potential_flow"]'))
    np.testing.assert_array_equal(study.axes["restitution"], [0.2, 0.8])
    assert list(study.axes["added_mass_model"]) == ["gap_flow", "potential_flow"]
    assert study.size == 4


def test_swept_only_required_input_must_be_set_for_a_point():
    study = load_text(with_lines('[sweep.axes] load.rotary_speed = ["100 rpm", "200 rpm"]').replace(
        'rotary_speed = "300 rpm"\n', ""))
    with pytest.raises(ConfigError, match="load.rotary_speed: given only as a sweep axis"):
        study.point()
    assert study.point(rotary_speed=10.0)["rotary_speed"] == 10.0


def test_overrides_from_the_command_line():
    overrides = config.parse_set(['load.rotary_speed="200 rpm"', "impact.restitution=0.7", "solver.method=core"])
    study = load_text(MINIMAL, overrides=overrides)
    assert study.inputs["rotary_speed"] == pytest.approx(200 * 2 * np.pi / 60)
    assert study.inputs["restitution"] == 0.7
    with pytest.raises(ConfigError, match="expected section.key=VALUE"):
        config.parse_set(["restitution"])
    with pytest.raises(ConfigError, match="--set pipe: unknown field"):
        load_text(MINIMAL, overrides={"pipe": 1})


def test_default_config_is_the_papers_example():
    study = config.load(ROOT / "configs" / "paper.toml")
    point = study.point()
    # Paper §VI: 4 1/2-in pipe, E 30e6 psi, nu 0.30, rock 5e6 psi / 0.20, mud 0.0433 lb/in^3, T0 = 10 000 lb, 300 rpm.
    assert point["outer_diameter"] == pytest.approx(4.5 * 0.0254)
    assert point["pipe_youngs_modulus"] == pytest.approx(30e6 * PSI)
    assert point["rock_youngs_modulus"] == pytest.approx(5e6 * PSI)
    assert point["mud_density"] == pytest.approx(0.0433 * 0.45359237 / 0.0254**3)
    assert point["axial_tension"] == pytest.approx(1e4 * LBF)
    assert point["rotary_speed"] == pytest.approx(10 * np.pi)
    assert study.size >= 1000  # the sweep workflow's default study size


def test_missing_file_is_a_config_error():
    with pytest.raises(ConfigError, match="cannot read config"):
        config.load(ROOT / "configs" / "no-such-file.toml")


def test_binary_garbage_as_a_config_names_the_file(tmp_path):
    garbage = tmp_path / "results.nc"  # e.g. a dataset passed where the config goes
    garbage.write_bytes(b"\x89HDF\r\n\x1a\n\x00\x00\xff\xfe")
    with pytest.raises(ConfigError) as info:
        config.load(garbage)
    assert str(info.value) == (f"{garbage}: 1 problem(s)\n  - not a text config: byte 0x89 at offset 0 is not UTF-8 "
                               "(a config is a TOML text file)")


def test_a_range_with_stop_below_start_names_both():
    with pytest.raises(ConfigError) as info:
        load_text(with_lines('[sweep.axes] load.rotary_speed = { start = "300 rpm", stop = "50 rpm", step = "10 rpm" }'))
    assert "sweep.axes.load.rotary_speed: stop = '50 rpm' is below start = '300 rpm'" in str(info.value)
    assert "step" not in str(info.value).split("below")[0]  # the step is not blamed
    with pytest.raises(ConfigError, match=r"sweep.axes.load.rotary_speed.step = '-10 rpm': must be > 0"):
        load_text(with_lines('[sweep.axes] load.rotary_speed = { start = "50 rpm", stop = "300 rpm", step = "-10 rpm" }'))


@pytest.mark.parametrize("value, accepted", [(10, True), (0, False), (-1, False), (2.5, False), (True, False)])
def test_sweep_max_points_is_a_whole_number_of_at_least_one(value, accepted):
    text = with_lines(f"[sweep] max_points = {str(value).lower()}")
    if accepted:
        assert load_text(text).sweep["max_points"] == value
    else:
        with pytest.raises(ConfigError, match=f"sweep.max_points = {value!r}: must be the most points a sweep accepts"):
            load_text(text)


# --- fuzzing: whatever a user writes, the answer is a Study or a ConfigError, never a crash ----------
from hypothesis import given, settings
from hypothesis import strategies as st

_VALUES = st.one_of(
    st.integers(-10**6, 10**6), st.floats(allow_nan=True, allow_infinity=True), st.booleans(),
    st.text(max_size=12), st.sampled_from(["4.5 in", "-3 ft", "10 ppg", "300 rpm", "1e400 psi", "lbf", "3 Hz",
                                           "nan in", "0 in", "in", "2 m/s**2", "5 rev/s", "1/0", "3 deg/100ft",
                                           "2 deg/30m", "walk_right", "1e400 deg/100ft", "3 deg/1e-400ft"]),
    st.lists(st.integers(-5, 5), max_size=3),
)
_PATHS = st.sampled_from([f.path for f in config.FIELDS] + ["pipe.colour", "sweep.chunk_size", "sweep.workers",
                                                            "sweep.scheduler", "mud.densty"])


@settings(max_examples=300, deadline=None)
@given(st.lists(st.tuples(_PATHS, _VALUES), min_size=1, max_size=4))
def test_fuzzed_configs_load_or_are_refused_cleanly(edits):
    overrides = {path: value for path, value in edits}
    try:
        study = load_text(MINIMAL, overrides=overrides)
    except ConfigError as exc:
        assert exc.problems and all(isinstance(p, str) and p for p in exc.problems)
        return
    assert isinstance(study.inputs, dict)


@settings(max_examples=200, deadline=None)
@given(st.text(max_size=200))
def test_fuzzed_text_is_refused_cleanly(text):
    try:
        load_text(text)
    except ConfigError as exc:
        assert exc.problems


def test_screen_config_is_the_default_grid_with_the_sdof_method():
    default = config.load(ROOT / "configs" / "paper.toml")
    screen = config.load(ROOT / "configs" / "screen.toml")
    assert screen.inputs["solver_method"] == "sdof" and screen.name == "screen"
    assert {k: v for k, v in screen.inputs.items() if k != "solver_method"} == \
        {k: v for k, v in default.inputs.items() if k != "solver_method"}
    assert all(np.array_equal(screen.axes[k], default.axes[k]) for k in default.axes)


def test_crosscheck_config_is_the_paper_example_with_the_self_consistent_closure():
    default = config.load(ROOT / "configs" / "paper.toml")
    check = config.load(ROOT / "configs" / "crosscheck.toml")
    assert check.inputs["solver_method"] == "crosscheck" and check.inputs["closure"] == "self_consistent"
    assert check.inputs["span_length"] is None  # the periodic solution finds its own span
    changed = {"solver_method", "closure", "modes", "span_length"}
    assert {k: v for k, v in check.inputs.items() if k not in changed | set(check.axes)} == \
        {k: v for k, v in default.inputs.items() if k not in changed | set(check.axes)}
    assert list(check.axes["impact_pattern"]) == ["one_wall", "alternating"]
    assert list(check.axes["restitution"]) == [0.5, 1.0]
    assert check.axes["rotary_speed"] * 60 / (2 * np.pi) == pytest.approx([50, 75, 100, 150, 200, 250, 300])


# --- limits a drilling engineer decides with: pipe grade, strengths, tool joint, fatigue ------------
KSI = 1000 * PSI


def test_limit_fields_default_to_stated_values():
    inputs = load_text(MINIMAL).inputs
    # E-75: the lowest-strength API grade, so a point under its yield is under every grade's.
    assert inputs["pipe_grade"] == "E-75"
    assert inputs["yield_strength"] is None and inputs["tensile_strength"] is None  # from the grade
    assert inputs["stress_concentration"] == 1.0  # the pipe body's nominal stress
    assert inputs["joint_length"] == pytest.approx(31 * 0.3048)  # API Range 2, the typical 31-ft joint
    assert inputs["sn_curve"] == "B1"  # DNV-RP-C203 Table 2-1: non-welded base material
    assert inputs["mean_stress_correction"] == "goodman"
    assert inputs["cycles_per_revolution"] == 1.0  # rotating bending (Hansford & Lubinski 1966)


@pytest.mark.parametrize(
    "line, name, expected",
    [
        ('[pipe] yield_strength = "95 ksi"', "yield_strength", 95 * KSI),  # below E-75's 100 ksi tensile
        ('[pipe] yield_strength = "95000 psi"', "yield_strength", 95 * KSI),
        ('[pipe] yield_strength = "655 MPa"', "yield_strength", 655e6),
        ("[pipe] yield_strength = 6.55e8", "yield_strength", 6.55e8),
        ('[pipe] tensile_strength = "145 ksi"', "tensile_strength", 145 * KSI),
        ('[pipe] grade = "S-135"', "pipe_grade", "S-135"),
        ("[pipe] stress_concentration = 1.6", "stress_concentration", 1.6),
        ('[pipe] joint_length = "31 ft"', "joint_length", 31 * 0.3048),
        ('[fatigue] sn_curve = "D"', "sn_curve", "D"),
        ('[fatigue] mean_stress = "gerber"', "mean_stress_correction", "gerber"),
        ("[fatigue] cycles_per_revolution = 2", "cycles_per_revolution", 2.0),
    ],
    ids=lambda v: v if isinstance(v, str) and "=" in v else None,
)
def test_limit_fields_are_read_in_the_units_users_write(line, name, expected):
    value = load_text(with_lines(line)).inputs[name]
    assert value == (pytest.approx(expected, rel=1e-12) if isinstance(expected, float) else expected)


BAD_LIMITS = [
    ('[pipe] grade = "P-110"', "pipe.grade = 'P-110': must be one of 'E-75', 'X-95', 'G-105', 'S-135'"),
    ("[pipe] grade = 105", "pipe.grade = 105: must be one of 'E-75'"),
    ('[pipe] yield_strength = "-5 ksi"', "pipe.yield_strength = '-5 ksi' (= -3.44738e+07 Pa): must be a finite "
                                          "number [Pa] > 0"),
    ('[pipe] yield_strength = "135 ksi/in"', "pipe.yield_strength = '135 ksi/in': "),
    ('[pipe] yield_strength = "135"', "pipe.yield_strength = '135': '135' has no units"),
    # a given yield above E-75's minimum tensile strength (100 ksi)
    ('[pipe] yield_strength = "120 ksi"', "pipe.yield_strength = 8.27371e+08 Pa: must be < pipe.tensile_strength"
                                          " = 6.89476e+08 Pa (given, or grade E-75's minimum"),
    ('[pipe] tensile_strength = "70 ksi"', "must be < pipe.tensile_strength = 4.82633e+08 Pa"),
    ("[pipe] stress_concentration = 0.8", "pipe.stress_concentration = 0.8: must be a finite number >= 1"),
    ('[pipe] joint_length = "0 ft"', "pipe.joint_length = '0 ft'"),
    ('[fatigue] sn_curve = "F"', "fatigue.sn_curve = 'F': must be one of 'B1', 'B2', 'C', 'D'"),
    ('[fatigue] mean_stress = "walker"', "fatigue.mean_stress = 'walker': must be one of 'goodman', 'gerber', "
                                         "'soderberg', 'none'"),
    ("[fatigue] cycles_per_revolution = 0", "fatigue.cycles_per_revolution = 0: must be a finite number > 0"),
    ('[fatigue] curve = "B1"', "fatigue.curve: unknown key (did you mean 'sn_curve'?)"),
]


@pytest.mark.parametrize("line, fragment", BAD_LIMITS, ids=[b[0] for b in BAD_LIMITS])
def test_bad_limit_fields_are_refused_with_field_value_and_rule(line, fragment):
    with pytest.raises(ConfigError) as info:
        load_text(with_lines(line))
    assert fragment in str(info.value)


def test_grade_sweeps_check_each_grade_against_the_given_strengths():
    # a given yield strength between S-135's minimum yield and minimum tensile strength is accepted
    assert load_text(with_lines('[pipe] grade = "S-135"', '[pipe] yield_strength = "140 ksi"')).inputs[
        "yield_strength"] == pytest.approx(140 * KSI)
    # each swept grade pairs its own minima: E-75 and S-135 together are fine ...
    study = load_text(with_lines('[sweep.axes] pipe.grade = ["S-135", "E-75"]'))
    assert list(study.axes["pipe_grade"]) == ["S-135", "E-75"]
    # ... but a given tensile strength of 120 ksi is below S-135's minimum yield (135 ksi)
    with pytest.raises(ConfigError, match="grade S-135's minimum"):
        load_text(with_lines('[pipe] tensile_strength = "120 ksi"', '[sweep.axes] pipe.grade = ["E-75", "S-135"]'))


def test_every_limit_option_is_a_config_field():
    # study.physics.limits.design_limits takes the config's fields by name: a point's inputs feed it.
    from study.physics.limits import LIMIT_INPUTS, design_limits

    inputs = load_text(MINIMAL).inputs
    assert set(LIMIT_INPUTS) <= set(config.FIELDS_BY_NAME)
    result = design_limits(100e6, 20e6, 50e6, inputs["rotary_speed"], **{k: inputs[k] for k in LIMIT_INPUTS})
    assert result.yield_utilisation == pytest.approx(100e6 / (75_000 * PSI))


# Issue 32: the study name is joined to outputs/ - it must be one plain folder name there.
@pytest.mark.parametrize("name, why", [
    ("../../x", "path separator"),
    ("/abs/path", "path separator"),
    ("a\\\\b", "path separator"),
    ("..", "relative folder"),
    (".", "relative folder"),
    ("two\\nlines", "control character '\\n'"),
    ("bell\\u0007", "control character"),
    ("x" * 500, "500 characters; at most 100"),
    (" padded", "spaces"),
], ids=["up", "absolute", "backslash", "dotdot", "dot", "newline", "bell", "long", "padded"])
def test_a_study_name_that_is_not_one_plain_folder_name_is_refused(name, why):
    with pytest.raises(ConfigError) as refused:
        load_text(f'name = "{name}"\n' + MINIMAL)
    [problem] = refused.value.problems
    assert problem.startswith("name = ") and why in problem and "allowed: one folder name under outputs/" in problem
    assert len(problem) < 400  # a 5000-character name is named by its start, not printed whole


def test_a_plain_study_name_is_kept_and_a_file_name_that_cannot_be_one_is_refused():
    assert load_text('name = "drill pipe, 8° hole (v2)"\n' + MINIMAL).name == "drill pipe, 8° hole (v2)"
    assert load_text(MINIMAL, source="configs/x.toml").name == "x"
    with pytest.raises(ConfigError, match="the config file's name"):
        load_text(MINIMAL, source="configs/" + "y" * 120 + ".toml")


# Issue 32: the parser is bounded - every input below was a hang, a traceback or gigabytes before any check.
def _refused_quickly(text, fragment, seconds=10.0):
    # the bound tells a hang (or gigabytes of work) from a refusal, not speed: loose enough for a loaded 2-core CI
    import time

    start = time.perf_counter()
    with pytest.raises(ConfigError) as refused:
        load_text(text)
    assert time.perf_counter() - start < seconds
    assert fragment in str(refused.value), str(refused.value)[:500]
    assert len(str(refused.value)) < 2000  # the bad value is named by its start, never printed whole


@pytest.mark.parametrize("line, fragment", [
    ('[pipe] outer_diameter = "9**9**9 in"', "pipe.outer_diameter = '9**9**9 in': '9**9**9 in' cannot be read"),
    ('[pipe] outer_diameter = "10**400 in"', "pipe.outer_diameter = '10**400 in'"),
    ('[pipe] outer_diameter = "1e400 in"', "beyond a float's range"),
    ('[pipe] outer_diameter = "4.5 in**99"', "an exponent is a whole number of at most 12"),
    ("[pipe] youngs_modulus = " + "9" * 400, "an integer of 400 digits is too large"),
    ('[pipe] outer_diameter = "' + "4" * 400 + ' in"', "at most 100 characters"),
    ('[pipe] outer_diameter = "1 m;import os"', "is not a number, a unit name"),
    ('[sweep] axes = { "load.rotary_speed" = { start = "50 rpm", stop = "300 rpm", num = 1000000000 } }',
     "sweep.axes.load.rotary_speed.num = 1000000000: must be a whole number >= 1 and <= 1e+07"),
    ('[sweep] axes = { "load.rotary_speed" = { start = "1 rpm", stop = "300 rpm", step = "1e-9 rpm" } }',
     "at most 1e+07 values on one axis"),
    ("[sweep] max_points = 100000000", "sweep.max_points = 100000000: must be the most points a sweep accepts"),
    ("[sweep] workers = 100000", "sweep.workers = 100000: must be local worker processes"),
    ("[pipe] outer_diameter = [" + "1, " * 50000 + "1]", "pipe.outer_diameter = <an array of 50001>: "),
], ids=["tower", "huge-power", "overflow", "exponent", "400-digit-int", "long-number", "garbage", "num-1e9",
        "step-1e9", "max-points", "workers", "long-array-value"])
def test_values_that_would_hang_or_overflow_are_refused_at_once(line, fragment):
    _refused_quickly(with_lines(line), fragment)


def test_a_grid_over_ten_million_points_is_refused_by_the_config():
    _refused_quickly(with_lines('[sweep] axes = { "load.rotary_speed" = { start = "50 rpm", stop = "300 rpm", '
                                'num = 10000 }, "load.axial_tension" = { start = "1 lbf", stop = "9 lbf", num = 1001 } }'),
                     "sweep.axes: the grid has 10,010,000 points (10000 rotary_speed x 1001 axial_tension); at most "
                     "10,000,000 in one study")


@pytest.mark.parametrize("text, fragment", [
    ("v = " + "[" * 100_000 + "]" * 100_000, "nested too deep"),
    ("[sweep.axes" + ".a" * 3000 + "]\nb = 1\n" + MINIMAL, "nested more than 10 deep"),
    (MINIMAL + "[sweep.axes]\n" + "x" * 1_000_000 + " = 1\n", "at most 1,000,000"),
    (MINIMAL + "[sweep.axes]\n" + "x" * 500 + " = 1\n", "a key of 500 characters; at most 100"),
    (MINIMAL + 'title = "' + "t" * 900_000 + '"\n', "a string of 900000 characters; at most 1000"),
    ("x = 1" + "0" * 5000, "not a valid value"),
], ids=["deep-arrays", "deep-tables", "huge-file", "long-key", "long-string", "5000-digit-int"])
def test_configs_too_deep_or_too_large_are_refused_before_anything_is_built(text, fragment):
    _refused_quickly(text, fragment)


def test_the_config_file_is_read_only_if_it_is_a_small_regular_file(tmp_path):
    import os

    big = tmp_path / "big.toml"
    big.write_text("# " + "x" * 1_100_000 + "\n")
    with pytest.raises(ConfigError, match="more than 1,000,000 bytes"):
        config.load(big)
    os.mkfifo(tmp_path / "fifo.toml")  # reading it would wait for a writer forever
    with pytest.raises(ConfigError, match="not a regular file"):
        config.load(tmp_path / "fifo.toml")
    with pytest.raises(ConfigError, match="not a regular file"):
        config.load("/dev/zero")


@pytest.mark.parametrize("written, si, unit", [
    # every unit spelling the shipped configs and tests use, and the dogleg severities of another field
    ("4.5 in", 0.1143, "m"), ("15.0 lb/ft", 15.0 * 0.45359237 / 0.3048, "kg/m"),
    ("16.6 lbm/ft", 16.6 * 0.45359237 / 0.3048, "kg/m"), ("10 ppg", 10 * 0.45359237 / 0.003785411784, "kg/m^3"),
    ("0.0433 lb/in^3", 0.0433 * 0.45359237 / 0.0254**3, "kg/m^3"), ("7.4 ft/s", 7.4 * 0.3048, "m/s"),
    ("88.6 in/s", 88.6 * 0.0254, "m/s"), ("10000 lbf", 10000 * 4.4482216152605, "N"),
    ("30e6 psi", 30e6 * 6894.757293168361, "Pa"), ("120 ksi", 120e3 * 6894.757293168361, "Pa"),
    ("2 m/s**2", 2.0, "m/s^2"),
    ("3 deg/100ft", math.radians(3) / 30.48, "rad/m"), ("3 deg/100 ft", math.radians(3) / 30.48, "rad/m"),
    ("3 deg/(100 ft)", math.radians(3) / 30.48, "rad/m"), ("3 deg/30m", math.radians(3) / 30, "rad/m"),
])
def test_units_as_users_write_them_are_read_by_the_bounded_grammar(written, si, unit):
    # expected values: the exact definitions of the inch (0.0254 m), foot, pound (0.45359237 kg), US gallon
    # (3.785411784 L), pound-force (4.4482216152605 N) and psi (NIST SP 811 appendix B)
    from study.units import parse_quantity

    assert parse_quantity(written, unit) == pytest.approx(si, rel=1e-12)


# --- the well: dogleg severity and direction (issue 33) ---------------------------------------------
DEG_PER_100FT = np.pi / 180 / 30.48  # 1°/100 ft in rad/m: 100 ft = 30.48 m exactly


@pytest.mark.parametrize(
    "line, name, expected",
    [
        ('[hole] dogleg_severity = "3 deg/100ft"', "dogleg_curvature", 3 * DEG_PER_100FT),
        ('[hole] dogleg_severity = "3 deg/100 ft"', "dogleg_curvature", 3 * DEG_PER_100FT),
        ('[hole] dogleg_severity = "3 deg/30m"', "dogleg_curvature", 3 * np.pi / 180 / 30),
        ('[hole] dogleg_severity = "0.0017 rad/m"', "dogleg_curvature", 0.0017),
        ("[hole] dogleg_severity = 0.0017", "dogleg_curvature", 0.0017),  # a number is SI
        ('[hole] dogleg_severity = "30 deg/100ft"', "dogleg_curvature", 30 * DEG_PER_100FT),  # the bound itself
        # the angle towards the centre of curvature from the low side (+y) towards +z = x × y
        ('[hole] dogleg_direction = "drop"', "dogleg_direction", 0.0),
        ('[hole] dogleg_direction = "build"', "dogleg_direction", np.pi),
        ('[hole] dogleg_direction = "walk_left"', "dogleg_direction", np.pi / 2),
        ('[hole] dogleg_direction = "walk_right"', "dogleg_direction", -np.pi / 2),
        ('[hole] dogleg_direction = "45 deg"', "dogleg_direction", np.pi / 4),
        ("[hole] dogleg_direction = 1.0", "dogleg_direction", 1.0),
    ],
    ids=lambda v: v if isinstance(v, str) and "=" in v else None,
)
def test_dogleg_fields_are_read_in_the_units_users_write(line, name, expected):
    assert load_text(with_lines(line)).inputs[name] == pytest.approx(expected, rel=1e-12, abs=1e-15)


def test_dogleg_fields_default_to_a_straight_hole():
    inputs = load_text(MINIMAL).inputs
    assert inputs["dogleg_curvature"] == 0.0 and inputs["dogleg_direction"] == 0.0


BAD_DOGLEGS = [
    ('[hole] dogleg_severity = "31 deg/100ft"', "hole.dogleg_severity = '31 deg/100ft' (= 0.0177511 1/m): must be a "
                                                "finite number [1/m] >= 0 and <= 0.0171784 (at most 30 deg/100ft)"),
    ('[hole] dogleg_severity = "-1 deg/100ft"', "hole.dogleg_severity = '-1 deg/100ft' (= -0.000572615 1/m): must"),
    ("[hole] dogleg_severity = 3", "hole.dogleg_severity = 3: must be a finite number [1/m] >= 0"),  # 3 rad/m
    ('[hole] dogleg_severity = "3 deg/100"', "hole.dogleg_severity = '3 deg/100': '3 deg/100' cannot be read as an "
                                             "angle per length; write it as '3 deg/100ft', '3 deg/30m' or"),
    ('[hole] dogleg_severity = "3/100ft"', "'3/100ft' cannot be read as an angle per length"),  # no angle named
    ('[hole] dogleg_severity = "3 deg/0ft"', "'3 deg/0ft' cannot be read as an angle per length"),
    ('[hole] dogleg_severity = "3 deg/100in"', "'3 deg/100in' cannot be read as an angle per length"),
    ('[hole] dogleg_direction = "sideways"', "a direction is one of 'drop', 'build', 'walk_right', 'walk_left' or"),
    ('[hole] dogleg_direction = "90"', "hole.dogleg_direction = '90': '90' has no units"),
    ("[hole] dogleg_direction = 90", "hole.dogleg_direction = 90: must be a finite number [rad] >= -6.28319 and "
                                     "<= 6.28319 (-360 to 360 deg)"),  # 90 rad: degrees meant
    ('[hole] dogleg_direction = "3 m"', "hole.dogleg_direction = '3 m'"),
]


@pytest.mark.parametrize("line, fragment", BAD_DOGLEGS, ids=[b[0] for b in BAD_DOGLEGS])
def test_bad_dogleg_fields_are_refused_with_field_value_and_rule(line, fragment):
    with pytest.raises(ConfigError) as info:
        load_text(with_lines(line))
    assert fragment in str(info.value)


def test_dogleg_fields_sweep_as_grid_axes():
    study = load_text(with_lines(
        '[sweep.axes] hole.dogleg_severity = { start = "0 deg/100ft", stop = "6 deg/100ft", step = "2 deg/100ft" }\n'
        'hole.dogleg_direction = ["build", "drop", "walk_left", "45 deg", "drop"]'))
    np.testing.assert_allclose(study.axes["dogleg_curvature"], np.array([0, 2, 4, 6]) * DEG_PER_100FT, rtol=1e-12)
    np.testing.assert_allclose(study.axes["dogleg_direction"], [0, np.pi / 4, np.pi / 2, np.pi])  # sorted, unique
    assert study.size == 16
    point = study.point(dogleg_curvature=study.axes["dogleg_curvature"][1], dogleg_direction=np.pi)
    assert point["dogleg_curvature"] == pytest.approx(2 * DEG_PER_100FT) and point["dogleg_direction"] == np.pi
    with pytest.raises(ConfigError, match=r"sweep.axes.hole.dogleg_severity\[1\] = '40 deg/100ft'"):
        load_text(with_lines('[sweep.axes] hole.dogleg_severity = ["1 deg/100ft", "40 deg/100ft"]'))


def test_dogleg_severity_from_the_command_line():
    overrides = config.parse_set(['hole.dogleg_severity="3 deg/30m"', "hole.dogleg_direction=walk_right"])
    inputs = load_text(MINIMAL, overrides=overrides).inputs
    assert inputs["dogleg_curvature"] == pytest.approx(np.pi / 180 / 10)
    assert inputs["dogleg_direction"] == -np.pi / 2
