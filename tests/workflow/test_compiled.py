"""Compiling the solver kernels ahead (study.workflow.compiled): the first run says it compiles, later ones
load numba's cache, and compiling ahead leaves no kernel a method reaches to compile."""

import json
import os
import re
import shutil
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


#: The kernel the test takes out of the cache: a small one every warm-up reaches (the reference model's extremes).
DROPPED = "study.solvers.kernels.extremes._extremes_kernel"


def _cache_without(cache: Path, dropped: str) -> int:
    """Fill the folder ``cache`` (a NUMBA_CACHE_DIR) with this checkout's compiled kernels (numba's cache beside the
    sources, which `make setup` fills) but ``dropped``'s, as after a change of that kernel's source; return how many
    kernels there are. Compiling all of them into an empty cache takes minutes (219 s in the last fresh-clone CI),
    which this spares the suite; the files are numba's own, moved between its two cache locations by the dispatchers'
    public ``stats.cache_path`` (each index is keyed by the source file's stamp, not by where it lies)."""
    found = compiled.kernels()
    where = subprocess.run([sys.executable, "-c", "import json; from study.workflow import compiled; "
                            "print(json.dumps({n: d.stats.cache_path for n, d in compiled.kernels().items()}))"],
                           capture_output=True, text=True, env={**os.environ, "NUMBA_CACHE_DIR": str(cache)}, cwd=ROOT)
    targets = json.loads(where.stdout)
    name = dropped.rsplit(".", 1)[1]
    stem = Path(found[dropped].py_func.__code__.co_filename).stem
    for kernel, dispatcher in found.items():
        source, target = Path(dispatcher.stats.cache_path), Path(targets[kernel])
        target.mkdir(parents=True, exist_ok=True)
        for path in [*source.glob("*.nbi"), *source.glob("*.nbc")]:
            if not path.name.startswith(f"{stem}.{name}-"):
                shutil.copy2(path, target / path.name)
    return len(found)


def test_first_point_says_it_compiles_and_the_second_loads_the_cache(tmp_path):
    # a cache that lacks one kernel is an install whose kernel source changed since `make setup` (an empty one, a
    # fresh install that skipped it, takes the same path over every kernel)
    total = _cache_without(tmp_path, DROPPED)
    first = _point(tmp_path)
    assert first.returncode == 0, first.stderr
    compiling = re.search(r"compiling (\d+) solver kernels", first.stderr)
    assert compiling and re.search(r"compiled in \d+ s", first.stderr), first.stderr
    # the dropped kernel and at most those no warm-up reaches (not in the cache beside the sources either): not all
    assert 1 <= int(compiling.group(1)) < total / 4, first.stderr
    # the notice goes to stderr: stdout stays one JSON object (the default study's first point: the bouncing reference)
    assert json.loads(first.stdout)["method"] == "reference"
    second = _point(tmp_path)
    assert second.returncode == 0 and "compiling" not in second.stderr, second.stderr
    assert json.loads(second.stdout)["peak_contact_force"] == json.loads(first.stdout)["peak_contact_force"]
    left = subprocess.run([sys.executable, "-c", "from study.workflow import compiled; print(compiled.uncached())"],
                          capture_output=True, text=True, env={**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)})
    assert left.stdout.strip() == "[]", left.stdout + left.stderr
    # what the compile-ahead cached is recorded beside the cache, the dropped kernel in it: the kernels later runs
    # are checked for
    (record,) = tmp_path.rglob(compiled.RECORD)
    assert {"study.solvers.kernels.whirl_kernel.advance", DROPPED} <= set(json.loads(record.read_text()))
