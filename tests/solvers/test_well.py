"""The reference model's scene as a real well (issue 33; docs/reference_model.md §1, §2): the periodic section of a
long string whose tool joints rest on the wall, checked against the closed forms of a continuous beam-column on equal
supports (study.physics.well) and of a free rigid body."""

from pathlib import Path

import numpy as np
import pytest

from study import config
from study.physics import string_modes, well
from study.physics import whirl as whirl_physics
from study.solvers.methods import auto, freewhirl, reference, sliding
from study.solvers.model.options import Tolerances
from study.solvers.model.scene import Scene

ROOT = Path(__file__).resolve().parents[2]


#: The pipe joints' eccentricities aligned in a three-joint section: the reading the figures of these tests were
#: measured in (the default study turns them 90° in four joints, docs/reference_model.md §1; :func:`_study`).
ALIGNED = {"pipe.eccentricity_turn": "aligned", "contact.section_length": "93 ft"}


def _study(rpm: float, klbf: float, **extra) -> dict:
    """A point of configs/default.toml in its own reading (straight hole, e = 0.3, 9 ppg, no flow)."""
    point = config.load(ROOT / "configs" / "default.toml", {
        "load.rotary_speed": f"{rpm} rpm", "load.axial_tension": f"{klbf * 1000} lbf", "impact.restitution": 0.3,
        "mud.density": "9 ppg", "mud.flow_velocity": "0 ft/s"}).point()
    return {**point, **extra}


def _default(rpm: float, klbf: float, **extra) -> dict:
    """:func:`_study`'s point with the pipe joints' eccentricities aligned in three joints (:data:`ALIGNED`)."""
    point = config.load(ROOT / "configs" / "default.toml", {
        "load.rotary_speed": f"{rpm} rpm", "load.axial_tension": f"{klbf * 1000} lbf", "impact.restitution": 0.3,
        "mud.density": "9 ppg", "mud.flow_velocity": "0 ft/s", **ALIGNED}).point()
    return {**point, **extra}


def test_the_periodic_basis_repeats_and_has_one_modal_mass():
    # docs/reference_model.md §1: ψ_0 = 1/√2, cos and sin of 2πjx/L; ∫ψ_m ψ_n dx = (L/2) δ_mn (Gauss-Legendre, exact
    # for these trigonometric polynomials at 64 points), ψ(x + L) = ψ(x), and ψ'' = −k² ψ
    L, N = 28.3464, 9
    gx, gw = whirl_physics.gauss_legendre(64)
    x, w = 0.5 * L * (gx + 1), 0.5 * L * gw
    shapes = string_modes.mode_shapes(x, L, N)
    np.testing.assert_allclose(shapes.T @ (shapes * w[:, None]), 0.5 * L * np.eye(N), atol=1e-12 * L)
    np.testing.assert_allclose(string_modes.mode_shapes(x + L, L, N), shapes, atol=1e-12)
    k = string_modes.mode_wavenumbers(L, N)
    np.testing.assert_allclose(string_modes.mode_shapes(x, L, N, 2), -shapes * k**2, atol=1e-12)


@pytest.mark.parametrize("tension", [0.0, 5e3, 1.3e5, -2e3])
def test_the_static_moment_of_a_point_load_on_the_periodic_beam_column_is_its_series(tension):
    # periodic_point_moment's closed form (Gradshteyn & Ryzhik 1.445.2, 1.443.3) against its own Fourier series
    # (2/L) Σ_{j≥1} cos(k_j s)/(k_j² + T/EI), summed to j = J = 200 000: the tail is at most (2/L) Σ_{j>J} 1/k_j² <
    # L/(2π² J) [m], the bound held
    L, ei = 28.3464, 8.3e5
    s = np.linspace(-L, 2 * L, 37)
    j = np.arange(1, 200_001)
    k = 2 * np.pi * j / L
    series = (2 / L) * np.cos(np.outer(s, k)) @ (1.0 / (k**2 + tension / ei))
    closed = string_modes.periodic_point_moment(s, L, ei, tension)
    np.testing.assert_allclose(closed, series, rtol=0, atol=L / (2 * np.pi**2 * j[-1]))


def test_a_free_rigid_section_under_a_constant_side_load_accelerates_as_w_over_m():
    # Newton: a body of mass M per length under w per length, nothing else: u = w t²/(2M). The string's rigid
    # translation has ω = 0, where the Lawson step keeps its plain form (whirl_kernel._lawson_step); without the tool
    # joints' mass, which a uniform load would bend the string against
    inputs = _default(100, 10, hole_diameter=0.5, eccentricity=0.0, reference_damping="none", side_load=30.0,
                      tool_joint_length=0.0)
    model = reference.build_model(inputs)
    N = model.n_modes
    for scheme in reference.SCHEMES:
        run = reference.Integrator(model, 1e-6, np.zeros(4 * N + 4), scheme)
        run.run(0.05)
        u = run.z[0] * model.phi[0, 0]
        assert u == pytest.approx(0.5 * 30.0 / model.props["mass_per_length"] * 0.05**2, rel=1e-12), scheme
        assert np.all(run.z[1:N] == 0.0)  # a uniform load bends nothing


def _joint_system(model, joint_mass):
    """The periodic basis' stiffness (diagonal) and mass matrices with ``joint_mass`` at each tool joint."""
    L, n = model.span, model.modes
    k = string_modes.mode_wavenumbers(L, n)
    ei, tn = model.props["bending_stiffness"], model.props["effective_tension"]
    joints = string_modes.contact_layout(L, L / 3, 0)[0]
    shapes = string_modes.mode_shapes(joints, L, n)
    return 0.5 * L * (ei * k**4 + tn * k**2), 0.5 * model.props["mass_per_length"] * L * np.eye(n.size) + \
        joint_mass * shapes.T @ shapes


