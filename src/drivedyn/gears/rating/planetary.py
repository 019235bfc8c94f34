"""ISO 6336 rating of every mesh of a planetary stage: sun-planet (external) and ring-planet (internal).

What a stage adds to the rating of a pair (rating.py), by source (a helical stage: module and
pressure angle normal, the transverse ones below, the sun of one hand and planets and ring of the other):

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

The internal gear's tooth root is rated with its root section given (chord, fillet radius and diameter at
the 60 deg tangent; rating._root_internal says why it is not built), else not rated. Units as rating.py
(mm, N, rpm).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

from ...core.errors import ModelError
from ..mesh import iso6336
from ..mesh.geometry import CENTRE_TOLERANCE, inv, inv_inverse
from .mesh import Load, Material, Pair, rate

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
    ring_root_section: tuple | None = None  # the ring's (s_Fn, rho_F, d_sFn) at its 60 deg tangent; none: not rated
    beta: float = 0.0              # helix angle (sun one hand, planets and ring the other); module, alpha_n normal

    @property
    def transverse(self) -> tuple[float, float]:
        """(m_t, alpha_t): m_n / cos beta, atan(tan alpha_n / cos beta) (ISO 21771)."""
        c = math.cos(self.beta)
        return self.module / c, math.atan(math.tan(self.alpha_n) / c)

    def diameters(self) -> dict:
        zs, zp, zr = self.z
        m = self.module
        m_t, a_t = self.transverse
        d = [zz * m_t for zz in self.z]
        da = list(self.tip_diameter) if self.tip_diameter else [
            d[0] + 2 * m * (self.h_ap + self.x[0]), d[1] + 2 * m * (self.h_ap + self.x[1]),
            d[2] - 2 * m * (self.h_ap + self.x[2])]
        df = [d[0] - 2 * m * (self.h_fp[0] - self.x[0]), d[1] - 2 * m * (self.h_fp[1] - self.x[1]),
              d[2] + 2 * m * (self.h_fp[2] - self.x[2])]
        db = [di * math.cos(a_t) for di in d]
        return {"d": d, "da": da, "df": df, "db": db}


def working_geometry(st: StageGears, field: str = "planetary") -> dict:
    """Transverse working pressure angles and zero-backlash centre distances of both meshes (ISO 21771:
    inv alpha_wt = inv alpha_t + 2 tan alpha_n sum(x) / sum(z), a = sum(z) m_t cos alpha_t / (2 cos alpha_wt),
    the internal mesh with z_r negative)."""
    zs, zp, zr = st.z
    t = math.tan(st.alpha_n)
    m, a_n = st.transverse          # transverse module and pressure angle (the normal ones for spur gears)
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
    for name, base in (("sun-planet", (zs + zp) * m / 2 * c), ("ring-planet", (zr - zp) * m / 2 * c)):
        if not 0 < base < a:     # the base circles' distance past the centres': no working pressure angle
            raise ModelError(f"{a:.6f} mm is not more than the {name} base circles' distance {base:.6f} mm: the "
                             f"teeth ({zs}, {zp}, {zr}) cannot mesh at this centre distance", field=f"{field}.centre_distance")
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
    common = dict(mn=st.module, alpha_n=st.alpha_n, beta=st.beta, aw=wg["a_w"])
    sun = Pair(z1=zs, z2=zp, x1=st.x[0], x2=st.x[1], b=min(st.b[0], st.b[1]), da1=g["da"][0], da2=g["da"][1],
               h_fp=(st.h_fp[0], st.h_fp[1]), rho_fp=(st.rho_fp[0], st.rho_fp[1]), E=(st.E[0], st.E[1]),
               nu=(st.nu[0], st.nu[1]), b_each=(st.b[0], st.b[1]), **common)
    ring = Pair(z1=zp, z2=zr, x1=st.x[1], x2=st.x[2], b=min(st.b[1], st.b[2]), da1=g["da"][1], da2=g["da"][2],
                h_fp=(st.h_fp[1], st.h_fp[2]), rho_fp=(st.rho_fp[1], st.rho_fp[2]), E=(st.E[1], st.E[2]),
                nu=(st.nu[1], st.nu[2]), b_each=(st.b[1], st.b[2]), internal=True,
                root_section2=st.ring_root_section, **common)
    _check_tips(st, g, sun, ring, field)
    return sun, ring, wg


def _check_tips(st: StageGears, g: dict, sun: Pair, ring: Pair, field: str) -> None:
    """Tip circles that the rating's geometry can use, refused in one line otherwise (a tip inside
    its base circle, or a contact ratio no tooth gives, failed with a math domain error)."""
    from .mesh import geometry

    where = f"{field}.rating.tip_diameters" if st.tip_diameter else f"{field}.x"
    for k, gear in enumerate(("sun", "planet", "ring")):
        if not g["da"][k] > g["db"][k]:
            raise ModelError(f"the {gear}'s tip diameter {g['da'][k]:.6g} mm is not outside its base circle "
                             f"({g['db'][k]:.6g} mm): its teeth have no involute to mesh with", field=where)
    for name, p in (("sun-planet", sun), ("ring-planet", ring)):
        eps = geometry(p)["eps_alpha"]
        if not 1.0 <= eps < 4.0:
            raise ModelError(f"the tip diameters give the {name} mesh a transverse contact ratio of {eps:.4g} "
                             "(a spur mesh has 1 to 4: below 1 the contact breaks between teeth, ISO 6336-2's "
                             "Z_epsilon ends at 4)", field=where)


def stiffness(p: Pair, low_load: float | None = None, blank_factor: float = 1.0):
    """ISO 6336-1 c' and c_gamma_alpha of one mesh: q' of the pinion (fewer teeth) first, z_n = infinity
    for an internal gear (9.3.2)."""
    from .mesh import geometry

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
                                         low_load=low_load is not None, beta=p.beta)


def rate_stage(st: StageGears, mats: tuple, *, planets: int, torque_sun: float, speed_sun_rel: float,
               k_gamma: float = 1.0, kv: tuple | None = None, ka: float = 1.0, life_hours: float = 20000.0,
               nu40: float = 220.0, rz_flank: tuple = (6.0, 6.0, 6.0), rz_root: tuple = (10.0, 10.0, 10.0),
               k_hbeta: tuple | None = None, k_halpha: tuple | None = None, f_ma: float = 10.0,
               f_pb: float | tuple = 7.0, f_falpha: float | tuple = 7.0, tip_relief: float | None = None, blank_factor: float = 1.0,
               s_hmin: float = 1.0, s_fmin: float = 1.0, field: str = "planetary") -> dict:
    """Ratings of the sun-planet and ring-planet meshes of a stage (``mats`` = sun, planet, ring).

    ``torque_sun``: the sun's torque (N m, all planets); ``speed_sun_rel``: the sun's speed relative to
    the carrier (rpm). ``kv`` = (sun-planet, ring-planet) K_v, else ISO 6336-1 method B with the
    planetary reduced masses. ``k_hbeta``, ``k_halpha``: given per mesh, else computed.
    """
    zs, zp, zr = st.z
    sun, ring, wg = pairs(st, field)
    m_t = st.transverse[0]
    ft = 2000.0 * torque_sun / planets / (zs * m_t)                    # N per planet at the sun's reference circle
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
        # running-in of two different materials: the mean of the two (ISO 6336-1); deviations per mesh
        mb = iso6336.MethodB(z1=p.z1, c_single=iso.c_single, c_gamma=iso.c_gamma, m_red=m_red[j], eps_gamma=0.0,
                             load_per_width=w, f_pb=_per_mesh(f_pb, j), f_falpha=_per_mesh(f_falpha, j),
                             material=_run_in_class(mi, mi), sigma_hlim=mi.sigma_hlim, c_a=tip_relief,
                             pitch_radius=p.z1 * m_t / 2e3,
                             material2=None if mi == mj else _run_in_class(mj, mj),
                             sigma_hlim2=None if mi == mj else mj.sigma_hlim)
        from .mesh import geometry

        eps = geometry(p)["eps_gamma"]
        mb = iso6336.MethodB(**{**mb.__dict__, "eps_gamma": eps})
        kv_b, ratio_n, region = mb.kv(n1 / 60.0)
        k_v = kv[j] if kv is not None else kv_b
        idx = {"sun": 0, "planet": 1, "ring": 2}
        load = Load(torque1=ft * p.z1 * m_t / 2000.0, n1=n1, kv=k_v, ka=ka, life_hours=life_hours, nu40=nu40,
                    rz_flank=tuple(rz_flank[idx[g]] for g in gears), rz_root=tuple(rz_root[idx[g]] for g in gears),
                    f_ma=f_ma, f_pb=_per_mesh(f_pb, j), c_gamma_alpha=iso.c_gamma,
                    k_hbeta=None if k_hbeta is None else k_hbeta[j], k_halpha=None if k_halpha is None else k_halpha[j],
                    s_hmin=s_hmin, s_fmin=s_fmin, k_gamma=k_gamma,
                    y_m=tuple(0.7 if g == "planet" else 1.0 for g in gears), cycles=tuple(cyc[g] for g in gears))
        try:
            r = rate(p, (mi, mj), load)
        except ValueError as exc:      # the ring's given root section does not fit its teeth
            raise ModelError(str(exc), field=f"{field}.rating.ring_root_section") from None
        r.geometry.update({"pinion": gears[0], "wheel": gears[1]})
        r.factors.update({"c_single": iso.c_single, "c_gamma_alpha": iso.c_gamma, "m_red": m_red[j],
                          "n_E1": mb.resonance_speed * 60.0, "N": ratio_n, "K_v_method_b": kv_b, "region": region})
        out[name] = r
    return out


def _per_mesh(v, j: int) -> float:
    """A value given for both meshes, or one per mesh (sun-planet, ring-planet)."""
    return float(v[j]) if isinstance(v, (tuple, list)) else float(v)


def _run_in_class(a: Material, b: Material) -> str:
    order = ("GG", "St", "V", "NT", "Eh")
    cls = min((a.cls, b.cls), key=order.index)
    return "St" if cls == "V" else cls


def _material(name, iso, hardness=None) -> Material:
    from .mesh import STEELS

    if name is None:
        name = iso.steel
    if name is not None:
        s = STEELS[name]
        return Material(s["class"], s["sigma_hlim"], s["sigma_flim"], s["yield_strength"], hardness_hb=hardness)
    return Material(iso.material, iso.sigma_hlim / 1e6, iso.sigma_flim / 1e6,
                    None if iso.yield_strength is None else iso.yield_strength / 1e6, hardness_hb=hardness)


def _si(v):
    return None if v is None or (isinstance(v, float) and math.isnan(v)) else float(v)


def rate_spec(spec, iso, k_gamma: float, torque_sun: float, speeds: dict, field: str = "planetary",
              kv_run: tuple | None = None, integrated: bool = False) -> dict:
    """The summary entry (SI) of the rating of a model's planetary stage with the model's [iso] data
    ``iso``: K_gamma given or ``k_gamma``
    (the computed load sharing), the sun's torque ``torque_sun`` (N m), member ``speeds`` (rad/s); K_v
    given, else ``kv_run`` (sun-planet, ring-planet: the time integration's), else ISO method B.
    ``integrated``: the stage was integrated in time if it has [dynamics] (a run, not a check)."""
    r = spec.rating
    st = gears_of_spec(spec)
    mats = [_material(s, iso, r.ring_hardness if k == 2 else None) for k, s in enumerate(r.steels or (None,) * 3)]
    for k in range(3):
        if r.sigma_hlim is not None:
            mats[k] = replace(mats[k], sigma_hlim=r.sigma_hlim[k] / 1e6)
        if r.sigma_flim is not None:
            mats[k] = replace(mats[k], sigma_flim=r.sigma_flim[k] / 1e6)
        gear = ("sun", "planet", "ring")[k]
        if gear in r.yield_strength:
            mats[k] = replace(mats[k], yield_strength=r.yield_strength[gear] / 1e6)
    mats = tuple(mats)
    rpm = 30.0 / math.pi
    rz_f = tuple(x * 1e6 for x in r.flank_roughness) if r.flank_roughness else (iso.flank_roughness * 1e6,) * 3
    rz_r = tuple(x * 1e6 for x in r.root_roughness) if r.root_roughness else (iso.root_roughness * 1e6,) * 3
    kg = r.load_sharing_factor if r.load_sharing_factor is not None else max(k_gamma, 1.0)
    both = lambda v: None if v is None else (v, v)      # noqa: E731
    out = rate_stage(st, mats, planets=spec.planets, torque_sun=abs(torque_sun),
                     speed_sun_rel=abs(speeds["sun"] - speeds["carrier"]) * rpm, k_gamma=kg,
                     kv=r.dynamic_factors or (None if kv_run is None else tuple(max(k, 1.0) for k in kv_run)),
                     ka=iso.application_factor, life_hours=iso.life / 3600.0, nu40=iso.lubricant_viscosity * 1e6,
                     rz_flank=rz_f, rz_root=rz_r,
                     k_hbeta=tuple(r.face_load_factors) if r.face_load_factors else both(iso.face_load_factor),
                     k_halpha=both(iso.transverse_load_factor), f_ma=iso.mesh_misalignment * 1e6,
                     f_pb=iso.pitch_deviation * 1e6, f_falpha=iso.profile_deviation * 1e6,
                     tip_relief=None if iso.tip_relief is None else iso.tip_relief * 1e6, blank_factor=iso.blank_factor,
                     s_hmin=iso.min_safety_pitting, s_fmin=iso.min_safety_bending, field=field)
    dyn = spec.dynamics
    if r.dynamic_factors:
        source = "given"
        note = ("not from a time integration: given (rating.dynamic_factors)"
                + ("; the stage's time integration gives its own in dynamics.kv" if dyn is not None and integrated else ""))
    elif kv_run is not None:
        source = "time integration"
        note = ("from the time integration (the stage's model with time-varying mesh stiffness: the largest mesh "
                "force over the largest quasi-static one, the largest over the planets; dynamics.kv); ISO 6336-1 "
                "method B beside it (K_v_method_b)")
    else:
        source = "ISO 6336-1 method B"
        why = ("dynamics.rating_kv = \"method-b\"" if dyn is not None and integrated else
               "not integrated by a check: `drivedyn run` integrates it" if dyn is not None else
               "the planetary stage is not integrated in time (give [dynamics])")
        note = f"not from a time integration ({why}): ISO 6336-1 method B with the planetary reduced masses"
    summary = {"K_gamma": kg, "K_gamma_source": "given" if r.load_sharing_factor is not None else "load sharing",
               "load_cycles": {k: float(v) for k, v in out["cycles"].items()}, "meshes": {},
               # said where K_v is read: given, from the stage's time integration, or method B
               "K_v_note": note}
    for name in ("sun-planet", "ring-planet"):
        rt = out[name]
        f = rt.factors
        e = {"pinion": rt.geometry["pinion"], "wheel": rt.geometry["wheel"],
             "working_pressure_angle": rt.geometry["alpha_wt"], "contact_ratio": rt.geometry["eps_alpha"],
             "overlap_ratio": rt.geometry["eps_beta"],
             "K_v": f["K_v"], "K_v_method_b": f["K_v_method_b"], "K_v_source": source,
             "K_v_run": None if kv_run is None else float(kv_run[0 if name == "sun-planet" else 1]),
             "reduced_mass": f["m_red"] * 1e3, "resonance_speed_rpm": f["n_E1"],
             "iso_c_single": f["c_single"] * 1e9, "iso_c_gamma": f["c_gamma_alpha"] * 1e9}
        for key in ("K_A", "K_gamma", "K_Hbeta", "K_Fbeta", "K_Halpha", "K_Falpha", "Z_H", "Z_eps", "Z_beta", "Y_beta",
                    "Z_L", "Z_v", "Z_R"):
            e[key] = f[key]
        worst = []
        for who, g in (("pinion", rt.pinion), ("wheel", rt.wheel)):
            gear = rt.geometry[who]
            e[gear] = {"sigma_H": g["sigma_H"] * 1e6, "sigma_HP": g["sigma_HP"] * 1e6, "S_H": g["S_H"],
                       "sigma_F": _si(g["sigma_F"] * 1e6), "sigma_FP": _si(g["sigma_FP"] * 1e6), "S_F": _si(g["S_F"]),
                       "Y_F": _si(g["Y_F"]), "Y_S": _si(g["Y_S"]), "Y_M": g["Y_M"], "Z_NT": g["Z_NT"],
                       "Y_NT": _si(g["Y_NT"]), "Z_W": g["Z_W"], "Z_B_or_Z_D": g["Z_B_or_Z_D"], "load_cycles": g["N_L"],
                       "material_class": g["material_class"]}
            if g["S_H"] < iso.min_safety_pitting:
                worst.append(f"{gear} pitting S_H {g['S_H']:.3f} < {iso.min_safety_pitting:g}")
            if not math.isnan(g["S_F"]) and g["S_F"] < iso.min_safety_bending:
                worst.append(f"{gear} root S_F {g['S_F']:.3f} < {iso.min_safety_bending:g}")
        e["verdict"] = ("fails: " + "; ".join(worst)) if worst else "passes (S_H and S_F at or above the minimums)"
        e["notes"] = list(dict.fromkeys(rt.notes))
        summary["meshes"][name] = e
    summary["S_H_min_required"], summary["S_F_min_required"] = iso.min_safety_pitting, iso.min_safety_bending
    return summary


def gears_of_spec(spec) -> StageGears:
    """StageGears (mm) of a model's ``planetary`` section with its ``rating`` data."""
    r = spec.rating
    zr = spec.ring_teeth or spec.sun_teeth + 2 * spec.planet_teeth
    return StageGears(z=(spec.sun_teeth, spec.planet_teeth, zr), module=spec.module * 1e3, alpha_n=spec.pressure_angle,
                      beta=spec.helix_angle,
                      x=tuple(spec.profile_shifts), b=(r.face_width * 1e3,) * 3 if r else (1.0, 1.0, 1.0),
                      centre_distance=None if spec.centre_distance is None else spec.centre_distance * 1e3,
                      tip_diameter=None if r is None or r.tip_diameters is None else tuple(d * 1e3 for d in r.tip_diameters),
                      rho_fp=tuple(r.root_radius) if r else (0.25, 0.25, 0.25),
                      bore=tuple(d * 1e3 for d in r.bore_diameters) if r else (0.0, 0.0, 0.0),
                      ring_root_section=None if r is None or r.ring_root_section is None
                      else tuple(v * 1e3 for v in r.ring_root_section))
