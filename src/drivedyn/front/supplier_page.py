"""The first pages of report.html for a drive with a supplier's report (summary.supplier, written
by belt/supplier.py): the results an engineer signs (belt part, design tension, B10 against its
target, the smallest sign-off slip factor and where, the arm against its stops), then the tables in
a supplier report's order: layout, tensioner positions, the duty cycle's span tensions, hub loads
and slip factors, the tolerance and acceleration tables, the resonance and the belt life's shares.
Every number is laid out from the summary, none recomputed (the layout's spans and wraps are the
drawn geometry of the model file). Tables as overview.py's: ``{"title", "head", "rows", "note"}``.

The **sign-off slip factor** of a pulley in a duty row is the smaller of the two conventions'
(docs/supplier-report.md): the supplier's fixed arm and the arm at its running balance (creep
theory, in practice the smaller); it is what the verdict's duty_slip_factor judges.
"""
from __future__ import annotations

from .overview import DEG, RPM, _f

SIGN_OFF = ("sign-off slip factor: the smaller of the fixed-arm (the supplier's) and the running-arm factor of the "
            "pulley in the row, as the verdict's duty_slip_factor judges it")


def wanted(summary: dict) -> bool:
    sup = summary.get("supplier") or {}
    return bool(sup.get("duty") or sup.get("positions"))


def sign_off(row: dict, name: str):
    """The sign-off slip factor of pulley ``name`` in a duty row (None: no factor in either convention)."""
    vals = [row[c]["slip_factor"].get(name) for c in ("fixed_arm", "running_arm") if row.get(c)]
    vals = [v for v in vals if v is not None]
    return min(vals) if vals else None


def _mm(v, digits=1):
    return _f(None if v is None else 1e3 * v, f"{{:.{digits}f}}")


def _rel(pos: dict | None, travel):
    """An arm's travel from the drawn position (into the belt +) as degrees from the free arm, the
    position table's convention (the drawn arm is the table's mean row)."""
    if pos is None or "mean" not in pos["rows"] or travel is None:
        return None
    return (pos["rows"]["mean"]["rel"] - travel) * DEG


def results(summary: dict) -> list[list[str]]:
    """The results block: [quantity, value, limit, where / how] rows."""
    sup = summary["supplier"]
    crit = summary.get("criteria") or {}
    out = []
    b = sup.get("belt") or {}
    if b.get("effective_length"):
        part = f"{b.get('ribs') or ''}{b.get('profile') or ''}{b['effective_length'] * 1e3:.0f}"
        out.append(["belt", part, "", (f"nominal effective length {_mm(b['effective_length'])} mm +- "
                    f"{_mm(b['length_tolerance'])} mm, wear allowance {100 * b['wear_allowance']:.2f} %")])
    pos = next(iter((sup.get("positions") or {}).items()), None)
    if pos:
        name, t = pos
        out.append(["design tension", f"{t['design_tension']:.1f} N", "",
                    f"tensioner {name} at its mean (drawn) position, {t['rows']['mean']['rel'] * DEG:.2f} deg from "
                    "the free arm" if "mean" in t["rows"] else ""])
        if "installed" in t:
            r = t["installed"]
            out.append(["installed tension", f"{r['tension']:.1f} N", "",
                        (f"the part installed: the arm at {r['rel'] * DEG:.2f} deg from the free arm, where the "
                        f"required belt length is the part's")])
    life = sup.get("life")
    if life:
        c = crit.get("belt_life")
        out.append(["belt life B10", f"{life['b10_hours']:.0f} h",
                    f">= {life['target_hours']:.0f} h" if life.get("target_hours") else "no target",
                    ("pass" if c["pass"] else "FAIL") if c else "not judged"])
    c = crit.get("duty_slip_factor")
    if c:
        out.append(["smallest sign-off slip factor", f"{c['value']:.2f}", f">= {c['limit']:.2f}",
                    f"{c['where']}: {'pass' if c['pass'] else 'FAIL'}"])
    duty = sup.get("duty")
    if duty and duty["rows"]:
        fixed = [(v, n, r["crank_speed"]) for r in duty["rows"] for n, v in r["fixed_arm"]["slip_factor"].items()
                 if v is not None and r["torques"].get(n)]
        if fixed:
            v, n, w = min(fixed)
            out.append(["smallest fixed-arm slip factor", f"{v:.2f}", "",
                        (f"{n} at {w * RPM:.0f} rpm: the supplier's convention, not signed on (the arm's running "
                        "balance slackens the spans)")])
        n_rows = len(duty["rows"])
        lost = [r for r in duty["rows"] if r["running_arm"] is None]
        out.append(["duty rows carried", f"{n_rows - len(lost)} of {n_rows}", f"{n_rows} of {n_rows}",
                    "; ".join(f"{r['crank_speed'] * RPM:.0f} rpm: {r['note']}" for r in lost) or "pass"])
    c = crit.get("tolerance_slip_factor")
    if c:
        out.append(["over the belt's tolerance and wear", f"{c['value']:.2f}", f">= {c['limit']:.2f}",
                    f"smallest sign-off slip factor, at the {c['where']}: {'pass' if c['pass'] else 'FAIL'}"])
    out += _arm_rows(sup, crit)
    hubs = _largest_hubs(duty)
    if hubs:
        out.append(["largest hub loads", ", ".join(f"{n} {v:.0f}" for n, v in hubs.items()) + " N", "",
                    "over the duty cycle, the larger of the fixed and running arm"])
    res = sup.get("resonance") or {}
    if res.get("frequency_hz"):
        out.append(["system resonance", f"{res['frequency_hz']:.1f} Hz", "",
                    f"first rotational mode, the crank free on its inertia ({res['crank_held_hz']:.1f} Hz held)"])
    return out


