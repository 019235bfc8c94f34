"""Tooth load sharing on one pulley and the torque at which a tooth climbs out.

Quasi-static shear-lag chain, the model behind the load-distribution studies seed 001 cites
(Koyama et al. 1979, Naji & Marshek 1983, Kagotani et al. 1983): the belt's tension member is an
elastic bar (EA) wrapped on the pulley's pitch line; each of the n teeth in mesh is a linear spring
k_t between the bar and its groove; the lands between grooves carry Coulomb friction (coefficient
mu) against the radial pressure T/R of the wrapped belt (capstan: dT = mu T dtheta).

Coordinates: s along the pitch line from tooth 1 (next to the tight span, tension T1) to tooth n
(next to the slack span, T2). Every node k (a tooth, or a land point) has a displacement d_k of
the belt relative to the pulley, positive towards the tight side. An element of the bar between
nodes k and k+1, of length L_k, carries

    T_k = T_ref + EA / L_k * (d_k - d_(k+1) - e L_k / p)                        (1)

where e is the pitch error (belt pitch minus groove spacing on the belt pitch line, both at the
reference tension T_ref, the installation tension) and p the groove spacing. Node equilibrium:

    T_in - T_out = Q(d_k)  (tooth)    or    mu N_k tanh(d_k / u_s)  (land)        (2)

where the tooth spring has a dead band of the tooth's sideways play c in its groove,
Q = k_t (d - c) for d > c, k_t (d + c) for d < -c, 0 between, smoothed over u_s (softplus;
c = 0 gives exactly Q = k_t d),
and N_k = (T_in + T_out) / 2 * l_k / R the radial force on the land length l_k and u_s a slip
scale that regularises the sign of the friction (a land sliding less than u_s carries a share of
its limiting friction). The sum of (2) over the nodes gives T1 - T2 = sum of tooth loads + sum of
land friction: the balance the tests check. Without friction and pitch error (1)-(2) reduce to the
linear recurrence tau_(i-1) - (2 + k_t / k_c) tau_i + tau_(i+1) = 0 for tau_i = T_i - T_ref and
k_c = EA / p, whose geometric solution the tests rebuild independently.

Jumping (ratcheting): a rigid tooth pressed with load Q against a flank at angle phi to the groove
axis, with flank friction angle rho = atan(mu), is pushed outwards by Q tan(phi - rho) (the wedge
of an inclined plane with friction; rho opposes the outward slide). The wrapped belt holds one
pitch down with the radial resultant of its tension over that pitch, T p / R (the capstan normal
force). A tooth starts to climb when

    Q tan(phi - rho) >= T_local p / R                                              (3)

with T_local the mean tension at the tooth; phi is the steepest contact angle (to the groove axis)
met while the seated tooth, pressed on its flank, lifts out of the groove (``exit_path``: the
boundary of the tooth's free region in the groove, found with the exact contours).
A belt supported under its cord by a radial stiffness k_r per length (its lands, teeth and the
pulley's surface) sinks by delta = T / (R k_r) under the wrap's pressure T / R; a pitch of cord then
spans p / (R - delta) of the pulley, which on the pitch circle is p (1 + delta / R): the pulley sees
the cord in series with that sinking (delta measured from T_ref, as e),

    1 / EA_eff = 1 / EA + 1 / (R^2 k_r)                                            (4)

(k_r infinite: the cord on the pitch circle, EA_eff = EA).

The jump torque is the smallest torque at which (3) holds for some tooth. It is the onset of
climbing of a rigid tooth: a deflected tooth (rotated flank), centrifugal tension and the belt's
own bending lower it; phi <= rho is self-locking (no finite jump torque in this model).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from scipy.linalg import solve_banded


@dataclass(frozen=True)
class Chain:
    """The belt on one pulley: whole-width stiffnesses (SI)."""

    teeth: int                 # n, teeth in mesh
    pitch: float               # p, groove spacing on the belt pitch line (m)
    radius: float              # R, belt pitch-line radius (m)
    tooth_stiffness: float     # k_t per tooth (N/m)
    cord_stiffness: float      # EA (N)
    land_share: float = 0.5    # share of a pitch where the belt land rests on the pulley
    friction: float = 0.0      # mu on the lands
    pitch_error: float = 0.0   # e (m per pitch) at the reference tension
    land_nodes: int = 4        # points per land where friction acts (the angle discretisation)
    slip_scale: float = 1e-6   # u_s (m)
    clearance: float = 0.0     # c, sideways play of a seated tooth before it bears on a flank (m)
    radial_stiffness: float = float("inf")  # k_r, the belt's support under its cord per length (N/m^2)

    def nodes(self):
        """Node positions s (m), tooth flags and land lengths l_k carried by each node."""
        n, p, m = self.teeth, self.pitch, self.land_nodes if self.friction > 0 else 0
        land = self.land_share * p
        s, tooth, trib = [], [], []
        for i in range(n):
            s.append(i * p)
            tooth.append(True)
            trib.append(0.0)
            if i < n - 1 and m > 0:
                # midpoints of m equal pieces of the land, which is centred between the grooves
                start = i * p + 0.5 * (p - land)
                for j in range(m):
                    s.append(start + (j + 0.5) * land / m)
                    tooth.append(False)
                    trib.append(land / m)
        return np.array(s), np.array(tooth), np.array(trib)


@dataclass
class Sharing:
    """A solved chain: node and element data, tooth loads and the boundary tensions."""

    s: np.ndarray          # node positions (m)
    tooth: np.ndarray      # node is a tooth
    d: np.ndarray          # displacement of the belt towards the tight side (m)
    element_s: np.ndarray  # element midpoints (m)
    element_T: np.ndarray  # element tensions (N)
    tooth_load: np.ndarray  # Q_i, teeth 1..n (N)
    land_friction: np.ndarray  # friction force of each land node (N)
    tension_in: np.ndarray  # tension arriving at each node from the tight side (N)
    tension_out: np.ndarray
    T1: float
    T2: float
    iterations: int

    @property
    def tooth_tension(self):
        """Mean tension at each tooth (N)."""
        return 0.5 * (self.tension_in + self.tension_out)[self.tooth]


def cord_stiffness(chain) -> float:
    """The cord's stiffness along the pitch circle (N), (4): EA in series with the belt's sinking."""
    return 1.0 / (1.0 / chain.cord_stiffness + 1.0 / (chain.radius ** 2 * chain.radial_stiffness))


def _state(chain, s, tooth, trib, d, T1, T2, T_ref):
    L = np.diff(s)
    a = cord_stiffness(chain) / L
    Te = T_ref + a * (d[:-1] - d[1:] - chain.pitch_error * L / chain.pitch)
    Tin = np.concatenate([[T1], Te])
    Tout = np.concatenate([Te, [T2]])
    return a, Te, Tin, Tout


class _Stalled(RuntimeError):
    pass


def solve(chain: Chain, T1: float, T2: float, T_ref: float) -> Sharing:
    """Displacements, tensions and tooth loads of ``chain`` between tensions T1 (tight, tooth 1)
    and T2 (slack, tooth n), the pitch error measured at T_ref. Newton on (1)-(2) (tridiagonal);
    if it stalls, continuation from a 10^4 times wider slip scale down to the chain's."""
    try:
        return _newton(chain, T1, T2, T_ref)
    except _Stalled:
        pass
    d = None
    for k in (4, 3, 2, 1, 0):
        try:
            sh = _newton(replace(chain, slip_scale=chain.slip_scale * 10.0 ** k), T1, T2, T_ref, d0=d)
        except _Stalled as exc:
            raise RuntimeError(f"load sharing did not converge ({exc})") from None
        d = sh.d
    return sh


