"""Checks of a gear-train run: is the RK4 step stable, is the steady window steady, does K_v grow?

- Step (before integrating): RK4 multiplies a mode with eigenvalue lambda by
  R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24, z = h lambda, per step; it is stable for |R| <= 1. On the
  imaginary axis |R(iy)|^2 = 1 - y^6/72 + y^8/576, so an undamped mode needs h omega <= 2 sqrt 2
  = 2.83 (on the negative real axis the bound is 2.785; Hairer & Wanner, Solving ODEs II, sec.
  IV.2). The check takes the eigenvalues of the linear model with every mesh at its stiffest.
- Window, decay: a mode rings down as exp(-t / tau), tau = 1 / (zeta omega); the window should
  start after 3 tau (5 % of the start-up amplitude left) of the slowest mode the run excites.
- Window, drift: the per-mesh-period peak and trough forces should not drift across the window
  (drivedyn.core.window.drift against the nominal force).
- Growth (kv-unstable): a stable linear periodic system settles to a response with the mesh
  period, so the force amplitude is the same in both halves of the window; a parametrically
  unstable one grows as exp(sigma t) (Floquet), and its K_v is whatever the window end reached.
"""
from __future__ import annotations

import math

import numpy as np

from ...core.errors import ModelError
from ...core.window import drift, in_window

#: RK4 on the imaginary axis: |R(iy)| <= 1 for |y| <= 2 sqrt 2
RK4_IMAG_BOUND = 2.0 * math.sqrt(2.0)
#: the window must start this many decay times 1/(zeta omega) of the slowest excited mode into the run
DECAY_TIMES = 3.0
#: a mode is excited when its share of a mesh force swings by more than this share of the nominal force
EXCITED = 1e-3
#: largest drift of the per-period peak or trough force across the window, in nominal forces
DRIFT_LIMIT = 0.02
#: Floquet multiplier modulus above exp(FLOQUET_TOL) per period is growth (RK4 errs towards damping)
FLOQUET_TOL = 1e-6
#: largest ratio of the force amplitude in the second half of the window to that in the first
GROWTH_LIMIT = 1.2


def rk4_growth(z) -> np.ndarray:
    """|R(z)| of classical RK4 (the amplification of one step)."""
    z = np.asarray(z, dtype=complex)
    return np.abs(1 + z + z ** 2 / 2 + z ** 3 / 6 + z ** 4 / 24)


def stiff_eigenvalues(sys_) -> np.ndarray:
    """Eigenvalues (1/s) of the linear model with every mesh at its largest table stiffness
    (the rigid-body pair removed)."""
    K, C, M = sys_.coupling()
    for j in range(sys_.m):
        g = np.zeros(sys_.n)
        g[sys_.mesh_a[j]], g[sys_.mesh_b[j]] = sys_.rb_a[j], -sys_.rb_b[j]
        K = K + (sys_.tables[j].stiffness.max() - sys_.tables[j].mean) * np.outer(g, g)
    n = sys_.n
    Mi = np.diag(1.0 / np.diag(M))
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Mi @ K, -Mi @ C]])
    lam = np.linalg.eigvals(A)
    if not np.all(np.isfinite(lam)):
        return lam[np.isfinite(lam)]
    scale = max(np.abs(lam).max(), 1.0)
    return lam[np.abs(lam) > 1e-6 * scale]


def rk4_step_limit(sys_) -> tuple[float, float]:
    """(largest stable RK4 step in s, omega_max in rad/s) of the stiffest linear model."""
    lam = stiff_eigenvalues(sys_)
    if lam.size == 0:
        return math.inf, 0.0
    w_max = float(np.abs(lam).max())
    stable = lambda h: rk4_growth(h * lam).max() <= 1.0 + 1e-12
    hs = np.linspace(0.0, 3.0 / w_max, 301)[1:]         # the region reaches |z| < 3 on every ray
    bad = [h for h in hs if not stable(h)]
    if not bad:
        return float(hs[-1]), w_max
    hi = bad[0]
    lo = hi - hs[0]
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if stable(mid) else (lo, mid)
    return lo, w_max


