"""Tests of the compiled integrator of the reference model (study.solvers.kernels.whirl_kernel).

The model's physics checks (Jeffcott, rolling whirl, energy, the event-driven time domain, scipy on the same
equations) are in test_reference.py; here the integrator itself: an impact on a linear wall against the
piecewise-linear oscillator in closed form, the onset located within its tolerance, its work counted, and the
Hunt–Crossley damping set at an onset from the approach speed, down to ONSET_SPEED_FLOOR; for every scheme
(reference.SCHEMES), and the Lawson form's exactness on the modes' free motion and its order on a forced one.
"""

import ast
import inspect
import textwrap

import numpy as np
import pytest

from study.solvers.methods import reference
from study.solvers.kernels import whirl_kernel


def _one_mode(inputs):
    """The model of ``inputs`` with its first bending mode alone (ψ_1 = cos 2πx/L of the periodic basis, index 1):
    one mode with stiffness (the rigid translation left out)."""
    import dataclasses

    model = reference.build_model({**inputs, "reference_modes": 2, "tool_joint_length": 0.0})  # the basis itself
    keep = [1]
    return dataclasses.replace(model, modes=model.modes[keep], omega=model.omega[keep], phi=model.phi[:, keep],
                               eccentric=model.eccentric[keep], side=model.side[keep], damping=model.damping[keep],
                               drag_shapes=model.drag_shapes[:, keep], cache={})


def _one_mode_on_a_linear_wall(base):
    """One mode in one plane, touching at its crest (φ = 1) a linear spring without dashpot (penalty law, e = 1),
    nothing else acting: a piecewise-linear oscillator."""
    inputs = {**base, "contact_points": [0.0], "contact_kinds": [0], "friction": 0.0,
              "eccentricity": 0.0, "reference_damping": "none", "contact_law": "penalty", "restitution": 1.0}
    model = _one_mode(inputs)
    assert model.penalty_damping[0] == 0.0 and model.phi[0, 0] == pytest.approx(1.0)
    return model


def _closed_form_cycle(model, v0):
    """Out from the centre at v0, onto the wall, back: (time to the wall, contact time, peak force).

    Flight q = (v0/ω) sin ωt reaches c at t1 = asin(ωc/v0)/ω with speed v1 = √(v0² − ω²c²); in contact
    q̈ = −ω²q − (k/m)(q − c): a harmonic motion q − q_e = A cos(Ωτ − ψ) about q_e = (k/m)c/Ω² at Ω² = ω² + k/m,
    ψ = atan2(v1/Ω, c − q_e), which is at c again, leaving the wall at −v1, after 2ψ/Ω (Shaw & Holmes 1983, J. Sound Vib. 90, 129–155,
    doi:10.1016/0022-460X(83)90407-8: the flight and contact solutions of the piecewise-linear oscillator)."""
    om, c, k, m = model.omega[0], model.clearance[0], model.penalty_stiffness[0], model.mass
    t1 = np.arcsin(om * c / v0) / om
    v1 = np.sqrt(v0**2 - (om * c) ** 2)
    big = np.sqrt(om**2 + k / m)
    qe = k / m * c / big**2
    psi = np.arctan2(v1 / big, c - qe)
    amplitude = np.hypot(c - qe, v1 / big)
    return t1, 2.0 * psi / big, k * (qe + amplitude - c)


