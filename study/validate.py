"""``study validate``: the project's record of how right it is, computed against printed numbers.

Every row is computed now, by the code under test, and set beside the number printed in the
source it names. ``make validate`` writes the report to ``docs/validation.md``.
"""

from __future__ import annotations

import re
import tempfile
from pathlib import Path

import numpy as np

from study import __version__
from study.config import load
from study.physics import hertz, restitution
from study.solvers import OUTPUTS, solve_point
from study.solvers.methods.crosscheck import DEFAULT_TOLERANCE
from study.solvers.kernels.orbit import STABILITY_TOL
from study.units import convert, pint_unit
from study.workflow.execute import run_grid
from study.workflow.grid import Grid
from study.workflow.sweep import study_grid

DEFAULT_CONFIG = Path(__file__).resolve().parents[1] / "configs" / "paper.toml"
CROSSCHECK_CONFIG = DEFAULT_CONFIG.with_name("crosscheck.toml")

#: Paper appendix D ("taken from reference 3", Timoshenko & Goodier): θ [deg] -> (m, n) as printed.
HERTZ_TABLE = {
    30: (2.731, 0.493), 35: (2.397, 0.530), 40: (2.136, 0.567), 45: (1.926, 0.604),
    50: (1.754, 0.641), 55: (1.611, 0.678), 60: (1.486, 0.717), 65: (1.378, 0.759),
    70: (1.284, 0.802), 75: (1.202, 0.846), 80: (1.128, 0.893), 85: (1.061, 0.944), 90: (1.000, 1.000),
}


class Uncertain(str):
    """A line of the record whose numbers are statistics of a chaotic motion (or derived from them): a machine
    whose last bits differ follows another trajectory and prints other numbers, equally right within the
    ``tolerance`` (relative) the line carries — twice the stated error of the figures it shows
    (:func:`record_differences`)."""

    tolerance: float

    def __new__(cls, text: str, tolerance: float):
        line = super().__new__(cls, text)
        line.tolerance = float(tolerance) if np.isfinite(tolerance) else float("inf")
        return line


#: A number as the record prints it: sign, digits, decimals, exponent.
NUMBER = re.compile(r"[-+]?\d+(?:\.\d+)?(?:e[-+]?\d+)?")
#: Words a chaotic figure's line may change between machines: a figure at the edge of its tolerance is converged
#: on one and not on the other.
STATUS_WORDS = {"ok", "not_converged"}


def _printed_unit(token: str) -> float:
    """The unit of the last digit a number was printed with (``"1.429"`` -> 0.001, ``"1.0e-06"`` -> 1e-07)."""
    mantissa, _, exponent = token.lower().partition("e")
    decimals = len(mantissa.partition(".")[2])
    return 10.0 ** (int(exponent or 0) - decimals)


def _numbers_agree(a: str, b: str, tolerance: float) -> bool:
    """Whether two printed numbers are one within one unit of their last printed digit (a value computed to an
    integrator's tolerance rounds either way at a digit's edge) or the relative ``tolerance``."""
    x, y = float(a), float(b)
    return abs(x - y) <= max(_printed_unit(a), _printed_unit(b), tolerance * max(abs(x), abs(y))) * (1 + 1e-9)


def record_differences(committed: str, lines: list[str]) -> list[str]:
    """The lines where a committed record and the one computed now (:func:`record_lines`) differ beyond what the
    machine may change: every word the same, and every number within one unit of its last printed digit or, on an
    :class:`Uncertain` line, within that line's tolerance (there the words ``ok``/``not_converged`` may swap).
    Empty when the record is current."""
    old = committed.rstrip("\n").split("\n")
    new = "\n".join(lines).rstrip("\n").split("\n")
    tolerance = []
    for line in lines:
        tolerance += [getattr(line, "tolerance", 0.0)] * (line.count("\n") + 1)
    if len(old) != len(new):
        return [f"{len(old)} lines committed, {len(new)} computed"]
    out = []
    for k, (a, b, tol) in enumerate(zip(old, new, tolerance), start=1):
        if a == b:
            continue
        words_a, words_b = NUMBER.split(a), NUMBER.split(b)
        nums_a, nums_b = NUMBER.findall(a), NUMBER.findall(b)
        same_words = len(words_a) == len(words_b) and all(
            u == v or (tol > 0 and set(re.findall(r"\w+", u)) ^ set(re.findall(r"\w+", v)) <= STATUS_WORDS)
            for u, v in zip(words_a, words_b))
        if not (same_words and len(nums_a) == len(nums_b)
                and all(_numbers_agree(u, v, tol) for u, v in zip(nums_a, nums_b))):
            out.append(f"line {k}: committed {a!r}, computed {b!r}" + (f" (tolerance {tol:.3g})" if tol else ""))
    return out


def _row(*cells) -> str:
    return "| " + " | ".join(str(c) for c in cells) + " |"


