"""study: parameter studies of a rotating drill pipe striking the bore-hole wall.

Layers (imports point down the list only):

- ``study.physics``  pure functions of arrays, SI units, no I/O;
- ``study.solvers``  methods for one design point, one registry, results with status;
- ``study.workflow`` config, grid, parallel sweep, CF netCDF dataset;
- ``study.charts`` and ``study.cli``  presentation.
"""

import os

# One BLAS thread per process, unless the user set it: a design point's matrices are small (tens to hundreds of
# rows) and the parallelism is across points (the sweep's worker processes); a multithreaded BLAS on cores the
# workers already fill waits for its own threads. Measured on the project's 2-core machine under load: one
# (5 x 4048)(4048 x 101) product took 0.3-0.5 s with OpenBLAS's default threads, 0.3 ms with one. It takes effect
# when study is imported before numpy (the ``study`` command, its dask workers, which inherit it, and the tests).
for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

__version__ = "0.2.0"
