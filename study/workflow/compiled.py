"""The solvers' compiled kernels: whether numba's on-disk cache holds them, and compiling them ahead.

numba compiles a kernel on its first call in a process and, with ``cache=True``, keeps the machine code
beside the source (``__pycache__``, keyed on the source file's time stamp and size), so that a later
process loads it instead of compiling again. Compiling every method's kernels takes about 260 s on
this project's 2-core machine (measured by :func:`compile_ahead`; ``docs/performance_compile.md``,
``make bench-compile``). So:

- ``make setup`` runs ``study compile``: every method solved once on the warm-up points (the paper's
  example in two readings and the default study's first point), which leaves every kernel in the cache;
- ``study point`` and ``study sweep`` check the cache first (:func:`uncached`, milliseconds: the kernels the
  last compile-ahead cached, :data:`RECORD`) and, when a kernel is missing (a fresh install that skipped ``make setup``,
  or a kernel's source changed), say that they are compiling, for how long it should take, and how long it took;
- a sweep compiles in its own process before it starts its workers, which would otherwise each compile the
  same kernels at once.

numba has no public API that tells whether its cache holds a kernel without compiling or loading it (numba 0.68.1: a
dispatcher's public attributes are ``stats`` alone, whose ``cache_hits`` and ``cache_misses`` count only once a call has
loaded or compiled it; numba's "Notes on Caching" document one pickled ``.nbi`` index per function, but not its file
name nor how it records the source's stamp that makes an entry stale, so reading the files ourselves would copy the same
private format), so :func:`cached` reads the index through the dispatcher's private cache object, of the pinned numba
(pyproject.toml); an unreadable index counts as a missing one. Whether a kernel is cached at all and where its cache
folder is come from the dispatcher's public ``stats.cache_path`` (None without ``cache=True``).
"""

from __future__ import annotations

import importlib
import json
import time
from pathlib import Path
from typing import Any, Callable, Iterable, Mapping

from study.atomic import atomic_path

#: Modules holding numba kernels compiled with ``cache=True``.
KERNEL_MODULES = ("study.physics.beam", "study.physics.contact", "study.physics.fatigue", "study.physics.hertz",
                  "study.physics.interpolation",
                  "study.physics.midspan", "study.physics.roots", "study.solvers.kernels.event_driven",
                  "study.solvers.kernels.extremes", "study.solvers.kernels.stress_kernel",
                  "study.solvers.kernels.whirl_kernel", "study.solvers.kernels.pulse", "study.solvers.kernels.impact",
                  "study.solvers.kernels.drag",
                  "study.solvers.methods.periodic.span_search")
#: The kernels the last compile-ahead left in the cache, kept beside them: the ones a run is checked for (a kernel
#: no method reaches at the warm-up points — a physics function's array form kept for its users and tests, a path
#: of a method those points do not take — compiles on its own first call, without a notice).
RECORD = "study-compiled-kernels.json"
#: The warm-up points: the first point of each of these configs of the project (``configs/``), with overrides:
#: the paper's example in its default reading and in the one that finds spans, and the default study.
WARM_UP_CONFIGS = (("paper.toml", {}),
                   ("paper.toml", {"impact.pattern": "one_wall", "impact.closure": "self_consistent"}),
                   ("default.toml", {}))
CONFIG_DIR = Path(__file__).resolve().parents[2] / "configs"
#: Seconds to compile every kernel from nothing: ``study compile`` took 255 s into an empty cache on the project's
#: 2-core machine, quiet, in `make setup` of a fresh clone (2026-11-27, at 3d2696d; docs/performance_compile.md has the
#: bench's measurement, on a loaded machine); quoted to the user before a compile starts.
COMPILE_SECONDS = 260


