"""Tests of study.physics.beam: modal load factors, the closed-form periodic modal response, the
static beam-column deflection and the (quasi-statically corrected) modal sums.

Every expected value names its source: "closed form" (derived in the test, independently of the
module's formula), "Timoshenko" (Vibration Problems in Engineering: impulse and periodic response
of the undamped oscillator, modes of the simply supported beam), "Roark" / "Timoshenko & Gere"
(static beam-columns), "quadrature" (scipy.integrate.quad), "ODE" (scipy solve_ivp), or
"convergence to reference".
"""

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

from study.physics import beam as bm
from study.physics import fourier as fs
from study.physics import midspan as ms

SHAPES = ["point", "uniform", "parabolic"]
PATTERNS = ["one_wall", "alternating"]


# --- modal load factors -----------------------------------------------------------------------
@pytest.mark.parametrize("shape", ["uniform", "parabolic"])
@pytest.mark.parametrize("b", [1e-4, 0.05, 0.7, 3.0], ids=lambda b: f"b={b}")
def test_modal_load_factors_match_quadrature(shape, b):
    # source: quadrature of ∫ g(x) sin(nπx/L) dx
    span, modes = 10.0, np.arange(1, 40)
    g = bm.modal_load_factors(modes, span, b, shape)
    for n, gn in zip(modes, g):
        ref = quad(lambda x: bm.load_shape(x, span, b, shape) * np.sin(n * np.pi * x / span),
                   span / 2 - b, span / 2 + b, epsabs=0, epsrel=1e-13, limit=200)[0]
        assert gn == pytest.approx(ref, rel=1e-10, abs=1e-13)


@pytest.mark.parametrize("shape", SHAPES)
def test_modal_load_factors_point_limit_and_parity(shape):
    # source: closed form — as b → 0 every shape tends to the Dirac, g_n = sin(nπ/2)
    modes = np.arange(1, 12)
    g = bm.modal_load_factors(modes, 10.0, 1e-9, shape)
    np.testing.assert_allclose(g, np.sin(modes * np.pi / 2), atol=1e-14)
    assert np.all(g[1::2] == 0.0)


def test_load_shape_unit_integral():
    # source: quadrature — the shapes have unit total
    for shape in ("uniform", "parabolic"):
        assert quad(lambda x: bm.load_shape(x, 10.0, 0.3, shape), 4.7, 5.3)[0] == pytest.approx(1.0, rel=1e-12)


# --- the pulse ---------------------------------------------------------------------------------
@pytest.mark.parametrize("omega", [0.0, 100.0, np.pi / 2e-3, 5000.0, 3e4], ids=lambda w: f"w={w:g}")
def test_pulse_spectrum_matches_quadrature(omega):
    # source: quadrature of ∫ h(t) e^{−iωt} dt
    tl = 2e-3
    re = quad(lambda t: bm.unit_pulse(t, tl) * np.cos(omega * t), 0, tl, epsabs=1e-14, epsrel=1e-12, limit=200)[0]
    im = -quad(lambda t: bm.unit_pulse(t, tl) * np.sin(omega * t), 0, tl, epsabs=1e-14, epsrel=1e-12, limit=200)[0]
    h = bm.pulse_spectrum(omega, tl)
    assert h.real == pytest.approx(re, abs=1e-13) and h.imag == pytest.approx(im, abs=1e-13)


# --- periodic modal response ------------------------------------------------------------------
def fourier_reference(t, omega, tl, tau, pattern, harmonics):
    """Brute-force time Fourier series of the periodic response (Timoshenko: steady forced response
    harmonic by harmonic), c_m = H(mΩ)/τ (× 2 for odd m and 0 for even m if alternating)."""
    big = 2 * np.pi / tau
    m = np.arange(1, harmonics + 1)
    c = bm.pulse_spectrum(m * big, tl) / tau
    if pattern == "alternating":
        c = np.where(m % 2 == 1, 2 * c, 0)
        mean = 0.0
    else:
        mean = 1.0 / (tau * omega**2)
    e = np.exp(1j * np.outer(t, m * big))
    q = mean + 2 * (e * (c / (omega**2 - (m * big) ** 2))).real.sum(axis=1)
    v = 2 * (e * (1j * m * big * c / (omega**2 - (m * big) ** 2))).real.sum(axis=1)
    return q, v


CASES = [  # (omega [rad/s], T_L [s], tau [s]) — off resonance, ω T_L below, near and above π
    (7.3, 1e-3, 0.21),
    (130.0, 5e-3, 0.21),
    (np.pi / 4.7e-3, 4.7e-3, 0.21),  # ω = π/T_L: the removable singularity of the pulse response
    (2100.0, 5e-3, 0.21),
]


@pytest.mark.parametrize("pattern", PATTERNS)
@pytest.mark.parametrize("omega,tl,tau", CASES, ids=[f"w={c[0]:.4g}" for c in CASES])
def test_periodic_response_matches_fourier_series(pattern, omega, tl, tau):
    # source: convergence to reference (time Fourier series, 200 000 harmonics)
    t = np.linspace(-0.1, 0.5, 61) + 1e-4
    q, v = bm.modal_periodic_response(t, omega, tl, tau, pattern)
    qf, vf = fourier_reference(t, omega, tl, tau, pattern, 200_000)
    scale = np.max(np.abs(qf))
    assert np.max(np.abs(q - qf)) < 1e-8 * scale
    assert np.max(np.abs(v - vf)) < 1e-4 * np.max(np.abs(vf))  # velocity series converges slowly


@pytest.mark.parametrize("pattern", PATTERNS)
@pytest.mark.parametrize("omega,tl,tau", CASES, ids=[f"w={c[0]:.4g}" for c in CASES])
def test_periodic_response_is_periodic_solution_of_the_ode(pattern, omega, tl, tau):
    # source: ODE — integrate q̈ + ω² q = h(t) over one period from the computed state at t = 0;
    # the trajectory must follow the closed form and return to the start (periodicity)
    q0, v0 = bm.modal_periodic_response(0.0, omega, tl, tau, pattern)
    rhs = lambda t, s: [s[1], bm.pulse_train(t, tl, tau, pattern) - omega**2 * s[0]]  # noqa: E731
    t_eval = np.linspace(0, tau, 401)
    sol = solve_ivp(rhs, (0, tau), [q0, v0], t_eval=t_eval, rtol=1e-11, atol=1e-14, max_step=tl / 20,
                    method="DOP853")
    q, v = bm.modal_periodic_response(t_eval, omega, tl, tau, pattern)
    scale = np.max(np.abs(q))
    np.testing.assert_allclose(sol.y[0], q, atol=1e-7 * scale)
    np.testing.assert_allclose(sol.y[1], v, atol=1e-7 * np.max(np.abs(v)))
    assert abs(sol.y[0, -1] - q0) < 1e-7 * scale


