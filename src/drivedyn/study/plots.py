"""Plots of a study: any summary key against the swept parameters.

One parameter: a line (failed cases shown as gaps and marked on the axis). Two grid parameters:
a map (``pcolormesh`` on the parameter values) with failed cases crossed out; this is the
stability map of a span study when the key is a stability flag or margin. Cases that ended with
diagnostics (status "warning": outside the model's valid regime) are left out of the line and
the colour scale, so that they cannot swamp it, and marked with an orange triangle. Sampled designs, or more
than two grid dimensions: one scatter panel per parameter (main effects), coloured by a second
parameter. Built on ``matplotlib.figure.Figure`` (no pyplot, no backend), so it runs headless.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .shown import parameter_names


def _label(ds, name):
    """'critical speed margin (m/s)': the key's last part in words, its unit ('ratio' for '1')."""
    var = ds[name]
    unit = var.attrs.get("units", "")
    unit = "ratio" if unit == "1" else unit
    if name in ds.coords:        # a parameter: its label, as the study file names it
        return f"{name} ({unit})" if unit else name
    words = str(var.attrs.get("long_name", name)).split(".")[-1].replace("_", " ")
    return f"{words} ({unit})" if unit else words


def _numeric(ds, name):
    return ds[name].dtype.kind in "fiub"


def _monotonic(coord) -> bool:
    """True for numeric axes in strictly increasing or decreasing order (else: plot by index)."""
    if coord.dtype.kind not in "fiu":
        return False
    d = np.diff(coord.values.astype(float))
    return bool(np.all(d > 0) or np.all(d < 0))


#: how cases that did not give a valid value are marked: status -> (marker, colour, legend label)
_MARKS = {"warning": ("^", "darkorange", "warning (see diagnostics)"), "failed": ("x", "C3", "failed")}


def _masks(ds):
    """(valid, {mark: mask}) of the cases: valid = success; warning; failed = everything else."""
    status = ds["status"]
    ok = status == "success"
    warn = status == "warning"
    return ok, {"warning": warn, "failed": ~ok & ~warn}


