"""Whirl of a rotating pipe section in the hole: the drive, the wall friction and the closed forms.

Pure functions of numpy arrays, SI units. They are the pieces of the reference model
(``docs/reference_model.md``; :mod:`study.solvers.methods.reference`) that have a closed form, and the
closed forms the model is checked against:

- the rotating centrifugal load of a mass eccentricity ε of the pipe, m_p ε Ω² per unit length
  (Jeffcott's unbalance; Vance, *Rotordynamics of Turbomachinery*, Wiley 1988, ch. 2; Genta,
  *Dynamics of Rotating Systems*, Springer 2005, §4.2, doi:10.1007/0-387-28687-X);
- its projection on the pinned section's modes sin(nπx/L);
- the unbalance response of a damped Jeffcott rotor: amplitude and phase lag against speed, and the
  speed at which it first reaches a clearance;
- the sliding velocity of the pipe's surface on the wall and the regularised Coulomb friction it
  drives (the mechanism of backward whirl: Jansen, *Nonlinear rotor dynamics as applied to
  oilwell drillstring vibrations*, J. Sound Vib. 147 (1991) 115–135);
- the whirl rate of rolling without slip on the wall, −(r_contact/c) Ω (Bently & Muszynska's dry
  whip; Jansen 1991 §3).
"""

from __future__ import annotations

import functools

import numpy as np


@functools.lru_cache(maxsize=16)
def gauss_legendre(points: int) -> tuple[np.ndarray, np.ndarray]:
    """Nodes and weights of the Gauss–Legendre rule of ``points`` points on [−1, 1], over which the whirl models
    integrate the mud's drag along the section (numpy's ``leggauss``, about 1.5 ms; cached, read only: every
    point of a study asks for the same rule)."""
    nodes, weights = np.polynomial.legendre.leggauss(points)
    nodes.flags.writeable = False
    weights.flags.writeable = False
    return nodes, weights


def eccentric_load(pipe_mass, eccentricity, rotary_speed):
    """Amplitude of the rotating centrifugal load per unit length m_p ε Ω² [N/m].

    pipe_mass m_p [kg/m] (the steel: a mass eccentricity of the wall; the mud inside stays centred),
    eccentricity ε [m], rotary_speed Ω [rad/s]. The load points along the eccentricity, which turns
    with the pipe: (cos Ωt, sin Ωt) in the hole's (y, z) axes.
    """
    return np.asarray(pipe_mass) * np.asarray(eccentricity) * np.asarray(rotary_speed) ** 2


def turned_joint_share(turn, tension, bending_stiffness, spacing, terms=2000):
    """Quasi-static load on each tool joint of a long string lying on its joints, from a uniform load q per length on
    every pipe joint whose phase turns by ``turn`` from one pipe joint to the next, over the aligned share q s [-].

    The string is a continuous beam-column (EI y'''' − T y'' = q(x) − Σ R_j δ(x − j s)) on rigid supports at the
    joints, spacing s; the load on the j-th pipe joint is q e^{i j τ}, so the reactions are R_j = R e^{i j τ} (a Bloch
    wave). Its Fourier–Bloch series over the wavenumbers k_m = (τ + 2πm)/s, with D_m = EI k_m⁴ + T k_m² and the load's
    coefficients Q_m = q (1 − e^{−iτ})/(i k_m s), and the support condition y(0) = 0 give
    R = s Σ Q_m/D_m / Σ 1/D_m (the sums over |m| ≤ ``terms``: their tails fall as m⁻⁴). Aligned (τ = 0) every support
    carries q s; at T = 0 the series is Clapeyron's theorem of three moments for equal spans,
    |cos(τ/2)| (5 + cos τ)/(4 + 2 cos τ) (Timoshenko, *Strength of Materials* I, §47); as T s²/EI grows the spans act
    as strings and it tends to the two half spans' vector sum |1 + e^{iτ}|/2 = |cos(τ/2)|; at τ = 180° it is nil.
    turn τ [rad], tension T [N] (below the span's Euler load if negative), bending_stiffness EI [N m²], spacing s [m].
    """
    tau = np.remainder(np.asarray(turn, dtype=float), 2.0 * np.pi)
    m = np.arange(-int(terms), int(terms) + 1)
    k = (tau[..., None] + 2.0 * np.pi * m) / float(spacing)
    aligned = np.isclose(tau, 0.0, atol=1e-12) | np.isclose(tau, 2.0 * np.pi, atol=1e-12)
    k = np.where(aligned[..., None] & (m == 0), 1.0, k)  # the aligned case's k = 0 term is set apart below
    D = float(bending_stiffness) * k**4 + float(tension) * k**2
    Q = (1.0 - np.exp(-1j * tau[..., None])) / (1j * k * float(spacing))
    share = np.abs(np.sum(Q / D, axis=-1) / np.sum(1.0 / D, axis=-1))
    return np.where(aligned, 1.0, share)


