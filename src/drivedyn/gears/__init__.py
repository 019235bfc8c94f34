"""Gear-train torsional dynamics (seed 003): time-varying mesh stiffness, dynamic factor K_v.

``Model`` is the model file (``kind = "gear-train"``); ``run`` simulates it (and sweeps the
input speed if asked); ``check`` reports geometry, stiffness and natural frequencies; ``plot``
draws the standard figures.

The entry points are registered in ``drivedyn.core.analyses`` and reached through ``drivedyn.run``,
``drivedyn.check`` and ``drivedyn.plot``.
"""
from .model import Model

__all__ = ["Model"]
