"""Belt-drive dynamics: the discrete multibody model of Kubas (seed 000), validated and fast.

``Model`` is the model file; ``run`` simulates it; ``check`` reports layout and statics;
``plot`` draws the standard figures.

The entry points are registered in ``drivedyn.core.analyses`` and reached through ``drivedyn.run``,
``drivedyn.check`` and ``drivedyn.plot``.
"""
from .model import Model

__all__ = ["Model"]
