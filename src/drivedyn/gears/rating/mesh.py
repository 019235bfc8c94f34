"""ISO 6336-2 (pitting) and ISO 6336-3 (tooth root) load capacity, method B, of one external mesh.

Units follow the standard inside (N, mm, N/mm^2, rpm, um); ``rate`` takes and returns plain floats in
those units. Equation sources, by clause of ISO 6336-1/-2/-3:2006:

- geometry (transverse and virtual quantities): ISO 21771:2007;
- K_Hbeta method C (ISO 6336-1, 7.6: f_sh with the pinion offset s = 0, F_betax = 1.33 f_sh + f_ma,
  running-in y_beta = 0.15 F_betax for case-hardened and nitrided gears; other materials get no
  running-in credit here), K_Fbeta = K_Hbeta^N_F (7.6, eq. for N_F), K_Halpha = K_Falpha (8.3,
  eqs. 73-76, with their limits);
- contact (ISO 6336-2): Z_H, Z_E, Z_eps, Z_beta = 1/sqrt(cos beta), Z_B / Z_D from M_1 / M_2,
  sigma_H0, sigma_H, Z_NT (life factor lines of table 2 with 0.85 at 1e10 cycles), Z_L, Z_v
  (C_ZL from sigma_Hlim, C_Zv = C_ZL + 0.02), Z_R with R_z10 = R_z (10/rho_red)^(1/3), Z_W = Z_X = 1;
- root (ISO 6336-3 method B, load at the outer point of single pair contact, 30 deg tangent):
  E, G, H, theta (iterated), s_Fn, rho_F, d_en, alpha_en, gamma_e, alpha_Fen, h_Fe, Y_F, Y_S,
  Y_beta = 1 - eps_beta beta/120 deg (eps_beta <= 1, beta <= 30 deg), Y_B = 1 (solid rim),
  Y_DT = 1 (eps_alpha_n <= 2.05), Y_ST = 2, Y_NT (table 2), Y_deltarelT (slip-layer thickness
  rho'), Y_RrelT (root roughness), Y_X (module).

The contact chain is checked digit by digit against ISO/TR 6336-30:2017 example 1
(tests/gears/test_rating.py); the root geometry (s_Fn, rho_F at the 30 deg tangent) against the
fillet that the basic rack generates (to 2e-5 m_n); and both chains, external and internal contact
and the external gears' root factors, against a KISSsoft report of a planetary stage to its printed
digits (tests/gears/test_planetary_rating.py). An internal gear's tooth root is rated when its root
section (s_Fn, rho_F, d_sFn) is given (_root_internal says why it is not built); else not rated.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field, replace

from ..mesh.geometry import inv

#: Materials with their allowable stress numbers and the published worked example they come from.
#: class: ISO 6336 material class (Eh case-hardened, V through-hardened, NT nitrided, St, GG).
STEELS = {
    "case-carburized": {
        "class": "Eh", "sigma_hlim": 1500.0, "sigma_flim": 430.0, "yield_strength": None,
        "source": "case-hardened steel of DIN 3990-11 example 1 (sigma_Hlim 1500, sigma_FE 860 N/mm^2 = "
                  "2 sigma_Flim); sigma_Hlim 1500 N/mm^2 is also the carburized steel of ISO/TR 6336-30 example 1"},
    "through-hardened": {
        "class": "V", "sigma_hlim": 740.0, "sigma_flim": 295.0, "yield_strength": 900.0,
        "source": "quenched and tempered steel of DIN 3990-11 example 1 (sigma_Hlim 740, sigma_FE 590, "
                  "R_p0.2 900 N/mm^2, 266 HB)"},
}


@dataclass(frozen=True)
class Pair:
    """One external mesh, pinion (1) and wheel (2), in mm and rad."""

    z1: int
    z2: int
    mn: float
    alpha_n: float
    beta: float
    x1: float
    x2: float
    b: float                    # common face width
    da1: float
    da2: float
    aw: float
    h_fp: tuple = (1.25, 1.25)  # dedendum of the basic rack, / m_n
    rho_fp: tuple = (0.25, 0.25)  # root radius of the basic rack, / m_n
    E: tuple = (206000.0, 206000.0)
    nu: tuple = (0.3, 0.3)
    b_each: tuple | None = None  # face widths of each gear (for K_Fbeta's b/h), default b
    internal: bool = False      # gear 2 is an internal gear (a ring): z2 > 0, da2 its (inner) tip diameter,
                                # x2 its profile shift as ISO 21771 writes it (d_a2 = d2 - 2 m_n (h_aP + x2))
    root_section2: tuple | None = None  # internal gear 2: (s_Fn, rho_F, d_sFn) at its 60 deg tangent, mm, given
                                        # (virtual gear of the normal section); none: its root is not rated


@dataclass(frozen=True)
class Material:
    cls: str                    # Eh, NT, V, St, GG
    sigma_hlim: float
    sigma_flim: float
    yield_strength: float | None = None
    hardness_hb: float | None = None   # Brinell hardness, for the work hardening factor Z_W of a soft gear


@dataclass(frozen=True)
class Load:
    """Operating point and the factors that are not computed here (K_v comes from the caller)."""

    torque1: float              # N m at the pinion
    n1: float                   # pinion speed, rpm
    kv: float
    ka: float = 1.0
    life_hours: float = 20000.0
    nu40: float = 220.0         # mm^2/s
    rz_flank: tuple = (6.0, 6.0)  # um
    rz_root: tuple = (10.0, 10.0)  # um
    f_ma: float = 10.0          # mesh misalignment from manufacturing, um
    f_pb: float = 7.0           # transverse base pitch deviation, um (K_alpha)
    c_gamma_alpha: float = 20.0  # N/(mm um), ISO 6336-1 9.4 (from the caller)
    k_hbeta: float | None = None  # given instead of method C
    k_halpha: float | None = None  # given instead of eqs. 73-76
    s_hmin: float = 1.0
    s_fmin: float = 1.0
    k_gamma: float = 1.0        # mesh load factor of a planetary stage (ISO 6336-1: K_gamma multiplies F_t)
    y_m: tuple = (1.0, 1.0)     # mean stress factor per gear (0.7: a planet's teeth bent both ways)
    cycles: tuple | None = None  # load cycles per gear; default n1 60 h (pinion) and that / u (wheel)


@dataclass
class Rating:
    """Everything the rating computed (standard's units): factors, stresses and safety factors."""

    geometry: dict = field(default_factory=dict)
    factors: dict = field(default_factory=dict)
    pinion: dict = field(default_factory=dict)
    wheel: dict = field(default_factory=dict)
    notes: list = field(default_factory=list)

    def as_dict(self) -> dict:
        return asdict(self)


def geometry(p: Pair) -> dict:
    """Transverse and virtual-gear quantities (ISO 21771)."""
    at = math.atan(math.tan(p.alpha_n) / math.cos(p.beta))
    d1, d2 = p.z1 * p.mn / math.cos(p.beta), p.z2 * p.mn / math.cos(p.beta)
    db1, db2 = d1 * math.cos(at), d2 * math.cos(at)
    beta_b = math.atan(math.tan(p.beta) * math.cos(at))
    # internal (ISO 21771): the ring's tip circle lies inside, the path of contact runs from its tip
    # inwards, the centre distance is the difference of the radii
    sign = -1.0 if p.internal else 1.0
    a = 0.5 * (d2 + sign * d1)
    awt = math.acos(a * math.cos(at) / p.aw)
    pbt = math.pi * p.mn * math.cos(at) / math.cos(p.beta)
    g_alpha = 0.5 * (math.sqrt(p.da1 ** 2 - db1 ** 2) + sign * math.sqrt(p.da2 ** 2 - db2 ** 2)) - sign * p.aw * math.sin(awt)
    eps_a = g_alpha / pbt
    eps_b = p.b * math.sin(p.beta) / (math.pi * p.mn)
    zn = [z / (math.cos(beta_b) ** 2 * math.cos(p.beta)) for z in (p.z1, p.z2)]
    return {"alpha_t": at, "alpha_wt": awt, "beta_b": beta_b, "d1": d1, "d2": d2, "db1": db1, "db2": db2,
            "p_bt": pbt, "eps_alpha": eps_a, "eps_beta": eps_b, "eps_gamma": eps_a + eps_b,
            "zn1": zn[0], "zn2": zn[1], "u": p.z2 / p.z1}


def _loglog(n: float, pts) -> float:
    """Life-factor line through (cycles, factor) points, straight on log-log axes, flat outside."""
    xs, ys = zip(*pts)
    if n <= xs[0]:
        return ys[0]
    if n >= xs[-1]:
        return ys[-1]
    for (x0, y0), (x1, y1) in zip(pts[:-1], pts[1:]):
        if n <= x1:
            t = math.log(n / x0) / math.log(x1 / x0)
            return math.exp(math.log(y0) + t * (math.log(y1) - math.log(y0)))
    return ys[-1]


# ISO 6336-2:2006 table 2: Z_NT, static value, reference at 5e7 (Eh, V, St) or 2e6 (NT, GG), 0.85 at 1e10
_ZNT = {"Eh": ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85)), "V": ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85)),
        "St": ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85)), "NT": ((1e5, 1.3), (2e6, 1.0), (1e10, 0.85)),
        "GG": ((1e5, 1.3), (2e6, 1.0), (1e10, 0.85))}
