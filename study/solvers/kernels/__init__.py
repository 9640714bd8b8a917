"""Compiled numerics the methods call: the reference model's whirl integrator, the event-driven flights with the
orbits and revolutions sampled on them, the stress extremes. Imports physics (and the model) only: no method."""
