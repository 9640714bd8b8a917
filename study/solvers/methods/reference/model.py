"""The reference model's section (docs/reference_model.md §1–2): :class:`WhirlModel` and :func:`build_model` from a
design point's inputs; the modes left out given back statically (:func:`residual_flexibility`,
:func:`static_correction`) or as residual vectors (:func:`residual_ritz`); the side loads."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Mapping

import numpy as np

from study.physics import hertz, section, well, whirl
from study.physics.damping import viscous_modal_damping_ratio
from study.physics.contact import (calibrated_hysteresis, hertz_energy, linear_contact_damping,
                                   linearised_stiffness)
from study.solvers.model.options import ReferenceOptions
from study.solvers.model.point import DesignPoint
from study.physics.string_modes import (contact_layout, eccentric_factors, joint_modes, mode_shapes,
                                        mode_wavenumbers, periodic_point_deflection, periodic_point_moment,
                                        series_contact, symmetric_points)
from study.solvers.model.scene import Scene


CONTACT_LAWS = ReferenceOptions.choices("contact_law")


#: Default regularisation velocity of the Coulomb friction [m/s]: 1/250 of the 4½-in body's surface
#: speed at 100 rpm; tested not to change the outputs beyond 2 % when divided by ten.
SLIP_VELOCITY = ReferenceOptions.default("slip_velocity")


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
    #: angle β of the model's +y from the hole's low side towards +z: the side load's direction [rad]
    frame: float = 0.0
    #: κ⃗ of the hole in the model's frame [1/m]
    hole_curvature: np.ndarray = field(default_factory=lambda: np.zeros(2))
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
    #: the modes left out as residual vectors, K per contact point (``reference_residual_vectors``), in the kernel's
    #: modes (``reference_residual = "dynamic"`` or ``"radiating"``: :func:`residual_ritz`; None: the residual
    #: flexibility, if any, static in series)
    ritz: dict | None = None
    joint_x: np.ndarray = field(default_factory=lambda: np.zeros(0))  #: the tool joints' positions x_j [m]
    #: (P,) which contact points are the joints whose mass is lumped (None: no joints' mass), for the quasi-static
    #: correction of their inertia forces (:func:`joint_inertia_forces`)
    joint_points: np.ndarray | None = None
    #: with the residual vectors, what the fields take for the modes left out (``reference_recovery``): the contact
    #: forces' static field ("force", the mode-acceleration method) or the vectors' coordinates s_p ("vectors")
    recovery: str = "force"
    #: the strikes' pulses at the tool joints (``reference_strike_force = "pulse"``: :func:`strike_pulses`; None: the
    #: contact law at every strike)
    pulse: dict | None = None
    #: with the residual vectors and the pulses, a pulse's onset speed: the point's whole approach rate ("approach") or
    #: the kept modes' part of it ("kept": without the vectors' motion; ``reference_pulse_speed``)
    pulse_speed: str = "approach"
    #: with the pulses, their size: the local strike's history ("local") or scaled to its net work ("matched",
    #: "mobility"; ``reference_pulse_work``, :func:`study.solvers.kernels.pulse.matched_scale`)
    pulse_work: str = "local"
    #: the upper edge ω_b [rad/s] of the band of the section's bending the stresses state (``reference_stress_band``:
    #: :func:`stress_band_edge`; inf: every kept mode): the kept modes above it enter the fields by their quasi-static
    #: response (:func:`study.solvers.methods.reference.fields.field_states`), the motion keeps them all
    stress_band: float = float("inf")
    #: the precision of the integrator's drag sums (``reference_drag_precision``: "double", or "single", float32)
    drag_precision: str = "double"
    #: the integrator's drag on the first N_d modes alone (``reference_drag_modes``, :func:`drag_on_slow_modes`): their
    #: shapes (G_d, N_d) at the rule of N_d, its weights (G_d,) [m], and each mode's factor ∫ ψ_n² dx / L [-] (N,) of
    #: the linear equivalent of the modes above (0 below N_d, and with none; kernels.drag.drag_linearised); None: every
    #: mode's drag summed
    slow_drag: tuple | None = None
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
    def joint_spacing(self) -> float:
        """The least spacing [m] of the tool joints along the string (of the section's joint contact points where the
        joints' places are not given; the section's length with one joint or none): how far a strike's bending waves
        travel to the next joint and back (:func:`study.physics.strike.return_time`)."""
        joints = np.sort(self.points[self.kinds == 1])
        if self.joint_x.size > 1:
            return float(np.min(np.diff(np.sort(self.joint_x))))
        return float(np.min(np.diff(joints))) if joints.size > 1 else float(self.span)

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
        the residual vectors (:attr:`dynamic`) the kernel's modes are the N + K·P modes of the kept modes and K
        residual vectors per contact point (:func:`residual_ritz`): their frequencies, shapes at the contact and drag
        points and loads; the linear damping the modes' ratio at their frequencies (none with the drag)."""
        S, wts = (self.drag_shapes, self.drag_weights) if self.slow_drag is None else self.slow_drag[:2]
        fpar = np.array([self.drag, self.rotary_speed, self.friction, self.slip_velocity, 1.0 / self.mass,
                         float(self.law), self.hysteresis])
        if not self.dynamic:
            return (self.omega**2, self.damping, self.eccentric, self.side, S, wts,
                    self.phi, self.clearance, self.radius, self.stiffness, self.penalty_stiffness,
                    self.penalty_damping, fpar, self.flexibility) + self.pulse_arrays()
        r = self.ritz
        kept = ()
        if self.pulse is not None and self.pulse_speed == "kept":  # the pulses' onset speed from the kept modes' part
            kept = (self.phi @ r["vectors"][:self.n_modes],)
        return (r["omega2"], r["damping"], r["eccentric"], r["side"], r["drag_shapes"], self.drag_weights,
                r["phi"], self.clearance, self.radius, self.stiffness, self.penalty_stiffness, self.penalty_damping,
                fpar, np.zeros(self.points.size)) + self.pulse_arrays() + kept

    def pulse_arrays(self) -> tuple:
        """The strikes' pulse tables for the kernel (:func:`strike_pulses`; ``whirl_kernel.kernel_system``): per point
        the floor speed [m/s], the table's speeds [m/s], peaks [N], durations [s] and shape coefficients; () without."""
        if self.pulse is None:
            return ()
        q = self.pulse
        return q["floor"], q["speeds"], q["peak"], q["duration"], q["coefficients"]

    @property
    def dynamic(self) -> bool:
        """Whether the modes left out are residual vectors in the kernel's modes (``reference_residual =
        "dynamic"``)."""
        return self.ritz is not None

    @property
    def kernel_modes(self) -> int:
        """The kernel's modes per direction: N, and K·P more with K residual vectors per contact point."""
        return self.n_modes + (self.ritz["count"] * self.points.size if self.dynamic else 0)

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
        split, :func:`series_contact`), the higher orders' (``reference_residual_vectors`` > 1) and the rates zero,
        mapped onto the kernel's modes; else z itself (a copy)."""
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
        higher = np.zeros(K - N - P)  # the higher-order vectors' coordinates (reference_residual_vectors > 1): none
        out = np.zeros(4 * K + 4)
        for j in range(4):
            out[j * K:(j + 1) * K] = inverse @ np.concatenate((z[j * N:(j + 1) * N], T.T @ forces[j], higher))
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
        motion is (the first-order vectors'; their higher orders, reference_residual_vectors > 1, not counted)."""
        z = np.asarray(z, float)
        N, K, P = self.n_modes, self.kernel_modes, self.points.size
        to_forces = self.ritz["combinations"] @ self.ritz["vectors"][N:N + P]  # (P, K)
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


def residual_flexibility(model: "WhirlModel") -> np.ndarray:
    """(P,) the static flexibility of the modes left out at each contact point [m/N], f_p = Σ_{n ≥ N} ψ_n(x_p)²/(m ω_n²)
    (m = M L/2): the periodic beam-column's whole, :func:`periodic_point_deflection` at s = 0, less the kept modes'
    terms (the rigid translation has none). It vanishes as N grows (like N⁻³: terms like j⁻⁴); in series with a
    contact's Hertz spring (:func:`study.solvers.kernels.whirl_kernel.series_hertz`) it makes a held contact's static
    answer the continuous beam's (docs/reference_model.md §2.1). With the tool joints' mass the kept modes span the same
    basis functions, so their static part is the basis' own, a matter of stiffness alone (as in
    :func:`static_correction`): m ω_n² = (L/2)(EI k_n⁴ + T k_n²) on the basis."""
    ei, tn = model.props["bending_stiffness"], model.props["effective_tension"]
    whole = float(periodic_point_deflection(0.0, model.span, ei, tn))
    return np.maximum(whole - mode_shapes(model.points, model.span, model.modes) ** 2 @ basis_static_gain(model), 0.0)


#: Harmonics above the kept ones that :func:`residual_second_moment` sums (its terms fall like j⁻⁸: the tail past them
#: is below 1e-9 of the sum up to 128 modes, and counted by its integral beyond).
SECOND_MOMENT_HARMONICS = 4096


def residual_second_moments(model: "WhirlModel") -> np.ndarray:
    """(P, P) the modes left out's second moments between the contact points [m/N s²],
    G_pq = Σ_{n ≥ N} ψ_n(x_p) ψ_n(x_q) /(m ω_n⁴): the mass of the residual vectors (:func:`residual_ritz`); its diagonal
    is :func:`residual_second_moment` (the tail beyond the harmonics summed counted there only: off it the terms
    alternate in sign and fall like j⁻⁸). :func:`residual_moments` of order 2."""
    out = residual_moments(model, 2, model.points)
    J = (model.n_modes + 2 * SECOND_MOMENT_HARMONICS - 1) // 2
    ei = model.props["bending_stiffness"]
    out[np.diag_indices_from(out)] += (model.mass * (2.0 / (model.span * ei)) ** 2 * (model.span / (2 * np.pi)) ** 8
                                       / (7.0 * (J + 0.5) ** 7))
    return out


def residual_moments(model: "WhirlModel", order: int, x: np.ndarray) -> np.ndarray:
    """(P, X) the modes left out's moments of ``order`` j ≥ 2 between the contact points and the stations x [m],
    S_j(x_p, x) = Σ_{n ≥ N} ψ_n(x_p) ψ_n(x) /(m ω_n^{2j}) [m/N s^{2j−2}], summed over the basis functions left out
    (1/(m ω_n²) = 1/((L/2)(EI k_n⁴ + T k_n²)), as :func:`residual_flexibility`) up to :data:`SECOND_MOMENT_HARMONICS`
    harmonics above the kept ones (terms like n^{−4j}; j = 1 is the static field, :func:`static_correction`, in closed
    form). S_j(x_p, ·) is the left-out modes' (j−1)-th Krylov vector from a unit force at x_p: their flexibility applied
    to the pipe's mass times the (j−1)-th's (:func:`krylov_fields`)."""
    ei, tn = model.props["bending_stiffness"], model.props["effective_tension"]
    L, N = model.span, model.n_modes
    n = np.arange(N, N + 2 * SECOND_MOMENT_HARMONICS)
    k = mode_wavenumbers(L, n)
    gain = 1.0 / (0.5 * L * (ei * k**4 + tn * k**2))
    weight = model.mass ** (order - 1) * gain**order
    return (mode_shapes(model.points, L, n) * weight) @ mode_shapes(np.asarray(x, float), L, n).T


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


def eccentric_parts(model: "WhirlModel") -> tuple[np.ndarray, np.ndarray]:
    """(a, b) (N,) the real and imaginary parts of the model's generalised eccentric force per modal mass [m/s²]:
    the turning load drives mode n by (a cos Ωt − b sin Ωt, a sin Ωt + b cos Ωt) in (y, z)."""
    e = np.asarray(model.eccentric)
    return e.real.astype(float), (e.imag.astype(float) if np.iscomplexobj(e) else np.zeros(e.size))


def build_model(point: DesignPoint | Mapping[str, Any]) -> WhirlModel:
    """The reference model of one design point (see the module docstring): its ``reference`` options and its scene
    (SI inputs are typed first, :meth:`DesignPoint.of`). Raises ValueError naming the field for inputs that make no
    scene (a tool joint wider than the hole, thinner than the pipe)."""
    point = DesignPoint.of(point)
    option = point.reference
    scene = point.scene
    props = dict(scene.props)
    r_o, hole_r = scene.outer_radius, scene.hole_radius
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
        scene.pipe_density, 2 * tj, tj_bore, tj_length, props["pipe_mass"], 2 * r_o,
        scene.inner_diameter, scene.mud_density)
    if joint_mass < 0.0:
        raise ValueError(f"pipe.tool_joint_length = {tj_length:.6g} m with pipe.tool_joint_diameter = {2 * tj:.6g} m, "
                         f"pipe.tool_joint_inner_diameter = {tj_bore:.6g} m makes a joint {-joint_mass:.4g} kg lighter "
                         "than the plain pipe it replaces: set pipe.tool_joint_length = 0 where pipe.linear_mass "
                         "counts the joints already")
    joint_x = contact_layout(L, joint, 0)[0]
    joint_side = joint_weight * float(np.sin(scene.inclination))  # along the low side
    # ω_n and the modes with the joints' mass (the basis itself without); NaN where ω² < 0: the section buckles
    omega, basis = joint_modes(L, N, M, props["bending_stiffness"], props["effective_tension"], joint_x, joint_mass)
    if option.contact_points is not None:
        x = np.atleast_1d(np.asarray(option.contact_points, float)) * L
        kinds = np.atleast_1d(np.asarray(np.zeros(x.size) if option.contact_kinds is None else option.contact_kinds,
                                         int))
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
    Om = scene.rotary_speed
    eps = float(option.eccentricity)
    factors = np.zeros(N)
    factors[0] = L / np.sqrt(2.0)  # ∫₀ᴸ ψ_n dx: a uniform load drives the rigid translation only
    # the body's, not the joints'; in phases that turn from pipe joint to pipe joint (eccentric_factors)
    eccentric = lift(whirl.eccentric_load(props["pipe_mass"], eps, Om)
                     * eccentric_factors(L, joint, N, float(option.eccentricity_turn))) / mass
    w_y, w_z, curvature = scene.side_loads()
    if joint_side and scene.side_load is None:
        w_y += joint_side * joint_x.size / L  # the joints' weight's mean along the string, in the uniform load
    # the scene is axisymmetric but for the side load, whose direction is constant: the model's frame is the hole's
    # turned by the side load's angle β, so that the load lies along its +y (every output is the same in any frame)
    frame = float(np.arctan2(w_z, w_y)) if (w_y or w_z) else 0.0
    w_side = float(np.hypot(w_y, w_z))
    cb, sb = np.cos(frame), np.sin(frame)
    hole_curvature = np.array([cb * curvature[0] + sb * curvature[1], -sb * curvature[0] + cb * curvature[1]])
    load = w_side * factors
    if joint_side and scene.side_load is None:
        # the joints' weight at the joints less its mean (in w_side): a load at the supports, along the low side (its
        # part across the model's +y, where a walking dogleg turns the frame, is left out: docs/reference_model.md §9)
        load = load + joint_side * cb * (mode_shapes(joint_x, L, N).sum(axis=0) - joint_x.size / L * factors)
    at_joint = (kinds == 1) & np.any(np.abs(x[:, None] - joint_x[None, :]) <= 1e-9 * L, axis=1)  # contacts at joints
    point_side = None
    if joint_side and scene.side_load is None and np.any(at_joint):
        point_side = np.where(at_joint, joint_side * cb, 0.0)
    side = lift(load) / mass
    damping_model = option.reference_damping
    damping = np.zeros(N)
    if damping_model == "viscous":
        damping = 2.0 * float(option.damping_ratio) * omega
    elif damping_model == "drag+viscous":
        # the mud's viscous loss on each mode at its frequency: the Stokes layer confined by the hole (Chen,
        # Wambsganss & Jendrzejczyk 1976), 2ζ_nω_n = c(ω_n)/M on the plain pipe's mass (the joints' lumped mass left
        # out of M: ζ_n a little high); 0 on the rigid translation (ω = 0, the drag alone) and on a buckled mode (NaN
        # ω_n: refused below)
        zeta = viscous_modal_damping_ratio(omega, M, scene.mud_density, r_o, scene.mud_viscosity
                                           / max(scene.mud_density, 1e-300), hole_r)
        damping = np.nan_to_num(2.0 * np.asarray(zeta) * omega)
    drag_x, drag_w = drag_quadrature(L, N, option.reference_drag_quadrature)
    shapes = lift(mode_shapes(drag_x, L, N))
    drag = props["drag_coefficient_per_length"] if damping_model in ("drag", "drag+viscous") else 0.0
    e = scene.restitution
    law = CONTACT_LAWS.index(option.contact_law)
    # the linear penalty: Hertz linearised at the elastic approach of the point's effective mass at Ω c_p
    m_eff = mass / np.maximum(np.sum(phi**2, axis=1), 1e-12)
    alpha = hertz.hertz_impact(m_eff, np.maximum(Om * clearance, 1e-6), K).max_approach
    kp = linearised_stiffness(alpha, K)
    cp = linear_contact_damping(kp, m_eff, e)
    model = WhirlModel(span=L, modes=modes, omega=omega, mass=mass, rotary_speed=Om, points=x, kinds=kinds,
                      clearance=clearance, radius=radius, stiffness=K, phi=phi, eccentric=eccentric, side=side,
                      damping=damping, drag=float(drag), drag_shapes=shapes, drag_weights=drag_w,
                      friction=mu, slip_velocity=float(option.slip_velocity),
                      restitution=e, hysteresis=calibrated_hysteresis(e), law=law,
                      penalty_stiffness=np.asarray(kp, float), penalty_damping=np.asarray(cp, float), props=props,
                      eccentricity=eps, frame=frame, hole_curvature=hole_curvature, basis=basis,
                      joint_mass=float(joint_mass), joint_weight=float(joint_side), point_side=point_side,
                      joint_points=at_joint if joint_mass > 0.0 and np.any(at_joint) else None)
    if option.reference_residual in DYNAMIC_RESIDUALS and np.all(np.isfinite(omega)) and symmetric_points(x, L):
        # the modes left out as one residual vector per contact point in the kernel's modes, matched to their
        # flexibility and its second moment (their receptance f + g ω² + … at low frequency), the joints' mass on them;
        # "radiating": with the bending waves' resistance at the points as their damping; docs/reference_model.md §2.1
        model.joint_x = joint_x if joint_mass > 0.0 else np.zeros(0)
        model.residual = residual_flexibility(model)
        model.residual_mass = residual_second_moment(model) / model.residual**2
        if option.reference_residual_vectors > 1 and option.reference_recovery == "vectors":
            raise ValueError(f"reference_residual_vectors = {option.reference_residual_vectors!r} with "
                             "reference_recovery = 'vectors': allowed only with 'force' (the vectors' own field is "
                             "the first order's)")
        model.ritz = residual_ritz(model, drag_x,
                                   float(option.damping_ratio) if damping_model == "viscous" else 0.0,
                                   radiating=option.reference_residual == "radiating",
                                   count=option.reference_residual_vectors)
        model.recovery = option.reference_recovery
        model.pulse_speed = option.reference_pulse_speed
    elif option.reference_residual != "none" and np.all(np.isfinite(omega)):
        # the modes left out respond to a contact force statically: their flexibility at the point in series with its
        # spring (the penalty's folded in, k/(1 + k f)); docs/reference_model.md §2.1. Also for "dynamic" where the
        # contact points do not lie symmetrically about the middle (the residual vectors would mix the modes' parities)
        model.residual = residual_flexibility(model)
        model.penalty_stiffness = model.penalty_stiffness / (1.0 + model.penalty_stiffness * model.residual)
    model.drag_precision = option.reference_drag_precision
    if option.reference_strike_force == "pulse" and law == 0:
        model.pulse = strike_pulses(model)
        model.pulse_work = option.reference_pulse_work
    if option.reference_stress_band == "timoshenko":
        model.stress_band = stress_band_edge(scene)
    if option.reference_drag_modes != "all":
        model.slow_drag = drag_on_slow_modes(model, option, scene)
    return model


