"""Run-up results: a belt-drive run whose crank (the prescribed-speed pulley) sweeps a speed range,
read per engine-speed bin as a drive engineer reads a run-up on the test bench.

Per bin of crank mean speed (``output.runup_bin`` wide, rpm; default a twentieth of the range), a
run-down's bins apart from the run-up's (``sweep``: "up" or "down" per bin):
min / max / mean of every span tension, the tensioner arms' travel range, the slip of every
pulley against the crank (from the bin's mean speeds), the peak hub loads; and order tracking: the amplitude of
engine orders of the span tensions and hub loads, from the Fourier coefficient over the crank's
mean angle phi_m (the integral of the mean speed) within the bin,

    a_k = | 2 / N sum (x - mean x) exp(-i k phi_m) |,

over the whole engine cycles (two revolutions) in the bin, so that an order keeps its place as
the speed changes and the orders do not leak into one another (order tracking by angle, as bench
analysers do; the bins should hold several crank revolutions).
"""
from __future__ import annotations

import math

import numpy as np

from ...core.results import variable

RPM = 60 / (2 * math.pi)



#: the order cuts behind ``runup.order_peaks.<key>``: key -> (the Dataset's variable, its member dimension)
ORDER_VARIABLES = {"span_tension": ("runup_tension_order", "span"), "hub_load": ("runup_hub_load_order", "pulley"),
                   "arm_travel": ("runup_arm_travel_order", "arm")}

def crank_index(model):
    """The prescribed-speed pulley whose mean speed changes by more than 10 % (a run-up), or None."""
    for j, p in enumerate(model.pulleys):
        if p.speed_time is not None:
            w = np.abs([r[1] for r in p.speed_time])
            if len(w) >= 2 and w.max() > 0 and (w.max() - w.min()) > 0.1 * w.max():
                return j
    return None


#: the longest period (crank revolutions) a periodic run-up solves for
MAX_PERIOD_REVS = 8


def excitation_orders(model, j, rho) -> list[float]:
    """The drive's excitation in orders of the crank (pulley j): its speed orders and each
    accessory's own harmonics at its nominal speed ratio |rho_j / rho_k|."""
    orders = [o.order for o in model.pulleys[j].speed_orders]
    for k, p in enumerate(model.pulleys):
        orders += [hm.order * abs(rho[j] / rho[k]) for hm in p.load_harmonics]
    return orders


def period_revolutions(model, j, rho, strict: bool = False):
    """Crank revolutions in one period of the drive's excitation (excitation_orders: 2 with half
    orders; a 7th order on a pulley turning 1.25 times the crank: 4 revolutions), at most
    MAX_PERIOD_REVS; an excitation that does not repeat within them gives MAX_PERIOD_REVS (a window
    to read a drift over), or None with ``strict`` (a periodic solution does not exist)."""
    orders = excitation_orders(model, j, rho)
    for n in range(1, MAX_PERIOD_REVS + 1):
        if all(abs(n * o - round(n * o)) < 0.02 for o in orders):
            return n
    return None if strict else MAX_PERIOD_REVS


def mean_speed(p, t):
    xs = np.array([r[0] for r in p.speed_time])
    ys = np.array([r[1] for r in p.speed_time])
    return np.interp(t, xs, ys)


def mean_angle(p, t):
    """Integral of the piecewise-linear mean speed from 0 to each t (exact)."""
    xs = np.array([r[0] for r in p.speed_time])
    grid = np.unique(np.concatenate([[0.0], xs[(xs > 0) & (xs < t[-1])], t]))
    w = mean_speed(p, grid)
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(grid))])
    return np.interp(t, grid, cum)


def orders_of(p):
    return sorted({1.0, 2.0, 3.0, 4.0} | {float(o.order) for o in p.speed_orders})


def add_runup(ds, model, bin_width=None, up_only=False) -> dict:
    """Adds the per-bin variables to ``ds`` (dim ``speed_bin``, coordinate its centre in rpm) and
    returns the summary entry ``runup`` (lists per bin), or {} when the run is no run-up.
    ``up_only``: every sample belongs to the up sweep (a periodic run-up's held speeds)."""
    if crank_index(model) is None or ds.sizes.get("time", 0) < 4:
        return {}
    r = ds["pulley_rolling_radius" if "pulley_rolling_radius" in ds else "pulley_radius"].values
    travel = (ds["arm_travel"].values, ds["arm"].values.tolist()) if "arm_travel" in ds else None
    tables = runup_tables(model, ds["time"].values, ds["span_tension"].values, ds["hub_load"].values,
                          ds["speed"].values, r, ds["span"].values.tolist(), ds["pulley"].values.tolist(), travel,
                          bin_width, up_only,
                          gross=ds["gross_slip_share"].values if "gross_slip_share" in ds else None)
    if tables is None:
        return {}
    out, variables, coords = tables
    ds.attrs["runup_crank"] = out["crank"]
    # one update: each assignment aligns the whole dataset again (2 ms apiece)
    ds.coords.update(coords)
    ds.update(variables)
    from ...mechanics.layout import compute_layout
    from .span_stability import runup as span_runup

    stab = span_runup(model, compute_layout(model), ds, out, out["crank"])
    return {"runup": out, **({"span_stability": stab} if stab else {})}


