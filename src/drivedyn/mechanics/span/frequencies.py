"""Natural frequencies of a span and the field method: tension from a measured frequency.

Forward models (pinned span of length L, tension T, mass per metre m, bending stiffness EI):

- string:        f_n = (n / 2L) sqrt(T / m)                                  (Rayleigh)
- beam:          f_n = (n / 2L) sqrt((T + n^2 F*) / m),  F* = pi^2 EI / L^2    (pinned tensioned beam)
- moving string: f_n = (n / 2L) c (1 - V^2 / c^2),  c = sqrt(T / m)       (Mote 1965; Wickert & Mote 1990)
- moving beam:   eigenvalues of the gyroscopic Galerkin system of seed eq. 1 on sin(j pi x / L),
                 j = 1..J, which reduces to the two formulas above when EI = 0 or V = 0.

The inverse solves the moving-beam model for T (it is increasing in T), so it includes the
bending and speed corrections; the uncertainty is propagated to first order from those of f, L, m
and EI with numerical derivatives.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...core._roots import find_root
from ...core.errors import ModelError

GALERKIN_TERMS = 24


def string_frequency(T, m, L, n=1):
    """f_n = (n / 2L) sqrt(T / m) (Hz)."""
    return n / (2.0 * L) * np.sqrt(np.asarray(T, float) / m)


def beam_frequency(T, m, L, EI, n=1):
    """Pinned tensioned beam: f_n = (n / 2L) sqrt((T + n^2 pi^2 EI / L^2) / m) (Hz)."""
    return n / (2.0 * L) * np.sqrt((np.asarray(T, float) + n * n * np.pi ** 2 * EI / L ** 2) / m)


def moving_string_frequency(T, m, L, V, n=1):
    """Axially moving string: f_n = (n / 2L) c (1 - V^2/c^2), c = sqrt(T/m) (Hz); 0 at V >= c."""
    c = np.sqrt(np.asarray(T, float) / m)
    return np.where(V < c, n / (2.0 * L) * c * (1.0 - V ** 2 / c ** 2), 0.0)


def _galerkin(T, m, L, EI, V, J):
    """The Galerkin system's stiffness diagonal k (..., J) and gyroscopic matrix G (..., J, J) for
    tensions T and speeds V (scalars or arrays of one shape)."""
    T, V = np.asarray(T, float)[..., None], np.asarray(V, float)[..., None]
    j = np.arange(1, J + 1)
    kj = j * np.pi / L
    k = kj ** 2 * (T - V ** 2 * m) + EI * kj ** 4
    # G_ij = (2/L) 2 V m int_0^L sin(i pi x/L) d/dx sin(j pi x/L) dx  (Galerkin of 2 V rhoA y_xt)
    i_, j_ = np.meshgrid(j, j, indexing="ij")
    odd = (i_ + j_) % 2 == 1
    with np.errstate(divide="ignore", invalid="ignore"):
        g = np.where(odd, 8.0 * m * i_ * j_ / (L * (i_ ** 2 - j_ ** 2)), 0.0)
    return k, V[..., None] * g


def moving_beam_spectrum(T, m, L, EI, V, modes=3, terms=GALERKIN_TERMS):
    """First ``modes`` natural frequencies (Hz) of the moving tensioned beam (seed eq. 1) for arrays
    of tensions T and speeds V (one shape): an array of that shape + (modes,), NaN where the span
    is at or above its critical speed."""
    k, G = _galerkin(T, m, L, EI, V, terms)
    ok = k.min(axis=-1) > 0
    # m q'' + G q' + K q = 0 with K = diag(k) and G skew: in y = (W q, q'), W = sqrt(K / m), it reads
    # y' = S y with S = [[0, W], [-W, -G / m]] skew-symmetric, whose eigenvalues +-i w make w^2 a double
    # eigenvalue of the symmetric S^T S (a symmetric solve: a quarter of the general one's time)
    J = terms
    W = np.sqrt(np.where(ok[..., None], k, 1.0) / m)[..., None] * np.eye(J)
    S = np.zeros(k.shape[:-1] + (2 * J, 2 * J))
    S[..., :J, J:] = W
    S[..., J:, :J] = -W
    S[..., J:, J:] = -G / m
    w2 = np.linalg.eigvalsh(np.swapaxes(S, -1, -2) @ S)
    f = np.sqrt(np.clip(w2, 0.0, None))[..., ::2][..., :modes] / (2.0 * np.pi)
    return np.where(ok[..., None], f, np.nan)


def moving_beam_frequencies(T, m, L, EI, V, modes=3, terms=GALERKIN_TERMS):
    """First ``modes`` natural frequencies (Hz) of the moving tensioned beam (seed eq. 1).

    Raises ModelError if the span has diverged (some stiffness not positive definite).
    """
    f = moving_beam_spectrum(float(T), m, L, EI, float(V), modes, terms)
    if np.isnan(f).any():
        raise ModelError(f"{V:.4g} m/s is at or above the critical speed of the span "
                         f"({np.sqrt((T + np.pi ** 2 * EI / L ** 2) / m):.4g} m/s): it has no natural frequency",
                         field="speed")
    return f


def span_frequencies(T, m, L, EI, V, modes=3):
    """All four models' frequencies (Hz) as a dict of arrays over modes 1..``modes``."""
    n = np.arange(1, modes + 1)
    return {
        "string": string_frequency(T, m, L, n),
        "beam": beam_frequency(T, m, L, EI, n),
        "moving_string": moving_string_frequency(T, m, L, V, n),
        "moving_beam": moving_beam_frequencies(T, m, L, EI, V, modes),
    }