@pytest.mark.parametrize("scheme", reference.SCHEMES)
@pytest.mark.parametrize("rtol", [1e-6, 1e-9])
def test_an_impact_on_a_linear_wall_is_the_closed_form_cycle(paper_inputs, rtol, scheme):
    # after flight, contact and the flight back the mode is at the centre again at -v0 (closed form above), to
    # 1e-5 of c and Ωc as the planar impacts of test_reference against the event-driven time domain; at rtol 1e-9
    # the onset tolerance (1e-6 c) is the floor. (The kernel before the located contact ends and PI control:
    # 4.8e-4 c at rtol 1e-6, 2.6e-6 c at 1e-9; with them 9e-7 c and 2.5e-6 c.)
    model = _one_mode_on_a_linear_wall(paper_inputs)
    c, om = model.clearance[0], model.rotary_speed
    v0 = 3.0 * model.omega[0] * c
    t1, contact, peak = _closed_form_cycle(model, v0)
    z0 = np.zeros(4 + 4)
    z0[2] = v0
    run = reference.Integrator(model, rtol, z0, scheme)
    window = run.run(2 * t1 + contact)
    tolerance = 1e-5
    assert run.outcome == whirl_kernel.OK
    assert int(window.onsets[0]) == 1
    assert abs(run.z[0]) / c < tolerance
    assert abs(run.z[2] + v0) / (om * c) < tolerance
    assert np.all(run.z[[1, 3]] == 0.0)  # it stays in its plane
    assert window.peak[0] == pytest.approx(peak, rel=1e-2)  # the largest force at a step's end
    # both ends of the contact located: its length (4e-4 measured; before, only to within the steps in it)
    assert window.contact_time[0] == pytest.approx(contact, rel=1e-3)
    # every evaluation counted: the first, six per attempted step, one where the contact opened
    work = run.work
    attempts = work[whirl_kernel.S_ACCEPTED] + work[whirl_kernel.S_ERROR_REJECTED] + work[whirl_kernel.S_SWITCH_REDONE]
    assert work[whirl_kernel.S_RHS] == 1 + 6 * attempts + 1
    assert work[whirl_kernel.S_ACCEPTED] == run.steps


@pytest.mark.parametrize("scheme", reference.SCHEMES)
def test_the_onset_is_located_within_its_tolerance(paper_inputs, scheme):
    # stopped inside the contact, the time in contact dates the onset: within ONSET_TOLERANCE c of the wall, at the
    # closed-form approach speed, from the closed-form time (above)
    model = _one_mode_on_a_linear_wall(paper_inputs)
    c = model.clearance[0]
    v0 = 3.0 * model.omega[0] * c
    t1, contact, _ = _closed_form_cycle(model, v0)
    v1 = np.sqrt(v0**2 - (model.omega[0] * c) ** 2)
    z0 = np.zeros(8)
    z0[2] = v0
    run = reference.Integrator(model, 1e-6, z0, scheme)
    run.h = 0.5 * t1  # a first step that would carry the point well past the wall
    end = t1 + 0.1 * contact
    window = run.run(end)
    assert window.onsets[0] == 1 and run.active[0]
    onset = end - window.contact_time[0]
    assert abs(onset - t1) <= 2 * whirl_kernel.ONSET_TOLERANCE * c / v1


def _one_mode_hertz(base, **extra):
    """One mode in one plane touching at its crest, Hertz contact with e = 0.5, nothing else acting."""
    return _one_mode({**base, "contact_points": [0.0], "contact_kinds": [0], "friction": 0.0, "eccentricity": 0.0,
                      "reference_damping": "none", "restitution": 0.5, **extra})



