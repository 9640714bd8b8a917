"""The mud's quadratic drag summed on the slow modes alone (``reference_drag_modes``, ``reference_drag_rest``;
``reference.model.drag_on_slow_modes``, ``kernels.drag.drag_linearised``; docs/reference_model.md §4): the first N_d
modes' drag at the rule of N_d, the modes above by its linear equivalent about their velocity field, or none."""

from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from study.benchmarks.reference import fixed_window
from study.config import load
from study.solvers.kernels import whirl_kernel
from study.solvers.methods import reference
from study.solvers.methods.reference.model import drag_on_slow_modes

ROOT = Path(__file__).resolve().parents[2]
MODES = 16
SLOW = 8


@pytest.fixture(scope="module")
def model():
    point = load(ROOT / "configs" / "default.toml").point()
    return reference.build_model({**point, "reference_modes": MODES, "reference_max_modes": MODES})


def slow_system(model, rest="linear"):
    """The kernel's tuple of ``model`` with its drag on the first :data:`SLOW` modes (a count the option's choices,
    sized for the study's 64-128 modes, do not hold: set here as ``drag_on_slow_modes`` reads it)."""
    option = SimpleNamespace(reference_drag_modes=str(SLOW), reference_drag_quadrature="gauss",
                             reference_drag_rest=rest)
    model.slow_drag = drag_on_slow_modes(model, option, None)
    try:
        return whirl_kernel.kernel_system(model.system(), float, model.slow_drag[2])
    finally:
        model.slow_drag = None


def test_the_default_sums_every_modes_drag_and_a_count_above_the_modes_changes_nothing(model):
    assert model.slow_drag is None
    sy = whirl_kernel.kernel_system(model.system())
    assert sy[4].shape[0] == MODES and not np.any(sy[22])
    point = load(ROOT / "configs" / "default.toml").point()
    assert reference.build_model({**point, "reference_modes": MODES, "reference_max_modes": MODES,
                                  "reference_drag_modes": "32"}).slow_drag is None


def test_the_slow_modes_drag_is_summed_at_their_own_rule_and_alone_moving_matches_every_modes(model, kernel_drag):
    sy = slow_system(model)
    assert sy[4].shape[0] == SLOW and sy[5].size == 2 * SLOW + 8  # Gauss–Legendre at 2N_d + 8 points
    rng = np.random.default_rng(5)
    z = np.zeros(4 * MODES + 4)
    for part in (2, 3):  # the slow modes alone moving, a 1/n spectrum [m/s]
        z[part * MODES:part * MODES + SLOW] = rng.standard_normal(SLOW) / np.maximum(np.arange(SLOW), 1.0)
    full, power = kernel_drag(whirl_kernel.kernel_system(model.system()), z)
    slow, slow_power = kernel_drag(sy, z)
    low = np.r_[0:SLOW, MODES:MODES + SLOW]
    # the two rules sum the same field: they differ by their quadrature errors (|u̇| u̇ is no polynomial), measured
    # 1.9e-3 of the force and 2.3e-4 of the power
    assert np.linalg.norm(slow[low] - full[low]) < 1e-2 * np.linalg.norm(full[low])
    assert slow_power == pytest.approx(power, rel=2e-3)
    # the modes above, at rest: their linear equivalent exerts nothing on them
    assert np.all(slow[np.r_[SLOW:MODES, MODES + SLOW:2 * MODES]] == 0.0)


