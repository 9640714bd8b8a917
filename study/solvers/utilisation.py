"""The design limits of one solved point, as data (docs/model.md §5): how near the pipe is to yield and to its
endurance limit, Miner's damage rate and the hours of rotation to failure.

Added to every result that carries the stresses (:func:`study.solvers.solve_point`); a utilisation above 1 is a
flag for the charts and the operating envelope, never a status — the point is solved, the pipe is over its
limit. Composed from :func:`study.physics.limits.design_limits` with the config's grade, strengths, stress
concentration, S-N curve and mean-stress correction (:data:`study.physics.limits.LIMIT_INPUTS`).
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np

from study.physics import section
from study.physics.limits import LIMIT_INPUTS, design_limits
from study.solvers.result import PointResult

#: What :func:`add_limits` adds, keyed as :data:`study.solvers.result.OUTPUTS`.
LIMIT_OUTPUTS = ("yield_utilisation", "endurance_utilisation", "equivalent_alternating_stress", "damage_rate",
                 "fatigue_life")


def add_limits(result: PointResult, inputs: Mapping[str, Any]) -> PointResult:
    """``result`` with :data:`LIMIT_OUTPUTS` in its values where it has the max normal and alternating bending
    stresses (unchanged otherwise)."""
    values = result.values
    normal, alternating = values.get("max_normal_stress"), values.get("alternating_bending_stress")
    if normal is None or alternating is None or not (np.isfinite(normal) and np.isfinite(alternating)):
        return result
    area = values.get("steel_area") or float(section.steel_area(inputs["outer_diameter"] / 2.0,
                                                                inputs["inner_diameter"] / 2.0))
    options = {name: inputs[name] for name in LIMIT_INPUTS if inputs.get(name) is not None}
    limits = design_limits(normal, alternating, inputs["axial_tension"] / area, inputs["rotary_speed"], **options)
    values.update(yield_utilisation=float(limits.yield_utilisation),
                  endurance_utilisation=float(limits.endurance_utilisation),
                  equivalent_alternating_stress=float(limits.equivalent_amplitude),
                  damage_rate=float(limits.damage_rate), fatigue_life=float(limits.fatigue_life))
    return result
