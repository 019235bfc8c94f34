"""Compiled step of the rotational belt-drive model (rotational/simulate.py states the formulation).

One unknown per pulley (angle, speed; a clutch rotor behind it), per tensioner (travel, rate) and
per span and wrap (their unstretched belt contents u and W); with the elastic-plastic law each wrap's
belt in cells the rim carries, each with its tension and bristle deflection (``_cells_*``). The pulleys, clutches and tensioners
advance through the same stages as the segment model (``_kernels._step_pulleys``,
``_kernels._step_arms``): their loads, orders, clutch laws, springs, friction and stops are the
segment model's by construction. Symplectic Euler: forces from this step's state, then speeds,
then positions and belt contents; gross slip by a return map on each wrap's tension ratio. The
contents move over the step at the new speeds with the span tensions, wrap angles and the span
dampers' rates of the step's middle, extrapolated from the last two steps: second order in h on a
smooth response (tests/belt/test_rotational.py), where this step's values left it first order;
events between steps (a wrap's gross slip starting, the arm's stick-slip, a clutch) stay first
order.
"""
import math
from typing import NamedTuple

import numpy as np
from numba import njit
from numba.extending import register_jitable

from ..dynamics import _bodies as BK
from ..dynamics._cubic import _cubic, _periodic
from ..steady._wraps import sunk_depth, wrap_axial_stiffness
from .teeth import chain_energy

# plain Python in _wraps (check uses them without numba) and teeth.py (the periodic run-up's state):
# compiled and inlined where called here
register_jitable(inline="always")(sunk_depth)
register_jitable(inline="always")(wrap_axial_stiffness)
register_jitable(inline="always")(chain_energy)


class Rot(NamedTuple):
    """The rotational model's constants (SI units, spans and wraps in belt order: span k leaves
    pulley k)."""
    nk: int
    rho: np.ndarray          # signed contact radius per pulley (layout.rho)
    EA: float
    bax: float               # axial damping (N s): T = EA eps + bax d eps / dt
    m: float                 # belt mass per length (kg/m)
    mu: np.ndarray           # friction coefficient per wrap
    c1: float                # contact law per unit length (N/m^3, N/m^2), the belt's depth in the groove
    c2: float
    centre: bool             # friction.radius = "centre": the belt runs on its depth's radius r - p
    dmax: float              # the elastic-plastic law's Delta_max (m): the wraps' bristles; 0: adhesion
    L: np.ndarray            # span lengths at rest (m)
    dx: np.ndarray           # span directions at rest (unit)
    dy: np.ndarray
    wrap: np.ndarray         # wrap angles at rest (rad)
    # geometry tables per tensioner a over its travel grid q0[a] + i dq[a]: changes from rest
    q0: np.ndarray
    dq: np.ndarray
    tL: np.ndarray           # (na, ng, nspan) straight span length
    t0: np.ndarray           # (na, ng, nspan) belt rolled onto the span's start pulley (rho dalpha)
    t1: np.ndarray           # (na, ng, nspan) ... and onto its end pulley
    tdx: np.ndarray          # (na, ng, nspan) direction
    tdy: np.ndarray
    tw: np.ndarray           # (na, ng, nk) wrap angle
    ncell: np.ndarray        # per wrap: cells of its belt (elastic-plastic law; _cells_*)
    p0: np.ndarray           # per wrap: the depth the belt's content is measured from (m; _content)
    # a synchronous belt (rotational/teeth.py): per wrap 1 where the belt's teeth hold it in grooves
    # (no creep, no slip: the belt passes at the grooves' rate, pr = belt pitch / groove pitch of
    # unstretched belt per unit of pitch line), and the quasi-static tooth chain's end compliances
    # (m/N: first end's motion = ga dT_in + gb dT_out, the last end's = gc dT_in + gd dT_out)
    grooved: np.ndarray
    pr: np.ndarray
    ga: np.ndarray
    gb: np.ndarray
    gc: np.ndarray
    gd: np.ndarray
    chain: bool              # any grooved wrap
    trest: float             # the rest tension the chains' energy is counted from (N)
    # non-circular grooved pulleys (pitch_curves.py; rotational/curves.py): per curve its pulley, the
    # period of its geometry in its angle, the belt's sense, perimeter / 2 pi, and tables over one period
    # (cubic, periodic): changes from the circle layout of span lengths, directions and wraps, the
    # effective radii where the belt arrives and leaves, and the periodic part of the arc positions of
    # the arriving and leaving tangent points on the curve (S + perimeter theta / 2 pi)
    cpul: np.ndarray
    cP: np.ndarray
    csig: np.ndarray
    cper: np.ndarray
    cL: np.ndarray           # (nc, N, nspan)
    cdx: np.ndarray
    cdy: np.ndarray
    cw: np.ndarray           # (nc, N, nk)
    crin: np.ndarray         # (nc, N)
    crout: np.ndarray
    cse: np.ndarray
    csx: np.ndarray
    ct0: np.ndarray          # (nc, N, nspan): belt rolled onto each span's circles as their tangent points move (m)
    ct1: np.ndarray
    cA: np.ndarray           # (nc, N): the belt's arc on the curve (its wrap's length on the pitch line, m)
    cW: np.ndarray           # (nc, N): ... and its wrap angle (rad), the tensioners at rest


#: Gauss-Legendre nodes and weights on [0, 1] for the belt's depth along a slip arc (steady/creep.py uses
#: 8; the integrand is smooth: 4 left the wrap's content within 1e-9 m on fead-runup's drive, 2 move
#: its periodic run-up tables by 1e-5 relative at most and save 6 % per step)
GL_N = 2
_X, _WG = np.polynomial.legendre.leggauss(GL_N)
GL_X = 0.5 * (_X + 1.0)
GL_W = 0.5 * _WG


@njit(cache=True, inline="always")
def wrap_content(r, theta, t_in, t_out, c, mu, EA, c1, c2):
    """Unstretched belt on a wrap in steady running (steady._wrap_length): an adhesion arc at the
    entry tension, then a slip arc where T - c ~ exp(+-mu phi), the belt at the depth of its
    contact pressure (T - c) / r."""
    p_in = sunk_depth((t_in - c) / r, c1, c2)
    lo = min(t_in, t_out)
    if t_in == t_out or mu <= 0.0 or lo <= c:
        return (r - p_in) * theta / (1.0 + t_in / EA)
    phi = abs(math.log((t_out - c) / (t_in - c))) / mu
    if phi > theta:
        phi = theta
    adh = (r - p_in) * (theta - phi) / (1.0 + t_in / EA)
    k = mu if t_out > t_in else -mu
    t_end = c + (t_in - c) * math.exp(k * phi)
    B = 1.0 + c / EA
    sink = 0.0
    for g in range(GL_N):
        T = c + (t_in - c) * math.exp(k * phi * GL_X[g])
        sink += GL_W[g] * sunk_depth((T - c) / r, c1, c2) / (1.0 + T / EA)
    return adh + r * (phi - math.log((1.0 + t_end / EA) / (1.0 + t_in / EA)) / k) / B - sink * phi


@njit(cache=True, inline="always")
def _locate(q, q0, dq, ng):
    """Grid interval i (nodes i-1 .. i+2 used) and the fraction in it."""
    x = (q - q0) / dq
    i = int(math.floor(x))
    if i < 1:
        i = 1
    elif i > ng - 3:
        i = ng - 3
    return i, x - i


