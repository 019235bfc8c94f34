"""The chord-sag rule of belt.segments = "auto" (belt/segments/resolution.py) on a running drive: a two-pulley
drive (40 mm pulleys 120 mm apart, the 5PK belt of examples/belt-5pk.toml at 300 N), the driver held
at a constant speed, the driven pulley (1e-3 kg m^2, 3 N m load) given a 1 ms torque pulse; its
torsional ringing frequency, read from the driven pulley's speed after the pulse, at segment counts
around "auto" (chord sag / contact depth 1.0 at half of it, 0.25 at it), at a belt speed of 4 and
24 m/s. The linear model (check's modes) gives 315.5 Hz: without creep and belt transport.

Run: python benchmarks/bench_chord_sag.py [--speeds 100 600] [--factors 0.5 1 2]
(not a timed test; numbers depend on the machine)
"""
import argparse

import numpy as np

import drivedyn
from drivedyn.mechanics.layout import compute_layout
from drivedyn.belt.geometry.segment_count import auto_segments, chord_sag
from drivedyn.core.model import from_dict, to_dict


def drive(segments, omega=600.0, duration=0.2):
    """The two-pulley drive, driver held at omega (rad/s, from rest in 50 ms), pulse at 0.1 s."""
    d = to_dict(drivedyn.load(drivedyn.example_path("belt-5pk")))
    d["belt"].update(segments=segments, pretension=300.0)
    d["pulleys"][0].update(center=[0.0, 0.0], radius=0.04)
    d["pulleys"][0].pop("torque_time", None)
    d["pulleys"][0]["speed_time"] = [[0.0, 0.0], [0.05, -omega], [duration, -omega]]
    p = d["pulleys"][1]
    p.update(center=[0.12, 0.0], radius=0.04, inertia=1e-3)
    p.pop("torque_speed", None)
    p["torque_time"] = [[0, 0], [0.05, 3.0], [0.1, 3.0], [0.1005, 6.0], [0.101, 3.0], [duration, 3.0]]
    d["simulation"].update(duration=duration, method="semi-implicit")
    d["output"].update(interval=2e-5, frames=1, segments=[0], steady_window=[duration - 0.05, duration])
    return from_dict(d)


def ringing(result, after=0.102, fmin=50.0, fmax=2000.0):
    """The driven pulley's ringing frequency (Hz) after the pulse: peak of its speed's spectrum
    between fmin and fmax (quadratic trend removed, Hann window, zero-padded 64x); above fmax lie
    the segments' landings (v / l, 5 kHz at half the "auto" count), not the torsional mode."""
    t = result.ds["time"].values
    om = result.ds["speed"].values[:, 1]
    sel = t > after
    x = om[sel] - np.polyval(np.polyfit(t[sel], om[sel], 2), t[sel])
    nfft = 64 * len(x)
    X = np.abs(np.fft.rfft(x * np.hanning(len(x)), nfft))
    f = np.fft.rfftfreq(nfft, t[1] - t[0])
    ok = (f > fmin) & (f < fmax)
    return float(f[ok][np.argmax(X[ok])])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--speeds", type=float, nargs="+", default=[100.0, 600.0], help="driver rad/s")
    ap.add_argument("--factors", type=float, nargs="+", default=[0.5, 1.0, 2.0], help="x the auto count")
    a = ap.parse_args()
    m = drive("auto")
    n_auto, why = auto_segments(m)
    lay = compute_layout(m)
    print(f"auto: {n_auto} segments ({why})")
    for omega in a.speeds:
        print(f"driver {omega:.0f} rad/s ({omega * 0.04:.1f} m/s)")
        for k in a.factors:
            n = int(round(k * n_auto))
            r = drivedyn.run(drive(n, omega))
            sag = chord_sag(m, lay, lay.length / n)
            print(f"  {n:5d} segments, sag/depth {sag:5.2f}: {ringing(r):7.1f} Hz, wall {r.summary['solver']['wall_time']:.1f} s",
                  flush=True)


if __name__ == "__main__":
    main()
