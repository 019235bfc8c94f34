"""What a step leaves for the outputs: the accumulators' share of a step, the chunk's end probe,
and the drive's energy (a test of the integrators)."""
import math

from numba import njit

from ..dynamics._bodies import (_spring_energy)
from .records import STAGE
from ._curves import contact_at


@njit(**STAGE)
def _accumulate(h, hl, x, y, c, s, vx, vy, jfk, jdx, jdy, seg_n, seg_t, span_geo, span_joint, track_seg, acc_span,
                acc_track, acc_diss, pax, pb, pcd, pfr, diss_cl):
    """Stage: the step's share of the accumulators: mid-span tension and belt speed (following the
    joint nearest each span's midpoint as the belt moves), tracked segments, dissipation."""
    n = x.shape[0]
    nspan = span_geo.shape[0]
    ntrack = track_seg.shape[0]
    # mid-span tension: follow the joint nearest each span's midpoint as the belt moves
    for q in range(nspan):
        best = span_joint[q]
        bestd = 1e300
        for dk in range(-2, 3):
            jj = span_joint[q] + dk
            if jj < 0:
                jj += n
            elif jj >= n:
                jj -= n
            kk = jj - 1 if jj > 0 else n - 1
            px = 0.5 * (x[jj] - hl * c[jj] + x[kk] + hl * c[kk]) - span_geo[q, 0]
            py = 0.5 * (y[jj] - hl * s[jj] + y[kk] + hl * s[kk]) - span_geo[q, 1]
            dd = px * px + py * py
            if dd < bestd:
                bestd = dd
                best = jj
        span_joint[q] = best
        acc_span[q, 0] += h * jfk[best] * math.sqrt(jdx[best] * jdx[best] + jdy[best] * jdy[best])
        kb_ = best - 1 if best > 0 else n - 1
        acc_span[q, 1] += h * 0.5 * ((vx[best] + vx[kb_]) * span_geo[q, 2] + (vy[best] + vy[kb_]) * span_geo[q, 3])
    for q in range(ntrack):
        i = track_seg[q]
        jn = i + 1 if i < n - 1 else 0       # the joint after segment i
        acc_track[q, 0] += h * jfk[jn] * math.sqrt(jdx[jn] * jdx[jn] + jdy[jn] * jdy[jn])
        acc_track[q, 1] += h * seg_n[i]
        acc_track[q, 2] += h * seg_t[i]
    acc_diss[0] += h * pax
    acc_diss[1] += h * pb
    acc_diss[2] += h * pcd
    acc_diss[3] += h * pfr
    acc_diss[5] += diss_cl


@njit(cache=True, inline="always")
def _probe(n, nk, S, P, W):
    """The run's health for the caller (simulate._healthy) in one pass, 0.5 us against 50 us for
    the same checks in numpy per output sample: a sum that is finite only if every coordinate and
    speed is, the largest squared segment speed, pulley surface speed, penetration, segment
    turning rate and pulley speed."""
    x, y, vx, vy, w, om, pr, seg_p = S.x, S.y, S.vx, S.vy, S.w, S.om, P.r, W.seg_p
    fin = 0.0
    v2m = 0.0
    pm = 0.0
    wm_ = 0.0
    wc = 0.0
    for i in range(n):
        fin += x[i] + y[i] + vx[i] + vy[i] + w[i]
        v2m = max(v2m, vx[i] * vx[i] + vy[i] * vy[i])
        pm = max(pm, seg_p[i])
        wm_ = max(wm_, abs(w[i]))
    sm = 0.0
    for j in range(nk):
        fin += om[j]
        sm = max(sm, abs(om[j]) * pr[j])
        wc = max(wc, abs(om[j]))
    W.probe[0] = fin
    W.probe[1] = v2m
    W.probe[2] = sm
    W.probe[3] = pm
    W.probe[4] = wm_
    W.probe[5] = wc