def _newton(chain: Chain, T1, T2, T_ref, d0=None, tol=1e-10, max_iter=100) -> Sharing:
    s, tooth, trib = chain.nodes()
    K = len(s)
    kt = np.where(tooth, chain.tooth_stiffness, 0.0)
    c = trib / chain.radius
    mu, us = chain.friction, chain.slip_scale
    scale = max(abs(T1), abs(T2), abs(T1 - T2), 1.0)

    cl = chain.clearance

    def spring(d):
        """Tooth load and its derivative: k_t (d -+ c) outside the play, smoothed over u_s."""
        if cl <= 0:
            return kt * d, kt
        up, dn = (d - cl) / us, (-d - cl) / us
        q = kt * us * (np.logaddexp(0, up) - np.logaddexp(0, dn))
        # floor: a chain whose teeth all float in their play has no stiffness against sliding
        dq = kt * (0.5 * (1 + np.tanh(up / 2)) + 0.5 * (1 + np.tanh(dn / 2)) + 1e-9)
        return q, dq

    def residual(d):
        a, Te, Tin, Tout = _state(chain, s, tooth, trib, d, T1, T2, T_ref)
        th = np.tanh(d / us) if mu > 0 else np.zeros(K)
        g = mu * th
        q, dq = spring(d)
        return Tin - Tout - q - g * c * 0.5 * (Tin + Tout), (a, Tin, Tout, th, g, dq)

    def jacobian(d, a, Tin, Tout, th, g, dq):
        gp = mu * (1 - th ** 2) / us if mu > 0 else np.zeros(K)
        ab = np.zeros((3, K))
        lower = a * (1 - c[1:] * g[1:] / 2)       # J[k, k-1], k = 1..K-1
        upper = a * (1 + c[:-1] * g[:-1] / 2)     # J[k, k+1], k = 0..K-2
        ab[0, 1:] = upper
        ab[2, :-1] = lower
        diag = -dq - c * gp * 0.5 * (Tin + Tout)
        diag[1:] -= lower
        diag[:-1] -= upper
        ab[1] = diag
        return ab

    if d0 is not None:
        d = d0.copy()
    elif cl > 0 or mu > 0:  # start from the linear chain, each tooth shifted across its play
        linear = replace(chain, clearance=0.0, friction=0.0)
        d = np.interp(s, linear.nodes()[0], _newton(linear, T1, T2, T_ref).d)
        d = d + cl * np.sign(d) * tooth
    else:
        d = np.zeros(K)
    it = 0
    r, aux = residual(d)
    a_max = float(np.max(aux[0])) if K > 1 else 0.0
    for it in range(1, max_iter + 1):
        # round-off floor: a cord element's tension is a (d_k - d_(k+1)), a = EA / L
        if np.max(np.abs(r)) <= max(tol * scale, 16 * np.finfo(float).eps * a_max * np.max(np.abs(d))):
            break
        try:
            step = solve_banded((1, 1), jacobian(d, *aux), -r)
        except np.linalg.LinAlgError:
            raise _Stalled("singular Jacobian") from None
        norm = np.linalg.norm(r)
        lam = 1.0
        while True:  # backtracking: the tanh friction makes far steps overshoot
            trial = d + lam * step
            r_new, aux_new = residual(trial)
            if np.linalg.norm(r_new) < (1 - 1e-4 * lam) * norm:
                break
            lam *= 0.5
            if lam < 1e-8:
                raise _Stalled(f"line search stalled at residual {np.max(np.abs(r)):.3g} N")
        d, r, aux = trial, r_new, aux_new
    else:
        raise _Stalled(f"{max_iter} Newton steps, residual {np.max(np.abs(r)):.3g} N")
    a, Te, Tin, Tout = _state(chain, s, tooth, trib, d, T1, T2, T_ref)
    friction = np.where(tooth, 0.0, aux[4] * c * 0.5 * (Tin + Tout))
    return Sharing(s=s, tooth=tooth, d=d, element_s=0.5 * (s[:-1] + s[1:]), element_T=Te,
                   tooth_load=spring(d)[0][tooth], land_friction=friction[~tooth], tension_in=Tin,
                   tension_out=Tout, T1=T1, T2=T2, iterations=it)


