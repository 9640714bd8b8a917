"""The well: side loads, doglegs and the string on its joints (docs/model.md §13).

Pure functions of numpy arrays (or floats), SI units. The hole frame: x along the hole, downwards; y towards
the low side of the hole; z = x × y. A positive rotary speed turns the pipe from +y towards +z (clockwise
seen from above, as a drill string turns).

- The side load per length on the pipe: the buoyed weight's side component w_b sin θ towards the low side,
  plus the tension's T κ towards the centre of curvature of a dogleg (the soft-string model of Johancsik,
  Friesen & Dawson 1984, "Torque and drag in directional wells — prediction and measurement", J. Pet.
  Technol. 36(6) 987–992, doi:10.2118/11380-PA).
- The pipe body between two tool joints resting on the wall: a continuous beam-column on equal supports,
  clamped at each joint by symmetry, under a uniform side load w and tension T: its support and mid-joint
  moments and its deflection in closed form (Timoshenko & Gere, *Theory of Elastic Stability*, 2nd ed.,
  McGraw-Hill 1961, ch. 1, the beam-column with built-in ends under uniform load; the tension case is the
  compression case with k → i k).
- The bending stress of a pipe that follows a dogleg, E r_o κ, and Lubinski's magnification near the tool
  joints under tension, σ = (E D κ/2) KL/tanh(KL) (Lubinski 1961, "Maximum permissible dog-legs in rotary
  boreholes", JPT 13(2) 175, doi:10.2118/1543-G-PA; used by API RP 7G).
- The whirl rate of a tool joint rolling without slip on the wall, −Ω R/c (Black 1968, "Interaction of a
  whirling rotor with a vibrating stator across a clearance annulus", J. Mech. Eng. Sci. 10, 1–12; Jansen 1991,
  "Non-linear rotor dynamics as applied to oilwell drillstring vibrations", J. Sound Vib. 147, 115–135).

The beam-column functions take a signed tension: in compression (T < 0) they are the same analytic
functions of z = T s²/(4 EI) (hyperbolic → trigonometric), valid below the clamped span's Euler load
(z > −π², |T| < 4π² EI/s²); at and beyond it they return nan (the span has buckled between its supports:
a status for the caller, not an exception). Near T = 0 they use their Taylor series in z, so T → 0 and
T = 0 give the classical clamped-beam figures without cancellation.
"""

from __future__ import annotations

import math

import numpy as np

from study.physics import whirl

#: Radians per metre of 1°/100 ft, the oilfield unit of dogleg severity.
DEG_PER_100FT = math.radians(1.0) / (100 * 0.3048)
#: The largest dogleg severity a config accepts [rad/m]: 30°/100 ft, a radius of curvature of 191 ft (58 m),
#: already a short-radius curve, sharper than a rotating string of drill pipe is run through.
MAX_DOGLEG_SEVERITY = 30.0 * DEG_PER_100FT
#: The named dogleg directions [rad]: the angle of the unit vector towards the centre of curvature, from +y
#: (the low side) towards +z. A drop curves the hole down (centre on the low side), a build up (centre on the
#: high side). Seen along the hole (x down-hole, y low side), z = x × y points to the driller's left, so a
#: walk to the right (azimuth increasing) has its centre at −z.
DOGLEG_DIRECTIONS = {
    "drop": 0.0,
    "build": math.pi,
    "walk_right": -math.pi / 2,
    "walk_left": math.pi / 2,
}

# Below |z| = _SERIES_LIMIT the functions of z use their Taylor series (radius of convergence π², so the terms
# fall by 1/π² ≈ 0.1 each: 24 terms reach 1e-24); at and above it the closed forms lose to cancellation at most
# 5e-15 of the span's largest deflection and 1.1e-15 of the moments (measured against the series at 1 <= |z| <= 2).
_SERIES_LIMIT = 1.0
_TERMS = 24
_COSH = np.array([1.0 / math.factorial(2 * m) for m in range(_TERMS + 2)])  # cosh u = Σ z^m/(2m)!
_SINHC = np.array([1.0 / math.factorial(2 * m + 1) for m in range(_TERMS + 2)])  # sinh u/u = Σ z^m/(2m+1)!


