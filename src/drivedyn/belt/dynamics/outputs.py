"""What both dynamic models write from a run: the Dataset variables of clutches and tensioners, the
summary (pulleys, spans, belt, clutches, tensioners over the steady window) and its units. A model's
system is read through the segment model's interface (layout, pulleys, arms, rest state, rolling
radius); the rotational model passes a view of its own (rotational/simulate.py)."""
from __future__ import annotations

import math

import numpy as np

from ...core.results import variable


def clutch_variables(ds, model, sysm, rec, ns, interval):
    """Rotor speed behind each clutch and the clutch torque on the rotor in its drive sense (interval
    mean, exact: I_r d omega_r / dt minus the accessory loads on the rotor)."""
    P = sysm.pulleys
    sel = [j for j in range(P.nk) if P.cl_kind[j] > 0]
    if not sel:
        return
    ds.coords["clutch"] = [model.pulleys[j].name for j in sel]
    omr = rec.omr[:ns, sel]
    prev = np.vstack([np.zeros((1, len(sel))), omr[:-1]])
    tc = (P.cl_ir[sel] * (omr - prev) / interval - rec.tq_ext[:ns, sel]) * P.cl_s[sel]
    ds.update({"rotor_speed": variable(omr, ("time", "clutch"), "rad/s", "accessory rotor speed behind the clutch"),
               "clutch_torque": variable(tc, ("time", "clutch"), "N m", "torque the clutch passes to the rotor, in its "
                                         "drive sense (interval mean; >= 0 for an overrunning clutch)")})


def tensioner_variables(ds, model, sysm, rec, ns):
    """Arm angle and speed (pivoted tensioners), slide position and speed (linear ones), over time."""
    A = sysm.arms
    for kind, dim, names in ((0, "arm", "arm"), (1, "slider", "slider")):
        sel = [a for a in range(A.na) if A.kind[a] == kind]
        if not sel:
            continue
        ds.coords[dim] = [model.pulleys[A.pulley[a]].name for a in sel]
        q, qd = rec.q[:ns, sel], rec.qd[:ns, sel]
        if kind == 0:      # (one update: each assignment aligns the whole dataset again)
            psi = A.psi0[sel] + A.sgn[sel] * q
            ds.update({
                "arm_angle": variable(psi, ("time", dim), "rad", "tensioner arm angle about its pivot (counter-clockwise from x)"),
                "arm_travel": variable(q, ("time", dim), "rad", "arm travel from the drawn position, into the belt positive"),
                "arm_speed": variable(qd, ("time", dim), "rad/s", "arm travel rate")})
        else:
            ds.update({
                "slider_travel": variable(q, ("time", dim), "m", "slider travel from the drawn position, into the belt positive"),
                "slider_speed": variable(qd, ("time", dim), "m/s", "slider travel rate")})


#: units of the summary keys (results.unit_map: first matching pattern wins; "1" for ratios)
UNITS = {
    "steady_window": "s",
    "pulleys.*.speed_mean": "rad/s", "pulleys.*.hub_load": "N", "pulleys.*.hub_force": "N",
    "pulleys.*.torque_mean": "N*m", "pulleys.*.power_mean": "W",
    "pulleys.*.slip": "1", "pulleys.*.creep": "1", "pulleys.*.creep_bound": "1", "pulleys.*.sliding": "1",
    "pulleys.*.sliding_share": "1", "pulleys.*.contact_share": "1", "pulleys.*.peak_normal_ratio": "1",
    "pulleys.*.chordal_error": "1", "pulleys.*.slip_margin": "1",
    "spans.*.tension_*": "N", "spans.*.speed_mean": "m/s",
    "power.efficiency": "1", "power.energy_residual_*": "1", "power.*": "W",
    "belt.pretension": "N", "belt.segment_length": "m", "belt.path_length": "m", "belt.displacement_limit": "m",
    "discretisation.segment_length": "m", "discretisation.chordal_speed_error": "1",
    "discretisation.segments*": "", "discretisation.unresolved_wraps.*": "deg",
    "discretisation.estimate.coarse_segments": "", "discretisation.estimate.auto_segments": "",
    "discretisation.estimate.method": "", "discretisation.estimate.power_loss_method": "",
    "discretisation.estimate.unavailable": "", "discretisation.estimate.power_loss_note": "",
    "discretisation.estimate.runup_note": "",
    "discretisation.estimate.coarse_status": "", "discretisation.estimate.power_loss.*": "W",
    "discretisation.estimate.*": "1", "discretisation.grid_damping.bending_damper": "N*m*s/rad",
    "discretisation.grid_damping.damping_ratio": "1", "discretisation.*": "",
    "steady.*": "1", "at_rest.speed_max.*": "rad/s", "at_rest.residual_force": "1",
    "solver.last_step": "s", "solver.step": "s", "solver.stability_limit": "s", "solver.wall_time": "s",
    "solver.simulated_time": "s", "solver.real_time_factor": "1",
    "tensioners.*.arm_angle_*": "rad", "tensioners.*.travel_*": "rad", "tensioners.*.slide_*": "m",
    "tensioners.*.hub_load*": "N", "tensioners.*.rest_*_torque": "N*m", "tensioners.*.rest_*_force": "N",
    "tensioners.*.rest_arm_angle": "rad", "tensioners.*.rest_travel": "rad", "tensioners.*.rest_slide": "m",
    "tensioners.*.rest_tension": "N",
    "clutches.*.torque_mean": "N*m", "clutches.*.rotor_speed_mean": "rad/s", "clutches.*.overrun_share": "1",
    "runup.order_peaks.arm_travel.*.amplitude": "rad", "runup.order_peaks.*.amplitude": "N",
    "runup.order_peaks.*.rpm": "rpm", "runup.speed_rpm": "rpm", "runup.sweep": "", "runup.span_tension_*": "N", "runup.hub_load_max.*": "N", "runup.slip.*": "1", "runup.gross_slip_share.*": "1",
    "runup.arm_travel_range.*": "rad", "runup.orders": "1", "runup.crank": "",
    "span_stability.spans.*.tension_mean": "N", "span_stability.spans.*.effective_tension": "N",
    "span_stability.spans.*.speed": "m/s", "span_stability.spans.*.length": "m",
    "span_stability.spans.*.frequency_1": "Hz", "span_stability.spans.*.nearest.frequency": "Hz",
    "span_stability.spans.*.nearest.tongue_centre": "Hz", "span_stability.spans.*.nearest.band": "Hz",
    "span_stability.spans.*.rpm": "rpm", "span_stability.spans.*.inside_rpm": "rpm",
    "span_stability.sampled_to": "Hz", "span_stability.*": "",
}
#: the rotational model's own keys besides :data:`UNITS`
ROTATIONAL_UNITS = {"belt.unstretched_length": "m", "discretisation.step": "s", "discretisation.fastest_mode_bound_hz": "Hz"}