@pytest.mark.parametrize("scheme", reference.SCHEMES)
def test_a_mass_on_a_hertz_spring_is_hertzs_closed_form_impact(paper_inputs, scheme):
    # the kernel's one-mode case: the rigid translation alone (ω = 0) thrown at v0 onto its wall, Hertz contact without
    # damping (e = 1) and without the modes left out (residual law "none": the spring K δ^{3/2} alone), nothing else
    # acting; the point's mass m/φ². Hertz's impact in closed form (Johnson, Contact Mechanics, 1985, §11.4):
    # δ_max = (5 m v0² / 4K)^{2/5}, F_max = K δ_max^{3/2} = K^{2/5} (5/4 m v0²)^{3/5}, contact time
    # 2 δ_max/v0 ∫_0^1 (1 − x^{5/2})^{-1/2} dx = 2.9432 δ_max/v0, rebound at −v0. Held in contact by the same step as a
    # bouncing point's (DOPRI5 in contact for "lawson-flight" and "dopri5", the Lawson form for "lawson")
    import dataclasses

    inputs = {**paper_inputs, "contact_points": [0.0], "contact_kinds": [0], "friction": 0.0, "eccentricity": 0.0,
              "reference_damping": "none", "restitution": 1.0, "reference_residual": "none"}
    model = reference.build_model({**inputs, "reference_modes": 2, "tool_joint_length": 0.0})
    keep = [0]
    model = dataclasses.replace(model, modes=model.modes[keep], omega=model.omega[keep], phi=model.phi[:, keep],
                                eccentric=model.eccentric[keep], side=model.side[keep], damping=model.damping[keep],
                                drag_shapes=model.drag_shapes[:, keep], cache={})
    sy = model.system()
    K, fr, inv_m, hyst = sy[9][0], sy[13][0], sy[12][4], sy[12][6]
    assert model.omega[0] == 0.0 and fr == 0.0 and hyst == 0.0 and np.all(model.side == 0.0)
    phi, c = model.phi[0, 0], model.clearance[0]
    mass = 1.0 / (inv_m * phi**2)
    v0 = 0.3  # [m/s], the thrown string's speed of tests/solvers/test_modes.py
    delta = (5.0 * mass * v0**2 / (4.0 * K)) ** 0.4
    from scipy.integrate import quad

    shape = quad(lambda x: 1.0 / np.sqrt(1.0 - x**2.5), 0.0, 1.0, limit=200)[0]
    assert shape == pytest.approx(1.4716, abs=1e-4)  # Johnson's 2.94 = 2 x 1.47
    gap = 1e-5  # [m] off the wall
    z0 = np.zeros(8)
    z0[0], z0[2] = (c - gap) / phi, v0 / phi
    run = reference.Integrator(model, 1e-6, z0, scheme)
    contact = 2.0 * shape * delta / v0
    window = run.run(2.0 * gap / v0 + contact)
    assert run.outcome == whirl_kernel.OK and int(window.onsets[0]) == 1 and not run.active[0]
    # the largest force at a step's end: within the steps' spacing near the crest (0.4-0.42 % below, 13-14 steps)
    assert window.peak[0] == pytest.approx(K ** 0.4 * (1.25 * mass * v0**2) ** 0.6, rel=1e-2)
    assert window.contact_time[0] == pytest.approx(contact, rel=1e-4)  # both ends located (9e-7, 1.5e-5 Lawson)
    # the rebound at −v0 (no energy lost) and back where it started, to 1e-5 of Ωc and c as the impact on a linear wall
    # above (the steps' error scale: rtol 1e-6 of Ωc and c a step)
    om = model.rotary_speed
    assert abs(run.z[2] * phi + v0) / (om * c) < 1e-5
    assert abs(run.z[0] * phi - (c - gap)) / c < 1e-5

def test_hunt_crossley_damping_is_set_from_the_approach_speed(paper_inputs):
    # χ = h(e)/v1 (Hunt & Crossley 1975, doi:10.1115/1.3423596, with the calibrated h(e)) at the closed-form
    # approach speed v1 = √(v0² − ω²c²) of the free flight (as in _closed_form_cycle)
    from study.physics.contact import calibrated_hysteresis

    model = _one_mode_hertz(paper_inputs)
    om, c = model.omega[0], model.clearance[0]
    v0 = np.hypot(om * c, 3.0 * om * c)
    t1 = np.arcsin(om * c / v0) / om
    z0 = np.zeros(8)
    z0[2] = v0
    run = reference.Integrator(model, 1e-9, z0)
    run.run(t1 * (1 + 1e-3))
    assert run.active[0]
    assert run.chi[0] == pytest.approx(calibrated_hysteresis(0.5) / (3.0 * om * c), rel=1e-4)


