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
        return next(self.points(range(flat_index, flat_index + 1)))

    def points(self, indices: range) -> Iterator[dict[str, Any]]:
        """SI inputs of the points ``indices`` (C order; any range, a step included), unravelled once for the
        whole range."""
        names = list(self.axes)
        columns = [self.axes[name][i].tolist() for name, i in
                   zip(names, np.unravel_index(np.asarray(indices, dtype=int), self.shape))] if names else []
        for row in range(len(indices)):
            inputs = dict(self.base)
            for name, column in zip(names, columns):
                inputs[name] = column[row]
            yield inputs

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


def grid_id(grid: Grid) -> str:
    """Hash of the normalised fixed inputs, the axes' values and the solver version."""
    axes = {name: [_normalise(v) for v in np.asarray(values).tolist()] for name, values in grid.axes.items()}
    return point_id({**grid.base, "__axes__": json.dumps(axes, sort_keys=True), "__order__": list(grid.axes)})


def chunk_key(grid: Grid, indices: range, grid_hash: str | None = None) -> str:
    """Key of a chunk: its index range within the hashed grid. The grid fixes every point's inputs (C
    order over the axes), so the key changes with any input, axis value or solver version and never
    reuses a stale result - the same guarantee as hashing each point, without hashing each point."""
    base = grid_hash or grid_id(grid)
    return hashlib.sha256(f"{base}|{indices.start}|{indices.stop}".encode()).hexdigest()[:32]
