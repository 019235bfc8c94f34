"""Standard figures of a belt-drive run (seed figs. 10-17) and an animation of the belt.

Functions are ``plot_x(ds, ..., ax=None)`` (a new figure when no ``ax``) and never touch pyplot or
the backend; ``plot_all`` marks every figure of a warned or failed run (drivedyn.core.plotting).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..core import plotting


def _fig(nrows=1, height=3.2):
    """Stacked panels sharing the time axis, legends to their right. A fixed layout (not
    matplotlib's constrained layout, which draws each figure several times): half the time per
    figure (0.10 against 0.19 s, measured)."""
    from matplotlib.figure import Figure

    h = height * nrows + 0.6
    fig = Figure(figsize=(10, h))
    fig.subplots_adjust(left=0.08, right=0.70, top=1 - 0.45 / h, bottom=0.55 / h, hspace=0.55 / (height - 0.6))
    axes = fig.subplots(nrows, 1, sharex=True, squeeze=False)[:, 0]
    return fig, axes


RPM = 30 / np.pi


def colour(ds, pulley):
    """The one colour of a pulley in every belt plot (its place in belt order)."""
    names = [str(n) for n in ds["pulley"].values]
    return f"C{names.index(str(pulley)) % 10}"


def _window(ds, ax):
    """Shade the steady window (the summary's means) on a time axis; a run-up has none (it is read
    per crank-speed bin)."""
    if "speed_bin" in ds.coords:
        return
    w = ds.attrs.get("steady_window")
    if w is not None and len(w) == 2:
        ax.axvspan(float(w[0]), float(w[1]), color="0.85", alpha=0.5, lw=0, label="steady window")


def _steady(ds) -> np.ndarray:
    """Mask of the samples in the run's steady window (window.py's rule: the model's window as
    the run recorded it, else the last quarter), all samples if it holds none."""
    from ..core.window import in_window, steady_window

    t = ds["time"].values
    w = ds.attrs.get("steady_window")
    sel = in_window(t, steady_window(w if w is not None and len(w) == 2 else None, float(t[-1])))
    return sel if sel.any() else np.ones(len(t), bool)


def _legend(ax, **kw):
    """Legend beside the axes, never over the data."""
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False, borderaxespad=0, **kw)


def twins(curves: dict, tol=0.01) -> dict:
    """{name: (earlier name, relative difference)} for each curve that lies within ``tol`` of an
    earlier one (largest difference over the larger peak): drawn as it is, it would hide it (the
    two pulleys of a two-pulley drive carry the same hub load)."""
    out, names = {}, list(curves)
    for k, nm in enumerate(names):
        a = np.asarray(curves[nm], float)
        for ref in names[:k]:
            if ref in out:
                continue
            b = np.asarray(curves[ref], float)
            top = max(float(np.nanmax(np.abs(a), initial=0)), float(np.nanmax(np.abs(b), initial=0)))
            rel = float(np.nanmax(np.abs(a - b), initial=0)) / top if top > 0 else 0.0
            if rel < tol:
                out[nm] = (ref, rel)
                break
    return out


def _twin_style(twin, name):
    """Line style and label tail of a curve drawn over an equal one: dashed, on top, and the
    legend says which it covers and how closely they agree."""
    if name not in twin:
        return {}, ""
    ref, rel = twin[name]
    pct = max(np.ceil(rel * 1000) / 10, 0.1)
    return dict(ls=(0, (4, 3)), lw=1.8, zorder=3), f"\n(same as {ref} within {pct:.1f} %)"


def plot_speeds(ds, ax=None):
    ax = plotting.ax_or_new(ax)
    t = ds["time"].values
    _window(ds, ax)
    names = [str(nm) for nm in ds["pulley"].values]
    twin = twins({nm: ds["speed"].sel(pulley=nm).values for nm in names})
    for nm in names:
        style, tail = _twin_style(twin, nm)
        ax.plot(t, ds["speed"].sel(pulley=nm), label=nm + tail, color=colour(ds, nm), **style)
    if "rotor_speed" in ds:       # an overrunning clutch's rotor behind its pulley
        for nm in ds["clutch"].values.tolist():
            ax.plot(t, ds["rotor_speed"].sel(clutch=nm), label=f"{nm} rotor (clutch)", color=colour(ds, nm),
                    ls=":", lw=1.4)
    ax.set_ylabel("speed (rad/s)")
    sec = ax.secondary_yaxis("right", functions=(lambda w: w * RPM, lambda n: n / RPM))
    sec.set_ylabel("rpm")
    ax.set_title("pulley speeds (counter-clockwise positive)")
    # beside the rpm axis
    ax.legend(loc="upper left", bbox_to_anchor=(1.12, 1.0), fontsize=8, frameon=False, borderaxespad=0)
    ax.grid(alpha=0.3)


def plot_slip(ds, driver, ax=None):
    """Each friction contact's slip against the driver; grooved pulleys left out (their teeth do not
    slip: what they show against the driver is the teeth's deflection, phase_error.png)."""
    ax = plotting.ax_or_new(ax)
    t = ds["time"].values
    _window(ds, ax)
    r = ds["pulley_radius"]
    vd = np.abs(ds["speed"].sel(pulley=driver) * r.sel(pulley=driver)).values
    ok = vd > 0.05 * max(np.max(vd), 1e-12)
    grooved = set(ds["toothed_pulley"].values.tolist()) if "toothed_pulley" in ds.coords else set()
    shown = 0
    for nm in ds["pulley"].values:
        if nm == driver or nm in grooved:
            continue
        shown += 1
        v = np.abs(ds["speed"].sel(pulley=nm) * r.sel(pulley=nm)).values
        sl = np.where(ok, 1 - v / np.where(ok, vd, 1), np.nan)
        ax.plot(t, 100 * sl, label=f"{nm}", color=colour(ds, nm))
    ax.set_ylabel("slip (%)")
    who = "the driver" if str(driver) == "driver" else f"the driver {driver}"
    ax.set_title(f"slip against {who}: 1 - |w r| / |w_d r_d|")
    left = sorted(map(str, grooved - {driver}))
    if left:
        ax.text(0.01, 0.97, f"grooved pulleys ({', '.join(left)}) left out: their teeth do not slip "
                "(transmission error: phase_error.png)", transform=ax.transAxes, va="top", fontsize=8)
    if shown:
        _legend(ax)
    ax.grid(alpha=0.3)


