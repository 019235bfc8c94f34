"""Gear-train torsional dynamics (seed 003): time-varying mesh stiffness, dynamic factor K_v.

``Model`` is the model file (``kind = "gear-train"``); ``run`` simulates it (and sweeps the
input speed if asked); ``check`` reports geometry, stiffness and natural frequencies; ``plot``
draws the standard figures.
"""
from .model import Model


def run(model, progress=None):
    from .simulate import run as _run

    return _run(model, progress=progress)


def check(model) -> str:
    from .report import report

    return report(model)


def plot(result, outdir):
    from .plots import plot_all

    return plot_all(result, outdir)


__all__ = ["Model", "run", "check", "plot"]
