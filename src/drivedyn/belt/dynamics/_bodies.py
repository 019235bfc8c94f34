"""Compiled kernels of the bodies both dynamic belt models move: pulleys (applied torques, engine
orders, prescribed speeds, one-way clutches and decouplers) and tensioners (arms and sliders:
springs, stops, damping, friction), with the records the time loops advance (``State``, ``Work``;
the segment model fills their belt arrays, the rotational model leaves them empty). The segment
model's step (segments/_kernels.py) and the rotational model's (rotational/_kernels.py) call the
same ``_step_pulleys`` and ``_step_arms``, so their loads, clutch laws, springs and stops agree by
construction. The records' contract (named parameter groups, SI units, nothing compiled at
import) is stated in segments/_kernels.py.
"""
import math
from typing import NamedTuple

import numpy as np
from numba import njit

from ...core import tables

# plain Python in tables.py (check reads spring and load tables without numba): compiled here
table = njit(cache=True, inline="always")(tables.table)

# fast-math without the no-NaN/no-inf assumptions, so that blow-ups still show as NaN/inf
FAST = {"contract", "arcp", "reassoc", "nsz"}


class Pulleys(NamedTuple):
    nk: int
    cx: np.ndarray           # centre x (m)
    cy: np.ndarray           # centre y (m)
    r: np.ndarray            # contact radius (m)
    inertia: np.ndarray      # kg m^2
    inv_i: np.ndarray        # 1 / inertia
    mode: np.ndarray         # int64: 0 dynamic, 1 prescribed speed (sp_* table over time)
    tq_const: np.ndarray     # N m
    tq_visc: np.ndarray      # N m s/rad (torque -tq_visc om)
    tt_off: np.ndarray       # torque over time tables (off, x, y)
    tt_x: np.ndarray
    tt_y: np.ndarray
    ts_off: np.ndarray       # torque over speed tables
    ts_x: np.ndarray
    ts_y: np.ndarray
    hm_off: np.ndarray       # harmonics of the angle: amp sin(order th + phase)
    hm_order: np.ndarray
    hm_amp: np.ndarray
    hm_phase: np.ndarray
    sp_off: np.ndarray       # prescribed speed over time tables
    sp_x: np.ndarray
    sp_y: np.ndarray
    tq_drag: np.ndarray      # bearing drag (N m), Coulomb over +-w_drag (rad/s)
    w_drag: np.ndarray
    tq_quad: np.ndarray      # pump-like load: torque -tq_quad om |om| (N m s^2/rad^2)
    tq_pow: np.ndarray       # electrical load / efficiency (W): torque -tq_pow / om above w_cut
    w_cut: np.ndarray        # rad/s
    so_off: np.ndarray       # engine orders on a prescribed speed (flattened by pulley)
    so_order: np.ndarray
    so_amp: np.ndarray       # speed amplitude (rad/s)
    so_ang: np.ndarray       # angle amplitude (rad): speed amplitude order x mean speed
    so_phase: np.ndarray
    cl_kind: np.ndarray      # int64: 0 none, 1 one-way clutch, 2 decoupler (spring + one-way)
    cl_ir: np.ndarray        # rotor inertia behind the clutch (kg m^2)
    cl_k: np.ndarray         # decoupler spring (N m/rad) and damping (N m s/rad)
    cl_c: np.ndarray
    cl_s: np.ndarray         # +-1: the rotor's drive sense


