"""Chunk files (study.workflow.chunks): checksummed, verified on every read, found by their points' keys."""

import numpy as np
import pytest

from study.workflow.chunks import ChunkDamaged, Store, load_chunk, save_chunk
from study.workflow.grid import KEY_DTYPE


def columns(keys, scale=1.0):
    n = len(keys)
    return {"peak_contact_force": scale * np.arange(n, dtype=float), "status": np.zeros(n, dtype=np.int8),
            "message": np.array([f"point {i}" for i in range(n)]), "point_key": np.array(keys, dtype=KEY_DTYPE)}


def truncate(path):
    path.write_bytes(path.read_bytes()[: path.stat().st_size // 2])


def empty(path):
    path.write_bytes(b"")


def flip_a_bit(path):
    # One bit of the first column's data, past its zip and npy headers (npy format 1.0: magic, two
    # version bytes, a 2-byte header length, the header).
    data = bytearray(path.read_bytes())
    magic = data.index(b"\x93NUMPY", data.index(b"peak_contact_force.npy"))
    start = magic + 10 + int.from_bytes(data[magic + 8:magic + 10], "little")
    data[start + 8] ^= 0x01  # the second float's lowest byte: 1.0 becomes 1.0000000000000002
    path.write_bytes(bytes(data))


def rewrite_a_value(path):
    # A consistent zip whose payload was altered (CRC-32 recomputed): only the sha256 member can tell.
    with np.load(path) as data:
        members = {name: data[name] for name in data.files}
    members["peak_contact_force"] = members["peak_contact_force"] + 1.0
    np.savez(path, **members)


def drop_the_checksum(path):  # e.g. a chunk written before checksums existed
    with np.load(path) as data:
        np.savez(path, **{name: data[name] for name in data.files if name != "sha256"})


@pytest.mark.parametrize("damage", [truncate, empty, flip_a_bit, rewrite_a_value, drop_the_checksum])
def test_a_damaged_chunk_is_refused_when_read(tmp_path, damage):
    path = tmp_path / "a.npz"
    save_chunk(path, columns([b"k1", b"k2", b"k3"]))
    assert load_chunk(path)["message"].tolist() == ["point 0", "point 1", "point 2"]  # intact: reads back
    damage(path)
    with pytest.raises(ChunkDamaged):
        load_chunk(path)


def test_the_store_finds_points_by_key_and_removes_damaged_files(tmp_path):
    save_chunk(tmp_path / "a.npz", columns([b"k1", b"k2"]))
    save_chunk(tmp_path / "b.npz", columns([b"k3", b"k4"], scale=10.0))
    save_chunk(tmp_path / "c.npz", columns([b"k5"]))
    truncate(tmp_path / "c.npz")
    store = Store.scan(tmp_path)
    assert [(p.name, reason.split()[0]) for p, reason in store.damaged] == [("c.npz", "unreadable")]
    assert not (tmp_path / "c.npz").exists()
    wanted = np.array([b"k4", b"k5", b"k1"], dtype=KEY_DTYPE)
    file, row = store.locate(wanted)
    assert file.tolist() == [1, -1, 0] and row.tolist()[::2] == [1, 0]
    with pytest.raises(ValueError, match="1 points are not in the store"):
        store.columns(wanted)
    stored = store.columns(wanted[[0, 2]])  # in the order asked for, across files
    assert stored["peak_contact_force"].tolist() == [10.0, 0.0]
    assert stored["message"].tolist() == ["point 1", "point 0"]
