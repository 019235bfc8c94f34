"""Figures of a toothed-mesh run, drawn from the Result alone (so ``drivedyn plot`` can redraw).

Superposed contours like the seed's figs. 6-8 (mm, pulley frame, height from the outside
circle), interference against the pulley angle, a flank colour map, the maps and comparison
table, and an animation (GIF, matplotlib's PillowWriter). Matplotlib ``Figure`` only, no pyplot.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import shapely
from matplotlib.figure import Figure

from ..mechanics.teeth.kinematics import to_pulley

MM = 1e3


def _geometry(ds):
    uv = np.column_stack([ds["tooth_u"].values, ds["tooth_v"].values])
    ring = np.column_stack([ds["pulley_x"].values, ds["pulley_y"].values])
    return uv, ring, float(ds.attrs["belt_radius"]), float(ds.attrs["tooth_offset"]), float(ds.attrs["outside_radius"])


def _tooth_at(ds, phi):
    uv, _, rb, off, _ = _geometry(ds)
    return to_pulley(uv, np.array([phi]), rb, off)[0]


def _draw_pulley(ax, ds):
    _, ring, _, _, r_o = _geometry(ds)
    ax.fill(ring[:, 0] * MM, (ring[:, 1] - r_o) * MM, color="0.88", lw=0)
    return ax.plot(ring[:, 0] * MM, (ring[:, 1] - r_o) * MM, color="k", lw=1.0)


def _draw_tooth(ax, ds, phi, color, pulley=None, lw=1.0):
    """Tooth contour (with a stretch of land) at ``phi``, overlap with the pulley in red."""
    uv, ring, rb, off, r_o = _geometry(ds)
    pts = _tooth_at(ds, phi)
    land = float(ds.attrs["tooth_land"])
    half = 0.5 * float(np.ptp(uv[:, 0])) + 1e-3
    ext = to_pulley(np.array([[-half, land], [uv[0, 0], land]]), np.array([phi]), rb, off)[0]
    ext2 = to_pulley(np.array([[uv[-1, 0], land], [half, land]]), np.array([phi]), rb, off)[0]
    arts = ax.plot(pts[:, 0] * MM, (pts[:, 1] - r_o) * MM, color=color, lw=lw)
    for e in (ext, ext2):
        arts += ax.plot(e[:, 0] * MM, (e[:, 1] - r_o) * MM, color=color, lw=lw, ls=":")
    if pulley is None:
        pulley = shapely.Polygon(ring)
    ov = shapely.intersection(shapely.Polygon(pts), pulley)
    for g in getattr(ov, "geoms", [ov]):
        if g.geom_type == "Polygon" and not g.is_empty:
            x, y = np.asarray(g.exterior.coords).T
            arts += ax.fill(x * MM, (y - r_o) * MM, facecolor="red", edgecolor="red", lw=2.0)  # edge: slivers stay visible
    return arts


def _contact_range(ds):
    """Angles from the approach (clearance under a tooth height) to seating."""
    phi = ds["angle"].values
    near = np.nan_to_num(ds["clearance"].values, nan=np.inf) < float(ds.attrs["tooth_land"] - ds.attrs["tooth_tip"])
    start = phi[np.argmax(near)] if near.any() else phi[0]
    return min(start, -1e-9)


def _zero_based_top(val):
    """Top of a colour scale that starts at 0: the largest value, or 1 (in the plot's unit) when
    everything is 0, so an all-zero map shows the palest colour on a 0..1 scale."""
    top = float(np.nanmax(val, initial=0))
    return top if top > 0 else 1.0


def _say_zero(ax, text):
    ax.text(0.5, 0.5, text, transform=ax.transAxes, ha="center", va="center", fontsize=10,
            bbox=dict(boxstyle="round", fc="w", ec="0.6", alpha=0.9))


def plot_contours(ds, axes=None):
    """Superposed contours for a sequence of angles, entry and exit (seed figs. 6-8)."""
    fig = None
    if axes is None:
        fig = Figure(figsize=(11, 4.6), layout="constrained")
        axes = fig.subplots(1, 2, sharey=True)
    from matplotlib import colormaps

    pulley = shapely.Polygon(np.column_stack([ds["pulley_x"].values, ds["pulley_y"].values]))
    start = _contact_range(ds)
    uv, _, _, _, _ = _geometry(ds)
    width = float(np.ptp(uv[:, 0]))
    for ax, sign, title in ((axes[0], 1, "entry (pulley angle < 0)"), (axes[1], -1, "exit (pulley angle > 0)")):
        _draw_pulley(ax, ds)
        phis = sign * np.linspace(start, 0.0, 7)
        cmap = colormaps["viridis"]
        for k, phi in enumerate(phis):
            _draw_tooth(ax, ds, phi, cmap(k / (len(phis) - 1)), pulley)
        ax.set_title(f"{title}: {abs(np.degrees(start)):.1f} deg to seating")
        ax.set_xlim(-1.6 * width * MM, 1.6 * width * MM)
        ax.set_ylim((ds.attrs["tooth_tip"] - 0.6 * width) * MM, 1.0 * width * MM)
        ax.set_aspect("equal")
        ax.set_xlabel("x (mm)")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("height above the outside circle (mm)")
    if fig is not None:
        fig.suptitle(f"{ds.attrs.get('title', '')}: tooth contours (viridis: first to last), overlap in red",
                     fontsize=10)
    return fig


def plot_interference(ds):
    """Overlap area, penetration and clearance per flank against the pulley angle."""
    fig = Figure(figsize=(8, 8), layout="constrained")
    axes = fig.subplots(3, 1, sharex=True)
    deg = np.degrees(ds["angle"].values)
    axes[0].plot(deg, ds["overlap_area"] * 1e6, color="k")
    axes[0].set_ylabel("overlap area (mm²)")
    for key, c in (("leading", "C0"), ("trailing", "C3")):
        axes[1].plot(deg, ds[f"penetration_{key}"] * MM, color=c, label=f"{key} flank")
        axes[2].plot(deg, ds[f"clearance_{key}"] * MM, color=c, label=f"{key} flank")
    axes[1].set_ylabel("max penetration (mm)")
    axes[2].set_ylabel("clearance (mm)")
    axes[2].set_ylim(0, min(1.0, float(np.nanmax(ds["clearance"].values * MM, initial=0.1)) * 1.05 + 1e-3))
    axes[2].set_xlabel("pulley angle from full seating (deg): entry < 0 < exit")
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.axvline(0, color="0.5", lw=0.8)
    axes[1].legend(fontsize=8)
    axes[0].set_title(ds.attrs.get("title", ""))
    return fig


def plot_flank_map(ds):
    """The tooth contour coloured by its largest penetration over the engagement, and the
    penetration along the contour against the angle."""
    from matplotlib.collections import LineCollection

    fig = Figure(figsize=(11, 4.4), layout="constrained")
    ax0, ax1 = fig.subplots(1, 2, width_ratios=[1, 1.3])
    u, v = ds["tooth_u"].values * MM, ds["tooth_v"].values * MM
    depth = ds["flank_depth"].values * MM
    worst = depth.max(axis=0)
    segs = np.stack([np.column_stack([u[:-1], v[:-1]]), np.column_stack([u[1:], v[1:]])], axis=1)
    vmax = _zero_based_top(worst)
    lc = LineCollection(segs, array=0.5 * (worst[:-1] + worst[1:]), cmap="inferno_r", linewidths=5,
                        norm=None)
    lc.set_clim(0, vmax)
    ax0.add_collection(lc)
    ax0.plot(u, v, color="0.6", lw=0.5)
    ax0.set_xlim(u.min() - 0.5, u.max() + 0.5)
    ax0.set_ylim(v.min() - 0.5, v.max() + 0.5)
    ax0.set_aspect("equal")
    ax0.set_xlabel("along the belt (mm), leading flank > 0")
    ax0.set_ylabel("from the pitch line (mm)")
    ax0.set_title("largest penetration on the flank")
    fig.colorbar(lc, ax=ax0, label="penetration (mm)", shrink=0.8)
    deg = np.degrees(ds["angle"].values)
    s = ds["tooth_s"].values * MM
    im = ax1.pcolormesh(deg, s, depth.T, cmap="inferno_r", vmin=0, vmax=vmax, shading="nearest")
    tip = s[np.argmin(np.abs(u))]
    ax1.axhline(tip, color="0.5", lw=0.8, ls="--")
    ax1.text(deg[0], tip, " tip", va="bottom", fontsize=8)
    ax1.set_ylabel("contour length from the trailing land (mm)\ntrailing flank below the tip, leading above")
    ax1.set_xlabel("pulley angle (deg)")
    ax1.set_title("penetration along the contour")
    if not worst.max() > 0:
        for ax in (ax0, ax1):
            _say_zero(ax, "no penetration anywhere")
    fig.colorbar(im, ax=ax1, label="penetration (mm)")
    fig.suptitle(f"{ds.attrs.get('title', '')}: where the flank penetrates the groove", fontsize=11)
    return fig


def plot_maps(ds):
    """Maximum overlap area and penetration over tooth count x pitch error."""
    fig = Figure(figsize=(11, 4.2), layout="constrained")
    axes = fig.subplots(1, 2)
    z = ds["map_teeth"].values
    e = ds["map_pitch_error"].values * MM
    for ax, var, scale, label in ((axes[0], "map_overlap_area", 1e6, "max overlap area (mm²)"),
                                  (axes[1], "map_penetration", MM, "max penetration (mm)")):
        val = ds[var].values * scale
        # overlap cannot be negative: the scale starts at 0 with 0 the palest colour (autoscaled,
        # an all-zero map sat mid-scale on -0.1..0.1, as if negative)
        top = _zero_based_top(val)
        im = ax.imshow(val, origin="lower", aspect="auto", cmap="magma_r", vmin=0, vmax=top)
        ax.set_xticks(range(len(e)), [f"{x:g}" for x in e])
        ax.set_yticks(range(len(z)), [str(k) for k in z])
        for i in range(len(z)):
            for j in range(len(e)):
                ax.text(j, i, f"{val[i, j]:.3g}", ha="center", va="center", fontsize=8,
                        color="w" if val[i, j] > 0.6 * top else "k")
        ax.set_xlabel("pitch error / tooth offset (mm)")
        ax.set_ylabel("pulley teeth z")
        ax.set_title(label.split(" (")[0] + " over tooth count and pitch error")
        if not np.nanmax(val, initial=0) > 0:
            _say_zero(ax, "0 everywhere: no overlap")
        fig.colorbar(im, ax=ax, label=label)
    fig.suptitle(f"{ds.attrs.get('title', '')}: interference maps", fontsize=11)
    return fig


def plot_comparison(ds):
    """Bar chart of the comparison table."""
    fig = Figure(figsize=(9, 1.2 + 0.5 * ds.sizes["pair"]), layout="constrained")
    axes = fig.subplots(1, 2, sharey=True)
    labels = [str(x) for x in ds["pair"].values]
    y = np.arange(len(labels))
    for ax, var, scale, colour, unit in ((axes[0], "compare_max_overlap_area", 1e6, "C3", "mm²"),
                                         (axes[1], "compare_max_penetration", MM, "C0", "mm")):
        val = ds[var].values * scale
        ax.barh(y, val, color=colour)
        top = max(float(np.nanmax(val)), 1e-12)
        for k, v in enumerate(val):     # the value beside each bar: a zero bar is otherwise invisible
            ax.text(v + 0.02 * top, k, f"{v:.3g}" if v else "0 (no overlap)", va="center", fontsize=8)
        ax.set_xlim(0, 1.3 * top)
    axes[0].set_yticks(y, labels)
    axes[0].invert_yaxis()
    axes[0].set_xlabel("max overlap area (mm²)")
    axes[1].set_xlabel("max penetration (mm)")
    axes[0].set_title("largest overlap area")
    axes[1].set_title("largest penetration")
    fig.suptitle("profile pairs compared (unloaded meshing)", fontsize=11)
    for ax in axes:
        ax.grid(alpha=0.3, axis="x")
    return fig


def plot_load(ds):
    """Load sharing on the pulley: per-tooth loads (with the load at which each would climb), the
    cord tension along the wrap, and the jump torque against the installation tension."""
    fig = Figure(figsize=(13, 4.2), layout="constrained")
    ax0, ax1, ax2 = fig.subplots(1, 3, width_ratios=[1.1, 1.1, 1])
    teeth = ds["load_tooth"].values
    q = ds["tooth_load"].values
    ax0.bar(teeth, q, color="C0", label="tooth load Q")
    # the load at which each tooth starts to climb: hold / tan(phi - rho), hold = T_local p / R
    f = float(ds.attrs["load_climb_factor"])
    if f > 0:
        climb = ds["tooth_tension"].values * ds.attrs["load_pitch"] / ds.attrs["belt_radius"] / f
        ax0.plot(teeth, climb, "_", color="C3", ms=14, mew=2, label="load at which it climbs")
    ax0.set_xlabel("tooth in mesh (1: tight side)")
    ax0.set_ylabel("N")
    ax0.set_title(f"tooth loads at {ds.attrs['load_torque']:.3g} N m")
    ax0.set_xticks(teeth if len(teeth) <= 24 else teeth[:: max(len(teeth) // 12, 1)])
    ax0.legend(fontsize=8)
    s = ds["wrap_position"].values * MM
    ax1.step(s, ds["wrap_tension"].values, where="mid", color="k")
    for x in (teeth - 1) * ds.attrs["load_pitch"] * MM:
        ax1.axvline(x, color="0.8", lw=0.6, zorder=0)
    ax1.axhline(ds.attrs["load_T0"], color="0.5", ls="--", lw=0.8, label="installation tension")
    ax1.set_xlabel("along the wrap from tooth 1 (mm); grey lines: teeth")
    ax1.set_ylabel("cord tension (N)")
    ax1.set_title("tension along the wrap")
    ax1.set_ylim(bottom=0)
    ax1.legend(fontsize=8)
    t0 = ds["jump_tension"].values
    mj = ds["jump_torque"].values
    ax2.plot(t0, mj, "o-", color="C3", label="jump torque")
    ax2.plot(t0, 2 * t0 * ds.attrs["belt_radius"], color="0.6", ls=":", label="slack span at zero: 2 T0 R")
    ax2.plot([ds.attrs["load_T0"]], [ds.attrs["load_torque"]], "k*", ms=10, label="this run")
    ax2.set_xlabel("installation tension T0 (N)")
    ax2.set_ylabel("torque (N m)")
    ax2.set_title("jump torque against installation tension")
    ax2.set_xlim(left=0)
    ax2.set_ylim(bottom=0)
    ax2.legend(fontsize=8)
    for ax in (ax0, ax1, ax2):
        ax.grid(alpha=0.3)
    fig.suptitle(f"{ds.attrs.get('title', '')}: load sharing and tooth jump", fontsize=11)
    return fig


def animate(ds, path, frames=48, fps=12):
    """GIF of the tooth entering, seating and leaving the groove: the pulley drawn once, the tooth
    and the angle over it in each frame."""
    fig = Figure(figsize=(5, 4), dpi=80, layout="constrained")
    ax = fig.subplots()
    start = _contact_range(ds)
    phis = np.linspace(start, -start, frames)
    pulley = shapely.Polygon(np.column_stack([ds["pulley_x"].values, ds["pulley_y"].values]))
    uv = np.column_stack([ds["tooth_u"].values, ds["tooth_v"].values])
    width = float(np.ptp(uv[:, 0]))
    _draw_pulley(ax, ds)
    ax.set_xlim(-1.6 * width * MM, 1.6 * width * MM)
    ax.set_ylim((ds.attrs["tooth_tip"] - 0.6 * width) * MM, 0.8 * width * MM)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_title(" ", fontsize=9)       # its room in the layout; the angle is drawn per frame

    def frame(k):
        title = ax.text(0.5, 1.0, f"pulley angle {np.degrees(phis[k]):+.2f} deg", transform=ax.transAxes,
                        ha="center", va="baseline", fontsize=9)
        title.set_position((0.5, 1.0 + 6 / 72 * fig.dpi / ax.bbox.height))     # the title's 6 pt pad
        return _draw_tooth(ax, ds, phis[k], "C0", pulley, lw=1.5) + [title]

    from ..core import plotting

    return plotting.save_gif(fig, path, frames, frame, fps=fps)


def plot_all(result, outdir, meanwhile=None, workers=None) -> list[Path]:
    """Write the standard figures and the animation into ``outdir``; returns the paths. They are
    drawn by plotting.write_figures (in two processes where it can; ``workers=1``: here) while this
    one runs ``meanwhile()``."""
    from ..core import plotting

    ds, outdir = result.ds, Path(outdir)
    jobs = [("mesh-contours.png", plot_contours), ("mesh-interference.png", plot_interference),
            ("mesh-flank-map.png", plot_flank_map)]
    if "map_overlap_area" in ds:
        jobs.append(("mesh-maps.png", plot_maps))
    if "tooth_load" in ds:
        jobs.append(("mesh-load.png", plot_load))
    if "pair" in ds.dims and ds.sizes["pair"] > 1:
        jobs.append(("mesh-comparison.png", plot_comparison))
    jobs = [(name, lambda fn=fn: fn(ds)) for name, fn in jobs]
    # the animation first: the longest job (48 frames), so the two processes end together
    jobs.insert(0, ("mesh-animation.gif", lambda: animate(ds, outdir / "mesh-animation.gif")))
    done = plotting.write_figures(jobs, outdir, result, meanwhile, workers, dpi=110)
    return done[1:] + done[:1]
