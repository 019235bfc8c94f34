"""The toothed-mesh model file (``kind = "toothed-mesh"``): a belt tooth, a pulley, the angles.

A profile is either a catalogue name (``profile = "HTD8M"``) or a shape given by its defining
dimensions (``[belt.tooth]`` / ``[pulley.shape]`` with ``type = ...``). Lengths in metres or
with units ("1.91 mm"); angles in radians or with units ("40 deg"). The cross-checks that need
both sides (pitch mismatch, tooth taller than the groove) are in :func:`pair.resolve`, called
here so that a bad file fails at load time with one line.
"""
from __future__ import annotations

from typing import Annotated, Literal, Optional, Union

import numpy as np
from pydantic import Field, field_validator, model_validator

from ..core.model import Spec, quantity
from .criteria import Criteria

Length = quantity("m")
Positive = quantity("m", gt=0)
NonNeg = quantity("m", ge=0)


class TrapezoidalToothSpec(Spec):
    """Straight-flanked tooth (ISO 5296, DIN 7721 T)."""

    type: Literal["trapezoidal"]
    """Tooth shape: "trapezoidal"."""
    pitch: Positive
    """Belt pitch p: tooth-to-tooth distance on the pitch line."""
    height: Positive
    """Tooth height from the land to the tip."""
    width: Positive
    """Tooth width at the land (the tooth's base)."""
    angle: quantity("rad", gt=0, lt=np.pi) = float(np.radians(40))
    """Included angle 2 beta between the flanks (40 deg: ISO 5296)."""
    tip_radius: NonNeg = 0.0
    """Radius rounding the tip corners (0: sharp)."""
    root_radius: NonNeg = 0.0
    """Radius of the fillets between flank and land (0: sharp)."""
    pld: NonNeg
    """Pitch line differential: distance from the belt's land (tooth base) to its pitch line (the cord)."""
    thickness: NonNeg = 0.0
    """Total belt thickness, land to back (for the drawings; 0: not given)."""


class ArcToothSpec(Spec):
    """HTD-like tooth: one arc centred on the tooth axis, plus root fillets."""

    type: Literal["arc"]
    """Tooth shape: "arc" (HTD-like)."""
    pitch: Positive
    """Belt pitch p: tooth-to-tooth distance on the pitch line."""
    height: Positive
    """Tooth height from the land to the tip."""
    arc_radius: Positive
    """Radius of the tooth's arc, centred on the tooth axis."""
    root_radius: NonNeg = 0.0
    """Radius of the fillets between arc and land (0: sharp)."""
    pld: NonNeg
    """Pitch line differential: distance from the belt's land (tooth base) to its pitch line (the cord)."""
    thickness: NonNeg = 0.0
    """Total belt thickness, land to back (for the drawings; 0: not given)."""


class GTToothSpec(Spec):
    """GT-like tooth: tip arc, flank arcs centred on the pitch line, root fillets."""

    type: Literal["gt"]
    """Tooth shape: "gt" (GT-like)."""
    pitch: Positive
    """Belt pitch p: tooth-to-tooth distance on the pitch line."""
    height: Positive
    """Tooth height from the land to the tip."""
    tip_radius: Positive
    """Radius of the tip arc."""
    flank_radius: Positive
    """Radius of the flank arcs, centred on the pitch line."""
    flank_offset: NonNeg
    """Distance of the flank arcs' centres from the tooth axis, along the pitch line."""
    root_radius: Positive
    """Radius of the fillets between flank and land."""
    pld: NonNeg
    """Pitch line differential: distance from the belt's land (tooth base) to its pitch line (the cord)."""
    thickness: NonNeg = 0.0
    """Total belt thickness, land to back (for the drawings; 0: not given)."""


