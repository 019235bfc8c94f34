"""What every analysis's plots share: figures without pyplot, and the run's status on each figure.

Plot functions of the analyses take the data and an optional ``ax`` (``plot_x(ds, ax=None)``);
``plot_all(result, outdir)`` draws the standard set, calls :func:`mark_status` on each figure and
saves it with :func:`save`, so a figure of a run that ended in ``warning`` or ``failed`` says so
on its face. matplotlib is imported only where a figure is made (importing it costs 0.3 s), so
that :class:`Painters` forked before a solve import it on the core the solve leaves idle.
"""
from __future__ import annotations

import contextlib
import os
from pathlib import Path

_COLOURS = {"warning": "#b8860b", "failed": "#b22222"}


def figure(nrows: int = 1, ncols: int = 1, size=(8, 3.2), **kw):
    """A constrained-layout Figure and its 2-D array of axes (never pyplot: runs headless)."""
    from matplotlib.figure import Figure

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


def mark_status(fig, result) -> None:
    """Write the run's status across the top of ``fig`` when it is not a clean success."""
    text = status_text(result)
    if text:
        fig.suptitle(text, color=_COLOURS[result.status], fontsize=10, fontweight="bold")


def literal(fig) -> None:
    """Draw every text of ``fig`` as written: names are data, and a ``$`` in a pulley name or a
    study value is not matplotlib math text (an unknown command in it would end the drawing).
    The package's own labels use Unicode (mm\u00b2), not math text."""
    from matplotlib.text import Text
    from matplotlib.ticker import LogFormatter, LogFormatterMathtext

    for t in fig.findobj(Text):
        t.set_parse_math(False)
    # a log axis labels its ticks in math text ($\mathdefault{10^{-1}}$), which would print raw:
    # plain numbers instead (0.1, 1, 10)
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            if isinstance(axis.get_major_formatter(), LogFormatterMathtext):
                axis.set_major_formatter(LogFormatter(labelOnlyBase=True))
            if isinstance(axis.get_minor_formatter(), LogFormatterMathtext):
                axis.set_minor_formatter(LogFormatter(labelOnlyBase=True))


def savefig(fig, path, **kw) -> Path:
    """``fig.savefig`` with every text literal (tick labels made while drawing too), written by
    replacing ``path`` (never through a link there; see :mod:`drivedyn.core.outputs`)."""
    import matplotlib

    from .outputs import replace_write

    path = Path(path)
    literal(fig)
    kw.setdefault("format", path.suffix.lstrip(".") or "png")

    def write(tmp):
        with matplotlib.rc_context({"text.parse_math": False}):
            fig.savefig(tmp, **kw)
    return replace_write(path, write)


def save_animation(anim, path, **kw) -> Path:
    """``anim.save`` with literal texts, written by replacing ``path`` (as :func:`savefig`)."""
    import matplotlib

    from .outputs import replace_write

    def write(tmp):
        with matplotlib.rc_context({"text.parse_math": False}):
            anim.save(str(tmp), **kw)
    return replace_write(path, write)


def save_gif(fig, path, frames: int, draw_frame, fps: float = 12) -> Path:
    """An animated GIF of ``fig``: what it holds now is drawn once (its layout fixed then), and
    each frame ``k`` draws only the artists ``draw_frame(k)`` adds and returns, over that still.
    matplotlib's FuncAnimation laid out and drew the whole figure again for every frame: 15 s for
    the 48 frames of a toothed mesh on a 2-core AMD EPYC (now 1.7 s), most of it in the layout and
    the axes' ticks. Written by
    replacing ``path`` (as :func:`savefig`)."""
    import matplotlib
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from PIL import Image

    from .outputs import replace_write

    with matplotlib.rc_context({"text.parse_math": False}):
        canvas = FigureCanvasAgg(fig)
        literal(fig)
        canvas.draw()
        fig.set_layout_engine("none")        # the still's layout holds for every frame
        still = canvas.copy_from_bbox(fig.bbox)
        images = []
        for k in range(frames):
            canvas.restore_region(still)
            arts = draw_frame(k)
            for a in arts:         # (texts made here are literal: rc_context above)
                fig.draw_artist(a)
            images.append(Image.frombuffer("RGBA", canvas.get_width_height(), bytes(canvas.buffer_rgba()),
                                           "raw", "RGBA", 0, 1).convert("RGB"))
            for a in arts:
                a.remove()

    def write(tmp):
        images[0].save(tmp, format="GIF", save_all=True, append_images=images[1:],
                       duration=round(1000 / fps), loop=0)
    return replace_write(Path(path), write)


def save(fig, path: Path, result=None, files: list | None = None, **kw) -> Path:
    """Mark the status (if ``result``), save ``fig`` to ``path`` and append it to ``files``."""
    if result is not None:
        mark_status(fig, result)
    if str(path).endswith(".png"):
        kw.setdefault("pil_kwargs", {"compress_level": 1})     # 25 % faster to write, files ~30 % larger
    savefig(fig, path, **kw)
    if files is not None:
        files.append(Path(path))
    return Path(path)