def hertz_table_section() -> list[str]:
    lines = ["## Hertz contact coefficients m, n (paper appendix D)", "",
             "Exact values from complete elliptic integrals (`study.physics.hertz.contact_coefficients`) "
             "against the table the paper reprints from Timoshenko & Goodier. `ok` means equal to the "
             "printed three decimals; otherwise the difference is shown.", "",
             _row("θ [deg]", "m printed", "m exact", "n printed", "n exact", "verdict"),
             _row(*["---"] * 6)]
    worst = 0.0
    misprints = 0
    for deg, (m_p, n_p) in HERTZ_TABLE.items():
        m, n = (float(v) for v in hertz.contact_coefficients(np.radians(deg)))
        diffs = [m - m_p, n - n_p]
        worst = max(worst, *map(abs, diffs))
        bad = [f"{name} off by {d:+.4f}" for name, d in zip("mn", diffs) if abs(d) > 0.0005 + 1e-12]
        misprints += len(bad)
        lines.append(_row(deg, f"{m_p:.3f}", f"{m:.5f}", f"{n_p:.3f}", f"{n:.5f}", "; ".join(bad) or "ok"))
    lines += ["", f"{26 - misprints} of 26 printed entries agree to their printed digits; the largest "
              f"difference is {worst:.4f}. The exact values are confirmed by an independent quadrature "
              "of Hertz's potential integrals in `tests/physics/test_hertz.py` (agreement ~1e-11), so the "
              "differing entries are errors of the printed table (Cooper, J. Appl. Mech. 36, 1969, "
              "reports errors in the classical tables), not of the code.", ""]
    return lines


def impact_constants_section() -> list[str]:
    c_h = hertz.HERTZ_DURATION_CONSTANT
    ratio = hertz.LEE_TO_HERTZ_DURATION_RATIO
    area = 1.6 / c_h
    return [
        "## Hertz impact and Lee's pulse (paper eq. 12, appendix C)", "",
        _row("quantity", "printed", "computed", "difference", "note"), _row(*["---"] * 5),
        _row("T_H v0/α_max", "2.94", f"{c_h:.6f}", f"{(c_h - 2.94) / 2.94:+.2%}",
             "0.8 B(2/5, 1/2), eq. 12"),
        _row("∫F dt/(F_max T_H)", "0.5492", f"{area:.4f}", f"{(area - 0.5492) / 0.5492:+.2%}",
             "paper's finite-difference construction of Fig. 2 (step 0.005) overestimates the area"),
        _row("T_L/T_H", "0.855", f"{ratio:.4f}", f"{(ratio - 0.855) / 0.855:+.2%}",
             "equal normalised peaks, derived (Lee's value; the paper's own area would give 0.8627)"),
        "",
    ]


def textbook_section() -> list[str]:
    e = float(restitution.restitution_from_rebound(2.0, 1.5))
    rebound = float(restitution.rebound_height(3.0, e))
    ratio = restitution.collision(60.0, 1.0, 10.0, 0.0, 0.0).v1  # box on a free roller (Example 8.2)
    cycle = restitution.periodic_impact_steady_state(float(ratio), 1.4715)
    return [
        "## Textbook impact examples (Harrison & Nettleton, chapter 8)", "",
        _row("case", "printed / closed form", "computed", "source"), _row(*["---"] * 4),
        _row("Problem 8.1: e from 2 m drop, 1.5 m rebound", "√0.75 = 0.8660 (closed form)", f"{e:.4f}",
             "book, Problem 8.1"),
        _row("Problem 8.1: rebound from 3 m", "2.25 m (closed form)", f"{rebound:.4f} m", "book, Problem 8.1"),
        _row("Example 8.2: velocity ratio at a roller", "6/7 = 0.8571", f"{float(ratio):.4f}", "book, Example 8.2"),
        _row("Example 8.2: steady mean velocity", "2.187 m/s", f"{float(cycle.mean):.4f} m/s", "book, Example 8.2"),
        "", "The full catalogue of the textbook's worked examples is `docs/textbook_examples.md`.", "",
    ]


def paper_example_section() -> list[str]:
    study = load(DEFAULT_CONFIG)
    point = study.point()
    result = solve_point(point, "core")
    v = result.values

    def show(name, unit):
        return f"{convert(v[name], pint_unit(OUTPUTS[name][0]), unit):.4g} {unit}"

    rows = [
        ("bending stiffness EI", show("bending_stiffness", "lbf*in**2")),
        ("pipe mass", show("pipe_mass", "lb/ft")),
        ("mud inside the pipe", show("internal_mud_mass", "lb/ft")),
        ("added mass (potential flow)", show("added_mass", "lb/ft")),
        ("total mass M", show("mass_per_length", "lb/ft")),
        ("effective tension", show("effective_tension", "lbf")),
        ("first natural frequency of the 345-ft span", show("first_natural_frequency", "Hz")),
        ("equivalent mass 2ML/π", show("equivalent_mass", "lb")),
        ("impact velocity Ω c (prescribed closure)", show("impact_velocity", "in/s")),
        ("Hertz duration T_H", show("hertz_duration", "ms")),
        ("Lee duration T_L", show("contact_duration", "ms")),
        ("peak contact force", show("peak_contact_force", "lbf")),
        ("contact half-length / half-width", show("contact_half_length", "in") + " / "
         + show("contact_half_width", "in")),
    ]
    return [
        "## The paper's example (configs/paper.toml), physics core at the printed span", "",
        "Inputs as read and reconstructed in `configs/paper.toml` (its header says which were "
        "reconstructed and how). Here the span is the paper's printed 345 ft, given: the physics core "
        "evaluates the section, the mud and the impact there. The periodic methods that search for the "
        "span and compute the stresses are compared with the printed span (345 ft; 337 ft without "
        "mud-flow and drag terms), normal stress (order 10⁴ psi) and shear stress (order 500 psi) in the "
        "section on the periodic solution below.", "",
        _row("quantity", "value"), _row("---", "---"), *[_row(a, b) for a, b in rows], "",
        f"Status `{result.status}`: {result.message}.", "",
        "Note the scale: with V_p = Ω c and the assumed-mode curvature κ = c(π/L)², the equivalent "
        "mass of a 345-ft span strikes with a Lee peak force of "
        f"{convert(v['peak_contact_force'], 'N', 'lbf'):.3g} lbf spread over a contact "
        f"{convert(2 * v['contact_half_length'], 'm', 'ft'):.3g} ft long. Whether the paper's stresses of order 10⁴ "
        "psi follow from this closure is the question of the periodic-solution issue.", "",
    ]


