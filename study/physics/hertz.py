"""Hertz contact and impact of the drill pipe on the bore-hole wall.

Pure functions of numpy arrays (broadcasting; floats accepted), SI units, no I/O. Sources:
the paper's appendix D (Timoshenko & Goodier form of Hertz contact, "reference 3"; eq. 7) and
its section on impact (eq. 8–17, appendix C); Timoshenko & Goodier, *Theory of Elasticity*,
§140 (T&G); Johnson, *Contact Mechanics*, ch. 3–4 (eq. 3.63–3.64 / 4.39).

Notation: K1, K2 compliances [1/Pa]; A ≤ B half-sums of relative principal curvatures [1/m];
θ [rad] with cos θ = (B − A)/(A + B) (θ = π/2: sphere, θ → 0: line contact); e the
eccentricity of the contact ellipse, c² = 1 − e² = b²/a²; K(e), E(e) complete elliptic
integrals of parameter e² (scipy convention).
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import NamedTuple

import llvmlite.binding as llvm
import numba
import numpy as np
from numba import types
from numba.extending import get_cython_function_address
from scipy.special import beta, binom

from study.physics.contact import hertz_force, hertz_force_one
from study.physics.interpolation import interp_one


class ContactCoefficients(NamedTuple):
    m: np.ndarray  #: semi-major axis a = m X [-]
    n: np.ndarray  #: semi-minor axis b = n X [-]


class ContactEllipse(NamedTuple):
    contact_half_length: np.ndarray  #: semi-axis along the pipe axis [m]
    contact_half_width: np.ndarray  #: circumferential semi-axis [m]
    A: np.ndarray  #: smaller curvature half-sum [1/m]
    B: np.ndarray  #: larger curvature half-sum [1/m]
    theta: np.ndarray  #: auxiliary angle θ [rad]


class HertzImpact(NamedTuple):
    max_approach: np.ndarray  #: α_max [m]
    max_force: np.ndarray  #: F_max [N]
    duration: np.ndarray  #: T_H [s]
    impulse: np.ndarray  #: ∫F dt = 1.6 F_max α_max / v0 = 2 m_e v0 [N s]


class Validity(NamedTuple):
    ok: np.ndarray  #: True where Hertz theory is applicable [bool]
    criterion: str  #: "ok" or the name of the first failed criterion
    message: str  #: human-readable explanation with the numbers compared


# --- elliptic contact: θ -> e -> (m, n) -------------------------------------------------------
# Maclaurin series (in e²) of K = π/2 Σ a_k e^2k and E = π/2 Σ ε_k e^2k, and of the numerator
# N = (2 − e²)E − 2(1 − e²)K = π/2 Σ ν_k e^2k (ν_0 = ν_1 = 0): used for small e², where the
# closed form of cos θ = N/(e² E) loses its leading digits to cancellation.
_k = np.arange(24)
_A_K = (binom(2 * _k, _k) / 4.0**_k) ** 2
_E_K = _A_K / (1 - 2 * _k)
_N_K = 2 * _E_K - 2 * _A_K
_N_K[1:] += 2 * _A_K[:-1] - _E_K[:-1]
_SERIES_MAX = 0.02  # e² below which the series is used (0.02**24 ~ 1e-41)
_P_MIN = -690.0  # log(1 − e²) lower bracket: 1 − e² ≈ 1e-300


def _special(name: str):
    """scipy.special's compiled double → double function ``name`` (scipy.special.cython_special),
    callable from compiled code: its address is registered under a symbol name that the cached
    machine code links against in every process."""
    symbol = f"study_scipy_special_{name}"
    llvm.add_symbol(symbol, get_cython_function_address("scipy.special.cython_special", name))
    return types.ExternalFunction(symbol, types.float64(types.float64))


_ELLIPKM1 = _special("ellipkm1")  # K(1 − m): no loss as e → 1
_ELLIPE = _special("ellipe")


@numba.njit(cache=True, nogil=True)
def _shape_functions(p):
    """(cos θ, 1 − cos θ, K(e), E(e)) for p = log(1 − e²) < 0, each to full relative precision."""
    c2, e2 = math.exp(p), -math.expm1(p)
    kk, ee = _ELLIPKM1(c2), _ELLIPE(e2)
    if e2 < _SERIES_MAX:  # cos θ = N/(e² E) by the series: the closed form cancels
        num, den = 0.0, 0.0
        for j in range(_N_K.size - 1, 1, -1):
            num = num * e2 + _N_K[j]
        for j in range(_E_K.size - 1, -1, -1):
            den = den * e2 + _E_K[j]
        cos_t = e2 * num / den
        return cos_t, 1.0 - cos_t, kk, ee
    # 1 − cos θ = 2 c² (K − E)/(e² E), exact rearrangement of Johnson 4.39, accurate as θ → 0
    return ((1.0 + c2) * ee - 2.0 * c2 * kk) / (e2 * ee), 2.0 * c2 * (kk - ee) / (e2 * ee), kk, ee


@numba.njit(cache=True, nogil=True)
def _angle_residual(p, theta, target):
    """Residual of θ(p) = θ on a log scale, increasing in p: log of 1 − cos θ = 2 sin²(θ/2) for
    θ ≤ π/4 (resolves θ down to ~1e-149 rad), of cos θ above (resolves θ → π/2). ``target``: that log at
    θ itself (:func:`_angle_target`), the same at every p of a solve. Returns (residual, K(e), E(e))."""
    cos_t, one_minus, kk, ee = _shape_functions(p)
    if theta <= 0.25 * math.pi:
        return math.log(one_minus) - target, kk, ee
    return target - math.log(cos_t), kk, ee


@numba.njit(cache=True, nogil=True)
def _angle_target(theta):
    """log(1 − cos θ) = log 2 + 2 log sin(θ/2) for θ ≤ π/4, log cos θ above: the θ side of
    :func:`_angle_residual`."""
    if theta <= 0.25 * math.pi:
        return math.log(2.0) + 2.0 * math.log(math.sin(0.5 * theta))
    return math.log(math.cos(theta))


@numba.njit(cache=True, nogil=True)
def _solve_log_c2(theta, guess):
    """p = log(1 − e²) of θ ∈ (0, π/2) by regula falsi (Illinois) to 1e-15 relative: on ±1e-3 |p| round
    ``guess`` when that brackets the root, else (or with a NaN guess) on the whole range
    1 − e² ∈ [1e-300, 1); θ beyond that range is clipped to 1 − e² = 1e-300. Returns (p, K(e), E(e)), the
    elliptic integrals as evaluated at that p during the solve."""
    a, b, fa, fb = _P_MIN, -1e-300, math.nan, math.nan
    kk_a = ee_a = kk_b = ee_b = math.nan
    target = _angle_target(theta)
    if math.isfinite(guess):
        width = 1e-3 * abs(guess) + 1e-9
        lo, hi = guess - width, min(guess + width, -1e-300)
        f_lo, kk_lo, ee_lo = _angle_residual(lo, theta, target)
        f_hi, kk_hi, ee_hi = _angle_residual(hi, theta, target)
        if f_lo * f_hi <= 0.0:  # the bracket's values are the first step's
            a, b, fa, fb, kk_a, ee_a, kk_b, ee_b = lo, hi, f_lo, f_hi, kk_lo, ee_lo, kk_hi, ee_hi
    if math.isnan(fa):
        fa, kk_a, ee_a = _angle_residual(a, theta, target)
        fb, kk_b, ee_b = _angle_residual(b, theta, target)
    if a == _P_MIN and fa >= 0.0:
        return _P_MIN, kk_a, ee_a
    side = 0
    for _ in range(400):
        if fa == 0.0:
            return a, kk_a, ee_a
        if fb == 0.0 or b - a <= 1e-15 * abs(b):
            break
        mid = b - fb * (b - a) / (fb - fa)
        if not a < mid < b:
            mid = 0.5 * (a + b)
            if not a < mid < b:
                break
        fm, kk_m, ee_m = _angle_residual(mid, theta, target)
        if (fm < 0.0) == (fa < 0.0):  # the root is in [mid, b]
            if side == 1:
                fb *= 0.5
            a, fa, side, kk_a, ee_a = mid, fm, 1, kk_m, ee_m
        else:
            if side == -1:
                fa *= 0.5
            b, fb, side, kk_b, ee_b = mid, fm, -1, kk_m, ee_m
    return (a, kk_a, ee_a) if abs(fa) < abs(fb) else (b, kk_b, ee_b)


@numba.njit(cache=True, nogil=True)
def _coefficients_kernel(theta, guess):
    """(m, n, 2K(e)/(π m)) for every angle of ``theta`` [rad] (flat), p solved from ``guess``."""
    out = np.empty((3, theta.size))
    for i in range(theta.size):
        out[0, i], out[1, i], out[2, i] = _coefficients_one(theta[i], guess[i])
    return out


@numba.njit(cache=True, nogil=True)
def _coefficients_one(t, guess):
    """(m, n, 2K(e)/(π m)) of one angle t [rad], p = log(1 − e²) solved from ``guess``."""
    if math.isnan(t):
        return math.nan, math.nan, math.nan
    if t >= 0.5 * math.pi:  # a sphere
        return 1.0, 1.0, 1.0
    if t <= 0.0:  # line contact: the ellipse is unbounded
        return math.inf, 0.0, 0.0
    p, kk, ee = _solve_log_c2(t, guess)
    m = np.cbrt(2.0 * ee / math.pi) * math.exp(-p / 3.0)  # m³ = 2E/(π(1 − e²))
    return m, m * math.exp(0.5 * p), 2.0 * kk / (math.pi * m)  # n = m √(1 − e²)


@numba.njit(cache=True, nogil=True)
def contact_one(force, pipe_radius, hole_radius, axial_curvature, compliance_sum, guess_table):
    """(contact_half_length [m], contact_half_width [m], Hertz stiffness K [N m^(−3/2)]) of one
    contact, compiled: :func:`contact_ellipse` and :func:`hertz_stiffness` at its curvature sums, in
    the same arithmetic (the T_L–curvature iteration of the periodic solution runs in a compiled
    loop). force F [N], pipe_radius, hole_radius [m], axial_curvature κ [1/m], compliance_sum
    [1/Pa]; guess_table: :func:`guess_table` (log θ, p) for the eccentricity's starting value."""
    k_c = 1.0 / pipe_radius - 1.0 / hole_radius
    a_sum, b_sum = 0.5 * min(k_c, axial_curvature), 0.5 * max(k_c, axial_curvature)
    theta = math.atan2(2.0 * math.sqrt(a_sum * b_sum), b_sum - a_sum)
    m, n, k_factor = _coefficients_one(theta, interp_one(math.log(theta), guess_table[0], guess_table[1]))
    x = np.cbrt(3.0 * math.pi * force * compliance_sum / (4.0 * (a_sum + b_sum)))
    x_1 = np.cbrt(3.0 * math.pi * 1.0 * compliance_sum / (4.0 * (a_sum + b_sum)))
    coefficient = 0.75 * math.pi * k_factor * compliance_sum / x_1
    stiffness = math.inf if coefficient == 0.0 else coefficient**-1.5
    if axial_curvature <= k_c:  # the major axis along the pipe
        return m * x, n * x, stiffness
    return n * x, m * x, stiffness


