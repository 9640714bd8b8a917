"""Fatigue of the rotating pipe: S-N curves, mean-stress correction, Miner's damage rate and life.

Pure functions of numpy arrays (broadcasting), SI units inside (stresses in Pa, rotary speed in
rad/s, damage rate in 1/s, life in s; a chart shows them per hour and in hours).

- **S-N curves**: the two-slope design curves in air of DNV-RP-C203 (DNV GL, *Fatigue design of
  offshore steel structures*, April 2016, Table 2-1): log₁₀ N = log₁₀ ā₁ − m₁ log₁₀ Δσ up to
  N = 10⁷ cycles, log₁₀ ā₂ − m₂ log₁₀ Δσ beyond, with Δσ the stress *range* in MPa. Curve B1, the
  highest class, is DNV-RP-C203's curve for non-welded base material (its Appendix A classifies
  details); we take it for the seamless, unwelded pipe body, and it is the default. The lower
  classes B2, C and D are offered for a rougher or notched detail. They are design curves (mean
  minus two standard deviations of log N).
- **Endurance limit**: the stress range at 10⁷ cycles that Table 2-1 prints as each curve's
  fatigue limit; as an amplitude, half of it. Below it the curve continues on the shallower slope
  m₂ (DNV-RP-C203 gives no cut-off for variable amplitude), so a point under the endurance limit
  still accumulates a little damage: the limit is a flag, not a switch.
- **Mean stress**: the axial (mean) stress enters through an equivalent fully reversed amplitude
  σ_ar, on Goodman's line (default), Gerber's parabola or Soderberg's line (Dowling, *Mechanical
  Behavior of Materials*, 4th ed., 2013, ch. 9, mean-stress effects; Budynas & Nisbett, *Shigley's
  Mechanical Engineering Design*, ch. 6, fluctuating stresses). A compressive mean is given no
  credit (σ_m taken as 0), the conservative choice for these rules.
- **Stress concentration**: the tool joint and its upset raise the local alternating bending stress
  above the pipe body's nominal value by a factor K_t ≥ 1 (an input); it multiplies the alternating
  stress, not the mean, as DNV-RP-C203 applies its stress concentration factors (Section 3) to the
  stress range.
- **Damage**: Miner's rule (Miner 1945, J. Appl. Mech. 12, A159, doi:10.1115/1.4009458) at a
  constant amplitude: each stress cycle does damage 1/N(Δσ); a fibre of a rotating bent pipe sees
  ``cycles_per_revolution`` cycles per turn (one for rotating bending: Hansford & Lubinski 1966,
  *Cumulative fatigue damage of drill pipe in dog-legs*, JPT 18(3), 359, doi:10.2118/1258-PA).
  Failure at D = 1.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np

MPA = 1e6  # Pa


@dataclass(frozen=True)
class SNCurve:
    """A two-slope S-N curve of DNV-RP-C203 Table 2-1 (stress range in MPa)."""

    m1: float
    log_a1: float
    m2: float
    log_a2: float
    printed_fatigue_limit: float  # stress range at the knee as printed [MPa]
    description: str
    knee_cycles: float = 1e7


#: DNV-RP-C203 (April 2016) Table 2-1, S-N curves in air: name -> curve.
SN_CURVES = {
    "B1": SNCurve(4.0, 15.117, 5.0, 17.146, 106.97,
                  "DNV-RP-C203 B1 in air: non-welded base material (taken for the pipe body)"),
    "B2": SNCurve(4.0, 14.885, 5.0, 16.856, 93.59, "DNV-RP-C203 B2 in air"),
    "C": SNCurve(3.0, 12.592, 5.0, 16.320, 73.10, "DNV-RP-C203 C in air"),
    "D": SNCurve(3.0, 12.164, 5.0, 15.606, 52.63, "DNV-RP-C203 D in air"),
}

#: Mean-stress corrections: name -> the rule it applies.
MEAN_STRESS_CORRECTIONS = {
    "goodman": "Goodman's line: sigma_a/sigma_ar + sigma_m/sigma_u = 1",
    "gerber": "Gerber's parabola: sigma_a/sigma_ar + (sigma_m/sigma_u)^2 = 1",
    "soderberg": "Soderberg's line: sigma_a/sigma_ar + sigma_m/sigma_y = 1",
    "none": "no correction: sigma_ar = sigma_a",
}


def _curve(curve: str) -> SNCurve:
    if curve not in SN_CURVES:
        raise ValueError(f"fatigue S-N curve = {curve!r}; allowed: {', '.join(SN_CURVES)}")
    return SN_CURVES[curve]


def fatigue_limit(curve: str = "B1") -> float:
    """Stress *range* Δσ at the curve's knee (10⁷ cycles) [Pa], from its first segment."""
    c = _curve(curve)
    return MPA * 10.0 ** ((c.log_a1 - np.log10(c.knee_cycles)) / c.m1)


