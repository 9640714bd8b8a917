"""The span search of the periodic impact solution: the poles located, the screening residual sampled and its
sign changes shrunk inside every interval between wide poles, and the roots screened at midspan (docs/model.md
§4.5).

F(L) has a pole wherever a natural frequency ω_n(L) meets a harmonic of the pulse train: a sign change across a pole
is not a root. The poles are located analytically (:func:`study.solvers.kernels.impact.resonances`), F
times the distances to the interval's two poles is sampled inside every interval (:func:`search_intervals`,
:func:`roots_between`; its values at the poles follow from their residues), and only sign changes inside one interval
are bracketed and shrunk (regula falsi in lockstep, compiled). The midspan screen (:func:`midspan_screen`) keeps the
roots whose midspan stays inside the wall over the period; :mod:`study.solvers.kernels.impact` refines
them with the exact model, and :mod:`study.solvers.methods.periodic` checks the constraints. Where the time goes and why
it is built so: docs/profile_fast.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numba
import numpy as np

from study.physics import beam, midspan
from study.physics.interpolation import interp_one
from study.physics.roots import bracket_done, closer_end, falsi_point, keep_sign_change
from study.solvers.kernels.impact import (impacts_at, kernel_args, odd_modes,
                                                         resonances, unit_state)
from study.solvers.model.options import Options
from study.solvers.model.scene import Scene


#: Relative width at which the span search stops shrinking a bracket of the screening residual with no
#: pole within :data:`POLE_FREE_WINDOW` bracket widths (F is continuous there, so its sign change is a
#: root, and the midspan state that the screen reads at it does not swing across the bracket); others
#: go on to 1e-10. The exact root differs from the screening one by more (median 7e-6 relative, over
#: the 24 benchmark points and the paper's point in four readings), and :func:`refine_roots` takes it
#: from there.
ROOT_RTOL = 1e-6


POLE_FREE_WINDOW = 10.0


def screen_residual(scene: Scene, options: Options):
    """A cheap, smooth stand-in for F(L), vectorised over spans, for the search.

    T_L(L) and the contact half-length b(L) come from one fixed-point step at a dozen spans,
    interpolated in log L; the roots found with it are refined with the exact model afterwards.
    Returns a function of an array of spans (compiled, :func:`_screen_state`), or None when no span
    gives a valid pulse; its ``shrink`` shrinks sign-changing brackets of F times the distances to two
    poles onto their roots in lockstep rounds of compiled loops (:func:`_shrink_points`, :func:`_shrink_update`).
    """
    grid = np.geomspace(options.min_span, options.max_span, 12)
    impacts = impacts_at(scene, grid, options, max_iterations=1)
    durations = np.array([i.contact_duration for i in impacts])
    halves = np.array([i.contact_half_length for i in impacts])
    ok = np.isfinite(durations) & (durations > 0)
    if not np.any(ok):
        return None
    table = (np.log(grid[ok]), np.log(durations[ok]), halves[ok])
    state, all_modes, _, closure = kernel_args(scene, options)
    any_modes = state[:-1] + (False,)  # modes not 1, 3, 5, ...

    def pulse(spans):
        """(T_L, b) interpolated at ``spans`` (numpy's log and exp of whole arrays: SIMD)."""
        log_spans = np.log(spans)
        return np.exp(np.interp(log_spans, table[0], table[1])), np.interp(log_spans, table[0], table[2])

    def residual(spans, modes=None):
        """F(L) at ``spans``; with ``modes`` (see :func:`unit_state`) F + 1 from those modes alone."""
        spans = np.asarray(spans, dtype=float)
        if modes is None:
            flat = np.ascontiguousarray(spans.ravel())
            values = _screen_values_batch(flat, *pulse(flat), all_modes.size, 1.0, state, closure)
        else:
            per_span = np.broadcast_to(np.asarray(modes, dtype=float), spans.shape + np.shape(modes)[-1:])
            values = _screen_values(np.ascontiguousarray(spans.ravel()),
                                    np.ascontiguousarray(per_span.reshape(spans.size, -1)), 0.0, table, any_modes,
                                    closure)
        return values.reshape(spans.shape)

    def shrink(lo, hi, f_lo, f_hi, pole_lo, pole_hi, rtol=1e-10, iterations=60, poles=None, pole_free_rtol=None):
        """Brackets [lo, hi] of G = F (L − pole_lo)(pole_hi − L) with G = f_lo, f_hi at the ends, shrunk
        onto their sign change (regula falsi with the Illinois modification, :mod:`study.physics.roots`)
        until narrower than ``rtol`` (relative) or at an exact zero — or than ``pole_free_rtol`` once
        none of ``poles`` (sorted [m]) lies within :data:`POLE_FREE_WINDOW` bracket widths. Returns
        (roots, G at the roots, final lo, final hi, (3, n) y₁, v₁, y₁'' at the roots as
        :func:`unit_state` with the screening pulse, NaN where not evaluated), the root being the end
        with the smaller weighted |G|."""
        a, b, fa, fb, pole_lo, pole_hi = (np.array(v, dtype=float) for v in (lo, hi, f_lo, f_hi, pole_lo, pole_hi))
        raw_a, raw_b, side, tol = fa.copy(), fb.copy(), np.zeros(a.size, dtype=np.int64), np.full(a.size, float(rtol))
        states = np.full((2, 3, a.size), np.nan)  # y₁, v₁, y₁'' at the lower and the upper end
        poles = np.zeros(0) if poles is None else np.ascontiguousarray(poles, dtype=float)
        free_rtol = float(rtol if pole_free_rtol is None else pole_free_rtol)
        running, below = np.arange(a.size), np.full(a.size, -1, dtype=np.int64)
        # every bracket takes the steps it would take alone, all in lockstep: each round evaluates the new
        # points of the brackets still open at once (the pulse by numpy, the modal sums in one SIMD call)
        for done in range(int(iterations)):
            running, points = _shrink_points(a, b, fa, fb, tol, running, poles, free_rtol, below)
            if running.size == 0:
                break
            if running.size <= SHRINK_TAIL:  # the few brackets left (next to a pole) in one compiled loop
                _shrink_tail(running, points, int(iterations) - done, a, b, fa, fb, raw_a, raw_b, side, tol, states,
                             pole_lo, pole_hi, poles, free_rtol, below, table, all_modes.size, state, closure)
                break
            values, y1, v1, curv1 = _screen_batch(points, *pulse(points), all_modes.size, 1.0, state, closure)
            _shrink_update(running, points, values, y1, v1, curv1, a, b, fa, fb, raw_a, raw_b, side, states, pole_lo,
                           pole_hi)
        out = _shrink_result(a, b, fa, fb, raw_a, raw_b, states)
        return out[0], out[1], out[2], out[3], out[4:]

    def residue(spans, modes, floor=0.0):
        """R [m] of the term of mode ``modes`` in F at its pole ``spans``: F ≈ R/(L − L_p) there; NaN
        where |R| is certainly below ``floor`` [m] (broadcast with spans), not computed.

        The term is −m_e(1 + e) Ω w q(0) (prescribed) or −m_e(1 + e) w q̇(0) (self-consistent), w the
        mode's midspan weight, and q(0), q̇(0) (:func:`beam.modal_state_at_pulse_start`) carry the pole
        through κ ≈ 1/(x − x_p), x = ω s (s = τ/2 for cot(ωτ/2), τ/4 for −tan(ωτ/4)): the factor of κ,
        A cos φ/(2ω) or A sin φ/2 (A e^{−iφ} = H(ω), :func:`beam.pulse_spectrum`), over s dω/dL."""
        spans, n, floors = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (spans, modes, floor)))
        flat = [np.ascontiguousarray(v.ravel()) for v in (spans, n)]
        return _residues_kernel(*flat, table, state, closure, np.ascontiguousarray(floors.ravel())).reshape(spans.shape)

    residual.pulse = pulse
    residual.residue = residue
    residual.shrink = shrink
    return residual


