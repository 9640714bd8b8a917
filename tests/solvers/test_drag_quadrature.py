"""The rule the reference model sums the mud's quadratic drag by along the section (``reference_drag_quadrature``,
``reference.model.drag_quadrature``; docs/reference_model.md §4, §6): Gauss–Legendre at 2N + 8 points (the default)
or the periodic midpoint rule at 3N/2 + 8 points; and the precision of the integrator's sums
(``reference_drag_precision``): double (the default) or single."""

from pathlib import Path

import numpy as np
import pytest

from study.benchmarks.reference import fixed_window
from study.config import load
from study.physics.string_modes import mode_shapes
from study.solvers.kernels import whirl_kernel
from study.solvers.methods import reference
from study.solvers.methods.reference.model import drag_quadrature

ROOT = Path(__file__).resolve().parents[2]
L = 93 * 0.3048  # the default section: three 31-ft joints [m]


def exponentials(n):
    """Basis function n of :func:`mode_shapes` as {harmonic h: coefficient of e^{2πi h x/L}}: ψ_0 = 1/√2,
    ψ_{2j−1} = cos k_j x = (e^{ik_j x} + e^{−ik_j x})/2, ψ_{2j} = sin k_j x = (e^{ik_j x} − e^{−ik_j x})/2i
    (k_j = 2πj/L)."""
    if n == 0:
        return {0: 1 / np.sqrt(2)}
    j = (n + 1) // 2
    return {j: 0.5, -j: 0.5} if n % 2 == 1 else {j: -0.5j, -j: 0.5j}


def triple_integral(a, b, c):
    """∫₀ᴸ ψ_a ψ_b ψ_c dx in closed form: L times the sum of the coefficients' products whose harmonics add to
    0 (∫₀ᴸ e^{2πi h x/L} dx = L δ_h0)."""
    total = 0.0
    for ha, ca in exponentials(a).items():
        for hb, cb in exponentials(b).items():
            for hc, cc in exponentials(c).items():
                if ha + hb + hc == 0:
                    total += ca * cb * cc
    return L * float(np.real(total))


@pytest.mark.parametrize("modes", [9, 16])
def test_the_uniform_rule_integrates_products_of_three_basis_functions_exactly(modes):
    # harmonics up to 3N/2 < G = 3N/2 + 8: the trapezoidal rule of a period is exact on them (Trefethen & Weideman
    # 2014, doi:10.1137/130932132), to rounding (measured 4e-16 L and 1e-15 L); Gauss–Legendre at 2N + 8 points is not
    # (its largest error measured 8.6e-6 L and 1.4e-2 L at 9 and 16 modes)
    errors = {}
    for rule in ("uniform", "gauss"):
        x, w = drag_quadrature(L, modes, rule)
        psi = mode_shapes(x, L, modes)
        errors[rule] = max(abs(np.sum(w * psi[:, a] * psi[:, b] * psi[:, c]) - triple_integral(a, b, c))
                           for a in range(modes) for b in range(a, modes) for c in range(b, modes))
    assert errors["uniform"] < 1e-13 * L
    assert errors["gauss"] > 1e3 * errors["uniform"]


def drag_forces(model, x, w, vy, vz):
    """(2N,) the modal drag forces Σ_g w_g S_gn D |u̇_g| u̇_g [N] (docs/reference_model.md §1) by the rule
    (x, w)."""
    S = model.shapes(x)
    uy, uz = S @ vy, S @ vz
    speed = np.hypot(uy, uz)
    return np.concatenate((S.T @ (w * model.drag * speed * uy), S.T @ (w * model.drag * speed * uz)))


@pytest.mark.parametrize("modes", [16, 64])
def test_the_uniform_rule_sums_the_drag_closer_to_its_integral_than_gauss_legendre(modes):
    # the default study's model (the joints' modes) and 20 random velocity fields with a 1/n spectrum, against
    # Gauss–Legendre at 8N points (converged: 16N points move it by 2.8e-6 and 2.3e-7 of the force). Measured: uniform
    # at most 1.8e-3 and 6.0e-4 of the force, a median 1.9e-4 and 7.6e-5; Gauss–Legendre's median 4.0e-4 and 3.8e-4
    point = load(ROOT / "configs" / "default.toml").point()
    model = reference.build_model({**point, "reference_modes": modes, "reference_max_modes": modes})
    fine = drag_quadrature(model.span, 8 * modes, "gauss")
    rules = {rule: drag_quadrature(model.span, modes, rule) for rule in ("uniform", "gauss")}
    rng = np.random.default_rng(7)
    errors = {rule: [] for rule in rules}
    for _ in range(20):
        amplitude = 1.0 / np.maximum(np.arange(modes), 1.0)
        vy, vz = rng.standard_normal(modes) * amplitude, rng.standard_normal(modes) * amplitude
        exact = drag_forces(model, *fine, vy, vz)
        for rule, (x, w) in rules.items():
            errors[rule].append(np.linalg.norm(drag_forces(model, x, w, vy, vz) - exact) / np.linalg.norm(exact))
    assert max(errors["uniform"]) < 2.5e-3
    assert np.median(errors["uniform"]) < np.median(errors["gauss"])


