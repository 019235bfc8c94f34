"""Compiled kernels of the toothed-mesh analysis.

Contract: float64 C-contiguous arrays in, arrays out; no Python objects; scalar loop bounds.

- ``nearest_distance(pts, a, b, margin)``: for every point ``pts[i, j]`` (shape (n, m, 2)) the
  distance to the nearest segment ``a[k] -> b[k]`` (shape (K, 2)), searching for each i only the
  segments whose bounding box meets the bounding box of ``pts[i]`` grown by ``margin``; points
  with no such segment get +inf.
- ``on_polyline(pts, which, q)``: for every point ``q[v]`` the distance to the polyline
  ``pts[which[v]]`` and the arc length along it to the nearest point (the first nearest segment,
  as GEOS's line_locate_point takes it): the overlap's vertices located on the tooth's flank.
"""
from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def nearest_distance(pts, a, b, margin):
    n, m = pts.shape[0], pts.shape[1]
    k_all = a.shape[0]
    out = np.full((n, m), np.inf)
    lo_x = np.minimum(a[:, 0], b[:, 0])
    hi_x = np.maximum(a[:, 0], b[:, 0])
    lo_y = np.minimum(a[:, 1], b[:, 1])
    hi_y = np.maximum(a[:, 1], b[:, 1])
    sel = np.empty(k_all, np.int64)
    for i in range(n):
        x0, x1 = pts[i, 0, 0], pts[i, 0, 0]
        y0, y1 = pts[i, 0, 1], pts[i, 0, 1]
        for j in range(m):
            x0 = min(x0, pts[i, j, 0])
            x1 = max(x1, pts[i, j, 0])
            y0 = min(y0, pts[i, j, 1])
            y1 = max(y1, pts[i, j, 1])
        x0 -= margin
        y0 -= margin
        x1 += margin
        y1 += margin
        ns = 0
        for k in range(k_all):
            if hi_x[k] >= x0 and lo_x[k] <= x1 and hi_y[k] >= y0 and lo_y[k] <= y1:
                sel[ns] = k
                ns += 1
        last = sel[0] if ns else 0
        for j in range(m):
            px, py = pts[i, j, 0], pts[i, j, 1]
            best = np.inf
            # the previous point's nearest segment first (the flank is sampled densely, so it is
            # near), then only the segments whose box is nearer than the best so far
            for q in range(-1, ns):
                k = last if q < 0 else sel[q]
                if q >= 0:
                    gx = max(lo_x[k] - px, px - hi_x[k], 0.0)
                    gy = max(lo_y[k] - py, py - hi_y[k], 0.0)
                    if gx * gx + gy * gy >= best:
                        continue
                dx, dy = b[k, 0] - a[k, 0], b[k, 1] - a[k, 1]
                ll = dx * dx + dy * dy
                t = 0.0
                if ll > 0:
                    t = ((px - a[k, 0]) * dx + (py - a[k, 1]) * dy) / ll
                    t = min(max(t, 0.0), 1.0)
                ex, ey = a[k, 0] + t * dx - px, a[k, 1] + t * dy - py
                d2 = ex * ex + ey * ey
                if d2 < best:
                    best = d2
                    last = k
            out[i, j] = np.sqrt(best) if ns else np.inf
    return out


@njit(cache=True)
def on_polyline(pts, which, q):
    nv, m = q.shape[0], pts.shape[1]
    dist = np.empty(nv)
    at = np.empty(nv)
    for v in range(nv):
        i = which[v]
        px, py = q[v, 0], q[v, 1]
        best, s_best, s0 = np.inf, 0.0, 0.0
        for k in range(m - 1):
            ax, ay = pts[i, k, 0], pts[i, k, 1]
            dx, dy = pts[i, k + 1, 0] - ax, pts[i, k + 1, 1] - ay
            ll = dx * dx + dy * dy
            t = 0.0
            if ll > 0:
                t = min(max(((px - ax) * dx + (py - ay) * dy) / ll, 0.0), 1.0)
            ex, ey = ax + t * dx - px, ay + t * dy - py
            d2 = ex * ex + ey * ey
            seg = np.sqrt(ll)
            if d2 < best:
                best, s_best = d2, s0 + t * seg
            s0 += seg
        dist[v] = np.sqrt(best)
        at[v] = s_best
    return dist, at
