"""The implicit scheme's linear algebra: the chain matrix factored along the segments' directions
(_chain.py) with the pulleys' columns, the base solve, the stick-slip active set pass by pass, the
velocity change, and which pulleys are integrated with the segments they anchor."""
import math

from numba import njit

from ..dynamics._bodies import (_small_solve)
from . import _chain
from .records import LAW_ELASTIC_PLASTIC, STAGE, STAGE_PY
from ._implicit_contacts import C_AK, C_ATR, C_ATX, C_ATY, C_CA, C_CAN, C_F0X, C_F0Y, C_F0Z, C_KAP, C_N, C_NX, C_NY, C_P, C_R, C_T, C_T0, C_T0B, C_TB, C_TMX, C_TMY, C_VPX, C_VPY, I_J, I_LIST, I_PEND, I_SLOT, _anchor, _pressed


# ---- tensioners ------------------------------------------------------------------------------


# ---- semi-implicit and implicit integrators ---------------------------------------------------

# the implicit scheme refactors its chain matrix once the fastest segment has turned this far
# (rad): the explicit forces are exact, the implicit terms act along the factored directions
# (see _chain.py), so a stuck segment's friction tilts by up to this angle. Loaded accessory drive
# at its default step, slips against the reference: free idler +0.027 points at 0.05 rad, +0.003
# at 0.02, -0.005 at 0.01; 1-2 % more factorisations on the 5PK (0.019 against 0.012 per step)
REFACTOR_ANGLE = 0.02
# segments whose stick-slip state differs from the factored one within a step (CMAX), and
# segments whose columns A_f^-1 [e_x e_y] are cached between factorisations (ZMAX)
CMAX = 8
ZMAX = 8
# passes of the stick-slip active set per step (each a small dense solve): anchors let go in any
# of them, sliding segments are anchored in all but the last; one more pass takes the last changes in
PASSES = 6


@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _refactor(n, h, hl, eax, eb, linear, kax, bax, kb, bb, c, s, w, phi, jfk, jdx, jdy, turn, m, ieff, sig, gam,
              geo, kap, kat, knx, kny, dmat, omat, emat, dinv, ymat, xmat):
    """Factor the chain matrix at the current angles (joint tangent stiffnesses at the current
    gaps); returns the number of steps it serves (turning of the fastest segment, REFACTOR_ANGLE).
    geo: scratch (n), the joints' geometric stiffness on the segments' rotation: the force F of a
    joint turning the arm a of a segment end stiffens that rotation by F . a (the tension's
    T l / 2 per end, which sets the segment-scale transverse waves, h < l / sqrt(T / rho),
    explicitly); taken only where positive so that A stays positive definite."""
    wmax = 0.0
    for i in range(n):
        geo[i] = 0.0
    for i in range(n):
        k = i - 1 if i > 0 else n - 1
        ga = jfk[i] * (jdx[i] * hl * c[k] + jdy[i] * hl * s[k])
        gb = jfk[i] * (jdx[i] * hl * c[i] + jdy[i] * hl * s[i])
        geo[k] += 0.5 * h * h * max(ga, 0.0)
        geo[i] += 0.5 * h * h * max(gb, 0.0)
        kt = kax[i]
        if not linear:   # tangent of kax |d|^e (its larger, radial-direction value)
            kt = kax[i] * max(eax, 1.0) * math.sqrt(jdx[i] * jdx[i] + jdy[i] * jdy[i]) ** (eax - 1.0)
        sig[i] = 0.5 * h * h * kt + h * bax[i]
        kbt = kb[i]
        if eb != 1.0:
            dphi = phi[i] - phi[k] + (turn if i == 0 else 0.0)
            kbt = kb[i] * eb * max(abs(dphi), 1e-6) ** (eb - 1.0)
        gam[i] = 0.5 * h * h * kbt + h * bb[i]
        wmax = max(wmax, abs(w[i]))
    _chain.factor(n, hl, c, s, m, ieff, sig, gam, geo, kap, kat, knx, kny, dmat, omat, emat, dinv, ymat, xmat)
    return max(1, min(1000, int(REFACTOR_ANGLE / (h * wmax + 1e-300))))


