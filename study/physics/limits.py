"""The limits of one design point from its stresses: yield, endurance, fatigue damage rate and life.

Pure functions of numpy arrays (broadcasting over a grid), SI units. One call composes
:mod:`study.physics.materials` and :mod:`study.physics.fatigue` with the options a config names
(:data:`LIMIT_INPUTS`, the config's field names), so every method reports the same limits:

- yield utilisation |σ_max|/σ_y of the pipe body's largest normal stress |T0/A_s| + |σ_b|;
- endurance utilisation σ_ar/σ_e of the tool joint's equivalent amplitude: the alternating bending
  stress times the stress concentration factor, corrected for the axial mean stress T0/A_s;
- Miner's damage rate [1/s] and the time of rotation to failure [s] at that amplitude.

A utilisation above 1 is a flag for the charts and the envelope, not a failure of the point.
"""

from __future__ import annotations

from typing import NamedTuple

from study.physics import fatigue, materials

#: The config inputs (names as in the config's fields) that :func:`design_limits` takes as keywords.
LIMIT_INPUTS = ("pipe_grade", "yield_strength", "tensile_strength", "stress_concentration", "sn_curve",
                "mean_stress_correction", "cycles_per_revolution")


class Limits(NamedTuple):
    """Limit outputs of a design point (arrays of the broadcast shape of the inputs)."""

    yield_utilisation: object  # |σ_max|/σ_y [-]
    endurance_utilisation: object  # σ_ar/σ_e [-]
    equivalent_amplitude: object  # σ_ar at the tool joint [Pa]
    damage_rate: object  # Miner's damage per second of rotation [1/s]
    fatigue_life: object  # time of rotation to failure [s]


def design_limits(max_normal_stress, alternating_bending_stress, axial_stress, rotary_speed, *,
                  pipe_grade="E-75", yield_strength=None, tensile_strength=None, stress_concentration=1.0,
                  sn_curve="B1", mean_stress_correction="goodman", cycles_per_revolution=1.0) -> Limits:
    """Yield and endurance utilisation, damage rate and life of the pipe at one or many design points.

    max_normal_stress σ_max [Pa] (pipe body, |T0/A_s| + |σ_b|), alternating_bending_stress σ_a [Pa]
    (half the range over the period, pipe body), axial_stress σ_m = T0/A_s [Pa] (the mean; compression
    earns no credit), rotary_speed Ω [rad/s]. Keywords as the config's fields: pipe_grade (one of
    :data:`study.physics.materials.GRADES`), yield_strength / tensile_strength [Pa] (None: the grade's
    minima), stress_concentration K_t [-] on σ_a, sn_curve (one of
    :data:`study.physics.fatigue.SN_CURVES`), mean_stress_correction (one of
    :data:`study.physics.fatigue.MEAN_STRESS_CORRECTIONS`), cycles_per_revolution [-].
    """
    sigma_y, sigma_u = materials.grade_strengths(pipe_grade, yield_strength, tensile_strength)
    amplitude = fatigue.local_equivalent_amplitude(
        alternating_bending_stress, axial_stress, sigma_u, sigma_y,
        stress_concentration=stress_concentration, correction=mean_stress_correction)
    rate = fatigue.damage_rate(amplitude, rotary_speed, cycles_per_revolution, sn_curve)
    return Limits(
        yield_utilisation=materials.yield_utilisation(max_normal_stress, sigma_y),
        endurance_utilisation=fatigue.endurance_utilisation(amplitude, sn_curve),
        equivalent_amplitude=amplitude,
        damage_rate=rate,
        fatigue_life=fatigue.fatigue_life(rate),
    )


def history_damage(stress, segments=None, at=None, *, pipe_grade="E-75", yield_strength=None, tensile_strength=None,
                   stress_concentration=1.0, sn_curve="B1", mean_stress_correction="goodman",
                   cycles_per_revolution=None):
    """Miner's damage [-] of a fibre's stress history [Pa] by rainflow counting
    (:func:`study.physics.fatigue.history_damage`) with the strengths, stress concentration, S-N curve and
    mean-stress correction a config names (the keywords of :func:`design_limits`); with ``segments`` (each stretch's
    first index) the damage of each stretch, ``at`` the time [s] of each point of the history (default its index).
    ``cycles_per_revolution`` is accepted and not used: the counting finds the cycles."""
    sigma_y, sigma_u = materials.grade_strengths(pipe_grade, yield_strength, tensile_strength)
    return fatigue.history_damage(stress, sigma_u, sigma_y, stress_concentration=stress_concentration,
                                  correction=mean_stress_correction, curve=sn_curve, segments=segments, at=at)