# ISO 6336-3:2006 table 2: Y_NT, reference at 3e6, 0.85 at 1e10
_YNT = {"Eh": ((1e3, 2.5), (3e6, 1.0), (1e10, 0.85)), "V": ((1e4, 2.5), (3e6, 1.0), (1e10, 0.85)),
        "St": ((1e4, 2.5), (3e6, 1.0), (1e10, 0.85)), "NT": ((1e3, 1.6), (3e6, 1.0), (1e10, 0.85)),
        "GG": ((1e3, 1.6), (3e6, 1.0), (1e10, 0.85))}
# ISO 6336-3:2006 table 3: Y_X against the normal module (mm)
_YX = {"Eh": ((5, 1.0), (25, 0.8)), "NT": ((5, 1.0), (25, 0.8)), "V": ((5, 1.0), (30, 0.85)),
       "St": ((5, 1.0), (30, 0.85)), "GG": ((5, 1.0), (25, 0.7))}


def _lin(x, pts):
    (x0, y0), (x1, y1) = pts
    return y0 if x <= x0 else y1 if x >= x1 else y0 + (y1 - y0) * (x - x0) / (x1 - x0)


def _c_zl(sigma_hlim: float) -> float:
    """ISO 6336-2:2006, 11.x: C_ZL from sigma_Hlim (850..1200 N/mm^2 linear)."""
    if sigma_hlim < 850:
        return 0.83
    if sigma_hlim < 1200:
        return sigma_hlim / 4375.0 + 0.6357
    return 0.91


