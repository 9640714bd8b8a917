"""The reference model (method ``reference``; ``docs/reference_model.md``): the rotating pipe section in
the hole, in both lateral directions, driven by what drives it.

Scene (our choices, stated; the equations in :mod:`study.solvers.whirl_kernel`):

- **section** a piece of a long string, spatially periodic (the string repeats from section to section, so its
  end joints lie on the wall like the others; docs/reference_model.md §1), length L = ``section_length`` (config
  ``contact.section_length``, default 93 ft: three 31-ft joints; a whole number of joints), under the effective
  tension T0 − m_i V_m², mass M = m_p + m_i + m_a per unit length
  (:func:`study.solvers.scene.section_properties`); deflection u(x, t) = (y, z) = Σ_n (q_yn, q_zn) ψ_n(x) over
  the periodic basis ψ_0 = 1/√2 (the rigid translation, ω_0 = 0), ψ_{2j−1} = cos k_j x, ψ_{2j} = sin k_j x,
  k_j = 2πj/L (:func:`mode_shapes`), n = 0 … N − 1 (``reference_modes``, default 16, modes per direction),
  modal mass M L/2 and ω_n² = (EI k_n⁴ + T k_n²)/M.
- **drive**: the pipe's mass eccentricity ε (``eccentricity``, config ``pipe.eccentricity``), the same size in every
  pipe joint, whose centrifugal load m_p ε Ω² per unit length turns with the pipe
  (:func:`study.physics.whirl.eccentric_load`), in the same phase in every pipe joint (``eccentricity_turn`` 0, the
  default) or turned from joint to joint (:func:`eccentric_factors`); and the uniform side load (:func:`side_loads`): in an inclined
  hole (``inclination``, config ``hole.inclination``, default 0) the buoyed weight's side component, in a curved
  hole (``dogleg_curvature``, ``dogleg_direction``) the tension's T κ towards the centre of curvature, whose
  curvature also bends the pipe that follows it (``side_load`` [N/m] sets the load directly in code). A uniform
  load drives the rigid translation ψ_0 alone. Nothing else: with ε = 0 and a centred pipe in a straight vertical
  hole nothing moves.
- **mud**: added mass in M; quadratic drag −D |u̇| u̇ per unit length with the velocity's magnitude in
  both directions (``reference_damping = "drag"``, default; D from
  :func:`study.physics.section.drag_coefficient_per_length`), projected on the modes by
  Gauss–Legendre quadrature with 2N + 8 points. For validation ``"viscous"`` (modal damping ratio
  ``damping_ratio`` in every mode) and ``"none"``.
- **contact points**: the tool joints at 0, s, 2s, … (s = ``joint_length``; x = L is the joint at 0 again),
  radius r_tj = ``tool_joint_diameter``/2, clearance R − r_tj; and the pipe body halfway between neighbouring
  joints, radius r_o, clearance R − r_o (:func:`contact_layout`; ``reference_body_stations`` of them, raised by
  :func:`solve_with_modes` where the body passes its wall between them).
  ``contact_points`` (fractions of L) and ``contact_kinds`` (0 body, 1 joint) replace them in code.
- **wall**: Hertz normal force K_p δ^{3/2}(1 + χ δ̇)₊ with K_p from
  :func:`study.physics.hertz.hertz_stiffness` for the point's radius in the hole at the curvature of the
  assumed mode c_p (π/L)² (as :mod:`study.solvers.timedomain`), χ = h(e)/v0 set at each onset with the
  calibrated h(e) of :func:`study.physics.contact.calibrated_hysteresis` (exact restitution for one
  mass); Coulomb friction μ (``friction``, config ``contact.friction``, default 0.3) on the sliding
  velocity u̇·t̂ + Ω r_p, regularised over ``slip_velocity`` (default :data:`SLIP_VELOCITY`). The modes left out
  are given back statically (``reference_residual = "series"``, docs/reference_model.md §2.1): their flexibility
  at each contact point (:func:`residual_flexibility`) in series with its Hertz spring, and their static field
  under every contact force at every instant in the stresses (:func:`static_correction`); or dynamically
  (``"dynamic"``): one residual vector per contact point, that static field, in the integrated modes
  (:func:`residual_ritz`), its modal part measured between N/2 and N modes (:func:`doubling_modal_error`).
- **rotation**: Ω constant (the rotary table holds it; the friction torque does not slow it); no
  gyroscopic terms (a pipe's polar inertia per length is negligible at these speeds).

Run: from the string's rest on the wall where a side load lays it there, else its synchronous whirl without walls
(:func:`initial_state`; ``reference_initial = "rest"``: the centred pipe at rest), revolution by revolution (the compiled Dormand–Prince integrator of
:mod:`study.solvers.whirl_kernel`, ``reference_rtol`` default 1e-6, in its Lawson form between contacts:
``reference_integrator``) until the state at the revolution
boundaries repeats (1–8 revolutions, :func:`study.solvers.timedomain.settled_period`), the pipe bounces with
stationary statistics (:func:`stationary`, checked every ``reference_window`` revolutions from three times that on) or
``reference_revolutions`` (default 40) have passed; then a window of ``reference_window`` revolutions
(default 6; the period's multiple when periodic) is recorded and the outputs are taken over it. Where the modes
left out take a figure's error over half the study's tolerance (:func:`modal_check`, measured on the run) the point
is run again with more modes, up to ``reference_max_modes`` (default 64; :func:`solve`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Mapping

import numpy as np

from study.physics import fatigue, hertz, limits, section, well, whirl
from study.physics.contact import (calibrated_hysteresis, hertz_energy, hertz_force, linear_contact_damping,
                                   linearised_stiffness)
from study.solvers import stress_kernel, whirl_kernel
from study.solvers.options import ReferenceOptions, statistical_tolerance, study_tolerance
from study.solvers.result import REGIMES, PointResult
from study.solvers.scene import make_scene, section_properties
from study.solvers.timedomain import settled_period
from study.solvers.utilisation import limit_options

METHOD = "reference"
CONTACT_LAWS = ReferenceOptions.choices("contact_law")
SCHEMES = ReferenceOptions.choices("reference_integrator")
#: the kernel's code of each scheme (whirl_kernel.advance)
SCHEME_CODES = {"dopri5": whirl_kernel.DOPRI5, "lawson": whirl_kernel.LAWSON, "lawson-flight": whirl_kernel.LAWSON_FLIGHT}
#: Default regularisation velocity of the Coulomb friction [m/s]: 1/250 of the 4½-in body's surface
#: speed at 100 rpm; tested not to change the outputs beyond 2 % when divided by ten.
SLIP_VELOCITY = ReferenceOptions.default("slip_velocity")
#: Largest step times the highest natural frequency (Dormand–Prince 5(4) is stable on the imaginary axis
#: up to about 3.3; Hairer & Wanner, Solving ODEs II, §IV.2).
STABLE_STEP = 2.5
#: The regime of the study's charts (study.solvers.result.REGIMES) each whirl verdict is.
WHIRL_REGIMES = {"no_contact": "no_contact", "forward": "forward_whirl", "backward": "backward_whirl",
                 "bouncing": "bouncing", "sliding": "sliding"}
#: Whirl verdicts -> integer code (output ``whirl_class``): its regime's code, one code table (result.Regime).
WHIRL_CLASSES = {verdict: REGIMES[regime] for verdict, regime in WHIRL_REGIMES.items()}
#: |whirl rate/Ω| below which a pipe in contact at least SLIDING_CONTACT of the time lies on the wall, sliding.
SLIDING_RATE, SLIDING_CONTACT = 0.05, 0.99


@dataclass
class WhirlModel:
    """The section's modal model in both directions (SI)."""

    span: float  #: section length L [m]
    modes: np.ndarray  #: mode indices n = 0 … N − 1 (N,) of the periodic basis (:func:`mode_shapes`)
    omega: np.ndarray  #: ω_n [rad/s] (ω_0 = 0: the rigid translation)
    mass: float  #: modal mass M L/2 [kg]
    rotary_speed: float
    points: np.ndarray  #: contact positions x_p [m]
    kinds: np.ndarray  #: 0 body, 1 tool joint
    clearance: np.ndarray  #: c_p [m]
    radius: np.ndarray  #: r_p [m]
    stiffness: np.ndarray  #: Hertz K_p [N m^-3/2]
    phi: np.ndarray  #: (P, N) ψ_n(x_p)
    #: (N,) generalised eccentric force per modal mass [m/s²]; complex where the joints' eccentricities turn, its
    #: phase the lead on cos Ωt (:func:`eccentric_factors`, :func:`eccentric_parts`)
    eccentric: np.ndarray
    side: np.ndarray  #: (N,) generalised side load per modal mass [m/s²]
    damping: np.ndarray  #: (N,) linear modal damping per mass 2ζω_n [1/s]
    drag: float  #: D [kg/m²]
    drag_shapes: np.ndarray  #: (G, N)
    drag_weights: np.ndarray  #: (G,) [m]
    friction: float
    slip_velocity: float
    restitution: float
    hysteresis: float  #: calibrated h(e) = χ v0 [-]
    law: int  #: 0 Hertz, 1 linear penalty
    penalty_stiffness: np.ndarray  #: (P,) [N/m]
    penalty_damping: np.ndarray  #: (P,) [N s/m]
    props: Mapping[str, float] = field(default_factory=dict)
    eccentricity: float = 0.0
    frame: float = 0.0  #: angle β of the model's +y from the hole's low side towards +z: the side load's direction [rad]
    hole_curvature: np.ndarray = field(default_factory=lambda: np.zeros(2))  #: κ⃗ of the hole in the model's frame [1/m]
    #: (N, N) the modes on the periodic basis with the tool joints' mass (:func:`joint_modes`); None: the basis itself
    basis: np.ndarray | None = None
    joint_mass: float = 0.0  #: m_j, each tool joint's mass beyond the plain pipe's, lumped at the joint [kg]
    joint_weight: float = 0.0  #: the side component of each joint's buoyed weight beyond the pipe's [N]
    #: (P,) the joints' weight at the contact points that are joints, along the model's +y [N] (None: none), for the
    #: quasi-static correction (:func:`periodic_fields`), which completes it as it completes the contact forces
    point_side: np.ndarray | None = None
    #: (P,) residual flexibility of the modes left out at each contact point [m/N], in series with its Hertz spring
    #: (:func:`residual_flexibility`; empty: the kept modes alone)
    residual: np.ndarray = field(default_factory=lambda: np.zeros(0))
    #: (P,) the residual oscillator's mass μ_p = g_p/f_p² at each contact point [kg] (``reference_residual =
    #: "dynamic"``: :func:`residual_second_moment`; empty: the residual flexibility, if any, static in series)
    residual_mass: np.ndarray = field(default_factory=lambda: np.zeros(0))
    #: the modes left out as residual vectors, one per contact point, in the kernel's modes (``reference_residual =
    #: "dynamic"``: :func:`residual_ritz`; None: the residual flexibility, if any, static in series)
    ritz: dict | None = None
    joint_x: np.ndarray = field(default_factory=lambda: np.zeros(0))  #: the tool joints' positions x_j [m]
    #: (P,) which contact points are the joints whose mass is lumped (None: no joints' mass), for the quasi-static
    #: correction of their inertia forces (:func:`joint_inertia_forces`)
    joint_points: np.ndarray | None = None
    cache: dict = field(default_factory=dict, repr=False)  #: the static correction's fields, per stations

    @property
    def wavenumber(self) -> np.ndarray:
        """k_n [1/m] of the modes (0 for the rigid translation)."""
        return mode_wavenumbers(self.span, self.modes)

    @property
    def weights(self) -> np.ndarray:
        """(N,) each mode's weight in the integrator's error scale: 1/n² with n = k L/π the half-waves of its
        wavenumber over the section (at least 1: the rigid translation weighs as the first bending mode), so that
        each mode's contribution to the moment (k² q) is held alike."""
        return 1.0 / np.maximum(self.wavenumber * self.span / np.pi, 1.0) ** 2

    def first_left_out(self) -> float:
        """ω of the first mode left out of the basis [rad/s]."""
        k = float(mode_wavenumbers(self.span, [int(np.max(self.modes)) + 1])[0])
        return float(np.sqrt((self.props["bending_stiffness"] * k**4 + self.props["effective_tension"] * k**2)
                             / self.props["mass_per_length"]))

    @property
    def period(self) -> float:
        return 2.0 * np.pi / self.rotary_speed

    @property
    def n_modes(self) -> int:
        return int(self.modes.size)

    def state_scale(self) -> np.ndarray:
        """(4N,) scale of the state: the body clearance c for q, Ω c for q̇."""
        c = float(np.max(self.clearance))
        N = self.n_modes
        return np.concatenate((np.full(2 * N, c), np.full(2 * N, self.rotary_speed * c)))

    def shapes(self, x, derivative: int = 0) -> np.ndarray:
        """(X, N) the modes' shapes (or their ``derivative``-th derivative along x) at x [m]: :func:`mode_shapes`, on
        the joints' modes (:attr:`basis`) where the tool joints' mass is lumped."""
        out = mode_shapes(x, self.span, self.modes, derivative)
        return out if self.basis is None else out @ self.basis

    def moment_shapes(self, x) -> np.ndarray:
        """(X, N) each mode's moment −EI ψ_n'' at x [m] per unit coordinate [N m/m]: EI k_n² ψ_n on the basis."""
        out = mode_shapes(x, self.span, self.modes) * (self.props["bending_stiffness"] * self.wavenumber**2)
        return out if self.basis is None else out @ self.basis

    def system(self) -> tuple:
        """The model's arrays for the compiled integrator (:func:`whirl_kernel.kernel_system` makes its tuple). With
        the residual vectors (:attr:`dynamic`) the kernel's modes are the N + P modes of the kept modes and one
        residual vector per contact point (:func:`residual_ritz`): their frequencies, shapes at the contact and drag
        points and loads; the linear damping the modes' ratio at their frequencies (none with the drag)."""
        fpar = np.array([self.drag, self.rotary_speed, self.friction, self.slip_velocity, 1.0 / self.mass,
                         float(self.law), self.hysteresis])
        if not self.dynamic:
            return (self.omega**2, self.damping, self.eccentric, self.side, self.drag_shapes, self.drag_weights,
                    self.phi, self.clearance, self.radius, self.stiffness, self.penalty_stiffness,
                    self.penalty_damping, fpar, self.flexibility)
        r = self.ritz
        return (r["omega2"], r["damping"], r["eccentric"], r["side"], r["drag_shapes"], self.drag_weights,
                r["phi"], self.clearance, self.radius, self.stiffness, self.penalty_stiffness, self.penalty_damping,
                fpar, np.zeros(self.points.size))

    @property
    def dynamic(self) -> bool:
        """Whether the modes left out are residual vectors in the kernel's modes (``reference_residual =
        "dynamic"``)."""
        return self.ritz is not None

    @property
    def kernel_modes(self) -> int:
        """The kernel's modes per direction: N, and P more with the residual vectors."""
        return self.n_modes + (self.points.size if self.dynamic else 0)

    @property
    def kernel_phi(self) -> np.ndarray:
        """(P, kernel modes) the kernel's modes' shapes at the contact points."""
        return self.ritz["phi"] if self.dynamic else self.phi

    @property
    def residual_omega2(self) -> np.ndarray:
        """(P,) k_p/μ_p = 1/(f_p μ_p) [rad²/s²]: each residual vector's own frequency (its Rayleigh quotient without
        the joints' mass; with :attr:`residual_mass`)."""
        return 1.0 / (self.residual * self.residual_mass)

    def extend(self, z) -> np.ndarray:
        """The kernel's state from the modal one (4N + 4,): with the residual vectors their coordinates set to their
        static response to each contact's normal force at the kept modes' approach, s_p = −F_n n̂ (the series law's
        split, :func:`series_contact`), zero rates, mapped onto the kernel's modes; else z itself (a copy)."""
        z = np.array(z, float)
        if not self.dynamic or z.size == 4 * self.kernel_modes + 4:
            return z
        N, P, K = self.n_modes, self.points.size, self.kernel_modes
        y, w = self.phi @ z[:N], self.phi @ z[N:2 * N]
        r = np.hypot(y, w)
        force = series_contact(r - self.clearance, self.stiffness, self.residual)[1]
        with np.errstate(invalid="ignore", divide="ignore"):
            scale = np.where(r > 0, -force / np.maximum(r, 1e-300), 0.0)
        forces = [scale * y, scale * w, np.zeros(P), np.zeros(P)]
        inverse, T = self.ritz["inverse"], self.ritz["combinations"]
        out = np.zeros(4 * K + 4)
        for j in range(4):
            out[j * K:(j + 1) * K] = inverse @ np.concatenate((z[j * N:(j + 1) * N], T.T @ forces[j]))
        out[-4:] = z[4 * N:]
        return out

    def reduce(self, z) -> np.ndarray:
        """The modal state(s) (..., 4N + 4) from the kernel's: with the residual vectors the kept modes' coordinates
        of the kernel's modes (:meth:`residual_coordinates` gives the residual vectors')."""
        z = np.asarray(z, float)
        if not self.dynamic:
            return z
        N, K = self.n_modes, self.kernel_modes
        kept = self.ritz["vectors"][:N]
        return np.concatenate([z[..., j * K:(j + 1) * K] @ kept.T for j in range(4)] + [z[..., -4:]], axis=-1)

    def residual_coordinates(self, z) -> np.ndarray:
        """(..., 4, P) the residual vectors' coordinates s_y, s_z, ṡ_y, ṡ_z [N, N/s] from the kernel's state(s): the
        forces at the contact points whose static field of the modes left out (:func:`static_correction`) their
        motion is."""
        z = np.asarray(z, float)
        N, K = self.n_modes, self.kernel_modes
        to_forces = self.ritz["combinations"] @ self.ritz["vectors"][N:]  # (P, K)
        return np.stack([z[..., j * K:(j + 1) * K] @ to_forces.T for j in range(4)], axis=-2)

    def kernel_energy(self, z) -> float:
        """The kernel state's Σ ½ m (η̇² + ω² η²) over its modes in both directions plus the contacts' Hertz energy
        [J] (the residual vectors' kinetic and strain energy in the modes' sum)."""
        if not self.dynamic:
            return self.energy(z)
        K = self.kernel_modes
        z = np.asarray(z, float)
        w2 = np.tile(self.ritz["omega2"], 2)
        phi = self.ritz["phi"]
        d = np.maximum(np.hypot(phi @ z[:K], phi @ z[K:2 * K]) - self.clearance, 0.0)
        contact = hertz_energy(d, self.stiffness) if self.law == 0 else 0.5 * self.penalty_stiffness * d**2
        return float(0.5 * self.mass * np.sum(z[2 * K:4 * K] ** 2 + w2 * z[:2 * K] ** 2) + np.sum(contact))

    @property
    def flexibility(self) -> np.ndarray:
        """(P,) the residual flexibility in series with each contact's Hertz spring [m/N] (zeros where none, and with
        the residual oscillators, which carry it dynamically)."""
        if self.dynamic or self.residual.size != self.points.size:
            return np.zeros(self.points.size)
        return self.residual

    def energy(self, z) -> float:
        """Σ ½ m (q̇² + ω² q²) over both directions plus the contacts' elastic energy [J]."""
        N = self.n_modes
        z = np.asarray(z, float)
        q, v = z[:2 * N], z[2 * N:4 * N]
        w2 = np.concatenate((self.omega, self.omega)) ** 2
        y, w = self.phi @ z[:N], self.phi @ z[N:2 * N]
        d = np.maximum(np.hypot(y, w) - self.clearance, 0.0)
        if self.law == 0:  # the Hertz spring's 2/5 K δ_H^{5/2} and the series flexibility's f F²/2
            approach, force = series_contact(d, self.stiffness, self.flexibility)
            contact = hertz_energy(approach, self.stiffness) + 0.5 * self.flexibility * force**2
        else:
            contact = 0.5 * self.penalty_stiffness * d**2
        return float(0.5 * self.mass * np.sum(v**2 + w2 * q**2) + np.sum(contact))


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


