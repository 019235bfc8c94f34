"""Timing-belt meshing: profile catalogue and exact tooth/groove interference (seed 001, Pakula).

``Model`` is the model file (``kind = "toothed-mesh"``); ``run`` sweeps a belt tooth through its
groove (entry, full seating, exit) and measures the overlap; ``check`` reports the pair's
geometry; ``plot`` draws the superposed contours (seed figs. 6-8), interference curves, the flank
colour map, maps and an animation.

The entry points are registered in ``drivedyn.core.analyses`` and reached through ``drivedyn.run``,
``drivedyn.check`` and ``drivedyn.plot``.
"""
from .model import Model

__all__ = ["Model"]