@njit(**STAGE_PY)
def _joint_transport(n, h, hl, linear, eax, kax, bax, c, s, w, jdx, jdy, fx, fy, mz):
    """Stage (implicit scheme): the joints' share of A acting on the gap's acceleration, not on its
    linear part alone. A's joint term sig G^T G reads the velocity change G dv of a joint's two
    ends, whose true gap acceleration also holds the ends' centripetal terms w_i^2 b + w_k^2 a. A
    chain rolling round a pulley keeps its gaps, yet G dv = -h w^2 (chord): read alone, every
    joint on a wrap pushed its segments apart by sig w^2 l, (h w)^2 EA / 2 (52 N at 0.024 rad per
    step on the 6PK belt: the implicit scheme's loss of accuracy at a large turn per step). Here
    the centripetal part joins the right-hand side, so that A acts on the deviation from rolling:
    the force -sig G^T q, q = w_i^2 b + w_k^2 a."""
    for j in range(n):
        k = j - 1 if j > 0 else n - 1
        kt = kax[j]
        if not linear:
            kt = kax[j] * max(eax, 1.0) * math.sqrt(jdx[j] * jdx[j] + jdy[j] * jdy[j]) ** (eax - 1.0)
        sig = 0.5 * h * h * kt + h * bax[j]
        ax = hl * c[k]
        ay = hl * s[k]
        bx = hl * c[j]
        by = hl * s[j]
        wi2 = w[j] * w[j]
        wk2 = w[k] * w[k]
        gx = -sig * (wi2 * bx + wk2 * ax)
        gy = -sig * (wi2 * by + wk2 * ay)
        fx[j] += gx
        fy[j] += gy
        mz[j] += by * gx - bx * gy
        fx[k] -= gx
        fy[k] -= gy
        mz[k] += ay * gx - ax * gy


@njit(**STAGE)
def _velocity_change(n, nk, nC, ipl, dom, qv, cseg, zslot, lin_u, zc, yx, yy, yz, fx, fy, mz):
    """Stage (implicit scheme, chain solve): the step's acceleration (fx, fy, mz) = A_f^-1 F from the
    base solve y, the implicit pulleys' speed changes dom over their columns U_k (lin_u) and the
    active set's force corrections qv over their cached columns Z_c (zc)."""
    for i in range(n):
        fx[i] = yx[i]
        fy[i] = yy[i]
        mz[i] = yz[i]
    for kk in range(nk):
        if ipl[kk]:
            dk = dom[kk]
            for i in range(n):
                fx[i] += dk * lin_u[kk, i, 0]
                fy[i] += dk * lin_u[kk, i, 1]
                mz[i] += dk * lin_u[kk, i, 2]
    for d in range(nC):
        sd = 2 * zslot[cseg[d]]
        p0 = qv[2 * d]
        p1 = qv[2 * d + 1]
        for i in range(n):
            fx[i] += p0 * zc[sd, i, 0] + p1 * zc[sd + 1, i, 0]
            fy[i] += p0 * zc[sd, i, 1] + p1 * zc[sd + 1, i, 1]
            mz[i] += p0 * zc[sd, i, 2] + p1 * zc[sd + 1, i, 2]


@njit(**STAGE)
def _factored_state(n, h, si, sc, fkap, fnx, fny, fca, far, kat, zslot):
    """Stage (implicit scheme): the contact and friction state A is about to be factored with
    (contact coefficients, normals, anchor slopes and arms); empties the cache of columns."""
    # A holds a segment's contact only while the contact pushes (N > 0). A segment that leaves
    # faster than the contact pushes (N <= 0: eq. 10 clips the force at zero, no adhesion) kept
    # A's contact damping h delta b, a damper that pulled it back and dissipated energy no loss term
    # counted: fead-runup's drive held at 3000 rpm without orders, 333 segments, lost 63 W unseen at
    # 11.4 us (efficiency 0.959; semi-implicit 0.965) and 13 W with this rule (0.968)
    for i in range(n):
        fkap[i] = sc[i, C_KAP] if _pressed(si[i, I_J], sc, i) else 0.0
        fnx[i] = sc[i, C_NX]
        fny[i] = sc[i, C_NY]
        fca[i] = sc[i, C_CA]
        far[i] = sc[i, C_R]
        kat[i] = h * sc[i, C_CA]
        zslot[i] = -1


