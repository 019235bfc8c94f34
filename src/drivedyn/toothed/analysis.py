"""``run(model)``: the engagement of the model's pair, comparison table and maps, as a Result."""
from __future__ import annotations

import numpy as np
import xarray as xr

from ..core.model import dumps
from ..core.results import Result, unit_map, variable
from .engagement import comparison, geometry, headline, maps, sweep
from ..mechanics.teeth.pair import resolve


#: units of the summary keys: the keys carry their unit as a suffix (summary.json keeps mm and deg)
UNITS = {"*_mm2": "mm^2", "*_mm": "mm", "*_deg": "deg", "*groove_depth_used": "1", "*_N_m": "N*m", "*_N": "N",
         "*_N_per_m": "N/m", "load.first_tooth_share": "1", "load.land_share": "1", "load.friction": "1"}


def run(model, progress=None) -> Result:
    """Compute the engagement of ``model`` (see the package docstring) and return its Result."""
    pair = resolve(model)
    if progress:
        progress(0.0, "engagement")
    sw = sweep(pair, model.mesh.angles, model.mesh.half_range)
    o = sw.out
    if progress:
        progress(0.5, "comparison")
    a, p = ("angle",), ("point",)
    data = {
        "overlap_area": variable(o["area"], a, "m2", "overlap area of belt tooth and pulley"),
        "penetration": variable(o["penetration"], a, "m", "maximum penetration depth"),
        "penetration_leading": variable(o["penetration_leading"], a, "m", "maximum penetration, leading flank"),
        "penetration_trailing": variable(o["penetration_trailing"], a, "m", "maximum penetration, trailing flank"),
        "location_leading": variable(o["location_leading"], a, "m", "depth below the land of the leading maximum"),
        "location_trailing": variable(o["location_trailing"], a, "m", "depth below the land of the trailing maximum"),
        "clearance": variable(o["clearance"], a, "m", "smallest tooth-pulley clearance (0 with overlap)"),
        "clearance_leading": variable(o["clearance_leading"], a, "m", "clearance of the leading flank"),
        "clearance_trailing": variable(o["clearance_trailing"], a, "m", "clearance of the trailing flank"),
        "flank_depth": variable(o["depth_map"], ("angle", "point"), "m", "penetration along the tooth contour"),
        "tooth_u": variable(sw.flank.uv[:, 0], p, "m", "tooth contour, along the belt (leading > 0)"),
        "tooth_v": variable(sw.flank.uv[:, 1], p, "m", "tooth contour, from the pitch line to the belt back"),
        "tooth_s": variable(sw.flank.s, p, "m", "arc length along the tooth contour from the trailing land"),
    }
    ring = np.asarray(sw.pulley.exterior.coords)
    data["pulley_x"] = variable(ring[:, 0], ("pulley_point",), "m", "pulley outline near the groove, x")
    data["pulley_y"] = variable(ring[:, 1], ("pulley_point",), "m", "pulley outline near the groove, y (groove axis)")
    rows = comparison(model, progress)
    pairs = [r["label"] for r in rows]
    data["compare_max_overlap_area"] = variable(1e-6 * np.array([r["max_overlap_area_mm2"] for r in rows]),
                                                ("pair",), "m2", "maximum overlap area")
    data["compare_max_penetration"] = variable(1e-3 * np.array([r["max_penetration_mm"] for r in rows]),
                                               ("pair",), "m", "maximum penetration depth")
    data["compare_groove_depth_used"] = variable([r["groove_depth_used"] for r in rows], ("pair",), "1",
                                                 "tooth height / groove depth")
    coords = {"angle": variable(sw.phi, a, "rad", "pulley angle from full seating (entry < 0 < exit)"),
              "pair": ("pair", np.array(pairs, dtype=object))}
    summary = headline(sw)
    summary["geometry"] = geometry(pair)
    summary["geometry"]["first_contact_deg"] = float(np.degrees(sw.phi[-1]))
    summary["comparison"] = rows
    if model.maps is not None:
        area, pen = maps(model, progress)
        coords["map_teeth"] = ("map_teeth", np.array(model.maps.teeth))
        coords["map_pitch_error"] = variable(model.maps.pitch_error, ("map_pitch_error",), "m",
                                             "pitch error (tooth offset from its groove)")
        data["map_overlap_area"] = variable(area, ("map_teeth", "map_pitch_error"), "m2", "maximum overlap area")
        data["map_penetration"] = variable(pen, ("map_teeth", "map_pitch_error"), "m", "maximum penetration")
        summary["maps"] = {"teeth": list(model.maps.teeth),
                           "pitch_error_mm": [1e3 * e for e in model.maps.pitch_error],
                           "max_overlap_area_mm2": (1e6 * area).tolist(), "max_penetration_mm": (1e3 * pen).tolist()}
    diags, load_attrs = [], {}
    if model.load is not None:
        from .loadcase import run_load

        if progress:
            progress(0.72, "load sharing")
        ld_data, ld_coords, summary["load"], diags, load_attrs = run_load(model, pair, progress)
        data.update(ld_data)
        coords.update(ld_coords)
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(**load_attrs)
    ds.attrs.update(model_toml=dumps(model), belt_radius=pair.belt_radius, outside_radius=pair.outside_radius,
                    tooth_offset=pair.offset, tooth_land=pair.tooth.land, tooth_tip=pair.tooth.tip,
                    belt_thickness=pair.tooth.thickness, teeth=pair.teeth, title=model.name)
    if progress:
        progress(1.0, "done")
    result = Result("toothed-mesh", ds, summary, units=unit_map(summary, UNITS))
    for d in diags:
        result.diagnose(*d)
    return result
