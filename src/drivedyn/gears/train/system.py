"""From the model file to plain arrays: topology, speeds, torques, mesh tables, statics and modes.

Coordinates: one rotation angle per gear, positive in the gear's own nominal direction of rotation
(seed 003 convention). A mesh (a drives b) has the deflection along its line of action
delta = r_ba theta_a - r_bb theta_b = g . theta with g_a = r_ba, g_b = -r_bb; a shaft joining a and b
has delta = theta_a - theta_b. Mesh force f = k(u) delta + c delta' (seed 003, eqs. 9-11).
"""
from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass, field

import numpy as np

from ...core.errors import ModelError
from ...core.tables import flatten
from ..mesh import iso6336, stiffness
from ..mesh.geometry import GearGeometry, pair


@dataclass
class System:
    """Everything the kernels and reports need, as arrays (SI)."""

    model: object
    names: list
    inertia: np.ndarray
    gears: list                   # GearGeometry
    ratio: np.ndarray             # nominal speed of each gear per unit input speed
    omega_in: float
    input_index: int
    torque_input: float
    torque_const: np.ndarray      # constant external torques, N m (loads negative)
    mesh_names: list
    mesh_a: np.ndarray
    mesh_b: np.ndarray
    rb_a: np.ndarray
    rb_b: np.ndarray
    z_a: np.ndarray
    phase: np.ndarray             # mesh cycles
    damping: np.ndarray           # N s/m
    mu: np.ndarray
    separation: np.ndarray        # 1 = tooth separation on
    backlash: np.ndarray
    pairs: list                   # PairGeometry
    tables: list                  # stiffness.MeshTable
    iso: list                     # iso6336.IsoStiffness
    shaft_a: np.ndarray
    shaft_b: np.ndarray
    shaft_k: np.ndarray
    shaft_c: np.ndarray
    ts_off: np.ndarray
    ts_x: np.ndarray
    ts_y: np.ndarray
    tt_off: np.ndarray
    tt_x: np.ndarray
    tt_y: np.ndarray
    force_nominal: np.ndarray = field(default=None)

    @property
    def n(self) -> int:
        return len(self.names)

    @property
    def m(self) -> int:
        return len(self.mesh_names)

    def ktab(self):
        return np.array([t.stiffness for t in self.tables])

    def friction_tables(self):
        fa = np.array([mu * t.arm_driving for mu, t in zip(self.mu, self.tables)])
        fb = np.array([mu * t.arm_driven for mu, t in zip(self.mu, self.tables)])
        return fa, fb

    def mesh_frequency(self, omega_in: float) -> np.ndarray:
        """Mesh frequency of each mesh (Hz) at input speed ``omega_in`` (rad/s)."""
        return self.z_a * self.ratio[self.mesh_a] * omega_in / (2 * math.pi)

    def coupling(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(K, C, M) of the linear model with the mean mesh stiffness."""
        n = self.n
        K, C = np.zeros((n, n)), np.zeros((n, n))
        for j in range(self.m):
            g = np.zeros(n)
            g[self.mesh_a[j]], g[self.mesh_b[j]] = self.rb_a[j], -self.rb_b[j]
            K += self.tables[j].mean * np.outer(g, g)
            C += self.damping[j] * np.outer(g, g)
        for j in range(len(self.shaft_k)):
            g = np.zeros(n)
            g[self.shaft_a[j]], g[self.shaft_b[j]] = 1.0, -1.0
            K += self.shaft_k[j] * np.outer(g, g)
            C += self.shaft_c[j] * np.outer(g, g)
        return K, C, np.diag(self.inertia)

    def static(self, k_mesh=None, torque=None):
        """Static deflections (rad) and mesh forces (N) under the constant torques.

        The rigid-body acceleration of any unbalanced torque is taken out first (d'Alembert), so
        the elastic solution exists; ``k_mesh`` (N/m per mesh) defaults to the mean stiffness.
        """
        K, _, M = self.coupling()
        T = self.torque_const if torque is None else torque
        if k_mesh is not None:
            K = K.copy()
            for j in range(self.m):
                g = np.zeros(self.n)
                g[self.mesh_a[j]], g[self.mesh_b[j]] = self.rb_a[j], -self.rb_b[j]
                K += (k_mesh[j] - self.tables[j].mean) * np.outer(g, g)
        phi = self.ratio
        acc = phi @ T / (phi @ M @ phi)
        q = np.linalg.lstsq(K, T - M @ phi * acc, rcond=None)[0]
        q -= phi * (phi @ M @ q) / (phi @ M @ phi)         # no rigid-body part
        kk = np.array([self.tables[j].mean for j in range(self.m)]) if k_mesh is None else np.asarray(k_mesh)
        f = kk * (self.rb_a * q[self.mesh_a] - self.rb_b * q[self.mesh_b])
        return q, f, acc

    def modes(self):
        """Natural frequencies (Hz, ascending, rigid-body mode removed), mass-normalised shapes, damping ratios."""
        from scipy.linalg import eigh

        K, C, M = self.coupling()
        lam, vec = eigh(K, M)
        scale = max(abs(lam).max(), 1.0)
        keep = lam > 1e-9 * scale
        lam, vec = lam[keep], vec[:, keep]
        w = np.sqrt(lam)
        zeta = np.array([vec[:, r] @ C @ vec[:, r] / (2 * w[r]) for r in range(len(w))])
        return w / (2 * math.pi), vec, zeta


def _tables(gears, key, units_x):
    return flatten([getattr(g, key) for g in gears])


def _speed_ratios(model, index, pairs):
    """Nominal speed of every gear per unit input speed, by a walk over meshes and shafts."""
    n = len(model.gears)
    links = [[] for _ in range(n)]
    for j, (ms, geo) in enumerate(zip(model.meshes, pairs)):
        a, b = index[ms.gears[0]], index[ms.gears[1]]
        links[a].append((b, geo.g1.rb / geo.g2.rb, f"meshes[{j}]"))
        links[b].append((a, geo.g2.rb / geo.g1.rb, f"meshes[{j}]"))
    for j, sh in enumerate(model.shafts):
        a, b = index[sh.gears[0]], index[sh.gears[1]]
        links[a].append((b, 1.0, f"shafts[{j}]"))
        links[b].append((a, 1.0, f"shafts[{j}]"))
    ratio = np.full(n, np.nan)
    start = index[model.drive.input]
    ratio[start] = 1.0
    todo = deque([start])
    while todo:
        i = todo.popleft()
        for k, r, where in links[i]:
            want = ratio[i] * r
            if np.isnan(ratio[k]):
                ratio[k] = want
                todo.append(k)
            elif abs(ratio[k] - want) > 1e-9 * want:
                raise ModelError(f"the speed ratios around a closed loop do not agree at gear "
                                 f"{model.gears[k].name!r} ({ratio[k]:.6g} vs {want:.6g})", field=where)
    lost = [model.gears[i].name for i in range(n) if np.isnan(ratio[i])]
    if lost:
        raise ModelError(f"gear(s) {lost} are not connected to the input gear {model.drive.input!r} by meshes or shafts",
                         field="meshes")
    return ratio


def assemble(model) -> System:
    """Build the :class:`System` of a gear-train model (raises ModelError naming the field)."""
    names = [g.name for g in model.gears]
    index = {n: i for i, n in enumerate(names)}
    geos = [GearGeometry.of(g) for g in model.gears]
    pairs = []
    for j, ms in enumerate(model.meshes):
        a, b = index[ms.gears[0]], index[ms.gears[1]]
        pairs.append(pair(geos[a], geos[b], ms.center_distance, field=f"meshes[{j}]"))
    ratio = _speed_ratios(model, index, pairs)
    w_in = model.drive.speed
    i_in = index[model.drive.input]
    T_in = model.drive.torque if model.drive.torque is not None else model.drive.power / w_in
    Tc = np.array([g.torque for g in model.gears], dtype=float)
    Tc[i_in] += T_in
    for i, g in enumerate(model.gears):
        if g.load_fraction:
            Tc[i] -= g.load_fraction * T_in / ratio[i]     # power fraction taken off at gear i
    if sum(g.load_fraction for g in model.gears) > 1 + 1e-9:
        raise ModelError("the load fractions add up to more than 1", field="gears")

    ma = np.array([index[ms.gears[0]] for ms in model.meshes], dtype=np.int64)
    mb = np.array([index[ms.gears[1]] for ms in model.meshes], dtype=np.int64)
    sys_ = System(
        model=model, names=names, inertia=np.array([g.inertia for g in model.gears]), gears=geos, ratio=ratio,
        omega_in=w_in, input_index=i_in, torque_input=T_in, torque_const=Tc,
        mesh_names=[ms.name for ms in model.meshes], mesh_a=ma, mesh_b=mb,
        rb_a=np.array([p.g1.rb for p in pairs]), rb_b=np.array([p.g2.rb for p in pairs]),
        z_a=np.array([p.g1.z for p in pairs], dtype=float),
        phase=np.array([ms.phase if ms.phase is not None else
                        (-p.g1.z * ms.position_angle / (2 * math.pi)) % 1.0 for ms, p in zip(model.meshes, pairs)]),
        damping=np.zeros(len(pairs)), mu=np.array([ms.friction for ms in model.meshes]),
        separation=np.array([1 if ms.separation else 0 for ms in model.meshes], dtype=np.int64),
        backlash=np.array([ms.backlash for ms in model.meshes]), pairs=pairs, tables=[], iso=[],
        shaft_a=np.array([index[s.gears[0]] for s in model.shafts], dtype=np.int64),
        shaft_b=np.array([index[s.gears[1]] for s in model.shafts], dtype=np.int64),
        shaft_k=np.array([s.stiffness for s in model.shafts], dtype=float),
        shaft_c=np.array([s.damping for s in model.shafts], dtype=float),
        **dict(zip(("ts_off", "ts_x", "ts_y"), _tables(model.gears, "torque_speed", "rad/s"))),
        **dict(zip(("tt_off", "tt_x", "tt_y"), _tables(model.gears, "torque_time", "s"))),
    )
    # the nominal mesh forces decide the ISO low-load factor: a first static pass with unit stiffness
    # gives them exactly for statically determinate trains, and closely otherwise
    for j, p in enumerate(pairs):
        sys_.tables.append(stiffness.MeshTable(u=None, stiffness=None, pairs=None, arm_driving=None, arm_driven=None,
                                               pair_s=None, pair_k=None, mean=1e8))
    _, f0, _ = sys_.static()
    ka = model.iso.application_factor
    # one table size for all meshes, independent of the step: at the slowest speed run (nominal or
    # sweep) a cell lasts under 1/64 of the shortest free period (estimated with twice the ISO or
    # given mean stiffness), so a stiffness jump stays a jump for the dynamics
    w_low = min(w_in, model.sweep.speed_min or w_in) if model.sweep.enabled else w_in
    t_mesh = max(2 * math.pi / (p.g1.z * ratio[ma[j]] * w_low) for j, p in enumerate(pairs))
    count = np.bincount(np.concatenate([ma, mb]), minlength=len(names))
    inert = np.array([g.inertia for g in model.gears])
    f_est = 0.0
    for j, (ms, p) in enumerate(zip(model.meshes, pairs)):
        k = ms.stiffness.mean or ms.stiffness.double or 1e9 * 30.0 * min(p.g1.b, p.g2.b) * 1.4
        f_est = max(f_est, math.sqrt(2 * k * (count[ma[j]] * p.g1.rb ** 2 / inert[ma[j]]
                                              + count[mb[j]] * p.g2.rb ** 2 / inert[mb[j]])) / (2 * math.pi))
    n_tab = int(min(max(stiffness.N_TABLE, math.ceil(64 * t_mesh * f_est)), 2 ** 18))
    for j, (ms, p) in enumerate(zip(model.meshes, pairs)):
        ga, gb = model.gears[ma[j]], model.gears[mb[j]]
        b = min(p.g1.b, p.g2.b)
        w = ka * abs(f0[j]) * math.cos(p.g1.alpha_t) / (b * 1e3)     # K_A F_t / b, N/mm (F_t at the reference circle)
        iso = iso6336.single_pair_stiffness(p.g1.z, p.g2.z, p.g1.x, p.g2.x, p.contact_ratio, max(w, 1e-9),
                                            dedendum=(ga.dedendum, gb.dedendum), alpha_deg=math.degrees(p.g1.alpha),
                                            youngs=(ga.youngs_modulus, gb.youngs_modulus),
                                            blank_factor=model.iso.blank_factor, low_load=model.iso.low_load,
                                            beta=p.g1.beta)
        sys_.iso.append(iso)
        c1, cg = iso.si(b)
        r_int = tuple(0.5 * g.bore_diameter if g.bore_diameter is not None else 0.5 * geo.rf
                      for g, geo in ((ga, p.g1), (gb, p.g2)))
        try:
            tab = stiffness.build(p, ms.stiffness, c1, cg, b=b, E=(ga.youngs_modulus, gb.youngs_modulus),
                                  nu=(ga.poisson, gb.poisson), r_int=r_int, n_table=n_tab)
        except ValueError as exc:
            raise ModelError(str(exc), field=f"meshes[{j}].stiffness") from None
        sys_.tables[j] = tab
        m_a = sys_.inertia[ma[j]] / p.g1.rb ** 2
        m_b = sys_.inertia[mb[j]] / p.g2.rb ** 2
        if ms.damping is not None:
            sys_.damping[j] = ms.damping
        else:
            zeta = 0.05 if ms.damping_ratio is None else ms.damping_ratio
            sys_.damping[j] = 2 * zeta * math.sqrt(tab.mean * m_a * m_b / (m_a + m_b))
    # nominal force: static, mean stiffness, before the friction loss is taken off the loads
    # (for the split path F = T1 / (2 r_b1), seed 003 eq. 13)
    _, f, _ = sys_.static()
    sys_.force_nominal = f
    _absorb_friction_loss(sys_, model, f)
    for j, fj in enumerate(f):
        if fj <= 0:
            raise ModelError(f"the nominal mesh force is {fj:.4g} N: gear {model.meshes[j].gears[0]!r} does not "
                             f"drive {model.meshes[j].gears[1]!r} under these torques (swap the gears of the mesh)",
                             field=f"meshes[{j}].gears")
    return sys_


def reduced_mass_per_mesh(sys_: System) -> np.ndarray:
    """ISO 6336-1 method B reduced mass (kg) of each mesh, the inertia of a gear in n meshes shared by n.

    m* = J / r_b^2 (ISO 6336-1:2006 eq. 30 written with the real inertias); for a pinion driving
    two wheels in phase this gives m1* m2* / (m1* + 2 m2*), the in-phase mode of a split path.
    """
    count = np.bincount(np.concatenate([sys_.mesh_a, sys_.mesh_b]), minlength=sys_.n)
    out = np.empty(sys_.m)
    for j in range(sys_.m):
        ma = sys_.inertia[sys_.mesh_a[j]] / sys_.rb_a[j] ** 2 / count[sys_.mesh_a[j]]
        mb = sys_.inertia[sys_.mesh_b[j]] / sys_.rb_b[j] ** 2 / count[sys_.mesh_b[j]]
        out[j] = ma * mb / (ma + mb)
    return out


def method_b(model, sys_: System, j: int, m_red: float) -> "iso6336.MethodB":
    """ISO 6336-1 method B inputs of mesh ``j`` with the reduced mass ``m_red`` (kg)."""
    p_ = sys_.pairs[j]
    iso = sys_.iso[j]
    b_mm = min(p_.g1.b, p_.g2.b) * 1e3
    return iso6336.MethodB(z1=p_.g1.z, c_single=iso.c_single, c_gamma=iso.c_gamma, m_red=m_red / b_mm,
                           eps_gamma=p_.total_contact_ratio, load_per_width=iso.load_per_width,
                           f_pb=model.iso.pitch_deviation * 1e6, f_falpha=model.iso.profile_deviation * 1e6,
                           material=model.iso.material, sigma_hlim=model.iso.sigma_hlim / 1e6,
                           c_a=None if model.iso.tip_relief is None else model.iso.tip_relief * 1e6, pitch_radius=p_.g1.r)


def _absorb_friction_loss(sys_: System, model, f) -> None:
    """Lower the power-fraction loads by the mean tooth-friction loss, so the train keeps its speed.

    With constant torques that balance the input power exactly, the friction loss would slowly
    brake the whole train (0.6 % speed lost in 0.05 s in the seed case), shifting the mesh frequency
    during the run; the outputs receive the input power minus the loss instead.
    """
    loads = np.array([g.load_fraction > 0 for g in model.gears])
    if not loads.any():
        return
    fa, fb = sys_.friction_tables()
    m_fr = np.zeros(sys_.n)
    np.add.at(m_fr, sys_.mesh_a, fa.mean(axis=1) * f)
    np.add.at(m_fr, sys_.mesh_b, fb.mean(axis=1) * f)
    T = sys_.torque_const
    p_load = np.sum(sys_.ratio[loads] * T[loads])
    p_rest = np.sum(sys_.ratio[~loads] * T[~loads]) + np.sum(sys_.ratio * m_fr)
    if p_load < 0:
        T[loads] *= -p_rest / p_load