def _arm_rows(sup, crit) -> list[list[str]]:
    duty = sup.get("duty")
    if not duty or not duty["rows"]:
        return []
    out = []
    positions = sup.get("positions") or {}
    for n, (lo, hi) in duty["rows"][0]["arm_stops"].items():
        tr = [r["arm_travel"][n] for r in duty["rows"] if r["arm_travel"].get(n) is not None]
        if not tr:
            continue
        pos = positions.get(n)
        a, b = _rel(pos, max(tr)), _rel(pos, min(tr))
        c = crit.get("duty_stop_clearance")
        clear = f"; nearest stop {100 * c['value']:.0f} % of the travel away ({c['where']})" if c else ""
        if a is not None:
            out.append([f"tensioner {n} running", f"{_f(a, '{:.2f}')} .. {_f(b, '{:.2f}')} deg",
                        f"{_f(_rel(pos, hi), '{:.1f}')} .. {_f(_rel(pos, lo), '{:.1f}')} deg",
                        (f"arm from the free arm over the duty cycle, against its stops (free-arm side .. load stop)"
                        f"{clear}")])
        else:
            out.append([f"tensioner {n} running", f"{_f(min(tr) * DEG, '{:.2f}')} .. {_f(max(tr) * DEG, '{:.2f}')} deg",
                        f"{_f(lo * DEG, '{:.1f}')} .. {_f(hi * DEG, '{:.1f}')} deg",
                        f"travel from the drawn position, into the belt positive, against its stops{clear}"])
    return out


def _largest_hubs(duty) -> dict:
    if not duty or not duty["rows"]:
        return {}
    names = list(duty["rows"][0]["fixed_arm"]["hub_load"])
    return {n: max(max(r["fixed_arm"]["hub_load"][n], (r["running_arm"] or {"hub_load": {n: 0.0}})["hub_load"][n])
                   for r in duty["rows"]) for n in names}


def tables(summary: dict, model=None) -> list[dict]:
    """The supplier report's tables in its order (after the results block)."""
    sup = summary["supplier"]
    out = []
    lay = _layout(sup, model)
    if lay:
        out.append(lay)
    out += _positions(sup)
    duty = sup.get("duty")
    if duty and duty["rows"]:
        out += _duty(sup, duty)
    if sup.get("tolerance"):
        out.append(_tolerance(sup["tolerance"]))
    if sup.get("acceleration"):
        out.append(_acceleration(sup["acceleration"]))
    res = sup.get("resonance") or {}
    if res.get("frequency_hz"):
        part = ", ".join(f"{n} {100 * v:.0f} %" for n, v in res["participation"].items() if v > 0.05)
        out.append({"title": "system resonance", "head": ["mode", "crank free (Hz)", "crank held (Hz)", "taking part"],
                    "rows": [["1", f"{res['frequency_hz']:.2f}", _f(res.get("crank_held_hz"), "{:.2f}"), part or "-"]],
                    "note": "the first rotational mode of the drive at rest with the crank's inertia (the supplier's "
                            "Mode 1) and with the crank held; taking part: shares of the mode's kinetic energy"})
    if sup.get("life"):
        out += _life(sup["life"], sup, duty)
    return out


