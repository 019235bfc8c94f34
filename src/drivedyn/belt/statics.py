"""What is known without simulating: layout, belt length, wraps, static tensions, hub loads, the
installation table (installation.py), the steady running state of creep theory with the slip
margins (steady/creep.py), the rotational modes (modes.py) and the step the integrator will use."""
from __future__ import annotations

import math

import numpy as np

from .model import integrator


def capstan_torque(tension, radius, wrap, mu):
    """Largest torque a pulley transmits before gross slip (Euler-Eytelwein, T1/T2 = e^(mu theta)),
    with T1 + T2 = 2 T0 (constant belt length): M = 2 T0 r (e - 1)/(e + 1)."""
    return 2 * tension * radius * math.tanh(mu * wrap / 2)  # = (e - 1)/(e + 1), no overflow


def check_data(model, sysm=None) -> dict:
    """What ``check`` knows, as plain data (``drivedyn check --json``): the steady running state of
    creep theory (steady/creep.py), the slip margins and the rotational modes (modes.py). ``model``: a
    model or its geometry.drive.Drive; ``sysm``: the segment model's system (or its system.Placed), when built."""
    from . import supplier
    from .geometry.drive import resolve
    from .geometry.installation import installation_table
    from ..mechanics.layout import compute_layout
    from .steady.modes import modes
    from .steady.creep import steady_state

    drive = resolve(model)
    model = drive.model
    rest = sysm.rest if sysm is not None else drive.equilibrium
    run = None
    if rest is not None:
        # with tensioners: the drive as they hold it at rest, its tension that of the installed
        # length (the discrete chain's; creep theory's continuum length follows from it); under
        # the running loads the tensioners move to where their springs balance the running tensions
        from .steady.running import running

        belt = rest.model.belt.model_copy(update={"pretension": float(rest.tension), "length": None})
        drawn, model = model, rest.model.model_copy(update={"belt": belt})
        run = running(drawn, rest)
    if sysm is not None:
        lay = sysm.layout
    else:    # as drawn, or with the tensioners where they hold the belt at rest
        lay = drive.layout if rest is None else compute_layout(model)
    st = steady_state(model, lay) if run is None else run[3]
    if sysm is not None:
        t0 = sysm.init.tension
    elif model.belt.pretension is not None:
        t0 = model.belt.pretension
    else:   # installed by length: the tension of that length at rest
        from .steady.creep import drive_of, tensions

        t0 = float(np.mean(tensions(drive_of(model, lay), np.zeros(len(model.pulleys)), 0.0, True)))
    inst = installation_table(model, t0, lay)
    # about the drive as it runs: the tensioners where they hold it, the spans at their steady tensions
    running = [st.spans[sp.name] for sp in lay.spans] if st.spans else None
    if running is not None and not all(math.isfinite(x) for x in running):
        running = None          # no steady state (a drive that cannot turn): the modes at rest
    md = modes(model, lay, tensions=running, travel=rest.travel if rest is not None else None)
    fin = lambda x: float(x) if math.isfinite(x) else None     # JSON: no inf (an unloaded pulley never slips)
    out = {
        "steady": {
            "state": st.state, "belt_speed": st.speed, "acceleration": st.acceleration,
            "centrifugal_tension": st.centrifugal, "unstretched_length": st.unstretched_length,
            "driver": st.driver, "gross_slip": st.gross_slip or None,
            "slip_margin": fin(st.margin), "limiting_pulley": st.limiting or None,
            "notes": st.notes + (["tensioners at their running equilibrium (the spring against the running span "
                                  "tensions less m v^2)"] if run is not None else
                                 ["tensioners held at their rest position (no steady running balance found)"]
                                 if rest is not None else []),
            "spans": {n: {"tension": t} for n, t in st.spans.items()},
            "pulleys": {p.name: {"torque": p.torque, "speed": p.speed, "wrap": p.wrap,
                                 "tension_in": p.tension_in, "tension_out": p.tension_out,
                                 "slip_arc": fin(p.slip_arc), "adhesion_arc": p.adhesion_arc,
                                 "creep": p.creep, "speed_ratio": p.speed_ratio,
                                 "slip_margin": fin(p.slip_margin),
                                 "slip_torque": fin(abs(p.torque) * p.slip_margin) if p.torque else None}
                        for p in st.pulleys.values()},
        },
        "installation": inst,
        **({"tensioners": _tensioner_data(drawn, rest, run)} if rest is not None else {}),
        "modes": {"dofs": list(md.dofs), "rigid_modes": md.rigid_modes, "frequencies_hz": md.frequencies_hz,
                  **({"free_rotor_hz": md.free_rotor_hz} if md.free_rotor_hz else {}),
                  "shapes": md.shapes, "participation": md.participation},
        **({"supplier": supplier.report_data(drive)} if supplier.wanted(model) else {}),
    }
    from .geometry import pitch_turn

    if pitch_turn.wanted(model):     # the belt path on the pitch curves over a turn, on check's centres
        out["pitch_curves"] = pitch_turn.turn_data(model, lay.centers)
    from .criteria import judge_check

    return {**judge_check(drive.model, out), **out}       # the verdict first


