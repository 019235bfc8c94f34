"""Single tooth-pair stiffness from the tooth geometry by the potential-energy method.

The tooth is a non-uniform cantilever on the gear body, loaded along the line of action at the
contact point (x_c, h_c); x runs along the tooth centreline from the gear centre, h is the
half thickness, alpha_1 the angle between the load and the normal to the centreline:

    alpha_1 = tan(alpha_c) - alpha_2,  alpha_2 = pi/(2z) + 2 x tan(alpha)/z + inv(alpha)
    1/k_b = int [(x_c - x) cos a1 - h_c sin a1]^2 / (E I_x) dx      I_x = 2/3 h^3 b   (Yang & Lin 1987)
    1/k_s = int 1.2 cos^2 a1 / (G A_x) dx                          A_x = 2 h b       (Tian 2004)
    1/k_a = int sin^2 a1 / (E A_x) dx                                                 (Yang & Lin 1987)
    1/k_h = 4 (1 - nu^2) / (pi E b)                                Hertz, load-independent (Yang & Lin 1987)
    1/k_f = cos^2 a1 / (E b) [L* (u_f/S_f)^2 + M* (u_f/S_f) + P* (1 + Q* tan^2 a1)]
                                                                   fillet foundation (Sainsot et al. 2004)

The integrals are taken numerically over the real profile: the involute above the base circle and,
where the root circle lies below it, a radial flank from the root to the base circle (the usual
assumption); where the root circle lies above the base circle the beam starts at the root on the
involute (the classic closed forms in alpha are wrong there, gears-formulas.md 4).
"""
from __future__ import annotations

import math

import numpy as np

from .geometry import GearGeometry, PairGeometry, inv

_GL_X, _GL_W = np.polynomial.legendre.leggauss(24)

# Sainsot, Velex & Duverger, J. Mech. Des. 126 (2004) 748-752, table 1:
# X* = A/theta_f^2 + B h_f^2 + C h_f/theta_f + D/theta_f + E h_f + F
_FILLET = {
    "L": (-5.574e-5, -1.9986e-3, -2.3015e-4, 4.7702e-3, 0.0271, 6.8045),
    "M": (60.111e-5, 28.100e-3, -83.431e-4, -9.9256e-3, 0.1624, 0.9086),
    "P": (-50.952e-5, 185.50e-3, 0.0538e-4, 53.300e-3, 0.2895, 0.9236),
    "Q": (-6.2042e-5, 9.0889e-3, -4.0964e-4, 7.8297e-3, -0.1472, 0.6904),
}


def _fillet_coef(name, h_f, th_f):
    a, b, c, d, e, f = _FILLET[name]
    return a / th_f ** 2 + b * h_f ** 2 + c * h_f / th_f + d / th_f + e * h_f + f


def _profile(g: GearGeometry, r):
    """Centreline coordinate x and half thickness h of the tooth at radius r (array)."""
    a2 = g.half_angle_base
    r = np.asarray(r, dtype=float)
    beta = np.where(r > g.rb, a2 - (np.sqrt(np.maximum(r ** 2 / g.rb ** 2 - 1, 0)) - np.arccos(np.minimum(g.rb / r, 1.0))), a2)
    return r * np.cos(beta), r * np.sin(beta)


def tooth_compliance(g: GearGeometry, rho: float, b: float, E: float, nu: float, r_int: float) -> float:
    """Bending + shear + axial + fillet compliance (m/N) of one tooth loaded at ``rho`` from its tangent point."""
    a1 = rho / g.rb - g.half_angle_base                 # load angle alpha_1 = tan(alpha_c) - alpha_2
    r_c = math.hypot(g.rb, rho)
    xc, hc = (float(v) for v in _profile(g, r_c))
    G = E / (2 * (1 + nu))
    ca, sa = math.cos(a1), math.sin(a1)
    comp = 0.0
    r0 = g.rf
    # integrate in r over [r_f, r_b] (radial flank) and [max(r_f, r_b), r_c] (involute), Gauss-Legendre
    for lo, hi in ((r0, min(g.rb, r_c)), (max(r0, g.rb), r_c)):
        if hi <= lo:
            continue
        rr = 0.5 * (hi - lo) * _GL_X + 0.5 * (hi + lo)
        x, h = _profile(g, rr)
        eps = 1e-7 * (hi - lo)
        dxdr = (_profile(g, rr + eps)[0] - _profile(g, rr - eps)[0]) / (2 * eps)
        w = 0.5 * (hi - lo) * _GL_W * dxdr
        I, A = 2.0 / 3.0 * h ** 3 * b, 2 * h * b
        bend = ((xc - x) * ca - hc * sa) ** 2 / (E * I)
        shear = 1.2 * ca ** 2 / (G * A)
        axial = sa ** 2 / (E * A)
        comp += float(np.sum(w * (bend + shear + axial)))
    # fillet foundation (Sainsot 2004): u_f from the root circle to where the load line crosses the centreline
    th_f = g.half_angle_base - (inv(math.acos(g.rb / g.rf)) if g.rf > g.rb else 0.0)
    s_f = 2 * g.rf * th_f
    u_f = g.rb / ca - g.rf
    h_f = g.rf / r_int
    L, M, P, Q = (_fillet_coef(n, h_f, th_f) for n in "LMPQ")
    comp += ca ** 2 / (E * b) * (L * (u_f / s_f) ** 2 + M * (u_f / s_f) + P * (1 + Q * math.tan(a1) ** 2))
    return comp


def pair_stiffness(geo: PairGeometry, rho1, b: float, E: tuple, nu: tuple, r_int: tuple):
    """Stiffness (N/m) of one tooth pair in contact at ``rho1`` (array, from T1) along the line of action."""
    rho1 = np.atleast_1d(np.asarray(rho1, dtype=float))
    # Hertz: two equal-width cylinders, Yang & Lin: 1/k_h = 4(1-nu^2)/(pi E b), averaged for two materials
    ch = 2.0 / (math.pi * b) * ((1 - nu[0] ** 2) / E[0] + (1 - nu[1] ** 2) / E[1])
    out = np.empty_like(rho1)
    for k, r1 in enumerate(rho1):
        c1 = tooth_compliance(geo.g1, r1, b, E[0], nu[0], r_int[0])
        c2 = tooth_compliance(geo.g2, geo.tangent_length - r1, b, E[1], nu[1], r_int[1])
        out[k] = 1.0 / (ch + c1 + c2)
    return out