def periodic_solution_section(modes: int = 21) -> list[str]:
    """The span search of the fast method on the paper's example, in every reading of docs/model.md §4."""
    point = load(DEFAULT_CONFIG).point()
    rows, stress_rows = [], []
    for pattern in ("alternating", "one_wall"):
        for closure in ("prescribed", "self_consistent"):
            result = solve_point({**point, "impact_pattern": pattern, "closure": closure, "modes": modes}, "fast")
            v = result.values
            spans = (", ".join(f"{convert(L, 'm', 'ft'):.1f}" for L in result.extras.get("candidate_spans", []))
                     or "none")
            rows.append(_row(pattern, closure, int(v["root_count"]), int(v["pole_count"]),
                             int(v["pole_count"] - v["narrow_count"]), spans,
                             f"`{result.status}`: {result.message.split('; ', 1)[-1]}"))
            if "max_normal_stress" in v:
                stress_rows.append(_row(f"{pattern}, {closure}", f"{convert(v['span_length'], 'm', 'ft'):.2f}",
                                        f"{convert(v['max_normal_stress'], 'Pa', 'psi'):.3g}",
                                        f"{convert(v['max_shear_stress'], 'Pa', 'psi'):.3g}",
                                        f"{convert(v['alternating_bending_stress'], 'Pa', 'psi'):.3g}",
                                        f"{result.error_estimate:.2g}"))
    stress_table = ([_row("reading", "span [ft]", "max normal stress [psi]", "max shear stress [psi]",
                          "alternating bending stress [psi]", "error estimate"), _row(*["---"] * 6),
                     *stress_rows, _row("paper (§VII)", "345", "order 10⁴", "order 500", "-", "-"), ""]
                    if stress_rows else [])
    return [
        "## The periodic solution of the paper's example (method `fast`)", "",
        f"Span search of `study point --method fast` ({modes} modes, spans 3 m to 1000 ft) on the paper's "
        "example, in the four readings of docs/model.md §4: the impact pattern (one wall per revolution, or "
        "both walls alternately) and the closure of the impact velocity (prescribed V_p = Ω c, or the "
        "solution's own pre-impact velocity). Paper: 345 ft with all terms, 337 ft without the mud-flow "
        "and drag terms.", "",
        _row("pattern", "closure", "roots of condition 2", "poles", "poles searched (wider than 1e-6 L)",
             "valid spans [ft]", "verdict"),
        _row(*["---"] * 7), *rows, "",
        "No reading yields a valid span near the paper's 345 ft (the team's earlier prototype, docs/model.md "
        "§4.6, found none either). Roots of condition 2 (the midspan at the wall when the pulse starts) are plentiful "
        "- nearly one next to every resonance pole - but at nearly all of them the solution's own "
        "shape contradicts the impact: the pipe is not convex towards the wall at the contact, the "
        "midspan is moving away from the wall when contact starts, or the pipe crosses the hole "
        "elsewhere (condition 1). One wall per revolution with the impact velocity from the solution "
        "itself gives two valid spans close together, 22.02 ft and 22.14 ft, the same pair at 11, 21, "
        "41 and 61 modes (15 modes adds a third, 15.1 ft; tests/solvers/test_fast.py checks 11 and 21); "
        "the stresses at the smaller converge with the modes (max normal stress 9.05e4 psi from 21 to "
        "61 modes). Both walls with the self-consistent closure also gives valid spans, but they change "
        "with the truncation (22.1 and 37.5 ft at 21 modes, none at 41, 22.6 ft at 61) and with where the "
        "T_L-curvature iteration starts: in the undamped "
        "model modes near resonance ring with large amplitude, so those spans are not a converged "
        "answer. The search skips resonances narrower than 1e-6 of the span (`solver.resonance_width`): "
        "the root such a resonance pins lies within about that distance of its pole, and any damping of "
        "that order removes it (tests/solvers/test_periodic.py checks that nothing else is skipped). "
        "The paper's span is therefore not reproduced; the next section asks whether the damped periodic "
        "solution (docs/model.md §7.1) has one. "
        "The time domain's check of the 22-ft solutions follows.", "",
        *stress_table,
    ]


def cross_check_section() -> list[str]:
    """The impact of the paper's point by the methods that model it at the given span."""
    point = load(DEFAULT_CONFIG).point()
    rows = []
    for method in ("core", "sdof", "time-domain"):
        result = solve_point(point, method)
        v = result.values
        rows.append(_row(method, f"`{result.status}`", f"{v.get('impact_velocity', float('nan')):.4g}",
                         f"{convert(v.get('peak_contact_force', float('nan')), 'N', 'lbf'):.4g}",
                         f"{v.get('impacts_per_revolution', float('nan')):.3g}", result.message.split(";")[0]))
    return [
        "## Cross-check of the impact at the paper's point (345-ft span given)", "",
        "`core` takes the prescribed closure V_p = Ω c; `sdof` finds the first mode's periodic orbit between "
        "the walls under a harmonic drive equal to the mean impact force of that closure (its default); "
        "`time-domain` integrates the span's modes through Hertz contact with the same drive until the "
        "motion repeats. The peak force is Lee's for `core` (e = 0.5) and the elastic Hertz peak of the "
        "orbit's impact for `sdof`; `time-domain` reports the force it integrated.", "",
        _row("method", "status", "impact velocity [m/s]", "peak contact force [lbf]", "impacts per revolution",
             "verdict"), _row(*["---"] * 6), *rows, "",
    ]


