"""ISO 6336 rating of every mesh of a planetary stage: sun-planet (external) and ring-planet (internal).

What a stage adds to the rating of a pair (rating.py), by source:

- geometry with profile shifts (ISO 21771): sun-planet inv alpha_w = inv alpha_t + 2 tan alpha_n (x_s + x_p)
  / (z_s + z_p); ring-planet (internal, x_r as ISO 21771 writes an internal gear's shift, d_a = d - 2 m_n
  (h_aP + x_r)) inv alpha_w = inv alpha_t + 2 tan alpha_n (x_p + x_r) / (z_p - z_r), a = (z_r - z_p) m_t
  cos alpha_t / (2 cos alpha_w); the zero-backlash centre distances of both meshes must meet the
  given one within geometry.CENTRE_TOLERANCE (an internal mesh interferes above its own);
- mesh stiffness (ISO 6336-1:2006 9.3): q' with z_n = infinity for the internal gear;
- load: F_t at the sun per planet, times K_gamma (ISO 6336-1: the mesh load factor of the planets'
  load sharing) in every K factor product;
- speeds and load cycles relative to the carrier: the sun meets N planets a turn (N_L = 60 h N n_s,rel),
  the ring N (60 h N n_r,rel), a planet meshes twice a turn, once on each flank: its contact sees
  60 h n_p,rel cycles per flank and its teeth are bent both ways (mean stress factor Y_M = 0.7,
  ISO 6336-3:2019 / ISO 6336-3:2006 0.7 sigma_Flim for idler gears);
- ISO 6336-1:2006 method B K_v with the planetary reduced masses (6.5.9): m* = pi/8 (d_m / d_b)^2 d_m^2
  (1 - q^4) rho per unit face width (d_m = (d_a + d_f) / 2, q = d_i / d_m), sun-planet
  m_red = m_s* m_p* / (m_s* + N m_p*), ring-planet m_red = m_p* (the ring held);
- ISO 6336-2 for an internal pair: u < 0 in sigma_H0, rho_red = rho_1 rho_2 / (rho_2 - rho_1), Z_D = 1.

The internal gear's tooth root is not rated (rating.py says why). Units as rating.py (mm, N, rpm).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import ModelError
from . import iso6336
from .geometry import CENTRE_TOLERANCE, inv, inv_inverse
from .rating import Load, Material, Pair, rate

STEEL_DENSITY = 7.83e-6            # kg/mm^3, ISO 6336-1:2006 6.5.9 (rho of steel)


@dataclass(frozen=True)
class StageGears:
    """Tooth data of sun, planet and ring (mm, rad; ring teeth and diameters positive)."""

    z: tuple                       # (sun, planet, ring)
    module: float
    alpha_n: float
    x: tuple                       # profile shifts; the ring's as ISO 21771 writes an internal gear's
    b: tuple                       # face widths
    centre_distance: float | None = None   # default: the sun-planet zero-backlash one
    tip_diameter: tuple | None = None      # default ISO 21771 with h_aP; the ring's is its inner one
    h_fp: tuple = (1.25, 1.25, 1.25)
    rho_fp: tuple = (0.25, 0.25, 0.25)
    h_ap: float = 1.0
    E: tuple = (206000.0, 206000.0, 206000.0)
    nu: tuple = (0.3, 0.3, 0.3)
    bore: tuple = (0.0, 0.0, 0.0)  # inner diameters d_i (for the reduced mass); ring: its outer one

    def diameters(self) -> dict:
        zs, zp, zr = self.z
        m = self.module
        d = [zz * m for zz in self.z]
        da = list(self.tip_diameter) if self.tip_diameter else [
            d[0] + 2 * m * (self.h_ap + self.x[0]), d[1] + 2 * m * (self.h_ap + self.x[1]),
            d[2] - 2 * m * (self.h_ap + self.x[2])]
        df = [d[0] - 2 * m * (self.h_fp[0] - self.x[0]), d[1] - 2 * m * (self.h_fp[1] - self.x[1]),
              d[2] + 2 * m * (self.h_fp[2] - self.x[2])]
        db = [di * math.cos(self.alpha_n) for di in d]
        return {"d": d, "da": da, "df": df, "db": db}


def working_geometry(st: StageGears, field: str = "planetary") -> dict:
    """Working pressure angles and zero-backlash centre distances of both meshes (spur)."""
    zs, zp, zr = st.z
    a_n = st.alpha_n
    t = math.tan(a_n)
    m = st.module
    w_s = inv_inverse(inv(a_n) + 2 * t * (st.x[0] + st.x[1]) / (zs + zp))
    a_s = (zs + zp) * m / 2 * math.cos(a_n) / math.cos(w_s)
    w_r0 = inv_inverse(inv(a_n) + 2 * t * (st.x[1] + st.x[2]) / (zp - zr))
    a_r = (zr - zp) * m / 2 * math.cos(a_n) / math.cos(w_r0)
    a = st.centre_distance if st.centre_distance is not None else a_s
    if a < a_s * (1 - CENTRE_TOLERANCE):
        raise ModelError(f"{a:.6f} mm is {(a_s - a) * 1e3:.4g} um below the sun-planet zero-backlash centre distance "
                         f"{a_s:.6f} mm (more than {CENTRE_TOLERANCE:g} of it): sun and planets would interfere",
                         field=f"{field}.centre_distance")
    if a > a_r * (1 + CENTRE_TOLERANCE):
        raise ModelError(f"{a:.6f} mm is {(a - a_r) * 1e3:.4g} um above the ring-planet zero-backlash centre distance "
                         f"{a_r:.6f} mm (more than {CENTRE_TOLERANCE:g} of it): planets and ring would interfere "
                         "(check the profile shifts)", field=f"{field}.centre_distance")
    c = math.cos(a_n)
    return {"a_w": a, "alpha_w_sun": math.acos((zs + zp) * m / 2 * c / a), "alpha_w_ring": math.acos((zr - zp) * m / 2 * c / a),
            "a_zero_backlash_sun": a_s, "a_zero_backlash_ring": a_r}


def mass_per_width(d_a: float, d_f: float, d_b: float, d_i: float, rho: float = STEEL_DENSITY) -> float:
    """m* = pi/8 (d_m / d_b)^2 d_m^2 (1 - q^4) rho, kg/mm (ISO 6336-1:2006 6.5.9, eq. 30)."""
    dm = 0.5 * (d_a + d_f)
    q = d_i / dm
    return math.pi / 8 * (dm / d_b) ** 2 * dm ** 2 * (1 - q ** 4) * rho


def reduced_masses(st: StageGears, planets: int) -> tuple[float, float]:
    """ISO 6336-1:2006 6.5.9 reduced masses (kg/mm) of the sun-planet and ring-planet meshes."""
    g = st.diameters()
    ms = mass_per_width(g["da"][0], g["df"][0], g["db"][0], st.bore[0])
    mp = mass_per_width(g["da"][1], g["df"][1], g["db"][1], st.bore[1])
    return ms * mp / (ms + planets * mp), mp


def pairs(st: StageGears, field: str = "planetary") -> tuple[Pair, Pair, dict]:
    """The rating pairs: sun (1) with planet (2), and planet (1) with ring (2, internal)."""
    wg = working_geometry(st, field)
    g = st.diameters()
    zs, zp, zr = st.z
    common = dict(mn=st.module, alpha_n=st.alpha_n, beta=0.0, aw=wg["a_w"])
    sun = Pair(z1=zs, z2=zp, x1=st.x[0], x2=st.x[1], b=min(st.b[0], st.b[1]), da1=g["da"][0], da2=g["da"][1],
               h_fp=(st.h_fp[0], st.h_fp[1]), rho_fp=(st.rho_fp[0], st.rho_fp[1]), E=(st.E[0], st.E[1]),
               nu=(st.nu[0], st.nu[1]), b_each=(st.b[0], st.b[1]), **common)
    ring = Pair(z1=zp, z2=zr, x1=st.x[1], x2=st.x[2], b=min(st.b[1], st.b[2]), da1=g["da"][1], da2=g["da"][2],
                h_fp=(st.h_fp[1], st.h_fp[2]), rho_fp=(st.rho_fp[1], st.rho_fp[2]), E=(st.E[1], st.E[2]),
                nu=(st.nu[1], st.nu[2]), b_each=(st.b[1], st.b[2]), internal=True, **common)
    return sun, ring, wg


def stiffness(p: Pair, low_load: float | None = None, blank_factor: float = 1.0):
    """ISO 6336-1 c' and c_gamma_alpha of one mesh: q' of the pinion (fewer teeth) first, z_n = infinity
    for an internal gear (9.3.2)."""
    from .rating import geometry

    eps = geometry(p)["eps_alpha"]
    if p.internal:
        zz, xx = (p.z1, math.inf), (p.x1, p.x2)
    elif p.z1 <= p.z2:
        zz, xx = (p.z1, p.z2), (p.x1, p.x2)
    else:
        zz, xx = (p.z2, p.z1), (p.x2, p.x1)
    return iso6336.single_pair_stiffness(zz[0], zz[1], xx[0], xx[1], eps, low_load if low_load is not None else 1e9,
                                         dedendum=p.h_fp, alpha_deg=math.degrees(p.alpha_n),
                                         youngs=(p.E[0] * 1e6, p.E[1] * 1e6), blank_factor=blank_factor,
                                         low_load=low_load is not None)


def rate_stage(st: StageGears, mats: tuple, *, planets: int, torque_sun: float, speed_sun_rel: float,
               k_gamma: float = 1.0, kv: tuple | None = None, ka: float = 1.0, life_hours: float = 20000.0,
               nu40: float = 220.0, rz_flank: tuple = (6.0, 6.0, 6.0), rz_root: tuple = (10.0, 10.0, 10.0),
               k_hbeta: tuple | None = None, k_halpha: tuple | None = None, f_ma: float = 10.0, f_pb: float = 7.0,
               f_falpha: float = 7.0, tip_relief: float | None = None, blank_factor: float = 1.0,
               s_hmin: float = 1.0, s_fmin: float = 1.0, field: str = "planetary") -> dict:
    """Ratings of the sun-planet and ring-planet meshes of a stage (``mats`` = sun, planet, ring).

    ``torque_sun``: the sun's torque (N m, all planets); ``speed_sun_rel``: the sun's speed relative to
    the carrier (rpm). ``kv`` = (sun-planet, ring-planet) K_v, else ISO 6336-1 method B with the
    planetary reduced masses. ``k_hbeta``, ``k_halpha``: given per mesh, else computed.
    """
    zs, zp, zr = st.z
    sun, ring, wg = pairs(st, field)
    ft = 2000.0 * torque_sun / planets / (zs * st.module)              # N per planet at the sun's reference circle
    n_p = speed_sun_rel * zs / zp
    n_r = speed_sun_rel * zs / zr
    cyc = {"sun": 60 * life_hours * planets * speed_sun_rel, "planet": 60 * life_hours * n_p,
           "ring": 60 * life_hours * planets * n_r}
    m_red = reduced_masses(st, planets)
    out = {"geometry": wg, "cycles": cyc, "reduced_mass": {"sun-planet": m_red[0], "ring-planet": m_red[1]},
           "F_t": ft}
    for j, (name, p, (mi, mj), n1, gears) in enumerate((
            ("sun-planet", sun, (mats[0], mats[1]), speed_sun_rel, ("sun", "planet")),
            ("ring-planet", ring, (mats[1], mats[2]), n_p, ("planet", "ring")))):
        w = ka * k_gamma * ft / p.b
        iso = stiffness(p, w, blank_factor)
        mb = iso6336.MethodB(z1=p.z1, c_single=iso.c_single, c_gamma=iso.c_gamma, m_red=m_red[j], eps_gamma=0.0,
                             load_per_width=w, f_pb=f_pb, f_falpha=f_falpha, material=_run_in_class(mi, mj),
                             sigma_hlim=min(mi.sigma_hlim, mj.sigma_hlim), c_a=tip_relief,
                             pitch_radius=p.z1 * p.mn / 2e3)
        from .rating import geometry

        eps = geometry(p)["eps_gamma"]
        mb = iso6336.MethodB(**{**mb.__dict__, "eps_gamma": eps})
        kv_b, ratio_n, region = mb.kv(n1 / 60.0)
        k_v = kv[j] if kv is not None else kv_b
        idx = {"sun": 0, "planet": 1, "ring": 2}
        load = Load(torque1=ft * p.z1 * p.mn / 2000.0, n1=n1, kv=k_v, ka=ka, life_hours=life_hours, nu40=nu40,
                    rz_flank=tuple(rz_flank[idx[g]] for g in gears), rz_root=tuple(rz_root[idx[g]] for g in gears),
                    f_ma=f_ma, f_pb=f_pb, c_gamma_alpha=iso.c_gamma,
                    k_hbeta=None if k_hbeta is None else k_hbeta[j], k_halpha=None if k_halpha is None else k_halpha[j],
                    s_hmin=s_hmin, s_fmin=s_fmin, k_gamma=k_gamma,
                    y_m=tuple(0.7 if g == "planet" else 1.0 for g in gears), cycles=tuple(cyc[g] for g in gears))
        r = rate(p, (mi, mj), load)
        r.geometry.update({"pinion": gears[0], "wheel": gears[1]})
        r.factors.update({"c_single": iso.c_single, "c_gamma_alpha": iso.c_gamma, "m_red": m_red[j],
                          "n_E1": mb.resonance_speed * 60.0, "N": ratio_n, "K_v_method_b": kv_b, "region": region})
        out[name] = r
    return out


def _run_in_class(a: Material, b: Material) -> str:
    order = ("GG", "St", "V", "NT", "Eh")
    cls = min((a.cls, b.cls), key=order.index)
    return "St" if cls == "V" else cls
