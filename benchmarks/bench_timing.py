"""The example cam drive (examples/timing-cam-drive.toml), 1 s at 3000 rpm, on the segment model with
its teeth and on the rotational timing model: wall of drivedyn.run (kernels cached: one warm-up run
first) and of its solver, min / median / max over repeats, and the ratio of the two models' medians
measured in this one run. Run on one core: `taskset -c 0 python benchmarks/bench_timing.py`."""
import argparse
import statistics
import time

import drivedyn


def measure(model, repeat):
    drivedyn.run(drivedyn.replace(model, {"simulation.duration": 0.01, "output.steady_window": None}))   # kernels
    walls, solver = [], []
    for _ in range(repeat):
        t0 = time.perf_counter()
        res = drivedyn.run(model)
        walls.append(time.perf_counter() - t0)
        solver.append(res.summary["solver"]["wall_time"])
    return walls, solver, res


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--duration", type=float, default=1.0)
    a = ap.parse_args()
    model = drivedyn.load(drivedyn.example_path("timing-cam-drive"))
    model = drivedyn.replace(model, {"simulation.duration": a.duration,
                                     "output.steady_window": [a.duration / 2, a.duration]})
    f = lambda xs: f"{min(xs):.3f} / {statistics.median(xs):.3f} / {max(xs):.3f} s"     # noqa: E731
    med = {}
    for name in ("segments", "rotational"):
        walls, solver, res = measure(drivedyn.replace(model, {"simulation.model": name}), a.repeat)
        med[name] = statistics.median(walls), statistics.median(solver)
        print(f"timing-cam-drive, {name}, {a.duration:g} s simulated, {res.summary['solver']['steps']} steps of "
              f"{res.summary['solver']['step'] * 1e6:.2f} us, {res.ds.sizes['time']} samples")
        print(f"  drivedyn.run wall (min / median / max): {f(walls)}")
        print(f"  solver wall:                            {f(solver)}")
    s, r = med["segments"], med["rotational"]
    print(f"rotational against segments (medians): drivedyn.run {s[0] / r[0]:.1f}x, solver {s[1] / r[1]:.1f}x")


if __name__ == "__main__":
    main()