def test_the_linear_equivalent_of_a_uniform_whirl_is_the_derivative_of_the_drag(model, kernel_drag):
    # u̇_q = (a, b)/√2 along the whole span (the rigid translation ψ_0 = 1/√2 alone among the slow modes): the drag's
    # Jacobian d(D |u̇| u̇)/du̇ = D (|u̇| I + u̇ u̇ᵀ/|u̇|) is the same everywhere, so a fast mode's part is exactly
    # D |u̇_q| (I + e eᵀ) ∫ ψ_n² dx per modal mass; against the full drag's derivative by central differences of mode
    # n's velocity (every mode's drag summed): measured within 1e-9 (ψ_0 = 0.677 along the span, the joints' mass in
    # the basis, model.shapes)
    sy_full, sy = whirl_kernel.kernel_system(model.system()), slow_system(model)
    z = np.zeros(4 * MODES + 4)
    z[2 * MODES], z[3 * MODES] = 0.3, 0.2
    linear, _ = kernel_drag(sy, z)
    h = 1e-6
    for n in range(SLOW, MODES):
        for part in (2, 3):
            i = part * MODES + n
            up, down = z.copy(), z.copy()
            up[i] += h
            down[i] -= h
            exact = (kernel_drag(sy_full, up)[0] - kernel_drag(sy_full, down)[0])[i - 2 * MODES] / (2 * h)
            zz = z.copy()
            zz[i] += h
            equivalent = (kernel_drag(sy, zz)[0] - linear)[i - 2 * MODES] / h
            assert equivalent == pytest.approx(exact, rel=1e-6), (n, part)
    # the closed form itself: a push (h, h) on mode N_d gives D |u̇_q| (I + e eᵀ) (1, 1) ∫ ψ_n² dx per modal mass
    speed = np.hypot(0.3, 0.2) * model.shapes(np.zeros(1))[0, 0]
    e = np.array([0.3, 0.2]) / np.hypot(0.3, 0.2)
    zz = z.copy()
    zz[2 * MODES + SLOW] += h
    zz[3 * MODES + SLOW] += h
    got = (kernel_drag(sy, zz)[0] - linear)[[SLOW, MODES + SLOW]] / h
    closed = model.drag * speed * model.span * sy[22][SLOW] * (np.ones(2) + e * e.sum()) / model.mass
    assert got == pytest.approx(-closed, rel=1e-6)  # a drag: against the push


def test_without_the_rest_the_fast_modes_feel_no_drag_and_a_bad_count_is_named(model, kernel_drag):
    sy = slow_system(model, "none")
    z = np.zeros(4 * MODES + 4)
    z[2 * MODES], z[2 * MODES + SLOW + 1] = 0.3, 0.1
    force, _ = kernel_drag(sy, z)
    assert np.all(force[SLOW:MODES] == 0.0) and force[0] != 0.0
    point = load(ROOT / "configs" / "default.toml").point()
    with pytest.raises(ValueError, match="reference_drag_modes = '12'; allowed: all, band, 32"):
        reference.build_model({**point, "reference_drag_modes": "12"})


#: The bound on each figure's change in :func:`test_the_slow_modes_drag_moves_a_thrown_strings_figures_little`: measured
#: 8.0e-5 with the linear rest (the peak force) and 3.5e-4 without (the max normal stress), the same 26 onsets
BOUND = {"linear": 5e-4, "none": 2e-3}


@pytest.mark.parametrize("rest", ["linear", "none"])
def test_the_slow_modes_drag_moves_a_thrown_strings_figures_little(rest):
    # the deterministic window of study.benchmarks.reference.fixed_window (the string thrown rigidly at 0.3 m/s onto
    # its joints' wall, a quarter revolution: no chaos, the same start) at 40 modes, the drag on the first 32 against
    # every mode's: within BOUND[rest] of each figure, the same onsets
    point = load(ROOT / "configs" / "default.toml").point()
    inputs = {**point, "reference_modes": 40, "reference_max_modes": 40}
    default = fixed_window(inputs, 0.25)
    slow = fixed_window({**inputs, "reference_drag_modes": "32", "reference_drag_rest": rest}, 0.25)
    assert slow["onsets"] == default["onsets"]
    for name in ("peak_contact_force", "max_normal_stress", "alternating_bending_stress", "max_deflection"):
        assert slow[name] == pytest.approx(default[name], rel=BOUND[rest]), name
