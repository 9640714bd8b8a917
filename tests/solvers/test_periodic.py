"""The periodic solution's closure, pole location and span search (study.solvers.methods.periodic)."""

import re
from pathlib import Path

import numpy as np
import pytest

from study.solvers.kernels import extremes
from study.solvers.kernels import impact as impact_model
from study.solvers.methods.periodic import span_search
from study.solvers.methods import periodic

ROOT = Path(__file__).resolve().parents[2]
RPM = np.pi / 30


def scene_of(inputs, pattern, closure, rpm=300.0):
    return periodic.make_scene({**inputs, "impact_pattern": pattern, "closure": closure, "rotary_speed": rpm * RPM})


@pytest.mark.parametrize("pattern", ["alternating", "one_wall"])
def test_poles_are_where_a_natural_frequency_meets_a_harmonic(paper_inputs, pattern):
    # docs/model.md §4: the undamped periodic response has a pole where omega_n tau/2pi is a harmonic of the
    # train - any integer (one_wall) or an odd integer (alternating).
    scene = scene_of(paper_inputs, pattern, "prescribed")
    modes = impact_model.odd_modes(9)
    poles = impact_model.resonant_spans(scene, modes, 10.0, 300.0)
    assert poles.size > 10 and np.all(np.diff(poles) > 0)
    nu = scene.natural_frequencies(poles, modes) * scene.period / (2 * np.pi)  # (poles, modes)
    nearest = np.round(nu)
    hit = np.abs(nu - nearest) < 1e-9 * nu
    if pattern == "alternating":
        hit &= nearest % 2 == 1
    assert np.all(hit.any(axis=1))


def test_galloping_search_is_numpy_s_searchsorted():
    # source: np.searchsorted(side="right"), over arrays with repeated values, keys outside and on the values,
    # and hints anywhere (before, inside, past the end)
    rng = np.random.default_rng(0)
    for _ in range(3000):
        values = np.sort(rng.integers(0, 20, rng.integers(0, 40)).astype(float))
        x = float(rng.integers(-2, 23)) + rng.choice([0.0, 0.5])
        hint = int(rng.integers(-3, values.size + 4))
        assert span_search._search_right(values, x, hint) == np.searchsorted(values, x, side="right")


def test_roots_lie_between_poles_and_zero_the_screening_residual(paper_inputs):
    scene = scene_of(paper_inputs, "alternating", "prescribed")
    options = periodic.Options(modes=11, min_span=20.0, max_span=120.0)
    search = span_search.find_roots(scene, options)
    assert search.roots.size > 0
    poles = impact_model.resonant_spans(scene, impact_model.odd_modes(11), 20.0, 120.0)
    for root, (a, b) in zip(search.roots, search.brackets):
        assert a <= root <= b
        assert not np.any((poles > a) & (poles < b))  # a bracket never straddles a pole
    # located to ROOT_RTOL (relative) where no pole lies within POLE_FREE_WINDOW of that, else to 1e-10:
    # F changes sign within that distance of each root
    all_poles = impact_model.resonances(scene, impact_model.odd_modes(11), 20.0, 120.0)[0]
    reach = (1 + span_search.POLE_FREE_WINDOW) * span_search.ROOT_RTOL * search.roots
    near = np.searchsorted(all_poles, search.roots - reach) < np.searchsorted(all_poles, search.roots + reach)
    width = 1.01 * np.where(near, 1e-10, span_search.ROOT_RTOL) * search.roots
    below, above = search.residual(search.roots - width), search.residual(search.roots + width)
    assert np.all(np.sign(below) * np.sign(above) <= 0)
    assert np.count_nonzero(~near) > 0.9 * near.size


def test_refined_root_satisfies_condition_2_exactly(paper_inputs):
    # Condition 2 (docs/model.md §4): y(L/2, 0) = c with the exact T_L and contact curvature of the solution.
    scene = scene_of(paper_inputs, "alternating", "prescribed")
    options = periodic.Options(modes=15, min_span=9.0)
    search = span_search.find_roots(scene, options)
    refined = [impact_model.refine_root(scene, options, float(r), b) for r, b in zip(search.roots, search.brackets)]
    good = [i for i in refined if not i.problems]
    assert len(good) >= 5
    for impact in good:
        y1, _, curv1 = impact_model.unit_state(scene, impact.span_length, impact.contact_duration,
                                           impact.contact_half_length, options)
        assert -impact.impulse * y1 == pytest.approx(scene.clearance, rel=1e-7)
        # The contact curvature is the solution's own: kappa = -y''(L/2, 0).
        assert impact.axial_curvature == pytest.approx(impact.impulse * curv1, rel=1e-6)


