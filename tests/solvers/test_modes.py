"""Convergence in the modes at contacts (docs/reference_model.md §2.1, §3.1): the residual flexibility of the modes
left out, in series with each contact's Hertz spring, and the modal part of every figure's error measured on the run;
the residual vectors (``reference_residual = "dynamic"``), their second moment, receptance, rest and impact, and their
modal part measured between N/2 and N modes; the same damped by the bending waves' resistance (``"radiating"``): a
joint's response to a blow against the joint's mass on the infinite beam."""

import numpy as np
import pytest
from scipy.special import erfcx

from study.physics import string_modes
from study.solvers.methods import reference
from study.solvers.kernels import whirl_kernel
from study.solvers.model.options import ReferenceOptions
from study.solvers.model.result import PointResult

L, EI = 93 * 0.3048, 8.3e5  # the default section (three 31-ft joints) and about the 4½-in pipe's EI [N m²]


def direct_sum(s, tension, harmonics=2_000_000):
    """The periodic beam-column's static deflection per unit point load, summed term by term: (2/L) Σ_j
    cos(k_j s)/(EI k_j⁴ + T k_j²), k_j = 2πj/L (its Fourier series; the tail past 2e6 harmonics below 1e-19 m/N)."""
    k = 2 * np.pi * np.arange(1, harmonics + 1) / L
    return float(np.sum((2 / L) * np.cos(k * s) / (EI * k**4 + tension * k**2)))


@pytest.mark.parametrize("tension", [0.0, 10.0, 5e3, 1.3e5, -2e3])
@pytest.mark.parametrize("s", [0.0, 3.1, 14.0])
def test_the_periodic_point_deflection_in_closed_form_is_its_fourier_series(s, tension):
    # Gradshteyn & Ryzhik 1.445.2 (the hyperbolic form), 1.443.3/1.443.6 (tensionless: Bernoulli polynomials) against
    # the series itself; near T = 0 the closed form's difference cancels to about 1e-9 relative (measured 6e-10)
    closed = float(string_modes.periodic_point_deflection(s, L, EI, tension))
    assert closed == pytest.approx(direct_sum(s, tension), rel=2e-9)


def test_the_tensionless_point_deflection_is_the_beams_l3_over_720_ei():
    # (2/(L EI)) (L/2π)⁴ ζ(4) = L³/(720 EI) under the load (ζ(4) = π⁴/90)
    assert float(string_modes.periodic_point_deflection(0.0, L, EI, 0.0)) == pytest.approx(L**3 / (720 * EI), rel=1e-14)


@pytest.fixture(scope="module")
def model(paper_inputs):
    return reference.build_model({**paper_inputs, "inclination": np.radians(8), "reference_modes": 16})


def test_the_residual_flexibility_is_the_left_out_modes_sum(model):
    # f_p = Σ_{n≥N} ψ_n(x_p)²/(m ω_n²) summed over the modes left out directly (the basis's harmonics 9 … 200 000 and
    # the sine of harmonic 8, whose cosine the 16 modes keep), against the closed form less the kept terms
    p = model.props
    big = 400_001
    k = string_modes.mode_wavenumbers(model.span, big)[16:]
    shapes = string_modes.mode_shapes(model.points, model.span, np.arange(16, big))
    omega2 = (p["bending_stiffness"] * k**4 + p["effective_tension"] * k**2) / p["mass_per_length"]
    direct = (shapes**2) @ (1.0 / (model.mass * omega2))
    np.testing.assert_allclose(model.residual, direct, rtol=1e-9)
    assert np.all(model.residual > 0)


def test_the_residual_flexibility_vanishes_as_the_modes_grow(paper_inputs):
    # its terms fall like j⁻⁴, so the sum above N like N⁻³: 8x less for twice the modes, within the tension's share
    flex = [reference.build_model({**paper_inputs, "reference_modes": n}).residual.max() for n in (16, 32, 64, 128)]
    ratios = np.array(flex[:-1]) / np.array(flex[1:])
    assert np.all((ratios > 7.0) & (ratios < 8.5)), ratios
    none = reference.build_model({**paper_inputs, "reference_modes": 16, "reference_residual": "none"})
    assert np.all(none.flexibility == 0.0)


@pytest.mark.parametrize("f", [0.0, 1e-9, 2e-8, 1e-6])
def test_the_series_spring_splits_the_approach_between_hertz_and_the_flexibility(f):
    # δ_H + f F = d with F = K δ_H^{3/2}: the kernel's Newton iteration against its definition; f = 0 is Hertz exactly
    K = 1.2e10
    for d in (1e-7, 1e-5, 3e-4, 2e-3):
        F = whirl_kernel.series_hertz(d, K, f)
        dh = (F / K) ** (2.0 / 3.0)
        assert dh + f * F == pytest.approx(d, rel=1e-12)
        assert F <= K * d**1.5 * (1 + 1e-14) and (f > 0 or F == pytest.approx(K * d**1.5, rel=1e-14))
        approach, force = string_modes.series_contact(np.array([d]), K, f)
        assert force[0] == pytest.approx(F, rel=1e-12) and approach[0] == pytest.approx(dh, rel=1e-9)