def residual_flexibility(model: "WhirlModel") -> np.ndarray:
    """(P,) the static flexibility of the modes left out at each contact point [m/N], f_p = Σ_{n ≥ N} ψ_n(x_p)²/(m ω_n²)
    (m = M L/2): the periodic beam-column's whole, :func:`periodic_point_deflection` at s = 0, less the kept modes'
    terms (the rigid translation has none). It vanishes as N grows (like N⁻³: terms like j⁻⁴); in series with a
    contact's Hertz spring (:func:`study.solvers.whirl_kernel.series_hertz`) it makes a held contact's static answer
    the continuous beam's (docs/reference_model.md §2.1). With the tool joints' mass the kept modes span the same
    basis functions, so their static part is the basis' own, a matter of stiffness alone (as in
    :func:`static_correction`): m ω_n² = (L/2)(EI k_n⁴ + T k_n²) on the basis."""
    ei, tn = model.props["bending_stiffness"], model.props["effective_tension"]
    whole = float(periodic_point_deflection(0.0, model.span, ei, tn))
    return np.maximum(whole - mode_shapes(model.points, model.span, model.modes) ** 2 @ basis_static_gain(model), 0.0)


#: Harmonics above the kept ones that :func:`residual_second_moment` sums (its terms fall like j⁻⁸: the tail past them
#: is below 1e-9 of the sum up to 128 modes, and counted by its integral beyond).
SECOND_MOMENT_HARMONICS = 4096


def residual_second_moments(model: "WhirlModel") -> np.ndarray:
    """(P, P) the modes left out's second moments between the contact points [m/N s²], G_pq = Σ_{n ≥ N} ψ_n(x_p) ψ_n(x_q)
    /(m ω_n⁴): the mass of the residual vectors (:func:`residual_ritz`); its diagonal is :func:`residual_second_moment`
    (the tail beyond the harmonics summed counted there only: off it the terms alternate in sign and fall like j⁻⁸)."""
    ei, tn = model.props["bending_stiffness"], model.props["effective_tension"]
    L, N = model.span, model.n_modes
    n = np.arange(N, N + 2 * SECOND_MOMENT_HARMONICS)
    k = mode_wavenumbers(L, n)
    gain = 1.0 / (0.5 * L * (ei * k**4 + tn * k**2))
    shapes = mode_shapes(model.points, L, n)
    out = (shapes * (model.mass * gain**2)) @ shapes.T
    J = (N + 2 * SECOND_MOMENT_HARMONICS - 1) // 2
    out[np.diag_indices_from(out)] += model.mass * (2.0 / (L * ei)) ** 2 * (L / (2 * np.pi)) ** 8 / (7.0 * (J + 0.5) ** 7)
    return out


def residual_second_moment(model: "WhirlModel") -> np.ndarray:
    """(P,) the second moment of the modes left out at each contact point [m/N s²], g_p = Σ_{n ≥ N} ψ_n(x_p)²/(m ω_n⁴)
    (m = M L/2): the ω² term of their receptance Σ ψ_n²/(m (ω_n² − ω²)) = f_p + g_p ω² + O(ω⁴) at the point, the
    diagonal of :func:`residual_second_moments`. On the basis functions left out (as :func:`residual_flexibility`, a
    matter of stiffness and the one modal mass), summed over :data:`SECOND_MOMENT_HARMONICS` harmonics and the tail
    beyond by its integral (terms (2/L)² m/(EI k⁴)² per harmonic where tension no longer counts; tested against the
    tensionless closed form (2/(L EI))² m (L/2π)⁸ ζ(8) and the series summed further)."""
    return np.diag(residual_second_moments(model)).copy()


def basis_static_gain(model: "WhirlModel") -> np.ndarray:
    """(N,) each basis function's static gain 1/(m ω_n²) = 1/((L/2)(EI k_n⁴ + T k_n²)) [m/N per unit shape], 0 for the
    rigid translation: a matter of stiffness alone, so the same with or without the tool joints' mass."""
    ei, tn = model.props["bending_stiffness"], model.props["effective_tension"]
    k = model.wavenumber
    gain = np.zeros(model.n_modes)
    flexible = k > 0
    gain[flexible] = 1.0 / (0.5 * model.span * (ei * k[flexible] ** 4 + tn * k[flexible] ** 2))
    return gain


def series_contact(d, stiffness, flexibility) -> tuple[np.ndarray, np.ndarray]:
    """The Hertz approach δ_H [m] and normal force F [N] of Hertz springs K [N m^-3/2] (``stiffness``) in series with
    the flexibility f [m/N] at total approaches d [m] (0 where d ≤ 0): δ_H + f F = d, F = K δ_H^{3/2}, by the Newton
    iteration of :func:`study.solvers.whirl_kernel.series_hertz`, vectorised."""
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


def eccentric_parts(model: "WhirlModel") -> tuple[np.ndarray, np.ndarray]:
    """(a, b) (N,) the real and imaginary parts of the model's generalised eccentric force per modal mass [m/s²]:
    the turning load drives mode n by (a cos Ωt − b sin Ωt, a sin Ωt + b cos Ωt) in (y, z)."""
    e = np.asarray(model.eccentric)
    return e.real.astype(float), (e.imag.astype(float) if np.iscomplexobj(e) else np.zeros(e.size))


def side_loads(inputs: Mapping[str, Any], props: Mapping[str, float]) -> tuple[float, float, np.ndarray]:
    """The uniform side load (w_y, w_z) [N/m] on the string in the hole's frame (y towards the low side) and the
    hole's curvature vector κ⃗ (2,) [1/m]: :func:`study.physics.well.side_load_vector` of the buoyed weight
    (:func:`study.physics.whirl.side_load`'s, as every method reads it), the inclination, the effective tension and,
    in a curved hole, ``dogleg_curvature`` κ [1/m] towards ``dogleg_direction`` φ [rad] from the low side (the
    tension's T κ towards the centre of curvature). ``side_load`` [N/m] in the inputs sets the load along +y
    directly (code and tests)."""
    kappa = float(inputs.get("dogleg_curvature") or 0.0)
    phi = float(inputs.get("dogleg_direction") or 0.0)
    curvature = kappa * np.array([np.cos(phi), np.sin(phi)])
    if inputs.get("side_load") is not None:
        return float(inputs["side_load"]), 0.0, curvature
    r_o = inputs["outer_diameter"] / 2.0
    buoyed = float(whirl.side_load(props["pipe_mass"], props["internal_mud_mass"], inputs["mud_density"], r_o,
                                   0.5 * np.pi))  # the whole buoyed weight per length (sin 90° = 1)
    w_y, w_z = well.side_load_vector(buoyed, float(inputs.get("inclination") or 0.0), props["effective_tension"],
                                     kappa, phi)
    return float(w_y), float(w_z), curvature