def _log_c2(theta, full_bracket=False):
    """p = log(1 − e²) of a scalar θ [rad] (:func:`_solve_log_c2`): from the tabulated guess
    (:func:`_guess_log_c2`), or on the whole range when ``full_bracket``. θ ≥ π/2 gives 0 (NaN stays
    NaN), θ ≤ 0 gives −inf."""
    if np.isnan(theta) or theta >= np.pi / 2:
        return theta * 0.0  # nan stays nan
    if theta <= 0.0:
        return -np.inf
    return _solve_log_c2(float(theta), np.nan if full_bracket else _guess_log_c2(theta))[0]


@lru_cache(maxsize=1)
def guess_table():
    """(log θ, p) on 200 angles from 1e-6 rad to just below π/2, solved on the full bracket."""
    theta = np.concatenate((np.geomspace(1e-6, 0.3, 80), np.linspace(0.3, np.pi / 2 - 1e-6, 121)[1:]))
    return np.log(theta), np.array([_log_c2(t, full_bracket=True) for t in theta])


def _guess_log_c2(theta):
    """p = log(1 − e²) at θ interpolated in the table (about 1e-4 relative); θ outside it: its end."""
    log_theta, p = guess_table()
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.interp(np.log(theta), log_theta, p)


def _coefficients(theta):
    """(m, n, 2K(e)/(π m)) of θ [rad], scalar or array (one compiled loop); the last factor scales
    the approach (=1 for a sphere)."""
    theta = np.asarray(theta, dtype=float)
    flat = np.ascontiguousarray(theta.ravel())
    out = _coefficients_kernel(flat, np.ascontiguousarray(_guess_log_c2(flat), dtype=float))
    if theta.ndim == 0:
        return tuple(np.float64(v) for v in out[:, 0])
    return tuple(out[i].reshape(theta.shape) for i in range(3))


