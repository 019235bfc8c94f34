"""Standard figures of a span-stability run: the chart (seed fig. 3a), the zoomed tongue (fig. 3b),
the Floquet map, frequency-vs-tension curves, the tooth force and (if computed) the response.

Each ``plot_*`` takes the result Dataset (and summary) and an ``ax`` (None: a new Figure) and
returns the artists; nothing touches pyplot or the backend.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.colors import LogNorm
from matplotlib.figure import Figure

DIVERGENCE = "#f4b6b0"
TONGUE = "#3b6fb6"


def _ax(ax, size=(7, 5)):
    if ax is not None:
        return ax.figure, ax
    fig = Figure(figsize=size, layout="constrained")
    return fig, fig.subplots()


def _mark_model(ax, summary):
    return ax.plot(summary["pretension"], summary["speed"], marker="*", ms=12, color="k", ls="none",
                   label=f"model: {summary['pretension']:.4g} N, {summary['speed']:.4g} m/s")


def plot_chart(ds, summary, ax=None, suffix="", inset=True):
    """Stability chart in the (F0, V) plane: divergence region, tongues, Floquet-unstable points."""
    fig, ax = _ax(ax)
    F0 = ds[f"pretension{suffix}"].values
    V = ds[f"speed{suffix}"].values
    vcr = ds[f"critical_speed{suffix}"].values
    top = max(V.max(), vcr.max()) * 1.05
    arts = [ax.fill_between(F0, vcr, top, color=DIVERGENCE, label="divergence (V > V_cr)")]
    arts += ax.plot(F0, vcr, color="#b03a2e", lw=1.5, label="critical speed V_cr")
    if f"floquet_multiplier{suffix}" in ds:
        region = ds[f"region{suffix}"].values
        rho = ds[f"floquet_multiplier{suffix}"].values
        show = np.where(region == 2, rho - 1.0, np.nan).T
        if np.isfinite(show).any():
            arts.append(ax.pcolormesh(F0, V, show, cmap="Blues", shading="nearest",
                                      norm=LogNorm(vmin=max(np.nanmin(show), 1e-6), vmax=max(np.nanmax(show), 2e-6))))
    fine = "_fine" if not suffix and "tongue_low_fine" in ds else suffix
    Vt = ds["speed_tongues"].values if fine == "_fine" else V
    lo, hi = ds[f"tongue_low{fine}"].values, ds[f"tongue_high{fine}"].values
    arts += _tongues(ax, Vt, lo, hi, ds[f"first_order_low{fine}"].values, ds[f"first_order_high{fine}"].values)
    arts += _mark_model(ax, summary)
    ax.set_xlim(F0.min(), F0.max())
    ax.set_ylim(V.min(), V.max())
    ax.set_xlabel("pretension F0 (N)")
    ax.set_ylabel("belt speed V (m/s)")
    ax.legend(loc="upper left", fontsize=8)
    ax.grid(alpha=0.3)
    if inset and fine == "_fine":
        ins = ax.inset_axes([0.5, 0.08, 0.47, 0.4])
        _tongues(ins, Vt, lo, hi, ds["first_order_low_fine"].values, ds["first_order_high_fine"].values)
        ins.plot(summary["pretension"], summary["speed"], marker="*", ms=9, color="k")
        ins.set_xlim(F0.min(), F0.max())
        ins.set_ylim(0.0, Vt.max())
        ins.tick_params(labelsize=7)
        ins.set_title("tongues n = 1, 2, 3 (magnified in V)", fontsize=7)
        ins.grid(alpha=0.3)
    return arts


def _tongues(ax, V, lo, hi, fo_lo, fo_hi):
    arts = []
    for n in range(lo.shape[0]):
        arts.append(ax.fill_betweenx(V, lo[n], hi[n], color=TONGUE, alpha=0.9 if n == 0 else 0.5, lw=0.8,
                                     label="exact tongue n = 1" if n == 0 else ("higher tongues n = 2.." if n == 1 else None)))
    arts += ax.plot(fo_lo, V, "--", color="#e67e22", lw=1.0, label="first order (seed)")
    arts += ax.plot(fo_hi, V, "--", color="#e67e22", lw=1.0)
    return arts


def plot_tongue(ds, summary, ax=None):
    """Zoomed principal tongue (seed fig. 3b): Floquet map, exact and first-order boundaries."""
    fig, ax = _ax(ax)
    F0 = ds["pretension_zoom"].values
    V = ds["speed_zoom"].values
    arts = []
    if "floquet_multiplier_zoom" in ds:
        rho = ds["floquet_multiplier_zoom"].values.T
        m = ax.pcolormesh(F0, V, np.where(rho > 1 + 1e-6, rho, np.nan), cmap="Blues", shading="nearest")
        arts.append(m)
        fig.colorbar(m, ax=ax, label="largest Floquet multiplier |lambda| (full Phi)")
    lo, hi = ds["tongue_low_zoom"].values[0], ds["tongue_high_zoom"].values[0]
    arts += ax.plot(lo, V, color="k", lw=1.2, label="exact (Mathieu a_1, b_1)")
    arts += ax.plot(hi, V, color="k", lw=1.2)
    a, b = ds["first_order_low_zoom"].values, ds["first_order_high_zoom"].values
    arts += ax.plot(a, V, "--", color="#e67e22", lw=1.2, label="first order (seed)")
    arts += ax.plot(b, V, "--", color="#e67e22", lw=1.2)
    vcr = ds["critical_speed_zoom"].values
    if vcr.min() < V.max():
        arts.append(ax.fill_between(F0, vcr, V.max(), color=DIVERGENCE, label="divergence"))
    for band in summary.get("resonance_bands", []):
        arts += ax.plot([summary["pretension"]] * 2, band, color="#c0392b", lw=3, solid_capstyle="butt",
                        label=f"band at model F0: {band[0]:.4g}-{band[1]:.4g} m/s")
    arts += _mark_model(ax, summary)
    ax.set_xlim(F0.min(), F0.max())
    ax.set_ylim(V.min(), V.max())
    ax.set_xlabel("pretension F0 (N)")
    ax.set_ylabel("belt speed V (m/s)")
    ax.set_title(f"principal parametric resonance ({summary.get('period_convention', '')} period)")
    ax.legend(loc="upper left", fontsize=8)
    ax.grid(alpha=0.3)
    return arts


def plot_floquet(ds, summary, ax=None):
    """Map of log10 of the largest Floquet multiplier over the full chart."""
    fig, ax = _ax(ax)
    F0 = ds["pretension"].values
    V = ds["speed"].values
    rho = ds["floquet_multiplier"].values.T
    with np.errstate(divide="ignore", invalid="ignore"):
        m = ax.pcolormesh(F0, V, np.log10(np.maximum(rho, 1e-300)), cmap="magma_r", shading="nearest",
                          vmin=0.0, vmax=max(np.nanpercentile(np.log10(rho), 99), 1e-3))
    fig.colorbar(m, ax=ax, label="log10 max |lambda| per period")
    arts = [m] + ax.plot(F0, ds["critical_speed"].values, color="#2e86c1", lw=1, label="V_cr")
    arts += _mark_model(ax, summary)
    ax.set_ylim(V.min(), V.max())
    ax.set_xlabel("pretension F0 (N)")
    ax.set_ylabel("belt speed V (m/s)")
    ax.set_title("Floquet multipliers of the Hill equation (full Phi)")
    ax.legend(loc="upper left", fontsize=8)
    if "floquet_multiplier_zoom" in ds:
        # the resonance tongues are far narrower than this grid near V = 0: the zoomed map
        # (computed on its own fine grid around the model's point) as an inset
        ins = ax.inset_axes([0.52, 0.08, 0.44, 0.42])
        rz = ds["floquet_multiplier_zoom"].values.T
        with np.errstate(divide="ignore", invalid="ignore"):
            ins.pcolormesh(ds["pretension_zoom"].values, ds["speed_zoom"].values, np.log10(np.maximum(rz, 1e-300)),
                           cmap="magma_r", shading="nearest", vmin=0.0,
                           vmax=max(np.nanpercentile(np.log10(rz), 99), 1e-3))
        _mark_model(ins, summary)
        ins.set_title("zoom on tongue n = 1 (own grid)", fontsize=7)
        ins.tick_params(labelsize=6)
        arts.append(ins)
    return arts


def plot_frequencies(ds, summary, ax=None):
    """First span frequency against tension (string, beam, moving beam) and the measurement."""
    fig, ax = _ax(ax)
    F0 = ds["pretension"].values
    arts = []
    beam, moving = ds["frequency_beam"].values, ds["frequency_moving_beam"].values
    gap = float(np.nanmax(np.abs(moving - beam) / np.maximum(np.abs(beam), 1e-300)))
    # the moving beam drawn first and wide, the beam dashed on top: at low speed they coincide
    for k, style, lw, z in (("string", ":", 1.5, 3), ("moving_beam", "-", 4, 1), ("beam", "--", 1.5, 2)):
        label = k.replace("_", " ")
        if k == "moving_beam":
            label += f" (V = {summary['speed']:.3g} m/s; differs from the beam by {100 * gap:.2g} % at most)"
        arts += ax.plot(F0, ds[f"frequency_{k}"].values, style, lw=lw, zorder=z, label=label,
                        alpha=0.45 if k == "moving_beam" else 1.0)
    me = summary.get("measurement")
    if me:
        arts.append(ax.errorbar([me["tension"]], [me["frequency"]], xerr=[me["uncertainty"]], fmt="o", color="k",
                                label=f"measured {me['frequency']:.4g} Hz -> {me['tension']:.4g} +- {me['uncertainty']:.2g} N"))
    ax.set_xlabel("span tension (N)")
    ax.set_ylabel("first span frequency (Hz)")
    ax.set_title("first span frequency against tension"
                 + ("\n(and the tension a measured frequency gives)" if me else ""), fontsize=10)
    ax.legend(loc="lower right", fontsize=8)
    ax.grid(alpha=0.3)
    return arts


def plot_tooth_force(ds, summary, ax=None):
    """Tooth force over one tooth and its Fourier series."""
    fig, ax = _ax(ax, (7, 4))
    phi = ds["phase"].values
    arts = []
    if "tooth_force" in ds:
        arts += ax.plot(phi, ds["tooth_force"].values, color="k", lw=2, label="tooth force (given)")
    arts += ax.plot(phi, ds["tooth_force_series"].values, color="#2e86c1",
                    label=f"Fourier series, {ds.sizes['harmonic']} harmonics (F1 = {summary['f1']:.4g} N)")
    ax.set_xlabel("phase over one tooth (rad)")
    ax.set_ylabel("force (N)")
    ax.set_title("tooth force over one tooth pitch and its Fourier series", fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return arts


def plot_response(ds, summary, ax=None):
    """Modal coordinate q(t) (mid-span deflection)."""
    fig, ax = _ax(ax, (8, 3.5))
    arts = ax.plot(ds["time"].values, 1e3 * ds["modal_coordinate"].values, lw=0.8)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("q (mm)")
    ax.set_title("modal coordinate (mid-span deflection)")
    ax.grid(alpha=0.3)
    return arts


def plot_all(result, outdir, meanwhile=None, workers=None) -> list[Path]:
    """Write the standard PNGs of a span-stability result into ``outdir`` (a warned run says so on
    each); plotting.write_figures draws them (in two processes where it can; ``workers=1``: here)
    while this one runs ``meanwhile()``."""
    from ..core import plotting

    ds, s = result.ds, result.summary
    jobs = [("span-chart.png", plot_chart, (7, 5)), ("span-tongue.png", plot_tongue, (7.5, 5)),
            ("span-frequencies.png", plot_frequencies, (7, 4.5)), ("span-tooth-force.png", plot_tooth_force, (7, 4))]
    if "floquet_multiplier" in ds:
        jobs.append(("span-floquet.png", plot_floquet, (7, 5)))
    if "modal_coordinate" in ds:
        jobs.append(("span-response.png", plot_response, (8, 3.5)))

    def figure(fn, size):
        fig = Figure(figsize=size, layout="constrained")
        fn(ds, s, fig.subplots())
        if fn is plot_chart:
            fig.axes[0].set_title(f"stability chart: {ds.attrs.get('title', '')}", fontsize=10)
        return fig
    return plotting.write_figures([(name, lambda fn=fn, size=size: figure(fn, size)) for name, fn, size in jobs],
                                  outdir, result, meanwhile, workers, dpi=110)