def _series_quotient(numerator, denominator, terms):
    """Coefficients of the power series numerator/denominator (denominator[0] = 1); numerator may carry trailing
    array axes (coefficients of several series at once)."""
    q = []
    for n in range(terms):
        value = numerator[n] - sum(denominator[m] * q[n - m] for m in range(1, n + 1))
        q.append(value)
    return q


#: u coth u = cosh u / (sinh u / u) and u / sinh u = 1 / (sinh u / u) as series in z = u².
_U_COTH_U = np.array(_series_quotient(_COSH, _SINHC, _TERMS + 1))
_U_CSCH_U = np.array(_series_quotient(np.eye(1, _TERMS + 2)[0], _SINHC, _TERMS + 1))


def _polyval(coefficients, z):
    """Σ coefficients[n] z^n by Horner's rule (coefficients along the first axis)."""
    result = np.zeros(np.broadcast_shapes(np.shape(z), np.shape(coefficients[0])))
    for c in coefficients[::-1]:
        result = result * z + c
    return result


def _buckled(z):
    return z <= -np.pi**2


def _series_part(z):
    """(|z| < _SERIES_LIMIT, z there and 0 elsewhere): the series are evaluated only where they are used."""
    small = np.abs(z) < _SERIES_LIMIT
    return small, np.where(small, z, 0.0)


def _u_coth_u(z):
    """u coth u with u = √z (v cot v with v = √−z for z < 0); 1 at z = 0, nan for z ≤ −π²."""
    z = np.asarray(z, dtype=float)
    small, z_small = _series_part(z)
    with np.errstate(all="ignore"):
        u = np.sqrt(np.abs(z))
        closed = np.where(z > 0, u / np.tanh(u), u / np.tan(u))
    result = np.where(small, _polyval(_U_COTH_U, z_small), closed)
    return np.where(_buckled(z), np.nan, result)


def _u_csch_u(z):
    """u / sinh u with u = √z (v / sin v for z < 0); 1 at z = 0, nan for z ≤ −π². No overflow for large u."""
    z = np.asarray(z, dtype=float)
    small, z_small = _series_part(z)
    with np.errstate(all="ignore"):
        u = np.sqrt(np.abs(z))
        closed = np.where(z > 0, 2.0 * u * np.exp(-u) / -np.expm1(-2.0 * u), u / np.sin(u))
    result = np.where(small, _polyval(_U_CSCH_U, z_small), closed)
    return np.where(_buckled(z), np.nan, result)


def _span_parameter(tension, bending_stiffness, spacing):
    """z = u² = (k s/2)² = T s²/(4 EI) [-], signed with the tension."""
    return np.asarray(tension, dtype=float) * np.asarray(spacing, dtype=float) ** 2 / (
        4.0 * np.asarray(bending_stiffness, dtype=float))


def dogleg_curvature(severity):
    """Curvature κ [1/m] of a hole of dogleg severity ``severity`` [rad/m] (already in SI: the identity).

    A dogleg severity is the change of the hole's direction per length, so in SI it is the curvature of the
    hole's axis: 3°/100 ft = 0.0017178 rad/m, a radius of 582 m. Raises ValueError for a negative or
    non-finite severity (the config refuses those before they get here).
    """
    kappa = np.asarray(severity, dtype=float)
    if not np.all(np.isfinite(kappa)) or np.any(kappa < 0):
        raise ValueError(f"dogleg severity {severity!r} rad/m: must be finite and >= 0")
    return kappa if kappa.ndim else float(kappa)