def test_the_joints_mass_makes_modes_of_the_generalized_eigenproblem():
    # docs/reference_model.md §1: K a = ω² M a on the periodic basis with the joints' point masses (Rayleigh-Ritz)
    inputs = _default(100, 10)
    model = reference.build_model(inputs)
    m_j = model.joint_mass
    assert m_j > 40.0  # the default 6 1/4 x 3 1/4-in joint of 20 in: 45 kg beyond the plain pipe's
    K, M = _joint_system(model, m_j)
    B = model.basis
    # the modes are M- and K-orthogonal, each of the one modal mass M L/2 the kernel divides by
    np.testing.assert_allclose(B.T @ M @ B, model.mass * np.eye(model.n_modes), atol=1e-9 * model.mass)
    np.testing.assert_allclose(B.T @ (K[:, None] * B), model.mass * np.diag(model.omega**2),
                               atol=1e-9 * model.mass * model.omega[-1] ** 2)
    # the rigid translation: a constant whose mass is the string's, M L + Σ m_j (Newton)
    assert model.omega[0] == 0.0 and np.count_nonzero(B[:, 0]) == 1
    assert B[0, 0] ** 2 * (model.props["mass_per_length"] * model.span + 3 * m_j) == pytest.approx(
        model.props["mass_per_length"] * model.span, rel=1e-12)
    # sin 2π·3x/L has its nodes at the joints (x = 0, L/3, 2L/3): the masses do not move, ω is the basis' own
    plain = reference.build_model({**inputs, "tool_joint_length": 0.0})
    assert model.omega[6] == pytest.approx(plain.omega[6], rel=1e-12)
    assert np.all(model.omega[1:] <= plain.omega[1:] * (1 + 1e-12))  # more mass, no stiffer: no mode rises
    # Rayleigh's principle: the first bending mode lies at or below the quotient of its trial function cos 2πx/L,
    # which the joints' masses see as Σ cos² = 3/2 of m_j, ω² ≤ (EI k⁴ + T k²)/(M + 3 m_j/(2·L/2)); with that function
    # and the constant alone (3 modes) the cosine is M-orthogonal to the constant (Σ cos = 0) and it is exact
    ceiling = np.sqrt(K[1] / M[1, 1])
    assert model.omega[1] <= ceiling and model.omega[1] == pytest.approx(ceiling, rel=0.02)
    three = reference.build_model({**inputs, "reference_modes": 3})
    assert three.omega[1] == pytest.approx(ceiling, rel=1e-12)
    # without the joints' mass the basis itself, and the frequencies of before
    assert plain.basis is None
    np.testing.assert_array_equal(plain.omega, np.where(np.arange(16) == 0, 0.0, np.sqrt(
        (plain.props["bending_stiffness"] * plain.wavenumber**4 + plain.props["effective_tension"]
         * plain.wavenumber**2) / plain.props["mass_per_length"])))


def test_a_free_string_with_its_joints_accelerates_as_its_whole_mass():
    # Newton: the string's centre of mass under the side load w L, nothing else, moves w L t²/(2 (M L + Σ m_j)) — the
    # rigid translation's coordinate; the uniform load against the joints' point masses also bends it (the modes
    # above the rigid one, which the joints' mass couples to the load)
    inputs = _default(100, 10, hole_diameter=0.5, eccentricity=0.0, reference_damping="none", side_load=30.0)
    model = reference.build_model(inputs)
    N = model.n_modes
    total = model.props["mass_per_length"] * model.span + 3 * model.joint_mass
    for scheme in reference.SCHEMES:
        run = reference.Integrator(model, 1e-6, np.zeros(4 * N + 4), scheme)
        run.run(0.05)
        u = run.z[0] * model.phi[0, 0]
        assert u == pytest.approx(0.5 * 30.0 * model.span / total * 0.05**2, rel=1e-12), scheme
        assert np.any(run.z[1:N] != 0.0)


@pytest.mark.parametrize("klbf", [0, 10, 30])
def test_at_rest_every_joint_carries_its_share_on_a_continuous_beam_column(klbf):
    # issue 33: in a straight inclined hole (30 deg here) every joint lies on the low side with its share w s of the
    # buoyed weight's side load; the body between joints is a continuous beam-column on equal supports, clamped at
    # each joint by symmetry (docs/model.md §13.3): its deflection relative to the joints and its moments at the joints and
    # at mid-joint are well.beam_column_deflection, support_moment and midspan_moment (Timoshenko & Gere 1961, §1.11)
    inputs = _default(100, klbf, inclination=np.radians(30.0), friction=0.0)
    model = reference.build_model(inputs)
    rest = sliding.rest(model)
    assert rest["found"]
    props = model.props
    w = float(whirl_physics.side_load(props["pipe_mass"], props["internal_mud_mass"], inputs["mud_density"],
                                      inputs["outer_diameter"] / 2, np.radians(30.0)))
    joints = model.kinds == 1
    spacing = model.span / np.count_nonzero(joints)
    # and each joint its own weight beyond the plain pipe's (the lumped joint, well.tool_joint_excess), which
    # lies on the support and does not bend the body
    joint = well.tool_joint_excess(7850.0, inputs["tool_joint_diameter"], inputs["tool_joint_inner_diameter"],
                                   inputs["tool_joint_length"], props["pipe_mass"], inputs["outer_diameter"],
                                   inputs["inner_diameter"], inputs["mud_density"])[1] * np.sin(np.radians(30.0))
    assert joint > 0.1 * w * spacing
    np.testing.assert_allclose(rest["normal"][joints], w * spacing + joint, rtol=1e-9)
    assert np.all(rest["touching"] == joints)
    ei, tension = props["bending_stiffness"], props["effective_tension"]
    x = np.linspace(0.0, spacing, 41)
    forces = rest["forces"][None, :, 0]
    fields = reference.periodic_fields(model, rest["state"][None, :model.n_modes], forces, x, 0)
    relative = fields["deflection"][0] - fields["deflection"][0][0]
    expected = well.beam_column_deflection(x, w, tension, ei, spacing)
    np.testing.assert_allclose(relative, expected, atol=1e-6 * np.max(expected))
    assert fields["moment"][0][0] == pytest.approx(well.support_moment(w, tension, ei, spacing), rel=1e-6)
    assert fields["moment"][0][20] == pytest.approx(well.midspan_moment(w, tension, ei, spacing), rel=1e-6)
    # and the joints on the wall: at their clearance plus the Hertz approach (F/K)^(2/3)
    approach = (rest["normal"][joints] / model.stiffness[joints]) ** (2 / 3)
    np.testing.assert_allclose(rest["u"][joints, 0], model.clearance[joints] + approach, rtol=1e-9)


