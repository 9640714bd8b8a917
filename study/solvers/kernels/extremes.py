"""Stress maxima located, not sampled (docs/model.md §5).

A method's fields are first sampled on its grids over the span and the period; the largest value found
there is then *located*: the field is evaluated again on a 9 × 9 grid over the cells around it, the
window closing in on the largest value each round, until the largest value changes by less than the
asked relative tolerance between rounds. The change of the last round is what is left of the sampling
error; the caller adds it to the method's error estimate.

``field_at(kind, x, t)`` is any callable giving the field ``kind`` ("deflection", "moment", "shear") on
the grid t × x (shape t.shape + x.shape) — the fast or series fields of the periodic methods.
:func:`stresses_from_fields` makes a point's deflection and stress maxima from its fields, the same for every method
that has them (the periodic methods, the damped solution, the time domain).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numba
import numpy as np

from study.physics import section
from study.solvers.model.options import DEFAULT_TOLERANCE
from study.solvers.model.scene import Scene

FieldAt = Callable[[str, np.ndarray, np.ndarray], np.ndarray]

POINTS = 9  #: points per direction of each zoom round
MAX_ROUNDS = 12  #: zoom rounds at most (each shrinks the window fourfold)


@dataclass
class Located:
    """A located extreme: value, where (x [m], t [s]) and the relative change of its last round."""

    value: float
    x: float
    t: float
    residual: float


def _window(grid: np.ndarray, index: int) -> tuple[float, float]:
    """The interval between the neighbours of grid[index] (the grid's ends where it has none)."""
    return float(grid[max(index - 1, 0)]), float(grid[min(index + 1, grid.size - 1)])


def locate(field_at: FieldAt, kind: str, x: np.ndarray, t: np.ndarray, i: int, j: int, tolerance: float,
           sign: float = 0.0) -> Located:
    """Locate the extreme of ``kind`` sampled at (t[i], x[j]): the largest |f| (``sign`` 0), the largest f
    (+1) or the smallest f (−1) in the cells around it, by zooming (module doc), to ``tolerance``
    (relative change between rounds)."""
    def score(values):
        return np.abs(values) if sign == 0 else sign * values

    (x0, x1), (t0, t1) = _window(x, j), _window(t, i)
    best = Located(float(field_at(kind, x[j:j + 1], t[i:i + 1])[0, 0]), float(x[j]), float(t[i]), np.inf)
    for _ in range(MAX_ROUNDS):
        xs, ts = np.linspace(x0, x1, POINTS), np.linspace(t0, t1, POINTS)
        values = field_at(kind, xs, ts)
        r, c = np.unravel_index(np.nanargmax(score(values)), values.shape)
        found = float(values[r, c])
        if score(np.array(found)) >= score(np.array(best.value)):
            change = abs(found - best.value) / max(abs(found), 1e-300)
            best = Located(found, float(xs[c]), float(ts[r]), change)
        else:
            best = Located(best.value, best.x, best.t, 0.0)
        if best.residual <= tolerance:
            break
        dx, dt = (x1 - x0) / (POINTS - 1), (t1 - t0) / (POINTS - 1)
        x0, x1 = max(best.x - dx, x[0]), min(best.x + dx, x[-1])
        t0, t1 = max(best.t - dt, t[0]), min(best.t + dt, t[-1])
    return best


def locate_half_range(field_at: FieldAt, kind: str, x: np.ndarray, t: np.ndarray, values: np.ndarray,
                      tolerance: float) -> Located:
    """Half the range over time of ``kind`` at its worst section, located: the section x and the times of
    its largest and smallest value are zoomed together (module doc). ``values``: the field sampled on
    t × x. Returns the half range, the section, the time of its largest value and the last change."""
    half = 0.5 * (np.nanmax(values, axis=0) - np.nanmin(values, axis=0))
    j = int(np.nanargmax(half))
    i_hi, i_lo = int(np.nanargmax(values[:, j])), int(np.nanargmin(values[:, j]))
    (x0, x1), (a0, a1), (b0, b1) = _window(x, j), _window(t, i_hi), _window(t, i_lo)
    best = Located(float(half[j]), float(x[j]), float(t[i_hi]), np.inf)
    for _ in range(MAX_ROUNDS):
        xs = np.linspace(x0, x1, POINTS)
        hi_t, lo_t = np.linspace(a0, a1, POINTS), np.linspace(b0, b1, POINTS)
        f = field_at(kind, xs, np.concatenate([hi_t, lo_t]))
        tops, bottoms = f[:POINTS], f[POINTS:]
        ranges = 0.5 * (np.nanmax(tops, axis=0) - np.nanmin(bottoms, axis=0))
        c = int(np.nanargmax(ranges))
        r_hi, r_lo = int(np.nanargmax(tops[:, c])), int(np.nanargmin(bottoms[:, c]))
        if ranges[c] >= best.value:
            change = abs(ranges[c] - best.value) / max(abs(ranges[c]), 1e-300)
            best = Located(float(ranges[c]), float(xs[c]), float(hi_t[r_hi]), change)
        else:
            best = Located(best.value, best.x, best.t, 0.0)
        if best.residual <= tolerance:
            break
        dx, da, db = (x1 - x0) / (POINTS - 1), (a1 - a0) / (POINTS - 1), (b1 - b0) / (POINTS - 1)
        x0, x1 = max(xs[c] - dx, x[0]), min(xs[c] + dx, x[-1])
        a0, a1 = max(hi_t[r_hi] - da, t[0]), min(hi_t[r_hi] + da, t[-1])
        b0, b1 = max(lo_t[r_lo] - db, t[0]), min(lo_t[r_lo] + db, t[-1])
    return best


def stresses_from_fields(scene: Scene, x, t, deflection, moment, shear=None, mirrored: bool | None = None,
                         field_at=None, tolerance: float | None = None) -> dict[str, float]:
    """Deflection and stress maxima over the span and the period from the fields (docs/model.md §5, paper
    eq. 37–38) — the same for every method, whatever made the fields.

    x [m], t [s] (the half period for the alternating pattern: the other half mirrors it), deflection
    y [m], moment M_b = −EI y'' [N m], shear V = −EI y''' [N] (None: no shear outputs), each of shape
    t × x. ``mirrored``: whether the other half period is the mirror image (default: the alternating
    pattern of ``scene``). Bending stress σ_b = M_b r_o/I; combined normal stress |T0/A_s| + |σ_b|
    (the larger of T0/A_s ± σ_b); shear stress 2V/A_s (thin tube); alternating bending stress: half the
    range of σ_b over the period at the worst section (σ(t + τ/2) = −σ(t) when mirrored).

    With ``field_at(kind, x, t)`` (the fields anywhere, shape t × x) each maximum found on the grid is
    located to ``tolerance`` (relative) by :func:`locate`, and ``location_residual`` is
    the largest relative change of the last refinement round — what is left of the sampling error.
    """
    p = scene.props
    mirrored = scene.pattern == "alternating" if mirrored is None else mirrored
    x, t = np.asarray(x, dtype=float), np.asarray(t, dtype=float)
    r_o, r_i = scene.outer_radius, scene.inner_radius
    inertia = float(section.second_moment_of_area(r_o, r_i))
    area = p["steel_area"]
    deflection, moment = np.asarray(deflection, dtype=float), np.asarray(moment, dtype=float)
    i_b, largest, smallest = _field_extremes(moment, columns=True)
    scale = r_o / inertia  # σ_b = M_b r_o/I
    # over the full period σ(t + τ/2) = −σ(t) when mirrored, so half its range is max |σ| there
    half_range = np.maximum(largest, -smallest) if mirrored else 0.5 * (largest - smallest)
    axial = abs(scene.axial_tension) / area
    i_y = _field_extremes(deflection)[0]
    out = {
        "max_deflection": float(np.abs(deflection[i_y])),
        "max_bending_stress": float(np.abs(moment[i_b]) * scale),
        "max_normal_stress": float(axial + np.abs(moment[i_b]) * scale),
        "max_normal_stress_x": float(x[i_b[1]]),
        "max_normal_stress_t": float(t[i_b[0]]),
        "alternating_bending_stress": float(np.nanmax(half_range) * scale),
    }
    if shear is not None:
        shear = np.asarray(shear, dtype=float)
        i_s = _field_extremes(shear)[0]
        out.update(max_shear_stress=float(2.0 * np.abs(shear[i_s]) / area), max_shear_stress_x=float(x[i_s[1]]),
                   max_shear_stress_t=float(t[i_s[0]]))
    if field_at is None:
        return out
    tol = 0.1 * (DEFAULT_TOLERANCE if tolerance is None else tolerance)
    y = locate(field_at, "deflection", x, t, *i_y, tol)
    m = locate(field_at, "moment", x, t, *i_b, tol)
    out.update(max_deflection=max(out["max_deflection"], abs(y.value)),
               max_bending_stress=abs(m.value) * scale, max_normal_stress=axial + abs(m.value) * scale,
               max_normal_stress_x=m.x, max_normal_stress_t=m.t)
    residuals = [y.residual, m.residual]
    if mirrored:
        out["alternating_bending_stress"] = max(out["alternating_bending_stress"], out["max_bending_stress"])
    else:
        a = locate_half_range(field_at, "moment", x, t, moment, tol)
        out["alternating_bending_stress"] = max(out["alternating_bending_stress"], a.value * scale)
        residuals.append(a.residual)
    if shear is not None:
        v = locate(field_at, "shear", x, t, *i_s, tol)
        out.update(max_shear_stress=max(out["max_shear_stress"], 2.0 * abs(v.value) / area),
                   max_shear_stress_x=v.x, max_shear_stress_t=v.t)
        residuals.append(v.residual)
    out["location_residual"] = float(max(residuals))
    return out


#: Relative difference below which two maxima of a field are equal: the first in time (then x) is reported,
#: so that rounding cannot move the reported (x, t) of a maximum reached twice (a symmetric motion).
TIE_TOLERANCE = 1e-9


def _field_extremes(values, columns: bool = False) -> tuple:
    """(index of the largest |value| ignoring NaN — the first within :data:`TIE_TOLERANCE` of it, in
    time, then x — and with ``columns`` the largest and smallest value of
    each column, NaN in a column with a NaN) of a field of shape t × x; a ValueError when every value is
    NaN (as np.nanargmax)."""
    values = np.asarray(values, dtype=float)  # any layout: the fields are views of one product
    index, largest, smallest = _extremes_kernel(values, columns)
    if index < 0:
        raise ValueError("all the field's values are NaN (a resonant or buckled mode)")
    return np.unravel_index(index, values.shape), largest, smallest


@numba.njit(cache=True, nogil=True)
def _extremes_kernel(values, columns):
    """Three passes without data-dependent jumps in the first two, so that they run at memory speed:
    the largest |value| (NaN never compares larger), each column's largest and smallest (a NaN sticks),
    then the first value within TIE_TOLERANCE of the largest, in time, then x (-1: none)."""
    rows, cols = values.shape
    peak = -1.0
    for i in range(rows):
        for j in range(cols):
            size = abs(values[i, j])
            peak = size if size > peak else peak
    largest, smallest = np.full(cols, -np.inf), np.full(cols, np.inf)
    if columns:
        for i in range(rows):
            for j in range(cols):
                v = values[i, j]
                largest[j] = v if (v > largest[j] or v != v) else largest[j]
                smallest[j] = v if (v < smallest[j] or v != v) else smallest[j]
    if peak < 0.0:  # every value NaN
        return -1, largest, smallest
    floor = peak * (1.0 - TIE_TOLERANCE)
    for i in range(rows):
        for j in range(cols):
            if abs(values[i, j]) >= floor:
                return i * cols + j, largest, smallest
    return -1, largest, smallest
