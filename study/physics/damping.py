"""The mud's drag linearised and the end moments that keep the damped motion periodic (docs/model.md §7).

The source paper's appendix A keeps the drag D|ẏ|ẏ of the annular mud. It replaces it by a uniform viscous
term c ẏ that dissipates the same energy over the span and the period (paper eq. A3–A4), and feeds that
energy back through moments M(t) applied at both ends of the span, chosen so that the response is in phase
with the impact force (eq. A14). Appendix B shows for one degree of freedom that a second force which removes
the phase lag between the response and the first force does exactly the work the damping dissipates.

The building blocks here, for the beam-column EI y'''' − T y'' + M ÿ + c ẏ = p(x, t) on 0 ≤ x ≤ L, simply
supported, with the symmetric end moment −EI y''(0, t) = −EI y''(L, t) = M_e(t):

- :func:`equivalent_damping`, :func:`harmonic_equivalent_damping`: c from equal dissipation;
- :func:`end_moment_static`, :func:`end_moment_modal_factors`: the static shape under unit end moments and
  its modal forcing;
- :func:`modal_transfer`, :func:`in_phase_moments`, :func:`compensated_amplitudes`: per harmonic of the
  motion, the modal response and the end moment in quadrature with the load that brings the response the
  load works on back in phase with it (appendix B's construction, extended to the span as the paper says).

Pure functions of numpy arrays, SI units, no I/O.
"""

from __future__ import annotations

import numpy as np

#: ∫₀^{2π} |cos θ|³ dθ / ∫₀^{2π} cos² θ dθ = (8/3)/π: the ratio that turns D ω Y into c_eq for harmonic motion.
HARMONIC_FACTOR = 8.0 / (3.0 * np.pi)


def equivalent_damping(drag, velocity, weights=None) -> float:
    """Uniform viscous coefficient c [N s/m²] dissipating what the quadratic drag does (paper eq. A3–A4).

    Equal dissipation over the span and the period: ∫∫ D|ẏ|ẏ · ẏ dx dt = ∫∫ c ẏ · ẏ dx dt, so

        c = D ∫∫ |ẏ|³ dx dt / ∫∫ ẏ² dx dt.

    drag D [kg/m²] (drag force per length D ẏ²); velocity ẏ [m/s] sampled on a grid over the span and the
    period (any shape); weights: quadrature weights of the grid broadcastable to ``velocity`` (default:
    uniform). 0 where the pipe does not move. For harmonic motion of amplitude Y this is
    :func:`harmonic_equivalent_damping`.
    """
    v = np.asarray(velocity, dtype=float)
    w = np.ones_like(v) if weights is None else np.broadcast_to(np.asarray(weights, dtype=float), v.shape)
    power = float(np.sum(w * v**2))
    return 0.0 if power == 0.0 else float(drag) * float(np.sum(w * np.abs(v) ** 3)) / power


def harmonic_equivalent_damping(drag, frequency, amplitude):
    """c_eq = 8 D ω Y/(3π) [N s/m²]: equal dissipation per cycle of y = Y sin ωt (docs/model.md eq. 7.1).

    drag D [kg/m²], frequency ω [rad/s], amplitude Y [m]."""
    return HARMONIC_FACTOR * np.asarray(drag, dtype=float) * np.asarray(frequency, dtype=float) \
        * np.asarray(amplitude, dtype=float)