def test_a_held_contact_sees_the_continuous_beams_static_flexibility(paper_inputs):
    # a static point force F on the periodic beam at a contact point: the kept modes' static deflection there plus
    # the residual flexibility times F is the continuous beam's G(0) F, whatever N (the series spring's static limit).
    # Without the tool joints' mass: with it the kept modes' static part differs by how the load's mean is carried
    # (the rigid translation's inertia relief, 0.3 % here), which the modes left out (mean-free) do not share
    for n in (4, 16, 64):
        m = reference.build_model({**paper_inputs, "reference_modes": n, "tool_joint_length": 0.0})
        gain = np.zeros(n)
        flexible = m.wavenumber > 0
        gain[flexible] = 1.0 / (m.mass * m.omega[flexible] ** 2)
        kept = (m.phi**2) @ gain
        whole = string_modes.periodic_point_deflection(0.0, m.span, m.props["bending_stiffness"],
                                                     m.props["effective_tension"])
        np.testing.assert_allclose(kept + m.residual, whole, rtol=1e-12)
        # and the deflection the quasi-static correction adds at the point itself is that flexibility's
        correction = reference.static_correction(m, m.points)[:, :m.points.size]
        np.testing.assert_allclose(np.diag(correction), m.residual, rtol=1e-9)


@pytest.mark.parametrize("n", [4, 16])
def test_a_held_contact_is_at_rest_where_the_continuous_beam_rests(paper_inputs, n):
    # one frictionless contact (the joint at 0) holding up the string under its side load w: the continuous beam
    # rests on it with F = w L, the Hertz approach δ_H = (F/K)^(2/3) and the bending G(x − x_p) F
    # (periodic_point_deflection). Its kept modes' static part, ψ_n(x_p) F/(m ω_n²), with the rigid translation placing
    # the point at c + δ_H + f F (the Hertz approach plus the residual flexibility's), is at rest in the kernel's
    # equations (every acceleration zero) whatever n; with the kept modes' plain Hertz law it is not. With the residual
    # vectors ("dynamic") the same state, their coordinates at the contact's force (WhirlModel.extend), is at rest too
    for residual, at_rest in (("series", True), ("none", False), ("dynamic", True)):
        m = reference.build_model({**paper_inputs, "inclination": np.radians(8), "reference_modes": n, "tool_joint_length": 0.0,
                                   "contact_points": [0.0], "contact_kinds": [1], "friction": 0.0, "eccentricity": 0.0,
                                   "reference_damping": "none", "reference_residual": residual})
        w = m.side[0] * m.mass / m.phi[0, 0] / m.span  # the side load per length [N/m] from its modal force
        F = w * m.span
        f = float(reference.residual_flexibility(m)[0])
        gain = np.zeros(n)
        gain[1:] = 1.0 / (m.mass * m.omega[1:] ** 2)
        z = np.zeros(4 * n + 4)
        z[1:n] = -m.phi[0, 1:] * F * gain[1:]  # the force on the pipe pushes it off the low side (−y)
        total = m.clearance[0] + (F / m.stiffness[0]) ** (2.0 / 3.0) + f * F
        z[0] = (total - m.phi[0, 1:] @ z[1:n]) / m.phi[0, 0]
        sy = whirl_kernel.kernel_system(m.system())
        kernel = m.extend(z)
        out, fc, pen = np.zeros(kernel.size), np.zeros((1, 3)), np.zeros((1, 2))
        scratch = whirl_kernel.drag_scratch(m.kernel_modes, m.drag_weights.size)
        whirl_kernel.rhs(0.0, kernel, np.zeros(1), out, fc, pen, scratch, sy)
        k = m.kernel_modes
        accel = np.max(np.abs(out[2 * k:4 * k])) / (m.side[0])
        assert bool(accel < 1e-9) is at_rest, (residual, accel, fc[0, 2] / F)
        if at_rest:
            # and the field along the section (modes plus the correction) is the continuous beam's
            x = np.linspace(0.0, m.span, 13)
            field = reference.periodic_fields(m, z[None, :n], fc[None, :, 0], x)["deflection"][0]
            # the contact at c + δ_H, the string sagging towards the low side away from it by (G(0) − G(s)) F
            ei, tn = m.props["bending_stiffness"], m.props["effective_tension"]
            sag = (string_modes.periodic_point_deflection(0.0, m.span, ei, tn)
                   - string_modes.periodic_point_deflection(x, m.span, ei, tn)) * F
            np.testing.assert_allclose(field, total - f * F + sag, rtol=1e-9)


