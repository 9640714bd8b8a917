"""A chunk of a sweep: its columns (one row per point), its file, and the store of chunk files.

A chunk file ``<store>/<chunk key>.npz`` holds the columns of its points, their keys
(``point_key``) and ``sha256``, a checksum of every other member (name, dtype, shape and bytes).
It is written atomically and verified whenever it is read: a truncated, emptied or altered file
is reported and its points are solved again. The points' keys, not the file's name or place,
say which results it holds, so any grid (another chunk size, another number of workers, one axis
value changed) reuses every stored point it contains.

This module's source is part of :func:`study.workflow.grid.code_hash`: a change to how a point's
result becomes a row changes every key.
"""

from __future__ import annotations

import hashlib
import zipfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Mapping

import numpy as np

from study.atomic import atomic_path
from study.solvers import OUTPUTS, STATUS_CODES, solve_point
from study.workflow.grid import KEY_DTYPE, Points, code_hash

CHECKSUM = "sha256"  # the member holding the checksum of the others

#: The code hash of the solver sources as this process loaded them: computed when this module is first imported,
#: right after it imported the solvers (a worker imports it with its first task, or in its warm-up). A dask worker
#: that outlives an edit of the sources keeps running the code it loaded, and keeps this hash with it.
LOADED_CODE = code_hash()


class ChunkDamaged(Exception):
    """A chunk file that cannot be read whole or whose checksum does not match its contents."""


def solve_chunk(points: Points) -> dict[str, np.ndarray]:
    """Solve ``points``; columns of SI values (NaN where not computed), with each point's key."""
    n = len(points)
    columns = {name: np.full(n, np.nan) for name in OUTPUTS}
    columns["error_estimate"] = np.full(n, np.nan)
    columns["wall_time"] = np.zeros(n)
    status = np.zeros(n, dtype=np.int8)
    messages, methods = [], []
    for row, inputs in enumerate(points):
        result = solve_point(inputs)
        for name, value in result.values.items():
            if name in columns:
                columns[name][row] = value
        if result.error_estimate is not None:
            columns["error_estimate"][row] = result.error_estimate
        columns["wall_time"][row] = result.wall_time
        status[row] = STATUS_CODES[result.status]
        messages.append(result.message)
        methods.append(result.method)
    columns["status"] = status
    columns["message"] = np.array(messages, dtype=str)
    columns["method"] = np.array(methods, dtype=str)
    columns["point_key"] = np.asarray(points.keys, dtype=KEY_DTYPE)
    return columns


def solve_task(points: Points, code: str) -> tuple[str, dict[str, np.ndarray] | None]:
    """A sweep's task: ``(the code hash this process runs, solve_chunk(points))``, the points solved only when
    that hash is ``code`` (the one the points' keys were made with); ``(hash, None)`` otherwise, so a worker
    running other code never has its results stored under the new code's keys."""
    if LOADED_CODE != code:
        return LOADED_CODE, None
    return LOADED_CODE, solve_chunk(points)


def checksum(columns: Mapping[str, np.ndarray]) -> str:
    """SHA-256 of the columns: each member's name, dtype, shape and bytes, in name order."""
    digest = hashlib.sha256()
    for name in sorted(columns):
        if name == CHECKSUM:
            continue
        array = np.ascontiguousarray(columns[name])
        digest.update(f"{name}|{array.dtype.str}|{array.shape}|".encode())
        digest.update(array.tobytes())
    return digest.hexdigest()


def save_chunk(path: Path, columns: Mapping[str, np.ndarray]) -> None:
    """Write a chunk file atomically, with the checksum of its columns."""
    with atomic_path(path) as tmp:
        np.savez(tmp, **columns, **{CHECKSUM: np.array(checksum(columns))})


