"""Span stability from the run (seed 002 on seed 000's run): each span's mean tension and the
largest components of its tension fluctuation, placed on the span's parametric-resonance tongues
(drivedyn.mechanics.span.tongues).

Per span, the first transverse frequency f1 is the moving beam's at the run's mean tension T and belt
speed V (mechanics.span.frequencies.moving_beam_spectrum, as the flap table: steady/flap.py), and a
fluctuation component dT at f_e has the depth e = dT / N with N = T + pi^2 EI / L^2 - m V^2
(mechanics.span.quantities.effective_tension; the run's tension holds m V^2). Each component is judged
alone against the principal and the next tongue (f_e ~ 2 f1 and f1) with the damping ratio
``criteria.flap_damping_ratio``: components at incommensurate frequencies make no periodic Hill
equation, and the largest is the one that counts.

The components of a steady window come from its spectrum: the tension less its mean and linear trend,
Hann-windowed; the largest local peaks, their frequencies refined by a parabola through the log
magnitudes of the three bins at each peak (exact for a Gaussian; for the Hann window within 0.016 of
a bin, tests/belt/test_span_stability.py: Gade & Herlufsen, Bruel & Kjaer Technical Review 3, 1987),
then all amplitudes at once by least squares on the unwindowed samples (mean, trend, a cosine and a
sine per peak: within 5e-4 of the amplitude for one sinusoid). A run-up's come
from its order tracking (dynamics/runup.py): per crank-speed bin, the order amplitudes at k n / 60 Hz.
"""
from __future__ import annotations

import math

import numpy as np

from ...mechanics.span.frequencies import moving_beam_spectrum
from ...mechanics.span.quantities import SpanProperties, effective_tension
from ...mechanics.span.tongues import nearest, nearest_tongue, place, screen

#: fluctuation components placed per span
COMPONENTS = 3
#: a peak below this share of the largest is no component (the window's leakage and round-off)
PEAK_FLOOR = 1e-3


def largest_components(t, x, count=COMPONENTS):
    """(mean, [(frequency Hz, amplitude), ...]) of a uniformly sampled series: its ``count`` largest
    spectral peaks, largest first (see the module's docstring)."""
    t, x = np.asarray(t, float), np.asarray(x, float)
    n = len(x)
    mean = float(np.mean(x)) if n else float("nan")
    if n < 8:
        return mean, []
    dt = (t[-1] - t[0]) / (n - 1)
    tc = t - t.mean()
    base = np.column_stack([np.ones(n), tc])
    y = x - base @ np.linalg.lstsq(base, x, rcond=None)[0]
    mag = np.abs(np.fft.rfft(y * np.hanning(n)))
    if not mag.max() > 0:
        return mean, []
    # local maxima past the two lowest bins (what the trend leaves), largest first
    k = np.arange(2, len(mag) - 1)
    k = k[(mag[k] > mag[k - 1]) & (mag[k] >= mag[k + 1]) & (mag[k] > PEAK_FLOOR * mag[2:].max())]
    k = k[np.argsort(mag[k])[::-1]]
    picked = []
    for i in k:
        if all(abs(int(i) - j) > 2 for j in picked):     # a peak's own sidelobes are no second peak
            picked.append(int(i))
        if len(picked) == count:
            break
    if not picked:
        return mean, []
    freqs = []
    for i in picked:
        a, b, c = np.log(mag[i - 1:i + 2] + 1e-300)
        d = 0.5 * (a - c) / (a - 2 * b + c) if (a - 2 * b + c) < 0 else 0.0
        freqs.append((i + d) / (n * dt))
    w = 2 * math.pi * np.asarray(freqs)
    cols = [np.ones(n), tc] + [f(wk * tc) for wk in w for f in (np.cos, np.sin)]
    coef = np.linalg.lstsq(np.column_stack(cols), x, rcond=None)[0]
    amps = np.hypot(coef[2::2], coef[3::2])
    out = sorted(zip(freqs, amps), key=lambda p: -p[1])
    return mean, [(float(f), float(a)) for f, a in out]


