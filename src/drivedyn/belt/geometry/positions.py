"""The tensioner's position table as a belt supplier prints it: the arm at the free arm, at the
belt lengths of a replaced (worn) belt, the longest, the nominal and the shortest belt (the drawn
position is the nominal belt's; the others lie ``belt.length_tolerance``, plus the wear allowance,
either side of it in belt length), and at the load stop; at each, the arm angle, the pulley centre, the effective drive length and the required
belt length (catalogue.py), the tensioner wrap, the angle between hub load and arm, and the belt
tension, hub load and its direction that the spring holds.

Angles are the supplier's: ``rel`` from the free arm (no belt, spring torque ``free_torque``) away
from the belt, the absolute angle from +x counter-clockwise (pivot to pulley centre). The tension
is the spring's torque over the belt's lever, by virtual work without friction:
T = M / (a sin(beta) 2 sin(phi / 2)), a the arm length, beta the angle between hub load and arm
(pulley centre to pivot), phi the tensioner wrap; hub load 2 T sin(phi / 2). The belt take-up
ratio is d(EDL)/d(arm angle) at the nominal length. Rows: Gates "Accessory Belt Drive System"
reports' "Tensioner Geometry" table (tests/belt/test_supplier_report.py).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...core._roots import find_root
from ...core.errors import ModelError
from . import tensioner as TN
from .catalogue import effective_diameters, effective_drive_length, length_offset
from ...mechanics.layout import compute_layout
from ..model import free_arm_angle

ROWS = ("free arm", "replace", "max belt", "mean", "min belt", "load stop")


@dataclass(frozen=True)
class Position:
    name: str
    rel: float                 # arm angle from the free arm, away from the belt (rad)
    angle: float               # absolute arm angle, pivot to pulley centre, from +x CCW (rad)
    travel: float              # drivedyn's travel from the drawn position, into the belt (rad)
    centre: tuple              # pulley centre (m)
    edl: float                 # effective drive length (m)
    rebl: float                # required effective belt length (m)
    wrap: float                # wrap on the tensioner pulley (rad)
    beta: float                # angle between hub load and arm (rad)
    spring_torque: float       # N m
    tension: float             # belt tension the spring holds (N)
    hub_load: float            # N
    hub_direction: float       # direction of the belt's force on the pulley, from +x CCW (rad)


@dataclass(frozen=True)
class PositionTable:
    pulley: str
    rows: tuple                # Position per ROWS entry (None where the arm cannot reach it)
    unreached: dict            # row name -> why it is not in the table
    take_up: float             # d(EDL)/d(arm angle) at the mean position (m/rad)
    design_tension: float      # the tension at the mean position (N)
    offset: float              # belt.length_offset in use (m)
    installed: Position | None = None   # where the part's belt puts the arm: required length = belt.effective_length
    drawn_length: float = math.nan      # the required belt length of the drawn (mean) position (m)


def position_tables(drive) -> list[PositionTable]:
    """One table per arm tensioner with supplier data (arm.free_angle); the belt's nominal length
    (belt.effective_length) sets the rows. Empty without such tensioners."""
    model = drive.model
    arms = [(j, s) for j, s in zip(drive.tensioners, drive.senses)
            if model.pulleys[j].arm is not None and model.pulleys[j].arm.free_angle is not None]
    if not arms:
        return []
    if model.belt.effective_length is None:
        raise ModelError("the tensioner's position table needs the belt's nominal length: belt.effective_length "
                         "(e.g. \"1020 mm\" for an 8PK1020)", field="belt.effective_length")
    d_eff = effective_diameters(model)
    offset = length_offset(model, drive.layout, d_eff)
    return [_table(model, j, s, d_eff, offset) for j, s in arms]


def _table(model, j, s, d_eff, offset) -> PositionTable:
    p = model.pulleys[j]
    arm, belt = p.arm, model.belt
    field = f"pulleys.{j}.arm"
    signed = free_arm_angle(p.center, arm)
    rel_drawn = abs(signed)
    if math.copysign(1.0, signed) != s:
        raise ModelError(f"pulley {p.name!r}: arm.free_angle {math.degrees(arm.free_angle):.4g} deg lies on the side "
                         "that slackens the belt: the free arm is where the spring would swing the pulley with no "
                         "belt on, into the belt's side", field=field + ".free_angle")
    load_stop = arm.load_stop if arm.load_stop is not None else rel_drawn - arm.stops[0]

    def at(rel):
        q = rel_drawn - rel
        c = TN.centre(model, j, q, s)
        lay = compute_layout(TN.with_centres(model, {j: c}))
        return q, c, lay

    def rebl(rel):
        return effective_drive_length(at(rel)[2], d_eff) - offset

    def row(name, rel):
        q, c, lay = at(rel)
        f = lay.hub_load_static(1.0)[j]                      # the belt's force per unit tension
        r = np.array(c) - np.array(arm.pivot)
        lever = abs(r[0] * f[1] - r[1] * f[0])               # a |f| sin(beta)
        M = TN.spring_load(arm, q)
        T = M / lever if lever > 0 else math.inf
        to_pivot = -r
        cosb = float(np.dot(f, to_pivot) / (np.linalg.norm(f) * np.linalg.norm(to_pivot)))
        edl = effective_drive_length(lay, d_eff)
        return Position(name, rel, math.atan2(r[1], r[0]), q, (float(c[0]), float(c[1])), edl, edl - offset,
                        float(lay.wrap[j]), math.acos(max(-1.0, min(1.0, cosb))), M, T, T * float(np.linalg.norm(f)),
                        math.atan2(f[1], f[0]))

    # the rows' belt lengths from the drawn (mean) position's: the reports' rows lie tol, tol + wear
    # and -tol from it whatever their printed offset between drive length and belt length
    tol, wear = belt.length_tolerance, belt.wear_allowance * belt.effective_length
    nominal = rebl(rel_drawn)
    targets = {"replace": nominal + tol + wear, "max belt": nominal + tol, "min belt": nominal - tol}
    fixed = {"free arm": 0.0, "mean": rel_drawn, "load stop": load_stop}      # rows at a known arm angle
    lo_len, hi_len = rebl(load_stop), rebl(0.0)          # the arm's reach in required belt length
    # the belt is the part: the tensioner finds the installed position from its length; a belt the arm
    # cannot hold between its load stop and its free arm (a length_offset of +-60 mm read a required
    # length of 1079.69 mm for a 1020 mm belt) is refused with the arm's reach
    L = belt.effective_length
    if not min(lo_len, hi_len) <= L <= max(lo_len, hi_len):
        where = "beyond the free arm" if L > max(lo_len, hi_len) else "beyond the load stop"
        raise ModelError(f"the {L * 1e3:.2f} mm belt lies {where} of tensioner {p.name!r}: with the offset "
                         f"{offset * 1e3:.2f} mm the arm reaches required belt lengths of {lo_len * 1e3:.2f}-"
                         f"{hi_len * 1e3:.2f} mm (the drawn arm holds {nominal * 1e3:.2f} mm)",
                         field="belt.length_offset" if belt.length_offset else "belt.effective_length")
    rows, unreached = [], {}
    for name in ROWS:
        if name in fixed:
            rows.append(row(name, fixed[name]))
            continue
        target = targets[name]
        if not lo_len <= target <= hi_len:
            where = "beyond the free arm" if target > hi_len else "beyond the load stop"
            why = (f"a required belt length of {target * 1e3:.2f} mm lies {where} (the arm reaches "
                   f"{lo_len * 1e3:.2f}-{hi_len * 1e3:.2f} mm)")
            if name == "replace":
                unreached[name] = why
                rows.append(None)
                continue
            raise ModelError(f"pulley {p.name!r}: the tensioner's travel does not cover the belt's tolerance "
                             f"(belt.length_tolerance +- {tol * 1e3:.1f} mm): for the {name} row {why}", field=field)
        rel = find_root(lambda x: rebl(x) - target, 0.0, load_stop, xtol=1e-12)
        rows.append(row(name, rel))
    mean = rows[ROWS.index("mean")]
    h = 1e-5
    take_up = -(rebl(mean.rel + h) - rebl(mean.rel - h)) / (2 * h)
    # the part: the arm where the required belt length is the belt's effective length
    L = belt.effective_length
    installed = None
    if lo_len <= L <= hi_len:
        installed = row("installed", find_root(lambda x: rebl(x) - L, 0.0, load_stop, xtol=1e-12))
    else:
        unreached["installed"] = (f"the belt's {L * 1e3:.2f} mm lies {'beyond the free arm' if L > hi_len else 'beyond the load stop'}"
                                  f" (the arm reaches {lo_len * 1e3:.2f}-{hi_len * 1e3:.2f} mm of required belt length)")
    return PositionTable(p.name, tuple(rows), unreached, take_up, mean.tension, offset, installed, nominal)
