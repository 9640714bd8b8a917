"""The model hierarchy: per design point, the cheapest model that serves it (docs/model.md §9).

A ladder is module data (:data:`LADDERS`), cheapest rung first: each rung names a method and, above the
first, which failures of the rung below it the rung can mend (:data:`MENDS`). A point is solved by the first
rung; its result passes the gate every result passes (:func:`study.solvers.model.gate.admit`); if it is not ``ok``
and the next rung can mend that failure, the point goes up. What a point ends with is the first ``ok``
result, or — when nothing served — the ``not_converged`` answer with the smallest error estimate among the
rungs tried (else the last rung's result), with the ladder it climbed at the head of its message and in
``extras["methods_tried"]`` (method → status and error estimate). A status no rung
can mend (buckling, missing inputs) is a property of the point, returned at once.

``auto`` (the default study's method) climbs the reference model's hierarchy:

- ``free-whirl``: the reference model's scene clear of the wall, in closed form (synchronous whirl about the
  sag; exact there) — a few milliseconds; ``out_of_scope`` where the free motion would reach the wall;
- ``sliding``: the same scene lying on the wall at its tool joints (an inclined hole), the contact held and
  sliding round: the rest on the wall and the synchronous whirl about it — milliseconds; the state the
  reference model reaches only as its start-up ringing dies (after hundreds of revolutions, more than its
  budget); ``out_of_scope`` where the contact would open or the section does not reach the wall; where its
  error estimate is above the tolerance but within :data:`SLIDING_STANDS_BELOW` (5 %) its ``not_converged``
  answer stands, the reference model's being farther from convergence there;
- ``reference``: the section in both lateral directions through Hertz contact with friction — a fraction of a
  second to seconds; it mends whatever the cheaper rungs could not answer.

Every rung is given the same typed design point (:class:`~study.solvers.model.point.DesignPoint`, built once by
:func:`study.solvers.solve_point`); the series gets it with its own harmonics' tolerance.

The free whirl depends on no restitution (``INDEPENDENT_OF`` in its module): its answers are kept by the other inputs
(:func:`solve_rung`), so a sweep over the restitution solves it once. (The sliding state's figures do not depend on it
either, but its checks of stability and of a second motion run the reference model, whose held contacts it damps.)

Where the sliding state is stable but a second motion coexists with it (the reference model's run from rest bounces,
or chatters on the wall: output ``coexisting_motion`` 1), the point goes up too and its answer is the reference
model's, the worse for the limits, flagged and naming the sliding one's figures — unless that run came to the sliding
motion, told by its regime and its design figures within their stated errors (:func:`worse_figures`,
:func:`_coexisting`). Where it chatters the reference model starts at the check's mode count (:func:`_chatter_modes`).

The paper's periodic solution is not on this ladder: the reference check (method ``reference-check``,
docs/reference_model.md) found it outside the study's tolerance at every point surveyed — it strikes the wall
where the section whirls clear of it, and where both touch its forces and stresses are off by factors. It keeps
a ladder of its own, ``periodic``: ``fast``, then the paper's ``series`` where only ``fast``'s error estimate
failed and its span held with doubled modes (the series searches the same spans), then the paper's ``damped``
solution where the undamped one's dropped drag is not small (``terms_not_small``, docs/model.md §6, §7.1).
"""

from __future__ import annotations

import copy
import re
import sys
import threading
from collections import OrderedDict
from dataclasses import replace
from typing import Any, Callable, Mapping

import numpy as np

from study.solvers.methods.periodic import damped, fast, series
from study.solvers.methods import freewhirl, reference, sliding, sliding_parts
from study.solvers.model import gate
from study.solvers.model.options import Tolerances
from study.solvers.model.point import DesignPoint
from study.solvers.model.result import PointResult

Solve = Callable[[DesignPoint], PointResult]
#: Statuses that are properties of the point: no model answers them differently.
FINAL = ("buckled", "incomplete")


def _error_only(result: PointResult, point: DesignPoint) -> bool:
    """The span held with doubled modes and only the error estimate is above the tolerance."""
    tolerance = point.tolerances.tolerance
    return (result.status == "not_converged" and result.extras.get("span_converged", False)
            and result.error_estimate is not None and result.error_estimate > tolerance)


def _not_final(result: PointResult, point: DesignPoint) -> bool:
    """Anything but a property of the point: the reference model answers what the free whirl cannot."""
    return result.status not in FINAL


#: Up to this error estimate a sliding answer stands where it is not converged: the reference model reaches the
#: sliding state only over hundreds of revolutions (docs/reference_model.md §10), more than its budget, and at the
#: default study's 8 such points it ended 19-31 % from convergence against the sliding method's 1.9-2.2 %.
SLIDING_STANDS_BELOW = 0.05


