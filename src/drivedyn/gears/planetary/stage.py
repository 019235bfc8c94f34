"""A simple planetary stage (sun, planets on a carrier, ring) as a lumped torsional model:
mesh phasing, natural modes and static load sharing with planet position errors.

Coordinates: absolute rotations of the sun, ring and carrier and of each planet (rad, all positive
in one sense); sun, planets and ring are standard gears (no profile shift, so the ring has
z_r = z_s + 2 z_p teeth and the planets sit at radius R = (z_s + z_p) m / 2), meshing at the
pressure angle alpha; a helical stage is taken in its transverse section (m = m_t, alpha = alpha_t,
stiffnesses along the transverse lines of action; axial forces and tilting are not modelled). In the carrier's frame the stage is an ordinary train with fixed axes, which
gives the mesh deflections along the lines of action (compressive positive when the sun drives):

    sun-planet n  (external): d_sn = r_bs (th_s - th_c) + r_bp (th_n - th_c) - e_n cos(alpha)
    ring-planet n (internal): d_rn = r_br (th_r - th_c) - r_bp (th_n - th_c) - e_n cos(alpha)

e_n is the tangential position error of planet n's pin (along the carrier's rotation): moving a
pin by e acts like turning the carrier by e / R for that planet only, and R cos(alpha) = r_bs + r_bp
= r_br - r_bp. Potential energy V = 1/2 sum(k_sp d_sn^2 + k_rp d_rn^2) with the mean mesh
stiffnesses, kinetic energy 1/2 (J_s w_s^2 + J_r w_r^2 + (J_c + N m_p R^2) w_c^2 + J_p sum w_n^2),
torsional supports k_s, k_r, k_c to ground (a member given as fixed is removed). This is the
rotational part of Lin & Parker's lumped model (J. Vib. Acoust. 121 (1999) 316-321): the
translational degrees of freedom, and with them the translational modes, are not modelled.

Closed forms that follow from these equations (tests/gears/test_planetary.py):

- planet modes: with N >= 2 equally spaced identical planets, the central members at rest and the
  planets moving with amplitudes that sum to zero, every planet obeys J_p th'' = -r_bp^2 (k_sp + k_rp) th:
  omega^2 = r_bp^2 (k_sp + k_rp) / J_p, multiplicity N - 1;
- rotational modes: all planets alike; they are the modes of the reduced model with one planet of
  N times the stiffness and inertia;
- load sharing (carrier and ring held, torque T on the sun): planet n carries
  F_n = T / (N r_bs) + k_e 2 cos(alpha) (mean(e) - e_n), k_e = k_sp k_rp / (k_sp + k_rp);
- mesh phasing (counting rule): seen in the carrier's frame the sun turns past planet n's mesh
  z_s psi_n / (2 pi) teeth after it passed planet 1's, the ring (turning the other way) z_r psi_n / (2 pi)
  teeth before: gamma_sn = frac(z_s psi_n / 2 pi), gamma_rn = frac(-z_r psi_n / 2 pi) mesh periods.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np


@dataclass(frozen=True)
class Stage:
    """Data of one stage (SI)."""

    z_sun: int
    z_planet: int
    module: float
    planet_angles: tuple               # psi_n, rad
    k_sun_planet: float                # mean mesh stiffness, N/m
    k_ring_planet: float
    inertia_sun: float
    inertia_ring: float
    inertia_carrier: float
    inertia_planet: float
    mass_planet: float
    pressure_angle: float = math.radians(20.0)
    position_errors: tuple = ()        # e_n, m (tangential, + with the carrier's rotation)
    support: dict = field(default_factory=dict)   # member -> torsional stiffness (N m/rad) or "fixed"
    ring_teeth: int | None = None      # none: z_s + 2 z_p (standard gears)
    centre_distance: float | None = None   # none: (z_s + z_p) m / 2 (no profile shift)

    @property
    def z_ring(self) -> int:
        return self.ring_teeth or self.z_sun + 2 * self.z_planet

    @property
    def cosines(self) -> tuple[float, float]:
        """cos of the working pressure angles of the sun-planet and ring-planet meshes:
        R cos(alpha_ws) = r_bs + r_bp, R cos(alpha_wr) = r_br - r_bp."""
        rbs, rbp, rbr, R = self.radii
        return (rbs + rbp) / R, (rbr - rbp) / R

    @property
    def n(self) -> int:
        return len(self.planet_angles)

    @property
    def radii(self) -> tuple:
        """(r_bs, r_bp, r_br, R) in m."""
        c = math.cos(self.pressure_angle)
        rs, rp, rr = (0.5 * z * self.module for z in (self.z_sun, self.z_planet, self.z_ring))
        return rs * c, rp * c, rr * c, self.centre_distance or rs + rp

    def errors(self) -> np.ndarray:
        e = np.zeros(self.n)
        e[:len(self.position_errors)] = self.position_errors
        return e


def assembly_ok(z_sun: int, z_ring: int, n: int) -> bool:
    """Equally spaced planets fit when (z_s + z_r) / N is a whole number (each planet then meets the
    sun and the ring teeth as the first one does)."""
    return (z_sun + z_ring) % n == 0


def phases(st: Stage) -> tuple[np.ndarray, np.ndarray]:
    """Mesh phases (mesh periods, relative to planet 1) of the sun-planet and ring-planet meshes."""
    psi = np.asarray(st.planet_angles, dtype=float) - st.planet_angles[0]
    g_s = np.mod(st.z_sun * psi / (2 * math.pi), 1.0)
    g_r = np.mod(-st.z_ring * psi / (2 * math.pi), 1.0)
    # whole numbers within rounding are 0 (in phase), not 0.9999999
    g_s[np.isclose(g_s, 1.0, atol=1e-9)] = 0.0
    g_r[np.isclose(g_r, 1.0, atol=1e-9)] = 0.0
    return g_s, g_r


MEMBERS = ("sun", "ring", "carrier")


def mesh_rows(st: Stage) -> tuple[np.ndarray, np.ndarray]:
    """The rows a_n, b_n (N x (3 + N), over [sun, ring, carrier, planet 1..N]) with the mesh deflections
    d_sn = a_n . q - e_n cos(alpha_ws) and d_rn = b_n . q - e_n cos(alpha_wr)."""
    rbs, rbp, rbr = st.radii[:3]
    n = st.n
    A, B = np.zeros((n, 3 + n)), np.zeros((n, 3 + n))
    for i in range(n):
        A[i, 0], A[i, 2], A[i, 3 + i] = rbs, -(rbs + rbp), rbp
        B[i, 1], B[i, 2], B[i, 3 + i] = rbr, -(rbr - rbp), -rbp
    return A, B


def matrices(st: Stage) -> tuple[np.ndarray, np.ndarray, list[str]]:
    """Mass and stiffness matrices over the free coordinates [sun, ring, carrier, planet 1..N]
    (fixed members removed) and the coordinate names."""
    R = st.radii[3]
    n = st.n
    names = [*MEMBERS, *(f"planet{i + 1}" for i in range(n))]
    M = np.diag([st.inertia_sun, st.inertia_ring, st.inertia_carrier + n * st.mass_planet * R ** 2,
                 *([st.inertia_planet] * n)])
    K = np.zeros((3 + n, 3 + n))
    A, B = mesh_rows(st)
    for a, b in zip(A, B):
        K += st.k_sun_planet * np.outer(a, a) + st.k_ring_planet * np.outer(b, b)
    keep = []
    for j, m in enumerate(MEMBERS):
        s = st.support.get(m, 0.0)
        if s == "fixed":
            continue
        K[j, j] += float(s)
        keep.append(j)
    keep += list(range(3, 3 + n))
    return M[np.ix_(keep, keep)], K[np.ix_(keep, keep)], [names[j] for j in keep]


def modes(st: Stage) -> tuple[np.ndarray, np.ndarray, list[str], list[str]]:
    """Natural frequencies (Hz, ascending, rigid-body modes at 0), mass-normalised shapes, the
    coordinate names, and each mode's type: "rotational" (the planets move alike), "planet" (the
    central members at rest, the planets' amplitudes summing to zero) or "mixed"."""
    from scipy.linalg import eigh

    M, K, names = matrices(st)
    w2, V = eigh(K, M)
    f = np.sqrt(np.clip(w2, 0.0, None)) / (2 * math.pi)
    planets = [i for i, nm in enumerate(names) if nm.startswith("planet")]
    central = [i for i, nm in enumerate(names) if not nm.startswith("planet")]
    kinds = []
    scale = np.abs(V).max(axis=0)
    for r in range(V.shape[1]):
        v = V[:, r] / scale[r]
        p = v[planets]
        if np.abs(v[central]).max(initial=0.0) < 1e-8 and abs(p.sum()) < 1e-8:
            kinds.append("planet")
        elif np.ptp(p) < 1e-8 * max(np.abs(p).max(), 1e-300) or np.abs(p).max() < 1e-12:
            kinds.append("rotational")
        else:
            kinds.append("mixed")
    return f, V, names, kinds


