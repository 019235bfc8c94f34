"""The segment model's contact and friction laws, the one place for them (both integrators):
the normal force and its damping, friction (Threlfall's law, the elastic-plastic bristle) and the
contact geometry of a segment on a pulley. Notation and records: _kernels.py."""
import math

from numba import njit

from ..dynamics._bodies import (smoothstep, solve_threlfall, threlfall)
from .records import LAW_THRELFALL


# ---- contact and friction: the one place for the laws (both integrators) -------------------

@njit(cache=True, inline="always")
def normal_force(c1, c2, bc, pmax, p, vn, hm):
    """Normal force of eqs. 9-10 on segment i at penetration p > 0 and normal velocity vn (outward,
    before the contact acts). hm = h/m > 0: the damping implicit in the new normal velocity,
    vn_new = vn + hm N; hm = 0: explicit. Returns (N, delta(p) b); N <= 0 means no contact force."""
    db = smoothstep(p / pmax) * bc
    N = (c1 * p * p + c2 * p - db * vn) / (1.0 + db * hm)
    return N, db


@njit(cache=True, inline="always")
def clipped_power(c1, c2, p, vn):
    """The contact damper's power where it holds the normal force at zero (N = k(p) - db vn <= 0:
    the segment separates faster than the contact pushes): the damper then carries the whole
    elastic force k(p) against the separation speed vn, so the contact's elastic energy is
    dissipated, not returned (without this term it left the energy balance unseen, 1 % of the
    power at 3000 rpm on examples/fead-runup.toml's drive, where segments leave the tensioner's
    moving pulley)."""
    return (c1 * p * p + c2 * p) * vn if vn > 0.0 else 0.0


@njit(cache=True, inline="always")
def contact_energy(Ct, i, p):
    """Potential of the elastic part of eq. 9 at penetration p > 0 (J)."""
    return Ct.c1[i] * p * p * p / 3.0 + Ct.c2[i] * p * p / 2.0


@njit(cache=True, inline="always")
def friction(mu, law, dv, dmax, N, wslip, hm, h, z, i):
    """Friction force T on segment i (along the tangent Z x n) under normal force N, for the slip
    wslip of the pulley surface relative to the segment before friction acts. Implicit in the new
    slip with hm = h/m > 0, explicit with hm = 0. Updates z[i] (elastic-plastic state).
    Returns (T, slip after), so that T * slip is the friction power."""
    muN = mu * N
    if law == LAW_THRELFALL:
        sl = solve_threlfall(wslip, hm * muN, dv)
        T = muN * threlfall(sl, dv)
    else:
        T, sl, z[i] = _bristle(muN, dmax, wslip, z[i], h, hm)
    return T, sl


@njit(cache=True, inline="always")
def _bristle(muN, dmax, wslip, z, h, hm):
    """The elastic-plastic law (``friction``): T = K z with K = mu N / dmax, z_new = z + h slip_new,
    clipped at the displacement limit; branch-free so that a loop of it vectorises. Returns (T,
    slip after, z_new)."""
    K = muN / dmax
    zn = min(max((z + h * wslip) / (1.0 + h * hm * K), -dmax), dmax)
    T = K * zn
    return T, wslip - hm * T, zn


@njit(cache=True, inline="always")
def contact(Ct, i, rx, ry, d2, r, vx, vy, om, hm, h, z):
    """Segment i inside the contact radius r of a pulley (d2 = |rx, ry|^2 < r^2, (rx, ry) from the
    pulley centre to the segment centre), segment velocity (vx, vy), pulley speed om: normal force
    and friction (eqs. 4-17). Returns (p, N, T, nx, ny, contact damping power, friction power);
    N <= 0: no force (the segment leaves faster than the contact pushes)."""
    dist = math.sqrt(d2)
    inv = 1.0 / dist
    nx = rx * inv
    ny = ry * inv
    p = r - dist
    vn = vx * nx + vy * ny
    N, db = normal_force(Ct.c1[i], Ct.c2[i], Ct.bc[i], Ct.pmax, p, vn, hm)
    if N <= 0.0:
        return p, N, 0.0, nx, ny, clipped_power(Ct.c1[i], Ct.c2[i], p, vn), 0.0
    vn_new = vn + hm * N
    # tangent tau = Z x n; slip of the pulley surface relative to the segment
    vt = vx * -ny + vy * nx
    T, sl = friction(Ct.mu[i], Ct.law, Ct.dv, Ct.dmax, N, om * (dist if Ct.centre else r) - vt, hm, h, z, i)
    return p, N, T, nx, ny, db * vn_new * vn_new, T * sl
