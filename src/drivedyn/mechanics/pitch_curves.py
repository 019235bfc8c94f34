"""Convex pitch curves of non-circular sprockets and pulleys: the radius r(phi) against the pulley's own
polar angle phi (counter-clockwise, from the pulley's own reference line), turned with the pulley.

A curve turned by the pulley's angle theta has its point of own angle phi at the world polar angle
psi = phi + theta:

    p(phi) = r(phi) (cos psi, sin psi),  the tangent (increasing phi) r' e_r + r e_psi,
    the outward normal r e_r - r' e_psi,  at the world angle psi - mu,  mu = atan2(r', r),
    the curvature  kappa = (r^2 + 2 r'^2 - r r'') / (r^2 + r'^2)^(3/2)

(do Carmo, Differential Geometry of Curves and Surfaces, sec. 1-5, the curvature of a plane curve,
written in polar form). A belt follows only a convex curve (kappa > 0 everywhere): on a concave stretch
it would bridge the hollow as a straight span. The curves:

- ``Circle(r)``;
- ``Oval(r0, e, phase, order=n)``: r = r0 (1 + e cos(n (phi - phase))), the n-th order term of the
  curve's Fourier series in phi. Order 2 is the oval crank sprocket: to first order in e it is the
  centred ellipse of semi-axes r0 (1 +- e) (1 / r^2 = cos^2 u / a^2 + sin^2 u / b^2 = (1 - 2 e cos 2u) / r0^2
  + O(e^2)), the elliptical crank pulley of Zhu et al., "A rotational order vibration reduction method
  using a regular non-circular pulley", Actuators 14(8) 371 (2025), sec. 2.2.1. Convex while
  e < 1 / (n^2 + 1): at the flattest point, phi = phase + pi / n, r' = 0 and r^2 - r r'' =
  r0^2 (1 - e) (1 - e - n^2 e);
- ``Ellipse(a, b, phase)``: the centred ellipse itself, r = a b / sqrt(b^2 cos^2 u + a^2 sin^2 u);
- ``Table(rows)``: the periodic cubic spline through rows [phi, r] over one turn (de Boor, A Practical
  Guide to Splines, ch. IV: the periodic end conditions).

What a layout needs of a curve: ``support(curve, alpha, theta)``, the point whose outward normal points
along the world angle alpha and its distance h from the centre along that normal (the support function
of the convex curve, Schneider, Convex Bodies: the Brunn-Minkowski Theory, sec. 1.7), and the arc
length between two of its points (``arc_length``).
"""
from __future__ import annotations

import bisect
import math

import numpy as np

TWO_PI = 2 * math.pi
#: Gauss-Legendre nodes per interval of the arc-length table
_GX, _GW = np.polynomial.legendre.leggauss(8)
_GX, _GW = [float(x) for x in _GX], [float(w) for w in _GW]
#: points per turn at which convexity is checked (besides a table's rows)
CHECK_POINTS = 4096


class PitchCurve:
    """A convex pitch curve r(phi). Subclasses give ``r(phi) -> (r, r', r'')`` on plain floats."""

    name = "curve"

    def r(self, phi: float) -> tuple[float, float, float]:
        raise NotImplementedError

    def radii(self, phi) -> np.ndarray:
        """r at an array of own angles."""
        return np.array([self.r(float(p))[0] for p in np.ravel(phi)]).reshape(np.shape(phi))

    @property
    def mean_radius(self) -> float:
        """The average of r over a turn (r0 of an oval)."""
        if not hasattr(self, "_mean"):
            phi = np.arange(CHECK_POINTS) * (TWO_PI / CHECK_POINTS)
            object.__setattr__(self, "_mean", float(np.mean(self.radii(phi))))
        return self._mean

    @property
    def min_radius(self) -> float:
        return self._extremes()[0]

    @property
    def max_radius(self) -> float:
        return self._extremes()[1]

    def _extremes(self):
        if not hasattr(self, "_ext"):
            r = self.radii(np.arange(CHECK_POINTS) * (TWO_PI / CHECK_POINTS))
            object.__setattr__(self, "_ext", (float(r.min()), float(r.max())))
        return self._ext

    # --- arc length: a table of the cumulative length at uniform breaks, Gauss-Legendre within ---
    _intervals = 64

    def _arc_table(self):
        if not hasattr(self, "_cum"):
            m = self._intervals
            h = TWO_PI / m
            cum = [0.0]
            for k in range(m):
                cum.append(cum[-1] + self._gauss(k * h, (k + 1) * h))
            object.__setattr__(self, "_cum", cum)
            object.__setattr__(self, "_h", h)
        return self._cum, self._h

    def _gauss(self, a: float, b: float) -> float:
        c, w = 0.5 * (a + b), 0.5 * (b - a)
        s = 0.0
        for x, g in zip(_GX, _GW):
            r, dr, _ = self.r(c + w * x)
            s += g * math.sqrt(r * r + dr * dr)
        return s * w

    def cumulative(self, phi: float) -> float:
        """Arc length S(phi) from own angle 0 to phi along increasing phi (S(phi + 2 pi) = S(phi) + perimeter)."""
        cum, h = self._arc_table()
        turns = math.floor(phi / TWO_PI)
        x = phi - turns * TWO_PI
        k = min(int(x / h), self._intervals - 1)
        return turns * cum[-1] + cum[k] + self._gauss(k * h, x)

    @property
    def perimeter(self) -> float:
        return self._arc_table()[0][-1]