def endurance_limit(curve: str = "B1") -> float:
    """Endurance limit as a stress *amplitude* [Pa]: half the curve's fatigue-limit range."""
    return 0.5 * fatigue_limit(curve)


def cycles_to_failure(stress_range, curve: str = "B1"):
    """Cycles to failure N at a constant stress range Δσ [Pa] on a DNV-RP-C203 curve [-].

    Above the knee's stress range the first segment (slope m₁) applies, below it the second (m₂).
    A zero range never fails (N = inf); an infinite range fails at once (N = 0).
    """
    c = _curve(curve)
    s = np.asarray(stress_range, dtype=float) / MPA
    knee = fatigue_limit(curve) / MPA
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        log_s = np.log10(s)
        log_n = np.where(s >= knee, c.log_a1 - c.m1 * log_s, c.log_a2 - c.m2 * log_s)
        return 10.0**log_n


def equivalent_alternating_stress(alternating_stress, mean_stress, tensile_strength, yield_strength=None,
                                  correction: str = "goodman"):
    """Fully reversed amplitude σ_ar [Pa] with the same life as amplitude σ_a about mean σ_m.

    alternating_stress σ_a [Pa] (its magnitude is used), mean_stress σ_m [Pa] (a compressive mean is
    given no credit: σ_m < 0 counts as 0), tensile_strength σ_u [Pa], yield_strength σ_y [Pa] (for
    Soderberg only); correction one of :data:`MEAN_STRESS_CORRECTIONS`. Where the mean reaches the
    strength the rule allows no alternating stress at all and σ_ar is infinite.
    """
    if correction not in MEAN_STRESS_CORRECTIONS:
        raise ValueError(f"fatigue mean-stress correction = {correction!r}; "
                         f"allowed: {', '.join(MEAN_STRESS_CORRECTIONS)}")
    amplitude = np.abs(np.asarray(alternating_stress, dtype=float))
    mean = np.maximum(np.asarray(mean_stress, dtype=float), 0.0)
    if correction == "none":
        return amplitude * np.ones_like(mean)
    if correction == "soderberg":
        if yield_strength is None:
            raise ValueError("the Soderberg correction needs the yield strength")
        remaining = 1.0 - mean / np.asarray(yield_strength, dtype=float)
    elif correction == "gerber":
        remaining = 1.0 - (mean / np.asarray(tensile_strength, dtype=float)) ** 2
    else:
        remaining = 1.0 - mean / np.asarray(tensile_strength, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(remaining > 0.0, amplitude / np.where(remaining > 0.0, remaining, 1.0), np.inf)


def local_equivalent_amplitude(alternating_stress, mean_stress, tensile_strength, yield_strength=None, *,
                               stress_concentration=1.0, correction: str = "goodman"):
    """σ_ar [Pa] at the tool joint: K_t times the nominal alternating stress, corrected for the mean.

    stress_concentration K_t [-] multiplies the alternating (bending) stress only; the rest as
    :func:`equivalent_alternating_stress`.
    """
    local = np.asarray(stress_concentration, dtype=float) * np.asarray(alternating_stress, dtype=float)
    return equivalent_alternating_stress(local, mean_stress, tensile_strength, yield_strength, correction)


def endurance_utilisation(equivalent_amplitude, curve: str = "B1"):
    """σ_ar / endurance limit [-]: above 1 the alternating stress exceeds the endurance limit (a flag).

    equivalent_amplitude σ_ar [Pa] from :func:`local_equivalent_amplitude`.
    """
    return np.asarray(equivalent_amplitude, dtype=float) / endurance_limit(curve)


def damage_rate(equivalent_amplitude, rotary_speed, cycles_per_revolution=1.0, curve: str = "B1"):
    """Miner's damage per second of rotation [1/s] at a constant equivalent amplitude.

    equivalent_amplitude σ_ar [Pa] (fully reversed, so the range is 2 σ_ar), rotary_speed Ω [rad/s],
    cycles_per_revolution [-]: stress cycles a fibre sees per turn. Rate = (Ω/2π)·cycles/N(2 σ_ar);
    times 3600 for damage per hour.
    """
    cycles_per_second = np.asarray(cycles_per_revolution, dtype=float) * np.asarray(rotary_speed) / (2.0 * np.pi)
    n = cycles_to_failure(2.0 * np.asarray(equivalent_amplitude, dtype=float), curve)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(n > 0.0, cycles_per_second / np.where(n > 0.0, n, 1.0), np.inf)


def reversal_indices(stress) -> np.ndarray:
    """Indices of the reversals (turning points) of a history, its first and last point included: what ASTM E1049
    §5.4.4's rainflow counting reads of it (a plateau counts once, at its first point, as the ``rainflow`` package's
    ``reversals`` does). In numpy, so that a long recorded history reaches the counting as its few reversals."""
    x = np.asarray(stress, dtype=float).ravel()
    if x.size < 3:
        return np.arange(x.size)
    moved = np.flatnonzero(np.concatenate(([True], np.diff(x) != 0.0)))  # the first point of every plateau
    step = np.diff(x[moved])
    turns = np.flatnonzero(step[:-1] * step[1:] < 0.0) + 1
    keep = np.concatenate(([0], turns, [moved.size - 1])) if moved.size > 1 else np.array([0])
    return moved[keep]


def rainflow_cycles(stress, with_ends: bool = False):
    """The cycles of a stress history [Pa] by rainflow counting (ASTM E1049-85 (2017) §5.4.4, as implemented by the
    ``rainflow`` package): their ranges Δσ [Pa], means [Pa] and counts (1 a full cycle, 0.5 a half), each (C,);
    with ``with_ends`` also the indices into ``stress`` of each cycle's two reversals, in time order. A history whose
    impacts put several cycles into a revolution counts each, where one cycle per revolution of the largest range
    would miss the smaller ones. The history is reduced to its reversals first (:func:`reversal_indices`: the same
    count)."""
    x = np.asarray(stress, dtype=float).ravel()
    where = reversal_indices(x)
    ranges, means, counts, first, second = _rainflow_kernel(np.ascontiguousarray(x[where]))
    if with_ends:
        return ranges, means, counts, where[first], where[second]
    return ranges, means, counts


@numba.njit(cache=True, nogil=True)
def _rainflow_kernel(series):  # pragma: no cover - compiled; its Python twin is the rainflow package
    """(ranges, means, counts, first, second) of the cycles of ``series`` (C,) each, in the order the ``rainflow``
    package's ``extract_cycles`` (3.2.0) yields them, by its arithmetic (|x1 − x2|, 0.5 (x1 + x2)): ASTM E1049-85
    §5.4.4 on the series' reversals (the package's ``reversals``: a repeated value skipped, the first and the last
    point kept, none but the first for two points), the points kept on a stack; ``first``/``second`` the indices into
    ``series`` of each cycle's two reversals. Compiled: the package's generators cost some 20 µs a cycle."""
    n = series.size
    at = np.empty(n, np.int64)  # the reversals' indices, as rainflow.reversals yields them
    m = 0
    if n >= 2:
        at[0] = 0
        m = 1
        x_last, x = series[0], series[1]
        d_last = x - x_last
        last = -1
        for k in range(2, n):
            x_next = series[k]
            last = k
            if x_next == x:
                continue
            d_next = x_next - x
            if d_last * d_next < 0:
                at[m] = k - 1
                m += 1
            x_last, x = x, x_next
            d_last = d_next
        if last >= 0:
            at[m] = last
            m += 1
    ranges, means, counts = np.empty(n), np.empty(n), np.empty(n)
    first, second = np.empty(n, np.int64), np.empty(n, np.int64)
    stack = np.empty(n, np.int64)  # the package's deque: stack[lo:hi]
    lo, hi, c = 0, 0, 0
    for r in range(m):
        stack[hi] = at[r]
        hi += 1
        while hi - lo >= 3:
            x1, x2, x3 = series[stack[hi - 3]], series[stack[hi - 2]], series[stack[hi - 1]]
            if abs(x3 - x2) < abs(x2 - x1):
                break
            if hi - lo == 3:  # the range holds the starting point: a half cycle, the first point dropped
                i1, i2 = stack[lo], stack[lo + 1]
                ranges[c], means[c], counts[c] = abs(series[i1] - series[i2]), 0.5 * (series[i1] + series[i2]), 0.5
                first[c], second[c] = i1, i2
                c += 1
                lo += 1
            else:  # a full cycle: its peak and valley dropped
                i1, i2 = stack[hi - 3], stack[hi - 2]
                ranges[c], means[c], counts[c] = abs(series[i1] - series[i2]), 0.5 * (series[i1] + series[i2]), 1.0
                first[c], second[c] = i1, i2
                c += 1
                stack[hi - 3] = stack[hi - 1]
                hi -= 2
    while hi - lo > 1:  # the ranges left: half cycles
        i1, i2 = stack[lo], stack[lo + 1]
        ranges[c], means[c], counts[c] = abs(series[i1] - series[i2]), 0.5 * (series[i1] + series[i2]), 0.5
        first[c], second[c] = i1, i2
        c += 1
        lo += 1
    return ranges[:c], means[:c], counts[:c], first[:c], second[:c]


def history_damage(stress, tensile_strength, yield_strength=None, *, stress_concentration=1.0,
                   correction: str = "goodman", curve: str = "B1", segments=None, at=None):
    """Miner's damage [-] of a fibre's stress history [Pa]: the cycles by rainflow counting
    (:func:`rainflow_cycles`), each cycle's amplitude Δσ/2 times the stress concentration K_t and corrected for its
    own mean (:func:`equivalent_alternating_stress`), its damage count/N(2 σ_ar) (:func:`cycles_to_failure`),
    summed (Miner 1945).

    With ``segments`` (the first index of each of consecutive stretches of the history, the first 0) the damage of
    each stretch (S,): each cycle's damage spread over the stretches that the time between its two reversals spans,
    in proportion (``at``: the time of each point of the history, default its index), so that the revolutions of a
    periodic history get the same damage each wherever its cycles close, and the stretches' damages sum to the
    history's; their scatter says how well a mean over the stretches (revolutions) is known."""
    x = np.asarray(stress, dtype=float).ravel()
    ranges, means, counts, begins, ends = rainflow_cycles(x, with_ends=True)
    if ranges.size == 0:
        return np.zeros(len(segments)) if segments is not None else 0.0
    amplitude = equivalent_alternating_stress(0.5 * np.asarray(stress_concentration, dtype=float) * ranges, means,
                                              tensile_strength, yield_strength, correction)
    n = cycles_to_failure(2.0 * amplitude, curve)
    with np.errstate(divide="ignore", invalid="ignore"):
        damage = np.where(n > 0.0, counts / np.where(n > 0.0, n, 1.0), np.inf)
    if segments is None:
        return float(np.sum(damage))
    starts = np.asarray(segments, dtype=np.int64)
    at = np.arange(x.size, dtype=float) if at is None else np.asarray(at, dtype=float)
    return _spread(damage, at[begins], at[ends], at[starts], at[-1])


def _spread(damage, begin, end, lows, last) -> np.ndarray:
    """Each cycle's ``damage`` spread over the stretches [lows[k], lows[k + 1]) (the last up to ``last``) in
    proportion to their overlap with its span [begin, end]; a cycle of no span wholly in the stretch of its end."""
    lows = np.asarray(lows, dtype=float)
    highs = np.append(lows[1:], max(float(last), lows[-1]))
    out = np.zeros(lows.size)
    first = np.clip(np.searchsorted(lows, begin, side="right") - 1, 0, lows.size - 1)
    final = np.clip(np.searchsorted(lows, end, side="right") - 1, 0, lows.size - 1)
    span = end - begin
    point = (span <= 0.0) | (first == final)
    np.add.at(out, final[point], damage[point])
    for d, a, b, i, j in zip(damage[~point], begin[~point], end[~point], first[~point], final[~point]):
        overlap = np.minimum(highs[i:j + 1], b) - np.maximum(lows[i:j + 1], a)
        out[i:j + 1] += d * np.maximum(overlap, 0.0) / (b - a)
    return out


def history_damage_rate(stress, duration, tensile_strength, yield_strength=None, *, stress_concentration=1.0,
                        correction: str = "goodman", curve: str = "B1"):
    """Miner's damage per second [1/s] of a fibre's stress history [Pa] lasting ``duration`` [s]:
    :func:`history_damage` over the duration. For a history of whole sinusoidal cycles about a constant mean it
    equals :func:`damage_rate` at one cycle per period."""
    return history_damage(stress, tensile_strength, yield_strength, stress_concentration=stress_concentration,
                          correction=correction, curve=curve) / float(duration)


def damage_exponent(curve: str = "B1") -> float:
    """The exponent m by which Miner's damage goes with the stress, D ∝ σ^m, below the curve's knee (its second
    slope m₂, 5 for every curve of DNV-RP-C203 Table 2-1): a relative stress error e is a damage error
    (1 + e)^m − 1 there (27.6 % for 5 %)."""
    return float(_curve(curve).m2)


def fatigue_life(damage_rate_per_second):
    """Time of rotation to failure, Miner's D = 1 [s]: 1/rate, infinite where no damage accrues."""
    rate = np.asarray(damage_rate_per_second, dtype=float)
    with np.errstate(divide="ignore"):
        return np.where(rate > 0.0, 1.0 / np.where(rate > 0.0, rate, 1.0), np.inf)
