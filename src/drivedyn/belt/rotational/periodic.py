"""Periodic run-ups (``simulation.runup = "periodic"``, rotational model): the drive's steady
response at each crank speed of a run-up, instead of a time integration of a slow ramp. At each
speed every free pulley (and the rotor behind its clutch) carries its inertia's torque -J alpha at
the ramp's acceleration there: a run-up speeds them up, and the belt pays for it as for a load.

At a constant mean crank speed the steady response repeats after a period of whole crank
revolutions: one for integer engine orders, two with half orders, and as many as the accessories'
own harmonics need at their nominal speed ratios (a 7th order on a pulley turning 1.25 times the
crank: four; their phase is set back in step with the crank at each period, so creep does not let
them drift). The periodic solution is found by shooting on the period map Phi: the state (pulley
and rotor speeds, decoupler wind-up, tensioner travel and rate, the belt in each span and wrap, the
span dampers' rates) at the start of a period -> the state one period later, integrated by the
rotational model (rotational/simulate.py); x = Phi(x) is solved by Anderson-accelerated fixed-point
iteration (Walker & Ni, SIAM J. Numer. Anal. 49 (2011) 1715-1735), with continuation in speed:
each speed starts from the last one's solution. Creep damps the drive's transients within a few
periods; the acceleration guards against lightly damped ones. A speed whose change per period
stays above the tolerance is reported (``unconverged-periodic``, ``runup.periodic_residual``).
"""
from __future__ import annotations

import itertools
import math
import time as _time

import numpy as np

from ...core.errors import ModelError, Stopped, stop_reason
from ...core.limits import bytes_problem, steps_problem
from . import _kernels as RK
from . import teeth as TT
from ..geometry.drive import resolve
from . import simulate as RT
from ..dynamics.frequencies import add_flap_and_modes
from ..dynamics.runup import MAX_PERIOD_REVS, RPM, crank_index, excitation_orders, period_revolutions

#: periodicity tolerance: the largest change over one period of a tension (share of the rest
#: tension), a speed (share of the crank's) or the arm travel (share of 1 mrad)
TOLERANCE = 1e-4
#: period-map evaluations per speed at most
MAX_ITER = 60
#: Anderson memory (past residuals mixed)
MEMORY = 6
#: samples recorded per revolution of the periodic solution
SAMPLES_PER_REV = 96


def speeds_of(model, j):
    """Crank speeds (rad/s, signed) of the sweep: the centres of the run-up's bins (runup.add_runup:
    output.runup_bin wide, 20 bins without one) over the range of the crank's speed table, its
    spin-up from rest left out."""
    p = model.pulleys[j]
    w = [r[1] for r in p.speed_time]
    nonzero = [abs(x) for x in w if abs(x) > 0.05 * max(abs(x) for x in w)]
    lo, hi = min(nonzero), max(nonzero)
    if not hi > lo * (1 + 1e-9):
        raise ModelError(f"\"periodic\" sweeps a run-up: pulley {p.name!r}'s speed_time holds one "
                         "speed after its spin-up (no speed range to sweep)", field="simulation.runup")
    width = model.output.runup_bin or (hi - lo) / 20
    edges = np.arange(math.floor(lo / width) * width, hi + width, width)
    if len(edges) < 2:      # a bin wider than float resolves beside the speeds (1e29 rad/s): one bin
        edges = np.array([math.floor(lo / width) * width, math.floor(lo / width) * width + width])
    keep = (edges[1:] > lo) & (edges[:-1] < hi)
    # each bin's centre within the crank's range: a bin the range covers in part is solved at the
    # middle of that part (a bin of 250 rpm swept 0.01-0.1 rpm at 125 rpm)
    centres = 0.5 * (np.maximum(edges[:-1], lo) + np.minimum(edges[1:], hi))
    if keep.sum() < 2:      # one held speed is no run-up: its tables would be left out without a word
        raise ModelError(f"{width * RPM:.4g} rpm bins leave {int(keep.sum())} crank speed(s) of pulley {p.name!r}'s "
                         f"range {lo * RPM:.4g}-{hi * RPM:.4g} rpm: a periodic run-up solves at least two (a narrower "
                         "bin)", field="output.runup_bin")
    sign = math.copysign(1.0, max(w, key=abs))
    return sign * centres[keep]


