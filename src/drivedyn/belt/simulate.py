"""Time integration driver: builds the system, runs the compiled kernels sample by sample,
keeps every sample computed (also when the solve fails) and assembles the Result."""
from __future__ import annotations

import math
import time as _time

import numpy as np
import xarray as xr

from ..errors import ModelError, SolverError, Stopped, stop_reason
from ..model import dumps
from ..results import Result, unit_map, variable
from ..window import in_window, steady_window
from . import _kernels as K
from .system import BeltSystem, build, clear_accumulators, new_state, new_work, stability_limit
from .model import integrator
from .resolution import discretisation

# the implicit scheme's accuracy rule, per friction law: a segment rolling on a pulley turns at
# most this far per step (rad), measured by the fastest pulley's speed. It was 0.003 while the
# chain's grid-scale rotation mode ran undamped (system.GRID_ZETA): at larger turns the steps
# pumped that mode and the 5PK held at 800 rad/s read 1.2-4.9 % high. With the mode damped,
# against the semi-implicit scheme at the same segments: the 5PK at 800 rad/s (424 segments)
# within 0.04 % (elastic-plastic) and 0.3 % (Threlfall) at 0.020 rad per step, 0.2 % and 1 % at
# 0.028 (Threlfall's then misses 4 % of the energy); examples/fead-runup.toml's drive held with
# its orders (333 segments, elastic-plastic) within 1.5 % at 5000 rpm and 0.012-0.035 rad and
# within 1 % of the 4x-refined run at 3000 rpm and 0.032 rad, but at 0.056 rad (5000 rpm, 40 us) it
# ran away and the step control halved the step. Under Threlfall's law the same drive at 3000 rpm
# (330 segments) read the alternator-tensioner span's minimum 3.6 % high at 0.019 rad per step,
# 0.4 % at 0.0096 (tests/belt/test_implicit.py).
TURN_PER_STEP = {"elastic-plastic": 0.02, "threlfall": 0.01}
# a run has blown up once a segment or pulley surface moves faster than this (m/s) or a segment
# sinks deeper than this share of the smallest pulley radius (_blow_up, _healthy)
SPEED_MAX = 1e3
#: a stable step below this (s) means a stiffness or mass far outside any belt (1-40 us): refused
MIN_STEP = 1e-8
PEN_MAX = 0.5


class _Recorder:
    """Preallocated sample arrays; trimmed to what was computed."""

    def __init__(self, ns, nk, nspan, ntrack, nframes, n, na=0):
        self.t = np.zeros(ns)
        self.omr = np.zeros((ns, nk))        # rotor speed behind a clutch, at the sample
        self.q = np.zeros((ns, na))          # tensioner travel (rad or m) and rate, at the sample
        self.qd = np.zeros((ns, na))
        self.theta = np.zeros((ns, nk))
        self.omega = np.zeros((ns, nk))
        self.tq_ext = np.zeros((ns, nk))
        self.tq_belt = np.zeros((ns, nk))
        self.hubx = np.zeros((ns, nk))
        self.huby = np.zeros((ns, nk))
        self.pin = np.zeros((ns, nk))
        self.span = np.zeros((ns, nspan))
        self.span_speed = np.zeros((ns, nspan))
        self.track = np.zeros((ns, ntrack, 3))
        self.diss = np.zeros((ns, 6))        # cumulative dissipated energy by mechanism (J)
        self.work = np.zeros(ns)             # cumulative work in (J)
        self.energy = np.zeros(ns)
        self.frame_t = np.zeros(nframes)
        self.fx = np.zeros((nframes, n))
        self.fy = np.zeros((nframes, n))
        self.fn = np.zeros((nframes, n))
        self.ft = np.zeros((nframes, n))
        self.ftension = np.zeros((nframes, n))
        self.ns = 0
        self.steps, self.step = 0, 0.0  # adaptive steps and last step size so far (rkf45)
        self.rejected, self.rhs = 0, 0  # rejected steps and right-hand-side evaluations (rkf45)
        self.nf = 0