class Arms(NamedTuple):
    """Tensioners, na of them: each carries pulley ``pulley[a]`` on one coordinate q (the travel
    from the drawn position, positive into the belt): a pivoted arm (kind 0; q in rad, the centre
    at pivot + length (cos psi, sin psi), psi = psi0 + sgn q) or a slider (kind 1; q in m, the
    centre at (px, py) + q (dx, dy)). Generalised load on q: spring (preload - rate q, or the
    table over q when it has rows), stops (penalty kstop, damping cstop), viscous damping (visc
    moving into the belt, visc_away moving away: a hydraulic tensioner's check valve), Coulomb
    friction (fric + fshare x |spring load| moving into the belt, x asym moving away; Threlfall-
    regularised over fv), and the belt's hub force projected on d centre / dq."""
    na: int
    pulley: np.ndarray       # int64
    kind: np.ndarray         # int64: 0 arm, 1 slider
    px: np.ndarray           # pivot (arm) or drawn centre (slider), m
    py: np.ndarray
    length: np.ndarray       # arm length (m)
    psi0: np.ndarray         # arm angle at the drawn position (rad)
    sgn: np.ndarray          # +-1: the arm's rotation sense into the belt
    dx: np.ndarray           # slider direction into the belt (unit)
    dy: np.ndarray
    inertia: np.ndarray      # kg m^2 (arm) or kg (slider)
    preload: np.ndarray      # N m or N
    rate: np.ndarray         # N m/rad or N/m
    visc: np.ndarray         # N m s/rad or N s/m
    fric: np.ndarray         # N m or N
    asym: np.ndarray         # friction away from the belt / into it
    fv: np.ndarray           # regularisation speed (rad/s or m/s)
    qmin: np.ndarray         # stops
    qmax: np.ndarray
    kstop: np.ndarray
    cstop: np.ndarray
    visc_away: np.ndarray    # viscous damping moving away from the belt (as visc)
    fshare: np.ndarray       # friction per unit spring load (a damper the spring presses)
    tab_off: np.ndarray      # spring tables over q (flattened, see ``tables``)
    tab_x: np.ndarray
    tab_y: np.ndarray
    par: np.ndarray          # (na, ARM_NPAR): the float fields above, packed for the time loop


# columns of Arms.par (the time loop passes one array: a call with more than 30 arguments cannot
# be inlined, and an array passed to a function that is not inlined costs reference counting)
(ARM_PSI0, ARM_SGN, ARM_LEN, ARM_PX, ARM_PY, ARM_DX, ARM_DY, ARM_IN, ARM_PRE, ARM_RATE, ARM_VISC, ARM_FRIC,
 ARM_ASYM, ARM_FV, ARM_QMIN, ARM_QMAX, ARM_KSTOP, ARM_CSTOP, ARM_VISC_AWAY, ARM_FSHARE, ARM_NPAR) = range(21)


ARM_FIELDS = ("psi0", "sgn", "length", "px", "py", "dx", "dy", "inertia", "preload", "rate", "visc", "fric",
              "asym", "fv", "qmin", "qmax", "kstop", "cstop", "visc_away", "fshare")


class State(NamedTuple):
    x: np.ndarray
    y: np.ndarray
    phi: np.ndarray
    c: np.ndarray
    s: np.ndarray
    vx: np.ndarray
    vy: np.ndarray
    w: np.ndarray
    th: np.ndarray
    om: np.ndarray
    z: np.ndarray
    cx: np.ndarray           # pulley centres (m) and their velocities (m/s): tensioners move them
    cy: np.ndarray
    cvx: np.ndarray
    cvy: np.ndarray
    q: np.ndarray            # tensioner travel (rad or m, see Arms) and its rate
    qd: np.ndarray
    thm: np.ndarray          # mean angle of a prescribed pulley (integral of its mean speed): order phases
    thr: np.ndarray          # rotor angle and speed behind a clutch, decoupler wind-up (rad)
    omr: np.ndarray
    dcp: np.ndarray


