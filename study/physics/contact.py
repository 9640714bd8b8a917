"""The contact law of the pipe on the wall, written once: Hertz's force with its Hunt–Crossley damping, its
energy and linearised stiffness, the damping that a coefficient of restitution asks for, and one impact.

Pure functions, SI units, no I/O. The law (docs/model.md §3, §10):

    F = K δ^{3/2} (1 + χ δ̇)₊        δ > 0 the approach [m], δ̇ its rate [m/s]

with K the Hertz stiffness [N m^-3/2] (:func:`study.physics.hertz.hertz_stiffness`, paper eq. 7–8) and χ the
hysteresis factor [s/m] (Hunt & Crossley, J. Appl. Mech. 42 (1975) 440–445; Lankarani & Nikravesh, J. Mech.
Des. 112 (1990) 369–376). The elastic force stores the energy (2/5) K δ^{5/2}; linearised at δ it is a spring
of stiffness (3/2) K δ^{1/2}. A linear spring–dashpot contact rebounds with e = exp(−ζπ/√(1 − ζ²)), so
ζ(e) = −ln e/√(π² + ln² e) (any vibration text's logarithmic decrement; Harrison & Nettleton ch. 9).

The functions that the compiled kernels call have a compiled twin (``_one``: the same source compiled by numba,
inlined at the call), so that the law is written once for both numpy's arrays and the kernels' scalars.
"""

from __future__ import annotations

import functools
from typing import NamedTuple

import numba
import numpy as np

from study.physics.restitution import check_range, check_restitution

__all__ = [
    "hertz_force",
    "hertz_force_one",
    "hertz_energy",
    "linearised_stiffness",
    "damping_ratio",
    "linear_contact_damping",
    "hunt_crossley_damping",
    "HertzWallImpact",
    "hertz_wall_impact",
    "calibrated_hysteresis",
]


def hertz_force(approach, stiffness, rate=0.0, hysteresis=0.0):
    """Hertz's normal force with Hunt–Crossley damping, F = K δ^{3/2} (1 + χ δ̇)₊ [N] (module docstring).

    approach δ ≥ 0 [m], stiffness K [N m^-3/2], rate δ̇ [m/s] (positive closing), hysteresis χ [s/m]; with the
    defaults the elastic force K δ^{3/2}. The bracket is held at zero: the wall never pulls the pipe. Arrays
    broadcast; :func:`hertz_force_one` is the compiled twin.
    """
    bracket = 1.0 + hysteresis * rate
    # its positive part, bit for bit max(bracket, 0) (b + |b| = 2b exactly), written with abs alone so that numpy's
    # arrays and numba's scalars both take it and numba lowers it in place, no compiled helper linked into the
    # kernel that inlines it (docs/reference_model.md §6)
    return stiffness * approach**1.5 * (0.5 * (bracket + abs(bracket)))


#: :func:`hertz_force` compiled for the kernels' scalars (inlined where they call it).
hertz_force_one = numba.njit(cache=True, nogil=True, inline="always")(hertz_force)


def hertz_energy(approach, stiffness):
    """Elastic energy (2/5) K δ^{5/2} [J] stored at the approach δ ≥ 0 [m], K [N m^-3/2]: the work of K δ^{3/2}."""
    return 0.4 * stiffness * approach**2.5


def linearised_stiffness(approach, stiffness):
    """Stiffness dF/dδ = (3/2) K δ^{1/2} [N/m] of the elastic Hertz force at the approach δ ≥ 0 [m];
    K [N m^-3/2]."""
    return 1.5 * stiffness * np.sqrt(approach)


def damping_ratio(restitution):
    """Damping ratio ζ = −ln e/√(π² + ln² e) [-] of a linear spring–dashpot contact that rebounds with the
    restitution e ∈ (0, 1] (module docstring); 1 as e → 0 (no rebound)."""
    e = float(restitution)
    if e <= 0.0:
        return 1.0
    le = np.log(e)
    return -le / np.sqrt(np.pi**2 + le**2)


def linear_contact_damping(stiffness, mass, restitution):
    """Dashpot c = 2 ζ(e) √(k m) [N s/m] of a linear contact of stiffness k [N/m] on the mass m [kg] that rebounds
    with the restitution e (:func:`damping_ratio`)."""
    return 2.0 * damping_ratio(restitution) * np.sqrt(stiffness * mass)


def hunt_crossley_damping(impact_velocity, restitution, model: str = "lankarani_nikravesh"):
    """Hysteresis factor χ [s/m] of the contact force F = K δ^(3/2) (1 + χ δ̇), closed forms.

    - ``"lankarani_nikravesh"``: χ = 3(1 − e²)/(4 v0) (Lankarani & Nikravesh 1990), from
      the energy lost per impact for e close to 1;
    - ``"hunt_crossley"``: χ = 3(1 − e)/(2 v0) (Hunt & Crossley 1975).

    Both are low-velocity relations, accurate for e near 1 (within a few % of e for e ≳ 0.8);
    :func:`calibrated_hysteresis` is exact for any e.

    Parameters
    ----------
    impact_velocity : array_like
        v0 [m/s], > 0.
    restitution : array_like
        e [-], 0 ≤ e ≤ 1.
    """
    v0 = check_range(impact_velocity, "impact_velocity", 0.0, np.inf, low_open=True,
                     high_open=True)
    e = check_restitution(restitution)
    if model == "lankarani_nikravesh":
        return 3.0 * (1.0 - e**2) / (4.0 * v0)
    if model == "hunt_crossley":
        return 3.0 * (1.0 - e) / (2.0 * v0)
    raise ValueError(f"model = {model!r}; allowed: 'lankarani_nikravesh', 'hunt_crossley'")


