"""Crank input with engine orders, and an overrunning alternator clutch, on the 5PK two-pulley drive:
the order shows in the span tension at k omega; the prescribed speed carries the order's amplitude;
the clutch never passes a negative torque and lets the rotor overrun when the crank decelerates;
the energy balance closes with the clutch."""
from __future__ import annotations

import math

import numpy as np
import pytest

import drivedyn
from drivedyn.core.model import from_dict, to_dict


def drive(crank, driven=None, duration=0.4, window=(0.2, 0.4)):
    d = to_dict(drivedyn.load(drivedyn.example_path("belt-5pk")))
    p0, p1 = d["pulleys"]
    for k in ("torque_time", "torque", "torque_speed"):
        p0.pop(k, None)
        p1.pop(k, None)
    p0.update(crank)
    p1.update(driven or {"viscous_torque": 0.02})
    d["simulation"] = {"duration": duration}
    d["output"] = {"interval": "0.5 ms", "frames": 2, "segments": [0], "steady_window": list(window)}
    return from_dict(d)


def test_engine_order_shows_at_k_omega():
    w, k, A = -100.0, 2.0, math.radians(0.5)        # clockwise 955 rpm, 2nd order, 0.5 deg
    m = drive({"speed_time": [[0, 0], [0.1, w]], "speed_orders": [{"order": k, "angle": A}]})
    r = drivedyn.run(m)
    assert r.status in ("success", "warning"), r.message
    t = r.ds["time"].values
    sel = (t > 0.2)
    # the prescribed speed: mean w and the order's speed amplitude k A |w| (sampled 31 times a period)
    om = r.ds["speed"].sel(pulley="driver").values[sel]
    assert np.mean(om) == pytest.approx(w, rel=2e-3)
    assert 0.5 * (om.max() - om.min()) == pytest.approx(k * A * abs(w), rel=0.01)
    # the order's part of the span tension (less the same run-up without the order: the ramp
    # leaves the drive's first torsional mode ringing, lightly damped) peaks at k |w| / 2 pi
    free = drivedyn.run(drive({"speed_time": [[0, 0], [0.1, w]]}))
    T = r.ds["span_tension"].isel(span=0).values[sel] - free.ds["span_tension"].isel(span=0).values[sel]
    T = (T - T.mean()) * np.hanning(len(T))
    spec = np.abs(np.fft.rfft(T))
    f = np.fft.rfftfreq(len(T), t[1] - t[0])
    f_peak = f[1 + np.argmax(spec[1:])]
    assert f_peak == pytest.approx(k * abs(w) / (2 * math.pi), abs=f[1])
    assert spec[1:].max() > 20 * np.median(spec[1:])


def test_overrunning_clutch_passes_drive_torque_only():
    # the crank runs up to 150 rad/s, holds it, and is pulled down in 20 ms; the alternator rotor
    # (3e-3 kg m^2, 300 W) would drive the belt back without its one-way clutch
    crank = {"speed_time": [[0, 0], [0.1, -150.0], [0.5, -150.0], [0.52, -60.0], [0.6, -60.0]]}
    alt = {"inertia": "2e-4 kg*m^2", "power": "300 W", "efficiency": 0.7, "drag": "0.05 N*m", "cut_in_speed": "50 rad/s",
           "clutch": {"type": "one-way", "inertia": "3e-3 kg*m^2"}}
    r = drivedyn.run(drive(crank, alt, duration=0.6, window=(0.3, 0.5)))
    assert r.status in ("success", "warning"), r.message
    tc = r.ds["clutch_torque"].sel(clutch="driven").values
    wr = r.ds["rotor_speed"].sel(clutch="driven").values
    wp = r.ds["speed"].sel(pulley="driven").values
    t = r.ds["time"].values
    load = 300 / 0.7 / 150 + 0.05                   # N m the rotor needs at 150 rad/s
    assert tc.min() > -1e-6 * load                   # never negative (interval means, to round-off)
    steady = (t > 0.3) & (t < 0.5)       # 0.2 s: the drive's torsional swing averages out
    assert np.mean(tc[steady]) == pytest.approx(load, rel=0.03)
    # while the crank decelerates the rotor runs ahead of the pulley (clockwise: more negative)
    # and the clutch passes nothing
    decel = (t > 0.505) & (t < 0.52)
    over = wr[decel] - wp[decel]
    assert np.all(over < -1.0), over
    assert np.all(tc[decel] < 1e-6 * load)
    assert r.summary["clutches"]["driven"]["torque_mean"] == pytest.approx(load, rel=0.03)
    assert r.summary["clutches"]["driven"]["overrun_share"] == 0.0     # the window 0.3-0.5 s: driven
    # energy balance with the clutch's engagement losses
    resid = abs(float(r.ds["energy_residual"].values[-1]))
    work = float(np.max(np.abs(r.ds["work_in"].values)))
    assert resid < 0.01 * work, (resid, work)


def test_decoupler_spring_winds_up_under_load():
    # decoupler: spring 10 N m/rad; at a steady 100 rad/s the wind-up carries the rotor's load
    crank = {"speed_time": [[0, 0], [0.1, -100.0]]}
    alt = {"inertia": "2e-4 kg*m^2", "power": "200 W", "cut_in_speed": "20 rad/s",
           "clutch": {"type": "decoupler", "inertia": "3e-3 kg*m^2", "rate": "10 N*m/rad", "damping": "0.2 N*m*s/rad"}}
    # rotor on the spring: 9.2 Hz, damping ratio 0.58
    r = drivedyn.run(drive(crank, alt, duration=0.6, window=(0.4, 0.6)))
    tc = r.ds["clutch_torque"].sel(clutch="driven").values
    t = r.ds["time"].values
    sel = t > 0.4
    assert np.mean(tc[sel]) == pytest.approx(200 / 100, rel=0.03)
    resid = abs(float(r.ds["energy_residual"].values[-1]))
    assert resid < 0.01 * float(np.max(np.abs(r.ds["work_in"].values)))


def test_bad_load_input():
    from drivedyn.core.errors import ModelError
    for change, words in [({"speed_orders": [{"order": 2, "angle": 0.01}]}, "speed_orders need"),
                          ({"efficiency": 0.0}, "efficiency"),
                          ({"clutch": {"type": "decoupler", "inertia": 0.01}}, "rate > 0"),
                          ({"drag": -1.0}, "drag")]:
        d = to_dict(drive({"speed_time": [[0, 0], [0.1, -100.0]]}))
        d["pulleys"][1].update(change)
        with pytest.raises(ModelError) as e:
            from_dict(d)
        assert words in str(e.value) and "\n" not in str(e.value), str(e.value)
