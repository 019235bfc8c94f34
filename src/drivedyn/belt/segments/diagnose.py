"""Belt-drive diagnostics: does the computed run stay inside the model's valid regime?

Each check reads the Result (window means, frames) and the built system, adds its numbers to the
summary and, past its limit, a diagnostic (codes of :data:`drivedyn.core.diagnostics.CODES`):

- gross-slip: creep theory (Euler-Eytelwein / Grashof) puts the pulley surface speed between the
  speeds of the belt arriving and leaving (adhesion arc at the entry, sliding arc at the exit); in
  gross slip it leaves that band. Measured: sliding = 1 - |v_arrive| / |omega r_eff|, against the
  elastic-creep bound (T_hi - T_lo) / (EA + T_hi) plus the chain's chordal speed error
  (r_eff: the chain's rolling radius, system.BeltSystem.rolling_radius).
- contact-chatter, contact-damping-depth: share of the wrapped segments in contact and peak
  normal force against the capstan value T l / r, from the frames inside the window.
- window-not-steady: drift of pulley speeds and span tensions inside the window (window.drift).
- energy-residual: |work in - dissipated - energy change| over the window against the work in.
- coarse-discretisation: fewer segments than "auto" takes (the error is then not known: the
  summary's discretisation.estimate), a wrap holding fewer than WRAP_LIMIT segments, or a chordal
  speed error l^2 / (12 r^2) above CHORDAL_LIMIT.
- at-rest-drift: a drive with no excitation whose pulleys move (it starts at static equilibrium).
"""
from __future__ import annotations

import math

import numpy as np

from ...core.window import in_window
from ..dynamics.checks import energy_balance, excited, runup_slip, slip_margin, steady_drift
from .equilibrium import FORCE_TOL
from ..model import integrator

#: gross slip: sliding beyond twice the creep band plus the largest discretisation speed error the
#: coarse-discretisation check lets pass (CHORDAL_LIMIT): then it cannot be creep or chordal action
SLIP_FACTOR = 2.0
#: contact chatter: fewer wrapped segments in contact than this share, or a peak normal force
#: above this multiple of the capstan value T l / r
CONTACT_SHARE = 0.75
PEAK_FACTOR = 3.0
#: the damping depth is "far" from the static penetration beyond this ratio
DEPTH_RATIO = 10.0
#: chordal speed error of a pulley. A chain of chords l on a circle r (chord midpoints on r)
#: carries the belt at r_eff = l / (2 asin(l / 2 R_e)), R_e = sqrt(r^2 + l^2/4): r_eff / r - 1
#: = l^2 / (12 r^2) + O(l^4) (README "Chordal action": 0.96 % alternator-crank error at 110
#: segments = 9.9^2/12 (1/27^2 - 1/80^2)). Above 2 % (l > 0.49 r) it exceeds the creep of a
#: belt at rated load (1-2 %) and would be read as slip.
CHORDAL_LIMIT = 0.02
#: segments on a wrap below which its slip is not resolved (resolution.py: 2.8 segments on the
#: accessory drive's tensioner misread its slip by 0.25 points, 5.6 by 0.004)
WRAP_LIMIT = 3.0


def chordal_error(l: float, r) -> np.ndarray:
    """Relative speed error l^2 / (12 r^2) of the segment chain on a pulley of radius r."""
    return l * l / (12.0 * np.asarray(r, dtype=float) ** 2)


def run_checks(result, model, sysm, sel) -> None:
    """Add the belt diagnostics and their numbers to ``result`` (summary and diagnostics)."""
    if not np.any(sel) or result.ds.sizes.get("time", 0) < 3:
        return
    _gross_slip(result, model, sysm, sel)
    _contact(result, model, sysm)
    steady_drift(result, model, sysm, sel)
    energy_balance(result, model, sel)
    _coarse(result, model, sysm)
    _at_rest(result, model, sysm)
    slip_margin(result, model, sysm, sel)
    runup_slip(result)
    _implicit_turn(result, model, sel)
    from ..dynamics.loadcheck import check_loads

    check_loads(result, model, sel)


def _spans_at(sysm, j, forward):
    """(arriving, leaving) span index at pulley j; span k leaves pulley k in belt order."""
    nk = len(sysm.layout.names)
    return ((j - 1) % nk, j) if forward else (j, (j - 1) % nk)