def load_sharing(st: Stage, torque: float, member: str = "sun") -> dict:
    """Static mesh forces with a torque (N m) on ``member``, the other members held or supported as
    given (the two others held for a stage in service), and the planets' position errors. Returns the sun-planet and ring-planet forces (N) per planet, each planet's share
    of the total and the load sharing factor K_gamma = largest sun-planet force / mean."""
    rbs, rbp, rbr, R = st.radii
    M, K, names = matrices(st)
    n = st.n
    e = st.errors()
    c_s, c_r = st.cosines
    full = len(MEMBERS) + n
    # the error terms: V contains 1/2 k (a.q - e c)^2, so the load vector gains k e c a
    f = np.zeros(full)
    f[MEMBERS.index(member)] = torque
    A, B = mesh_rows(st)
    for i in range(n):
        f += st.k_sun_planet * e[i] * c_s * A[i] + st.k_ring_planet * e[i] * c_r * B[i]
    keep = [MEMBERS.index(nm) if nm in MEMBERS else 3 + int(nm[6:]) - 1 for nm in names]
    q_free = np.linalg.solve(K, f[keep])
    q = np.zeros(full)
    q[keep] = q_free
    ths, thr, thc = q[0], q[1], q[2]
    thp = q[3:]
    d_s = rbs * (ths - thc) + rbp * (thp - thc) - e * c_s
    d_r = rbr * (thr - thc) - rbp * (thp - thc) - e * c_r
    F_s, F_r = st.k_sun_planet * d_s, st.k_ring_planet * d_r
    if F_s.sum() < 0:
        # the torque loads the other flanks (the carrier or ring drives the sun backwards in this
        # sign convention): forces on the loaded flanks are positive
        F_s, F_r = -F_s, -F_r
    mean = F_s.mean()
    return {"sun_planet_force": F_s, "ring_planet_force": F_r, "share": F_s / F_s.sum(),
            "load_sharing_factor": float(F_s.max() / mean) if mean > 0 else math.inf,
            "contact_lost": bool((F_s < 0).any() or (F_r < 0).any())}


