"""Benchmark: `check` of the belt design layer (creep-theory steady state + slip margins + modes).

Run: PYTHONPATH=src python benchmarks/bench_steady.py
"""
import time

from drivedyn.belt.statics import check_data
from drivedyn.model import load


def bench(path, repeat=20):
    m = load(path)
    check_data(m)                                   # imports, first call
    t = time.perf_counter()
    for _ in range(repeat):
        check_data(m)
    return (time.perf_counter() - t) / repeat * 1e3


if __name__ == "__main__":
    for p in ("examples/belt-accessory.toml", "examples/belt-5pk.toml"):
        print(f"{p}: steady state + margins + modes {bench(p):.1f} ms")
