"""wheel-sweep: run a slip sweep or a study matrix (wheels x soils x slips) of wheel-rig runs.

Modules: config (the sweep config: parsing, validation, the point matrix), toml_out (writes the
points' rig configs), runner (runs points concurrently, resume, signals), cli (command line).
Docs: docs/sweeps.md.
"""