@pytest.mark.parametrize("omega", [3.0, 47.0, 400.0])
def test_periodic_response_impulse_limit(omega):
    # source: Timoshenko (periodic impulses on an undamped oscillator): one_wall
    # q = cos(ω(t − τ/2))/(2ω sin(ωτ/2)); alternating q = sin(ω(t − τ/4))/(2ω cos(ωτ/4)), 0 < t < P
    tau, tl = 0.2, 1e-9
    t = np.linspace(0.001, 0.099, 50)
    q1 = bm.modal_periodic_response(t + 0.1, omega, tl, tau, "one_wall").displacement
    ref1 = np.cos(omega * (t + 0.1 - tau / 2)) / (2 * omega * np.sin(omega * tau / 2))
    np.testing.assert_allclose(q1, ref1, rtol=0, atol=1e-6 * np.abs(ref1).max())  # O(ω T_L) shift
    q2 = bm.modal_periodic_response(t, omega, tl, tau, "alternating").displacement
    ref2 = np.sin(omega * (t - tau / 4)) / (2 * omega * np.cos(omega * tau / 4))
    np.testing.assert_allclose(q2, ref2, rtol=0, atol=1e-6 * np.abs(ref2).max())
    # antiperiodicity over τ/2
    q3 = bm.modal_periodic_response(t + tau / 2, omega, tl, tau, "alternating").displacement
    np.testing.assert_allclose(q3, -q2, rtol=1e-12)


def test_resonance_is_nan_and_distance():
    # source: closed form — resonance at ωτ = 2πk (one_wall), ωτ/2 = π(2k+1) (alternating)
    tau = 0.2
    big = 2 * np.pi / tau
    om = np.array([1.0, 2.0, 3.0, 2.5, 1.25]) * big
    d1 = bm.resonance_distance(om, tau, "one_wall")
    d2 = bm.resonance_distance(om, tau, "alternating")
    np.testing.assert_allclose(d1, [0, 0, 0, 0.5, 0.25], atol=1e-12)
    np.testing.assert_allclose(d2, [0, 1, 0, 0.5, 0.25], atol=1e-12)
    with np.errstate(all="raise"):
        q = bm.modal_periodic_response(0.01, om, 1e-3, tau, "one_wall").displacement
        q2 = bm.modal_periodic_response(0.01, om, 1e-3, tau, "alternating").displacement
    assert np.isnan(q[:3]).all() and np.isfinite(q[3:]).all()
    assert np.isnan(q2[[0, 2]]).all() and np.isfinite(q2[[1, 3, 4]]).all()
    # the pulse must fit in the (half) period; a buckled mode (NaN ω) gives NaN
    assert np.isnan(bm.modal_periodic_response(0.0, 7.0, 0.15, tau, "alternating").displacement)
    assert np.isnan(bm.modal_periodic_response(0.0, np.nan, 1e-3, tau).displacement)


# --- static beam-column -------------------------------------------------------------------------
L_S, EI_S = 30.0, 1.0e6  # [m], [N m²]
TENSIONS = [0.0, 1e-9, 5e4, 2e6, -5e3, -0.9 * EI_S * (np.pi / L_S) ** 2]
T_IDS = ["T=0", "T=tiny", "T=5e4", "T=2e6", "T=-5e3", "T=0.9Tcr"]


def modal_static(x, tension, b, shape, n_max=200_001):
    """Static deflection as the mode sum Σ g_n sin(k_n x)/((L/2)(EI k_n⁴ + T k_n²)) (Timoshenko:
    series solution of the simply supported beam-column), tail ~ n⁻³."""
    n = np.arange(1, n_max + 1, 2)
    k = n * np.pi / L_S
    g = bm.modal_load_factors(n, L_S, b, shape)
    return (np.sin(np.outer(x, k)) * (g / (0.5 * L_S * (EI_S * k**4 + tension * k**2)))).sum(axis=1)


@pytest.mark.parametrize("shape", SHAPES)
@pytest.mark.parametrize("tension", TENSIONS, ids=T_IDS)
def test_static_deflection_matches_mode_sum(shape, tension):
    # source: convergence to reference (the modal series of the static problem, 10⁵ odd modes)
    x = np.array([0.0, 2.0, 9.0, 14.7, 15.0, 21.0, 30.0])
    g = bm.static_deflection(x, L_S, EI_S, tension, 0.4, shape)
    ref = modal_static(x, tension, 0.4, shape)
    np.testing.assert_allclose(g, ref, rtol=1e-9, atol=1e-12 * np.abs(ref).max())


def test_static_point_load_closed_forms():
    # source: Timoshenko & Gere / Roark (beam-column, centre load): T = 0: PL³/(48EI);
    # T > 0: [x − sinh λx/(λ cosh λL/2)]/(2T); T < 0: [x − sin λx/(λ cos λL/2)]/(2T)
    assert bm.static_deflection(L_S / 2, L_S, EI_S, 0.0) == pytest.approx(L_S**3 / (48 * EI_S), rel=1e-14)
    x = np.linspace(0, L_S / 2, 7)
    lam = np.sqrt(5e4 / EI_S)
    np.testing.assert_allclose(bm.static_deflection(x, L_S, EI_S, 5e4),
                               (x - np.sinh(lam * x) / (lam * np.cosh(lam * L_S / 2))) / (2 * 5e4), rtol=1e-12)
    lam = np.sqrt(5e3 / EI_S)
    np.testing.assert_allclose(bm.static_deflection(x, L_S, EI_S, -5e3),
                               (x - np.sin(lam * x) / (lam * np.cos(lam * L_S / 2))) / (2 * -5e3), rtol=1e-12)
    # moment of the plain beam: x/2; of the beam-column: sinh(λx)/(2λ cosh(λL/2))
    np.testing.assert_allclose(bm.static_moment(x, L_S, EI_S, 0.0), x / 2, rtol=1e-14)
    lam = np.sqrt(5e4 / EI_S)
    np.testing.assert_allclose(bm.static_moment(x, L_S, EI_S, 5e4),
                               np.sinh(lam * x) / (2 * lam * np.cosh(lam * L_S / 2)), rtol=1e-12)