@pytest.mark.parametrize("options", [{"reference_drag_quadrature": "uniform"}])
def test_the_cheaper_drag_leaves_a_thrown_strings_figures_within_half_a_percent(options):
    # the deterministic window of study.benchmarks.reference.fixed_window (the string thrown rigidly at 0.3 m/s onto
    # its joints' wall, a quarter revolution: no chaos, the same start) at 16 modes: measured within 0.072 % (the max
    # normal stress, which moves as much with the drag in single precision alone, a change of 3e-7 of the drag: the
    # window's largest stress is that sensitive), the peak force within 1.1e-5, the same 11 onsets. The single
    # precision is held here at the right-hand side (the test below): run through the integrator it compiles a second
    # integrator (3 minutes of the suite's CPU) for the same arithmetic; measured so with both options, 0.072 %
    point = load(ROOT / "configs" / "default.toml").point()
    inputs = {**point, "reference_modes": 16, "reference_max_modes": 16}
    default = fixed_window(inputs, 0.25)
    cheaper = fixed_window({**inputs, **options}, 0.25)
    assert cheaper["onsets"] == default["onsets"]
    for name in ("peak_contact_force", "max_normal_stress", "alternating_bending_stress", "max_deflection"):
        assert cheaper[name] == pytest.approx(default[name], rel=5e-3), name


@pytest.mark.parametrize("rule", ["gauss", "uniform"])
def test_the_drag_summed_in_single_precision_is_the_doubles_to_a_millionth(rule, kernel_drag):
    # the integrator's right-hand side with the drag and without it (its drag part) at 20 random states with a 1/n
    # spectrum of the default study's model at 16 modes: float32 sums round at 6e-8 a term; measured at most 4.2e-7
    # of the drag force and 2.3e-7 of its power over a revolution of the bouncing point 292 at 64 and 128 modes
    point = load(ROOT / "configs" / "default.toml").point()
    inputs = {**point, "reference_modes": 16, "reference_max_modes": 16, "reference_drag_quadrature": rule}
    systems = {precision: reference.Integrator(reference.build_model({**inputs, "reference_drag_precision": precision}),
                                               1e-6).sy for precision in ("double", "single")}
    assert systems["single"][4].dtype == np.float32 and systems["double"][4].dtype == np.float64
    N = 16
    rng = np.random.default_rng(3)

    for _ in range(20):
        z = np.zeros(4 * N + 4)
        z[2 * N:4 * N] = rng.standard_normal(2 * N) * np.tile(1.0 / np.maximum(np.arange(N), 1.0), 2)
        (force, power), (single, single_power) = kernel_drag(systems["double"], z), kernel_drag(systems["single"], z)
        assert np.linalg.norm(single - force) < 1e-6 * np.linalg.norm(force)
        assert single_power == pytest.approx(power, rel=1e-6)


def test_the_default_rule_is_gauss_legendre_at_2n_plus_8_points_and_a_bad_rule_is_named():
    point = load(ROOT / "configs" / "default.toml").point()
    model = reference.build_model({**point, "reference_modes": 16, "reference_max_modes": 16})
    x, w = drag_quadrature(model.span, 16, "gauss")
    nodes, weights = np.polynomial.legendre.leggauss(40)
    assert np.array_equal(model.drag_weights, w) and np.array_equal(model.drag_shapes, model.shapes(x))
    np.testing.assert_allclose(x, 0.5 * model.span * (nodes + 1), rtol=0, atol=1e-14 * model.span)
    np.testing.assert_allclose(w, 0.5 * model.span * weights, rtol=1e-14)
    uniform = reference.build_model({**point, "reference_modes": 16, "reference_drag_quadrature": "uniform"})
    assert uniform.drag_weights.size == 32 and np.allclose(uniform.drag_weights, uniform.span / 32)
    with pytest.raises(ValueError, match="reference_drag_quadrature = 'simpson'; allowed: gauss, uniform"):
        reference.build_model({**point, "reference_drag_quadrature": "simpson"})
    with pytest.raises(ValueError, match="reference_drag_quadrature = 'simpson'; allowed: gauss, uniform"):
        drag_quadrature(L, 16, "simpson")
