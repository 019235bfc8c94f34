"""The belt and pulleys as catalogues give them: ribbed profiles, effective diameters, the effective
drive length and the required belt length of a layout.

A ribbed (poly-V) belt is sold by its effective length, measured on pulleys' effective diameters
(ISO 9981, ISO 9982); the belt's pitch line (its tension member) runs on the pitch diameter, which the
layout uses (``pulley.radius`` is the pitch radius). Grooved pulleys carry the ribs: d_e = d_p - 2 hb;
back-side (flat) pulleys carry the belt's back: d_e = d_p + 2 hb.

- effective drive length EDL = the tangent spans between pitch circles + sum of wrap x effective radius;
- required effective belt length REBL = EDL - ``belt.length_offset`` (by default 0). Suppliers'
  reports print an offset of 0 to 3.5 mm whose rule they do not publish: give theirs to compare.

Both reproduce the position tables of Gates accessory-drive reports (tests/belt/test_supplier_report.py).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...core.errors import ModelError
from ...mechanics.layout import Layout


@dataclass(frozen=True)
class Profile:
    rib_pitch: float            # m (ISO 9982)
    hb: float | None            # pitch-to-effective offset per side (m); None: not known to drivedyn


#: rib pitches of ISO 9982 (PH 1.60, PJ 2.34, PK 3.56, PL 4.70, PM 9.40 mm). hb of PK, 1.2 mm, is the one
#: Gates' accessory-drive reports use (their pitch and effective diameters differ by 2.4 mm on every
#: pulley); for the other profiles give each pulley's effective_diameter
PROFILES = {"PH": Profile(1.60e-3, None), "PJ": Profile(2.34e-3, None), "PK": Profile(3.56e-3, 1.2e-3),
            "PL": Profile(4.70e-3, None), "PM": Profile(9.40e-3, None)}


def effective_diameters(model) -> np.ndarray:
    """Effective diameter (m) per pulley: the pulley's own, else 2 x radius -+ 2 hb by the profile."""
    prof = PROFILES.get(model.belt.profile) if model.belt.profile else None
    out = []
    for j, p in enumerate(model.pulleys):
        if p.effective_diameter is not None:
            out.append(p.effective_diameter)
            continue
        if prof is None or prof.hb is None:
            what = f"belt.profile {model.belt.profile}" if model.belt.profile else "no belt.profile"
            raise ModelError(f"pulley {p.name!r}: no effective diameter ({what} gives no hb): give "
                             "effective_diameter, or belt.profile = \"PK\"", field=f"pulleys.{j}.effective_diameter")
        out.append(2 * p.radius + (2 * prof.hb if p.side == "back" else -2 * prof.hb))
    return np.array(out)


def effective_drive_length(lay: Layout, d_eff) -> float:
    """EDL (m): the tangent spans between pitch circles plus each wrap on its effective radius."""
    return float(sum(sp.length for sp in lay.spans) + np.sum(lay.wrap * np.asarray(d_eff) / 2))


def length_offset(model, drawn: Layout, d_eff) -> float:
    """belt.length_offset, or 0 (the required belt length is the effective drive length). The offset
    is a property of the layout, not of the belt: a longer belt moves the tensioner."""
    return model.belt.length_offset if model.belt.length_offset is not None else 0.0