def root_section(z_n: float, x: float, mn: float, alpha_n: float, h_fp: float, rho_fp: float) -> dict:
    """ISO 6336-3 method B: the critical section at the 30 deg tangent of a rack-generated fillet (mm)."""
    hf, rf = h_fp * mn, rho_fp * mn
    E = math.pi / 4 * mn - hf * math.tan(alpha_n) - (1 - math.sin(alpha_n)) * rf / math.cos(alpha_n)
    G = rho_fp - h_fp + x
    H = 2.0 / z_n * (math.pi / 2 - E / mn) - math.pi / 3
    theta = math.pi / 6
    for _ in range(100):
        new = 2 * G / z_n * math.tan(theta) - H
        if abs(new - theta) < 1e-13:
            theta = new
            break
        theta = new
    s_fn = mn * (z_n * math.sin(math.pi / 3 - theta) + math.sqrt(3) * (G / math.cos(theta) - rho_fp))
    rho_f = mn * (rho_fp + 2 * G ** 2 / (math.cos(theta) * (z_n * math.cos(theta) ** 2 - 2 * G)))
    return {"E": E, "G": G, "H": H, "theta": theta, "s_Fn": s_fn, "rho_F": rho_f}


def _root(p: Pair, g: dict, which: int, mat: Material, load: Load, notes: list) -> dict:
    z, x, da = (p.z1, p.x1, p.da1) if which == 0 else (p.z2, p.x2, p.da2)
    d = g["d1"] if which == 0 else g["d2"]
    z_n = g["zn1"] if which == 0 else g["zn2"]
    sec = root_section(z_n, x, p.mn, p.alpha_n, p.h_fp[which], p.rho_fp[which])
    cbb = math.cos(g["beta_b"]) ** 2
    eps_an = g["eps_alpha"] / cbb
    dn = d / cbb
    dbn = dn * math.cos(p.alpha_n)
    dan = dn + da - d
    den = 2 * math.sqrt((math.sqrt((dan / 2) ** 2 - (dbn / 2) ** 2)
                         - math.pi * d * math.cos(p.beta) * math.cos(p.alpha_n) / z * (eps_an - 1)) ** 2 + (dbn / 2) ** 2)
    aen = math.acos(dbn / den)
    gamma_e = (0.5 * math.pi + 2 * math.tan(p.alpha_n) * x) / z_n + inv(p.alpha_n) - inv(aen)
    afen = aen - gamma_e
    m = p.mn
    h_fe = 0.5 * m * ((math.cos(gamma_e) - math.sin(gamma_e) * math.tan(afen)) * den / m
                      - z_n * math.cos(math.pi / 3 - sec["theta"]) - sec["G"] / math.cos(sec["theta"]) + p.rho_fp[which])
    s_fn, rho_f = sec["s_Fn"], sec["rho_F"]
    y_f = 6 * h_fe / m * math.cos(afen) / ((s_fn / m) ** 2 * math.cos(p.alpha_n))
    L = s_fn / h_fe
    q_s = s_fn / (2 * rho_f)
    y_s = (1.2 + 0.13 * L) * q_s ** (1 / (1.21 + 2.3 / L))
    if not 1.0 <= q_s < 8.0:
        notes.append(f"{'pinion' if which == 0 else 'wheel'}: notch parameter q_s = {q_s:.3g} outside 1..8 "
                     "(ISO 6336-3 validity of Y_S)")
    return {"z_n": z_n, "d_en": den, "alpha_en": aen, "gamma_e": gamma_e, "alpha_Fen": afen, "h_Fe": h_fe,
            "s_Fn": s_fn, "rho_F": rho_f, "theta": sec["theta"], "Y_F": y_f, "Y_S": y_s, "q_s": q_s,
            "eps_alpha_n": eps_an}


