"""The ``check`` report: geometry, ISO stiffness, stiffness tables, statics and natural frequencies."""
from __future__ import annotations

import math

import numpy as np

from .train.system import assemble, method_b, reduced_mass_per_mesh


def report(model) -> str:
    """Text report of what is known without integrating: per gear, per mesh, and the train's modes."""
    if model.planetary is not None and not model.meshes:
        return "\n".join([f"planetary stage: {model.name or '(unnamed)'}", *gearbox_lines(model)])
    s = assemble(model)
    out = [f"gear train: {model.name or '(unnamed)'}", ""]
    out.append(f"{'gear':10s} {'z':>4s} {'m mm':>6s} {'x':>6s} {'b mm':>6s} {'d mm':>8s} {'d_b mm':>8s} "
               f"{'d_a mm':>8s} {'d_f mm':>8s} {'n rpm':>9s} {'T N m':>9s}")
    for i, (g, geo) in enumerate(zip(model.gears, s.gears)):
        out.append(f"{g.name:10s} {g.teeth:4d} {g.module * 1e3:6.3f} {g.profile_shift:6.3f} {g.face_width * 1e3:6.1f} "
                   f"{2 * geo.r * 1e3:8.3f} {2 * geo.rb * 1e3:8.3f} {2 * geo.ra * 1e3:8.3f} {2 * geo.rf * 1e3:8.3f} "
                   f"{s.ratio[i] * s.omega_in * 30 / math.pi:9.2f} {s.torque_const[i]:9.3f}")
    mred = reduced_mass_per_mesh(s)
    f_mesh = s.mesh_frequency(s.omega_in)
    for j, ms in enumerate(model.meshes):
        p, iso, tab = s.pairs[j], s.iso[j], s.tables[j]
        b = min(p.g1.b, p.g2.b)
        c1, cg = iso.si(b)
        mb = method_b(model, s, j, mred[j])
        kv, N, region = mb.kv(s.ratio[s.mesh_a[j]] * s.omega_in / (2 * math.pi))
        out += ["", f"mesh {ms.name}: {ms.gears[0]} drives {ms.gears[1]}",
                f"  working pressure angle {math.degrees(p.alpha_w):.4f} deg, centre distance {p.a_w * 1e3:.4f} mm "
                f"(zero backlash {p.a_zero_backlash * 1e3:.4f} mm)",
                f"  base pitch p_bt {p.base_pitch * 1e3:.4f} mm, path of contact g_alpha {p.path_of_contact * 1e3:.4f} mm, "
                f"contact ratio eps_alpha {p.contact_ratio:.4f}",
                *([f"  helical: beta {math.degrees(p.g1.beta):.4f} deg ({p.g1.hand}-hand driving gear), beta_b "
                   f"{math.degrees(p.g1.beta_b):.4f} deg, overlap ratio eps_beta {p.overlap_ratio:.4f}, eps_gamma "
                   f"{p.total_contact_ratio:.4f}; axial force on the bearings {s.force_nominal[j] * math.tan(p.g1.beta_b):.1f} N"]
                  if p.g1.beta > 0 else []),
                f"  T1A {p.rho_start * 1e3:.4f} mm, T1C (pitch point) {p.rho_pitch * 1e3:.4f} mm, T1E {p.rho_end * 1e3:.4f} mm, "
                f"T1T2 {p.tangent_length * 1e3:.4f} mm",
                f"  ISO 6336-1: q' {iso.q_prime:.5f}, c'_th {iso.c_th:.3f}, C_M {iso.c_m}, C_R {iso.c_r}, C_B {iso.c_b:.4f}, "
                f"E factor {iso.e_factor:.3f}, low-load factor {iso.low_load_factor:.4f} (K_A F_t/b = {iso.load_per_width:.1f} N/mm)",
                f"    c' = {iso.c_single:.3f} N/(mm um) = {c1:.4g} N/m, c_gamma_alpha = {iso.c_gamma:.3f} N/(mm um) = {cg:.4g} N/m"
                + ("" if iso.valid else "  (x1 + x2 outside the ISO range -0.5..2)"),
                f"  stiffness model {ms.stiffness.model}: mean {tab.mean:.4g} N/m, min {tab.stiffness.min():.4g}, "
                f"max {tab.stiffness.max():.4g}, phase {s.phase[j]:.4f} mesh periods",
                f"  nominal force {s.force_nominal[j]:.2f} N, mesh frequency {f_mesh[j]:.2f} Hz, damping {s.damping[j]:.4g} N s/m, "
                f"friction mu {s.mu[j]:g}",
                f"  ISO method B: n_E1 {mb.resonance_speed * 60:.0f} rpm, N {N:.4f} ({region}), K_v {kv:.4f}"]
        if model.iso.rating:
            out += _rating_lines(model, s, j, kv if model.iso.dynamic_factor is None else model.iso.dynamic_factor)
    freqs, shapes, zeta = s.modes()
    out += ["", "natural frequencies (mean mesh stiffness, rigid-body mode removed):"]
    for r, (f, z) in enumerate(zip(freqs, zeta)):
        orders = ", ".join(f"{f / fm:.2f}" for fm in sorted(set(np.round(f_mesh, 6))))
        shape = " ".join(f"{v:+.3f}" for v in shapes[:, r] / np.abs(shapes[:, r]).max())
        out.append(f"  {f:10.2f} Hz  zeta {z:.4f}  = {orders} x mesh frequency  shape [{shape}]")
    if model.planetary is not None:
        out += gearbox_lines(model, s)
    return "\n".join(out)


