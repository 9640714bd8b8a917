"""Physics of the drill-pipe impact scene: pure functions of numpy arrays, SI units, no I/O."""
