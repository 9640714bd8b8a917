"""The paper's check of the dropped terms: term-ratio table over the span and the period (paper §VI).

The equation of motion (docs/model.md §2, paper eq. 33–35)

    EI y'''' − T0 y'' + m_i V_m² y'' + M ÿ + D |ẏ| ẏ = p(x, t)

is solved undamped (drag dropped, paper eq. 35 → 36) and, in the paper's reduced form, also without
the mud-flow term (eq. 39). A dropped term is acceptable only if it is small beside the kept ones
(docs/model.md §6). Following the paper's numerical example, each term's magnitude is evaluated on a grid
of (t, x) over the period and the span, and compared with a reference term (the dropped one, = 1):

    (A) "max":   max|term| / max|reference|          ratios of the maximum magnitudes,
    (B) "mean":  mean|term| / mean|reference|        ratios of the average magnitudes (timewise and
                                                      location-wise),
    (C) "least": mean|term| / max|reference|         the lowest ratios: the average of the other terms
                                                      divided by the maximum magnitude of the dropped term.

The paper's example, relative to the drag term A3 ẏ² = 1 (the copy's OCR, our reading; docs/model.md §6): one term
(A) 60, (B) 100, (C) 40; another 7 / 3 / 2; a third 100 / 100 / 300; it drops the drag, and then the
mud-flow term "of the same order of magnitude" as the drag.

Pure functions of numpy arrays, SI units, no I/O. The fields (y'''', y'', ÿ, ẏ) come from any periodic
method, e.g. :func:`study.physics.fourier.series_field` with kinds "d4", "d2", "acceleration", "velocity".
"""

from __future__ import annotations

from typing import Mapping

import numpy as np

#: The terms of the equation of motion (docs/model.md §2). ``kept``: kept in the project's undamped model
#: (paper eq. 35 without drag; the mud-flow force enters through T_eff = T0 − m_i V_m²);
#: ``kept_eq39``: kept in the paper's reduced equation (39), which also drops the mud-flow term.
TERMS = {
    "bending": {"expression": "EI y''''", "unit": "N/m",
                "description": "elastic bending resistance of the pipe (EI the bending stiffness)",
                "kept": True, "kept_eq39": True},
    "tension": {"expression": "−T0 y''", "unit": "N/m",
                "description": "axial load T0 acting on the curvature (tension stiffens the span)",
                "kept": True, "kept_eq39": True},
    "mud_flow": {"expression": "m_i V_m² y''", "unit": "N/m",
                 "description": "centrifugal force of the mud (mass m_i per length) flowing at V_m "
                                "through the curved pipe; dropped in the paper's reduced eq. 39",
                 "kept": True, "kept_eq39": False},
    "inertia": {"expression": "M ÿ", "unit": "N/m",
                "description": "inertia of pipe, mud inside and added mass of annular mud (M per length)",
                "kept": True, "kept_eq39": True},
    "drag": {"expression": "D |ẏ| ẏ", "unit": "N/m",
             "description": "turbulent drag of the annular mud (D per length, C_d = 0.5); dropped in "
                            "the undamped solution (paper eq. 35 → 36)",
             "kept": False, "kept_eq39": False},
}

#: Field arrays :func:`term_magnitudes` needs, all on the same (t, x) grid: name → meaning [unit].
FIELDS = {
    "d4": "y'''' [1/m³]",
    "d2": "y'' [1/m]",
    "acceleration": "ÿ [m/s²]",
    "velocity": "ẏ [m/s]",
}

#: Scalar properties :func:`term_magnitudes` needs (names as in :func:`study.solvers.model.scene.section_of`
#: and the SI inputs): name → meaning [unit]. ``mud_flow_velocity`` defaults to 0.
PROPS = {
    "bending_stiffness": "EI [N m²]",
    "axial_tension": "T0 [N] (the axial load, not T_eff)",
    "internal_mud_mass": "m_i [kg/m]",
    "mud_flow_velocity": "V_m [m/s]",
    "mass_per_length": "M [kg/m]",
    "drag_coefficient_per_length": "D [kg/m²] (drag force per length D ẏ²)",
}

RATIO_KINDS = ("max", "mean", "least")


def term_magnitudes(fields: Mapping[str, np.ndarray], props: Mapping[str, float]) -> dict[str, np.ndarray]:
    """Magnitude of each term of the equation of motion at every grid point [N/m] (docs/model.md §2).

    fields: arrays on one (t, x) grid (any common broadcastable shape), keyed as :data:`FIELDS`:
    "d4" y'''' [1/m³], "d2" y'' [1/m], "acceleration" ÿ [m/s²], "velocity" ẏ [m/s].
    props: scalars keyed as :data:`PROPS`: EI [N m²], T0 [N], m_i [kg/m], V_m [m/s] (default 0),
    M [kg/m], D [kg/m²]. Returns term → |term| for every key of :data:`TERMS`:

        bending |EI y''''|, tension |T0 y''|, mud_flow |m_i V_m² y''|, inertia |M ÿ|, drag D ẏ².
    """
    missing = [k for k in FIELDS if k not in fields]
    if missing:
        raise KeyError(f"fields missing {', '.join(missing)} (need {', '.join(FIELDS)})")
    missing = [k for k in PROPS if k not in props and k != "mud_flow_velocity"]
    if missing:
        raise KeyError(f"props missing {', '.join(missing)} (need {', '.join(PROPS)})")
    d4, d2, acc, vel = np.broadcast_arrays(*(np.asarray(fields[k], dtype=float) for k in FIELDS))
    vm = float(props.get("mud_flow_velocity", 0.0))
    return {
        "bending": np.abs(float(props["bending_stiffness"]) * d4),
        "tension": np.abs(float(props["axial_tension"]) * d2),
        "mud_flow": np.abs(float(props["internal_mud_mass"]) * vm**2 * d2),
        "inertia": np.abs(float(props["mass_per_length"]) * acc),
        "drag": np.abs(float(props["drag_coefficient_per_length"])) * vel**2,
    }