def _layout(sup, model) -> dict | None:
    pulleys = sup.get("pulleys")
    if not pulleys:
        return None
    wraps, spans = {}, {}
    if model is not None:
        from ..mechanics.layout import compute_layout

        lay = compute_layout(model)
        wraps = dict(zip(lay.names, lay.wrap.tolist()))
        spans = {lay.names[sp.start]: (sp.name, sp.length) for sp in lay.spans}
    rows = []
    for n, p in pulleys.items():
        sp = spans.get(n)
        rows.append([n, p["contact"], _mm(p["pitch_diameter"], 2), _mm(p["effective_diameter"], 2),
                     _f(p["speed_ratio"], "{:.3f}"), _f(wraps.get(n) and wraps[n] * DEG, "{:.1f}"),
                     sp[0] if sp else "-", _mm(sp[1]) if sp else "-"])
    b = sup.get("belt") or {}
    note = (f"effective drive length {_mm(b.get('effective_drive_length'), 2)} mm (spans on pitch circles, wraps on "
            "effective diameters)") if b else ""
    if "required_length" in b:
        note += (f", required belt length {_mm(b['required_length'], 2)} mm (less the offset "
                 f"{_mm(b['length_offset'], 2)} mm)")
    note += ("; speed ratio: the crank's pitch diameter over the pulley's; wraps and spans as drawn (the tensioner at "
             "its drawn position), each span leaving the pulley of its row")
    return {"title": "layout", "head": ["pulley", "contact", "pitch d (mm)", "effective d (mm)", "speed ratio",
                                        "wrap (deg)", "span", "span length (mm)"], "rows": rows, "note": note}


def _positions(sup) -> list[dict]:
    out = []
    for name, t in (sup.get("positions") or {}).items():
        shown = dict(t["rows"], **({"installed": t["installed"]} if "installed" in t else {}))
        rows = [[row, _f(r["rel"] * DEG, "{:.2f}"), _f(r["angle"] * DEG % 360, "{:.2f}"), _mm(r["centre"][0]),
                 _mm(r["centre"][1]), _mm(r["edl"]), _mm(r["required_length"]), _f(r["wrap"] * DEG, "{:.1f}"),
                 _f(r["beta"] * DEG, "{:.1f}"), _f(r["spring_torque"], "{:.2f}"), _f(r["tension"], "{:.1f}"),
                 _f(r["hub_load"], "{:.1f}"), _f(r["hub_direction"] * DEG % 360, "{:.1f}")] for row, r in shown.items()]
        rows += [[row, "not reached: " + why] + [""] * 11 for row, why in t["unreached"].items()]
        note = (f"design tension (the mean row) {t['design_tension']:.1f} N, belt take-up {t['take_up'] * 1e3 / DEG:.3f} "
                "mm/deg; arm: degrees from the free arm (no belt); abs: the arm's angle, pivot to pulley centre, "
                "counter-clockwise from +x; REBL: the required effective belt length"
                + ("; installed: where the part's length puts the arm" if "installed" in t else ""))
        out.append({"title": f"tensioner {name}: positions", "head": [
            "position", "arm (deg)", "abs (deg)", "X (mm)", "Y (mm)", "EDL (mm)", "REBL (mm)", "wrap (deg)",
            "hub-arm (deg)", "spring (N m)", "tension (N)", "hub load (N)", "hub dir (deg)"], "rows": rows, "note": note})
    return out