def drag_on_slow_modes(model: WhirlModel, option, scene: Scene) -> tuple | None:
    """The integrator's drag summed on the first N_d modes alone (``reference_drag_modes``: "band" the modes up to
    :func:`stress_band_edge`, "32" the first 32; docs/reference_model.md §4): their shapes (G_d, N_d) at the drag rule
    of N_d (:func:`drag_quadrature`, 2N_d + 8 Gauss points), its weights [m], and the modes above's linear factors
    ∫ ψ_n² dx / L [-] (N,) (by the full rule; ½ on the periodic basis, less on the joints' modes; 0 below N_d) with
    ``reference_drag_rest = "linear"``, zeros with "none" (kernels.drag.drag_linearised); None where N_d is every
    mode. Raises ValueError with the
    residual vectors (their drag shapes mix the kept modes')."""
    count = (int(np.count_nonzero(model.omega <= stress_band_edge(scene))) if option.reference_drag_modes == "band"
             else int(option.reference_drag_modes))
    if count >= model.n_modes:
        return None
    if model.dynamic:
        raise ValueError(f"reference_drag_modes = {option.reference_drag_modes!r} with reference_residual = "
                         f"{option.reference_residual!r}: allowed only with series or none")
    x, w = drag_quadrature(model.span, count, option.reference_drag_quadrature)
    rest = np.zeros(model.n_modes)
    if option.reference_drag_rest == "linear":
        rest = model.drag_weights @ model.drag_shapes**2 / model.span
        rest[:count] = 0.0
    return np.ascontiguousarray(model.shapes(x)[:, :count]), w, rest