def _root_internal(p: Pair, g: dict, notes: list) -> dict:
    """ISO 6336-3:2006 method B, 6.2 and 6.3, for an internal gear (gear 2) with its root section given.

    The section (chord s_Fn, fillet radius rho_F, diameter d_sFn at the 60 deg tangent that ISO 6336-3
    takes for internal gears) comes from the caller: ISO builds it from the pinion-type cutter, and
    neither the external gears' rack construction (E, G, H, theta with z_n < 0 and the 60 deg tangent:
    s_Fn 128.6 mm, rho_F 6.8 mm) nor an exact numerical generation by the cutter (z_0 36, x_0 0,
    rho_a0 0.3 m_n: s_Fn 132.16 mm, rho_F 13.57 mm, d_sFn 2673.25 mm) reproduces the 129.40 mm,
    22.24 mm, 2673.52 mm that KISSsoft prints for NREL 5 MW stage 1's ring (its note: "roF and sFn
    according to ISO 6336-3:2007-04-01"); stage 2's ring: 57.53 / 7.78 against 56.76 / 8.78 mm.

    The rest is built here. Load at the single-contact point nearest the ring's tip (its smallest
    diameter): p_bn (eps_alpha_n - 1) beyond its tip contact along the line of action, where the roll
    distance grows towards its root, d_en = 2 sqrt((sqrt(r_an^2 - r_bn^2) + p_bn (eps_alpha_n - 1))^2
    + r_bn^2); the internal tooth's half angle there gamma_e = (pi/2 + 2 x tan alpha_n) / z_n - inv alpha_n
    + inv alpha_en (the tooth widens outwards), alpha_Fen = alpha_en + gamma_e; the load line crosses
    the tooth's centre line at d_en/2 (cos gamma_e + sin gamma_e tan alpha_Fen), and h_Fe is that
    point's distance to the section chord at sqrt((d_sFn/2)^2 - (s_Fn/2)^2). Y_F, Y_S: ISO 6336-3
    eqs. as for external gears. Checked against both NREL reports: d_en 2497.634 / 1928.178 mm
    (printed d-D 2497.634 / 1928.177), alpha_Fen, h_F, Y_F, Y_S, sigma_F0 to the printed digits.
    """
    s_fn, rho_f, d_sfn = p.root_section2
    cbb = math.cos(g["beta_b"]) ** 2
    z_n, m = g["zn2"], p.mn
    eps_an = g["eps_alpha"] / cbb
    dn = g["d2"] / cbb
    dbn = dn * math.cos(p.alpha_n)
    dan = dn - (g["d2"] - p.da2)
    den = 2 * math.sqrt((math.sqrt((dan / 2) ** 2 - (dbn / 2) ** 2) + math.pi * m * math.cos(p.alpha_n) * (eps_an - 1)) ** 2
                        + (dbn / 2) ** 2)
    aen = math.acos(dbn / den)
    gamma_e = (0.5 * math.pi + 2 * math.tan(p.alpha_n) * p.x2) / z_n - inv(p.alpha_n) + inv(aen)
    afen = aen + gamma_e
    y_load = den / 2 * (math.cos(gamma_e) + math.sin(gamma_e) * math.tan(afen))
    if not 0 < s_fn < d_sfn or d_sfn <= den:
        raise ValueError(f"the root section (chord {s_fn:.6g} mm, diameter {d_sfn:.6g} mm) must lie beyond the load "
                         f"point's diameter {den:.6g} mm, with the chord shorter than the diameter")
    h_fe = math.sqrt((d_sfn / 2) ** 2 - (s_fn / 2) ** 2) - y_load
    if h_fe <= 0:
        raise ValueError(f"the root section at diameter {d_sfn:.6g} mm lies inside the load line's crossing of the "
                         f"tooth's centre line (at {2 * y_load:.6g} mm): bending arm {h_fe:.4g} mm")
    y_f = 6 * h_fe / m * math.cos(afen) / ((s_fn / m) ** 2 * math.cos(p.alpha_n))
    L = s_fn / h_fe
    q_s = s_fn / (2 * rho_f)
    y_s = (1.2 + 0.13 * L) * q_s ** (1 / (1.21 + 2.3 / L))
    if not 1.0 <= q_s < 8.0:
        notes.append(f"wheel: notch parameter q_s = {q_s:.3g} outside 1..8 (ISO 6336-3 validity of Y_S)")
    notes.append("wheel: internal gear: root section (s_Fn, rho_F, d_sFn) given, not computed")
    return {"z_n": z_n, "d_en": den, "alpha_en": aen, "gamma_e": gamma_e, "alpha_Fen": afen, "h_Fe": h_fe,
            "s_Fn": s_fn, "rho_F": rho_f, "d_sFn": d_sfn, "theta": float("nan"), "Y_F": y_f, "Y_S": y_s, "q_s": q_s,
            "eps_alpha_n": eps_an}


def _y_delta(mat: Material, q_s: float, notes: list, who: str) -> float:
    """Relative notch sensitivity Y_deltarelT (ISO 6336-3:2006, 11.x), slip-layer thickness rho' in mm."""
    if mat.cls == "Eh":
        rho = 0.0030
    elif mat.cls == "NT":
        rho = 0.1005
    elif mat.cls == "V" and mat.yield_strength is not None:
        ys = min(max(mat.yield_strength, 500.0), 1000.0)
        pts = ((500, 0.0281), (600, 0.0194), (800, 0.0064), (1000, 0.0014))
        rho = next(r0 + (r1 - r0) * (ys - y0) / (y1 - y0) for (y0, r0), (y1, r1) in zip(pts[:-1], pts[1:]) if ys <= y1)
    else:
        notes.append(f"{who}: Y_deltarelT taken as 1 (no slip-layer data for class {mat.cls} without a yield strength)")
        return 1.0
    x_star = (1 + 2 * q_s) / 5
    return (1 + math.sqrt(rho * x_star)) / (1 + math.sqrt(rho * 1.2))


