"""Compiled kernels of the belt-drive model (Kubas, seed 000). Contract:

- float64 arrays, int64 index arrays, scalars; no Python objects; nothing compiled at import
  (``@njit(cache=True)`` without signatures).
- Belt state, n segments (index base 0, segment i joined to i-1 by joint i; joint 0 closes the loop
  between n-1 and 0): x, y, phi (unwrapped), c = cos(phi), s = sin(phi), vx, vy, w.
  Pulley state, nk pulleys: th, om.
- Notation (seed): joint force F = c_L * Delta_l^e_L + b_L * dDelta_l/dt along the gap vector d
  from the end of segment i-1 to the start of segment i (eqs. 18, 20); bending moment
  M = c_B (dphi)^e_B + b_B dw (eq. 19); contact N = c1 p^2 + c2 p + delta(p) b pdot (eqs. 9-10);
  friction T = mu(v_T) N (eqs. 11-17, Threlfall's law: cubic step from -mu to +mu over |v| < dv).
  Arrays: kax = c_L, bax = b_L, kb = c_B, bb = b_B per joint; c1, c2, bc per segment.
- The friction acts at the contact radius r_j (pulley surface speed om_j r_j, moment -r_j T on the
  pulley), so that friction power is exactly T * slip (energy-consistent reading of eqs. 12, 22).

Scheme ``step_chunk``: symplectic (semi-implicit) Euler. Elastic and bending forces and gravity
explicit; each joint's axial damper implicit for that joint (see ``joint_forces``); for each
segment in contact, the contact damping and the regularised friction are solved implicitly in the
segment's new velocity (a scalar monotone equation per contact, pulley speeds frozen during the
step), which makes the stiff friction law (slope mu N / dv) unconditionally stable; the step is
limited only by the elastic chain, h < 2 / sqrt(12 k / m) (``system.stability_limit``).
"""
import math

import numpy as np
from numba import njit

from ..tables import table

# fast-math without the no-NaN/no-inf assumptions, so that blow-ups still show as NaN/inf
FAST = {"contract", "arcp", "reassoc", "nsz"}

# integer parameter slots (ip)
I_N, I_NK, I_LAW, I_NSPAN, I_NTRACK, I_NEXP, I_LINEAR = range(7)
# float parameter slots (fp)
F_EAX, F_EB, F_PMAX, F_DV, F_DMAX, F_G, F_TURN, F_HL, F_ISCALE = range(9)


@njit(cache=True)
def smoothstep(x):
    """delta of eq. 10 on x = p / p_max: 0 below 0, x^2 (3 - 2x) inside, 1 above 1."""
    if x <= 0.0:
        return 0.0
    if x >= 1.0:
        return 1.0
    return x * x * (3.0 - 2.0 * x)


@njit(cache=True)
def threlfall(s, dv):
    """mu / mu_k for slip velocity s: cubic from -1 at -dv to +1 at +dv (seed fig. 4)."""
    x = s / dv
    if x >= 1.0:
        return 1.0
    if x <= -1.0:
        return -1.0
    return 0.5 * x * (3.0 - x * x)


@njit(cache=True)
def solve_threlfall(w, a, dv):
    """Slip s solving s + a * mu(s) = w (a = h N mu / m >= 0): the implicit friction update."""
    if w >= dv + a:
        return w - a
    if w <= -dv - a:
        return w + a
    # inside the regularisation band: dv x + a (3x - x^3)/2 = w, monotone on (-1, 1).
    x = w / (dv + 1.5 * a)
    for _ in range(60):
        f = dv * x + 0.5 * a * x * (3.0 - x * x) - w
        fp = dv + 1.5 * a * (1.0 - x * x)
        dx = f / fp
        x -= dx
        if abs(dx) < 1e-13:
            break
    if x > 1.0:
        x = 1.0
    elif x < -1.0:
        x = -1.0
    return x * dv


@njit(cache=True)
def external_torque(j, t, th, om, tq_const, tq_visc, tt_off, tt_x, tt_y, ts_off, ts_x, ts_y,
                    hm_off, hm_order, hm_amp, hm_phase):
    """Applied torque on pulley j (N m): constant + table(t) + table(omega) - c omega + harmonics."""
    M = tq_const[j] - tq_visc[j] * om
    M += table(tt_x, tt_y, tt_off[j], tt_off[j + 1], t, False)
    M += table(ts_x, ts_y, ts_off[j], ts_off[j + 1], om, True)
    for k in range(hm_off[j], hm_off[j + 1]):
        M += hm_amp[k] * math.sin(hm_order[k] * th + hm_phase[k])
    return M


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


