"""The placement's walk along the closed path (placement.py), in plain Python: a placement takes a
few dozen walks, where importing numba (``check``) or compiling them (a first run) would take longer.

The path is a sequence of pieces, one row each: kind (0 line, 1 arc), arc length at its start,
its length, then (x0, y0, x1, y1) of a line or (cx, cy, R, angle0, sweep) of an arc. ``pc`` is a
list of rows of floats (indexing a list is several times faster than indexing an array).
"""
import math

import numpy as np


def piece(pc, s):
    """The piece holding arc length s, 0 <= s < the path's length."""
    k = len(pc) - 1
    while k > 0 and pc[k][1] > s:
        k -= 1
    return k


def point(pc, total, s):
    """The path's point at arc length s (taken modulo the length)."""
    s = s % total
    r = pc[piece(pc, s)]
    u = (s - r[1]) / r[2] if r[2] > 0 else 0.0
    if r[0] == 0.0:
        return r[3] + (r[5] - r[3]) * u, r[4] + (r[6] - r[4]) * u
    a = r[6] + r[7] * u
    return r[3] + r[5] * math.cos(a), r[4] + r[5] * math.sin(a)


def next_end(pc, total, s, px, py, c):
    """Smallest arc length beyond s where the path is at distance c from (px, py), the path's point
    at s; -1 if none. Exact per piece: a line's crossing of the circle of radius c about the point
    is a quadratic, an arc's is rho cos(a - beta) = K. The path is at most c away before s + c
    (a chord is at most its arc), so crossings before s + c / 2 are the one behind."""
    m = len(pc)
    sm = s % total
    base = s - sm
    k = piece(pc, sm)
    eps = 1e-12
    for it in range(m + 2):
        kk = (k + it) % m
        r = pc[kk]
        s0 = base + total * ((k + it) // m) + r[1]
        L = r[2]
        if L <= 0.0:
            continue
        best = math.inf
        if r[0] == 0.0:
            dx, dy = r[5] - r[3], r[6] - r[4]
            wx, wy = r[3] - px, r[4] - py
            A = dx * dx + dy * dy
            # the foot of the point on the line and its distance h (cross product: exact where the
            # point lies on the line), the crossings at u_foot +- sqrt(c^2 - h^2) / |d|
            uf = -(wx * dx + wy * dy) / A
            cr = wx * dy - wy * dx
            e2 = c * c - cr * cr / A
            if e2 >= 0.0:
                du = math.sqrt(e2 / A)
                for u in (uf - du, uf + du):
                    t = s0 + u * L
                    if -eps <= u <= 1.0 + eps and t > s + 0.5 * c:
                        best = min(best, t)
        else:
            R, a0, sw = r[5], r[6], r[7]
            wx, wy = r[3] - px, r[4] - py
            rho = math.sqrt(wx * wx + wy * wy)
            K = (c * c - rho * rho - R * R) / (2.0 * R)
            # rho^2 - K^2 in factors (Heron's form), exact where the chord c is small against R
            d = rho - R
            q = (c - d) * (c + d) * (rho + R - c) * (rho + R + c) / (4.0 * R * R)
            if sw != 0.0 and rho > 0.0 and q >= 0.0:
                beta = math.atan2(wy, wx)            # (C - p) . e(a) = rho cos(a - beta) = K
                th = math.atan2(math.sqrt(q), K)
                du = 2.0 * math.pi / abs(sw)         # u of one turn
                for astar in (beta + th, beta - th):
                    u = (astar - a0) / sw
                    u -= math.floor(u / du) * du     # in [0, du)
                    if u > du - eps:                 # at the piece's start, at round-off
                        u -= du
                    while u <= 1.0 + eps:
                        t = s0 + u * L
                        if u >= -eps and t > s + 0.5 * c:
                            best = min(best, t)
                        u += du
        if best < math.inf:
            return best
    return -1.0


def _advance(r, c):
    """Arc length from one end of a chord of length c to the other, both on piece r (a line: c;
    an arc of radius R: R 2 asin(c / 2R)); None where no chord c fits the piece's circle."""
    if c <= 0.0:
        return 0.0
    if r[0] == 0.0:
        return c
    R = r[5]
    return 2.0 * R * math.asin(0.5 * c / R) if c < 2.0 * R else None


def _points(r, base, s):
    """The points at arc lengths s (an array) on piece r, whose start lies at base + r[1]."""
    u = (s - (base + r[1])) / r[2]
    if r[0] == 0.0:
        return np.stack([r[3] + (r[5] - r[3]) * u, r[4] + (r[6] - r[4]) * u], axis=1)
    a = r[6] + r[7] * u
    return np.stack([r[3] + r[5] * np.cos(a), r[4] + r[5] * np.sin(a)], axis=1)


def _whole_pairs(pc, total, s, l, g, most):
    """Chord-and-gap pairs from s that lie wholly on s's piece: on a line or an arc every pair
    advances the arc length by the same amount, so they are placed at once (a walk of n chords
    costs its pieces, not n searches). (m, advance per chord, advance per pair, piece, base)."""
    sm = s % total
    k = piece(pc, sm)
    r = pc[k]
    base = s - sm
    al, ag = _advance(r, l), _advance(r, g)
    if al is None or ag is None or al + ag <= 0.0 or r[2] <= 0.0:
        return 0, 0.0, 0.0, r, base
    room = base + r[1] + r[2] - s - 1e-9 * r[2]      # (clear of the piece's end: round-off there)
    m = min(most, int(room // (al + ag))) if room > 0.0 else 0
    return max(m, 0), al, al + ag, r, base


def walk_pieces(pc, total, n, l, g):
    """Chord, gap, chord, ... from arc length 0: the n chords' start and end points and the arc
    length reached; s = -1 where a chord or gap finds no end on the path. Pairs wholly on one piece
    are placed at once (``_whole_pairs``), the others searched (``next_end``)."""
    starts = np.empty((n, 2))
    ends = np.empty((n, 2))
    s = 0.0
    px, py = point(pc, total, 0.0)
    i = 0
    while i < n:
        m, al, d, r, base = _whole_pairs(pc, total, s, l, g, n - i)
        if m > 0:
            s0 = s + d * np.arange(m)
            starts[i:i + m] = _points(r, base, s0)
            ends[i:i + m] = _points(r, base, s0 + al)
            s += d * m
            px, py = point(pc, total, s)
            i += m
            continue
        starts[i, 0], starts[i, 1] = px, py
        for k in range(2):               # the chord, then the gap to the next one
            c = l if k == 0 else g
            if c > 0.0:
                s = next_end(pc, total, s, px, py, c)
                if s < 0.0:
                    return starts, ends, -1.0
                px, py = point(pc, total, s)
            if k == 0:
                ends[i, 0], ends[i, 1] = px, py
        i += 1
    return starts, ends, s
