"""The seed's integrator, adaptive Runge-Kutta-Fehlberg 4(5), for comparison with the
semi-implicit scheme. Fully explicit: with the seed's Delta_v = 1e-5 m/s the friction law is so
stiff that the step collapses (use a larger velocity_threshold to compare)."""
from __future__ import annotations

import numpy as np

from ..errors import ModelError
from ..tables import table
from . import _kernels as K


def integrate_rkf45(sysm, progress, rec, nsamples, frame_every, interval, max_steps_per_sample=2_000_000):
    model = sysm.model
    if model.friction.law != "threlfall":
        raise ModelError("rkf45 supports the threlfall friction law only", field="simulation.method")
    init, seg, pul = sysm.init, sysm.seg, sysm.pul
    n, nk = sysm.n, len(sysm.layout.names)
    y = np.zeros(6 * n + 2 * nk)
    y[0:n], y[n:2 * n], y[2 * n:3 * n] = init.x, init.y, init.phi
    z = np.zeros(n)
    fx, fy, mz, jfk, jdx, jdy, sn, st = (np.zeros(n) for _ in range(8))
    acc_p, acc_tq = np.zeros(4 + nk), np.zeros(4 * nk)
    o = 3 * n + nk
    args = (sysm.ip, sysm.fp, z, seg["m"], seg["inertia"], seg["mu"], seg["kax"], seg["bax"], seg["kb"], seg["bb"],
            seg["c1"], seg["c2"], seg["bc"], pul["pcx"], pul["pcy"], pul["pr"], pul["pinv_i"], pul["pmode"],
            pul["tq_const"], pul["tq_visc"], pul["tt_off"], pul["tt_x"], pul["tt_y"], pul["ts_off"], pul["ts_x"],
            pul["ts_y"], pul["hm_off"], pul["hm_order"], pul["hm_amp"], pul["hm_phase"], pul["sp_off"], pul["sp_x"],
            pul["sp_y"], fx, fy, mz, jfk, jdx, jdy, sn, st)

    def state_parts():
        return (y[0:n], y[n:2 * n], y[2 * n:3 * n], y[o:o + n], y[o + n:o + 2 * n], y[o + 2 * n:o + 3 * n], y[o + 3 * n:])

    def energy():
        x_, y_, phi, vx, vy, w, om = state_parts()
        return K.energy(sysm.ip, sysm.fp, x_, y_, phi, np.cos(phi), np.sin(phi), vx, vy, w, om, seg["m"],
                        seg["inertia"], seg["kax"], seg["kb"], seg["c1"], seg["c2"], pul["pcx"], pul["pcy"], pul["pr"],
                        pul["pinertia"], pul["pmode"])

    def snapshot(t):
        """Instantaneous element forces at the current state (one extra RHS call)."""
        K.rhs(t, y, np.zeros_like(y), *args, np.zeros(4 + nk), np.zeros(4 * nk))
        return jfk * np.hypot(jdx, jdy)

    def capture(t):
        k = rec.nf
        if k >= len(rec.frame_t):
            return
        ten = snapshot(t)
        rec.frame_t[k] = t
        rec.fx[k], rec.fy[k], rec.fn[k], rec.ft[k], rec.ftension[k] = y[0:n], y[n:2 * n], sn, st, ten
        rec.nf += 1

    E0 = energy()
    capture(0.0)
    t, h, steps, work = 0.0, min(sysm.step, interval), 0, 0.0
    rec.rejected, rec.rhs = 0, 0
    diss = np.zeros(4)
    for k in range(nsamples):
        acc_p[:], acc_tq[:] = 0.0, 0.0
        t_end = (k + 1) * interval
        t, h, a, r = K.rkf45_chunk(t, t_end, h, y, model.simulation.rtol, model.simulation.atol,
                                    max_steps_per_sample, *args[:-2], sn, st, acc_p, acc_tq)
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
            if pul["pmode"][j] == 1:
                rec.omega[k, j] = table(pul["sp_x"], pul["sp_y"], pul["sp_off"][j], pul["sp_off"][j + 1], t, False)
        rec.tq_ext[k], rec.tq_belt[k] = acc_tq[:nk] / interval, acc_tq[nk:2 * nk] / interval
        rec.hubx[k], rec.huby[k] = acc_tq[2 * nk:3 * nk] / interval, acc_tq[3 * nk:] / interval
        rec.pin[k] = acc_p[4:] / interval
        work += float(np.sum(acc_p[4:]))
        diss += acc_p[:4]
        # span tensions and tracked segments: instantaneous at the sample instant
        jx = 0.5 * (y[0:n] + np.roll(y[0:n], 1))
        jy = 0.5 * (y[n:2 * n] + np.roll(y[n:2 * n], 1))
        vx_, vy_ = y[o:o + n], y[o + n:o + 2 * n]
        for q, (mx, my, ux, uy) in enumerate(sysm.span_geo):
            jj = int(np.argmin((jx - mx) ** 2 + (jy - my) ** 2))
            rec.span[k, q] = ten[jj]
            rec.span_speed[k, q] = 0.5 * ((vx_[jj] + vx_[jj - 1]) * ux + (vy_[jj] + vy_[jj - 1]) * uy)
        for q, i in enumerate(sysm.track):
            rec.track[k, q] = (ten[(i + 1) % n], sn[i], st[i])
        rec.diss[k], rec.work[k], rec.energy[k] = diss, work, energy() - E0
        rec.ns = k + 1
        rec.steps, rec.step = steps, h  # what a stop (time limit, Ctrl-C) reports
        if (k + 1) % frame_every == 0:
            capture(t)
        if progress is not None:
            progress((k + 1) / nsamples, f"t = {t:.4f} s, {steps} steps")
    return nsamples, "", steps, h