@pytest.mark.parametrize("shape,ref", [("point", L_S / 4), ("uniform", L_S / 4 - 0.4 / 4),
                                       ("parabolic", L_S / 4 - 3 * 0.4 / 16)])
def test_static_midspan_moment_plain_beam(shape, ref):
    # source: closed form (statics): M(L/2) = ½·L/2 − ½·(centroid of the half load from midspan):
    # 0, b/2 (uniform), 3b/8 (parabolic)
    assert bm.static_moment(L_S / 2, L_S, EI_S, 0.0, 0.4, shape) == pytest.approx(ref, rel=1e-13)


@pytest.mark.parametrize("shape", SHAPES)
@pytest.mark.parametrize("tension", TENSIONS, ids=T_IDS)
def test_static_moment_and_shear_equilibrium(shape, tension):
    # source: closed form (Timoshenko & Gere: beam-column moment M = M0 − T y, M0 the plain-beam
    # moment; transverse force −EI y''' + T y' = ½ − ∫_a^x g on the left half)
    x = np.array([1.0, 7.0, 14.7, 14.9])
    m = bm.static_moment(x, L_S, EI_S, tension, 0.4, shape)
    m0 = bm.static_moment(x, L_S, EI_S, 0.0, 0.4, shape)
    y = bm.static_deflection(x, L_S, EI_S, tension, 0.4, shape)
    np.testing.assert_allclose(m, m0 - tension * y, rtol=1e-10, atol=1e-12)
    v = bm.static_shear(x, L_S, EI_S, tension, 0.4, shape, include_tension=True)
    if shape == "point":
        expect = np.full_like(x, 0.5)
    else:
        expect = np.array([0.5 - quad(lambda s: bm.load_shape(s, L_S, 0.4, shape), 14.6, xx)[0] if xx > 14.6
                           else 0.5 for xx in x])
    np.testing.assert_allclose(v, expect, atol=1e-10)
    # the section shear is dM/dx (central difference)
    h = 1e-4
    dm = (bm.static_moment(x + h, L_S, EI_S, tension, 0.4, shape)
          - bm.static_moment(x - h, L_S, EI_S, tension, 0.4, shape)) / (2 * h)
    np.testing.assert_allclose(bm.static_shear(x, L_S, EI_S, tension, 0.4, shape), dm, atol=1e-7)


def test_static_string_limit():
    # source: closed form — as EI → 0 the beam-column becomes a string, G = x/(2T) for x ≤ L/2;
    # the bending boundary layer costs a relative 1/u at midspan, u = λL/2
    tension, u = 5e4, 300.0
    ei = tension * (L_S / 2 / u) ** 2
    x = np.array([3.0, 9.0, 15.0])
    g = bm.static_deflection(x, L_S, ei, tension)
    np.testing.assert_allclose(g, x / (2 * tension), rtol=1.01 / u)
    assert g[-1] == pytest.approx((L_S / 2 - L_S / 2 / u) / (2 * tension), rel=1e-12)


def test_static_buckled_is_nan():
    # source: closed form — Euler load T_cr = −EI π²/L²
    with np.errstate(all="raise"):
        g = bm.static_deflection(np.array([5.0, 15.0]), L_S, EI_S, -1.01 * EI_S * (np.pi / L_S) ** 2)
    assert np.isnan(g).all()


# --- modal sums with and without the quasi-static correction ---------------------------------
def field_args(span, tl, pattern, shape="point"):
    return dict(span_length=span, bending_stiffness=1e6, tension=5e4, mass=40.0, impulse=100.0,
                pulse_duration=tl, period=0.2, pattern=pattern, half_length=0.02, shape=shape)


@pytest.mark.parametrize("span,tl", [(6.0, 1e-2), (8.0, 6e-3)], ids=["L=6", "L=8"])
def test_corrected_moment_beats_plain(span, tl):
    # source: convergence to reference (corrected sum with 20 001 modes) — docs/model.md §9 claim:
    # corrected sum with 21 modes beats the plain sum with 2001 modes for the midspan moment
    # during the pulse (holds when ω_21 T_L ≫ 1; see the report for spans where it does not)
    args = field_args(span, tl, "alternating")
    t, x = np.linspace(0.1, 0.9, 5) * tl, np.array([span / 2])
    ref = bm.bending_moment(x, t, n_modes=20001, **args)
    err_qs = np.abs(bm.bending_moment(x, t, n_modes=21, **args) - ref).max()
    err_plain = np.abs(bm.bending_moment(x, t, n_modes=2001, quasi_static=False, **args) - ref).max()
    assert err_qs < err_plain < 1e-2 * np.abs(ref).max()


@pytest.mark.parametrize("pattern", PATTERNS)
@pytest.mark.parametrize("shape", SHAPES)
def test_corrected_and_plain_sums_agree(pattern, shape):
    # source: convergence to reference — both sums converge to the same field; plain moment
    # error falls like 1/N at midspan (point load), corrected converges like N^-3 or faster
    span, tl = 10.0, 5e-3
    args = field_args(span, tl, pattern, shape)
    t = np.concatenate([np.linspace(0.1, 0.9, 4) * tl, [0.03, 0.13]])
    x = np.array([span / 2, span / 3, span / 7])
    y_qs = bm.deflection(x, t, n_modes=4001, **args)
    y_pl = bm.deflection(x, t, n_modes=4001, quasi_static=False, **args)
    np.testing.assert_allclose(y_pl, y_qs, atol=1e-7 * np.abs(y_qs).max())
    m_qs = bm.bending_moment(x, t, n_modes=4001, **args)
    m_pl = bm.bending_moment(x, t, n_modes=200001, quasi_static=False, **args)
    np.testing.assert_allclose(m_pl, m_qs, atol=2e-4 * np.abs(m_qs).max())
    xs = x[1:]  # shear off midspan (the series gives the mean of the two sides there)
    v_qs = bm.shear_force(xs, t, n_modes=4001, **args)
    v_pl = bm.shear_force(xs, t, n_modes=200001, quasi_static=False, **args)
    np.testing.assert_allclose(v_pl, v_qs, atol=1e-4 * np.abs(v_qs).max())
    # corrected sums: 321 modes already at the 4001-mode value
    np.testing.assert_allclose(bm.bending_moment(x, t, n_modes=321, **args), m_qs, atol=1e-5 * np.abs(m_qs).max())


