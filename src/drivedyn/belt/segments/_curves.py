"""Non-circular pulleys (``pulleys[].pitch_curve``) in the segment model: a segment's contact with a
turning convex curve, and the tables it is read from.

A pulley's contact curve is its pitch curve (mechanics/pitch_curves.py) offset along the normal by the
distance between its pitch line and its contact radius (on a circle: the contact radius less the
pitch radius), tabulated as the radius r_c(phi) against the pulley's own polar angle phi over one turn
(TABLE_NODES uniform nodes, read by a periodic cubic). A segment centre at distance d from the centre
and own angle phi = psi - theta (psi its world polar angle, theta the pulley's angle) meets it where

    tan(mu) = r_c' / r_c,  n = cos(mu) (e_r - tan(mu) e_psi)  the outward normal,
    p = (r_c - d) cos(mu)  the penetration along it (first order in p: exact as p / r -> 0),

(the polar form of the normal, mechanics/pitch_curves.py). The turning curve's surface moves at
omega d e_psi: along the tangent tau = Z x n by omega d cos(mu) (friction's arm), along the normal by
-omega d sin(mu), so the normal force has the arm d sin(mu) about the axis and pushes the belt as the
curve's long axis sweeps by: that is how an oval turns the belt's tension into torque, the span's
pull acting on its effective radius (mechanics/curve_layout.py). On a circle mu = 0: the circle's
contact as written in _laws.py, every number the same.

Teeth on a grooved curve: its grooves sit one groove pitch (perimeter / z) apart along the pitch
curve; a tooth's arc position is the pitch curve's S(phi) at the foot of its normal, S(phi) +
(d - r_p) tan(mu) to first order, and its deflection that less its groove's, measured along the
chain's curve (x r_c / r_p, as a circle's tooth at the contact radius: segments/_teeth.py).
"""
import math

import numpy as np
from numba import njit

from ..dynamics._cubic import _periodic

#: table nodes over one turn: the cubic's error falls as (2 pi / N)^4; an oval of order 2 and ovality
#: 0.04 on a 50 mm pitch radius is read within 1e-12 m at 1024
TABLE_NODES = 1024


@njit(cache=True, inline="always")
def table_at(tab, a, phi):
    """Row a of a periodic table over one turn at own angle phi: (value, derivative per radian)."""
    return _periodic(tab, a, phi, 2.0 * math.pi)


@njit(cache=True, inline="always")
def contact_at(crad, a, rx, ry, th):
    """Curve a's contact radius r_c and tan(mu), cos(mu) at the point (rx, ry) from its centre, the
    pulley turned by th."""
    rc, drc = table_at(crad, a, math.atan2(ry, rx) - th)
    tb = drc / rc
    return rc, tb, 1.0 / math.sqrt(1.0 + tb * tb)


def tables(model, contact_radius) -> dict:
    """The Contact record's curve fields for ``model`` with the pulleys' contact radii (m; P.r, the
    chain's radius on a grooved circle): ccur -1 and the reach its radius on a circle."""
    from ...mechanics.pitch_curves import curvature, offset_radii, samples

    ps = model.pulleys
    nk = len(ps)
    ccur = np.full(nk, -1, dtype=np.int64)
    reach = np.array(contact_radius, dtype=float).copy()
    idx = [j for j, q in enumerate(ps) if q.pitch_curve is not None]
    N = TABLE_NODES
    nc = len(idx)
    crad, cpr, ckap, carc, cper = (np.zeros((nc, N)), np.zeros((nc, N)), np.zeros((nc, N)), np.zeros((nc, N)),
                                   np.zeros(nc))
    grid = np.arange(N) * (2 * math.pi / N)
    for a, j in enumerate(idx):
        c = ps[j].curve
        ccur[j] = a
        off = float(contact_radius[j]) - c.mean_radius
        # the offset points at twice the nodes, resampled at the nodes
        crad[a] = offset_radii(samples(c, 2 * N), off, grid)
        cpr[a] = c.radii(grid)
        ckap[a] = curvature(c, grid)
        per = c.perimeter / (2 * math.pi)
        cper[a] = per
        carc[a] = np.array([c.cumulative(float(f)) for f in grid]) - per * grid
        reach[j] = float(crad[a].max()) * (1 + 1e-9)
    return dict(ccur=ccur, creach=reach, crad=crad, cpr=cpr, ckap=ckap, carc=carc, cper=cper)


def table_values(tab, a, phi):
    """numpy ``table_at``: (values, derivatives per radian) of row a at the own angles phi."""
    n = tab.shape[1]
    d = 2 * math.pi / n
    x = (np.asarray(phi, float) % (2 * math.pi)) / d
    i = np.floor(x).astype(np.int64)
    f = x - i
    w = [-f * (f - 1) * (f - 2) / 6, (f + 1) * (f - 1) * (f - 2) / 2, -(f + 1) * f * (f - 2) / 2, (f + 1) * f * (f - 1) / 6]
    dw = [-(3 * f * f - 6 * f + 2) / 6, (3 * f * f - 4 * f - 1) / 2, -(3 * f * f - 2 * f - 2) / 2, (3 * f * f - 1) / 6]
    rows = [tab[a, (i + k) % n] for k in (-1, 0, 1, 2)]
    return sum(wk * rk for wk, rk in zip(w, rows)), sum(wk * rk for wk, rk in zip(dw, rows)) / d


def penetrations(C, P, j, rx, ry, th=0.0):
    """numpy: penetration p and outward normal (nx, ny) of points (rx, ry) from pulley j's centre, the
    pulley turned by th: the kernels' contact geometry (a circle's where C.ccur[j] < 0)."""
    d = np.hypot(rx, ry)
    a = int(C.ccur[j]) if len(C.ccur) else -1
    if a < 0:
        return P.r[j] - d, rx / d, ry / d
    rc, drc = table_values(C.crad, a, np.arctan2(ry, rx) - th)
    tb = drc / rc
    cb = 1 / np.sqrt(1 + tb * tb)
    er_x, er_y = rx / d, ry / d
    return (rc - d) * cb, cb * (er_x + tb * er_y), cb * (er_y - tb * er_x)
