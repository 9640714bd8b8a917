"""The reference model's basis (docs/reference_model.md §1): the periodic modes of the section, their lumped joint
modes, the static point-load fields of the periodic beam-column, the contact layout and the eccentricity's phases
along the string. Functions of the section's span and properties only."""

from __future__ import annotations

import numpy as np


def _indices(modes) -> np.ndarray:
    """The mode indices: 0 … N − 1 for a count N, else the indices given."""
    return np.arange(int(modes)) if np.ndim(modes) == 0 else np.asarray(modes, int)


def mode_wavenumbers(span: float, modes) -> np.ndarray:
    """k_n [1/m] of the periodic basis's modes n (``modes``: their count N, n = 0 … N − 1, or their indices): 0 for
    ψ_0, 2πj/L for ψ_{2j−1} and ψ_{2j}."""
    return 2.0 * np.pi * ((_indices(modes) + 1) // 2) / float(span)


def mode_shapes(x, span: float, modes, derivative: int = 0) -> np.ndarray:
    """(X, N) the spatially periodic basis of the section (docs/reference_model.md §1) at x [m], or its
    ``derivative``-th derivative (0–3) along x; ``modes`` their count N (n = 0 … N − 1) or their indices n:
    ψ_0 = 1/√2 (the rigid translation), ψ_{2j−1} = cos k_j x,
    ψ_{2j} = sin k_j x, k_j = 2πj/L. Each has ∫₀ᴸ ψ² dx = L/2 (one modal mass M L/2 for all) and the string
    repeats from section to section: u(x + L) = u(x)."""
    x = np.atleast_1d(np.asarray(x, float))
    n = _indices(modes)
    k = mode_wavenumbers(span, n)
    phase = np.outer(x, k)
    cos, sin = np.cos(phase), np.sin(phase)
    # d/dx of (cos, sin) is k (−sin, cos): the derivative-th of each, by quarter turns
    turns = [(cos, sin), (-sin, cos), (-cos, -sin), (sin, -cos)][derivative]
    out = np.where(n % 2 == 1, turns[0], turns[1]) * k**derivative
    rigid = n == 0
    out[:, rigid] = 1.0 / np.sqrt(2.0) if derivative == 0 else 0.0
    return out


def joint_modes(span: float, modes, mass_per_length: float, bending_stiffness: float, tension: float,
                joints, joint_mass: float) -> tuple[np.ndarray, np.ndarray | None]:
    """ω_n [rad/s] (N,) and the modes (N, N) of the periodic section with a point mass ``joint_mass`` m_j [kg] at each
    of ``joints`` (x_j [m], tool joints; docs/reference_model.md §1): the generalized eigenproblem K a = ω² M a of
    the periodic basis (:func:`mode_shapes`), K = (L/2) diag(EI k_n⁴ + T k_n²), M = (M L/2) I + m_j Σ_j ψ(x_j) ψ(x_j)ᵀ
    (Rayleigh–Ritz; scipy.linalg.eigh), column n the coefficients of mode n on the basis, scaled to the one modal
    mass M L/2 (aᵀ M a = M L/2), so the kernel takes them as it takes the basis. The joints of a periodic section
    lie symmetrically about its middle (x → L − x maps joint to joint), so M couples the symmetric basis functions
    (ψ_0, the cosines: odd n and 0) only among themselves and the antisymmetric (the sines) likewise: each family is
    solved apart and its modes, in rising frequency, take its basis functions' places (mode 0 is the rigid
    translation, ω_0 = 0 exactly; each mode keeps a parity, which the kernel's drag sums use). ω is NaN where
    ω² < 0 (buckled). Without joint mass the basis itself: (ω, None)."""
    n = _indices(modes)
    L = float(span)
    k = mode_wavenumbers(L, n)
    stiffness = 0.5 * L * (bending_stiffness * k**4 + tension * k**2)
    mass = 0.5 * mass_per_length * L
    if float(joint_mass) == 0.0:
        with np.errstate(invalid="ignore"):
            omega2 = (bending_stiffness * k**4 + tension * k**2) / mass_per_length  # as the basis' ω always was
            return np.where(omega2 >= 0.0, np.sqrt(np.maximum(omega2, 0.0)), np.nan), None
    from scipy.linalg import eigh

    shapes = mode_shapes(np.asarray(joints, float), L, n)  # (J, N)
    matrix = mass * np.eye(n.size) + float(joint_mass) * shapes.T @ shapes
    omega2 = np.zeros(n.size)
    basis = np.zeros((n.size, n.size))
    for family in ((n == 0) | (n % 2 == 1), (n > 0) & (n % 2 == 0)):
        at = np.flatnonzero(family)
        if at.size == 0:
            continue
        values, vectors = eigh(np.diag(stiffness[at]), matrix[np.ix_(at, at)])
        rigid = k[at] == 0.0
        order = np.argsort(values, kind="stable")
        if np.any(rigid):  # the rigid translation first: the eigenvalue nearest 0 (a buckled mode's is below it)
            first = int(np.argmin(np.abs(values)))
            order = np.concatenate(([first], order[order != first]))
        vectors = vectors[:, order] * np.sqrt(mass)  # eigh's vectors have aᵀ M a = 1
        values = values[order]
        if np.any(rigid):  # the rigid translation: no stiffness, ω = 0 exactly, a constant
            values[0] = 0.0
            vectors[:, 0] = 0.0
            vectors[rigid, 0] = np.sqrt(mass / matrix[np.ix_(at, at)][np.ix_(rigid, rigid)][0, 0])
        # each mode's sign: its largest coefficient positive (the basis function it grew from)
        sign = np.sign(vectors[np.argmax(np.abs(vectors), axis=0), np.arange(at.size)])
        omega2[at] = values
        basis[np.ix_(at, at)] = vectors * sign
    with np.errstate(invalid="ignore"):
        omega = np.where(omega2 >= 0.0, np.sqrt(np.maximum(omega2, 0.0)), np.nan)
    return omega, basis


def periodic_point_deflection(s, span: float, bending_stiffness: float, tension: float):
    """The static deflection [m per N] at a distance s [m] along the string from a unit point load on the periodic
    beam-column of period L, EI u^(4) − T u'' = δ(x − a) − 1/L (the load's mean carried by the rigid translation),
    without the rigid translation: the modes' static sum G(s) = (2/L) Σ_{j≥1} cos(k_j s)/(EI k_j⁴ + T k_j²),
    k_j = 2πj/L, in closed form. With 1/(k²(k² + a²)) = (1/a²)(1/k² − 1/(k² + a²)), a² = T/EI, it is
    (1/T)[B(s) − M(s)]: M the moment of :func:`periodic_point_moment` (Gradshteyn & Ryzhik 1.445.2), B its tensionless
    limit (G&R 1.443.3); where |a²| L² < 1e-3 (the difference cancels) the series in a² instead,
    (2/(L EI)) Σ_m (−a²)^m Σ_j cos(k_j s)/k_j^{4+2m}, its m = 0, 1 terms in closed form (the Bernoulli polynomials of
    G&R 1.443.6; L³/(720 EI) and −a² L⁵/(30240 EI) at s = 0), the next left out (below 1e-6 relative there)."""
    L = float(span)
    sp = np.mod(np.asarray(s, float), L)
    ei = float(bending_stiffness)
    a2 = float(tension) / ei
    if abs(a2) * L * L >= 1e-3:
        tensionless = periodic_point_moment(sp, L, ei, 0.0)
        return (tensionless - periodic_point_moment(sp, L, ei, float(tension))) / float(tension)
    x = sp / L  # Σ_j cos(2πjx)/j^{2n} = (−1)^{n+1} (2π)^{2n} B_2n(x)/(2 (2n)!), 0 ≤ x ≤ 1
    b4 = x**4 - 2 * x**3 + x**2 - 1.0 / 30.0
    b6 = x**6 - 3 * x**5 + 2.5 * x**4 - 0.5 * x**2 + 1.0 / 42.0
    s4 = -(2 * np.pi) ** 4 * b4 / (2 * 24.0)
    s6 = (2 * np.pi) ** 6 * b6 / (2 * 720.0)
    kL = L / (2 * np.pi)
    return 2.0 / (L * ei) * (kL**4 * s4 - a2 * kL**6 * s6)


def periodic_point_moment(s, span: float, bending_stiffness: float, tension: float):
    """The static moment −EI u'' [N m per N] at a distance s [m] along the string from a unit point load on the
    periodic beam-column of period L (EI u'''' − T u'' = δ(x − a) − 1/L, the load's mean carried by the rigid
    translation; the modes' static sum (2/L) Σ_{j≥1} cos(k_j s)/(k_j² + T/EI), k_j = 2πj/L) in closed form: with
    a = √(T/EI), (1/L)[(L/2a) cosh(a(L/2 − s'))/sinh(aL/2) − 1/a²], s' = s mod L (Fourier series of the
    hyperbolic cosine; Gradshteyn & Ryzhik 1.445.2); its trigonometric form in compression (a imaginary) and
    the tensionless limit (L/2π²)(π²/6 − πθ/2 + θ²/4), θ = 2πs'/L (G&R 1.443.3), for |a| L < 1e-4."""
    L = float(span)
    sp = np.mod(np.asarray(s, float), L)
    a2 = float(tension) / float(bending_stiffness)
    if abs(a2) * L * L < 1e-8:
        theta = 2.0 * np.pi * sp / L
        return L / (2.0 * np.pi**2) * (np.pi**2 / 6.0 - np.pi * theta / 2.0 + theta**2 / 4.0)
    if a2 > 0.0:
        a = np.sqrt(a2)
        # cosh(a(L/2 − s'))/sinh(aL/2) without overflow: e^{−a s'} (1 + e^{−2a(L/2 − s')})... as exponentials
        e1, e2, e3 = np.exp(-a * sp), np.exp(-a * (L - sp)), np.exp(-a * L)
        ratio = (e1 + e2) / (1.0 - e3)
        return (L / (2.0 * a) * ratio - 1.0 / a2) / L
    b = np.sqrt(-a2)
    return (-L / (2.0 * b) * np.cos(b * (L / 2.0 - sp)) / np.sin(b * L / 2.0) - 1.0 / a2) / L


def series_contact(d, stiffness, flexibility) -> tuple[np.ndarray, np.ndarray]:
    """The Hertz approach δ_H [m] and normal force F [N] of Hertz springs K [N m^-3/2] (``stiffness``) in series with
    the flexibility f [m/N] at total approaches d [m] (0 where d ≤ 0): δ_H + f F = d, F = K δ_H^{3/2}, by the Newton
    iteration of :func:`study.solvers.kernels.whirl_kernel.series_hertz`, vectorised."""
    d = np.maximum(np.asarray(d, float), 0.0)
    K = np.broadcast_to(np.asarray(stiffness, float), d.shape)
    c = np.broadcast_to(np.asarray(flexibility, float), d.shape) * K
    x = np.sqrt(d)
    on = (c > 0) & (d > 0)
    x[on] = np.minimum(x[on], np.cbrt(d[on] / c[on]))
    for _ in range(40):
        step = np.zeros_like(x)
        step[on] = (c[on] * x[on] ** 3 + x[on] ** 2 - d[on]) / (3.0 * c[on] * x[on] ** 2 + 2.0 * x[on])
        x = x - step
        if np.all(step <= 1e-15 * x):
            break
    return x * x, K * x**3


def contact_layout(span: float, joint_length: float, body_stations: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """Contact positions x_p [m] and kinds (0 body, 1 tool joint) of the periodic section: the tool joints at
    0, s, 2s, … (x = L is the joint at 0 again), ``body_stations`` on the body evenly between neighbouring joints
    (one: halfway). The section must hold a whole number of joints (within 1e-6): raises ValueError naming both
    fields otherwise."""
    count = float(span) / float(joint_length)
    joints = int(round(count))
    if joints < 1 or abs(count - joints) > 1e-6 * max(count, 1.0):
        raise ValueError(f"contact.section_length = {span:.6g} m holds {count:.6g} joints of pipe.joint_length = "
                         f"{joint_length:.6g} m: the periodic section must hold a whole number of joints (1 or more)")
    spacing = float(span) / joints
    stations = np.arange(joints) * spacing
    k = int(body_stations)
    if k < 0:
        raise ValueError(f"reference_body_stations = {k}: must be >= 0")
    body = (stations[:, None] + spacing * np.arange(1, k + 1)[None, :] / (k + 1)).ravel()
    x = np.concatenate((stations, body))
    kinds = np.concatenate((np.ones(joints, int), np.zeros(body.size, int)))
    order = np.argsort(x)
    return x[order], kinds[order]


def eccentricity_phases(span: float, joint_length: float, turn: float) -> np.ndarray:
    """The phases φ_j [rad] of the mass eccentricity of the section's pipe joints j = 0 … n − 1 (the body from the tool
    joint at j s to the next), each turned by ``turn`` [rad] from the previous one: φ_j = j·turn. The section repeats,
    so it must hold whole turns of the pattern, n·turn a multiple of 2π (within 1e-9): raises ValueError naming both
    fields otherwise (docs/reference_model.md §1)."""
    n = contact_layout(span, joint_length, 0)[0].size
    turns = n * float(turn) / (2.0 * np.pi)
    if abs(turns - round(turns)) > 1e-9 * max(turns, 1.0):
        raise ValueError(f"pipe.eccentricity_turn = {np.degrees(turn):.6g} deg: the periodic section of "
                         f"contact.section_length = {span:.6g} m holds {n} joints, which turn the eccentricity by "
                         f"{np.degrees(n * turn):.6g} deg; allowed: a turn whose multiple by {n} is a whole number of "
                         "turns (360 deg/n times an integer, 0 for aligned), or a section holding whole turns of it")
    return np.arange(n) * float(turn)


def eccentric_factors(span: float, joint_length: float, modes, turn: float = 0.0) -> np.ndarray:
    """(N,) ∫₀ᴸ e^{iφ(x)} ψ_n(x) dx [m] over the periodic basis (:func:`mode_shapes`), φ(x) the phase of the mass
    eccentricity of the pipe joint at x (:func:`eccentricity_phases`): the turning load m_p ε Ω² e^{i(Ωt + φ(x))}
    per unit length (y + i z) drives basis function n by m_p ε Ω² times it. Aligned (``turn`` 0) it is real, L/√2 on
    the rigid translation and nil on the others (a uniform load drives ψ_0 alone); turned, complex, its phase the
    drive's lead on cos Ωt: the joints' loads sum to nil on ψ_0 where the phases close a whole turn, and drive the
    Bloch wave of the turn (wavenumber turn/s) and its images."""
    n = _indices(modes)
    out = np.zeros(n.size)
    if float(turn) == 0.0:
        out[n == 0] = span / np.sqrt(2.0)
        return out
    phases = eccentricity_phases(span, joint_length, turn)
    s = span / phases.size
    a = np.arange(phases.size) * s
    k = mode_wavenumbers(span, n)
    kk = np.where(k > 0, k, 1.0)
    # ∫ over each pipe joint [a, a + s] of ψ_n: s/√2 (ψ_0), (sin k b − sin k a)/k (cos), (cos k a − cos k b)/k (sin)
    lo, hi = np.outer(a, k), np.outer(a + s, k)
    pieces = np.where(n % 2 == 1, (np.sin(hi) - np.sin(lo)) / kk, (np.cos(lo) - np.cos(hi)) / kk)
    pieces[:, n == 0] = s / np.sqrt(2.0)
    return np.exp(1j * phases) @ pieces


def symmetric_points(x, span: float) -> bool:
    """Whether the contact points x [m] lie symmetrically about the periodic section's middle (x → L − x maps them
    onto themselves), as :func:`residual_ritz` needs."""
    x = np.asarray(x, float)
    L = float(span)
    gap = np.abs(np.mod(np.mod(L - x, L)[:, None] - x[None, :] + 0.5 * L, L) - 0.5 * L)
    return bool(np.all(np.min(gap, axis=1) <= 1e-9 * L))
