"""Time integration of a planetary stage with time-varying mesh stiffness: K_v of every sun-planet and
ring-planet mesh at the operating speed and, optionally, against speed.

Model: the lumped torsional model of ``planetary`` (absolute rotations of sun, ring, carrier and
planets, the held member removed or on its torsional support; the rotational part of Lin & Parker,
J. Vib. Acoust. 121 (1999) 316-321), with each mean mesh stiffness replaced by the time-varying one of
a gear train's mesh (``stiffness.build``: Cai's parabola, the rectangular wave or a constant, about
the stage's given mean) and viscous mesh damping c = 2 zeta sqrt(k m_a m_b / (m_a + m_b)), m = J / r_b^2
of the mesh's two gears (as a train's mesh; a held member's m infinite). The lateral (translational)
degrees of freedom are integrated with ``model = "lateral"``: the lateral-torsional model of
``planetary_lateral`` (Lin & Parker's coordinates, the pin errors in the pins' springs, the carrier's
rotation terms left out, the mesh positions from the rotations; ``_lateral_arrays``).

Mesh positions (mesh periods, frac taken), in the carrier's frame as the planets' positions dictate:

    sun-planet n:   u_sn = z_s (th_s - th_c) / 2 pi - gamma_sn
    ring-planet n:  u_rn = -z_p (th_n - th_c) / 2 pi + u_rs - gamma_rn

with gamma_sn, gamma_rn the phases of the counting rule (``planetary.phases``; Parker & Lin,
J. Mech. Des. 126 (2004) 365-370) and u_rs the phase of a planet's ring mesh against its sun mesh. Each
mesh's position is 0 where a tooth pair enters contact (A, at the driving gear's root: the sun's in the
sun mesh, the planet's in the ring mesh) and s_C = (T1C - T1A) / p_b where a pair passes the pitch
point. A pair is at the sun mesh's pitch point when a planet tooth's centre line lies the half tooth
angle phi_s (at the planet's working pitch circle of that mesh) past the line of centres on the sun
side, and at the ring mesh's when one lies phi_r before it on the ring side, half a turn away:

    u_rs = s_Cr - s_Cs - z_p (pi - phi_s - phi_r) / 2 pi,
    phi = (pi/2 + 2 x_p tan alpha_n) / z_p + inv alpha_t - inv alpha_w     (ISO 21771 tooth thickness)

For standard gears (phi = pi / 2 z_p) the pitch-point passages of a planet's two meshes are in phase
for an odd z_p and half a period apart for an even one. A stage whose static forces load the other
flanks (the carrier or the ring driving the sun) is integrated as its mirror image (every rotation,
torque and pin error negated), which loads the flanks above; the stiffness shapes are symmetric in
their contact (s -> eps - s), so running a mesh backwards changes nothing else.

K_v of a mesh separates the dynamic response from the quasi-static shift of load between the planets
(a stage of several planets is statically indeterminate: with the sun held on its axis, a planet whose
meshes are momentarily stiffer takes more of the torque). At every step of the window (``window_cycles``
mesh periods after ``settle``, started in static equilibrium at the start position) the quasi-static
mesh forces are the static solution with that instant's mesh stiffnesses (a linear solve); then

    K_v                  = largest mesh force / largest quasi-static force of that mesh
    quasi-static share   = largest over the window of (quasi-static force / mean quasi-static force of the
                           planets' meshes of that kind): a time-varying K_gamma (with the pin errors)

so K_v tends to 1 far below the modes with a smooth stiffness, and for one planet (the quasi-static force
constant) it is a train's K_v. The largest force over the static force with the mean stiffnesses (K_v
before the separation) is reported too, as ``force_max_over_nominal_*``.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from ...core.errors import ModelError
from . import stage as tors
from ..mesh import stiffness

MODEL_TEXT = {"torsional": "torsional (Lin & Parker 1999, rotational part) with time-varying mesh stiffness",
              "lateral": "lateral-torsional (Lin & Parker 1999, without the carrier's rotation terms) with "
                         "time-varying mesh stiffness"}


@dataclass(frozen=True)
class MeshGeometry:
    """What ``stiffness.build`` reads of a mesh (m): positions along the line of action from the driving
    gear's tangent point T1."""

    contact_ratio: float
    overlap_ratio: float
    base_pitch: float
    rho_start: float
    rho_end: float
    rho_pitch: float
    tangent_length: float