def test_prescribed_closure_uses_omega_c(paper_inputs):
    scene = scene_of(paper_inputs, "alternating", "prescribed")
    impact = impact_model.impact_at(scene, 100.0, periodic.Options(modes=11))
    assert impact.impact_velocity == pytest.approx(scene.rotary_speed * scene.clearance)
    assert impact.impulse == pytest.approx(impact.equivalent_mass * (1 + scene.restitution) * impact.impact_velocity)


def test_resonance_width_is_the_residue_of_the_resonant_term(paper_inputs):
    # source: the definition - near its pole the resonant mode's term of F is R/(L - L_p) (a simple pole):
    # term x (L - L_p) is the same R on both sides, 1e-9 L_p and 1e-10 L_p from the pole, and width = |R|/L_p.
    scene = scene_of(paper_inputs, "alternating", "prescribed", rpm=100.0)
    options = periodic.Options(modes=15, min_span=9.0, max_span=120.0)
    poles, modes = impact_model.resonances(scene, impact_model.odd_modes(15), 9.0, 120.0)
    residual = span_search.screen_residual(scene, options)
    pick = np.linspace(0, poles.size - 1, 12).astype(int)
    widths = span_search.resonance_widths(residual, poles[pick], modes[pick])
    for eps in (1e-9, 1e-10, -1e-9, -1e-10):
        near = poles[pick] * (1 + eps)
        residue = residual(near, modes=modes[pick, None]) * (near - poles[pick])
        np.testing.assert_allclose(np.abs(residue) / poles[pick], widths, rtol=1e-4)
    assert np.all(widths > 0)


@pytest.mark.parametrize("pattern, closure", [("alternating", "prescribed"), ("one_wall", "self_consistent")])
def test_residues_skipped_below_a_floor_are_certainly_below_it(paper_inputs, pattern, closure):
    # source: the definition of the bound - |g_n H(w)| <= min(1, 1/|u^2 - 1|) for a non-negative load and
    # pulse; a residue is left out (NaN) only when that bound, hence |R|, is below the floor. Every pole of
    # the point up to 150 m: with the floor just under each exact |R| none is left out (the bound is never
    # below |R|); with the search's floor (1e-6 L) the ones left out are exactly narrow, and they are most.
    scene = scene_of(paper_inputs, pattern, closure, rpm=100.0)
    options = periodic.Options(modes=41, max_span=150.0)
    poles, modes = impact_model.resonances(scene, impact_model.odd_modes(41), options.min_span, options.max_span)
    residual = span_search.screen_residual(scene, options)
    exact = residual.residue(poles, modes)
    assert np.all(np.isfinite(exact))
    assert not np.any(np.isnan(residual.residue(poles, modes, np.abs(exact) * (1 - 1e-12))))
    floors = options.resonance_width * poles
    skipped = np.isnan(residual.residue(poles, modes, floors))
    assert np.all(np.abs(exact[skipped]) < floors[skipped])
    assert np.count_nonzero(skipped) > 0.5 * np.count_nonzero(np.abs(exact) < floors)