def energy(B, Ct, P, A, S):
    """Kinetic + potential energy (J): belt, dynamic pulleys, joints, bending, contact, gravity.
    The segments' rotational inertia is the one the integrator uses (times B.iscale). Called from
    Python through the arrays (``_energy``), whose compiled wrapper is cheap (the records' was
    most of 4.5 s of a first run's compile)."""
    return _energy(B.n, B.eax, B.eb, B.hl, B.turn, B.g, B.iscale, B.m, B.inertia, B.kax, B.kb, S.x, S.y, S.phi, S.c,
                   S.s, S.vx, S.vy, S.w, Ct.c1, Ct.c2, Ct.ccur, Ct.crad, P.nk, S.cx, S.cy, P.r, P.mode, P.inertia,
                   S.om, P.cl_kind, P.cl_ir, P.cl_k, S.omr, S.dcp, A.na, A.inertia, A.tab_off, A.tab_x, A.tab_y, A.preload, A.rate, A.qmin, A.qmax,
                   A.kstop, S.q, S.qd, S.th)


@njit(cache=True, inline="always")
def _energy_of(B, Ct, P, A, S):
    """``energy`` in a kernel: the same stage, for the same argument types (compiled once)."""
    return _energy(B.n, B.eax, B.eb, B.hl, B.turn, B.g, B.iscale, B.m, B.inertia, B.kax, B.kb, S.x, S.y, S.phi, S.c,
                   S.s, S.vx, S.vy, S.w, Ct.c1, Ct.c2, Ct.ccur, Ct.crad, P.nk, S.cx, S.cy, P.r, P.mode, P.inertia,
                   S.om, P.cl_kind, P.cl_ir, P.cl_k, S.omr, S.dcp, A.na, A.inertia, A.tab_off, A.tab_x, A.tab_y, A.preload, A.rate, A.qmin, A.qmax,
                   A.kstop, S.q, S.qd, S.th)


@njit(cache=True, no_cfunc_wrapper=True)
def _energy(n, eax, eb, hl, turn, g, iscale, m, inertia, kax, kb, x, y, phi, c, s, vx, vy, w, c1, c2, ccur, crad, nk, pcx,
            pcy, pr, pmode, pinertia, om, cl_kind, cl_ir, cl_k, omr, dcp, na, a_inertia, tab_off, tab_x, tab_y, preload, rate,
            qmin, qmax, kstop, q, qd, th):
    """``energy`` on the arrays it reads: the time loop calls it with these alone (the records
    passed whole flattened to 670 arguments)."""
    E = 0.0
    for i in range(n):
        E += 0.5 * m[i] * (vx[i] * vx[i] + vy[i] * vy[i]) + 0.5 * (inertia[i] * iscale) * w[i] * w[i] \
            + m[i] * g * y[i]
        k = i - 1 if i > 0 else n - 1
        dx = (x[i] - hl * c[i]) - (x[k] + hl * c[k])
        dy = (y[i] - hl * s[i]) - (y[k] + hl * s[k])
        dl = math.sqrt(dx * dx + dy * dy)
        E += kax[i] * dl ** (eax + 1.0) / (eax + 1.0)
        dphi = phi[i] - phi[k]
        if i == 0:
            dphi += turn
        E += kb[i] * abs(dphi) ** (eb + 1.0) / (eb + 1.0)
        for j in range(nk):
            rx = x[i] - pcx[j]
            ry = y[i] - pcy[j]
            if ccur[j] < 0:
                p = pr[j] - math.sqrt(rx * rx + ry * ry)
            else:
                rc, tb, cb = contact_at(crad, ccur[j], rx, ry, th[j])
                p = (rc - math.sqrt(rx * rx + ry * ry)) * cb
            if p > 0.0:     # (_laws.contact_energy on the contact's arrays: the record whole flattens to 50 arguments)
                E += c1[i] * p * p * p / 3.0 + c2[i] * p * p / 2.0
    for j in range(nk):
        if pmode[j] == 0:
            E += 0.5 * pinertia[j] * om[j] * om[j]
    for j in range(nk):   # accessory rotors behind clutches, decoupler springs
        if cl_kind[j] > 0:
            E += 0.5 * cl_ir[j] * omr[j] * omr[j] + 0.5 * cl_k[j] * dcp[j] * dcp[j]
    for a in range(na):   # arm or slider: kinetic (pulley mass included), spring and stops
        E += 0.5 * a_inertia[a] * qd[a] * qd[a] + _spring_energy(a, q[a], tab_off, tab_x, tab_y, preload, rate, qmin,
                                                                 qmax, kstop)
    return E