def span_labels(ds) -> dict:
    """'a-b (tight), mean 806 N, 800-813' per span, from the steady window."""
    sel = _steady(ds)
    T = ds["span_tension"].values[sel]
    mean = T.mean(axis=0)
    tight, slack = int(np.argmax(mean)), int(np.argmin(mean))
    out = {}
    for q, sp in enumerate(ds["span"].values):
        role = " (tight)" if q == tight else " (slack)" if q == slack and len(mean) > 1 else ""
        out[str(sp)] = f"{sp}{role}: {mean[q]:.0f} N, {T[:, q].min():.0f}-{T[:, q].max():.0f}"
    if max(map(len, out.values())) > 40:    # long span names: the numbers on a second line (else cut at the figure's edge)
        out = {k: v.replace(": ", "\n", 1) for k, v in out.items()}
    return out


def plot_spans(ds, ax=None):
    ax = plotting.ax_or_new(ax)
    t = ds["time"].values
    _window(ds, ax)
    labels = span_labels(ds)
    for q, sp in enumerate(ds["span"].values):
        ax.plot(t, ds["span_tension"].sel(span=sp), label=labels[str(sp)], color=f"C{q % 10}", lw=1)
    ax.set_ylabel("tension (N)")
    ax.set_title("mid-span tensions (legend: mean, min-max in the steady window)")
    _legend(ax)
    ax.grid(alpha=0.3)


def plot_hub_loads(ds, ax=None):
    ax = plotting.ax_or_new(ax)
    t = ds["time"].values
    _window(ds, ax)
    names = [str(nm) for nm in ds["pulley"].values]
    twin = twins({nm: ds["hub_load"].sel(pulley=nm).values for nm in names})
    for nm in names:
        hx = float(ds["hub_force_x"].sel(pulley=nm).values[-1])
        hy = float(ds["hub_force_y"].sel(pulley=nm).values[-1])
        ang = round(float(np.degrees(np.arctan2(hy, hx)))) % 360     # 0-360, as the positions table (no "-0")
        style, tail = _twin_style(twin, nm)
        ax.plot(t, ds["hub_load"].sel(pulley=nm), label=f"{nm} (towards {ang:.0f} deg){tail}",
                color=colour(ds, nm), **style)
    ax.set_ylim(bottom=0)     # from zero: a ripple of a few per cent looks like one
    ax.set_ylabel("hub load (N)")
    ax.set_title("hub loads (direction of the belt's force on the pulley at the end)")
    _legend(ax)
    ax.grid(alpha=0.3)


def plot_lines(ds, var, dim, ylabel, title, ax=None, prefix=""):
    ax = plotting.ax_or_new(ax)
    t = ds["time"].values
    for key in ds[dim].values:
        ax.plot(t, ds[var].sel({dim: key}), label=f"{prefix}{key}")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    _legend(ax)
    ax.grid(alpha=0.3)


def plot_energy(ds, ax=None):
    """Energy balance (top) and, on their own scale, the losses by mechanism and the residual."""
    if ax is None or not hasattr(ax, "__len__"):
        fig, ax = _fig(2)
    t = ds["time"].values
    a = ax[0]
    a.plot(t, ds["work_in"], label="work in", color="k")
    a.plot(t, ds["energy_change"], label="energy stored (kinetic + potential)", color="C4")
    a.plot(t, ds["dissipated"].sum("mechanism"), label="dissipated (all)", color="C3")
    a.set_ylabel("energy (J)")
    a.set_title("energy balance")
    _legend(a)
    a.grid(alpha=0.3)
    b = ax[1]
    D = ds["dissipated"]
    for k, m in enumerate(ds["mechanism"].values):
        if float(np.abs(D.sel(mechanism=m)).max()) > 0:
            b.plot(t, D.sel(mechanism=m), label=str(m).replace("_", " "), color=f"C{k % 10}")
    b.plot(t, ds["energy_residual"], label="residual (integration error)", ls="--", color="0.3")
    b.set_ylabel("energy (J)")
    b.set_xlabel("time (s)")
    b.set_title("dissipated by mechanism (zero ones left out), and the residual")
    _legend(b)
    b.grid(alpha=0.3)


