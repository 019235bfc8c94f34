"""Design criteria of a belt drive (``[criteria]`` of a belt-drive model) and their evaluation.

The defaults and where they come from are in docs/criteria.md; in short: slip 2 % (beyond the
creep of an elastic belt, 1 % or less at rated load, a V-ribbed belt slides over its whole arc),
slip margin 1.3 (the friction coefficient of rubber on steel scatters by about 25 % with humidity,
temperature and wear), smallest span tension less the centrifugal part 10 % of the installation
tension (no slack span), 10 % of the tensioner's stop-to-stop travel kept free at either end
(belt stretch and wear over the belt's life), no crossing of a span's first flap mode by an
excited crank order within 10 % of the run's speed range. Hub loads are judged only against a
bearing limit the user gives; crossings of the rotational modes are listed, judged only when a
number is given (the run computes the response through them; the slip, tension and hub-load
criteria judge its consequences).
"""
from __future__ import annotations

import math

import numpy as np

from ..core.criteria import Criterion
from .dynamics.frequencies import add_flap_and_modes, judged

RPM = 30 / math.pi


def speed_range(ds, summary, driver) -> tuple[float, float]:
    """The crank's speed range over the judged samples (rpm)."""
    sel = judged(ds)
    if "crank_rpm" in ds:
        n = ds["crank_rpm"].values[sel]
    else:
        n = np.abs(ds["speed"].sel(pulley=driver).values[sel]) * RPM
    return (float(n.min()), float(n.max())) if n.size else (0.0, 0.0)


def judged_speed_range(model, ds, summary, driver) -> tuple[float, float]:
    """The crank speeds the rotational resonances are listed over (rpm): the run's, widened to the
    duty cycle's rows where the model has one (the drive runs at those speeds in service)."""
    lo, hi = speed_range(ds, summary, driver)
    dc = getattr(model, "duty_cycle", None)
    if dc is not None and dc.rows:
        w = [abs(r.crank_speed) * RPM for r in dc.rows]
        lo, hi = (min(w), max(w)) if hi <= 0 else (min(lo, min(w)), max(hi, max(w)))
    return lo, hi


def add_supplier(model, result) -> None:
    """summary.supplier: the supplier's report tables (supplier.py), for a model that asks for them."""
    from . import supplier
    from ..core.errors import ModelError
    from .geometry.drive import resolve

    if "supplier" in result.summary or not supplier.wanted(model):
        return
    import numpy as np

    try:
        result.summary["supplier"] = supplier.report_data(resolve(model))
    except (ModelError, np.linalg.LinAlgError, ArithmeticError, ValueError) as exc:
        # after a finished run: the run's results stand, the report's tables say why they are missing
        result.summary["supplier_skipped"] = str(exc)


