"""The rotational timing model against the segment model on examples/timing-cam-drive.toml: each model
held at crank speeds across the range, its span tension extremes and the cams' phase error, the
deviation of the rotational model's extremes from the segment model's as a share of the rotational
half band (max - min) / 2 (what rotational/simulate.py's TIMING_SHARE must cover), and the walls of
drivedyn.run of both (kernels cached) with their ratio; then a periodic run-up 800-6000 rpm on the
rotational model. `python benchmarks/bench_timing_rotational.py [--nodes N] [--speeds 1500 2000 ...]`"""
import argparse
import math
import statistics
import time

import drivedyn


def held(model, rpm, kind, nodes):
    w = rpm * math.pi / 30
    m = drivedyn.replace(model, {"simulation.model": kind, "pulleys.CRK.speed_time": [[0.0, 0.0], [0.1, w]],
                                 "belt.teeth.nodes_per_tooth": nodes})
    t0 = time.perf_counter()
    try:
        res = drivedyn.run(m)
    except drivedyn.SolverError as exc:       # the segment model may diverge at a resonance: say so
        print(f"  {kind} at {rpm:.0f} rpm: {exc}")
        return None, time.perf_counter() - t0
    return res, time.perf_counter() - t0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--nodes", type=int, default=1, help="the segment model's nodes_per_tooth")
    ap.add_argument("--speeds", type=float, nargs="*", default=[1500, 2000, 2500, 3000, 3500, 4000])
    a = ap.parse_args()
    model = drivedyn.load(drivedyn.example_path("timing-cam-drive"))
    for kind in ("rotational", "segments"):      # compile
        drivedyn.run(drivedyn.replace(model, {"simulation.model": kind, "simulation.duration": 0.01,
                                              "output.steady_window": None}))
    walls = {"rotational": [], "segments": []}
    worst = 0.0
    for rpm in a.speeds:
        rr, wr = held(model, rpm, "rotational", a.nodes)
        rs, ws = held(model, rpm, "segments", a.nodes)
        walls["rotational"].append(wr)
        if rs is None:
            continue
        walls["segments"].append(ws)
        line = []
        for sp, v in rr.summary["spans"].items():
            s = rs.summary["spans"][sp]
            half = 0.5 * (v["tension_max"] - v["tension_min"])
            dev = max(abs(v["tension_max"] - s["tension_max"]), abs(v["tension_min"] - s["tension_min"]))
            share = dev / half if half > 0 else math.inf
            worst = max(worst, share)
            line.append(f"{sp} {v['tension_min']:.0f}-{v['tension_max']:.0f} / {s['tension_min']:.0f}-"
                        f"{s['tension_max']:.0f} N ({share:.2f})")
        pe = [(rr.summary["teeth"]["pulleys"][c]["phase_error_pp"], rs.summary["teeth"]["pulleys"][c]["phase_error_pp"])
              for c in ("CAM1", "CAM2")]
        print(f"{rpm:.0f} rpm ({rs.status}): " + "; ".join(line))
        print(f"    phase error pp CAM1 {pe[0][0]:.2f} / {pe[0][1]:.2f}, CAM2 {pe[1][0]:.2f} / {pe[1][1]:.2f} crank deg "
              f"(rotational / segments)")
    print(f"largest deviation of an extreme: {worst:.2f} x the rotational half band")
    f = lambda xs: f"{min(xs):.2f} / {statistics.median(xs):.2f} / {max(xs):.2f} s"     # noqa: E731
    print(f"drivedyn.run wall, 0.4 s simulated (min / median / max): rotational {f(walls['rotational'])}, "
          f"segments ({a.nodes} node(s) per tooth) {f(walls['segments'])}; median ratio "
          f"{statistics.median(walls['segments']) / statistics.median(walls['rotational']):.0f}x")
    up = drivedyn.replace(model, {"simulation.model": "rotational", "simulation.runup": "periodic",
                                  "simulation.duration": 1.0, "output.steady_window": None,
                                  "output.runup_bin": 2 * math.pi * 200 / 60,
                                  "pulleys.CRK.speed_time": [[0.0, 800 * math.pi / 30], [1.0, 6000 * math.pi / 30]]})
    t0 = time.perf_counter()
    res = drivedyn.run(up)
    ru = res.summary["runup"]
    print(f"periodic run-up 800-6000 rpm, {len(ru['speed_rpm'])} speeds: drivedyn.run {time.perf_counter() - t0:.2f} s, "
          f"solver {res.summary['solver']['wall_time']:.2f} s, largest residual {max(ru['periodic_residual']):.2g}")


if __name__ == "__main__":
    main()
