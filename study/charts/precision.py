"""Cost against accuracy of the periodic methods (a work-precision diagram, MODEL.md §9)."""

from __future__ import annotations

from matplotlib.figure import Figure

MARKERS = {"fast": "o", "series": "s"}


def work_precision_chart(rows, case: str) -> Figure:
    """Relative error of the max normal and shear stresses against time per evaluation, per method.

    rows: the dicts of :func:`study.solvers.series.convergence_table` (method, modes, harmonics,
    wall_time [s], error, shear_error); case: a one-line description for the title.
    """
    figure = Figure(figsize=(9.0, 4.2), dpi=150, layout="constrained")
    axes = figure.subplots(1, 2, sharex=True)
    for ax, key, label in zip(axes, ("error", "shear_error"), ("max normal stress", "max shear stress")):
        for method in sorted({r["method"] for r in rows}):
            mine = [r for r in rows if r["method"] == method]
            ax.loglog([r["wall_time"] * 1e3 for r in mine], [max(r[key], 1e-16) for r in mine],
                      marker=MARKERS.get(method, "^"), label=method)
            for r in mine:
                tag = f"N={r['modes']}" + (f", M={r['harmonics']}" if r["harmonics"] else "")
                ax.annotate(tag, (r["wall_time"] * 1e3, max(r[key], 1e-16)), fontsize=6,
                            textcoords="offset points", xytext=(3, 3))
        ax.set_xlabel("time per evaluation [ms]")
        ax.set_ylabel(f"relative error, {label} [-]")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    figure.suptitle("Work and precision of the periodic methods\n" + case, fontsize=9)
    return figure