@njit(cache=True, inline="always")
def _geometry(Lr, dxr, dyr, wr, q0, dq, tL, tt0, tt1, tdx, tdy, tw, q, qd, L, Ld, t0, t1, dx, dy, wrap):
    """Span lengths L (and their rates Ld), the belt rolled onto each span's ends t0, t1 (from
    rest), span directions and wrap angles at tensioner travel q (rates qd): the rest geometry plus
    each tensioner's change, read from its table (cubic between grid points). Plain arrays: in the
    time loop a record's field read costs a reference-count pair."""
    ns = Lr.shape[0]
    for j in range(ns):
        L[j] = Lr[j]
        Ld[j] = 0.0
        t0[j] = 0.0
        t1[j] = 0.0
        dx[j] = dxr[j]
        dy[j] = dyr[j]
        wrap[j] = wr[j]
    for a in range(q.shape[0]):
        i, f = _locate(q[a], q0[a], dq[a], tL.shape[1])
        wm, w0, w1, w2, dm, d0, d1, d2 = _cubic(f)
        rate = qd[a] / dq[a]
        for j in range(ns):
            L[j] += wm * tL[a, i - 1, j] + w0 * tL[a, i, j] + w1 * tL[a, i + 1, j] + w2 * tL[a, i + 2, j]
            Ld[j] += (dm * tL[a, i - 1, j] + d0 * tL[a, i, j] + d1 * tL[a, i + 1, j] + d2 * tL[a, i + 2, j]) * rate
            t0[j] += wm * tt0[a, i - 1, j] + w0 * tt0[a, i, j] + w1 * tt0[a, i + 1, j] + w2 * tt0[a, i + 2, j]
            t1[j] += wm * tt1[a, i - 1, j] + w0 * tt1[a, i, j] + w1 * tt1[a, i + 1, j] + w2 * tt1[a, i + 2, j]
            dx[j] += wm * tdx[a, i - 1, j] + w0 * tdx[a, i, j] + w1 * tdx[a, i + 1, j] + w2 * tdx[a, i + 2, j]
            dy[j] += wm * tdy[a, i - 1, j] + w0 * tdy[a, i, j] + w1 * tdy[a, i + 1, j] + w2 * tdy[a, i + 2, j]
            wrap[j] += wm * tw[a, i - 1, j] + w0 * tw[a, i, j] + w1 * tw[a, i + 1, j] + w2 * tw[a, i + 2, j]
    for j in range(ns):
        n = math.sqrt(dx[j] * dx[j] + dy[j] * dy[j])
        dx[j] /= n
        dy[j] /= n


@njit(cache=True, inline="always")
def _curve_geometry(rho, cpul, cP, cL, cdx, cdy, cw, crin, crout, ct0, ct1, th, om, L, Ld, t0, t1, dx, dy, wrap, rin,
                    rout):
    """The non-circular pulleys' share of the geometry at their angles th (rates om): span lengths (and
    rates), directions, rolled-on belt, wraps and the effective radii rin, rout (|rho| on a circle).
    Called after ``_geometry``, which normalised the directions: they are normalised again. One set of
    cubic weights per curve serves all its tables (they share the nodes)."""
    nk = rho.shape[0]
    for k in range(nk):
        rin[k] = abs(rho[k])
        rout[k] = rin[k]
    nc = cpul.shape[0]
    if nc == 0:
        return
    ns = L.shape[0]
    n = cL.shape[1]
    for a in range(nc):
        k = cpul[a]
        P = cP[a]
        d = P / n
        x = (th[k] % P) / d
        i = int(math.floor(x))
        wm, w0, w1, w2, dm, d0, d1, d2 = _cubic(x - i)
        im, i1, i2 = (i - 1) % n, (i + 1) % n, (i + 2) % n
        i = i % n
        rate = om[k] / d
        for j in range(ns):
            L[j] += wm * cL[a, im, j] + w0 * cL[a, i, j] + w1 * cL[a, i1, j] + w2 * cL[a, i2, j]
            Ld[j] += (dm * cL[a, im, j] + d0 * cL[a, i, j] + d1 * cL[a, i1, j] + d2 * cL[a, i2, j]) * rate
            dx[j] += wm * cdx[a, im, j] + w0 * cdx[a, i, j] + w1 * cdx[a, i1, j] + w2 * cdx[a, i2, j]
            dy[j] += wm * cdy[a, im, j] + w0 * cdy[a, i, j] + w1 * cdy[a, i1, j] + w2 * cdy[a, i2, j]
            t0[j] += wm * ct0[a, im, j] + w0 * ct0[a, i, j] + w1 * ct0[a, i1, j] + w2 * ct0[a, i2, j]
            t1[j] += wm * ct1[a, im, j] + w0 * ct1[a, i, j] + w1 * ct1[a, i1, j] + w2 * ct1[a, i2, j]
        for j in range(nk):
            wrap[j] += wm * cw[a, im, j] + w0 * cw[a, i, j] + w1 * cw[a, i1, j] + w2 * cw[a, i2, j]
        rin[k] = wm * crin[a, im] + w0 * crin[a, i] + w1 * crin[a, i1] + w2 * crin[a, i2]
        rout[k] = wm * crout[a, im] + w0 * crout[a, i] + w1 * crout[a, i1] + w2 * crout[a, i2]
    for j in range(ns):
        nn = math.sqrt(dx[j] * dx[j] + dy[j] * dy[j])
        dx[j] /= nn
        dy[j] /= nn


@njit(cache=True, inline="always")
def _arc_position(tab, per, a, th, P):
    """Arc position on curve a's pitch line of a tangent point at the pulley's angle th (m, from its
    value at 0): the table's periodic part less perimeter th / 2 pi."""
    return _periodic(tab, a, th, P)[0] - per[a] * th


@njit(cache=True, inline="always")
def _wrap_arcs(rho, wrap, cpul, cP, cA, cW, th, aw, rr):
    """Each wrap's arc and pressure radius at the pulleys' angles th (RotWork.aw, rr): a circle's |rho|
    wrap and |rho|, a pitch curve's tabulated arc (plus what the tensioners' travel adds to its wrap, at
    its mean radius) and arc / wrap."""
    for k in range(rho.shape[0]):
        r = abs(rho[k])
        aw[k] = r * wrap[k]
        rr[k] = r
    for a in range(cpul.shape[0]):
        k = cpul[a]
        aw[k] = _periodic(cA, a, th[k], cP[a])[0] + abs(rho[k]) * (wrap[k] - _periodic(cW, a, th[k], cP[a])[0])
        rr[k] = aw[k] / wrap[k]


@njit(cache=True, inline="always")
def _curve_of(cpul, k):
    """The curve row of pulley k, -1 for a circle."""
    for a in range(cpul.shape[0]):
        if cpul[a] == k:
            return a
    return -1


@njit(cache=True)
def geometry(R, q, qd, L, Ld, t0, t1, dx, dy, wrap, th, om, rin, rout):
    """``_geometry`` and ``_curve_geometry`` on the Rot record."""
    _geometry(R.L, R.dx, R.dy, R.wrap, R.q0, R.dq, R.tL, R.t0, R.t1, R.tdx, R.tdy, R.tw, q, qd, L, Ld, t0, t1,
              dx, dy, wrap)
    _curve_geometry(R.rho, R.cpul, R.cP, R.cL, R.cdx, R.cdy, R.cw, R.crin, R.crout, R.ct0, R.ct1, th, om, L, Ld, t0, t1,
                    dx, dy, wrap, rin, rout)


