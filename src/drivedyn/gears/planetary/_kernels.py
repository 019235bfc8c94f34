"""Compiled kernels of a planetary stage's time integration (``planetary_dynamics``). Contract:

- float64 arrays, int64 scalars; nothing compiled at import (``@njit(cache=True)``). Index base 0.
- State y (2n): the free coordinates q (the torsional model's rotations in rad, or the lateral model's
  translations and rotations as displacements in m, the held coordinates removed) then their speeds.
- Parameters ``p`` = (minv, load, Ks, G, offset, H, phase, kt, cm, w, s_reg), built by
  ``planetary_dynamics.params``: inverse masses (n), constant generalised forces (n: the torques and
  what the constant springs' offsets load), the constant stiffness matrix Ks (n x n: torsional supports,
  bearings, pins), the mesh rows G (m x n: deflection d_j = G_j . q + offset_j along the line of action,
  m), H (m x n: mesh position u_j = frac(H_j . q / 2 pi + phase_j)), the stiffness tables kt (m x N over
  one mesh period, as ``_kernels``), the mesh damping cm (N s/m), and w = M phi (n, phi the rigid-body
  motion) with the scale s_reg that fixes the quasi-static solve's rigid-body part (w . q = 0).
- Mesh force f_j = k_j(u_j) d_j + c_j G_j . q'; the generalised force on q is load - Ks q - sum_j f_j G_j.
- Quasi-static mesh forces at an instant: the static solution with the instant's mesh stiffnesses k_j(u_j),
  (Ks + sum_j k_j G_j G_j^T + s_reg w w^T) q = load - sum_j k_j offset_j G_j (the loads are balanced, so
  w . q = 0 and the rigid-body term does nothing else), f_qs,j = k_j (G_j . q + offset_j).
- Classical RK4 with a fixed step, as the gear train's sweep (``_kernels.sweep_rk4``): start at the
  given state, settle ``n_settle`` steps, then track the mesh forces and their quasi-static values over
  ``n_window`` steps.
"""
import math

import numpy as np
from numba import njit, prange

from ..train._kernels import _periodic

TWO_PI = 2.0 * math.pi


@njit(cache=True)
def rhs(y, p, dy, fm, km):
    """dy = f(y) (no explicit time dependence: the loads are constant); mesh forces into fm (m), mesh
    stiffnesses into km (m)."""
    minv, load, Ks, G, off, H, phase, kt, cm, _w, _s_reg = p
    n = minv.size
    for i in range(n):
        dy[i] = y[n + i]
        a = load[i]
        for k in range(n):
            a -= Ks[i, k] * y[k]
        dy[n + i] = a
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
        k = _periodic(kt, j, u)
        km[j] = k
        f = k * d + cm[j] * dd
        fm[j] = f
        for i in range(n):
            dy[n + i] -= G[j, i] * f
    for i in range(n):
        dy[n + i] *= minv[i]


@njit(cache=True)
def quasi_static(p, km, A, b, q, fq):
    """Quasi-static mesh forces fq (m) with the mesh stiffnesses km (module docstring); A (n x n), b and q
    (n) work arrays."""
    minv, load, Ks, G, off, _H, _phase, _kt, _cm, w, s_reg = p
    n = minv.size
    m = G.shape[0]
    for i in range(n):
        b[i] = load[i]
        for k in range(n):
            A[i, k] = Ks[i, k] + s_reg * w[i] * w[k]
    for j in range(m):
        kj = km[j]
        for i in range(n):
            gi = G[j, i]
            if gi != 0.0:
                b[i] -= kj * off[j] * gi
                for k in range(n):
                    A[i, k] += kj * gi * G[j, k]
    # Cholesky A = L L^T in place (lower triangle), then the two triangular solves
    for i in range(n):
        for k in range(i + 1):
            s = A[i, k]
            for r in range(k):
                s -= A[i, r] * A[k, r]
            if i == k:
                A[i, i] = math.sqrt(s) if s > 0.0 else math.nan
            else:
                A[i, k] = s / A[k, k]
    for i in range(n):
        s = b[i]
        for r in range(i):
            s -= A[i, r] * q[r]
        q[i] = s / A[i, i]
    for i in range(n - 1, -1, -1):
        s = q[i]
        for r in range(i + 1, n):
            s -= A[r, i] * q[r]
        q[i] = s / A[i, i]
    for j in range(m):
        d = off[j]
        for i in range(n):
            d += G[j, i] * q[i]
        fq[j] = km[j] * d