@njit(**STAGE)
def _pulley_columns(n, nk, nc, far, fca, fnx, fny, si, ipl, ux, uy, uz, lin_dinv, lin_y, lin_x, lin_r, lin_u, lin_g):
    """Stage (implicit scheme, after a factorisation): each implicit pulley's anchors
    g_k = sum fca r tau_f (r: each anchor's factored arm) and their columns U_k = A_f^-1 g_k
    (lin_u); lin_g holds G[j, k] = g_j . U_k and, in column nk, R_j = sum fca r^2."""
    for jj in range(nk):
        for kk in range(nk + 1):
            lin_g[jj, kk] = 0.0
    for jj in range(nk):
        if not ipl[jj]:
            continue
        for i in range(n):
            if fca[i] > 0.0 and si[i, I_J] == jj:
                ux[i] = fca[i] * far[i] * -fny[i]
                uy[i] = fca[i] * far[i] * fnx[i]
                lin_g[jj, nk] += fca[i] * far[i] * far[i]
            else:
                ux[i] = 0.0
                uy[i] = 0.0
            uz[i] = 0.0
        _chain.solve(n, ux, uy, uz, lin_dinv, lin_y, lin_x, lin_r)
        for i in range(n):
            lin_u[jj, i, 0] = ux[i]
            lin_u[jj, i, 1] = uy[i]
            lin_u[jj, i, 2] = uz[i]
    for q in range(nc):
        i = si[q, I_LIST]
        jj = si[i, I_J]
        if fca[i] > 0.0 and ipl[jj]:
            gx = fca[i] * far[i] * -fny[i]
            gy = fca[i] * far[i] * fnx[i]
            for kk in range(nk):
                if ipl[kk]:
                    lin_g[jj, kk] += gx * lin_u[kk, i, 0] + gy * lin_u[kk, i, 1]


@njit(**STAGE)
def _base_solve(n, nk, nc, nC, vx, vy, om, pvx, pvy, pr, fkap, fnx, fny, fca, far, si, cseg, sc, yx, yy, yz, s0,
                gyv, ipl, lin_dinv, lin_y, lin_x, lin_r):
    """Stage (implicit scheme, chain solve): y = A_f^-1 F_base, F_base the forces with every contact
    segment in its factored state (anchored along its factored tangent with its factored slope
    and arm, or sliding with its friction now), and per pulley the base friction torque s0 and
    g_j . y.
    Empties C (nC members before); lists in si[:, I_PEND] the segments whose state differs from
    the factored one. Returns their number."""
    for p in range(nC):
        si[cseg[p], I_SLOT] = -1
    npend = 0
    for i in range(n):
        yx[i] = sc[i, C_F0X]
        yy[i] = sc[i, C_F0Y]
        yz[i] = sc[i, C_F0Z]
    for jj in range(nk):
        s0[jj] = 0.0
        gyv[jj] = 0.0
    for q in range(nc):
        i = si[q, I_LIST]
        j = si[i, I_J]
        cT = sc[i, C_T]
        sc[i, C_TB] = cT
        sc[i, C_T0B] = sc[i, C_T0]
        s0[j] += sc[i, C_T0] * sc[i, C_R]
        if fkap[i] > 0.0:
            # the contact term of A, fkap fn fn^T, would read a segment's turn round the pulley
            # (its velocity turning inward by h v_t^2 / r) as an inward normal velocity change
            # and push back by fkap v_t^2 / r (outward; 90 N per segment at 23.6 m/s on a 75 mm
            # crank at 38.5 us, twice its normal force): taken out here, so that A's contact
            # term acts on the deviation from rolling round the pulley
            tvx = vx[i] - pvx[j]
            tvy = vy[i] - pvy[j]
            vt = -tvx * fny[i] + tvy * fnx[i]
            can = vt * vt / (pr[j] - sc[i, C_P])
            sc[i, C_CAN] = can
            yx[i] -= fkap[i] * can * fnx[i]
            yy[i] -= fkap[i] * can * fny[i]
        else:
            sc[i, C_CAN] = 0.0
        if fca[i] > 0.0:
            tx = -fny[i]
            ty = fnx[i]
            sl = (om[j] * far[i] - (vx[i] - pvx[j]) * tx - (vy[i] - pvy[j]) * ty
                  - sc[i, C_VPX] * (sc[i, C_TMX] - tx) - sc[i, C_VPY] * (sc[i, C_TMY] - ty))
            yx[i] += fca[i] * sl * tx + cT * sc[i, C_NY]
            yy[i] += fca[i] * sl * ty - cT * sc[i, C_NX]
            s0[j] += fca[i] * sl * far[i]
        else:
            s0[j] += cT * sc[i, C_R]
        if (fca[i] > 0.0) != (sc[i, C_CA] > 0.0):
            si[npend, I_PEND] = i
            npend += 1
    _chain.solve(n, yx, yy, yz, lin_dinv, lin_y, lin_x, lin_r)
    for q in range(nc):
        i = si[q, I_LIST]
        j = si[i, I_J]
        if fca[i] > 0.0 and ipl[j]:
            gyv[j] += fca[i] * far[i] * (-fny[i] * yx[i] + fnx[i] * yy[i])
    return npend


