"""Convergence of the accessory drive's answers in the number of segments: the six-pulley drive of
examples/fead-runup.toml held at a constant crank speed with its 2nd/4th orders (0.8 s, window
0.6-0.8 s): every pulley's slip, the crank-compressor span's tension band, the arm's travel, the
contact damping and the transmission efficiency (the losses converge as 1 / n^2: 136 / 98 / 90 W at
333 / 666 / 1332 segments at 3000 rpm), the wall time and the status, per resolution; and, without
orders, the slips against steady creep theory.

Run: python benchmarks/bench_fead_convergence.py [--rpm 3000] [--segments 150 300 600]
(not a timed test; numbers depend on the machine)
"""
import argparse
import math

import drivedyn
from drivedyn.core.model import from_dict, to_dict


def fead_belt() -> dict:
    """examples/fead-runup.toml's belt, contact and friction sections (SI), for drives built around them."""
    d = to_dict(drivedyn.load(drivedyn.example_path("fead-runup")))
    return {k: d[k] for k in ("belt", "contact", "friction")}


def held(rpm: float, segments, orders: bool = True, duration: float = 0.8):
    d = to_dict(drivedyn.load(drivedyn.example_path("fead-runup")))
    w = -rpm * math.pi / 30
    crank = d["pulleys"][0]
    crank["speed_time"] = [[0.0, 0.0], [0.3, w], [duration, w]]
    if not orders:
        crank.pop("speed_orders", None)
        for p in d["pulleys"]:
            p.pop("harmonics", None)
    d["belt"]["segments"] = segments
    d["simulation"]["duration"] = duration
    d["output"].update(runup_bin=None, steady_window=[duration - 0.2, duration])
    return from_dict(d)


def row(r):
    s = r.summary
    names = list(s["pulleys"])
    slips = " / ".join(f"{100 * s['pulleys'][n]['slip']:.3f}" for n in names[1:])
    sp = next(iter(s["spans"].values()))
    arm = next(iter(s.get("tensioners", {}).values()), {})
    travel = (arm.get("travel_max", math.nan) - arm.get("travel_min", math.nan)) * 180 / math.pi
    codes = ",".join(d.code for d in r.diagnostics) or "-"
    pw = s.get("power", {})
    return (f"{s['belt']['segments']:5d} {s['solver']['wall_time']:7.1f} {slips:>44s} "
            f"{sp['tension_min']:6.0f}-{sp['tension_max']:<6.0f} {travel:6.2f} "
            f"{pw.get('losses', {}).get('contact_damping', math.nan):7.1f} {pw.get('efficiency', math.nan):6.4f} "
            f"{r.status}:{codes}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rpm", type=float, default=3000.0)
    ap.add_argument("--segments", nargs="+", default=["auto", "150", "300", "600"], help="counts or auto")
    ap.add_argument("--no-orders", action="store_true")
    a = ap.parse_args()
    drivedyn.run(drivedyn.replace(held(a.rpm, 150), {"simulation.duration": 0.01, "output.steady_window": None}))   # compile
    print(f"held at {a.rpm:.0f} rpm, {'no orders' if a.no_orders else 'orders 2 and 4'}")
    names = None
    for n in a.segments:
        r = drivedyn.run(held(a.rpm, n if n == "auto" else int(n), orders=not a.no_orders))
        if names is None:
            names = list(r.summary["pulleys"])[1:]
            print(f"{'n':>5s} {'wall s':>7s} {'slip %: ' + ' / '.join(names):>44s} {'span 1 min-max N':>14s} "
                  f"{'arm deg':>6s} {'cont. W':>7s} {'effic.':>6s} status")
        print(row(r), flush=True)
    if a.no_orders:
        from drivedyn.belt.steady.creep import steady_state
        st = steady_state(held(a.rpm, "auto", orders=False))
        print("steady creep theory, slip %:", " / ".join(f"{100 * (1 - abs(st.pulleys[n].speed_ratio)):.3f}" for n in names))


if __name__ == "__main__":
    main()
