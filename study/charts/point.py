"""One point, seen: what the pipe does at a design point, from the reference model's motion there
(:mod:`study.solvers.methods.reference`: the section in both lateral directions, with its tool joints and the wall).

Three panels: the orbit of the most-touching point of the section in the hole's cross-section, with the wall (the
clearance circle of that point: the pipe's centre cannot go past it but for the Hertz approach); the normal contact
forces over the recorded window, one line per point that touches; the deflection and the bending stress along the
section at the instant of the largest contact force (the worst instant), with the clearance of every contact point.
Oilfield units.
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np
from matplotlib.figure import Figure

from study.charts.design import DPI, Chart, figure_title
from study.physics import section
from study.units import convert

#: The oilfield units the chart is drawn in, in SI (study.units: pint's definitions).
IN, FT, LBF, PSI = (convert(1.0, unit, si) for unit, si in (("in", "m"), ("ft", "m"), ("lbf", "N"), ("psi", "Pa")))


def point_chart(inputs: Mapping[str, Any]) -> Chart:
    """The reference model's motion at the point ``inputs`` (SI, as :meth:`study.config.Study.point` gives them)
    as a :class:`~study.charts.design.Chart` named "point". Raises ValueError where the model cannot run there
    (a buckled section): the message says why."""
    from study.solvers.methods import reference
    from study.solvers.model.scene import make_scene

    model = reference.build_model(inputs)
    if not np.all(np.isfinite(model.omega)):
        raise ValueError(f"the {model.span:.4g} m section buckles at effective tension "
                         f"{model.props['effective_tension']:.4g} N: no motion to draw")
    run = reference.simulate(inputs, model)
    if run["verdict"] == "failed" or run["window"] is None:
        raise ValueError(f"the reference model failed at this point: {run.get('failure')}")
    window = run["window"]
    measure = reference.whirl_measure(model, window)
    N = model.n_modes
    y = window.states[:, :N] @ model.phi.T  # (R, P) lateral displacement of each contact point [m]
    z = window.states[:, N:2 * N] @ model.phi.T
    touching = np.flatnonzero((window.contact_time > 0) | (window.onsets > 0))
    p = int(np.argmax(window.contact_time)) if touching.size else int(np.argmin(np.abs(model.points - model.span / 2)))
    revolutions = (window.times - window.times[0]) / model.period
    fig = Figure(figsize=(15.0, 5.0), dpi=DPI, layout="constrained")
    orbit, forces, shape = fig.subplots(1, 3, gridspec_kw={"width_ratios": [1.0, 1.4, 1.4]})
    # the orbit in the cross-section, with the wall
    angle = np.linspace(0.0, 2.0 * np.pi, 361)
    wall = model.clearance[p] / IN
    orbit.plot(wall * np.cos(angle), wall * np.sin(angle), color="k", lw=2.0, label="wall (clearance circle)",
               gid="wall")
    orbit.plot(y[:, p] / IN, z[:, p] / IN, color="C0", lw=0.8, label="the pipe's centre")
    orbit.set_aspect("equal")
    orbit.set_xlabel("lateral displacement y [in]")
    orbit.set_ylabel("lateral displacement z [in]")
    orbit.set_title(f"orbit at {model.points[p] / FT:.1f} ft along the section", fontsize=9)
    orbit.legend(fontsize=7, loc="upper right")
    # the contact forces over the window
    shown = touching if touching.size else np.array([p])
    for k in shown:
        forces.plot(revolutions, window.forces[:, k, 2] / LBF, lw=0.9,
                    label=f"{model.points[k] / FT:.1f} ft ({'tool joint' if model.kinds[k] else 'pipe body'})")
    forces.set_xlabel("revolutions of the window")
    forces.set_ylabel("normal contact force [lbf]")
    forces.set_title("contact forces over the window" if touching.size else "no contact in the window", fontsize=9)
    forces.legend(fontsize=7, title="point", title_fontsize=7)
    # the deflection along the section at the worst instant
    worst = int(np.argmax(np.max(window.forces[:, :, 2], axis=1))) if touching.size else \
        int(np.argmax(np.hypot(y[:, p], z[:, p])))
    x = np.linspace(0.0, model.span, 193)
    # the section's fields at that instant in both directions (reference.periodic_fields: the periodic basis, the
    # moment the pipe's whole, the hole's curvature included)
    fy, fz = (reference.periodic_fields(model, window.states[worst:worst + 1, j * N:(j + 1) * N], None, x, j)
              for j in range(2))
    radial = np.hypot(fy["deflection"][0], fz["deflection"][0])
    scene = make_scene(inputs)
    r_o, r_i = float(scene.outer_radius), float(scene.inner_radius)
    bending = np.hypot(fy["moment"][0], fz["moment"][0]) * r_o / float(section.second_moment_of_area(r_o, r_i))
    shape.plot(x / FT, radial / IN, color="C3", lw=1.5, label="radial deflection")
    shape.plot(model.points / FT, model.clearance / IN, ls="none", marker="_", ms=14, mew=2.0, color="k",
               label="clearance at each contact point")
    shape.set_xlabel("position along the section [ft]")
    shape.set_ylabel("radial deflection [in]")
    shape.set_title(f"deflection and bending along the section at the worst instant ({revolutions[worst]:.2f} rev)",
                    fontsize=9)
    stress = shape.twinx()
    stress.plot(x / FT, bending / PSI, color="C2", lw=1.2, ls="--", label="bending stress (right axis)")
    stress.set_ylabel("bending stress M r_o / I [psi]")
    stress.set_ylim(bottom=0.0)
    lines = shape.get_legend_handles_labels()
    more = stress.get_legend_handles_labels()
    shape.legend(lines[0] + more[0], lines[1] + more[1], fontsize=7)
    speed = convert(scene.rotary_speed, "rad/s", "rpm")
    load = scene.axial_tension / LBF
    figure_title(fig, "One point, seen: the reference model's motion", [
        f"{speed:.0f} rpm, {load:,.0f} lbf; whirl {measure['whirl']} ({measure['whirl_frequency_ratio']:+.3f} Ω); "
        f"window of {revolutions[-1]:.1f} revolutions after {run['revolutions']} of transient"], 15.0)
    caption = ("What the pipe does at this point in the reference model: the orbit of its most-touching point inside "
               "the wall, the contact forces over the recorded window, and the deflection and the bending stress along "
               "the section at the instant of the largest force (the modes' fields; the hole's curvature included).")
    return Chart("point", fig, caption)
