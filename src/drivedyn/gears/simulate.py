"""Run a gear-train model: initial state, compiled integration, K_v and the Result."""
from __future__ import annotations

import math
import time

import numpy as np
import xarray as xr

from ..core.errors import SolverError, Stopped, stop_reason
from ..core.results import Result, unit_map, variable
from ..core.window import in_window, steady_window
from .train import _kernels
from .train.kernel_inputs import params, stiffness_at, static_start
from .planetary.stage import PLANETARY_UNITS
from .train.system import assemble, method_b


#: wall time aimed at per compiled chunk: progress, Ctrl-C and a study's time limit act between chunks
CHUNK_SECONDS = 0.2
#: right-hand-side evaluations per second assumed for the first chunk (then measured)
_RHS_RATE = 2e6


class _Integration:
    """State of a chunked integration; ``chunk()`` advances it, ``record()`` is the solver record."""

    def __init__(self, sys_, sim, y0, p, window):
        n, m = sys_.n, sys_.m
        self.sim, self.p, self.window = sim, p, window
        self.y = y0.copy()
        self.h = sim.step
        self.failed_at = None
        if sim.method == "rk4":
            interval = sim.output_interval or self.h
            self.every = max(1, int(round(interval / self.h)))
            self.nsteps = int(math.ceil(sim.duration / self.h - 1e-9))
            nout = self.nsteps // self.every + 1
            self.dt_out = self.every * self.h
            self.s = 0
        else:
            self.dt_out = sim.output_interval if sim.output_interval else max(self.h, sim.duration / 20000)
            nout = int(math.floor(sim.duration / self.dt_out + 1e-9)) + 1
            self.atol = np.concatenate([np.full(n, sim.atol / sys_.rb_a.min()),
                                        np.full(n, sim.atol / sys_.rb_a.min() * 1e4)])
            self.h_max = 1.0 / sys_.mesh_frequency(sys_.omega_in).max() / 20
            self.K = np.zeros((7, 2 * n))
            self.st = np.array([0.0, self.h, 0.0, 1.0])      # t, next step, last accepted step, next sample
            self.counts = np.zeros(3, dtype=np.int64)
        self.out_y = np.full((nout, 2 * n), np.nan)
        self.out_f = np.full((nout, m), np.nan)
        self.out_d = np.full((nout, m), np.nan)
        self.out_y[0] = y0
        self.stats = np.zeros((m, 4))
        self.stats[:, 0], self.stats[:, 1] = -np.inf, np.inf
        self.t = np.arange(nout) * self.dt_out
        if sim.method == "dopri5":
            _kernels.dopri5_start(self.y, p, self.K, self.out_y, self.out_f, self.out_d, self.counts)
        self.rate = _RHS_RATE / max(sys_.n + sys_.m, 1)         # rhs evaluations per second, refined

    @property
    def done(self) -> bool:
        if self.failed_at is not None:
            return True
        if self.sim.method == "rk4":
            return self.s > self.nsteps
        return self.st[0] >= self.sim.duration * (1 - 1e-14)

    @property
    def time(self) -> float:
        """Simulated time reached."""
        return self.s * self.h if self.sim.method == "rk4" else float(self.st[0])

    def chunk(self) -> None:
        """Integrate for about CHUNK_SECONDS of wall time."""
        w0, w1 = self.window
        t0 = time.perf_counter()
        if self.sim.method == "rk4":
            n = max(1000, int(self.rate * CHUNK_SECONDS / 4))
            s1 = min(self.s + n, self.nsteps + 1)
            done = _kernels.run_rk4(self.y, self.h, self.s, s1, self.nsteps, self.every, self.p, w0, w1,
                                    self.out_y, self.out_f, self.out_d, self.stats)
            evals = 4 * (done - self.s)
            if done < s1:
                self.failed_at = done * self.h
            self.s = done if done < s1 else s1
        else:
            before = int(self.counts[2])
            # a chunk of simulated time from the step size reached (dopri5 adapts it)
            span = max(self.st[1], self.st[2]) * self.rate * CHUNK_SECONDS / 7
            ok = _kernels.run_dopri5(self.y, self.K, self.st, self.st[0] + span, self.sim.duration, self.h_max,
                                     self.sim.rtol, self.atol, self.p, self.dt_out, w0, w1, self.out_y, self.out_f,
                                     self.out_d, self.stats, self.counts)
            evals = int(self.counts[2]) - before
            if not ok:
                self.failed_at = float(self.st[0])
        wall = time.perf_counter() - t0
        if wall > 1e-3 and evals > 0:
            self.rate = evals / wall

    def record(self, wall: float, status: str) -> dict:
        """The solver record (same keys as the belt's): method, steps, rejected_steps,
        rhs_evaluations, last_step, wall_time, simulated_time, status."""
        if self.sim.method == "rk4":
            steps = min(self.s, self.nsteps)
            return {"method": "rk4", "step": self.h, "steps": int(steps), "rejected_steps": 0,
                    "rhs_evaluations": int(4 * steps + (self.s > self.nsteps)), "last_step": self.h,
                    "wall_time": wall, "simulated_time": float(min(self.time, self.sim.duration)), "status": status}
        return {"method": "dopri5", "rtol": self.sim.rtol, "max_step": self.h_max, "steps": int(self.counts[0]),
                "rejected_steps": int(self.counts[1]), "rhs_evaluations": int(self.counts[2]),
                "last_step": float(self.st[2]), "wall_time": wall, "simulated_time": float(self.st[0]),
                "status": status}