@pytest.mark.parametrize("n", [4, 16])
def test_a_held_contacts_fields_are_the_continuous_beams_under_either_recovery(paper_inputs, n):
    # the rest of the test above with the residual vectors: their coordinates at the contact's force (s_p = F where
    # the contact is held, WhirlModel.extend), so the fields recovered from the contact force (the mode-acceleration
    # method, reference_recovery = "force") and from the vectors' coordinates ("vectors") are one field, the continuous
    # beam's: G(0) F at the contact less the sag (G(0) − G(s)) F, and its moment the periodic point load's
    # (periodic_point_moment, Gradshteyn & Ryzhik 1.445.2), whatever n; the series law's the same
    fields = {}
    for residual, recovery in (("series", "force"), ("dynamic", "force"), ("dynamic", "vectors")):
        m = reference.build_model({**paper_inputs, "inclination": np.radians(8), "reference_modes": n,
                                   "tool_joint_length": 0.0, "contact_points": [0.0], "contact_kinds": [1],
                                   "friction": 0.0, "eccentricity": 0.0, "reference_damping": "none",
                                   "reference_residual": residual, "reference_recovery": recovery})
        assert m.dynamic is (residual == "dynamic") and (not m.dynamic or m.recovery == recovery)
        F = m.side[0] * m.mass / m.phi[0, 0]
        f = float(reference.residual_flexibility(m)[0])
        gain = np.zeros(n)
        gain[1:] = 1.0 / (m.mass * m.omega[1:] ** 2)
        z = np.zeros(4 * n + 4)
        z[1:n] = -m.phi[0, 1:] * F * gain[1:]
        total = m.clearance[0] + (F / m.stiffness[0]) ** (2.0 / 3.0) + f * F
        z[0] = (total - m.phi[0, 1:] @ z[1:n]) / m.phi[0, 0]
        kernel = m.extend(z)
        forces = np.array([[[-F, 0.0, F]]])  # on the pipe, off the low side (−y)
        window = reference.Window(times=np.zeros(1), states=m.reduce(kernel)[None], forces=forces,
                                  peak=np.array([F]), onsets=np.zeros(1, int), contact_time=np.ones(1),
                                  any_contact_time=1.0, start=0.0, end=0.0,
                                  residual=m.residual_coordinates(kernel[None]) if m.dynamic else None)
        if m.dynamic:
            np.testing.assert_allclose(window.residual[0, 0], -F, rtol=1e-9)  # s_p = F (on the pipe) where held
        x = np.linspace(0.0, m.span, 13)
        fields[residual, recovery] = reference.periodic_fields(m, window.states[:, :n], window.correction_forces(m, 0),
                                                               x)
        ei, tn = m.props["bending_stiffness"], m.props["effective_tension"]
        sag = (string_modes.periodic_point_deflection(0.0, m.span, ei, tn)
               - string_modes.periodic_point_deflection(x, m.span, ei, tn)) * F
        np.testing.assert_allclose(fields[residual, recovery]["deflection"][0], total - f * F + sag, rtol=1e-9)
        np.testing.assert_allclose(fields[residual, recovery]["moment"][0],
                                   -F * string_modes.periodic_point_moment(x, m.span, ei, tn),
                                   rtol=1e-7, atol=1e-9 * F * m.span)



def test_clear_of_the_wall_the_force_recovery_gives_the_series_laws_fields(paper_inputs):
    # no contact force: the fields recovered from the contact forces ("force") take the joints' weight and inertia
    # statically, as the series law's do (reference.stresses, the same kept modes and correction), so the same kept
    # modes' motion gives the same stresses and deflection to rounding; from the vectors' coordinates ("vectors") it is
    # another field (here the vectors at rest: no correction for the joints' weight and inertia)
    inputs = {**paper_inputs, "inclination": np.radians(8), "reference_modes": 8}
    series = reference.build_model(inputs)
    models = {r: reference.build_model({**inputs, "reference_residual": "dynamic", "reference_recovery": r})
              for r in ("force", "vectors")}
    assert series.joint_points is not None and series.point_side is not None and models["force"].dynamic
    rng = np.random.default_rng(36)
    N, P, R = series.n_modes, series.points.size, 24
    times = np.linspace(0.0, series.period, R)
    states = np.zeros((R, 4 * N + 4))
    states[:, :4 * N] = rng.normal(size=(R, 4 * N)) * series.state_scale() * 0.1
    window = reference.Window(times=times, states=states, forces=np.zeros((R, P, 3)), peak=np.zeros(P),
                              onsets=np.zeros(P, int), contact_time=np.zeros(P), any_contact_time=0.0, start=0.0,
                              end=float(times[-1]), residual=np.zeros((R, 4, P)))
    want = reference.stresses(inputs, series, window)
    names = ("max_normal_stress", "alternating_bending_stress", "max_deflection", "max_shear_stress")
    got = {r: reference.stresses(inputs, m, window) for r, m in models.items()}
    for name in names:
        assert got["force"][name] == pytest.approx(want[name], rel=1e-12), name
    assert max(abs(got["vectors"][name] / want[name] - 1.0) for name in names) > 1e-3


@pytest.fixture(scope="module")
def bouncing(default_point):
    # configs/default.toml at 250 rpm, 5 000 lbf, e = 0.7, 9 ppg, no flow: the joints bounce chaotically, contacts of
    # 1-15 ms, shorter than the period of the first mode left out (ω_{N+1} T_c/2π = 0.4-1 at 16-64 modes)
    # (the modes' own force, reference_strike_force "modes": the series law's correction measured at N and 2N)
    point = {**default_point(250, 5, 0.7, 9, 0.0), "reference_strike_force": "modes"}
    return {n: reference.solve({**point, "reference_modes": n, "reference_max_modes": n}) for n in (16, 32)}