class Circle(PitchCurve):
    name = "circle"

    def __init__(self, radius: float):
        self.radius = float(radius)

    def r(self, phi):
        return self.radius, 0.0, 0.0

    def radii(self, phi):
        return np.full(np.shape(phi), self.radius)

    @property
    def mean_radius(self):
        return self.radius

    def _extremes(self):
        return self.radius, self.radius

    def cumulative(self, phi):
        return self.radius * phi

    @property
    def perimeter(self):
        return TWO_PI * self.radius

    def __repr__(self):
        return f"Circle({self.radius!r})"


class Oval(PitchCurve):
    """r = r0 (1 + e cos(n (phi - phase))): its long axes at phi = phase + 2 pi k / n."""

    name = "oval"

    def __init__(self, radius: float, ovality: float, phase: float = 0.0, order: int = 2):
        self.r0, self.e, self.phase, self.n = float(radius), float(ovality), float(phase), int(order)

    def r(self, phi):
        u = self.n * (phi - self.phase)
        c, s = math.cos(u), math.sin(u)
        a = self.r0 * self.e
        return self.r0 + a * c, -a * self.n * s, -a * self.n * self.n * c

    def radii(self, phi):
        return self.r0 * (1 + self.e * np.cos(self.n * (np.asarray(phi, float) - self.phase)))

    @property
    def mean_radius(self):
        return self.r0

    def _extremes(self):
        return self.r0 * (1 - abs(self.e)), self.r0 * (1 + abs(self.e))

    def cumulative(self, phi):
        return self.r0 * phi if self.e == 0 else super().cumulative(phi)

    def __repr__(self):
        return f"Oval({self.r0!r}, {self.e!r}, phase={self.phase!r}, order={self.n})"


class Ellipse(PitchCurve):
    """The centred ellipse of semi-axes a (along phi = phase) and b."""

    name = "ellipse"

    def __init__(self, a: float, b: float, phase: float = 0.0):
        self.a, self.b, self.phase = float(a), float(b), float(phase)

    def r(self, phi):
        u = phi - self.phase
        a2, b2 = self.a * self.a, self.b * self.b
        c, s = math.cos(u), math.sin(u)
        q = b2 * c * c + a2 * s * s
        dq = (a2 - b2) * 2 * s * c
        ddq = 2 * (a2 - b2) * (c * c - s * s)
        ab = self.a * self.b
        r = ab / math.sqrt(q)
        return r, -0.5 * r * dq / q, ab * (0.75 * dq * dq * q ** -2.5 - 0.5 * ddq * q ** -1.5)

    def __repr__(self):
        return f"Ellipse({self.a!r}, {self.b!r}, phase={self.phase!r})"


class Table(PitchCurve):
    """The periodic cubic spline through rows [phi (rad), r (m)] over one turn (``check_table`` first)."""

    name = "table"

    def __init__(self, rows):
        from scipy.interpolate import CubicSpline

        check_table(rows)
        x = np.array([float(q[0]) for q in rows])
        y = np.array([float(q[1]) for q in rows])
        y[-1] = y[0]
        sp = CubicSpline(x, y, bc_type="periodic")
        self.x0 = float(x[0])
        self.knots = [float(v) - self.x0 for v in x]
        # the pieces as plain floats: a scalar evaluation in pure Python is ~20x faster than scipy's call
        self.coef = [tuple(float(v) for v in sp.c[:, k]) for k in range(sp.c.shape[1])]
        self._intervals = max(64, 4 * (len(rows) - 1))

    def r(self, phi):
        x = (phi - self.x0) % TWO_PI
        k = min(max(bisect.bisect_right(self.knots, x) - 1, 0), len(self.coef) - 1)
        t = x - self.knots[k]
        c3, c2, c1, c0 = self.coef[k]
        return ((c3 * t + c2) * t + c1) * t + c0, (3 * c3 * t + 2 * c2) * t + c1, 6 * c3 * t + 2 * c2

    def __repr__(self):
        return f"Table({len(self.knots)} rows)"