def span_tensions(torque, T0, radius):
    """Tight and slack tension for ``torque`` at installation tension T0: T1,2 = T0 +- M/(2R)
    (equal span stiffness, constant belt length), the slack side not below zero."""
    half = torque / (2 * radius)
    if half <= T0:
        return T0 + half, T0 - half
    return torque / radius, 0.0


def climb_factor(flank_angle, friction):
    """tan(phi - rho) of (3), or 0 when the flank is self-locking (phi <= rho)."""
    return float(max(np.tan(flank_angle - np.arctan(friction)), 0.0))


def jump_margin(sh: Sharing, chain: Chain, factor: float):
    """Per tooth: outward push Q tan(phi - rho) minus the hold T_local p / R (N); > 0 climbs."""
    hold = sh.tooth_tension * chain.pitch / chain.radius
    return sh.tooth_load * factor - hold


def jump_torque(chain: Chain, T0: float, factor: float, rtol=1e-6):
    """Smallest torque (N m) at which a tooth satisfies (3), by bisection on the torque; None if
    the flank is self-locking or no tooth climbs below 1000 T0 R."""
    if factor <= 0:
        return None
    R = chain.radius

    def margin(M):
        T1, T2 = span_tensions(M, T0, R)
        return float(np.max(jump_margin(solve(chain, T1, T2, T0), chain, factor)))

    if margin(0.0) >= 0:
        return 0.0
    lo, hi = 0.0, 2 * T0 * R  # the slack span goes slack at 2 T0 R
    while margin(hi) < 0:
        lo, hi = hi, 2 * hi
        if hi > 1000 * T0 * R:
            return None
    while hi - lo > rtol * hi:
        mid = 0.5 * (lo + hi)
        if margin(mid) >= 0:
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


