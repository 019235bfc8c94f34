"""The lateral-torsional model of a planetary stage (Lin & Parker, J. Vib. Acoust. 121 (1999) 316-321):
translations and rotations of sun, ring, carrier and planets on bearings, mean mesh stiffnesses,
natural modes classed as the paper classes them, and static load sharing with pin position errors
and a floating sun.

Coordinates (the paper's, at zero carrier speed): sun, ring and carrier have translations x, y (m,
fixed frame) and a rotation written as a displacement u = r theta (m), r the base radius of sun and
ring and the centre distance R of the carrier; planet n (at angle psi_n) has a radial and a
tangential translation zeta_n, eta_n and u_n = r_bp theta_n, all rotations positive in one sense.
Deflections, compression positive (Lin & Parker, eqs. 1-3; alpha_s, alpha_r the working pressure
angles of the sun-planet and ring-planet meshes, psi_sn = psi_n - alpha_s, psi_rn = psi_n + alpha_r):

    sun-planet   d_sn = -x_s sin psi_sn + y_s cos psi_sn + u_s - zeta_n sin alpha_s - eta_n cos alpha_s + u_n
    ring-planet  d_rn = -x_r sin psi_rn + y_r cos psi_rn + u_r + zeta_n sin alpha_r - eta_n cos alpha_r - u_n
    planet pin   d_zn =  x_c cos psi_n + y_c sin psi_n - zeta_n
                 d_en = -x_c sin psi_n + y_c cos psi_n + u_c - eta_n + e_n

with e_n the tangential pin position error (+ along the carrier's rotation; with rigid pins it enters
the mesh deflections as -e_n cos alpha, as in the torsional model of ``planetary``). Potential energy
1/2 sum k d^2 over the meshes, the planet bearings (k_p, both directions), the radial bearings of sun,
ring and carrier (k_j on x_j, y_j) and their torsional supports (k_tj on theta_j, in N m/rad);
kinetic energy 1/2 sum (m_j (x'^2 + y'^2) + J_j / r_j^2 u'^2). A member held rigidly in a direction
loses that coordinate; a radial stiffness of 0 lets it float (a floating sun is centred by its
meshes only).

Mode classes (Lin & Parker, section 3, equally spaced identical planets): rotational (central
members only rotate, all planets move alike), translational (central members only translate,
multiplicity 2), planet (central members at rest, multiplicity N - 3). Other stages give "mixed".
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

MEMBERS = ("sun", "ring", "carrier")
#: a coordinate is "at rest" in a mode when its amplitude is below this share of the largest one
AT_REST = 1e-6


@dataclass(frozen=True)
class LateralStage:
    """Data of one stage for the lateral-torsional model (SI)."""

    base_radius_sun: float
    base_radius_planet: float
    base_radius_ring: float
    centre_distance: float                 # R, radius of the planet pins
    alpha_sun: float                       # working pressure angle of the sun-planet meshes, rad
    alpha_ring: float                      # of the ring-planet meshes
    planet_angles: tuple                   # psi_n, rad
    k_sun_planet: float                    # N/m
    k_ring_planet: float
    k_planet_bearing: float                # N/m, radial and tangential
    mass: dict                             # member or "planet" -> kg
    inertia: dict                          # member or "planet" -> kg m^2
    bearing: dict = field(default_factory=dict)   # member -> radial stiffness N/m, 0 floating, "fixed" rigid
    torsion: dict = field(default_factory=dict)   # member -> torsional support N m/rad, "fixed" rigid
    position_errors: tuple = ()

    @property
    def n(self) -> int:
        return len(self.planet_angles)

    def radius(self, member: str) -> float:
        return {"sun": self.base_radius_sun, "ring": self.base_radius_ring, "carrier": self.centre_distance,
                "planet": self.base_radius_planet}[member]

    def errors(self) -> np.ndarray:
        e = np.zeros(self.n)
        e[:len(self.position_errors)] = self.position_errors
        return e


def coordinate_names(n: int) -> list[str]:
    out = [f"{m}.{c}" for m in MEMBERS for c in ("x", "y", "u")]
    return out + [f"planet{i + 1}.{c}" for i in range(n) for c in ("zeta", "eta", "u")]


def _springs(st: LateralStage):
    """(kind, planet, stiffness, g, offset) of every spring: d = g . q + offset (full coordinates)."""
    n = st.n
    size = 9 + 3 * n
    e = st.errors()
    out = []
    a_s, a_r = st.alpha_sun, st.alpha_ring
    for i, psi in enumerate(st.planet_angles):
        p = 9 + 3 * i
        g = np.zeros(size)
        g[0:3] = -math.sin(psi - a_s), math.cos(psi - a_s), 1.0
        g[p:p + 3] = -math.sin(a_s), -math.cos(a_s), 1.0
        out.append(("sun-planet", i, st.k_sun_planet, g, 0.0))
        g = np.zeros(size)
        g[3:6] = -math.sin(psi + a_r), math.cos(psi + a_r), 1.0
        g[p:p + 3] = math.sin(a_r), -math.cos(a_r), -1.0
        out.append(("ring-planet", i, st.k_ring_planet, g, 0.0))
        g = np.zeros(size)
        g[6:8] = math.cos(psi), math.sin(psi)
        g[p] = -1.0
        out.append(("pin-radial", i, st.k_planet_bearing, g, 0.0))
        g = np.zeros(size)
        g[6:9] = -math.sin(psi), math.cos(psi), 1.0
        g[p + 1] = -1.0
        out.append(("pin-tangential", i, st.k_planet_bearing, g, float(e[i])))
    for j, m in enumerate(MEMBERS):
        k = st.bearing.get(m, 0.0)
        if k != "fixed" and k > 0:
            for c in (0, 1):
                g = np.zeros(size)
                g[3 * j + c] = 1.0
                out.append(("bearing", m, float(k), g, 0.0))
        kt = st.torsion.get(m, 0.0)
        if kt != "fixed" and kt > 0:
            g = np.zeros(size)
            g[3 * j + 2] = 1.0
            out.append(("torsion", m, float(kt) / st.radius(m) ** 2, g, 0.0))
    return out


def _kept(st: LateralStage) -> list[int]:
    drop = set()
    for j, m in enumerate(MEMBERS):
        if st.bearing.get(m, 0.0) == "fixed":
            drop |= {3 * j, 3 * j + 1}
        if st.torsion.get(m, 0.0) == "fixed":
            drop.add(3 * j + 2)
    return [i for i in range(9 + 3 * st.n) if i not in drop]


def matrices(st: LateralStage) -> tuple[np.ndarray, np.ndarray, list[str]]:
    """Mass and stiffness matrices over the kept coordinates, and their names."""
    n = st.n
    size = 9 + 3 * n
    diag = []
    for m in MEMBERS:
        diag += [st.mass[m], st.mass[m], st.inertia[m] / st.radius(m) ** 2]
    diag += [st.mass["planet"], st.mass["planet"], st.inertia["planet"] / st.base_radius_planet ** 2] * n
    K = np.zeros((size, size))
    for _, _, k, g, _ in _springs(st):
        K += k * np.outer(g, g)
    keep = _kept(st)
    names = coordinate_names(n)
    return np.diag(diag)[np.ix_(keep, keep)], K[np.ix_(keep, keep)], [names[i] for i in keep]


def classify(v: np.ndarray, names: list[str]) -> str:
    """Lin & Parker's class of one mode shape (see the module docstring)."""
    a = np.abs(v) / max(np.abs(v).max(), 1e-300)
    trans = [a[i] for i, nm in enumerate(names) if nm.split(".")[0] in MEMBERS and nm[-1] in "xy"]
    rot = [a[i] for i, nm in enumerate(names) if nm.split(".")[0] in MEMBERS and nm.endswith(".u")]
    t, r = max(trans, default=0.0), max(rot, default=0.0)
    if t < AT_REST and r < AT_REST:
        return "planet"
    if t < AT_REST:
        # every planet alike (each in its own radial/tangential frame)
        blocks = np.array([[v[names.index(f"{p}.{c}")] for c in ("zeta", "eta", "u")]
                           for p in dict.fromkeys(nm.split(".")[0] for nm in names if nm.startswith("planet"))])
        same = np.abs(blocks - blocks[0]).max() < AT_REST * np.abs(v).max()
        return "rotational" if same else "mixed"
    if r < AT_REST:
        return "translational"
    return "mixed"


