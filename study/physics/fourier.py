"""The paper's double Fourier series of the span under the periodic pulse train (docs/model.md §4 "series", paper
eq. 25, 36): the reproduction of the source's solution and the slow reference of :mod:`study.physics.beam`'s closed
form.

Each mode's response is the sum over the pulse train's harmonics (:func:`train_coefficients`,
:func:`modal_fourier_response`), and the fields over the span and the period are summed over modes and harmonics,
by FFT over a uniform time grid where one fits (:func:`series_fields`, :func:`series_field`).

Pure functions of numpy arrays, SI units, no I/O.
"""

from __future__ import annotations

import numpy as np

from study.physics.beam import (IMPACT_PATTERNS, ModalResponse, check_choice, modal_load_factors, pulse_spectrum,
                                resonance_distance)


# --- the paper's double Fourier series (docs/model.md §4 "series", paper eq. 25, 36) ------------------
#: Largest number of array elements one vectorised block of a series evaluation may hold; larger
#: evaluations are chunked (over time, or over the flattened broadcast shape).
_SERIES_CHUNK = 4_000_000


def harmonic_numbers(harmonics, pattern):
    """Harmonic numbers m kept, |m| ≤ M: 0, 1, …, M (one_wall) or 1, 3, …, ≤ M (alternating; the
    train is anti-periodic over τ/2, so even harmonics vanish and there is no mean)."""
    mmax = int(harmonics)
    if mmax < 0:
        raise ValueError(f"harmonics = {harmonics!r} must be ≥ 0")
    return np.arange(1, mmax + 1, 2, dtype=float) if pattern == "alternating" else np.arange(0, mmax + 1, dtype=float)


def train_coefficients(m, pulse_duration, period, pattern):
    """One-sided Fourier coefficients w_m c_m [1/s] of the unit-impulse pulse train (complex).

    h(t) = Σ_{m ≥ 0} Re[w_m c_m e^{imΩt}], Ω = 2π/τ, with c_m = H(mΩ)/τ (H = :func:`pulse_spectrum`,
    the pulse starting at t = 0), w_0 = 1 and w_m = 2 for m ≥ 1 (the ±m pair of the real series);
    alternating: the train's coefficients are c_m (1 − (−1)^m), i.e. 2 c_m for odd m.
    """
    tau = np.asarray(period, dtype=float)
    c = pulse_spectrum(m * (2.0 * np.pi / tau), pulse_duration) / tau
    w = np.where(m == 0, 1.0, 2.0)
    if pattern == "alternating":
        w = w * (1.0 - (-1.0) ** m)
    return w * c


def _invalid_modes(omega_n, pulse_duration, period, pattern, resonance_tol):
    """Mask where :func:`modal_periodic_response` returns NaN: exact resonance (as there), pulse longer
    than the (half) period, or NaN ω (buckled mode)."""
    om = np.asarray(omega_n, dtype=float)
    tau = np.asarray(period, dtype=float)
    p = 0.5 * tau if pattern == "alternating" else tau
    with np.errstate(invalid="ignore"):
        nu = om * tau / (2.0 * np.pi)
        return ((resonance_distance(om, tau, pattern) <= resonance_tol * np.maximum(1.0, nu))
                | (np.asarray(pulse_duration, dtype=float) > p) | ~np.isfinite(om))


