import sys
sys.path.insert(0, "/work/tools")
import drivedyn
from small import small
for model in sys.argv[1:]:
    m = small(2000.0, amp=0.0)
    m = drivedyn.replace(m, {"belt.segments": 452} if model == "segments" else {"simulation.model": "rotational"})
    r = drivedyn.run(m)
    print(model, {p: round(100 * v["slip"], 4) for p, v in r.summary["pulleys"].items()}, {s: round(v["tension_mean"], 2) for s, v in r.summary["spans"].items()})