def _span_of(values) -> str:
    """'a' or 'a-b' (3 significant digits) for the smallest and largest of ``values``."""
    low, high = f"{min(values):.3g}", f"{max(values):.3g}"
    return low if low == high else f"{low}-{high}"


def _orbit_cell(found) -> str:
    """The crosscheck's real-contact orbit in one table cell."""
    if found.get("status") != "converged":
        return "none" if found.get("status") == "no_orbit" else f"not found ({found.get('status')})"
    return (f"{found['distance']:.3g} away; force {found['peak_force_ratio']:.3f}, stress "
            f"{found['normal_stress_ratio']:.3f}; {'stable' if found['stable'] else 'unstable'}, "
            f"μ {found['largest_multiplier']:.3g}")


def replay_section(modes: int = 21, restitutions=(0.5, 1.0)) -> list[str]:
    """The crosscheck method on the readings of the paper's example that have a periodic solution, at the
    paper's e = 0.5 and at e = 1 (where the single mass peaks exactly at Lee's force)."""
    point = load(DEFAULT_CONFIG).point()
    rows, found = [], {}
    for e in restitutions:
        for pattern in ("one_wall", "alternating"):
            result = solve_point({**point, "impact_pattern": pattern, "closure": "self_consistent", "modes": modes,
                                  "restitution": e}, "crosscheck")
            v = result.values
            if "impulse_ratio" not in v:
                rows.append(_row(pattern, f"{e:g}", *["-"] * 10, f"`{result.status}`: {result.message}"))
                continue
            td = result.extras["time_domain"]
            one_mass = td["one_mass_peak_force"] / v["peak_contact_force"]
            for key, value in (("one_mass", one_mass), ("span", v["peak_force_ratio"]),
                               ("gap", -td["midspan_at_lee_peak"]), ("need", td["approach_at_lee_peak"]),
                               ("distance", v["orbit_distance"]), ("multiplier", v["max_floquet_multiplier"]),
                               ("orbit", v["orbit_peak_force_ratio"])):
                if np.isfinite(value):
                    found.setdefault((key, e), []).append(value)
            rows.append(_row(pattern, f"{e:g}", f"{convert(v['span_length'], 'm', 'ft'):.2f}",
                             *(f"{v[name]:.3f}" for name in ("impulse_ratio", "peak_force_ratio",
                                                              "normal_stress_ratio", "deflection_ratio")),
                             f"{v['periodicity_defect']:.3g}", f"{one_mass:.3f}",
                             f"{td['midspan_at_lee_peak'] * 1e6:.3g}", f"{td['approach_at_lee_peak'] * 1e6:.3g}",
                             _orbit_cell(td["orbit"]), f"`{result.status}`"))

    def span(key, restitution, scale=1.0):
        values = found.get((key, restitution))
        return _span_of([scale * x for x in values]) if values else "-"

    half, elastic = restitutions
    return [
        "## Is the periodic solution an orbit of the real contact? (method `crosscheck`)", "",
        f"The periodic solution ({modes} modes, the solution's own impact velocity, the paper's equivalent "
        "mass 2ML/π) is put into the time domain a little before its impact - its own modal state, "
        "the same span and modes, no damping or drive (the periodic model has neither), Hertz contact at "
        "midspan with the stiffness at the solution's own curvature and Hunt-Crossley damping that "
        "rebounds one mass with e - and run through one revolution of real contact "
        "(`study.solvers.methods.crosscheck`). Ratios are time domain over periodic solution; the periodicity "
        "defect is the largest change of the modal state over the revolution (q in units of c, q' in "
        "units of Ω c); \"one mass\" is the peak of the equivalent mass alone on the same contact over "
        "Lee's peak; the last two columns are the periodic solution's midspan position at the peak of "
        "Lee's pulse (y - c, positive into the wall) and the Hertz approach (F̂/K)^(2/3) that peak force "
        "needs; the real-contact orbit is the periodic orbit of the replay's scene nearest the periodic "
        "solution, found by shooting (`study.solvers.kernels.orbit`), with its distance from the periodic "
        "solution's state, its peak force and largest normal stress over the periodic solution's, and its "
        f"largest Floquet multiplier. Tolerance {DEFAULT_TOLERANCE:g}.", "",
        _row("pattern", "e", "span [ft]", "impulse", "peak contact force", "max normal stress", "max deflection",
             "periodicity defect", "one mass", "y - c at Lee's peak [µm]", "approach Lee's peak needs [µm]",
             "real-contact orbit", "verdict"), _row(*["---"] * 13), *rows, "",
        f"At e = {half:g} the real contact delivers the impulse the closure assumes and the span carries the "
        "periodic solution's stress and deflection within 2 %; what it does not reproduce is the force "
        "history. Lee's pulse is imposed on the span, not a contact: at its peak the periodic solution's "
        f"midspan is {span('gap', half, 1e6)} µm off the wall where the force needs "
        f"{span('need', half, 1e6)} µm of Hertz approach. The real contact has the approach its force "
        f"needs, and peaks {span('span', half)}x Lee's. The contact law alone (the equivalent mass on the "
        f"same damped contact) peaks {span('one_mass', half)}x Lee's at e = {half:g}, but "
        f"{span('one_mass', elastic)}x at e = {elastic:g}, where the span still peaks "
        f"{span('span', elastic)}x: there the whole difference is the span's modes moving under a pulse "
        f"that does not follow them. At e = {half:g} the contact law and the modes both act, and the near "
        "match of the two ratios does not single out the contact law (an earlier version of this page "
        "drew that conclusion from e = 0.5 alone). At e = 1 the closure's "
        "impulse itself is off (one wall) and the state does not return after the revolution. There the "
        "scene is conservative and the real contact does have a periodic orbit near the periodic "
        f"solution (within {span('distance', elastic)} of its state), but it is unstable (largest Floquet "
        f"multiplier {span('multiplier', elastic)}) and peaks {span('orbit', elastic)}x Lee's force: "
        "the peak force of the periodic state is sensitive to the state the span meets the wall with, "
        "and Lee's pulse does not carry that state. With e = 0.5 nothing feeds the energy the contact "
        "takes, so there is no orbit to find. Every "
        "reading is flagged `disagrees`, with these reasons in its message; "
        "`tests/solvers/test_crosscheck.py` checks these findings.", "",
    ]


