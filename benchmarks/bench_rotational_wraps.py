"""Where the rotational model departs from the segment model: the span tensions' response at the
crank's orders, against the linear model with the belt stuck to every wrap.

fead-runup's drive held at a crank speed with its 2nd and 4th orders (0.8 s, window 0.6-0.8 s). For
each span: the mean tension and the amplitude (N) and phase (deg, against the crank's speed) of
its tension at each order (the phase of Y in Re(Y e^(i W t)): negative lags), from

- the segment model (belt.segments, default "auto"),
- the rotational model (simulation.model = "rotational"),
- the linear model (belt/steady/modes.py ``drive_linear_model``: the modes' K and M with the crankshaft a
  DOF, driven at each order's frequency; the spans' and the arm's dampers; no creep, no slip, the
  one-way clutch locked), unless --no-linear.

With --two-pulley, a clean case instead: two pulleys (R 50 mm, 150 mm centres, EA 1.5e5 N, 0.1
kg/m, 800 N, fead-runup's contact law), the crank at --rpm with a 0.5 rad/s speed order at --ratio x
the stuck-belt torsional mode, the driven pulley (2e-3 kg m^2) with a --load N m load: the driven
pulley's speed over the crank's (|H|, phase) from each model. Its first flap mode (293 Hz) is clear of
the forcing.

Options make the drive closer to linear: --linear replaces the alternator's one-way clutch by a
rigid rotor and takes the arm's dry friction out; --small scales the orders by 0.1 (the amplitudes
are printed scaled back) and drops the compressor's own harmonic; --mu sets the friction
coefficient.

Run: python benchmarks/bench_rotational_wraps.py [--rpm 3000] [--segments auto] [--linear]
     [--small] [--mu 1.0] [--rotational-only]
     python benchmarks/bench_rotational_wraps.py --two-pulley [--ratio 0.6] [--load 10] [--segments auto]
(not a timed test; the segment model takes about 15 s at "auto" on a 2-core machine)
"""
import argparse
import math

import numpy as np

import drivedyn
from bench_fead_convergence import held
from drivedyn.belt.steady.modes import drive_linear_model, linear_model
from drivedyn.core.model import from_dict, to_dict


def drive(rpm, segments, linear, small, mu):
    d = to_dict(held(rpm, segments))
    names = [p["name"] for p in d["pulleys"]]
    if linear:
        alt = d["pulleys"][names.index("alternator")]
        alt["inertia"] = alt["inertia"] + alt.pop("clutch")["inertia"]
        d["pulleys"][names.index("tensioner")]["arm"]["friction"] = 0.0
    if small:
        for o in d["pulleys"][0]["speed_orders"]:
            o["amplitude"] *= 0.1
        d["pulleys"][names.index("compressor")].pop("harmonics", None)
    if mu is not None:
        d["friction"]["coefficient"] = mu
    return from_dict(d)


def amplitude(t, y, W):
    """Complex amplitude Y of y at W (y ~ Re(Y e^(i W t)) + mean), least squares over t."""
    X = np.column_stack([np.cos(W * t), np.sin(W * t), np.ones(len(t))])
    a, b, _ = np.linalg.lstsq(X, y, rcond=None)[0]
    return complex(a, -b)


def from_run(r, orders, rpm):
    """Per span: mean, and per order the complex amplitude with the crank's speed at phase 0."""
    t = r.ds["time"].values
    w = (t > 0.6 + 1e-9) & (t <= 0.8 + 1e-9)
    T = r.ds["span_tension"].values[w]
    crank = r.ds["speed"].sel(pulley="crankshaft").values[w]
    out = {}
    for k in orders:
        W = k * rpm * math.pi / 30
        ref = amplitude(t[w], crank, W)
        out[k] = np.array([amplitude(t[w], T[:, j], W) for j in range(T.shape[1])]) / ref * abs(ref)
    return T.mean(axis=0), out


def from_linear(m, tensions, orders, rpm):
    """The linear model driven by the crank's speed orders (amplitude a rad/s each)."""
    lin = drive_linear_model(m, tensions=tensions, held_as_dofs=True)
    c = lin.dofs.index("crankshaft")
    n = len(lin.dofs)
    C = np.einsum("k,ka,kb->ab", lin.span_stiffness * m.belt.axial_damping / m.belt.axial_stiffness, lin.G, lin.G)
    for p in m.pulleys:
        if p.tensioner is not None:
            a = lin.dofs.index(f"{p.name}.{'arm' if p.arm is not None else 'slider'}")
            C[a, a] += p.tensioner.damping
    amp = {o.order: o.amplitude for o in m.pulleys[0].speed_orders}
    out = {}
    f = [i for i in range(n) if i != c]
    for k in orders:
        W = k * rpm * math.pi / 30
        D = lin.K - W * W * lin.M_locked + 1j * W * C
        X = np.zeros(n, complex)
        X[c] = amp[k] / W / 1j            # crank angle whose speed is amp (phase 0)
        X[f] = np.linalg.solve(D[np.ix_(f, f)], -D[np.ix_(f, [c])][:, 0] * X[c])
        out[k] = lin.span_stiffness * (lin.G @ X)
    return out


