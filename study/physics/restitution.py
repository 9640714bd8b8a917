"""Newton's law of restitution for direct central impact, and the impact sequences built on it.

Pure functions of numpy arrays (broadcasting; floats accepted), SI units, no I/O.

Source: Harrison & Nettleton, *Principles of Engineering Mechanics*, 2nd ed.,
ch. 8 "Momentum and impulse" (impact). The copy of the chapter the project holds
(docs/model.md §8.3) starts part-way through the chapter, so the section that defines the
coefficient of restitution and its equation number are *not* in it; no equation number is cited
for the law itself. What the copy does contain and this module reproduces:

- the plastic (common-velocity) impact and its energy loss ½ I1 I2/(I1+I2) (ω1 − ω2)², in the
  clutch example before Example 8.2;
- Example 8.2, the box on a roller conveyor: an impulsive velocity ratio 6/7 at each roller and
  constant acceleration between rollers, leading to a steady mean velocity 2.187 m/s;
- Example 8.7 and 8.8, "velocity of approach equals velocity of recession" for ideal impact;
- Problem 8.1, ball dropped on a floor and Problem 8.2, Newton's cradle.

Law used (standard form): for two bodies moving along the common normal, positive direction from
body 1 towards body 2, with approach velocity v1 − v2 > 0 before impact,

    v2' − v1' = e (v1 − v2),        m1 v1' + m2 v2' = m1 v1 + m2 v2,

with 0 ≤ e ≤ 1 (e = 0 perfectly plastic, e = 1 perfectly elastic / "ideal impact").
A rigid immovable wall is body 2 with ``m2 = np.inf``.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

__all__ = [
    "CollisionResult",
    "BounceSummary",
    "ImpactCycle",
    "ImpactSequence",
    "restitution_from_rebound",
    "rebound_height",
    "restitution_from_velocities",
    "collision",
    "energy_loss",
    "collision_impulse",
    "impulse_on_wall",
    "bounce_heights",
    "bounce_to_rest",
    "collision_chain",
    "impact_sequence",
    "periodic_impact_steady_state",
    "check_range",
    "check_restitution",
]

STANDARD_GRAVITY = 9.81  # [m/s^2] value used throughout the textbook chapter


class CollisionResult(NamedTuple):
    v1: np.ndarray  #: velocity of body 1 just after impact [m/s]
    v2: np.ndarray  #: velocity of body 2 just after impact [m/s]


class BounceSummary(NamedTuple):
    total_time: np.ndarray  #: time from release until the ball comes to rest [s]
    total_distance: np.ndarray  #: total path length travelled (down + up) [m]


class ImpactCycle(NamedTuple):
    before: np.ndarray  #: speed just before each impact in the steady cycle [m/s]
    after: np.ndarray  #: speed just after each impact in the steady cycle [m/s]
    mean: np.ndarray  #: time-mean speed over one cycle (constant acceleration) [m/s]


class ImpactSequence(NamedTuple):
    before: np.ndarray  #: speeds just before impacts 1..n, last axis = impact index [m/s]
    after: np.ndarray  #: speeds just after impacts 1..n, last axis = impact index [m/s]


# --- validation -----------------------------------------------------------------------------


def _describe(values: np.ndarray) -> str:
    """Offending values for an error message (scalar as is, arrays abbreviated)."""
    flat = np.ravel(values)
    if flat.size == 1:
        return repr(float(flat[0]))
    shown = ", ".join(repr(float(v)) for v in flat[:5])
    more = f", ... ({flat.size} values)" if flat.size > 5 else ""
    return f"[{shown}{more}]"


def check_range(value, name: str, low: float, high: float, *, low_open: bool = False,
                 high_open: bool = False) -> np.ndarray:
    """Return ``value`` as a float array; raise ValueError naming it if outside the range.

    NaN is always rejected. ``high = np.inf`` with ``high_open=False`` admits +inf.
    """
    arr = np.asarray(value, dtype=float)
    with np.errstate(invalid="ignore"):
        ok_low = arr > low if low_open else arr >= low
        ok_high = arr < high if high_open else arr <= high
    bad = ~(ok_low & ok_high)  # NaN fails both comparisons
    if np.any(bad):
        lo = "(" if low_open else "["
        hi = ")" if high_open else "]"
        rng = f"{lo}{low:g}, {high:g}{hi}"
        raise ValueError(f"{name} = {_describe(arr[bad])} is outside the allowed range {rng}")
    return arr


def check_restitution(restitution, name: str = "restitution") -> np.ndarray:
    """``restitution`` as a float array, checked to lie in [0, 1] (ValueError naming it otherwise)."""
    return check_range(restitution, name, 0.0, 1.0)


def _mass_fractions(m1: np.ndarray, m2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """m1/(m1+m2) and m2/(m1+m2), exact in the limits m1 → ∞ or m2 → ∞."""
    both = np.isinf(m1) & np.isinf(m2)
    if np.any(both):
        raise ValueError("m1 and m2 are both infinite; at most one body may be immovable "
                         "(allowed range of each: (0, inf], not both inf)")
    with np.errstate(invalid="ignore", divide="ignore"):
        f1 = np.where(np.isinf(m1), 1.0, np.where(np.isinf(m2), 0.0, m1 / (m1 + m2)))
        f2 = np.where(np.isinf(m2), 1.0, np.where(np.isinf(m1), 0.0, m2 / (m1 + m2)))
    return f1, f2


def _reduced_mass(m1: np.ndarray, m2: np.ndarray) -> np.ndarray:
    """m1 m2/(m1+m2) [kg]; equals m1 when m2 = inf (rigid wall) and m2 when m1 = inf."""
    f1, _ = _mass_fractions(m1, m2)
    with np.errstate(invalid="ignore"):
        return np.where(np.isinf(m2), m1, np.where(np.isinf(m1), m2, f1 * m2))


def _approach(v1, v2) -> np.ndarray:
    """Approach velocity v1 − v2 [m/s], which must be ≥ 0 for an impact to occur."""
    v1 = np.asarray(v1, dtype=float)
    v2 = np.asarray(v2, dtype=float)
    return check_range(v1 - v2, "approach velocity v1 - v2", 0.0, np.inf, high_open=True)


# --- bouncing on a rigid floor --------------------------------------------------------------


def restitution_from_rebound(drop_height, rebound_height):
    """Coefficient of restitution e = √(h_r / h_d) of a ball dropped on a rigid floor.

    Parameters
    ----------
    drop_height : array_like
        Height h_d from which the ball is released from rest [m], > 0.
    rebound_height : array_like
        Height h_r reached after the first bounce [m], 0 ≤ h_r ≤ h_d.

    Returns
    -------
    ndarray
        e [-]. Impact speed √(2 g h_d) and rebound speed √(2 g h_r) (energy conserved in flight),
        and e = rebound speed / impact speed; g cancels.

    Textbook: ch. 8, Problem 8.1: dropped from 2 m, rebounds 1.5 m.
    """
    hd = check_range(drop_height, "drop_height", 0.0, np.inf, low_open=True, high_open=True)
    hr = check_range(rebound_height, "rebound_height", 0.0, np.inf, high_open=True)
    ratio = hr / hd
    if np.any(ratio > 1.0):
        bad = np.broadcast_to(hr, ratio.shape)[ratio > 1.0]
        raise ValueError(f"rebound_height = {_describe(bad)} exceeds drop_height; allowed range "
                         "[0, drop_height] (e would exceed 1)")
    return np.sqrt(ratio)


def rebound_height(drop_height, restitution):
    """Height h_r = e² h_d reached after one bounce on a rigid floor.

    Parameters
    ----------
    drop_height : array_like
        Release height h_d (from rest) [m], ≥ 0.
    restitution : array_like
        Coefficient of restitution e [-], 0 ≤ e ≤ 1.

    Returns
    -------
    ndarray
        Rebound height [m].

    Textbook: ch. 8, Problem 8.1.
    """
    hd = check_range(drop_height, "drop_height", 0.0, np.inf, high_open=True)
    e = check_restitution(restitution)
    return e**2 * hd


def bounce_heights(drop_height, restitution, n_bounces: int):
    """Apex heights after bounces 1..n: h_k = e^(2k) h_d [m].

    Parameters
    ----------
    drop_height : array_like
        Release height h_d (from rest) [m], ≥ 0.
    restitution : array_like
        e [-], 0 ≤ e ≤ 1.
    n_bounces : int
        Number of bounces n ≥ 0.

    Returns
    -------
    ndarray
        Shape ``broadcast(drop_height, restitution).shape + (n_bounces,)`` [m].

    Textbook: repeated application of Problem 8.1.
    """
    if int(n_bounces) != n_bounces or n_bounces < 0:
        raise ValueError(f"n_bounces = {n_bounces!r} is outside the allowed range: integers >= 0")
    hd = check_range(drop_height, "drop_height", 0.0, np.inf, high_open=True)
    e = check_restitution(restitution)
    k = np.arange(1, int(n_bounces) + 1)
    return (hd[..., None] * e[..., None] ** (2 * k))


def bounce_to_rest(drop_height, restitution, g=STANDARD_GRAVITY):
    """Total time and total distance until a ball dropped on a rigid floor comes to rest.

    Closed-form geometric series (each bounce rebounds with speed e × impact speed):

        t_total = √(2 h_d / g) (1 + e)/(1 − e),    s_total = h_d (1 + e²)/(1 − e²).

    For e = 1 both are infinite (returned as ``inf``). Infinitely many bounces occur in the
    finite time for 0 < e < 1; this is the idealisation of instantaneous impacts.

    Parameters
    ----------
    drop_height : array_like
        Release height h_d (from rest) [m], ≥ 0.
    restitution : array_like
        e [-], 0 ≤ e ≤ 1.
    g : array_like, optional
        Gravitational field strength [m/s²] (N/kg), > 0. Default 9.81.

    Returns
    -------
    BounceSummary
        ``total_time`` [s] and ``total_distance`` [m].

    Textbook: extension of Problem 8.1; not a printed result.
    """
    hd = check_range(drop_height, "drop_height", 0.0, np.inf, high_open=True)
    e = check_restitution(restitution)
    g = check_range(g, "g", 0.0, np.inf, low_open=True, high_open=True)
    t_fall = np.sqrt(2.0 * hd / g)
    with np.errstate(divide="ignore", invalid="ignore"):
        time = np.where(e == 1.0, np.where(hd > 0, np.inf, 0.0), t_fall * (1 + e) / (1 - e))
        dist = np.where(e == 1.0, np.where(hd > 0, np.inf, 0.0), hd * (1 + e**2) / (1 - e**2))
    return BounceSummary(total_time=time, total_distance=dist)


# --- two-body direct central impact ---------------------------------------------------------


def restitution_from_velocities(v1_before, v2_before, v1_after, v2_after):
    """Coefficient of restitution from measured velocities along the line of impact.

    e = (v2_after − v1_after) / (v1_before − v2_before)  (velocity of recession / velocity of
    approach). Positive direction from body 1 towards body 2. The result is *not* clipped to
    [0, 1]: a value outside it signals inconsistent data.

    Parameters
    ----------
    v1_before, v2_before : array_like
        Velocities just before impact [m/s]; the approach velocity v1 − v2 must be > 0.
    v1_after, v2_after : array_like
        Velocities just after impact [m/s].

    Returns
    -------
    ndarray
        e [-].

    Textbook: ch. 8, "velocity of approach equals velocity of recession" for ideal impact
    (Example 8.7).
    """
    v1b = np.asarray(v1_before, dtype=float)
    v2b = np.asarray(v2_before, dtype=float)
    approach = check_range(v1b - v2b, "approach velocity v1_before - v2_before", 0.0, np.inf,
                            low_open=True, high_open=True)
    recession = np.asarray(v2_after, dtype=float) - np.asarray(v1_after, dtype=float)
    return recession / approach


def collision(m1, v1, m2, v2, restitution) -> CollisionResult:
    """Velocities after a direct central impact (momentum conserved, approach reversed by e).

        v1' = v1 − (1 + e) m2/(m1 + m2) (v1 − v2),
        v2' = v2 + (1 + e) m1/(m1 + m2) (v1 − v2).

    Parameters
    ----------
    m1, m2 : array_like
        Masses [kg], in (0, inf]; ``m2 = np.inf`` is a rigid immovable wall (then v1' =
        v2 − e (v1 − v2)), likewise ``m1 = np.inf``; not both infinite. For rotating bodies
        coupled without bounce (e = 0) the same algebra holds with moments of inertia [kg m²]
        and angular velocities [rad/s] (clutch example).
    v1, v2 : array_like
        Velocities just before impact along the common normal [m/s], positive from body 1
        towards body 2; the approach velocity v1 − v2 must be ≥ 0 (0: no impact, unchanged).
    restitution : array_like
        e [-], 0 ≤ e ≤ 1.

    Returns
    -------
    CollisionResult
        ``v1``, ``v2`` just after impact [m/s].

    Textbook: ch. 8; common velocity (e = 0) eq. (iii) of the clutch example,
    conveyor impulsive ratio 6/7 (Example 8.2), Example 8.7.
    """
    m1 = check_range(m1, "m1", 0.0, np.inf, low_open=True)
    m2 = check_range(m2, "m2", 0.0, np.inf, low_open=True)
    e = check_restitution(restitution)
    v1 = np.asarray(v1, dtype=float)
    v2 = np.asarray(v2, dtype=float)
    approach = _approach(v1, v2)
    f1, f2 = _mass_fractions(m1, m2)
    return CollisionResult(v1=v1 - (1.0 + e) * f2 * approach, v2=v2 + (1.0 + e) * f1 * approach)


def energy_loss(m1, v1, m2, v2, restitution):
    """Kinetic energy lost in a direct central impact.

        ΔT = ½ m1 m2/(m1 + m2) (1 − e²) (v1 − v2)²   [J];   = ½ m1 (1 − e²)(v1 − v2)² for a wall.

    Parameters: as :func:`collision` (masses [kg], velocities [m/s], e [-]).

    Returns
    -------
    ndarray
        Energy lost (≥ 0) [J].

    Textbook: for e = 0 this is the clutch result "energy lost = ½ I1 I2/(I1+I2)(ω1 − ω2)²".
    """
    m1 = check_range(m1, "m1", 0.0, np.inf, low_open=True)
    m2 = check_range(m2, "m2", 0.0, np.inf, low_open=True)
    e = check_restitution(restitution)
    approach = _approach(v1, v2)
    return 0.5 * _reduced_mass(m1, m2) * (1.0 - e**2) * approach**2


def collision_impulse(m1, v1, m2, v2, restitution):
    """Magnitude of the impulse exchanged in a direct central impact.

        J = m1 m2/(m1 + m2) (1 + e)(v1 − v2)   [N s];   = m1 (1 + e)(v1 − v2) for a wall.

    Body 1 receives −J, body 2 receives +J (positive direction from 1 towards 2).
    Parameters: as :func:`collision`.

    Textbook: ch. 8, impulse = change of momentum.
    """
    m1 = check_range(m1, "m1", 0.0, np.inf, low_open=True)
    m2 = check_range(m2, "m2", 0.0, np.inf, low_open=True)
    e = check_restitution(restitution)
    approach = _approach(v1, v2)
    return _reduced_mass(m1, m2) * (1.0 + e) * approach


def impulse_on_wall(mass, approach_velocity, restitution):
    """Impulse J = m (1 + e) v delivered to a rigid wall by a body striking it normally.

    Parameters
    ----------
    mass : array_like
        Mass of the striking body [kg], > 0.
    approach_velocity : array_like
        Normal speed towards the wall just before impact [m/s], ≥ 0.
    restitution : array_like
        e [-], 0 ≤ e ≤ 1.

    Returns
    -------
    ndarray
        Impulse [N s] (the body rebounds with speed e v).

    Textbook: ch. 8, impulse = change of momentum with Newton's law of restitution.
    """
    m = check_range(mass, "mass", 0.0, np.inf, low_open=True, high_open=True)
    v = check_range(approach_velocity, "approach_velocity", 0.0, np.inf, high_open=True)
    e = check_restitution(restitution)
    return m * (1.0 + e) * v


# --- sequences of impacts --------------------------------------------------------------------


def collision_chain(masses, velocities, restitution, *, max_impacts: int = 100_000,
                    rtol: float = 1e-12):
    """Outcome of a row of bodies on a line, as a sequence of binary direct impacts.

    Sweeps the row from left to right, applying :func:`collision` to every pair of neighbours
    that approach (v_i > v_{i+1}), and repeats the sweeps until no neighbours approach. This is
    the sequential-impact idealisation of Newton's cradle (for bodies arriving from the left the
    disturbance travels along the row in the sweep direction). For identical bodies and e = 1 every impact swaps the two
    velocities, so the result does not depend on the order; for e < 1 with bodies in contact the
    outcome depends on the contact model and this is only one idealisation.

    Parameters
    ----------
    masses : array_like, shape (n,)
        Masses in order along the line [kg], > 0, finite.
    velocities : array_like, shape (n,)
        Velocities before the first impact [m/s], positive towards higher index.
    restitution : float
        e [-], 0 ≤ e ≤ 1, the same for every pair.
    max_impacts : int
        Safety limit; RuntimeError if not settled after this many impacts.
    rtol : float
        Neighbours with approach velocity ≤ rtol × max|v| count as not approaching.

    Returns
    -------
    ndarray, shape (n,)
        Velocities after the last impact [m/s].

    Textbook: ch. 8, Problem 8.2 (Newton's cradle).
    """
    m = check_range(masses, "masses", 0.0, np.inf, low_open=True, high_open=True)
    v = np.array(velocities, dtype=float)
    if m.ndim != 1 or v.shape != m.shape:
        raise ValueError(f"masses and velocities must be 1-D of equal length; got shapes "
                         f"{m.shape} and {v.shape}")
    if not np.all(np.isfinite(v)):
        raise ValueError(f"velocities = {_describe(v[~np.isfinite(v)])} is outside the allowed "
                         "range (-inf, inf)")
    e = float(check_restitution(restitution))
    tol = rtol * float(np.max(np.abs(v), initial=0.0))
    impacts = 0
    while True:
        struck = False
        for i in range(v.size - 1):  # one left-to-right sweep
            if v[i] - v[i + 1] > tol:
                if impacts >= max_impacts:
                    raise RuntimeError(
                        f"collision_chain did not settle within max_impacts = {max_impacts}")
                v[i], v[i + 1] = collision(m[i], v[i], m[i + 1], v[i + 1], e)
                impacts += 1
                struck = True
        if not struck:
            return v


def impact_sequence(initial_speed, velocity_ratio, speed_squared_gain, n_impacts: int):
    """Speeds before and after each of a sequence of impacts separated by constant acceleration.

    Between impacts the body gains kinetic energy at constant acceleration a over a fixed
    distance s, so v_before² = v_after_previous² + Δ with Δ = 2 a s; each impact multiplies the
    speed by the impulsive velocity ratio R (e.g. R = (m1 − e m2)/(m1 + m2) for body 1 striking a
    stationary body 2, see :func:`collision`).

    Parameters
    ----------
    initial_speed : array_like
        Speed at the start of the first free interval [m/s], ≥ 0.
    velocity_ratio : array_like
        R = v_after / v_before at each impact [-], 0 ≤ R ≤ 1.
    speed_squared_gain : array_like
        Δ = 2 a s gained between impacts [m²/s²], ≥ 0.
    n_impacts : int
        Number of impacts n ≥ 1.

    Returns
    -------
    ImpactSequence
        ``before`` and ``after``, last axis = impact index 1..n [m/s].

    Textbook: Example 8.2, roller conveyor, equations (i) and (iii):
    R = 6/7, Δ = 2 m g l sin α/(m + 3I/r²) = 1.4715 m²/s².
    """
    if int(n_impacts) != n_impacts or n_impacts < 1:
        raise ValueError(f"n_impacts = {n_impacts!r} is outside the allowed range: integers >= 1")
    v = check_range(initial_speed, "initial_speed", 0.0, np.inf, high_open=True)
    r = check_range(velocity_ratio, "velocity_ratio", 0.0, 1.0)
    d = check_range(speed_squared_gain, "speed_squared_gain", 0.0, np.inf, high_open=True)
    v, r, d = np.broadcast_arrays(v, r, d)
    before = np.empty(v.shape + (int(n_impacts),))
    after = np.empty_like(before)
    current = v.astype(float)
    for k in range(int(n_impacts)):
        before[..., k] = np.sqrt(current**2 + d)
        after[..., k] = r * before[..., k]
        current = after[..., k]
    return ImpactSequence(before=before, after=after)


def periodic_impact_steady_state(velocity_ratio, speed_squared_gain) -> ImpactCycle:
    """Steady cycle of repeated impacts separated by equal intervals of constant acceleration.

    The speed lost at each impact is exactly regained in the following free interval:
    v_b² = (R v_b)² + Δ, hence

        v_before = √(Δ / (1 − R²)),   v_after = R v_before,   v_mean = (v_before + v_after)/2,

    the mean being the time average over an interval of constant acceleration. This is the
    fixed point of :func:`impact_sequence`, which approaches it geometrically (ratio R²).

    Parameters
    ----------
    velocity_ratio : array_like
        R = v_after / v_before at each impact [-], 0 ≤ R < 1 (R = 1: no steady state).
    speed_squared_gain : array_like
        Δ = 2 a s gained between impacts [m²/s²], ≥ 0.

    Returns
    -------
    ImpactCycle
        ``before``, ``after``, ``mean`` [m/s].

    Textbook: Example 8.2(b), roller conveyor: 2.3551 m/s before,
    2.0187 m/s after, mean 2.1869 m/s (printed 2.187 m/s in the statement, line 157).
    """
    r = check_range(velocity_ratio, "velocity_ratio", 0.0, 1.0, high_open=True)
    d = check_range(speed_squared_gain, "speed_squared_gain", 0.0, np.inf, high_open=True)
    before = np.sqrt(d / (1.0 - r**2))
    after = r * before
    return ImpactCycle(before=before, after=after, mean=0.5 * (before + after))
