"""Study engine: grids, executors, the resumable store and the runner."""
