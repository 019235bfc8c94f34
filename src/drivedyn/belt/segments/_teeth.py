"""The tooth contact of a synchronous belt (semi-implicit scheme): each tooth-carrying segment near a
grooved pulley is tied to the groove nearest it by the tooth's spring.

A tooth's deflection u is the arc (on the pulley's pitch circle, radius r) from its groove's centre
to the segment's angular position: u = r (alpha - theta_j - phase_j - 2 pi g / z), g the nearest
groove; u > 0 when the belt runs ahead of its groove (counter-clockwise). The tooth's load is the
spring with the dead band of its sideways play c (Q = k_t (u -+ c/2) beyond it, 0 within: the
linear chain of mechanics/teeth/loadshare.py, eq. 2) plus a damper on the deflection rate, and it
acts against the deflection: -Q along the pitch circle's tangent on the belt, +Q on the pulley
(torque Q d, d the segment's distance from the centre), so the tooth loads on a pulley sum to its
belt torque / radius.

Climbing (loadshare.py, eq. 3): a tooth whose outward push Q tan(phi - rho) reaches the hold of the
wrapped belt, T p / R (T the mean tension of the tooth's two joints), slides: its load is held at
that limit, the belt moves on relative to the groove and the tooth falls into the next groove once
past half a pitch; a change of groove while engaged is counted as a jump (when, on which pulley).
Explicit forces: the step limit takes the tooth spring (system.stability_limit)."""
import math

from numba import njit

from .records import STAGE
from ._curves import contact_at, table_at


@njit(**STAGE)
def _teeth(n, nk, t, Ct, S, pr, fx, fy, jfk, jdx, jdy, tq, tqs, tj, tg, thold, tstat, tq_belt, hubx, huby):
    """Stage: add each tooth's force to its segment (fx, fy) and to its pulley's belt torque and hub
    force; record its load (tq, N), its spring's load before the climb limit (tqs), pulley (tj, -1: none),
    groove (tg) and hold (thold, N); tstat: steps, jumps, time and pulley of the last jump, tooth-steps
    at the climb limit, time and pulley of the first."""
    band = Ct.tband
    hp = 0.5 * Ct.tplay
    two_pi = 2.0 * math.pi
    for i in range(n):
        k = Ct.tk[i]
        if k == 0.0:
            continue
        jn = -1
        d2 = 0.0
        dx = 0.0
        dy = 0.0
        for j in range(nk):
            if Ct.gz[j] == 0:
                continue
            ex = S.x[i] - S.cx[j]
            ey = S.y[i] - S.cy[j]
            e2 = ex * ex + ey * ey
            lim = Ct.creach[j] + band
            if e2 < lim * lim:
                jn = j
                d2 = e2
                dx = ex
                dy = ey
                break
        rc = 0.0
        tb = 0.0
        cb = 1.0
        if jn >= 0 and Ct.ccur[jn] >= 0:      # a grooved curve: within band of it
            rc, tb, cb = contact_at(Ct.crad, Ct.ccur[jn], dx, dy, S.th[jn])
            if d2 >= (rc + band) * (rc + band):
                jn = -1
        if jn < 0:
            tj[i] = -1
            tq[i] = 0.0
            tqs[i] = 0.0
            continue
        j = jn
        d = math.sqrt(d2)
        ca = dx / d
        sa = dy / d
        a = Ct.ccur[j]
        if a < 0:
            dth = two_pi / Ct.gz[j]
            rel = math.atan2(dy, dx) - S.th[j] - Ct.gphase[j]
            g = math.floor(rel / dth + 0.5)
            u = pr[j] * (rel - g * dth)
            R = pr[j]
        else:
            # the arc position of the normal's foot on the pitch curve (segments/_curves.py), grooves one
            # groove pitch apart from gphase (m) along it; the deflection along the chain's curve
            phi = math.atan2(dy, dx) - S.th[j]
            rp = table_at(Ct.cpr, a, phi)[0]
            sa_ = table_at(Ct.carc, a, phi)[0] + Ct.cper[a] * phi + (d - rp) * tb - Ct.gphase[j]
            sp = two_pi * Ct.cper[a] / Ct.gz[j]
            g = math.floor(sa_ / sp + 0.5)
            u = (sa_ - g * sp) * rc / rp
            R = 1.0 / table_at(Ct.ckap, a, phi)[0] + rc - rp    # the chain's radius of curvature
        gi = int(g) % Ct.gz[j]
        if tj[i] == j and tg[i] != gi:
            tstat[1] += 1.0          # a jump: the tooth sits in another groove than a step ago
            tstat[2] = t
            tstat[3] = j
        tj[i] = j
        tg[i] = gi
        # the tooth acts along the curve's tangent tau = cos(mu) (e_psi + tan(mu) e_r): on a circle e_psi
        txx = cb * (-sa + tb * ca)
        tyy = cb * (ca + tb * sa)
        vrel = (S.vx[i] - S.cvx[j]) * txx + (S.vy[i] - S.cvy[j]) * tyy - S.om[j] * d * cb
        if u > hp:
            Q = k * (u - hp) + Ct.tc[i] * vrel
        elif u < -hp:
            Q = k * (u + hp) + Ct.tc[i] * vrel
        else:
            Q = 0.0
        ib = i + 1 if i + 1 < n else 0
        T = 0.5 * (max(jfk[i] * math.sqrt(jdx[i] * jdx[i] + jdy[i] * jdy[i]), 0.0)
                   + max(jfk[ib] * math.sqrt(jdx[ib] * jdx[ib] + jdy[ib] * jdy[ib]), 0.0))
        hold = T * Ct.tpitch / R
        tqs[i] = Q
        if Ct.tclimb > 0.0:
            qmax = hold / Ct.tclimb
            if Q > qmax or Q < -qmax:
                Q = qmax if Q > 0.0 else -qmax
                if tstat[4] == 0.0:        # the first tooth to climb: when and where
                    tstat[5] = t
                    tstat[6] = j
                tstat[4] += 1.0
        tq[i] = Q
        thold[i] = hold
        fx[i] -= Q * txx
        fy[i] -= Q * tyy
        tq_belt[j] += Q * d * cb
        hubx[j] += Q * txx
        huby[j] += Q * tyy
    tstat[0] += 1.0
