"""Display units, axis labels and value formatting for the design charts.

The dataset is SI with CF/UDUNITS unit strings ("kg m-3", "rad s-1"). A chart shows the unit
users think in: the ``display_units`` attribute of a coordinate (rpm, lbf, ppg, ...), and for an
output the oilfield unit of its dimension (psi for stresses, ft for spans, lbf for forces, ms for
durations, Hz, in/s). Conversion goes through pint (:data:`study.units.ureg`); nothing here knows
any physics.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np
import xarray as xr
from matplotlib import ticker

from study.units import UDUNITS_TOKEN, display_unit, pint_unit, ureg

#: Short names for labels (the ``long_name`` attributes are sentences, too long for an axis).
SHORT_NAMES = {
    "rotary_speed": "rotary speed",
    "axial_tension": "axial tension",
    "restitution": "restitution",
    "mud_density": "mud density",
    "mud_flow_velocity": "mud flow velocity",
    "dogleg_curvature": "dogleg severity",
    "added_mass_model": "added-mass model",
    "impact_pattern": "impact pattern",
    "hole_diameter": "hole diameter",
    "outer_diameter": "pipe OD",
    "inner_diameter": "pipe ID",
    "max_normal_stress": "maximum normal stress",
    "alternating_bending_stress": "alternating bending stress",
    "max_shear_stress": "maximum shear stress",
    "span_length": "span length",
    "peak_contact_force": "peak contact force",
    "contact_duration": "contact duration",
    "first_natural_frequency": "first natural frequency",
    "second_natural_frequency": "second natural frequency",
    "third_natural_frequency": "third natural frequency",
    "impact_velocity": "impact velocity",
    "peak_force_ratio": "peak force, real / periodic",
    "reference_peak_force_ratio": "peak force, periodic / reference",
    "reference_normal_stress_ratio": "normal stress, periodic / reference",
    "reference_alternating_stress_ratio": "alternating stress, periodic / reference",
    "normal_stress_ratio": "normal stress, real / periodic",
    "deflection_ratio": "deflection, real / periodic",
    "orbit_peak_force_ratio": "orbit's peak force / periodic",
    "orbit_normal_stress_ratio": "orbit's normal stress / periodic",
    "max_floquet_multiplier": "largest Floquet multiplier",
}

_SUPERSCRIPTS = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


def pretty_unit(udunits: str | None) -> str:
    """A UDUNITS string for a label: 'kg m-3' -> 'kg/m³', 'N m2' -> 'N·m²', '1' -> '-'."""
    if not udunits or udunits.strip() == "1":
        return "-"
    numerator, denominator = [], []
    for token in udunits.split():
        match = UDUNITS_TOKEN.fullmatch(token)
        if match is None:
            return udunits
        name, power = match.groups()
        power = int(power) if power else 1
        (numerator if power > 0 else denominator).append(
            name + (str(abs(power)).translate(_SUPERSCRIPTS) if abs(power) != 1 else ""))
    text = "·".join(numerator) or "1"
    return text + ("/" + "·".join(denominator) if denominator else "")


def format_value(value) -> str:
    """A coordinate value for a title or legend: '9', '0.5', '10,000', 'gap_flow'."""
    if isinstance(value, (str, np.str_)):
        return str(value)
    value = float(value)
    if not math.isfinite(value):
        return str(value)
    if abs(value) >= 1000:
        return f"{value:,.0f}"
    return f"{value:.3g}"


def tick_format(value, _pos=None) -> str:
    """Tick labels without offsets or powers of ten: 40,000 rather than 4 with ×10⁴."""
    if value == 0:
        return "0"
    if abs(value) >= 1000:
        return f"{value:,.0f}"
    return f"{value:.4g}"


class TickFormatter(ticker.Formatter):
    """Plain tick labels with the same number of decimals along an axis: 0.9, 1.0, 1.1 (not 1) and
    40,000 (not 4 with an offset ×10⁴). Logarithmic axes get each value as short as it goes."""

    def __call__(self, value, pos=None):
        return tick_format(value)

    def format_ticks(self, values):
        values = [float(v) for v in values]
        if len(values) < 2 or self.axis is not None and self.axis.get_scale() != "linear":
            return [tick_format(v) for v in values]
        step = min(abs(b - a) for a, b in zip(values, values[1:])) or 1.0
        decimals = max(0, min(8, -math.floor(math.log10(step) + 1e-9)))
        # a step like 0.25 needs one more decimal than its order of magnitude
        while decimals < 8 and any(abs(round(v, decimals) - v) > 1e-6 * step for v in values):
            decimals += 1
        return [f"{v:,.{decimals}f}" if v != 0 else "0" for v in values]


@dataclass(frozen=True)
class Quantity:
    """How one coordinate or variable is shown: its label and the conversion to display units."""

    name: str
    short_name: str
    unit_label: str  # "rpm", "-" for a dimensionless number, "" for text
    convert: Callable[[np.ndarray], np.ndarray]
    is_text: bool = False

    @property
    def label(self) -> str:
        """Axis label with the unit: 'rotary speed [rpm]'; text coordinates have no unit."""
        return self.short_name if self.is_text else f"{self.short_name} [{self.unit_label}]"

    def describe(self, value) -> str:
        """'mud density = 9 ppg', 'restitution = 0.5', 'added-mass model = gap_flow'."""
        if self.is_text:
            return f"{self.short_name} = {value}"
        shown = format_value(self.convert(np.asarray(value, dtype=float)))
        unit = "" if self.unit_label == "-" else f" {self.unit_label}"
        return f"{self.short_name} = {shown}{unit}"

    def value_text(self, value) -> str:
        """A value in display units with its unit, for a legend entry: '10,000 lbf'."""
        if self.is_text:
            return str(value)
        shown = format_value(self.convert(np.asarray(value, dtype=float)))
        return shown if self.unit_label == "-" else f"{shown} {self.unit_label}"


def _converter(from_unit: str, to_unit: str) -> Callable[[np.ndarray], np.ndarray]:
    if from_unit == to_unit or not from_unit:
        return lambda values: np.asarray(values, dtype=float)
    factor = ureg.Quantity(1.0, from_unit).to(to_unit).magnitude
    offset = ureg.Quantity(0.0, from_unit).to(to_unit).magnitude
    if offset != 0.0:  # an affine unit (temperatures); convert exactly
        return lambda values: ureg.Quantity(np.asarray(values, dtype=float), from_unit).to(to_unit).magnitude
    return lambda values: np.asarray(values, dtype=float) * factor


def short_name(name: str) -> str:
    """What a reader calls an input or output: :data:`SHORT_NAMES`' name, else its own with spaces ("mud density")."""
    return SHORT_NAMES.get(name, name.replace("_", " "))


