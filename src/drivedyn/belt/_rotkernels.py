"""Compiled step of the rotational belt-drive model (rotational.py states the formulation).

One unknown per pulley (angle, speed; a clutch rotor behind it), per tensioner (travel, rate) and
per span and wrap (their unstretched belt contents u and W). The pulleys, clutches and tensioners
advance through the same stages as the segment model (``_kernels._step_pulleys``,
``_kernels._step_arms``): their loads, orders, clutch laws, springs, friction and stops are the
segment model's by construction. Symplectic Euler: forces from this step's state, then speeds,
then positions and belt contents; gross slip by a return map on each wrap's tension ratio.
"""
import math
from typing import NamedTuple

import numpy as np
from numba import njit

from . import _kernels as K


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


#: Gauss-Legendre nodes and weights on [0, 1] for the belt's depth along a slip arc (steady.py)
_X, _WG = np.polynomial.legendre.leggauss(8)
GL_X = 0.5 * (_X + 1.0)
GL_W = 0.5 * _WG


@njit(cache=True, inline="always")
def _depth(q, c1, c2):
    """Depth p (m) at which the contact law carries q (N/m): c1 p^2 + c2 p = q (steady.penetration)."""
    if q <= 0.0:
        return 0.0
    return 2.0 * q / (c2 + math.sqrt(c2 * c2 + 4.0 * c1 * q))


@njit(cache=True)
def wrap_content(r, theta, t_in, t_out, c, mu, EA, c1, c2):
    """Unstretched belt on a wrap in steady running (steady._wrap_length): an adhesion arc at the
    entry tension, then a slip arc where T - c ~ exp(+-mu phi), the belt at the depth of its
    contact pressure (T - c) / r."""
    p_in = _depth((t_in - c) / r, c1, c2)
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
    for g in range(8):
        T = c + (t_in - c) * math.exp(k * phi * GL_X[g])
        sink += GL_W[g] * _depth((T - c) / r, c1, c2) / (1.0 + T / EA)
    return adh + r * (phi - math.log((1.0 + t_end / EA) / (1.0 + t_in / EA)) / k) / B - sink * phi


@njit(cache=True, inline="always")
def _locate(q, q0, dq, ng):
    x = (q - q0) / dq
    i = int(math.floor(x))
    if i < 0:
        i = 0
    elif i > ng - 2:
        i = ng - 2
    return i, x - i


@njit(cache=True)
def geometry(R, q, qd, L, Ld, t0, t1, dx, dy, wrap):
    """Span lengths L (and their rates Ld), the belt rolled onto each span's ends t0, t1 (from
    rest), span directions and wrap angles at tensioner travel q (rates qd): the rest geometry plus
    each tensioner's change, read from its table (linear between grid points)."""
    ns = R.L.shape[0]
    for j in range(ns):
        L[j] = R.L[j]
        Ld[j] = 0.0
        t0[j] = 0.0
        t1[j] = 0.0
        dx[j] = R.dx[j]
        dy[j] = R.dy[j]
    for k in range(R.nk):
        wrap[k] = R.wrap[k]
    na = q.shape[0]
    for a in range(na):
        ng = R.tL.shape[1]
        i, f = _locate(q[a], R.q0[a], R.dq[a], ng)
        g = 1.0 - f
        for j in range(ns):
            L[j] += g * R.tL[a, i, j] + f * R.tL[a, i + 1, j]
            Ld[j] += (R.tL[a, i + 1, j] - R.tL[a, i, j]) / R.dq[a] * qd[a]
            t0[j] += g * R.t0[a, i, j] + f * R.t0[a, i + 1, j]
            t1[j] += g * R.t1[a, i, j] + f * R.t1[a, i + 1, j]
            dx[j] += g * R.tdx[a, i, j] + f * R.tdx[a, i + 1, j]
            dy[j] += g * R.tdy[a, i, j] + f * R.tdy[a, i + 1, j]
        for k in range(R.nk):
            wrap[k] += g * R.tw[a, i, k] + f * R.tw[a, i + 1, k]
    for j in range(ns):
        n = math.sqrt(dx[j] * dx[j] + dy[j] * dy[j])
        dx[j] /= n
        dy[j] /= n


