"""Units at the edges: one pint registry for configs coming in and labels going out.

Inside the package every number is a plain SI float or array. This module turns what users
write ("4.5 in", "16.6 lb/ft", "10 ppg", "300 rpm", "10000 lbf", "30e6 psi") into SI and
back into the units a chart or table shows.
"""

from __future__ import annotations

import math
import re

import pint

ureg = pint.UnitRegistry()
# Oilfield spellings that pint does not know.
ureg.define("pounds_per_gallon = pound / gallon = ppg")
ureg.define("@alias revolution = rev")


class UnitProblem(ValueError):
    """A value that cannot be read in the units a field needs; the message says why."""


def parse_quantity(value, si_unit: str, *, angular: bool = False) -> float:
    """Return ``value`` in ``si_unit`` as a float.

    value : a number (taken as already in SI) or a string with units ("4.5 in").
    si_unit : the SI unit of the field, e.g. "m", "kg/m^3", "rad/s", "" for dimensionless.
    angular : the field is an angular speed. Pint counts radians as dimensionless, so
        "3 Hz" would silently become 3 rad/s; such values must name an angle (rpm, rev/s,
        rad/s) and a bare "1/s" or "Hz" is refused as ambiguous.

    Raises :class:`UnitProblem` with a message naming the value and what was expected.
    """
    if isinstance(value, bool):
        raise UnitProblem(f"{value!r} is a boolean; expected a number or a string with units")
    if isinstance(value, (int, float)):
        return float(value)
    if not isinstance(value, str):
        raise UnitProblem(f"{value!r} is a {type(value).__name__}; expected a number or a string with units")
    try:
        quantity = ureg.Quantity(value.strip())
    except (pint.errors.UndefinedUnitError, pint.errors.DefinitionSyntaxError, AttributeError, TypeError, ValueError) as exc:
        raise UnitProblem(f"{value!r} cannot be read as a quantity ({exc})") from None
    except Exception as exc:  # pint's tokenizer raises a variety of errors on garbage
        raise UnitProblem(f"{value!r} cannot be read as a quantity ({type(exc).__name__})") from None
    target = ureg.Unit(si_unit) if si_unit else ureg.dimensionless
    if not isinstance(quantity, pint.Quantity):  # a bare number in a string, e.g. "0.5"
        quantity = ureg.Quantity(float(quantity))
    if si_unit and quantity.dimensionless and quantity.units == ureg.dimensionless and not angular:
        raise UnitProblem(f"{value!r} has no units; expected units of {describe_unit(si_unit)}")
    if angular and "radian" not in quantity.to_root_units().units._units:
        raise UnitProblem(
            f"{value!r} is ambiguous as a rotary speed; write it in rpm, rev/s or rad/s"
        )
    try:
        result = float(quantity.to(target).magnitude)
    except pint.errors.DimensionalityError:
        raise UnitProblem(
            f"{value!r} has dimension {quantity.dimensionality}; expected {describe_unit(si_unit)}"
        ) from None
    return result


def describe_unit(si_unit: str) -> str:
    """A human description of an SI unit with its dimension, e.g. 'm ([length])'."""
    if not si_unit:
        return "a dimensionless number"
    return f"{si_unit} ({ureg.Unit(si_unit).dimensionality})"


def convert(value, from_unit: str, to_unit: str):
    """Convert a plain number or array between units (for display): convert(31.4, 'rad/s', 'rpm')."""
    return ureg.Quantity(value, from_unit).to(to_unit).magnitude


def is_finite_number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


