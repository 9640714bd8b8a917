"""Tests of the reference model (study.solvers.methods.reference): checked against closed forms no one here wrote."""

from pathlib import Path

import numpy as np
import pytest
from scipy import stats

from study.physics import string_modes
from study.benchmarks import reference as reference_bench
from study.solvers import METHODS, solve_point
from study.solvers.methods import reference
from study.solvers.model.options import ReferenceOptions, Tolerances
from study.solvers.model.scene import Scene


@pytest.fixture(scope="module")
def base(paper_inputs):
    return dict(paper_inputs)


def test_nothing_moves_without_a_drive(base):
    # issue 20: zero eccentricity, a vertical hole and a centred pipe -> nothing moves
    inputs = {**base, "eccentricity": 0.0, "inclination": 0.0, "reference_modes": 6, "reference_revolutions": 3}
    run = reference.simulate(inputs)
    assert run["verdict"] == "periodic"
    assert np.all(run["integrator"].z == 0.0)
    assert np.all(run["window"].states == 0.0)
    result = solve_point(inputs, "reference")
    assert result.status == "ok" and result.values["regime"] == 0  # clear of the wall is an answer: no contact
    assert result.values["max_deflection"] == 0.0 and result.values["peak_contact_force"] == 0.0


def test_contact_layout_of_three_joints():
    # 93-ft periodic section of 31-ft joints: joints at 0, 31 and 62 ft (93 ft is the joint at 0 again), the body
    # halfway between them
    x, kinds = string_modes.contact_layout(93 * 0.3048, 31 * 0.3048)
    assert np.allclose(x / 0.3048, [0, 15.5, 31, 46.5, 62, 77.5])
    assert list(kinds) == [1, 0, 1, 0, 1, 0]


def test_a_section_of_no_whole_number_of_joints_is_refused_naming_both_fields(base):
    with pytest.raises(ValueError, match="contact.section_length .* pipe.joint_length"):
        string_modes.contact_layout(100 * 0.3048, 31 * 0.3048)


@pytest.mark.parametrize("field, value", [("tool_joint_diameter", 9.0 * 0.0254), ("tool_joint_diameter", 4.0 * 0.0254)])
def test_bad_tool_joint_is_refused_naming_the_field(base, field, value):
    with pytest.raises(ValueError, match="pipe.tool_joint_diameter"):
        reference.build_model({**base, field: value})


def test_registered_as_a_method():
    assert "reference" in METHODS


def test_every_value_is_a_registered_output(base):
    from study.solvers.model.result import OUTPUTS

    result = solve_point({**base, "inclination": np.pi / 6, "reference_modes": 4, "reference_revolutions": 4,
                          "reference_window": 2}, "reference")
    assert result.status in ("ok", "not_converged"), result.message  # two revolutions of a window: not converged
    assert set(result.values) <= set(OUTPUTS)


# --- no contact: the Jeffcott rotor ----------------------------------------------------------------------


def _wide(base, **extra):
    """One point whose walls are out of reach (a 20-in hole), with linear modal damping, without the tool joints' mass
    (against which the body's unbalance would bend the string: test_the_joints_mass_whirls_with_the_string)."""
    return {**base, "hole_diameter": 20 * 0.0254, "reference_damping": "viscous", "damping_ratio": 0.1,
            "reference_revolutions": 80, "reference_tolerance": 1e-7, "tool_joint_length": 0.0, **extra}


@pytest.mark.parametrize("modes", [1, 8])
def test_clear_of_the_wall_the_string_whirls_as_a_rigid_jeffcott_rotor(base, modes):
    # Vance 1988 eq. 2.11-2.12: the synchronous response to the turning unbalance m_p ε Ω² of a mass M per length on
    # a support of natural frequency ω is (m_p/M) ε r²/|1 − r²| behind by π (r = Ω/ω → ∞ here): a uniform eccentricity
    # drives the string's rigid translation alone (ω_0 = 0), a circle of radius (m_p/M) ε opposite the unbalance at
    # every section; nothing bends, so the whirl is forward synchronous with no bending stress
    inputs = {**_wide(base, reference_modes=modes), "rotary_speed": 10.0}
    run = reference.simulate(inputs)
    model, window = run["model"], run["window"]
    relative = (window.states[:, 0] + 1j * window.states[:, modes]) * model.phi[0, 0] * \
        np.exp(-1j * model.rotary_speed * window.times)
    radius = model.props["pipe_mass"] / model.props["mass_per_length"] * model.eccentricity
    np.testing.assert_allclose(np.abs(relative), radius, rtol=1e-6)
    np.testing.assert_allclose(np.angle(-relative), 0.0, atol=1e-6)
    assert np.all(window.states[:, 1:modes] == 0.0) and np.all(window.states[:, modes + 1:2 * modes] == 0.0)
    result = solve_point(inputs, "reference")
    assert result.status == "ok" and result.extras["whirl"] == "no_contact"
    assert result.values["whirl_frequency_ratio"] == pytest.approx(1.0, abs=1e-6)
    assert result.values["max_bending_stress"] == 0.0 and result.values["alternating_bending_stress"] == 0.0


@pytest.mark.parametrize("factor, touches", [(0.99, False), (1.01, True)])
def test_in_a_vertical_hole_the_joints_touch_where_the_rigid_whirl_reaches_them(base, factor, touches):
    # the rigid whirl's radius (m_p/M) ε (above) against the tool joints' clearance R − r_tj, at any speed (without
    # drag, which lags the whirl and sets it to a smaller circle after a transient from the start's)
    base = {**base, "tool_joint_length": 0.0}  # the rigid whirl of the string without the joints' mass
    model = reference.build_model(base)
    joint = float(np.min(model.clearance))
    eccentricity = factor * joint * model.props["mass_per_length"] / model.props["pipe_mass"]
    # (4 modes, not doubled: the rigid whirl is the first mode's, and the touching run's doubling towards
    # reference_max_modes' default of 64 took 15x the time without changing whether it touches)
    result = solve_point({**base, "eccentricity": eccentricity, "reference_modes": 4, "reference_max_modes": 4,
                          "reference_revolutions": 6, "reference_window": 2, "reference_damping": "none"},
                         "reference")  # no drag: no lag
    assert (result.values["contact_fraction"] > 0) is touches, result.message
    if not touches:
        assert result.values["max_deflection"] == pytest.approx(factor * joint, rel=1e-6)