@njit(**STAGE)
def _join(n, nC, npend, si, cseg, zslot, zc, lin_cnt, ux, uy, uz, lin_dinv, lin_y, lin_x, lin_r):
    """Stage (implicit scheme, active set): the segments in si[:, I_PEND] join C, their columns
    Z = A_f^-1 [e_x e_y] solved unless cached. Returns (members, whether C or the cache is full:
    then the caller refactors)."""
    zcap = zc.shape[0] // 2
    for a in range(npend):
        i = si[a, I_PEND]
        if si[i, I_SLOT] >= 0:
            continue
        if nC == CMAX or (zslot[i] < 0 and lin_cnt[2] == zcap):
            return nC, True
        if zslot[i] < 0:
            sl_ = lin_cnt[2]
            lin_cnt[2] += 1
            zslot[i] = sl_
            for col in range(2):
                for r in range(n):
                    ux[r] = 0.0
                    uy[r] = 0.0
                    uz[r] = 0.0
                if col == 0:
                    ux[i] = 1.0
                else:
                    uy[i] = 1.0
                _chain.solve(n, ux, uy, uz, lin_dinv, lin_y, lin_x, lin_r)
                for r in range(n):
                    zc[2 * sl_ + col, r, 0] = ux[r]
                    zc[2 * sl_ + col, r, 1] = uy[r]
                    zc[2 * sl_ + col, r, 2] = uz[r]
        cseg[nC] = i
        si[i, I_SLOT] = nC
        nC += 1
    return nC, False


