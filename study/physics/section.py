"""Pipe section, drilling-mud and beam-column properties of the sample span.

Pure functions of numpy arrays (broadcasting), SI units throughout. The equations
are those of the source paper (``docs/model.md`` §2; paper eq. 1–4, 26–35) with
the reconstructions written there.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import brentq

#: Added-mass models for the annular mud: name -> one-line description.
ADDED_MASS_MODELS = {
    "potential_flow": "inviscid potential flow about a cylinder in a concentric confining cylinder "
    "(Chen, Wambsganss & Jendrzejczyk 1976): rho*pi*r_o^2*(R^2+r_o^2)/(R^2-r_o^2)",
    "gap_flow": "the source paper's estimate (eq. 31): annular mud accelerated at the gap velocity, "
    "rho*pi*(R^2-r_o^2)*r_o/S with S = R - r_o",
}


def second_moment_of_area(outer_radius, inner_radius):
    """Second moment of area of a tube, I = π (r_o⁴ − r_i⁴)/4 [m⁴].

    outer_radius, inner_radius : [m]
    """
    return np.pi * (np.asarray(outer_radius) ** 4 - np.asarray(inner_radius) ** 4) / 4.0


def steel_area(outer_radius, inner_radius):
    """Cross-section area of the tube wall, A_s = π (r_o² − r_i²) [m²]."""
    return np.pi * (np.asarray(outer_radius) ** 2 - np.asarray(inner_radius) ** 2)


def bending_stiffness(youngs_modulus, outer_radius, inner_radius):
    """Bending stiffness EI [N m²] of the pipe: youngs_modulus [Pa], radii [m]."""
    return np.asarray(youngs_modulus) * second_moment_of_area(outer_radius, inner_radius)


def internal_mud_mass(mud_density, inner_radius):
    """Mass of mud inside unit length of pipe, m_i = ρ_mud π r_i² [kg/m] (paper eq. 4).

    mud_density [kg/m³], inner_radius [m].
    """
    return np.asarray(mud_density) * np.pi * np.asarray(inner_radius) ** 2


def mean_gap(outer_radius, hole_radius):
    """Mean width of the annular gap on either side of the pipe, S = R_hole − r_o [m] (paper eq. 27)."""
    return np.asarray(hole_radius) - np.asarray(outer_radius)


def added_mass(mud_density, outer_radius, hole_radius, model="potential_flow"):
    """Virtual (added) mass of the annular mud per unit length [kg/m].

    mud_density [kg/m³], outer_radius r_o [m], hole_radius R [m]; ``model`` one of
    :data:`ADDED_MASS_MODELS`:

    - ``"potential_flow"`` (default): the classical inviscid result for a cylinder moving in a
      concentric rigid cylinder, m_a = ρ π r_o² (R² + r_o²)/(R² − r_o²). It is exact for small
      motions of an ideal fluid and reduces to the unbounded-fluid value ρ π r_o² as R → ∞, which is
      why it is the default.
    - ``"gap_flow"``: the paper's estimate (eq. 31, docs/model.md §2): the pipe at V_p drives the annular
      mud through the two side gaps at V_f = V_p r_o/S; taking that acceleration for all the
      annular mud gives m_a = ρ π (R² − r_o²) r_o/S = ρ π r_o (R + r_o). It does not tend to
      ρ π r_o² for a wide hole; it exceeds the potential-flow value when R/r_o is above 1.521 (the
      real root of x³ − x − 2 = 0) and falls below it in narrower annuli, where potential flow
      grows without bound as the gap closes.
    """
    rho = np.asarray(mud_density, dtype=float)
    r_o = np.asarray(outer_radius, dtype=float)
    big_r = np.asarray(hole_radius, dtype=float)
    if model == "potential_flow":
        return rho * np.pi * r_o**2 * (big_r**2 + r_o**2) / (big_r**2 - r_o**2)
    if model == "gap_flow":
        return rho * np.pi * (big_r**2 - r_o**2) * r_o / mean_gap(r_o, big_r)
    raise ValueError(f"added_mass model = {model!r}; allowed: {', '.join(ADDED_MASS_MODELS)}")


def drag_coefficient_per_length(mud_density, outer_radius, hole_radius, drag_coefficient=0.5):
    """Quadratic drag coefficient D [kg/m²] of the term D |ẏ| ẏ (force per unit length).

    Paper eq. 26–30 as read in docs/model.md §2: the relative velocity of the gap flow to the pipe is
    V_p (1 + r_o/S), and drag on a cylinder of diameter 2 r_o in that stream gives
    D = ½ ρ C_d (2 r_o) (1 + r_o/S)². mud_density [kg/m³], radii [m], drag_coefficient C_d [-]
    (paper: 0.5 for the highly turbulent annular flow).
    """
    r_o = np.asarray(outer_radius, dtype=float)
    ratio = 1.0 + r_o / mean_gap(r_o, hole_radius)
    return 0.5 * np.asarray(mud_density) * np.asarray(drag_coefficient) * 2.0 * r_o * ratio**2


def mass_per_length(pipe_mass, internal_mud, added):
    """Total vibrating mass per unit length M = m_p + m_i + m_a [kg/m] (paper eq. 4, 31)."""
    return np.asarray(pipe_mass) + np.asarray(internal_mud) + np.asarray(added)


def effective_tension(axial_tension, internal_mud, mud_flow_velocity):
    """Effective tension T_eff = T0 − m_i V_m² [N] (paper eq. 1–3, A1 of eq. 34).

    axial_tension T0 [N], internal_mud m_i [kg/m], mud_flow_velocity V_m [m/s]: the mud
    flowing through the curved pipe pushes outwards like a compressive force m_i V_m².
    """
    return np.asarray(axial_tension) - np.asarray(internal_mud) * np.asarray(mud_flow_velocity) ** 2


def natural_frequencies(span_length, bending_stiffness, tension, mass, modes=(1,)):
    """Natural circular frequencies ω_n [rad/s] of a simply supported beam-column.

    ω_n² = [EI (nπ/L)⁴ + T_eff (nπ/L)²]/M (docs/model.md §2). span_length L [m], bending_stiffness EI
    [N m²], tension T_eff [N], mass M [kg/m], modes: mode numbers n. The last axis of the result
    runs over ``modes``. A mode whose ω² ≤ 0 has buckled: its frequency is returned as NaN (see
    :func:`is_buckled`).
    """
    n = np.asarray(modes, dtype=float)
    k = n * np.pi / np.asarray(span_length, dtype=float)[..., None]
    omega_sq = (np.asarray(bending_stiffness)[..., None] * k**4 + np.asarray(tension)[..., None] * k**2) / np.asarray(
        mass
    )[..., None]
    with np.errstate(invalid="ignore"):
        return np.where(omega_sq > 0.0, np.sqrt(np.where(omega_sq > 0.0, omega_sq, 0.0)), np.nan)


def euler_buckling_tension(span_length, bending_stiffness):
    """Effective tension at which a simply supported span buckles, T_cr = −EI (π/L)² [N] (< 0)."""
    return -np.asarray(bending_stiffness) * (np.pi / np.asarray(span_length)) ** 2


def buckling_length(bending_stiffness, tension):
    """Shortest simply supported span that buckles under effective tension T_eff < 0 [m].

    L_cr = π sqrt(EI/|T_eff|); infinite when T_eff ≥ 0 (a span in tension never buckles).
    """
    t = np.asarray(tension, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(t < 0.0, np.pi * np.sqrt(np.asarray(bending_stiffness) / np.abs(t)), np.inf)


def is_buckled(span_length, bending_stiffness, tension):
    """True where the span's first mode has ω₁² ≤ 0, i.e. T_eff ≤ −EI (π/L)²."""
    return np.asarray(tension) <= euler_buckling_tension(span_length, bending_stiffness)


