"""Roots of many sign-changing brackets at once (vectorised regula falsi), for the physics and solvers.

Pure numerics on numpy arrays, no I/O: the span search (:mod:`study.solvers.periodic`) and the
inversion of the Hertz contact angle (:mod:`study.physics.hertz`) each solve thousands of scalar
equations whose brackets are known; one array call per step replaces a Python loop of scalar solvers.
"""

from __future__ import annotations

import numpy as np


def bracketed_roots(func, lo: np.ndarray, hi: np.ndarray, iterations: int = 60, rtol: float = 1e-12) -> np.ndarray:
    """Roots of sign-changing brackets, all at once: regula falsi with the Illinois modification
    (superlinear; the end kept twice in a row has its value halved, so both ends close in). A bracket
    is done when it is narrower than ``rtol`` (relative) or at an exact zero; only the unfinished
    brackets are evaluated: ``func(x, rows)`` gets the points and the indices of their brackets.
    Returns the end with the smaller |f|."""
    lo, hi = lo.astype(float).copy(), hi.astype(float).copy()
    every = np.arange(lo.size)
    f_lo, f_hi = func(lo, every), func(hi, every)
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
        lo[active], hi[active], f_lo[active], f_hi[active] = a, b, fa, fb
        side[active] = np.where(left, 1, -1)
        done[active] = (b - a <= rtol * np.abs(b)) | (fm == 0)
    return np.where(np.abs(f_lo) < np.abs(f_hi), lo, hi)