def drag_quadrature(span: float, modes: int, rule: str = "gauss") -> tuple[np.ndarray, np.ndarray]:
    """The points x_g [m] and weights w_g [m] at which the model sums the mud's quadratic drag over the section
    [0, L] (the integral ∫ ψ_n D |u̇| u̇ dx of docs/reference_model.md §1, §4) for N ``modes``, symmetric about
    midspan (the kernel sums the drag by mirror pairs, :func:`whirl_kernel.drag_halves`). ``"gauss"``:
    Gauss–Legendre with 2N + 8 points. ``"uniform"``: the midpoint rule with ⌊3N/2⌋ + 8 evenly spaced points
    x_g = (g + ½) L/G, weights L/G — the trapezoidal rule of a period, which integrates e^{2πi h x/L} exactly for
    every harmonic 0 < |h| < G (Trefethen & Weideman, SIAM Rev. 56, 385–458, 2014, doi:10.1137/130932132), so the
    products of three of the periodic basis' N functions (harmonics up to 3N/2, :func:`mode_shapes`) exactly, where
    Gauss–Legendre, made for polynomials on an interval, needs more points per harmonic (docs/reference_model.md §6:
    at 64 and 128 modes fewer points and a smaller quadrature error than "gauss"'s). The drag's |u̇| u̇ is no such
    product: neither rule is exact on it. Raises ValueError for another rule."""
    if rule == "gauss":
        gx, gw = whirl.gauss_legendre(2 * modes + 8)
        return 0.5 * span * (gx + 1), 0.5 * span * gw
    if rule == "uniform":
        G = 3 * modes // 2 + 8
        return (np.arange(G) + 0.5) * (span / G), np.full(G, span / G)
    raise ValueError(f"reference_drag_quadrature = {rule!r}; allowed: "
                     f"{', '.join(ReferenceOptions.choices('reference_drag_quadrature'))}")


