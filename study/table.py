"""The point table: one design point's result as ``study point`` prints it (``--json`` gives it whole, in SI).

Every output the method returns is printed — the scalar outputs of :data:`study.solvers.model.result.OUTPUTS`, any
other scalar it returns, and its other results (lists, texts, flags; nested records as a pointer to ``--json``)
— each in the table's unit system: oilfield units by default (psi, lbf, in, ft, ppg, h; the choices of
:func:`study.units.display_unit`), SI with ``--si`` (MPa for stresses, else the base units). Dimensionless values
print no unit. The error estimate says which figure it is the error of, and the message's quantities are shown
in the table's units where they are written as a number and a unit.
"""

from __future__ import annotations

import math
import re
from typing import Any, Mapping

from study.solvers.model.result import OUTPUTS, STATUS
from study.units import convert, display_unit, pint_unit

UNIT_SYSTEMS = ("oilfield", "si")

#: SI display where the base unit reads badly (pint unit, label); any other SI unit is shown as it is.
SI_UNITS = {"Pa": ("MPa", "MPa"), "N m2": ("N*m**2", "N·m²"), "m s-1": ("m/s", "m/s"), "kg m-1": ("kg/m", "kg/m"),
            "kg m-2": ("kg/m**2", "kg/m²"), "kg m-3": ("kg/m**3", "kg/m³"), "N s m-2": ("N*s/m**2", "N·s/m²"),
            "N s": ("N*s", "N·s"), "N m": ("N*m", "N·m"), "m2": ("m**2", "m²"), "m-1": ("1/m", "1/m"),
            "s-1": ("1/s", "1/s"), "N m-1": ("N/m", "N/m"), "N s m-1": ("N*s/m", "N·s/m")}

#: What a method's error estimate is the relative error of (the reference model's is its worst figure's, named
#: from its ``convergence`` record where it has one: :func:`error_of`).
ERROR_OF = {
    "fast": "max normal stress (the modes left out)",
    "series": "max normal stress (the modes and harmonics left out, and the maxima's location)",
    "damped": "max normal stress (the modes left out)",
    "free-whirl": "max normal stress (the modes left out, and the drag's fixed point)",
    "sliding": "the worst of peak contact force, max normal stress and alternating bending stress "
               "(linearisation, modes and the drag's fixed point)",
    "reference": "the worst of peak contact force, max normal stress and alternating bending stress",
}
FIGURE_NAMES = {"peak_contact_force": "peak contact force", "max_normal_stress": "max normal stress",
                "alternating_bending_stress": "alternating bending stress",
                "damage_rate": "fatigue damage rate (as the stress error that makes it)"}

#: Outputs a method returns beside :data:`OUTPUTS` (``extras``, and scalars some methods add to their values):
#: name -> (SI unit, or None for a text, flag or record; what it is).
EXTRA_OUTPUTS = {
    "candidate_spans": ("m", "every span that satisfies the constraints, in the part of the range searched"),
    "span_converged": (None, "the span held with doubled modes"),
    "closure": (None, "impact closure (impact.closure)"),
    "impact_pattern": (None, "impact pattern (impact.pattern)"),
    "whirl": (None, "whirl verdict of the reference model"),
    "whirl_point": ("m", "position along the section of the most-touching point, where the whirl is measured"),
    "local_strikes": ("1", "strikes at the tool joints over the window whose peak force the local model gave"),
    "touching_points": ("m", "positions along the section of the points touching the wall"),
    "contact_points": ("m", "positions along the section of the points that may touch the wall"),
    "contact_kinds": (None, "kind of each contact point (0 pipe body, 1 tool joint)"),
    "rest_normal_force": ("N", "normal force of each touching point at rest"),
    "reference_modes": ("1", "modes per lateral direction of the section"),
    "reference_residual": (None, "how the reference model gave back the modes left out: static in series with the "
                                 "contacts, as residual vectors in the modes (dynamic; radiating: damped by the "
                                 "bending waves' resistance), or not at all (none)"),
    "reference_residual_vectors": ("1", "residual vectors a contact point in the modes (the left-out modes' Krylov "
                                        "sequence; 0 without them)"),
    "modal_by_doubling": (None, "the modal part of the errors is each figure's change from the run at half the modes "
                                "(the residual vectors, the strikes' pulses), not the in-run measure"),
    "continued_from_modes": ("1", "modes of the run whose end this run started from (the count tried before it; "
                                  "none: started from the wall's rest)"),
    "steps": ("1", "integrator steps"),
    "quasi_static_correction": (None, "the quasi-static correction for the modes left out was applied"),
    "modal_error": (None, "modal part of each figure's error: from the strikes replayed at more modes, or the size "
                          "of the correction for the modes left out, measured on the run"),
    "modes_tried": (None, "the mode counts the reference model ran, with their modal parts and figures"),
    "replay": (None, "the strikes replayed at more modes for the modal part of the errors: the counts, the part stated "
                     "at each and each strike's figures (docs/reference_model.md §2.2)"),
    "reference_body_stations": ("1", "contact stations on the pipe body between neighbouring joints, raised where "
                                "the body passed its wall between them"),
    "body_stations_tried": (None, "the body station counts the reference model ran, with how far the body passed its "
                                  "wall and their wall times"),
    "revolutions_needed": ("1", "revolutions in all that would bring the figures within the tolerance"),
    "revolutions_needed_by_figure": (None, "per figure left over its tolerance, the revolutions in all that would "
                                           "bring it within (inf: its modes or integrator part is over)"),
    "window_stopped_by": (None, "per figure left over its tolerance, why the window stopped: modes (its modes or "
                                "integrator part is over), forecast (beyond FORECAST_SLACK times the budget), budget "
                                "(spent), others (stopped by a figure that could not get there), none"),
    "modal_quarter_fraction": ("1", "share of the largest bending moment carried by the upper quarter of the modes "
                               "(a truncation indicator)"),
    "drag_iterations": ("1", "iterations of the drag's fixed point"),
    "linearisation_error": ("1", "relative change of the figures from the contact's and the drag's linearisation"),
    "contact_linearisation": ("1", "relative change of the figures with the Hertz secant stiffness"),
    "drag_linearisation": ("1", "relative change of the figures with the drag made viscous at the mean speed"),
    "truncation_error": ("1", "relative change of the figures with half the modes"),
    "harmonic_balance": (None, "the sliding state solved exactly by harmonic balance (harmonics, Newton iterations, "
                               "last correction, the figures' change from half the harmonics, the linear answer's "
                               "estimate)"),
    "methods_tried": (None, "the models tried by auto, in order, and their verdicts"),
    "convergence": (None, "error of each figure, by its parts"),
    "energy_budget": (None, "energy balance over the window"),
    "series_modes": ("1", "modes of the double Fourier series"),
    "series_harmonics": ("1", "harmonics of the double Fourier series"),
    "time_integrator": (None, "time integrator"),
    "drive_source": (None, "what drives the first mode"),
    "sdof_mass_model": (None, "mass of the one-degree-of-freedom model"),
    "orbits_found": ("1", "periodic orbits found"),
    "stability": (None, "stability of the orbit"),
    "damping_converged": (None, "the equivalent damping settled"),
}