def test_a_contact_settling_at_a_vanishing_speed_gets_the_damping_of_the_floor(paper_inputs):
    # laid 1e-10 c off the wall under a side load that sags it to twice the clearance: it reaches the wall at
    # √(2 a 1e-10 c) (about 1e-6 m/s, a = s - ω²c), far below ONSET_SPEED_FLOOR, and takes that floor's χ
    from study.physics.contact import calibrated_hysteresis

    import dataclasses

    unit = _one_mode_hertz(paper_inputs)
    om, c = unit.omega[0], unit.clearance[0]
    model = dataclasses.replace(unit, side=np.array([2.0 * om**2 * c]))  # a load on this mode alone
    a = model.side[0] - om**2 * c
    assert np.sqrt(2 * a * 1e-10 * c) < 1e-2 * whirl_kernel.ONSET_SPEED_FLOOR
    z0 = np.zeros(8)
    z0[0] = c * (1 - 1e-10)
    run = reference.Integrator(model, 1e-9, z0)
    run.run(0.01 / om)
    assert run.active[0]
    assert run.chi[0] == pytest.approx(calibrated_hysteresis(0.5) / whirl_kernel.ONSET_SPEED_FLOOR, rel=1e-12)


# --- the Lawson form: exact on the modes' linear part ------------------------------------------------------


def _clear_of_the_wall(base, **extra):
    """The paper's section in a 20-in hole (the walls out of reach), no eccentricity, no side load, no drag: the
    modes' linear part alone, unless ``extra`` drives it."""
    return reference.build_model({**base, "hole_diameter": 20 * 0.0254, "eccentricity": 0.0, "side_load": 0.0,
                                  "reference_damping": "none", **extra})


def _forced(base):
    """Four modes clear of the wall, with linear modal damping, each driven by a turning load ε_n and a fixed one s_n
    (the rigid translation ψ_0 by the turning load alone: it has no stiffness to hold a fixed one)."""
    import dataclasses

    model = _clear_of_the_wall(base, eccentricity=0.1 * 0.0254, reference_modes=4, reference_damping="viscous",
                               damping_ratio=0.05, rotary_speed=20.0)
    drive = model.eccentric[0] * np.array([1.0, 0.5, 0.25, 0.125])
    return dataclasses.replace(model, eccentric=drive, side=np.array([0.0, 2.0, 1.0, 0.5]) * drive[0])


def _static(model):
    """s_n/ω_n², 0 where ω_n = 0 (no fixed load there)."""
    return np.divide(model.side, model.omega**2, out=np.zeros(model.n_modes), where=model.omega > 0)


@pytest.mark.parametrize("ratio", [0.0, 0.05, 1.0, 1.5], ids=["undamped", "underdamped", "critical", "overdamped"])
def test_a_free_modal_oscillator_is_exact_at_large_steps(paper_inputs, ratio):
    # the free motion of each mode, q̈ = −ω² q − 2ζω q̇, over 20 periods of the first mode in steps of 30 periods of the
    # highest, against the matrix exponential of [[0, 1], [−ω², −2ζω]] (scipy.linalg.expm; Moler & Van Loan 2003,
    # doi:10.1137/S00361445024180): exact to rounding (the Dormand–Prince pair on the whole right-hand side is held
    # within its stability interval, 3.3/ω_max: undamped, 51 129 steps and 7.9e-5 of c at rtol 1e-6, measured on the
    # pinned section; this one 263 steps and up to 8e-11 of c ω on the periodic section, whose highest mode turns
    # through 4 300 radians; the rigid translation ψ_0, ω = 0, is held still)
    from scipy.linalg import expm

    model = _clear_of_the_wall(paper_inputs, reference_damping="viscous" if ratio else "none", damping_ratio=ratio)
    N = model.n_modes
    c = float(np.min(model.clearance))
    rng = np.random.default_rng(7)
    z0 = np.zeros(4 * N + 4)
    z0[:2 * N] = 0.01 * c * rng.standard_normal(2 * N)
    z0[2 * N:4 * N] = 0.01 * c * np.tile(model.omega, 2) * rng.standard_normal(2 * N)  # the rigid translation's 0
    end = 20 * 2 * np.pi / model.omega[1]  # the first bending mode's (ψ_0, the rigid translation, has ω = 0)
    run = reference.Integrator(model, 1e-6, z0, "lawson")
    run.h = run.h_max = 30 * 2 * np.pi / model.omega[-1]
    run.run(end)
    assert run.outcome == whirl_kernel.OK
    # large steps: the error estimate is rounding (the steps shorter than h_max are the cap at a predicted onset)
    assert end / run.steps > 10 * 2 * np.pi / model.omega[-1]
    for m in range(N):
        flow = expm(end * np.array([[0.0, 1.0], [-model.omega[m] ** 2, -model.damping[m]]]))
        for j in range(2):
            exact = flow @ z0[[j * N + m, (2 + j) * N + m]]
            assert abs(run.z[j * N + m] - exact[0]) < 1e-10 * c
            assert abs(run.z[(2 + j) * N + m] - exact[1]) <= 1e-10 * c * max(model.omega[m], model.omega[1])


