"""The ``damped`` method: the paper's damped periodic solution (appendices A and B; docs/model.md §7.1).

The mud's drag is kept, linearised by equal dissipation over the span and the period into a uniform viscous
term c ẏ (:func:`study.physics.damping.equivalent_damping`, paper eq. A3–A4), and the energy it takes is fed
back by moments M_e(t) at both ends of the span, one amplitude per harmonic of the motion, in quadrature with
the load's harmonic and sized so that the displacement the impact load works on is in phase with it
(:func:`study.physics.damping.in_phase_moments`, paper eq. A14). The impact load then does no net work over
a period and the end moments do exactly what the damping dissipates (appendix B).

Everything else is the undamped solution's (:mod:`study.solvers.methods.periodic`, docs/model.md §3–5): the same
closures, Lee's pulse at the T_L–κ–b fixed point, condition 1, the same grids and stresses. The field is the
undamped closed form (:func:`study.physics.beam.periodic_fields`, exact in time, with the quasi-static
correction) plus a harmonic series of what damping and end moments change (docs/model.md eq. 7.5), whose
terms fall like ω_m⁻⁴: modal transfer H_nm = 1/(ω_n² − ω_m² + i ω_m c/M) against the undamped one, and the
end moments' static shape in closed form (:func:`study.physics.damping.end_moment_static`) with a modal
dynamic remainder.

Span search (docs/model.md §7.1): with damping the response has no poles, so every root of the damped
condition 2 is continued from a root of the undamped one — the undamped search's roots that pass its
midspan screen (:func:`study.solvers.methods.periodic.span_search.find_roots`), refined by secant steps on the damped
residual in ascending order until one satisfies condition 1. The first is reported (a root the damping creates away
from every undamped root is not searched). The damping c starts from the paper's assumed motion
y = c sin(πx/L) sin Ωt and is iterated with the solution's own velocity field at the chosen span, the span
following it, until c changes by less than ``damping_tolerance`` (status ``not_converged`` otherwise).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

from study.physics import beam, damping, fourier, hertz, midspan
from study.solvers.kernels import extremes
from study.solvers.kernels import impact as impact_model
from study.solvers.methods.periodic import span_search
from study.solvers.methods import periodic
from study.solvers.model.options import DampedOptions, Options, study_tolerance
from study.solvers.model.result import PointResult
from study.solvers.model.point import DesignPoint
from study.solvers.model.scene import Scene

METHOD = "damped"
#: Most secant steps of the damped residual from one undamped root.
SECANT_STEPS = 12
#: |F| below which a damped root is refined.
ROOT_TOL = 1e-9
#: Why a secant left its interval: around an undamped root, or between two samples of :func:`scan` (no root
#: there: the residual changed sign across a pole of the in-phase moments).
LEFT = "the damped root left its interval"


@dataclass
class Spectrum:
    """What damping and end moments add to the undamped periodic response of one span, per unit impulse along
    +y, harmonic by harmonic (docs/model.md §7.1)."""

    span: float
    damping: float  #: c [N s/m²]
    modes: np.ndarray  #: odd n
    k: np.ndarray  #: k_n [1/m]
    parity: np.ndarray  #: sin(nπ/2)
    frequency: np.ndarray  #: ω_m [rad/s] of the kept harmonics
    coef: np.ndarray  #: one-sided train coefficients [1/s] (complex)
    transfer: np.ndarray  #: H_nm damped (harmonics × modes)
    load: np.ndarray  #: a_n = g_n/(M L/2) [1/kg]: the load's modal forcing per unit force
    moment_factors: np.ndarray  #: e_n = 4 k_n/(M L) [1/(kg m)]: the end moments' per unit moment
    moments: np.ndarray  #: μ_m [m]: the end moment's harmonic is i μ_m c_m per unit impulse
    dynamic: np.ndarray  #: z_nm: modal remainder of the end moments' response over their static shape
    correction: np.ndarray  #: modal amplitude added to the undamped one, without the static shape
    static: tuple  #: (s, m_s, s') of the end-moment static shape at (mid, mid, end): (L/2, L/2, 0)
    props: Mapping[str, float]

    @property
    def total(self) -> np.ndarray:
        """Full modal amplitudes q_nm = (a_n + i μ_m e_n) H_nm (harmonics × modes)."""
        return damping.compensated_amplitudes(self.load, self.moment_factors, self.transfer, self.moments)


def spectrum(scene: Scene, span: float, duration: float, half: float, c: float, options: Options,
             harmonics: int) -> Spectrum:
    """The :class:`Spectrum` of a span L [m] with Lee's pulse of T_L [s] over b [m] and damping c [N s/m²]."""
    p = scene.props
    ei, tn, mass = p["bending_stiffness"], p["effective_tension"], p["mass_per_length"]
    n = impact_model.odd_modes(options.modes)
    k = n * np.pi / span
    om_n = np.sqrt((ei * k**2 + tn) * k**2 / mass)
    g = beam.modal_load_factors(n, span, half, options.load_shape).reshape(-1)
    load = g / (0.5 * mass * span)
    e = damping.end_moment_modal_factors(n, span, mass)
    m = fourier.harmonic_numbers(harmonics, scene.pattern)
    om = m * scene.rotary_speed
    coef = fourier.train_coefficients(m, duration, scene.period, scene.pattern)
    rate = c / mass
    h = damping.modal_transfer(om_n[None, :], om[:, None], rate)
    with np.errstate(divide="ignore", invalid="ignore"):
        undamped = 1.0 / (om_n[None, :] ** 2 - om[:, None] ** 2)
        mu = damping.in_phase_moments(load, e, h, g) if c > 0 else np.zeros(m.size)
    s_n = e / om_n**2  # sine coefficients of the end moments' static shape
    dynamic = s_n[None, :] * (om[:, None] ** 2 - 1j * om[:, None] * rate) * h  # its modal remainder
    correction = load[None, :] * (h - undamped) + 1j * mu[:, None] * dynamic
    s, ms, _ = damping.end_moment_static(np.array([0.5 * span]), span, ei, tn)
    slope = damping.end_moment_static(np.array([0.0]), span, ei, tn)[2]
    parity = np.where(n % 4 == 1, 1.0, -1.0)
    return Spectrum(span, c, n, k, parity, om, coef, h, load, e, mu, dynamic, correction,
                    (float(s[0]), float(ms[0]), float(slope[0])), p)