@numba.njit(cache=True, nogil=True)
def _screen_state(span, modes, offset, table, state, closure):
    """(F(L) + 1 − ``offset``, y₁, v₁, y₁'') at one span [m] (compiled): T_L and b interpolated in
    log L from ``table`` (log L, log T_L, b), the midspan state per unit impulse summed over ``modes``
    (:func:`midspan.midspan_state_one` with ``state``), then the closure (``closure`` of
    :func:`kernel_args`: self-consistent?, m_e/L [kg/m], e, Ω [rad/s], ...): −m_e (1 + e) v₁ (self-consistent:
    m_e (1+e) V_p/J with V_p = c v₁/y₁, J = −c/y₁) or −m_e (1 + e) Ω y₁ (prescribed: −J y₁/c with
    J = m_e (1 + e) Ω c); y₁, v₁, y₁'' the midspan state per unit impulse of :func:`unit_state`."""
    duration, half = _pulse_one(span, table)
    ei, tension, mass, period, one_wall, code, tol, consecutive = state
    y1, v1, curv1 = midspan.midspan_state_one(span, duration, half, modes, ei, tension, mass, period, one_wall, code,
                                           tol, consecutive)
    self_consistent, mass_factor, restitution, omega, _, _, _ = closure
    impulse_factor = mass_factor * span * (1.0 + restitution)
    if self_consistent:
        return -impulse_factor * v1 - offset, y1, v1, curv1
    return -impulse_factor * omega * y1 - offset, y1, v1, curv1