def _tensioner_data(model, rest, run=None) -> dict:
    from .geometry.tensioner import arm_angle, indices, senses, spring_load

    idx = indices(model)
    sense = senses(model) if idx else []
    out = {}
    for a, j in enumerate(idx):
        p = model.pulleys[j]
        e = {"type": "arm" if p.arm is not None else "slider", "hub_load": float(rest.hub[a]),
             "tension": float(rest.tension)}
        if p.arm is not None:
            e.update(arm_angle=float(rest.angle[a]), travel=float(rest.travel[a]), spring_torque=float(rest.spring[a]))
        else:
            e.update(slide=float(rest.travel[a]), spring_force=float(rest.spring[a]))
        if run is not None:     # under the running loads (creep theory)
            q = float(run[0][a])
            e["running_travel"] = q
            e["running_spring"] = float(spring_load(p.tensioner, q))
            if p.arm is not None:
                e["running_arm_angle"] = arm_angle(model, j, q, sense[a])
        out[p.name] = e
    return out


#: units of check_data's keys (angles in rad, margins and creep are ratios)
CHECK_UNITS = {"steady.spans.*.tension": "N", "steady.pulleys.*.torque": "N*m", "steady.pulleys.*.slip_torque": "N*m",
               "steady.pulleys.*.speed": "rad/s", "steady.pulleys.*.tension_*": "N", "steady.pulleys.*.wrap": "rad",
               "steady.pulleys.*.*_arc": "rad", "steady.pulleys.*": "1", "steady.belt_speed": "m/s",
               "steady.acceleration": "m/s^2", "steady.centrifugal_tension": "N", "steady.unstretched_length": "m",
               "steady.slip_margin": "1", "installation.tolerance": "1", "installation.spans.*.length": "m",
               "installation.spans.*.tension": "N", "installation.spans.*.frequency*": "Hz",
               "installation.spans.*.band": "Hz", "installation.spans.*.bending_correction": "1",
               "modes.frequencies_hz": "Hz", "modes.participation*": "1", "modes.shapes*": "rad",
               "tensioners.*.hub_load": "N", "tensioners.*.tension": "N", "tensioners.*.arm_angle": "rad",
               "tensioners.*.travel": "rad", "tensioners.*.spring_torque": "N*m", "tensioners.*.slide": "m",
               "tensioners.*.spring_force": "N", "tensioners.*.type": "", "tensioners.*.running_travel": "rad",
               "tensioners.*.running_spring": "N*m", "tensioners.*.running_arm_angle": "rad",
               "supplier.belt.profile": "", "supplier.belt.ribs": "", "supplier.belt.wear_allowance": "1",
               "supplier.belt.*": "m", "supplier.pulleys.*.contact": "", "supplier.pulleys.*.speed_ratio": "1",
               "supplier.pulleys.*": "m", "supplier.positions.*.rows.*.centre": "m",
               "supplier.positions.*.rows.*.edl": "m", "supplier.positions.*.rows.*.required_length": "m",
               "supplier.positions.*.rows.*.spring_torque": "N*m", "supplier.positions.*.rows.*.tension": "N",
               "supplier.positions.*.rows.*.hub_load": "N", "supplier.positions.*.rows.*": "rad",
               "supplier.positions.*.take_up": "m/rad", "supplier.positions.*.design_tension": "N",
               "supplier.positions.*.length_offset": "m", "supplier.positions.*.unreached*": "",
               "supplier.duty.design_tension": "N", "supplier.duty.idler_drag": "W",
               "supplier.duty.rows.crank_speed": "rad/s", "supplier.duty.rows.share": "1",
               "supplier.duty.rows.belt_speed": "m/s", "supplier.duty.rows.torques*": "N*m",
               "supplier.duty.rows.*.spans*": "N", "supplier.duty.rows.*.hub_load*": "N",
               "supplier.duty.rows.*.hub_direction*": "rad", "supplier.duty.rows.*.slip_factor*": "1",
               "supplier.duty.rows.arm_*": "rad", "supplier.duty.rows.slip_margin*": "1",
               "supplier.duty.rows.note": "", "supplier.life.b10_hours": "h", "supplier.life.target_hours": "h",
               "supplier.life.*_share*": "1", "supplier.life.*": "", "supplier.resonance.*_hz": "Hz",
               "supplier.resonance.participation*": "1",
               "supplier.alignment.*": "rad", "supplier.acceleration.acceleration": "rad/s^2",
               "supplier.acceleration.part_load": "1", "supplier.acceleration.speeds.crank_speed": "rad/s",
               "supplier.acceleration.speeds.*.pulley": "", "supplier.acceleration.speeds.*": "1",
               "supplier.duty_dynamic.crank_speed": "rad/s", "supplier.duty_dynamic.hub_load*": "N",
               "supplier.duty_dynamic.span_tension*": "N", "supplier.duty_dynamic.slip_margin*": "1",
               "supplier.duty_dynamic.arm_travel*": "rad", "supplier.duty_dynamic.*": "",
               "supplier.tolerance.tension": "N", "supplier.tolerance.slip_factor*": "1",
               "supplier.tolerance.hub_load*": "N", "supplier.tolerance.stop_clearance": "1",
               "supplier.tolerance.rows_not_carried": "rad/s", "supplier.tolerance.position": "",
               "pitch_curves.pulley": "", "pitch_curves.turns": "1", "pitch_curves.positions": "1",
               "pitch_curves.curves.*.kind": "", "pitch_curves.curves.*.ratio": "1", "pitch_curves.curves.*": "m",
               "pitch_curves.*.order": "1", "pitch_curves.*.*.order": "1", "pitch_curves.pulleys.*.wrap.*": "rad",
               "pitch_curves.*": "m"}