def _supplier_criteria(model, s, out, skipped):
    """The duty cycle's slip safety factors, the arm's running travel against its stops, rows the
    drive cannot carry, and B10 against the target life."""
    c = model.criteria
    sup = s.get("supplier") or {}
    if "supplier_skipped" in s:
        skipped["supplier"] = s["supplier_skipped"]
    duty = sup.get("duty")
    if duty:
        sfs = [(v, n, r["crank_speed"] * RPM, conv) for r in duty["rows"] for conv in ("fixed_arm", "running_arm")
               if r[conv] for n, v in r[conv]["slip_factor"].items() if v is not None and r["torques"].get(n)]
        if sfs:
            v, n, rpm, conv = min(sfs)
            out.append(Criterion("duty_slip_factor", v, c.slip_margin_min, "1", "min",
                                 "smallest sign-off slip factor of the duty cycle: per pulley and row the smaller of "
                                 "the fixed arm's (the supplier's) and the running arm's slip safety factor (the torque "
                                 "that slips the pulley over its whole wrap over the torque it carries)",
                                 f"{n} at {rpm:.0f} rpm ({conv.replace('_', ' ')})"))
        lost = [f"{r['crank_speed'] * RPM:.0f} rpm" for r in duty["rows"] if r["running_arm"] is None]
        out.append(Criterion("duty_rows_carried", len(lost), 0, "", "max",
                             "duty rows with no running balance (gross slip, a slack span, the arm on a stop)",
                             ", ".join(lost)))
        clear = []
        for r in duty["rows"]:
            for n, q in r["arm_travel"].items():
                lo, hi = r["arm_stops"][n]
                clear.append((min(q - lo, hi - q) / (hi - lo), n, r["crank_speed"] * RPM))
        if clear:
            v, n, rpm = min(clear)
            out.append(Criterion("duty_stop_clearance", v, c.stop_clearance_min, "1", "min",
                                 "free travel of the tensioner to its nearer stop at its running balance over the duty "
                                 "cycle, as a share of the stop-to-stop travel", f"{n} at {rpm:.0f} rpm"))
    dyn = sup.get("duty_dynamic")
    if dyn:
        bad = [f"{e['crank_speed'] * RPM:.0f} rpm ({e['status']})" for e in dyn if e["status"] != "success"]
        out.append(Criterion("duty_dynamic_rows", len(bad), 0, "", "max",
                             "duty rows whose held run (rotational model) did not end success", ", ".join(bad)))
        sm = [(v, n, e["crank_speed"] * RPM) for e in dyn if e["status"] != "failed"
              for n, v in e["slip_margin"].items()]
        if sm:
            v, n, rpm = min(sm)
            out.append(Criterion("duty_dynamic_slip_margin", v, c.slip_margin_min, "1", "min",
                                 "smallest slip margin of the duty rows held in the rotational model", f"{n} at {rpm:.0f} rpm"))
    tol = sup.get("tolerance")
    if tol:
        sf = [(min(x for x in (e["slip_factor_fixed"], e["slip_factor_running"]) if x is not None), e["position"])
              for e in tol if e["slip_factor_fixed"] is not None or e["slip_factor_running"] is not None]
        v, where = min(sf) if sf else (math.inf, "no pulley carries a torque")
        out.append(Criterion("tolerance_slip_factor", v, c.slip_margin_min, "1", "min",
                             "smallest sign-off slip factor of the duty cycle at any belt length of the tolerance "
                             "band and wear", f"{where} belt"))
        lost = [f"{e['position']}: {len(e['rows_not_carried'])}" for e in tol if e["rows_not_carried"]]
        out.append(Criterion("tolerance_rows_carried", sum(len(e["rows_not_carried"]) for e in tol), 0, "", "max",
                             "duty rows with no running balance at any belt length of the tolerance band and wear",
                             "; ".join(lost)))
    al = sup.get("alignment")
    if al:
        v, n = max((max(a.values()), n) for n, a in al["entry_angles"].items())
        out.append(Criterion("entry_angle", v, c.entry_angle_max, "rad", "max",
                             "largest belt entry angle on a pulley from offsets and misalignment", n))
    life = sup.get("life")
    if life and life.get("target_hours"):
        out.append(Criterion("belt_life", life["b10_hours"], life["target_hours"], "h", "min",
                             "B10 belt life by rib fatigue over the duty cycle (a fit to supplier reports)"
                             + ("" if life["in_range"] else ": outside the fit's pulley range"), ""))
    elif life:
        skipped["belt_life"] = "no target life given (duty_cycle.life.target)"


def _teeth_criteria(c, teeth, out, skipped):
    """A synchronous belt's teeth: the smallest jump margin, the jumps, the largest tooth load."""
    margins = [(p["jump_margin_min"], n) for n, p in teeth["pulleys"].items()
               if p.get("jump_margin_min") is not None and math.isfinite(p["jump_margin_min"])]
    if margins:
        v, n = min(margins)
        out.append(Criterion("jump_margin", v, c.jump_margin_min, "1", "min",
                             "smallest hold T p / R over outward push Q tan(phi - rho) of a tooth in mesh over the "
                             "steady window (below 1 it climbs)", n))
    else:
        skipped["jump_margin"] = "the flank is self-locking (flank angle at or below the flank friction angle): no jump"
    if teeth["jumps"] is None:
        skipped["tooth_jumps"] = ("the rotational model's teeth cannot change groove: its jump margin judges them "
                                  "(simulation.model = \"segments\" counts the jumps)")
    else:
        where = f"last at t = {teeth['last_jump_time']:.4g} s on {teeth['last_jump_pulley']}" if teeth["jumps"] else "none"
        out.append(Criterion("tooth_jumps", teeth["jumps"], c.tooth_jumps_max, "", "max",
                             "teeth that changed groove during the run (jumped)", where))
    pe = max(((p["phase_error_pp"], n) for n, p in teeth["pulleys"].items() if p.get("phase_error_pp") is not None),
             default=None)
    if c.phase_error_max is None:
        skipped["phase_error"] = "no phase error limit given (criteria.phase_error_max)"
    elif pe:
        out.append(Criterion("phase_error", pe[0], math.degrees(c.phase_error_max), "deg", "max",
                             "largest peak-to-peak transmission error of a grooved pulley against the first, in its "
                             "degrees, over the steady window", pe[1]))
    peak = max(((p["max_tooth_load"], n) for n, p in teeth["pulleys"].items()), default=None)
    if c.tooth_load_max is None:
        skipped["tooth_load"] = "no rated tooth load given (criteria.tooth_load_max)"
    elif peak:
        out.append(Criterion("tooth_load", peak[0], c.tooth_load_max, "N", "max",
                             "largest load of one tooth over the steady window", peak[1]))