class Painters:
    """Processes forked before a long solve that write its outputs after it.

    While the solve runs on one core they import matplotlib, h5netcdf and xarray's writers and
    write a tiny figure and netCDF file on the other, one painter after the other, so that writing starts at
    full speed when the result is there. ``submit(result, fn, *args)`` runs ``fn(result, *args)`` in a
    painter; the result travels once, pickled to a temporary file each painter reads once.
    :meth:`start` gives None where forking is unsafe (threads running) or pointless (one core).
    """

    def __init__(self, module: str, workers: int = 2):
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor

        ctx = multiprocessing.get_context("fork")
        self._ex = ProcessPoolExecutor(workers, mp_context=ctx, initializer=_painter_start, initargs=(module, ctx.Lock()))
        self._ex.submit(int)       # with fork, the first job starts every worker: now, before the solve
        self._pickled = None       # (id of the result, temporary file)

    @classmethod
    def start(cls, module: str, workers: int = 2):
        import threading

        if workers < 2 or (os.cpu_count() or 1) < 2 or not hasattr(os, "fork") or threading.active_count() != 1:
            return None
        return cls(module, workers)

    def submit(self, result, fn, *args):
        if self._pickled is None or self._pickled[0] != id(result):
            import pickle
            import tempfile

            self._forget()
            fd, path = tempfile.mkstemp(prefix="drivedyn-", suffix=".pickle")
            with os.fdopen(fd, "wb") as f:
                pickle.dump(result, f, protocol=pickle.HIGHEST_PROTOCOL)
            self._pickled = (id(result), path)
        return self._ex.submit(_painter_call, self._pickled[1], fn, *args)

    def _forget(self):
        if self._pickled is not None:
            Path(self._pickled[1]).unlink(missing_ok=True)
            self._pickled = None

    def close(self):
        self._ex.shutdown(wait=True, cancel_futures=True)
        self._forget()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


_DRAW = None     # the draw(k) of draw_all's forked workers (inherited, never pickled)


def _draw_forked(k):
    return _DRAW(k)


def draw_all(count: int, draw, meanwhile=None, workers=None) -> list:
    """``[draw(k) for k in range(count)]``, the figures of a run. Where this process runs no other
    thread, two processes forked now draw them in parallel while this one runs ``meanwhile()``
    (1.5x faster on two cores, measured on a belt drive's seven figures); else one by one after
    it. ``workers=1`` forces the serial path."""
    import threading

    global _DRAW
    workers = min(2, os.cpu_count() or 1) if workers is None else workers
    if workers > 1 and count > 2 and threading.active_count() == 1 and hasattr(os, "fork"):
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor

        # matplotlib loaded and its first figure's fonts and text set up once, here, before the
        # fork: each child otherwise pays them (0.3-0.5 s) on the critical path of a short run
        rehearse_png()
        _DRAW = draw
        try:
            # forked: the children inherit draw and what it reads; only what it returns travels back
            with ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("fork")) as ex:
                pending = ex.map(_draw_forked, range(count))
                if meanwhile is not None:
                    meanwhile()
                return list(pending)
        finally:
            _DRAW = None
    if meanwhile is not None:
        meanwhile()
    return [draw(k) for k in range(count)]


def write_figures(jobs, outdir, result, meanwhile=None, workers=None, **kw) -> list[Path]:
    """Draw ``jobs``, (file name, function returning its Figure), by :func:`draw_all` and save each
    into ``outdir`` with the run's status on it (:func:`save`; ``kw`` to savefig); their paths, in
    the jobs' order. A function that writes its own file (an animation) returns its path instead."""
    outdir = Path(outdir)
    status = StatusOnly.of(result)

    def draw(k):
        name, make = jobs[k]
        out = make()
        return str(out) if isinstance(out, (str, Path)) else str(save(out, outdir / name, status, None, **kw))
    return [Path(p) for p in draw_all(len(jobs), draw, meanwhile, workers)]


_PAINTER_RESULT = None     # (file, Result) last read by this painter


def _painter_start(module: str, one_at_a_time):
    import importlib
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)   # Ctrl-C stops the parent, which ends its painters
    # a lower priority: on a first run two processes compile the kernels on the two cores, and the
    # painters' start-up (1-2 s each) took its share of them; on an idle core it runs at full speed
    # (the solve, the wait on the second process's compile)
    with contextlib.suppress(OSError, AttributeError):
        os.nice(10)
    with one_at_a_time:     # one painter loads at a time: together they would slow the solve on two cores
        importlib.import_module(module)
        _rehearse()


def _rehearse():
    """Write a tiny netCDF file and PNG: the first of each costs 0.2-0.3 s more than the next
    (imports, xarray's backend lookup, which imports dask.distributed, fonts, mathtext), measured."""
    import tempfile

    import numpy as np
    import xarray as xr

    with tempfile.TemporaryDirectory() as tmp:
        xr.Dataset({"x": ("t", np.zeros(3))}).to_netcdf(Path(tmp) / "r.nc", engine="h5netcdf")
    rehearse_png()


def rehearse_png():
    """Draw and write a tiny PNG: matplotlib's imports, fonts and mathtext set up for the figures."""
    import io

    from matplotlib.figure import Figure

    fig = Figure(figsize=(2, 2))
    ax = fig.subplots(2, 1)
    ax[0].plot([1, 2], [1, 2], label="x")
    ax[0].legend()
    ax[0].set_title("x")
    ax[1].semilogy([1, 2], [1, 10])
    fig.savefig(io.BytesIO(), format="png", dpi=30)


def _painter_call(path: str, fn, *args):
    global _PAINTER_RESULT
    if _PAINTER_RESULT is None or _PAINTER_RESULT[0] != path:
        import pickle

        with open(path, "rb") as f:
            _PAINTER_RESULT = (path, pickle.load(f))
    return fn(_PAINTER_RESULT[1], *args)


def save_result(result, outdir):
    """``result.save(outdir)`` (a module function, to be run in a painter)."""
    return result.save(outdir)