def _integrate_semi_implicit(sysm: BeltSystem, progress, rec: _Recorder, nsamples, steps_per_sample, h, frame_every):
    B, C, P, A = sysm.groups
    S = new_state(sysm)
    W = new_work(sysm, S)

    def energy():
        return K.energy(B, C, P, A, S)

    def capture_frame(t):
        k = rec.nf
        if k >= len(rec.frame_t):
            return
        rec.frame_t[k] = t
        rec.fx[k], rec.fy[k], rec.fn[k], rec.ft[k] = S.x, S.y, W.seg_n, W.seg_t
        rec.ftension[k] = W.jfk * np.hypot(W.jdx, W.jdy)
        rec.nf += 1

    # fill joint forces once so that frame 0 has element tensions
    K.joint_forces(B, S, W, 0.0)
    E0 = energy()
    t = 0.0
    capture_frame(t)
    interval = steps_per_sample * h
    work = 0.0
    diss_total = np.zeros(6)
    last_report = -1.0
    saved_parts = (*S, W.span_joint)         # what a replay restores
    saved = [a.copy() for a in saved_parts]
    r_min = float(np.min(sysm.pulleys.r))

    lin = True if B.implicit else None       # the implicit scheme's compile-time switch
    step = _compiled(K.step_chunk, (1, 0.0, h, B, C, P, A, S, W, lin))
    hstep = [h]

    def advance(nsteps, t):
        return step(nsteps, t, hstep[0], B, C, P, A, S, W, lin)

    # the implicit scheme's step control: checkpoints every 10 ms; a run that goes unstable (a
    # segment turning far faster than any pulley, or a blow-up) goes back two checkpoints and
    # continues at half the step, down to the semi-implicit scheme's step
    implicit = B.implicit
    every = max(1, int(round(0.01 / interval)))
    checkpoints = []
    # (or an eighth of the step where the explicit limit is the larger: the verification drive)
    h_min = min(0.85 * stability_limit(sysm.model, sysm.init, B, C), h / 8) if implicit else h
    rec.step_reductions, rec.speed_reductions, rec.steps_done = 0, 0, 0
    speed_rule = implicit and sysm.model.simulation.step is None     # a step the user gave is kept
    turn_max = TURN_PER_STEP[sysm.model.friction.law]
    k = 0
    while k < nsamples:
        if implicit and k % every == 0:
            checkpoints = (checkpoints + [(k, t, [a.copy() for a in saved_parts] + [W.lin_st.copy()], work,
                                           diss_total.copy(), rec.nf, rec.steps_done)])[-3:]
        clear_accumulators(W)
        for a, b in zip(saved, saved_parts):
            np.copyto(a, b)
        t0 = t
        t = advance(steps_per_sample, t)
        rec.steps_done += steps_per_sample
        healthy = _healthy(W.probe, r_min, implicit)
        if not healthy and implicit and hstep[0] / 2 >= h_min and checkpoints:
            k, t, parts, work, diss_total, rec.nf, rec.steps_done = checkpoints[0]
            diss_total = diss_total.copy()
            for a, b in zip(saved_parts + (W.lin_st,), parts):
                a[...] = b
            checkpoints = checkpoints[:1]
            steps_per_sample *= 2
            hstep[0] = interval / steps_per_sample
            W.lin_cnt[0] = 0                     # refactor at the new step
            W.cand_skip[:] = 0                   # and test every contact again
            rec.step_reductions += 1
            continue
        if not healthy and _blow_up(S.x, S.y, S.vx, S.vy, S.om, W.seg_p, sysm):
            # replay the sample step by step from its start to name the first quantity that ran away
            for a, b in zip(saved_parts, saved):
                a[...] = b
            W.lin_cnt[0] = 0          # the implicit scheme refactors its chain matrix from there
            W.cand_skip[:] = 0        # and tests every contact again
            rec.steps_done -= steps_per_sample
            return k, "diverged " + _first_runaway(advance, t0, steps_per_sample, hstep[0], S, sysm)
        work += float(np.sum(W.acc_pin))
        diss_total += W.acc_diss
        rec.t[k] = (k + 1) * interval      # exact sample times (the accumulated t carries round-off)
        rec.theta[k], rec.omega[k] = S.th, S.om
        rec.q[k], rec.qd[k] = S.q, S.qd
        rec.omr[k] = S.omr
        rec.tq_ext[k], rec.tq_belt[k] = W.acc_tq_ext / interval, W.acc_tq_belt / interval
        rec.hubx[k], rec.huby[k] = W.acc_hubx / interval, W.acc_huby / interval
        rec.pin[k] = W.acc_pin / interval
        rec.span[k] = W.acc_span[:, 0] / interval
        rec.span_speed[k] = W.acc_span[:, 1] / interval
        rec.track[k] = W.acc_track / interval
        rec.diss[k] = diss_total
        rec.work[k] = work
        rec.energy[k] = W.energy[0] - E0
        rec.ns = k + 1
        if (k + 1) % frame_every == 0:
            capture_frame(t)
        if progress is not None and (k + 1) / nsamples - last_report >= 0.01:
            last_report = (k + 1) / nsamples
            progress(last_report, f"t = {t:.3f} s")
        # the implicit scheme's work: chain factorisations, active-set passes, stick-slip changes
        rec.implicit = (int(W.lin_cnt[1]), int(W.lin_cnt[3]), int(W.lin_stat[0] + W.lin_stat[1]))
        rec.h_final = hstep[0]
        k += 1
        if speed_rule and hstep[0] * W.probe[5] > turn_max:
            # the implicit scheme's accuracy rule: a segment rolling on a pulley turns at most
            # turn_max per step (the pulley's speed: the segments' own rates jump where they
            # land); a faster drive continues at the step that keeps it, with 5 % to spare (a
            # run-up changes it every few percent of speed, not at every sample)
            steps = max(steps_per_sample + 1, math.ceil(1.05 * interval * W.probe[5] / turn_max))
            if interval / steps >= h_min:      # (else as small as it goes: the diagnostics say so)
                steps_per_sample = steps
                hstep[0] = interval / steps_per_sample
                W.lin_cnt[0] = 0
                rec.speed_reductions += 1
    return nsamples, ""