@numba.njit(cache=True, nogil=True)
def _pulse_one(span, table):
    """(T_L [s], b [m]) of the screening residual at one span [m]: ``pulse`` of :func:`screen_residual`,
    compiled, from ``table`` (log L, log T_L, b)."""
    log_span = math.log(span)
    return math.exp(interp_one(log_span, table[0], table[1])), interp_one(log_span, table[0], table[2])


@numba.njit(cache=True, nogil=True, error_model="numpy")  # no division check: a jump in the loop stops SIMD
def _residues_kernel(spans, modes, table, state, closure, floors):
    """``screen_residual(...).residue`` at every pole (compiled): spans L_p [m], modes n, the rest as
    :func:`_screen_state`; NaN, not computed, where a bound without trigonometry puts |R| below
    ``floors`` [m] (one per pole).

    The bound: |g_n H(ω)| ≤ min(1, 1/|u² − 1|), u = ωT_L/π. The load and the pulse are non-negative, so
    |g_n| ≤ g(0) = 1 and |H(ω)| ≤ H(0) = 1, and H = A e^{−iφ} with |A| = |cos φ/(1 − u²)|. T_L is at
    least the table's shortest (the interpolation stays within its values), so u ≥ ω min T_L/π."""
    ei, tension, mass, _, _, code, _, _ = state
    self_consistent, mass_factor, restitution, omega_rot, _, interval, _ = closure
    shortest = math.exp(np.min(table[1]))
    out = np.empty(spans.size)
    omegas, scales = np.empty(spans.size), np.empty(spans.size)
    for i in range(spans.size):  # the bound of every pole first, in SIMD instructions (no jump, no library call)
        span, n = spans[i], modes[i]
        k_sq = (n * math.pi / span) ** 2
        om_sq = (ei * k_sq + tension) * k_sq / mass
        omega = math.sqrt(om_sq) if om_sq > 0.0 else math.nan
        slope = -(2.0 * ei * k_sq**2 + tension * k_sq) / (mass * span * omega)  # dω/dL
        scale = -mass_factor * span * (1.0 + restitution) * 2.0 / (mass * span) / (0.5 * interval * slope)
        u = omega * shortest / math.pi
        bound = abs(scale) * (1.0 / (u * u - 1.0) if u * u > 2.0 else 1.0) * (
            0.5 if self_consistent else omega_rot / (2.0 * omega))
        omegas[i], scales[i], out[i] = omega, scale, math.nan if bound < floors[i] else 0.0
    for i in range(spans.size):
        if out[i] != 0.0:
            continue
        span, n, omega, scale = spans[i], modes[i], omegas[i], scales[i]
        duration, half = _pulse_one(span, table)
        real, imag = beam.loaded_spectrum_one(omega, span, n, duration, half, code)  # |g_n| H(ω)
        out[i] = scale * (-0.5 * imag if self_consistent else omega_rot * real / (2.0 * omega))
    return out


@numba.njit(cache=True, nogil=True)
def _screen_batch(spans, durations, halves, n_odd, offset, state, closure):
    """(F(L) + 1 − ``offset``, y₁, v₁, y₁'') of :func:`_screen_state` at every span of ``spans`` [m] with the
    screening pulse's T_L ``durations`` [s] and b ``halves`` [m] there (``pulse`` of :func:`screen_residual`)
    and the odd modes 1, 3, …, 2 ``n_odd`` − 1, the modal sums of all spans at once in SIMD instructions
    (:func:`midspan.midspan_states`; equal to :func:`_screen_state` but for rounding)."""
    ei, tension, mass, period, one_wall, code, tol, _ = state
    y1, v1, curv1 = midspan.midspan_states(spans, durations, halves, n_odd, ei, tension, mass, period, one_wall, code,
                                           tol)
    self_consistent, mass_factor, restitution, omega, _, _, _ = closure
    factor = mass_factor * spans * (1.0 + restitution)
    values = -factor * v1 - offset if self_consistent else -factor * omega * y1 - offset
    return values, y1, v1, curv1


