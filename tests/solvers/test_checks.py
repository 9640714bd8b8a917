"""Tests of study.solvers.methods.periodic.checks: the paper's term-ratio table (paper §VI, docs/model.md §6).

Synthetic field y = Y sin(πx/L) sin(Ωt) on a grid where every term's max and mean are known in
closed form ("closed form"): x at the midpoints x_i = (i + ½)L/n_x, n_x odd (so x = L/2 is a grid
point), t_j = jτ/n_t, n_t divisible by 4 (so t = 0, τ/4 are grid points). Discrete means (exact):
mean_i sin(πx_i/L) = 1/(n_x sin(π/(2n_x))) → 2/π, mean_i sin²(πx_i/L) = ½,
mean_j |sin(Ωt_j)| = mean_j |cos(Ωt_j)| = (2/n_t) cot(π/n_t) → 2/π, mean_j cos²(Ωt_j) = ½.
"""

import numpy as np
import pytest

from study.physics import fourier as fs
from study.solvers.methods.periodic import checks

L, TAU, Y = 40.0, 0.2, 0.02  # span [m], period [s], amplitude [m]
OMEGA = 2 * np.pi / TAU
K = np.pi / L
NX, NT = 201, 400
PROPS = dict(bending_stiffness=3.0e6, axial_tension=4.0e4, internal_mud_mass=8.0, mud_flow_velocity=3.0,
             mass_per_length=45.0, drag_coefficient_per_length=60.0)


def grid(nx=NX, nt=NT):
    x = (np.arange(nx) + 0.5) * L / nx
    t = np.arange(nt) * TAU / nt
    return x, t


def synthetic_fields(nx=NX, nt=NT):
    x, t = grid(nx, nt)
    s, st, ct = np.sin(K * x), np.sin(OMEGA * t)[:, None], np.cos(OMEGA * t)[:, None]
    y = Y * st * s
    return {"d4": K**4 * y, "d2": -(K**2) * y, "acceleration": -(OMEGA**2) * y, "velocity": Y * OMEGA * ct * s}


def expected(nx=NX, nt=NT):
    """Closed-form (max, mean) of each term's magnitude on the grid."""
    ax = 1 / (nx * np.sin(np.pi / (2 * nx)))  # mean |sin(πx/L)|
    at = 2 / nt / np.tan(np.pi / nt)  # mean |sin Ωt|
    p = PROPS
    amp = {"bending": p["bending_stiffness"] * K**4 * Y, "tension": p["axial_tension"] * K**2 * Y,
           "mud_flow": p["internal_mud_mass"] * p["mud_flow_velocity"] ** 2 * K**2 * Y,
           "inertia": p["mass_per_length"] * OMEGA**2 * Y}
    out = {k: (a, a * ax * at) for k, a in amp.items()}
    drag = p["drag_coefficient_per_length"] * (Y * OMEGA) ** 2
    out["drag"] = (drag, drag * 0.25)
    return out


def test_terms_table():
    # source: docs/model.md §2 — five terms, only the drag dropped from the undamped model; eq. 39 also
    # drops the mud-flow term
    assert set(checks.TERMS) == {"bending", "tension", "mud_flow", "inertia", "drag"}
    assert [k for k, v in checks.TERMS.items() if not v["kept"]] == ["drag"]
    assert [k for k, v in checks.TERMS.items() if not v["kept_eq39"]] == ["mud_flow", "drag"]
    assert all(v["description"] and v["expression"] for v in checks.TERMS.values())