def test_friction_turns_the_resting_string_aside_by_its_friction_angle():
    # Coulomb: the string turning on its joints is held by the wall's normal force and the friction μ s F_n (s the
    # regularised sign of the surface's sliding speed Ω r_tj); their resultant balances the weight's side load, so the
    # joints sit turned from the low side by −atan(μ s) against the rotation, F_n = w s_j/√(1 + μ² s²)
    inputs = _default(100, 10, inclination=np.radians(30.0), friction=0.3)
    model = reference.build_model(inputs)
    rest = sliding.rest(model)
    joints = model.kinds == 1
    s = whirl_physics.friction_factor(model.rotary_speed * model.radius[joints], model.slip_velocity)
    angle = np.arctan2(rest["u"][joints, 1], rest["u"][joints, 0])
    np.testing.assert_allclose(angle, -np.arctan(0.3 * s), rtol=1e-9)
    # the side load each joint carries, the body's and its own weight (the rigid translation's generalised force
    # over ψ_0's sum at the joints)
    share = model.side[0] * model.mass / (3 * model.phi[joints, 0].mean())
    np.testing.assert_allclose(rest["normal"][joints], share / np.sqrt(1 + (0.3 * s) ** 2), rtol=1e-9)


# --- a curved hole ---------------------------------------------------------------------------------------------

DOGLEG = np.radians(3.0) / (100 * 0.3048)  # 3 deg/100 ft [1/m]


def _curved(klbf: float, direction: float, **extra) -> dict:
    """The default study's pipe in a vertical hole curving at 3 deg/100 ft towards ``direction`` [rad]."""
    return _default(100, klbf, inclination=0.0, dogleg_curvature=DOGLEG, dogleg_direction=direction, **extra)


@pytest.mark.parametrize("direction", [0.0, np.pi / 2, np.pi])
def test_in_a_curved_hole_the_joints_rest_on_the_inside_of_the_curve_at_lubinskis_stress(direction):
    # the tension's side load T κ presses the joints onto the inside of the curve (towards its centre, φ from the low
    # side), each with its share T κ s; where the body between them stays clear its bending at the joints is
    # Lubinski's (1961, doi:10.2118/1543-G-PA; API RP 7G): σ = (E D κ/2) KL/tanh KL, K = √(T/EI), L half the joint
    # spacing — the curve's E r_o κ raised by the tension straightening the body between the joints
    inputs = _curved(30, direction, friction=0.0, eccentricity=0.0)
    model = reference.build_model(inputs)
    rest = sliding.rest(model)
    assert rest["found"]
    props = model.props
    joints = model.kinds == 1
    spacing = model.span / np.count_nonzero(joints)
    tension, ei = props["effective_tension"], props["bending_stiffness"]
    np.testing.assert_allclose(rest["normal"][joints], tension * DOGLEG * spacing, rtol=1e-9)
    assert np.all(rest["touching"] == joints)  # the body clear (19 mm of sag against 22 mm more room)
    # the joints' direction in the hole's frame: the model's frame is turned by the side load's angle
    angle = model.frame + np.arctan2(rest["u"][joints, 1], rest["u"][joints, 0])
    np.testing.assert_allclose(np.cos(angle - direction), 1.0, atol=1e-12)
    # a revolution of the pipe lying there (the sliding state, nothing turning but the pipe): the stresses
    state = sliding.steady_state(inputs)
    values = reference.stresses(inputs, state["model"], state["window"], correction=True)
    r_o = inputs["outer_diameter"] / 2
    lubinski = well.lubinski_bending_stress(inputs["pipe_youngs_modulus"], 2 * r_o, DOGLEG, tension, ei, spacing / 2)
    assert values["max_bending_stress"] == pytest.approx(lubinski, rel=1e-6)
    assert values["alternating_bending_stress"] == pytest.approx(lubinski, rel=1e-3)  # every fibre through it
    assert values["alternating_bending_stress"] >= well.curvature_bending_stress(inputs["pipe_youngs_modulus"], r_o,
                                                                                 DOGLEG)
    # at a joint: every joint bends alike, so which one the largest stress is found at is a tie that the last bits break
    # (on an AMD znver4 host the station at x = L, the periodic section's image of the joint at 0)
    off = values["max_normal_stress_x"] - model.points[joints]
    assert np.min(np.abs((off + model.span / 2) % model.span - model.span / 2)) < 1e-9