def test_field_static_limit_and_shapes():
    # source: closed form — the deflection is linear in J; at resonance the field is NaN;
    # output shape t.shape + x.shape
    args = field_args(10.0, 5e-3, "alternating")
    y = bm.deflection(np.zeros((2, 3)), np.zeros(4), n_modes=11, **args)
    assert y.shape == (4, 2, 3)
    args2 = dict(args, impulse=200.0)
    np.testing.assert_allclose(bm.deflection([3.0], [1e-3], n_modes=51, **args2),
                               2 * bm.deflection([3.0], [1e-3], n_modes=51, **args), rtol=1e-13)


# --- the paper's double Fourier series ------------------------------------------------------------
FOURIER_MS = np.array([400, 1600, 6400, 25600])


@pytest.mark.parametrize("pattern", PATTERNS)
@pytest.mark.parametrize("omega,tl,tau", CASES, ids=[f"w={c[0]:.4g}" for c in CASES])
def test_fourier_response_converges_to_closed_form(pattern, omega, tl, tau):
    """source: convergence to reference (the closed form :func:`modal_periodic_response`).

    The half-sine train is continuous with kinks (jumps of h') at the pulse start t = 0 and end
    t = T_L, so c_m ~ m⁻². Rates measured (least-squares slope over M = 400…25 600, all four CASES,
    both patterns), relative to max|q| or max|q̇| over the points:
      q  at t = 0 and t = T_L (kinks, slowest):  M^-3.00 … M^-3.05
      q  during the pulse (t = T_L/4):           M^-3.9 … M^-4.2
      q  between pulses (t = 0.37 τ):            M^-3.9 … M^-4.3
      q̇  at t = 0, T_L/4, T_L, 0.37 τ:           M^-2.8 … M^-3.2 (the sup over t, near the kinks, is
                                                  ~M^-2 like a Gibbs layer of width 1/(MΩ))
      (q̇ at the pulse midpoint t = T_L/2 is exact to round-off for every M: by the symmetry of the
       train about T_L/2 the truncation error of q̇ is odd about it.)
    At M = 25 600: q error 1e-11 … 1.3e-9, q̇ error 5e-11 … 2e-8 relative.
    """
    t = np.array([0.0, tl / 4, tl, 0.37 * tau])
    q, v = bm.modal_periodic_response(t, omega, tl, tau, pattern)
    eq, ev = [], []
    for m in FOURIER_MS:
        qf, vf = fs.modal_fourier_response(t, omega, tl, tau, pattern, harmonics=m)
        eq.append(np.abs(qf - q) / np.abs(q).max())
        ev.append(np.abs(vf - v) / np.abs(v).max())
    eq, ev = np.array(eq), np.array(ev)
    rate = lambda e: -np.polyfit(np.log(FOURIER_MS), np.log(e), 1)[0]  # noqa: E731
    assert 2.9 < rate(eq[:, 0]) < 3.2 and 2.9 < rate(eq[:, 2]) < 3.2  # kinks: M^-3
    assert rate(eq[:, 1]) > 3.7 and rate(eq[:, 3]) > 3.7  # smooth parts: M^-4
    assert all(rate(ev[:, j]) > 2.6 for j in range(4))
    assert np.all(np.diff(eq[:, [0, 2]], axis=0) < 0)  # monotone at the kinks
    assert eq[-1].max() < 2e-9 and ev[-1].max() < 3e-8
    if omega == 130.0:  # a smooth case (ω T_L < π, well off resonance): < 1e-8 relative
        assert eq[-1].max() < 1e-10 and ev[-1].max() < 1e-9


