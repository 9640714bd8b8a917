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
ureg.define("@alias pound = lbm")  # pound-mass, as oilfield tables write it ("16.6 lbm/ft")
ureg.define("deg_per_100ft = 0.01 * degree / foot")  # a dogleg severity as drillers state it (API RP 7G)

#: The longest value string read as a quantity, and the most tokens and parentheses in it: a value is a number and
#: its units ("30e6 psi", "3 deg/100ft"), never a long text.
MAX_VALUE_LENGTH = 100
MAX_TOKENS = 40
MAX_PARENTHESES = 4
#: The largest integer exponent of a unit ("in^3", "m**-3", "s^-2").
MAX_EXPONENT = 12

#: One token of a value: a number, a unit name, an operator or a parenthesis (what else there is, is refused).
_TOKEN = re.compile(r"""\s*(?:
    (?P<number>(?:\d+(?:_\d+)*(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?)
  | (?P<name>[^\W\d]\w*)
  | (?P<op>\*\*|\^|\*|/|\(|\)|[+-])
)""", re.VERBOSE)
#: A number: its magnitude at most this many characters (digits, point, exponent)
MAX_NUMBER_LENGTH = 30


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
    if isinstance(value, int):
        try:
            return float(value)
        except OverflowError:
            raise UnitProblem(f"an integer of {len(str(abs(value)))} digits is too large for a float") from None
    if isinstance(value, float):
        return value
    if not isinstance(value, str):
        text = repr(value)
        shown = text if len(text) <= 60 else f"{text[:30]}... ({len(text)} characters written)"
        raise UnitProblem(f"{shown} is a {type(value).__name__}; expected a number or a string with units")
    quantity = read_quantity(value)
    target = ureg.Unit(si_unit) if si_unit else ureg.dimensionless
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


def read_quantity(text: str) -> pint.Quantity:
    """A value string as a pint quantity, read by a small grammar instead of pint's expression evaluator.

    value  := [+|-] number [units]          "4.5 in", "-20000 lbf", "30e6 psi", "0.5"
    units  := factor (("*" | "/" | " ") factor)*      left to right, as pint reads them
    factor := atom [("**" | "^") [+|-] integer]         exponent at most :data:`MAX_EXPONENT` in size
    atom   := name | number name | "(" units ")"      a number with a name is one factor: "deg/100ft" and
                                                      "deg/100 ft" are degrees per 100 feet
    Each name is looked up in the registry alone (``ureg.Unit(name)``). Nothing is evaluated but these products,
    quotients and small integer powers, so "9**9**9 in" or "10**400 in" is refused at once, and the text is at most
    :data:`MAX_VALUE_LENGTH` characters. Raises :class:`UnitProblem` naming the value and what is wrong.
    """
    shown = repr(text) if len(text) <= 60 else f"{text[:40]!r}... ({len(text)} characters)"
    if len(text) > MAX_VALUE_LENGTH:
        raise UnitProblem(f"{shown} is too long; a value is a number and its units, at most {MAX_VALUE_LENGTH} "
                          "characters")
    tokens, at, stripped = [], 0, text.rstrip()
    while at < len(stripped):
        match = _TOKEN.match(stripped, at)
        if match is None or match.end() == at:
            raise UnitProblem(f"{shown} cannot be read as a quantity: {stripped[at:].strip()[:10]!r} is not a number, "
                              "a unit name or one of * / ** ^ ( )")
        kind = match.lastgroup
        tokens.append((kind, match.group(kind)))
        at = match.end()
    if len(tokens) > MAX_TOKENS:
        raise UnitProblem(f"{shown} has {len(tokens)} parts; a value is a number and its units")
    return _Reader(tokens, shown).value()