class RotState(NamedTuple):
    u: np.ndarray            # unstretched belt in each span (m)
    W: np.ndarray            # unstretched belt on each wrap (m)
    ud: np.ndarray           # du/dt of the last step (the span dampers' strain rate)
    vs: np.ndarray           # material speed in each span along the belt order (m/s), last step
    t0: np.ndarray           # belt rolled onto the span ends at the last step (m)
    t1: np.ndarray


class RotWork(NamedTuple):
    L: np.ndarray
    Ld: np.ndarray
    t0: np.ndarray
    t1: np.ndarray
    dx: np.ndarray
    dy: np.ndarray
    wrap: np.ndarray
    T: np.ndarray            # span tensions of the step (N)
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


@njit(cache=True, inline="always")
def _tension(EA, L, u):
    return EA * (L / u - 1.0)


@njit(cache=True)
def _return_map(R, S, Wk, h, lim_passes):
    """Gross slip: where a wrap's tension ratio (T_hi - c) / (T_lo - c) exceeds e^(mu theta), the
    belt slides over the whole wrap from the slack to the tight span until the ratio is at the
    limit (Coulomb's law on the wrap, as a return map; Gauss-Seidel over the wraps, which share
    spans). Returns the friction power of the sliding (W)."""
    nk = R.nk
    EA = R.EA
    P = 0.0
    for k in range(nk):
        Wk.slip[k] = 0.0
    for _ in range(lim_passes):
        moved = False
        for k in range(nk):
            ji = (k - 1) % nk          # the span arriving at pulley k (belt order)
            jo = k
            vs = 0.5 * (S.vs[ji] + S.vs[jo])
            c = R.m * vs * vs
            Ti = _tension(EA, Wk.L[ji], S.u[ji])
            To = _tension(EA, Wk.L[jo], S.u[jo])
            lim = math.exp(R.mu[k] * Wk.wrap[k])
            if Ti >= To:
                hi, lo, sgn = ji, jo, -1.0      # material slides back, from span jo into ji
            else:
                hi, lo, sgn = jo, ji, 1.0
            Lh, Ll = Wk.L[hi], Wk.L[lo]
            uh, ul = S.u[hi], S.u[lo]
            f = (_tension(EA, Lh, uh) - c) - lim * (_tension(EA, Ll, ul) - c)
            if f <= 1e-9 * EA:
                continue
            # f(d) = EA Lh / (uh + d) - lim EA Ll / (ul - d) + const, decreasing: Newton from 0
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
            Th0 = _tension(EA, Lh, uh)
            Tl0 = _tension(EA, Ll, ul)
            S.u[hi] = uh + d
            S.u[lo] = ul - d
            Wk.slip[k] += sgn * d
            # work of the tension difference on the sliding belt (mean of before and after)
            dT = 0.5 * (Th0 - Tl0 + _tension(EA, Lh, uh + d) - _tension(EA, Ll, ul - d))
            P += dT * d / h
            moved = True
        if not moved:
            break
    return P