def contact_coefficients(theta):
    """T&G coefficients (m, n) of the contact ellipse, a = m X, b = n X [-] (paper app. D; T&G §140).

    theta [rad] in [0, π/2]. Exact values from m³ = 2E(e)/(π(1 − e²)), n = m √(1 − e²), with e
    solved from cos θ = [(2 − e²)E(e) − 2(1 − e²)K(e)]/(e² E(e)) (Johnson eq. 4.39). θ = π/2
    gives m = n = 1; m → ∞, n → 0 as θ → 0 (θ = 0 returns m = inf, n = 0: line contact;
    θ below ~1e-140 rad is clipped at 1 − e² = 1e-300). T&G's printed three-decimal table
    (paper app. D) is off from these exact values by up to 0.002 at 35°, 55°, 65°, 70°, 75°.
    """
    m, n, _ = _coefficients(theta)
    return ContactCoefficients(m, n)


# --- compliance and geometry ------------------------------------------------------------------
def compliance(youngs_modulus, poisson_ratio):
    """Compliance K_i = (1 − ν_i²)/(π E_i) [1/Pa] (paper eq. 7). youngs_modulus [Pa], poisson_ratio [-]."""
    nu = np.asarray(poisson_ratio, dtype=float)
    return (1.0 - nu**2) / (np.pi * np.asarray(youngs_modulus, dtype=float))