def mesh_geometry(spec, where: str = "planetary") -> tuple[MeshGeometry, MeshGeometry, float]:
    """Geometry of the sun-planet (sun driving) and ring-planet (planet driving) meshes, and the phase
    u_rs (mesh periods) of a planet's ring mesh against its sun mesh (module docstring)."""
    from ..mesh.geometry import inv
    from ..rating.planetary import gears_of_spec, working_geometry

    sg = gears_of_spec(spec)
    wg = working_geometry(sg, where)
    g = sg.diameters()
    rb = [0.5e-3 * d for d in g["db"]]
    ra = [0.5e-3 * d for d in g["da"]]
    a = wg["a_w"] * 1e-3
    a_ws, a_wr = wg["alpha_w_sun"], wg["alpha_w_ring"]
    m_t, a_t = sg.transverse
    p_b = math.pi * m_t * 1e-3 * math.cos(a_t)
    b = spec.rating.face_width if spec.rating is not None else 0.0
    eps_b = b * math.sin(spec.helix_angle) / (math.pi * spec.module)
    for k, gear in enumerate(("sun", "planet", "ring")):
        if not ra[k] > rb[k]:
            raise ModelError(f"the {gear}'s tip diameter {2e3 * ra[k]:.6g} mm is not outside its base circle "
                             f"({2e3 * rb[k]:.6g} mm)", field=f"{where}.dynamics")
    t_s = a * math.sin(a_ws)
    sun = MeshGeometry(contact_ratio=0.0, overlap_ratio=eps_b, base_pitch=p_b,
                       rho_start=t_s - math.sqrt(ra[1] ** 2 - rb[1] ** 2), rho_end=math.sqrt(ra[0] ** 2 - rb[0] ** 2),
                       rho_pitch=rb[0] * math.tan(a_ws), tangent_length=t_s)
    # internal mesh: the ring's tangent point T2 lies behind the planet's T1 (T2 T1 = a sin alpha_wr), the
    # contact runs from the ring's tip (rho_A) outwards to the planet's tip
    t_r = a * math.sin(a_wr)
    ring = MeshGeometry(contact_ratio=0.0, overlap_ratio=eps_b, base_pitch=p_b,
                        rho_start=math.sqrt(ra[2] ** 2 - rb[2] ** 2) - t_r, rho_end=math.sqrt(ra[1] ** 2 - rb[1] ** 2),
                        rho_pitch=rb[1] * math.tan(a_wr), tangent_length=t_r)
    out = []
    for name, m in (("sun-planet", sun), ("ring-planet", ring)):
        if m.rho_start < 0:
            raise ModelError(f"the {name} mesh's contact would start inside the driving gear's base circle (tip "
                             f"interference, T1A = {m.rho_start * 1e3:.4g} mm)", field=f"{where}.dynamics")
        eps = (m.rho_end - m.rho_start) / p_b
        if not 1.0 <= eps < 4.0:
            raise ModelError(f"the {name} mesh's transverse contact ratio is {eps:.4g} (the time-varying stiffness "
                             "needs 1 to 4)", field=f"{where}.dynamics")
        out.append(MeshGeometry(**{**m.__dict__, "contact_ratio": eps}))
    zp, xp = spec.planet_teeth, spec.profile_shifts[1]

    def half_angle(alpha_w):
        return (0.5 * math.pi + 2 * xp * math.tan(spec.pressure_angle)) / zp + inv(a_t) - inv(alpha_w)

    s_cs = (out[0].rho_pitch - out[0].rho_start) / p_b
    s_cr = (out[1].rho_pitch - out[1].rho_start) / p_b
    u_rs = (s_cr - s_cs - zp * (math.pi - half_angle(a_ws) - half_angle(a_wr)) / (2 * math.pi)) % 1.0
    return out[0], out[1], u_rs


