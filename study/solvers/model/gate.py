"""The one gate every method's result passes before it is called ``ok`` (docs/model.md §6).

A method reports what it computed and whether it succeeded; whether the answer is *physical* is decided
here, once, for every method — as scipy's ``OdeSolver.step`` owns its status transitions while each
method only reports success and a message. :func:`admit` is applied by
:func:`study.solvers.solve_point` to every result; it only ever moves a result *from* ``ok`` to a
failure status, appending what failed (with the numbers) to the message.

The checks, in order (each a plain function ``check(values, scene, tolerances) -> problem | None`` in
:data:`CHECKS`, given the point's :class:`~study.solvers.model.scene.Scene` and
:class:`~study.solvers.model.options.Tolerances`; the first failed one sets the status, every failed one is named in the
message):

- ``finite``: the principal outputs (:data:`PRINCIPAL`) that a method reports are finite (``failed``).
- ``within_clearance``: the largest deflection stays inside the hole, |y| ≤ c (1 + tol) + α_max — the
  clearance c, the study's relative tolerance and, at a contact, the Hertz approach α_max — and, where the method
  reports it (``max_wall_excess``, the reference model), no point of the body passes its wall by more than c tol
  beyond its contacts' own Hertz approach (``unphysical``).
- ``hertz_valid``: the contact ellipse at the peak contact force is a Hertz contact
  (:func:`study.physics.hertz.contact_validity`: small beside the radii of curvature and the span, no
  longer than the pipe is wide, not degenerate); the ellipse is computed here from the peak force and
  the axial curvature where the method did not report it (``hertz_invalid``).
- ``consistent_stresses``: the combined normal stress is at least the bending stress and the axial
  stress, each non-negative (``unphysical``).
- ``within_tolerance``: the method's error estimate is within the study's tolerance (``solver.tolerance``; where
  the method's figures are means over the revolutions of a motion that does not repeat, ``statistical_figures``,
  ``solver.statistical_tolerance``) (``not_converged``).
- ``within_yield``: the largest normal stress is within the grade's yield strength, ``yield_utilisation`` ≤ 1
  (:func:`study.solvers.model.utilisation.add_limits`, applied before the gate) (``yields``): past it the pipe yields,
  which the elastic models do not follow; the figures are kept. Last, so that a point not converged stays
  ``not_converged`` (the envelope decides its yield within its error estimate).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any, Callable, Mapping

import numpy as np

from study.physics import hertz
from study.solvers.model.options import Tolerances
from study.solvers.model.scene import Scene
from study.solvers.model.result import PointResult


#: Outputs that an ``ok`` result may not report as NaN or infinite (absent is fine: a method fills what it
#: computes).
PRINCIPAL = ("span_length", "impact_velocity", "impulse", "peak_contact_force", "max_deflection",
             "max_bending_stress", "max_normal_stress", "max_shear_stress", "alternating_bending_stress",
             "contact_duration", "error_estimate")

Problem = tuple[str, str]  #: (status, message with the numbers)


def finite(values: Mapping[str, Any], scene: Scene, tolerances: Tolerances) -> Problem | None:
    """Every principal output the method reports is a finite number."""
    bad = [f"{name} = {values[name]}" for name in PRINCIPAL
           if values.get(name) is not None and not np.isfinite(values[name])]
    return ("failed", "not finite: " + ", ".join(bad)) if bad else None


def within_clearance(values: Mapping[str, Any], scene: Scene, tolerances: Tolerances) -> Problem | None:
    """|y|max ≤ c (1 + tol) + α_max: the pipe stays inside the hole but for the Hertz approach at a contact."""
    deflection, clearance = values.get("max_deflection"), values.get("clearance")
    if deflection is None or clearance is None or not np.isfinite(deflection):
        return None
    approach = values.get("max_approach")
    approach = float(approach) if approach is not None and np.isfinite(approach) else 0.0
    bound = clearance * (1.0 + tolerances.tolerance) + approach
    if deflection > bound:
        return ("unphysical", f"the largest deflection {deflection:.4g} m ({deflection / clearance:.4g} c) "
                              f"passes the wall: the bound is the clearance {clearance:.4g} m (1 + tolerance) plus "
                              f"the Hertz approach {approach:.4g} m")
    excess = values.get("max_wall_excess")  # anywhere along the body, beyond each contact's own approach
    if excess is not None and np.isfinite(excess) and excess > clearance * tolerances.tolerance:
        return ("unphysical", f"the pipe body passes its wall by up to {excess:.4g} m ({excess / clearance:.3g} c) "
                              "beyond its contacts' Hertz approach between its contact stations (the reference model "
                              "raises them up to reference_max_body_stations; more hold it)")
    return None


def contact_ellipse_of(values: Mapping[str, Any], scene: Scene):
    """(half_length, half_width, A, B) [m, m, 1/m, 1/m] of the contact at the peak force: as the method
    reported it, else from the peak contact force and the axial curvature (Hertz, elliptic integrals);
    None where the result has no contact."""
    force, curvature = values.get("peak_contact_force"), values.get("axial_curvature")
    if force is None or curvature is None or not (np.isfinite(force) and force > 0):
        return None
    r_o, hole_r = scene.outer_radius, scene.hole_radius
    compliance = scene.compliance_sum
    a_sum, b_sum = hertz.curvature_sums(r_o, hole_r, curvature)
    length, width = values.get("contact_half_length"), values.get("contact_half_width")
    if length is None or width is None:
        ellipse = hertz.contact_ellipse(force, r_o, hole_r, curvature, compliance)
        length, width = float(ellipse.contact_half_length), float(ellipse.contact_half_width)
    return length, width, float(a_sum), float(b_sum)


def hertz_valid(values: Mapping[str, Any], scene: Scene, tolerances: Tolerances) -> Problem | None:
    """The contact at the peak force is a Hertz contact (:func:`study.physics.hertz.contact_validity`)."""
    ellipse = contact_ellipse_of(values, scene)
    if ellipse is None:
        return None
    verdict = hertz.contact_validity(*ellipse, span_length=values.get("span_length"),
                                     pipe_diameter=scene.outer_diameter)
    if bool(np.all(verdict.ok)):
        return None
    force = values["peak_contact_force"]
    return ("hertz_invalid", f"at the peak contact force {force:.4g} N: {verdict.message.rstrip('.')}")


def consistent_stresses(values: Mapping[str, Any], scene: Scene, tolerances: Tolerances) -> Problem | None:
    """max normal stress ≥ max bending stress ≥ 0 and ≥ the axial stress |T0|/A_s (MODEL §5 combination)."""
    normal, bending = values.get("max_normal_stress"), values.get("max_bending_stress")
    if normal is None or bending is None:
        return None
    axial = abs(scene.axial_tension) / values["steel_area"] if values.get("steel_area") else 0.0
    slack = 1e-9 * max(abs(normal), abs(bending), axial)
    if bending < 0 or normal + slack < bending or normal + slack < axial:
        return ("unphysical", f"the stresses are inconsistent: max normal stress {normal:.4g} Pa, max bending "
                              f"stress {bending:.4g} Pa, axial stress {axial:.4g} Pa (normal = axial + bending)")
    return None


def held_to(values: Mapping[str, Any], tolerances: Tolerances) -> tuple[float, str]:
    """The tolerance a result's error estimate is held to and the config field that sets it: the study's
    ``solver.tolerance``, or ``solver.statistical_tolerance`` where the result's figures are means over the revolutions
    of a motion that does not repeat (``values['statistical_figures']`` = 1: the reference model's bouncing pipe,
    docs/reference_model.md §3.1)."""
    statistical = values.get("statistical_figures")
    if statistical is not None and np.isfinite(statistical) and statistical > 0:
        return tolerances.statistical, "solver.statistical_tolerance"
    return tolerances.tolerance, "solver.tolerance"


def within_tolerance(values: Mapping[str, Any], scene: Scene, tolerances: Tolerances) -> Problem | None:
    """The method's error estimate (``values['error_estimate']``) meets the tolerance it is held to
    (:func:`held_to`)."""
    estimate = values.get("error_estimate")
    tolerance, field = held_to(values, tolerances)
    if estimate is not None and np.isfinite(estimate) and estimate > tolerance:
        return ("not_converged", f"error estimate {estimate:.3g} is above the tolerance {tolerance:.3g} ({field})")
    return None


def within_yield(values: Mapping[str, Any], scene: Scene, tolerances: Tolerances) -> Problem | None:
    """The largest normal stress is within the yield strength: ``yield_utilisation`` ≤ 1 (issue 32: a point at
    10^7 lbf tension was ``ok`` with a 15.6 GPa normal stress)."""
    use, normal = values.get("yield_utilisation"), values.get("max_normal_stress")
    if use is None or normal is None or not (np.isfinite(use) and use > 1.0):
        return None
    return ("yields", f"the largest normal stress {normal:.4g} Pa is {use:.3g} times the yield strength "
                      f"{normal / use:.4g} Pa: the pipe yields (the elastic figures are kept)")


#: The checks, in the order their statuses take precedence.
CHECKS: tuple[Callable[[Mapping[str, Any], Scene, Tolerances], Problem | None], ...] = (
    finite, within_clearance, hertz_valid, consistent_stresses, within_tolerance, within_yield)


def problems(result: PointResult, scene: Scene, tolerances: Tolerances) -> list[Problem]:
    """Every gate check the result of the point ``scene`` fails with its ``tolerances``, in :data:`CHECKS` order
    (empty: it may be called ``ok``)."""
    values = dict(result.values)
    if result.error_estimate is not None:
        values["error_estimate"] = result.error_estimate
    found = []
    for check in CHECKS:
        problem = check(values, scene, tolerances)
        if problem is not None:
            found.append(problem)
    return found


def admit(result: PointResult, scene: Scene, tolerances: Tolerances) -> PointResult:
    """``result`` unchanged unless it is ``ok`` and fails a check; then a copy with the first failed check's
    status and every failure named in the message (the values are kept, so a user sees what failed)."""
    if result.status != "ok":
        return result
    found = problems(result, scene, tolerances)
    if not found:
        return result
    note = "; ".join(f"{status}: {message}" for status, message in found)
    message = f"{result.message}; not ok - {note}" if result.message else f"not ok - {note}"
    return replace(result, status=found[0][0], message=message)
