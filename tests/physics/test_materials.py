"""Drill-pipe grades and yield utilisation (study.physics.materials) against the printed API table."""

import numpy as np
import pytest

from study.physics import materials

# NIST SP 811 (2008), App. B.8: 1 psi = 6.894 757 293 168 E+03 Pa.
PSI_NIST = 6894.757293168


@pytest.mark.parametrize(
    "grade, min_yield, max_yield, min_tensile",
    [
        # API Spec 5D, 2nd ed. (1991), Table 6.3, as reprinted in "Tech Facts: API drill pipe
        # requirements" (tensile requirements, psi).
        ("E-75", 75_000, 105_000, 100_000),
        ("X-95", 95_000, 125_000, 105_000),
        ("G-105", 105_000, 135_000, 115_000),
        ("S-135", 135_000, 165_000, 145_000),
    ],
)
def test_grades_carry_the_printed_strengths(grade, min_yield, max_yield, min_tensile):
    spec = materials.GRADES[grade]
    assert spec.min_yield == pytest.approx(min_yield * PSI_NIST, rel=1e-12)
    assert spec.max_yield == pytest.approx(max_yield * PSI_NIST, rel=1e-12)
    assert spec.min_tensile == pytest.approx(min_tensile * PSI_NIST, rel=1e-12)


@pytest.mark.parametrize("grade", list(materials.GRADES))
def test_grade_number_is_the_minimum_yield_in_ksi(grade):
    # Sperry-Sun, Basic Drill String Design §1.1.4: "the numbers in the pipe grade specifically refer
    # to the yield strength of the pipe ... G-105 has a minimum yield strength of 105,000 lb/in^2".
    ksi = float(grade.split("-")[1])
    assert materials.GRADES[grade].min_yield / PSI_NIST == pytest.approx(ksi * 1000, rel=1e-12)
    # and every grade's minimum tensile strength is above its minimum yield
    assert materials.GRADES[grade].min_tensile > materials.GRADES[grade].min_yield


def test_design_uses_the_minima_unless_strengths_are_given():
    assert materials.grade_strengths("G-105") == (materials.GRADES["G-105"].min_yield,
                                                  materials.GRADES["G-105"].min_tensile)
    assert materials.grade_strengths("G-105", yield_strength=800e6) == (800e6, materials.GRADES["G-105"].min_tensile)
    assert materials.grade_strengths("E-75", tensile_strength=900e6)[1] == 900e6


def test_unknown_grade_is_refused_with_the_allowed_grades():
    with pytest.raises(ValueError, match=r"pipe grade = 'P-110'; allowed: E-75, X-95, G-105, S-135"):
        materials.grade_strengths("P-110")


def test_yield_utilisation_is_one_at_yield_in_tension_and_compression():
    yield_strength = materials.GRADES["S-135"].min_yield
    stresses = np.array([-yield_strength, -0.5 * yield_strength, 0.0, yield_strength, 1.2 * yield_strength])
    np.testing.assert_allclose(materials.yield_utilisation(stresses, yield_strength), [1.0, 0.5, 0.0, 1.0, 1.2])