def buoyed_weight(pipe_mass, internal_mud_mass, mud_density, outer_radius):
    """Buoyed weight per length of a pipe full of mud, (m_p + m_i − ρ_mud π r_o²) g [N/m].

    pipe_mass m_p [kg/m], internal_mud_mass m_i [kg/m] (ρ_mud π r_i² for a pipe full of the same mud, which
    makes this (m_p − ρ_mud A_s) g), mud_density ρ_mud [kg/m³], outer_radius r_o [m]. The hole's side load at
    90° inclination, :func:`study.physics.whirl.side_load` (Archimedes: the annular mud displaced).
    """
    return whirl.side_load(pipe_mass, internal_mud_mass, mud_density, outer_radius, np.pi / 2)


def side_load_vector(buoyed_weight, inclination, tension, curvature, direction):
    """Side load per length on the pipe in the hole frame, (w_y, w_z) [N/m].

    The buoyed weight's side component w_b sin θ along +y (the low side) plus the tension's T κ towards the
    centre of curvature, (cos φ, sin φ) in (y, z): w_y = w_b sin θ + T κ cos φ, w_z = T κ sin φ. Its magnitude
    is the soft-string normal force per length of Johancsik, Friesen & Dawson (1984, doi:10.2118/11380-PA),
    √((T κ sin φ)² + (w_b sin θ + T κ cos φ)²).

    buoyed_weight w_b [N/m]; inclination θ from vertical [rad]; tension T [N] (negative: compression, which
    pushes the pipe away from the centre); curvature κ [1/m]; direction φ [rad] of the centre of curvature
    from +y towards +z (``DOGLEG_DIRECTIONS``: drop 0, build π, walk right −π/2, walk left π/2).
    """
    side = np.asarray(buoyed_weight, dtype=float) * np.sin(np.asarray(inclination, dtype=float))
    pull = np.asarray(tension, dtype=float) * np.asarray(curvature, dtype=float)
    phi = np.asarray(direction, dtype=float)
    return side + pull * np.cos(phi), pull * np.sin(phi)


def support_moment(w, tension, bending_stiffness, spacing):
    """Bending moment M = −EI y'' at the supports (tool joints) of the pipe body [N m].

    A continuous beam-column on equal supports ``spacing`` s apart, under a uniform side load w [N/m] (y along
    w) and tension T [N], bending stiffness EI [N m²]: by symmetry each span is clamped at its supports, and
    M'' − k² M = −w gives M = (w/k²)(1 − u/tanh u), k = √(T/EI), u = k s/2 — negative (hogging) for w > 0,
    tending to the clamped beam's −w s²/12 as T → 0 (Timoshenko & Gere 1961, ch. 1). Large tension: → −w s/(2k)
    (the boundary layer of a taut string). nan at and beyond the span's Euler load in compression.
    """
    z = _span_parameter(tension, bending_stiffness, spacing)
    small, z_small = _series_part(z)
    with np.errstate(all="ignore"):
        ratio = np.where(small, _polyval(3.0 * _U_COTH_U[1:], z_small), 3.0 * (_u_coth_u(z) - 1.0) / z)
    return -np.asarray(w, dtype=float) * np.asarray(spacing, dtype=float) ** 2 / 12.0 * ratio


def midspan_moment(w, tension, bending_stiffness, spacing):
    """Bending moment M = −EI y'' at mid-joint [N m], of the span of :func:`support_moment`.

    M = (w/k²)(1 − u/sinh u), k = √(T/EI), u = k s/2: w s²/24 as T → 0 (the clamped beam), w/k² = w EI/T as
    T → ∞ (the span is straight there, the moment that of the boundary layers' tail).
    """
    z = _span_parameter(tension, bending_stiffness, spacing)
    small, z_small = _series_part(z)
    with np.errstate(all="ignore"):
        ratio = np.where(small, _polyval(-6.0 * _U_CSCH_U[1:], z_small), 6.0 * (1.0 - _u_csch_u(z)) / z)
    return np.asarray(w, dtype=float) * np.asarray(spacing, dtype=float) ** 2 / 24.0 * ratio


