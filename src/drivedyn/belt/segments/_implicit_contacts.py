"""The implicit scheme's contact stages: gravity and contact along the rolled chord, anchors
(stuck segments) and sliding friction, the free segments' spin damper, and the update at the
solved velocities (hub loads, the move). Its per-segment scratch columns are defined here."""
import math

from numba import njit

from .records import LAW_ELASTIC_PLASTIC, STAGE
from ._laws import clipped_power, normal_force
from ._motion import _contact_candidate, _move


# the anchor slope, x mu N / Delta_v: the secant of the Threlfall law to its saturation, so an
# anchor lets go where the law saturates (its tangent at zero, 1.5, flickered and drifted at 20 us)
ANCHOR = 1.0
# the implicit scheme's limiter of the segments' alternating rotation in free spans. Under tension
# T a segment of a free span rotating against its neighbours is held by T l alone (the joints do
# not stretch): omega^2 = 12 T / (m l), 6 kHz for 4.5 mm segments at 300 N, undamped (no bending
# damping by default) and resolved only marginally at the implicit scheme's 20-40 us, where segment
# transport can pump it: segments of the free spans spinning within milliseconds (the accessory
# drive at 337 segments halved its step four times, to 2.2 us). Where a free segment's rotation rate
# departs from its neighbours' mean by more than SPIN_LIMIT x the fastest pulley's speed (which
# ordinary running stays well below), a damper on the second difference of the rates (zero for a
# rigid turn and a uniformly changing one) gives that mode the damping ratio SPIN_ZETA; explicit,
# stable while zeta h omega < 1. Below the limit the model runs undamped, as the reference does.
SPIN_ZETA = 0.2
SPIN_LIMIT = 3.0


# the implicit scheme's per-segment scratch within a chunk: float columns of ``sc`` (n, NSC) ...
(C_NX, C_NY,        # contact normal
 C_P, C_R,          # penetration, distance from the pulley's centre (friction's arm)
 C_N, C_KAP,        # normal force, A's contact coefficient
 C_CA, C_T, C_TB,   # anchor slope now (N s/m; 0: sliding), sliding friction now and in F_base
 C_CAN,             # centripetal acceleration v_t^2 / r (see _base_solve)
 C_TMX, C_TMY,      # the chord's tangent t_m (see _contacts)
 C_VPX, C_VPY,      # the rolling prediction vp
 C_AK, C_ATX, C_ATY, C_ATR,  # the anchor as the last pass solved it: slope, direction, arm
 C_F0X, C_F0Y, C_F0Z,   # F_base: the step's forces with every segment in its factored state
 C_T0, C_T0B,       # an anchor's explicit force now and in F_base (elastic-plastic: K z; Threlfall: 0)
 C_DB, C_VN, C_HCN,  # contact damping rate delta(p) b, the normal velocity it was read at, h v_t^2 / r
 NSC) = range(27)
# ... and int columns of ``si`` (n, NSI): the pulley it touches (-1: none), the list of segments in
# contact, a segment's place in the active set C (-1: none), the list of segments to join C
(I_J, I_LIST, I_SLOT, I_PEND, NSI) = range(5)


