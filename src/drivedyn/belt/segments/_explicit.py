"""The explicit right-hand side of the seed's equations and the RKF45 (Fehlberg 4(5)) integrator
over it: the seed's own scheme, kept as the reference the faster schemes are checked against."""

import numpy as np
from numba import njit

from ..dynamics._bodies import (State, external_torque, prescribed_speed)
from ._joints import _joint_forces_of
from ._laws import contact


# ---- explicit right-hand side and RKF45 -----------------------------------------------------

@njit(cache=True, no_cfunc_wrapper=True)
def rhs(t, yv, dy, B, Ct, P, W, z):
    """Explicit right-hand side of the seed's equations of motion (eqs. 21-22) for RKF45.

    State y = [x(n), y(n), phi(n), th(nk), vx(n), vy(n), w(n), om(nk)]. Contact damping and
    friction at the current velocities (``contact`` with hm = 0). Fills W: joint forces, seg_n,
    seg_t, tq_ext, tq_belt, hubx, huby, pin (per pulley) and diss (dissipation rates).
    """
    n = B.n
    nk = P.nk
    x = yv[0:n]
    y = yv[n:2 * n]
    phi = yv[2 * n:3 * n]
    th = yv[3 * n:3 * n + nk]
    o = 3 * n + nk
    vx = yv[o:o + n]
    vy = yv[o + n:o + 2 * n]
    w = yv[o + 2 * n:o + 3 * n]
    om = yv[o + 3 * n:o + 3 * n + nk].copy()
    for j in range(nk):
        if P.mode[j] == 1:
            om[j] = prescribed_speed(P, j, t)
    e0 = np.zeros(0)
    S = State(x, y, phi, np.cos(phi), np.sin(phi), vx, vy, w, th, om, z, P.cx, P.cy, np.zeros(nk), np.zeros(nk), e0, e0,
              np.zeros(nk), np.zeros(nk), np.zeros(nk), np.zeros(nk))
    pax, pb = _joint_forces_of(B, S, W, 0.0)
    pcd = 0.0
    pfr = 0.0
    for j in range(nk):
        W.tq_belt[j] = 0.0
        W.hubx[j] = 0.0
        W.huby[j] = 0.0
    for i in range(n):
        ax = W.fx[i]
        ay = W.fy[i] - B.m[i] * B.g
        Ntot = 0.0
        Ttot = 0.0
        for j in range(nk):
            rx = x[i] - P.cx[j]
            ry = y[i] - P.cy[j]
            d2 = rx * rx + ry * ry
            if d2 >= P.r[j] * P.r[j]:
                continue
            p, N, T, nx, ny, pc, pf = contact(Ct, i, rx, ry, d2, P.r[j], vx[i], vy[i], om[j], 0.0, 0.0, z)
            if N <= 0.0:
                continue
            pcd += pc
            pfr += pf
            ax += N * nx + T * -ny
            ay += N * ny + T * nx
            Ntot += N
            Ttot += T
            W.tq_belt[j] -= P.r[j] * T
            W.hubx[j] -= N * nx + T * -ny
            W.huby[j] -= N * ny + T * nx
        W.seg_n[i] = Ntot
        W.seg_t[i] = Ttot
        dy[i] = vx[i]
        dy[n + i] = vy[i]
        dy[2 * n + i] = w[i]
        dy[o + i] = ax / B.m[i]
        dy[o + n + i] = ay / B.m[i]
        dy[o + 2 * n + i] = W.mz[i] / (B.inertia[i] * B.iscale)
    W.diss[0] = pax
    W.diss[1] = pb
    W.diss[2] = pcd
    W.diss[3] = pfr
    for j in range(nk):
        dy[3 * n + j] = om[j]
        if P.mode[j] == 1:
            dy[o + 3 * n + j] = 0.0
            W.tq_ext[j] = 0.0
            W.pin[j] = -W.tq_belt[j] * om[j]
        else:
            M = external_torque(P, j, t, th[j], om[j])
            W.tq_ext[j] = M
            W.pin[j] = M * om[j]
            dy[o + 3 * n + j] = (M + W.tq_belt[j]) * P.inv_i[j]


# Runge-Kutta-Fehlberg 4(5) tableau (Fehlberg 1969), the seed's integrator
_C = np.array([0.0, 0.25, 3 / 8, 12 / 13, 1.0, 0.5])
_A = np.array([[0, 0, 0, 0, 0],
               [1 / 4, 0, 0, 0, 0],
               [3 / 32, 9 / 32, 0, 0, 0],
               [1932 / 2197, -7200 / 2197, 7296 / 2197, 0, 0],
               [439 / 216, -8, 3680 / 513, -845 / 4104, 0],
               [-8 / 27, 2, -3544 / 2565, 1859 / 4104, -11 / 40]])
_B4 = np.array([25 / 216, 0, 1408 / 2565, 2197 / 4104, -1 / 5, 0])
_B5 = np.array([16 / 135, 0, 6656 / 12825, 28561 / 56430, -9 / 50, 2 / 55])


@njit(cache=True, no_cfunc_wrapper=True)
def rkf45_chunk(t, t_end, h, yv, rtol, atol, max_steps, B, Ct, P, W, Wst, z):
    """Adaptive RKF45 from t to t_end (advancing with the 4th-order solution, error from the
    embedded 5th). The first stage writes W, the others the scratch Wst; W's accumulators get
    the h-weighted stage-1 outputs (acc_tq_ext, acc_tq_belt, acc_hubx, acc_huby, acc_pin,
    acc_diss). Returns (t, h, accepted steps, rejected steps); t < t_end means max_steps was hit."""
    N = yv.shape[0]
    nk = P.nk
    K = np.zeros((6, N))
    yt = np.zeros(N)
    acc = 0
    rej = 0
    while t < t_end and acc + rej < max_steps:
        if t + h > t_end:
            h = t_end - t
        rhs(t, yv, K[0], B, Ct, P, W, z)
        for st in range(1, 6):
            for q in range(N):
                v = yv[q]
                for r in range(st):
                    v += h * _A[st, r] * K[r, q]
                yt[q] = v
            rhs(t + _C[st] * h, yt, K[st], B, Ct, P, Wst, z)
        err = 0.0
        for q in range(N):
            y4 = yv[q]
            e5 = 0.0
            for r in range(6):
                y4 += h * _B4[r] * K[r, q]
                e5 += h * (_B5[r] - _B4[r]) * K[r, q]
            yt[q] = y4
            sc = atol + rtol * abs(yv[q])
            e = abs(e5) / sc
            if e > err:
                err = e
        if err <= 1.0 or not np.isfinite(err):
            if not np.isfinite(err):
                return t, h, acc, rej
            for q in range(4):
                W.acc_diss[q] += h * W.diss[q]
            for j in range(nk):
                W.acc_tq_ext[j] += h * W.tq_ext[j]
                W.acc_tq_belt[j] += h * W.tq_belt[j]
                W.acc_hubx[j] += h * W.hubx[j]
                W.acc_huby[j] += h * W.huby[j]
                W.acc_pin[j] += h * W.pin[j]
            for q in range(N):
                yv[q] = yt[q]
            t += h
            acc += 1
            fac = 5.0 if err == 0.0 else min(5.0, 0.9 * err ** -0.2)
        else:
            rej += 1
            fac = max(0.1, 0.9 * err ** -0.25)
        h *= fac
        if h < 1e-15:
            return t, h, acc, rej
    return t, h, acc, rej