def check_json(model) -> str:
    return json_of(check_data(model))


def json_of(data: dict) -> str:
    """check_data's ``data`` as the JSON of ``check --json``, with its units."""
    from ..core.results import dumps_json, unit_map

    data = dict(data)
    data["units"] = unit_map(data, CHECK_UNITS)
    for name, c in data.get("criteria", {}).items():
        if c["unit"]:
            data["units"][f"criteria.{name}.value"] = data["units"][f"criteria.{name}.limit"] = c["unit"]
    return dumps_json(data, indent=1)     # strict JSON: null where no steady state exists


def report(model) -> str:
    """The text of ``drivedyn check``: the verdict first, then what check computes."""
    return report_and_data(model)[0]


def report_and_data(model):
    """(check's text, check_data's data) of a model, computed once."""
    from .geometry.installation import installation_table, table_lines
    from .geometry.segment_count import auto_segments
    from .geometry.drive import resolve
    from .segments.system import placed

    drive = resolve(model)
    model = drive.model        # (a belt installed by its part: with the length it installs)
    sysm = placed(drive)       # the chain as placed and its step: no settling, no kernels
    lay = sysm.layout
    T0 = sysm.init.tension
    belt, fr = model.belt, model.friction
    lines = [f"belt drive: {model.name or '(unnamed)'}",
             f"loop: {'counter-clockwise' if lay.orientation > 0 else 'clockwise'} in the listed order; "
             f"path length {lay.length * 1e3:.2f} mm at the contact radii",
             f"belt: unstretched length {sysm.init.seg_length * sysm.n * 1e3:.2f} mm, pretension {T0:.1f} N "
             f"(strain {T0 / belt.axial_stiffness * 100:.3f} %), {sysm.n} segments of {sysm.init.seg_length * 1e3:.3f} mm"
             + (f" (auto: {auto_segments(model)[1]})" if belt.segments == "auto" else ""),
             "friction: " + (f"elastic-plastic law, mu {fr.coefficient:g}, Delta_max {fr.displacement_limit * 1e3:g} mm"
                             if fr.law == "elastic-plastic" else
                             f"Threlfall's law (seed 000), mu {fr.coefficient:g}, Delta_v {fr.velocity_threshold:g} m/s"),
             "", f"{'pulley':14s} {'x mm':>9s} {'y mm':>9s} {'r mm':>7s} {'side':>6s} {'wrap deg':>9s} {'hub load N':>11s} "
             f"{'hub dir deg':>11s} {'penetr. mm':>10s}"]
    hub = lay.hub_load_static(T0)
    for j, p in enumerate(model.pulleys):
        H = hub[j]
        lines.append(f"{p.name:14s} {p.center[0] * 1e3:9.2f} {p.center[1] * 1e3:9.2f} {p.radius * 1e3:7.2f} {p.side:>6s} "
                     f"{math.degrees(lay.wrap[j]):9.2f} {np.hypot(*H):11.1f} {math.degrees(math.atan2(H[1], H[0])):11.1f} "
                     f"{sysm.init.penetration[j] * 1e3:10.4f}")
    lines += angle_load_lines(model)
    lines += [""] + table_lines(installation_table(model, T0, lay))
    data = check_data(drive, sysm)
    for name, t in data.get("tensioners", {}).items():
        if t["type"] == "arm":
            arm = next(p.arm for p in model.pulleys if p.name == name)
            rel = ""
            if arm.free_angle is not None:        # the supplier's convention: from the free arm, toward the belt
                from .model import free_arm_angle

                drawn = abs(free_arm_angle(next(p.center for p in model.pulleys if p.name == name), arm))
                rel = f"{math.degrees(drawn - t['travel']) + 0.0:.2f} deg from the free arm, "
            lines.append(f"tensioner {name} (arm) at rest: {rel}travel {math.degrees(t['travel']) + 0.0:.3f} deg into "
                         f"the belt from the drawn position (absolute arm angle {math.degrees(t['arm_angle']) % 360:.2f} deg, "
                         f"pivot to pulley from +x counter-clockwise), spring torque {t['spring_torque']:.3f} N m, "
                         f"hub load {t['hub_load']:.1f} N, belt tension {t['tension']:.1f} N")
        else:
            lines.append(f"tensioner {name} (slider) at rest: travel {t['slide'] * 1e3:.3f} mm into the belt, spring "
                         f"force {t['spring_force']:.2f} N, hub load {t['hub_load']:.1f} N, belt tension {t['tension']:.1f} N")
    lines += [""] + _steady_lines(data, model)
    if model.belt.teeth is not None:
        from .steady.tooth_loads import tooth_lines, tooth_table

        st = data["steady"]["pulleys"]
        tens = {n: (r["tension_in"], r["tension_out"], r["torque"]) for n, r in st.items()}
        data["teeth"] = tooth_table(model, lay, sysm.init.seg_length * sysm.n, tens, T0)
        lines += tooth_lines(data["teeth"])
    if "pitch_curves" in data:
        from .geometry.pitch_turn import turn_lines

        lines += [""] + turn_lines(data["pitch_curves"])
    if "supplier" in data:
        from .supplier import report_lines

        lines += report_lines(data["supplier"])
    from .criteria import verdict_lines

    lines = verdict_lines(data) + [""] + lines
    lines += ["", "static: no load, no gravity sag; span frequencies of the belt at rest (taut beam, pinned ends)."]
    from .segments.system import RKF45_STAGES, rkf45_step

    h_f = rkf45_step(model, sysm.init.tension) if integrator(model) == "rkf45" else None
    duration = model.simulation.duration
    if h_f is not None:      # its step is the friction law's, not the chain's (system.rkf45_step)
        lines.append(f"integration: rkf45 (explicit, adaptive): the friction law limits its step to about {h_f:.2g} s, "
                     f"{duration / h_f:.3g} steps of {RKF45_STAGES} stages for {duration:g} s (the semi-implicit "
                     f"scheme's stable step {sysm.step_limit * 1e6:.3f} us: {duration / sysm.step_limit:.3g} steps)")
    else:
        lines.append(f"integration: {integrator(model)}, step {sysm.step * 1e6:.3f} us (stability limit "
                     f"{sysm.step_limit * 1e6:.3f} us), {duration / sysm.step:.3g} steps for {duration:g} s")
    return "\n".join(lines), data


