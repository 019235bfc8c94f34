"""Non-circular pitch curves and the belt path on them (mechanics/pitch_curves.py, curve_layout.py,
curve_turn.py) against references written here: a brute-force minimisation of the common tangent,
closed forms (the ellipse's perimeter and support function, the oval's convexity limit, the belt
length's first-order change), and mechanics/layout.py for circles."""
import math

import mpmath
import numpy as np
import pytest
from scipy.optimize import brentq
from scipy.special import ellipe

from drivedyn.core.errors import ModelError
from drivedyn.mechanics.curve_layout import common_tangent, layout_at
from drivedyn.mechanics.curve_turn import over_a_turn
from drivedyn.mechanics.layout import layout_from
from drivedyn.mechanics.pitch_curves import (Circle, Ellipse, Oval, Table, check_convex, convexity, normal, point,
                                             support, tangent)


# --- the brute-force reference: the tangent line found by minimising, in nobody's Newton ---

def _radius_oval(r0, e, phase, n):
    return lambda phi, m=math: r0 * (1 + e * m.cos(n * (phi - phase)))


def _radius_ellipse(a, b, phase):
    return lambda phi, m=math: a * b / m.sqrt((b * m.cos(phi - phase)) ** 2 + (a * m.sin(phi - phase)) ** 2)


def _offset(rfun, centre, theta, sigma, beta):
    """(c, phi): the line n . x = c of direction beta touching the curve, the curve on its left (sigma = +1:
    c = min over the curve of n . p) or on its right (sigma = -1: the max); a grid of 1024 then golden
    sections in floats."""
    nx, ny = -math.sin(beta), math.cos(beta)
    phi = np.linspace(0, 2 * math.pi, 1024, endpoint=False)
    r = rfun(phi, np)
    v = sigma * (nx * (centre[0] + r * np.cos(phi + theta)) + ny * (centre[1] + r * np.sin(phi + theta)))
    k = int(np.argmin(v))
    f = lambda p: sigma * (nx * (centre[0] + rfun(p) * math.cos(p + theta)) + ny * (centre[1] + rfun(p) * math.sin(p + theta)))
    lo, hi = phi[k] - 2 * math.pi / 1024, phi[k] + 2 * math.pi / 1024
    g = (math.sqrt(5) - 1) / 2
    for _ in range(75):
        a, b = hi - g * (hi - lo), lo + g * (hi - lo)
        if f(a) < f(b):
            hi = b
        else:
            lo = a
    p = 0.5 * (lo + hi)
    return sigma * f(p), p


def _argmin_mp(rfun, centre, theta, sigma, beta, phi0):
    """The touching point's own angle at the found beta, by golden sections in 30-digit arithmetic within
    1e-7 rad of the floats' (a minimum is flat: floats place it to only ~1e-8 rad)."""
    mpmath.mp.dps = 30
    beta = mpmath.mpf(beta)
    nx, ny = -mpmath.sin(beta), mpmath.cos(beta)
    f = lambda p: sigma * (nx * (centre[0] + rfun(p, mpmath) * mpmath.cos(p + theta))
                           + ny * (centre[1] + rfun(p, mpmath) * mpmath.sin(p + theta)))
    lo, hi = mpmath.mpf(phi0) - mpmath.mpf(1e-7), mpmath.mpf(phi0) + mpmath.mpf(1e-7)
    g = (mpmath.sqrt(5) - 1) / 2
    for _ in range(60):
        a, b = hi - g * (hi - lo), lo + g * (hi - lo)
        if f(a) < f(b):
            hi = b
        else:
            lo = a
    p = (lo + hi) / 2
    r = rfun(p, mpmath)
    return float(centre[0] + r * mpmath.cos(p + theta)), float(centre[1] + r * mpmath.sin(p + theta))


def _brute_tangent(ra, ca, ta, sa, rb, cb, tb, sb, beta_guess):
    """The common tangent: the beta at which both curves' touching lines coincide (brentq on the offsets)."""
    g = lambda beta: _offset(ra, ca, ta, sa, beta)[0] - _offset(rb, cb, tb, sb, beta)[0]
    beta = brentq(g, beta_guess - 0.2, beta_guess + 0.2, xtol=1e-15, rtol=1e-15)
    pa = _argmin_mp(ra, ca, ta, sa, beta, _offset(ra, ca, ta, sa, beta)[1])
    pb = _argmin_mp(rb, cb, tb, sb, beta, _offset(rb, cb, tb, sb, beta)[1])
    return beta, pa, pb


