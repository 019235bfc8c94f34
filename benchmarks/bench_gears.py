"""Gear-train speed: the seed 003 split-path case, 0.1 s simulated, and a 200-speed K_v sweep.

Run: python benchmarks/bench_gears.py   (not a timed test; numbers depend on the machine)
"""
import statistics
import time
import warnings

import drivedyn


def main():
    warnings.simplefilter("ignore")
    base = drivedyn.load(drivedyn.example_path("gears-split-path"))
    single = drivedyn.replace(base, {"sweep.enabled": False, "simulation.duration": 0.1,
                                     "simulation.steady_window": [0.05, 0.1]})
    drivedyn.run(drivedyn.replace(single, {"simulation.duration": 0.001, "simulation.steady_window": [0, 0.001]}))
    walls = []
    for _ in range(5):
        t = time.perf_counter()
        r = drivedyn.run(single)
        walls.append(time.perf_counter() - t)
    steps = r.summary["solver"]["steps"]
    print(f"seed case, RK4 h = 5 us, 0.1 s simulated ({steps} steps): wall min/median "
          f"{min(walls):.3f}/{statistics.median(walls):.3f} s (incl. assembly and results), "
          f"K_v = {r.summary['meshes']['m12']['kv']:.4f}")
    sw = drivedyn.replace(base, {"simulation.duration": 0.001, "simulation.steady_window": [0, 0.001]})
    drivedyn.run(drivedyn.replace(sw, {"sweep.count": 2}))                       # compile the sweep
    for _ in range(2):
        t = time.perf_counter()
        r = drivedyn.run(sw)
        wall = time.perf_counter() - t
        s = r.summary["sweep"]
        print(f"sweep, {s['count']} speeds {s['speed_min'] * 30 / 3.14159265:.0f}-{s['speed_max'] * 30 / 3.14159265:.0f} rpm, "
              f"settle {s['settle'] * 1e3:.0f} ms + {s['window_cycles']} mesh periods each: sweep wall {s['wall_time']:.2f} s "
              f"(run total {wall:.2f} s)")


if __name__ == "__main__":
    main()