def gearbox_lines(model, sys_=None) -> list[str]:
    """The ``check`` text of a model's planetary stages and, for a gearbox, its whole-train modes."""
    from .planetary.stage import report_lines

    out = report_lines(model.planetary, model.iso)
    for k, spec in enumerate(model.stages):
        out += [line.replace("planetary stage:", f"stage {k + 2} (planetary):", 1) for line in report_lines(spec, model.iso, f"stages[{k}]")]
    last = [model.planetary, *model.stages][-1]
    if model.stages or (sys_ is not None and last.output_gear is not None):
        from .planetary.gearbox import modes as gearbox_modes

        gb = gearbox_modes(model, sys_ if last.output_gear is not None else None)
        drives = f", the last driving {gb['output_gear']!r}" if gb["output_gear"] and sys_ is not None else ""
        out += ["", f"gearbox: {' -> '.join(gb['stages'])}{drives}, joined by their output shafts; modes of the whole "
                    f"train ({', '.join(dict.fromkeys(gb['model']))} stage models, rigid-body mode removed; kinetic "
                    "energy share in the planetary stages):",
                *(f"  {f:10.2f} Hz  stages {e:5.3f}" for f, e in zip(gb["natural_frequencies_hz"], gb["stage_energy_share"]))]
    return out


def _rating_lines(model, s, j, kv) -> list[str]:
    """ISO 6336-2/-3 method B at the nominal load with ISO's K_v (the run uses the simulated one)."""
    from .rating.mesh import rate_mesh

    r = rate_mesh(model, s, j, kv)
    f = r.factors
    src = "ISO's" if model.iso.dynamic_factor is None else "the given"
    out = [f"  ISO 6336-2/-3 rating with {src} K_v {kv:.4f} ({r.geometry['pinion']} = pinion): K_Hbeta {f['K_Hbeta']:.4f}, "
           f"K_Fbeta {f['K_Fbeta']:.4f}, K_Halpha {f['K_Halpha']:.4f}, Z_H {f['Z_H']:.4f}, Z_E {f['Z_E']:.2f} sqrt(N)/mm, "
           f"Z_eps {f['Z_eps']:.4f}, Z_L {f['Z_L']:.4f}, Z_v {f['Z_v']:.4f}, Z_R {f['Z_R']:.4f}"]
    for who, g in (("pinion", r.pinion), ("wheel", r.wheel)):
        out.append(f"    {who:6s}: sigma_H {g['sigma_H']:.1f} / sigma_HP {g['sigma_HP']:.1f} N/mm^2, S_H {g['S_H']:.3f}; "
                   f"Y_F {g['Y_F']:.4f}, Y_S {g['Y_S']:.4f}, sigma_F {g['sigma_F']:.1f} / sigma_FP {g['sigma_FP']:.1f} N/mm^2, "
                   f"S_F {g['S_F']:.3f} (Z_NT {g['Z_NT']:.3f}, Y_NT {g['Y_NT']:.3f}, {g['N_L']:.3g} cycles)")
    out += [f"    note: {n}" for n in dict.fromkeys(r.notes)]
    return out
