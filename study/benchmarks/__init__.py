"""The benchmarks ``study bench`` runs (:mod:`study.bench`), apart from the solvers: the methods' work and
precision, timed against the reference implementations a user would write instead (scipy's solve_ivp on the same
equations with a penalty contact) and against converged runs. One module per method benchmarked.
"""
