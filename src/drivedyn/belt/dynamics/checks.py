"""Diagnostics both dynamic models run on their Result (segments/diagnose.py lists the codes): the
steady window's drift, the energy balance, the slip margin by creep theory at the run's loads, gross
slip over a run-up's bins. A model's system is read through the segment model's interface (layout,
pulleys, rest state, ``init.seg_length`` and ``init.tension``)."""
from __future__ import annotations

import math

import numpy as np

from ...core.errors import ModelError
from ...core.window import drift


#: drift of a window mean over the window, against its scale
DRIFT_LIMIT = 0.02


#: energy residual over the window against the work in
ENERGY_LIMIT = 0.01


#: in a run-up, slip beyond this against the crank over a speed bin is gross slip (creep stays < 1 %)
RUNUP_SLIP = 0.03


def runup_slip(result):
    ru = result.summary.get("runup")
    if not ru:
        return
    rpm = np.array(ru["speed_rpm"])
    for name, vals in ru["slip"].items():
        v = np.abs(np.array(vals))
        bad = v > RUNUP_SLIP
        if np.any(bad):
            result.diagnose("gross-slip", f"pulley {name} slips {100 * v.max():.1f} % against the crank at "
                            f"{rpm[bad].min():.0f}-{rpm[bad].max():.0f} rpm in the run-up",
                            f"runup.slip.{name}", float(v.max()), RUNUP_SLIP, "1")


def slip_margin(result, model, sysm, sel):
    """pulleys.<name>.slip_margin: the load multiplier at gross-slip onset by creep theory
    (steady/creep.py) for the run's mean loads in the window (inertia torques J dw/dt included, so that
    an accelerating drive counts what its belt transmits), from the run's own tension level: the belt
    creep theory counts is the one that carries the window's mean span tensions on the layout (the
    model's belt.length is the unstretched belt on pitch circles, not sunk into the grooves as creep
    theory counts it: on examples/fead-ag0868.toml its spans read 160 N slacker than the run's)."""
    from ..steady.creep import drive_of, length_of, steady_state

    if result.summary.get("runup"):
        # a run-up is judged bin by bin (slip_runup): one margin over the swept window says nothing
        return
    if model.belt.teeth is not None:
        # creep theory would take the grooved wraps for friction wraps: a synchronous belt's teeth carry
        # the load, judged by their jump margin (summary["teeth"]); its smooth idlers carry none
        return
    ds = result.ds
    t = ds["time"].values[sel]
    w = ds["speed"].values[sel]
    if len(t) < 3:
        return
    acc = np.polyfit(t - t[0], w, 1)[0]
    J = np.array([p.inertia for p in model.pulleys])
    loads = ds["torque_applied"].values[sel].mean(axis=0) - J * acc
    d = int(np.argmax(np.abs(w.mean(axis=0)) * np.abs(sysm.layout.rho)))
    speed = float(w.mean(axis=0)[d] * sysm.layout.rho[d])
    T = ds["span_tension"].values[sel].mean(axis=0) if "span_tension" in ds else None
    creep = drive_of(model, sysm.layout)
    c = model.belt.mass_per_length * speed ** 2
    if (T is not None and [str(x) for x in ds["span"].values] == list(creep.span_names)
            and np.all(np.isfinite(T)) and np.all(T > c)):
        L0 = length_of(creep, T, c, speed >= 0)
        model = model.model_copy(update={"belt": model.belt.model_copy(update={"length": L0, "pretension": None})})
    try:
        st = steady_state(model, sysm.layout, loads=loads, speed=speed)
    except ModelError:       # a slack belt: the run's own diagnostics say what happened
        return
    for name, p in st.pulleys.items():
        result.summary["pulleys"][name]["slip_margin"] = float(p.slip_margin) if np.isfinite(p.slip_margin) else float("nan")