class PolylineToothSpec(Spec):
    """Any tooth as right-half points [distance from the axis, depth below the land], tip first."""

    type: Literal["polyline"]
    """Tooth shape: "polyline" (any outline as points)."""
    pitch: Positive
    """Belt pitch p: tooth-to-tooth distance on the pitch line."""
    pld: NonNeg
    """Pitch line differential: distance from the belt's land (tooth base) to its pitch line (the cord)."""
    points: list[tuple[Length, Length]]
    """The right half of the tooth as points [distance from the tooth axis, depth below the land], tip first (on the
    axis) to the land (depth 0)."""
    thickness: NonNeg = 0.0
    """Total belt thickness, land to back (for the drawings; 0: not given)."""

    @field_validator("points")
    @classmethod
    def _points(cls, v):
        if len(v) < 2:
            raise ValueError("needs at least 2 points, tip (on the axis) first, land last")
        if abs(v[0][0]) > 1e-12 or abs(v[-1][1]) > 1e-12:
            raise ValueError("the first point must be on the axis (x = 0) and the last on the land (depth = 0)")
        return v


ToothSpec = Annotated[Union[TrapezoidalToothSpec, ArcToothSpec, GTToothSpec, PolylineToothSpec],
                      Field(discriminator="type")]


class TrapezoidalGrooveSpec(Spec):
    """Straight-sided groove with a flat bottom (ISO 5294, DIN 7721-2)."""

    type: Literal["trapezoidal"]
    """Groove shape: "trapezoidal"."""
    pitch: Positive
    """Groove pitch on the pulley's pitch circle (equal to the belt's pitch)."""
    depth: Positive
    """Groove depth below the outside circle."""
    bottom_width: Positive
    """Width of the groove's flat bottom."""
    angle: quantity("rad", gt=0, lt=np.pi / 2) = float(np.radians(20))
    """Angle of each flank to the groove's axis (20 deg: half the 40 deg of ISO 5294)."""
    bottom_radius: NonNeg = 0.0
    """Radius of the fillets between flank and bottom (0: sharp)."""
    tip_radius: NonNeg = 0.0
    """Radius rounding the groove's edges at the outside circle (0: sharp)."""
    pld: NonNeg
    """Pitch line differential of the pulley: pitch radius minus outside radius."""


class ArcGrooveSpec(Spec):
    """HTD-like groove: bottom arc on the groove axis, straight flanks, tip radius."""

    type: Literal["arc"]
    """Groove shape: "arc" (HTD-like)."""
    pitch: Positive
    """Groove pitch on the pulley's pitch circle (equal to the belt's pitch)."""
    depth: Positive
    """Groove depth below the outside circle."""
    width: Positive
    """Groove width at the outside circle."""
    angle: quantity("rad", ge=0, lt=np.pi / 2) = float(np.radians(14))
    """Angle of each straight flank to the groove's axis."""
    bottom_radius: Positive
    """Radius of the bottom arc, centred on the groove's axis."""
    tip_radius: NonNeg = 0.0
    """Radius rounding the groove's edges at the outside circle (0: sharp)."""
    pld: NonNeg
    """Pitch line differential of the pulley: pitch radius minus outside radius."""


GrooveSpec = Annotated[Union[TrapezoidalGrooveSpec, ArcGrooveSpec], Field(discriminator="type")]


def _tooth_count(v):
    # upper: catalogue pulleys stop near 200 teeth; the tooth outlines scale with z
    if v < 6:
        raise ValueError(f"must be >= 6, got {v}")
    if v > 1000:
        raise ValueError(f"must be <= 1000, got {v}")
    return v


def _profile_name(v):
    from ..mechanics.teeth.catalogue import canonical

    return None if v is None else canonical(v)


class Belt(Spec):
    """The belt: a catalogue ``profile`` or a custom ``tooth``."""

    profile: Optional[str] = None
    """Catalogue profile of the belt ("HTD8M", "T10", "L", ...; mechanics/teeth/catalogue.py); give this or tooth."""
    tooth: Optional[ToothSpec] = None
    """A custom tooth by its defining dimensions (type = "trapezoidal", "arc", "gt" or "polyline")."""

    @field_validator("profile")
    @classmethod
    def _known(cls, v):
        return _profile_name(v)

    @model_validator(mode="after")
    def _one(self):
        if (self.profile is None) == (self.tooth is None):
            raise ValueError("give either profile (a catalogue name) or [belt.tooth], not both or neither")
        return self