def curvature_sums(pipe_radius, hole_radius, axial_curvature=0.0):
    """Half-sums (A, B), A ≤ B [1/m], of the relative curvatures of pipe and wall (T&G §140).

    pipe_radius r_o [m], hole_radius R_hole > r_o [m], axial_curvature κ ≥ 0 of the bent pipe at
    the contact [1/m]. Relative curvatures: circumferential k_c = 1/r_o − 1/R_hole (concave
    wall), axial k_a = κ (straight wall). A + B = ½(k_c + k_a), B − A = ½|k_c − k_a|, i.e.
    A = ½ min(k_c, k_a), B = ½ max(k_c, k_a) (computed so, without cancellation).
    """
    k_c = 1.0 / np.asarray(pipe_radius, dtype=float) - 1.0 / np.asarray(hole_radius, dtype=float)
    k_a = np.asarray(axial_curvature, dtype=float)
    return 0.5 * np.minimum(k_c, k_a), 0.5 * np.maximum(k_c, k_a)


def contact_angle(A, B):
    """θ [rad] with cos θ = (B − A)/(A + B) (paper app. D); A, B [1/m].

    Evaluated as atan2(2√(AB), B − A), accurate at both ends (θ → 0 and θ → π/2).
    """
    A, B = np.asarray(A, dtype=float), np.asarray(B, dtype=float)
    return np.arctan2(2.0 * np.sqrt(A * B), B - A)


def _x_length(force, A, B, compliance_sum):
    """X = [3π F (K1 + K2)/(4(A + B))]^(1/3) [m] (T&G §140)."""
    return np.cbrt(3.0 * np.pi * np.asarray(force, dtype=float) * compliance_sum / (4.0 * (A + B)))


def contact_semi_axes(force, A, B, compliance_sum):
    """Semi-major a = m X and semi-minor b = n X [m] of the contact ellipse (T&G §140).

    force F [N], A ≤ B [1/m], compliance_sum K1 + K2 [1/Pa]; a lies along the direction of A.
    """
    A, B = np.asarray(A, dtype=float), np.asarray(B, dtype=float)
    m, n = contact_coefficients(contact_angle(A, B))
    x = _x_length(force, A, B, compliance_sum)
    return m * x, n * x