# --- contact ----------------------------------------------------------------------------------------------


def _rolling(base, kind, **extra):
    """A section dropped from rest onto the low side of a 30-degree hole, touching at midspan only, high friction.

    Dropped: the impact sets it whirling. Laid on the wall at rest (the default start) it stays there, sliding
    (test_laid_on_the_wall_it_slides): both motions exist, as dry whip needs a trigger. The kinematics of rolling on
    the kept modes' contact: three modes, without the residual flexibility of the modes left out (with three modes
    most of the beam's, docs/reference_model.md §2.1), which softens the contact into bouncing."""
    return {**base, "contact_points": [0.5], "contact_kinds": [kind], "friction": 1.0, "inclination": np.pi / 6,
            "reference_modes": 3, "reference_revolutions": 20, "reference_window": 4, "reference_initial": "rest",
            "reference_max_modes": 3, "reference_residual": "none", **extra}


@pytest.mark.parametrize("kind, expected", [(0, -2.25 / 2.125), (1, -3.125 / 1.25)],
                         ids=["body -1.06", "tool joint -2.5"])
def test_high_friction_reaches_backward_rolling_whirl(base, kind, expected):
    # issue 20 / Jansen 1991: rolling without slip on the wall whirls backwards at -(r_contact/c) Omega
    result = solve_point(_rolling(base, kind), "reference")
    assert result.extras["whirl"] == "backward"
    assert result.values["contact_fraction"] == pytest.approx(1.0)
    assert result.values["whirl_frequency_ratio"] == pytest.approx(expected, rel=3e-3)


def test_laid_on_the_wall_it_slides(base):
    result = solve_point(_rolling(base, 0, reference_initial="forced"), "reference")
    assert result.extras["whirl"] == "sliding"
    assert abs(result.values["whirl_frequency_ratio"]) < reference.SLIDING_RATE
    assert result.values["contact_fraction"] == pytest.approx(1.0)


def test_slip_velocity_does_not_change_the_answers(base):
    # the regularisation velocity 0.01 m/s against ten times less: whirl within 0.2 %, force and stress within 1 %
    coarse = solve_point(_rolling(base, 0), "reference").values
    fine = solve_point(_rolling(base, 0, slip_velocity=reference.SLIP_VELOCITY / 10), "reference").values
    assert coarse["whirl_frequency_ratio"] == pytest.approx(fine["whirl_frequency_ratio"], rel=2e-3)
    for name in ("peak_contact_force", "max_bending_stress", "alternating_bending_stress"):
        assert coarse[name] == pytest.approx(fine[name], rel=1e-2), name


@pytest.mark.parametrize("case", [
    dict(reference_modes=6, rotary_speed=2 * np.pi, eccentricity=0.0254),  # forward whirl with impacts, 60 rpm
    dict(contact_points=[0.5], contact_kinds=[0], friction=1.0, inclination=np.pi / 6, reference_modes=3,
         reference_initial="rest"),  # backward whirl
], ids=["impacts", "backward whirl"])
def test_energy_balance_over_the_window(base, case):
    # work of the eccentric (and side) load and of friction = drag + contact losses + change of energy
    inputs = {**base, **case, "reference_revolutions": 10, "reference_window": 2}
    loose = solve_point({**inputs, "reference_rtol": 1e-6}, "reference").extras["energy_budget"]
    tight = solve_point({**inputs, "reference_rtol": 1e-8}, "reference").extras["energy_budget"]
    assert abs(loose["residual"]) < 1e-3
    assert abs(tight["residual"]) < 1e-5
    assert tight["drag_loss"] > 0 and tight["contact_loss"] > -1e-3 * abs(tight["drag_loss"])


def test_compiled_integrator_solves_the_penalty_equations_as_solve_ivp(base):
    # the same equations (linear penalty contact) by the compiled Dormand-Prince and by scipy's DOP853
    inputs = {**base, "reference_modes": 3, "rotary_speed": 2 * np.pi, "eccentricity": 0.0254}
    model = reference.build_model({**inputs, "contact_law": "penalty"})
    scipy_run = reference_bench.whirl_penalty_reference(inputs, 1.0, rtol=1e-10, method="DOP853")
    ours = reference_bench.compiled_run({**inputs, "contact_law": "penalty"}, 1.0, rtol=1e-10)
    scale = model.state_scale()
    n = 4 * model.n_modes
    assert np.max(np.abs(ours["final_state"][:n] - scipy_run["final_state"][:n]) / scale) < 1e-6
    assert np.max(np.abs(scipy_run["final_state"][:n]) / scale) > 0.1  # it moved


def test_a_buckled_section_is_flagged_not_run(base):
    # Euler: the periodic section's first bending mode, k = 2π/L, has ω² ≤ 0 when T_eff <= -EI (2π/L)², the pinned
    # Euler load of half its length
    from study.physics import section

    model = reference.build_model(base)
    euler = float(section.euler_buckling_tension(model.span / 2, model.props["bending_stiffness"]))
    mud_flow = base["axial_tension"] - model.props["effective_tension"]  # T0 - T_eff
    below = solve_point({**base, "axial_tension": mud_flow + 1.01 * euler}, "reference")
    assert below.status == "buckled" and "buckles" in below.message
    above = solve_point({**base, "axial_tension": mud_flow + 0.9 * euler, "reference_modes": 4,
                         "reference_revolutions": 2, "reference_window": 1}, "reference")
    assert above.status != "buckled"


# --- how converged each figure is (docs/reference_model.md §3.1) ------------------------------------------