def midspan_correction(spec: Spectrum) -> tuple[float, float, float]:
    """(Δy₁ [m/(N s)], Δv₁, Δ(−y₁'')) at midspan at the start of the pulse, per unit impulse along +y: what
    damping and end moments add to :func:`study.physics.midspan.midspan_state_at_pulse_start`."""
    s_mid, ms_mid, _ = spec.static
    ei = spec.props["bending_stiffness"]
    moment = 1j * spec.moments * spec.coef
    y = spec.coef * _dot(spec.correction, spec.parity) + moment * s_mid
    curv = spec.coef * _dot(spec.correction, spec.parity * spec.k**2) + moment * ms_mid / ei
    return float(y.real.sum()), float((1j * spec.frequency * y).real.sum()), float(curv.real.sum())


def correction_fields(spec: Spectrum, x, t, kinds) -> dict[str, np.ndarray]:
    """What damping and end moments add to the undamped fields per unit impulse along +y, shape t × x:
    "deflection" y [m/(N s)], "velocity" ẏ [m/(N s²)], "moment" −EI y'' [1/s], "shear" −EI y''' [1/(m s)]."""
    x, t = np.asarray(x, dtype=float), np.asarray(t, dtype=float)
    ei, tn = spec.props["bending_stiffness"], spec.props["effective_tension"]
    s, ms, slope = damping.end_moment_static(x, spec.span, ei, tn)
    kx = np.outer(spec.k, x.ravel())
    e = np.exp(1j * np.outer(t.ravel(), spec.frequency))
    moment = 1j * spec.moments * spec.coef
    amp = spec.coef[:, None] * spec.correction
    lam = tn / ei  # m_s'' = lam m_s: −EI s''' = m_s'
    ms_prime = _moment_slope(x, spec.span, lam)
    out = {}
    for kind in kinds:
        if kind in ("deflection", "velocity"):
            field = _dot(amp, np.sin(kx)) + moment[:, None] * s.ravel()[None, :]
            if kind == "velocity":
                field = field * (1j * spec.frequency)[:, None]
        elif kind == "moment":
            field = _dot(amp, ei * spec.k[:, None] ** 2 * np.sin(kx)) + moment[:, None] * ms.ravel()[None, :]
        elif kind == "shear":
            field = _dot(amp, ei * spec.k[:, None] ** 3 * np.cos(kx)) + moment[:, None] * ms_prime.ravel()[None, :]
        else:
            raise ValueError(f"kind = {kind!r}; allowed: deflection, velocity, moment, shear")
        out[kind] = (e @ field).real.reshape(t.shape + x.shape)
    return out


