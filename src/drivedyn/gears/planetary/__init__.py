"""Planetary stages: phasing, torsional modes and load sharing (stage.py), the lateral-torsional
model (lateral.py), time runs (dynamics.py, _kernels.py) and gearboxes of stages (gearbox.py).
Imports the mesh, rating and train rooms (its kernels reuse the train's periodic integrator)."""
