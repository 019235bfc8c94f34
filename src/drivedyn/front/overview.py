"""What a person reads first, for the terminal and report.html alike: the verdict table, then a
few tables per object (pulleys, spans, tensioners, modes; meshes; the span; the tooth mesh), in
the units engineers use (rpm, %, degrees). The full summary stays in summary.json, behind
``drivedyn run --all`` and the report's folded table.

A table is ``{"title", "head": [...], "rows": [[...], ...], "note": ""}`` of strings.
"""
from __future__ import annotations

import math

import numpy as np

from ..core.criteria import rows as criteria_rows

DEG = 180 / math.pi
RPM = 30 / math.pi


def verdict_table(summary: dict) -> dict:
    verdict = summary.get("verdict", "not judged")
    rows = [[r["name"], r["value"], r["limit"], r["unit"], r["pass"], r["where"], r["text"]] for r in criteria_rows(summary)]
    skipped = summary.get("criteria_skipped") or {}
    note = "; ".join(f"{k}: {v}" for k, v in skipped.items())
    return {"title": f"verdict: {verdict}", "head": ["criterion", "value", "limit", "unit", "", "where", "what it judges"],
            "rows": rows, "note": note, "verdict": verdict}


def tables(result, supplier=True) -> list[dict]:
    """The per-object tables of a result (after the verdict); ``supplier=False``: a belt drive's without
    the supplier report's static tables (report.html lays them out first, supplier_page.py)."""
    fn = {"belt-drive": _belt, "gear-train": _gears, "span-stability": _span, "toothed-mesh": _toothed}.get(result.kind)
    try:
        if fn is _belt:
            return _belt(result, supplier)
        return fn(result) if fn else []
    except Exception as exc:      # a partial result may lack what a table needs: say so, never fail the output
        return [{"title": "results", "head": [], "rows": [], "note": f"no overview ({exc})"}]


def _f(v, fmt="{:.4g}"):
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "-"
    text = fmt.format(v + 0.0)
    return text[1:] if text.startswith("-") and not any(c in "123456789" for c in text) else text   # no "-0"


def _range(a, b, fmt="{:.0f}"):
    return f"{_f(a, fmt)} .. {_f(b, fmt)}"


def _resolution_note(s) -> str:
    """The discretisation error the slips and span tensions carry, as the summary estimates it."""
    d = s.get("discretisation") or {}
    e = d.get("estimate") or {}
    if "slip_largest" in e:
        how = (f"the change against {e['coarse_segments']} segments" if "coarse_segments" in e
               else "the \"auto\" rule's accuracy on examples/fead-runup.toml's drive")
        near = (f"; near a resonance a run-up's bins carry more (up to "
                f"{_f(100 * e['runup_tension_relative_largest'], '{:.0f}')} % there)"
                if "runup_tension_relative_largest" in e else "")
        return (f"; discretisation ({d.get('segments')} segments): slip within {_f(100 * e['slip_largest'], '{:.3f}')}"
                f" points, span tensions within {_f(100 * e['tension_relative_largest'], '{:.1f}')} % ({how}){near}")
    if e.get("unavailable"):
        return f"; discretisation: {e['unavailable']}"
    return ""