class RotState(NamedTuple):
    u: np.ndarray            # unstretched belt in each span (m)
    W: np.ndarray            # unstretched belt on each wrap (m)
    ud: np.ndarray           # du/dt of the last step (the span dampers' strain rate)
    vs: np.ndarray           # material speed in each span along the belt order (m/s), last step
    t0: np.ndarray           # belt rolled onto the span ends at the last step (m)
    t1: np.ndarray
    Tp: np.ndarray           # span tensions of the last step (N)
    ed: np.ndarray           # the span dampers' strain rate of the last step (1/s)
    eb: np.ndarray           # per wrap: the bristles' energy (J)
    zc: np.ndarray           # (nk, ncell max): per wrap cell, its belt's bristle deflection (m, belt order positive)
    Tc: np.ndarray           # (nk, ncell max): ... and its tension (N)
    wsum: np.ndarray         # per wrap: the sum of its cells' content per unit arc (``_content``)
    dz: np.ndarray           # (nk, ncell max): the cells' last bristle increment (m): sliding on, or turning
    cw0: np.ndarray          # per grooved wrap: the tensions its tooth chain holds at its first and last end (N)
    cw1: np.ndarray


class RotWork(NamedTuple):
    L: np.ndarray
    Ld: np.ndarray
    t0: np.ndarray
    t1: np.ndarray
    dx: np.ndarray
    dy: np.ndarray
    wrap: np.ndarray
    T: np.ndarray            # span tensions of the step (N)
    Tm: np.ndarray           # ... the belt's stage's
    wm: np.ndarray           # wrap angles at the step's middle
    a: np.ndarray            # belt flux into each wrap from the span before it (unstretched m/s)
    b: np.ndarray            # belt flux out of each wrap into the span after it
    tq: np.ndarray           # belt torque per pulley (N m)
    hubx: np.ndarray
    huby: np.ndarray
    slip: np.ndarray         # per wrap: belt slid through the wrap this step (m, belt order positive)
    acc_T: np.ndarray        # per span: h-weighted sums of tension and speed
    acc_v: np.ndarray
    acc_slip: np.ndarray     # per wrap: sliding speed (m/s) and time in gross slip (s)
    acc_gross: np.ndarray
    acc_diss: np.ndarray     # (6): axial damping, 0, 0, friction (creep and slip), tensioner, clutch
    bm: np.ndarray           # (nk, nk) and (nk): the bristles' linear system
    bv: np.ndarray
    ex: np.ndarray           # per span: the damper's strain rate of the step (1/s)
    Xc: np.ndarray           # (nk, ncell max): the cells' displacement per unit tension change at the wrap's
    Yc: np.ndarray           # first (X) and last (Y) end in belt order (m/N)
    Kc: np.ndarray           # (nk, ncell max): the cells' bristle stiffness (N/m; 0 sliding)
    Fc: np.ndarray           # (nk, ncell max): the cells' bristle stiffness short of Delta_max (N/m)
    cp: np.ndarray           # (ncell max) scratch
    ca: np.ndarray           # per wrap: its ends' compliances (m/N): first end's motion = ca dT_first + cb dT_last,
    cb: np.ndarray           # the last end's = cc dT_first + cd dT_last (forward positive)
    cc: np.ndarray
    cd: np.ndarray
    eb0: np.ndarray          # per wrap: the bristles' energy before the step's update (J)
    Tw0: np.ndarray          # per wrap: the tension its belt holds at its first and last end (N)
    Tw1: np.ndarray
    ew: np.ndarray           # per wrap: its axial stiffness EA_w (N)
    off: np.ndarray          # per span: belt the wraps let into it this step (m, unstretched)
    m0: np.ndarray           # per wrap: its first and last end's motion this step (m, forward positive)
    m1: np.ndarray
    rin: np.ndarray          # per pulley: effective radius where the belt arrives and leaves (m; |rho| on a circle)
    rout: np.ndarray
    thb: np.ndarray          # per pulley: its angle at the step's start (rad)
    aw: np.ndarray           # per wrap: its arc (m; |rho| wrap on a circle, the curve's arc on a pitch curve)
    rr: np.ndarray           # per wrap: the radius its pressure (T - m v^2) / r reads (|rho|; arc / wrap on a curve)


@njit(cache=True, inline="always")
def _content(T, c, r, p0, EA, c1, c2):
    """Unstretched belt per unit of rim arc at tension T: its centre line at the depth p(T) of its
    pressure (T - m v^2) / r, measured from p0 (0 with friction.radius = "centre", the rest
    tension's depth at the contact radius), stretched by T / EA."""
    return (1.0 - (sunk_depth((T - c) / r, c1, c2) - p0) / r) / (1.0 + T / EA)


# its own function: with numpy's error model (no division-by-zero test, which no positive tension
# can meet) LLVM vectorises the loop
@njit(cache=True, error_model="numpy", fastmath={"nsz", "arcp", "contract", "afn", "reassoc"})
def _content_sum(T, n, c, r, p0, EA, c1, c2):
    """The summed ``_content`` of the first n tensions T."""
    w = 0.0
    for i in range(n):
        w += _content(T[i], c, r, p0, EA, c1, c2)
    return w


