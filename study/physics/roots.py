"""Roots of many sign-changing brackets at once (vectorised regula falsi), for the physics and solvers.

Pure numerics on numpy arrays, no I/O: the span search (:mod:`study.solvers.periodic`) solves
thousands of scalar equations whose brackets are known; one array call per step replaces a Python
loop of scalar solvers.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np


class Shrunk(NamedTuple):
    """The brackets of :func:`shrink_brackets` when they are done."""

    roots: np.ndarray  #: the end with the smaller |f|
    values: np.ndarray  #: func at the roots (as computed by func)
    lo: np.ndarray  #: the final brackets [lo, hi], still holding the sign change
    hi: np.ndarray
    f_lo: np.ndarray  #: func at lo and hi (as computed by func)
    f_hi: np.ndarray


def shrink_brackets(func, lo: np.ndarray, hi: np.ndarray, iterations: int = 60, rtol: float = 1e-12,
                    f_lo=None, f_hi=None) -> Shrunk:
    """Shrink sign-changing brackets onto their sign change, all at once: regula falsi with the Illinois
    modification (superlinear; the end kept twice in a row has its value halved, so both ends close in).
    A bracket is done when it is narrower than ``rtol`` (relative) or at an exact zero; only the
    unfinished brackets are evaluated: ``func(x, rows)`` gets the points and the indices of their
    brackets. ``f_lo``, ``f_hi``: func at the ends when the caller has them (saves two evaluations per
    bracket). Returns the final brackets, their ends' values and the end with the smaller |f|."""
    lo, hi = lo.astype(float).copy(), hi.astype(float).copy()
    every = np.arange(lo.size)
    f_lo = func(lo, every) if f_lo is None else np.asarray(f_lo, dtype=float).copy()
    f_hi = func(hi, every) if f_hi is None else np.asarray(f_hi, dtype=float).copy()
    raw_lo, raw_hi = f_lo.copy(), f_hi.copy()  # func at the current ends (f_lo, f_hi get halved)
    side = np.zeros(lo.shape, dtype=int)  # which end was kept last time (Illinois weight)
    done = (hi - lo <= rtol * np.abs(hi)) | (f_lo == 0) | (f_hi == 0)
    for _ in range(iterations):
        active = np.nonzero(~done)[0]
        if active.size == 0:
            break
        a, b, fa, fb, sd = lo[active], hi[active], f_lo[active], f_hi[active], side[active]
        with np.errstate(invalid="ignore", divide="ignore"):
            mid = np.where(np.isfinite(fa) & np.isfinite(fb) & (fb != fa), b - fb * (b - a) / (fb - fa), 0.5 * (a + b))
        mid = np.where((mid > a) & (mid < b), mid, 0.5 * (a + b))
        fm = func(mid, active)
        left = np.sign(fm) == np.sign(fa)  # the root is in [mid, b]: mid replaces a
        fb = np.where(left & (sd == 1), 0.5 * fb, fb)
        fa = np.where(~left & (sd == -1), 0.5 * fa, fa)
        a, fa = np.where(left, mid, a), np.where(left, fm, fa)
        b, fb = np.where(left, b, mid), np.where(left, fb, fm)
        raw_lo[active] = np.where(left, fm, raw_lo[active])
        raw_hi[active] = np.where(left, raw_hi[active], fm)
        lo[active], hi[active], f_lo[active], f_hi[active] = a, b, fa, fb
        side[active] = np.where(left, 1, -1)
        done[active] = (b - a <= rtol * np.abs(b)) | (fm == 0)
    low = np.abs(f_lo) < np.abs(f_hi)
    return Shrunk(np.where(low, lo, hi), np.where(low, raw_lo, raw_hi), lo, hi, raw_lo, raw_hi)

