"""A synchronous belt at rest and under steady load, per grooved pulley: the teeth in mesh, the
tooth loads of the quasi-static shear-lag chain between the wrap's span tensions (the toothed-mesh
analysis's chain, mechanics/teeth/loadshare.py, with this belt's pitch difference and play), the
smallest jump margin and the torque at which a tooth would climb (jump torque). What ``check``
says of the teeth before a run; the run's own tooth loads come from the segment model."""
from __future__ import annotations

import math

from ...mechanics.teeth.loadshare import Chain, jump_margin, jump_torque, solve, teeth_in_mesh


def tooth_table(model, layout, unstretched_length: float, tensions: dict, T0: float) -> dict:
    """``tensions``: per pulley name (T_in, T_out, torque) of the steady state; T0 the belt's tension at
    rest. Returns the belt's tooth data and a row per grooved pulley."""
    from ..geometry.teeth import belt_teeth, sinking

    bt = belt_teeth(model, layout.length)
    p0 = unstretched_length / bt.count        # the belt's pitch unstretched
    out = {"profile": bt.profile, "pitch": bt.pitch, "count": bt.count, "count_source": bt.count_source,
           "belt_pitch_unstretched": p0, "belt_pitch_at_rest": p0 * (1 + T0 / model.belt.axial_stiffness),
           "tooth_stiffness": bt.stiffness, "play": bt.play, "flank_angle": bt.flank_angle,
           "climb_factor": bt.climb, "pulleys": {}}
    for j, q in enumerate(model.pulleys):
        if not q.teeth:
            continue
        n = teeth_in_mesh(q.teeth, float(layout.wrap[j]))
        # the pitch error at the installation tension T0, the belt's pitch at rest against the grooves
        # (the segment model's chain rides, as installed, on the pitch circle), and about T0 the belt's
        # sinking into its support in series with the cord (loadshare.py, eq. 4)
        chain = Chain(teeth=n, pitch=bt.pitch, radius=q.radius, tooth_stiffness=bt.stiffness,
                      cord_stiffness=model.belt.axial_stiffness, friction=0.0,
                      pitch_error=out["belt_pitch_at_rest"] - bt.pitch, clearance=0.5 * bt.play,
                      radial_stiffness=sinking(model.contact, T0 / q.radius)[1])
        T_in, T_out, M = tensions.get(q.name, (T0, T0, 0.0))
        tight, slack = max(T_in, T_out), max(min(T_in, T_out), 0.0)
        row = {"teeth": q.teeth, "teeth_in_mesh": n, "tension_tight": tight, "tension_slack": slack, "torque": M}
        try:
            sh = solve(chain, tight, slack, T0)
            row["max_tooth_load"] = float(max(abs(sh.tooth_load)))
            if bt.climb > 0:
                push = abs(sh.tooth_load) * bt.climb
                hold = sh.tooth_tension * chain.pitch / chain.radius
                row["jump_margin"] = float(min(h / x for h, x in zip(hold, push) if x > 0)) if any(push > 0) else math.inf
                row["jump_margin_excess"] = float(max(jump_margin(sh, chain, bt.climb)))
                jt = jump_torque(chain, T0, bt.climb)
                row["jump_torque"] = jt
        except Exception as exc:  # noqa: BLE001  (a chain that does not converge says so in its row)
            row["note"] = f"the quasi-static chain did not solve: {exc}"
        out["pulleys"][q.name] = row
    return out


def tooth_lines(data: dict) -> list[str]:
    """check's teeth section."""
    d = data
    lines = ["", f"teeth: {d['profile']}, {d['count']} teeth of {d['pitch'] * 1e3:.4g} mm ({d['count_source']}); the "
                 f"belt's pitch {d['belt_pitch_unstretched'] * 1e3:.4f} mm unstretched, {d['belt_pitch_at_rest'] * 1e3:.4f} "
                 f"mm at rest (against {d['pitch'] * 1e3:.4g} mm of the grooves); tooth spring "
                 f"{d['tooth_stiffness'] / 1e3:.4g} N/mm, play {d['play'] * 1e3:.3g} mm, flank {math.degrees(d['flank_angle']):.2f} deg",
             f"{'pulley':14s} {'grooves':>7s} {'in mesh':>7s} {'T tight N':>9s} {'T slack N':>9s} {'load N m':>9s} "
             f"{'tooth load N':>12s} {'jump margin':>11s} {'jump at N m':>11s}"]
    for name, r in d["pulleys"].items():
        jm = r.get("jump_margin")
        jt = r.get("jump_torque")
        lines.append(f"{name:14s} {r['teeth']:7d} {r['teeth_in_mesh']:7d} {r['tension_tight']:9.1f} {r['tension_slack']:9.1f} "
                     f"{r['torque']:9.3f} {r.get('max_tooth_load', float('nan')):12.1f} "
                     f"{'-' if jm is None else f'{jm:.2f}':>11s} {'-' if jt is None else f'{jt:.2f}':>11s}"
                     + (f"  ({r['note']})" if "note" in r else ""))
    lines.append("  the quasi-static shear-lag chain per pulley (mechanics/teeth/loadshare.py) between the steady state's "
                 "span tensions; jump margin: hold T p / R over push Q tan(phi - rho), below 1 a tooth climbs; jump at: "
                 "the torque at which the first tooth climbs at this installation tension. A synchronous belt does not "
                 "creep on its grooved pulleys: the creep theory's slip columns below apply to its smooth pulleys only.")
    return lines
