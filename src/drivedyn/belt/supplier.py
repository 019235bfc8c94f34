"""The accessory-drive report a belt supplier prints, from the model: the belt and pulleys as the
catalogue gives them (geometry/catalogue.py), the tensioner's position table and take-up ratio
(geometry/positions.py), the duty cycle's span tensions, hub loads and slip safety factors in the
supplier's convention and with the arm's running balance (steady/duty.py), and the belt's B10 life
by rib fatigue (steady/life.py). ``report_data`` gives them as plain data (``check --json`` and the
run's summary), ``report_lines`` as the text tables of ``drivedyn check``. docs/supplier-report.md
defines every column.
"""
from __future__ import annotations

import math

DEG = 180 / math.pi


def wanted(model) -> bool:
    """Whether the model asks for the supplier's report (catalogue data, supplier tensioner data, a
    duty cycle or pulley alignment)."""
    from .geometry.alignment import has_alignment

    return (model.duty_cycle is not None or model.belt.effective_length is not None
            or any(p.arm is not None and p.arm.free_angle is not None for p in model.pulleys)
            or has_alignment(model))


def report_data(drive) -> dict:
    """The report's tables as plain data (SI units; angles in rad)."""
    from .geometry.catalogue import effective_diameters, effective_drive_length, length_offset
    from .geometry.positions import ROWS, position_tables

    model = drive.model
    belt = model.belt
    out = {}
    d_eff = effective_diameters(model) if (belt.profile or all(p.effective_diameter for p in model.pulleys)) else None
    if d_eff is not None:
        edl = effective_drive_length(drive.layout, d_eff)
        b = {"profile": belt.profile, "ribs": belt.ribs, "effective_drive_length": edl}
        if belt.effective_length is not None or belt.length_offset is not None:
            off = length_offset(model, drive.layout, d_eff)
            b.update(effective_length=belt.effective_length, length_tolerance=belt.length_tolerance,
                     wear_allowance=belt.wear_allowance, length_offset=off, required_length=edl - off)
        out["belt"] = b
        out["pulleys"] = {p.name: {"pitch_diameter": 2 * p.radius, "effective_diameter": float(d),
                                   "contact": "back" if p.side == "back" else "grooved",
                                   "speed_ratio": _ratio(drive, j)}
                          for j, (p, d) in enumerate(zip(model.pulleys, d_eff))}
    from .geometry.alignment import entry_angles, has_alignment

    if has_alignment(model):
        out["alignment"] = {"entry_angles": entry_angles(model, drive.layout),
                            "limit": model.criteria.entry_angle_max}
    tables = position_tables(drive)
    if tables:
        out["positions"] = {t.pulley: {
            "rows": {name: _position(r) for name, r in zip(ROWS, t.rows) if r is not None},
            "unreached": t.unreached, "take_up": t.take_up, "design_tension": t.design_tension,
            "length_offset": t.offset, "drawn_length": t.drawn_length,
            **({"installed": _position(t.installed)} if t.installed is not None else {})} for t in tables}
        from .geometry.part import length_warnings

        out["installation"] = _installation(drive, tables[0])
        out["warnings"] = length_warnings(drive, tables[0])
    if any(p.speed_time is not None for p in model.pulleys):
        import numpy as np

        from .steady.modes import crank_free_modes, drive_modes

        try:
            free, held = crank_free_modes(drive), drive_modes(drive)
            out["resonance"] = {"frequency_hz": free.frequencies_hz[0] if free.frequencies_hz else None,
                                "crank_held_hz": held.frequencies_hz[0] if held.frequencies_hz else None,
                                "participation": free.participation[0] if free.participation else {}}
        except (np.linalg.LinAlgError, ArithmeticError, ValueError) as exc:   # a drive with no elastic mode
            out["resonance_skipped"] = f"no rotational modes: {exc}"
    if model.duty_cycle is not None:
        from .steady.duty import duty_cycle
        from .steady.life import belt_life

        if model.duty_cycle.dynamic:
            dynamic_cost(drive)            # the held rows' steps, before the static rows are solved
        design = tables[0].design_tension if tables else _installation_tension(drive)
        rows = duty_cycle(drive, design)
        out["duty"] = {"design_tension": design, "idler_drag": model.duty_cycle.idler_drag,
                       "rows": [_duty_row(r) for r in rows]}
        if model.duty_cycle.dynamic:
            out["duty_dynamic"] = dynamic_duty(drive)
        if model.duty_cycle.tolerance and tables:
            out["tolerance"] = tolerance_study(drive, tables[0])
        if model.duty_cycle.acceleration is not None:
            from .steady.duty import acceleration_envelope

            out["acceleration"] = {"acceleration": model.duty_cycle.acceleration,
                                   "part_load": model.duty_cycle.part_load,
                                   "speeds": acceleration_envelope(drive, design)}
        if belt.ribs and belt.effective_length and d_eff is not None:
            life = belt_life(model, design, [r.belt_speed for r in rows])
            out["life"] = {"b10_hours": life.b10_hours, "pulley_share": life.pulley_share,
                           "row_share": life.row_share, "in_range": life.in_range,
                           "out_of_range": life.out_of_range,
                           "target_hours": (model.duty_cycle.life.target / 3600
                                            if model.duty_cycle.life.target is not None else None)}
        else:
            out["life_skipped"] = "belt life needs belt.ribs, belt.effective_length and effective diameters"
    return out