@pytest.mark.parametrize("scheme", ["lawson", "dopri5"])
def test_a_forced_oscillator_converges_at_fifth_order(paper_inputs, scheme):
    # the unbalance response with a side load from the forced state (reference.initial_state): the Jeffcott whirl
    # Re(Q_n e^{iΩt}), Q_n = ε_n/(ω_n² − Ω² + iΩ d_n), plus the static sag s_n/ω_n² is the exact solution (Vance 1988
    # eq. 2.11-2.12); at fixed steps (rtol too loose to reject, steps at h_max) its error over one revolution falls
    # as h^5 (Hairer, Nørsett & Wanner 1993 §II.5; Hochbruck & Ostermann 2010 §2.4 for the Lawson form)
    model = _forced(paper_inputs)
    N = model.n_modes
    Q = model.eccentric / (model.omega**2 - model.rotary_speed**2 + 1j * model.rotary_speed * model.damping)
    z0 = np.concatenate((Q.real + _static(model), Q.imag, (1j * model.rotary_speed * Q).real,
                         (1j * model.rotary_speed * Q).imag, np.zeros(4)))
    end = model.period
    phase = np.exp(1j * model.rotary_speed * end)
    exact = np.concatenate(((Q * phase).real + _static(model), (Q * phase).imag,
                            (1j * model.rotary_speed * Q * phase).real, (1j * model.rotary_speed * Q * phase).imag))
    scale = np.concatenate((np.full(2 * N, np.max(np.abs(Q))), np.full(2 * N, model.rotary_speed * np.max(np.abs(Q)))))
    errors = []
    steps = [12, 24, 48]
    for count in steps:
        run = reference.Integrator(model, 1e10, z0, scheme)
        run.h = run.h_max = end / count
        run.h_stable = run.h_max
        run.run(end)
        assert run.outcome == whirl_kernel.OK and abs(run.steps - count) <= 1
        errors.append(np.max(np.abs(run.z[:4 * N] - exact) / scale))
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(orders > 4.6) and np.all(orders < 5.6), (errors, orders)


def test_a_flights_rows_come_from_the_lawson_steps_continuous_extension(paper_inputs):
    # a Lawson step in flight is longer than the rows' spacing (τ/256): its rows are taken at their times from the
    # step's continuous extension (4th order; Hairer, Nørsett & Wanner 1993 §II.6) mapped by e^{θhL}, here within
    # 1e-6 of the forced response's size from the exact Jeffcott whirl plus sag (as above) at rtol 1e-6
    model = _forced(paper_inputs)
    N = model.n_modes
    om = model.rotary_speed
    Q = model.eccentric / (model.omega**2 - om**2 + 1j * om * model.damping)
    z0 = np.concatenate((Q.real + _static(model), Q.imag, (1j * om * Q).real, (1j * om * Q).imag, np.zeros(4)))
    run = reference.Integrator(model, 1e-6, z0, "lawson-flight")
    window = run.run(2 * model.period, record=True)
    assert window.times.size > 3 * run.steps  # several rows a step (its steps are at h_max, τ/64)
    np.testing.assert_allclose(np.diff(window.times), model.period / 256, rtol=1e-9)
    phase = np.exp(1j * om * window.times)[:, None]
    exact = np.hstack(((Q * phase).real + _static(model), (Q * phase).imag, (1j * om * Q * phase).real,
                       (1j * om * Q * phase).imag))
    size = np.max(np.abs(Q))
    assert np.max(np.abs(window.states[:, :2 * N] - exact[:, :2 * N])) < 1e-6 * size
    assert np.max(np.abs(window.states[:, 2 * N:4 * N] - exact[:, 2 * N:])) < 1e-6 * om * size
    assert np.all(window.forces == 0.0)