def sweep_acceleration(model, j, w):
    """The crank's acceleration (rad/s^2, signed) where its speed_time table passes the speed w
    (rad/s, signed): the slope of the first of the table's pieces that holds w with a change of
    speed; 0 where none does."""
    rows = model.pulleys[j].speed_time
    for (t0, w0), (t1, w1) in itertools.pairwise(rows):
        if w1 != w0 and t1 > t0 and min(w0, w1) <= w <= max(w0, w1):
            return (w1 - w0) / (t1 - t0)
    return 0.0


class _Drive:
    """The rotational system with the crank held at one mean speed: its state as one vector."""

    def __init__(self, sysm, j):
        self.sysm, self.j = sysm, j
        self.S, self.W, self.RS, self.RW = RT.new_states(sysm)
        P = sysm.P
        self.dyn = np.nonzero(P.mode == 0)[0]
        self.cl = np.nonzero(P.cl_kind > 0)[0]

    def held_at(self, w, accel=0.0):
        """The pulley record with the crank's speed table a constant w (rad/s), and every other
        pulley loaded by its inertia's torque -J alpha at the crank's acceleration ``accel`` (rad/s^2),
        alpha at its rigid speed ratio: the torque the run-up's sweep draws from the belt (d'Alembert);
        the rotor behind a clutch with it as the drive speeds up (slowing down, the rotor overruns).
        Held at one speed, fead-runup's drive read its spans from the crank to the alternator 27-53 N
        below the time-integrated run-up's bins; the alternator's rotor, 3e-3 kg m^2 at 2.7 times
        the crank's 110 rad/s^2, takes about 32 N of it."""
        P, R = self.sysm.P, self.sysm.R
        sp_x, sp_y = P.sp_x.copy(), P.sp_y.copy()
        o0, o1 = P.sp_off[self.j], P.sp_off[self.j + 1]
        sp_y[o0:o1] = w
        tq = P.tq_const.copy()
        speeding_up = accel * w > 0.0    # a run-down's rotor overruns its clutch: its inertia stays off the belt
        for k in self.dyn:
            inertia = P.inertia[k] + (P.cl_ir[k] if P.cl_kind[k] != 0 and speeding_up else 0.0)
            tq[k] -= inertia * accel * R.rho[self.j] / R.rho[k]
        return P._replace(sp_x=sp_x, sp_y=sp_y, tq_const=tq)

    def get(self):
        S, RS = self.S, self.RS
        return np.concatenate([S.om[self.dyn], S.omr[self.cl], S.dcp[self.cl], S.q, S.qd, RS.u, RS.W, RS.ud, RS.vs, RS.Tp,
                               RS.ed, RS.zc.ravel(), RS.Tc.ravel(), RS.wsum, RS.dz.ravel(), RS.cw0, RS.cw1])

    def set(self, x):
        S, RS = self.S, self.RS
        parts = [(S.om, self.dyn), (S.omr, self.cl), (S.dcp, self.cl)]
        k = 0
        for arr, idx in parts:
            arr[idx] = x[k:k + len(idx)]
            k += len(idx)
        for arr in (S.q, S.qd, RS.u, RS.W, RS.ud, RS.vs, RS.Tp, RS.ed):
            arr[:] = x[k:k + len(arr)]
            k += len(arr)
        for arr in (RS.zc, RS.Tc, RS.wsum, RS.dz, RS.cw0, RS.cw1):
            arr.ravel()[:] = x[k:k + arr.size]
            k += arr.size
        R = self.sysm.R
        for j in np.flatnonzero(R.grooved):      # a tooth chain's energy follows from its end tensions
            RS.eb[j] = TT.chain_energy(R.ga[j], R.gb[j], R.gc[j], R.gd[j], R.trest, RS.cw0[j], RS.cw1[j])
        # the belt rolled onto the span ends is a function of the travel: no spurious transfer at
        # the next step when an iterate moves the tensioner
        RW = self.RW
        RK.geometry(self.sysm.R, S.q, S.qd, RW.L, RW.Ld, RW.t0, RW.t1, RW.dx, RW.dy, RW.wrap, S.th, S.om, RW.rin, RW.rout)
        RS.t0[:], RS.t1[:] = RW.t0, RW.t1

    def scale(self, w):
        """Per component: the size a change of which counts as one tolerance unit."""
        sysm = self.sysm
        R = sysm.R
        vw = abs(w * R.rho[self.j])
        sp = [vw / abs(R.rho[i]) for i in self.dyn] + [vw / abs(R.rho[i]) for i in self.cl]
        na = sysm.A.na
        # a span's content: the change that moves its tension by the rest tension
        du = R.L * sysm.rest_tension / R.EA
        return np.concatenate([sp, 1e-3 * np.ones(len(self.cl)), 1e-3 * np.ones(na), 1e-3 * (abs(w) + 1) * np.ones(na),
                               du, du, 100 * du * abs(w), 100 * vw * np.ones(R.nk),
                               sysm.rest_tension * np.ones(R.nk), 100 * du / R.L * abs(w),
                               R.dmax * np.ones(self.RS.zc.size) + 1e-12,
                               sysm.rest_tension * np.ones(self.RS.Tc.size), np.maximum(self.sysm.R.ncell, 1.0),
                               R.dmax * np.ones(self.RS.dz.size) + 1e-12,
                               sysm.rest_tension * np.ones(2 * R.nk)])