# --------------------------------------------------------------------------------------------
# data of a pair: teeth in mesh, land share, flank angle, tooth stiffness from the profile

def teeth_in_mesh(z: int, wrap: float) -> int:
    """Whole teeth seated over the wrap angle: floor(z wrap / 2 pi), at least 1."""
    return max(int(np.floor(z * wrap / (2 * np.pi) + 1e-9)), 1)


def land_share(pair) -> float:
    """Share of a pitch where the belt land rests on the outside circle (between grooves)."""
    from .profiles import tooth_outline

    r_o, z = pair.outside_radius, pair.teeth
    if pair.groove is not None:
        end = pair.groove.half(r_o, max(pair.tol, 1e-6))[-1]
        groove_angle = 2 * np.arctan2(end[0], end[1])
    else:
        half_width = np.max(np.abs(tooth_outline(pair.tooth, max(pair.tol, 1e-6))[:, 0]))
        groove_angle = 2 * (half_width + pair.generated_clearance) / r_o
    return float(np.clip(1 - groove_angle * z / (2 * np.pi), 0.0, 1.0))


def exit_path(pair, lifts=60, method="rays"):
    """The seated tooth lifted along the groove axis by y and pushed sideways (+x) until it
    touches: (y, x_max(y)) in m. This is the boundary of the tooth's free region (its configuration
    space) in the groove: a tooth that climbs while pressed on its flank follows it, and its slope
    dx/dy = tan(phi) is the contact normal's angle phi to the groove axis.

    Two polygons translated along +x first touch where a vertex of one meets an edge of the other:
    ``method="rays"`` casts each tooth vertex along +x onto the pulley's edges and each pulley vertex
    along -x onto the tooth's (the pulley's edges near the groove only: those within the tooth's sweep),
    the nearest hit being x_max; ``"advance"``: conservative advancement, x stepped by the shapely
    distance until it is below 1e-9 m (the reference: the rays give its path within 1e-8 m at a
    tenth of its cost or less, tests/toothed/test_loadshare.py)."""
    import shapely
    import shapely.affinity

    from .kinematics import to_pulley
    from .profiles import tooth_outline
    from .pulley import pulley_polygon

    tol = max(pair.tol, 1e-6)
    tooth = shapely.Polygon(to_pulley(tooth_outline(pair.tooth, tol), np.array([0.0]), pair.belt_radius)[0])
    pulley = pulley_polygon(pair)
    shapely.prepare(pulley)
    ys = np.linspace(0.0, pair.tooth.height, lifts + 1)
    xs = np.full_like(ys, np.inf)
    reach = pair.tooth.pitch
    if method == "advance":
        for j, y in enumerate(ys):
            x = 0.0
            for _ in range(500):
                d = shapely.distance(shapely.affinity.translate(tooth, x, y), pulley)
                if d < 1e-9:
                    break
                x += d
                if x > reach:
                    x = np.inf
                    break
            xs[j] = x
        return ys, xs
    # the pulley's edges the tooth can meet: those crossing the box it sweeps (2 % wider)
    rings = [np.asarray(r.coords) for r in (pulley.exterior, *pulley.interiors)]
    pa = np.concatenate([r[:-1] for r in rings])
    pb = np.concatenate([r[1:] for r in rings])
    x0, y0, x1, y1 = tooth.bounds
    m = 0.02 * reach
    near = ((np.maximum(pa[:, 0], pb[:, 0]) >= x0 - m) & (np.minimum(pa[:, 0], pb[:, 0]) <= x1 + reach + m)
            & (np.maximum(pa[:, 1], pb[:, 1]) >= y0 - m) & (np.minimum(pa[:, 1], pb[:, 1]) <= y1 + ys[-1] + m))
    pa, pb = pa[near], pb[near]
    T = np.asarray(tooth.exterior.coords)
    L, nt, npv = len(ys), len(T) - 1, 2 * len(pa)
    # every lift at once: the tooth's vertices lifted, cast along +x onto the pulley's edges; the
    # pulley's edges' ends lowered by the lift (the tooth's frame), cast along -x onto the tooth's edges
    up = _ray_hits(np.tile(T[:-1, 0], L), (T[None, :-1, 1] + ys[:, None]).ravel(), pa, pb, 1.0).reshape(L, nt)
    pv = np.concatenate([pa, pb])
    down = _ray_hits(np.tile(pv[:, 0], L), (pv[None, :, 1] - ys[:, None]).ravel(), T[:-1], T[1:], -1.0).reshape(L, npv)
    xs[:] = np.minimum(up.min(axis=1, initial=np.inf), down.min(axis=1, initial=np.inf))
    for j, y in enumerate(ys):
        if shapely.intersects(shapely.affinity.translate(tooth, 0.0, y), pulley):
            xs[j] = 0.0          # touching or inside at the seat's abscissa
    xs[xs > reach] = np.inf
    return ys, xs


