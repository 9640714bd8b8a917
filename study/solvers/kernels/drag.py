"""The mud's drag of the fast modes in the reference model's integrator, as its linear equivalent
(``reference_drag_modes``, ``reference_drag_rest = "linear"``; docs/reference_model.md §4): a kernel
:func:`whirl_kernel.rhs` inlines (``inline="always"``: nothing compiled apart is linked into advance,
whirl_kernel.FASTMATH)."""

from __future__ import annotations

import numba
import numpy as np


@numba.njit(cache=True, nogil=True, inline="always")
def drag_linearised(z, out, uy, uz, wts, D, lin, inv_m, Nq, N):
    """The drag of the modes n ≥ Nq (``reference_drag_modes``, docs/reference_model.md §4) as its linear equivalent
    about the first Nq modes' velocity field u̇_q (uy, uz [m/s] at the drag points, weights ``wts`` [m]), subtracted
    from their accelerations in ``out``; returns its power [W]. D |u̇| u̇ is to first order in u̇_r = u̇ − u̇_q
    D |u̇_q| u̇_q + J u̇_r, J = D (|u̇_q| I + u̇_q u̇_qᵀ/|u̇_q|); mode n's part ∫ ψ_n J ψ_n dx q̇_n with J at its
    span mean, ∫ ψ_n² J dx ≈ (∫ ψ_n² dx / L) ∫ J dx, its coupling to the other modes left out. D [kg/m²] (the drag
    per length over the speed squared), ``lin`` (N,) ∫ ψ_n² dx / L [-], ``inv_m`` 1/modal mass [1/kg]."""
    jyy = jyz = jzz = 0.0
    for g in range(wts.size):
        sp = np.sqrt(uy[g] * uy[g] + uz[g] * uz[g])
        if sp > 0.0:
            jyy += wts[g] * (sp + uy[g] * uy[g] / sp)
            jyz += wts[g] * (uy[g] * uz[g] / sp)
            jzz += wts[g] * (sp + uz[g] * uz[g] / sp)
    power = 0.0
    for n in range(Nq, N):
        vy = z[2 * N + n]
        vz = z[3 * N + n]
        fy = D * lin[n] * (jyy * vy + jyz * vz)
        fz = D * lin[n] * (jyz * vy + jzz * vz)
        power += fy * vy + fz * vz
        out[2 * N + n] -= fy * inv_m
        out[3 * N + n] -= fz * inv_m
    return power