def _anderson(phi, x0, scale, tol, memory=MEMORY, max_iter=MAX_ITER):
    """Fixed point x = phi(x) by Anderson acceleration (type II, least squares on the last
    residual differences). Returns (x, residual, evaluations)."""
    X, G = [], []
    x = x0
    res = math.inf
    for it in range(1, max_iter + 1):
        gx = phi(x)
        f = (gx - x) / scale
        res = float(np.max(np.abs(f)))
        if res < tol:
            return gx, res, it
        X.append(x)
        G.append(gx)
        X, G = X[-(memory + 1):], G[-(memory + 1):]
        if len(X) > 1:
            F = np.array([(g - xx) / scale for xx, g in zip(X, G)])
            dF = np.diff(F, axis=0).T
            gamma = np.linalg.lstsq(dF, f, rcond=None)[0]
            dG = np.diff(np.array(G), axis=0).T
            x = gx - dG @ gamma
        else:
            x = gx
    return gx, res, max_iter


def _sweep(drive, progress):
    """The periodic solution at each speed of the sweep, recorded: (system, samples, samples kept,
    speeds, residual and periods per speed, the held speeds' table, steps, wall time, failure)."""
    model = drive.model
    j = crank_index(model)
    if j is None:
        raise ModelError("\"periodic\" sweeps a run-up: one pulley's speed_time must change its "
                         "speed by more than 10 % (the crank)", field="simulation.runup")
    # a periodic solution needs an excitation that repeats: refused before any work otherwise
    revs = period_revolutions(model, j, drive.layout.rho, strict=True)
    if revs is None:
        orders = ", ".join(f"{o:.6g}" for o in excitation_orders(model, j, drive.layout.rho))
        raise ModelError(f"runup = \"periodic\" solves for a period of at most {MAX_PERIOD_REVS} crank revolutions; "
                         f"the excitation's orders of the crank ({orders}) do not repeat within them: use "
                         "runup = \"time\"", field="simulation.runup")
    speeds = speeds_of(model, j)
    # the bytes of the recorded periods, known before any work as a time run's are when its model is
    # read (belt.model._cost): the recorder's doubles per sample (`o` below), about three times over
    # once the Dataset, its derived variables and the netCDF writer hold copies
    nk, na = len(model.pulleys), sum(p.tensioner is not None for p in model.pulleys)
    samples = SAMPLES_PER_REV * max(revs, 2) * len(speeds)
    problem = bytes_problem(3 * samples * 8 * (9 + 12 * nk + 2 * na), "the periodic run-up",
                            f"{samples:.3g} samples, {SAMPLES_PER_REV * max(revs, 2)} at each of {len(speeds)} crank "
                            "speeds: a wider output.runup_bin")
    if problem:
        raise ModelError(problem, field="simulation.runup")
    sysm = RT.build(drive)
    # the steps of the at most MAX_ITER periods per speed the solutions may take: refused before any
    # work past the limit a time integration honours (a crawling crank's period is hours of steps)
    n_per = SAMPLES_PER_REV * revs
    most = MAX_ITER * sum(n_per * max(1, math.ceil(revs * 2 * math.pi / abs(w) / n_per / sysm.step)) for w in speeds)
    problem = steps_problem(most, "the periodic run-up",
                            f"up to {MAX_ITER} periods at each of {len(speeds)} crank speeds down to "
                            f"{min(abs(w) for w in speeds) * RPM:.3g} rpm: a faster crank or runup = \"time\"")
    if problem:
        raise ModelError(problem, field="simulation.runup")
    d = _Drive(sysm, j)
    R = sysm.R
    nk, na = R.nk, sysm.A.na
    ns_per = SAMPLES_PER_REV * max(revs, 2)
    N = ns_per * len(speeds)
    z = np.zeros
    o = dict(t=z(N), th=z((N, nk)), om=z((N, nk)), tq=z((N, nk)), tb=z((N, nk)), hx=z((N, nk)), hy=z((N, nk)),
             pin=z((N, nk)), T=z((N, nk)), v=z((N, nk)), slip=z((N, nk)), gross=z((N, nk)), q=z((N, na)),
             qd=z((N, na)), omr=z((N, nk)), E=z(N), work=z(N), diss=z((N, 6)))
    residual, iters, table = [], [], []
    wall0 = _time.perf_counter()
    t_total, k, steps_total, failure = 0.0, 0, 0, ""
    x = None
    try:
        for i, w in enumerate(speeds):
            P = d.held_at(w, sweep_acceleration(model, j, w))
            period = revs * 2 * math.pi / abs(w)
            # the period's steps a whole number per sample: each period map evaluation records
            # its samples, and the last one's are the periodic solution's
            n_per = SAMPLES_PER_REV * revs
            per_sample = max(1, int(math.ceil(period / n_per / sysm.step)))
            h = period / (n_per * per_sample)
            S, W, RS, RW = d.S, d.W, d.RS, d.RW
            if x is None:
                # from rest at the rigid drive's speeds (no start-up transient to wait for)
                S.om[:] = w * R.rho[j] / R.rho
                S.omr[:] = S.om
                x = d.get()
            else:
                x = x.copy()
                ratio = w / speeds[i - 1]
                nd, nc = len(d.dyn), len(d.cl)
                x[:nd + nc] *= ratio
                x[-3 * nk:-2 * nk] *= ratio      # the spans' speeds (vs)
            S.om[j] = w

            def phi(xv, P=P, per_sample=per_sample, h=h):
                d.set(xv)
                S.thm[j] = 0.0
                S.th[:] = 0.0         # the accessories' harmonics in phase with the crank each period
                S.thr[:] = 0.0
                RK.run_samples(k, k + n_per, per_sample, 0.0, h, R, P, sysm.A, S, W, RS, RW, RT.SLIP_PASSES, False,
                               *o.values())
                return d.get()

            # the samples kept are those of the last evaluation: the period from its start x, which
            # the period map moved by less than the tolerance
            x, res, it = _anderson(phi, x, d.scale(w), TOLERANCE)
            steps_total += n_per * per_sample * it
            if not np.all(np.isfinite(x)):
                failure = f"diverged at {abs(w) * RPM:.0f} rpm (a state is not finite)"
                break
            residual.append(res)
            iters.append(it)
            n_rec = ns_per
            for c in range(n_per, n_rec):      # one-revolution periods: whole engine cycles, repeated
                for arr in o.values():
                    arr[k + c] = arr[k + c - n_per]
                o["th"][k + c] += o["th"][k + n_per - 1]
            dt = period / n_per
            o["t"][k:k + n_rec] = t_total + (np.arange(n_rec) + 1) * dt
            table += [[t_total, float(w)], [t_total + n_rec * dt, float(w)]]
            t_total += n_rec * dt + 1e-9
            k += n_rec
            if progress is not None:
                progress((i + 1) / len(speeds), f"{abs(w) * RPM:.0f} rpm: {it} periods, residual {res:.2g}")
    except (Stopped, KeyboardInterrupt) as exc:
        failure = f"stopped: {stop_reason(exc)}"
    except ZeroDivisionError:      # an iterate ran away inside a period: the speeds before it stand
        failure = f"diverged at {abs(w) * RPM:.0f} rpm (a division by zero in the step: a state ran away)"
    wall = _time.perf_counter() - wall0
    return sysm, o, k, speeds, residual, iters, table, steps_total, wall, failure


