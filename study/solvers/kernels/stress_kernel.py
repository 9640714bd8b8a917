"""Compiled extremes of the reference model's recorded stress fields (docs/reference_model.md §3).

One pass over the recorded moments and deflections of a stretch (T times × X stations) finds what
:func:`study.solvers.methods.reference.stresses` reports: the largest bending moment |M| = √(M_y² + M_z²) and
where, the largest deflection |u|, the largest shear force |ΔM|/Δx between neighbouring stations and
where, and the alternating moment of the turning pipe's fibres — half the range over the stretch of
M_y cos(Ωt + ψ) + M_z sin(Ωt + ψ), the largest over the fibres ψ, per station. numpy took about 9 ms a
window of 2 000 rows for these in temporaries of the window's size; here none is made.
"""

from __future__ import annotations

import numba
import numpy as np


@numba.njit(cache=True, nogil=True)
def window_extremes(my, mz, uy, uz, x, cos_turn, sin_turn, cos_fibre, sin_fibre):
    """Extremes over the rows (times) of the moments ``my``, ``mz`` [N m] and deflections ``uy``, ``uz`` [m]
    (T, X) on the stations ``x`` (X,) [m], the pipe turned by Ωt (``cos_turn``, ``sin_turn``, (T,)) and its
    fibres at ψ (``cos_fibre``, ``sin_fibre``, (F,)).

    Returns (largest |M| [N m], its row, its station, largest |u| [m], largest |ΔM|/Δx [N], its row, the
    first station of its interval, the fibres' half ranges (X,) [N m]). The fibre ψ's moment is
    cos ψ (M_y cos Ωt + M_z sin Ωt) + sin ψ (M_z cos Ωt − M_y sin Ωt). A NaN anywhere makes every
    extreme NaN (its rows and stations −1), as numpy's max would.
    """
    T, X = my.shape
    F = cos_fibre.size
    hi = np.full((X, F), -np.inf)
    lo = np.full((X, F), np.inf)
    m_best, m_row, m_col = -1.0, -1, -1
    u_best = -1.0
    v_best, v_row, v_col = -1.0, -1, -1
    inv_dx = np.empty(max(X - 1, 0))
    for j in range(X - 1):
        inv_dx[j] = 1.0 / (x[j + 1] - x[j])
    finite = True
    for r in range(T):
        ct, st = cos_turn[r], sin_turn[r]
        for j in range(X):
            a, b = my[r, j], mz[r, j]
            m2 = a * a + b * b
            if not (m2 == m2):
                finite = False
            if m2 > m_best:
                m_best, m_row, m_col = m2, r, j
            u2 = uy[r, j] * uy[r, j] + uz[r, j] * uz[r, j]
            if not (u2 == u2):
                finite = False
            if u2 > u_best:
                u_best = u2
            if j + 1 < X:
                dy = (my[r, j + 1] - a) * inv_dx[j]
                dz = (mz[r, j + 1] - b) * inv_dx[j]
                v2 = dy * dy + dz * dz
                if v2 > v_best:
                    v_best, v_row, v_col = v2, r, j
            turned = a * ct + b * st  # the moment in the pipe's own frame
            across = b * ct - a * st
            for f in range(F):
                v = turned * cos_fibre[f] + across * sin_fibre[f]
                if v > hi[j, f]:
                    hi[j, f] = v
                if v < lo[j, f]:
                    lo[j, f] = v
    half = np.zeros(X)
    for j in range(X):
        for f in range(F):
            h = 0.5 * (hi[j, f] - lo[j, f])
            if h > half[j]:
                half[j] = h
    if not finite or T == 0:
        half[:] = np.nan
        return np.nan, -1, -1, np.nan, np.nan, -1, -1, half
    return (np.sqrt(m_best), m_row, m_col, np.sqrt(u_best), np.sqrt(v_best) if X > 1 else np.nan, v_row, v_col,
            half)