def evaluate(model, result):
    """([Criterion], {name: why not judged}) for a belt run."""
    from .steady import flap as flapmod

    c = model.criteria
    add_flap_and_modes(model, result)
    add_supplier(model, result)
    s, ds = result.summary, result.ds
    out, skipped = [], {}
    ru = s.get("runup")
    driver = (ru or {}).get("crank") or s.get("driver")
    pulleys = s.get("pulleys", {})

    teeth = s.get("teeth")
    if teeth:
        # a synchronous belt does not slip on its grooved pulleys: their teeth are judged instead
        toothed = set(teeth["pulleys"])
        pulleys = {n: p for n, p in pulleys.items() if n not in toothed}
        _teeth_criteria(c, teeth, out, skipped)
    # slip: per bin for a run-up (never a mean over the swept window), else the steady window's
    if ru and ru.get("slip"):
        worst = max(((abs(v), n, b) for n, vs in ru["slip"].items() for b, v in enumerate(vs) if v is not None),
                    default=None)
        if worst:
            out.append(Criterion("slip_runup", worst[0], c.slip_max, "1", "max",
                                 "largest slip of any pulley against the crank in any run-up bin",
                                 f"{worst[1]} at {ru['speed_rpm'][worst[2]]:.0f} rpm"))
    else:
        sl = [(abs(p["slip"]), n) for n, p in pulleys.items() if n != driver and p.get("slip") is not None
              and math.isfinite(p["slip"])]
        if sl:
            v, n = max(sl)
            out.append(Criterion("slip_mean", v, c.slip_max, "1", "max",
                                 "largest mean slip of any pulley over the steady window", n))

    # gross slip, the driver's included: slip is measured against the crank, so a crank whose belt
    # slides over its wrap never shows in slip_mean / slip_runup; each model's gross-slip diagnostic
    # says where a belt leaves creep for sliding (segments/diagnose.py, rotational/simulate.py)
    # (the pulley: pulleys.<name>.sliding_share, or runup.<table>.<name>)
    gross = sorted({d.quantity.split(".")[1 if d.quantity.startswith("pulleys.") else -1]
                    for d in getattr(result, "diagnostics", []) if d.code == "gross-slip" and d.quantity.count(".") >= 2})
    if teeth:
        gross = [g for g in gross if g not in teeth["pulleys"]]
    out.append(Criterion("gross_slip", len(gross), c.gross_slip_max, "", "max",
                         "pulleys whose belt slides grossly over its wrap (the gross-slip diagnostic), the driver "
                         "included", ", ".join(gross) or "none"))

    # slip margin: the pulleys that carry torque (an idler's margin says nothing)
    if ru:
        skipped["slip_margin"] = "run-up: the slip per bin is judged instead (slip_runup)"
    else:
        torques = {n: abs(p.get("torque_mean") or 0.0) for n, p in pulleys.items()}
        big = max(torques.values(), default=0.0)
        loaded = [(p["slip_margin"], n) for n, p in pulleys.items() if p.get("slip_margin") is not None
                  and math.isfinite(p["slip_margin"]) and (n == driver or torques[n] > 0.05 * big)]
        if loaded:
            v, n = min(loaded)
            out.append(Criterion("slip_margin", v, c.slip_margin_min, "1", "min",
                                 "smallest slip margin of a pulley that carries torque: creep theory's load "
                                 "multiplier at gross slip for the run's mean loads and span tensions", n))

    # span tension less its centrifugal part
    m = model.belt.mass_per_length
    limit = c.span_tension_min if c.span_tension_min is not None else 0.1 * (model.belt.pretension or 0.0)
    names = ds["pulley"].values.tolist()
    r = float(ds["pulley_radius"].values[names.index(driver)]) if driver in names else float("nan")
    cands = []
    if ru:
        for sp, vs in ru["span_tension_min"].items():
            for b, v in enumerate(vs):
                vb = ru["speed_rpm"][b] / RPM * r
                cands.append((v - m * vb ** 2, sp, f" at {ru['speed_rpm'][b]:.0f} rpm"))
    else:
        w = abs(pulleys.get(driver, {}).get("speed_mean") or 0.0)
        for sp, e in s.get("spans", {}).items():
            if e.get("tension_min") is not None:
                cands.append((e["tension_min"] - m * (w * r) ** 2, sp, ""))
    if cands:
        v, sp, at = min(cands)
        out.append(Criterion("span_tension", v, limit, "N", "min",
                             "smallest span tension less the centrifugal tension m v^2 (no slack span)", sp + at))

    # tensioner travel against its stops
    for p in model.pulleys:
        t = getattr(p, "arm", None) or getattr(p, "slider", None)
        if t is None or not hasattr(t, "stops"):
            continue
        var, dim = ("arm_travel", "arm") if p.arm is not None else ("slider_travel", "slider")
        if var not in ds or p.name not in ds[dim].values.tolist():
            continue
        q = ds[var].sel({dim: p.name}).values[judged(ds)]
        if not q.size:
            continue
        lo, hi = t.stops
        free = min(float(q.min()) - lo, hi - float(q.max())) / (hi - lo)
        out.append(Criterion("stop_clearance", free, c.stop_clearance_min, "1", "min",
                             "free travel of the tensioner to its nearer stop, as a share of the stop-to-stop "
                             "travel", p.name))

    # hub loads against a bearing limit
    if c.hub_load_max is not None:
        h = ds["hub_load"].values[judged(ds)]
        if h.size:
            k = int(np.argmax(h.max(axis=0)))
            out.append(Criterion("hub_load", float(h[:, k].max()), c.hub_load_max, "N", "max",
                                 "peak hub load of any pulley", names[k]))
    else:
        skipped["hub_load"] = "no bearing limit given (criteria.hub_load_max)"

    # span flap
    fl = s.get("flap")
    if fl and fl.get("spans"):
        orders = flapmod.excited_orders(model, driver, c.flap_amplitude_min, c.flap_orders)
        lo, hi = speed_range(ds, s, driver)
        rng = (lo * (1 - c.flap_speed_margin), hi * (1 + c.flap_speed_margin))
        if orders:
            amp, mean, end = _run_readers(ds, s)
            xs = flapmod.judged_crossings(model, fl, orders, rng, c.flap_damping_ratio, amp, mean, end)
            counted = [x for x in xs if x["counted"]]
            out.append(Criterion("flap_crossings", len(counted), c.flap_crossings_max, "", "max",
                                 f"crossings of a span's first flap mode by crank orders {_orders(orders)} within "
                                 f"{rng[0]:.0f}-{rng[1]:.0f} rpm that excite the span: directly (k n = f1, an end "
                                 f"moving with a tensioner) or parametrically (k n = 2 f1, tension modulation above "
                                 f"4 zeta, zeta {c.flap_damping_ratio:g})",
                                 "; ".join(_flap_where(x) for x in counted[:4])
                                 + (f"; {len(counted) - 4} more" if len(counted) > 4 else ""), xs))
            rest = [x for x in xs if not x["counted"]]
            if rest:
                skipped["flap_crossings_listed"] = (
                    f"{len(rest)} crossings listed, not counted: "
                    + "; ".join(f"{x['span']} order {_o(x['order'])} at {x['rpm']:.0f} rpm ({x['kind']}: {x['note']})"
                                for x in rest[:4]) + (f"; {len(rest) - 4} more" if len(rest) > 4 else ""))
        elif flapmod.excited_orders(model, driver, 0.0, c.flap_orders):
            skipped["flap_crossings"] = (f"not judged: every speed order of the crank is weaker than "
                                         f"criteria.flap_amplitude_min ({c.flap_amplitude_min:.4g} rad/s)")
        else:
            skipped["flap_crossings"] = "the crank declares no speed orders (criteria.flap_orders names more)"

    # span stability from the run: each span's tension fluctuation on its Mathieu tongues
    st = s.get("span_stability")
    if st and st.get("spans"):
        out.append(_span_stability(st, c))
    elif "span_stability" not in s:
        skipped["span_stability"] = "no steady window or run-up bins to read the span tensions from"

    # rotational resonances inside the speed range
    modes = s.get("modes", {}).get("frequencies_hz")
    if modes:
        orders = flapmod.excited_orders(model, driver, c.flap_amplitude_min, c.flap_orders)
        lo, hi = judged_speed_range(model, ds, s, driver)
        over = "the run's speeds" + (" and the duty cycle's" if model.duty_cycle is not None else "")
        xs = [{"mode": i + 1, "order": k, "rpm": 60 * f / k, "frequency_hz": f}
              for i, f in enumerate(modes) for k in orders if lo <= 60 * f / k <= hi]
        if c.resonance_crossings_max is not None:
            out.append(Criterion("resonance_crossings", len(xs), c.resonance_crossings_max, "", "max",
                                 f"crossings of the drive's rotational modes by the crank orders inside "
                                 f"{lo:.0f}-{hi:.0f} rpm ({over})", "; ".join(f"mode {x['mode']} ({x['frequency_hz']:.0f} Hz) order "
                                                          f"{_o(x['order'])} at {x['rpm']:.0f} rpm" for x in xs[:4]), xs))
        else:
            skipped["resonance_crossings"] = (f"listed, not judged ({len(xs)} inside {lo:.0f}-{hi:.0f} rpm; "
                                              "criteria.resonance_crossings_max judges them)")
    _supplier_criteria(model, s, out, skipped)
    return out, skipped


