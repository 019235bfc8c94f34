"""Standard plots of a gear-train Result (matplotlib Figure objects only, no pyplot).

Each ``plot_*`` takes the Result's Dataset and an optional Axes and returns the artists drawn;
``plot_all`` writes the PNG files: stiffness (seed fig. 5 and roll angle with contact zones),
torsional vibration (fig. 7), K_v in time (fig. 8), forces/DTE/load sharing, spectrum in mesh
orders, and, after a sweep, K_v against speed with ISO method B and a Campbell diagram; for planetary
stages their planet loads and modes and, when integrated, their mesh forces and K_v sweep.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np


def _figure(nrows=1, ncols=1, size=(8, 4.5)):
    from matplotlib.figure import Figure

    fig = Figure(figsize=size, dpi=100, layout="constrained")
    axes = fig.subplots(nrows, ncols, squeeze=False)
    return fig, axes


def _ax(ax):
    if ax is None:
        _, axes = _figure()
        return axes[0, 0]
    return ax


def _window(ds):
    w0, w1 = ds.attrs["steady_window"]
    return ds.sel(time=slice(w0, w1))


def _distinct(ds, var, dim, w=None):
    """(key, label) for the members of ``dim`` whose ``var`` differs: a member equal to an earlier
    one (to 1e-9 of its range) joins its label ("m12 = m13") instead of hiding under it."""
    src = ds if w is None else w
    keys, labels, vals = [], [], []
    for k in src[dim].values:
        x = np.asarray(src[var].sel({dim: k}).values, float)
        for i, y in enumerate(vals):
            if x.shape == y.shape and np.allclose(x, y, rtol=1e-9, atol=1e-12 * (np.ptp(y) + abs(y).max() + 1e-300)):
                labels[i] += f" = {k}"
                break
        else:
            keys.append(k)
            labels.append(str(k))
            vals.append(x)
    return list(zip(keys, labels))


def plot_stiffness_time(ds, ax=None, periods=2.5):
    """Mesh stiffness against time over a few mesh periods, each mesh with its phase (seed fig. 5)."""
    ax = _ax(ax)
    t0 = float(ds.time[0])
    sel = ds.sel(time=slice(t0, t0 + periods / ds.attrs["mesh_frequency_hz"][0]))
    arts = [ax.plot(sel.time * 1e3, sel.mesh_stiffness.sel(mesh=m) / 1e6, label=f"mesh {label}")[0]
            for m, label in _distinct(ds, "mesh_stiffness", "mesh", sel)]     # equal meshes: one line
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("mesh stiffness [N/um]")
    ax.set_title("time-varying mesh stiffness")
    ax.legend(loc="center")     # between the high and low levels (lower right covered the last rise)
    ax.grid(alpha=0.3)
    return arts


def plot_stiffness_roll(ds, mesh=None, ax=None):
    """Mesh and single-pair stiffness against mesh position, double-contact zones shaded."""
    ax = _ax(ax)
    mesh = str(ds.mesh.values[0]) if mesh is None else mesh
    u = ds.mesh_position.values
    k = ds.stiffness_table.sel(mesh=mesh).values / 1e6
    npairs = ds.pairs_in_contact.sel(mesh=mesh).values
    uu = np.concatenate([u, u + 1])
    kk = np.concatenate([k, k])
    nn = np.concatenate([npairs, npairs])
    arts = [ax.plot(uu, kk, "k", lw=1.6, label="mesh")[0]]
    ps = np.array(ds.attrs[f"pair_s_{mesh}"])
    pk = np.array(ds.attrs[f"pair_k_{mesh}"]) / 1e6
    arts.append(ax.plot(ps, pk, "C1--", label="one tooth pair")[0])
    double = nn >= 2
    edges = np.flatnonzero(np.diff(np.concatenate([[0], double.astype(int), [0]])))
    for a, b in zip(edges[::2], edges[1::2]):
        arts.append(ax.axvspan(uu[a], uu[min(b, len(uu) - 1)], color="C0", alpha=0.12, lw=0))
    pitch = ds.attrs[f"pitch_s_{mesh}"]
    arts.append(ax.axvline(pitch, color="C3", lw=0.8, ls=":", label="pitch point (pair 0)"))
    ax.set_xlabel("mesh position [mesh periods = pinion roll through one base pitch]")
    ax.set_ylabel("stiffness [N/um]")
    ax.set_title(f"mesh {mesh}: stiffness over roll angle (shaded: two pairs in contact)")
    ax.set_ylim(bottom=0)
    ax.legend(loc="lower right")
    ax.grid(alpha=0.3)
    return arts


def plot_vibration(ds, ax=None):
    """Torsional vibration of every gear: angle minus nominal rigid rotation (seed fig. 7), less
    its linear drift over the steady window (a constant speed error would hide the vibration)."""
    ax = _ax(ax)
    w0, w1 = ds.attrs["steady_window"]
    t = ds.time.values
    sel = (t >= w0) & (t <= w1)
    arts = []
    if sel.sum() < 3:
        sel = np.ones(len(t), bool)
    for g, label in _distinct(ds, "vibration", "gear"):
        x = ds.vibration.sel(gear=g).values[sel]
        drift = np.polyfit(t[sel], x, 1)
        arts.append(ax.plot(t[sel], (x - np.polyval(drift, t[sel])) * 1e3, lw=0.7,
                            label=f"{label} (drift {drift[0] * 1e3:.3g} mrad/s removed)")[0])
    ax.set_xlabel("time [s]")
    ax.set_ylabel("angle - nominal rotation [mrad]")
    ax.set_title(f"torsional vibration in the steady window {w0:.3g}-{w1:.3g} s\n(linear drift removed)")
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=8, frameon=False)
    ax.grid(alpha=0.3)
    return arts


def plot_kv_time(ds, ax=None):
    """Mesh force over the nominal force in the steady window, and K_v (seed fig. 8)."""
    ax = _ax(ax)
    w = _window(ds)
    arts = []
    for j, (m, label) in enumerate(_distinct(ds, "kv_t", "mesh", w)):
        arts.append(ax.plot(w.time, w.kv_t.sel(mesh=m), lw=0.8, label=f"mesh {label}: K_v = {float(ds.kv.sel(mesh=m)):.3f}")[0])
        arts.append(ax.axhline(float(ds.kv.sel(mesh=m)), color=f"C{j}", ls="--", lw=0.8))
    ax.set_xlabel("time [s]")
    ax.set_ylabel("F / F_nominal")
    ax.set_title("dynamic factor in the steady window")
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=8, frameon=False)
    ax.grid(alpha=0.3)
    return arts


def plot_forces(ds, axes=None):
    """Dynamic mesh force, transmission error and load sharing in the steady window (3 axes)."""
    if axes is None:
        _, a = _figure(3, 1, (8, 8))
        axes = a[:, 0]
    w = _window(ds)
    arts = []
    for m, label in _distinct(ds, "mesh_force", "mesh", w):
        arts.append(axes[0].plot(w.time, w.mesh_force.sel(mesh=m), lw=0.7, label=label)[0])
        arts.append(axes[1].plot(w.time, w.dte.sel(mesh=m) * 1e6, lw=0.7, label=label)[0])
    share = w.load_share.values
    if np.ptp(share) < 1e-6:      # a constant share is a number, not a curve
        text = ", ".join(f"{m} {float(w.load_share.sel(mesh=m).values[0]):.3f}" for m in ds.mesh.values)
        axes[2].text(0.5, 0.5, f"load share constant over the window: {text}", transform=axes[2].transAxes,
                     ha="center", va="center")
        axes[2].set_yticks([])
        axes[2].set_xlim(axes[0].get_xlim())
    else:
        for m in ds.mesh.values:
            arts.append(axes[2].plot(w.time, w.load_share.sel(mesh=m), lw=0.7, label=str(m))[0])
        axes[2].legend(loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=8, frameon=False)
    for ax, lab in zip(axes, ("mesh force [N]", "DTE [um]", "load share [-]")):
        ax.set_ylabel(lab)
        ax.grid(alpha=0.3)
    for ax in axes[:2]:
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=8, frameon=False)
    axes[0].set_title("mesh forces, dynamic transmission error, load sharing")
    axes[2].set_xlabel("time [s]")
    return arts


def plot_spectrum(ds, ax=None, max_order=25):
    """Mesh-force amplitude at each order of the first mesh frequency (bars: the largest line of
    the spectrum within half an order), natural frequencies dotted."""
    ax = _ax(ax)
    order = ds.order.values
    ks = np.arange(1, max_order + 1)
    meshes = _distinct(ds, "force_spectrum", "mesh")
    width = 0.8 / max(len(meshes), 1)
    arts = []
    for i, (m, label) in enumerate(meshes):
        amp = ds.force_spectrum.sel(mesh=m).values
        bars = [amp[(order > k - 0.5) & (order <= k + 0.5)].max(initial=0.0) for k in ks]
        arts.append(ax.bar(ks + (i - (len(meshes) - 1) / 2) * width, bars, width=width, label=label, log=True))
    f_mesh = ds.attrs["mesh_frequency_hz"][0]
    for f in ds.natural_frequency.values:
        if f / f_mesh <= max_order:
            arts.append(ax.axvline(f / f_mesh, color="0.5", ls=":", lw=0.8))
    ax.set_xlabel(f"order of the mesh frequency ({f_mesh:.1f} Hz); dotted: natural frequencies")
    ax.set_ylabel("force amplitude [N]")
    ax.set_title("mesh-force amplitude per mesh order (steady window)")
    ax.legend(loc="upper right", fontsize=8)
    ax.grid(alpha=0.3, which="both", axis="y")
    return arts


def plot_sweep(ds, ax=None):
    """K_v against input speed: simulated per mesh and ISO 6336-1 method B."""
    ax = _ax(ax)
    rpm = ds.sweep_speed.values * 30 / math.pi
    arts = []
    meshes = _distinct(ds, "kv_sweep", "mesh")          # identical meshes: one curve, "m12 = m13"
    if len(meshes) != len(_distinct(ds, "kv_iso_sweep", "mesh")):
        meshes = [(m, str(m)) for m in ds.mesh.values]
    for j, (m, label) in enumerate(meshes):
        arts.append(ax.plot(rpm, ds.kv_sweep.sel(mesh=m), f"C{j}", lw=1, label=f"simulated, mesh {label}")[0])
        arts.append(ax.plot(rpm, ds.kv_iso_sweep.sel(mesh=m), f"C{j}--", lw=1.2, label=f"ISO 6336-1 method B, mesh {label}")[0])
    op = ds.attrs["input_speed"] * 30 / math.pi
    arts.append(ax.axvline(op, color="k", lw=0.8, ls=":", label=f"operating speed {op:.0f} rpm"))
    if "sweep_unstable" in ds:
        bad = ds.sweep_unstable.values.any(axis=1)
        if bad.any():                         # speeds where the linear model grows without bound
            step = np.diff(rpm).mean() / 2 if len(rpm) > 1 else 1.0
            for k, r in enumerate(rpm[bad]):
                arts.append(ax.axvspan(r - step, r + step, color="#b22222", alpha=0.18, lw=0,
                                       label="unstable (kv-unstable): K_v meaningless" if k == 0 else None))
    finite = ds.kv_sweep.values[np.isfinite(ds.kv_sweep.values)]
    top = min(np.nanmax(finite) if finite.size else 3, 6.0)
    ax.set_ylim(0.8, max(top * 1.05, 2.8))
    ax.set_xlabel("input speed [rpm]")
    ax.set_ylabel("K_v")
    ax.set_title("K_v against input speed\n(shaded: parametric instability of the linear model)")
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=8, frameon=False)   # beside: the peaks sit top left
    ax.grid(alpha=0.3)
    return arts


def plot_campbell(ds, ax=None, orders=(1, 2, 3, 4, 5)):
    """Natural frequencies against input speed with the mesh-order lines k f_mesh(n)."""
    ax = _ax(ax)
    w_in = ds.attrs["input_speed"]
    n_max = float(ds.sweep_speed.values[-1]) if "sweep_speed" in ds else 2 * w_in
    rpm = np.linspace(0, n_max * 30 / math.pi, 200)
    arts = []
    fmax = float(ds.natural_frequency.max()) * 1.3 if ds.sizes["mode"] else 1.0
    for f in ds.natural_frequency.values:
        arts.append(ax.axhline(f, color="k", lw=1))
        arts.append(ax.text(rpm[-1], f, f" {f:.0f} Hz", va="bottom", ha="right", fontsize=8))
    for fm, m in zip(sorted(set(np.round(ds.attrs["mesh_frequency_hz"], 6))), ds.mesh.values):
        per_rpm = fm / (w_in * 30 / math.pi)
        for k in orders:
            arts.append(ax.plot(rpm, k * per_rpm * rpm, lw=0.8, label=f"{k} x mesh frequency")[0])
            for f in ds.natural_frequency.values:
                n_cross = f / (k * per_rpm)
                if n_cross <= rpm[-1]:
                    arts.append(ax.plot(n_cross, f, "o", mfc="none", color="C3")[0])
    arts.append(ax.axvline(w_in * 30 / math.pi, color="0.4", ls=":", lw=0.8, label="operating speed"))
    ax.set_xlim(0, rpm[-1])
    ax.set_ylim(0, fmax)
    ax.set_xlabel("input speed [rpm]")
    ax.set_ylabel("frequency [Hz]")
    ax.set_title("Campbell diagram: natural frequencies and mesh orders (circles: resonances)")
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=8, frameon=False)   # beside: the low orders sit top left
    ax.grid(alpha=0.3)
    return arts


#: what each model's static load sharing is, in a figure's title: the verdict's K_gamma is the
#: lateral-torsional model's when the stage has one (planetary.analyse), else the torsional model's
LOAD_MODEL = {True: "lateral-torsional model, as the verdict reads it", False: "torsional model, the sun held on its axis"}


def _loads(ax, p, sun, ring, title):
    arts = [ax.bar(p - 0.18, sun, 0.36, label="sun-planet"), ax.bar(p + 0.18, ring, 0.36, label="ring-planet")]
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set(xlabel="planet", ylabel="static mesh force (N)", xticks=p, title=title)
    ax.legend()
    return arts


def _modes(ax, f, title):
    from matplotlib.ticker import MaxNLocator

    art = ax.stem(np.arange(1, len(f) + 1), f)
    ax.set(xlabel="mode", ylabel="natural frequency (Hz)", title=title)
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))      # modes are counted: 1, 2, 3, not 1.5
    return [art]


def plot_planet_loads(ds, ax=None):
    """Static sun-planet and ring-planet mesh force of each planet, of the model the verdict reads."""
    if ax is None:
        _, ax = _figure()
        ax = ax[0, 0]
    lateral = "lateral_sun_planet_force" in ds and "lateral_ring_planet_force" in ds
    pre = "lateral_" if lateral else ""
    return _loads(ax, ds.planet.values, ds[f"{pre}sun_planet_force"].values, ds[f"{pre}ring_planet_force"].values,
                  f"load sharing ({LOAD_MODEL[lateral]})")


def plot_planetary_modes(ds, ax=None):
    """Natural frequencies of the stage (fixed member held)."""
    if ax is None:
        _, ax = _figure()
        ax = ax[0, 0]
    return _modes(ax, ds.natural_frequency.values, "modes (torsional model, fixed member held)")


def _stage_labels(ds, suffix: str) -> list[str]:
    """The planetary stages ("planetary", "stage2", ...) with a ``<label><suffix>`` variable in ``ds``."""
    return [str(k)[:-len(suffix)] for k in ds.data_vars if str(k).endswith(suffix)]


def plot_stage_loads(ds, label, axes):
    """A gearbox stage's static planet forces and natural frequencies (2 axes)."""
    lateral = f"{label}_lateral_sun_planet_force" in ds
    pre = f"{label}_lateral_" if lateral else f"{label}_"
    arts = _loads(axes[0], ds[f"{label}_planet"].values, ds[f"{pre}sun_planet_force"].values,
                  ds[f"{pre}ring_planet_force"].values, f"{label}: load sharing\n({LOAD_MODEL[lateral]})")
    arts += _modes(axes[1], ds[f"{label}_natural_frequency"].values, f"{label}: modes (torsional model)")
    return arts


