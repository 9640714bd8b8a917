"""The ``fast`` periodic method: closed-form periodic modal response with a quasi-static correction.

No time series: each mode's steady response to the periodic pulse train is summed in closed form
(:func:`study.physics.beam.modal_periodic_response`), and the quasi-static split makes moment and shear
converge in few modes (MODEL.md §9). The span is found by the pole-bracketed search of
:mod:`study.solvers.periodic`; the smallest span that satisfies the constraints is reported with its
impact and stresses (MODEL.md §5).
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np

from study.physics import beam, section
from study.solvers import periodic, series
from study.solvers.result import PointResult


def stresses(scene: periodic.Scene, impact: periodic.Impact, inputs: Mapping[str, Any],
             options: periodic.Options) -> dict[str, float]:
    """Deflection and stress maxima over the span and the period (MODEL.md §5, paper eq. 37–38) from
    the closed-form fields with the quasi-static correction (see :func:`periodic.stresses_from_fields`)."""
    p = scene.props
    x = periodic.space_grid(impact.span_length, impact.contact_half_length, options)
    t = periodic.time_grid(scene, impact.contact_duration, options)
    args = (impact.span_length, p["bending_stiffness"], p["effective_tension"], p["mass_per_length"],
            -impact.impulse, impact.contact_duration, scene.period, scene.pattern,
            impact.contact_half_length, options.load_shape, options.modes)
    return periodic.stresses_from_fields(scene, inputs, x, t, beam.deflection(x, t, *args),
                                         beam.bending_moment(x, t, *args), beam.shear_force(x, t, *args))


def truncation_bound(scene: periodic.Scene, impact: periodic.Impact, inputs: Mapping[str, Any],
                     options: periodic.Options, reach: int = 8) -> float:
    """Upper bound [Pa] on the bending stress carried by the modes left out, n in (N, reach·N].

    Each left-out mode adds at most (r_o/I) EI k_n² |a_n(t) − a_n,qs(t)| to the stress anywhere on the
    span (|sin k_n x| ≤ 1), where a_n − a_n,qs is its dynamic remainder after the quasi-static split
    (MODEL.md §9); its maximum over the period is taken on the solver's time grid. Summing the modes
    up to reach·N catches a near-resonant mode just above the truncation, which a comparison with
    fewer modes cannot see; the modes beyond fall off like n⁻⁴ once ω_n T_L ≫ 1.
    """
    p = scene.props
    r_o, r_i = inputs["outer_diameter"] / 2.0, inputs["inner_diameter"] / 2.0
    inertia = float(section.second_moment_of_area(r_o, r_i))
    n = periodic.odd_modes(reach * options.modes)
    n = n[n > options.modes]
    if n.size == 0:
        return 0.0
    t = periodic.time_grid(scene, impact.contact_duration, options)
    omega = periodic.natural_frequencies(scene, impact.span_length, n)
    g = beam.modal_load_factors(n, impact.span_length, impact.contact_half_length, options.load_shape)
    q = beam.modal_periodic_response(t[:, None], omega, impact.contact_duration, scene.period,
                                     scene.pattern).displacement
    h = beam.pulse_train(t[:, None], impact.contact_duration, scene.period, scene.pattern)
    remainder = np.nanmax(np.abs(q - h / omega**2), axis=0)
    k_sq = (n * np.pi / impact.span_length) ** 2
    amplitude = abs(impact.impulse) * np.abs(g) / (0.5 * p["mass_per_length"] * impact.span_length) * remainder
    return float(r_o / inertia * p["bending_stiffness"] * np.sum(k_sq * amplitude))


def finish(scene: periodic.Scene, chosen: periodic.Impact, inputs: Mapping[str, Any],
           options: periodic.Options, result: PointResult) -> None:
    """The fast method's part of the pipeline: stresses, the truncation bound as error estimate, and the
    paper's term-ratio check."""
    values = stresses(scene, chosen, inputs, options)
    result.values.update(values)
    result.error_estimate = truncation_bound(scene, chosen, inputs, options) / values["max_normal_stress"]
    series.add_term_ratios(scene, chosen, inputs, options, result)


def solve(inputs: Mapping[str, Any]) -> PointResult:
    """Find the span and solve the periodic impact of one design point (see module docstring)."""
    return periodic.design_point(inputs, "fast", finish)