def _belt(result, supplier=True) -> list[dict]:
    from ..belt.dynamics.frequencies import judged

    s, ds = result.summary, result.ds
    ru = s.get("runup") or {}
    driver = ru.get("crank") or s.get("driver")
    sel = judged(ds) if "time" in ds.dims else None
    out = []
    pulleys = s.get("pulleys", {})
    torques = {n: abs(p.get("torque_mean") or 0.0) for n, p in pulleys.items()}
    big = max(torques.values(), default=0.0)
    rows = []
    # a grooved pulley carries its load by its teeth: no slip, and its speed against the driver's is the
    # teeth's deflection (the teeth table and phase_error.png say what moves)
    grooved = set((s.get("teeth") or {}).get("pulleys", {}))
    for k, name in enumerate(ds["pulley"].values.tolist() if "pulley" in ds.coords else []):
        p = pulleys.get(name, {})
        w = np.abs(ds["speed"].values[sel, k]) * RPM if sel is not None and sel.any() else np.array([np.nan])
        if name in grooved:
            slip, margin = None, None
            peak = (max(ru.get("hub_load_max", {}).get(name, [np.nan])) if ru else
                    float(np.max(ds["hub_load"].values[sel, k])) if sel is not None and sel.any() else None)
        elif ru:
            slips = [v for v in ru.get("slip", {}).get(name, []) if v is not None]
            slip = max(slips, key=abs) if slips else (0.0 if name == driver else None)
            margin = None
            peak = max(ru.get("hub_load_max", {}).get(name, [np.nan]))
        else:
            slip = p.get("slip")
            carries = name == driver or torques.get(name, 0.0) > 0.05 * big
            margin = p.get("slip_margin") if carries else None
            peak = float(np.max(ds["hub_load"].values[sel, k])) if sel is not None and sel.any() else None
        hub = ds["hub_load"].values[sel, k] if sel is not None and sel.any() else np.array([np.nan])
        fx = ds["hub_force_x"].values[sel, k].mean() if sel is not None and sel.any() else np.nan
        fy = ds["hub_force_y"].values[sel, k].mean() if sel is not None and sel.any() else np.nan
        rows.append([name, _range(w.min(), w.max()),
                     "teeth" if name in grooved else _f(None if slip is None else 100 * slip, "{:.2f}"),
                     "teeth" if name in grooved else _f(margin, "{:.2f}"), _f(float(np.mean(hub)), "{:.0f}"),
                     _f(peak, "{:.0f}"),
                     _f(round(math.degrees(math.atan2(fy, fx))) % 360 if np.isfinite(fx) else None, "{:.0f}")])
    where = "over the run-up" if ru else "over the steady window"
    out.append({"title": f"pulleys ({where})",
                "head": ["pulley", "speed (rpm)", "slip (%)" + (" largest bin" if ru else ""), "run's slip margin",
                         "hub load mean (N)", "peak (N)", "direction (deg)"],
                "rows": rows,
                "note": "run's slip margin: creep theory's load multiplier at gross slip for the run's mean loads, "
                        "for the pulleys that carry torque"
                        + ("; the duty cycle's sign-off slip factors are in their own table" if s.get("supplier", {}).get("duty") else "")
                        + ("; judged per bin in a run-up" if ru else "")
                        + ("; teeth: a grooved pulley, no slip (its teeth's loads and jump margin in the teeth table)"
                           if grooved else "")
                        + "; direction: of the mean hub force on the pulley, counter-clockwise from +x"})
    if s.get("teeth"):
        out.append(_teeth_table(s["teeth"]))
    fl = s.get("flap", {}).get("spans", {})
    rows = []
    for name, e in s.get("spans", {}).items():
        if ru:
            lo = min(ru["span_tension_min"].get(name, [np.nan]))
            hi = max(ru["span_tension_max"].get(name, [np.nan]))
            mean = e.get("tension_mean")
        else:
            lo, hi, mean = e.get("tension_min"), e.get("tension_max"), e.get("tension_mean")
        f1 = fl.get(name, {}).get("f1", [])
        rows.append([name, _f(lo, "{:.0f}"), _f(mean, "{:.0f}") if not ru else "-", _f(hi, "{:.0f}"),
                     _range(min(f1), max(f1)) if len(f1) > 1 else (_f(f1[0], "{:.1f}") if f1 else "-")])
    out.append({"title": f"spans ({where})",
                "head": ["span", "tension min (N)", "mean (N)", "max (N)", "flap f1 (Hz)"], "rows": rows,
                "note": "flap f1: first transverse frequency of the moving span at its running tension and belt speed"
                        + (" (range over the run-up bins)" if ru else "") + _resolution_note(s)})
    st = span_stability_table(s.get("span_stability") or {}, bool(ru))
    if st:
        out.append(st)
    tens = s.get("tensioners", {})
    if tens:
        from ..core.model import loads

        model = loads(ds.attrs["model_toml"]) if "model_toml" in ds.attrs else None
        # the drawn arm's angle from the free arm (the supplier's convention), where a positions table gives it
        free_arm = {n: t["rows"]["mean"]["rel"] * DEG for n, t in (s.get("supplier") or {}).get("positions", {}).items()
                    if "mean" in t["rows"]}
        rows = []
        for name, e in tens.items():
            p = next((p for p in model.pulleys if p.name == name), None) if model is not None else None
            t = (getattr(p, "arm", None) or getattr(p, "slider", None)) if p is not None else None
            arm = "arm_travel" in ds and name in ds["arm"].values.tolist() if "arm" in ds.coords else False
            if arm:
                q = ds["arm_travel"].sel(arm=name).values[sel]
                psi = ds["arm_angle"].sel(arm=name).values[sel] * DEG % 360      # 0-360, as the positions table
                rel = free_arm.get(name)
                rows.append([name, _range(psi.min(), psi.max(), "{:.1f}"),
                             _range(rel - q.max() * DEG, rel - q.min() * DEG, "{:.2f}") if rel is not None else "-",
                             _range(q.min() * DEG, q.max() * DEG, "{:.2f}"),
                             _range(t.stops[0] * DEG, t.stops[1] * DEG, "{:.0f}") if t is not None else "-",
                             _f(e.get("hub_load"), "{:.0f}"), _f(e.get("hub_load_max"), "{:.0f}")])
            else:
                q = ds["slider_travel"].sel(slider=name).values[sel] if "slider_travel" in ds else np.array([np.nan])
                rows.append([name, "-", "-", _range(q.min() * 1e3, q.max() * 1e3, "{:.2f}") + " mm",
                             _range(t.stops[0] * 1e3, t.stops[1] * 1e3, "{:.1f}") + " mm" if t is not None else "-",
                             _f(e.get("hub_load"), "{:.0f}"), _f(e.get("hub_load_max"), "{:.0f}")])
        out.append({"title": f"tensioners ({where})",
                    "head": ["tensioner", "arm angle (deg)", "from the free arm (deg)", "travel (deg)", "stops (deg)",
                             "hub load mean (N)", "peak (N)"], "rows": rows,
                    "note": "arm angle: of the arm about its pivot, counter-clockwise from +x (0-360), as drawn in "
                            "belt.png; from the free arm: as in the positions table; travel: from the drawn position, "
                            "into the belt positive, and its stops"})
    modes = s.get("modes", {}).get("frequencies_hz") or []
    if modes:
        from ..belt.criteria import judged_speed_range, speed_range
        from ..belt.steady.flap import excited_orders

        orders, model = [], None
        if "model_toml" in ds.attrs:
            from ..core.model import loads

            model = loads(ds.attrs["model_toml"])
            orders = excited_orders(model, driver)
        lo, hi = ((judged_speed_range(model, ds, s, driver) if model is not None else speed_range(ds, s, driver))
                  if sel is not None else (0, 0))
        rows = []
        for i, f in enumerate(modes):
            cross = [f"order {k:g} at {60 * f / k:.0f} rpm" for k in orders if lo <= 60 * f / k <= hi]
            rows.append([str(i + 1), f"{f:.1f}", "; ".join(cross) or "-"])
        out.append({"title": "rotational modes (linearised, spans EA/L)", "head": ["mode", "frequency (Hz)",
                    f"crossed by the crank's orders in {lo:.0f}-{hi:.0f} rpm"], "rows": rows,
                    "note": "" if orders else "the crank declares no speed orders: no crossing to list"})
    inst = _installation(s, ds)
    if inst:
        out.append(inst)
    if ru:
        out.append(runup_table(s))
    sup = s.get("supplier") or {}
    out += supplier_tables(sup) if supplier else [t for t in [duty_dynamic_table(sup)] if t]
    return out