def _y_r(mat: Material, rz: float) -> float:
    """Relative surface factor Y_RrelT from the root roughness R_z in um (ISO 6336-3:2006, 12.x)."""
    if mat.cls in ("Eh", "V"):
        return 1.12 if rz < 1 else 1.674 - 0.529 * (rz + 1) ** 0.1
    if mat.cls == "St":
        return 1.07 if rz < 1 else 5.306 - 4.203 * (rz + 1) ** 0.01
    return 1.025 if rz < 1 else 4.299 - 3.259 * (rz + 1) ** 0.0058


def rate(p: Pair, mats: tuple, load: Load) -> Rating:
    """Contact and root stresses, permissible stresses and safety factors of pinion and wheel."""
    g = geometry(p)
    r = Rating(geometry=g)
    notes = r.notes
    d1, u, b = g["d1"], g["u"], p.b
    ft = 2000.0 * load.torque1 / d1
    v = math.pi * d1 * load.n1 / 60000.0
    # ISO 6336-1 7.6 method C (pinion offset s = 0, no helix modification)
    fm = ft * load.ka * load.k_gamma * load.kv
    if load.k_hbeta is None:
        f_sh = fm / b * 0.023 * (b / d1) ** 2
        f_betax = 1.33 * f_sh + load.f_ma
        hardened = all(m.cls in ("Eh", "NT") for m in mats)
        y_beta = min(0.15 * f_betax, 6.0) if hardened else 0.0
        f_betay = f_betax - y_beta
        c_gb = 0.85 * load.c_gamma_alpha
        w = f_betay * c_gb / (2 * fm / b)
        k_hb = 1 + w if w <= 1 else 2 * math.sqrt(w)
    else:
        f_sh = f_betax = f_betay = y_beta = float("nan")
        k_hb = load.k_hbeta
    h1 = (p.da1 - (g["d1"] - 2 * p.mn * (p.h_fp[0] - p.x1))) / 2
    h2 = ((g["d2"] + 2 * p.mn * (p.h_fp[1] - p.x2)) - p.da2) / 2 if p.internal else \
        (p.da2 - (g["d2"] - 2 * p.mn * (p.h_fp[1] - p.x2))) / 2
    bb = p.b_each or (b, b)
    bh = max(min(bb[0] / h1, bb[1] / h2), 3.0)
    n_f = bh ** 2 / (1 + bh + bh ** 2)
    k_fb = k_hb ** n_f
    # contact factors, ISO 6336-2
    ea, eb = g["eps_alpha"], g["eps_beta"]
    if p.beta == 0:
        z_eps = math.sqrt((4 - ea) / 3)
    elif eb < 1:
        z_eps = math.sqrt((4 - ea) / 3 * (1 - eb) + eb / ea)
    else:
        z_eps = math.sqrt(1 / ea)
    # ISO 6336-1 8.3, eqs. 73-76: K_Falpha = K_Halpha from the base pitch deviation after running-in
    from ..mesh.iso6336 import running_in

    if load.k_halpha is None:
        y_a = running_in(load.f_pb, _running_class(mats), min(m.sigma_hlim for m in mats), v)
        f_th = ft * load.ka * load.k_gamma * load.kv * k_hb
        term = load.c_gamma_alpha * max(load.f_pb - y_a, 0.0) / (f_th / b)
        eg = g["eps_gamma"]
        k_a = (eg / 2 * (0.9 + 0.4 * term)) if eg <= 2 else 0.9 + 0.4 * math.sqrt(2 * (eg - 1) / eg) * term
        k_ha = min(max(k_a, 1.0), eg / (ea * z_eps ** 2))
        k_fa = min(max(k_a, 1.0), eg / (0.25 * ea + 0.75))
    else:
        k_ha = k_fa = load.k_halpha
    z_h = math.sqrt(2 * math.cos(g["beta_b"]) * math.cos(g["alpha_wt"]) / (math.cos(g["alpha_t"]) ** 2 * math.sin(g["alpha_wt"])))
    z_e = math.sqrt(1 / (math.pi * ((1 - p.nu[0] ** 2) / p.E[0] + (1 - p.nu[1] ** 2) / p.E[1])))
    z_beta = 1 / math.sqrt(math.cos(p.beta))
    ra1, rb1, rb2 = p.da1 / 2, g["db1"] / 2, g["db2"] / 2
    # M_1, M_2 (ISO 6336-2 6.2): sqrt of the product of the radii of curvature at the pitch point over
    # that at the inner point of single contact B of the pinion (D of the wheel). Along the line of
    # action from the pinion's tangent point, the pinion's radius is s and the wheel's T1T2 - s
    # (external) or s + a_w sin(alpha_wt) (internal); B = E - p_bt, D = A + p_bt. For an external pair
    # this is ISO's formula with the tip radii written out.
    t = math.tan(g["alpha_wt"])
    lwt = p.aw * math.sin(g["alpha_wt"])
    s_e = math.sqrt(ra1 ** 2 - rb1 ** 2)
    s_a = s_e - g["eps_alpha"] * g["p_bt"]

    def rho2(s):
        return s + lwt if p.internal else lwt - s

    def mm(s):
        return t / math.sqrt(s / rb1 * rho2(s) / rb2)

    m1, m2 = mm(s_e - g["p_bt"]), mm(s_a + g["p_bt"])

    def zbd(mm):
        if eb >= 1 or mm <= 1:
            return 1.0
        return mm if p.beta == 0 else mm - eb * (mm - 1)

    # ISO 6336-2 6.2: Z_D = 1 for an internal wheel
    z_b, z_d = zbd(m1), (1.0 if p.internal else zbd(m2))
    # (u + 1) / u with u negative for an internal pair (ISO 6336-2 eq. for sigma_H0)
    u_s = -u if p.internal else u
    sigma_h0 = z_h * z_e * z_eps * z_beta * math.sqrt(ft / (d1 * b) * (u_s + 1) / u_s)
    k_h = load.ka * load.k_gamma * load.kv * k_hb * k_ha
    # lubricant, velocity, roughness (ISO 6336-2 11): one C_ZL from the weaker flank
    shl = min(m.sigma_hlim for m in mats)
    c_zl = _c_zl(shl)
    z_l = c_zl + 4 * (1 - c_zl) / (1.2 + 134.0 / load.nu40) ** 2
    c_zv = c_zl + 0.02
    z_v = c_zv + 2 * (1 - c_zv) / math.sqrt(0.8 + 32.0 / v)
    rho1, rho2_ = rb1 * t, rb2 * t
    rho_red = rho1 * rho2_ / (rho2_ - rho1 if p.internal else rho1 + rho2_)
    rz10 = 0.5 * (load.rz_flank[0] + load.rz_flank[1]) * (10.0 / rho_red) ** (1 / 3)
    c_zr = 0.15 if shl < 850 else (0.32 - 0.0002 * shl if shl < 1200 else 0.08)
    z_r = (3.0 / rz10) ** c_zr
    n_l = load.cycles or (60.0 * load.life_hours * load.n1, 60.0 * load.life_hours * load.n1 / u)
    z_w = _z_w(mats)
    r.factors = {"F_t": ft, "v": v, "K_A": load.ka, "K_gamma": load.k_gamma, "K_v": load.kv, "K_Hbeta": k_hb,
                 "K_Fbeta": k_fb,
                 "K_Halpha": k_ha, "K_Falpha": k_fa, "f_sh": f_sh, "F_betax": f_betax, "y_beta": y_beta,
                 "F_betay": f_betay, "N_F": n_f, "Z_H": z_h, "Z_E": z_e, "Z_eps": z_eps, "Z_beta": z_beta,
                 "Z_L": z_l, "Z_v": z_v, "Z_R": z_r, "R_z10": rz10, "sigma_H0": sigma_h0, "rho_red": rho_red,
                 "M_1": m1, "M_2": m2,
                 "Y_beta": 1 - min(eb, 1.0) * min(math.degrees(p.beta), 30.0) / 120.0}
    for which, (mat, zbd_, out) in enumerate(((mats[0], z_b, r.pinion), (mats[1], z_d, r.wheel))):
        who = "pinion" if which == 0 else "wheel"
        sigma_h = zbd_ * sigma_h0 * math.sqrt(k_h)
        z_nt = _loglog(n_l[which], _ZNT[mat.cls])
        sigma_hg = mat.sigma_hlim * z_nt * z_l * z_v * z_r * z_w[which]     # Z_X = 1
        out.update({"Z_B_or_Z_D": zbd_, "sigma_H": sigma_h, "N_L": n_l[which], "Z_NT": z_nt, "Z_W": z_w[which],
                    "sigma_HG": sigma_hg, "sigma_HP": sigma_hg / load.s_hmin, "S_H": sigma_hg / sigma_h,
                    "sigma_Hlim": mat.sigma_hlim, "sigma_Flim": mat.sigma_flim, "material_class": mat.cls})
        if which == 1 and p.internal and p.root_section2 is None:
            # ISO 6336-3 rates an internal gear's root with the tooth form its pinion-type cutter generates;
            # that construction is not built here (see _root_internal): without the section given, the
            # ring's root is not rated
            notes.append("wheel: internal gear: tooth root not rated (give its root section: chord s_Fn, fillet "
                          "radius rho_F and diameter d_sFn at the 60 deg tangent, from the tooth form)")
            nan = float("nan")
            out.update({k: nan for k in ("Y_F", "Y_S", "sigma_F0", "sigma_F", "Y_NT", "Y_deltarelT", "Y_RrelT",
                                         "Y_X", "sigma_FG", "sigma_FP", "S_F")})
            out["Y_M"] = load.y_m[which]
            continue
        if which == 1 and p.internal:
            root = _root_internal(p, g, notes)
        else:
            root = _root(p, g, which, mat, load, notes)
        if root["eps_alpha_n"] > 2.05:
            notes.append(f"{who}: eps_alpha_n = {root['eps_alpha_n']:.3f} > 2.05: Y_DT = 1 kept (accuracy grade not modelled)")
        y_b = y_dt = 1.0
        bw = (p.b_each or (b, b))[which]
        sigma_f0 = ft / (bw * p.mn) * root["Y_F"] * root["Y_S"] * r.factors["Y_beta"] * y_b * y_dt
        sigma_f = sigma_f0 * load.ka * load.k_gamma * load.kv * k_fb * k_fa
        y_nt = _loglog(n_l[which], _YNT[mat.cls])
        y_d = _y_delta(mat, root["q_s"], notes, who)
        y_r = _y_r(mat, (load.rz_root[which]))
        y_x = _lin(p.mn, _YX[mat.cls])
        # Y_ST = 2; Y_M (ISO 6336-3:2019, 0.7 for teeth bent both ways, ISO 6336-3:2006 applied 0.7 to sigma_Flim)
        sigma_fg = mat.sigma_flim * 2.0 * y_nt * y_d * y_r * y_x * load.y_m[which]
        out.update({**root, "sigma_F0": sigma_f0, "sigma_F": sigma_f, "Y_NT": y_nt, "Y_deltarelT": y_d,
                    "Y_RrelT": y_r, "Y_X": y_x, "Y_M": load.y_m[which], "sigma_FG": sigma_fg,
                    "sigma_FP": sigma_fg / load.s_fmin, "S_F": sigma_fg / sigma_f})
    return r


