"""Steady running state of a belt drive by classical creep theory, and the gross-slip margins.

Creep theory (Grashof; Reynolds; Firbank, Wear 15 (1970) 347-361; Johnson, Contact Mechanics,
ch. 8; multi-pulley form: Kong & Parker, J. Appl. Mech. 72 (2005) 25-34), for a belt of axial
stiffness EA, mass per length m, speed v (centrifugal tension c = m v^2):

- each wrap: the belt enters in an adhesion arc at the entry span's tension, then a slip arc where
  T - c varies as exp(+-mu phi) up to the exit span's tension; slip arc phi_s = ln((T_hi - c)/(T_lo - c))/mu;
  gross slip when phi_s would exceed the wrap;
- torque balance of pulley j: M_j + rho_j (T_exit - T_entry) = 0 (rho_j the radius signed by the
  sense the travelling belt turns round it), so all span tensions follow from one of them;
- mass conservation: a belt element at tension T runs at v0 (1 + T/EA); a pulley turns with the
  belt at its entry, omega = v0 (1 + T_in/EA) / r, and the creep of pulley j (1 - v_exit/v_entry)
  is (T_in - T_out)/(EA + T_in). With friction.radius = "centre" (the friction read at the belt's
  centre line) the stuck belt runs on r - p(T_in) (below: the depth) and speed ratios are read
  against the rolling radii at rest, r - p(T_rest), as the dynamic model's slip is; this theory
  then leaves out the slide of a belt landing on a wrap while it sinks (docs/belt-drive.md);
- the unstretched length L0 is fixed at installation (sum of L_k/(1 + T_k/EA) over spans plus
  the wraps' integrals of (r - p) dphi/(1 + T/EA)); it, not T1 + T2 = 2 T0, sets the tension level;
- the belt sinks into the pulley by the depth p at which the contact law carries the pressure
  (T - c)/r of a belt on an arc (seed eq. 9 per unit length: c1 p^2 + c2 p = (T - c)/r), so a
  wrap's belt length is (r - p(T)) dphi: a loaded wrap, mostly at the slack side's low tension
  (T - c ~ e^(mu phi)), rides higher than at installation, the path grows and so does the tension
  level (measured: the 5PK drive's gross-slip onset 29.0 N m without, 31.1 N m with it, against
  31.0-31.25 N m in the dynamic model at 150, 300 and 600 segments).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...core._roots import find_root
from ...core.errors import ModelError
from ...core.tables import table
from ...mechanics.layout import Layout, compute_layout
from ..geometry.placement import penetration


@dataclass
class PulleySteady:
    name: str
    wrap: float            # rad
    radius: float          # m (contact radius)
    torque: float          # load applied to the pulley (N m, counter-clockwise positive)
    speed: float           # rad/s (counter-clockwise positive)
    tension_in: float      # N, span the belt arrives from
    tension_out: float     # N, span it leaves by
    slip_arc: float        # rad (inf: gross slip)
    adhesion_arc: float    # rad
    creep: float           # 1 - v_exit / v_entry = (T_in - T_out) / (EA + T_in)
    speed_ratio: float     # omega r0 / (omega r0) of the driver, r0 the rolling radius at rest (CreepData.running_radius)
    slip_margin: float = math.inf   # load multiplier at which this pulley's slip arc fills its wrap


@dataclass
class Steady:
    state: str                 # "running" | "accelerating" | "at rest"
    speed: float               # belt speed (m/s) at the driver's entry, signed along the listed order
    acceleration: float        # belt acceleration (m/s^2) of an accelerating drive (0 else)
    centrifugal: float         # m v^2 (N)
    unstretched_length: float  # L0 (m)
    driver: str
    spans: dict                # span name -> tension (N)
    pulleys: dict              # name -> PulleySteady
    gross_slip: str = ""       # pulley that cannot hold the loads ("" when a steady state exists)
    margin: float = math.inf   # drive's slip margin (smallest of the pulleys')
    limiting: str = ""         # pulley that slips first
    notes: list = field(default_factory=list)


# --- the wrap: adhesion then slip ---------------------------------------------------------------

def _arc(t_in, t_out, c, mu):
    """Slip arc (rad) from t_in to t_out with T - c ~ exp(+-mu phi); inf when it cannot exist."""
    if t_in == t_out:
        return 0.0
    if min(t_in, t_out) <= c or mu <= 0:
        return math.inf
    return abs(math.log((t_out - c) / (t_in - c))) / mu


#: Gauss-Legendre nodes and weights on [0, 1] for the depth along a slip arc: its integrand
#: p(T) / (1 + T/EA), T - c ~ e^(mu phi), is smooth (p ~ T or sqrt(T)); 8 nodes leave < 1e-13 m
#: (Python floats: the creep solver's arithmetic runs on Python floats, several times quicker than
#: on numpy scalars and the same numbers)
_GL = [(float(0.5 * (x + 1.0)), float(0.5 * w)) for x, w in zip(*np.polynomial.legendre.leggauss(8))]
_GL2 = [(x, w * 2.0) for x, w in _GL]      # the weights doubled, as the integrand has them


def _sunk_arc(t_in, k, phi, c, r, EA, c1, c2):
    """int p(T) dphi / (1 + T/EA) (m rad) over a slip arc of phi rad, T = c + (t_in - c) e^(k x)."""
    out = 0.0
    d, kp, c22, c14 = t_in - c, k * phi, c2 * c2, 4.0 * c1     # (the same operations, once)
    for x, w2 in _GL2:
        T = c + d * math.exp(kp * x)
        q = (T - c) / r
        out += w2 * q / (c2 + math.sqrt(c22 + c14 * q)) / (1.0 + T / EA)
    return out * phi


def _wrap_length(r, theta, t_in, t_out, c, mu, EA, c1=0.0, c2=math.inf):
    """Unstretched belt length on a wrap: adhesion arc at t_in, then the slip arc, the belt at the
    depth p(T) of the contact law (``penetration``; c2 = inf: rigid pulleys, p = 0).
    Slip arc: int r dphi / (1 + T/EA) with T = c + (t_in - c) e^(k phi) is
    r [phi - ln(1 + T/EA)/k] / (1 + c/EA) (elementary integral), less the depth's share
    (``_sunk_arc``)."""
    rigid = not math.isfinite(c2)
    q_in = max(t_in - c, 0.0) / r
    p_in = 0.0 if rigid else 2.0 * q_in / (c2 + math.sqrt(c2 * c2 + 4.0 * c1 * q_in))   # ``penetration``
    phi = _arc(t_in, t_out, c, mu)
    phi = min(phi, theta)                         # gross slip: the arc cannot exceed the wrap
    if phi == 0.0 or mu <= 0 or min(t_in, t_out) <= c:   # no steady state there: length at the entry tension
        return (r - p_in) * theta / (1 + t_in / EA)
    adh = (r - p_in) * (theta - phi) / (1 + t_in / EA)
    k = math.copysign(mu, t_out - t_in)
    t_end = c + (t_in - c) * math.exp(k * phi)
    B = 1 + c / EA
    sink = 0.0 if rigid else _sunk_arc(t_in, k, phi, c, r, EA, c1, c2)
    return adh + r * (phi - math.log((1 + t_end / EA) / (1 + t_in / EA)) / k) / B - sink


# --- the core: tensions from the loads and the length ------------------------------------------

@dataclass
class CreepData:
    """What the creep solver needs of a drive (drive_of), in the listed belt order."""
    names: tuple
    rho: np.ndarray       # signed radii (layout.rho)
    wrap: np.ndarray
    span_length: np.ndarray
    span_names: tuple
    mu: np.ndarray
    EA: float
    m: float
    L0: float
    c1: float = 0.0        # contact law per unit length (N/m^3, N/m^2); c2 = inf: rigid pulleys
    c2: float = math.inf
    t_rest: float = 0.0    # the belt's tension at rest (N): sets the rolling radii r0 at rest
    centre: bool = False   # friction.radius = "centre": a stuck belt runs at its depth's radius

    def running_radius(self, j, t_in, c):
        """Signed radius (m) a stuck belt entering pulley j at tension t_in runs at: the contact
        radius, or with friction.radius = "centre" the radius of its centre line, r - p(t_in - c)."""
        if not self.centre:
            return float(self.rho[j])
        r = abs(self.rho[j])
        return math.copysign(r - float(penetration((t_in - c) / r, self.c1, self.c2)), self.rho[j])


def drive_of(model, layout: Layout | None = None) -> CreepData:
    lay = layout or compute_layout(model)
    b = model.belt
    EA = b.axial_stiffness
    c1, c2 = model.contact.stiffness_quadratic, model.contact.stiffness_linear
    # installation: the belt at rest carries the pretension everywhere (or has the given length),
    # sunk into every wrap by the depth p0 of the pretension's pressure T0 / r. The path is the
    # layout's at the contact radii less sum p0 theta: a taut path is stationary in its tangent
    # points, so to first order a radius change dr_j lengthens it by theta_j dr_j (p0 ~ 1e-4 m)
    if b.length is not None:
        L0 = b.length
    else:
        radii = np.abs(lay.rho)
        sunk = float(np.sum(lay.wrap * penetration(b.pretension / radii, c1, c2)))
        L0 = (lay.length - sunk) / (1 + b.pretension / EA)
    mu = np.full(len(lay.names), model.friction.coefficient)
    d = CreepData(lay.names, lay.rho.copy(), lay.wrap.copy(), np.array([sp.length for sp in lay.spans]),
              tuple(sp.name for sp in lay.spans), mu, EA, b.mass_per_length, L0, float(c1), float(c2),
              centre=model.friction.radius == "centre")
    if b.pretension is not None:
        d.t_rest = float(b.pretension)
    elif d.centre:          # the rolling radii at rest need the tension the length gives
        T = tensions(d, np.zeros(len(lay.names)), 0.0, True)
        d.t_rest = float(T[0]) if T is not None else 0.0
    return d


def entry_exit(nk, forward):
    """(entry span, exit span) per pulley; span k leaves pulley k in the listed order."""
    return [((j - 1) % nk, j) if forward else (j, (j - 1) % nk) for j in range(nk)]


def tension_offsets(d: CreepData, M, forward):
    """Span tensions relative to span 0 from the torque balances, walking in the travel sense."""
    nk = len(d.names)
    s = 1.0 if forward else -1.0
    off = np.zeros(nk)
    ee = entry_exit(nk, forward)
    # start at pulley 1 (forward: entry span 0) or pulley 0 (backward: entry span 0)
    j = 1 % nk if forward else 0
    for _ in range(nk - 1):
        a, b = ee[j]
        off[b] = off[a] - M[j] / (s * d.rho[j])   # M_j + rho'_j (T_exit - T_entry) = 0
        j = (j + 1) % nk if forward else (j - 1) % nk
    return off


def length_of(d: CreepData, T, c, forward):
    """Unstretched length of the belt carrying span tensions T (listed order)."""
    L = float(np.sum(d.span_length / (1 + T / d.EA)))
    # the wraps on Python floats (the same numbers as numpy scalars give, several times quicker)
    Tl, rho, wrap, mu, c = T.tolist(), d.rho.tolist(), d.wrap.tolist(), d.mu.tolist(), float(c)
    for j, (a, b) in enumerate(entry_exit(len(d.names), forward)):
        L += _wrap_length(abs(rho[j]), wrap[j], Tl[a], Tl[b], c, mu[j], d.EA, d.c1, d.c2)
    return L


def tensions(d: CreepData, M, c, forward):
    """Span tensions (listed order) under pulley loads M (balanced: sum M_j / rho_j = 0) at
    centrifugal tension c, with L0 conserved. None when the belt would go slack (T <= c)."""
    off = tension_offsets(d, M, forward)
    f = lambda t0: length_of(d, t0 + off, c, forward) - d.L0
    lo = c - off.min() + 1e-9 * (d.EA + abs(c))
    if f(lo) <= 0:                     # even the slackest tight-enough belt is too short to need more
        return None
    hi = max(lo, 1.0) * 2
    while f(hi) > 0:
        hi *= 2
        if hi > 1e3 * d.EA:
            raise ModelError("no belt tension holds this installation (belt length?)", field="belt")
    t0 = find_root(f, lo, hi, xtol=1e-10 * hi, rtol=1e-13)
    return t0 + off


def slip_arcs(d: CreepData, T, c, forward):
    return np.array([_arc(T[a], T[b], c, d.mu[j]) for j, (a, b) in enumerate(entry_exit(len(d.names), forward))])


def _fill(d: CreepData, M, c, forward, lam):
    """Largest slip-arc share of the wrap per pulley at loads lam * M (inf when slack)."""
    T = tensions(d, lam * M, c, forward)
    if T is None:
        return np.full(len(d.names), math.inf)
    return slip_arcs(d, T, c, forward) / d.wrap


def margins(d: CreepData, M, c, forward, max_factor=1e3):
    """Load multiplier per pulley at which its slip arc reaches its wrap (inf: never, e.g. an
    unloaded idler), by bisection on the factor (the driver keeps balancing the scaled loads)."""
    nk = len(d.names)
    out = np.full(nk, math.inf)
    if not np.any(M):
        return out
    fills = {}                           # the fills at a load multiplier, for every pulley at once

    def fill(lam):
        if lam not in fills:
            fills[lam] = _fill(d, M, c, forward, lam)
        return fills[lam]

    for j in range(nk):
        if M[j] == 0:
            continue
        g = lambda lam: min(fill(lam)[j], 10.0) - 1.0   # finite: the root finder on a slack jump
        hi = 1.0
        while g(hi) < 0 and hi < max_factor:
            hi *= 2
        if g(hi) < 0:
            continue
        lo = 0.0 if hi == 1.0 else hi / 2
        # a load multiplier to 1e-5 (printed to four digits)
        out[j] = lo if g(lo) >= 0 else find_root(g, lo, hi, xtol=1e-6, rtol=1e-5)
    return out


# --- the loads: steady speed, driver, or a uniformly accelerating drive ------------------------

def applied_torque(p, omega):
    """Mean torque on pulley p at steady speed omega: constant + the last torque_time value +
    the torque-speed table + viscous + bearing drag + pump + alternator power (the laws of
    ``_kernels._torque``); harmonics average out; a clutch is locked and passes its rotor's load."""
    M = p.constant_torque - p.viscous_torque * omega
    if p.torque_time:
        M += p.torque_time[-1][1]
    if p.torque_speed:   # extrapolated linearly beyond the ends, as the dynamic model reads it
        rows = np.asarray(p.torque_speed, dtype=float)
        M += table(rows[:, 0], rows[:, 1], 0, len(rows), float(omega), True)
    if p.drag:
        M -= p.drag * max(-1.0, min(1.0, omega / p.drag_speed))
    M -= p.quadratic_torque * omega * abs(omega)
    if p.power and abs(omega) > p.cut_in_speed:
        M -= p.power / p.efficiency * min(abs(omega) / p.cut_in_speed - 1.0, 1.0) / omega
    return M


