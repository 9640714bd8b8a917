"""The one-degree-of-freedom screen (study.solvers.methods.sdof): the design point -> SDOF mapping and the orbit."""

from pathlib import Path

import numpy as np
import pytest

from study import config
from study.physics import oscillator, section
from study.solvers.methods import sdof
from study.solvers.model.point import DesignPoint
from study.solvers.model.equivalent import equivalent_parameters as equivalent_of

ROOT = Path(__file__).resolve().parents[2]


def equivalent_parameters(inputs):
    """The span's one-degree-of-freedom model at a point given by its inputs (its Scene and sdof options)."""
    point = DesignPoint.from_inputs(inputs)
    return equivalent_of(point.scene, point.sdof)


@pytest.fixture(scope="module")
def point():
    return config.load(ROOT / "configs" / "paper.toml").point()


def test_equivalent_parameters_of_the_span(point):
    par = equivalent_parameters(point)
    props = par.scene.props
    L, M = point["span_length"], props["mass_per_length"]
    w1 = float(section.natural_frequencies(L, props["bending_stiffness"], props["effective_tension"], M)[0])
    assert par.mass == pytest.approx(M * L / 2)  # modal mass of sin(pi x / L)
    assert par.omega1 == pytest.approx(w1) and par.stiffness == pytest.approx(M * L / 2 * w1**2)
    assert par.clearance == pytest.approx((8.75 - 4.5) / 2 * 0.0254)
    # linearised drag 8 D Omega c/(3 pi) per length, projected on sin(pi x/L): x 4L/(3 pi)
    D, Om, c = props["drag_coefficient_per_length"], point["rotary_speed"], par.clearance
    assert par.damping == pytest.approx(8 * D * Om * c / (3 * np.pi) * 4 * L / (3 * np.pi))
    # default drive: mean impact force of the prescribed closure, two impacts per revolution
    tau = 2 * np.pi / Om
    assert par.drive_amplitude == pytest.approx(2 * par.mass * 1.5 * Om * c / tau)
    other = equivalent_parameters({**point, "sdof_mass": "momentum", "sdof_damping": "none",
                                        "drive_amplitude": 123.0, "span_length": 40.0})
    assert other.mass == pytest.approx(2 * M * 40.0 / np.pi) and other.damping == 0.0
    assert other.drive_amplitude == 123.0
    assert other.stiffness / other.mass == pytest.approx(
        float(section.natural_frequencies(40.0, props["bending_stiffness"], props["effective_tension"], M)[0]) ** 2)


def test_stable_alternating_orbit_satisfies_the_impact_map(point):
    r = sdof.solve(point)
    assert r.status == "ok" and r.extras["stability"] == "stable", r.message
    p = sdof.impact_params(equivalent_parameters(point))
    v, tau, T = r.values["impact_velocity"], r.extras["orbit_phase"], 2 * np.pi / point["rotary_speed"]
    # the flight from +c (leaving at -e v) reaches -c half a revolution later at speed v
    st = oscillator.flight_state(tau + T / 2, (p.gap, -p.restitution * v), p, tau)
    assert float(st.x) == pytest.approx(-p.gap, rel=1e-9) and float(st.v) == pytest.approx(-v, rel=1e-9)
    # stability checked independently: event-driven motion from a 20 % perturbation returns to it
    imp = sdof.two_wall_impacts(tau, (p.gap, -1.2 * p.restitution * v), p, 30)
    assert [w for _, w, _ in imp[-2:]] == [-1.0, 1.0]
    assert imp[-1][2] == pytest.approx(v, rel=1e-8)
    assert ((imp[-1][0] - tau) / T) % 1.0 == pytest.approx(0.0, abs=1e-8) or \
        ((imp[-1][0] - tau) / T) % 1.0 == pytest.approx(1.0, abs=1e-8)
    assert np.max(np.abs(r.extras["floquet_multipliers"])) < 1
    assert r.values["impulse"] == pytest.approx(r.values["equivalent_mass"] * 1.5 * v)
    assert r.values["peak_contact_force"] > 0 and r.values["impacts_per_revolution"] == 2