def _teeth_table(th: dict) -> dict:
    """A synchronous belt's teeth per grooved pulley (the segment model's tooth contact)."""
    rows = []
    for name, p in th["pulleys"].items():
        ratio = p.get("speed_ratio")
        rows.append([name, str(p["teeth"]), _f(p["teeth_in_mesh"], "{:.1f}"), _f(p["max_tooth_load"], "{:.1f}"),
                     _f(p["max_tooth_load_angle"], "{:.0f}"), _f(p["jump_margin_min"], "{:.2f}"),
                     "-" if ratio is None else f"{ratio:.6f} ({p['tooth_ratio']:.6f})"])
    if th["jumps"] is None:       # the rotational model's chains: no groove change to count
        jumps = "the rotational model's quasi-static chains (no play, no jump: the margin judges)"
    else:
        jumps = f"{th['jumps']} jump(s), the last at t = {th['last_jump_time']:.4g} s on {th['last_jump_pulley']}" \
            if th["jumps"] else "no tooth jumped"
    return {"title": f"teeth ({th['profile']}, {th['count']} teeth of {th['pitch'] * 1e3:.4g} mm; over the steady window)",
            "head": ["pulley", "grooves", "teeth in mesh", "largest tooth load (N)", "at (deg)", "jump margin",
                     "speed ratio (tooth ratio)"],
            "rows": rows,
            "note": f"{jumps}; tooth spring {th['tooth_stiffness'] / 1e3:.4g} N/mm ({th['tooth_stiffness_source']}), "
                    f"play {th['play'] * 1e3:.3g} mm ({th['play_source']}), flank {math.degrees(th['flank_angle']):.2f} "
                    f"deg; at: the groove position counter-clockwise from +x; jump margin: hold T p / R over the outward "
                    "push Q tan(phi - rho) (below 1 a tooth climbs); speed ratio: turns of the pulley over the first "
                    "grooved pulley's over the run (what differs from the tooth ratio is the teeth's change of deflection)"}


