"""The belt's joints (seed 000, eqs. 18-21): axial and bending forces between neighbouring
segments, and the static forces (joints, gravity, contact) of a state. Records: _kernels.py."""
import math

from numba import njit

from ..dynamics._bodies import (FAST)
from .records import STAGE_PY
from ._curves import contact_at
from ._laws import normal_force


# ---- belt joints (eqs. 18-21) ---------------------------------------------------------------

@njit(cache=True, inline="always", fastmath=FAST)
def _joint(i, k, hl, h, x, y, c, s, vx, vy, w, phi, kax, bax, kb, bb, eax, eb, linear, inv_m, inv_i,
           jfk, jdx, jdy, jmk, jmi):
    """Joint i between segment k (+ end) and segment i (- end): stores its gap vector (jdx, jdy),
    jfk (force vector = jfk * d, on k; minus that on i) and its moments on k and on i (arms and
    bending). Returns the power of its axial and bending dampers."""
    ax = hl * c[k]
    ay = hl * s[k]
    bx = hl * c[i]
    by = hl * s[i]
    dx = (x[i] - bx) - (x[k] + ax)
    dy = (y[i] - by) - (y[k] + ay)
    dvx = (vx[i] + w[i] * by) - (vx[k] - w[k] * ay)
    dvy = (vy[i] - w[i] * bx) - (vy[k] + w[k] * ax)
    dd = dx * dx + dy * dy
    num = dx * dvx + dy * dvy                     # Delta_l * dDelta_l/dt
    # damper force per unit gap, b (dDelta_l/dt) / Delta_l, with the implicit factor
    # 1 / (1 + h b w_eff) folded into the one division (num = 0 when the gap closes)
    hb = h * bax[i]
    cak = ax * dy - ay * dx
    cbi = bx * dy - by * dx
    den = dd * (1.0 + hb * (inv_m[k] + inv_m[i])) + hb * (cak * cak * inv_i[k] + cbi * cbi * inv_i[i])
    fd = bax[i] * num / max(den, 1e-300)
    if linear:
        fk = kax[i] + fd
    else:
        fk = kax[i] * dd ** (0.5 * (eax - 1.0)) + fd
    Fx = fk * dx
    Fy = fk * dy
    dphi = phi[i] - phi[k]
    if eb == 1.0:
        M = kb[i] * dphi
    else:
        M = kb[i] * math.copysign(abs(dphi) ** eb, dphi)
    dw = w[i] - w[k]
    M += bb[i] * dw
    jfk[i] = fk
    jdx[i] = dx
    jdy[i] = dy
    jmk[i] = ax * Fy - ay * Fx + M        # on k: arm (+a) x F, plus the bending moment
    jmi[i] = bx * Fy - by * Fx - M        # on i: arm (-b) x (-F) = b x F, minus it
    return fd * num, bb[i] * dw * dw


@njit(**STAGE_PY)
def _joint_forces(n, eax, eb, hl, turn, linear, x, y, c, s, vx, vy, w, phi, kax, bax, kb, bb, fx, fy, mz, jfk, jdx,
                  jdy, h, inv_m, inv_i, jmk, jmi):
    """``joint_forces`` on plain arrays: the compiled loop sees arrays, not records, so that it
    vectorises. A stage (``STAGE``): compiled with reference counting, as a separate function
    it made the step 30-45 % slower (4.0-4.5 against 2.95-3.05 us per step, AMD EPYC)."""
    # two passes without scattered writes (so that the loops vectorise): the joints, then each
    # segment sums its two joints. Joint 0 closes the loop, where phi jumps by the total turn.
    pax, pb = _joint(0, n - 1, hl, h, x, y, c, s, vx, vy, w, phi, kax, bax, kb, bb, eax, eb, linear, inv_m, inv_i,
                     jfk, jdx, jdy, jmk, jmi)
    if eb == 1.0:
        Mt = kb[0] * turn
    else:
        d0 = phi[0] - phi[n - 1]
        Mt = kb[0] * (math.copysign(abs(d0 + turn) ** eb, d0 + turn) - math.copysign(abs(d0) ** eb, d0))
    jmk[0] += Mt
    jmi[0] -= Mt
    if linear and eb == 1.0:
        # linear joints, written out here (``_joint`` less its dampers' power): with the power
        # summed in this loop, or ``_joint`` inlined into it, it compiled scalar; so it vectorises
        # (333 joints, with the power loop and the sums below: 3.2 against 6.3 us, 2-core AMD EPYC)
        for i in range(1, n):
            k = i - 1
            ax = hl * c[k]
            ay = hl * s[k]
            bx = hl * c[i]
            by = hl * s[i]
            dx = (x[i] - bx) - (x[k] + ax)
            dy = (y[i] - by) - (y[k] + ay)
            dvx = (vx[i] + w[i] * by) - (vx[k] - w[k] * ay)
            dvy = (vy[i] - w[i] * bx) - (vy[k] + w[k] * ax)
            hb = h * bax[i]
            cak = ax * dy - ay * dx
            cbi = bx * dy - by * dx
            den = ((dx * dx + dy * dy) * (1.0 + hb * (inv_m[k] + inv_m[i]))
                   + hb * (cak * cak * inv_i[k] + cbi * cbi * inv_i[i]))
            fk = kax[i] + bax[i] * (dx * dvx + dy * dvy) / max(den, 1e-300)
            Fx = fk * dx
            Fy = fk * dy
            M = kb[i] * (phi[i] - phi[k]) + bb[i] * (w[i] - w[k])
            jfk[i] = fk
            jdx[i] = dx
            jdy[i] = dy
            jmk[i] = ax * Fy - ay * Fx + M
            jmi[i] = bx * Fy - by * Fx - M
        # the dampers' power, b (d|d|/dt)^2 / (implicit factor) and bb (dw)^2, from the stored gaps
        for i in range(1, n):
            k = i - 1
            dvx = (vx[i] + w[i] * hl * s[i]) - (vx[k] - w[k] * hl * s[k])
            dvy = (vy[i] - w[i] * hl * c[i]) - (vy[k] + w[k] * hl * c[k])
            pax += (jfk[i] - kax[i]) * (jdx[i] * dvx + jdy[i] * dvy)
            dw = w[i] - w[k]
            pb += bb[i] * dw * dw
    else:
        for i in range(1, n):
            a, b = _joint(i, i - 1, hl, h, x, y, c, s, vx, vy, w, phi, kax, bax, kb, bb, eax, eb, linear, inv_m,
                          inv_i, jfk, jdx, jdy, jmk, jmi)
            pax += a
            pb += b
    for i in range(n - 1):
        fx[i] = jfk[i + 1] * jdx[i + 1] - jfk[i] * jdx[i]
        fy[i] = jfk[i + 1] * jdy[i + 1] - jfk[i] * jdy[i]
        mz[i] = jmi[i] + jmk[i + 1]
    fx[n - 1] = jfk[0] * jdx[0] - jfk[n - 1] * jdx[n - 1]
    fy[n - 1] = jfk[0] * jdy[0] - jfk[n - 1] * jdy[n - 1]
    mz[n - 1] = jmi[n - 1] + jmk[0]
    return pax, pb