def test_narrow_resonances_only_hide_the_roots_pinned_to_them(paper_inputs):
    # The search with every pole (resonance_width = 0) against the default (1e-6): the default finds no
    # root the full search does not, and every root it skips lies within 1e-5 L of a resonance narrower
    # than 1e-6 L (the root such a resonance pins; any damping of that order removes it, docs/model.md §7).
    scene = scene_of(paper_inputs, "alternating", "prescribed", rpm=100.0)
    options = periodic.Options(modes=15, min_span=9.0, max_span=120.0)
    full = span_search.find_roots(scene, periodic.Options(**{**options.__dict__, "resonance_width": 0.0}))
    cut = span_search.find_roots(scene, options)
    assert full.narrow_count == 0 and cut.narrow_count > 10 and cut.pole_count == full.pole_count
    poles, modes = impact_model.resonances(scene, impact_model.odd_modes(15), 9.0, 120.0)
    widths = span_search.resonance_widths(cut.residual, poles, modes)

    def missing(a, b):
        return [r for r in a if np.min(np.abs(b - r)) > 2.0 * span_search.ROOT_RTOL * r]  # each located to ROOT_RTOL

    assert missing(cut.roots, full.roots) == []
    skipped = missing(full.roots, cut.roots)
    assert 10 < len(skipped) < full.roots.size / 4
    for root in skipped:
        nearest = np.argmin(np.abs(poles - root))
        assert abs(poles[nearest] - root) < 1e-5 * root and widths[nearest] < 1e-6


@pytest.mark.parametrize("pattern, closure", [("alternating", "prescribed"), ("one_wall", "self_consistent")])
def test_many_spans_at_once_solve_each_as_alone(paper_inputs, pattern, closure):
    # source: the definition - impacts_at iterates every span's own T_L-curvature fixed point; masking the
    # finished spans must not change the others. Spans from 5 to 200 m, one on a resonance pole (which
    # fails), and a mixture of converging and rejected ones (not convex, not approaching).
    scene = scene_of(paper_inputs, pattern, closure)
    options = periodic.Options(modes=11)
    pole = impact_model.resonant_spans(scene, impact_model.odd_modes(11), 30.0, 200.0)[0]
    spans = np.concatenate([np.geomspace(5.0, 200.0, 23), [pole]])
    batch = impact_model.impacts_at(scene, spans, options)
    alone = [impact_model.impact_at(scene, float(L), options) for L in spans]
    assert {tuple(i.problems) for i in batch} != {()}  # some spans fail ...
    assert any(not i.problems for i in batch)  # ... and some converge
    assert any("resonance" in p for p in batch[-1].problems)
    for b, a in zip(batch, alone):
        assert b.problems == a.problems
        assert b.iterations == a.iterations
        for name in ("residual", "impulse", "impact_velocity", "contact_duration", "peak_contact_force",
                     "contact_half_length", "axial_curvature", "hertz_duration"):
            np.testing.assert_array_equal(getattr(b, name), getattr(a, name), err_msg=name)


def test_roots_refined_together_are_refined_as_alone(paper_inputs):
    # source: the definition - refine_roots moves every root by its own secant steps inside its own bracket.
    scene = scene_of(paper_inputs, "alternating", "prescribed")
    options = periodic.Options(modes=15, min_span=9.0)
    search = span_search.find_roots(scene, options)
    roots, brackets = search.roots, search.brackets
    together = impact_model.refine_roots(scene, options, roots, brackets)
    alone = [impact_model.refine_root(scene, options, float(r), b) for r, b in zip(roots, brackets)]
    assert sum(not i.problems for i in together) >= 5
    assert any(i.problems for i in together)
    for t, a in zip(together, alone):
        assert t.problems == a.problems
        assert t.span_length == a.span_length and t.contact_duration == a.contact_duration \
            or (np.isnan(t.contact_duration) and np.isnan(a.contact_duration))


def test_rejected_roots_are_counted_by_kind(paper_inputs):
    # source: the definition - the no_span message counts the rejections by kind (condition 1, not convex,
    # ...), not one line per value of |y|/c or of the residual.
    import re

    scene = scene_of(paper_inputs, "alternating", "prescribed")
    choice = periodic.find_span(scene, periodic.Options(modes=11))
    assert sum(len(v) for v in choice.reasons.values()) >= 3
    assert not [key for key in choice.reasons if re.search(r"\d\.\d", key)]


@pytest.mark.parametrize("pattern, closure, rpm", [("alternating", "self_consistent", 300.0),
                                                   ("one_wall", "self_consistent", 100.0)])