@njit(cache=True)
def step_chunk(nsteps, t, h, R, P, A, S, W, RS, RW, gross_passes):
    """Advance the drive nsteps steps of h from time t; accumulates (h-weighted) into W's and RW's
    accumulators. Returns the time reached."""
    nk = R.nk
    ns = nk
    EA, bax, m = R.EA, R.bax, R.m
    rho = R.rho
    na = A.na
    for _ in range(nsteps):
        # --- forces of this state: span tensions (elastic + damper), belt torques and hub forces
        geometry(R, S.q, S.qd, RW.L, RW.Ld, RW.t0, RW.t1, RW.dx, RW.dy, RW.wrap)
        P_ax = 0.0
        for j in range(ns):
            u = RS.u[j]
            eps = RW.L[j] / u - 1.0
            epsd = RW.Ld[j] / u - RW.L[j] * RS.ud[j] / (u * u)
            T = EA * eps + bax * epsd
            if T < 0.0:          # a slack span carries nothing (the belt buckles)
                T = 0.0
            else:
                P_ax += bax * epsd * epsd * RW.L[j]
            RW.T[j] = T
        for k in range(nk):
            ji = (k - 1) % nk
            vw = rho[k] * S.om[k]
            c = m * vw * vw
            RW.tq[k] = rho[k] * (RW.T[k] - RW.T[ji])
            # the wrap's pressure (T - c) / r: the hub carries the spans' pull less the belt's
            # centrifugal force on the wrap
            RW.hubx[k] = (RW.T[k] - c) * RW.dx[k] - (RW.T[ji] - c) * RW.dx[ji]
            RW.huby[k] = (RW.T[k] - c) * RW.dy[k] - (RW.T[ji] - c) * RW.dy[ji]
        # --- tensioners and pulleys: the segment model's stages
        P_arm = K._step_arms(na, A.pulley, A.kind, A.par, A.tab_off, A.tab_x, A.tab_y, S.q, S.qd, S.cx, S.cy,
                             S.cvx, S.cvy, RW.hubx, RW.huby, h)
        diss_cl = K._step_pulleys(t, h, RW.tq, RW.hubx, RW.huby, P, S, W)
        # --- the belt: fluxes through the wraps at the new speeds, contents updated
        geometry(R, S.q, S.qd, RW.L, RW.Ld, RW.t0, RW.t1, RW.dx, RW.dy, RW.wrap)
        P_fr = 0.0
        for k in range(nk):
            ji = (k - 1) % nk
            jo = k
            vw = rho[k] * S.om[k]
            c = m * vw * vw
            Ti, To = RW.T[ji], RW.T[jo]
            ei = Ti / EA
            eo = To / EA
            # the belt arrives in adhesion: it moves with the pulley surface at the strain of the
            # span it comes from; the wrap's content relaxes to its steady value over one passage
            r = abs(rho[k])
            if vw >= 0.0:
                Weq = wrap_content(r, RW.wrap[k], Ti, To, c, R.mu[k], EA, R.c1, R.c2)
            else:
                Weq = wrap_content(r, RW.wrap[k], To, Ti, c, R.mu[k], EA, R.c1, R.c2)
            if abs(vw) > 0.0:
                tau = r * RW.wrap[k] / abs(vw)
                dW = (Weq - RS.W[k]) * (1.0 - math.exp(-h / tau))
            else:
                dW = 0.0
            if vw >= 0.0:
                RW.a[k] = vw / (1.0 + ei)
                RW.b[k] = RW.a[k] - dW / h
            else:
                RW.b[k] = vw / (1.0 + eo)
                RW.a[k] = RW.b[k] + dW / h
            RS.W[k] += dW
            # friction (creep) power on the wrap: the spans' power in less the pulley's
            P_fr += To * RW.b[k] * (1.0 + eo) - Ti * RW.a[k] * (1.0 + ei) - RW.tq[k] * S.om[k]
        for j in range(ns):
            k1 = (j + 1) % nk
            eps = RW.T[j] / EA
            # the tangent points' travel: belt rolled from the span onto its pulleys (adhesion)
            d0 = (RW.t0[j] - RS.t0[j]) / (1.0 + eps)
            d1 = (RW.t1[j] - RS.t1[j]) / (1.0 + eps)
            RS.t0[j] = RW.t0[j]
            RS.t1[j] = RW.t1[j]
            u_old = RS.u[j]
            RS.u[j] = u_old + h * (RW.b[j] - RW.a[k1]) - d0 - d1
            RS.W[j] += d0
            RS.W[k1] += d1
            RS.ud[j] = u_old      # (the rate once the return map has acted)
            RS.vs[j] = 0.5 * (RW.b[j] + RW.a[k1]) * (1.0 + eps)
        P_sl = _return_map(R, RS, RW, h, gross_passes) if gross_passes > 0 else 0.0
        for j in range(ns):
            RS.ud[j] = (RS.u[j] - RS.ud[j]) / h
        for k in range(nk):
            RW.acc_slip[k] += RW.slip[k] * (1.0 + RW.T[k] / EA)
            if RW.slip[k] != 0.0:
                RW.acc_gross[k] += h
        for j in range(ns):
            RW.acc_T[j] += h * RW.T[j]
            RW.acc_v[j] += h * RS.vs[j]
        RW.acc_diss[0] += h * P_ax
        RW.acc_diss[3] += h * (P_fr + P_sl)
        RW.acc_diss[4] += h * P_arm
        RW.acc_diss[5] += diss_cl
        t += h
    return t


