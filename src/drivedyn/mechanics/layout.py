"""Belt path from pulley centres, radii and sides: spans, wrap angles, length (planar geometry).

Each pulley is wrapped with a signed radius rho: positive when the belt goes round it
counter-clockwise. On a loop traversed counter-clockwise, pulleys inside the loop have
rho = +r and back-side idlers rho = -r (and the opposite for a clockwise loop). The common
tangent leaving circle A for circle B has direction angle beta with
sin(gamma - beta) = (rho_B - rho_A) / d, where d, gamma are the length and angle of C_B - C_A;
its touching points are C - rho * n(beta), n = (-sin beta, cos beta).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.errors import ModelError


@dataclass(frozen=True)
class Span:
    name: str          # "<from>-<to>" in belt order
    start: int         # index of the pulley the belt leaves
    end: int           # index of the pulley the belt reaches
    p0: tuple          # leaving tangent point (m)
    p1: tuple          # arriving tangent point (m)
    length: float      # m
    angle: float       # direction of travel along the span (rad), for the loop orientation

    @property
    def midpoint(self):
        return ((self.p0[0] + self.p1[0]) / 2, (self.p0[1] + self.p1[1]) / 2)


@dataclass(frozen=True)
class Layout:
    names: tuple
    centers: np.ndarray    # (nk, 2)
    radii: np.ndarray      # (nk,) the radii used for this path
    rho: np.ndarray        # signed radii
    orientation: int       # +1 counter-clockwise loop, -1 clockwise
    spans: tuple           # Span, span k leaves pulley k
    wrap: np.ndarray       # wrap angles (rad, > 0)
    arc_start: np.ndarray  # polar angle of the arriving tangent point on each pulley
    length: float          # path length (m)

    def hub_load_static(self, tension: float) -> np.ndarray:
        """Force of the belt on each pulley (N, vectors) for a uniform span tension."""
        nk = len(self.names)
        out = np.zeros((nk, 2))
        for k, sp in enumerate(self.spans):
            t = np.array([math.cos(sp.angle), math.sin(sp.angle)])
            out[sp.start] += tension * t      # the leaving span pulls the pulley along it
            out[sp.end] -= tension * t        # the arriving span pulls it back
        return out

    # --- the path as a function of arc length, starting at the beginning of span 0 ---
    def pieces(self):
        """Path pieces in order: ('line', p0, p1, L) and ('arc', center, R, angle0, sweep, L)."""
        nk = len(self.names)
        out = []
        for k in range(nk):
            sp = self.spans[k]
            out.append(("line", np.array(sp.p0), np.array(sp.p1), sp.length))
            j = sp.end
            sweep = self.wrap[j] * math.copysign(1.0, self.rho[j])
            out.append(("arc", self.centers[j], self.radii[j], self.arc_start[j], sweep, self.radii[j] * self.wrap[j]))
        return out


def _orientation(centers: np.ndarray) -> int:
    x, y = centers[:, 0], centers[:, 1]
    area = 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)
    return -1 if area < -1e-12 else 1


def loop_orientation(centers: np.ndarray, sides) -> int:
    """+1 counter-clockwise, -1 clockwise: the shoelace sign of the inside pulleys' centres (of all,
    with fewer than three inside)."""
    inside = [k for k, s in enumerate(sides) if s == "inside"]
    return _orientation(centers[inside]) if len(inside) >= 3 else _orientation(centers)


def refuse_overlaps(names, cx, cy, radii, what: str = "radii") -> None:
    """ModelError (field "pulleys") for two pulleys closer than the sum of ``radii`` (named ``what``)."""
    nk = len(names)
    for a in range(nk):
        for b in range(a + 1, nk):
            d = math.hypot(cx[b] - cx[a], cy[b] - cy[a])
            if d < radii[a] + radii[b]:
                raise ModelError(f"pulleys {names[a]!r} and {names[b]!r} overlap (centre distance {d * 1e3:.1f} mm "
                                 f"< sum of {what} {(radii[a] + radii[b]) * 1e3:.1f} mm)", field="pulleys")


def refuse_spans_through(spans, names, cx, cy, radii) -> None:
    """ModelError (field "pulleys") for a span that cuts through another pulley's circle of ``radii``."""
    for sp in spans:
        (x0, y0), (x1, y1) = sp.p0, sp.p1
        ex, ey = x1 - x0, y1 - y0
        for j in range(len(names)):
            if j in (sp.start, sp.end):
                continue
            t = min(max(((cx[j] - x0) * ex + (cy[j] - y0) * ey) / max(sp.length ** 2, 1e-300), 0.0), 1.0)
            if math.hypot(x0 + t * ex - cx[j], y0 + t * ey - cy[j]) < radii[j] * (1 - 1e-9):
                raise ModelError(f"span {sp.name} passes through pulley {names[j]!r}", field="pulleys")