def span_entry(sp: SpanProperties, T: float, V: float, components, zeta: float, f_driver: float,
               passing: float = 0.0, tol: float = 0.0, f1: float | None = None) -> dict:
    """The summary entry of one span: mean tension, f1, each component's depth and the tongue it is
    nearest, the nearest of all, and whether any is inside a tongue. A component within ``tol`` Hz
    (or 2 %: the segments' length varies with the tension along the belt) of a multiple of ``passing`` (the segments' passing frequency, Hz) is the segment
    model's polygon effect: listed, not placed. ``f1``: the span's first frequency if already known
    (moving_beam_spectrum at T and V)."""
    f1 = f1 if f1 is not None else float(moving_beam_spectrum(np.asarray(T, float), sp.mass_per_length, sp.length, sp.bending_stiffness,
                                    np.asarray(V, float), 1)[..., 0])
    N = float(effective_tension(T, V, sp))
    e = {"tension_mean": float(T), "speed": float(V), "effective_tension": N, "frequency_1": f1,
         "length": sp.length, "components": []}
    if not (math.isfinite(f1) and f1 > 0 and N > 0):
        e.update(inside=False, tongue_distance=None, note="at or above the critical speed: no transverse frequency")
        return e
    places = []
    for fe, amp in components:
        depth = amp / N
        k = round(fe / passing) if passing > 0 else 0
        artefact = k >= 1 and abs(fe - k * passing) <= max(tol, 0.02 * k * passing)
        best = (fe, place(f1, fe, depth, zeta)) if fe > 0 and not artefact else None
        c = {"frequency": float(fe), "order": float(fe / f_driver) if f_driver > 0 else None,
             "amplitude": float(amp), "depth": depth}
        if artefact:
            c["note"] = "segment passing" + (f" x{k}" if k > 1 else "") + " (discretisation): not placed"
        if best is not None:
            p = best[1]
            places.append(best)
            c.update(tongue=p.tongue, tongue_centre=p.centre, band=list(p.band) if p.band else None,
                     inside=p.inside, distance=p.distance, multiplier=p.multiplier)
        e["components"].append(c)
    best = nearest(places)
    e["inside"] = any(p.inside for _, p in places)
    e["tongue_distance"] = None if best is None else best[1].distance
    if best is not None:
        e["nearest"] = {"frequency": best[0], "tongue": best[1].tongue, "tongue_centre": best[1].centre,
                        "open": best[1].open, "band": list(best[1].band) if best[1].band else None}
    return e


def reach(f1, fe, depth) -> float:
    """The share of the nearest tongue's centre between f_e and the widest the tongue can be at this
    depth (tongues.screen): below 0 it may be inside, and needs the Floquet pass."""
    n = nearest_tongue(f1, fe)
    return abs(fe * n / (2.0 * f1) - 1.0) - screen(depth)


def _span_properties(model, lay):
    b = model.belt
    zeta = float(model.criteria.flap_damping_ratio)
    return {sp.name: SpanProperties(sp.length, b.mass_per_length, b.bending_stiffness, zeta) for sp in lay.spans}


def steady(model, lay, ds, sel, f_driver, segments: int = 0) -> dict:
    """``summary.span_stability`` of a steady window: {span: entry} (span_entry); ``segments``: the
    segment model's count (0: the rotational model), whose passing frequency is no fluctuation."""
    if not np.any(sel) or "span_tension" not in ds:
        return {}
    zeta = float(model.criteria.flap_damping_ratio)
    props = _span_properties(model, lay)
    t = ds["time"].values[sel]
    ten, vel = ds["span_tension"].values[sel], ds["span_speed"].values[sel]
    out = {}
    for q, name in enumerate(ds["span"].values.tolist()):
        if name not in props:
            continue
        mean, comps = largest_components(t, ten[:, q])
        V = abs(float(np.mean(vel[:, q])))
        passing = V * segments / lay.length if segments else 0.0
        tol = 1.0 / (t[-1] - t[0]) if len(t) > 1 else 0.0        # a bin of the window's spectrum
        out[name] = span_entry(props[name], mean, V, comps, zeta, f_driver, passing, tol)
    if out:
        out["_sampled_to"] = 0.5 / float(np.median(np.diff(t))) if len(t) > 1 else float("nan")
    return _finish(out)


