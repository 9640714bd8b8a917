"""The performance record's file (docs/performance.md and the other records of ``study bench``): written atomically,
its sections measured by hand kept where ``study bench`` rewrites it."""

from __future__ import annotations

from pathlib import Path

from study.atomic import atomic_path


#: The mark of a section of the performance record measured by hand (its command in its text), which `study bench`
#: does not make and keeps where it rewrites the record.
HAND_MARK = "(recorded by hand, not by `make bench`)"


def hand_sections(path: str | Path) -> str:
    """The sections of the record at ``path`` whose heading carries :data:`HAND_MARK`, each to the next heading,
    as they are; "" where the file or such a section does not exist."""
    path = Path(path)
    if not path.exists():
        return ""
    kept, keeping = [], False
    for line in path.read_text().splitlines():
        if line.startswith("#"):
            keeping = HAND_MARK in line
        if keeping:
            kept.append(line)
    return "\n".join(kept).rstrip() + "\n" if kept else ""


def write_record(out: str | Path, report: str) -> None:
    """Write ``report`` to ``out`` atomically (a reader never sees half a record), followed by the sections measured by
    hand that the record there held (:func:`hand_sections`)."""
    kept = hand_sections(out)
    with atomic_path(out) as tmp:
        Path(tmp).write_text(report + ("\n" + kept if kept else ""))
