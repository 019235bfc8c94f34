"""Span flap: the transverse natural frequencies of every free span of a belt run, at its running
tension and belt speed, and where the crank's orders cross them.

Each span is taken as the axially moving, tensioned beam of the span analysis
(``drivedyn.mechanics.span.frequencies.moving_beam_spectrum``: pinned ends, length L between its
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

from ...mechanics.span.frequencies import moving_beam_spectrum

RPM = 30 / math.pi
MODES = 2


def span_frequencies(T, m, L, EI, V, modes=MODES) -> np.ndarray:
    """First ``modes`` flap frequencies (Hz) of a span at tensions T and belt speeds V (arrays of one
    length): shape (len, modes); 0 where the span has no stiffness left (T <= m V^2: at or above its
    critical speed)."""
    return np.nan_to_num(moving_beam_spectrum(np.asarray(T, float), m, L, EI, np.asarray(V, float), modes), nan=0.0)


def flap(model, ds, summary) -> dict:
    """Flap frequencies of every span: ``{"speed_rpm": [...], "spans": {name: {"length",
    "f1": [...], "f2": [...]}}, "crank": name}``; one entry per run-up bin, or one for a steady
    run (the steady window's means)."""
    from ...mechanics.layout import compute_layout

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
        fs = span_frequencies(tension[sp.name], m, sp.length, EI, V)
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


def crossings(fl: dict, orders, speed_range, mode="f1", factor=1.0) -> list[dict]:
    """Where order k meets a span's ``mode`` frequency inside ``speed_range`` (rpm, lo..hi):
    [{"span", "order", "rpm", "frequency_hz"}], sorted by speed. A steady run (one point) is
    taken at constant frequency: the crossing is at n = 60 f / k."""
    lo, hi = speed_range
    out = []
    rpm = np.asarray(fl.get("speed_rpm", []), float)
    for name, s in fl.get("spans", {}).items():
        f = factor * np.asarray(s[mode], float)
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


def moving_ends(model, lay) -> dict:
    """Per span with an end on a tensioner pulley: the transverse motion of that end per unit arm
    rotation (m/rad, an arm: its length times the share of its swing normal to the span) or slider
    travel (m/m), and the tensioner's name."""
    out = {}
    for sp in lay.spans:
        d = np.subtract(sp.p1, sp.p0)
        d = d / max(float(np.hypot(*d)), 1e-12)
        for j in (sp.start, sp.end):
            p = model.pulleys[j]
            if p.arm is not None:
                arm = np.subtract(lay.centers[j], p.arm.pivot)
                swing = np.array([-arm[1], arm[0]])          # the centre's motion per radian
                e = abs(float(swing[0] * d[1] - swing[1] * d[0]))
            elif p.slider is not None:
                u = np.asarray(p.slider.direction, float)
                u = u / max(float(np.hypot(*u)), 1e-12)
                e = abs(float(u[0] * d[1] - u[1] * d[0]))
            else:
                continue
            out[sp.name] = (max(e, out.get(sp.name, (0.0, ""))[0]), p.name)
    return out


def judged_crossings(model, fl: dict, orders, speed_range, zeta, tension_amp, tension_mean, end_amp) -> list[dict]:
    """The flap crossings classed by what excites the span (Mathieu's equation for a string whose
    stiffness the tension modulates; the forced string for a moving end):

    - ``direct``: order k at the first flap frequency (k n = f1) on a span whose end moves with a
      tensioner: its end's transverse motion e (end_amp(span, order, rpm), m) drives the first mode,
      at resonance to about e (2 / pi) / (2 zeta) = e / (pi zeta) (``amplitude``); counted;
    - ``parametric``: order k at twice the first flap frequency (k n = 2 f1, the principal parametric
      resonance): counted where the order's tension amplitude dT exceeds 4 zeta (T - m v^2), the
      damped Mathieu threshold (eps > 4 zeta, eps = dT / (T - m v^2)); listed below it;
    - ``none``: order k at f1 on a span between fixed pulleys: a rotational order does not move it
      across (an ideal drive in its plane; pulley run-out and belt non-uniformity are not modelled),
      so it is listed, not counted.

    ``tension_amp(span, order, rpm)`` and ``tension_mean(span, rpm)`` (N) read the run."""
    from ...mechanics.layout import compute_layout

    ends = moving_ends(model, compute_layout(model))
    m = model.belt.mass_per_length
    # belt speed per crank rpm (the flap points' ratio)
    per_rpm = (fl["belt_speed"][0] / fl["speed_rpm"][0]) if fl.get("speed_rpm") and fl["speed_rpm"][0] else 0.0
    out = []
    for x in crossings(fl, orders, speed_range):
        e_per = ends.get(x["span"])
        if e_per is not None:
            e = end_amp(e_per[1], x["order"], x["rpm"]) * e_per[0]
            out.append(dict(x, kind="direct", counted=True, end_motion=e, amplitude=e / (math.pi * zeta),
                            note=f"its end moves with {e_per[1]}"))
        else:
            out.append(dict(x, kind="none", counted=False, note="both ends on fixed pulleys"))
    for x in crossings(fl, orders, speed_range, factor=2.0):
        v = x["rpm"] * per_rpm
        T = tension_mean(x["span"], x["rpm"]) - m * v * v
        dT = tension_amp(x["span"], x["order"], x["rpm"])
        eps = dT / T if T > 0 else math.inf
        out.append(dict(x, kind="parametric", counted=bool(eps > 4 * zeta), modulation=eps, threshold=4 * zeta,
                        note=f"tension modulation {eps:.3f} against {4 * zeta:.3f}"))
    return sorted(out, key=lambda c: c["rpm"])
