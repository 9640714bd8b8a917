"""The design limits of one solved point, as data (docs/model.md §5): how near the pipe is to yield and to its
endurance limit, Miner's damage rate and the hours of rotation to failure.

Added to every result that carries the stresses (:func:`study.solvers.solve_point`); a utilisation above 1 is a
flag for the charts and the operating envelope, never a status — the point is solved, the pipe is over its
limit. Composed from :func:`study.physics.limits.design_limits` with the config's grade, strengths, stress
concentration, S-N curve and mean-stress correction (:class:`study.solvers.model.options.LimitOptions`).
"""

from __future__ import annotations

import numpy as np

from study.physics import fatigue, section
from study.physics.limits import design_limits
from study.solvers.model.options import LimitOptions
from study.solvers.model.result import PointResult
from study.solvers.model.scene import Scene

#: What :func:`add_limits` adds, keyed as :data:`study.solvers.model.result.OUTPUTS`.
LIMIT_OUTPUTS = ("yield_utilisation", "endurance_utilisation", "equivalent_alternating_stress", "damage_rate",
                 "fatigue_life")


def add_limits(result: PointResult, scene: Scene, limits: LimitOptions) -> PointResult:
    """``result`` with :data:`LIMIT_OUTPUTS` in its values where it has the max normal and alternating bending
    stresses (unchanged otherwise), from the point's ``scene`` (its radii, axial tension and rotary speed) and its
    ``limits`` (the grade, strengths, S-N curve ...). Where the method counted the damage itself (a finite
    ``damage_rate`` in its values: the reference model's rainflow count of the worst fibre's stress history,
    docs/model.md §5.1) that rate and its fatigue life are kept; elsewhere the damage is one cycle of the alternating
    stress per revolution (``cycles_per_revolution``)."""
    values = result.values
    normal, alternating = values.get("max_normal_stress"), values.get("alternating_bending_stress")
    if normal is None or alternating is None or not (np.isfinite(normal) and np.isfinite(alternating)):
        return result
    area = values.get("steel_area") or float(section.steel_area(scene.outer_radius, scene.inner_radius))
    counted = values.get("damage_rate")
    counted = float(counted) if counted is not None and np.isfinite(counted) else None
    found = design_limits(normal, alternating, scene.axial_tension / area, scene.rotary_speed, **limits.keywords())
    rate = float(found.damage_rate) if counted is None else counted
    values.update(yield_utilisation=float(found.yield_utilisation),
                  endurance_utilisation=float(found.endurance_utilisation),
                  equivalent_alternating_stress=float(found.equivalent_amplitude),
                  damage_rate=rate, fatigue_life=float(fatigue.fatigue_life(rate)))
    return result
