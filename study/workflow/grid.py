"""The design grid: the cartesian product of the sweep axes, its points and their keys.

Points are numbered in C order over the axes (the last axis varies fastest), so a flat index
maps to one tuple of axis indices with ``numpy.unravel_index``. Every point has a key: a hash of
its normalised inputs and of the code that computes it (:func:`code_hash`), so a stored result is
reused only for the same inputs solved by the same code, whatever grid it was computed in.
"""

from __future__ import annotations

import functools
import hashlib
import json
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Iterator, Mapping

import numpy as np

import study
from study import __version__

#: The package sources whose change changes a point's result: the physics, the solvers, and the
#: workflow module that turns a point's result into a chunk's columns (relative to the package).
CODE_SOURCES = ("__init__.py", "physics", "solvers", "workflow/chunks.py")

KEY_DTYPE = "S32"  # a point key: 128-bit BLAKE2b digest in hex


def code_hash(package: str | None = None) -> str:
    """SHA-256 of the source files that compute a point (:data:`CODE_SOURCES` under ``package``, by
    default this installed package, read once a process), each with its path: any edit to the physics
    or a solver changes it."""
    return _hash_sources(Path(package)) if package else _installed_code_hash()


@functools.lru_cache(maxsize=1)
def _installed_code_hash() -> str:
    return _hash_sources(Path(study.__file__).parent)


def _hash_sources(root: Path) -> str:
    digest = hashlib.sha256(f"study {__version__}".encode())
    for source in CODE_SOURCES:
        path = root / source
        files = sorted(path.rglob("*.py")) if path.is_dir() else [path]
        for file in files:
            digest.update(f"\n{file.relative_to(root).as_posix()}\n".encode())
            digest.update(file.read_bytes())
    return digest.hexdigest()


@dataclass(frozen=True)
class Points:
    """Some points of a grid, self-contained (a task carries its own inputs): the fixed inputs, the
    swept inputs' values at these points, and the points' keys."""

    base: Mapping[str, Any]
    columns: Mapping[str, np.ndarray]
    keys: np.ndarray

    def __len__(self) -> int:
        return len(self.keys)

    def __iter__(self) -> Iterator[dict[str, Any]]:
        names = list(self.columns)
        values = [np.asarray(self.columns[name]).tolist() for name in names]
        for row in range(len(self)):
            inputs = dict(self.base)
            for name, column in zip(names, values):
                inputs[name] = column[row]
            yield inputs


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
        return iter(self.take(np.asarray(indices, dtype=np.int64), np.zeros(len(indices), KEY_DTYPE)))

    def take(self, indices: np.ndarray, keys: np.ndarray) -> Points:
        """The points at the flat ``indices`` with their ``keys``, as a self-contained :class:`Points`."""
        indices = np.asarray(indices, dtype=np.int64)
        unravelled = np.unravel_index(indices, self.shape) if self.axes else ()
        columns = {name: np.asarray(values)[i] for (name, values), i in zip(self.axes.items(), unravelled)}
        return Points(dict(self.base), columns, np.asarray(keys, dtype=KEY_DTYPE))

    def point_keys(self, code: str | None = None) -> np.ndarray:
        """The key of every point (C order): :func:`point_key` of its inputs, computed for the whole grid
        by hashing the inputs' common prefix once (about a microsecond a point)."""
        code = code_hash() if code is None else code
        names = sorted(set(self.base) | set(self.axes))
        swept = [name for name in names if name in self.axes]
        segments = [f"{code}|"]
        for name in names:
            if name in self.axes:
                segments[-1] += f"{json.dumps(name)}="
                segments.append(";")
            else:
                segments[-1] += f"{json.dumps(name)}={_token(self.base[name])};"
        tokens = [[_token(v).encode() for v in np.asarray(self.axes[name]).tolist()] for name in swept]
        tails = [segment.encode() for segment in segments[1:]]
        shape = [len(t) for t in tokens]
        keys = np.empty(math.prod(shape), dtype=KEY_DTYPE)
        position = 0

        def fill(level: int, prefix):
            nonlocal position
            if level == len(tokens):
                keys[position] = prefix.hexdigest().encode()
                position += 1
                return
            for token in tokens[level]:
                state = prefix.copy()
                state.update(token + tails[level])
                fill(level + 1, state)

        fill(0, hashlib.blake2b(segments[0].encode(), digest_size=16))
        if not swept:
            return keys
        order = [swept.index(name) for name in self.axes]  # hashed in name order; the grid's C order
        return keys.reshape(shape).transpose(order).ravel()


def _token(value) -> str:
    """A value's normalised text: floats exactly (hex), anything else as JSON."""
    if isinstance(value, float):
        return json.dumps(float.hex(value) if math.isfinite(value) else repr(value))
    return json.dumps(value)


def point_key(inputs: Mapping[str, Any], code: str | None = None) -> bytes:
    """Key of one point: BLAKE2b of its normalised inputs (every input, in name order, floats exactly)
    and of the code that computes it (:func:`code_hash`); signac's job id idea, at point granularity."""
    code = code_hash() if code is None else code
    text = f"{code}|" + "".join(f"{json.dumps(name)}={_token(inputs[name])};" for name in sorted(inputs))
    return hashlib.blake2b(text.encode(), digest_size=16).hexdigest().encode()


def auto_chunk_size(size: int) -> int:
    """Points per task when the config does not say (``sweep.chunk_size``): about 32 tasks, to balance a few
    workers when the points' costs differ a thousandfold (the default study: 3 ms for the free whirl, up to 2 s
    for the reference model), at least 8 and at most 512 points to amortise the scheduler's per-task cost (a
    few ms per task against 1 ms to 1 s per point). It depends on the grid alone, never on the number of workers
    (reuse does not depend on it either: a stored point is found by its key)."""
    return int(min(512, max(8, math.ceil(size / 32))))


#: The last :data:`TAPER_SHARE` of a sweep's points go in chunks :data:`TAPER_FACTOR` times smaller.
TAPER_SHARE, TAPER_FACTOR = 0.25, 4


def chunks(indices: np.ndarray, chunk_size: int, taper: bool = False) -> Iterator[np.ndarray]:
    """Consecutive runs of ``indices``, each at most ``chunk_size`` long; with ``taper`` (the sweep's own chunk
    size, :func:`auto_chunk_size`), those of the last quarter of the indices at most a quarter of that (at least
    1): the workers run out of work together instead of one finishing a whole chunk alone. On the 1408 points
    of ``make bench``'s default-study grid on two workers (each point's time measured in one process, the tasks
    dealt in order to the first free worker), chunks of 44 keep the two busy 98.5 % of the sweep, tapered (56
    tasks) 99.99 %."""
    n = len(indices)
    tail = n - int(TAPER_SHARE * n) if taper else n
    start = 0
    while start < n:
        size = chunk_size if start < tail else max(1, chunk_size // TAPER_FACTOR)
        yield indices[start:start + size]
        start += size


def chunk_key(keys: np.ndarray) -> str:
    """Name of a chunk file: a hash of its points' keys (the same points give the same name)."""
    return hashlib.blake2b(b"".join(np.asarray(keys, dtype=KEY_DTYPE).tolist()), digest_size=16).hexdigest()
