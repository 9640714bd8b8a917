"""Strength of drill-pipe steel: the API grades' minimum yield and tensile strengths, and utilisation.

Pure functions and a table, SI units (Pa). The grades and their specified strengths are those of
API Spec 5D (2nd ed., 1991, Table 6.3; now API Spec 5DP), the table drill-pipe design follows in
API RP 7G: minimum yield strength, maximum yield strength and minimum tensile strength, in psi.
A user may give a yield or tensile strength directly; it replaces the grade's value.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: One pound-force per square inch in pascals, exact by definition (lbf = 0.45359237 kg x 9.80665 m/s²,
#: in = 0.0254 m).
PSI = 0.45359237 * 9.80665 / 0.0254**2


@dataclass(frozen=True)
class Grade:
    """Specified strengths of one drill-pipe grade [Pa]."""

    min_yield: float
    max_yield: float
    min_tensile: float


#: API drill-pipe grades (API Spec 5D, 2nd ed., Table 6.3): name -> strengths [Pa].
GRADES = {
    "E-75": Grade(min_yield=75_000 * PSI, max_yield=105_000 * PSI, min_tensile=100_000 * PSI),
    "X-95": Grade(min_yield=95_000 * PSI, max_yield=125_000 * PSI, min_tensile=105_000 * PSI),
    "G-105": Grade(min_yield=105_000 * PSI, max_yield=135_000 * PSI, min_tensile=115_000 * PSI),
    "S-135": Grade(min_yield=135_000 * PSI, max_yield=165_000 * PSI, min_tensile=145_000 * PSI),
}


def grade_strengths(grade: str, yield_strength=None, tensile_strength=None) -> tuple[float, float]:
    """Yield and tensile strength [Pa] to design with: the grade's specified minima, or given values.

    grade: one of :data:`GRADES`; yield_strength, tensile_strength [Pa]: replace the grade's minimum
    yield / minimum tensile strength when given (not None). Design uses the specified *minimum*
    strengths, as API RP 7G does for the pipe body's tensile and torsional capacity.
    """
    if grade not in GRADES:
        raise ValueError(f"pipe grade = {grade!r}; allowed: {', '.join(GRADES)}")
    spec = GRADES[grade]
    return (
        spec.min_yield if yield_strength is None else float(yield_strength),
        spec.min_tensile if tensile_strength is None else float(tensile_strength),
    )


def yield_utilisation(stress, yield_strength):
    """|σ| / σ_y [-]: above 1 the stress exceeds the yield strength (a flag, not a failure).

    stress [Pa] (normal stress of either sign; compression yields as tension does), yield_strength [Pa].
    """
    return np.abs(np.asarray(stress, dtype=float)) / np.asarray(yield_strength, dtype=float)