def runup(model, lay, ds, out_runup, crank) -> dict:
    """``summary.span_stability`` of a run-up: per span the bin whose tracked order is nearest a
    tongue (inside first), with the crank speed, and the bins inside a tongue."""
    need = ("runup_tension_order", "runup_tension_mean")
    if not all(v in ds for v in need) or "speed_bin" not in ds.coords:
        return {}
    zeta = float(model.criteria.flap_damping_ratio)
    props = _span_properties(model, lay)
    rpm = np.asarray(ds["speed_bin"].values, float)
    orders = [float(k) for k in np.atleast_1d(ds["order"].values)]
    names = ds["pulley"].values.tolist()
    r = float(ds["pulley_radius"].values[names.index(crank)])
    out = {}
    for name in ds["span"].values.tolist():
        if name not in props:
            continue
        amp = ds["runup_tension_order"].sel(span=name).values           # (bin, order)
        mean = ds["runup_tension_mean"].sel(span=name).values
        V = rpm / 60.0 * 2 * math.pi * r
        sp = props[name]
        f1 = moving_beam_spectrum(np.asarray(mean, float), sp.mass_per_length, sp.length, sp.bending_stiffness, V, 1)[:, 0]
        N = effective_tension(np.asarray(mean, float), V, sp)
        comps = [sorted(((k * n / 60.0, float(amp[b, o])) for o, k in enumerate(orders)), key=lambda c: -c[1])[:COMPONENTS]
                 for b, n in enumerate(rpm)]
        # the bins worth a Floquet pass: a component within reach of a tongue (tongues.screen), or
        # else the one nearest; the rest cannot be inside one
        key = np.full(len(rpm), np.inf)
        for b in range(len(rpm)):
            if math.isfinite(f1[b]) and f1[b] > 0 and N[b] > 0:
                key[b] = min((reach(f1[b], fe, a / N[b]) for fe, a in comps[b] if fe > 0), default=np.inf)
        # the Floquet pass on the components within reach; the bin nearest a tongue in full
        placed = {}
        for b in range(len(rpm)):
            if key[b] < 0:
                for fe, a in comps[b]:
                    if fe > 0 and reach(f1[b], fe, a / N[b]) < 0:
                        p = place(f1[b], fe, a / N[b], zeta, refine=False)
                        placed[b] = min(placed.get(b, (True, True, np.inf)), (not p.inside, not p.open, p.distance))
        b = min(placed, key=placed.get) if placed else int(np.argmin(key))
        e = span_entry(sp, float(mean[b]), float(V[b]), comps[b], zeta, rpm[b] / 60.0, f1=float(f1[b]))
        inside_rpm = [float(rpm[k]) for k, v in placed.items() if not v[0]]
        e = dict(e, rpm=float(rpm[b]))
        e["inside_rpm"] = inside_rpm
        out[name] = e
    return _finish(out)


def _finish(out: dict) -> dict:
    if not out:
        return {}
    sampled = out.pop("_sampled_to", None)
    inside = [n for n, e in out.items() if e.get("inside")]
    dist = [(not e["inside"], not e["nearest"]["open"], e["tongue_distance"], n) for n, e in out.items()
            if e.get("tongue_distance") is not None]
    best = min(dist) if dist else None
    res = {"spans": out, "inside": inside, "tongue_distance": best[2] if best else None,
           "nearest_span": best[3] if best else None}
    if sampled is not None:
        res["sampled_to"] = sampled
    return res
