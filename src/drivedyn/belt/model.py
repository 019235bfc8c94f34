"""The belt-drive model file (``kind = "belt-drive"``): pure data, validated.

Coefficients are belt *properties* (per unit length or EA-like), so a model means the same
physics whatever the number of segments. The seed's per-element values (Kubas, eqs. 9, 18, 19)
map onto them as documented in ``examples/belt-5pk.toml``:

    element stiffness    c_L = axial_stiffness / l      (seed's c_L read as EA, see the example)
    element damping      b_L = axial_damping / l
    bending stiffness    c_B = bending_stiffness / l    (N m/rad per joint)
    bending damping      b_B = bending_damping / l
    contact c1, c2, b    = contact.*  x l               (per unit length of belt -> per segment)
"""
from __future__ import annotations

import math

from typing import Annotated, Literal, Optional, Union

from pydantic import Field, field_validator, model_validator

from ..core.model import Spec, check_name, limit, quantity, table_rows

Length = quantity("m")
Time = quantity("s")


#: "auto" never picks more
MAX_AUTO = 2000

class Harmonic(Spec):
    """A torque component amplitude * sin(order * theta + phase), theta the pulley's own angle."""

    order: float
    """Order of the component: cycles per revolution of this pulley (in (0, 1000])."""
    amplitude: quantity("N*m")
    """Torque amplitude of the component; counter-clockwise positive, like every torque of the drive."""
    phase: quantity("rad") = 0.0
    """Phase of the component at the pulley's angle 0 (the sine starts at 0 by default)."""

    @field_validator("order")
    @classmethod
    def _order(cls, v):
        # as the speed orders: an order above 1000 asks for steps no drive needs (and -1e29 is a typo)
        if not 0 < v <= 1000:
            raise ValueError(f"must lie in (0, 1000], got {v}")
        return v


class SpeedOrder(Spec):
    """An engine order on a prescribed speed: omega = omega_m(t) + sum (amplitude + order angle
    omega_m) cos(order phi_m + phase), phi_m the integral of the mean speed omega_m (speed_time).
    Give the order's speed amplitude (rad/s) or its angle amplitude (rad), or both."""

    order: float
    """Engine order: cycles per crank revolution (in (0, 1000]; 2 for a four-cylinder's firing order)."""
    amplitude: quantity("rad/s") = 0.0
    """Speed amplitude of the order (added to the angle amplitude times order times mean speed); 0: none."""
    angle: quantity("rad") = 0.0
    """Angle amplitude of the order (its speed amplitude grows with order x mean speed); 0: none."""
    phase: quantity("rad") = 0.0
    """Phase of the order's cosine at the crank's mean angle 0."""

    @field_validator("order")
    @classmethod
    def _order(cls, v):
        if not 0 < v <= 1000:
            raise ValueError(f"must lie in (0, 1000], got {v}")
        return v


class Clutch(Spec):
    """An accessory's rotor behind the pulley: an overrunning (one-way) clutch transmits torque
    only while the pulley drives the rotor; a decoupler adds a torsion spring (rate, damping) in
    series, which also only transmits drive torque. The pulley's loads (torque, tables,
    viscous, quadratic, power, harmonics, drag) then act on the rotor. ``sense``: the rotor's
    running sense (ccw, cw); by default that of the pulley when the belt runs as the crank
    (the prescribed-speed pulley, else the one with the largest applied torque) drives it."""

    type: Literal["one-way", "decoupler"] = "one-way"
    """"one-way": an overrunning clutch (rigid while it drives the rotor, free while the rotor overruns); "decoupler":
    the same with a torsion spring (rate, damping) in series."""
    inertia: quantity("kg*m^2", gt=0)
    """The accessory rotor's moment of inertia about its axis, behind the clutch (the pulley's own inertia stays in
    the pulley's inertia)."""
    rate: quantity("N*m/rad", ge=0) = 0.0
    """Torsional stiffness of a decoupler's spring between pulley and rotor; required (> 0) for a decoupler, unused by
    a one-way clutch."""
    damping: quantity("N*m*s/rad", ge=0) = 0.0
    """Viscous damping of the decoupler's spring (torque per relative speed of pulley and rotor)."""
    sense: Optional[Literal["ccw", "cw"]] = None
    """The rotor's running sense, "ccw" or "cw" (the sense in which the clutch transmits drive); none: the pulley's
    sense when the crank drives the belt."""

    @model_validator(mode="after")
    def _spring(self):
        if self.type == "decoupler" and not self.rate > 0:
            raise ValueError("a decoupler needs rate > 0 (its torsion spring)")
        return self


class _Tensioner(Spec):
    """What arm and slider share. The coordinate is the travel from the drawn position (the
    pulley's ``center``), positive into the belt (the sense that tightens it); the code finds that
    sense from the layout. Spring load = preload - rate x travel, or a table over travel."""

    friction_asymmetry: float = 1.0
    """Coulomb friction moving away from the belt over friction moving into it (1: symmetric; an asymmetric damper
    resists belt-tightening less: its friction in the loading sense, away from the belt, is the larger, Liu and Serkh,
    Gates, US 6,609,988)."""
    friction_share: float = 0.0
    """Friction of a damper the spring itself presses, as a share of the spring's load, added to friction (both then
    x friction_asymmetry moving away from the belt): the mechanical automatic tensioner whose damping shoe or bushing
    carries the torsion spring's reaction, so that its hysteresis loop widens with the spring torque (the loops Bastien,
    Michon, Manin and Dufour, J. Sound Vib. 302 (2007) 841, and Long, Yin, Zhao and Shangguan, Adv. Mech. Eng. 11
    (2019), doi 10.1177/1687814019890228, measure). With friction 0 the loop runs at spring x (1 + share x
    friction_asymmetry) loading (away from the belt) and spring x (1 - share) unloading. In [0, 1); 0: friction
    alone."""
    spring_table: Optional[list[list]] = None
    """The spring as a table of rows [travel, load] (arm: rad, N*m; slider: m, N; travel from the drawn position,
    positive into the belt; at least 2 rows); replaces preload and rate."""

    @field_validator("friction_asymmetry")
    @classmethod
    def _asym(cls, v):
        if not 0 < v <= 100:
            raise ValueError(f"must lie in (0, 100], got {v}")
        return v

    @field_validator("friction_share")
    @classmethod
    def _share(cls, v):
        if not 0 <= v < 1:
            raise ValueError(f"must lie in [0, 1) (a share of the spring's load; at 1 the spring cannot move the "
                             f"arm against it), got {v}")
        return v

    @model_validator(mode="after")
    def _stops(self):
        if self.spring_table is not None and (self.rate or self.preload):
            # the table replaces the linear spring: a rate or preload beside it would be ignored
            raise ValueError("give spring_table or preload and rate, not both (the table is the whole spring: "
                             f"preload {self.preload:g}, rate {self.rate:g} would be ignored)")
        lo, hi = self.stops
        if not hi > lo:
            raise ValueError(f"stops must be [min, max] with max > min, got [{lo:.4g}, {hi:.4g}] (SI)")
        if not lo <= 0 <= hi:
            raise ValueError(f"stops [{lo:.4g}, {hi:.4g}] (SI: rad for an arm, m for a slider) exclude the drawn "
                             "position (travel 0)")
        return self