@dataclass
class StageSystem:
    """The stage's arrays for the kernels (SI; coordinates as ``planetary.matrices``)."""

    names: list
    M: np.ndarray            # diagonal masses (n): inertias, or masses and J / r^2 of the lateral model
    K_const: np.ndarray      # constant stiffness matrix (n x n): supports, and the lateral model's bearings and pins
    G: np.ndarray            # mesh rows (m x n): sun-planet 1..N, then ring-planet 1..N
    H: np.ndarray            # mesh position rows (m x n)
    offset: np.ndarray       # m
    phase: np.ndarray        # m
    tables: list             # stiffness.MeshTable, sun-planet then ring-planet
    damping: np.ndarray      # m
    load: np.ndarray         # n (constant generalised forces, balanced: torques, the constant springs' offsets)
    phi: np.ndarray          # n, speeds per unit input speed
    mirrored: bool
    mesh_names: list
    u_rs: float
    z_sun: int
    planets: int
    contact_ratio: tuple = (math.nan, math.nan)     # sun-planet, ring-planet
    model: str = "torsional"                         # or "lateral"

    @property
    def kt(self) -> np.ndarray:
        return np.array([t.stiffness for t in self.tables])

    def k_mean(self) -> np.ndarray:
        return np.array([t.mean for t in self.tables])

    def stiffness(self, k_mesh=None) -> np.ndarray:
        k = self.k_mean() if k_mesh is None else np.asarray(k_mesh)
        return (self.G.T * k) @ self.G + self.K_const

    def mesh_frequency(self, omega_in: float) -> float:
        """Mesh frequency (Hz) at input speed ``omega_in``: z_s |w_s - w_c| / 2 pi."""
        return abs(self.H[0] @ self.phi) * omega_in / (2 * math.pi)

    def modes(self):
        """Natural frequencies (Hz, rigid-body modes removed) and modal damping ratios (mean stiffness)."""
        from scipy.linalg import eigh

        K = self.stiffness()
        C = (self.G.T * self.damping) @ self.G
        lam, V = eigh(K, np.diag(self.M))
        keep = lam > 1e-9 * max(abs(lam).max(), 1.0)
        w = np.sqrt(lam[keep])
        V = V[:, keep]
        zeta = np.array([V[:, r] @ C @ V[:, r] / (2 * w[r]) for r in range(len(w))])
        return w / (2 * math.pi), zeta

    def static(self, k_mesh=None) -> tuple[np.ndarray, np.ndarray]:
        """Static coordinates (rigid-body part removed) and mesh forces with the mesh stiffnesses ``k_mesh``
        (default the means)."""
        k = self.k_mean() if k_mesh is None else np.asarray(k_mesh)
        K = self.stiffness(k)
        f = self.load - self.G.T @ (k * self.offset)
        q = np.linalg.lstsq(K, f, rcond=None)[0]
        # the torques are balanced: remove the rigid-body rotation (M-orthogonal), which no spring feels
        phi, M = self.phi, self.M
        q -= phi * (phi @ (M * q)) / (phi @ (M * phi))
        return q, k * (self.G @ q + self.offset)

    def stiffness_at(self, q) -> np.ndarray:
        """Mesh stiffnesses (N/m) at coordinates q by the tables."""
        kt = self.kt
        N = kt.shape[1]
        u = (self.H @ q / (2 * math.pi) + self.phase) % 1.0
        x = u * N
        i0 = np.minimum(x.astype(int), N - 1)
        w = x - i0
        rows = np.arange(len(u))
        return kt[rows, i0] * (1 - w) + kt[rows, (i0 + 1) % N] * w

    def static_start(self) -> np.ndarray:
        """Deflections in static equilibrium with the stiffness at the start position."""
        q, _ = self.static()
        for _ in range(3):
            q, _ = self.static(self.stiffness_at(q))
        return q


@dataclass(frozen=True)
class _Shape:
    """What ``stiffness.build`` reads of a mesh's stiffness spec (as model.Stiffness, without importing
    the model file's module: it imports this package's modules back)."""

    model: str
    mean: float
    engagement: float
    single: None = None
    double: None = None