def two_pulley(rpm, ratio, load, segments, mu):
    """The clean two-pulley case (module doc), its crank's order frequency (rad/s) and its linear
    model (the crank a DOF)."""
    EA, m, R, L, J = 1.5e5, 0.1, 0.05, 0.15, 2e-3
    lin = linear_model(_two(EA, m, R, L, J, rpm, 1.0, 0.0, "auto", mu), held_as_dofs=True)
    W = ratio * float(np.sqrt(lin.K[1, 1] / lin.M[1, 1]))
    return _two(EA, m, R, L, J, rpm, W / (rpm * math.pi / 30), load, segments, mu), W, lin


def _two(EA, m, R, L, J, rpm, order, load, segments, mu):
    w0 = rpm * math.pi / 30
    return from_dict({
        "kind": "belt-drive",
        "belt": {"mass_per_length": m, "axial_stiffness": EA, "pretension": 800.0, "segments": segments},
        "contact": {"stiffness_linear": 9.75e7, "stiffness_quadratic": 4.54e11},
        "friction": {"coefficient": 1.0 if mu is None else mu}, "gravity": 0.0,
        "simulation": {"duration": 0.6},
        "output": {"interval": 5e-5, "steady_window": [0.4, 0.6]},
        "pulleys": [{"name": "crank", "center": [0, 0], "radius": R, "speed_time": [[0, 0], [0.05, w0], [10, w0]],
                     "speed_orders": [{"order": order, "amplitude": 0.5}]},
                    {"name": "driven", "center": [L, 0], "radius": R, "inertia": J,
                     "torque_speed": [[0.0, 0.0], [w0, -load], [2 * w0, -2 * load]]}]})


def _response(r, W):
    t = r.ds["time"].values
    sel = t > 0.4
    speed = lambda p: r.ds["speed"].sel(pulley=p).values[sel]
    return amplitude(t[sel], speed("driven"), W) / amplitude(t[sel], speed("crank"), W)


def main_two_pulley(a):
    seg = a.segments if a.segments == "auto" else int(a.segments)
    m, W, lin = two_pulley(a.rpm, a.ratio, a.load, seg, a.mu)
    D = lin.K - W * W * lin.M
    rows = [("linear (stuck)", -D[1, 0] / D[1, 1], "")]
    r = drivedyn.run(drivedyn.replace(m, {"simulation.model": "rotational"}))
    rows.append(("rotational", _response(r, W), r.status))
    if not a.rotational_only:
        r = drivedyn.run(m)
        rows.append((f"segments {r.summary['belt']['segments']}", _response(r, W), r.status))
    print(f"two pulleys at {a.rpm:.0f} rpm, order at {a.ratio} x the stuck mode ({W / 2 / math.pi:.1f} Hz), "
          f"load {a.load} N m: the driven pulley's speed over the crank's (phase < 0: it lags)")
    for name, H, status in rows:
        print(f"  {name:16s} |H| {abs(H):.4f}  phase {np.degrees(np.angle(H)):6.1f} deg  {status}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rpm", type=float, default=3000.0)
    ap.add_argument("--segments", default="auto")
    ap.add_argument("--linear", action="store_true", help="clutch as a rigid rotor, no arm friction")
    ap.add_argument("--small", action="store_true", help="orders x 0.1, no compressor harmonic")
    ap.add_argument("--mu", type=float, default=None)
    ap.add_argument("--rotational-only", action="store_true")
    ap.add_argument("--no-linear", action="store_true")
    ap.add_argument("--two-pulley", action="store_true", help="the clean two-pulley case")
    ap.add_argument("--ratio", type=float, default=0.6, help="two-pulley: order over the stuck mode")
    ap.add_argument("--load", type=float, default=10.0, help="two-pulley: driven load (N m)")
    a = ap.parse_args()
    if a.two_pulley:
        return main_two_pulley(a)
    seg = a.segments if a.segments == "auto" else int(a.segments)
    m = drive(a.rpm, seg, a.linear, a.small, a.mu)
    orders = (2.0, 4.0)
    scale = 10.0 if a.small else 1.0
    rows = []
    rot = drivedyn.run(drivedyn.replace(m, {"simulation.model": "rotational"}))
    rows.append(("rotational", *from_run(rot, orders, a.rpm)))
    if not a.rotational_only:
        r = drivedyn.run(m)
        rows.insert(0, (f"segments {r.summary['belt']['segments']}", *from_run(r, orders, a.rpm)))
    if not a.no_linear:
        rows.append(("linear (stuck)", rows[0][1], from_linear(m, rows[0][1], orders, a.rpm)))
    spans = list(rot.ds["span"].values)
    print(f"fead-runup held at {a.rpm:.0f} rpm{', linear' if a.linear else ''}{', small (x10)' if a.small else ''}"
          f"{f', mu {a.mu}' if a.mu is not None else ''}: span tension mean, and |T| (N) / phase (deg) per order")
    print(f"{'span':24s}" + "".join(f" | {name:^30s}" for name, _, _ in rows))
    for j, sp in enumerate(spans):
        cells = []
        for _, mean, amp in rows:
            cells.append(f"{mean[j]:5.0f} " + " ".join(f"{scale * abs(amp[k][j]):6.1f}/{np.degrees(np.angle(amp[k][j])):4.0f}"
                                                       for k in orders))
        print(f"{sp[:24]:24s}" + "".join(f" | {c:30s}" for c in cells))


if __name__ == "__main__":
    main()
