"""examples/study-oval-crank.toml: the design study's wall (drivedyn study, two local workers), then the
round sprocket (ovality 0) and the best oval side by side through the run-up: each span's 2nd-order
tension amplitude per crank-speed bin (the periodic run-up's order cuts, results.nc runup_tension_order).
`python benchmarks/bench_oval_crank.py [--out DIR]`"""
import argparse
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import drivedyn


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    out = Path(a.out or tempfile.mkdtemp()) / "study-oval-crank"
    study = Path(__file__).resolve().parents[1] / "examples" / "study-oval-crank.toml"
    t0 = time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "drivedyn", "study", str(study), "-o", str(out)], capture_output=True,
                          text=True)
    wall = time.perf_counter() - t0
    print(done.stdout[-900:])
    print(f"drivedyn study wall: {wall:.1f} s")
    best = drivedyn.load(out / "best.toml")
    round_ = drivedyn.replace(best, {"pulleys.CRK.pitch_curve.ovality": 0.0})
    rows = {}
    for name, m in (("round", round_), ("oval", best)):
        res = drivedyn.run(m)
        rows[name] = res.ds["runup_tension_order"].sel(order=2.0)
    spans = list(rows["round"]["span"].values)
    print("crank rpm  " + "  ".join(f"{s:>19s}" for s in spans) + "   (2nd order, N: round / oval)")
    for i, rpm in enumerate(rows["round"]["runup_speed"].values if "runup_speed" in rows["round"].coords
                            else rows["round"][rows["round"].dims[0]].values):
        cells = "  ".join(f"{float(rows['round'][i, q]):8.1f} / {float(rows['oval'][i, q]):8.1f}" for q in range(len(spans)))
        print(f"{float(rpm):9.0f}  {cells}")


if __name__ == "__main__":
    main()
