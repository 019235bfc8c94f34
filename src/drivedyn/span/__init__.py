"""Belt span vibration and stability (Belyaev, seed 002): critical speed, parametric resonance
(first order, exact Mathieu, Floquet), span frequencies and tension from a measured frequency.

``Model`` is the model file; ``run`` computes the stability chart and the span quantities;
``check`` reports what is known without running; ``plot`` draws the standard figures.

The entry points are registered in ``drivedyn.core.analyses`` and reached through ``drivedyn.run``,
``drivedyn.check`` and ``drivedyn.plot``.
"""
from .model import Model

__all__ = ["Model"]