def test_without_tension_a_turning_pipe_in_the_curve_is_bent_by_e_r_kappa_and_back():
    # T = 0: the curve's bending E r_o κ alone (Lubinski's KL → 0) with the weight's own sag between joints in a
    # horizontal plane: the alternating stress of a turning fibre is at least E r_o κ (issue 33)
    inputs = _default(100, 0, inclination=np.radians(8.0), dogleg_curvature=DOGLEG, dogleg_direction=np.pi / 2,
                      friction=0.3)
    result = sliding.solve(inputs)
    assert result.status in ("ok", "not_converged"), result.message
    r_o = inputs["outer_diameter"] / 2
    floor = well.curvature_bending_stress(inputs["pipe_youngs_modulus"], r_o, DOGLEG)
    assert result.values["alternating_bending_stress"] >= floor


@pytest.mark.parametrize("rpm, klbf, dogleg", [(100, 10, 0.0), (150, 30, DOGLEG)])
def test_the_answer_does_not_depend_on_the_section_holding_three_or_six_joints(rpm, klbf, dogleg):
    # the string repeats from section to section: a section of 6 joints holds the same steady state on the wall as
    # one of 3 (the sliding method keeps 48 modes on either, half the wavenumbers on the longer: measured within
    # 1.3e-4 on the figures; the reference model's runs, 16 and 32 modes, within 0.1-1.3 %, inside their stated
    # errors, docs/reference_model.md §7)
    three = sliding.solve(_default(rpm, klbf, dogleg_curvature=dogleg, dogleg_direction=np.pi))
    six = sliding.solve(_default(rpm, klbf, dogleg_curvature=dogleg, dogleg_direction=np.pi,
                                 section_length=6 * 31 * 0.3048))
    assert three.status == six.status == "ok"
    for name in ("peak_contact_force", "max_normal_stress", "alternating_bending_stress"):
        assert six.values[name] == pytest.approx(three.values[name], rel=5e-4), name


# --- contact anywhere along the pipe ---------------------------------------------------------------------------


def test_the_body_wall_excess_bounds_every_point_between_the_stations():
    # docs/reference_model.md §2: on stations h apart, max|u(x)| ≤ max over the stations + h²/8 max|u''| (the linear
    # interpolant's error, de Boor, A Practical Guide to Splines, ch. II; |u| of the interpolant is at most its ends'
    # by convexity): the excess stated on the 97 stations of the stresses is at least the true excess on a grid 64
    # times finer, and above it by no more than the bound, for random modal fields of the periodic string
    model = reference.build_model(_default(100, 10))
    rng = np.random.default_rng(33)
    coarse = np.unique(np.concatenate([np.linspace(0.0, model.span, 97), model.points]))
    fine = np.linspace(0.0, model.span, 64 * 96 + 1)
    c_b = float(np.max(model.clearance))
    ei = model.props["bending_stiffness"]
    quiet = np.zeros((1, model.points.size))  # no contact force: no approach
    for _ in range(5):
        q = rng.normal(size=(2, model.n_modes)) * c_b / (1.0 + np.arange(model.n_modes)) ** 2
        q[:, 0] = c_b  # lying towards the wall
        u = [model.shapes(coarse) @ q[j] for j in range(2)]
        moment = np.hypot(*(model.moment_shapes(fine) @ q[j] for j in range(2)))
        excess, bound = reference.body_wall_excess(model, coarse, u[0][None], u[1][None], quiet, np.max(moment))
        true = float(np.max(np.hypot(*(model.shapes(fine) @ q[j] for j in range(2))))) - c_b
        h = np.max(np.diff(coarse))
        assert bound == pytest.approx(h * h / 8 * np.max(moment) / ei, rel=1e-12)
        assert true <= excess <= true + bound
    # a body contact pressed in by its Hertz approach (F/K)^(2/3) is at its wall, not past it
    body = np.flatnonzero(model.kinds == 0)[0]
    force = np.zeros((1, model.points.size))
    force[0, body] = 2000.0
    alpha = (2000.0 / model.stiffness[body]) ** (2 / 3)
    at = np.array([model.points[body]])
    excess, bound = reference.body_wall_excess(model, at, np.array([[c_b + alpha]]), np.zeros((1, 1)), force, 0.0)
    assert bound == 0.0 and excess == pytest.approx(0.0, abs=1e-15)


def test_the_gate_calls_a_body_past_its_wall_between_stations_unphysical():
    from study.solvers.model import gate

    values = {"max_deflection": 0.05, "clearance": 0.054, "max_wall_excess": 0.02 * 0.054}
    status, message = gate.within_clearance(values, None, Tolerances(tolerance=0.01))
    assert status == "unphysical" and "beyond its contacts' Hertz approach" in message
    assert gate.within_clearance({**values, "max_wall_excess": 0.005 * 0.054}, None, Tolerances(tolerance=0.01)) is None


# --- backward whirl --------------------------------------------------------------------------------------------