def _gross_slip(result, model, sysm, sel):
    ds, s = result.ds, result.summary
    init = sysm.init
    EA = model.belt.axial_stiffness
    l = init.seg_length
    r_eff = sysm.rolling_radius
    speed = ds["speed"].values[sel].mean(axis=0)
    vsp = ds["span_speed"].values[sel].mean(axis=0)
    ten = ds["span_tension"].values[sel].mean(axis=0)
    forward = float(np.nansum(vsp)) >= 0
    v_scale = max(float(np.max(np.abs(speed) * r_eff)), float(np.max(np.abs(vsp))))
    share = _sliding_share(result, model, sysm)
    t_w = s["steady_window"][1] - s["steady_window"][0]
    for j, name in enumerate(sysm.layout.names):
        a, b = _spans_at(sysm, j, forward)
        surf, v_arr = abs(speed[j]) * r_eff[j], abs(vsp[a])
        t_hi, t_lo = max(ten[a], ten[b]), min(ten[a], ten[b])
        # elastic creep at the capstan limit (whole wrap sliding): strain difference of the spans
        bound = (t_hi - t_lo) / (EA + t_hi) if EA + t_hi > 0 else 0.0
        p = s["pulleys"][name]
        p["creep_bound"] = float(bound)
        p["sliding_share"] = share.get(name, float("nan"))
        # the belt must pass at least one segment through the window, else speeds are start-up noise
        if v_scale * t_w < l or max(surf, v_arr) < 1e-3 * v_scale:
            p["sliding"] = float("nan")
            continue
        sliding = (surf - v_arr) / max(surf, v_arr)
        p["sliding"] = float(sliding)
        limit = SLIP_FACTOR * bound + CHORDAL_LIMIT
        if abs(sliding) > limit and excited(model):   # a free drive: at-rest-drift says it
            who = "pulley outruns the belt" if sliding > 0 else "belt outruns the pulley"
            result.diagnose("gross-slip", f"pulley {name} slips grossly ({who}): sliding {abs(sliding):.3g} against "
                            f"the creep band {bound:.3g} (T1 {t_hi:.0f} N, T2 {t_lo:.0f} N); "
                            f"{_pct(share.get(name))} of its wrap slides; more pretension or less load",
                            f"pulleys.{name}.sliding", abs(sliding), limit, "1")


def _pct(x):
    return "?" if x is None or not np.isfinite(x) else f"{100 * x:.0f} %"


def _frames_in_window(result):
    ds = result.ds
    if ds.sizes.get("frame", 0) == 0:
        return np.zeros(0, dtype=int)
    w = result.summary["steady_window"]
    idx = np.nonzero(in_window(ds["frame_time"].values, w))[0]
    return idx


def _centre_at(ds, sysm, frames, j):
    """Centre of pulley j at the frames (nf, 2): where its tensioner has moved it, else where drawn."""
    A, c = sysm.arms, np.array([sysm.pulleys.cx[j], sysm.pulleys.cy[j]])
    nf = len(frames)
    for a in range(A.na):
        if A.pulley[a] != j:
            continue
        name = sysm.model.pulleys[j].name
        t, tf = ds["time"].values, ds["frame_time"].values[frames]
        if A.kind[a] == 0:
            q = np.interp(tf, t, ds["arm_travel"].sel(arm=name).values)
            psi = A.psi0[a] + A.sgn[a] * q
            return np.column_stack([A.px[a] + A.length[a] * np.cos(psi), A.py[a] + A.length[a] * np.sin(psi)])
        q = np.interp(tf, t, ds["slider_travel"].sel(slider=name).values)
        return np.column_stack([A.px[a] + q * A.dx[a], A.py[a] + q * A.dy[a]])
    return np.repeat(c[None, :], nf, axis=0)


def _on_pulley(ds, sysm, frames, j):
    """Mask (frames, segments) of segment centres inside pulley j's contact radius, the pulley
    where its tensioner holds it at each frame."""
    c = _centre_at(ds, sysm, frames, j)
    rx, ry = ds["belt_x"].values[frames] - c[:, :1], ds["belt_y"].values[frames] - c[:, 1:]
    d = np.hypot(rx, ry)
    C = sysm.contact
    a = int(C.ccur[j]) if len(C.ccur) else -1
    if a >= 0:      # a pitch curve, turned by the pulley's angle at the frames
        from ._curves import table_values

        th = np.interp(ds["frame_time"].values[frames], ds["time"].values, ds["angle"].values[:, j])
        return d < table_values(C.cpr, a, np.arctan2(ry, rx) - th[:, None])[0]
    return d < sysm.model.pulleys[j].radius