@njit(**STAGE)
def _spin_damper(n, h, hl, spin_lim, ieff, w, jfk, jdx, jdy, seg_n, spd, cs, mz, pb):
    """Stage (implicit scheme): SPIN_ZETA's damper on segments whose neighbours two either side were
    free at the last step, where their rate departs from the neighbours' by spin_lim (SPIN_LIMIT).
    Adds its moments to mz; returns pb less its power."""
    for i in range(n):
        free = True
        for dk in range(-2, 3):
            kk = i + dk
            if kk < 0:
                kk += n
            elif kk >= n:
                kk -= n
            free = free and seg_n[kk] == 0.0
        im = i - 1 if i > 0 else n - 1
        ip = i + 1 if i < n - 1 else 0
        spd[i] = w[im] - 2.0 * w[i] + w[ip] if free else 0.0
        # the mode's stiffness T l (T the mean force of the segment's two joints) and its
        # modified inertia I + h^2/2 T l; the alternating pattern sees 16 x the coefficient
        ka = 0.5 * (jfk[i] * math.sqrt(jdx[i] * jdx[i] + jdy[i] * jdy[i])
                    + jfk[ip] * math.sqrt(jdx[ip] * jdx[ip] + jdy[ip] * jdy[ip])) * 2.0 * hl
        ka = max(ka, 0.0)
        on = free and abs(spd[i]) > spin_lim
        cs[i] = 2.0 * SPIN_ZETA * math.sqrt(ka * (ieff[i] + 0.5 * h * h * ka)) / 16.0 if on else 0.0
    for i in range(n):
        im = i - 1 if i > 0 else n - 1
        ip = i + 1 if i < n - 1 else 0
        ms = -(cs[im] * spd[im] - 2.0 * cs[i] * spd[i] + cs[ip] * spd[ip])
        mz[i] += ms
        pb -= ms * w[i]
    return pb


@njit(**STAGE)
def _contacts(n, nk, h, hvb, g, m, c1, c2, bc, pmax, centre, x, y, vx, vy, pcx, pcy, pvx, pvy, pr, cand_j, cand_skip,
              stk, z, fy, si, sc):
    """Stage (implicit scheme), gravity and contact: per segment the pulley it touches, its normal
    and penetration, its normal force (``normal_force`` at the explicit normal velocity) and A's
    contact coefficient, and the chord it rolls along. Returns (segments in contact, listed in
    si[:, I_LIST]; contact damping power)."""
    nc = 0
    pcd = 0.0
    for i in range(n):
        fy[i] -= m[i] * g
        si[i, I_J] = -1
        j, rx, ry, d2 = _contact_candidate(i, nk, x, y, pcx, pcy, pr, cand_j, cand_skip, hvb)
        if j >= 0:      # pulleys do not overlap: one contact per segment
            dist = math.sqrt(d2)
            nx = rx / dist
            ny = ry / dist
            p = pr[j] - dist
            rvx = vx[i] - pvx[j]
            rvy = vy[i] - pvy[j]
            # the normal velocity at the middle of the last step's chord: a segment rolling
            # round the pulley arrives along a chord that leaves the circle's normal by half
            # its turn, which read at the end point is a separating v_t^2 h / 2 r (at 0.03 rad
            # per step it took nearly all the damping's share of the normal force)
            vt_ = -rvx * ny + rvy * nx
            vn = rvx * nx + rvy * ny - 0.5 * h * vt_ * vt_ / dist
            N, db = normal_force(c1[i], c2[i], bc[i], pmax, p, vn, 0.0)
            si[i, I_J] = j
            sc[i, C_NX] = nx
            sc[i, C_NY] = ny
            sc[i, C_P] = p
            sc[i, C_R] = dist if centre else pr[j]
            sc[i, C_KAP] = 0.5 * h * h * (c2[i] + 2.0 * c1[i] * p) + h * db
            if N < 0.0:
                N = 0.0
            sc[i, C_N] = N
            # the damping's power is counted at the solved velocity (_update_implicit)
            sc[i, C_DB] = db if N > 0.0 else 0.0
            sc[i, C_VN] = vn
            sc[i, C_HCN] = h * vt_ * vt_ / dist
            if N <= 0.0:
                pcd += clipped_power(c1[i], c2[i], p, vn)
            # slip is read along the chord of the step (t_m: the tangent turned by half
            # the segment's turn round the pulley, h v_t / 2 dist), the direction of a
            # rolling segment's new velocity, whose difference from any other tangent
            # t is read off the rolling prediction vp (rv turned by the whole turn):
            # slip = om r - v_new . t - vp . (t_m - t). Read along the current tangent, a
            # rolling segment's new velocity shows a slip of v (h Omega)^2 / 8, 0.75 mm/s
            # at 0.016 rad per step: against a friction law of 1e-5 m/s the anchors let go.
            ps = 0.5 * h * vt_ / dist
            cps = math.cos(ps)
            sps = math.sin(ps)
            sc[i, C_TMX] = -ny * cps - nx * sps
            sc[i, C_TMY] = -ny * sps + nx * cps
            c2s = cps * cps - sps * sps
            s2s = 2.0 * sps * cps
            sc[i, C_VPX] = rvx * c2s - rvy * s2s
            sc[i, C_VPY] = rvx * s2s + rvy * c2s
        if si[i, I_J] < 0:
            stk[i] = 0.0
            z[i] = 0.0
        else:
            si[nc, I_LIST] = i
            nc += 1
    return nc, pcd