@njit(cache=True, inline="always")
def _cells_respond(nk, ncell, EA, c1, c2, m, mu, dmax, rho, om, wrap, zc, Tc, Kc, Fc, Xc, Yc, cp, ca, cb, cc, cd,
                   Tw0, Tw1, ew, dz, aw, rr):
    """Per wrap, the elastic response of its belt's cells to tension changes at its ends: nodes at the
    cells' centres joined by the belt (EA_w / ds, EA_w the wrap's axial stiffness with its sinking,
    ``wrap_axial_stiffness``), each held to the rim by its bristles, K = mu (T - m v^2) / (r Delta_max)
    ds while short of Delta_max and 0 once at it (the elastic-plastic law's tangent: a bristle at its
    limit slides on). Solves the tridiagonal system for a unit tension change at each end (by shooting, below);
    the ends' compliances, and the tensions the wrap's belt holds at its ends (Tw0, Tw1)."""
    for k in range(nk):
        n = ncell[k]
        r = rr[k]
        vw = rho[k] * om[k]
        c = m * vw * vw
        ds = aw[k] / n
        Tbar = 0.5 * (Tc[k, 0] + Tc[k, n - 1]) - c
        e = wrap_axial_stiffness(EA, c1, c2, Tbar / r if Tbar > 0.0 else 0.0, r)
        ew[k] = e
        kb = e / ds
        kq = mu[k] * ds / (r * dmax)
        for i in range(n):
            q = Tc[k, i] - c
            kp = kq * q if q > 0.0 else 0.0
            Fc[k, i] = kp
            # at Delta_max and pushed on outward last step: sliding, no stiffness (a bristle the step
            # before pulled back holds again: elastic)
            Kc[k, i] = 0.0 if abs(zc[k, i]) >= dmax * (1.0 - 1e-9) and dz[k, i] * zc[k, i] > 0.0 else kp
        Tw0[k] = Tc[k, 0] - 0.5 * Fc[k, 0] * zc[k, 0]
        Tw1[k] = Tc[k, n - 1] + 0.5 * Fc[k, n - 1] * zc[k, n - 1]
        # the responses to a unit pull at either end (the first and last columns of the inverse of the
        # symmetric tridiagonal stiffness, diagonal D_i = K_i + kb n_i, off-diagonal -kb): each solves
        # the homogeneous equations of every node but the pulled one, so it follows from the far end by
        # the recurrence x_{i-1} = (D_i / kb) x_i - x_{i+1} (shooting toward the pull, where the
        # response grows: the stable direction) and is scaled by the pulled node's equation. Two
        # independent chains without a division: a quarter of the Thomas solve's time
        reg = 1e-6 * kb
        ikb = 1.0 / kb
        for i in range(n):
            nb = 2.0 - (1.0 if i == 0 else 0.0) - (1.0 if i == n - 1 else 0.0)
            cp[i] = (Kc[k, i] + reg) * ikb + nb
        xa, xb = 1.0, 0.0           # X from the last node back, Y from the first node on
        ya, yb = 1.0, 0.0
        Xc[k, n - 1] = 1.0
        Yc[k, 0] = 1.0
        for i in range(n - 1, 0, -1):
            xa, xb = cp[i] * xa - xb, xa
            yi = n - 1 - i
            ya, yb = cp[yi] * ya - yb, ya
            Xc[k, i - 1] = xa
            Yc[k, yi + 1] = ya
            if abs(xa) > 1e150 or abs(ya) > 1e150:     # stiff bristles: rescale before overflow
                for jj in range(n):
                    Xc[k, jj] *= 1e-150
                    Yc[k, jj] *= 1e-150
                xa *= 1e-150
                xb *= 1e-150
                ya *= 1e-150
                yb *= 1e-150
        # the pulled node's equation: kb (D_0 / kb x_0 - x_1) = -1 (X), kb (D_n-1 / kb y_n-1 - y_n-2) = 1 (Y)
        sx = -1.0 / (kb * (cp[0] * Xc[k, 0] - Xc[k, 1]))
        sy = 1.0 / (kb * (cp[n - 1] * Yc[k, n - 1] - Yc[k, n - 2]))
        for i in range(n):
            Xc[k, i] *= sx
            Yc[k, i] *= sy
        ca[k] = Xc[k, 0] - 0.5 * ds / e
        cb[k] = Yc[k, 0]
        cc[k] = Xc[k, n - 1]
        cd[k] = Yc[k, n - 1] + 0.5 * ds / e


@njit(cache=True, inline="always")
def _cells_couple(nk, EA, L, u, T, ca, cb, cc, cd, Tw0, Tw1, bm, bv, off, m0, m1):
    """The span tensions T (in: from the spans' contents; out: with the belt the wraps let out) and
    that belt per span, off_j = the last end's motion of wrap j less the first end's of wrap j+1,
    T_j = T0_j - s_j off_j (s_j = EA L_j / u_j^2): a cyclic system in T, solved densely."""
    for j in range(nk):
        for i in range(nk):
            bm[j, i] = 0.0
    for j in range(nk):
        k1 = (j + 1) % nk
        jm = (j - 1) % nk
        sj = EA * L[j] / (u[j] * u[j])
        bm[j, j] += 1.0 + sj * (cd[j] - ca[k1])
        bm[j, jm] += sj * cc[j]
        bm[j, k1] -= sj * cb[k1]
        bv[j] = T[j] + sj * (cc[j] * Tw0[j] + cd[j] * Tw1[j] - ca[k1] * Tw0[k1] - cb[k1] * Tw1[k1])
    BK._small_solve(nk, bm, bv)
    for k in range(nk):
        jm = (k - 1) % nk
        m0[k] = ca[k] * (bv[jm] - Tw0[k]) + cb[k] * (bv[k] - Tw1[k])
        m1[k] = cc[k] * (bv[jm] - Tw0[k]) + cd[k] * (bv[k] - Tw1[k])
    for j in range(nk):
        off[j] = m1[j] - m0[(j + 1) % nk]
    for j in range(nk):
        T[j] = bv[j]


@njit(cache=True, inline="always")
def _cells_update(nk, ncell, dmax, rho, wrap, T, zc, Tc, Xc, Yc, Fc, Tw0, Tw1, ew, eb, dz, aw):
    """The cells after the wraps' ends met the span tensions T: each node moves by X dT_first + Y dT_last,
    its tension by the mean of the belt's change on either side, its bristle by its motion, to at most
    Delta_max (beyond, the belt slides). eb: the bristles' energy per wrap (J). What the stretch changed
    in the cells' content beyond the ends' motions (the bars' linearisation) the transport books at the
    exit (``_cell_transport``)."""
    for k in range(nk):
        n = ncell[k]
        ji = (k - 1) % nk
        d0 = T[ji] - Tw0[k]
        d1 = T[k] - Tw1[k]
        ds = aw[k] / n
        kb = ew[k] / ds
        left = d0
        e = 0.0
        for i in range(n):
            di = Xc[k, i] * d0 + Yc[k, i] * d1
            if i < n - 1:
                right = kb * (Xc[k, i + 1] * d0 + Yc[k, i + 1] * d1 - di)
            else:
                right = d1
            Tc[k, i] += 0.5 * (left + right)
            left = right
            dz[k, i] = di
            zn = zc[k, i] + di
            if zn > dmax:
                zn = dmax
            elif zn < -dmax:
                zn = -dmax
            zc[k, i] = zn
            e += 0.5 * Fc[k, i] * zn * zn
        eb[k] = e
        # the tensions the wrap's belt now holds at its ends: the rim carries it out at them
        Tw0[k] = Tc[k, 0] - 0.5 * Fc[k, 0] * zc[k, 0]
        Tw1[k] = Tc[k, n - 1] + 0.5 * Fc[k, n - 1] * zc[k, n - 1]


@njit(cache=True, inline="always")
def _at(a, k, i, n, below, beyond):
    """Wrap k's cell i of array a; ``below`` before the first cell, ``beyond`` past the last."""
    if i < 0:
        return below
    if i > n - 1:
        return beyond
    return a[k, i]


@njit(cache=True, inline="always")
def _stencil(A, k, i, n, below, beyond, wm, w0, w1, w2):
    """The cubic's weighted sum over wrap k's cells i-1 .. i+2 of A, ``below`` / ``beyond`` past its ends."""
    return (wm * _at(A, k, i - 1, n, below, beyond) + w0 * _at(A, k, i, n, below, beyond)
            + w1 * _at(A, k, i + 1, n, below, beyond) + w2 * _at(A, k, i + 2, n, below, beyond))