def _sliding_share(result, model, sysm) -> dict:
    """Share of the segments in contact on each pulley whose friction is saturated (|T| = mu N,
    Threlfall's law past Delta_v): the sliding arc of creep theory; 1 in gross slip."""
    ds = result.ds
    fr = _frames_in_window(result)
    if len(fr) == 0:
        return {}
    fn, ft = ds["belt_normal_force"].values[fr], ds["belt_friction_force"].values[fr]
    mu = sysm.contact.mu[None, :]
    out = {}
    for j, p in enumerate(model.pulleys):
        inc = _on_pulley(ds, sysm, fr, j) & (fn > 0)
        n = inc.sum()
        out[p.name] = float((inc & (np.abs(ft) >= 0.99 * mu * fn)).sum() / n) if n else float("nan")
    return out


def _contact(result, model, sysm):
    ds, s = result.ds, result.summary
    fr = _frames_in_window(result)
    if len(fr) == 0:
        return
    init = sysm.init
    lg = init.seg_length + init.gap                               # segment pitch at the pretension
    fn = ds["belt_normal_force"].values[fr]
    ten = ds["span_tension"].values
    sel = in_window(ds["time"].values, s["steady_window"])
    t_max = float(ten[sel].max()) if np.any(sel) else init.tension
    depth = float(sysm.contact.pmax)
    p0 = init.penetration
    worst = None
    for j, p in enumerate(model.pulleys):
        expected = sysm.layout.wrap[j] * p.radius / lg          # segments the wrap holds
        inc = _on_pulley(ds, sysm, fr, j) & (fn > 0)
        share = float(np.mean(inc.sum(axis=1)) / expected) if expected >= 1 else float("nan")
        n_static = t_max * lg / p.radius                       # capstan pressure T / r on one segment
        peak = float(np.max(np.where(inc, fn, 0.0)) / n_static)
        s["pulleys"][p.name]["contact_share"] = min(share, 1.0)
        s["pulleys"][p.name]["peak_normal_ratio"] = peak
        if expected >= 3 and (share < CONTACT_SHARE or peak > PEAK_FACTOR):
            if worst is None or share < worst[1]:
                worst = (p.name, share, peak, j)
    if worst is None:
        return
    name, share, peak, j = worst
    if share < CONTACT_SHARE:
        result.diagnose("contact-chatter", f"belt segments bounce on pulley {name}: {100 * share:.0f} % of the wrapped "
                        f"segments in contact, peak normal force {peak:.1f} x the static value",
                        f"pulleys.{name}.contact_share", share, CONTACT_SHARE, "1")
    else:
        result.diagnose("contact-chatter", f"belt segments bounce on pulley {name}: peak normal force {peak:.1f} x the "
                        f"static value T l / r", f"pulleys.{name}.peak_normal_ratio", peak, PEAK_FACTOR, "1")
    if depth > DEPTH_RATIO * float(np.max(p0)):
        result.diagnose("contact-damping-depth", f"contact.damping_depth {depth * 1e3:.3g} mm is "
                        f"{depth / np.max(p0):.0f} x the static penetration {np.max(p0) * 1e6:.3g} um: the contact "
                        "damping is far below nominal; omit damping_depth (it then follows the static penetration)",
                        "contact.damping_depth", depth, DEPTH_RATIO * float(np.max(p0)), "m")


def _implicit_turn(result, model, sel):
    """The implicit scheme's accuracy rule (system.TURN_PER_STEP) checked on the run: how far a
    segment rolling on the fastest pulley turns per step in the steady window. Beyond twice the
    rule (a step the user set, or the smallest step the rule may take) the results are not known to
    hold: examples/fead-runup.toml's drive held at 5000 rpm ran away at 0.056 rad per step, the
    5PK under Threlfall's law missed 4 % of the energy at 0.028 (system.TURN_PER_STEP)."""
    if integrator(model) != "implicit":
        return
    from .system import TURN_PER_STEP

    rule = TURN_PER_STEP[model.friction.law]
    h = result.summary["solver"]["step"]
    w = np.abs(result.ds["speed"].values[sel])
    j = int(np.argmax(w.max(axis=0)))
    turn = float(h * w[:, j].max())
    result.summary["solver"]["turn_per_step"] = turn
    if turn > 2 * rule:
        name = model.pulleys[j].name
        result.diagnose("step-too-large", f"the implicit step {h * 1e6:.3g} us turns a segment on pulley {name} by "
                        f"{turn:.3g} rad per step, over twice the accuracy rule's {rule:g} (span tensions "
                        "drift by percents): a smaller simulation.step, or method semi-implicit",
                        "solver.turn_per_step", turn, 2 * rule, "rad")


