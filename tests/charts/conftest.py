"""A synthetic design study for the decision charts, built as study.workflow.dataset writes one.

The stresses are made-up smooth functions of the inputs; everything derived from them is computed by the
project's own physics (yield and endurance utilisation and life by study.physics.limits.design_limits, the
section's stiffness and masses as study.physics.section does), so the limits in the charts are consistent.
"""

import math

import numpy as np
import pytest
import xarray as xr

from study.physics.limits import design_limits
from study.solvers.model.result import STATUS

RPM = 2 * math.pi / 60  # rad/s per rpm
LBF = 4.4482216152605  # N
PPG = 119.82642731689663  # kg/m^3
PSI = 6894.757293168361  # Pa
INCH = 0.0254
FT = 0.3048

OD, ID = 4.5 * INCH, 3.826 * INCH
AREA = math.pi / 4 * (OD**2 - ID**2)
EI = 206.84e9 * math.pi / 64 * (OD**4 - ID**4)
STEEL = 7850.0 * AREA  # kg/m, bare pipe
AXES = {"rotary_speed": np.arange(60.0, 301.0, 20.0), "axial_tension": np.array([5000.0, 10000.0, 20000.0, 40000.0]),
        "restitution": np.array([0.2, 0.8]), "mud_density": np.array([9.0, 12.0])}
SCALE = {"rotary_speed": RPM, "axial_tension": LBF, "restitution": 1.0, "mud_density": PPG}
ATTRS = {"rotary_speed": {"units": "rad s-1", "display_units": "rpm", "long_name": "rotary speed"},
         "axial_tension": {"units": "N", "display_units": "lbf", "long_name": "axial tension"},
         "restitution": {"units": "1", "long_name": "coefficient of restitution"},
         "mud_density": {"units": "kg m-3", "display_units": "ppg", "long_name": "mud density"}}


def build(axes=None, status=None, mud_mass=True):
    """The study over ``axes`` (display units); ``status`` maps a flag to a function of the display-unit inputs
    (broadcast DataArrays) marking where it is set; where not ok, outputs that need a solution are NaN."""
    axes = axes or AXES
    ds = xr.Dataset(coords={d: xr.Variable(d, np.asarray(v, float) * SCALE[d], ATTRS[d]) for d, v in axes.items()})
    scalars = {"joint_length": (9.144, "m", "ft"), "outer_diameter": (OD, "m", "in"), "inner_diameter": (ID, "m", "in"),
               "stress_concentration": (1.0, "1", None), "cycles_per_revolution": (1.0, "1", None)}
    for name, (value, unit, display) in scalars.items():
        ds.coords[name] = xr.Variable((), value, {"units": unit, **({"display_units": display} if display else {})})
    for name, value in {"pipe_grade": "E-75", "sn_curve": "B1", "mean_stress_correction": "goodman"}.items():
        ds.coords[name] = xr.Variable((), value)
    g = {d: ds[d] / SCALE[d] for d in axes}
    n, t = g["rotary_speed"], g["axial_tension"]
    e = g.get("restitution", 0.5)
    rho = g.get("mud_density", 10.0)
    dims = list(axes)

    def full(x):
        return (x + xr.zeros_like(sum(ds[d] for d in dims))).transpose(*dims)

    codes = full(xr.zeros_like(n, dtype=np.int8))
    for flag, where in (status or {}).items():
        codes = xr.where(full(where(g)), STATUS[flag][0], codes).astype(np.int8)
    ok = codes == 0
    normal = full(PSI * (8000 + 200 * n + 0.5 * t) * (1 + e)).where(ok)
    alternating = full(PSI * (500 + 15 * n) * (1 + e / 2) * (rho / 10)).where(ok)
    limits = design_limits(normal.values, alternating.values, full(t * LBF).values / AREA, full(n * RPM).values)
    mud = rho * PPG * (math.pi / 4 * ID**2 + 1.2 * math.pi / 4 * OD**2) if mud_mass else 0 * rho
    values = {
        "max_normal_stress": (normal, "Pa"), "alternating_bending_stress": (alternating, "Pa"),
        "peak_contact_force": (full(LBF * 100 * n * (1 + e)).where(ok), "N"),
        "span_length": (full(FT * (300 - 0.3 * n) + 0 * t).where(ok), "m"),
        "bending_stiffness": (full(EI + 0 * n), "N m2"), "effective_tension": (full(t * LBF + 0 * n), "N"),
        "mass_per_length": (full(STEEL + mud + 0 * n + 0 * t), "kg m-1"),
        # as study.solvers.model.utilisation: limits only where the stresses are (design_limits gives life 0 for NaN)
        "yield_utilisation": (np.where(ok, limits.yield_utilisation, np.nan), "1"),
        "endurance_utilisation": (np.where(ok, limits.endurance_utilisation, np.nan), "1"),
        "fatigue_life": (np.where(ok, limits.fatigue_life, np.nan), "s"),
    }
    for name, (data, unit) in values.items():
        ds[name] = xr.Variable(dims, np.asarray(getattr(data, "values", data), float), {"units": unit})
    ds["status"] = xr.Variable(dims, codes.values, {"flag_values": np.array([c for c, _ in STATUS.values()], np.int8),
                                                    "flag_meanings": " ".join(STATUS)})
    ds["method"] = xr.Variable(dims, np.full(codes.shape, "fast"))
    ds.attrs.update(title="synthetic decision study", study_name="synthetic", source="study 0.2.0",
                    date_created="2026-11-24T09:00:00+00:00", config_hash="abc123",
                    config='name = "synthetic"\n[load]\nrotary_speed = "300 rpm"\n')
    return ds


@pytest.fixture(scope="session")
def study():
    """The study with no valid span at the lowest load above 200 rpm at restitution 0.8."""
    return build(status={"no_span": lambda g: (g["axial_tension"] == 5000) & (g["rotary_speed"] > 200)
                         & (g["restitution"] == 0.8)})


@pytest.fixture(scope="session")
def build_study():
    """:func:`build`, for a test that needs other axes or flags."""
    return build
