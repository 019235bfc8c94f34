"""Where the time of a default `drivedyn run examples/belt-5pk.toml` goes: solving against writing
the outputs (results.nc + summary.json, each plot, report.html).

Run: python benchmarks/bench_outputs.py [example]   (not a timed test; numbers depend on the machine)
"""
import sys
import tempfile
import time
from pathlib import Path

import drivedyn
from drivedyn import plotting


def main(name="belt-5pk"):
    model = drivedyn.load(drivedyn.example_path(name))
    drivedyn.run(drivedyn.replace(model, {"simulation.duration": 0.01}))      # kernels loaded once
    out = Path(tempfile.mkdtemp())
    t0 = time.perf_counter()
    r = drivedyn.run(model)
    t_run = time.perf_counter() - t0
    t0 = time.perf_counter()
    r.save(out)
    t_save = time.perf_counter() - t0
    times = {}
    orig = plotting.save

    def timed_save(fig, path, *a, **k):      # the time each figure takes to draw and write
        t = time.perf_counter()
        p = orig(fig, path, *a, **k)
        times[Path(path).name] = time.perf_counter() - t
        return p

    plotting.save = timed_save
    t0 = time.perf_counter()
    files = drivedyn.api.plot(r, out)
    t_plot = time.perf_counter() - t0
    plotting.save = orig
    t0 = time.perf_counter()
    from drivedyn.report import write_report

    write_report(r, out, files, model=model)
    t_report = time.perf_counter() - t0
    total = t_run + t_save + t_plot + t_report
    print(f"{name}: run {t_run:.2f} s, save {t_save:.2f} s, plots {t_plot:.2f} s ({len(files)} files), "
          f"report {t_report:.2f} s; outputs {100 * (total - t_run) / total:.0f} % of {total:.2f} s")
    for k, v in sorted(times.items(), key=lambda kv: -kv[1]):
        print(f"  {k:22s} {v:.2f} s (savefig, in this process)")
    # as the command line does it: the figures drawn in two forked processes while this one
    # writes results.nc, then report.html
    out2 = Path(tempfile.mkdtemp())
    t0 = time.perf_counter()
    files = drivedyn.api.plot(r, out2, meanwhile=lambda: r.save(out2))
    write_report(r, out2, files, model=model)
    t_out = time.perf_counter() - t0
    print(f"{name} as `drivedyn run` writes them: outputs {t_out:.2f} s, {100 * t_out / (t_run + t_out):.0f} % of "
          f"{t_run + t_out:.2f} s")
    gif = [f for f in files if f.suffix == ".gif"]
    if gif:
        print(f"  animation: {', '.join(f.name for f in gif)} (written outside plotting.save)")


if __name__ == "__main__":
    main(*sys.argv[1:])