def test_condition_1_for_many_impacts_is_the_check_on_the_whole_grid(paper_inputs, pattern, closure, rpm):
    # source: the definition of condition 1 - |y| <= c (1 + tolerance) everywhere on the span x period grid
    # outside the contact, from the field solution (beam.deflection) per impact; the batched check starts
    # at the midspan with the compiled modal sum and stops at the first time past the wall, which it
    # reports: there the field itself is that far past the wall. Every refined root of the point (spans
    # 3-120 m) is checked both ways; some pass.
    scene = scene_of(paper_inputs, pattern, closure, rpm)
    options = periodic.Options(modes=21, max_span=120.0)
    search = span_search.find_roots(scene, options)
    durations, halves = search.residual.pulse(search.roots)
    refined = [i for i in impact_model.refine_roots(scene, options, search.roots, search.brackets, durations=durations,
                                                halves=halves) if not i.problems]
    assert len(refined) > 20
    problems = periodic.constraint_violations(scene, refined, options)
    p = scene.props
    verdicts = set()
    for impact, problem in zip(refined, problems):
        x = periodic.space_grid(impact.span_length, impact.contact_half_length, options)
        t = periodic.time_grid(scene, impact.contact_duration, options)
        y = periodic.beam.deflection(x, t, impact.span_length, p["bending_stiffness"], p["effective_tension"],
                                     p["mass_per_length"], -impact.impulse, impact.contact_duration, scene.period,
                                     scene.pattern, impact.contact_half_length, options.load_shape, options.modes)
        contact = (np.abs(x - 0.5 * impact.span_length) <= impact.contact_half_length)[None, :] \
            & (t <= impact.contact_duration)[:, None]
        passes = np.max(np.where(contact, 0.0, np.abs(y))) <= scene.clearance * (1 + options.tolerance)
        assert (problem is None) == passes, (impact.span_length, problem)
        verdicts.add(problem is None)
        if problem and f"x = {0.5 * impact.span_length:.4g} m" in problem:  # found at the midspan: where
            ratio, when = (float(v) for v in re.search(r"reaches (\S+) c at .* t = (\S+) s", problem).groups())
            assert ratio >= 1.0  # past c (1 + tolerance), printed to 4 digits
            mid = np.argmin(np.abs(x - 0.5 * impact.span_length))
            near = np.abs(t - when) <= 5e-4 * when  # the time printed to 4 digits
            assert np.any(np.abs(np.abs(y[near, mid]) / scene.clearance - ratio) <= 5e-4 * ratio)
    assert verdicts == {True, False}


def test_field_extremes_ignore_nan_as_numpy_does():
    # source: numpy's nanargmax and the NaN-propagating max/min along the time axis, which the compiled
    # pass over the field replaces; a field sliced from a wider one (any memory layout).
    rng = np.random.default_rng(3)
    wide = rng.normal(size=(40, 30))
    field = wide[:, 10:20]
    field[5, 3] = np.nan
    index, largest, smallest = extremes._field_extremes(field, columns=True)
    assert index == np.unravel_index(np.nanargmax(np.abs(field)), field.shape)
    np.testing.assert_array_equal(largest, field.max(axis=0))  # NaN in column 3
    np.testing.assert_array_equal(smallest, field.min(axis=0))
    with pytest.raises(ValueError, match="all the field's values are NaN"):
        extremes._field_extremes(np.full((3, 4), np.nan))


@pytest.mark.parametrize("jitter", [-1e-13, 0.0, 1e-13])
def test_field_extremes_report_the_first_of_equal_maxima(jitter):
    # source: the definition (extremes.TIE_TOLERANCE) - a maximum reached twice, at t index 7 and 31
    # (a symmetric motion), differing only by rounding: the earlier one is reported whichever is larger.
    field = np.zeros((40, 6))
    field[7, 2] = -5.0
    field[31, 4] = 5.0 * (1.0 + jitter)
    assert extremes._field_extremes(field)[0] == (7, 2)
    field[31, 4] = 5.0 * (1.0 + 1e-6)  # a real difference still wins
    assert extremes._field_extremes(field)[0] == (31, 4)