def centre_distance(spec) -> float:
    """The stage's centre distance (m): given, else the sun-planet zero-backlash one (profile shifts)."""
    if spec.centre_distance is not None:
        return spec.centre_distance
    from ..rating.planetary import gears_of_spec, working_geometry

    return working_geometry(gears_of_spec(spec))["a_w"] * 1e-3


def stage_of(spec, support=None) -> Stage:
    """The Stage of a model's ``planetary`` section (SI)."""
    n = spec.planets
    psi = tuple(spec.planet_angles) if spec.planet_angles is not None else tuple(2 * math.pi * i / n for i in range(n))
    shifted = spec.centre_distance is not None or any(spec.profile_shifts) or spec.ring_teeth is not None
    # a helical stage in its transverse section (m_t, alpha_t): the mesh stiffnesses act along the
    # transverse lines of action; axial forces and tilting are not modelled
    c = math.cos(spec.helix_angle)
    return Stage(ring_teeth=spec.ring_teeth, centre_distance=centre_distance(spec) if shifted else None,
                 z_sun=spec.sun_teeth, z_planet=spec.planet_teeth, module=spec.module / c, planet_angles=psi,
                 k_sun_planet=spec.sun_planet_stiffness, k_ring_planet=spec.ring_planet_stiffness,
                 inertia_sun=spec.sun_inertia, inertia_ring=spec.ring_inertia, inertia_carrier=spec.carrier_inertia,
                 inertia_planet=spec.planet_inertia, mass_planet=spec.planet_mass,
                 pressure_angle=math.atan(math.tan(spec.pressure_angle) / c), position_errors=tuple(spec.position_errors),
                 support=support if support is not None else {spec.fixed: "fixed"})


