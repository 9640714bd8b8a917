"""Stress, contact force and fatigue life over rotary speed × axial load, with the design limits drawn in.

Each chart is one figure for the whole study: the other swept inputs are reduced to the worst case over
every answered point — ok, or not converged with its values and error estimate, whose cells are veiled with the
error written in (see :mod:`study.charts.plane`) — the limits are outlines of the cells over them as computed (from
the dataset's ``yield_utilisation``, ``endurance_utilisation`` and ``fatigue_life``, docs/model.md §5.1; whether a
veiled cell's limit is decided at its error is the envelope's verdict), and the rotary speeds to avoid
(:mod:`study.charts.critical`) are shaded bands. Each colour scale includes its limit (the yield strength, the
fatigue target), and each caption names the legend's entries, so it says only what is drawn.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib.colors import LogNorm

from study.charts import design
from study.charts.critical import avoid_bands
from study.charts.design import Chart
from study.charts.labels import format_value, quantity
from study.charts.plane import answered_values, plane, plane_chart, worst_panel
from study.physics.fatigue import MEAN_STRESS_CORRECTIONS, SN_CURVES
from study.physics.materials import grade_strengths

#: Target life of the fatigue chart and the envelope unless given [h].
DEFAULT_TARGET_LIFE_HOURS = 1000.0
HOUR = 3600.0  # s
YIELD_STYLE = {"colors": "k", "linewidths": 2.2}
ENDURANCE_STYLE = {"colors": "#08519c", "linewidths": 2.2, "linestyles": "--"}
LIFE_STYLE = {"colors": "k", "linewidths": 2.2}
WORST = "worst case over every answered point"


def _scalar(ds: xr.Dataset, name: str, default=None):
    """A fixed input's value; the values joined by "/" where it is swept; ``default`` when absent."""
    if name not in ds.coords:
        return default
    values = np.atleast_1d(ds[name].values)
    if values.size == 1:
        value = values[0]
        return value.item() if hasattr(value, "item") else value
    return "/".join(str(v) for v in values)


def yield_strengths(ds: xr.Dataset) -> list[tuple[str, float]]:
    """(grade, yield strength [Pa]) of the dataset: the grade's minimum unless ``yield_strength`` is given."""
    grades = np.atleast_1d(ds["pipe_grade"].values) if "pipe_grade" in ds.coords else np.array(["E-75"])
    given = np.atleast_1d(ds["yield_strength"].values) if "yield_strength" in ds.coords else np.array([None])
    return [(str(g), grade_strengths(str(g), None if y is None or not np.isfinite(float(y)) else float(y))[0])
            for g in grades for y in given]


def _over(ds: xr.Dataset, p, name: str, above: float = 1.0) -> np.ndarray:
    """Cells where some answered point's ``name`` is above the limit (as computed: a veiled cell's point may be
    undecided, see the envelope)."""
    values = answered_values(ds, name)
    return p.reduce(values > above, "any")


def stress_limit_maps(ds: xr.Dataset) -> list[Chart]:
    """Maximum normal stress with the grade's yield outlined, and alternating bending stress with the endurance
    limit outlined, over rotary speed × axial load (worst case over the other inputs, every answered point), with the
    critical-speed bands. Without both speed and load swept: the line charts of :func:`design.stress_maps`."""
    names = [n for n in design.STRESSES if n in ds.data_vars]
    p = plane(ds)
    if not names:
        return []
    if p is None:
        return design.stress_maps(ds)
    strengths = yield_strengths(ds)
    panels = []
    for name in names:
        q = quantity(ds[name])
        panel = worst_panel(p, ds, name, "max", q.label, f"{q.short_name}, {WORST}")
        if name == "max_normal_stress" and "yield_utilisation" in ds.data_vars:
            yields = ", ".join(f"{g} {format_value(q.convert(s))} {q.unit_label}" for g, s in strengths)
            panel.limits.append((_over(ds, p, "yield_utilisation"), f"black outline, hatched: over the yield strength "
                                 f"({yields}) as computed", YIELD_STYLE))
            panel.marks = [float(q.convert(s)) for _, s in strengths]
            panel.title += "\nbar line: yield strength"
        if name == "alternating_bending_stress" and "endurance_utilisation" in ds.data_vars:
            panel.limits.append((_over(ds, p, "endurance_utilisation"), "dashed blue outline, hatched: over the "
                                 "endurance limit (tool joint, mean-stress corrected) as computed", ENDURANCE_STYLE))
        panels.append(panel)
    context = p.context("worst case (highest stress)") + [_fatigue_text(ds)]
    caption = ("The highest stress the pipe sees at each rotary speed and load over the other swept inputs, every "
               "answered point counted.")
    return [plane_chart(p, "stress_limits", "Pipe stresses against the grade's yield and endurance limits", panels,
                        context, caption, bands=avoid_bands(p))]