@pytest.mark.parametrize("low, high", [(5.2035, 5.2065), (3.1900, 3.1930), (4.7480, 4.7520)])
def test_every_root_of_the_continuous_residual_is_kept(paper_inputs, low, high):
    # source: the intermediate value theorem - F is continuous between its poles, so a sign change
    # between two scan points with no pole between them is a root. A dense scan of short windows of the
    # paper's point (one wall, self-consistent V_p; roots pinned beside wide poles among them) finds such
    # roots; the search keeps each one, however close one of its samples lies to it (a test of |F|
    # against the samples' values once rejected some), except those within 1e-5 L of a resonance
    # narrower than 1e-6 L, which it does not search by design (see the test above).
    scene = scene_of(paper_inputs, "one_wall", "self_consistent")
    options = periodic.Options(modes=21)
    search = span_search.find_roots(scene, options)
    poles, modes = impact_model.resonances(scene, impact_model.odd_modes(21), options.min_span, options.max_span)
    narrow = poles[span_search.resonance_widths(search.residual, poles, modes) < options.resonance_width]
    x = np.linspace(low, high, 30001)
    f = search.residual(x)
    change = np.nonzero(np.sign(f[:-1]) * np.sign(f[1:]) < 0)[0]
    free = np.searchsorted(poles, x[change], side="right") == np.searchsorted(poles, x[change + 1], side="left")
    pinned = np.searchsorted(narrow, x[change] * (1 - 1e-5)) < np.searchsorted(narrow, x[change + 1] * (1 + 1e-5))
    cells = change[free & ~pinned]
    assert cells.size >= 1
    slack = 1.01 * span_search.ROOT_RTOL  # a root is located to ROOT_RTOL (relative) at worst
    for k in cells:
        assert np.any((search.roots >= x[k] * (1 - slack)) & (search.roots <= x[k + 1] * (1 + slack))), (x[k], x[k + 1])


def test_roots_pinned_closer_to_a_wide_pole_than_any_sample_are_kept(paper_inputs):
    # source: the definition of the residue - G = F (L - a)(b - L) tends to R_a (b - a) at the pole a, so the
    # search takes G's value at each wide pole in closed form and brackets a root however close to the pole
    # it is pinned (the samples once started a thousandth of the resonance width inside each pole and
    # missed the roots closer than that). F scanned from 1e-7 to 3e-3 of |R| on both sides of every wide
    # pole of the paper's point (one wall, self-consistent V_p, spans 3-40 m): each sign change with no
    # pole between its scan points is a root the search kept, and some lie within 1e-3 |R| of their pole.
    scene = scene_of(paper_inputs, "one_wall", "self_consistent")
    options = periodic.Options(modes=21, max_span=40.0)
    search = span_search.find_roots(scene, options)
    poles, modes = impact_model.resonances(scene, impact_model.odd_modes(21), options.min_span, options.max_span)
    residues = search.residual.residue(poles, modes)
    wide = np.abs(residues) >= options.resonance_width * poles
    fractions = np.geomspace(1e-7, 3e-3, 200)
    closest = []
    for pole, residue in zip(poles[wide], np.abs(residues[wide])):
        for side in (-1.0, 1.0):
            x = pole + side * residue * fractions
            f = search.residual(x)
            change = np.nonzero(np.sign(f[:-1]) * np.sign(f[1:]) < 0)[0]
            for k in change:
                a, b = sorted((x[k], x[k + 1]))
                if np.searchsorted(poles, a, side="right") != np.searchsorted(poles, b, side="left"):
                    continue  # a narrow pole between the scan points: a sign change, not a root
                slack = 1.01 * span_search.ROOT_RTOL  # a root is located to ROOT_RTOL (relative) at worst
                assert np.any((search.roots >= a * (1 - slack)) & (search.roots <= b * (1 + slack))), (pole, a, b)
                closest.append(fractions[k + 1])
    assert len(closest) > 5 and min(closest) < 1e-3