def _dot(a, b):
    """a @ b for complex a and real b (a vector or a matrix), as two real products: BLAS's complex products of
    these small sizes cost more in thread wake-ups than they compute."""
    b = np.asarray(b, dtype=float)
    if b.ndim == 1:
        return (a * b).sum(axis=-1)
    return a.real @ b + 1j * (a.imag @ b)


def _moment_slope(x, span, lam):
    """m_s' [1/m] of :func:`damping.end_moment_static` (m_s'' = lam m_s, lam = T/EI)."""
    xi = np.asarray(x, dtype=float) - 0.5 * span
    half = 0.5 * span * math.sqrt(abs(lam))
    if half < 1e-4:
        return np.zeros_like(xi)
    k = math.sqrt(abs(lam))
    if lam > 0:
        return k * np.sinh(k * xi) / math.cosh(half)
    return -k * np.sin(k * xi) / math.cos(half)


def fields(scene: Scene, impact: impact_model.Impact, spec: Spectrum, options: Options, x, t, kinds) -> dict:
    """The damped fields at this span and impact (the real load −J): undamped closed form + correction."""
    p = scene.props
    base = [k for k in kinds if k != "velocity"]
    out = beam.periodic_fields(x, t, base, impact.span_length, p["bending_stiffness"], p["effective_tension"],
                               p["mass_per_length"], -impact.impulse, impact.contact_duration, scene.period,
                               scene.pattern, impact.contact_half_length, options.load_shape, options.modes) \
        if base else {}
    extra = correction_fields(spec, x, t, kinds)
    for kind in kinds:
        out[kind] = (out[kind] if kind in out else 0.0) - impact.impulse * extra[kind]
    return out


def velocity_field(spec: Spectrum, impulse: float, x, t) -> np.ndarray:
    """ẏ [m/s] of the whole damped motion (the real load −J) on x × t, from the full modal amplitudes."""
    amp = spec.coef[:, None] * spec.total * (1j * spec.frequency)[:, None]
    e = np.exp(1j * np.outer(np.asarray(t, dtype=float), spec.frequency))
    return -impulse * (e @ _dot(amp, np.sin(np.outer(spec.k, np.asarray(x, dtype=float))))).real


# --- the impact at one span ---------------------------------------------------------------------
@dataclass
class DampedImpact:
    """The impact of one span with damping (as :class:`impact_model.Impact`) and the spectrum it was solved with."""

    impact: impact_model.Impact
    spec: Spectrum | None


@functools.lru_cache(maxsize=1)
def _table():
    """The Hertz eccentricity's starting table (:func:`hertz.guess_table`), built once."""
    return hertz.guess_table()