def supplier_tables(sup: dict) -> list[dict]:
    """The supplier report's position and duty tables (belt/supplier.py), as the supplier prints them."""
    out = []
    for name, t in sup.get("positions", {}).items():
        rows = [[row, f"{r['rel'] * DEG:.2f}", f"{r['angle'] * DEG % 360:.2f}", f"{r['centre'][0] * 1e3:.1f}",
                 f"{r['centre'][1] * 1e3:.1f}", f"{r['edl'] * 1e3:.1f}", f"{r['required_length'] * 1e3:.1f}",
                 f"{r['wrap'] * DEG:.1f}", f"{r['beta'] * DEG:.1f}", f"{r['tension']:.1f}", f"{r['hub_load']:.1f}",
                 f"{r['hub_direction'] * DEG % 360:.1f}"] for row, r in t["rows"].items()]
        note = (f"design tension {t['design_tension']:.1f} N, belt take-up {t['take_up'] * 1e3 / DEG:.3f} mm/deg; "
                "arm angle from the free arm, away from the belt"
                + "".join(f"; {k}: {v}" for k, v in t["unreached"].items()))
        out.append({"title": f"tensioner {name}: position table", "head": [
            "position", "arm (deg)", "abs (deg)", "X (mm)", "Y (mm)", "EDL (mm)", "belt (mm)", "wrap (deg)",
            "hub-arm (deg)", "tension (N)", "hub load (N)", "hub dir (deg)"], "rows": rows, "note": note})
    duty = sup.get("duty")
    if duty and duty["rows"]:
        names = list(duty["rows"][0]["fixed_arm"]["hub_load"])
        rows = []
        for r in duty["rows"]:
            fa, ra = r["fixed_arm"], r["running_arm"]
            sf = min((v for v in fa["slip_factor"].values() if v is not None), default=None)
            sfr = min((v for v in (ra or {"slip_factor": {}})["slip_factor"].values() if v is not None), default=None)
            rows.append([f"{r['crank_speed'] * RPM:.0f}", f"{100 * r['share']:.1f}"]
                        + [f"{fa['hub_load'][n]:.0f} | " + (f"{ra['hub_load'][n]:.0f}" if ra else "-") for n in names]
                        + [f"{_f(sf, '{:.2f}')} | {_f(sfr, '{:.2f}')}", r["note"] or "-"])
        out.append({"title": "duty cycle: hub loads, fixed arm | running arm", "head": [
            "crank (rpm)", "share (%)"] + [f"{n} (N)" for n in names] + ["min slip factor fixed | running", "note"],
            "rows": rows,
            "note": f"fixed arm (the supplier's convention): the span into the tensioner held at "
                    f"{duty['design_tension']:.1f} N, hub loads the vector sum of T; running arm: the installed "
                    "belt length kept, hub loads from T - m v^2 (docs/supplier-report.md); the sign-off slip factor is "
                    "the smaller of the two (the verdict's duty_slip_factor)"})
    dyn = duty_dynamic_table(sup)
    if dyn:
        out.append(dyn)
    life = sup.get("life")
    if life:
        out.append({"title": "belt life (rib fatigue)", "head": ["B10 (h)", "target (h)", "pulley shares", "row shares"],
                    "rows": [[f"{life['b10_hours']:.0f}", _f(life["target_hours"], "{:.0f}"),
                              ", ".join(f"{n} {100 * v:.1f} %" for n, v in life["pulley_share"].items()),
                              ", ".join(f"{100 * v:.0f} %" for v in life["row_share"])]],
                    "note": "a fit to supplier reports (belt/steady/life.py): within 2.4 % RMS where every pulley's "
                            "effective diameter lies in 79.6-175 mm" + ("" if life["in_range"] else
                            f"; outside it here ({', '.join(life['out_of_range'])}): expect about 0.55 x")})
    return out


def duty_dynamic_table(sup: dict) -> dict | None:
    """The duty rows held in the rotational model (belt/supplier.py's dynamic_duty)."""
    dyn, duty = sup.get("duty_dynamic"), sup.get("duty")
    if dyn and duty and duty["rows"]:
        names = list(duty["rows"][0]["fixed_arm"]["hub_load"])
        rel = {n: t["rows"]["mean"]["rel"] * DEG for n, t in (sup.get("positions") or {}).items() if "mean" in t["rows"]}
        rows = []
        for e in dyn:
            if e["status"] == "failed":
                rows.append([f"{e['crank_speed'] * RPM:.0f}"] + ["-"] * (len(names) + 2) + [f"failed: {e['note']}"])
                continue
            # the arm from the free arm (the positions table's convention) where the table gives the drawn arm's
            arm = "; ".join(f"{n} {_range(rel[n] - hi * DEG, rel[n] - lo * DEG, '{:.2f}')}" if n in rel
                            else f"{n} {_range(lo * DEG, hi * DEG, '{:.2f}')} (travel)" for n, (lo, hi) in e["arm_travel"].items())
            rows.append([f"{e['crank_speed'] * RPM:.0f}"]
                        + [f"{e['hub_load_mean'][n]:.0f} / {e['hub_load_peak'][n]:.0f}" for n in names]
                        + [_f(min(e["slip_margin"].values(), default=None), "{:.2f}"), arm or "-",
                           e["status"] + (f" ({', '.join(e['diagnostics'])})" if e["diagnostics"] else "")])
        return {"title": "duty cycle from the dynamics: hub loads mean / peak", "head": [
            "crank (rpm)"] + [f"{n} (N)" for n in names] + ["min slip margin (dynamic)", "arm from the free arm (deg)",
                                                             "status"],
            "rows": rows, "note": "the rotational model held at each row's speed with its loads and the crank's "
                                  "declared orders (docs/supplier-report.md); slip margin: each held run's own (creep "
                                  "theory at its mean loads), beside the static sign-off slip factor"}
    return None