def test_refinement_and_iteration_say_why_they_stopped(paper_inputs):
    # source: the definition - a root whose secant step leaves its bracket, one still off in F when the steps
    # run out, and a T_L-curvature iteration cut short each carry their own problem, with the solution
    # they reached (a span that fails inside the iteration carries none).
    scene = scene_of(paper_inputs, "alternating", "prescribed")
    options = periodic.Options(modes=15, min_span=9.0)
    search = span_search.find_roots(scene, options)
    good = [k for k, i in enumerate(impact_model.refine_roots(scene, options, search.roots, search.brackets))
            if not i.problems]
    root = float(search.roots[good[0]])
    tight = impact_model.refine_root(scene, options, root, (root * (1 - 1e-13), root * (1 + 1e-13)))
    assert tight.problems == ["the exact root left the interval between the searched poles around the screening root"]
    assert np.isfinite(tight.contact_duration)
    cut = impact_model.refine_root(scene, options, root, search.brackets[good[0]], steps=0)
    assert len(cut.problems) == 1 and cut.problems[0].startswith("condition 2 residual ")
    assert abs(cut.residual) > 1e-8 and cut.problems[0].endswith(" after refinement")
    short = impact_model.impact_at(scene, root, options, max_iterations=2)
    assert short.problems == ["T_L–curvature iteration not converged in 2 steps"] and short.iterations == 2
    assert np.isfinite(short.contact_duration)


def test_search_keeps_the_midspan_state_at_each_root(paper_inputs):
    # source: the definition - the regula falsi evaluates y1, v1, y1'' with F at every point; the state it
    # keeps for a root is unit_state there with the screening pulse (the midspan screen's input), to rounding
    # (the compiled and the numpy paths may order a sum differently: 1e-16 absolute seen on one machine).
    scene = scene_of(paper_inputs, "one_wall", "self_consistent")
    options = periodic.Options(modes=21, max_span=60.0)
    search = span_search.find_roots(scene, options)
    duration, half = search.residual.pulse(search.roots)
    expected = np.array(impact_model.unit_state(scene, search.roots, duration, half, options))
    known = ~np.isnan(search.states[0])
    assert search.states.shape == (3, search.roots.size) and np.mean(known) > 0.9
    np.testing.assert_allclose(search.states[:, known], expected[:, known], rtol=1e-12, atol=0)


def test_roots_between_runs_of_intervals_are_the_search_over_all_of_them(paper_inputs):
    # source: the definition - each interval's roots depend on that interval alone, so the search over two runs
    # of intervals is find_roots over all of them, root for root
    scene = scene_of(paper_inputs, "one_wall", "self_consistent", rpm=150.0)
    options = periodic.Options(modes=11, min_span=5.0, max_span=40.0)
    intervals = span_search.search_intervals(scene, options)
    whole = span_search.find_roots(scene, options)
    assert whole.roots.size > 20 and intervals.lo.size > 20
    assert np.all(intervals.hi > intervals.lo) and np.all(intervals.lo[1:] == intervals.hi[:-1])
    half = intervals.lo.size // 2
    parts = [span_search.roots_between(intervals, 0, half, options),
             span_search.roots_between(intervals, half, intervals.lo.size, options)]
    np.testing.assert_array_equal(np.concatenate([p.roots for p in parts]), whole.roots)
    np.testing.assert_array_equal(np.concatenate([p.brackets for p in parts]), whole.brackets)
    assert np.all(parts[0].brackets[:, 1] <= intervals.hi[half - 1]) and np.all(parts[1].roots > intervals.hi[half - 1])


def test_search_that_stops_at_the_first_valid_span_reports_the_same_smallest_span(paper_inputs, monkeypatch):
    # source: the definition (docs/model.md §4.5) - stopping after the run of intervals that holds the first valid
    # span finds the smallest valid span of the whole search; its roots are the whole search's up to where it
    # stopped, and it counts fewer (runs of 16, 32, 64, ... of the 1242 intervals here: it stops at 1008)
    monkeypatch.setattr(periodic, "FIRST_RUN", 16)
    scene = scene_of(paper_inputs, "one_wall", "self_consistent", rpm=300.0)
    options = periodic.Options(modes=11, max_span=60.0)
    whole, first = periodic.find_span(scene, options), periodic.find_span(scene, options, first=True)
    assert len(whole.candidates) >= 2 and whole.searched_to == options.max_span
    assert first.candidates[0].span_length == whole.candidates[0].span_length
    assert first.searched_to < options.max_span and "the search stopped past the first valid span" in first.summary
    assert 1 <= len(first.candidates) <= len(whole.candidates)
    assert 0 < first.search.roots.size < whole.search.roots.size
    np.testing.assert_array_equal(first.search.roots, whole.search.roots[:first.search.roots.size])
    assert np.all(first.search.roots <= first.searched_to)


