"""The belt path on non-circular pitch curves over one turn of a chosen pulley (mechanics/curve_layout.py
at each angle): belt length, span lengths, wraps and effective radii against that pulley's angle, their
ranges and their order content.

The other pulleys stand still (``ratios="fixed"``: the belt path a static check sees at each position
of one pulley) or turn with it at their mean speed ratios: a rigid belt passes the same length over
every pulley on average, so that pulley i turns by sigma_i / sigma_k * P_k / P_i times pulley k's angle
(P the curves' perimeters, sigma the senses of mechanics/layout.py; for toothed pulleys whose pitch
curves fit their teeth, the tooth ratio z_k / z_i), or at the ratios given.

The order content of a quantity q(theta) sampled at N uniform angles over the turn is its discrete
Fourier series: the amplitude of order m is 2 |Q_m| / N, Q_m = sum_j q_j exp(-i m theta_j), the
trigonometric interpolant's (Oppenheim & Schafer, Discrete-Time Signal Processing, 3rd ed., sec. 8.1).
When the others turn at ratios whose curves do not return after one turn of pulley k, the samples are
those of one turn of k, and orders of the other curves show as their ratio times their own order.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .curve_layout import layout_at, senses
from .pitch_curves import Circle, PitchCurve


@dataclass(frozen=True)
class Turn:
    names: tuple
    span_names: tuple
    pulley: int            # the pulley turned
    theta: np.ndarray      # (N,) its angle (rad), uniform over one turn from its angle in ``start``
    angles: np.ndarray     # (N, nk) all pulleys' angles
    length: np.ndarray     # (N,) belt path length (m)
    spans: np.ndarray      # (N, nk) span lengths (m), span k leaves pulley k
    wrap: np.ndarray       # (N, nk) wrap angles (rad)
    radius_in: np.ndarray  # (N, nk) effective radius where the belt arrives on each pulley (m)
    radius_out: np.ndarray  # (N, nk) effective radius where it leaves (m)

    def orders(self, values, top: int = 8) -> np.ndarray:
        """Amplitudes of orders 0..top of samples over the turn (order 0: the mean)."""
        q = np.fft.rfft(np.asarray(values, float), axis=0) / len(self.theta)
        amp = 2 * np.abs(q)
        amp[0] /= 2
        return amp[: top + 1]


def ratios_of(curves, sides, centers, pulley: int, teeth=None) -> np.ndarray:
    """Each pulley's angle per angle of ``pulley``, turning with it at the mean speed ratio."""
    _, sig = senses(centers, sides)
    if teeth is not None and teeth[pulley] and all(teeth):
        size = [float(z) for z in teeth]
    else:
        size = [c.perimeter for c in curves]
    return np.array([sig[i] / sig[pulley] * size[pulley] / size[i] for i in range(len(curves))])


def over_a_turn(names, centers, curves, sides, pulley: int = 0, start=None, ratios="turning", points: int = 360,
                teeth=None) -> Turn:
    """The layout at ``points`` uniform angles over one turn of ``pulley`` (index in belt order), the others
    at ``start`` (rad, zeros when none) and fixed (``ratios="fixed"``), turning at the mean speed ratios
    (``"turning"``) or at the given ratios (one per pulley)."""
    curves = tuple(c if isinstance(c, PitchCurve) else Circle(c) for c in curves)
    nk = len(names)
    start = np.zeros(nk) if start is None else np.asarray(start, float)
    if isinstance(ratios, str):
        if ratios == "fixed":
            rat = np.zeros(nk)
            rat[pulley] = 1.0
        else:
            rat = ratios_of(curves, sides, centers, pulley, teeth)
    else:
        rat = np.asarray(ratios, float)
    dtheta = np.arange(points) * (2 * math.pi / points)
    angles = start[None, :] + dtheta[:, None] * rat[None, :]
    L = np.zeros(points)
    S, W, Ri, Ro = (np.zeros((points, nk)) for _ in range(4))
    lay = None
    for i in range(points):
        lay = layout_at(names, centers, curves, sides, angles[i])
        L[i] = lay.length
        S[i] = lay.span_lengths
        W[i] = lay.wrap
        Ri[i] = lay.radius_in
        Ro[i] = lay.radius_out
    return Turn(tuple(names), tuple(s.name for s in lay.spans), pulley, start[pulley] + dtheta, angles, L, S, W, Ri, Ro)