class Pulley(Spec):
    """The pulley: tooth count, groove profile (catalogue or custom) and how the groove is made."""

    teeth: int
    """Number of teeth (grooves) of the pulley (6..1000)."""
    profile: Optional[str] = None
    """Catalogue profile of the pulley's grooves; none: the belt's profile."""
    groove: Literal["standard", "generated"] = "standard"
    """"standard": the catalogue's (or shape's) groove; "generated": the groove the belt tooth cuts as a rack rolling
    on the pitch circle."""
    shape: Optional[GrooveSpec] = None
    """A custom groove by its defining dimensions (type = "trapezoidal" or "arc"); none: the catalogue's."""
    pld: Optional[NonNeg] = None
    """Pitch line differential: outside radius = pitch radius - pld; none: from the profile."""
    generated_clearance: NonNeg = 0.0
    """Clearance added around the belt tooth when the groove is generated."""

    @field_validator("profile")
    @classmethod
    def _known(cls, v):
        return _profile_name(v)

    _teeth = field_validator("teeth")(classmethod(lambda cls, v: _tooth_count(v)))


class Mesh(Spec):
    """The engagement sweep and its discretisation."""

    angles: int = 181
    """Number of pulley angles of the engagement sweep (3..10000)."""
    half_range: Optional[quantity("rad", gt=0)] = None
    """Half the swept angle range, either side of the seated position; none: from the first possible contact."""
    tooth_offset: Length = 0.0
    """Belt tooth ahead (+) of its groove when seated, along the pitch line (a pitch error)."""
    # floors far below the profile data's precision (10 um): finer sampling only costs time and
    # memory (a 1e-12 m spacing would mean 1e10 samples of one tooth)
    chord_tolerance: quantity("m", ge=1e-9) = 2e-7
    """Largest chord error of the tooth and groove outlines' polygons (the profile data's precision is about 10 um)."""
    flank_spacing: quantity("m", ge=1e-7) = 2e-5
    """Spacing of the sample points along the flanks."""

    _angles = field_validator("angles")(classmethod(lambda cls, v: _angle_count(v)))


def _angle_count(v):
    if not 3 <= v <= 10_000:  # each angle is one polygon intersection per tooth pair
        raise ValueError(f"must lie in 3..10000, got {v}")
    return v


class Maps(Spec):
    """Maximum interference over tooth counts x pitch errors (tooth offsets)."""

    teeth: list[int]
    """Pulley tooth counts of the map's rows."""
    pitch_error: list[Length] = [0.0]
    """Pitch errors (tooth offsets) of the map's columns."""
    angles: int = 61
    """Number of angles of each cell's engagement sweep."""

    _angles = field_validator("angles")(classmethod(lambda cls, v: _angle_count(v)))
    _teeth = field_validator("teeth")(classmethod(lambda cls, v: [_tooth_count(z) for z in v]))

    @model_validator(mode="after")
    def _size(self):
        # every cell is a full engagement sweep (and is checked at load): keep the map a figure
        if not self.teeth or not self.pitch_error or len(self.teeth) * len(self.pitch_error) > 400:
            raise ValueError(f"maps needs 1..400 cells (teeth x pitch errors), got "
                             f"{len(self.teeth)} x {len(self.pitch_error)}")
        return self


class Pair(Spec):
    """One row of the comparison table (catalogue profiles)."""

    belt: str
    """Catalogue profile of the belt."""
    pulley: Optional[str] = None
    """Catalogue profile of the pulley; none: the belt's."""
    teeth: int
    """Number of teeth of the pulley."""
    groove: Literal["standard", "generated"] = "standard"
    """"standard" (catalogue groove) or "generated" (cut by the belt tooth)."""
    label: str = ""
    """Label of the row in the table and plots; empty: from the profiles."""

    @field_validator("belt", "pulley")
    @classmethod
    def _known(cls, v):
        return _profile_name(v)

    _teeth = field_validator("teeth")(classmethod(lambda cls, v: _tooth_count(v)))