def _ray_hits(px, py, a, b, direction):
    """Per ray from (px[i], py[i]) along ``direction`` x (+1 or -1): the nearest distance (m) at which
    it meets one of the segments a -> b, inf if none. A ray meets only the segments that span its
    height: those are found by sorting the segments by their lower end (the short ones: a window of
    the longest short segment's height; the few long ones against every ray). A segment level with
    the ray is met at its ends, which its neighbours carry."""
    dy = b[:, 1] - a[:, 1]
    keep = dy != 0.0
    a, b, dy = a[keep], b[keep], dy[keep]
    lo_y = np.minimum(a[:, 1], b[:, 1])
    span = np.abs(dy)
    short = span <= 20.0 * np.median(span) if len(span) else span > 0
    out = np.full(len(px), np.inf)

    def meet(i, k):
        s = (py[i] - a[k, 1]) / dy[k]
        t = direction * (a[k, 0] + s * (b[k, 0] - a[k, 0]) - px[i])
        t = np.where((s >= 0.0) & (s <= 1.0) & (t >= 0.0), t, np.inf)
        np.minimum.at(out, i, t)

    ks = np.flatnonzero(short)
    if len(ks):
        order = ks[np.argsort(lo_y[ks])]
        ys_sorted = lo_y[order]
        h = float(span[ks].max())
        first = np.searchsorted(ys_sorted, py - h, "left")
        last = np.searchsorted(ys_sorted, py, "right")
        count = last - first
        i = np.repeat(np.arange(len(px)), count)
        k = order[np.repeat(first, count) + np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)]
        meet(i, k)
    kl = np.flatnonzero(~short)
    if len(kl):
        meet(np.repeat(np.arange(len(px)), len(kl)), np.tile(kl, len(px)))
    return out


def flank_angle(pair, lifts=60, path=None) -> float:
    """Steepest angle phi (rad, to the groove axis) of the contact along the exit path of the
    seated tooth (exit_path), up to where it is free to slide over the rim; negative where the
    path turns back (an undercut that traps a rigid tooth). 0 if the tooth is free at once."""
    ys, xs = exit_path(pair, lifts) if path is None else path
    free = np.flatnonzero(~np.isfinite(xs))
    last = free[0] if len(free) else len(xs)
    if last < 2:
        return 0.0
    dx, dy = np.diff(xs[:last]), np.diff(ys[:last])
    return float(np.min(np.arctan2(dx, dy)))


def tooth_stiffness_per_width(tooth, shear_modulus: float) -> float:
    """Tooth spring per unit width (N/m per m) from its shape and the shear modulus G of its
    material: a cantilever of the tooth's width at mid-height s, loaded at mid-height h/2 above the
    land; Timoshenko bending + shear, E = 3 G (incompressible rubber), shear factor 6/5:

        1 / k' = (4 (h/2)^3 / (3 s^3) + 1.2 (h/2) / s) / G

    The root's rotation in the belt body is left out, so this is a stiff estimate."""
    half = tooth.half(1e-6 * tooth.height)  # chord tolerance relative: the estimate is scale-free
    v_mid = tooth.land - tooth.height / 2
    order = np.argsort(half[:, 1])
    s = 2 * float(np.interp(v_mid, half[order, 1], np.abs(half[order, 0])))
    hc = tooth.height / 2
    return shear_modulus / (4 * hc ** 3 / (3 * s ** 3) + 1.2 * hc / s)