@numba.njit(cache=True, nogil=True)
def _screen_values_batch(spans, durations, halves, n_odd, offset, state, closure):
    """The first of :func:`_screen_batch`'s arrays alone, to the last bit: the modal sum of y₁ (prescribed) or v₁
    (self-consistent) only (:func:`midspan.midspan_sums`)."""
    ei, tension, mass, period, one_wall, code, tol, _ = state
    self_consistent, mass_factor, restitution, omega, _, _, _ = closure
    total = midspan.midspan_sums(spans, durations, halves, n_odd, ei, tension, mass, period, one_wall, code, tol,
                              self_consistent)
    factor = mass_factor * spans * (1.0 + restitution)
    return -factor * total - offset if self_consistent else -factor * omega * total - offset


@numba.njit(cache=True, nogil=True)
def _screen_values(spans, modes, offset, table, state, closure):
    """The screening residual of :func:`_screen_state` at every span; ``modes`` one row for all spans or
    one row per span."""
    out = np.empty(spans.size)
    per_span = modes.shape[0] > 1
    for i in range(spans.size):
        out[i] = _screen_state(spans[i], modes[i if per_span else 0], offset, table, state, closure)[0]
    return out


@numba.njit(cache=True, nogil=True)
def _search_right(values, x, hint):
    """``np.searchsorted(values, x, side="right")`` of ascending ``values`` and a finite x, galloping from index
    ``hint`` (steps of 1, 2, 4, … towards the answer, then halving): a few comparisons when the answer is near
    the hint, as it is for the span search's brackets taken in ascending order."""
    n = values.size
    hint = min(max(hint, 0), n)
    step = 1
    if hint < n and values[hint] <= x:  # the answer is above the hint
        lo = hint + 1
        hi = lo
        while hi < n and values[hi] <= x:
            lo = hi + 1
            hi = lo + step
            step *= 2
        hi = min(hi, n)
    else:  # at or below it
        hi = hint
        lo = hi
        while lo > 0 and values[lo - 1] > x:
            hi = lo - 1
            lo = hi - step
            step *= 2
        lo = max(lo, 0)
    while lo < hi:  # values[lo - 1] <= x (or lo = 0) and values[hi] > x (or hi = n)
        mid = (lo + hi) // 2
        if values[mid] <= x:
            lo = mid + 1
        else:
            hi = mid
    return lo


@numba.njit(cache=True, nogil=True)
def _shrink_points(a, b, fa, fb, tol, running, poles, pole_free_rtol, below):
    """One round of ``screen_residual(...).shrink`` for the brackets ``running``: each bracket's tolerance
    (``pole_free_rtol`` once none of ``poles`` lies within :data:`POLE_FREE_WINDOW` bracket widths, updated in
    ``tol``), and the brackets not yet done with their next point (regula falsi, :mod:`study.physics.roots`).
    ``below``: per bracket, how many poles lie at or below a − W (b − a) (W the window) at its last check, −1
    before the first; that point only moves up as the bracket shrinks, so each check walks on from there.
    Returns (those brackets, their points)."""
    still, points = np.empty(running.size, dtype=np.int64), np.empty(running.size)
    count, hint = 0, 0
    for i in running:
        if tol[i] != pole_free_rtol and b[i] - a[i] <= pole_free_rtol * abs(b[i]):  # far from every pole?
            left = a[i] - POLE_FREE_WINDOW * (b[i] - a[i])
            if below[i] < 0:  # the brackets come in ascending order: search on from the last one's place
                below[i] = hint = _search_right(poles, left, hint)
            while below[i] < poles.size and poles[below[i]] <= left:
                below[i] += 1
            first = below[i]
            if first == poles.size or poles[first] >= b[i] + POLE_FREE_WINDOW * (b[i] - a[i]):
                tol[i] = pole_free_rtol
        if bracket_done(a[i], b[i], fa[i], fb[i], tol[i]):
            continue
        still[count], points[count] = i, falsi_point(a[i], b[i], fa[i], fb[i])
        count += 1
    return still[:count].copy(), points[:count].copy()


@numba.njit(cache=True, nogil=True)
def _shrink_update(running, points, values, y1, v1, curv1, a, b, fa, fb, raw_a, raw_b, side, states, pole_lo,
                   pole_hi):
    """The brackets ``running`` after F = ``values`` at their ``points`` (G = F (L − pole_lo)(pole_hi − L)):
    the end with G's sign moves there (Illinois weights, :func:`keep_sign_change`), and y₁, v₁, y₁'' there
    are kept for that end (``states`` [0] lower, [1] upper)."""
    for k in range(running.size):
        i, x = running[k], points[k]
        g = values[k] * (x - pole_lo[i]) * (pole_hi[i] - x)
        a[i], b[i], fa[i], fb[i], raw_a[i], raw_b[i], side[i] = keep_sign_change(
            a[i], b[i], fa[i], fb[i], raw_a[i], raw_b[i], side[i], x, g)
        end = 0 if side[i] == 1 else 1
        states[end, 0, i], states[end, 1, i], states[end, 2, i] = y1[k], v1[k], curv1[k]


