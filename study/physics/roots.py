"""Regula falsi with the Illinois modification, one compiled step at a time, for the compiled root
finders of the physics and solvers (the span search, :mod:`study.solvers.methods.periodic`, shrinks thousands
of sign-changing brackets of its screening residual in one compiled loop).

Pure numerics on floats, no I/O. A caller's loop::

    while not bracket_done(a, b, fa, fb, rtol):
        x = falsi_point(a, b, fa, fb)
        a, b, fa, fb, raw_a, raw_b, side = keep_sign_change(a, b, fa, fb, raw_a, raw_b, side, x, f(x))

and the root is :func:`closer_end`. Superlinear on smooth functions: the end kept twice in a row has
its value halved, so both ends close in (plain regula falsi crawls along a convex side).
"""

from __future__ import annotations

import math

import numba


@numba.njit(cache=True, nogil=True)
def bracket_done(a, b, fa, fb, rtol):
    """Whether the bracket [a, b] is narrower than ``rtol`` (relative to b) or holds an exact zero at an end."""
    return b - a <= rtol * abs(b) or fa == 0.0 or fb == 0.0


@numba.njit(cache=True, nogil=True)
def falsi_point(a, b, fa, fb):
    """The next point inside (a, b): where the chord through (a, fa), (b, fb) crosses zero, or the
    midpoint when the chord is unusable (an end value not finite, equal end values) or falls on or
    outside an end."""
    if math.isfinite(fa) and math.isfinite(fb) and fb != fa:
        x = b - fb * (b - a) / (fb - fa)
        if a < x < b:
            return x
    return 0.5 * (a + b)


@numba.njit(cache=True, nogil=True)
def keep_sign_change(a, b, fa, fb, raw_a, raw_b, side, x, fx):
    """The bracket after evaluating f(x) = ``fx`` at x in (a, b): x replaces the end whose value has
    the sign of fx (a NaN replaces b). fa, fb: the Illinois weights (f at the ends, halved each time
    the other end moved twice in a row); raw_a, raw_b: f at the ends as computed; side: which end
    moved last (1: a, −1: b, 0: none yet). Returns (a, b, fa, fb, raw_a, raw_b, side)."""
    if (fx > 0.0 and fa > 0.0) or (fx < 0.0 and fa < 0.0):  # the sign change is in [x, b]
        if side == 1:
            fb *= 0.5
        return x, b, fx, fb, fx, raw_b, 1
    if side == -1:
        fa *= 0.5
    return a, x, fa, fx, raw_a, fx, -1


@numba.njit(cache=True, nogil=True)
def closer_end(a, b, fa, fb, raw_a, raw_b):
    """(root, f at the root): the end of the final bracket with the smaller weighted |f|."""
    if abs(fa) < abs(fb):
        return a, raw_a
    return b, raw_b
