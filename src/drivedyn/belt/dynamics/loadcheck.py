"""Checks of the accessory loads a belt run was given (diagnostics ``table-extrapolated`` and
``load-delivers-power``).

A ``torque_speed`` table is extrapolated linearly beyond its ends (belt/model.py). Written with
positive speeds for a pulley that turns clockwise, it is read at the running speed through zero
and beyond, where it may turn a load into a motor: the run would balance a pump that drives the
belt. Both are measured in the steady window: the pulley's speed against the table's range, and
the mean power its applied torque puts into the drive.
"""
from __future__ import annotations

import numpy as np

#: a load pulley delivering more than this share of the driver's power (at least 1 W) is flagged
POWER_SHARE = 0.01


def intended_driver(model) -> int:
    """The pulley meant to drive: the prescribed-speed one, else the largest applied torque
    (as system.running_senses reads it)."""
    for j, p in enumerate(model.pulleys):
        if p.speed_time is not None:
            return j
    peak = [max([abs(p.torque)] + [abs(r[1]) for r in (p.torque_time or [])]) for p in model.pulleys]
    return int(np.argmax(peak))


def check_loads(result, model, sel) -> None:
    ds = result.ds
    if not np.any(sel) or "speed" not in ds or "power_in" not in ds:
        return
    speed = ds["speed"].values[sel]
    power = ds["power_in"].values[sel].mean(axis=0)
    d = intended_driver(model)
    reference = max(abs(float(power[d])), 1.0)
    for j, p in enumerate(model.pulleys):
        if not p.torque_speed:
            continue
        # behind a clutch the table acts on the rotor, whose speed is not this pulley's
        w = (ds["rotor_speed"].sel(clutch=p.name).values[sel] if p.clutch is not None and "rotor_speed" in ds
             else speed[:, j])
        lo, hi = p.torque_speed[0][0], p.torque_speed[-1][0]
        outside = float(np.mean((w < lo) | (w > hi)))
        if outside > 0.5:
            wm = float(np.mean(w))
            result.diagnose("table-extrapolated",
                            f"pulley {p.name} runs at {wm:.4g} rad/s, outside its torque_speed table "
                            f"[{lo:.4g}, {hi:.4g}] rad/s for {100 * outside:.0f} % of the steady window: its load is "
                            "extrapolated (speeds are signed: counter-clockwise positive)",
                            "share of the window outside the table", outside, 0.5, "1")
        if j != d and power[j] > POWER_SHARE * reference:
            result.diagnose("load-delivers-power",
                            f"pulley {p.name}, loaded by a torque_speed table, delivers {power[j]:.4g} W into the belt "
                            f"(the driver {model.pulleys[d].name}: {power[d]:.4g} W): check the table's speed sign",
                            "mean power delivered", float(power[j]), POWER_SHARE * reference, "W")