def impact_at(scene: Scene, span: float, c: float, options: Options, harmonics: int, duration: float | None = None,
              half: float = 0.0, max_iterations: int = 60) -> DampedImpact:
    """The T_L–κ–b fixed point of one span with damping c (as :func:`impact_model.impact_at`, docs/model.md §3.6):
    the closure residual F(L) and the impact. Problems are named in ``impact.problems``."""
    p = scene.props
    m_e = float(scene.equivalent_mass(span))
    cl, table = scene.clearance, _table()
    radius, hole, compliance = scene.outer_radius, scene.hole_radius, scene.compliance_sum
    velocity = scene.rotary_speed * cl
    out = impact_model.Impact(span_length=span, residual=math.nan, equivalent_mass=m_e)
    if duration is None or not 0 < duration < scene.impact_interval:
        stiffness = hertz.contact_one(1.0, radius, hole, cl * (math.pi / span) ** 2, compliance, table)[2]
        duration = hertz.lee_duration_one(m_e, velocity, stiffness)
    half = min(max(half, 0.0), 0.45 * span)
    modes = impact_model.odd_modes(options.modes)
    spec = None
    # secant steps on map(T_L) − T_L, a relaxed fixed-point step (halved when it overshoots) where a secant
    # step is not usable — as impact_model.impact_at
    relaxation, last_step, previous, previous_step = 1.0, 0.0, math.nan, math.nan
    for iteration in range(1, max_iterations + 1):
        if not duration < scene.impact_interval:
            out.problems.append(f"pulse longer than the time between impacts (T_L = {duration:.3g} s)")
            return DampedImpact(out, spec)
        y1, v1, k1 = (float(v) for v in midspan.midspan_state_at_pulse_start(
            span, duration, half, modes, p["bending_stiffness"], p["effective_tension"], p["mass_per_length"],
            scene.period, scene.pattern, options.load_shape))
        spec = spectrum(scene, span, duration, half, c, options, harmonics)
        dy, dv, dk = midspan_correction(spec)
        y1, v1, k1 = y1 + dy, v1 + dv, k1 + dk
        if not all(map(math.isfinite, (y1, v1, k1))):
            out.problems.append("the span is at a resonance or buckled")
            return DampedImpact(out, spec)
        if scene.closure == "self_consistent":
            impulse, velocity = -cl / y1, cl * v1 / y1
            residual = m_e * (1.0 + scene.restitution) * velocity / impulse - 1.0
        else:
            impulse = m_e * (1.0 + scene.restitution) * velocity
            residual = -impulse * y1 / cl - 1.0
        curvature = impulse * k1
        out.residual, out.impulse, out.impact_velocity, out.axial_curvature = residual, impulse, velocity, curvature
        if not (curvature > 0 and velocity > 0 and impulse > 0):
            out.problems.append("the pipe is not convex towards the wall at the contact" if curvature <= 0 else
                                "the midspan does not approach the wall before contact" if velocity <= 0 else
                                "condition 2 needs a negative impulse")
            return DampedImpact(out, spec)
        peak = math.pi * impulse / (2.0 * duration)
        half, half_width, stiffness = hertz.contact_one(peak, radius, hole, curvature, compliance, table)
        half = min(half, 0.45 * span)
        mapped = hertz.lee_duration_one(m_e, velocity, stiffness)
        out.contact_duration, out.contact_half_length, out.contact_half_width = duration, half, half_width
        out.peak_contact_force, out.iterations = peak, iteration
        step = mapped - duration
        if abs(step) <= options.fixed_point_tol * mapped:
            elastic = hertz.hertz_impact(m_e, velocity, stiffness)
            out.hertz_duration, out.hertz_peak_force = float(elastic.duration), float(elastic.max_force)
            out.max_approach = float(elastic.max_approach)
            return DampedImpact(out, spec)
        if last_step * step < 0:
            relaxation *= 0.5
        last_step = step
        secant = math.nan
        if math.isfinite(previous) and step != previous_step:
            secant = duration - step * (duration - previous) / (step - previous_step)
        previous, previous_step = duration, step
        duration = secant if 0.0 < secant < scene.impact_interval else duration + relaxation * step
    out.problems.append(f"T_L–curvature iteration not converged in {max_iterations} steps")
    return DampedImpact(out, spec)


def refine(scene: Scene, span: float, bracket, c: float, options: Options, harmonics: int,
           duration: float | None = None, half: float = 0.0) -> DampedImpact:
    """The root of the damped residual F(L) nearest ``span`` [m] by secant steps kept inside ``bracket``."""
    lo, hi = min(bracket), max(bracket)
    x0 = span
    last = impact_at(scene, x0, c, options, harmonics, duration, half)
    if last.impact.problems:
        return last
    x1 = x0 * (1.0 + 1e-6) if hi - x0 > x0 - lo else x0 * (1.0 - 1e-6)
    here = impact_at(scene, x1, c, options, harmonics, last.impact.contact_duration, last.impact.contact_half_length)
    for _ in range(SECANT_STEPS):
        f0, f1 = last.impact.residual, here.impact.residual
        if here.impact.problems or abs(f1) < ROOT_TOL:
            return here
        if f1 == f0:
            break
        x2 = x1 - f1 * (x1 - x0) / (f1 - f0)
        if not lo < x2 < hi:
            here.impact.problems.append(LEFT)
            return here
        x0, last, x1 = x1, here, x2
        here = impact_at(scene, x1, c, options, harmonics, last.impact.contact_duration,
                         last.impact.contact_half_length)
    if not here.impact.problems and abs(here.impact.residual) > 1e-8:
        here.impact.problems.append(f"condition 2 residual {here.impact.residual:.2g} after refinement")
    return here