def _duty(sup, duty) -> list[dict]:
    rows = duty["rows"]
    spans = list(rows[0]["fixed_arm"]["spans"])
    names = list(rows[0]["fixed_arm"]["hub_load"])
    pos = sup.get("positions") or {}

    def lead(r):
        return [f"{r['crank_speed'] * RPM:.0f}", f"{100 * r['share']:.1f}", f"{abs(r['belt_speed']):.2f}"]

    def pair(r, key, n, fmt="{:.0f}"):
        ra = r["running_arm"]
        return f"{_f(r['fixed_arm'][key][n], fmt)} | " + (_f(ra[key][n], fmt) if ra else "none")

    head = ["crank (rpm)", "share (%)", "belt (m/s)"]
    conv = ("fixed arm | running arm. Fixed arm (the supplier's convention): the span into the tensioner held at "
            f"{duty['design_tension']:.1f} N; running arm: the installed belt length kept and the arm at its running "
            "balance (creep theory; none: the row has no running balance, see its note)")
    arms = list(rows[0]["arm_stops"])
    span_rows = [lead(r) + [pair(r, "spans", sp) for sp in spans] + [r["note"] or "-"] for r in rows]
    hub_rows = []
    for r in rows:
        cells = lead(r) + [pair(r, "hub_load", n) for n in names]
        for n in arms:
            q = r["arm_travel"].get(n)
            rel = _rel(pos.get(n), q)
            cells.append(_f(rel, "{:.2f}") if rel is not None else _f(None if q is None else q * DEG, "{:.2f}"))
        hub_rows.append(cells)
    arm_head = [f"{n} arm (deg)" for n in arms]
    arm_note = ("; arm: the running arm's angle from the free arm, as in the positions table" if arms and all(
        "mean" in (pos.get(n) or {}).get("rows", {}) for n in arms) else
        "; arm: the running travel from the drawn position, into the belt positive" if arms else "")
    sf_rows = []
    for r in rows:
        cells = lead(r)
        for n in names:
            so = sign_off(r, n)
            cells.append(f"{_f(so, '{:.2f}')} ({_f(r['fixed_arm']['slip_factor'].get(n), '{:.2f}')})"
                         if r["torques"].get(n) else "no load")
        cells.append(r["note"] or "-")
        sf_rows.append(cells)
    return [
        {"title": "duty cycle: span tensions", "head": head + [f"{sp} (N)" for sp in spans] + ["note"],
         "rows": span_rows, "note": "span tension " + conv},
        {"title": "duty cycle: hub loads", "head": head + [f"{n} (N)" for n in names] + arm_head, "rows": hub_rows,
         "note": "hub load " + conv + "; hub loads running from T - m v^2 (the wrapped belt carries its centrifugal "
                 "tension itself)" + arm_note},
        {"title": "duty cycle: sign-off slip factors", "head": head + [f"{n}" for n in names] + ["note"],
         "rows": sf_rows,
         "note": SIGN_OFF + "; in brackets the fixed-arm factor (the supplier's). A slip safety factor: the torque that "
                 "slips the pulley over its whole wrap over the torque it carries; no load: the pulley carries no torque"},
    ]


def _tolerance(tol) -> dict:
    names = list(tol[0]["hub_load_fixed"])
    rows = []
    for e in tol:
        vals = [x for x in (e["slip_factor_fixed"], e["slip_factor_running"]) if x is not None]
        rows.append([e["position"], f"{e['tension']:.1f}", _f(min(vals) if vals else None, "{:.2f}"),
                     _f(e["slip_factor_fixed"], "{:.2f}")]
                    + [f"{_f(e['hub_load_fixed'][n], '{:.0f}')} | {_f(e['hub_load_running'][n], '{:.0f}')}" for n in names]
                    + [_f(100 * e["stop_clearance"], "{:.0f}"),
                       ", ".join(f"{w * RPM:.0f} rpm" for w in e["rows_not_carried"]) or "all"])
    return {"title": "tolerance: the duty cycle at each belt length", "head": [
        "belt", "tension (N)", "sign-off slip factor", "fixed arm", *[f"{n} hub (N)" for n in names],
        "stop clearance (%)", "rows carried"], "rows": rows,
        "note": "each reachable row of the positions table (a replaced belt, the longest, the nominal, the shortest), "
                "its tension installed; the smallest slip factor over the duty rows and pulleys (" + SIGN_OFF
                + "), the largest hub loads fixed | running arm, the arm's smallest clearance to its stops running"}


