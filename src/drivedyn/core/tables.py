"""Piecewise-linear tables (torque against time or speed, speed against time) for the kernels.

Tables of several objects are flattened into one (xs, ys) pair of arrays with offsets: rows
off[j] .. off[j+1]-1 belong to object j. Time tables are held beyond their ends (ramps, steps);
speed tables are extrapolated linearly (loads proportional to speed).

Plain Python: the kernels compile :func:`table` themselves (njit, inlined), so that check reads a
tensioner's spring table without importing numba.
"""
import numpy as np


def flatten(tables):
    """[rows or None per object] -> (offsets int64 (n+1,), xs, ys) for :func:`table`."""
    off = np.zeros(len(tables) + 1, dtype=np.int64)
    xs, ys = [], []
    for j, rows in enumerate(tables):
        rows = rows or []
        off[j + 1] = off[j] + len(rows)
        xs += [r[0] for r in rows]
        ys += [r[1] for r in rows]
    return off, np.array(xs, float), np.array(ys, float)


def table(xs, ys, o0, o1, x, extrapolate):
    """y(x) from rows o0..o1-1 (x increasing); 0 for an empty table, held or extrapolated
    linearly beyond the ends."""
    m = o1 - o0
    if m == 0:
        return 0.0
    if m == 1:
        return ys[o0]
    if x <= xs[o0]:
        if extrapolate:
            return ys[o0] + (ys[o0 + 1] - ys[o0]) * (x - xs[o0]) / (xs[o0 + 1] - xs[o0])
        return ys[o0]
    if x >= xs[o1 - 1]:
        if extrapolate:
            return ys[o1 - 1] + (ys[o1 - 1] - ys[o1 - 2]) * (x - xs[o1 - 1]) / (xs[o1 - 1] - xs[o1 - 2])
        return ys[o1 - 1]
    lo, hi = o0, o1 - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if xs[mid] <= x:
            lo = mid
        else:
            hi = mid
    return ys[lo] + (ys[hi] - ys[lo]) * (x - xs[lo]) / (xs[hi] - xs[lo])
