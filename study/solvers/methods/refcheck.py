"""Does the periodic solution agree with the reference model? (method ``reference-check``; issue 20)

For one design point, the paper's periodic solution (``fast``: span search, Lee's pulse at midspan) and the
reference model (:mod:`study.solvers.methods.reference`: the section in both directions driven by its mass
eccentricity, Hertz contact with friction at the tool joints and body; ``docs/reference_model.md``) are
solved on the same inputs and compared on what a designer takes from them: whether the pipe strikes the
wall at all, the peak contact force, the largest normal stress and the alternating bending stress.

Verdict (tolerance ``check_tolerance``, default 0.02, relative):

- both strike the wall and every ratio periodic/reference is within the tolerance of 1: ``ok``;
- both strike it but some ratio is not: ``disagrees``, naming each with both values;
- one strikes it and the other does not: ``disagrees``, saying which;
- neither does (the periodic solution finds no valid span, the reference no contact): ``no_impact``.

The values are the periodic solution's (as ``fast`` reports them), with the ratios
``reference_*_ratio`` and the reference's ``whirl_class``, ``whirl_frequency_ratio`` and
``contact_fraction``; the reference's own values are in ``extras['reference']``.
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np

from study import solvers
from study.solvers.model.point import DesignPoint
from study.solvers.model.result import PointResult

METHOD = "reference-check"
#: Compared quantities: value name -> (ratio output, what it is).
COMPARED = {
    "peak_contact_force": ("reference_peak_force_ratio", "peak contact force"),
    "max_normal_stress": ("reference_normal_stress_ratio", "largest normal stress"),
    "alternating_bending_stress": ("reference_alternating_stress_ratio", "alternating bending stress"),
}


def verdict(periodic_values: Mapping[str, float] | None, reference_values: Mapping[str, float], touches: bool,
            tolerance: float) -> tuple[str, dict[str, float], list[str]]:
    """(status, ratios, reasons) of the comparison (module docstring). ``periodic_values``: the periodic
    solution's values, None when it has none; ``touches``: whether the reference model touches the wall."""
    if periodic_values is None:
        if not touches:
            return "no_impact", {}, ["neither strikes the wall: the periodic solution has no valid span and the "
                                     "reference model does not touch"]
        return "disagrees", {}, [f"the reference model touches the wall (peak force "
                                 f"{reference_values['peak_contact_force']:.4g} N) where the periodic solution "
                                 "has no valid span"]
    if not touches:
        return "disagrees", {}, [f"the periodic solution strikes the wall (peak force "
                                 f"{periodic_values['peak_contact_force']:.4g} N) where the reference model does "
                                 "not touch it"]
    ratios, reasons = {}, []
    for name, (ratio_name, what) in COMPARED.items():
        mine, theirs = periodic_values.get(name, np.nan), reference_values.get(name, np.nan)
        ratio = float(mine / theirs) if theirs else float("nan")
        ratios[ratio_name] = ratio
        if not abs(ratio - 1.0) <= tolerance:
            reasons.append(f"{what}: periodic {mine:.4g}, reference {theirs:.4g} (ratio {ratio:.4g})")
    return ("disagrees" if reasons else "ok"), ratios, reasons


def solve(inputs: Mapping[str, Any]) -> PointResult:
    """The reference check at a point given by its SI inputs (:func:`run` of its :class:`DesignPoint`)."""
    return run(DesignPoint.from_inputs(inputs))


def run(point: DesignPoint) -> PointResult:
    """The ``reference-check`` method (module docstring): ``fast`` and ``reference`` at the same point, each through
    the registry (:func:`study.solvers.method`)."""
    result = solvers.method("fast")(point)
    result.method = METHOD
    ref = solvers.method("reference")(point)
    result.extras["reference"] = dict(status=ref.status, message=ref.message, **ref.values)
    if ref.status != "ok":
        result.status = ref.status
        result.message = f"the reference model gave no answer: {ref.message}"
        return result
    for name in ("whirl_class", "regime", "whirl_frequency_ratio", "contact_fraction"):
        result.values[name] = ref.values[name]
    solved = all(name in result.values for name in COMPARED)  # a solution, flagged or not
    periodic_values = result.values if solved else None
    if not solved and result.status != "no_span":
        result.message = f"no periodic solution to compare: {result.message}"
        return result
    tolerance = float(point.check.check_tolerance)
    touches = ref.values.get("contact_fraction", 0.0) > 0 or ref.values.get("peak_contact_force", 0.0) > 0
    status, ratios, reasons = verdict(periodic_values, ref.values, touches, tolerance)
    result.values.update(ratios)
    result.status = status
    whirl = ref.extras.get("whirl", "no_contact")
    if status == "ok":
        result.message = f"the periodic solution agrees with the reference model ({whirl}) within {tolerance:g}"
    else:
        result.message = f"reference model: {whirl}; " + "; ".join(reasons)
    return result
