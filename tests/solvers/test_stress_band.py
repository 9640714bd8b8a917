"""The stresses stated in the band where the beam theory holds (``reference_stress_band``; docs/reference_model.md
§2.3.1, §3): the kept modes above the band's edge enter the fields by their quasi-static response."""

from pathlib import Path

import numpy as np
import pytest

from study import config
from study.solvers.methods import reference
from study.solvers.methods.reference.fields import field_states, modal_fields
from study.solvers.methods.reference.model import static_correction, stress_band_edge
from study.solvers.model import options
from study.solvers.model.point import DesignPoint

NAMES = ("max_normal_stress", "alternating_bending_stress", "max_deflection", "max_shear_stress", "max_wall_excess")


def test_the_option_is_validated_naming_the_field():
    assert options.ReferenceOptions().reference_stress_band == "timoshenko"
    with pytest.raises(ValueError, match="reference_stress_band = 'shear'; allowed: all, timoshenko$"):
        options.ReferenceOptions.from_inputs({"reference_stress_band": "shear"})
    with pytest.raises(config.ConfigError,
                       match="solver.reference_stress_band = 'shear': must be one of 'all', 'timoshenko'$"):
        config.load(Path(__file__).resolve().parents[2] / "configs" / "default.toml",
                    {"solver.reference_stress_band": "shear"})


def _window(model, rng, forces=None):
    """A recorded window of random states (and contact forces) over one revolution: fields' inputs, no motion."""
    N, P, R = model.n_modes, model.points.size, 24
    times = np.linspace(0.0, model.period, R)
    states = np.zeros((R, 4 * N + 4))
    states[:, :4 * N] = rng.normal(size=(R, 4 * N)) * model.state_scale() * 0.1
    if forces is None:
        forces = np.zeros((R, P, 3))
    return reference.Window(times=times, states=states, forces=forces, peak=np.max(forces[:, :, 2], axis=0),
                            onsets=np.zeros(P, int), contact_time=np.zeros(P), any_contact_time=0.0, start=0.0,
                            end=float(times[-1]))


def test_a_band_over_every_kept_mode_gives_every_modes_stresses(paper_inputs):
    # 8 modes of the paper's section reach some 20 Hz, far under the band's edge (some 0.3 kHz): "timoshenko" is "all"
    # to the last bit, the joints' mass and weight in the model (an 8° hole)
    inputs = {**paper_inputs, "inclination": np.radians(8), "reference_modes": 8}
    every = reference.build_model({**inputs, "reference_stress_band": "all"})
    band = reference.build_model({**inputs, "reference_stress_band": "timoshenko"})
    assert every.stress_band == np.inf and np.max(band.omega) < band.stress_band < np.inf
    assert band.joint_points is not None and band.point_side is not None
    window = _window(every, np.random.default_rng(36))
    want, got = reference.stresses(inputs, every, window), reference.stresses(inputs, band, window)
    for name in NAMES:
        assert got[name] == want[name], name


@pytest.fixture(scope="module")
def plain(paper_inputs):
    """The paper's section of 16 modes without the joints' mass (the modes the periodic basis' own), no eccentric,
    side or drag load: each mode's load is the contact forces' alone; its band's edge set between the 7th and 8th
    modes (the rigid translation the first), and the model of those 7 modes."""
    inputs = {**paper_inputs, "inclination": 0.0, "tool_joint_length": 0.0, "eccentricity": 0.0,
              "reference_damping": "none"}
    model = reference.build_model({**inputs, "reference_modes": 16})
    small = reference.build_model({**inputs, "reference_modes": 7})
    assert model.basis is None and model.drag == 0.0 and not np.any(model.side)
    assert not np.any(model.eccentric) and not np.any(model.damping)
    model.stress_band = 0.5 * (model.omega[6] + model.omega[7])
    assert np.all(model.omega[:7] < model.stress_band) and np.all(model.omega[7:] > model.stress_band)
    return inputs, model, small


def test_the_modes_above_the_band_give_their_static_response_to_the_contact_forces(plain):
    # the fields with the band: the 7 modes within it as they move plus, for the modes above it and those left out, the
    # static field of the contact forces less the 7 modes' share: the point load's on the periodic beam-column in
    # closed form (static_correction of the 7-mode model: Gradshteyn & Ryzhik 1.445.2, docs/reference_model.md §3),
    # whatever the modes above the band do (their states here random: a ringing the band leaves out)
    inputs, model, small = plain
    rng = np.random.default_rng(7)
    P, R = model.points.size, 24
    forces = np.zeros((R, P, 3))
    forces[:, :, :2] = rng.normal(size=(R, P, 2)) * 2e4
    forces[:, :, 2] = np.hypot(forces[:, :, 0], forces[:, :, 1])
    window = _window(model, rng, forces)
    x = np.linspace(0.0, model.span, 41)
    for j in range(2):
        q = window.states[:, j * 16:(j + 1) * 16].copy()
        q[:, 7:] = 0.0
        want = modal_fields(model, q, x) + forces[:, :, j] @ static_correction(small, x)
        got = reference.periodic_fields(model, field_states(model, window, j), forces[:, :, j], x, j)
        scale = np.max(np.abs(want), axis=0)
        np.testing.assert_allclose(got["deflection"], want[:, :x.size], rtol=0, atol=1e-10 * scale[:x.size].max())
        np.testing.assert_allclose(got["moment"], want[:, x.size:], rtol=0, atol=1e-10 * scale[x.size:].max())
        # the strikes' loads masked (statistics.strike_stress_values): none of their static response above the band
        masked = field_states(model, window, j, np.ones((R, P), bool))
        assert np.array_equal(masked[:, :7], window.states[:, j * 16:j * 16 + 7])
        assert np.max(np.abs(masked[:, 7:])) < 1e-12 * np.max(np.abs(field_states(model, window, j)[:, 7:]))


def test_at_rest_under_its_loads_the_band_changes_nothing(plain):
    # a static load: the modes above the band at rest at their static response, L_n/ω_n², so the band's fields are
    # every mode's (to rounding)
    inputs, model, _ = plain
    rng = np.random.default_rng(11)
    N, P, R = model.n_modes, model.points.size, 24
    forces = np.zeros((R, P, 3))
    forces[:, :, 0] = rng.normal(size=(1, P)) * 2e4
    forces[:, :, 2] = np.abs(forces[:, :, 0])
    window = _window(model, rng, forces)
    window.states[:, 2 * N:4 * N] = 0.0
    window.states[:, 7:N] = forces[:, :, 0] @ model.phi[:, 7:] / (model.mass * model.omega[7:] ** 2)
    window.states[:, N + 7:2 * N] = 0.0  # no load along z
    every = reference.build_model({**inputs, "reference_modes": 16, "reference_stress_band": "all"})
    want, got = reference.stresses(inputs, every, window), reference.stresses(inputs, model, window)
    for name in NAMES:
        assert got[name] == pytest.approx(want[name], rel=1e-9, abs=1e-15), name


def test_the_default_pipes_band_edge(default_point):
    # docs/reference_model.md §2.3.1: 283 Hz at 12 ppg, 304 Hz at 9 ppg (5 %: solver.statistical_tolerance)
    for ppg, hz in ((12, 283.2), (9, 304.2)):
        scene = DesignPoint.from_inputs(default_point(250, 20, 0.3, ppg, 0.0)).scene
        assert stress_band_edge(scene) / (2 * np.pi) == pytest.approx(hz, abs=0.5)
