"""The ``auto`` method: per design point, the cheapest model of the hierarchy that serves it (docs/model.md §9).

The hierarchy is module data, :data:`LADDER`, cheapest first: each rung names a method and says which
failures of the rungs below it can mend (:data:`MENDS`). A point is solved by the first rung; its result
passes the gate every result passes (:func:`study.solvers.gate.admit`); if it is not ``ok`` and a higher
rung can mend that failure, the point goes up. What a point ends with is the first ``ok`` result, or —
when nothing served — the most informative failure (the last rung's that was tried), with the ladder it
climbed in its message and ``extras["methods_tried"]`` (method → status and error estimate). A status
that no rung can mend (buckling, missing inputs) is a property of the point, returned at once.

- ``fast``: the periodic solution (closed form in time, quasi-static correction).
- ``series``: the paper's double series on the same span; it mends only an error estimate above
  ``solver.tolerance`` where the span itself held when the modes doubled (its time series converges by
  doubling the harmonics; the span search is the same as ``fast``'s).
"""

from __future__ import annotations

import time
from typing import Any, Callable, Mapping

from study.solvers import fast, gate, series
from study.solvers.options import DEFAULT_TOLERANCE
from study.solvers.result import PointResult

Solve = Callable[[Mapping[str, Any]], PointResult]


def _error_only(result: PointResult, inputs: Mapping[str, Any]) -> bool:
    """The span held with doubled modes and only the error estimate is above the tolerance."""
    tolerance = float(inputs.get("tolerance") or DEFAULT_TOLERANCE)
    return (result.status == "not_converged" and result.extras.get("span_converged", False)
            and result.error_estimate is not None and result.error_estimate > tolerance)


def _series_inputs(inputs: Mapping[str, Any]) -> dict[str, Any]:
    """The series doubles its harmonics until the study's tolerance."""
    tolerance = float(inputs.get("tolerance") or DEFAULT_TOLERANCE)
    return {**inputs, "series_tolerance": inputs.get("series_tolerance") or tolerance}


#: The hierarchy, cheapest first: method name -> (solve, how its inputs are made from the point's).
LADDER: dict[str, tuple[Solve, Callable[[Mapping[str, Any]], Mapping[str, Any]]]] = {
    "fast": (fast.solve, dict),
    "series": (series.solve, _series_inputs),
}
#: For each rung above the first: which results of the rungs below it the rung can mend.
MENDS: dict[str, Callable[[PointResult, Mapping[str, Any]], bool]] = {
    "series": _error_only,
}


def solve(inputs: Mapping[str, Any]) -> PointResult:
    """Climb :data:`LADDER` until a rung serves the point (see the module docstring)."""
    start = time.perf_counter()
    tried: list[PointResult] = []
    for name, (method, prepare) in LADDER.items():
        if tried and not MENDS[name](tried[-1], inputs):
            continue
        tried.append(gate.admit(method(prepare(inputs)), inputs))
        if tried[-1].status == "ok":
            break
    result = tried[-1]
    why = (f"{result.method} answered" if result.status == "ok" else
           f"no model served ({result.method}'s {result.status} is what is known)")
    if len(tried) > 1:
        why += " after " + ", ".join(f"{r.method}: {r.status}" for r in tried[:-1])
    result.message = f"auto: {why}; {result.message}"
    result.extras["methods_tried"] = {r.method: {"status": r.status, "error_estimate": r.error_estimate}
                                      for r in tried}
    result.wall_time = time.perf_counter() - start
    return result
