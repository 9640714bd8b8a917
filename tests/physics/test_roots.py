"""Compiled regula falsi, one step at a time (study.physics.roots)."""

import math

import numpy as np
import pytest

from study.physics import roots


def shrink(func, a, b, rtol, iterations=200):
    """The caller's loop of the module doc, in Python: (root, f there, evaluations)."""
    fa, fb = func(a), func(b)
    raw_a, raw_b, side, count = fa, fb, 0, 0
    while count < iterations and not roots.bracket_done(a, b, fa, fb, rtol):
        x = roots.falsi_point(a, b, fa, fb)
        a, b, fa, fb, raw_a, raw_b, side = roots.keep_sign_change(a, b, fa, fb, raw_a, raw_b, side, x, func(x))
        count += 1
    root, value = roots.closer_end(a, b, fa, fb, raw_a, raw_b)
    return root, value, count


@pytest.mark.parametrize("rtol", [1e-10, 1e-14])
@pytest.mark.parametrize("cube", [1e-3, 0.7, 1.0, 30.0, 1e6])
def test_cube_roots(cube, rtol):
    # source: closed form - x^3 = a has the root a^(1/3); brackets [0, a + 1] of very different widths.
    root, value, _ = shrink(lambda x: x**3 - cube, 0.0, cube + 1.0, rtol)
    assert root == pytest.approx(np.cbrt(cube), rel=max(10 * rtol, 1e-13))
    assert value == root**3 - cube  # the value returned is f at the root


def test_an_end_at_a_zero_is_the_root():
    # source: the definition - a bracket with f = 0 at an end is done at once.
    assert shrink(math.sin, 0.0, 1.0, 1e-12)[::2] == (0.0, 0)
    assert shrink(math.sin, 3.0, math.pi, 1e-12)[0] == pytest.approx(math.pi, rel=1e-15)


@pytest.mark.parametrize("k", [1.0, 10.0, 50.0, 200.0])
def test_stiff_functions_converge_superlinearly(k):
    # source: closed form - exp(k (x - 1)) - 1 = 0 at x = 1. Plain regula falsi crawls along the convex
    # side (98 steps at k = 1; at k = 10 and above it has not narrowed [0, 3] after 10^5); the Illinois
    # halving closes in within 70 (of them, about log2 f(3) = 1.44 k halvings of the end's weight at most).
    root, _, count = shrink(lambda x: math.expm1(k * (x - 1.0)), 0.0, 3.0, 1e-13)
    assert root == pytest.approx(1.0, rel=1e-12)
    assert count < 70


def test_unusable_chords_fall_back_to_the_midpoint():
    # source: the definition - a non-finite end value or equal end values give no chord.
    assert roots.falsi_point(0.0, 2.0, math.inf, -1.0) == 1.0
    assert roots.falsi_point(0.0, 2.0, math.nan, -1.0) == 1.0
    assert roots.falsi_point(0.0, 2.0, 1.0, 1.0) == 1.0
    assert roots.falsi_point(0.0, 2.0, 1.0, -3.0) == 0.5