def kernels(modules: Iterable[str] = KERNEL_MODULES) -> dict[str, Any]:
    """Every cached numba kernel of ``modules``: 'module.function' -> dispatcher (not those inlined into their
    callers, ``inline="always"``, which are never compiled on their own)."""
    from numba.core.registry import CPUDispatcher

    found = {}
    for name in modules:
        module = importlib.import_module(name)
        for attr, value in vars(module).items():
            if (isinstance(value, CPUDispatcher) and value.stats.cache_path is not None
                    and value.targetoptions.get("inline", "never") == "never"):
                found[f"{name}.{attr}"] = value
    return found


def cached(dispatcher) -> bool:
    """Whether numba's on-disk cache holds at least one compiled version of ``dispatcher`` that is
    current with its source (the index numba keeps per function: empty when absent or stale). No public call reads
    it without loading the kernel (numba 0.68), hence the private ``_cache._cache_file._load_index``."""
    try:
        return bool(dispatcher._cache._cache_file._load_index())
    except Exception:  # noqa: BLE001 - an unreadable index is a missing one: numba compiles again
        return False


def _record_path(found: dict[str, Any]) -> Path | None:
    """Where :data:`RECORD` sits: numba's cache folder of the first kernel (``__pycache__`` beside the sources, or
    under ``NUMBA_CACHE_DIR``); None without kernels or a cache folder."""
    first = next(iter(found.values()), None)
    try:
        return Path(first.stats.cache_path) / RECORD if first is not None else None
    except Exception:  # noqa: BLE001 - no cache folder: nothing recorded
        return None


def uncached(modules: Iterable[str] = KERNEL_MODULES) -> list[str]:
    """The kernels ('module.function') a run would compile: of those the last compile-ahead cached (all of them
    before any), the ones not in the cache now."""
    found = kernels(modules)
    path = _record_path(found)
    try:
        wanted = set(json.loads(path.read_text())) if path else set(found)
    except (OSError, ValueError):
        wanted = set(found)
    return [name for name, dispatcher in found.items() if name in wanted and not cached(dispatcher)]


def warm_up_points(extra: Iterable[Mapping[str, Any]] = ()) -> list[dict[str, Any]]:
    """The points every method is solved at to compile its kernels: the project's warm-up configs'
    first points (when the configs are beside the package) and ``extra``."""
    from study.config import load

    points = [load(CONFIG_DIR / name, overrides).point() for name, overrides in WARM_UP_CONFIGS
              if (CONFIG_DIR / name).is_file()]
    return points + [dict(point) for point in extra]


def compile_ahead(points: Iterable[Mapping[str, Any]] | None = None, say: Callable[[str], None] | None = None) -> float:
    """Solve every method once at each of ``points`` (default :func:`warm_up_points`) so that numba
    compiles and caches every kernel; return the seconds it took. Results are discarded."""
    from study.solvers import METHODS, solve_point

    start = time.perf_counter()
    for inputs in (warm_up_points() if points is None else list(points)):
        for method in METHODS:
            began = time.perf_counter()
            solve_point(inputs, method)
            if say:
                say(f"  {method}: {time.perf_counter() - began:.1f} s")
    found = kernels()
    path = _record_path(found)
    if path:
        try:
            with atomic_path(path) as tmp:
                Path(tmp).write_text(json.dumps(sorted(name for name, d in found.items() if cached(d))))
        except OSError:  # a read-only cache folder: every kernel stays checked
            pass
    return time.perf_counter() - start


def ensure_compiled(inputs: Mapping[str, Any] | None = None, say: Callable[[str], None] = print) -> float | None:
    """Compile ahead when some kernel is not in the cache, telling the user before and after; return
    the seconds spent compiling, or None when everything was cached. ``inputs``: a point of the user's
    study, added to the warm-up points."""
    missing = uncached()
    if not missing:
        return None
    say(f"compiling {len(missing)} solver kernels for their first use after installation or a change of the "
        f"code (about {COMPILE_SECONDS} s on 2 cores, once: later runs load them from numba's cache; "
        "`make setup` does this ahead)")
    seconds = compile_ahead(warm_up_points([inputs] if inputs else []))
    say(f"compiled in {seconds:.0f} s")
    return seconds