@njit(**STAGE)
def _corrections(nC, vx, vy, om, pvx, pvy, fnx, fny, fca, far, si, sc, cseg, cpar):
    """Stage (implicit scheme, active set): each member's force correction (its state now less its
    factored state), affine in its velocity change and its pulley's: phi_c = a + B dv_c + e dw_j,
    and its torque on the pulley's belt side alpha + beta . dv_c + gamma dw_j (the friction times
    its arm), into cpar (a0, a1, b00, b01, b11, e0, e1, alpha, beta0, beta1, gamma)."""
    for p in range(nC):
        i = cseg[p]
        j = si[i, I_J]
        ctx = -sc[i, C_NY]
        cty = sc[i, C_NX]
        a0 = 0.0
        a1 = 0.0
        b00 = 0.0
        b01 = 0.0
        b11 = 0.0
        e0 = 0.0
        e1 = 0.0
        al = 0.0
        be0 = 0.0
        be1 = 0.0
        ga = 0.0
        # an anchor's explicit force (elastic-plastic K z) now less the one in F_base
        dT0 = sc[i, C_T0] - sc[i, C_T0B]
        a0 += dT0 * ctx
        a1 += dT0 * cty
        al += dT0 * sc[i, C_R]
        for side in range(2):
            # + its state now (anchor along the current tangent, or its sliding friction),
            # - its factored state (anchor along the factored tangent, or its friction in F_base)
            if side == 0:
                sg, kp, tx, ty, Tsl, ar = 1.0, sc[i, C_CA], ctx, cty, sc[i, C_T], sc[i, C_R]
            else:
                sg, kp, tx, ty, Tsl = -1.0, fca[i], -fny[i], fnx[i], sc[i, C_TB]
                ar = far[i] if kp > 0.0 else sc[i, C_R]
            if kp > 0.0:
                sl = (om[j] * ar - (vx[i] - pvx[j]) * tx - (vy[i] - pvy[j]) * ty
                      - sc[i, C_VPX] * (sc[i, C_TMX] - tx) - sc[i, C_VPY] * (sc[i, C_TMY] - ty))
                a0 += sg * kp * sl * tx
                a1 += sg * kp * sl * ty
                b00 -= sg * kp * tx * tx
                b01 -= sg * kp * tx * ty
                b11 -= sg * kp * ty * ty
                e0 += sg * kp * ar * tx
                e1 += sg * kp * ar * ty
                al += sg * kp * sl * ar
                be0 -= sg * kp * tx * ar
                be1 -= sg * kp * ty * ar
                ga += sg * kp * ar * ar
            else:
                a0 += sg * Tsl * ctx
                a1 += sg * Tsl * cty
                al += sg * Tsl * ar
        cpar[p, 0] = a0
        cpar[p, 1] = a1
        cpar[p, 2] = b00
        cpar[p, 3] = b01
        cpar[p, 4] = b11
        cpar[p, 5] = e0
        cpar[p, 6] = e1
        cpar[p, 7] = al
        cpar[p, 8] = be0
        cpar[p, 9] = be1
        cpar[p, 10] = ga


@njit(**STAGE)
def _small_system(h, nk, nC, pinv_i, mext, zslot, zc, lin_u, lin_g, si, cseg, cpar, qm, qv, yx, yy, s0, gyv,
                  ipl, dom, lin_cnt):
    """Stage (implicit scheme, active set): the members' force corrections and the implicit
    pulleys' speed changes from the dense (2 nC + nk) system: rows 2p, 2p + 1 for member p, row
    2 nC + j for pulley j (its torque balance over the step, applied torque mext). Solved into
    qv; the speed changes into dom."""
    msz = 2 * nC + nk
    for r in range(msz):
        qv[r] = 0.0
        for q in range(msz):
            qm[r, q] = 0.0
    for p in range(nC):
        i = cseg[p]
        j = si[i, I_J]
        b00 = cpar[p, 2]
        b01 = cpar[p, 3]
        b11 = cpar[p, 4]
        r0 = 2 * p
        qm[r0, r0] = 1.0
        qm[r0 + 1, r0 + 1] = 1.0
        for d in range(nC):
            sd = 2 * zslot[cseg[d]]
            for col in range(2):
                z0 = zc[sd + col, i, 0]
                z1 = zc[sd + col, i, 1]
                qm[r0, 2 * d + col] -= h * (b00 * z0 + b01 * z1)
                qm[r0 + 1, 2 * d + col] -= h * (b01 * z0 + b11 * z1)
        for kk in range(nk):
            if ipl[kk]:
                u0 = lin_u[kk, i, 0]
                u1 = lin_u[kk, i, 1]
                qm[r0, 2 * nC + kk] -= h * (b00 * u0 + b01 * u1)
                qm[r0 + 1, 2 * nC + kk] -= h * (b01 * u0 + b11 * u1)
        qm[r0, 2 * nC + j] -= cpar[p, 5]
        qm[r0 + 1, 2 * nC + j] -= cpar[p, 6]
        qv[r0] = cpar[p, 0] + h * (b00 * yx[i] + b01 * yy[i])
        qv[r0 + 1] = cpar[p, 1] + h * (b01 * yx[i] + b11 * yy[i])
    for jj in range(nk):
        r0 = 2 * nC + jj
        if not ipl[jj]:
            qm[r0, r0] = 1.0
            continue
        qm[r0, r0] += 1.0 / pinv_i[jj] + h * lin_g[jj, nk]
        for kk in range(nk):
            qm[r0, 2 * nC + kk] -= h * h * lin_g[jj, kk]
        for d in range(nC):
            qm[r0, 2 * d] -= h * h * lin_u[jj, cseg[d], 0]
            qm[r0, 2 * d + 1] -= h * h * lin_u[jj, cseg[d], 1]
        qv[r0] = h * mext[jj] - h * s0[jj] + h * h * gyv[jj]
        for p in range(nC):
            i = cseg[p]
            if si[i, I_J] != jj:
                continue
            be0 = cpar[p, 8]
            be1 = cpar[p, 9]
            qm[r0, r0] += h * cpar[p, 10]
            for kk in range(nk):
                if ipl[kk]:
                    qm[r0, 2 * nC + kk] += h * h * (be0 * lin_u[kk, i, 0] + be1 * lin_u[kk, i, 1])
            for d in range(nC):
                sd = 2 * zslot[cseg[d]]
                for col in range(2):
                    qm[r0, 2 * d + col] += h * h * (be0 * zc[sd + col, i, 0] + be1 * zc[sd + col, i, 1])
            qv[r0] -= h * (cpar[p, 7] + h * (be0 * yx[i] + be1 * yy[i]))
    _small_solve(msz, qm, qv)
    for jj in range(nk):
        dom[jj] = qv[2 * nC + jj]
    lin_cnt[3] += 1