class Arm(_Tensioner):
    """Automatic tensioner: the pulley on an arm that swings about a fixed pivot (seed 000's
    tensioner idler, made dynamic). Travel and stops in rad."""

    pivot: tuple[Length, Length]
    """Position [x, y] of the arm's fixed pivot, in the drive's coordinates (the same frame as the pulleys' centres)."""
    inertia: quantity("kg*m^2", gt=0)
    """Moment of inertia of the arm about its pivot, the pulley's mass included (the pulley's own spin inertia is the
    pulley's inertia)."""
    preload: quantity("N*m", ge=0) = 0.0
    """Spring torque at the drawn position (travel 0), acting into the belt; replaced by the one free_torque gives."""
    rate: quantity("N*m/rad", ge=0) = 0.0
    """Torsional rate of the spring: its torque falls by rate x travel as the arm swings into the belt."""
    damping: quantity("N*m*s/rad", ge=0) = 0.0
    """Viscous damping of the arm about its pivot (moving into the belt only, when damping_away is given)."""
    damping_away: Optional[quantity("N*m*s/rad", ge=0)] = None
    """Viscous damping of the arm moving away from the belt, when it differs from damping: a hydraulic tensioner
    (its check valve closes as the belt pushes the plunger back, the oil leaks out through the plunger's clearance:
    the high damping; it refills through the valve as the plunger extends into the belt: damping, the low). Under a
    steady load the arm leaks down at the load over damping_away (a leak-down test's load x time / travel gives it).
    None: damping both ways."""
    friction: quantity("N*m", ge=0) = 0.0
    """Coulomb friction torque of the arm's damper moving into the belt (away from it: x friction_asymmetry)."""
    friction_speed: quantity("rad/s", gt=0) = 0.01
    """Arm speed over which the Coulomb friction is regularised (smoothed from 0 to full); smaller is closer to dry
    friction and needs smaller steps."""
    stops: tuple[quantity("rad"), quantity("rad")] = (-0.5, 0.5)
    """Travel [min, max] of the arm from the drawn position at which its stops engage (min <= 0 <= max, positive into
    the belt); replaced by [drawn-to-load-stop, drawn-to-free-arm] when load_stop is given."""
    stop_stiffness: quantity("N*m/rad", gt=0) = 1e4
    """Torsional stiffness of the stops once the arm reaches one (a stiff penalty spring)."""
    stop_damping: quantity("N*m*s/rad", ge=0) = 1.0
    """Viscous damping acting while the arm presses on a stop."""
    free_angle: Optional[quantity("rad")] = None
    """Supplier data (the position table, geometry/positions.py): the arm's absolute angle with no belt, pivot to
    pulley centre, from +x counter-clockwise; needed by free_torque and load_stop. None: not given."""
    free_torque: Optional[quantity("N*m", ge=0)] = None
    """Supplier data: the spring torque at the free arm; preload then follows as free_torque + rate x the angle from
    the free arm to the drawn arm. None: preload as given."""
    load_stop: Optional[quantity("rad", gt=0)] = None
    """Supplier data: the load stop as an angle from the free arm (> 0); the stops then become [drawn-to-load-stop,
    drawn-to-free-arm]. None: stops as given."""

    @field_validator("spring_table")
    @classmethod
    def _table(cls, v):
        return None if v is None else table_rows(v, ("rad", "N*m"), "spring_table (travel, torque)", min_rows=2)

    @model_validator(mode="after")
    def _supplier(self):
        if (self.free_torque is not None or self.load_stop is not None) and self.free_angle is None:
            raise ValueError("free_torque and load_stop are measured from the free arm: give free_angle too")
        if self.free_torque is not None and self.spring_table is not None:
            raise ValueError("give spring_table or free_torque and rate, not both")
        return self


class Slider(_Tensioner):
    """Linear tensioner: the pulley on a slide along ``direction``; with rate 0, a fixed-force
    tensioner. Travel and stops in m."""

    direction: tuple[float, float]
    """Direction [x, y] of the slide (any length, not zero); the code finds which way along it tightens the belt."""
    mass: quantity("kg", gt=0)
    """Moving mass of the slider, the pulley included."""
    preload: quantity("N", ge=0) = 0.0
    """Spring force at the drawn position (travel 0), pushing into the belt."""
    rate: quantity("N/m", ge=0) = 0.0
    """Spring rate: the force falls by rate x travel as the slider moves into the belt; 0: a constant-force tensioner."""
    damping: quantity("N*s/m", ge=0) = 0.0
    """Viscous damping of the slide (moving into the belt only, when damping_away is given)."""
    damping_away: Optional[quantity("N*s/m", ge=0)] = None
    """Viscous damping of the slide moving away from the belt, when it differs from damping: a hydraulic tensioner's
    plunger (its check valve closes as the belt pushes it back, the oil leaks out through its clearance: the high
    damping; it refills through the valve as the plunger extends: damping, the low). Under a steady load the plunger
    leaks down at the load over damping_away (a leak-down test's load x time / stroke gives it). None: damping both
    ways."""
    friction: quantity("N", ge=0) = 0.0
    """Coulomb friction force of the slide moving into the belt (away from it: x friction_asymmetry)."""
    friction_speed: quantity("m/s", gt=0) = 1e-3
    """Slider speed over which the Coulomb friction is regularised (smoothed from 0 to full)."""
    stops: tuple[Length, Length] = (-0.02, 0.02)
    """Travel [min, max] from the drawn position at which the slide's stops engage (min <= 0 <= max, positive into the
    belt)."""
    stop_stiffness: quantity("N/m", gt=0) = 1e6
    """Stiffness of the stops once the slider reaches one (a stiff penalty spring)."""
    stop_damping: quantity("N*s/m", ge=0) = 100.0
    """Viscous damping acting while the slider presses on a stop."""

    @field_validator("spring_table")
    @classmethod
    def _table(cls, v):
        return None if v is None else table_rows(v, ("m", "N"), "spring_table (travel, force)", min_rows=2)

    @field_validator("direction")
    @classmethod
    def _dir(cls, v):
        if not (v[0] ** 2 + v[1] ** 2) > 1e-24:
            raise ValueError("must be a non-zero vector [x, y]")
        return v


def free_arm_angle(center, arm) -> float:
    """Angle (rad, > 0 on the belt's side) from the drawn arm to the free arm, in the sense that
    moves the pulley into the belt (the free arm is where the spring would put it with no belt)."""
    drawn = math.atan2(center[1] - arm.pivot[1], center[0] - arm.pivot[0])
    return math.remainder(arm.free_angle - drawn, 2 * math.pi)


def _supplier_arm(name, center, arm):
    """The arm with preload and stops from its supplier data (free_angle, free_torque, load_stop)."""
    rel = abs(free_arm_angle(center, arm))         # the drawn arm's angle from the free arm
    if not rel > 1e-9:
        raise ValueError(f"pulley {name!r}: arm.free_angle {math.degrees(arm.free_angle):.6g} deg is the drawn arm's "
                         "angle: the free arm lies where the spring puts the pulley with no belt, away from the drawn "
                         "position")
    # the supplier's data rule: preload and stops follow from them (a value the file gives for them,
    # e.g. written back by drivedyn.dumps, is replaced), so that a design loop may vary free_angle,
    # free_torque, rate or load_stop alone
    upd = {}
    if arm.free_torque is not None:
        upd["preload"] = arm.free_torque + arm.rate * rel
    if arm.load_stop is not None:
        if not arm.load_stop > rel:
            raise ValueError(f"pulley {name!r}: arm.load_stop {math.degrees(arm.load_stop):.4g} deg from the free arm "
                             f"lies before the drawn arm ({math.degrees(rel):.4g} deg from it)")
        upd["stops"] = (rel - arm.load_stop, rel)
    return arm.model_copy(update=upd)


class PitchCurve(Spec):
    """A non-circular pitch curve (an oval crank sprocket, a pulley's ovality): the radius of the belt's pitch line
    against the pulley's own angle phi, counter-clockwise from the pulley's reference line, which points along +x as
    drawn (mechanics/pitch_curves.py). It turns with the pulley. ``drivedyn check`` reports the belt path on it over
    a turn; the dynamic models still run on the circle of the pulley's radius."""

    kind: Literal["oval", "table"]
    """"oval": r = radius (1 + ovality cos(order (phi - phase))), the order-th term of the curve's Fourier series (order
    2: to first order in the ovality the centred ellipse of semi-axes radius (1 +- ovality), the elliptical crank
    pulley of Actuators 14(8) 371, 2025); "table": the periodic cubic spline through ``rows``."""
    ovality: Annotated[float, Field(ge=0, lt=1)] = 0.0
    """Oval: the relative amplitude e of the radius, (r_max - r_min) / (r_max + r_min); convex (followed by a belt)
    below 1 / (order^2 + 1), 0.2 for order 2."""
    phase: quantity("rad") = 0.0
    """Oval: the pulley's own angle of a longest radius (of the first of its ``order`` long axes), counter-clockwise
    from +x as drawn."""
    order: Annotated[int, Field(ge=2, le=24)] = 2
    """Oval: the number of long axes round the curve, the order of the span lengths' modulation on the pulley's own
    turn (2: an oval, 3: a trilobe)."""
    rows: Optional[list[list]] = None
    """Table: rows [angle, radius] over one turn of the pulley's own angle ("0 deg", "30.2 mm"; numbers in rad and m),
    the angles spanning exactly 360 deg and the last radius repeating the first; the pulley's radius is the table's
    mean radius (within 0.5 %)."""

    @field_validator("rows")
    @classmethod
    def _rows(cls, v):
        if v is None:
            return None
        from ..mechanics.pitch_curves import check_table

        rows = table_rows(v, ("rad", "m"), "rows")
        check_table(rows, radius_tol=1e-6)
        return rows

    @model_validator(mode="after")
    def _kind(self):
        if self.kind == "table" and self.rows is None:
            raise ValueError('kind "table" needs rows = [[angle, radius], ...] over one turn')
        if self.kind == "oval" and self.rows is not None:
            raise ValueError('rows belong to kind = "table"; an oval is given by ovality, phase and order')
        if self.kind == "table" and (self.ovality != 0 or self.phase != 0 or self.order != 2):
            raise ValueError('ovality, phase and order belong to kind = "oval"; a table gives its rows')
        return self

    def curve(self, radius: float):
        """The mechanics/pitch_curves.py curve of a pulley of this radius."""
        from ..mechanics.pitch_curves import Oval, Table

        if self.kind == "oval":
            return Oval(radius, self.ovality, self.phase, self.order)
        return Table(self.rows)