@njit(cache=True, fastmath=FAST)
def joint_forces(ip, fp, x, y, c, s, vx, vy, w, phi, kax, bax, kb, bb, fx, fy, mz, jfk, jdx, jdy, h, inv_m, inv_i,
                 jmk, jmi):
    """Elastic + damping forces of all joints into fx, fy, mz (zeroed here).

    Stores per joint the gap vector (jdx, jdy) and jfk with force vector = jfk * d (tension
    = jfk |d|). Returns (dissipated power in axial dampers, in bending dampers).

    With h > 0 the axial damper is integrated implicitly for its own joint: its force
    b v_n / (1 + h b w_eff), w_eff the inverse effective mass of the two segment ends along the
    gap (translation and rotation). The damper acts along the gap vector (eq. 18), which at low
    tension need not be along the belt, and then damps the segments' stiff rotation; explicitly
    that limits the step below the elastic limit, implicitly it does not. h = 0 gives eq. 18 as
    written (used by RKF45).
    """
    n = ip[I_N]
    eax = fp[F_EAX]
    eb = fp[F_EB]
    hl = fp[F_HL]
    linear = ip[I_LINEAR] == 1
    # two passes without scattered writes (so that the loops vectorise): the joints, then each
    # segment sums its two joints. Joint 0 closes the loop, where phi jumps by the total turn.
    pax, pb = _joint(0, n - 1, hl, h, x, y, c, s, vx, vy, w, phi, kax, bax, kb, bb, eax, eb, linear, inv_m, inv_i,
                     jfk, jdx, jdy, jmk, jmi)
    turn = fp[F_TURN]
    if eb == 1.0:
        Mt = kb[0] * turn
    else:
        d0 = phi[0] - phi[n - 1]
        Mt = kb[0] * (math.copysign(abs(d0 + turn) ** eb, d0 + turn) - math.copysign(abs(d0) ** eb, d0))
    jmk[0] += Mt
    jmi[0] -= Mt
    for i in range(1, n):
        a, b = _joint(i, i - 1, hl, h, x, y, c, s, vx, vy, w, phi, kax, bax, kb, bb, eax, eb, linear, inv_m, inv_i,
                      jfk, jdx, jdy, jmk, jmi)
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


