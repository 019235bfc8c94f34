"""Where one tension fluctuation of a span sits against the span's parametric-resonance tongues.

A span of first transverse frequency f1 (Hz) whose tension carries a fluctuation dT at frequency f_e
obeys, one mode kept, the damped Hill equation of seed 002 (eq. 5; ``floquet.py``)

    q'' + 2 zeta Omega q' + Omega^2 (1 + e cos(2 pi f_e t)) q = 0,   Omega = 2 pi f1,
    e = dT / N,  N = T + F* - m V^2   (quantities.effective_tension: the span's stiffness per pi^2/l^2),

i.e. in ``_kernels``' form alpha = (f1 / f_e)^2, beta = e alpha, gamma = 2 zeta sqrt(alpha)
(floquet.hill_parameters with F1 = dT). With z = pi f_e t it is Mathieu's equation
y'' + (a - 2 q cos 2z) y = 0 with a = 4 alpha and |q| = 2 beta = a e / 2; tongue n (n = 1 principal,
f_e ~ 2 f1 / n) is b_n(|q|) < a < a_n(|q|) (McLachlan 1947, ch. 4; mathieu.characteristic_values).
Since |q| grows with a at a fixed depth e, each edge is the root of a - c_n(a e / 2): the undamped
band [f_low, f_high] of the tongue at that depth. Damping narrows it and closes it below a threshold
depth (about e = 4 zeta for the principal tongue: Nayfeh & Mook 1979, sec. 5.2.6); the damped band
is read from the Floquet multipliers (floquet.multipliers) inside the undamped one.

For an axially moving span, f1 is the moving span's frequency (Mote 1965's gyroscopic span: the
principal resonance sits at twice it, Mockensturm, Perkins & Ulsoy 1996, J. Vib. Acoust. 118, 346);
the width from the one-mode equation is the seed's approximation.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import optimize

from .chart import UNSTABLE
from .floquet import multipliers
from .mathieu import characteristic_values

#: tongues judged: the principal (f_e ~ 2 f1) and the next (f_e ~ f1)
TONGUES = (1, 2)
#: points across the undamped band where the damped tongue's multipliers are computed (an open
#: tongue's edges then refined between them to EDGE_TOL of the frequency)
SCAN = 21
EDGE_TOL = 1e-7
#: RK4 steps per free oscillation of the Floquet integration (floquet.multipliers: |lambda| to ~1e-6)
STEPS = 48


@dataclass(frozen=True)
class TonguePlace:
    """One excitation against one tongue.

    Attributes
    ----------
    tongue : int
        Tongue order n (f_e ~ 2 f1 / n).
    centre : float
        2 f1 / n (Hz).
    band : tuple or None
        (f_low, f_high) of the tongue at this depth with damping (Hz); None where the depth is
        below the damped tongue's threshold (closed).
    band_undamped : tuple or None
        The same without damping (Hz); None at zero depth.
    inside : bool
        The largest Floquet multiplier at (f_e, depth) exceeds 1 (chart.UNSTABLE): the span's
        transverse motion grows.
    multiplier : float
        That multiplier's modulus.
    distance : float
        The share of f_e by which f_e must move to enter the damped band (0 inside); where the band
        is closed, to reach the tongue's centre 2 f1 / n (where it opens first as the depth grows).
    """

    tongue: int
    centre: float
    band: tuple | None
    band_undamped: tuple | None
    inside: bool
    multiplier: float
    distance: float

    @property
    def open(self) -> bool:
        """The damped tongue exists at this depth."""
        return self.band is not None


def _rho(f1, fe, depth, zeta):
    """Largest multiplier modulus at excitation frequencies ``fe`` (array), one harmonic."""
    alpha = (f1 / np.asarray(fe, float)) ** 2
    return multipliers(alpha, depth * alpha, 2.0 * zeta * np.sqrt(alpha), [1.0], [0.0], STEPS)[2]


def undamped_band(f1: float, depth: float, n: int):
    """(f_low, f_high) in Hz of the undamped tongue n of a span of first frequency f1 at depth
    e = dT / N, from Mathieu's characteristic values; None at zero depth or where an edge has no
    root (a depth so large that the tongue is no band in frequency)."""
    if not depth > 0:
        return None
    a_edges = []
    for k in (0, 1):        # lower and upper characteristic value
        def g(a):
            return a - float(characteristic_values(n, 0.5 * a * depth)[k])

        lo, hi = 1e-9, 4.0 * (n + 1) ** 2
        if not g(lo) < 0 < g(hi):
            return None
        a_edges.append(optimize.brentq(g, lo, hi, xtol=1e-13, rtol=1e-13))
    # f_e = f1 * 2 / sqrt(a): the upper characteristic value is the lower frequency edge
    return 2.0 * f1 / math.sqrt(a_edges[1]), 2.0 * f1 / math.sqrt(a_edges[0])


def nearest_tongue(f1: float, fe: float) -> int:
    """The tongue whose centre 2 f1 / n lies nearest f_e (in ratio)."""
    return min(TONGUES, key=lambda n: abs(math.log(fe * n / (2.0 * f1))))


def screen(depth: float) -> float:
    """The share of its centre frequency 2 f1 / n within which tongue n's band at depth e surely lies
    (e <= 2): the undamped band lies within e / 4 + O(e^2) of the centre for n = 1 and e^2 / 8 + O(e^4)
    for n = 2 (first-order characteristic values, McLachlan 1947, sec. 4.13), damping only narrows it;
    tests/span/test_tongues.py checks the bound on the exact edges. A component beyond it needs no
    Floquet pass to be outside."""
    return 0.3 * depth + 0.01


def place(f1: float, fe: float, depth: float, zeta: float, n: int | None = None, refine: bool = True) -> TonguePlace:
    """The excitation (f_e Hz, depth e = dT / N) against tongue n (default: the nearest,
    :func:`nearest_tongue`) of a span of first frequency f1 (Hz) and modal damping ratio zeta.
    ``refine=False``: an open tongue's edges interpolated linearly on the SCAN grid, not refined
    (within a grid step: to rank many places, then refine the one kept)."""
    n = nearest_tongue(f1, fe) if n is None else n
    und = undamped_band(f1, depth, n)
    if und is None:
        rho = float(_rho(f1, [fe], depth, zeta)[0])
        band = None
    else:
        # one Floquet pass: f_e and a grid across the undamped band, which holds the damped one
        grid = np.linspace(und[0], und[1], SCAN)
        r = _rho(f1, np.append(grid, fe), depth, zeta)
        rho, r = float(r[-1]), r[:-1]
        band = und if zeta <= 0 else _damped_band(f1, depth, zeta, grid, r, refine)
    # growth at f_e belongs to this tongue where f_e is inside its undamped band (the tongues of one
    # depth do not overlap below e ~ 1: McLachlan 1947, fig. 8)
    inside = rho > UNSTABLE and und is not None and und[0] <= fe <= und[1]
    if band is None:
        dist = float(abs(fe - 2.0 * f1 / n) / fe)
    elif band[0] <= fe <= band[1] or inside:
        dist = 0.0
    else:
        dist = float((band[0] - fe) / fe if fe < band[0] else (fe - band[1]) / fe)
    return TonguePlace(n, 2.0 * f1 / n, band, und, bool(inside), rho, dist)


def _damped_band(f1, depth, zeta, grid, r, refine=True):
    """The damped tongue's (f_low, f_high) from the multipliers ``r`` on ``grid`` (across the
    undamped band): each edge by Brent's method in the grid interval where r crosses UNSTABLE
    (only for an open tongue; ``refine=False``: interpolated linearly there); None if closed."""
    bad = np.nonzero(r > UNSTABLE)[0]
    if not len(bad):
        return None
    i, j = bad[0], bad[-1]
    if not refine:
        def cross(k):
            g0, g1 = r[k] - UNSTABLE, r[k + 1] - UNSTABLE
            return float(grid[k] + (grid[k + 1] - grid[k]) * g0 / (g0 - g1))

        return (cross(i - 1) if i > 0 else float(grid[0])), (cross(j) if j < len(grid) - 1 else float(grid[-1]))

    def g(f):
        return float(_rho(f1, [f], depth, zeta)[0]) - UNSTABLE

    tol = EDGE_TOL * float(grid[-1])
    lo = optimize.brentq(g, grid[i - 1], grid[i], xtol=tol) if i > 0 else float(grid[0])
    hi = optimize.brentq(g, grid[j], grid[j + 1], xtol=tol) if j < len(grid) - 1 else float(grid[-1])
    return float(lo), float(hi)


def nearest(places):
    """The (f_e, place) of a list nearest its tongue: inside first, then open tongues, then the
    smallest distance (None for an empty list)."""
    if not places:
        return None
    return min(places, key=lambda p: (not p[1].inside, not p[1].open, p[1].distance))
