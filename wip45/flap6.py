import sys, json
sys.path.insert(0, "/work/tools")
import drivedyn, numpy as np
from small import small
rpm = float(sys.argv[1])
C = np.array([[0, 0], [0.3, 0.0], [0.15, 0.15]]); R = np.array([0.07, 0.03, 0.035])
for ex in sys.argv[2:]:
    m = small(rpm, amp=0.3, order=6)
    m = drivedyn.replace(m, {"belt.segments": 452, "output.frames": 3000, **json.loads(ex)})
    r = drivedyn.run(m)
    ds = r.ds
    t = ds.frame_time.values; sel = t > 0.4
    X = ds.belt_x.values[sel]; Y = ds.belt_y.values[sel]
    x0, y0 = X[0], Y[0]
    dist = np.sqrt((x0[:, None] - C[:, 0]) ** 2 + (y0[:, None] - C[:, 1]) ** 2) - R
    free = dist.min(1) > 0.003
    pts = np.stack([x0[free], y0[free]], 1)
    # cluster free nodes into 3 lines by nearest pair of pulleys' midpoint
    mids = {"crank-alt": 0, "alt-ten": 1, "ten-crank": 2}
    pairs = [(0, 1), (1, 2), (2, 0)]
    lab = np.argmin([np.linalg.norm(pts - 0.5 * (C[a] + C[b]), axis=1) for a, b in pairs], axis=0)
    out = []
    for s, (a, b) in enumerate(pairs):
        q = pts[lab == s]
        P = q.mean(0); u, sv, vt = np.linalg.svd(q - P); d = vt[0]; nrm = np.array([-d[1], d[0]])
        offs = []
        for k in range(X.shape[0]):
            rel = np.stack([X[k] - P[0], Y[k] - P[1]], 1)
            near = (np.abs(rel @ d) < 0.01) & (np.abs(rel @ nrm) < 0.02)
            if near.any():
                offs.append(np.mean((rel @ nrm)[near]))
        offs = np.array(offs)
        out.append(f"{list(mids)[s]} std {1e3*offs.std():.4f} mm range {1e3*(offs.max()-offs.min()):.4f} mm")
    print(ex, "; ".join(out), flush=True)
