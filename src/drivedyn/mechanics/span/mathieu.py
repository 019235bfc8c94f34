"""Parametric-resonance boundaries in the (F0, V) plane: first order (seed) and exact (Mathieu).

Keeping the first harmonic, Phi = cos(omega t), eq. 6 of the seed,
q'' + Omega^2 (1 + 2 mu cos omega t) q = 0, becomes with z = omega t / 2 the Mathieu equation
y'' + (a - 2 q cos 2z) y = 0 with

    a = 4 Omega^2 / omega^2 = 4 k^2 N / (rhoA omega^2),     |q| = a mu = 2 k^2 F1 / (rhoA omega^2),

k = pi / l, N = F0 + F* - V^2 rhoA. The tongue of order n (n = 1 principal, omega ~ 2 Omega / n)
lies between the characteristic values b_n(|q|) and a_n(|q|) (McLachlan 1947, ch. 4;
Abramowitz & Stegun 20.2). Since |q| depends on V only and a is linear in F0, every boundary is
an explicit curve F0(V):

    F0 = a_n(|q|) rhoA omega^2 / (4 k^2) - F* + V^2 rhoA.

The seed's first-order boundaries omega = 2 Omega sqrt(1 +- mu) (Bolotin 1956) read
1/a = 1 -+ mu, i.e. N = rhoA omega^2 / (4 k^2) +- F1 / 2: a band of constant width F1 in F0.
"""
from __future__ import annotations

import numpy as np
from scipy import optimize, special

from .quantities import SpanProperties, critical_speed, excitation_frequency


def characteristic_values(n: int, q):
    """(lower, upper) edges of the Mathieu tongue of order n >= 1 at |q|: sorted b_n, a_n."""
    q = np.abs(np.asarray(q, dtype=float))
    a = special.mathieu_a(n, q)
    b = special.mathieu_b(n, q)
    return np.minimum(a, b), np.maximum(a, b)


def _k2_over_m(sp):
    return (np.pi / sp.length) ** 2 / sp.mass_per_length


def mathieu_q(V, sp: SpanProperties, F1, teeth, pitch, convention="tooth-passing"):
    """|q| = 2 k^2 F1 / (rhoA omega^2) at speed V (inf at V = 0)."""
    w = excitation_frequency(V, teeth, pitch, convention)
    with np.errstate(divide="ignore"):
        return 2.0 * _k2_over_m(sp) * F1 / w ** 2


def exact_boundaries(V, n: int, sp: SpanProperties, F1, teeth, pitch, convention="tooth-passing"):
    """Pretensions (F0_low, F0_high) of the exact tongue n at speeds V (N).

    The tongue is the set F0_low < F0 < F0_high; NaN where V = 0.
    """
    V = np.asarray(V, dtype=float)
    w = excitation_frequency(V, teeth, pitch, convention)
    q = mathieu_q(V, sp, F1, teeth, pitch, convention)
    lo, hi = characteristic_values(n, np.where(np.isfinite(q), q, 0.0))
    scale = w ** 2 / (4.0 * _k2_over_m(sp))
    shift = -sp.euler_load + V ** 2 * sp.mass_per_length
    bad = ~(V > 0)
    return np.where(bad, np.nan, lo * scale + shift), np.where(bad, np.nan, hi * scale + shift)


def first_order_boundaries(V, sp: SpanProperties, F1, teeth, pitch, convention="tooth-passing"):
    """Pretensions (F0_low, F0_high) of the seed's first-order principal tongue at speeds V (N)."""
    V = np.asarray(V, dtype=float)
    w = excitation_frequency(V, teeth, pitch, convention)
    centre = w ** 2 / (4.0 * _k2_over_m(sp)) - sp.euler_load + V ** 2 * sp.mass_per_length
    return centre - 0.5 * F1, centre + 0.5 * F1


def tongue_centre_speed(F0, n: int, sp: SpanProperties, teeth, pitch, convention="tooth-passing"):
    """Speed where omega = 2 Omega / n at pretension F0 (m/s): the backbone of tongue n.

    From N = n^2 rhoA omega^2 / (4 k^2) with omega = c V: V^2 = (F0 + F*) / (rhoA (1 + n^2 c^2 / (4 k^2 rhoA)))
    """
    c = excitation_frequency(1.0, teeth, pitch, convention)
    m = sp.mass_per_length
    return np.sqrt((np.asarray(F0, float) + sp.euler_load) / (m + n * n * c * c * m / (4.0 * (np.pi / sp.length) ** 2)))


def speed_band(F0: float, n: int, sp: SpanProperties, F1, teeth, pitch, convention="tooth-passing",
               method: str = "exact"):
    """[v_low, v_high] (m/s) of tongue n at pretension F0, or None if there is no band.

    Each boundary F0_b(V) is increasing in V near the tongue, so each edge is the root of
    F0_b(V) - F0 in a bracket around the backbone speed.
    """
    vc = float(tongue_centre_speed(F0, n, sp, teeth, pitch, convention))
    vmax = float(critical_speed(F0, sp))

    def edge(k):
        def g(v):
            if method == "first-order":
                return first_order_boundaries(v, sp, F1, teeth, pitch, convention)[k] - F0
            return exact_boundaries(v, n, sp, F1, teeth, pitch, convention)[k] - F0

        lo, hi = 0.25 * vc, min(2.0 * vc, vmax * (1 - 1e-12))
        grid = np.linspace(lo, hi, 401)
        vals = np.array([float(g(v)) for v in grid])
        ok = np.isfinite(vals)
        sign = np.where(ok[:-1] & ok[1:] & (np.sign(vals[:-1]) != np.sign(vals[1:])))[0]
        if len(sign) == 0:
            return np.nan
        # the crossing nearest the backbone
        i = sign[np.argmin(np.abs(grid[sign] - vc))]
        return optimize.brentq(lambda v: float(g(v)), grid[i], grid[i + 1], xtol=1e-12, rtol=1e-12)

    # F0_high(V) = F0 at the lower speed edge, F0_low(V) = F0 at the upper speed edge
    v_low, v_high = edge(1), edge(0)
    if not (np.isfinite(v_low) and np.isfinite(v_high)) or v_high <= v_low:
        return None
    return [float(v_low), float(v_high)]