#: The outputs of method crosscheck the survey reads.
SURVEY_COLUMNS = ("span_length", "peak_force_ratio", "normal_stress_ratio", "deflection_ratio", "orbit_distance",
                  "orbit_peak_force_ratio", "orbit_normal_stress_ratio", "max_floquet_multiplier")


def crosscheck_survey(workers: int = 2) -> dict[str, np.ndarray]:
    """Method crosscheck at e = 1 over the grid of ``configs/crosscheck.toml`` without its 50-rpm and
    40 000-lbf rows (their shooting is the slowest, up to half a minute a point), solved in parallel by
    the sweep's own runner; the columns :func:`survey_section` reads, over the points in grid order, with
    the swept inputs."""
    study = load(CROSSCHECK_CONFIG)
    axes = dict(study.axes, restitution=np.array([1.0]))
    axes["rotary_speed"] = axes["rotary_speed"][axes["rotary_speed"] > convert(60.0, "rpm", "rad/s")]
    axes["axial_tension"] = axes["axial_tension"][axes["axial_tension"] < convert(30000.0, "lbf", "N")]
    grid = Grid(base=dict(study.inputs), axes=axes)
    with tempfile.TemporaryDirectory() as store:
        stored = run_grid(grid, Path(store), workers=workers, progress=False)
        columns = {name: stored[name] for name in SURVEY_COLUMNS}
    for name, column in zip(grid.dims, np.meshgrid(*grid.axes.values(), indexing="ij")):
        columns[name] = column.ravel()
    return columns