@njit(cache=True)
def step_chunk(nsteps, t, h, ip, fp,
               x, y, phi, c, s, vx, vy, w, th, om, z,
               m, inertia, mu, kax, bax, kb, bb, c1, c2, bc,
               pcx, pcy, pr, pinv_i, pmode,
               tq_const, tq_visc, tt_off, tt_x, tt_y, ts_off, ts_x, ts_y, hm_off, hm_order, hm_amp, hm_phase,
               sp_off, sp_x, sp_y,
               span_geo, span_joint, track_seg,
               fx, fy, mz, jfk, jdx, jdy, seg_n, seg_t, seg_p,
               acc_tq_ext, acc_tq_belt, acc_hubx, acc_huby, acc_pin, acc_span, acc_track, acc_diss):
    """Advance ``nsteps`` semi-implicit Euler steps from time t; returns the new time.

    Accumulators (added h * value, the caller divides by the interval): acc_tq_ext[j] applied
    torque, acc_tq_belt[j] belt torque on the pulley, acc_hubx/y[j] belt force on the pulley,
    acc_pin[j] power into the system through pulley j, acc_span[q, 0:2] mid-span tension and belt
    speed along the span (span_geo[q] = midpoint x, y and unit direction x, y in belt order),
    acc_track[q, 0:3] element force / normal force / friction force (along the segment) of tracked
    segments, acc_diss[0:4] dissipation in axial dampers, bending dampers, contact damping,
    friction.
    """
    n = ip[I_N]
    nk = ip[I_NK]
    law = ip[I_LAW]
    nspan = ip[I_NSPAN]
    ntrack = ip[I_NTRACK]
    pmax = fp[F_PMAX]
    dv = fp[F_DV]
    dmax = fp[F_DMAX]
    g = fp[F_G]
    hl = fp[F_HL]
    tq_belt = np.zeros(nk)
    hubx = np.zeros(nk)
    huby = np.zeros(nk)
    # reciprocals once per chunk: divisions cost more than the rest of a segment's update
    hm_ = np.empty(n)
    hi_ = np.empty(n)
    inv_m = np.empty(n)
    inv_i = np.empty(n)
    jmk = np.empty(n)
    jmi = np.empty(n)
    for i in range(n):
        inv_m[i] = 1.0 / m[i]
        inv_i[i] = 1.0 / inertia[i]
        hm_[i] = h * inv_m[i]
        # selective mass scaling of the segments' rotation: inertia x F_ISCALE (see system.py)
        hi_[i] = h / (inertia[i] * fp[F_ISCALE])
    hg = h * g
    for _ in range(nsteps):
        pax, pb = joint_forces(ip, fp, x, y, c, s, vx, vy, w, phi, kax, bax, kb, bb, fx, fy, mz, jfk, jdx, jdy,
                               h, inv_m, inv_i, jmk, jmi)
        pcd = 0.0
        pfr = 0.0
        for j in range(nk):
            tq_belt[j] = 0.0
            hubx[j] = 0.0
            huby[j] = 0.0
        for i in range(n):
            hm = hm_[i]
            vxs = vx[i] + hm * fx[i]
            vys = vy[i] + hm * fy[i] - hg
            Ntot = 0.0
            Ttot = 0.0
            pen = 0.0
            incontact = False
            for j in range(nk):
                rx = x[i] - pcx[j]
                ry = y[i] - pcy[j]
                d2 = rx * rx + ry * ry
                if d2 >= pr[j] * pr[j]:
                    continue
                incontact = True
                dist = math.sqrt(d2)
                inv = 1.0 / dist
                nx = rx * inv
                ny = ry * inv
                p = pr[j] - dist
                pen = p
                # normal: N = c1 p^2 + c2 p - delta b vn_new, vn_new = vn* + h N / m  (implicit damping)
                db = smoothstep(p / pmax) * bc[i]
                vn = vxs * nx + vys * ny
                N = (c1[i] * p * p + c2[i] * p - db * vn) / (1.0 + db * hm)
                if N <= 0.0:
                    continue
                vn_new = vn + hm * N
                pcd += db * vn_new * vn_new
                # tangent tau = Z x n; slip of the pulley surface relative to the segment
                tx = -ny
                ty = nx
                vt = vxs * tx + vys * ty
                wslip = om[j] * pr[j] - vt
                muN = mu[i] * N
                if law == 0:
                    sl = solve_threlfall(wslip, hm * muN, dv)
                    T = muN * threlfall(sl, dv)
                else:
                    # elastic-plastic: T = K z, z_new = z + h slip_new, clipped at the displacement limit
                    K = muN / dmax
                    zn = (z[i] + h * wslip) / (1.0 + h * hm * K)
                    T = K * zn
                    if T > muN:
                        T = muN
                        zn = dmax
                    elif T < -muN:
                        T = -muN
                        zn = -dmax
                    z[i] = zn
                    sl = wslip - hm * T
                pfr += T * sl
                vxs += hm * (N * nx + T * tx)
                vys += hm * (N * ny + T * ty)
                Ntot += N
                Ttot += T
                tq_belt[j] -= pr[j] * T
                hubx[j] -= N * nx + T * tx
                huby[j] -= N * ny + T * ty
            if not incontact:
                z[i] = 0.0
            seg_n[i] = Ntot
            seg_t[i] = Ttot
            seg_p[i] = pen
            vx[i] = vxs
            vy[i] = vys
            w[i] += hi_[i] * mz[i]
            x[i] += h * vxs
            y[i] += h * vys
            # rotate (c, s) by a = h w exactly to round-off (series to a^5; |a| < 1e-2 here)
            a = h * w[i]
            phi[i] += a
            a2 = a * a
            ca = 1.0 - 0.5 * a2 * (1.0 - a2 / 12.0)
            sa = a * (1.0 - a2 / 6.0 * (1.0 - a2 / 20.0))
            cn = c[i] * ca - s[i] * sa
            s[i] = s[i] * ca + c[i] * sa
            c[i] = cn
        # pulleys (explicit in the belt torque, which the implicit friction solve bounded)
        for j in range(nk):
            if pmode[j] == 1:
                om_new = table(sp_x, sp_y, sp_off[j], sp_off[j + 1], t + h, False)
                Mext = 0.0
                acc_pin[j] += h * (-tq_belt[j]) * om[j]
            else:
                Mext = external_torque(j, t, th[j], om[j], tq_const, tq_visc, tt_off, tt_x, tt_y, ts_off, ts_x, ts_y,
                                       hm_off, hm_order, hm_amp, hm_phase)
                acc_pin[j] += h * Mext * om[j]
                om_new = om[j] + h * (Mext + tq_belt[j]) * pinv_i[j]
            acc_tq_ext[j] += h * Mext
            acc_tq_belt[j] += h * tq_belt[j]
            acc_hubx[j] += h * hubx[j]
            acc_huby[j] += h * huby[j]
            om[j] = om_new
            th[j] += h * om_new
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
        t += h
    return t