def random_joint_share_rms(tension, bending_stiffness, spacing, samples=720):
    """Root mean square of :func:`turned_joint_share` over a string made up at random [-]: each pipe joint's
    eccentricity in an independent, uniformly distributed phase. The phases form white noise along the string, which
    drives every Bloch wave τ alike, so a joint's mean-square load is the mean of the squared share over τ ∈ [0, 2π)
    (Parseval; Rayleigh 1880's sum of vibrations of arbitrary phase), here by the midpoint rule on ``samples`` turns.
    Its limit for strings (T s²/EI → ∞) is the two half spans' E|1 + e^{iφ}|/2 = √2/2, the share of a 90° turn.
    tension T [N], bending_stiffness EI [N m²], spacing s [m]."""
    tau = (np.arange(int(samples)) + 0.5) * 2.0 * np.pi / int(samples)
    return float(np.sqrt(np.mean(turned_joint_share(tau, tension, bending_stiffness, spacing) ** 2)))


def lift_off_speed(rest_force, share, pipe_mass, eccentricity, spacing):
    """Rotary speed [rad/s] at which a tool joint's turning load, share · m_p ε Ω² s (:func:`turned_joint_share`),
    equals the force it rests on the wall with, F = w s + W_j sin θ (its share of the body's side load and its own
    weight's): the balance of forces Ω = √(F / (share m_p ε s)). Aligned (share 1) it is the whole string's, m_p ε Ω² L
    = w L + Σ W_j sin θ. Quasi-static: the spans' dynamics lift the joints sooner near their modes on the joints
    (docs/reference_model.md §7). rest_force F [N], share [-], pipe_mass m_p [kg/m], eccentricity ε [m], spacing s
    [m]."""
    return np.sqrt(np.asarray(rest_force, dtype=float)
                   / (np.asarray(share, dtype=float) * float(pipe_mass) * float(eccentricity) * float(spacing)))


def uniform_load_modal_factors(modes, span_length):
    """∫₀ᴸ sin(nπx/L) dx = L (1 − cos nπ)/(nπ) [m]: 2L/(nπ) for odd n, 0 for even n.

    The generalised force of a uniform load w [N/m] on mode n is w times this factor.
    """
    n = np.asarray(modes, dtype=float)
    return np.asarray(span_length, dtype=float) * (1.0 - np.cos(n * np.pi)) / (n * np.pi)


def jeffcott_response(frequency_ratio, damping_ratio):
    """Unbalance response of the damped Jeffcott rotor: (amplitude / ε, phase lag [rad]).

    |r| / ε = (Ω/ω)² / sqrt((1 − (Ω/ω)²)² + (2ζ Ω/ω)²), and the deflection lags the unbalance by
    φ = atan2(2ζ Ω/ω, 1 − (Ω/ω)²) ∈ [0, π): in phase below the critical speed, π/2 at it, opposite
    above (Vance 1988 eq. 2.11–2.12; Childs, *Turbomachinery Rotordynamics*, Wiley 1993, ch. 1;
    Genta 2005 §4.2). frequency_ratio Ω/ω [-], damping_ratio ζ [-].
    """
    r = np.asarray(frequency_ratio, dtype=float)
    z = np.asarray(damping_ratio, dtype=float)
    return r**2 / np.hypot(1.0 - r**2, 2.0 * z * r), np.arctan2(2.0 * z * r, 1.0 - r**2)


