"""Accessory-drive answers at the defaults against a refined reference: the six-pulley drive of
examples/fead-runup.toml held at a crank speed with its 2nd/4th orders (0.8 s, window 0.6-0.8 s),
at belt.segments = "auto" (the default) and at 150 segments, against a run at four times the
"auto" segments: every pulley's mean slip (percentage points off the reference), every span's
tension minimum and maximum (% off), the arm's travel range, status and wall time.

Run: python benchmarks/bench_fead_defaults.py [--rpm 3000] [--refine 4] [--law elastic-plastic]
[--method implicit --step 19.2e-6] (the method and step for the "150" and "auto" runs; the
reference is semi-implicit at its own step, unscaled)
(not a timed test; numbers depend on the machine: the 4x reference takes several minutes)
"""
import argparse
import math

import drivedyn
from bench_fead_convergence import held


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rpm", type=float, default=3000.0)
    ap.add_argument("--refine", type=int, default=4)
    ap.add_argument("--law", default=None, help="friction.law for every run (default: the example's)")
    ap.add_argument("--method", default=None, help="simulation.method of the 150 and auto runs (default: auto)")
    ap.add_argument("--step", type=float, default=None, help="simulation.step (s) of the 150 and auto runs")
    a = ap.parse_args()
    def make(rpm, segs, ref=False):
        m = held(rpm, segs)
        over = {"friction.law": a.law} if a.law else {}
        if ref:
            over.update({"simulation.method": "semi-implicit", "simulation.rotation_scaling": False})
        else:
            over.update({k: v for k, v in (("simulation.method", a.method), ("simulation.step", a.step)) if v})
        return drivedyn.replace(m, over) if over else m
    drivedyn.run(drivedyn.replace(make(a.rpm, 150), {"simulation.duration": 0.01, "output.steady_window": None}))
    runs = {}
    for label, segs in (("150", 150), ("auto", "auto")):
        runs[label] = drivedyn.run(make(a.rpm, segs))
    n_ref = a.refine * runs["auto"].summary["belt"]["segments"]
    runs[f"{n_ref}"] = ref = drivedyn.run(make(a.rpm, n_ref, ref=True))
    rs = ref.summary
    print(f"held at {a.rpm:.0f} rpm, orders 2 and 4; reference {n_ref} segments")
    for label, r in runs.items():
        s = r.summary
        dslip = max(abs(100 * (s["pulleys"][p]["slip"] - rs["pulleys"][p]["slip"])) for p in s["pulleys"])
        off = {k: {q: s["spans"][q][k] / rs["spans"][q][k] - 1 for q in s["spans"]} for k in ("tension_min", "tension_max")}
        qmin = max(off["tension_min"], key=lambda q: abs(off["tension_min"][q]))
        qmax = max(off["tension_max"], key=lambda q: abs(off["tension_max"][q]))
        dmin, dmax = abs(off["tension_min"][qmin]), abs(off["tension_max"][qmax])
        arm = s["tensioners"]["tensioner"]
        codes = ",".join(d.code for d in r.diagnostics) or "-"
        print(f"  {label:>5s}: {s['belt']['segments']:5d} segments, {s['solver']['method']} at "
              f"{1e6 * s['solver']['step']:.3g} us, wall {s['solver']['wall_time']:6.1f} s; slips "
              + " / ".join(f"{100 * s['pulleys'][p]['slip']:.3f}" for p in s["pulleys"])
              + f" %, largest off {dslip:.3f} points; span minima off up to {100 * dmin:.1f} % ({qmin}), maxima "
              f"{100 * dmax:.1f} % ({qmax}); arm range {(arm['travel_max'] - arm['travel_min']) * 180 / math.pi:.3f} deg; "
              f"{r.status}: {codes}", flush=True)


if __name__ == "__main__":
    main()
