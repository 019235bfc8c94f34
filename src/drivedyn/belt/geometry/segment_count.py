"""How many segments the belt is cut into (``belt.segments = "auto"``, the default), and why: what
the discretisation leaves in the numbers a run reports (segments/resolution.py states it in each run).

A chain of rigid segments of length l differs from the belt it stands for in two ways that reach
slip and span tension (tests/belt/test_resolution.py measures both against refined runs):

- polygon kinematics: the chain rolls on a pulley of radius r at about r (1 + l^2 / (12 r^2)).
  Slip is measured against the chain's own rolling radius (system.BeltSystem.rolling_radius), so
  this mean effect is no longer read as slip; what is left is the chordal impacts of segments
  entering and leaving the pulley, small while l is well below r.
- wrap resolution: a wrap holding few segments has its creep, its contact pressure and the span
  tensions at its ends sampled by those few. On the six-pulley accessory drive of
  examples/fead-runup.toml at 3000 rpm, the 45-degree tensioner wrap misreads its slip by 0.25
  points with 2.8 segments on it and by 0.004 with 5.6; the crank span's tension band is 10 %
  narrow at 150 segments against 600 (3 % at 300).

- chordal landing: a segment wrapped on a pulley of radius r stands off the circle by its chord
  sag l^2 / (8 r) at its ends, and each landing segment drops that far into the contact at the
  polygon frequency v / l. Where the sag is not small against the depth p to which the belt's
  tension presses it into the groove (contact pressure T / r, placement.penetration), landings shake
  the contact, the wraps carry their load in bursts and the drive's response at the engine orders
  is off by several per cent, converging only once the sag is a fraction of p. Measured on
  examples/fead-runup.toml's drive held at 3000 rpm with its orders (benchmarks/
  bench_fead_convergence.py): at sag / depth 0.87 (330 segments) span minima up to 9 % off 1320
  segments; at 0.25 (666) within 2.8 % of 1332 but one (4.5 %; with the tensioner arm held, or the
  alternator's one-way clutch replaced by a rigid rotor, every minimum within 1.7-1.9 % at
  660-666). A two-pulley drive's torsional mode, measured while running, is 3.3 % low at 4 m/s
  and 14 % low at 24 m/s at sag / depth 1.07, within 0.7 % at 0.27.

- the friction law decides how much of the landing must be resolved (the elastic-plastic law is
  the default): with Threlfall's law a
  landing segment slides at once (docs/belt-drive.md, "Friction's radius"), with the elastic-plastic
  law its pre-sliding displacement takes the landing up. The same drive with the elastic-plastic
  law at sag / depth 1.0 (333 segments) is within 2.0 / 2.8 / 3.2 % (span minima), 0.5 / 1.3 /
  2.4 % (maxima) and 0.016 / 0.003 / 0.007 points (slips) of 1332 segments at 1000 / 3000 / 5000
  rpm, where Threlfall's law at that sag is up to 9.4 % off.

"auto" takes the longest segment that puts WRAP_SEGMENTS on the shortest wrap, is at most
CHORD_RATIO of the smallest radius and whose chord sag is at most the friction law's sag ratio
(SAG_RATIO, SAG_RATIO_PRESLIDING) of the contact depth at the pretension on every pulley, with
MIN_SEGMENTS at least.
"""
from __future__ import annotations

import math

from ...core.errors import ModelError
from ..model import MAX_AUTO
from ...mechanics.layout import compute_layout
from .placement import penetration

#: segments on the shortest wrap (the wrap-resolution rule above)
WRAP_SEGMENTS = 6
#: largest segment length against the smallest pulley radius (chordal speed error 0.75 % before
#: the rolling-radius correction, impacts of entering segments small)
CHORD_RATIO = 0.3
MIN_SEGMENTS = 60
#: largest chord sag l^2 / (8 r) against the contact depth at the pretension (the chordal rule above)
SAG_RATIO = 0.25
#: ... with the elastic-plastic friction law, whose pre-sliding takes up the landings
SAG_RATIO_PRESLIDING = 1.0
#: wraps shorter than this (deg) are left out of the wrap rule: a 7-degree idler wrap would ask for
#: 3000 segments and carries almost no torque; discretisation.unresolved_wraps names them
WRAP_MIN_DEG = 20.0


