"""The segment model's flap (transverse) damping: a span's first mode in free decay.

    python benchmarks/bench_flap_decay.py [--rpm 1000 3000] [--speed 0.05 0.5 2.5]

A two-pulley drive with examples/fead-runup.toml's belt (crank 70 mm driven at a constant speed,
accessory 50 mm with 5 N m, centres 350 mm apart) runs to a steady state at 0.35 s; then every
segment of its slack span is given a transverse velocity in the shape of the span's first mode,
sin(pi s / L) x the given speed (m/s; 0.05 gives about 0.2 mm of swing, 2.5 about 5 mm), and the
midpoint's swing across the span's rest chord is recorded for 0.25 s. Printed: its frequency (the
spectrum's peak) and the damping ratio from the decay of its peaks, with the axially moving
string's frequency at the pretension, n c (1 - v^2 / c^2) / (2 L), c^2 = T / m, for scale.

Measured (2-core Intel Xeon, 227 segments; midpoint swing 0.2 / 1 / 5 mm): damping ratios 0.0003 /
0.0012 / 0.0049 at 1000 rpm, 0.0004 / -0.0001 / 0.0019 at 3000 rpm (the fit's scatter is about 0.001);
frequencies 72 and 60 Hz against the string's 77.5 and 66.4 Hz at the pretension (the slack span runs
below it). The segment model's spans ring for hundreds of periods: its bending damper
(system.GRID_ZETA) does not reach them and their landing on the wraps takes little.
Not a timed test.
"""
from __future__ import annotations

import argparse
import math

import numpy as np
from bench_fead_convergence import fead_belt

from drivedyn.belt.geometry.drive import resolve
from drivedyn.belt.segments import _kernels as K
from drivedyn.belt.segments.compiled import compiled
from drivedyn.belt.segments.simulate import _loop_args
from drivedyn.belt.segments.state import new_state, new_work
from drivedyn.belt.segments.system import build
from drivedyn.core.model import from_dict

SETTLE = 0.35       # s at constant speed before the kick
RECORD = 0.25       # s of free decay
SAMPLE = 5e-5       # s between samples


def drive(rpm: float):
    w = -rpm * math.pi / 30
    return from_dict({
        "kind": "belt-drive", **fead_belt(),
        "simulation": {"duration": 1.0},
        "pulleys": [
            {"name": "crank", "center": [0, 0], "radius": 0.07, "speed_time": [[0, 0], [0.2, w], [2, w]]},
            {"name": "accessory", "center": [0.35, 0.0], "radius": 0.05, "inertia": 2e-3, "torque": 5.0,
             "drag": 0.1}]})


def decay(rpm: float, speed: float) -> dict:
    sysm = build(resolve(drive(rpm)), before_settle=None)
    S = new_state(sysm)
    W = new_work(sysm, S)
    steps = max(1, math.ceil(SAMPLE / sysm.step))
    h = SAMPLE / steps
    records = _loop_args(sysm, h, S, W)[3:]
    step = compiled(K._advance, (1, 0.0, h, *records))
    t = 0.0
    while t < SETTLE - 1e-12:
        t = step(steps, t, h, *records)
    span = sysm.layout.spans[1]          # accessory -> crank: the slack span
    p0, p1 = np.array(span.p0), np.array(span.p1)
    L = span.length
    e = (p1 - p0) / L
    n = np.array([-e[1], e[0]])

    def across():
        d = np.stack([S.x - p0[0], S.y - p0[1]], 1)
        return d @ e, d @ n

    s, w = across()
    on = (s > 0) & (s < L) & (np.abs(w) < 0.02)
    along = np.sign(np.mean(S.c[on] * e[0] + S.s[on] * e[1]))
    shape = np.sin(math.pi * s[on] / L)
    S.vx[on] += speed * shape * n[0]
    S.vy[on] += speed * shape * n[1]
    S.w[on] += along * speed * math.pi / L * np.cos(math.pi * s[on] / L)   # the segments turn with the slope
    W.lin_cnt[0] = 0                     # the implicit scheme refactors its chain matrix

    def midpoint():
        s, w = across()
        sel = (s > 0.05 * L) & (s < 0.95 * L) & (np.abs(w) < 0.02)
        o = np.argsort(s[sel])
        return float(np.interp(0.5 * L, s[sel][o], w[sel][o]))

    x = []
    for _ in range(int(RECORD / SAMPLE)):
        t = step(steps, t, h, *records)
        x.append(midpoint())
    x = np.array(x) - np.mean(x)
    spec = np.abs(np.fft.rfft(x * np.hanning(len(x))))
    f = float(np.fft.rfftfreq(len(x), SAMPLE)[np.argmax(spec[1:]) + 1])
    peaks = [i for i in range(1, len(x) - 1) if abs(x[i]) >= abs(x[i - 1]) and abs(x[i]) > abs(x[i + 1])
             and abs(x[i]) > 0.5 * np.abs(x).max()]
    tp = np.array(peaks) * SAMPLE
    slope = np.polyfit(tp, np.log(np.abs(x[peaks])), 1)[0] if len(peaks) > 3 else math.nan
    v = abs(rpm * math.pi / 30 * 0.07)
    c = math.sqrt(350.0 / 0.115)
    return {"rpm": rpm, "segments": sysm.n, "swing_mm": 1e3 * float(np.abs(x).max()), "f_hz": f,
            "f_string_hz": c / (2 * L) * (1 - v * v / (c * c)), "zeta": -slope / (2 * math.pi * f)}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rpm", nargs="+", type=float, default=[1000.0, 3000.0])
    ap.add_argument("--speed", nargs="+", type=float, default=[0.05, 0.5, 2.5], help="kick, m/s")
    a = ap.parse_args()
    print("| rpm | segments | swing (mm) | frequency (Hz) | string at the pretension (Hz) | damping ratio |")
    print("|---|---|---|---|---|---|")
    for rpm in a.rpm:
        for sp in a.speed:
            r = decay(rpm, sp)
            print(f"| {r['rpm']:.0f} | {r['segments']} | {r['swing_mm']:.2f} | {r['f_hz']:.1f} | "
                  f"{r['f_string_hz']:.1f} | {r['zeta']:.4f} |", flush=True)


if __name__ == "__main__":
    main()