def _acceleration(ac) -> dict:
    keys = ("part_load_accelerating", "part_load_decelerating", "full_load_accelerating", "full_load_decelerating")
    rows = []
    for e in ac["speeds"]:
        worst = min(keys, key=lambda k: e[k]["slip_factor"])
        rows.append([f"{e['crank_speed'] * RPM:.0f}"] + [_f(e[k]["slip_factor"], "{:.2f}") for k in keys]
                    + [e[worst]["pulley"]])
    pct = f"{100 * ac['part_load']:.0f} %"
    return {"title": f"slip under +-{ac['acceleration'] * RPM:.0f} rpm/s of the crank", "head": [
        "crank (rpm)", f"{pct} load, speeding up", f"{pct}, slowing down", "full load, speeding up",
        "full, slowing down", "limiting pulley"], "rows": rows,
        "note": "the smallest slip safety factor of the pulleys with the arm fixed (the supplier's convention) while the "
                "crank speeds up or slows down, every pulley's inertia torque on top of its load"}


def _life(life, sup, duty) -> list[dict]:
    pulleys = sup.get("pulleys") or {}
    rows = [[n, pulleys.get(n, {}).get("contact", "-"), _mm(pulleys.get(n, {}).get("effective_diameter"), 2),
             f"{100 * v:.1f}"] for n, v in life["pulley_share"].items()]
    note = (f"B10 {life['b10_hours']:.0f} h" + (f" against a target of {life['target_hours']:.0f} h"
                                                if life.get("target_hours") else "")
            + "; a fit to supplier reports (belt/steady/life.py): within 2.4 % RMS where every pulley's effective "
            "diameter lies in 79.6-175 mm" + ("" if life["in_range"] else
                                             f"; outside it here ({', '.join(life['out_of_range'])}): expect about 0.55 x"))
    out = [{"title": "belt life: shares by pulley", "head": ["pulley", "contact", "effective d (mm)", "share (%)"],
            "rows": rows, "note": note}]
    if duty and duty["rows"] and len(duty["rows"]) == len(life["row_share"]):
        rows = [[f"{r['crank_speed'] * RPM:.0f}", f"{100 * r['share']:.1f}", f"{abs(r['belt_speed']):.2f}",
                 f"{100 * v:.1f}"] for r, v in zip(duty["rows"], life["row_share"])]
        out.append({"title": "belt life: shares by duty row", "head": [
            "crank (rpm)", "share of time (%)", "belt (m/s)", "share of damage (%)"], "rows": rows,
            "note": "a row's damage grows with its share of time times its belt speed (bends per hour)"})
    return out


def margins_sentence(summary: dict) -> str:
    """One sentence where the run's slip margin and the duty cycle's sign-off slip factor both stand
    in the verdict (they are one quantity, creep theory's load multiplier at gross slip, for two
    states)."""
    crit = summary.get("criteria") or {}
    run, duty = crit.get("slip_margin"), crit.get("duty_slip_factor")
    if not run or not duty:
        return ""
    dyn = crit.get("duty_dynamic_slip_margin")
    rpm = ""
    w = summary.get("driver") and (summary.get("pulleys") or {}).get(summary["driver"], {}).get("speed_mean")
    if w:
        rpm = f" at {abs(w) * RPM:.0f} rpm"
    text = (f"Slip margins: the run's slip_margin ({run['value']:.2f} on {run['where']}{rpm}) is creep theory's load "
            "multiplier at gross slip for the run's own mean loads and span tensions; duty_slip_factor "
            f"({duty['value']:.2f}, {duty['where']}) is the same multiplier at each duty row's loads (with the "
            "supplier's drag on the idlers and tensioner) and the arm's static running balance: the sign-off slip "
            "factor")
    if dyn:
        text += (f"; duty_dynamic_slip_margin ({dyn['value']:.2f}, {dyn['where']}) is the run's margin of each row "
                 "held in the rotational model")
    return text + ". They differ as their speeds, loads and tensions differ."
