"""The compiled extremes of the reference model's stress fields (study/solvers/kernels/stress_kernel.py)."""

import numpy as np
import pytest

from study.solvers.kernels import stress_kernel

FIBRES = np.linspace(0.0, np.pi, 16, endpoint=False)


def extremes(my, mz, uy, uz, x, turn):
    return stress_kernel.window_extremes(my, mz, uy, uz, x, np.cos(turn), np.sin(turn), np.cos(FIBRES),
                                        np.sin(FIBRES))


def test_a_bend_turning_with_the_pipe_alternates_in_no_fibre_and_a_fixed_one_by_its_size():
    # a steady bend in the pipe's own frame (a synchronous whirl: M_y, M_z turning with the pipe) alternates in no
    # fibre; a fixed bend (lying on the wall) alternates by its whole size in the worst fibre (Vance,
    # Rotordynamics of Turbomachinery, Wiley 1988, ch. 2): to within the 16 fibres' spacing, cos(π/32)
    turn = np.linspace(0.0, 2.0 * np.pi, 400, endpoint=False)
    x = np.array([0.0, 1.0])
    zero = np.zeros((400, 2))
    *_, steady = extremes(np.outer(np.cos(turn), [1.0, 2.0]), np.outer(np.sin(turn), [1.0, 2.0]), zero, zero, x, turn)
    np.testing.assert_allclose(steady, 0.0, atol=1e-12)
    largest, *_, fixed = extremes(np.full((400, 2), 3.0), zero, zero, zero, x, turn)
    assert largest == pytest.approx(3.0, rel=1e-15)
    np.testing.assert_allclose(fixed, 3.0, rtol=1e-4)


@pytest.mark.parametrize("seed", [3, 11])
def test_the_extremes_are_numpys_over_the_whole_window(seed):
    # the same extremes numpy's direct evaluation gives (the code this kernel replaced): largest |M| and where, largest
    # |u|, largest |ΔM|/Δx and where, and the fibres' half ranges
    rng = np.random.default_rng(seed)
    my, mz, uy, uz = rng.standard_normal((4, 300, 9))
    x = np.sort(rng.uniform(0.0, 10.0, 9))
    turn = rng.uniform(0.0, 20.0, 300)
    largest, it, ix, deflection, shear, jt, jx, half = extremes(my, mz, uy, uz, x, turn)
    moment = np.hypot(my, mz)
    assert (it, ix) == np.unravel_index(np.argmax(moment), moment.shape)
    assert largest == pytest.approx(moment.max(), rel=1e-15)
    assert deflection == pytest.approx(np.hypot(uy, uz).max(), rel=1e-15)
    v = np.hypot(np.diff(my, axis=1), np.diff(mz, axis=1)) / np.diff(x)
    assert (jt, jx) == np.unravel_index(np.argmax(v), v.shape)
    assert shear == pytest.approx(v.max(), rel=1e-14)
    direct = np.max([0.5 * np.ptp(my * np.cos(turn + p)[:, None] + mz * np.sin(turn + p)[:, None], axis=0)
                     for p in FIBRES], axis=0)
    np.testing.assert_allclose(half, direct, rtol=1e-13)


def test_a_nan_makes_every_extreme_nan():
    rng = np.random.default_rng(5)
    my, mz, uy, uz = rng.standard_normal((4, 50, 4))
    my[7, 2] = np.nan  # as numpy's max gives it
    largest, it, ix, deflection, shear, jt, jx, half = extremes(my, mz, uy, uz, np.arange(4.0), np.zeros(50))
    assert np.isnan(largest) and np.isnan(deflection) and np.isnan(shear) and np.isnan(half).all()
    assert (it, ix, jt, jx) == (-1, -1, -1, -1)