def test_sign_changes_and_real_roots_are_the_numpy_formulas():
    # source: the numpy expressions they replace (G = F (L - lo)(hi - L), its ends R (hi - lo) and -R (hi - lo) at a
    # pole; a root is unsure where a pole lies in its widened last bracket), on random intervals and poles
    rng = np.random.default_rng(3)
    edges = np.cumsum(rng.uniform(0.5, 1.5, 41)) + 3.0
    lo, hi = edges[:-1], edges[1:]
    residue_lo, residue_hi = rng.normal(size=40), rng.normal(size=40)
    residue_lo[0], residue_hi[-1] = np.nan, np.nan  # the search range's ends
    fractions = np.array([0.1, 0.4, 0.8])
    spans, inside = span_search._sample_spans(lo, hi, residue_lo, residue_hi, fractions)
    assert spans.shape == (40, 5) and inside.size == 40 * 3 + 2
    np.testing.assert_array_equal(spans[:, 1:-1], lo[:, None] + (hi - lo)[:, None] * fractions)
    assert spans[0, 0] == lo[0] * (1 + 1e-12) and spans[-1, -1] == hi[-1] * (1 - 1e-12)
    f = rng.normal(size=inside.size)
    values = np.full(spans.shape, np.inf)
    mask = np.ones(spans.shape, dtype=bool)
    mask[1:, 0], mask[:-1, -1] = False, False
    values[mask] = f
    with np.errstate(invalid="ignore"):
        g = values * (spans - lo[:, None]) * (hi[:, None] - spans)
    g[1:, 0], g[:-1, -1] = (residue_lo * (hi - lo))[1:], (-residue_hi * (hi - lo))[:-1]
    i, j = np.nonzero(np.sign(g[:, :-1]) * np.sign(g[:, 1:]) < 0)
    out = span_search._sign_changes(spans, f, lo, hi, residue_lo, residue_hi)
    assert i.size > 20
    np.testing.assert_array_equal(out, [spans[i, j], spans[i, j + 1], g[i, j], g[i, j + 1], lo[i], hi[i],
                                        np.minimum(np.abs(values[i, j]), np.abs(values[i, j + 1]))])
    roots = 0.5 * (out[0] + out[1])
    poles = np.sort(np.concatenate([edges, rng.uniform(edges[0], edges[-1], 200)]))
    start = np.maximum(out[0] - 1e-12 * out[1], out[4] * (1 + 2e-12))
    stop = np.minimum(out[1] + 1e-12 * out[1], out[5] * (1 - 2e-12))
    unsure = np.searchsorted(poles, start, side="left") < np.searchsorted(poles, stop, side="right")
    root_values = rng.normal(size=roots.size) * 1e-3
    with np.errstate(divide="ignore"):
        real = ~unsure | (np.abs(root_values / ((roots - out[4]) * (out[5] - roots))) < 1e-3 * out[6])
    assert unsure.any() and (~unsure).any()
    np.testing.assert_array_equal(span_search._real_roots(roots, root_values, out[0], out[1], out[4], out[5], out[6],
                                                       poles), real)


def test_shrink_tail_in_one_compiled_loop_shrinks_as_the_rounds_one_by_one(paper_inputs, monkeypatch):
    # source: the definition - the compiled tail takes the same regula falsi steps; only the pulse's log and exp
    # (the C library's instead of numpy's) may differ in the last bits
    scene = scene_of(paper_inputs, "one_wall", "self_consistent", rpm=150.0)
    options = periodic.Options(modes=11, min_span=5.0, max_span=40.0)
    monkeypatch.setattr(span_search, "SHRINK_TAIL", 0)
    rounds = span_search.find_roots(scene, options)
    monkeypatch.setattr(span_search, "SHRINK_TAIL", 10**9)
    tail = span_search.find_roots(scene, options)
    assert rounds.roots.size > 20
    np.testing.assert_array_equal(tail.brackets, rounds.brackets)
    np.testing.assert_allclose(tail.roots, rounds.roots, rtol=1e-12)
    np.testing.assert_allclose(tail.states, rounds.states, rtol=1e-9)