#: Brackets left below which ``screen_residual(...).shrink`` takes its remaining rounds in one compiled loop
#: (:func:`_shrink_tail`): the brackets next to a pole, shrunk to 1e-10, take up to 40 rounds of a few hundred.
SHRINK_TAIL = 1024


@numba.njit(cache=True, nogil=True)
def _shrink_tail(running, points, rounds, a, b, fa, fb, raw_a, raw_b, side, tol, states, pole_lo, pole_hi, poles,
                 pole_free_rtol, below, table, n_odd, state, closure):
    """The last ``rounds`` rounds of ``screen_residual(...).shrink`` from the brackets ``running`` and their next
    ``points`` on, in one compiled loop: each round the screening pulse at the points (:func:`_pulse_one`), the
    residual and midspan state there (:func:`_screen_batch`), the brackets moved (:func:`_shrink_update`) and
    their next points (:func:`_shrink_points`)."""
    for _ in range(rounds):
        if running.size == 0:
            break
        durations, halves = np.empty(points.size), np.empty(points.size)
        for k in range(points.size):
            durations[k], halves[k] = _pulse_one(points[k], table)
        values, y1, v1, curv1 = _screen_batch(points, durations, halves, n_odd, 1.0, state, closure)
        _shrink_update(running, points, values, y1, v1, curv1, a, b, fa, fb, raw_a, raw_b, side, states, pole_lo,
                       pole_hi)
        running, points = _shrink_points(a, b, fa, fb, tol, running, poles, pole_free_rtol, below)


@numba.njit(cache=True, nogil=True)
def _shrink_result(a, b, fa, fb, raw_a, raw_b, states):
    """Rows root, G at the root, final lo, final hi, and y₁, v₁, y₁'' at the root (NaN at an end no round
    evaluated), the root being the end with the smaller weighted |G| (:func:`closer_end`)."""
    out = np.empty((7, a.size))
    for i in range(a.size):
        out[0, i], out[1, i] = closer_end(a[i], b[i], fa[i], fb[i], raw_a[i], raw_b[i])
        out[2, i], out[3, i] = a[i], b[i]
        end = 0 if out[0, i] == a[i] else 1
        out[4, i], out[5, i], out[6, i] = states[end, 0, i], states[end, 1, i], states[end, 2, i]
    return out


def resonance_widths(residual, spans, modes) -> np.ndarray:
    """Relative width of each resonance [-]: |R|/L_p, R the residue in L of the resonant mode's term of
    the closure residual F at its pole L_p (``spans``, mode numbers ``modes``), in closed form
    (``residual.residue`` of :func:`screen_residual`).

    Near the pole F = R/(L − L_p) + B(L): the resonant mode alone moves F by more than 1 (it alone
    carries the midspan to the wall) only within |L − L_p| < |R|, and the root it pins sits within
    |R/B| of the pole. Light damping of ratio ζ bounds the resonant term by about |R|/(ζ L_p), so a
    resonance with |R|/L_p ≪ ζ has no root once the pipe is damped at all (docs/model.md §7): such a root is
    an artefact of the undamped model.
    """
    spans = np.asarray(spans, dtype=float)
    return np.abs(residual.residue(spans, np.asarray(modes, dtype=float))) / spans


@dataclass
class SpanSearch:
    """All roots of condition 2 in the search range, ascending, with their brackets."""

    roots: np.ndarray
    brackets: np.ndarray  #: (n, 2) the interval between the two poles around each root (free of wide poles)
    pole_count: int
    residual: Any = None  #: the screening residual (with ``.pulse``), for the screening checks
    narrow_count: int = 0  #: poles not searched, their resonance narrower than ``Options.resonance_width``
    #: (3, n) y₁, v₁, y₁'' at each root as :func:`unit_state` with the screening pulse (NaN: not evaluated)
    states: np.ndarray | None = None


