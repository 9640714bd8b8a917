"""study: parameter studies of a rotating drill pipe striking the bore-hole wall.

Layers (imports point down the list only):

- ``study.physics``  pure functions of arrays, SI units, no I/O;
- ``study.solvers``  methods for one design point, one registry, results with status;
- ``study.workflow`` config, grid, parallel sweep, CF netCDF dataset;
- ``study.charts`` and ``study.cli``  presentation.
"""

__version__ = "0.2.0"