def _installation(s, ds) -> dict | None:
    """check's installation table: what a tension meter should read on each span at rest."""
    if "model_toml" not in ds.attrs:
        return None
    from ..belt.geometry.installation import installation_table
    from ..mechanics.layout import compute_layout
    from ..core.model import loads

    model = loads(ds.attrs["model_toml"])
    rest = [t.get("rest_tension") for t in s.get("tensioners", {}).values() if t.get("rest_tension")]
    T0 = rest[0] if rest else model.belt.pretension
    if not T0:
        return None
    tb = installation_table(model, T0, compute_layout(model))
    rows = [[n + ("  <- measure here" if n == tb["measure_on"] else ""), f"{e['length'] * 1e3:.1f}",
             f"{e['tension']:.0f}", f"{e['frequency']:.1f}", f"{e['band'][0]:.1f} .. {e['band'][1]:.1f}"]
            for n, e in tb["spans"].items()]
    return {"title": "installation (belt at rest, as drivedyn check gives it)",
            "head": ["span", "length (mm)", "tension (N)", "f1 (Hz)", f"band for +-{100 * tb['tolerance']:g} % (Hz)"],
            "rows": rows, "note": "the frequency a tension meter reads on each span at the installation tension"}


def runup_table(s) -> dict:
    """Per crank-speed bin: the extremes (never a mean over the swept window)."""
    ru = s["runup"]
    spans = list(ru["span_tension_max"])
    arms = ru.get("arm_travel_range", {})
    rows = []
    for b, rpm in enumerate(ru["speed_rpm"]):
        worst = max(ru["slip"], key=lambda n: abs(ru["slip"][n][b] or 0)) if ru.get("slip") else ""
        hub = max(ru.get("hub_load_max", {}).items(), key=lambda kv: kv[1][b], default=None)
        sweep = ru.get("sweep", [])
        down = b < len(sweep) and sweep[b] == "down"
        row = [f"{rpm:.0f}" + (" down" if down else ""), f"{min(ru['span_tension_min'][sp][b] for sp in spans):.0f}",
               min(spans, key=lambda sp: ru['span_tension_min'][sp][b]),
               f"{max(ru['span_tension_max'][sp][b] for sp in spans):.0f}",
               f"{100 * ru['slip'][worst][b]:.2f}" if worst else "-", worst,
               f"{hub[1][b]:.0f} ({hub[0]})" if hub else "-"]
        row += [f"{arms[a][b] * DEG:.2f}" for a in arms]
        rows.append(row)
    head = ["crank rpm", "tension min (N)", "on span", "max (N)", "largest slip (%)", "on", "largest hub load (N)"]
    head += [f"{a} travel range (deg)" for a in arms]
    return {"title": f"run-up of {ru['crank']}: extremes per crank-speed bin", "head": head, "rows": rows,
            "note": "every span's tension per bin: runup.span_tension_min / max in summary.json, runup.png"
                    + ("; a run-down's bins (down) after the run-up's" if "down" in ru.get("sweep", []) else "")}


def _kv_rows(items, units, prefix=""):
    from ..core.results import number_text

    rows = []
    for k, v in items:
        unit = units.get(prefix + k, "")
        if isinstance(v, bool) or v is None or isinstance(v, str):
            text = str(v)
        elif isinstance(v, (int, float)):
            text = number_text(float(v), "" if unit == "rad/s" else unit)
        else:
            text = compact(v)
        rows.append([k, text, "" if unit == "1" else unit])
    return rows


def compact(v) -> str:
    """A list as one short cell: short flat lists whole, anything longer or nested by its shape."""
    if isinstance(v, (list, tuple)):
        arr = np.asarray(v, dtype=object)
        flat = all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in v)
        if flat and len(v) <= 4:
            return "[" + ", ".join(f"{x + 0.0:.4g}" for x in v) + "]"
        shape = "x".join(str(n) for n in arr.shape) if arr.dtype != object or flat else str(len(v))
        return f"[{shape} values: summary.json]"
    return str(v)


