"""A segment's move and turn over a step, and the pulley it may touch (both schemes)."""
import math

from numba import njit



@njit(cache=True, inline="always")
def _move(i, h, vxs, vys, x, y, vx, vy, w, phi, c, s):
    """Segment i takes its new velocity (vxs, vys) and moves over the step (``_turn``)."""
    vx[i] = vxs
    vy[i] = vys
    x[i] += h * vxs
    y[i] += h * vys
    _turn(i, h, w, phi, c, s)


@njit(cache=True, inline="always")
def _turn(i, h, w, phi, c, s):
    """Segment i's angle turns by a = h w over the step, (c, s) rotated exactly to round-off
    (series to a^5; |a| < 2e-2 here)."""
    a = h * w[i]
    phi[i] += a
    a2 = a * a
    ca = 1.0 - 0.5 * a2 * (1.0 - a2 / 12.0)
    sa = a * (1.0 - a2 / 6.0 * (1.0 - a2 / 20.0))
    cn = c[i] * ca - s[i] * sa
    s[i] = s[i] * ca + c[i] * sa
    c[i] = cn


# a free segment's contact test is skipped for at most this many steps (see _contact_candidate)
SKIP_MAX = 64


@njit(cache=True, inline="always")
def _contact_candidate(i, nk, x, y, pcx, pcy, pr, cand_j, cand_skip, hvb):
    """The pulley whose circle holds segment i's centre, or -1, and the centre's offset from it
    (rx, ry) and its square d2 (zeros for -1); pulleys do not overlap, so at most one. Not every
    pulley is tested every step: a segment on a pulley is tested against that one first; a free
    segment, once tested against all, is not tested again for as many steps as it needs to cross
    its clearance to the nearest pulley at the speed bound hvb / h (twice the fastest segment and
    pulley centre, plus 1 m/s; at most SKIP_MAX steps)."""
    j0 = cand_j[i]
    if j0 >= 0:
        rx = x[i] - pcx[j0]
        ry = y[i] - pcy[j0]
        d2 = rx * rx + ry * ry
        if d2 < pr[j0] * pr[j0]:
            return j0, rx, ry, d2
    elif cand_skip[i] > 0:
        cand_skip[i] -= 1
        return -1, 0.0, 0.0, 0.0
    gmin = 1e300
    for j in range(nk):
        rx = x[i] - pcx[j]
        ry = y[i] - pcy[j]
        d2 = rx * rx + ry * ry
        if d2 < pr[j] * pr[j]:
            cand_j[i] = j
            return j, rx, ry, d2
        gmin = min(gmin, math.sqrt(d2) - pr[j])
    cand_j[i] = -1
    cand_skip[i] = min(SKIP_MAX, int(gmin / hvb))
    return -1, 0.0, 0.0, 0.0