def end_moment_static(x, span_length, bending_stiffness, tension):
    """Static deflection s [m/(N m)], bending moment m_s = −EI s'' [-] and slope s' [1/(N m)] of the span
    under a unit sagging moment at both ends (−EI y'' = 1 at x = 0 and x = L, y = 0 there).

    EI s'''' − T s'' = 0 gives m_s'' = (T/EI) m_s, so with k² = T/EI (tension T > 0)

        m_s = cosh(k(x − L/2))/cosh(kL/2),   s = (1 − m_s)/T,

    cos for compression (k² < 0) and s = x(L − x)/(2EI), m_s = 1 without axial load. x [m], span_length L
    [m], bending_stiffness EI [N m²], tension T [N] (above buckling)."""
    x = np.asarray(x, dtype=float)
    L, ei, tn = float(span_length), float(bending_stiffness), float(tension)
    xi = x - 0.5 * L
    lam = 0.5 * L * np.sqrt(abs(tn) / ei)  # k L/2
    if lam < 1e-4:  # no axial load to this order: the parabola (relative error ~ λ²/12)
        return x * (L - x) / (2.0 * ei), np.ones_like(x), (0.5 * L - x) / ei
    k = 2.0 * lam / L
    if tn > 0:
        moment = np.cosh(k * xi) / np.cosh(lam)
        slope_m = k * np.sinh(k * xi) / np.cosh(lam)
    else:
        moment = np.cos(k * xi) / np.cos(lam)
        slope_m = -k * np.sin(k * xi) / np.cos(lam)
    return (1.0 - moment) / tn, moment, -slope_m / tn


def end_moment_modal_factors(modes, span_length, mass):
    """e_n = 4 k_n/(M L) [1/(kg m)]: the modal forcing of mode sin(k_n x) per unit end moment per unit modal
    mass (the moments at both ends work on the end slopes, 2 k_n for odd n, over the modal mass M L/2).

    Equal to s_n ω_n², s_n the sine coefficient of :func:`end_moment_static` (integration by parts of
    EI s'''' − T s'' = 0 against sin k_n x). modes: odd n; span_length L [m]; mass M [kg/m]."""
    k = np.asarray(modes, dtype=float) * np.pi / float(span_length)
    return 4.0 * k / (float(mass) * float(span_length))


def modal_transfer(natural_frequency, forcing_frequency, damping_rate):
    """H = 1/(ω_n² − ω² + i ω c/M) [s²] per unit modal force per unit modal mass (complex).

    natural_frequency ω_n [rad/s], forcing_frequency ω [rad/s], damping_rate c/M [1/s]; broadcast."""
    om_n = np.asarray(natural_frequency, dtype=float)
    om = np.asarray(forcing_frequency, dtype=float)
    return 1.0 / (om_n**2 - om**2 + 1j * om * np.asarray(damping_rate, dtype=float))