def test_magnitudes_and_ratios_closed_form():
    # source: closed form (discrete means above) — ratios relative to the drag
    mags = checks.term_magnitudes(synthetic_fields(), PROPS)
    assert set(mags) == set(checks.TERMS) and mags["bending"].shape == (NT, NX)
    ex = expected()
    for k, (mx, mean) in ex.items():
        assert mags[k].max() == pytest.approx(mx, rel=1e-12)
        assert mags[k].mean() == pytest.approx(mean, rel=1e-12)
    r = checks.term_ratios(mags)
    dmx, dmean = ex["drag"]
    for k, (mx, mean) in ex.items():
        if k == "drag":
            assert r[k] == {"max": 1.0, "mean": 1.0, "least": 1.0}
            continue
        assert r[k]["max"] == pytest.approx(mx / dmx, rel=1e-12)
        assert r[k]["mean"] == pytest.approx(mean / dmean, rel=1e-12)
        assert r[k]["least"] == pytest.approx(mean / dmx, rel=1e-12)
    # continuous limit: mean|sin x sin t| = 4/π², mean sin²cos² = 1/4 → (B) = (16/π²)·(A)
    assert r["inertia"]["mean"] == pytest.approx(16 / np.pi**2 * r["inertia"]["max"], rel=1e-4)
    assert r["inertia"]["max"] == pytest.approx(PROPS["mass_per_length"] / (PROPS["drag_coefficient_per_length"] * Y))


def test_reference_convention():
    # source: closed form — re-referencing: ratio to inertia = ratio to drag / (inertia's ratio to drag)
    mags = checks.term_magnitudes(synthetic_fields(), PROPS)
    r_drag = checks.term_ratios(mags, reference="drag")
    r_in = checks.term_ratios(mags, reference="inertia")
    assert r_in["inertia"] == {"max": 1.0, "mean": 1.0, "least": 1.0}
    for k in ("bending", "tension", "mud_flow"):
        for s in ("max", "mean"):
            assert r_in[k][s] == pytest.approx(r_drag[k][s] / r_drag["inertia"][s], rel=1e-12)
        assert r_in[k]["least"] == pytest.approx(r_drag[k]["least"] / r_drag["inertia"]["max"], rel=1e-12)
    with pytest.raises(ValueError):
        checks.term_ratios(mags, reference="gravity")
    # a vanishing reference (no mud flow) gives inf; 0/0 gives NaN
    mags0 = checks.term_magnitudes(synthetic_fields(), dict(PROPS, mud_flow_velocity=0.0))
    r0 = checks.term_ratios(mags0, reference="mud_flow")
    assert r0["drag"]["max"] == np.inf
    assert checks.term_ratios({"a": np.zeros(3), "b": np.zeros(3)}, reference="a")["b"]["mean"] != 0.0
    with pytest.raises(KeyError, match="velocity"):
        checks.term_magnitudes({k: v for k, v in synthetic_fields().items() if k != "velocity"}, PROPS)