#: a duty row held in the rotational model: the crank ramps to the row's speed over RAMP, is held,
#: and the last WINDOW is read (the drive's slowest mode, the arm's at ~50 Hz, settles in it)
RAMP, HOLD, WINDOW = 0.2, 0.4, 0.2


def dynamic_duty(drive) -> list[dict]:
    """Each duty row from the dynamics: the rotational model (rotational/simulate.py) with the crank
    held at the row's speed (its declared speed orders on it) and the row's loads as viscous
    torques P / omega^2 (the row's power at its speed, opposing the motion as it ramps up): mean and
    peak hub loads, span tension bands, the arm's travel band and its stops, slip margins, the run's
    status and diagnostics. A first use (numba compiling the rotational kernels) says so on stderr,
    with how long it takes."""
    from .segments.compiled import compile_said

    with compile_said(f"compiling the rotational model's kernels for the duty cycle's dynamic rows (first use "
                      f"only: {COMPILE_SECONDS} s; later checks load them from numba's cache)"):
        return _dynamic_rows(drive)


#: seconds numba takes to compile the rotational kernels on a first check with duty_cycle.dynamic
#: (empty cache, examples/fead-ag0868.toml: measured over 360 s of wall, 110 s of CPU, on a shared 2-core machine)
COMPILE_SECONDS = "60-400"


def _dynamic_rows(drive) -> list[dict]:
    import numpy as np

    from ..core.errors import SolverError
    from ..core.window import in_window
    from .rotational.simulate import run

    model = drive.model
    dc = model.duty_cycle
    out = []
    for row in dc.rows:
        held = _held(drive, row)
        try:
            r = run(held)
        except SolverError as exc:
            out.append({"crank_speed": row.crank_speed, "status": "failed", "note": str(exc)})
            continue
        s, ds = r.summary, r.ds
        sel = in_window(ds["time"].values, ds.attrs.get("steady_window"))
        hub = ds["hub_load"].values[sel]
        names = [p.name for p in model.pulleys]
        e = {"crank_speed": row.crank_speed, "status": r.status,
             "diagnostics": [d.code for d in r.diagnostics],
             "hub_load_mean": {n: float(x) for n, x in zip(names, hub.mean(axis=0))},
             "hub_load_peak": {n: float(x) for n, x in zip(names, hub.max(axis=0))},
             "span_tension_min": {n: v["tension_min"] for n, v in s["spans"].items()},
             "span_tension_max": {n: v["tension_max"] for n, v in s["spans"].items()},
             "slip_margin": {n: v.get("slip_margin") for n, v in s["pulleys"].items()
                             if v.get("slip_margin") is not None and np.isfinite(v["slip_margin"])},
             "arm_travel": {n: [v["travel_min"], v["travel_max"]] for n, v in (s.get("tensioners") or {}).items()
                            if "travel_min" in v},
             "note": ""}
        out.append(e)
    return out


