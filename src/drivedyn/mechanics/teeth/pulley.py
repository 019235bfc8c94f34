"""The pulley body near the meshing groove, as a shapely polygon in the pulley frame.

Only the groove and two neighbours on each side are built (a sector closed by an inner arc),
which is all a single tooth can reach; small pulleys get the whole outline. A standard groove
comes from its shape (profiles.py); a generated groove is the envelope cut by the belt tooth
used as a rack (the region swept by the tooth over the engagement, kinematics.py), optionally
widened by a clearance.
"""
from __future__ import annotations

import numpy as np
import shapely
import shapely.affinity

from .contour import arc_angles, join, rotate
from .kinematics import first_contact, to_pulley
from .profiles import groove_cell, tooth_outline

NEIGHBOURS = 2


def _sector(outline_left_to_right, r_in, a_right, a_left, tol):
    inner = arc_angles((0.0, 0.0), r_in, a_right, a_left, tol)
    return shapely.Polygon(join(outline_left_to_right, inner))


def pulley_polygon(pair):
    """The pulley body around the groove at +y (shapely Polygon)."""
    z, r_o, tol = pair.teeth, pair.outside_radius, pair.tol
    pitch_angle = 2 * np.pi / z
    full = 2 * NEIGHBOURS + 1 >= z
    ks = range(z) if full else range(-NEIGHBOURS, NEIGHBOURS + 1)
    span = (NEIGHBOURS + 0.5) * pitch_angle
    r_in = max(r_o - 2 * pair.groove_depth - 1e-3, 0.2 * r_o)
    if pair.groove is not None:
        cell = groove_cell(pair.groove, r_o, z, tol)
        outline = join(*[rotate(cell, -k * pitch_angle) for k in ks])
        if full:
            return shapely.Polygon(outline)
        return _sector(outline, r_in, np.pi / 2 - span, np.pi / 2 + span, tol)
    # generated: body without grooves, then cut by the swept tooth
    if full:
        body = shapely.Polygon(arc_angles((0.0, 0.0), r_o, np.pi / 2 + np.pi, np.pi / 2 - np.pi, tol)[:-1])
    else:
        rim = arc_angles((0.0, 0.0), r_o, np.pi / 2 + span, np.pi / 2 - span, tol)
        body = _sector(rim, r_in, np.pi / 2 - span, np.pi / 2 + span, tol)
    cut = generated_cut(pair)
    cuts = [shapely.affinity.rotate(cut, -k * pitch_angle, origin=(0, 0), use_radians=True) for k in ks]
    result = body.difference(shapely.union_all(cuts))
    if result.geom_type != "Polygon":  # keep the body, drop slivers left between cuts
        result = max(result.geoms, key=lambda g: g.area)
    return result


def generated_cut(pair, step=2e-5):
    """Region swept by the belt tooth (as a rack, centred: no offset) through the engagement.

    Poses are spaced ``step`` (m) of belt travel apart; the scallops this leaves are about
    step^2 / (8 rho) deep for a tooth curvature radius rho (0.1 um for 20 um and 0.5 mm).
    """
    uv = tooth_outline(pair.tooth, pair.tol)
    phi_max = first_contact(uv, pair.belt_radius, pair.outside_radius)
    n = int(np.clip(2 * phi_max * pair.belt_radius / step, 50, 5000)) | 1
    pts = to_pulley(uv, np.linspace(-phi_max, phi_max, n), pair.belt_radius)
    cut = shapely.union_all(shapely.polygons(pts))
    if pair.generated_clearance > 0:
        cut = cut.buffer(pair.generated_clearance, quad_segs=32)
    # the union keeps every pose's vertices; dropping those within tol changes the shape by < tol
    return shapely.simplify(cut, pair.tol)
