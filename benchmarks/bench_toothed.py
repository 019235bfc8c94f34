"""Wall time of one full engagement at 1000 angles (HTD 8M belt, 24-tooth HTD 8M pulley).

Run: python benchmarks/bench_toothed.py. The first call compiles the numba kernel (cached on
disk afterwards); the timed calls do not include it.
"""
import time

import numpy as np

from drivedyn.mechanics.teeth import catalogue
from drivedyn.toothed.engagement import sweep
from drivedyn.mechanics.teeth.pair import build


def main():
    for belt, pulley, z, groove in (("HTD8M", "HTD8M", 24, "standard"), ("L", "L", 20, "standard"),
                                    ("HTD8M", "HTD8M", 24, "generated")):
        pair = build(catalogue.tooth(belt), pulley, None, z, groove, None, 0.0, 0.0, 2e-7, 2e-5)
        sweep(pair, 11)  # warm-up (kernel compilation, imports)
        times = []
        for _ in range(3):
            t0 = time.perf_counter()
            sw = sweep(pair, 1000)
            times.append(time.perf_counter() - t0)
        print(f"{belt} on {pulley} z{z} {groove:9s}: 1000 angles, {len(sw.flank.uv)} flank samples, "
              f"{len(sw.pulley.exterior.coords)} pulley vertices: best {min(times):.3f} s "
              f"(median {np.median(times):.3f} s); max overlap {sw.out['area'].max() * 1e6:.4f} mm^2")


if __name__ == "__main__":
    main()