def friction_law(model) -> dict:
    """What the summary says of the friction law (the answers depend on it: docs/belt-drive.md,
    Delta_max): its name and, for the elastic-plastic law, Delta_max."""
    f = model.friction
    if f.law == "elastic-plastic":
        return {"friction_law": f.law, "displacement_limit": float(f.displacement_limit)}
    return {"friction_law": f.law}


def run_summary(model, sysm, ds, solver, sel, window, disc) -> dict:
    t = ds["time"].values
    w0, w1 = window
    mean = lambda v: ds[v].values[sel].mean(axis=0) if np.any(sel) else np.full(ds[v].shape[1:], np.nan)
    names = list(sysm.layout.names)
    speed, pin = mean("speed"), mean("power_in")
    hx, hy, tq = mean("hub_force_x"), mean("hub_force_y"), mean("torque_applied")
    # a pulley held at a prescribed speed: the torque that holds it there against the belt (the
    # drive's reaction torque, minus the belt's torque on it), so that torque x speed is its power
    tqb = mean("torque_belt")
    tq = np.where(sysm.pulleys.mode == 1, -tqb, tq)
    # slip against the chain's own rolling kinematics: the polygon effect of the segments, a speed
    # ratio error of about l^2 / (12 r^2) between pulleys of different radii, is no slip
    radius = sysm.rolling_radius
    d = int(np.nanargmax(pin)) if np.any(np.isfinite(pin)) else 0
    vd = abs(speed[d] * radius[d])
    pulleys = {}
    for j, nm in enumerate(names):
        pulleys[nm] = {
            "speed_mean": float(speed[j]),
            "slip": float(1 - abs(speed[j] * radius[j]) / vd) if vd > 0 else float("nan"),
            "hub_load": float(math.hypot(hx[j], hy[j])),
            "hub_force": [float(hx[j]), float(hy[j])],
            "torque_mean": float(tq[j]),
            "power_mean": float(pin[j]),
        }
    ten, vsp = mean("span_tension"), mean("span_speed")
    tsel = ds["span_tension"].values[sel] if np.any(sel) else np.zeros((0, len(ten)))
    spans = {sp: {"tension_mean": float(ten[q]),
                  "tension_min": float(tsel[:, q].min()) if len(tsel) else float("nan"),
                  "tension_max": float(tsel[:, q].max()) if len(tsel) else float("nan"),
                  "speed_mean": float(vsp[q])}
             for q, sp in enumerate(ds["span"].values.tolist())}
    # creep on each pulley: 1 - |belt speed leaving| / |belt speed arriving| (span k leaves pulley k)
    forward = float(np.nansum(vsp)) >= 0
    for j, nm in enumerate(names):
        v_arr, v_out = (vsp[j - 1], vsp[j]) if forward else (vsp[j], vsp[j - 1])
        pulleys[nm]["creep"] = float(1 - abs(v_out) / abs(v_arr)) if abs(v_arr) > 1e-9 else float("nan")
    p_in = float(np.sum(pin[pin > 0]))
    p_out = float(-np.sum(pin[pin < 0])) + 0.0     # + 0.0: no "-0" when nothing is taken out
    # mean dissipation rates over the window from the cumulative energies
    D = ds["dissipated"].values
    tw = t[sel]
    if len(tw) >= 2:
        idx = np.nonzero(sel)[0]
        rates = (D[idx[-1]] - D[idx[0]]) / (tw[-1] - tw[0])
        resid = ds["energy_residual"].values
        resid_rate = (resid[idx[-1]] - resid[idx[0]]) / (tw[-1] - tw[0])
    else:
        rates, resid_rate = np.full(D.shape[1], np.nan), float("nan")
    mech = ds["mechanism"].values.tolist()
    # the energy stored per second over the window (kinetic and elastic): a run-up stores, a
    # run-down gives back; the transmission efficiency leaves it out, output over output + losses
    E = ds["energy_change"].values
    stored = float((E[idx[-1]] - E[idx[0]]) / (tw[-1] - tw[0])) if len(tw) >= 2 else float("nan")
    lost = float(np.sum(rates))
    return {
        "driver": names[d],
        "steady_window": [float(w0), float(w1)],
        "pulleys": pulleys,
        "spans": spans,
        "power": {
            "input": p_in, "output": p_out,
            "efficiency": p_out / (p_out + lost) if p_out + lost > 0 else float("nan"),
            "stored": stored,
            "losses": {m: float(r) for m, r in zip(mech, rates)},
            "unaccounted": float(resid_rate),
            "energy_residual_relative": float("nan"),     # dynamics/checks.energy_balance: against the work in
        },
        "belt": {"pretension": sysm.init.tension, "segment_length": sysm.init.seg_length,
                 "segments": sysm.n, "path_length": sysm.layout.length, **friction_law(model)},
        "discretisation": disc,
        **tensioner_summary(ds, sysm, sel),
        **clutch_summary(ds, sel),
        **span_stability_summary(model, sysm, ds, sel, abs(float(speed[d])) / (2 * math.pi)),
        "solver": solver,
    }