# --- the curve turned by the pulley's angle theta ---

def point(curve: PitchCurve, phi: float, theta: float = 0.0) -> tuple[float, float]:
    """The point of own angle phi, relative to the pulley's centre, with the pulley turned by theta."""
    r = curve.r(phi)[0]
    return r * math.cos(phi + theta), r * math.sin(phi + theta)


def tangent(curve: PitchCurve, phi: float, theta: float = 0.0) -> tuple[float, float]:
    """Unit tangent along increasing phi (counter-clockwise round the centre)."""
    r, dr, _ = curve.r(phi)
    psi, m = phi + theta, math.hypot(r, dr)
    c, s = math.cos(psi), math.sin(psi)
    return (dr * c - r * s) / m, (dr * s + r * c) / m


def normal(curve: PitchCurve, phi: float, theta: float = 0.0) -> tuple[float, float]:
    """Unit outward normal."""
    tx, ty = tangent(curve, phi, theta)
    return ty, -tx


def curvature(curve: PitchCurve, phi) -> np.ndarray:
    """kappa(phi) (1/m), positive where the curve bends toward its centre (convex)."""
    out = []
    for p in np.ravel(phi):
        r, dr, ddr = curve.r(float(p))
        out.append((r * r + 2 * dr * dr - r * ddr) / (r * r + dr * dr) ** 1.5)
    return np.array(out).reshape(np.shape(phi))


def convexity(curve: PitchCurve, points: int = CHECK_POINTS) -> tuple[float, float, float, float]:
    """(smallest curvature 1/m, its own angle rad, smallest radius m, its angle rad) on a fine grid."""
    phi = np.arange(points) * (TWO_PI / points)
    if isinstance(curve, Table):
        phi = np.sort(np.concatenate([phi, (np.array(curve.knots[:-1]) + curve.x0) % TWO_PI]))
    k = curvature(curve, phi)
    r = curve.radii(phi)
    i, j = int(np.argmin(k)), int(np.argmin(r))
    # the smallest curvature refined between the grid's neighbours (golden sections)
    lo, hi = float(phi[i - 1]) - (TWO_PI if i == 0 else 0.0), float(phi[(i + 1) % len(phi)]) + (TWO_PI if i == len(phi) - 1 else 0.0)
    f = lambda x: float(curvature(curve, x))
    g = (math.sqrt(5) - 1) / 2
    for _ in range(50):
        a, b = hi - g * (hi - lo), lo + g * (hi - lo)
        if f(a) < f(b):
            hi = b
        else:
            lo = a
    at = 0.5 * (lo + hi)
    kmin = min(f(at), float(k[i]))
    return kmin, (at if kmin < k[i] else float(phi[i])) % TWO_PI, float(r[j]), float(phi[j])


def check_convex(curve: PitchCurve) -> None:
    """ValueError (one line, the numbers) unless r > 0 and the curvature > 0 all round."""
    kmin, at, rmin, rat = convexity(curve)
    if rmin <= 0:
        raise ValueError(f"the radius falls to {rmin * 1e3:.4g} mm at {math.degrees(rat):.2f} deg: a pitch curve "
                         "needs a positive radius all round")
    if kmin <= 0:
        hint = ""
        if isinstance(curve, Oval):
            hint = (f"; an oval of order {curve.n} is convex for ovality below 1/(n^2 + 1) = "
                    f"{1 / (curve.n ** 2 + 1):.4g}, got {curve.e:.4g}")
        raise ValueError(f"the pitch curve is not convex: its curvature is {kmin:.4g} 1/m at "
                         f"{math.degrees(at):.2f} deg (a belt cannot follow a concave pitch curve){hint}")