def _speeds(d: CreepData, v0, T, forward, c=0.0):
    """Pulley speeds (rad/s): each turns with the belt arriving at it, v0 (1 + T_in/EA), on its
    running radius (``CreepData.running_radius``)."""
    ee = entry_exit(len(d.names), forward)
    return np.array([v0 * (1 + T[a] / d.EA) / d.running_radius(j, T[a], c) for j, (a, _) in enumerate(ee)])


def _steady_speed(model, d: CreepData, T, prescribed):
    """Belt speed v0 (unstretched, signed along the listed order) where the loads balance
    (sum M_j / rho_j = 0), or None when they never do."""
    pulleys = model.pulleys
    if prescribed is not None:
        j = prescribed
        w = pulleys[j].speed_time[-1][1]
        v_try = w * d.rho[j]
        forward = v_try >= 0
        a = entry_exit(len(d.names), forward)[j][0]
        return w * d.running_radius(j, T[a], 0.0) / (1 + T[a] / d.EA)

    def g(v0):
        w = _speeds(d, v0, T, v0 >= 0, d.m * v0 * v0)
        return sum(applied_torque(p, w[j]) / d.rho[j] for j, p in enumerate(pulleys))

    # candidates: table corners mapped to belt speed, and wide brackets; net torque is piecewise linear
    cand = {0.0}
    for j, p in enumerate(pulleys):
        for row in (p.torque_speed or []):
            cand.add(row[0] * d.rho[j])
    vmax = max(abs(x) for x in cand) if len(cand) > 1 else 1.0
    cand |= {-10 * vmax - 100, 10 * vmax + 100}
    xs = sorted(cand)
    gs = [g(x) for x in xs]
    roots = []
    for (x0, g0), (x1, g1) in zip(zip(xs, gs), zip(xs[1:], gs[1:])):
        if g0 == 0 and x0 != 0:
            roots.append(x0)
        elif g0 * g1 < 0:
            roots.append(find_root(g, x0, x1, xtol=1e-12))
    stable = [x for x in roots if g(x + 1e-6 * max(abs(x), 1)) < g(x - 1e-6 * max(abs(x), 1))]
    if stable:
        return max(stable, key=abs)
    if all(abs(x) < 1e-12 for x in gs):   # nothing loads the drive
        return 0.0
    return None


