"""Span stability speed: wall time of a 200 x 200 Floquet chart (seed 002 T10 span, full Phi).

Run: python benchmarks/bench_span.py   (not a timed test; numbers depend on the machine)
"""
import statistics
import time

import numpy as np

import drivedyn
from drivedyn.span.analysis import tooth_force_harmonics
from drivedyn.mechanics.span.floquet import floquet_chart
from drivedyn.span.source import resolve


def chart(setup, harm, F0, V, steps=48):
    t = time.perf_counter()
    rho, _ = floquet_chart(F0, V, setup.span, harm.f1, harm.shape(), setup.teeth, setup.pitch, setup.convention, steps)
    return time.perf_counter() - t, rho


def main():
    model = drivedyn.load(drivedyn.example_path("span-t10"))
    setup = resolve(model)
    harm = tooth_force_harmonics(model, setup)
    K = len(harm.amplitudes)
    t0 = time.perf_counter()
    chart(setup, harm, np.linspace(10, 20, 3), np.linspace(1, 2, 3))
    print(f"first call (numba compile or cache load): {time.perf_counter() - t0:.2f} s")
    cases = [("full chart F0 0-300 N x V 0-70 m/s", np.linspace(0, 300, 200), np.linspace(0, 70, 200)),
             ("zoomed tongue F0 80-120 N x V 0.9-1.3 m/s", np.linspace(80, 120, 200), np.linspace(0.9, 1.3, 200)),
             ("low speeds F0 0-300 N x V 0.1-3 m/s (tongues n = 1..10)", np.linspace(0, 300, 200), np.linspace(0.1, 3, 200))]
    for name, F0, V in cases:
        walls = [chart(setup, harm, F0, V)[0] for _ in range(3)]
        print(f"200 x 200 Floquet, {K} harmonics, 48 RK4 steps/oscillation, {name}: "
              f"wall min/median {min(walls):.3f}/{statistics.median(walls):.3f} s")
    t = time.perf_counter()
    drivedyn.run(model)
    print(f"drivedyn.run(span-t10) (200x200 chart + 160x160 zoom, bands, frequencies): {time.perf_counter() - t:.2f} s")


if __name__ == "__main__":
    main()