def _compiled(dispatcher, args):
    """The compiled entry of ``dispatcher`` for these argument types: calling it skips numba's
    type dispatch, which for the kernel's records costs about 28 us a call against 15 (one call per
    output sample). The dispatcher itself when numba's internals differ."""
    try:
        dispatcher.compile(tuple(dispatcher.typeof_pyval(a) for a in args))
        sig = tuple(dispatcher.typeof_pyval(a) for a in args)
        return dispatcher.overloads[sig].entry_point
    except Exception:   # an internal API that moved: the ordinary call still works
        return dispatcher


def _first_runaway(advance, t, nsteps, h, state, sysm):
    """Step one step at a time and report the first segment or pulley speed that ran away."""
    vx, vy, om = state.vx, state.vy, state.om
    pr = sysm.pulleys.r
    v_ref = max(float(np.max(np.hypot(vx, vy))), float(np.max(np.abs(om) * pr)), 1.0)
    for _ in range(nsteps):
        v_before = np.hypot(vx, vy)
        t = advance(1, t)
        v = np.hypot(vx, vy)
        bad = ~(v < 10 * v_ref)
        if np.any(bad):
            i = int(np.argmax(np.where(bad, np.inf, v)) if np.any(~np.isfinite(v)) else np.argmax(v))
            return (f"at t = {t:.6g} s: segment {i} speed {v[i]:.3g} m/s (was {v_before[i]:.3g} m/s a step "
                    f"before, {h:.3g} s); is the step above the stability limit ({sysm.step_limit:.3g} s)?")
        spd = np.abs(om) * pr
        if not np.all(spd < 10 * v_ref + 100):
            j = int(np.argmax(np.where(np.isfinite(spd), spd, np.inf)))
            return f"at t = {t:.6g} s: pulley {sysm.layout.names[j]} speed {om[j]:.3g} rad/s"
    return f"by t = {t:.6g} s: the belt state ran out of bounds"


def _healthy(probe, r_min, implicit):
    """The kernel's probe of the state at the end of a chunk (_kernels.Work.probe) passes the
    checks of ``_blow_up`` and, under the implicit scheme, no segment spins: none turns ten times
    faster than the fastest pulley (and over 100 rad/s), that scheme's sign that its step is too
    large (gross slip at 40 us on the 5PK). 0.5 us against 50 us for the checks in numpy."""
    fin, v2, surface, pen, w = probe[:5]
    ok = math.isfinite(fin) and v2 <= SPEED_MAX ** 2 and surface <= SPEED_MAX and pen <= PEN_MAX * r_min
    return ok and not (implicit and w > 10 * surface / r_min + 100.0)


def _blow_up(x, y, vx, vy, om, pen, sysm):
    """Name the quantity that blew up, or return ''."""
    v2 = vx * vx + vy * vy
    i = int(np.argmax(v2))
    if not np.isfinite(v2[i]) or not np.all(np.isfinite(x)) or not np.all(np.isfinite(y)):
        return f"segment {i} state is not finite"
    if v2[i] > SPEED_MAX ** 2:
        return f"segment {i} speed {math.sqrt(v2[i]):.3g} m/s"
    pr = sysm.pulleys.r
    j = int(np.argmax(np.abs(om) * pr))
    if not np.isfinite(om[j]) or abs(om[j]) * pr[j] > SPEED_MAX:
        return f"pulley {sysm.layout.names[j]} speed {om[j]:.3g} rad/s"
    if np.max(pen) > PEN_MAX * np.min(pr):
        i = int(np.argmax(pen))
        return f"segment {i} penetration {pen[i] * 1e3:.3g} mm"
    return ""


def lean_possible(model, keys) -> bool:
    """Whether :func:`run_lean` gives the summary keys ``keys`` (patterns) of ``model``: a periodic
    run-up of the rotational model, the keys its run-up tables (periodic.lean_keys)."""
    if model.simulation.model != "rotational" or model.simulation.runup != "periodic":
        return False
    from .periodic import lean_keys

    return lean_keys(keys) is not None


