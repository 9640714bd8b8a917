"""The model of a design point and of what a method returns: the typed :class:`~study.solvers.model.scene.Scene`,
each method's options, the :class:`~study.solvers.model.result.PointResult`, the gate (the one place that says
``ok``) and the design limits. Imports physics only: no method, no kernel."""
