"""Compiled kernels of a planetary stage's time integration (``planetary_dynamics``). Contract:

- float64 arrays, int64 scalars; nothing compiled at import (``@njit(cache=True)``). Index base 0.
- State y (2n): the free coordinates q (rad: sun, ring, carrier, planets, the held member removed)
  then their speeds.
- Parameters ``p`` = (minv, torque, k_support, G, offset, H, phase, kt, cm), built by
  ``planetary_dynamics.params``: inverse inertias (n), constant torques (n), torsional support
  stiffnesses of the coordinates (n), the mesh rows G (m x n: deflection d_j = G_j . q + offset_j along
  the line of action, m), H (m x n: mesh position u_j = frac(H_j . q / 2 pi + phase_j)), the
  stiffness tables kt (m x N over one mesh period, as ``_kernels``) and the mesh damping cm (N s/m).
- Mesh force f_j = k_j(u_j) d_j + c_j G_j . q'; the generalised force on q is -sum_j f_j G_j.
- Classical RK4 with a fixed step, as the gear train's sweep (``_kernels.sweep_rk4``): start at the
  given state, settle ``n_settle`` steps, then track the mesh forces over ``n_window`` steps.
"""
import math

import numpy as np
from numba import njit, prange

from ._kernels import _periodic

TWO_PI = 2.0 * math.pi


@njit(cache=True)
def rhs(y, p, dy, fm):
    """dy = f(y) (no explicit time dependence: the torques are constant); mesh forces into fm (N)."""
    minv, torque, ksup, G, off, H, phase, kt, cm = p
    n = minv.size
    for i in range(n):
        dy[i] = y[n + i]
        dy[n + i] = torque[i] - ksup[i] * y[i]
    for j in range(G.shape[0]):
        d = off[j]
        dd = 0.0
        u = 0.0
        for i in range(n):
            g = G[j, i]
            d += g * y[i]
            dd += g * y[n + i]
            u += H[j, i] * y[i]
        u = u / TWO_PI + phase[j]
        u -= math.floor(u)
        f = _periodic(kt, j, u) * d + cm[j] * dd
        fm[j] = f
        for i in range(n):
            dy[n + i] -= G[j, i] * f
    for i in range(n):
        dy[n + i] *= minv[i]


@njit(cache=True)
def _integrate(y, h, n_settle, n_window, p, fmax, fmin, fmean, halves, out_f):
    """RK4 from the state y (in place): n_settle steps, then n_window steps over which the mesh forces
    (at the start of every step) go into fmax, fmin, fmean (m), the max and min of the first and second
    half of the window into halves (m x 4), and, when out_f has n_window rows, every step's into out_f."""
    nv = y.size
    m = fmax.size
    k1 = np.empty(nv)
    k2 = np.empty(nv)
    k3 = np.empty(nv)
    k4 = np.empty(nv)
    tmp = np.empty(nv)
    fm = np.empty(m)
    fs = np.empty(m)
    for j in range(m):
        fmax[j] = -np.inf
        fmin[j] = np.inf
        fmean[j] = 0.0
        halves[j, 0] = -np.inf
        halves[j, 1] = np.inf
        halves[j, 2] = -np.inf
        halves[j, 3] = np.inf
    record = out_f.shape[0] == n_window
    mid = n_settle + n_window // 2
    for s in range(n_settle + n_window):
        rhs(y, p, k1, fm)
        for i in range(nv):
            tmp[i] = y[i] + 0.5 * h * k1[i]
        rhs(tmp, p, k2, fs)
        for i in range(nv):
            tmp[i] = y[i] + 0.5 * h * k2[i]
        rhs(tmp, p, k3, fs)
        for i in range(nv):
            tmp[i] = y[i] + h * k3[i]
        rhs(tmp, p, k4, fs)
        for i in range(nv):
            y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
        if s >= n_settle:
            c = 0 if s < mid else 2
            for j in range(m):
                f = fm[j]
                fmax[j] = max(fmax[j], f)
                fmin[j] = min(fmin[j], f)
                fmean[j] += f / n_window
                halves[j, c] = max(halves[j, c], f)
                halves[j, c + 1] = min(halves[j, c + 1], f)
                if record:
                    out_f[s - n_settle, j] = f


@njit(cache=True)
def run(y, h, n_settle, n_window, p, fmax, fmin, fmean, halves, out_f):
    """One run at one speed (see ``_integrate``)."""
    _integrate(y, h, n_settle, n_window, p, fmax, fmin, fmean, halves, out_f)


@njit(cache=True, parallel=True)
def sweep(omegas, phi, q0, p, h, n_settle, n_window, fmax, fmin, fmean, halves):
    """One run per input speed omegas[k] (prange): from the static deflection q0 and the speeds
    phi * omegas[k], settle n_settle[k] steps of h[k], track the forces over n_window[k] steps into
    fmax, fmin, fmean (ns x m) and halves (ns x m x 4)."""
    n = q0.size
    for k in prange(omegas.size):
        y = np.empty(2 * n)
        for i in range(n):
            y[i] = q0[i]
            y[n + i] = phi[i] * omegas[k]
        none = np.empty((0, fmax.shape[1]))
        _integrate(y, h[k], n_settle[k], n_window[k], p, fmax[k], fmin[k], fmean[k], halves[k], none)