#: Display unit of an output by its SI (UDUNITS) unit: (pint unit, label).
OUTPUT_UNITS = {
    "Pa": ("psi", "psi"),
    "N": ("lbf", "lbf"),
    "s": ("ms", "ms"),
    "Hz": ("Hz", "Hz"),
    "m s-1": ("in/s", "in/s"),
    "m": ("in", "in"),
    "kg m-1": ("lb/ft", "lb/ft"),
    "kg": ("lb", "lb"),
    "N s": ("lbf*s", "lbf·s"),
    "m-1": ("1/ft", "1/ft"),
    "m2": ("in**2", "in²"),
    "N m2": ("lbf*in**2", "lbf·in²"),
    "kg m-2": ("lb/ft**2", "lb/ft²"),
    "kg m-3": ("ppg", "ppg"),
}
#: Outputs whose display unit differs from the default of their dimension.
OUTPUT_UNITS_BY_NAME = {
    "span_length": ("ft", "ft"),
    "buckling_length": ("ft", "ft"),
    "wall_time": ("s", "s"),
    "fatigue_life": ("hour", "h"),
    "damage_rate": ("1/hour", "1/h"),
}

UDUNITS_TOKEN = re.compile(r"([A-Za-z_]+)(-?\d+)?")


def pint_unit(udunits: str | None) -> str:
    """A CF/UDUNITS unit string in pint's syntax: 'kg m-3' -> 'kg * m ** -3'; '1' or '' -> ''."""
    if not udunits or udunits.strip() == "1":
        return ""
    parts = []
    for token in udunits.split():
        match = UDUNITS_TOKEN.fullmatch(token)
        if match is None:
            return udunits  # not UDUNITS-style; let pint read it as it is
        name, power = match.groups()
        parts.append(f"{name} ** {power}" if power else name)
    return " * ".join(parts)


def display_unit(name: str, udunits: str) -> tuple[str, str]:
    """The unit an output is shown in: (pint unit, label), by its name first, else by its SI unit.

    name: the output's name (e.g. "span_length"); udunits: its SI unit in CF/UDUNITS form ("m").
    An output with no listed display unit is shown in SI.
    """
    if name in OUTPUT_UNITS_BY_NAME:
        return OUTPUT_UNITS_BY_NAME[name]
    if udunits in OUTPUT_UNITS:
        return OUTPUT_UNITS[udunits]
    return pint_unit(udunits), udunits


# A dogleg severity as drillers write it: an angle per a count of lengths, "3 deg/100ft", "3 deg/30m",
# "0.0017 rad/m". Pint reads "3 deg/100ft" as (3 deg/100)·ft, so this form is read here, by a pattern of
# two numbers and two named units from the tables below: nothing in the text is evaluated.
_NUMBER = r"[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?"
_PER_LENGTH = re.compile(rf"\s*(?P<value>{_NUMBER})\s*(?P<angle>[A-Za-z°]+)\s*/\s*(?P<count>{_NUMBER})?\s*"
                         rf"(?P<length>[A-Za-z]+)\s*")
_ANGLES = {"deg": math.pi / 180, "degree": math.pi / 180, "degrees": math.pi / 180, "°": math.pi / 180,
           "rad": 1.0, "radian": 1.0, "radians": 1.0}
_LENGTHS = {"ft": 0.3048, "foot": 0.3048, "feet": 0.3048, "m": 1.0, "meter": 1.0, "meters": 1.0, "metre": 1.0,
            "metres": 1.0}


def parse_angle_per_length(value) -> float:
    """A change of angle per length (a dogleg severity) in rad/m: "3 deg/100ft", "3 deg/30m", "0.0017 rad/m".

    A number is taken as already in rad/m. A string is an angle in deg or rad over a length in ft or m, with an
    optional count of lengths ("/100ft", "/30 m", "/m"). Raises :class:`UnitProblem` naming the value and
    the forms allowed.
    """
    if isinstance(value, (bool, int, float)) or not isinstance(value, str):
        return parse_quantity(value, "rad/m")
    match = _PER_LENGTH.fullmatch(value)
    angle = _ANGLES.get(match["angle"]) if match else None
    length = _LENGTHS.get(match["length"]) if match else None
    count = float(match["count"]) if match and match["count"] else 1.0
    if angle is None or length is None or not count > 0:
        raise UnitProblem(f"{value!r} cannot be read as an angle per length; write it as '3 deg/100ft', '3 deg/30m' "
                          "or '0.0017 rad/m'")
    return float(match["value"]) * angle / (count * length)