def plot_stage_kv(ds, label, axes):
    """A planetary stage's time integration: every mesh's force over the nominal in the window at the
    operating speed, and (after a sweep) the largest K_v over the planets of each mesh against speed."""
    mesh = [str(m) for m in ds[f"{label}_mesh"].values]
    t = ds[f"{label}_dynamics_time"].values
    F = ds[f"{label}_dynamics_force"].values / ds[f"{label}_dynamics_force_nominal"].values
    # K_v: the largest force over the largest quasi-static force (the load shift between the planets apart)
    qs = f"{label}_dynamics_force_quasi_static"
    kv = (ds[f"{label}_dynamics_force"].values.max(axis=0) / ds[qs].values.max(axis=0) if qs in ds
          else F.max(axis=0))
    shown = t <= 4.0 / ds.attrs[f"{label}_dynamics_mesh_frequency_hz"]        # four mesh periods; K_v over all
    arts = []
    n = len(mesh) // 2
    for j, m in enumerate(mesh):
        arts.append(axes[0].plot(t[shown] * 1e3, F[shown, j], f"C{j % n}", ls="-" if j < n else "--", lw=0.9,
                                 label=f"{m}: K_v {kv[j]:.3f}")[0])
    rpm = ds.attrs[f"{label}_dynamics_speed"] * 30 / math.pi
    axes[0].set(xlabel="time in the window (ms), four mesh periods", ylabel="F / F_static",
                title=f"{label}: mesh forces at {rpm:.0f} rpm (solid sun-planet, dashed ring-planet)")
    axes[0].legend(loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=8, frameon=False)
    axes[0].grid(alpha=0.3)
    if f"{label}_kv_sweep" in ds:
        w = ds[f"{label}_sweep_speed"].values * 30 / math.pi
        kv = ds[f"{label}_kv_sweep"].values
        for j, m in ((0, "sun-planet"), (1, "ring-planet")):
            k = kv[:, j * n:(j + 1) * n]
            arts.append(axes[1].plot(w, k.max(axis=1), f"C{j}", lw=1.2, label=f"{m}, largest over the planets")[0])
            arts.append(axes[1].fill_between(w, k.min(axis=1), k.max(axis=1), color=f"C{j}", alpha=0.15, lw=0))
        axes[1].axvline(rpm, color="k", lw=0.8, ls=":")
        axes[1].set(xlabel="input member speed (rpm); dotted: the operating speed", ylabel="K_v",
                    title=f"{label}: K_v against speed (band: spread over the planets)")
        axes[1].legend(loc="upper left", fontsize=8)
        axes[1].grid(alpha=0.3)
    else:
        axes[1].set_axis_off()
    return arts


