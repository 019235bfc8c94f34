"""The rotational model against the segment model on the drive of examples/fead-runup.toml.

1. The whole run-up (4.8 s, 800 -> 5000 rpm, orders 2 and 4): the segment model at 150 segments
   (semi-implicit) and at its default resolution, the rotational model integrated in time, and
   the periodic run-up (simulation.runup = "periodic", 17 crank-speed bins): wall time of
   drivedyn.run and of the solve, in one run; ratios against the 150-segment run.
2. With --compare: the drive held at 1000, 3000 and 5000 rpm (0.8 s, window 0.6-0.8 s), the
   rotational model against the segment model at "auto" and twice its segments (the convergence
   check): span tension min / mean / max, slip per pulley, arm travel range, hub load peaks.

Run: python benchmarks/bench_rotational.py [--compare] [--skip-segments]
(not a timed test; numbers depend on the machine)
"""
import argparse
import math
import time

import numpy as np

import drivedyn
from bench_fead_convergence import held


def timed(m):
    t = time.perf_counter()
    r = drivedyn.run(m)
    return r, time.perf_counter() - t


def runup(skip_segments):
    base = drivedyn.load(drivedyn.example_path("fead-runup"))
    rot = drivedyn.replace(base, {"simulation.model": "rotational"})
    per = drivedyn.replace(base, {"simulation.model": "rotational", "simulation.runup": "periodic"})
    for m in (rot, per, drivedyn.replace(base, {"belt.segments": 150, "simulation.duration": 0.01,
                                                     "output.steady_window": None, "output.runup_bin": None})):
        drivedyn.run(m)                                      # compile and load the kernels
    rows = []
    if not skip_segments:
        for segs in (150, "auto"):
            r, w = timed(drivedyn.replace(base, {"belt.segments": segs}))
            rows.append((f"segments {r.summary['belt']['segments']}", r, w))
    for name, m in (("rotational, time", rot), ("rotational, periodic", per)):
        r, w = timed(m)
        rows.append((name, r, w))
    ref = rows[0][2] if not skip_segments else math.nan
    print("fead-runup, the whole run-up (drivedyn.run wall / solve wall, s; ratio to the first row)")
    for name, r, w in rows:
        ru = r.summary["runup"]
        print(f"  {name:22s} {w:7.2f} {r.summary['solver']['wall_time']:7.3f}  x{ref / w:6.1f}  "
              f"{len(ru['speed_rpm'])} bins, status {r.status}: {','.join(d.code for d in r.diagnostics) or '-'}")


def compare():
    print("held speeds: rotational / segments auto / segments 2 x auto (window 0.6-0.8 s)")
    for rpm in (1000.0, 3000.0, 5000.0):
        runs = {}
        m = held(rpm, "auto")
        runs["rot"] = timed(drivedyn.replace(m, {"simulation.model": "rotational"}))
        ra = timed(m)
        runs["auto"] = ra
        runs["2x"] = timed(drivedyn.replace(m, {"belt.segments": 2 * ra[0].summary["belt"]["segments"]}))
        print(f" {rpm:.0f} rpm: wall " + " / ".join(f"{runs[k][1]:.1f} s" for k in runs)
              + "; status " + " / ".join(runs[k][0].status for k in runs))
        s = {k: v[0].summary for k, v in runs.items()}
        for sp in s["rot"]["spans"]:
            cells = [" {:4.0f}/{:4.0f}/{:4.0f}".format(*(s[k]["spans"][sp][q] for q in ("tension_min", "tension_mean", "tension_max")))
                     for k in runs]
            print(f"   {sp:26s}" + " |".join(cells))
        for p in s["rot"]["pulleys"]:
            hub = [float(runs[k][0].ds["hub_load"].sel(pulley=p).values[runs[k][0].ds["time"].values > 0.6].max()) for k in runs]
            print(f"   {p:14s} slip % " + " / ".join(f"{100 * s[k]['pulleys'][p]['slip']:.3f}" for k in runs)
                  + "   hub max N " + " / ".join(f"{x:.0f}" for x in hub))
        arm = [s[k]["tensioners"]["tensioner"]["travel_max"] - s[k]["tensioners"]["tensioner"]["travel_min"] for k in runs]
        print("   arm travel range deg " + " / ".join(f"{x * 180 / math.pi:.3f}" for x in arm))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--compare", action="store_true", help="held speeds against the segment model (minutes)")
    ap.add_argument("--skip-segments", action="store_true", help="the rotational rows only")
    a = ap.parse_args()
    runup(a.skip_segments)
    if a.compare:
        compare()


if __name__ == "__main__":
    np.set_printoptions(precision=3)
    main()