def test_set_rolling_the_joints_roll_backwards_without_slip_with_the_body_clear():
    # dry whip: a tool joint rolling without slip on the wall whirls at −Ω R/c (Black 1968; Jansen 1991;
    # well.rolling_whirl_rate). The default study's pipe (9 ppg, no flow) in a 30° hole, μ = 0.8, 200 rpm, 20 000 lbf,
    # three contact stations on the body between joints, set on the wall whirling backwards at that rate (the string's
    # rigid translation at the joints' clearance: not its bent rolling shape, so it bounces first, for as many
    # revolutions as the last bits of the arithmetic decide, 5-8 measured) settles on rolling: four revolutions in a
    # row with the joints touching throughout, whirling at −R/c within 1 % (the slip of the regularised friction:
    # −2.497 against −2.5 measured), and, rolling on, no point of the body at its wall (docs/reference_model.md §7; a
    # drop from the hole's centre reaches it too, after about 200 revolutions, or bounces chaotically with the body
    # past its wall between three stations, which needs denser body stations)
    # (the kept modes' stiff contact: with the residual flexibility in series, docs/reference_model.md §2.1, the
    # bouncing before the rolling lasted 38 revolutions on one compilation and more than 60 on another)
    inputs = {**_default(200, 20), "friction": 0.8, "inclination": np.radians(30.0), "reference_body_stations": 3,
              "reference_residual": "none"}
    model = reference.build_model(inputs)
    N = model.n_modes
    joint = model.kinds == 1
    c, R = model.clearance[joint][0], model.radius[joint][0]
    rate = well.rolling_whirl_rate(1.0, R, c)
    start = np.zeros(4 * N + 4)
    start[0] = c / model.phi[np.flatnonzero(joint)[0], 0]
    start[3 * N] = start[0] * rate * model.rotary_speed
    run = reference.Integrator(model, 1e-6, start)
    held = []
    for _ in range(60):
        revolution = run.run(run.t + model.period, record=True)
        rolling = (np.all(revolution.contact_time[joint] >= (1 - 1e-9) * model.period)
                   and reference.whirl_measure(model, revolution)["whirl_frequency_ratio"] == pytest.approx(rate, rel=0.01))
        held = held + [revolution] if rolling else []
        if len(held) == 4:
            break
    assert len(held) == 4, "no four revolutions of rolling in 60"
    # rolling on: after 8 more revolutions (the start's ringing gone) the body is clear of its wall by a fifth of it
    run.run(run.t + 8 * model.period)
    window = run.run(run.t + 4 * model.period, record=True)
    assert np.all(window.contact_time[joint] >= (1 - 1e-9) * 4 * model.period)
    assert reference.whirl_measure(model, window)["whirl_frequency_ratio"] == pytest.approx(rate, rel=0.01)
    assert reference.stresses(inputs, model, window)["max_wall_excess"] < -0.2 * float(np.max(model.clearance))


def test_a_backward_bouncing_body_past_its_wall_gets_stations_until_it_is_within_it():
    # the chaotic backward bouncing of a drop (μ = 0.8, 30°, 200 rpm, 20 000 lbf; short: 16 modes, 6 revolutions and
    # a window of 2, held to a tolerance of 5 %) passes its wall between one body station a joint by 26 % of the
    # body's clearance (max_wall_excess, the bound along the whole body); the model raises its stations 1 -> 3 -> 7
    # (measured 15 %, then 2.8 %) and the answer's body is within its wall but for its contacts' Hertz approach and
    # the tolerance: the gate's clearance check passes (docs/reference_model.md §2, §7)
    from study.solvers.model import gate

    inputs = {**_default(200, 20), "friction": 0.8, "inclination": np.radians(30.0), "reference_initial": "rest",
              "reference_modes": 16, "reference_max_modes": 16, "reference_revolutions": 6, "reference_window": 2,
              "reference_max_revolutions": 8, "tolerance": 0.05}
    result = reference.solve_with_modes(inputs)
    tried = result.extras["body_stations_tried"]
    clearance = result.values["clearance"]
    assert tried[0]["stations"] == 1 and tried[0]["max_wall_excess"] > 0.1 * clearance
    assert [t["stations"] for t in tried] == [2 ** (i + 1) - 1 for i in range(len(tried))]
    assert result.extras["reference_body_stations"] == tried[-1]["stations"] <= 31
    assert result.values["max_wall_excess"] <= 0.05 * clearance
    assert gate.within_clearance(result.values, Scene.from_inputs(inputs), Tolerances.from_inputs(inputs)) is None
    assert result.values["whirl_frequency_ratio"] < -0.5 and result.values["impacts_per_revolution"] > 1
    assert "body stations raised from 1" in result.message


def test_the_modal_accelerations_are_the_recorded_velocities_rate():
    # the joints' inertia forces −m_j ü(x_j) of the quasi-static correction take q̈ from the modal equations with the
    # recorded contact forces (reference.modal_accelerations): on a recorded revolution of the string lying on its
    # joints (8°, 150 rpm) they are the central differences of the recorded velocities (second order in the rows'
    # spacing: 2e-4 of the largest measured), and their projection on the joints is the full one's
    inputs = {**_default(150, 10), "inclination": np.radians(8.0)}
    model = reference.build_model(inputs)
    N = model.n_modes
    run = reference.Integrator(model, 1e-9, reference.initial_state(model))
    run.run(3 * model.period)
    window = run.run(4 * model.period, record=True)
    assert window.contact_time.max() > 0.99 * model.period and window.onsets.sum() == 0
    t, rows = np.unique(window.times, return_index=True)
    acc = reference.modal_accelerations(model, window)
    rate = np.gradient(window.states[rows, 2 * N:4 * N], t, axis=0)
    assert np.max(np.abs(rate[2:-2] - acc[rows][2:-2])) < 1e-3 * np.max(np.abs(acc))
    at = model.joint_points
    joints = reference.modal_accelerations(model, window, model.phi[at].T)
    J = int(np.count_nonzero(at))
    np.testing.assert_allclose(joints[:, :J], acc[:, :N] @ model.phi[at].T, atol=1e-12 * np.max(np.abs(joints)))


# --- the eccentricity's phases from pipe joint to pipe joint -----------------------------------------------------