def equivalent_mass(mass, span_length):
    """Mass of the equivalent sphere moving with midspan, m_e = 2 M L/π [kg] (paper eq. 5).

    Equating the momentum of the span moving in the shape sin(πx/L) with that of a mass moving
    at the midspan velocity. mass M [kg/m], span_length L [m].
    """
    return 2.0 * np.asarray(mass) * np.asarray(span_length) / np.pi


def cowper_shear_coefficient(poisson_ratio, outer_radius, inner_radius):
    """Timoshenko's shear coefficient κ [-] of a hollow circular section (Cowper 1966, J. Appl. Mech. 33, 335,
    doi:10.1115/1.3625046, Table 1): κ = 6(1 + ν)(1 + m²)² / [(7 + 6ν)(1 + m²)² + (20 + 12ν) m²], m = r_i/r_o;
    6(1 + ν)/(7 + 6ν) for the solid section (m = 0), 2(1 + ν)/(4 + 3ν) for the thin tube (m → 1).
    poisson_ratio ν [-], radii [m]."""
    nu = np.asarray(poisson_ratio, dtype=float)
    m2 = (np.asarray(inner_radius, dtype=float) / np.asarray(outer_radius, dtype=float)) ** 2
    return 6.0 * (1.0 + nu) * (1.0 + m2) ** 2 / ((7.0 + 6.0 * nu) * (1.0 + m2) ** 2 + (20.0 + 12.0 * nu) * m2)


