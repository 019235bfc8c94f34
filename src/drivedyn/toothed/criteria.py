"""Design criteria of a timing-belt mesh (``[criteria]`` of a toothed-mesh model).

Defaults (docs/criteria.md), judged when the model has a ``[load]`` section: the jump torque at
least 1.5 times the transmitted torque (the rigid-tooth jump criterion of mechanics/teeth/loadshare.py
ignores tooth deflection, so real belts jump earlier), and at least 6 teeth in mesh (the usual
rule of timing-belt catalogues: fewer teeth carry the load with too little reserve against
jumping and wear).
"""
from __future__ import annotations

from typing import Annotated

from pydantic import Field

from ..core.criteria import Criterion
from ..core.model import Spec, limit


class Criteria(Spec):
    """Limits the verdict judges a mesh under load against (every field optional)."""

    jump_margin_min: limit("1", "below 1 it accepts a torque past the one that jumps the belt", ge=1) = 1.5
    """Smallest jump torque over the transmitted torque allowed."""
    teeth_in_mesh_min: Annotated[int, Field(ge=1)] = 6
    """Fewest teeth in mesh on the pulley allowed (timing-belt catalogues ask for 6)."""


def evaluate(model, result):
    c = model.criteria
    ld = result.summary.get("load")
    out, skipped = [], {}
    if not ld:
        return out, {"jump_margin": "no [load] section", "teeth_in_mesh": "no [load] section"}
    torque = ld.get("torque_N_m")
    if ld.get("jump_torque_N_m") is not None and torque:
        out.append(Criterion("jump_margin", ld["jump_torque_N_m"] / abs(torque), c.jump_margin_min, "1", "min",
                             "jump torque over the transmitted torque"))
    if ld.get("teeth_in_mesh") is not None:
        out.append(Criterion("teeth_in_mesh", ld["teeth_in_mesh"], c.teeth_in_mesh_min, "", "min",
                             "teeth in mesh on the pulley"))
    return out, skipped