class HertzWallImpact(NamedTuple):
    rebound_velocity: float  #: separation speed [m/s]
    restitution: float  #: achieved e = rebound / impact speed [-]
    duration: float  #: contact duration [s]
    max_penetration: float  #: largest δ [m]
    status: str  #: 'ok' or 'not_converged'
    message: str
    max_force: float = float("nan")  #: largest contact force K δ^(3/2)(1 + χ δ̇) [N]


def hertz_wall_impact(mass, stiffness, impact_velocity, hysteresis) -> HertzWallImpact:
    """Single impact on a compliant wall, m δ̈ = −K δ^(3/2)(1 + χ δ̇), δ(0) = 0, δ̇(0) = v0.

    Integrated with solve_ivp (DOP853) to separation (δ = 0 with δ̇ < 0, or the contact force
    reaching zero: with Hunt–Crossley damping F = 0 when δ̇ = −1/χ), the peak force located where
    dF/dt falls through zero. The equation carries the bracket (1 + χ δ̇) unclipped: past F = 0 it pulls
    the rebound speed back to 1/χ, where the clipped law (:func:`hertz_force`) holds it, without the kink.
    With χ = 0 this is the elastic Hertz impact of :func:`study.physics.hertz.hertz_impact`.

    Parameters
    ----------
    mass : float
        m [kg] > 0.
    stiffness : float
        K [N m^(−3/2)] > 0.
    impact_velocity : float
        v0 [m/s] > 0.
    hysteresis : float
        χ [s/m] ≥ 0 (:func:`hunt_crossley_damping`, :func:`calibrated_hysteresis`).

    Returns
    -------
    HertzWallImpact
    """
    from scipy.integrate import solve_ivp

    from study.physics.hertz import hertz_impact

    m = float(check_range(mass, "mass", 0.0, np.inf, low_open=True, high_open=True))
    K = float(check_range(stiffness, "stiffness", 0.0, np.inf, low_open=True, high_open=True))
    v0 = float(check_range(impact_velocity, "impact_velocity", 0.0, np.inf, low_open=True,
                           high_open=True))
    chi = float(check_range(hysteresis, "hysteresis", 0.0, np.inf, high_open=True))
    ref = hertz_impact(m, v0, K)
    T_H, a_max = float(ref.duration), float(ref.max_approach)

    def rhs(t, y):
        return [y[1], -hertz_force(max(y[0], 0.0), K) * (1.0 + chi * y[1]) / m]

    def leave(t, y):
        return y[0] if y[1] < 0 else a_max

    def turn(t, y):
        return y[1]

    def force(y):
        return hertz_force(max(y[0], 0.0), K, y[1], chi)

    def peak(t, y):  # dF/dt / K = 1.5 δ^½ δ̇ (1 + χ δ̇) + δ^(3/2) χ δ̈, falling through zero at the peak
        d = max(y[0], 0.0)
        return (linearised_stiffness(d, 1.0) * y[1] * (1.0 + chi * y[1])
                + hertz_force(d, 1.0) * chi * rhs(t, y)[1])

    leave.terminal, leave.direction = True, -1
    turn.direction = peak.direction = -1
    sol = solve_ivp(rhs, (0.0, 10 * T_H), [0.0, v0], events=(leave, turn, peak), rtol=1e-10,
                    atol=1e-12 * a_max, method="DOP853", max_step=T_H / 50)
    if sol.t_events[0].size == 0:
        return HertzWallImpact(float("nan"), float("nan"), float("nan"), float(np.max(sol.y[0])),
                               "not_converged", "no separation within 10 elastic durations")
    te = float(sol.t_events[0][0])
    ve = float(sol.y_events[0][0][1])
    dmax = float(sol.y_events[1][0][0]) if sol.t_events[1].size else float(np.max(sol.y[0]))
    f_max = max([force(y) for y in sol.y_events[2]] + [force(y) for y in sol.y.T])
    return HertzWallImpact(-ve, -ve / v0, te, dmax, "ok", "", float(f_max))


@functools.lru_cache(maxsize=64)
def calibrated_hysteresis(restitution: float) -> float:
    """h = χ v0 [-] for which the Hunt–Crossley Hertz impact rebounds with ``restitution`` e ∈ (0, 1].

    Scale-free (m = K = v0 = 1 in :func:`hertz_wall_impact`: scale δ by α_max and t by α_max/v0 and m, K drop
    out), solved by brentq; 0 for e = 1. A contact starting at the approach speed v0 takes χ = h/v0.
    """
    from scipy.optimize import brentq

    e = float(restitution)
    if not 0.0 < e <= 1.0:
        raise ValueError(f"restitution = {e}: the calibrated contact needs 0 < e <= 1")
    if e >= 1.0:
        return 0.0

    def miss(h):
        return hertz_wall_impact(1.0, 1.0, 1.0, h).restitution - e

    hi = 1.0
    while miss(hi) > 0:
        hi *= 4.0
        if hi > 1e6:
            raise ValueError(f"restitution = {e}: too small for the Hunt–Crossley contact")
    return float(brentq(miss, 0.0, hi, xtol=1e-9, rtol=1e-9))
