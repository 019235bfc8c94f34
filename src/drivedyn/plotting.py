"""What every analysis's plots share: figures without pyplot, and the run's status on each figure.

Plot functions of the analyses take the data and an optional ``ax`` (``plot_x(ds, ax=None)``);
``plot_all(result, outdir)`` draws the standard set, calls :func:`mark_status` on each figure and
saves it with :func:`save`, so a figure of a run that ended in ``warning`` or ``failed`` says so
on its face.
"""
from __future__ import annotations

from pathlib import Path

from matplotlib.figure import Figure

_COLOURS = {"warning": "#b8860b", "failed": "#b22222"}


def figure(nrows: int = 1, ncols: int = 1, size=(8, 3.2), **kw):
    """A constrained-layout Figure and its 2-D array of axes (never pyplot: runs headless)."""
    fig = Figure(figsize=size, layout="constrained")
    axes = fig.subplots(nrows, ncols, squeeze=False, **kw)
    return fig, axes


def ax_or_new(ax, size=(8, 3.2)):
    """``ax`` if given, else the single axes of a new figure."""
    if ax is not None:
        return ax
    return figure(size=size)[1][0, 0]


def status_text(result) -> str:
    """'' for a clean run; else e.g. 'WARNING: gross-slip, window-not-steady' or 'FAILED: ...'."""
    status = result.status
    if status == "success":
        return ""
    if status == "failed":
        return f"FAILED: {result.message}"[:110]
    codes = list(dict.fromkeys(d.code for d in result.diagnostics))
    return "WARNING: " + ", ".join(codes) + " (see summary.json)"


class StatusOnly:
    """What ``mark_status`` reads of a Result (status, message, diagnostics)."""

    def __init__(self, status, message, diagnostics):
        self.status, self.message, self.diagnostics = status, message, diagnostics

    @classmethod
    def of(cls, result):
        return cls(result.status, result.message, list(result.diagnostics))


def mark_status(fig: Figure, result) -> None:
    """Write the run's status across the top of ``fig`` when it is not a clean success."""
    text = status_text(result)
    if text:
        fig.suptitle(text, color=_COLOURS[result.status], fontsize=10, fontweight="bold")


def save(fig: Figure, path: Path, result=None, files: list | None = None, **kw) -> Path:
    """Mark the status (if ``result``), save ``fig`` to ``path`` and append it to ``files``."""
    if result is not None:
        mark_status(fig, result)
    if str(path).endswith(".png"):
        kw.setdefault("pil_kwargs", {"compress_level": 1})     # 25 % faster to write, files ~30 % larger
    fig.savefig(path, **kw)
    if files is not None:
        files.append(Path(path))
    return Path(path)