def test_the_turned_eccentric_load_is_its_integral_over_the_pipe_joints():
    # ∫₀ᴸ e^{iφ(x)} ψ_n(x) dx with φ = j·turn on the j-th pipe joint (string_modes.eccentric_factors) against
    # Gauss–Legendre quadrature on each joint (exact to rounding for these smooth pieces at 64 nodes); aligned, L/√2 on
    # the rigid translation alone (a uniform load); a third of a turn over three joints sums to nothing on it (1 + e^{2πi/3} +
    # e^{4πi/3} = 0) and drives the Bloch wave of wavenumber 2π/L (cos and sin k_1 x) most
    L, s, N = 3 * 9.4488, 9.4488, 16
    aligned = string_modes.eccentric_factors(L, s, N, 0.0)
    assert not np.iscomplexobj(aligned) and aligned[0] == L / np.sqrt(2.0) and np.all(aligned[1:] == 0.0)
    g, w = np.polynomial.legendre.leggauss(64)
    for turn in (2 * np.pi / 3, 4 * np.pi / 3, 2 * np.pi):
        quad = np.zeros(N, complex)
        for j in range(3):
            x = j * s + 0.5 * s * (g + 1.0)
            quad += np.exp(1j * j * turn) * (0.5 * s * w) @ string_modes.mode_shapes(x, L, N)
        np.testing.assert_allclose(string_modes.eccentric_factors(L, s, N, turn), quad, atol=1e-12 * L)
    turned = string_modes.eccentric_factors(L, s, N, 2 * np.pi / 3)
    assert abs(turned[0]) < 1e-12 * L and int(np.argmax(np.abs(turned))) in (1, 2)


def test_a_turn_that_does_not_close_over_the_section_is_refused_naming_both_fields():
    with pytest.raises(ValueError, match=r"pipe\.eccentricity_turn = 90 deg.*contact\.section_length"):
        reference.build_model(_default(100, 10, eccentricity_turn=np.radians(90.0)))
    reference.build_model(_default(100, 10, eccentricity_turn=np.radians(90.0), section_length=4 * 31 * 0.3048))
    point = config.load(ROOT / "configs" / "default.toml", {"pipe.eccentricity_turn": "aligned"}).point()
    assert point["eccentricity_turn"] == 0.0
    # and a config says it before any run (exit code 2 from the CLI): the default study's 90° in a three-joint section
    study = config.load(ROOT / "configs" / "default.toml").point()
    assert study["eccentricity_turn"] == np.pi / 2 and study["section_length"] == pytest.approx(4 * 31 * 0.3048)
    with pytest.raises(config.ConfigError, match=r"pipe\.eccentricity_turn = 90 deg.*multiple of 120 deg"):
        config.load(ROOT / "configs" / "default.toml", {"contact.section_length": "93 ft"})
    config.load(ROOT / "configs" / "default.toml", {**ALIGNED, "pipe.eccentricity_turn": "240 deg"})


def test_a_whole_turn_between_joints_gives_the_aligned_answers():
    # 360° between successive joints is the aligned string taken through the turned load's path (its complex modal
    # load, the kernel's quadrature part): the same answers to rounding, on the wall (the sliding state, 100 rpm,
    # 10 000 lbf; 356.653 N measured before the turn was an input) and clear of it (the paper's point, vertical:
    # the free whirl and the reference model's forward whirl)
    aligned = sliding.solve(_default(100, 10))
    whole = sliding.solve(_default(100, 10, eccentricity_turn=2 * np.pi))
    assert aligned.values["peak_contact_force"] == pytest.approx(356.6533, rel=1e-6)
    for name in ("peak_contact_force", "max_normal_stress", "alternating_bending_stress"):
        assert whole.values[name] == pytest.approx(aligned.values[name], rel=1e-9), name
    paper = config.load(ROOT / "configs" / "paper.toml").point()
    a, b = reference.solve_with_modes(paper), reference.solve_with_modes({**paper, "eccentricity_turn": 2 * np.pi})
    for name in ("max_deflection", "max_bending_stress", "alternating_bending_stress"):
        assert b.values[name] == pytest.approx(a.values[name], rel=1e-8), name


def test_clear_of_the_wall_the_turned_string_whirls_as_the_free_whirl_says():
    # a third of a turn between joints, the paper's point (vertical, 300 rpm): the string is no longer a rigid rotor;
    # it whirls forward bent in the Bloch wave of the turn, which the free whirl solves in closed form and the
    # reference model integrates (measured 0.8 % apart in deflection, 0.2 % in bending: the reference model's 16
    # modes and its start-up's drift off the centre, docs/reference_model.md §7)
    paper = {**config.load(ROOT / "configs" / "paper.toml").point(), "eccentricity_turn": 2 * np.pi / 3}
    free, ref = freewhirl.solve(paper), reference.solve_with_modes(paper)
    assert free.status == ref.status == "ok" and ref.values["peak_contact_force"] == 0.0
    assert ref.values["whirl_frequency_ratio"] == pytest.approx(1.0, abs=1e-3)
    assert ref.values["max_deflection"] == pytest.approx(free.values["max_deflection"], rel=0.02)
    assert ref.values["max_bending_stress"] == pytest.approx(free.values["max_bending_stress"], rel=0.02)
    # five times the aligned string's bending (its joints' mass only bends that one)
    aligned = freewhirl.solve({**paper, "eccentricity_turn": 0.0})
    assert free.values["max_bending_stress"] > 5 * aligned.values["max_bending_stress"]


