"""The documentation a clone has: docstrings and comments cite docs/model.md, not files outside it.

docs/model.md is the project's own account of its physics (issue 18, "Self-contained documentation").
Its sections §1-§9 keep the numbering of the team's first notes, so that a citation keeps its meaning;
every "docs/model.md §N" cited in the code must name a section the file has; and no source or test
file may point at a file a clone does not have (the team's notes, the OCR seeds and their line numbers).
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
MODEL = ROOT / "docs" / "model.md"
SOURCES = sorted(p for top in ("study", "tests") for p in (ROOT / top).rglob("*.py"))

#: The sections every citation of the first notes relies on (their numbers and subjects).
NUMBERED = {1: "scene", 2: "equation of motion", 3: "impact load", 4: "periodic solution", 5: "stresses",
            6: "dropped terms", 7: "damping", 8: "one-degree-of-freedom", 9: "methods"}

#: References to files outside the repository: name -> pattern. Built from pieces so that this file
#: does not match itself.
OUTSIDE = {
    "the team's notes": re.compile(r"\b" + "MODEL" + r"\.md"),  # case-sensitive: docs/model.md passes
    "the shared folder": re.compile(r"\.\./" + "shared" + r"|/work/" + "shared"),
    "the OCR seeds": re.compile("seeds" + r"/|\bseed (?:lines?|0\d\d)\b|``0\d\d_[0-9a-f]{16}\.txt``"),
    "the architecture notes": re.compile("ARCHITECTURE" + r"\.md"),
}


def _sections() -> set[str]:
    """Section numbers of docs/model.md: "4" for "## 4. …", "4.5" for "### 4.5 …"."""
    return set(re.findall(r"^#{2,3} (\d+(?:\.\d+)?)\.? ", MODEL.read_text(), flags=re.MULTILINE))


def test_model_keeps_the_section_numbering_of_the_first_notes():
    # source: the numbering of the notes the code cited (§1 The scene … §9 Methods); a citation
    # "docs/model.md §N" must keep the meaning "MODEL.md §N" had
    headings = dict(re.findall(r"^## (\d+)\. (.+)$", MODEL.read_text(), flags=re.MULTILINE))
    for number, subject in NUMBERED.items():
        assert subject in headings.get(str(number), "").lower(), (number, headings.get(str(number)))


def test_every_cited_section_exists():
    sections = _sections()
    cited = re.compile(r"docs/model\.md((?:(?:\s*[,;/]\s*|\s+and\s+|\s*)§\d+(?:\.\d+)?(?:\s*[–-]\s*\d+(?:\.\d+)?)?)+)")
    missing = []
    for path in SOURCES:
        for number, line in enumerate(path.read_text().splitlines(), 1):
            for group in cited.findall(line):
                for section in re.findall(r"\d+(?:\.\d+)?", group):
                    if section not in sections:
                        missing.append(f"{path.relative_to(ROOT)}:{number}: §{section}")
    assert not missing, "cited sections that docs/model.md lacks:\n" + "\n".join(missing)


@pytest.mark.parametrize("kind", OUTSIDE)
def test_no_reference_outside_the_repository(kind):
    pattern = OUTSIDE[kind]
    found = [f"{path.relative_to(ROOT)}:{number}: {line.strip()}"
             for path in SOURCES if path.name != Path(__file__).name
             for number, line in enumerate(path.read_text().splitlines(), 1) if pattern.search(line)]
    assert not found, f"references to {kind} (cite docs/model.md instead):\n" + "\n".join(found)


def test_the_constants_the_model_quotes_are_the_code_s():
    # source: study/physics/hertz.py (the derived constants) and section.py (the added-mass crossover):
    # docs/model.md §2.2 and §3.3-3.4 quote them to four or five digits; a change of the code shows here
    import numpy as np

    from study.physics import hertz, section

    text = MODEL.read_text()
    c_h = hertz.HERTZ_DURATION_CONSTANT
    quoted = {
        "C_H = (4/5) B(2/5, 1/2) = 2.94328": f"{c_h:.5f}",
        "T_L / T_H = (4π/5)/C_H = π / B(2/5, 1/2) = 0.8539": f"{hertz.LEE_TO_HERTZ_DURATION_RATIO:.4f}",
        "The exact area is 1.6/C_H = 0.5436": f"{1.6 / c_h:.4f}",
    }
    for phrase, value in quoted.items():
        assert phrase in text and phrase.endswith(value), (phrase, value)
    # the gap-flow and potential-flow added masses cross at R/r_o = 1.521 (§2.2)
    ratio = 1.521
    gap_lo, pot_lo = (section.added_mass(1.0, 1.0, ratio - 1e-3, m) for m in ("gap_flow", "potential_flow"))
    gap_hi, pot_hi = (section.added_mass(1.0, 1.0, ratio + 1e-3, m) for m in ("gap_flow", "potential_flow"))
    assert gap_lo < pot_lo and gap_hi > pot_hi and "R/r_o > 1.521" in text
    assert np.isclose(c_h * hertz.LEE_TO_HERTZ_DURATION_RATIO, 0.8 * np.pi)  # T_L = (4π/5) α_max/v0, eq. 3.9