def span_stability_summary(model, sysm, ds, sel, f_driver) -> dict:
    """``span_stability`` of a steady window (dynamics/span_stability.py); a run-up's, with its bins
    (runup.add_runup), takes its place (a crank held at one speed has no bins: its window is read)."""
    from .span_stability import steady

    out = steady(model, sysm.layout, ds, sel, f_driver, int(getattr(sysm, "n", 0) or 0))
    return {"span_stability": out} if out else {}


def clutch_summary(ds, sel) -> dict:
    """Per clutch over the window: mean torque passed, rotor speed, and the share of the time the
    rotor overruns (the clutch passes less than 1 % of its mean torque)."""
    if "clutch" not in ds.coords or not np.any(sel):
        return {}
    out = {}
    for name in ds["clutch"].values.tolist():
        tc = ds["clutch_torque"].sel(clutch=name).values[sel]
        mean = float(np.mean(tc))
        out[name] = {"torque_mean": mean, "rotor_speed_mean": float(np.mean(ds["rotor_speed"].sel(clutch=name).values[sel])),
                     "overrun_share": float(np.mean(tc < 0.01 * abs(mean)))}
    return {"clutches": out}


def tensioner_summary(ds, sysm, sel) -> dict:
    """Per tensioner: the equilibrium at rest, and over the window the arm angle or slide travel
    (mean / min / max) and the hub load (mean, max)."""
    A, rest = sysm.arms, sysm.rest
    if not A.na:
        return {}
    out = {}
    hub = ds["hub_load"].values
    for a in range(A.na):
        j = int(A.pulley[a])
        name = sysm.model.pulleys[j].name
        h = hub[sel, j] if np.any(sel) else np.full(1, np.nan)
        e = {"hub_load": float(np.mean(h)), "hub_load_max": float(np.max(h))}
        if A.kind[a] == 0:
            psi = ds["arm_angle"].sel(arm=name).values[sel] if np.any(sel) else np.full(1, np.nan)
            q = ds["arm_travel"].sel(arm=name).values[sel] if np.any(sel) else np.full(1, np.nan)
            e.update(arm_angle_mean=float(np.mean(psi)), arm_angle_min=float(np.min(psi)), arm_angle_max=float(np.max(psi)),
                     travel_mean=float(np.mean(q)), travel_min=float(np.min(q)), travel_max=float(np.max(q)),
                     rest_arm_angle=float(rest.angle[a]), rest_travel=float(rest.travel[a]),
                     rest_spring_torque=float(rest.spring[a]))
        else:
            q = ds["slider_travel"].sel(slider=name).values[sel] if np.any(sel) else np.full(1, np.nan)
            e.update(slide_mean=float(np.mean(q)), slide_min=float(np.min(q)), slide_max=float(np.max(q)),
                     rest_slide=float(rest.travel[a]), rest_spring_force=float(rest.spring[a]))
        e["rest_tension"] = float(rest.tension)
        out[name] = e
    return {"tensioners": out}
