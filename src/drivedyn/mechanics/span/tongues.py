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
#: points of the undamped band searched for the damped tongue (with the excitation's own frequency)
SCAN = 9
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


def place(f1: float, fe: float, depth: float, zeta: float, n: int) -> TonguePlace:
    """The excitation (f_e Hz, depth e = dT / N) against tongue n of a span of first frequency f1
    (Hz) and modal damping ratio zeta."""
    rho = float(_rho(f1, [fe], depth, zeta)[0])
    und = undamped_band(f1, depth, n)
    # growth at f_e belongs to this tongue where f_e is inside its undamped band (the tongues of one
    # depth do not overlap below e ~ 1: McLachlan 1947, fig. 8)
    inside = rho > UNSTABLE and und is not None and und[0] <= fe <= und[1]
    band = None
    if und is not None:
        band = und if zeta <= 0 else _damped_band(f1, fe, depth, zeta, und, inside)
    if band is None:
        dist = abs(fe - 2.0 * f1 / n) / fe
    elif band[0] <= fe <= band[1] or inside:
        dist = 0.0
    else:
        dist = (band[0] - fe) / fe if fe < band[0] else (fe - band[1]) / fe
    return TonguePlace(n, 2.0 * f1 / n, band, und, bool(inside), rho, dist)


def _damped_band(f1, fe, depth, zeta, und, inside):
    """The damped tongue's (f_low, f_high) within the undamped band ``und``, or None if closed."""
    lo, hi = und
    grid = np.linspace(lo, hi, SCAN + 2)[1:-1]
    if inside and lo < fe < hi:
        grid = np.sort(np.append(grid, fe))
    r = _rho(f1, grid, depth, zeta)
    bad = np.nonzero(r > UNSTABLE)[0]
    if not len(bad):
        return None

    def g(f):
        return float(_rho(f1, [f], depth, zeta)[0]) - UNSTABLE

    f_low = optimize.brentq(g, lo, grid[bad[0]], xtol=1e-9 * hi) if g(lo) < 0 else lo
    f_high = optimize.brentq(g, grid[bad[-1]], hi, xtol=1e-9 * hi) if g(hi) < 0 else hi
    return float(f_low), float(f_high)


def nearest(places):
    """The (f_e, place) of a list nearest its tongue: inside first, then open tongues, then the
    smallest distance (None for an empty list)."""
    if not places:
        return None
    return min(places, key=lambda p: (not p[1].inside, not p[1].open, p[1].distance))