@njit(cache=True, inline="always")
def _cell_transport(k, n, r, ds, phi, Tf, c, p0, EA, c1, c2, zc, Tc, buf, wsum, let_out):
    """The rim carries wrap k's cells by phi cells (signed, belt order = the cells' order when
    positive): semi-Lagrangian, the cubic through the four cells about where each cell's belt was
    (its diffusion shrinks as ds^3), fresh belt (no bristle deflection, tension Tf) entering, the exit
    cell's own values past the exit. Returns the unstretched belt that left past the exit (m): what
    came in less the cells' content change since the last step's shift (wsum[k], at the centrifugal
    tension then; now at c) less what the ends' motions let out already (let_out), so belt is conserved
    exactly: the shift's, the stretch's beyond its linearisation and the speed's lift of the belt in
    the groove."""
    w0c = wsum[k]
    # every cell's belt came from phi cells back: the same base and weights for all
    x = -phi
    fx = math.floor(x)
    b0 = int(fx)
    wm, w0, w1, w2 = _cubic(x - fx)[:4]
    # cells whose four points are all inside the wrap: a plain loop, without the ends' tests
    jlo = min(max(1 - b0, 0), n)
    jhi = max(min(n - 2 - b0, n), jlo)
    for arr in range(2):
        A = zc if arr == 0 else Tc
        fresh = 0.0 if arr == 0 else Tf
        below, beyond = (fresh, A[k, n - 1]) if phi >= 0.0 else (A[k, 0], fresh)
        for j in range(jlo):
            i = j + b0
            buf[j] = _stencil(A, k, i, n, below, beyond, wm, w0, w1, w2)
        for j in range(jlo, jhi):
            i = j + b0
            buf[j] = wm * A[k, i - 1] + w0 * A[k, i] + w1 * A[k, i + 1] + w2 * A[k, i + 2]
        for j in range(jhi, n):
            i = j + b0
            buf[j] = _stencil(A, k, i, n, below, beyond, wm, w0, w1, w2)
        for j in range(n):
            A[k, j] = buf[j]
    w1c = _content_sum(Tc[k], n, c, r, p0, EA, c1, c2)
    wsum[k] = w1c
    return abs(phi) * ds * _content(Tf, c, r, p0, EA, c1, c2) - (w1c - w0c) * ds - let_out


@njit(cache=True, inline="always")
def _cell_transport_curve(k, n, r, ds0, ds1, de, dx, Tin, Tout, c, p0, EA, c1, c2, zc, Tc, buf, wsum, let_out):
    """``_cell_transport`` on a pitch curve: the rim carries the cells by the arcs de past the entry and dx
    past the exit (signed, belt order positive; they differ as the curve turns) while the wrap's arc goes
    from n ds0 to n ds1: cell j's belt was at (j + 1/2) ds1 - de along the old cells, each cell its own
    cubic; fresh belt (no bristle deflection) enters at the entry (tension Tin) when de > 0, at the exit
    (Tout) when dx < 0. Returns (the belt that came in past the entry, the belt that left past the exit),
    unstretched m, belt order positive: belt conserved as there."""
    w0c = wsum[k]
    for arr in range(2):
        A = zc if arr == 0 else Tc
        below = (0.0 if arr == 0 else Tin) if de >= 0.0 else A[k, 0]
        beyond = (0.0 if arr == 0 else Tout) if dx < 0.0 else A[k, n - 1]
        for j in range(n):
            x = ((j + 0.5) * ds1 - de) / ds0 - 0.5
            fx = math.floor(x)
            i = int(fx)
            wm, w0, w1, w2 = _cubic(x - fx)[:4]
            buf[j] = _stencil(A, k, i, n, below, beyond, wm, w0, w1, w2)
        for j in range(n):
            A[k, j] = buf[j]
    w1c = _content_sum(Tc[k], n, c, r, p0, EA, c1, c2)
    wsum[k] = w1c
    # the flux where fresh belt enters is its content; the other end's is what the wrap's balance leaves
    dw = w1c * ds1 - w0c * ds0
    if de >= 0.0:
        gin = de * _content(Tin, c, r, p0, EA, c1, c2)
        return gin, gin - dw - let_out
    out = dx * _content(Tout if dx < 0.0 else Tc[k, n - 1], c, r, p0, EA, c1, c2)
    return out + dw + let_out, out


@njit(cache=True, inline="always")
def _tension(EA, L, u):
    return EA * (L / u - 1.0)


@njit(cache=True, inline="always")
def _return_map(nk, EA, m, mu, u, vs, L, wrap, slip, h, passes, grooved):
    """Gross slip: where a wrap's tension ratio (T_hi - c) / (T_lo - c) exceeds e^(mu theta), the
    belt slides over the whole wrap from the slack to the tight span until the ratio is at the
    limit (Coulomb's law on the wrap, as a return map; Gauss-Seidel over the wraps, which share
    spans). Returns the friction power of the sliding (W)."""
    P = 0.0
    for k in range(nk):
        slip[k] = 0.0
    for _ in range(passes):
        moved = False
        for k in range(nk):
            if grooved[k]:             # teeth in grooves: no slip (a tooth climbs instead: rotational/teeth.py)
                continue
            ji = (k - 1) % nk          # the span arriving at pulley k (belt order)
            jo = k
            v = 0.5 * (vs[ji] + vs[jo])
            c = m * v * v
            if L[ji] / u[ji] >= L[jo] / u[jo]:
                hi, lo, sgn = ji, jo, -1.0      # material slides back, from span jo into ji
            else:
                hi, lo, sgn = jo, ji, 1.0
            Lh, Ll, uh, ul = L[hi], L[lo], u[hi], u[lo]
            lim = math.exp(mu[k] * wrap[k])
            f = (EA * (Lh / uh - 1.0) - c) - lim * (EA * (Ll / ul - 1.0) - c)
            if f <= 1e-9 * EA:
                continue
            # f(d) = EA Lh / (uh + d) - lim EA Ll / (ul - d) + const, decreasing and convex: Newton from 0
            d = 0.0
            for _it in range(30):
                fd = EA * (Lh / (uh + d) - 1.0) - c - lim * (EA * (Ll / (ul - d) - 1.0) - c)
                dfd = -EA * Lh / (uh + d) ** 2 - lim * EA * Ll / (ul - d) ** 2
                step = fd / dfd
                d -= step
                if abs(step) < 1e-15 * (uh + ul):
                    break
            if d <= 0.0:
                continue
            u[hi] = uh + d
            u[lo] = ul - d
            slip[k] += sgn * d
            # work of the tension difference on the sliding belt (mean of before and after)
            dT = 0.5 * (EA * (Lh / uh - Ll / ul) + EA * (Lh / (uh + d) - Ll / (ul - d)))
            P += dT * d / h
            moved = True
        if not moved:
            break
    return P


@njit(cache=True)
def energy(R, P, A, S, RS, RW):
    """Mechanical energy (J): pulleys, rotors and arms; tensioner springs; the spans' and the
    wraps' strain energy (a wrap at its arriving span's strain)."""
    geometry(R, S.q, S.qd, RW.L, RW.Ld, RW.t0, RW.t1, RW.dx, RW.dy, RW.wrap, S.th, S.om, RW.rin, RW.rout)
    return _energy_at(R, P, A, S, RS, RW)


@njit(cache=True, inline="always")
def _energy_at(R, P, A, S, RS, RW):
    """``energy`` with RW's geometry already that of the state (as the step leaves it)."""
    E = 0.0
    for k in range(R.nk):
        if P.mode[k] == 0:        # a prescribed pulley's work is its belt torque's (as the segment model's)
            E += 0.5 * P.inertia[k] * S.om[k] ** 2
        if P.cl_kind[k] > 0:
            E += 0.5 * P.cl_ir[k] * S.omr[k] ** 2
            if P.cl_kind[k] == 2:
                E += 0.5 * P.cl_k[k] * S.dcp[k] ** 2
    for a in range(A.na):
        E += 0.5 * A.inertia[a] * S.qd[a] ** 2 + BK.spring_energy(A, a, S.q[a])
    for j in range(R.nk):
        uj = RS.u[j]
        eps = RW.L[j] / uj - 1.0
        if eps > 0.0:
            E += 0.5 * R.EA * eps * eps * uj
        ji = (j - 1) % R.nk
        e_in = RW.L[ji] / RS.u[ji] - 1.0
        if e_in > 0.0 and not R.grooved[j]:      # a tooth chain's energy is its eb
            E += 0.5 * R.EA * e_in * e_in * RS.W[j]
        E += RS.eb[j]
    return E


