"""The belt path on non-circular pitch curves over one turn of a chosen pulley (mechanics/curve_layout.py
at each angle): belt length, span lengths, wraps and effective radii against that pulley's angle, their
ranges and their order content.

The other pulleys stand still (``ratios="fixed"``: the belt path a static check sees at each position
of one pulley) or turn with it at their mean speed ratios: a rigid belt passes the same length over
every pulley on average, so that pulley i turns by sigma_i / sigma_k * P_k / P_i times pulley k's angle
(P the curves' perimeters, sigma the senses of mechanics/layout.py; on toothed pulleys, teeth x pitch:
the tooth ratio), or at the ratios given. Over several turns of pulley k (``whole_turns``: a cam at half
the crank's speed makes a whole turn in two), the samples cover whole turns of every curve.

The order content of a quantity q(theta) sampled at N uniform angles over the turn is its discrete
Fourier series: the amplitude of order m is 2 |Q_m| / N, Q_m = sum_j q_j exp(-i m theta_j), the
trigonometric interpolant's (Oppenheim & Schafer, Discrete-Time Signal Processing, 3rd ed., sec. 8.1).
Orders are counted per turn of pulley k: a curve of order n on a pulley turning at ratio q shows at
order q n.
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

    turns: int = 1         # turns of the pulley sampled (each non-circular curve makes whole turns in them)

    def orders(self, values, top: int = 8) -> np.ndarray:
        """Amplitudes of orders 0..top of the turned pulley (order 0: the mean) of samples over the turns;
        with several turns, the bins between whole orders are left out."""
        q = np.fft.rfft(np.asarray(values, float), axis=0) / len(self.theta)
        amp = 2 * np.abs(q)
        amp[0] /= 2
        return amp[: top * self.turns + 1: self.turns]

    def dominant(self, values) -> tuple[float, float]:
        """(order, amplitude) of the largest harmonic (order > 0, fractional with several turns)."""
        q = np.fft.rfft(np.asarray(values, float)) / len(self.theta)
        amp = 2 * np.abs(q[1:])
        k = int(np.argmax(amp))
        return (k + 1) / self.turns, float(amp[k])


def ratios_of(curves, sides, centers, pulley: int, lengths=None) -> np.ndarray:
    """Each pulley's angle per angle of ``pulley``, turning with it at the mean speed ratio: the ratio of the
    belt lengths one turn passes (``lengths``, e.g. teeth x pitch on toothed pulleys; the curves' perimeters
    when none)."""
    _, sig = senses(centers, sides)
    size = [c.perimeter for c in curves] if lengths is None else [float(x) for x in lengths]
    return np.array([sig[i] / sig[pulley] * size[pulley] / size[i] for i in range(len(curves))])


def whole_turns(curves, ratios, pulley: int, most: int = 6) -> int:
    """The fewest turns of ``pulley`` (up to ``most``) in which every non-circular curve makes whole turns
    (1 when none fits)."""
    moving = [abs(r) for c, r in zip(curves, ratios) if not isinstance(c, Circle)]
    for m in range(1, most + 1):
        if all(abs(m * r - round(m * r)) < 1e-6 for r in moving):
            return m
    return 1


def over_a_turn(names, centers, curves, sides, pulley: int = 0, start=None, ratios="turning", points: int = 360,
                lengths=None, turns: int = 1) -> Turn:
    """The layout at ``points`` uniform angles per turn over ``turns`` turns of ``pulley`` (index in belt
    order), the others at ``start`` (rad, zeros when none) and fixed (``ratios="fixed"``), turning at the
    mean speed ratios (``"turning"``) or at the given ratios (one per pulley)."""
    curves = tuple(c if isinstance(c, PitchCurve) else Circle(c) for c in curves)
    nk = len(names)
    start = np.zeros(nk) if start is None else np.asarray(start, float)
    if isinstance(ratios, str):
        if ratios == "fixed":
            rat = np.zeros(nk)
            rat[pulley] = 1.0
        else:
            rat = ratios_of(curves, sides, centers, pulley, lengths)
    else:
        rat = np.asarray(ratios, float)
    dtheta = np.arange(points * turns) * (2 * math.pi / points)
    angles = start[None, :] + dtheta[:, None] * rat[None, :]
    L = np.zeros(len(dtheta))
    S, W, Ri, Ro = (np.zeros((len(dtheta), nk)) for _ in range(4))
    lay = None
    for i in range(len(dtheta)):
        lay = layout_at(names, centers, curves, sides, angles[i])
        L[i] = lay.length
        S[i] = lay.span_lengths
        W[i] = lay.wrap
        Ri[i] = lay.radius_in
        Ro[i] = lay.radius_out
    return Turn(tuple(names), tuple(s.name for s in lay.spans), pulley, start[pulley] + dtheta, angles, L, S, W, Ri, Ro,
                turns)