def _span_stability(st, c):
    """Criterion: spans inside a tongue (dynamics/span_stability.py), where: those spans, else the
    nearest one and how far."""
    spans = st["spans"]

    def at(n, e):
        x = e.get("nearest") or {}
        rpm = f" at {e['rpm']:.0f} rpm" if e.get("rpm") is not None else ""
        what = (f"{x.get('frequency', float('nan')):.1f} Hz against tongue {x.get('tongue')} "
                f"(2 f1 / {x.get('tongue')} = {x.get('tongue_centre', float('nan')):.1f} Hz)")
        if e.get("inside"):
            return f"{n}{rpm}: {what}, inside"
        d = e.get("tongue_distance")
        state = "open" if x.get("open") else "closed at this depth"
        return f"{n}{rpm}: {what}, {state}, {100 * d:.0f} % off" if d is not None else f"{n}: {e.get('note', '')}"

    inside = st.get("inside", [])
    if inside:
        where = "; ".join(at(n, spans[n]) for n in inside[:4]) + (f"; {len(inside) - 4} more" if len(inside) > 4 else "")
    elif st.get("nearest_span"):
        where = "nearest: " + at(st["nearest_span"], spans[st["nearest_span"]])
    else:
        where = ""
    return Criterion("span_stability", len(inside), c.parametric_spans_max, "", "max",
                     "spans inside a parametric-resonance tongue: a component of the run's span tension at the "
                     "frequency and depth where the span's transverse motion grows (Mathieu tongues with damping "
                     f"ratio {c.flap_damping_ratio:g}, principal and next)", where)


