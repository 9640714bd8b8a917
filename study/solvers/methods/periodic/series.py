"""The ``series`` periodic method: the paper's double Fourier series (docs/model.md §4, §9 "series").

The design point is solved exactly as by the ``fast`` method — the pole-bracketed span search, the
midspan screen, the exact refinement and the constraint check of :mod:`study.solvers.methods.periodic`
(:func:`design_point`) — but the fields at the chosen span (deflection, bending moment, shear) come
from the paper's double series :func:`study.physics.fourier.series_field`, n_modes (odd n ≤ N) ×
harmonics (m ≤ M) terms, with NO quasi-static correction. It is the reproduction of the paper and
the slow baseline against which the fast method is measured (:func:`study.benchmarks.series.convergence_table`).

Truncation. N is ``solver.modes`` (as for fast). M is ``solver.harmonics`` (default
:data:`DEFAULT_HARMONICS`) or, with ``solver.series_tolerance`` set, found by doubling M from that
start until the maximum normal stress changes by less than the tolerance, at most
``solver.series_max_harmonics`` (default :data:`MAX_HARMONICS`; status ``not_converged`` when the cap
is reached first).

Error estimate. The larger of two: the relative change of the maximum normal stress between the last
two truncations in time (M/2 and M), and the bound on the modes left out
(``periodic.truncation_bound``, shared with ``fast``). The first alone is what the paper could have
done to judge its own truncation, and it is NOT a bound:
on the test case of ``tests/solvers/test_series.py`` the change from M = 1600 to 3200 at N = 99 is
below 1e-6 while the error against the converged series is 2.2e-4 — a near-resonant mode above N
(n = 219, 0.001 harmonics from resonance) is invisible to a comparison in M, and a near-resonant
harmonic above M is invisible until M reaches it; hence the second.

Both periodic methods compute stresses from fields the same way
(:func:`study.solvers.kernels.extremes.stresses_from_fields`, the contract of ``fast.stresses``), and both can
report the paper's §VI term-ratio table (:func:`term_ratio_table`, stored in ``extras["term_ratios"]``; status
``terms_not_small`` when the verdict of :func:`study.solvers.methods.periodic.checks.dropped_terms_small` fails on an
otherwise valid point).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from study.physics import beam, fourier
from study.solvers.kernels import extremes
from study.solvers.kernels import impact as impact_model
from study.solvers.methods.periodic import checks
from study.solvers.methods import periodic
from study.solvers.model.options import SeriesOptions, study_tolerance
from study.solvers.model.point import DesignPoint
from study.solvers.model.result import PointResult
from study.solvers.model.scene import Scene

#: Highest harmonic number M of the series when neither ``harmonics`` nor a tolerance is given.
DEFAULT_HARMONICS = SeriesOptions.default("harmonics")
#: Cap on M when doubling to meet ``series_tolerance``.
MAX_HARMONICS = SeriesOptions.default("series_max_harmonics")
#: Kinds of field the stresses need (keys of :func:`fields`).
STRESS_KINDS = ("deflection", "moment", "shear")


@dataclass(frozen=True)
class Truncation:
    """Time truncation of the series: fixed M, or doubling from M until ``tolerance`` (≤ ``cap``)."""

    harmonics: int = DEFAULT_HARMONICS
    tolerance: float | None = None
    cap: int = MAX_HARMONICS


def truncation_from(option: SeriesOptions) -> Truncation:
    """The truncation of the series' options ``harmonics``, ``series_tolerance``, ``series_max_harmonics``."""
    return Truncation(harmonics=int(option.harmonics),
                      tolerance=None if option.series_tolerance is None else float(option.series_tolerance),
                      cap=int(option.series_max_harmonics))


# --- fields and stresses -----------------------------------------------------------------------
def _beam_args(scene: Scene, impact: impact_model.Impact, options: periodic.Options) -> dict[str, Any]:
    """Keyword arguments of the beam field functions for this span and impact (the real load pushes
    the pipe off the wall: impulse −J, as in ``fast.stresses``)."""
    p = scene.props
    return {"span_length": impact.span_length, "bending_stiffness": p["bending_stiffness"],
            "tension": p["effective_tension"], "mass": p["mass_per_length"], "impulse": -impact.impulse,
            "pulse_duration": impact.contact_duration, "period": scene.period, "pattern": scene.pattern,
            "half_length": impact.contact_half_length, "shape": options.load_shape, "n_modes": options.modes}