class Load(Spec):
    """The belt under load on this pulley: tooth load sharing and the jump torque (loadshare.py).

    Stiffnesses are per unit belt width; the tooth spring comes from ``tooth_stiffness`` or from
    the tooth's shape and ``tooth_modulus`` (shear modulus of the tooth material); the cord
    stiffness EA per width from ``cord_stiffness`` or the catalogue (where a source gives it)."""

    width: quantity("m", gt=0, le=10.0)
    """Belt width (the stiffnesses are per unit width)."""
    installation_tension: quantity("N", gt=0)
    """Installation (static) tension of the belt, whole width."""
    torque: quantity("N*m", ge=0) = 0.0
    """Torque transmitted by the pulley."""
    wrap: quantity("rad", gt=0, le=2 * np.pi) = float(np.pi)
    """Wrap angle of the belt on the pulley."""
    cord_stiffness: Optional[quantity("N/m", gt=0)] = None
    """Cord stiffness EA per unit belt width; none: the catalogue's, where a source gives it."""
    tooth_stiffness: Optional[quantity("N/m^2", gt=0)] = None
    """Tooth stiffness per unit belt width (give this or tooth_modulus)."""
    tooth_modulus: Optional[quantity("Pa", gt=0)] = None
    """Shear modulus of the tooth material, from which the tooth spring follows with its shape (give this or
    tooth_stiffness)."""
    friction: float = Field(0.0, ge=0, le=2.0)
    """Friction coefficient between the belt's lands and the pulley (0..2)."""
    flank_angle: Optional[quantity("rad", gt=0, lt=np.pi / 2)] = None
    """Flank angle of the tooth for the jump criterion; none: from the contours."""
    pitch_error: Length = 0.0
    """Pitch error added to the pair's own (belt pitch - groove spacing on the belt's pitch radius)."""
    clearance: Optional[NonNeg] = None
    """Sideways play of a seated tooth before it bears on a flank; none: from the contours."""
    slip_scale: quantity("m", ge=1e-9, le=1e-3) = 1e-6
    """Slip displacement u_s over which land friction is regularised (mechanics/teeth/loadshare.py)."""
    land_nodes: int = Field(4, ge=1, le=64)
    """Points per land where friction acts (1..64)."""
    tensions: list[quantity("N", gt=0)] = []
    """Installation tensions of the jump-torque curve (at most 50); empty: 0.25 to 2 x installation_tension."""

    @field_validator("tensions")
    @classmethod
    def _tensions(cls, v):
        if len(v) > 50:  # each is a bisection of load-sharing solves
            raise ValueError(f"at most 50 installation tensions, got {len(v)}")
        return v

    @model_validator(mode="after")
    def _tooth(self):
        if (self.tooth_stiffness is None) == (self.tooth_modulus is None):
            raise ValueError("give either tooth_stiffness (per width) or tooth_modulus (shear modulus "
                             "of the tooth material), not both or neither")
        return self


class Model(Spec):
    """A toothed-belt meshing study (seed 001)."""

    kind: Literal["toothed-mesh"]
    """The kind of model file: "toothed-mesh"."""
    schema_version: Literal[1] = 1
    """Version of the model-file format (1)."""
    name: str = ""
    """A name for the study, shown in reports."""
    belt: Belt
    """The belt: a catalogue profile or a custom tooth."""
    pulley: Pulley
    """The pulley: tooth count and groove."""
    mesh: Mesh = Mesh()
    """How the engagement is swept: angles, range, tooth offset and the outlines' resolution."""
    maps: Optional[Maps] = None
    """Maximum interference over tooth counts x pitch errors; none: no map."""
    compare: list[Pair] = []
    """Rows of a comparison table of catalogue belt/pulley pairs."""
    load: Optional[Load] = None
    """The belt under load on this pulley: tooth load sharing and the jump torque; none: geometry only."""
    criteria: Criteria = Criteria()
    """Design limits of the verdict (criteria.py, docs/criteria.md)."""

    @model_validator(mode="after")
    def _pair(self):
        from ..mechanics.teeth.pair import resolve, resolve_row

        pair = resolve(self)
        if self.load is not None:
            from .loadcase import check_load

            check_load(self, pair)
        for k, row in enumerate(self.compare):
            try:
                resolve_row(row, self.mesh)
            except ValueError as exc:
                raise ValueError(f"compare[{k}]: {exc}") from None
        if self.maps is not None:
            for z in self.maps.teeth:
                for e in self.maps.pitch_error:
                    try:
                        resolve(self, teeth=z, offset=e)
                    except ValueError as exc:
                        raise ValueError(f"maps (teeth {z}, pitch error {e * 1e3:g} mm): {exc}") from None
        return self