def test_the_joints_share_of_the_turning_load_by_the_balance_of_forces():
    # on the wall, turning at 100 rpm (below the spans' first mode on the joints, 224 rpm at 30 000 lbf, and above the
    # string's sway along the wall, a pendulum of about 45 rpm), the turning load is carried nearly statically: aligned,
    # every span carries the same load, so each joint its share m_p ε Ω² s (as the side load's, by the periodic
    # string's symmetry), and the joint's force swings by that about its rest (measured 1.06 times it: the spans'
    # dynamics; 1.18 at 50 rpm, near the sway, 1.32 at 200 rpm, near the spans' mode); the joints alternating
    # (180°), the two spans on a joint pull it equally in opposite senses, so its force does not swing at all — at any
    # speed, also at 200 rpm and 30 000 lbf, where the aligned string's joints lift (their share amplified 1.32 times
    # by the spans' dynamics beats the 290 N they rest with, docs/reference_model.md §7) and the alternating ones lie
    # with their rest's force
    for rpm, klbf, turn, ratio in ((100, 30, 0.0, 1.0), (50, 30, np.pi, 0.0), (200, 30, np.pi, 0.0)):
        state = sliding.steady_state(_default(rpm, klbf, eccentricity_turn=turn, section_length=2 * 31 * 0.3048))
        assert state["why"] is None, (rpm, turn, state["why"])
        model = state["model"]
        joints = model.kinds == 1
        force = state["window"].forces[:, joints, 2]
        share = float(whirl_physics.eccentric_load(model.props["pipe_mass"], model.eccentricity, model.rotary_speed)
                      * model.span / np.count_nonzero(joints))
        swing = 0.5 * (force.max(axis=0) - force.min(axis=0))
        np.testing.assert_allclose(swing / share, ratio, atol=0.1 if ratio else 1e-6)
    assert "contact would open" in sliding.steady_state(_default(200, 30))["why"]
    # and the whole string's balance (Newton): aligned, the turning load m_p ε Ω² L lifts it off the low side where it
    # beats the side load of body and joints, w L + Σ W_j sin θ: at 227.0 rpm at 9 ppg in the 8° hole (docs/
    # reference_model.md §1, §7; the sliding state's contact opens sooner, 177.7 rpm, by the spans' dynamics); turned a
    # third of a turn from joint to joint, the three joints' loads sum to nothing (1 + e^{2πi/3} + e^{4πi/3} = 0): no
    # speed lifts the string as a whole
    model = reference.build_model(_default(200, 30))
    w = float(np.hypot(*Scene.from_inputs(_default(200, 30)).side_loads()[:2]))
    joints = model.kinds == 1
    lift = np.sqrt((w * model.span + np.count_nonzero(joints) * model.joint_weight)
                   / (model.props["pipe_mass"] * model.eccentricity * model.span))
    assert lift * 30 / np.pi == pytest.approx(227.0, abs=0.1)
    turned = string_modes.eccentric_factors(model.span, model.span / np.count_nonzero(joints), 4, 2 * np.pi / 3)
    assert abs(turned[0]) < 1e-12 * model.span


def test_the_default_reading_lifts_a_joint_by_the_balance_of_its_forces():
    # the default study's pipe joints turned 90° from one to the next in a four-joint section (docs/reference_model.md
    # §1, §7). Turning slowly (30 rpm, 30 000 lbf, 9 ppg) each joint's force swings by the 90° wave's quasi-static share
    # of the aligned m_p ε Ω² s: whirl.turned_joint_share, the Fourier–Bloch series of the beam-column on its joints
    # (Clapeyron's three moments without tension), 0.8325 here (the sliding state: 0.839, the spans' dynamics)
    point = _study(30, 30)
    assert point["eccentricity_turn"] == np.pi / 2
    state = sliding.steady_state(point)
    assert state["why"] is None
    model = state["model"]
    joints = model.kinds == 1
    assert np.count_nonzero(joints) == 4
    s = model.span / 4
    m_p, props = model.props["pipe_mass"], model.props
    force = state["window"].forces[:, joints, 2]
    swing = 0.5 * (force.max(axis=0) - force.min(axis=0))
    aligned = float(whirl_physics.eccentric_load(m_p, model.eccentricity, model.rotary_speed) * s)
    share = float(whirl_physics.turned_joint_share(np.pi / 2, props["effective_tension"], props["bending_stiffness"], s))
    assert share == pytest.approx(0.8325, abs=1e-4)
    np.testing.assert_allclose(swing / aligned, share, rtol=0.02)
    # the balance of a joint's forces: it lifts where share · m_p ε Ω² s beats its rest, w s + W_j sin θ (302.8 N at
    # 9 ppg, docs/reference_model.md §7): at 248.8 rpm for the 90° string, 227.0 rpm aligned (the whole string's
    # balance, as test_the_joints_share_of_the_turning_load_by_the_balance_of_forces computes it)
    w = float(np.hypot(*Scene.from_inputs(point).side_loads()[:2]))
    rest = w * s + model.joint_weight
    assert rest == pytest.approx(302.77, abs=0.01)
    rpm = lambda share_: float(whirl_physics.lift_off_speed(rest, share_, m_p, model.eccentricity, s)) * 30 / np.pi
    assert rpm(share) == pytest.approx(248.8, abs=0.1)
    assert rpm(1.0) == pytest.approx(227.0, abs=0.1)


def test_at_200_rpm_and_30_klbf_the_default_string_lies_below_the_eccentricity_that_lifts_it():
    # issue 33's check: at 200 rpm and 30 000 lbf in the straight hole (9 ppg) the joints lie, in contact all the time,
    # each with a force of the order of its share of the side load w s + W_j sin θ — where the mass eccentricity lets
    # them. The sliding state is linear in ε: with the default 0.1 in its joints' force swings by 343.9 N about the
    # 290.0 N they rest with (1.46 aligned shares: the spans' dynamics near their first mode on the joints, 214 rpm,
    # amplify the 90° wave's quasi-static 0.833 by 1.76): the contact opens and the string bounces (the reference model: docs/reference_model.md §7);
    # below 0.1 in × 290.0/343.9 = 0.084 in they lie. At 0.08 in `auto` answers the sliding state, ok
    opens = sliding.steady_state(_study(200, 30))
    assert "contact would open" in opens["why"]
    point = _study(200, 30, eccentricity=0.08 * 0.0254)
    result = auto.solve(point)
    assert (result.method, result.status) == ("sliding", "ok"), result.message
    assert result.values["contact_fraction"] == 1.0
    model = reference.build_model(point)
    s = model.span / np.count_nonzero(model.kinds == 1)
    share = float(np.hypot(*Scene.from_inputs(point).side_loads()[:2])) * s + model.joint_weight
    assert 1.0 < result.values["peak_contact_force"] / share < 2.5  # measured 568.5 N over 302.8 N: 1.88