def _job(nrows, ncols, size, draw):
    """A figure to draw: ``draw(axes)`` on a new ``nrows`` x ``ncols`` figure of ``size`` inches."""
    def make():
        fig, ax = _figure(nrows, ncols, size)
        draw(ax)
        return fig
    return make


def _stage_jobs(ds) -> list:
    jobs = []
    for label in _stage_labels(ds, "_sun_planet_force"):
        if f"{label}_planet" not in ds.coords:     # a single stage's lateral load sharing (lateral_...): no stage
            continue
        jobs.append((label, _job(1, 2, (10, 4), lambda ax, label=label: plot_stage_loads(ds, label, ax[0]))))
    for label in _stage_labels(ds, "_dynamics_force"):
        jobs.append((f"{label}-kv", _job(2, 1, (9, 7.5), lambda ax, label=label: plot_stage_kv(ds, label, ax[:, 0]))))
    return jobs


def _jobs(ds) -> list:
    """The standard figures of ``ds``: (name, function drawing the Figure), in order."""
    if ds.attrs.get("planetary_only"):
        def planetary(ax):
            plot_planet_loads(ds, ax[0, 0])
            plot_planetary_modes(ds, ax[0, 1])
        return [("planetary", _job(1, 2, (10, 4), planetary))] + _stage_jobs(ds)

    def stiffness(ax):
        plot_stiffness_time(ds, ax[0, 0])
        plot_stiffness_roll(ds, ax=ax[1, 0])
    one = (8, 4.5)
    jobs = [("stiffness", _job(2, 1, (8, 7.5), stiffness)),
            ("vibration", _job(1, 1, one, lambda ax: plot_vibration(ds, ax[0, 0]))),
            ("kv", _job(1, 1, one, lambda ax: plot_kv_time(ds, ax[0, 0]))),
            ("forces", _job(3, 1, (8, 8), lambda ax: plot_forces(ds, ax[:, 0]))),
            ("spectrum", _job(1, 1, one, lambda ax: plot_spectrum(ds, ax[0, 0])))]
    if "kv_sweep" in ds:
        jobs.append(("sweep", _job(1, 1, one, lambda ax: plot_sweep(ds, ax[0, 0]))))
    jobs.append(("campbell", _job(1, 1, one, lambda ax: plot_campbell(ds, ax[0, 0]))))
    return jobs + _stage_jobs(ds)


def plot_all(result, outdir, meanwhile=None, workers=None) -> list[Path]:
    """Write the standard PNGs into ``outdir`` (a warned or failed run says so on each); their paths.
    plotting.write_figures draws them (in two processes where it can; ``workers=1``: here) while
    this one runs ``meanwhile()``."""
    from ..core import plotting

    jobs = [(f"gears-{name}.png", make) for name, make in _jobs(result.ds)]
    return plotting.write_figures(jobs, outdir, result, meanwhile, workers)
