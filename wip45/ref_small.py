# segment-model references for the three-pulley drive (2x auto segments), stored as JSON
import sys, json
sys.path.insert(0, "/work/tools")
import drivedyn
from small import small
out = {}
for rpm in [float(x) for x in sys.argv[1].split(",")]:
    m = small(rpm)
    n = drivedyn.run(m).summary["belt"]["segments"]
    rs = drivedyn.run(drivedyn.replace(m, {"belt.segments": 2 * n}))
    out[str(rpm)] = {"spans": rs.summary["spans"], "slip": {p: v["slip"] for p, v in rs.summary["pulleys"].items()},
                     "arm": [rs.summary["tensioners"]["tensioner"]["travel_min"], rs.summary["tensioners"]["tensioner"]["travel_max"]]}
    print(rpm, flush=True)
json.dump(out, open(sys.argv[2], "w"), default=float)
