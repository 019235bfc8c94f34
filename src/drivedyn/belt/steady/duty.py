"""The duty cycle a supplier's report evaluates (``[duty_cycle]`` of the model): per row, every
span's tension, every pulley's hub load (magnitude and direction) and slip safety factor, in two
conventions side by side:

- the supplier's ("fixed arm"): the tensioner's arm stays where the belt length puts it, so the
  span between the tensioner and the pulley before it in the belt's travel (in the usual layout,
  the slack span from the crank) keeps the design tension whatever the loads, and every other span
  follows from the pulleys' torques (Gates "Pulley Hubload Analysis", which lists the pulleys
  against the belt's travel); hub loads are the vector sum of the two span tensions, as the supplier
  prints them;
- the running balance ("running arm", creep theory, running.py and creep.py): the belt's installed
  length kept, the arm where its spring balances the running span tensions less m v^2 (a slack span
  falls 3-25 % under load on the public reports), the hub loads from T - m v^2 (the wrapped belt
  carries its centrifugal tension itself), the arm's running position against its stops.

Loads: each row's powers or torques by pulley; every other pulley but the crank (the prescribed-speed
pulley) carries the idler drag ``duty_cycle.idler_drag`` (Gates adds 0.01 kW on each idler and
the tensioner). Slip safety factor, the torque at which the pulley slips over its whole wrap over
the torque it carries: with the arm fixed, the slack span's tension held (the tensioner holds it),
(T_slack - m v^2)(e^(mu phi) - 1) r / M; with the belt length kept, creep theory's load multiplier
at gross slip (creep.margins: the extra torque also slackens the spans the pulley shares).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...core.errors import ModelError
from .creep import entry_exit, tension_offsets, drive_of


@dataclass(frozen=True)
class DutyColumns:
    """One convention's numbers for one duty row (listed order; span k leaves pulley k)."""
    spans: dict                # span name -> tension (N)
    hub_load: dict             # pulley -> magnitude (N)
    hub_direction: dict        # pulley -> direction of the belt's force, from +x CCW (rad)
    slip_factor: dict          # pulley -> slip safety factor (inf: no torque)


@dataclass(frozen=True)
class DutyRowResult:
    crank_speed: float         # rad/s
    share: float
    belt_speed: float          # m/s
    torques: dict              # pulley -> load torque magnitude it carries (N m; the crank: what it delivers)
    fixed_arm: DutyColumns
    running_arm: DutyColumns | None     # None: no running balance (why in ``note``)
    arm_travel: dict           # tensioner pulley -> running travel from the drawn position (rad or m)
    arm_stops: dict            # tensioner pulley -> (stop away from the belt, stop into it)
    slip_margin: dict          # pulley -> creep theory's load multiplier at gross slip (running balance)
    note: str = ""


def crank_of(model) -> int:
    """The crank: the prescribed-speed pulley the duty rows set the speed of."""
    presc = [j for j, p in enumerate(model.pulleys) if p.speed_time is not None]
    if len(presc) != 1:
        raise ModelError("a duty cycle needs one crank: the pulley with a prescribed speed (speed_time)",
                         field="duty_cycle")
    return presc[0]


def _frame(drive):
    """(model, its duty cycle, the crank's index, the drawn layout, creep theory's drive data)."""
    model = drive.model
    return model, model.duty_cycle, crank_of(model), drive.layout, drive_of(model, drive.layout)


def belt_speed(drive, crank_speed: float) -> float:
    """Belt speed (m/s, signed along the listed order) at a crank speed (rad/s, its magnitude; the
    sense the crank's speed_time gives)."""
    c = crank_of(drive.model)
    return math.copysign(1.0, drive.model.pulleys[c].speed_time[-1][1] or 1.0) * crank_speed * drive.layout.rho[c]


def row_power(row, name: str, speed: float, default=None):
    """The power (W) a duty row puts on pulley ``name`` turning at ``speed`` (rad/s): its power, its
    torque x speed, else ``default``."""
    return row.torque[name] * speed if name in row.torque else row.power.get(name, default)


def duty_cycle(drive, design_tension: float) -> list[DutyRowResult]:
    """Every row of the model's duty cycle in both conventions; ``design_tension``: the tension the
    supplier holds in the span leaving the tensioner (the position table's mean row)."""
    model, dc, c, lay, d = _frame(drive)
    nk = len(lay.names)
    out = []
    for k, row in enumerate(dc.rows):
        v = belt_speed(drive, row.crank_speed)
        forward = v > 0
        w = v / lay.rho                                         # pulley speeds (rad/s, CCW positive)
        M = np.zeros(nk)
        for j, p in enumerate(model.pulleys):
            if j != c:                                          # a load opposes the pulley's turning
                M[j] = -math.copysign(row_power(row, p.name, abs(w[j]), dc.idler_drag) / abs(w[j]), w[j])
        M[c] = -lay.rho[c] * float(np.sum(np.delete(M / lay.rho, c)))
        torques = {p.name: abs(float(M[j])) for j, p in enumerate(model.pulleys)}
        fixed = _fixed_arm(model, drive, d, M, forward, design_tension, v)
        run, travel, margin, note = _running_arm(model, drive, M, v)
        out.append(DutyRowResult(row.crank_speed, row.share, abs(v), torques, fixed, run, travel,
                                 {model.pulleys[j].name: tuple(model.pulleys[j].tensioner.stops)
                                  for j in drive.tensioners}, margin, note))
    return out