def _flap_where(x):
    if x["kind"] == "direct":
        return (f"{x['span']} order {_o(x['order'])} at {x['rpm']:.0f} rpm ({x['frequency_hz']:.0f} Hz, direct: "
                f"{x['note']}, about {1e3 * x['amplitude']:.1f} mm at resonance)")
    return (f"{x['span']} order {_o(x['order'])} at {x['rpm']:.0f} rpm ({x['frequency_hz']:.0f} Hz = 2 f1, "
            f"parametric: {x['note']})")


def _run_readers(ds, s):
    """(tension_amp(span, order, rpm), tension_mean(span, rpm), end_amp(tensioner, order, rpm)) from a
    run: a run-up's order tables between its bins; a steady run's half bands (an order's amplitude is
    at most the half band: conservative)."""
    ru = s.get("runup")
    if ru and "runup_tension_order" in ds and "speed_bin" in ds.coords:
        rpm = np.asarray(ds["speed_bin"].values, float)
        order = [float(k) for k in np.atleast_1d(ds["order"].values)] if "order" in ds.coords else []
        up = np.argsort(rpm)

        def at(values, n):
            return float(np.interp(n, rpm[up], np.asarray(values, float)[up]))

        def amp(span, k, n):
            if float(k) in order:
                return at(ds["runup_tension_order"].sel(span=span).values[:, order.index(float(k))], n)
            return 0.5 * (at(ds["runup_tension_max"].sel(span=span).values, n)
                          - at(ds["runup_tension_min"].sel(span=span).values, n))

        def mean(span, n):
            return at(ds["runup_tension_mean"].sel(span=span).values, n)

        def end(name, k, n):
            if "runup_arm_travel_order" in ds and name in ds["arm"].values.tolist() and float(k) in order:
                return at(ds["runup_arm_travel_order"].sel(arm=name).values[:, order.index(float(k))], n)
            if "runup_arm_travel_max" in ds and "arm" in ds.coords and name in ds["arm"].values.tolist():
                return 0.5 * (at(ds["runup_arm_travel_max"].sel(arm=name).values, n)
                              - at(ds["runup_arm_travel_min"].sel(arm=name).values, n))
            return 0.0
        return amp, mean, end
    spans, ten = s.get("spans", {}), s.get("tensioners", {})

    def amp(span, k, n):
        e = spans.get(span, {})
        return 0.5 * (e.get("tension_max", 0.0) - e.get("tension_min", 0.0))

    def mean(span, n):
        return spans.get(span, {}).get("tension_mean", 0.0)

    def end(name, k, n):
        e = ten.get(name, {})
        return 0.5 * (e.get("travel_max", 0.0) - e.get("travel_min", 0.0))
    return amp, mean, end


