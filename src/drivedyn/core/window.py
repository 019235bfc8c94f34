"""The steady window: one rule for choosing it and one for judging whether it is steady.

Time-domain analyses (belt drives, gear trains) report means, extremes and K_v over a window at
the end of the run. Unless the model gives one, the window is the last quarter of the run. A
window is steady when the quantities do not drift inside it: the change of the least-squares
line through a quantity over the window, against a scale of that quantity (its mean, or a
nominal value), stays below a tolerance.
"""
from __future__ import annotations

import numpy as np

#: share of the run at its end taken as the steady window when the model gives none
DEFAULT_SHARE = 0.25


def steady_window(given, duration: float) -> tuple[float, float]:
    """The window ``given`` in the model, else the last quarter of ``duration``."""
    if given is not None:
        return float(given[0]), float(given[1])
    return (1.0 - DEFAULT_SHARE) * duration, float(duration)


def in_window(t, window) -> np.ndarray:
    """Mask of the samples ``t`` inside ``window`` (start excluded, end included, with round-off)."""
    t = np.asarray(t)
    return (t > window[0]) & (t <= window[1] * (1 + 1e-12) + 1e-15)


def drift(t, y, scale, period=None) -> np.ndarray:
    """Change of the least-squares line through each column of ``y`` over the span of ``t``,
    divided by ``scale`` (per column or one number): 0 for a steady signal, 1 when it moves by
    a whole scale. Oscillations with many periods in the window hardly move the line; one with
    few does (an oscillation of amplitude A and period T tilts it by up to about A T / W over a
    window W): where the excitation's period is known (``period``, s; the samples evenly spaced),
    each column is first averaged over one period (a moving mean), which takes out the period
    and all its harmonics, and the line is fitted to that (when the window holds two periods); its
    change is read over the whole window."""
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    if y.ndim == 1:
        y = y[:, None]
    span = t[-1] - t[0] if len(t) else 0.0
    if period is not None and len(t) > 2:
        dt = span / (len(t) - 1)
        k = int(round(period / dt))
        if k >= 2 and 2 * k <= len(t):
            c = np.cumsum(np.vstack([np.zeros((1, y.shape[1])), y]), axis=0)
            y = (c[k:] - c[:-k]) / k
            t = 0.5 * (t[k - 1:] + t[:len(t) - k + 1])
    if len(t) < 3:
        return np.full(y.shape[1], np.nan)
    tc = t - t.mean()
    slope = (tc[:, None] * (y - y.mean(axis=0))).sum(axis=0) / (tc * tc).sum()
    return np.abs(slope * span) / np.maximum(np.abs(np.asarray(scale, dtype=float)), 1e-300)