#: How far [-] below the Euler–Bernoulli beam's frequency Timoshenko's may lie within the stresses' band
#: (``reference_stress_band = "timoshenko"``, :func:`stress_band_edge`): the study's statistical tolerance
#: (solver.statistical_tolerance, 5 %), the accuracy its chaotic figures are held to, so that the beam theory's own
#: error in the modes the stresses take is no larger than what the figures may be off anyway. For the default study's
#: 4½-in pipe the edge is 283 Hz at 12 ppg, 304 Hz at 9 ppg (the 47th mode of its 37.8-m section;
#: docs/reference_model.md §2.3.1).
BAND_FRACTION = 0.05


def stress_band_edge(scene: Scene, fraction: float = BAND_FRACTION) -> float:
    """ω_b [rad/s]: the Euler–Bernoulli frequency of the scene's section at which Timoshenko's bending branch lies
    ``fraction`` below it (:func:`study.physics.section.timoshenko_band_edge`; Graff 1975 §3.4): the section's whole
    mass per length (mud and added mass with it) against its steel's shear stiffness κGA (κ of Cowper 1966 for the
    tube, G = E/(2(1 + ν))) and rotary inertia ρ_s I, the effective tension with them."""
    props = scene.props
    r_o, r_i = scene.outer_radius, scene.inner_radius
    youngs, nu = scene.pipe_youngs_modulus, scene.pipe_poisson_ratio
    shear = (float(section.cowper_shear_coefficient(nu, r_o, r_i)) * youngs / (2.0 * (1.0 + nu))
             * props["steel_area"])
    rotary = scene.pipe_density * float(section.second_moment_of_area(r_o, r_i))
    return section.timoshenko_band_edge(fraction, props["bending_stiffness"], shear, props["mass_per_length"], rotary,
                                        props["effective_tension"])