def _kernels_of(function, seen=None):
    """The numba kernels of whirl_kernel that ``function`` calls, directly or through the kernels inlined into it:
    {name: (dispatcher, inlined at numba's level)}."""
    import numba.core.registry

    seen = {} if seen is None else seen
    for name in function.py_func.__code__.co_names:
        callee = getattr(whirl_kernel, name, None)
        if isinstance(callee, numba.core.registry.CPUDispatcher) and name not in seen:
            seen[name] = (callee, callee.targetoptions.get("inline") == "always")
            if seen[name][1]:
                _kernels_of(callee, seen)
    return seen


#: numpy functions numba lowers in place on scalars (no compiled helper linked into the caller)
IN_PLACE = {"sqrt", "cos", "sin", "exp", "cosh", "sinh", "isfinite"}


def test_the_licensed_integrator_links_no_compiled_code():
    # docs/reference_model.md §6: advance runs under a floating-point licence (whirl_kernel.FASTMATH), and its bits are
    # its own only if nothing compiled apart is linked into it: a separately compiled kernel, and equally numba's own
    # helpers — the power operator's, an allocation's, a slice assignment's shape check — which a process compiles
    # once, with the licence of the first kernel that needs them, and LLVM then inlines. Measured: the 40 points of
    # configs/dense.toml answered differently after `study compile` (other kernels compiled first) than alone, until
    # advance's ``x ** 2`` became ``x * x``; then one answer after five compilation orders.
    assert whirl_kernel.advance.targetoptions["fastmath"] == whirl_kernel.FASTMATH
    kernels = _kernels_of(whirl_kernel.advance)
    assert {"rhs", "_step", "_lawson_step", "_switch_fraction", "point_state"} <= set(kernels)  # the walk sees them
    assert [name for name, (_, inlined) in kernels.items() if not inlined] == []
    found = []
    for name, dispatcher in [("advance", whirl_kernel.advance)] + [(n, d) for n, (d, _) in kernels.items()]:
        tree = ast.parse(textwrap.dedent(inspect.getsource(dispatcher.py_func)))
        for node in ast.walk(tree):
            if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Pow) and not _float_power(node):
                found.append(f"{name}: ** {ast.unparse(node.right)}")
            if (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
                    and isinstance(node.func.value, ast.Name) and node.func.value.id == "np"
                    and node.func.attr not in IN_PLACE):
                found.append(f"{name}: np.{node.func.attr}")
            if isinstance(node, (ast.Assign, ast.AugAssign)):
                targets = node.targets if isinstance(node, ast.Assign) else [node.target]
                for target in targets:
                    if isinstance(target, ast.Subscript) and any(isinstance(n, ast.Slice) for n in ast.walk(target)):
                        found.append(f"{name}: slice assignment {ast.unparse(target)}")
    assert found == []


def _float_power(node) -> bool:
    """A power with a negative or fractional exponent (``err ** -0.2``), which numba lowers to LLVM's pow in place;
    integer powers it compiles apart (docs/reference_model.md §6)."""
    exponent = node.right
    if isinstance(exponent, ast.UnaryOp) and isinstance(exponent.op, ast.USub):
        exponent = exponent.operand
    return not (isinstance(exponent, ast.Constant) and isinstance(exponent.value, int))


