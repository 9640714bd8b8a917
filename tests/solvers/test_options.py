"""Every method's options declared once (study.solvers.model.options): the config takes its defaults from them, a bad
choice is refused naming it, and loading the config loads no solver."""

import subprocess
import sys
from dataclasses import fields

import pytest

from study import config
from study.solvers.model import options


@pytest.mark.parametrize("declared", [options.Options, options.TimeDomainOptions, options.SdofOptions,
                                      options.SeriesOptions, options.CrosscheckOptions, options.ReferenceOptions])
def test_the_config_defaults_are_the_declared_ones(declared):
    names = getattr(declared, "CONFIG_FIELDS", None) or [f.name for f in fields(declared)]
    configured = [name for name in names if name in config.FIELDS_BY_NAME]
    assert configured, declared
    for name in configured:
        assert config.FIELDS_BY_NAME[name].default == getattr(declared(), name), name


def test_the_config_choices_are_the_declared_ones():
    for name in ("time_integrator", "time_damping", "time_initial"):
        assert config.FIELDS_BY_NAME[name].choices == options.TimeDomainOptions.choices(name)
    for name in ("sdof_mass", "sdof_damping"):
        assert config.FIELDS_BY_NAME[name].choices == options.SdofOptions.choices(name)


def test_a_choice_outside_the_declared_values_is_refused_by_name():
    with pytest.raises(ValueError, match="time_damping = 'viscous'; allowed: linearised, drag, none"):
        options.TimeDomainOptions.from_inputs({"time_damping": "viscous"})


def test_the_residual_vectors_field_recovery_is_refused_by_name_outside_its_choices():
    # reference_recovery (docs/reference_model.md §2.1): the contact forces' static field ("force", the default) or the
    # residual vectors' coordinates ("vectors")
    assert options.ReferenceOptions().reference_recovery == "force"
    with pytest.raises(ValueError, match="reference_recovery = 'modes'; allowed: force, vectors"):
        options.ReferenceOptions.from_inputs({"reference_recovery": "modes"})


def test_unset_inputs_take_the_declared_defaults():
    chosen = options.TimeDomainOptions.from_inputs({"time_modes": 9, "time_step": None, "outer_diameter": 0.1})
    assert chosen.time_modes == 9 and chosen.time_step is None and chosen.time_revolutions == 60


def test_loading_the_config_loads_no_solver():
    code = ("import sys, study.config; print(sorted(m for m in sys.modules if m.startswith('study.solvers.')))")
    loaded = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert loaded.strip() == "['study.solvers.model', 'study.solvers.model.options', 'study.solvers.model.result']"


def test_the_statistical_tolerance_is_five_percent_unless_set_and_refused_outside_zero_to_one():
    # issue 36: the tolerance of figures that are means over revolutions (docs/reference_model.md §3.1)
    assert options.statistical_tolerance({}) == options.DEFAULT_STATISTICAL_TOLERANCE == 0.05
    assert options.statistical_tolerance({"statistical_tolerance": None}) == 0.05
    assert options.statistical_tolerance({"statistical_tolerance": 0.1}) == 0.1
    assert config.FIELDS_BY_NAME["statistical_tolerance"].default == 0.05
    for bad in (0.0, 1.0, -0.05, float("nan"), "five"):
        with pytest.raises(ValueError, match=r"solver.statistical_tolerance = .*: must be a number > 0 and < 1"):
            options.statistical_tolerance({"statistical_tolerance": bad})


def test_the_force_tolerance_is_fifteen_percent_unless_set_and_refused_outside_zero_to_one():
    # issue 36: the peak contact force is held to its own tolerance, what its inputs allow (a rock modulus known to
    # ±50 % moves a Hertz peak force by −22/+15 %: options.DEFAULT_FORCE_TOLERANCE, docs/reference_model.md §3.1)
    assert options.force_tolerance({}) == options.DEFAULT_FORCE_TOLERANCE == 0.15
    assert options.force_tolerance({"force_tolerance": None}) == 0.15
    assert options.force_tolerance({"force_tolerance": 0.05}) == 0.05
    assert config.FIELDS_BY_NAME["force_tolerance"].default == 0.15
    for bad in (0.0, 1.0, -0.1, float("nan"), "fifteen"):
        with pytest.raises(ValueError, match=r"solver.force_tolerance = .*: must be a number > 0 and < 1"):
            options.force_tolerance({"force_tolerance": bad})


def _typed(inputs):
    """Everything a solver reads of a point: its Scene and every options class built from it."""
    from study.solvers.model.scene import Scene

    built = [Scene.from_inputs(inputs), options.Tolerances.from_inputs(inputs), options.LimitOptions.from_inputs(inputs)]
    return built + [declared.from_inputs(inputs) for declared in (
        options.Options, options.TimeDomainOptions, options.SdofOptions, options.SeriesOptions, options.DampedOptions,
        options.CrosscheckOptions, options.ReferenceOptions)]


def test_every_config_field_reaches_the_scene_or_an_options_class():
    # issue 35: a parameter followed from the TOML to the physics by the typed point: each field of the config
    # (configs/paper.toml's point, each field moved in turn within its rule) changes the Scene or an options object
    # built from the point; solver.method alone is read by name, by solve_point's dispatch
    from pathlib import Path

    point = config.load(Path(__file__).resolve().parents[2] / "configs" / "paper.toml").point()
    base = _typed(point)
    unread = []
    for spec in config.FIELDS:
        value = point[spec.name]
        if spec.name == "solver_method":
            continue
        if spec.choices is not None:
            moved = next(choice for choice in spec.choices if choice != value)
        elif value is None:
            moved = 10.0 if spec.name != "yield_strength" else 5e8
        elif value == 0:
            moved = 1 if spec.integer else 0.1
        else:
            moved = type(value)(value * 2) if spec.integer else value * 0.9
        if _typed({**point, spec.name: moved}) == base:
            unread.append(spec.path)
    assert not unread, unread


def test_the_limit_options_are_the_limits_inputs():
    # source: study/physics/limits.py LIMIT_INPUTS, the keywords of design_limits that a config sets
    from study.physics.limits import LIMIT_INPUTS

    assert tuple(f.name for f in fields(options.LimitOptions)) == LIMIT_INPUTS
    assert options.LimitOptions.from_inputs({"sn_curve": "D", "yield_strength": None}).keywords() == {"sn_curve": "D"}
