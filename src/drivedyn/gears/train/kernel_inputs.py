"""What the compiled kernels start from: their parameter tuple, the mesh stiffness at given angles
and the static equilibrium at the start position, all read off an assembled ``train.System``.

Below ``simulate``, ``sweep`` and ``checks``, which all use them (no module of this package that
this one imports imports any of those back).
"""
from __future__ import annotations

import math

import numpy as np

from .system import System


def params(sys_: System, ramp: float = 0.0, tables: bool = True) -> tuple:
    """The kernel parameter tuple (order: see the contract of ``_kernels``)."""
    fa, fb = sys_.friction_tables()
    empty_i, empty_f = np.zeros(sys_.n + 1, dtype=np.int64), np.zeros(0)
    ts = (sys_.ts_off, sys_.ts_x, sys_.ts_y) if tables else (empty_i, empty_f, empty_f)
    tt = (sys_.tt_off, sys_.tt_x, sys_.tt_y) if tables else (empty_i, empty_f, empty_f)
    return (sys_.inertia.astype(float), sys_.torque_const.astype(float), float(ramp), *ts, *tt,
            sys_.mesh_a, sys_.mesh_b, sys_.rb_a, sys_.rb_b, sys_.z_a, sys_.phase, sys_.damping, sys_.separation,
            sys_.backlash, sys_.ktab(), fa, fb, sys_.shaft_a, sys_.shaft_b, sys_.shaft_k, sys_.shaft_c)


def stiffness_at(sys_: System, theta_a) -> np.ndarray:
    """Mesh stiffness (N/m) of every mesh at driving-gear angles ``theta_a`` (..., m) by the tables;
    NaN where an angle is not finite (a diverged run)."""
    kt = sys_.ktab()
    N = kt.shape[1]
    theta_a = np.asarray(theta_a, dtype=float)
    ok = np.isfinite(theta_a)
    u = (sys_.z_a * np.where(ok, theta_a, 0.0) / (2 * math.pi) + sys_.phase) % 1.0
    x = u * N
    i0 = np.minimum(x.astype(int), N - 1)
    w = x - i0
    i1 = (i0 + 1) % N
    cols = np.arange(sys_.m)
    return np.where(ok, kt[cols, i0] * (1 - w) + kt[cols, i1] * w, np.nan)


def static_start(sys_: System) -> np.ndarray:
    """Deflections (rad) in static equilibrium with the stiffness at the start position (theta = 0)."""
    q = np.zeros(sys_.n)
    for _ in range(3):      # the stiffness depends (weakly) on the deflected angle: a few fixed-point passes
        q, _, _ = sys_.static(k_mesh=stiffness_at(sys_, q[sys_.mesh_a]))
    return q