def _compare(curve_a, ra, ca, ta, sa, curve_b, rb, cb, tb, sb):
    sol = common_tangent(ca, curve_a, ta, sa, cb, curve_b, tb, sb)
    beta, pa, pb, L = sol[0], sol[5], sol[6], sol[7]
    bb, qa, qb = _brute_tangent(ra, ca, ta, sa, rb, cb, tb, sb, beta)
    assert abs(math.remainder(beta - bb, 2 * math.pi)) < 1e-10
    assert math.dist(pa, qa) < 1e-9 and math.dist(pb, qb) < 1e-9
    assert abs(L - math.dist(qa, qb)) < 1e-9
    return sol


ANGLES = np.linspace(0, 2 * math.pi, 16, endpoint=False)


@pytest.mark.parametrize("sides", [(1, 1), (1, -1), (-1, 1)])
def test_tangent_oval_and_circle_against_brute_force(sides):
    """An order-2 oval (ovality 0.1, nearly an ellipse of semi-axes r0 (1 +- e)) and a circle, open (both
    senses +1) and crossed, the oval turned through a turn in 16 steps: tangent points to 1e-9 m."""
    sa, sb = sides
    oval, circle = Oval(0.04, 0.1, phase=0.3), Circle(0.06)
    ro, rc = _radius_oval(0.04, 0.1, 0.3, 2), (lambda phi, m=math: 0.06 + 0 * phi)
    ca, cb = (0.0, 0.0), (0.22, 0.13)
    for th in ANGLES:
        _compare(oval, ro, ca, th, sa, circle, rc, cb, 0.0, sb)
        _compare(circle, rc, cb, 0.0, sb, oval, ro, ca, th, sa)


def test_tangent_ellipse_and_circle_against_brute_force():
    """The centred ellipse itself (a = 45 mm, b = 35 mm) and a circle, both ways round."""
    ell, circle = Ellipse(0.045, 0.035, phase=-0.2), Circle(0.03)
    re, rc = _radius_ellipse(0.045, 0.035, -0.2), (lambda phi, m=math: 0.03 + 0 * phi)
    ca, cb = (0.01, -0.02), (-0.15, 0.2)
    for th in ANGLES:
        _compare(ell, re, ca, th, 1, circle, rc, cb, 0.4, 1)
        _compare(circle, rc, cb, 0.4, 1, ell, re, ca, th, 1)


def test_tangent_two_ovals_against_brute_force():
    """Two ovals turning at different rates (order 2, e = 0.1 and order 3, e = 0.05), open and crossed."""
    a, b = Oval(0.035, 0.1, phase=0.1), Oval(0.07, 0.05, phase=1.0, order=3)
    ra, rb = _radius_oval(0.035, 0.1, 0.1, 2), _radius_oval(0.07, 0.05, 1.0, 3)
    ca, cb = (0.0, 0.0), (0.3, -0.05)
    for th in ANGLES:
        for sb in (1, -1):
            _compare(a, ra, ca, th, 1, b, rb, cb, -0.5 * th + 0.2, sb)
            _compare(b, rb, cb, -0.5 * th + 0.2, sb, a, ra, ca, th, 1)


def test_newton_converges_to_round_off():
    a, b = Oval(0.035, 0.15, phase=0.1), Oval(0.07, 0.05, phase=1.0, order=3)
    for th in ANGLES:
        sol = common_tangent((0, 0), a, th, 1, (0.3, -0.05), b, 2 * th, 1)
        assert sol[-1] <= 6        # Newton steps from the circle solution


# --- closed forms of single curves ---

def test_ellipse_perimeter_and_support_function():
    """Perimeter 4 a E(1 - b^2/a^2) (complete elliptic integral of the second kind, scipy's ellipe takes
    m = k^2); support function h(alpha) = sqrt(a^2 cos^2 + b^2 sin^2) of (alpha - phase - theta)."""
    a, b, ph = 0.05, 0.03, 0.4
    ell = Ellipse(a, b, phase=ph)
    assert ell.perimeter == pytest.approx(4 * a * ellipe(1 - b * b / (a * a)), rel=1e-13)
    for alpha in np.linspace(-3, 3, 37):
        phi, h = support(ell, alpha, theta=0.7)
        u = alpha - ph - 0.7
        assert h == pytest.approx(math.hypot(a * math.cos(u), b * math.sin(u)), rel=1e-13)
        # the point found has the outward normal asked for, and lies on the tangent line at h
        nx, ny = normal(ell, phi, 0.7)
        assert math.atan2(ny, nx) == pytest.approx(math.remainder(alpha, 2 * math.pi), abs=1e-13)
        px, py = point(ell, phi, 0.7)
        assert px * math.cos(alpha) + py * math.sin(alpha) == pytest.approx(h, rel=1e-13)
        tx, ty = tangent(ell, phi, 0.7)
        assert tx * nx + ty * ny == pytest.approx(0, abs=1e-15)