def run(drive, progress=None, keys=None):
    """The periodic run-up of ``drive`` (geometry.drive.Drive, or a model; rotational model): a
    Result with the run-up tables of a time-integrated run-up, each speed's periodic solution as
    its samples.

    ``keys`` (summary key patterns, e.g. a design loop's objective and constraints; see
    :func:`lean_keys`): a lean Result whose summary holds only the ``runup`` entry (without the
    order tracking unless asked for) and no Dataset, no criteria and no diagnostics but the
    solve's own; its numbers are the full run's."""
    from ...core.errors import SolverError

    drive = resolve(drive)
    model = drive.model
    sysm, o, k, speeds, residual, iters, table, steps_total, wall, failure = _sweep(drive, progress)
    j = crank_index(model)
    # the energy balance restarts at each speed: not one run
    o["E"][:], o["work"][:], o["diss"][:] = np.nan, np.nan, np.nan
    # the sweep as a staircase of held speeds, for the run-up tables (runup.add_runup)
    stair = model.model_copy(update={"pulleys": [q.model_copy(update={"speed_time": table}) if n == j else q
                                                 for n, q in enumerate(model.pulleys)]}) if table else model
    if keys is not None:
        result = _lean(model, sysm, o, k, stair, orders="order_peaks" in lean_keys(keys))
    else:
        result = RT._assemble(model, sysm, o, k, steps_total, sysm.step, wall, failure, runup_model=stair,
                              window=(table[-2][0], table[-1][0]) if table else None)
    done = len(residual)
    ru = result.summary.get("runup")
    if ru is not None:
        ru["periodic_residual"] = [float(r) for r in residual]
        ru["periodic_periods"] = [int(n) for n in iters]
        ru["method"] = "periodic"
        bad = [i for i, r in enumerate(residual) if not r <= TOLERANCE]
        if bad:
            rpm = np.abs(speeds[bad]) * RPM
            result.diagnose("unconverged-periodic", f"the periodic solution did not settle within {MAX_ITER} periods at "
                            f"{len(bad)} of {done} speeds ({rpm.min():.0f}-{rpm.max():.0f} rpm): largest change per "
                            f"period {max(residual):.2g} tolerance units", "runup.periodic_residual",
                            max(residual), TOLERANCE, "1")
    if keys is None:
        add_flap_and_modes(drive.model, result)
        RT.extremes_estimate(result, RT.TIMING_SHARE if sysm.wraps else RT.PERIODIC_SHARE, teeth=bool(sysm.wraps))
    if failure:
        raise SolverError(failure + f" (periodic solutions kept for {done} of {len(speeds)} speeds)", partial=result)
    return result