def run(model, progress=None) -> Result:
    """Simulate a gear-train model; K_v per mesh over the steady window; optional speed sweep.

    The integration runs in chunks: ``progress`` is called between them, and a ``Stopped`` from it
    or a Ctrl-C ends the run with a SolverError whose ``partial`` Result keeps what was computed.
    """
    from .train.checks import check_step, diagnose, diagnose_sweep

    if model.planetary is not None and not model.meshes:
        from .planetary.gearbox import run_stage

        return run_stage(model, progress)
    t0 = time.perf_counter()
    sys_ = assemble(model)
    sim = model.simulation
    if sim.method == "rk4":
        check_step(sys_, sim.step)              # one line before integrating, never a blown-up run
    n = sys_.n
    q0 = static_start(sys_) if sim.start == "static" else np.zeros(n)
    y0 = np.concatenate([q0, sys_.ratio * sys_.omega_in])
    ramp = sim.ramp_time if sim.start == "ramp" else 0.0
    window = steady_window(sim.steady_window, sim.duration)
    run_ = _Integration(sys_, sim, y0, params(sys_, ramp), window)
    failure = ""
    if progress:
        progress(0.0, "compiling / integrating")
    try:
        while not run_.done:
            run_.chunk()
            if progress:
                progress(0.9 * min(run_.time / sim.duration, 1.0), f"t = {run_.time:.4g} s")
    except (Stopped, KeyboardInterrupt) as exc:
        why = stop_reason(exc)
        failure = f"stopped at t = {run_.time:.6g} s: {why}"
    if run_.failed_at is not None:
        failure = (f"the state stopped being finite at t = {run_.failed_at:.6g} s (mesh forces diverged: "
                   "parametric instability of the linear model, or a step too large)")
    wall = time.perf_counter() - t0
    solver = run_.record(wall, "failed" if failure else "success")
    if progress and not failure:
        progress(0.9, "results")
    result = _result(model, sys_, run_.t, run_.out_y, run_.out_f, run_.out_d, run_.stats, window, solver)
    if failure:
        result.success = False
        result.message = failure
        _units(result)
        raise SolverError(failure + f" (results kept up to t = {run_.time:.6g} s)", partial=result)
    diagnose(result, sys_, model)
    if model.sweep.enabled:
        from .train.sweep import run_sweep

        try:
            sw = run_sweep(sys_, model, progress=progress)
        except (Stopped, KeyboardInterrupt) as exc:
            # the single run is complete: keep it, without the sweep
            why = stop_reason(exc)
            result.success, result.message = False, f"sweep stopped: {why}"
            _units(result)
            raise SolverError(result.message + " (the single run is kept)", partial=result) from None
        _add_sweep(result, sys_, sw)
        diagnose_sweep(result, sys_, sw)
    result.summary["solver"]["wall_time"] = time.perf_counter() - t0
    if model.planetary is not None:
        from .planetary.gearbox import add_stages

        add_stages(result, model, sys_)
    _units(result)
    if progress:
        progress(1.0, "done")
    return result