def _not_final_nor_sliding(result: PointResult, point: DesignPoint) -> bool:
    """Anything the sliding state does not answer well enough: not this state (``out_of_scope``), or its answer
    not converged with an error estimate above :data:`SLIDING_STANDS_BELOW`."""
    if result.method == "sliding" and result.values.get("coexisting_motion") == 1.0:
        return True  # a second motion coexists with it: the reference model's run decides (:func:`climb`)
    if result.method == "sliding" and result.status == "not_converged":
        return result.error_estimate is None or not result.error_estimate <= SLIDING_STANDS_BELOW
    return _not_final(result, point)


def _drag_not_small(result: PointResult, point: DesignPoint) -> bool:
    """The undamped solution answered but its dropped drag term is not small: the damped solution keeps it."""
    return result.status == "terms_not_small"


def as_is(point: DesignPoint, below: PointResult | None = None) -> DesignPoint:
    """The point as the ladder was given it."""
    return point


def _series_point(point: DesignPoint, below: PointResult | None = None) -> DesignPoint:
    """The series doubles its harmonics until the study's tolerance."""
    tolerance = point.series.series_tolerance or point.tolerances.tolerance
    return point.with_series(replace(point.series, series_tolerance=tolerance))


def _chatter_modes(point: DesignPoint, below: PointResult | None = None) -> DesignPoint:
    """The point as given, or, where the rung below (the sliding state) found a chatter on the wall beside its motion
    (its check's run from rest, ``sliding_parts.from_rest``: a joint striking revolution after revolution while the
    others hold the string on the wall), with the reference model's first mode count raised to the check's, at least:
    the default's 16 modes do not carry the chatter the check's 48 show (at default grid point 384 the run from rest on
    16 modes settles, on 32-64 it chatters; docs/reference_model.md §10). Where the chatter came late (the check's run
    settled on the wall, then chattered: ``late``), its transient lasts at least until the check's last window began
    (``reference_min_revolutions``): the same run from the same rest on those modes, whose start-up's strikes a shorter
    transient would take for the motion (at default grid point 650 its statistics found them stationary after 12
    revolutions)."""
    found = below.extras.get("second_motion") if below is not None else None
    if not found or not found.get("chattered"):
        return point
    modes = max(int(point.reference.reference_modes), int(found["modes"]))
    late = {}
    if found.get("late") is not None:
        late["reference_min_revolutions"] = max(int(point.reference.reference_min_revolutions),
                                                int(found["revolutions"]) - sliding_parts.LATE_WINDOW)
    return point.with_reference(reference_modes=modes,
                                reference_max_modes=max(modes, int(point.reference.reference_max_modes)), **late)


#: The hierarchies, cheapest first: ladder -> {method name: (its typed solve, the point it is given from the ladder's
#: and the result of the rung below, None on the first)}.
LADDERS: dict[str, dict[str, tuple[Solve, Callable[[DesignPoint, PointResult | None], DesignPoint]]]] = {
    "auto": {"free-whirl": (freewhirl.run, as_is), "sliding": (sliding.run, as_is),
             "reference": (reference.run, _chatter_modes)},
    "periodic": {"fast": (fast.run, as_is), "series": (series.run, _series_point), "damped": (damped.run, as_is)},
}
#: For each rung above the first: which results of the rung below it the rung can mend.
MENDS: dict[str, Callable[[PointResult, DesignPoint], bool]] = {
    "sliding": _not_final,
    "reference": _not_final_nor_sliding,
    "series": _error_only,
    "damped": _drag_not_small,
}


#: The answers of rungs whose method declares inputs it does not depend on (its module's ``INDEPENDENT_OF``), kept
#: by the other inputs, at most this many in a process (the least recently used dropped): a sweep over the
#: restitution solves the free whirl once for all its values.
MEMO_SIZE = 4096
_memo: OrderedDict[tuple, PointResult] = OrderedDict()
_memo_lock = threading.Lock()  # a worker may run several threads


def clear_memo() -> None:
    """Empty the memo of rung answers (:data:`MEMO_SIZE`): a benchmark's runs each start from nothing."""
    with _memo_lock:
        _memo.clear()