def contact_ellipse(force, pipe_radius, hole_radius, axial_curvature, compliance_sum):
    """Contact ellipse of the pipe on the wall, a = m X, b = n X (T&G §140; paper app. D).

    force F [N], pipe_radius r_o [m], hole_radius R_hole [m], axial_curvature κ [1/m],
    compliance_sum K1 + K2 [1/Pa]. The major axis lies along the direction of the smaller
    curvature A: along the pipe when κ < k_c = 1/r_o − 1/R_hole (the usual case), round the
    circumference when κ > k_c. ``contact_half_length`` [m] is always the semi-axis along the
    pipe axis and ``contact_half_width`` [m] the circumferential one, whichever is the larger.
    Also returns A, B [1/m] and θ [rad].
    """
    A, B = curvature_sums(pipe_radius, hole_radius, axial_curvature)
    major, minor = contact_semi_axes(force, A, B, compliance_sum)
    axial_is_major = np.asarray(axial_curvature) <= 1.0 / pipe_radius - 1.0 / hole_radius
    return ContactEllipse(
        np.where(axial_is_major, major, minor), np.where(axial_is_major, minor, major), A, B,
        contact_angle(A, B))


# --- approach-force law ----------------------------------------------------------------------
def approach_coefficient(A, B, compliance_sum):
    """K' [m N^(-2/3)] in δ = K' F^(2/3) (Johnson eq. 3.64/4.39; paper eq. 7).

    δ = 3 F K(e)/(2π a E*) with a = m X and 1/E* = π(K1 + K2). A, B [1/m], compliance_sum
    K1 + K2 [1/Pa]. Line contact (A = 0) gives the formal limit K' = 0.
    """
    A, B = np.asarray(A, dtype=float), np.asarray(B, dtype=float)
    _, _, k_factor = _coefficients(contact_angle(A, B))  # k_factor = 2K(e)/(π m)
    # δ/F^(2/3) = 3 K(e)(K1+K2)/(2 m X1), X1 = X at F = 1 N
    return 0.75 * np.pi * k_factor * compliance_sum / _x_length(1.0, A, B, compliance_sum)


def approach(force, A, B, compliance_sum):
    """Mutual approach δ = K' F^(2/3) [m] of distant points of the two bodies; force F [N]."""
    return approach_coefficient(A, B, compliance_sum) * np.asarray(force, dtype=float) ** (2.0 / 3.0)


def hertz_stiffness(A, B, compliance_sum):
    """Hertz stiffness K = K'^(−3/2) [N m^(−3/2)] so that F = K δ^(3/2) (paper eq. 7–8).

    A, B [1/m], compliance_sum K1 + K2 [1/Pa]; line contact (A = 0) gives inf.
    """
    with np.errstate(divide="ignore"):
        return approach_coefficient(A, B, compliance_sum) ** -1.5


# --- Hertz impact (paper eq. 8–12) -----------------------------------------------------------
#: C_H = 2 ∫0^1 (1 − x^(5/2))^(−1/2) dx = 0.8 B(2/5, 1/2) (paper prints 2.94).
HERTZ_DURATION_CONSTANT = 0.8 * beta(0.4, 0.5)


def hertz_impact(equivalent_mass, velocity, stiffness):
    """Elastic Hertz impact m_e α̈ = −K α^(3/2), α(0) = 0, α̇(0) = v0 (paper eq. 8–12).

    equivalent_mass m_e [kg], velocity v0 [m/s], stiffness K [N m^(−3/2)]. Returns
    α_max = (5 m_e v0²/(4K))^(2/5) [m], F_max = K α_max^(3/2) [N], T_H = C_H α_max/v0 [s],
    impulse ∫F dt = 1.6 F_max α_max/v0 = 2 m_e v0 [N s].
    """
    m_e, v0 = np.asarray(equivalent_mass, dtype=float), np.asarray(velocity, dtype=float)
    alpha = (1.25 * m_e * v0**2 / stiffness) ** 0.4
    f_max = hertz_force(alpha, stiffness)
    return HertzImpact(alpha, f_max, HERTZ_DURATION_CONSTANT * alpha / v0, 1.6 * f_max * alpha / v0)