def _result(model, sys_, t, out_y, out_f, out_d, stats, window, solver) -> Result:
    from .. import dumps
    from .train.system import reduced_mass_per_mesh

    n, m = sys_.n, sys_.m
    th, om = out_y[:, :n], out_y[:, n:]
    F = sys_.force_nominal
    k_t = stiffness_at(sys_, th[:, sys_.mesh_a])
    share = np.full_like(out_f, np.nan)
    for j in range(m):
        same = sys_.mesh_a == sys_.mesh_a[j]
        share[:, j] = out_f[:, j] / out_f[:, same].sum(axis=1)
    fmax, fmin = stats[:, 0], stats[:, 1]
    fmean = stats[:, 2] / np.maximum(stats[:, 3], 1)
    freqs, shapes, zeta = sys_.modes()
    f_mesh = sys_.mesh_frequency(sys_.omega_in)
    win = in_window(t, window) & np.isfinite(out_f[:, 0])
    spec_f, spec = _spectrum(t[win], out_f[win])
    mred = reduced_mass_per_mesh(sys_)
    meshes, found = {}, []
    iso_b = []
    for j, name in enumerate(sys_.mesh_names):
        p_ = sys_.pairs[j]
        iso = sys_.iso[j]
        mb = method_b(model, sys_, j, mred[j])
        iso_b.append(mb)
        kv_iso, n_ratio, region = mb.kv(sys_.ratio[sys_.mesh_a[j]] * sys_.omega_in / (2 * math.pi))
        c1, cg = iso.si(min(p_.g1.b, p_.g2.b))
        meshes[name] = {
            "kv": fmax[j] / F[j], "force_nominal": F[j], "force_max": fmax[j], "force_min": fmin[j],
            "force_mean": fmean[j], "load_share": fmean[j] / fmean[sys_.mesh_a == sys_.mesh_a[j]].sum(),
            "kv_iso_method_b": kv_iso, "iso_speed_ratio_N": n_ratio, "iso_region": region,
            "iso_resonance_speed_rpm": mb.resonance_speed * 60.0,
            "contact_ratio": p_.contact_ratio, "mesh_frequency": f_mesh[j], "phase": sys_.phase[j],
            "stiffness_model": model.meshes[j].stiffness.model, "stiffness_mean": sys_.tables[j].mean,
            "stiffness_min": float(sys_.tables[j].stiffness.min()), "stiffness_max": float(sys_.tables[j].stiffness.max()),
            "iso_c_single": c1, "iso_c_gamma": cg, "damping": sys_.damping[j],
            "helix_angle": p_.g1.beta, "overlap_ratio": p_.overlap_ratio, "total_contact_ratio": p_.total_contact_ratio,
            # axial force on each gear's bearings: F_a = F_bt tan(beta_b) (F_bt along the transverse line of action)
            "axial_force_nominal": F[j] * math.tan(p_.g1.beta_b), "axial_force_max": fmax[j] * math.tan(p_.g1.beta_b),
        }
        if not model.meshes[j].separation and fmin[j] < 0:
            found.append(("tooth-separation",
                          f"mesh {name}: the mesh force goes negative ({fmin[j]:.4g} N) in the steady window: the teeth "
                          f"would separate; switch on tooth separation (meshes[{j}].separation = true)",
                          f"meshes.{name}.force_min", fmin[j], 0.0, "N"))
    rating = _rating(model, sys_, [meshes[n]["kv"] for n in sys_.mesh_names],
                     [meshes[n]["kv_iso_method_b"] for n in sys_.mesh_names])
    start = model.simulation.start
    how = {"static": "static equilibrium at the start position (no start-up step)",
           "ramp": f"load ramped smoothly over {model.simulation.ramp_time:g} s",
           "rest": "undeflected, full load at t = 0 (start-up transient present)"}[start]
    summary = {
        "meshes": meshes,
        "natural_frequencies_hz": [float(x) for x in freqs],
        "modal_damping_ratios": [float(x) for x in zeta],
        "steady_window": [float(window[0]), float(window[1])],
        "start": how,
        "input": {"gear": sys_.names[sys_.input_index], "speed": sys_.omega_in, "torque": sys_.torque_input},
        "gears": {nm: {"speed_nominal": sys_.ratio[i] * sys_.omega_in,
                       "speed_mean": float(np.nanmean(om[win, i])) if win.any() else None,
                       "torque": sys_.torque_const[i]} for i, nm in enumerate(sys_.names)},
        "solver": solver,
    }
    if rating:
        summary["rating"] = rating
    T0 = 1.0 / f_mesh[0]
    ds = xr.Dataset(
        {
            "angle": variable(th, ("time", "gear"), "rad", "rotation angle (own direction of rotation positive)"),
            "speed": variable(om, ("time", "gear"), "rad/s", "angular speed"),
            "vibration": variable(th - np.outer(t, sys_.ratio * sys_.omega_in), ("time", "gear"), "rad",
                                  "torsional vibration: angle minus the nominal rigid rotation"),
            "mesh_force": variable(out_f, ("time", "mesh"), "N", "dynamic mesh force along the line of action"),
            "dte": variable(out_d, ("time", "mesh"), "m", "dynamic transmission error r_ba theta_a - r_bb theta_b"),
            "axial_force": variable(out_f * np.array([math.tan(p.g1.beta_b) for p in sys_.pairs]), ("time", "mesh"), "N",
                                    "axial (thrust) force of the mesh on each gear's bearings, F tan(beta_b)"),
            "mesh_stiffness": variable(k_t, ("time", "mesh"), "N/m", "time-varying mesh stiffness"),
            "kv_t": variable(out_f / F, ("time", "mesh"), "1", "mesh force over the nominal force"),
            "load_share": variable(share, ("time", "mesh"), "1", "share of the driving gear's mesh forces"),
            "force_nominal": variable(F, ("mesh",), "N", "nominal (static, mean stiffness) mesh force"),
            "kv": variable(fmax / F, ("mesh",), "1", "dynamic factor: max force in the steady window / nominal"),
            "stiffness_table": variable(sys_.ktab().T, ("mesh_position", "mesh"), "N/m",
                                        "mesh stiffness over one mesh period"),
            "pairs_in_contact": variable(np.array([tb.pairs for tb in sys_.tables]).T, ("mesh_position", "mesh"), "1",
                                         "number of tooth pairs in contact"),
            "natural_frequency": variable(freqs, ("mode",), "Hz", "natural frequency (mean stiffness)"),
            "mode_shape": variable(shapes, ("gear", "mode"), "1", "mass-normalised mode shape"),
            "force_spectrum": variable(spec, ("frequency", "mesh"), "N", "amplitude spectrum of the mesh force (steady window)"),
        },
        coords={"time": ("time", t, {"units": "s", "long_name": "time"}),
                "gear": sys_.names, "mesh": sys_.mesh_names,
                "mesh_position": ("mesh_position", sys_.tables[0].u, {"units": "1", "long_name": "mesh position (periods)"}),
                "mode": np.arange(len(freqs)),
                "frequency": ("frequency", spec_f, {"units": "Hz", "long_name": "frequency"}),
                "order": ("frequency", spec_f * T0, {"units": "1", "long_name": f"order of the mesh frequency of {sys_.mesh_names[0]}"})},
        attrs={"model_toml": dumps(model), "steady_window": list(window), "start": how,
               "mesh_frequency_hz": list(map(float, f_mesh)), "input_speed": float(sys_.omega_in), "title": model.name or "gear train"},
    )
    for j, name in enumerate(sys_.mesh_names):
        ds.attrs[f"pair_s_{name}"] = list(map(float, sys_.tables[j].pair_s[::8]))
        ds.attrs[f"pair_k_{name}"] = list(map(float, sys_.tables[j].pair_k[::8]))
        ds.attrs[f"contact_ratio_{name}"] = float(sys_.pairs[j].contact_ratio)
        ds.attrs[f"pitch_s_{name}"] = float((sys_.pairs[j].rho_pitch - sys_.pairs[j].rho_start) / sys_.pairs[j].base_pitch)
    result = Result(kind="gear-train", ds=ds, summary=summary)
    for d in found:
        result.diagnose(*d)
    return result


