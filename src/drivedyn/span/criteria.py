"""Design criteria of a span (``[criteria]`` of a span-stability model) and their evaluation.

Defaults (docs/criteria.md): belt speed at most half the span's critical speed (there the first
natural frequency of the moving span has fallen by a quarter, (1 - V^2/c^2) = 0.75, and the
span's transverse stiffness with it); the operating speed at least 5 % away from the nearest
parametric-resonance region (tongue) of the span, and not in one.
"""
from __future__ import annotations

from ..core.criteria import Criterion
from ..core.model import Spec, limit, quantity


class Criteria(Spec):
    """Limits the verdict judges a span against (every field optional)."""

    critical_speed_ratio_max: quantity("1", gt=0, le=1) = 0.5
    """Largest belt speed over the span's critical speed allowed (0.5: the first natural frequency has fallen by a
    quarter there)."""
    tongue_distance_min: limit("1", "0 can never fail: the distance is 0 inside a tongue", gt=0) = 0.05
    """Smallest distance of the operating speed to the nearest parametric-resonance region (tongue), a share of the
    speed (0: inside one)."""


def evaluate(model, result):
    c = model.criteria
    s = result.summary
    out, skipped = [], {}
    V, vcr = s.get("speed"), s.get("v_critical")
    if V is not None and vcr:
        out.append(Criterion("critical_speed_ratio", abs(V) / vcr, c.critical_speed_ratio_max, "1", "max",
                             "belt speed over the span's critical speed"))
    bands = s.get("tongue_bands") or s.get("resonance_bands") or []
    if V is not None and bands and V == 0:
        skipped["tongue_distance"] = "the belt stands still: no parametric excitation"
    elif V is not None and bands:
        d, where = min(((0.0 if a <= V <= b else min(abs(V - a), abs(V - b)) / abs(V), f"{a:.4g}-{b:.4g} m/s")
                        for a, b in bands), key=lambda x: x[0])
        out.append(Criterion("tongue_distance", d, c.tongue_distance_min, "1", "min",
                             "distance of the belt speed to the nearest parametric-resonance region, share of the "
                             "speed (0: inside)", where))
    return out, skipped