class Work(NamedTuple):
    # per joint (n): force vector jfk * (jdx, jdy) on segment i-1, moments on i-1 (jmk) and i (jmi)
    fx: np.ndarray
    fy: np.ndarray
    mz: np.ndarray
    jfk: np.ndarray
    jdx: np.ndarray
    jdy: np.ndarray
    jmk: np.ndarray
    jmi: np.ndarray
    # per segment (n): normal force, friction force, penetration of the last step / evaluation
    seg_n: np.ndarray
    seg_t: np.ndarray
    seg_p: np.ndarray
    # per pulley (nk), instantaneous: applied torque, belt torque, belt force x/y, power in
    tq_ext: np.ndarray
    tq_belt: np.ndarray
    hubx: np.ndarray
    huby: np.ndarray
    pin: np.ndarray
    diss: np.ndarray         # (4) dissipation rates: axial, bending dampers, contact damping, friction
    # accumulators (sum of h * value)
    acc_tq_ext: np.ndarray
    acc_tq_belt: np.ndarray
    acc_hubx: np.ndarray
    acc_huby: np.ndarray
    acc_pin: np.ndarray
    acc_span: np.ndarray     # (nspan, 2): mid-span tension, belt speed along the span
    acc_track: np.ndarray    # (ntrack, 3): element force, normal force, friction force
    acc_diss: np.ndarray     # (6) as diss, then tensioners (damping, friction, stops), clutches
    energy: np.ndarray       # (1) total energy at the end of the last step_chunk (J), see ``energy``
    probe: np.ndarray        # (6) health at its end: finite sum, max v^2, max pulley surface speed, max penetration,
    #                          max |w|, max pulley speed |om|
    # probes
    span_geo: np.ndarray     # (nspan, 4): midpoint x, y, unit direction x, y (belt order)
    span_joint: np.ndarray   # (nspan,) int64: joint followed nearest each midpoint
    track: np.ndarray        # (ntrack,) int64: tracked segments
    # the implicit scheme's chain matrix (_chain.py): (n, 9) blocks, (n, 3) right-hand side, (n,)
    # joint coefficients; size 0 for the other schemes
    lin_d: np.ndarray
    lin_o: np.ndarray
    lin_e: np.ndarray
    lin_dinv: np.ndarray
    lin_y: np.ndarray
    lin_x: np.ndarray
    lin_r: np.ndarray
    lin_sig: np.ndarray
    lin_gam: np.ndarray
    lin_fk: np.ndarray       # (n,) contact coefficient each segment had when the matrix was factored
    lin_fa: np.ndarray       # (n,) anchor slope (friction, N s/m) it was factored with
    lin_far: np.ndarray      # (n,) its friction's arm (distance from the pulley's centre) then
    lin_fnx: np.ndarray      # (n,) contact normal it was factored with
    lin_fny: np.ndarray
    lin_geo: np.ndarray      # (n,) scratch: geometric stiffness terms
    lin_u: np.ndarray        # (nk, n, 3): A^-1 of each pulley's anchors (its unit speed change)
    lin_zslot: np.ndarray    # (n,) int64: cache slot of a segment's column A_f^-1 w (-1: none)
    lin_zc: np.ndarray       # (2 ZMAX, n, 3) cached columns A_f^-1 e_x, A_f^-1 e_y at a segment
    lin_g: np.ndarray        # (nk, nk + 1): the pulleys' coupling g_j . U_k and sum of fca r^2
    lin_stat: np.ndarray     # (4): stick-slip changes within steps (let go, anchored), unused, unused
    cand_j: np.ndarray       # int64 (n): contact candidates, the pulley a segment touched (-1: none)
    cand_skip: np.ndarray    # int64 (n): steps in which a free segment cannot reach a pulley
    lin_st: np.ndarray       # (n,) 1: the segment stuck to its pulley at the last step
    lin_cnt: np.ndarray      # int64 (4): steps until the next factorisation, factorisations, cached columns, active-set passes
    pul_dw: np.ndarray       # (nk) each pulley's speed change over the last step (the implicit scheme's explicit pulleys)
    # a synchronous belt's teeth (segments/_teeth.py), per segment (n; size 0 without teeth): the tooth's load
    # (N, + against a belt running ahead of its groove), its pulley (-1: none), its groove, the hold T p / R (N);
    # tooth_qs: its spring's load before the climb limit; tooth_stat (8): steps, jumps, time and pulley of the
    # last jump, tooth-steps at the climb limit, time and pulley of the first, unused
    tooth_q: np.ndarray
    tooth_qs: np.ndarray
    tooth_j: np.ndarray
    tooth_g: np.ndarray
    tooth_hold: np.ndarray
    tooth_stat: np.ndarray


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
    """Slip s solving s + a * mu(s) = w (a = h N mu / m >= 0): the implicit friction update
    (a = 0: explicit, s = w)."""
    if a == 0.0:
        return w
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


@njit(cache=True, inline="always")
def external_torque(P, j, t, th, om):
    """Applied torque on pulley j (N m): see ``_torque``."""
    return _torque(j, t, th, om, P.tq_const, P.tq_visc, P.tq_drag, P.w_drag, P.tq_quad, P.tq_pow, P.w_cut,
                   P.tt_off, P.tt_x, P.tt_y, P.ts_off, P.ts_x, P.ts_y, P.hm_off, P.hm_order, P.hm_amp, P.hm_phase)