def system(spec, where: str = "planetary", omega_low: float | None = None) -> StageSystem:
    """The StageSystem of a model's stage with its ``dynamics`` data; ``omega_low`` the lowest input speed
    that will be run (sizes the stiffness tables)."""
    dyn = spec.dynamics
    lat = spec.lateral
    hold = lat.support_stiffness if lat is not None and lat.support_stiffness is not None else "fixed"
    st = tors.stage_of(spec, support={spec.fixed: hold})
    M, _, names = tors.matrices(st)
    keep = [tors.MEMBERS.index(nm) if nm in tors.MEMBERS else 3 + int(nm[6:]) - 1 for nm in names]
    n, N = len(names), st.n
    rbs, rbp, rbr = st.radii[:3]
    c_s, c_r = st.cosines
    A, B = tors.mesh_rows(st)
    e = st.errors()
    G = np.vstack([A, B])[:, keep]
    zs, zp = st.z_sun, st.z_planet
    Hf = np.zeros((2 * N, 3 + N))
    Hf[:N, 0], Hf[:N, 2] = zs, -zs
    for i in range(N):
        Hf[N + i, 3 + i], Hf[N + i, 2] = -zp, zp
    H = Hf[:, keep]
    offset = np.concatenate([-e * c_s, -e * c_r])
    ksup = np.zeros(n)
    for j, nm in enumerate(names):
        s = st.support.get(nm, 0.0)
        if nm in tors.MEMBERS and s != "fixed":
            ksup[j] = float(s)
    sun_geo, ring_geo, u_rs = mesh_geometry(spec, where)
    g_s, g_r = tors.phases(st)
    phase = np.concatenate([(-g_s) % 1.0, (u_rs - g_r) % 1.0])
    # rigid-body speeds per unit input speed: members by Willis, planets rolling on the sun
    w = tors.member_speeds(st, spec.fixed, spec.input, 1.0)
    wp = w["carrier"] - rbs / rbp * (w["sun"] - w["carrier"])
    phi_full = np.array([w["sun"], w["ring"], w["carrier"], *([wp] * N)])
    phi = phi_full[keep]
    output = next(m for m in tors.MEMBERS if m not in (spec.fixed, spec.input))
    torque = np.zeros(n)
    torque[names.index(spec.input)] = spec.torque
    torque[names.index(output)] = -spec.torque * phi[names.index(spec.input)] / phi[names.index(output)]
    held = {m: m not in names for m in tors.MEMBERS}
    masses, K_const, load = np.diag(M).copy(), np.diag(ksup), torque
    if dyn.model == "lateral":
        # the lateral-torsional model: the pin errors act in the pins' springs, not in the meshes
        names, masses, K_const, pins, G, H, phi, load = _lateral_arrays(spec, st, hold, output)
        load = load + pins
        offset = np.zeros(2 * N)
    # tables: at least N_TABLE points a period; a cell shorter than 1/64 of the highest mode's period
    # at the lowest speed run (a stiffness jump stays a jump for the dynamics), as a train's tables
    m_eq = {"sun": st.inertia_sun / rbs ** 2 if not held["sun"] else math.inf,       # a held member: infinite
            "ring": st.inertia_ring / rbr ** 2 if not held["ring"] else math.inf}
    m_p = st.inertia_planet / rbp ** 2
    tables, damping = [], []
    tmp = StageSystem(names=names, M=masses, K_const=K_const, G=G, H=H, offset=offset, phase=phase,
                      tables=[stiffness.MeshTable(*(None,) * 7, mean=k) for k in
                              [st.k_sun_planet] * N + [st.k_ring_planet] * N],
                      damping=np.zeros(2 * N), load=load, phi=phi, mirrored=False, mesh_names=[], u_rs=u_rs,
                      z_sun=zs, planets=N)
    f_hi = 1.3 * tmp.modes()[0].max(initial=1.0)
    w_low = omega_low if omega_low is not None else (dyn.speed or spec.rating.speed)
    t_mesh = 1.0 / max(tmp.mesh_frequency(w_low), 1e-300)
    n_tab = int(min(max(stiffness.N_TABLE, math.ceil(64 * t_mesh * f_hi)), 2 ** 18))
    for k, geo, m_a, m_b, name in ((st.k_sun_planet, sun_geo, m_eq["sun"], m_p, "sun_planet_stiffness"),
                                   (st.k_ring_planet, ring_geo, m_p, m_eq["ring"], "ring_planet_stiffness")):
        spec_k = _Shape(model=dyn.stiffness_model, mean=k, engagement=dyn.engagement)
        try:
            tab = stiffness.build(geo, spec_k, 0.0, 0.0, b=1.0, n_table=n_tab)
        except ValueError as exc:
            raise ModelError(str(exc), field=f"{where}.dynamics.stiffness_model") from None
        tables += [tab] * N
        m_red = m_a * m_b / (m_a + m_b) if math.isfinite(m_a) and math.isfinite(m_b) else min(m_a, m_b)
        damping += [2 * dyn.damping_ratio * math.sqrt(tab.mean * m_red)] * N
    sys_ = StageSystem(names=names, M=masses, K_const=K_const, G=G, H=H, offset=offset, phase=phase,
                       tables=tables, damping=np.array(damping), load=load, phi=phi, mirrored=False,
                       mesh_names=[f"sun-planet{i + 1}" for i in range(N)] + [f"ring-planet{i + 1}" for i in range(N)],
                       u_rs=u_rs, z_sun=zs, planets=N, contact_ratio=(sun_geo.contact_ratio, ring_geo.contact_ratio),
                       model=dyn.model)
    _, f = sys_.static()
    if f[:N].sum() < 0:
        # the other flanks carry the load: integrate the mirror image (module docstring)
        sys_.load, sys_.phi, sys_.offset, sys_.mirrored = -load, -phi, -offset, True
    return sys_