def _gears(result) -> list[dict]:
    s = result.summary
    rows = []
    for n, e in s.get("meshes", {}).items():
        rows.append([n, _f(e.get("kv"), "{:.3f}"), _f(e.get("kv_iso_method_b"), "{:.3f}"),
                     _f(e.get("force_nominal"), "{:.0f}"), _range(e.get("force_min"), e.get("force_max")),
                     _f(e.get("mesh_frequency"), "{:.1f}"), _f(e.get("contact_ratio"), "{:.3f}")])
    out = [{"title": "meshes (steady window)", "head": ["mesh", "K_v", "K_v ISO 6336-1 B", "force nominal (N)",
            "force min .. max (N)", "mesh frequency (Hz)", "contact ratio"], "rows": rows, "note": ""}]
    rows = []
    for n, r in (s.get("rating") or {}).items():
        for w in ("pinion", "wheel"):
            g = r[w + "_rating"]
            rows.append([n, r[w] if r[w] == w else f"{r[w]} ({w})", _f(g["sigma_H"] / 1e6, "{:.0f}"), _f(g["sigma_HP"] / 1e6, "{:.0f}"),
                         _f(g["S_H"], "{:.3f}"), _f(g["sigma_F"] / 1e6, "{:.0f}"), _f(g["sigma_FP"] / 1e6, "{:.0f}"),
                         _f(g["S_F"], "{:.3f}")])
    if rows:
        out.append({"title": "ISO 6336 rating, method B (K_v from the dynamic run)",
                    "head": ["mesh", "gear", "sigma_H (MPa)", "sigma_HP (MPa)", "S_H", "sigma_F (MPa)",
                             "sigma_FP (MPa)", "S_F"], "rows": rows,
                    "note": "S_H and S_F with ISO's K_v, and every factor: rating.* in summary.json"})
    stages = [("planetary", s["planetary"], "planetary.")] if s.get("planetary") else []
    stages += [(k, v, f"stages.{k}.") for k, v in (s.get("stages") or {}).items()]
    for k, (name, pl, prefix) in enumerate(stages):
        label = "planetary stage" if len(stages) == 1 else f"stage {k + 1}"
        out += _stage_tables(label, pl, dict(result.units), prefix)
    gb = s.get("gearbox")
    if gb and gb.get("natural_frequencies_hz"):
        names = gb.get("stages") or []
        shares = gb.get("energy_share") or {}
        head = ["mode", "frequency (Hz)"] + [f"energy in {n} (%)" for n in names] + ["energy in the train (%)"]
        rows = []
        for i, f in enumerate(gb["natural_frequencies_hz"][:12]):
            per = [shares.get(n, [float("nan")] * (i + 1))[i] for n in names]
            rows.append([str(i + 1), f"{f:.1f}"] + [f"{100 * x:.1f}" for x in per]
                        + [f"{100 * max(0.0, 1.0 - gb['stage_energy_share'][i]):.1f}"])
        n = len(gb["natural_frequencies_hz"])
        out.append({"title": "gearbox: modes of the whole train (" + " + ".join(gb.get("model") or []) + " stages, train)",
                    "head": head, "rows": rows,
                    "note": (f"lowest 12 of {n}; " if n > 12 else "") + "every mode: gearbox.* in summary.json"})
    fr = s.get("natural_frequencies_hz") or []
    if fr:
        out.append({"title": "natural frequencies" + (" of the train" if stages else "") + " (linear, mean mesh stiffness)",
                    "head": ["mode", "frequency (Hz)"],
                    "rows": [[str(i + 1), f"{f:.1f}"] for i, f in enumerate(fr)], "note": ""})
    return out


_STAGE_NAMES = {"planet_mode_frequency_closed_form_hz": "planet modes, closed form",
                "speed_ratio_input_over_output": "speed ratio input / output", "torque_sun": "sun torque",
                "sun_planet_force": "sun-planet force", "ring_planet_force": "ring-planet force",
                "phase_sun_planet": "mesh phase sun-planet (periods)", "phase_ring_planet": "mesh phase ring-planet (periods)",
                "load_sharing_factor": "load sharing factor K_gamma"}