@njit(cache=True, inline="always")
def _torque(j, t, th, om, tq_const, tq_visc, tq_drag, w_drag, tq_quad, tq_pow, w_cut,
            tt_off, tt_x, tt_y, ts_off, ts_x, ts_y, hm_off, hm_order, hm_amp, hm_phase):
    """Applied torque (N m) at angle th, speed om: constant + table(t) + table(omega) - c omega
    + harmonics of the angle, bearing drag (Coulomb, linear inside +-w_drag), a pump's
    -c omega |omega|, an alternator's -P / (eta omega) (its power 0 below the cut-in speed w_c,
    rising linearly to full at 2 w_c).
    Plain arrays, for the time loop."""
    M = tq_const[j] - tq_visc[j] * om
    M += table(tt_x, tt_y, tt_off[j], tt_off[j + 1], t, False)
    M += table(ts_x, ts_y, ts_off[j], ts_off[j + 1], om, True)
    for k in range(hm_off[j], hm_off[j + 1]):
        M += hm_amp[k] * math.sin(hm_order[k] * th + hm_phase[k])
    if tq_drag[j] > 0.0:
        x = om / w_drag[j]
        M -= tq_drag[j] * (x if abs(x) < 1.0 else math.copysign(1.0, x))
    M -= tq_quad[j] * om * abs(om)
    if tq_pow[j] > 0.0 and abs(om) > w_cut[j]:
        # the output rises from 0 at cut-in to the full power at twice the cut-in speed
        M -= tq_pow[j] * min(abs(om) / w_cut[j] - 1.0, 1.0) / om
    return M


@njit(cache=True, inline="always")
def _orders(j, thm, wm, so_off, so_order, so_amp, so_ang, so_phase):
    """Speed fluctuation of prescribed pulley j (rad/s) at mean angle thm, mean speed wm."""
    dw = 0.0
    for k in range(so_off[j], so_off[j + 1]):
        dw += (so_amp[k] + so_order[k] * so_ang[k] * wm) * math.cos(so_order[k] * thm + so_phase[k])
    return dw


@njit(cache=True, inline="always")
def prescribed_speed(P, j, t):
    """Speed of a kinematically driven pulley (mode 1) at time t (rad/s)."""
    return table(P.sp_x, P.sp_y, P.sp_off[j], P.sp_off[j + 1], t, False)


@njit(cache=True, inline="always")
def arm_centre(A, a, q):
    """Pulley centre of tensioner a at travel q and d centre / dq."""
    return _arm_centre(a, q, A.kind, A.par)


@njit(cache=True, inline="always")
def _arm_centre(a, q, kind, par):
    if kind[a] == 0:
        sg = par[a, ARM_SGN]
        psi = par[a, ARM_PSI0] + sg * q
        cs = math.cos(psi)
        sn = math.sin(psi)
        L = par[a, ARM_LEN]
        return par[a, ARM_PX] + L * cs, par[a, ARM_PY] + L * sn, -sg * L * sn, sg * L * cs
    return par[a, ARM_PX] + q * par[a, ARM_DX], par[a, ARM_PY] + q * par[a, ARM_DY], par[a, ARM_DX], par[a, ARM_DY]


@njit(cache=True, inline="always")
def _spring_load(a, q, par, tab_off, tab_x, tab_y):
    """Spring load on the travel coordinate (into the belt positive): table or preload - rate q,
    plus the stops' penalty. Returns (load, on a stop, the spring's part of the load)."""
    if tab_off[a + 1] > tab_off[a]:
        Q = table(tab_x, tab_y, tab_off[a], tab_off[a + 1], q, True)
    else:
        Q = par[a, ARM_PRE] - par[a, ARM_RATE] * q
    if q < par[a, ARM_QMIN]:
        return Q + par[a, ARM_KSTOP] * (par[a, ARM_QMIN] - q), True, Q
    if q > par[a, ARM_QMAX]:
        return Q - par[a, ARM_KSTOP] * (q - par[a, ARM_QMAX]), True, Q
    return Q, False, Q