@pytest.fixture(scope="module")
def default_study():
    from pathlib import Path

    from study import config

    # the pipe joints' eccentricities aligned in three joints, the reading these figures were measured in (the default
    # study turns them 90° in four joints, docs/reference_model.md §1)
    return config.load(Path(__file__).resolve().parents[2] / "configs" / "default.toml",
                       {"pipe.eccentricity_turn": "aligned", "contact.section_length": "93 ft"})


def _default_point(study, rpm, klbf, restitution, ppg, flow):
    """A point of configs/default.toml's grid (8 deg hole), its swept inputs in the units of the config."""
    return study.point(rotary_speed=rpm * np.pi / 30, axial_tension=klbf * 4448.2216152605,
                       restitution=restitution, mud_density=ppg * 119.826427, mud_flow_velocity=flow * 0.3048)


def test_standard_error_by_batch_means_holds_for_correlated_values():
    # an AR(1) series x_k = phi x_(k-1) + e_k, var e = 1: the variance of its mean is 1/((1 - phi)^2 n) for large
    # n (its spectral density at zero; Law & Kelton, Simulation Modeling and Analysis, 3rd ed., §9.5.3); batch
    # means find it where the naive standard deviation / sqrt(n) misses it by sqrt((1 + phi)/(1 - phi)) = 3 for
    # phi = 0.8
    rng = np.random.default_rng(7)
    phi, n, runs = 0.8, 2500, 200
    e = rng.standard_normal((runs, n))
    x = np.zeros((runs, n))
    for k in range(1, n):
        x[:, k] = phi * x[:, k - 1] + e[:, k]
    expected = 1.0 / ((1 - phi) * np.sqrt(n))
    estimates = np.array([reference.standard_error(row) for row in x])
    assert np.mean(estimates) == pytest.approx(expected, rel=0.1)
    assert np.std(np.mean(x, axis=1)) == pytest.approx(expected, rel=0.15)  # the closed form holds here
    quarter = np.array([reference.standard_error(row[:n // 4]) for row in x])
    assert np.mean(quarter) / np.mean(estimates) == pytest.approx(2.0, rel=0.1)  # falls as 1/sqrt(n)
    naive = np.mean(np.std(x, axis=1) / np.sqrt(n))
    assert expected / naive == pytest.approx(np.sqrt((1 + phi) / (1 - phi)), rel=0.1)
    assert reference.standard_error(np.full(10, 3.0)) == 0.0
    assert np.isnan(reference.standard_error([1.0]))  # one value: no estimate


@pytest.mark.parametrize("n", [6, 12, 24, 48])
def test_the_window_bound_covers_the_mean_of_correlated_values(n):
    # an AR(1) series (phi = 0.5) of n values, the window's per-revolution figures: the batch-means interval, the
    # mean plus or minus Student's t on the batches' b - 1 degrees of freedom times the standard error (Schmeiser 1982,
    # doi:10.1287/opre.30.3.556, section 3), covers the true mean (0) at about its 95 %; two standard errors (the
    # normal's bound) cover 74-88 % at these lengths (measured with this seed), short of the 90 % the held-back check
    # of the stated errors asks (docs/validation.md)
    rng = np.random.default_rng(11)
    phi, runs = 0.5, 4000
    e = rng.standard_normal((runs, n + 50))
    x = np.zeros_like(e)
    for k in range(1, n + 50):
        x[:, k] = phi * x[:, k - 1] + e[:, k]
    x = x[:, 50:]  # past the start-up
    error = np.array([reference.standard_error(row) for row in x])
    bound = reference.confidence(n)
    assert bound == pytest.approx(stats.t.ppf(0.975, n // int(np.sqrt(n)) - 1))  # b = n // floor(sqrt(n)) batches
    assert np.mean(np.abs(x.mean(axis=1)) <= bound * error) >= 0.9
    assert np.mean(np.abs(x.mean(axis=1)) <= 2.0 * error) < 0.9


@pytest.mark.parametrize("window, part", [(6, 0.12), (12, 0.052), (12, 0.10), (18, 0.30)])
def test_the_forecast_of_the_window_counts_its_bound_falling(window, part):
    # a window part of t standard errors (reference.confidence) over `window` revolutions of a record twice as long,
    # asked to 5 %-10 %: the window w' foreseen holds the standard error falling as 1/sqrt(w') and the t quantile with
    # its batches (Schmeiser 1982), so its own bound there is within the room, and not far inside it (the forecast
    # takes the fewest batches w' may give, floor(sqrt(w')), a slight overestimate)
    room = 0.1 if window == 6 else 0.05
    more = reference.revolutions_for(2 * window, window, part, room)
    grown = window * (1 + more / (2 * window))
    assert grown == int(grown) > window
    bound = reference.confidence(int(grown)) * (part / reference.confidence(window)) * np.sqrt(window / grown)
    assert 0.8 * room < bound <= room
    if part >= 2 * room:  # far over: fewer than a constant bound foresees (near it, t's discrete steps ask more)
        assert more < 2 * window * ((part / room) ** 2 - 1)
    assert reference.revolutions_for(2 * window, window, 0.8 * room, room) == 0.0  # within: none


def test_slow_settling_on_the_wall_is_not_called_ok(default_study):
    # configs/default.toml at 100 rpm, 5 000 lbf, e = 0.3, 9 ppg, no flow: the tool joints slide on the low side and
    # the motion settles slowly (on the pinned section of issue 20 at 50 rpm the peak force after the default 40
    # revolutions was 17 % above the one after 120 and the old fixed run called it ok; starting from the rest on the
    # joints, 0.9 % here): its stated error says so, and more revolutions than the budget would bring it within 1 %
    from study.solvers.model import gate

    # (the kept modes' stiff contact, without the residual flexibility of docs/reference_model.md §2.1: with it the
    # joints' contact is softer and this point settles within 0.6 % in 46 revolutions; a motion that does not repeat:
    # its figures are held to solver.statistical_tolerance, 1 % here; a budget of 100 revolutions, which it grows
    # into (to 58) until it foresees more than twice the budget: reference.FORECAST_SLACK)
    point = {**_default_point(default_study, 100, 5, 0.3, 9, 0.0), "reference_residual": "none",
             "statistical_tolerance": 0.01, "reference_max_revolutions": 100}
    raw = reference.solve(point)
    short = gate.admit(raw, Scene.from_inputs(point), Tolerances.from_inputs(point))  # as solve_point does
    assert short.extras["whirl"] == "sliding"
    assert short.status == "not_converged", short.message
    assert "above the tolerance" in short.message and np.isfinite(short.values["peak_contact_force"])
    # its stated error covers how far it is from a run 80 revolutions longer (budget = the run: no extension), that
    # run's own stated error beside it: the difference of two estimates, each with its error (the short one alone,
    # 1.7 % at two standard errors, did not cover the 3.1 % of a slide still settling slower than the halves of a
    # 58-revolution record can tell)
    longer = solve_point({**point, "reference_revolutions": 120, "reference_max_revolutions": 120}, "reference")
    stated = short.extras["convergence"]["peak_contact_force"]
    assert stated["dominant"] == "window"
    off = abs(short.values["peak_contact_force"] / longer.values["peak_contact_force"] - 1.0)
    assert stated["total"] > 0.01 and stated["total"] + longer.extras["convergence"]["peak_contact_force"]["total"] >= off
    assert short.extras["revolutions_needed"] > reference.FORECAST_SLACK * 100
    # a looser tolerance admits the same answer, values unchanged
    loose = gate.admit(raw, Scene.from_inputs(point), Tolerances.from_inputs({**point, "statistical_tolerance": 0.5}))
    assert loose.status == "ok" and loose.values["peak_contact_force"] == short.values["peak_contact_force"]


def test_a_periodic_answer_states_a_small_error(base):
    # forward synchronous whirl clear of the wall (the Jeffcott case above): every cycle the same, so the
    # figures' window part is the periodicity tolerance and the error is far inside the study's 1 %
    result = solve_point({**_wide(base), "rotary_speed": 2.0}, "reference")
    assert result.status == "ok" and "periodic every 1 revolution" in result.message
    assert result.error_estimate < 0.005  # what is left is the modes' share (16 modes), well inside 1 %
    for name, parts in result.extras["convergence"].items():
        assert parts["window"] == 1e-7, name  # _wide's periodicity tolerance
    for name, (largest, _) in reference.FIGURES.items():
        # mean = largest (the alternating stress of a synchronous whirl is a remnant near zero: to 1e-3)
        assert result.values[largest] == pytest.approx(result.values[name], rel=1e-3, abs=1e-9)


def test_chaotic_bouncing_figures_are_statistics_whose_error_reflects_their_scatter(default_study):
    # configs/default.toml at 250 rpm, 5 000 lbf, e = 0.7, 9 ppg, no flow: above the speed where the uniform
    # eccentricity's load m_p ε Ω² beats the weight's side load the string leaves the low side and its joints bounce,
    # not periodic; the per-revolution maxima scatter, so the largest seen is above the mean, and the mean of the
    # per-revolution maxima stays within its stated error
    # (without the tool joints' mass: the figures below were measured so; the statistics are the subject here)
    point = {**_default_point(default_study, 250, 5, 0.7, 9, 0.0), "reference_max_revolutions": 1,
             "tool_joint_length": 0.0, "reference_residual": "none"}  # and the kept modes' stiff contact likewise
    # both windows after the same 12-revolution transient (where the short run finds the bouncing stationary)
    short = reference.simulate({**point, "reference_window": 6, "reference_revolutions": 12})
    long = reference.simulate({**point, "reference_window": 72, "reference_revolutions": 12})  # its window: 42
    assert short["verdict"] == long["verdict"] == "not_periodic"
    a = reference.settling(short["cycles"], short["preceding"])
    b = reference.settling(long["cycles"], long["preceding"])
    for name in reference.FIGURES:
        assert b[name]["largest"] > b[name]["value"] and a[name]["largest"] > a[name]["value"], name
        # the short window's stated error (standard error or drift) covers its distance from the long window's: the
        # difference of two estimates, each with its stated error, within three of their combined errors (a two-sigma
        # bound failed one figure of three on another compilation: 10.0 % against 2 x 4.6 %, issue 32)
        assert abs(a[name]["value"] / b[name]["value"] - 1.0) < 3.0 * np.hypot(a[name]["window"], b[name]["window"]), name
    for name in ("max_normal_stress", "alternating_bending_stress"):
        # standard errors: sqrt(6/42) = 0.38 expected of a 6-revolution window's for independent revolutions, more
        # for correlated ones (0.49-0.50 measured); each 6-revolution estimate rests on few batches (about +-30 %),
        # so the long window's is held against the mean of its own seven 6-revolution stretches' estimates, not
        # against one realisation's (which scattered from 0.33 to 1.2 with the last bits of the arithmetic)
        x = np.array([cycle[name] for cycle in long["cycles"]])
        assert x.size >= 36
        sixes = np.mean([reference.standard_error(x[i:i + 6]) / np.mean(x[i:i + 6]) for i in range(0, x.size - 5, 6)])
        assert b[name]["error"] < 0.75 * sixes, name
    # a bounce's peak force scatters from revolution to revolution, so after 42 revolutions the force's standard
    # error is still above the study's 1 % and its stated window part (t standard errors, reference.confidence)
    # above 2 % (measured 4.8 % on one compilation; on a generic-CPU one 4.2 %, beside stresses' 4.1 and 4.7 %: which
    # scatters more, the force or the bending it leaves, is the realisation's, so it is not asserted; a threshold of
    # 5 % on the force alone held for one compilation and not for the next: the last bits move a chaotic trajectory)
    assert b["peak_contact_force"]["error"] > 0.01
    assert b["peak_contact_force"]["window"] >= b["peak_contact_force"]["confidence"] * b["peak_contact_force"]["error"] > 0.02
    assert b["peak_contact_force"]["confidence"] == reference.confidence(len(long["cycles"]))
    result = solve_point(point, "reference")
    assert result.status == "not_converged" and result.extras["whirl"] == "bouncing"
    assert result.values["window_largest_contact_force"] > result.values["peak_contact_force"] > 0


def test_the_window_grows_until_the_figures_converge_within_the_budget(default_study):
    # configs/default.toml at 150 rpm, 5 000 lbf, e = 0.7, 9 ppg, no flow, a statistical tolerance of 3 %: the joints
    # slide on the low side and settle slowly; after the fixed run (40 + 6 revolutions) the error is about 3.5 %, and
    # the record grows, the first half dropped while it drifts, until the figures are within the tolerance, inside
    # the default budget
    point = {**_default_point(default_study, 150, 5, 0.7, 9, 0.0), "statistical_tolerance": 0.03}
    fixed = solve_point({**point, "reference_max_revolutions": 46}, "reference")  # no room to grow
    assert fixed.values["revolutions_simulated"] == pytest.approx(46)
    assert fixed.status == "not_converged" and fixed.error_estimate > 0.03
    # it foresaw the revolutions the settling needs from how fast the state's changes shrink
    needed = fixed.extras["revolutions_needed"]
    assert 46 < needed <= ReferenceOptions.default("reference_max_revolutions")
    grown = solve_point(point, "reference")
    assert grown.status == "ok", grown.message
    assert grown.error_estimate <= 0.03 and 46 < grown.values["revolutions_simulated"] <= ReferenceOptions.default(
        "reference_max_revolutions") + 1e-6
    # the grown answer lies within the fixed one's stated error of it, for the force and the normal stress; not for
    # the alternating stress, whose slow settling the fixed run's two halves do not see: 3.82 MPa after 46
    # revolutions, stated 5.4 %, 3.21 MPa after 200 (19 %; docs/reference_model.md §3.1, an open gap)
    for name, parts in fixed.extras["convergence"].items():
        if name in ("alternating_bending_stress", "damage_rate"):
            continue
        assert abs(fixed.values[name] / grown.values[name] - 1.0) <= parts["total"] + grown.error_estimate, name


def test_a_bouncing_window_grows_until_its_statistics_meet_the_statistical_tolerance(default_study, monkeypatch):
    # issue 36: configs/default.toml at 250 rpm, 20 000 lbf, e = 0.3, 9 ppg, no flow: the joints bounce, the figures
    # are means over revolutions (statistical_figures) held to solver.statistical_tolerance, and the record grows
    # from the first look (24 revolutions, its halves drifting apart: 35 % here) by a record's length, where the halves
    # agree and the window is the whole record, then towards where the standard errors are foreseen to meet the
    # tolerance, and stops there (36 revolutions measured for 15 % and for 5 %, the default). The modes' part and the
    # quasi-static correction's are set aside (at a bouncing point 16 modes state 10-60 %, above any statistical
    # tolerance, and the growth would stop at once): the window part alone decides
    monkeypatch.setattr(reference.method, "modal_check", lambda *args, **kwargs: dict.fromkeys(reference.MODAL_FIGURES, 0.0))
    # (and the strikes' replayed part, docs/reference_model.md §2.2)
    monkeypatch.setattr(reference.method, "impact_modal_error",
                        lambda *args, **kwargs: dict.fromkeys(reference.MODAL_FIGURES, 0.0))
    # (the modes' own force, reference_strike_force "modes": the local model's own 9 % part is not a modes' part)
    point = {**_default_point(default_study, 250, 20, 0.3, 9, 0.0), "statistical_tolerance": 0.15,
             "reference_strike_force": "modes"}
    first = solve_point({**point, "reference_max_revolutions": 1}, "reference")  # the first look, no room to grow
    assert first.extras["whirl"] == "bouncing" and first.values["statistical_figures"] == 1.0
    assert first.status == "not_converged" and first.error_estimate > 0.15
    grown = [solve_point({**point, "statistical_tolerance": tolerance}, "reference") for tolerance in (0.15, 0.1)]
    for result, tolerance in zip(grown, (0.15, 0.1)):
        assert result.status == "ok" and result.error_estimate <= tolerance, result.message
        assert f"solver.statistical_tolerance {tolerance:g}" in result.message
        # the damage rate is held to the same tolerance as a stress: (1 + tolerance)^5 - 1 (fatigue.damage_exponent)
        assert result.extras["convergence"]["damage_rate"]["total"] <= (1 + tolerance) ** 5 - 1
    revolutions = [r.values["revolutions_simulated"] for r in (first, *grown)]
    assert revolutions[0] < revolutions[1] <= revolutions[2] <= ReferenceOptions.default("reference_max_revolutions")
    # a tolerance the budget cannot reach: stopped short of the budget, the revolutions it would take said
    short = solve_point({**point, "statistical_tolerance": 0.01}, "reference")
    assert short.status == "not_converged" and short.values["revolutions_simulated"] < ReferenceOptions.default(
        "reference_max_revolutions")
    assert short.extras["revolutions_needed"] > ReferenceOptions.default("reference_max_revolutions")


def test_a_figure_within_reach_grows_the_window_while_another_cannot(default_study, monkeypatch):
    # issue 36: the window grows for every figure that can reach its tolerance within the budget, whatever the others.
    # The bouncing point of the test above (250 rpm, 20 000 lbf, e = 0.3, 9 ppg) with a peak force whose modes' part
    # alone (50 %, set here) is over its tolerance: before, that stopped the record at its first look for every figure;
    # now the stresses, the deflection and the damage rate grow their window to within a 15 % tolerance (16 modes, no
    # doubling) while the force is named as what the revolutions cannot fix
    def modal(*args, **kwargs):
        return {**dict.fromkeys(reference.MODAL_FIGURES, 0.0), "peak_contact_force": 0.5}

    monkeypatch.setattr(reference.method, "modal_check", modal)
    # (the modes' own force, reference_strike_force "modes", whose modes' part is the one set here)
    point = {**_default_point(default_study, 250, 20, 0.3, 9, 0.0), "statistical_tolerance": 0.15,
             "force_tolerance": 0.3, "reference_max_modes": 16, "reference_window_growth": "figure",
             "reference_strike_force": "modes"}
    first = solve_point({**point, "reference_max_revolutions": 1}, "reference")  # the first look, no room to grow
    # the default growth ("point") stops at the first look: the force cannot get there, so the point stays over
    held = solve_point({**point, "reference_window_growth": "point"}, "reference")
    assert held.values["revolutions_simulated"] == first.values["revolutions_simulated"]
    # and its message says so: the figures over their tolerance within reach were stopped by the force, not by a
    # budget they would exceed (their forecasts are within it)
    stopped = held.extras["window_stopped_by"]
    assert stopped.pop("peak_contact_force") == "modes" and stopped and set(stopped.values()) == {"others"}
    assert "window stopped as peak force could not get there" in held.message
    assert "more than the budget" not in held.message
    grown = solve_point(point, "reference")
    assert grown.extras["whirl"] == "bouncing" and grown.status == "not_converged"
    assert grown.values["revolutions_simulated"] > first.values["revolutions_simulated"]
    parts = grown.extras["convergence"]
    for name in ("max_normal_stress", "alternating_bending_stress", "max_deflection"):
        assert parts[name]["total"] <= 0.15, name
    assert parts["damage_rate"]["total"] <= 1.15**5 - 1  # held as the stress error that makes it
    assert grown.extras["revolutions_needed_by_figure"] == {"peak_contact_force": np.inf}
    assert "peak force: more revolutions would not bring it within" in grown.message
    # the force's error is stated whole, and counted in the point's estimate as its share of its own tolerance (30 %
    # here) in the statistical one: total x 0.15 / 0.3
    force = parts["peak_contact_force"]
    assert force["modes"] == 0.5 and grown.values["peak_contact_force_error"] == force["total"] > 0.5
    assert force["equivalent"] == pytest.approx(force["total"] * 0.15 / 0.3)
    assert grown.error_estimate == pytest.approx(max(e["equivalent"] for e in parts.values()))
    # the grown answer's stated errors cover a longer run's (the same point at a 5 % tolerance: more revolutions): the
    # difference of two estimates within the sum of their stated window parts
    longer = solve_point({**point, "statistical_tolerance": 0.05}, "reference")
    assert longer.values["revolutions_simulated"] > grown.values["revolutions_simulated"]
    for name in ("max_normal_stress", "alternating_bending_stress", "max_deflection", "peak_contact_force"):
        off = abs(grown.values[name] / longer.values[name] - 1.0)
        assert off <= parts[name]["window"] + longer.extras["convergence"][name]["window"], name


def test_a_pulse_runs_window_is_not_stopped_by_the_in_run_modal_part(default_study, monkeypatch):
    # issue 36: with the strikes' pulses (docs/reference_model.md §2.4) the modal part stated is the figures' change
    # between whole runs at N/2 and N modes (reference.doubling_modal_error); the in-run measure's (here a force part
    # of 50 %, set, over the force's 30 %), which stopped the window at its first look under the default growth
    # ("point"), does not stop it: the point of the test above grows its window until each figure is within its
    # tolerance (15 %) or its forecast is out of reach, none stopped for its modes or by another figure
    def modal(*args, **kwargs):
        return {**dict.fromkeys(reference.MODAL_FIGURES, 0.0), "peak_contact_force": 0.5}

    monkeypatch.setattr(reference.method, "modal_check", modal)
    point = {**_default_point(default_study, 250, 20, 0.3, 9, 0.0), "statistical_tolerance": 0.15,
             "force_tolerance": 0.3, "reference_modes": 8, "reference_strike_force": "pulse",
             "reference_revolutions": 12, "reference_max_revolutions": 60}
    first = reference.simulate({**point, "reference_max_revolutions": 1})  # the first look, no room to grow
    grown = reference.simulate(point)
    assert grown["verdict"] == "not_periodic" and grown["model"].pulse is not None
    assert len(grown["cycles"]) + grown["revolutions"] > len(first["cycles"]) + first["revolutions"]
    assert not {"modes", "others"} & set(grown["stopped_by"].values())
    assert all(np.isfinite(n) for n in grown["needed_by"].values())
    # the modes' part is still what the run measured in-run (stated where no run at half the modes is there)
    assert grown["modal"]["peak_contact_force"] == 0.5


def test_the_stopped_windows_message_says_why_each_figure_stopped():
    # issue 36: a figure left over its tolerance stopped for its own reason (its modes part, its forecast beyond
    # FORECAST_SLACK x the budget, the budget spent) or, with reference_window_growth = "point", because another could
    # not get there; the message said "more than the budget" of 42 revolutions under a budget of 200
    slack = reference.FORECAST_SLACK
    needed = {"peak_contact_force": np.inf, "alternating_bending_stress": 42.0,
              "max_normal_stress": slack * 200 + 1.0}
    assert reference.method.stop_reasons(needed, 24, 200) == {
        "peak_contact_force": "modes", "alternating_bending_stress": "others", "max_normal_stress": "forecast"}
    labels = {"peak_contact_force": "peak force", "alternating_bending_stress": "alternating stress",
              "max_normal_stress": "max normal stress"}
    text = reference.method.stop_message(needed, reference.method.stop_reasons(needed, 24, 200), 200, labels)
    assert ("alternating stress: about 42 revolutions in all would, within reach of the budget of 200 "
            "(solver.reference_max_revolutions), but the window stopped as peak force and max normal stress could not "
            "get there") in text
    assert f"max normal stress: about {slack * 200 + 1:.0f} revolutions in all would, beyond {slack:g} times" in text
    assert "peak force: more revolutions would not bring it within" in text
    # the budget spent: more than it, as said before
    assert reference.method.stop_reasons({"max_normal_stress": 250.0}, 200, 200) == {"max_normal_stress": "budget"}
    assert "more than the budget of 200" in reference.method.stop_message(
        {"max_normal_stress": 250.0}, {"max_normal_stress": "budget"}, 200, labels)
    # a forecast asking for no more (a settling ratio of nought) is not called out of reach
    assert reference.method.stop_reasons({"max_normal_stress": 24.0}, 24, 200) == {"max_normal_stress": "none"}


def test_the_force_is_held_to_its_own_tolerance_in_the_point_estimate():
    # issue 36: figure_tolerance and stress_equivalent, the rule the gate's estimate follows (docs/reference_model.md
    # §3.1): the force may be off by its own tolerance where a stress may be off by the point's; the damage rate by
    # (1 + tolerance)^m - 1 (m = 5, DNV-RP-C203's second slope)
    assert reference.figure_tolerance("peak_contact_force", 0.05, 5.0, 0.15) == 0.15
    assert reference.figure_tolerance("peak_contact_force", 0.05, 5.0) == 0.05  # no force tolerance given: the point's
    assert reference.figure_tolerance("max_normal_stress", 0.05, 5.0, 0.15) == 0.05
    assert reference.figure_tolerance(reference.DAMAGE, 0.05, 5.0, 0.15) == pytest.approx(1.05**5 - 1)
    # a force 12 % off under a 15 % force tolerance and a 5 % statistical one counts as 4 %: within the gate's 5 %
    assert reference.stress_equivalent("peak_contact_force", 0.12, 5.0, 0.05 / 0.15) == pytest.approx(0.04)
    assert reference.stress_equivalent("max_normal_stress", 0.12, 5.0, 0.05 / 0.15) == 0.12
    assert reference.stress_equivalent(reference.DAMAGE, 1.05**5 - 1, 5.0) == pytest.approx(0.05)


START_UP = [4900.0, 1200.0, 140.0, 9000.0, 30.0, 800.0]  # the first 6 revolutions: never in the test


@pytest.mark.parametrize("case, peaks, impacts, shrink, expected", [
    ("stationary scatter", [5.0, 9.0, 6.0, 8.0, 7.0, 6.0, 9.0, 5.0, 8.0, 6.0, 7.0, 7.0], [4, 6, 5] * 4, 1.0, True),
    ("force drifting down", [12.0, 11.5, 11.0, 10.5, 10.0, 9.5, 9.0, 8.5, 8.0, 7.5, 7.0, 6.5], [4, 6, 5] * 4, 1.0,
     False),
    ("strikes in 1 of the last 6 revolutions", [5.0, 9.0, 6.0, 8.0, 7.0, 6.0, 9.0, 5.0, 8.0, 6.0, 7.0, 7.0],
     [4, 6, 5, 4, 6, 5, 3, 0, 0, 0, 0, 0], 1.0, False),
    ("state settling by 20 % a revolution", [5.0, 9.0, 6.0, 8.0, 7.0, 6.0, 9.0, 5.0, 8.0, 6.0, 7.0, 7.0],
     [4, 6, 5] * 4, 0.8, False),
])
def test_the_transient_ends_where_bouncing_is_stationary(case, peaks, impacts, shrink, expected):
    # constructed series after a wild start-up: per-revolution peak forces and onsets, and boundary states whose
    # changes shrink by `shrink` a revolution (1: wandering, not settling)
    rng = np.random.default_rng(1)
    steps = [shrink**k * (1.0 + 0.1 * rng.standard_normal(4)) for k in range(18)]
    states = np.cumsum([np.zeros(4)] + steps, axis=0)
    assert reference.stationary(START_UP + peaks, [50] * 6 + impacts, states, np.ones(4), 6) is expected, case
    assert not reference.stationary(peaks, impacts, states[:13], np.ones(4), 6)  # before 3 x 6 revolutions: never


def test_sliding_after_a_violent_start_is_not_taken_for_stationary_bouncing(base):
    # the paper's example in an 8-degree hole at 50 rpm, dropped from the hole's centre (reference_initial = "rest"):
    # strikes in the first revolutions, then the joints lie on the wall and slide: the transient runs its 40
    # revolutions (and the record no more: the budget leaves no room to grow it)
    inputs = {**base, "rotary_speed": 50 * np.pi / 30, "inclination": np.radians(8), "reference_initial": "rest",
              "reference_max_revolutions": 1}
    run = reference.simulate(inputs)
    assert not run["stationary"] and run["revolutions"] == 40


def test_the_cycles_compared_share_one_decision_on_the_quasi_static_correction(base, monkeypatch):
    # the paper's example in an 8-degree hole at 50 rpm grows its record after the 40-revolution transient; were the
    # correction decided apart for the revolutions recorded first and those added (here made to differ: applied to
    # the first, not to the others), the window and the stretch before it would mix corrected and plain stresses and
    # show a drift that is not in the motion
    decisions = iter([True])
    monkeypatch.setattr(reference.statistics, "quasi_static_applies", lambda model, window: next(decisions, False))
    run = reference.simulate({**base, "rotary_speed": 50 * np.pi / 30, "inclination": np.radians(8)})
    assert len(run["cycles"]) + len(run["preceding"]) > 6  # the record grew
    assert {c["correction"] for c in run["cycles"] + run["preceding"]} == {False}


def test_a_stationary_bouncing_ends_its_transient_early_within_its_stated_error(default_study):
    # configs/default.toml at 250 rpm, 5 000 lbf, e = 0.7, 9 ppg, no flow: the joints bounce chaotically from the
    # first revolutions; the transient ends when two 6-revolution stretches agree (18 revolutions here, not 40),
    # and the answer lies within the stated errors of a run whose transient is the full 40 revolutions (a 21-
    # revolution window cannot end it early: 2 x 21 > 40)
    point = _default_point(default_study, 250, 5, 0.7, 9, 0.0)
    early = solve_point(point, "reference")
    assert early.values["revolutions_simulated"] < 40 and "stationary statistics" in early.message
    full = solve_point({**point, "reference_window": 21}, "reference")
    assert full.values["revolutions_simulated"] == pytest.approx(40 + 21)
    for name in reference.FIGURES:
        off = abs(early.values[name] / full.values[name] - 1.0)
        assert off < 2.0 * (early.extras["convergence"][name]["total"] + full.extras["convergence"][name]["total"]), name


def test_a_least_transient_keeps_its_first_revolutions_out_of_the_window(default_study):
    # solver.reference_min_revolutions (set by auto where the sliding check's run chattered only after tens of quiet
    # revolutions, docs/reference_model.md §10): the same point as above on 16 modes, 3-revolution stretches; its
    # statistics end the transient on the start-up's bouncing (after 6 revolutions, measured); with 24 asked, neither
    # the window nor the stretch before it holds any of the first 24
    point = {**_default_point(default_study, 250, 5, 0.7, 9, 0.0), "reference_modes": 16, "reference_max_modes": 16,
             "reference_window": 3, "reference_max_revolutions": 40}
    free = reference.solve(point)
    assert free.values["revolutions_simulated"] - free.values["window_revolutions"] < 24
    floored = reference.solve({**point, "reference_min_revolutions": 24})
    assert floored.values["revolutions_simulated"] - floored.values["window_revolutions"] >= 24, floored.message
    assert "none of the first 24 revolutions in the window" in floored.message
    run = reference.simulate({**point, "reference_min_revolutions": 24})
    assert run["revolutions"] >= 24 and run["window"].start >= 24 * run["model"].period * (1 - 1e-9)
    options = ReferenceOptions(reference_min_revolutions=24, reference_window=3)
    assert reference.transient_bounds(options) == (24, 40)
    assert reference.transient_bounds(options, start={"modes": 16}) == (0, 40)  # a continued run is past it
    assert reference.transient_bounds(ReferenceOptions(reference_min_revolutions=36, reference_window=3)) == (36, 42)
    assert reference.transient_bounds(ReferenceOptions(reference_window=21)) == (0, 40)  # none asked: as given


def test_an_unknown_integrator_scheme_is_refused_naming_the_option(base):
    model = reference.build_model({**base, "reference_modes": 2})
    with pytest.raises(ValueError, match="reference_integrator = 'rk4'; allowed: lawson, lawson-flight, dopri5"):
        reference.Integrator(model, 1e-6, scheme="rk4")
    result = solve_point({**base, "reference_integrator": "rk4"}, "reference")  # a point's bad input: its status
    assert result.status == "failed" and "reference_integrator = 'rk4'; allowed:" in result.message


def test_restitution_zero_is_refused_not_computed_as_an_elastic_contact():
    # issue 32: e = 0 set the reference model's hysteresis to 0, the perfectly elastic contact of e = 1 (bit-identical
    # results). The Hunt-Crossley damping that stops a rebound grows without bound as e -> 0: the model cannot
    # represent it, and says so (status failed, the calibration's words); a config refuses e = 0 (test_config.py).
    from study import config
    from study.solvers import solve_point

    root = Path(__file__).resolve().parents[2]
    inputs = {**config.load(root / "configs" / "paper.toml").point(), "restitution": 0.0}
    result = solve_point(inputs, "reference")
    assert result.status == "failed" and "restitution = 0.0: the calibrated contact needs 0 < e <= 1" in result.message


def test_drag_and_viscous_keeps_the_drag_and_damps_each_mode_by_the_mud_s_stokes_layer(base):
    # issue 36: "drag+viscous" keeps the quadratic drag of "drag" and adds each mode's linear damping c(ω_n)/M, the
    # Stokes layer of the mud's plastic viscosity confined by the hole. Its thin-layer limit (|s| = a√(ω/ν) >> 1):
    # c = 2√2 πρa√(ων) (1 + γ³)/(1 − γ²)², γ = a/b (Stokes 1851; Chen, Wambsganss & Jendrzejczyk 1976), within
    # O(1/|s|) (the modes' 1 to 4 % here); ten times the viscosity: √10 times the layer's, with
    # its O(1/|s|) √10 times larger
    options = {**base, "reference_modes": 16}
    drag = reference.build_model(options)
    model = reference.build_model({**options, "reference_damping": "drag+viscous", "plastic_viscosity": 0.020})
    thick = reference.build_model({**options, "reference_damping": "drag+viscous", "plastic_viscosity": 0.200})
    assert model.drag == drag.drag > 0 and np.all(drag.damping == 0.0)
    scene = Scene.from_inputs(base)
    rho, a, b = scene.mud_density, scene.outer_radius, scene.hole_radius
    gamma = a / b
    omega = model.omega[4:]
    layer = (2 * np.sqrt(2) * np.pi * rho * a * np.sqrt(omega * 0.020 / rho) * (1 + gamma**3) / (1 - gamma**2) ** 2
             / model.props["mass_per_length"])
    s = a * np.sqrt(omega * rho / 0.020)
    assert np.all(np.abs(model.damping[4:] / layer - 1.0) < 4.0 / s)  # the next term: 2.7/|s| here
    thin = np.abs(thick.damping[4:] / (np.sqrt(10.0) * layer) - 1.0)  # √10 the layer, |s| √10 smaller
    assert np.all(thin < 4.0 * np.sqrt(10.0) / s) and np.all(thin > np.abs(model.damping[4:] / layer - 1.0))
    assert np.all(model.damping[1:] > 0.0) and model.damping[0] == 0.0  # the rigid translation (ω = 0): drag alone
    # the mud's viscosity reaches the scene from its input, 20 cP by default
    assert scene.mud_viscosity == 0.020 and Scene.from_inputs({**base, "plastic_viscosity": 0.05}).mud_viscosity == 0.05


@pytest.mark.parametrize("at, doubled", [(0.5, True), (0.3, False)], ids=["symmetric: vectors", "not: series law"])
def test_the_modal_measure_is_the_one_the_model_took(base, at, doubled):
    # reference_residual = "dynamic" asks for the residual vectors, whose modal part is the figures' change from half
    # the modes (reference.modal_by_doubling); where the contact points do not lie symmetrically about the section's
    # middle the model keeps the series law (docs/reference_model.md §2.1), and the count's choice follows the model,
    # not the option (reference.run reads it from the run)
    result = solve_point(_rolling(base, 0, contact_points=[at], reference_residual="dynamic"), "reference")
    assert result.extras["reference_residual"] == ("dynamic" if doubled else "series")
    assert result.extras["modal_by_doubling"] is doubled