def in_phase_moments(load_factors, moment_factors, transfer, work_weights):
    """μ_m [N m per unit load] of the end moment M_m = i μ_m F_m in quadrature with each harmonic F_m of the
    load, so that the displacement the load works on, U_m = Σ_n g_n q_nm, is in phase with F_m.

    With q_nm = (a_n + i μ_m e_n) H_nm F_m (a_n the load's modal forcing, e_n the moment's, H the modal
    transfer, :func:`modal_transfer`) and U_m/F_m = S_a + i μ_m S_e, S_a = Σ g a H, S_e = Σ g e H, the phase
    vanishes when Im S_a + μ_m Re S_e = 0:

        μ_m = −Im S_a / Re S_e                      (paper eq. A14–A15; appendix B's F₂₀/F₁₀ for one mode)

    load_factors a_n, moment_factors e_n, work_weights g_n: shape (modes,); transfer: (harmonics, modes).
    0 where the load's response is already in phase (no damping); ±inf or NaN where the end moments cannot
    move the in-phase part (Re S_e = 0)."""
    h = np.asarray(transfer, dtype=complex)
    g = np.asarray(work_weights, dtype=float)
    # summed elementwise: a BLAS complex matrix-vector product of this size costs more in thread wake-ups
    s_a = (h * (g * np.asarray(load_factors, dtype=float))).sum(axis=-1)
    s_e = (h * (g * np.asarray(moment_factors, dtype=float))).sum(axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(s_a.imag == 0.0, 0.0, -s_a.imag / s_e.real)


def compensated_amplitudes(load_factors, moment_factors, transfer, moments):
    """Modal amplitudes q_nm = (a_n + i μ_m e_n) H_nm per unit load harmonic (complex, harmonics × modes):
    the response to the load and the in-phase end moments of :func:`in_phase_moments` (``moments`` μ_m)."""
    a = np.asarray(load_factors, dtype=float)[None, :]
    e = np.asarray(moment_factors, dtype=float)[None, :]
    return (a + 1j * np.asarray(moments, dtype=float)[:, None] * e) * np.asarray(transfer)


def oscillating_cylinder_force_coefficients(radius, frequency, kinematic_viscosity, outer_radius=None):
    """Added-mass and damping coefficients of a cylinder oscillating across its axis in a viscous fluid, per length.

    A cylinder of radius a moving with velocity U e^{iωt} in a fluid of density ρ and kinematic viscosity ν (the
    linearised, unsteady Stokes equations) feels per length F = −(iω C_m ρπa² + C_c ρπa² ω) U, returned as
    (C_m, C_c) [-]: the added mass is C_m ρπa² [kg/m], the damping c = C_c ρπa²ω [N s/m²].

    - Unbounded fluid (``outer_radius`` None): Stokes (1851, "On the effect of the internal friction of fluids on
      the motion of pendulums", Trans. Camb. Phil. Soc. 9, 8; Landau & Lifshitz, Fluid Mechanics §24, problem 5):
      C_m − i C_c = 1 + 4 K₁(s)/(s K₀(s)), s = a √(iω/ν). For large |s|, C_m → 1 (potential flow) and
      c → 2√2 πρa √(ων) (the Stokes layer), with relative corrections O(1/|s|).
    - Fluid confined by a fixed concentric cylinder of radius b (the annulus): the same equations with no slip on
      both walls (Chen, Wambsganss & Jendrzejczyk 1976, "Added mass and damping of a vibrating rod in confined
      viscous fluids", J. Appl. Mech. 43(2) 325–329). The stream function ψ = F(r) sin θ,
      F = A r + B/r + C I₁(kr) + D K₁(kr), k = √(iω/ν), takes F(a) = a, F'(a) = 1, F(b) = F'(b) = 0 (unit
      velocity), solved here as its 4 × 4 system (the Bessel functions scaled so that it stays well conditioned at
      large |k|b); the wall's force is πa[iωρ(Aa − B/a) + μF''(a)] (pressure −iωρ(Ar − B/r) cos θ of the potential
      part; the normal viscous stress vanishes on the rigid wall). Its inviscid limit is the potential-flow
      C_m = (b² + a²)/(b² − a²).

    radius a [m], frequency ω [rad/s] (> 0), kinematic_viscosity ν [m²/s] (> 0), outer_radius b [m] (> a) or None.
    Broadcast over ``frequency`` (and the others, scalars in the confined case).
    """
    from scipy import special

    a = np.asarray(radius, dtype=float)
    om = np.asarray(frequency, dtype=float)
    nu = np.asarray(kinematic_viscosity, dtype=float)
    k = np.sqrt(1j * om / nu)  # principal root: Re k > 0
    s = k * a
    if outer_radius is None:
        gamma = 1.0 + 4.0 * special.kve(1, s) / (s * special.kve(0, s))  # the scalings e^{s} cancel
        return gamma.real, -gamma.imag
    b = float(outer_radius)
    if not np.all(b > a):
        raise ValueError(f"outer_radius = {b:.6g} m: must exceed the cylinder's radius {float(np.max(a)):.6g} m")
    a_, k_ = np.broadcast_arrays(a, k)
    gam = np.empty(k_.shape, dtype=complex)
    for index in np.ndindex(k_.shape):
        ai, ki = float(a_[index]), complex(k_[index])
        gam[index] = _confined_gamma(ai, b, ki)
    return gam.real, -gam.imag


def _bessel_columns(k, r, b, a):
    """Values, first and second r-derivatives at r of I₁(kr) e^{−kb} and K₁(kr) e^{ka} (scaled to stay finite)."""
    from scipy import special

    z = k * r
    # scaled: ive(n, z) = I_n(z) e^{−|Re z|}, kve(n, z) = K_n(z) e^{z}
    i_scale = np.exp(abs(z.real) - k * b)
    k_scale = np.exp(-z + k * a)
    i0, i1 = special.ive(0, z) * i_scale, special.ive(1, z) * i_scale
    k0, k1 = special.kve(0, z) * k_scale, special.kve(1, z) * k_scale
    di, dk = i0 - i1 / z, -k0 - k1 / z  # I₁' = I₀ − I₁/z, K₁' = −K₀ − K₁/z
    # z² y'' + z y' − (z² + 1) y = 0 for both
    ddi = ((z * z + 1.0) * i1 - z * di) / (z * z)
    ddk = ((z * z + 1.0) * k1 - z * dk) / (z * z)
    return (i1, k * di, k * k * ddi), (k1, k * dk, k * k * ddk)


def _confined_gamma(a, b, k):
    """C_m − i C_c of a cylinder of radius a in a fixed concentric one of radius b (see
    :func:`oscillating_cylinder_force_coefficients`); k = √(iω/ν) [1/m]."""
    ia, ka = _bessel_columns(k, a, b, a)
    ib, kb = _bessel_columns(k, b, b, a)
    system = np.array([[a, 1.0 / a, ia[0], ka[0]],
                       [1.0, -1.0 / a**2, ia[1], ka[1]],
                       [b, 1.0 / b, ib[0], kb[0]],
                       [1.0, -1.0 / b**2, ib[1], kb[1]]], dtype=complex)
    A, B, C, D = np.linalg.solve(system, np.array([a, 1.0, 0.0, 0.0], dtype=complex))
    second = 2.0 * B / a**3 + C * ia[2] + D * ka[2]  # F''(a)
    # F_x/(−iωρπa²) with μ/(iωρ) = ν/(iω) = 1/k²: −[(Aa − B/a) + F''(a)/k²]/a
    return -((A * a - B / a) + second / (k * k)) / a


def viscous_modal_damping_ratio(natural_frequency, mass_per_length, mud_density, radius, kinematic_viscosity,
                                outer_radius=None):
    """ζ_n = c(ω_n)/(2 m ω_n) [-]: the modal damping ratio the mud's viscous loss gives a bending mode of the pipe.

    c(ω) = C_c ρπa²ω [N s/m²] is the damping per length of :func:`oscillating_cylinder_force_coefficients` (the
    Stokes layer on the pipe's outer wall; confined by the hole where ``outer_radius`` is given); every point of the
    span moves at the mode's frequency, so the modal damping is c/m whatever the mode's shape. natural_frequency
    ω_n [rad/s] (NaN stays NaN; ≤ 0 gives 0), mass_per_length m [kg/m] (the pipe's with the mud inside and the
    added mass), mud_density ρ [kg/m³], radius a [m] (the pipe's outer), kinematic_viscosity ν [m²/s] (the mud's
    plastic viscosity over its density), outer_radius b [m] (the hole's) or None."""
    om = np.asarray(natural_frequency, dtype=float)
    out = np.zeros(om.shape)
    out[np.isnan(om)] = np.nan
    live = np.isfinite(om) & (om > 0.0)
    if np.any(live) and float(kinematic_viscosity) > 0.0 and float(mud_density) > 0.0:
        _, c_c = oscillating_cylinder_force_coefficients(radius, om[live], kinematic_viscosity, outer_radius)
        c = c_c * float(mud_density) * np.pi * float(radius) ** 2 * om[live]
        out[live] = c / (2.0 * float(mass_per_length) * om[live])
    return out if out.ndim else float(out)
