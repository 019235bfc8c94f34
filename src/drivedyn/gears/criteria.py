"""Design criteria of a gear train (``[criteria]`` of a gear-train model) and their evaluation.

Defaults (docs/criteria.md): no loss of tooth contact at the operating speed (the smallest mesh
force stays above 0: a mesh that separates hammers, and the linear K_v no longer describes it);
the linear model parametrically stable at the operating speed (Floquet growth rate <= 0: an
unstable K_v is whatever the window end reached); no unstable or separating speed range in the
speed sweep, if one was run. K_v itself is judged only against a limit the user gives
(``kv_max``): it enters the rating (ISO 6336-1), whose limits are the rating's.
"""
from __future__ import annotations

import math
from typing import Annotated

from pydantic import Field

from ..core.criteria import Criterion
from ..core.model import Spec, quantity


RPM = 30 / math.pi


class Criteria(Spec):
    """Limits the verdict judges a gear-train run against (every field optional)."""

    kv_max: quantity("1", ge=1) | None = None
    """Largest dynamic factor K_v of any mesh allowed; none: not judged."""
    separation: bool = False
    """Allow loss of tooth contact at the operating speed (false: the smallest mesh force must stay above 0)."""
    stable: bool = True
    """Require the linear model parametrically stable at the operating speed (Floquet growth rate <= 0)."""
    sweep_unstable_ranges_max: Annotated[int, Field(ge=0)] = 0
    """Unstable or separating speed ranges allowed in the sweep."""
    load_sharing_max: quantity("1", ge=1) | None = None
    """Largest planet mesh load factor K_gamma (the most loaded planet's share over the mean one) from the static load
    sharing; none: reported beside the verdict, not judged."""


def evaluate(model, result):
    c = model.criteria
    s = result.summary
    out, skipped = [], {}
    meshes = s.get("meshes", {})
    if c.kv_max is not None and meshes:
        v, n = max((e.get("kv") or 0.0, n) for n, e in meshes.items())
        out.append(Criterion("kv", v, c.kv_max, "1", "max", "largest dynamic factor K_v of any mesh", n))
    elif meshes:
        skipped["kv"] = "no limit given (criteria.kv_max)"
    if not c.separation and meshes:
        v, n = min((e.get("force_min", 0.0), n) for n, e in meshes.items())
        out.append(Criterion("mesh_force_min", v, 0.0, "N", "min",
                             "smallest mesh force at the operating speed (below 0: the teeth separate)", n))
    elif meshes:      # a check switched off is said beside the verdict, never silently passed
        v = min(e.get("force_min", 0.0) for e in meshes.values())
        skipped["mesh_force_min"] = (f"not judged: criteria.separation = true allows loss of tooth contact "
                                     f"(smallest mesh force {v:.4g} N{', the teeth separate' if v < 0 else ''})")
    if c.stable and s.get("floquet_growth_rate") is not None:
        out.append(Criterion("floquet_growth_rate", s["floquet_growth_rate"], 0.0, "1/s", "max",
                             "largest Floquet growth rate of the linear model at the operating speed (> 0: unstable)"))
    elif s.get("floquet_growth_rate") is not None:
        g = s["floquet_growth_rate"]
        skipped["floquet_growth_rate"] = (f"not judged: criteria.stable = false (growth rate {g:.4g} 1/s"
                                          f"{', unstable' if g > 0 else ''})")
    # ISO 6336-2/-3 safety factors (K_v from the dynamic run) against the minimums of [iso]
    for n, r in (s.get("rating") or {}).items():
        for kind, key, what in (("pitting", "S_H", "contact (pitting) safety factor S_H, ISO 6336-2"),
                                ("bending", "S_F", "tooth-root safety factor S_F, ISO 6336-3")):
            v, who = min((r[w + "_rating"][key], r[w]) for w in ("pinion", "wheel"))
            out.append(Criterion(f"{key}_{n}", v, r[f"{key}_min_required"], "1", "min", f"smallest {what}",
                                 f"{n}: {who}"))
    # the planetary stage's meshes (planetary_rating.py): every rated gear of both meshes
    stages = [("planetary", s.get("planetary") or {}), *((s.get("stages") or {}).items())]
    # where, in words: "stage 1", "stage 2", ... in a gearbox, else "planetary"
    shown = {label: (f"stage {k + 1}" if len(stages) > 1 else label) for k, (label, _) in enumerate(stages)}
    for label, n, r, pr in ((label, n, r, st.get("rating") or {}) for label, st in stages
                            for n, r in ((st.get("rating") or {}).get("meshes") or {}).items()):
        for kind, key, what in (("pitting", "S_H", "contact (pitting) safety factor S_H, ISO 6336-2"),
                                ("bending", "S_F", "tooth-root safety factor S_F, ISO 6336-3")):
            rated = [(r[w][key], w) for w in (r["pinion"], r["wheel"]) if r[w].get(key) is not None]
            if rated:
                v, who = min(rated)
                out.append(Criterion(f"{key}_{label}_{n}", v, pr[f"{key}_min_required"], "1", "min",
                                     f"smallest {what} of the {n} mesh of {shown[label]}", f"{shown[label]} {n}: {who}"))
            missing = [w for w in (r["pinion"], r["wheel"]) if r[w].get(key) is None]
            if missing:
                skipped[f"{key}_{label}_{n}_{missing[0]}"] = f"the {missing[0]}'s {key} is not rated ({'; '.join(r['notes'])})"
    for label, st in stages:
        # the lateral-torsional model's load sharing where there is one (as the rating's K_gamma)
        src = st["lateral"] if "load_sharing_factor" in (st.get("lateral") or {}) else st
        kg = src.get("load_sharing_factor")
        if kg is None:
            continue
        share = max(src.get("load_share") or [0.0])
        where = (f"{shown[label]}: the most loaded planet carries {100 * share:.0f} %"
                 + (" (lateral-torsional model)" if src is not st else ""))
        if c.load_sharing_max is not None:
            out.append(Criterion(f"load_sharing_{label}", kg, c.load_sharing_max, "1", "max",
                                 "mesh load factor K_gamma of the planets (the most loaded planet's share over the "
                                 "mean share)", where))
        else:
            skipped[f"load_sharing_{label}"] = f"K_gamma {kg:.3g} ({where}): no limit given (criteria.load_sharing_max)"
    sweep = (s.get("sweep") or {}).get("meshes") or {}
    if sweep:
        ranges = [(n, r) for n, e in sweep.items() for r in (e.get("unstable_speeds", []) + e.get("separation_speeds", []))]
        out.append(Criterion("sweep_unstable_ranges", len(ranges), c.sweep_unstable_ranges_max, "", "max",
                             "unstable or separating speed ranges in the sweep",
                             "; ".join(f"{n} {a * RPM:.0f}-{b * RPM:.0f} rpm" for n, (a, b) in ranges[:4])
                             + (f"; {len(ranges) - 4} more" if len(ranges) > 4 else "")))
    return out, skipped
