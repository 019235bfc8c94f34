"""Belt-drive dynamics: the discrete multibody model of Kubas (seed 000), validated and fast.

``Model`` is the model file; ``run`` simulates it; ``check`` reports layout and statics;
``plot`` draws the standard figures.
"""
from .model import Model


def run(model, progress=None):
    from .simulate import run as _run

    return _run(model, progress=progress)


def check(model) -> str:
    from .statics import report

    return report(model)


def warmup():
    """Load (or compile) the numba kernels once, e.g. on each Dask worker before its first case."""
    from .simulate import warm

    warm()


def plot(result, outdir):
    from .plots import plot_all

    return plot_all(result, outdir)


__all__ = ["Model", "run", "check", "plot", "warmup"]