@njit(cache=True)
def energy(R, P, A, S, RS, RW):
    """Mechanical energy (J): pulleys, rotors and arms; tensioner springs; the spans' and the
    wraps' strain energy (a wrap at its arriving span's strain)."""
    E = 0.0
    for k in range(R.nk):
        E += 0.5 * P.inertia[k] * S.om[k] ** 2
        if P.cl_kind[k] > 0:
            E += 0.5 * P.cl_ir[k] * S.omr[k] ** 2
            if P.cl_kind[k] == 2:
                E += 0.5 * P.cl_k[k] * S.dcp[k] ** 2
    for a in range(A.na):
        E += 0.5 * A.inertia[a] * S.qd[a] ** 2 + K.spring_energy(A, a, S.q[a])
    geometry(R, S.q, S.qd, RW.L, RW.Ld, RW.t0, RW.t1, RW.dx, RW.dy, RW.wrap)
    for j in range(R.nk):
        eps = RW.L[j] / RS.u[j] - 1.0
        if eps > 0.0:
            E += 0.5 * R.EA * eps * eps * RS.u[j]
        ji = (j - 1) % R.nk
        e_in = RW.L[ji] / RS.u[ji] - 1.0
        if e_in > 0.0:
            E += 0.5 * R.EA * e_in * e_in * RS.W[j]
    return E


@njit(cache=True)
def run_samples(k0, k1, steps, t, h, R, P, A, S, W, RS, RW, passes, out_t, out_th, out_om, out_tq, out_tb,
                out_hx, out_hy, out_pin, out_T, out_v, out_slip, out_gross, out_q, out_qd, out_omr, out_E,
                out_work, out_diss):
    """Samples k0..k1-1 of ``steps`` steps each: interval means of the loads, tensions, speeds and
    slips, the state at the sample's end, cumulative work in and dissipation. Returns the time."""
    nk = R.nk
    interval = steps * h
    work = out_work[k0 - 1] if k0 > 0 else 0.0
    for k in range(k0, k1):
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
        t = step_chunk(steps, t, h, R, P, A, S, W, RS, RW, passes)
        out_t[k] = t
        for j in range(nk):
            out_th[k, j] = S.th[j]
            out_om[k, j] = S.om[j]
            out_omr[k, j] = S.omr[j]
            out_tq[k, j] = W.acc_tq_ext[j] / interval
            out_tb[k, j] = W.acc_tq_belt[j] / interval
            out_hx[k, j] = W.acc_hubx[j] / interval
            out_hy[k, j] = W.acc_huby[j] / interval
            out_pin[k, j] = W.acc_pin[j] / interval
            out_T[k, j] = RW.acc_T[j] / interval
            out_v[k, j] = RW.acc_v[j] / interval
            out_slip[k, j] = RW.acc_slip[j] / interval
            out_gross[k, j] = RW.acc_gross[j] / interval
            work += W.acc_pin[j]
        for a in range(A.na):
            out_q[k, a] = S.q[a]
            out_qd[k, a] = S.qd[a]
        for i in range(6):
            out_diss[k, i] = (out_diss[k - 1, i] if k > 0 else 0.0) + RW.acc_diss[i]
        out_work[k] = work
        out_E[k] = energy(R, P, A, S, RS, RW)
    return t