def test_oval_perimeter_to_second_order():
    """P = int sqrt(r^2 + r'^2) dphi = 2 pi r0 (1 + n^2 e^2 / 4) + O(e^4): int r = 2 pi r0 exactly, and
    sqrt(r^2 + r'^2) = r + r'^2 / (2 r) + ..., r'^2 / (2 r) = r0 n^2 e^2 sin^2 / 2 + O(e^3), whose
    cubic term integrates to 0 (odd in cos)."""
    for n in (2, 3, 5):
        e = 0.004
        assert Oval(0.03, e, order=n).perimeter == pytest.approx(2 * math.pi * 0.03 * (1 + n * n * e * e / 4),
                                                                 abs=2 * math.pi * 0.03 * (n * e) ** 4)


@pytest.mark.parametrize("n", [2, 3, 4])
def test_oval_convex_up_to_one_over_n2_plus_one(n):
    """At phi = phase + pi/n, r' = 0 and r^2 - r r'' = r0^2 (1 - e)(1 - e - n^2 e): zero curvature at
    e = 1/(n^2 + 1); below, convex; above, refused with the numbers."""
    lim = 1 / (n * n + 1)
    kmin, at, _, _ = convexity(Oval(0.03, lim, phase=0.2, order=n))
    assert kmin == pytest.approx(0, abs=1e-9)      # 1/m, against 1/r0 = 33 1/m
    assert math.remainder(at - (0.2 + math.pi / n), 2 * math.pi / n) == pytest.approx(0, abs=2e-3)
    check_convex(Oval(0.03, 0.98 * lim, order=n))
    with pytest.raises(ValueError, match=f"not convex.*{1 / (n * n + 1):.4g}") as exc:
        check_convex(Oval(0.03, 1.05 * lim, order=n))
    assert "\n" not in str(exc.value)


def test_table_through_an_oval():
    """A periodic spline through 73 rows of an oval: the curve within the spline's h^4 error (de Boor,
    ch. IV: |r - s| <= 5/384 h^4 max|r''''|, here 5/384 (2 pi/72)^4 r0 e 16 = 4.9e-9 m), its perimeter
    and a layout on it alike."""
    r0, e = 0.04, 0.08
    oval = Oval(r0, e, phase=0.5)
    phi = np.linspace(0, 2 * math.pi, 73)
    tab = Table([[p, float(oval.radii(p))] for p in phi])
    x = np.linspace(0, 2 * math.pi, 1001)
    assert np.max(np.abs(tab.radii(x) - oval.radii(x))) < 5 / 384 * (2 * math.pi / 72) ** 4 * r0 * e * 16
    assert tab.perimeter == pytest.approx(oval.perimeter, rel=1e-7)
    a = layout_at(["a", "b"], [(0, 0), (0.3, 0.0)], [oval, 0.05], ["inside"] * 2, [0.3, 0])
    b = layout_at(["a", "b"], [(0, 0), (0.3, 0.0)], [tab, 0.05], ["inside"] * 2, [0.3, 0])
    assert b.length == pytest.approx(a.length, abs=1e-8)
    assert b.radius_out == pytest.approx(a.radius_out, abs=1e-8)


# --- the round drive reproduced ---

DRIVES = [
    (["a", "b"], [(0, 0), (0.5, 0)], [0.05, 0.1], ["inside", "inside"]),
    (["crank", "alt", "pump", "idler"], [(0.04, -0.30), (0.16, -0.10), (0, 0), (-0.02, -0.13)],
     [0.08, 0.056, 0.027, 0.031], ["inside", "inside", "inside", "back"]),
    (["idler", "pump", "alt", "crank"], [(-0.02, -0.13), (0, 0), (0.16, -0.10), (0.04, -0.30)],
     [0.031, 0.027, 0.056, 0.08], ["back", "inside", "inside", "inside"]),
]


@pytest.mark.parametrize("k", range(len(DRIVES)))
def test_circle_as_oval_of_ovality_zero_reproduces_layout(k):
    """Every number of mechanics/layout.py's layout_from, to round-off, from ovals of ovality 0 turned
    by arbitrary angles (and plain circles)."""
    names, C, R, S = DRIVES[k]
    ref = layout_from(names, C, R, S)
    for curves, angles in (([Oval(r, 0.0, phase=0.7) for r in R], np.linspace(0.3, 2.0, len(R))),
                           ([Circle(r) for r in R], None)):
        lay = layout_at(names, C, curves, S, angles)
        assert lay.orientation == ref.orientation
        assert lay.rho == pytest.approx(ref.rho, abs=1e-16)
        assert lay.length == pytest.approx(ref.length, abs=1e-15)
        assert lay.wrap == pytest.approx(ref.wrap, abs=1e-15)
        assert np.abs(np.remainder(lay.arc_start - ref.arc_start + math.pi, 2 * math.pi) - math.pi).max() < 1e-15
        assert lay.arc == pytest.approx(ref.radii * ref.wrap, abs=1e-16)
        for a, b in zip(lay.spans, ref.spans):
            assert a.name == b.name and (a.start, a.end) == (b.start, b.end)
            assert a.p0 == pytest.approx(b.p0, abs=1e-16) and a.p1 == pytest.approx(b.p1, abs=1e-16)
            assert a.length == pytest.approx(b.length, abs=1e-16)
            assert a.angle == pytest.approx(b.angle, abs=1e-15)
            assert (a.radius0, a.radius1) == pytest.approx((R[a.start], R[a.end]), abs=1e-17)


