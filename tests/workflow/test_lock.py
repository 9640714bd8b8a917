"""The study folder's lock (study.workflow.lock): one sweep at a time, a dead holder's lock taken over."""

import json
import os
import socket
import subprocess
import sys

import pytest

from study.workflow.lock import LOCK, Locked, folder_lock


def test_a_second_holder_is_refused_with_the_first_ones_details(tmp_path):
    with folder_lock(tmp_path, "configs/a.toml") as holder:
        assert holder["pid"] == os.getpid() and holder["host"] == socket.gethostname()
        with pytest.raises(Locked) as refused:
            with folder_lock(tmp_path, "configs/b.toml"):
                pass
        message = str(refused.value)
        for part in (f"pid {os.getpid()}", socket.gethostname(), f"started {holder['started']}", "configs/a.toml"):
            assert part in message
    assert not (tmp_path / LOCK).exists()  # released and removed
    with folder_lock(tmp_path, "configs/b.toml"):  # free again
        pass


def test_a_lock_left_by_a_killed_process_is_taken_over(tmp_path):
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True)
    pid = int(dead.stdout)  # a process that has ended
    (tmp_path / LOCK).write_text(json.dumps({"pid": pid, "host": socket.gethostname(),
                                             "started": "2026-01-01T00:00:00+00:00", "config": "old.toml"}))
    said = []
    with folder_lock(tmp_path, "new.toml", said.append) as holder:
        assert holder["pid"] == os.getpid()
        assert json.loads((tmp_path / LOCK).read_text())["config"] == "new.toml"
    assert said == [f"took over the stale lock of pid {pid} on {socket.gethostname()}, started "
                    "2026-01-01T00:00:00+00:00, config old.toml (no longer running)"]
