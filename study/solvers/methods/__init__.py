"""The methods, one module or package each (the periodic family in :mod:`study.solvers.methods.periodic`, the
reference model in :mod:`study.solvers.methods.reference`); a method imports kernels, physics and the model, and
another method only where tests/test_structure.py lists the edge with its reason."""