#: what a stiffness matrix that double precision cannot solve says (its stiffnesses lie too far apart)
_SPREAD = ("its stiffnesses lie too far apart for double precision (mesh stiffnesses, supports and bearings "
           "within about 1e12 of one another solve)")


def analyse(spec, iso=None, where: str = "planetary", dynamics: tuple | None = None) -> tuple[dict, dict]:
    """Summary entry and arrays of a model's planetary stage: phasing, modes (the fixed member held),
    load sharing (the fixed member and the output held, the torque on the input); with ``lateral``
    the lateral-torsional modes and load sharing, with ``dynamics`` (the summary and arrays of the
    stage's time integration, planetary_dynamics.run: a run, not a check) its K_v, with ``rating`` the
    ISO rating of both meshes (``iso``: the model's [iso] section)."""
    lat = spec.lateral
    hold = lat.support_stiffness if lat is not None and lat.support_stiffness is not None else "fixed"
    st = stage_of(spec, support={spec.fixed: hold})
    rbs, rbp, rbr, R = st.radii
    g_s, g_r = phases(st)
    f, V, names, kinds = modes(st)
    rigid = f < 1e-6 * max(f.max(), 1e-300)
    f_planet = math.sqrt(rbp ** 2 * (st.k_sun_planet + st.k_ring_planet) / st.inertia_planet) / (2 * math.pi)
    output = next(m for m in MEMBERS if m not in (spec.fixed, spec.input))
    held = stage_of(spec, support={spec.fixed: hold, output: "fixed"})
    # the sun's share of the torques (T_s : T_r : T_c = 1 : z_r / z_s : -(1 + z_r / z_s), the stage in balance)
    t_sun = {"sun": spec.torque, "ring": spec.torque * st.z_sun / st.z_ring,
             "carrier": spec.torque * st.z_sun / (st.z_sun + st.z_ring)}[spec.input]
    from ...core.errors import ModelError

    if min(held.k_sun_planet, held.k_ring_planet) <= 1e-12 * max(held.k_sun_planet, held.k_ring_planet):
        # (a mesh of 1e-29 N/m beside 1e9: whether LAPACK then finds the stiffness matrix singular,
        # or solves it to noise, differed between two machines; said the same on every one)
        raise ModelError(f"the stage's load sharing cannot be solved: {_SPREAD}", field=where)
    try:
        ls = load_sharing(held, spec.torque, spec.input)
    except np.linalg.LinAlgError:      # a stiffness 1e-29 N/m beside 1e9: one line, not a traceback
        raise ModelError(f"the stage's load sharing cannot be solved: {_SPREAD}", field=where) from None
    summary = {
        "ring_teeth": st.z_ring, "planets": st.n, "planet_angles": [float(a) for a in st.planet_angles],
        "centre_distance": R, "output": output,
        "speed_ratio_input_over_output": _speed_ratio(st, spec.input, output),
        "equally_spaced_assembly": assembly_ok(st.z_sun, st.z_ring, st.n),
        "phase_sun_planet": [float(x) for x in g_s], "phase_ring_planet": [float(x) for x in g_r],
        "planets_in_phase": bool(np.allclose(g_s, 0.0) and np.allclose(g_r, 0.0)),
        "natural_frequencies_hz": [float(x) for x, r in zip(f, rigid) if not r],
        "mode_types": [k for k, r in zip(kinds, rigid) if not r],
        "planet_mode_frequency_closed_form_hz": f_planet if st.n > 1 else None,
        "torque_sun": t_sun,
        "sun_planet_force": [float(x) for x in ls["sun_planet_force"]],
        "ring_planet_force": [float(x) for x in ls["ring_planet_force"]],
        "load_share": [float(x) for x in ls["share"]],
        "load_sharing_factor": ls["load_sharing_factor"],
        "position_errors": [float(x) for x in st.errors()],
    }
    arrays = {"f": f[~rigid], "V": V[:, ~rigid], "names": names, "forces": ls}
    k_gamma = ls["load_sharing_factor"]
    if lat is not None:
        try:
            lsum, larr = _lateral(spec, st, output)
        except (ValueError, np.linalg.LinAlgError) as exc:     # a support of 1e29 N m/rad hid the others
            from ...core.errors import ModelError

            if isinstance(exc, ModelError):
                raise
            raise ModelError(f"{exc} (or {_SPREAD})", field=f"{where}.lateral") from None
        summary["lateral"] = lsum
        arrays["lateral"] = larr
        k_gamma = lsum["load_sharing_factor"]
    kv_run = None
    integrate = dynamics is not None
    if integrate:
        summary["dynamics"], arrays["dynamics"] = dynamics
        if spec.dynamics.rating_kv == "run":
            kv_run = (summary["dynamics"]["kv"]["sun-planet"], summary["dynamics"]["kv"]["ring-planet"])
    if spec.rating is not None and iso is not None:
        from ..rating.planetary import rate_spec

        summary["rating"] = rate_spec(spec, iso, k_gamma, t_sun, member_speeds(st, spec.fixed, spec.input,
                                                                               spec.rating.speed), where,
                                      kv_run=kv_run, integrated=integrate)
    return summary, arrays


