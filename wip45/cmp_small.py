import sys, json, time
sys.path.insert(0, "/work/tools")
import drivedyn
from small import small
ref = json.load(open(sys.argv[1]))
worst = 0
for rpm, rf in ref.items():
    m = drivedyn.replace(small(float(rpm)), {"simulation.model": "rotational", **json.loads(sys.argv[2] if len(sys.argv) > 2 else "{}")})
    t = time.perf_counter(); rr = drivedyn.run(m); w = time.perf_counter() - t
    print(rpm, rr.status, [d.code for d in rr.diagnostics], f"{w:.2f} s")
    for sp, b in rf["spans"].items():
        a = rr.summary["spans"][sp]
        d = [100 * (a[q] - b[q]) / b[q] for q in ("tension_min", "tension_mean", "tension_max")]
        worst = max(worst, max(abs(x) for x in d))
        print(f"  {sp:22s} " + " ".join(f"{a[q]:7.1f}/{b[q]:7.1f} ({x:+.1f} %)" for q, x in zip(("tension_min", "tension_mean", "tension_max"), d)))
    print("  slip", {p: f"{100*rr.summary['pulleys'][p]['slip']:.3f}/{100*v:.3f}" for p, v in rf["slip"].items()})
    a = rr.summary["tensioners"]["tensioner"]
    print("  arm", a["travel_max"] - a["travel_min"], rf["arm"][1] - rf["arm"][0])
print("worst", worst)