def joint_forces(B, S, W, h):
    """``_joint_forces_of`` called from Python: through the plain arrays, whose compiled wrapper is
    cheap (a record's unboxes each of its arrays: 0.9 s of a first run's compile)."""
    return _joint_forces(B.n, B.eax, B.eb, B.hl, B.turn, B.linear, S.x, S.y, S.c, S.s, S.vx, S.vy, S.w, S.phi,
                         B.kax, B.bax, B.kb, B.bb, W.fx, W.fy, W.mz, W.jfk, W.jdx, W.jdy, h, B.inv_m, B.inv_i,
                         W.jmk, W.jmi)


@njit(cache=True, inline="always")
def _joint_forces_of(B, S, W, h):
    """Elastic + damping forces of all joints into W.fx, W.fy, W.mz (overwritten).

    Stores per joint the gap vector (jdx, jdy) and jfk with force vector = jfk * d (tension
    = jfk |d|), and the moments on both segments (jmk, jmi). Returns (dissipated power in axial
    dampers, in bending dampers).

    With h > 0 the axial damper is integrated implicitly for its own joint: its force
    b v_n / (1 + h b w_eff), w_eff the inverse effective mass of the two segment ends along the
    gap (translation and rotation). The damper acts along the gap vector (eq. 18), which at low
    tension need not be along the belt, and then damps the segments' stiff rotation; explicitly
    that limits the step below the elastic limit, implicitly it does not. h = 0 gives eq. 18 as
    written (used by RKF45).
    """
    return _joint_forces(B.n, B.eax, B.eb, B.hl, B.turn, B.linear, S.x, S.y, S.c, S.s, S.vx, S.vy, S.w, S.phi,
                         B.kax, B.bax, B.kb, B.bb, W.fx, W.fy, W.mz, W.jfk, W.jdx, W.jdy, h, B.inv_m, B.inv_i,
                         W.jmk, W.jmi)


def static_forces(B, Ct, P, S, W):
    """Generalised forces -dE/dq of the belt at rest (S with zero velocities, so that no damper
    acts): joints, contact normal force (the integrators' ``normal_force``), gravity, into W.fx,
    W.fy, W.mz (used by equilibrium.relax). Through the plain arrays, as ``joint_forces`` (the
    records' compiled wrapper and flattened arguments: 3.7 s of a first run's compile)."""
    joint_forces(B, S, W, 0.0)
    _static_contacts(B.n, P.nk, B.m, B.g, S.x, S.y, S.cx, S.cy, P.r, Ct.c1, Ct.c2, Ct.bc, Ct.pmax, W.fx, W.fy,
                     Ct.ccur, Ct.creach, Ct.crad, S.th)


@njit(cache=True, no_cfunc_wrapper=True)
def _static_contacts(n, nk, m, g, x, y, pcx, pcy, pr, c1, c2, bc, pmax, fx, fy, ccur, creach, crad, th):
    """``static_forces``' contact normal forces and gravity, added to fx, fy; a non-circular pulley's
    along its curve's normal (segments/_curves.py)."""
    for i in range(n):
        for j in range(nk):
            rx = x[i] - pcx[j]
            ry = y[i] - pcy[j]
            d2 = rx * rx + ry * ry
            if d2 >= creach[j] * creach[j]:
                continue
            dist = math.sqrt(d2)
            if ccur[j] < 0:
                N, _ = normal_force(c1[i], c2[i], bc[i], pmax, pr[j] - dist, 0.0, 0.0)
                fx[i] += N * rx / dist
                fy[i] += N * ry / dist
                continue
            rc, tb, cb = contact_at(crad, ccur[j], rx, ry, th[j])
            if rc <= dist:
                continue
            N, _ = normal_force(c1[i], c2[i], bc[i], pmax, (rc - dist) * cb, 0.0, 0.0)
            erx = rx / dist
            ery = ry / dist
            fx[i] += N * cb * (erx + tb * ery)
            fy[i] += N * cb * (ery - tb * erx)
        fy[i] -= m[i] * g