def lateral_stage(spec, st: Stage, torsion: dict):
    """The planetary_lateral.LateralStage of a model's stage with its ``lateral`` data."""
    from .lateral import LateralStage

    lat = spec.lateral
    rbs, rbp, rbr, R = st.radii
    c_s, c_r = st.cosines
    rigid = lambda k: "fixed" if k is None else k       # noqa: E731
    return LateralStage(base_radius_sun=rbs, base_radius_planet=rbp, base_radius_ring=rbr, centre_distance=R,
                        alpha_sun=math.acos(c_s), alpha_ring=math.acos(c_r), planet_angles=st.planet_angles,
                        k_sun_planet=st.k_sun_planet, k_ring_planet=st.k_ring_planet,
                        k_planet_bearing=lat.planet_bearing_stiffness,
                        mass={"sun": lat.sun_mass, "ring": lat.ring_mass, "carrier": lat.carrier_mass,
                              "planet": st.mass_planet},
                        inertia={"sun": st.inertia_sun, "ring": st.inertia_ring, "carrier": st.inertia_carrier,
                                 "planet": st.inertia_planet},
                        bearing={"sun": lat.sun_bearing_stiffness, "ring": rigid(lat.ring_bearing_stiffness),
                                 "carrier": rigid(lat.carrier_bearing_stiffness)},
                        torsion=torsion, position_errors=st.position_errors)


