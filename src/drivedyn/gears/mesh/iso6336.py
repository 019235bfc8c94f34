"""ISO 6336-1:2006 mesh stiffness (clause 9, method B) and dynamic factor K_v (clause 6.3, method B).

Units follow the standard inside the formulas (N, mm, um, N/(mm um)); the wrappers return SI.
The K_v equation numbers are those of ISO 6336-1:2006 as cited by an independent open implementation
(gfsReboucas/Drivetrain ISO_6336.m); for the stiffness only clauses are cited (equation numbers
not verified against the text); the formulas were re-derived here from the standard's text
as gathered in docs (gears-formulas.md), with the known mistakes of open codes avoided: C_R divides
by m_n once, C_B is computed (not fixed at 0.975), the region limit N_S uses K_A F_t / b < 100,
C_ay uses 1/18, y_alpha = 160 f_pb / sigma_Hlim, and the C7 term of q' multiplies x2.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

# ISO 6336-1:2006, 9.3.2, Table 9 (coefficients of q' for spur/helical gears with basic rack
# ISO 53, N/(mm um) per mm of face width)
C_Q = (0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182)
E_STEEL = 206000.0   # N/mm^2, ISO 6336-1:2006, 9.3.1 (reference modulus of steel)


@dataclass(frozen=True)
class IsoStiffness:
    """c' and c_gamma_alpha of one mesh, N/(mm um) per mm face width, with their factors."""

    q_prime: float
    c_th: float
    c_m: float
    c_r: float
    c_b: float
    e_factor: float
    low_load_factor: float
    c_single: float          # c'
    c_gamma: float           # c_gamma_alpha
    load_per_width: float    # K_A F_t / b, N/mm
    valid: bool              # inside the ISO range -0.5 <= x1 + x2 <= 2

    def si(self, b: float) -> tuple[float, float]:
        """(c' b, c_gamma b) in N/m for a face width ``b`` in m."""
        return self.c_single * b * 1e9, self.c_gamma * b * 1e9


def q_prime(z1: int, z2: int, x1: float, x2: float) -> float:
    """Minimum flexibility q' of a tooth pair, ISO 6336-1:2006 9.3.2 (spur: z_n = z)."""
    c = C_Q
    return (c[0] + c[1] / z1 + c[2] / z2 + c[3] * x1 + c[4] * x1 / z1 + c[5] * x2 + c[6] * x2 / z2
            + c[7] * x1 ** 2 + c[8] * x2 ** 2)


def basic_rack_factor(h_fp: float, alpha_pn_deg: float) -> float:
    """C_B = [1 + 0.5 (1.2 - h_fP/m_n)] [1 - 0.02 (20 deg - alpha_Pn)], ISO 6336-1:2006 9.3.5."""
    return (1 + 0.5 * (1.2 - h_fp)) * (1 - 0.02 * (20.0 - alpha_pn_deg))


def single_pair_stiffness(z1, z2, x1, x2, eps_alpha, load_per_width, *, dedendum=(1.25, 1.25),
                          alpha_deg=20.0, youngs=(206e9, 206e9), blank_factor=1.0, low_load=True,
                          beta=0.0) -> IsoStiffness:
    """ISO 6336-1:2006, 9.3 method B: c' = c'_th C_M C_R C_B cos(beta).

    q' takes the virtual tooth numbers z_n = z / (cos^2 beta_b cos beta) (9.3.2); ``beta`` is the
    helix angle in rad (0: spur). ``load_per_width`` is K_A F_t / b in N/mm; below 100 N/mm c' is
    multiplied by (K_A F_t / b / 100)^0.25 (9.3.1) when ``low_load``.
    """
    if beta > 0:
        at = math.atan(math.tan(math.radians(alpha_deg)) / math.cos(beta))
        bb = math.atan(math.tan(beta) * math.cos(at))
        zn = [z / (math.cos(bb) ** 2 * math.cos(beta)) for z in (z1, z2)]
    else:
        zn = [z1, z2]
    q = q_prime(zn[0], zn[1], x1, x2)
    c_th = 1.0 / q                                                   # 9.3.2: c'_th = 1/q'
    c_m = 0.8                                                        # 9.3.3: C_M, theoretical -> measured
    c_r = blank_factor                                               # 9.3.4: C_R = 1 for solid blanks
    # 9.3.5: C_B of a pair with different basic racks is the mean of the two gears' factors
    c_b = 0.5 * (basic_rack_factor(dedendum[0], alpha_deg) + basic_rack_factor(dedendum[1], alpha_deg))
    e1, e2 = (y / 1e6 for y in youngs)                              # N/mm^2
    e_factor = (2 * e1 * e2 / (e1 + e2)) / E_STEEL                  # 9.3.1 (eq. 88 as cited by a python-gearbox fork): other materials
    f_ll = (load_per_width / 100.0) ** 0.25 if (low_load and load_per_width < 100.0) else 1.0
    c1 = c_th * c_m * c_r * c_b * e_factor * f_ll * math.cos(beta)
    # 9.4: c_gamma_alpha = c' (0.75 eps_alpha + 0.25), 10 % lower for eps_alpha < 1.2
    cg = c1 * (0.75 * eps_alpha + 0.25) * (0.9 if eps_alpha < 1.2 else 1.0)
    return IsoStiffness(q_prime=q, c_th=c_th, c_m=c_m, c_r=c_r, c_b=c_b, e_factor=e_factor, low_load_factor=f_ll,
                        c_single=c1, c_gamma=cg, load_per_width=load_per_width, valid=-0.5 <= x1 + x2 <= 2.0)