class Pulley(Spec):
    """A pulley or idler, in belt order. Counter-clockwise is positive for angles and torques."""

    name: str
    """Name used in results, span names ("crank-alternator") and overrides; no spaces, dots, dashes or slashes."""
    center: tuple[Length, Length]
    """Position [x, y] of the pulley's axis in the drive's plane (x right, y up, as drawn)."""
    radius: quantity("m", gt=0)
    """Radius on which the belt's centre line (its pitch line, the tension member) runs: the pitch radius of the
    pulley (geometry/catalogue.py); the layout, the belt's length and the contact penetration are measured from it."""
    side: Literal["inside", "back"] = "inside"
    """Which face of the belt runs on the pulley: "inside" (the ribbed or toothed face, wrapped by the loop) or "back"
    (a backside idler outside the loop)."""
    inertia: quantity("kg*m^2", gt=0) = 1e-3
    """Moment of inertia of the pulley about its axis (of everything turning rigidly with it; a clutch's rotor is
    clutch.inertia)."""
    torque: quantity("N*m") = 0.0
    """Constant external torque on the pulley, counter-clockwise positive (a driver turning clockwise has a negative
    torque; a load opposes its rotation)."""
    torque_time: Optional[list[list]] = None
    """Torque over time as rows [time, torque], linearly interpolated and held beyond the last row; added to torque."""
    torque_speed: Optional[list[list]] = None
    """Torque over the pulley's speed as rows [speed, torque] (at least 2, speed counter-clockwise positive),
    extrapolated linearly; added to torque."""
    viscous_torque: quantity("N*m*s/rad", ge=0) = 0.0
    """Viscous load coefficient: a torque -c omega opposing the pulley's speed."""
    harmonics: list[Harmonic] = []
    """Torque components amplitude sin(order theta + phase) on the pulley's own angle theta (an accessory's pulsating
    load, e.g. a compressor)."""
    torque_angle: Optional[list[list]] = None
    """Load torque over one turn of the pulley's own angle theta as rows [angle, torque] (a camshaft's valve-train
    torque), counter-clockwise positive, linear between rows: the angles span exactly 360 deg and the last torque
    repeats the first (one period); none: no such load. Turned at load time into its mean (added to torque) and its
    harmonics (added to harmonics): its Fourier series up to order 40, the orders at least 1e-3 of the largest
    (belt/angle_torque.py; drivedyn check lists them)."""
    speed_time: Optional[list[list]] = None
    """Prescribed speed over time as rows [time, speed] (counter-clockwise positive): makes this pulley the crank,
    driven kinematically; excludes torques, loads and clutches on it."""
    speed_orders: list[SpeedOrder] = []
    """Engine orders (firing pulsation) superposed on the prescribed speed; needs speed_time."""
    drag: quantity("N*m", ge=0) = 0.0
    """Bearing drag: a Coulomb torque opposing the rotation, regularised over +-drag_speed."""
    drag_speed: quantity("rad/s", gt=0) = 1.0
    """Speed over which the bearing drag rises from 0 to its full value (regularisation of the Coulomb law)."""
    quadratic_torque: quantity("N*m*s^2/rad^2", ge=0) = 0.0
    """Quadratic load coefficient c of a pump or fan: torque -c omega |omega|."""
    power: quantity("W", ge=0) = 0.0
    """Electrical power an alternator delivers (not shaft power: the shaft takes power / efficiency), by the alternator
    law: none below cut_in_speed (955 rpm by default), rising linearly to the full at twice it; a pump or fan is
    quadratic_torque or torque_speed. A duty row's power (duty_cycle.rows) is shaft power."""
    efficiency: float = 1.0
    """Efficiency of the alternator (in (0, 1]): the shaft power is power / efficiency."""
    cut_in_speed: quantity("rad/s", gt=0) = 100.0
    """Alternator cut-in speed (100 rad/s, 955 rpm): no electrical load below it, rising linearly to the full power at
    twice it."""
    teeth: Optional[Annotated[int, Field(ge=8, le=400)]] = None
    """Grooves of a toothed pulley (with belt.teeth): its radius must be the pitch radius teeth x pitch / (2 pi)
    within 0.5 %; none: a smooth pulley or idler (friction contact, the belt's back on a back-side idler).
    The pitch radius is where the belt's tension member runs."""
    pitch_curve: Optional[PitchCurve] = None
    """A non-circular pitch curve (an oval crank sprocket, a table of radius against angle) on which ``drivedyn check``
    follows the belt path over a turn (mechanics/curve_layout.py); none: the circle of ``radius``. The dynamic models
    run on the circle of ``radius`` (the oval's mean radius) for now."""
    clutch: Optional[Clutch] = None
    """An overrunning clutch or decoupler between this pulley and its accessory's rotor; none: the loads act on the
    pulley itself."""
    arm: Optional[Arm] = None
    """A pivoted (automatic) tensioner carrying this pulley; none: the pulley's axis is fixed."""
    slider: Optional[Slider] = None
    """A linear tensioner carrying this pulley; none: the pulley's axis is fixed."""
    effective_diameter: Optional[quantity("m", gt=0)] = None
    """Effective diameter of a ribbed (poly-V) pulley, on which a catalogue belt's length is measured (ISO 9981,
    ISO 9982); none: from the belt's profile, 2 x radius - 2 h_b on a grooved pulley, + 2 h_b on a back-side one
    (geometry/catalogue.py)."""
    axial_offset: quantity("m") = 0.0
    """Axial position of the groove's centre plane from the drive's plane (geometry/alignment.py); a misaligned pulley
    bends the belt sideways into its groove."""
    misalignment: quantity("rad") = 0.0
    """Angular misalignment: the pulley's plane turned by this angle about the in-plane direction misalignment_axis
    (geometry/alignment.py)."""
    misalignment_axis: quantity("rad") = 0.0
    """In-plane direction about which the pulley's plane is turned by misalignment, from +x counter-clockwise."""

    @field_validator("name")
    @classmethod
    def _name(cls, v):
        return check_name(v, " .-/")   # dashes join pulley names into span names

    @field_validator("torque_time")
    @classmethod
    def _tt(cls, v):
        return None if v is None else table_rows(v, ("s", "N*m"), "torque_time")

    @field_validator("torque_speed")
    @classmethod
    def _ts(cls, v):
        if v is None:
            return None
        return table_rows(v, ("rad/s", "N*m"), "torque_speed (extrapolated linearly)", min_rows=2)

    @field_validator("speed_time")
    @classmethod
    def _st(cls, v):
        return None if v is None else table_rows(v, ("s", "rad/s"), "speed_time")

    @field_validator("torque_angle")
    @classmethod
    def _ta(cls, v):
        if v is None:
            return None
        from .angle_torque import check_closed

        rows = table_rows(v, ("rad", "N*m"), "torque_angle")
        check_closed(rows)
        return rows

    @property
    def angle_load(self) -> tuple[float, list[Harmonic]]:
        """(mean torque, harmonics) of ``torque_angle`` (belt/angle_torque.py); (0, []) without one."""
        if self.torque_angle is None:
            return 0.0, []
        from .angle_torque import series

        mean, hs = series(self.torque_angle)
        return mean, [Harmonic(order=k, amplitude=a, phase=p) for k, a, p in hs]

    @property
    def load_harmonics(self) -> list[Harmonic]:
        """The torque harmonics the pulley carries: ``harmonics`` and those of ``torque_angle``."""
        return list(self.harmonics) + self.angle_load[1]

    @property
    def constant_torque(self) -> float:
        """The constant torque the pulley carries: ``torque`` and the mean of ``torque_angle``."""
        return self.torque + self.angle_load[0]

    @model_validator(mode="after")
    def _excitation(self):
        if self.speed_time is not None and (self.torque != 0 or self.torque_time or self.torque_speed
                                            or self.viscous_torque or self.harmonics or self.torque_angle or self.drag
                                            or self.quadratic_torque or self.power or self.clutch):
            raise ValueError(f"pulley {self.name!r}: speed_time (prescribed speed) excludes torques, loads and clutches")
        if self.speed_orders and self.speed_time is None:
            raise ValueError(f"pulley {self.name!r}: speed_orders need a prescribed mean speed (speed_time)")
        if self.speed_orders and not any(abs(r[1]) > 0 for r in self.speed_time):
            # an engine order is a ripple on a turning crank; at a standing crank its speed term
            # would be a steady speed (cos of a constant angle), turning the crank at rest
            raise ValueError(f"pulley {self.name!r}: speed_orders on a crank whose mean speed (speed_time) is 0 "
                             "throughout: an engine order needs a turning crank")
        if not 0 < self.efficiency <= 1:
            raise ValueError(f"pulley {self.name!r}: efficiency must lie in (0, 1], got {self.efficiency}")
        if self.arm is not None and self.slider is not None:
            raise ValueError(f"pulley {self.name!r}: give arm or slider, not both")
        if (self.arm is not None or self.slider is not None) and self.speed_time is not None:
            raise ValueError(f"pulley {self.name!r}: a tensioner pulley cannot have a prescribed speed")
        if self.arm is not None:
            d = ((self.center[0] - self.arm.pivot[0]) ** 2 + (self.center[1] - self.arm.pivot[1]) ** 2) ** 0.5
            # an eccentric tensioner's pivot lies inside its pulley (a timing drive's 5 mm arm): only an arm of
            # no length, which cannot move the pulley, is refused
            if not d > 1e-3 * self.radius:
                raise ValueError(f"pulley {self.name!r}: arm.pivot lies at the pulley's centre ({d * 1e3:.3g} mm from "
                                 "it): the arm cannot move the pulley (an eccentric tensioner's pivot lies off the "
                                 "centre by its arm's length)")
            if self.arm.free_angle is not None:
                object.__setattr__(self, "arm", _supplier_arm(self.name, self.center, self.arm))
        if self.pitch_curve is not None:
            self._pitch_curve()
        return self

    def _pitch_curve(self):
        from ..mechanics.pitch_curves import check_convex

        c = self.curve
        if self.pitch_curve.kind == "table":
            mean = c.mean_radius
            if abs(mean - self.radius) > 0.005 * mean:
                raise ValueError(f"pitch_curve.rows: pulley {self.name!r}: the table's mean radius is {mean * 1e3:.4f} mm "
                                 f"but radius is {self.radius * 1e3:.4f} mm (more than 0.5 % apart): give radius = "
                                 f"\"{mean * 1e3:.4f} mm\"")
        try:
            check_convex(c)
        except ValueError as exc:
            raise ValueError(f"pitch_curve: pulley {self.name!r}: {exc}") from None

    @property
    def curve(self):
        """The pulley's pitch curve (mechanics/pitch_curves.py): its ``pitch_curve``, else the circle of ``radius``."""
        from ..mechanics.pitch_curves import Circle

        return Circle(self.radius) if self.pitch_curve is None else self.pitch_curve.curve(self.radius)

    @property
    def tensioner(self):
        return self.arm if self.arm is not None else self.slider


