import sys, time, math
import drivedyn
from drivedyn.model import from_dict
def small(rpm=2000.0, law="elastic-plastic", dur=0.6, amp=3.0, order=2):
    w = -rpm * math.pi / 30
    return from_dict({
        "kind": "belt-drive",
        "belt": {"mass_per_length": 0.115, "axial_stiffness": 1.82e5, "axial_damping": 0.197, "bending_stiffness": 2.5e-4, "pretension": 350.0, "segments": "auto"},
        "contact": {"stiffness_linear": 9.75e7, "stiffness_quadratic": 4.54e11, "damping": 4.5e4},
        "friction": {"law": law, "coefficient": 1.0, "displacement_limit": 1e-4},
        "simulation": {"duration": dur},
        "output": {"interval": 2e-4, "steady_window": [dur - 0.2, dur]},
        "pulleys": [
            {"name": "crank", "center": [0, 0], "radius": 0.07, "speed_time": [[0, 0], [0.3, w], [dur, w]],
             "speed_orders": [{"order": order, "amplitude": amp}]},
            {"name": "alternator", "center": [0.3, 0.0], "radius": 0.03, "inertia": 2e-3, "torque": 2.0, "drag": 0.1},
            {"name": "tensioner", "center": [0.15, 0.15], "radius": 0.035, "inertia": 1e-4,
             "arm": {"pivot": [0.07, 0.15], "inertia": 2e-3, "preload": 25.0, "rate": 40.0, "damping": 0.05}}]})
if __name__ == '__main__':
  rpm = float(sys.argv[1]); law = sys.argv[2] if len(sys.argv) > 2 else "elastic-plastic"
  m = small(rpm, law)
  ra = drivedyn.run(m); n = ra.summary["belt"]["segments"]
  t = time.perf_counter(); rs = drivedyn.run(drivedyn.replace(m, {"belt.segments": 2 * n})); ws = time.perf_counter() - t
  t = time.perf_counter(); rr = drivedyn.run(drivedyn.replace(m, {"simulation.model": "rotational"})); wr = time.perf_counter() - t
  print(rpm, law, n, rs.status, [d.code for d in rs.diagnostics], rr.status, [d.code for d in rr.diagnostics], f"{ws:.1f} s / {wr:.2f} s")
  for sp in rs.summary["spans"]:
      a, b = rr.summary["spans"][sp], rs.summary["spans"][sp]
      print(f"  {sp:22s} " + " ".join(f"{a[q]:7.1f}/{b[q]:7.1f} ({100*(a[q]-b[q])/b[q]:+.1f} %)" for q in ("tension_min", "tension_mean", "tension_max")))
  for p in rs.summary["pulleys"]:
      print(f"  {p:12s} slip {100*rr.summary['pulleys'][p]['slip']:.4f} / {100*rs.summary['pulleys'][p]['slip']:.4f}")
  a, b = rr.summary["tensioners"]["tensioner"], rs.summary["tensioners"]["tensioner"]
  print("  arm", a["travel_max"] - a["travel_min"], b["travel_max"] - b["travel_min"])