def survey_section(workers: int = 2) -> list[str]:
    """Is there a stable real-contact orbit near a periodic solution anywhere? :func:`crosscheck_survey`."""
    c = crosscheck_survey(workers)

    def agrees(name):  # within the crosscheck's own tolerance of the periodic solution
        return np.abs(c[name] - 1.0) <= DEFAULT_TOLERANCE

    has_solution = np.isfinite(c["peak_force_ratio"])
    has_orbit = np.isfinite(c["orbit_distance"])
    stable = has_orbit & (c["max_floquet_multiplier"] <= 1.0 + STABILITY_TOL)
    rows, summary = [], []
    order = [i for pattern in ("one_wall", "alternating") for i in np.flatnonzero(has_solution)
             if c["impact_pattern"][i] == pattern]
    for i in order:
        cells = [c["impact_pattern"][i], f"{convert(c['rotary_speed'][i], 'rad/s', 'rpm'):.0f}",
                 f"{convert(c['axial_tension'][i], 'N', 'lbf'):.0f}",
                 f"{convert(c['span_length'][i], 'm', 'ft'):.2f}"]
        cells += [f"{c[name][i]:.3f}" for name in ("peak_force_ratio", "normal_stress_ratio", "deflection_ratio")]
        if has_orbit[i]:
            cells += [f"{c['orbit_distance'][i]:.3g}", f"{c['orbit_peak_force_ratio'][i]:.3f}",
                      f"{c['orbit_normal_stress_ratio'][i]:.3f}", f"{c['max_floquet_multiplier'][i]:.3g}"]
        else:
            cells += ["not found", "-", "-", "-"]
        rows.append(_row(*cells))
    for pattern in ("one_wall", "alternating"):
        mine = c["impact_pattern"] == pattern
        solved, found = has_solution & mine, has_orbit & mine
        mu = c["max_floquet_multiplier"][found]
        summary.append(_row(pattern, int(mine.sum()), int(solved.sum()), int(found.sum()), int((stable & mine).sum()),
                            _span_of(mu) if mu.size else "-",
                            _span_of(c["orbit_peak_force_ratio"][found]) if mu.size else "-",
                            int((solved & agrees("normal_stress_ratio")).sum())))
    mu_all = c["max_floquet_multiplier"][has_orbit]
    force = c["orbit_peak_force_ratio"][has_orbit]
    close = agrees("orbit_peak_force_ratio")[has_orbit]
    if stable.any():
        finding = (f"{int(stable.sum())} of the {int(has_orbit.sum())} orbits found are stable: "
                   + "; ".join(f"{c['impact_pattern'][i]} at {convert(c['rotary_speed'][i], 'rad/s', 'rpm'):.0f} "
                               f"rpm, {convert(c['axial_tension'][i], 'N', 'lbf'):.0f} lbf (force "
                               f"{c['orbit_peak_force_ratio'][i]:.3f}, stress {c['orbit_normal_stress_ratio'][i]:.3f})"
                               for i in np.flatnonzero(stable)) + ".")
    else:
        finding = (f"None of the {int(has_orbit.sum())} orbits found is stable (largest Floquet multiplier "
                   f"{_span_of(mu_all)}): wherever the periodic solution has a real-contact counterpart, it is a "
                   "state the span moves away from, not one it settles in. The condition under which the time "
                   "domain and the periodic solution should agree within 2 % - a periodic state that exists and "
                   "is stable - is met nowhere in this survey, and every point is flagged `disagrees` with its "
                   "reasons.")
    n_points = int(has_solution.size)
    stress_close = int((has_solution & agrees("normal_stress_ratio") & agrees("deflection_ratio")).sum())
    return [
        "## Over the design space: is the real contact's periodic state stable anywhere? "
        "(`configs/crosscheck.toml`)", "",
        f"Method `crosscheck` at e = 1 (where the replay's scene is conservative and can have an orbit) over "
        f"{n_points} points: the grid of `configs/crosscheck.toml` (`make sweep CONFIG=configs/crosscheck.toml` "
        "runs all of it, e = 0.5 and the 50-rpm and 40 000-lbf rows included) without its 50-rpm and 40 000-lbf "
        "rows, whose shooting is the slowest. Each point: the periodic solution (`fast`, 21 modes, the solution's own "
        "impact velocity) finds its span; its revolution is replayed through the real contact; shooting finds "
        "the real contact's periodic orbit nearest it and its Floquet multipliers. Ratios are real contact over "
        f"periodic solution; a multiplier above 1 + {STABILITY_TOL:g} is unstable.", "",
        _row("pattern", "points", "with a periodic solution", "real-contact orbit found", "stable",
             "largest Floquet multiplier", "orbit's peak force / Lee's", "replay's stress within 2 %"),
        _row(*["---"] * 8), *summary, "",
        _row("pattern", "rpm", "tension [lbf]", "span [ft]", "replay: peak force", "max normal stress",
             "max deflection", "orbit: distance", "peak force", "max normal stress", "Floquet multiplier"),
        _row(*["---"] * 11), *rows, "",
        f"{finding} The orbits that exist peak {_span_of(force) if force.size else '-'}x Lee's force "
        f"({int(close.sum())} within 2 %). The replay's largest normal stress and deflection are within 2 % "
        f"of the periodic solution's at {stress_close} of the {int(has_solution.sum())} points with a periodic "
        "solution. Where no orbit is found, Newton's iteration left the section's flight (a contact open at the "
        "section time) or did not converge; the point's message says which. Shooting finds the orbit nearest "
        "the periodic solution; a stable orbit of the real contact farther from it is what the time-domain "
        "method settles in, and is not the periodic solution's.", "",
    ]


STUDY_CONFIG = DEFAULT_CONFIG.with_name("default.toml")
#: The damped solution's survey (docs/model.md §7.1): (rpm, hole inclination [deg]) on the paper's example;
#: vertical as the paper's, and 8° (the default study's deviation) where the reference model touches the wall.
DAMPED_POINTS = ((50, 0), (100, 0), (300, 0), (50, 8), (100, 8), (300, 8))
#: The spans scanned for a damped root near the paper's 345 ft [ft].
PAPER_SPAN_WINDOW = (300.0, 400.0)


def _compared(result, ref: dict | None) -> tuple[str, float]:
    """'status: span ft, force / σ ratios to the reference' of a periodic result (``ref`` None: the reference
    model does not touch the wall), and its largest |log ratio| (inf where there is nothing to compare)."""
    v = result.values
    if "span_length" not in v:
        return f"`{result.status}`", float("inf")
    head = f"`{result.status}`: {convert(v['span_length'], 'm', 'ft'):.1f} ft"
    if ref is None:
        return f"{head}, strikes the wall", float("inf")
    ratios = [v[name] / ref[name] for name in ("peak_contact_force", "max_normal_stress")]
    return f"{head}, force {ratios[0]:.3g}x, σ {ratios[1]:.3g}x", max(abs(np.log(r)) for r in ratios)