def euler_bernoulli_frequency(wavenumber, bending_stiffness, mass, tension=0.0):
    """ω [rad/s] of the Euler–Bernoulli beam-column's bending wave of wavenumber k [1/m]:
    ω² = (EI k⁴ + T k²)/M (docs/model.md §2). bending_stiffness EI [N m²], mass M [kg/m], tension T [N]."""
    k = np.asarray(wavenumber, dtype=float)
    return np.sqrt((np.asarray(bending_stiffness) * k**4 + np.asarray(tension) * k**2) / np.asarray(mass))


def timoshenko_frequencies(wavenumber, bending_stiffness, shear_stiffness, mass, rotary_inertia, tension=0.0):
    """(lower, upper) ω [rad/s] of Timoshenko's beam for the wavenumber k [1/m] (Graff 1975, Wave Motion in Elastic
    Solids, §3.4): the two roots in ω² of the determinant of its equations for w = W e^{i(kx − ωt)},
    ψ = Ψ e^{i(kx − ωt)},

        | κGA k² + T k² − M ω²    i κGA k                 |
        | −i κGA k                EI k² + κGA − ρI ω²      | = 0,

    i.e. M ρI ω⁴ − [ρI (κGA + T) k² + M (EI k² + κGA)] ω² + (κGA + T) EI k⁴ + T κGA k² = 0. The lower root is the
    bending branch, which tends to Euler–Bernoulli's (EI k⁴ + T k²)/M as k → 0 (:func:`euler_bernoulli_frequency`); the
    upper starts at the cut-off √(κGA/ρI). bending_stiffness EI [N m²], shear_stiffness κGA [N] (κ:
    :func:`cowper_shear_coefficient`), mass M [kg/m] (the section's whole, mud and added mass with it), rotary_inertia
    ρI [kg m] (the steel's: ρ_s I; 0: the shear beam, its upper branch inf), tension T [N]."""
    k2 = np.asarray(wavenumber, dtype=float) ** 2
    ei, ks, m, j, t = (np.asarray(v, dtype=float) for v in (bending_stiffness, shear_stiffness, mass, rotary_inertia,
                                                             tension))
    a = m * j
    b = j * (ks + t) * k2 + m * (ei * k2 + ks)
    c = (ks + t) * ei * k2**2 + t * ks * k2
    root = np.sqrt(b * b - 4.0 * a * c)
    lower = 2.0 * c / (b + root)  # the smaller root without cancellation
    with np.errstate(divide="ignore"):  # no rotary inertia: no upper branch (inf)
        upper = np.sqrt((b + root) / (2.0 * a))
    return np.sqrt(lower), upper


def timoshenko_band_edge(fraction, bending_stiffness, shear_stiffness, mass, rotary_inertia, tension=0.0) -> float:
    """The Euler–Bernoulli frequency ω_b [rad/s] at which Timoshenko's bending branch (:func:`timoshenko_frequencies`)
    lies ``fraction`` [-] below it, 1 − ω_T/ω_EB = fraction (the ratio falls monotonically with k, from 1 at k = 0): the
    upper edge of the band where the Euler–Bernoulli beam holds within that fraction (docs/reference_model.md §2.3.1).
    To first order in k², 1 − ω_T/ω_EB ≈ (k r)²/2 (E/κG + ρ_s A_s/M), r² = I/A_s. Arguments as
    :func:`timoshenko_frequencies`."""
    fraction = float(fraction)
    if not 0.0 < fraction < 1.0:
        raise ValueError(f"fraction = {fraction}: must lie in (0, 1)")
    args = (bending_stiffness, shear_stiffness, mass, rotary_inertia, tension)

    def gap(log_k):
        k = np.exp(log_k)
        return 1.0 - float(timoshenko_frequencies(k, *args)[0] / euler_bernoulli_frequency(
            k, bending_stiffness, mass, tension)) - fraction

    # the first-order estimate's k, then a bracket about it: the gap grows from −fraction at k → 0 towards 1 − fraction
    first = np.sqrt(2.0 * fraction / (bending_stiffness / shear_stiffness + rotary_inertia / mass))
    low, high = np.log(first) - 1.0, np.log(first) + 1.0
    while gap(low) > 0.0:
        low -= 1.0
    while gap(high) < 0.0:
        high += 1.0
    k = float(np.exp(brentq(gap, low, high, xtol=1e-14, rtol=1e-14)))
    return float(euler_bernoulli_frequency(k, bending_stiffness, mass, tension))
