"""A drive with non-circular pitch curves (``pulleys[].pitch_curve``) over a turn: the belt length, span
lengths, wraps and effective radii against the crank's angle (mechanics/curve_turn.py on the centres
``check`` lays the belt on), their ranges and dominant orders, as ``drivedyn check`` reports them.

The pulley turned is the crank (the one with a prescribed speed), else the first non-circular one; the
others turn with it at their mean speed ratios (teeth x pitch on toothed pulleys, else the curves'
perimeters), over as many of its turns as make every non-circular curve turn whole turns. The rotational
model (rotational/curves.py) and the segment model (segments/_curves.py) drive friction and timing belts
through the curves.
"""
from __future__ import annotations

import math

import numpy as np

from ...mechanics.curve_turn import over_a_turn, ratios_of, whole_turns

#: positions per turn of the turned pulley (2 deg: the order content up to order 90)
POINTS = 180
#: below this amplitude (m, rad) a quantity is reported as unchanged over the turn (round-off)
FLAT = 1e-10


def wanted(model) -> bool:
    return any(p.pitch_curve is not None for p in model.pulleys)


def turned_pulley(model) -> int:
    for k, p in enumerate(model.pulleys):
        if p.speed_time is not None:
            return k
    return next(k for k, p in enumerate(model.pulleys) if p.pitch_curve is not None)


def turn_of(model, centers=None, points: int = POINTS):
    """mechanics.curve_turn.Turn of the model's drive (its centres as drawn unless given)."""
    ps = model.pulleys
    names = [p.name for p in ps]
    centers = np.array([p.center for p in ps], float) if centers is None else np.asarray(centers, float)
    curves = [p.curve for p in ps]
    sides = [p.side for p in ps]
    k = turned_pulley(model)
    lengths = None
    if model.belt.teeth is not None:
        from ...mechanics.teeth import catalogue

        pitch = catalogue.entry(model.belt.teeth.profile).pitch
        lengths = [p.teeth * pitch if p.teeth else c.perimeter for p, c in zip(ps, curves)]
    rat = ratios_of(curves, sides, centers, k, lengths)
    turns = whole_turns(curves, rat, k)
    return over_a_turn(names, centers, curves, sides, pulley=k, ratios=rat, points=points, turns=turns)


def _stats(turn, values) -> dict:
    values = np.asarray(values, float)
    order, amp = turn.dominant(values)
    if amp < FLAT:       # a quantity the curves leave unchanged: no order to name
        order, amp = None, 0.0
    return {"min": float(values.min()), "max": float(values.max()), "mean": float(values.mean()),
            "order": order, "amplitude": amp}


def turn_data(model, centers=None) -> dict:
    """check_data's "pitch_curves": the ranges over the turn (SI: m, rad)."""
    turn = turn_of(model, centers)
    ps = model.pulleys
    k = turn.pulley
    ratios = turn.angles[1] / turn.angles[1, k] if len(turn.theta) > 1 else np.ones(len(ps))
    return {
        "pulley": ps[k].name, "turns": turn.turns, "positions": len(turn.theta),
        "curves": {p.name: {"kind": p.pitch_curve.kind, "perimeter": p.curve.perimeter,
                            "radius_min": p.curve.min_radius, "radius_max": p.curve.max_radius,
                            "ratio": float(ratios[j])}
                   for j, p in enumerate(ps) if p.pitch_curve is not None},
        "belt_length": _stats(turn, turn.length),
        "spans": {name: _stats(turn, turn.spans[:, i]) for i, name in enumerate(turn.span_names)},
        "pulleys": {p.name: {"wrap": _stats(turn, turn.wrap[:, j]), "radius_in": _stats(turn, turn.radius_in[:, j]),
                             "radius_out": _stats(turn, turn.radius_out[:, j])}
                    for j, p in enumerate(ps)},
    }


def turn_lines(data: dict) -> list:
    """check's text of turn_data."""
    mm = 1e3
    turns = data["turns"]
    over = "one turn" if turns == 1 else f"{turns} turns"
    out = [f"pitch curves over {over} of {data['pulley']} ({data['positions']} positions, the others at their mean "
           "speed ratios; mechanics/curve_layout.py):"]
    for name, c in data["curves"].items():
        out.append(f"  {name}: {c['kind']}, radius {c['radius_min'] * mm:.3f}-{c['radius_max'] * mm:.3f} mm, "
                   f"perimeter {c['perimeter'] * mm:.3f} mm, {c['ratio']:+.4g} turns per turn of {data['pulley']}")
    L = data["belt_length"]
    largest = ("" if L["order"] is None else
               f", largest order {L['order']:g} of {data['pulley']}, amplitude {L['amplitude'] * mm:.4f} mm")
    out.append(f"  belt path length {L['min'] * mm:.3f}-{L['max'] * mm:.3f} mm (range {(L['max'] - L['min']) * mm:.4f} mm"
               f"{largest})")
    out.append(f"  {'span':24s} {'min mm':>9s} {'max mm':>9s} {'range mm':>9s} {'order':>6s} {'ampl. mm':>9s}")
    for name, s in data["spans"].items():
        order = "-" if s["order"] is None else f"{s['order']:g}"
        out.append(f"  {name:24s} {s['min'] * mm:9.3f} {s['max'] * mm:9.3f} {(s['max'] - s['min']) * mm:9.4f} "
                   f"{order:>6s} {s['amplitude'] * mm:9.4f}")
    out.append(f"  {'pulley':14s} {'wrap deg':>15s} {'r_eff in mm':>17s} {'r_eff out mm':>17s}")
    for name, p in data["pulleys"].items():
        w, ri, ro = p["wrap"], p["radius_in"], p["radius_out"]
        out.append(f"  {name:14s} {math.degrees(w['min']):7.2f}-{math.degrees(w['max']):<7.2f} "
                   f"{ri['min'] * mm:8.3f}-{ri['max'] * mm:<8.3f} {ro['min'] * mm:8.3f}-{ro['max'] * mm:<8.3f}")
    out.append("  (r_eff: the span's distance from the pulley's centre where the belt arrives and leaves.) Both dynamic "
               "models (simulation.model = \"segments\", \"rotational\") drive the belt on the turning curves.")
    return out