def contact_force_map(ds: xr.Dataset) -> list[Chart]:
    """Peak contact force against the wall over rotary speed × axial load, worst case over the other inputs."""
    p = plane(ds)
    if p is None or "peak_contact_force" not in ds.data_vars:
        return []
    q = quantity(ds["peak_contact_force"])
    panel = worst_panel(p, ds, "peak_contact_force", "max", q.label, f"{q.short_name}, {WORST}", cmap="PuRd")
    caption = ("The hardest blow of the pipe against the bore-hole wall at each rotary speed and load (worst case "
               "over the other swept inputs, every answered point counted)." + _strike_force_text(ds))
    return [plane_chart(p, "contact_force", "Peak contact force against the wall", [panel],
                        p.context("worst case (highest force)"), caption, bands=avoid_bands(p))]


def _strike_force_text(ds: xr.Dataset) -> str:
    """Where the reference model answered: at how many of its points the peak force is the strikes' local model's
    (output ``local_strike_force``, docs/reference_model.md §2.3); empty where no point's is."""
    if "local_strike_force" not in ds.data_vars:
        return ""
    flag = ds["local_strike_force"].values.ravel()
    local, answered = int(np.sum(flag == 1.0)), int(np.sum(np.isfinite(flag)))
    if local == 0:
        return ""
    return (f" At {local} of the {answered} points the reference model answered, the force is that of the strikes' "
            "local model (the tool joint's mass on an infinite beam against the Hertz wall, from each strike's onset "
            "speed), which states a smaller error there than the modes' own contact (local_strike_force).")


def _fatigue_text(ds: xr.Dataset) -> str:
    """The fatigue limits' inputs: S-N curve, mean-stress correction and the tool joint's stress concentration."""
    curve = _scalar(ds, "sn_curve", "B1")
    correction = _scalar(ds, "mean_stress_correction", "goodman")
    kt = _scalar(ds, "stress_concentration", 1.0)
    curve_text = SN_CURVES[curve].description if curve in SN_CURVES else f"S-N curve {curve}"
    correction_text = MEAN_STRESS_CORRECTIONS.get(correction, str(correction))
    return (f"S-N curve: {curve_text}; mean stress: {correction_text}; tool-joint stress concentration "
            f"{format_value(kt) if not isinstance(kt, str) else kt}")


def _damage_text(ds: xr.Dataset) -> str:
    """How the damage was counted (study.solvers.model.utilisation.add_limits): Miner's sum over the rainflow-counted
    stress history where the reference model answered (docs/model.md §5.1), one cycle of the alternating stress per
    revolution (``cycles_per_revolution``) elsewhere."""
    cycles = _scalar(ds, "cycles_per_revolution", 1.0)
    per_revolution = (f"{format_value(cycles) if not isinstance(cycles, str) else cycles} cycle(s) of the alternating "
                      "stress per revolution")
    counted = 0
    if "method" in ds.data_vars and "fatigue_life" in ds.data_vars:
        answered = answered_values(ds, "fatigue_life").notnull()
        counted = int((answered & (ds["method"].astype(str) == "reference")).sum())
    if not counted:
        return f"Miner's rule, {per_revolution}"
    return (f"Miner's rule: at the reference model's {counted} points over its stress history counted by rainflow "
            f"(ASTM E1049), elsewhere {per_revolution}")


def fatigue_life_map(ds: xr.Dataset, target_hours: float = DEFAULT_TARGET_LIFE_HOURS) -> list[Chart]:
    """Hours of rotation to fatigue failure (Miner's sum 1) over rotary speed × axial load, on a log colour scale;
    the shortest life over the other inputs (every answered point); outlined: the cells under ``target_hours``."""
    p = plane(ds)
    if p is None or "fatigue_life" not in ds.data_vars:
        return []
    panel = worst_panel(p, ds, "fatigue_life", "min", "hours to failure [h]",
                        f"hours of rotation to fatigue failure, {WORST}", scale=lambda v: np.asarray(v) / HOUR,
                        cmap="RdYlGn", marks=[target_hours])
    hours = panel.values
    finite = hours[np.isfinite(hours) & (hours > 0)]
    if not finite.size:
        return []
    # the scale shows its target: at least a factor of 3 either side of it
    low, high = min(float(finite.min()), target_hours / 3.0), max(float(finite.max()), target_hours * 3.0)
    panel.values = np.where(np.isposinf(hours), high, hours)  # no damage at all: the top of the scale
    panel.norm = LogNorm(low, high)
    short = p.reduce(answered_values(ds, "fatigue_life") < target_hours * HOUR, "any")
    panel.limits.append((short, f"black outline, hatched: life under the target {format_value(target_hours)} h as "
                         "computed", LIFE_STYLE))
    panel.title += f"\nbar line: target {format_value(target_hours)} h"
    context = p.context("shortest life") + [_fatigue_text(ds), _damage_text(ds)]
    caption = ("How many hours the pipe can rotate at each speed and load before fatigue cracks it (worst case over "
               "the other swept inputs, every answered point counted, log scale; a stress off by n % moves the life "
               "by up to (1 + n)⁵).")
    return [plane_chart(p, "fatigue_life", "Fatigue: hours to failure", [panel], context, caption,
                        bands=avoid_bands(p))]
