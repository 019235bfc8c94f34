"""Pose of a rigid belt tooth on the wrapped pitch line, in the pulley frame.

The pulley turns clockwise by ``phi``; the belt runs in +x along the tangent at the top of the
pulley and wraps it from there (entry), or leaves it along that tangent (exit, by mirror
symmetry). The tooth is rigid and rides on the belt's pitch line at its centre point:

- while its centre is on the free span (entry, phi < 0; exit, phi > 0) the tooth is a rack
  tooth: centre at x = R_b phi + e on the tangent y = R_b (seed eqs. 10-11, with the seed's r_c
  replaced by the belt's pitch-line radius R_b = r_o + a_belt, which makes the pitch-line
  differential exact, and e the tooth's offset from its groove);
- once its centre reaches the tangent point (phi = 0) the belt is wrapped and the pose relative
  to the groove no longer changes (full seating, tooth land tangent to the outside circle).

The groove, fixed in the pulley frame {O_k}, sits on +y. A world point w maps to the pulley
frame as q = R(phi) w with R the counter-clockwise rotation (the inverse of the seed's eq. 2,
whose matrix turns the pulley clockwise).
"""
from __future__ import annotations

import numpy as np


def to_pulley(uv, phi, belt_radius, offset=0.0):
    """Tooth points ``uv`` (belt frame, shape (m, 2)) at angles ``phi`` (n,) -> (n, m, 2)."""
    phi = np.atleast_1d(np.asarray(phi, float))
    wx = belt_radius * phi[:, None] + offset + uv[None, :, 0]
    wy = belt_radius + uv[None, :, 1] + 0 * phi[:, None]
    c, s = np.cos(phi)[:, None], np.sin(phi)[:, None]
    return np.stack([c * wx - s * wy, s * wx + c * wy], axis=-1)


def first_contact(uv, belt_radius, outside_radius, offset=0.0):
    """Smallest |phi| beyond which no tooth point can be inside the outside circle.

    On the tangent, a point (x + u, R_b + v) is outside the circle of radius r_o when
    (x + u)^2 >= r_o^2 - (R_b + v)^2; the bound is the largest such |x| over the points.
    """
    reach = np.sqrt(np.clip(outside_radius ** 2 - (belt_radius + uv[:, 1]) ** 2, 0, None))
    x_max = np.max(np.abs(uv[:, 0]) + reach) + abs(offset)
    return x_max / belt_radius
