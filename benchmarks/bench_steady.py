"""Benchmark: `check` of the belt design layer (creep-theory steady state + slip margins + modes).

Run: PYTHONPATH=src python benchmarks/bench_steady.py
"""
import time

from drivedyn.belt.statics import check_data
from drivedyn.core.model import load


def bench(path, repeat=20):
    m = load(path)
    check_data(m)                                   # imports, first call
    t = time.perf_counter()
    for _ in range(repeat):
        check_data(m)
    return (time.perf_counter() - t) / repeat * 1e3


def bench_fead(repeat=10):
    """The six-pulley FEAD with its tensioner: the static equilibrium of belt and arm (discrete
    placements), then the steady state with the arm at its running balance + margins + modes."""
    from drivedyn.belt.steady.modes import modes
    from drivedyn.belt.steady.creep import steady_state
    from drivedyn.belt.geometry.tensioner import equilibrium
    from drivedyn.belt.steady.running import running

    m = load("examples/fead-runup.toml")
    t = time.perf_counter()
    rest = equilibrium(m)
    t_rest = time.perf_counter() - t
    t = time.perf_counter()
    for _ in range(repeat):
        q, m_run, lay, st = running(m, rest)
    t_run = (time.perf_counter() - t) / repeat
    t = time.perf_counter()
    for _ in range(repeat):
        steady_state(m_run, lay)
        modes(m_run, lay)
    t_sm = (time.perf_counter() - t) / repeat
    print(f"examples/fead-runup.toml (6 pulleys, tensioner): static equilibrium {t_rest * 1e3:.0f} ms, running "
          f"balance of the arm {t_run * 1e3:.0f} ms, steady state + margins + modes at it {t_sm * 1e3:.1f} ms")


if __name__ == "__main__":
    for p in ("examples/belt-accessory.toml", "examples/belt-5pk.toml"):
        print(f"{p}: steady state + margins + modes {bench(p):.1f} ms")
    bench_fead()
