"""Steady mechanics: what creep theory and the linear dynamics know without a run. The steady
running state with slip arcs, creep and slip margins (creep.py), the tensioners' running balance
(running.py), the rotational modes and the drive's linear model (modes.py), span flap (flap.py), the
supplier's duty cycle (duty.py) and belt life (life.py). Imports only the geometry below it."""