def _lateral_arrays(spec, st, hold, output):
    """The lateral-torsional model's arrays (``planetary_lateral``: Lin & Parker 1999, the carrier's
    rotation terms left out) over its kept coordinates: names, masses, the constant stiffness matrix (pins,
    bearings, the held member's support), the load of the constant springs' offsets (the pin errors), the
    mesh rows G (sun-planet 1..N, then ring-planet 1..N), the mesh position rows H, the rigid-body motion
    phi per unit input speed, and the torques' generalised forces per unit torque on the input."""
    from . import lateral as pl

    lst = tors.lateral_stage(spec, st, {spec.fixed: hold})
    M, _, names = pl.matrices(lst)
    keep = pl._kept(lst)
    N = st.n
    size = 9 + 3 * N
    K_const, load = np.zeros((size, size)), np.zeros(size)
    G = np.zeros((2 * N, size))
    for kind, who, k, g, off in pl._springs(lst):
        if kind == "sun-planet":
            G[who] = g
        elif kind == "ring-planet":
            G[N + who] = g
        else:
            K_const += k * np.outer(g, g)
            load -= k * off * g                     # 1/2 k (g.q + off)^2 loads the coordinates by -k off g
    rbs, rbp, rbr, R = st.radii
    r = {"sun": rbs, "ring": rbr, "carrier": R}
    col = {nm: i for i, nm in enumerate(pl.coordinate_names(N))}
    H = np.zeros((2 * N, size))
    H[:N, col["sun.u"]] = st.z_sun / rbs
    H[:N, col["carrier.u"]] = -st.z_sun / R
    for i in range(N):
        H[N + i, col[f"planet{i + 1}.u"]] = -st.z_planet / rbp
        H[N + i, col["carrier.u"]] = st.z_planet / R
    w = tors.member_speeds(st, spec.fixed, spec.input, 1.0)
    wp = w["carrier"] - rbs / rbp * (w["sun"] - w["carrier"])
    phi = np.zeros(size)
    for m_ in tors.MEMBERS:
        phi[col[f"{m_}.u"]] = r[m_] * w[m_]
    for i in range(N):
        phi[col[f"planet{i + 1}.eta"]] = R * w["carrier"]
        phi[col[f"planet{i + 1}.u"]] = rbp * wp
    torque = np.zeros(size)
    torque[col[f"{spec.input}.u"]] = spec.torque / r[spec.input]
    # the output's torque balances the input's power: T_out w_out = -T_in w_in, generalised force T / r
    torque[col[f"{output}.u"]] = -spec.torque * w[spec.input] / w[output] / r[output]
    return (names, np.diag(M).copy(), K_const[np.ix_(keep, keep)], load[keep], G[:, keep], H[:, keep],
            phi[keep], torque[keep])