def _lateral(spec, st: Stage, output: str) -> tuple[dict, dict]:
    """Lateral-torsional modes (the fixed member on its support) and load sharing (output held too)."""
    from . import lateral as pl

    lat = spec.lateral
    hold = "fixed" if lat.support_stiffness is None else lat.support_stiffness
    ls_ = lateral_stage(spec, st, {spec.fixed: hold})
    f, V, names, kinds = pl.modes(ls_)
    rigid = f < 1e-6 * max(f.max(), 1e-300)
    ls = pl.load_sharing(lateral_stage(spec, st, {spec.fixed: hold, output: "fixed"}), spec.torque, spec.input)
    counts = {k: sum(1 for kk, r in zip(kinds, rigid) if kk == k and not r)
              for k in ("rotational", "translational", "planet", "mixed")}
    out = {"floating_sun": lat.sun_bearing_stiffness == 0.0,
           "natural_frequencies_hz": [float(x) for x, r in zip(f, rigid) if not r],
           "mode_types": [k for k, r in zip(kinds, rigid) if not r], "mode_counts": counts,
           "sun_planet_force": [float(x) for x in ls["sun_planet_force"]],
           "ring_planet_force": [float(x) for x in ls["ring_planet_force"]],
           "pin_force_tangential": [float(x) for x in ls["pin_force_tangential"]],
           "load_share": [float(x) for x in ls["share"]], "load_sharing_factor": ls["load_sharing_factor"],
           "sun_displacement": [float(x) for x in ls["sun_displacement"]]}
    return out, {"f": f[~rigid], "V": V[:, ~rigid], "names": names, "forces": ls}


def member_speeds(st: Stage, fixed: str, inp: str, speed: float) -> dict:
    """Speeds (rad/s, one sense) of sun, ring and carrier with ``fixed`` at rest and ``inp`` at ``speed``
    (Willis: w_s - w_c = -(z_r / z_s)(w_r - w_c))."""
    zs, zr = st.z_sun, st.z_ring
    unit = {"ring": {"carrier": 1.0, "sun": 1.0 + zr / zs, "ring": 0.0},
            "carrier": {"carrier": 0.0, "sun": 1.0, "ring": -zs / zr},
            "sun": {"sun": 0.0, "carrier": 1.0, "ring": 1.0 + zs / zr}}[fixed]
    return {m: speed * w / unit[inp] for m, w in unit.items()}


def _speed_ratio(st: Stage, inp: str, out: str) -> float:
    """Input over output speed with the third member held (Willis: w_s - w_c = -(z_r / z_s)(w_r - w_c))."""
    zs, zr = st.z_sun, st.z_ring
    held = next(m for m in MEMBERS if m not in (inp, out))
    # speeds of (sun, ring, carrier) with the held member at 0 and a unit speed of a free one
    if held == "ring":
        w = {"carrier": 1.0, "sun": 1.0 + zr / zs, "ring": 0.0}
    elif held == "carrier":
        w = {"carrier": 0.0, "sun": 1.0, "ring": -zs / zr}
    else:
        w = {"sun": 0.0, "carrier": 1.0, "ring": 1.0 + zs / zr}
    return w[inp] / w[out]


