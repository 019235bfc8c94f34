"""The belt path on convex pitch curves (mechanics/pitch_curves.py) at given pulley angles: spans as the
common tangents of the curves, wraps, arc lengths, belt length and the effective radii.

The conventions are mechanics/layout.py's: each pulley has a sense sigma = +1 when the belt goes round
it counter-clockwise (a pulley inside a counter-clockwise loop), -1 otherwise; a span of travel
direction t = (cos beta, sin beta) has the left normal n = (-sin beta, cos beta) and touches pulley A
where A's outward normal points along -sigma_A n. With h_A(u) the support function of A's curve
(the distance from its centre of its tangent line of outward normal u, Schneider, Convex Bodies,
sec. 1.7), the span's line n . x = c touches A and B when

    F(beta) = n . (C_B - C_A) - sigma_B h_B(-sigma_B n) + sigma_A h_A(-sigma_A n) = 0,

which for circles (h = r, sigma r = rho) is layout.py's sin(gamma - beta) = (rho_B - rho_A) / d. The
derivative of a support function is the support point (dh/du = q, the envelope theorem), so that
F'(beta) = -t . (p_B - p_A) = -L, the span's length: Newton's method beta <- beta + F / L from the
circle solution at the curves' mean radii converges in a few steps and to round-off, each step two
support points (pitch_curves.support, itself a bracketed Newton on the curve's own angle).

On a wrap the travel direction turns by the wrap angle w (the normal's turn), and the own angle of the
touching point moves by sigma w + mu_out - mu_in (mu = atan2(r', r), the angle between the radius and
the normal); the arc is that stretch of the curve's length. The effective radius of a pulley at a
span's end is h, the distance of the span's line from its centre: the lever arm of the span's tension
about the pulley's axis, and the belt's speed over the pulley's angular speed there.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.errors import ModelError
from .layout import loop_orientation, refuse_overlaps, refuse_spans_through
from .pitch_curves import Circle, PitchCurve, support

#: the span equation is solved to this (m)
TOL = 1e-13
MAX_ITER = 40


@dataclass(frozen=True)
class CurveSpan:
    name: str          # "<from>-<to>" in belt order
    start: int         # index of the pulley the belt leaves
    end: int           # index of the pulley the belt reaches
    p0: tuple          # leaving tangent point (m, world)
    p1: tuple          # arriving tangent point (m, world)
    length: float      # m
    angle: float       # direction of travel along the span (rad)
    phi0: float        # own angle of the leaving point on the start pulley's curve (rad)
    phi1: float        # own angle of the arriving point on the end pulley's curve (rad)
    radius0: float     # effective radius of the start pulley: the span's distance from its centre (m)
    radius1: float     # effective radius of the end pulley (m)
    iterations: int    # Newton steps taken


@dataclass(frozen=True)
class CurveLayout:
    names: tuple
    centers: np.ndarray    # (nk, 2)
    curves: tuple          # PitchCurve per pulley
    angles: np.ndarray     # the pulleys' angles theta (rad, counter-clockwise)
    rho: np.ndarray        # signed mean radii (sigma r_mean), as layout.py's rho for circles
    orientation: int       # +1 counter-clockwise loop, -1 clockwise
    spans: tuple           # CurveSpan; span k leaves pulley k
    wrap: np.ndarray       # wrap angles (rad, > 0): the travel direction's turn on each pulley
    arc_start: np.ndarray  # world polar angle of the arriving tangent point on each pulley
    arc: np.ndarray        # length of belt on each pulley (m)
    length: float          # path length (m)

    @property
    def span_lengths(self) -> np.ndarray:
        return np.array([s.length for s in self.spans])

    @property
    def radius_in(self) -> np.ndarray:
        """Each pulley's effective radius where the belt arrives (m)."""
        nk = len(self.names)
        return np.array([self.spans[j - 1].radius1 for j in range(nk)])

    @property
    def radius_out(self) -> np.ndarray:
        """Each pulley's effective radius where the belt leaves (m)."""
        return np.array([s.radius0 for s in self.spans])


def senses(centers, sides, orientation=None) -> tuple[int, list[int]]:
    """(orientation, sigma per pulley) from the sides "inside"/"back", as mechanics/layout.py decides them."""
    centers = np.asarray(centers, float)
    if orientation is None:
        orientation = loop_orientation(centers, sides)
    return orientation, [orientation if s == "inside" else -orientation for s in sides]


