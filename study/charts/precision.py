"""Cost against accuracy of the periodic methods (a work-precision diagram, docs/model.md §9)."""

from __future__ import annotations

from matplotlib.figure import Figure

MARKERS = {"fast": "o", "series": "s"}


def work_precision_chart(rows, case: str, title: str = "Work and precision of the periodic methods",
                         time_label: str = "time per evaluation [ms]",
                         labels: tuple[str, str] = ("max normal stress", "max shear stress")) -> Figure:
    """Relative error of two figures (``labels``: the rows' ``error`` and ``shear_error``) against time, per method.

    rows: the dicts of :func:`study.benchmarks.series.convergence_table` (method, modes, harmonics,
    wall_time [s], error: max normal stress, shear_error: max shear stress) or of
    :func:`study.bench.bench_reference_modes` (method the residual law, shear_error the peak contact force's);
    case: a one-line description for the title.
    """
    figure = Figure(figsize=(9.0, 4.2), dpi=150, layout="constrained")
    axes = figure.subplots(1, 2, sharex=True)
    for ax, key, label in zip(axes, ("error", "shear_error"), labels):
        for method in sorted({r["method"] for r in rows}):
            mine = [r for r in rows if r["method"] == method]
            ax.loglog([r["wall_time"] * 1e3 for r in mine], [max(r[key], 1e-16) for r in mine],
                      marker=MARKERS.get(method, "^"), label=method)
            for r in mine:
                tag = (f"N={r['modes']}" + (f", M={r['harmonics']}" if r["harmonics"] else "")
                       + (f", rtol {r['rtol']:g}" if r.get("rtol") else ""))
                ax.annotate(tag, (r["wall_time"] * 1e3, max(r[key], 1e-16)), fontsize=6,
                            textcoords="offset points", xytext=(3, 3))
        ax.set_xlabel(time_label)
        ax.set_ylabel(f"relative error, {label} [-]")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    figure.suptitle(f"{title}\n" + case, fontsize=9)
    return figure


TIME_DOMAIN_STYLE = {"event": ("o", "C0"), "explicit": ("s", "C1"), "implicit": ("D", "C2"),
                     "penalty_rk45": ("^", "C3")}


def time_domain_chart(work_rows, stability_rows, case: str) -> Figure:
    """The time-domain integrators: cost against error, and error against step (failures marked ×).

    work_rows: :func:`study.benchmarks.time_domain.benchmark` rows (name, setting, wall_time [s], error);
    stability_rows: :func:`study.benchmarks.time_domain.step_stability` rows (name, step_ratio, error, NaN
    when failed); case: a one-line description for the title.
    """
    figure = Figure(figsize=(9.0, 4.2), dpi=150, layout="constrained")
    work, steps = figure.subplots(1, 2)
    for name in dict.fromkeys(r["name"] for r in work_rows):
        mine = [r for r in work_rows if r["name"] == name]
        marker, colour = TIME_DOMAIN_STYLE.get(name, ("v", "C4"))
        label = name + (" (linear penalty model)" if name == "penalty_rk45" else "")
        work.loglog([r["wall_time"] * 1e3 for r in mine], [max(r["error"], 1e-16) for r in mine], marker=marker,
                    color=colour, label=label)
    work.set_xlabel("time for the run [ms]")
    work.set_ylabel("error of the final modal state [-]")
    work.set_title("work and precision", fontsize=9)
    for name in dict.fromkeys(r["name"] for r in stability_rows):
        mine = [r for r in stability_rows if r["name"] == name]
        marker, colour = TIME_DOMAIN_STYLE.get(name, ("v", "C4"))
        ok = [r for r in mine if r["error"] == r["error"]]
        steps.loglog([r["step_ratio"] for r in ok], [max(r["error"], 1e-16) for r in ok], marker=marker, color=colour,
                     label=name + (" (RK4 contact step)" if name == "event" else " (Verlet step)"))
        failed = [r for r in mine if r["error"] != r["error"]]
        if failed:
            steps.scatter([r["step_ratio"] for r in failed], [1.0] * len(failed), marker="x", color=colour, s=50,
                          label=f"{name}: failed (blow-up detected)")
    steps.axvline(1.0, color="0.4", lw=0.8, ls="--")
    steps.set_xlabel("step / explicit limit 2/ω_max [-]")
    steps.set_ylabel("error of the final modal state [-]")
    steps.set_title("stability against the contact stiffness", fontsize=9)
    for ax in (work, steps):
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    figure.suptitle("Time-domain integrators\n" + case, fontsize=9)
    return figure