def diagnose_stage(result, summary: dict, prefix: str = "planetary") -> None:
    """tooth-separation when a planet's static mesh force is negative, in the torsional or the
    lateral-torsional load sharing: that planet's teeth would lose contact (the linear load sharing
    does not hold)."""
    for key, what in (("", "torsional"), ("lateral", "lateral-torsional")):
        s = summary.get(key) if key else summary
        if not s:
            continue
        forces = s["sun_planet_force"] + s["ring_planet_force"]
        fmin = min(forces)
        if fmin < 0 or s["load_sharing_factor"] == math.inf:
            where = prefix + "." + (key + "." if key else "") + "sun_planet_force"
            result.diagnose("tooth-separation", f"{prefix} ({what} model): a planet's mesh force is negative "
                            f"({fmin:.4g} N) at the given torque and pin position errors: that planet's teeth would "
                            "lose contact (the linear load sharing does not hold)", where, fmin, 0.0, "N")
    d = summary.get("dynamics")
    if d:
        fmin = min(d["force_min_sun_planet"] + d["force_min_ring_planet"])
        if fmin < 0:
            result.diagnose("tooth-separation", f"{prefix} (time integration at {d['speed']:.6g} rad/s): a mesh force "
                            f"goes negative ({fmin:.4g} N) in the window: the teeth would separate, the linear model "
                            "keeps them in mesh (its K_v does not hold)", f"{prefix}.dynamics.force_min_sun_planet",
                            fmin, 0.0, "N")
        if d["window_growth"] is not None and d["window_growth"] > 1.1:
            result.diagnose("kv-unstable", f"{prefix} (time integration at {d['speed']:.6g} rad/s): the mesh forces "
                            f"grow over the window (second half's range {d['window_growth']:.3g} x the first's): a "
                            "parametric instability or a start-up transient left; K_v does not hold",
                            f"{prefix}.dynamics.window_growth", d["window_growth"], 1.1, "1")


PLANETARY_UNITS = {"planetary.dynamics.speed": "rad/s", "planetary.dynamics.*_hz": "Hz",
                   "planetary.dynamics.step": "s", "planetary.dynamics.settle": "s", "planetary.dynamics.wall_time": "s",
                   "planetary.dynamics.force_*": "N", "planetary.dynamics.damping.*": "N*s/m",
                   "planetary.dynamics.sweep.speed_*": "rad/s", "planetary.dynamics.sweep.diverged_speeds": "rad/s",
                   "planetary.dynamics.sweep.mesh_hz_per_rad_s": "Hz*s/rad", "planetary.dynamics.*": "1",
                   "planetary.rating.meshes.*.K_v*": "1",
                   "planetary.lateral.natural_frequencies_hz": "Hz", "planetary.lateral.*_force": "N",
                   "planetary.lateral.sun_displacement": "m", "planetary.lateral.*": "1",
                   "planetary.rating.meshes.*.*.sigma_*": "Pa", "planetary.rating.meshes.*.reduced_mass": "kg/m",
                   "planetary.rating.meshes.*.resonance_speed_rpm": "rpm", "planetary.rating.meshes.*.iso_c_*": "N/m^2",
                   "planetary.rating.meshes.*.working_pressure_angle": "rad", "planetary.rating.*": "1",
                   "planetary.planet_angles": "rad", "planetary.centre_distance": "m",
                   "planetary.natural_frequencies_hz": "Hz", "planetary.planet_mode_frequency_closed_form_hz": "Hz",
                   "planetary.torque_sun": "N*m", "planetary.*_force": "N", "planetary.position_errors": "m",
                   "planetary.*": "1"}
# further stages of a gearbox ("stages.stage2.", ...) have the first one's units; the gearbox's modes
PLANETARY_UNITS.update({k.replace("planetary.", "stages.*.", 1): v for k, v in list(PLANETARY_UNITS.items())})
PLANETARY_UNITS.update({"gearbox.natural_frequencies_hz": "Hz", "gearbox.*": "1"})


