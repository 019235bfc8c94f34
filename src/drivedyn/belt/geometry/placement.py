"""Discretisation of the belt into n rigid segments, placed near static equilibrium.

Segments are chords of length l whose ends lie on the path; consecutive segments are joined by a
gap g carried by the zero-length longitudinal spring (seed eq. 18), g = l (T0/EA)^(1/e_L) at the
pretension T0 (element law F = EA (g/l)^e_L). On an arc the segment centre (the chord midpoint)
must sit inside the contact radius by the static penetration p0 (contact force per length
c1 p^2 + c2 p = T0 / r, the capstan pressure), so chord ends are placed on a circle of radius
sqrt((r - p0)^2 + (l/2)^2). Walking the closed path with alternating chords l and gaps g and
adjusting l (pretension given) or T0 (unstretched length given) until the walk closes starts every
element at the pretension: placing centres evenly on the arcs instead would put about three times
the pretension into the arc elements (the chord sagitta l^2/8r exceeds p0).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...core._roots import find_root
from ...core.errors import ModelError
from . import walk
from ...mechanics.layout import Layout, layout_from
from ...mechanics.pitch_curves import Circle, samples as curve_samples


@dataclass(frozen=True)
class InitialState:
    layout: Layout          # the path the chord ends were placed on
    x: np.ndarray
    y: np.ndarray
    phi: np.ndarray         # unwrapped along the chain; phi[n-1] ~ phi[0] + turn
    seg_length: float       # l (m), unstretched segment length
    tension: float          # T0 (N)
    penetration: np.ndarray # static penetration per pulley (m)
    turn: float             # +-2 pi: total turn of the loop (orientation)
    residual: float = float("nan")  # largest static force left / pretension (nan: not relaxed)
    gap: float = 0.0        # joint gap at the pretension, l (T0 / EA)^(1/e) (m): segment pitch l + gap


class _Path:
    """The closed path as an array of pieces for the walk (walk.py: one row per piece)."""

    def __init__(self, layout: Layout):
        rows, s0 = [], 0.0
        for piece in layout.pieces():
            if piece[0] == "line":
                _, p0, p1, L = piece
                rows.append([0.0, s0, L, p0[0], p0[1], p1[0], p1[1], 0.0])
            else:
                _, c, R, a0, sweep, L = piece
                rows.append([1.0, s0, L, c[0], c[1], R, a0, sweep])
            s0 += L
        self.pieces = np.array(rows, dtype=float)
        self.length = float(s0)


class _CurvePath(_Path):
    """The closed path on pitch curves (mechanics/curve_layout.CurveLayout at the pulleys' rest angles):
    its spans as lines, its wraps on the circles as arcs, on the curves as ARCS_PER_TURN circular arcs a
    turn, each through the curve's points at its ends and middle (within 1e-8 m of an oval of order 2
    and ovality 0.02 on 50 mm: below the contact's static penetration by three orders)."""

    ARCS_PER_TURN = 256

    def __init__(self, lay):
        rows, s0 = [], 0.0
        nk = len(lay.names)
        for k in range(nk):
            sp = lay.spans[k]
            rows.append([0.0, s0, sp.length, sp.p0[0], sp.p0[1], sp.p1[0], sp.p1[1], 0.0])
            s0 += sp.length
            j = sp.end
            c = lay.curves[j]
            sig = 1.0 if lay.rho[j] > 0 else -1.0
            cx, cy = lay.centers[j]
            if isinstance(c, Circle):
                L = c.radius * lay.wrap[j]
                rows.append([1.0, s0, L, cx, cy, c.radius, lay.arc_start[j], sig * lay.wrap[j]])
                s0 += L
                continue
            phi_in, phi_out = sp.phi1, lay.spans[j].phi0
            r_in, dr_in, _ = c.r(phi_in)
            r_out, dr_out, _ = c.r(phi_out)
            sweep = sig * lay.wrap[j] + math.atan2(dr_out, r_out) - math.atan2(dr_in, r_in)
            m = max(2, int(math.ceil(abs(sweep) / (2 * math.pi) * self.ARCS_PER_TURN)))
            th = lay.angles[j]
            pt = lambda f: (cx + c.r(f)[0] * math.cos(f + th), cy + c.r(f)[0] * math.sin(f + th))
            for q in range(m):
                f0 = phi_in + sweep * q / m
                f1 = phi_in + sweep * (q + 1) / m
                a, b, e = pt(f0), pt(0.5 * (f0 + f1)), pt(f1)
                ox, oy, R = _circle_through(a, b, e)
                a0 = math.atan2(a[1] - oy, a[0] - ox)
                a1 = math.atan2(e[1] - oy, e[0] - ox)
                sw = (a1 - a0) % (2 * math.pi) if sig > 0 else -((a0 - a1) % (2 * math.pi))
                rows.append([1.0, s0, R * abs(sw), ox, oy, R, a0, sw])
                s0 += R * abs(sw)
        self.pieces = np.array(rows, dtype=float)
        self.length = float(s0)


def _circle_through(a, b, c):
    """(centre x, y, radius) of the circle through three points."""
    ax, ay = a
    bx, by = b[0] - ax, b[1] - ay
    cx, cy = c[0] - ax, c[1] - ay
    d = 2 * (bx * cy - by * cx)
    b2, c2 = bx * bx + by * by, cx * cx + cy * cy
    ux, uy = (cy * b2 - by * c2) / d, (bx * c2 - cx * b2) / d
    return ax + ux, ay + uy, math.hypot(ux, uy)


def _offset_curve(sampled, offset):
    """mechanics.pitch_curves.Table of the curve ``sampled`` (pitch_curves.samples) offset along its outward
    normal by offset(kappa) (m; kappa the curvature there, an array)."""
    from ...mechanics.pitch_curves import Table, offset_radii

    # 181 rows: the periodic spline's error (h^4 / 384 of r's 4th derivative) is 1e-10 m on an oval of
    # order 2 and ovality 0.02
    grid = np.linspace(0.0, 2 * math.pi, 181)
    r = offset_radii(sampled, offset(sampled[2]), grid)
    r[-1] = r[0]
    t = Table(np.column_stack([grid, r]).tolist())
    t._intervals = 90      # its arc lengths are not walked (_CurvePath): a coarse table serves layout_at
    object.__setattr__(t, "_mean", float(np.mean(r[:-1])))     # from the rows, not 4096 points of the spline
    object.__setattr__(t, "_ext", (float(r.min()), float(r.max())))
    return t


def penetration(q, c1, c2):
    """Depth p (m) at which the contact law's elastic part carries the pressure q (N/m, per unit
    length of belt): c1 p^2 + c2 p = q (seed eq. 9, per unit length as in the model's contact
    data); the root in the form 2 q / (c2 + sqrt(c2^2 + 4 c1 q)), exact also as c1 -> 0."""
    q = np.maximum(q, 0.0)
    return 2.0 * q / (c2 + np.sqrt(c2 * c2 + 4.0 * c1 * q))   # c2 = inf: 0 (rigid)


def static_penetration(tension, radius, contact):
    """Penetration p0 (m) where c1 p^2 + c2 p = T / r (per unit length: capstan pressure)."""
    q = tension / radius
    c1, c2 = contact.stiffness_quadratic, contact.stiffness_linear
    if c1 > 0:
        return (-c2 + math.sqrt(c2 * c2 + 4 * c1 * q)) / (2 * c1)
    return q / c2


def _walk(path: _Path, n: int, l: float, g: float):
    """Place n chords of length l separated by gaps g; return ends and the arc length reached.
    Interpreted (walk.py), also in a run: a placement takes 10-80 walks (6 / 60-90 ms for the 5PK drive
    and fead-runup on a slow 2-core machine), where compiling the walk on a first run took 1.1 s,
    ahead of everything else."""
    starts, ends, s = walk.walk_pieces(path.pieces.tolist(), path.length, n, l, g)
    if not s >= 0:
        raise ModelError("cannot place the belt segments on the path", field="belt.segments")
    return starts, ends, s


def _bracketed_root(f, guess):
    """Root of f near guess (f increasing): widen the bracket until it changes sign."""
    lo, hi = 0.98 * guess, 1.01 * guess
    for _ in range(20):
        flo, fhi = f(lo), f(hi)
        if flo < 0 < fhi:
            return find_root(f, lo, hi, xtol=1e-13 * guess)
        if flo >= 0:
            lo *= 0.97
        if fhi <= 0:
            hi *= 1.03
    raise ModelError("cannot close the belt on the path with these segments", field="belt.segments")


def check_length(model, layout: Layout, too_long: bool = True) -> None:
    """A belt given by its length must be shorter than the path and stretch less than 5 % on it.
    ``too_long=False``: the second only (a segment chain, which rides at a rolling radius above the
    pulleys' and may be a little longer than the drawn path, is checked by its placement)."""
    belt = model.belt
    if too_long and belt.length >= layout.length:
        raise ModelError(f"belt too long to be tensioned: unstretched length {belt.length:.4f} m >= path length "
                         f"{layout.length:.4f} m", field="belt.length")
    strain = layout.length / belt.length - 1
    if (strain > 0.05 and belt.axial_exponent == 1.0) or strain ** belt.axial_exponent > 0.05:
        raise ModelError(f"belt too short to wrap the pulleys: unstretched length {belt.length:.4f} m against a path of "
                         f"{layout.length:.4f} m would need {strain * 100:.1f} % strain", field="belt.length")


def initial_state(model, layout: Layout) -> InitialState:
    belt, n = model.belt, model.belt.segments
    r_min = min(p.radius for p in model.pulleys)
    if layout.length / n > r_min:
        raise ModelError(f"{n} segments of about {layout.length / n * 1e3:.1f} mm are too coarse for the "
                         f"{r_min * 1e3:.1f} mm pulley: use at least {math.ceil(layout.length / r_min)}", field="belt.segments")
    EA, e = belt.axial_stiffness, belt.axial_exponent
    radii = np.array([p.radius for p in model.pulleys])
    names = [p.name for p in model.pulleys]
    sides = [p.side for p in model.pulleys]

    curved = any(p.pitch_curve is not None for p in model.pulleys)
    samples = {j: curve_samples(p.curve, 720) for j, p in enumerate(model.pulleys) if p.pitch_curve is not None}

    def place(l, T):
        p0 = np.array([static_penetration(T, r, model.contact) for r in radii])
        if np.any(p0 >= 0.5 * radii):
            raise ModelError(f"contact too soft: static penetration {p0.max() * 1e3:.2f} mm at the pretension", field="contact")
        Re = np.sqrt((radii - p0) ** 2 + (l / 2) ** 2)
        g = l * (T / EA) ** (1.0 / e)
        if curved:      # the chord ends on the curves offset as the circles are, by their curvature's radius
            from ...mechanics.curve_layout import layout_at

            curves = [Circle(Re[j]) if q.pitch_curve is None else
                      _offset_curve(samples[j], lambda k, p=p0[j]: np.sqrt((1 / k - p) ** 2 + l * l / 4) - 1 / k)
                      for j, q in enumerate(model.pulleys)]
            cl = layout_at(names, layout.centers, curves, sides, orientation=layout.orientation)
            path = _CurvePath(cl)
            lay = layout_from(names, layout.centers, Re, sides, orientation=layout.orientation)
            object.__setattr__(lay, "_curve_path", path)   # the walked path, beside the circles (frozen)
            return lay, _walk(path, n, l, g), p0
        lay = layout_from(names, layout.centers, Re, sides, orientation=layout.orientation)
        return lay, _walk(_Path(lay), n, l, g), p0

    def path_length(lay):
        return lay._curve_path.length if curved else _Path(lay).length

    if belt.pretension is not None:
        T = belt.pretension
        L_path = layout.length
        guess = L_path / n / (1 + (T / EA) ** (1 / e))

        def resid(l):
            lay, (_, _, s_end), _ = place(l, T)
            return s_end - path_length(lay)

        l = _bracketed_root(resid, guess)
    else:
        l = belt.length / n
        check_length(model, layout, too_long=False)

        def resid_T(T):
            lay, (_, _, s_end), _ = place(l, T)
            return s_end - path_length(lay)

        # a coarse chain rides at a rolling radius above the pulleys' and may be longer than the
        # drawn path: start the bracket from a small strain then
        strain = max(layout.length / belt.length - 1, 1e-3)
        T_guess = EA * strain ** e
        # the chords run inside the arcs, so the closing tension can lie well off the continuum
        # guess at low strain: widen the bracket until the residual changes sign
        lo, hi = 0.2 * T_guess, 3.0 * T_guess
        for _ in range(8):
            try:
                r_lo, r_hi = resid_T(lo), resid_T(hi)
            except ModelError:
                r_lo = r_hi = 0.0
            if r_lo * r_hi < 0:
                break
            lo, hi = lo / 5, hi * 2
        try:
            T = find_root(resid_T, lo, hi, xtol=1e-9 * T_guess)
        except ValueError:
            raise ModelError("cannot place the belt on the layout at this length (too short to wrap?)", field="belt.length") from None
    if belt.length is None and l * n < 0.5 * layout.length:
        raise ModelError("pretension too high for the axial stiffness", field="belt.pretension")

    lay, (starts, ends, _), p0 = place(l, T)
    mid = 0.5 * (starts + ends)
    d = ends - starts
    phi = np.unwrap(np.arctan2(d[:, 1], d[:, 0]))
    turn = 2 * math.pi * layout.orientation
    return InitialState(lay, mid[:, 0].copy(), mid[:, 1].copy(), phi, float(l), float(T), p0, turn,
                        gap=float(l * (T / EA) ** (1.0 / e)))
