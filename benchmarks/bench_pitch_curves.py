"""Benchmark: the belt path on non-circular pitch curves at one set of pulley angles
(mechanics/curve_layout.layout_at), its range over a turn (mechanics/curve_turn.over_a_turn) and
what `check` adds for it (belt/geometry/pitch_turn.turn_data). The curves are built once (their
arc-length tables are cached), as a turn or a run uses them. Target: one layout within 1 ms.

Run: PYTHONPATH=src python benchmarks/bench_pitch_curves.py
"""
import math
import time

import numpy as np

from drivedyn.mechanics.curve_layout import layout_at
from drivedyn.mechanics.curve_turn import over_a_turn
from drivedyn.mechanics.pitch_curves import Circle, Oval

# a four-pulley drive (tests/belt/test_layout.py's): an oval crank (order 2, ovality 0.05) and a trilobe
# back-side idler, two round pulleys
NAMES = ["crank", "alt", "pump", "idler"]
CENTERS = [(0.04, -0.30), (0.16, -0.10), (0, 0), (-0.02, -0.13)]
SIDES = ["inside", "inside", "inside", "back"]
CURVES = [Oval(0.08, 0.05, phase=0.3), Circle(0.056), Circle(0.027), Oval(0.031, 0.03, order=3)]
TWO = (["crank", "cam"], [(0, 0), (0.2515, 0)], ["inside", "inside"], [Oval(0.0280113, 0.04), Circle(0.0560225)])


def times(fn, repeat):
    out = []
    for k in range(repeat):
        t = time.perf_counter()
        fn(k)
        out.append(time.perf_counter() - t)
    return np.array(out) * 1e3


def show(label, ms):
    print(f"{label:58s} min {ms.min():7.3f}  median {np.median(ms):7.3f}  max {ms.max():7.3f} ms")


def main():
    layout_at(NAMES, CENTERS, CURVES, SIDES)          # imports, the curves' arc-length tables
    ang = lambda k: [0.0137 * k, 0, 0, -0.02 * k]
    show("layout at given angles, 4 pulleys (2 non-circular)", times(lambda k: layout_at(NAMES, CENTERS, CURVES, SIDES, ang(k)), 500))
    n, c, s, cv = TWO
    layout_at(n, c, cv, s)
    show("layout at given angles, 2 pulleys (oval crank)", times(lambda k: layout_at(n, c, cv, s, [0.0137 * k, 0.00685 * k]), 500))
    show("a turn in 180 positions, 4 pulleys", times(lambda k: over_a_turn(NAMES, CENTERS, CURVES, SIDES, points=180), 5))

    import drivedyn
    from drivedyn.belt.geometry.pitch_turn import turn_data

    text = drivedyn.example_path("belt-5pk").read_text().replace(
        'torque_time = [["0 s", "0 N*m"], ["0.3 s", "-15 N*m"]]',
        'torque_time = [["0 s", "0 N*m"], ["0.3 s", "-15 N*m"]]\n[pulleys.pitch_curve]\nkind = "oval"\novality = 0.05\n', 1)
    m = drivedyn.loads(text)
    show("check's pitch-curve ranges (belt-5pk, oval driver)", times(lambda k: turn_data(m), 5))


if __name__ == "__main__":
    main()
