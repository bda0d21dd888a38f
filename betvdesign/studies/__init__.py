"""Design-space studies on serial, process or dask executors.

Design-space studies: push/pull map, vertical regime diagram, Δs against λ,
tolerance Monte Carlo and calibration, on serial / process / dask executors with
streamed, resumable results (see each module's docstring).
"""
