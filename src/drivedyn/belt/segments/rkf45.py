"""The seed's integrator, adaptive Runge-Kutta-Fehlberg 4(5), for comparison with the
semi-implicit scheme. Fully explicit: with the seed's Delta_v = 1e-5 m/s the friction law is so
stiff that the step collapses (use a larger velocity_threshold to compare)."""
from __future__ import annotations

import numpy as np

from ...core.errors import ModelError
from . import _kernels as K
from .compiled import compile_note, compiled
from ..dynamics import _bodies as BK
from .state import clear_accumulators, new_work
from .system import MAX_STEPS_PER_SAMPLE


def integrate_rkf45(sysm, progress, rec, nsamples, frame_every, interval, max_steps_per_sample=MAX_STEPS_PER_SAMPLE):
    model = sysm.model
    if model.friction.law != "threlfall":
        # the elastic-plastic state z is reset when a segment leaves contact and clipped at
        # Delta_max: jumps an explicit adaptive Runge-Kutta cannot integrate without events
        raise ModelError("rkf45 supports the threlfall friction law only", field="simulation.method")
    B, C, P, A = sysm.groups
    init = sysm.init
    n, nk = sysm.n, P.nk
    y = np.zeros(6 * n + 2 * nk)
    y[0:n], y[n:2 * n], y[2 * n:3 * n] = init.x, init.y, init.phi
    z = np.zeros(n)
    W, Wst = new_work(sysm), new_work(sysm)
    o = 3 * n + nk

    def state():
        """Kernel State view of y (pulley speeds as integrated, c and s from phi)."""
        phi = y[2 * n:3 * n]
        return BK.State(y[0:n], y[n:2 * n], phi, np.cos(phi), np.sin(phi), y[o:o + n], y[o + n:o + 2 * n],
                       y[o + 2 * n:o + 3 * n], y[3 * n:3 * n + nk], y[o + 3 * n:], z, P.cx, P.cy,
                       np.zeros(nk), np.zeros(nk), np.zeros(0), np.zeros(0),   # fixed centres (no tensioners)
                       np.zeros(nk), np.zeros(nk), np.zeros(nk), np.zeros(nk))  # no orders, no clutches

    def energy():
        return K.energy(B, C, P, A, state())

    def snapshot(t):
        """Instantaneous element forces at the current state (one extra RHS call)."""
        rhs(t, y, np.zeros_like(y), B, C, P, W, z)
        return W.jfk * np.hypot(W.jdx, W.jdy)

    def capture(t):
        k = rec.nf
        if k >= len(rec.frame_t):
            return
        ten = snapshot(t)
        rec.frame_t[k] = t
        rec.fx[k], rec.fy[k], rec.fn[k], rec.ft[k], rec.ftension[k] = y[0:n], y[n:2 * n], W.seg_n, W.seg_t, ten
        rec.nf += 1

    with compile_note(progress, "rkf45"):
        E0 = energy()
        rhs = compiled(K.rhs, (0.0, y, np.zeros_like(y), B, C, P, W, z))
        chunk = compiled(K.rkf45_chunk, (0.0, 0.0, 1e-6, y, 1e-6, 1e-9, 1, B, C, P, W, Wst, z))
    capture(0.0)
    t, h, steps, work = 0.0, min(sysm.step, interval), 0, 0.0
    rec.rejected, rec.rhs = 0, 0
    diss = np.zeros(6)
    for k in range(nsamples):
        clear_accumulators(W)
        t_end = (k + 1) * interval
        t, h, a, r = chunk(t, t_end, h, y, float(model.simulation.rtol), float(model.simulation.atol),
                           max_steps_per_sample, B, C, P, W, Wst, z)
        steps += a
        rec.rejected += r
        rec.rhs += 6 * (a + r) + 1           # six stages per attempt, one snapshot per sample
        if t < t_end - 1e-12 or not np.all(np.isfinite(y)):
            return k, (f"rkf45 stopped at t = {t:.6g} s: step size collapsed to {h:.3g} s "
                       f"(stiff friction law; raise friction.velocity_threshold)"), steps, h
        ten = snapshot(t)
        rec.t[k] = (k + 1) * interval      # exact sample times (the accumulated t carries round-off)
        rec.theta[k], rec.omega[k] = y[3 * n:3 * n + nk], y[o + 3 * n:]
        for j in range(nk):
            if P.mode[j] == 1:
                rec.omega[k, j] = BK.prescribed_speed(P, j, t)
        rec.tq_ext[k], rec.tq_belt[k] = W.acc_tq_ext / interval, W.acc_tq_belt / interval
        rec.hubx[k], rec.huby[k] = W.acc_hubx / interval, W.acc_huby / interval
        rec.pin[k] = W.acc_pin / interval
        work += float(np.sum(W.acc_pin))
        diss += W.acc_diss
        # span tensions and tracked segments: instantaneous at the sample instant
        jx = 0.5 * (y[0:n] + np.roll(y[0:n], 1))
        jy = 0.5 * (y[n:2 * n] + np.roll(y[n:2 * n], 1))
        vx_, vy_ = y[o:o + n], y[o + n:o + 2 * n]
        for q, (mx, my, ux, uy) in enumerate(sysm.span_geo):
            jj = int(np.argmin((jx - mx) ** 2 + (jy - my) ** 2))
            rec.span[k, q] = ten[jj]
            rec.span_speed[k, q] = 0.5 * ((vx_[jj] + vx_[jj - 1]) * ux + (vy_[jj] + vy_[jj - 1]) * uy)
        for q, i in enumerate(sysm.track):
            rec.track[k, q] = (ten[(i + 1) % n], W.seg_n[i], W.seg_t[i])
        rec.diss[k], rec.work[k], rec.energy[k] = diss, work, energy() - E0
        rec.ns = k + 1
        rec.steps, rec.step = steps, h  # what a stop (time limit, Ctrl-C) reports
        if (k + 1) % frame_every == 0:
            capture(t)
        if progress is not None:
            progress((k + 1) / nsamples, f"t = {t:.4f} s, {steps} steps")
    return nsamples, "", steps, h