def find_roots(scene: Scene, options: Options) -> SpanSearch:
    """Roots of the closure residual F(L) in [min_span, max_span], bracketed between poles.

    Poles whose resonance is narrower than ``options.resonance_width`` (:func:`resonance_widths`) are
    not searched (their residues not even computed where a bound without trigonometry shows it,
    :func:`_residues_kernel`): the root each pins lies within that relative distance of the pole and
    vanishes with any damping of that order. Between the remaining poles the search works on G = F (L − a)(b − L),
    a and b the poles around L: the same roots, continuous up to both poles, where it equals R_a (b − a)
    and −R_b (b − a) (R the poles' residues, :func:`resonance_widths`) — the ends' values in closed
    form, so a root pinned however close to a pole is bracketed. G is sampled between the poles and
    its sign changes are shrunk by regula falsi, to :data:`ROOT_RTOL` where no pole is near and to
    1e-10 where one is. A sign change that converges onto no pole but the interval's own is a root (G
    is continuous there); one with a narrow pole in its last bracket is a root only where |F| has
    fallen far below its values at the samples. (:func:`search_intervals`, then :func:`roots_between`
    over all its intervals.)
    """
    intervals = search_intervals(scene, options)
    return roots_between(intervals, 0, intervals.lo.size, options)


@dataclass
class SearchIntervals:
    """The span search's intervals between consecutive wide poles (and the ends of the search range), ascending,
    with what sampling them needs (:func:`search_intervals`)."""

    poles: np.ndarray  #: every pole in the range [m], ascending (the narrow ones included)
    lo: np.ndarray  #: each interval's lower end [m]
    hi: np.ndarray  #: each interval's upper end [m]
    residue_lo: np.ndarray  #: the residue [m] of the pole at lo (NaN: the end of the search range)
    residue_hi: np.ndarray  #: the residue [m] of the pole at hi (NaN: the end of the search range)
    residual: Any = None  #: the screening residual (:func:`screen_residual`); None: no span gives a valid pulse
    narrow_count: int = 0  #: poles not searched, their resonance narrower than ``Options.resonance_width``


def search_intervals(scene: Scene, options: Options) -> SearchIntervals:
    """The poles in [min_span, max_span], their residues, and the intervals between the wide ones
    (steps 1–2 of :func:`find_roots`): no interval when no span gives a valid pulse."""
    modes = odd_modes(options.modes)
    poles, pole_modes = resonances(scene, modes, options.min_span, options.max_span)
    residual = screen_residual(scene, options)
    if residual is None:
        empty = np.zeros(0)
        return SearchIntervals(poles, empty, empty, empty, empty)
    floors = options.resonance_width * poles  # resonance_widths, from the same residues (NaN: narrow for sure)
    residues = residual.residue(poles, pole_modes.astype(float), floors) if poles.size else np.zeros(0)
    wide = np.abs(residues) >= floors
    edges, edge_residues = _merged_poles(poles[wide], residues[wide])
    edges = np.concatenate([[options.min_span], edges, [options.max_span]])
    edge_residues = np.concatenate([[np.nan], edge_residues, [np.nan]])  # NaN: the search range's end, no pole
    lo, hi = edges[:-1], edges[1:]
    keep = hi > lo * (1 + 1e-12)
    return SearchIntervals(poles, lo[keep], hi[keep], edge_residues[:-1][keep], edge_residues[1:][keep], residual,
                           int(np.count_nonzero(~wide)))


def roots_between(intervals: SearchIntervals, first: int, stop: int, options: Options) -> SpanSearch:
    """The roots of condition 2 in the intervals ``first`` to ``stop`` − 1 of ``intervals`` (steps 3 of
    :func:`find_roots`: sampled, bracketed and shrunk), ascending. Each interval's roots depend on that
    interval alone, so the search can be taken a run of intervals at a time."""
    lo, hi = intervals.lo[first:stop], intervals.hi[first:stop]
    residue_lo, residue_hi = intervals.residue_lo[first:stop], intervals.residue_hi[first:stop]
    poles, residual = intervals.poles, intervals.residual
    if lo.size == 0:
        return SpanSearch(np.array([]), np.zeros((0, 2)), int(poles.size), residual,
                          narrow_count=intervals.narrow_count, states=np.zeros((3, 0)))
    # samples strictly inside each interval, denser towards the poles where F changes fastest; at a
    # pole G is R (b − a) in closed form, at an end of the search range F is computed just inside it
    fractions = 0.5 - 0.5 * np.cos(np.pi * (np.arange(options.samples) + 0.5) / options.samples)
    spans, inside = _sample_spans(lo, hi, residue_lo, residue_hi, fractions)
    brackets = _sign_changes(spans, residual(inside), lo, hi, residue_lo, residue_hi)
    if brackets.shape[1] == 0:
        return SpanSearch(np.array([]), np.zeros((0, 2)), int(poles.size), residual,
                          narrow_count=intervals.narrow_count, states=np.zeros((3, 0)))
    # regula falsi on G: no singularity at the ends, so it converges in a few steps instead of
    # crawling along the pole's hyperbola
    roots, root_values, final_lo, final_hi, states = residual.shrink(*brackets[:6], poles=poles,
                                                                     pole_free_rtol=ROOT_RTOL)
    # G is continuous between poles and at the wide ones around the interval: a sign change left in a
    # bracket free of every other pole (the narrow ones included) is a root. One with a narrow pole
    # inside may have converged onto the pole, where |F| grows: it is a root only if |F| there is
    # far below its value at the samples.
    real = _real_roots(roots, root_values, final_lo, final_hi, brackets[4], brackets[5], brackets[6], poles)
    between = np.stack([brackets[4][real], brackets[5][real]], axis=1)
    return SpanSearch(roots=roots[real], brackets=between, pole_count=int(poles.size), residual=residual,
                      narrow_count=intervals.narrow_count, states=states[:, real])