@njit(cache=True)
def energy(ip, fp, x, y, phi, c, s, vx, vy, w, om, m, inertia, kax, kb, c1, c2, pcx, pcy, pr, pinertia, pmode):
    """Kinetic + potential energy (J): belt, dynamic pulleys, joints, bending, contact, gravity."""
    n = ip[I_N]
    nk = ip[I_NK]
    eax = fp[F_EAX]
    eb = fp[F_EB]
    hl = fp[F_HL]
    turn = fp[F_TURN]
    g = fp[F_G]
    E = 0.0
    for i in range(n):
        E += 0.5 * m[i] * (vx[i] * vx[i] + vy[i] * vy[i]) + 0.5 * inertia[i] * w[i] * w[i] + m[i] * g * y[i]
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
            p = pr[j] - math.sqrt(rx * rx + ry * ry)
            if p > 0.0:
                E += c1[i] * p * p * p / 3.0 + c2[i] * p * p / 2.0
    for j in range(nk):
        if pmode[j] == 0:
            E += 0.5 * pinertia[j] * om[j] * om[j]
    return E


@njit(cache=True)
def rhs(t, yv, dy, ip, fp, z, m, inertia, mu, kax, bax, kb, bb, c1, c2, bc, pcx, pcy, pr, pinv_i, pmode,
        tq_const, tq_visc, tt_off, tt_x, tt_y, ts_off, ts_x, ts_y, hm_off, hm_order, hm_amp, hm_phase,
        sp_off, sp_x, sp_y, fx, fy, mz, jfk, jdx, jdy, seg_n, seg_t, out_p, out_tq):
    """Explicit right-hand side of the seed's equations of motion (eqs. 21-22) for RKF45.

    State y = [x(n), y(n), phi(n), th(nk), vx(n), vy(n), w(n), om(nk)]. Contact damping and
    friction are evaluated at the current velocities (no implicit treatment). Fills seg_n, seg_t,
    out_tq[0:nk] applied torque, out_tq[nk:2nk] belt torque, out_tq[2nk:4nk] hub force x/y,
    out_p[0:4] dissipation rates, out_p[4:4+nk] power in per pulley.
    """
    n = ip[I_N]
    nk = ip[I_NK]
    pmax = fp[F_PMAX]
    dv = fp[F_DV]
    g = fp[F_G]
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
        if pmode[j] == 1:
            om[j] = table(sp_x, sp_y, sp_off[j], sp_off[j + 1], t, False)
    c = np.cos(phi)
    s = np.sin(phi)
    pax, pb = joint_forces(ip, fp, x, y, c, s, vx, vy, w, phi, kax, bax, kb, bb, fx, fy, mz, jfk, jdx, jdy,
                           0.0, m, inertia, np.empty(n), np.empty(n))
    pcd = 0.0
    pfr = 0.0
    for j in range(4 * nk):
        out_tq[j] = 0.0
    for i in range(n):
        ax = fx[i]
        ay = fy[i] - m[i] * g
        Ntot = 0.0
        Ttot = 0.0
        for j in range(nk):
            rx = x[i] - pcx[j]
            ry = y[i] - pcy[j]
            d2 = rx * rx + ry * ry
            if d2 >= pr[j] * pr[j]:
                continue
            dist = math.sqrt(d2)
            nx = rx / dist
            ny = ry / dist
            p = pr[j] - dist
            db = smoothstep(p / pmax) * bc[i]
            vn = vx[i] * nx + vy[i] * ny
            N = c1[i] * p * p + c2[i] * p - db * vn
            if N <= 0.0:
                continue
            pcd += db * vn * vn
            tx = -ny
            ty = nx
            sl = om[j] * pr[j] - (vx[i] * tx + vy[i] * ty)
            T = mu[i] * N * threlfall(sl, dv)
            pfr += T * sl
            ax += N * nx + T * tx
            ay += N * ny + T * ty
            Ntot += N
            Ttot += T
            out_tq[nk + j] -= pr[j] * T
            out_tq[2 * nk + j] -= N * nx + T * tx
            out_tq[3 * nk + j] -= N * ny + T * ty
        seg_n[i] = Ntot
        seg_t[i] = Ttot
        dy[i] = vx[i]
        dy[n + i] = vy[i]
        dy[2 * n + i] = w[i]
        dy[o + i] = ax / m[i]
        dy[o + n + i] = ay / m[i]
        dy[o + 2 * n + i] = mz[i] / inertia[i]
    out_p[0] = pax
    out_p[1] = pb
    out_p[2] = pcd
    out_p[3] = pfr
    for j in range(nk):
        dy[3 * n + j] = om[j]
        if pmode[j] == 1:
            dy[o + 3 * n + j] = 0.0
            out_tq[j] = 0.0
            out_p[4 + j] = -out_tq[nk + j] * om[j]
        else:
            M = external_torque(j, t, th[j], om[j], tq_const, tq_visc, tt_off, tt_x, tt_y, ts_off, ts_x, ts_y,
                                hm_off, hm_order, hm_amp, hm_phase)
            out_tq[j] = M
            out_p[4 + j] = M * om[j]
            dy[o + 3 * n + j] = (M + out_tq[nk + j]) * pinv_i[j]


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