def _held(drive, row):
    """The model of a duty row held in the rotational model (dynamic_duty)."""
    from .steady.duty import belt_speed, crank_of, row_power

    model = drive.model
    dc = model.duty_cycle
    c = crank_of(model)
    lay = drive.layout
    w_c = math.copysign(row.crank_speed, model.pulleys[c].speed_time[-1][1] or 1.0)
    pulleys = []
    for j, p in enumerate(model.pulleys):
        if j == c:
            pulleys.append(p.model_copy(update={"speed_time": [[0.0, 0.0], [RAMP, w_c], [RAMP + HOLD, w_c]]}))
            continue
        w = abs(belt_speed(drive, row.crank_speed) / lay.rho[j])
        P = row_power(row, p.name, w, dc.idler_drag)
        pulleys.append(p.model_copy(update={
            "torque": 0.0, "torque_time": None, "torque_speed": None, "power": 0.0, "quadratic_torque": 0.0,
            "harmonics": [], "viscous_torque": P / w ** 2}))
    return model.model_copy(update={
        "pulleys": pulleys,
        "simulation": model.simulation.model_copy(update={"model": "rotational", "runup": "time",
                                                          "duration": RAMP + HOLD, "step": None}),
        "output": model.output.model_copy(update={"steady_window": (RAMP + HOLD - WINDOW, RAMP + HOLD)})})


def dynamic_cost(drive) -> None:
    """The held rows' integration steps together (each row's run is the same length on the same
    stable step: the first row's times the rows) against the steps limit, before any row is
    evaluated (report_data calls it before the static rows)."""
    from ..core.errors import ModelError
    from ..core.limits import steps_problem
    from .rotational.simulate import build, planned

    rows = drive.model.duty_cycle.rows
    held = _held(drive, rows[0])
    samples, per_sample = planned(held, build(held))
    problem = steps_problem(float(samples) * per_sample * len(rows), "duty_cycle.dynamic",
                            f"{len(rows)} held rows of {samples * per_sample} steps each (the rotational model over "
                            f"{RAMP + HOLD:g} s): fewer rows, or dynamic = false")
    if problem:
        raise ModelError(problem)


TOLERANCE_ROWS = ("replace", "max belt", "mean", "min belt")


def tolerance_study(drive, table) -> list[dict]:
    """The duty cycle at each reachable belt length of the position table (a replaced belt, the
    longest, the nominal, the shortest): the tensioner drawn at that row's position with that row's
    tension installed, both conventions. Per row: the smallest slip factor (fixed and running arm),
    the largest hub load of each pulley (fixed and running), the arm's smallest clearance to its
    stops at its running balance, and the duty rows the drive cannot carry."""
    from .. import replace
    from .geometry.drive import resolve
    from .geometry.positions import ROWS
    from .steady.duty import duty_cycle

    model = drive.model
    j = [p.name for p in model.pulleys].index(table.pulley)
    out = []
    for name, pos in zip(ROWS, table.rows):
        if name not in TOLERANCE_ROWS or pos is None:
            continue
        # the arm drawn at the row: its preload and stops follow again from the supplier data
        moved = replace(model, {f"pulleys.{j}.center": list(pos.centre), f"pulleys.{j}.arm.preload": 0.0,
                                f"pulleys.{j}.arm.stops": [-0.5, 0.5], "belt.pretension": pos.tension,
                                "belt.length": None, "duty_cycle.tolerance": False, "duty_cycle.dynamic": False})
        rows = duty_cycle(resolve(moved), pos.tension)
        fin = [x for r in rows for x in r.fixed_arm.slip_factor.values() if math.isfinite(x)]
        run = [x for r in rows if r.running_arm for x in r.running_arm.slip_factor.values() if math.isfinite(x)]
        clear = [min(q - lo, hi - q) / (hi - lo) for r in rows for n, q in r.arm_travel.items()
                 for lo, hi in [r.arm_stops[n]]]
        names = [p.name for p in model.pulleys]
        out.append({"position": name, "tension": pos.tension,
                    "slip_factor_fixed": min(fin, default=None), "slip_factor_running": min(run, default=None),
                    "hub_load_fixed": {n: max(r.fixed_arm.hub_load[n] for r in rows) for n in names},
                    "hub_load_running": {n: max((r.running_arm.hub_load[n] for r in rows if r.running_arm),
                                                default=math.nan) for n in names},
                    "stop_clearance": min(clear, default=math.nan),
                    "rows_not_carried": [r.crank_speed for r in rows if r.running_arm is None]})
    return out


