"""FEAD cost: the six-pulley run-up example with its tensioner arm, overrunning clutch and engine
orders, against the same drive with the tensioner pulley fixed where the arm holds it at rest, no
clutch and no orders (the fixed-idler drive of the same size); and the whole run-up.

Run: python benchmarks/bench_fead.py   (not a timed test; numbers depend on the machine)
"""
import time

import drivedyn
from drivedyn.belt.segments.system import build
from drivedyn.core.model import from_dict, to_dict


def per_step(model, repeat=3):
    best = None
    for _ in range(repeat):
        r = drivedyn.run(model)
        s = r.summary["solver"]
        us = s["wall_time"] / s["steps"] * 1e6
        best = us if best is None else min(best, us)
    return best, s


def main():
    full = drivedyn.load(drivedyn.example_path("fead-runup"))
    idle = drivedyn.replace(full, {"simulation.duration": 0.6, "output.runup_bin": None})
    d = to_dict(idle)
    rest = build(idle, settle=False).rest
    for p in d["pulleys"]:
        p.pop("speed_orders", None)
        p.pop("clutch", None)
        if p.get("arm"):
            p.pop("arm")
            p["center"] = list(rest.model.pulleys[5].center)     # held where the arm holds it at rest
    fixed = from_dict(d)
    drivedyn.run(drivedyn.replace(idle, {"simulation.duration": 0.01}))
    drivedyn.run(drivedyn.replace(fixed, {"simulation.duration": 0.01}))
    t0 = time.perf_counter()
    build(idle)
    t_build = time.perf_counter() - t0
    t0 = time.perf_counter()
    build(fixed)
    t_build_fixed = time.perf_counter() - t0
    a, sa = per_step(idle)
    b, sb = per_step(fixed)
    print(f"FEAD 6 pulleys, {idle.belt.segments} segments, step {sa['step'] * 1e6:.3f} us, 0.6 s at idle:")
    print(f"  tensioner arm + clutch + orders: {a:.2f} us/step, {a * 1e-6 / sa['step']:.2f} s wall per simulated s, build {t_build:.2f} s")
    print(f"  fixed idler, no clutch, no orders: {b:.2f} us/step, {b * 1e-6 / sb['step']:.2f} s wall per simulated s, build {t_build_fixed:.2f} s")
    print(f"  ratio (tensioner drive / fixed drive) per step: {a / b:.3f}")
    t0 = time.perf_counter()
    r = drivedyn.run(full)
    wall = time.perf_counter() - t0
    s = r.summary["solver"]
    print(f"whole run-up 800-5000 rpm, {s['simulated_time']:.1f} s simulated: {wall:.1f} s wall (integration "
          f"{s['wall_time']:.1f} s, {s['wall_time'] / s['simulated_time']:.2f} s per simulated s), status {r.status}")


if __name__ == "__main__":
    main()