def test_at_impacts_n_and_2n_modes_agree_within_the_stated_error(bouncing):
    # every figure of 16 modes lies within the stated errors of it and of 32 modes' (a chaotic motion's figures are
    # means over 6-revolution windows, each with its statistical part beside the modal one; measured: peak force 7.0
    # against 18.2 kN, stated 128 times itself, the correction's size at impacts; alternating stress 40 % apart
    # against 33 % + 21 % stated, its modal parts 28 % and 14 %)
    # (the design figures of the modes' measurement: the force and the stresses. The rainflow damage rate is not held
    # here: on a generic-CPU compilation its 16- and 32-mode windows differed 7.1x against 2.1 stated, the window of 6
    # revolutions too short for a heavy-tailed damage: docs/reference_model.md §3.1, an open gap)
    coarse, fine = bouncing[16], bouncing[32]
    assert coarse.extras["whirl"] == fine.extras["whirl"] == "bouncing"
    for name in reference.FIGURES:
        parts = coarse.extras["convergence"][name]
        off = abs(fine.values[name] / coarse.values[name] - 1.0)
        assert off <= parts["total"] + fine.extras["convergence"][name]["total"], (name, off, parts)
    assert coarse.extras["convergence"]["peak_contact_force"]["modes"] > 1.0  # the force: over 100 %, from below
    for name in reference.MODAL_FIGURES:
        assert name in coarse.extras["modal_error"]
    # the correction's size, the modal part, falls as the modes grow: the force's with the residual flexibility
    # (like N⁻³; 128 to 14.7 measured), the stresses' with the static moment of the modes left out at a point load
    # (like 1/N beside the force's growth; 32 % to 28 %)
    coarse_parts, fine_parts = coarse.extras["convergence"], fine.extras["convergence"]
    assert fine_parts["peak_contact_force"]["modes"] < 0.5 * coarse_parts["peak_contact_force"]["modes"]
    assert fine_parts["max_normal_stress"]["modes"] < coarse_parts["max_normal_stress"]["modes"]


def test_the_mode_count_doubles_at_impacts_and_says_so(default_point):
    # the same point with the default counts: 16 modes state a modal part far over half the 1 % tolerance, so the
    # count grows to reference_max_modes (here 32, to keep the test short); a point clear of the wall keeps 16
    point = default_point(250, 5, 0.7, 9, 0.0)
    result = reference.solve({**point, "reference_max_modes": 32})
    tried = result.extras["modes_tried"]
    assert [t["modes"] for t in tried] == [16, 32] and result.extras["reference_modes"] == 32
    assert "modes doubled from 16 to 32" in result.message
    # the 32-mode run went on from where the 16-mode one ended (reference.continued_state), and says so
    assert result.extras["continued_from_modes"] == 16
    assert "started where the 16-mode run ended" in result.message
    assert result.final_state is None  # the model is not handed out with the answer
    clear = reference.solve({**point, "rotary_speed": 10.0, "inclination": 0.0, "reference_window": 2,
                             "reference_revolutions": 4})
    assert [t["modes"] for t in clear.extras["modes_tried"]] == [16]


def test_a_run_goes_on_from_a_revolution_boundary_with_its_contacts_open_as_they_were(default_point):
    # configs/default.toml at 250 rpm, 5 000 lbf, e = 0.7, 9 ppg (the joints bounce): a 16-mode run stopped at the first
    # revolution boundary after the start-up where a contact is open, and continued at the same count from its end
    # (reference.continued_state, reference.start_integrator, as the run at more modes starts), strikes as the
    # uninterrupted run does over the next 5 % of a revolution: the same peak force at every contact point, to the
    # phase's rounding (measured 1e-11). Started from the same state with the contacts' state of a fresh start the
    # open contact is not seen (measured: no force at all where the uninterrupted run's peak is 6.9 kN)
    point = {**default_point(250, 5, 0.7, 9, 0.0), "reference_modes": 16}
    model = reference.build_model(point)
    option = ReferenceOptions.from_inputs(point)
    run = reference.start_integrator(model, option)
    for k in range(1, 41):
        run.run(k * model.period)
        if k > 6 and run.active.any():
            break
    assert run.active.any(), "no contact open at a revolution boundary within 40 revolutions"
    before = PointResult(method="reference")
    before.final_state = reference.end_state(run, None)
    start = reference.continued_state(before, model)
    assert start["modes"] == 16 and np.array_equal(start["active"], run.active)
    assert np.all(start["state"][-4:] == 0.0)  # the power integrals from nil
    span = 0.05 * model.period
    uninterrupted = run.run(run.t + span)
    continued = reference.start_integrator(model, option, start).run(span)
    assert continued.peak == pytest.approx(uninterrupted.peak, rel=1e-6, abs=1e-6)
    fresh = reference.Integrator(model, 1e-6, start["state"]).run(span)
    opened = start["active"]
    assert np.max(np.abs(fresh.peak[opened] / uninterrupted.peak[opened] - 1.0)) > 0.01
    # with other contact points (the body's stations raised) the contacts start afresh: only the state is carried
    other = reference.build_model({**point, "reference_modes": 32, "reference_body_stations": 3})
    lifted = reference.continued_state(before, other)
    assert lifted["active"] is None and lifted["state"].size == 4 * 32 + 4
    assert reference.continued_state(PointResult(method="reference"), model) is None