def _ratio(drive, j) -> float:
    """Speed ratio to the crank (crank pitch radius over the pulley's), where a crank is set."""
    presc = [k for k, p in enumerate(drive.model.pulleys) if p.speed_time is not None]
    return drive.model.pulleys[presc[0]].radius / drive.model.pulleys[j].radius if presc else float("nan")


def _installation(drive, table) -> dict:
    """How the belt is installed and the lengths and tensions that relate the part to the run."""
    model, eq = drive.model, drive.equilibrium
    by = "pretension" if model.belt.pretension is not None else "part" if table.installed is not None else "length"
    from ..mechanics.layout import compute_layout

    return {"by": by, "unstretched_length": drive.installed_length,
            "rest_tension": float(eq.tension) if eq is not None else None,
            "path_length": compute_layout(eq.model).length if eq is not None else drive.layout.length}


def _installation_tension(drive) -> float:
    eq = drive.equilibrium
    if eq is not None:
        return float(eq.tension)
    if drive.model.belt.pretension is not None:
        return float(drive.model.belt.pretension)
    from .steady.creep import steady_state

    st = steady_state(drive.model, drive.layout, with_margins=False)
    return float(max(st.spans.values()))


def _relating(data, t) -> list[str]:
    """One paragraph relating the lengths and tensions check prints."""
    b, inst = data.get("belt", {}), data.get("installation", {})
    L = b.get("effective_length")
    if not L or not inst:
        return []
    mm = lambda x: f"{x * 1e3:.2f} mm"
    by = {"part": f"the part ({mm(L)} effective) installs the belt: the tensioner sits at the 'installed' row, where "
                  f"the required belt length is {mm(L)}, holding {t['installed']['tension']:.1f} N"
          if "installed" in t else "",
          "pretension": "belt.pretension installs the belt at the drawn layout",
          "length": "belt.length installs the belt"}[inst["by"]]
    text = (f"lengths and tensions: {by}. The required belt length is the effective drive length "
            f"(spans on pitch circles, wraps on effective diameters) less {mm(t['length_offset'])}; the drawn "
            f"tensioner (the 'mean' row, the supplier's design position and its design tension "
            f"{t['design_tension']:.1f} N) needs {mm(t['drawn_length'])}. The unstretched belt the dynamics "
            f"start from is {mm(inst['unstretched_length'])} (on pitch circles, sunk into the grooves, at rest)"
            + (f"; at rest it carries {inst['rest_tension']:.1f} N" if inst.get("rest_tension") else "")
            + f" on a path of {mm(inst['path_length'])} (pitch circles, the tensioner at rest).")
    return [text]


def _sf(factors) -> str:
    """The smallest slip safety factor of a row as printed ("-": no pulley carries a torque)."""
    return f"{min(factors):.2f}" if factors else "-"