def stress_grid(scene: Scene, impact: impact_model.Impact, options: periodic.Options):
    """(x, t): the solver's grids over the half span and the (half) period (as ``fast.stresses``)."""
    return (periodic.space_grid(impact.span_length, impact.contact_half_length, options),
            periodic.time_grid(scene, impact.contact_duration, options))


def fields(scene: Scene, impact: impact_model.Impact, options: periodic.Options, harmonics: int | None = None,
           kinds: Iterable[str] = STRESS_KINDS, x=None, t=None) -> dict[str, np.ndarray]:
    """Fields of the periodic solution at this span and impact, shape t.shape + x.shape.

    harmonics None: the fast method's fields (closed form in time, quasi-static correction;
    ``beam.deflection``/``bending_moment``/``shear_force``, kinds deflection, moment, shear only).
    harmonics M: the paper's double series ``fourier.series_field`` with options.modes × M terms, any
    kind of :data:`study.physics.fourier.SERIES_KINDS`. x, t default to :func:`stress_grid`.
    """
    if x is None or t is None:
        gx, gt = stress_grid(scene, impact, options)
        x = gx if x is None else x
        t = gt if t is None else t
    args = _beam_args(scene, impact, options)
    if harmonics is None:
        unknown = [k for k in kinds if k not in beam.FIELD_KINDS]
        if unknown:
            raise ValueError(f"the fast fields are {', '.join(beam.FIELD_KINDS)}; not {', '.join(unknown)}")
        return beam.periodic_fields(x, t, list(kinds), **args)
    return fourier.series_fields(x, t, list(kinds), harmonics=int(harmonics), **args)


def stresses(scene: Scene, impact: impact_model.Impact, inputs: Mapping[str, Any],
             options: periodic.Options, harmonics: int | None = None) -> dict[str, float]:
    """Stress maxima (docs/model.md §5, paper eq. 37–38) from the fast fields (harmonics None: the ``fast`` method's)
    or from the double series with options.modes × harmonics terms, sampled on :func:`stress_grid` and
    located to a tenth of the study's tolerance (:func:`extremes.stresses_from_fields`)."""
    x, t = stress_grid(scene, impact, options)
    f = fields(scene, impact, options, harmonics, STRESS_KINDS, x, t)

    def field_at(kind, xs, ts):
        return fields(scene, impact, options, harmonics, (kind,), xs, ts)[kind]

    return extremes.stresses_from_fields(scene, x, t, f["deflection"], f["moment"], f["shear"],
                                         field_at=field_at, tolerance=study_tolerance(inputs))


@dataclass
class SeriesStresses:
    """Series stresses at the final truncation and the history of the doubling."""

    values: dict[str, float]
    harmonics: int
    change: float  #: relative change of max normal stress between the last two truncations
    converged: bool
    history: list[tuple[int, float]] = field(default_factory=list)  #: (M, max normal stress)