# --- the residual oscillator (reference_residual = "dynamic", docs/reference_model.md §2.1) ---------------------------


def test_the_second_moment_of_all_the_flexible_modes_is_its_tensionless_closed_form(paper_inputs):
    # without tension Σ_j (ψ_c² + ψ_s²)/(m ω_j⁴) = m (2/(L EI))² Σ_j k_j⁻⁸ = m (2/(L EI))² (L/2π)⁸ ζ(8), ζ(8) = π⁸/9450
    # (Abramowitz & Stegun 23.2.16); one mode kept (the rigid translation), every flexible one left out
    m = reference.build_model({**paper_inputs, "reference_modes": 1})
    m.props = {**m.props, "effective_tension": 0.0}
    ei = m.props["bending_stiffness"]
    closed = m.mass * (2 / (m.span * ei)) ** 2 * (m.span / (2 * np.pi)) ** 8 * np.pi**8 / 9450
    np.testing.assert_allclose(reference.residual_second_moment(m), closed, rtol=1e-12)


@pytest.mark.parametrize("n", [16, 64])
def test_the_residual_oscillator_has_the_left_out_modes_receptance_at_low_frequency(paper_inputs, n):
    # the modes left out respond at a contact point p to a force at ω as Σ_{n≥N} ψ_n(x_p)²/(m (ω_n² − ω²)) (their modal
    # sum, here 400 000 basis functions summed directly) = f + g ω² + O(ω⁴) (Rubin, AIAA J. 13, 995-1006, 1975: residual
    # flexibility and residual mass); the oscillator's 1/(k − μ ω²), k = 1/f, μ = g/f², matches it to O(ω⁴), where the
    # static series flexibility f alone errs by g ω²/f
    m = reference.build_model({**paper_inputs, "inclination": np.radians(8), "reference_modes": n,
                               "reference_residual": "dynamic", "tool_joint_length": 0.0})
    assert m.dynamic and np.all(m.residual_mass > 0)
    p = m.props
    big = 400_001
    k = string_modes.mode_wavenumbers(m.span, big)[n:]
    shapes = string_modes.mode_shapes(m.points, m.span, np.arange(n, big)) ** 2
    omega2 = (p["bending_stiffness"] * k**4 + p["effective_tension"] * k**2) / p["mass_per_length"]
    np.testing.assert_allclose(reference.residual_second_moment(m), shapes @ (1.0 / (m.mass * omega2**2)), rtol=1e-9)
    for share in (0.1, 0.3):
        w2 = (share * m.first_left_out()) ** 2
        modal = shapes @ (1.0 / (m.mass * (omega2 - w2)))
        oscillator = 1.0 / (1.0 / m.residual - m.residual_mass * w2)
        static = m.residual
        off, static_off = np.abs(oscillator / modal - 1), np.abs(static / modal - 1)
        # the oscillator's error is of the fourth order: (0.3)⁴ of the static one's second-order share, about
        assert np.all(off < 0.02 * share**2) and np.all(off < 0.1 * static_off), (share, off, static_off)
    # its frequency √(k/μ) lies just above the first mode left out (the step the integrator takes in contact)
    ratio = np.sqrt(m.residual_omega2) / m.first_left_out()
    assert np.all((ratio > 1.0) & (ratio < 2.0)), ratio


@pytest.mark.parametrize("n", [16, 64])
def test_k_residual_vectors_match_the_left_out_modes_receptance_to_the_order_of_omega_4k(paper_inputs, n):
    # the modes left out respond at a contact point p as Σ_{n≥N} ψ_n(x_p)²/(m (ω_n² − ω²)) (their modal sum, here
    # 400 000 basis functions summed directly); K vectors a point (the left-out modes' Krylov sequence, Wilson, Yuan &
    # Dickens 1982, reference.residual_ritz) match its first 2K moments, so the Ritz modes' receptance less the kept
    # modes' own errs like (ω/ω_N)^{4K}: measured at 0.3 and 0.6 of the first mode left out 6.5e-4, 1.6e-2 (K = 1),
    # 2.1e-7, 1.1e-4 (K = 2), 7e-12, 6.6e-8 (K = 3) at 16 modes; 7.9e-4, 1.7e-2; 3.5e-7, 1.7e-4; 1.4e-10, 1.6e-6 at 64
    # (the sum's own floor some 4e-11). No joints' mass: the kept modes the basis functions, the vectors' span theirs
    inputs = {**paper_inputs, "inclination": np.radians(8), "reference_modes": n, "reference_residual": "dynamic",
              "tool_joint_length": 0.0}
    models = {K: reference.build_model({**inputs, "reference_residual_vectors": K}) for K in (1, 2, 3)}
    m = models[1]
    p = m.props
    big = 400_001
    k = string_modes.mode_wavenumbers(m.span, big)[n:]
    shapes = string_modes.mode_shapes(m.points, m.span, np.arange(n, big)) ** 2
    omega2 = (p["bending_stiffness"] * k**4 + p["effective_tension"] * k**2) / p["mass_per_length"]
    off = {}
    for share in (0.3, 0.6):
        w2 = (share * m.first_left_out()) ** 2
        modal = shapes @ (1.0 / (m.mass * (omega2 - w2)))
        for K, model in models.items():
            assert model.kernel_modes == n + K * m.points.size
            whole = model.ritz["phi"] ** 2 @ (1.0 / (model.mass * (model.ritz["omega2"] - w2)))
            kept = model.phi**2 @ (1.0 / (model.mass * (model.omega**2 - w2)))
            off[K, share] = float(np.max(np.abs((whole - kept) / modal - 1)))
            assert off[K, share] < 0.2 * share ** (4 * K), (K, share, off)
    for K in (1, 2, 3):
        # doubling ω multiplies the error by about 2^{4K} (at least 2^{4K − 1})
        assert off[K, 0.6] / off[K, 0.3] > 2.0 ** (4 * K - 1), off
    # each vector a point's order adds its frequencies above: the top of the Ritz spectrum (the step in contact)
    tops = [float(np.max(models[K].ritz["omega2"])) for K in (1, 2, 3)]
    assert tops[0] < tops[1] < tops[2], tops