def quantity(data: xr.DataArray, unit: str | None = None) -> Quantity:
    """The display of a coordinate or output, from its ``units``/``display_units`` attributes.

    unit : force this display unit (pint spelling, also the label), e.g. "rpm" where a chart's
        arithmetic needs it.
    """
    name = str(data.name)
    short = short_name(name)
    if data.dtype.kind in "USO":
        return Quantity(name, short, "", lambda values: values, is_text=True)
    si = data.attrs.get("units", "")
    source = pint_unit(si)
    display = data.attrs.get("display_units")
    if unit:
        target, label = unit, unit
    elif display:
        target, label = display, display
    else:
        target, label = display_unit(name, si)
        if target == source:
            label = pretty_unit(si)
    try:
        convert = _converter(source, pint_unit(target))
    except Exception:  # an unknown unit: show SI rather than fail the chart
        convert, label = _converter("", ""), pretty_unit(si)
    return Quantity(name, short, label, convert)


def figure_labels(figure) -> dict[str, list[str]]:
    """The texts a reader sees on a figure, for checks: axis and colour-bar labels, titles, legends.

    Returns a dict with ``xlabels``, ``ylabels`` (colour-bar labels included: a vertical colour bar
    is an axes whose y label is the bar's label), ``titles`` (panel titles and the figure title, the last as one line)
    and ``legend`` (legend entries and titles).
    """
    visible = [ax for ax in figure.axes if ax.get_visible()]
    out = {
        "xlabels": [ax.get_xlabel() for ax in visible if ax.get_xlabel()],
        "ylabels": [ax.get_ylabel() for ax in visible if ax.get_ylabel()],
        "titles": [ax.get_title() for ax in visible if ax.get_title()],
        "legend": [],
    }
    if figure.get_suptitle():  # as one line: its wrapping to the figure's width undone
        out["titles"].append(" ".join(figure.get_suptitle().split()))
    for legend in list(figure.legends) + [ax.get_legend() for ax in visible if ax.get_legend()]:
        if legend.get_title().get_text():
            out["legend"].append(legend.get_title().get_text())
        out["legend"] += [text.get_text() for text in legend.get_texts()]
    return out
