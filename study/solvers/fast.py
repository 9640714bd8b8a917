"""The ``fast`` periodic method: closed-form periodic modal response with a quasi-static correction.

No time series: each mode's steady response to the periodic pulse train is summed in closed form
(:func:`study.physics.beam.modal_periodic_response`), and the quasi-static split makes moment and shear
converge in few modes (MODEL.md §9). The span is found by the pole-bracketed search of
:mod:`study.solvers.periodic`; the smallest span that satisfies the constraints is reported with its
impact and stresses (MODEL.md §5).
"""

from __future__ import annotations

import time
from typing import Any, Mapping

import numpy as np

from study.physics import beam, section
from study.solvers import periodic
from study.solvers.result import PointResult


def options_from(inputs: Mapping[str, Any]) -> periodic.Options:
    """Solver settings from the point's inputs (defaults where the config leaves them out)."""
    defaults = periodic.Options()
    return periodic.Options(
        modes=int(inputs.get("modes") or defaults.modes),
        min_span=float(inputs.get("min_span") or defaults.min_span),
        max_span=float(inputs.get("max_span") or defaults.max_span),
        load_shape=inputs.get("load_shape") or defaults.load_shape,
    )


def stresses(scene: periodic.Scene, impact: periodic.Impact, inputs: Mapping[str, Any],
             options: periodic.Options) -> dict[str, float]:
    """Deflection and stress maxima over the span and the period (MODEL.md §5, paper eq. 37–38).

    Bending stress σ_b = M_b r_o/I with M_b = −EI y''; combined normal stress |T0/A_s| + |σ_b| (the
    larger of T0/A_s ± σ_b); shear stress 2V/A_s (thin tube) with V = −EI y'''; alternating bending
    stress: half the range of σ_b over the period at the worst section.
    """
    p = scene.props
    r_o, r_i = inputs["outer_diameter"] / 2.0, inputs["inner_diameter"] / 2.0
    inertia = float(section.second_moment_of_area(r_o, r_i))
    area = p["steel_area"]
    x = periodic.space_grid(impact.span_length, impact.contact_half_length, options)
    t = periodic.time_grid(scene, impact.contact_duration, options)
    args = (impact.span_length, p["bending_stiffness"], p["effective_tension"], p["mass_per_length"],
            -impact.impulse, impact.contact_duration, scene.period, scene.pattern,
            impact.contact_half_length, options.load_shape, options.modes)
    y = beam.deflection(x, t, *args)
    sigma = beam.bending_moment(x, t, *args) * r_o / inertia
    shear = beam.shear_force(x, t, *args)
    # The alternating pattern's second half period mirrors the first: σ(t + τ/2) = −σ(t).
    full = np.concatenate([sigma, -sigma]) if scene.pattern == "alternating" else sigma
    half_range = 0.5 * (full.max(axis=0) - full.min(axis=0))
    axial = abs(inputs["axial_tension"]) / area
    i_b = np.unravel_index(np.nanargmax(np.abs(sigma)), sigma.shape)
    i_s = np.unravel_index(np.nanargmax(np.abs(shear)), shear.shape)
    i_y = np.unravel_index(np.nanargmax(np.abs(y)), y.shape)
    return {
        "max_deflection": float(np.abs(y[i_y])),
        "max_bending_stress": float(np.abs(sigma[i_b])),
        "max_normal_stress": float(axial + np.abs(sigma[i_b])),
        "max_normal_stress_x": float(x[i_b[1]]),
        "max_normal_stress_t": float(t[i_b[0]]),
        "max_shear_stress": float(2.0 * np.abs(shear[i_s]) / area),
        "max_shear_stress_x": float(x[i_s[1]]),
        "max_shear_stress_t": float(t[i_s[0]]),
        "alternating_bending_stress": float(np.nanmax(half_range)),
    }


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


def solve(inputs: Mapping[str, Any]) -> PointResult:
    """Find the span and solve the periodic impact of one design point (see module docstring)."""
    start = time.perf_counter()
    result = PointResult(method="fast")
    options = options_from(inputs)
    scene = periodic.make_scene(inputs)
    result.values.update(scene.props)
    max_span = min(options.max_span, scene.props["buckling_length"] * (1 - 1e-9))
    if max_span <= options.min_span:
        result.status = "buckled"
        result.message = (f"effective tension {scene.props['effective_tension']:.4g} N buckles every span "
                          f"longer than {scene.props['buckling_length']:.4g} m, below the shortest searched")
        result.wall_time = time.perf_counter() - start
        return result
    options = periodic.Options(**{**options.__dict__, "max_span": max_span})
    search = periodic.find_roots(scene, options)
    screened = periodic.midspan_screen(scene, options, search)
    survivors = search.roots[screened]
    candidates, reasons = [], {}
    for root, bracket in zip(survivors, search.brackets[screened]):
        impact = periodic.refine_root(scene, options, float(root), bracket)
        problem = "; ".join(impact.problems) or periodic.constraint_violation(scene, impact, options)
        if problem is None:
            candidates.append(impact)
        else:
            reasons.setdefault(problem.split(" at ")[0].split(" (")[0], []).append(root)
    result.values.update(root_count=float(search.roots.size), pole_count=float(search.pole_count),
                         candidate_count=float(len(candidates)))
    result.extras.update(closure=scene.closure, impact_pattern=scene.pattern,
                         candidate_spans=[c.span_length for c in candidates])
    summary = (f"{search.roots.size} roots of condition 2 between {search.pole_count} poles in "
               f"[{options.min_span:.4g}, {options.max_span:.4g}] m; {survivors.size} pass the midspan screen")
    if not candidates:
        result.status = "no_span"
        detail = "; ".join(f"{len(v)} x {k}" for k, v in sorted(reasons.items(), key=lambda kv: -len(kv[1]))[:3])
        result.message = f"{summary}; none satisfies condition 1" + (f" ({detail})" if detail else "")
        result.wall_time = time.perf_counter() - start
        return result
    chosen = candidates[0]
    result.values.update(
        span_length=chosen.span_length, equivalent_mass=chosen.equivalent_mass,
        impact_velocity=chosen.impact_velocity, impulse=chosen.impulse, axial_curvature=chosen.axial_curvature,
        max_approach=chosen.max_approach, hertz_duration=chosen.hertz_duration,
        hertz_peak_force=chosen.hertz_peak_force, contact_duration=chosen.contact_duration,
        peak_contact_force=chosen.peak_contact_force, contact_half_length=chosen.contact_half_length,
        contact_half_width=chosen.contact_half_width,
    )
    omega = periodic.natural_frequencies(scene, chosen.span_length, [1.0])
    result.values["first_natural_frequency"] = float(omega[0] / (2.0 * np.pi))
    fine = stresses(scene, chosen, inputs, options)
    result.values.update(fine)
    result.error_estimate = truncation_bound(scene, chosen, inputs, options) / fine["max_normal_stress"]
    result.message = f"{summary}; {len(candidates)} satisfy the constraints; the smallest is reported"
    result.wall_time = time.perf_counter() - start
    return result
