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

    def place(l, T):
        p0 = np.array([static_penetration(T, r, model.contact) for r in radii])
        if np.any(p0 >= 0.5 * radii):
            raise ModelError(f"contact too soft: static penetration {p0.max() * 1e3:.2f} mm at the pretension", field="contact")
        Re = np.sqrt((radii - p0) ** 2 + (l / 2) ** 2)
        lay = layout_from(names, layout.centers, Re, sides, orientation=layout.orientation)
        g = l * (T / EA) ** (1.0 / e)
        return lay, _walk(_Path(lay), n, l, g), p0

    if belt.pretension is not None:
        T = belt.pretension
        L_path = layout.length
        guess = L_path / n / (1 + (T / EA) ** (1 / e))

        def resid(l):
            lay, (_, _, s_end), _ = place(l, T)
            return s_end - _Path(lay).length

        l = _bracketed_root(resid, guess)
    else:
        l = belt.length / n
        check_length(model, layout, too_long=False)

        def resid_T(T):
            lay, (_, _, s_end), _ = place(l, T)
            return s_end - _Path(lay).length

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
