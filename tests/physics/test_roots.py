"""Roots of many brackets at once (study.physics.roots)."""

import numpy as np
import pytest

from study.physics.roots import shrink_brackets


@pytest.mark.parametrize("rtol", [1e-10, 1e-14])
def test_cube_roots_of_many_brackets(rtol):
    # source: closed form - x^3 = a has the root a^(1/3); brackets [0, a + 1] of very different widths.
    a = np.geomspace(1e-3, 1e6, 200)
    seen = []

    def func(x, rows):
        seen.append(rows.size)
        return x**3 - a[rows]

    roots = shrink_brackets(func, np.zeros_like(a), a + 1.0, iterations=200, rtol=rtol).roots
    np.testing.assert_allclose(roots, np.cbrt(a), rtol=max(10 * rtol, 1e-13))
    assert seen[-1] < a.size  # finished brackets are no longer evaluated


def test_an_end_at_a_zero_is_the_root():
    # source: the definition - a bracket with f = 0 at an end is done at once.
    roots = shrink_brackets(lambda x, rows: np.sin(x), np.array([0.0, 3.0]), np.array([1.0, np.pi])).roots
    assert roots[0] == 0.0
    assert roots[1] == pytest.approx(np.pi, rel=1e-15)


def test_stiff_functions_converge_to_the_tolerance():
    # source: closed form - tan(x) = 1e6 (x - 0.5)... has no closed root; use exp(k x) = e^k at x = 1
    # instead: regula falsi alone would crawl along the convex side; the Illinois halving does not.
    k = np.array([1.0, 10.0, 50.0, 200.0])
    roots = shrink_brackets(lambda x, rows: np.expm1(k[rows] * (x - 1.0)), np.zeros(4), np.full(4, 3.0),
                            iterations=200, rtol=1e-13).roots
    np.testing.assert_allclose(roots, 1.0, rtol=1e-12)


def test_given_end_values_and_returned_values_are_the_functions():
    # source: the definition - f_lo, f_hi stand for func at the ends; the values returned are func at the roots.
    a = np.linspace(2.0, 50.0, 30)
    lo, hi = np.ones_like(a), a + 1.0

    def func(x, rows):
        return x**3 - a[rows]

    plain = shrink_brackets(func, lo, hi, rtol=1e-12).roots
    every = np.arange(a.size)
    roots, values = shrink_brackets(func, lo, hi, rtol=1e-12, f_lo=func(lo, every), f_hi=func(hi, every))[:2]
    np.testing.assert_array_equal(roots, plain)
    np.testing.assert_array_equal(values, func(roots, every))