def layout_from(names, centers, radii, sides, orientation=None) -> Layout:
    """Compute the belt path. ``sides`` holds "inside" or "back" per pulley, in belt order."""
    centers = np.asarray(centers, float)
    radii = np.asarray(radii, float)
    nk = len(names)
    if orientation is None:
        orientation = loop_orientation(centers, sides)
    rho = np.array([orientation * r if s == "inside" else -orientation * r for r, s in zip(radii, sides)])

    # the checks on plain floats: a design loop builds hundreds of layouts per model (tensioner tables)
    cx, cy, rr = centers[:, 0].tolist(), centers[:, 1].tolist(), radii.tolist()
    refuse_overlaps(names, cx, cy, rr)

    spans, betas = [], []
    for k in range(nk):
        a, b = k, (k + 1) % nk
        D = centers[b] - centers[a]
        d = float(np.hypot(*D))
        gamma = math.atan2(D[1], D[0])
        s = (rho[b] - rho[a]) / d
        if abs(s) >= 1:
            raise ModelError(f"no belt tangent from {names[a]!r} to {names[b]!r}", field="pulleys")
        beta = gamma - math.asin(s)
        n = np.array([-math.sin(beta), math.cos(beta)])
        p0 = centers[a] - rho[a] * n
        p1 = centers[b] - rho[b] * n
        L = float(np.hypot(*(p1 - p0)))
        spans.append(Span(f"{names[a]}-{names[b]}", a, b, tuple(p0), tuple(p1), L, beta))
        betas.append(beta)

    wrap = np.zeros(nk)
    arc_start = np.zeros(nk)
    for j in range(nk):
        b_in, b_out = betas[j - 1], betas[j]
        turn = (b_out - b_in) % (2 * math.pi)          # counter-clockwise turn of the travel direction
        wrap[j] = turn if rho[j] > 0 else (2 * math.pi - turn) % (2 * math.pi)
        p_in = np.array(spans[j - 1].p1)
        arc_start[j] = math.atan2(p_in[1] - centers[j][1], p_in[0] - centers[j][0])
    total_turn = float(np.sum(np.sign(rho) * wrap))
    if abs(total_turn - orientation * 2 * math.pi) > 1e-6 or np.any(wrap <= 1e-9):
        bad = [names[j] for j in range(nk) if wrap[j] <= 1e-9 or wrap[j] >= 2 * math.pi - 1e-9]
        backs = [names[j] for j in range(nk) if sides[j] == "back"]
        hint = (f"; a back-side idler ({', '.join(backs)}) must press into the span between its neighbours"
                if backs else "")
        raise ModelError("the belt order does not make a simple loop" + (f" (no wrap on {', '.join(bad)})" if bad else "")
                         + ": list pulleys in belt order and check each side" + hint, field="pulleys")

    refuse_spans_through(spans, names, cx, cy, rr)      # spans must not cut through other pulleys

    length = sum(sp.length for sp in spans) + float(np.sum(radii * wrap))
    return Layout(tuple(names), centers, radii, rho, orientation, tuple(spans), wrap, arc_start, length)


def compute_layout(model) -> Layout:
    """The belt path of a belt-drive model at the pulleys' contact radii."""
    p = model.pulleys
    return layout_from([q.name for q in p], [q.center for q in p], [q.radius for q in p], [q.side for q in p])
