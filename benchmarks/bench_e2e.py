"""End to end, as a person waits on it: the wall time of each command from a fresh interpreter
(a subprocess, as from a shell), and the import time of drivedyn.front.cli.

    python benchmarks/bench_e2e.py [--repeat N] [--cold]

Commands: `drivedyn --help`, `drivedyn check examples/fead-runup.toml`, `drivedyn run
examples/belt-5pk.toml -o TMP` (after a first run, so the kernels are cached), `drivedyn run
examples/fead-runup.toml --set simulation.model=rotational -o TMP` with and without
`--no-plots --no-report`, and the same pair for the toothed mesh, span and gear examples
(mesh-htd8m, span-t10, gears-split-path). Each is run --repeat times (default 3); the table gives the best and the
median. --cold also times the first `run examples/belt-5pk.toml` with NUMBA_CACHE_DIR pointing at
an empty folder (every kernel compiled: minutes on a 2-core machine). --pyc unsets
PYTHONDONTWRITEBYTECODE for the commands, so that drivedyn's modules are read from __pycache__ as
after `pip install` (which compiles them); with it set, every start compiles drivedyn's ~0.3 s of
source anew.

Not a timed test: the numbers depend on the machine and on what else runs on it (the load
average is printed with the table); compare numbers measured back to back.
"""
from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CLI = [sys.executable, "-m", "drivedyn.front.cli"]


PYC = False     # --pyc


def env(**extra) -> dict:
    e = dict(os.environ)
    if PYC:
        e.pop("PYTHONDONTWRITEBYTECODE", None)
    src = str(ROOT / "src")
    e["PYTHONPATH"] = src + (os.pathsep + e["PYTHONPATH"] if e.get("PYTHONPATH") else "")
    e.update(extra)
    return e


def wall(args, environ=None) -> float:
    """Seconds from start to exit of ``args`` in a fresh interpreter (output discarded); exits
    other than 0 (or 4/5, a failed verdict under --strict, never used here) are reported."""
    t = time.perf_counter()
    p = subprocess.run(args, cwd=ROOT, env=environ or env(), stdout=subprocess.DEVNULL,
                       stderr=subprocess.PIPE, text=True, check=False)
    dt = time.perf_counter() - t
    if p.returncode != 0:
        print(f"  ! {' '.join(map(str, args[2:]))} exited {p.returncode}: {p.stderr.strip()[-300:]}",
              file=sys.stderr)
    return dt


def import_time(environ=None) -> float:
    """drivedyn.front.cli's import, measured inside a fresh interpreter (no interpreter start-up)."""
    code = "import time; t = time.perf_counter(); import drivedyn.front.cli; print(time.perf_counter() - t)"
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=environ or env(),
                         capture_output=True, text=True, check=True).stdout
    return float(out.strip())


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--cold", action="store_true", help="also a first run from an empty kernel cache")
    ap.add_argument("--pyc", action="store_true", help="let Python cache drivedyn's bytecode, as an installed package has it")
    a = ap.parse_args(argv)
    global PYC
    PYC = a.pyc

    with tempfile.TemporaryDirectory(prefix="drivedyn-e2e-") as tmp:
        out = str(Path(tmp) / "out")
        rot = ["run", "examples/fead-runup.toml", "--set", "simulation.model=rotational", "-o", out, "-q"]
        cases = [
            ("import drivedyn.front.cli (in process)", None),
            ("drivedyn --help", ["--help"]),
            ("drivedyn check examples/fead-runup.toml", ["check", "examples/fead-runup.toml"]),
            ("drivedyn run examples/belt-5pk.toml (kernels cached)", ["run", "examples/belt-5pk.toml", "-o", out, "-q"]),
            ("run fead-runup, rotational model", rot),
            ("run fead-runup, rotational, --no-plots --no-report", rot + ["--no-plots", "--no-report"]),
        ]
        # the other analyses' examples, with and without their outputs (figures, report, netCDF)
        for ex in ("mesh-htd8m", "span-t10", "gears-split-path"):
            cmd = ["run", f"examples/{ex}.toml", "-o", out, "-q"]
            cases += [(f"run {ex}", cmd), (f"run {ex} --no-plots --no-report", cmd + ["--no-plots", "--no-report"])]
        rows = []
        if a.cold:
            cache = Path(tmp) / "numba-cache"
            cache.mkdir()
            t = wall(CLI + ["run", "examples/belt-5pk.toml", "-o", out, "-q"], env(NUMBA_CACHE_DIR=str(cache)))
            rows.append(("first run belt-5pk, empty kernel cache", [t]))
        wall(CLI + ["run", "examples/belt-5pk.toml", "-o", out, "-q"])     # warm the kernel cache
        wall(CLI + rot + ["--no-plots", "--no-report"])
        for ex in ("mesh-htd8m", "span-t10", "gears-split-path"):      # their kernels cached too
            wall(CLI + ["run", f"examples/{ex}.toml", "-o", out, "-q", "--no-plots", "--no-report"])
        for name, args in cases:
            times = [import_time() if args is None else wall(CLI + args) for _ in range(a.repeat)]
            rows.append((name, times))

    load = os.getloadavg()
    print(f"\n{sys.platform}, {os.cpu_count()} cores, load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}, "
          f"{a.repeat} runs each; bytecode {'cached' if 'PYTHONDONTWRITEBYTECODE' not in env() else 'not cached (PYTHONDONTWRITEBYTECODE)'}\n")
    w = max(len(n) for n, _ in rows)
    print(f"| {'command':<{w}} | best s | median s |")
    print(f"|{'-' * (w + 2)}|-------:|---------:|")
    for name, times in rows:
        print(f"| {name:<{w}} | {min(times):6.2f} | {statistics.median(times):8.2f} |")


if __name__ == "__main__":
    main()
