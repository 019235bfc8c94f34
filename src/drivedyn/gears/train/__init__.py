"""The parallel-axis train (seed 003): topology, statics and modes (system.py), the compiled
kernels' inputs (kernel_inputs.py) and kernels (_kernels.py), speed sweeps with Floquet stability
(sweep.py), step checks and diagnostics (checks.py). Imports the mesh room only."""
