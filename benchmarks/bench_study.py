"""Study scaling: wall time of a 16-case belt-drive study on 1 and on 2 local Dask workers.

Run: python benchmarks/bench_study.py [duration_s]   (not a timed test; numbers depend on the machine)

The study is the 5PK drive, pretension (400..800 N) x load torque (5..15 N m), 4 x 4 cases of
``duration`` simulated seconds (default 0.5 s), every case successful. Each worker count gets a
fresh output folder (empty cache) and its own LocalCluster; the time of the study is measured from
submission to the written study.nc, and the cluster start-up is reported apart.
"""
import statistics
import sys
import tempfile
import time
from pathlib import Path

from distributed import Client

import drivedyn
from drivedyn.study import load_study, run_study
from drivedyn.study.execute import _local_cluster

STUDY = """
name = "bench: 5PK pretension x load torque"
base = "{base}"
[overrides]
"simulation.duration" = {duration}
"output.frames" = 2
"output.segments" = []
[[parameters]]
path = "belt.pretension"
range = ["400 N", "800 N"]
num = 4
[[parameters]]
name = "load_torque"
path = ["pulleys.driver.torque_time.1.1", "pulleys.driven.torque_speed.0.1", "pulleys.driven.torque_speed.1.1"]
factors = [-1, 1, -1]
unit = "N*m"
range = ["5 N*m", "15 N*m"]
num = 4
[outputs]
summary = ["pulleys.driven.slip", "spans.*.tension_mean"]
"""


def bench(study_path, workers, tmp):
    t0 = time.perf_counter()
    cluster = _local_cluster(workers)      # the one a study starts
    client = Client(cluster)
    t1 = time.perf_counter()
    try:
        res = run_study(study_path, out=Path(tmp) / f"w{workers}", client=client, plots=False)
        t2 = time.perf_counter()
    finally:
        client.close()
        cluster.close()
    assert res.counts["success"] == 16, res.counts
    per_case = res.ds["wall_time"].values.ravel()
    return t1 - t0, t2 - t1, per_case


def main():
    duration = float(sys.argv[1]) if len(sys.argv) > 1 else 0.5
    base = drivedyn.example_path("belt-5pk")
    drivedyn.run(drivedyn.replace(drivedyn.load(base), {"simulation.duration": 0.005}))  # fill numba's disk cache
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "study.toml"
        path.write_text(STUDY.format(base=base.as_posix(), duration=duration))
        load_study(path)
        times = {}
        for w in (1, 2):
            start, wall, per_case = bench(path, w, tmp)
            times[w] = wall
            print(f"{w} worker(s): study {wall:6.2f} s for 16 cases of {duration:g} s simulated "
                  f"(cluster start {start:.2f} s); per case median {statistics.median(per_case):.2f} s, "
                  f"min {per_case.min():.2f} s, max {per_case.max():.2f} s")
        print(f"speed-up 1 -> 2 workers: {times[1] / times[2]:.2f}x")


if __name__ == "__main__":
    main()