#: The slowest approach [m/s] at which a strike at a tool joint is a pulse (``reference_strike_force = "pulse"``): below
#: it the contact law takes it (a joint settling onto its wall, rolling or sliding is no strike).
PULSE_SPEED_FLOOR = 1e-2


def strike_pulses(model: WhirlModel) -> dict[str, np.ndarray] | None:
    """The strikes' pulses at the model's tool joints (docs/reference_model.md §2.4): each joint's local strike
    (:func:`study.physics.strike.strike_pulse_table`: its mass m_j on an infinite beam of the string's ρA and EI, the
    wall's K and the calibrated Hunt–Crossley damping) at the table's speeds (with the wall's loss ∫F dδ [J] per speed,
    ``loss``, for ``reference_pulse_work = "matched"``), and per point the floor speed [m/s] from
    which every strike is a pulse — at least :data:`PULSE_SPEED_FLOOR`, and where from there on up the local strike's
    history (to its end, or where the wall's damping holds the joint on it, to :data:`study.physics.strike.PAST_PEAK`
    times its rise: the rest of its force is the contact law's) is over before the bending waves of the neighbouring
    joints (the joints' spacing away) come back (:func:`study.physics.strike.return_time`); inf at the body's points.
    None without tool joints or without the joints' mass (the beam alone never lets go of the wall)."""
    from study.physics import strike

    joints = np.flatnonzero(model.kinds == 1)
    if joints.size == 0 or model.joint_mass <= 0.0:
        return None
    ei, rho = model.props["bending_stiffness"], model.props["mass_per_length"]
    spacing = model.joint_spacing
    P = model.points.size
    S, G = strike.TABLE_SPEEDS.size, strike.PULSE_GRID
    floor = np.full(P, np.inf)
    peak, duration, loss = np.ones((P, S)), np.ones((P, S)), np.ones((P, S))
    coefficients = np.zeros((P, S, 4, G - 1))
    for p in joints:
        table = strike.strike_pulse_table(float(model.joint_mass), float(model.stiffness[p]), float(rho), float(ei),
                                          float(model.hysteresis))
        holds = table["duration"] < strike.return_time(table["duration"], spacing, rho, ei)
        bad = np.flatnonzero(~holds)
        first = int(bad[-1]) + 1 if bad.size else 0  # every speed from here on holds
        if first < S:
            floor[p] = max(PULSE_SPEED_FLOOR, float(table["speeds"][first]))
        peak[p], duration[p], coefficients[p] = table["peak"], table["duration"], table["coefficients"]
        loss[p] = table["loss"]
    return dict(floor=floor, speeds=strike.TABLE_SPEEDS.copy(), peak=peak, duration=duration,
                coefficients=coefficients, loss=loss)