def test_contact_mask():
    # source: closed form — a spike inside the contact (the load region) does not change the
    # ratios once masked; the masked statistics are those of the points left
    mags = checks.term_magnitudes(synthetic_fields(), PROPS)
    x, t = grid()
    contact = (np.abs(x - L / 2) <= 0.5)[None, :] & (t <= 0.01)[:, None]
    assert contact.any()
    spiked = dict(mags, bending=np.where(contact, 1e9, mags["bending"]))
    r_spiked = checks.term_ratios(spiked)
    assert r_spiked["bending"]["max"] > 1e3 * checks.term_ratios(mags)["bending"]["max"]
    r_masked = checks.term_ratios(spiked, exclude=contact)
    keep = ~contact
    for k in mags:
        if k == "drag":
            continue
        assert r_masked[k]["max"] == pytest.approx(mags[k][keep].max() / mags["drag"][keep].max(), rel=1e-12)
        assert r_masked[k]["mean"] == pytest.approx(mags[k][keep].mean() / mags["drag"][keep].mean(), rel=1e-12)
        assert r_masked[k]["least"] == pytest.approx(mags[k][keep].mean() / mags["drag"][keep].max(), rel=1e-12)
    # the drag max at (t = 0, x = L/2) is masked, its twin at t = τ/2 is not: the max stays,
    # the mean of the points left changes
    assert contact[0, NX // 2] and not contact[NT // 2, NX // 2]
    assert mags["drag"][keep].max() == mags["drag"].max()
    assert mags["drag"][keep].mean() != mags["drag"].mean()
    # a mask over x only broadcasts along t
    xmask = np.abs(x - L / 2) <= 0.5
    r_x = checks.term_ratios(mags, exclude=xmask)
    assert r_x["inertia"]["mean"] == pytest.approx(
        mags["inertia"][:, ~xmask].mean() / mags["drag"][:, ~xmask].mean(), rel=1e-12)
    with pytest.raises(ValueError, match="excluded"):
        checks.term_ratios(mags, exclude=np.ones(NX, dtype=bool))


def test_verdict_small_and_not_small():
    # source: closed form — inertia/drag: (A) = M/(D Y), (B) = (16/π²)(A) on a fine grid
    mags = checks.term_magnitudes(synthetic_fields(), PROPS)  # (A) 37.5, (B) ≈ 60.8
    ok, msg = checks.dropped_terms_small(checks.term_ratios(mags))
    assert ok and "drag is small" in msg and "inertia" in msg and "≥ 10" in msg
    # a 10× heavier drag: (B) ≈ 6.1 < 10
    heavy = checks.term_magnitudes(synthetic_fields(), dict(PROPS, drag_coefficient_per_length=600.0))
    ok, msg = checks.dropped_terms_small(checks.term_ratios(heavy))
    assert not ok and "drag is NOT small" in msg and "damped" in msg
    # the thresholds are arguments; the verdict is the same whatever the reference term
    assert not checks.dropped_terms_small(checks.term_ratios(mags), threshold=100.0)[0]
    assert checks.dropped_terms_small(checks.term_ratios(heavy), threshold=5.0)[0]
    assert checks.dropped_terms_small(checks.term_ratios(mags, reference="bending"))[0]
    # eq. 39 also drops the mud flow: m_i V_m² k² / (M Ω² ...) is small here too
    ok, msg = checks.dropped_terms_small(checks.term_ratios(mags), dropped=("drag", "mud_flow"))
    assert ok and "mud_flow is small" in msg


def test_verdict_fails_on_a_local_peak():
    # source: closed form — a dropped term 100× smaller on average but comparable at one point
    # passes (B) and fails (A): max ratio 2 < 10/3
    shape = (40, 50)
    kept = np.ones(shape)
    drop = np.full(shape, 0.01)
    drop[3, 7] = 0.5
    ratios = checks.term_ratios({"inertia": kept, "drag": drop})
    assert ratios["inertia"]["mean"] > 10 and ratios["inertia"]["max"] == pytest.approx(2.0)
    ok, msg = checks.dropped_terms_small(ratios)
    assert not ok and "A, needs ≥ 3.33" in msg
    assert checks.dropped_terms_small(ratios, max_threshold=1.5)[0]
    # NaN (resonance) is never small; a missing dropped term is reported
    assert not checks.dropped_terms_small({"inertia": {"max": np.nan, "mean": np.nan}, "drag": ratios["drag"]})[0]
    ok, msg = checks.dropped_terms_small(ratios, dropped=("mud_flow",))
    assert not ok and "mud_flow" in msg


def test_ratio_table_from_the_series_solution():
    # source: convergence to reference — the pipeline on the paper's double series (fourier.series_field)
    # runs end to end: every ratio finite and positive, the contact masked
    span, tl, tau = 10.0, 5e-3, 0.2
    args = dict(span_length=span, bending_stiffness=1e6, tension=5e4, mass=40.0, impulse=100.0,
                pulse_duration=tl, period=tau, pattern="alternating", half_length=0.02, shape="parabolic")
    x = np.linspace(0, span, 41)
    t = np.linspace(0, tau, 80, endpoint=False)
    fields = {k: fs.series_field(x, t, k, n_modes=41, harmonics=400, **args) for k in checks.FIELDS}
    props = dict(PROPS, bending_stiffness=1e6, axial_tension=5e4, mass_per_length=40.0)
    mags = checks.term_magnitudes(fields, props)
    wrapped = np.mod(t, tau / 2)
    contact = (np.abs(x - span / 2) <= 0.5)[None, :] & (wrapped <= tl)[:, None]
    r = checks.term_ratios(mags, exclude=contact)
    assert all(np.isfinite(v[s]) and v[s] > 0 for v in r.values() for s in checks.RATIO_KINDS)
    ok, msg = checks.dropped_terms_small(r)
    assert isinstance(ok, bool) and "drag" in msg
