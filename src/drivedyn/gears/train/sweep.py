"""K_v against input speed: one compiled RK4 run per speed (in parallel), ISO method B beside it.

Each speed starts in static equilibrium at the nominal torques (held constant over the sweep),
settles, then K_v is the largest mesh force over ``window_cycles`` mesh periods of the first mesh
divided by the nominal force. The default settling time is five decay times 1/(zeta_r omega_r) of
the least damped mode, and at least 20 mesh periods.
"""
from __future__ import annotations

import math
import time

import numpy as np

from . import _kernels
from .kernel_inputs import params, static_start
from .system import method_b, reduced_mass_per_mesh


def speed_range(sys_, model) -> tuple[float, float]:
    """Default sweep range: up to 1.3 x the speed where the first mesh frequency meets the highest mode."""
    sw = model.sweep
    freqs, _, _ = sys_.modes()
    per_rad = sys_.mesh_frequency(1.0)[0]                  # mesh Hz per rad/s of input speed
    hi = sw.speed_max or 1.3 * freqs.max() / per_rad
    lo = sw.speed_min or hi / 100.0
    return lo, hi


def run_sweep(sys_, model, progress=None) -> dict:
    """Simulated and ISO 6336-1 method B K_v of every mesh over the speed range."""
    t0 = time.perf_counter()
    sw = model.sweep
    lo, hi = speed_range(sys_, model)
    speeds = np.linspace(lo, hi, sw.count)
    freqs, _, zeta = sys_.modes()
    w = 2 * math.pi * freqs
    decay = 1.0 / np.maximum(zeta * w, 1e-12)
    settle = sw.settle if sw.settle is not None else float(min(5 * decay.max(), 0.5))
    fm = sys_.mesh_frequency(1.0)[0] * speeds               # Hz of the first mesh
    h = np.minimum(model.simulation.step, 1.0 / (fm * sw.steps_per_cycle))
    n_settle = np.ceil(np.maximum(settle, 20.0 / fm) / h).astype(np.int64)
    n_window = np.ceil(sw.window_cycles / fm / h).astype(np.int64)
    p = params(sys_, 0.0, tables=False)
    q0 = static_start(sys_)
    ns, m = len(speeds), sys_.m
    kv_max, kv_min, f_mean = np.zeros((ns, m)), np.zeros((ns, m)), np.zeros((ns, m))
    halves = np.zeros((ns, m, 4))
    # in chunks of speeds (each one parallel over its speeds), so that progress is reported and a
    # study's case_timeout can act between them
    chunk = max(8, -(-ns // 10))
    for a in range(0, ns, chunk):
        b = min(ns, a + chunk)
        if progress:
            progress(0.92 + 0.07 * a / ns, f"sweep: {a} of {ns} speeds")
        _kernels.sweep_rk4(speeds[a:b], sys_.ratio, q0, p, h[a:b], n_settle[a:b], n_window[a:b],
                           kv_max[a:b], kv_min[a:b], f_mean[a:b], halves[a:b])
    F = sys_.force_nominal
    mred = reduced_mass_per_mesh(sys_)
    kv_iso = np.zeros((ns, m))
    for j in range(m):
        mb = method_b(model, sys_, j, mred[j])
        for k, om in enumerate(speeds):
            kv_iso[k, j] = mb.kv(sys_.ratio[sys_.mesh_a[j]] * om / (2 * math.pi))[0]
    # force amplitude in the second half of the window over the first: 1 when steady, > 1 growing
    with np.errstate(divide="ignore", invalid="ignore"):
        growth = (halves[:, :, 2] - halves[:, :, 3]) / (halves[:, :, 0] - halves[:, :, 1])
    from .checks import floquet_growth

    linear = np.array([not ms.separation for ms in model.meshes])
    floquet = floquet_growth(sys_, speeds, model.simulation.step) if linear.any() else np.full(ns, np.nan)
    return {"speeds": speeds, "kv": kv_max / F, "floquet": floquet, "linear": linear, "kv_min": kv_min / F, "f_mean": f_mean, "kv_iso": kv_iso,
            "growth": growth,
            "settle": settle, "window_cycles": sw.window_cycles, "wall_time": time.perf_counter() - t0}