def test_fourier_response_harmonic_count_and_mean():
    # source: closed form — M = 0 keeps only the mean 1/(τω²) (one_wall) and nothing (alternating);
    # M counts the highest harmonic, so alternating M = 50 and M = 49 are the same sum
    omega, tl, tau = 130.0, 5e-3, 0.21
    t = np.linspace(0, tau, 7)
    q0, v0 = fs.modal_fourier_response(t, omega, tl, tau, "one_wall", harmonics=0)
    np.testing.assert_allclose(q0, 1 / (tau * omega**2), rtol=1e-15)
    assert np.all(v0 == 0)
    assert np.all(fs.modal_fourier_response(t, omega, tl, tau, "alternating", harmonics=0).displacement == 0)
    a50 = fs.modal_fourier_response(t, omega, tl, tau, "alternating", harmonics=50)
    a49 = fs.modal_fourier_response(t, omega, tl, tau, "alternating", harmonics=49)
    np.testing.assert_array_equal(a50.displacement, a49.displacement)
    # and it is the brute-force reference series of the closed-form tests
    qf, vf = fourier_reference(t, omega, tl, tau, "alternating", 49)
    np.testing.assert_allclose(a49.displacement, qf, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(a49.velocity, vf, rtol=1e-12, atol=1e-13)


def test_fourier_response_broadcast_chunks_and_nan(monkeypatch):
    # source: closed form — broadcasting like modal_periodic_response, chunking changes nothing,
    # NaN exactly where the closed form is NaN (resonance, pulse longer than P, NaN ω)
    tau, tl = 0.2, 1e-3
    big = 2 * np.pi / tau
    om = np.array([1.0, 2.5, 3.0, np.nan, 1.25]) * big
    t = np.linspace(-0.05, 0.3, 9)
    with np.errstate(all="raise"):
        full = fs.modal_fourier_response(t[:, None], om[None, :], tl, tau, "one_wall", harmonics=300)
    assert full.displacement.shape == (9, 5)
    closed = bm.modal_periodic_response(t[:, None], om[None, :], tl, tau, "one_wall")
    np.testing.assert_array_equal(np.isnan(full.displacement), np.isnan(closed.displacement))
    assert np.isnan(full.displacement[:, [0, 2, 3]]).all() and np.isfinite(full.velocity[:, [1, 4]]).all()
    monkeypatch.setattr(fs, "_SERIES_CHUNK", 1000)  # 3 points per chunk
    chunked = fs.modal_fourier_response(t[:, None], om[None, :], tl, tau, "one_wall", harmonics=300)
    np.testing.assert_allclose(chunked.displacement, full.displacement, rtol=1e-14)
    alt = fs.modal_fourier_response(0.0, 7.0, 0.15, tau, "alternating")
    assert np.isnan(alt.displacement)


SERIES_NM = [(41, 400), (161, 1600), (641, 6400)]


@pytest.mark.parametrize("pattern", PATTERNS)
@pytest.mark.parametrize("shape", ["point", "parabolic"])
def test_series_field_converges_to_quasi_static_fields(pattern, shape):
    """source: convergence to reference (the closed-form-in-time, quasi-statically corrected modal sums
    with 4001 modes). Measured, relative to the field's max over the points, for (N, M) = (41, 400),
    (161, 1600), (641, 6400):
      deflection            1.2e-4, 2.9e-5, 2.9e-8 (one_wall)   5e-5, 6e-7, 1.5e-8 (alternating)
      moment, point load    0.13, 0.05, 0.008 (one_wall)        0.18, 0.05, 0.012  — ~1/N at midspan
      moment, parabolic     0.12, 0.036, 9e-5 (one_wall)        0.15, 0.022, 1.5e-4 (b = 2 cm: the
                            spread load's modal factors die out once k_n b ≳ π)
      shear off midspan     0.29, 0.29, 3e-3 (one_wall, point)  0.09, 0.036, 5e-3 (alternating, point)
    The one_wall shear stalls between N = 41 and 161: not monotone enough to assert strictly."""
    span = 10.0
    args = field_args(span, 5e-3, pattern, shape)
    t = np.array([0.0, 1.25e-3, 5e-3, 0.03, 0.13])
    x = np.array([span / 2, span / 3, span / 7])
    refs = {"deflection": bm.deflection(x, t, n_modes=4001, **args),
            "moment": bm.bending_moment(x, t, n_modes=4001, **args),
            "shear": bm.shear_force(x[1:], t, n_modes=4001, **args)}
    errs = {key: [] for key in refs}
    for n, m in SERIES_NM:
        for key, ref in refs.items():
            xx = x[1:] if key == "shear" else x
            val = fs.series_field(xx, t, key, n_modes=n, harmonics=m, **args)
            errs[key].append(np.abs(val - ref).max() / np.abs(ref).max())
    for key, e in errs.items():
        assert e[1] < 1.02 * e[0] and e[2] < 0.3 * e[1], (key, e)
    assert errs["deflection"][-1] < 1e-7
    assert errs["moment"][-1] < (2e-2 if shape == "point" else 1e-3)
    assert errs["shear"][-1] < 1e-2


@pytest.mark.parametrize("pattern", PATTERNS)
def test_series_field_satisfies_truncated_equation_of_motion(pattern):
    # source: closed form — every (n, m) term solves EI y'''' − T y'' + M ÿ = J c_m e^{imΩt} g_n
    # sin(k_n x)/(L/2), so the kinds must combine to the truncated load; order aliases and
    # the d2/d4 kinds are the moment/bending load divided by ±EI
    span = 10.0
    args = field_args(span, 5e-3, pattern, "parabolic")
    ei, tn, mass, imp, tl, tau = 1e6, 5e4, 40.0, 100.0, 5e-3, 0.2
    t = np.linspace(0, tau, 13)[:, None] + np.array([0.0, 1e-3])  # shape (13, 2)
    x = np.linspace(0.5, span / 2, 4)
    nm = dict(n_modes=41, harmonics=120)
    f = {k: fs.series_field(x, t, k, **nm, **args) for k in fs.SERIES_KINDS}
    assert f["deflection"].shape == (13, 2, 4)
    lhs = f["bending_load"] - tn * f["d2"] + mass * f["acceleration"]
    n = np.arange(1, 42, 2)
    gx = (bm.modal_load_factors(n, span, 0.02, "parabolic") * np.sin(np.outer(x, n * np.pi / span))).sum(1) / (span / 2)
    m = np.arange(0, 121) if pattern == "one_wall" else np.arange(1, 121, 2)
    c = bm.pulse_spectrum(m * 2 * np.pi / tau, tl) / tau * np.where(m == 0, 1, 2) * (2 if pattern == "alternating" else 1)
    h_trunc = (c * np.exp(1j * 2 * np.pi / tau * m * t[..., None])).real.sum(-1)
    np.testing.assert_allclose(lhs, imp * h_trunc[..., None] * gx, atol=1e-9 * np.abs(lhs).max())
    # the same sums divided by ±EI: equal to the rounding of sums of 41 x 120 terms (about 1e-16 each of the
    # largest), held on the fields' largest value, not pointwise (a field near zero keeps its absolute rounding)
    for kind, exact in (("d2", -f["moment"] / ei), ("d4", f["bending_load"] / ei)):
        np.testing.assert_allclose(f[kind], exact, rtol=0, atol=1e-12 * np.abs(exact).max())
    for order, kind in [(0, "deflection"), (2, "moment"), (3, "shear"), (4, "bending_load")]:
        np.testing.assert_array_equal(fs.series_field(x, t, order, **nm, **args), f[kind])
    with pytest.raises(ValueError):
        fs.series_field(x, t, "slope", **nm, **args)


@pytest.mark.parametrize("pattern", PATTERNS)
def test_series_velocity_converges_to_closed_form_modal_sum(pattern, monkeypatch):
    # source: convergence to reference — ẏ = Σ [J g_n/(M L/2)] q̇_n sin(k_n x), q̇_n from the closed
    # form, same 21 modes; the series error falls ~M^-3 at fixed points (measured: 1.9e-3, 8.6e-6,
    # 1.3e-7 one_wall; 1.3e-3, 4.7e-6, 7.3e-8 alternating for M = 200, 800, 3200); chunking over
    # time and harmonics changes nothing
    span, tl, tau = 10.0, 5e-3, 0.2
    args = field_args(span, tl, pattern)
    t = np.array([0.0, 1.2e-3, 3e-3, 0.04, 0.15])
    x = np.array([span / 2, span / 5])
    n = np.arange(1, 22, 2)
    k = n * np.pi / span
    omega = np.sqrt((1e6 * k**4 + 5e4 * k**2) / 40.0)
    amp = 100.0 * bm.modal_load_factors(n, span, 0.02, "point") / (0.5 * 40.0 * span)
    qd = bm.modal_periodic_response(t[:, None], omega, tl, tau, pattern).velocity
    ref = (qd * amp) @ np.sin(np.outer(k, x))
    errs = [np.abs(fs.series_field(x, t, "velocity", n_modes=21, harmonics=m, **args) - ref).max()
            / np.abs(ref).max() for m in (200, 800, 3200)]
    assert errs[0] > errs[1] > errs[2] and errs[2] < 1e-6
    full = fs.series_field(x, t, "velocity", n_modes=21, harmonics=800, **args)
    monkeypatch.setattr(fs, "_SERIES_CHUNK", 1000)
    np.testing.assert_allclose(fs.series_field(x, t, "velocity", n_modes=21, harmonics=800, **args), full,
                               rtol=1e-12, atol=1e-12 * np.abs(full).max())


@pytest.mark.parametrize("pattern", ["one_wall", "alternating"])
def test_state_at_pulse_start_equals_the_full_response_at_t0(pattern):
    # source: the closed form itself - modal_state_at_pulse_start is modal_periodic_response at t = 0
    # without the in-pulse terms (zero there); resonant frequencies are NaN in both.
    omega = np.array([0.3, 7.3, 31.0, 400.0, 5000.0, 2 * np.pi / 0.2 * 3])
    full = bm.modal_periodic_response(0.0, omega, 1e-3, 0.2, pattern)
    start = bm.modal_state_at_pulse_start(omega, 1e-3, 0.2, pattern)
    np.testing.assert_allclose(start.displacement, full.displacement, rtol=1e-12, equal_nan=True)
    np.testing.assert_allclose(start.velocity, full.velocity, rtol=1e-12, atol=1e-15, equal_nan=True)


@pytest.mark.parametrize("pattern", PATTERNS)
@pytest.mark.parametrize("shape", SHAPES)
def test_midspan_state_sum_equals_the_modal_sum(pattern, shape):
    # source: the closed form itself - the compiled midspan sum is sum_n w_n (q_n(0), q'_n(0), -k_n^2 q_n(0))
    # with w_n = 2 g_n sin(n pi/2)/(M L), g_n from modal_load_factors and q_n from the full periodic response
    # at t = 0; spans from 3 to 300 m cross thousands of resonances, contact half-lengths reach beta > 0.5.
    rng = np.random.default_rng(7)
    span, tl, half = rng.uniform(3, 300, 4000), rng.uniform(1e-4, 3e-3, 4000), rng.uniform(0, 0.3, 4000)
    modes = np.arange(1, 42, 2.0)
    ei, tension, mass, tau = 1.1e6, 4e4, 43.0, 0.2
    y, v, curv = ms.midspan_state_at_pulse_start(span, tl, half, modes, ei, tension, mass, tau, pattern, shape)
    k = modes * np.pi / span[:, None]
    omega = np.sqrt((ei * k**4 + tension * k**2) / mass)
    state = bm.modal_periodic_response(0.0, omega, tl[:, None], tau, pattern)
    w = 2 * bm.modal_load_factors(modes, span, half, shape) / (mass * span[:, None]) * np.where(modes % 4 == 1, 1, -1)
    for got, want in [(y, (w * state.displacement).sum(1)), (v, (w * state.velocity).sum(1)),
                      (curv, -(w * k**2 * state.displacement).sum(1))]:
        # near a resonance both lose the same few digits: compare against the largest value
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-9 * np.abs(want).max())
    # per-span modes: one mode each, as the resonance widths use it
    one = ms.midspan_state_at_pulse_start(span[:5], tl[:5], half[:5], modes[3:8, None], ei, tension, mass, tau,
                                          pattern, shape)[0]
    np.testing.assert_allclose(one, (w * state.displacement)[np.arange(5), np.arange(3, 8)], rtol=1e-9)