@njit(cache=True)
def spring_energy(A, a, q):
    """Potential of the spring and stops at travel q (J): -integral of the spring load from 0."""
    return _spring_energy(a, q, A.tab_off, A.tab_x, A.tab_y, A.preload, A.rate, A.qmin, A.qmax, A.kstop)


@njit(cache=True, inline="always")
def _spring_energy(a, q, tab_off, tab_x, tab_y, preload, rate, qmin, qmax, kstop):
    """``spring_energy`` on the arrays it reads (the segment model's energy stage inlines it)."""
    return _potential(q, tab_off[a], tab_off[a + 1], tab_x, tab_y, preload[a], rate[a], qmin[a], qmax[a], kstop[a])


@njit(cache=True, inline="always")
def _potential(q, o0, o1, tab_x, tab_y, preload, rate, qmin, qmax, kstop):
    """The spring's and stops' potential at travel q on one tensioner's scalars (its table rows o0..o1)."""
    if o1 > o0:
        # exact for the piecewise-linear table: trapezoids between its breakpoints inside [0, q]
        lo = min(0.0, q)
        hi = max(0.0, q)
        xp = lo
        yp = table(tab_x, tab_y, o0, o1, lo, True)
        W = 0.0
        for k in range(o0, o1 + 1):
            xk = tab_x[k] if k < o1 else hi
            if xk <= lo:
                continue
            if xk > hi:
                xk = hi
            yk = table(tab_x, tab_y, o0, o1, xk, True)
            W += 0.5 * (yp + yk) * (xk - xp)
            xp = xk
            yp = yk
            if xk >= hi:
                break
        E = -W if q >= 0.0 else W
    else:
        E = -(preload * q - 0.5 * rate * q * q)
    if q < qmin:
        E += 0.5 * kstop * (qmin - q) ** 2
    elif q > qmax:
        E += 0.5 * kstop * (q - qmax) ** 2
    return E


@njit(cache=True, inline="always")
def _step_arms(na, pulley, kind, par, tab_off, tab_x, tab_y, sq, sqd, cx, cy, cvx, cvy, hubx, huby, h):
    """One semi-implicit step of every tensioner under the belt's hub forces of this step: the
    spring explicit, viscous and stop damping and the regularised Coulomb friction implicit in the
    new rate (the same scalar solve as the belt friction). Damping and friction that differ with
    the sense of motion take the sense of v = qd + h Q / I: every term of the implicit balance
    qd (1 + h c / I) + h fr mu(qd) / I = v has the sign of qd, so the new rate moves as v does. The
    friction's load-proportional part reads the spring's load at the step's start (explicit, as
    the spring). Moves the pulley centres. Returns the power dissipated.

    The stops: explicit, as the spring, while the step resolves them (h omega_stop < 1/2, omega_stop
    = sqrt(k_stop / I)); at a longer step (the rotational model's: a stop 1e4 times stiffer than the
    belt on the arm would otherwise set it) the stop acts at the new travel (backward Euler, the
    contact's complementarity: a stop force only where the new travel lies beyond the stop), stable
    at any step. That scheme takes a share of an impact's energy (about pi h omega_stop of it per
    bounce): on such steps what the arm dissipated is booked as what the belt's work on it leaves of
    its energy's change, so the run's energy balance closes.

    Inlined, on plain arrays: as a separate function (or reading the record's fields) it cost
    12 % per step (measured, six-pulley FEAD)."""
    P_diss = 0.0
    for a in range(na):
        j = pulley[a]
        q = sq[a]
        _, _, jx, jy = _arm_centre(a, q, kind, par)
        Q, on_stop, Qs = _spring_load(a, q, par, tab_off, tab_x, tab_y)
        Qh = hubx[j] * jx + huby[j] * jy            # the belt pushes the pulley out (Q < 0)
        hI = h / par[a, ARM_IN]
        ks = par[a, ARM_KSTOP]
        qlo, qhi = par[a, ARM_QMIN], par[a, ARM_QMAX]
        stiff = h * h * ks > 0.25 * par[a, ARM_IN]
        Qf = (Qs if stiff else Q) + Qh              # the stop's explicit load only where it is resolved
        fv = par[a, ARM_FV]
        fr0 = par[a, ARM_FRIC] + par[a, ARM_FSHARE] * abs(Qs)
        kimp = 0.0
        qs = 0.0
        for _ in range(2):      # free; again with the stop at the new travel if it lands beyond one
            v = sqd[a] + hI * (Qf + kimp * (qs - q))
            fr = fr0
            if v >= 0.0:       # moving into the belt
                c = par[a, ARM_VISC]
            else:              # away from it: the asymmetric damper's loading sense
                c = par[a, ARM_VISC_AWAY]
                fr *= par[a, ARM_ASYM]
            if (on_stop and not stiff) or kimp > 0.0:
                c += par[a, ARM_CSTOP]
            den = 1.0 + hI * (c + h * kimp)
            qd = solve_threlfall(v / den, hI * fr / den, fv)
            q1 = q + h * qd
            if not stiff or kimp > 0.0 or qlo <= q1 <= qhi:
                break
            kimp = ks
            qs = qhi if q1 > qhi else qlo
        if stiff and (on_stop or kimp > 0.0):
            o0, o1 = tab_off[a], tab_off[a + 1]
            pre, rt = par[a, ARM_PRE], par[a, ARM_RATE]
            dU = (_potential(q1, o0, o1, tab_x, tab_y, pre, rt, qlo, qhi, ks)
                  - _potential(q, o0, o1, tab_x, tab_y, pre, rt, qlo, qhi, ks))
            dK = 0.5 * par[a, ARM_IN] * (qd * qd - sqd[a] * sqd[a])
            P_diss += (Qh * (q1 - q) - dU - dK) / h
        else:
            P_diss += c * qd * qd + fr * threlfall(qd, fv) * qd
        q = q1
        sq[a] = q
        sqd[a] = qd
        x, y, jx, jy = _arm_centre(a, q, kind, par)
        cx[j] = x
        cy[j] = y
        cvx[j] = jx * qd
        cvy[j] = jy * qd
    return P_diss


