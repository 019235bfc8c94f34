"""Standard figures of a belt-drive run (seed figs. 10-17) and an animation of the belt.

Functions are ``plot_x(ds, ..., ax=None)`` (a new figure when no ``ax``) and never touch pyplot or
the backend; ``plot_all`` marks every figure of a warned or failed run (drivedyn.plotting).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from .. import plotting


def _fig(nrows=1, height=3.2):
    fig = Figure(figsize=(8, height * nrows), layout="constrained")
    axes = fig.subplots(nrows, 1, sharex=True, squeeze=False)[:, 0]
    return fig, axes


def plot_speeds(ds, ax=None):
    ax = plotting.ax_or_new(ax)
    t = ds["time"].values
    for nm in ds["pulley"].values:
        ax.plot(t, ds["speed"].sel(pulley=nm), label=str(nm))
    ax.set_ylabel("speed (rad/s)")
    ax.set_title("pulley speeds (counter-clockwise positive)")
    ax.legend(loc="best", fontsize=8)
    ax.grid(alpha=0.3)


def plot_slip(ds, driver, ax=None):
    ax = plotting.ax_or_new(ax)
    t = ds["time"].values
    r = ds["pulley_radius"]
    vd = np.abs(ds["speed"].sel(pulley=driver) * r.sel(pulley=driver)).values
    ok = vd > 0.05 * max(np.max(vd), 1e-12)
    for nm in ds["pulley"].values:
        if nm == driver:
            continue
        v = np.abs(ds["speed"].sel(pulley=nm) * r.sel(pulley=nm)).values
        s = np.where(ok, 1 - v / np.where(ok, vd, 1), np.nan)
        ax.plot(t, 100 * s, label=f"{nm} vs {driver}")
    ax.set_ylabel("slip (%)")
    ax.set_title("slip 1 - |w r| / |w_d r_d|")
    ax.legend(loc="best", fontsize=8)
    ax.grid(alpha=0.3)


def plot_lines(ds, var, dim, ylabel, title, ax=None):
    ax = plotting.ax_or_new(ax)
    t = ds["time"].values
    for key in ds[dim].values:
        ax.plot(t, ds[var].sel({dim: key}), label=str(key))
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.legend(loc="best", fontsize=8)
    ax.grid(alpha=0.3)


def plot_energy(ds, ax=None):
    ax = plotting.ax_or_new(ax)
    t = ds["time"].values
    ax.plot(t, ds["work_in"], label="work in", color="k")
    D = ds["dissipated"]
    for m in ds["mechanism"].values:
        ax.plot(t, D.sel(mechanism=m), label=f"dissipated: {m}")
    ax.plot(t, ds["energy_change"], label="energy change (kinetic + potential)")
    ax.plot(t, ds["energy_residual"], label="residual (integration error)", ls="--")
    ax.set_ylabel("energy (J)")
    ax.set_xlabel("time (s)")
    ax.set_title("energy balance")
    ax.legend(loc="best", fontsize=8)
    ax.grid(alpha=0.3)


def draw_drive(ds, frame, ax, vmax=None):
    """Pulleys and the belt at one frame, segments coloured by the element force."""
    import matplotlib.patches as mpatches

    for j in range(ds.sizes["pulley"]):
        ax.add_patch(mpatches.Circle((float(ds["pulley_x"][j]), float(ds["pulley_y"][j])), float(ds["pulley_radius"][j]),
                                     fill=False, lw=1.2, color="0.4"))
        ax.annotate(str(ds["pulley"].values[j]), (float(ds["pulley_x"][j]), float(ds["pulley_y"][j])), ha="center",
                    va="center", fontsize=7, color="0.3")
    x = np.append(ds["belt_x"][frame].values, ds["belt_x"][frame].values[0])
    y = np.append(ds["belt_y"][frame].values, ds["belt_y"][frame].values[0])
    ten = ds["belt_tension"][frame].values
    vmax = vmax or max(float(ds["belt_tension"].max()), 1.0)
    sc = ax.scatter(x[:-1], y[:-1], c=ten, s=6, cmap="viridis", vmin=0, vmax=vmax)
    ax.plot(x, y, lw=0.5, color="0.6")
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(f"belt at t = {float(ds['frame_time'][frame]):.3f} s (colour: element force, N)")
    return sc


def plot_campbell(ds, frequencies_hz, driver, ax=None, orders=(1, 2, 3, 4, 6), rpm_max=None):
    """Campbell diagram: the drive's rotational modes (horizontal) against the orders of the
    driver's rotation (k x driver speed); crossings are resonances a run-up passes through."""
    ax = plotting.ax_or_new(ax)
    w = np.abs(ds["speed"].sel(pulley=driver).values)
    rpm_run = float(w.max()) * 30 / np.pi if len(w) else 0.0
    top_rpm = rpm_max or max(1.25 * rpm_run, 1.0)
    f_top = max([1.1 * f for f in frequencies_hz] + [orders[-1] * top_rpm / 60])
    for f in frequencies_hz:
        ax.axhline(f, color="C0", lw=1.2)
        ax.text(top_rpm * 0.99, f, f" {f:.1f} Hz", va="bottom", ha="right", fontsize=8, color="C0")
    n = np.array([0.0, top_rpm])
    for k in orders:
        ax.plot(n, k * n / 60, color="0.5", lw=0.8, ls="--")
        ax.text(top_rpm, k * top_rpm / 60, f" {k}", fontsize=8, color="0.4", va="center")
        for f in frequencies_hz:   # resonance: order k at the speed where k n / 60 = f
            if 60 * f / k <= top_rpm:
                ax.plot(60 * f / k, f, "o", color="C3", ms=5)
    if rpm_run > 0:
        ax.axvline(rpm_run, color="k", lw=0.8, ls=":", label=f"{driver}: {rpm_run:.0f} rpm (run's largest)")
        ax.legend(loc="upper left", fontsize=8)
    ax.set_xlim(0, top_rpm * 1.08)
    ax.set_ylim(0, f_top)
    ax.set_xlabel(f"{driver} speed (rpm)")
    ax.set_ylabel("frequency (Hz)")
    ax.set_title("Campbell diagram: rotational modes (spans EA/L) and orders of the driver (dashed)")
    ax.grid(alpha=0.3)
    return ax