def angle_load_lines(model) -> list:
    """The torque_angle tables as the run applies them: mean and harmonics (belt/angle_torque.py)."""
    out = []
    for p in model.pulleys:
        if p.torque_angle is None:
            continue
        mean, hs = p.angle_load
        out += ["", f"{p.name}: torque_angle ({len(p.torque_angle)} rows) runs as mean {mean:.6g} N m (added to torque) "
                    f"and {len(hs)} harmonics amplitude sin(order theta + phase) (added to harmonics):",
                f"  {'order':>5s} {'amplitude N m':>14s} {'phase deg':>10s}"]
        out += [f"  {h.order:5g} {h.amplitude:14.6g} {math.degrees(h.phase):10.3f}" for h in hs]
    return out


def _steady_lines(data, model) -> list:
    st, md = data["steady"], data["modes"]
    what = {"running": f"running steady at belt speed {abs(st['belt_speed']):.4g} m/s (centrifugal tension "
                       f"{st['centrifugal_tension']:.3g} N)",
            "accelerating": f"accelerating uniformly ({abs(st['acceleration']):.4g} m/s^2 of belt)",
            "at rest": "at rest (no load)"}[st["state"]]
    out = [f"steady state (creep theory, belt length kept; driver {st['driver']}): {what}"]
    out += ["  " + n for n in st["notes"]]
    rpm = 30 / math.pi
    for p in model.pulleys:     # a swept prescribed speed: say which speed check evaluates
        speeds = sorted({abs(r[1]) for r in (p.speed_time or [])} - {0.0})
        if len(speeds) > 1:
            out.append(f"  evaluated at the last row of {p.name}.speed_time, {abs(p.speed_time[-1][1]) * rpm:.0f} rpm; "
                       f"the table runs {speeds[0] * rpm:.0f}-{speeds[-1] * rpm:.0f} rpm, and the lowest running speed "
                       "(idle) is often the critical one for slip: the run judges every speed bin")
    for p in model.pulleys:     # the alternator law of ``power`` (a pump given a power carried almost none)
        if p.power > 0:
            w = abs(st["belt_speed"]) / p.radius
            shaft = p.power / p.efficiency
            now = shaft * min(w / p.cut_in_speed - 1.0, 1.0) if w > p.cut_in_speed else 0.0
            out.append(f"  {p.name}.power {p.power:.4g} W is an alternator's electrical output (shaft power / efficiency "
                       f"{shaft:.4g} W): none below its cut_in_speed {p.cut_in_speed * rpm:.0f} rpm, rising to the full at "
                       f"{2 * p.cut_in_speed * rpm:.0f} rpm; here at {w * rpm:.0f} rpm it takes {now:.4g} W of shaft power "
                       "(a pump or fan: quadratic_torque or torque_speed)")
    out.append(f"{'pulley':14s} {'load N m':>9s} {'T in N':>8s} {'T out N':>8s} {'slip arc':>9s} {'of wrap':>8s} "
               f"{'creep %':>8s} {'margin':>7s} {'slips at N m':>12s}")
    for name, p in st["pulleys"].items():
        arc, m, mt = p["slip_arc"], p["slip_margin"], p["slip_torque"]
        arc_s = "gross" if arc is None else "%5.1f deg" % math.degrees(arc)
        share = "-" if arc is None else "%5.1f %%" % (100 * arc / p["wrap"])
        m_s = "-" if m is None else "%7.3f" % m
        mt_s = "-" if mt is None else "%12.2f" % mt
        out.append(f"{name:14s} {p['torque']:9.3f} {p['tension_in']:8.1f} {p['tension_out']:8.1f} {arc_s:>9s} "
                   f"{share:>8s} {100 * p['creep']:8.4f} {m_s:>7s} {mt_s:>12s}")
    out.append("  " + ", ".join(f"span {n} {s['tension']:.1f} N" for n, s in st["spans"].items()))
    grooved = {q.name for q in model.pulleys if q.teeth}
    if st["gross_slip"] and st["gross_slip"] in grooved:
        out.append("  the grooved pulleys carry their load by their teeth (the teeth section), not by friction")
    elif st["gross_slip"]:
        out.append(f"  no steady state: pulley {st['gross_slip']} slips grossly under these loads (slip arc > wrap)")
    elif st["slip_margin"] is not None:
        out.append(f"  slip margin {st['slip_margin']:.3f}: the loads x {st['slip_margin']:.3f} make pulley "
                   f"{st['limiting_pulley']} slip grossly (its slip arc reaches its wrap)")
    fr = ", ".join(f"{f:.1f}" for f in md["frequencies_hz"]) or "none"
    wraps = (", the wraps' pre-sliding compliance" if model.friction.law == "elastic-plastic" else "")
    out.append(f"rotational modes (spans EA/L with the belt's mass{wraps}, DOFs {', '.join(md['dofs'])}): {fr} Hz"
               + (" (one-way clutches locked)" if md.get("free_rotor_hz") else ""))
    if md.get("free_rotor_hz"):
        out.append("  clutches overrunning (rotors free): " + ", ".join(f"{f:.1f}" for f in md["free_rotor_hz"]) + " Hz")
    for k, part in enumerate(md["participation"]):
        top = sorted(part.items(), key=lambda kv: -kv[1])
        out.append(f"  {md['frequencies_hz'][k]:8.1f} Hz: " + ", ".join(f"{n} {100 * e:.0f} %" for n, e in top if e >= 0.01))
    return out
