"""Compiled kernels of the gear-train torsional model (seed 003). Contract:

- float64 arrays, int64 index arrays, float/int scalars; no Python objects; nothing compiled at
  import (``@njit(cache=True)`` without signatures). Index base 0.
- State y (2n): angles theta_i (rad) then speeds omega_i (rad/s), each positive in gear i's own
  nominal direction of rotation.
- Parameters ``p`` is the tuple built by ``kernel_inputs.params`` (order fixed by ``unpack`` below):
  J (n), Tc (n) constant torques, ramp (float, s; 0 = none), ts_off/ts_x/ts_y and tt_off/tt_x/tt_y
  (torque-speed and torque-time tables of all gears, flattened, offsets n+1), mesh arrays
  ma, mb (int), rba, rbb, za, phase, cm, sep (int), bl (m), tables kt, fa, fb (m x N) over one
  mesh period, shaft arrays sa, sb (int), sk, sc.
- Mesh j (seed 003, eqs. 9-11): u = frac(z_a theta_a / 2 pi + phase_j) is the mesh position;
  delta = r_ba theta_a - r_bb theta_b; f = k(u) delta + c delta' (with tooth separation: zero inside
  the backlash, never pulling); torque -r_ba f + fa(u) f on the driving gear, r_bb f + fb(u) f on
  the driven one (fa, fb: tooth friction moment per unit force, sign change at the pitch point).
- RK4 (fixed step, as the seed) and Dormand-Prince 5(4) (adaptive, Hairer, Norsett & Wanner,
  Solving ODEs I, table II.5.2, with cubic Hermite output) loop in compiled code, in chunks of
  steps that the caller strings together (progress, Ctrl-C and time limits between chunks).
"""
import math

import numpy as np
from numba import njit, prange

from ...core import tables

# plain Python in tables.py (check reads spring and load tables without numba): compiled here
table = njit(cache=True, inline="always")(tables.table)

TWO_PI = 2.0 * math.pi


@njit(cache=True)
def _periodic(tab, j, u):
    """Value of row j of a periodic table at u in [0, 1)."""
    N = tab.shape[1]
    x = u * N
    i0 = int(x)
    if i0 >= N:
        i0 = N - 1
    w = x - i0
    i1 = i0 + 1
    if i1 == N:
        i1 = 0
    return tab[j, i0] * (1.0 - w) + tab[j, i1] * w


@njit(cache=True)
def _shafts_and_inertia(y, dy, n, J, sa, sb, sk, sc):
    """Add the torsional shafts' moments to the torques in dy[n:], then divide by the inertias."""
    for j in range(sa.size):
        a = sa[j]
        b = sb[j]
        M = sk[j] * (y[a] - y[b]) + sc[j] * (y[n + a] - y[n + b])
        dy[n + a] -= M
        dy[n + b] += M
    for i in range(n):
        dy[n + i] /= J[i]


@njit(cache=True)
def rhs(t, y, p, dy, fm, dm):
    """dy = f(t, y); mesh forces into fm (N) and mesh deflections into dm (m)."""
    (J, Tc, ramp, ts_off, ts_x, ts_y, tt_off, tt_x, tt_y, ma, mb, rba, rbb, za, phase, cm, sep, bl,
     kt, fa, fb, sa, sb, sk, sc) = p
    n = J.size
    r = 1.0
    if ramp > 0.0 and t < ramp:
        s = t / ramp
        r = s * s * (3.0 - 2.0 * s)       # smooth load ramp: no step to excite the modes
    for i in range(n):
        T = Tc[i]
        if ts_off[i + 1] > ts_off[i]:
            T += table(ts_x, ts_y, ts_off[i], ts_off[i + 1], y[n + i], True)
        if tt_off[i + 1] > tt_off[i]:
            T += table(tt_x, tt_y, tt_off[i], tt_off[i + 1], t, False)
        dy[n + i] = r * T
        dy[i] = y[n + i]
    for j in range(ma.size):
        a = ma[j]
        b = mb[j]
        u = za[j] * y[a] / TWO_PI + phase[j]
        u -= math.floor(u)
        k = _periodic(kt, j, u)
        d = rba[j] * y[a] - rbb[j] * y[b]
        dd = rba[j] * y[n + a] - rbb[j] * y[n + b]
        if sep[j] == 0:
            f = k * d + cm[j] * dd
        elif d > 0.0:
            f = max(k * d + cm[j] * dd, 0.0)          # contact cannot pull
        elif d < -bl[j]:
            f = min(k * (d + bl[j]) + cm[j] * dd, 0.0)  # back-flank contact
        else:
            f = 0.0
        fm[j] = f
        dm[j] = d
        dy[n + a] += (-rba[j] + _periodic(fa, j, u)) * f
        dy[n + b] += (rbb[j] + _periodic(fb, j, u)) * f
    _shafts_and_inertia(y, dy, n, J, sa, sb, sk, sc)


