"""Interference of a belt tooth and the pulley per angle, vectorised with shapely 2.

For every angle phi:

- overlap area: area of (tooth polygon) intersected with (pulley body) (the seed's criterion);
- penetration: at each vertex of the overlap, the larger of its distance to the pulley boundary
  (a tooth point pushed into the pulley) and to the tooth flank (a pulley corner pushed into the
  tooth); the maximum over the vertices is the penetration depth, located on the flank by the
  nearest flank point (leading flank u > 0, trailing u < 0);
- signed distance of every flank sample to the pulley boundary (negative inside): its minimum
  per flank is the clearance where there is no overlap, and its negative part per sample is the
  flank colour map.

The tooth polygon is closed by its land; the belt body above the land is not part of it (its
land is tangent to the outside circle when seated, so it cannot overlap the rim there).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

from .kinematics import to_pulley


@dataclass
class Flank:
    """The tooth contour (belt frame) densified, with its arc length and flank sides."""

    uv: np.ndarray  # (m, 2)
    s: np.ndarray  # arc length from the trailing land end
    lead: np.ndarray  # bool, u > 0

    @classmethod
    def from_outline(cls, outline, spacing):
        seg = np.diff(outline, axis=0)
        length = np.hypot(seg[:, 0], seg[:, 1])
        n = np.maximum(np.ceil(length / spacing).astype(int), 1)
        # straight pieces get intermediate points too, so the colour map is resolved everywhere
        parts = [outline[i] + seg[i] * np.arange(n[i])[:, None] / n[i] for i in range(len(seg))]
        uv = np.vstack(parts + [outline[-1:]])
        d = np.hypot(*np.diff(uv, axis=0).T)
        s = np.concatenate([[0.0], np.cumsum(d)])
        return cls(uv=uv, s=s, lead=uv[:, 0] > 0)


def evaluate(flank: Flank, pulley, phi, belt_radius, offset, land, margin=1e-3):
    """Interference arrays over the angles ``phi`` (see the module docstring).

    Clearances larger than about ``margin`` (m) may come out as +inf (nothing searched that far).
    """
    n, m = len(phi), len(flank.uv)
    pts = to_pulley(flank.uv, phi, belt_radius, offset)  # (n, m, 2)
    closed = np.concatenate([pts, pts[:, :1]], axis=1)
    teeth = shapely.polygons(closed)
    shapely.prepare(pulley)
    overlap = shapely.intersection(teeth, pulley)
    area = shapely.area(overlap)

    boundary = pulley.exterior
    segs = np.asarray(boundary.coords)
    tree = shapely.STRtree(shapely.linestrings(np.stack([segs[:-1], segs[1:]], axis=1)))

    # signed distance of every flank sample to the pulley boundary (compiled: many points)
    from ._kernels import nearest_distance

    flat = pts.reshape(-1, 2)
    dist_all = nearest_distance(np.ascontiguousarray(pts), np.ascontiguousarray(segs[:-1]),
                                np.ascontiguousarray(segs[1:]), margin)
    inside = shapely.contains_xy(pulley, flat[:, 0], flat[:, 1]).reshape(n, m)
    signed = np.where(inside, -dist_all, dist_all)
    depth_map = np.clip(-signed, 0, None)

    def side_min(mask):
        sd = signed[:, mask]
        low = sd.min(axis=1)
        return np.where(low < 0, 0.0, np.where(np.isfinite(low), low, np.nan))

    clear_lead, clear_trail = side_min(flank.lead), side_min(~flank.lead)

    # penetration from the overlap vertices
    coords, which = shapely.get_coordinates(overlap, return_index=True)
    pen = {k: np.zeros(n) for k in ("all", "lead", "trail")}
    loc = {k: np.full(n, np.nan) for k in ("all", "lead", "trail")}
    if len(coords):
        vp = shapely.points(coords)
        (vi, _), dp = tree.query_nearest(vp, return_distance=True, all_matches=False)
        d_p = np.empty(len(coords))
        d_p[vi] = dp
        # (compiled: GEOS's distance and line_locate_point took 3.7 of a 6 s map of 25 pairs)
        from ._kernels import on_polyline

        d_t, s_at = on_polyline(np.ascontiguousarray(pts), which.astype(np.int64), np.ascontiguousarray(coords))
        depth = np.maximum(d_p, d_t)
        u_at = np.interp(s_at, flank.s, flank.uv[:, 0])
        below = land - np.interp(s_at, flank.s, flank.uv[:, 1])  # depth below the land
        for key, mask in (("all", np.ones(len(coords), bool)), ("lead", u_at > 0), ("trail", u_at <= 0)):
            if not mask.any():
                continue
            w, d, b = which[mask], depth[mask], below[mask]
            order = np.lexsort((d, w))  # by angle, then depth: the last of each angle is its max
            w, d, b = w[order], d[order], b[order]
            last = np.r_[w[1:] != w[:-1], True]
            pen[key][w[last]] = d[last]
            loc[key][w[last]] = b[last]
        # the colour map also takes the pulley corners pushed into the tooth
        k = np.clip(np.searchsorted(flank.s, s_at), 0, m - 1)
        np.maximum.at(depth_map, (which, k), depth)
    return dict(area=area, penetration=pen["all"], penetration_leading=pen["lead"],
                penetration_trailing=pen["trail"], location=loc["all"], location_leading=loc["lead"],
                location_trailing=loc["trail"], clearance=np.minimum(clear_lead, clear_trail),
                clearance_leading=clear_lead, clearance_trailing=clear_trail, depth_map=depth_map,
                signed=signed, overlap=overlap)