@njit(cache=True)
def rkf45_chunk(t, t_end, h, yv, rtol, atol, max_steps, ip, fp, z, m, inertia, mu, kax, bax, kb, bb, c1, c2, bc,
                pcx, pcy, pr, pinv_i, pmode, tq_const, tq_visc, tt_off, tt_x, tt_y, ts_off, ts_x, ts_y,
                hm_off, hm_order, hm_amp, hm_phase, sp_off, sp_x, sp_y, fx, fy, mz, jfk, jdx, jdy, seg_n, seg_t,
                acc_p, acc_tq):
    """Adaptive RKF45 from t to t_end (advancing with the 4th-order solution, error from the
    embedded 5th). Accumulates h-weighted stage-1 outputs in acc_p / acc_tq.
    Returns (t, h, accepted steps, rejected steps); t < t_end means max_steps was hit."""
    N = yv.shape[0]
    K = np.zeros((6, N))
    yt = np.zeros(N)
    out_p = np.zeros(acc_p.shape[0])
    out_tq = np.zeros(acc_tq.shape[0])
    acc = 0
    rej = 0
    while t < t_end and acc + rej < max_steps:
        if t + h > t_end:
            h = t_end - t
        rhs(t, yv, K[0], ip, fp, z, m, inertia, mu, kax, bax, kb, bb, c1, c2, bc, pcx, pcy, pr, pinv_i, pmode,
            tq_const, tq_visc, tt_off, tt_x, tt_y, ts_off, ts_x, ts_y, hm_off, hm_order, hm_amp, hm_phase,
            sp_off, sp_x, sp_y, fx, fy, mz, jfk, jdx, jdy, seg_n, seg_t, out_p, out_tq)
        for st in range(1, 6):
            for q in range(N):
                v = yv[q]
                for r in range(st):
                    v += h * _A[st, r] * K[r, q]
                yt[q] = v
            _stage(st, t, h, yt, K, ip, fp, z, m, inertia, mu, kax, bax, kb, bb, c1, c2, bc, pcx, pcy, pr, pinv_i,
                   pmode, tq_const, tq_visc, tt_off, tt_x, tt_y, ts_off, ts_x, ts_y, hm_off, hm_order, hm_amp,
                   hm_phase, sp_off, sp_x, sp_y, fx, fy, mz, jfk, jdx, jdy, out_p.shape[0], out_tq.shape[0])
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
            for q in range(acc_p.shape[0]):
                acc_p[q] += h * out_p[q]
            for q in range(acc_tq.shape[0]):
                acc_tq[q] += h * out_tq[q]
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


@njit(cache=True)
def _stage(st, t, h, yt, K, ip, fp, z, m, inertia, mu, kax, bax, kb, bb, c1, c2, bc, pcx, pcy, pr, pinv_i, pmode,
           tq_const, tq_visc, tt_off, tt_x, tt_y, ts_off, ts_x, ts_y, hm_off, hm_order, hm_amp, hm_phase,
           sp_off, sp_x, sp_y, fx, fy, mz, jfk, jdx, jdy, np_, ntq):
    """One RKF stage evaluation with scratch outputs (stage-1 outputs are the recorded ones)."""
    n = ip[I_N]
    sn = np.zeros(n)
    stt = np.zeros(n)
    rhs(t + _C[st] * h, yt, K[st], ip, fp, z, m, inertia, mu, kax, bax, kb, bb, c1, c2, bc, pcx, pcy, pr, pinv_i,
        pmode, tq_const, tq_visc, tt_off, tt_x, tt_y, ts_off, ts_x, ts_y, hm_off, hm_order, hm_amp, hm_phase,
        sp_off, sp_x, sp_y, fx, fy, mz, jfk, jdx, jdy, sn, stt, np.zeros(np_), np.zeros(ntq))
    return 0