def _coarse(result, model, sysm):
    l = sysm.init.seg_length
    err = chordal_error(l, [p.radius for p in model.pulleys])
    for j, p in enumerate(model.pulleys):
        result.summary["pulleys"][p.name]["chordal_error"] = float(err[j])
    disc = result.summary.get("discretisation", {})
    est = disc.get("estimate", {})
    n_auto = est.get("auto_segments")
    if n_auto is not None and sysm.n < n_auto and not model.simulation.resolution_check:
        # below the "auto" count the error is not known (resolution.rule_estimate); with the
        # resolution check on, it is measured and unconverged-resolution judges it instead
        from .resolution import RULE_ACCURACY

        slip, tension = RULE_ACCURACY[model.friction.law]
        result.diagnose("coarse-discretisation", f"{sysm.n} segments against the {n_auto} that belt.segments = "
                        f"\"auto\" takes: the discretisation error of slip and span tension is not known (at "
                        f"\"auto\" within about {100 * slip:.3f} points and {100 * tension:.1f} %); use \"auto\", or "
                        "simulation.resolution_check = true to measure it", "discretisation.segments",
                        sysm.n, n_auto, "")
    if (disc.get("segments_on_shortest_wrap") or math.inf) < WRAP_LIMIT:
        from ..geometry.segment_count import auto_segments

        name, k = disc["shortest_wrap"], disc["segments_on_shortest_wrap"]
        result.diagnose("coarse-discretisation", f"the wrap on pulley {name} holds {k:.1f} segments of {l * 1e3:.3g} mm: "
                        f"its slip and the tensions of its spans are not resolved; belt.segments = \"auto\" takes "
                        f"{auto_segments(model, sysm.layout)[0]}", "discretisation.segments_on_shortest_wrap", k,
                        WRAP_LIMIT, "")
    j = int(np.argmax(err))
    if err[j] > CHORDAL_LIMIT:
        need = math.ceil(sysm.layout.length / (model.pulleys[j].radius * math.sqrt(12 * CHORDAL_LIMIT)))
        result.diagnose("coarse-discretisation", f"segments of {l * 1e3:.3g} mm on the {model.pulleys[j].radius * 1e3:.3g} mm "
                        f"pulley {model.pulleys[j].name}: chordal speed error {100 * err[j]:.1f} %; "
                        f"use belt.segments >= {need}", f"pulleys.{model.pulleys[j].name}.chordal_error",
                        err[j], CHORDAL_LIMIT, "1")


def at_rest_limit(sysm, duration) -> np.ndarray:
    """Largest pulley speed (rad/s) a free drive may reach: the belt starts at its static
    equilibrium (equilibrium.relax) with every residual force below FORCE_TOL T0; n such forces
    acting on the belt's mass m for the whole run give it at most n FORCE_TOL T0 t / m (Newton's
    law; the pulleys' inertia, coupled by friction, only lowers it). A start out of equilibrium
    swings in the chain's cogging well instead (about 0.1-2 rad/s for the 5PK drive)."""
    n, T0 = sysm.n, sysm.init.tension
    mass = float(np.sum(sysm.belt.m))
    v = n * FORCE_TOL * T0 * duration / mass
    return v / np.array(sysm.pulleys.r, dtype=float)


def _at_rest(result, model, sysm):
    """A drive that nothing drives must keep its belt in place (limit: at_rest_limit)."""
    if excited(model):
        return
    ds = result.ds
    t = ds["time"].values
    w_max = np.abs(ds["speed"].values).max(axis=0)
    limit = at_rest_limit(sysm, max(float(t[-1]), 1e-12))
    result.summary["at_rest"] = {"speed_max": {n: float(v) for n, v in zip(sysm.layout.names, w_max)},
                                 "residual_force": float(sysm.init.residual)}
    j = int(np.argmax(w_max / limit))
    if w_max[j] > limit[j]:
        why = ("the belt did not start at its static equilibrium" if not np.isfinite(sysm.init.residual)
               else "a force the static balance does not hold")
        result.diagnose("at-rest-drift", f"nothing drives this belt, yet pulley {sysm.layout.names[j]} reaches "
                        f"{w_max[j]:.3g} rad/s ({why})",
                        f"at_rest.speed_max.{sysm.layout.names[j]}", w_max[j], limit[j], "rad/s")