class FrictionZone(Spec):
    """A stretch of belt (arc length from the start of segment 0) with its own friction coefficient."""

    start: Length
    """Start of the zone: arc length along the belt from the start of segment 0."""
    end: Length
    """End of the zone: arc length along the belt from the start of segment 0 (after start)."""
    coefficient: float
    """Friction coefficient mu of belt segments in the zone, instead of friction.coefficient (>= 0)."""

    @model_validator(mode="after")
    def _order(self):
        if not self.end > self.start:
            raise ValueError(f"friction zone end ({self.end}) must be after start ({self.start})")
        if self.coefficient < 0:
            raise ValueError("friction zone coefficient must be >= 0")
        return self


class Teeth(Spec):
    """The belt's teeth (a synchronous belt): each tooth engages the grooves of every pulley that gives
    ``teeth`` (back-side idlers stay friction contacts). A tooth is a spring between the belt's tension
    member and its groove with the tooth's sideways play as a dead band; past the climb criterion of
    the wrapped belt (mechanics/teeth/loadshare.py, eq. 3: Q tan(phi - rho) >= T p / R) it climbs and
    slides over the land into the next groove, a jump the run reports. No creep: a tooth stays in its
    groove while it does not jump, so the mean speed ratio is the tooth ratio."""

    profile: str
    """Tooth profile from the catalogue (HTD8M, HTD9.525, GT2-3M, T10, L, ...; mechanics/teeth/catalogue.py): its pitch,
    and its tooth's shape for the tooth stiffness, play and flank angle left out here."""
    width: quantity("m", gt=0, le=1.0)
    """Belt width (the tooth stiffness per unit width times this)."""
    count: Optional[Annotated[int, Field(ge=10, le=2000)]] = None
    """Teeth on the belt; none: belt.length / pitch when belt.length is given (it must be a whole number of pitches),
    else the drawn path's length over the pitch, rounded."""
    tooth_stiffness: Optional[quantity("N/m", gt=0)] = None
    """Stiffness of one tooth in its groove, whole width (N per m of tangential deflection); none: from the tooth's
    shape and tooth_modulus (a Timoshenko cantilever, mechanics/teeth/loadshare.py: tooth_stiffness_per_width)."""
    tooth_modulus: quantity("Pa", gt=0) = 4.0e6
    """Shear modulus G of the tooth's rubber, for the tooth stiffness from its shape (4 MPa: chloroprene rubber of
    about 70 Shore A, G = E / 3 with E = 12 MPa; Gent, Engineering with Rubber, 3rd ed., fig. 1.5)."""
    damping_ratio: float = Field(0.05, ge=0, le=1.0)
    """Damping of a tooth on its groove as a share of the critical damping of a segment on the tooth spring."""
    play: Optional[quantity("m", ge=0)] = None
    """Sideways play of a seated tooth in its groove, the dead band of its spring; none: from the profile pair's
    exact contours (the toothed-mesh analysis's exit path, seed 001) for the smallest toothed pulley."""
    flank_angle: Optional[quantity("rad", gt=0, lt=math.pi / 2)] = None
    """Flank angle phi of the climb criterion (to the groove axis); none: from the profile pair's contours as for
    play."""
    flank_friction: float = Field(0.0, ge=0, le=2.0)
    """Friction coefficient on the flank (rho = atan of it) of the climb criterion (0, as the toothed-mesh analysis's
    load.friction; a flank angle at or below atan(flank_friction) is self-locking: no jump)."""
    nodes_per_tooth: Annotated[int, Field(ge=1, le=8)] = 1
    """Segments per belt tooth (the belt has count x nodes_per_tooth segments; one in nodes_per_tooth carries a
    tooth): 2 halves the chord between teeth, for the convergence check."""


class Belt(Spec):
    """The belt: mass, axial and bending stiffness and damping as properties per unit length (the
    segments' values follow from them, so a model means the same physics at any segment count), the
    segment count, the installation tension or the unstretched length, and its catalogue name."""

    mass_per_length: quantity("kg/m", gt=0)
    """Mass of the belt per metre of length."""
    axial_stiffness: quantity("N", gt=0)
    """Axial (tensile) stiffness EA: tension = EA x strain (to the power axial_exponent); the seed's element stiffness
    c_L is EA / l (Kubas, seed 000, eq. 9; examples/belt-5pk.toml)."""
    axial_damping: quantity("N*s", ge=0) = 0.0
    """Axial damping per unit strain rate (N s): the element damping is axial_damping / l (seed 000, b_L)."""
    bending_stiffness: quantity("N*m^2", ge=0) = 0.0
    """Bending stiffness EI of the belt: the joint stiffness between segments is bending_stiffness / l (seed 000,
    c_B)."""
    bending_damping: quantity("N*m^2*s", ge=0) = 0.0
    """Bending damping: joint damping bending_damping / l (seed 000, b_B). Below the damper that damps the segment
    chain's grid-scale rotation mode (system.GRID_ZETA, summary.discretisation.grid_damping), that damper is used."""
    axial_exponent: float = 1.0
    """Exponent e of the tension law F = EA strain^e (1: linear; in [0.5, 3]; seed 000, eq. 9)."""
    bending_exponent: float = 1.0
    """Exponent of the bending law between segments (1: linear; in [0.5, 3])."""
    segments: Union[int, Literal["auto"]] = "auto"
    """Number of rigid segments the belt is divided into (12..5000); "auto": chosen for accuracy by resolution.py (at
    most 2000)."""
    pretension: Optional[quantity("N", gt=0)] = None
    """Installation (static) tension of the belt; the unstretched length follows from the layout. Give one of
    pretension and length, or neither where the part's effective_length and a supplier tensioner install the belt."""
    length: Optional[quantity("m", gt=0)] = None
    """Unstretched length of the belt's centre line (on the pulleys' radius, not a catalogue's effective length); the
    tension follows from the layout. Give exactly one of pretension and length."""
    profile: Optional[Literal["PH", "PJ", "PK", "PL", "PM"]] = None
    """Ribbed (poly-V) profile as ISO 9982 names it (PK for automotive drives); none: not a catalogue belt."""
    ribs: Optional[Annotated[int, Field(ge=1, le=100)]] = None
    """Number of ribs (the 8 of 8PK1020)."""
    effective_length: Optional[quantity("m", gt=0)] = None
    """Nominal effective length, as the catalogue name gives it (1020 mm for 8PK1020; ISO 9982). With a supplier
    tensioner (arm.free_angle) and no pretension or length, the part installs the belt: the tensioner sits where the
    required belt length is this, and the belt there holds what the spring holds (docs/supplier-report.md)."""
    length_tolerance: quantity("m", ge=0) = 0.0
    """Tolerance +- on the effective length (the supplier's report checks the tensioner over it)."""
    wear_allowance: quantity("1", ge=0, lt=0.1) = 0.0
    """Allowance for the belt's wear and growth in service, a share of the length (0.01: 1 %)."""
    length_offset: Optional[quantity("m")] = None
    """Required belt length = effective drive length - length_offset; none: 0 (suppliers print 0 to 3.5 mm and do
    not publish their rule: give theirs to compare)."""
    teeth: Optional[Teeth] = None
    """A synchronous (toothed) belt: its teeth engage the pulleys that give ``teeth``; none: a friction belt."""

    @field_validator("segments")
    @classmethod
    def _n(cls, v):
        if v == "auto":
            return v
        # upper: the stable step falls with the segment length and the cost grows with n^2;
        # 5000 segments already run ~1000 times longer than the 150 of the examples
        if v < 12:
            raise ValueError(f"must be >= 12, got {v}")
        if v > 5000:
            raise ValueError(f"must be <= 5000, got {v}")
        return v

    @field_validator("axial_exponent", "bending_exponent")
    @classmethod
    def _e(cls, v):
        if not 0.5 <= v <= 3.0:
            raise ValueError(f"must lie in [0.5, 3], got {v}")
        return v

    @model_validator(mode="after")
    def _tension(self):
        if self.pretension is not None and self.length is not None:
            raise ValueError("give one of belt.pretension (N) or belt.length (unstretched, m), not both")
        if self.pretension is None and self.length is None and self.effective_length is None:
            raise ValueError("give belt.pretension (N), belt.length (unstretched, m), or the part's "
                             "belt.effective_length with a supplier tensioner (arm.free_angle)")
        return self

    @field_validator("teeth")
    @classmethod
    def _profile(cls, v):
        if v is not None:
            from ..mechanics.teeth import catalogue

            try:
                catalogue.canonical(v.profile)
            except ValueError as exc:
                raise ValueError(f"profile: {exc}") from None
        return v


