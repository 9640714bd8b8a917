"""The design grid: the cartesian product of the sweep axes, in chunks of flat indices.

Points are numbered in C order over the axes (the last axis varies fastest), so a flat index
maps to one tuple of axis indices with ``numpy.unravel_index`` and chunks are plain ranges.
"""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import dataclass
from typing import Any, Iterator, Mapping

import numpy as np

from study import __version__


@dataclass(frozen=True)
class Grid:
    """Fixed inputs and the axes (name -> sorted SI values) of a sweep."""

    base: Mapping[str, Any]
    axes: Mapping[str, np.ndarray]

    @property
    def dims(self) -> tuple[str, ...]:
        return tuple(self.axes)

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(len(v) for v in self.axes.values())

    @property
    def size(self) -> int:
        return int(math.prod(self.shape))

    def point(self, flat_index: int) -> dict[str, Any]:
        """SI inputs of the point at ``flat_index`` (C order)."""
        inputs = dict(self.base)
        if self.axes:
            for name, i in zip(self.axes, np.unravel_index(flat_index, self.shape)):
                value = self.axes[name][i]
                inputs[name] = value.item() if isinstance(value, np.generic) else value
        return inputs

    def chunks(self, chunk_size: int) -> Iterator[range]:
        """Consecutive ranges of flat indices, each at most ``chunk_size`` long."""
        for start in range(0, self.size, chunk_size):
            yield range(start, min(start + chunk_size, self.size))


def auto_chunk_size(size: int, workers: int) -> int:
    """Points per task: about 8 tasks per worker to balance, at least 16 and at most 512 points to
    amortise the scheduler's per-task cost (a few ms per task against about 1 ms per point)."""
    return int(min(512, max(16, math.ceil(size / max(1, 8 * workers)))))


def _normalise(value):
    if isinstance(value, float):
        return float.hex(value) if math.isfinite(value) else repr(value)
    return value


def point_id(inputs: Mapping[str, Any]) -> str:
    """Hash of the normalised inputs of one point and the solver version (signac's job id idea)."""
    text = json.dumps({k: _normalise(v) for k, v in sorted(inputs.items())}, sort_keys=True)
    return hashlib.sha256(f"{__version__}|{text}".encode()).hexdigest()


def chunk_key(grid: Grid, indices: range) -> str:
    """Key of a chunk: hash of its points' ids, so changed inputs or code never reuse a result."""
    digest = hashlib.sha256()
    for index in indices:
        digest.update(point_id(grid.point(index)).encode())
    return digest.hexdigest()[:32]
