"""A belt tooth and a pulley resolved to shapes and numbers, with the checks that need both.

Pitch-line differential: the belt's land rests on the pulley's outside circle (radius
r_o = z p_pulley / (2 pi) - a_pulley), so the belt's pitch line (its cord) wraps at
R_b = r_o + a_belt. For a matched pair R_b is the pulley's pitch radius; for a mixed pair it is
not, and the belt pitch differs from the groove spacing measured on the belt pitch line,
2 pi R_b / z, by the pitch error reported here.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np

from . import catalogue
from .profiles import ArcGroove, ArcTooth, GTTooth, PolylineTooth, TrapezoidalGroove, TrapezoidalTooth, tooth_outline


@dataclass(frozen=True)
class Pair:
    """Everything the engagement needs, in SI numbers and shape objects."""

    tooth: object
    groove: Optional[object]  # None when the groove is generated
    teeth: int
    pulley_pitch: float
    pulley_pld: float
    generated: bool
    generated_clearance: float
    offset: float
    tol: float
    spacing: float
    label: str = ""

    @property
    def pitch_radius(self) -> float:
        """Pulley pitch radius r_c = z p / (2 pi)."""
        return self.teeth * self.pulley_pitch / (2 * np.pi)

    @property
    def outside_radius(self) -> float:
        """Outside radius r_o = r_c - a_pulley."""
        return self.pitch_radius - self.pulley_pld

    @property
    def belt_radius(self) -> float:
        """Radius of the belt's pitch line on the pulley, R_b = r_o + a_belt."""
        return self.outside_radius + self.tooth.pld

    @property
    def pitch_error(self) -> float:
        """Belt pitch minus the groove spacing on the belt pitch line (m)."""
        return self.tooth.pitch - 2 * np.pi * self.belt_radius / self.teeth

    @property
    def groove_depth(self) -> float:
        """Standard groove depth, or the generated groove's (the tooth height plus clearance)."""
        return self.groove.depth if self.groove is not None else self.tooth.height + self.generated_clearance


def make_tooth(spec):
    """A tooth shape from a model's ``[belt.tooth]`` table."""
    d = spec.model_dump()
    kind = d.pop("type")
    if kind == "trapezoidal":
        return TrapezoidalTooth(**d)
    if kind == "arc":
        return ArcTooth(**d)
    if kind == "gt":
        return GTTooth(**d)
    pts = tuple(tuple(p) for p in d.pop("points"))
    return PolylineTooth(height=max(p[1] for p in pts), points=pts, **d)


def make_groove(spec):
    """A groove shape from a model's ``[pulley.shape]`` table."""
    d = spec.model_dump()
    kind = d.pop("type")
    return TrapezoidalGroove(**d) if kind == "trapezoidal" else ArcGroove(**d)


def build(tooth, pulley_profile, shape, z, groove_kind, pld, clearance, offset, tol, spacing, label=""):
    """Resolve and check a pair; ValueError with a one-line message when it cannot mesh."""
    groove = None
    if shape is not None:
        groove = make_groove(shape)
    elif groove_kind == "standard":
        if pulley_profile is None:
            raise ValueError("pulley: give profile or [pulley.shape] for a standard groove, or groove = 'generated'")
        groove = catalogue.groove(pulley_profile, z)
        if groove is None:
            raise ValueError(f"pulley.profile: {pulley_profile!r} has no standard groove in the catalogue; "
                             "use groove = 'generated' (the belt tooth as a rack cuts it)")
    if groove_kind == "generated":
        groove_obj = None
        pitch = groove.pitch if groove is not None else (
            catalogue.entry(pulley_profile).pitch if pulley_profile else tooth.pitch)
        a_p = pld if pld is not None else (groove.pld if groove is not None else (
            catalogue.tooth(pulley_profile).pld if pulley_profile else tooth.pld))
    else:
        groove_obj = groove
        pitch = groove.pitch
        a_p = pld if pld is not None else groove.pld
    pair = Pair(tooth=tooth, groove=groove_obj, teeth=z, pulley_pitch=pitch, pulley_pld=a_p,
                generated=groove_kind == "generated", generated_clearance=clearance, offset=offset,
                tol=tol, spacing=spacing, label=label)
    check(pair)
    return pair


def check(pair: Pair) -> None:
    """The cross-checks of the issue: one tooth must be able to engage, and seat."""
    t = pair.tooth
    spacing = 2 * np.pi * pair.belt_radius / pair.teeth
    err = pair.pitch_error + pair.offset
    if abs(err) >= spacing / 2:
        raise ValueError(f"pitch mismatch: belt pitch {t.pitch * 1e3:.3f} mm (offset {pair.offset * 1e3:g} mm) "
                         f"against a groove spacing of {spacing * 1e3:.3f} mm on the belt pitch line is "
                         f"{abs(err) * 1e3:.3f} mm, more than half a pitch: no tooth can engage its groove")
    if abs(pair.offset) >= spacing / 2:
        raise ValueError(f"mesh.tooth_offset {pair.offset * 1e3:g} mm is more than half a groove pitch")
    if pair.groove is not None and t.height >= pair.groove.depth:
        raise ValueError(f"belt tooth height {t.height * 1e3:.3f} mm is not less than the groove depth "
                         f"{pair.groove.depth * 1e3:.3f} mm: the tooth is taller than the groove admits")
    if pair.outside_radius - pair.groove_depth <= 0:
        raise ValueError(f"pulley of {pair.teeth} teeth is too small for its groove depth")
    half = tooth_outline(t, max(pair.tol, 1e-6))
    if 2 * np.max(np.abs(half[:, 0])) >= t.pitch:
        raise ValueError(f"belt tooth ({2 * np.max(np.abs(half[:, 0])) * 1e3:.3f} mm at the land) is wider "
                         f"than its pitch {t.pitch * 1e3:.3f} mm")
    if pair.groove is not None:
        from .profiles import groove_cell

        try:
            groove_cell(pair.groove, pair.outside_radius, pair.teeth, max(pair.tol, 1e-6))
        except ValueError as exc:
            raise ValueError(f"pulley groove cannot be built for {pair.teeth} teeth ({exc})") from None


def resolve(model, teeth=None, offset=None):
    """The Pair of a Model (optionally with another tooth count or tooth offset)."""
    b, p, m = model.belt, model.pulley, model.mesh
    tooth = catalogue.tooth(b.profile) if b.profile else make_tooth(b.tooth)
    profile = p.profile or (b.profile if p.shape is None else None)
    return build(tooth, profile, p.shape, teeth or p.teeth, p.groove, p.pld, p.generated_clearance,
                 m.tooth_offset if offset is None else offset, m.chord_tolerance, m.flank_spacing,
                 label=model.name)


def resolve_row(row, mesh):
    """The Pair of a comparison-table row."""
    pulley = row.pulley or row.belt
    label = row.label or (f"{row.belt} on {pulley} z{row.teeth}" + (" gen" if row.groove == "generated" else ""))
    return build(catalogue.tooth(row.belt), pulley, None, row.teeth, row.groove, None, 0.0, 0.0,
                 mesh.chord_tolerance, mesh.flank_spacing, label=label)