def plot_key(ds, key, fig=None):
    """Draw summary ``key`` of study Dataset ``ds`` against its parameters; returns the Figure.

    Parameters
    ----------
    ds : xarray.Dataset
        A study Dataset (``drivedyn.study.run_study(...).ds`` or ``xr.load_dataset("study.nc")``).
    key : str
        A numeric variable of ``ds`` (a collected summary key).
    fig : matplotlib.figure.Figure, optional
        Figure to draw into (a new one otherwise).
    """
    from matplotlib.figure import Figure

    if key not in ds.data_vars:
        close = [v for v in ds.data_vars if key in v][:3]
        raise KeyError(f"{key!r} is not in the study Dataset" + (f" (did you mean {', '.join(close)}?)" if close else ""))
    if not _numeric(ds, key):
        raise TypeError(f"{key!r} is not numeric and cannot be plotted")
    params = parameter_names(ds)
    from .shown import in_shown_units

    ds = in_shown_units(ds, [key] + [p for p in params if p in ds.variables])   # deg and rpm as the study writes them
    var = ds[key]
    fig = fig or Figure(figsize=(6.4, 4.8), layout="constrained")
    ok, marks = _masks(ds)
    grid = "case" not in var.dims
    extra = [d for d in var.dims if d not in params and d != "case"]
    if extra:  # a list-valued key: plot its first component
        var = var.isel({d: 0 for d in extra})
    title = ds.attrs.get("title", "study")
    if grid and len(params) == 1:
        p = params[0]
        ax = fig.add_subplot()
        x = ds[p].values
        numeric_x = ds[p].dtype.kind in "fiu"
        xs = x if numeric_x else np.arange(len(x))
        good = var.where(ok).values
        ax.plot(xs, good, "o-", label=key)
        floor = np.nanmin(good) if np.isfinite(good).any() else 0.0
        for mark, mask in marks.items():
            m = mask.values
            if m.any():
                sym, colour, label = _MARKS[mark]
                ax.plot(xs[m], np.full(m.sum(), floor), sym, color=colour, ms=8, label=label)
        if any(mask.values.any() for mask in marks.values()):
            ax.legend()
        if not numeric_x:
            ax.set_xticks(xs, [str(v) for v in x])
        ax.set_xlabel(_label(ds, p))
        ax.set_ylabel(_label(ds, key))
        ax.grid(True, alpha=0.3)
    elif grid and len(params) == 2:
        py, px = params  # first parameter up the page, second across: the Dataset's (row, column) order
        ax = fig.add_subplot()
        z = var.where(ok).transpose(py, px).values.astype(float)
        xv, yv = ds[px].values, ds[py].values
        xs = xv.astype(float) if _monotonic(ds[px]) else np.arange(len(xv), dtype=float)
        ys = yv.astype(float) if _monotonic(ds[py]) else np.arange(len(yv), dtype=float)
        mesh = ax.pcolormesh(xs, ys, np.ma.masked_invalid(z), shading="nearest", cmap="viridis")
        fig.colorbar(mesh, ax=ax, label=_label(ds, key))
        # contours only where the grid is fine enough for them to mean something
        if min(len(xs), len(ys)) >= 6 and np.isfinite(z).all() and np.nanmax(z) > np.nanmin(z):
            ax.contour(xs, ys, np.ma.masked_invalid(z), colors="white", linewidths=0.7, alpha=0.8)
        shown = False
        for mark, mask in marks.items():
            yy, xx = np.nonzero(mask.transpose(py, px).values)
            if len(xx):
                sym, colour, label = _MARKS[mark]
                ax.plot(xs[xx], ys[yy], sym, color=colour, ms=9, mew=2, label=label)
                shown = True
        if shown:
            ax.legend(loc="upper right", fontsize=8)
        if not _monotonic(ds[px]):
            ax.set_xticks(xs, [f"{v:.4g}" if isinstance(v, float) else str(v) for v in xv])
        if not _monotonic(ds[py]):
            ax.set_yticks(ys, [f"{v:.4g}" if isinstance(v, float) else str(v) for v in yv])
        ax.set_xlabel(_label(ds, px))
        ax.set_ylabel(_label(ds, py))
    else:
        flat = ds.stack(_c=params) if grid else ds.rename({"case": "_c"})
        fv = (var.stack(_c=params) if grid else var.rename({"case": "_c"})).values.astype(float)
        fok = (ok.stack(_c=params) if grid else ok.rename({"case": "_c"})).values
        axes = fig.subplots(1, len(params), sharey=True, squeeze=False)[0]
        colour = params[1] if len(params) > 1 and flat[params[1]].dtype.kind in "fiu" else None
        for ax, p in zip(axes, params):
            x = flat[p].values
            kw = {}
            if colour is not None and p != colour:
                kw = dict(c=flat[colour].values[fok].astype(float), cmap="viridis")
            sc = ax.scatter(x[fok], fv[fok], s=14, **kw)
            floor = np.nanmin(fv[fok]) if np.isfinite(fv[fok]).any() else 0.0
            for mark, mask in marks.items():
                fm = (mask.stack(_c=params) if grid else mask.rename({"case": "_c"})).values
                if fm.any():
                    sym, mark_colour, label = _MARKS[mark]
                    ax.scatter(x[fm], np.full(fm.sum(), floor), marker=sym, color=mark_colour, label=label)
            ax.set_xlabel(_label(ds, p))
            ax.grid(True, alpha=0.3)
        axes[0].set_ylabel(key)
        if colour is not None and len(params) > 1:
            fig.colorbar(sc, ax=list(axes), label=_label(ds, colour))
    fig.suptitle(f"{title}: {key}")
    return fig


def plot_study(ds, outdir, keys=None) -> list[Path]:
    """Write one PNG per summary key into ``outdir``; returns the files written.

    ``keys`` may hold glob patterns; default: the keys the study collected (``summary_keys``
    attr), numeric ones only.
    """
    import fnmatch

    outdir = Path(outdir)
    available = [k for k in ds.attrs.get("summary_keys", "").split("\n") if k and k in ds and _numeric(ds, k)]
    if keys is None:
        chosen = available
    else:
        chosen = [k for k in available if any(fnmatch.fnmatchcase(k.lower(), p.lower()) for p in keys)]
    if not chosen or not np.isin(ds["status"].values, ("success", "warning")).any():
        return []
    from ..core.outputs import file_stem, make_folder
    from ..core.plotting import savefig

    make_folder(outdir)
    files = []
    for k in chosen:
        fig = plot_key(ds, k)
        path = outdir / f"{file_stem(k.replace('.', '_'))}.png"
        savefig(fig, path, dpi=110)
        files.append(path)
    return files