def test_the_residual_vectors_count_is_validated_naming_the_field(paper_inputs):
    inputs = {**paper_inputs, "inclination": np.radians(8), "reference_modes": 8, "reference_residual": "dynamic"}
    with pytest.raises(ValueError, match="reference_residual_vectors = 0: allowed a whole number of 1 or more"):
        reference.build_model({**inputs, "reference_residual_vectors": 0})
    with pytest.raises(ValueError, match="reference_residual_vectors = 2 with reference_recovery = 'vectors'"):
        reference.build_model({**inputs, "reference_residual_vectors": 2, "reference_recovery": "vectors"})


def _joint_blow_velocity(m, t):
    """The velocity [m/s] at the model's first tool joint at times t [s] after a unit impulse [N s] there: the kernel's
    modes' damped free motion, Σ_k ψ_k²/m e^{−d_k t/2} (cos ω_dk t − d_k/(2ω_dk) sin ω_dk t), ω_dk² = ω_k² − d_k²/4
    (the residual vectors' Ritz modes and their damping where the model has them)."""
    p = int(np.flatnonzero(m.kinds == 1)[0])
    w2, d, shape = (m.ritz["omega2"], m.ritz["damping"], m.ritz["phi"][p]) if m.dynamic else (m.omega**2, m.damping,
                                                                                            m.phi[p])
    wd = np.sqrt(np.maximum(w2 - d**2 / 4, 0.0))[:, None]
    t = np.asarray(t, float)[None, :]
    sine = np.where(wd > 0, np.sin(wd * t) / np.where(wd > 0, wd, 1.0), t)
    return (shape**2 / m.mass) @ (np.exp(-d[:, None] * t / 2) * (np.cos(wd * t) - d[:, None] / 2 * sine))


def test_the_radiating_residual_vectors_give_the_joint_the_infinite_beams_blow_response(default_point):
    # a blow on a tool joint: its mass m_j on the infinite beam (docs/reference_model.md §2.3) answers a unit impulse
    # with X(s) = 1/(m_j s² + 2ρA√(2a) s^{3/2}) (the beam's receptance, study.physics.strike.beam_impulse_response), a
    # velocity v(t) = e^{λ² t} erfc(λ √t)/m_j, λ = 2ρA√(2a)/m_j (the Mittag-Leffler function E_½(−λ√t): Podlubny,
    # Fractional Differential Equations, 1999, §1.2); the string's modes hold it until the waves come back from the
    # next joints (9.45 m: 4 ms and more below 2 kHz). Measured over 0.05-3 ms (the largest relative difference): 256
    # modes 1.4 %; the residual vectors undamped ("dynamic") ring coherently, 17 % and 20 % off at 64 and 128 modes;
    # with the bending waves' resistance as their damping ("radiating") 4.7 % and 2.2 %, converging
    inputs = {**default_point(250, 5, 0.7, 9, 0.0), "reference_damping": "drag"}
    t = np.array([0.05, 0.1, 0.2, 0.3, 0.45, 0.6, 0.8, 1.0, 1.5, 2.0, 3.0]) * 1e-3
    models = {(n, r): reference.build_model({**inputs, "reference_modes": n, "reference_residual": r})
              for n, r in ((256, "none"), (64, "dynamic"), (128, "dynamic"), (64, "radiating"), (128, "radiating"))}
    m = models[256, "none"]
    rho, ei, mj = m.props["mass_per_length"], m.props["bending_stiffness"], m.joint_mass
    lam = 2 * rho * np.sqrt(2 * np.sqrt(ei / rho)) / mj
    beam = erfcx(lam * np.sqrt(t)) / mj
    off = {key: float(np.max(np.abs(_joint_blow_velocity(model, t) / beam - 1))) for key, model in models.items()}
    assert off[256, "none"] < 0.02, off
    assert off[64, "radiating"] < 0.08 and off[128, "radiating"] < 0.05, off
    for n in (64, 128):
        assert off[n, "radiating"] < 0.6 * off[n, "dynamic"], off