def beam_column_deflection(x, w, tension, bending_stiffness, spacing):
    """Deflection y(x) [m] of the clamped–clamped beam-column span of :func:`support_moment`, along w.

    EI y'''' − T y'' = w with y = y' = 0 at x = 0 and x = s. With ξ = x − s/2, k = √(T/EI), u = k s/2:

        y = (w/T) [x (s − x)/2 − u (cosh u − cosh kξ) / (k² sinh u)]

    which tends to w x² (s − x)²/(24 EI) as T → 0 (taken by its series in T, no cancellation) and, for
    large T, to the taut string's w x (s − x)/(2T) less the clamped ends' boundary layers. x [m] in
    [0, s] (nan outside), w [N/m], T [N], EI [N m²], s [m]. Its cancellation for T ≠ 0 costs at most about
    5e-15 of the span's largest deflection.
    """
    s = np.asarray(spacing, dtype=float)
    eta = 2.0 * np.asarray(x, dtype=float) / s - 1.0
    z = _span_parameter(tension, bending_stiffness, spacing)
    z, eta = np.broadcast_arrays(z, eta)
    outside = np.abs(eta) > 1.0
    eta = np.clip(eta, -1.0, 1.0)
    one_minus = 1.0 - eta**2
    small, z_small = _series_part(z)
    series = 0.0
    if np.any(small):
        # F = ((1 − η²)/2 − N/S)/z = −Σ_{n≥1} q_n z^{n−1}, q the series of N/S,
        # N = Σ_{n≥1} (1 − η^{2n}) z^{n−1}/(2n)!, S = sinh u/u
        numerator = [(1.0 - eta ** (2 * n)) / math.factorial(2 * n) for n in range(1, _TERMS + 3)]
        quotient = _series_quotient(numerator, _SINHC, _TERMS + 1)
        series = -_polyval(np.array(quotient[1:]), z_small)
    with np.errstate(all="ignore"):
        u = np.sqrt(np.abs(z))
        a, b = u * (1.0 + eta) / 2.0, u * (1.0 - eta) / 2.0  # a + b = u
        # (cosh u − cosh uη)/(u sinh u) = 2 sinh a sinh b/(u sinh u) for z > 0, without cancellation or overflow;
        # (cos v − cos vη)/(−v sin v) = 2 sin a sin b/(v sin v) for z < 0.
        hyper = np.expm1(-2.0 * a) * np.expm1(-2.0 * b) / (-u * np.expm1(-2.0 * u))
        trig = 2.0 * np.sin(a) * np.sin(b) / (u * np.sin(u))
        closed = (one_minus / 2.0 - np.where(z > 0, hyper, trig)) / z
    shape = np.where(small, series, closed)
    shape = np.where(_buckled(z) | outside, np.nan, shape)
    return np.asarray(w, dtype=float) * s**4 / (16.0 * np.asarray(bending_stiffness, dtype=float)) * shape


def curvature_bending_stress(youngs_modulus, outer_radius, curvature):
    """Bending stress at the outer fibre of a pipe bent to the hole's curvature, E r_o κ [Pa].

    youngs_modulus E [Pa], outer_radius r_o [m], curvature κ [1/m]. A turning pipe's fibre goes from +E r_o κ
    to −E r_o κ once a revolution: this is the amplitude of the alternating stress in a dogleg away from the
    tool joints (Lubinski 1961, the case KL → 0).
    """
    return np.asarray(youngs_modulus, dtype=float) * np.asarray(outer_radius, dtype=float) * np.asarray(
        curvature, dtype=float)