def check_table(rows, angle_tol: float = 1e-9, radius_tol: float = 1e-9) -> None:
    """ValueError (one line, the numbers) unless rows [phi rad, r m] span one turn, increasing, with
    positive radii and the last radius repeating the first."""
    if len(rows) < 4:
        raise ValueError(f"needs at least 4 rows over one turn (0 .. 360 deg), got {len(rows)}")
    xs = [float(q[0]) for q in rows]
    if any(b <= a for a, b in zip(xs, xs[1:])):
        raise ValueError("the angles must increase strictly")
    span = xs[-1] - xs[0]
    if abs(span - TWO_PI) > angle_tol:
        raise ValueError(f"the angles must span one turn, 360 deg: they run from {math.degrees(xs[0]):.6g} to "
                         f"{math.degrees(xs[-1]):.6g} deg ({math.degrees(span):.6g} deg)")
    for k, q in enumerate(rows):
        if not float(q[1]) > 0:
            raise ValueError(f"row {k} gives a radius of {float(q[1]) * 1e3:.6g} mm at {math.degrees(xs[k]):.6g} deg: "
                             "a pitch curve's radius must be > 0")
    r0, r1 = float(rows[0][1]), float(rows[-1][1])
    if abs(r1 - r0) > radius_tol * max(r0, r1):
        raise ValueError(f"the table does not close over the turn: the radius at {math.degrees(xs[-1]):.6g} deg "
                         f"({r1 * 1e3:.6g} mm) differs from the radius at {math.degrees(xs[0]):.6g} deg "
                         f"({r0 * 1e3:.6g} mm)")


def support(curve: PitchCurve, alpha: float, theta: float = 0.0) -> tuple[float, float]:
    """(phi, h): the own angle of the point whose outward normal points along the world angle alpha, and
    h = p . (cos alpha, sin alpha), the distance from the centre of the tangent line there.

    Solves G(phi) = phi - mu(phi) - (alpha - theta) = 0, mu = atan2(r', r) in (-pi/2, pi/2) since r > 0,
    so that the root lies within pi/2 of alpha - theta; G' = 1 - mu' = (r^2 + 2 r'^2 - r r'') / (r^2 + r'^2)
    = kappa |p'| > 0 on a convex curve: Newton's method kept inside the bracket (bisection when a step
    leaves it). At the root the normal makes the angle mu with the radius: h = r cos mu = r^2 / |p'|."""
    target = alpha - theta
    lo, hi = target - 0.5 * math.pi, target + 0.5 * math.pi
    phi = target
    for _ in range(60):
        r, dr, ddr = curve.r(phi)
        q = r * r + dr * dr
        g = phi - math.atan2(dr, r) - target
        if g > 0:
            hi = phi
        else:
            lo = phi
        if abs(g) < 1e-15:
            break
        step = g * q / (q + dr * dr - r * ddr)
        nxt = phi - step
        if not lo < nxt < hi:
            nxt = 0.5 * (lo + hi)
        if abs(nxt - phi) < 1e-16:
            phi = nxt
            break
        phi = nxt
    r, dr, _ = curve.r(phi)
    return phi, r / math.sqrt(1.0 + (dr / r) ** 2)


def samples(curve: PitchCurve, m: int):
    """(points (m, 2), outward unit normals (m, 2), curvature (m,)) at m uniform own angles, the curve unturned."""
    phi = np.arange(m) * (TWO_PI / m)
    r = curve.radii(phi)
    pts = np.column_stack([r * np.cos(phi), r * np.sin(phi)])
    return pts, np.array([normal(curve, float(f)) for f in phi]), curvature(curve, phi)


def offset_radii(sampled, offset, grid) -> np.ndarray:
    """The radius at the polar angles ``grid`` (rad) of the curve ``sampled`` (``samples``) offset along its
    outward normals by ``offset`` (m: one number, or one per sample): the periodic cubic spline through the
    offset points (a convex curve's small offset turns once round with it)."""
    from scipy.interpolate import CubicSpline

    pts, nrm, _ = sampled
    pts = pts + np.reshape(offset, (-1, 1)) * nrm
    ang = np.unwrap(np.arctan2(pts[:, 1], pts[:, 0]))
    ang -= TWO_PI * np.floor(ang[0] / TWO_PI)
    rad = np.hypot(pts[:, 0], pts[:, 1])
    cs = CubicSpline(np.append(ang, ang[0] + TWO_PI), np.append(rad, rad[0]), bc_type="periodic")
    grid = np.asarray(grid, float)
    return cs(np.where(grid < ang[0], grid + TWO_PI, grid))


def arc_length(curve: PitchCurve, phi0: float, phi1: float) -> float:
    """Arc length from own angle phi0 to phi1 (signed: negative when phi1 < phi0)."""
    return curve.cumulative(phi1) - curve.cumulative(phi0)
