"""Methods for one design point, behind one interface.

``METHODS`` is the registry (as scipy.integrate's solver table): name -> (solve function, one-line
description). Every solve function takes the SI inputs of one point and returns a
:class:`~study.solvers.result.PointResult` whose status and message say what happened; none raises
for a numerical or physical failure of the point.
"""

from __future__ import annotations

import time
import traceback
from typing import Any, Mapping

from study.solvers import auto, core, crosscheck, fast, reference, refcheck, sdof, series, timedomain
from study.solvers.result import OUTPUTS, STATUS, STATUS_CODES, PointResult

METHODS = {
    "core": (core.solve, "physics core: section, mud, tension, and the Hertz/Lee impact at a given span"),
    "fast": (fast.solve, "periodic impact solution: span search, closed-form modal response with a "
             "quasi-static correction, stresses"),
    "series": (series.solve, "the paper's double Fourier series (modes x harmonics) with the same span search "
               "as fast: the reproduction, and the slow reference"),
    "auto": (auto.solve, "the cheapest periodic method (fast, then series) whose error estimate meets "
             "solver.tolerance"),
    "time-domain": (timedomain.solve, "modal span integrated through Hertz contact with both walls (explicit "
                    "Verlet or implicit LSODA) until periodic: the check on the periodic assumption"),
    "crosscheck": (crosscheck.solve, "the fast periodic solution replayed through one revolution of real Hertz "
                   "contact in the time domain: agrees within solver.check_tolerance, or flagged with the reasons"),
    "reference": (reference.solve, "the reference model: the pipe section in both lateral directions, driven by its "
                  "mass eccentricity, Hertz wall contact with friction at tool joints and body, mud drag; whirl, "
                  "contact and stresses after the transient"),
    "reference-check": (refcheck.solve, "the periodic solution (fast) against the reference model on the same point: "
                        "contact or not, peak force, max normal and alternating stress within solver.check_tolerance"),
    "sdof": (sdof.solve, "one-degree-of-freedom screen: first-mode impact oscillator between the walls, "
             "exact period-1 orbit and Floquet stability at a given span"),
}

__all__ = ["METHODS", "OUTPUTS", "STATUS", "STATUS_CODES", "PointResult", "solve_point"]


def solve_point(inputs: Mapping[str, Any], method: str | None = None) -> PointResult:
    """Solve one design point with ``method`` (default: ``inputs['solver_method']``, config solver.method).

    An unexpected exception inside a method is caught and returned as status ``failed`` with its
    message, so that one bad point never sinks a sweep.
    """
    name = method or inputs.get("solver_method") or "core"
    if name not in METHODS:
        raise ValueError(f"method = {name!r}; allowed: {', '.join(METHODS)}")
    start = time.perf_counter()
    try:
        return METHODS[name][0](inputs)
    except Exception as exc:  # noqa: BLE001 - recorded as a status, by design
        last = traceback.extract_tb(exc.__traceback__)[-1]
        return PointResult(method=name, status="failed",
                           message=f"{type(exc).__name__}: {exc} (at {last.filename.rsplit('/', 1)[-1]}:{last.lineno})",
                           wall_time=time.perf_counter() - start)