@njit(cache=True)
def _integrate(y, h, n_settle, n_window, p, fmax, fmin, fmean, halves, qs, out_f, out_q):
    """RK4 from the state y (in place): n_settle steps, then n_window steps over which the mesh forces
    (at the start of every step) go into fmax, fmin, fmean (m), the max and min of the first and second
    half of the window into halves (m x 4), the quasi-static forces' max and min, the largest quasi-static
    share (force over the mean force of the mesh's half of the meshes: sun-planet, ring-planet) and the
    largest force over its quasi-static value into qs (m x 4), and, when out_f and out_q have n_window rows,
    every step's forces and quasi-static forces into them."""
    nv = y.size
    n = nv // 2
    m = fmax.size
    half = m // 2
    k1 = np.empty(nv)
    k2 = np.empty(nv)
    k3 = np.empty(nv)
    k4 = np.empty(nv)
    tmp = np.empty(nv)
    fm = np.empty(m)
    fs = np.empty(m)
    km = np.empty(m)
    ks = np.empty(m)
    fq = np.empty(m)
    A = np.empty((n, n))
    b = np.empty(n)
    q = np.empty(n)
    for j in range(m):
        fmax[j] = -np.inf
        fmin[j] = np.inf
        fmean[j] = 0.0
        halves[j, 0] = -np.inf
        halves[j, 1] = np.inf
        halves[j, 2] = -np.inf
        halves[j, 3] = np.inf
        qs[j, 0] = -np.inf
        qs[j, 1] = np.inf
        qs[j, 2] = -np.inf
        qs[j, 3] = -np.inf
    record = out_f.shape[0] == n_window
    mid = n_settle + n_window // 2
    for s in range(n_settle + n_window):
        rhs(y, p, k1, fm, km)
        if s >= n_settle:
            quasi_static(p, km, A, b, q, fq)
        for i in range(nv):
            tmp[i] = y[i] + 0.5 * h * k1[i]
        rhs(tmp, p, k2, fs, ks)
        for i in range(nv):
            tmp[i] = y[i] + 0.5 * h * k2[i]
        rhs(tmp, p, k3, fs, ks)
        for i in range(nv):
            tmp[i] = y[i] + h * k3[i]
        rhs(tmp, p, k4, fs, ks)
        for i in range(nv):
            y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
        if s >= n_settle:
            c = 0 if s < mid else 2
            for g in range(2):
                mean = 0.0
                for j in range(g * half, (g + 1) * half):
                    mean += fq[j] / half
                for j in range(g * half, (g + 1) * half):
                    # a mean of 0 (a stage whose torque is round-off beside its pin errors' forces):
                    # no share is defined, and an infinite one fails any limit
                    qs[j, 2] = max(qs[j, 2], fq[j] / mean if mean != 0.0 else np.inf)
            for j in range(m):
                f = fm[j]
                fmax[j] = max(fmax[j], f)
                fmin[j] = min(fmin[j], f)
                fmean[j] += f / n_window
                halves[j, c] = max(halves[j, c], f)
                halves[j, c + 1] = min(halves[j, c + 1], f)
                qs[j, 0] = max(qs[j, 0], fq[j])
                qs[j, 1] = min(qs[j, 1], fq[j])
                qs[j, 3] = max(qs[j, 3], f / fq[j] if fq[j] != 0.0 else np.inf)
                if record:
                    out_f[s - n_settle, j] = f
                    out_q[s - n_settle, j] = fq[j]


@njit(cache=True)
def run(y, h, n_settle, n_window, p, fmax, fmin, fmean, halves, qs, out_f, out_q):
    """One run at one speed (see ``_integrate``)."""
    _integrate(y, h, n_settle, n_window, p, fmax, fmin, fmean, halves, qs, out_f, out_q)


@njit(cache=True, parallel=True)
def sweep(omegas, phi, q0, p, h, n_settle, n_window, fmax, fmin, fmean, halves, qs):
    """One run per input speed omegas[k] (prange): from the static deflection q0 and the speeds
    phi * omegas[k], settle n_settle[k] steps of h[k], track the forces over n_window[k] steps into
    fmax, fmin, fmean (ns x m), halves (ns x m x 4) and qs (ns x m x 4)."""
    n = q0.size
    for k in prange(omegas.size):
        y = np.empty(2 * n)
        for i in range(n):
            y[i] = q0[i]
            y[n + i] = phi[i] * omegas[k]
        none = np.empty((0, fmax.shape[1]))
        _integrate(y, h[k], n_settle[k], n_window[k], p, fmax[k], fmin[k], fmean[k], halves[k], qs[k], none, none)
