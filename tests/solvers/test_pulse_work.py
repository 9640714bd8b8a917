"""The strikes' pulses scaled to the local strike's net work (``reference_pulse_work = "matched"``;
study.solvers.kernels.pulse.matched_scale; docs/reference_model.md §2.4)."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from study.physics import strike
from study.physics.contact import calibrated_hysteresis
from study.solvers.kernels import pulse
from study.solvers.model import options

# the default study's joint and pipe (tests/physics/test_strike.py): m_j [kg], the joints' Hertz K, ρA [kg/m], EI
JOINT, K, RHO, EI = 45.117, 6.289e11, 49.346, 827410.0
H = calibrated_hysteresis(0.7)


def test_the_option_is_opt_in_and_validated_naming_the_field():
    assert options.ReferenceOptions.default("reference_pulse_work") == "local"
    with pytest.raises(ValueError, match="reference_pulse_work = 'energy'; allowed: local, matched, mobility"):
        options.ReferenceOptions.from_inputs({"reference_pulse_work": "energy"})


def test_without_the_beam_the_local_loss_is_the_restitutions():
    # ρA → 0 (the beam gives nothing): the joint alone on the Hunt–Crossley Hertz wall, calibrated to rebound at e, so
    # the wall takes ½ m v0² (1 − e²) (contact.calibrated_hysteresis's definition of e); the table's ∫F dδ
    table = strike.strike_pulse_table(JOINT, K, 1e-6, EI, H)
    for i in (4, 8, 12):  # 10 mm/s, 0.1 m/s, 1 m/s
        v = table["speeds"][i]
        assert table["ended"][i]
        assert table["loss"][i] == pytest.approx(0.5 * JOINT * v**2 * (1 - 0.7**2), rel=5e-3), v


def _kernel_pulse(speed, modal_mass, state, omega):
    """One mode (φ = 1, modal mass m, ω) whose point is at y = state[0] moving at state[2]: the pulse of the default
    joint's local strike at ``speed`` started there (start_strike), scaled by matched_scale; its state row, spline
    coefficients (1, S, 4, G − 1), the table and the scale."""
    table = strike.strike_pulse_table(JOINT, K, RHO, EI, H)
    pst = np.zeros((1, pulse.N_PULSE_STATE))
    logv = np.log(table["speeds"])
    assert pulse.start_strike(0, 0.0, speed, pst, np.zeros(1), logv, np.log(table["peak"])[None],
                              np.log(table["duration"])[None], np.full(1, K))
    coef = np.ascontiguousarray(table["coefficients"][None])
    z = np.asarray(state, float)
    lam = pulse.matched_scale(z, np.ones((1, 1)), np.array([omega**2]), 1.0 / modal_mass, 0, 1, pst, coef,
                              np.log(table["loss"])[None], np.zeros(coef.shape[3] + 1))
    return pst, coef, table, lam


def test_a_free_masss_matched_pulse_leaves_it_with_the_local_strikes_energy():
    # a free mass m_eff (ω = 0) at v0: W = −F̂ v0 J₁ + F̂² J₁²/2m is −loss at the larger root, where the mass leaves at
    # −√(v0² − 2 loss/m) (closed form: its energy after the wall took the local strike's loss, rebounding)
    v0, m = 0.2, 74.0
    pst, coef, table, lam = _kernel_pulse(v0, m, [0.05, 0.0, v0, 0.0], 0.0)
    s = np.linspace(0.0, 1.0, coef.shape[3] + 1)
    shape = np.array([pulse.pulse_force(x * pst[0, pulse.P_DURATION], pst, coef, 0) for x in s]) / pst[0, pulse.P_PEAK]
    j1 = np.trapezoid(shape, s * pst[0, pulse.P_DURATION])
    loss = np.exp(np.interp(np.log(v0), np.log(table["speeds"]), np.log(table["loss"])))
    after = v0 - lam * pst[0, pulse.P_PEAK] * j1 / m
    assert after == pytest.approx(-np.sqrt(v0**2 - 2 * loss / m), rel=1e-3)
    assert lam > 1.0  # a mass heavier than the local joint-and-beam needs more impulse to rebound so
    # "mobility" takes the free motion as the local model's steady approach at the onset speed: a free mass's own
    steady = pulse.matched_scale(np.array([0.05, 0.0, v0, 0.0]), np.ones((1, 1)), np.zeros(1), 1.0 / m, 0, 1,
                                 pst.copy(), coef, np.log(table["loss"])[None], np.zeros(coef.shape[3] + 1), True)
    assert steady == pytest.approx(lam, rel=1e-12)


@pytest.mark.parametrize("hz", [0.0, 200.0, 565.0])
def test_an_oscillators_matched_pulse_does_the_local_strikes_work(hz):
    # one mode (m = 74 kg, the default joint's kept modes' mass m/Σφ² at 64 modes, 292's; 0-565 Hz, the top kept mode
    # there) struck at 0.2 m/s from its rest: the scaled pulse's force (pulse_force, the spline the kernel applies)
    # integrated with the mode (scipy DOP853, rtol 1e-10); the work it did, the mode's energy change, against the local
    # model's −∫F dδ at that speed (strike.strike_pulse_table). Measured 0.003-0.05 % apart (λ 1.25, 1.21, 0.90): the
    # trapezoidal rule of matched_scale on the 65 knots against the spline's integral. (A mode far above 1/T_c,
    # 1500 Hz, turns back under the pulse: its free motion leaves the wall, no amplitude takes the loss, and the pulse
    # keeps its table's size)
    v0, m, omega = 0.2, 74.0, 2 * np.pi * hz
    y0 = 0.0  # the onset at the mode's rest: the point's offset is the slow modes'
    pst, coef, table, lam = _kernel_pulse(v0, m, [y0, 0.0, v0, 0.0], omega)
    pst[0, pulse.P_PEAK] *= lam
    T = pst[0, pulse.P_DURATION]

    def rhs(t, u):
        return [u[1], -omega**2 * u[0] - pulse.pulse_force(t, pst, coef, 0) / m]

    sol = solve_ivp(rhs, (0.0, T), [y0, v0], method="DOP853", rtol=1e-10, atol=1e-14, max_step=T / 400)
    energy = 0.5 * m * (sol.y[1] ** 2 + omega**2 * sol.y[0] ** 2)
    loss = np.exp(np.interp(np.log(v0), np.log(table["speeds"]), np.log(table["loss"])))
    assert energy[-1] - energy[0] == pytest.approx(-loss, rel=2e-3), lam
    assert sol.y[1, -1] < 0.0  # the point leaves the wall, as the local joint does
