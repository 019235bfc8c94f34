"""The share of a default `drivedyn run examples/belt-5pk.toml` spent writing its outputs
(results.nc, summary.json, the plots, report.html), as a user sees it: each run in a fresh
interpreter, timed from the start of the script to the end of the command; "outputs" is the time
from the end of the solve (drivedyn.run returning) to the end.

Run: python benchmarks/bench_outputs.py [example] [runs]   (not a timed test; numbers depend on
the machine and on what else runs on it: compare numbers measured back to back)
"""
import json
import statistics
import subprocess
import sys
import time

T0 = time.perf_counter()


def one(example):
    """One `drivedyn run EXAMPLE -o tmp -q` in this process; prints its timings as JSON."""
    import contextlib
    import io
    import tempfile

    from drivedyn import api
    from drivedyn.front import cli

    marks = {}
    run = api.run

    def timed_run(*a, **k):
        try:
            return run(*a, **k)
        finally:
            marks["solved"] = time.perf_counter() - T0

    api.run = timed_run
    with tempfile.TemporaryDirectory() as out, contextlib.redirect_stdout(io.StringIO()), \
            contextlib.redirect_stderr(io.StringIO()):
        code = cli.main(["run", str(api.example_path(example)), "-o", out, "-q"])
        end = time.perf_counter() - T0
    print(json.dumps({"code": code, "total": end, "outputs": end - marks["solved"]}))


def main(example="belt-5pk", runs=3):
    rows = []
    for _ in range(int(runs)):
        p = subprocess.run([sys.executable, __file__, "--one", example], capture_output=True, text=True, check=True)
        rows.append(json.loads(p.stdout.strip().splitlines()[-1]))
    for r in rows:
        print(f"  total {r['total']:.2f} s, outputs {r['outputs']:.2f} s ({100 * r['outputs'] / r['total']:.0f} %)")
    total = statistics.median(r["total"] for r in rows)
    outputs = statistics.median(r["outputs"] for r in rows)
    share = statistics.median(r["outputs"] / r["total"] for r in rows)
    print(f"{example}, median of {len(rows)}: run {total:.2f} s, outputs {outputs:.2f} s, "
          f"{100 * share:.0f} % of the run")


if __name__ == "__main__":
    if sys.argv[1:2] == ["--one"]:
        one(sys.argv[2])
    else:
        main(*sys.argv[1:])