def _rating(model, sys_, kv_dyn, kv_iso) -> dict:
    """ISO 6336-2/-3 ratings per mesh with K_v from the run (largest over the steady window) and from
    ISO 6336-1 method B; empty when switched off or when the run has no finite K_v."""
    from .rating.mesh import rate_mesh, summary_of

    if not model.iso.rating:
        return {}
    out = {}
    given = model.iso.dynamic_factor
    for j, name in enumerate(sys_.mesh_names):
        if given is None and not (np.isfinite(kv_dyn[j]) and kv_dyn[j] > 0):
            continue
        # a K_v given in [iso] replaces the run's (the rating of a report with a prescribed K_v)
        r_dyn = rate_mesh(model, sys_, j, float(kv_dyn[j] if given is None else given))
        r_iso = rate_mesh(model, sys_, j, float(kv_iso[j]))
        out[name] = summary_of(r_dyn, r_iso, (model.iso.min_safety_pitting, model.iso.min_safety_bending))
        out[name]["kv_source"] = "time integration" if given is None else "given (iso.dynamic_factor)"
    return out


#: units of the summary keys (fnmatch patterns, first match wins; "1" for ratios)
UNITS = {
    "meshes.*.force_*": "N", "meshes.*.axial_force_*": "N", "meshes.*.helix_angle": "rad", "meshes.*.kv*": "1", "meshes.*.load_share": "1", "meshes.*.iso_speed_ratio_N": "1",
    "meshes.*.iso_resonance_speed_rpm": "rpm", "meshes.*.contact_ratio": "1", "meshes.*.mesh_frequency": "Hz",
    "meshes.*.phase": "1", "meshes.*.stiffness_*": "N/m", "meshes.*.iso_c_*": "N/m", "meshes.*.damping": "N*s/m",
    "meshes.*.window_drift": "1", "meshes.*.window_growth": "1", "natural_frequencies_hz": "Hz", "modal_damping_ratios": "1",
    "steady_window": "s", "window_decay_times": "1", "input.speed": "rad/s", "input.torque": "N*m",
    "gears.*.speed_*": "rad/s", "gears.*.torque": "N*m",
    "solver.step": "s", "solver.last_step": "s", "solver.max_step": "s", "solver.wall_time": "s",
    "solver.simulated_time": "s", "solver.rtol": "1",
    "sweep.speed_*": "rad/s", "sweep.settle": "s", "sweep.wall_time": "s", "sweep.meshes.*.kv*": "1",
    "sweep.meshes.*.speed_at_kv_max*": "rad/s", "sweep.meshes.*.unstable_speeds": "rad/s",
    "sweep.meshes.*.separation_speeds": "rad/s", "floquet_growth_rate": "1/s",
    "rating.*.*_rating.sigma_*": "Pa", "rating.*.*_rating.load_cycles": "1", "rating.*.*_rating.*": "1",
    "rating.*.Z_E": "Pa^0.5", "rating.*.*": "1",
}
UNITS.update(PLANETARY_UNITS)