def _stage_tables(label: str, pl: dict, units: dict, prefix: str) -> list[dict]:
    """A planetary stage's tables: its quantities, the ISO rating of every gear of both meshes, its modes."""
    # in the units a gear engineer reads: angles in degrees, lengths in mm, pin errors in um, shares in %
    show = {"planet_angles": ("deg", DEG), "centre_distance": ("mm", 1e3), "position_errors": ("um", 1e6),
            "load_share": ("%", 100.0)}
    items = []
    for k, v in pl.items():
        if isinstance(v, dict) or k in ("natural_frequencies_hz", "mode_types"):
            continue
        if k in show and v is not None:
            u, f = show[k]
            v = [x * f for x in v] if isinstance(v, (list, tuple)) else v * f
            units[prefix + k] = u
        items.append((k, v))
    rows = [[_STAGE_NAMES.get(r[0], r[0].replace("_", " ")), *r[1:]] for r in _kv_rows(items, units, prefix)]
    out = [{"title": label, "head": ["quantity", "value", "unit"], "rows": rows, "note": f"every value: {prefix}* in summary.json"}]
    rt = pl.get("rating")
    if rt:
        rows, kv = [], []
        for mesh, e in rt["meshes"].items():
            kv.append(f"{mesh} {e['K_v']:.4f} ({e['K_v_source']})")
            for i, gear in enumerate((e["pinion"], e["wheel"])):
                g = e[gear]
                sf = "not rated" if g["S_F"] is None else f"{g['S_F']:.3f}"
                rows.append([mesh if i == 0 else "", gear, f"{g['sigma_H'] / 1e6:.1f}", f"{g['S_H']:.3f}",
                             "" if g["sigma_F"] is None else f"{g['sigma_F'] / 1e6:.1f}", sf,
                             f"{g['load_cycles'] / 1e6:.4g}"])
        out.append({"title": f"{label}: ISO 6336 rating, method B",
                    "head": ["mesh", "gear", "sigma_H (MPa)", "S_H", "sigma_F (MPa)", "S_F", "cycles (1e6)"],
                    "rows": rows,
                    "note": f"K_gamma {rt['K_gamma']:.3f} ({rt['K_gamma_source']}); K_v " + ", ".join(kv)
                    + (f", {rt['K_v_note'].split(':')[0]}" if rt.get("K_v_note") else "")
                    + f"; required S_H {rt['S_H_min_required']:g}, S_F {rt['S_F_min_required']:g}; every factor: "
                    f"{prefix}rating.* in summary.json"})
    dyn = pl.get("dynamics")
    if dyn:
        n = len(dyn["kv_sun_planet"])
        rows = [[f"{mesh}: {what}", *(f"{k:.4f}" for k in dyn[key + mesh.replace("-", "_")]),
                 f"{max(dyn[key + mesh.replace('-', '_')]):.4f}"]
                for mesh in ("sun-planet", "ring-planet")
                for what, key in (("K_v", "kv_"), ("load shift", "load_sharing_quasi_static_"))
                if key + mesh.replace("-", "_") in dyn]
        sw = dyn.get("sweep")
        note = (f"at {dyn['speed'] * 30 / math.pi:.6g} rpm of the input member (mesh frequency "
                f"{dyn['mesh_frequency_hz']:.1f} Hz), {dyn['stiffness_model']} mesh stiffness; K_v = largest mesh force "
                "over the window / largest quasi-static force (the static forces with the instant's mesh stiffnesses); "
                "load shift = largest quasi-static force / the mean over the planets (a time-varying K_gamma)")
        if sw and sw["kv_max"]["sun-planet"] is not None:
            note += (f"; sweep {sw['speed_min'] * 30 / math.pi:.4g}-{sw['speed_max'] * 30 / math.pi:.4g} rpm: largest K_v "
                     f"{sw['kv_max']['sun-planet']:.3f} (sun-planet, {sw['speed_at_kv_max']['sun-planet'] * 30 / math.pi:.0f} "
                     f"rpm), {sw['kv_max']['ring-planet']:.3f} (ring-planet, "
                     f"{sw['speed_at_kv_max']['ring-planet'] * 30 / math.pi:.0f} rpm)")
        kind = "lateral-torsional" if dyn.get("model", "").startswith("lateral") else "torsional"
        out.append({"title": f"{label}: K_v from the time integration ({kind} model)",
                    "head": ["mesh", *(f"planet {i + 1}" for i in range(n)), "largest"], "rows": rows,
                    "note": note + f"; every value: {prefix}dynamics.* in summary.json"})
    if pl.get("natural_frequencies_hz"):
        types = pl.get("mode_types") or [""] * len(pl["natural_frequencies_hz"])
        out.append({"title": f"{label}: modes (lumped torsional model)", "head": ["mode", "frequency (Hz)", "type"],
                    "rows": [[str(i + 1), f"{f:.1f}", str(t)] for i, (f, t) in
                             enumerate(zip(pl["natural_frequencies_hz"], types))], "note": ""})
    la = pl.get("lateral")
    if la and la.get("natural_frequencies_hz"):
        f_la = la["natural_frequencies_hz"]
        out.append({"title": f"{label}: modes (lateral-torsional model{', floating sun' if la.get('floating_sun') else ''})",
                    "head": ["mode", "frequency (Hz)", "type"],
                    "rows": [[str(i + 1), f"{f:.1f}", str(t)] for i, (f, t) in enumerate(zip(f_la[:12], la["mode_types"]))],
                    "note": (f"lowest 12 of {len(f_la)}; " if len(f_la) > 12 else "")
                    + f"K_gamma {la['load_sharing_factor']:.4f} with this model"})
    return out