class Contact(Spec):
    """Penalty contact (seed eqs. 9-10), coefficients per unit length of belt."""

    stiffness_linear: quantity("N/m^2", ge=0)
    """Linear contact stiffness per unit length of belt: a segment of length l pressed p into its pulley carries a
    normal force (stiffness_linear p + stiffness_quadratic p^2) l (seed 000, eq. 9: c2 = this x l)."""
    stiffness_quadratic: quantity("N/m^3", ge=0) = 0.0
    """Quadratic contact stiffness per unit length of belt (seed 000, eq. 9: c1 = this x segment length l)."""
    damping: quantity("N*s/m^2", ge=0) = 0.0
    """Contact damping per unit length of belt (seed 000, eq. 10, b = this x segment length), ramped in over
    damping_depth."""
    damping_depth: Optional[quantity("m", gt=0)] = None
    """Penetration p_max over which the contact damping ramps in (seed 000, eq. 10); none: the smallest static
    penetration at the pretension (system.damping_depth), so that a stiff contact keeps its nominal damping."""

    @model_validator(mode="after")
    def _some_stiffness(self):
        if self.stiffness_linear <= 0 and self.stiffness_quadratic <= 0:
            raise ValueError("contact needs stiffness_linear or stiffness_quadratic > 0")
        return self


class Friction(Spec):
    """Friction between belt and pulleys: the elastic-plastic law (a stuck bit of belt held by its
    cover's shear up to the displacement limit Delta_max, then sliding with mu N; docs/belt-drive.md)
    or seed 000's Threlfall regularised Coulomb law (eqs. 11-17), with its coefficient, per-zone
    coefficients, and `radius`, where the pulley's speed is read for the slip and the friction's
    moment arm: "contact" (the contact radius: classical creep theory's thin belt) or "centre" (the
    segment's centre below it: stuck belt turns with the pulley and its speed follows its depth;
    docs/belt-drive.md)."""

    law: Literal["threlfall", "elastic-plastic"] = "elastic-plastic"
    """"elastic-plastic": a stuck bit of belt held by its cover's shear up to displacement_limit, then sliding with mu
    N (docs/belt-drive.md); "threlfall": seed 000's regularised Coulomb law (eqs. 11-17)."""
    coefficient: float = 1.0
    """Friction coefficient mu between belt and pulleys (static = kinetic; a poly-V belt's apparent coefficient
    includes the wedge effect)."""
    velocity_threshold: quantity("m/s", gt=0) = 1e-5
    """Slip speed Delta_v over which Threlfall's law rises to full friction (seed 000, eq. 11)."""
    displacement_limit: quantity("m", gt=0) = 1e-4
    """Elastic displacement Delta_max of a stuck bit of belt before it slides (elastic-plastic law only)."""
    zones: list[FrictionZone] = []
    """Stretches of belt with their own friction coefficient (arc length from the start of segment 0)."""
    radius: Literal["contact", "centre"] = "contact"
    """Where the pulley's speed is read for the slip and the friction's moment arm (seed 000, eq. 12): "contact" (the
    contact radius: classical creep theory's thin belt) or "centre" (the segment's centre)."""

    @field_validator("coefficient")
    @classmethod
    def _mu(cls, v):
        if v < 0:
            raise ValueError(f"must be >= 0, got {v}")
        return v


class Simulation(Spec):
    """How the drive is simulated: for how long, which belt model (``model``: "segments", the belt
    as rigid segments, seed 000; "rotational", pulleys, rotors and tensioners with the spans as
    axial springs and creep on the wraps, docs/belt-drive.md), which integration scheme for the
    segments (``method``: "auto" takes the implicit scheme, the semi-implicit one with rotation
    scaling and for drives with tensioners, clutches or orders under Threlfall's law; ``step``;
    ``rotation_scaling``, the segments' rotational inertia x 3.3
    for a longer stable step of the semi-implicit scheme, left out (none) means on with the
    elastic-plastic friction law and off with Threlfall's), and a run-up by time integration or as
    periodic solutions per crank-speed bin (``runup``, rotational model)."""

    duration: quantity("s", gt=0) = 1.0
    """Simulated time from the start of the run."""
    model: Literal["segments", "rotational"] = "segments"
    """Belt model: "segments", the belt as a chain of rigid segments (seed 000); "rotational", pulleys, arms and
    rotors with the spans as axial springs and creep on the wraps (rotational/simulate.py; milliseconds per
    simulated second)."""
    runup: Literal["time", "periodic"] = "time"
    """A run-up by time integration of the crank's speed table ("time"), or its steady response at each crank-speed
    bin as a periodic solution ("periodic", rotational model only: periodic.py)."""
    method: Literal["auto", "implicit", "semi-implicit", "rkf45"] = "auto"
    """Integration scheme of the segments: "auto" is the implicit scheme, the semi-implicit one with rotation_scaling
    = true and for a drive with tensioners, clutches or orders under Threlfall's law; "rkf45" does not integrate
    tensioners, clutches or speed orders."""
    step: Optional[quantity("s", gt=0)] = None
    """Fixed time step; none: the stable step the scheme needs, found from the model."""
    rotation_scaling: Optional[bool] = None
    """Scale the segments' rotational inertia by 3.3 (system.ROTATION_SCALE) for a 1.3x longer stable step of the
    semi-implicit scheme; none: on with the elastic-plastic law, off with Threlfall's."""
    resolution_check: bool = False
    """Run the drive a second time at 0.7 x the segments and report the change as an estimate of the discretisation
    error (resolution.py; about 1.5 x the cost; segment model only)."""
    rtol: float = 1e-6
    """Relative error tolerance of the adaptive rkf45 scheme (other schemes ignore it)."""
    atol: float = 1e-9
    """Absolute error tolerance of the adaptive rkf45 scheme, in the state's SI units (other schemes ignore it)."""

    @model_validator(mode="after")
    def _periodic(self):
        if self.runup == "periodic" and self.model != "rotational":
            raise ValueError("runup = \"periodic\" needs model = \"rotational\" (the segment model integrates in time)")
        if self.resolution_check and self.model == "rotational":
            raise ValueError("resolution_check reruns the segment model at fewer segments: the rotational model has none")
        return self


class Output(Spec):
    """What a run records: the sampling interval, snapshots of the whole belt, the segments whose time
    series are kept, the steady window, the run-up bins and the animation."""

    interval: quantity("s", gt=0) = 1e-3
    """Sampling interval of the recorded time series."""
    frames: int = 100
    """Number of snapshots of the whole belt (every segment's state) kept for plots and the animation (1..10000)."""
    segments: list[int] = [0]
    """Indices of the segments whose time series are recorded (0 is the first segment; < belt.segments)."""
    steady_window: Optional[tuple[Time, Time]] = None
    """Time window [start, end] of the steady-state statistics (tensions, slip, hub loads); none: the last quarter of
    the run."""
    runup_bin: Optional[quantity("rad/s", gt=0)] = None
    """Width of the crank-speed bins a run-up (a crank speed table that sweeps a range) is evaluated in; none: a
    twentieth of the crank's speed range."""
    animation: bool = False
    """Write belt.gif, an animation of the belt (a few seconds to write)."""

    @model_validator(mode="after")
    def _window(self):
        if self.steady_window is not None and not self.steady_window[1] > self.steady_window[0]:
            raise ValueError("steady_window must be [start, end] with end > start")
        if not 1 <= self.frames <= 10_000:  # each frame stores every segment's state
            raise ValueError(f"frames must lie in 1..10000, got {self.frames}")
        return self