def test_midspan_state_is_nan_at_resonance_buckling_and_overlong_pulse():
    # source: modal_periodic_response's NaN rules - exact resonance, a buckled mode, T_L > the (half) period
    ei, mass, tau = 1.0e6, 40.0, 0.2
    span_res = np.pi * (ei / mass) ** 0.25 / np.sqrt(2 * np.pi / tau * 3)  # mode 1 at the 3rd harmonic, T = 0
    args = ([1.0, 3.0, 5.0], ei, 0.0, mass, tau, "one_wall", "point")
    assert np.isnan(ms.midspan_state_at_pulse_start(span_res, 1e-3, 0.0, *args)[0])
    assert np.isfinite(ms.midspan_state_at_pulse_start(span_res * 1.001, 1e-3, 0.0, *args)[0])
    buckled = ms.midspan_state_at_pulse_start(30.0, 1e-3, 0.0, [1.0, 3.0], ei, -2 * ei * (np.pi / 30) ** 2,
                                              mass, tau, "one_wall", "point")
    assert np.isnan(buckled[0])
    assert np.isnan(ms.midspan_state_at_pulse_start(30.0, 0.25, 0.0, *args)[1])  # T_L = 0.25 s > tau
    assert np.isfinite(ms.midspan_state_at_pulse_start(30.0, 0.15, 0.0, *args)[1])
    assert np.isnan(ms.midspan_state_at_pulse_start(30.0, 0.15, 0.0, [1.0], ei, 0.0, mass, tau, "alternating",
                                                    "point")[1])  # T_L = 0.15 s > tau/2


@pytest.mark.parametrize("pattern", PATTERNS)
def test_largest_excursion_is_the_maximum_of_the_weighted_closed_form(pattern):
    # source: modal_periodic_response (the closed form) summed with weights and maximised over the times
    # in numpy; per row its own times (during and after the pulse, past a period; random steps, or
    # uniform ones along which the kernel turns sin and cos instead of evaluating them), frequencies, T_L
    rng = np.random.default_rng(7)
    R, T, M = 6, 40, 9
    t = np.sort(rng.uniform(-0.05, 0.45, (R, T)), axis=1)
    t[3:] = np.linspace(rng.uniform(0.0, 0.05, 3), rng.uniform(0.15, 0.45, 3), T).T  # uniform rows: turned
    omega = np.sort(rng.uniform(2.0, 3e3, (R, M)), axis=1)
    tl = rng.uniform(1e-3, 0.04, R)
    w = rng.normal(size=(R, M))
    q = bm.modal_periodic_response(t[:, :, None], omega[:, None, :], tl[:, None, None], 0.2, pattern).displacement
    want = np.max(np.abs(np.einsum("rtm,rm->rt", q, w)), axis=1)
    np.testing.assert_allclose(bm.largest_excursion(t, omega, tl, w, 0.2, pattern), want, rtol=1e-12)
    omega[2, 4] = 2 * np.pi / 0.2 * 3  # the third harmonic: resonant for both patterns, the row is NaN
    got = bm.largest_excursion(t, omega, tl, w, 0.2, pattern)
    assert np.isnan(got[2]) and np.isfinite(np.delete(got, 2)).all()


