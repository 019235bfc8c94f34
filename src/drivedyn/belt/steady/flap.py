"""Span flap: the transverse natural frequencies of every free span of a belt run, at its running
tension and belt speed, and where the crank's orders cross them.

Each span is taken as the axially moving, tensioned beam of the span analysis
(``drivedyn.span.frequencies.moving_beam_frequencies``: pinned ends, length L between its
tangent points in the drawn layout, tension T, mass per metre m, bending stiffness EI, belt
speed V), whose first frequency without bending is the moving string's

    f_1 = c (1 - V^2 / c^2) / (2 L),   c = sqrt(T / m)        (Mote 1965; Wickert & Mote 1990).

The span tension of a run already holds the centrifugal part m V^2 (it is the force in the
moving belt), so it is used as T directly: at T = m V^2 the span has no stiffness left, f_1 = 0.
A steady run gives one point per span (the window's mean tension and belt speed); a run-up one
per crank-speed bin (the bin's mean tension, the belt speed of the bin's crank speed). An order k
of the crank excites the span at k n / 60 Hz (n in rpm): the crossings are the crank speeds where
k n / 60 = f_1(n), found between bins by linear interpolation of k n / 60 - f_1(n).
"""
from __future__ import annotations

import math

import numpy as np

from ...span.frequencies import moving_beam_frequencies

RPM = 30 / math.pi
MODES = 2


def span_frequencies(T, m, L, EI, V, modes=MODES) -> list[float]:
    """First ``modes`` flap frequencies (Hz) of a span; 0 where the span has no stiffness left
    (T <= m V^2: at or above its critical speed)."""
    try:
        return [float(f) for f in moving_beam_frequencies(float(T), m, L, EI, float(V), modes)]
    except Exception:          # at or beyond the critical speed: no natural frequency
        return [0.0] * modes


def flap(model, ds, summary) -> dict:
    """Flap frequencies of every span: ``{"speed_rpm": [...], "spans": {name: {"length",
    "f1": [...], "f2": [...]}}, "crank": name}``; one entry per run-up bin, or one for a steady
    run (the steady window's means)."""
    from ..geometry.layout import compute_layout

    lay = compute_layout(model)
    m = model.belt.mass_per_length
    EI = model.belt.bending_stiffness
    driver = summary.get("runup", {}).get("crank") or summary.get("driver")
    names = ds["pulley"].values.tolist()
    j = names.index(driver) if driver in names else 0
    r = float(ds["pulley_radius"].values[j])
    if "speed_bin" in ds.coords:
        rpm = np.asarray(ds["speed_bin"].values, float)
        tension = {s: ds["runup_tension_mean"].sel(span=s).values for s in ds["span"].values.tolist()}
    else:
        w = summary.get("pulleys", {}).get(driver, {}).get("speed_mean")
        if w is None:
            return {}
        rpm = np.array([abs(w) * RPM])
        tension = {s: np.array([summary["spans"][s]["tension_mean"]]) for s in summary.get("spans", {})}
    V = rpm / RPM * r
    out = {"crank": driver, "speed_rpm": rpm.tolist(), "belt_speed": V.tolist(), "spans": {}}
    for sp in lay.spans:
        if sp.name not in tension:
            continue
        fs = np.array([span_frequencies(T, m, sp.length, EI, v) for T, v in zip(tension[sp.name], V)])
        out["spans"][sp.name] = {"length": sp.length, **{f"f{n + 1}": fs[:, n].tolist() for n in range(MODES)}}
    return out


def excited_orders(model, crank: str, amplitude_min: float = 0.0, extra=()) -> list[float]:
    """Orders of the crank that excite the drive: its declared speed orders (amplitude in rad/s,
    the angle amplitude (rad) counted at 1000 rpm as angle x order x speed, at least ``amplitude_min``)
    and the ``extra`` orders the criteria name."""
    p = next((p for p in model.pulleys if p.name == crank), None)
    orders = set(float(k) for k in extra)
    for o in (p.speed_orders if p is not None else []):
        amp = abs(getattr(o, "amplitude", 0.0) or 0.0)
        ang = abs(o.angle)
        if max(amp, ang * o.order * 1000 / RPM) >= amplitude_min:
            orders.add(float(o.order))
    return sorted(orders)


def crossings(fl: dict, orders, speed_range, mode="f1") -> list[dict]:
    """Where order k meets a span's ``mode`` frequency inside ``speed_range`` (rpm, lo..hi):
    [{"span", "order", "rpm", "frequency_hz"}], sorted by speed. A steady run (one point) is
    taken at constant frequency: the crossing is at n = 60 f / k."""
    lo, hi = speed_range
    out = []
    rpm = np.asarray(fl.get("speed_rpm", []), float)
    for name, s in fl.get("spans", {}).items():
        f = np.asarray(s[mode], float)
        for k in orders:
            if len(rpm) == 1:
                if f[0] > 0:
                    n = 60 * f[0] / k
                    if lo <= n <= hi:
                        out.append({"span": name, "order": k, "rpm": float(n), "frequency_hz": float(f[0])})
                continue
            g = k * rpm / 60 - f
            for b in range(len(rpm) - 1):
                if g[b] == 0 or g[b] * g[b + 1] < 0:
                    x = b + (g[b] / (g[b] - g[b + 1]) if g[b] != g[b + 1] else 0.0)
                    n = float(np.interp(x, np.arange(len(rpm)), rpm))
                    if lo <= n <= hi:
                        out.append({"span": name, "order": k, "rpm": n, "frequency_hz": k * n / 60})
    return sorted(out, key=lambda c: c["rpm"])
