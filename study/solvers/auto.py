"""The ``auto`` method: per design point, the cheapest periodic method whose error estimate meets the
study's tolerance (MODEL.md §9).

The periodic methods are tried in order of cost - ``fast`` (closed form in time, error estimate a bound
on the modes left out), then ``series`` (the paper's double series, doubling its harmonics until the
tolerance) - and the first result that is ``ok`` with ``error_estimate <= tolerance`` is returned. A
status other than ``ok`` (no valid span, buckling, ...) is a property of the design point, not of the
method, and is returned at once from the cheapest method. When no method meets the tolerance, the
result with the smallest estimate is returned with status ``not_converged``.
"""

from __future__ import annotations

import time
from typing import Any, Callable, Mapping

from study.solvers import fast, series
from study.solvers.gate import DEFAULT_TOLERANCE
from study.solvers.result import PointResult

#: The candidates, cheapest first: name -> solve function.
CANDIDATES: dict[str, Callable[[Mapping[str, Any]], PointResult]] = {"fast": fast.solve, "series": series.solve}


def solve(inputs: Mapping[str, Any]) -> PointResult:
    """Solve with the cheapest candidate that meets ``inputs['tolerance']`` (relative, max normal stress)."""
    start = time.perf_counter()
    tolerance = float(inputs.get("tolerance") or DEFAULT_TOLERANCE)
    tried = []
    for name, method in CANDIDATES.items():
        trial = {**inputs, "series_tolerance": inputs.get("series_tolerance") or tolerance} if name == "series" \
            else inputs
        result = method(trial)
        tried.append(result)
        if result.status != "ok" or (result.error_estimate is not None and result.error_estimate <= tolerance):
            break
    else:
        result = min(tried, key=lambda r: r.error_estimate if r.error_estimate is not None else float("inf"))
        result.status = "not_converged"
        result.message += f"; no method met the tolerance {tolerance:.2g}"
    result.message = (f"auto chose {result.method} (tried {', '.join(r.method for r in tried)}); " + result.message)
    result.extras["methods_tried"] = {r.method: r.error_estimate for r in tried}
    result.wall_time = time.perf_counter() - start
    return result