def check_step(sys_, h: float) -> None:
    """ModelError naming simulation.step when RK4 with step h would blow up (step-too-large)."""
    h_lim, w_max = rk4_step_limit(sys_)
    if h > h_lim:
        raise ModelError(
            f"{h:.4g} s is too large for RK4 (step-too-large): h omega_max = {h * w_max:.3g} > {RK4_IMAG_BOUND:.3g}, "
            f"the RK4 stability bound (omega_max = 2 pi x {w_max / (2 * math.pi):.5g} Hz, the highest natural "
            f"frequency with the meshes at their stiffest); use step <= {h_lim:.3g} s, a few times less for accuracy",
            field="simulation.step")


def excited_modes(result, sys_) -> np.ndarray:
    """Indices of the modes that swing some mesh force by more than EXCITED x its nominal force."""
    ds = result.ds
    freqs, shapes, _ = sys_.modes()
    vib = ds.vibration.values[::max(1, ds.sizes["time"] // 20000)]     # a swing needs no every step
    ok = np.all(np.isfinite(vib), axis=1)
    if not ok.any() or shapes.size == 0:
        return np.zeros(0, dtype=int)
    eta = vib[ok] @ (sys_.inertia[:, None] * shapes)          # modal coordinates (mass-normalised shapes)
    swing = np.ptp(eta, axis=0) / 2
    k_mean = np.array([tb.mean for tb in sys_.tables])
    g = k_mean[:, None] * (sys_.rb_a[:, None] * shapes[sys_.mesh_a] - sys_.rb_b[:, None] * shapes[sys_.mesh_b])
    share = np.abs(g) * swing[None, :] / sys_.force_nominal[:, None]      # (mesh, mode)
    return np.flatnonzero(share.max(axis=0) > EXCITED)


def window_decay(result, sys_) -> tuple[float, int, float] | None:
    """(window start in decay times, mode, tau) of the slowest excited mode, or None."""
    freqs, _, zeta = sys_.modes()
    modes = excited_modes(result, sys_)
    if modes.size == 0:
        return None
    tau = 1.0 / np.maximum(zeta[modes] * 2 * math.pi * freqs[modes], 1e-300)
    r = int(modes[np.argmax(tau)])
    t_r = float(tau.max())
    return result.summary["steady_window"][0] / t_r, r, t_r


def _period_extremes(t, f, period):
    """Times, peaks and troughs of f over the whole periods of length ``period`` in t (sorted)."""
    k = np.floor((t - t[0]) / period).astype(int)
    whole = k < k.max()                       # the last period may be cut short
    k, t, f = k[whole], t[whole], f[whole]
    if k.size == 0:
        return np.zeros(0), np.zeros(0), np.zeros(0)
    starts = np.flatnonzero(np.diff(k, prepend=-1))
    counts = np.diff(np.append(starts, k.size))
    return (np.add.reduceat(t, starts) / counts, np.maximum.reduceat(f, starts), np.minimum.reduceat(f, starts))


def growth_of(t, f) -> float:
    """Force amplitude (max - min)/2 in the second half of the samples over that in the first."""
    h = len(t) // 2
    if h < 2:
        return math.nan
    a1, a2 = np.ptp(f[:h]), np.ptp(f[h:])
    return float(a2 / a1) if a1 > 0 else (math.inf if a2 > 0 else 1.0)


def diagnose(result, sys_, model) -> None:
    """kv-unstable and window-not-steady diagnostics of a completed single run.

    kv-unstable: the largest Floquet growth rate of the linear model at the run's speed is > 0
    (when the meshes share one mesh frequency and at least one has no tooth separation); else,
    per mesh, the force amplitude grows by more than GROWTH_LIMIT from the first to the second half
    of the window. window-not-steady: per mesh, the per-period amplitude or mean force drifts by
    more than DRIFT_LIMIT nominal forces across the window; and, once per run, the window starts
    less than DECAY_TIMES decay times of the slowest excited mode into the run.
    """
    ds, summary = result.ds, result.summary
    window = summary["steady_window"]
    t = ds.time.values
    win = in_window(t, window)
    f_mesh = sys_.mesh_frequency(sys_.omega_in)
    rpm = sys_.omega_in * 30 / math.pi
    linear = [j for j in range(sys_.m) if not model.meshes[j].separation]
    growing = set()
    sigma = math.nan
    if linear and common_period(sys_, sys_.omega_in) is not None:
        sigma = float(floquet_growth(sys_, [sys_.omega_in], model.simulation.step)[0])
        summary["floquet_growth_rate"] = sigma
        if sigma * common_period(sys_, sys_.omega_in) > FLOQUET_TOL:
            growing.update(linear)
            names = ", ".join(sys_.mesh_names[j] for j in linear)
            seen = max((summary["meshes"][sys_.mesh_names[j]]["kv"] for j in linear), default=math.nan)
            result.diagnose(
                "kv-unstable",
                f"mesh{'es' if len(linear) > 1 else ''} {names}: the linear mesh model is parametrically unstable at "
                f"{rpm:.0f} rpm (largest Floquet growth rate {sigma:.3g} 1/s, e-folding time {1e3 / sigma:.3g} ms): "
                f"any disturbance of the unstable mode grows without bound, so K_v = {seen:.4g} stands only while "
                f"that mode is not excited (e.g. by exact symmetry); switch on tooth separation",
                "floquet_growth_rate", sigma, 0.0, "1/s")
    for j, name in enumerate(sys_.mesh_names):
        f = ds.mesh_force.values[win, j]
        tw = t[win]
        n_periods = (tw[-1] - tw[0]) * f_mesh[j] if len(tw) else 0.0
        if n_periods < 4 or not np.all(np.isfinite(f)):
            continue                          # too short a window to judge (2 mesh periods per half)
        F = sys_.force_nominal[j]
        kv = summary["meshes"][name]["kv"]
        g = growth_of(tw, f)
        summary["meshes"][name]["window_growth"] = g
        tc, peak, trough = _period_extremes(tw, f, 1.0 / f_mesh[j])
        d_amp = float(drift(tc, (peak - trough) / 2, F)[0]) if len(tc) >= 4 else 0.0
        d_mid = float(drift(tc, (peak + trough) / 2, F)[0]) if len(tc) >= 4 else 0.0
        summary["meshes"][name]["window_drift"] = max(d_amp, d_mid)
        where = f"(K_v = {kv:.4g} at {rpm:.0f} rpm)"
        if j in growing:
            continue
        if g > GROWTH_LIMIT:
            growing.add(j)
            result.diagnose(
                "kv-unstable",
                f"mesh {name}: the force amplitude grows x{g:.3g} from the first to the second half of the steady "
                f"window {where}: the mesh model is unstable here, or K_v has not converged",
                f"meshes.{name}.window_growth", g, GROWTH_LIMIT, "1")
        elif max(d_amp, d_mid) > DRIFT_LIMIT:
            d = max(d_amp, d_mid)
            result.diagnose(
                "window-not-steady",
                f"mesh {name}: the per-period force {'amplitude' if d_amp >= d_mid else 'mean'} drifts by {d:.3g} x "
                f"the nominal force across the steady window {window[0]:.4g}-{window[1]:.4g} s (limit {DRIFT_LIMIT:g}) "
                f"{where}: K_v is not a steady value",
                f"meshes.{name}.window_drift", d, DRIFT_LIMIT, "1")
    dec = window_decay(result, sys_)
    if dec is not None:
        n_tau, r, tau = dec
        freqs = summary["natural_frequencies_hz"]
        summary["window_decay_times"] = n_tau
        if n_tau < DECAY_TIMES:
            result.diagnose(
                "window-not-steady",
                f"the steady window starts at {window[0]:.4g} s, {n_tau:.2g} decay times into the run of the mode at "
                f"{freqs[r]:.5g} Hz (tau = 1/(zeta omega) = {tau * 1e3:.3g} ms); start it after "
                f"{DECAY_TIMES:g} tau = {DECAY_TIMES * tau:.3g} s (simulation.steady_window, simulation.duration)",
                "window_decay_times", n_tau, DECAY_TIMES, "1")


def unstable_ranges(speeds, bad) -> list[tuple[int, int]]:
    """Index ranges [a, b] (inclusive) of consecutive True entries of ``bad``."""
    out, a = [], None
    for k, b in enumerate(bad):
        if b and a is None:
            a = k
        if not b and a is not None:
            out.append((a, k - 1))
            a = None
    if a is not None:
        out.append((a, len(bad) - 1))
    return out


def _rpm_ranges(speeds, ranges) -> str:
    rpm = speeds * 30 / math.pi
    return ", ".join(f"{rpm[a]:.0f}" if a == b else f"{rpm[a]:.0f}-{rpm[b]:.0f}" for a, b in ranges) + " rpm"


def diagnose_sweep(result, sys_, sw) -> None:
    """kv-unstable and tooth-separation over the speed sweep: one diagnostic each for the meshes
    that share the same speed ranges, naming the ranges; the unstable speeds go to the Dataset
    (``sweep_unstable``) and per mesh to the summary (``unstable_speeds``, ``separation_speeds``,
    rad/s), with ``kv_max_stable`` the largest K_v over the other speeds and ``kv_max`` the largest
    over the speeds where the model holds (stable, no tooth separation in a linear mesh)."""
    from ...core.results import variable

    speeds, kv, growth, sigma = sw["speeds"], sw["kv"], sw["growth"], sw["floquet"]
    T = np.array([common_period(sys_, w) or np.nan for w in speeds])
    unstable = np.where(np.isfinite(sigma), sigma * T > FLOQUET_TOL, False)[:, None] & sw["linear"][None, :]
    bad = unstable | (growth > GROWTH_LIMIT) | ~np.isfinite(kv) | ~np.isfinite(growth)
    sep = (sw["kv_min"] < 0) & ~bad & sw["linear"][None, :]
    result.ds["sweep_unstable"] = variable(bad, ("sweep_speed", "mesh"), "1",
                                           "K_v grows without bound (parametric instability) or does not converge")
    groups = {"kv-unstable": {}, "tooth-separation": {}}
    for j, name in enumerate(sys_.mesh_names):
        s = result.summary["sweep"]["meshes"][name]
        r_bad, r_sep = unstable_ranges(speeds, bad[:, j]), unstable_ranges(speeds, sep[:, j])
        s["unstable_speeds"] = [[float(speeds[a]), float(speeds[b])] for a, b in r_bad]
        s["separation_speeds"] = [[float(speeds[a]), float(speeds[b])] for a, b in r_sep]
        ok = ~bad[:, j]
        s["kv_max_stable"] = float(np.nanmax(kv[ok, j])) if ok.any() else None
        # K_v only where the model holds: stable, and (linear meshes) the teeth in contact; the largest
        # over every speed is kept beside it, named as such
        valid = ok & ~sep[:, j]
        s["kv_max_all_speeds"], s["speed_at_kv_max_all_speeds"] = s["kv_max"], s["speed_at_kv_max"]
        if valid.any():
            k = int(np.flatnonzero(valid)[np.nanargmax(kv[valid, j])])
            s["kv_max"], s["speed_at_kv_max"] = float(kv[k, j]), float(speeds[k])
        else:
            s["kv_max"], s["speed_at_kv_max"] = None, None
        if r_bad:
            groups["kv-unstable"].setdefault(tuple(r_bad), []).append(j)
        if r_sep:
            groups["tooth-separation"].setdefault(tuple(r_sep), []).append(j)
    n = len(speeds)
    for ranges, js in groups["kv-unstable"].items():
        names = ", ".join(sys_.mesh_names[j] for j in js)
        idx = np.concatenate([np.arange(a, b + 1) for a, b in ranges])
        kmax = float(np.nanmax(kv[np.ix_(idx, js)])) if np.isfinite(kv[np.ix_(idx, js)]).any() else math.inf
        sg = sigma[idx]
        if np.isfinite(sg).any() and np.nanmax(sg) > 0:
            smax = float(np.nanmax(sg))
            why = f"largest Floquet growth rate {smax:.3g} 1/s"
            q, v, lim, u = "sweep.floquet_growth_rate", smax, 0.0, "1/s"
        else:
            g = growth[np.ix_(idx, js)]
            gmax = float(np.nanmax(np.where(np.isfinite(g), g, np.inf)))
            why = f"force amplitude up to x{gmax:.3g} from the first to the second half of the window"
            q, v, lim, u = f"sweep.meshes.{sys_.mesh_names[js[0]]}.window_growth", gmax, GROWTH_LIMIT, "1"
        result.diagnose(
            "kv-unstable",
            f"mesh{'es' if len(js) > 1 else ''} {names}: the linear mesh model is unstable at {_rpm_ranges(speeds, ranges)} "
            f"({idx.size} of {n} sweep speeds; {why}; K_v there up to {kmax:.4g}, meaningless)", q, v, lim, u)
    for ranges, js in groups["tooth-separation"].items():
        names = ", ".join(sys_.mesh_names[j] for j in js)
        idx = np.concatenate([np.arange(a, b + 1) for a, b in ranges])
        fmin = float(np.min(sw["kv_min"][np.ix_(idx, js)] * sys_.force_nominal[js][None, :]))
        result.diagnose(
            "tooth-separation",
            f"mesh{'es' if len(js) > 1 else ''} {names}: the mesh force goes negative (down to {fmin:.4g} N) at "
            f"{_rpm_ranges(speeds, ranges)} in the sweep ({idx.size} of {n} speeds): the teeth would separate; "
            f"switch on tooth separation", f"sweep.meshes.{sys_.mesh_names[js[0]]}.kv_min", fmin, 0.0, "N")


def common_period(sys_, omega: float) -> float | None:
    """The period (s) of the linear model at input speed ``omega``: the mesh period when every mesh
    has the same mesh frequency; None otherwise (quasi-periodic: no Floquet analysis)."""
    f = sys_.mesh_frequency(omega)
    if np.ptp(f) > 1e-9 * f.max():
        return None
    return 1.0 / f.max()


def floquet_growth(sys_, omegas, h_max: float) -> np.ndarray:
    """Largest Floquet growth rate sigma = ln|mu| / T (1/s) of the linear parametric model at each
    input speed (NaN where the meshes have different frequencies). The rigid-body pair of
    multipliers (a Jordan block at 1) is left out. Monodromy by RK4 at <= h_max and <= 1/20 of the
    fastest period, >= 64 steps per mesh period."""
    from . import _kernels
    from .kernel_inputs import params

    omegas = np.atleast_1d(np.asarray(omegas, dtype=float))
    T = np.array([common_period(sys_, w) or np.nan for w in omegas])
    ok = np.isfinite(T)
    out = np.full(omegas.size, np.nan)
    if not ok.any():
        return out
    _, w_max = rk4_step_limit(sys_)
    h = min(h_max, 2 * math.pi / max(w_max, 1e-300) / 20)
    nsteps = np.maximum(np.ceil(T[ok] / h), 64).astype(np.int64)
    n2 = 2 * sys_.n
    phi = np.zeros((int(ok.sum()), n2, n2))
    _kernels.monodromy(omegas[ok], sys_.ratio.astype(float), T[ok], nsteps, params(sys_, 0.0, tables=False), phi)
    mu = np.linalg.eigvals(phi)
    order = np.argsort(np.abs(mu - 1.0), axis=1)[:, 2:]
    elastic = np.take_along_axis(np.abs(mu), order, axis=1)
    out[ok] = np.log(np.maximum(elastic.max(axis=1), 1e-300)) / T[ok]
    return out
