"""One sweep at a time in a study folder: an advisory lock on ``<folder>/.lock``.

The lock is a ``fcntl.flock`` on the file, which the kernel releases when its holder exits however
it ends (kill -9 included): a lock left by a dead process is stale and is simply taken over. The
file holds who took it (pid, host, start time, config) so that a refused run names the running one.
"""

from __future__ import annotations

import contextlib
import datetime as _dt
import fcntl
import json
import os
import socket
import stat
from pathlib import Path
from typing import Iterator

LOCK = ".lock"


class Locked(Exception):
    """The folder is being swept by another process; str() names it."""


def _describe(holder: dict) -> str:
    if not holder:
        return "another sweep (starting up)"
    return (f"pid {holder.get('pid')} on {holder.get('host')}, started {holder.get('started')}, "
            f"config {holder.get('config')}")


@contextlib.contextmanager
def folder_lock(folder: Path, config: str, say=None) -> Iterator[dict]:
    """Hold the lock of ``folder`` for the block; raise :class:`Locked` naming the holder if another
    process has it. ``say`` is told when a stale lock (its process gone) is taken over."""
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / LOCK
    while True:
        fd = _open_regular(path)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = _read(fd)
            os.close(fd)
            raise Locked(f"{folder} is being swept by {_describe(holder)}; wait for it to finish or stop it "
                         f"(a lock whose process has ended is taken over)") from None
        try:
            same = os.fstat(fd).st_ino == os.stat(path).st_ino
        except FileNotFoundError:
            same = False
        if same:
            break
        os.close(fd)  # the holder removed the file as we opened it: take the new one
    try:
        previous = _read(fd)
        if previous and say:  # its holder ended without removing it (killed): nobody holds its lock
            say(f"took over the stale lock of {_describe(previous)} (no longer running)")
        holder = {"pid": os.getpid(), "host": socket.gethostname(),
                  "started": _dt.datetime.now(_dt.timezone.utc).replace(microsecond=0).isoformat(),
                  "config": config}
        os.ftruncate(fd, 0)
        os.pwrite(fd, json.dumps(holder).encode(), 0)
        os.fsync(fd)
        yield holder
    finally:
        with contextlib.suppress(FileNotFoundError):
            path.unlink()
        os.close(fd)


def _open_regular(path: Path) -> int:
    """Open (or create) the lock file itself: never through a symbolic link (its target would be overwritten
    with the lock's JSON), and only a regular file. Raises :class:`Locked` saying what is there instead."""
    refuse = (f"{path} is not the sweep's lock file but {{what}}; it is left as it is: remove it and run the "
              "same command again")
    try:
        fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW | os.O_NONBLOCK, 0o666)
    except OSError as exc:
        if path.is_symlink():
            raise Locked(refuse.format(what=f"a symbolic link to {os.readlink(path)}")) from None
        raise
    if not stat.S_ISREG(os.fstat(fd).st_mode):
        os.close(fd)
        raise Locked(refuse.format(what="not a regular file"))
    return fd


def _read(fd: int) -> dict:
    try:
        return json.loads(os.pread(fd, 65536, 0).decode() or "{}")
    except (ValueError, OSError):
        return {}
