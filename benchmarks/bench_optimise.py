"""Design by optimisation at scale: N designs of examples/study-tensioner-design.toml on local workers.

Run: python benchmarks/bench_optimise.py [N] [--workers 2] [--one-design]
(not a timed test; numbers depend on the machine and on what else runs on it)

The study is the example (differential evolution over the tensioner's preload, rate, friction and
damping; each design a periodic run-up of the rotational model, 17 crank-speed bins) with its
budget set to N designs (default 1000), run by ``run_optimisation`` on a fresh output folder (empty
cache) and a LocalCluster of single-threaded worker processes started beforehand (its start-up is
reported apart). Reported: the study's wall time from the call to the written study.nc, the CPU
time of the workers and of this process (scheduler, client, differential evolution, the Dataset)
per design, the best design and its objective (to compare two versions of the code: the same
designs must give the same digits).

``--one-design``: the example's base design (the shipped tensioner) evaluated the way a worker
evaluates a case (``study.cases.run_case``), on one core: CPU per design, median of repeats.
"""
import argparse
import resource
import statistics
import tempfile
import time
from pathlib import Path

import drivedyn
from drivedyn.study import load_study


def cpu_self(dask_worker=None):
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def study_text(n: int) -> str:
    src = drivedyn.example_path("study-tensioner-design")
    text = src.read_text()
    text = text.replace('base = "fead-runup.toml"', f'base = "{drivedyn.example_path("fead-runup").as_posix()}"')
    return text.replace("budget = 80", f"budget = {n}")


def many(n: int, workers: int):
    from distributed import Client

    from drivedyn.study.execute import _local_cluster, run_optimisation

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "study.toml"
        path.write_text(study_text(n))
        study = load_study(path)
        t0 = time.perf_counter()
        cluster = _local_cluster(workers)      # the one a study starts
        client = Client(cluster)
        t1 = time.perf_counter()
        try:
            w0 = sum(client.run(cpu_self).values())
            c0 = cpu_self()
            t2 = time.perf_counter()
            run = run_optimisation(study, Path(tmp) / "out", client=client, plots=False)
            wall = time.perf_counter() - t2
            c1 = cpu_self()
            w1 = sum(client.run(cpu_self).values())
        finally:
            client.close()
            cluster.close()
        o = run.optimum
        ds = run.ds
        nd = len(o.evaluations)
        print(f"{nd} designs on {workers} worker(s): study wall {wall:.1f} s ({wall / nd * 1e3:.1f} ms per design; "
              f"cluster start {t1 - t0:.1f} s apart)")
        print(f"  CPU per design: workers {(w1 - w0) / nd * 1e3:.1f} ms, this process {(c1 - c0) / nd * 1e3:.1f} ms, "
              f"total {((w1 - w0) + (c1 - c0)) / nd * 1e3:.1f} ms; case wall median "
              f"{statistics.median(ds['wall_time'].values) * 1e3:.1f} ms")
        print("  statuses: " + ", ".join(f"{k} {v}" for k, v in run.counts.items() if isinstance(v, int) and v
                                         and k in ("success", "warning", "failed", "invalid", "error", "lost", "missing")))
        print(f"  feasible {int(ds['feasible'].sum())}; best {study.spec.optimise.objective} = {o.objective:.6g}")
        for k, v in (o.values or {}).items():
            print(f"    {k} = {v:.6g}")
        return wall, o


def one(repeats: int = 5):
    """CPU of one design the way a worker runs it (the record, the cache folder), on this core."""
    from drivedyn.study.cases import TOKEN, resolve, run_case, warm_worker
    from drivedyn.study.design import Design, overrides_of

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "study.toml"
        path.write_text(study_text(20))
        study = load_study(path)
        labels = [p.label for p in study.spec.parameters]
        base = {"pulleys.tensioner.arm.preload": 20.0, "pulleys.tensioner.arm.rate": 30.0,
                "pulleys.tensioner.arm.friction": 2.0, "pulleys.tensioner.arm.damping": 0.1}
        warm_worker("belt-drive")
        cache = Path(tmp) / "cases"
        cache.mkdir()
        (cache / TOKEN).write_text("bench")
        times = []
        for i in range(repeats + 1):
            vals = dict(base, **{"pulleys.tensioner.arm.preload": 20.0 + 0.01 * i})    # a new model each time
            case = resolve(study, Design(labels, False, {}, [{k: vals[k] for k in labels}]), overrides_of)[0]
            extra = {"keys": case.keys} if getattr(case, "keys", None) else {}
            c = time.process_time()
            rec = run_case(case.toml, case.key, str(cache), "bench", [], None, study.spec.eval_mode, **extra)
            times.append(time.process_time() - c)
        times = times[1:]
        print(f"one design as a worker runs it: CPU median {statistics.median(times) * 1e3:.0f} ms "
              f"(min {min(times) * 1e3:.0f}, max {max(times) * 1e3:.0f}, {repeats} designs); status {rec['status']}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("n", nargs="?", type=int, default=1000, help="designs (the study's budget)")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--one-design", action="store_true", help="one design's CPU on one core only")
    a = ap.parse_args()
    print(f"drivedyn from {Path(drivedyn.__file__).parent}")
    # fill numba's disk cache (the workers load the compiled kernels from it)
    base = drivedyn.load(drivedyn.example_path("fead-runup"))
    drivedyn.run(drivedyn.replace(base, {"simulation.model": "rotational", "simulation.runup": "periodic"}))
    if a.one_design:
        one()
        return
    many(a.n, a.workers)


if __name__ == "__main__":
    main()