def solve_rung(method: Solve, point: DesignPoint) -> PointResult:
    """``method(point)``, or a copy of its answer at a point whose inputs differ only in what the method does not
    depend on (:data:`MEMO_SIZE`)."""
    ignored = getattr(sys.modules[method.__module__], "INDEPENDENT_OF", ())
    if not ignored:
        return method(point)
    key = (method.__module__, method.__qualname__,
           tuple(sorted((name, repr(value)) for name, value in point.inputs.items() if name not in ignored)))
    with _memo_lock:
        kept = _memo.get(key)
        if kept is not None:
            _memo.move_to_end(key)
    if kept is None:
        result = method(point)
        with _memo_lock:
            _memo[key] = copy.deepcopy(result)  # as answered, before the gate and the climb add to it
            if len(_memo) > MEMO_SIZE:
                _memo.popitem(last=False)
        return result
    result = copy.deepcopy(kept)
    return result


def figure_error(result: PointResult, name: str, tolerance: float) -> float:
    """The relative error [-] of ``result``'s figure ``name`` that :func:`worse_figures` credits: its own output
    ``<name>_error`` where the result states one (the reference model, docs/reference_model.md §3.1), else its error
    estimate (the sliding state's: the largest over its figures), at most ``tolerance`` (the figure's: a figure known
    only within more than its tolerance cannot show another to be the same figure beyond it); ``tolerance`` where
    neither is stated."""
    own = result.values.get(f"{name}_error")
    stated = own if own is not None and np.isfinite(own) else result.error_estimate
    if stated is None or not np.isfinite(stated):
        return tolerance
    return min(float(stated), tolerance)


def worse_figures(lower: PointResult, higher: PointResult, tolerances: Tolerances) -> dict[str, tuple[float, float]]:
    """The design figures (``sliding.FIGURES``: peak contact force, max normal and alternating stress) in which
    ``higher``'s motion is worse than ``lower``'s — figure → (higher's h, lower's l) — where

        h − l > (t + e_h) |h| + e_l |l|,

    t the figure's tolerance (``tolerances.force`` for the force; for the stresses the higher run's,
    :func:`gate.held_to`), e_h and e_l the figures' stated relative errors as :func:`figure_error` credits them (each
    at most t). t is what the study calls the same figure, and it covers what a reference run's stated error leaves
    out: a run on its way to the sliding motion still rings, its figures above that motion's by more than its window's
    scatter states (docs/reference_model.md §10). A figure either does not have counts as worse (nothing shows it is
    not). Empty: the higher run's figures are those of the lower's motion, or lower."""
    stress_tolerance = gate.held_to(higher.values, tolerances)[0]
    worse = {}
    for name in sliding.FIGURES:
        tolerance = tolerances.force if name == "peak_contact_force" else stress_tolerance
        h, lo = higher.values.get(name, np.nan), lower.values.get(name, np.nan)
        allowed = ((tolerance + figure_error(higher, name, tolerance)) * abs(h)
                   + figure_error(lower, name, tolerance) * abs(lo))
        if not (np.isfinite(h) and np.isfinite(lo)) or h - lo > allowed:
            worse[name] = (float(h), float(lo))
    return worse


#: The scale and unit in which :func:`_coexisting`'s messages give the figures of ``sliding.FIGURES``.
FIGURE_UNITS = {"peak_contact_force": (1.0, "N"), "max_normal_stress": (1e6, "MPa"),
                "alternating_bending_stress": (1e6, "MPa")}


def _figure(name: str, value: float) -> str:
    """``value`` of the figure ``name`` as a message names it (the reference model's name of it)."""
    scale, unit = FIGURE_UNITS[name]
    return f"{reference.FIGURES[name][1]} {value / scale:.4g} {unit}"