_NUMBER = r"[-+±]?\d+(?:\.\d+)?(?:e[-+]?\d+)?"
#: Quantities in messages (a number, a space, an SI unit) and their oilfield display (pint from, pint to, label).
_MESSAGE_UNITS = {"mm": ("mm", "in", "in"), "m": ("m", "ft", "ft"), "kN": ("kN", "lbf", "lbf"),
                  "N": ("N", "lbf", "lbf"), "N m": ("N*m", "lbf*ft", "lbf·ft"), "MPa": ("MPa", "psi", "psi"),
                  "kPa": ("kPa", "psi", "psi"), "Pa": ("Pa", "psi", "psi"), "m/s": ("m/s", "ft/s", "ft/s"),
                  "kg/m": ("kg/m", "lb/ft", "lb/ft"), "N s/m²": ("N*s/m**2", "lbf*s/ft**2", "lbf·s/ft²")}
_MESSAGE_QUANTITY = re.compile(rf"(?<![\w.])({_NUMBER}) "
                               rf"({'|'.join(sorted(map(re.escape, _MESSAGE_UNITS), key=len, reverse=True))})"
                               r"(?![\w/²·])")


#: Lengths along the pipe, shown in feet in oilfield units (a position along a 93-ft section reads badly in inches).
ALONG_THE_PIPE = {"touching_points", "contact_points", "whirl_point", "contact_spacing", "candidate_spans"}


def shown_unit(name: str, udunits: str, system: str = "oilfield") -> tuple[str, str]:
    """(pint unit, label) of an output in the table: the label is "" for a dimensionless value."""
    if not udunits or udunits.strip() == "1":
        return "", ""
    if system == "si":
        return SI_UNITS.get(udunits, (pint_unit(udunits), udunits))
    if udunits == "m" and (name in ALONG_THE_PIPE or name.endswith("_x")):
        return "ft", "ft"
    unit, label = display_unit(name, udunits)
    return unit, label


def describe(name: str, system: str = "oilfield") -> tuple[str | None, str]:
    """(SI unit or None, description) of an output for the table. The fatigue damage rate's description follows
    the unit it is shown in."""
    if name in OUTPUTS:
        unit, text = OUTPUTS[name]
    elif name in EXTRA_OUTPUTS:
        unit, text = EXTRA_OUTPUTS[name]
    else:
        unit, text = None, "(no description: see --json)"
    if name == "damage_rate" and system == "oilfield":
        text = text.replace("per second of rotation", "per hour of rotation")
    return unit, text


def _number(value: float, udunits: str | None, name: str, system: str) -> str:
    if udunits is None:
        return f"{value:.5g}"
    unit, label = shown_unit(name, udunits, system)
    shown = convert(value, pint_unit(udunits), unit) if unit else value
    return f"{shown:.5g}" + (f" {label}" if label else "")