def report_lines(spec, iso=None, where: str = "planetary") -> list[str]:
    """The ``check`` text of a planetary stage (``where``: its field, for a refusal's line)."""
    s, _ = analyse(spec, iso, where)
    out = ["", f"planetary stage: sun {spec.sun_teeth}, planets {spec.planet_teeth} x {spec.planets}, ring {s['ring_teeth']} "
               f"teeth, module {spec.module * 1e3:g} mm"
               + (f", helix {math.degrees(spec.helix_angle):g} deg" if spec.helix_angle else "")
               + f", centre distance {s['centre_distance'] * 1e3:.3f} mm; "
               f"{spec.input} in, {s['output']} out, {spec.fixed} fixed: speed ratio {s['speed_ratio_input_over_output']:.5g}",
           f"  mesh phases (periods, planet 1 = 0): sun-planet {[round(x, 4) for x in s['phase_sun_planet']]}, "
           f"ring-planet {[round(x, 4) for x in s['phase_ring_planet']]}"
           + (" (in phase)" if s["planets_in_phase"] else ""),
           f"  natural frequencies ({spec.fixed} held): "
           + ", ".join(f"{f:.1f} Hz {k}" for f, k in zip(s["natural_frequencies_hz"], s["mode_types"]))
           + (f"; planet modes by the closed form {s['planet_mode_frequency_closed_form_hz']:.1f} Hz"
              if s["planet_mode_frequency_closed_form_hz"] else ""),
           f"  load sharing ({spec.torque:g} N m on the {spec.input}, {s['output']} held): sun-planet forces "
           + ", ".join(f"{x:.1f}" for x in s["sun_planet_force"]) + f" N, K_gamma {s['load_sharing_factor']:.4f}"]
    if "lateral" in s:
        la = s["lateral"]
        out += [f"  lateral-torsional model (Lin & Parker 1999){', floating sun' if la['floating_sun'] else ''}: "
                + ", ".join(f"{n} {k}" for k, n in la["mode_counts"].items() if n) + " modes; "
                + ", ".join(f"{f:.1f} Hz {k[:5]}" for f, k in zip(la["natural_frequencies_hz"], la["mode_types"])),
                "  load sharing (lateral-torsional): sun-planet forces " + ", ".join(f"{x:.1f}" for x in la["sun_planet_force"])
                + f" N, K_gamma {la['load_sharing_factor']:.4f} (torsional model: {s['load_sharing_factor']:.4f})"]
    if spec.dynamics is not None:
        d = spec.dynamics
        out.append(f"  time integration ([dynamics], {d.stiffness_model} mesh stiffness, damping ratio {d.damping_ratio:g}): "
                   + ("`drivedyn run` integrates the lateral-torsional model" if d.model == "lateral"
                      else "`drivedyn run` integrates the torsional model") + " for K_v of every mesh"
                   + (" and sweeps the speed" if d.sweep else "")
                   + ("; the rating then takes K_v from the run (below: method B)"
                      if d.rating_kv == "run" and spec.rating is not None and spec.rating.dynamic_factors is None else ""))
    if "rating" in s:
        r = s["rating"]
        out.append(f"  ISO 6336 rating, K_gamma {r['K_gamma']:.4f} ({r['K_gamma_source']}); load cycles "
                   + ", ".join(f"{k} {v:.4g}" for k, v in r["load_cycles"].items()))
        for name, e in r["meshes"].items():
            out.append(f"    {name}: alpha_w {math.degrees(e['working_pressure_angle']):.3f} deg, eps_alpha {e['contact_ratio']:.4f}, "
                       f"K_v {e['K_v']:.4f} ({e['K_v_source']}), Z_H {e['Z_H']:.4f}, Z_eps {e['Z_eps']:.4f}, {e['verdict']}")
            for gear in (e["pinion"], e["wheel"]):
                g = e[gear]
                sf = "not rated" if g["S_F"] is None else f"{g['S_F']:.3f} (Y_F {g['Y_F']:.4f}, Y_S {g['Y_S']:.4f}, Y_M {g['Y_M']:g})"
                out.append(f"      {gear:7s}: sigma_H {g['sigma_H'] / 1e6:.1f} N/mm^2, S_H {g['S_H']:.3f} (Z_NT {g['Z_NT']:.3f}, "
                           f"Z_W {g['Z_W']:.3f}); S_F {sf}; {g['load_cycles']:.4g} cycles")
            out += [f"      note: {n}" for n in e["notes"]]
    return out