def depths(model, layout) -> list[float]:
    """Per pulley, the contact depth p (m) at the pressure T / r of the belt's tension at rest: the
    pretension, or for a given unstretched length the tension stretching it over the drawn path
    (0 for a slack belt)."""
    T = model.belt.pretension
    if T is None:
        T = max(0.0, model.belt.axial_stiffness * (layout.length / model.belt.length - 1.0))
    c = model.contact
    return [float(penetration(T / p.radius, c.stiffness_quadratic, c.stiffness_linear)) for p in model.pulleys]


def chord_sag(model, layout, l) -> float:
    """The largest chord sag l^2 / (8 r) of segments of length l against the contact depth at rest
    over the pulleys (inf where the belt is slack)."""
    return max(l * l / (8.0 * p.radius * d) if d > 0 else math.inf for p, d in zip(model.pulleys, depths(model, layout)))


def sag_ratio(model) -> float:
    """The largest chord sag against the contact depth "auto" allows with the model's friction law."""
    return SAG_RATIO_PRESLIDING if model.friction.law == "elastic-plastic" else SAG_RATIO


def auto_segments(model, layout=None) -> tuple[int, str]:
    """The number of segments "auto" picks for ``model``, and the rule that set it."""
    lay = layout or compute_layout(model)
    if model.belt.teeth is not None:
        from .teeth import belt_teeth

        bt = belt_teeth(model, lay.length)
        return bt.count * bt.nodes, f"{bt.count} teeth ({bt.count_source}) x {bt.nodes} segment(s) per tooth"
    radii = [p.radius for p in model.pulleys]
    arcs = [w * r if math.degrees(w) >= WRAP_MIN_DEG else math.inf for w, r in zip(lay.wrap, radii)]
    j = min(range(len(arcs)), key=arcs.__getitem__)
    k = min(range(len(radii)), key=radii.__getitem__)
    ratio = sag_ratio(model)
    sags = [math.sqrt(ratio * 8.0 * r * d) if d > 0 else math.inf for r, d in zip(radii, depths(model, lay))]
    q = min(range(len(sags)), key=sags.__getitem__)
    rules = [(arcs[j] / WRAP_SEGMENTS, f"{WRAP_SEGMENTS} segments on the shortest wrap ({model.pulleys[j].name}, "
                                       f"{math.degrees(lay.wrap[j]):.0f} deg on {radii[j] * 1e3:.3g} mm)"),
             (CHORD_RATIO * radii[k], f"segments at most {CHORD_RATIO:g} x the smallest radius ({model.pulleys[k].name}, "
                                      f"{radii[k] * 1e3:.3g} mm)"),
             (sags[q], f"chord sag at most {ratio:g} x the contact depth at rest ({model.pulleys[q].name}, "
                       f"{radii[q] * 1e3:.3g} mm)")]
    l, why = min(rules, key=lambda rule: rule[0])
    n = max(MIN_SEGMENTS, math.ceil(lay.length / l))
    if n > MAX_AUTO:
        raise ModelError(f"\"auto\" would need {n} segments ({why}), over the {MAX_AUTO} it may pick: give "
                         "belt.segments as a number", field="belt.segments")
    return n, why


def resolved(model):
    """``model`` with ``belt.segments`` a number ("auto" resolved); itself when it already is one."""
    if model.belt.segments != "auto":
        return model
    n, _ = auto_segments(model)
    for q in model.output.segments:
        if not 0 <= q < n:
            raise ModelError(f"index {q} outside 0..{n - 1} (belt.segments \"auto\" picks {n})", field="output.segments")
    return model.model_copy(update={"belt": model.belt.model_copy(update={"segments": n})})