def steady_state(model, layout: Layout | None = None, loads=None, speed=None, with_margins=True) -> Steady:
    """Steady state of ``model``. ``loads`` (N m per pulley) and ``speed`` (belt m/s, signed along
    the listed order) override the model's loads: a run's mean torques and speed.
    ``with_margins=False`` leaves the slip margins out (inf): they cost most of the time."""
    d = drive_of(model, layout)
    nk = len(d.names)
    pulleys = model.pulleys
    presc = [j for j, p in enumerate(pulleys) if p.speed_time]
    notes = []
    T = np.full(nk, model.belt.pretension or 0.0)
    if model.belt.pretension is None:
        T = tensions(d, np.zeros(nk), 0.0, True)
    accel = 0.0
    if loads is not None:
        # a run's mean loads at its belt speed (m/s at the driver's entry): loads balanced below
        M = np.asarray(loads, float).copy()
        v = float(speed or 0.0)
        state = "running" if v else "at rest"
    else:
        state, v0 = "running", None
        for _ in range(12):                # loads depend on the speeds, speeds on the tensions (creep, depth)
            v0 = _steady_speed(model, d, T, presc[0] if presc else None)
            if v0 is None:
                break
            w = _speeds(d, v0, T, v0 >= 0, d.m * v0 * v0)
            M = np.array([applied_torque(p, w[j]) for j, p in enumerate(pulleys)])
            Tn = tensions(d, _balanced(d, M, w, presc), d.m * (v0 * (1 + T.mean() / d.EA)) ** 2, v0 >= 0)
            if Tn is None:
                break
            done = np.max(np.abs(Tn - T)) <= 1e-13 * np.max(np.abs(Tn))
            T = Tn
            if done:
                break
        if v0 is None:
            # loads never balance at a steady speed: the drive accelerates as one body (belt
            # acceleration a, pulley j at a / rho_j); the inertia torques -J_j a / rho_j close the balance
            M = np.array([applied_torque(p, 0.0) for p in pulleys])
            Jr = np.array([p.inertia for p in pulleys]) / d.rho
            accel = float(np.sum(M / d.rho) / np.sum(Jr / d.rho))
            M = M - Jr * accel
            v, state = 0.0, "accelerating"
            notes.append(f"the loads do not balance at any speed: the drive accelerates at {accel:.4g} m/s^2 "
                         "(belt); tensions of that uniform acceleration, no centrifugal tension")
        else:
            drv = _driver(_balanced(d, M, w, presc), w, presc)
            v = v0 * (1 + T[entry_exit(nk, v0 >= 0)[drv][0]] / d.EA)
            if abs(v0) < 1e-12:
                state = "at rest"
            notes += _table_notes(pulleys, w, M, drv)
    return _solve(d, M, v, accel, state, presc, notes, with_margins)