#: The ``reference_residual`` values that integrate the modes left out as residual vectors (:func:`residual_ritz`).
DYNAMIC_RESIDUALS = ("dynamic", "radiating")


def residual_ritz(model: WhirlModel, drag_points: np.ndarray, damping_ratio: float = 0.0,
                  radiating: bool = False, count: int = 1) -> dict:
    """The kept modes augmented by ``count`` residual vectors per contact point (modal truncation augmentation:
    Dickens, Nakagawa & Wittbrodt, Comput. Struct. 62, 985–998, 1997; the residual flexibility and mass of Rubin, AIAA
    J. 13, 995–1006, 1975; several a point as the load-dependent Ritz vectors of Wilson, Yuan & Dickens, Earthq. Eng.
    Struct. Dyn. 10, 813–821, 1982), the Rayleigh–Ritz modes of the two (docs/reference_model.md §2.1). Residual
    vector (1, p) is the static field of the modes left out under a unit force at contact point x_p, v_1p(x)
    (:func:`static_correction`'s deflection: the periodic beam-column's less the kept modes'); vector (k + 1, p) their
    flexibility applied to the pipe's mass times vector (k, p),
    v_kp(x) = S_k(x_p, x) = Σ_{n≥N} ψ_n(x_p) ψ_n(x)/(m ω_n^{2k}) (:func:`krylov_fields`, scaled by ω_r^{2(k−1)}, ω_r
    the first mode left out's frequency, so that all are of one size). With the coordinates (q, s),
    u(x) = Σ q_n φ_n(x) + Σ s_kp v_kp(x) (s_1p [N] the force whose field v_1p is), the stiffness is diag(m ω_n²) ⊕ F,
    F_(kp)(lq) = S_{k+l−1}(x_p, x_q), the mass m I ⊕ G, G_(kp)(lq) = S_{k+l}(x_p, x_q)
    (:func:`residual_moments`; S_1 in closed form, S_2 :func:`residual_second_moments`), + the tool joints' m_j at x_j
    on u(x_j) (their coupling of the kept modes and the vectors, m_j φ(x_j) v_kp(x_j)): the vectors are orthogonal to
    the kept modes in the pipe's mass (the modes left out's span), and the Ritz solve orthogonalises them among
    themselves. K vectors a point match the left-out modes' receptance at the points, Σ ψ_n ψ_nᵀ/(m (ω_n² − ω²)), in
    its first 2K moments S_1 … S_2K (its Taylor series in ω² to ω^{2(2K−1)}; one vector f + g ω²). The kept modes and
    the vectors are each of one parity about the section's middle where the contact points are (pairs x, L − x: their
    sum and difference), so the modes are solved per parity and keep one, as the kernel's drag sums need. Raises
    ValueError where the contact points are not so (:func:`symmetric_points`; :func:`build_model` keeps the series law
    there).

    Returns omega2 (Q,) with Q = N + count·P, vectors (Q, Q) (column k: mode k on (q, σ), σ the vectors' parity
    combinations per order k, s_k = C σ_k; scaled to the modal mass m), combinations C (P, P), inverse (Q, Q)
    (vectorsᵀ M/m: (q, σ) to the modes), and the kernel's phi (P, Q), drag_shapes (G, Q) at ``drag_points`` [m],
    eccentric and side (Q,) per modal mass, damping (Q,) 2ζω (with ``radiating`` plus :func:`radiation_damping`),
    weights (Q,) of the error scale (1/n² of the half-waves of each mode's frequency), and count."""
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
    if int(count) < 1:
        raise ValueError(f"reference_residual_vectors = {count!r}: allowed a whole number of 1 or more")
    count = int(count)
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
    whole = np.kron(np.eye(count), combinations)  # (count·P)²: each order's vectors in their parity combinations
    moments = krylov_moments(model, 2 * count)  # (2K, P, P): S_j
    scale2 = model.first_left_out() ** 2  # order k's vectors scaled by ω_r^{2(k−1)}: (k, l)'s blocks by ω_r^{2(k+l)}
    KP = count * P
    flexibility = np.block([[moments[k + l] * scale2 ** (k + l) for l in range(count)]
                            for k in range(count)])  # S_{k+l−1}
    mass_rr = np.block([[moments[k + l + 1] * scale2 ** (k + l) for l in range(count)]
                        for k in range(count)])  # S_{k+l}
    coupling = np.zeros((N, KP))
    if model.joint_mass > 0.0 and model.joint_x.size:
        at_joints = krylov_fields(model, model.joint_x, count).reshape(KP, -1)  # (count·P, J): v_kp(x_j)
        coupling = model.joint_mass * model.shapes(model.joint_x).T @ at_joints.T
        mass_rr = mass_rr + model.joint_mass * at_joints @ at_joints.T
    K = N + KP
    stiffness = np.zeros((K, K))
    stiffness[:N, :N] = np.diag(m * np.nan_to_num(model.omega) ** 2)
    stiffness[N:, N:] = whole.T @ flexibility @ whole
    mass = np.zeros((K, K))
    mass[:N, :N] = m * np.eye(N)
    mass[:N, N:] = coupling @ whole
    mass[N:, :N] = mass[:N, N:].T
    mass[N:, N:] = whole.T @ mass_rr @ whole
    kept_symmetric = (model.modes == 0) | (model.modes % 2 == 1)
    n_sym = len(symmetric)
    order = np.arange(KP) % P  # each vector's combination
    rows_of = [np.concatenate((np.flatnonzero(kept_symmetric), N + np.flatnonzero(order < n_sym))),
               np.concatenate((np.flatnonzero(~kept_symmetric), N + np.flatnonzero(order >= n_sym)))]
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
    at_points = np.hstack([moments[k].T * scale2**k for k in range(count)]) @ whole  # (P, count·P): at the points
    phi = np.hstack((model.phi, at_points)) @ vectors
    at_drag = krylov_fields(model, np.asarray(drag_points, float), count).reshape(KP, -1)  # (count·P, G)
    drag_shapes = np.hstack((model.drag_shapes, at_drag.T @ whole)) @ vectors
    side = kept.T @ model.side
    if model.point_side is not None:  # the joints' weight at the joints: on the vectors, Σ_q W_q v_kp(x_q)
        weights_field = np.concatenate([moments[k] * scale2**k @ model.point_side for k in range(count)])
        side = side + residual.T @ (whole.T @ weights_field) / m
    omega = np.sqrt(omega2)
    ei, tn, M = (model.props[k] for k in ("bending_stiffness", "effective_tension", "mass_per_length"))
    wavenumber = np.sqrt(np.maximum((-tn + np.sqrt(tn**2 + 4 * ei * M * omega2)) / (2 * ei), 0.0))
    damping = 2.0 * float(damping_ratio) * omega
    if radiating:
        damping = damping + radiation_damping(omega, at_points @ residual, m, M, ei)
    return dict(omega2=omega2, vectors=vectors, combinations=combinations, inverse=vectors.T @ mass / m, phi=phi,
                drag_shapes=drag_shapes, eccentric=kept.T @ model.eccentric, side=side, damping=damping,
                weights=1.0 / np.maximum(wavenumber * L / np.pi, 1.0) ** 2, count=count)