# --- over a turn ---

def test_belt_length_over_a_turn_first_order_in_ovality():
    """The belt length of an oval crank (order 2, r0, e) and a round pulley r_B at distance d.

    Closed form: an open belt round two convex pulleys is the boundary of their convex hull, whose
    length is the integral of its support function over the normal's angle (Cauchy's formula, Santalo,
    Integral Geometry and Geometric Probability, eq. 1.15): L = int max(h_A(alpha), r_B + d cos alpha)
    dalpha, alpha from the line of centres. The oval's support function is h_A = r0 (1 + e cos 2(alpha -
    psi)) + O(e^2), psi = theta + phase (the support point sits O(e) off the polar angle alpha, which
    changes h by O(e^2)). To first order only the stretch where A bounds the hull changes (at the
    switch the two are equal): alpha in (a*, 2 pi - a*), cos a* = (r0 - r_B)/d, the wrap on A being
    2 (pi - a*), so

        L(theta) - L_round = r0 e int_{a*}^{2 pi - a*} cos 2(alpha - psi) dalpha = -r0 e sin(2 a*) cos(2 psi).

    It vanishes for equal pulleys (a 180 deg wrap): the first-order change is the wrap's. The
    remainder is O(r0 e^2): checked at two ovalities, the error falls as e^2."""
    r0, rb, d, ph = 0.03, 0.06, 0.25, 0.4
    round_ = layout_from(["a", "b"], [(0, 0), (d, 0)], [r0, rb], ["inside"] * 2).length
    astar = math.acos((r0 - rb) / d)
    errs = []
    for e in (0.01, 0.005):
        turn = over_a_turn(["a", "b"], [(0, 0), (d, 0)], [Oval(r0, e, phase=ph), Circle(rb)], ["inside"] * 2,
                           ratios="fixed", points=90)
        first = -r0 * e * math.sin(2 * astar) * np.cos(2 * (turn.theta + ph))
        err = np.max(np.abs(turn.length - round_ - first))
        assert err < 4 * r0 * e * e
        errs.append(err)
        # the order content: order 2 at r0 e |sin 2a*|, odd orders nil
        amp = turn.orders(turn.length, top=4)
        assert amp[2] == pytest.approx(r0 * e * abs(math.sin(2 * astar)), abs=2 * r0 * e * e)
        assert amp[1] < 1e-15 and amp[3] < 1e-15
    assert errs[0] / errs[1] == pytest.approx(4, rel=0.1)


def test_effective_radius_is_the_support_function_and_wraps_close():
    """At each angle the effective radius at a span's end is the span line's distance from the centre,
    the wraps turn the travel direction once round, and the path is spans plus arcs."""
    names, C, R, S = DRIVES[1]
    curves = [Oval(R[0], 0.06), Circle(R[1]), Circle(R[2]), Oval(R[3], 0.03, order=3)]
    turn = over_a_turn(names, C, curves, S, points=36)
    # the back idler turns the other way, at the perimeters' ratio
    assert turn.angles[:, 3] == pytest.approx(-turn.angles[:, 0] * curves[0].perimeter / curves[3].perimeter)
    for i in range(0, 36, 7):
        lay = layout_at(names, C, curves, S, turn.angles[i])
        for sp in lay.spans:
            t = np.array([math.cos(sp.angle), math.sin(sp.angle)])
            for j, p, h in ((sp.start, sp.p0, sp.radius0), (sp.end, sp.p1, sp.radius1)):
                assert abs(t[0] * (p[1] - C[j][1]) - t[1] * (p[0] - C[j][0])) == pytest.approx(h, rel=1e-12)
        assert np.sum(np.sign(lay.rho) * lay.wrap) == pytest.approx(2 * math.pi * lay.orientation)
        assert lay.length == pytest.approx(lay.span_lengths.sum() + lay.arc.sum(), rel=1e-15)
        assert turn.length[i] == lay.length


def test_no_tangent_and_overlap_refused():
    with pytest.raises(ModelError, match="overlap"):
        layout_at(["a", "b"], [(0, 0), (0.05, 0)], [Oval(0.03, 0.1), 0.03], ["inside"] * 2)
