"""Time integration driver: builds the system, runs the compiled kernels sample by sample,
keeps every sample computed (also when the solve fails) and assembles the Result."""
from __future__ import annotations

import math
import time as _time

import numpy as np
import xarray as xr

from ...core.errors import ModelError, SolverError, Stopped, stop_reason
from ...core.model import dumps
from ...core.results import Result, unit_map, variable
from ...core.window import in_window, steady_window
from . import _kernels as K
from .teeth_outputs import TeethRecorder
from .teeth_outputs import summary as teeth_summary
from .teeth_outputs import variables as teeth_variables
from . import ahead as _ahead
from . import tail as _tail
from .compiled import compile_note, compiled
from .state import clear_accumulators, new_state, new_work
from .system import TURN_PER_STEP, BeltSystem, build, stability_limit
from ..geometry.drive import resolve
from ..model import integrator
from .resolution import discretisation
from ..dynamics.outputs import UNITS, clutch_variables, run_summary, tensioner_variables

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
        self.teeth = None               # teeth_outputs.TeethRecorder of a synchronous belt


def _loop_args(sysm: BeltSystem, h, S, W):
    """The time loop's (``_kernels._advance``) arguments for one step of h from state S."""
    B, C, P, A = sysm.groups
    return (1, 0.0, h, B, C, P, A, S, W, *K.scheme(B), K.scratch(B, P))


def _compile_ahead(sysm: BeltSystem):
    """The time loop compiled in a second process while the belt settles (ahead.py), or None."""
    S = new_state(sysm)
    return _ahead.start(K.__name__, "_advance", _loop_args(sysm, sysm.step, S, new_work(sysm, S)),
                        before=f"{_tail.__name__}:compile_forward")


def _integrate_semi_implicit(sysm: BeltSystem, progress, rec: _Recorder, nsamples, steps_per_sample, h, frame_every,
                             ahead=None):
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

    records = _loop_args(sysm, h, S, W)[3:]    # (step_chunk, once per run)
    with compile_note(progress, integrator(sysm.model), now=ahead is not None):
        if ahead is not None:
            # the loop's last stages compiled here meanwhile, from the last back (tail.py)
            _tail.compile_back(_tail.stages(h, *records[:6], records[-1]), ahead.busy, ahead.claims)
            if ahead.busy():     # xarray's first dataset looks for dask and pint (0.4 s): done meanwhile
                xr.Dataset({"warm": ("time", np.zeros(1))})
            ahead.wait()         # then loaded from numba's cache (or compiled here if that failed)
        step = compiled(K._advance, (1, 0.0, h, *records))
    hstep = [h]

    def advance(nsteps, t):
        return step(nsteps, t, hstep[0], *records)

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
        if rec.teeth is not None:
            rec.teeth.sample(k, S, W)
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


def run(drive, progress=None) -> Result:
    """Integrate ``drive`` (geometry.drive.Drive, or a model) with the segment model."""
    drive = resolve(drive)
    model = drive.model
    ahead = []        # the time loop compiling in a second process (the first system built starts it)

    def before_settle(sysm):
        if not ahead:
            ahead.append(_compile_ahead(sysm))

    try:
        sysm = build(drive, before_settle=None if integrator(model) == "rkf45" else before_settle)
        return _run(drive, sysm, progress, ahead[0] if ahead else None)
    finally:
        if ahead and ahead[0] is not None:
            ahead[0].close()


def _run(drive, sysm, progress, ahead) -> Result:
    model = drive.model
    sim = model.simulation
    if sim.step is None:     # the step the model sets (a given one was checked with the model)
        from ...core.limits import steps_problem

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
    rec.teeth = TeethRecorder(nsamples, sysm) if sysm.contact.teeth else None
    wall0 = _time.perf_counter()
    steps_per_sample = max(1, int(math.ceil(interval / sysm.step)))
    h = interval / steps_per_sample
    try:
        if integrator(model) != "rkf45":
            done, failure = _integrate_semi_implicit(sysm, progress, rec, nsamples, steps_per_sample, h, frame_every,
                                                     ahead)
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
    if rec.teeth is not None:
        ds = teeth_variables(ds, rec.teeth, ns, sysm)
    tensioner_variables(ds, model, sysm, rec, ns)
    clutch_variables(ds, model, sysm, rec, ns, float(rec.t[0]) if ns else 1.0)
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
    summary = run_summary(model, sysm, ds, solver, sel, window, discretisation(model, sysm))
    if rec.teeth is not None and ns:
        summary["teeth"] = teeth_summary(ds, rec.teeth, sel, sysm, model)
    ds.attrs["steady_window"] = [float(window[0]), float(window[1])]   # for the plots
    ds.attrs["animation"] = int(model.output.animation)
    if ns:
        from ..dynamics.runup import add_runup

        summary.update(add_runup(ds, model, model.output.runup_bin))
    result = Result("belt-drive", ds, summary, success=not failure, message=failure)
    if ns:
        from .diagnose import run_checks

        run_checks(result, model, sysm, sel)
    result.units = unit_map(result.summary, UNITS)
    return result