def _table_notes(pulleys, w, M, drv) -> list:
    """A torque_speed table read outside its speed range at the steady speed, or a load pulley
    that would deliver power (the run reports both as diagnostics: belt/dynamics/loadcheck.py)."""
    out = []
    for j, p in enumerate(pulleys):
        if not p.torque_speed or j == drv or p.clutch is not None:
            continue
        lo, hi = p.torque_speed[0][0], p.torque_speed[-1][0]
        if not lo <= w[j] <= hi:
            out.append(f"warning: pulley {p.name} runs at {w[j]:.4g} rad/s, outside its torque_speed table "
                       f"[{lo:.4g}, {hi:.4g}] rad/s (speeds signed, counter-clockwise positive): extrapolated")
        if M[j] * w[j] > 0:
            out.append(f"warning: pulley {p.name}'s torque_speed load delivers {M[j] * w[j]:.4g} W into the belt: "
                       "check the table's speed sign")
    return out


def _solve(d: CreepData, M, v, accel, state, presc, notes, with_margins=True) -> Steady:
    """Tensions, arcs, creep, speeds and margins for loads M at belt speed v (at the driver's entry)."""
    nk = len(d.names)
    forward = (accel >= 0) if state == "accelerating" else (v >= 0)
    sense = accel if state == "accelerating" else v          # the sense of motion picks the driver
    w_rigid = np.array([sense / r for r in d.rho])
    Mb = _balanced(d, M, w_rigid, presc)
    drv = _driver(Mb, w_rigid, presc)
    c = d.m * v * v
    T = tensions(d, Mb, c, forward)
    slack = T is None
    if slack:
        # a span would need a tension below m v^2: no steady state; the pulley that slips first
        # as the loads grow from zero is the one that cannot hold them
        T = np.full(nk, math.nan)
        notes.append("no steady state: a span would go slack under these loads")
    arcs = slip_arcs(d, T, c, forward) if not slack else np.full(nk, math.inf)
    ee = entry_exit(nk, forward)
    marg = margins(d, Mb, c, forward) if with_margins else np.full(nk, math.inf)
    over = [j for j in range(nk) if arcs[j] > d.wrap[j] and (not slack or Mb[j] != 0)]
    if slack:
        over = [int(np.argmin(marg))]
    e_drv = 1 + T[ee[drv][0]] / d.EA
    cw = d.m * (v / e_drv) ** 2        # the depths' centrifugal share, as the loads were read (steady_state)
    w = _speeds(d, v / e_drv, T, forward, cw)
    # speed ratios against the rolling radii at rest (r - p(T_rest)): the dynamic model's slip
    turn = np.array([(1 + T[a] / d.EA) * abs(d.running_radius(j, d.t_rest, 0.0) / d.running_radius(j, T[a], cw))
                     for j, (a, _) in enumerate(ee)])
    ratio = turn / turn[drv]
    ps = {}
    for j, name in enumerate(d.names):
        a, b = ee[j]
        ps[name] = PulleySteady(name, float(d.wrap[j]), float(abs(d.rho[j])), float(Mb[j]), float(w[j]),
                                float(T[a]), float(T[b]), float(arcs[j]), float(max(d.wrap[j] - arcs[j], 0.0)),
                                float((T[a] - T[b]) / (d.EA + T[a])), float(ratio[j]),
                                float(marg[j]))
    k = int(np.argmin(marg))
    return Steady(state, float(v), accel, c, d.L0, d.names[drv], {n: float(t) for n, t in zip(d.span_names, T)},
                  ps, gross_slip=d.names[over[0]] if over else "", margin=float(marg[k]),
                  limiting=d.names[k] if np.isfinite(marg[k]) else "", notes=notes)


def _driver(M, w, presc):
    if presc:
        return presc[0]
    return int(np.argmax(M * w)) if np.any(M * w > 0) else int(np.argmax(np.abs(M)))


def _balanced(d: CreepData, M, w, presc):
    """Loads with the driver's torque set to balance the others (sum M_j / rho_j = 0)."""
    M = np.array(M, float)
    j = _driver(M, w, presc)
    M[j] = 0.0
    M[j] = -d.rho[j] * float(np.sum(M / d.rho))
    return M