def plot_spectrum(ds, driver, ax):
    """Amplitude spectra over the steady window: tight-span tension, driven speeds, hub loads;
    dotted lines at the driver's orders."""
    t = ds["time"].values
    sel = _steady(ds)
    n = int(sel.sum())
    if n < 16:
        return False
    dt = t[1] - t[0]
    f = np.fft.rfftfreq(n, dt)
    win = np.hanning(n)

    def amp(x):
        x = x[sel] - x[sel].mean()
        return np.abs(np.fft.rfft(x * win)) * 2 / win.sum()

    # at most ~500 points per line: the largest of each block, so that every peak stays drawn
    block = max(1, (len(f) - 1) // 500)
    m = (len(f) - 1) // block * block

    def peaks(a):
        return a[1:1 + m].reshape(-1, block).max(axis=1)

    fb = f[1:1 + m].reshape(-1, block).mean(axis=1)

    labels = span_labels(ds)
    tight = int(np.argmax(ds["span_tension"].values[sel].mean(axis=0)))
    sp = str(ds["span"].values[tight])
    a_tight = amp(ds["span_tension"].values[:, tight])
    if np.any(peaks(a_tight) > 0):      # every span slack (no grip: a drive sliding grossly) has none
        ax[0].semilogy(fb, peaks(a_tight), color=f"C{tight % 10}", lw=0.8, label=labels[sp])
    else:
        ax[0].text(0.5, 0.5, "the span tensions do not vary", transform=ax[0].transAxes, ha="center", va="center")
    ax[0].set_ylabel("tension (N)")
    ax[0].set_title("spectrum of the tight span's tension (steady window)")
    held = prescribed(ds)
    for nm in ds["pulley"].values:
        for a, var in ((ax[1], "speed"), (ax[2], "hub_load")):
            if var == "speed" and str(nm) in held:
                continue
            y = peaks(amp(ds[var].sel(pulley=nm).values))
            if np.any(y > 0):       # a pulley held at a constant speed has none to draw on a log axis
                a.semilogy(fb, y, color=colour(ds, nm), lw=0.8, label=str(nm))
    ax[1].set_ylabel("speed (rad/s)")
    ax[1].set_title("spectra of the pulley speeds" + (f" ({', '.join(held)}: prescribed, left out)" if held else ""))
    ax[2].set_ylabel("hub load (N)")
    ax[2].set_title("spectra of the hub loads")
    ax[2].set_xlabel("frequency (Hz)")
    fd = abs(float(ds["speed"].sel(pulley=driver).values[sel].mean())) / (2 * np.pi)
    from matplotlib.ticker import NullLocator

    # dotted lines at the driver's orders 1-6 only where they stand apart (at 4 Hz on a 500 Hz
    # axis they crowd the left edge); the order axis on top reads any peak as an order
    spread = fd > 0 and 6 * fd > 0.15 * f[-1]
    for a in ax:
        a.yaxis.set_minor_locator(NullLocator())    # 8 unlabelled ticks a decade: a third of the figure's time
        if spread:
            for k in range(1, 7):
                if k * fd < f[-1]:
                    a.axvline(k * fd, color="0.5", ls=":", lw=0.8)
        a.grid(alpha=0.3)
        _legend(a)
    a = ax[0]
    if fd > 0:
        order = a.secondary_xaxis("top", functions=(lambda x: x / fd, lambda o: o * fd))
        dotted = "; dotted: orders 1-6" if spread else ""
        order.set_xlabel(f"order of the driver's mean speed ({fd:.3g} Hz, {60 * fd:.0f} rpm){dotted}", fontsize=8)
        order.tick_params(labelsize=8)
        a.set_title(a.get_title(), pad=30)
        # at full resolution, not the drawn blocks
        _label_peaks(a, f, a_tight, fd, _segment_passing(ds, driver, fd))
    return True


def prescribed(ds) -> list[str]:
    """The pulleys whose speed the model prescribes (speed_time): their speed spectrum is round-off."""
    if "model_toml" not in ds.attrs:
        return []
    from ..core.model import loads

    return [p.name for p in loads(ds.attrs["model_toml"]).pulleys if p.speed_time is not None]


def _segment_passing(ds, driver, fd):
    """The frequency at which the segment model's segments pass a point (its polygon effect, a
    discretisation artefact): the belt's speed on the driver over the segment length of the last
    frame; None without frames (the rotational model has no segments)."""
    if ds.sizes.get("frame", 0) == 0 or "belt_x" not in ds or "pulley_radius" not in ds:
        return None
    x, y = ds["belt_x"].values[-1], ds["belt_y"].values[-1]
    perimeter = float(np.hypot(np.diff(np.append(x, x[0])), np.diff(np.append(y, y[0]))).sum())
    r = float(ds["pulley_radius"].sel(pulley=driver))
    return 2 * np.pi * fd * r * len(x) / perimeter if perimeter > 0 else None


def _label_peaks(ax, f, amp, fd, passing=None, count=3):
    """Name the largest peaks of a spectrum by frequency and driver order; a peak at the segments'
    passing frequency ``passing`` or its harmonics is named as the discretisation's."""
    # local maxima standing a decade above the lowest point within +-5 % of the band on either
    # side (a prominence test; scipy.signal.find_peaks costs a 0.65 s import in a fresh painter)
    la = np.log10(np.maximum(amp, 1e-300))
    w = max(2, len(la) // 20)
    # from the 3rd bin on: the Hann window's main lobe spans 2 bins either side of 0 Hz, where the
    # window's mean and a drift over it leak (a "1 Hz, order 0.0" peak of a run-up's tension)
    idx = [i for i in range(3, len(la) - 1) if la[i] > la[i - 1] and la[i] >= la[i + 1]
           and la[i] - min(la[max(0, i - w):i].min(), la[i + 1:i + 1 + w].min()) >= 1.0]
    idx = np.array(idx, dtype=int)
    top = idx[np.argsort(amp[idx])[::-1][:count]] if len(idx) else idx
    # within 2 bins or 2 %: the segments' length varies with the tension along the belt
    tol = max(2 * (f[1] - f[0]), 0.02 * passing) if passing else 0.0
    for i in top:
        k = round(f[i] / passing) if passing else 0
        text = (f"{f[i]:.0f} Hz\norder {f[i] / fd:.1f}" if not (k >= 1 and abs(f[i] - k * passing) <= k * tol)
                else f"{f[i]:.0f} Hz\nsegment passing{f' x{k}' if k > 1 else ''}\n(discretisation)")
        ax.annotate(text, (f[i], amp[i]), xytext=(3, 2), textcoords="offset points", fontsize=7, va="bottom",
                    color="0.25")
    if len(top):
        lo, hi = ax.get_ylim()
        ax.set_ylim(lo, hi * 8)     # room for the labels above the peaks (log axis)


def draw_drive(ds, frame, ax, vmax=None):
    """Pulleys and the belt at one frame, segments coloured by the element force."""
    import matplotlib.patches as mpatches

    curves = _pitch_curves(ds)
    for j in range(ds.sizes["pulley"]):
        nm = ds["pulley"].values[j]
        cx, cy = float(ds["pulley_x"][j]), float(ds["pulley_y"][j])
        if j in curves:     # a pitch curve, turned by the pulley's angle at the frame, and its reference line
            th = float(np.interp(float(ds["frame_time"][frame]), ds["time"].values, ds["angle"].values[:, j]))
            phi = np.linspace(0, 2 * math.pi, 361)
            r = curves[j].radii(phi)
            ax.plot(cx + r * np.cos(phi + th), cy + r * np.sin(phi + th), lw=1.4, color=colour(ds, nm))
            ax.plot([cx, cx + r[0] * math.cos(th)], [cy, cy + r[0] * math.sin(th)], lw=0.8, color=colour(ds, nm))
        else:
            ax.add_patch(mpatches.Circle((cx, cy), float(ds["pulley_radius"][j]), fill=False, lw=1.4,
                                         color=colour(ds, nm)))
        ax.annotate(str(nm), (float(ds["pulley_x"][j]), float(ds["pulley_y"][j])), ha="center", va="center",
                    fontsize=7, color=colour(ds, nm))
    _draw_arms(ds, frame, ax)
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


def _pitch_curves(ds) -> dict:
    """{pulley index: its pitch curve} of the run's model (mechanics/pitch_curves.py), {} without."""
    if "model_toml" not in ds.attrs or "pitch_curve" not in ds.attrs["model_toml"] or "angle" not in ds:
        return {}
    from ..core.model import loads

    return {j: p.curve for j, p in enumerate(loads(ds.attrs["model_toml"]).pulleys) if p.pitch_curve is not None}


def _draw_arms(ds, frame, ax):
    """Each tensioner arm at the frame: pivot, arm, and its stops (thin lines at the stop angles)."""
    if "arm_angle" not in ds or "model_toml" not in ds.attrs:
        return
    from ..core.model import loads

    model = loads(ds.attrs["model_toml"])
    t = float(ds["frame_time"][frame])
    for p in model.pulleys:
        if getattr(p, "arm", None) is None or p.name not in ds["arm"].values.tolist():
            continue
        px, py = p.arm.pivot
        cx, cy = p.center
        L = math.hypot(cx - px, cy - py)
        psi0 = math.atan2(cy - py, cx - px)
        psi_t = ds["arm_angle"].sel(arm=p.name).values
        q_t = ds["arm_travel"].sel(arm=p.name).values
        psi = float(np.interp(t, ds["time"].values, psi_t))
        k = int(np.argmax(np.abs(q_t)))
        sense = 1.0 if abs(q_t[k]) < 1e-12 else float(np.sign(np.angle(np.exp(1j * (psi_t[k] - psi0))) / q_t[k]))
        for q in p.arm.stops:
            a = psi0 + sense * q
            ax.plot([px, px + 1.15 * L * math.cos(a)], [py, py + 1.15 * L * math.sin(a)], color="0.55", lw=0.8, ls=":")
        ax.plot([px, px + L * math.cos(psi)], [py, py + L * math.sin(psi)], color="0.2", lw=2.2, solid_capstyle="round")
        ax.plot([px], [py], "o", color="0.2", ms=5)
        ax.annotate("pivot", (px, py), xytext=(3, -9), textcoords="offset points", fontsize=6, color="0.3")


def _mean_tensions(ds):
    """Span tensions over the steady window (the modes' geometric stiffness), None without spans."""
    if "span_tension" not in ds or ds.sizes.get("time", 0) == 0:
        return None
    w = ds.attrs.get("steady_window")
    t = ds["time"].values
    sel = (t >= w[0]) & (t <= w[1]) if w is not None else np.ones(len(t), bool)
    ten = ds["span_tension"].values[sel if np.any(sel) else slice(None)].mean(axis=0)
    return ten if np.all(np.isfinite(ten)) else None


def plot_campbell(ds, frequencies_hz, driver, ax=None, orders=(1, 2, 3, 4, 6), rpm_max=None, flap=None,
                  speed_range=None, own_orders=None, free_rotor_hz=(), duty_range=None, counted=None):
    """Campbell diagram: the drive's rotational modes (horizontal; one-way clutches locked, and
    dotted with their rotors free) and the spans' first flap frequencies (``flap``: {span: (rpm,
    Hz)}, belt/steady/flap.py) against the orders of the driver's rotation (k x driver speed).
    ``speed_range``: the run's (rpm; a line where it is one speed), ``duty_range``: the duty cycle's
    crank speeds (shaded; the axis covers them). Circles mark the mode crossings the verdict lists:
    of the ``counted`` orders (default: all drawn) inside the run's and the duty cycle's range.
    ``own_orders``: {label: order in driver orders} of accessories' own excitations (an A/C
    compressor's pistons)."""
    ax = plotting.ax_or_new(ax)
    for f in free_rotor_hz:
        ax.axhline(f, color="C0", lw=0.9, ls=":", alpha=0.8)
        ax.text(0.01, f, f"{f:.1f} Hz (clutch overrunning)", va="bottom", ha="left",
                fontsize=7, color="C0", alpha=0.8, transform=ax.get_yaxis_transform())
    w = np.abs(ds["speed"].sel(pulley=driver).values)
    rpm_run = float(w.max()) * 30 / np.pi if len(w) else 0.0
    top_rpm = rpm_max or max(1.25 * rpm_run, 1.08 * duty_range[1] if duty_range else 0.0, 1.0)
    orders = sorted(set(orders))
    counted = orders if counted is None else sorted(set(counted))
    flap = flap or {}
    f_flap = [float(np.max(f)) for _, f in flap.values() if len(f)]
    f_top = max([1.1 * f for f in list(frequencies_hz) + list(free_rotor_hz) + f_flap]
                + [max(orders or [1]) * top_rpm / 60 * 0.6])
    if duty_range is not None:
        ax.axvspan(*duty_range, color="0.88", zorder=0, label=f"duty cycle: {duty_range[0]:.0f}-{duty_range[1]:.0f} rpm")
    if speed_range is not None:
        lo, hi = speed_range
        if hi - lo < 0.005 * max(hi, 1.0):      # one speed: a line (a band of no width is not drawn)
            ax.axvline(hi, color="0.45", lw=1.0, ls="-.", zorder=0, label=f"run: {hi:.0f} rpm")
        else:
            ax.axvspan(lo, hi, color="0.78", zorder=0, alpha=0.6, label=f"run: {lo:.0f}-{hi:.0f} rpm")
    judged = [x for x in (speed_range, duty_range) if x is not None]
    j_lo = min((x[0] for x in judged), default=0.0)
    j_hi = max((x[1] for x in judged), default=top_rpm)
    for f in frequencies_hz:
        if f > f_top:
            continue
        ax.axhline(f, color="C0", lw=1.2)
        ax.text(top_rpm * 0.99, f, f" {f:.1f} Hz", va="bottom", ha="right", fontsize=8, color="C0")
    n = np.array([0.0, top_rpm])
    lines = [(k, f"{k:g}", "0.4") for k in orders] + [(k, lab, "C4") for lab, k in (own_orders or {}).items()]
    marked = False
    for k, lab, col in lines:
        ax.plot(n, k * n / 60, color=col, lw=0.8, ls="--")
        y = k * top_rpm / 60
        if y <= f_top:
            ax.text(top_rpm, y, f" {lab}", fontsize=8, color=col, va="center")
        else:
            ax.text(60 * f_top / k, f_top, f"{lab} ", fontsize=8, color=col, va="top", ha="right")
        if k not in counted:
            continue
        for f in frequencies_hz:   # resonance: order k at the speed where k n / 60 = f
            if j_lo <= 60 * f / k <= j_hi:
                ax.plot(60 * f / k, f, "o", color="C3", ms=5,
                        label=None if marked else "mode crossed by a declared order (listed in the verdict)")
                marked = True
    from .steady.flap import crossings

    squares = False
    for i, (span, (rpm, f)) in enumerate(flap.items()):
        rpm, f = np.asarray(rpm), np.asarray(f)
        style = dict(color=f"C{(i + 1) % 10}", lw=1.6)
        if len(rpm) > 1:
            ax.plot(rpm, f, label=f"flap {span}", **style)
        else:
            ax.axhline(f[0], ls="-.", label=f"flap {span}", **style)
        fl = {"speed_rpm": rpm.tolist(), "spans": {span: {"f1": f.tolist()}}}
        for x in crossings(fl, counted, speed_range or (0, top_rpm)):
            ax.plot(x["rpm"], x["frequency_hz"], "s", mfc="none", mec="C3", ms=7,
                    label=None if squares else "flap crossed in the run")
            squares = True
    ax.set_xlim(0, top_rpm * 1.08)
    ax.set_ylim(0, f_top)
    ax.set_xlabel(f"{driver} speed (rpm)")
    ax.set_ylabel("frequency (Hz)")
    said = "orders of the driver (dashed" + ("" if counted else "; the crank declares none: no crossing counted") + ")"
    ax.set_title("Campbell diagram: rotational modes (blue" + ("; dotted: clutch overrunning" if free_rotor_hz else "")
                 + ")" + (", span flap f1 (coloured)" if flap else "") + ",\n" + said, fontsize=9)
    if ax.get_legend_handles_labels()[0]:
        _legend(ax)        # beside the axes: inside, it hid the top modes' and orders' labels
    ax.grid(alpha=0.3)
    return ax


def plot_tooth_map(ds, name, ax, window=None):
    """The loads of the teeth in mesh on grooved pulley ``name`` through time: a map over the groove
    positions (the pulley's fixed-frame angle) and time, over the steady window."""
    m = list(ds["toothed_pulley"].values).index(name)
    t = ds["time"].values
    sel = np.ones(len(t), bool) if window is None else (t >= window[0]) & (t <= window[1])
    z = int(ds["grooves"].values[m])
    q = ds["tooth_load"].values[sel, m, :z]
    lim = float(np.nanmax(np.abs(q))) if np.isfinite(q).any() else 1.0
    mesh = ax.pcolormesh((np.arange(z) + 0.5) * 360.0 / z, t[sel], q, cmap="RdBu_r", vmin=-lim, vmax=lim,
                         shading="nearest")
    ax.set_xlim(0.0, 360.0)
    ax.set_ylabel("time (s)")
    ax.set_title(f"tooth loads on {name} ({z} grooves): largest {lim:.1f} N", fontsize=10)
    return mesh


def plot_phase_error(ds, ax, window=None):
    """Each grooved pulley's angle against its tooth ratio to the first (the crank), in crank degrees."""
    t = ds["time"].values
    sel = np.ones(len(t), bool) if window is None else (t >= window[0]) & (t <= window[1])
    names = list(ds["toothed_pulley"].values)
    first = names[0]
    crank = np.degrees(ds["angle"].sel(pulley=first).values[sel])
    crank = crank - crank[0] if len(crank) else crank
    for m, name in enumerate(names[1:], start=1):
        e = ds["phase_error"].values[sel, m]
        ax.plot(crank, e - e.mean(), lw=1.0, label=f"{name}: {e.max() - e.min():.2f} deg peak to peak")
    ax.set_xlabel(f"{first} angle over the window (deg)")
    ax.set_ylabel(f"phase error ({first} deg)")
    ax.set_title(f"transmission error against the tooth ratio to {first} (mean taken off)", fontsize=10)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False)


def _figures(ds, driver):
    """The standard figures as (file name, function that draws it), in writing order."""
    jobs = []

    def speeds():
        fig, ax = _fig(2)
        plot_speeds(ds, ax=ax[0])
        plot_slip(ds, driver, ax=ax[1])
        ax[1].set_xlabel("time (s)")
        return fig

    def tensions():
        fig, ax = _fig(2)
        plot_spans(ds, ax=ax[0])
        plot_hub_loads(ds, ax=ax[1])
        ax[1].set_xlabel("time (s)")
        return fig

    def segment_forces():
        fig, ax = _fig(3, 2.6)
        for k, (var, title) in enumerate((("element_force", "longitudinal element force after segment (seed fig. 11)"),
                                           ("normal_force", "contact normal force on segment (seed fig. 12)"),
                                           ("friction_force", "friction force on segment (seed fig. 13)"))):
            plot_lines(ds, var, "tracked", "force (N)", title, ax=ax[k], prefix="segment ")
        ax[2].set_xlabel("time (s)")
        return fig

    def energy():
        fig, ax = _fig(2)
        plot_energy(ds, ax=ax)
        return fig

    def spectrum():
        fig, ax = _fig(3, 2.6)
        h = fig.get_figheight()
        fig.subplots_adjust(top=1 - 0.85 / h)     # room for the order axis above the first panel
        return fig if plot_spectrum(ds, driver, ax) else None

    def campbell():   # the drive's rotational modes (modes.py) against the driver's orders
        from ..core.model import loads
        from .steady.modes import drive_modes

        from .criteria import speed_range
        from .steady.flap import excited_orders

        model = loads(ds.attrs["model_toml"])
        md = drive_modes(model, tensions=_mean_tensions(ds))
        flap = {}
        if "flap_frequency" in ds:
            for sp in ds["flap_span"].values.tolist():
                flap[sp] = (ds["flap_rpm"].values, ds["flap_frequency"].sel(flap_span=sp, flap_mode=1).values)
        if not md.frequencies_hz and not flap:
            return None
        orders = excited_orders(model, driver, extra=model.criteria.flap_orders) or [1, 2, 3, 4]
        # an accessory's own orders (on its own angle) in orders of the driver: k r_driver / r_accessory
        names = ds["pulley"].values.tolist()
        r = ds["pulley_radius"].values
        jd = names.index(driver) if driver in names else 0
        own = {f"{p.name} {h.order:g}": h.order * r[jd] / r[names.index(p.name)]
               for p in model.pulleys for h in (getattr(p, "load_harmonics", None) or []) if p.name in names}
        fig, ax = _fig(1, 5)
        fig.subplots_adjust(top=1 - 0.85 / fig.get_figheight())     # a two-line title and the status line above it
        dc = model.duty_cycle
        duty = None
        if dc is not None and dc.rows:
            w = [abs(r.crank_speed) * 30 / np.pi for r in dc.rows]
            duty = (min(w), max(w))
        plot_campbell(ds, md.frequencies_hz, driver, ax=ax[0], orders=orders, flap=flap, own_orders=own,
                      speed_range=speed_range(ds, {}, driver), free_rotor_hz=md.free_rotor_hz, duty_range=duty,
                      counted=excited_orders(model, driver, model.criteria.flap_amplitude_min, model.criteria.flap_orders))
        return fig

    def runup():
        from matplotlib.figure import Figure

        fig = Figure(figsize=(10, 11), layout="constrained")
        ax = fig.subplots(4 if "runup_arm_travel_min" in ds else 3, 1, sharex=True)
        plot_runup(ds, ax)
        return fig

    def waterfall():
        from matplotlib.figure import Figure

        fig = Figure(figsize=(8, 5), layout="constrained")
        tight = str(ds["span"].values[int(np.argmax(ds["runup_tension_mean"].values.mean(axis=0)))])
        try:
            from ..core.model import loads
            from .steady.modes import drive_modes

            fm = drive_modes(loads(ds.attrs["model_toml"]), tensions=_mean_tensions(ds)).frequencies_hz
        except Exception:
            fm = []
        plot_waterfall(ds, tight, fig.add_subplot(), modes=fm)
        return fig

    def belt():
        # sized to the drive's aspect, so that it fills the page
        xs, ys = ds["belt_x"].values, ds["belt_y"].values
        aspect = (np.ptp(ys) + 0.1 * np.ptp(xs)) / max(np.ptp(xs), 1e-9)
        from matplotlib.figure import Figure

        fig = Figure(figsize=(8, min(max(8 * aspect * 0.85 + 0.8, 2.6), 9)), layout="constrained")
        a = fig.add_subplot()
        sc = draw_drive(ds, ds.sizes["frame"] - 1, a)
        # a flat drive (equal aspect) is short: a colour bar beside it would stand taller than it
        wide = aspect < 0.6
        fig.colorbar(sc, ax=a, label="element force (N)", location="bottom" if wide else "right",
                     shrink=0.5 if wide else 0.8, aspect=40 if wide else 30, pad=0.01)
        return fig

    def teeth():
        names = list(ds["toothed_pulley"].values)
        window = ds.attrs.get("steady_window")
        fig, ax = _fig(len(names), 2.4)
        ax = np.atleast_1d(ax)
        for k, name in enumerate(names):
            mesh = plot_tooth_map(ds, name, ax[k], window)
            fig.colorbar(mesh, ax=ax[k], label="tooth load (N)", fraction=0.05, pad=0.01)
        ax[-1].set_xlabel("groove position (deg, counter-clockwise from +x)")
        return fig

    def phase():
        fig, ax = _fig(1)
        plot_phase_error(ds, np.atleast_1d(ax)[0], ds.attrs.get("steady_window"))
        return fig

    jobs += [("speeds.png", speeds), ("tensions.png", tensions)]
    if "tooth_load" in ds:
        jobs.append(("teeth.png", teeth))
        if ds.sizes.get("toothed_pulley", 0) > 1:
            jobs.append(("phase_error.png", phase))
    if "tracked" in ds.coords:            # the segment model's tracked segments (not the rotational model)
        jobs.append(("segment_forces.png", segment_forces))
    if np.isfinite(ds["energy_residual"].values).any():     # a periodic run-up has no one energy balance
        jobs.append(("energy.png", energy))
    jobs.append(("spectrum.png", spectrum))
    if "model_toml" in ds.attrs:
        jobs.append(("campbell.png", campbell))
    if "speed_bin" in ds.coords:
        jobs += [("runup.png", runup), ("waterfall.png", waterfall)]
    if ds.sizes.get("frame", 0):
        jobs.append(("belt.png", belt))
    return jobs


def _draw_figure(jobs, k, outdir, result):
    import matplotlib

    name, fn = jobs[k]
    # titles at a fixed height: matplotlib otherwise measures every tick label once more to
    # place them (nothing sits above these axes); 8 % of the drawing time, measured
    with matplotlib.rc_context({"axes.titley": 1.0}):
        fig = fn()
    if fig is None:
        return None
    return str(plotting.save(fig, outdir / name, result, None, dpi=90))


def _paint(result, outdir, k):
    """Figure ``k`` of the standard set, drawn in a painter (plotting.Painters)."""
    return _draw_figure(_figures(result.ds, _driver(result)), k, outdir, result)


def _driver(result):
    return result.summary.get("driver", str(result.ds["pulley"].values[0]))


def painters_useful(model) -> bool:
    """Whether painters forked before ``model``'s solve pay off: not for the rotational model, whose
    solve takes a fraction of a second, shorter than their one-at-a-time start, which then waits on
    the critical path (its figures are drawn by processes forked after the solve: plot_all)."""
    return model.simulation.model != "rotational"


def plot_all(result, outdir, workers=None, meanwhile=None, painters=None) -> list[Path]:
    """Write the standard figures (and belt.gif when ``output.animation``). ``painters``
    (plotting.Painters, forked before the solve) draw them while this process runs
    ``meanwhile()``; else plotting.draw_all draws them (in two processes forked now where it can).
    ``workers=1`` forces the serial path."""
    ds, outdir = result.ds, Path(outdir)
    if ds.sizes.get("time", 0) == 0:
        if meanwhile is not None:
            meanwhile()
        return []
    jobs = _figures(ds, _driver(result))
    if painters is not None and workers != 1:
        pending = [painters.submit(result, _paint, outdir, k) for k in range(len(jobs))]
        if meanwhile is not None:
            meanwhile()
        done = [f.result() for f in pending]
    else:
        status = plotting.StatusOnly.of(result)
        done = plotting.draw_all(len(jobs), lambda k: _draw_figure(jobs, k, outdir, status), meanwhile, workers)
    files = [Path(p) for p in done if p]
    if ds.sizes.get("frame", 0) and ds.attrs.get("animation"):
        files.append(animate(ds, outdir / "belt.gif"))
    return files


def plot_runup(ds, ax):
    """Run-up per crank-speed bin: span tension bands, largest slip, arm travel, order cuts."""
    rpm = ds["speed_bin"].values
    # one colour per span, its bin minimum solid and maximum dashed (six overlapping bands could
    # not be read); the smallest minimum is what the slack-span criterion judges
    for q, sp in enumerate(ds["span"].values):
        lo, hi = ds["runup_tension_min"].values[:, q], ds["runup_tension_max"].values[:, q]
        line, = ax[0].plot(rpm, lo, label=str(sp), lw=1.4)
        ax[0].plot(rpm, hi, color=line.get_color(), ls="--", lw=0.9)
    ax[0].set_ylabel("span tension (N)")
    ax[0].set_title("span tension per crank-speed bin: minimum (solid) and maximum (dashed)")
    _legend(ax[0])
    crank = ds.attrs.get("runup_crank")
    for nm in ds["pulley"].values:
        if str(nm) != crank:
            ax[1].plot(rpm, 100 * ds["runup_slip"].sel(pulley=nm), label=str(nm), color=colour(ds, nm))
    ax[1].set_ylabel("slip (%)")
    ax[1].set_title("slip against the crank (bin mean speeds)")
    _legend(ax[1])
    tight = int(np.argmax(ds["runup_tension_mean"].values.mean(axis=0)))
    for k in ds["order"].values:
        ax[2].plot(rpm, ds["runup_tension_order"].sel(order=k).values[:, tight], label=f"order {k:g}")
    ax[2].set_ylabel("amplitude (N)")
    ax[2].set_title(f"order cuts: tension of span {ds['span'].values[tight]}")
    _legend(ax[2])
    if "runup_arm_travel_min" in ds:
        for a, nm in enumerate(ds["arm"].values):
            lo = np.degrees(ds["runup_arm_travel_min"].values[:, a])
            hi = np.degrees(ds["runup_arm_travel_max"].values[:, a])
            ax[3].fill_between(rpm, lo, hi, alpha=0.4, label=f"{nm}: travel range")
        ax[3].set_ylabel("arm travel (deg)")
        ax[3].set_title("tensioner arm travel per bin (into the belt positive)")
        _legend(ax[3])
    ax[-1].set_xlabel("crank speed (rpm)")
    for a in ax:
        a.grid(alpha=0.3)


def plot_waterfall(ds, span, ax, modes=None):
    """Spectrum of a span tension against crank speed (short windows along the run-up), with the
    engine-order lines f = k n / 60."""
    t = ds["time"].values
    x = ds["span_tension"].sel(span=span).values
    rpm_t = np.interp(t, *_crank_rpm(ds))
    dt = t[1] - t[0]
    nwin = int(2 ** np.floor(np.log2(max(16, 0.1 / dt))))      # about 0.1 s windows
    starts = range(0, len(t) - nwin, nwin // 2)
    f = np.fft.rfftfreq(nwin, dt)
    S, R = [], []
    for i in starts:
        seg = x[i:i + nwin]
        S.append(np.abs(np.fft.rfft((seg - seg.mean()) * np.hanning(nwin))) * 4 / nwin)
        R.append(rpm_t[i + nwin // 2])
    if not S:
        return
    S = np.array(S)
    fmax = min(f[-1], 8 * max(R) / 60)
    keep = f <= fmax
    from matplotlib.colors import LogNorm

    A = S[:, keep]
    top = float(A.max()) if A.size and A.max() > 0 else 1.0
    # logarithmic amplitude: the orders and resonances span three decades
    mesh = ax.pcolormesh(f[keep], R, np.maximum(A, top * 1e-3), shading="nearest", cmap="viridis",
                         norm=LogNorm(vmin=top * 1e-3, vmax=top))
    cb = ax.figure.colorbar(mesh, ax=ax, label="amplitude (N, log scale)")
    # plain numbers: figures are written with math text off (every label literal), which would
    # print a log axis's default labels as "$\mathdefault{10^{2}}$"
    from matplotlib.ticker import FuncFormatter

    cb.ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    for k in ds["order"].values:
        ax.plot(np.array(R) * k / 60, R, "w--", lw=0.7)
        x = max(R) * k / 60
        if x < fmax * 0.97:
            ax.text(x, max(R), f" {k:g}", color="w", fontsize=8, ha="left", va="top")
        else:     # the order leaves through the right edge: label it there
            ax.text(fmax * 0.99, 60 * fmax / k, f"{k:g} ", color="w", fontsize=8, ha="right", va="center")
    for fm in (modes or []):
        if fm < fmax:
            ax.axvline(fm, color="C1", lw=0.8, ls=":")
            ax.text(fm, min(R), f" {fm:.0f} Hz", color="C1", fontsize=7, rotation=90, va="bottom", ha="right")
    if "flap_frequency" in ds and span in ds["flap_span"].values.tolist():
        ff = ds["flap_frequency"].sel(flap_span=span, flap_mode=1).values
        # named in the title: a legend in a corner hid the modes' labels along the bottom edge
        ax.plot(ff, ds["flap_rpm"].values, color="C3", lw=1.2, label=f"flap f1 of {span}")
    ax.set_xlim(0, fmax)
    ax.set_xlabel("frequency (Hz)")
    ax.set_ylabel("crank speed (rpm)")
    ax.set_title(f"waterfall: tension of span {span}\n(dashed: engine orders; dotted: rotational modes; red: the span's flap f1)", fontsize=9)


def _crank_rpm(ds):
    return ds["time"].values, ds["crank_rpm"].values


def animate(ds, path, max_frames=60) -> Path:
    """GIF of the belt moving, segments coloured by the element force."""
    from matplotlib.animation import FuncAnimation, PillowWriter
    from matplotlib.figure import Figure

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
    return plotting.save_animation(anim, path, writer=PillowWriter(fps=10), dpi=70)


def plot_pitch_turn(turn, ax=None):
    """The belt path on non-circular pitch curves over a turn (a mechanics.curve_turn.Turn, e.g.
    geometry/pitch_turn.turn_of(model)): the belt length's and each span's change from its mean
    against the turned pulley's angle (mm), legends with the ranges."""
    ax = plotting.ax_or_new(ax)
    deg = np.degrees(turn.theta - turn.theta[0])
    name = turn.names[turn.pulley]
    out = ax.plot(deg, (turn.length - turn.length.mean()) * 1e3, color="k", lw=1.5,
                  label=f"belt length {turn.length.mean() * 1e3:.2f} mm, range {np.ptp(turn.length) * 1e3:.3f} mm")
    for i, sp in enumerate(turn.span_names):
        s = turn.spans[:, i]
        out += ax.plot(deg, (s - s.mean()) * 1e3, color=f"C{i % 10}", lw=1,
                       label=f"span {sp} {s.mean() * 1e3:.2f} mm, range {np.ptp(s) * 1e3:.3f} mm")
    ax.set_xlabel(f"angle of {name} (deg)")
    ax.set_ylabel("change from the mean (mm)")
    ax.set_title(f"belt path on the pitch curves over {turn.turns} turn(s) of {name}")
    ax.set_xlim(0, 360 * turn.turns)
    ax.legend(fontsize=7, loc="best")
    ax.grid(alpha=0.3)
    return out