# ISO 6336-1:2006, 6.3.2, Table 8: C_v1..C_v6 for 1 < eps_gamma <= 2
def _cv(eps: float) -> tuple:
    if eps <= 2.0:
        cv = (0.32, 0.34, 0.23, 0.90, 0.47, 0.47)
    else:
        cv = (0.32, 0.57 / (eps - 0.3), 0.096 / (eps - 1.56), (0.57 - 0.05 * eps) / (eps - 1.44), 0.47,
              0.12 / (eps - 1.74))
    if eps <= 1.5:
        cv7 = 0.75
    elif eps <= 2.5:
        cv7 = 0.125 * math.sin(math.pi * (eps - 2.0)) + 0.875
    else:
        cv7 = 1.0
    return (*cv, cv7)


def running_in(f_um: float, material: str, sigma_hlim: float, v: float) -> float:
    """Running-in allowance y (um) of a deviation f (um), ISO 6336-1:2006 / ISO 6336-1 annex (y_alpha, 9.x)."""
    if material == "St":
        y = 160.0 * f_um / sigma_hlim
        if 5 < v <= 10:
            y = min(y, 12800.0 / sigma_hlim)
        elif v > 10:
            y = min(y, 6400.0 / sigma_hlim)
    elif material == "GG":
        y = 0.275 * f_um
        if 5 < v <= 10:
            y = min(y, 22.0)
        elif v > 10:
            y = min(y, 11.0)
    else:   # case hardened / nitrided
        y = min(0.075 * f_um, 3.0)
    return y


@dataclass(frozen=True)
class MethodB:
    """ISO 6336-1 method B inputs of one mesh (SI except where the standard's units are stated)."""

    z1: int
    c_single: float          # c', N/(mm um)
    c_gamma: float           # c_gamma_alpha, N/(mm um)
    m_red: float             # reduced mass per face width, kg/mm
    eps_gamma: float
    load_per_width: float    # K_A F_t / b, N/mm
    f_pb: float              # um
    f_falpha: float          # um
    material: str
    sigma_hlim: float        # N/mm^2
    c_a: float | None        # tip relief, um (None: running-in C_ay)
    pitch_radius: float      # m (for the pitch-line speed)
    material2: str | None = None      # the other gear's, when the two differ: running-in values are
    sigma_hlim2: float | None = None  # the mean of the two gears' (ISO 6336-1:2006, 8.3.x and 6.3.x)

    @property
    def resonance_speed(self) -> float:
        """n_E1 in rev/s: ISO 6336-1:2006 eq. (6), n_E1 = 30000/(pi z1) sqrt(c_gamma_alpha/m_red) min^-1."""
        return 30000.0 / (math.pi * self.z1) * math.sqrt(self.c_gamma / self.m_red) / 60.0

    def kv(self, n1: float) -> tuple[float, float, str]:
        """(K_v, N, region) at pinion speed ``n1`` (rev/s)."""
        n = n1 / self.resonance_speed                                  # eq. (9)
        w = self.load_per_width
        ns = 0.5 + 0.35 * math.sqrt(w / 100.0) if w < 100.0 else 0.85  # eqs. (11), (12)
        v = 2 * math.pi * self.pitch_radius * n1
        gears = [(self.material, self.sigma_hlim)]
        if self.material2 is not None:
            gears.append((self.material2, self.sigma_hlim2))
        y_p = sum(running_in(self.f_pb, m, sh, v) for m, sh in gears) / len(gears)
        y_f = sum(running_in(self.f_falpha, m, sh, v) for m, sh in gears) / len(gears)
        # running-in tip relief, um
        c_ay = sum((1.0 / 18.0) * (sh / 97.0 - 18.45) ** 2 + 1.5 for _, sh in gears) / len(gears)
        c_a = c_ay if self.c_a is None else self.c_a
        bp = self.c_single * max(self.f_pb - y_p, 0.0) / w          # eq. (15)
        bf = self.c_single * max(self.f_falpha - y_f, 0.0) / w      # eq. (16)
        bk = abs(1.0 - self.c_single * c_a / w)                     # eq. (17)
        cv1, cv2, cv3, cv4, cv5, cv6, cv7 = _cv(self.eps_gamma)

        def main(nn):
            return cv1 * bp + cv2 * bf + cv4 * bk + 1.0               # eq. (20)

        def super_(nn):
            return cv5 * bp + cv6 * bf + cv7                          # eq. (21)

        if n <= ns:
            return n * (cv1 * bp + cv2 * bf + cv3 * bk) + 1.0, n, "subcritical"   # eqs. (13), (14)
        if n <= 1.15:
            return main(n), n, "main resonance"
        if n >= 1.5:
            return super_(n), n, "supercritical"
        k15, k115 = super_(1.5), main(1.15)                            # eq. (22)
        return k15 + (k115 - k15) * (1.5 - n) / 0.35, n, "intermediate"