def load_chunk(path: Path) -> dict[str, np.ndarray]:
    """Read a whole chunk file and verify it; raises :class:`ChunkDamaged` saying what is wrong."""
    try:
        with np.load(path, allow_pickle=False) as data:
            columns = {key: data[key] for key in data.files}
    except (OSError, ValueError, EOFError, zipfile.BadZipFile, KeyError) as exc:
        raise ChunkDamaged(f"unreadable ({type(exc).__name__}: {exc})") from None
    stored = columns.pop(CHECKSUM, None)
    if stored is None:
        raise ChunkDamaged("no checksum")
    if str(stored) != checksum(columns):
        raise ChunkDamaged("checksum mismatch")
    if "point_key" not in columns or any(len(v) != len(columns["point_key"]) for v in columns.values()):
        raise ChunkDamaged("columns of unequal length")
    return columns


@dataclass
class Store:
    """The verified chunk files of a store folder and the point keys each holds."""

    folder: Path
    files: list[Path] = field(default_factory=list)
    keys: list[np.ndarray] = field(default_factory=list)
    damaged: list[tuple[Path, str]] = field(default_factory=list)

    @classmethod
    def scan(cls, folder: Path) -> "Store":
        """Verify every chunk file in ``folder``; a damaged one is removed and listed in ``damaged``."""
        store = cls(folder)
        for path in sorted(folder.glob("*.npz")):
            if path.name.startswith("."):
                continue
            try:
                store.add(path, load_chunk(path)["point_key"])
            except ChunkDamaged as exc:
                store.damaged.append((path, str(exc)))
                path.unlink(missing_ok=True)
        return store

    def add(self, path: Path, keys: np.ndarray) -> None:
        self.files.append(path)
        self.keys.append(np.asarray(keys, dtype=KEY_DTYPE))

    def locate(self, wanted: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """For each of the ``wanted`` keys: the number of the file holding it (-1 if none) and its row."""
        file = np.full(len(wanted), -1, dtype=np.int64)
        row = np.zeros(len(wanted), dtype=np.int64)
        if not self.keys:
            return file, row
        stored = np.concatenate(self.keys)
        owner = np.repeat(np.arange(len(self.keys)), [len(k) for k in self.keys])
        rows = np.concatenate([np.arange(len(k)) for k in self.keys])
        order = np.argsort(stored, kind="stable")
        stored = stored[order]
        at = np.clip(np.searchsorted(stored, wanted), 0, len(stored) - 1)
        found = stored[at] == wanted
        file[found] = owner[order][at[found]]
        row[found] = rows[order][at[found]]
        return file, row

    def columns(self, wanted: np.ndarray) -> "StoredColumns":
        file, row = self.locate(wanted)
        if np.any(file < 0):
            raise ValueError(f"{int(np.sum(file < 0))} points are not in the store {self.folder}")
        return StoredColumns(self.files, file, row)


class StoredColumns:
    """The stored results of some points read one column at a time: ``columns[name]`` is that output
    for every point in the order asked for, loaded from each file's member alone (the zip member's
    CRC-32 is checked as it is read). Memory holds one column; ``columns["index"]`` is 0, 1, 2, ..."""

    def __init__(self, files: list[Path], file: np.ndarray, row: np.ndarray):
        self.files, self.file, self.row = files, file, row
        order = np.argsort(file, kind="stable")
        numbers, starts = np.unique(file[order], return_index=True)
        self.groups = list(zip(numbers.tolist(), np.split(order, starts[1:])))
        self.paths = [files[number] for number, _ in self.groups]

    def __len__(self) -> int:
        return len(self.file)

    def __getitem__(self, name: str) -> np.ndarray:
        if name == "index":
            return np.arange(len(self.file))
        parts = []
        for number, where in self.groups:
            try:
                with np.load(self.files[number], allow_pickle=False) as data:
                    parts.append((where, data[name][self.row[where]]))
            except (OSError, ValueError, EOFError, zipfile.BadZipFile) as exc:
                raise ChunkDamaged(f"{self.files[number]}: {type(exc).__name__}: {exc}") from None
        out = np.empty(len(self.file), dtype=np.result_type(*[values.dtype for _, values in parts]))
        for where, values in parts:
            out[where] = values
        return out