def modes(st: LateralStage) -> tuple[np.ndarray, np.ndarray, list[str], list[str]]:
    """Natural frequencies (Hz, ascending; rigid-body modes at 0), mass-normalised shapes over the
    kept coordinates, the coordinate names and each mode's class."""
    from scipy.linalg import eigh

    M, K, names = matrices(st)
    w2, V = eigh(K, M)
    f = np.sqrt(np.clip(w2, 0.0, None)) / (2 * math.pi)
    return f, V, names, [classify(V[:, r], names) for r in range(V.shape[1])]


def load_sharing(st: LateralStage, torque: float, member: str = "sun") -> dict:
    """Static mesh and pin forces with ``torque`` (N m) on ``member``, the supports as given, and the
    pin position errors. K_gamma = largest sun-planet force / mean."""
    M, K, names = matrices(st)
    keep = _kept(st)
    size = 9 + 3 * st.n
    j = MEMBERS.index(member)
    if 3 * j + 2 not in keep:
        raise ValueError(f"the torque acts on the {member}, which is held")
    f = np.zeros(size)
    f[3 * j + 2] = torque / st.radius(member)         # u = r theta: the generalised force of T is T / r
    springs = _springs(st)
    for _, _, k, g, off in springs:
        f -= k * off * g                               # 1/2 k (g.q + off)^2 loads the coordinates by -k off g
    if np.linalg.matrix_rank(K) < K.shape[0]:
        raise ValueError("the stage is not held: a rigid-body motion is left (hold a member or give support stiffnesses)")
    q = np.zeros(size)
    q[keep] = np.linalg.solve(K, f[keep])
    forces = {}
    for kind, who, k, g, off in springs:
        forces.setdefault(kind, []).append((who, k * (g @ q + off)))
    F_s = np.array([v for _, v in forces["sun-planet"]])
    F_r = np.array([v for _, v in forces["ring-planet"]])
    flank = -1.0 if F_s.sum() < 0 else 1.0            # the loaded flanks' forces positive (see planetary.py)
    F_s, F_r = flank * F_s, flank * F_r
    mean = F_s.mean()
    return {"sun_planet_force": F_s, "ring_planet_force": F_r,
            "pin_force_radial": np.array([v for _, v in forces["pin-radial"]]),
            "pin_force_tangential": np.array([v for _, v in forces["pin-tangential"]]),
            "share": F_s / F_s.sum(), "load_sharing_factor": float(F_s.max() / mean) if mean > 0 else math.inf,
            "sun_displacement": (float(q[0]), float(q[1])), "coordinates": q,
            "contact_lost": bool((F_s < 0).any() or (F_r < 0).any())}
