"""The shared core every analysis and the front use: the model file's base classes and loading
(model.py), units at the edge (units.py), errors (errors.py) and environment limits (limits.py),
results and their netCDF / JSON form (results.py, outputs.py), criteria and the verdict
(criteria.py), diagnostics (diagnostics.py), the analysis registry (analyses.py), the steady window
(window.py), tables and root finding (tables.py, _roots.py), plotting helpers (plotting.py).
It imports no analysis, the front or the mechanics (the registry names the analyses by string)."""
