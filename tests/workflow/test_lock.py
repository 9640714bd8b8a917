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


def test_a_lock_file_that_is_a_symbolic_link_is_refused_and_its_target_left_alone(tmp_path):
    # issue 32: the lock was opened through the link and its target overwritten with the lock's JSON
    target = tmp_path / "precious.txt"
    target.write_text("keep me")
    folder = tmp_path / "study"
    folder.mkdir()
    (folder / LOCK).symlink_to(target)
    with pytest.raises(Locked, match="symbolic link to .*precious.txt.*remove it"):
        with folder_lock(folder, "a.toml"):
            pass
    assert target.read_text() == "keep me"
    assert (folder / LOCK).is_symlink()  # left as it was


def test_a_lock_path_that_is_not_a_regular_file_is_refused(tmp_path):
    os.mkfifo(tmp_path / LOCK)
    with pytest.raises(Locked, match="not a regular file"):
        with folder_lock(tmp_path, "a.toml"):
            pass