@njit(**STAGE)
def _check(h, nk, nc, nC, npend, npass, Ct, vx, vy, om, pvx, pvy, fnx, fny, fca, far, stk, z, zslot,
           zc, lin_u, lin_stat, si, sc, cseg, yx, yy, qv, dom, ipl):
    """Stage (implicit scheme, active set): every contact segment at the velocity pass npass
    solved. An anchor whose force would exceed mu N lets go (slides with mu N this step) in any
    of the PASSES, a sliding segment whose slip the step would turn sticks in all but the last.
    Changed segments not in C join si[:, I_PEND]. Returns (whether any changed, their number)."""
    mu, law, dv, dmax = Ct.mu, Ct.law, Ct.dv, Ct.dmax
    changed = False
    for q in range(nc):
        i = si[q, I_LIST]
        N = sc[i, C_N]
        if N <= 0.0:
            continue
        j = si[i, I_J]
        ax_ = yx[i]
        ay_ = yy[i]
        for kk in range(nk):
            if ipl[kk]:
                ax_ += dom[kk] * lin_u[kk, i, 0]
                ay_ += dom[kk] * lin_u[kk, i, 1]
        for d in range(nC):
            sd = 2 * zslot[cseg[d]]
            ax_ += qv[2 * d] * zc[sd, i, 0] + qv[2 * d + 1] * zc[sd + 1, i, 0]
            ay_ += qv[2 * d] * zc[sd, i, 1] + qv[2 * d + 1] * zc[sd + 1, i, 1]
        rvx = vx[i] + h * ax_ - pvx[j]
        rvy = vy[i] + h * ay_ - pvy[j]
        nx = sc[i, C_NX]
        ny = sc[i, C_NY]
        if sc[i, C_CA] > 0.0:
            if si[i, I_SLOT] >= 0:
                kp = sc[i, C_CA]
                tx = -ny
                ty = nx
                ar = sc[i, C_R]
            else:
                kp = fca[i]
                tx = -fny[i]
                ty = fnx[i]
                ar = far[i]
            T = sc[i, C_T0] + kp * ((om[j] + dom[j]) * ar - rvx * tx - rvy * ty
                                    - sc[i, C_VPX] * (sc[i, C_TMX] - tx) - sc[i, C_VPY] * (sc[i, C_TMY] - ty))
            sc[i, C_AK] = kp           # the anchor as this pass solved it (the update reads it)
            sc[i, C_ATX] = tx
            sc[i, C_ATY] = ty
            sc[i, C_ATR] = ar
            if abs(T) > mu[i] * N and npass < PASSES:
                # lets go: slides this step with mu N
                Ts = math.copysign(mu[i] * N, T)
                sc[i, C_AK] = 0.0
                sc[i, C_CA] = 0.0
                stk[i] = 0.0
                sc[i, C_T] = Ts
                dT = Ts - sc[i, C_T0]
                sc[i, C_T0] = 0.0
                sc[i, C_F0X] += dT * -ny
                sc[i, C_F0Y] += dT * nx
                changed = True
                lin_stat[0] += 1
                if si[i, I_SLOT] < 0:
                    si[npend, I_PEND] = i
                    npend += 1
        elif sc[i, C_T] != 0.0 and npass < PASSES - 1:
            cT = sc[i, C_T]
            sl = (om[j] + dom[j]) * sc[i, C_R] - rvx * sc[i, C_TMX] - rvy * sc[i, C_TMY]
            if sl * cT < 0.0:
                # a sliding segment whose slip the step would turn: it sticks (elastic-plastic:
                # its bristle held at z, its force K z)
                ca, T0 = _anchor(law, mu[i], N, dv, dmax, h, z[i])
                sc[i, C_CA] = ca
                sc[i, C_F0X] += (T0 - cT) * -ny
                sc[i, C_F0Y] += (T0 - cT) * nx
                sc[i, C_T] = 0.0
                sc[i, C_T0] = T0
                stk[i] = 1.0
                changed = True
                lin_stat[1] += 1
                if si[i, I_SLOT] < 0:
                    si[npend, I_PEND] = i
                    npend += 1
    return changed, npend