def _is_number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def format_value(name: str, value: Any, system: str = "oilfield") -> str:
    """One output's value as the table shows it (display units, the unit after it)."""
    udunits, _ = describe(name, system)
    if value is None:
        return "none"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if _is_number(value):
        if isinstance(value, int) and (udunits in (None, "1")):
            return str(value)
        if not math.isfinite(value):
            label = shown_unit(name, udunits or "1", system)[1]
            return str(value) + (f" {label}" if label else "")
        return _number(float(value), udunits, name, system)
    if isinstance(value, complex):
        return f"{abs(value):.4g} (modulus)"
    if isinstance(value, str):
        return value
    if isinstance(value, (list, tuple)):
        if not value:
            return "none"
        if all(_is_number(v) for v in value):
            unit, label = shown_unit(name, udunits or "1", system)
            shown = [convert(float(v), pint_unit(udunits), unit) if unit else float(v) for v in value]
            head = ", ".join(f"{v:.4g}" for v in shown[:8]) + (f", … ({len(value)} in all)" if len(value) > 8 else "")
            return head + (f" {label}" if label else "")
        if all(isinstance(v, complex) for v in value):
            return ", ".join(f"{abs(v):.4g}" for v in value[:8]) + " (moduli)"
        return f"{len(value)} entries (--json)"
    if isinstance(value, Mapping):
        return _record(name, value)
    return str(value)


def _record(name: str, value: Mapping) -> str:
    """A nested record in one line where it is short (auto's methods tried, the errors per figure), else a pointer
    to ``--json``."""
    if name == "methods_tried":
        return "; ".join(f"{method} {entry.get('status')}" + (f" (error {entry['error_estimate']:.3g})"
                                                              if _is_number(entry.get("error_estimate")) else "")
                         for method, entry in value.items())
    if name == "convergence":
        return "; ".join(f"{FIGURE_NAMES.get(figure, figure)} {entry['total']:.3g}" for figure, entry in value.items()
                         if isinstance(entry, Mapping) and _is_number(entry.get("total")))
    flat = {k: v for k, v in value.items() if _is_number(v) and not isinstance(v, bool)}
    if flat and len(flat) == len(value) and len(flat) <= 6:
        return ", ".join(f"{k} {v:.4g}" for k, v in flat.items())
    return f"a record of {len(value)} entries (--json)"


def error_of(result) -> str:
    """Which figure the result's error estimate is the relative error of (by each figure's error as a stress error,
    ``equivalent``, where the record states it)."""
    record = result.extras.get("convergence")
    if isinstance(record, Mapping):
        totals = {figure: entry.get("equivalent", entry.get("total")) for figure, entry in record.items()
                  if isinstance(entry, Mapping) and _is_number(entry.get("equivalent", entry.get("total")))}
        if totals:
            worst = max(totals, key=totals.get)
            return f"the worst figure, the {FIGURE_NAMES.get(worst, worst)} (each figure's: convergence)"
    return ERROR_OF.get(result.method, f"the {result.method} method's own measure")


def message_units(message: str, system: str = "oilfield") -> str:
    """``message`` with each "number unit" in SI (mm, m, N, kN, N m, Pa, MPa, m/s, kg/m, N s/m²) shown in the
    table's units: oilfield converts them (4 significant digits), SI leaves them."""
    if system == "si":
        return message

    def swap(match):
        text, unit = match.group(1), match.group(2)
        sign = "±" if text.startswith("±") else ""
        source, target, label = _MESSAGE_UNITS[unit]
        value = convert(float(text.lstrip("±")), source, target)
        return f"{sign}{value:.4g} {label}"

    return _MESSAGE_QUANTITY.sub(swap, message)


def point_table(result, inputs: Mapping[str, Any] | None = None, system: str = "oilfield") -> str:
    """The table of one point's result: method, status and message, then every output with its unit and what it
    is, the error estimate with the figure it is the error of, and the wall time."""
    if system not in UNIT_SYSTEMS:
        raise ValueError(f"system = {system!r}; allowed: {', '.join(UNIT_SYSTEMS)}")
    meaning = STATUS.get(result.status, (None, ""))[1]
    lines = [f"method {result.method}: status {result.status}" + (f" ({meaning})" if meaning else ""),
             f"  {message_units(result.message, system)}",
             f"  units: {'SI' if system == 'si' else 'oilfield (SI with --si)'}", ""]

    def row(name, text, description):
        lines.append(f"  {name:30s} {text:>14s}  {description}" if len(text) <= 14 else
                     f"  {name:30s} {text}\n  {'':30s} {'':14s}  {description}")

    for name, value in result.values.items():
        row(name, format_value(name, value, system), describe(name, system)[1])
    if result.error_estimate is not None:
        estimate = result.error_estimate
        row("error_estimate", f"{estimate:.3g}" if math.isfinite(estimate) else str(estimate),
            f"relative error of {error_of(result)}")
    for name, value in result.extras.items():
        row(name, format_value(name, value, system), describe(name, system)[1])
    wall = result.wall_time
    lines.append(f"\n  wall time {wall * 1e3:.3g} ms" if wall < 1 else f"\n  wall time {wall:.3g} s")
    return "\n".join(lines)
