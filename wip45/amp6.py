import sys, json
sys.path.insert(0, "/work/tools")
import drivedyn, numpy as np
from small import small
model = sys.argv[1]; rpm = float(sys.argv[2]); order = float(sys.argv[3])
for ex in sys.argv[4:]:
    m = small(rpm, amp=0.3, order=order)
    m = drivedyn.replace(m, {"belt.segments": 452} if model == "segments" else {"simulation.model": "rotational"})
    m = drivedyn.replace(m, json.loads(ex))
    r = drivedyn.run(m)
    ds = r.ds; t = ds.time.values; sel = t > 0.4
    T = ds.span_tension.values[sel]; tt = t[sel]
    f = order * rpm / 60
    amps = []
    for j in range(T.shape[1]):
        y = T[:, j] - T[:, j].mean()
        c = 2 * np.mean(y * np.exp(-2j * np.pi * f * tt))
        rest = y - np.real(c * np.exp(2j * np.pi * f * tt))
        amps.append(f"{abs(c):6.2f} (rest rms {rest.std():5.2f})")
    q = ds.arm_travel.values[sel, 0] if "arm_travel" in ds else ds.arm_angle.values[sel, 0]
    cq = 2 * np.mean((q - q.mean()) * np.exp(-2j * np.pi * f * tt))
    print(model, rpm, ex, " | ".join(amps), f"arm {1e3*abs(cq):.3f}", flush=True)