def violation(scene: Scene, found: DampedImpact, options: Options) -> str | None:
    """Condition 1 on the solver's grid with the damped fields (None: it holds; docs/model.md §4.3)."""
    impact = found.impact
    x = periodic.space_grid(impact.span_length, impact.contact_half_length, options)
    t = periodic.time_grid(scene, impact.contact_duration, options)
    y = fields(scene, impact, found.spec, options, x, t, ["deflection"])["deflection"]
    contact = ((np.abs(x - 0.5 * impact.span_length) <= max(impact.contact_half_length, 1e-9))[None, :]
               & (t <= impact.contact_duration)[:, None])
    excess = np.where(contact, 0.0, np.abs(y)) - scene.clearance * (1.0 + options.tolerance)
    if not np.all(np.isfinite(y)):
        return "the deflection is not finite (resonance)"
    if np.max(excess) > 0:
        i, j = np.unravel_index(np.argmax(excess), excess.shape)
        return f"|y| reaches {abs(y[i, j]) / scene.clearance:.4g} c at x = {x[j]:.4g} m, t = {t[i]:.4g} s (condition 1)"
    return None


# --- energy -------------------------------------------------------------------------------------
def energy_grid(scene: Scene, spec: Spectrum):
    """(x, t, weights): a uniform grid over the half span and one interval between impacts, fine enough for
    the cube of the velocity (4 points per period of the highest harmonic kept), trapezoid weights in x."""
    x = np.linspace(0.0, 0.5 * spec.span, 33)
    nt = int(max(256, 4 * spec.frequency.max() / scene.rotary_speed if spec.frequency.size else 256))
    t = np.linspace(0.0, scene.impact_interval, nt, endpoint=False)
    w = np.full(x.size, x[1] - x[0])
    w[[0, -1]] *= 0.5
    return x, t, w[None, :] * (t[1] - t[0])


def energy(scene: Scene, found: DampedImpact) -> dict[str, float]:
    """Per period τ: the nonlinear drag's dissipation D ∫∫|ẏ|³ [J], the linear damper's c ∫∫ẏ² [J] (both on
    :func:`energy_grid`), the end moments' work ∮ 2 M_e θ̇(0) dt [J] and the impact load's work [J] (both from
    the harmonics), and the equivalent damping of this motion (:func:`damping.equivalent_damping`)."""
    spec, impulse = found.spec, found.impact.impulse
    x, t, w = energy_grid(scene, spec)
    v = velocity_field(spec, impulse, x, t)
    scale = 2.0 * scene.impacts_per_revolution  # both halves of the span, every interval of the period
    drag = spec.props["drag_coefficient_per_length"]
    nonlinear = scale * drag * float(np.sum(w * np.abs(v) ** 3))
    linear = scale * spec.damping * float(np.sum(w * v**2))
    moment = -impulse * 1j * spec.moments * spec.coef  # M_e harmonics [N m]
    slope = -impulse * spec.coef * (_dot(spec.transfer * spec.load[None, :], spec.k)
                                    + 1j * spec.moments * (_dot(spec.dynamic, spec.k) + spec.static[2]))  # y'(0)
    work_moments = scene.period * float(np.sum((moment * np.conj(1j * spec.frequency * slope)).real))
    force = -impulse * spec.coef
    conjugate = force * _dot(spec.total, spec.load * 0.5 * spec.props["mass_per_length"] * spec.span)
    work_load = scene.period * float(np.sum(0.5 * (force * np.conj(1j * spec.frequency * conjugate)).real))
    return {"drag_dissipation": nonlinear, "damper_dissipation": linear, "end_moment_work": work_moments,
            "impact_work": work_load, "equivalent_damping": damping.equivalent_damping(drag, v, w)}


