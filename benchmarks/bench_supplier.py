"""The supplier's accessory-drive report of examples/fead-ag0868.toml (belt/supplier.py): the static
tables (catalogue, position table, duty cycle in both conventions, acceleration envelope, resonance,
life), the dynamic columns (the rotational model held at each of the six duty rows) and the
tolerance study (the duty cycle at four belt lengths), compute only
(the model loaded and the kernels compiled first). Prints min / median / max of 5 repeats.

    python benchmarks/bench_supplier.py
"""
import statistics
import time

import drivedyn
from drivedyn.belt.geometry.drive import resolve
from drivedyn.belt.supplier import report_data


def timed(model, n=5):
    out = []
    for _ in range(n):
        t = time.perf_counter()
        report_data(resolve(model))      # a fresh Drive each time: nothing cached between repeats
        out.append(time.perf_counter() - t)
    return min(out), statistics.median(out), max(out)


if __name__ == "__main__":
    model = drivedyn.load(drivedyn.example_path("fead-ag0868"))
    static = drivedyn.replace(model, {"duty_cycle.dynamic": False, "duty_cycle.tolerance": False})
    dynamic = drivedyn.replace(model, {"duty_cycle.tolerance": False})
    report_data(resolve(model))          # compile the rotational kernels (cached after the first run)
    for label, m in (("static report", static), ("with the dynamic columns (6 rows)", dynamic),
                     ("with the tolerance study (4 x 6 rows) too", model)):
        lo, med, hi = timed(m)
        print(f"{label:36s} min {lo:6.3f} s  median {med:6.3f} s  max {hi:6.3f} s")