def runup_tables(model, t, ten, hub, speed, r, spans, pulleys, travel=None, bin_width=None, up_only=False,
                 orders=True, gross=None):
    """The run-up tables from the samples' arrays (time; span tension and hub load, pulley speed
    (time x span / pulley); the rolling radii; ``travel``: (arm travel (time x arm), arm names) or
    None): (the summary entry ``runup``, its Dataset variables, their coordinates), or None when
    the run is no run-up. ``orders=False`` leaves out the order tracking (its amplitudes and
    peaks), which the rest does not use. ``gross`` (time x pulley, the rotational model's share of
    each sample's interval a wrap slid as a whole): its mean per bin, ``gross_slip_share``."""
    j = crank_index(model)
    if j is None or len(t) < 4:
        return None
    p = model.pulleys[j]
    rpm = np.abs(mean_speed(p, t)) * RPM
    # a crank spun up from rest: the spin-up (to the table's second row) is no part of the run-up
    knots = p.speed_time
    t0 = knots[1][0] if abs(knots[0][1]) < 0.05 * max(abs(r[1]) for r in knots) else -np.inf
    live = t >= t0
    if live.sum() < 4:
        return None
    lo, hi = float(rpm[live].min()), float(rpm[live].max())
    width = bin_width * RPM if bin_width else (hi - lo) / 20
    if not width > 0:
        return None
    edges = np.arange(math.floor(lo / width) * width, hi + width, width)
    if len(edges) < 2:      # a bin wider than float resolves beside the speeds: one bin
        edges = np.array([math.floor(lo / width) * width, math.floor(lo / width) * width + width])
    nb = len(edges) - 1
    # a run-down is read apart from the run-up (the drive's response differs with the sweep's
    # direction: the clutch overruns, the tensioner's friction turns): its bins follow the up
    # sweep's, numbered nb + b, in falling speed
    # (against a floor: on a held speed np.gradient's weights leave round-off of either sign, which
    # read as a run-down made a spurious bin of a few idle samples)
    w_abs = np.abs(mean_speed(p, t))
    floor = 1e-9 * float(w_abs.max()) / max(float(t[-1] - t[0]), 1e-12) if len(t) > 1 else 0.0
    down = np.gradient(w_abs, t) < -floor if len(t) > 1 and not up_only else np.zeros(len(t), bool)
    which = np.where(live, np.clip(np.digitize(rpm, edges) - 1, 0, nb - 1) + np.where(down, nb, 0), -1)
    used = [b for b in range(nb) if np.sum(which == b) >= 4]
    used += [b for b in range(2 * nb - 1, nb - 1, -1) if np.sum(which == b) >= 4]
    if not used:
        return None
    centre = np.array([0.5 * (edges[b % nb] + edges[b % nb + 1]) for b in used])
    sweep = ["down" if b >= nb else "up" for b in used]
    order_list = orders_of(p)
    # the chain's rolling radius (older results: the contact radius): the polygon effect is no slip
    vd = np.abs(speed[:, j] * r[j])
    v = np.abs(speed * r)

    def per_bin(x, fn):
        return np.array([fn(x[which == b], axis=0) for b in used])

    basis = []

    def order_amp(x):
        if not basis:           # each bin's samples and order phasors, once for every table
            phi = mean_angle(p, t)
            for b in used:
                idx = np.nonzero(which == b)[0]
                # whole engine cycles (two revolutions: half orders too) or revolutions only, so
                # that the orders stay orthogonal and do not leak into one another
                span = abs(phi[idx[-1]] - phi[idx[0]])
                cycle = 4 * math.pi if span >= 4 * math.pi else 2 * math.pi
                if span >= cycle:
                    idx = idx[np.abs(phi[idx] - phi[idx[0]]) < cycle * math.floor(span / cycle)]
                basis.append((idx, np.exp(-1j * np.outer(order_list, phi[idx])) * (2 / len(idx))))
        out = np.zeros((len(used), len(order_list), x.shape[1]))
        for a, (idx, E) in enumerate(basis):
            out[a] = np.abs(E @ (x[idx] - x[idx].mean(axis=0)))
        return out

    dims = ("speed_bin",)
    var = {"crank_rpm": variable(rpm, ("time",), "rpm", "crank mean speed (prescribed, without the orders)")}
    coords = {"speed_bin": variable(centre, dims, "rpm", "crank mean speed, bin centre"), "sweep": ("speed_bin", sweep),
              "order": order_list}
    tmin, tmax = per_bin(ten, np.min), per_bin(ten, np.max)
    var["runup_tension_min"] = variable(tmin, dims + ("span",), "N", "span tension, bin minimum")
    var["runup_tension_max"] = variable(tmax, dims + ("span",), "N", "span tension, bin maximum")
    var["runup_tension_mean"] = variable(per_bin(ten, np.mean), dims + ("span",), "N", "span tension, bin mean")
    hmax = per_bin(hub, np.max)
    var["runup_hub_load_max"] = variable(hmax, dims + ("pulley",), "N", "hub load, bin maximum")
    # slip as the bin's mean speed ratio: the instantaneous ratio also swings with the torsional
    # vibration the engine orders excite, which is no slip
    vd_bin = per_bin(vd, np.mean)
    slip = 1 - per_bin(v, np.mean) / np.where(vd_bin > 0, vd_bin, np.nan)[:, None]
    var["runup_slip"] = variable(slip, dims + ("pulley",), "1",
                                 "slip against the crank over the bin, 1 - mean |w r| / mean |w_c r_c| (r: the chain's rolling radius)")
    if orders:
        var["runup_tension_order"] = variable(order_amp(ten), dims + ("order", "span"), "N", "span tension, amplitude of engine order")
        var["runup_hub_load_order"] = variable(order_amp(hub), dims + ("order", "pulley"), "N", "hub load, amplitude of engine order")
    out = {"crank": p.name, "speed_rpm": centre.tolist(), "sweep": sweep, "orders": order_list,
           "span_tension_min": {s: tmin[:, q].tolist() for q, s in enumerate(spans)},
           "span_tension_max": {s: tmax[:, q].tolist() for q, s in enumerate(spans)},
           "slip": {n: slip[:, q].tolist() for q, n in enumerate(pulleys) if q != j},
           "hub_load_max": {n: hmax[:, q].tolist() for q, n in enumerate(pulleys)}}
    if gross is not None:
        g = per_bin(gross, np.mean)
        var["runup_gross_slip_share"] = variable(g, dims + ("pulley",), "1",
                                                 "share of the bin a wrap slid as a whole (tension ratio at e^(mu theta))")
        out["gross_slip_share"] = {n: g[:, q].tolist() for q, n in enumerate(pulleys)}
    if travel is not None:
        q, arms = travel
        qmin, qmax = per_bin(q, np.min), per_bin(q, np.max)
        var["runup_arm_travel_min"] = variable(qmin, dims + ("arm",), "rad", "arm travel, bin minimum")
        var["runup_arm_travel_max"] = variable(qmax, dims + ("arm",), "rad", "arm travel, bin maximum")
        out["arm_travel_range"] = {a: (qmax[:, k] - qmin[:, k]).tolist() for k, a in enumerate(arms)}
        if orders:
            var["runup_arm_travel_order"] = variable(order_amp(q), dims + ("order", "arm"), "rad", "arm travel, amplitude of engine order")
    if not orders:
        return out, var, coords
    # order cuts of every span, hub load and arm: each order's largest amplitude over the run and
    # the crank speed where it peaks (the whole cuts: runup_*_order in results.nc, runup.png)
    peaks = {}
    members = {"span": spans, "pulley": pulleys, "arm": travel[1] if travel is not None else []}
    for key, (name, dim) in ORDER_VARIABLES.items():
        if name not in var:
            continue
        names = members[dim]
        a = var[name].values
        peaks[key] = {str(nm): {f"{k:g}": {"amplitude": float(a[:, o, q].max()),
                                           "rpm": float(centre[int(np.argmax(a[:, o, q]))])}
                                for o, k in enumerate(order_list)}
                      for q, nm in enumerate(names)}
    out["order_peaks"] = peaks
    return out, var, coords


def table_lines(summary) -> list[str]:
    """The per-bin table the CLI and the closing notes print."""
    ru = summary.get("runup")
    if not ru:
        return []
    spans = list(ru["span_tension_max"])
    head = f"{'rpm':>6s} " + " ".join(f"{s[:18]:>18s}" for s in spans) + "  slip %  (largest, pulley)"
    lines = [f"run-up of {ru['crank']}: span tension min-max (N) per crank-speed bin", head]
    for b, rpm in enumerate(ru["speed_rpm"]):
        cells = " ".join(f"{ru['span_tension_min'][s][b]:8.0f}-{ru['span_tension_max'][s][b]:<9.0f}" for s in spans)
        worst = max(ru["slip"], key=lambda n: abs(ru["slip"][n][b])) if ru["slip"] else ""
        lines.append(f"{rpm:6.0f} {cells}  {100 * ru['slip'][worst][b]:6.2f}  ({worst})" if worst else f"{rpm:6.0f} {cells}")
    return lines