@pytest.mark.parametrize("pattern", PATTERNS)
def test_largest_excursion_with_a_limit_stops_a_row_at_its_first_time_above_it(pattern):
    # source: the same numpy closed form as above; a row whose running maximum first passes its limit at
    # time i returns the excursion at i (above the limit, below the row's maximum when a later time is
    # larger); a row that never passes it returns its full maximum - the verdict largest <= limit is the
    # unlimited one either way
    rng = np.random.default_rng(11)
    R, T, M = 5, 30, 7
    t = np.sort(rng.uniform(0.0, 0.4, (R, T)), axis=1)
    omega = np.sort(rng.uniform(2.0, 3e3, (R, M)), axis=1)
    tl = rng.uniform(1e-3, 0.04, R)
    w = rng.normal(size=(R, M))
    q = bm.modal_periodic_response(t[:, :, None], omega[:, None, :], tl[:, None, None], 0.2, pattern).displacement
    excursion = np.abs(np.einsum("rtm,rm->rt", q, w))
    full = excursion.max(axis=1)
    limit = np.array([0.5, 0.8, 0.95, 0.999, 1.5]) * full  # the last row never passes it
    got = bm.largest_excursion(t, omega, tl, w, 0.2, pattern, limit=limit)
    first = [np.argmax(np.maximum.accumulate(row) > lim) for row, lim in zip(excursion, limit)]
    want = [excursion[r, i] if full[r] > limit[r] else full[r] for r, i in enumerate(first)]
    np.testing.assert_allclose(got, want, rtol=1e-12)
    assert np.all((got <= limit) == (full <= limit))
    assert got[0] < full[0] or np.argmax(excursion[0]) == first[0]


@pytest.mark.parametrize("shape", SHAPES)
@pytest.mark.parametrize("pattern", PATTERNS)
def test_excursion_verdicts_are_the_largest_excursion_s_wherever_they_decide(pattern, shape):
    # source: largest_excursion (the library's sin and cos) with the midspan weights 2 g_n/(M L) of the odd
    # modes (modal_load_factors x sin(n pi/2)) and natural_frequencies; limits spread round each row's
    # maximum, and within 1e-15 of it (rounding: there the verdict must be left to largest_excursion, undecided)
    from study.physics import section
    rng = np.random.default_rng(5)
    ei, tension, mass, tau, n_odd = 1.6e6, 4e4, 30.0, 0.2, 11
    R = 400
    spans = rng.uniform(5.0, 40.0, R)
    tl = rng.uniform(5e-4, 0.02, R)
    half = rng.uniform(0.0, 0.2, R)
    fractions = rng.uniform(0.0, 1.0, (R, 24))
    end = tau if pattern == "one_wall" else tau / 2
    t = tl[:, None] + (end - tl[:, None]) * np.clip(fractions, 1e-6, 1 - 1e-6)
    modes = np.arange(1, 2 * n_odd, 2.0)
    omega = section.natural_frequencies(spans, ei, tension, mass, modes)
    weight = 2 * bm.modal_load_factors(modes, spans, half, shape) * np.where(modes % 4 == 1, 1.0, -1.0) / (
        mass * spans[:, None])
    full = bm.largest_excursion(t, omega, tl, weight, tau, pattern)
    limit = full * np.concatenate([rng.uniform(0.3, 1.7, R - 40), 1 + rng.choice([-1, 1], 40) * 1e-15 * rng.uniform(
        0.1, 1.0, 40)])
    verdict = ms.excursion_verdicts(t, spans, tl, half, n_odd, ei, tension, mass, tau, pattern, shape, limit=limit)
    decided = verdict >= 0
    np.testing.assert_array_equal(verdict[decided] == 1, (full > limit)[decided])
    assert decided[:R - 40].mean() > 0.99  # far from the limit it decides
    assert not decided[R - 40:].any()  # within rounding of it, it does not
    inside = t.copy()
    inside[0, 3] = 0.5 * tl[0]  # a time inside the pulse: undecided
    assert ms.excursion_verdicts(inside, spans, tl, half, n_odd, ei, tension, mass, tau, pattern, shape,
                                 limit=limit)[0] == -1


@pytest.mark.parametrize("pattern", PATTERNS)
@pytest.mark.parametrize("tl", [1e-3, 0.03])
def test_compiled_periodic_displacement_equals_the_closed_form(pattern, tl):
    # source: the closed form itself (modal_periodic_response, tested against the ODE and the Fourier
    # series above) - the compiled grid version rearranges it into per-mode factors times sin/cos of the
    # phase, turned step by step along the uniform runs of the grid; times over several periods, before
    # and after t = 0, on a uniform grid and on a grid of random steps, frequencies across seven decades
    # and on both sides of the pulse frequency pi/T_L (where the pulse from rest changes form).
    a = np.pi / tl
    omega = np.concatenate([np.geomspace(0.5, 5e4, 250), a * (1.0 + np.array([-0.05, -2e-2, -1e-2, -1e-5, 0.0,
                                                                                1e-5, 1e-2, 2e-2, 0.05]))])
    rng = np.random.default_rng(7)
    t = np.linspace(-0.3, 0.5, 1601) if tl < 0.01 else np.sort(rng.uniform(-0.3, 0.5, 1601))
    got = bm.periodic_displacement(t, omega, tl, 0.2, pattern)
    want = bm.modal_periodic_response(t[:, None], omega, tl, 0.2, pattern).displacement
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-13 * np.nanmax(np.abs(want)))  # NaN where resonant (a = pi/T_L is, at T_L = 1 ms)
    resonant = np.array([2 * np.pi / 0.2 * 3, 40.0])  # the third harmonic: resonant for both patterns
    assert np.isnan(bm.periodic_displacement(t[:3], resonant, tl, 0.2, pattern)[:, 0]).all()
    assert np.isfinite(bm.periodic_displacement(t[:3], resonant, tl, 0.2, pattern)[:, 1]).all()


@pytest.mark.parametrize("tension", [0.0, 5e4, 5e6, -0.5 * 2e6 * (np.pi / 10.0) ** 2],
                         ids=["no tension", "tension", "strong tension", "half the Euler compression"])
def test_point_load_moment_is_the_sum_of_its_modal_series(tension):
    # Source: the closed-form Green's function must equal its own Fourier sine series
    # sum (2/L) EI sin(k a) sin(k x)/(EI k^2 + T) (the terms fall like 1/n^2: 2e5 terms, tail ~1e-6).
    span, ei, load_at = 10.0, 2e6, 3.3
    x = np.linspace(0.0, span, 9)
    k = np.arange(1, 200_001, dtype=float) * np.pi / span
    series = ((2.0 / span) * ei * np.sin(k * load_at) / (ei * k**2 + tension)) @ np.sin(np.outer(k, x))
    closed = bm.point_load_moment(x, load_at, span, ei, tension)
    assert np.max(np.abs(closed - series)) <= 1e-6 * np.max(np.abs(series))