@njit(cache=True, inline="always")
def _anchor(law, mu, N, dv, dmax, h, z):
    """A stuck segment's anchor in the implicit scheme: its slope in A and its explicit force.
    Threlfall: the law's secant ANCHOR mu N / Delta_v, no force; elastic-plastic: the bristle
    T = K (z + h slip), K = mu N / Delta_max, as ``friction`` integrates it: slope h K, force K z."""
    if law == LAW_ELASTIC_PLASTIC:
        K = mu * N / dmax
        return h * K, K * z
    return ANCHOR * mu * N / dv, 0.0


@njit(cache=True, inline="always")
def _pressed(j, sc, i):
    """Whether segment i (on pulley j, -1 for none) is pressed onto its pulley (explicit normal
    force N > 0): the contact set the chain matrix A holds (``_factored_state``, ``_friction``)."""
    return j >= 0 and sc[i, C_N] > 0.0


@njit(**STAGE)
def _friction(n, h, Ct, om, stk, z, fkap, fx, fy, mz, si, sc):
    """Stage (implicit scheme), friction: by its state at the last step, a contact segment is
    anchored to the pulley surface (in A) or slides with mu N against its slip (explicit); the
    contact forces join the step's forces, kept as F_base. The anchor: ``_anchor`` (its explicit
    force in C_T0); an elastic-plastic bristle short of Delta_max is elastic (anchored), one at it
    slides until its slip turns.
    Returns whether the contact set (segments pressed onto a pulley: explicit normal force N > 0)
    differs from the one A was factored with."""
    mu, law, dv, dmax = Ct.mu, Ct.law, Ct.dv, Ct.dmax
    cchg = False
    for i in range(n):
        j = si[i, I_J]
        sc[i, C_T] = 0.0
        sc[i, C_T0] = 0.0
        sc[i, C_CA] = 0.0
        sc[i, C_AK] = 0.0
        if j >= 0:
            N = sc[i, C_N]
            if N > 0.0:
                if stk[i] > 0.0 or (law == LAW_ELASTIC_PLASTIC and abs(z[i]) < dmax):
                    sc[i, C_CA], sc[i, C_T0] = _anchor(law, mu[i], N, dv, dmax, h, z[i])
                else:
                    sl = om[j] * sc[i, C_R] - (sc[i, C_VPX] * sc[i, C_TMX] + sc[i, C_VPY] * sc[i, C_TMY])
                    sc[i, C_T] = math.copysign(mu[i] * N, sl)
            ft = sc[i, C_T] + sc[i, C_T0]
            fx[i] += N * sc[i, C_NX] - ft * sc[i, C_NY]
            fy[i] += N * sc[i, C_NY] + ft * sc[i, C_NX]
        if _pressed(j, sc, i) != (fkap[i] > 0.0):
            cchg = True
        sc[i, C_F0X] = fx[i]
        sc[i, C_F0Y] = fy[i]
        sc[i, C_F0Z] = mz[i]
    return cchg


