"""A synchronous drive's transmission (phase) error, shared by both dynamic models' teeth outputs
(segments/teeth_outputs.py, rotational/teeth.py): each grooved pulley's angle against its tooth ratio
to the first grooved pulley (the crank), in the crank's degrees, and its largest orders."""
from __future__ import annotations

import math

import numpy as np


def phase_error(th, tp, z):
    """(samples, len(tp)) phase error in degrees: theta_j - (z_0 / z_j) theta_0 scaled by z_j / z_0, its
    start value taken off; ``th`` (samples, pulleys) angles, ``tp`` the grooved pulleys, ``z`` their grooves."""
    ns = th.shape[0]
    pe = np.zeros((ns, len(tp)))
    for m, j in enumerate(tp):
        if m and ns:
            e = (th[:, j] - z[0] / z[m] * th[:, tp[0]]) * z[m] / z[0]
            pe[:, m] = np.degrees(e - e[0])
    return pe


def phase_rows(rows, names, th, pe, sel):
    """Into ``rows`` (per pulley name): the phase error's peak to peak, mean and largest orders over
    the window ``sel``, for every grooved pulley after the first (``names``, in pe's order)."""
    if not sel.any() or len(names) < 2:
        return
    th0 = th[sel]
    for m, name in enumerate(names):
        if m:
            e = pe[sel, m]
            rows[name].update(phase_error_pp=float(e.max() - e.min()), phase_error_mean=float(e.mean()),
                              phase_error_orders=orders_of(th0, e))


def orders_of(theta, e, n=3):
    """The n largest orders of e over the angle theta (rad, turning steadily), by a least-squares fit of
    cosines and sines at the half orders up to 12 (a cam drive's content: the crank's orders)."""
    turns = abs(theta[-1] - theta[0]) / (2 * math.pi) if len(theta) > 1 else 0.0
    if turns < 1.0:
        return []
    phi = theta - theta[0]
    orders = np.arange(0.5, 12.01, 0.5)
    cols = [np.ones_like(phi)]
    for k in orders:
        cols += [np.cos(k * phi), np.sin(k * phi)]
    coef, *_ = np.linalg.lstsq(np.column_stack(cols), e - e.mean(), rcond=None)
    amp = np.hypot(coef[1::2], coef[2::2])
    top = np.argsort(amp)[::-1][:n]
    return [{"order": float(orders[i]), "amplitude": float(amp[i])} for i in top if amp[i] > 0]