#: the span's operating point in words and engineering units, as the belt and gear tables read:
#: (summary key, words, unit shown, factor from the summary's SI value)
SPAN_ROWS = [("pretension", "belt tension (pretension)", "N", 1.0), ("speed", "belt speed", "m/s", 1.0),
             ("v_critical", "critical speed of the span", "m/s", 1.0),
             ("natural_frequency_hz", "first natural frequency", "Hz", 1.0),
             ("excitation_frequency", "excitation frequency (tooth passing)", "Hz", 1.0 / (2 * math.pi)),
             ("frequency_ratio", "excitation over the first natural frequency", "", 1.0),
             ("floquet_multiplier", "largest Floquet multiplier per excitation period", "", 1.0),
             ("stability", "stability", "", 1.0)]


def _span(result) -> list[dict]:
    from ..core.results import number_text

    s = result.summary
    rows = []
    for key, words, unit, factor in SPAN_ROWS:
        v = s.get(key)
        if key not in s:
            continue
        text = str(v) if isinstance(v, (str, bool)) or v is None else number_text(float(v) * factor, unit)
        rows.append([words, text, unit])
    out = [{"title": "span at the operating point", "head": ["quantity", "value", "unit"], "rows": rows,
            "note": "every value in SI: summary.json (excitation_frequency in rad/s)"}]
    fr = s.get("frequencies", {})
    if fr:
        n = max(len(v) for v in fr.values())
        out.append({"title": "natural frequencies of the span (Hz)", "head": ["model"] + [f"mode {i + 1}" for i in range(n)],
                    "rows": [[m] + [f"{x:.2f}" for x in v] for m, v in fr.items()], "note": ""})
    return out


def _toothed(result) -> list[dict]:
    s = result.summary
    items = [(k, s[k]) for k in ("max_overlap_area_mm2", "max_penetration_mm", "groove_depth_used") if k in s]
    items += [(f"seated.{k}", v) for k, v in (s.get("seated") or {}).items()]
    items += [(f"engagement.{k}", v) for k, v in (s.get("engagement") or {}).items()]
    out = [{"title": "mesh geometry", "head": ["quantity", "value", "unit"], "rows": _kv_rows(items, result.units),
            "note": ""}]
    ld = s.get("load")
    if ld:
        keys = ["torque_N_m", "jump_torque_N_m", "teeth_in_mesh", "max_tooth_load_N", "most_loaded_tooth",
                "first_tooth_share", "tight_tension_N", "slack_tension_N"]
        out.append({"title": "under load", "head": ["quantity", "value", "unit"],
                    "rows": _kv_rows([(k, ld[k]) for k in keys if k in ld], result.units, "load."), "note": ""})
    return out


def span_stability_table(st: dict, runup: bool) -> dict | None:
    """The spans' tension fluctuation on their parametric-resonance tongues (belt/dynamics/span_stability.py)."""
    spans = st.get("spans") or {}
    if not spans:
        return None
    rows = []
    for name, e in spans.items():
        comps = [f"{c['amplitude']:.3g} N at {c['frequency']:.1f} Hz"
                 + (f" (order {c['order']:.2f})" if c.get("order") is not None else "")
                 + (" [segments]" if c.get("note") else "") for c in e.get("components", [])]
        x = e.get("nearest") or {}
        d = e.get("tongue_distance")
        if e.get("inside"):
            verdict = "INSIDE"
        elif d is None:
            verdict = e.get("note", "-")
        else:
            verdict = f"{100 * d:.1f} % off" + ("" if x.get("open") else " (closed)")
        tongue = (f"{x['tongue']}: {x['band'][0]:.1f} .. {x['band'][1]:.1f}" if x.get("band")
                  else f"{x['tongue']}: at {x['tongue_centre']:.1f}" if x else "-")
        rows.append([name + (f" @ {e['rpm']:.0f} rpm" if runup and e.get("rpm") is not None else ""),
                     _f(e.get("tension_mean"), "{:.0f}"), _f(e.get("frequency_1"), "{:.1f}"),
                     "; ".join(comps) or "-", tongue, verdict])
    note = ("largest components of each span's tension fluctuation against its Mathieu tongues (n = 1: f ~ 2 f1, "
            "n = 2: f ~ f1) at their depth dT / (T + EI pi^2/L^2 - m v^2), with criteria.flap_damping_ratio; "
            "% off: how far the frequency must move to enter the tongue (closed: the depth is below the tongue's "
            "threshold, counted to its centre)")
    if runup:
        note += "; run-up: the bin nearest a tongue, from the tracked orders"
    elif st.get("sampled_to"):
        note += f"; the window's samples resolve up to {st['sampled_to']:.0f} Hz"
    return {"title": "span stability (tension fluctuation on the span's tongues)",
            "head": ["span", "mean (N)", "f1 (Hz)", "largest components", "nearest tongue (Hz)", "distance"],
            "rows": rows, "note": note}
