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

from ..model import Spec, quantity
from .criteria import Criteria

Length = quantity("m")
Positive = quantity("m", gt=0)
NonNeg = quantity("m", ge=0)


class TrapezoidalToothSpec(Spec):
    """Straight-flanked tooth (ISO 5296, DIN 7721 T)."""

    type: Literal["trapezoidal"]
    pitch: Positive
    height: Positive
    width: Positive  # at the land
    angle: quantity("rad", gt=0, lt=np.pi) = float(np.radians(40))  # included angle 2 beta
    tip_radius: NonNeg = 0.0
    root_radius: NonNeg = 0.0
    pld: NonNeg
    thickness: NonNeg = 0.0


class ArcToothSpec(Spec):
    """HTD-like tooth: one arc centred on the tooth axis, plus root fillets."""

    type: Literal["arc"]
    pitch: Positive
    height: Positive
    arc_radius: Positive
    root_radius: NonNeg = 0.0
    pld: NonNeg
    thickness: NonNeg = 0.0


class GTToothSpec(Spec):
    """GT-like tooth: tip arc, flank arcs centred on the pitch line, root fillets."""

    type: Literal["gt"]
    pitch: Positive
    height: Positive
    tip_radius: Positive
    flank_radius: Positive
    flank_offset: NonNeg
    root_radius: Positive
    pld: NonNeg
    thickness: NonNeg = 0.0


class PolylineToothSpec(Spec):
    """Any tooth as right-half points [distance from the axis, depth below the land], tip first."""

    type: Literal["polyline"]
    pitch: Positive
    pld: NonNeg
    points: list[tuple[Length, Length]]
    thickness: NonNeg = 0.0

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
    pitch: Positive
    depth: Positive
    bottom_width: Positive
    angle: quantity("rad", gt=0, lt=np.pi / 2) = float(np.radians(20))  # flank to groove axis
    bottom_radius: NonNeg = 0.0
    tip_radius: NonNeg = 0.0
    pld: NonNeg


class ArcGrooveSpec(Spec):
    """HTD-like groove: bottom arc on the groove axis, straight flanks, tip radius."""

    type: Literal["arc"]
    pitch: Positive
    depth: Positive
    width: Positive  # at the outside circle
    angle: quantity("rad", ge=0, lt=np.pi / 2) = float(np.radians(14))
    bottom_radius: Positive
    tip_radius: NonNeg = 0.0
    pld: NonNeg


GrooveSpec = Annotated[Union[TrapezoidalGrooveSpec, ArcGrooveSpec], Field(discriminator="type")]


def _tooth_count(v):
    # upper: catalogue pulleys stop near 200 teeth; the tooth outlines scale with z
    if v < 6:
        raise ValueError(f"must be >= 6, got {v}")
    if v > 1000:
        raise ValueError(f"must be <= 1000, got {v}")
    return v


def _profile_name(v):
    from .catalogue import canonical

    return None if v is None else canonical(v)


class Belt(Spec):
    """The belt: a catalogue ``profile`` or a custom ``tooth``."""

    profile: Optional[str] = None
    tooth: Optional[ToothSpec] = None

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
    profile: Optional[str] = None  # default: the belt's profile
    groove: Literal["standard", "generated"] = "standard"
    shape: Optional[GrooveSpec] = None
    pld: Optional[NonNeg] = None  # outside radius = pitch radius - pld; default from the profile
    generated_clearance: NonNeg = 0.0

    @field_validator("profile")
    @classmethod
    def _known(cls, v):
        return _profile_name(v)

    _teeth = field_validator("teeth")(classmethod(lambda cls, v: _tooth_count(v)))


class Mesh(Spec):
    """The engagement sweep and its discretisation."""

    angles: int = 181
    half_range: Optional[quantity("rad", gt=0)] = None  # default: from first possible contact
    tooth_offset: Length = 0.0  # belt tooth ahead (+) of its groove when seated (pitch error)
    # floors far below the profile data's precision (10 um): finer sampling only costs time and
    # memory (a 1e-12 m spacing would mean 1e10 samples of one tooth)
    chord_tolerance: quantity("m", ge=1e-9) = 2e-7
    flank_spacing: quantity("m", ge=1e-7) = 2e-5

    _angles = field_validator("angles")(classmethod(lambda cls, v: _angle_count(v)))


def _angle_count(v):
    if not 3 <= v <= 10_000:  # each angle is one polygon intersection per tooth pair
        raise ValueError(f"must lie in 3..10000, got {v}")
    return v


class Maps(Spec):
    """Maximum interference over tooth counts x pitch errors (tooth offsets)."""

    teeth: list[int]
    pitch_error: list[Length] = [0.0]
    angles: int = 61

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
    pulley: Optional[str] = None
    teeth: int
    groove: Literal["standard", "generated"] = "standard"
    label: str = ""

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
    installation_tension: quantity("N", gt=0)
    torque: quantity("N*m", ge=0) = 0.0
    wrap: quantity("rad", gt=0, le=2 * np.pi) = float(np.pi)
    cord_stiffness: Optional[quantity("N/m", gt=0)] = None
    tooth_stiffness: Optional[quantity("N/m^2", gt=0)] = None
    tooth_modulus: Optional[quantity("Pa", gt=0)] = None
    friction: float = Field(0.0, ge=0, le=2.0)
    flank_angle: Optional[quantity("rad", gt=0, lt=np.pi / 2)] = None
    pitch_error: Length = 0.0  # added to the pair's own (belt pitch - groove spacing on R_b)
    clearance: Optional[NonNeg] = None  # sideways play of a seated tooth; default from the contours
    slip_scale: quantity("m", ge=1e-9, le=1e-3) = 1e-6
    land_nodes: int = Field(4, ge=1, le=64)
    tensions: list[quantity("N", gt=0)] = []

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
    schema_version: Literal[1] = 1
    name: str = ""
    belt: Belt
    pulley: Pulley
    mesh: Mesh = Mesh()
    maps: Optional[Maps] = None
    compare: list[Pair] = []
    load: Optional[Load] = None
    criteria: Criteria = Criteria()               # design limits of the verdict (criteria.py, docs/criteria.md)

    @model_validator(mode="after")
    def _pair(self):
        from .pair import resolve, resolve_row

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