def build_model(inputs: Mapping[str, Any]) -> WhirlModel:
    """The reference model of one design point (see the module docstring). Raises ValueError naming the
    field for inputs that make no scene (a tool joint wider than the hole, thinner than the pipe)."""
    option = ReferenceOptions.from_inputs(inputs)
    props = section_properties(inputs)
    scene = make_scene(inputs)
    r_o, hole_r = inputs["outer_diameter"] / 2.0, inputs["hole_diameter"] / 2.0
    if r_o >= hole_r:
        raise ValueError(f"pipe.outer_diameter = {2 * r_o:.6g} m: must be smaller than hole.diameter = "
                         f"{2 * hole_r:.6g} m")
    tj = float(option.tool_joint_diameter) / 2.0
    if not r_o <= tj < hole_r:
        raise ValueError(f"pipe.tool_joint_diameter = {2 * tj:.6g} m: must be at least pipe.outer_diameter "
                         f"({2 * r_o:.6g} m) and smaller than hole.diameter ({2 * hole_r:.6g} m)")
    L = float(option.section_length)
    joint = float(option.joint_length)
    if L <= 0 or joint <= 0:
        raise ValueError(f"contact.section_length = {L:.6g} m, pipe.joint_length = {joint:.6g} m: both must be > 0")
    mu = float(option.friction)
    if mu < 0:
        raise ValueError(f"contact.friction = {mu}: must be >= 0")
    N = int(option.reference_modes)
    if N < 1:
        raise ValueError(f"reference_modes = {N}: at least 1")
    modes = np.arange(N)
    M = props["mass_per_length"]
    # the tool joints' mass beyond the plain pipe's, lumped at the joints (docs/reference_model.md §1, §9)
    tj_bore, tj_length = float(option.tool_joint_inner_diameter), float(option.tool_joint_length)
    if not 0.0 <= tj_bore < 2 * tj:
        raise ValueError(f"pipe.tool_joint_inner_diameter = {tj_bore:.6g} m: must be >= 0 and smaller than "
                         f"pipe.tool_joint_diameter ({2 * tj:.6g} m)")
    if not 0.0 <= tj_length < joint:
        raise ValueError(f"pipe.tool_joint_length = {tj_length:.6g} m: must be >= 0 and shorter than "
                         f"pipe.joint_length ({joint:.6g} m)")
    joint_mass, joint_weight = well.tool_joint_excess(
        inputs.get("pipe_density") or 7850.0, 2 * tj, tj_bore, tj_length, props["pipe_mass"], 2 * r_o,
        inputs["inner_diameter"], inputs["mud_density"])
    if joint_mass < 0.0:
        raise ValueError(f"pipe.tool_joint_length = {tj_length:.6g} m with pipe.tool_joint_diameter = {2 * tj:.6g} m, "
                         f"pipe.tool_joint_inner_diameter = {tj_bore:.6g} m makes a joint {-joint_mass:.4g} kg lighter "
                         "than the plain pipe it replaces: set pipe.tool_joint_length = 0 where pipe.linear_mass "
                         "counts the joints already")
    joint_x = contact_layout(L, joint, 0)[0]
    joint_side = joint_weight * float(np.sin(float(inputs.get("inclination") or 0.0)))  # along the low side
    # ω_n and the modes with the joints' mass (the basis itself without); NaN where ω² < 0: the section buckles
    omega, basis = joint_modes(L, N, M, props["bending_stiffness"], props["effective_tension"], joint_x, joint_mass)
    if inputs.get("contact_points") is not None:
        x = np.atleast_1d(np.asarray(inputs["contact_points"], float)) * L
        kinds = np.atleast_1d(np.asarray(inputs.get("contact_kinds", np.zeros(x.size)), int))
    else:
        x, kinds = contact_layout(L, joint, int(option.reference_body_stations))
    radius = np.where(kinds == 1, tj, r_o)
    clearance = hole_r - radius
    kappa = clearance * (np.pi / L) ** 2
    a_sum, b_sum = hertz.curvature_sums(radius, hole_r, kappa)
    K = np.asarray(hertz.hertz_stiffness(a_sum, b_sum, scene.compliance_sum), float)
    phi = mode_shapes(x, L, N)
    mass = 0.5 * M * L
    lift = (lambda a: a) if basis is None else (lambda a: a @ basis)  # the basis' values to the modes'
    phi = lift(phi)
    Om = float(inputs["rotary_speed"])
    eps = float(option.eccentricity)
    factors = np.zeros(N)
    factors[0] = L / np.sqrt(2.0)  # ∫₀ᴸ ψ_n dx: a uniform load drives the rigid translation only
    # the body's, not the joints'; in phases that turn from pipe joint to pipe joint (eccentric_factors)
    eccentric = lift(whirl.eccentric_load(props["pipe_mass"], eps, Om)
                     * eccentric_factors(L, joint, N, float(option.eccentricity_turn))) / mass
    w_y, w_z, curvature = side_loads(inputs, props)
    if joint_side and inputs.get("side_load") is None:
        w_y += joint_side * joint_x.size / L  # the joints' weight's mean along the string, in the uniform load
    # the scene is axisymmetric but for the side load, whose direction is constant: the model's frame is the hole's
    # turned by the side load's angle β, so that the load lies along its +y (every output is the same in any frame)
    frame = float(np.arctan2(w_z, w_y)) if (w_y or w_z) else 0.0
    w_side = float(np.hypot(w_y, w_z))
    cb, sb = np.cos(frame), np.sin(frame)
    hole_curvature = np.array([cb * curvature[0] + sb * curvature[1], -sb * curvature[0] + cb * curvature[1]])
    load = w_side * factors
    if joint_side and inputs.get("side_load") is None:
        # the joints' weight at the joints less its mean (in w_side): a load at the supports, along the low side (its
        # part across the model's +y, where a walking dogleg turns the frame, is left out: docs/reference_model.md §9)
        load = load + joint_side * cb * (mode_shapes(joint_x, L, N).sum(axis=0) - joint_x.size / L * factors)
    at_joint = (kinds == 1) & np.any(np.abs(x[:, None] - joint_x[None, :]) <= 1e-9 * L, axis=1)  # contacts at joints
    point_side = None
    if joint_side and inputs.get("side_load") is None and np.any(at_joint):
        point_side = np.where(at_joint, joint_side * cb, 0.0)
    side = lift(load) / mass
    damping_model = option.reference_damping
    damping = np.zeros(N)
    if damping_model == "viscous":
        damping = 2.0 * float(option.damping_ratio) * omega
    G = 2 * N + 8
    gx, gw = whirl.gauss_legendre(G)
    shapes = lift(mode_shapes(0.5 * L * (gx + 1), L, N))
    drag = props["drag_coefficient_per_length"] if damping_model == "drag" else 0.0
    e = float(inputs["restitution"])
    law = CONTACT_LAWS.index(option.contact_law)
    # the linear penalty: Hertz linearised at the elastic approach of the point's effective mass at Ω c_p
    m_eff = mass / np.maximum(np.sum(phi**2, axis=1), 1e-12)
    alpha = hertz.hertz_impact(m_eff, np.maximum(Om * clearance, 1e-6), K).max_approach
    kp = linearised_stiffness(alpha, K)
    cp = linear_contact_damping(kp, m_eff, e)
    model = WhirlModel(span=L, modes=modes, omega=omega, mass=mass, rotary_speed=Om, points=x, kinds=kinds,
                      clearance=clearance, radius=radius, stiffness=K, phi=phi, eccentric=eccentric, side=side,
                      damping=damping, drag=float(drag), drag_shapes=shapes, drag_weights=0.5 * L * gw,
                      friction=mu, slip_velocity=float(option.slip_velocity),
                      restitution=e, hysteresis=calibrated_hysteresis(e), law=law,
                      penalty_stiffness=np.asarray(kp, float), penalty_damping=np.asarray(cp, float), props=props,
                      eccentricity=eps, frame=frame, hole_curvature=hole_curvature, basis=basis,
                      joint_mass=float(joint_mass), joint_weight=float(joint_side), point_side=point_side,
                      joint_points=at_joint if joint_mass > 0.0 and np.any(at_joint) else None)
    if option.reference_residual == "dynamic" and np.all(np.isfinite(omega)) and symmetric_points(x, L):
        # the modes left out as one residual vector per contact point in the kernel's modes, matched to their
        # flexibility and its second moment (their receptance f + g ω² + … at low frequency), the joints' mass on them;
        # docs/reference_model.md §2.1
        model.joint_x = joint_x if joint_mass > 0.0 else np.zeros(0)
        model.residual = residual_flexibility(model)
        model.residual_mass = residual_second_moment(model) / model.residual**2
        model.ritz = residual_ritz(model, 0.5 * L * (gx + 1),
                                   float(option.damping_ratio) if damping_model == "viscous" else 0.0)
    elif option.reference_residual != "none" and np.all(np.isfinite(omega)):
        # the modes left out respond to a contact force statically: their flexibility at the point in series with its
        # spring (the penalty's folded in, k/(1 + k f)); docs/reference_model.md §2.1. Also for "dynamic" where the
        # contact points do not lie symmetrically about the middle (the residual vectors would mix the modes' parities)
        model.residual = residual_flexibility(model)
        model.penalty_stiffness = model.penalty_stiffness / (1.0 + model.penalty_stiffness * model.residual)
    return model


def symmetric_points(x, span: float) -> bool:
    """Whether the contact points x [m] lie symmetrically about the periodic section's middle (x → L − x maps them
    onto themselves), as :func:`residual_ritz` needs."""
    x = np.asarray(x, float)
    L = float(span)
    gap = np.abs(np.mod(np.mod(L - x, L)[:, None] - x[None, :] + 0.5 * L, L) - 0.5 * L)
    return bool(np.all(np.min(gap, axis=1) <= 1e-9 * L))


def residual_ritz(model: WhirlModel, drag_points: np.ndarray, damping_ratio: float = 0.0) -> dict:
    """The kept modes augmented by one residual vector per contact point (modal truncation augmentation: Dickens,
    Nakagawa & Wittbrodt, Comput. Struct. 62, 985–998, 1997; the residual flexibility and mass of Rubin, AIAA J. 13,
    995–1006, 1975), the Rayleigh–Ritz modes of the two (docs/reference_model.md §2.1). Residual vector p is the static
    field of the modes left out under a unit force at contact point x_p, v_p(x) (:func:`static_correction`'s
    deflection: the periodic beam-column's less the kept modes'); with the coordinates (q, s), s_p [N] the force whose
    field v_p is, u(x) = Σ q_n φ_n(x) + Σ s_p v_p(x), the stiffness is diag(m ω_n²) ⊕ F, F_pq = v_p(x_q) (Maxwell–Betti:
    v_p is the left-out modes' flexibility), the mass m I ⊕ G + the tool joints' m_j at x_j on u(x_j) (their coupling
    of the kept modes and the vectors, m_j φ(x_j) v_p(x_j)), G_pq = Σ_{n≥N} ψ_n(x_p) ψ_n(x_q)/(m ω_n⁴)
    (:func:`residual_second_moments`). The kept modes and the vectors are each of one parity about the section's middle
    where the contact points are (pairs x, L − x: their sum and difference), so the modes are solved per parity and
    keep one, as the kernel's drag sums need. Raises ValueError where the contact points are not so
    (:func:`symmetric_points`; :func:`build_model` keeps the series law there).

    Returns omega2 (K,) with K = N + P, vectors (K, K) (column k: mode k on (q, σ), σ the vectors' parity
    combinations, s = C σ; scaled to the modal mass m), combinations C (P, P), inverse (K, K) (vectorsᵀ M/m: (q, σ) to
    the modes), and the kernel's phi (P, K), drag_shapes (G, K) at ``drag_points`` [m], eccentric and side (K,) per
    modal mass, damping (K,) 2ζω, weights (K,) of the error scale (1/n² of the half-waves of each mode's
    frequency)."""
    from scipy.linalg import eigh

    N, P, L, m = model.n_modes, model.points.size, model.span, model.mass
    x = model.points
    # the contact points' mirror images about the middle: pairs and points of their own
    mirror = np.mod(L - x, L)
    gap = np.abs(np.mod(mirror[:, None] - x[None, :] + 0.5 * L, L) - 0.5 * L)
    partner = np.argmin(gap, axis=1)
    if not symmetric_points(x, L):
        raise ValueError("reference_residual = 'dynamic': the contact points must lie symmetrically about the "
                         f"section's middle (x and L - x), at {np.round(x / L, 6).tolist()} of L")
    symmetric, antisymmetric = [], []
    for p in range(P):
        q = int(partner[p])
        e = np.zeros(P)
        if q == p:
            e[p] = 1.0
            symmetric.append(e)
        elif p < q:
            e[p], e[q] = np.sqrt(0.5), np.sqrt(0.5)
            symmetric.append(e.copy())
            e[q] = -np.sqrt(0.5)
            antisymmetric.append(e)
    combinations = np.column_stack(symmetric + antisymmetric)
    flexibility = static_correction(model, x)[:, :P]
    flexibility = 0.5 * (flexibility + flexibility.T)
    mass_rr = residual_second_moments(model)
    coupling = np.zeros((N, P))
    if model.joint_mass > 0.0 and model.joint_x.size:
        at_joints = static_correction(model, model.joint_x)[:, :model.joint_x.size]  # (P, J): v_p(x_j)
        coupling = model.joint_mass * model.shapes(model.joint_x).T @ at_joints.T
        mass_rr = mass_rr + model.joint_mass * at_joints @ at_joints.T
    K = N + P
    stiffness = np.zeros((K, K))
    stiffness[:N, :N] = np.diag(m * np.nan_to_num(model.omega) ** 2)
    stiffness[N:, N:] = combinations.T @ flexibility @ combinations
    mass = np.zeros((K, K))
    mass[:N, :N] = m * np.eye(N)
    mass[:N, N:] = coupling @ combinations
    mass[N:, :N] = mass[:N, N:].T
    mass[N:, N:] = combinations.T @ mass_rr @ combinations
    kept_symmetric = (model.modes == 0) | (model.modes % 2 == 1)
    n_sym = len(symmetric)
    rows_of = [np.concatenate((np.flatnonzero(kept_symmetric), N + np.arange(n_sym))),
               np.concatenate((np.flatnonzero(~kept_symmetric), N + np.arange(n_sym, P)))]
    omega2, vectors = np.zeros(K), np.zeros((K, K))
    column = 0
    for rows in rows_of:
        if rows.size == 0:
            continue
        values, vecs = eigh(stiffness[np.ix_(rows, rows)], mass[np.ix_(rows, rows)])
        vecs = vecs * np.sqrt(m)  # eigh's have yᵀ M y = 1
        rigid = rows == 0  # the rigid translation (kept mode 0): no stiffness, exactly a mode of its own
        if np.any(rigid) and model.omega[0] == 0.0:
            first = int(np.argmin(np.abs(values)))
            values[first] = 0.0
            vecs[:, first] = 0.0
            vecs[rigid, first] = 1.0
        span = slice(column, column + rows.size)
        omega2[span] = np.maximum(values, 0.0)
        vectors[np.ix_(rows, np.arange(column, column + rows.size))] = vecs
        column += rows.size
    kept, residual = vectors[:N], vectors[N:]
    phi = np.hstack((model.phi, flexibility @ combinations)) @ vectors
    at_drag = static_correction(model, np.asarray(drag_points, float))[:, :np.size(drag_points)]  # (P, G)
    drag_shapes = np.hstack((model.drag_shapes, at_drag.T @ combinations)) @ vectors
    side = kept.T @ model.side
    if model.point_side is not None:  # the joints' weight at the joints: on the vectors, Σ_q W_q v_p(x_q)
        side = side + residual.T @ (combinations.T @ (flexibility @ model.point_side)) / m
    omega = np.sqrt(omega2)
    ei, tn, M = (model.props[k] for k in ("bending_stiffness", "effective_tension", "mass_per_length"))
    wavenumber = np.sqrt(np.maximum((-tn + np.sqrt(tn**2 + 4 * ei * M * omega2)) / (2 * ei), 0.0))
    return dict(omega2=omega2, vectors=vectors, combinations=combinations, inverse=vectors.T @ mass / m, phi=phi,
                drag_shapes=drag_shapes, eccentric=kept.T @ model.eccentric, side=side,
                damping=2.0 * float(damping_ratio) * omega,
                weights=1.0 / np.maximum(wavenumber * L / np.pi, 1.0) ** 2)