# --- the design point ---------------------------------------------------------------------------
def assumed_damping(scene: Scene) -> float:
    """c₀ [N s/m²] of the paper's assumed motion y = c sin(πx/L) sin Ωt (the clearance c; paper appendix A):
    equal dissipation over the span and the period, (8/(3π))² D Ω c — eq. 7.1 with the span average of
    |sin|³ over sin², also 8/(3π)."""
    return float(damping.HARMONIC_FACTOR * damping.harmonic_equivalent_damping(
        scene.props["drag_coefficient_per_length"], scene.rotary_speed, scene.clearance))


def seeds(scene: Scene, options: Options) -> tuple[list, span_search.SpanSearch]:
    """The undamped roots to continue from: those passing the undamped midspan screen, refined exactly
    (T_L, b at their fixed point; those whose refinement failed are dropped, as the undamped search drops
    them), ascending, each with its bracket: [(Impact, bracket)], and the search."""
    search = span_search.find_roots(scene, options)
    screened = span_search.midspan_screen(scene, options, search)
    roots, brackets = search.roots[screened], search.brackets[screened]
    if roots.size == 0:
        return [], search
    durations, halves = search.residual.pulse(roots)
    refined = impact_model.refine_roots(scene, options, roots, brackets, durations=durations, halves=halves)
    return sorted(((imp, tuple(b)) for imp, b in zip(refined, brackets) if not imp.problems),
                  key=lambda item: item[0].span_length), search


def continue_root(scene: Scene, seed: impact_model.Impact, bracket, c: float, options: Options,
                  harmonics: int) -> DampedImpact:
    """The damped root continued from an undamped one: secant steps on the damped residual from its span, T_L
    and b."""
    return refine(scene, seed.span_length, bracket, c, options, harmonics, seed.contact_duration,
                  seed.contact_half_length)


def iterate_damping(scene: Scene, found: DampedImpact, bracket, options: Options, settings: DampedOptions):
    """c and the span to their joint fixed point at the chosen root (module docstring): c ← E(c), E the
    equal-dissipation damping of the motion that c gives (its span re-solved), by secant steps on E(c) − c
    once two iterates exist (plain steps before, and wherever a secant step would leave c > 0); returns (the
    impact, the history of c, converged?, message)."""
    history, images = [found.spec.damping], []
    for _ in range(settings.damping_iterations):
        images.append(energy(scene, found)["equivalent_damping"])
        c = images[-1]
        if len(images) > 1:
            slope = (images[-1] - history[-1] - images[-2] + history[-2]) / (history[-1] - history[-2])
            secant = history[-1] - (images[-1] - history[-1]) / slope if slope else math.nan
            c = secant if secant > 0 else c
        if abs(images[-1] - history[-1]) <= settings.damping_tolerance * images[-1]:
            return found, history, True, ""
        nxt = refine(scene, found.impact.span_length, bracket, c, options, settings.damped_harmonics,
                     found.impact.contact_duration, found.impact.contact_half_length)
        if nxt.impact.problems:
            return found, history, False, (f"the span is lost while the equivalent damping moves from "
                                           f"{history[-1]:.4g} to {c:.4g} N s/m² ({'; '.join(nxt.impact.problems)})")
        found = nxt
        history.append(c)
    return found, history, False, (f"the equivalent damping did not settle in {settings.damping_iterations} steps "
                                   f"(last {history[-1]:.4g}, its motion's {images[-1]:.4g} N s/m²)")


def stresses(scene: Scene, found: DampedImpact, inputs: Mapping[str, Any], options: Options) -> dict[str, float]:
    """Deflection and stress maxima of the damped motion (docs/model.md §5) from its fields on the solver's
    grids, located to a tenth of the study's tolerance (:func:`extremes.stresses_from_fields`)."""
    impact = found.impact
    x = periodic.space_grid(impact.span_length, impact.contact_half_length, options)
    t = periodic.time_grid(scene, impact.contact_duration, options)
    kinds = ("deflection", "moment", "shear")
    f = fields(scene, impact, found.spec, options, x, t, kinds)

    def field_at(kind, xs, ts):
        return fields(scene, impact, found.spec, options, xs, ts, [kind])[kind]

    return extremes.stresses_from_fields(scene, x, t, f["deflection"], f["moment"], f["shear"],
                                         field_at=field_at, tolerance=study_tolerance(inputs))