def test_the_lift_off_eccentricity_turning_slowly_is_the_balance_of_a_joints_forces():
    # sliding.lift_off_eccentricity against the closed form it tends to where the spans' dynamics are weak (30 rpm,
    # 30 000 lbf, 9 ppg, the default 90° string): a joint lifts where share · m_p ε Ω² s beats the normal force it
    # rests with (whirl.lift_off_speed, tested above; the share whirl.turned_joint_share's 0.8325, the rest 290.0 N,
    # the sliding rest's w s + W_j sin θ turned aside by the friction). Inverted: at the point's ε (0.1 in) the
    # sliding state's linear estimate ε F/(F − min F_n) lifts the joints at the point's speed by the closed form (the
    # sliding state's share 0.839 against the series' 0.8325: 0.5 % in speed, measured 30.16 rpm); the eccentricity
    # itself (5.90 in, the secant on the least force) is lower by the second order of the joints' swing along the
    # wall at so large an ε (measured: the closed form's speed at it 31.70 rpm, 5.7 % above)
    point = _study(30, 30)
    state = sliding.steady_state(point)
    model, props = state["model"], state["model"].props
    s = model.span / 4
    share = float(whirl_physics.turned_joint_share(np.pi / 2, props["effective_tension"], props["bending_stiffness"], s))
    joints = model.kinds == 1
    rest = float(np.min(state["rest"]["normal"][joints]))
    assert rest == pytest.approx(302.77 / np.hypot(1.0, model.friction), rel=1e-3)  # the balance above, turned aside
    least = float(np.min(state["window"].forces[:, joints, 2]))
    linear = model.eccentricity * rest / (rest - least)
    speed = lambda eps: float(whirl_physics.lift_off_speed(rest, share, props["pipe_mass"], eps, s))
    assert speed(linear) == pytest.approx(model.rotary_speed, rel=0.01)
    lift = sliding.lift_off_eccentricity(point, state)
    assert lift < linear
    assert speed(lift) == pytest.approx(model.rotary_speed, rel=0.07)


@pytest.mark.parametrize("ppg, inches", [(9, 0.0854), (12, 0.0669)])
def test_the_lift_off_eccentricity_at_200_rpm_decides_whether_the_reference_model_lies_or_bounces(ppg, inches):
    # issue 33's check at 200 rpm, 30 000 lbf in the straight hole: the default string's joints lie where its mass
    # eccentricity is below sliding.lift_off_eccentricity (docs/reference_model.md §7: 0.1 in × 290.0/343.9 = 0.084
    # in by the swing of the sliding state's joint force at 9 ppg, 0.066 in at 12 ppg; the least force's secant gives
    # 0.0854 and 0.0669 in). The reference model itself (its run from the rest on the joints, 30 revolutions of
    # transient): at 0.9 ε_lift in contact all the time, no onset, a joint's force of the order of its share of the
    # side load (302.8 N at 9 ppg; measured 572-580 N: 1.9 shares, the turning load's swing on top); at 1.2 ε_lift the
    # joints bounce (measured: 36-45 onsets in the window, in contact 26-28 % of the time, 10-13 kN peaks)
    point = config.load(ROOT / "configs" / "default.toml", {
        "load.rotary_speed": "200 rpm", "load.axial_tension": "30000 lbf", "impact.restitution": 0.3,
        "mud.density": f"{ppg} ppg", "mud.flow_velocity": "0 ft/s"}).point()
    lift = sliding.lift_off_eccentricity(point)
    assert lift / 0.0254 == pytest.approx(inches, abs=0.001)
    quick = dict(reference_revolutions=30, reference_max_revolutions=34)
    lies = reference.simulate({**point, "eccentricity": 0.9 * lift, **quick})
    window, model = lies["window"], lies["model"]
    joints = model.kinds == 1
    share = float(np.hypot(*Scene.from_inputs(point).side_loads()[:2])) * model.span / 4 + model.joint_weight
    assert np.all(window.onsets[joints] <= 1)
    assert np.all(window.contact_time[joints] / (window.end - window.start) > 0.99)
    assert np.all((window.peak[joints] > share) & (window.peak[joints] < 3 * share))
    bounces = reference.simulate({**point, "eccentricity": 1.2 * lift, **quick})
    window = bounces["window"]
    assert np.all(window.onsets[joints] >= 5)
    assert np.all(window.contact_time[joints] / (window.end - window.start) < 0.8)
    assert np.max(window.peak[joints]) > 10 * share


def test_the_lift_off_eccentricity_is_an_output_where_a_side_load_lays_the_string_down():
    # solve_point adds it to the reference model's scene's methods (study.solvers.LIFT_OFF_METHODS), SI with its unit in
    # OUTPUTS; NaN in a straight vertical hole, where nothing lies on the wall (the free whirl's scene); the sliding
    # method's own value is the function's on its state
    from study.solvers import OUTPUTS, solve_point

    assert OUTPUTS["lift_off_eccentricity"][0] == "m"
    point = _study(100, 10)
    result = solve_point(point, "sliding")
    assert result.values["lift_off_eccentricity"] == sliding.lift_off_eccentricity(point)
    assert 0.0254 * 0.3 < result.values["lift_off_eccentricity"] < 0.0254 * 1.0  # measured 0.558 in
    assert np.isnan(sliding.lift_off_eccentricity({**point, "inclination": 0.0}))