class DutyRow(Spec):
    """One row of a duty cycle: the crank's speed, the row's share of the running time, the
    accessories' loads as powers or torques (by pulley name), and the temperature."""

    crank_speed: quantity("rad/s", gt=0)
    """Crank speed of this row."""
    share: quantity("1", ge=0, le=1)
    """Share of the running time spent at this row (the rows' shares add up to 1; 0: the row is evaluated and shown,
    and carries no share of the belt's damage)."""
    power: dict[str, quantity("W", ge=0)] = {}
    """Accessory loads as shaft powers (W, at the row's speed, no cut-in; an alternator's is its electrical output /
    efficiency), by pulley name."""
    torque: dict[str, quantity("N*m", ge=0)] = {}
    """Accessory loads as torques, by pulley name (magnitudes opposing the rotation); a pulley has power or torque,
    not both."""
    temperature: Optional[float] = None
    """Ambient temperature of this row in deg C (-60..250); none: the duty cycle's temperature."""

    @field_validator("temperature")
    @classmethod
    def _t(cls, v):
        return None if v is None else _temperature(v)


def _temperature(v):
    """An ambient temperature in deg C within [-60, 250] (a rubber belt's range and more; the life
    fit's 2^((theta - theta_ref) / halving) stays within double precision over it)."""
    if not -60 <= v <= 250:
        raise ValueError(f"must lie in [-60, 250] deg C, got {v}")
    return v


class Life(Spec):
    """Belt life by rib fatigue (steady/life.py): a published fit to Gates accessory-drive reports
    (MFSim, kaydgn/MFSim js/fead-core.js, "FATIGUE", MIT licence; a fit, not the supplier's model).
    Damage rate D = [sum of w_i d_e,i^-exponent] x [sum of share x v / L] x (T_design / ribs)^
    tension_exponent x 2^((temperature - reference_temperature) / halving); B10 = constant / D
    hours, d_e in mm, v in m/s, L in m, T in N."""

    exponent: float = 5.6
    """Exponent on the effective diameter d_e (mm) in the damage rate: small pulleys dominate the damage (MFSim fit to
    Gates reports, steady/life.py; in (0, 20])."""
    back_side_weight: float = 0.31
    """Weight w of a back-side pulley against a grooved one in the damage sum (in [0, 10])."""
    tension_exponent: float = 0.96
    """Exponent on the design tension per rib T_design / ribs (N) in the damage rate (in [0, 10])."""
    constant: float = 1.475304e-4
    """Constant of the fit: B10 life (hours) = constant / damage rate (> 0)."""
    reference_temperature: float = 80.0
    """Temperature (deg C) at which the fit's life holds unchanged (in [-60, 250], the duty cycle's temperatures)."""
    halving: float = 23.0
    """Temperature rise (deg C) that halves the life (in [1, 1000]; the fit's 23: rubber's life halves every 10-25
    deg C)."""
    target: Optional[quantity("s", gt=0)] = None
    """B10 life the verdict asks for; none: the life is reported, not judged."""

    @model_validator(mode="after")
    def _positive(self):
        # the fit's domain: a constant of either sign or 0 gives no life; a halving below 1 deg C puts
        # 2^(310 / halving) past double precision over the temperatures allowed
        bounds = {"exponent": (0, 20, False), "tension_exponent": (0, 10, True), "halving": (1, 1000, True),
                  "back_side_weight": (0, 10, True), "reference_temperature": (-60, 250, True)}
        for k, (lo, hi, closed) in bounds.items():
            v = getattr(self, k)
            if not ((lo <= v if closed else lo < v) and v <= hi):
                raise ValueError(f"{k} must lie in {'[' if closed else '('}{lo:g}, {hi:g}], got {v:g}")
        if not self.constant > 0:
            raise ValueError(f"constant must be > 0, got {self.constant:g}")
        return self


class DutyCycle(Spec):
    """The duty cycle a supplier's report evaluates: rows of crank speed, share of time and
    accessory loads (steady/duty.py), the drag the supplier puts on every idler and tensioner
    pulley, the temperature and the belt-life fit."""

    rows: list[DutyRow]
    """The duty cycle's rows: crank speed, share of time, accessory loads and temperature."""
    idler_drag: quantity("W", ge=0) = 10.0
    """Drag power put on each pulley without a declared load, idlers and tensioner pulleys (Gates: 0.01 kW)."""
    acceleration: Optional[quantity("rad/s^2", gt=0)] = None
    """The crank's acceleration and deceleration under which the slip factors are checked, with each pulley's inertia,
    at part_load and at full accessory load (the rows' largest); none: not checked."""
    part_load: quantity("1", gt=0, le=1) = 0.1
    """Part accessory load of the acceleration check, a share of the full load."""
    dynamic: bool = False
    """Also evaluate each row from the dynamics: the rotational model held at the row (supplier.py), the crank's speed
    orders included: mean and peak hub loads, span tension bands, the arm's travel against its stops, slip margins
    (about a second per row)."""
    tolerance: bool = False
    """The tolerance study: the duty cycle at every reachable position-table row (replaced, longest, nominal and
    shortest belt), both conventions (supplier.py; about half a second per row)."""
    temperature: float = 80.0
    """Ambient temperature in deg C of every row that gives none (-60..250)."""
    life: Life = Life()
    """The belt-life fit (rib fatigue) and its target."""

    @field_validator("temperature")
    @classmethod
    def _t(cls, v):
        return _temperature(v)

    @model_validator(mode="after")
    def _rows(self):
        if not self.rows:
            raise ValueError("rows: a duty cycle needs at least one row")
        total = sum(r.share for r in self.rows)
        if not 0.98 <= total <= 1.02:
            raise ValueError(f"rows: the shares add up to {100 * total:.4g} %, not 100 %")
        return self

    @model_validator(mode="before")
    @classmethod
    def _cost(cls, data):
        """The cost before the work, counted before the rows are read (10 000 rows take seconds to
        read): each row's running balance, again at each of the tolerance study's four belt lengths
        (a held dynamic row's steps are counted when the drive is assembled, supplier.py)."""
        from ..core.limits import balances_problem

        if not isinstance(data, dict) or not isinstance(data.get("rows"), list):
            return data
        n, tolerance = len(data["rows"]), data.get("tolerance") is True
        problem = balances_problem(n * (1 + 4 * tolerance), "rows", f"{n} rows" + (
            " x 5 (the duty cycle and the tolerance study's four belt lengths)" if tolerance else "")
            + ": fewer rows" + (", or tolerance = false" if tolerance else ""))
        if problem:
            raise ValueError(problem)
        return data


class Criteria(Spec):
    """Limits the verdict judges a belt run against (every field optional)."""

    slip_max: limit("1", "a slip of 1 is a belt standing still on its pulley: it can never fail", gt=0, lt=1) = 0.02
    """Largest slip of any pulley allowed (a fraction: 0.02 = 2 %)."""
    slip_margin_min: limit("1", "below 1 it accepts a wrap that slips by the capstan equation", ge=1) = 1.3
    """Smallest slip margin of a pulley that carries torque (the torque the wrap could carry over the torque it
    carries; docs/criteria.md)."""
    gross_slip_max: Annotated[int, Field(ge=0)] = 0
    """Pulleys allowed in gross slip (the gross-slip diagnostic of either model), the driver included: slip is
    measured against the driver, so a driving pulley's own gross slip shows only here."""
    span_tension_min: quantity("N", ge=0) | None = None
    """Smallest span tension allowed, T - m v^2 (the tension left for the wraps); none: 0.1 x belt.pretension."""
    stop_clearance_min: quantity("1", ge=0, lt=0.5) = 0.1
    """Free travel kept at each tensioner stop, a share of the stop-to-stop travel (< 0.5)."""
    hub_load_max: quantity("N", gt=0) | None = None
    """Bearing limit on the peak hub load of any pulley; none: not judged."""
    jump_margin_min: quantity("1", ge=0) = 1.0
    """Synchronous belt: smallest hold over outward push of any tooth in mesh (the climb criterion of
    mechanics/teeth/loadshare.py, eq. 3; below 1 a tooth climbs out of its groove). 1 is the onset, no safety factor:
    give one of your own."""
    tooth_jumps_max: Annotated[int, Field(ge=0)] = 0
    """Synchronous belt: teeth that may change groove (jump) during the run."""
    tooth_load_max: quantity("N", gt=0) | None = None
    """Synchronous belt: the rated load of one tooth, whole width (the belt maker's); none: not judged."""
    phase_error_max: quantity("rad", gt=0) | None = None
    """Synchronous belt: the largest peak-to-peak transmission (phase) error of a grooved pulley against the first
    grooved pulley (the crank), in the crank's angle, over the steady window (a valve timing's tolerance, the
    engine maker's); none: not judged."""
    flap_crossings_max: Annotated[int, Field(ge=0)] = 0
    """Crossings of a span's first transverse (flap) mode by an excited order allowed in the run's speed range."""
    flap_speed_margin: quantity("1", ge=0, lt=1) = 0.1
    """The run's speed range widened by this share each way for the flap check."""
    flap_orders: list[float] = []
    """Orders of the crank to judge besides its declared speed orders (each in (0, 1000])."""
    flap_amplitude_min: quantity("rad/s", ge=0) = 0.0
    """Declared speed orders weaker than this speed amplitude are not judged."""
    flap_damping_ratio: quantity("1", gt=0, lt=1) = 0.02
    """Damping ratio of a span's first flap mode: sets the parametric threshold (tension modulation above 4 x it)
    and the direct response's size at resonance (assumed: 1-3 % is the usual range for belt spans; measure it
    when a crossing sits near the threshold)."""
    parametric_spans_max: Annotated[int, Field(ge=0)] = 0
    """Spans allowed inside a parametric-resonance tongue of their own (the run's tension fluctuation at the
    frequency and depth where the span's transverse motion grows: seed 002, Mathieu and Floquet with
    flap_damping_ratio; docs/criteria.md)."""
    resonance_crossings_max: Annotated[int, Field(ge=0)] | None = None
    """Crossings of the drive's rotational modes by excited orders allowed; none: listed, not judged."""
    entry_angle_max: limit("rad", "an entry angle is less than 90 deg: a larger limit can never fail", gt=0,
                           lt=0.5 * math.pi) = 0.9 * math.pi / 180
    """Largest entry angle of the belt on a pulley from offsets and misalignment (judged when any is given): Gates'
    limit for PK belts on grooved pulleys, 0.9 deg (chirp begins near 0.33 deg: Meckstroth et al., SAE
    1999-01-1709)."""

    @field_validator("flap_orders")
    @classmethod
    def _orders(cls, v):
        bad = [o for o in v if not (math.isfinite(o) and 0 < o <= 1000)]
        if bad:     # a negative order was accepted and never judged
            raise ValueError(f"orders must lie in (0, 1000], got {bad}")
        return v


