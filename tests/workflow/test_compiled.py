"""Compiling the solver kernels ahead (study.workflow.compiled): the first run says it compiles, later ones
load numba's cache, and compiling ahead leaves no kernel a method reaches to compile."""

import json
import os
import re
import subprocess
import sys
from pathlib import Path

from study.workflow import compiled

ROOT = Path(__file__).resolve().parents[2]


def test_every_module_with_cached_kernels_is_listed():
    # a kernel module missing from KERNEL_MODULES would be compiled silently by the first run
    with_kernels = set()
    for path in (ROOT / "study").rglob("*.py"):
        if re.search(r"njit\([^)]*cache=True", path.read_text()):
            parts = path.relative_to(ROOT).with_suffix("").parts
            with_kernels.add(".".join(parts[:-1] if parts[-1] == "__init__" else parts))  # a package's own
    assert with_kernels == set(compiled.KERNEL_MODULES)


def test_kernels_finds_the_dispatchers():
    found = compiled.kernels()
    assert "study.solvers.kernels.whirl_kernel.advance" in found and "study.physics.hertz.contact_one" in found
    assert all(name.rsplit(".", 1)[0] in compiled.KERNEL_MODULES for name in found)


def _point(cache: Path) -> subprocess.CompletedProcess:
    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache)}
    return subprocess.run([sys.executable, "-m", "study.cli", "point", str(ROOT / "configs" / "default.toml"), "--json"],
                          capture_output=True, text=True, env=env, cwd=ROOT, timeout=600)


def test_first_point_says_it_compiles_and_the_second_loads_the_cache(tmp_path):
    # an empty cache (NUMBA_CACHE_DIR) is a fresh install that skipped `make setup`
    first = _point(tmp_path)
    assert first.returncode == 0, first.stderr
    assert re.search(r"compiling \d+ solver kernels", first.stderr) and re.search(r"compiled in \d+ s", first.stderr)
    # the notice goes to stderr: stdout stays one JSON object (the default study's first point: the bouncing reference)
    assert json.loads(first.stdout)["method"] == "reference"
    second = _point(tmp_path)
    assert second.returncode == 0 and "compiling" not in second.stderr, second.stderr
    assert json.loads(second.stdout)["peak_contact_force"] == json.loads(first.stdout)["peak_contact_force"]
    left = subprocess.run([sys.executable, "-c", "from study.workflow import compiled; print(compiled.uncached())"],
                          capture_output=True, text=True, env={**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)})
    assert left.stdout.strip() == "[]", left.stdout + left.stderr
    # what the compile-ahead cached is recorded beside the cache: the kernels later runs are checked for
    (record,) = tmp_path.rglob(compiled.RECORD)
    assert "study.solvers.kernels.whirl_kernel.advance" in json.loads(record.read_text())
