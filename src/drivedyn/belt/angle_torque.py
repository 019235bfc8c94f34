"""A load torque given as a table over one turn of the pulley's own angle (a camshaft's valve-train
torque, a pump's), turned at load time into its mean and harmonics amplitude sin(order theta + phase),
which the kernels already apply (dynamics/_bodies.py), so that a cam drive runs unchanged.

The table is periodic: its angles span one turn (last - first = 360 deg) and its last torque repeats
its first. Its Fourier coefficients

    c_k = (1 / M) sum_j T(theta_j) exp(-i k theta_j),   T = c_0 + sum_k 2 |c_k| sin(k theta + arg c_k + pi/2)

are taken over M uniform samples of one turn: the table's own rows (without the repeated last) when
they are evenly spaced, which makes the series the trigonometric interpolant through the rows, exact
for a table sampled from harmonics below M / 2 (the discrete Fourier transform's orthogonality:
Oppenheim & Schafer, Discrete-Time Signal Processing, 3rd ed., sec. 8.1); else the rows' linear
interpolant sampled at SAMPLES points (its Fourier series, aliased by less than its content above
order SAMPLES / 2). Orders up to MAX_ORDER (and below M / 2) whose amplitude is at least FLOOR of the
largest are kept.
"""
from __future__ import annotations

import math

import numpy as np

#: the highest order kept (a four-stroke cam's valve events sit at orders 2-8 of the cam: 4 cylinders,
#: 2 valves each; 40 keeps the lobes' flanks)
MAX_ORDER = 40
#: orders below this share of the largest amplitude are dropped
FLOOR = 1e-3
#: uniform samples of an uneven table's linear interpolant
SAMPLES = 4096
#: the angles must span one turn to this (rad), the last torque repeat the first to this share of the
#: table's largest torque
ANGLE_TOL = 1e-9
TORQUE_TOL = 1e-9


def check_closed(rows) -> None:
    """ValueError (one line with the numbers; the loader names the field) unless the table closes
    over one turn."""
    if len(rows) < 3:
        raise ValueError(f"needs at least 3 rows over one turn (0 .. 360 deg), got {len(rows)}")
    span = rows[-1][0] - rows[0][0]
    if abs(span - 2 * math.pi) > ANGLE_TOL:
        raise ValueError(f"the angles must span one turn, 360 deg: they run from {math.degrees(rows[0][0]):.6g} "
                         f"to {math.degrees(rows[-1][0]):.6g} deg ({math.degrees(span):.6g} deg)")
    big = max(abs(r[1]) for r in rows)
    if abs(rows[-1][1] - rows[0][1]) > TORQUE_TOL * max(big, 1e-300):
        raise ValueError(f"the table does not close over the turn: the torque at "
                         f"{math.degrees(rows[-1][0]):.6g} deg ({rows[-1][1]:.6g} N*m) differs from the torque at "
                         f"{math.degrees(rows[0][0]):.6g} deg ({rows[0][1]:.6g} N*m)")


def series(rows):
    """(mean torque N m, [(order, amplitude N m, phase rad), ...] by order) of a closed table (check_closed)."""
    x = np.array([r[0] for r in rows], float)
    y = np.array([r[1] for r in rows], float)
    step = np.diff(x)
    if np.all(np.abs(step - step.mean()) <= ANGLE_TOL):
        theta, torque = x[:-1], y[:-1]
    else:
        theta = x[0] + 2 * math.pi * np.arange(SAMPLES) / SAMPLES
        torque = np.interp(theta, x, y)
    m = len(theta)
    top = min(MAX_ORDER, (m - 1) // 2)
    k = np.arange(1, top + 1)
    c = np.exp(-1j * np.outer(k, theta)) @ torque / m
    amp = 2 * np.abs(c)
    keep = amp >= FLOOR * amp.max() if top and amp.max() > 0 else np.zeros(top, bool)
    phase = np.angle(c) + 0.5 * math.pi
    phase = (phase + math.pi) % (2 * math.pi) - math.pi
    return float(torque.mean()), [(int(kk), float(a), float(p)) for kk, a, p, ok in zip(k, amp, phase, keep) if ok]