def test_the_radiation_damping_is_on_the_residual_vectors_alone(paper_inputs):
    # "radiating" is "dynamic" with damping added, nothing else: the same Ritz modes; each damping the resistance
    # 2 ρA √(ω a) (study.physics.strike.driving_point_resistance) on the vectors' share of the mode at the points, so
    # the kept modes' own part undamped (the modes below the vectors' a few per mille at most) and the vectors' modes
    # underdamped; the default ("series") has no vectors, "dynamic" none of this damping
    inputs = {**paper_inputs, "inclination": np.radians(8), "reference_modes": 16, "reference_damping": "drag"}
    plain = reference.build_model({**inputs, "reference_residual": "dynamic"})
    damped = reference.build_model({**inputs, "reference_residual": "radiating"})
    assert reference.build_model(inputs).ritz is None
    assert np.all(plain.ritz["damping"] == 0.0)
    for key in ("omega2", "phi", "vectors"):
        np.testing.assert_array_equal(damped.ritz[key], plain.ritz[key])
    N, omega = damped.n_modes, np.sqrt(damped.ritz["omega2"])
    own = damped.ritz["phi"] - damped.phi @ damped.ritz["vectors"][:N]  # the vectors' share of each mode at the points
    rho, ei = damped.props["mass_per_length"], damped.props["bending_stiffness"]
    expected = 2 * rho * np.sqrt(omega * np.sqrt(ei / rho)) * np.sum(own**2, axis=0) / damped.mass
    np.testing.assert_allclose(damped.ritz["damping"], expected, rtol=1e-9, atol=1e-12)
    zeta = damped.ritz["damping"] / (2 * np.maximum(omega, 1e-300))
    top = np.argsort(omega)[-damped.points.size:]
    assert np.all(zeta[top] > 0.02) and np.all(zeta[top] < 1.0), zeta[top]
    assert np.all(zeta[np.argsort(omega)[:-damped.points.size]] < 5e-3), zeta


def test_a_radiating_run_says_so_and_its_energy_balance_is_not_the_integrators_error(default_point):
    # the bouncing point of the tests below at 8 modes: the undamped vectors' energy balance closes (§4: the loads'
    # work less the losses is the energy's change), the radiating vectors' loses what their damping takes, which the
    # balance does not count (docs/reference_model.md §2.1), so the figures' integrator part is rtol alone
    point = {**default_point(250, 5, 0.7, 9, 0.0), "reference_modes": 8, "reference_max_modes": 8,
             "reference_max_revolutions": 12, "reference_window": 6}
    plain = reference.solve({**point, "reference_residual": "dynamic"})
    damped = reference.solve({**point, "reference_residual": "radiating"})
    assert plain.extras["reference_residual"] == "dynamic" and damped.extras["reference_residual"] == "radiating"
    assert abs(plain.extras["energy_budget"]["residual"]) < 1e-3
    assert damped.extras["energy_budget"]["residual"] > 0.05  # the radiation's loss, a share of the largest term
    for name in ("peak_contact_force", "max_normal_stress", "alternating_bending_stress"):
        assert damped.extras["convergence"][name]["integrator"] == pytest.approx(1e-6), name  # reference_rtol


def _first_impact(inputs, n, residual, speed=0.3, vectors=1):
    """The largest contact force [N] of the string thrown rigidly at speed [m/s] onto its joints' wall from 10 µm off
    it (a straight vertical hole, no drive, no damping: one impact in 30 ms), with n modes (and ``vectors`` residual
    vectors a contact point with the residual vectors)."""
    m = reference.build_model({**inputs, "reference_modes": n, "reference_residual": residual,
                               "reference_residual_vectors": vectors})
    z = np.zeros(4 * n + 4)
    z[0] = (float(np.min(m.clearance)) - 1e-5) / m.phi[0, 0]
    z[2 * n] = speed / m.phi[0, 0]
    window = reference.Integrator(m, 1e-8, z).run(0.03, record=True)
    return float(np.max(window.peak))


def test_an_impact_converges_in_the_modes_faster_with_the_residual_vectors(default_point):
    # the three joints strike at once at 0.3 m/s (configs/default.toml's pipe, 250 rpm, 5 000 lbf, 9 ppg). Measured:
    # 256 modes 143.2 kN (residual vectors) and 143.5 kN (kept modes alone); with the residual vectors 186, 160, 146 kN at
    # 16, 32 and 64 modes, the kept modes alone 245, 187, 160 kN, the static series law 24, 49, 96 kN: the residual
    # vectors reach at N what the kept modes alone reach at 2N, and the series law, which puts the whole string's mass
    # behind the flexibility of the modes left out, is the slowest
    inputs = {**default_point(250, 5, 0.7, 9, 0.0), "inclination": 0.0, "eccentricity": 0.0,
              "reference_damping": "none"}
    converged = _first_impact(inputs, 256, "none")
    off = {(n, r): _first_impact(inputs, n, r) / converged - 1.0
           for n in (16, 32, 64) for r in ("dynamic", "none", "series")}
    for n in (16, 32, 64):
        assert abs(off[n, "dynamic"]) < abs(off[n, "none"]) < abs(off[n, "series"]), (n, off)
    assert abs(off[32, "dynamic"]) < 0.15 and abs(off[64, "dynamic"]) < 0.05, off
    assert abs(off[64, "series"]) > 0.25, off


