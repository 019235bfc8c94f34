"""The belt's resolution: how many segments (``belt.segments = "auto"``, the default) and what the
discretisation leaves in the numbers a run reports.

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

"auto" takes the longest segment that puts WRAP_SEGMENTS on the shortest wrap and is at most
CHORD_RATIO of the smallest radius, with MIN_SEGMENTS at least.
"""
from __future__ import annotations

import math

from ..errors import ModelError
from .layout import compute_layout

#: segments on the shortest wrap (the wrap-resolution rule above)
WRAP_SEGMENTS = 6
#: largest segment length against the smallest pulley radius (chordal speed error 0.75 % before
#: the rolling-radius correction, impacts of entering segments small)
CHORD_RATIO = 0.3
MIN_SEGMENTS = 60
#: wraps shorter than this (deg) are left out of the wrap rule: a 7-degree idler wrap would ask for
#: 3000 segments and carries almost no torque; discretisation.unresolved_wraps names them
WRAP_MIN_DEG = 20.0
#: "auto" never picks more (the semi-implicit scheme's cost grows as n^2)
MAX_AUTO = 2000


def auto_segments(model, layout=None) -> tuple[int, str]:
    """The number of segments "auto" picks for ``model``, and the rule that set it."""
    lay = layout or compute_layout(model)
    radii = [p.radius for p in model.pulleys]
    arcs = [w * r if math.degrees(w) >= WRAP_MIN_DEG else math.inf for w, r in zip(lay.wrap, radii)]
    j = min(range(len(arcs)), key=arcs.__getitem__)
    k = min(range(len(radii)), key=radii.__getitem__)
    by_wrap, by_chord = arcs[j] / WRAP_SEGMENTS, CHORD_RATIO * radii[k]
    if by_wrap <= by_chord:
        l, why = by_wrap, (f"{WRAP_SEGMENTS} segments on the shortest wrap ({model.pulleys[j].name}, "
                           f"{math.degrees(lay.wrap[j]):.0f} deg on {radii[j] * 1e3:.3g} mm)")
    else:
        l, why = by_chord, f"segments at most {CHORD_RATIO:g} x the smallest radius ({model.pulleys[k].name}, {radii[k] * 1e3:.3g} mm)"
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


def discretisation(model, sysm) -> dict:
    """What the summary reports of the resolution: segments, their length, the rule, the
    segments on each wrap's shortest and the polygon's speed error (taken out of slip)."""
    lay, l = sysm.layout, sysm.init.seg_length
    resolved_ = [j for j in range(len(model.pulleys)) if math.degrees(lay.wrap[j]) >= WRAP_MIN_DEG]
    per_wrap = {model.pulleys[j].name: float(lay.wrap[j] * model.pulleys[j].radius / l) for j in resolved_}
    short = min(per_wrap, key=per_wrap.get) if per_wrap else None
    r_min = min(p.radius for p in model.pulleys)
    rule = auto_segments(model, lay)[1] if model.belt.segments == "auto" else "given (belt.segments)"
    return {"segments": int(sysm.n), "segment_length": float(l), "rule": rule,
            "shortest_wrap": short, "segments_on_shortest_wrap": per_wrap[short] if short else None,
            "unresolved_wraps": {p.name: float(math.degrees(lay.wrap[j])) for j, p in enumerate(model.pulleys)
                                 if j not in resolved_},
            "chordal_speed_error": float(l * l / (12 * r_min * r_min)),
            "slip_measured_against": "the chain's rolling radius (polygon effect removed)"}