def common_tangent(ca, curve_a: PitchCurve, theta_a: float, sigma_a: int,
                   cb, curve_b: PitchCurve, theta_b: float, sigma_b: int, beta0: float | None = None):
    """The span leaving curve A (centre ca, turned by theta_a, sense sigma_a) for curve B:
    (beta, phi_a, h_a, phi_b, h_b, p_a, p_b, length, iterations); None when the circles at the mean
    radii have no such tangent (one inside the other)."""
    ax, ay = float(ca[0]), float(ca[1])
    bx, by = float(cb[0]), float(cb[1])
    dx, dy = bx - ax, by - ay
    if beta0 is None:
        d = math.hypot(dx, dy)
        s = (sigma_b * curve_b.mean_radius - sigma_a * curve_a.mean_radius) / d
        if abs(s) >= 1:
            return None
        beta0 = math.atan2(dy, dx) - math.asin(s)
    beta = beta0
    half = 0.5 * math.pi
    for it in range(MAX_ITER + 1):
        sb, cbeta = math.sin(beta), math.cos(beta)
        # outward normals -sigma n at the world angles beta - sigma pi/2
        phi_a, h_a = support(curve_a, beta - sigma_a * half, theta_a)
        phi_b, h_b = support(curve_b, beta - sigma_b * half, theta_b)
        F = -sb * dx + cbeta * dy - sigma_b * h_b + sigma_a * h_a
        ra, rb = curve_a.r(phi_a)[0], curve_b.r(phi_b)[0]
        pa = (ax + ra * math.cos(phi_a + theta_a), ay + ra * math.sin(phi_a + theta_a))
        pb = (bx + rb * math.cos(phi_b + theta_b), by + rb * math.sin(phi_b + theta_b))
        L = cbeta * (pb[0] - pa[0]) + sb * (pb[1] - pa[1])
        if abs(F) <= TOL or it == MAX_ITER:
            break
        if not L > 0:
            return None
        beta += F / L
    if abs(F) > 1e3 * TOL or not L > 0:
        return None
    return beta, phi_a, h_a, phi_b, h_b, pa, pb, L, it


def layout_at(names, centers, curves, sides, angles=None, orientation=None) -> CurveLayout:
    """The belt path on the curves (PitchCurve, or a radius for a circle) turned by ``angles`` (rad; 0s
    when none). ``sides`` holds "inside" or "back" per pulley, in belt order. Raises ModelError
    (field "pulleys") on a path that makes no simple loop, as mechanics/layout.py does."""
    centers = np.asarray(centers, float)
    curves = tuple(c if isinstance(c, PitchCurve) else Circle(c) for c in curves)
    nk = len(names)
    angles = np.zeros(nk) if angles is None else np.asarray(angles, float)
    orientation, sig = senses(centers, sides, orientation)
    cx, cy = centers[:, 0].tolist(), centers[:, 1].tolist()
    rmin = [c.min_radius for c in curves]
    refuse_overlaps(names, cx, cy, rmin, "their smallest radii")
    spans = []
    th = angles.tolist()
    for k in range(nk):
        a, b = k, (k + 1) % nk
        sol = common_tangent(centers[a], curves[a], th[a], sig[a], centers[b], curves[b], th[b], sig[b])
        if sol is None:
            raise ModelError(f"no belt tangent from {names[a]!r} to {names[b]!r}", field="pulleys")
        beta, phi_a, h_a, phi_b, h_b, pa, pb, L, it = sol
        spans.append(CurveSpan(f"{names[a]}-{names[b]}", a, b, pa, pb, L, beta, phi_a, phi_b, h_a, h_b, it))

    wrap, arc_start, arc = np.zeros(nk), np.zeros(nk), np.zeros(nk)
    for j in range(nk):
        b_in, b_out = spans[j - 1].angle, spans[j].angle
        turn = (b_out - b_in) % (2 * math.pi)
        wrap[j] = turn if sig[j] > 0 else (2 * math.pi - turn) % (2 * math.pi)
        p_in = spans[j - 1].p1
        arc_start[j] = math.atan2(p_in[1] - cy[j], p_in[0] - cx[j])
        c = curves[j]
        phi_in, phi_out = spans[j - 1].phi1, spans[j].phi0
        if isinstance(c, Circle):
            arc[j] = c.radius * wrap[j]
        else:
            r_in, dr_in, _ = c.r(phi_in)
            r_out, dr_out, _ = c.r(phi_out)
            sweep = sig[j] * wrap[j] + math.atan2(dr_out, r_out) - math.atan2(dr_in, r_in)
            arc[j] = abs(c.cumulative(phi_in + sweep) - c.cumulative(phi_in))
    total_turn = float(np.sum(np.array(sig) * wrap))
    if abs(total_turn - orientation * 2 * math.pi) > 1e-6 or np.any(wrap <= 1e-9):
        bad = [names[j] for j in range(nk) if wrap[j] <= 1e-9 or wrap[j] >= 2 * math.pi - 1e-9]
        raise ModelError("the belt order does not make a simple loop" + (f" (no wrap on {', '.join(bad)})" if bad else "")
                         + ": list pulleys in belt order and check each side", field="pulleys")
    refuse_spans_through(spans, names, cx, cy, rmin)     # through another pulley's smallest radius
    length = sum(sp.length for sp in spans) + float(np.sum(arc))
    rho = np.array([s * c.mean_radius for s, c in zip(sig, curves)])
    return CurveLayout(tuple(names), centers, curves, angles, rho, orientation, tuple(spans), wrap, arc_start, arc,
                       length)
