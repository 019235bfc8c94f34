"""Belt span vibration and stability (Belyaev, seed 002): critical speed, parametric resonance
(first order, exact Mathieu, Floquet), span frequencies and tension from a measured frequency.

``Model`` is the model file; ``run`` computes the stability chart and the span quantities;
``check`` reports what is known without running; ``plot`` draws the standard figures.
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