def params(sys_: StageSystem) -> tuple:
    """The kernel parameter tuple (order: see ``_stage_kernels``)."""
    w = sys_.M * sys_.phi
    s_reg = float(np.diag(sys_.stiffness()).mean() / (w @ w))
    return (1.0 / sys_.M, sys_.load.astype(float), np.ascontiguousarray(sys_.K_const, dtype=float),
            np.ascontiguousarray(sys_.G), sys_.offset.astype(float), np.ascontiguousarray(sys_.H),
            sys_.phase.astype(float), sys_.kt, sys_.damping.astype(float), w.astype(float), s_reg)


def _timing(sys_: StageSystem, dyn, speeds, f_hi, settle):
    fm = np.array([sys_.mesh_frequency(w) for w in speeds])
    h_max = dyn.step if dyn.step is not None else 1.0 / (20.0 * f_hi)
    h = np.minimum(h_max, 1.0 / (fm * dyn.steps_per_cycle))
    # as floats: a speed of 1e-29 rpm asks for 1e31 steps, past int64 (it came back negative); the
    # counts are checked against the limits (_cost) before they become the kernel's integers
    with np.errstate(over="ignore", divide="ignore"):
        n_settle = np.ceil(np.maximum(settle, 20.0 / fm) / h)
        n_window = np.ceil(dyn.window_cycles / fm / h)
    return fm, h, n_settle, n_window


def solvable(sys_: StageSystem, p: tuple, where: str) -> None:
    """Refuse, before the integration, a stage whose quasi-static solve double precision cannot do:
    the kernel factors Ks + sum_j k_j G_j G_j^T + s_reg w w^T at every step (Cholesky), which is at
    least its value at each mesh's least stiffness; scaled to a unit diagonal, its condition number
    must stay below 1e12 (a 1e-29 N/m sun mesh beside 5e8 divided by zero in the kernel)."""
    from .stage import _SPREAD

    w, s_reg = p[-2], p[-1]
    A = sys_.stiffness(sys_.kt.min(axis=1)) + s_reg * np.outer(w, w)
    d = np.diag(A)
    cond = math.inf
    if np.all(np.isfinite(A)) and np.all(d > 0):
        scale = 1.0 / np.sqrt(d)
        with np.errstate(all="ignore"):
            cond = float(np.linalg.cond(A * np.outer(scale, scale)))
    if not cond < 1e12:
        raise ModelError(f"the stage's time integration cannot be solved (condition number {cond:.3g} of its "
                         f"stiffness matrix): {_SPREAD}", field=f"{where}.dynamics")


#: a force range in the window below this share of the force is the integration's round-off (K_v is
#: 1 to that many digits): no growth is read from it (a constant stiffness gave K_v = 1 + 2e-10 and a
#: "growth" of 1.27, the ratio of two round-off ranges)
ROUND_OFF = 1e-9


def window_growth(halves) -> np.ndarray:
    """Per mesh, the second half's force range over the first half's (halves: m x 4, max and min of
    each half), NaN where both ranges are round-off beside the force (ROUND_OFF)."""
    first, second = halves[:, 0] - halves[:, 1], halves[:, 2] - halves[:, 3]
    size = np.abs(halves).max(axis=1)
    real = np.maximum(first, second) > ROUND_OFF * size
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(real, second / first, np.nan)


def _cost(steps: float, nbytes: float, h, ns, nw, where: str) -> None:
    """The run's steps (its own settle and window, and the sweep's) and bytes against the limits."""
    from ...core.limits import bytes_problem, steps_problem

    fix = ("a higher dynamics.speed (the window is window_cycles mesh periods), a longer dynamics.step, fewer "
           "steps_per_cycle or window_cycles, a shorter settle or a smaller sweep count")
    what = (f"{where}.dynamics: a step of {float(h[0]):.3g} s over {float(ns[0]):.3g} settling and "
            f"{float(nw[0]):.3g} window steps")
    problem = (steps_problem(steps if math.isfinite(steps) else math.inf, what, fix)
               or bytes_problem(nbytes if math.isfinite(nbytes) else math.inf, what, fix))
    if not problem and not steps < 2.0 ** 62:     # DRIVEDYN_MAX_STEPS = inf: still no count a kernel can take
        problem = f"{what}: {steps:.3g} integration steps, more than any run can take ({fix})"
    if problem:
        raise ModelError(problem)


