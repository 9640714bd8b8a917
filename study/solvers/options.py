"""Every method's options, declared once with their defaults (docs/model.md §9).

Pure data, importing nothing of the solvers: the config (:mod:`study.config`) takes its ``solver.*``
defaults and choices from here, and the methods build their settings from a point's inputs with the same
declarations, so a default is written in one place. Loading this module loads no solver.
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any, Mapping

#: The methods behind :func:`study.solvers.solve_point`, name -> what it computes (the registry of solve
#: functions, :data:`study.solvers.METHODS`, is built from these names).
METHOD_DESCRIPTIONS = {
    "core": "physics core: section, mud, tension, and the Hertz/Lee impact at a given span",
    "fast": "periodic impact solution: span search, closed-form modal response with a quasi-static correction, "
            "stresses",
    "series": "the paper's double Fourier series (modes x harmonics) with the same span search as fast: the "
              "reproduction, and the slow reference",
    "auto": "the cheapest model of the hierarchy that serves the point (fast, then series where only its error "
            "estimate failed)",
    "time-domain": "modal span integrated through Hertz contact with both walls (event-driven, explicit Verlet "
                   "or implicit LSODA) until periodic: the check on the periodic assumption",
    "crosscheck": "the fast periodic solution replayed through one revolution of real Hertz contact in the time "
                  "domain: agrees within solver.check_tolerance, or flagged with the reasons",
    "sdof": "one-degree-of-freedom screen: first-mode impact oscillator between the walls, exact period-1 orbit "
            "and Floquet stability at a given span",
}

#: Relative accuracy asked of every method's answer (config ``solver.tolerance``): 1 %, what a design decision
#: needs. A result whose error estimate is above it is ``not_converged`` (study.solvers.gate).
DEFAULT_TOLERANCE = 1e-2
#: The mass of the closure's impulse (periodic.Scene.equivalent_mass): 2ML/π (the paper's) or ML/2.
IMPACT_MASSES = ("momentum", "modal")
#: Resonance candidates the span search may enumerate (config ``solver.max_poles``; a memory guard).
MAX_POLES = 20_000_000


@dataclass(frozen=True)
class Options:
    """Resolution and search settings of the periodic methods (``fast``, ``series``, ``auto``, ``crosscheck``).

    The first five are config fields (``solver.modes`` ...); the rest are internal resolutions.
    """

    modes: int = 41  #: highest (odd) mode number kept
    min_span: float = 3.0  #: shortest span searched [m]
    max_span: float = 304.8  #: longest span searched [m] (1000 ft)
    load_shape: str = "parabolic"  #: spatial shape of the contact load (beam.LOAD_SHAPES)
    resonance_width: float = 1e-6  #: resonances narrower than this (relative span) are not searched
    samples: int = 4  #: samples of F inside each interval between (wide) poles
    time_points: int = 480  #: points over one (half) period outside the pulse, for condition 1
    pulse_points: int = 64  #: points across the pulse
    space_points: int = 48  #: points over half the span
    tolerance: float = 1e-6  #: relative slack of condition 1, |y| <= c (1 + tolerance)
    fixed_point_tol: float = 1e-9  #: relative change of T_L that ends the T_L-κ iteration

    #: the fields a config sets (same names in the point's inputs)
    CONFIG_FIELDS = ("modes", "min_span", "max_span", "load_shape", "resonance_width")

    @classmethod
    def from_inputs(cls, inputs: Mapping[str, Any]) -> "Options":
        """The settings of a point: its inputs where set (not None), the declared defaults elsewhere."""
        given = {name: inputs[name] for name in cls.CONFIG_FIELDS if inputs.get(name) is not None}
        types = {f.name: f.type for f in fields(cls)}
        return cls(**{name: (int(v) if types[name] == "int" else v if types[name] == "str" else float(v))
                      for name, v in given.items()})
