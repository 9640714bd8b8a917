"""Stress maxima located, not sampled (docs/model.md §5).

A method's fields are first sampled on its grids over the span and the period; the largest value found
there is then *located*: the field is evaluated again on a 9 × 9 grid over the cells around it, the
window closing in on the largest value each round, until the largest value changes by less than the
asked relative tolerance between rounds. The change of the last round is what is left of the sampling
error; the caller adds it to the method's error estimate.

``field_at(kind, x, t)`` is any callable giving the field ``kind`` ("deflection", "moment", "shear") on
the grid t × x (shape t.shape + x.shape) — the fast or series fields of the periodic methods.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

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