def test_odd_harmonics_by_angle_addition_equal_sin_and_cos():
    # source: the definition - sin(n theta), cos(n theta) for odd n, here by turning from one odd n to
    # the next; 400 modes (anchored afresh every bm._ROTATION_STEPS) over a span's points.
    theta = np.linspace(0.0, np.pi / 2, 63)
    n = np.arange(1, 800, 2)
    s, c = bm._odd_harmonics(theta, n.size)
    # to a few roundings of the argument n theta (up to 1255 here: 1255 eps = 2.8e-13) either way
    np.testing.assert_allclose(s, np.sin(np.outer(n, theta)), rtol=0, atol=5e-13)
    np.testing.assert_allclose(c, np.cos(np.outer(n, theta)), rtol=0, atol=5e-13)


@pytest.mark.parametrize("shape", ["point", "uniform", "parabolic"])
def test_loaded_pulse_spectrum_is_the_load_factor_times_the_spectrum(shape):
    # source: the two closed forms it fuses, modal_load_factors and pulse_spectrum (tested above), over
    # frequencies on both sides of u = omega T_L/pi = 1 and contact lengths from a point to a tenth of the span
    tl, span = 2e-3, 12.0
    omega = np.concatenate([np.geomspace(1.0, 1e6, 400), np.pi / tl * (1.0 + np.array([-1e-3, -1e-9, 0.0, 1e-9, 1e-3]))])
    n = np.arange(1, 2 * omega.size, 2)[: omega.size].astype(float)
    half = np.linspace(0.0, 1.2, omega.size)
    real, imag = bm.loaded_pulse_spectrum(omega, span, n, tl, half, shape)
    factors = np.array([bm.modal_load_factors([k], span, b, shape)[0] for k, b in zip(n, half)])
    want = np.abs(factors) * bm.pulse_spectrum(omega, tl)
    np.testing.assert_allclose(real, want.real, rtol=0, atol=1e-13)
    np.testing.assert_allclose(imag, want.imag, rtol=0, atol=1e-13)


def test_sincos_is_the_library_s_sine_and_cosine_to_two_ulp():
    # source: math.sin and math.cos (the C library); |sin|, |cos| <= 1, so 2 ulp of 1 absolute
    import math

    import numba

    @numba.njit
    def both(x):
        out = np.empty((2, x.size))
        for i in range(x.size):
            out[0, i], out[1, i] = ms.sincos(x[i])
        return out

    rng = np.random.default_rng(7)
    x = np.concatenate([rng.uniform(-1e7, 1e7, 20000), rng.uniform(-10, 10, 20000), rng.uniform(-1e-8, 1e-8, 100),
                        np.arange(-8, 9) * np.pi / 4, [0.0]])
    got = both(x)
    np.testing.assert_allclose(got[0], [math.sin(v) for v in x], rtol=0, atol=4.5e-16)
    np.testing.assert_allclose(got[1], [math.cos(v) for v in x], rtol=0, atol=4.5e-16)
    assert np.all(np.isnan(both(np.array([np.nan]))))


@pytest.mark.parametrize("pattern", ["one_wall", "alternating"])
@pytest.mark.parametrize("shape", ["point", "uniform", "parabolic"])
def test_midspan_states_of_many_spans_are_the_scalar_loop_s_to_the_last_bit(pattern, shape):
    # source: midspan_state_one, the scalar loop over the same terms in the same order
    spans = np.geomspace(3.0, 300.0, 3001)
    durations = np.where(spans < 100, 1.5e-3, 4e-3)
    durations[::500] = 0.3  # longer than the half period: NaN
    modes = np.arange(1.0, 42.0, 2.0)
    args = (1.6e6, 4e4, 30.0, 0.2, pattern == "one_wall", bm.SHAPE_CODES[shape], 1e-15)
    simd = np.array(ms.midspan_states(spans, durations, 0.002 * spans, modes.size, *args))
    scalar = ms._midspan_state_kernel(spans, durations, 0.002 * spans, modes[None, :], *args, True)
    assert np.isnan(scalar).sum() >= 18 and np.array_equal(simd, scalar, equal_nan=True)
    # and y1 or v1 alone (midspan_sums) is the same sum
    for velocity, row in ((False, 0), (True, 1)):
        alone = ms.midspan_sums(spans, durations, 0.002 * spans, modes.size, *args, velocity)
        assert np.array_equal(alone, scalar[row], equal_nan=True)


@pytest.mark.parametrize("pattern", ["one_wall", "alternating"])
def test_series_on_a_uniform_grid_by_fft_is_the_direct_sum(pattern):
    # source: the direct sum over harmonics (the path taken when one time leaves the grid jτ/K)
    tau = 0.2
    t = np.linspace(0.0, tau if pattern == "one_wall" else tau / 2, 300, endpoint=False)
    x = np.linspace(0.0, 5.0, 11)
    args = dict(span_length=10.0, bending_stiffness=1.6e6, tension=4e4, mass=30.0, impulse=50.0, pulse_duration=2e-3,
                period=tau, pattern=pattern, half_length=0.01, shape="parabolic", n_modes=21, harmonics=400)
    kinds = ["deflection", "acceleration", "d4", "shear"]
    assert fs._steps_per_period(t, tau) == (300 if pattern == "one_wall" else 600)
    by_fft = fs.series_fields(x, t, kinds, **args)
    direct = fs.series_fields(x, np.append(t, 0.123456789 * tau), kinds, **args)
    for kind in kinds:
        np.testing.assert_allclose(by_fft[kind], direct[kind][:-1], rtol=0, atol=1e-12 * np.abs(direct[kind]).max())


@pytest.mark.parametrize("pattern", ["one_wall", "alternating"])
def test_dynamic_remainder_is_the_response_less_its_quasi_static_part(pattern):
    # source: modal_periodic_response and pulse_train (the complex closed form), q - h/omega^2
    t = np.linspace(0.0, 0.2, 700)
    omega = np.array([40.0, 310.0, 1570.0, 9000.0])
    q = bm.modal_periodic_response(t[:, None], omega, 2e-3, 0.2, pattern).displacement
    h = bm.pulse_train(t[:, None], 2e-3, 0.2, pattern)
    expected = q - h / omega**2
    np.testing.assert_allclose(bm.dynamic_remainder(t, omega, 2e-3, 0.2, pattern), expected, rtol=0,
                               atol=1e-10 * np.abs(expected).max())
