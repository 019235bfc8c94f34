"""``check(model)``: the pair's geometry, known without sweeping the engagement."""
from __future__ import annotations

import numpy as np

from .engagement import geometry
from ..mechanics.teeth.interference import evaluate, Flank
from ..mechanics.teeth.kinematics import first_contact
from ..mechanics.teeth.pair import resolve
from ..mechanics.teeth.profiles import tooth_outline
from ..mechanics.teeth.pulley import pulley_polygon


def report(model) -> str:
    """A text report: profiles and sources, radii, pitch error, seated clearances."""
    pair = resolve(model)
    g = geometry(pair)
    flank = Flank.from_outline(tooth_outline(pair.tooth, pair.tol), pair.spacing)
    seated = evaluate(flank, pulley_polygon(pair), np.array([0.0]), pair.belt_radius, pair.offset,
                      pair.tooth.land)
    tip = int(np.argmin(np.abs(flank.uv[:, 0]) + np.abs(flank.uv[:, 1] - pair.tooth.tip)))
    phi0 = first_contact(flank.uv, pair.belt_radius, pair.outside_radius, pair.offset)
    width = 2 * np.max(np.abs(flank.uv[:, 0]))
    lines = [
        f"toothed mesh: {model.name or '(unnamed)'}",
        f"  belt tooth    {g['belt_profile']}: pitch {g['belt_pitch_mm']:.3f} mm, height {g['tooth_height_mm']:.3f} mm,"
        f" PLD {g['belt_pld_mm']:.3f} mm, width over root fillets {1e3 * width:.3f} mm",
        f"                source: {g['tooth_source']}",
        f"  pulley        {pair.teeth} teeth, groove {g['pulley_profile']}: pitch {g['pulley_pitch_mm']:.3f} mm,"
        f" depth {g['groove_depth_mm']:.3f} mm, PLD {g['pulley_pld_mm']:.3f} mm",
        f"                source: {g['groove_source']}",
        f"  radii         pitch r_c {g['pitch_radius_mm']:.3f} mm, outside r_o {g['outside_radius_mm']:.3f} mm,"
        f" belt pitch line R_b = r_o + a_belt {g['belt_pitch_line_radius_mm']:.3f} mm",
        f"  pitch error   {g['pitch_error_mm']:+.4f} mm (belt pitch - groove spacing on R_b); tooth offset"
        f" {g['tooth_offset_mm']:+.4f} mm",
        f"  depth used    {g['tooth_height_mm'] / g['groove_depth_mm']:.1%} of the groove (tooth height / depth)",
        f"  seated        overlap {1e6 * seated['area'][0]:.4g} mm^2, tip clearance {1e3 * seated['signed'][0, tip]:.4f} mm,"
        f" flank clearance leading {1e3 * seated['clearance_leading'][0]:.4f} / trailing"
        f" {1e3 * seated['clearance_trailing'][0]:.4f} mm",
        f"  engagement    first possible contact at +-{np.degrees(phi0):.2f} deg of pulley turn;"
        f" {model.mesh.angles} angles",
    ]
    if model.compare:
        lines.append(f"  compare       {len(model.compare)} more pair(s)")
    if model.maps is not None:
        lines.append(f"  maps          teeth {model.maps.teeth} x pitch error "
                     f"{[round(1e3 * e, 4) for e in model.maps.pitch_error]} mm")
    if model.load is not None:
        from .loadcase import chain_of, stiffnesses

        ch = chain_of(model, pair)
        kt, kt_src, ea, ea_src = stiffnesses(model, pair)
        ld = model.load
        lines += [f"  load          {ch.teeth} teeth in mesh over {np.degrees(ld.wrap):.0f} deg, T0 {ld.installation_tension:.4g} N,"
                  f" torque {ld.torque:.4g} N m, pitch error {1e3 * ch.pitch_error:+.4f} mm per tooth",
                  f"                tooth spring {1e-3 * ch.tooth_stiffness:.4g} N/mm ({kt_src}); cord EA {ch.cord_stiffness:.4g} N"
                  f" ({ea_src}); land share {ch.land_share:.2f}, friction {ld.friction:g}"]
    return "\n".join(lines)