def modal_fourier_response(t, omega_n, pulse_duration, period, pattern="one_wall", harmonics=50,
                           resonance_tol=1e-15):
    """Steady periodic response of q̈ + ω² q = h(t) as the truncated Fourier series in time (paper eq. 25, 36).

    The same response and normalisation as :func:`modal_periodic_response` (h the unit-impulse pulse
    train of :func:`pulse_train`), computed the paper's way, harmonic by harmonic (docs/model.md §4, §9
    "series"): with Ω = 2π/τ and c_m = H(mΩ)/τ the train's coefficients (:func:`pulse_spectrum`;
    c_m (1 − (−1)^m) for the alternating train),

        h(t) = Σ_{|m| ≤ M} c_m e^{imΩt},   q = Σ_{|m| ≤ M} c_m e^{imΩt}/(ω² − (mΩ)²),
        q̇ = Σ_{|m| ≤ M} i mΩ c_m e^{imΩt}/(ω² − (mΩ)²),

    summed as the real one-sided series (the m = 0 term of one_wall is the mean response
    h̄/ω² = 1/(τω²); the alternating train has odd m only and no mean).

    t [s] (any real; broadcast against omega_n, pulse_duration and period, e.g. t[:, None] with
    omega_n[None, :]), omega_n ω [rad/s], pulse_duration T_L [s], period τ [s], pattern one of
    :data:`IMPACT_PATTERNS`, harmonics M: the highest harmonic number kept (alternating with M = 50
    keeps m = 1, 3, …, 49). Returns ModalResponse(q [s], q̇ [-]) of the broadcast shape.

    The half-sine has kinks (a jump of h') at the pulse start and end, so c_m ~ m⁻² and the error
    falls like M⁻³ (q) and M⁻² (q̇) at those instants, faster elsewhere (see the tests for the
    measured rates). NaN where :func:`modal_periodic_response` is NaN (exact resonance, T_L longer
    than the (half) period, NaN ω), whether or not the resonant harmonic is kept. Evaluated in
    chunks of at most ``_SERIES_CHUNK`` elements × harmonics.
    """
    check_choice("pattern", pattern, IMPACT_PATTERNS)
    t, om, tl, tau = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (t, omega_n, pulse_duration, period)))
    shape = t.shape
    t, om, tl, tau = (v.ravel() for v in (t, om, tl, tau))
    m = harmonic_numbers(harmonics, pattern)
    bad = _invalid_modes(om, tl, tau, pattern, resonance_tol)
    oms = np.where(bad, 1.0, om)
    tm = t - np.floor(t / tau) * tau  # one period [0, τ): keeps the phases mΩt small
    q = np.zeros(t.size)
    v = np.zeros(t.size)
    step = max(1, _SERIES_CHUNK // max(1, m.size))
    with np.errstate(divide="ignore", invalid="ignore"):
        for i in range(0, t.size, step):
            s = slice(i, i + step)
            big = 2.0 * np.pi / tau[s, None]
            wm = m * big
            coef = train_coefficients(m, tl[s, None], tau[s, None], pattern) / (oms[s, None] ** 2 - wm**2)
            terms = coef * np.exp(1j * wm * tm[s, None])
            q[s] = terms.real.sum(axis=1)
            v[s] = (1j * wm * terms).real.sum(axis=1)
    return ModalResponse(np.where(bad, np.nan, q).reshape(shape), np.where(bad, np.nan, v).reshape(shape))


#: Quantities :func:`series_field` evaluates: kind → description [unit]. The integer ``order`` 0, 2, 3, 4
#: is accepted as an alias of deflection, moment, shear, bending_load (``_SERIES_ORDERS``).
SERIES_KINDS = {
    "deflection": "y [m]",
    "velocity": "ẏ [m/s]",
    "acceleration": "ÿ [m/s²]",
    "d2": "y'' [1/m] (curvature of the small-slope beam)",
    "d4": "y'''' [1/m³]",
    "moment": "bending moment −EI y'' [N m] (sagging positive, as :func:`bending_moment`)",
    "shear": "section shear −EI y''' [N] (as :func:`shear_force` without tension)",
    "bending_load": "EI y'''' [N/m] (the bending term of the equation of motion, docs/model.md §2)",
}


_SERIES_ORDERS = {0: "deflection", 2: "moment", 3: "shear", 4: "bending_load"}


def series_fields(x, t, kinds, span_length, bending_stiffness, tension, mass, impulse, pulse_duration, period,
                  pattern="one_wall", half_length=0.0, shape="point", n_modes=101, harmonics=200,
                  resonance_tol=1e-15):
    """The paper's double Fourier series of the periodic field (paper eq. 25, 36; docs/model.md §4, §9 "series").

    kinds: names of :data:`SERIES_KINDS` (or the integer orders 0, 2, 3, 4); returns {kind: field}, the
    time factors e^{imΩt} computed once for all kinds. Each kind: "deflection" y [m], "velocity" ẏ
    [m/s], "acceleration" ÿ [m/s²], "d2" y'' [1/m], "d4" y'''' [1/m³], "moment" −EI y'' [N m], "shear" −EI y''' [N],
    "bending_load" EI y'''' [N/m]; or the integer ``order`` 0, 2, 3, 4 for deflection, moment,
    shear, bending_load. x [m] (0 ≤ x ≤ L), t [s] (any real); the result has shape t.shape + x.shape.
    Scalars and load as :func:`deflection`; n_modes: highest mode number N (odd n ≤ N); harmonics:
    highest harmonic number M (|m| ≤ M; odd m only for the alternating pattern).

    Double series, NO quasi-static correction (the paper's solution):

        y(x, t) = Σ_{n odd ≤ N} Σ_{|m| ≤ M} [J g_n/(M L/2)] c_m e^{imΩt}/(ω_n² − (mΩ)²) sin(k_n x),

    c_m the coefficients of the unit-impulse train (:func:`modal_fourier_response`), g_n the modal
    load factors (:func:`modal_load_factors`), ω_n² = (EI k_n⁴ + T k_n²)/M. Derivatives act term by
    term: ∂/∂t → imΩ, ∂²/∂x² → −k_n², …; shear = EI Σ k_n³ cos(k_n x)(…). Each (n, m) term satisfies
    EI y'''' − T y'' + M ÿ = J c_m e^{imΩt} g_n sin(k_n x)/(L/2) exactly, i.e. the truncated series
    solves the equation of motion under the truncated load. Summed as Re[E (W S)] with E = e^{imΩt}
    (times × harmonics), W the (harmonics × modes) coefficients and S the (modes × x) shapes, so no
    times × modes × harmonics array is formed; chunked over time. Slow: moment converges like 1/N at
    midspan under a point load and shear does not converge there (the paper's "doubtful accuracy").
    NaN at resonance or buckling of any kept mode (as :func:`deflection`).
    """
    kinds = [_SERIES_ORDERS.get(kind, kind) if not isinstance(kind, str) else kind for kind in kinds]
    for kind in kinds:
        check_choice("kind", kind, SERIES_KINDS)
    check_choice("pattern", pattern, IMPACT_PATTERNS)
    x, t = np.asarray(x, dtype=float), np.asarray(t, dtype=float)
    L, ei, tn, mm, tl, tau = (float(v) for v in (span_length, bending_stiffness, tension, mass, pulse_duration, period))
    n = np.arange(1, int(n_modes) + 1, 2, dtype=float)
    k = n * np.pi / L
    with np.errstate(invalid="ignore"):
        omega = np.sqrt(np.where(ei * k**4 + tn * k**2 > 0, (ei * k**4 + tn * k**2) / mm, np.nan))
    bad = _invalid_modes(omega, tl, tau, pattern, resonance_tol)
    amp = float(impulse) * modal_load_factors(n, L, half_length, shape) / (0.5 * mm * L)
    amp = np.where(bad, np.nan, amp)
    oms = np.where(bad, 1.0, omega)
    kx = np.outer(k, x.ravel())
    kc = k[:, None]
    m = harmonic_numbers(harmonics, pattern)
    wm = m * (2.0 * np.pi / tau)
    c0 = train_coefficients(m, tl, tau, pattern)
    hstep = max(1, _SERIES_CHUNK // max(1, n.size))
    ws = {}  # per kind: W S (harmonics × x), W in chunks of harmonics
    for kind in kinds:
        # spatial shapes (modes × x)
        if kind in ("deflection", "velocity", "acceleration"):
            s = np.sin(kx)
        elif kind == "d2":
            s = -kc**2 * np.sin(kx)
        elif kind == "d4":
            s = kc**4 * np.sin(kx)
        elif kind == "moment":
            s = ei * kc**2 * np.sin(kx)
        elif kind == "shear":
            s = ei * kc**3 * np.cos(kx)
        else:  # bending_load
            s = ei * kc**4 * np.sin(kx)
        # harmonic coefficients (harmonics × modes)
        c = c0 * 1j * wm if kind == "velocity" else c0 * -(wm**2) if kind == "acceleration" else c0
        ws[kind] = np.empty((m.size, x.size), dtype=complex)
        for i in range(0, m.size, hstep):
            h = slice(i, i + hstep)
            with np.errstate(divide="ignore", invalid="ignore"):
                w = c[h, None] * amp[None, :] / (oms[None, :] ** 2 - wm[h, None] ** 2)
            ws[kind][h] = w.real @ s + 1j * (w.imag @ s)
    tf = t.ravel()
    tm = tf - np.floor(tf / tau) * tau
    steps = _steps_per_period(tm, tau)
    if steps:  # t on a grid jτ/K: the sum over m is a discrete Fourier transform of length K
        j = np.rint(tm * (steps / tau)).astype(np.int64) % steps
        rows = m.astype(np.int64) % steps
        out = {}
        for kind in kinds:
            folded = np.zeros((steps, x.size), dtype=complex)
            np.add.at(folded, rows, ws[kind])
            out[kind] = (np.fft.ifft(folded, axis=0) * steps)[j].real
        return {kind: out[kind].reshape(t.shape + x.shape) for kind in kinds}
    out = {kind: np.empty((tf.size, x.size)) for kind in kinds}
    step = max(1, _SERIES_CHUNK // max(1, m.size))
    for i in range(0, tf.size, step):
        e = np.exp(1j * np.outer(tm[i:i + step], wm))  # e^{imΩt}, once for every kind
        for kind in kinds:
            out[kind][i:i + step] = (e @ ws[kind]).real
    return {kind: out[kind].reshape(t.shape + x.shape) for kind in kinds}


#: Most points per period of a time grid that :func:`series_fields` sums by FFT.
_MAX_FFT_STEPS = 1 << 16


def _steps_per_period(tm, period) -> int:
    """K when every time of ``tm`` [s] (in [0, τ)) lies within 1e-9 of a step on the grid jτ/K, K the period
    ``period`` τ [s] over the step between the first two times (a uniform grid such as the term ratios'); 0
    otherwise (or for fewer than 8 times, or K above :data:`_MAX_FFT_STEPS`)."""
    if tm.size < 8 or not tm[1] > tm[0]:
        return 0
    steps = int(round(period / (tm[1] - tm[0])))
    if not 0 < steps <= _MAX_FFT_STEPS:
        return 0
    phase = tm * (steps / period)
    return steps if np.all(np.abs(phase - np.rint(phase)) <= 1e-9) else 0


def series_field(x, t, kind, span_length, bending_stiffness, tension, mass, impulse, pulse_duration, period,
                 pattern="one_wall", half_length=0.0, shape="point", n_modes=101, harmonics=200,
                 resonance_tol=1e-15):
    """One field of :func:`series_fields` (``kind`` a name of :data:`SERIES_KINDS` or the integer order
    0, 2, 3, 4); arguments and units as there."""
    kind = _SERIES_ORDERS.get(kind, kind) if not isinstance(kind, str) else kind  # the key of the result
    return series_fields(x, t, [kind], span_length, bending_stiffness, tension, mass, impulse, pulse_duration,
                         period, pattern, half_length, shape, n_modes, harmonics, resonance_tol)[kind]
