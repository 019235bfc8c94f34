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


def drift(t, y, scale) -> np.ndarray:
    """Change of the least-squares line through each column of ``y`` over the span of ``t``,
    divided by ``scale`` (per column or one number): 0 for a steady signal, 1 when it moves by
    a whole scale. Oscillations with many periods in the window hardly move the line."""
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    if y.ndim == 1:
        y = y[:, None]
    if len(t) < 3:
        return np.full(y.shape[1], np.nan)
    tc = t - t.mean()
    slope = (tc[:, None] * (y - y.mean(axis=0))).sum(axis=0) / (tc * tc).sum()
    return np.abs(slope * (t[-1] - t[0])) / np.maximum(np.abs(np.asarray(scale, dtype=float)), 1e-300)
