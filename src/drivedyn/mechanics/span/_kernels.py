"""Compiled kernels of the span analysis: Floquet monodromy of the damped Hill equation.

Contract: float64 1-D arrays of equal length for per-point inputs, float64 1-D arrays for the
Fourier shape, Python ints for step controls; outputs are written into preallocated float64
arrays; no Python objects, no allocation per point, nothing compiled at import (cache=True, no
signatures).

The equation (seed eq. 5 made dimensionless with tau = omega t, one period tau in [0, 2 pi)):

    q'' + gamma q' + (alpha + beta Phi(tau)) q = 0,
    Phi(tau) = sum_j a_j cos(j tau) + b_j sin(j tau)      (j = 1..K)

with alpha = Omega^2 / omega^2, beta = (pi/l)^2 F1 / (rhoA omega^2) = 2 mu alpha, and
gamma = 2 zeta Omega / omega. The monodromy matrix is integrated with classical RK4 at
``n = max(n_min, ceil(steps_per_osc * sqrt(|alpha| + |beta| * s)))`` steps per period
(s = sum |a_j| + |b_j|, sqrt(...) the number of free oscillations per period).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit


@njit(cache=True)
def _phi(tau, a, b):
    s = 0.0
    for j in range(a.shape[0]):
        x = (j + 1) * tau
        s += a[j] * math.cos(x) + b[j] * math.sin(x)
    return s


@njit(cache=True)
def monodromy(alpha, beta, gamma, a, b, n):
    """Monodromy matrix (m11, m12, m21, m22) of one point over one period, n RK4 steps."""
    h = 2.0 * math.pi / n
    # columns of the fundamental matrix: (q, q') for q(0)=1,q'(0)=0 and q(0)=0,q'(0)=1
    x1, v1, x2, v2 = 1.0, 0.0, 0.0, 1.0
    for i in range(n):
        t0 = i * h
        k0 = alpha + beta * _phi(t0, a, b)
        km = alpha + beta * _phi(t0 + 0.5 * h, a, b)
        k1 = alpha + beta * _phi(t0 + h, a, b)
        # RK4 for y' = (v, -gamma v - k(t) x), same stiffness samples shared by both columns
        ax1, av1 = v1, -gamma * v1 - k0 * x1
        ax2, av2 = v2, -gamma * v2 - k0 * x2
        bx1 = v1 + 0.5 * h * av1
        bv1 = -gamma * bx1 - km * (x1 + 0.5 * h * ax1)
        bx2 = v2 + 0.5 * h * av2
        bv2 = -gamma * bx2 - km * (x2 + 0.5 * h * ax2)
        cx1 = v1 + 0.5 * h * bv1
        cv1 = -gamma * cx1 - km * (x1 + 0.5 * h * bx1)
        cx2 = v2 + 0.5 * h * bv2
        cv2 = -gamma * cx2 - km * (x2 + 0.5 * h * bx2)
        dx1 = v1 + h * cv1
        dv1 = -gamma * dx1 - k1 * (x1 + h * cx1)
        dx2 = v2 + h * cv2
        dv2 = -gamma * dx2 - k1 * (x2 + h * cx2)
        x1 += h / 6.0 * (ax1 + 2.0 * bx1 + 2.0 * cx1 + dx1)
        v1 += h / 6.0 * (av1 + 2.0 * bv1 + 2.0 * cv1 + dv1)
        x2 += h / 6.0 * (ax2 + 2.0 * bx2 + 2.0 * cx2 + dx2)
        v2 += h / 6.0 * (av2 + 2.0 * bv2 + 2.0 * cv2 + dv2)
    return x1, x2, v1, v2


@njit(cache=True)
def floquet_points(alpha, beta, gamma, a, b, steps_per_osc, n_min, n_max, out_trace, out_det, out_rho):
    """Trace, determinant and largest multiplier modulus of the monodromy at every point.

    NaN inputs give NaN outputs. ``out_rho`` = max |lambda| over the two Floquet multipliers.
    """
    s = 0.0
    for j in range(a.shape[0]):
        s += abs(a[j]) + abs(b[j])
    for p in range(alpha.shape[0]):
        al, be, ga = alpha[p], beta[p], gamma[p]
        if not (math.isfinite(al) and math.isfinite(be) and math.isfinite(ga)):
            out_trace[p] = np.nan
            out_det[p] = np.nan
            out_rho[p] = np.nan
            continue
        osc = math.sqrt(abs(al) + abs(be) * s)
        n = int(math.ceil(steps_per_osc * osc))
        n = min(max(n, n_min), n_max)
        m11, m12, m21, m22 = monodromy(al, be, ga, a, b, n)
        tr = m11 + m22
        det = m11 * m22 - m12 * m21
        disc = tr * tr - 4.0 * det
        if disc >= 0.0:
            r = math.sqrt(disc)
            rho = max(abs(0.5 * (tr + r)), abs(0.5 * (tr - r)))
        else:
            rho = math.sqrt(abs(det))
        out_trace[p] = tr
        out_det[p] = det
        out_rho[p] = rho
