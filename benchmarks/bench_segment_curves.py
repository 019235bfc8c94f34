"""The example cam drive (examples/timing-cam-drive.toml), 1 s at 3000 rpm, on the segment model with
its round crank sprocket and with the oval one examples/study-oval-crank.toml chose (ovality 0.0174,
phase 71.7 deg): wall of drivedyn.run (kernels cached: one warm-up run first) and of its solver, min /
median / max over repeats, and the oval's median over the round's measured in this one run (the
target: within 1.5x). With --speeds: the round and the oval crank held at each crank speed (0.6 s, the
window 0.3-0.6 s) in the segment and the rotational model, each span's 2nd-order tension (N): the
segment model's check of the study's design. Run on one core:
`taskset -c 0 python benchmarks/bench_segment_curves.py [--speeds 1125 3625]`."""
import argparse
import math
import statistics

import drivedyn
from bench_timing import measure

OVAL = {"kind": "oval", "ovality": 0.0174, "phase": "71.7 deg"}


def orders_at(base, rpm):
    """{model: {design: {span: 2nd-order tension amplitude (N)}}} of the round and the oval crank at rpm."""
    from drivedyn.belt.dynamics.phase import orders_of

    out = {}
    for name in ("segments", "rotational"):
        for design in ("round", "oval"):
            m = drivedyn.replace(base, {"pulleys.CRK.speed_time": [[0, 0], [0.1, rpm * math.pi / 30]],
                                        "simulation.model": name, "simulation.duration": 0.6,
                                        "output.steady_window": [0.3, 0.6]})
            if design == "oval":
                m = drivedyn.replace(m, {"pulleys.CRK.pitch_curve": OVAL})
            ds = drivedyn.run(m).ds
            sel = ds["time"].values >= 0.3
            th = ds["angle"].values[sel, 0]
            row = {}
            for sp in ds["span"].values:
                fit = orders_of(th, ds["span_tension"].sel(span=sp).values[sel])
                row[str(sp)] = next((o["amplitude"] for o in fit if o["order"] == 2.0), 0.0)
            out.setdefault(name, {})[design] = row
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--duration", type=float, default=1.0)
    ap.add_argument("--speeds", type=float, nargs="*", default=[])
    a = ap.parse_args()
    if a.speeds:
        base = drivedyn.load(drivedyn.example_path("timing-cam-drive"))
        for rpm in a.speeds:
            r = orders_at(base, rpm)
            print(f"crank {rpm:.0f} rpm, 2nd-order span tension (N): round / oval")
            for sp in r["segments"]["round"]:
                print(f"  {sp:10s} segments {r['segments']['round'][sp]:7.1f} / {r['segments']['oval'][sp]:7.1f}   "
                      f"rotational {r['rotational']['round'][sp]:7.1f} / {r['rotational']['oval'][sp]:7.1f}")
        return
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