def _o(k):
    return f"{k:g}"


def _orders(orders):
    return ", ".join(_o(k) for k in orders)


def judge_check(model, data: dict) -> dict:
    """The verdict of what ``check`` computes (statics.check_data's ``data``): the supplier report's
    criteria (the duty cycle's slip factors, rows carried and stop clearance, belt life, entry
    angles, the tolerance study; ``_supplier_criteria``), and the warnings check found. Returns
    {"verdict", "criteria", "criteria_skipped", "warnings"}, the verdict "not judged" where the model
    asks for none of these (a model without a duty cycle: the run judges it)."""
    from ..core.criteria import verdict_of

    out, skipped = [], {}
    _supplier_criteria(model, {"supplier": data["supplier"]} if "supplier" in data else {}, out, skipped)
    warnings = [n[len("warning: "):] for n in data.get("steady", {}).get("notes", []) if n.startswith("warning: ")]
    sup = data.get("supplier") or {}
    life = sup.get("life")
    if life and not life["in_range"]:
        warnings.append(f"belt life: {', '.join(life['out_of_range'])} outside the fit's 79.6-175 mm effective "
                        "diameters: its B10 is about 0.55 x the supplier's there (steady/life.py)")
    for name, t in (sup.get("positions") or {}).items():
        for row, why in t["unreached"].items():
            warnings.append(f"tensioner {name}: the {row} row is not reached: {why}")
    warnings += sup.get("warnings", [])
    if not out:
        skipped.setdefault("check", "no duty cycle, belt life, alignment or tolerance study to judge: "
                                    "'drivedyn run' judges the dynamics")
    return {"verdict": verdict_of(out, "success"), "criteria": {c.name: c.to_dict() for c in out},
            **({"criteria_skipped": skipped} if skipped else {}), "warnings": warnings}


def verdict_lines(head: dict) -> list[str]:
    """The check's verdict as text: the verdict, one line per criterion, the warnings."""
    from ..core.criteria import rows

    crit = rows(head)
    bad = [r["name"] for r in crit if not r["ok"]]
    lines = [f"verdict: {head['verdict']}" + (f" ({len(bad)} of {len(crit)} criteria failed: {', '.join(bad)})" if bad
                                               else f" ({len(crit)} criteria)" if crit else "")]
    if crit:
        w = max(len(r["name"]) for r in crit)
        for r in crit:
            where = f" at {r['where']}" if r["where"] else ""
            lines.append(f"  {r['pass']:4s} {r['name']:{w}s} {r['value']:>8s} {r['unit']:3s} (limit {r['limit']}){where}: "
                         f"{r['text']}")
    for k, v in (head.get("criteria_skipped") or {}).items():
        lines.append(f"  not judged: {k}: {v}")
    for w in head["warnings"]:
        lines.append(f"  warning: {w}")
    return lines
