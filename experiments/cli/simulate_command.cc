// Filled in by the simulator commit.