@njit(cache=True, inline="always")
def _small_solve(k, a, b):
    """b <- a^-1 b for a small dense k x k (Gaussian elimination with partial pivoting; a is
    overwritten)."""
    for c in range(k):
        p = c
        for r in range(c + 1, k):
            if abs(a[r, c]) > abs(a[p, c]):
                p = r
        if p != c:
            for q in range(k):
                a[c, q], a[p, q] = a[p, q], a[c, q]
            b[c], b[p] = b[p], b[c]
        for r in range(c + 1, k):
            f = a[r, c] / a[c, c]
            for q in range(c, k):
                a[r, q] -= f * a[c, q]
            b[r] -= f * b[c]
    for c in range(k - 1, -1, -1):
        s = b[c]
        for q in range(c + 1, k):
            s -= a[c, q] * b[q]
        b[c] = s / a[c, c]


@njit(cache=True, inline="always")
def _step_pulleys(t, h, tq_belt, hubx, huby, P, S, W):
    """Stage: every pulley over the step, explicit in the belt torque tq_belt (which the friction
    solve bounded) and hub force of this step: prescribed speeds with their engine orders, dynamic
    pulleys under their loads, clutch and decoupler rotors. Adds to W's accumulators; returns the
    energy the clutches dissipated."""
    return _step_pulleys_on(t, h, tq_belt, hubx, huby, P, S.th, S.om, S.thm, S.thr, S.omr, S.dcp,
                            W.acc_pin, W.acc_tq_ext, W.acc_tq_belt, W.acc_hubx, W.acc_huby)