def test_half_map_jacobian_against_finite_differences(point):
    p = sdof.impact_params(equivalent_parameters(point))
    o = [o for o in sdof.symmetric_orbits(p) if o["verdict"] == "stable"][0]
    T, e = o["period"], p.restitution

    def half_map(tau, v):  # leave +c at tau with -e v, mirrored hit of -c
        ev = oscillator.next_impact_time(tau + T / 2, (-p.gap, e * v), p, tau + 2 * T)
        return np.array([ev.time - T, ev.velocity])

    tau, v = o["phase"], o["velocity"]
    h = 1e-6
    fd = np.column_stack([(half_map(tau + h * T, v) - half_map(tau - h * T, v)) / (2 * h * T),
                          (half_map(tau, v * (1 + h)) - half_map(tau, v * (1 - h))) / (2 * h * v)])
    np.testing.assert_allclose(o["jacobian"], fd, rtol=1e-4, atol=1e-6 * np.abs(fd).max())


def test_one_wall_orbit_satisfies_the_one_wall_impact_map(point):
    # a 7 m span (omega_1 = 28.5 rad/s, just below Omega) preloaded towards +c by a side force
    inputs = {**point, "impact_pattern": "one_wall", "span_length": 7.0, "drive_amplitude": 2e3,
              "side_force": 4e3}
    r = sdof.solve(inputs)
    assert r.status == "ok" and r.extras["stability"] == "stable", r.message
    assert r.values["impacts_per_revolution"] == 1
    assert sdof.solve({**inputs, "impact_pattern": "alternating"}).status == "incomplete"
    p = sdof.impact_params(equivalent_parameters(inputs))
    ev = oscillator.impact_map(r.extras["orbit_phase"], r.values["impact_velocity"], p)
    T = 2 * np.pi / point["rotary_speed"]
    assert ev.time == pytest.approx(r.extras["orbit_phase"] + T, rel=1e-9)
    assert ev.velocity == pytest.approx(r.values["impact_velocity"], rel=1e-8)


def test_tiny_drive_reports_no_impact(point):
    r = sdof.solve({**point, "drive_amplitude": 1.0})
    assert r.status == "no_impact" and r.extras["stability"] == "no_impact"
    assert r.values["impacts_per_revolution"] == 0 and r.values["impact_velocity"] == 0
    assert r.values["free_amplitude"] < 1e-3 * r.values["clearance"]


def test_strong_drive_is_unstable_and_no_span_is_incomplete(point):
    r = sdof.solve({**point, "drive_amplitude": 2e5})
    assert r.status == "unstable" and r.extras["stability"] == "unstable"
    assert "symmetry-breaking" in r.message
    assert sdof.solve({**point, "span_length": None}).status == "incomplete"


def test_a_side_force_holding_the_span_on_the_wall_is_sticking(point):
    # a 20-m span, one wall: the 1-kN side force exceeds the spring's k c = 864 N plus the 100-N drive, so at
    # rest on the wall the net force pushes into it at every phase: sticking (was "chattering" while the side
    # force was left out of the net force)
    inputs = {**point, "impact_pattern": "one_wall", "span_length": 20.0, "drive_amplitude": 100.0,
              "side_force": 1e3}
    par = equivalent_parameters(inputs)
    assert par.side_force - par.drive_amplitude > par.stiffness * par.clearance
    r = sdof.solve(inputs)
    assert r.status == "sticking" and "(sticking)" in r.message


def test_solve_reads_its_options_from_the_inputs_once(point, monkeypatch):
    # issue 35: the screen's options are built once, with the design point, and passed to equivalent_parameters (each
    # read them from the inputs again before: two builds a point)
    from study.solvers.model.options import SdofOptions

    builds = []
    read = SdofOptions.from_inputs
    monkeypatch.setattr(SdofOptions, "from_inputs", classmethod(lambda cls, inputs: builds.append(cls) or read(inputs)))
    assert sdof.solve(point).status == "ok" and builds == [SdofOptions]
