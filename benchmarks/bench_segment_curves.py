"""The example cam drive (examples/timing-cam-drive.toml), 1 s at 3000 rpm, on the segment model with
its round crank sprocket and with the oval one examples/study-oval-crank.toml chose (ovality 0.0174,
phase 71.7 deg): wall of drivedyn.run (kernels cached: one warm-up run first) and of its solver, min /
median / max over repeats, and the oval's median over the round's measured in this one run (the
issue's target: within 1.5x). Run on one core: `taskset -c 0 python benchmarks/bench_segment_curves.py`."""
import argparse
import statistics

import drivedyn
from bench_timing import measure

OVAL = {"kind": "oval", "ovality": 0.0174, "phase": "71.7 deg"}


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
    for name, m in (("round", model), ("oval", drivedyn.replace(model, {"pulleys.CRK.pitch_curve": OVAL}))):
        walls, solver, res = measure(m, a.repeat)
        med[name] = statistics.median(walls), statistics.median(solver)
        print(f"timing-cam-drive, segment model, {name} crank, {a.duration:g} s simulated, "
              f"{res.summary['solver']['steps']} steps of {res.summary['solver']['step'] * 1e6:.2f} us; "
              f"diagnostics: {[d.code for d in res.diagnostics] or 'none'}")
        print(f"  drivedyn.run wall (min / median / max): {f(walls)}")
        print(f"  solver wall:                            {f(solver)}")
    o, r = med["oval"], med["round"]
    print(f"oval against round (medians): drivedyn.run {o[0] / r[0]:.2f}x, solver {o[1] / r[1]:.2f}x")


if __name__ == "__main__":
    main()
