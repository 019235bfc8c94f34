"""The semi-implicit scheme's contact stage: per segment, contact and friction implicit in its new
velocity under the joints and gravity, then the move. Its per-segment rows are defined here."""
import math

from numba import njit

from .records import LAW_ELASTIC_PLASTIC, STAGE
from ._laws import _bristle, clipped_power, friction, normal_force
from ._motion import _contact_candidate, _turn
from ._curves import contact_at


# the semi-implicit contact stage's per-segment rows of ``sq`` (Q_*, n): its contact pulley's
# offset (x, y, squared length), that pulley's centre velocity, radius and speed (a segment without
# one gets a stand-in that gives p = 0: no force), 1 in contact; the normal force, the unit normal,
# friction's arm, the slip before friction, the friction force; the contact damping's and friction's power;
# on a non-circular pulley tan and cos of its normal's angle to the radius (0 and 1 on a circle) and the
# normal force's arm about the axis (segments/_curves.py)
(Q_RX, Q_RY, Q_D2, Q_PVX, Q_PVY, Q_R, Q_OM, Q_ON, Q_N, Q_NX, Q_NY, Q_ARM, Q_WS, Q_T, Q_PC, Q_PF, Q_TB, Q_CB, Q_NA,
 NQ) = range(20)


@njit(**STAGE)
def _contacts_semi(n, nk, h, hg, hvb, hm_, hi_, fx, fy, mz, Ct, S, pr, cand_j, cand_skip, seg_n, seg_t, seg_p, sj, sq,
                   tq_belt, hubx, huby):
    """Stage (semi-implicit scheme): each segment's contact and friction at its new velocity under
    the joints and gravity, implicit in it (the contact damping and the regularised friction:
    ``normal_force``, ``friction``, the pulley's speed frozen over the step); then the move. Adds
    to the pulleys' belt torques and hub forces; returns the contact damping's and friction's power.

    In passes over the segments so that the arithmetic vectorises: the contact test (branches and
    a pulley index) and the sums (into the pulleys, and the powers: ``_advance`` is not compiled
    with fast-math, so a sum in a loop keeps it scalar) are loops of their own; between them every
    segment does the same arithmetic, a segment off the pulleys on a stand-in that gives no force.
    Written per segment with its branches, the stage compiled scalar: fead-runup's drive at 333
    segments stepped in 8.6-8.7 us, in 7.3-7.6 us with the passes (2-core AMD EPYC, alternating
    runs)."""
    c1, c2, bc, mu, pmax, law, dv, dmax, centre = Ct.c1, Ct.c2, Ct.bc, Ct.mu, Ct.pmax, Ct.law, Ct.dv, Ct.dmax, Ct.centre
    x, y, phi, c, s, vx, vy, w, om, z = S.x, S.y, S.phi, S.c, S.s, S.vx, S.vy, S.w, S.om, S.z
    pcx, pcy, pvx, pvy = S.cx, S.cy, S.cvx, S.cvy
    qrx = sq[Q_RX]
    qry = sq[Q_RY]
    qd2 = sq[Q_D2]
    qpvx = sq[Q_PVX]
    qpvy = sq[Q_PVY]
    qr = sq[Q_R]
    qom = sq[Q_OM]
    qon = sq[Q_ON]
    qn = sq[Q_N]
    qnx = sq[Q_NX]
    qny = sq[Q_NY]
    qarm = sq[Q_ARM]
    qws = sq[Q_WS]
    qt = sq[Q_T]
    qpc = sq[Q_PC]
    qpf = sq[Q_PF]
    qtb = sq[Q_TB]
    qcb = sq[Q_CB]
    qna = sq[Q_NA]
    ccur, crad, th = Ct.ccur, Ct.crad, S.th
    for i in range(n):          # the contact test
        j, rx, ry, d2 = _contact_candidate(i, nk, x, y, pcx, pcy, Ct.creach, cand_j, cand_skip, hvb)
        rj = 0.0
        tb = 0.0
        cb = 1.0
        if j >= 0:
            if ccur[j] >= 0:        # a curve: within its reach, in contact where inside it
                rj, tb, cb = contact_at(crad, ccur[j], rx, ry, th[j])
                if rj * rj <= d2:
                    j = -1
            else:
                rj = pr[j]
        sj[i] = j
        qtb[i] = tb
        qcb[i] = cb
        if j >= 0:
            qrx[i] = rx
            qry[i] = ry
            qd2[i] = d2
            qpvx[i] = pvx[j]
            qpvy[i] = pvy[j]
            qr[i] = rj
            qom[i] = om[j]
            qon[i] = 1.0
        else:
            qrx[i] = 1.0        # the stand-in: p = 0, no force
            qry[i] = 0.0
            qd2[i] = 1.0
            qpvx[i] = 0.0
            qpvy[i] = 0.0
            qr[i] = 1.0
            qom[i] = 0.0
            qon[i] = 0.0
    for i in range(n):          # the normal force, implicit in the contact damping
        hm = hm_[i]
        dist = math.sqrt(qd2[i])
        inv = 1.0 / dist
        erx = qrx[i] * inv
        ery = qry[i] * inv
        tb = qtb[i]
        cb = qcb[i]
        nx = cb * (erx + tb * ery)
        ny = cb * (ery - tb * erx)
        p = (qr[i] - dist) * cb
        # velocities relative to the pulley centre (a tensioner moves it), and to a curve's surface
        # moving along its normal, omega d e_psi . n = -omega d sin(mu)
        rvx = vx[i] + hm * fx[i] - qpvx[i]
        rvy = vy[i] + hm * fy[i] - hg - qpvy[i]
        vn = rvx * nx + rvy * ny + qom[i] * dist * tb * cb
        N, db = normal_force(c1[i], c2[i], bc[i], pmax, p, vn, hm)
        Np = max(N, 0.0)
        vn_new = vn + hm * Np
        qpc[i] = db * vn_new * vn_new if N > 0.0 else clipped_power(c1[i], c2[i], p, vn)
        arm = (dist if centre else qr[i]) * cb
        qna[i] = dist * tb * cb
        qn[i] = Np
        qnx[i] = nx
        qny[i] = ny
        qarm[i] = arm
        # slip of the pulley surface relative to the segment, along tau = Z x n = (-ny, nx)
        qws[i] = qom[i] * arm - (rvx * -ny + rvy * nx)
        seg_p[i] = p
    if law == LAW_ELASTIC_PLASTIC:
        for i in range(n):      # friction: ``friction``'s bristle, every segment (N = 0: no force)
            T, sl, zn = _bristle(mu[i] * qn[i], dmax, qws[i], z[i], h, hm_[i])
            z[i] = zn if qn[i] > 0.0 else z[i] * qon[i]
            qt[i] = T
            qpf[i] = T * sl
    else:
        for i in range(n):
            T = 0.0
            sl = 0.0
            if qn[i] > 0.0:
                T, sl = friction(mu[i], law, dv, dmax, qn[i], qws[i], hm_[i], h, z, i)
            elif qon[i] == 0.0:
                z[i] = 0.0
            qt[i] = T
            qpf[i] = T * sl
    for i in range(n):          # the force N n + T tau acts; the move
        hm = hm_[i]
        N = qn[i]
        T = qt[i]
        fcx = N * qnx[i] - T * qny[i]
        fcy = N * qny[i] + T * qnx[i]
        qrx[i] = fcx
        qry[i] = fcy
        seg_n[i] = N
        seg_t[i] = T
        vxs = vx[i] + hm * (fx[i] + fcx)
        vys = vy[i] + hm * (fy[i] + fcy) - hg
        vx[i] = vxs
        vy[i] = vys
        x[i] += h * vxs
        y[i] += h * vys
    for i in range(n):          # the turn (a loop of its own: one loop writing all twelve arrays compiled scalar)
        w[i] += hi_[i] * mz[i]
        _turn(i, h, w, phi, c, s)
    # the belt's torque and force on its pulleys, summed along each run of segments on one pulley
    # (not into the pulley's entry per segment: a chain through memory); the powers' sums
    pcd = 0.0
    pfr = 0.0
    jr = -1
    tq = 0.0
    hx = 0.0
    hy = 0.0
    for i in range(n):
        pcd += qpc[i]
        pfr += qpf[i]
        j = sj[i]
        if j != jr:
            if jr >= 0:
                tq_belt[jr] -= tq
                hubx[jr] -= hx
                huby[jr] -= hy
            jr = j
            tq = 0.0
            hx = 0.0
            hy = 0.0
        tq += qarm[i] * qt[i] - qna[i] * qn[i]
        hx += qrx[i]
        hy += qry[i]
    if jr >= 0:
        tq_belt[jr] -= tq
        hubx[jr] -= hx
        huby[jr] -= hy
    return pcd, pfr
