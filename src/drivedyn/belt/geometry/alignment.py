"""Belt entry (fleeting) angles from the pulleys' axial offsets and angular misalignment.

Each pulley's groove plane sits ``axial_offset`` from the drive's plane and is turned by
``misalignment`` about the in-plane direction ``misalignment_axis``: its normal is
n = e_z cos(a) + (u x e_z) sin(a), u the axis direction. A span runs from its leaving tangent point
to its arriving one, rising by the difference of the two offsets over its length; its angle to a
pulley's groove plane is asin(D . n), D its unit direction. Turning a pulley about the span's own
direction leaves the span in its plane (first order); turning it about the perpendicular direction
tilts the groove against the span by the whole angle. Each pulley's entry angle is the one of the
span arriving at it in the belt's travel, its exit angle the leaving span's; both are reported.
"""
from __future__ import annotations

import math

import numpy as np


def has_alignment(model) -> bool:
    return any(p.axial_offset or p.misalignment for p in model.pulleys)


def entry_angles(model, lay) -> dict:
    """Per pulley: {"arriving": angle of the span arriving in the listed order, "leaving": of the span
    leaving it} (rad, >= 0)."""
    z = [p.axial_offset for p in model.pulleys]
    normals = []
    for p in model.pulleys:
        a, psi = p.misalignment, p.misalignment_axis
        u = np.array([math.cos(psi), math.sin(psi), 0.0])
        normals.append(np.array([0.0, 0.0, math.cos(a)]) + np.cross(u, [0.0, 0.0, 1.0]) * math.sin(a))
    out = {p.name: {} for p in model.pulleys}
    for sp in lay.spans:
        d = np.array([sp.p1[0] - sp.p0[0], sp.p1[1] - sp.p0[1], z[sp.end] - z[sp.start]])
        d /= np.linalg.norm(d)
        out[model.pulleys[sp.start].name]["leaving"] = abs(math.asin(float(np.clip(d @ normals[sp.start], -1, 1))))
        out[model.pulleys[sp.end].name]["arriving"] = abs(math.asin(float(np.clip(d @ normals[sp.end], -1, 1))))
    return out
