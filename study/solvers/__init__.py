"""Methods for one design point, behind one interface.

``METHODS`` is the registry (as scipy.integrate's solver table): name -> (solve function, one-line
description), built on first use from :data:`METHOD_MODULES` and the descriptions declared with the options
(:mod:`study.solvers.model.options`). Every solve function takes one typed
:class:`~study.solvers.model.point.DesignPoint` (built once, by :func:`solve_point`) and returns a
:class:`~study.solvers.model.result.PointResult` whose status and message say what happened; none raises
for a numerical or physical failure of the point. Each method's module keeps ``solve(inputs)``, which builds the point
from SI inputs and calls the typed ``run(point)``, for scripts and tests that hold only the inputs.
"""

from __future__ import annotations

import time
import traceback
from typing import Any, Mapping

import importlib

from study.solvers.model.options import METHOD_DESCRIPTIONS
from study.solvers.model.result import OUTPUTS, STATUS, STATUS_CODES, PointResult

#: Methods whose results get the lift-off eccentricity (:func:`study.solvers.methods.sliding.add_lift_off`): those whose
#: scene is the reference model's and that may answer a pipe lying on the wall (the free whirl answers only where
#: nothing lies there). Named here, so that solving another method imports no reference model.
LIFT_OFF_METHODS = ("sliding", "reference")

#: The module of each method under :mod:`study.solvers.methods` (its ``run`` is the method); imported on first use, so
#: that importing the package, its options or its result type (as the config does) loads no solver.
METHOD_MODULES = {"core": "core", "fast": "periodic.fast", "series": "periodic.series", "auto": "auto",
                  "time-domain": "timedomain", "crosscheck": "crosscheck", "reference": "reference",
                  "reference-check": "refcheck", "free-whirl": "freewhirl", "sliding": "sliding", "sdof": "sdof",
                  "damped": "periodic.damped"}


#: Methods whose solve function is not their module's ``run``: name -> (module, function).
METHOD_FUNCTIONS = {"periodic": ("auto", "run_periodic")}


def _registry() -> dict:
    table = {name: (module, "run") for name, module in METHOD_MODULES.items()} | METHOD_FUNCTIONS
    return {name: (getattr(importlib.import_module(f"study.solvers.methods.{module}"), function),
                   METHOD_DESCRIPTIONS[name]) for name, (module, function) in table.items()}


def __getattr__(name: str):
    if name == "METHODS":  # the registry, built once on first access (PEP 562)
        globals()["METHODS"] = methods = _registry()
        return methods
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = ["METHODS", "OUTPUTS", "STATUS", "STATUS_CODES", "PointResult", "method", "solve_point"]


def method(name: str):
    """The typed solve function of method ``name`` (:data:`METHODS`): how a method that runs another (the checks)
    reaches it, through the registry rather than by import."""
    return (globals().get("METHODS") or __getattr__("METHODS"))[name][0]


def solve_point(inputs: Mapping[str, Any], method: str | None = None) -> PointResult:
    """Solve one design point with ``method`` (default: ``inputs['solver_method']``, config solver.method).

    Every result passes :func:`study.solvers.model.gate.admit`, the one place that decides whether an answer
    the method calls ``ok`` is physical, and gets the design limits of its stresses
    (:func:`study.solvers.model.utilisation.add_limits`: yield and endurance utilisation, fatigue life), both given the
    point's typed :class:`~study.solvers.model.point.DesignPoint` — built here from ``inputs`` once and passed to the
    method, the limits and the gate; the methods of the reference model's scene (:data:`LIFT_OFF_METHODS`) get the
    lift-off eccentricity (:func:`study.solvers.methods.sliding.add_lift_off`). An unexpected exception inside a method
    (or a bad value in building the point) is caught and returned as status ``failed`` with its message, so that one bad
    point never sinks a sweep. The result's ``wall_time`` is stamped here, once, for every method.
    """
    from study.solvers.model import gate, utilisation
    from study.solvers.model.point import DesignPoint

    methods = globals().get("METHODS") or __getattr__("METHODS")
    name = method or inputs.get("solver_method") or "core"
    if name not in methods:
        raise ValueError(f"method = {name!r}; allowed: {', '.join(methods)}")
    start = time.perf_counter()
    try:
        point = DesignPoint.from_inputs(inputs)
        result = methods[name][0](point)
        if result.method in LIFT_OFF_METHODS:  # the lift-off eccentricity of the reference model's scene
            from study.solvers.methods import sliding

            sliding.add_lift_off(result, point.inputs)
        if result.status == "ok" or "max_normal_stress" in result.values:  # what the limits and the gate judge
            result = gate.admit(utilisation.add_limits(result, point.scene, point.limits), point.scene,
                                point.tolerances)
    except Exception as exc:  # noqa: BLE001 - recorded as a status, by design
        last = traceback.extract_tb(exc.__traceback__)[-1]
        where = f"{last.filename.rsplit('/', 1)[-1]}:{last.lineno}"
        result = PointResult(method=name, status="failed", message=f"{type(exc).__name__}: {exc} (at {where})")
    result.wall_time = time.perf_counter() - start  # the one stamp: the method, its limits and the gate
    return result