def test_a_thrown_string_converges_faster_with_more_residual_vectors_a_point(default_point):
    # the string thrown onto its three joints at 0.3 m/s as above (256 modes 143.2 kN). Measured with K = 1, 2, 3, 4
    # vectors a point (reference_residual_vectors): 186.1, 164.4, 153.4, 147.4 kN at 16 modes; 159.8, 150.5, 145.6,
    # 143.1 at 32; 146.1, 142.9, 142.3, 142.9 at 64: each order nearer at 16 and 32 modes, 64 within 1 % from K = 2
    inputs = {**default_point(250, 5, 0.7, 9, 0.0), "inclination": 0.0, "eccentricity": 0.0,
              "reference_damping": "none"}
    converged = _first_impact(inputs, 256, "none")
    off = {(n, K): _first_impact(inputs, n, "dynamic", vectors=K) / converged - 1.0
           for n in (16, 32, 64) for K in (1, 2, 3, 4)}
    for n in (16, 32):
        for K in (2, 3, 4):
            assert abs(off[n, K]) < abs(off[n, K - 1]), (n, K, off)
    assert abs(off[16, 4]) < 0.05 and abs(off[32, 4]) < 0.02, off
    assert all(abs(off[64, K]) < 0.015 for K in (2, 3, 4)), off


def test_with_the_residual_vectors_the_stated_error_covers_four_times_the_modes(default_point):
    # the bouncing point of the tests above (250 rpm, 5 000 lbf, e = 0.7, 9 ppg) with the residual vectors, 8 then 16
    # modes (its modal part the figures' change between them, reference.doubling_modal_error), against 64 modes: each
    # figure a chaotic window's mean, so the 64-mode answer's own window part is allowed beside the 16-mode answer's
    # whole stated error. Measured (60-revolution budget): force 70.6 against 52.5 kN (26 %, stated 31 %), max normal
    # stress 40.5 against 45.9 MPa (13 %, stated 26 %), alternating 26.8 against 32.0 MPa (19 %, stated 32 %)
    # Each run is one chaotic realisation and the stated error a bound at about 95 % (issue 36 asks it to cover
    # the true difference at 90 % of points), so one figure of the four may fall outside: on the merged model
    # (the joints' eccentricity parts, the contact law's own function) the max normal stress came out 39.8 against
    # 48.4 MPa (22 %) with 19 % stated and the 64-mode window's 3 % beside it, over 24-revolution windows.
    # (the fields recovered from the vectors' coordinates, the reading these figures were measured in)
    point = {**default_point(250, 5, 0.7, 9, 0.0), "reference_residual": "dynamic", "reference_max_revolutions": 60,
             "reference_window": 24, "reference_recovery": "vectors"}
    coarse = reference.solve({**point, "reference_modes": 8, "reference_max_modes": 16})
    fine = reference.solve({**point, "reference_modes": 64, "reference_max_modes": 64})
    assert [t["modes"] for t in coarse.extras["modes_tried"]] == [8, 16]
    assert coarse.extras["reference_residual"] == fine.extras["reference_residual"] == "dynamic"
    assert coarse.extras["whirl"] == fine.extras["whirl"] == "bouncing"
    # A figure outside is still not grossly off: within 3 times its stated error (the held-back check of
    # docs/validation.md found the alternating stress up to 2.04 times its stated error; a generic-CPU compilation's
    # realisation of this point had it 33 % off against 13.6 % stated, 2.4 times)
    covered = {}
    (half, full) = coarse.extras["modes_tried"]
    for name in reference.FIGURES:
        stated = coarse.extras["convergence"][name]
        if name != "alternating_bending_stress":  # (its parts are relative to the max bending stress, not kept there)
            # measured between 8 and 16 modes, not the in-run bound: their whole change (reference.doubling_modal_error,
            # docs/reference_model.md §3.1), from the figures kept per count
            change = abs(full[name] - half[name]) / full[name]
            assert stated["modes"] == pytest.approx(change, rel=1e-9, abs=1e-12), name
        assert stated["modes"] > 0.0
        off = abs(fine.values[name] / coarse.values[name] - 1.0)
        covered[name] = off <= stated["total"] + fine.extras["convergence"][name]["window"]
        assert off <= 3.0 * stated["total"] + fine.extras["convergence"][name]["window"], (name, off, stated)
    # Covered: 3-4 of the 4 on this machine's compilation; 2 of 4 on a generic-CPU compilation (the max normal and
    # the alternating stress outside, within the 3x above): one realisation of a chaotic window at each count, so at
    # least half, not the 90 % the held-back sample of docs/validation.md measures over 20 points
    assert sum(covered.values()) >= len(covered) // 2, covered