def krylov_fields(model: WhirlModel, x: np.ndarray, count: int) -> np.ndarray:
    """(count, P, X) the residual vectors of :func:`residual_ritz` on the stations x [m] [m/N]: order 1 the left-out
    modes' static field under a unit force at each contact point (:func:`static_correction`), order k + 1 ≥ 2 their
    moment S_{k+1}(x_p, x) (:func:`residual_moments`) times ω_r^{2k}, ω_r the first mode left out's frequency."""
    x = np.asarray(x, float)
    scale2 = model.first_left_out() ** 2
    out = [static_correction(model, x)[:, :x.size]]
    out += [residual_moments(model, k, x) * scale2 ** (k - 1) for k in range(2, count + 1)]
    return np.stack(out)


def krylov_moments(model: WhirlModel, orders: int) -> list:
    """The left-out modes' moments between the contact points, S_j (P, P) for j = 1 … ``orders``
    [m/N s^{2j−2}] (:func:`residual_moments`; S_1 the closed form's :func:`static_correction`, symmetrised, S_2
    :func:`residual_second_moments` with its tail)."""
    x = model.points
    first = static_correction(model, x)[:, :x.size]
    out = [0.5 * (first + first.T), residual_second_moments(model)]
    out += [residual_moments(model, j, x) for j in range(3, orders + 1)]
    return out[:orders]