@dataclass
class Window:
    """The motion recorded over the output window."""

    times: np.ndarray  #: (R,) [s]
    states: np.ndarray  #: (R, 4N + 4)
    forces: np.ndarray  #: (R, P, 3) F_y, F_z, F_n on the pipe [N]
    peak: np.ndarray  #: (P,) largest F_n [N]
    onsets: np.ndarray  #: (P,) contact onsets
    contact_time: np.ndarray  #: (P,) [s]
    any_contact_time: float  #: [s]
    start: float
    end: float
    #: (R, 4, P) the residual vectors' s_y, s_z, ṡ_y, ṡ_z [N, N/s] per row (None without them)
    residual: np.ndarray | None = None
    #: the kernel's first and last states (with the residual vectors; None without them), for the energy balance
    ends: tuple | None = None

    def correction_forces(self, model: "WhirlModel", direction: int) -> np.ndarray:
        """(R, P) the forces [N] whose static field of the modes left out completes the kept modes' (the quasi-static
        correction, :func:`static_correction`) in one direction: the contact forces on the pipe, or with the residual
        vectors their coordinates s_p (:func:`residual_ritz`: the field their motion is), less the joints' weight that
        :func:`periodic_fields` adds (it is in s_p already)."""
        if self.residual is not None and model.dynamic:
            forces = self.residual[:, direction, :]
            return forces - model.point_side if direction == 0 and model.point_side is not None else forces
        return self.forces[:, :, direction]


class Integrator:
    """Runs the compiled kernel on a model, keeping the contact state between calls; ``scheme`` one of
    :data:`SCHEMES` (option ``reference_integrator``: :func:`whirl_kernel.advance`). Raises ValueError for another."""

    def __init__(self, model: WhirlModel, rtol: float = 1e-6, state=None,
                 scheme: str = ReferenceOptions.default("reference_integrator")):
        if scheme not in SCHEMES:
            raise ValueError(f"reference_integrator = {scheme!r}; allowed: {', '.join(SCHEMES)}")
        self.model = model
        self.scheme = SCHEME_CODES[scheme]
        self.sy = whirl_kernel.kernel_system(model.system())
        N, P = model.kernel_modes, model.points.size
        # the kernel's state: with the residual vectors P more modes (WhirlModel.extend)
        self.z = model.extend(np.zeros(4 * model.n_modes + 4) if state is None else state)
        self.t = 0.0
        self.active = np.zeros(P, bool)
        self.chi = np.zeros(P)
        # a start on the wall (the string's rest, :func:`initial_state`): its contacts open, with the Hunt–Crossley
        # damping of the slowest onset (whirl_kernel.ONSET_SPEED_FLOOR), not counted as onsets
        y, w = model.kernel_phi @ self.z[:N], model.kernel_phi @ self.z[N:2 * N]
        self.active[:] = np.hypot(y, w) > model.clearance
        self.chi[self.active] = model.hysteresis / whirl_kernel.ONSET_SPEED_FLOOR
        self.rtol = float(rtol)
        # error scale weighted by 1/n^2: the bending moment weighs mode n by k_n^2, so its error is kept even
        self.scale = model.state_scale() * np.tile(model.weights, 4)
        if model.dynamic:  # the kernel's modes weighed by the half-waves of their frequencies
            c = float(np.max(model.clearance))
            self.scale = np.concatenate((np.full(2 * N, c), np.full(2 * N, model.rotary_speed * c))) * np.tile(
                model.ritz["weights"], 4)
        self.h = model.period / 1000.0
        # and, for Dormand-Prince on the whole right-hand side, within its stability interval on the imaginary axis
        # (about 3.3/omega): the error estimate alone lets an undamped high mode ring at the edge of it. The Lawson
        # form takes the modes' free motion exactly, at any step
        fastest = float(np.sqrt(np.max(model.ritz["omega2"]))) if model.dynamic else float(np.max(model.omega))
        self.h_stable = STABLE_STEP / max(fastest, 1e-300)  # (the rigid translation alone: none)
        self.h_max = model.period / 64.0 if scheme != "dopri5" else min(model.period / 64.0, self.h_stable)
        self.buffers = whirl_kernel.workspace(N, P, model.drag_weights.size)  #: the kernel's room, kept across runs
        self.steps = 0
        self.work = np.zeros(whirl_kernel.N_STATS)  #: the kernel's stats summed over the runs (whirl_kernel.S_*)
        self.outcome = whirl_kernel.OK

    def run(self, t_end: float, record: bool = False, rows_per_revolution: int = 256,
            max_steps: int = 2_000_000) -> Window:
        P = self.model.points.size
        stats, peak, onsets, ctime = np.zeros(whirl_kernel.N_STATS), np.zeros(P), np.zeros(P, np.int64), np.zeros(P)
        tau = self.model.period
        revs = max((t_end - self.t) / tau, 1e-9)
        cap = int(rows_per_revolution * 16 * revs) + 16 if record else 1
        rec_t = np.empty(cap)  # rows written by the kernel before they are read (the first n_rec)
        rec_z = np.empty((cap, self.z.size))
        rec_f = np.empty((cap, P, 3))
        rec_dt = np.array([tau / rows_per_revolution, tau / (16 * rows_per_revolution)])
        start = self.t
        t, h, outcome, n_rec, steps = whirl_kernel.advance(
            self.t, t_end, self.z, self.active, self.chi, self.h, self.sy, self.buffers, self.rtol, self.scale,
            self.h_max, max_steps, stats, peak, onsets, ctime, record, rec_dt, rec_t, rec_z, rec_f, 0, self.scheme,
            self.h_stable)
        self.t, self.h, self.outcome = t, h, outcome
        self.steps += steps
        self.work += stats
        # the rows written, copied: the buffers (room for a contact all the way) are freed
        rows = rec_z[:n_rec]
        return Window(times=rec_t[:n_rec].copy(), states=self.model.reduce(rows).copy(), forces=rec_f[:n_rec].copy(),
                      peak=peak, onsets=onsets, contact_time=ctime, any_contact_time=float(stats[0]), start=start,
                      end=t, residual=self.model.residual_coordinates(rows) if self.model.dynamic else None,
                      ends=(rows[0].copy(), rows[-1].copy()) if self.model.dynamic and n_rec else None)

    def modal_state(self) -> np.ndarray:
        """The modal state (4N,) now, without the power integrals and the residual oscillators."""
        return self.model.reduce(self.z)[:4 * self.model.n_modes].copy()


def initial_state(model: WhirlModel, kind: str = "forced") -> np.ndarray:
    """The state the run starts from (4N + 4,): ``"rest"`` the centred pipe at rest; ``"forced"`` (default)
    where a side load lays the string on the wall, its rest there (the sliding method's static equilibrium on the
    touching points, :func:`study.solvers.sliding.rest`: every joint on the low side); without a side load the
    synchronous forward whirl without walls, Q_n e^{iΩt} with Q_n = ε_n/(ω_n² − Ω² + iΩ d_n) (the modal Jeffcott
    response; linear damping only; a uniform eccentricity drives the rigid translation alone), scaled down as a
    whole until every contact point is clear of its wall. It removes the start-up ringing of the low modes,
    which the quadratic drag damps slowly at small amplitude; with no drive it is the centred pipe at rest too."""
    N = model.n_modes
    z = np.zeros(4 * N + 4)
    if kind == "rest":
        return z
    om = model.rotary_speed
    if np.any(model.side != 0.0):
        from study.solvers import sliding  # it builds on this module

        rested = sliding.rest(model)
        if rested["found"]:
            z[:2 * N] = rested["state"]
            return z
        # no equilibrium found: the rigid translation laid onto the low side at the joints' clearance
        z[0] = float(np.min(model.clearance[model.kinds == 1] if np.any(model.kinds == 1) else model.clearance)
                     / model.phi[0, 0])
        return z
    with np.errstate(divide="ignore", invalid="ignore"):
        Q = model.eccentric / (model.omega**2 - om**2 + 1j * om * model.damping)
    Q = np.where(np.isfinite(Q), Q, 0.0)
    z[:N], z[N:2 * N] = Q.real, Q.imag
    velocity = 1j * om * Q
    z[2 * N:3 * N], z[3 * N:4 * N] = velocity.real, velocity.imag
    reach = np.hypot(model.phi @ z[:N], model.phi @ z[N:2 * N])
    if np.any(reach > 0):
        z[:4 * N] *= min(1.0, 0.99 * float(np.min(model.clearance / np.maximum(reach, 1e-300))))
    return z


#: The design figures whose convergence the error estimate states, with the names of their largest values seen
#: in the window and what the message calls them (docs/reference_model.md §3.1).
FIGURES = {"peak_contact_force": ("window_largest_contact_force", "peak force"),
           "max_normal_stress": ("window_largest_normal_stress", "max normal stress"),
           "alternating_bending_stress": ("window_largest_alternating_stress", "alternating stress"),
           "max_deflection": ("window_largest_deflection", "max deflection")}
#: The statistic of the fatigue damage beside :data:`FIGURES`: Miner's damage per cycle of the worst fibre's stress
#: history, counted by rainflow (:func:`fibre_damage`), named as the output it is reported as (per second; its
#: relative error the same), whose inverse is the fatigue life.
DAMAGE = "damage_rate"
#: Fibres round the pipe, evenly from ψ = 0, whose stress histories the damage is counted on, the worst of them the
#: figure. Where the bending stands in the hole's frame and the pipe turns through it every fibre sees the same
#: history; where it turns with the pipe (a whirl) the fibre nearest the worst may lie π/8 off it, its amplitude
#: cos(π/8) = 0.92 of the worst's, its damage 0.92^5 = 0.67 (and in a chaotic bouncing the fibres are alike on
#: average).
DAMAGE_FIBRES = 8
#: Standard errors in a figure's window part: a mean's stated error is a bound at about 95 % (two standard errors of a
#: normal mean), not its 1-sigma scatter, which a figure passes at one point in three; the held-back check of the
#: stated errors (``study coverage``, docs/validation.md) asks them to cover the true difference at 90 % of points.
CONFIDENCE = 2.0
#: The record is still settling where a figure's window mean differs from the preceding stretch's by more than
#: this many of their combined standard errors (a two-sided z-test at about 95 %).
DRIFT_SIGNIFICANCE = 2.0
#: A run not converged goes on to its budget unless it foresees more than this many times the budget: a forecast from
#: the scatter of a short record is itself uncertain by about a factor 2 (the standard error of 12 revolutions rests
#: on three batches), and one that gave up at the first look's forecast left 246 of the default grid's 301 bouncing
#: points short of 5 % (docs/reference_model.md §3.1).
FORECAST_SLACK = 2.0
#: The largest per-revolution settling ratio :func:`settle_ratio` states: a drift over h revolutions that shrinks
#: by 1 % a revolution is taken to have 1/(1 − 0.99^h) times itself still to come.
MAX_SETTLE_RATIO = 0.99


def stationary(peaks, impacts, states, scale, n: int) -> bool:
    """Whether a motion that has not repeated is done with its transient: it bounces — contact onsets in at least a
    third of the revolutions of each of the last two stretches of n revolutions —, the means of each revolution's
    largest contact force and of its contact onsets over those two stretches differ by no more than
    :data:`DRIFT_SIGNIFICANCE` of their combined standard errors (:func:`standard_error`), and the state's changes
    from one revolution boundary to the next do not shrink beyond doubt (:func:`settle_ratio`): a chaotic
    bouncing, whose statistics are stationary, and not a motion still settling towards a rest, a slide or a
    cycle (docs/reference_model.md §3.1). The first n revolutions (the start-up, whose scatter would hide any
    drift) are never in the two stretches: False before 3n revolutions."""
    if len(peaks) < 3 * n:
        return False
    if min(np.count_nonzero(impacts[-2 * n:-n]), np.count_nonzero(impacts[-n:])) < n / 3:
        return False  # too few strikes: lying or sliding on the wall, or clear of it, not bouncing
    for series in (impacts, peaks):
        before, last = np.asarray(series[-2 * n:-n], float), np.asarray(series[-n:], float)
        spread = np.hypot(*(standard_error(x) if np.ptp(x) > 0 else 0.0 for x in (before, last)))
        if abs(np.mean(last) - np.mean(before)) > DRIFT_SIGNIFICANCE * spread:
            return False
    return not np.isfinite(settle_ratio(states, scale))


def merge(windows: list[Window]) -> Window:
    """One window from consecutive ones (their recordings joined, their counts added)."""
    residual = (np.concatenate([w.residual for w in windows])
                if all(w.residual is not None for w in windows) else None)
    return Window(times=np.concatenate([w.times for w in windows]), states=np.concatenate([w.states for w in windows]),
                  forces=np.concatenate([w.forces for w in windows]), peak=np.max([w.peak for w in windows], axis=0),
                  onsets=np.sum([w.onsets for w in windows], axis=0),
                  contact_time=np.sum([w.contact_time for w in windows], axis=0),
                  any_contact_time=float(sum(w.any_contact_time for w in windows)), start=windows[0].start,
                  end=windows[-1].end, residual=residual,
                  ends=(windows[0].ends[0], windows[-1].ends[1])
                  if residual is not None and windows[0].ends is not None and windows[-1].ends is not None else None)


def cycle_values(inputs: Mapping[str, Any], model: WhirlModel, cycles: list[Window]) -> list[dict[str, Any]]:
    """The outputs of each of consecutive cycles of the motion (a revolution, or the period when periodic):
    :func:`stresses` (with the quasi-static correction of the modes left out wherever a contact force acts,
    :func:`quasi_static_applies`; the fields computed once) and the peak contact force, exact at every step of the
    integrator; ``correction`` says whether the correction entered, ``start`` is the cycle's start [s]; :data:`DAMAGE` the Miner's
    damage of each of :data:`DAMAGE_FIBRES` fibres in the cycle (F,), counted by rainflow over the cycles' joined
    history at the section of their largest alternating stress (:func:`fibre_damage`)."""
    joined = merge(cycles)
    correction = quasi_static_applies(model, joined)
    ends = np.cumsum([c.times.size for c in cycles])
    segments = list(zip(np.concatenate(([0], ends[:-1])), ends))
    values = stresses(inputs, model, joined, correction=correction, segments=segments)
    station = values[int(np.argmax([v["alternating_bending_stress"] for v in values]))]["alternating_bending_stress_x"]
    damage = fibre_damage(inputs, model, joined, station, [first for first, _ in segments], correction)
    return [dict(v, peak_contact_force=float(np.max(c.peak)), correction=correction, start=c.start, **{DAMAGE: d})
            for v, c, d in zip(values, cycles, damage)]


