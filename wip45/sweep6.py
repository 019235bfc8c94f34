import sys, json
sys.path.insert(0, "/work/tools")
import drivedyn
from small import small
model = sys.argv[1]; amp = float(sys.argv[2]); order = float(sys.argv[3]); extra = json.loads(sys.argv[4]) if len(sys.argv) > 4 else {}
for rpm in range(1500, 2601, 100):
    m = small(float(rpm), amp=amp, order=order)
    m = drivedyn.replace(m, {"belt.segments": 452} if model == "segments" else {"simulation.model": "rotational"})
    if extra: m = drivedyn.replace(m, extra)
    r = drivedyn.run(m)
    row = {sp: 0.5 * (v["tension_max"] - v["tension_min"]) for sp, v in r.summary["spans"].items()}
    a = r.summary["tensioners"]["tensioner"]
    print(rpm, " ".join(f"{v:7.2f}" for v in row.values()), f"arm {1e3*(a['travel_max']-a['travel_min']):.3f} mrad", flush=True)