def speed_reaching_clearance(natural_frequency, damping_ratio, eccentricity, clearance):
    """Lowest rotary speed Ω [rad/s] at which the Jeffcott unbalance response reaches the clearance.

    Solves r⁴ = (c/ε)² ((1 − r²)² + 4ζ² r²) for the smallest r² = (Ω/ω)² > 0: with a = (c/ε)²,
    (a − 1) s² + (4ζ² − 2) a s + a = 0 in s = r². NaN when the response never reaches c (a small
    eccentricity and enough damping: the peak ≈ 1/(2ζ) stays below c/ε). natural_frequency ω
    [rad/s], damping_ratio ζ [-], eccentricity ε [m] (the mode's effective eccentricity), clearance c [m].
    """
    a = (np.asarray(clearance, dtype=float) / np.asarray(eccentricity, dtype=float)) ** 2
    z2 = np.asarray(damping_ratio, dtype=float) ** 2
    qa, qb, qc = a - 1.0, (4.0 * z2 - 2.0) * a, a
    disc = qb**2 - 4.0 * qa * qc
    with np.errstate(invalid="ignore", divide="ignore"):
        root = np.sqrt(disc)
        # the smaller positive root of the quadratic (stable form: 2c/(−b + sqrt(disc)))
        s = np.where(np.isclose(qa, 0.0), -qc / qb, 2.0 * qc / (-qb + root))
    s = np.where((disc >= 0) & (s > 0), s, np.nan)
    return np.asarray(natural_frequency, dtype=float) * np.sqrt(s)


def sliding_velocity(tangential_velocity, rotary_speed, contact_radius):
    """Sliding velocity of the pipe's surface on the wall, v_s = u̇·t̂ + Ω r_c [m/s].

    tangential_velocity u̇·t̂ [m/s]: the centre's velocity along t̂ = e_x × n̂ (n̂ the outward normal
    towards the wall, t̂ a quarter turn ahead of it in the sense of rotation); rotary_speed Ω [rad/s];
    contact_radius r_c [m] (pipe body or tool joint). Zero when the pipe rolls on the wall, which
    needs the centre to whirl backwards at −Ω r_c/c.
    """
    return np.asarray(tangential_velocity) + np.asarray(rotary_speed) * np.asarray(contact_radius)


def friction_factor(sliding, regularisation_velocity):
    """Regularised sign of the sliding velocity, v_s / sqrt(v_s² + v_ε²) [-].

    Coulomb's law F_t = −μ F_n sign(v_s), smoothed within |v_s| ≲ v_ε so that an explicit integrator
    can step through rolling (v_s = 0); it tends to sign(v_s) as v_ε → 0. sliding v_s [m/s],
    regularisation_velocity v_ε [m/s] > 0.
    """
    v = np.asarray(sliding, dtype=float)
    return v / np.sqrt(v**2 + np.asarray(regularisation_velocity, dtype=float) ** 2)


def rolling_whirl_ratio(contact_radius, clearance):
    """Whirl rate over rotary speed of rolling without slip on the wall, −r_c/c [-].

    contact_radius r_c [m] (the radius that touches: pipe body or tool joint), clearance c = R_hole − r_c
    [m]. 4½-in body in an 8¾-in hole: −2.25/2.125 = −1.059; 6¼-in tool joint: −3.125/1.25 = −2.5.
    """
    return -np.asarray(contact_radius, dtype=float) / np.asarray(clearance, dtype=float)


#: Standard gravity [m/s²].
GRAVITY = 9.80665


def side_load(pipe_mass, internal_mud, mud_density, outer_radius, inclination):
    """Side component of the buoyed weight per unit length in an inclined hole [N/m].

    (m_p + m_i − ρ_mud π r_o²) g sin θ: the pipe and the mud inside it, less the annular mud it
    displaces (Archimedes), towards the low side. pipe_mass m_p, internal_mud m_i [kg/m], mud_density
    [kg/m³], outer_radius r_o [m], inclination θ from vertical [rad].
    """
    buoyed = (np.asarray(pipe_mass) + np.asarray(internal_mud)
              - np.asarray(mud_density) * np.pi * np.asarray(outer_radius) ** 2)
    return buoyed * GRAVITY * np.sin(np.asarray(inclination, dtype=float))