@numba.njit(cache=True, nogil=True)
def _sample_spans(lo, hi, residue_lo, residue_hi, fractions):
    """The samples of :func:`roots_between`, (intervals, samples + 2) [m]: each interval's ends (its poles;
    the search range's ends, NaN residue, moved 1e-12 inside) and lo + (hi − lo) ``fractions`` between them;
    and, flat in row order, those where F is computed (all but the poles)."""
    n, m = lo.size, fractions.size
    spans = np.empty((n, m + 2))
    inside = np.empty(n * (m + 2))
    count = 0
    for i in range(n):
        width = hi[i] - lo[i]
        spans[i, 0] = lo[i] * (1.0 + 1e-12) if math.isnan(residue_lo[i]) else lo[i]
        spans[i, m + 1] = hi[i] * (1.0 - 1e-12) if math.isnan(residue_hi[i]) else hi[i]
        for j in range(m):
            spans[i, j + 1] = lo[i] + width * fractions[j]
        for j in range(m + 2):
            if 0 < j < m + 1 or (j == 0 and math.isnan(residue_lo[i])) or (j == m + 1 and math.isnan(residue_hi[i])):
                inside[count] = spans[i, j]
                count += 1
    return spans, inside[:count].copy()


@numba.njit(cache=True, nogil=True)
def _sign_changes(spans, inside_values, lo, hi, residue_lo, residue_hi):
    """The sign changes of G = F (L − lo)(hi − L) between consecutive samples of :func:`_sample_spans` (F at its
    flat ``inside`` spans; at a pole G is R (hi − lo) and −R (hi − lo), R its residue). Rows: bracket lo, hi [m],
    G there, the interval's lo, hi [m], and the smaller |F| at the bracket's two samples (infinite at a pole)."""
    n, m = spans.shape
    g, f = np.empty(m), np.empty(m)
    out = np.empty((7, n * (m - 1)))
    count, k = 0, 0
    for i in range(n):
        width = hi[i] - lo[i]
        for j in range(m):
            pole = (j == 0 and not math.isnan(residue_lo[i])) or (j == m - 1 and not math.isnan(residue_hi[i]))
            if pole:
                f[j] = math.inf
                g[j] = residue_lo[i] * width if j == 0 else -residue_hi[i] * width
            else:
                f[j] = inside_values[k]
                g[j] = f[j] * (spans[i, j] - lo[i]) * (hi[i] - spans[i, j])
                k += 1
        for j in range(m - 1):
            if (g[j] > 0.0 and g[j + 1] < 0.0) or (g[j] < 0.0 and g[j + 1] > 0.0):
                out[0, count], out[1, count] = spans[i, j], spans[i, j + 1]
                out[2, count], out[3, count] = g[j], g[j + 1]
                out[4, count], out[5, count], out[6, count] = lo[i], hi[i], min(abs(f[j]), abs(f[j + 1]))
                count += 1
    return out[:, :count].copy()


@numba.njit(cache=True, nogil=True)
def _real_roots(roots, root_values, final_lo, final_hi, lo, hi, ends, poles):
    """Which shrunk sign changes of G are roots (:func:`roots_between`): those whose last bracket [final_lo,
    final_hi] (widened by 1e-12, the interval [lo, hi]'s own poles excluded) holds no pole of ``poles`` (sorted),
    and those where |F| = |G|/((L − lo)(hi − L)) has fallen below 1e-3 of ``ends`` (the smaller |F| at the
    bracket's samples). The brackets come in ascending order, so the poles are walked through once."""
    out = np.empty(roots.size, dtype=np.bool_)
    k = np.searchsorted(poles, lo[0]) if roots.size else 0
    for r in range(roots.size):
        margin = 1e-12 * final_hi[r]
        start = max(final_lo[r] - margin, lo[r] * (1 + 2e-12))
        stop = min(final_hi[r] + margin, hi[r] * (1 - 2e-12))
        while k > 0 and poles[k - 1] >= start:
            k -= 1
        while k < poles.size and poles[k] < start:
            k += 1
        unsure = k < poles.size and poles[k] <= stop
        distance = (roots[r] - lo[r]) * (hi[r] - roots[r])
        out[r] = not unsure or abs(root_values[r] / distance) < 1e-3 * ends[r]
    return out