@njit(cache=True, inline="always")
def _step_pulleys_on(t, h, tq_belt, hubx, huby, P, th, om, thm, thr, omr, dcp,
                     acc_pin, acc_tq_ext, acc_tq_belt, acc_hubx, acc_huby):
    """``_step_pulleys`` on the arrays of S and W it reads: the segment model's stage takes these
    alone (its records passed whole flattened to 839 arguments a call, which LLVM's passes over
    the time loop paid for)."""
    nk, pmode, pinv_i = P.nk, P.mode, P.inv_i
    tq_const, tq_visc, hm_off, hm_order, hm_amp, hm_phase = P.tq_const, P.tq_visc, P.hm_off, P.hm_order, P.hm_amp, P.hm_phase
    tt_off, tt_x, tt_y, ts_off, ts_x, ts_y = P.tt_off, P.tt_x, P.tt_y, P.ts_off, P.ts_x, P.ts_y
    sp_off, sp_x, sp_y = P.sp_off, P.sp_x, P.sp_y
    tq_drag, w_drag, tq_quad, tq_pow, w_cut = P.tq_drag, P.w_drag, P.tq_quad, P.tq_pow, P.w_cut
    so_off, so_order, so_amp, so_ang, so_phase = P.so_off, P.so_order, P.so_amp, P.so_ang, P.so_phase
    cl_kind, cl_ir, cl_k, cl_c, cl_s = P.cl_kind, P.cl_ir, P.cl_k, P.cl_c, P.cl_s
    diss_cl = 0.0
    for j in range(nk):
        Mb = tq_belt[j]
        if pmode[j] == 1:
            # prescribed: mean speed (table) plus engine orders on the mean angle, whose
            # integral is exact for the piecewise-linear mean speed (trapezoid)
            wm1 = table(sp_x, sp_y, sp_off[j], sp_off[j + 1], t + h, False)
            thm[j] += 0.5 * h * (table(sp_x, sp_y, sp_off[j], sp_off[j + 1], t, False) + wm1)
            om_new = wm1 + _orders(j, thm[j], wm1, so_off, so_order, so_amp, so_ang, so_phase)
            Mext = 0.0
            acc_pin[j] += h * (-Mb) * om[j]
        else:
            # the loads act on the pulley, or on the accessory rotor behind its clutch, at its angle
            # and speed (one call of the inlined _torque: each one is compiled anew)
            rotor = cl_kind[j] != 0
            thj = thr[j] if rotor else th[j]
            omj = omr[j] if rotor else om[j]
            Mext = _torque(j, t, thj, omj, tq_const, tq_visc, tq_drag, w_drag, tq_quad, tq_pow, w_cut,
                           tt_off, tt_x, tt_y, ts_off, ts_x, ts_y, hm_off, hm_order, hm_amp, hm_phase)
            acc_pin[j] += h * Mext * omj
            if not rotor:
                om_new = om[j] + h * (Mext + Mb) * pinv_i[j]
            else:
                sj = cl_s[j]
                ir = cl_ir[j]
                if cl_kind[j] == 1:
                    # one-way clutch: locked exactly when, free, the pulley would pass the rotor in
                    # the drive sense (then the clutch torque drives the rotor: it is >= 0)
                    wp = om[j] + h * Mb * pinv_i[j]
                    wr = omr[j] + h * Mext / ir
                    if sj * (wp - wr) > 0.0:
                        ip_ = 1.0 / pinv_i[j]
                        dw = om[j] - omr[j]
                        diss_cl += 0.5 * ip_ * ir / (ip_ + ir) * dw * dw     # engagement: the relative kinetic energy
                        wr = (ip_ * om[j] + ir * omr[j] + h * (Mb + Mext)) / (ip_ + ir)
                        wp = wr
                else:
                    # decoupler: the spring's wind-up dcp >= 0 carries k dcp + c (rate) to the rotor;
                    # the clutch in series lets the rotor overrun (wind-up held at 0)
                    rel = sj * (om[j] - omr[j])
                    Ts = cl_k[j] * dcp[j] + cl_c[j] * rel if (dcp[j] > 0.0 or rel > 0.0) else 0.0
                    if Ts < 0.0:
                        Ts = 0.0
                    if Ts > 0.0:
                        diss_cl += h * cl_c[j] * rel * rel
                    wp = om[j] + h * (Mb - sj * Ts) * pinv_i[j]
                    wr = omr[j] + h * (Mext + sj * Ts) / ir
                    d_new = dcp[j] + h * sj * (wp - wr)
                    if d_new < 0.0:
                        diss_cl += 0.5 * cl_k[j] * dcp[j] * dcp[j]     # unwound through the clutch
                        d_new = 0.0
                    dcp[j] = d_new
                om_new = wp
                omr[j] = wr
                thr[j] += h * wr
        acc_tq_ext[j] += h * Mext
        acc_tq_belt[j] += h * Mb
        acc_hubx[j] += h * hubx[j]
        acc_huby[j] += h * huby[j]
        om[j] = om_new
        th[j] += h * om_new
    return diss_cl