# --- Lee's half-sine pulse (paper eq. 15–17, appendix C) --------------------------------------
def impact_impulse(equivalent_mass, velocity, restitution):
    """Impulse J = m_e (1 + e) V_p [N s] (paper eq. 16); mass [kg], velocity [m/s], e ∈ [0, 1] [-]."""
    return np.asarray(equivalent_mass) * (1.0 + np.asarray(restitution)) * np.asarray(velocity)


def lee_duration(equivalent_mass, velocity, stiffness):
    """Duration T_L = π m_e v0/F_max [s] of Lee's pulse (paper eq. 17, appendix C).

    Chosen so that peak/impulse of the half-sine, π/(2 T_L), equals that of the elastic Hertz
    impact, F_max/(2 m_e v0). equivalent_mass [kg], velocity [m/s], stiffness [N m^(−3/2)].
    """
    f_max = hertz_impact(equivalent_mass, velocity, stiffness).max_force
    return np.pi * np.asarray(equivalent_mass) * np.asarray(velocity) / f_max


@numba.njit(cache=True, nogil=True)
def lee_duration_one(equivalent_mass, velocity, stiffness):
    """:func:`lee_duration` of one impact, compiled, in the same arithmetic: T_L = π m_e v0/F_max with
    F_max = K α_max^(3/2), α_max = (5 m_e v0²/(4K))^(2/5) [s]."""
    alpha = (1.25 * equivalent_mass * velocity**2 / stiffness) ** 0.4
    return math.pi * equivalent_mass * velocity / hertz_force_one(alpha, stiffness)


def lee_peak_force(impulse, duration):
    """Peak F̂ = π J/(2 T_L) [N] of the half-sine of impulse J [N s] and duration T_L [s] (eq. 15)."""
    return np.pi * np.asarray(impulse) / (2.0 * np.asarray(duration))


def lee_pulse(t, duration, impulse):
    """Lee's pulse f(t') = F̂ sin(π t'/T_L) on 0 ≤ t' ≤ T_L, zero elsewhere [N] (paper eq. 15).

    t time since first contact [s], duration T_L [s], impulse J [N s].
    """
    t, duration = np.asarray(t, dtype=float), np.asarray(duration, dtype=float)
    inside = (t >= 0.0) & (t <= duration)
    return np.where(inside, lee_peak_force(impulse, duration) * np.sin(np.pi * t / duration), 0.0)


#: T_L/T_H = (π/2)(1.6/C_H) (paper: 0.855), derived from the functions above.
LEE_TO_HERTZ_DURATION_RATIO = float(lee_duration(1.0, 1.0, 1.0) / hertz_impact(1.0, 1.0, 1.0).duration)


# --- validity ---------------------------------------------------------------------------------
#: Longest contact along the pipe [-, times the pipe's outer diameter] for which the half-space solution is
#: taken: beyond it the tube's ovalisation, not local indentation, carries the load (our choice: a contact no
#: longer than the pipe is wide; docs/model.md §3).
MAX_LENGTH_TO_DIAMETER = 1.0
#: Most elongated ellipse [-, major over minor semi-axis] reported as a point contact: beyond it the ellipse is a
#: line contact in all but name (our choice: 1/limit² with the default limit 0.1; docs/model.md §3).
MAX_ASPECT_RATIO = 100.0