def end_moment_history(scene: Scene, found: DampedImpact, points: int = 64) -> tuple[np.ndarray, np.ndarray]:
    """(t [s], M_e(t) [N m]) over one period: the moment required at each end (sagging positive)."""
    spec = found.spec
    t = np.linspace(0.0, scene.period, points, endpoint=False)
    harmonics = -found.impact.impulse * 1j * spec.moments * spec.coef
    return t, (np.exp(1j * np.outer(t, spec.frequency)) @ harmonics).real


def solve(inputs: Mapping[str, Any]) -> PointResult:
    """The damped solution at a point given by its SI inputs (:func:`run` of its :class:`DesignPoint`)."""
    return run(DesignPoint.from_inputs(inputs))


def run(point: DesignPoint) -> PointResult:
    """The damped periodic solution of one design point (module docstring)."""
    result = PointResult(method=METHOD)
    options, settings, scene, inputs = point.periodic, point.damped, point.scene, point.inputs
    result.values.update(scene.props)

    def done(status: str, message: str) -> PointResult:
        result.status, result.message = status, message
        return result

    max_span = min(options.max_span, scene.props["buckling_length"] * (1 - 1e-9))
    if max_span <= options.min_span:
        return done("buckled", f"effective tension {scene.props['effective_tension']:.4g} N buckles every span "
                               f"longer than {scene.props['buckling_length']:.4g} m, below the shortest searched")
    options = Options(**{**options.__dict__, "max_span": max_span})
    too_many = impact_model.span_search_too_large(scene, options)
    if too_many is not None:
        return done("failed", too_many)
    c0 = assumed_damping(scene)
    starts, search = seeds(scene, options)
    result.values.update(root_count=float(search.roots.size), pole_count=float(search.pole_count),
                         narrow_count=float(search.narrow_count))
    result.extras.update(closure=scene.closure, impact_pattern=scene.pattern)
    reasons: dict[str, int] = {}
    chosen = bracket = None
    c, history, converged, why = c0, [c0], True, ""
    for seed, window in starts:
        found = continue_root(scene, seed, window, c, options, settings.damped_harmonics)
        problem = "; ".join(found.impact.problems) or violation(scene, found, options)
        if problem is None:  # settle c with this motion, then condition 1 again
            found, history, converged, why = iterate_damping(scene, found, window, options, settings)
            problem = None if not converged else violation(scene, found, options)
            if problem is None:  # valid, or its damping did not settle (reported as not converged)
                chosen, bracket = found, window
                break
            c = history[-1]  # the next roots are continued with the damping this motion settled at
            problem = "breaks condition 1 at its settled damping"
        key = periodic.rejection_kind(problem)
        reasons[key] = reasons.get(key, 0) + 1
    summary = (f"{search.roots.size} roots of the undamped condition 2, {len(starts)} pass its midspan screen and "
               f"are continued with the drag (c0 = {c0:.4g} N s/m²)")
    if chosen is None:
        detail = "; ".join(f"{v} x {k}" for k, v in sorted(reasons.items(), key=lambda kv: -kv[1])[:3])
        return done("no_span", f"{summary}; none satisfies condition 1 with damping"
                    + (f" ({detail})" if detail else ""))
    result.extras.update(damping_history=[float(v) for v in history], damping_converged=converged)
    status, notes = ("ok", []) if converged else ("not_converged", [why])
    impact = chosen.impact
    finer = periodic.doubled(options)
    check = refine(scene, impact.span_length, bracket, chosen.spec.damping, finer, settings.damped_harmonics,
                   impact.contact_duration, impact.contact_half_length)
    drift = abs(check.impact.span_length / impact.span_length - 1.0) if not check.impact.problems else math.inf
    result.extras["span_converged"] = drift <= point.tolerances.tolerance
    if not result.extras["span_converged"] and status == "ok":
        status = "not_converged"
        notes.append(f"the span {impact.span_length:.6g} m moves by {drift:.2g} with the modes doubled to "
                     f"{finer.modes}")
    result.values.update(
        span_length=impact.span_length, equivalent_mass=impact.equivalent_mass, impact_velocity=impact.impact_velocity,
        impulse=impact.impulse, axial_curvature=impact.axial_curvature, max_approach=impact.max_approach,
        hertz_duration=impact.hertz_duration, hertz_peak_force=impact.hertz_peak_force,
        contact_duration=impact.contact_duration, peak_contact_force=impact.peak_contact_force,
        contact_half_length=impact.contact_half_length, contact_half_width=impact.contact_half_width,
        first_natural_frequency=float(scene.natural_frequencies(impact.span_length, [1.0])[0] / (2 * np.pi)))
    values = stresses(scene, chosen, inputs, options)
    result.values.update(values)
    balance = energy(scene, chosen)
    t, moment = end_moment_history(scene, chosen)
    taken = balance["drag_dissipation"]
    residual = abs(balance["end_moment_work"] - taken) / taken if taken > 0 else abs(balance["end_moment_work"])
    omega1 = scene.natural_frequencies(impact.span_length, [1.0])[0]
    result.values.update(
        equivalent_damping=chosen.spec.damping,
        damping_ratio=float(chosen.spec.damping / (2.0 * scene.props["mass_per_length"] * omega1)),
        end_moment_amplitude=float(np.max(np.abs(moment))), end_moment_power=balance["end_moment_work"] / scene.period,
        drag_dissipation=balance["drag_dissipation"], energy_residual=float(residual))
    result.extras.update(end_moment_history={"t": t.tolist(), "moment": moment.tolist()},
                         impact_work=balance["impact_work"], damper_dissipation=balance["damper_dissipation"])
    tolerance = point.tolerances.tolerance
    if residual > tolerance and status == "ok":
        status = "not_converged"
        notes.append(f"energy balance: the end moments feed {balance['end_moment_work']:.4g} J per period, the drag "
                     f"takes {balance['drag_dissipation']:.4g} J (residual {residual:.2g} > {tolerance:.2g})")
    result.error_estimate = (periodic.truncation_bound(scene, impact, options) / values["max_normal_stress"]
                             + values["location_residual"])
    message = (f"{summary}; the first valid is at {impact.span_length:.6g} m; equivalent damping "
               f"{chosen.spec.damping:.4g} N s/m² after {len(history) - 1} steps; end moment "
               f"{result.values['end_moment_amplitude']:.4g} N m feeding {result.values['end_moment_power']:.4g} W; "
               f"energy residual {residual:.2g}")
    return done(status, "; ".join([message] + notes))