def fibre_stress(inputs: Mapping[str, Any], model: WhirlModel, window: Window, station: float,
                 correction: bool = True, fibres: int = DAMAGE_FIBRES) -> np.ndarray:
    """(R, F) the normal stress [Pa] of ``fibres`` fibres of the turning pipe, at ψ = 2πk/F from the fibre that
    faces +y at t = 0, at the section x = ``station`` [m] over the window's rows: T0/A_s plus
    (M_y cos(Ωt + ψ) + M_z sin(Ωt + ψ)) r_o/I (the moments of :func:`periodic_fields`, with the quasi-static
    correction where ``correction``; the fibre stress whose half range over a cycle is the alternating stress of
    :func:`stresses`)."""
    N = model.n_modes
    x = np.array([float(station)])
    moments = [periodic_fields(model, window.states[:, j * N:(j + 1) * N], window.correction_forces(model, j)
                               if correction else None, x, j)["moment"][:, 0] for j in range(2)]
    r_o, r_i = inputs["outer_diameter"] / 2.0, inputs["inner_diameter"] / 2.0
    scale = r_o / float(section.second_moment_of_area(r_o, r_i))
    angle = model.rotary_speed * window.times[:, None] + 2.0 * np.pi * np.arange(fibres)[None, :] / fibres
    bending = moments[0][:, None] * np.cos(angle) + moments[1][:, None] * np.sin(angle)
    return inputs["axial_tension"] / model.props["steel_area"] + scale * bending


def fibre_damage(inputs: Mapping[str, Any], model: WhirlModel, window: Window, station: float, starts,
                 correction: bool = True) -> np.ndarray:
    """(S, F) Miner's damage [-] in each of the stretches that begin at the window's rows ``starts`` (its cycles), of
    each fibre of :func:`fibre_stress` at x = ``station`` [m]: the fibre's stress history over the whole window
    counted by rainflow (ASTM E1049, :func:`study.physics.limits.history_damage` with the point's strengths, stress
    concentration, S-N curve and mean-stress correction), each cycle's damage spread over the stretches the time
    between its two reversals spans, so that several cycles a revolution (impacts ringing the pipe) count each, a
    periodic motion's revolutions get the same damage, and the stretches' damages sum to the window's."""
    stress = fibre_stress(inputs, model, window, station, correction)
    options = limit_options(inputs)
    return np.column_stack([limits.history_damage(stress[:, k], starts, at=window.times, **options)
                            for k in range(stress.shape[1])])


def window_summary(cycles: list[Mapping[str, Any]], stats: Mapping[str, Mapping[str, Any]]) -> dict[str, Any]:
    """The stress outputs of the window from its cycles' (:func:`cycle_values`): the design figures as
    :func:`settling` states them (the mean over the cycles) and their largest values; the max bending stress
    the mean of the cycles' too (so that normal = axial + bending holds); the largest shear stress over the
    window (a bound); positions and times (from the window's start) of the cycle with the
    largest normal (alternating) stress; the modal tail and quarter fractions the means over the cycles;
    ``correction`` whether the quasi-static correction was applied in every cycle."""
    out = {name: s["value"] for name, s in stats.items()}
    out.update({largest: stats[name]["largest"] for name, (largest, _) in FIGURES.items()})
    origin = cycles[0]["start"]
    worst = cycles[int(np.argmax([c["max_normal_stress"] for c in cycles]))]
    alternating = cycles[int(np.argmax([c["alternating_bending_stress"] for c in cycles]))]
    sheared = cycles[int(np.argmax([c["max_shear_stress"] for c in cycles]))]
    out.update(max_bending_stress=float(np.mean([c["max_bending_stress"] for c in cycles])),
               max_wall_excess=float(np.max([c["max_wall_excess"] for c in cycles])),
               max_normal_stress_x=worst["max_normal_stress_x"],
               max_normal_stress_t=worst["max_normal_stress_t"] + worst["start"] - origin,
               alternating_bending_stress_x=alternating["alternating_bending_stress_x"],
               max_shear_stress=sheared["max_shear_stress"], max_shear_stress_x=sheared["max_shear_stress_x"],
               max_shear_stress_t=sheared["max_shear_stress_t"] + sheared["start"] - origin,
               modal_tail_fraction=float(np.mean([c["modal_tail_fraction"] for c in cycles])),
               modal_quarter_fraction=float(np.mean([c["modal_quarter_fraction"] for c in cycles])),
               correction=all(c["correction"] for c in cycles))
    return out


def standard_error(x) -> float:
    """Standard error of the mean of the series x: the larger of the batch-means estimate (batches of ⌊√n⌋
    consecutive values, the first values dropped to make them whole; Schmeiser 1982, doi:10.1287/opre.30.3.556),
    which holds where consecutive values are correlated, and the plain s/√n, which is steadier where the batches
    are few. 0 for a constant series, NaN for fewer than two values."""
    x = np.asarray(x, float)
    if x.size < 2:
        return float("nan")
    plain = float(np.std(x, ddof=1) / np.sqrt(x.size))
    size = max(1, int(np.sqrt(x.size)))
    count = x.size // size
    if count < 2:
        return plain
    means = x[x.size - count * size:].reshape(count, size).mean(axis=1)
    return max(plain, float(np.std(means, ddof=1) / np.sqrt(count)))


