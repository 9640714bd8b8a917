"""The typed design point every method solves: the Scene and every option, built once from a point's SI inputs.

:meth:`DesignPoint.from_inputs` is the one builder, at the config's edge: :func:`study.solvers.solve_point` calls it
once per point and passes the point to the method (:data:`study.solvers.METHODS`), the ladder (``auto``) passes the
same point to each rung and the checks (``crosscheck``, ``reference-check``) to both methods they run. A parameter
is followed from the TOML (:data:`study.config.FIELDS`) through the point's fields — the
:class:`~study.solvers.model.scene.Scene` and the options of :mod:`study.solvers.model.options` — to the physics.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from types import MappingProxyType
from typing import Any, Mapping

from study.solvers.model.options import (CrosscheckOptions, DampedOptions, LimitOptions, Options, ReferenceOptions,
                                         SdofOptions, SeriesOptions, TimeDomainOptions, Tolerances)
from study.solvers.model.scene import Scene


@dataclass(frozen=True)
class DesignPoint:
    """One design point, typed: its scene, its tolerances and design limits, and each method's options (each field
    built once by :meth:`from_inputs`); ``inputs``, the SI inputs it was built from (read-only), go to the parts of
    the reference and time-domain methods that still take them whole."""

    inputs: Mapping[str, Any]  #: the point's SI inputs, keyed as :data:`study.config.FIELDS` names (read-only)
    scene: Scene  #: the pipe, hole, rock, mud, load and impact
    tolerances: Tolerances  #: solver.tolerance, statistical_tolerance, force_tolerance
    limits: LimitOptions  #: the design limits' settings (the grade, the S-N curve ...)
    periodic: Options  #: the periodic methods' resolution and span search (fast, series, damped, crosscheck)
    series: SeriesOptions  #: the series' harmonics
    damped: DampedOptions  #: the damped solution's harmonics and iteration
    time: TimeDomainOptions  #: the time-domain method's
    sdof: SdofOptions  #: the one-degree-of-freedom screen's (its drive also the time domain's)
    check: CrosscheckOptions  #: the checks' tolerance (crosscheck, reference-check)
    reference: ReferenceOptions  #: the reference model's (also the free whirl's and the sliding state's scene)

    @classmethod
    def from_inputs(cls, inputs: Mapping[str, Any]) -> "DesignPoint":
        """The typed point of a point's SI inputs: :meth:`Scene.from_inputs` and each options class's
        ``from_inputs``. Raises ValueError naming the field for a choice or tolerance outside its values."""
        inputs = MappingProxyType(dict(inputs))
        return cls(inputs=inputs, scene=Scene.from_inputs(inputs), tolerances=Tolerances.from_inputs(inputs),
                   limits=LimitOptions.from_inputs(inputs), periodic=Options.from_inputs(inputs),
                   series=SeriesOptions.from_inputs(inputs), damped=DampedOptions.from_inputs(inputs),
                   time=TimeDomainOptions.from_inputs(inputs), sdof=SdofOptions.from_inputs(inputs),
                   check=CrosscheckOptions.from_inputs(inputs), reference=ReferenceOptions.from_inputs(inputs))

    def with_series(self, series: SeriesOptions) -> "DesignPoint":
        """This point with the series' options ``series`` (its inputs too, for the parts that read them)."""
        return replace(self, series=series,
                       inputs=MappingProxyType({**self.inputs, "series_tolerance": series.series_tolerance}))
