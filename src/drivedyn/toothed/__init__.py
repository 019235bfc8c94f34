"""Timing-belt meshing: profile catalogue and exact tooth/groove interference (seed 001, Pakula).

``Model`` is the model file (``kind = "toothed-mesh"``); ``run`` sweeps a belt tooth through its
groove (entry, full seating, exit) and measures the overlap; ``check`` reports the pair's
geometry; ``plot`` draws the superposed contours (seed figs. 6-8), interference curves, the flank
colour map, maps and an animation.
"""
from .model import Model


def run(model, progress=None):
    from .analysis import run as _run

    return _run(model, progress=progress)


def check(model) -> str:
    from .report import report

    return report(model)


def plot(result, outdir):
    from .plots import plot_all

    return plot_all(result, outdir)


__all__ = ["Model", "run", "check", "plot"]