def _z_w(mats) -> tuple:
    """Work hardening factor Z_W of each gear (ISO 6336-2:2006, 13): a through-hardened or structural
    steel gear of Brinell hardness HB meshing with a surface-hardened one gains
    Z_W = 1.2 - (HB - 130) / 1700 (HB within 130..470); 1 otherwise and without a hardness."""
    out = []
    for me, other in ((mats[0], mats[1]), (mats[1], mats[0])):
        if me.cls in ("V", "St") and other.cls in ("Eh", "NT") and me.hardness_hb is not None:
            hb = min(max(me.hardness_hb, 130.0), 470.0)
            out.append(1.2 - (hb - 130.0) / 1700.0)
        else:
            out.append(1.0)
    return tuple(out)


def _running_class(mats) -> str:
    """The running-in class of the pair for y_alpha (the softer gear governs)."""
    order = ("GG", "St", "V", "NT", "Eh")
    cls = min((m.cls for m in mats), key=order.index)
    return "St" if cls == "V" else cls


def material_of(model, gear) -> Material:
    """The material of one gear: its own ``steel``, else the model's ``iso`` section; its own
    ``yield_strength`` before either's."""
    iso = model.iso
    name = gear.steel or iso.steel
    if name is not None:
        s = STEELS[name]
        mat = Material(s["class"], s["sigma_hlim"], s["sigma_flim"], s["yield_strength"])
    else:
        mat = Material(iso.material, iso.sigma_hlim / 1e6, iso.sigma_flim / 1e6,
                       None if iso.yield_strength is None else iso.yield_strength / 1e6)
    if getattr(gear, "yield_strength", None) is not None:
        mat = replace(mat, yield_strength=gear.yield_strength / 1e6)
    return mat