class Model(Spec):
    """A belt drive: belt, pulleys in belt order, contact, friction, simulation and output."""

    kind: Literal["belt-drive"]
    """The kind of model file: "belt-drive"."""
    schema_version: Literal[1] = 1
    """Version of the model-file format (1)."""
    name: str = ""
    """A name for the drive, shown in reports."""
    belt: Belt
    """The belt: mass, stiffness, damping, segments, tension or length, catalogue name."""
    pulleys: list[Pulley]
    """Pulleys and idlers in the order the belt passes them round its loop (at least 2; the spans are named
    "from-to" in this order)."""
    contact: Contact
    """Penalty contact between belt and pulleys (seed 000, eqs. 9-10)."""
    friction: Friction = Friction()
    """Friction law between belt and pulleys."""
    gravity: quantity("m/s^2") = 9.81
    """Gravitational acceleration on the belt segments, acting along -y (0: none)."""
    simulation: Simulation = Simulation()
    """How long and how the drive is simulated."""
    output: Output = Output()
    """What the run records and writes."""
    criteria: Criteria = Criteria()
    """Design limits of the verdict (criteria.py, docs/criteria.md)."""
    duty_cycle: Optional[DutyCycle] = None
    """The supplier report's duty cycle (steady/duty.py); none: no supplier report."""

    @model_validator(mode="after")
    def _pulleys(self):
        if len(self.pulleys) < 2:
            raise ValueError("pulleys: a belt drive needs at least 2 pulleys")
        names = [p.name for p in self.pulleys]
        dup = {n for n in names if names.count(n) > 1}
        if dup:
            raise ValueError(f"pulleys: duplicate name(s) {sorted(dup)}")
        if not any(p.side == "inside" for p in self.pulleys):
            raise ValueError("pulleys: at least one pulley must be inside the belt loop")
        for q in self.output.segments:
            if q < 0:
                raise ValueError(f"output.segments: index {q} is negative (segments count from 0)")
            if self.belt.segments != "auto" and q >= self.belt.segments:     # "auto": checked once resolved
                raise ValueError(f"output.segments: index {q} outside 0..{self.belt.segments - 1}")
        if self.simulation.method == "rkf45" and _accessory_parts(self.pulleys):
            raise ValueError("simulation.method: rkf45 does not integrate tensioners, clutches or speed orders; "
                             "use semi-implicit or implicit")
        if self.output.steady_window is not None and self.output.steady_window[1] > self.simulation.duration * (1 + 1e-9):
            raise ValueError("output.steady_window ends after simulation.duration")
        self._teeth()
        self._pivots()
        self._clutch_on_driver()
        self._reversing()
        self._cost()
        self._duty_names(names)
        self._duty_bounds()
        return self

    def _teeth(self):
        """A toothed belt and its pulleys: grooves only with belt.teeth, on the inside of the loop, a
        pitch radius that fits the groove count, a belt length of whole teeth."""
        teeth = self.belt.teeth
        for k, q in enumerate(self.pulleys):
            if q.teeth is None:
                continue
            if teeth is None:
                raise ValueError(f"pulleys[{k}].teeth: pulley {q.name!r} has {q.teeth} grooves but the belt has no teeth "
                                 "(give [belt.teeth] for a synchronous belt, or leave teeth out for a smooth pulley)")
            if q.side == "back":
                raise ValueError(f"pulleys[{k}].teeth: pulley {q.name!r} runs on the belt's back, which has no teeth "
                                 "(a back-side idler is smooth: leave teeth out)")
        if teeth is None:
            return
        from ..mechanics.teeth import catalogue

        pitch = catalogue.entry(teeth.profile).pitch
        if not any(q.teeth for q in self.pulleys):
            raise ValueError("belt.teeth: no pulley has grooves (give teeth = N on the pulleys the belt's teeth engage)")
        for k, q in enumerate(self.pulleys):
            if q.teeth is None:
                continue
            if q.pitch_curve is not None:      # the curve's length holds the teeth
                per = q.curve.perimeter
                if abs(per - q.teeth * pitch) > 0.005 * q.teeth * pitch:
                    fit = max(round(per / pitch), 1)
                    fits = f"{fit} grooves fit, or " if abs(per - fit * pitch) <= 0.005 * fit * pitch else ""
                    scale = (f"a radius of {q.radius * q.teeth * pitch / per * 1e3:.4f} mm" if q.pitch_curve.kind == "oval"
                             else f"the table's radii x {q.teeth * pitch / per:.6f}")
                    raise ValueError(f"pulleys[{k}].teeth: pulley {q.name!r} has {q.teeth} grooves of the {teeth.profile} "
                                     f"pitch {pitch * 1e3:.4g} mm, {q.teeth * pitch * 1e3:.4f} mm of pitch line, but its "
                                     f"pitch curve is {per * 1e3:.4f} mm long (more than 0.5 % apart): {fits}{scale} "
                                     "fits the grooves")
                continue
            r = q.teeth * pitch / (2 * math.pi)
            if abs(q.radius - r) > 0.005 * r:
                raise ValueError(f"pulleys[{k}].radius: pulley {q.name!r} has {q.teeth} grooves of the {teeth.profile} "
                                 f"pitch {pitch * 1e3:.4g} mm, a pitch radius of {r * 1e3:.4f} mm, but radius "
                                 f"{q.radius * 1e3:.4f} mm (more than 0.5 % apart): give the pitch radius, or the "
                                 "groove count that fits")
        if self.belt.length is not None:
            n = self.belt.length / pitch
            if abs(n - round(n)) > 1e-3:
                raise ValueError(f"belt.length: {self.belt.length * 1e3:.6g} mm is {n:.4f} pitches of "
                                 f"{pitch * 1e3:.4g} mm, not a whole number of teeth "
                                 f"({round(n)} teeth are {round(n) * pitch * 1e3:.6g} mm)")
            if teeth.count is not None and round(n) != teeth.count:
                raise ValueError(f"belt.teeth.count: {teeth.count} teeth of {pitch * 1e3:.4g} mm are "
                                 f"{teeth.count * pitch * 1e3:.6g} mm, but belt.length is {self.belt.length * 1e3:.6g} mm")
        if self.simulation.method in ("implicit", "rkf45"):
            raise ValueError(f"simulation.method: a toothed belt runs with the semi-implicit scheme (its teeth are "
                             f"explicit springs), not {self.simulation.method!r}")
        if self.belt.segments != "auto":
            raise ValueError("belt.segments: a toothed belt has teeth.count x teeth.nodes_per_tooth segments; leave "
                             "segments out (or \"auto\")")

    def _pivots(self):
        """A tensioner arm's pivot inside another pulley (its own is checked with the pulley) was
        accepted and the arm drawn through that pulley."""
        for k, p in enumerate(self.pulleys):
            if p.arm is None:
                continue
            for q in self.pulleys:
                d = math.hypot(p.arm.pivot[0] - q.center[0], p.arm.pivot[1] - q.center[1])
                if q is not p and not d > q.radius:
                    raise ValueError(f"pulleys[{k}].arm.pivot: the arm pivot of pulley {p.name!r} lies inside pulley "
                                     f"{q.name!r} ({d * 1e3:.4g} mm from its centre, radius {q.radius * 1e3:.4g} mm)")

    def _reversing(self):
        """A periodic run-up holds the crank at speeds of one direction; a speed table that changes
        sign turns the crank both ways, which is no run-up (it was swept as |speed| in the table's
        last direction, or refused with a message about its spin-up)."""
        if self.simulation.runup != "periodic":
            return
        for k, p in enumerate(self.pulleys):
            w = [r[1] for r in p.speed_time or ()]
            if w and min(w) < 0 < max(w):
                first = next(r for r in p.speed_time if r[1] != 0)
                turn = next(r for r in p.speed_time if r[1] * first[1] < 0)
                raise ValueError(f"pulleys[{k}].speed_time: pulley {p.name!r} reverses (its speed changes sign: "
                                 f"{first[1]:.4g} rad/s at {first[0]:.4g} s, {turn[1]:.4g} rad/s at {turn[0]:.4g} s): "
                                 "runup = \"periodic\" sweeps "
                                 "a crank turning one way; a reversing drive is integrated in time (runup = \"time\")")

    def _duty_names(self, names):
        if self.duty_cycle is None:
            return
        # the crank (a prescribed speed) takes no load of its own: the rows set its speed and it
        # delivers what the others take (steady/duty.py), so a load on it would change nothing
        driven = [p.name for p in self.pulleys if p.speed_time is None]
        for k, row in enumerate(self.duty_cycle.rows):
            for what in ("power", "torque"):
                for n in getattr(row, what):
                    if n in names and n not in driven:
                        raise ValueError(f"duty_cycle.rows[{k}].{what}: pulley {n!r} is the crank (its speed is "
                                         "prescribed, speed_time): it delivers what the other pulleys take and carries "
                                         f"no load of its own (loaded pulleys: {', '.join(driven)})")
                    if n not in names:
                        raise ValueError(f"duty_cycle.rows[{k}].{what}: no pulley named {n!r} (have: {', '.join(driven)})")
            both = set(row.power) & set(row.torque)
            if both:
                raise ValueError(f"duty_cycle.rows[{k}]: give power or torque for {sorted(both)}, not both")

    def _duty_bounds(self):
        """A duty row's speed and loads, and the cycle's acceleration, within what a belt can be: its
        belt speed below the belt's longitudinal wave speed c = sqrt(EA / m), at which the centrifugal
        tension m v^2 alone equals EA (the belt stretched by its own length), and the span force a
        load or the acceleration asks (P / v, M / r, sum J alpha r_c / r^2) below EA. Past either no belt and no model of one holds (a 1e29 rpm row was solved and
        marked "no running balance"); within them creep theory says what the row carries."""
        if self.duty_cycle is None:
            return
        crank = next((p for p in self.pulleys if p.speed_time is not None), None)
        if crank is None:
            return
        ea, m = self.belt.axial_stiffness, self.belt.mass_per_length
        c = math.sqrt(ea / m)
        radius = {p.name: p.radius for p in self.pulleys}
        alpha = self.duty_cycle.acceleration
        if alpha is not None:
            # the belt force that speeds every other pulley up with the crank: sum J_n alpha r_c / r_n^2
            force = sum(p.inertia * alpha * crank.radius / p.radius ** 2 for p in self.pulleys if p is not crank)
            if force >= ea:
                raise ValueError(f"duty_cycle.acceleration: {alpha * 30 / math.pi:.4g} rpm/s of the crank asks the belt "
                                 f"for {force:.3g} N to speed the other pulleys up with it (their inertias), not below "
                                 f"its axial stiffness EA = {ea:.4g} N (a span stretched by its own length)")
        for k, row in enumerate(self.duty_cycle.rows):
            v = row.crank_speed * crank.radius
            if v >= c:
                raise ValueError(f"duty_cycle.rows[{k}].crank_speed: {row.crank_speed * 30 / math.pi:.4g} rpm runs the "
                                 f"belt at {v:.3g} m/s on the crank's {crank.radius * 1e3:.4g} mm radius, not below the "
                                 f"{c:.4g} m/s (sqrt(EA / m)) at which its centrifugal tension m v^2 alone would "
                                 "stretch it by its own length")
            for what, load in (("power", row.power), ("torque", row.torque)):
                for n, x in load.items():
                    force = x / v if what == "power" else x / radius.get(n, math.inf)
                    if force >= ea:
                        unit = "W" if what == "power" else "N*m"
                        raise ValueError(f"duty_cycle.rows[{k}].{what}: {x:.4g} {unit} on pulley {n!r} asks the belt "
                                         f"for a span force of {force:.3g} N at {row.crank_speed * 30 / math.pi:.4g} "
                                         f"rpm, not below its axial stiffness EA = {ea:.4g} N (a span stretched by its "
                                         "own length)")

    def _clutch_on_driver(self):
        """An overrunning clutch or decoupler carries drive from the belt into an accessory; on the
        pulley that drives the belt (no prescribed speed: the largest applied torque) it would
        never pass that torque on, and the drive would stand still with status success."""
        if any(p.speed_time is not None for p in self.pulleys):
            return
        peak = [max([abs(p.torque)] + [abs(r[1]) for r in (p.torque_time or [])]) for p in self.pulleys]
        drv = max(range(len(peak)), key=peak.__getitem__)
        p = self.pulleys[drv]
        if p.clutch is not None and peak[drv] > 0:
            raise ValueError(f"pulleys[{drv}].clutch: pulley {p.name!r} drives the belt (the largest applied torque, "
                             f"{peak[drv]:g} N*m), and a {p.clutch.type} clutch only carries drive from the belt "
                             "into an accessory: it would never pass this torque on")

    def _cost(self):
        """Samples, frames and run-up bins known from the model: refuse what would not fit."""
        from ..core.limits import bytes_problem

        sim, out = self.simulation, self.output
        samples = sim.duration / out.interval
        nk, na = len(self.pulleys), sum(p.tensioner is not None for p in self.pulleys)
        # the recorder's doubles per sample (simulate._Recorder), about three times over once the
        # Dataset, its derived variables and the netCDF writer hold copies
        per_sample = 8 * (8 * nk + 2 * na + 2 * nk + 3 * len(out.segments) + 9)
        frames = min(out.frames, samples)

        segments = MAX_AUTO if self.belt.segments == "auto" else self.belt.segments    # "auto": its upper bound
        nbytes = 3 * (samples * per_sample + frames * 5 * 8 * segments)
        problem = bytes_problem(nbytes, "output.interval", f"{samples:.3g} samples of {out.interval:.3g} s over "
                                f"{sim.duration:.3g} s: a longer output.interval or a shorter simulation.duration")
        if problem:
            raise ValueError(problem)
        if out.interval < 1e-9:
            raise ValueError(f"output.interval: {out.interval:.3g} s is shorter than any belt step (at least 1e-9 s)")
        if out.runup_bin is not None:
            speeds = [abs(r[1]) for p in self.pulleys if p.speed_time is not None for r in p.speed_time]
            if speeds:
                bins = (max(speeds) - min(speeds)) / out.runup_bin
                if bins > 10_000 or bins > samples / 4:
                    raise ValueError(f"output.runup_bin: {out.runup_bin:.3g} rad/s makes {bins:.3g} bins of the crank's "
                                     f"speed range, more than {min(10_000, samples / 4):.4g} (at most 10 000, and 4 "
                                     "samples per bin): a wider bin")
        if sim.step is not None:
            from ..core.limits import steps_problem

            problem = steps_problem(sim.duration / min(sim.step, out.interval), "simulation.step",
                                    "a longer step, or leave step out for the stable one")
            if problem:
                raise ValueError(problem)


