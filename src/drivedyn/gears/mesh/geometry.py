"""Involute spur and helical gear geometry: radii of one gear and the contact of a pair.

Formulas: ISO 21771:2007 (DIN 3960) for radii, working pressure angle and centre distance
(transverse quantities of a helical gear: m_t = m_n / cos beta, tan alpha_t = tan alpha_n / cos beta,
tan beta_b = tan beta cos alpha_t, inv alpha_wt = inv alpha_t + 2 tan alpha_n (x1 + x2) / (z1 + z2));
the path of contact and the transverse contact ratio from the tangent-point construction in the
transverse plane (Niemann & Winter, Maschinenelemente II, 21.3); the overlap ratio
eps_beta = b sin beta / (pi m_n). Lengths in m, angles in rad.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ...core.errors import ModelError


#: relative tolerance of a centre distance below the zero-backlash one: profile shifts printed to four
#: decimals (x within 5e-5) move the zero-backlash centre distance by up to about 1e-4 m_n, a few 1e-7
#: of it; a printed centre distance that far below is the same gear pair, not an interference
CENTRE_TOLERANCE = 1e-6


def inv(alpha: float) -> float:
    """Involute function inv(a) = tan(a) - a."""
    return math.tan(alpha) - alpha


def inv_inverse(y: float) -> float:
    """The angle whose involute is ``y`` (Newton, from Cheng's start ~ (3y)^(1/3))."""
    a = (3.0 * y) ** (1.0 / 3.0) if y > 0 else 0.0
    for _ in range(50):
        f = math.tan(a) - a - y
        da = f / math.tan(a) ** 2 if a > 0 else 0.0
        a -= da
        if abs(da) < 1e-15:
            break
    return a


@dataclass(frozen=True)
class GearGeometry:
    """Radii of one gear (ISO 21771: d = z m_t, d_b = d cos alpha_t, d_a = d + 2 m_n (h_aP* + x),
    d_f = d - 2 m_n (h_fP* - x)); ``m`` and ``alpha`` are the normal module and pressure angle."""

    z: int
    m: float
    alpha: float
    x: float
    b: float
    r: float
    rb: float
    ra: float
    rf: float
    half_angle_base: float   # alpha_2 of the potential-energy method: half tooth angle at the base circle
    beta: float = 0.0        # helix angle at the reference cylinder (>= 0)
    hand: str = "right"

    @classmethod
    def of(cls, gear) -> "GearGeometry":
        z, m, a, x = gear.teeth, gear.module, gear.pressure_angle, gear.profile_shift
        beta = getattr(gear, "helix_angle", 0.0)
        at = math.atan(math.tan(a) / math.cos(beta))
        r = 0.5 * z * m / math.cos(beta)
        ra = 0.5 * gear.tip_diameter if gear.tip_diameter is not None else r + m * (gear.addendum + x)
        rf = r - m * (gear.dedendum - x)
        # half tooth thickness angle at the base circle: pi/(2z) + 2 x tan(a)/z + inv(a) (Yang & Lin 1987; spur)
        a2 = math.pi / (2 * z) + 2 * x * math.tan(at) / z + inv(at)
        return cls(z=z, m=m, alpha=a, x=x, b=gear.face_width, r=r, rb=r * math.cos(at), ra=ra, rf=rf,
                   half_angle_base=a2, beta=beta, hand=getattr(gear, "hand", "right"))

    @property
    def alpha_t(self) -> float:
        """Transverse pressure angle."""
        return math.atan(math.tan(self.alpha) / math.cos(self.beta))

    @property
    def beta_b(self) -> float:
        """Base helix angle."""
        return math.atan(math.tan(self.beta) * math.cos(self.alpha_t))

    @property
    def base_pitch(self) -> float:
        """Transverse base pitch p_bt = pi m_t cos(alpha_t) (= pi m cos(alpha) for spur)."""
        return math.pi * self.m / math.cos(self.beta) * math.cos(self.alpha_t)


@dataclass(frozen=True)
class PairGeometry:
    """Contact geometry of gear 1 (driving) with gear 2 (external spur pair).

    Positions along the line of action are distances ``rho`` from the pinion's tangent point T1;
    the pair's contact runs from A (rho_start) to E (rho_end); the pitch point is at rho_pitch.
    """

    g1: GearGeometry
    g2: GearGeometry
    alpha_w: float
    a_w: float
    a_zero_backlash: float
    tangent_length: float    # T1T2 = a_w sin(alpha_w)
    rho_start: float         # T1A
    rho_end: float           # T1E
    rho_pitch: float         # T1C = r_b1 tan(alpha_w)

    @property
    def base_pitch(self) -> float:
        return self.g1.base_pitch

    @property
    def path_of_contact(self) -> float:
        """g_alpha = AE."""
        return self.rho_end - self.rho_start

    @property
    def contact_ratio(self) -> float:
        """Transverse contact ratio eps_alpha = g_alpha / p_bt."""
        return self.path_of_contact / self.base_pitch

    @property
    def overlap_ratio(self) -> float:
        """eps_beta = b sin(beta) / (pi m_n), b the common face width."""
        return min(self.g1.b, self.g2.b) * math.sin(self.g1.beta) / (math.pi * self.g1.m)

    @property
    def total_contact_ratio(self) -> float:
        """eps_gamma = eps_alpha + eps_beta."""
        return self.contact_ratio + self.overlap_ratio

    @property
    def ratio(self) -> float:
        """u = z2 / z1."""
        return self.g2.z / self.g1.z

    @property
    def r_w1(self) -> float:
        return self.g1.rb / math.cos(self.alpha_w)

    @property
    def r_w2(self) -> float:
        return self.g2.rb / math.cos(self.alpha_w)


def pair(g1: GearGeometry, g2: GearGeometry, center_distance: float | None = None, field: str = "meshes") -> PairGeometry:
    """Contact geometry of an external spur pair; raises ModelError naming ``field`` if it cannot mesh."""
    if abs(g1.m - g2.m) > 1e-9 * g1.m:
        raise ModelError(f"the gears have different modules ({g1.m * 1e3:g} and {g2.m * 1e3:g} mm): they cannot mesh", field=f"{field}.gears")
    if abs(g1.alpha - g2.alpha) > 1e-9:
        raise ModelError("the gears have different pressure angles: they cannot mesh", field=f"{field}.gears")
    if abs(g1.beta - g2.beta) > 1e-9:
        raise ModelError(f"the gears have different helix angles ({math.degrees(g1.beta):g} and "
                         f"{math.degrees(g2.beta):g} deg): they cannot mesh", field=f"{field}.gears")
    if g1.beta > 0 and g1.hand == g2.hand:
        raise ModelError(f"both gears are {g1.hand}-handed: an external helical pair needs opposite hands",
                         field=f"{field}.gears")
    at = g1.alpha_t
    a0 = g1.r + g2.r
    # zero-backlash working pressure angle (ISO 21771, eq. for inv alpha_wt)
    inv_w = inv(at) + 2 * math.tan(g1.alpha) * (g1.x + g2.x) / (g1.z + g2.z)
    alpha_w0 = inv_inverse(inv_w)
    a_zb = a0 * math.cos(at) / math.cos(alpha_w0)
    if center_distance is None:
        alpha_w, a_w = alpha_w0, a_zb
    else:
        if center_distance < a_zb * (1 - CENTRE_TOLERANCE):
            raise ModelError(f"{center_distance * 1e3:.6f} mm is {(a_zb - center_distance) * 1e6:.4g} um below the "
                             f"zero-backlash centre distance {a_zb * 1e3:.6f} mm (more than {CENTRE_TOLERANCE:g} of it): "
                             "the teeth would interfere", field=f"{field}.center_distance")
        a_w = center_distance
        alpha_w = math.acos(a0 * math.cos(at) / a_w)
    t12 = a_w * math.sin(alpha_w)
    for g, name in ((g1, "driving"), (g2, "driven")):
        if g.ra <= g.rb:
            raise ModelError(f"the {name} gear's tip radius {g.ra * 1e3:.4g} mm is not above its base radius", field=f"{field}.gears")
    rho_e = math.sqrt(g1.ra ** 2 - g1.rb ** 2)
    rho_a = t12 - math.sqrt(g2.ra ** 2 - g2.rb ** 2)
    if rho_a < 0:
        raise ModelError(f"the driven gear's tip reaches past the driving gear's base circle (tip interference, "
                         f"T1A = {rho_a * 1e3:.3g} mm)", field=f"{field}.gears")
    if rho_e > t12:
        raise ModelError("the driving gear's tip reaches past the driven gear's base circle (tip interference)", field=f"{field}.gears")
    geo = PairGeometry(g1=g1, g2=g2, alpha_w=alpha_w, a_w=a_w, a_zero_backlash=a_zb, tangent_length=t12,
                       rho_start=rho_a, rho_end=rho_e, rho_pitch=g1.rb * math.tan(alpha_w))
    if geo.contact_ratio < 1.0:
        raise ModelError(f"contact ratio {geo.contact_ratio:.3f} is below 1: the gears would lose contact "
                         f"between pairs (check tip diameters)", field=f"{field}")
    return geo