def _ratio(num, den):
    """num/den with +inf for num > 0 = den and NaN for 0/0 (a vanishing reference term)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return float(np.float64(num) / np.float64(den))


def term_ratios(magnitudes: Mapping[str, np.ndarray], reference: str = "drag",
                exclude=None) -> dict[str, dict[str, float]]:
    """The paper's term-ratio table (paper §VI, docs/model.md §6): each term relative to ``reference`` [-].

    magnitudes: term → |term| on one (t, x) grid (:func:`term_magnitudes`); reference: the term set
    to 1 (the paper's convention: the dropped term); exclude: boolean mask broadcastable to the grid,
    True at points left out — e.g. inside the contact (|x − L/2| ≤ b during 0 ≤ t ≤ T_L), where the
    load is concentrated and the truncated series' derivatives are meaningless. Over the points kept,
    with max_k, mean_k the maximum and average magnitude of term k:

        "max"   (A) = max_k / max_ref,   "mean" (B) = mean_k / mean_ref,   "least" (C) = mean_k / max_ref.

    The reference term's own entries are 1 for all three (the paper's table). A vanishing reference
    gives inf (NaN for a term that vanishes too); NaN fields (resonance) give NaN ratios. Raises
    ValueError for an unknown reference or when every point is excluded.
    """
    if reference not in magnitudes:
        raise ValueError(f"reference = {reference!r}; allowed: {', '.join(magnitudes)}")
    arrays = dict(zip(magnitudes, np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in magnitudes.values()))))
    shape = arrays[reference].shape
    keep = np.ones(shape, dtype=bool) if exclude is None else ~np.broadcast_to(np.asarray(exclude, dtype=bool), shape)
    if not keep.any():
        raise ValueError("every grid point is excluded: no magnitudes to compare")
    stats = {k: (float(v[keep].max()), float(v[keep].mean())) for k, v in arrays.items()}
    ref_max, ref_mean = stats[reference]
    out = {}
    for k, (mx, mean) in stats.items():
        if k == reference:
            out[k] = {"max": 1.0, "mean": 1.0, "least": 1.0}
        else:
            out[k] = {"max": _ratio(mx, ref_max), "mean": _ratio(mean, ref_mean), "least": _ratio(mean, ref_max)}
    return out


def dropped_terms_small(ratios: Mapping[str, Mapping[str, float]], threshold: float = 10.0,
                        dropped=("drag",), max_threshold: float | None = None) -> tuple[bool, str]:
    """Verdict on the dropped terms from the ratio table (paper §VI, docs/model.md §6) → (ok, message).

    ratios: the table of :func:`term_ratios` (any reference term: the ratios are re-referenced to each
    dropped term); dropped: the terms left out of the model (("drag",) for the undamped solution,
    ("drag", "mud_flow") for the paper's eq. 39); every other term in the table counts as kept.

    Rule: a dropped term d is small when the largest kept term exceeds it by at least ``threshold``
    in the (B) average sense, mean_kept/mean_d ≥ threshold, AND by at least ``max_threshold``
    (default threshold/3) in the (A) maximum sense, max_kept/max_d ≥ max_threshold. Why: the paper
    judges by orders of magnitude, and its averages (B) are its main evidence — in its example the
    largest kept term is ~100 × the drag both on average and at the maxima, and it calls that
    "convincing"; its (A) column runs below (B) (60 vs 100) because the maxima are single grid
    points, sampled near the contact and the kinks of the pulse where a truncated series is least
    accurate. So the average must clear a full order of magnitude, while the maxima must only clear
    about half an order (10/3 ≈ √10): enough to catch a term that is small on average but locally
    comparable (where then the dropped term would change the peak response), without failing on
    the noise of a single peak. The (C) "least" ratio is reported, not tested. Both thresholds are
    arguments. NaN ratios (resonance) or a missing term give ok = False. The message names each
    dropped term, the largest kept terms, their ratios and the thresholds.
    """
    max_threshold = threshold / 3.0 if max_threshold is None else max_threshold
    kept = [k for k in ratios if k not in dropped]
    if not kept:
        return False, "no kept term to compare the dropped terms with"
    ok_all, parts = True, []
    for d in dropped:
        if d not in ratios:
            ok_all = False
            parts.append(f"{d}: not in the ratio table")
            continue
        rel = {k: {s: _ratio(ratios[k][s], ratios[d][s]) for s in ("max", "mean")} for k in kept}
        k_mean = max(kept, key=lambda k: -np.inf if np.isnan(rel[k]["mean"]) else rel[k]["mean"])
        k_max = max(kept, key=lambda k: -np.inf if np.isnan(rel[k]["max"]) else rel[k]["max"])
        r_mean, r_max = rel[k_mean]["mean"], rel[k_max]["max"]
        ok = bool(r_mean >= threshold and r_max >= max_threshold)  # False for NaN
        ok_all &= ok
        verdict = "small" if ok else "NOT small"
        parts.append(f"dropped term {d} is {verdict}: largest kept term on average {k_mean} "
                     f"{r_mean:.3g}× (B, needs ≥ {threshold:.3g}), at the maxima {k_max} {r_max:.3g}× "
                     f"(A, needs ≥ {max_threshold:.3g})")
    message = "; ".join(parts)
    if not ok_all:
        message += " — a model keeping the dropped terms (damped) is needed"
    return ok_all, message
