"""The two belt schemes on an accessory drive: the six-pulley drive of examples/fead-runup.toml
(tensioner arm, one-way clutch, crank orders 2 and 4) held at 1000, 3000 and 5000 rpm, 0.6 s with
the window 0.4-0.6 s, at the default resolution ("auto"), under the semi-implicit scheme and the
implicit one (what "auto" takes for such drives under the elastic-plastic law): step, wall time,
and every pulley's slip and the crank span's tension band, measured in one run. With --turn, the
implicit scheme also runs at the step that turns the fastest pulley (the 28 mm alternator) by that
angle per step (0.016 rad: 19.2 us at 3000 rpm) instead of its accuracy rule's.

Run: python benchmarks/bench_fead_schemes.py [--rpm 1000 3000 5000] [--turn 0.016]
(not a timed test; numbers depend on the machine)
"""
import argparse
import math

import drivedyn
from bench_fead_convergence import held, row


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rpm", type=float, nargs="+", default=[1000.0, 3000.0, 5000.0])
    ap.add_argument("--turn", type=float, default=None, help="also the implicit scheme at this turn per step (rad)")
    a = ap.parse_args()
    for method in ("semi-implicit", "implicit"):      # compile both first
        drivedyn.run(drivedyn.replace(held(1000, 150, duration=0.35),
                                      {"simulation.method": method, "simulation.duration": 0.02, "output.steady_window": None}))
    for rpm in a.rpm:
        print(f"held at {rpm:.0f} rpm, orders 2 and 4")
        base = held(rpm, "auto", duration=0.6)
        runs = [("semi-implicit", {}), ("implicit", {})]
        if a.turn:
            radii = [p.radius for p in base.pulleys]
            fastest = rpm * math.pi / 30 * radii[0] / min(radii)      # the crank drives
            runs.append(("implicit", {"simulation.step": a.turn / fastest}))
        for method, over in runs:
            m = drivedyn.replace(base, {"simulation.method": method, "output.steady_window": [0.4, 0.6], **over})
            r = drivedyn.run(m)
            sv = r.summary["solver"]
            print(f"  {method:13s} step {sv['step'] * 1e6:6.2f} us  {row(r)}", flush=True)


if __name__ == "__main__":
    main()
