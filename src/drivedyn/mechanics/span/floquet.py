"""Floquet analysis of the span's Hill equation (seed eq. 5) with the full periodic tension.

    q'' + 2 zeta Omega q' + Omega^2 (1 + 2 mu Phi(omega t)) q = 0

is integrated over one excitation period (compiled RK4, ``_kernels``); the span is stable where
both Floquet multipliers (eigenvalues of the monodromy matrix) lie in the unit disc. Undamped,
det = 1 and the multipliers sit on the unit circle outside the tongues; inside a tongue one of
them is real with modulus above 1 (Bolotin 1956, ch. 2; Nayfeh & Mook 1979, sec. 5.2).
"""
from __future__ import annotations

import numpy as np

from . import _kernels
from .quantities import SpanProperties, effective_tension, excitation_frequency

N_MIN = 64          # steps per period at least (resolves ~8 harmonics of Phi)
N_MAX = 2_000_000   # guard against runaway step counts at vanishing speeds


def hill_parameters(F0, V, sp: SpanProperties, F1: float, teeth: int, pitch: float,
                    convention: str = "tooth-passing"):
    """(alpha, beta, gamma) of the dimensionless Hill equation at (F0, V) (see ``_kernels``).

    NaN where V = 0 (no excitation: the period is infinite).
    """
    F0, V = np.broadcast_arrays(np.asarray(F0, float), np.asarray(V, float))
    k2 = (np.pi / sp.length) ** 2 / sp.mass_per_length
    w = excitation_frequency(V, teeth, pitch, convention)
    with np.errstate(divide="ignore", invalid="ignore"):
        w2 = np.where(w > 0, w * w, np.nan)
        alpha = k2 * effective_tension(F0, V, sp) / w2
        beta = k2 * F1 / w2
        # modal damping is a ratio of the loaded frequency; none once the span has diverged
        gamma = 2.0 * sp.damping_ratio * np.sqrt(np.maximum(alpha, 0.0))
    return alpha, beta, gamma


def multipliers(alpha, beta, gamma, a, b, steps_per_oscillation: int = 48):
    """Monodromy trace, determinant and largest multiplier modulus for arrays of points.

    Parameters
    ----------
    alpha, beta, gamma : array_like
        Coefficients of ``q'' + gamma q' + (alpha + beta Phi) q = 0`` (broadcast together).
    a, b : array_like
        Cosine and sine coefficients of Phi(tau), harmonics 1..K.
    steps_per_oscillation : int
        RK4 steps per free oscillation (48 gives |lambda| to about 1e-6).

    Returns
    -------
    trace, det, rho : numpy.ndarray
        Same shape as the broadcast inputs.
    """
    alpha, beta, gamma = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (alpha, beta, gamma)))
    shape = alpha.shape
    al, be, ga = (np.ascontiguousarray(x.ravel()) for x in (alpha, beta, gamma))
    out = [np.empty(al.size) for _ in range(3)]
    _kernels.floquet_points(al, be, ga, np.ascontiguousarray(a, dtype=float), np.ascontiguousarray(b, dtype=float),
                            int(steps_per_oscillation), N_MIN, N_MAX, *out)
    return tuple(o.reshape(shape) for o in out)


def mathieu_multiplier(a, q, steps_per_oscillation: int = 64):
    """Largest Floquet multiplier modulus of y'' + (a - 2 q cos 2z) y = 0 (Mathieu, z period pi).

    With tau = 2 z this is y_tautau + (a/4 - (q/2) cos tau) y = 0. Used to check the kernel
    against scipy's characteristic values a_n(q), b_n(q).
    """
    a = np.asarray(a, dtype=float)
    q = np.asarray(q, dtype=float)
    return multipliers(a / 4.0, -q / 2.0, 0.0 * a, [1.0], [0.0], steps_per_oscillation)[2]


def floquet_chart(F0, V, sp: SpanProperties, F1: float, shape_ab, teeth: int, pitch: float,
                  convention: str = "tooth-passing", steps_per_oscillation: int = 48):
    """Largest multiplier modulus on the grid F0 (rows) x V (columns), and the trace.

    Points at V = 0 get rho = 1 when the span is stable statically (no excitation), else NaN.
    """
    FF, VV = np.meshgrid(np.asarray(F0, float), np.asarray(V, float), indexing="ij")
    alpha, beta, gamma = hill_parameters(FF, VV, sp, F1, teeth, pitch, convention)
    trace, det, rho = multipliers(alpha, beta, gamma, shape_ab[0], shape_ab[1], steps_per_oscillation)
    still = VV <= 0
    rho = np.where(still & (effective_tension(FF, VV, sp) > 0), 1.0, rho)
    return rho, trace