def _merged_poles(poles, residues):
    """Poles [m] closer than 1e-12 (relative) to the one before merged into one, with the sum of their
    residues [m] (coinciding resonances of two modes add their terms); both ascending."""
    if poles.size == 0:
        return poles, residues
    first = np.concatenate([[True], poles[1:] > poles[:-1] * (1 + 1e-12)])
    starts = np.nonzero(first)[0]
    return poles[starts], np.add.reduceat(residues, starts)


def midspan_screen(scene: Scene, options: Options, search: SpanSearch) -> np.ndarray:
    """Cheap necessary conditions for every root at once (with the screening T_L and b): the midspan
    approaches the wall before contact, the pipe is convex towards the wall there (the checks
    :func:`impact_at` makes at its first iterate) and the midspan stays inside the hole over the
    period. True = survives."""
    if search.roots.size == 0:
        return np.zeros(0, dtype=bool)
    spans = search.roots
    duration, half = search.residual.pulse(spans)
    c, e = scene.clearance, scene.restitution
    y0, v0, curv0 = np.full((3, spans.size), np.nan) if search.states is None else search.states.copy()
    missing = np.isnan(y0)  # where the search did not evaluate the state at the root
    if np.any(missing):
        y0[missing], v0[missing], curv0[missing] = unit_state(scene, spans[missing], duration[missing], half[missing],
                                                              options)
    m_e = scene.equivalent_mass(spans)
    impulse = -c / y0 if scene.closure == "self_consistent" else m_e * (1.0 + e) * scene.rotary_speed * c
    # as impact_at rejects at its first iterate: approach, convex towards the wall, a positive impulse
    keep = (-impulse * v0 > 0) & (impulse * curv0 > 0) & (impulse > 0)
    rows = np.nonzero(keep)[0]
    if rows.size == 0:
        return keep
    spans, duration, half, impulse = spans[rows], duration[rows], half[rows], np.broadcast_to(impulse, keep.shape)[rows]
    span_t = scene.impact_interval
    # coarse (sampling can miss a violation, never invent one): 48 times after the pulse, interleaved
    # so that the first dozen span the whole period, each root dropped at its first violation
    fractions = np.linspace(0.0, 1.0, 50)[1:-1].reshape(-1, 4).T.ravel()
    times = duration[:, None] + (span_t - duration[:, None]) * fractions[None, :]  # after the pulse, per root
    limit = c * 1.02 / np.abs(impulse)
    # the verdict of largest_excursion without its library calls where rounding cannot change it, it elsewhere
    p = scene.props
    verdict = midspan.excursion_verdicts(times, spans, duration, half, odd_modes(options.modes).size,
                                         p["bending_stiffness"], p["effective_tension"], p["mass_per_length"],
                                         scene.period, scene.pattern, options.load_shape, limit=limit)
    within = verdict == 0
    unsure = np.nonzero(verdict < 0)[0]
    if unsure.size:
        omega, weight = midspan_weights(scene, spans[unsure], half[unsure], options)
        largest = beam.largest_excursion(times[unsure], omega, duration[unsure], weight, scene.period, scene.pattern,
                                         limit=limit[unsure])
        within[unsure] = largest <= limit[unsure]  # NaN (a resonant mode): dropped
    keep[rows] = within
    return keep


def midspan_weights(scene: Scene, spans, halves, options: Options) -> tuple[np.ndarray, np.ndarray]:
    """(ω_n [rad/s], w_n [m/(N s)]) of shape (spans, odd modes): the natural frequencies and the
    midspan deflection of each mode per unit modal coordinate per unit impulse, 2 g_n sin(nπ/2)/(M L)
    (g_n :func:`beam.modal_load_factors` for contact half-lengths ``halves`` [m]) — the weights that
    :func:`beam.largest_excursion` sums, as :func:`beam.periodic_fields` does at x = L/2."""
    spans = np.asarray(spans, dtype=float)
    modes = odd_modes(options.modes)
    g = beam.modal_load_factors(modes, spans, np.asarray(halves, dtype=float), options.load_shape)
    weight = 2.0 * g / (scene.props["mass_per_length"] * spans[:, None]) * np.where(modes % 4 == 1, 1.0, -1.0)
    return scene.natural_frequencies(spans, modes), weight