def plot_all(result, outdir) -> list[Path]:
    ds, outdir = result.ds, Path(outdir)
    driver = result.summary.get("driver", str(ds["pulley"].values[0]))
    files = []

    def save(fig, name):
        plotting.save(fig, outdir / name, result, files, dpi=110)

    if ds.sizes.get("time", 0) == 0:
        return files
    fig, ax = _fig(2)
    plot_speeds(ds, ax=ax[0])
    plot_slip(ds, driver, ax=ax[1])
    ax[1].set_xlabel("time (s)")
    save(fig, "speeds.png")

    fig, ax = _fig(2)
    plot_lines(ds, "span_tension", "span", "tension (N)", "mid-span tensions", ax=ax[0])
    plot_lines(ds, "hub_load", "pulley", "hub load (N)", "hub loads", ax=ax[1])
    ax[1].set_xlabel("time (s)")
    save(fig, "tensions.png")

    fig, ax = _fig(3, 2.6)
    plot_lines(ds, "element_force", "tracked", "force (N)", "longitudinal element force after segment (seed fig. 11)", ax=ax[0])
    plot_lines(ds, "normal_force", "tracked", "force (N)", "contact normal force on segment (seed fig. 12)", ax=ax[1])
    plot_lines(ds, "friction_force", "tracked", "force (N)", "friction force on segment (seed fig. 13)", ax=ax[2])
    ax[2].set_xlabel("time (s)")
    save(fig, "segment_forces.png")

    fig, ax = _fig(1, 4)
    plot_energy(ds, ax=ax[0])
    save(fig, "energy.png")

    if "model_toml" in ds.attrs:   # the drive's rotational modes (modes.py) against the driver's orders
        from ..model import loads
        from .modes import modes

        freqs = modes(loads(ds.attrs["model_toml"])).frequencies_hz
        if freqs:
            fig, ax = _fig(1, 4)
            plot_campbell(ds, freqs, driver, ax=ax[0])
            save(fig, "campbell.png")

    if ds.sizes.get("frame", 0):
        fig = Figure(figsize=(8, 5), layout="constrained")
        a = fig.add_subplot()
        sc = draw_drive(ds, ds.sizes["frame"] - 1, a)
        fig.colorbar(sc, ax=a, label="element force (N)")
        save(fig, "belt.png")
        files.append(animate(ds, outdir / "belt.gif"))
    return files


def animate(ds, path, max_frames=60) -> Path:
    """GIF of the belt moving, segments coloured by the element force."""
    from matplotlib.animation import FuncAnimation, PillowWriter

    nf = ds.sizes["frame"]
    idx = np.unique(np.linspace(0, nf - 1, min(nf, max_frames)).astype(int))
    fig = Figure(figsize=(6, 4), layout="constrained")
    ax = fig.add_subplot()
    vmax = max(float(ds["belt_tension"].max()), 1.0)

    def draw(k):
        ax.clear()
        draw_drive(ds, idx[k], ax, vmax=vmax)
        return []

    anim = FuncAnimation(fig, draw, frames=len(idx), blit=False)
    anim.save(str(path), writer=PillowWriter(fps=10), dpi=70)
    return Path(path)