def steady_drift(result, model, sysm, sel):
    ds, s = result.ds, result.summary
    t = ds["time"].values[sel]
    if len(t) < 3:
        return
    from ..dynamics.runup import crank_index, mean_speed, period_revolutions

    j = crank_index(model)
    period = None
    if j is not None:
        wm = np.abs(mean_speed(model.pulleys[j], t))
        if wm.max() - wm.min() > 0.02 * max(wm.max(), 1e-9):
            s["steady"] = {"skipped": "run-up: the crank's mean speed sweeps the window (see runup.*)"}
            return
        # the crank held: its orders and the accessories' harmonics repeat with the drive's
        # period (4 crank revolutions on examples/fead-runup.toml's drive, for the compressor's
        # 7th order at 1.25 times crank speed), over which the drift is read: fitted to the raw
        # signal, the part periods in a 0.2 s window at 3000 rpm tilted the line by 2.0 % of the
        # tight span's tension (window-not-steady), while the one-period means moved by 0.02 %
        if wm.mean() > 0:
            period = period_revolutions(model, j, [p.radius for p in model.pulleys]) * 2 * math.pi / wm.mean()
    init = sysm.init
    r = np.array([p.radius for p in model.pulleys])
    w = ds["speed"].values[sel]
    # speeds: against their mean, at least the speed that moves the belt by one segment per window
    floor = init.seg_length / (t[-1] - t[0]) / r
    d_speed = drift(t, w, np.maximum(np.abs(w.mean(axis=0)), floor), period)
    ten = ds["span_tension"].values[sel]
    # tensions: against the drive's tension level (the tight span's mean, at least the
    # pretension): a slack span's few newtons of slow swing do not make the drive unsteady
    d_ten = drift(t, ten, max(float(np.max(np.abs(ten.mean(axis=0)))), init.tension), period)
    names, spans = list(sysm.layout.names), [sp.name for sp in sysm.layout.spans]
    s["steady"] = {"speed_drift": {n: float(v) for n, v in zip(names, d_speed)},
                   "tension_drift": {n: float(v) for n, v in zip(spans, d_ten)}, "limit": DRIFT_LIMIT}
    k, q = int(np.nanargmax(d_speed)), int(np.nanargmax(d_ten))
    if d_speed[k] >= d_ten[q]:
        qty, val, what = f"steady.speed_drift.{names[k]}", d_speed[k], f"speed of pulley {names[k]}"
    else:
        qty, val, what = f"steady.tension_drift.{spans[q]}", d_ten[q], f"tension of span {spans[q]}"
    if val > DRIFT_LIMIT:
        result.diagnose("window-not-steady", f"the {what} drifts by {100 * val:.1f} % inside the steady window "
                        f"{t[0]:.3g}-{t[-1]:.3g} s: run longer or move output.steady_window", qty, val, DRIFT_LIMIT, "1")


def energy_balance(result, model, sel):
    ds, s = result.ds, result.summary
    idx = np.nonzero(sel)[0]
    R = ds["energy_residual"].values
    pin = ds["power_in"].values
    t = ds["time"].values
    dt = np.diff(np.concatenate([[0.0], t]))
    work_pos = np.cumsum(np.clip(pin, 0, None).sum(axis=1) * dt)     # work in (J), positive flows only
    D = ds["dissipated"].values.sum(axis=1)
    # whole run: residual against the energy that flowed (work in, or what the drive dissipated
    # when nothing drives it); undefined (None) when nothing flowed at all
    # flows below a billionth of the belt's stored elastic energy T0^2 L / (2 EA) are round-off
    # of that energy (a drive at rest): nothing flowed
    b = model.belt
    T0 = result.summary["belt"]["pretension"]
    stored = T0 ** 2 * result.summary["belt"]["path_length"] / (2 * b.axial_stiffness)
    scale = max(float(work_pos[-1]), float(D[-1]))
    scale = scale if scale > 1e-9 * stored else 0.0
    s["power"]["energy_residual_relative"] = float(abs(R[-1]) / scale) if scale > 0 else float("nan")
    i0 = max(idx[0] - 1, 0)
    w_win = float(work_pos[idx[-1]] - work_pos[i0])
    r_win = abs(float(R[idx[-1]] - R[i0]))
    rel = r_win / w_win if w_win > 0 else float("nan")
    s["power"]["energy_residual_window"] = rel
    if np.isfinite(rel) and rel > ENERGY_LIMIT:
        result.diagnose("energy-residual", f"the energy balance misses {100 * rel:.1f} % of the work in over the steady "
                        "window: a smaller simulation.step, or see the other diagnostics", "power.energy_residual_window",
                        rel, ENERGY_LIMIT, "1")


def excited(model) -> bool:
    return any(p.torque or p.torque_time or p.torque_speed or p.harmonics or p.torque_angle or p.speed_time for p in model.pulleys)
