"""The ``fast`` periodic method: closed-form periodic modal response with a quasi-static correction.

No time series: each mode's steady response to the periodic pulse train is summed in closed form
(:func:`study.physics.beam.modal_periodic_response`), and the quasi-static split makes moment and shear
converge in few modes (docs/model.md §9). The span is found by the pole-bracketed search of
:mod:`study.solvers.methods.periodic`; the smallest span that satisfies the constraints is reported with its
impact and stresses (docs/model.md §5).
"""

from __future__ import annotations

from typing import Any, Mapping


from study.solvers.kernels import impact as impact_model
from study.solvers.methods.periodic import series
from study.solvers.methods import periodic
from study.solvers.model.point import DesignPoint
from study.solvers.model.result import PointResult
from study.solvers.model.scene import Scene


def stresses(scene: Scene, impact: impact_model.Impact, inputs: Mapping[str, Any],
             options: periodic.Options) -> dict[str, float]:
    """Deflection and stress maxima over the span and the period (docs/model.md §5, paper eq. 37–38) from
    the closed-form fields with the quasi-static correction, located (:func:`series.stresses` with no
    harmonics)."""
    return series.stresses(scene, impact, inputs, options)


def finish(scene: Scene, chosen: impact_model.Impact, inputs: Mapping[str, Any],
           options: periodic.Options, result: PointResult) -> None:
    """The fast method's part of the pipeline: stresses, the truncation bound as error estimate, and the
    paper's term-ratio check."""
    values = stresses(scene, chosen, inputs, options)
    result.values.update(values)
    result.error_estimate = (periodic.truncation_bound(scene, chosen, options) / values["max_normal_stress"]
                             + values["location_residual"])
    series.add_term_ratios(scene, chosen, inputs, options, result)


def solve(inputs: Mapping[str, Any]) -> PointResult:
    """The fast method at a point given by its SI inputs (:func:`run` of its :class:`DesignPoint`)."""
    return run(DesignPoint.from_inputs(inputs))


def run(point: DesignPoint) -> PointResult:
    """Find the span and solve the periodic impact of one design point (see module docstring)."""
    return periodic.design_point(point, "fast", finish)