def _position(r) -> dict:
    return {"rel": r.rel, "angle": r.angle, "travel": r.travel, "centre": list(r.centre), "edl": r.edl,
            "required_length": r.rebl, "wrap": r.wrap, "beta": r.beta, "spring_torque": r.spring_torque,
            "tension": r.tension, "hub_load": r.hub_load, "hub_direction": r.hub_direction}


def _cols(c) -> dict | None:
    if c is None:
        return None
    fin = lambda x: float(x) if math.isfinite(x) else None
    return {"spans": c.spans, "hub_load": c.hub_load, "hub_direction": c.hub_direction,
            "slip_factor": {k: fin(v) for k, v in c.slip_factor.items()}}


def _duty_row(r) -> dict:
    fin = lambda x: float(x) if math.isfinite(x) else None
    return {"crank_speed": r.crank_speed, "share": r.share, "belt_speed": r.belt_speed, "torques": r.torques,
            "fixed_arm": _cols(r.fixed_arm), "running_arm": _cols(r.running_arm), "arm_travel": r.arm_travel,
            "arm_stops": {k: list(v) for k, v in r.arm_stops.items()},
            "slip_margin": {k: fin(v) for k, v in r.slip_margin.items()}, "note": r.note}


def report_lines(data) -> list[str]:
    """The report's tables as the text of ``drivedyn check``, in the supplier's units (mm, deg, N, kW)."""
    lines = []
    if "belt" in data:
        b = data["belt"]
        head = f"belt: {b['ribs'] or ''}{b['profile'] or ''}"
        if b.get("effective_length"):
            head += (f"{b['effective_length'] * 1e3:.0f}, nominal effective length {b['effective_length'] * 1e3:.1f} mm "
                     f"+- {b['length_tolerance'] * 1e3:.1f} mm, wear allowance {100 * b['wear_allowance']:.2f} %")
        lines += ["", "supplier report (geometry/catalogue.py, positions.py; steady/duty.py, life.py)", head,
                  f"effective drive length {b['effective_drive_length'] * 1e3:.2f} mm"
                  + (f", required belt length {b['required_length'] * 1e3:.2f} mm (offset "
                     f"{b['length_offset'] * 1e3:.2f} mm)" if "required_length" in b else "")]
        lines.append(f"{'pulley':12s} {'pitch d mm':>10s} {'eff. d mm':>10s} {'contact':>8s} {'ratio':>7s}")
        for n, p in data["pulleys"].items():
            lines.append(f"{n:12s} {p['pitch_diameter'] * 1e3:10.2f} {p['effective_diameter'] * 1e3:10.2f} "
                         f"{p['contact']:>8s} {p['speed_ratio']:7.3f}")
    for name, t in data.get("positions", {}).items():
        lines += ["", f"tensioner {name}: position table (arm angle from the free arm, away from the belt)",
                  f"{'position':10s} {'rel deg':>8s} {'abs deg':>8s} {'X mm':>8s} {'Y mm':>8s} {'EDL mm':>8s} "
                  f"{'REBL mm':>8s} {'wrap deg':>8s} {'beta deg':>8s} {'T N':>7s} {'hub N':>7s} {'dir deg':>7s}"]
        for row, r in t["rows"].items():
            lines.append(f"{row:10s} {r['rel'] * DEG:8.2f} {r['angle'] * DEG % 360:8.2f} {r['centre'][0] * 1e3:8.2f} "
                         f"{r['centre'][1] * 1e3:8.2f} {r['edl'] * 1e3:8.2f} {r['required_length'] * 1e3:8.2f} "
                         f"{r['wrap'] * DEG:8.2f} {r['beta'] * DEG:8.2f} {r['tension']:7.1f} {r['hub_load']:7.1f} "
                         f"{r['hub_direction'] * DEG % 360:7.1f}")
        shown = dict(t["rows"], **({"installed": t["installed"]} if "installed" in t else {}))
        for row, r in list(shown.items())[len(t["rows"]):]:
            lines.append(f"{row:10s} {r['rel'] * DEG:8.2f} {r['angle'] * DEG % 360:8.2f} {r['centre'][0] * 1e3:8.2f} "
                         f"{r['centre'][1] * 1e3:8.2f} {r['edl'] * 1e3:8.2f} {r['required_length'] * 1e3:8.2f} "
                         f"{r['wrap'] * DEG:8.2f} {r['beta'] * DEG:8.2f} {r['tension']:7.1f} {r['hub_load']:7.1f} "
                         f"{r['hub_direction'] * DEG % 360:7.1f}")
        for row, why in t["unreached"].items():
            lines.append(f"{row:10s} not reached: {why}")
        lines.append(f"design tension {t['design_tension']:.1f} N; belt take-up {t['take_up'] * 1e3 / DEG:.3f} mm/deg")
        lines += _relating(data, t)
    if "duty" in data:
        du = data["duty"]
        names = list(data.get("pulleys") or du["rows"][0]["fixed_arm"]["hub_load"])
        lines += ["", f"duty cycle: hub loads N (fixed arm: the span into the tensioner held at "
                      f"{du['design_tension']:.1f} N, hub = vector sum of T | running arm: belt length kept, "
                      "T - m v^2), smallest slip safety factor fixed | running arm (the sign-off factor: the smaller of the two)"]
        lines.append(f"{'rpm':>6s} {'share':>6s} " + " ".join(f"{n[:11]:>11s}" for n in names) + f" {'min SF':>14s}")
        for r in du["rows"]:
            fa, ra = r["fixed_arm"], r["running_arm"]
            cells = []
            for n in names:
                cells.append(f"{fa['hub_load'][n]:5.0f}|" + (f"{ra['hub_load'][n]:<5.0f}" if ra else "  -  "))
            sf = [v for v in fa["slip_factor"].values() if v is not None]
            sfr = [v for v in (ra or {"slip_factor": {}})["slip_factor"].values() if v is not None]
            lines.append(f"{r['crank_speed'] * 30 / math.pi:6.0f} {100 * r['share']:5.1f}% " + " ".join(f"{c:>11s}" for c in cells)
                         + f" {_sf(sf):>6s}|{_sf(sfr) if ra else 'none':<6s}"
                         + (f"  {r['note']}" if r["note"] else ""))
        for n in (du["rows"][0]["arm_stops"] if du["rows"] else {}):
            lo, hi = du["rows"][0]["arm_stops"][n]
            tr = [r["arm_travel"].get(n) for r in du["rows"] if r["arm_travel"].get(n) is not None]
            if tr:
                pos = data.get("positions", {}).get(n)
                rel = ""
                if pos and "mean" in pos["rows"]:       # the supplier's convention, as in the position table
                    d = pos["rows"]["mean"]["rel"]
                    rel = (f"arm {(d - max(tr)) * DEG:.2f} to {(d - min(tr)) * DEG:.2f} deg from the free arm "
                           f"(load stop {(d - lo) * DEG:.2f} deg); ")
                lines.append(f"tensioner {n} running: {rel}travel {min(tr) * DEG:.2f} to {max(tr) * DEG:.2f} deg into the "
                             f"belt from the drawn position (stops {lo * DEG:.2f} / {hi * DEG:.2f} deg)")
    if "duty_dynamic" in data:
        dd = data["duty_dynamic"]
        names = list(data["duty"]["rows"][0]["fixed_arm"]["hub_load"]) if data.get("duty") else []
        lines += ["", "duty cycle from the dynamics (the rotational model held at each row, its speed orders on the "
                      "crank): hub loads mean / peak N, smallest slip margin, arm travel band deg, status"]
        for e in dd:
            if e["status"] == "failed":
                lines.append(f"{e['crank_speed'] * 30 / math.pi:6.0f}  failed: {e['note']}")
                continue
            arm = "; ".join(f"{n} {lo * DEG:.2f}..{hi * DEG:.2f}" for n, (lo, hi) in e["arm_travel"].items())
            sm = _sf(list(e["slip_margin"].values()))
            lines.append(f"{e['crank_speed'] * 30 / math.pi:6.0f}  "
                         + "  ".join(f"{n} {e['hub_load_mean'][n]:.0f}/{e['hub_load_peak'][n]:.0f}" for n in names)
                         + f"  margin {sm}  {arm}  {e['status']}"
                         + (f" ({', '.join(e['diagnostics'])})" if e["diagnostics"] else ""))
    if "tolerance" in data:
        lines += ["", "tolerance study: the duty cycle at each belt length of the position table (slip factor fixed | "
                      "running arm, largest hub loads fixed | running, the arm's clearance to its stops)"]
        for e in data["tolerance"]:
            hubs = "  ".join(f"{n} {e['hub_load_fixed'][n]:.0f}|{e['hub_load_running'][n]:.0f}" for n in e["hub_load_fixed"])
            sf = [e["slip_factor_fixed"]], [e["slip_factor_running"]]
            lines.append(f"{e['position']:10s} T {e['tension']:6.1f} N  SF {_sf([x for x in sf[0] if x is not None])}|"
                         f"{_sf([x for x in sf[1] if x is not None])}  {hubs}  clearance {100 * e['stop_clearance']:.0f} %"
                         + (f"  not carried at {', '.join(f'{w * 30 / math.pi:.0f}' for w in e['rows_not_carried'])} rpm"
                            if e["rows_not_carried"] else ""))
    if "alignment" in data:
        al = data["alignment"]
        lines += ["", f"belt entry angles (geometry/alignment.py), limit {al['limit'] * DEG:.2f} deg: "
                      + ", ".join(f"{n} {a.get('arriving', 0) * DEG:.2f} / {a.get('leaving', 0) * DEG:.2f} deg"
                                  for n, a in al["entry_angles"].items()) + " (arriving / leaving span, listed order)"]
    if "acceleration" in data:
        ac = data["acceleration"]
        lines += ["", f"slip safety factor under +-{ac['acceleration'] * 30 / math.pi:.0f} rpm/s of the crank (fixed arm; "
                      f"accessories at {100 * ac['part_load']:.0f} % and 100 % load, their inertias)",
                  f"{'rpm':>6s} {'part acc':>10s} {'part dec':>10s} {'full acc':>10s} {'full dec':>10s}  limiting"]
        for e in ac["speeds"]:
            keys = ("part_load_accelerating", "part_load_decelerating", "full_load_accelerating", "full_load_decelerating")
            worst = min(keys, key=lambda k: e[k]["slip_factor"])
            lines.append(f"{e['crank_speed'] * 30 / math.pi:6.0f} " + " ".join(f"{e[k]['slip_factor']:10.2f}" for k in keys)
                         + f"  {e[worst]['pulley']}")
    if data.get("resonance", {}).get("frequency_hz"):
        r = data["resonance"]
        lines += ["", f"system resonance (first rotational mode, the crank free on its inertia): {r['frequency_hz']:.2f} Hz "
                      f"(crank held: {r['crank_held_hz']:.2f} Hz); "
                      + ", ".join(f"{n} {100 * v:.0f} %" for n, v in r["participation"].items() if v > 0.05)]
    if "life" in data:
        li = data["life"]
        lines += ["", f"belt life B10 {li['b10_hours']:.0f} h (rib fatigue, steady/life.py: a fit to supplier reports"
                      + ("" if li["in_range"] else f"; {', '.join(li['out_of_range'])} outside its 79.6-175 mm range:"
                                                   " expect about 0.55 x") + ")"
                  + (f", target {li['target_hours']:.0f} h" if li["target_hours"] else ""),
                  "  pulley shares " + ", ".join(f"{n} {100 * v:.1f} %" for n, v in li["pulley_share"].items()),
                  "  duty row shares " + ", ".join(f"{100 * v:.0f} %" for v in li["row_share"])]
    return lines
