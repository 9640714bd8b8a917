"""Critical rotary speeds ("rpm to avoid") of a pinned span of drill pipe.

Pure functions of numpy arrays, SI units (lengths in m, rotary speeds in rad/s; rpm = 60 Ω/2π).

Two estimates, drawn side by side:

- **API RP 7G's rule of thumb** for the transverse vibration of one joint of drill pipe between
  its tool joints, "as a violin string" (API RP 7G, *Drill stem design and operating limits*, section
  on critical rotary speeds; also the HOMCO Technical Data Handbook, §9):
  rpm = 4 760 000 √(D² + d²)/L², with L the joint length and D, d the pipe's outer and inner
  diameters, all in inches; "probably accurate within 15 %", and rotary speeds within 15 % of it are
  to be avoided. The constant is the first mode of a bare, simply supported steel tube without axial
  load: with f₁ = (π/2L²)√(EI/m), I/A = (D² + d²)/16 and m = ρA, rpm = 60 f₁ =
  (15π/2)·√(E/ρ)·√(D² + d²)/L² (√(E/ρ) in in/s), and E = 30·10⁶ psi with ρ = 490 lb/ft³ gives
  4.762·10⁶.
- **The span's own natural frequencies** (:func:`study.physics.section.natural_frequencies`, the
  source paper's beam-column, eq. 1–4): ω_n² = [EI (nπ/L)⁴ + T_eff (nπ/L)²]/M with the effective
  tension and the mass of pipe, internal mud and annular added mass. The span whirls synchronously
  — an out-of-balance or bent pipe forces it once per revolution — so a critical rotary speed is
  where the rotation frequency equals a natural frequency: Ω = ω_n, rpm = 60 f_n. An excitation of
  order k (k forcing cycles per revolution, e.g. impacts against both walls) is critical at
  Ω = ω_n/k.

The rule of thumb has no tension and no mud: for a bare joint the two estimates agree to the
rounding of its constant; tension raises and mud lowers the span's critical speeds.
"""

from __future__ import annotations

import numpy as np

from study.physics.section import natural_frequencies

INCH = 0.0254  # m, exact
RPM = 2.0 * np.pi / 60.0  # rad/s per rpm

#: API RP 7G's constant of the rule of thumb [rpm·in] (rpm = constant·√(D² + d²)/L², inches).
API_RP7G_CONSTANT = 4_760_000.0
#: Stated accuracy of the rule of thumb, and the margin by which API RP 7G says to avoid it [-].
API_RP7G_ACCURACY = 0.15


def rp7g_critical_speed(joint_length, outer_diameter, inner_diameter):
    """API RP 7G's critical rotary speed of one joint of drill pipe [rad/s].

    joint_length L [m] (between tool joints), outer_diameter D [m], inner_diameter d [m]; evaluates
    rpm = 4 760 000 √(D² + d²)/L² with lengths in inches and returns it in rad/s.
    """
    d_out = np.asarray(outer_diameter, dtype=float) / INCH
    d_in = np.asarray(inner_diameter, dtype=float) / INCH
    length = np.asarray(joint_length, dtype=float) / INCH
    return API_RP7G_CONSTANT * np.sqrt(d_out**2 + d_in**2) / length**2 * RPM


def critical_rotary_speeds(span_length, bending_stiffness, tension, mass, modes=(1, 2, 3), order=1):
    """Rotary speeds Ω [rad/s] at which an excitation of ``order`` per revolution meets a mode.

    span_length L [m] of the pinned span, bending_stiffness EI [N m²], tension T_eff [N], mass M
    [kg/m] (pipe + internal mud + added mass), modes: mode numbers n, order k [-] (1: synchronous
    whirl). Ω = ω_n/k; the last axis runs over ``modes``; a buckled mode gives NaN.
    """
    omega = natural_frequencies(span_length, bending_stiffness, tension, mass, modes)
    return omega / float(order)


def avoid_band(critical_speed, margin=API_RP7G_ACCURACY):
    """Rotary speeds to avoid around a critical speed: (Ω (1 − margin), Ω (1 + margin)) [rad/s]."""
    speed = np.asarray(critical_speed, dtype=float)
    return speed * (1.0 - margin), speed * (1.0 + margin)
