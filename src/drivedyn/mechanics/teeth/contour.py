"""Plane-geometry helpers for profiles made of straight segments and circular arcs.

Profiles are built exactly (arc centres, tangent points, intersections) and only then sampled
into polylines. Arcs are sampled so that the chord sagitta stays below ``tol`` (metres): the
polygon error, hence the overlap-area error, shrinks linearly with ``tol`` (convergence test).
All coordinates are SI (metres); angles in radians.
"""
from __future__ import annotations

import numpy as np


def unit(v):
    """The unit vector of ``v``."""
    v = np.asarray(v, float)
    return v / np.hypot(v[0], v[1])


def left_normal(d):
    """``d`` turned by +90 degrees."""
    return np.array([-d[1], d[0]])


def foot(point, p, d):
    """Foot of the perpendicular from ``point`` on the line through ``p`` with unit direction ``d``."""
    point, p = np.asarray(point, float), np.asarray(p, float)
    return p + np.dot(point - p, d) * d


def line_circle(p, d, c, r, pick):
    """Intersection of the line ``p + t d`` with the circle (c, r).

    ``pick`` chooses among the (up to two) points: a function of the point returning a sort key,
    the point with the largest key is returned. Raises ValueError when the line misses the circle.
    """
    p, d, c = np.asarray(p, float), unit(d), np.asarray(c, float)
    f = p - c
    b = np.dot(f, d)
    disc = b * b - (np.dot(f, f) - r * r)
    if disc < 0:
        raise ValueError("line misses circle")
    pts = [p + (-b + s * np.sqrt(disc)) * d for s in (-1.0, 1.0)]
    return max(pts, key=pick)


def circle_circle(c1, r1, c2, r2, pick):
    """Intersection of two circles; ``pick`` as in :func:`line_circle`."""
    c1, c2 = np.asarray(c1, float), np.asarray(c2, float)
    dvec = c2 - c1
    dist = np.hypot(*dvec)
    if dist > r1 + r2 or dist < abs(r1 - r2) or dist == 0:
        raise ValueError("circles do not intersect")
    x = (dist * dist + r1 * r1 - r2 * r2) / (2 * dist)
    h = np.sqrt(max(r1 * r1 - x * x, 0.0))
    e = dvec / dist
    base = c1 + x * e
    pts = [base + s * h * left_normal(e) for s in (-1.0, 1.0)]
    return max(pts, key=pick)


def fillet_lines(p1, d1, side1, p2, d2, side2, r):
    """Circle of radius ``r`` tangent to two lines.

    Each line is a point and a unit direction; ``side`` (+1/-1) says on which side of the line
    (left or right of its direction) the fillet centre lies. Returns (centre, tangent on line 1,
    tangent on line 2).
    """
    d1, d2 = unit(d1), unit(d2)
    q1 = np.asarray(p1, float) + side1 * r * left_normal(d1)
    q2 = np.asarray(p2, float) + side2 * r * left_normal(d2)
    # offset lines q1 + t d1 and q2 + s d2 meet at the centre
    m = np.column_stack([d1, -d2])
    t, _ = np.linalg.solve(m, q2 - q1)
    c = q1 + t * d1
    return c, foot(c, p1, d1), foot(c, p2, d2)


def fillet_line_circle(p, d, side, c0, r0, outside, r, pick):
    """Circle of radius ``r`` tangent to a line and to a circle (c0, r0).

    ``side`` places the centre left (+1) or right (-1) of the line; ``outside`` True for a fillet
    touching the circle from outside (|C - c0| = r0 + r), False from inside (r0 - r). ``pick``
    chooses between the two solutions (key function of the centre). Returns (centre, tangent on
    the line, tangent on the circle).
    """
    d = unit(d)
    q = np.asarray(p, float) + side * r * left_normal(d)
    rr = r0 + r if outside else r0 - r
    c = line_circle(q, d, c0, rr, pick)
    c0 = np.asarray(c0, float)
    t_circle = c0 + (c - c0) * (r0 / rr)
    return c, foot(c, p, d), t_circle


def arc(c, r, p_from, p_to, tol, ccw=None):
    """Points of the arc of circle (c, r) from ``p_from`` to ``p_to`` (both included).

    ``ccw`` forces the sense; None takes the shorter arc. The number of chords keeps the sagitta
    r (1 - cos(dtheta / 2)) below ``tol``.
    """
    c = np.asarray(c, float)
    a0 = np.arctan2(p_from[1] - c[1], p_from[0] - c[0])
    a1 = np.arctan2(p_to[1] - c[1], p_to[0] - c[0])
    sweep = (a1 - a0) % (2 * np.pi)  # counter-clockwise sweep in [0, 2 pi)
    if ccw is None:
        ccw = sweep <= np.pi
    if not ccw:
        sweep = sweep - 2 * np.pi
    return arc_angles(c, r, a0, a0 + sweep, tol)


def arc_angles(c, r, a0, a1, tol):
    """Points of the arc (c, r) from angle ``a0`` to ``a1`` (radians, either sense)."""
    dmax = 2 * np.arccos(max(1 - tol / r, -1.0)) if tol < 2 * r else np.pi
    n = max(int(np.ceil(abs(a1 - a0) / dmax)), 1)
    a = np.linspace(a0, a1, n + 1)
    return np.column_stack([c[0] + r * np.cos(a), c[1] + r * np.sin(a)])


def join(*pieces):
    """Concatenate point arrays, dropping points that repeat the previous one."""
    pts = np.vstack([np.atleast_2d(p) for p in pieces if len(p)])
    keep = np.ones(len(pts), bool)
    keep[1:] = np.hypot(*(np.diff(pts, axis=0).T)) > 1e-12
    return pts[keep]


def mirror_half(half):
    """Full symmetric contour from its right half (ordered from the axis outwards).

    Returns the points from the left end, through the axis, to the right end.
    """
    left = half[::-1].copy()
    left[:, 0] *= -1
    return join(left[:-1] if abs(half[0, 0]) < 1e-15 else left, half)


def rotate(pts, angle):
    """Points turned counter-clockwise by ``angle`` about the origin."""
    ca, sa = np.cos(angle), np.sin(angle)
    return np.column_stack([ca * pts[:, 0] - sa * pts[:, 1], sa * pts[:, 0] + ca * pts[:, 1]])
