"""Compiled one-point interpolation (study.physics.interpolation)."""

import math

import numpy as np
import pytest

from study.physics.interpolation import interp_one

XP = np.log(np.geomspace(3.0, 304.8, 12))
FP = np.log(np.geomspace(4e-4, 2e-3, 12)) + 0.01 * np.sin(XP)


@pytest.mark.parametrize("x", [XP[0] - 1.0, XP[0], XP[3], 0.5 * (XP[3] + XP[4]), XP[4] - 1e-15, XP[-1], XP[-1] + 2.0,
                               *np.random.default_rng(3).uniform(XP[0], XP[-1], 40)])
def test_one_point_is_numpys_interp(x):
    # source: the definition - interp_one is np.interp of one point, in the same arithmetic.
    assert interp_one(x, XP, FP) == np.interp(x, XP, FP)


def test_nan_stays_nan():
    assert math.isnan(interp_one(math.nan, XP, FP))
