"""Belt-drive speed: wall time per simulated second and cost per step, and its growth with the
number of segments n and of pulleys k.

Run: python benchmarks/bench_belt.py   (not a timed test; numbers depend on the machine)
     python benchmarks/bench_belt.py --implicit   (only the two schemes against each other)
"""
import statistics

import numpy as np

import drivedyn
from drivedyn.core.model import from_dict, to_dict


def timed(model, repeat=3):
    walls, steps = [], 0
    for _ in range(repeat):
        r = drivedyn.run(model)
        walls.append(r.summary["solver"]["wall_time"])
        steps = r.summary["solver"]["steps"]
    return walls, steps, r


def main(only_implicit=False):
    # the seed's case as it was benchmarked from the start: 150 segments, the semi-implicit scheme
    base = drivedyn.replace(drivedyn.load(drivedyn.example_path("belt-5pk")),
                            {"belt.segments": 150, "simulation.method": "semi-implicit", "output.segments": [107]})
    drivedyn.run(drivedyn.replace(base, {"simulation.duration": 0.01}))      # compile once
    drivedyn.run(drivedyn.replace(base, {"simulation.duration": 0.01, "simulation.method": "implicit"}))
    if only_implicit:
        implicit_against_reference(base)
        return
    m = drivedyn.replace(base, {"simulation.duration": 1.0, "output.steady_window": [0.75, 1.0]})
    walls, steps, r = timed(m)
    med = statistics.median(walls)
    print(f"5PK seed case, 150 segments, Delta_v = 1e-5 m/s, 1 s simulated: wall min/median/max "
          f"{min(walls):.3f}/{med:.3f}/{max(walls):.3f} s, real-time factor {1 / med:.2f}, {steps} steps of "
          f"{r.summary['solver']['step'] * 1e6:.3f} us, {med / steps * 1e6:.2f} us per step")
    print(f"{'n':>5s} {'step us':>8s} {'steps/s sim':>12s} {'us/step':>8s} {'wall s per sim s':>17s}")
    for n in (50, 100, 150, 300, 600):
        mn = drivedyn.replace(base, {"belt.segments": n, "simulation.duration": 0.1, "output.segments": [0]})
        walls, steps, r = timed(mn, repeat=2)
        w = min(walls)
        print(f"{n:5d} {r.summary['solver']['step'] * 1e6:8.3f} {steps / 0.1:12.0f} {w / steps * 1e6:8.2f} {w / 0.1:17.2f}")

    implicit_against_reference(base)

    # k pulleys of 27 mm on a regular polygon, the 5PK belt (1.2 m path, 150 segments), the
    # seed's driver and load on the first two, free idlers on the others
    print(f"{'pulleys':>7s} {'us/step':>8s} {'wall s per sim s':>17s}")
    for k in (2, 3, 4, 6, 8):
        mk = ring(base, k)
        drivedyn.run(drivedyn.replace(mk, {"simulation.duration": 0.002}))
        walls, steps, r = timed(mk, repeat=2)
        w = min(walls)
        print(f"{k:7d} {w / steps * 1e6:8.2f} {w / 0.1:17.2f}")


def implicit_against_reference(base):
    # the implicit scheme (issue 14) against the semi-implicit reference, in one run: wall time per
    # simulated second over 0.3 s of the 5PK start (ramp and slip arcs forming), its growth with n.
    # The two schemes alternate, three runs each, and the fastest of each counts: this machine's
    # speed drifts by 10-40 % within minutes, which a single pair of runs reads as a ratio
    print(f"{'n':>5s} {'semi us':>8s} {'impl us':>8s} {'semi s/s':>9s} {'impl s/s':>9s} {'ratio':>6s} "
          f"{'factor/step':>11s} {'passes/step':>11s}")
    ns, walls = [], []
    for n in (50, 100, 150, 300, 600, 1200):
        row = {}
        for _ in range(3):
            for method in ("semi-implicit", "implicit"):
                if method == "semi-implicit" and n > 600:
                    continue
                mn = drivedyn.replace(base, {"belt.segments": n, "simulation.duration": 0.3, "output.segments": [0],
                                             "simulation.method": method})
                w, steps, r = timed(mn, repeat=1)
                if method not in row or min(w) / 0.3 < row[method][0]:
                    row[method] = (min(w) / 0.3, r.summary["solver"])
        si, im = row.get("semi-implicit"), row["implicit"]
        ns.append(n)
        walls.append(im[0])
        print(f"{n:5d} {si[1]['step'] * 1e6 if si else float('nan'):8.3f} {im[1]['step'] * 1e6:8.3f} "
              f"{si[0] if si else float('nan'):9.2f} {im[0]:9.2f} {si[0] / im[0] if si else float('nan'):6.2f} "
              f"{im[1]['factorisations'] / im[1]['steps']:11.3f} {im[1]['active_set_passes'] / im[1]['steps']:11.2f}",
              flush=True)
    slope = np.polyfit(np.log(ns), np.log(walls), 1)[0]
    big = [k for k, n in enumerate(ns) if n >= 150]
    slope_big = np.polyfit(np.log(np.take(ns, big)), np.log(np.take(walls, big)), 1)[0]
    print(f"implicit: wall per simulated second grows as n^{slope:.2f} over n = {ns[0]}..{ns[-1]} "
          f"(n^{slope_big:.2f} over 150..{ns[-1]})")


def ring(base, k, radius=0.027, path=1.2):
    """The 5PK drive with its belt around k pulleys on a regular polygon (same path length)."""
    d = to_dict(base)
    rc = (path - 2 * np.pi * radius) / (2 * k * np.sin(np.pi / k))
    pulleys = []
    for i in range(k):
        p = dict(d["pulleys"][i]) if i < 2 else {"name": f"idler{i}", "radius": radius, "inertia": 0.001}
        a = np.pi + 2 * np.pi * i / k
        p["center"] = [rc * np.cos(a), rc * np.sin(a)]
        pulleys.append(p)
    d["pulleys"] = pulleys
    d["simulation"]["duration"] = 0.1
    d["output"]["segments"] = [0]
    return from_dict(d, source=f"ring of {k} pulleys")


if __name__ == "__main__":
    import sys

    main(only_implicit="--implicit" in sys.argv)   # --implicit: only the comparison of the two schemes