def damped_section() -> list[str]:
    """The damped periodic solution against the undamped one and the reference model on a handful of points of
    the paper's example, and whether any reading now has a span near the paper's 345 ft."""
    from study.solvers.methods.periodic import damped
    from study.solvers.methods import periodic
    from study.solvers.methods.reference import WHIRL_CLASSES

    whirls = {code: name for name, code in WHIRL_CLASSES.items()}
    point = load(DEFAULT_CONFIG).point()
    point = {k: v for k, v in point.items() if k != "span_length"}
    psi = convert(1.0, "psi", "Pa")
    lines = ["## The damped periodic solution (method `damped`, paper appendices A and B)", "",
             "The mud's drag kept, linearised by equal dissipation and fed back by end moments in phase with the "
             "impact (docs/model.md §7.1), on the paper's example in the reading where the undamped solution has "
             "spans (one wall per revolution, the solution's own impact velocity), beside the undamped `fast` and "
             "the reference model (`reference`: the section in both lateral directions, whirl and Hertz contact "
             "with friction). Ratios are periodic / reference, for the peak contact force and the max normal "
             "stress; the statuses are the gate's (a `hertz_invalid` solution keeps its values).", "",
             _row("rpm", "inclination", "reference: whirl, peak force [lbf], max normal stress [psi]", "fast",
                  "damped", "damped: c [N s/m²], ζ₁, end moment [lbf ft], energy residual"),
             _row(*["---"] * 6)]
    closer, compared, changes, stress_ratios, untouched, tolerances = 0, 0, [], [], 0, []
    for rpm, inclination in DAMPED_POINTS:
        inputs = {**point, "rotary_speed": convert(rpm, "rpm", "rad/s"), "inclination": np.radians(inclination),
                  "impact_pattern": "one_wall", "closure": "self_consistent"}
        ref = solve_point(inputs, "reference")
        r = ref.values
        # an answer, converged or with its error stated (a chaotic bouncing's figures are statistics of a window)
        touches = ref.status in ("ok", "not_converged") and r.get("peak_contact_force", 0.0) > 0
        quick, slow = solve_point(inputs, "fast"), solve_point(inputs, "damped")
        cell_fast, far_fast = _compared(quick, r if touches else None)
        cell_damped, far_damped = _compared(slow, r if touches else None)
        if np.isfinite(far_fast) and np.isfinite(far_damped):
            compared += 1
            closer += far_damped < far_fast
            stress_ratios.append(slow.values["max_normal_stress"] / r["max_normal_stress"])
        untouched += not touches and "span_length" in slow.values
        if "span_length" in quick.values and "span_length" in slow.values:
            changes.append(slow.values["max_normal_stress"] / quick.values["max_normal_stress"] - 1.0)
        d = slow.values
        extra = (f"{d['equivalent_damping']:.4g}, {d['damping_ratio']:.3f}, "
                 f"{convert(d['end_moment_amplitude'], 'N*m', 'lbf*ft'):.4g}, {d['energy_residual']:.1e}"
                 if "energy_residual" in d else "-")
        stated = ref.error_estimate if ref.error_estimate is not None and touches else None
        error = f" (error {stated:.0%})" if stated is not None else ""
        row = _row(rpm, f"{inclination}°", f"`{ref.status}` {whirls.get(r.get('whirl_class'), '?')}, "
                   f"{convert(r.get('peak_contact_force', 0.0), 'N', 'lbf'):.4g}, "
                   f"{r.get('max_normal_stress', float('nan')) / psi:.4g}{error}", cell_fast, cell_damped, extra)
        if stated is not None:  # the reference's figures are a window's statistics: twice their stated error
            tolerances.append(2.0 * stated)
            row = Uncertain(row, tolerances[-1])
        lines.append(row)
    change = f"{100 * min(changes):+.0f} to {100 * max(changes):+.0f} %" if changes else "-"
    ratio = f"{min(stress_ratios):.3g}-{max(stress_ratios):.3g}" if stress_ratios else "-"
    lines += ["",
              Uncertain(f"Where both strike the wall ({compared} points) the damped solution is nearer the reference "
                        "model "
              f"than the undamped one at {closer} (by the larger |log ratio| of force and stress); its max normal "
              f"stress is {ratio} times the reference's there. Keeping the drag moves the max normal stress of the "
              f"undamped solution by {change} on these points. At {untouched} points the damped solution strikes the "
              "wall where the reference model whirls clear of it. The end moments' work equals the drag's dissipation "
              "to the energy residual shown (tests/solvers/test_damped.py asserts < 1e-3 at the paper's "
              "point).", max(tolerances, default=0.0)), "",
              "Near the paper's span: every root of the damped condition 2 between "
              f"{PAPER_SPAN_WINDOW[0]:.0f} and {PAPER_SPAN_WINDOW[1]:.0f} ft, found directly (201 spans sampled, "
              "sign changes refined; `damped.scan`) with the paper's assumed-mode damping, at the paper's point "
              "(300 rpm, vertical), in the four readings; beside it the first valid span of `study point --method "
              "damped` (with the gate's status):", "",
              _row("pattern", "closure", "damped roots near 345 ft [ft]: verdict", "first valid damped span"),
              _row(*["---"] * 4)]
    low, high = (convert(v, "ft", "m") for v in PAPER_SPAN_WINDOW)
    roots_found, valid = 0, 0
    for pattern in ("alternating", "one_wall"):
        for closure in ("prescribed", "self_consistent"):
            inputs = {**point, "impact_pattern": pattern, "closure": closure}
            scene, options = periodic.make_scene(inputs), periodic.options_from(inputs)
            roots = damped.scan(scene, options, damped.assumed_damping(scene), low, high)
            roots_found += len(roots)
            valid += sum(problem is None for _, problem in roots)
            cells = "; ".join(f"{convert(span, 'm', 'ft'):.1f}: {(problem or 'valid').replace('|', '&#124;')}"
                              for span, problem in roots)
            result = solve_point(inputs, "damped")
            first = (f"{convert(result.values['span_length'], 'm', 'ft'):.2f} ft (`{result.status}`)"
                     if "span_length" in result.values else f"none (`{result.status}`)")
            lines.append(_row(pattern, closure, cells or "none", first))
    lines += ["", f"{roots_found} damped root(s) of condition 2 near the paper's span in the four readings, {valid} "
              "satisfying condition 1: " + ("a reading now gives a span near 345 ft." if valid else
                                            "no reading gives a valid span near the paper's 345 ft with the drag "
                                            "kept either."), ""]
    return lines


#: Points of the default study's grid in the hierarchy's held-back sample (every k-th point, k = size / this).
HIERARCHY_SAMPLE = 12