#: The state of the default study's point 275 rpm, 10 000 lbf, e 0.3, 12 ppg, 7.4 ft/s in its straight hole at the start
#: of its 16th revolution (16 modes; the kernel's z, 4N + 4), as the kernel before ENDING_RETRIES reached it: from here
#: that kernel cut one step sixty times at the end of joint 0's Hunt–Crossley force (χ = 3 087 s/m, a contact opened at
#: the floor speed) and stopped with a step size underflow, the point's status `failed` in the sweep.
_UNDERFLOW_STATE = [
    0.0450629838402261, -0.0009986435631962986, -0.0009607892411994583, -0.00023922740273470112,
    -2.2781960374612874e-05, 0.002098210839406523, -0.00020623651699342953, -0.000365364651814905,
    -9.041959066270116e-07, -6.040155364660877e-05, -4.362821911151596e-05, 6.473243169261695e-05,
    -1.0839254454433593e-06, 3.2508291914765026e-05, -1.13770332985183e-05, -1.6274151798825273e-05,
    -0.012806902582295464, 0.001462612666542041, -0.0016296063470905592, -0.0003641362947490351,
    -1.0183506319202482e-05, 0.002124763020157557, 0.001370615781245545, -4.784101573865506e-05,
    -9.998553855839348e-07, -1.717062972686166e-05, 5.9839121965332664e-05, 4.185035872729976e-05,
    -1.8527263714875478e-08, 2.6088408940708866e-05, -2.391697177930349e-06, -1.7553238050437214e-05,
    -0.008109320095972278, -0.020540615419324587, 0.029601147019462606, 0.007526826234945227,
    2.6418995695687542e-05, 0.006026060265286576, 0.053706571806734105, 0.010947797093026965,
    -3.495727099961513e-05, -0.0019128871335568512, -0.006694237900006968, 0.007791324185003127,
    -6.315537056113271e-05, 0.010480037864056952, -0.0025476190772596814, 0.0006371593842193438,
    -0.003359297126005958, -0.027869335044119554, -0.03117526641487012, 0.0015259792799999735,
    1.4115968188509933e-05, -0.036055676152571284, 0.06097554621061754, 0.0021996660969045216,
    -0.00017852615502575005, 0.00011031709451189518, 4.544184987790025e-05, 0.00034663831312575837,
    -2.8436816952442365e-05, -0.00046455593714676797, -0.001960061153292098, -0.0009115619272122138,
    70.4051380988842, -34.25422098593256, 8.434819998868337, 15.141756393838135,
]
_UNDERFLOW_CHI = [0.0, 0.0, 1009.5928932004227, 0.0, 328.5047728803065, 0.0, 102.21929263301607, 0.0]
_UNDERFLOW_T, _UNDERFLOW_H = 3.272727272727273, 0.0010887902175439278


def test_the_end_of_a_stiff_hunt_crossley_force_is_located_to_what_the_steps_resolve():
    # whirl_kernel.ENDING_RETRIES: the bracket 1 + χ δ̇ of a contact opened at the floor speed moves by χ = 3 087 s/m
    # times the rate's error, and the steps resolve the rate to about rtol Ω c, not the 3e-10 m/s that ONSET_TOLERANCE
    # of the bracket asks: the continuous extension put the end a little late at every cut (the step's end 5e-5 past
    # it after each), each cut shortened the step by 0.01-0.1 % and the sixty attempts ran out (step size underflow,
    # reproduced by the kernel as it was, from this state). Located after two cuts within ONSET_TOLERANCE of Ω c_p in
    # the rate, the revolution ends, and the force ended where its bracket is within that of nil
    from pathlib import Path

    from study import config

    root = Path(__file__).resolve().parents[2]
    point = config.load(root / "configs" / "default.toml", {
        "load.rotary_speed": "275 rpm", "load.axial_tension": "10000 lbf", "impact.restitution": 0.3,
        "mud.density": "12 ppg", "mud.flow_velocity": "7.4 ft/s", "hole.dogleg_severity": "0 deg/100ft"}).point()
    model = reference.build_model(point)
    assert model.n_modes == 16 and model.points.size == 8
    run = reference.Integrator(model, 1e-6, np.zeros(4 * model.n_modes + 4))
    run.z[:] = _UNDERFLOW_STATE
    run.chi[:] = _UNDERFLOW_CHI
    run.active[:] = run.chi > 0
    run.t, run.h = _UNDERFLOW_T, _UNDERFLOW_H
    run.run(16 * model.period)
    assert run.outcome == whirl_kernel.OK, whirl_kernel.OUTCOMES[run.outcome]
    assert run.t == pytest.approx(16 * model.period, rel=1e-12)
    assert whirl_kernel.ENDING_RETRIES < 60