def _units(result) -> None:
    result.units = unit_map(result.summary, UNITS)


def _spectrum(t, f):
    """Single-sided amplitude spectrum (Hann window, amplitude-corrected) of each column of f."""
    if len(t) < 8:
        return np.zeros(1), np.zeros((1, f.shape[1]))
    dt = t[1] - t[0]
    w = np.hanning(len(t))
    x = (f - f.mean(axis=0)) * w[:, None]
    X = np.abs(np.fft.rfft(x, axis=0)) * 2 / w.sum()
    return np.fft.rfftfreq(len(t), dt), X


def _add_sweep(result, sys_, sw):
    ds = result.ds
    ds["sweep_speed"] = variable(sw["speeds"], ("sweep_speed",), "rad/s", "input speed of the sweep")
    ds = ds.assign_coords(sweep_speed=("sweep_speed", sw["speeds"], {"units": "rad/s", "long_name": "input speed"}))
    ds["kv_sweep"] = variable(sw["kv"], ("sweep_speed", "mesh"), "1", "simulated K_v against input speed")
    ds["kv_min_sweep"] = variable(sw["kv_min"], ("sweep_speed", "mesh"), "1", "min force / nominal against input speed")
    ds["kv_iso_sweep"] = variable(sw["kv_iso"], ("sweep_speed", "mesh"), "1", "ISO 6336-1 method B K_v")
    ds["floquet_growth_sweep"] = variable(sw["floquet"], ("sweep_speed",), "1/s",
                                          "largest Floquet growth rate of the linear model (> 0: unstable)")
    result.ds = ds
    result.summary["sweep"] = {
        "speed_min": float(sw["speeds"][0]), "speed_max": float(sw["speeds"][-1]), "count": len(sw["speeds"]),
        "settle": sw["settle"], "window_cycles": sw["window_cycles"], "wall_time": sw["wall_time"],
        "meshes": {name: {"kv_max": float(np.nanmax(sw["kv"][:, j])),
                          "speed_at_kv_max": float(sw["speeds"][np.nanargmax(sw["kv"][:, j])]),
                          "kv_iso_max": float(np.nanmax(sw["kv_iso"][:, j]))}
                   for j, name in enumerate(sys_.mesh_names)},
    }