def hierarchy_sample(count: int = HIERARCHY_SAMPLE) -> list[dict]:
    """Every k-th point of the default study's grid solved by ``auto``; where a cheaper model than the reference
    answered, the reference model too (held back): method, wall times and values."""
    study = load(STUDY_CONFIG)
    grid = study_grid(study)
    step = max(grid.size // count, 1)
    rows = []
    for inputs in grid.points(range(step // 2, grid.size, step)):
        auto = solve_point(inputs, "auto")
        ref = solve_point(inputs, "reference") if auto.method != "reference" else auto
        rows.append(dict(inputs=inputs, method=auto.method, status=auto.status, ref_status=ref.status,
                         auto_time=auto.wall_time, ref_time=ref.wall_time, auto=auto.values, ref=ref.values,
                         errors=(auto.error_estimate, ref.error_estimate)))
    return rows


def hierarchy_section(count: int = HIERARCHY_SAMPLE) -> list[str]:
    """The default study's model hierarchy on a sample: which model answered, what it cost against the reference
    model everywhere, and how far the cheap answers are from the reference's (held back)."""
    rows = hierarchy_sample(count)
    psi = convert(1.0, "psi", "Pa")
    lines = [
        "## The default study's model hierarchy against the reference model (configs/default.toml)", "",
        f"{len(rows)} points spread evenly over the default study's {load(STUDY_CONFIG).size}-point grid, solved by "
        "`auto` (the free whirl where the pipe stays clear of the wall, the sliding state where it lies on its tool "
        "joints, else the reference model); where a cheaper model answered, the reference model was run too, held "
        "back. Stresses in psi.", "",
        "| dogleg [°/100 ft] | rpm | tension [lbf] | e | mud [ppg] | flow [ft/s] | auto's model | max normal stress: "
        "auto / reference | alternating: auto / reference | max deflection: auto / reference [in] |",
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |",
    ]
    errors = {"max_normal_stress": [], "max_deflection": []}
    alternating, tolerances = [], []
    for r in rows:
        i, a, ref = r["inputs"], r["auto"], r["ref"]
        dogleg = convert(float(i.get("dogleg_curvature") or 0.0), "1/m", "deg_per_100ft")
        cells = [f"{dogleg:.3g}", f"{convert(i['rotary_speed'], 'rad/s', 'rpm'):.0f}",
                 f"{convert(i['axial_tension'], 'N', 'lbf'):.0f}",
                 f"{i['restitution']:g}", f"{convert(i['mud_density'], 'kg/m^3', 'ppg'):.3g}",
                 f"{convert(i['mud_flow_velocity'], 'm/s', 'ft/s'):.3g}", f"`{r['method']}` ({r['status']})"]
        for name, unit in (("max_normal_stress", psi), ("alternating_bending_stress", psi),
                           ("max_deflection", 0.0254)):
            cells.append(f"{a.get(name, np.nan) / unit:.4g} / {ref.get(name, np.nan) / unit:.4g}")
        # the figures' stated errors (a chaotic bouncing's are a window's statistics): twice the larger, the line's
        # tolerance on another machine
        stated = max((e for e in r["errors"] if e is not None), default=0.0)
        tolerances.append(2.0 * stated)
        lines.append(Uncertain(_row(*cells), tolerances[-1]))
        if r["method"] != "reference" and r["status"] == "ok" and r["ref_status"] == "ok":
            for name in errors:
                errors[name].append(abs(a[name] / ref[name] - 1.0))
            alternating.append(abs(a["alternating_bending_stress"] - ref["alternating_bending_stress"]) / psi)
    methods = [r["method"] for r in rows]
    shares = ", ".join(f"`{m}` {methods.count(m)} of {len(rows)}" for m in dict.fromkeys(methods))
    worst = {k: (max(v) if v else float("nan")) for k, v in errors.items()}
    lines += ["",
              f"Which model answered: {shares} (the time it saves against the reference model everywhere is measured "
              f"by `make bench`, docs/performance.md). Where a cheaper model answered `ok` "
              f"({len(errors['max_normal_stress'])} points) it is within "
              f"{100 * worst['max_normal_stress']:.2g} % of the reference model's max normal stress and "
              f"{100 * worst['max_deflection']:.2g} % of its deflection, and its alternating stress within "
              f"{max(alternating, default=float('nan')):.3g} psi: the reference model's 40-revolution transient and "
              "6-revolution window have not settled onto the sliding state, which it reaches over hundreds of "
              "revolutions (docs/reference_model.md §10).", ""]
    return lines


def record_lines() -> list[str]:
    """The validation report's lines (:class:`Uncertain` where its numbers are a chaotic motion's statistics)."""
    lines = ["# Validation", "",
             f"Generated by `study validate --out docs/validation.md` (`make validate`), study {__version__}. "
             "Every computed value below is produced by the code at the time of generation.", ""]
    lines += (hertz_table_section() + impact_constants_section() + textbook_section() + paper_example_section()
              + cross_check_section() + periodic_solution_section() + damped_section() + replay_section()
              + survey_section()
              + hierarchy_section() + coverage_section())
    return lines


def coverage_section() -> list[str]:
    """The held-back coverage of the stated errors, from the results ``study coverage`` stored (docs/coverage.json;
    :func:`study.coverage.coverage_section`): read, not computed, so that ``study validate`` stays fast."""
    from study.coverage import coverage_section as stored

    return stored()


def run_validate(lines: list[str] | None = None) -> str:
    """The validation report as markdown (of ``lines``, default :func:`record_lines` computed now)."""
    return "\n".join(record_lines() if lines is None else lines).rstrip() + "\n"