#: the run-up entries a lean run gives (runup.<entry>...)
LEAN = ("crank", "speed_rpm", "sweep", "orders", "span_tension_min", "span_tension_max", "slip", "hub_load_max",
        "arm_travel_range", "order_peaks", "periodic_residual", "periodic_periods", "method")


def lean_keys(keys):
    """The run-up entries that summary key patterns ``keys`` name, or None when one of them may
    name a key outside :data:`LEAN` (then only the full run gives it): each pattern must name its
    entry literally, ``runup.slip.*`` but not ``runup.*``."""
    found = set()
    for key in keys:
        parts = str(key).split(".")
        if len(parts) < 2 or parts[0] != "runup" or parts[1] not in LEAN:
            return None
        found.add(parts[1])
    return found


def _lean(model, sysm, o, ns, stair, orders):
    """The lean Result: the run-up tables from the recorded samples, as the full run computes them."""
    import xarray as xr

    from ...core.results import Result, unit_map
    from ..dynamics.runup import runup_tables
    from ..dynamics.outputs import UNITS

    lay, A = sysm.layout, sysm.A
    arms = [a for a in range(A.na) if A.kind[a] == 0]      # arm_travel: the pivoted arms'
    travel = (o["q"][:ns, arms], [model.pulleys[A.pulley[a]].name for a in arms]) if arms else None
    hub = np.hypot(o["hx"][:ns], o["hy"][:ns])
    tables = runup_tables(stair, o["t"][:ns], o["T"][:ns], hub, o["om"][:ns], np.abs(lay.rho),
                          [sp.name for sp in lay.spans], list(lay.names), travel, model.output.runup_bin,
                          up_only=True, orders=orders) if ns >= 4 else None
    summary = {"runup": tables[0]} if tables is not None else {}
    result = Result("belt-drive", xr.Dataset(), summary)
    result.units = unit_map(summary, UNITS)
    return result
