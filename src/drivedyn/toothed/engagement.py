"""One full engagement (entry, seating, exit) of a pair, and the run that assembles the Result."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..mechanics.teeth.interference import Flank, evaluate
from ..mechanics.teeth.kinematics import first_contact
from ..mechanics.teeth.pair import Pair, resolve, resolve_row
from ..mechanics.teeth.profiles import tooth_outline
from ..mechanics.teeth.pulley import pulley_polygon


@dataclass
class Sweep:
    """A pair's engagement: angles, contours and the interference arrays of interference.evaluate."""

    pair: Pair
    phi: np.ndarray
    flank: Flank
    pulley: object
    out: dict
    seated: dict


def sweep(pair: Pair, n_angles: int, half_range=None) -> Sweep:
    """Evaluate ``pair`` at ``n_angles`` angles symmetric about full seating (phi = 0)."""
    flank = Flank.from_outline(tooth_outline(pair.tooth, pair.tol), pair.spacing)
    pulley = pulley_polygon(pair)
    if half_range is None:
        half_range = first_contact(flank.uv, pair.belt_radius, pair.outside_radius, pair.offset)
    phi = np.linspace(-half_range, half_range, n_angles)
    out = evaluate(flank, pulley, phi, pair.belt_radius, pair.offset, pair.tooth.land)
    seated = evaluate(flank, pulley, np.array([0.0]), pair.belt_radius, pair.offset, pair.tooth.land)
    return Sweep(pair, phi, flank, pulley, out, seated)


def headline(sw: Sweep) -> dict:
    """The summary numbers of one sweep (mm and degrees, as named)."""
    o, s, pair = sw.out, sw.seated, sw.pair
    tip = int(np.argmin(np.abs(sw.flank.uv[:, 0]) + (sw.flank.uv[:, 1] - pair.tooth.tip) ** 2 * 1e6))

    def flank(key):
        pen = o[f"penetration_{key}"]
        i = int(np.argmax(pen))
        hit = pen[i] > 0
        return {"max_penetration_mm": 1e3 * pen[i],
                "location_below_land_mm": 1e3 * o[f"location_{key}"][i] if hit else None,
                "angle_deg": float(np.degrees(sw.phi[i])) if hit else None,
                "seated_clearance_mm": 1e3 * s[f"clearance_{key}"][0]}

    i = int(np.argmax(o["penetration"]))
    # smallest gap while the tooth moves (0 where it overlaps): for a pair that never touches,
    # how close it comes, which can be well below the seated clearance (L z20: 0.106 vs 0.161 mm)
    gap = np.where(np.isfinite(o["clearance"]), o["clearance"], np.inf)
    k = int(np.argmin(gap))
    return {
        "max_overlap_area_mm2": 1e6 * float(o["area"].max()),
        "max_penetration_mm": 1e3 * float(o["penetration"][i]),
        "angle_of_max_penetration_deg": float(np.degrees(sw.phi[i])) if o["penetration"][i] > 0 else None,
        "flanks": {"leading": flank("leading"), "trailing": flank("trailing")},
        "seated": {"overlap_area_mm2": 1e6 * float(s["area"][0]),
                   "tip_clearance_mm": 1e3 * float(s["signed"][0, tip]),
                   "clearance_mm": 1e3 * float(s["clearance"][0])},
        "groove_depth_used": pair.tooth.height / pair.groove_depth,
        "engagement": {"min_clearance_mm": 1e3 * float(gap[k]) if np.isfinite(gap[k]) else None,
                       "angle_deg": float(np.degrees(sw.phi[k])) if np.isfinite(gap[k]) else None},
    }


def geometry(pair: Pair) -> dict:
    """The pair's geometry numbers (mm)."""
    t = pair.tooth
    return {"belt_profile": t.name, "pulley_profile": pair.groove.name if pair.groove is not None else "generated",
            "teeth": pair.teeth, "belt_pitch_mm": 1e3 * t.pitch, "pulley_pitch_mm": 1e3 * pair.pulley_pitch,
            "pitch_radius_mm": 1e3 * pair.pitch_radius, "outside_radius_mm": 1e3 * pair.outside_radius,
            "belt_pitch_line_radius_mm": 1e3 * pair.belt_radius, "pitch_error_mm": 1e3 * pair.pitch_error,
            "tooth_offset_mm": 1e3 * pair.offset, "tooth_height_mm": 1e3 * t.height,
            "groove_depth_mm": 1e3 * pair.groove_depth, "belt_pld_mm": 1e3 * t.pld,
            "pulley_pld_mm": 1e3 * pair.pulley_pld, "tooth_source": t.source,
            "groove_source": pair.groove.source if pair.groove is not None else "envelope of the belt tooth as a rack"}


def comparison(model, progress=None) -> list[dict]:
    """Rows of the comparison table: the model's pair first, then ``model.compare``."""
    rows = []
    n = min(model.mesh.angles, 121)
    pairs = [resolve(model)] + [resolve_row(r, model.mesh) for r in model.compare]
    for k, pair in enumerate(pairs):
        h = headline(sweep(pair, n))
        g = geometry(pair)
        rows.append({"label": pair.label or "model", "belt": g["belt_profile"], "pulley": g["pulley_profile"],
                     "teeth": pair.teeth, "pitch_error_mm": g["pitch_error_mm"],
                     "max_overlap_area_mm2": h["max_overlap_area_mm2"], "max_penetration_mm": h["max_penetration_mm"],
                     "leading_max_penetration_mm": float(h["flanks"]["leading"]["max_penetration_mm"]),
                     "trailing_max_penetration_mm": float(h["flanks"]["trailing"]["max_penetration_mm"]),
                     "seated_tip_clearance_mm": h["seated"]["tip_clearance_mm"],
                     "seated_clearance_mm": h["seated"]["clearance_mm"],
                     "min_clearance_mm": h["engagement"]["min_clearance_mm"],
                     "groove_depth_used": h["groove_depth_used"]})
        if progress:
            progress(0.5 + 0.2 * (k + 1) / len(pairs), f"compare {pair.label}")
    return rows


def maps(model, progress=None):
    """Maximum overlap area (m^2) and penetration (m) over tooth counts x pitch errors."""
    m = model.maps
    area = np.zeros((len(m.teeth), len(m.pitch_error)))
    pen = np.zeros_like(area)
    for i, z in enumerate(m.teeth):
        for j, e in enumerate(m.pitch_error):
            o = sweep(resolve(model, teeth=z, offset=e), m.angles).out
            area[i, j], pen[i, j] = o["area"].max(), o["penetration"].max()
        if progress:
            progress(0.7 + 0.3 * (i + 1) / len(m.teeth), f"map z = {z}")
    return area, pen