def scan(scene: Scene, options: Options, c: float, lo: float, hi: float, samples: int = 201,
         harmonics: int = DampedOptions.default("damped_harmonics")) -> list[tuple[float, str | None]]:
    """Every root of the damped condition 2 with damping c [N s/m²] in [lo, hi] [m], found directly (not
    continued from the undamped roots): the residual sampled at ``samples`` spans, each sign change between two
    evaluated samples refined inside its interval, and kept when the residual vanishes there (not at a pole of
    the in-phase moments, where it changes sign too). Returns (span [m], None or why condition 1 or the impact
    rejects it) per root, ascending — the check of a given span range, e.g. around the paper's 345 ft."""
    spans = np.linspace(lo, hi, samples)
    values, starts, start = [], [], (None, 0.0)
    for span in spans:
        found = impact_at(scene, float(span), c, options, harmonics, *start)
        ok = not found.impact.problems
        values.append(found.impact.residual if ok else math.nan)
        starts.append((found.impact.contact_duration, found.impact.contact_half_length) if ok else (None, 0.0))
        start = starts[-1]
    values = np.asarray(values)
    out = []
    for i in np.nonzero(np.sign(values[:-1]) * np.sign(values[1:]) < 0)[0]:
        found = refine(scene, 0.5 * (spans[i] + spans[i + 1]), (spans[i], spans[i + 1]), c, options, harmonics,
                       *starts[i])
        if LEFT in found.impact.problems:
            continue
        problem = "; ".join(found.impact.problems) or violation(scene, found, options)
        out.append((found.impact.span_length, problem))
    return out