def _coexisting(tried: list[PointResult], tolerances: Tolerances) -> PointResult | None:
    """The point's answer where a rung found a stable motion beside a second one (output ``coexisting_motion`` 1: the
    sliding state, :func:`study.solvers.methods.sliding_parts.second_motion`) and a higher rung answered it after.

    The higher run came to the stable motion where its regime is the stable motion's and none of its design figures
    is above the stable motion's beyond their tolerance and stated errors (:func:`worse_figures`, each figure's error
    credited up to its tolerance, so a run not converged is judged by its figures as far as its error and the
    tolerance allow, and a run that strikes at three times the sliding force is another motion whatever its label
    and its stated error): the stable motion's answer then stands, flagged 0 (its second motion not found by the
    higher model). Else the higher rung's answer — the motion the pipe reaches from rest, the safe side for the limits
    (a kicked pipe bounces or chatters on the wall), whatever its error — flagged with ``coexisting_motion`` 1, the
    other motion's figures in its message and extras ``coexisting`` (with the figures that are worse, ``worse``).
    None where no rung was so flagged or none answered after it."""
    flagged = next((r for r in tried[:-1] if r.values.get("coexisting_motion") == 1.0), None)
    if flagged is None:
        return None
    higher = tried[-1]
    same_regime = higher.values.get("regime") == flagged.values.get("regime")
    worse = worse_figures(flagged, higher, tolerances)
    if same_regime and not worse:  # the higher model's run found the same motion
        flagged.values["coexisting_motion"] = 0.0
        figures = ", ".join(_figure(name, higher.values[name]) for name in sliding.FIGURES)
        flagged.message = (re.split("; (?:" + "|".join(sliding_parts.COEXISTS.values()) + ")", flagged.message)[0]
                           + f"; the {higher.method} model's run from the rest came to this motion too ({figures}: "
                             f"none above this motion's beyond their tolerance and errors)")
        return flagged
    higher.values["coexisting_motion"] = 1.0
    figures = {k: flagged.values.get(k) for k in sliding.FIGURES}
    higher.extras["coexisting"] = dict(method=flagged.method, status=str(flagged.status), **figures,
                                       worse=sorted(worse))
    stable = ", ".join(_figure(name, figures[name]) for name in sliding.FIGURES if figures[name] is not None)
    if (flagged.extras.get("second_motion") or {}).get("late") is not None:  # the check's run left it by itself
        higher.message += (f"; beside it a {flagged.method} motion ({stable}), which the check's run from rest came "
                           "near and then left by itself, chattering: the figures are those of the motion reached "
                           "from rest")
    else:
        higher.message += (f"; beside it a stable {flagged.method} motion ({stable}), which a pipe run up gently may "
                           "keep: the figures are those of the motion reached from rest, which a kick throws it into")
    if same_regime:
        higher.message += (f" (its regime the same, its figures above the {flagged.method} motion's beyond their "
                           f"tolerance and errors: " + ", ".join(f"{_figure(name, h)} against "
                                                                 f"{lo / FIGURE_UNITS[name][0]:.4g}"
                                                                 for name, (h, lo) in worse.items()) + ")")
    return higher


def climb(ladder: str, point: DesignPoint) -> PointResult:
    """Climb :data:`LADDERS` [ladder] until a rung serves the point (see the module docstring)."""
    tried: list[PointResult] = []
    for name, (method, prepare) in LADDERS[ladder].items():
        if tried and not MENDS[name](tried[-1], point):
            continue
        answer = solve_rung(method, prepare(point, tried[-1] if tried else None))
        tried.append(gate.admit(answer, point.scene, point.tolerances) if answer.status == "ok" else answer)
        if tried[-1].status == "ok" and tried[-1].values.get("coexisting_motion") != 1.0:
            break  # (an ok answer beside which a second motion coexists goes up: the worse motion is reported)
    result = tried[-1]
    answers = [r for r in tried if r.status == "not_converged" and r.error_estimate is not None
               and np.isfinite(r.error_estimate)]
    if result.status == "not_converged" and answers:  # nothing converged: the answer nearest to it stands
        result = min(answers, key=lambda r: r.error_estimate)
    result = _coexisting(tried, point.tolerances) or result  # two motions: the one reached from rest, flagged
    why = (f"{result.method} answered" if result.status == "ok" else
           f"no model served ({result.method}'s {result.status} is what is known)")
    if len(tried) > 1:
        why += " after " + ", ".join(f"{r.method}: {r.status}" + (f" (error {r.error_estimate:.2g})"
                                                                  if r.status == "not_converged" else "")
                                     for r in tried if r is not result)
    result.message = f"{ladder}: {why}; {result.message}"
    result.extras["methods_tried"] = {r.method: {"status": r.status, "error_estimate": r.error_estimate}
                                      for r in tried}
    return result


def solve(inputs: Mapping[str, Any]) -> PointResult:
    """``auto`` at a point given by its SI inputs (:func:`run` of its :class:`DesignPoint`)."""
    return run(DesignPoint.from_inputs(inputs))


def run(point: DesignPoint) -> PointResult:
    """The reference model's hierarchy: the free whirl where the pipe stays clear, the sliding state where it lies
    on the wall, else the reference model."""
    return climb("auto", point)


def solve_periodic(inputs: Mapping[str, Any]) -> PointResult:
    """``periodic`` at a point given by its SI inputs (:func:`run_periodic` of its :class:`DesignPoint`)."""
    return run_periodic(DesignPoint.from_inputs(inputs))


def run_periodic(point: DesignPoint) -> PointResult:
    """The paper's periodic solution: ``fast``, then ``series`` where only its error estimate failed, then
    ``damped`` where the dropped drag is not small."""
    return climb("periodic", point)
