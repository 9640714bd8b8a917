"""Work-precision data of the periodic methods (``study bench``; docs/model.md §9, docs/performance.md): each method
and resolution timed at a fixed span and impact against a converged double series.
"""

from __future__ import annotations

import time
from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np

from study.physics import fourier
from study.solvers.kernels import extremes
from study.solvers.kernels import impact as impact_model
from study.solvers.methods.periodic import series
from study.solvers.methods import periodic
from study.solvers.model.scene import Scene


def convergence_table(scene: Scene, impact: impact_model.Impact, inputs: Mapping[str, Any],
                      resolutions: Iterable[tuple[str, Any]], reference: tuple[int, int] = (961, 25_600),
                      options: periodic.Options | None = None) -> list[dict[str, Any]]:
    """Work-precision rows of each method and resolution at a fixed span and impact (docs/model.md §9).

    resolutions: ("fast", N) or ("series", (N, M)) pairs. reference: (N, M) of the converged double
    series every row is compared with (default: converged to ~1e-8 in max normal stress on the test
    case). options: grids and load shape (default ``periodic.Options()``); only ``modes`` varies.
    Each row: method, modes, harmonics (None for fast), terms (number of (n, m) terms, N_odd for
    fast), wall_time [s] of one stress evaluation (fields + maxima; median of at least five calls and
    0.3 s), and the relative errors against
    the reference: error (max normal stress), deflection_error (max |Δy| over the grid / max |y|),
    max_deflection_error, shear_error (max shear stress). Rows in the order given.
    """
    options = options or periodic.Options()

    def evaluate(n, m, repeat=5, budget=0.3):
        opts = periodic.Options(**{**options.__dict__, "modes": int(n)})
        x, t = series.stress_grid(scene, impact, opts)
        walls = []
        # the median of at least ``repeat`` calls filling ``budget`` seconds: the first call may load
        # compiled code, and a sub-millisecond call needs many to outlast the machine's jitter
        while len(walls) < repeat or sum(walls) < budget:
            start = time.perf_counter()
            f = series.fields(scene, impact, opts, m, series.STRESS_KINDS, x, t)
            values = extremes.stresses_from_fields(scene, x, t, f["deflection"], f["moment"], f["shear"])
            walls.append(time.perf_counter() - start)
        return values, f["deflection"], float(np.median(walls))

    ref, y_ref, _ = evaluate(*reference, repeat=1, budget=0.0)
    rows = []
    for method, res in resolutions:
        if method == "fast":
            n, m = int(res), None
        elif method == "series":
            n, m = (int(v) for v in res)
        else:
            raise ValueError(f"method = {method!r}; allowed: fast, series")
        values, y, wall = evaluate(n, m)
        n_odd = (n + 1) // 2
        m_kept = None if m is None else fourier.harmonic_numbers(m, scene.pattern).size
        rows.append({
            "method": method, "modes": n, "harmonics": m, "terms": n_odd if m is None else n_odd * m_kept,
            "wall_time": wall,
            "error": abs(values["max_normal_stress"] / ref["max_normal_stress"] - 1.0),
            "deflection_error": float(np.nanmax(np.abs(y - y_ref)) / np.nanmax(np.abs(y_ref))),
            "max_deflection_error": abs(values["max_deflection"] / ref["max_deflection"] - 1.0),
            "shear_error": abs(values["max_shear_stress"] / ref["max_shear_stress"] - 1.0),
        })
    return rows