def acceleration_envelope(drive, design_tension: float) -> list[dict]:
    """The slip safety factors (fixed arm) at each duty row's crank speed while the crank speeds up
    and slows down at ``duty_cycle.acceleration``: each pulley's inertia torque J alpha (alpha its
    angular acceleration, the crank's times its speed ratio) on top of the accessory loads at
    ``part_load`` and at full load (each accessory's largest over the rows). Per speed and load:
    the smallest factor and the pulley, accelerating and decelerating (Gates' slip page uses
    +-1000 rpm/s at 10 % and 100 % load)."""
    model, dc, c, lay, d = _frame(drive)
    nk = len(lay.names)
    full = {}
    for row in dc.rows:                   # each accessory's largest power over the rows, at its speed
        for j, p in enumerate(model.pulleys):
            P = row_power(row, p.name, abs(belt_speed(drive, row.crank_speed) / lay.rho[j]))
            if P is not None:
                full[p.name] = max(full.get(p.name, 0.0), P)
    out = []
    for row in dc.rows:
        v = belt_speed(drive, row.crank_speed)
        w = v / lay.rho
        entry = {"crank_speed": row.crank_speed}
        for label, share in (("part_load", dc.part_load), ("full_load", 1.0)):
            for sense, sgn in (("accelerating", 1.0), ("decelerating", -1.0)):
                a = sgn * v / abs(v) * dc.acceleration * abs(lay.rho[c])       # belt acceleration along the list
                M = np.zeros(nk)
                for j, p in enumerate(model.pulleys):
                    if j == c:
                        continue
                    P = share * full[p.name] if p.name in full else dc.idler_drag
                    M[j] = -math.copysign(P / abs(w[j]), w[j]) - p.inertia * a / lay.rho[j]
                M[c] = -lay.rho[c] * float(np.sum(np.delete(M / lay.rho, c)))
                cols = _fixed_arm(model, drive, d, M, v > 0, design_tension, v)
                sf = [(f, n) for n, f in cols.slip_factor.items() if math.isfinite(f)]
                f, n = min(sf) if sf else (math.inf, "")
                entry[f"{label}_{sense}"] = {"slip_factor": f, "pulley": n,
                                             "factors": {k: x for k, x in cols.slip_factor.items() if math.isfinite(x)}}
        out.append(entry)
    return out


def _fixed_arm(model, drive, d, M, forward, design_tension, v) -> DutyColumns:
    lay = drive.layout
    nk = len(lay.names)
    off = tension_offsets(d, M, forward)
    ee = entry_exit(nk, forward)
    anchor = ee[drive.tensioners[0]][0] if drive.tensioners else None
    if anchor is None:
        raise ModelError("the supplier's duty table holds the span leaving the tensioner at the design tension: "
                         "this drive has no tensioner", field="duty_cycle")
    T = design_tension - off[anchor] + off
    return _columns(model, lay, T, T, forward, model.belt.mass_per_length * v * v, M)


def _running_arm(model, drive, M, v):
    from .creep import steady_state
    from .running import running_balance

    try:
        if drive.tensioners:
            run, why = running_balance(model, drive.equilibrium, torques=M, speed=v)
            if run is None:
                return None, {}, {}, f"not carried: {why}"
            qv, m, lay, st = run
            travel = {model.pulleys[j].name: float(q) for j, q in zip(drive.tensioners, qv)}
        else:
            lay, travel = drive.layout, {}
            st = steady_state(model, lay, loads=M, speed=v)
    except ModelError as exc:
        return None, {}, {}, f"no running balance: {exc}"
    if st.gross_slip or not all(math.isfinite(t) for t in st.spans.values()):
        return None, travel, {}, f"no steady state: pulley {st.gross_slip or '?'} slips over its whole wrap"
    T = np.array([st.spans[sp.name] for sp in lay.spans])
    margin = {n: float(p.slip_margin) for n, p in st.pulleys.items()}
    # with the belt length kept, a pulley's extra torque also slackens the spans it shares: its
    # slip factor is creep theory's load multiplier at gross slip (creep.margins), the arm held
    cols = _columns(model, lay, T, T - st.centrifugal, v > 0, st.centrifugal, M, margin)
    return cols, travel, margin, ""


def _columns(model, lay, T, T_hub, forward, c, M, margin=None) -> DutyColumns:
    """Span tensions, hub loads from ``T_hub`` and slip factors for span tensions T (``margin``:
    the slip factors given, per pulley)."""
    nk = len(lay.names)
    hub = np.zeros((nk, 2))
    for k, sp in enumerate(lay.spans):
        u = np.array([math.cos(sp.angle), math.sin(sp.angle)])
        hub[sp.start] += T_hub[k] * u
        hub[sp.end] -= T_hub[k] * u
    ee = entry_exit(nk, forward)
    mu = model.friction.coefficient
    sf = {}
    for j, p in enumerate(model.pulleys):
        a, b = ee[j]
        slack = min(T[a], T[b]) - c
        cap = max(slack, 0.0) * math.expm1(mu * lay.wrap[j]) * abs(lay.rho[j])
        sf[p.name] = (margin[p.name] if margin is not None else cap / abs(M[j])) if M[j] else math.inf
    return DutyColumns({sp.name: float(t) for sp, t in zip(lay.spans, T)},
                       {p.name: float(np.hypot(*hub[j])) for j, p in enumerate(model.pulleys)},
                       {p.name: math.atan2(hub[j][1], hub[j][0]) for j, p in enumerate(model.pulleys)}, sf)