def radiation_damping(omega, residual_shapes, modal_mass, mass_per_length, bending_stiffness) -> np.ndarray:
    """(K,) d_k = Σ_p Re Z(ω_k) ψ_pk²/m [1/s], the linear damping per modal mass (2ζ_k ω_k) of the residual vectors'
    Ritz modes (``reference_residual = "radiating"``, docs/reference_model.md §2.1): a dashpot of the infinite beam's
    driving-point resistance Re Z(ω) = 2 ρA c_B(ω) (:func:`study.physics.strike.driving_point_resistance`) at each
    contact point p on the vectors' own motion there, evaluated at the mode's frequency ω_k [rad/s] and kept on the
    diagonal. ``residual_shapes`` (P, K) ψ_pk [m per unit modal coordinate], the vectors' part of mode k's deflection
    at point p, Σ_q v_q(x_p) s_q (0 on a kept mode's own part, which stays undamped); ``modal_mass`` m [kg],
    ``mass_per_length`` ρA [kg/m], ``bending_stiffness`` EI [N m²]. It stands for the dispersal of the modes left out:
    in the continuous string a point's ringing above the kept modes leaves it as bending waves (the modes there dense
    against the strike's time), while one vector a point would ring on coherently and strike with it again. A single
    vector alone (mass μ, flexibility f at one point, ψ² = m/μ) rings down as e^{−t Re Z/(2μ)}."""
    from study.physics.strike import driving_point_resistance

    resistance = driving_point_resistance(omega, mass_per_length, bending_stiffness)
    return resistance * np.sum(np.asarray(residual_shapes, float) ** 2, axis=0) / modal_mass


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