# a pulley's speed joins the implicit scheme's chain solve where its stuck belt would turn it
# faster than an explicit step can follow: h^2 S / I above this (the explicit limit is 4)
PULLEY_IMPLICIT = 0.5


@njit(cache=True, inline="always")
def _implicit_pulleys(h, B, Ct, P, S, ipl):
    """Which dynamic pulleys (no clutch) the implicit scheme solves with the chain. Under
    Threlfall's law all: a stuck segment's anchor is a stiff viscous slope (mu N / Delta_v), which
    an explicit pulley would not follow. Under the elastic-plastic law the anchors are the
    bristles, a spring K = mu N / Delta_max each: the pulley's rotation on them has
    S = sum K r^2 (N m per rad, from each contact segment's elastic normal force now), and an
    explicit pulley is stable for h^2 S / I < 4; it stays explicit below PULLEY_IMPLICIT, where it
    spares the step a chain solve per pulley and factorisation (fead-runup's drive held with its
    orders, 333 segments, 0.016 rad per step on the alternator: 1.2-1.3x faster at 1000 and 5000
    rpm, 1.5-1.6x at 3000, bands within 1 % of the implicit pulleys'; benchmarks/bench_fead_schemes.py)."""
    nk = P.nk
    for j in range(nk):
        ipl[j] = False
        if P.mode[j] != 0 or P.cl_kind[j] != 0:
            continue
        if Ct.law != LAW_ELASTIC_PLASTIC:
            ipl[j] = True
            continue
        stiff = 0.0
        for i in range(B.n):
            rx = S.x[i] - S.cx[j]
            ry = S.y[i] - S.cy[j]
            d2 = rx * rx + ry * ry
            if d2 < P.r[j] * P.r[j]:
                p = P.r[j] - math.sqrt(d2)
                arm = math.sqrt(d2) if Ct.centre else P.r[j]
                stiff += Ct.mu[i] * (Ct.c1[i] * p * p + Ct.c2[i] * p) / Ct.dmax * arm * arm
        ipl[j] = h * h * stiff * P.inv_i[j] > PULLEY_IMPLICIT
    return ipl