def run_lean(model, keys, progress=None):
    """A run that computes only the summary keys ``keys`` (a design loop's objective and
    constraints), with the full run's numbers; None when only the full run gives them."""
    if not lean_possible(model, keys):
        return None
    from .periodic import run as run_periodic

    return run_periodic(model, progress, keys=keys)


def run(model, progress=None) -> Result:
    if model.simulation.model == "rotational":
        from .periodic import run as run_periodic
        from .rotational import run as run_rotational

        return (run_periodic if model.simulation.runup == "periodic" else run_rotational)(model, progress)
    sysm = build(model)
    sim = model.simulation
    if sim.step is None:     # the step the model sets (a given one was checked with the model)
        from ..limits import steps_problem

        if sysm.step < MIN_STEP:
            raise ModelError(f"the stable step of this belt is {sysm.step:.3g} s, below {MIN_STEP:g} s (belts run at "
                             "1-40 us): contact.stiffness_*, belt.axial_stiffness or the segment mass is not "
                             "physical", field="contact")
        problem = steps_problem(sim.duration / sysm.step, "simulation.duration",
                                f"the stable step of this belt is {sysm.step:.3g} s (set by its contact and "
                                "element stiffness and segment mass): a shorter duration, softer contact.stiffness_*, "
                                "or fewer belt.segments")
        if problem:
            raise ModelError(problem, field="simulation.duration")
    sim, out = model.simulation, model.output
    # whole samples that end exactly at the duration (the interval is adjusted by < half a sample)
    nsamples = max(1, int(round(sim.duration / out.interval)))
    interval = sim.duration / nsamples
    nk, n = len(sysm.layout.names), sysm.n
    frames = min(out.frames, nsamples)
    frame_every = max(1, nsamples // frames)
    rec = _Recorder(nsamples, nk, len(sysm.span_mid), len(sysm.track), nsamples // frame_every + 2, n, sysm.arms.na)
    wall0 = _time.perf_counter()
    steps_per_sample = max(1, int(math.ceil(interval / sysm.step)))
    h = interval / steps_per_sample
    try:
        if integrator(model) != "rkf45":
            done, failure = _integrate_semi_implicit(sysm, progress, rec, nsamples, steps_per_sample, h, frame_every)
            nsteps = rec.steps_done
            h = getattr(rec, "h_final", h)
        else:
            from .rkf45 import integrate_rkf45

            done, failure, nsteps, h = integrate_rkf45(sysm, progress, rec, nsamples, frame_every, interval)
    except (Stopped, KeyboardInterrupt, ZeroDivisionError) as exc:
        # a time limit, Ctrl-C, or a state that ran away inside a sample (a joint or a span of zero
        # length): keep the whole samples recorded so far (rec.ns counts them)
        if isinstance(exc, ZeroDivisionError):
            failure = (f"diverged after t = {rec.t[rec.ns - 1] if rec.ns else 0.0:.6g} s (a division by zero in "
                       "the step: a state ran away; is the step above the stability limit?)")
        else:
            failure = f"stopped: {stop_reason(exc)}"
        if integrator(model) != "rkf45":
            nsteps = getattr(rec, "steps_done", rec.ns * steps_per_sample)
        else:
            nsteps, h = rec.steps, rec.step or h
    wall = _time.perf_counter() - wall0
    result = _assemble(model, sysm, rec, wall, nsteps, h, failure)
    if not failure and sim.resolution_check:
        from .resolution import check

        if progress is not None:
            progress(1.0, "resolution check: a second run at 0.7 x the segments")
        check(model, result, run)
    if failure:
        raise SolverError(failure + f" (results kept up to t = {rec.t[rec.ns - 1] if rec.ns else 0.0:.6g} s)", partial=result)
    return result


def _assemble(model, sysm, rec: _Recorder, wall, nsteps, h, failure) -> Result:
    ns, nf = rec.ns, rec.nf
    names = list(sysm.layout.names)
    spans = [sp.name for sp in sysm.layout.spans]
    tr = sysm.track
    hub = np.hypot(rec.hubx[:ns], rec.huby[:ns])
    E, W, D = rec.energy[:ns], rec.work[:ns], rec.diss[:ns]
    ds = xr.Dataset(
        {
            "angle": variable(rec.theta[:ns], ("time", "pulley"), "rad", "pulley angle (counter-clockwise positive)"),
            "speed": variable(rec.omega[:ns], ("time", "pulley"), "rad/s", "pulley angular speed (counter-clockwise positive)"),
            "torque_applied": variable(rec.tq_ext[:ns], ("time", "pulley"), "N m", "applied torque, interval mean"),
            "torque_belt": variable(rec.tq_belt[:ns], ("time", "pulley"), "N m", "torque of the belt on the pulley, interval mean"),
            "hub_force_x": variable(rec.hubx[:ns], ("time", "pulley"), "N", "belt force on the pulley, x, interval mean"),
            "hub_force_y": variable(rec.huby[:ns], ("time", "pulley"), "N", "belt force on the pulley, y, interval mean"),
            "hub_load": variable(hub, ("time", "pulley"), "N", "hub load magnitude"),
            "power_in": variable(rec.pin[:ns], ("time", "pulley"), "W", "power into the belt system through the pulley"),
            "span_tension": variable(rec.span[:ns], ("time", "span"), "N", "mid-span element force, interval mean"),
            "span_speed": variable(rec.span_speed[:ns], ("time", "span"), "m/s", "mid-span belt speed along the span (belt order positive)"),
            "element_force": variable(rec.track[:ns, :, 0], ("time", "tracked"), "N", "longitudinal element force after the segment (seed fig. 11)"),
            "normal_force": variable(rec.track[:ns, :, 1], ("time", "tracked"), "N", "contact normal force on the segment (seed fig. 12)"),
            "friction_force": variable(rec.track[:ns, :, 2], ("time", "tracked"), "N", "friction force on the segment, along the pulley's counter-clockwise tangent (seed fig. 13)"),
            "energy_change": variable(E, ("time",), "J", "mechanical energy minus its initial value"),
            "work_in": variable(W, ("time",), "J", "cumulative work done on the system by the pulleys"),
            "dissipated": variable(D, ("time", "mechanism"), "J", "cumulative dissipated energy"),
            "energy_residual": variable(W - D.sum(axis=1) - E, ("time",), "J", "work in - dissipated - energy change (integration error)"),
            "belt_x": variable(rec.fx[:nf], ("frame", "segment"), "m", "segment centre x"),
            "belt_y": variable(rec.fy[:nf], ("frame", "segment"), "m", "segment centre y"),
            "belt_normal_force": variable(rec.fn[:nf], ("frame", "segment"), "N", "contact normal force per segment"),
            "belt_friction_force": variable(rec.ft[:nf], ("frame", "segment"), "N", "friction force per segment"),
            "belt_tension": variable(rec.ftension[:nf], ("frame", "joint"), "N", "element force per joint (joint i joins segment i-1 to i)"),
            "pulley_x": variable(sysm.pulleys.cx.copy(), ("pulley",), "m", "pulley centre x (a tensioner's: at rest)"),
            "pulley_y": variable(sysm.pulleys.cy.copy(), ("pulley",), "m", "pulley centre y (a tensioner's: at rest)"),
            "pulley_radius": variable([p.radius for p in model.pulleys], ("pulley",), "m", "contact radius"),
            "pulley_rolling_radius": variable(sysm.rolling_radius, ("pulley",), "m",
                                              "belt length the segment chain carries per radian of pulley turn, no load"),
        },
        coords={"time": rec.t[:ns], "pulley": names, "span": spans, "tracked": tr, "frame_time": ("frame", rec.frame_t[:nf]),
                "mechanism": ["axial_damping", "bending_damping", "contact_damping", "friction", "tensioner", "clutch"]},
        attrs={"model_toml": dumps(model), "title": model.name or "belt drive"},
    )
    _tensioner_variables(ds, model, sysm, rec, ns)
    _clutch_variables(ds, model, sysm, rec, ns, float(rec.t[0]) if ns else 1.0)
    ds["time"].attrs["units"] = "s"
    t = rec.t[:ns]
    t_end = float(t[-1]) if ns else 0.0
    window = steady_window(model.output.steady_window, model.simulation.duration)
    sel = in_window(t, window)
    if not np.any(sel):     # a run stopped before the window: the last quarter of what was computed
        window = steady_window(None, t_end)
        sel = in_window(t, window)
    semi = integrator(model) != "rkf45"
    # the one solver record (same keys in every time integration), extras after it
    solver = {"method": integrator(model), "steps": int(nsteps),
              "rejected_steps": 0 if semi else int(rec.rejected),
              "rhs_evaluations": int(nsteps) if semi else int(rec.rhs),   # semi-implicit: one force pass per step
              "last_step": float(h), "wall_time": float(wall), "simulated_time": t_end,
              "status": "failed" if failure else "success",
              "step": float(h), "stability_limit": float(sysm.step_limit),
              "rotation_scaling": bool(sysm.belt.iscale > 1.0),
              "real_time_factor": float(t_end / wall) if wall > 0 else float("nan")}
    if integrator(model) == "implicit" and getattr(rec, "implicit", None):
        solver["factorisations"], solver["active_set_passes"], solver["stick_slip_changes"] = rec.implicit
        solver["step_reductions"] = int(getattr(rec, "step_reductions", 0))      # a run going unstable
        solver["speed_reductions"] = int(getattr(rec, "speed_reductions", 0))    # the accuracy rule
    summary = _summary(model, sysm, ds, solver, sel, window)
    ds.attrs["steady_window"] = [float(window[0]), float(window[1])]   # for the plots
    ds.attrs["animation"] = int(model.output.animation)
    if ns:
        from .runup import add_runup

        summary.update(add_runup(ds, model, model.output.runup_bin))
    result = Result("belt-drive", ds, summary, success=not failure, message=failure)
    if ns:
        from .diagnose import run_checks

        run_checks(result, model, sysm, sel)
    result.units = unit_map(result.summary, UNITS)
    return result


def _clutch_variables(ds, model, sysm, rec, ns, interval):
    """Rotor speed behind each clutch and the clutch torque on the rotor in its drive sense (interval
    mean, exact: I_r d omega_r / dt minus the accessory loads on the rotor)."""
    P = sysm.pulleys
    sel = [j for j in range(P.nk) if P.cl_kind[j] > 0]
    if not sel:
        return
    ds.coords["clutch"] = [model.pulleys[j].name for j in sel]
    omr = rec.omr[:ns, sel]
    prev = np.vstack([np.zeros((1, len(sel))), omr[:-1]])
    tc = (P.cl_ir[sel] * (omr - prev) / interval - rec.tq_ext[:ns, sel]) * P.cl_s[sel]
    ds["rotor_speed"] = variable(omr, ("time", "clutch"), "rad/s", "accessory rotor speed behind the clutch")
    ds["clutch_torque"] = variable(tc, ("time", "clutch"), "N m", "torque the clutch passes to the rotor, in its drive "
                                   "sense (interval mean; >= 0 for an overrunning clutch)")


def _tensioner_variables(ds, model, sysm, rec, ns):
    """Arm angle and speed (pivoted tensioners), slide position and speed (linear ones), over time."""
    A = sysm.arms
    for kind, dim, names in ((0, "arm", "arm"), (1, "slider", "slider")):
        sel = [a for a in range(A.na) if A.kind[a] == kind]
        if not sel:
            continue
        ds.coords[dim] = [model.pulleys[A.pulley[a]].name for a in sel]
        q, qd = rec.q[:ns, sel], rec.qd[:ns, sel]
        if kind == 0:
            psi = A.psi0[sel] + A.sgn[sel] * q
            ds["arm_angle"] = variable(psi, ("time", dim), "rad", "tensioner arm angle about its pivot (counter-clockwise from x)")
            ds["arm_travel"] = variable(q, ("time", dim), "rad", "arm travel from the drawn position, into the belt positive")
            ds["arm_speed"] = variable(qd, ("time", dim), "rad/s", "arm travel rate")
        else:
            ds["slider_travel"] = variable(q, ("time", dim), "m", "slider travel from the drawn position, into the belt positive")
            ds["slider_speed"] = variable(qd, ("time", dim), "m/s", "slider travel rate")


#: units of the summary keys (results.unit_map: first matching pattern wins; "1" for ratios)
UNITS = {
    "steady_window": "s",
    "pulleys.*.speed_mean": "rad/s", "pulleys.*.hub_load": "N", "pulleys.*.hub_force": "N",
    "pulleys.*.torque_mean": "N*m", "pulleys.*.power_mean": "W",
    "pulleys.*.slip": "1", "pulleys.*.creep": "1", "pulleys.*.creep_bound": "1", "pulleys.*.sliding": "1",
    "pulleys.*.sliding_share": "1", "pulleys.*.contact_share": "1", "pulleys.*.peak_normal_ratio": "1",
    "pulleys.*.chordal_error": "1", "pulleys.*.slip_margin": "1",
    "spans.*.tension_*": "N", "spans.*.speed_mean": "m/s",
    "power.efficiency": "1", "power.energy_residual_*": "1", "power.*": "W",
    "belt.pretension": "N", "belt.segment_length": "m", "belt.path_length": "m", "belt.displacement_limit": "m",
    "discretisation.segment_length": "m", "discretisation.chordal_speed_error": "1",
    "discretisation.segments*": "", "discretisation.unresolved_wraps.*": "deg",
    "discretisation.estimate.coarse_segments": "", "discretisation.estimate.auto_segments": "",
    "discretisation.estimate.method": "", "discretisation.estimate.power_loss_method": "",
    "discretisation.estimate.unavailable": "", "discretisation.estimate.power_loss_note": "",
    "discretisation.estimate.runup_note": "",
    "discretisation.estimate.coarse_status": "", "discretisation.estimate.power_loss.*": "W",
    "discretisation.estimate.*": "1", "discretisation.grid_damping.bending_damper": "N*m*s/rad",
    "discretisation.grid_damping.damping_ratio": "1", "discretisation.*": "",
    "steady.*": "1", "at_rest.speed_max.*": "rad/s", "at_rest.residual_force": "1",
    "solver.last_step": "s", "solver.step": "s", "solver.stability_limit": "s", "solver.wall_time": "s",
    "solver.simulated_time": "s", "solver.real_time_factor": "1",
    "tensioners.*.arm_angle_*": "rad", "tensioners.*.travel_*": "rad", "tensioners.*.slide_*": "m",
    "tensioners.*.hub_load*": "N", "tensioners.*.rest_*_torque": "N*m", "tensioners.*.rest_*_force": "N",
    "tensioners.*.rest_arm_angle": "rad", "tensioners.*.rest_travel": "rad", "tensioners.*.rest_slide": "m",
    "tensioners.*.rest_tension": "N",
    "clutches.*.torque_mean": "N*m", "clutches.*.rotor_speed_mean": "rad/s", "clutches.*.overrun_share": "1",
    "runup.order_peaks.arm_travel.*.amplitude": "rad", "runup.order_peaks.*.amplitude": "N",
    "runup.order_peaks.*.rpm": "rpm", "runup.speed_rpm": "rpm", "runup.sweep": "", "runup.span_tension_*": "N", "runup.hub_load_max.*": "N", "runup.slip.*": "1",
    "runup.arm_travel_range.*": "rad", "runup.orders": "1", "runup.crank": "",
}


def warm():
    """Run a tiny drive for a few steps so that every kernel is loaded from numba's cache."""
    from ..model import from_dict

    m = from_dict({"kind": "belt-drive", "belt": {"mass_per_length": 0.1, "axial_stiffness": 1e5, "pretension": 100.0,
                                                   "segments": 24},
                   "contact": {"stiffness_linear": 1e8}, "simulation": {"duration": 2e-4},
                   "output": {"interval": 1e-4, "frames": 1},
                   "pulleys": [{"name": "a", "center": [0, 0], "radius": 0.03},
                               {"name": "b", "center": [0.2, 0], "radius": 0.03}]})
    run(m)


def friction_law(model) -> dict:
    """What the summary says of the friction law (the answers depend on it: docs/belt-drive.md,
    Delta_max): its name and, for the elastic-plastic law, Delta_max."""
    f = model.friction
    if f.law == "elastic-plastic":
        return {"friction_law": f.law, "displacement_limit": float(f.displacement_limit)}
    return {"friction_law": f.law}


def _summary(model, sysm, ds, solver, sel, window, disc=None) -> dict:
    t = ds["time"].values
    w0, w1 = window
    mean = lambda v: ds[v].values[sel].mean(axis=0) if np.any(sel) else np.full(ds[v].shape[1:], np.nan)
    names = list(sysm.layout.names)
    speed, pin = mean("speed"), mean("power_in")
    hx, hy, tq = mean("hub_force_x"), mean("hub_force_y"), mean("torque_applied")
    # a pulley held at a prescribed speed: the torque that holds it there against the belt (the
    # drive's reaction torque, minus the belt's torque on it), so that torque x speed is its power
    tqb = mean("torque_belt")
    tq = np.where(sysm.pulleys.mode == 1, -tqb, tq)
    # slip against the chain's own rolling kinematics: the polygon effect of the segments, a speed
    # ratio error of about l^2 / (12 r^2) between pulleys of different radii, is no slip
    radius = sysm.rolling_radius
    d = int(np.nanargmax(pin)) if np.any(np.isfinite(pin)) else 0
    vd = abs(speed[d] * radius[d])
    pulleys = {}
    for j, nm in enumerate(names):
        pulleys[nm] = {
            "speed_mean": float(speed[j]),
            "slip": float(1 - abs(speed[j] * radius[j]) / vd) if vd > 0 else float("nan"),
            "hub_load": float(math.hypot(hx[j], hy[j])),
            "hub_force": [float(hx[j]), float(hy[j])],
            "torque_mean": float(tq[j]),
            "power_mean": float(pin[j]),
        }
    ten, vsp = mean("span_tension"), mean("span_speed")
    tsel = ds["span_tension"].values[sel] if np.any(sel) else np.zeros((0, len(ten)))
    spans = {sp: {"tension_mean": float(ten[q]),
                  "tension_min": float(tsel[:, q].min()) if len(tsel) else float("nan"),
                  "tension_max": float(tsel[:, q].max()) if len(tsel) else float("nan"),
                  "speed_mean": float(vsp[q])}
             for q, sp in enumerate(ds["span"].values.tolist())}
    # creep on each pulley: 1 - |belt speed leaving| / |belt speed arriving| (span k leaves pulley k)
    forward = float(np.nansum(vsp)) >= 0
    for j, nm in enumerate(names):
        v_arr, v_out = (vsp[j - 1], vsp[j]) if forward else (vsp[j], vsp[j - 1])
        pulleys[nm]["creep"] = float(1 - abs(v_out) / abs(v_arr)) if abs(v_arr) > 1e-9 else float("nan")
    p_in = float(np.sum(pin[pin > 0]))
    p_out = float(-np.sum(pin[pin < 0])) + 0.0     # + 0.0: no "-0" when nothing is taken out
    # mean dissipation rates over the window from the cumulative energies
    D = ds["dissipated"].values
    tw = t[sel]
    if len(tw) >= 2:
        idx = np.nonzero(sel)[0]
        rates = (D[idx[-1]] - D[idx[0]]) / (tw[-1] - tw[0])
        resid = ds["energy_residual"].values
        resid_rate = (resid[idx[-1]] - resid[idx[0]]) / (tw[-1] - tw[0])
    else:
        rates, resid_rate = np.full(D.shape[1], np.nan), float("nan")
    mech = ds["mechanism"].values.tolist()
    # the energy stored per second over the window (kinetic and elastic): a run-up stores, a
    # run-down gives back; the transmission efficiency leaves it out, output over output + losses
    E = ds["energy_change"].values
    stored = float((E[idx[-1]] - E[idx[0]]) / (tw[-1] - tw[0])) if len(tw) >= 2 else float("nan")
    lost = float(np.sum(rates))
    return {
        "driver": names[d],
        "steady_window": [float(w0), float(w1)],
        "pulleys": pulleys,
        "spans": spans,
        "power": {
            "input": p_in, "output": p_out,
            "efficiency": p_out / (p_out + lost) if p_out + lost > 0 else float("nan"),
            "stored": stored,
            "losses": {m: float(r) for m, r in zip(mech, rates)},
            "unaccounted": float(resid_rate),
            "energy_residual_relative": float("nan"),     # diagnose._energy: against the work in
        },
        "belt": {"pretension": sysm.init.tension, "segment_length": sysm.init.seg_length,
                 "segments": sysm.n, "path_length": sysm.layout.length, **friction_law(model)},
        "discretisation": discretisation(model, sysm) if disc is None else disc,
        **_tensioner_summary(ds, sysm, sel),
        **_clutch_summary(ds, sel),
        "solver": solver,
    }


def _clutch_summary(ds, sel) -> dict:
    """Per clutch over the window: mean torque passed, rotor speed, and the share of the time the
    rotor overruns (the clutch passes less than 1 % of its mean torque)."""
    if "clutch" not in ds.coords or not np.any(sel):
        return {}
    out = {}
    for name in ds["clutch"].values.tolist():
        tc = ds["clutch_torque"].sel(clutch=name).values[sel]
        mean = float(np.mean(tc))
        out[name] = {"torque_mean": mean, "rotor_speed_mean": float(np.mean(ds["rotor_speed"].sel(clutch=name).values[sel])),
                     "overrun_share": float(np.mean(tc < 0.01 * abs(mean)))}
    return {"clutches": out}


def _tensioner_summary(ds, sysm, sel) -> dict:
    """Per tensioner: the equilibrium at rest, and over the window the arm angle or slide travel
    (mean / min / max) and the hub load (mean, max)."""
    A, rest = sysm.arms, sysm.rest
    if not A.na:
        return {}
    out = {}
    hub = ds["hub_load"].values
    for a in range(A.na):
        j = int(A.pulley[a])
        name = sysm.model.pulleys[j].name
        h = hub[sel, j] if np.any(sel) else np.full(1, np.nan)
        e = {"hub_load": float(np.mean(h)), "hub_load_max": float(np.max(h))}
        if A.kind[a] == 0:
            psi = ds["arm_angle"].sel(arm=name).values[sel] if np.any(sel) else np.full(1, np.nan)
            q = ds["arm_travel"].sel(arm=name).values[sel] if np.any(sel) else np.full(1, np.nan)
            e.update(arm_angle_mean=float(np.mean(psi)), arm_angle_min=float(np.min(psi)), arm_angle_max=float(np.max(psi)),
                     travel_mean=float(np.mean(q)), travel_min=float(np.min(q)), travel_max=float(np.max(q)),
                     rest_arm_angle=float(rest.angle[a]), rest_travel=float(rest.travel[a]),
                     rest_spring_torque=float(rest.spring[a]))
        else:
            q = ds["slider_travel"].sel(slider=name).values[sel] if np.any(sel) else np.full(1, np.nan)
            e.update(slide_mean=float(np.mean(q)), slide_min=float(np.min(q)), slide_max=float(np.max(q)),
                     rest_slide=float(rest.travel[a]), rest_spring_force=float(rest.spring[a]))
        e["rest_tension"] = float(rest.tension)
        out[name] = e
    return {"tensioners": out}