class _Reader:
    """The recursive-descent reader of :func:`read_quantity`'s grammar over its tokens."""

    def __init__(self, tokens, shown):
        self.tokens, self.shown, self.at, self.depth = tokens, shown, 0, 0

    def problem(self, why: str) -> UnitProblem:
        return UnitProblem(f"{self.shown} cannot be read as a quantity: {why}; write a number and its units, "
                           "e.g. '4.5 in', '10 ppg', '3 deg/100ft'")

    def peek(self):
        return self.tokens[self.at] if self.at < len(self.tokens) else (None, None)

    def take(self):
        token = self.peek()
        self.at += 1
        return token

    def number(self, text: str) -> float:
        if len(text) > MAX_NUMBER_LENGTH:
            raise self.problem(f"the number {text[:20]}... has {len(text)} characters; at most {MAX_NUMBER_LENGTH}")
        value = float(text)
        if not math.isfinite(value):
            raise self.problem(f"the number {text} is beyond a float's range")
        return value

    def value(self) -> pint.Quantity:
        sign = 1.0
        if self.peek() == ("op", "-") or self.peek() == ("op", "+"):
            sign = -1.0 if self.take()[1] == "-" else 1.0
        kind, text = self.take()
        if kind != "number":
            raise self.problem("it does not begin with a number")
        magnitude = sign * self.number(text)
        units = self.units() if self.peek()[0] is not None else ureg.Quantity(1.0)
        if self.peek()[0] is not None:
            raise self.problem(f"unexpected {self.peek()[1]!r}")
        try:
            return magnitude * units
        except (ArithmeticError, ValueError) as exc:
            raise self.problem(str(exc)) from None

    def units(self) -> pint.Quantity:
        result = self.factor()
        while True:
            kind, text = self.peek()
            if kind == "op" and text in ("*", "/"):
                self.take()
                right = self.factor()
                result = result * right if text == "*" else result / right
            elif kind in ("name", "number") or (kind, text) == ("op", "("):
                result = result * self.factor()  # implicit multiplication: "lbf s"
            else:
                return result

    def factor(self) -> pint.Quantity:
        base = self.atom()
        if self.peek() in (("op", "**"), ("op", "^")):
            self.take()
            sign = 1
            if self.peek() in (("op", "-"), ("op", "+")):
                sign = -1 if self.take()[1] == "-" else 1
            kind, text = self.take()
            if kind != "number" or not text.isdigit() or int(text) > MAX_EXPONENT:
                raise self.problem(f"an exponent is a whole number of at most {MAX_EXPONENT} in size, not "
                                   f"{text!r}")
            try:
                return base ** (sign * int(text))
            except (ArithmeticError, ValueError) as exc:
                raise self.problem(str(exc)) from None
        return base

    def atom(self) -> pint.Quantity:
        kind, text = self.take()
        if kind == "name":
            return ureg.Quantity(1.0, self.unit(text))
        if kind == "number":  # a scaled unit: "100ft" in "deg/100ft"
            scale = self.number(text)
            if not scale > 0:
                raise self.problem(f"a number inside the units must be positive, not {text}")
            if self.peek()[0] != "name":
                raise self.problem(f"the number {text} inside the units needs a unit after it (e.g. 100ft)")
            return ureg.Quantity(scale, self.unit(self.take()[1]))
        if (kind, text) == ("op", "("):
            self.depth += 1
            if self.depth > MAX_PARENTHESES:
                raise self.problem(f"more than {MAX_PARENTHESES} nested parentheses")
            inner = self.units()
            if self.take() != ("op", ")"):
                raise self.problem("a parenthesis is not closed")
            self.depth -= 1
            return inner
        raise self.problem("a unit is missing" if kind is None else f"unexpected {text!r}")

    def unit(self, name: str):
        try:
            return ureg.Unit(name)
        except (pint.errors.UndefinedUnitError, pint.errors.DefinitionSyntaxError, AttributeError, TypeError,
                ValueError) as exc:
            raise self.problem(f"{name!r} is not a unit ({exc})") from None


def describe_unit(si_unit: str) -> str:
    """A human description of an SI unit with its dimension, e.g. 'm ([length])'."""
    if not si_unit:
        return "a dimensionless number"
    return f"{si_unit} ({ureg.Unit(si_unit).dimensionality})"


def convert(value, from_unit: str, to_unit: str):
    """Convert a plain number or array between units (for display): convert(31.4, 'rad/s', 'rpm')."""
    return ureg.Quantity(value, from_unit).to(to_unit).magnitude


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
    "dogleg_curvature": ("deg_per_100ft", "°/100 ft"),  # the hole's curvature as a dogleg severity
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