def speed_range(sys_: StageSystem, dyn, f_hi: float) -> tuple[float, float]:
    """Default sweep range: up to 1.3 x the speed where the mesh frequency meets the highest mode."""
    hi = dyn.speed_max or 1.3 * f_hi / sys_.mesh_frequency(1.0)
    lo = dyn.speed_min or hi / 100.0
    return lo, hi


def run(spec, where: str = "planetary", progress=None) -> tuple[dict, dict]:
    """K_v of every mesh at the operating speed (and with ``sweep`` against speed): summary entry and
    arrays."""
    from . import _kernels as kern

    t0 = time.perf_counter()
    dyn = spec.dynamics
    omega = dyn.speed or spec.rating.speed
    probe = system(spec, where, omega)
    freqs, zeta = probe.modes()
    f_top = freqs.max(initial=1.0)
    lo = omega
    if dyn.sweep:
        lo = min(omega, speed_range(probe, dyn, f_top)[0])
    sys_ = system(spec, where, lo) if lo < omega else probe
    decay = 1.0 / np.maximum(zeta * 2 * math.pi * freqs, 1e-12)
    settle = dyn.settle if dyn.settle is not None else float(min(5 * decay.max(initial=0.0), 0.5))
    f_hi = 1.3 * f_top          # the stiffness peaks raise the frequencies: a step for the stiffest instant
    p = params(sys_)
    solvable(sys_, p, where)
    fm, h, ns, nw = _timing(sys_, dyn, [omega], f_hi, settle)
    N = sys_.planets
    m = 2 * N
    steps, nbytes = float(ns[0] + nw[0]), 3 * 2 * 8 * m * float(nw[0])
    if dyn.sweep:
        lo_s, hi_s = speed_range(sys_, dyn, f_top)
        speeds = np.linspace(lo_s, hi_s, dyn.count)
        _, hs, nss, nws = _timing(sys_, dyn, speeds, f_hi, settle)
        steps += float(np.sum(nss + nws))
    _cost(steps, nbytes, h, ns, nw, where)
    if dyn.sweep:
        nss, nws = nss.astype(np.int64), nws.astype(np.int64)
    q0 = sys_.static_start()
    _, F = sys_.static()
    y = np.concatenate([q0, sys_.phi * omega])
    fmax, fmin, fmean, halves, qs = np.zeros(m), np.zeros(m), np.zeros(m), np.zeros((m, 4)), np.zeros((m, 4))
    out_f, out_q = np.zeros((int(nw[0]), m)), np.zeros((int(nw[0]), m))
    if progress:
        progress(0.1, "planetary stage: time integration")
    kern.run(y, float(h[0]), int(ns[0]), int(nw[0]), params(sys_), fmax, fmin, fmean, halves, qs, out_f, out_q)
    if not np.all(np.isfinite(fmax)):
        raise ModelError("the stage's time integration diverged (the state stopped being finite): a step too large "
                         "for its modes, or a parametric instability of the linear model; give a smaller "
                         "dynamics.step", field=f"{where}.dynamics")
    kv = fmax / qs[:, 0]
    shift = qs[:, 0] / F
    growth = window_growth(halves)

    def per(x):
        return [float(v) for v in x[:N]], [float(v) for v in x[N:]]

    def both(x):
        return {"sun-planet": float(x[:N].max()), "ring-planet": float(x[N:].max())}

    summary = {
        "model": MODEL_TEXT[sys_.model],
        "stiffness_model": dyn.stiffness_model, "speed": float(omega), "mesh_frequency_hz": float(fm[0]),
        "step": float(h[0]), "settle": float(ns[0] * h[0]), "window_cycles": dyn.window_cycles,
        "damping": {"sun-planet": float(sys_.damping[0]), "ring-planet": float(sys_.damping[N])},
        "contact_ratio": {"sun-planet": float(sys_.contact_ratio[0]), "ring-planet": float(sys_.contact_ratio[1])},
        "phase_ring_vs_sun_mesh": float(sys_.u_rs), "other_flanks": bool(sys_.mirrored),
        "force_nominal_sun_planet": per(F)[0], "force_nominal_ring_planet": per(F)[1],
        "force_max_sun_planet": per(fmax)[0], "force_max_ring_planet": per(fmax)[1],
        "force_min_sun_planet": per(fmin)[0], "force_min_ring_planet": per(fmin)[1],
        "force_quasi_static_max_sun_planet": per(qs[:, 0])[0], "force_quasi_static_max_ring_planet": per(qs[:, 0])[1],
        "force_quasi_static_min_sun_planet": per(qs[:, 1])[0], "force_quasi_static_min_ring_planet": per(qs[:, 1])[1],
        "kv_sun_planet": per(kv)[0], "kv_ring_planet": per(kv)[1], "kv": both(kv),
        "load_sharing_quasi_static_sun_planet": per(qs[:, 2])[0],
        "load_sharing_quasi_static_ring_planet": per(qs[:, 2])[1],
        "load_sharing_factor_quasi_static": both(qs[:, 2]),
        "force_max_over_nominal_sun_planet": per(fmax / F)[0], "force_max_over_nominal_ring_planet": per(fmax / F)[1],
        "quasi_static_max_over_nominal": both(shift),
        "force_over_quasi_static_max": both(qs[:, 3]),
        "window_growth": float(np.nanmax(growth)) if np.isfinite(growth).any() else None,
        "natural_frequencies_hz": [float(x) for x in freqs], "modal_damping_ratios": [float(x) for x in zeta],
    }
    arrays = {"time": np.arange(int(nw[0])) * float(h[0]), "force": out_f, "force_quasi_static": out_q,
              "force_nominal": F, "mesh_names": sys_.mesh_names, "speed": float(omega), "mesh_frequency_hz": float(fm[0])}
    if dyn.sweep:
        ns_ = len(speeds)
        smax, smin, smean = np.zeros((ns_, m)), np.zeros((ns_, m)), np.zeros((ns_, m))
        shalves, sqs = np.zeros((ns_, m, 4)), np.zeros((ns_, m, 4))
        chunk = max(8, -(-ns_ // 10))
        for a in range(0, ns_, chunk):
            b = min(ns_, a + chunk)
            if progress:
                progress(0.2 + 0.7 * a / ns_, f"planetary sweep: {a} of {ns_} speeds")
            kern.sweep(speeds[a:b], sys_.phi, q0, p, hs[a:b], nss[a:b], nws[a:b], smax[a:b], smin[a:b], smean[a:b],
                       shalves[a:b], sqs[a:b])
        kvs = smax / sqs[:, :, 0]
        ok = np.isfinite(kvs).all(axis=1)
        summary["sweep"] = {
            "speed_min": float(speeds[0]), "speed_max": float(speeds[-1]), "count": ns_,
            "mesh_hz_per_rad_s": float(sys_.mesh_frequency(1.0)),
            "kv_max": {"sun-planet": float(np.nanmax(kvs[ok][:, :N])) if ok.any() else None,
                       "ring-planet": float(np.nanmax(kvs[ok][:, N:])) if ok.any() else None},
            "speed_at_kv_max": {"sun-planet": float(speeds[ok][np.nanargmax(kvs[ok][:, :N].max(axis=1))]) if ok.any() else None,
                                "ring-planet": float(speeds[ok][np.nanargmax(kvs[ok][:, N:].max(axis=1))]) if ok.any() else None},
            "diverged_speeds": [float(x) for x in speeds[~ok]],
        }
        arrays["sweep_speed"] = speeds
        arrays["kv_sweep"] = kvs
        arrays["load_sharing_sweep"] = sqs[:, :, 2]
    summary["wall_time"] = time.perf_counter() - t0
    return summary, arrays