def settle_ratio(states, scale) -> float:
    """Per-revolution ratio ρ by which the change of the state from one revolution boundary to the next shrinks
    while the motion settles, taken at the slow end of what the data allow: exp of the least-squares slope of the
    change's logarithm over the later half of the revolutions run, plus two of its standard errors, at most
    :data:`MAX_SETTLE_RATIO`. NaN where the changes do not shrink beyond doubt (that bound is 1 or more: a
    stationary or wandering motion) or there are fewer than six of them."""
    S = np.asarray(states) / scale
    change = np.max(np.abs(np.diff(S, axis=0)), axis=1)
    change = change[change.size // 2:]
    k = np.flatnonzero(change > 0)
    if k.size < 6:
        return float("nan")
    (slope, _), cov = np.polyfit(k, np.log(change[k]), 1, cov=True)
    upper = float(np.exp(slope + 2.0 * np.sqrt(cov[0, 0])))
    return min(upper, MAX_SETTLE_RATIO) if upper < 1.0 else float("nan")


def settling(window: list[Mapping[str, Any]], preceding: list[Mapping[str, Any]],
             ratio: float = float("nan")) -> dict[str, dict[str, Any]]:
    """Per design figure (:data:`FIGURES`, and :data:`DAMAGE` where the cycles carry it: per fibre, the fibre of the
    largest mean over the window taken, ``fibre``), from its per-cycle values over the window and the preceding
    stretch of equal length (empty when the motion is periodic, or taken as stationary): ``value`` (the mean over
    the window's cycles), ``largest`` (over them), ``error`` (relative standard error of the mean by batch means),
    ``drift`` (relative difference of the window's and the preceding stretch's means), ``significant`` (that
    difference is more than :data:`DRIFT_SIGNIFICANCE` combined standard errors: still settling) and ``window``, the
    window's part of the figure's error: the larger of :data:`CONFIDENCE` standard errors and the drift, and where the motion
    settles (the state's changes shrink by ``ratio`` ρ a revolution, :func:`settle_ratio`) with the drifts still to
    come if they shrink alike, drift/(1 − ρ^h) for a window of h revolutions."""
    out = {}
    h = len(window)
    settles = bool(np.isfinite(ratio))  # the state's changes shrink: it settles
    for name in (*FIGURES, DAMAGE):
        if name not in window[0]:
            continue
        x = np.array([v[name] for v in window], float)
        fibre = None
        if x.ndim == 2:  # the damage per fibre: the fibre of the largest mean over the window
            fibre = int(np.argmax(np.mean(x, axis=0)))
            x = x[:, fibre]
        value, largest = float(np.mean(x)), float(np.max(x))
        size = max(abs(value), 1e-300)
        error = standard_error(x) if np.ptp(x) > 0 else 0.0
        drift, significant = 0.0, False
        if preceding:
            before = np.array([v[name] for v in preceding], float)
            before = before[:, fibre] if fibre is not None else before
            change = abs(value - float(np.mean(before)))
            spread = np.hypot(np.nan_to_num(error, nan=np.inf), standard_error(before) if np.ptp(before) > 0 else 0.0)
            drift, significant = change / size, bool(change > DRIFT_SIGNIFICANCE * spread)
        error = error / size if np.isfinite(error) else np.inf
        part = max(CONFIDENCE * error, drift / (1.0 - ratio**h) if settles else drift)
        out[name] = dict(value=value, largest=largest, error=error, drift=drift, significant=significant,
                         window=float(part))
        if fibre is not None:
            out[name]["fibre"] = fibre
    return out


#: The figures whose modal part :func:`modal_check` measures: the design figures, the bending stress and the deflection.
MODAL_FIGURES = ("peak_contact_force", "max_normal_stress", "alternating_bending_stress", "max_bending_stress",
                 "max_deflection")


def quasi_static_ratio(model: WhirlModel, window: Window) -> float:
    """(2π/(ω_{N+1} T_c))², at most 1: how far the first mode left out is from responding statically to the window's
    contacts, T_c the shortest mean contact (contact time over onsets per touching point; the window's length for a
    contact held throughout). A mode of frequency ω under a force that changes over a time T responds statically but
    for a remainder of relative size (2π/(ω T))² (its static response's second derivative over ω²); a held contact's
    is nil, an impact's (shorter than that mode's period) the whole. 0 without contact."""
    touching = window.contact_time > 0
    if not np.any(touching):  # clear of the wall: the joints' inertia forces corrected, their frequency Ω's
        if model.joint_points is None or np.any(window.onsets > 0):
            return 0.0
        return float(min(1.0, (model.rotary_speed / model.first_left_out()) ** 2))
    durations = window.contact_time[touching] / np.maximum(window.onsets[touching], 1)
    ratio = 2.0 * np.pi / (model.first_left_out() * float(np.min(durations)))
    return float(min(1.0, ratio**2))


def modal_check(inputs: Mapping[str, Any], model: WhirlModel, window: Window,
                cycles: list[Mapping[str, Any]]) -> dict[str, float]:
    """The modal part of each figure's error (relative), measured on the run (docs/reference_model.md §3.1): the size
    of what the modes left out were given — the quasi-static correction of the fields and the residual flexibility in
    series with the contacts (:func:`residual_flexibility`) — times :func:`quasi_static_ratio`, how far they are from
    responding statically (1 at impacts: the whole correction; nil for held contacts, where it is exact). Stresses
    and deflection: the cycles' figures recomputed from the same motion and forces without the correction, the mean
    over the cycles of each cycle's difference over the figure's mean (the largest deflection: its difference).
    Peak contact force: at each cycle's largest recorded force, the Hertz force K d^{3/2} at the contact's total
    approach d against the series force there (:func:`series_contact`), the mean of their relative differences: how
    much the flexibility of the modes left out softened the contact. Both vanish as the modes grow (the residual
    flexibility like N⁻³). Zeros without contact."""
    out = dict.fromkeys(MODAL_FIGURES, 0.0)
    ratio = quasi_static_ratio(model, window)
    if not cycles or window.times.size == 0 or ratio == 0.0:
        return out
    first = np.searchsorted(window.times, [c["start"] for c in cycles])
    segments = list(zip(first, list(first[1:]) + [window.times.size]))
    plain = stresses(inputs, model, window, correction=False, segments=segments)
    for name in ("max_normal_stress", "alternating_bending_stress", "max_bending_stress"):
        mean = float(np.mean([c[name] for c in cycles]))
        if name == "alternating_bending_stress":  # relative to the bending it alternates within (convergence)
            mean = max(mean, float(np.mean([c["max_bending_stress"] for c in cycles])))
        if mean > 0:
            out[name] = ratio * float(np.mean([abs(a[name] - c[name]) for a, c in zip(plain, cycles)]) / mean)
    largest = max(c["max_deflection"] for c in cycles)
    if largest > 0:
        out["max_deflection"] = ratio * abs(max(a["max_deflection"] for a in plain) - largest) / largest
    # the peak force: the Hertz force at each cycle's largest recorded force's total approach against the series one
    N = model.n_modes
    flexibility = model.flexibility if np.any(model.flexibility > 0) else residual_flexibility(model)
    fn = window.forces[:, :, 2]
    changes = []
    for a, b in segments:
        if b <= a or not np.any(fn[a:b] > 0):
            continue
        row, p = np.unravel_index(int(np.argmax(fn[a:b])), fn[a:b].shape)
        q = window.states[a + row]
        d = float(np.hypot(model.phi[p] @ q[:N], model.phi[p] @ q[N:2 * N]) - model.clearance[p])
        if d <= 0:
            continue
        series = float(series_contact(np.array([d]), model.stiffness[p], flexibility[p])[1][0])
        hertz = float(hertz_force(d, model.stiffness[p]))
        if model.law == 0 and series > 0:
            changes.append(hertz / series - 1.0)
    out["peak_contact_force"] = ratio * float(np.mean(changes)) if changes else 0.0
    return out


#: A bending stress below this share of the max normal stress is nothing (the rounding of a string whirling as a
#: rigid body): its error parts are counted relative to the normal stress (:func:`convergence`).
NEGLIGIBLE_BENDING = 1e-9


def convergence(inputs: Mapping[str, Any], model: WhirlModel, window: Window, values: Mapping[str, Any],
                stats: Mapping[str, Mapping[str, Any]], periodic: bool, residual: float | None = None,
                modal: Mapping[str, float] | None = None) -> dict:
    """The error of each design figure by its parts (relative; docs/reference_model.md §3.1): ``window`` (the
    larger of the standard error and the drift from the preceding stretch; the periodicity tolerance when the
    motion is periodic), ``integrator`` (the larger of rtol and the energy balance's residual over the window,
    which is whole but with ``reference_damping = "viscous"``),
    ``modes`` (measured on the run, :func:`modal_check`, given as ``modal``; 0 where not given); ``total`` their
    sum. The alternating stress's error is relative to the larger of it and the max bending stress."""
    option = ReferenceOptions.from_inputs(inputs)
    # the energy balance is whole only without the linear modal damping of "viscous", whose loss is not integrated
    whole = residual is not None and option.reference_damping != "viscous"
    integrator = max(float(option.reference_rtol), abs(residual) if whole else 0.0)
    normal = values["max_normal_stress"]
    modes = {name: float((modal or {}).get(name, 0.0)) for name in FIGURES}
    # an alternating stress far below the bending stress (a synchronous whirl's remnant) is counted relative to the
    # bending it alternates within, as the modal part is: its relative size alone would make noise of nothing; and a
    # bending stress below NEGLIGIBLE_BENDING of the normal stress (the rounding of a string whirling as a rigid body,
    # 1e-11 Pa) relative to that
    floor = NEGLIGIBLE_BENDING * normal
    if values["max_bending_stress"] < floor:
        modes = {name: 0.0 for name in modes}
    scale = {"alternating_bending_stress": max(values["alternating_bending_stress"], values["max_bending_stress"],
                                               floor)}
    # the damage goes as the stress to the S-N curve's power m: the stresses' integrator and modal parts as damage
    exponent = fatigue.damage_exponent(inputs.get("sn_curve") or "B1")
    modes[DAMAGE] = (1.0 + modes["alternating_bending_stress"]) ** exponent - 1.0
    # the damage rate goes as the alternating stress to the power m: its window part, as the stress error that makes
    # it, is counted relative to the bending the stress alternates within, as the alternating stress's is (a
    # synchronous whirl's remnant of tens of Pa has a damage rate whose relative scatter is large and means nothing)
    alternating_share = min(1.0, values["alternating_bending_stress"] / scale["alternating_bending_stress"]
                            if scale["alternating_bending_stress"] > 0 else 1.0)
    out = {}
    for name, s in stats.items():
        share = abs(s["value"]) / scale[name] if scale.get(name, 0) > 0 else 1.0
        window_part = float(option.reference_tolerance) if periodic else s["window"] * share
        if name == DAMAGE and not periodic:
            window_part = (1.0 + stress_equivalent(DAMAGE, s["window"], exponent) * alternating_share) ** exponent - 1.0
        own = (1.0 + integrator) ** exponent - 1.0 if name == DAMAGE else integrator
        parts = dict(window=window_part, integrator=own, modes=modes[name])
        total = float(sum(parts.values()))
        out[name] = dict(parts, total=total, dominant=max(parts, key=parts.get),
                         equivalent=stress_equivalent(name, total, exponent))
    return out


def stress_equivalent(name: str, error: float, exponent: float) -> float:
    """A figure's relative error as the stress error that makes it: the damage's (:data:`DAMAGE`) (1 + e)^(1/m) − 1
    (D ∝ σ^m), the stress figures' and the force's the error itself. The point's ``error_estimate`` is the largest
    of these, held against the tolerance as a stress error."""
    return float((1.0 + error) ** (1.0 / exponent) - 1.0) if name == DAMAGE else float(error)


def figure_tolerance(name: str, tolerance: float, exponent: float) -> float:
    """The relative error a figure may have at the stress ``tolerance``: the damage's (:data:`DAMAGE`)
    (1 + tolerance)^m − 1 (27.6 % for 5 % on m = 5), the others' the tolerance."""
    return float((1.0 + tolerance) ** exponent - 1.0) if name == DAMAGE else float(tolerance)


def simulate(inputs: Mapping[str, Any], model: WhirlModel | None = None) -> dict[str, Any]:
    """Transient until periodic, stationary bouncing (:func:`stationary`) or ``reference_revolutions``, then the
    recorded window, extended while its
    figures have not converged (docs/reference_model.md §3.1).

    Periodic: the window is ``reference_window`` revolutions rounded up to whole periods, its cycles the
    periods. Not periodic: the last ``reference_window`` revolutions of the transient are recorded too, and the
    record (one cycle a revolution) grows while the error of a design figure (:func:`convergence`) is above its
    tolerance (:func:`figure_tolerance` of ``solver.statistical_tolerance``), more revolutions could bring it there
    (its window part is what is over; not foreseen beyond :data:`FORECAST_SLACK` times the budget) and
    ``reference_max_revolutions`` allow, by the revolutions foreseen, at least ``reference_window`` and at most the
    record's length at a time. Where the record's halves agree (no drift beyond :data:`DRIFT_SIGNIFICANCE`) and the
    state does not settle the window is the whole record; else the window is its second half, the preceding stretch
    its first, and where they differ significantly (still settling) the first half is dropped.

    Returns model, integrator, verdict ('periodic', 'not_periodic', 'failed'), period (revolutions or None),
    revolutions (before the window), window (:class:`Window` or None), cycles and preceding (per-cycle values
    of the window and of the stretch before it, :func:`cycle_values`), budget_spent (stopped over the tolerance:
    the budget would not do), revolutions_needed (the revolutions in all foreseen to bring every figure within
    the tolerance; inf where more would not), ratio (:func:`settle_ratio`), failure (text or None), stationary
    (the transient ended as the bouncing was found stationary), modal (:func:`modal_check` of the
    window), stats (:func:`settling` of the window as the last look took it; None when periodic).
    """
    option = ReferenceOptions.from_inputs(inputs)
    model = model or build_model(inputs)
    start = initial_state(model, option.reference_initial)
    run = Integrator(model, float(option.reference_rtol), start, option.reference_integrator)
    tau = model.period
    revolutions = int(option.reference_revolutions)
    n_window = int(option.reference_window)
    budget = int(option.reference_max_revolutions)
    tolerance = statistical_tolerance(inputs)  # the window grows only where the motion does not repeat: means
    exponent = fatigue.damage_exponent(inputs.get("sn_curve") or "B1")
    tol = float(option.reference_tolerance)
    N = model.n_modes
    scale = model.state_scale()
    states = [run.modal_state()]
    period = None
    ratio = float("nan")

    def failed(where: str) -> dict[str, Any]:
        return dict(model=model, integrator=run, verdict="failed", period=None, revolutions=len(states) - 1,
                    window=None, cycles=[], preceding=[], budget_spent=False,
                    failure=f"{whirl_kernel.OUTCOMES[run.outcome]} {where}")

    kept: list[Window] = []  # the transient's last revolutions, recorded
    peaks, impacts = [], []  # each revolution's largest contact force [N] and contact onsets
    bouncing = False  # the transient ended on stationary bouncing
    for k in range(1, revolutions + 1):
        # the last revolutions are kept: n_window where the transient ends at the last, 2 n_window where a
        # stationary bouncing ends it (from 3 n_window on): those are its window and the stretch before it
        keep = k > min(n_window, revolutions - n_window)
        cycle = run.run(k * tau, record=keep)
        if run.outcome != whirl_kernel.OK:
            return failed(f"in revolution {k}")
        if keep:
            kept = (kept + [cycle])[-2 * n_window:]
        peaks.append(float(np.max(cycle.peak)) if cycle.peak.size else 0.0)
        impacts.append(float(np.sum(cycle.onsets)))
        states.append(run.modal_state())
        if np.max(np.abs(states[-1]) / scale) == 0.0:  # nothing moves
            period = 1 if k >= 2 else None
        else:
            period = settled_period(states, scale, tol)
        if period is not None:
            break
        if k % n_window == 0 and stationary(peaks, impacts, states, scale, n_window):
            bouncing = True
            break
    done = len(states) - 1
    budget_spent, needed = False, float(done)
    if period:
        blocks = []
        for _ in range(max(1, int(np.ceil(n_window / period)))):
            blocks.append(run.run(run.t + period * tau, record=True))
            if run.outcome != whirl_kernel.OK:
                return failed("in the output window")
        window_cycles, preceding, window = list(zip(blocks, cycle_values(inputs, model, blocks))), [], merge(blocks)
        modal = modal_check(inputs, model, window, [v for _, v in window_cycles])
    else:
        # (cycle, its values) per recorded revolution: a stationary bouncing has its window and the stretch before
        # it recorded already (the two stretches :func:`stationary` compared); else the transient's last n_window
        kept = kept if bouncing else kept[-n_window:]
        record: list[tuple[Window | None, dict[str, Any]]] = list(zip(kept, cycle_values(inputs, model, kept)))
        first = 0  # the record's first revolution
        step = 0 if bouncing else n_window  # revolutions to add before the next look
        while True:
            added = []
            for _ in range(step):
                added.append(run.run(run.t + tau, record=True))
                if run.outcome != whirl_kernel.OK:
                    return failed("in the output window")
                states.append(run.modal_state())
            if added:
                record += zip(added, cycle_values(inputs, model, added))
                live = record[first:]  # the cycles still recorded: one decision on the correction for them all
                if len({values["correction"] for _, values in live}) > 1:
                    record[first:] = zip([c for c, _ in live], cycle_values(inputs, model, [c for c, _ in live]))
            half = (len(record) - first) // 2
            preceding = [v for _, v in record[len(record) - 2 * half:len(record) - half]]
            window_cycles = record[len(record) - half:]
            ratio = settle_ratio(states, scale)
            stats = settling([v for _, v in window_cycles], preceding, ratio)
            stationary_record = not np.isfinite(ratio) and not any(s["significant"] for s in stats.values())
            if stationary_record:
                # the halves agree and nothing settles: the figures are means over the whole record, their window
                # part its standard error; the halves' drifts are kept as what they were (window_spread)
                whole = settling([v for _, v in record[len(record) - 2 * half:]], [], ratio)
                stats = {name: dict(whole[name], drift=stats[name]["drift"]) for name in whole}
                window_cycles, preceding = record[len(record) - 2 * half:], []
            window = merge([c for c, _ in window_cycles])
            cycles = [v for _, v in window_cycles]
            modal = modal_check(inputs, model, window, cycles)
            errors = convergence(inputs, model, window, window_summary(cycles, stats), stats, periodic=False,
                                 modal=modal)
            used = len(states) - 1
            more = 0.0  # the revolutions more that the figures over the tolerance need, as far as can be foreseen
            for name, e in errors.items():
                limit = figure_tolerance(name, tolerance, exponent)
                room = limit - (e["total"] - e["window"])  # what the window part may be
                if e["total"] <= limit:
                    continue
                if room <= 0:
                    more = np.inf  # the integrator or the modes take it over: more revolutions do not help
                elif np.isfinite(ratio) and e["window"] > CONFIDENCE * stats[name]["error"]:  # settling: drifts shrink by ρ
                    more = max(more, np.log(room / e["window"]) / np.log(ratio) if ratio > 0 else 0.0)
                else:  # the standard error falls as the root of the window's length (half the record's if settling)
                    length = len(window_cycles) * (1 if stationary_record else 2)
                    if bouncing and e["window"] > CONFIDENCE * stats[name]["error"]:
                        # a stationary bouncing's halves' drift, not a standard error (its intermittency): no root law
                        # foresees it (it vanishes once the halves agree and the window is the whole record), so one
                        # record's length more and look again (a slide that settles slowly keeps the forecast)
                        more = max(more, float(length))
                    else:
                        more = max(more, length * ((e["window"] / room) ** 2 - 1.0))
            needed = used + more
            if more == 0.0 or used >= budget or used + more > FORECAST_SLACK * budget:
                budget_spent = more > 0.0
                break
            # on towards where the figures are foreseen to be within the tolerance, at least a window more and at most
            # the record's length again (a forecast from a short record's scatter is itself rough): few looks; the
            # budget is spent where the forecast is within FORECAST_SLACK of it
            step = int(np.ceil(min(max(more, n_window), max(len(record) - first, n_window), budget - used)))
            if any(s["significant"] for s in stats.values()):
                first = len(record) - half  # still settling: drop the first half
            for i in range(first):
                record[i] = (None, record[i][1])  # free the recordings no longer needed
        done = used - len(window_cycles)
    return dict(model=model, integrator=run, verdict="periodic" if period else "not_periodic", period=period,
                revolutions=done, window=window, cycles=[v for _, v in window_cycles], preceding=preceding,
                budget_spent=budget_spent, revolutions_needed=float(needed), ratio=ratio, failure=None,
                stationary=bouncing, modal=modal, stats=None if period else stats)


# --- outputs -----------------------------------------------------------------------------------------


def whirl_measure(model: WhirlModel, window: Window) -> dict[str, Any]:
    """Whirl rate over Ω of the most-touching contact point (midspan without contact) and its verdict:
    no_contact; sliding (in contact nearly all the time, |rate| < 0.05 Ω: lying on the wall); forward
    (rate > 0.5 Ω); backward (rate < −0.5 Ω); otherwise bouncing (impacts without a settled whirl)."""
    N = model.n_modes
    if np.any(window.contact_time > 0):
        p = int(np.argmax(window.contact_time))
        shape = model.phi[p]
        where = float(model.points[p])
    else:
        p, where = -1, 0.5 * model.span
        shape = model.shapes(where)[0]
    y = window.states[:, :N] @ shape
    w = window.states[:, N:2 * N] @ shape
    angle = np.unwrap(np.arctan2(w, y))
    duration = window.times[-1] - window.times[0]
    ratio = float((angle[-1] - angle[0]) / (model.rotary_speed * duration)) if duration > 0 else float("nan")
    if not np.any(window.onsets > 0) and not np.any(window.contact_time > 0):
        verdict = "no_contact"
    elif abs(ratio) < SLIDING_RATE and window.any_contact_time >= SLIDING_CONTACT * duration:
        verdict = "sliding"
    elif ratio > 0.5:
        verdict = "forward"
    elif ratio < -0.5:
        verdict = "backward"
    else:
        verdict = "bouncing"
    return dict(whirl_frequency_ratio=ratio, whirl=verdict, whirl_point=where)


def quasi_static_applies(model: WhirlModel, window: Window) -> bool:
    """Whether the quasi-static correction of the modes left out (:func:`static_correction`) enters the window's
    stresses: wherever a contact force acts in it. It is applied to every contact force at every instant, in step
    with the residual flexibility the contact's spring has in series (:func:`residual_flexibility`), and is not
    switched on or off by the contacts' durations (docs/reference_model.md §2.1, §3). Without contact: where the tool
    joints' mass is lumped (their inertia forces, point loads of the motion's own frequencies, are completed
    statically: :func:`joint_inertia_forces`), else False (nothing to correct)."""
    return bool(np.any(window.contact_time > 0) or np.any(window.onsets > 0) or model.joint_points is not None)



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


def static_correction(model: WhirlModel, x: np.ndarray) -> np.ndarray:
    """Per unit force at each contact point, the static deflection and moment of the modes left out on the stations
    x [m], [y_s, m_s] (P, 2X): the full static field of a point load on the periodic beam-column
    (:func:`periodic_point_moment`, :func:`periodic_point_deflection`, both in closed form) minus the
    kept modes' static terms ψ_n(x_p) ψ_n(x)/(m ω_n²) (the rigid translation has no static term: the load's mean
    is carried by the other contacts). Cached on the model per stations."""
    key = np.asarray(x, float).tobytes()
    if key in model.cache:
        return model.cache[key]
    L, N = model.span, model.n_modes
    ei, tn = model.props["bending_stiffness"], model.props["effective_tension"]
    k = model.wavenumber
    flexible = k > 0  # the kept modes with a static term (the rigid translation has none)
    at = model.points
    gain = np.zeros(N)
    if model.basis is None:
        shapes, kept_at = model.shapes(x), model.phi  # (X, N), (P, N)
        gain[flexible] = 1.0 / (model.mass * model.omega[flexible] ** 2)
    else:
        # with the joints' mass the kept modes span the same basis functions: their static part is the basis' own, a
        # matter of stiffness alone (the static field the correction completes balances the load's mean uniformly)
        shapes, kept_at = mode_shapes(x, L, model.modes), mode_shapes(at, L, model.modes)
        gain = basis_static_gain(model)
    kept_moment = (kept_at * gain * ei * k**2) @ shapes.T
    moment = periodic_point_moment(x[None, :] - at[:, None], L, ei, tn) - kept_moment
    # the deflection likewise: the whole static field in closed form (:func:`periodic_point_deflection`) less the kept
    # modes' terms (the harmonics above the kept ones, and the sine of a harmonic whose cosine alone is kept)
    deflection = periodic_point_deflection(x[None, :] - at[:, None], L, ei, tn) - (kept_at * gain) @ shapes.T
    out = np.hstack([deflection, moment])
    out.flags.writeable = False
    model.cache[key] = out
    return out


def periodic_fields(model: WhirlModel, q: np.ndarray, forces: np.ndarray | None, x: np.ndarray,
                    direction: int | None = None) -> dict:
    """Deflection [m] and moment −EI u'' [N m] on the stations x [m] (shape times × x) of one direction from the
    modal states q (T, N) (ψ_n'' = −k_n² ψ_n: mode n's moment is EI k_n² ψ_n q_n, none for the rigid translation),
    plus with ``forces`` (T, P) on the pipe the quasi-static correction for the modes left out
    (:func:`static_correction`). With ``direction`` (0 y, 1 z) the moment is the pipe's whole, −EI (κ + u''), κ the
    hole's curvature in that direction (the pipe follows the curved hole)."""
    x = np.asarray(x, float)
    base = mode_shapes(x, model.span, model.modes)
    moments = base * (model.props["bending_stiffness"] * model.wavenumber**2)  # each mode's −EI ψ''
    if model.basis is not None:
        base, moments = base @ model.basis, moments @ model.basis
    both = q @ np.vstack([base, moments]).T
    if forces is not None:
        if direction == 0 and model.point_side is not None:
            forces = forces + model.point_side  # the joints' weight at the joints: a point load as the contacts'
        both = both + forces @ static_correction(model, x)
    moment = both[:, x.size:]
    if direction is not None and model.hole_curvature[direction] != 0.0:
        # the pipe follows the hole: its curvature is the hole's κ⃗ plus its own u'', M = −EI (κ⃗ + u'')
        moment = moment - model.props["bending_stiffness"] * model.hole_curvature[direction]
    return {"deflection": both[:, :x.size], "moment": moment}


def body_wall_excess(model: WhirlModel, x: np.ndarray, uy: np.ndarray, uz: np.ndarray, normal: np.ndarray,
                     largest_moment: float) -> tuple[float, float]:
    """How far the pipe body passes its wall beyond the Hertz approach of its contacts, anywhere along it
    (docs/reference_model.md §2): the largest over the rows (times) and the stations x [m] (X,) of
    |u(x, t)| − c_b − α(x, t), with u = (``uy``, ``uz``) (T, X) [m], c_b the body's clearance and α the Hertz
    approach (F_n/K)^{2/3} of the body's contact points at that row (``normal`` (T, P) [N]), linear between
    neighbouring ones along the periodic string (a contact's own at its station); plus the bound of what lies
    between the stations, h²/8 max|u''| (h the widest gap between stations; the linear interpolant of the vector
    u errs by at most that, and |u| of the interpolant is at most its ends' by convexity), with |u''| ≤ (|M| + EI
    |κ⃗|)/EI from the largest moment ``largest_moment`` [N m] (the hole's curvature κ⃗ is in the moment, not in u).
    Returns (excess [m], the bound in it [m]); a negative excess: clear of the wall everywhere. NaN without body
    stations of contact kind in the model (no body clearance to hold it to)."""
    rows = row_wall_excess(model, x, uy, uz, normal)
    bound = wall_excess_bound(model, x, largest_moment)
    return (float(np.max(rows)) + bound if rows.size else float("nan")), bound


def row_wall_excess(model: WhirlModel, x: np.ndarray, uy: np.ndarray, uz: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """(T,) each row's largest |u(x, t)| − c_b − α(x, t) over the stations x [m] (:func:`body_wall_excess`, without
    the bound between the stations); NaN without body contact points."""
    body = model.kinds == 0
    if not np.any(body):
        return np.full(uy.shape[0], np.nan)
    clearance = float(np.max(model.clearance[body]))
    at = model.points[body]
    if model.law == 0:
        alpha = (np.maximum(normal[:, body], 0.0) / model.stiffness[body]) ** (2.0 / 3.0)
    else:
        alpha = np.maximum(normal[:, body], 0.0) / model.penalty_stiffness[body]
    # the linear interpolation between the body's contact points along the periodic string, as a matrix (X, Pb),
    # cached on the model per stations
    key = ("wall", np.asarray(x, float).tobytes())
    weights = model.cache.get(key)
    if weights is None:
        order = np.argsort(at)
        ext = np.concatenate((at[order][-1:] - model.span, at[order], at[order][:1] + model.span))
        weights = np.zeros((x.size, at.size))
        j = np.clip(np.searchsorted(ext, x, side="right") - 1, 0, ext.size - 2)
        share = (x - ext[j]) / (ext[j + 1] - ext[j])
        cols = np.concatenate((order[-1:], order, order[:1]))
        np.add.at(weights, (np.arange(x.size), cols[j]), 1.0 - share)
        np.add.at(weights, (np.arange(x.size), cols[j + 1]), share)
        model.cache[key] = weights
    return np.max(np.hypot(uy, uz) - clearance - alpha @ weights.T, axis=1)


def wall_excess_bound(model: WhirlModel, x: np.ndarray, largest_moment: float) -> float:
    """h²/8 max|u''| [m], h the widest gap between the stations x [m], |u''| ≤ (|M| + EI |κ⃗|)/EI with the largest
    moment ``largest_moment`` [N m] (:func:`body_wall_excess`)."""
    ei = model.props["bending_stiffness"]
    h = float(np.max(np.diff(x))) if x.size > 1 else 0.0
    return h * h / 8.0 * (float(largest_moment) + ei * float(np.hypot(*model.hole_curvature))) / ei


def modal_accelerations(model: WhirlModel, window: Window, shapes: np.ndarray | None = None) -> np.ndarray:
    """(T, 2N) q̈ of the recorded rows (y then z modes) from the modal equations (module docstring of
    :mod:`study.solvers.whirl_kernel`) with the recorded contact forces: the modes' stiffness and linear damping,
    the turning eccentric load, the side load, the quadratic drag and the contacts. With ``shapes`` (N, K) the
    accelerations Σ_n q̈_n shapes_nk at K points instead, (T, 2K) (y then z)."""
    N = model.n_modes
    z = window.states
    qy, qz, vy, vz = z[:, :N], z[:, N:2 * N], z[:, 2 * N:3 * N], z[:, 3 * N:4 * N]
    turn = model.rotary_speed * window.times[:, None]
    w2 = model.omega**2
    out = shapes if shapes is not None else np.eye(N)
    ea, eb = eccentric_parts(model)
    ay = (-w2 * qy - model.damping * vy + model.side) @ out + np.cos(turn) * (ea @ out) - np.sin(turn) * (eb @ out)
    az = (-w2 * qz - model.damping * vz) @ out + np.sin(turn) * (ea @ out) + np.cos(turn) * (eb @ out)
    if model.drag > 0.0:
        S, wts = model.drag_shapes, model.drag_weights
        uy, uz = vy @ S.T, vz @ S.T
        c = model.drag * np.hypot(uy, uz) * wts
        projected = S @ out / model.mass
        ay -= (c * uy) @ projected
        az -= (c * uz) @ projected
    at = model.phi @ out / model.mass
    ay += window.forces[:, :, 0] @ at
    az += window.forces[:, :, 1] @ at
    return np.hstack([ay, az])


def joint_inertia_forces(model: WhirlModel, window: Window) -> np.ndarray:
    """(T, P, 2) the inertia forces −m_j ü(x_j) [N] of the tool joints' lumped mass on the pipe at the contact points
    that are joints (zero elsewhere), from :func:`modal_accelerations`: point loads whose part on the modes left out
    the quasi-static correction completes (:func:`periodic_fields`; docs/reference_model.md §3)."""
    at = model.joint_points
    J = int(np.count_nonzero(at))
    acc = modal_accelerations(model, window, model.phi[at].T)  # at the joints
    out = np.zeros(window.forces.shape[:2] + (2,))
    for j in range(2):
        out[:, at, j] = -model.joint_mass * acc[:, j * J:(j + 1) * J]
    return out


def stresses(inputs: Mapping[str, Any], model: WhirlModel, window: Window, space_points: int = 97,
             fibres: int = 16, correction: bool = True, segments: list[tuple[int, int]] | None = None):
    """Bending, normal and shear stresses over the window (the paper's §5 stresses in two directions;
    docs/reference_model.md §3).

    Moments M_y, M_z (−EI (κ_y + y''), −EI (κ_z + z'')) from :func:`periodic_fields` in each direction
    (the modes, plus with ``correction`` the quasi-static correction for the contact forces: the static response
    of the modes left out, whose flexibility the contacts have in series, :func:`residual_flexibility`; what the
    modes above N do beyond it is in :func:`modal_check`); bending stress |M| r_o/I; the
    alternating stress is half the range, over the window, of the stress of one fibre of the turning
    pipe, (M_y cos(Ωt + ψ) + M_z sin(Ωt + ψ)) r_o/I, at the worst fibre ψ and section; shear force
    dM/dx (the −EI y''' part, by differences of the corrected moment), shear stress 2|V|/A_s.

    With ``segments`` (row ranges [start, stop) of the recording), a list of those values per segment, times
    from each segment's first row (the fields computed once for all). ``modal_quarter_fraction``: the share of
    the modes N/4 … N/2 in the largest moment, beside ``modal_tail_fraction``'s of N/2 … N (truncation indicators).
    """
    N = model.n_modes
    L = model.span
    x = np.unique(np.concatenate([np.linspace(0.0, L, space_points), model.points]))
    ei, tn = model.props["bending_stiffness"], model.props["effective_tension"]
    fields = []
    # the joints' inertia forces corrected statically (with the residual vectors their coupling with the joints' mass
    # is in the motion already)
    inertia = (joint_inertia_forces(model, window) if correction and model.joint_points is not None
               and not model.dynamic else None)
    for j in range(2):
        forces = window.correction_forces(model, j) if correction else None  # without it, the modes alone
        if inertia is not None:
            forces = forces + inertia[:, :, j]  # the joints' inertia forces, point loads as the contacts'
        fields.append(periodic_fields(model, window.states[:, j * N:(j + 1) * N], forces, x, j))
    r_o, r_i = inputs["outer_diameter"] / 2.0, inputs["inner_diameter"] / 2.0
    scale = r_o / float(section.second_moment_of_area(r_o, r_i))
    area = model.props["steel_area"]
    k = model.wavenumber
    upper = model.modes >= N // 2
    second = (model.modes >= N // 4) & ~upper  # the quarter below: how fast the modal terms fall
    turn = model.rotary_speed * window.times
    cos_turn, sin_turn = np.cos(turn), np.sin(turn)
    psi = np.linspace(0.0, np.pi, fibres, endpoint=False)  # ψ and ψ + π have the same half range
    cos_fibre, sin_fibre = np.cos(psi), np.sin(psi)
    # how far the body passes its wall beyond its contacts' approach, row by row, for all the segments at once; where
    # no body contact pushes (no approach to allow) it is the largest deflection less the body's clearance
    body = model.kinds == 0
    pressed = np.any(window.forces[:, body, 2] > 0.0, axis=1) if np.any(body) else np.zeros(window.times.size, bool)
    excess_rows = (row_wall_excess(model, x, fields[0]["deflection"], fields[1]["deflection"], window.forces[:, :, 2])
                   if np.any(pressed) else None)
    body_clearance = float(np.max(model.clearance[body])) if np.any(body) else float("nan")
    outs = []
    for first, stop in (segments or [(0, window.times.size)]):
        rows = slice(first, stop)
        times = window.times[rows]
        my, mz = fields[0]["moment"][rows], fields[1]["moment"][rows]
        uy, uz = fields[0]["deflection"][rows], fields[1]["deflection"][rows]
        largest, it, ix, deflection, shear, jt, jx, half = stress_kernel.window_extremes(
            my, mz, uy, uz, x, cos_turn[rows], sin_turn[rows], cos_fibre, sin_fibre)
        # modal truncation indicator: the upper half of the modes' share of the largest modal moment
        shapes = model.shapes(x[ix])[0] * ei * k**2 if model.basis is None else model.moment_shapes(x[ix])[0]
        qy, qz = window.states[first + it, :N], window.states[first + it, N:2 * N]
        bend = ei * model.hole_curvature  # the hole's curvature: exact, in no mode
        full = np.hypot(qy @ shapes - bend[0], qz @ shapes - bend[1])
        tail = np.hypot(qy[upper] @ shapes[upper], qz[upper] @ shapes[upper])
        below = np.hypot(qy[second] @ shapes[second], qz[second] @ shapes[second])
        if excess_rows is not None and np.any(pressed[rows]):
            excess = float(np.max(excess_rows[rows]))
        else:
            excess = float(deflection) - body_clearance
        excess += wall_excess_bound(model, x, largest)
        outs.append(dict(max_deflection=float(deflection), max_wall_excess=excess,
                         max_bending_stress=float(largest * scale),
                         max_normal_stress=float(abs(inputs["axial_tension"]) / area + largest * scale),
                         max_normal_stress_x=float(x[ix]), max_normal_stress_t=float(times[it] - times[0]),
                         alternating_bending_stress=float(np.max(half) * scale),
                         alternating_bending_stress_x=float(x[int(np.argmax(half))]),
                         max_shear_stress=float(2.0 * shear / area),
                         max_shear_stress_x=float(0.5 * (x[jx] + x[jx + 1])),
                         max_shear_stress_t=float(times[jt] - times[0]),
                         modal_tail_fraction=float(tail / full) if full > 0 else 0.0,
                         modal_quarter_fraction=float(below / full) if full > 0 else 0.0))
    return outs if segments is not None else outs[0]


def contact_spacing(model: WhirlModel, window: Window) -> tuple[float, list[float]]:
    """Largest distance between neighbouring touching points along the periodic string (the first of the next
    section, x + L, follows the last) [m]; and the touching positions [m]."""
    touching = np.sort(model.points[(window.contact_time > 0) | (window.onsets > 0)])
    if touching.size == 0:
        return float("nan"), []
    stations = np.concatenate((touching, [touching[0] + model.span]))
    return float(np.max(np.diff(stations))), [float(v) for v in touching]


def energy_balance(model: WhirlModel, window: Window) -> dict[str, float]:
    """Energy budget over the window [J]: change of the mechanical energy, work of the loads and of the
    friction, drag and contact losses, and the residual relative to the largest term."""
    N = model.n_modes
    a, b = window.states[0], window.states[-1]
    dW = b[4 * N:] - a[4 * N:]
    if window.ends is not None:  # with the residual vectors: the kernel's energy, theirs in its modes
        dE = model.kernel_energy(window.ends[1]) - model.kernel_energy(window.ends[0])
    else:
        dE = model.energy(b) - model.energy(a)
    residual = dW[0] + dW[1] - dW[2] - dW[3] - dE
    size = max(abs(dW[0]), abs(dW[1]), abs(dW[2]), abs(dW[3]), abs(dE), 1e-300)
    return dict(energy_change=dE, load_work=dW[0], friction_work=dW[1], drag_loss=dW[2], contact_loss=dW[3],
                residual=float(residual / size))


def solve(inputs: Mapping[str, Any]) -> PointResult:
    """The ``reference`` method (module docstring). Values (SI) are listed in ``docs/reference_model.md``.

    The mode count is chosen per point: from ``reference_modes`` it doubles (or grows by the power of two that the
    residual flexibility's N⁻³ foresees) while the modal part of a design figure's error (:func:`modal_check`) is over
    half the study's tolerance and the count is within ``reference_max_modes``; the last run is the answer (``extras["reference_modes"]``), the counts tried and their
    figures in ``extras["modes_tried"]`` (docs/reference_model.md §3.1)."""
    option = ReferenceOptions.from_inputs(inputs)
    dynamic = option.reference_residual == "dynamic"
    count, top = int(option.reference_modes), max(int(option.reference_modes), int(option.reference_max_modes))
    tried = []
    previous = None
    while True:
        result = solve_with_modes({**inputs, "reference_modes": count}, previous if dynamic else None)
        parts = result.extras.get("convergence") or {}
        modal = modal_part(result)
        tried.append(dict(modes=count, modal=modal, error_estimate=float(result.error_estimate or 0.0),
                          **{name: float(result.values.get(name, np.nan)) for name in FIGURES},
                          window={name: float(e["window"]) for name, e in parts.items()}))
        # the gate's tolerance of the point: the statistical one where its figures are means over a motion that does
        # not repeat (with the residual vectors; the static law keeps the study's)
        tolerance = (statistical_tolerance(inputs) if dynamic and result.values.get("statistical_figures")
                     else study_tolerance(inputs))
        if result.status != "ok" or modal <= 0.5 * tolerance or 2 * count > top:
            break
        # the next count: doubled, or more where the modal part is far over (the residual flexibility falls like N⁻³,
        # so a part m asks about (m / (tolerance/2))^(1/3) times the modes): a choice of the count only, the part
        # stated is the one measured with it. With the residual vectors doubled: their modal part is measured
        # between a count and its half (:func:`doubling_modal_error`)
        factor = 2 if dynamic else 2 ** max(1, int(np.ceil(np.log2(max(modal / (0.5 * tolerance), 1.0)) / 3.0)))
        while count * factor > top:
            factor //= 2
        count *= factor
        previous = result
    result.extras["modes_tried"] = tried
    if len(tried) > 1:
        result.message += (f"; modes doubled from {tried[0]['modes']} to {count} (the modal part "
                           + ", ".join(f"{t['modes']}: {t['modal']:.2%}" for t in tried) + ")")
    return result


def modal_part(result: PointResult) -> float:
    """The largest modal part of a run's figures' errors (``extras["convergence"]``; 0 where none is stated): what
    decides whether the point goes on to more modes (:func:`solve`, :func:`solve_with_modes`)."""
    parts = result.extras.get("convergence") or {}
    return max((float(e["modes"]) for e in parts.values()), default=0.0)


def doubling_modal_error(previous: PointResult, values: Mapping[str, Any]) -> dict[str, float]:
    """The modal part of each figure's error (relative) at N modes with the residual vectors, from the run at N/2
    (``previous``): the figures' change between the two, relative to the figure at N (the alternating stress's to the
    larger of it and the max bending stress, as :func:`convergence` counts it). It is the error left at N if that
    falls at least as fast as 1/N, and its statistical part (the two windows' scatter) is not taken out: at the
    bouncing points measured the figures did not change monotonically from 8 to 128 modes (docs/reference_model.md
    §2.1), and less would not have covered them."""
    out = dict.fromkeys(MODAL_FIGURES, 0.0)
    for name in MODAL_FIGURES:
        now, then = float(values.get(name, np.nan)), float(previous.values.get(name, np.nan))
        if not (np.isfinite(now) and np.isfinite(then)) or now <= 0:
            continue
        size = max(now, float(values.get("max_bending_stress", now))) if name == "alternating_bending_stress" else now
        out[name] = float(abs(now - then) / size)
    return out


def solve_with_modes(inputs: Mapping[str, Any], previous: PointResult | None = None) -> PointResult:
    """The ``reference`` method with the inputs' ``reference_modes`` (:func:`solve` chooses the count): one run
    (:func:`solve_with_stations`), run again with the body's contact stations raised k -> 2k + 1 (the stations kept, one
    more between each pair) while the body passes its wall between them (``max_wall_excess``, a bound along the whole
    body, docs/reference_model.md §2) by more than the study's tolerance of its clearance — the gate's test — up to
    ``reference_max_body_stations``, at a mode count whose modal part does not send the point to more modes anyway; the
    count of the answer in ``extras["reference_body_stations"]``, the counts tried, their excess and wall times in
    ``extras["body_stations_tried"]``. Contact points given in code (``contact_points``) are kept. With the residual
    vectors and the run at half the modes (``previous``) the modal part of the errors is measured between the two
    (:func:`doubling_modal_error`) where the motion does not repeat."""
    option = ReferenceOptions.from_inputs(inputs)
    count = int(option.reference_body_stations)
    top = max(count, int(option.reference_max_body_stations))
    tolerance = study_tolerance(inputs)
    more_modes = 2 * int(option.reference_modes) <= int(option.reference_max_modes)
    tried = []
    while True:
        result = solve_with_stations({**inputs, "reference_body_stations": count}, previous)
        excess, clearance = result.values.get("max_wall_excess"), result.values.get("clearance")
        passed = (excess is not None and clearance is not None and np.isfinite(excess)
                  and excess > tolerance * clearance)
        tried.append(dict(stations=count, max_wall_excess=float(excess) if excess is not None else np.nan))
        # a run whose modes left out take a figure over half the tolerance is run again with more modes (solve), which
        # raise their own stations: its stations are not raised
        modal = modal_part(result)
        if (result.status != "ok" or not passed or 2 * count + 1 > top or inputs.get("contact_points") is not None
                or (more_modes and modal > 0.5 * tolerance)):
            break
        count = 2 * count + 1
    result.extras["reference_body_stations"] = count
    result.extras["body_stations_tried"] = tried
    if len(tried) > 1:
        result.message += (f"; body stations raised from {tried[0]['stations']} to {count} (the body past its wall by "
                           + ", ".join(f"{t['stations']}: {t['max_wall_excess'] / clearance:.2%} c" for t in tried)
                           + ")")
    return result


def solve_with_stations(inputs: Mapping[str, Any], previous: PointResult | None = None) -> PointResult:
    """One run of the ``reference`` method with the inputs' ``reference_modes`` and ``reference_body_stations``; with
    the residual vectors and the run at half the modes (``previous``) the modal part of the errors is measured between
    the two (:func:`doubling_modal_error`)."""
    result = PointResult(method=METHOD)
    model = build_model(inputs)
    vals = result.values
    vals.update(model.props)  # the section's properties, as every method of the hierarchy reports them
    vals.update(span_length=model.span, first_natural_frequency=model.omega[0] / (2 * np.pi)
                if np.isfinite(model.omega[0]) else np.nan, clearance=float(np.max(model.clearance)))
    if not np.all(np.isfinite(model.omega)):
        result.status = "buckled"
        result.message = (f"effective tension {model.props['effective_tension']:.4g} N buckles the "
                          f"{model.span:.4g} m section")
        return result
    run = simulate(inputs, model)
    result.extras.update(contact_points=[float(v) for v in model.points], contact_kinds=[int(v) for v in model.kinds],
                         reference_modes=model.n_modes,
                         reference_residual="dynamic" if model.dynamic else "series" if np.any(model.flexibility > 0)
                         else "none")
    if run["verdict"] == "failed":
        result.status = "failed"
        result.message = f"integration failed: {run['failure']}"
        return result
    window, cycles = run["window"], run["cycles"]
    tau = model.period
    revs = (window.end - window.start) / tau
    periodic = bool(run["period"])
    vals.update(revolutions_simulated=float(run["revolutions"] + revs), window_revolutions=float(revs),
                impacts_per_revolution=float(np.sum(window.onsets) / revs),
                contact_fraction=float(window.any_contact_time / (window.end - window.start)),
                eccentricity=model.eccentricity)
    if run["period"]:
        vals["period_revolutions"] = float(run["period"])
    measure = whirl_measure(model, window)
    vals.update(whirl_frequency_ratio=measure["whirl_frequency_ratio"],
                whirl_class=float(WHIRL_CLASSES[measure["whirl"]]), regime=float(REGIMES[WHIRL_REGIMES[measure["whirl"]]]))
    spacing, touching = contact_spacing(model, window)
    vals["contact_spacing"] = spacing
    # the largest Hertz approach of a contact on the body (the gate holds the largest deflection, on the body, to the
    # body's clearance plus it): its peak force's (F/K)^(2/3), or the penalty's F/k
    body = model.kinds == 0
    if np.any(body):
        peak = window.peak[body]
        approach = ((peak / model.stiffness[body]) ** (2.0 / 3.0) if model.law == 0
                    else peak / model.penalty_stiffness[body])
        vals["max_approach"] = float(np.max(approach))
    stats = run.get("stats") or settling(cycles, run["preceding"], run.get("ratio", np.nan))
    summary = window_summary(cycles, stats)
    budget = energy_balance(model, window)
    modal = run["modal"]
    if (model.dynamic and previous is not None and not periodic and previous.status == "ok"
            and previous.extras.get("reference_modes") == model.n_modes // 2):
        modal = doubling_modal_error(previous, summary)
    errors = convergence(inputs, model, window, summary, stats, periodic, residual=budget["residual"], modal=modal)
    correction = summary.pop("correction")
    quarter = summary.pop("modal_quarter_fraction")
    damage = summary.pop(DAMAGE)  # the worst fibre's mean damage per cycle
    vals.update(summary, window_spread=stats["peak_contact_force"]["drift"])
    # the damage rate counted by rainflow (add_limits keeps it and gives its fatigue life), its error the life's
    vals.update(damage_rate=float(damage * len(cycles) / (window.end - window.start)),
                fatigue_life_error=errors[DAMAGE]["total"], statistical_figures=float(not periodic),
                **{f"{name}_error": errors[name]["total"] for name in FIGURES})
    result.error_estimate = float(max(e["equivalent"] for e in errors.values()))
    result.extras.update(whirl=measure["whirl"], whirl_point=measure["whirl_point"], touching_points=touching,
                         energy_budget=budget, steps=run["integrator"].steps, quasi_static_correction=correction,
                         revolutions_needed=float(run.get("revolutions_needed", np.nan)), modal_quarter_fraction=quarter,
                         modal_error={name: float(v) for name, v in (modal or {}).items()},
                         convergence={name: {**e, "drift": stats[name]["drift"], "standard_error": stats[name]["error"]}
                                      for name, e in errors.items()})
    option = ReferenceOptions.from_inputs(inputs)
    cycle = f"{run['period']} revolution(s)" if periodic else "revolution"
    needed = run.get("revolutions_needed", np.nan)
    stopped = ""
    if run["budget_spent"]:
        stopped = ("; more revolutions would not bring them within the tolerance (the modes or the integrator take "
                   "them over)" if not np.isfinite(needed) else
                   f"; about {needed:.0f} revolutions in all would bring them within the tolerance, more than the "
                   f"budget of {option.reference_max_revolutions} (solver.reference_max_revolutions)")
    names = {**{name: label for name, (_, label) in FIGURES.items()}, DAMAGE: "fatigue damage rate"}
    figures = ", ".join(f"{names[name]} {e['total']:.2%} (mostly {e['dominant']}: window {e['window']:.2%}, "
                        f"integrator {e['integrator']:.1e}, "
                        f"modes {e['modes']:.2%})"
                        for name, e in errors.items())
    messages = [f"whirl {measure['whirl']} ({measure['whirl_frequency_ratio']:+.3f} Omega)",
                (f"periodic every {run['period']} revolution(s) after {run['revolutions']}" if periodic else
                 f"bouncing with stationary statistics after {run['revolutions']} revolutions (transient ended)"
                 if run.get("stationary") and run["revolutions"] < option.reference_revolutions else
                 f"not periodic within {run['revolutions']} revolutions"),
                f"figures: means over the window's {len(cycles)} cycle(s) of {cycle} of each cycle's largest value"
                f" (largest seen: window_largest_*){stopped}",
                f"window {revs:g} revolutions; {model.n_modes} modes per direction, rtol "
                f"{float(option.reference_rtol):g}"
                f"{' and the residual flexibility and quasi-static correction of the modes left out' if correction else ''}"
                f" (modal error of the largest deflection {(modal or {}).get('max_deflection', 0.0):.2%})",
                f"error of each figure (its largest part): {figures}",
                (f"held to solver.statistical_tolerance {statistical_tolerance(inputs):.3g} (means over the revolutions"
                 f" of a motion that does not repeat; the damage rate to (1 + it)^m - 1)" if not periodic else
                 f"held to solver.tolerance {study_tolerance(inputs):.3g}")]
    # clear of the wall is an answer too (the free whirl), so it is ok: the regime says which; an error above the
    # study's tolerance makes the gate call it not_converged
    result.status = "ok"
    result.message = "; ".join(messages)
    return result