@njit(**STAGE)
def _update_implicit(n, h, Ct, x, y, phi, c, s, vx, vy, w, om, pvx, pvy, fx, fy, mz, seg_n, seg_t,
                     seg_p, stk, z, fkap, fnx, fny, si, sc, dom, tq_belt, hub):
    """Stage (implicit scheme): each segment takes its velocity change (fx, fy, mz from
    ``_velocity_change``) and moves; its friction at the solved velocities (an anchor's force,
    or mu N sliding), the friction power, belt torques and hub forces (hub: rows x, y), the normal
    force the step applied (N and A's contact term), and its stick-slip state for the next step.
    Returns the friction power and the contact damping's: its force -delta b (v_n + dv_n), the
    part in A only where A holds the contact, times the solved normal velocity v_n + dv_n (dv_n:
    the velocity change along n less a rolling segment's turn, h v_t^2 / r, as A reads it)."""
    mu, law, dv, dmax = Ct.mu, Ct.law, Ct.dv, Ct.dmax
    pfr = 0.0
    pcd = 0.0
    for i in range(n):
        vxs = vx[i] + h * fx[i]
        vys = vy[i] + h * fy[i]
        w[i] += h * mz[i]
        j = si[i, I_J]
        if j >= 0:
            N = sc[i, C_N]
            if N > 0.0:
                # the normal velocity change less the turn of a rolling segment's velocity
                dvn = h * (sc[i, C_NX] * fx[i] + sc[i, C_NY] * fy[i]) + sc[i, C_HCN]
                pcd += sc[i, C_DB] * (sc[i, C_VN] + (dvn if fkap[i] > 0.0 else 0.0)) * (sc[i, C_VN] + dvn)
            T = sc[i, C_T]
            nx = sc[i, C_NX]
            ny = sc[i, C_NY]
            ak = sc[i, C_AK]
            if ak > 0.0:
                tx = sc[i, C_ATX]
                ty = sc[i, C_ATY]
                ar = sc[i, C_ATR]
            else:
                tx = -ny
                ty = nx
                ar = sc[i, C_R]
            if N > 0.0:
                sl = ((om[j] + dom[j]) * ar - (vxs - pvx[j]) * tx - (vys - pvy[j]) * ty
                      - sc[i, C_VPX] * (sc[i, C_TMX] - tx) - sc[i, C_VPY] * (sc[i, C_TMY] - ty))
                if ak > 0.0:
                    T = sc[i, C_T0] + ak * sl        # the anchor's force at the solved velocities
                pfr += T * sl
                if law == LAW_ELASTIC_PLASTIC:
                    # the bristle's new state, T = K z; at Delta_max it slides on, until its slip turns
                    muN = mu[i] * N
                    dm = dmax * T / muN if muN > 0.0 else 0.0
                    if ak > 0.0 and abs(dm) < dmax:
                        z[i] = dm
                        stk[i] = 1.0
                    elif muN == 0.0:    # no grip (mu = 0): no bristle
                        z[i] = 0.0
                        stk[i] = 0.0
                    else:
                        z[i] = math.copysign(dmax, T)
                        stk[i] = 1.0 if sl * T < 0.0 else 0.0
                elif ak == 0.0:
                    # a sliding segment whose slip reached the band or turned sticks next step
                    stk[i] = 1.0 if (abs(sl) < dv or sl * T < 0.0) else 0.0
                tq_belt[j] -= ar * T
            else:
                stk[i] = 0.0
            # the normal force the step applied: N and A's contact term (see _base_solve)
            N -= fkap[i] * (fnx[i] * fx[i] + fny[i] * fy[i] + sc[i, C_CAN])
            hub[0, j] -= N * nx + T * tx
            hub[1, j] -= N * ny + T * ty
            seg_n[i] = N
            seg_t[i] = T
            seg_p[i] = sc[i, C_P]
        else:
            seg_n[i] = 0.0
            seg_t[i] = 0.0
            seg_p[i] = 0.0
        _move(i, h, vxs, vys, x, y, vx, vy, w, phi, c, s)
    return pfr, pcd
