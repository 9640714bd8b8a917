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
    built once by :meth:`from_inputs`); ``inputs``, the SI inputs it was built from (read-only), go to the parts that
    still take them whole: the sliding state's (:mod:`study.solvers.methods.sliding`, its solve and lift-off), the
    ladder's cache key (``auto``) and the periodic methods' study tolerance."""

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

    @classmethod
    def of(cls, point: "DesignPoint | Mapping[str, Any]") -> "DesignPoint":
        """``point`` itself, or the typed point of SI inputs (:meth:`from_inputs`): for the functions of a method that
        scripts, tests and the sliding state's parts still call with a point's inputs (the reference model's
        ``build_model``, ``simulate``, ``stresses`` ...; the time domain's ``build_model`` and ``simulate``)."""
        return point if isinstance(point, cls) else cls.from_inputs(point)

    def changed(self, **parts: Mapping[str, Any]) -> "DesignPoint":
        """This point with fields of its parts changed, part name -> {field: value}: ``changed(scene=dict(span_length=
        9.0), time=dict(time_modes=5))`` (a method's variants of the point: the reference model's mode counts, the
        crosscheck's replay at fast's span); its inputs too, for the parts that read them."""
        flat = {name: value for changes in parts.values() for name, value in changes.items()}
        return replace(self, inputs=MappingProxyType({**self.inputs, **flat}),
                       **{part: replace(getattr(self, part), **changes) for part, changes in parts.items()})

    def with_reference(self, **changes) -> "DesignPoint":
        """This point with the reference model's options ``changes`` (:class:`ReferenceOptions` fields: the mode and
        body-station counts the method tries; :meth:`changed`)."""
        return self.changed(reference=changes)

    def with_series(self, series: SeriesOptions) -> "DesignPoint":
        """This point with the series' options ``series`` (its inputs too, for the parts that read them)."""
        return replace(self, series=series,
                       inputs=MappingProxyType({**self.inputs, "series_tolerance": series.series_tolerance}))