def converged_stresses(scene: Scene, impact: impact_model.Impact, inputs: Mapping[str, Any],
                       options: periodic.Options, truncation: Truncation) -> SeriesStresses:
    """Series stresses with the time truncation of ``truncation``.

    Fixed M: evaluated at M//2 and M, ``change`` = |σ(M) − σ(M/2)|/σ(M) for the max normal stress σ.
    With a tolerance: M doubles from truncation.harmonics until change < tolerance or M would exceed
    the cap. ``converged`` is change < tolerance (fixed M: always True). Not a bound (module doc).
    """
    m = max(2, int(truncation.harmonics))
    history: list[tuple[int, float]] = []
    values = stresses(scene, impact, inputs, options, m // 2)
    history.append((m // 2, values["max_normal_stress"]))
    while True:
        values = stresses(scene, impact, inputs, options, m)
        history.append((m, values["max_normal_stress"]))
        change = abs(history[-1][1] - history[-2][1]) / abs(history[-1][1])
        if truncation.tolerance is None:
            return SeriesStresses(values, m, float(change), True, history)
        if change < truncation.tolerance:
            return SeriesStresses(values, m, float(change), True, history)
        if 2 * m > truncation.cap:
            return SeriesStresses(values, m, float(change), False, history)
        m *= 2


# --- the paper's §VI term ratios -----------------------------------------------------------------
def term_grid(scene: Scene, impact: impact_model.Impact, points_per_pulse: int = 8, max_times: int = 2048,
              space_points: int = 49):
    """(x, t) for the term ratios: UNIFORM grids over the half span [0, L/2] and the (half) period,
    so that the averages (B) are the paper's time and location averages (the solver's grid is dense
    across the pulse and would weight it). Δt ≤ T_L/points_per_pulse, at most max_times points."""
    span_t = scene.impact_interval
    nt = int(min(max_times, max(200, np.ceil(span_t / impact.contact_duration * points_per_pulse))))
    return (np.linspace(0.0, 0.5 * impact.span_length, space_points),
            np.linspace(0.0, span_t, nt, endpoint=False))


def term_ratio_table(scene: Scene, impact: impact_model.Impact,
                     options: periodic.Options, harmonics: int = DEFAULT_HARMONICS) -> dict[str, Any]:
    """The paper's §VI table for this span and impact (docs/model.md §6) and its verdict.

    Terms of EI y'''' − T0 y'' + m_i V_m² y'' + M ÿ + D|ẏ|ẏ = p (``checks.TERMS``: bending, tension,
    mud_flow, inertia, drag) from the double series (options.modes × harmonics terms, the same
    solution for either periodic method: the fast fields have no closed form for y'''' and ÿ) on
    :func:`term_grid`, the contact |x − L/2| ≤ b during 0 ≤ t ≤ T_L masked out. Ratios relative to
    the drag term (= 1), ``checks.term_ratios``; verdict ``checks.dropped_terms_small`` on the drag.
    Returns {"ratios": table, "ok": bool, "message": str, "modes": N, "harmonics": M}.
    """
    x, t = term_grid(scene, impact)
    f = fields(scene, impact, options, harmonics, checks.FIELDS, x, t)
    p = scene.props
    props = {"bending_stiffness": p["bending_stiffness"], "axial_tension": scene.axial_tension,
             "internal_mud_mass": p["internal_mud_mass"],
             "mud_flow_velocity": float(scene.mud_flow_velocity),
             "mass_per_length": p["mass_per_length"],
             "drag_coefficient_per_length": p["drag_coefficient_per_length"]}
    magnitudes = checks.term_magnitudes(f, props)
    contact = ((np.abs(x - 0.5 * impact.span_length) <= impact.contact_half_length)[None, :]
               & (t <= impact.contact_duration)[:, None])
    ratios = checks.term_ratios(magnitudes, reference="drag", exclude=contact)
    ok, message = checks.dropped_terms_small(ratios)
    return {"ratios": ratios, "ok": bool(ok), "message": message, "modes": int(options.modes),
            "harmonics": int(harmonics)}


def add_term_ratios(scene: Scene, impact: impact_model.Impact, inputs: Mapping[str, Any],
                    options: periodic.Options, result: PointResult, harmonics: int = DEFAULT_HARMONICS) -> None:
    """Store :func:`term_ratio_table` in ``result.extras["term_ratios"]``; an otherwise "ok" point whose
    dropped drag is not small becomes "terms_not_small" (either periodic method may call this)."""
    table = term_ratio_table(scene, impact, options, harmonics)
    result.extras["term_ratios"] = table
    if not table["ok"] and result.status == "ok":
        result.status = "terms_not_small"
        result.message += f"; {table['message']}"


def solve(inputs: Mapping[str, Any]) -> PointResult:
    """The series at a point given by its SI inputs (:func:`run` of its :class:`DesignPoint`)."""
    return run(DesignPoint.from_inputs(inputs))


def run(point: DesignPoint) -> PointResult:
    """Find the span (as ``fast``) and evaluate it with the paper's double Fourier series."""
    truncation = truncation_from(point.series)

    def finish(scene, chosen, inputs, options, result):
        s = converged_stresses(scene, chosen, inputs, options, truncation)
        result.values.update(s.values)
        # The change with the harmonics says nothing of the modes left out: add their bound.
        modes_bound = periodic.truncation_bound(scene, chosen, options) / s.values["max_normal_stress"]
        result.error_estimate = max(s.change, modes_bound) + s.values["location_residual"]
        result.extras.update(series_modes=int(options.modes), series_harmonics=int(s.harmonics),
                             series_history=[list(h) for h in s.history])
        if not s.converged:
            result.status = "not_converged"
            result.message += (f"; max normal stress still changes by {s.change:.2g} at {s.harmonics} harmonics "
                               f"(tolerance {truncation.tolerance:.2g}, cap {truncation.cap})")
        add_term_ratios(scene, chosen, inputs, options, result, s.harmonics)

    return periodic.design_point(point, "series", finish)
