"""Belt-tooth and pulley-groove shapes, each built exactly from its defining dimensions.

Frames (all lengths in metres):

- belt tooth, frame {O_p} of the seed: ``u`` along the belt (positive in the direction of motion,
  so ``u > 0`` is the *leading* flank), ``v`` normal to the belt, positive towards the belt back.
  The pitch line (cord) is ``v = 0``, the land ``v = -a`` (a = pitch-line differential, PLD), the
  tip ``v = -a - h``.
- groove, frame {O_k} of the seed: origin at the pulley axis, groove axis along +y, outside
  circle of radius ``r_o``; ``x > 0`` is the groove's right half.

Each shape returns the *right half* of its contour as points, ordered from the axis outwards
(tooth: tip -> land; groove: bottom -> outside circle); :func:`contour.mirror_half` makes the
whole. The catalogue (catalogue.py) holds the numbers and their sources.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .contour import arc, arc_angles, circle_circle, fillet_line_circle, fillet_lines, join, line_circle

_DOWN = np.array([0.0, -1.0])
_RIGHT = np.array([1.0, 0.0])


@dataclass(frozen=True)
class Tooth:
    """Common data of a belt tooth: pitch, height, PLD, belt thickness and where they come from."""

    pitch: float
    height: float
    pld: float
    thickness: float = 0.0
    source: str = ""
    name: str = "custom"

    @property
    def land(self) -> float:
        """v of the land (belt underside between teeth)."""
        return -self.pld

    @property
    def tip(self) -> float:
        """v of the tooth tip."""
        return -self.pld - self.height


@dataclass(frozen=True)
class TrapezoidalTooth(Tooth):
    """ISO 5296 / DIN 7721 tooth: straight flanks of included angle ``angle``, width ``width`` at
    the land, tip radius and root fillet radius (ISO 5296 table 1 symbols 2beta, s, ra, rr)."""

    width: float = 0.0
    angle: float = np.radians(40)
    tip_radius: float = 0.0
    root_radius: float = 0.0

    def half(self, tol):
        b = self.angle / 2
        land_pt = np.array([self.width / 2, self.land])
        d_flank = np.array([-np.sin(b), -np.cos(b)])  # from the land down towards the tip
        tip_pt = np.array([0.0, self.tip])
        pieces = [tip_pt[None]]
        if self.tip_radius > 0:  # convex corner: centre inside the tooth
            c, t_tip, t_fl = fillet_lines(tip_pt, _RIGHT, +1, land_pt, d_flank, -1, self.tip_radius)
            pieces += [t_tip[None], arc(c, self.tip_radius, t_tip, t_fl, tol)]
        else:
            pieces.append(land_pt + d_flank * (self.height / np.cos(b)))
        if self.root_radius > 0:  # concave corner: centre below the land, outside the tooth
            c, t_fl, t_land = fillet_lines(land_pt, d_flank, +1, land_pt, _RIGHT, -1, self.root_radius)
            pieces += [t_fl[None], arc(c, self.root_radius, t_fl, t_land, tol)]
        else:
            pieces.append(land_pt[None])
        return join(*pieces)


@dataclass(frozen=True)
class ArcTooth(Tooth):
    """HTD tooth (curvilinear, ISO 13050 system H as drawn in FCG): one arc of radius
    ``arc_radius`` centred on the tooth axis ``arc_radius`` above the tip, plus root fillets."""

    arc_radius: float = 0.0
    root_radius: float = 0.0

    def half(self, tol):
        o = np.array([0.0, self.tip + self.arc_radius])
        tip_pt = np.array([0.0, self.tip])
        if self.root_radius > 0:
            c, t_land, t_circ = fillet_line_circle((0.0, self.land), _RIGHT, -1, o, self.arc_radius, True,
                                                   self.root_radius, pick=lambda q: q[0])
            return join(arc(o, self.arc_radius, tip_pt, t_circ, tol, ccw=True),
                        arc(c, self.root_radius, t_circ, t_land, tol))
        x = line_circle((0.0, self.land), _RIGHT, o, self.arc_radius, pick=lambda q: q[0])
        return arc(o, self.arc_radius, tip_pt, x, tol, ccw=True)


@dataclass(frozen=True)
class GTTooth(Tooth):
    """Gates PowerGrip GT tooth (ISO 13050 system G as drawn in FCG): a tip arc centred on the
    tooth axis, flank arcs whose centres lie on the pitch line ``flank_offset`` to the other side
    of the axis, and root fillets. Tip and flank arcs are joined where they intersect."""

    tip_radius: float = 0.0
    flank_radius: float = 0.0
    flank_offset: float = 0.0
    root_radius: float = 0.0

    def half(self, tol):
        t = np.array([0.0, self.tip + self.tip_radius])
        f = np.array([-self.flank_offset, 0.0])
        tip_pt = np.array([0.0, self.tip])
        x = circle_circle(t, self.tip_radius, f, self.flank_radius, pick=lambda q: -q[1])
        c, t_land, t_circ = fillet_line_circle((0.0, self.land), _RIGHT, -1, f, self.flank_radius, True,
                                               self.root_radius, pick=lambda q: q[0])
        return join(arc(t, self.tip_radius, tip_pt, x, tol, ccw=True),
                    arc(f, self.flank_radius, x, t_circ, tol, ccw=True),
                    arc(c, self.root_radius, t_circ, t_land, tol))


@dataclass(frozen=True)
class PolylineTooth(Tooth):
    """A user tooth given as right-half points (distance from the axis, depth below the land),
    from the tip on the axis to the land."""

    points: tuple = field(default_factory=tuple)

    def half(self, tol):
        pts = np.asarray(self.points, float)
        return np.column_stack([pts[:, 0], self.land - pts[:, 1]])


# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Groove:
    """Common data of a standard groove: pitch, depth below the outside circle, PLD of the pulley
    (outside radius = pitch radius - pld) and the source."""

    pitch: float
    depth: float
    pld: float
    source: str = ""
    name: str = "custom"


@dataclass(frozen=True)
class TrapezoidalGroove(Groove):
    """ISO 5294 / DIN 7721-2 groove: flat bottom of width ``bottom_width``, straight flanks at
    ``angle`` to the groove axis (half-angle), bottom fillets and tip radius (ISO 5294 symbols bw,
    hg, phi, rb, rt)."""

    bottom_width: float = 0.0
    angle: float = np.radians(20)
    bottom_radius: float = 0.0
    tip_radius: float = 0.0

    def half(self, r_o, tol):
        yb = r_o - self.depth
        bot = np.array([0.0, yb])
        corner = np.array([self.bottom_width / 2, yb])
        d_fl = np.array([np.sin(self.angle), np.cos(self.angle)])  # up and outwards
        pieces = [bot[None]]
        if self.bottom_radius > 0:  # concave corner of the pulley: centre inside the groove
            c, t_b, t_f = fillet_lines(bot, _RIGHT, +1, corner, d_fl, +1, self.bottom_radius)
            pieces += [t_b[None], arc(c, self.bottom_radius, t_b, t_f, tol)]
        else:
            pieces.append(corner[None])
        pieces.append(_tip(corner, d_fl, r_o, self.tip_radius, tol))
        return join(*pieces)


@dataclass(frozen=True)
class ArcGroove(Groove):
    """HTD groove (CS/NS tables): a bottom arc of radius ``bottom_radius`` centred on the groove
    axis, straight flanks at ``angle`` to the axis through the width ``width`` at the outside
    circle, and tip radius. Where the tip radius leaves no straight flank (HTD 8M/14M), the tip
    fillet joins the bottom arc directly; the width is then only approximate."""

    width: float = 0.0
    angle: float = np.radians(14)
    bottom_radius: float = 0.0
    tip_radius: float = 0.0

    def half(self, r_o, tol):
        rb = self.bottom_radius
        b = np.array([0.0, r_o - self.depth + rb])
        bot = np.array([0.0, r_o - self.depth])
        x_od = self.width / 2
        p_od = np.array([x_od, np.sqrt(r_o ** 2 - x_od ** 2)])
        d_fl = np.array([np.sin(self.angle), np.cos(self.angle)])
        x = line_circle(p_od, d_fl, b, rb, pick=lambda q: q[1])
        tip = _tip(x, d_fl, r_o, self.tip_radius, tol)
        if np.dot(tip[0] - x, d_fl) >= 0:
            return join(arc(b, rb, bot, x, tol, ccw=True), tip)
        # no straight flank left: fillet between the bottom arc and the outside circle
        rt = self.tip_radius
        c = circle_circle((0.0, 0.0), r_o - rt, b, rb + rt, pick=lambda q: q[1])
        t_b = b + (c - b) * rb / (rb + rt)
        t_o = c * r_o / (r_o - rt)
        return join(arc(b, rb, bot, t_b, tol, ccw=True), arc(c, rt, t_b, t_o, tol))


def _tip(p_flank, d_flank, r_o, rt, tol):
    """The groove flank's end at the outside circle: tip fillet (centre in the pulley, inside the
    outside circle) or the plain intersection with it. Starts at the flank's tangent point."""
    if rt > 0:
        c, t_f, t_o = fillet_line_circle(p_flank, d_flank, -1, (0.0, 0.0), r_o, False, rt, pick=lambda q: q[1])
        return join(t_f[None], arc(c, rt, t_f, t_o, tol))
    return line_circle(p_flank, d_flank, (0.0, 0.0), r_o, pick=lambda q: q[1])[None]


def rim(end, r_o, z, tol):
    """Outside-circle arc from the groove's end point to the middle between two grooves."""
    half_pitch = np.pi / z
    a0 = np.arctan2(end[1], end[0])
    a1 = np.pi / 2 - half_pitch
    if a0 < a1:
        raise ValueError("groove wider than the pitch")
    return arc_angles((0.0, 0.0), r_o, a0, a1, tol)


def groove_cell(groove, r_o, z, tol):
    """The outline of one pitch of the pulley (groove on +y, rims to +-pi/z), left to right."""
    from .contour import mirror_half

    half = groove.half(r_o, tol)
    return mirror_half(join(half, rim(half[-1], r_o, z, tol)))


def tooth_outline(tooth, tol):
    """The tooth contour from the trailing land end through the tip to the leading land end."""
    from .contour import mirror_half

    return mirror_half(tooth.half(tol))