def contact_validity(half_length, half_width, A, B, span_length=None, limit=0.1, pipe_diameter=None):
    """Is Hertz theory applicable to this contact? Returns Validity(ok, criterion, message).

    half_length, half_width [m] (as from :func:`contact_ellipse`), A ≤ B [1/m], span_length [m]
    or None, limit [-]. Hertz treats each body as a half-space loaded over a region small
    beside the relative radii of curvature and the bodies. The semi-axis lying along the
    direction of A (the major one) is compared with 1/(2A), the other with 1/(2B); in the usual
    case κ < k_c that is the half-length with the axial radius. Criteria, in order:
    ``line_contact`` (A ≤ 0 or non-finite/zero semi-axis), ``half_length_vs_axial_radius``,
    ``half_width_vs_circumferential_radius``, ``half_length_vs_span`` (half_length > limit·span),
    ``length_vs_pipe_diameter`` (2 half_length > :data:`MAX_LENGTH_TO_DIAMETER` · pipe_diameter [m], when
    given) and ``aspect_ratio`` (major/minor semi-axis > :data:`MAX_ASPECT_RATIO`: a degenerate ellipse).
    Note a·2A → 0 as κ → 0 (a grows only like A^(−1/3), up to a logarithm), so a nearly
    straight pipe passes criterion (b) and is caught by the span check only. For arrays ``ok``
    is elementwise; criterion/message give the first criterion (in the order above) failed by
    any element, with the numbers of the first such element.
    """
    hl, hw, A, B = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (half_length, half_width, A, B)))
    along_a = hl >= hw  # the half-length is the major axis, lying along the direction of A
    span = np.broadcast_to(np.inf if span_length is None else np.asarray(span_length, dtype=float), hl.shape)
    diameter = np.broadcast_to(np.inf if pipe_diameter is None else np.asarray(pipe_diameter, dtype=float),
                               hl.shape)
    with np.errstate(divide="ignore", invalid="ignore"):
        aspect = np.maximum(hl, hw) / np.minimum(hl, hw)
        r_ax = 1.0 / (2.0 * np.where(along_a, A, B))  # relative radius of curvature along the pipe
        r_circ = 1.0 / (2.0 * np.where(along_a, B, A))  # ... round the circumference
        line = (A <= 0) | ~np.isfinite(hl) | ~np.isfinite(hw) | ((hl > 0) != (hw > 0))
        checks = [  # name, failed, (label, value), (label, reference), why
            ("half_length_vs_axial_radius", hl > limit * r_ax, ("half-length", hl),
             ("axial relative radius of curvature", r_ax),
             "the contact is not small beside the axial relative radius of curvature, so the "
             "surfaces are not locally paraboloids on elastic half-spaces"),
            ("half_width_vs_circumferential_radius", hw > limit * r_circ, ("half-width", hw),
             ("circumferential relative radius of curvature", r_circ),
             "the contact wraps round the pipe, so the circumferential curvature is not small "
             "over the contact and the half-space assumption fails"),
            ("half_length_vs_span", hl > limit * span, ("half-length", hl), ("span", span),
             "the contact is not short beside the pipe span, so the pipe is not a half-space "
             "there (its bending, not local indentation, governs the approach)"),
            ("length_vs_pipe_diameter", 2.0 * hl > MAX_LENGTH_TO_DIAMETER * diameter, ("length", 2.0 * hl),
             ("pipe diameter", diameter),
             "the contact is longer than the pipe is wide, so the tube's ovalisation, not local "
             "indentation of a half-space, carries the load"),
            ("aspect_ratio", aspect > MAX_ASPECT_RATIO, ("major/minor semi-axis", aspect),
             ("largest aspect ratio", np.full(hl.shape, MAX_ASPECT_RATIO)),
             "the ellipse is degenerate: a line contact in all but name"),
        ]
    fails = line.copy()
    for _, bad, *_ in checks:
        fails |= bad
    if line.any():
        i = np.flatnonzero(line)[0]
        return Validity(~fails, "line_contact", (
            f"line_contact: A = {A.flat[i]:.4g} 1/m, half-length = {hl.flat[i]:.4g} m, half-width = "
            f"{hw.flat[i]:.4g} m; the contact is a line, not a finite ellipse, so Hertz's "
            "point-contact solution does not apply."))
    factors = {"length_vs_pipe_diameter": MAX_LENGTH_TO_DIAMETER, "aspect_ratio": 1.0}
    for name, bad, (vl, v), (rl, r), why in checks:
        if bad.any():
            i = np.flatnonzero(bad)[0]
            unit = "" if name == "aspect_ratio" else " m"
            return Validity(~fails, name, (f"{name}: {vl} {v.flat[i]:.4g}{unit} > {factors.get(name, limit):g} x "
                                           f"{rl} {r.flat[i]:.4g}{unit}; {why}."))
    return Validity(~fails, "ok", "ok: the contact is small beside the relative radii of curvature"
                    + (" and the span" if span_length is not None else "")
                    + (" and no longer than the pipe is wide" if pipe_diameter is not None else "") + ".")