def lubinski_bending_stress(youngs_modulus, outer_diameter, curvature, tension, bending_stiffness, half_spacing):
    """Maximum bending stress of a pipe in tension through a dogleg, at its tool joints [Pa].

    σ = (E D κ/2) · KL/tanh(KL), K = √(T/EI), L half the tool-joint spacing (Lubinski 1961,
    doi:10.2118/1543-G-PA; API RP 7G's dogleg figures). The body between the joints is straightened by the
    tension and the joints take the bend: E D κ/2 as T → 0 (the pipe follows the curve), ≈ (E D κ/2) KL for
    KL ≳ 3. Lubinski's analysis assumes the body does not touch the wall between the joints.

    youngs_modulus E [Pa], outer_diameter D [m], curvature κ [1/m], tension T [N], bending_stiffness EI
    [N m²], half_spacing L [m]. nan for T < 0: the formula is for tension; in compression the body bows off
    the curve towards the wall, a case it does not cover.
    """
    T = np.asarray(tension, dtype=float)
    with np.errstate(invalid="ignore"):
        z = T * np.asarray(half_spacing, dtype=float) ** 2 / np.asarray(bending_stiffness, dtype=float)
    factor = np.where(T < 0, np.nan, _u_coth_u(np.maximum(z, 0.0)))
    return 0.5 * np.asarray(youngs_modulus, dtype=float) * np.asarray(outer_diameter, dtype=float) * np.asarray(
        curvature, dtype=float) * factor


def rolling_whirl_rate(rotary_speed, radius, clearance):
    """Whirl rate of a tool joint rolling without slip on the wall, −Ω R/c [rad/s].

    rotary_speed Ω [rad/s], radius R [m] of the joint that touches, clearance c = R_hole − R [m]. The rolling
    condition (no slip at the contact: the contact point's velocities of pipe and whirl cancel) makes the
    centre whirl backwards (Black 1968; Jansen 1991: the module's references);
    :func:`study.physics.whirl.rolling_whirl_ratio` times Ω.
    """
    return np.asarray(rotary_speed, dtype=float) * whirl.rolling_whirl_ratio(radius, clearance)


def tool_joint_excess(steel_density, joint_outer_diameter, joint_inner_diameter, joint_length, pipe_mass,
                      pipe_outer_diameter, pipe_inner_diameter, mud_density):
    """The mass [kg] and the buoyed weight [N] a tool joint adds to the string beyond the plain pipe's, as a point
    at the joint (docs/reference_model.md §9).

    A joint of outer diameter D_tj, bore d_tj and length ℓ (box and pin) replaces ℓ of plain pipe, whose mass per
    length m_p (the plain-end weight, API Spec 5DP) the string's mass per length already counts:
    m_j = ρ_s π/4 (D_tj² − d_tj²) ℓ − m_p ℓ + ρ_mud π/4 (d_tj² − d²) ℓ (its steel beyond the plain pipe's, and the
    mud inside its bore beyond the pipe's, which moves with it); the buoyed weight of that excess, Archimedes' on
    the annular mud it displaces beyond the body's, W_j = (m_j − ρ_mud π/4 (D_tj² − D²) ℓ) g (the pipe's own, as
    :func:`buoyed_weight`). The mud's added mass outside the joint is not in it (a half-metre joint lets the mud
    flow round its ends, which the plane added-mass formula does not).

    steel_density ρ_s [kg/m³]; joint_outer_diameter D_tj, joint_inner_diameter d_tj, joint_length ℓ [m]; pipe_mass
    m_p [kg/m]; pipe_outer_diameter D, pipe_inner_diameter d [m]; mud_density ρ_mud [kg/m³]. ℓ = 0 gives (0, 0).
    """
    length = np.asarray(joint_length, dtype=float)
    quarter = 0.25 * np.pi * length
    D_tj, d_tj = np.asarray(joint_outer_diameter, dtype=float), np.asarray(joint_inner_diameter, dtype=float)
    D, d, rho = (np.asarray(pipe_outer_diameter, dtype=float), np.asarray(pipe_inner_diameter, dtype=float),
                 np.asarray(mud_density, dtype=float))
    mass = (np.asarray(steel_density, dtype=float) * quarter * (D_tj**2 - d_tj**2)
            - np.asarray(pipe_mass, dtype=float) * length + rho * quarter * (d_tj**2 - d**2))
    weight = (mass - rho * quarter * (D_tj**2 - D**2)) * whirl.GRAVITY
    return (mass if mass.ndim else float(mass)), (weight if weight.ndim else float(weight))