def rate_mesh(model, sys_, j: int, kv: float) -> Rating:
    """ISO 6336-2/-3 rating of mesh ``j`` of an assembled train at the nominal load with dynamic factor ``kv``.

    The pinion (ISO's gear 1) is the gear with fewer teeth; the torque through the mesh is the nominal
    mesh force times that gear's base radius; its speed is the nominal one.
    """
    p_ = sys_.pairs[j]
    ia, ib = int(sys_.mesh_a[j]), int(sys_.mesh_b[j])
    (g1, i1, ga), (g2, i2, gb) = ((p_.g1, ia, model.gears[ia]), (p_.g2, ib, model.gears[ib]))
    if g2.z < g1.z:
        (g1, i1, ga), (g2, i2, gb) = (g2, i2, gb), (g1, i1, ga)
    iso = model.iso
    pair = Pair(z1=g1.z, z2=g2.z, mn=g1.m * 1e3, alpha_n=g1.alpha, beta=g1.beta, x1=g1.x, x2=g2.x,
                b=min(g1.b, g2.b) * 1e3, da1=2e3 * g1.ra, da2=2e3 * g2.ra, aw=p_.a_w * 1e3,
                h_fp=(ga.dedendum, gb.dedendum), rho_fp=(ga.root_radius, gb.root_radius),
                E=(ga.youngs_modulus / 1e6, gb.youngs_modulus / 1e6), nu=(ga.poisson, gb.poisson),
                b_each=(g1.b * 1e3, g2.b * 1e3))
    load = Load(torque1=abs(sys_.force_nominal[j]) * g1.rb, n1=abs(sys_.ratio[i1] * sys_.omega_in) * 30 / math.pi,
                kv=kv, ka=iso.application_factor, life_hours=iso.life / 3600.0, nu40=iso.lubricant_viscosity * 1e6,
                rz_flank=tuple((g.flank_roughness or iso.flank_roughness) * 1e6 for g in (ga, gb)),
                rz_root=tuple((g.root_roughness or iso.root_roughness) * 1e6 for g in (ga, gb)),
                f_ma=iso.mesh_misalignment * 1e6, f_pb=iso.pitch_deviation * 1e6,
                c_gamma_alpha=sys_.iso[j].c_gamma, k_hbeta=iso.face_load_factor, k_halpha=iso.transverse_load_factor,
                s_hmin=iso.min_safety_pitting, s_fmin=iso.min_safety_bending,
                cycles=tuple(cycles_of(sys_, i, j, iso.life) for i in (i1, i2)),
                y_m=tuple(0.7 if _both_flanks(sys_, i) else 1.0 for i in (i1, i2)))
    r = rate(pair, (material_of(model, ga), material_of(model, gb)), load)
    r.geometry.update({"pinion": model.gears[i1].name, "wheel": model.gears[i2].name})
    return r