def integrator(model) -> str:
    """The belt integration scheme a run uses: ``simulation.method``, where "auto" (the default)
    is the implicit scheme (its step set by the contact's normal mode and the turn per step,
    system.TURN_PER_STEP, not by the chain's stiff modes), except for a run that asks for
    rotation scaling (a semi-implicit device) and for a drive with tensioners, clutches or speed
    orders under Threlfall's law: its viscous anchors change between sticking and sliding at
    nearly every step, so there the implicit scheme is slower than the semi-implicit one.
    It integrates tensioners, clutches and speed orders (tests/belt/test_implicit.py against the
    semi-implicit reference); on examples/fead-runup.toml's drive (elastic-plastic law) held at
    1000 / 3000 / 5000 rpm at the "auto" resolution it took 1.2 / 2.3 / 3.5 s against 2.9 / 3.1 /
    3.0 s (benchmarks/bench_fead_schemes.py), its whole run-up 15.8 against 22.0 s, and its cost
    grows with the segments as n^0.95 against the semi-implicit scheme's n^2.1 (docs/belt-drive.md)."""
    method = model.simulation.method
    if method != "auto":
        return method
    if model.belt.teeth is not None:
        return "semi-implicit"      # the teeth are explicit springs (segments/_teeth.py)
    if any(p.pitch_curve is not None for p in model.pulleys):
        return "semi-implicit"      # the contact on a turning curve (segments/_curves.py)
    if model.simulation.rotation_scaling is True:
        return "semi-implicit"
    if model.friction.law == "threlfall" and _accessory_parts(model.pulleys):
        return "semi-implicit"
    return "implicit"


def _accessory_parts(pulleys) -> bool:
    """Whether the drive has tensioners, clutches or speed orders (which rkf45 does not integrate)."""
    return any(p.tensioner is not None or p.clutch is not None or p.speed_orders for p in pulleys)