# compiled without numba's reference counting (it allocates nothing): each array a stage inlined in
# the step loop takes, or a record's field it reads (the segment model's _step_pulleys reads about
# forty), otherwise costs an atomic reference-count pair per step. Fast-math without its no-NaN and
# no-infinity assumptions (a run that diverges must still show it): reassociated sums and reciprocals,
# 11-15 % of the step
@njit(cache=True, _nrt=False, fastmath={"nsz", "arcp", "contract", "afn", "reassoc"})
def run_samples(k0, k1, steps, t, h, R, P, A, S, W, RS, RW, passes, with_energy, out_t, out_th, out_om, out_tq, out_tb,
                out_hx, out_hy, out_pin, out_T, out_v, out_slip, out_gross, out_q, out_qd, out_omr, out_E,
                out_work, out_diss):
    """Samples k0..k1-1 of ``steps`` steps each: interval means of the loads, tensions, speeds and
    slips, the state at the sample's end, cumulative work in and dissipation and, with_energy, the
    mechanical energy. Returns the time."""
    nk = R.nk
    EA, bax, m, c1, c2 = R.EA, R.bax, R.m, R.c1, R.c2
    centre = R.centre                       # the belt runs on r - p(T) (friction.radius = "centre")
    rho, mu = R.rho, R.mu
    Lr, dxr, dyr, wr, q0, dq, tL, tt0, tt1, tdx, tdy, tw = R.L, R.dx, R.dy, R.wrap, R.q0, R.dq, R.tL, R.t0, R.t1, R.tdx, R.tdy, R.tw
    L, Ld, t0, t1, dx, dy, wrap = RW.L, RW.Ld, RW.t0, RW.t1, RW.dx, RW.dy, RW.wrap
    T, fa, fb, tq, hubx, huby, slip = RW.T, RW.a, RW.b, RW.tq, RW.hubx, RW.huby, RW.slip
    acc_T, acc_v, acc_slip, acc_gross, acc_diss = RW.acc_T, RW.acc_v, RW.acc_slip, RW.acc_gross, RW.acc_diss
    u, Wc, ud, vs, rt0, rt1, Tp, ed = RS.u, RS.W, RS.ud, RS.vs, RS.t0, RS.t1, RS.Tp, RS.ed
    dmax, eb, bm, bv, exr = R.dmax, RS.eb, RW.bm, RW.bv, RW.ex
    Tm, wm = RW.Tm, RW.wm
    ncell, zc, Tc, Kc, Fc, Xc, Yc, cpw, p0 = R.ncell, RS.zc, RS.Tc, RW.Kc, RW.Fc, RW.Xc, RW.Yc, RW.cp, R.p0
    ca, cb, ccw, cd, Tw0, Tw1, eww, offw, m0w, m1w = RW.ca, RW.cb, RW.cc, RW.cd, RW.Tw0, RW.Tw1, RW.ew, RW.off, RW.m0, RW.m1
    ebw = RW.eb0
    chain, grooved, pr, ga, gb, gc, gd, trest = R.chain, R.grooved, R.pr, R.ga, R.gb, R.gc, R.gd, R.trest
    cw0, cw1 = RS.cw0, RS.cw1
    cpul, cP, csig, cper, cL, cdx, cdy, cw, crin, crout, cse, csx = (R.cpul, R.cP, R.csig, R.cper, R.cL, R.cdx, R.cdy,
                                                                    R.cw, R.crin, R.crout, R.cse, R.csx)
    ct0, ct1, cA, cW = R.ct0, R.ct1, R.cA, R.cW
    rin, rout, thb = RW.rin, RW.rout, RW.thb
    aw, rr = RW.aw, RW.rr
    wsw = RS.wsum
    dzw = RS.dz
    om, q, qd = S.om, S.q, S.qd
    na, apul, akind, apar, atoff, atx, aty = A.na, A.pulley, A.kind, A.par, A.tab_off, A.tab_x, A.tab_y
    scx, scy, scvx, scvy = S.cx, S.cy, S.cvx, S.cvy
    # the geometry of this state: after the first step, the one the last step left (the travel
    # moves only in the tensioners' stage, whose geometry the belt's stage computes)
    _geometry(Lr, dxr, dyr, wr, q0, dq, tL, tt0, tt1, tdx, tdy, tw, q, qd, L, Ld, t0, t1, dx, dy, wrap)
    _curve_geometry(rho, cpul, cP, cL, cdx, cdy, cw, crin, crout, ct0, ct1, S.th, om, L, Ld, t0, t1, dx, dy, wrap,
                            rin, rout)
    _wrap_arcs(rho, wrap, cpul, cP, cA, cW, S.th, aw, rr)
    interval = steps * h
    work = out_work[k0 - 1] if k0 > 0 else 0.0
    for ks in range(k0, k1):
        for j in range(nk):
            W.acc_tq_ext[j] = 0.0
            W.acc_tq_belt[j] = 0.0
            W.acc_hubx[j] = 0.0
            W.acc_huby[j] = 0.0
            W.acc_pin[j] = 0.0
            RW.acc_T[j] = 0.0
            RW.acc_v[j] = 0.0
            RW.acc_slip[j] = 0.0
            RW.acc_gross[j] = 0.0
        for i in range(6):
            RW.acc_diss[i] = 0.0
        for _ in range(steps):
            # --- forces of this state: span tensions (elastic + damper), belt torques and hub forces
            P_ax = 0.0
            for j in range(nk):
                uj = u[j]
                eps = L[j] / uj - 1.0
                epsd = Ld[j] / uj - L[j] * ud[j] / (uj * uj)
                # the damper's rate at the step's start (the contents' last change is half a
                # step back): extrapolated from the last two steps' rates
                ex = 1.5 * epsd - 0.5 * ed[j]
                ed[j] = epsd
                exr[j] = ex
                T[j] = EA * eps + bax * ex
            if dmax > 0.0:         # the wraps' belt gives where the spans pull (its cells)
                _cells_respond(nk, ncell, EA, c1, c2, m, mu, dmax, rho, om, wrap, zc, Tc, Kc, Fc, Xc, Yc, cpw, ca, cb,
                               ccw, cd, Tw0, Tw1, eww, dzw, aw, rr)
                _cells_couple(nk, EA, L, u, T, ca, cb, ccw, cd, Tw0, Tw1, bm, bv, offw, m0w, m1w)
            elif chain:            # the grooved wraps' tooth chains give where the spans pull
                _cells_couple(nk, EA, L, u, T, ga, gb, gc, gd, cw0, cw1, bm, bv, offw, m0w, m1w)
            for j in range(nk):
                Tj = T[j]
                if Tj < 0.0:          # a slack span carries nothing (the belt buckles)
                    Tj = 0.0
                else:
                    P_ax += bax * exr[j] * exr[j] * L[j]
                T[j] = Tj
                # the belt's stage moves the contents over the step at the new speeds: it reads
                # the tensions at the step's middle, extrapolated (second order in h; this step's
                # tensions there left the answers first order, twice the error at twice the step)
                Tx = 1.5 * Tj - 0.5 * Tp[j]
                Tm[j] = Tx if Tx > 0.0 else 0.0
                Tp[j] = Tj
            if dmax > 0.0:
                for k in range(nk):
                    ebw[k] = eb[k]
                _cells_update(nk, ncell, dmax, rho, wrap, T, zc, Tc, Xc, Yc, Fc, Tw0, Tw1, eww, eb, dzw, aw)
            elif chain:
                for k in range(nk):
                    if grooved[k]:
                        ebw[k] = eb[k]
                        cw0[k] = T[(k - 1) % nk]
                        cw1[k] = T[k]
                        eb[k] = chain_energy(ga[k], gb[k], gc[k], gd[k], trest, cw0[k], cw1[k])
            for k in range(nk):
                ji = (k - 1) % nk
                vw = rho[k] * om[k]
                c = m * vw * vw
                # the friction's moment on the pulley: the spans' pull (less the belt's momentum
                # flux) on the friction's radius at each end (friction.radius: r, or r - p(T))
                if centre:
                    r = abs(rho[k])
                    ro = r - sunk_depth((T[k] - c) / r, c1, c2)
                    ri = r - sunk_depth((T[ji] - c) / r, c1, c2)
                    tq[k] = (ro * (T[k] - c) - ri * (T[ji] - c)) * (1.0 if rho[k] >= 0.0 else -1.0)
                else:
                    # each span's pull on its lever arm (the effective radius: |rho| on a circle)
                    tq[k] = (rout[k] * T[k] - rin[k] * T[ji]) * (1.0 if rho[k] >= 0.0 else -1.0)
                # the wrap's pressure (T - c) / r: the hub carries the spans' pull less the belt's
                # centrifugal force on the wrap
                hubx[k] = (T[k] - c) * dx[k] - (T[ji] - c) * dx[ji]
                huby[k] = (T[k] - c) * dy[k] - (T[ji] - c) * dy[ji]
            # --- tensioners and pulleys: the segment model's stages
            for k in range(nk):
                thb[k] = S.th[k]
            P_arm = BK._step_arms(na, apul, akind, apar, atoff, atx, aty, q, qd, scx, scy, scvx, scvy, hubx, huby, h)
            diss_cl = BK._step_pulleys(t, h, tq, hubx, huby, P, S, W)
            for k in range(nk):
                wm[k] = wrap[k]
            # --- the belt: fluxes through the wraps at the new speeds, contents updated
            _geometry(Lr, dxr, dyr, wr, q0, dq, tL, tt0, tt1, tdx, tdy, tw, q, qd, L, Ld, t0, t1, dx, dy, wrap)
            _curve_geometry(rho, cpul, cP, cL, cdx, cdy, cw, crin, crout, ct0, ct1, S.th, om, L, Ld, t0, t1, dx, dy, wrap,
                            rin, rout)
            _wrap_arcs(rho, wrap, cpul, cP, cA, cW, S.th, aw, rr)
            P_fr = 0.0
            for k in range(nk):
                wm[k] = 0.5 * (wm[k] + wrap[k])      # the wraps at the step's middle
            for k in range(nk):
                ji = (k - 1) % nk
                vw = rho[k] * om[k]
                c = m * vw * vw
                Ti, To = Tm[ji], Tm[k]
                ei = Ti / EA
                eo = To / EA
                r = abs(rho[k])
                a = _curve_of(cpul, k) if not grooved[k] else -1
                if a >= 0:
                    # a smooth pitch curve: the rim carries its surface past the arriving and the leaving
                    # tangent points by the arcs de, dx (their arc positions' change: r omega h on a circle)
                    de = csig[a] * (_arc_position(cse, cper, a, thb[k], cP[a]) - _arc_position(cse, cper, a, S.th[k], cP[a]))
                    dxa = csig[a] * (_arc_position(csx, cper, a, thb[k], cP[a]) - _arc_position(csx, cper, a, S.th[k], cP[a]))
                    sg = 1.0 if rho[k] >= 0.0 else -1.0
                    # what the curve's own turn changed of its arc and wrap this step (a tensioner's travel
                    # rolls belt on and off as on a circle: the spans' rolled-on belt and the cells' balance)
                    dA = _periodic(cA, a, S.th[k], cP[a])[0] - _periodic(cA, a, thb[k], cP[a])[0]
                    dWr = _periodic(cW, a, S.th[k], cP[a])[0] - _periodic(cW, a, thb[k], cP[a])[0]
                    if dmax > 0.0:
                        n = ncell[k]
                        gin, out = _cell_transport_curve(k, n, rr[k], (aw[k] - dA) / n, aw[k] / n, de, dxa, T[ji], T[k], c,
                                                         p0[k], EA, c1, c2, zc, Tc, cpw, wsw, m1w[k] - m0w[k])
                        fa[k] = gin / h
                        fb[k] = out / h
                        Wc[k] += h * (fa[k] - fb[k]) + m0w[k] - m1w[k]
                        P_fr += (T[k] * (fb[k] * (1.0 + eo) * h + m1w[k]) - T[ji] * (fa[k] * (1.0 + ei) * h + m0w[k])) / h \
                            - tq[k] * om[k] - (eb[k] - ebw[k]) / h
                    else:
                        # the belt stuck to the rim follows the arc's change at once (the steady content at the
                        # arc of the step's start and end); what creep has yet to settle relaxes over a passage
                        t_a, t_b = (Ti, To) if de >= 0.0 else (To, Ti)
                        Weq = wrap_content(rr[k], wm[k], t_a, t_b, c, mu[k], EA, c1, c2)
                        Weq0 = wrap_content((aw[k] - dA) / (wrap[k] - dWr), wm[k] - dWr, t_a, t_b, c, mu[k], EA, c1, c2)
                        renew = 1.0 - math.exp(-abs(de) / (rr[k] * wm[k]))
                        dW = Weq - Weq0 + (Weq0 - Wc[k]) * renew
                        if de >= 0.0:
                            fa[k] = de / h / (1.0 + ei)
                            fb[k] = fa[k] - dW / h
                        else:
                            fb[k] = dxa / h / (1.0 + eo)
                            fa[k] = fb[k] + dW / h
                        Wc[k] += dW
                        P_fr += T[k] * fb[k] * (1.0 + eo) - T[ji] * fa[k] * (1.0 + ei) - tq[k] * om[k]
                    # the tangent points move along the spans as the curve turns (the spans' strain energy
                    # books that work): the belt's speed there is the flux's plus theirs
                    P_fr += T[k] * (sg * rout[k] * om[k] - dxa / h) - T[ji] * (sg * rin[k] * om[k] - de / h)
                    continue
                if dmax > 0.0:
                    # the rim carries the wrap's cells (their belt stuck to it) by vw h: fresh belt in at the
                    # arriving span's tension, and out the content the cells' shift passed the exit: belt
                    # is conserved step by step; the belt the cells let out (creep, pre-sliding, sliding)
                    # has moved the spans already
                    n = ncell[k]
                    ds = r * wrap[k] / n
                    Tf = T[ji] if vw >= 0.0 else T[k]
                    gin = vw * h * _content(Tf, c, r, p0[k], EA, c1, c2)
                    out = _cell_transport(k, n, r, ds, vw * h / ds, Tf, c, p0[k], EA, c1, c2, zc, Tc, cpw, wsw,
                                          m1w[k] - m0w[k])
                    if vw >= 0.0:
                        fa[k] = gin / h
                        fb[k] = out / h
                    else:
                        fb[k] = gin / h
                        fa[k] = -out / h
                    Wc[k] += h * (fa[k] - fb[k]) + m0w[k] - m1w[k]
                    P_fr += (T[k] * (fb[k] * (1.0 + eo) * h + m1w[k]) - T[ji] * (fa[k] * (1.0 + ei) * h + m0w[k])) / h \
                        - tq[k] * om[k] - (eb[k] - ebw[k]) / h
                    continue
                if grooved[k]:
                    # teeth in grooves: the belt passes at the grooves' rate, one belt pitch per groove (no
                    # creep); the chain's ends moved the spans already. Its power balance: the strain the
                    # belt takes from one span to the other through the chain (zero around the loop in a
                    # steady state)
                    fa[k] = vw * pr[k]
                    fb[k] = fa[k]
                    for a in range(cpul.shape[0]):
                        if cpul[a] == k:
                            # on a pitch curve: the belt the turning curve carries past each tangent point
                            # (its arc position moves by S(theta) there, not r dtheta)
                            fa[k] = csig[a] * pr[k] * (_arc_position(cse, cper, a, thb[k], cP[a])
                                                       - _arc_position(cse, cper, a, S.th[k], cP[a])) / h
                            fb[k] = csig[a] * pr[k] * (_arc_position(csx, cper, a, thb[k], cP[a])
                                                       - _arc_position(csx, cper, a, S.th[k], cP[a])) / h
                    Wc[k] += h * (fa[k] - fb[k]) + m0w[k] - m1w[k]
                    # the spans' power at the tangent points: tension x the belt's speed there, the curve's
                    # surface speed omega h (on a circle the flux's; a pitch curve's tangent points move along
                    # the spans, whose strain energy books that work)
                    sg = 1.0 if rho[k] >= 0.0 else -1.0
                    P_fr += (T[k] * (sg * rout[k] * om[k] * pr[k] * (1.0 + eo) * h + m1w[k])
                             - T[ji] * (sg * rin[k] * om[k] * pr[k] * (1.0 + ei) * h + m0w[k])) / h \
                        - tq[k] * om[k] - (eb[k] - ebw[k]) / h
                    continue
                # the belt arrives in adhesion: it moves with the pulley at the friction's radius
                # (r, or r - p(T_in)) at the strain of the span it comes from; the wrap's content
                # relaxes to its steady value over one passage
                ve = vw * (1.0 - sunk_depth(((Ti if vw >= 0.0 else To) - c) / r, c1, c2) / r) if centre else vw
                if vw >= 0.0:
                    Weq = wrap_content(r, wm[k], Ti, To, c, mu[k], EA, c1, c2)
                else:
                    Weq = wrap_content(r, wm[k], To, Ti, c, mu[k], EA, c1, c2)
                # the share of the wrap's belt that one step renews
                renew = 1.0 - math.exp(-h * abs(vw) / (r * wm[k])) if vw != 0.0 else 0.0
                dW = (Weq - Wc[k]) * renew
                if vw >= 0.0:
                    fa[k] = ve / (1.0 + ei)
                    fb[k] = fa[k] - dW / h
                else:
                    fb[k] = ve / (1.0 + eo)
                    fa[k] = fb[k] + dW / h
                Wc[k] += dW
                # friction (creep) power on the wrap: the spans' power in less the pulley's
                P_fr += T[k] * fb[k] * (1.0 + eo) - T[ji] * fa[k] * (1.0 + ei) - tq[k] * om[k]
            for j in range(nk):
                k1 = (j + 1) % nk
                eps = Tm[j] / EA
                # the tangent points' travel: belt rolled from the span onto its pulleys (adhesion)
                # (onto a grooved pulley: one belt pitch per groove)
                d0 = (t0[j] - rt0[j]) * pr[j] if grooved[j] else (t0[j] - rt0[j]) / (1.0 + eps)
                d1 = (t1[j] - rt1[j]) * pr[k1] if grooved[k1] else (t1[j] - rt1[j]) / (1.0 + eps)
                rt0[j] = t0[j]
                rt1[j] = t1[j]
                u_old = u[j]
                u[j] = u_old + h * (fb[j] - fa[k1]) - d0 - d1 + offw[j]
                Wc[j] += d0
                Wc[k1] += d1
                # (the rate once the return map has acted; without the belt the wraps let out, which the
                # step's tensions took in implicitly: the damper acting on it a step late runs away at
                # large belt.axial_damping)
                ud[j] = u_old + offw[j] if dmax > 0.0 or chain else u_old
                vs[j] = 0.5 * (fb[j] + fa[k1] + (m1w[j] + m0w[k1]) / h) * (1.0 + eps) if dmax > 0.0 or chain else \
                    0.5 * (fb[j] + fa[k1]) * (1.0 + eps)
            if dmax > 0.0:
                # the cells' belt as it now is (their wrap's arc, depth and stretch at this speed): what
                # the exchanges above left unbooked (the arc rolled on or off as a tensioner moves, the
                # centrifugal unloading's lift) comes from the two spans, half each: belt is conserved
                for k in range(nk):
                    wn = wsw[k] * aw[k] / ncell[k]
                    res = wn - Wc[k]
                    u[(k - 1) % nk] -= 0.5 * res
                    u[k] -= 0.5 * res
                    Wc[k] = wn
            P_sl = _return_map(nk, EA, m, mu, u, vs, L, wrap, slip, h, passes, grooved) if passes > 0 else 0.0
            for j in range(nk):
                ud[j] = (u[j] - ud[j]) / h
            for k in range(nk):
                acc_slip[k] += slip[k] * (1.0 + T[k] / EA)
                if slip[k] != 0.0:
                    acc_gross[k] += h
                acc_T[k] += h * T[k]
                acc_v[k] += h * vs[k]
            acc_diss[0] += h * P_ax
            acc_diss[3] += h * (P_fr + P_sl)
            acc_diss[4] += h * P_arm
            acc_diss[5] += diss_cl
            t += h
        out_t[ks] = t
        for j in range(nk):
            out_th[ks, j] = S.th[j]
            out_om[ks, j] = S.om[j]
            out_omr[ks, j] = S.omr[j]
            out_tq[ks, j] = W.acc_tq_ext[j] / interval
            out_tb[ks, j] = W.acc_tq_belt[j] / interval
            out_hx[ks, j] = W.acc_hubx[j] / interval
            out_hy[ks, j] = W.acc_huby[j] / interval
            out_pin[ks, j] = W.acc_pin[j] / interval
            out_T[ks, j] = RW.acc_T[j] / interval
            out_v[ks, j] = RW.acc_v[j] / interval
            out_slip[ks, j] = RW.acc_slip[j] / interval
            out_gross[ks, j] = RW.acc_gross[j] / interval
            work += W.acc_pin[j]
        for a in range(A.na):
            out_q[ks, a] = S.q[a]
            out_qd[ks, a] = S.qd[a]
        for i in range(6):
            out_diss[ks, i] = (out_diss[ks - 1, i] if ks > 0 else 0.0) + RW.acc_diss[i]
        out_work[ks] = work
        if with_energy:      # (the step left RW's geometry that of this state)
            out_E[ks] = _energy_at(R, P, A, S, RS, RW)
    return t