def _role(sys_, i: int, j: int) -> str:
    """Which flank of gear ``i`` mesh ``j`` loads: the driving or the driven one."""
    return "driving" if int(sys_.mesh_a[j]) == i else "driven"


def _both_flanks(sys_, i: int) -> bool:
    """An idler: gear ``i`` drives one mesh and is driven in another, its teeth bent both ways
    (ISO 6336-3: mean stress factor Y_M = 0.7)."""
    return {_role(sys_, i, j) for j in range(sys_.m) if i in (int(sys_.mesh_a[j]), int(sys_.mesh_b[j]))} == {"driving", "driven"}


def cycles_of(sys_, i: int, j: int, life: float) -> float:
    """Load cycles of gear ``i``'s loaded flank in mesh ``j`` over ``life`` (s): a tooth meets every
    mesh that loads the same flank once a turn (a pinion driving two wheels: twice a turn)."""
    same = sum(1 for k in range(sys_.m) if i in (int(sys_.mesh_a[k]), int(sys_.mesh_b[k]))
               and _role(sys_, i, k) == _role(sys_, i, j))
    return abs(sys_.ratio[i] * sys_.omega_in) / (2 * math.pi) * life * same


def summary_of(r_dyn: Rating, r_iso: Rating, load_min: tuple) -> dict:
    """The summary entry of one mesh (SI): safety factors with K_v from the dynamics and from ISO method B."""
    s_hmin, s_fmin = load_min
    out = {"pinion": r_dyn.geometry["pinion"], "wheel": r_dyn.geometry["wheel"],
           "kv_dynamic": r_dyn.factors["K_v"], "kv_iso_method_b": r_iso.factors["K_v"]}
    for key in ("K_Hbeta", "K_Fbeta", "K_Halpha", "K_Falpha", "Z_H", "Z_E", "Z_eps", "Z_beta", "Z_L", "Z_v", "Z_R",
                "Y_beta"):
        out[key] = r_dyn.factors[key] * (1e3 if key == "Z_E" else 1.0)   # Z_E in sqrt(N)/m from sqrt(N)/mm
    worst = []
    for who, rd, ri in (("pinion", r_dyn.pinion, r_iso.pinion), ("wheel", r_dyn.wheel, r_iso.wheel)):
        out[who + "_rating"] = {
            "sigma_H": rd["sigma_H"] * 1e6, "sigma_HP": rd["sigma_HP"] * 1e6, "S_H": rd["S_H"], "S_H_iso_kv": ri["S_H"],
            "sigma_F": rd["sigma_F"] * 1e6, "sigma_FP": rd["sigma_FP"] * 1e6, "S_F": rd["S_F"], "S_F_iso_kv": ri["S_F"],
            "Y_F": rd["Y_F"], "Y_S": rd["Y_S"], "Z_NT": rd["Z_NT"], "Y_NT": rd["Y_NT"], "load_cycles": rd["N_L"],
            "sigma_Hlim": rd["sigma_Hlim"] * 1e6, "sigma_Flim": rd["sigma_Flim"] * 1e6, "material_class": rd["material_class"]}
        if rd["S_H"] < s_hmin:
            worst.append(f"{who} pitting S_H {rd['S_H']:.3f} < {s_hmin:g}")
        if rd["S_F"] < s_fmin:
            worst.append(f"{who} root S_F {rd['S_F']:.3f} < {s_fmin:g}")
    out["S_H_min_required"], out["S_F_min_required"] = s_hmin, s_fmin
    out["verdict"] = ("fails: " + "; ".join(worst)) if worst else "passes (S_H and S_F at or above the minimums)"
    out["notes"] = list(dict.fromkeys(r_dyn.notes))
    return out