@njit(cache=True)
def _rk4_step(t, y, h, p, k1, k2, k3, k4, tmp, fm, dm, fs, ds):
    """One classical RK4 step in place; forces and deflections at the step start into fm, dm."""
    rhs(t, y, p, k1, fm, dm)
    for i in range(y.size):
        tmp[i] = y[i] + 0.5 * h * k1[i]
    rhs(t + 0.5 * h, tmp, p, k2, fs, ds)
    for i in range(y.size):
        tmp[i] = y[i] + 0.5 * h * k2[i]
    rhs(t + 0.5 * h, tmp, p, k3, fs, ds)
    for i in range(y.size):
        tmp[i] = y[i] + h * k3[i]
    rhs(t + h, tmp, p, k4, fs, ds)
    for i in range(y.size):
        y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])


@njit(cache=True)
def run_rk4(y, h, s0, s1, nsteps, every, p, w0, w1, out_y, out_f, out_d, stats):
    """Fixed-step RK4: steps s0 .. s1 - 1 of h (of nsteps in all) from the state ``y`` at t = s0 h,
    in place; a sample every ``every`` steps. Called in chunks (the caller reports progress and
    honours interrupts between them); s = nsteps only evaluates the forces at the end.

    stats (m x 4, initialised by the caller): max force, min force, sum of force, count, over the
    steady window [w0, w1]. Returns s1, or the step at which the state stopped being finite.
    """
    m = out_f.shape[1]
    k1 = np.empty_like(y)
    k2 = np.empty_like(y)
    k3 = np.empty_like(y)
    k4 = np.empty_like(y)
    tmp = np.empty_like(y)
    fm = np.empty(m)
    dm = np.empty(m)
    fs = np.empty(m)
    ds = np.empty(m)
    for s in range(s0, min(s1, nsteps + 1)):
        t = s * h
        if s < nsteps:
            _rk4_step(t, y, h, p, k1, k2, k3, k4, tmp, fm, dm, fs, ds)
        else:
            rhs(t, y, p, k1, fm, dm)
        # fm, dm belong to the state at time t (before the update)
        if s % every == 0 and s // every < out_f.shape[0]:
            for j in range(m):
                out_f[s // every, j] = fm[j]
                out_d[s // every, j] = dm[j]
        if t >= w0 and t <= w1:
            for j in range(m):
                stats[j, 0] = max(stats[j, 0], fm[j])
                stats[j, 1] = min(stats[j, 1], fm[j])
                stats[j, 2] += fm[j]
                stats[j, 3] += 1.0
        for i in range(y.size):
            if not math.isfinite(y[i]):
                return s
        if s < nsteps and (s + 1) % every == 0 and (s + 1) // every < out_y.shape[0]:
            out_y[(s + 1) // every, :] = y
    return s1


# Dormand-Prince 5(4) tableau (Hairer, Norsett & Wanner I, table II.5.2)
_C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0])
_A = np.array([
    [0, 0, 0, 0, 0, 0],
    [1 / 5, 0, 0, 0, 0, 0],
    [3 / 40, 9 / 40, 0, 0, 0, 0],
    [44 / 45, -56 / 15, 32 / 9, 0, 0, 0],
    [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0, 0],
    [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656, 0],
    [35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84]])
_E = np.array([71 / 57600, 0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40])


@njit(cache=True)
def dopri5_start(y, p, K, out_y, out_f, out_d, counts):
    """First right-hand side (K[0], FSAL) and the sample at t = 0."""
    m = out_f.shape[1]
    fm = np.empty(m)
    dm = np.empty(m)
    rhs(0.0, y, p, K[0], fm, dm)
    counts[2] += 1
    out_y[0, :] = y
    for j in range(m):
        out_f[0, j] = fm[j]
        out_d[0, j] = dm[j]


@njit(cache=True)
def run_dopri5(y, K, st, t_stop, t_end, h_max, rtol, atol, p, dt_out, w0, w1, out_y, out_f, out_d, stats, counts):
    """Adaptive Dormand-Prince 5(4) from st[0] until t_stop (a chunk) or t_end; samples every dt_out
    by cubic Hermite. Resumable: y, K[0] (FSAL), st = [t, next step, last accepted step, next
    sample index] are updated in place; ``dopri5_start`` begins a run.

    ``atol`` is per component (2n). counts = [accepted, rejected, rhs evaluations].
    Forces in ``stats`` are taken at the samples. Returns False if the error stopped being finite.
    """
    nv = y.size
    m = out_f.shape[1]
    ynew = np.empty(nv)
    tmp = np.empty(nv)
    fm = np.empty(m)
    dm = np.empty(m)
    t = st[0]
    h = st[1]
    q = int(st[3])
    nout = out_y.shape[0]
    while t < t_end * (1 - 1e-14) and t < t_stop:
        h = min(h, h_max, t_end - t)
        for s in range(1, 7):
            for i in range(nv):
                acc = 0.0
                for r in range(s):
                    acc += _A[s, r] * K[r, i]
                tmp[i] = y[i] + h * acc
            rhs(t + _C[s] * h, tmp, p, K[s], fm, dm)
        counts[2] += 6
        err = 0.0
        for i in range(nv):
            ynew[i] = tmp[i]          # stage 7 state is the 5th-order solution (FSAL)
            e = 0.0
            for r in range(7):
                e += _E[r] * K[r, i]
            sc = atol[i] + rtol * max(abs(y[i]), abs(ynew[i]))
            err = max(err, abs(h * e) / sc)
        if not math.isfinite(err):
            st[0] = t
            st[1] = h
            st[3] = q
            return False
        if err <= 1.0:
            # samples in (t, t + h] by cubic Hermite between (y, K0) and (ynew, K6)
            while q < nout and q * dt_out <= t + h * (1 + 1e-12):
                th = (q * dt_out - t) / h
                h00 = 2 * th ** 3 - 3 * th ** 2 + 1
                h10 = th ** 3 - 2 * th ** 2 + th
                h01 = -2 * th ** 3 + 3 * th ** 2
                h11 = th ** 3 - th ** 2
                for i in range(nv):
                    tmp[i] = h00 * y[i] + h10 * h * K[0, i] + h01 * ynew[i] + h11 * h * K[6, i]
                out_y[q, :] = tmp
                rhs(q * dt_out, tmp, p, K[1], fm, dm)   # K[1] as scratch: overwritten next step
                for j in range(m):
                    out_f[q, j] = fm[j]
                    out_d[q, j] = dm[j]
                    if q * dt_out >= w0 and q * dt_out <= w1:
                        stats[j, 0] = max(stats[j, 0], fm[j])
                        stats[j, 1] = min(stats[j, 1], fm[j])
                        stats[j, 2] += fm[j]
                        stats[j, 3] += 1.0
                q += 1
            t += h
            st[2] = h
            for i in range(nv):
                y[i] = ynew[i]
                K[0, i] = K[6, i]
            counts[0] += 1
        else:
            counts[1] += 1
        fac = 0.9 * (1.0 / max(err, 1e-10)) ** 0.2
        h *= min(5.0, max(0.2, fac))
    st[0] = t
    st[1] = h
    st[3] = q
    return True


@njit(cache=True, parallel=True)
def sweep_rk4(omegas, ratio, q0, p, h, n_settle, n_window, kv_max, kv_min, f_mean, halves):
    """One RK4 run per input speed omegas[k] (prange): start at the static deflection q0 and the
    nominal speeds ratio * omega, settle n_settle[k] steps of h[k], then track the mesh forces over
    n_window[k] steps into kv_max, kv_min, f_mean (ns x m), and the max and min force of the first
    and of the second half of the window into halves (ns x m x 4), which shows growth."""
    ns = omegas.size
    n = q0.size
    m = kv_max.shape[1]
    for k in prange(ns):
        y = np.empty(2 * n)
        for i in range(n):
            y[i] = q0[i]
            y[n + i] = ratio[i] * omegas[k]
        k1 = np.empty(2 * n)
        k2 = np.empty(2 * n)
        k3 = np.empty(2 * n)
        k4 = np.empty(2 * n)
        tmp = np.empty(2 * n)
        fm = np.empty(m)
        dm = np.empty(m)
        fs = np.empty(m)
        ds = np.empty(m)
        for j in range(m):
            kv_max[k, j] = -np.inf
            kv_min[k, j] = np.inf
            f_mean[k, j] = 0.0
            halves[k, j, 0] = -np.inf
            halves[k, j, 1] = np.inf
            halves[k, j, 2] = -np.inf
            halves[k, j, 3] = np.inf
        hk = h[k]
        mid = n_settle[k] + n_window[k] // 2
        for s in range(n_settle[k] + n_window[k]):
            _rk4_step(s * hk, y, hk, p, k1, k2, k3, k4, tmp, fm, dm, fs, ds)
            if s >= n_settle[k]:
                for j in range(m):
                    kv_max[k, j] = max(kv_max[k, j], fm[j])
                    kv_min[k, j] = min(kv_min[k, j], fm[j])
                    f_mean[k, j] += fm[j] / n_window[k]
                    c = 0 if s < mid else 2
                    halves[k, j, c] = max(halves[k, j, c], fm[j])
                    halves[k, j, c + 1] = min(halves[k, j, c + 1], fm[j])


@njit(cache=True)
def _lin_rhs(t, y, p, w, dy):
    """Right-hand side of the linear parametric model: the perturbation y of the nominal rotation
    (gear speeds w), stiffness and friction arms at the nominal mesh positions u(t); no loads."""
    (J, Tc, ramp, ts_off, ts_x, ts_y, tt_off, tt_x, tt_y, ma, mb, rba, rbb, za, phase, cm, sep, bl,
     kt, fa, fb, sa, sb, sk, sc) = p
    n = J.size
    for i in range(n):
        dy[i] = y[n + i]
        dy[n + i] = 0.0
    for j in range(ma.size):
        a = ma[j]
        b = mb[j]
        u = za[j] * w[a] * t / TWO_PI + phase[j]
        u -= math.floor(u)
        f = _periodic(kt, j, u) * (rba[j] * y[a] - rbb[j] * y[b]) + cm[j] * (rba[j] * y[n + a] - rbb[j] * y[n + b])
        dy[n + a] += (-rba[j] + _periodic(fa, j, u)) * f
        dy[n + b] += (rbb[j] + _periodic(fb, j, u)) * f
    _shafts_and_inertia(y, dy, n, J, sa, sb, sk, sc)


@njit(cache=True, parallel=True)
def monodromy(omegas, ratio, periods, nsteps, p, phi):
    """Monodromy matrices phi[k] (2n x 2n) of the linear parametric model over one period
    periods[k] at input speed omegas[k], by RK4 with nsteps[k] steps (prange over speeds);
    their eigenvalues are the Floquet multipliers."""
    n = ratio.size
    for k in prange(omegas.size):
        w = ratio * omegas[k]
        h = periods[k] / nsteps[k]
        y = np.empty(2 * n)
        k1 = np.empty(2 * n)
        k2 = np.empty(2 * n)
        k3 = np.empty(2 * n)
        k4 = np.empty(2 * n)
        tmp = np.empty(2 * n)
        for c in range(2 * n):
            for i in range(2 * n):
                y[i] = 1.0 if i == c else 0.0
            for s in range(nsteps[k]):
                t = s * h
                _lin_rhs(t, y, p, w, k1)
                for i in range(2 * n):
                    tmp[i] = y[i] + 0.5 * h * k1[i]
                _lin_rhs(t + 0.5 * h, tmp, p, w, k2)
                for i in range(2 * n):
                    tmp[i] = y[i] + 0.5 * h * k2[i]
                _lin_rhs(t + 0.5 * h, tmp, p, w, k3)
                for i in range(2 * n):
                    tmp[i] = y[i] + h * k3[i]
                _lin_rhs(t + h, tmp, p, w, k4)
                for i in range(2 * n):
                    y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
            for i in range(2 * n):
                phi[k, i, c] = y[i]