@dataclass(frozen=True)
class TensionEstimate:
    """Tension from a measured span frequency.

    Attributes
    ----------
    tension : float
        With bending and speed corrections (moving-beam model), N.
    tension_string : float
        Plain string formula T = 4 m L^2 f^2 / n^2, N.
    bending_correction, speed_correction : float
        Changes of T from the bending stiffness and the belt speed, N (tension - string value
        = bending + speed, the split is taken in that order).
    uncertainty : float
        One standard deviation of ``tension`` (N), first-order propagation.
    contributions : dict
        Standard-deviation contribution of each input (N): frequency, length, mass, bending.
    """

    tension: float
    tension_string: float
    bending_correction: float
    speed_correction: float
    uncertainty: float
    contributions: dict


def string_tension(f, m, L, n=1):
    """T = 4 m L^2 f^2 / n^2 (N): the string formula of the field method."""
    return 4.0 * m * L ** 2 * f ** 2 / n ** 2


def tension_from_frequency(f, m, L, EI=0.0, V=0.0, n=1):
    """Span tension T (N) whose mode-n moving-beam frequency is ``f`` (Hz).

    Raises ModelError naming ``frequency`` if no positive tension gives f (bending alone
    already makes the span stiffer than measured).
    """
    def g(T):
        return moving_beam_frequencies(T, m, L, EI, V, n)[n - 1] - f

    # below this tension the span diverges at speed V; just above it the frequency is ~0
    t_min = max(V ** 2 * m - np.pi ** 2 * EI / L ** 2, 0.0) * (1 + 1e-9) + 1e-9
    if g(t_min) >= 0:
        bend = moving_beam_frequencies(t_min, m, L, EI, V, n)[n - 1]
        raise ModelError(f"{f:.4g} Hz is below the mode-{n} frequency of the span at zero tension "
                         f"({bend:.4g} Hz): check frequency, mode, length and bending stiffness", field="frequency")
    t_hi = max(string_tension(f, m, L, n), t_min) * 2 + 1.0
    while g(t_hi) < 0:
        t_hi *= 2
    return find_root(g, t_min, t_hi, xtol=1e-10, rtol=1e-13)


def estimate_tension(f, m, L, EI=0.0, V=0.0, n=1, sigma_f=0.0, sigma_L=0.0, sigma_m=0.0, sigma_EI=0.0):
    """Tension from a measured frequency with corrections and a first-order uncertainty.

    Examples
    --------
    >>> e = estimate_tension(50.0, 0.1, 0.5, n=1, sigma_f=0.5)        # string: T = 4 m L^2 f^2
    >>> round(e.tension, 6), round(e.uncertainty, 6)                  # sigma_T / T = 2 sigma_f / f
    (250.0, 5.0)
    """
    T = tension_from_frequency(f, m, L, EI, V, n)
    Ts = string_tension(f, m, L, n)
    Tb = tension_from_frequency(f, m, L, EI, 0.0, n)
    contrib = {}
    for name, x, s in (("frequency", f, sigma_f), ("length", L, sigma_L), ("mass", m, sigma_m),
                       ("bending", EI, sigma_EI)):
        if s <= 0:
            contrib[name] = 0.0
            continue
        # derivative step from the value (from the uncertainty only where the value is 0); one-sided
        # where the value cannot go below 0 (EI = 0)
        h = 1e-4 * (abs(x) if x != 0 else s)
        args = {"f": f, "m": m, "L": L, "EI": EI}
        key = {"frequency": "f", "length": "L", "mass": "m", "bending": "EI"}[name]
        up, dn = dict(args), dict(args)
        up[key] = x + h
        dn[key] = x - h if x - h >= 0 else x
        dTdx = (tension_from_frequency(V=V, n=n, **up) - tension_from_frequency(V=V, n=n, **dn)) / (up[key] - dn[key])
        contrib[name] = abs(dTdx) * s
    sigma = float(np.sqrt(sum(v ** 2 for v in contrib.values())))
    return TensionEstimate(float(T), float(Ts), float(Tb - Ts), float(T - Tb), sigma, contrib)
