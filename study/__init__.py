"""study: parameter studies of a rotating drill pipe striking the bore-hole wall.

Layers (imports point down the list only):

- ``study.physics``  pure functions of arrays, SI units, no I/O;
- ``study.solvers``  methods for one design point, one registry, results with status;
- ``study.workflow`` config, grid, parallel sweep, CF netCDF dataset;
- ``study.charts`` and ``study.cli``  presentation.
"""

import os
import re

# One BLAS thread per process, unless the user set it: a design point's matrices are small (tens to hundreds of
# rows) and the parallelism is across points (the sweep's worker processes); a multithreaded BLAS on cores the
# workers already fill waits for its own threads. Measured on the project's 2-core machine under load: one
# (5 x 4048)(4048 x 101) product took 0.3-0.5 s with OpenBLAS's default threads, 0.3 ms with one. It takes effect
# when study is imported before numpy (the ``study`` command, its dask workers, which inherit it, and the tests).
for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")


def _compiled_without_avx512() -> None:
    """With ``STUDY_AVX512=0`` in the environment (and ``NUMBA_CPU_FEATURES`` not set by the user), compile the numba
    kernels for this machine's features without AVX-512. Measured on the project's 2-core machine
    (docs/workers.md): the reference model's compiled step is no slower in one process without it (2.85 against
    2.82 µs) and does not slow when both cores run it (2.79 µs; 3.10 µs with AVX-512), so a sweep of the default
    study on two workers took 9 min 17 s instead of 10 min 13–21 s; but the fast periodic solution's span search,
    written for wide vectors, took 1.8 times as long (a median of 65 against 36 ms). So the default keeps AVX-512, and
    a user whose sweeps run the reference model on every core may turn it off. (Measured with the reference kernel's
    since-removed fastmath licence; not re-measured without it.) Like the BLAS threads above, it takes
    effect when study is imported before numba."""
    if os.environ.get("STUDY_AVX512", "1") != "0" or "NUMBA_CPU_FEATURES" in os.environ:
        return
    try:
        from llvmlite import binding

        features = binding.get_host_cpu_features().flatten()
    except Exception:  # noqa: BLE001 - no llvmlite, or no features to read: numba's own choice stands
        return
    os.environ["NUMBA_CPU_FEATURES"] = re.sub(r"\+([\w.-]*avx512[\w.-]*)", r"-\1", features)


_compiled_without_avx512()

__version__ = "0.2.0"
